// What a slave does with each message from rank 0: one handler per message type, all of them
// and the table that names them in SlaveHandlers.cpp, the one place a new message type touches
// on the slave side. Handlers run on the message loop's thread with SlaveWork::loopLock held.
#pragma once

#include <cstdint>
#include <vector>

#include "wire/Messages.h"

namespace prism {

struct SlaveWork;

// Whether the message loop goes on after a message (Stop: the master's Shutdown).
enum class AfterMessage { Continue, Stop };

// Serves one message with the handler of its type; a type a slave never receives (Ready, a
// TileResult, ...) is ignored. `bytes`: the message as it came. Throws on a message that
// cannot be served (malformed, or naming a photon map this rank lacks): the loop reports it.
AfterMessage handleMessage(SlaveWork& work, const wire::Message& message,
                           const std::vector<uint8_t>& bytes);

}  // namespace prism
