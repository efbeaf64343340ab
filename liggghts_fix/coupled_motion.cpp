#include "coupled_motion.h"

#include "coupler/coupling.h"
#include "coupler/pose_messages.h"
#include "coupler/protocol.h"
#include "coupler/transport.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace wheelsim {
namespace {

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

WheelPose CoupledMotion::broadcast(const WheelPose &pose) const {
  coupler::WheelState wire = coupler::to_message(pose);
  static_assert(sizeof wire == 13 * sizeof(double), "the wire state is 13 doubles");
  MPI_Bcast(&wire, 13, MPI_DOUBLE, 0, world_);
  return coupler::from_message(wire);
}

WheelPose CoupledMotion::connect(const WheelPose &initial, std::int64_t start_step, double dt_s) {
  WheelPose state = initial;
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
    const coupler::WheelState wire = coupler::to_message(initial);
    hello.p_WR_W = wire.p_WC_W;
    hello.p_WC_W = wire.p_WC_W;
    hello.q_WB = wire.q_WB;
    state = coupler::from_message(client_->connect(hello).state);
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

void CoupledMotion::wrench_computed(std::int64_t step, double time_s, const WheelWrench &wrench,
                                    long contacts) {
  if (!connected_ || rig_finished_ || step <= last_sent_step_ || !is_exchange_step(step))
    return;
  last_sent_step_ = step;
  if (rank_ != 0)
    return;
  client_->send_wrench(coupler::to_message(wrench, step, time_s, contacts));
}

WheelPose CoupledMotion::next_state(const WheelPose &now, std::int64_t next_step, double dt_s) {
  const WheelPose held = integrate_pose(now, dt_s); // the twist of `now` held
  if (rig_finished_ || !is_exchange_step(next_step))
    return held; // zero-order hold
  WheelPose state = now;
  int flags[2] = {0, 0}; // finished, checkpoint at the next exchange step
  int &finished = flags[0];
  if (rank_ == 0) {
    try {
      const coupler::Pose pose = client_->receive_pose(next_step);
      state = coupler::from_message(pose.state);
      flags[1] = (pose.flags & coupler::kPoseCheckpointNext) != 0u ? 1 : 0;
    } catch (const coupler::PeerClosedError &e) {
      if (e.reason() != coupler::CloseReason::Finished)
        throw;
      finished = 1;
      std::printf("fix wheel/cosim: the rig finished (%s) at step %lld; the wheel keeps its last "
                  "twist until the run ends\n",
                  e.peer_text().c_str(), static_cast<long long>(next_step));
    }
  }
  MPI_Bcast(flags, 2, MPI_INT, 0, world_);
  if (flags[1])
    checkpoint_step_ = next_step + settings_.exchange_every;
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
