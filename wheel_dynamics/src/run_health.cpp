#include "wheelsim/rig/run_health.h"

#include "wheelsim/config_messages.h"
#include "wheelsim/rig/slip_modes.h"
#include "wheelsim/rig/time_step.h"

#include <cmath>
#include <numeric>

namespace wheelsim::rig {
namespace {

using config::fmt;

double mean(const double *begin, const double *end) {
  return begin == end ? std::nan("") : std::accumulate(begin, end, 0.0) / double(end - begin);
}

/// The first non-finite value of `values` named by `names`, or nullptr.
const char *first_nonfinite(std::initializer_list<std::pair<const char *, double>> values,
                            double *value) {
  for (const auto &[name, v] : values)
    if (!std::isfinite(v)) {
      *value = v;
      return name;
    }
  return nullptr;
}

/// The slip the config imposes in the test phase, or NaN when slip is free: the slip mode's
/// (slip_modes.cpp).
double imposed_slip(const RigConfig &c, double effective_radius_m) {
  return slip_mode(c.carriage.mode).held_slip(c, effective_radius_m);
}

} // namespace

const char *to_string(Severity s) { return s == Severity::error ? "error" : "warning"; }

double batch_means_sem(const std::vector<double> &x, int batches) {
  if (batches < 2 || x.size() < 2 * static_cast<std::size_t>(batches))
    return std::nan("");
  const std::size_t per = x.size() / batches;
  std::vector<double> m(batches);
  for (int b = 0; b < batches; ++b)
    m[b] = mean(x.data() + b * per, x.data() + (b + 1) * per);
  const double mm = mean(m.data(), m.data() + batches);
  double ss = 0.0;
  for (double v : m)
    ss += (v - mm) * (v - mm);
  return std::sqrt(ss / (batches - 1) / batches);
}

RunHealth::RunHealth(const RigSimulation &sim, Report report, HealthLimits limits)
    : sim_(sim), report_(std::move(report)), limits_(limits) {}

void RunHealth::add(Severity severity, const std::string &code, const std::string &message,
                    long long step, double time_s) {
  HealthFinding f;
  f.step = step;
  f.time_s = time_s;
  f.code = code;
  f.severity = severity;
  f.message = message;
  findings_.push_back(f);
  if (report_)
    report_(findings_.back());
}

void RunHealth::stop(const std::string &code, const std::string &message, long long step,
                     double time_s) {
  add(Severity::error, code, message, step, time_s);
  throw RunHealthError(code + ": " + message);
}

void RunHealth::set_grid(double spacing_m, double elastic_K_Pa_m) {
  grid_spacing_m_ = spacing_m;
  elastic_K_Pa_m_ = elastic_K_Pa_m;
  const double R = sim_.wheel().rim_radius_m;
  if (spacing_m > limits_.grid_spacing_error * R)
    stop("grid_coarse",
         "terrain.grid_spacing = " + fmt(spacing_m) + " m is coarser than half the wheel's rim " +
             "radius (" + fmt(R) + " m): the contact patch cannot be resolved. grid_spacing is " +
             "in metres (did you mean " + fmt(spacing_m / 1000.0) + "?); use at most about " +
             fmt(R / 20.0) + " m (R/20)",
         sim_.step(), sim_.time_s());
  // Fewer than 3 node rows across the wheel: SCM's patch width b = 2A/L (Bekker's kc/b) and its
  // node sums are then off by up to a whole row, a third of the width or more.
  const double width_m = sim_.wheel().width_m;
  if (width_m > 0.0 && spacing_m > width_m / limits_.grid_nodes_across)
    stop("grid_coarse",
         "terrain.grid_spacing = " + fmt(spacing_m) + " m leaves fewer than " +
             fmt(limits_.grid_nodes_across) + " grid nodes across the wheel's width (" +
             fmt(width_m) + " m, wheel.mesh): the contact patch's width (Bekker's b) and its " +
             "force sums cannot be resolved; use at most " +
             fmt(width_m / limits_.grid_nodes_across) + " m (width/" +
             fmt(limits_.grid_nodes_across) + "); the shipped SCM configs have 16-50 nodes across",
         sim_.step(), sim_.time_s());
  // A lug narrower than the grid spacing can pass between two node rows: the terrain then sees
  // it only at some positions, and its thrust comes and goes with the lug's phase on the grid.
  const auto &wheel = sim_.wheel();
  if (wheel.lug_width_m > 0.0 && spacing_m > limits_.grid_lug_width * wheel.lug_width_m)
    add(Severity::warning, "grid_coarse",
        "terrain.grid_spacing = " + fmt(spacing_m) + " m is wider than the wheel's lugs (" +
            fmt(wheel.lug_width_m) + " m thick, " + wheel.lug_source +
            "): a lug can pass between grid nodes and is seen only at some positions; use at "
            "most " +
            fmt(wheel.lug_width_m / 2.0) + " m (half the lug thickness)",
        sim_.step(), sim_.time_s());
}

void RunHealth::set_contact_stiffness(double stiffness_N_m, double damping_N_s_m) {
  stiffness_N_m_ = stiffness_N_m;
  damping_N_s_m_ = damping_N_s_m;
}

void RunHealth::before_step(const WheelWrench &w) {
  double bad = 0.0;
  const char *name = first_nonfinite({{"contact force x", w.f_B_W.x()},
                                      {"contact force y", w.f_B_W.y()},
                                      {"contact force z", w.f_B_W.z()},
                                      {"contact torque x", w.t_B_W.x()},
                                      {"contact torque y", w.t_B_W.y()},
                                      {"contact torque z", w.t_B_W.z()}},
                                     &bad);
  if (name != nullptr)
    stop("nonfinite_state",
         std::string(name) + " is " + fmt(bad) + " at step " + std::to_string(sim_.step()) +
             " (t = " + fmt(sim_.time_s()) + " s, " + to_string(sim_.phase()) +
             " phase): the terrain's contact diverged; reduce run.dt or check the terrain",
         sim_.step(), sim_.time_s());
}

void RunHealth::after_step(const RigOutputs &o, double contacts) {
  last_step_ = o.step;
  last_time_s_ = o.time_s;
  const WheelPose s = sim_.wheel_state(); // state n+1
  double bad = 0.0;
  const char *name = first_nonfinite({{"wheel position x", s.p_WB_W.x()},
                                      {"wheel position z", s.p_WB_W.z()},
                                      {"wheel velocity x", s.v_WB_W.x()},
                                      {"wheel velocity z", s.v_WB_W.z()},
                                      {"wheel angular velocity y", s.w_WB_W.y()},
                                      {"driving torque", o.driving_torque_Nm},
                                      {"drawbar pull", o.drawbar_pull_N}},
                                     &bad);
  if (name != nullptr)
    stop("nonfinite_state",
         std::string(name) + " is " + fmt(bad) + " after step " + std::to_string(o.step) +
             " (t = " + fmt(o.time_s) + " s, " + to_string(o.phase) +
             " phase): the rig diverged; reduce run.dt",
         o.step, o.time_s);
  // Below one radius the wheel centre is under the undisturbed surface. Out of contact there
  // (a vanishing or far too coarse terrain), or below two radii (the whole wheel under the
  // surface), the run stops; still carried by the terrain (a locked wheel digging into a soft
  // DEM soil), it is a warning, once.
  const double R = sim_.wheel().rim_radius_m;
  const bool in_contact = o.contact.f_B_W.z() >= limits_.contact_load_fraction * o.vertical_load_N;
  const auto beyond_radius = [&] {
    return "the sinkage is " + fmt(o.sinkage_m) + " m at step " + std::to_string(o.step) +
           " (t = " + fmt(o.time_s) + " s): more than the rim radius " + fmt(R) + " m, ";
  };
  if (o.sinkage_m > R && (!in_contact || o.sinkage_m > 2.0 * R))
    stop("sinkage_beyond_radius",
         beyond_radius() + "the wheel centre is below the soil surface, and " +
             (in_contact ? "the whole wheel is under it (more than 2 radii)"
                         : "the terrain does not carry the wheel") +
             " (check terrain.grid_spacing, the soil, terrain.surface_height)",
         o.step, o.time_s);
  else if (o.sinkage_m > R && !buried_warned_) {
    buried_warned_ = true;
    add(Severity::warning, "sinkage_beyond_radius",
        beyond_radius() +
            "the wheel centre is below the undisturbed surface while the terrain still " +
            "carries it (vertical contact force " + fmt(o.contact.f_B_W.z()) +
            " N): the wheel is digging itself in",
        o.step, o.time_s);
  }

  // Stability: the contact as a spring-damper on the spindle's mass, against the integrator's
  // stable step (time_step.h, the bound wheel-rig --check applies to the springs the config fixes).
  // (SCM: Ke n Δ², no damper; the flat ground: the fixed k and c set_contact_stiffness gave)
  const double k = grid_spacing_m_ > 0.0
                       ? elastic_K_Pa_m_ * contacts * grid_spacing_m_ * grid_spacing_m_
                       : stiffness_N_m_;
  if (k > 0.0) {
    const OscillatorMode contact{"", k, damping_N_s_m_, sim_.rig().spindle_dof_mass_kg()};
    const double dt = sim_.config().run.dt_s, limit_s = contact.stable_time_step_s();
    const double share = dt / limit_s;
    // The message is built only for a finding: this runs at every step.
    const auto what = [&] {
      return "the contact's stiffness " + fmt(k) + " N/m" +
             (contact.damping_N_s_m > 0.0 ? " and damping " + fmt(contact.damping_N_s_m) + " N s/m"
                                          : std::string()) +
             " on the wheel + spindle mass " + fmt(contact.mass_kg) +
             " kg is stable up to dt = " + fmt(limit_s) +
             " s ((omega dt)^2 + 2 (c/m) dt < 4); run.dt = " + fmt(dt) + " s is " + fmt(share) +
             " of it (step " + std::to_string(o.step) + ")";
    };
    const auto margin = [&] { return fmt(limits_.stability_warning * limit_s); };
    if (share >= limits_.stability_error && !stability_failed_) {
      stability_failed_ = true;
      add(Severity::error, "dt_unstable",
          what() + ": the explicit integrator diverges; reduce run.dt below " + margin() + " s",
          o.step, o.time_s);
    } else if (share > limits_.stability_warning && !stability_warned_ && !stability_failed_) {
      stability_warned_ = true;
      add(Severity::warning, "dt_unstable",
          what() + ": less than a factor " +
              fmt(limits_.stability_error / limits_.stability_warning) +
              " inside the limit; reduce run.dt below " + margin() + " s for a margin",
          o.step, o.time_s);
    }
  }

  if (o.phase != Phase::test)
    return;
  ++test_steps_;
  load_N_ = o.vertical_load_N;
  if (o.contact.f_B_W.z() < limits_.contact_load_fraction * o.vertical_load_N)
    ++out_of_contact_steps_;
  const double target = imposed_slip(sim_.config(), sim_.wheel().effective_radius_m);
  if (std::isfinite(target))
    sum_slip_error_ += std::isfinite(o.slip) ? std::abs(o.slip - target) : 1.0;
  sum_slip_ += std::isfinite(o.slip) ? o.slip : 0.0;
  sum_output_power_W_ += o.drawbar_pull_N * o.forward_velocity_m_s;
  sum_input_power_W_ += o.driving_torque_Nm * o.omega_rad_s;
  sum_traction_N_ += o.traction_force_N;
  sum_drawbar_pull_N_ += o.drawbar_pull_N;
  sum_contacts_ += contacts;
  drawbar_pull_N_.push_back(o.drawbar_pull_N);
  sinkage_m_.push_back(o.sinkage_m);
  slip_.push_back(std::isfinite(o.slip) ? o.slip : 0.0);
}

void RunHealth::check_steady(const std::vector<double> &x, const char *quantity, const char *unit,
                             double threshold) {
  // Second half of the test phase, cut in two: the difference of the quarter means against its
  // standard error (batch means), and against a practical threshold.
  const std::size_t n = x.size() / 2;
  if (n < 40)
    return;
  const std::vector<double> a(x.end() - n, x.end() - n / 2), b(x.end() - n / 2, x.end());
  const double diff = mean(b.data(), b.data() + b.size()) - mean(a.data(), a.data() + a.size());
  const double sa = batch_means_sem(a), sb = batch_means_sem(b);
  const double sigma = std::sqrt(sa * sa + sb * sb);
  if (std::abs(diff) > limits_.trend_sigmas * sigma && std::abs(diff) > threshold)
    add(Severity::warning, "steady_state_trend",
        std::string(quantity) + " changed by " + fmt(diff) + " " + unit +
            " between the last two quarters of the test phase (" + fmt(std::abs(diff) / sigma) +
            " standard errors, threshold " + fmt(threshold) + " " + unit +
            "): not steady; lengthen run.duration",
        last_step_, last_time_s_);
}

void RunHealth::finish() {
  for (const std::string &w : sim_.warnings())
    add(Severity::warning, "settle_timeout", w, last_step_, last_time_s_);
  if (test_steps_ == 0)
    return;
  const double n = static_cast<double>(test_steps_);
  const RigConfig &c = sim_.config();

  const double lost = out_of_contact_steps_ / n;
  if (lost > limits_.lost_contact_warning) {
    const bool error = lost > limits_.lost_contact_error;
    add(error ? Severity::error : Severity::warning, "lost_contact",
        "the wheel was out of contact (vertical contact force below " +
            fmt(100.0 * limits_.contact_load_fraction) + " % of the load " + fmt(load_N_) +
            " N) in " + fmt(100.0 * lost) + " % of the test phase's steps (threshold " +
            fmt(100.0 * (error ? limits_.lost_contact_error : limits_.lost_contact_warning)) +
            " %): the wheel bounces or the terrain does not hold it",
        last_step_, last_time_s_);
  }

  const double target = imposed_slip(c, sim_.wheel().effective_radius_m);
  if (std::isfinite(target) && sum_slip_error_ / n > limits_.slip_tolerance)
    add(Severity::error, "slip_not_held",
        "the mean |slip - " + fmt(target) + "| over the test phase is " + fmt(sum_slip_error_ / n) +
            " (tolerance " + fmt(limits_.slip_tolerance) +
            "): the rig did not hold the imposed slip",
        last_step_, last_time_s_);

  const double slip = sum_slip_ / n;
  if (sum_input_power_W_ > 0.0 && slip >= 0.0 && slip < 1.0) {
    const double eta = sum_output_power_W_ / sum_input_power_W_;
    if (eta > 1.0 - slip + limits_.efficiency_tolerance)
      add(Severity::warning, "efficiency_bound",
          "the test phase's tractive efficiency (mean DP*v / mean T*omega) is " + fmt(eta) +
              ", above the bound 1 - s = " + fmt(1.0 - slip) + ": the traction force T/R_eff (" +
              fmt(sum_traction_N_ / n) + " N) is below the drawbar pull (" +
              fmt(sum_drawbar_pull_N_ / n) + " N), a negative rolling resistance; R_eff = " +
              fmt(sim_.wheel().effective_radius_m) +
              " m may be larger than the radius the soil acts at, or the run is not steady",
          last_step_, last_time_s_);
  }

  if (grid_spacing_m_ > 0.0) {
    const double nodes = sum_contacts_ / n;
    if (nodes < limits_.contact_nodes_warning) {
      const bool error = nodes < limits_.contact_nodes_error;
      add(error ? Severity::error : Severity::warning, "grid_coarse",
          "the contact patch held " + fmt(nodes) + " grid nodes on average in the test phase " +
              "(threshold " +
              fmt(error ? limits_.contact_nodes_error : limits_.contact_nodes_warning) +
              ") at terrain.grid_spacing = " + fmt(grid_spacing_m_) +
              " m: too coarse for the wheel; halve grid_spacing",
          last_step_, last_time_s_);
    }
  }

  const unsigned steady = slip_mode(c.carriage.mode).steady; // what the mode leaves free
  if (steady & steady_drawbar_pull)
    check_steady(drawbar_pull_N_, "the drawbar pull", "N", limits_.trend_load_fraction * load_N_);
  if (steady & steady_slip)
    check_steady(slip_, "the slip", "", limits_.trend_slip);
  if (steady & steady_sinkage)
    check_steady(sinkage_m_, "the sinkage", "m",
                 limits_.trend_radius_fraction * sim_.wheel().rim_radius_m);
}

void RunHealth::run_failed(const std::string &what) {
  add(Severity::error, "run_failed", what, sim_.step(), sim_.time_s());
}

bool RunHealth::has_error() const {
  for (const auto &f : findings_)
    if (f.severity == Severity::error)
      return true;
  return false;
}

std::string RunHealth::status() const {
  return has_error() ? "unhealthy" : findings_.empty() ? "healthy" : "warnings";
}

void RunHealth::save_checkpoint(CheckpointData &data) const {
  data.set_numbers("health/flags", {stability_warned_ ? 1.0 : 0.0, stability_failed_ ? 1.0 : 0.0});
  data.set_integer("health/last_step", last_step_);
  data.set_number("health/last_time", last_time_s_);
  data.set_integer("health/test_steps", test_steps_);
  data.set_integer("health/out_of_contact_steps", out_of_contact_steps_);
  data.set_numbers("health/sums",
                   {sum_slip_error_, sum_slip_, sum_output_power_W_, sum_input_power_W_,
                    sum_traction_N_, sum_drawbar_pull_N_, sum_contacts_, load_N_});
  data.set_numbers("health/drawbar_pull", drawbar_pull_N_);
  data.set_numbers("health/sinkage", sinkage_m_);
  data.set_numbers("health/slip", slip_);
  data.set_integer("health/findings", static_cast<std::int64_t>(findings_.size()));
  for (std::size_t k = 0; k < findings_.size(); ++k) {
    const HealthFinding &f = findings_[k];
    const std::string key = "health/finding/" + std::to_string(k) + "/";
    data.set_integer(key + "step", f.step);
    data.set_number(key + "time", f.time_s);
    data.set_text(key + "code", f.code);
    data.set_integer(key + "error", f.severity == Severity::error ? 1 : 0);
    data.set_text(key + "message", f.message);
  }
}

void RunHealth::restore_checkpoint(const CheckpointData &data) {
  const std::vector<double> &flags = data.numbers("health/flags"),
                            &sums = data.numbers("health/sums");
  if (flags.size() != 2 || sums.size() != 8)
    throw CheckpointError(data.source() + ": health/flags or health/sums has the wrong size");
  stability_warned_ = flags[0] != 0.0;
  stability_failed_ = flags[1] != 0.0;
  last_step_ = data.integer("health/last_step");
  last_time_s_ = data.number("health/last_time");
  test_steps_ = data.integer("health/test_steps");
  out_of_contact_steps_ = data.integer("health/out_of_contact_steps");
  sum_slip_error_ = sums[0];
  sum_slip_ = sums[1];
  sum_output_power_W_ = sums[2];
  sum_input_power_W_ = sums[3];
  sum_traction_N_ = sums[4];
  sum_drawbar_pull_N_ = sums[5];
  sum_contacts_ = sums[6];
  load_N_ = sums[7];
  drawbar_pull_N_ = data.numbers("health/drawbar_pull");
  sinkage_m_ = data.numbers("health/sinkage");
  slip_ = data.numbers("health/slip");
  findings_.clear();
  const std::int64_t n = data.integer("health/findings");
  for (std::int64_t k = 0; k < n; ++k) {
    const std::string key = "health/finding/" + std::to_string(k) + "/";
    HealthFinding f;
    f.step = data.integer(key + "step");
    f.time_s = data.number(key + "time");
    f.code = data.text(key + "code");
    f.severity = data.integer(key + "error") ? Severity::error : Severity::warning;
    f.message = data.text(key + "message");
    findings_.push_back(f);
  }
}

} // namespace wheelsim::rig
