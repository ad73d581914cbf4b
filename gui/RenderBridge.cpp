#include "gui/RenderBridge.h"

namespace prism {

RenderBridge::RenderBridge(QObject* parent) : QObject(parent) {
  // Queued connections copy their arguments, so Qt must know the types.
  qRegisterMetaType<PassInfo>("prism::PassInfo");
  qRegisterMetaType<LiveStats>("prism::LiveStats");
  qRegisterMetaType<std::shared_ptr<const TileResult>>("std::shared_ptr<const prism::TileResult>");
  qRegisterMetaType<uint32_t>("uint32_t");
}

}  // namespace prism
