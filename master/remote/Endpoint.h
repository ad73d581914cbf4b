// A TCP address as the user writes it: "HOST:PORT", "[IPv6]:PORT" or "PORT" (127.0.0.1).
#pragma once

#include <cstdint>
#include <string>

namespace prism {

struct Endpoint {
  std::string host = "127.0.0.1";
  uint16_t port = 0;

  // "127.0.0.1:4050", "[::1]:4050".
  std::string text() const;
};

// Throws std::invalid_argument naming what is wrong ("port 70000 is out of range").
Endpoint parseEndpoint(const std::string& text);

// Whether host names only this machine (127.0.0.0/8, ::1, localhost): what may be served on
// without asking for the network.
bool isLoopbackHost(const std::string& host);

}  // namespace prism
