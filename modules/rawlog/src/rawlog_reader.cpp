#include "gasp/rawlog/rawlog_reader.h"

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <deque>
#include <utility>
#include <exception>

#include "gasp/core/error.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"
#include "gasp/rawlog/rawlog_objects.h"
#include "lazy_load_base_guard.h"

namespace gasp {

struct RawlogReader::Impl {
  explicit Impl(const std::string& path) : objects(path) {}
  RawlogObjects objects;
  std::deque<mrpt::obs::CObservation::Ptr> pending;  ///< observations not yet returned
  bool at_end = false;
};

RawlogReader::RawlogReader(const std::string& path, bool read_sweeps, std::string sweep_label)
    : path_(path), read_sweeps_(read_sweeps), sweep_label_(std::move(sweep_label)) {
  impl_ = std::make_unique<Impl>(path);  // file checks: missing, directory, empty, unreadable
  images_dir_ = findRawlogImagesDirectory(path);

  // Read the first object now so that empty and garbage files fail at open.
  const auto first = impl_->objects.next();
  if (!first) throw Error("rawlog '" + path + "': empty rawlog (no MRPT object in the file)");
  if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(first)) {
    format_ = RawlogFormat::ActionsSensoryFrames;
    for (const auto& o : *sf) impl_->pending.push_back(o);
  } else if (std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(first)) {
    format_ = RawlogFormat::ActionsSensoryFrames;
    ++skipped_[rawlogClassName(*first)];
  } else if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(first)) {
    format_ = RawlogFormat::Observations;
    impl_->pending.push_back(obs);
  } else {
    throw Error("rawlog '" + path + "': not an MRPT rawlog (first object is a " + rawlogClassName(*first) +
                ", expected CObservation, CSensoryFrame or CActionCollection)");
  }
}

RawlogReader::~RawlogReader() = default;
RawlogReader::RawlogReader(RawlogReader&&) noexcept = default;
RawlogReader& RawlogReader::operator=(RawlogReader&&) noexcept = default;

std::optional<RgbdFrame> RawlogReader::next() {
  for (;;) {
    while (!impl_->pending.empty()) {
      auto obs = impl_->pending.front();
      impl_->pending.pop_front();
      if (!obs) continue;
      if (read_sweeps_ && isSweepObservation(*obs) && (sweep_label_.empty() || obs->sensorLabel == sweep_label_)) {
        RgbdFrame frame = sweepFrameFromObservation(
            *obs, "rawlog '" + path_ + "', sweep #" + std::to_string(scans_read_) + " ('" + obs->sensorLabel + "')");
        ++scans_read_;
        return frame;
      }
      auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
      if (!scan || isSweepObservation(*obs)) {  // a sweep not asked for: a 3D scan of points alone too
        ++skipped_[scan ? rawlogClassName(*obs) + " of 3D points without a range image" : rawlogClassName(*obs)];
        continue;
      }
      const std::string what = "rawlog '" + path_ + "', 3D scan #" + std::to_string(scans_read_);
      detail::LazyLoadBaseGuard base(images_dir_);
      RgbdFrame frame;
      try {
        frame = frameFromObservation(*scan, what);
      } catch (const Error&) {
        throw;
      } catch (const std::exception& e) {  // MRPT's, e.g. loading an external file of a bad name
        throw Error(what + ": " + exceptionMessage(e));
      }
      scan->unload();
      ++scans_read_;
      return frame;
    }
    if (impl_->at_end) break;

    auto obj = impl_->objects.next();  // gasp::Error for a truncated or corrupt stream
    if (!obj) {  // an action at the very end, without its sensory frame, ends the file (as in MRPT)
      impl_->at_end = true;
      continue;
    }
    if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj)) {
      for (const auto& o : *sf) impl_->pending.push_back(o);
    } else if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(obj)) {
      impl_->pending.push_back(obs);
    } else {
      ++skipped_[rawlogClassName(*obj)];
    }
  }
  if (scans_read_ == 0)
    throw Error("rawlog '" + path_ + "': no CObservation3DRangeScan of depth" +
                (read_sweeps_ ? ", CObservationRotatingScan or CObservationVelodyneScan" : "") + " in the file (it holds " +
                skippedSummary() + ")");
  return std::nullopt;
}

std::string RawlogReader::skippedSummary() const {
  if (skipped_.empty()) return "nothing";
  std::string s;
  for (const auto& [name, count] : skipped_) {
    if (!s.empty()) s += ", ";
    s += std::to_string(count) + " x " + name;
  }
  return s;
}

std::vector<RgbdFrame> readRawlogFrames(const std::string& path) {
  RawlogReader reader(path);
  std::vector<RgbdFrame> frames;
  while (auto f = reader.next()) frames.push_back(std::move(*f));
  return frames;
}

}  // namespace gasp
