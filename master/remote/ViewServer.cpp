#include "master/remote/ViewServer.h"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <ostream>
#include <stdexcept>
#include <thread>

#include "master/remote/AccessToken.h"
#include "master/remote/ConnectionFile.h"
#include "master/remote/WakePipe.h"
#include "util/InterruptSignal.h"

namespace prism {
namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kMaxPending = 16;                // connections not yet past their Hello
constexpr view::Limits kHelloLimits{4096, 4096};  // a Hello is a token and a name
constexpr int kPollMilliseconds = 100;            // how often interrupts and deadlines are checked
constexpr size_t kLoggedRefusals = 5;             // refusals named in the log; the rest counted

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

struct ViewServer::Pending {
  Socket socket;
  MessageReader reader{kHelloLimits};
  Clock::time_point since = Clock::now();
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

ViewServer::~ViewServer() = default;

void ViewServer::logLine(const std::string& line) {
  log_ << line << "\n";
  log_.flush();
}

void ViewServer::refuse(const Socket& socket, const std::string& why) {
  tryToSay(socket, view::encode(view::RefusedMessage{why}));
  if (refused_++ < kLoggedRefusals) logLine("refused    a connection: " + why);
}

void ViewServer::dropViewer(const std::string& why) {
  logLine("viewer     " + viewer_->name() + " left: " + why);
  viewer_.reset();
  if (options_.exitWithClient) reason_ = "the viewer left (--exit-with-client)";
}

std::string ViewServer::run() {
  WakePipe wake;
  std::atomic<bool> finished{false};
  std::exception_ptr failure;
  std::string endedBy;
  std::thread coordinator([&] {
    try {
      endedBy = source_.run([&wake](bool urgent) { wake.wake(urgent); });
    } catch (...) {
      failure = std::current_exception();
    }
    finished = true;
    wake.wake(true);
  });
  current_ = source_.start().view;
  source_.setView(current_);  // renders without a viewer: a viewer that comes finds the passes
  logLine("serving    " + endpoint_.text() +
          (options_.connectionFile.empty() ? "" : ", connection file " + options_.connectionFile));

  while (reason_.empty()) {
    pollOnce(wake);
    if (interruptRequested()) {
      reason_ = std::string("the job was interrupted (") + interruptSignalName() + ")";
    } else if (stopRequested_) {
      reason_ = "the job was stopped";
    } else if (finished) {
      reason_ = failure ? "the job failed" : endedBy.empty() ? "the job ended" : endedBy;
    }
    if (!reason_.empty()) break;
    const WakePipe::Woken woken = wake.drain();
    news_.waiting = news_.waiting || woken.any;
    news_.urgent = news_.urgent || woken.urgent;
    admitConnections();
    hearPending();
    if (!viewer_) continue;
    std::string gone = viewer_->read(source_, current_);
    if (gone.empty()) gone = viewer_->write(source_, news_, options_.clientTimeoutSeconds);
    if (!gone.empty()) dropViewer(gone);
  }

  if (viewer_) viewer_->tryToSay(view::encode(view::JobEndedMessage{reason_}));
  source_.stop();
  coordinator.join();
  if (!options_.connectionFile.empty()) ::unlink(options_.connectionFile.c_str());
  if (refused_ > kLoggedRefusals) logLine("refused    " + std::to_string(refused_) + " in all");
  logLine("served     until " + reason_);
  if (failure) std::rethrow_exception(failure);
  return reason_;
}

void ViewServer::pollOnce(const WakePipe& wake) {
  std::vector<pollfd> fds{{listener_.fd(), POLLIN, 0}, {wake.fd(), POLLIN, 0}};
  for (const auto& p : pending_) fds.push_back({p->socket.fd(), POLLIN, 0});
  int timeout = kPollMilliseconds;
  if (viewer_) {
    if (viewer_->mayTakeNews() && news_.waiting && !viewer_->newsDue(news_)) {
      const double left = ViewerConnection::kGatherSeconds - since(news_.lastTake);
      timeout = std::min(timeout, 1 + static_cast<int>(1e3 * std::max(0.0, left)));
    }
    const short events = POLLIN | (viewer_->wantsToWrite(news_) ? POLLOUT : 0);
    fds.push_back({viewer_->fd(), events, 0});
  }
  ::poll(fds.data(), fds.size(), timeout);
}

void ViewServer::admitConnections() {
  // When too many wait, the oldest goes: a flood of silent connections delays the right viewer
  // but never locks it out.
  while (Socket s = acceptConnection(listener_)) {
    if (pending_.size() >= kMaxPending) {
      refuse(pending_.front()->socket, "too many connections at once");
      pending_.erase(pending_.begin());
    }
    pending_.push_back(std::make_unique<Pending>());
    pending_.back()->socket = std::move(s);
  }
}

void ViewServer::hearPending() {
  std::erase_if(pending_, [this](const std::unique_ptr<Pending>& p) { return hear(*p); });
}

bool ViewServer::hear(Pending& p) {
  std::vector<view::Message> messages;
  try {
    const bool open = p.reader.readFrom(p.socket, messages);
    if (messages.empty()) {
      if (!open) {
        ++refused_;
        return true;
      }
      if (since(p.since) <= options_.helloTimeoutSeconds) return false;
      refuse(p.socket, "no token within the time allowed");
      return true;
    }
    const view::Message& first = messages.front();
    if (first.type != view::MessageType::Hello) {
      refuse(p.socket, "the first message must be Hello");
      return true;
    }
    const view::HelloMessage hello = view::decode<view::HelloMessage>(first);
    if (!tokenMatches(hello.token, token_)) {
      refuse(p.socket, "wrong token");
    } else if (viewer_) {
      refuse(p.socket, "another viewer (" + viewer_->name() +
                           ") is connected to this job; it serves one at a time");
    } else {
      // What came behind the Hello (and a message half read) is the viewer's.
      messages.erase(messages.begin());
      viewer_ = std::make_unique<ViewerConnection>(
          std::move(p.socket), std::move(p.reader), std::move(messages),
          hello.client.empty() ? "a viewer" : hello.client);
      ViewerStart start = source_.start();
      start.view = current_;
      start.resume = true;
      viewer_->queue(view::encode(view::WelcomeMessage{start}));
      logLine("viewer     " + viewer_->name() + " connected");
    }
  } catch (const std::exception& e) {
    refuse(p.socket, e.what());  // garbage, another version, an oversized length
  }
  return true;
}

}  // namespace prism
