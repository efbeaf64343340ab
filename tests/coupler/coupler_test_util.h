// Helpers of the coupler tests: sample messages, a fake rig and a fake LIGGGHTS side that check
// every value that crosses the link, a transport that can be cut like a crashed process.
#pragma once

#include "coupler/coupling.h"
#include "coupler/protocol.h"
#include "coupler/transport.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <thread>

namespace wheelsim::coupler::test {

using namespace std::chrono_literals;

constexpr double kDt = 1e-5; ///< [s]

inline Hello sample_hello(std::int64_t start_step = 100, std::uint32_t every = 1) {
  Hello h;
  h.exchange_every = every;
  h.start_step = start_step;
  h.dt_s = kDt;
  h.p_WR_W = {0.10, 0.0, 0.144};
  h.p_WC_W = {0.10, 0.0, 0.144};
  const double half = 0.25; // rotation of 0.5 rad about y
  h.q_WB = {std::cos(half), 0.0, std::sin(half), 0.0};
  return h;
}

/// The state the fake rig reports for `step` after the wrench `w` (every field depends on both,
/// so a value swapped or lost in transit is seen).
inline WheelState rig_state(std::int64_t step, const Wrench &w) {
  WheelState s;
  const double angle = 1e-3 * static_cast<double>(step);
  s.p_WC_W = {0.1 + 1e-6 * static_cast<double>(step), w.f_C_W[1], 0.144 - 1e-3 * w.f_C_W[2]};
  s.q_WB = {std::cos(angle / 2), 0.0, std::sin(angle / 2), 0.0};
  s.v_WC_W = {w.t_C_W[0], w.t_C_W[1], static_cast<double>(w.n_contacts)};
  s.w_WB_W = {0.0, w.time_s, -w.t_C_W[2]};
  return s;
}

inline Wrench sample_wrench(std::int64_t step) {
  Wrench w;
  w.step = step;
  w.time_s = kDt * static_cast<double>(step);
  w.f_C_W = {1.5, -0.25 * static_cast<double>(step), 30.0 + 1e-3 * static_cast<double>(step)};
  w.t_C_W = {0.125, -2.0 - static_cast<double>(step % 7), 1e-9 * static_cast<double>(step)};
  w.n_contacts = 40 + step % 13;
  return w;
}

/// What the fake rig saw.
struct RigResult {
  Hello hello{};
  std::int64_t wrenches = 0;
  bool all_wrenches_match = true;
  Close close{};
  bool got_close = false;
};

/// Fake rig: accept, welcome with the client's pose, answer every wrench with rig_state.
/// `stop_after` >= 0: return after that many wrenches without answering the last one (caller then
/// cuts the link or lets the objects die).
inline RigResult run_fake_rig(CouplingServer &server, double dt_s, std::int64_t stop_after = -1) {
  RigResult result;
  result.hello = server.accept(dt_s);
  Welcome welcome;
  welcome.start_step = result.hello.start_step;
  welcome.dt_s = dt_s;
  welcome.state.p_WC_W = result.hello.p_WC_W;
  welcome.state.q_WB = result.hello.q_WB;
  welcome.state.v_WC_W = {0.01, 0.0, 0.0};
  server.welcome(welcome);
  for (;;) {
    auto message = server.receive();
    if (auto *close = std::get_if<Close>(&message)) {
      result.close = *close;
      result.got_close = true;
      return result;
    }
    const Wrench &w = std::get<Wrench>(message);
    const Wrench expected = sample_wrench(w.step);
    result.all_wrenches_match =
        result.all_wrenches_match && std::memcmp(&w, &expected, sizeof w) == 0;
    ++result.wrenches;
    if (stop_after >= 0 && result.wrenches >= stop_after) {
      return result;
    }
    server.send_pose(Pose{w.step + result.hello.exchange_every,
                          rig_state(w.step + result.hello.exchange_every, w)});
  }
}

/// Fake LIGGGHTS: connect, `exchanges` Wrench -> Pose round trips checking every Pose, close.
/// Returns the number of poses that matched rig_state exactly.
inline std::int64_t run_fake_liggghts(CouplingClient &client, const Hello &hello,
                                      std::int64_t exchanges, bool close_at_end = true) {
  const Welcome welcome = client.connect(hello);
  std::int64_t matches = 0;
  if (welcome.state.p_WC_W != hello.p_WC_W || welcome.state.q_WB != hello.q_WB) {
    return -1;
  }
  for (std::int64_t k = 0; k < exchanges; ++k) {
    const std::int64_t step = hello.start_step + k * hello.exchange_every;
    const Wrench w = sample_wrench(step);
    client.send_wrench(w);
    const Pose pose = client.receive_pose(step + hello.exchange_every);
    const WheelState expected = rig_state(step + hello.exchange_every, w);
    if (pose.step == step + hello.exchange_every &&
        std::memcmp(&pose.state, &expected, sizeof expected) == 0) {
      ++matches;
    }
  }
  if (close_at_end) {
    client.close(CloseReason::Finished, "finished");
  }
  return matches;
}

/// Runs `body` in a thread; join() rethrows what it threw.
class Background {
public:
  explicit Background(std::function<void()> body)
      : thread_([this, body = std::move(body)] {
          try {
            body();
          } catch (...) {
            error_ = std::current_exception();
          }
        }) {}
  ~Background() {
    if (thread_.joinable()) {
      thread_.join();
    }
  }
  void join() {
    thread_.join();
    if (error_) {
      std::rethrow_exception(error_);
    }
  }
  std::exception_ptr error() {
    if (thread_.joinable()) {
      thread_.join();
    }
    return error_;
  }

private:
  std::exception_ptr error_;
  std::thread thread_;
};

/// Forwards to `inner` until cut(); afterwards sends vanish and receives see nothing, as with a
/// process that was killed.
class CuttableTransport final : public Transport {
public:
  explicit CuttableTransport(std::unique_ptr<Transport> inner) : inner_(std::move(inner)) {}
  void cut() { cut_ = true; }
  void send(const Bytes &message) override {
    if (!cut_) {
      inner_->send(message);
    }
  }
  Bytes receive(std::chrono::milliseconds timeout, const std::string &awaiting) override {
    if (cut_) {
      std::this_thread::sleep_for(timeout);
      throw receive_timeout(awaiting, peer_name(), timeout);
    }
    return inner_->receive(timeout, awaiting);
  }
  std::string peer_name() const override { return inner_->peer_name(); }

private:
  std::unique_ptr<Transport> inner_;
  std::atomic<bool> cut_{false};
};

/// The exception `f` throws, as (type matched, message); fails the test if nothing is thrown.
template <typename Error, typename F> std::string message_of(F &&f) {
  try {
    f();
  } catch (const Error &e) {
    return e.what();
  }
  return "<no exception thrown>";
}

/// Milliseconds `f` took (exceptions pass through: wrap an expected one in message_of).
template <typename F> double elapsed_ms_of(F &&f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace wheelsim::coupler::test
