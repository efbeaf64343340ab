// The SCM soft-soil terrain (scm/, docs/scm.md) as the rig's in-process Terrain: the same rig, the
// same wheel mesh and the same run file as a DEM run; only [terrain] differs.
#pragma once

#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/rig_simulation.h"
#include "wheelsim/rig/terrain.h"
#include "wheelsim/scm/scm_terrain.h"

namespace wheelsim::rig {

class ScmGround : public Terrain {
public:
  /// Loads the soil file (terrain.soil; the config's elastic_stiffness and damping override the
  /// file's) and the wheel mesh (wheel.mesh, required). The domain, if grid_length/grid_width are
  /// set, starts one rim radius behind the wheel's start and is centred on it in y; it must be at
  /// least as wide as the wheel and reach one rim radius beyond the wheel's end (its start plus the
  /// carriage's travel, where the config fixes the carriage speed).
  /// Throws RigConfigError naming the key (soil file, mesh or setting).
  ScmGround(const RigConfig &config, const WheelProperties &wheel);

  /// Steps the soil with the rig's time step (run.dt): call once per rig step, in order.
  WheelWrench contact(const WheelPose &state, double time_s) override;

  const scm::ScmTerrain &terrain() const { return terrain_; }
  double contact_count() const override { return last_.contact_nodes; }
  const scm::ScmTerrain *height_grid() const override { return &terrain_; }
  /// The contact of the last call (node and patch counts).
  const scm::ScmContact &last_contact() const { return last_; }

private:
  scm::ScmTerrain terrain_;
  double dt_s_;
  scm::ScmContact last_;
};

/// The soil of a config with terrain.type = "scm": the file's values with the config's overrides.
scm::SoilParameters scm_soil(const ScmTerrainConfig &config);
/// The SCM settings of a config (grid, normal direction, bulldozing, domain).
scm::ScmSettings scm_settings(const RigConfig &config, const WheelProperties &wheel);

} // namespace wheelsim::rig
