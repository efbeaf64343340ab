// The in-process loopback transport and the transports' shared message helpers.
#include "coupler/transport.h"

#include <condition_variable>
#include <deque>
#include <mutex>

namespace wheelsim::coupler {

std::string format_duration(std::chrono::milliseconds duration) {
  return format_number(static_cast<double>(duration.count()) / 1000.0) + " s";
}

TimeoutError receive_timeout(const std::string &awaiting, const std::string &peer,
                             std::chrono::milliseconds timeout) {
  return TimeoutError("no " + awaiting + " from " + peer + " within " + format_duration(timeout));
}

namespace {

/// The two directions of one loopback link.
struct LoopbackLink {
  std::mutex mutex;
  std::condition_variable arrived;
  std::deque<Bytes> queue[2]; ///< queue[i]: messages for end i
};

class LoopbackTransport final : public Transport {
public:
  LoopbackTransport(std::shared_ptr<LoopbackLink> link, int end, std::string peer)
      : link_(std::move(link)), end_(end), peer_(std::move(peer)) {}

  void send(const Bytes &message) override {
    {
      std::lock_guard<std::mutex> lock(link_->mutex);
      link_->queue[1 - end_].push_back(message);
    }
    link_->arrived.notify_all();
  }

  Bytes receive(std::chrono::milliseconds timeout, const std::string &awaiting) override {
    std::unique_lock<std::mutex> lock(link_->mutex);
    auto &queue = link_->queue[end_];
    if (!link_->arrived.wait_for(lock, timeout, [&] { return !queue.empty(); })) {
      throw receive_timeout(awaiting, peer_, timeout);
    }
    Bytes message = std::move(queue.front());
    queue.pop_front();
    return message;
  }

  std::string peer_name() const override { return peer_; }

private:
  std::shared_ptr<LoopbackLink> link_;
  int end_;
  std::string peer_;
};

} // namespace

std::pair<std::unique_ptr<Transport>, std::unique_ptr<Transport>>
make_loopback_pair(const std::string &first_peer_name, const std::string &second_peer_name) {
  auto link = std::make_shared<LoopbackLink>();
  return {std::make_unique<LoopbackTransport>(link, 0, first_peer_name),
          std::make_unique<LoopbackTransport>(link, 1, second_peer_name)};
}

} // namespace wheelsim::coupler
