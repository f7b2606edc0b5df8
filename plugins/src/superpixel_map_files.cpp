// CSuperpixelMap::saveMetricMapRepresentationToFile: PLY of the patches, a text table, and a
// .3Dscene of the visualisation for SceneViewer3D.
#include <mrpt/core/exceptions.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfObjects.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <iomanip>

#include "gasp/core/output_file.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/rawlog/gz_output_stream.h"

namespace gasp {

namespace {

/// Opened now, published whole by commit() (gasp/core/output_file.h); errors name the file.
OutputFile openOutput(const std::string& path, const std::string& what) {
  OutputFile f(path, what);
  f.stream().precision(9);
  return f;
}

void writePly(const std::string& path, const std::vector<MapPatch>& patches) {
  OutputFile file = openOutput(path, "superpixel map PLY");
  std::ostream& f = file.stream();
  f << "ply\nformat ascii 1.0\n"
       "comment gasp::CSuperpixelMap surface patches in the map frame: centroid [m], unit normal, colour, "
       "area [m^2], source view and patch\n"
    << "element vertex " << patches.size() << "\n"
    << "property float x\nproperty float y\nproperty float z\n"
       "property float nx\nproperty float ny\nproperty float nz\n"
       "property uchar red\nproperty uchar green\nproperty uchar blue\n"
       "property float area\nproperty int view\nproperty int patch\nend_header\n";
  for (const MapPatch& p : patches) {
    f << p.centroid.x() << ' ' << p.centroid.y() << ' ' << p.centroid.z() << ' ' << p.normal.x() << ' '
      << p.normal.y() << ' ' << p.normal.z() << ' ' << int(p.rgb[0]) << ' ' << int(p.rgb[1]) << ' ' << int(p.rgb[2])
      << ' ' << p.area_m2 << ' ' << p.view << ' ' << p.patch << '\n';
  }
  file.commit();
}

void writeTable(const std::string& path, const std::vector<SuperpixelMapView>& views,
                const std::vector<MapPatch>& patches) {
  OutputFile file = openOutput(path, "superpixel map table");
  std::ostream& f = file.stream();
  f << "# gasp::CSuperpixelMap: " << views.size() << " views, " << patches.size() << " patches (map frame)\n";
  for (std::size_t i = 0; i < views.size(); ++i) {
    const auto& t = views[i].T_map_camera;
    const Eigen::Quaterniond q(t.linear());
    f << "# view " << i << " '" << views[i].sensor_label << "' t=" << std::fixed << std::setprecision(6)
      << views[i].timestamp << std::defaultfloat << std::setprecision(9) << " T_map_camera xyz qxqyqzqw: " << t.translation().transpose() << ' ' << q.x() << ' ' << q.y() << ' '
      << q.z() << ' ' << q.w() << '\n';
  }
  f << "# view patch cx cy cz nx ny nz area_m2 pixels planarity r g b\n";
  for (const MapPatch& p : patches) {
    const SurfacePatch& s =
        views[static_cast<std::size_t>(p.view)].view.segmentation.patches[static_cast<std::size_t>(p.patch)];
    f << p.view << ' ' << p.patch << ' ' << p.centroid.x() << ' ' << p.centroid.y() << ' ' << p.centroid.z() << ' '
      << p.normal.x() << ' ' << p.normal.y() << ' ' << p.normal.z() << ' ' << p.area_m2 << ' ' << s.pixel_count
      << ' ' << s.planarity << ' ' << int(p.rgb[0]) << ' ' << int(p.rgb[1]) << ' ' << int(p.rgb[2]) << '\n';
  }
  file.commit();
}

}  // namespace

void CSuperpixelMap::saveMetricMapRepresentationToFile(const std::string& prefix) const {
  const std::vector<MapPatch> patches = patchesInMapFrame();
  writePly(prefix + "_patches.ply", patches);
  writeTable(prefix + "_patches.txt", views_, patches);
  mrpt::opengl::COpenGLScene scene;
  auto objects = mrpt::opengl::CSetOfObjects::Create();
  getVisualizationInto(*objects);
  scene.insert(objects);
  OutputFile scene_file(prefix + "_3D.3Dscene", "superpixel map 3D scene");
  GzOutputStream stream(scene_file, 1);  // gzip, as COpenGLScene::saveToFile() writes it
  mrpt::serialization::archiveFrom(stream) << scene;
  stream.finish();
}

}  // namespace gasp
