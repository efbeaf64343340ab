#include "coupled_motion.h"

#include "coupler/coupling.h"
#include "coupler/protocol.h"
#include "coupler/transport.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace wheelsim {
namespace {

coupler::WheelState to_wire(const WheelState &s) {
  coupler::WheelState w;
  for (int k = 0; k < 3; ++k) {
    w.p_WC_W[k] = s.position_m[k];
    w.v_WC_W[k] = s.velocity_m_s[k];
    w.w_WB_W[k] = s.angular_velocity_rad_s[k];
  }
  w.q_WB = {s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()};
  return w;
}

WheelState from_wire(const coupler::WheelState &w) {
  WheelState s;
  s.position_m = Eigen::Vector3d(w.p_WC_W[0], w.p_WC_W[1], w.p_WC_W[2]);
  s.orientation = Eigen::Quaterniond(w.q_WB[0], w.q_WB[1], w.q_WB[2], w.q_WB[3]);
  // The rig sends unit quaternions (checked to 1e-6 by the protocol). Renormalise only if it is
  // visibly off: renormalising a unit quaternion changes its last bits, and the coupled run is
  // tested to reproduce the prescribed one exactly.
  if (std::abs(s.orientation.squaredNorm() - 1.0) > 1e-12)
    s.orientation.normalize();
  s.velocity_m_s = Eigen::Vector3d(w.v_WC_W[0], w.v_WC_W[1], w.v_WC_W[2]);
  s.angular_velocity_rad_s = Eigen::Vector3d(w.w_WB_W[0], w.w_WB_W[1], w.w_WB_W[2]);
  return s;
}

std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(static_cast<long long>(std::ceil(seconds * 1000.0)));
}

} // namespace

CoupledMotion::CoupledMotion(const Settings &settings, MPI_Comm world)
    : settings_(settings), world_(world) {
  MPI_Comm_rank(world_, &rank_);
}

CoupledMotion::~CoupledMotion() { close(); }

std::string CoupledMotion::describe() const {
  std::ostringstream out;
  out << "coupled: rig at " << settings_.endpoint << ", exchange every " << settings_.exchange_every
      << " step(s), timeout " << settings_.step_timeout_s << " s";
  return out.str();
}

WheelState CoupledMotion::broadcast(const WheelState &state) const {
  double buf[13] = {state.position_m.x(),
                    state.position_m.y(),
                    state.position_m.z(),
                    state.orientation.w(),
                    state.orientation.x(),
                    state.orientation.y(),
                    state.orientation.z(),
                    state.velocity_m_s.x(),
                    state.velocity_m_s.y(),
                    state.velocity_m_s.z(),
                    state.angular_velocity_rad_s.x(),
                    state.angular_velocity_rad_s.y(),
                    state.angular_velocity_rad_s.z()};
  MPI_Bcast(buf, 13, MPI_DOUBLE, 0, world_);
  WheelState s;
  s.position_m = Eigen::Vector3d(buf[0], buf[1], buf[2]);
  s.orientation = Eigen::Quaterniond(buf[3], buf[4], buf[5], buf[6]);
  s.velocity_m_s = Eigen::Vector3d(buf[7], buf[8], buf[9]);
  s.angular_velocity_rad_s = Eigen::Vector3d(buf[10], buf[11], buf[12]);
  return s;
}

WheelState CoupledMotion::connect(const WheelState &initial, std::int64_t start_step, double dt_s) {
  WheelState state = initial;
  if (rank_ == 0) {
    coupler::Timeouts timeouts;
    timeouts.handshake = millis(settings_.handshake_timeout_s);
    timeouts.step = millis(settings_.step_timeout_s);
    client_ = std::make_unique<coupler::CouplingClient>(
        coupler::ZmqTransport::connect(settings_.endpoint, "the rig"), timeouts);
    coupler::Hello hello;
    hello.exchange_every = static_cast<std::uint32_t>(settings_.exchange_every);
    hello.start_step = start_step;
    hello.dt_s = dt_s;
    const coupler::WheelState wire = to_wire(initial);
    hello.p_WR_W = wire.p_WC_W;
    hello.p_WC_W = wire.p_WC_W;
    hello.q_WB = wire.q_WB;
    state = from_wire(client_->connect(hello).state);
  }
  state = broadcast(state);
  connected_ = true;
  start_step_ = start_step;
  last_sent_step_ = start_step - 1;
  return state;
}

bool CoupledMotion::is_exchange_step(std::int64_t step) const {
  return step >= start_step_ && (step - start_step_) % settings_.exchange_every == 0;
}

void CoupledMotion::wrench_computed(std::int64_t step, double time_s, const WheelWrench &wrench) {
  if (!connected_ || rig_finished_ || step <= last_sent_step_ || !is_exchange_step(step))
    return;
  last_sent_step_ = step;
  if (rank_ != 0)
    return;
  coupler::Wrench w;
  w.step = step;
  w.time_s = time_s;
  for (int k = 0; k < 3; ++k) {
    w.f_C_W[k] = wrench.force_N[k];
    w.t_C_W[k] = wrench.torque_Nm[k];
  }
  w.n_contacts = wrench.contacts;
  client_->send_wrench(w);
}

WheelState CoupledMotion::next_state(const WheelState &now, std::int64_t next_step, double dt_s) {
  const WheelState held = advance_pose(now, now.velocity_m_s, now.angular_velocity_rad_s, dt_s);
  if (rig_finished_ || !is_exchange_step(next_step))
    return held; // zero-order hold
  WheelState state = now;
  int finished = 0;
  if (rank_ == 0) {
    try {
      state = from_wire(client_->receive_pose(next_step).state);
    } catch (const coupler::PeerClosedError &e) {
      if (e.reason() != coupler::CloseReason::Finished)
        throw;
      finished = 1;
      std::printf("fix wheel/cosim: the rig finished (%s) at step %lld; the wheel keeps its last "
                  "twist until the run ends\n",
                  e.peer_text().c_str(), static_cast<long long>(next_step));
    }
  }
  MPI_Bcast(&finished, 1, MPI_INT, 0, world_);
  if (finished) {
    rig_finished_ = true;
    connected_ = false;
    return held;
  }
  return broadcast(state);
}

void CoupledMotion::close() {
  if (rank_ == 0 && client_)
    client_->close();
  connected_ = false;
}

} // namespace wheelsim
