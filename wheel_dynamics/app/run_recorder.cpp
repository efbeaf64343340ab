#include "run_recorder.h"

#include <array>
#include <vector>

namespace wheelsim::rig {

struct RunRecorder::Series {
  runfile::TimeSeries *position, *orientation, *velocity, *angular_velocity, *force, *torque,
      *contacts, *slip, *slip_velocity, *sinkage, *drawbar_pull, *drawbar_load, *driving_torque,
      *traction_force, *efficiency, *carriage_position, *carriage_velocity, *carriage_force,
      *lateral_force, *roll_torque, *yaw_torque, *spring_force, *vertical_load, *omega, *phase;
};

RunRecorder::RunRecorder(runfile::RunFile &file) : file_(file), s_(std::make_unique<Series>()) {
  auto obs = [&](const char *name, const char *unit, int n) {
    return &file_.observable(name, unit, n);
  };
  s_->position = obs("wheel/position", "m", 3);
  s_->orientation = obs("wheel/orientation", "1", 4);
  s_->velocity = obs("wheel/velocity", "m/s", 3);
  s_->angular_velocity = obs("wheel/angular_velocity", "rad/s", 3);
  s_->omega = obs("wheel/omega", "rad/s", 1);
  s_->force = obs("contact/force", "N", 3);
  s_->torque = obs("contact/torque", "N m", 3);
  s_->contacts = obs("contact/count", "1", 1);
  s_->slip = obs("slip", "1", 1);
  s_->slip_velocity = obs("slip_velocity", "m/s", 1);
  s_->sinkage = obs("sinkage", "m", 1);
  s_->drawbar_pull = obs("drawbar_pull", "N", 1);
  s_->drawbar_load = obs("drawbar_load_command", "N", 1);
  s_->driving_torque = obs("driving_torque", "N m", 1);
  s_->traction_force = obs("traction_force", "N", 1);
  s_->efficiency = obs("tractive_efficiency", "1", 1);
  s_->carriage_position = obs("carriage/position", "m", 1);
  s_->carriage_velocity = obs("carriage/velocity", "m/s", 1);
  s_->carriage_force = obs("carriage/force", "N", 1);
  s_->lateral_force = obs("lateral_force", "N", 1);
  s_->roll_torque = obs("roll_torque", "N m", 1);
  s_->yaw_torque = obs("yaw_torque", "N m", 1);
  s_->spring_force = obs("suspension/spring_force", "N", 1);
  s_->vertical_load = obs("vertical_load", "N", 1);
  s_->phase = obs("phase", "1", 1);
}

RunRecorder::~RunRecorder() = default;

void RunRecorder::record(std::int64_t step, const RigOutputs &o, double contacts) {
  const double t = o.time_s;
  const auto &w = o.wheel;
  const double p[3] = {w.p_WB_W.x(), w.p_WB_W.y(), w.p_WB_W.z()};
  const double q[4] = {w.q_WB.w(), w.q_WB.x(), w.q_WB.y(), w.q_WB.z()};
  const double v[3] = {w.v_WB_W.x(), w.v_WB_W.y(), w.v_WB_W.z()};
  const double om[3] = {w.w_WB_W.x(), w.w_WB_W.y(), w.w_WB_W.z()};
  const double f[3] = {o.contact.f_B_W.x(), o.contact.f_B_W.y(), o.contact.f_B_W.z()};
  const double tq[3] = {o.contact.t_B_W.x(), o.contact.t_B_W.y(), o.contact.t_B_W.z()};
  s_->position->append(step, t, p);
  s_->orientation->append(step, t, q);
  s_->velocity->append(step, t, v);
  s_->angular_velocity->append(step, t, om);
  s_->omega->append(step, t, o.omega_rad_s);
  s_->force->append(step, t, f);
  s_->torque->append(step, t, tq);
  s_->contacts->append(step, t, contacts);
  s_->slip->append(step, t, o.slip);
  s_->slip_velocity->append(step, t, o.slip_velocity_m_s);
  s_->sinkage->append(step, t, o.sinkage_m);
  s_->drawbar_pull->append(step, t, o.drawbar_pull_N);
  s_->drawbar_load->append(step, t, o.drawbar_load_command_N);
  s_->driving_torque->append(step, t, o.driving_torque_Nm);
  s_->traction_force->append(step, t, o.traction_force_N);
  s_->efficiency->append(step, t, o.tractive_efficiency);
  s_->carriage_position->append(step, t, o.carriage_x_m);
  s_->carriage_velocity->append(step, t, o.forward_velocity_m_s);
  s_->carriage_force->append(step, t, -o.drawbar_pull_N);
  s_->lateral_force->append(step, t, o.lateral_force_N);
  s_->roll_torque->append(step, t, o.roll_torque_Nm);
  s_->yaw_torque->append(step, t, o.yaw_torque_Nm);
  s_->spring_force->append(step, t, o.spring_force_N);
  s_->vertical_load->append(step, t, o.vertical_load_N);
  s_->phase->append(step, t, static_cast<double>(static_cast<int>(o.phase)));
}

} // namespace wheelsim::rig
