// One rig run on SCM for the reference tests: the study rig of TERRAMECHANICS.md §8 with a wheel
// from build/meshes, a soil from inputs/scm_soils, imposed slip, and test-phase statistics.
#pragma once

#include "wheelsim/rig/scm_ground.h"

#include <memory>
#include <string>

namespace wheelsim::test {

struct ScmRunSpec {
  std::string wheel = "smooth_1234"; ///< build/meshes/<wheel>.obj
  std::string soil = "lete_sand";    ///< inputs/scm_soils/<soil>.toml
  double load_N = 13200.0;
  double slip = 0.2;
  double grid_spacing_m = 0.02;
  double dt_s = 5e-4;
  double test_duration_s = 2.0;
  double elastic_K_Pa_m = 0.0; ///< 0: the soil file's
  bool vertical_normal = false;
  bool shear_at_lug_tips = false; ///< terrain.shear_surface = "lug_tips" (else "wheel")
  bool bulldozing = true;
  double flow_factor = 1.0;
};

/// Means and standard deviations over the second half of the test phase.
struct ScmRunResult {
  double sinkage_m = 0, sinkage_std_m = 0;
  double drawbar_pull_N = 0, drawbar_pull_std_N = 0;
  double driving_torque_Nm = 0;
  double slip = 0;
  double static_sinkage_m = 0; ///< end of the settle phase
  double rut_depth_m = 0;      ///< mean rut depth below the surface on the centre line behind it
  long long steps = 0;
};

/// The rig config text of a spec (what wheel-rig would read).
std::string scm_rig_config_text(const ScmRunSpec &spec);

/// Runs one spec on `ground` (a fresh one if null: then it is created from the spec and
/// returned through `ground_out`, so a second pass can reuse it).
ScmRunResult run_scm_rig(const ScmRunSpec &spec,
                         std::shared_ptr<rig::ScmGround> *ground_inout = nullptr);

} // namespace wheelsim::test
