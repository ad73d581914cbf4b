// The secret a viewer shows before a job serving its live session reads anything else from it:
// 256 random bits per job from OpenSSL's generator, written as 64 hex digits, compared in
// constant time (CRYPTO_memcmp), so the time a wrong guess takes says nothing of the right one.
#pragma once

#include <string>

namespace prism {

// A fresh token; throws std::runtime_error when the generator cannot be seeded.
std::string newAccessToken();

// Whether `offered` is `expected` (the comparison's time does not depend on where they differ).
bool tokenMatches(const std::string& offered, const std::string& expected);

// Whether text is a token as newAccessToken writes it (64 lowercase hex digits).
bool isWellFormedToken(const std::string& text);

}  // namespace prism
