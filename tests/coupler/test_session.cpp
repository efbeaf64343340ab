// CouplingClient and CouplingServer over the in-process loopback, client and server in two
// threads: round trips, mismatches seen on both sides, timeouts, a vanished peer, step mismatch.
#include "coupler_test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

using namespace wheelsim::coupler;
using namespace wheelsim::coupler::test;
using ::testing::HasSubstr;

namespace {

constexpr Timeouts kSessionTimeouts{300ms, 300ms};
/// Allowed lateness of a timeout on a loaded CI machine.
constexpr double kSessionMarginMs = 500.0;

struct LoopbackSession {
  LoopbackSession() {
    auto [client_end, server_end] = make_loopback_pair("the rig (loopback)", "LIGGGHTS (loopback)");
    client_transport = std::move(client_end);
    server_transport = std::move(server_end);
  }
  std::unique_ptr<Transport> client_transport;
  std::unique_ptr<Transport> server_transport;
};

} // namespace

TEST(CouplerSession, LoopbackRoundTrip) {
  for (std::uint32_t every : {1u, 5u}) {
    LoopbackSession s;
    CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
    RigResult rig;
    Background rig_thread([&] { rig = run_fake_rig(server, kDt); });
    CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
    const Hello hello = sample_hello(1000, every);
    EXPECT_EQ(run_fake_liggghts(client, hello, 200), 200) << "exchange_every " << every;
    rig_thread.join();
    EXPECT_EQ(rig.wrenches, 200);
    EXPECT_TRUE(rig.all_wrenches_match);
    EXPECT_EQ(rig.hello.exchange_every, every);
    EXPECT_EQ(std::memcmp(&rig.hello, &hello, sizeof hello), 0);
    ASSERT_TRUE(rig.got_close);
    EXPECT_EQ(rig.close.reason, CloseReason::Finished);
    EXPECT_EQ(rig.close.message(), "finished");
    EXPECT_FALSE(client.is_open());
    EXPECT_FALSE(server.is_open());
  }
}

TEST(CouplerSession, VersionMismatchIsReportedOnBothSides) {
  LoopbackSession s;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  std::string server_error;
  Background rig_thread(
      [&] { server_error = message_of<ProtocolError>([&] { server.accept(kDt); }); });
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  Hello hello = sample_hello();
  hello.protocol_version = 3;
  std::string client_error;
  CloseReason reason = CloseReason::Finished;
  try {
    client.connect(hello);
  } catch (const PeerClosedError &e) {
    client_error = e.what();
    reason = e.reason();
  }
  rig_thread.join();
  EXPECT_THAT(server_error, HasSubstr("client speaks protocol 3, server 2"));
  EXPECT_THAT(client_error, HasSubstr("client speaks protocol 3, server 2"));
  EXPECT_THAT(client_error, HasSubstr("the rig (loopback) closed the coupling"));
  EXPECT_EQ(reason, CloseReason::ProtocolError);
}

TEST(CouplerSession, ServerOfAnotherVersionIsRejectedByTheClient) {
  LoopbackSession s;
  Transport &rig = *s.server_transport;
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  Welcome welcome;
  welcome.protocol_version = 3;
  welcome.start_step = 100;
  welcome.dt_s = kDt;
  rig.send(encode(welcome));
  EXPECT_THAT(message_of<ProtocolError>([&] { client.connect(sample_hello(100)); }),
              HasSubstr("server speaks protocol 3, client 2"));
  ASSERT_EQ(peek_type(rig.receive(100ms, "Hello")), MessageType::Hello);
  const Close close = decode_close(rig.receive(100ms, "Close"));
  EXPECT_EQ(close.reason, CloseReason::ProtocolError);
  EXPECT_THAT(close.message(), HasSubstr("server speaks protocol 3, client 2"));
}

TEST(CouplerSession, TimeStepMismatchIsReportedOnBothSides) {
  LoopbackSession s;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  std::string server_error;
  Background rig_thread(
      [&] { server_error = message_of<ProtocolError>([&] { server.accept(2e-5); }); });
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  const std::string client_error =
      message_of<PeerClosedError>([&] { client.connect(sample_hello()); });
  rig_thread.join();
  for (const std::string &m : {server_error, client_error}) {
    EXPECT_THAT(m, HasSubstr("time step mismatch: client dt = 1e-05 s, server dt = 2e-05 s"));
  }
}

TEST(CouplerSession, TimeStepWithinRelativeToleranceIsAccepted) {
  LoopbackSession s;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  Background rig_thread([&] { run_fake_rig(server, kDt * (1 + 1e-12)); });
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  EXPECT_EQ(run_fake_liggghts(client, sample_hello(), 3), 3);
  rig_thread.join();
}

TEST(CouplerSession, SilentServerTimesOutNamingPeerAndWelcome) {
  LoopbackSession s; // the server end exists but nobody answers
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  std::string m;
  const double ms = elapsed_ms_of(
      [&] { m = message_of<TimeoutError>([&] { client.connect(sample_hello(100)); }); });
  EXPECT_EQ(m,
            "no Welcome (reply to Hello for start step 100) from the rig (loopback) within 0.3 s");
  EXPECT_GE(ms, 300.0);
  EXPECT_LE(ms, 300.0 + kSessionMarginMs);
}

TEST(CouplerSession, SilentClientTimesOutNamingPeerAndHello) {
  LoopbackSession s;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  std::string m;
  const double ms =
      elapsed_ms_of([&] { m = message_of<TimeoutError>([&] { server.accept(kDt); }); });
  EXPECT_EQ(m, "no Hello from LIGGGHTS (loopback) within 0.3 s");
  EXPECT_GE(ms, 300.0);
  EXPECT_LE(ms, 300.0 + kSessionMarginMs);
}

TEST(CouplerSession, RigThatVanishesMidRunIsATimeoutOnTheClient) {
  LoopbackSession s;
  auto cuttable = std::make_unique<CuttableTransport>(std::move(s.server_transport));
  CuttableTransport *cut = cuttable.get();
  Background rig_thread([&] {
    CouplingServer server(std::move(cuttable), kSessionTimeouts);
    run_fake_rig(server, kDt, 10); // answers 9 wrenches, then "crashes" on the 10th
    cut->cut();                    // the destructor's Close is lost like a killed process's
  });
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  std::string m;
  const double ms = elapsed_ms_of([&] {
    m = message_of<TimeoutError>([&] { run_fake_liggghts(client, sample_hello(100), 50); });
  });
  rig_thread.join();
  EXPECT_EQ(m, "no Pose for step 110 from the rig (loopback) within 0.3 s");
  EXPECT_LE(ms, 300.0 + kSessionMarginMs);
  EXPECT_FALSE(client.is_open());
}

TEST(CouplerSession, ClientThatVanishesMidRunIsATimeoutOnTheServer) {
  LoopbackSession s;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  std::string server_error;
  Background rig_thread(
      [&] { server_error = message_of<TimeoutError>([&] { run_fake_rig(server, kDt); }); });
  {
    CuttableTransport *cut = nullptr;
    auto cuttable = std::make_unique<CuttableTransport>(std::move(s.client_transport));
    cut = cuttable.get();
    CouplingClient client(std::move(cuttable), kSessionTimeouts);
    EXPECT_EQ(run_fake_liggghts(client, sample_hello(100, 2), 7, false), 7);
    cut->cut(); // LIGGGHTS dies: no Close
  }
  rig_thread.join();
  EXPECT_EQ(server_error, "no Wrench for step 114 from LIGGGHTS (loopback) within 0.3 s");
}

TEST(CouplerSession, CloseFromTheRigCarriesItsReason) {
  LoopbackSession s;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  Background rig_thread([&] {
    server.accept(kDt);
    Welcome w;
    w.start_step = 100;
    w.dt_s = kDt;
    server.welcome(w);
    (void)server.receive();
    server.close(CloseReason::Error, "error: spring stiffness became negative");
  });
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  client.connect(sample_hello(100));
  client.send_wrench(sample_wrench(100));
  try {
    client.receive_pose(101);
    ADD_FAILURE() << "no PeerClosedError";
  } catch (const PeerClosedError &e) {
    EXPECT_EQ(e.reason(), CloseReason::Error);
    EXPECT_EQ(e.peer_text(), "error: spring stiffness became negative");
    EXPECT_THAT(e.what(), HasSubstr("the rig (loopback) closed the coupling while we awaited "
                                    "Pose for step 101 (error): error: spring stiffness"));
  }
  rig_thread.join();
  EXPECT_FALSE(client.is_open());
}

TEST(CouplerSession, PoseForAnotherStepIsReportedWithBothSteps) {
  LoopbackSession s;
  Transport &rig = *s.server_transport;
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  Welcome w;
  w.start_step = 100;
  w.dt_s = kDt;
  rig.send(encode(w));
  client.connect(sample_hello(100));
  client.send_wrench(sample_wrench(100));
  rig.send(encode(Pose{102, rig_state(102, sample_wrench(100))}));
  EXPECT_THAT(message_of<ProtocolError>([&] { client.receive_pose(101); }),
              HasSubstr("expected the Pose for step 101 from the rig (loopback), got step 102"));
  (void)rig.receive(100ms, "Hello");
  (void)rig.receive(100ms, "Wrench");
  const Close close = decode_close(rig.receive(100ms, "Close"));
  EXPECT_EQ(close.reason, CloseReason::ProtocolError);
  EXPECT_THAT(close.message(), HasSubstr("step 101"));
}

TEST(CouplerSession, WrenchForAnotherStepIsReportedByTheServer) {
  LoopbackSession s;
  Transport &liggghts = *s.client_transport;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  liggghts.send(encode(sample_hello(100, 4)));
  server.accept(kDt);
  Welcome w;
  w.start_step = 100;
  w.dt_s = kDt;
  server.welcome(w);
  liggghts.send(encode(sample_wrench(100)));
  ASSERT_TRUE(std::holds_alternative<Wrench>(server.receive()));
  server.send_pose(Pose{104, rig_state(104, sample_wrench(100))});
  liggghts.send(encode(sample_wrench(105)));
  EXPECT_THAT(message_of<ProtocolError>([&] { server.receive(); }),
              HasSubstr("expected the Wrench for step 104 (start step 100, exchange_every 4) "
                        "from LIGGGHTS (loopback), got step 105"));
  (void)liggghts.receive(100ms, "Welcome");
  (void)liggghts.receive(100ms, "Pose");
  EXPECT_EQ(decode_close(liggghts.receive(100ms, "Close")).reason, CloseReason::ProtocolError);
}

TEST(CouplerSession, ClientRefusesToSendOutOfStepOrInvalidWrench) {
  LoopbackSession s;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  Background rig_thread([&] { run_fake_rig(server, kDt); });
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  client.connect(sample_hello(100, 1));
  EXPECT_THAT(message_of<ProtocolError>([&] { client.send_wrench(sample_wrench(99)); }),
              HasSubstr("the next exchange is at step 100 (start step 100, exchange_every 1), got "
                        "step 99"));
  EXPECT_FALSE(client.is_open());
  rig_thread.join(); // the rig got a Close and ended
}

TEST(CouplerSession, MalformedPoseIsRejectedAndThePeerTold) {
  LoopbackSession s;
  Transport &rig = *s.server_transport;
  CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
  Welcome w;
  w.start_step = 100;
  w.dt_s = kDt;
  rig.send(encode(w));
  client.connect(sample_hello(100));
  client.send_wrench(sample_wrench(100));
  Bytes pose = encode(Pose{101, rig_state(101, sample_wrench(100))});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(pose.data() + sizeof(MessageHeader) + offsetof(Pose, state) +
                  offsetof(WheelState, v_WC_W) + sizeof(double),
              &nan, sizeof nan);
  rig.send(pose);
  EXPECT_THAT(message_of<ProtocolError>([&] { client.receive_pose(101); }),
              HasSubstr("Pose.state.v_WC_W[1]: must be a finite number, got nan"));
  (void)rig.receive(100ms, "Hello");
  (void)rig.receive(100ms, "Wrench");
  const Close close = decode_close(rig.receive(100ms, "Close"));
  EXPECT_THAT(close.message(), HasSubstr("Pose.state.v_WC_W[1]"));
}

TEST(CouplerSession, DestroyedClientTellsTheRig) {
  LoopbackSession s;
  CouplingServer server(std::move(s.server_transport), kSessionTimeouts);
  RigResult rig;
  Background rig_thread([&] { rig = run_fake_rig(server, kDt); });
  {
    CouplingClient client(std::move(s.client_transport), kSessionTimeouts);
    run_fake_liggghts(client, sample_hello(), 3, false);
  } // e.g. an exception unwinds the fix: the destructor sends Close{aborted}
  rig_thread.join();
  ASSERT_TRUE(rig.got_close);
  EXPECT_EQ(rig.close.reason, CloseReason::Aborted);
  EXPECT_EQ(rig.wrenches, 3);
}
