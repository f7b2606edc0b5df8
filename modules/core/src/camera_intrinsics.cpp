#include "gasp/core/camera_intrinsics.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "gasp/core/error.h"
#include "gasp/core/output_file.h"
#include "gasp/core/text_file.h"

namespace gasp {

bool CameraIntrinsics::project(const Eigen::Vector3d& p, double& u, double& v) const {
  if (!(p.z() > 0.0)) return false;
  u = fx * p.x() / p.z() + cx;
  v = fy * p.y() / p.z() + cy;
  return true;
}

void CameraIntrinsics::validate() const {
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide)
    throw Error("camera intrinsics: image size must be from 1 to " + std::to_string(kMaxImageSide) + " pixels, got " + std::to_string(width) +
                "x" + std::to_string(height));
  if (!positive(fx) || !positive(fy))
    throw Error("camera intrinsics: focal lengths must be positive and finite");
  // Within an image size of the image: further out the pixels' rays are nearly parallel to the
  // image plane, and the segmentation's lattice would grow without bound.
  if (!(cx >= -width && cx <= 2.0 * width) || !(cy >= -height && cy <= 2.0 * height))
    throw Error("camera intrinsics: the principal point must lie within an image size of the image, got (" +
                std::to_string(cx) + ", " + std::to_string(cy) + ")");
  for (const double d : distortion)
    if (!std::isfinite(d)) throw Error("camera intrinsics: the distortion coefficients must be finite");
}

CameraIntrinsics CameraIntrinsics::tumFreiburg1() {
  CameraIntrinsics k;
  k.fx = 517.3; k.fy = 516.5; k.cx = 318.6; k.cy = 255.3;
  k.distortion = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};
  return k;
}
CameraIntrinsics CameraIntrinsics::tumFreiburg2() {
  CameraIntrinsics k;
  k.fx = 520.9; k.fy = 521.0; k.cx = 325.1; k.cy = 249.7;
  k.distortion = {0.2312, -0.7849, -0.0033, -0.0001, 0.9172};
  return k;
}
CameraIntrinsics CameraIntrinsics::tumFreiburg3() {
  CameraIntrinsics k;
  k.fx = 535.4; k.fy = 539.2; k.cx = 320.1; k.cy = 247.6;
  return k;
}
CameraIntrinsics CameraIntrinsics::rosDefault() { return CameraIntrinsics{}; }

CameraIntrinsics CameraIntrinsics::fromPreset(const std::string& name) {
  if (name == "fr1" || name == "freiburg1") return tumFreiburg1();
  if (name == "fr2" || name == "freiburg2") return tumFreiburg2();
  if (name == "fr3" || name == "freiburg3") return tumFreiburg3();
  if (name == "ros" || name == "default") return rosDefault();
  throw Error("unknown intrinsics preset '" + name + "' (expected fr1, fr2, fr3 or ros)");
}

CameraIntrinsics CameraIntrinsics::fromPresetOrFile(const std::string& s) {
  static const char* kPresets[] = {"fr1", "fr2", "fr3", "ros", "default",
                                   "freiburg1", "freiburg2", "freiburg3"};
  for (const char* p : kPresets)
    if (s == p) return fromPreset(s);
  if (!std::ifstream(s).good())
    throw Error("intrinsics '" + s + "': neither a preset (fr1, fr2, fr3, ros) nor a file that can be opened");
  return load(s);
}

CameraIntrinsics CameraIntrinsics::load(const std::string& path) {
  CameraIntrinsics k;
  std::map<std::string, bool> seen;
  forEachDataLine(path, [&](const std::string& line, int line_no) {
    const auto colon = line.find(':');
    if (colon == std::string::npos)
      throw Error(path + ":" + std::to_string(line_no) + ": expected 'key: value', got '" + line +
                  "'");
    const std::string key = trim(line.substr(0, colon));
    const std::vector<double> values = parseNumbers(line.substr(colon + 1), path, line_no);
    const std::size_t expected = key == "distortion" ? 5u : 1u;
    if (values.size() != expected)
      throw Error(path + ":" + std::to_string(line_no) + ": key '" + key + "' expects " +
                  std::to_string(expected) + " number(s)");
    if (seen.count(key))
      throw Error(path + ":" + std::to_string(line_no) + ": key '" + key + "' appears twice");
    if (key == "width" || key == "height") {
      // A whole number of pixels, within what a camera has (before the cast to int).
      if (!(values[0] >= 1 && values[0] <= kMaxImageSide) || values[0] != std::floor(values[0]))
        throw Error(path + ":" + std::to_string(line_no) + ": " + key + " must be a whole number of pixels from 1 to " +
                    std::to_string(kMaxImageSide) + ", got " + trim(line.substr(colon + 1)));
    }
    if (key == "width") k.width = static_cast<int>(values[0]);
    else if (key == "height") k.height = static_cast<int>(values[0]);
    else if (key == "fx") k.fx = values[0];
    else if (key == "fy") k.fy = values[0];
    else if (key == "cx") k.cx = values[0];
    else if (key == "cy") k.cy = values[0];
    else if (key == "distortion") std::copy(values.begin(), values.end(), k.distortion.begin());
    else
      throw Error(path + ":" + std::to_string(line_no) + ": unknown key '" + key +
                  "' (expected width, height, fx, fy, cx, cy, distortion)");
    seen[key] = true;
  });
  for (const char* required : {"width", "height", "fx", "fy", "cx", "cy"})
    if (!seen.count(required)) throw Error(path + ": missing key '" + std::string(required) + "'");
  try {
    k.validate();
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  return k;
}

void CameraIntrinsics::save(const std::string& path) const {
  OutputFile file(path, "intrinsics file");
  save(file.stream());
  file.commit();
}

void CameraIntrinsics::save(std::ostream& out) const {
  const auto precision = out.precision();
  out << std::setprecision(10);
  out << "# GASP camera intrinsics (pinhole; pixels)\n"
      << "width: " << width << "\nheight: " << height << "\nfx: " << fx << "\nfy: " << fy
      << "\ncx: " << cx << "\ncy: " << cy << "\ndistortion:";
  for (double d : distortion) out << ' ' << d;
  out << '\n';
  out.precision(precision);
}

bool operator==(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy &&
         a.cx == b.cx && a.cy == b.cy && a.distortion == b.distortion;
}

}  // namespace gasp
