// Dense scratch arrays for one step: the rectangle of grid nodes the wheel can reach this step,
// plus a margin for bulldozing. Per-step quantities live here; persistent ones in the tiles.
#pragma once

#include "tile_grid.h"

#include <cstdint>
#include <vector>

namespace wheelsim::scm::detail {

enum CellFlag : std::uint8_t {
  kContact = 1,  ///< wheel below the node's elastic level (elastic trial σ > 0)
  kBoundary = 2, ///< receives bulldozed soil this step
  kErosion = 4,  ///< in the erosion domain this step
};

class StepWindow {
public:
  /// Covers nodes i in [i0, i0 + nx), j in [j0, j0 + ny); node pointers of allocated tiles.
  void reset(std::int64_t i0, std::int64_t j0, int nx, int ny, const TileGrid &grid);
  void clear() { nx_ = ny_ = 0; }

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  std::int64_t i0() const { return i0_; }
  std::int64_t j0() const { return j0_; }
  int size() const { return nx_ * ny_; }
  bool contains(std::int64_t i, std::int64_t j) const {
    return i >= i0_ && j >= j0_ && i < i0_ + nx_ && j < j0_ + ny_;
  }
  int cell(std::int64_t i, std::int64_t j) const {
    return static_cast<int>((j - j0_) * nx_ + (i - i0_));
  }
  std::int64_t i_of(int c) const { return i0_ + c % nx_; }
  std::int64_t j_of(int c) const { return j0_ + c / nx_; }

  /// The node of cell c, allocating its tile (and refreshing the window's pointers into it).
  NodeState &node(int c, TileGrid &grid);
  /// The node of cell c or nullptr if its tile does not exist yet.
  NodeState *find(int c) const { return node_[c]; }

  std::vector<double> hit_z; ///< lowest wheel surface above/below the node [m]; +inf if none
  std::vector<int> hit_tri;  ///< triangle (index into the step's triangle list) of hit_z, or -1
  std::vector<std::uint8_t> flags;
  std::vector<int> patch; ///< contact patch id, -1 if none

private:
  void attach_tile(std::int64_t ti, std::int64_t tj, Tile *tile);

  std::int64_t i0_ = 0, j0_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<NodeState *> node_;
};

} // namespace wheelsim::scm::detail
