// `prism view --serve`: the job's live session served to one viewer at a time over TCP instead
// of shown here. The source renders on a thread of its own as it would under a window; this
// thread listens, lets a connection in only after its first message carried the job's token,
// and then relays (ViewerConnection): the viewer's views to the source, the source's news to
// the viewer as fast as the viewer takes it and no faster (news waits merged on the source's
// board, never queued, so a slow viewer costs the render nothing and the server holds at most
// one message and one image per viewer). Without a viewer the source keeps refining the last
// view; a viewer that comes back finds the accumulated passes. Bad connections (wrong token,
// garbage, another protocol version, an oversized length, silence, a viewer that stops reading)
// are dropped, and the job renders on.
#pragma once

#include <atomic>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "master/live/LiveSource.h"
#include "master/remote/Endpoint.h"
#include "master/remote/ServeOptions.h"
#include "master/remote/Socket.h"
#include "master/remote/ViewerConnection.h"

namespace prism {

class WakePipe;

class ViewServer {
 public:
  // Listens (refusing an address beyond loopback unless options.allowNetwork), makes the token
  // and writes the connection file when one is asked for. Throws std::runtime_error.
  ViewServer(LiveSource& source, const ServeOptions& options, std::ostream& log);
  ~ViewServer();

  const Endpoint& endpoint() const { return endpoint_; }
  const std::string& token() const { return token_; }

  // Serves until the job ends: Ctrl-C or SIGTERM, stop(), the source ending or failing, or the
  // viewer leaving under exitWithClient. Returns why it ended; rethrows the source's failure.
  std::string run();
  // Makes run() return soon. Any thread.
  void stop() { stopRequested_ = true; }

  // Connections refused so far (wrong token, garbage, too many at once, ...).
  size_t refused() const { return refused_; }

 private:
  struct Pending;

  // Waits for something to do (at most 100 ms, or until gathered news falls due).
  void pollOnce(const WakePipe& wake);
  // New connections join the ones waiting for their Hello, a bounded number.
  void admitConnections();
  // Reads the waiting connections: a right Hello makes the viewer; anything else is refused.
  void hearPending();
  // Returns whether to drop p (answered, refused, or silent too long).
  bool hear(Pending& p);
  void refuse(const Socket& socket, const std::string& why);
  void dropViewer(const std::string& why);
  void logLine(const std::string& line);

  LiveSource& source_;
  ServeOptions options_;
  std::ostream& log_;
  Socket listener_;
  Endpoint endpoint_;
  std::string token_;
  std::atomic<bool> stopRequested_{false};
  std::atomic<size_t> refused_{0};

  // run()'s state.
  std::vector<std::unique_ptr<Pending>> pending_;
  std::unique_ptr<ViewerConnection> viewer_;
  ViewerConnection::NewsState news_;
  ViewSettings current_;  // the view being rendered (a viewer that comes resumes it)
  std::string reason_;    // why run() ends ("" : it goes on)
};

}  // namespace prism
