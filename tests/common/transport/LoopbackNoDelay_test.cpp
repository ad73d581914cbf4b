#include "transport/LoopbackNoDelay.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <ifaddrs.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

namespace prism {
namespace {

bool noDelay(int fd) {
  int value = 0;
  socklen_t length = sizeof value;
  EXPECT_EQ(getsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &value, &length), 0);
  return value != 0;
}

// A TCP connection from a client socket to a listener bound to `address`: the client, the
// accepted end and the listener.
struct TcpConnection {
  int listener = -1;
  int client = -1;
  int accepted = -1;

  explicit TcpConnection(in_addr_t address) {
    listener = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in where{};
    where.sin_family = AF_INET;
    where.sin_addr.s_addr = address;
    socklen_t length = sizeof where;
    if (bind(listener, reinterpret_cast<sockaddr*>(&where), length) != 0 ||
        listen(listener, 1) != 0 ||
        getsockname(listener, reinterpret_cast<sockaddr*>(&where), &length) != 0) {
      return;
    }
    client = socket(AF_INET, SOCK_STREAM, 0);
    if (connect(client, reinterpret_cast<sockaddr*>(&where), length) != 0) return;
    accepted = accept(listener, nullptr, nullptr);
  }
  ~TcpConnection() {
    for (int fd : {listener, client, accepted}) {
      if (fd >= 0) close(fd);
    }
  }
  bool connected() const { return accepted >= 0; }
};

TEST(LoopbackNoDelay, BothEndsOfALoopbackTcpConnectionSendSmallMessagesAtOnce) {
  TcpConnection loopback(htonl(INADDR_LOOPBACK));
  ASSERT_TRUE(loopback.connected());
  ASSERT_FALSE(noDelay(loopback.client));  // Linux's default: Nagle on
  ASSERT_FALSE(noDelay(loopback.accepted));

  EXPECT_GE(disableNagleOnLoopbackConnections(), 2);
  EXPECT_TRUE(noDelay(loopback.client));
  EXPECT_TRUE(noDelay(loopback.accepted));
  EXPECT_FALSE(noDelay(loopback.listener)) << "a listening socket has no peer: left alone";
}

TEST(LoopbackNoDelay, OtherSocketsAreLeftAlone) {
  int local[2];
  ASSERT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, local), 0);
  const int datagram = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in loopback{};
  loopback.sin_family = AF_INET;
  loopback.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  loopback.sin_port = htons(9);
  ASSERT_EQ(connect(datagram, reinterpret_cast<sockaddr*>(&loopback), sizeof loopback), 0);

  EXPECT_EQ(disableNagleOnLoopbackConnections(), 0);
  for (int fd : {local[0], local[1], datagram}) close(fd);
}

// The first IPv4 address of this machine outside 127.0.0.0/8, if it has one.
bool outsideAddress(in_addr_t& address) {
  ifaddrs* interfaces = nullptr;
  if (getifaddrs(&interfaces) != 0) return false;
  bool found = false;
  for (const ifaddrs* i = interfaces; i && !found; i = i->ifa_next) {
    if (!i->ifa_addr || i->ifa_addr->sa_family != AF_INET) continue;
    address = reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr.s_addr;
    found = (ntohl(address) >> 24) != 127;
  }
  freeifaddrs(interfaces);
  return found;
}

TEST(LoopbackNoDelay, AConnectionToAnotherAddressKeepsNagle) {
  in_addr_t address = 0;
  if (!outsideAddress(address)) GTEST_SKIP() << "this machine has no IPv4 address but loopback";
  TcpConnection outside(address);
  if (!outside.connected()) GTEST_SKIP() << "cannot connect to this machine's own address";

  EXPECT_EQ(disableNagleOnLoopbackConnections(), 0);
  EXPECT_FALSE(noDelay(outside.client));
  EXPECT_FALSE(noDelay(outside.accepted));
}

}  // namespace
}  // namespace prism
