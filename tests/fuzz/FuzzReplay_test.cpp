// Replays every committed fuzz input (the seed corpus, grown by long runs, and every input that
// once crashed) through the harnesses in the normal test build, so regressions are caught
// without clang or libFuzzer.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "fuzz/Harnesses.h"
#include "wire/Messages.h"

namespace prism::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> inputsIn(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file() && entry.path().filename().string()[0] != '.') {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Counts {
  int accepted = 0;
  int rejected = 0;
};

Counts replay(const Harness& harness, const fs::path& dir) {
  Counts counts;
  for (const fs::path& file : inputsIn(dir)) {
    SCOPED_TRACE(file.string());
    const std::vector<uint8_t> bytes = readBytes(file);
    try {
      if (harness.run(bytes.data(), bytes.size()) == Outcome::Accepted) {
        ++counts.accepted;
      } else {
        ++counts.rejected;
      }
    } catch (const std::exception& e) {
      ADD_FAILURE() << file.string() << ": " << e.what();
    }
  }
  return counts;
}

const fs::path kFuzzDir = fs::path(PRISM_SOURCE_DIR) / "tests" / "fuzz";

}  // namespace

// Names the harness in test output instead of printing its bytes.
void PrintTo(const Harness& harness, std::ostream* os) {
  *os << harness.name;
}

namespace {

class FuzzReplay : public testing::TestWithParam<Harness> {};

// The corpus holds valid and invalid inputs alike (example scenes, bad-input files, what the
// fuzzer kept): both paths of each harness are replayed, and an empty folder is an error rather
// than a silent pass.
TEST_P(FuzzReplay, CorpusIsAcceptedOrRejectedCleanly) {
  const Counts counts = replay(GetParam(), kFuzzDir / "corpus" / GetParam().name);
  EXPECT_GT(counts.accepted, 0) << "no corpus input is accepted";
  EXPECT_GT(counts.rejected, 0) << "no corpus input is rejected";
}

TEST_P(FuzzReplay, EveryRegressionIsHandledCleanly) {
  replay(GetParam(), kFuzzDir / "regressions" / GetParam().name);
}

INSTANTIATE_TEST_SUITE_P(Harnesses, FuzzReplay, testing::ValuesIn(harnesses()),
                         [](const testing::TestParamInfo<Harness>& info) {
                           return std::string(info.param.name);
                         });

// The wire harness must reach the payload decoders, not only the envelope check.
TEST(WireHarness, TypeBytePlusValidPayloadIsAccepted) {
  wire::ByteWriter payload;
  payload.writeF64(0.5);  // Ready: build seconds, threads, start seconds, MPI_Init seconds
  payload.writeI32(4);
  payload.writeF64(0.25);
  payload.writeF64(0.125);
  std::vector<uint8_t> input = {static_cast<uint8_t>(wire::MessageType::Ready)};
  input.insert(input.end(), payload.bytes().begin(), payload.bytes().end());
  EXPECT_EQ(fuzzWire(input.data(), input.size()), Outcome::Accepted);
  input.pop_back();  // truncated payload
  EXPECT_EQ(fuzzWire(input.data(), input.size()), Outcome::Rejected);
}

TEST(SceneHarnesses, ExampleSceneIsAcceptedAndGarbageRejected) {
  const std::vector<uint8_t> scene = readBytes(fs::path(PRISM_SOURCE_DIR) / "scenes/default.yaml");
  EXPECT_EQ(fuzzYamlScene(scene.data(), scene.size()), Outcome::Accepted);
  const std::string garbage = "camera: [";
  EXPECT_EQ(fuzzYamlScene(reinterpret_cast<const uint8_t*>(garbage.data()), garbage.size()),
            Outcome::Rejected);
  EXPECT_EQ(fuzzNff(reinterpret_cast<const uint8_t*>(garbage.data()), garbage.size()),
            Outcome::Rejected);
  EXPECT_EQ(fuzzObj(reinterpret_cast<const uint8_t*>(garbage.data()), garbage.size()),
            Outcome::Rejected);
}

}  // namespace
}  // namespace prism::fuzz
