#include "master/remote/Endpoint.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace prism {
namespace {

TEST(Endpoint, PortAloneMeansLoopback) {
  const Endpoint e = parseEndpoint("4050");
  EXPECT_EQ(e.host, "127.0.0.1");
  EXPECT_EQ(e.port, 4050);
  EXPECT_EQ(e.text(), "127.0.0.1:4050");
}

TEST(Endpoint, HostPortAndBracketedIpv6) {
  EXPECT_EQ(parseEndpoint("node12:0").host, "node12");
  EXPECT_EQ(parseEndpoint("node12:0").port, 0);
  const Endpoint v6 = parseEndpoint("[::1]:9000");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(v6.port, 9000);
  EXPECT_EQ(v6.text(), "[::1]:9000");
}

TEST(Endpoint, BadAddressesAreClearErrors) {
  const auto message = [](const std::string& text) {
    try {
      parseEndpoint(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("70000"), "port 70000 is out of range (0 to 65535)");
  EXPECT_EQ(message("host:"), "'host:' has no port number (HOST:PORT or PORT)");
  EXPECT_EQ(message(":80"), "':80' has no host");
  EXPECT_EQ(message("[::1]"), "'[::1]' is not [IPv6]:PORT");
  EXPECT_EQ(message("a:b"), "'a:b' has no port number (HOST:PORT or PORT)");
}

TEST(Endpoint, LoopbackHostsAreKnown) {
  EXPECT_TRUE(isLoopbackHost("127.0.0.1"));
  EXPECT_TRUE(isLoopbackHost("127.1.2.3"));
  EXPECT_TRUE(isLoopbackHost("::1"));
  EXPECT_TRUE(isLoopbackHost("localhost"));
  EXPECT_FALSE(isLoopbackHost("0.0.0.0"));
  EXPECT_FALSE(isLoopbackHost("10.0.0.5"));
  EXPECT_FALSE(isLoopbackHost("node12"));
  EXPECT_FALSE(isLoopbackHost("::"));
}

}  // namespace
}  // namespace prism
