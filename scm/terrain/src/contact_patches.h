// Contact patches (TERRAMECHANICS.md §4 step 3): nodes in contact joined by 4-connectivity
// (flood fill, as Chrono), and b = 2A/L from the area A and perimeter L of the convex hull of the
// patch's node points (as Chrono; 1/b = 0 when A < 1e-6 m², as Chrono).
#pragma once

#include "step_window.h"

#include <Eigen/Core>

#include <vector>

namespace wheelsim::scm::detail {

struct ContactPatch {
  std::vector<int> cells; ///< window cells of the patch
  double area_m2 = 0.0;
  double perimeter_m = 0.0;
  double inv_b = 0.0; ///< L / (2A) [1/m]
};

/// Area and perimeter of the convex hull of 2D points (any order; duplicates allowed).
void convex_hull_area_perimeter(std::vector<Eigen::Vector2d> points, double &area,
                                double &perimeter);

/// Groups the window's contact cells (flag kContact; listed in `contact_cells`) into patches,
/// sets window.patch, and fills `patches` (cleared first).
void find_contact_patches(StepWindow &window, const std::vector<int> &contact_cells, double delta_m,
                          std::vector<ContactPatch> &patches);

} // namespace wheelsim::scm::detail
