// `prism view --serve`: the live session served to a viewer elsewhere instead of shown here.
#pragma once

#include <string>

namespace prism {

struct ServeOptions {
  std::string address;  // "HOST:PORT" or "PORT" (127.0.0.1); PORT 0 picks a free port; "": show
  std::string connectionFile;   // where host, port and token are written (mode 0600)
  bool exitWithClient = false;  // end the job when the viewer leaves
  // Listening beyond the loopback addresses must be asked for twice: by the address and by this.
  bool allowNetwork = false;
  double clientTimeoutSeconds = 10.0;  // a viewer silent, or not reading, this long is dropped
  double helloTimeoutSeconds = 5.0;    // a new connection must show its token within this

  bool serving() const { return !address.empty(); }
};

}  // namespace prism
