// TCP for the view protocol: an owned socket, listening, accepting, connecting with a timeout,
// and the two halves of a non-blocking stream of view messages (MessageReader checks each
// header before it reads the payload, and grows the payload only as its bytes arrive;
// OutBuffer holds what is yet to be written). POSIX sockets only; no threads here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "master/remote/Endpoint.h"
#include "master/remote/ViewProtocol.h"

namespace prism {

class Socket {
 public:
  Socket() = default;
  explicit Socket(int fd) : fd_(fd) {}
  ~Socket() { close(); }
  Socket(Socket&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }
  Socket& operator=(Socket&& o) noexcept;
  Socket(const Socket&) = delete;
  Socket& operator=(const Socket&) = delete;

  int fd() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  explicit operator bool() const { return valid(); }
  void close();
  // Ends both directions now (a thread blocked reading it returns), keeping the descriptor.
  void shutdown();

 private:
  int fd_ = -1;
};

// Listens on endpoint (non-blocking; port 0: a free one). Returns the socket and sets `bound`
// to the address it listens on. Throws std::runtime_error naming the address.
Socket listenTcp(const Endpoint& endpoint, Endpoint* bound);
// The next connection waiting on listener, non-blocking; an invalid socket when none waits.
Socket acceptConnection(const Socket& listener);
// Connects (then non-blocking), waiting at most timeoutSeconds. Throws std::runtime_error
// saying what failed ("connection refused: is the job serving on 127.0.0.1:4050?").
Socket connectTcp(const Endpoint& endpoint, double timeoutSeconds);

// Writes all of bytes to a non-blocking socket, waiting for room at most timeoutSeconds in all.
// Throws std::runtime_error when the peer is gone or too slow.
void sendAll(const Socket& socket, const std::vector<uint8_t>& bytes, double timeoutSeconds);

class MessageReader {
 public:
  explicit MessageReader(const view::Limits& limits) : limits_(limits) {}

  // Reads what the socket holds now (it never blocks) and appends every whole message. Returns
  // false once the peer closed its side. Throws wire::WireError for a bad message (the
  // connection must then be dropped) and std::runtime_error for a socket error.
  bool readFrom(const Socket& socket, std::vector<view::Message>& out);
  // Limits for the messages from now on (a viewer learns the frame's size from the Welcome).
  void setLimits(const view::Limits& limits) { limits_ = limits; }
  // Bytes of a message begun but not finished.
  size_t pending() const { return header_.size() + payload_.size(); }

 private:
  view::Limits limits_;
  std::vector<uint8_t> header_;
  bool haveHeader_ = false;
  view::Header parsed_{};
  std::vector<uint8_t> payload_;
};

class OutBuffer {
 public:
  bool empty() const { return offset_ == bytes_.size(); }
  // Queues bytes behind what is there (taking the vector as it is when nothing is).
  void put(std::vector<uint8_t>&& bytes);
  // Writes what the socket takes now. Returns the bytes written; throws std::runtime_error when
  // the peer is gone.
  size_t writeTo(const Socket& socket);
  size_t size() const { return bytes_.size() - offset_; }

 private:
  std::vector<uint8_t> bytes_;
  size_t offset_ = 0;
};

}  // namespace prism
