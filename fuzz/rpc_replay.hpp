#pragma once
// The protocol harnesses' client side: a channel that answers every call with the one
// reply under test (the flight adapter, the miniUGV base, the winch).

#include <string>

#include "ferret/link/message_stream.hpp"

namespace ferret::fuzz {

struct RpcReplay final : link::RpcChannel {
  link::StreamMessage reply;
  link::StreamMessage call(const std::string&) override { return reply; }
};

}  // namespace ferret::fuzz
