#pragma once
// Which parts of a grid changed, and when: the grid cut into square blocks, each with
// the revision at which one of its cells last changed. A map bumps it for every cell it
// changes (O(1)); a reader that remembers revision() when it computed something from
// the cells of a region knows, by looking at that region's blocks only, whether the
// result still holds. The Bayesian viewpoint search keeps each viewpoint's view this
// way (planning/viewpoint_search.hpp): one frame changes the cells near the robot, not
// the views across the space.

#include <cstdint>
#include <vector>

#include "ferret/core/grid.hpp"

namespace ferret {

class BlockRevisions {
 public:
  explicit BlockRevisions(const GridGeometry& geometry, int block_cells = 16);

  /// The cell at `idx` changed: its block takes the next revision.
  void touch(std::size_t idx) {
    const auto i = static_cast<int>(idx % static_cast<std::size_t>(width_cells_));
    const auto j = static_cast<int>(idx / static_cast<std::size_t>(width_cells_));
    blocks_[static_cast<std::size_t>(j / block_cells_) * static_cast<std::size_t>(blocks_x_) +
            static_cast<std::size_t>(i / block_cells_)] = ++revision_;
  }
  /// The last revision given (0: nothing changed yet).
  [[nodiscard]] std::uint64_t revision() const { return revision_; }
  /// True when no cell of the blocks that meet the cells [lo, hi] (clipped to the grid)
  /// changed after `revision`.
  [[nodiscard]] bool unchanged_since(std::uint64_t revision, Cell lo, Cell hi) const;
  [[nodiscard]] int block_cells() const { return block_cells_; }
  /// Unique to this object (a copy gets its own): a reader that keeps results for one
  /// map tells by it that it is still looking at that map, not another one at the same
  /// address whose revisions happen to be as high.
  [[nodiscard]] std::uint64_t lineage() const { return lineage_.value; }

 private:
  struct Lineage {
    Lineage() : value(next()) {}
    Lineage(const Lineage&) : value(next()) {}
    Lineage& operator=(const Lineage&) {
      value = next();
      return *this;
    }
    static std::uint64_t next();
    std::uint64_t value;
  };

  int width_cells_, height_cells_, block_cells_, blocks_x_, blocks_y_;
  std::vector<std::uint64_t> blocks_;
  std::uint64_t revision_ = 0;
  Lineage lineage_;
};

}  // namespace ferret
