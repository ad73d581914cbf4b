#include "master/remote/ViewServer.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <memory>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "master/remote/AccessToken.h"
#include "master/remote/ConnectionFile.h"
#include "util/InterruptSignal.h"

namespace prism {
namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kMaxPending = 16;                // connections not yet past their Hello
constexpr view::Limits kHelloLimits{4096, 4096};  // a Hello is a token and a name
constexpr int kPollMilliseconds = 100;            // how often interrupts and deadlines are checked
constexpr size_t kLoggedRefusals = 5;             // refusals named in the log; the rest counted
constexpr uint64_t kNewsInFlight = 2;             // news sent and not yet acknowledged, at most
// News that is not urgent (tiles handed out or finished, statistics) is gathered this long
// before it is sent: a 60 Hz display shows no more, and each message costs both ends a wake-up
// that preempts a render thread.
constexpr double kGatherSeconds = 1.0 / 60;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The source's wake() from the coordinator thread: one byte into a pipe the poll loop watches,
// 'u' for urgent news.
class WakePipe {
 public:
  WakePipe() {
    if (::pipe2(fds_, O_NONBLOCK | O_CLOEXEC) != 0) {
      throw std::runtime_error("cannot make the server's wake-up pipe");
    }
  }
  ~WakePipe() {
    ::close(fds_[0]);
    ::close(fds_[1]);
  }
  void wake(bool urgent) {
    const char byte = urgent ? 'u' : 'n';
    [[maybe_unused]] const ssize_t n = ::write(fds_[1], &byte, 1);  // full: a wake is pending
  }
  struct Woken {
    bool any = false;
    bool urgent = false;
  };
  // Empties the pipe; says whether anything, and anything urgent, was in it.
  Woken drain() {
    char buffer[64];
    Woken woken;
    ssize_t n;
    while ((n = ::read(fds_[0], buffer, sizeof buffer)) > 0) {
      woken.any = true;
      for (ssize_t i = 0; i < n; ++i) woken.urgent = woken.urgent || buffer[i] == 'u';
    }
    return woken;
  }
  int fd() const { return fds_[0]; }

 private:
  int fds_[2];
};

// Answers a connection that is being dropped, without waiting for it.
void tryToSay(const Socket& socket, const std::vector<uint8_t>& message) {
  try {
    sendAll(socket, message, 0.2);
  } catch (const std::exception&) {
  }
}

}  // namespace

struct ViewServer::Pending {
  Socket socket;
  MessageReader reader{kHelloLimits};
  Clock::time_point since = Clock::now();
};

struct ViewServer::Client {
  Socket socket;
  MessageReader reader{view::kClientToServer};
  std::vector<view::Message> early;  // read with the Hello, not yet handled
  OutBuffer out;
  Clock::time_point lastHeard = Clock::now();
  Clock::time_point lastProgress = Clock::now();  // of writing, while out was not empty
  bool wantsWhole = true;                         // the next news has every pixel
  // The last full-precision image asked for while another message was still going out: one
  // is sent when that has left, so however often a viewer asks, one image at most waits.
  std::optional<uint32_t> imageRequest;
  uint64_t newsSent = 0;
  uint64_t newsAcknowledged = 0;
  Clock::time_point lastAcknowledged = Clock::now();
  std::string name;
};

ViewServer::ViewServer(LiveSource& source, const ServeOptions& options, std::ostream& log)
    : source_(source), options_(options), log_(log) {
  const Endpoint asked = parseEndpoint(options.address);
  if (!isLoopbackHost(asked.host) && !options.allowNetwork) {
    throw std::runtime_error(
        "--serve " + options.address +
        " would listen beyond this machine: add --allow-network to mean it (anyone who reaches "
        "the port may try the token), or serve on 127.0.0.1 and reach it through `ssh -L`");
  }
  listener_ = listenTcp(asked, &endpoint_);
  token_ = newAccessToken();
  if (!options.connectionFile.empty()) {
    writeConnectionFile(options.connectionFile, {endpoint_, token_, view::kVersion});
  }
}

std::string ViewServer::run() {
  WakePipe wakePipe;
  std::atomic<bool> finished{false};
  std::exception_ptr failure;
  std::string endedBy;
  std::thread coordinator([&] {
    try {
      endedBy = source_.run([&wakePipe](bool urgent) { wakePipe.wake(urgent); });
    } catch (...) {
      failure = std::current_exception();
    }
    finished = true;
    wakePipe.wake(true);
  });
  ViewSettings current = source_.start().view;
  source_.setView(current);  // renders without a viewer: a viewer that comes finds the passes

  log_ << "serving    " << endpoint_.text()
       << (options_.connectionFile.empty() ? "" : ", connection file " + options_.connectionFile)
       << "\n";
  log_.flush();

  std::vector<std::unique_ptr<Pending>> pending;
  std::unique_ptr<Client> client;
  bool newsWaiting = false;
  bool urgentWaiting = false;
  Clock::time_point lastTake = Clock::now();
  std::string reason;
  const auto refuse = [&](const Socket& socket, const std::string& why) {
    tryToSay(socket, view::encode(view::RefusedMessage{why}));
    if (refused_++ < kLoggedRefusals) log_ << "refused    a connection: " << why << "\n";
  };
  const auto dropClient = [&](const std::string& why) {
    log_ << "viewer     " << client->name << " left: " << why << "\n";
    log_.flush();
    client.reset();
    if (options_.exitWithClient) reason = "the viewer left (--exit-with-client)";
  };

  while (reason.empty()) {
    std::vector<pollfd> fds{{listener_.fd(), POLLIN, 0}, {wakePipe.fd(), POLLIN, 0}};
    for (const auto& p : pending) fds.push_back({p->socket.fd(), POLLIN, 0});
    int timeout = kPollMilliseconds;
    if (client) {
      // Writable matters only with bytes to write, or news it may take now (else poll would
      // return at once, again and again, while the viewer has not acknowledged or the news is
      // still being gathered).
      const bool mayTake = client->newsSent - client->newsAcknowledged < kNewsInFlight;
      const double gathered = since(lastTake);
      const bool due =
          urgentWaiting || client->wantsWhole || (newsWaiting && gathered >= kGatherSeconds);
      if (mayTake && newsWaiting && !due) {
        timeout = std::min(timeout, 1 + static_cast<int>(1e3 * (kGatherSeconds - gathered)));
      }
      const bool wantsToWrite =
          !client->out.empty() || client->imageRequest.has_value() || (mayTake && due);
      fds.push_back(
          {client->socket.fd(), static_cast<short>(POLLIN | (wantsToWrite ? POLLOUT : 0)), 0});
    }
    ::poll(fds.data(), fds.size(), timeout);

    if (interruptRequested()) {
      reason = std::string("the job was interrupted (") + interruptSignalName() + ")";
      break;
    }
    if (stopRequested_) {
      reason = "the job was stopped";
      break;
    }
    const WakePipe::Woken woken = wakePipe.drain();
    newsWaiting = newsWaiting || woken.any;
    urgentWaiting = urgentWaiting || woken.urgent;
    if (finished) {
      reason = failure ? "the job failed" : endedBy.empty() ? "the job ended" : endedBy;
      break;
    }

    // New connections wait for their Hello, a bounded number at a time: when that many wait,
    // the oldest goes, so a flood of silent connections delays the right viewer but never
    // locks it out.
    while (Socket s = acceptConnection(listener_)) {
      if (pending.size() >= kMaxPending) {
        refuse(pending.front()->socket, "too many connections at once");
        pending.erase(pending.begin());
      }
      pending.push_back(std::make_unique<Pending>());
      pending.back()->socket = std::move(s);
    }
    for (size_t i = 0; i < pending.size();) {
      Pending& p = *pending[i];
      bool drop = false;
      std::vector<view::Message> messages;
      try {
        const bool open = p.reader.readFrom(p.socket, messages);
        if (messages.empty()) {
          if (!open) {
            drop = true;
            ++refused_;
          } else if (since(p.since) > options_.helloTimeoutSeconds) {
            refuse(p.socket, "no token within the time allowed");
            drop = true;
          }
        } else {
          drop = true;
          const view::Message& first = messages.front();
          if (first.type != view::MessageType::Hello) {
            refuse(p.socket, "the first message must be Hello");
          } else if (const view::HelloMessage hello = view::decode<view::HelloMessage>(first);
                     !tokenMatches(hello.token, token_)) {
            refuse(p.socket, "wrong token");
          } else if (client) {
            refuse(p.socket, "another viewer (" + client->name +
                                 ") is connected to this job; it serves one at a time");
          } else {
            client = std::make_unique<Client>();
            client->socket = std::move(p.socket);
            // What came behind the Hello (and a message half read) is the viewer's.
            client->reader = std::move(p.reader);
            client->reader.setLimits(view::kClientToServer);
            client->early.assign(std::make_move_iterator(messages.begin() + 1),
                                 std::make_move_iterator(messages.end()));
            client->name = hello.client.empty() ? "a viewer" : hello.client;
            ViewerStart start = source_.start();
            start.view = current;
            start.resume = true;
            client->out.put(view::encode(view::WelcomeMessage{start}));
            log_ << "viewer     " << client->name << " connected\n";
            log_.flush();
          }
        }
      } catch (const std::exception& e) {
        refuse(p.socket, e.what());  // garbage, another version, an oversized length
        drop = true;
      }
      if (drop) {
        pending.erase(pending.begin() + static_cast<std::ptrdiff_t>(i));
      } else {
        ++i;
      }
    }

    if (!client) continue;
    try {
      std::vector<view::Message> messages = std::move(client->early);
      client->early.clear();
      if (!client->reader.readFrom(client->socket, messages)) {
        dropClient("it closed the connection");
        continue;
      }
      bool bye = false;
      for (const view::Message& m : messages) {
        client->lastHeard = Clock::now();
        switch (m.type) {
          case view::MessageType::SetView:
            current = view::decode<ViewSettings>(m);
            source_.setView(current);
            break;
          case view::MessageType::FullImageRequest:
            client->imageRequest = view::decode<view::FullImageRequestMessage>(m).request;
            break;
          case view::MessageType::Ping:
            break;
          case view::MessageType::NewsReceived: {
            const uint64_t count = view::decode<view::NewsReceivedMessage>(m).count;
            if (count > client->newsSent || count < client->newsAcknowledged) {
              throw wire::WireError("acknowledged news it was not sent");
            }
            client->newsAcknowledged = count;
            client->lastAcknowledged = Clock::now();
            break;
          }
          case view::MessageType::Bye:
            bye = true;
            break;
          default:
            throw wire::WireError(std::string("a viewer does not send ") +
                                  view::messageTypeName(m.type));
        }
      }
      if (bye) {
        dropClient("it said goodbye");
        continue;
      }
      if (client->out.empty() && client->imageRequest) {
        client->out.put(
            view::encode(view::FullImageMessage{*client->imageRequest, source_.fullImage()}));
        client->imageRequest.reset();
        client->lastProgress = Clock::now();
      }
      const bool mayTake = client->newsSent - client->newsAcknowledged < kNewsInFlight;
      const bool due =
          urgentWaiting || client->wantsWhole || (newsWaiting && since(lastTake) >= kGatherSeconds);
      if (client->out.empty() && mayTake && due) {
        // The newest news, merged since the last; taken only when the last has left and the
        // viewer has nearly caught up.
        client->out.put(view::encode(source_.take(client->wantsWhole)));
        if (client->newsSent == client->newsAcknowledged) {
          client->lastAcknowledged = Clock::now();  // the wait for an answer starts now
        }
        ++client->newsSent;
        client->wantsWhole = false;
        newsWaiting = urgentWaiting = false;
        lastTake = client->lastProgress = Clock::now();
      }
      if (!mayTake && since(client->lastAcknowledged) > options_.clientTimeoutSeconds) {
        dropClient("it stopped reading");
        continue;
      }
      if (!client->out.empty()) {
        if (client->out.writeTo(client->socket) > 0) client->lastProgress = Clock::now();
        if (!client->out.empty() && since(client->lastProgress) > options_.clientTimeoutSeconds) {
          dropClient("it stopped reading");
          continue;
        }
      }
      if (since(client->lastHeard) > options_.clientTimeoutSeconds) {
        dropClient("silent for " + std::to_string(options_.clientTimeoutSeconds) + " s");
      }
    } catch (const std::exception& e) {
      dropClient(e.what());
    }
  }

  if (client) tryToSay(client->socket, view::encode(view::JobEndedMessage{reason}));
  source_.stop();
  coordinator.join();
  if (!options_.connectionFile.empty()) ::unlink(options_.connectionFile.c_str());
  if (refused_ > kLoggedRefusals) {
    log_ << "refused    " << refused_ << " connections in all\n";
  }
  log_ << "served     until " << reason << "\n";
  log_.flush();
  if (failure) std::rethrow_exception(failure);
  return reason;
}

}  // namespace prism
