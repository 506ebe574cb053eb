#include "mesh_bounds.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace ferret::internal {
namespace {

namespace fs = std::filesystem;

bool starts_with(const std::string& s, std::string_view prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

/// Bounds of every vertex under `root`, walking assimp's node tree with an explicit
/// stack (a scene file may nest nodes deeply).
void extend(const aiScene& scene, const aiNode& root, Eigen::AlignedBox3d& box) {
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack{{&root, aiMatrix4x4()}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    const aiMatrix4x4 X = parent * node->mTransformation;
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh& mesh = *scene.mMeshes[node->mMeshes[m]];
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D p = X * mesh.mVertices[v];
        box.extend(Eigen::Vector3d(p.x, p.y, p.z));
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) stack.emplace_back(node->mChildren[c], X);
  }
}

}  // namespace

fs::path resolve_mesh_path(const std::string& filename, const fs::path& urdf_dir,
                           std::vector<std::string>& tried) {
  std::vector<fs::path> candidates;
  if (starts_with(filename, "package://")) {
    const std::string rest = filename.substr(10);
    const auto slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    const fs::path inside =
        slash == std::string::npos ? fs::path() : fs::path(rest.substr(slash + 1));
    if (const char* env = std::getenv("ROS_PACKAGE_PATH")) {
      std::stringstream dirs(env);
      for (std::string dir; std::getline(dirs, dir, ':');)
        if (!dir.empty()) candidates.push_back(fs::path(dir) / package / inside);
    }
    // Beside the URDF: the usual layout is PKG/urdf/robot.urdf with PKG/meshes/...
    fs::path a = fs::absolute(urdf_dir.empty() ? fs::path(".") : urdf_dir).lexically_normal();
    for (;;) {
      candidates.push_back(a.filename() == package ? a / inside : a / package / inside);
      if (!a.has_parent_path() || a.parent_path() == a) break;
      a = a.parent_path();
    }
  } else {
    fs::path p(starts_with(filename, "file://") ? filename.substr(7) : filename);
    candidates.push_back(p.is_absolute() ? p : urdf_dir / p);
  }
  std::error_code ec;
  for (const auto& c : candidates) {
    if (fs::is_regular_file(c, ec)) return c;
    tried.push_back(c.string());
  }
  return {};
}

Eigen::AlignedBox3d mesh_vertex_bounds(const fs::path& path) {
  Assimp::Importer importer;
  // Only vertex positions are needed: no post-processing beyond what reading does.
  const aiScene* scene = importer.ReadFile(path.string(), 0);
  if (scene == nullptr || scene->mRootNode == nullptr)
    throw std::runtime_error(importer.GetErrorString());
  Eigen::AlignedBox3d box;
  box.setEmpty();
  extend(*scene, *scene->mRootNode, box);
  if (box.isEmpty()) throw std::runtime_error("the file holds no mesh vertices");
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(box.min()[i]) || !std::isfinite(box.max()[i]))
      throw std::runtime_error("vertices that are not finite numbers");
  return box;
}

}  // namespace ferret::internal
