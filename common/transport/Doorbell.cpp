#include "transport/Doorbell.h"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>

namespace prism {
namespace {

// An address in the abstract namespace: a leading NUL, then the name (no file to clean up).
socklen_t abstractAddress(const std::string& name, sockaddr_un& address) {
  std::memset(&address, 0, sizeof address);
  address.sun_family = AF_UNIX;
  const size_t length = std::min(name.size(), sizeof address.sun_path - 1);
  std::memcpy(address.sun_path + 1, name.data(), length);
  return static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + length);
}

// Reads every queued ring; true if there was one.
bool drainSocket(int fd) {
  bool any = false;
  char bytes[64];
  while (fd >= 0 && ::recv(fd, bytes, sizeof bytes, MSG_DONTWAIT) > 0) any = true;
  return any;
}

}  // namespace

Doorbell::Doorbell(const std::string& name) {
  if (::socketpair(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0, selfSocket_) != 0) {
    throw std::runtime_error(std::string("cannot make a wake-up socket: ") + std::strerror(errno));
  }
  if (name.empty()) return;
  socket_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (socket_ < 0) return;
  sockaddr_un address;
  const socklen_t length = abstractAddress(name, address);
  bound_ = ::bind(socket_, reinterpret_cast<const sockaddr*>(&address), length) == 0;
  if (!bound_) {
    ::close(socket_);
    socket_ = -1;
  }
}

Doorbell::~Doorbell() {
  if (socket_ >= 0) ::close(socket_);
  ::close(selfSocket_[0]);
  ::close(selfSocket_[1]);
}

bool Doorbell::ring(const std::string& name) const {
  sockaddr_un address;
  const socklen_t length = abstractAddress(name, address);
  const char byte = 1;
  const int from = socket_ >= 0 ? socket_ : selfSocket_[1];
  const ssize_t sent = ::sendto(from, &byte, 1, MSG_DONTWAIT | MSG_NOSIGNAL,
                                reinterpret_cast<const sockaddr*>(&address), length);
  if (sent == 1) return true;
  // Nobody bound the name: the peer's process has ended (its socket closed with it). Any other
  // failure (a full queue: a ring is waiting already) loses at most a wake-up.
  return errno != ECONNREFUSED && errno != ENOENT;
}

void Doorbell::ringSelf() const {
  const char byte = 1;
  // A full queue already holds a ring: nothing is lost by dropping this one.
  [[maybe_unused]] const ssize_t sent = ::send(selfSocket_[1], &byte, 1, MSG_DONTWAIT);
}

Doorbell::Heard Doorbell::wait(double seconds) {
  pollfd fds[2] = {{selfSocket_[0], POLLIN, 0}, {socket_, POLLIN, 0}};
  const nfds_t count = socket_ >= 0 ? 2 : 1;
  // poll() counts whole milliseconds; ppoll() takes the exact time.
  const double clamped = std::max(0.0, seconds);
  timespec timeout;
  timeout.tv_sec = static_cast<time_t>(clamped);
  timeout.tv_nsec = static_cast<long>((clamped - std::floor(clamped)) * 1e9);
  // A signal (EINTR) ends the wait too: the caller looks at its flags and waits again.
  if (::ppoll(fds, count, &timeout, nullptr) <= 0) return Heard::Nothing;
  const bool peer = drainSocket(socket_);
  if (drainSocket(selfSocket_[0])) return Heard::Self;  // read after the peers': none is missed
  return peer ? Heard::Peer : Heard::Nothing;
}

}  // namespace prism
