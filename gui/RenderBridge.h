// Carries LiveRenderer's news from the coordinator thread to the Qt main thread: every
// listener call becomes a signal, which Qt queues across the threads (the receivers live in
// the main thread). Nothing here touches a widget.
#pragma once

#include <QObject>
#include <memory>

#include "master/runtime/LiveRenderer.h"

Q_DECLARE_METATYPE(prism::PassInfo)
Q_DECLARE_METATYPE(prism::LiveStats)
Q_DECLARE_METATYPE(std::shared_ptr<const prism::TileResult>)

namespace prism {

class RenderBridge : public QObject, public LiveListener {
  Q_OBJECT

 public:
  explicit RenderBridge(QObject* parent = nullptr);

  void passStarted(const PassInfo& pass) override { emit passStartedSignal(pass); }
  void tileAssigned(uint32_t frame, uint32_t tile, int rank) override {
    emit tileAssignedSignal(frame, tile, rank);
  }
  void tileFinished(uint32_t frame, std::shared_ptr<const TileResult> tile, int rank) override {
    emit tileFinishedSignal(frame, std::move(tile), rank);
  }
  void passFinished(uint32_t frame, double seconds) override {
    emit passFinishedSignal(frame, seconds);
  }
  void statsUpdated(const LiveStats& stats) override { emit statsUpdatedSignal(stats); }

 signals:
  void passStartedSignal(const prism::PassInfo& pass);
  void tileAssignedSignal(uint32_t frame, uint32_t tile, int rank);
  void tileFinishedSignal(uint32_t frame, std::shared_ptr<const prism::TileResult> tile, int rank);
  void passFinishedSignal(uint32_t frame, double seconds);
  void statsUpdatedSignal(const prism::LiveStats& stats);
};

}  // namespace prism
