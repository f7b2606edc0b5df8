#include "gasp/mrpt/observation_matcher.h"

#include <mrpt/core/exceptions.h>
#include <mrpt/rtti/CObject.h>

IMPLEMENTS_VIRTUAL_MRPT_OBJECT(ObservationMatcher, mrpt::rtti::CObject, gasp)

namespace gasp {

std::shared_ptr<ObservationMatcher> createObservationMatcher(const std::string& class_name,
                                                             const mrpt::containers::yaml& params) {
  const auto object = mrpt::rtti::classFactory(class_name);
  if (!object && mrpt::rtti::findRegisteredClass(class_name)) {
    THROW_EXCEPTION_FMT("createObservationMatcher: '%s' is registered but cannot be created (an abstract class; "
                        "e.g. 'gasp::ObservationMatcher_GASP' can)",
                        class_name.c_str());
  }
  if (!object) {
    THROW_EXCEPTION_FMT(
        "createObservationMatcher: no class named '%s' is registered (is the GASP plugin loaded? "
        "names are namespace-qualified, e.g. 'gasp::ObservationMatcher_GASP')",
        class_name.c_str());
  }
  auto matcher = std::dynamic_pointer_cast<ObservationMatcher>(object);
  if (!matcher) THROW_EXCEPTION_FMT("createObservationMatcher: '%s' is not a gasp::ObservationMatcher", class_name.c_str());
  matcher->initialize(params);
  return matcher;
}

}  // namespace gasp
