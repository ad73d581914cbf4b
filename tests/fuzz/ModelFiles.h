// The files the OBJ and MTL harnesses hand the loader: two material libraries (one with a blank
// in its name) and a texture, so that fuzzed 'mtllib' and 'usemtl' lines and map_Kd statements
// reach the code that reads them.
#pragma once

#include <string>

#include "fuzz/MemoryFiles.h"

namespace prism::fuzz {

// A 2 x 2 texture, as a decoded PNG would give it.
inline TextureDesc smallTexture() {
  TextureDesc texture;
  texture.srgb.width = 2;
  texture.srgb.height = 2;
  texture.srgb.rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  return texture;
}

// fuzz.mtl defines a, b (textured), glass and mirror; "other lib.mtl" defines c and a again.
// extra is added at extraPath (the MTL harness's input).
inline MemoryFiles harnessFiles(const std::string& extraPath = {}, std::string extra = {}) {
  MemoryFiles files;
  files.add("fuzz.mtl",
            "newmtl a\nKd 0.5 0.2 0.1\nKs 0.3\nNs 20\nillum 2\n"
            "newmtl b\nKd 1 1 1\nmap_Kd -s 2 2 -o 0.5 0 tex.png\n"
            "newmtl glass\nKd 0\nKs 1\nNi 1.5\nTf 0.9\nillum 7\n"
            "newmtl mirror\nKs 0.8\nillum 3\nmap_Bump bump.png\n");
  files.add("other lib.mtl", "newmtl c\nKd 0 0.5 0\nd 0.5\nmap_Kd missing.png\nnewmtl a\n");
  files.addTexture("tex.png", smallTexture());
  if (!extraPath.empty()) files.add(extraPath, std::move(extra));
  return files;
}

}  // namespace prism::fuzz
