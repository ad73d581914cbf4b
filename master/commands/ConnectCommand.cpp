#include "master/commands/ConnectCommand.h"

#include <filesystem>
#include <ostream>

#include "image/ImageIo.h"
#include "master/commands/MasterSession.h"
#include "master/remote/ConnectionFile.h"
#include "master/remote/ViewClient.h"

namespace prism {
namespace {

ConnectionInfo connectionOf(const ConnectCommandOptions& options) {
  std::error_code error;
  if (std::filesystem::is_regular_file(options.target, error)) {
    if (!options.tokenFile.empty()) {
      throw std::runtime_error("--token-file is for HOST:PORT; the connection file has the token");
    }
    return readConnectionFile(options.target);
  }
  ConnectionInfo info;
  try {
    info.endpoint = parseEndpoint(options.target);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("'" + options.target +
                             "' is neither a connection file nor HOST:PORT (" + e.what() + ")");
  }
  info.token = tokenFromFileOrEnvironment(options.tokenFile);
  return info;
}

}  // namespace

int runConnect(const ConnectCommandOptions& options, std::ostream& out, std::ostream& err,
               Transport* session, const ViewerRunner& viewer) {
  if (session) {
    MasterSession run(session, RenderOptions{}, err);
    return run.refuse("prism connect is a viewer: run it alone, not under mpirun or srun");
  }
  try {
    if (!viewer) {
      throw std::runtime_error(
          "this prism was built without the viewer (Qt5 Widgets and Charts were not found); "
          "install qtbase5-dev and libqt5charts5-dev and rebuild");
    }
    if (!options.window.savePath.empty()) {
      std::string why;
      if (!isWritableImagePath(options.window.savePath, &why)) throw std::runtime_error(why);
    }
    ConnectOptions connect;
    connect.connectSeconds = options.timeoutSeconds;
    ViewClient client(connectionOf(options), connect);
    out << "connected  " << client.start().sceneName << ", " << client.start().width << "x"
        << client.start().height << "\n";
    const int code = viewer(client, options.window, out, err);
    out << "received   " << client.bytesReceived() << " bytes\n";
    return code;
  } catch (const std::exception& e) {
    err << "prism: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace prism
