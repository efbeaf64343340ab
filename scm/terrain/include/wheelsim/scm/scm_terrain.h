// The SCM soft-soil terrain (Krenn & Hirzinger's Soil Contact Model) as a grid algorithm,
// TERRAMECHANICS.md §4: a height grid of spacing Δ, Bekker pressure with elastic unloading (Ke)
// and damping, patch width b = 2A/L, Janosi–Hanamoto shear on accumulated shear displacement,
// Mohr–Coulomb, bulldozing with erosion, multi-pass memory. Where §4 is silent the choices are
// those of Project Chrono's SCMTerrain (listed in docs/scm-algorithm.md). Reference: docs/scm.md.
//
// Frames: world W (x forward, y left, z up; the undisturbed surface is z = surface_height_m),
// wheel body B = the mesh frame (origin Bo at the wheel centre, axle +y). The wheel's pose and the
// contact wrench are the shared types of wheelsim/pose.h (WheelPose, WheelWrench).
#pragma once

#include "wheelsim/pose.h"
#include "wheelsim/scm/soil.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace wheelsim::geometry {
struct TriangleMesh;
}

namespace wheelsim::scm {

/// Direction of the normal pressure on the wheel.
enum class NormalDirection {
  surface,  ///< along the wheel's surface normal at the node (default; compaction resistance in DP)
  vertical, ///< along the terrain's vertical, as Chrono's SCMTerrain (DP from shear alone)
};

/// Bulldozing: plastically displaced soil goes to the rim of each patch, then erodes.
struct BulldozingSettings {
  bool enabled = true;
  double erosion_angle_deg = 40.0; ///< angle of repose [deg], in (0, 90)
  double flow_factor = 1.0;        ///< displaced volume × this goes to the rim [-], ≥ 0
  int erosion_iterations = 3;      ///< smoothing sweeps per step, ≥ 0
  /// Rings of nodes around a patch that receive soil/erode, ≥ 1. 10: what every wheel-rig SCM run
  /// has used (docs/scm.md); also the rig config's default.
  int erosion_rings = 10;
};

struct ScmSettings {
  double grid_spacing_m = 0.02;  ///< Δ [m], > 0
  double surface_height_m = 0.0; ///< undisturbed surface level [m]
  NormalDirection normal = NormalDirection::surface;
  BulldozingSettings bulldozing;
  /// Where the soil is sheared [m]. Unset (default, as Chrono): each contact node's slip velocity
  /// is that of the wheel surface point above it. Set: that of the point at the same angle on the
  /// circle of this radius about the body's y axis through Bo (the wheel's axle), e.g. the lug
  /// tips' radius, so that soil caught between a lugged wheel's lugs turns with the wheel and the
  /// rim does not slide over it (docs/scm.md, "Shear surface"). Used for the shear only; the
  /// normal damping keeps the surface point's velocity.
  std::optional<double> shear_radius_m;
  /// Optional domain [m] (x_min, x_max, y_min, y_max); outside it the wheel meets no soil.
  /// Unset = unbounded: only touched tiles are stored, so track length costs nothing by itself.
  std::optional<Eigen::Vector4d> domain_m;
};

/// Result of one step.
struct ScmContact {
  WheelWrench wrench;    ///< soil force on the wheel and its torque about Bo, W [N, N m]
  int contact_nodes = 0; ///< nodes in contact this step
  int patches = 0;       ///< connected contact patches
};

/// Wall time [ms] of the parts of the last advance() (benchmarks), and the work they did.
struct ScmStepTimings {
  double rasterisation_ms = 0.0; ///< culling + exact rasterisation of the wheel onto the grid
  double node_law_ms = 0.0;      ///< elastic/plastic law, shear and force sums
  double patches_ms = 0.0;       ///< contact flood fill and b = 2A/L
  double bulldozing_ms = 0.0;    ///< displaced volume to the rim + erosion sweeps
  int triangles_rasterised = 0;  ///< triangles that covered at least one node
  int erosion_nodes = 0;         ///< nodes in the erosion domain
};

/// Node fields that can be sampled on a window of the grid (snapshots, maps).
enum class Field {
  height,             ///< current surface level [m]
  sinkage,            ///< initial − current level [m] (negative where soil piled up)
  plastic_sinkage,    ///< permanent sinkage [m]
  pressure,           ///< last normal pressure σ [Pa] (0 off contact)
  shear_stress,       ///< last shear stress τ [Pa]
  shear_displacement, ///< accumulated j [m]
};
const char *to_string(Field field);
const char *unit_of(Field field);

/// A sampled window: node (i, j) at x = x0_m + j Δ, y = y0_m + i Δ; values[i * cols + j].
struct FieldMap {
  double x0_m = 0.0, y0_m = 0.0, spacing_m = 0.0;
  std::size_t rows = 0, cols = 0;
  std::vector<double> values;
};

class ScmTerrain {
public:
  /// `wheel_mesh_B` is the wheel in its own frame B, in metres (closed, outward normals).
  /// Throws std::invalid_argument naming the offending setting or soil value.
  ScmTerrain(const SoilParameters &soil, const ScmSettings &settings,
             const geometry::TriangleMesh &wheel_mesh_B);
  ~ScmTerrain();
  ScmTerrain(ScmTerrain &&) noexcept;
  ScmTerrain &operator=(ScmTerrain &&) noexcept;

  /// Contact at `state`, and the soil's update over the step dt_s (shear displacement, plastic
  /// flow, bulldozing). Call once per step, in order.
  ScmContact advance(const WheelPose &state, double dt_s);

  /// Grid window [m] that holds every node ever touched (empty map if none).
  FieldMap sample(Field field) const;
  /// The field on the window x in [x_min, x_max], y in [y_min, y_max] (untouched nodes: their
  /// undisturbed values).
  FieldMap sample(Field field, double x_min, double x_max, double y_min, double y_max) const;

  /// Soil volume above (positive) / below the initial level summed over all nodes [m³],
  /// including bulldozed soil still waiting to be placed (Chrono's "mass remainder").
  double volume_change_m3() const;
  /// Nodes currently stored (tiles allocated × nodes per tile).
  std::size_t stored_nodes() const;

  const SoilParameters &soil() const;
  const ScmSettings &settings() const;
  /// Timings and counters of the last advance().
  const ScmStepTimings &last_step_timings() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace wheelsim::scm
