// The job's side of the one viewer connected to it (ViewServer): what it sent and what the viewer
// acknowledged, its messages handled, and what goes out to it: the newest news when it is due and
// the viewer has nearly caught up, a full-precision image when asked for (one at most waiting),
// never a queue. Single-threaded: the server's poll loop calls it.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "master/live/LiveSource.h"
#include "master/remote/Socket.h"

namespace prism {

class ViewerConnection {
 public:
  using Clock = std::chrono::steady_clock;

  // A connection past its Hello: its socket, its reader (which may hold a message half read)
  // and the messages that came behind the Hello.
  ViewerConnection(Socket socket, MessageReader reader, std::vector<view::Message> early,
                   std::string name);

  const std::string& name() const { return name_; }
  int fd() const { return socket_.fd(); }

  // What the viewer's news waits for: whether news is due (urgent, or gathered long enough),
  // and whether the viewer has acknowledged enough to be sent more.
  struct NewsState {
    bool waiting = false;  // news is on the source's board
    bool urgent = false;   // some of it is urgent
    Clock::time_point lastTake;
  };
  bool mayTakeNews() const;
  bool newsDue(const NewsState& news) const;
  // Whether the poll should wait for the socket to take bytes.
  bool wantsToWrite(const NewsState& news) const;

  // Handles what the viewer sent (views go to the source, `current` follows them). Returns why
  // the viewer is gone ("" while it stays): it closed, said goodbye, or broke the protocol.
  std::string read(LiveSource& source, ViewSettings& current);
  // Sends what is due; `news` is reset when news was taken. Returns why the viewer must be
  // dropped ("" while it stays): it stopped reading or acknowledging, or is silent.
  std::string write(LiveSource& source, NewsState& news, double timeoutSeconds);
  // Queues a message (the Welcome) before anything else.
  void queue(std::vector<uint8_t> message) { out_.put(std::move(message)); }
  // Says a last word without waiting for the viewer to read it.
  void tryToSay(const std::vector<uint8_t>& message);

  // Gathering: news that is not urgent waits this long after the last take.
  static constexpr double kGatherSeconds = 1.0 / 60;

 private:
  Socket socket_;
  MessageReader reader_;
  std::vector<view::Message> early_;  // read with the Hello, not yet handled
  std::string name_;
  OutBuffer out_;
  Clock::time_point lastHeard_ = Clock::now();
  Clock::time_point lastProgress_ = Clock::now();  // of writing, while out_ was not empty
  bool wantsWhole_ = true;                         // the next news has every pixel
  // The last full-precision image asked for while another message was still going out.
  std::optional<uint32_t> imageRequest_;
  uint64_t newsSent_ = 0;
  uint64_t newsAcknowledged_ = 0;
  Clock::time_point lastAcknowledged_ = Clock::now();
};

// Sends message to a socket that is being dropped, without waiting for it.
void tryToSay(const Socket& socket, const std::vector<uint8_t>& message);

}  // namespace prism
