// Message transports of the coupling: one interface, a ZeroMQ implementation (ipc://, tcp://)
// and an in-process loopback pair for tests. No ZeroMQ header here (the library links cppzmq
// privately).
#pragma once

#include "coupler/protocol.h"

#include <chrono>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace wheelsim::coupler {

/// A bidirectional, message-oriented link to exactly one peer. Not thread-safe: one thread uses
/// one end.
class Transport {
public:
  virtual ~Transport() = default;
  /// Queue one whole message for the peer. Throws TimeoutError if the message cannot be handed
  /// over within the transport's send timeout (no peer connected), CouplingError on failure.
  virtual void send(const std::vector<std::uint8_t> &message) = 0;
  /// The next whole message from the peer. Throws TimeoutError after `timeout` with the message
  /// "no <awaiting> from <peer_name()> within <timeout>", e.g.
  /// "no Pose for step 1200 from the rig (tcp://127.0.0.1:5555) within 30 s".
  virtual std::vector<std::uint8_t> receive(std::chrono::milliseconds timeout,
                                            const std::string &awaiting) = 0;
  /// Who is at the other end, for messages: "the rig (ipc:///tmp/run/rig.sock)".
  virtual std::string peer_name() const = 0;
  /// Queue a message without blocking at all; false if it could not be queued (no peer). Used for
  /// the best-effort Close on failures, so that telling a dead peer costs no time.
  virtual bool send_nowait(const std::vector<std::uint8_t> &message) noexcept {
    try {
      send(message);
      return true;
    } catch (...) {
      return false;
    }
  }
};

/// "30 s", "0.25 s".
std::string format_duration(std::chrono::milliseconds duration);

/// The TimeoutError every transport throws: "no <awaiting> from <peer> within <timeout>".
TimeoutError receive_timeout(const std::string &awaiting, const std::string &peer,
                             std::chrono::milliseconds timeout);

// --- in-process loopback ---

/// Two connected ends (first, second): what one sends the other receives, in order. Thread-safe
/// queues with condition variables; receive has the same timeout semantics as ZeroMQ. A
/// destroyed end is not reported to the other: like a dead process, it is noticed by a timeout.
/// Sends never block. `first_peer_name` is how the first end names its peer (the second end).
std::pair<std::unique_ptr<Transport>, std::unique_ptr<Transport>>
make_loopback_pair(const std::string &first_peer_name = "the rig (loopback)",
                   const std::string &second_peer_name = "LIGGGHTS (loopback)");

// --- ZeroMQ ---

struct ZmqOptions {
  /// How long send() may block. A PAIR send blocks only when no peer is connected: on the bound
  /// (server) end after the client is gone; the connecting end queues. So this is short.
  std::chrono::milliseconds send_timeout{1000};
  /// How long closing waits to deliver still-queued messages (e.g. a final Close) to a peer;
  /// bounded so that closing never hangs on a dead peer.
  std::chrono::milliseconds linger{200};
};

/// A ZeroMQ PAIR socket with its own context. Endpoints:
///   ipc://PATH              a Unix-domain socket file (PATH at most 107 bytes; its directory
///                           must exist); the preferred transport on one machine.
///   tcp://HOST:PORT         HOST a loopback address (127.x.y.z, ::1, "localhost"); PORT a
///                           number, or "*" to let the system pick one when binding (read it back
///                           with endpoint()). "tcp://:PORT" binds to 127.0.0.1.
/// Binding tcp to any other address given explicitly (including * and 0.0.0.0) is allowed with a
/// warning on stderr: the coupling is neither authenticated nor encrypted.
class ZmqTransport final : public Transport {
public:
  /// Server side: bind `endpoint`. `peer_label` names the connecting peer ("LIGGGHTS").
  static std::unique_ptr<ZmqTransport> bind(const std::string &endpoint,
                                            const std::string &peer_label = "LIGGGHTS",
                                            const ZmqOptions &options = {});
  /// Client side: connect to `endpoint` (succeeds before the server exists; messages queue).
  static std::unique_ptr<ZmqTransport> connect(const std::string &endpoint,
                                               const std::string &peer_label = "the rig",
                                               const ZmqOptions &options = {});
  ~ZmqTransport() override;
  ZmqTransport(const ZmqTransport &) = delete;
  ZmqTransport &operator=(const ZmqTransport &) = delete;

  void send(const std::vector<std::uint8_t> &message) override;
  std::vector<std::uint8_t> receive(std::chrono::milliseconds timeout,
                                    const std::string &awaiting) override;
  std::string peer_name() const override;
  bool send_nowait(const std::vector<std::uint8_t> &message) noexcept override;
  /// The endpoint as bound or connected (a "*" port resolved to the actual port).
  const std::string &endpoint() const;

private:
  struct Impl;
  explicit ZmqTransport(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The endpoint a server binds to after applying the rules above ("tcp://:5555" ->
/// "tcp://127.0.0.1:5555"); throws CouplingError naming the endpoint and what to write instead.
/// Sets *non_loopback when it is a tcp address off the loopback interface.
std::string normalize_bind_endpoint(const std::string &endpoint, bool *non_loopback = nullptr);
/// Same checks for a client (any tcp host may be connected to).
std::string normalize_connect_endpoint(const std::string &endpoint);

} // namespace wheelsim::coupler
