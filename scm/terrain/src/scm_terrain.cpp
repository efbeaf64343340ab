// ScmTerrain: the SCM grid algorithm of TERRAMECHANICS.md §4 on sparse tiles with an exact wheel
// intersection. The parts live in their own files: tile_grid (storage), step_window (per-step
// dense scratch), wheel_raster (exact intersection), node_law, contact_patches, bulldozing.
//
// Choices where §4 is silent. Checked against Project Chrono's SCMTerrain.cpp
// (SCMLoader::ComputeInternalForces, AddMaterialToNode, RemoveMaterialFromNode):
//  1. Sinkage z = level_initial − wheel surface height, vertical (flat terrain: Chrono's cos factor
//     is 1). Bekker uses this total sinkage. As Chrono.
//  2. Contact test = elastic trial Ke (z − z_plastic) > 0, i.e. the wheel is below the node's
//     elastically rebounded level (level_initial − z_plastic), which is at or above its displayed
//     level. As Chrono (its test is σ < 0 → skip).
//  3. Node level: set to the wheel surface height while in contact (elastic part included); when
//     contact ends the level stays where the wheel left it (no rebound of the displayed level).
//     As Chrono.
//  4. Plastic step only if the trial exceeds the yield: σ = (kc/b + kφ) z^n, yield = σ,
//     z_plastic = z − σ/Ke. Ke is taken as max(elastic_K, kφ). As Chrono.
//  5. Damping −R·v_n added to σ after the plastic step, not clamped (σ may go below 0 while the
//     wheel leaves); the damped σ enters Mohr–Coulomb and the force. As Chrono.
//  6. v_n, v_t: velocity of the wheel surface point relative to the soil (soil at rest), split
//     along the chosen normal (vertical: +z as Chrono; surface: the wheel normal). Differs from
//     Chrono in the point: Chrono takes the body velocity at (x, y, previous node level); we take
//     it at the wheel surface point above the node (v + ω × r), the point that touches the soil.
//     Option (ScmSettings::shear_radius_m, not in Chrono): v_t from the point at the same angle on
//     a circle of that radius about the axle (a lugged wheel's lug-tip envelope), v_n as above.
//  7. j += |v_t| dt while in contact; never reset (kept after contact is lost and over passes).
//     As Chrono. τ opposes v_t; τ = 0 direction-less when v_t = 0.
//  8. Patches: 4-connectivity flood fill (as Chrono) of the nodes in contact. Differs from Chrono:
//     Chrono floods all ray hits, including nodes where the wheel is up to its ray test offset
//     (0.1 m) above the soil, so its b grows with an unrelated ray-length setting.
//  9. b = 2A/L with A, L of the convex hull of the patch's node points (as Chrono); 1/b = 0 when
//     A < 1e-6 m² (as Chrono), so a one-row patch feels kφ only.
// 10. Node area Δ² (horizontal), for both normal directions. As Chrono.
// 11. Force applied at the wheel surface point above the node; moment about Bo. Differs from
//     Chrono (node at its previous level, moment about the body COM): our wheel frame origin is
//     the centre and the surface point is where the soil acts.
// 12. Bulldozing (as Chrono): per patch, flow = Σ Δz_plastic of its nodes; boundary = the
//     non-contact 4-neighbours of its nodes; each boundary node gets flow_factor·flow/|boundary|,
//     clamped so soil never rises into the wheel (the rest is kept as "remainder" that flows on);
//     raised soil raises level_initial too. Erosion domain = boundary dilated over non-contact
//     nodes; erosion_rings = Chrono's propagations + 1 (the boundary is ring 1). Sweeps: for each
//     domain node and each 4-neighbour, remainder flows by 0.5·Δremainder/4, and if the neighbour
//     is not in contact the step Δh above Δ tan(angle) is reduced by 0.5·(|Δh| − Δ tan)/4.
//     Differs from Chrono: (a) "touched" means in contact, not "damped σ > 0"; (b) every
//     neighbour takes part (Chrono skips nodes it never stored — tiles make storage
//     meaningless); (c) sweeps run in a fixed order (Chrono: hash-set order); (d) removal takes
//     from the remainder first and then the level, exactly conserving volume (Chrono's
//     remainder == amount case lowers the level without using the remainder).
// 13. Per-step reset of σ, τ of last step's contact nodes to 0 (as Chrono resets σ).
// 14. Wheel intersection: exact rasterisation, not Chrono's ray cast (float precision, 0.3–3 mm
//     error that Ke turns into large pressures). Domain bounds: nodes outside are not soil.
#include "wheelsim/scm/scm_terrain.h"

#include "bulldozing.h"
#include "contact_patches.h"
#include "node_law.h"
#include "settings_check.h"
#include "step_window.h"
#include "tile_grid.h"
#include "wheel_raster.h"

#include "wheelsim/geometry/triangle_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace wheelsim::scm {

const char *to_string(Field f) {
  switch (f) {
  case Field::height:
    return "height";
  case Field::sinkage:
    return "sinkage";
  case Field::plastic_sinkage:
    return "plastic_sinkage";
  case Field::pressure:
    return "pressure";
  case Field::shear_stress:
    return "shear_stress";
  case Field::shear_displacement:
    return "shear_displacement";
  }
  return "unknown";
}

const char *unit_of(Field f) {
  switch (f) {
  case Field::pressure:
  case Field::shear_stress:
    return "Pa";
  default:
    return "m";
  }
}

using namespace detail;

struct ScmTerrain::Impl {
  Impl(const SoilParameters &s, const ScmSettings &st, const geometry::TriangleMesh &mesh)
      : soil(s), settings(st), law(NodeLawConstants::from(s)), grid(st.surface_height_m),
        raster(mesh), max_level(st.surface_height_m) {
    bulldozing.flow_factor = st.bulldozing.flow_factor;
    bulldozing.max_step_m =
        st.grid_spacing_m * std::tan(st.bulldozing.erosion_angle_deg * M_PI / 180.0);
    bulldozing.iterations = st.bulldozing.erosion_iterations;
    bulldozing.rings = st.bulldozing.erosion_rings;
  }

  bool in_domain(std::int64_t i, std::int64_t j) const {
    if (!settings.domain_m)
      return true;
    const Eigen::Vector4d &d = *settings.domain_m;
    const double x = i * settings.grid_spacing_m, y = j * settings.grid_spacing_m;
    return x >= d[0] && x <= d[1] && y >= d[2] && y <= d[3];
  }

  ScmContact advance(const WheelPose &state, double dt);
  double value(const NodeState &n, Field f) const;

  /// The slip velocity that shears the soil at a contact point r from Bo (world frame; v: the
  /// surface point's velocity): v itself, or with settings.shear_radius_m that of the point at the
  /// same angle on the circle of that radius about the body's y axis (the axle) through Bo.
  Eigen::Vector3d shear_velocity(const WheelPose &state, const Eigen::Matrix3d &R_WB,
                                 const Eigen::Vector3d &r, const Eigen::Vector3d &v) const {
    if (!settings.shear_radius_m)
      return v;
    const Eigen::Vector3d axle = R_WB.col(1);
    const Eigen::Vector3d radial = r - r.dot(axle) * axle;
    const double rho = radial.norm();
    if (!(rho > 0.0))
      return v;
    const Eigen::Vector3d r_shear = r + radial * (*settings.shear_radius_m / rho - 1.0);
    return state.v_WB_W + state.w_WB_W.cross(r_shear);
  }

  SoilParameters soil;
  ScmSettings settings;
  NodeLawConstants law;
  BulldozingConstants bulldozing;
  TileGrid grid;
  WheelRasteriser raster;
  StepWindow window;
  std::vector<ContactPatch> patches;
  std::vector<int> contact_cells;
  std::vector<double> plastic_flow;
  std::vector<NodeState *> last_contact;
  double max_level; ///< upper bound of every node's elastic level [m]: the culling height
  bool touched = false;
  std::int64_t ti_lo = 0, ti_hi = -1, tj_lo = 0, tj_hi = -1; ///< bounds of touched nodes
  ScmStepTimings timings;
};

ScmContact ScmTerrain::Impl::advance(const WheelPose &state, double dt) {
  using clock = std::chrono::steady_clock;
  auto ms = [](clock::time_point a, clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  check_time_step(dt);
  const auto t0 = clock::now();
  for (NodeState *n : last_contact) {
    n->sigma = 0.0;
    n->tau = 0.0;
  }
  last_contact.clear();

  const double delta = settings.grid_spacing_m;
  const Eigen::Matrix3d R = state.q_WB.normalized().toRotationMatrix();
  const Eigen::Vector3d &p_Bo = state.p_WB_W;
  raster.rasterise(R, p_Bo, max_level, delta, bulldozing.rings + 2, grid, window);
  timings = ScmStepTimings{};
  timings.triangles_rasterised = raster.triangles_rasterised();
  ScmContact out;
  const auto t1 = clock::now();
  timings.rasterisation_ms = ms(t0, t1);
  if (window.size() == 0)
    return out;

  // Contact: elastic trial > 0.
  contact_cells.clear();
  const NodeState undisturbed = NodeState::undisturbed(settings.surface_height_m);
  for (int c = 0, size = window.size(); c < size; ++c) {
    if (window.hit_tri[c] < 0)
      continue;
    const NodeState *n = window.find(c);
    if (elastic_trial(n ? *n : undisturbed, window.hit_z[c], law.Ke) <= 0.0)
      continue;
    if (!in_domain(window.i_of(c), window.j_of(c)))
      continue;
    window.flags[c] |= kContact;
    contact_cells.push_back(c);
  }
  find_contact_patches(window, contact_cells, delta, patches);
  const auto t2 = clock::now();
  timings.patches_ms = ms(t1, t2);

  // Node law and force sums.
  plastic_flow.assign(window.size(), 0.0);
  const double area = delta * delta;
  const bool vertical = settings.normal == NormalDirection::vertical;
  const Eigen::Vector3d up(0.0, 0.0, 1.0);
  for (int c : contact_cells) {
    NodeState &n = window.node(c, grid);
    const Eigen::Vector3d p(window.i_of(c) * delta, window.j_of(c) * delta, window.hit_z[c]);
    const Eigen::Vector3d r = p - p_Bo;
    const Eigen::Vector3d v = state.v_WB_W + state.w_WB_W.cross(r);
    const Eigen::Vector3d v_shear = shear_velocity(state, R, r, v);
    const Eigen::Vector3d normal =
        vertical ? up : Eigen::Vector3d(-raster.normal_W(window.hit_tri[c]));
    const NodeLawResult res = apply_node_law(
        n, law, window.hit_z[c], patches[window.patch[c]].inv_b, normal, v, v_shear, dt);
    const Eigen::Vector3d F = area * (res.sigma * normal + res.tau * res.t_dir);
    out.wrench.f_B_W += F;
    out.wrench.t_B_W += r.cross(F);
    plastic_flow[c] = res.plastic_flow_m;
    max_level = std::max(max_level, n.level_initial - n.sinkage_plastic);
    last_contact.push_back(&n);
  }
  out.contact_nodes = static_cast<int>(contact_cells.size());
  out.patches = static_cast<int>(patches.size());
  const auto t3 = clock::now();
  timings.node_law_ms = ms(t2, t3);

  if (settings.bulldozing.enabled && !contact_cells.empty())
    timings.erosion_nodes =
        bulldoze(window, grid, patches, plastic_flow, bulldozing,
                 settings.domain_m ? &*settings.domain_m : nullptr, delta, max_level);
  timings.bulldozing_ms = ms(t3, clock::now());

  // Bounds of touched nodes: contact nodes and the reach of their bulldozing.
  const int reach = bulldozing.rings + 1;
  for (int c : contact_cells) {
    const std::int64_t i = window.i_of(c), j = window.j_of(c);
    if (!touched) {
      ti_lo = ti_hi = i;
      tj_lo = tj_hi = j;
      touched = true;
    }
    ti_lo = std::min(ti_lo, i - reach);
    ti_hi = std::max(ti_hi, i + reach);
    tj_lo = std::min(tj_lo, j - reach);
    tj_hi = std::max(tj_hi, j + reach);
  }
  return out;
}

double ScmTerrain::Impl::value(const NodeState &n, Field f) const {
  switch (f) {
  case Field::height:
    return n.level;
  case Field::sinkage:
    return settings.surface_height_m - n.level;
  case Field::plastic_sinkage:
    return n.sinkage_plastic;
  case Field::pressure:
    return n.sigma;
  case Field::shear_stress:
    return n.tau;
  case Field::shear_displacement:
    return n.shear_j;
  }
  return 0.0;
}

ScmTerrain::ScmTerrain(const SoilParameters &soil, const ScmSettings &settings,
                       const geometry::TriangleMesh &wheel_mesh_B) {
  check_soil(soil);
  check_settings(settings);
  if (wheel_mesh_B.triangles.empty())
    throw std::invalid_argument("scm wheel mesh must have at least one triangle, got 0");
  for (const auto &t : wheel_mesh_B.triangles)
    for (int k : t)
      if (k < 0 || k >= static_cast<int>(wheel_mesh_B.vertices_m.size()))
        throw std::invalid_argument("scm wheel mesh triangle index must be in [0, " +
                                    std::to_string(wheel_mesh_B.vertices_m.size()) + "), got " +
                                    std::to_string(k));
  impl_ = std::make_unique<Impl>(soil, settings, wheel_mesh_B);
}

ScmTerrain::~ScmTerrain() = default;
ScmTerrain::ScmTerrain(ScmTerrain &&) noexcept = default;
ScmTerrain &ScmTerrain::operator=(ScmTerrain &&) noexcept = default;

ScmContact ScmTerrain::advance(const WheelPose &state, double dt_s) {
  return impl_->advance(state, dt_s);
}

FieldMap ScmTerrain::sample(Field field) const {
  if (!impl_->touched)
    return FieldMap{0.0, 0.0, impl_->settings.grid_spacing_m, 0, 0, {}};
  const double d = impl_->settings.grid_spacing_m;
  return sample(field, impl_->ti_lo * d, impl_->ti_hi * d, impl_->tj_lo * d, impl_->tj_hi * d);
}

FieldMap ScmTerrain::sample(Field field, double x_min, double x_max, double y_min,
                            double y_max) const {
  const double d = impl_->settings.grid_spacing_m;
  FieldMap m;
  m.spacing_m = d;
  const std::int64_t i0 = static_cast<std::int64_t>(std::ceil(x_min / d - 1e-9));
  const std::int64_t i1 = static_cast<std::int64_t>(std::floor(x_max / d + 1e-9));
  const std::int64_t j0 = static_cast<std::int64_t>(std::ceil(y_min / d - 1e-9));
  const std::int64_t j1 = static_cast<std::int64_t>(std::floor(y_max / d + 1e-9));
  m.x0_m = i0 * d;
  m.y0_m = j0 * d;
  if (i1 < i0 || j1 < j0)
    return m;
  m.cols = static_cast<std::size_t>(i1 - i0 + 1);
  m.rows = static_cast<std::size_t>(j1 - j0 + 1);
  m.values.resize(m.rows * m.cols);
  const NodeState undisturbed = NodeState::undisturbed(impl_->settings.surface_height_m);
  for (std::int64_t j = j0; j <= j1; ++j)
    for (std::int64_t i = i0; i <= i1; ++i) {
      const NodeState *n = impl_->grid.find(i, j);
      m.values[(j - j0) * m.cols + (i - i0)] = impl_->value(n ? *n : undisturbed, field);
    }
  return m;
}

double ScmTerrain::volume_change_m3() const {
  const double surface = impl_->settings.surface_height_m;
  double sum = 0.0;
  impl_->grid.for_each_tile([&](std::int64_t, std::int64_t, const Tile &t) {
    for (const NodeState &n : t.nodes)
      sum += (n.level - surface) + n.remainder;
  });
  const double d = impl_->settings.grid_spacing_m;
  return sum * d * d;
}

std::size_t ScmTerrain::stored_nodes() const {
  return impl_->grid.tile_count() * static_cast<std::size_t>(kTileSize * kTileSize);
}

const SoilParameters &ScmTerrain::soil() const { return impl_->soil; }
const ScmSettings &ScmTerrain::settings() const { return impl_->settings; }
const ScmStepTimings &ScmTerrain::last_step_timings() const { return impl_->timings; }

} // namespace wheelsim::scm
