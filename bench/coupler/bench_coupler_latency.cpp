// bench-coupler-latency: round-trip time of one Wrench -> Pose exchange through the full coupler
// stack (CouplingClient/CouplingServer: encode, validate, ZeroMQ PAIR, decode) over ipc:// and
// tcp://127.0.0.1, the client (LIGGGHTS side) and the server (rig side, answering at once) in two
// processes (fork; or two threads with --threads). Prints median and p99 and their ratio to the
// issue's target (<= 30 µs per exchange). A benchmark, not a test: it prints, it does not judge.
#include "coupler/coupling.h"
#include "coupler/transport.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

using namespace wheelsim::coupler;

namespace {

constexpr double kTargetUs = 30.0;
constexpr double kDt = 1e-5; // [s]; any value, both sides agree

/// The rig side: accepts, then answers every Wrench with a Pose at once.
void serve(std::unique_ptr<Transport> transport) {
  CouplingServer server(std::move(transport));
  const Hello hello = server.accept(kDt);
  Welcome welcome;
  welcome.start_step = hello.start_step;
  welcome.dt_s = kDt;
  welcome.state.p_WC_W = hello.p_WC_W;
  welcome.state.q_WB = hello.q_WB;
  server.welcome(welcome);
  Pose pose;
  pose.state = welcome.state;
  for (;;) {
    auto message = server.receive();
    if (std::holds_alternative<Close>(message)) {
      return;
    }
    const Wrench &w = std::get<Wrench>(message);
    pose.step = w.step + hello.exchange_every;
    pose.state.v_WC_W = {1e-3 * w.f_C_W[0], 0.0, 0.0};
    server.send_pose(pose);
  }
}

/// The LIGGGHTS side: warm-up, then `n` timed exchanges; returns their durations [µs].
std::vector<double> drive(std::unique_ptr<Transport> transport, long warmup, long n) {
  CouplingClient client(std::move(transport));
  Hello hello;
  hello.dt_s = kDt;
  hello.p_WR_W = hello.p_WC_W = {0.1, 0.0, 0.144};
  client.connect(hello);
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(n));
  Wrench w;
  w.f_C_W = {1.0, 0.0, 30.0};
  w.n_contacts = 40;
  for (long k = 0; k < warmup + n; ++k) {
    w.step = k;
    w.time_s = kDt * static_cast<double>(k);
    const auto t0 = std::chrono::steady_clock::now();
    client.send_wrench(w);
    (void)client.receive_pose(k + 1);
    const auto t1 = std::chrono::steady_clock::now();
    if (k >= warmup) {
      us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
  }
  client.close();
  return us;
}

/// One measurement: server in a child process (or a thread), client here.
std::vector<double> measure(const std::string &bind_endpoint, bool threads, long warmup, long n) {
  if (threads) {
    auto server_transport = ZmqTransport::bind(bind_endpoint);
    const std::string endpoint = server_transport->endpoint();
    std::thread rig([t = std::move(server_transport)]() mutable { serve(std::move(t)); });
    auto us = drive(ZmqTransport::connect(endpoint), warmup, n);
    rig.join();
    return us;
  }
  // Fork before this process creates any ZeroMQ context; the child reports the bound endpoint
  // (a tcp "*" port resolved) through a pipe.
  int fds[2];
  if (::pipe(fds) != 0) {
    throw std::runtime_error("pipe failed");
  }
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    int status = 0;
    try {
      auto transport = ZmqTransport::bind(bind_endpoint);
      const std::string endpoint = transport->endpoint() + "\n";
      if (::write(fds[1], endpoint.data(), endpoint.size()) < 0) {
        std::_Exit(2);
      }
      ::close(fds[1]);
      serve(std::move(transport));
    } catch (const std::exception &e) {
      std::fprintf(stderr, "bench-coupler-latency (rig process): %s\n", e.what());
      status = 1;
    }
    std::_Exit(status);
  }
  ::close(fds[1]);
  std::string endpoint;
  char c = 0;
  while (::read(fds[0], &c, 1) == 1 && c != '\n') {
    endpoint.push_back(c);
  }
  ::close(fds[0]);
  if (endpoint.empty()) {
    ::waitpid(pid, nullptr, 0);
    throw std::runtime_error("the rig process could not bind " + bind_endpoint);
  }
  auto us = drive(ZmqTransport::connect(endpoint), warmup, n);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("the rig process failed");
  }
  return us;
}

double percentile(std::vector<double> sorted, double p) {
  const double pos = p * static_cast<double>(sorted.size() - 1);
  const auto i = static_cast<std::size_t>(pos);
  const double frac = pos - static_cast<double>(i);
  return i + 1 < sorted.size() ? sorted[i] * (1 - frac) + sorted[i + 1] * frac : sorted[i];
}

} // namespace

int main(int argc, char **argv) {
  CLI::App app{"Round-trip latency of one coupler Wrench -> Pose exchange (target <= 30 µs)"};
  long n = 100000;
  long warmup = 10000;
  bool threads = false;
  std::vector<std::string> transports{"ipc", "tcp"};
  app.add_option("-n,--exchanges", n, "timed exchanges per transport")->check(CLI::PositiveNumber);
  app.add_option("--warmup", warmup, "untimed exchanges first")->check(CLI::NonNegativeNumber);
  app.add_flag("--threads", threads,
               "client and server in two threads of one process "
               "(default: two processes)");
  app.add_option("--transport", transports, "ipc and/or tcp")->check(CLI::IsMember({"ipc", "tcp"}));
  CLI11_PARSE(app, argc, argv);

  try {
    char dir_pattern[] = "/tmp/wheelsim-bench-XXXXXX";
    if (::mkdtemp(dir_pattern) == nullptr) {
      throw std::runtime_error("mkdtemp failed");
    }
    const std::string dir = dir_pattern;
    std::printf("coupler round trip (Wrench -> Pose, full client/server stack), %s, "
                "%ld exchanges after %ld warm-up; target <= %.0f µs\n",
                threads ? "two threads" : "two processes", n, warmup, kTargetUs);
    std::printf("%-28s %10s %10s %10s %14s %14s\n", "transport", "median µs", "p99 µs", "max µs",
                "median/target", "p99/target");
    for (const std::string &transport : transports) {
      const std::string endpoint =
          transport == "ipc" ? "ipc://" + dir + "/rig.sock" : "tcp://127.0.0.1:*";
      std::vector<double> us = measure(endpoint, threads, warmup, n);
      std::sort(us.begin(), us.end());
      const double median = percentile(us, 0.5);
      const double p99 = percentile(us, 0.99);
      std::printf("%-28s %10.1f %10.1f %10.1f %14.2f %14.2f\n",
                  (transport + (transport == "ipc" ? " (ipc://)" : " (tcp://127.0.0.1)")).c_str(),
                  median, p99, us.back(), median / kTargetUs, p99 / kTargetUs);
    }
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "bench-coupler-latency: %s\n", e.what());
    return 1;
  }
  return 0;
}
