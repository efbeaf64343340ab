// wheelsim coupling protocol, version 2: LIGGGHTS (fix wheel/cosim, MPI rank 0) <-> wheel-rig.
// The whole protocol is in this header; docs/coupling-protocol.md is its prose version.
//
// Roles: the rig is the SERVER (binds the endpoint, integrates the wheel); LIGGGHTS is the CLIENT
// (connects, computes the soil's contact wrench on the wheel). Who sends what, in which order:
//
//   handshake   client -> server  Hello    protocol version, dt, start step s0, exchange_every N,
//                                          units "si", wheel reference point, initial wheel pose
//               server -> client  Welcome  protocol version, dt, accepted start step s0, wheel
//                                          state (pose and twist) for step s0
//               (or server -> client Close with the reason, e.g. a version or dt mismatch)
//   each exchange, at steps s = s0, s0 + N, s0 + 2N, ... (one-step explicit staggering):
//               client -> server  Wrench   step s, time, contact force and torque on the wheel
//                                          computed with the pose of step s
//               server -> client  Pose     step s + N: the wheel state after the rig advanced
//                                          N steps holding that wrench constant; flags
//                                          (kPoseCheckpointNext: both sides checkpoint at step
//                                          s + 2N, the next exchange step; docs/coupled-runs.md)
//               Between two exchanges (N > 1) the client holds the last received twist
//               constant (zero-order hold) and integrates the pose itself.
//   end         either side -> other  Close  reason code + text ("finished", "error: ...").
//               The client sends Close{finished} after its last Wrench or instead of the next
//               one; either side sends Close{error...} as soon as it fails, then stops.
//
// Wire format: one ZeroMQ message (or one loopback message) = MessageHeader followed by exactly
// one payload struct below, copied byte for byte. Numbers are in HOST byte order: both processes
// run on the same machine (or the same machine type); the build refuses big-endian hosts, so the
// wire is little-endian, IEEE-754 doubles. A peer of the other byte order is detected by the magic.
// Every struct is fixed-width with no padding (static_asserts below). The layout of MessageHeader
// and Close is frozen for all protocol versions, so a peer of any version can read why it was
// rejected.
//
// Frames and names (Drake style): W = world frame of the LIGGGHTS simulation box, B = wheel body
// frame (its origin is the wheel centre C, its axes are the mesh axes), q_WB = orientation of B in
// W as a unit quaternion (w, x, y, z), p_WC_W = position of C in W, v_WC_W = velocity of C in W,
// w_WB_W = angular velocity of B in W, f_C_W / t_C_W = contact force on the wheel / contact torque
// about C, expressed in W. Units: SI throughout (m, s, kg, N, N·m, rad). In C++ the two sides
// hold these as wheelsim::WheelPose / WheelWrench (wheelsim/pose.h) and convert them only through
// to_message / from_message of coupler/pose_messages.h.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace wheelsim::coupler {

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "wheelsim coupling protocol: host-order wire format, little-endian hosts only"
#endif

/// Protocol version. Bump it on any change of a struct, a field's meaning or the message order.
constexpr std::uint32_t kProtocolVersion = 2; // 2: Pose.flags (checkpoints)
/// First 4 bytes of every message: "WSCP" read as a little-endian uint32.
constexpr std::uint32_t kMagic = 0x50435357u;
/// Accepted deviation of |q| from 1 for every quaternion on the wire.
constexpr double kQuaternionNormTolerance = 1e-6;
/// Relative tolerance when the server compares the client's dt with its own.
constexpr double kTimeStepRelativeTolerance = 1e-9;
/// Units tag of Hello: only SI ("si") exists.
constexpr char kUnitsSI[] = "si";

using Bytes = std::vector<std::uint8_t>;
using Vec3 = std::array<double, 3>;
/// Unit quaternion (w, x, y, z).
using Quat = std::array<double, 4>;

// --- errors ---

/// Every failure of the coupling (protocol, timeout, peer closed).
class CouplingError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};
/// A message that is malformed (size, type, magic, non-finite number, non-unit quaternion) or
/// that disagrees with the handshake (version, dt, step). The message names the message type and
/// the field, and both values for a mismatch.
class ProtocolError : public CouplingError {
public:
  using CouplingError::CouplingError;
};
/// A receive (or a send to a peer that is gone) did not complete within its timeout. The message
/// names the peer and what was awaited.
class TimeoutError : public CouplingError {
public:
  using CouplingError::CouplingError;
};

// --- message types ---

enum class MessageType : std::uint32_t {
  Hello = 1,   ///< client -> server, once, first
  Welcome = 2, ///< server -> client, once, reply to Hello
  Wrench = 3,  ///< client -> server, every exchange
  Pose = 4,    ///< server -> client, reply to Wrench
  Close = 5,   ///< either way, last
};
/// "Hello", "Welcome", ...; "unknown type N" for anything else.
std::string to_string(MessageType type);

/// Why a side closed the coupling.
enum class CloseReason : std::uint32_t {
  Finished = 0,      ///< normal end of the run
  Error = 1,         ///< the sender failed (its text says how)
  ProtocolError = 2, ///< the sender rejected a message of the receiver (version, dt, step, field)
  Timeout = 3,       ///< the sender waited too long for the receiver
  Aborted = 4,       ///< the sender is shutting down without finishing (exception, signal)
};
/// "finished", "error", ...; "reason N" for a code this version does not know.
std::string to_string(CloseReason reason);

// --- wire structs (host order, no padding) ---

/// Precedes every payload. Frozen across protocol versions.
struct MessageHeader {
  std::uint32_t magic;         ///< kMagic
  std::uint32_t version;       ///< the sender's kProtocolVersion
  std::uint32_t type;          ///< MessageType
  std::uint32_t payload_bytes; ///< sizeof the payload struct that follows
};
static_assert(sizeof(MessageHeader) == 16);

/// Client -> server, first message.
struct Hello {
  /// Protocol version the client speaks (written into the header; decode fills it from there).
  std::uint32_t protocol_version = kProtocolVersion;
  /// Exchange every N >= 1 steps; the client holds the twist constant in between (zero-order
  /// hold), the rig holds the wrench constant.
  std::uint32_t exchange_every = 1;
  /// First step the client will send a Wrench for (LIGGGHTS' step counter, >= 0).
  std::int64_t start_step = 0;
  /// Time step [s] of the client (LIGGGHTS' `timestep`), finite and > 0.
  double dt_s = 0.0;
  /// Units of every number: "si" (NUL-padded).
  std::array<char, 8> units{'s', 'i', 0, 0, 0, 0, 0, 0};
  /// Wheel reference point [m], world frame, at the start step: the wheel centre, the point the
  /// client reports the torque about.
  Vec3 p_WR_W{};
  /// Client's initial wheel-centre position [m], world frame (the fix's `origin`).
  Vec3 p_WC_W{};
  /// Client's initial wheel orientation, unit quaternion (w, x, y, z), B in W.
  Quat q_WB{1.0, 0.0, 0.0, 0.0};
};
static_assert(sizeof(Hello) == 4 + 4 + 8 + 8 + 8 + 3 * 8 + 3 * 8 + 4 * 8);

/// Pose and twist of the wheel at one step.
struct WheelState {
  Vec3 p_WC_W{};                 ///< wheel-centre position [m], world frame
  Quat q_WB{1.0, 0.0, 0.0, 0.0}; ///< wheel orientation, unit quaternion (w, x, y, z), B in W
  Vec3 v_WC_W{};                 ///< wheel-centre velocity [m/s], world frame
  Vec3 w_WB_W{};                 ///< wheel angular velocity [rad/s], world frame
};
static_assert(sizeof(WheelState) == 13 * 8);

/// Server -> client, reply to Hello when the server accepts.
struct Welcome {
  /// Protocol version the server speaks (header; decode fills it from there).
  std::uint32_t protocol_version = kProtocolVersion;
  std::uint32_t reserved = 0; ///< 0; keeps the doubles 8-byte aligned
  /// Step the server accepts as the start; equals Hello::start_step.
  std::int64_t start_step = 0;
  /// Time step [s] of the server; equals Hello::dt_s.
  double dt_s = 0.0;
  /// Wheel state for the start step (the server may have overridden the client's initial pose).
  WheelState state;
};
static_assert(sizeof(Welcome) == 4 + 4 + 8 + 8 + sizeof(WheelState));

/// Client -> server, once per exchange.
struct Wrench {
  std::int64_t step = 0;       ///< step the wrench was computed at (pose of this step), >= 0
  double time_s = 0.0;         ///< simulated time of that step [s]
  Vec3 f_C_W{};                ///< total contact force of the soil on the wheel [N], world frame
  Vec3 t_C_W{};                ///< total contact torque about the wheel centre [N·m], world frame
  std::int64_t n_contacts = 0; ///< number of particle–wheel contacts, >= 0
};
static_assert(sizeof(Wrench) == 8 + 8 + 3 * 8 + 3 * 8 + 8);

/// Server -> client, reply to Wrench: the wheel state at step = wrench step + exchange_every.
struct Pose {
  std::int64_t step = 0; ///< step this state is for
  WheelState state;
  std::uint32_t flags = 0;    ///< kPose* bits; unknown bits are a ProtocolError
  std::uint32_t reserved = 0; ///< 0
};
static_assert(sizeof(Pose) == 8 + sizeof(WheelState) + 8);
/// Pose.flags: the rig asks for a checkpoint at the next exchange step (Pose.step + N). Both sides
/// then save their state of that step: LIGGGHTS a restart file after the step, before its Wrench;
/// the rig its checkpoint file when it has advanced to that step, before its Pose.
constexpr std::uint32_t kPoseCheckpointNext = 1u;

/// Either way, last message. Frozen across protocol versions.
struct Close {
  static constexpr std::size_t kTextBytes = 248;
  CloseReason reason = CloseReason::Finished;
  std::uint32_t reserved = 0;
  /// Human-readable reason, NUL-terminated UTF-8 (longer texts are cut at kTextBytes - 1).
  std::array<char, kTextBytes> text{};

  /// A Close with `reason` and `message` (cut to fit).
  static Close make(CloseReason reason, const std::string &message);
  std::string message() const; ///< text up to the NUL
};
static_assert(sizeof(Close) == 4 + 4 + Close::kTextBytes);

static_assert(std::is_trivially_copyable_v<MessageHeader> && std::is_trivially_copyable_v<Hello> &&
              std::is_trivially_copyable_v<Welcome> && std::is_trivially_copyable_v<Wrench> &&
              std::is_trivially_copyable_v<Pose> && std::is_trivially_copyable_v<Close>);

// --- encode / decode ---
// encode_* validate the message first (so a NaN wrench is caught where it was made) and throw
// ProtocolError like decode_*. decode_* check, in this order: size >= header, magic, version
// (except Close), type, payload size, then every field: finite numbers, unit quaternions, ranges.

Bytes encode(const Hello &message);
Bytes encode(const Welcome &message);
Bytes encode(const Wrench &message);
Bytes encode(const Pose &message);
Bytes encode(const Close &message);

/// Type of a message after checking size, magic and the header's payload size (not the version).
MessageType peek_type(const Bytes &bytes);

Hello decode_hello(const Bytes &bytes); ///< version mismatch: "client speaks protocol 2, server 1"
Welcome
decode_welcome(const Bytes &bytes); ///< version mismatch: "server speaks protocol 2, client 1"
Wrench decode_wrench(const Bytes &bytes);
Pose decode_pose(const Bytes &bytes);
Close decode_close(const Bytes &bytes); ///< any version

/// Validation alone (what encode and decode run).
void validate(const Hello &message);
void validate(const Welcome &message);
void validate(const Wrench &message);
void validate(const Pose &message);
void validate(const Close &message);

/// Shortest text that reads back as the same double ("1e-05", "0.1", "nan").
std::string format_number(double value);

} // namespace wheelsim::coupler
