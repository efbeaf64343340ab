// The two ends of a coupling session over any Transport: CouplingClient (LIGGGHTS side, one
// object on MPI rank 0) and CouplingServer (the rig side). They enforce the message order of
// protocol.h, check steps, and turn every failure into a CouplingError that says which peer and
// what was awaited. On a failure they detect themselves (bad message, mismatch, timeout) they
// first send the peer a Close with the reason, so both sides stop with a clear message.
#pragma once

#include "coupler/protocol.h"
#include "coupler/transport.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>

namespace wheelsim::coupler {

/// The peer sent Close where another message was expected (or during the handshake).
class PeerClosedError : public CouplingError {
public:
  PeerClosedError(const std::string &what, const Close &close)
      : CouplingError(what), close_(close) {}
  CloseReason reason() const { return close_.reason; }
  /// The peer's text, e.g. "time step mismatch: client dt = 1e-05 s, server dt = 2e-05 s".
  std::string peer_text() const { return close_.message(); }

private:
  Close close_;
};

/// Receive timeouts of a session.
struct Timeouts {
  /// Client: Hello -> Welcome; server: waiting for the Hello (start the two processes within it).
  std::chrono::milliseconds handshake{std::chrono::seconds(60)};
  /// Each exchange: client Wrench -> Pose; server Pose -> next Wrench (must cover the slowest
  /// LIGGGHTS step times exchange_every, plus output and load-balancing pauses).
  std::chrono::milliseconds step{std::chrono::seconds(30)};
};

/// The LIGGGHTS side. Usage:
///   CouplingClient client(ZmqTransport::connect("ipc:///tmp/run/rig.sock"));
///   Welcome w = client.connect(hello);                 // state for hello.start_step
///   for each exchange step s: client.send_wrench({s, ...});
///                             Pose p = client.receive_pose(s + hello.exchange_every);
///   client.close();                                    // Close{finished}
class CouplingClient {
public:
  explicit CouplingClient(std::unique_ptr<Transport> transport, Timeouts timeouts = {});
  /// If the session is open, sends Close{aborted} (best effort, never throws).
  ~CouplingClient();
  CouplingClient(const CouplingClient &) = delete;
  CouplingClient &operator=(const CouplingClient &) = delete;

  /// Sends Hello, waits (timeouts.handshake) for Welcome. Throws PeerClosedError with the
  /// server's reason if it refuses (version, dt), ProtocolError if the Welcome is malformed or
  /// disagrees with the Hello (version, dt, start step), TimeoutError if no answer.
  Welcome connect(const Hello &hello);
  /// Sends the wrench of step `wrench.step`, which must be the next exchange step
  /// (start_step + k * exchange_every) and follow the previous receive_pose.
  void send_wrench(const Wrench &wrench);
  /// Waits (timeouts.step) for the Pose of `expected_step` (= last wrench step + exchange_every).
  /// A Pose for another step is a ProtocolError naming both steps; a Close is a PeerClosedError
  /// carrying the rig's reason.
  Pose receive_pose(std::int64_t expected_step);
  /// Sends Close{reason, text} if the session is open; then the session is closed. Best effort:
  /// never throws (a peer that is gone cannot be told).
  void close(CloseReason reason = CloseReason::Finished, const std::string &text = "finished");

  bool is_open() const;
  const Hello &hello() const { return hello_; }
  Transport &transport() { return *transport_; }

private:
  enum class State { Idle, AwaitWrench, AwaitPose, Closed };
  /// Tells the peer why (Close, best effort) and marks the session closed; the caller throws.
  void abandon(CloseReason reason, const std::string &text) noexcept;
  std::unique_ptr<Transport> transport_;
  Timeouts timeouts_;
  State state_ = State::Idle;
  Hello hello_{};
  std::int64_t next_wrench_step_ = 0;
};

/// The rig side. Usage:
///   CouplingServer server(ZmqTransport::bind("ipc:///tmp/run/rig.sock"));
///   Hello h = server.accept(dt_s);                      // validates version and dt
///   server.welcome({..., h.start_step, dt_s, state});
///   for (;;) { auto m = server.receive();              // Wrench or Close
///              if (auto* c = std::get_if<Close>(&m)) break;
///              ... advance exchange_every steps ...; server.send_pose({w.step + N, state}); }
class CouplingServer {
public:
  explicit CouplingServer(std::unique_ptr<Transport> transport, Timeouts timeouts = {});
  /// If the session is open, sends Close{aborted} (best effort, never throws).
  ~CouplingServer();
  CouplingServer(const CouplingServer &) = delete;
  CouplingServer &operator=(const CouplingServer &) = delete;

  /// Waits (timeouts.handshake) for the client's Hello and validates it: protocol version and
  /// dt (relative tolerance kTimeStepRelativeTolerance) against `expected_dt_s`. On a mismatch or
  /// a malformed Hello sends Close{protocol error, reason} to the client, then throws
  /// ProtocolError naming both values ("client speaks protocol 2, server 1").
  Hello accept(double expected_dt_s);
  /// Replies to the Hello. `welcome.start_step` and `welcome.dt_s` must equal the Hello's.
  void welcome(const Welcome &welcome);
  /// Waits (timeouts.step) for the next Wrench, or a Close (the client finished or failed: the
  /// session is then closed). A Wrench for an unexpected step is a ProtocolError naming both.
  std::variant<Wrench, Close> receive();
  /// Replies to the last Wrench; `pose.step` must be that wrench's step + exchange_every. If
  /// the client is gone and its Close arrives (it ended its run after that Wrench), throws
  /// PeerClosedError with the client's reason (Finished for a normal end).
  void send_pose(const Pose &pose);
  /// Sends Close{reason, text} if the session is open. Best effort: never throws.
  void close(CloseReason reason = CloseReason::Finished, const std::string &text = "finished");

  bool is_open() const;
  const Hello &hello() const { return hello_; }
  Transport &transport() { return *transport_; }

private:
  enum class State { AwaitHello, AwaitWelcome, AwaitWrench, AwaitPose, Closed };
  /// Tells the peer why (Close, best effort) and marks the session closed; the caller throws.
  void abandon(CloseReason reason, const std::string &text) noexcept;
  std::unique_ptr<Transport> transport_;
  Timeouts timeouts_;
  State state_ = State::AwaitHello;
  Hello hello_{};
  std::int64_t next_wrench_step_ = 0;
  std::int64_t pose_step_ = 0;
};

} // namespace wheelsim::coupler
