#include "wheelsim/rig/scm_ground.h"

#include "wheelsim/config_messages.h"
#include "wheelsim/geometry/triangle_mesh.h"
#include "wheelsim/scm/soil_file.h"

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

namespace wheelsim::rig {
namespace {

using config::fmt;

/// The carriage speed at the end of the motor's ramp [m/s] where the config imposes it
/// (carriage.speed; (1 − carriage.slip) ω R_eff with an imposed ω); NaN where it emerges from the
/// contact (the load modes, an imposed slip with a torque motor).
double imposed_carriage_speed_m_s(const RigConfig &c, double effective_radius_m) {
  if (c.carriage.mode == CarriageMode::imposed_speed)
    return c.carriage.speed_m_s;
  if (c.carriage.mode == CarriageMode::imposed_slip && c.motor.mode == MotorMode::omega)
    return (1.0 - c.carriage.slip) * c.motor.omega_rad_s * effective_radius_m;
  return std::numeric_limits<double>::quiet_NaN();
}

/// A bounded soil (grid_length and grid_width, which the parser requires together) must hold the
/// whole wheel over the whole run: across its width (the mesh's extent along the axle) ...
void check_domain_width(const RigConfig &config, const WheelProperties &wheel) {
  const double width_m = *config.terrain.scm.grid_width_m;
  if (width_m < wheel.width_m)
    throw RigConfigError(config.source + ": terrain.grid_width = " + fmt(width_m) +
                         " m is narrower than the wheel (" + fmt(wheel.width_m) +
                         " m wide along its axle, wheel.mesh): the soil must span the wheel's "
                         "width; give at least " +
                         fmt(wheel.width_m) + " m (plus room for the bulldozed rims)");
}

/// ... and along x from one rim radius behind the wheel's start (where the soil starts) to one rim
/// radius beyond its end, the carriage's travel ahead: speed × (motor.ramp_time / 2 +
/// run.duration) where the config fixes the speed (the carriage stands still in the release and
/// settle phases and ramps with the motor).
void check_domain_length(const RigConfig &config, const WheelProperties &wheel) {
  const double length_m = *config.terrain.scm.grid_length_m;
  const double speed_m_s = imposed_carriage_speed_m_s(config, wheel.effective_radius_m);
  const double travel_time_s = 0.5 * config.motor.ramp_time_s + config.run.duration_s;
  const double travel_m = std::isfinite(speed_m_s) ? speed_m_s * travel_time_s : 0.0;
  const std::string speed_text =
      "the carriage's " + fmt(speed_m_s) +
      " m/s over motor.ramp_time / 2 + run.duration = " + fmt(travel_time_s) + " s";
  if (travel_m < 0.0)
    throw RigConfigError(config.source + ": " + speed_text + " drive the wheel " + fmt(-travel_m) +
                         " m backwards, off the bounded soil (terrain.grid_length starts one rim "
                         "radius behind the wheel's start); drive forwards or leave out "
                         "terrain.grid_length and terrain.grid_width for unbounded soil");
  const double rim_radius_m = wheel.rim_radius_m;
  const double needed_m = 2.0 * rim_radius_m + travel_m;
  if (length_m < needed_m)
    throw RigConfigError(
        config.source + ": terrain.grid_length = " + fmt(length_m) +
        " m is too short for the wheel: the soil starts one rim radius (" + fmt(rim_radius_m) +
        " m) behind the wheel's start and must reach one rim radius beyond its end" +
        (std::isfinite(speed_m_s) ? ", " + fmt(travel_m) + " m ahead (" + speed_text + ")"
                                  : " (its travel emerges in this carriage mode: not counted)") +
        "; give at least " + fmt(needed_m) + " m");
}

void check_domain(const RigConfig &config, const WheelProperties &wheel) {
  if (!config.terrain.scm.grid_length_m || !config.terrain.scm.grid_width_m)
    return; // unbounded
  check_domain_width(config, wheel);
  check_domain_length(config, wheel);
}

/// The wheel surface: the one resolve_wheel_properties loaded (resolved again for properties
/// built without it).
std::shared_ptr<const geometry::TriangleMesh> wheel_mesh(const RigConfig &config,
                                                         const WheelProperties &wheel) {
  if (config.wheel.mesh.empty())
    throw RigConfigError(config.source + ": terrain.type = \"scm\" needs the wheel's surface: set "
                                         "wheel.mesh (OBJ, STL or PLY in the wheel frame)");
  return wheel.mesh ? wheel.mesh : resolve_wheel_properties(config.wheel).mesh;
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
        const auto mesh = wheel_mesh(config, wheel);
        check_domain(config, wheel);
        try {
          return scm::ScmTerrain(scm_soil(config.terrain.scm), scm_settings(config, wheel), *mesh);
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
