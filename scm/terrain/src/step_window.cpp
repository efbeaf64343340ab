// Per-step dense window over the sparse tiles (see step_window.h).
#include "step_window.h"

#include <algorithm>
#include <limits>

namespace wheelsim::scm::detail {

void StepWindow::reset(std::int64_t i0, std::int64_t j0, int nx, int ny, const TileGrid &grid) {
  i0_ = i0;
  j0_ = j0;
  nx_ = nx;
  ny_ = ny;
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  hit_z.assign(n, std::numeric_limits<double>::infinity());
  hit_tri.assign(n, -1);
  flags.assign(n, 0);
  patch.assign(n, -1);
  node_.assign(n, nullptr);
  // One hash look-up per tile, not per node.
  for (std::int64_t tj = TileGrid::tile_of(j0); tj <= TileGrid::tile_of(j0 + ny - 1); ++tj)
    for (std::int64_t ti = TileGrid::tile_of(i0); ti <= TileGrid::tile_of(i0 + nx - 1); ++ti)
      if (Tile *t = grid.find_tile(ti, tj))
        attach_tile(ti, tj, t);
}

void StepWindow::attach_tile(std::int64_t ti, std::int64_t tj, Tile *tile) {
  const std::int64_t ia = std::max(i0_, ti * kTileSize);
  const std::int64_t ib = std::min(i0_ + nx_, (ti + 1) * kTileSize);
  const std::int64_t ja = std::max(j0_, tj * kTileSize);
  const std::int64_t jb = std::min(j0_ + ny_, (tj + 1) * kTileSize);
  for (std::int64_t j = ja; j < jb; ++j)
    for (std::int64_t i = ia; i < ib; ++i)
      node_[cell(i, j)] = &tile->nodes[TileGrid::local_of(j) * kTileSize + TileGrid::local_of(i)];
}

NodeState &StepWindow::node(int c, TileGrid &grid) {
  if (!node_[c]) {
    const std::int64_t ti = TileGrid::tile_of(i_of(c)), tj = TileGrid::tile_of(j_of(c));
    attach_tile(ti, tj, &grid.tile(ti, tj));
  }
  return *node_[c];
}

} // namespace wheelsim::scm::detail
