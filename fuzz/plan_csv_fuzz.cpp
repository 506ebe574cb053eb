// Plan CSV (t,x,y,z,yaw with a header) -> PlanFile.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/planning/plan_file.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)ferret::parse_plan(ferret::fuzz::as_string(data, size), "plan.csv");
  } catch (const ferret::InputError&) {
  }
  return 0;
}
