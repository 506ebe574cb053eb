#include "ferret/planning/floor_from_map.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace ferret {

std::optional<double> floor_z_from_map(const octomap::OcTree& observed, const Aabb3& box) {
  const double res = observed.getResolution();
  // Voxel centres lie at (k + 1/2) res; at most ~128 x 128 columns are looked at.
  const auto first = [&](double lo) { return (std::floor(lo / res) + 0.5) * res; };
  const double span = std::max(box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y());
  const int stride = std::max(1, static_cast<int>(std::ceil(span / res / 128.0)));
  const double z_lo = first(box.lo.z() - 1.0);
  std::map<long long, int> votes;  // floor top in voxels -> columns
  for (double y = first(box.lo.y()); y <= box.hi.y(); y += stride * res) {
    for (double x = first(box.lo.x()); x <= box.hi.x(); x += stride * res) {
      bool in_run = false;
      for (double z = z_lo; z <= box.hi.z() + 0.5 * res; z += res) {
        octomap::OcTreeKey key;
        bool occupied = false;
        if (observed.coordToKeyChecked(x, y, z, key)) {
          const octomap::OcTreeNode* node = observed.search(key);
          occupied = node && observed.isNodeOccupied(node);
        }
        if (occupied) {
          in_run = true;
        } else if (in_run) {
          ++votes[std::llround((z - 0.5 * res) / res)];  // the run's top face
          break;
        }
      }
    }
  }
  if (votes.empty()) return std::nullopt;
  const auto best = std::max_element(
      votes.begin(), votes.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  return static_cast<double>(best->first) * res;
}

}  // namespace ferret
