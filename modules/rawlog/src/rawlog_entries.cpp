#include "gasp/rawlog/rawlog_entries.h"

#include "gasp/core/error.h"

namespace gasp {

std::optional<RawlogEntry> RawlogEntries::next() {
  RawlogEntry entry;
  while (auto object = objects_.next()) {
    if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(object)) {
      if (entry.action)
        throw Error("rawlog '" + path() + "': object #" + std::to_string(objects_.objectsRead() - 1) +
                    " is an observation where the sensory frame of the action before it was expected");
      entry.observation = obs;
      return entry;
    }
    if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(object)) {
      entry.observations = sf;
      return entry;
    }
    if (auto action = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(object)) {
      if (entry.action)
        throw Error("rawlog '" + path() + "': object #" + std::to_string(objects_.objectsRead() - 1) +
                    " is a second action in a row (no sensory frame between them)");
      entry.action = action;
    }
    // Anything else (a map, a pose, ...) is not part of an entry: skipped.
  }
  ended_after_action_ = static_cast<bool>(entry.action);  // dropped, as MRPT's CRawlog does
  return std::nullopt;
}

}  // namespace gasp
