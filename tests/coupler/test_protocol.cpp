// Protocol encode/decode: exact round trips, and every malformed message rejected with a
// ProtocolError that names the message type and the field.
#include "coupler_test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <limits>

using namespace wheelsim::coupler;
using namespace wheelsim::coupler::test;
using ::testing::HasSubstr;

namespace {

constexpr std::size_t kHeader = sizeof(MessageHeader);

/// Overwrite the double at byte `offset` of the payload.
void poke_double(Bytes &bytes, std::size_t payload_offset, double value) {
  std::memcpy(bytes.data() + kHeader + payload_offset, &value, sizeof value);
}

void poke_u32(Bytes &bytes, std::size_t offset, std::uint32_t value) {
  std::memcpy(bytes.data() + offset, &value, sizeof value);
}

Pose sample_pose() { return Pose{101, rig_state(101, sample_wrench(100))}; }

} // namespace

TEST(CouplerProtocol, WireSizesAreFixed) {
  // The documented sizes (docs/coupling-protocol.md); a change here is a protocol version bump.
  EXPECT_EQ(encode(sample_hello()).size(), 16u + 112u);
  EXPECT_EQ(encode(Welcome{1, 0, 0, kDt, {}}).size(), 16u + 128u);
  EXPECT_EQ(encode(sample_wrench(5)).size(), 16u + 72u);
  EXPECT_EQ(encode(sample_pose()).size(), 16u + 120u);
  EXPECT_EQ(encode(Close::make(CloseReason::Finished, "finished")).size(), 16u + 256u);
}

TEST(CouplerProtocol, RoundTripIsExact) {
  const Hello hello = sample_hello(42, 5);
  const Hello h = decode_hello(encode(hello));
  EXPECT_EQ(std::memcmp(&h, &hello, sizeof h), 0);
  EXPECT_EQ(h.protocol_version, kProtocolVersion);

  Welcome welcome;
  welcome.start_step = 42;
  welcome.dt_s = kDt;
  welcome.state = rig_state(42, sample_wrench(41));
  const Welcome wl = decode_welcome(encode(welcome));
  EXPECT_EQ(std::memcmp(&wl, &welcome, sizeof wl), 0);

  const Wrench wrench = sample_wrench(123456789012LL);
  const Wrench wr = decode_wrench(encode(wrench));
  EXPECT_EQ(std::memcmp(&wr, &wrench, sizeof wr), 0);

  const Pose pose = sample_pose();
  const Pose p = decode_pose(encode(pose));
  EXPECT_EQ(std::memcmp(&p, &pose, sizeof p), 0);

  const Close close = decode_close(encode(Close::make(CloseReason::Error, "error: rig diverged")));
  EXPECT_EQ(close.reason, CloseReason::Error);
  EXPECT_EQ(close.message(), "error: rig diverged");
  EXPECT_EQ(peek_type(encode(pose)), MessageType::Pose);
}

TEST(CouplerProtocol, CloseTextIsCutToFit) {
  const std::string long_text(1000, 'x');
  const Close close = decode_close(encode(Close::make(CloseReason::Error, long_text)));
  EXPECT_EQ(close.message(), std::string(Close::kTextBytes - 1, 'x'));
}

TEST(CouplerProtocol, TruncatedMessageNamesTypeAndSizes) {
  Bytes bytes = encode(sample_wrench(7));
  bytes.resize(bytes.size() - 8);
  const std::string m = message_of<ProtocolError>([&] { decode_wrench(bytes); });
  EXPECT_THAT(m, HasSubstr("Wrench"));
  EXPECT_THAT(m, HasSubstr("80 bytes"));
  EXPECT_THAT(m, HasSubstr("expected 88 bytes"));

  const Bytes stub(10, 0);
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_pose(stub); }),
              HasSubstr("Pose: message is 10 bytes, shorter than the 16-byte header"));
  EXPECT_THAT(message_of<ProtocolError>([&] { peek_type(bytes); }), HasSubstr("payload_bytes"));
}

TEST(CouplerProtocol, WrongTypeNamesBoth) {
  const Bytes bytes = encode(sample_wrench(7));
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_pose(bytes); }),
              HasSubstr("expected a Pose message, got Wrench"));
  Bytes unknown = bytes;
  poke_u32(unknown, offsetof(MessageHeader, type), 77);
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_wrench(unknown); }),
              HasSubstr("expected a Wrench message, got unknown type 77"));
}

TEST(CouplerProtocol, BadMagicIsRejected) {
  Bytes bytes = encode(sample_wrench(7));
  poke_u32(bytes, 0, 0x12345678u);
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_wrench(bytes); }),
              HasSubstr("Wrench: header.magic is 0x12345678"));
  poke_u32(bytes, 0, 0x57534350u); // "WSCP" from a big-endian host
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_wrench(bytes); }), HasSubstr("byte order"));
}

TEST(CouplerProtocol, NanFieldIsNamed) {
  Bytes bytes = encode(sample_wrench(7));
  poke_double(bytes, offsetof(Wrench, f_C_W) + 2 * sizeof(double),
              std::numeric_limits<double>::quiet_NaN());
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_wrench(bytes); }),
              HasSubstr("Wrench.f_C_W[2]: must be a finite number, got nan"));

  Bytes pose = encode(sample_pose());
  poke_double(pose, offsetof(Pose, state) + offsetof(WheelState, w_WB_W) + sizeof(double),
              std::numeric_limits<double>::infinity());
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_pose(pose); }),
              HasSubstr("Pose.state.w_WB_W[1]: must be a finite number, got inf"));

  Bytes hello = encode(sample_hello());
  poke_double(hello, offsetof(Hello, dt_s), std::numeric_limits<double>::quiet_NaN());
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_hello(hello); }), HasSubstr("Hello.dt_s"));
}

TEST(CouplerProtocol, PoseCheckpointFlagRoundTripsAndUnknownBitsAreRejected) {
  Pose pose = sample_pose();
  pose.flags = kPoseCheckpointNext;
  EXPECT_EQ(decode_pose(encode(pose)).flags, kPoseCheckpointNext);
  Bytes bytes = encode(sample_pose());
  poke_u32(bytes, sizeof(MessageHeader) + offsetof(Pose, flags), 6u);
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_pose(bytes); }),
              HasSubstr("Pose.flags: unknown bits set: 6"));
}

TEST(CouplerProtocol, NonUnitQuaternionIsNamed) {
  Bytes bytes = encode(sample_pose());
  poke_double(bytes, offsetof(Pose, state) + offsetof(WheelState, q_WB), 1.2);
  const std::string m = message_of<ProtocolError>([&] { decode_pose(bytes); });
  EXPECT_THAT(m, HasSubstr("Pose.state.q_WB"));
  EXPECT_THAT(m, HasSubstr("unit quaternion"));

  Hello hello = sample_hello();
  hello.q_WB = {1.0, 0.0, 1e-3, 0.0}; // norm 1 + 5e-7: inside the tolerance
  EXPECT_NO_THROW(encode(hello));
  hello.q_WB = {1.0, 0.0, 1e-2, 0.0}; // norm 1 + 5e-5: outside
  EXPECT_THAT(message_of<ProtocolError>([&] { encode(hello); }), HasSubstr("Hello.q_WB"));
}

TEST(CouplerProtocol, HelloRangesAreChecked) {
  Hello hello = sample_hello();
  hello.exchange_every = 0;
  EXPECT_THAT(message_of<ProtocolError>([&] { encode(hello); }),
              HasSubstr("Hello.exchange_every: must be >= 1"));
  hello = sample_hello();
  hello.dt_s = -1e-5;
  EXPECT_THAT(message_of<ProtocolError>([&] { encode(hello); }),
              HasSubstr("Hello.dt_s: time step must be > 0 s, got -1e-05 s"));
  hello = sample_hello();
  hello.start_step = -3;
  EXPECT_THAT(message_of<ProtocolError>([&] { encode(hello); }),
              HasSubstr("Hello.start_step: must be >= 0, got -3"));
  hello = sample_hello();
  hello.units = {'c', 'g', 's', 0, 0, 0, 0, 0};
  EXPECT_THAT(message_of<ProtocolError>([&] { encode(hello); }),
              HasSubstr("Hello.units: must be \"si\""));
  Wrench wrench = sample_wrench(3);
  wrench.n_contacts = -1;
  EXPECT_THAT(message_of<ProtocolError>([&] { encode(wrench); }), HasSubstr("Wrench.n_contacts"));
}

TEST(CouplerProtocol, VersionMismatchNamesBothVersions) {
  Hello hello = sample_hello();
  hello.protocol_version = 1;
  const Bytes bytes = encode(hello);
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_hello(bytes); }),
              HasSubstr("client speaks protocol 1, server 2"));

  Welcome welcome;
  welcome.protocol_version = 7;
  welcome.dt_s = kDt;
  const Bytes wb = encode(welcome);
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_welcome(wb); }),
              HasSubstr("server speaks protocol 7, client 2"));

  Bytes wrench = encode(sample_wrench(1));
  poke_u32(wrench, offsetof(MessageHeader, version), 3);
  EXPECT_THAT(message_of<ProtocolError>([&] { decode_wrench(wrench); }),
              HasSubstr("client speaks protocol 3, server 2"));
}

TEST(CouplerProtocol, CloseIsReadableFromAnyVersion) {
  Bytes bytes =
      encode(Close::make(CloseReason::ProtocolError, "client speaks protocol 1, server 9"));
  poke_u32(bytes, offsetof(MessageHeader, version), 9);
  const Close close = decode_close(bytes);
  EXPECT_EQ(close.message(), "client speaks protocol 1, server 9");

  Close unterminated;
  unterminated.text.fill('x');
  EXPECT_THAT(message_of<ProtocolError>([&] { encode(unterminated); }),
              HasSubstr("Close.text: must be NUL-terminated"));
}
