// Mesh collision geometry: a mesh becomes the box around its scaled vertices, placed
// by the collision origin; package://, file:// and relative names resolve as
// documented; missing and corrupt files are InputErrors naming the URDF line and path.
// Every mesh is written by the test itself.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("ferret_mesh_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

/// An ASCII STL of a tetrahedron with vertices (0,-1,0), (2,-1,0), (0,1,0), (0,0,0.5):
/// bounding box [0, 2] x [-1, 1] x [0, 0.5].
std::string tetra_stl() {
  auto facet = [](const char* a, const char* b, const char* c) {
    return std::string("facet normal 0 0 0\n outer loop\n  vertex ") + a + "\n  vertex " + b +
           "\n  vertex " + c + "\n endloop\nendfacet\n";
  };
  const char *p0 = "0 -1 0", *p1 = "2 -1 0", *p2 = "0 1 0", *p3 = "0 0 0.5";
  return "solid tetra\n" + facet(p0, p2, p1) + facet(p0, p1, p3) + facet(p1, p2, p3) +
         facet(p2, p0, p3) + "endsolid tetra\n";
}

/// The same tetrahedron as a Wavefront OBJ.
std::string tetra_obj() {
  return "v 0 -1 0\nv 2 -1 0\nv 0 1 0\nv 0 0 0.5\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
}

/// A robot whose only collision is the mesh `filename` with `scale`, at xyz="1 0 0.2".
std::string mesh_robot(const std::string& filename, const std::string& scale = "") {
  return "<?xml version=\"1.0\"?>\n<robot name=\"m\">\n<link name=\"base_link\">\n"
         "<collision><origin xyz=\"1 0 0.2\"/><geometry>\n<mesh filename=\"" +
         filename + "\"" + (scale.empty() ? "" : " scale=\"" + scale + "\"") +
         "/></geometry></collision>\n</link>\n</robot>\n";
}

RobotDescription load_at(const fs::path& urdf, const std::string& xml) {
  write(urdf, xml);
  return load_robot_description(urdf);
}

void expect_box(const RobotDescription& r, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  ASSERT_EQ(r.collision_shapes.size(), 1u);
  EXPECT_EQ(r.collision_shapes[0].type, CollisionShape::Type::kBox);
  const Eigen::AlignedBox3d b = r.collision_shapes[0].aabb_B();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(b.min()[i], lo[i], 1e-6) << "axis " << i;
    EXPECT_NEAR(b.max()[i], hi[i], 1e-6) << "axis " << i;
  }
}

TEST(MeshCollision, AsciiStlBecomesItsScaledBoundingBoxAtTheCollisionOrigin) {
  const fs::path dir = scratch("stl");
  write(dir / "tetra.stl", tetra_stl());
  // Scale 0.1, 0.2, 0.4: box [0, 0.2] x [-0.2, 0.2] x [0, 0.2], shifted by (1, 0, 0.2).
  const auto r = load_at(dir / "r.urdf", mesh_robot("tetra.stl", "0.1 0.2 0.4"));
  expect_box(r, {1.0, -0.2, 0.2}, {1.2, 0.2, 0.4});
  EXPECT_NEAR(r.collision_shapes[0].box_size_m.x(), 0.2, 1e-6);
  EXPECT_EQ(r.collision_shapes[0].mesh, (dir / "tetra.stl").string());
  EXPECT_NEAR(r.ground_offset_m, -0.2, 1e-6);  // B is 0.2 m below the lowest point
}

TEST(MeshCollision, NegativeScaleMirrors) {
  const fs::path dir = scratch("mirror");
  write(dir / "tetra.stl", tetra_stl());
  // x mirrored: [-2, 0] before the origin's +1.
  const auto r = load_at(dir / "r.urdf", mesh_robot("tetra.stl", "-1 1 1"));
  expect_box(r, {-1.0, -1.0, 0.2}, {1.0, 1.0, 0.7});
}

TEST(MeshCollision, PackageUrlsResolveBesideTheUrdfAndOnRosPackagePath) {
  const fs::path dir = scratch("package");
  // The usual layout: mypkg/urdf/r.urdf and mypkg/meshes/tetra.obj.
  write(dir / "mypkg" / "meshes" / "tetra.obj", tetra_obj());
  const auto r =
      load_at(dir / "mypkg" / "urdf" / "r.urdf", mesh_robot("package://mypkg/meshes/tetra.obj"));
  expect_box(r, {1.0, -1.0, 0.2}, {3.0, 1.0, 0.7});

  // A package elsewhere, found through ROS_PACKAGE_PATH.
  const fs::path other = scratch("ros_path");
  write(other / "share" / "otherpkg" / "m" / "tetra.stl", tetra_stl());
  ::setenv("ROS_PACKAGE_PATH", ("/nonexistent:" + (other / "share").string()).c_str(), 1);
  const auto p = load_at(dir / "r2.urdf", mesh_robot("package://otherpkg/m/tetra.stl", "2 2 2"));
  ::unsetenv("ROS_PACKAGE_PATH");
  expect_box(p, {1.0, -2.0, 0.2}, {5.0, 2.0, 1.2});
}

TEST(MeshCollision, FileUrlsAndAbsolutePaths) {
  const fs::path dir = scratch("file_url");
  write(dir / "tetra.stl", tetra_stl());
  const auto r = load_at(scratch("elsewhere") / "r.urdf",
                         mesh_robot("file://" + (dir / "tetra.stl").string()));
  expect_box(r, {1.0, -1.0, 0.2}, {3.0, 1.0, 0.7});
}

InputError load_error(const fs::path& urdf, const std::string& xml) {
  write(urdf, xml);
  try {
    (void)load_robot_description(urdf);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

TEST(MeshCollision, MissingAndCorruptFilesNameTheUrdfLineAndTheMeshPath) {
  const fs::path dir = scratch("bad");
  const fs::path urdf = dir / "r.urdf";
  // The <mesh> element is on line 5 of mesh_robot().
  InputError e = load_error(urdf, mesh_robot("meshes/absent.stl"));
  EXPECT_EQ(e.source(), urdf.string() + ":5");
  EXPECT_EQ(e.field(), "link[base_link]/collision[0]/geometry/mesh@filename");
  EXPECT_NE(std::string(e.what()).find((dir / "meshes/absent.stl").string()), std::string::npos)
      << e.what();

  write(dir / "garbage.stl", "this is not a mesh \x01\x02\x03 at all\n");
  e = load_error(urdf, mesh_robot("garbage.stl"));
  EXPECT_EQ(e.source(), urdf.string() + ":5");
  EXPECT_NE(e.expected().find("a mesh file assimp can read"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find((dir / "garbage.stl").string()), std::string::npos);
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line";

  write(dir / "tetra.stl", tetra_stl());
  e = load_error(urdf, mesh_robot("tetra.stl", "1 0 1"));
  EXPECT_EQ(e.field(), "link[base_link]/collision[0]/geometry/mesh@scale");
  e = load_error(urdf, mesh_robot("package://nopkg/tetra.stl"));
  EXPECT_NE(e.expected().find("tried"), std::string::npos);
}

}  // namespace
}  // namespace ferret

namespace ferret {
namespace {

TEST(MeshCollision, OneMeshInManyCollisionsKeepsEachPlacement) {
  // 500 collisions of one file (read once): each box at its own origin.
  const fs::path dir = scratch("many");
  write(dir / "tetra.stl", tetra_stl());
  std::string xml = "<robot name=\"m\">\n<link name=\"base_link\">\n";
  for (int i = 0; i < 500; ++i) {
    std::string x = std::to_string(i);
    xml += "<collision><origin xyz=\"" + x + " 0 0\"/><geometry><mesh filename=\"tetra.stl\"/>";
    xml += "</geometry></collision>\n";
  }
  xml += "</link>\n</robot>\n";
  const auto r = load_at(dir / "r.urdf", xml);
  ASSERT_EQ(r.collision_shapes.size(), 500u);
  // The tetrahedron spans x in [0, 2]: shape i spans [i, i + 2].
  EXPECT_NEAR(r.collision_shapes[499].aabb_B().min().x(), 499.0, 1e-6);
  EXPECT_NEAR(r.bounding_box_B.max().x(), 501.0, 1e-6);
}

TEST(MeshCollision, MeshFilesAboveSixtyFourMebibytesAreRefusedUnread) {
  const fs::path dir = scratch("huge");
  { std::ofstream(dir / "huge.stl") << "solid x\n"; }
  fs::resize_file(dir / "huge.stl", (std::uintmax_t{64} << 20) + 1);  // sparse: nothing written
  const auto e = load_error(dir / "r.urdf", mesh_robot("huge.stl"));
  EXPECT_EQ(e.source(), (dir / "r.urdf").string() + ":5");
  EXPECT_EQ(e.field(), "link[base_link]/collision[0]/geometry/mesh@filename");
  EXPECT_EQ(e.expected(), "a mesh file of at most 64 MiB");
}

TEST(MeshCollision, NestedSceneNodesComposeTheirTransforms) {
  // Walked with an explicit stack. A Wavefront OBJ has no node tree; a Collada file
  // does. 2000 nested <node>s, each
  // translating by 0.001 along x, hold the tetrahedron: it ends up 2 m along x.
  const fs::path dir = scratch("nested");
  std::string dae =
      "<?xml version=\"1.0\"?>\n<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" "
      "version=\"1.4.1\">\n<asset><unit meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n"
      "<library_geometries><geometry id=\"g\"><mesh>\n"
      "<source id=\"p\"><float_array id=\"pa\" count=\"12\">0 -1 0 2 -1 0 0 1 0 0 0 0.5"
      "</float_array><technique_common><accessor source=\"#pa\" count=\"4\" stride=\"3\">"
      "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
      "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
      "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
      "<triangles count=\"4\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
      "<p>0 2 1 0 1 3 1 2 3 2 0 3</p></triangles>\n"
      "</mesh></geometry></library_geometries>\n"
      "<library_visual_scenes><visual_scene id=\"s\">\n";
  constexpr int kDepth = 2000;
  for (int i = 0; i < kDepth; ++i) dae += "<node><translate>0.001 0 0</translate>";
  dae += "<instance_geometry url=\"#g\"/>";
  for (int i = 0; i < kDepth; ++i) dae += "</node>";
  dae +=
      "\n</visual_scene></library_visual_scenes>\n"
      "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
  write(dir / "nested.dae", dae);
  const auto r = load_at(dir / "r.urdf", mesh_robot("nested.dae"));
  // [0, 2] shifted by 2000 x 0.001 m and the collision origin's 1 m; assimp composes
  // the 2000 transforms in float, so x is good to 1e-4. Y_UP: assimp rotates nothing.
  ASSERT_EQ(r.collision_shapes.size(), 1u);
  const Eigen::AlignedBox3d b = r.collision_shapes[0].aabb_B();
  EXPECT_NEAR(b.min().x(), 3.0, 1e-4);
  EXPECT_NEAR(b.max().x(), 5.0, 1e-4);
  EXPECT_NEAR(b.min().y(), -1.0, 1e-6);
  EXPECT_NEAR(b.max().z(), 0.7, 1e-6);
}

}  // namespace
}  // namespace ferret
