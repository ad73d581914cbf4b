// The bytes of a mesh file, for as long as its parser needs them. A regular file is mapped
// read-only (no copy: the parser's threads read the page cache directly and fault it in
// together); a pipe or a file that will not map is read into memory instead.
#pragma once

#include <string>
#include <string_view>

#include "util/FileLoc.h"
#include "util/MemorySize.h"

namespace prism {

class MeshFileBytes {
 public:
  // Opens path. referencedFrom is where the scene names it: a missing or unreadable file, or one
  // larger than the memory limit, is reported there (SceneError), before a byte is read.
  MeshFileBytes(const std::string& path, const FileLoc& referencedFrom, const MemoryLimit& limit);
  ~MeshFileBytes();
  MeshFileBytes(const MeshFileBytes&) = delete;
  MeshFileBytes& operator=(const MeshFileBytes&) = delete;

  std::string_view bytes() const { return {data_, size_}; }
  // Gives the bytes back (unmaps or frees them) as soon as the parser is done with them, so they
  // do not sit under what is built from them.
  void release();

 private:
  const char* data_ = nullptr;
  size_t size_ = 0;
  bool mapped_ = false;
  std::string read_;  // the bytes of a file that was read rather than mapped
};

}  // namespace prism
