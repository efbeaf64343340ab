// Run health (docs/run-health.md): the checks every rig run makes on itself, as it goes and at
// the end, so that a run that went physically wrong says so instead of exiting 0 with numbers.
//
//   RunHealth health(sim, report);          // report: terminal + /health of the run file
//   health.set_grid(spacing_m, stiffness);  // SCM; or set_contact_stiffness (flat ground)
//   loop: health.before_step(wrench); out = sim.advance(wrench); health.after_step(out, n);
//   health.finish();                        // end-of-run checks; then status()
//
// Each finding has a code (one per check), a severity (a warning, or an error: the run is
// unhealthy and wheel-rig exits 1) and a message with the numbers and what to do. Checks that
// cannot go on (non-finite state, wheel buried, grid coarser than the wheel) record their
// finding and throw RunHealthError. Thresholds: HealthLimits; reasons in docs/run-health.md.
#pragma once

#include "wheelsim/rig/rig_simulation.h"

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wheelsim::rig {

enum class Severity { warning, error };
const char *to_string(Severity severity); ///< "warning" / "error"

struct HealthFinding {
  long long step = 0; ///< rig step at which it was seen (the last step for end-of-run checks)
  double time_s = 0.0;
  std::string code; ///< nonfinite_state, sinkage_beyond_radius, grid_coarse, lost_contact,
                    ///< slip_not_held, efficiency_bound, dt_unstable, steady_state_trend,
                    ///< settle_timeout, run_failed
  Severity severity = Severity::warning;
  std::string message;
};

/// Ends a run that cannot go on; its finding has been reported before the throw.
class RunHealthError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Thresholds of the checks (docs/run-health.md gives the reason for each).
struct HealthLimits {
  double contact_load_fraction = 0.01; ///< F_z below this share of W: out of contact [-]
  double lost_contact_warning = 0.05;  ///< share of test-phase steps out of contact [-]
  double lost_contact_error = 0.5;     ///< [-]
  double slip_tolerance = 0.01;        ///< mean |s - s_target| over the test phase [-]
  double efficiency_tolerance = 0.01;  ///< η above 1 - s by more than this [-]
  double stability_warning = 0.5;      ///< dt over the contact's stable step (time_step.h) [-]
  double stability_error = 1.0;        ///< ... at or above which the integrator diverges [-]
  double grid_spacing_error = 0.5;     ///< grid spacing above this share of the rim radius [-]
  double grid_nodes_across = 3.0;      ///< ... or fewer nodes across the wheel's width [-]
  double grid_lug_width = 1.0;         ///< ... warning above this share of the lug thickness [-]
  double contact_nodes_warning = 20.0; ///< mean grid nodes in contact in the test phase [-]
  double contact_nodes_error = 4.0;    ///< [-]
  double trend_sigmas = 3.0;           ///< half-window difference over its standard error [-]
  double trend_load_fraction = 0.01;   ///< ... and above this share of W (drawbar pull) [-]
  double trend_radius_fraction = 0.01; ///< ... or of the rim radius (sinkage) [-]
  double trend_slip = 0.01;            ///< ... or in slip (load-controlled modes) [-]
};

/// Standard error of the mean of autocorrelated samples by non-overlapping batch means: the
/// series is cut into `batches` equal batches; SEM = std(batch means) / sqrt(batches). NaN with
/// fewer than 2 samples per batch.
double batch_means_sem(const std::vector<double> &samples, int batches = 10);

class RunHealth {
public:
  using Report = std::function<void(const HealthFinding &)>;
  RunHealth(const RigSimulation &sim, Report report, HealthLimits limits = {});

  /// SCM: the grid spacing Δ [m] and the soil's elastic stiffness Ke [Pa/m]. Checks Δ against
  /// the wheel now (throws RunHealthError if coarser than half the rim radius or than a third of
  /// the wheel's width; a warning if wider than the lugs, when the wheel's props file gives
  /// them), enables the contact-patch resolution check (contact counts are grid nodes) and the
  /// stability check with contact stiffness Ke·n·Δ².
  void set_grid(double spacing_m, double elastic_K_Pa_m);
  /// A fixed contact stiffness [N/m] and damping [N s/m] for the stability check (flat ground:
  /// its k_n and c_n).
  void set_contact_stiffness(double stiffness_N_m, double damping_N_s_m = 0.0);

  /// Before RigSimulation::advance: the wrench must be finite (throws RunHealthError).
  void before_step(const WheelWrench &wrench);
  /// After advance: the outputs of step n (with `contacts` of that step) and the new state.
  /// Throws RunHealthError on a non-finite state or a buried wheel.
  void after_step(const RigOutputs &out, double contacts);
  /// The end-of-run checks. Call once when the run has ended normally.
  void finish();
  /// Records an error that ended the run from outside the checks (e.g. the coupling failed).
  void run_failed(const std::string &what);

  /// Checkpoints (wheelsim/rig/checkpoint.h): the test-phase statistics, the stability flags and
  /// the findings so far, under keys "health/...". restore_checkpoint() does not report the
  /// restored findings again (the run file keeps them).
  void save_checkpoint(CheckpointData &data) const;
  void restore_checkpoint(const CheckpointData &data);

  const std::vector<HealthFinding> &findings() const { return findings_; }
  bool has_error() const;
  /// "healthy" (no finding), "warnings" or "unhealthy" (an error).
  std::string status() const;

private:
  void add(Severity severity, const std::string &code, const std::string &message, long long step,
           double time_s);
  [[noreturn]] void stop(const std::string &code, const std::string &message, long long step,
                         double time_s);
  void check_steady(const std::vector<double> &samples, const char *quantity, const char *unit,
                    double threshold);

  const RigSimulation &sim_;
  Report report_;
  HealthLimits limits_;
  double grid_spacing_m_ = 0.0; // 0: not a grid terrain
  double elastic_K_Pa_m_ = 0.0; // SCM: stiffness per area [Pa/m]
  double stiffness_N_m_ = 0.0;  // flat: fixed contact stiffness [N/m]
  double damping_N_s_m_ = 0.0;  // flat: fixed contact damping [N s/m]
  bool stability_warned_ = false, stability_failed_ = false;
  bool buried_warned_ = false; ///< sinkage_beyond_radius warned once (the wheel still carried)
  long long last_step_ = 0;
  double last_time_s_ = 0.0;
  // test-phase statistics
  long long test_steps_ = 0, out_of_contact_steps_ = 0;
  double sum_slip_error_ = 0.0, sum_slip_ = 0.0, sum_output_power_W_ = 0.0,
         sum_input_power_W_ = 0.0, sum_traction_N_ = 0.0, sum_drawbar_pull_N_ = 0.0,
         sum_contacts_ = 0.0, load_N_ = 0.0;
  std::vector<double> drawbar_pull_N_, sinkage_m_, slip_;
  std::vector<HealthFinding> findings_;
};

} // namespace wheelsim::rig
