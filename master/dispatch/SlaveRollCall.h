// The start of a job has phases in which rank 0 waits for one word from every slave before it
// goes on: each slave's Hello (what its CPU runs) before the scene is broadcast, and each
// slave's SceneAccepted (the scene fits its memory) before any rank builds. This is that wait.
#pragma once

#include <string>
#include <vector>

#include "wire/Messages.h"

namespace prism {

class Transport;

// The first message of each slave (index: rank; rank 0's entry is left empty), each of type
// `expected`. Waits up to timeoutSeconds in all. Throws std::runtime_error "rank k: text" for a
// slave's Error, "rank k sent Ready before Hello" for another type, and "rank k " + silence
// for a slave not heard in time.
std::vector<wire::Message> firstMessageOfEachSlave(Transport& cluster, wire::MessageType expected,
                                                   double timeoutSeconds,
                                                   const std::string& silence);

}  // namespace prism
