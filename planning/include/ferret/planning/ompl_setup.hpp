#pragma once
// Process-wide OMPL settings. OMPL draws every planner's randomness from seeds made
// by one process-wide generator, which must be seeded before the first ompl::RNG
// exists (OMPL 1.5) and only once; later calls cannot make a run deterministic.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ompl::base {
class Planner;
class SpaceInformation;
}  // namespace ompl::base

namespace ferret {

/// Seeds OMPL's generator the first time it is called in a process and returns true;
/// later calls return true only when they ask for the same seed (nothing changes).
/// Also quiets OMPL's console output below warnings.
bool seed_ompl_once(std::uint64_t seed);

/// Names of the OMPL geometric planners `make_ompl_planner` knows.
[[nodiscard]] const std::vector<std::string>& ompl_planner_names();
/// An OMPL planner by name ("rrtconnect", "rrt", "rrtstar", "prm", "lazyprm", "kpiece",
/// "bkpiece", "est", "bitstar"); throws InputError (source `source`) for an unknown one.
[[nodiscard]] std::shared_ptr<ompl::base::Planner> make_ompl_planner(
    const std::string& name, const std::shared_ptr<ompl::base::SpaceInformation>& si,
    const std::string& source = "--planner");

}  // namespace ferret
