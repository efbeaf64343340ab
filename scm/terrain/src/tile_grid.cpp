// Sparse tile storage of the SCM grid (see tile_grid.h).
#include "tile_grid.h"

namespace wheelsim::scm::detail {

Tile *TileGrid::find_tile(std::int64_t ti, std::int64_t tj) const {
  auto it = tiles_.find(pack(ti, tj));
  return it == tiles_.end() ? nullptr : it->second.get();
}

Tile &TileGrid::tile(std::int64_t ti, std::int64_t tj) {
  auto &slot = tiles_[pack(ti, tj)];
  if (!slot) {
    slot = std::make_unique<Tile>();
    slot->nodes.fill(NodeState::undisturbed(surface_m_));
  }
  return *slot;
}

const NodeState *TileGrid::find(std::int64_t i, std::int64_t j) const {
  const Tile *t = find_tile(tile_of(i), tile_of(j));
  return t ? &t->nodes[local_of(j) * kTileSize + local_of(i)] : nullptr;
}

NodeState &TileGrid::node(std::int64_t i, std::int64_t j) {
  return tile(tile_of(i), tile_of(j)).nodes[local_of(j) * kTileSize + local_of(i)];
}

} // namespace wheelsim::scm::detail
