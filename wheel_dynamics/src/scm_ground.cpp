#include "wheelsim/rig/scm_ground.h"

#include "wheelsim/geometry/mesh_io.h"
#include "wheelsim/scm/soil_file.h"

#include <limits>
#include <stdexcept>

namespace wheelsim::rig {
namespace {

geometry::TriangleMesh load_wheel_mesh(const RigConfig &config) {
  if (config.wheel.mesh.empty())
    throw RigConfigError(config.source + ": terrain.type = \"scm\" needs the wheel's surface: set "
                                         "wheel.mesh (OBJ, STL or PLY in the wheel frame)");
  try {
    geometry::LoadOptions options;
    options.scale = config.wheel.mesh_scale;
    return geometry::load_mesh(config.wheel.mesh, options);
  } catch (const std::exception &e) {
    throw RigConfigError(config.source + ": wheel.mesh: " + e.what());
  }
}

} // namespace

scm::SoilParameters scm_soil(const ScmTerrainConfig &config) {
  scm::SoilParameters soil;
  try {
    soil = scm::load_soil_file(config.soil);
  } catch (const std::exception &e) {
    throw RigConfigError(std::string("terrain.soil: ") + e.what());
  }
  if (config.elastic_stiffness_Pa_m)
    soil.elastic_K = *config.elastic_stiffness_Pa_m;
  if (config.damping_Pa_s_m)
    soil.damping_R = *config.damping_Pa_s_m;
  return soil;
}

scm::ScmSettings scm_settings(const RigConfig &config, const WheelProperties &wheel) {
  const ScmTerrainConfig &c = config.terrain.scm;
  scm::ScmSettings s;
  s.grid_spacing_m = c.grid_spacing_m;
  s.surface_height_m = config.terrain.surface_height_m;
  s.normal = c.vertical_normal ? scm::NormalDirection::vertical : scm::NormalDirection::surface;
  if (c.shear_at_lug_tips)
    s.shear_radius_m = wheel.effective_radius_m;
  s.bulldozing.enabled = c.bulldozing;
  s.bulldozing.erosion_angle_deg = c.erosion_angle_deg;
  s.bulldozing.flow_factor = c.flow_factor;
  s.bulldozing.erosion_iterations = static_cast<int>(c.erosion_iterations);
  s.bulldozing.erosion_rings = static_cast<int>(c.erosion_rings);
  if (c.grid_length_m || c.grid_width_m) {
    const double inf = std::numeric_limits<double>::infinity();
    const double x_min = c.grid_length_m ? -wheel.rim_radius_m : -inf;
    const double x_max = c.grid_length_m ? x_min + *c.grid_length_m : inf;
    const double half_width = c.grid_width_m ? 0.5 * *c.grid_width_m : inf;
    s.domain_m = Eigen::Vector4d(x_min, x_max, -half_width, half_width);
  }
  return s;
}

ScmGround::ScmGround(const RigConfig &config, const WheelProperties &wheel)
    : terrain_([&] {
        try {
          return scm::ScmTerrain(scm_soil(config.terrain.scm), scm_settings(config, wheel),
                                 load_wheel_mesh(config));
        } catch (const std::invalid_argument &e) {
          throw RigConfigError(config.source + ": [terrain] scm: " + e.what());
        }
      }()),
      dt_s_(config.run.dt_s) {}

WheelWrench ScmGround::contact(const WheelPose &state, double /*time_s*/) {
  last_ = terrain_.advance(state, dt_s_);
  return last_.wrench;
}

} // namespace wheelsim::rig
