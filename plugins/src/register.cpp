// The one place where GASP's MRPT classes are registered with MRPT's class factory. It runs when
// the plugin library is loaded: linked, or dlopen'ed by mrpt::system::loadPluginModule
// (rawlog-edit -p, RawLogViewer -l, SceneViewer3D -l).
#include <mrpt/core/initializer.h>
#include <mrpt/rtti/CObject.h>

#include "gasp/mrpt/ObservationMatcher_GASP.h"
#include "gasp/mrpt/observation_matcher.h"

MRPT_INITIALIZER(register_gasp_mrpt_classes) {
  using namespace gasp;
  mrpt::rtti::registerClass(CLASS_ID(ObservationMatcher));
  mrpt::rtti::registerClass(CLASS_ID(ObservationMatcher_GASP));
}
