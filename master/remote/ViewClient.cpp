#include "master/remote/ViewClient.h"

#include <poll.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>

namespace prism {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kPingSeconds = 1.0;
constexpr int kPollMilliseconds = 100;

std::string defaultClientName() {
  char host[256] = "";
  ::gethostname(host, sizeof host - 1);
  const char* user = std::getenv("USER");
  return std::string("prism connect, ") + (user ? user : "someone") + "@" + host;
}

// Waits for at least one whole message, at most `seconds`; the messages that came with it
// are kept in `got` too.
void receiveSome(const Socket& socket, MessageReader& reader, std::vector<view::Message>& got,
                 double seconds) {
  const auto start = Clock::now();
  while (got.empty()) {
    const double left = seconds - std::chrono::duration<double>(Clock::now() - start).count();
    if (left <= 0) {
      throw std::runtime_error("the job did not answer within " + std::to_string(seconds) + " s");
    }
    pollfd p{socket.fd(), POLLIN, 0};
    ::poll(&p, 1, static_cast<int>(left * 1000) + 1);
    if (!reader.readFrom(socket, got) && got.empty()) {
      throw std::runtime_error("the job closed the connection without an answer");
    }
  }
}

}  // namespace

ViewClient::ViewClient(const ConnectionInfo& job, const ConnectOptions& options)
    : options_(options), reader_(view::kServerToClient), board_(1, 1) {
  if (job.protocol != 0 && job.protocol != view::kVersion) {
    throw std::runtime_error("the job speaks viewer protocol " + std::to_string(job.protocol) +
                             ", this Prism speaks " + std::to_string(view::kVersion) +
                             ": use the same Prism release on both sides");
  }
  socket_ = connectTcp(job.endpoint, options.connectSeconds);
  const std::string name = options.clientName.empty() ? defaultClientName() : options.clientName;
  sendAll(socket_, view::encode(view::HelloMessage{job.token, name}), options.connectSeconds);
  try {
    receiveSome(socket_, reader_, early_, options.connectSeconds);
  } catch (const wire::WireError& e) {
    throw std::runtime_error(std::string("the job's answer is not a viewer's: ") + e.what());
  }
  const view::Message answer = std::move(early_.front());
  early_.erase(early_.begin());  // news that came right behind it waits for run()
  if (answer.type == view::MessageType::Refused) {
    throw std::runtime_error("the job refused the connection: " +
                             view::decode<view::RefusedMessage>(answer).reason);
  }
  start_ = view::decode<view::WelcomeMessage>(answer).start;
  start_.sceneName += " · job at " + job.endpoint.text();
  // From now on no message may be larger than the frame's full-precision image (and a little).
  const size_t frameBytes = static_cast<size_t>(start_.width) * start_.height * 13 + (1 << 20);
  reader_.setLimits({frameBytes, frameBytes});
  start_.lightSpaceRefusal =
      "the caustic maps' light-space images are shown only beside the job (`prism view` there)";
  board_ = NewsBoard(start_.width, start_.height);
}

ViewClient::~ViewClient() {
  stop();
}

void ViewClient::send(const std::vector<uint8_t>& message) {
  std::lock_guard lock(sendMutex_);
  sendAll(socket_, message, options_.connectSeconds);
}

void ViewClient::setView(const ViewSettings& view) {
  try {
    send(view::encode(view));
  } catch (const std::exception&) {
    // The connection is going: run() reports it.
  }
}

void ViewClient::stop() {
  {
    std::lock_guard lock(mutex_);
    if (stopped_) return;
    stopped_ = true;
  }
  try {
    send(view::encode(view::ByeMessage{}));
  } catch (const std::exception&) {
  }
  changed_.notify_all();
}

void ViewClient::received(view::Message&& message, const NewsWake& wake) {
  switch (message.type) {
    case view::MessageType::News: {
      DisplayNews news = view::decode<DisplayNews>(message);
      send(view::encode(view::NewsReceivedMessage{++newsReceived_}));
      bool first;
      {
        std::lock_guard lock(mutex_);
        if (news.stats) stats_ = *news.stats;
        board_.post(std::move(news));
        first = !waiting_;
        waiting_ = true;
      }
      if (first) wake(true);  // the job chose when to send it
      break;
    }
    case view::MessageType::FullImage: {
      view::FullImageMessage image = view::decode<view::FullImageMessage>(message);
      if (image.image.width != start_.width || image.image.height != start_.height ||
          image.image.pixels.size() != static_cast<size_t>(start_.width) * start_.height) {
        throw wire::WireError("FullImage of another size than the frame");
      }
      std::lock_guard lock(mutex_);
      image_ = std::move(image);
      changed_.notify_all();
      break;
    }
    case view::MessageType::JobEnded: {
      std::lock_guard lock(mutex_);
      ended_ = "the job ended: " + view::decode<view::JobEndedMessage>(message).reason;
      break;
    }
    default:
      throw wire::WireError(std::string("a job does not send ") +
                            view::messageTypeName(message.type));
  }
}

std::string ViewClient::run(NewsWake wake) {
  auto lastPing = Clock::now();
  std::string why;
  std::vector<view::Message> messages = std::move(early_);
  for (;;) {
    {
      std::lock_guard lock(mutex_);
      if (stopped_) break;
      if (!ended_.empty()) {
        why = ended_;
        break;
      }
    }
    pollfd p{socket_.fd(), POLLIN, 0};
    if (messages.empty()) ::poll(&p, 1, kPollMilliseconds);
    bool open;
    try {
      open = reader_.readFrom(socket_, messages);
      for (view::Message& m : messages) {
        bytesReceived_ += view::kHeaderSize + m.payload.size();
        received(std::move(m), wake);
      }
      messages.clear();
    } catch (const std::exception& e) {
      why = std::string("the connection to the job failed: ") + e.what();
      break;
    }
    if (!open) {
      std::lock_guard lock(mutex_);
      why = !ended_.empty() ? ended_ : stopped_ ? "" : "the connection to the job was lost";
      break;
    }
    if (std::chrono::duration<double>(Clock::now() - lastPing).count() > kPingSeconds) {
      lastPing = Clock::now();
      try {
        send(view::encode(view::PingMessage{}));
      } catch (const std::exception& e) {
        why = std::string("the connection to the job was lost: ") + e.what();
        break;
      }
    }
  }
  {
    std::lock_guard lock(mutex_);
    if (ended_.empty()) ended_ = why.empty() ? "the viewer left" : why;
  }
  changed_.notify_all();
  return why;
}

DisplayNews ViewClient::take(bool whole) {
  std::lock_guard lock(mutex_);
  waiting_ = false;
  return board_.take(whole);
}

ImageRgb ViewClient::fullImage() {
  uint32_t request;
  {
    std::lock_guard lock(mutex_);
    request = nextRequest_++;
    image_.reset();
  }
  send(view::encode(view::FullImageRequestMessage{request}));
  std::unique_lock lock(mutex_);
  const bool arrived =
      changed_.wait_for(lock, std::chrono::duration<double>(options_.requestSeconds),
                        [&] { return (image_ && image_->request == request) || !ended_.empty(); });
  if (!arrived || !image_ || image_->request != request) {
    throw std::runtime_error(
        "no full-precision image from the job" +
        (ended_.empty() ? std::string(" within the time allowed") : ": " + ended_));
  }
  return std::move(image_->image);
}

LiveStats ViewClient::stats() {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::shared_ptr<const CausticMapEstimator> ViewClient::causticMaps(bool) {
  throw std::runtime_error(start_.lightSpaceRefusal);
}

}  // namespace prism
