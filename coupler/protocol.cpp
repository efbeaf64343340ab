#include "coupler/protocol.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

namespace wheelsim::coupler {

namespace {

constexpr std::uint32_t kMagicByteSwapped = 0x57534350u;

std::string field_name(const char *message, const char *field) {
  return std::string(message) + "." + field;
}

void check_finite(const char *message, const char *field, double value) {
  if (!std::isfinite(value)) {
    throw ProtocolError(field_name(message, field) + ": must be a finite number, got " +
                        format_number(value));
  }
}

template <std::size_t N>
void check_finite(const char *message, const char *field, const std::array<double, N> &values) {
  for (std::size_t i = 0; i < N; ++i) {
    if (!std::isfinite(values[i])) {
      throw ProtocolError(field_name(message, field) + "[" + std::to_string(i) +
                          "]: must be a finite number, got " + format_number(values[i]));
    }
  }
}

void check_unit_quaternion(const char *message, const char *field, const Quat &q) {
  check_finite(message, field, q);
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(std::fabs(norm - 1.0) <= kQuaternionNormTolerance)) {
    throw ProtocolError(field_name(message, field) +
                        ": orientation must be a unit quaternion (w, x, y, z) within " +
                        format_number(kQuaternionNormTolerance) + ", got norm " +
                        format_number(norm));
  }
}

void check_step(const char *message, const char *field, std::int64_t step) {
  if (step < 0) {
    throw ProtocolError(field_name(message, field) + ": must be >= 0, got " + std::to_string(step));
  }
}

void check_time_step(const char *message, double dt_s) {
  check_finite(message, "dt_s", dt_s);
  if (!(dt_s > 0.0)) {
    throw ProtocolError(field_name(message, "dt_s") + ": time step must be > 0 s, got " +
                        format_number(dt_s) + " s");
  }
}

void check_state(const char *message, const WheelState &state) {
  check_finite(message, "state.p_WC_W", state.p_WC_W);
  check_unit_quaternion(message, "state.q_WB", state.q_WB);
  check_finite(message, "state.v_WC_W", state.v_WC_W);
  check_finite(message, "state.w_WB_W", state.w_WB_W);
}

template <typename Payload> Bytes pack(MessageType type, std::uint32_t version, const Payload &p) {
  const MessageHeader header{kMagic, version, static_cast<std::uint32_t>(type),
                             static_cast<std::uint32_t>(sizeof(Payload))};
  Bytes bytes(sizeof(MessageHeader) + sizeof(Payload));
  std::memcpy(bytes.data(), &header, sizeof header);
  std::memcpy(bytes.data() + sizeof header, &p, sizeof p);
  return bytes;
}

MessageHeader read_header(const Bytes &bytes, const char *expected) {
  MessageHeader header{};
  if (bytes.size() < sizeof header) {
    throw ProtocolError(std::string(expected) + ": message is " + std::to_string(bytes.size()) +
                        " bytes, shorter than the " + std::to_string(sizeof header) +
                        "-byte header (truncated or not a wheelsim coupling message)");
  }
  std::memcpy(&header, bytes.data(), sizeof header);
  if (header.magic != kMagic) {
    if (header.magic == kMagicByteSwapped) {
      throw ProtocolError(std::string(expected) +
                          ": header.magic is byte-swapped: the peer runs on a machine of the other "
                          "byte order, which the protocol does not support");
    }
    throw ProtocolError(std::string(expected) + ": header.magic is 0x" + [&] {
      char buf[16];
      auto r = std::to_chars(buf, buf + sizeof buf, header.magic, 16);
      return std::string(buf, r.ptr);
    }() + ", expected 0x50435357 (\"WSCP\"): not a wheelsim coupling message");
  }
  return header;
}

/// Header checks for a message of type `T` sent by `sender` to `receiver`; then copies the payload.
template <typename Payload>
Payload unpack(const Bytes &bytes, MessageType type, const char *sender, const char *receiver,
               bool check_version, std::uint32_t *version_out = nullptr) {
  const std::string name = to_string(type);
  const MessageHeader header = read_header(bytes, name.c_str());
  if (check_version && header.version != kProtocolVersion) {
    throw ProtocolError(name + ": protocol version mismatch: " + sender + " speaks protocol " +
                        std::to_string(header.version) + ", " + receiver + " " +
                        std::to_string(kProtocolVersion));
  }
  if (header.type != static_cast<std::uint32_t>(type)) {
    throw ProtocolError("expected a " + name + " message, got " +
                        to_string(static_cast<MessageType>(header.type)) +
                        " (header.type = " + std::to_string(header.type) + ")");
  }
  const std::size_t expected_size = sizeof(MessageHeader) + sizeof(Payload);
  if (header.payload_bytes != sizeof(Payload) || bytes.size() != expected_size) {
    throw ProtocolError(
        name + ": message is " + std::to_string(bytes.size()) +
        " bytes with header.payload_bytes = " + std::to_string(header.payload_bytes) +
        ", expected " + std::to_string(expected_size) + " bytes (" +
        std::to_string(sizeof(MessageHeader)) + "-byte header + " +
        std::to_string(sizeof(Payload)) + "-byte payload)");
  }
  Payload payload;
  std::memcpy(&payload, bytes.data() + sizeof(MessageHeader), sizeof payload);
  if (version_out != nullptr) {
    *version_out = header.version;
  }
  return payload;
}

} // namespace

std::string to_string(MessageType type) {
  switch (type) {
  case MessageType::Hello:
    return "Hello";
  case MessageType::Welcome:
    return "Welcome";
  case MessageType::Wrench:
    return "Wrench";
  case MessageType::Pose:
    return "Pose";
  case MessageType::Close:
    return "Close";
  }
  return "unknown type " + std::to_string(static_cast<std::uint32_t>(type));
}

std::string to_string(CloseReason reason) {
  switch (reason) {
  case CloseReason::Finished:
    return "finished";
  case CloseReason::Error:
    return "error";
  case CloseReason::ProtocolError:
    return "protocol error";
  case CloseReason::Timeout:
    return "timeout";
  case CloseReason::Aborted:
    return "aborted";
  }
  return "reason " + std::to_string(static_cast<std::uint32_t>(reason));
}

std::string format_number(double value) {
  if (std::isnan(value)) {
    return "nan";
  }
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, result.ptr);
}

Close Close::make(CloseReason reason, const std::string &message) {
  Close close;
  close.reason = reason;
  const std::size_t n = std::min(message.size(), kTextBytes - 1);
  std::memcpy(close.text.data(), message.data(), n);
  return close;
}

std::string Close::message() const {
  const auto *end = static_cast<const char *>(std::memchr(text.data(), '\0', text.size()));
  return std::string(text.data(), end != nullptr ? end : text.data() + text.size());
}

// --- validation ---

void validate(const Hello &m) {
  if (m.exchange_every < 1) {
    throw ProtocolError("Hello.exchange_every: must be >= 1 (exchange every N steps), got " +
                        std::to_string(m.exchange_every));
  }
  check_step("Hello", "start_step", m.start_step);
  check_time_step("Hello", m.dt_s);
  const auto *nul = static_cast<const char *>(std::memchr(m.units.data(), '\0', m.units.size()));
  const std::string units(m.units.data(), nul != nullptr ? nul : m.units.data() + m.units.size());
  if (nul == nullptr || units != kUnitsSI) {
    throw ProtocolError("Hello.units: must be \"si\" (the only unit system), got \"" + units +
                        "\"" + (nul == nullptr ? " (not NUL-terminated)" : ""));
  }
  check_finite("Hello", "p_WR_W", m.p_WR_W);
  check_finite("Hello", "p_WC_W", m.p_WC_W);
  check_unit_quaternion("Hello", "q_WB", m.q_WB);
}

void validate(const Welcome &m) {
  check_step("Welcome", "start_step", m.start_step);
  check_time_step("Welcome", m.dt_s);
  check_state("Welcome", m.state);
}

void validate(const Wrench &m) {
  check_step("Wrench", "step", m.step);
  check_finite("Wrench", "time_s", m.time_s);
  check_finite("Wrench", "f_C_W", m.f_C_W);
  check_finite("Wrench", "t_C_W", m.t_C_W);
  if (m.n_contacts < 0) {
    throw ProtocolError("Wrench.n_contacts: must be >= 0, got " + std::to_string(m.n_contacts));
  }
}

void validate(const Pose &m) {
  check_step("Pose", "step", m.step);
  check_state("Pose", m.state);
  if ((m.flags & ~kPoseCheckpointNext) != 0u)
    throw ProtocolError("Pose.flags: unknown bits set: " + std::to_string(m.flags) +
                        " (known: " + std::to_string(kPoseCheckpointNext) + " checkpoint)");
  if (m.reserved != 0u)
    throw ProtocolError("Pose.reserved: must be 0, got " + std::to_string(m.reserved));
}

void validate(const Close &m) {
  // Any reason code is accepted (a newer peer may know more); the text must be terminated.
  if (std::memchr(m.text.data(), '\0', m.text.size()) == nullptr) {
    throw ProtocolError("Close.text: must be NUL-terminated within " +
                        std::to_string(Close::kTextBytes) + " bytes");
  }
}

// --- encode ---

Bytes encode(const Hello &m) {
  validate(m);
  return pack(MessageType::Hello, m.protocol_version, m);
}
Bytes encode(const Welcome &m) {
  validate(m);
  return pack(MessageType::Welcome, m.protocol_version, m);
}
Bytes encode(const Wrench &m) {
  validate(m);
  return pack(MessageType::Wrench, kProtocolVersion, m);
}
Bytes encode(const Pose &m) {
  validate(m);
  return pack(MessageType::Pose, kProtocolVersion, m);
}
Bytes encode(const Close &m) {
  validate(m);
  return pack(MessageType::Close, kProtocolVersion, m);
}

// --- decode ---

MessageType peek_type(const Bytes &bytes) {
  const MessageHeader header = read_header(bytes, "message");
  if (header.payload_bytes != bytes.size() - sizeof(MessageHeader)) {
    throw ProtocolError("message: " + std::to_string(bytes.size()) +
                        " bytes but header.payload_bytes = " +
                        std::to_string(header.payload_bytes) + " (truncated or padded)");
  }
  return static_cast<MessageType>(header.type);
}

Hello decode_hello(const Bytes &bytes) {
  std::uint32_t version = 0;
  Hello m = unpack<Hello>(bytes, MessageType::Hello, "client", "server", true, &version);
  m.protocol_version = version;
  validate(m);
  return m;
}

Welcome decode_welcome(const Bytes &bytes) {
  std::uint32_t version = 0;
  Welcome m = unpack<Welcome>(bytes, MessageType::Welcome, "server", "client", true, &version);
  m.protocol_version = version;
  validate(m);
  return m;
}

Wrench decode_wrench(const Bytes &bytes) {
  Wrench m = unpack<Wrench>(bytes, MessageType::Wrench, "client", "server", true);
  validate(m);
  return m;
}

Pose decode_pose(const Bytes &bytes) {
  Pose m = unpack<Pose>(bytes, MessageType::Pose, "server", "client", true);
  validate(m);
  return m;
}

Close decode_close(const Bytes &bytes) {
  Close m = unpack<Close>(bytes, MessageType::Close, "peer", "we", false);
  validate(m);
  return m;
}

} // namespace wheelsim::coupler
