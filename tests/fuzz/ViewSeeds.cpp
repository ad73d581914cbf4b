// Writes the view fuzzer's seeds into tests/fuzz/corpus/view: every message of ViewExamples.h
// whole (for the envelope checks) and as its fields behind a type byte (the harness's second
// form), and two refused inputs:
//   build/tests/fuzz/prism_fuzz_view_seeds tests/fuzz/corpus/view
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz/ViewExamples.h"
#include "wire/FieldCodec.h"

namespace {

void writeFile(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

int main(int argc, char** argv) {
  using namespace prism;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  for (const auto& [name, bytes] : fuzz::viewExamples()) {
    writeFile(dir + "/" + name + ".msg", bytes);
    const view::Message message =
        view::decodeMessage(bytes.data(), bytes.size(), view::kServerToClient);
    std::vector<uint8_t> typed = {static_cast<uint8_t>(message.type)};
    typed.insert(typed.end(), message.payload.begin(), message.payload.end());
    writeFile(dir + "/" + name + ".typed", typed);
  }
  writeFile(dir + "/garbage.bin", {'G', 'E', 'T', ' ', '/', '\n'});
  std::vector<uint8_t> wrongVersion = fuzz::viewExamples().front().second;
  wrongVersion[4] = 99;
  writeFile(dir + "/wrong-version.msg", wrongVersion);
  return 0;
}
