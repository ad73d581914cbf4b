// Byte counts as people write and read them: "8G", "512M", "1.5 GiB".
#pragma once

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace prism {

// "8G", "8GB", "8GiB", "512M", "64k", "1.5T", "1000000" (bytes): binary units, case-insensitive.
// Throws std::invalid_argument for anything else, zero included.
uint64_t parseMemorySize(const std::string& text);

// "1.5 GiB", "312 KiB", "512 B".
std::string formatBytes(double bytes);

// a*b and a+b for byte counts, saturating at UINT64_MAX instead of wrapping, so an absurd request
// still compares as larger than any limit.
uint64_t saturatingMultiply(uint64_t a, uint64_t b);
uint64_t saturatingAdd(uint64_t a, uint64_t b);

// What a run may plan to use, and where that number came from (for the messages).
struct MemoryLimit {
  uint64_t bytes = std::numeric_limits<uint64_t>::max();  // default: no limit (tests, fuzzers)
  std::string source = "no limit";
};

// A request refused because of a limit; the message names what it would need and the limit.
class ResourceLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "WHAT needs 21.8 TiB (24000000000000 bytes); the memory limit is 16.0 GiB (17179869184 bytes,
// SOURCE): HINT".
std::string memoryRefusal(const std::string& what, uint64_t needed, const MemoryLimit& limit,
                          const std::string& hint);

}  // namespace prism
