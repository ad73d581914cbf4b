#include "master/remote/Endpoint.h"

#include <arpa/inet.h>

#include <charconv>
#include <stdexcept>

namespace prism {

std::string Endpoint::text() const {
  const bool v6 = host.find(':') != std::string::npos;
  return (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

Endpoint parseEndpoint(const std::string& text) {
  Endpoint endpoint;
  std::string port = text;
  if (!text.empty() && text.front() == '[') {
    const size_t close = text.find(']');
    if (close == std::string::npos || close + 1 >= text.size() || text[close + 1] != ':') {
      throw std::invalid_argument("'" + text + "' is not [IPv6]:PORT");
    }
    endpoint.host = text.substr(1, close - 1);
    port = text.substr(close + 2);
  } else if (const size_t colon = text.rfind(':'); colon != std::string::npos) {
    endpoint.host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (endpoint.host.empty()) throw std::invalid_argument("'" + text + "' has no host");
  }
  unsigned value = 0;
  const auto [end, error] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || error != std::errc() || end != port.data() + port.size()) {
    throw std::invalid_argument("'" + text + "' has no port number (HOST:PORT or PORT)");
  }
  if (value > 65535) {
    throw std::invalid_argument("port " + port + " is out of range (0 to 65535)");
  }
  endpoint.port = static_cast<uint16_t>(value);
  return endpoint;
}

bool isLoopbackHost(const std::string& host) {
  if (host == "localhost" || host == "::1") return true;
  in_addr v4{};
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  return false;
}

}  // namespace prism
