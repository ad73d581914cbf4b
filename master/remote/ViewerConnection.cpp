#include "master/remote/ViewerConnection.h"

#include <exception>

namespace prism {
namespace {

constexpr uint64_t kNewsInFlight = 2;  // news sent and not yet acknowledged, at most

double since(ViewerConnection::Clock::time_point t) {
  return std::chrono::duration<double>(ViewerConnection::Clock::now() - t).count();
}

}  // namespace

void tryToSay(const Socket& socket, const std::vector<uint8_t>& message) {
  try {
    sendAll(socket, message, 0.2);
  } catch (const std::exception&) {
  }
}

ViewerConnection::ViewerConnection(Socket socket, MessageReader reader,
                                   std::vector<view::Message> early, std::string name)
    : socket_(std::move(socket)),
      reader_(std::move(reader)),
      early_(std::move(early)),
      name_(std::move(name)) {
  reader_.setLimits(view::kClientToServer);
}

bool ViewerConnection::mayTakeNews() const {
  return newsSent_ - newsAcknowledged_ < kNewsInFlight;
}

bool ViewerConnection::newsDue(const NewsState& news) const {
  return news.urgent || wantsWhole_ || (news.waiting && since(news.lastTake) >= kGatherSeconds);
}

bool ViewerConnection::wantsToWrite(const NewsState& news) const {
  // Writable matters only with something to write now: otherwise poll would return at once,
  // again and again, while the viewer has not acknowledged or the news is being gathered.
  return !out_.empty() || imageRequest_.has_value() || (mayTakeNews() && newsDue(news));
}

void ViewerConnection::tryToSay(const std::vector<uint8_t>& message) {
  prism::tryToSay(socket_, message);
}

std::string ViewerConnection::read(LiveSource& source, ViewSettings& current) {
  std::vector<view::Message> messages = std::move(early_);
  early_.clear();
  try {
    if (!reader_.readFrom(socket_, messages)) return "it closed the connection";
    for (const view::Message& m : messages) {
      lastHeard_ = Clock::now();
      switch (m.type) {
        case view::MessageType::SetView:
          current = view::decode<ViewSettings>(m);
          source.setView(current);
          break;
        case view::MessageType::FullImageRequest:
          imageRequest_ = view::decode<view::FullImageRequestMessage>(m).request;
          break;
        case view::MessageType::Ping:
          break;
        case view::MessageType::NewsReceived: {
          const uint64_t count = view::decode<view::NewsReceivedMessage>(m).count;
          if (count > newsSent_ || count < newsAcknowledged_) {
            throw wire::WireError("acknowledged news it was not sent");
          }
          newsAcknowledged_ = count;
          lastAcknowledged_ = Clock::now();
          break;
        }
        case view::MessageType::Bye:
          return "it said goodbye";
        default:
          throw wire::WireError(std::string("a viewer does not send ") +
                                view::messageTypeName(m.type));
      }
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

std::string ViewerConnection::write(LiveSource& source, NewsState& news, double timeoutSeconds) {
  try {
    if (out_.empty() && imageRequest_) {
      out_.put(view::encode(view::FullImageMessage{*imageRequest_, source.fullImage()}));
      imageRequest_.reset();
      lastProgress_ = Clock::now();
    }
    if (out_.empty() && mayTakeNews() && newsDue(news)) {
      // The newest news, merged since the last; taken only when the last has left and the
      // viewer has nearly caught up.
      out_.put(view::encode(source.take(wantsWhole_)));
      if (newsSent_ == newsAcknowledged_) lastAcknowledged_ = Clock::now();  // waiting from now
      ++newsSent_;
      wantsWhole_ = false;
      news = {false, false, Clock::now()};
      lastProgress_ = news.lastTake;
    }
    if (!mayTakeNews() && since(lastAcknowledged_) > timeoutSeconds) return "it stopped reading";
    if (!out_.empty()) {
      if (out_.writeTo(socket_) > 0) lastProgress_ = Clock::now();
      if (!out_.empty() && since(lastProgress_) > timeoutSeconds) return "it stopped reading";
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  if (since(lastHeard_) > timeoutSeconds) {
    return "silent for " + std::to_string(timeoutSeconds) + " s";
  }
  return "";
}

}  // namespace prism
