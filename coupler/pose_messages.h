// Conversion between the wire structs of coupler/protocol.h and the wheel's pose and wrench types
// (wheelsim/pose.h): the one place where a coupling side turns a message into Eigen values and
// back. Field by field: WheelState.p_WC_W <-> WheelPose.p_WB_W (C = the wheel centre Bo),
// q_WB (w, x, y, z) <-> q_WB, v_WC_W <-> v_WB_W, w_WB_W <-> w_WB_W; Wrench.f_C_W <-> f_B_W,
// t_C_W <-> t_B_W. Values are copied bit for bit, except that from_message renormalises a
// quaternion that is visibly off unit length (see there).
#pragma once

#include "coupler/protocol.h"
#include "wheelsim/pose.h"

#include <cstdint>

namespace wheelsim::coupler {

/// The wire state of `pose` (its quaternion as it is: the protocol checks |q| = 1 to 1e-6).
WheelState to_message(const WheelPose &pose);
/// The pose of a wire state. The quaternion is renormalised only if | |q|^2 - 1 | > 1e-12:
/// renormalising a unit quaternion changes its last bits, and a coupled run with a fixed twist
/// is tested to reproduce the prescribed one exactly.
WheelPose from_message(const WheelState &message);
/// The client's initial pose of a Hello (p_WC_W, q_WB; zero twist), as from_message(WheelState).
WheelPose from_message(const Hello &message);

/// The Wrench message of step `step` at time `time_s` [s] with `n_contacts` particle contacts.
Wrench to_message(const WheelWrench &wrench, std::int64_t step, double time_s,
                  std::int64_t n_contacts);
/// The force and torque of a Wrench message (step, time and contact count are the caller's).
WheelWrench from_message(const Wrench &message);

} // namespace wheelsim::coupler
