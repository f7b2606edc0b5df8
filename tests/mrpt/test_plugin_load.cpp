// A fresh process that does not link GASP: loading the plugin module registers GASP's classes
// with MRPT's class factory and its map with MRPT's map factory, as rawlog-edit -p /
// RawLogViewer -l / SceneViewer3D -l (or LD_PRELOAD for observations2map) do.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/system/os.h>

#include <string>

TEST(PluginLoad, RegistersEveryGaspClassByName) {
  const char* names[] = {"gasp::ObservationMatcher", "gasp::ObservationMatcher_GASP", "gasp::CSuperpixelMap",
                         "gasp::CGaspAligner"};
  for (const char* name : names)
    EXPECT_EQ(mrpt::rtti::findRegisteredClass(name), nullptr)
        << name << " registered before the plugin was loaded: the test links GASP by mistake";
  std::string errors;
  ASSERT_TRUE(mrpt::system::loadPluginModule(GASP_MRPT_PLUGIN, errors)) << errors;
  for (const char* name : names) EXPECT_NE(mrpt::rtti::findRegisteredClass(name), nullptr) << name;
  for (const char* name : {"gasp::ObservationMatcher_GASP", "gasp::CSuperpixelMap", "gasp::CGaspAligner"}) {
    const auto object = mrpt::rtti::classFactory(name);
    ASSERT_TRUE(object) << name;
    EXPECT_STREQ(object->GetRuntimeClass()->className, name);
  }
  // The abstract base cannot be instantiated.
  EXPECT_FALSE(mrpt::rtti::classFactory("gasp::ObservationMatcher"));

  // MRPT's map factory: an ini section creates the map, with its creation options.
  mrpt::maps::TSetOfMetricMapInitializers init;
  init.loadFromConfigFile(mrpt::config::CConfigFileMemory("[Maps]\nsuperpixelMap_count=1\n"
                                                          "[Maps_superpixelMap_00_creationOpts]\n"
                                                          "target_patch_area_m2=0.008\n"),
                          "Maps");
  ASSERT_EQ(init.size(), 1u);
  mrpt::maps::CMultiMetricMap multi(init);
  ASSERT_EQ(multi.maps.size(), 1u);
  EXPECT_STREQ(multi.maps[0]->GetRuntimeClass()->className, "gasp::CSuperpixelMap");
  std::ostringstream dump;
  init.dumpToTextStream(dump);
  EXPECT_NE(dump.str().find("target_patch_area_m2"), std::string::npos) << dump.str();
  EXPECT_NE(dump.str().find("0.008"), std::string::npos) << dump.str();
}

TEST(PluginLoad, MissingModuleIsAnError) {
  std::string errors;
  EXPECT_FALSE(mrpt::system::loadPluginModule("/nonexistent/libgasp_nothing.so", errors));
  EXPECT_FALSE(errors.empty());
}
