#include "master/ViewCommand.h"

#include <ostream>

#include "image/ImageIo.h"
#include "master/ResourceCheck.h"
#include "master/SlaveShutdown.h"
#include "parse/SceneLoader.h"
#include "slave/SlaveLoop.h"
#include "transport/MpiSession.h"
#include "wire/Messages.h"

namespace prism {

int runView(const ViewOptions& options, std::ostream& out, std::ostream& err, MpiSession* session,
            const ViewerRunner& viewer) {
  if (session && session->rank() != 0) {
    SlaveOptions slave;
    slave.threads = options.render.threads;
    slave.fault = options.render.fault;
    return runSlave(*session, slave);
  }
  constexpr double kBroadcastTimeoutSeconds = 600.0;
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
    }
    description = loadScene(options.render.scenePath);
    applyOverrides(options.render, description.render);
    applyOverrides(options.render, description.caustics);  // --caustics, --photons
    checkRenderFits(description.render, physicalMemoryBytes());
    checkCausticsFit(description.caustics, physicalMemoryBytes());
  } catch (const std::exception& e) {
    if (session) {
      std::vector<uint8_t> bytes = wire::encodeError({e.what()});
      session->broadcast(bytes, kBroadcastTimeoutSeconds);
    }
    err << "prism: error: " << e.what() << "\n";
    return 1;
  }

  int exitCode = 0;
  try {
    if (session) {
      std::vector<uint8_t> bytes = wire::encodeScene(description);
      session->broadcast(bytes, kBroadcastTimeoutSeconds);
    }
    const Scene scene(description);
    exitCode = viewer(scene, description, options, session, out, err);
  } catch (const std::exception& e) {
    err << "prism: error: " << e.what() << "\n";
    exitCode = 1;
  }
  out.flush();
  return shutDownSlaves(session, exitCode, {}, err);
}

}  // namespace prism
