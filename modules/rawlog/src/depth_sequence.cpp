#include "gasp/rawlog/depth_sequence.h"

#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/rawlog/rawlog_reader.h"
#include "gasp/rawlog/tum_to_rawlog.h"

namespace gasp {

struct DepthSequence::Impl {
  std::optional<TumDataset> tum;
  std::optional<RawlogReader> rawlog;
  std::size_t next_tum = 0;    ///< TUM: index of the next frame to use
  std::size_t scans_seen = 0;  ///< rawlog: scans of the chosen sensor seen so far
};

DepthSequence::DepthSequence(const DepthSequenceOptions& options) : options_(options), impl_(std::make_unique<Impl>()) {
  if (options.tum_dir.empty() == options.rawlog_path.empty())
    throw Error("depth sequence: give either a TUM folder or a rawlog");
  if (options.every == 0) throw Error("depth sequence: every must be at least 1");
  if (!options.tum_dir.empty()) {
    TumDataset::Options tum;
    if (!options.intrinsics.empty()) tum.intrinsics = CameraIntrinsics::fromPresetOrFile(options.intrinsics);
    tum.depth_units_per_metre = options.depth_units_per_metre;
    tum.undistort = options.undistort;
    impl_->tum = TumDataset::open(options.tum_dir, tum);
    ground_truth_ = impl_->tum->groundTruth();
    if (options.first >= impl_->tum->size())
      throw Error(options.tum_dir + ": first frame " + std::to_string(options.first) + " but the folder has " +
                  std::to_string(impl_->tum->size()) + " frames");
    impl_->next_tum = options.first;
  } else {
    impl_->rawlog.emplace(options.rawlog_path, options.sweeps, options.sensor_label);
  }
}

DepthSequence::~DepthSequence() = default;
DepthSequence::DepthSequence(DepthSequence&&) noexcept = default;
DepthSequence& DepthSequence::operator=(DepthSequence&&) noexcept = default;

std::string DepthSequence::describe() const {
  return options_.tum_dir.empty() ? "rawlog " + options_.rawlog_path : "TUM folder " + options_.tum_dir;
}

std::string DepthSequence::intrinsicsSummary() const {
  if (impl_->tum) return impl_->tum->intrinsicsSummary();
  return sweeps_ ? "each sweep's own (its model's laser elevations and its columns' azimuths)" : "each scan's own (cameraParams)";
}

std::string DepthSequence::intrinsicsWarning() const { return impl_->tum ? impl_->tum->intrinsicsWarning() : ""; }

const RgbdFrame* DepthSequence::peek() {
  if (peek_error_) throw Error(*peek_error_);
  if (!peeked_ && !peeked_end_) {
    try {
      peeked_ = read(peeked_index_);
    } catch (const Error& e) {
      peek_error_ = e.what();  // the frame is gone from the input: next() says so again
      throw;
    }
    peeked_end_ = !peeked_;
  }
  return peeked_ ? &*peeked_ : nullptr;
}

std::optional<RgbdFrame> DepthSequence::next() {
  if (peek_error_) {
    const std::string error = *peek_error_;
    peek_error_.reset();  // said once more; the input goes on after it, as without the peek
    throw Error(error);
  }
  if (peeked_ || peeked_end_) {
    std::optional<RgbdFrame> out = std::move(peeked_);
    peeked_.reset();
    if (out) input_index_ = peeked_index_;
    return out;  // at the end, peeked_end_ stays: every later call is the end too
  }
  std::size_t index = 0;
  std::optional<RgbdFrame> out = read(index);
  if (out) input_index_ = index;
  return out;
}

std::optional<RgbdFrame> DepthSequence::read(std::size_t& index_out) {
  if (options_.max_frames != 0 && used_ >= options_.max_frames) return std::nullopt;  // read nothing more
  std::optional<RgbdFrame> out;
  if (impl_->tum) {
    if (impl_->next_tum < impl_->tum->size()) {
      index_out = impl_->next_tum;
      out = frameFromTum(*impl_->tum, index_out, options_.with_rgb);
      // No wrap-around for a huge `every`: past the end is the end.
      impl_->next_tum = options_.every > impl_->tum->size() - index_out ? impl_->tum->size() : index_out + options_.every;
    }
  } else {
    for (std::optional<RgbdFrame> f; (f = impl_->rawlog->next());) {
      if (!options_.sensor_label.empty() && f->sensor_label != options_.sensor_label) continue;
      // The sequence's kind is its first scan's. Without a sensor label, a rawlog that starts with
      // depth images reads them as it always did (its sweeps are skipped, not counted); one that
      // starts with sweeps and holds depth images too must name its sensor.
      if (!kind_decided_) {
        sweeps_ = f->isSweep();
        kind_decided_ = true;
      } else if (f->isSweep() != sweeps_) {
        if (!sweeps_ && options_.sensor_label.empty()) continue;
        throw Error(options_.rawlog_path + ": scan " + std::to_string(impl_->scans_seen) + " ('" + f->sensor_label +
                    "') is " +
                    (f->isSweep() ? "a LiDAR sweep, the first was a depth image" : "a depth image, the first was a LiDAR sweep") +
                    " (one sensor only; choose it with the sensor label)");
      }
      const std::size_t index = impl_->scans_seen++;
      if (index < options_.first || (index - options_.first) % options_.every != 0) continue;
      if (used_ == 0) {
        T_robot_camera_ = f->T_robot_camera;
      } else if (!T_robot_camera_.isApprox(f->T_robot_camera, 1e-9)) {
        throw Error(options_.rawlog_path + ": scan " + std::to_string(index) +
                    " has another sensorPose than the first (one camera only; choose it with the sensor label)");
      }
      index_out = index;
      out = std::move(f);
      break;
    }
    if (!out && used_ == 0)
      throw Error(options_.rawlog_path + ": no scan to use (" + std::to_string(impl_->scans_seen) + " scans" +
                  (options_.sensor_label.empty() ? std::string() : " of sensor '" + options_.sensor_label + "'") +
                  ", first " + std::to_string(options_.first) + ")");
  }
  if (out) {
    ++used_;
  }
  return out;
}

}  // namespace gasp
