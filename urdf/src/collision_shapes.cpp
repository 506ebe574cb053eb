// The collision geometry of the URDF loader: a mesh collision's bounding box, read with
// file:line in pass 1 (mesh_bounds.cpp reads the file), and every link's collision
// shapes from urdfdom's model in pass 2, meshes as their boxes.

#include <cstdint>
#include <system_error>

#include "loader_passes.hpp"
#include "mesh_bounds.hpp"
#include "xml_check.hpp"

// GCC 12 reports -Wrestrict falsely on inlined std::string concatenation such as
// "'" + printable(text) (GCC PR 105329); this file's messages are built that way.
// Clang has no such warning (and would refuse the pragma under -Werror).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace ferret::internal {

namespace {

/// Meshes larger than this are refused before assimp reads them (about 1.3 million
/// triangles of binary STL; robot collision meshes are far smaller).
constexpr std::uintmax_t kMaxMeshBytes = std::uintmax_t{64} << 20;

}  // namespace

MeshBox read_mesh(const XmlSource& src, const TiXmlElement* mesh, const std::string& field,
                  const std::filesystem::path& urdf_dir, MeshCache& cache) {
  const std::string filename = attr_or_empty(mesh, "filename");
  if (filename.empty())
    src.fail(mesh, field + "@filename", "a mesh file (package://, file:// or a path)");
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  if (const char* text = mesh->Attribute("scale")) {
    const auto values = parse_numbers(text);
    bool ok = values && values->size() == 3;
    if (ok)
      for (const double v : *values) ok = ok && v != 0.0;
    if (!ok) src.fail(mesh, field + "@scale", "three non-zero numbers", quoted(text));
    scale = Eigen::Vector3d((*values)[0], (*values)[1], (*values)[2]);
  }
  std::vector<std::string> tried;
  const auto path = internal::resolve_mesh_path(filename, urdf_dir, tried);
  if (path.empty())
    src.fail(mesh, field + "@filename", "a mesh file that exists (tried " + join(tried) + ")",
             quoted(filename.c_str()));
  std::error_code ec;
  if (const auto bytes = std::filesystem::file_size(path, ec); !ec && bytes > kMaxMeshBytes)
    src.fail(mesh, field + "@filename", "a mesh file of at most 64 MiB",
             "'" + internal::printable(path.string()) + "': " + std::to_string(bytes) + " bytes");
  Eigen::AlignedBox3d raw;
  try {
    const auto known = cache.find(path.string());
    raw = known != cache.end()
              ? known->second
              : cache.emplace(path.string(), internal::mesh_vertex_bounds(path)).first->second;
  } catch (const std::exception& e) {
    std::string why = e.what();
    for (char& c : why)
      if (c == '\n' || c == '\r') c = ' ';
    src.fail(mesh, field + "@filename",
             "a mesh file assimp can read (STL, OBJ, DAE, ...) with vertices",
             "'" + path.string() + "': " + why);
  }
  // Scaling is per axis about C's origin; a negative factor mirrors, so take both corners.
  MeshBox out;
  out.path = path.string();
  out.box_C.setEmpty();
  out.box_C.extend(raw.min().cwiseProduct(scale));
  out.box_C.extend(raw.max().cwiseProduct(scale));
  const Eigen::Vector3d size = out.box_C.sizes();
  if ((size.array() <= 0.0).any())
    src.fail(mesh, field + "@filename", "a mesh with extent along x, y and z",
             "'" + path.string() + "': bounding box " + num(size.x()) + " x " + num(size.y()) +
                 " x " + num(size.z()) + " m");
  return out;
}

void read_collision_shapes(const urdf::ModelInterface& model,
                           const std::map<std::string, Pose3>& X_BL, const Structure& structure,
                           RobotDescription& out) {
  for (const auto& [name, link] : model.links_) {
    const auto pose = X_BL.find(name);
    if (pose == X_BL.end()) continue;
    // A collision urdfdom dropped without a word would silently shrink the robot.
    const auto expected = structure.collisions.find(name);
    const std::size_t declared = expected == structure.collisions.end() ? 0 : expected->second;
    if (link->collision_array.size() != declared)
      throw InputError(structure.link_at.at(name), "link[" + name + "]/collision",
                       std::to_string(declared) + " <collision> elements urdfdom reads",
                       "urdfdom read " + std::to_string(link->collision_array.size()));
    int index = -1;
    for (const auto& col : link->collision_array) {
      ++index;  // urdfdom keeps a link's <collision> elements in file order
      if (!col || !col->geometry) continue;
      CollisionShape s;
      s.link = name;
      s.X_BS = pose->second * to_pose(col->origin);
      switch (col->geometry->type) {
        case urdf::Geometry::MESH: {
          const auto mesh = structure.meshes.find({name, index});
          if (mesh == structure.meshes.end()) continue;
          // The box around the mesh, centred on S: X_BS = X_BC * translation(centre in C).
          s.type = CollisionShape::Type::kBox;
          s.box_size_m = mesh->second.box_C.sizes();
          s.X_BS = s.X_BS * Eigen::Translation3d(mesh->second.box_C.center());
          s.mesh = mesh->second.path;
          break;
        }
        case urdf::Geometry::BOX: {
          const auto& d = static_cast<const urdf::Box&>(*col->geometry).dim;
          s.type = CollisionShape::Type::kBox;
          s.box_size_m = Eigen::Vector3d(d.x, d.y, d.z);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& c = static_cast<const urdf::Cylinder&>(*col->geometry);
          s.type = CollisionShape::Type::kCylinder;
          s.radius_m = c.radius;
          s.length_m = c.length;
          break;
        }
        case urdf::Geometry::SPHERE:
          s.type = CollisionShape::Type::kSphere;
          s.radius_m = static_cast<const urdf::Sphere&>(*col->geometry).radius;
          break;
        default:
          continue;  // rejected in check_structure
      }
      out.collision_shapes.push_back(s);
    }
  }
}

}  // namespace ferret::internal
