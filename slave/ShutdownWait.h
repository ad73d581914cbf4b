// After a failure, or when interrupted, a slave still waits (bounded) for the master's
// Shutdown, so the job ends through rank 0's clear message rather than this rank vanishing.
#pragma once

namespace prism {

class Transport;

// Waits up to timeoutSeconds for rank 0's Shutdown and acknowledges it; other messages (and
// malformed ones) are dropped. Whether the Shutdown came.
bool awaitShutdown(Transport& transport, double timeoutSeconds);

}  // namespace prism
