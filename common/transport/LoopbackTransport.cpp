#include "transport/LoopbackTransport.h"

#include <chrono>
#include <string>

namespace prism {

class LoopbackNetwork::Endpoint final : public Transport {
 public:
  Endpoint(LoopbackNetwork& network, int rank) : network_(network), rank_(rank) {}

  int rank() const override { return rank_; }
  int size() const override { return network_.size(); }
  int ranksOnThisNode() const override { return network_.size(); }  // threads of one process

  void broadcast(std::vector<uint8_t>& bytes, double timeoutSeconds) override {
    std::unique_lock<std::mutex> lock(network_.mutex_);
    if (rank_ == 0) {
      network_.broadcasts_.push_back(bytes);
      ++broadcastsTaken_;
      network_.changed_.notify_all();
      return;
    }
    const bool arrived = network_.changed_.wait_for(
        lock, std::chrono::duration<double>(timeoutSeconds),
        [this] { return network_.broadcasts_.size() > broadcastsTaken_; });
    if (!arrived) {
      throw TransportError("no scene from rank 0 within " + std::to_string(timeoutSeconds) + " s");
    }
    bytes = network_.broadcasts_[broadcastsTaken_++];
  }

  bool send(int dest, std::vector<uint8_t> bytes) override {
    return network_.deliver(rank_, dest, std::move(bytes));
  }
  size_t progressSends() override { return 0; }  // delivery is immediate

  std::optional<IncomingMessage> poll() override { return network_.take(rank_, 0.0); }
  std::optional<IncomingMessage> waitForMessage(double timeoutSeconds) override {
    return network_.take(rank_, timeoutSeconds);
  }
  void awaitActivity(double timeoutSeconds) override { network_.await(rank_, timeoutSeconds); }
  void wake() override { network_.wake(rank_); }
  bool wakesOnMessage() const override { return true; }  // a condition variable

  [[noreturn]] void abortJob(int exitCode) override {
    throw TransportError("job aborted by rank " + std::to_string(rank_) + " with exit code " +
                         std::to_string(exitCode));
  }

 private:
  LoopbackNetwork& network_;
  int rank_;
  size_t broadcastsTaken_ = 0;  // guarded by the network's mutex
};

LoopbackNetwork::LoopbackNetwork(int ranks) : mailboxes_(static_cast<size_t>(ranks)) {
  for (int r = 0; r < ranks; ++r) endpoints_.push_back(std::make_unique<Endpoint>(*this, r));
}

LoopbackNetwork::~LoopbackNetwork() = default;

Transport& LoopbackNetwork::endpoint(int rank) {
  return *endpoints_.at(static_cast<size_t>(rank));
}

void LoopbackNetwork::disconnect(int rank) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    Mailbox& box = mailboxes_.at(static_cast<size_t>(rank));
    box.connected = false;
    box.messages.clear();
  }
  changed_.notify_all();
}

bool LoopbackNetwork::connected(int rank) {
  const std::lock_guard<std::mutex> lock(mutex_);
  return mailboxes_.at(static_cast<size_t>(rank)).connected;
}

size_t LoopbackNetwork::deliveredTo(int rank) {
  const std::lock_guard<std::mutex> lock(mutex_);
  return mailboxes_.at(static_cast<size_t>(rank)).delivered;
}

bool LoopbackNetwork::deliver(int source, int dest, std::vector<uint8_t> bytes) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (dest < 0 || dest >= size()) {
      throw TransportError("send to rank " + std::to_string(dest) + " of " +
                           std::to_string(size()));
    }
    Mailbox& box = mailboxes_[static_cast<size_t>(dest)];
    if (!box.connected || !mailboxes_[static_cast<size_t>(source)].connected) return false;
    box.messages.push_back({source, std::move(bytes)});
    ++box.delivered;
  }
  changed_.notify_all();
  return true;
}

void LoopbackNetwork::wake(int rank) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    mailboxes_.at(static_cast<size_t>(rank)).woken = true;
  }
  changed_.notify_all();
}

void LoopbackNetwork::await(int rank, double timeoutSeconds) {
  std::unique_lock<std::mutex> lock(mutex_);
  Mailbox& box = mailboxes_.at(static_cast<size_t>(rank));
  changed_.wait_for(lock, std::chrono::duration<double>(timeoutSeconds),
                    [&box] { return !box.messages.empty() || box.woken; });
  box.woken = false;
}

std::optional<IncomingMessage> LoopbackNetwork::take(int rank, double timeoutSeconds) {
  std::unique_lock<std::mutex> lock(mutex_);
  Mailbox& box = mailboxes_.at(static_cast<size_t>(rank));
  changed_.wait_for(lock, std::chrono::duration<double>(timeoutSeconds),
                    [&box] { return !box.messages.empty() || box.woken; });
  if (timeoutSeconds > 0.0) box.woken = false;  // a wait heard it; poll() leaves it for one
  if (box.messages.empty()) return std::nullopt;
  IncomingMessage message = std::move(box.messages.front());
  box.messages.pop_front();
  return message;
}

}  // namespace prism
