// libFuzzer's entry point for one harness: tests/fuzz/CMakeLists.txt compiles this file once per
// harness with PRISM_FUZZ_HARNESS naming it. Uncaught exceptions abort, which libFuzzer reports
// as a crash with the input saved.
#include "fuzz/Harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prism::fuzz::PRISM_FUZZ_HARNESS(data, size);
  return 0;
}
