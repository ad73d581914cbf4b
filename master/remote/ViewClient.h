// `prism connect`: a job's live session over a connection, as a LiveSource, so the window on a
// desk is the same window as beside the job. Connecting sends the token first and waits for the
// job's Welcome (or its reason to refuse). run() then receives: news goes onto a NewsBoard
// (merged until the window takes it, as on the job's side), statistics are kept, and a ping
// each second tells the job the viewer is alive. setView() and fullImage() send from the
// caller's thread. When the job ends or the connection goes, run() returns saying so.
#pragma once

#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>

#include "master/live/LiveSource.h"
#include "master/live/NewsBoard.h"
#include "master/remote/ConnectionFile.h"
#include "master/remote/Socket.h"

namespace prism {

struct ConnectOptions {
  double connectSeconds = 10.0;  // to connect and be welcomed
  double requestSeconds = 60.0;  // for a full-precision image to arrive
  std::string clientName;        // how the job's log names this viewer ("" : user@host)
};

class ViewClient final : public LiveSource {
 public:
  // Connects and is welcomed. Throws std::runtime_error with the job's reason when refused.
  ViewClient(const ConnectionInfo& job, const ConnectOptions& options = {});
  ~ViewClient() override;

  const ViewerStart& start() const override { return start_; }
  void setView(const ViewSettings& view) override;
  std::string run(NewsWake wake) override;
  void stop() override;
  DisplayNews take(bool whole = false) override;
  ImageRgb fullImage() override;
  LiveStats stats() override;
  std::shared_ptr<const CausticMapEstimator> causticMaps(bool blur) override;

  // Bytes received so far: envelopes and compressed payloads as they came off the socket.
  uint64_t bytesReceived() const { return bytesReceived_; }

 private:
  void send(const std::vector<uint8_t>& message);
  void received(view::Message&& message, const NewsWake& wake);

  ConnectOptions options_;
  Socket socket_;
  MessageReader reader_;
  std::vector<view::Message> early_;  // what came behind the Welcome, for run()
  ViewerStart start_;
  std::mutex sendMutex_;

  std::mutex mutex_;  // guards what follows
  std::condition_variable changed_;
  NewsBoard board_;
  bool waiting_ = false;  // news on the board since the last take
  LiveStats stats_;
  bool stopped_ = false;
  std::string ended_;  // why the connection ended, once it has
  uint32_t nextRequest_ = 1;
  std::optional<view::FullImageMessage> image_;
  std::atomic<uint64_t> bytesReceived_{0};
  uint64_t newsReceived_ = 0;  // run()'s thread only
};

}  // namespace prism
