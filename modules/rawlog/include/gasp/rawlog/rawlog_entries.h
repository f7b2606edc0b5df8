#pragma once
/// \file rawlog_entries.h The entries of a rawlog as MRPT's map builders and graph-SLAM engine
/// consume them: an (action, sensory frame) pair in format #1, an observation in format #2.
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <cstddef>
#include <optional>
#include <string>

#include "gasp/rawlog/rawlog_objects.h"

namespace gasp {

/// One entry: either `observations` (format #1; `action` may be null when the file has a sensory
/// frame without an action before it) or `observation` (format #2).
struct RawlogEntry {
  mrpt::obs::CActionCollection::Ptr action;
  mrpt::obs::CSensoryFrame::Ptr observations;
  mrpt::obs::CObservation::Ptr observation;
};

/// The entries of a rawlog in file order: what mrpt::obs::CRawlog::getActionObservationPairOrObservation()
/// returns, except that a truncated or corrupt file is a gasp::Error (see RawlogObjects) instead of
/// an early end. Objects that are neither observations, sensory frames nor actions are skipped. An
/// action at the very end, without its sensory frame, ends the file as in MRPT's reader (several of
/// MRPT's own sample rawlogs end that way); endedAfterAction() says so.
class RawlogEntries {
 public:
  explicit RawlogEntries(const std::string& path) : objects_(path) {}

  /// The next entry, or nullopt at the end of the file.
  std::optional<RawlogEntry> next();

  /// Objects read so far (MRPT's "rawlog entry" counter).
  std::size_t objectsRead() const { return objects_.objectsRead(); }
  const std::string& path() const { return objects_.path(); }
  /// The file ended after an action without its sensory frame (that action was dropped).
  bool endedAfterAction() const { return ended_after_action_; }

 private:
  RawlogObjects objects_;
  bool ended_after_action_ = false;
};

}  // namespace gasp
