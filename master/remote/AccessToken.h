// The secret a viewer shows before a job serving its live session reads anything else from it:
// 256 random bits per job from libsodium's generator (the kernel's, through randombytes_buf),
// written as 64 hex digits, compared in constant time (sodium_memcmp), so the time a wrong
// guess takes says nothing of the right one. libsodium rather than OpenSSL's libcrypto: both do
// this, and libcrypto cost every process 2 ms at start-up, libsodium 0.15 (docs/dependencies.md).
#pragma once

#include <string>

namespace prism {

// A fresh token; throws std::runtime_error when libsodium cannot start.
std::string newAccessToken();

// Whether `offered` is `expected` (the comparison's time does not depend on where they differ).
bool tokenMatches(const std::string& offered, const std::string& expected);

// Whether text is a token as newAccessToken writes it (64 lowercase hex digits).
bool isWellFormedToken(const std::string& text);

}  // namespace prism
