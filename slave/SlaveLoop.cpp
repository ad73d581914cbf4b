#include "slave/SlaveLoop.h"

#include "slave/FaultInjectingTransport.h"
#include "slave/SlaveSession.h"

namespace prism {

SlaveEnd runSlave(Transport& session, const DistributionOptions& options,
                  const MemoryLimit& memoryLimit) {
  if (!options.fault.appliesTo(session.rank())) {
    return SlaveSession(session, options, memoryLimit).run();
  }
  FaultInjectingTransport faulty(session, options.fault.kind);
  return SlaveSession(faulty, options, memoryLimit).run();
}

}  // namespace prism
