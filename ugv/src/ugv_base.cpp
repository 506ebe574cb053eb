#include "ferret/ugv/ugv_base.hpp"

#include <array>

namespace ferret {

const char* to_string(UgvFault fault) {
  switch (fault) {
    case UgvFault::kLinkLost:
      return "link_lost";
    case UgvFault::kProtocolVersion:
      return "protocol_version";
    case UgvFault::kDrive:
      return "drive";
    case UgvFault::kSensor:
      return "sensor";
    case UgvFault::kCamera:
      return "camera";
    case UgvFault::kEpm:
      return "epm";
  }
  return "unknown";
}

std::string describe_faults(std::uint32_t faults) {
  static constexpr std::array kAll = {UgvFault::kLinkLost, UgvFault::kProtocolVersion,
                                      UgvFault::kDrive,    UgvFault::kSensor,
                                      UgvFault::kCamera,   UgvFault::kEpm};
  std::string out;
  for (const UgvFault f : kAll)
    if (faults & static_cast<std::uint32_t>(f))
      out += (out.empty() ? "" : ", ") + std::string(to_string(f));
  return out.empty() ? "none" : out;
}

}  // namespace ferret
