#pragma once
// The flight adapter protocol's conformance checks, for whoever writes an adapter
// (`ferret flight-adapter check --adapter HOST:PORT`, docs/flight_adapter.md): what a
// vehicle on the ground can be asked safely. Nothing here commands a take-off, a
// set-point or a landing; the flying half of the suite runs against the reference
// adapter in ferret's tests (tests/sim/flight_adapter_test.cpp).

#include <string>
#include <vector>

#include "ferret/link/message_stream.hpp"

namespace ferret {

struct AdapterCheck {
  std::string name;  ///< "hello", "state", "marker_frame", ...
  bool passed = false;
  std::string detail;  ///< what was seen (the failure's reason, or a summary)
};

/// Runs every ground check in order over `channel`. A check that fails does not stop
/// the others (but a channel that breaks fails the rest with its error).
[[nodiscard]] std::vector<AdapterCheck> check_flight_adapter(link::RpcChannel& channel);

}  // namespace ferret
