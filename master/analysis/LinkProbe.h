// Measures the link between rank 0 and its slaves the way tiles travel: Echo messages through
// the transport and each slave's message loop, so the numbers include the loops' polling as
// well as MPI. Small messages give the latency, tile-result-sized ones the bandwidth. The
// scheduling simulator (master/analysis/TileScheduleSimulator.h) is fed with the result.
#pragma once

#include <cstddef>

#include "master/analysis/ScalingMetrics.h"
#include "master/analysis/TileScheduleSimulator.h"
#include "master/dispatch/SlaveLink.h"

namespace prism {

struct LinkMeasurement {
  LinkModel model;        // latency one way, bandwidth
  size_t smallBytes = 0;  // whole messages, envelope included
  size_t largeBytes = 0;
  int roundTrips = 0;           // per size and slave
  bool wakesOnMessage = false;  // rank 0's waits (Transport::wakesOnMessage)
  TimingSpread smallRoundTrip;  // over every slave's round trips
  TimingSpread largeRoundTrip;
};

// Ping-pongs with every slave in turn, roundTrips times per size. Latency: half the median
// small round trip. Bandwidth: the extra bytes of the large message over half the extra median
// round trip (infinite when the difference drowns in noise). Ready messages that arrive
// meanwhile go into the roster; a slave's Error is thrown as std::runtime_error.
LinkMeasurement measureLink(SlaveLink& link, size_t largePayloadBytes, int roundTrips);

}  // namespace prism
