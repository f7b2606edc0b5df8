#pragma once
/// \file lazy_load_base_guard.h (private) Sets MRPT's global base folder of externally stored
/// data (mrpt::io lazy-load path, = CImage::getImagesPathBase()) for a scope and restores it.
#include <mrpt/io/lazy_load_path.h>

#include <string>

namespace gasp::detail {

class LazyLoadBaseGuard {
 public:
  explicit LazyLoadBaseGuard(const std::string& base) : saved_(mrpt::io::getLazyLoadPathBase()) {
    mrpt::io::setLazyLoadPathBase(base);
  }
  ~LazyLoadBaseGuard() { mrpt::io::setLazyLoadPathBase(saved_); }
  LazyLoadBaseGuard(const LazyLoadBaseGuard&) = delete;
  LazyLoadBaseGuard& operator=(const LazyLoadBaseGuard&) = delete;

 private:
  std::string saved_;
};

}  // namespace gasp::detail
