#include "master/remote/ConnectionFile.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "master/remote/AccessToken.h"

namespace prism {
namespace {

std::string trim(const std::string& s) {
  const size_t begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

}  // namespace

void writeConnectionFile(const std::string& path, const ConnectionInfo& info) {
  std::ostringstream text;
  text << "# Prism: a job serving its live session. Connect with: prism connect " << path << "\n"
       << "# Keep this file private: the token lets whoever has it steer the job's viewer.\n"
       << "host=" << info.endpoint.host << "\n"
       << "port=" << info.endpoint.port << "\n"
       << "token=" << info.token << "\n"
       << "protocol=" << info.protocol << "\n";
  const std::string body = text.str();
  const std::string temporary = path + ".tmp-" + std::to_string(::getpid());
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  // An existing temporary keeps its mode through O_TRUNC: set it.
  bool ok = ::fchmod(fd, 0600) == 0;
  ok = ok && ::write(fd, body.data(), body.size()) == static_cast<ssize_t>(body.size());
  ok = (::close(fd) == 0) && ok;
  if (!ok || ::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(temporary.c_str());
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
}

ConnectionInfo readConnectionFile(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    throw std::runtime_error("cannot read connection file " + path + ": " + std::strerror(errno));
  }
  if (status.st_mode & (S_IRWXG | S_IRWXO)) {
    throw std::runtime_error("connection file " + path +
                             " may be read by others (chmod 600 it): its token is a secret");
  }
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read connection file " + path);
  ConnectionInfo info;
  bool haveHost = false, havePort = false, haveToken = false, haveProtocol = false;
  std::string line;
  for (int number = 1; std::getline(file, line); ++number) {
    const std::string where = path + ":" + std::to_string(number) + ": ";
    line = trim(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    const size_t equals = line.find('=');
    if (equals == std::string::npos) throw std::runtime_error(where + "expected key=value");
    const std::string key = trim(line.substr(0, equals));
    const std::string value = trim(line.substr(equals + 1));
    const auto number32 = [&](uint32_t limit) {
      uint32_t n = 0;
      const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), n);
      if (value.empty() || error != std::errc() || end != value.data() + value.size() ||
          n > limit) {
        throw std::runtime_error(where + key + " '" + value + "' is not a number up to " +
                                 std::to_string(limit));
      }
      return n;
    };
    if (key == "host") {
      if (value.empty()) throw std::runtime_error(where + "empty host");
      info.endpoint.host = value;
      haveHost = true;
    } else if (key == "port") {
      info.endpoint.port = static_cast<uint16_t>(number32(65535));
      havePort = true;
    } else if (key == "token") {
      if (!isWellFormedToken(value)) {
        throw std::runtime_error(where + "the token is not 64 hex digits");
      }
      info.token = value;
      haveToken = true;
    } else if (key == "protocol") {
      info.protocol = number32(UINT32_MAX);
      haveProtocol = true;
    } else {
      throw std::runtime_error(where + "unknown key '" + key + "'");
    }
  }
  for (const auto& [have, key] :
       {std::pair{haveHost, "host"}, std::pair{havePort, "port"}, std::pair{haveToken, "token"},
        std::pair{haveProtocol, "protocol"}}) {
    if (!have) throw std::runtime_error("connection file " + path + " has no " + key);
  }
  return info;
}

std::string tokenFromFileOrEnvironment(const std::string& tokenFile) {
  std::string token;
  if (!tokenFile.empty()) {
    std::ifstream file(tokenFile);
    if (!file) throw std::runtime_error("cannot read token file " + tokenFile);
    std::getline(file, token);
    token = trim(token);
    if (token.empty()) throw std::runtime_error("token file " + tokenFile + " is empty");
    return token;
  }
  if (const char* variable = std::getenv("PRISM_TOKEN"); variable && *variable) {
    return trim(variable);
  }
  throw std::runtime_error(
      "no token: pass --token-file FILE or set PRISM_TOKEN (the job's connection file has it; "
      "or connect with the connection file itself)");
}

}  // namespace prism
