#include "master/remote/WakePipe.h"

#include <fcntl.h>
#include <unistd.h>

#include <stdexcept>

namespace prism {

WakePipe::WakePipe() {
  if (::pipe2(fds_, O_NONBLOCK | O_CLOEXEC) != 0) {
    throw std::runtime_error("cannot make the server's wake-up pipe");
  }
}

WakePipe::~WakePipe() {
  ::close(fds_[0]);
  ::close(fds_[1]);
}

void WakePipe::wake(bool urgent) {
  const char byte = urgent ? 'u' : 'n';
  [[maybe_unused]] const ssize_t n = ::write(fds_[1], &byte, 1);
}

WakePipe::Woken WakePipe::drain() {
  char buffer[64];
  Woken woken;
  ssize_t n;
  while ((n = ::read(fds_[0], buffer, sizeof buffer)) > 0) {
    woken.any = true;
    for (ssize_t i = 0; i < n; ++i) woken.urgent = woken.urgent || buffer[i] == 'u';
  }
  return woken;
}

}  // namespace prism
