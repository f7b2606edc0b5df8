// The one place where GASP's MRPT classes are registered: with MRPT's class factory
// (mrpt::rtti, for classFactory() and deserialization by class name) and with MRPT's metric map
// factory (TMetricMapTypesRegistry, for CMultiMetricMap ini sections). It runs when the plugin
// library is loaded: linked, LD_PRELOAD'ed, or dlopen'ed by mrpt::system::loadPluginModule
// (rawlog-edit -p, RawLogViewer -l, SceneViewer3D -l).
#include <mrpt/core/initializer.h>
#include <mrpt/maps/TMetricMapTypesRegistry.h>
#include <mrpt/rtti/CObject.h>

#include "gasp/mrpt/CGaspAligner.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/mrpt/ObservationMatcher_GASP.h"
#include "gasp/mrpt/observation_matcher.h"

// `superpixelMap_count=N` (or `gasp::CSuperpixelMap_count=N`) in a CMultiMetricMap ini section.
MAP_DEFINITION_REGISTER("superpixelMap,gasp::CSuperpixelMap", gasp::CSuperpixelMap)

MRPT_INITIALIZER(register_gasp_mrpt_classes) {
  using namespace gasp;
  mrpt::rtti::registerClass(CLASS_ID(ObservationMatcher));
  mrpt::rtti::registerClass(CLASS_ID(ObservationMatcher_GASP));
  mrpt::rtti::registerClass(CLASS_ID(CSuperpixelMap));
  mrpt::rtti::registerClass(CLASS_ID(CGaspAligner));
}
