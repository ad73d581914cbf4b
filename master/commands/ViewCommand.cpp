#include "master/commands/ViewCommand.h"

#include <ostream>

#include "caustics/CausticMapMemory.h"
#include "image/ImageIo.h"
#include "master/commands/PartialFrame.h"
#include "master/runtime/ResourceCheck.h"
#include "master/runtime/SlaveShutdown.h"
#include "parse/SceneLoader.h"
#include "transport/Transport.h"
#include "wire/Messages.h"

namespace prism {

int runView(const ViewOptions& options, std::ostream& out, std::ostream& err, Transport* session,
            const ViewerRunner& viewer) {
  SceneDescription description;
  try {
    if (!viewer) {
      throw std::runtime_error(
          "this prism was built without the viewer (Qt5 Widgets and Charts were not found); "
          "install qtbase5-dev and libqt5charts5-dev and rebuild");
    }
    if (!options.savePath.empty()) {
      std::string why;
      if (!isWritableImagePath(options.savePath, &why)) throw std::runtime_error(why);
      checkMayWriteFrame(options.savePath, options.render.overwrite);
    }
    description = loadSceneWithOverrides(options.render);  // --caustics, --photons too
  } catch (const std::exception& e) {
    return failBeforeScene(session, e.what(), err);
  }

  int exitCode = 0;
  try {
    if (session) {
      std::vector<uint8_t> bytes = wire::encodeScene(description);
      session->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
    }
    const Scene scene(description);
    checkCausticMapsFit(scene, memoryLimitOrPhysical(options.render.memoryLimit));
    exitCode = viewer(scene, description, options, session, out, err);
  } catch (const std::exception& e) {
    err << "prism: error: " << e.what() << "\n";
    exitCode = 1;
  }
  out.flush();
  return shutDownSlaves(session, exitCode, {}, err);
}

}  // namespace prism
