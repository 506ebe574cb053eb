#include "ferret/mapping/block_revisions.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>

namespace ferret {

BlockRevisions::BlockRevisions(const GridGeometry& geometry, int block_cells)
    : width_cells_(std::max(1, geometry.width)),
      height_cells_(std::max(1, geometry.height)),
      block_cells_(block_cells),
      blocks_x_(0),
      blocks_y_(0) {
  if (block_cells < 1)
    throw std::invalid_argument("BlockRevisions: block_cells must be at least 1");
  blocks_x_ = (width_cells_ + block_cells_ - 1) / block_cells_;
  blocks_y_ = (height_cells_ + block_cells_ - 1) / block_cells_;
  blocks_.assign(static_cast<std::size_t>(blocks_x_) * static_cast<std::size_t>(blocks_y_), 0);
}

std::uint64_t BlockRevisions::Lineage::next() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

bool BlockRevisions::unchanged_since(std::uint64_t revision, Cell lo, Cell hi) const {
  const int bi0 = std::clamp(lo.i, 0, width_cells_ - 1) / block_cells_;
  const int bj0 = std::clamp(lo.j, 0, height_cells_ - 1) / block_cells_;
  const int bi1 = std::clamp(hi.i, 0, width_cells_ - 1) / block_cells_;
  const int bj1 = std::clamp(hi.j, 0, height_cells_ - 1) / block_cells_;
  for (int bj = bj0; bj <= bj1; ++bj)
    for (int bi = bi0; bi <= bi1; ++bi)
      if (blocks_[static_cast<std::size_t>(bj) * static_cast<std::size_t>(blocks_x_) +
                  static_cast<std::size_t>(bi)] > revision)
        return false;
  return true;
}

}  // namespace ferret
