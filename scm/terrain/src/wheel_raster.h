// Exact intersection of the wheel with the grid's vertical lines: the wheel's downward-facing
// triangles, transformed to W, are rasterised onto the nodes they cover in xy; the height at a
// node is the exact barycentric interpolation of the triangle's vertex heights (double
// precision), the lowest over all triangles is kept. Triangles are culled in the wheel frame B:
// they are binned by the angle of their centroid about the axle (B's y axis) and, inside each
// angular sector, by their largest distance from the axle; a sector or bin is skipped when its
// bounding box cannot reach below the highest soil level.
#pragma once

#include "step_window.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace wheelsim::geometry {
struct TriangleMesh;
}

namespace wheelsim::scm::detail {

class WheelRasteriser {
public:
  explicit WheelRasteriser(const geometry::TriangleMesh &mesh_B, int sectors = 256, int bands = 8);

  /// Rasterises the wheel at pose (R_WB, p_WB_W) onto a new window of `window` (nodes at
  /// spacing delta_m), keeping only triangles that reach below z_cut_m. The window covers the
  /// xy footprint of the kept triangles plus `margin` nodes on each side (empty if none).
  /// Afterwards normal_W(hit_tri[c]) is the outward unit normal (W) of the triangle at cell c.
  void rasterise(const Eigen::Matrix3d &R_WB, const Eigen::Vector3d &p_WB_W, double z_cut_m,
                 double delta_m, int margin, const TileGrid &grid, StepWindow &window);

  const Eigen::Vector3d &normal_W(int step_triangle) const { return step_normal_W_[step_triangle]; }
  int triangles_rasterised() const { return static_cast<int>(step_normal_W_.size()); }

private:
  struct Box {
    Eigen::Vector3d lo, hi; ///< bounding box in B [m]
    /// Lowest value of up_B · v over the box.
    double lowest(const Eigen::Vector3d &up_B) const;
    void grow(const Eigen::Vector3d &v);
  };
  struct Bin {
    Box box;
    int begin = 0, end = 0; ///< range in tri_
  };
  struct Sector {
    Box box;
    std::vector<Bin> bands;
  };
  struct Triangle {
    std::array<int, 3> v; ///< vertex indices
    Eigen::Vector3d n_B;  ///< outward unit normal in B
  };

  std::vector<Eigen::Vector3d> vertices_B_;
  std::vector<Triangle> tri_; ///< sorted by sector, then band
  std::vector<Sector> sectors_;
  // Per step: vertices transformed to W on first use (stamp == step_), the normals (W) of the
  // triangles kept.
  std::vector<Eigen::Vector3d> vertices_W_;
  std::vector<unsigned> stamp_;
  unsigned step_ = 0;
  std::vector<Eigen::Vector3d> step_normal_W_;
};

} // namespace wheelsim::scm::detail
