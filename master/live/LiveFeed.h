// The live renderer's news for one viewer: a LiveListener that accumulates the passes' tiles
// (FrameAccumulator, full precision), and at take() hands over what changed as display bytes on
// a NewsBoard, merged since the last take. The coordinator never waits for the viewer: it only
// records, and a viewer that takes rarely gets the newest picture. Thread-safe: the coordinator
// feeds it while the viewer's thread (the window's, or a connection's) takes.
#pragma once

#include <functional>
#include <mutex>

#include "image/ImageRgb.h"
#include "image/ToneMap.h"
#include "master/live/FrameAccumulator.h"
#include "master/live/LiveRenderer.h"
#include "master/live/LiveSource.h"
#include "master/live/NewsBoard.h"

namespace prism {

// What a viewer needs of a PassInfo.
DisplayPass displayPass(const PassInfo& pass);

class LiveFeed final : public LiveListener {
 public:
  LiveFeed(int width, int height, float exposure);

  // Called when news arrives and the last was taken, and again when urgent news (a pass began
  // or completed) follows news that was not (so twice per take at most), on the coordinator
  // thread: it should only wake whoever takes. Set it before the renderer runs.
  void setWake(NewsWake wake) { wake_ = std::move(wake); }

  // Everything since the last take(), merged; `whole`: with every pixel (a viewer that just
  // came, or came back).
  DisplayNews take(bool whole = false);
  // The image on show at full precision (linear radiance, what an EXR save writes).
  ImageRgb image();

  // LiveListener: the coordinator's calls.
  void passStarted(const PassInfo& pass) override;
  void tileAssigned(uint32_t frame, uint32_t tile, int rank) override;
  void tileFinished(uint32_t frame, std::shared_ptr<const TileResult> tile, int rank) override;
  void passFinished(uint32_t frame, double seconds) override;
  void statsUpdated(const LiveStats& stats) override;

 private:
  // Something changed: returns whether to wake the viewer (the first news since its take, or
  // the first urgent news).
  bool noteLocked(bool urgent);
  void wakeIf(bool wake, bool urgent) {
    if (wake && wake_) wake_(urgent);
  }
  // Encodes the accumulator's changed rectangle onto the board.
  void encodeDirtyLocked();

  std::mutex mutex_;
  FrameAccumulator frame_;
  DisplayEncoder encoder_;
  NewsBoard board_;
  int fullPassesDone_ = 0;
  bool started_ = false;
  bool waiting_ = false;        // news since the last take
  bool waitingUrgent_ = false;  // urgent news since the last take
  NewsWake wake_;
};

}  // namespace prism
