#include "master/remote/AccessToken.h"

#include <sodium.h>

#include <array>
#include <stdexcept>

namespace prism {
namespace {
constexpr size_t kTokenBytes = 32;  // 256 bits
}  // namespace

std::string newAccessToken() {
  if (sodium_init() < 0) {
    throw std::runtime_error("cannot make an access token: libsodium did not initialise");
  }
  std::array<unsigned char, kTokenBytes> random{};
  randombytes_buf(random.data(), random.size());
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (const unsigned char b : random) {
    token += kHex[b >> 4];
    token += kHex[b & 15];
  }
  sodium_memzero(random.data(), random.size());
  return token;
}

bool tokenMatches(const std::string& offered, const std::string& expected) {
  // The length is not secret (every token has 64 digits); the digits are.
  if (offered.size() != expected.size() || expected.empty()) return false;
  return sodium_memcmp(offered.data(), expected.data(), expected.size()) == 0;
}

bool isWellFormedToken(const std::string& text) {
  if (text.size() != 2 * kTokenBytes) return false;
  for (const char c : text) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

}  // namespace prism
