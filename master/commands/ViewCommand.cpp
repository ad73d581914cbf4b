#include "master/commands/ViewCommand.h"

#include <ostream>

#include "image/ImageIo.h"
#include "master/commands/MasterSession.h"
#include "master/commands/PartialFrame.h"

namespace prism {

int runView(const ViewOptions& options, std::ostream& out, std::ostream& err, Transport* session,
            const ViewerRunner& viewer) {
  MasterSession run(session, options.render, err);
  const auto checkArguments = [&] {
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
  };
  if (!run.load(checkArguments)) return 1;  // --caustics, --photons too
  return run.runToEnd(
      [&] {
        run.start(true);  // the window shows the scene's sky
        return viewer(run, options, out, err);
      },
      out);
}

}  // namespace prism
