// The ZeroMQ transport: one PAIR socket per end (see docs/coupling-protocol.md, "Transports", for
// why PAIR and not REQ/REP).
#include "coupler/transport.h"

#include <zmq.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <limits>
#include <sys/stat.h>
#include <sys/un.h>

namespace wheelsim::coupler {

namespace {

constexpr const char *kIpcPrefix = "ipc://";
constexpr const char *kTcpPrefix = "tcp://";
constexpr std::size_t kMaxIpcPath = sizeof(sockaddr_un{}.sun_path) - 1;
constexpr const char *kEndpointHelp =
    "write ipc:///path/to/socket (same machine) or tcp://127.0.0.1:PORT";

bool starts_with(const std::string &s, const char *prefix) { return s.rfind(prefix, 0) == 0; }

bool is_loopback_host(const std::string &host) {
  if (host == "localhost" || host == "::1" || host == "[::1]") {
    return true;
  }
  if (!starts_with(host, "127.")) {
    return false;
  }
  for (char c : host) {
    if (c != '.' && (c < '0' || c > '9')) {
      return false;
    }
  }
  return true;
}

struct TcpAddress {
  std::string host;
  std::string port;
};

TcpAddress split_tcp(const std::string &endpoint, bool allow_wildcard_port) {
  const std::string rest = endpoint.substr(std::char_traits<char>::length(kTcpPrefix));
  const auto colon = rest.rfind(':');
  if (colon == std::string::npos) {
    throw CouplingError("coupling endpoint \"" + endpoint + "\": no port; " + kEndpointHelp);
  }
  TcpAddress address{rest.substr(0, colon), rest.substr(colon + 1)};
  const bool wildcard = address.port == "*";
  bool numeric = !address.port.empty() && address.port.size() <= 5;
  for (char c : address.port) {
    numeric = numeric && c >= '0' && c <= '9';
  }
  if (wildcard ? !allow_wildcard_port
               : !numeric || std::stoi(address.port) < 1 || std::stoi(address.port) > 65535) {
    throw CouplingError("coupling endpoint \"" + endpoint + "\": port \"" + address.port +
                        "\" must be a number 1..65535" +
                        (allow_wildcard_port ? " or * (any free port)" : "") + "; " +
                        kEndpointHelp);
  }
  if (address.host.empty()) {
    address.host = "127.0.0.1";
  }
  return address;
}

void check_ipc(const std::string &endpoint, bool binding) {
  const std::string path = endpoint.substr(std::char_traits<char>::length(kIpcPrefix));
  if (path.empty()) {
    throw CouplingError("coupling endpoint \"" + endpoint + "\": empty path; " + kEndpointHelp);
  }
  if (path.size() > kMaxIpcPath) {
    throw CouplingError("coupling endpoint \"" + endpoint + "\": the socket path is " +
                        std::to_string(path.size()) + " bytes, the system allows at most " +
                        std::to_string(kMaxIpcPath) + "; choose a shorter path (e.g. under /tmp)");
  }
  if (binding && path[0] != '@') { // '@': Linux abstract namespace, no file
    const auto slash = path.rfind('/');
    const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
    struct stat info {};
    if (::stat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) {
      throw CouplingError("coupling endpoint \"" + endpoint + "\": directory \"" + dir +
                          "\" does not exist; create it or choose another socket path");
    }
  }
}

} // namespace

std::string normalize_bind_endpoint(const std::string &endpoint, bool *non_loopback) {
  if (non_loopback != nullptr) {
    *non_loopback = false;
  }
  if (starts_with(endpoint, kIpcPrefix)) {
    check_ipc(endpoint, true);
    return endpoint;
  }
  if (starts_with(endpoint, kTcpPrefix)) {
    TcpAddress address = split_tcp(endpoint, true);
    if (address.host == "localhost") {
      address.host = "127.0.0.1"; // ZeroMQ binds to interfaces or addresses, not host names
    }
    if (non_loopback != nullptr) {
      *non_loopback = !is_loopback_host(address.host);
    }
    return std::string(kTcpPrefix) + address.host + ":" + address.port;
  }
  throw CouplingError("coupling endpoint \"" + endpoint + "\": unsupported transport; " +
                      kEndpointHelp);
}

std::string normalize_connect_endpoint(const std::string &endpoint) {
  if (starts_with(endpoint, kIpcPrefix)) {
    check_ipc(endpoint, false);
    return endpoint;
  }
  if (starts_with(endpoint, kTcpPrefix)) {
    const TcpAddress address = split_tcp(endpoint, false);
    return std::string(kTcpPrefix) + address.host + ":" + address.port;
  }
  throw CouplingError("coupling endpoint \"" + endpoint + "\": unsupported transport; " +
                      kEndpointHelp);
}

struct ZmqTransport::Impl {
  zmq::context_t context{1};
  zmq::socket_t socket{context, zmq::socket_type::pair};
  std::string endpoint;
  std::string peer;
  std::chrono::milliseconds send_timeout{0};
  int receive_timeout_ms = -2; ///< the value set on the socket (-2: not yet set)

  Impl(const std::string &peer_label, const ZmqOptions &options)
      : peer(peer_label), send_timeout(options.send_timeout) {
    socket.set(zmq::sockopt::linger, static_cast<int>(options.linger.count()));
    socket.set(zmq::sockopt::sndtimeo, static_cast<int>(options.send_timeout.count()));
  }
};

ZmqTransport::ZmqTransport(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ZmqTransport::~ZmqTransport() = default;

std::unique_ptr<ZmqTransport> ZmqTransport::bind(const std::string &endpoint,
                                                 const std::string &peer_label,
                                                 const ZmqOptions &options) {
  bool non_loopback = false;
  const std::string address = normalize_bind_endpoint(endpoint, &non_loopback);
  if (non_loopback) {
    std::fprintf(stderr,
                 "wheelsim coupler: warning: binding %s, which is not a loopback address: the "
                 "coupling is neither authenticated nor encrypted, anyone who can reach this port "
                 "can connect; use tcp://127.0.0.1:PORT or ipc:// when both processes run on this "
                 "machine\n",
                 address.c_str());
  }
  auto impl = std::make_unique<Impl>(peer_label, options);
  if (address.find('[') != std::string::npos) {
    impl->socket.set(zmq::sockopt::ipv6, 1);
  }
  try {
    impl->socket.bind(address);
  } catch (const zmq::error_t &e) {
    throw CouplingError("cannot bind the coupling endpoint " + address + ": " + e.what() +
                        (e.num() == EADDRINUSE
                             ? " (another process, e.g. a second wheel-rig, uses it; choose "
                               "another port or stop that process)"
                             : ""));
  }
  impl->endpoint = impl->socket.get(zmq::sockopt::last_endpoint);
  return std::unique_ptr<ZmqTransport>(new ZmqTransport(std::move(impl)));
}

std::unique_ptr<ZmqTransport> ZmqTransport::connect(const std::string &endpoint,
                                                    const std::string &peer_label,
                                                    const ZmqOptions &options) {
  const std::string address = normalize_connect_endpoint(endpoint);
  auto impl = std::make_unique<Impl>(peer_label, options);
  if (address.find('[') != std::string::npos) {
    impl->socket.set(zmq::sockopt::ipv6, 1);
  }
  try {
    impl->socket.connect(address);
  } catch (const zmq::error_t &e) {
    throw CouplingError("cannot connect to the coupling endpoint " + address + ": " + e.what());
  }
  impl->endpoint = address;
  return std::unique_ptr<ZmqTransport>(new ZmqTransport(std::move(impl)));
}

void ZmqTransport::send(const Bytes &message) {
  for (;;) {
    try {
      if (!impl_->socket.send(zmq::buffer(message), zmq::send_flags::none)) {
        throw TimeoutError("could not hand a message to " + peer_name() + " within " +
                           format_duration(impl_->send_timeout) + ": no peer connected");
      }
      return;
    } catch (const zmq::error_t &e) {
      if (e.num() != EINTR) {
        throw CouplingError("sending to " + peer_name() + " failed: " + e.what());
      }
    }
  }
}

bool ZmqTransport::send_nowait(const Bytes &message) noexcept {
  try {
    return static_cast<bool>(impl_->socket.send(zmq::buffer(message), zmq::send_flags::dontwait));
  } catch (...) {
    return false;
  }
}

Bytes ZmqTransport::receive(std::chrono::milliseconds timeout, const std::string &awaiting) {
  using std::chrono::steady_clock;
  const auto deadline = steady_clock::now() + timeout;
  // The full timeout on the first try keeps the socket option unchanged between calls (no
  // setsockopt per exchange). ZeroMQ times out on its own millisecond clock, which can end up to
  // a millisecond before ours: an early timeout, like an EINTR, waits for the rest of the time
  // (rounded up to a whole millisecond), so the wait is never shorter than `timeout`.
  for (auto remaining = timeout;;) {
    // ZMQ_RCVTIMEO is an int of ms: a longer wait (over ~24.8 days) is waited in pieces, since
    // a value past INT_MAX would wrap to a negative one (EINVAL, or -1: wait forever)
    const int timeout_ms = static_cast<int>(std::min<std::int64_t>(
        std::max<std::int64_t>(remaining.count(), 0), std::numeric_limits<int>::max()));
    if (timeout_ms != impl_->receive_timeout_ms) {
      impl_->socket.set(zmq::sockopt::rcvtimeo, timeout_ms);
      impl_->receive_timeout_ms = timeout_ms;
    }
    try {
      zmq::message_t message;
      if (impl_->socket.recv(message, zmq::recv_flags::none)) {
        const auto *data = static_cast<const std::uint8_t *>(message.data());
        return Bytes(data, data + message.size());
      }
      if (steady_clock::now() >= deadline) {
        throw receive_timeout(awaiting, peer_name(), timeout);
      }
    } catch (const zmq::error_t &e) {
      if (e.num() != EINTR) {
        throw CouplingError("receiving " + awaiting + " from " + peer_name() +
                            " failed: " + e.what());
      }
    }
    remaining = std::chrono::ceil<std::chrono::milliseconds>(deadline - steady_clock::now());
  }
}

std::string ZmqTransport::peer_name() const { return impl_->peer + " (" + impl_->endpoint + ")"; }

const std::string &ZmqTransport::endpoint() const { return impl_->endpoint; }

} // namespace wheelsim::coupler
