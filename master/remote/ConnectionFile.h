// How a viewer finds and enters a served job: host, port, token and protocol version, in a file
// only its owner may read (mode 0600), written by `prism view --serve` and read by
// `prism connect FILE`. Lines of key=value; '#' starts a comment.
#pragma once

#include <cstdint>
#include <string>

#include "master/remote/Endpoint.h"

namespace prism {

struct ConnectionInfo {
  Endpoint endpoint;
  std::string token;
  uint32_t protocol = 0;
};

// Writes atomically, created 0600 (never readable by others, not even for a moment). Throws
// std::runtime_error naming the path.
void writeConnectionFile(const std::string& path, const ConnectionInfo& info);

// Throws std::runtime_error naming the path and the line for a missing, unreadable or malformed
// file, and when the file may be read by others than its owner (the token would not be secret).
ConnectionInfo readConnectionFile(const std::string& path);

// The token for `prism connect HOST:PORT`: the first line of tokenFile when given, else the
// PRISM_TOKEN variable. Throws std::runtime_error saying where a token is looked for.
std::string tokenFromFileOrEnvironment(const std::string& tokenFile);

}  // namespace prism
