// A fresh process that does not link GASP: loading the plugin module registers GASP's classes
// with MRPT's class factory, as rawlog-edit -p / RawLogViewer -l / SceneViewer3D -l do.
#include <gtest/gtest.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/system/os.h>

#include <string>

TEST(PluginLoad, RegistersEveryGaspClassByName) {
  EXPECT_EQ(mrpt::rtti::findRegisteredClass("gasp::ObservationMatcher_GASP"), nullptr)
      << "registered before the plugin was loaded: the test links GASP by mistake";
  std::string errors;
  ASSERT_TRUE(mrpt::system::loadPluginModule(GASP_MRPT_PLUGIN, errors)) << errors;
  for (const char* name : {"gasp::ObservationMatcher", "gasp::ObservationMatcher_GASP"})
    EXPECT_NE(mrpt::rtti::findRegisteredClass(name), nullptr) << name;
  const auto object = mrpt::rtti::classFactory("gasp::ObservationMatcher_GASP");
  ASSERT_TRUE(object);
  EXPECT_STREQ(object->GetRuntimeClass()->className, "gasp::ObservationMatcher_GASP");
  // The abstract base cannot be instantiated.
  EXPECT_FALSE(mrpt::rtti::classFactory("gasp::ObservationMatcher"));
}

TEST(PluginLoad, MissingModuleIsAnError) {
  std::string errors;
  EXPECT_FALSE(mrpt::system::loadPluginModule("/nonexistent/libgasp_nothing.so", errors));
  EXPECT_FALSE(errors.empty());
}
