#include "parse/MeshFileBytes.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace prism {

namespace {

// Closes a descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

MeshFileBytes::MeshFileBytes(const std::string& path, const FileLoc& referencedFrom,
                             const MemoryLimit& limit) {
  auto fail = [&](int error) {
    throw SceneError(referencedFrom,
                     "cannot open mesh file '" + path + "': " + std::strerror(error));
  };
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (file.fd < 0) fail(errno);
  struct stat status {};
  if (::fstat(file.fd, &status) != 0) fail(errno);
  if (S_ISDIR(status.st_mode)) fail(EISDIR);
  const bool regular = S_ISREG(status.st_mode);
  const uint64_t size = regular ? static_cast<uint64_t>(status.st_size) : 0;
  if (size > limit.bytes) {
    throw SceneError(referencedFrom, memoryRefusal("reading mesh file '" + path + "'", size, limit,
                                                   "simplify the mesh or raise --memory-limit"));
  }
  if (regular && size > 0) {
    void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, file.fd, 0);
    if (map != MAP_FAILED) {
      // Read front to back by every parser; the kernel may read ahead generously.
      ::madvise(map, size, MADV_SEQUENTIAL);
      ::madvise(map, size, MADV_WILLNEED);
      data_ = static_cast<const char*>(map);
      size_ = size;
      mapped_ = true;
      return;
    }
  }
  // A pipe, or a file system that does not map: read in chunks.
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(errno);
    if (n == 0) break;
    read_.append(buffer, static_cast<size_t>(n));
    if (read_.size() > limit.bytes) {
      throw SceneError(referencedFrom,
                       memoryRefusal("reading mesh file '" + path + "'", read_.size(), limit,
                                     "simplify the mesh or raise --memory-limit"));
    }
  }
  data_ = read_.data();
  size_ = read_.size();
}

MeshFileBytes::~MeshFileBytes() {
  release();
}

void MeshFileBytes::release() {
  if (mapped_) ::munmap(const_cast<char*>(data_), size_);
  mapped_ = false;
  std::string().swap(read_);
  data_ = nullptr;
  size_ = 0;
}

}  // namespace prism
