// `motion coupled ENDPOINT` of fix wheel/cosim: the wheel moves as the wheel-rig process says.
//
// MPI rank 0 alone owns the coupling session (coupler/coupling.h, ZeroMQ); the wrench it sends is
// the fix's reduced global wrench, and the pose it receives is broadcast to every rank. Message
// order (docs/coupling-protocol.md): at the first setup, Hello -> Welcome (the rig's wheel state
// for the start step); then at every exchange step s (every `exchange_every` steps) the fix sends
// the wrench of step s from end_of_step and receives the pose of step s + N right before it
// computes the contacts of that step — so the rig works while LIGGGHTS integrates the particles,
// rebuilds neighbour lists and computes the pair forces. Between exchanges the twist is held
// constant (zero-order hold) and the pose integrated locally.
//
// Errors: a coupling failure (timeout, peer closed, protocol) throws wheelsim::coupler::
// CouplingError on rank 0 only; the fix turns it into LIGGGHTS' error->one, which ends all ranks.
#ifndef WHEELSIM_COUPLED_MOTION_H
#define WHEELSIM_COUPLED_MOTION_H

#include "wheel_motion.h"

#include <mpi.h>

#include <memory>
#include <string>

namespace wheelsim {
namespace coupler {
class CouplingClient;
}

class CoupledMotion : public WheelMotion {
public:
  struct Settings {
    std::string endpoint;              ///< e.g. ipc:///tmp/run/rig.sock or tcp://127.0.0.1:5555
    double step_timeout_s = 30.0;      ///< wait for each Pose [s]
    double handshake_timeout_s = 60.0; ///< wait for the rig's Welcome [s]
    int exchange_every = 1;            ///< exchange every N steps (N >= 1)
  };
  CoupledMotion(const Settings &settings, MPI_Comm world);
  ~CoupledMotion() override; // sends Close{finished} if the session is open

  std::string describe() const override;
  /// Handshake (rank 0 talks, all ranks get the result): returns the rig's pose and twist for
  /// `start_step`. `initial` is the fix's pose (origin), sent as the client's proposal.
  WheelPose connect(const WheelPose &initial, std::int64_t start_step, double dt_s);
  bool connected() const { return connected_; }
  /// True once the rig ended the session with Close{finished} (its test phase is over): the
  /// wheel then keeps its last twist (zero-order hold) until the deck's run ends.
  bool rig_finished() const { return rig_finished_; }
  void wrench_computed(std::int64_t step, double time_s, const WheelWrench &wrench,
                       long contacts) override;
  WheelPose next_state(const WheelPose &now, std::int64_t next_step, double dt_s) override;
  /// Ends the session with Close{finished} (rank 0; no-op if not connected).
  void close();
  /// The step at which the rig asked both sides to checkpoint (its Pose's kPoseCheckpointNext
  /// flag: the next exchange step after that Pose), on every rank; -1 if none is pending.
  std::int64_t checkpoint_step() const { return checkpoint_step_; }
  void checkpoint_done() { checkpoint_step_ = -1; }

private:
  bool is_exchange_step(std::int64_t step) const;
  /// Rank 0's pose on every rank (as its wire state: coupler::to_message / from_message).
  WheelPose broadcast(const WheelPose &pose) const;

  Settings settings_;
  MPI_Comm world_;
  int rank_ = 0;
  bool connected_ = false;
  bool rig_finished_ = false;
  std::int64_t start_step_ = 0;
  std::int64_t last_sent_step_ = -1;
  std::int64_t checkpoint_step_ = -1;
  std::unique_ptr<coupler::CouplingClient> client_; // rank 0 only
};

} // namespace wheelsim

#endif
