#include "ferret/planning/ompl_setup.hpp"

#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <functional>
#include <map>
#include <mutex>
#include <optional>

#include "ferret/core/error.hpp"

namespace og = ompl::geometric;

namespace ferret {
namespace {
using Factory =
    std::function<std::shared_ptr<ompl::base::Planner>(const ompl::base::SpaceInformationPtr&)>;
const std::map<std::string, Factory>& factories() {
  static const std::map<std::string, Factory> f{
      {"rrtconnect", [](const auto& si) { return std::make_shared<og::RRTConnect>(si); }},
      {"rrt", [](const auto& si) { return std::make_shared<og::RRT>(si); }},
      {"rrtstar", [](const auto& si) { return std::make_shared<og::RRTstar>(si); }},
      {"prm", [](const auto& si) { return std::make_shared<og::PRM>(si); }},
      {"lazyprm", [](const auto& si) { return std::make_shared<og::LazyPRM>(si); }},
      {"kpiece", [](const auto& si) { return std::make_shared<og::KPIECE1>(si); }},
      {"bkpiece", [](const auto& si) { return std::make_shared<og::BKPIECE1>(si); }},
      {"est", [](const auto& si) { return std::make_shared<og::EST>(si); }},
      {"bitstar", [](const auto& si) { return std::make_shared<og::BITstar>(si); }},
  };
  return f;
}
}  // namespace

bool seed_ompl_once(std::uint64_t seed) {
  static std::mutex mutex;
  static std::optional<std::uint64_t> seeded;
  std::lock_guard lock(mutex);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  if (seeded) return *seeded == seed;
  // OMPL takes a 32-bit-ish seed (boost::uint32_t); fold the 64 bits.
  const auto folded = static_cast<std::uint_fast32_t>((seed ^ (seed >> 32)) & 0x7fffffffu);
  ompl::RNG::setSeed(folded == 0 ? 1 : folded);  // OMPL ignores a zero seed
  seeded = seed;
  return true;
}

const std::vector<std::string>& ompl_planner_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, f] : factories()) n.push_back(name);
    return n;
  }();
  return names;
}

std::shared_ptr<ompl::base::Planner> make_ompl_planner(
    const std::string& name, const std::shared_ptr<ompl::base::SpaceInformation>& si,
    const std::string& source) {
  const auto it = factories().find(name);
  if (it == factories().end()) {
    std::string list;
    for (const auto& n : ompl_planner_names()) list += (list.empty() ? "" : ", ") + n;
    throw InputError(source, "", "one of " + list, name);
  }
  return it->second(si);
}

}  // namespace ferret
