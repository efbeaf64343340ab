// The ZeroMQ transport: round trips over ipc:// and tcp://127.0.0.1 (client and server in two
// threads), timeouts naming the peer, a peer process killed mid-run (fork + SIGKILL), endpoint
// rules (loopback default, warning for other addresses), closing that never hangs.
#include "coupler_test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sys/wait.h>
#include <unistd.h>

using namespace wheelsim::coupler;
using namespace wheelsim::coupler::test;
using ::testing::HasSubstr;

namespace {

constexpr Timeouts kShort{500ms, 500ms};
constexpr double kMarginMs = 500.0;

/// A fresh temporary directory for ipc socket files, removed at the end of the test.
class IpcDir {
public:
  IpcDir() {
    char pattern[] = "/tmp/wheelsim-coupler-XXXXXX";
    if (::mkdtemp(pattern) == nullptr) {
      throw std::runtime_error("mkdtemp failed");
    }
    path_ = pattern;
  }
  ~IpcDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::string endpoint(const std::string &name) const { return "ipc://" + path_ + "/" + name; }

private:
  std::string path_;
};

void round_trip(const std::string &bind_endpoint) {
  auto server_transport = ZmqTransport::bind(bind_endpoint);
  const std::string endpoint = server_transport->endpoint();
  CouplingServer server(std::move(server_transport), kShort);
  RigResult rig;
  Background rig_thread([&] { rig = run_fake_rig(server, kDt); });
  CouplingClient client(ZmqTransport::connect(endpoint), kShort);
  EXPECT_EQ(run_fake_liggghts(client, sample_hello(0, 1), 1000), 1000);
  rig_thread.join();
  EXPECT_EQ(rig.wrenches, 1000);
  EXPECT_TRUE(rig.all_wrenches_match);
  ASSERT_TRUE(rig.got_close);
  EXPECT_EQ(rig.close.reason, CloseReason::Finished);
}

/// Runs `child` in a forked process; `child` ends with die(), which kills the process with
/// SIGKILL while its objects are alive (no destructor, no Close: a crashed peer). An exception
/// exits with status 3. Call before this process opens its own ZeroMQ sockets.
pid_t fork_child(const std::function<void()> &child) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    try {
      child();
    } catch (...) {
      std::_Exit(3);
    }
    std::_Exit(4); // child() did not call die()
  }
  return pid;
}

void die() {
  ::raise(SIGKILL);
  std::_Exit(5);
}

int wait_for(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFSIGNALED(status) ? WTERMSIG(status) : -WEXITSTATUS(status);
}

} // namespace

TEST(CouplerZmq, RoundTripIpc) {
  IpcDir dir;
  round_trip(dir.endpoint("rig.sock"));
}

TEST(CouplerZmq, RoundTripTcpLoopbackAnyPort) {
  auto probe = ZmqTransport::bind("tcp://127.0.0.1:*");
  EXPECT_THAT(probe->endpoint(), ::testing::MatchesRegex("tcp://127\\.0\\.0\\.1:[0-9]+"));
  probe.reset();
  round_trip("tcp://127.0.0.1:*");
}

TEST(CouplerZmq, RoundTripTcpDefaultsToLoopback) {
  auto t = ZmqTransport::bind("tcp://:*");
  EXPECT_THAT(t->endpoint(), HasSubstr("tcp://127.0.0.1:"));
  auto l = ZmqTransport::bind("tcp://localhost:*");
  EXPECT_THAT(l->endpoint(), HasSubstr("tcp://127.0.0.1:"));
}

TEST(CouplerZmq, TimeoutLongerThanAnIntOfMillisecondsStillReceives) {
  // ZMQ_RCVTIMEO is an int of ms: 30 days (2.6e9 ms) used to wrap to a negative value, which
  // ZeroMQ refuses (EINVAL, thrown without the peer's name); now it is waited in pieces.
  IpcDir dir;
  auto server = ZmqTransport::bind(dir.endpoint("long.sock"));
  auto client = ZmqTransport::connect(server->endpoint());
  const std::vector<std::uint8_t> sent{1, 2, 3};
  client->send(sent);
  const auto thirty_days = std::chrono::milliseconds(30LL * 24 * 3600 * 1000);
  ASSERT_GT(thirty_days.count(), std::numeric_limits<int>::max());
  EXPECT_EQ(server->receive(thirty_days, "a message"), sent);
}

TEST(CouplerZmq, SilentServerTimesOutNamingEndpoint) {
  IpcDir dir;
  const std::string endpoint = dir.endpoint("nobody.sock");
  CouplingClient client(ZmqTransport::connect(endpoint), kShort);
  std::string m;
  const double ms = elapsed_ms_of(
      [&] { m = message_of<TimeoutError>([&] { client.connect(sample_hello(7)); }); });
  EXPECT_EQ(m, "no Welcome (reply to Hello for start step 7) from the rig (" + endpoint +
                   ") within 0.5 s");
  EXPECT_GE(ms, 500.0);
  EXPECT_LE(ms, 500.0 + kMarginMs);
}

TEST(CouplerZmq, SilentClientTimesOutNamingEndpoint) {
  auto transport = ZmqTransport::bind("tcp://127.0.0.1:*");
  const std::string endpoint = transport->endpoint();
  CouplingServer server(std::move(transport), kShort);
  std::string m;
  const double ms =
      elapsed_ms_of([&] { m = message_of<TimeoutError>([&] { server.accept(kDt); }); });
  EXPECT_EQ(m, "no Hello from LIGGGHTS (" + endpoint + ") within 0.5 s");
  EXPECT_GE(ms, 500.0);
  EXPECT_LE(ms, 500.0 + kMarginMs);
}

TEST(CouplerZmq, KilledRigIsATimeoutOnTheClient) {
  IpcDir dir;
  const std::string endpoint = dir.endpoint("rig.sock");
  const pid_t rig = fork_child([&] {
    CouplingServer server(ZmqTransport::bind(endpoint), Timeouts{5s, 5s});
    run_fake_rig(server, kDt, 5); // answers 4 wrenches, then dies on the 5th
    die();
  });
  ASSERT_GT(rig, 0);
  CouplingClient client(ZmqTransport::connect(endpoint), Timeouts{5s, 500ms});
  std::string m;
  double ms = 0;
  std::int64_t matched = 0;
  try {
    client.connect(sample_hello(100));
    for (std::int64_t step = 100;; ++step) {
      client.send_wrench(sample_wrench(step));
      ms = elapsed_ms_of(
          [&] { m = message_of<TimeoutError>([&] { client.receive_pose(step + 1); }); });
      if (m.find("<no exception") == std::string::npos) {
        break;
      }
      ++matched;
    }
  } catch (...) {
    (void)wait_for(rig);
    throw;
  }
  EXPECT_EQ(wait_for(rig), SIGKILL);
  EXPECT_EQ(matched, 4);
  EXPECT_EQ(m, "no Pose for step 105 from the rig (" + endpoint + ") within 0.5 s");
  EXPECT_LE(ms, 500.0 + kMarginMs);
}

TEST(CouplerZmq, KilledLiggghtsIsATimeoutOnTheRig) {
  IpcDir dir;
  const std::string endpoint = dir.endpoint("rig.sock");
  const pid_t liggghts = fork_child([&] {
    CouplingClient client(ZmqTransport::connect(endpoint), Timeouts{5s, 5s});
    run_fake_liggghts(client, sample_hello(100, 3), 6, false);
    die();
  });
  ASSERT_GT(liggghts, 0);
  auto transport = ZmqTransport::bind(endpoint);
  CouplingServer server(std::move(transport), Timeouts{5s, 500ms});
  std::string m;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    m = message_of<TimeoutError>([&] { run_fake_rig(server, kDt); });
  } catch (...) {
    (void)wait_for(liggghts);
    throw;
  }
  const auto total = std::chrono::steady_clock::now() - t0;
  EXPECT_EQ(wait_for(liggghts), SIGKILL);
  EXPECT_EQ(m, "no Wrench for step 118 from LIGGGHTS (" + endpoint + ") within 0.5 s");
  // The whole run (6 exchanges, then the timeout) ends within the handshake and step timeouts;
  // the Close the rig sends its dead peer costs nothing.
  const double total_ms = std::chrono::duration<double, std::milli>(total).count();
  EXPECT_LE(total_ms, 5000.0 + 500.0 + kMarginMs);
}

TEST(CouplerZmq, NonLoopbackBindWarns) {
  testing::internal::CaptureStderr();
  auto loopback = ZmqTransport::bind("tcp://127.0.0.1:*");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  testing::internal::CaptureStderr();
  auto any = ZmqTransport::bind("tcp://0.0.0.0:*");
  const std::string warning = testing::internal::GetCapturedStderr();
  EXPECT_THAT(warning, HasSubstr("warning: binding tcp://0.0.0.0:*, which is not a loopback"));
  EXPECT_THAT(warning, HasSubstr("use tcp://127.0.0.1:PORT or ipc://"));
}

TEST(CouplerZmq, BadEndpointsAreExplained) {
  EXPECT_THAT(message_of<CouplingError>([] { ZmqTransport::bind("udp://127.0.0.1:5555"); }),
              HasSubstr("\"udp://127.0.0.1:5555\": unsupported transport; write ipc://"));
  EXPECT_THAT(message_of<CouplingError>([] { ZmqTransport::connect("tcp://127.0.0.1:*"); }),
              HasSubstr("port \"*\" must be a number 1..65535"));
  EXPECT_THAT(message_of<CouplingError>([] { ZmqTransport::bind("tcp://127.0.0.1:70000"); }),
              HasSubstr("port \"70000\" must be a number 1..65535 or * (any free port)"));
  EXPECT_THAT(message_of<CouplingError>([] { ZmqTransport::bind("tcp://127.0.0.1"); }),
              HasSubstr("no port"));
  EXPECT_THAT(message_of<CouplingError>(
                  [] { ZmqTransport::bind("ipc:///nonexistent-wheelsim-dir/rig.sock"); }),
              HasSubstr("directory \"/nonexistent-wheelsim-dir/\" does not exist"));
  const std::string long_path = "ipc:///tmp/" + std::string(120, 'x');
  EXPECT_THAT(message_of<CouplingError>([&] { ZmqTransport::connect(long_path); }),
              HasSubstr("at most 107"));
}

TEST(CouplerZmq, PortInUseIsExplained) {
  auto first = ZmqTransport::bind("tcp://127.0.0.1:*");
  const std::string endpoint = first->endpoint();
  EXPECT_THAT(message_of<CouplingError>([&] { ZmqTransport::bind(endpoint); }),
              HasSubstr("cannot bind the coupling endpoint " + endpoint));
}

TEST(CouplerZmq, ClosingNeverHangsOnAMissingPeer) {
  IpcDir dir;
  const double ms = elapsed_ms_of([&] {
    auto client = ZmqTransport::connect(dir.endpoint("nobody.sock"));
    client->send(encode(sample_hello())); // queued for a server that never comes
  });                                     // destroyed here: waits at most the linger
  EXPECT_LE(ms, 200.0 + kMarginMs);

  auto server = ZmqTransport::bind(dir.endpoint("rig.sock"), "LIGGGHTS", ZmqOptions{200ms, 200ms});
  std::string m;
  const double send_ms = elapsed_ms_of(
      [&] { m = message_of<TimeoutError>([&] { server->send(encode(sample_wrench(1))); }); });
  EXPECT_THAT(m, HasSubstr("could not hand a message to LIGGGHTS (" + dir.endpoint("rig.sock") +
                           ") within 0.2 s: no peer connected"));
  EXPECT_GE(send_ms, 200.0);
  EXPECT_LE(send_ms, 200.0 + kMarginMs);
  const double nowait_ms =
      elapsed_ms_of([&] { EXPECT_FALSE(server->send_nowait(encode(sample_wrench(1)))); });
  EXPECT_LE(nowait_ms, 50.0);
}
