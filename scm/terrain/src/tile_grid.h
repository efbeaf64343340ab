// Sparse node storage: square tiles of kTileSize x kTileSize nodes, allocated on first write and
// kept in a hash map keyed by the tile index. Node (i, j) sits at x = i Δ, y = j Δ.
#pragma once

#include "node_state.h"

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>

namespace wheelsim::scm::detail {

constexpr int kTileShift = 5;
constexpr int kTileSize = 1 << kTileShift; ///< nodes per tile side (32)

struct Tile {
  std::array<NodeState, kTileSize * kTileSize> nodes; ///< node (li, lj) at [lj * kTileSize + li]
};

class TileGrid {
public:
  explicit TileGrid(double surface_m) : surface_m_(surface_m) {}

  /// Tile with index (ti, tj), or nullptr if never allocated.
  Tile *find_tile(std::int64_t ti, std::int64_t tj) const;
  /// Tile with index (ti, tj), allocated (all nodes undisturbed) if needed.
  Tile &tile(std::int64_t ti, std::int64_t tj);

  /// Node (i, j) or nullptr if its tile was never allocated.
  const NodeState *find(std::int64_t i, std::int64_t j) const;
  /// Node (i, j), allocating its tile if needed.
  NodeState &node(std::int64_t i, std::int64_t j);

  std::size_t tile_count() const { return tiles_.size(); }
  double surface_m() const { return surface_m_; }

  template <class F> void for_each_tile(F &&f) const {
    for (const auto &[key, tile] : tiles_)
      f(unpack_i(key), unpack_j(key), *tile);
  }

  static std::int64_t tile_of(std::int64_t i) { return i >> kTileShift; } // floor division
  static int local_of(std::int64_t i) { return static_cast<int>(i & (kTileSize - 1)); }

private:
  static std::uint64_t pack(std::int64_t ti, std::int64_t tj) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ti)) << 32) |
           static_cast<std::uint32_t>(tj);
  }
  static std::int64_t unpack_i(std::uint64_t k) {
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(k >> 32));
  }
  static std::int64_t unpack_j(std::uint64_t k) {
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(k));
  }
  struct KeyHash {
    std::size_t operator()(std::uint64_t k) const {
      k ^= k >> 33; // murmur3 finaliser: tile indices are small and clustered
      k *= 0xff51afd7ed558ccdULL;
      k ^= k >> 33;
      return static_cast<std::size_t>(k);
    }
  };

  double surface_m_;
  std::unordered_map<std::uint64_t, std::unique_ptr<Tile>, KeyHash> tiles_;
};

} // namespace wheelsim::scm::detail
