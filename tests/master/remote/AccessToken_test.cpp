#include "master/remote/AccessToken.h"

#include <gtest/gtest.h>

#include <set>

namespace prism {
namespace {

TEST(AccessToken, Is256RandomBitsAsHex) {
  std::set<std::string> seen;
  for (int i = 0; i < 100; ++i) {
    const std::string token = newAccessToken();
    EXPECT_TRUE(isWellFormedToken(token)) << token;
    seen.insert(token);
  }
  EXPECT_EQ(seen.size(), 100u);
}

TEST(AccessToken, MatchesOnlyItself) {
  const std::string token = newAccessToken();
  EXPECT_TRUE(tokenMatches(token, token));
  std::string last = token;
  last.back() = last.back() == '0' ? '1' : '0';
  EXPECT_FALSE(tokenMatches(last, token));
  EXPECT_FALSE(tokenMatches(token.substr(0, 63), token));
  EXPECT_FALSE(tokenMatches("", token));
  EXPECT_FALSE(tokenMatches("", ""));  // no token never opens anything
}

TEST(AccessToken, WellFormedMeans64LowercaseHexDigits) {
  EXPECT_FALSE(isWellFormedToken(std::string(63, 'a')));
  EXPECT_FALSE(isWellFormedToken(std::string(64, 'A')));
  EXPECT_FALSE(isWellFormedToken(std::string(64, 'g')));
  EXPECT_TRUE(isWellFormedToken(std::string(64, 'f')));
}

}  // namespace
}  // namespace prism
