#include "master/remote/Socket.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace prism {
namespace {

constexpr size_t kReadChunk = size_t{1} << 20;

void setNonBlocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  ::fcntl(fd, F_SETFL, flags | O_NONBLOCK);
}

void setNoDelay(int fd) {
  // Small messages (a view, a ping) go at once rather than waiting to be merged.
  const int on = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
}

struct AddressList {
  addrinfo* list = nullptr;
  ~AddressList() {
    if (list) ::freeaddrinfo(list);
  }
};

AddressList resolve(const Endpoint& endpoint, bool passive) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICSERV | (passive ? AI_PASSIVE : 0);
  AddressList addresses;
  const std::string port = std::to_string(endpoint.port);
  const int error = ::getaddrinfo(endpoint.host.c_str(), port.c_str(), &hints, &addresses.list);
  if (error != 0) {
    throw std::runtime_error("cannot resolve " + endpoint.host + ": " + ::gai_strerror(error));
  }
  return addresses;
}

// A socket for address a, or an invalid one with the reason in why.
Socket openSocket(const addrinfo* a, std::string& why) {
  Socket s(::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol));
  if (!s.valid()) why = std::strerror(errno);
  return s;
}

double secondsFrom(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Socket& Socket::operator=(Socket&& o) noexcept {
  if (this != &o) {
    close();
    fd_ = o.fd_;
    o.fd_ = -1;
  }
  return *this;
}

void Socket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void Socket::shutdown() {
  if (fd_ >= 0) ::shutdown(fd_, SHUT_RDWR);
}

Socket listenTcp(const Endpoint& endpoint, Endpoint* bound) {
  const AddressList addresses = resolve(endpoint, true);
  std::string why = "no address";
  for (const addrinfo* a = addresses.list; a; a = a->ai_next) {
    Socket s = openSocket(a, why);
    if (!s.valid()) continue;
    const int on = 1;
    ::setsockopt(s.fd(), SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    if (::bind(s.fd(), a->ai_addr, a->ai_addrlen) != 0 || ::listen(s.fd(), 64) != 0) {
      why = std::strerror(errno);
      continue;
    }
    setNonBlocking(s.fd());
    sockaddr_storage local{};
    socklen_t length = sizeof local;
    ::getsockname(s.fd(), reinterpret_cast<sockaddr*>(&local), &length);
    if (bound) {
      *bound = endpoint;
      bound->port =
          ntohs(local.ss_family == AF_INET6 ? reinterpret_cast<sockaddr_in6*>(&local)->sin6_port
                                            : reinterpret_cast<sockaddr_in*>(&local)->sin_port);
    }
    return s;
  }
  throw std::runtime_error("cannot listen on " + endpoint.text() + ": " + why);
}

Socket acceptConnection(const Socket& listener) {
  const int fd = ::accept4(listener.fd(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
  if (fd < 0) return Socket();
  setNoDelay(fd);
  return Socket(fd);
}

Socket connectTcp(const Endpoint& endpoint, double timeoutSeconds) {
  const AddressList addresses = resolve(endpoint, false);
  std::string why = "no address";
  for (const addrinfo* a = addresses.list; a; a = a->ai_next) {
    Socket s = openSocket(a, why);
    if (!s.valid()) continue;
    setNonBlocking(s.fd());
    if (::connect(s.fd(), a->ai_addr, a->ai_addrlen) != 0) {
      if (errno != EINPROGRESS) {
        why = std::strerror(errno);
        continue;
      }
      pollfd p{s.fd(), POLLOUT, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(timeoutSeconds * 1000));
      int error = 0;
      socklen_t length = sizeof error;
      ::getsockopt(s.fd(), SOL_SOCKET, SO_ERROR, &error, &length);
      if (ready <= 0 || error != 0) {
        why = ready <= 0 ? "no answer within " + std::to_string(timeoutSeconds) + " s"
                         : std::strerror(error);
        continue;
      }
    }
    setNoDelay(s.fd());
    return s;
  }
  throw std::runtime_error("cannot connect to " + endpoint.text() + ": " + why +
                           " (is the job serving there? through an SSH tunnel, is it up?)");
}

void sendAll(const Socket& socket, const std::vector<uint8_t>& bytes, double timeoutSeconds) {
  const auto start = std::chrono::steady_clock::now();
  size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(socket.fd(), bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      throw std::runtime_error(std::string("the connection failed: ") + std::strerror(errno));
    }
    const double left = timeoutSeconds - secondsFrom(start);
    if (left <= 0) throw std::runtime_error("the connection stopped taking data");
    pollfd p{socket.fd(), POLLOUT, 0};
    ::poll(&p, 1, std::max(1, static_cast<int>(left * 1000)));
  }
}

bool MessageReader::readFrom(const Socket& socket, std::vector<view::Message>& out) {
  uint8_t buffer[64 * 1024];
  for (;;) {
    // Read no further than the message being read: the header, then exactly its payload.
    size_t want = haveHeader_ ? parsed_.size - payload_.size() : view::kHeaderSize - header_.size();
    want = std::min(want, sizeof buffer);
    ssize_t n = want == 0 ? 0 : ::recv(socket.fd(), buffer, want, 0);
    if (want != 0) {
      if (n == 0) return false;
      if (n < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK) return true;
        if (errno == EINTR) continue;
        if (errno == ECONNRESET) return false;
        throw std::runtime_error(std::string("the connection failed: ") + std::strerror(errno));
      }
    }
    if (!haveHeader_) {
      header_.insert(header_.end(), buffer, buffer + n);
      if (header_.size() < view::kHeaderSize) continue;
      parsed_ = view::readHeader(header_.data(), limits_);  // throws before any payload is read
      haveHeader_ = true;
      payload_.clear();
    } else {
      // Grown as bytes arrive, never to the size a header merely claims.
      payload_.insert(payload_.end(), buffer, buffer + n);
    }
    if (haveHeader_ && payload_.size() == parsed_.size) {
      out.push_back(view::openPayload(parsed_, payload_.data(), limits_));
      header_.clear();
      payload_.clear();
      haveHeader_ = false;
    }
  }
}

void OutBuffer::put(std::vector<uint8_t>&& bytes) {
  if (empty()) {
    bytes_ = std::move(bytes);
    offset_ = 0;
    return;
  }
  bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
}

size_t OutBuffer::writeTo(const Socket& socket) {
  size_t written = 0;
  while (!empty()) {
    const ssize_t n =
        ::send(socket.fd(), bytes_.data() + offset_, bytes_.size() - offset_, MSG_NOSIGNAL);
    if (n > 0) {
      offset_ += static_cast<size_t>(n);
      written += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
    if (n < 0 && errno == EINTR) continue;
    throw std::runtime_error(std::string("the connection failed: ") + std::strerror(errno));
  }
  if (empty()) {
    bytes_ = {};  // its memory goes with it: one frame's message is the most kept per viewer
    offset_ = 0;
  }
  return written;
}

}  // namespace prism
