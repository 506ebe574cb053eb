#pragma once
// Mesh collision geometry for the loader: where a URDF's mesh filename points, and the
// box that bounds the mesh's vertices. Assimp stays behind this header (private to
// ferret::urdf).

#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

namespace ferret::internal {

/// The file a URDF mesh filename names (package://, file:// or a path), tried in the
/// order documented at load_robot_description; `tried` receives the candidates when
/// none exists (the result is then empty).
[[nodiscard]] std::filesystem::path resolve_mesh_path(const std::string& filename,
                                                      const std::filesystem::path& urdf_dir,
                                                      std::vector<std::string>& tried);

/// The axis-aligned box of every vertex of the mesh file (node transforms applied), in
/// the mesh's own frame, before any URDF scale. Throws std::runtime_error with the
/// importer's reason for an unreadable file or a mesh without vertices.
[[nodiscard]] Eigen::AlignedBox3d mesh_vertex_bounds(const std::filesystem::path& path);

}  // namespace ferret::internal
