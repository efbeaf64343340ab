#include "run_recorder.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <vector>

namespace wheelsim::rig {

namespace {

/// One observable of the run file: /observables/<name>, its unit, its number of components and
/// how its values come from a step's RigOutputs (and the contact count). The one place an
/// observable is declared (docs/extending.md, "Adding an observable"; docs/hdf5-layout.md).
struct Observable {
  const char *name;
  const char *unit;
  int components; ///< 1..4
  void (*values)(const RigOutputs &o, double contacts, double *out);
};

void vec3(const Eigen::Vector3d &v, double *out) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

// clang-format off
const Observable kObservables[] = {
  {"wheel/position", "m", 3, [](const RigOutputs &o, double, double *v) { vec3(o.wheel.p_WB_W, v); }},
  {"wheel/orientation", "1", 4, [](const RigOutputs &o, double, double *v) {
     v[0] = o.wheel.q_WB.w(); v[1] = o.wheel.q_WB.x(); v[2] = o.wheel.q_WB.y(); v[3] = o.wheel.q_WB.z(); }},
  {"wheel/velocity", "m/s", 3, [](const RigOutputs &o, double, double *v) { vec3(o.wheel.v_WB_W, v); }},
  {"wheel/angular_velocity", "rad/s", 3, [](const RigOutputs &o, double, double *v) { vec3(o.wheel.w_WB_W, v); }},
  {"wheel/omega", "rad/s", 1, [](const RigOutputs &o, double, double *v) { *v = o.omega_rad_s; }},
  {"contact/force", "N", 3, [](const RigOutputs &o, double, double *v) { vec3(o.contact.f_B_W, v); }},
  {"contact/torque", "N m", 3, [](const RigOutputs &o, double, double *v) { vec3(o.contact.t_B_W, v); }},
  {"contact/count", "1", 1, [](const RigOutputs &, double contacts, double *v) { *v = contacts; }},
  {"slip", "1", 1, [](const RigOutputs &o, double, double *v) { *v = o.slip; }},
  {"slip_velocity", "m/s", 1, [](const RigOutputs &o, double, double *v) { *v = o.slip_velocity_m_s; }},
  {"sinkage", "m", 1, [](const RigOutputs &o, double, double *v) { *v = o.sinkage_m; }},
  {"drawbar_pull", "N", 1, [](const RigOutputs &o, double, double *v) { *v = o.drawbar_pull_N; }},
  {"drawbar_load_command", "N", 1, [](const RigOutputs &o, double, double *v) { *v = o.drawbar_load_command_N; }},
  {"driving_torque", "N m", 1, [](const RigOutputs &o, double, double *v) { *v = o.driving_torque_Nm; }},
  {"traction_force", "N", 1, [](const RigOutputs &o, double, double *v) { *v = o.traction_force_N; }},
  {"tractive_efficiency", "1", 1, [](const RigOutputs &o, double, double *v) { *v = o.tractive_efficiency; }},
  {"carriage/position", "m", 1, [](const RigOutputs &o, double, double *v) { *v = o.carriage_x_m; }},
  {"carriage/velocity", "m/s", 1, [](const RigOutputs &o, double, double *v) { *v = o.forward_velocity_m_s; }},
  {"carriage/force", "N", 1, [](const RigOutputs &o, double, double *v) { *v = -o.drawbar_pull_N; }},
  {"lateral_force", "N", 1, [](const RigOutputs &o, double, double *v) { *v = o.lateral_force_N; }},
  {"roll_torque", "N m", 1, [](const RigOutputs &o, double, double *v) { *v = o.roll_torque_Nm; }},
  {"yaw_torque", "N m", 1, [](const RigOutputs &o, double, double *v) { *v = o.yaw_torque_Nm; }},
  {"suspension/spring_force", "N", 1, [](const RigOutputs &o, double, double *v) { *v = o.spring_force_N; }},
  {"vertical_load", "N", 1, [](const RigOutputs &o, double, double *v) { *v = o.vertical_load_N; }},
  {"phase", "1", 1, [](const RigOutputs &o, double, double *v) { *v = static_cast<double>(static_cast<int>(o.phase)); }},
};
// clang-format on

} // namespace

struct RunRecorder::Series {
  std::vector<runfile::TimeSeries *> series; ///< one per kObservables entry, same order
};

RunRecorder::RunRecorder(runfile::RunFile &file) : file_(file), s_(std::make_unique<Series>()) {
  for (const Observable &obs : kObservables)
    s_->series.push_back(&file_.observable(obs.name, obs.unit, obs.components));
}

RunRecorder::~RunRecorder() = default;

void RunRecorder::record(std::int64_t step, const RigOutputs &o, double contacts) {
  std::array<double, 4> values{};
  for (std::size_t i = 0; i < s_->series.size(); ++i) {
    kObservables[i].values(o, contacts, values.data());
    s_->series[i]->append(step, o.time_s, values.data());
  }
}

} // namespace wheelsim::rig
