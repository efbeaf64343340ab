#include "coupler/coupling.h"

#include <exception>

#include <cmath>
#include <utility>

namespace wheelsim::coupler {

namespace {

/// Sends a Close; swallows every failure (the peer may be gone, which is why we close).
void send_close_quietly(Transport &transport, CloseReason reason,
                        const std::string &text) noexcept {
  try {
    transport.send_nowait(encode(Close::make(reason, text)));
  } catch (...) { // encode: only std::bad_alloc is possible
  }
}

/// Sends `bytes`, adding what was being sent to a failure's message (same exception type).
void send_message(Transport &transport, const Bytes &bytes, const std::string &what) {
  try {
    transport.send(bytes);
  } catch (const TimeoutError &e) {
    throw TimeoutError("sending " + what + ": " + e.what());
  } catch (const CouplingError &e) {
    throw CouplingError("sending " + what + ": " + e.what());
  }
}

PeerClosedError peer_closed(const Transport &transport, const Bytes &bytes,
                            const std::string &awaiting) {
  const Close close = decode_close(bytes);
  return PeerClosedError(transport.peer_name() + " closed the coupling while we awaited " +
                             awaiting + " (" + to_string(close.reason) + "): " + close.message(),
                         close);
}

bool same_time_step(double a, double b) {
  return std::fabs(a - b) <= kTimeStepRelativeTolerance * std::max(std::fabs(a), std::fabs(b));
}

std::string step_rule(const Hello &hello) {
  return "start step " + std::to_string(hello.start_step) + ", exchange_every " +
         std::to_string(hello.exchange_every);
}

} // namespace

// ------------------------------------------------------------------------------------ client

CouplingClient::CouplingClient(std::unique_ptr<Transport> transport, Timeouts timeouts)
    : transport_(std::move(transport)), timeouts_(timeouts) {
  if (!transport_) {
    throw CouplingError("CouplingClient: no transport given");
  }
}

CouplingClient::~CouplingClient() {
  if (is_open()) {
    send_close_quietly(*transport_, CloseReason::Aborted,
                       "the client (LIGGGHTS) shut down without finishing the coupled run");
  }
}

bool CouplingClient::is_open() const {
  return state_ == State::AwaitWrench || state_ == State::AwaitPose;
}

void CouplingClient::abandon(CloseReason reason, const std::string &text) noexcept {
  send_close_quietly(*transport_, reason, text);
  state_ = State::Closed;
}

Welcome CouplingClient::connect(const Hello &hello) {
  if (state_ != State::Idle) {
    throw CouplingError(
        "CouplingClient::connect: called twice; one client object runs one session");
  }
  const Bytes hello_bytes = encode(hello); // validates; throws ProtocolError naming the field
  hello_ = hello;
  state_ = State::Closed; // until the Welcome is accepted
  send_message(*transport_, hello_bytes, "Hello");
  const std::string awaiting =
      "Welcome (reply to Hello for start step " + std::to_string(hello.start_step) + ")";
  Bytes bytes;
  try {
    bytes = transport_->receive(timeouts_.handshake, awaiting);
  } catch (const TimeoutError &e) {
    abandon(CloseReason::Timeout, e.what());
    throw;
  }
  Welcome welcome;
  try {
    const MessageType type = peek_type(bytes);
    if (type == MessageType::Close) {
      throw peer_closed(*transport_, bytes, awaiting);
    }
    welcome = decode_welcome(bytes);
    if (!same_time_step(welcome.dt_s, hello.dt_s)) {
      throw ProtocolError(
          "Welcome.dt_s: time step mismatch: client dt = " + format_number(hello.dt_s) +
          " s, server dt = " + format_number(welcome.dt_s) + " s");
    }
    if (welcome.start_step != hello.start_step) {
      throw ProtocolError("Welcome.start_step: the server accepted step " +
                          std::to_string(welcome.start_step) + ", the client starts at step " +
                          std::to_string(hello.start_step));
    }
  } catch (const PeerClosedError &) {
    throw;
  } catch (const ProtocolError &e) {
    abandon(CloseReason::ProtocolError, e.what());
    throw;
  }
  state_ = State::AwaitWrench;
  next_wrench_step_ = hello.start_step;
  return welcome;
}

void CouplingClient::send_wrench(const Wrench &wrench) {
  if (state_ != State::AwaitWrench) {
    throw CouplingError(std::string("CouplingClient::send_wrench: ") +
                        (state_ == State::AwaitPose
                             ? "the Pose of the previous Wrench was not received yet"
                             : "the session is not open (connect first; not after close)"));
  }
  if (wrench.step != next_wrench_step_) {
    const std::string message = "Wrench.step: the next exchange is at step " +
                                std::to_string(next_wrench_step_) + " (" + step_rule(hello_) +
                                "), got step " + std::to_string(wrench.step);
    abandon(CloseReason::ProtocolError, message);
    throw ProtocolError(message);
  }
  Bytes bytes;
  try {
    bytes = encode(wrench);
  } catch (const ProtocolError &e) {
    abandon(CloseReason::Error, std::string("client sent an invalid wrench: ") + e.what());
    throw;
  }
  send_message(*transport_, bytes, "Wrench for step " + std::to_string(wrench.step));
  state_ = State::AwaitPose;
}

Pose CouplingClient::receive_pose(std::int64_t expected_step) {
  if (state_ != State::AwaitPose) {
    throw CouplingError("CouplingClient::receive_pose: no Wrench was sent since the last Pose");
  }
  const std::string awaiting = "Pose for step " + std::to_string(expected_step);
  Bytes bytes;
  try {
    bytes = transport_->receive(timeouts_.step, awaiting);
  } catch (const TimeoutError &e) {
    abandon(CloseReason::Timeout, e.what());
    throw;
  }
  Pose pose;
  try {
    if (peek_type(bytes) == MessageType::Close) {
      state_ = State::Closed;
      throw peer_closed(*transport_, bytes, awaiting);
    }
    pose = decode_pose(bytes);
    if (pose.step != expected_step) {
      throw ProtocolError("Pose.step: step mismatch: expected the Pose for step " +
                          std::to_string(expected_step) + " from " + transport_->peer_name() +
                          ", got step " + std::to_string(pose.step));
    }
  } catch (const PeerClosedError &) {
    throw;
  } catch (const ProtocolError &e) {
    abandon(CloseReason::ProtocolError, e.what());
    throw;
  }
  next_wrench_step_ += hello_.exchange_every;
  state_ = State::AwaitWrench;
  return pose;
}

void CouplingClient::close(CloseReason reason, const std::string &text) {
  if (is_open()) {
    abandon(reason, text);
  }
  state_ = State::Closed;
}

// ------------------------------------------------------------------------------------ server

CouplingServer::CouplingServer(std::unique_ptr<Transport> transport, Timeouts timeouts)
    : transport_(std::move(transport)), timeouts_(timeouts) {
  if (!transport_) {
    throw CouplingError("CouplingServer: no transport given");
  }
}

CouplingServer::~CouplingServer() {
  if (is_open() || state_ == State::AwaitWelcome) {
    send_close_quietly(*transport_, CloseReason::Aborted,
                       "the server (wheel-rig) shut down without finishing the coupled run");
  }
}

bool CouplingServer::is_open() const {
  return state_ == State::AwaitWrench || state_ == State::AwaitPose;
}

void CouplingServer::abandon(CloseReason reason, const std::string &text) noexcept {
  send_close_quietly(*transport_, reason, text);
  state_ = State::Closed;
}

Hello CouplingServer::accept(double expected_dt_s) {
  if (state_ != State::AwaitHello) {
    throw CouplingError("CouplingServer::accept: called twice; one server object runs one session");
  }
  if (!std::isfinite(expected_dt_s) || !(expected_dt_s > 0.0)) {
    throw CouplingError("CouplingServer::accept: the server's time step must be finite and > 0 s, "
                        "got " +
                        format_number(expected_dt_s));
  }
  state_ = State::Closed; // until the Hello is accepted
  const Bytes bytes = transport_->receive(timeouts_.handshake, "Hello");
  Hello hello;
  try {
    if (peek_type(bytes) == MessageType::Close) {
      throw peer_closed(*transport_, bytes, "Hello");
    }
    hello = decode_hello(bytes);
    if (!same_time_step(hello.dt_s, expected_dt_s)) {
      throw ProtocolError(
          "Hello.dt_s: time step mismatch: client dt = " + format_number(hello.dt_s) +
          " s, server dt = " + format_number(expected_dt_s) +
          " s; use the same time step on both sides (the deck's timestep and the "
          "rig config's [run] dt)");
    }
  } catch (const PeerClosedError &) {
    throw;
  } catch (const ProtocolError &e) {
    abandon(CloseReason::ProtocolError, e.what());
    throw;
  }
  hello_ = hello;
  state_ = State::AwaitWelcome;
  return hello;
}

void CouplingServer::welcome(const Welcome &welcome) {
  if (state_ != State::AwaitWelcome) {
    throw CouplingError("CouplingServer::welcome: no Hello accepted (call accept first, once)");
  }
  if (welcome.start_step != hello_.start_step || !same_time_step(welcome.dt_s, hello_.dt_s)) {
    throw CouplingError("CouplingServer::welcome: the Welcome must echo the Hello: start step " +
                        std::to_string(welcome.start_step) + " vs " +
                        std::to_string(hello_.start_step) + ", dt " + format_number(welcome.dt_s) +
                        " s vs " + format_number(hello_.dt_s) + " s");
  }
  Welcome message = welcome;
  message.protocol_version = kProtocolVersion;
  send_message(*transport_, encode(message), "Welcome");
  next_wrench_step_ = hello_.start_step;
  state_ = State::AwaitWrench;
}

std::variant<Wrench, Close> CouplingServer::receive() {
  if (state_ != State::AwaitWrench) {
    throw CouplingError(std::string("CouplingServer::receive: ") +
                        (state_ == State::AwaitPose
                             ? "the Pose for the last Wrench was not sent yet"
                             : "the session is not open"));
  }
  const std::string awaiting = "Wrench for step " + std::to_string(next_wrench_step_);
  Bytes bytes;
  try {
    bytes = transport_->receive(timeouts_.step, awaiting);
  } catch (const TimeoutError &e) {
    abandon(CloseReason::Timeout, e.what());
    throw;
  }
  try {
    if (peek_type(bytes) == MessageType::Close) {
      state_ = State::Closed;
      return decode_close(bytes);
    }
    const Wrench wrench = decode_wrench(bytes);
    if (wrench.step != next_wrench_step_) {
      throw ProtocolError("Wrench.step: step mismatch: expected the Wrench for step " +
                          std::to_string(next_wrench_step_) + " (" + step_rule(hello_) + ") from " +
                          transport_->peer_name() + ", got step " + std::to_string(wrench.step));
    }
    pose_step_ = wrench.step + hello_.exchange_every;
    state_ = State::AwaitPose;
    return wrench;
  } catch (const ProtocolError &e) {
    abandon(CloseReason::ProtocolError, e.what());
    throw;
  }
}

void CouplingServer::send_pose(const Pose &pose) {
  if (state_ != State::AwaitPose) {
    throw CouplingError("CouplingServer::send_pose: no Wrench is waiting for its Pose");
  }
  if (pose.step != pose_step_) {
    throw CouplingError("CouplingServer::send_pose: the reply to the Wrench of step " +
                        std::to_string(pose_step_ - hello_.exchange_every) +
                        " must be the Pose for step " + std::to_string(pose_step_) + ", got step " +
                        std::to_string(pose.step));
  }
  Bytes bytes;
  try {
    bytes = encode(pose);
  } catch (const ProtocolError &e) {
    abandon(CloseReason::Error, std::string("server computed an invalid pose: ") + e.what());
    throw;
  }
  try {
    send_message(*transport_, bytes, "Pose for step " + std::to_string(pose.step));
  } catch (const CouplingError &) {
    // A client that ends its run right after its last Wrench closes without waiting for this
    // Pose; its Close is then already on the way. Report that as the client's Close, not as a
    // failed send.
    const std::exception_ptr send_failure = std::current_exception();
    Bytes reply;
    try {
      reply = transport_->receive(std::chrono::seconds(1), "a Close after the last Wrench");
    } catch (const CouplingError &) {
      std::rethrow_exception(send_failure);
    }
    if (reply.size() < sizeof(MessageHeader) || peek_type(reply) != MessageType::Close)
      std::rethrow_exception(send_failure);
    state_ = State::Closed;
    const Close close = decode_close(reply);
    throw PeerClosedError(transport_->peer_name() + " closed the coupling after its last Wrench (" +
                              to_string(close.reason) + "): " + close.message(),
                          close);
  }
  next_wrench_step_ = pose_step_;
  state_ = State::AwaitWrench;
}

void CouplingServer::close(CloseReason reason, const std::string &text) {
  if (is_open() || state_ == State::AwaitWelcome) {
    abandon(reason, text);
  }
  state_ = State::Closed;
}

} // namespace wheelsim::coupler
