#include "ferret/tether_model/winch_controllers.hpp"

#include <array>

#include "ferret/core/yaml_emit.hpp"

namespace ferret::tether {
namespace {

using Mpc = TautTetherMpc::Options;
using Baseline = FeedForwardPid::Options;

// Each key once, with its range: the reader and the emitter walk the same tables.
template <class O>
struct NumberKey {
  const char* key;
  double lo, hi;
  double& (*field)(O&);
};
template <class O>
struct FlagKey {
  const char* key;
  bool& (*field)(O&);
};

constexpr std::array<NumberKey<Mpc>, 18> kMpcNumbers{{
    {"prediction_dt_s", 1e-3, 1.0, [](Mpc& m) -> double& { return m.prediction_dt_s; }},
    {"acceleration_time_s", 0.0, 10.0, [](Mpc& m) -> double& { return m.acceleration_time_s; }},
    {"give_back_stiffness_factor", 1.0, 100.0,
     [](Mpc& m) -> double& { return m.give_back_stiffness_factor; }},
    {"weight_slack", 0.0, 1e6, [](Mpc& m) -> double& { return m.weight_slack; }},
    {"weight_command_rate", 0.0, 1e6, [](Mpc& m) -> double& { return m.weight_command_rate; }},
    {"weight_feedforward", 1e-6, 1e6, [](Mpc& m) -> double& { return m.weight_feedforward; }},
    {"weight_terminal", 0.0, 1e6, [](Mpc& m) -> double& { return m.weight_terminal; }},
    {"weight_soft_linear", 0.0, 1e8, [](Mpc& m) -> double& { return m.soft_linear_weight; }},
    {"weight_stretch_linear", 0.0, 1e8, [](Mpc& m) -> double& { return m.stretch_linear_weight; }},
    {"weight_soft_quadratic", 1e-6, 1e8, [](Mpc& m) -> double& { return m.soft_quadratic_weight; }},
    {"ugv_velocity_error_mps", 0.0, 10.0,
     [](Mpc& m) -> double& { return m.ugv_velocity_error.sigma_mps; }},
    {"ugv_velocity_error_time_s", 1e-3, 100.0,
     [](Mpc& m) -> double& { return m.ugv_velocity_error.time_s; }},
    {"ugv_velocity_error_window_s", 1e-3, 100.0,
     [](Mpc& m) -> double& { return m.ugv_velocity_error.window_s; }},
    {"ugv_velocity_error_prior_log_odds", 0.0, 100.0,
     [](Mpc& m) -> double& { return m.ugv_velocity_error.prior_log_odds; }},
    {"ugv_velocity_error_prior_log_odds_with_lag", 0.0, 100.0,
     [](Mpc& m) -> double& { return m.ugv_velocity_error.prior_log_odds_with_lag; }},
    {"ugv_velocity_error_long_window_s", 1e-3, 1e4,
     [](Mpc& m) -> double& { return m.ugv_velocity_error.long_window_s; }},
    {"ugv_response_window_s", 1e-3, 1e4,
     [](Mpc& m) -> double& { return m.ugv_response_identification.window_s; }},
    {"ugv_response_prior_log_odds", 0.0, 1e4,
     [](Mpc& m) -> double& { return m.ugv_response_identification.prior_log_odds; }},
}};
constexpr std::array<FlagKey<Mpc>, 4> kMpcFlags{{
    {"use_preview", [](Mpc& m) -> bool& { return m.use_preview; }},
    {"rate_penalty_about_tracking_command",
     [](Mpc& m) -> bool& { return m.rate_penalty_about_tracking_command; }},
    {"give_back_at_stopping_speed", [](Mpc& m) -> bool& { return m.give_back_at_stopping_speed; }},
    {"identify_ugv_response",
     [](Mpc& m) -> bool& { return m.ugv_response_identification.enabled; }},
}};
constexpr const char* kHorizon = "horizon";

constexpr std::array<NumberKey<Baseline>, 4> kBaselineNumbers{{
    {"kp_per_s", 0.0, 1e3, [](Baseline& b) -> double& { return b.kp_per_s; }},
    {"ki_per_s2", 0.0, 1e4, [](Baseline& b) -> double& { return b.ki_per_s2; }},
    {"kd", 0.0, 1e2, [](Baseline& b) -> double& { return b.kd; }},
    {"feedforward_gain", 0.0, 2.0, [](Baseline& b) -> double& { return b.feedforward_gain; }},
}};
constexpr std::array<FlagKey<Baseline>, 1> kBaselineFlags{{
    {"use_preview", [](Baseline& b) -> bool& { return b.use_preview; }},
}};

template <class O, std::size_t N, std::size_t M>
void read_keys(const yaml::MapReader& r, const std::array<NumberKey<O>, N>& numbers,
               const std::array<FlagKey<O>, M>& flags, O& o) {
  for (const auto& k : numbers) k.field(o) = r.get_in_range_or(k.key, k.lo, k.hi, k.field(o));
  for (const auto& k : flags) k.field(o) = r.get_or<bool>(k.key, k.field(o));
}

template <class O, std::size_t N, std::size_t M>
void emit_keys(YAML::Emitter& e, const std::array<NumberKey<O>, N>& numbers,
               const std::array<FlagKey<O>, M>& flags, O o) {
  for (const auto& k : numbers) internal::emit_key_number(e, k.key, k.field(o));
  for (const auto& k : flags) e << YAML::Key << k.key << YAML::Value << k.field(o);
}

template <class O, std::size_t N, std::size_t M>
std::vector<std::string_view> keys_of(const std::array<NumberKey<O>, N>& numbers,
                                      const std::array<FlagKey<O>, M>& flags) {
  std::vector<std::string_view> keys;
  for (const auto& k : numbers) keys.push_back(k.key);
  for (const auto& k : flags) keys.push_back(k.key);
  return keys;
}

}  // namespace

WinchControllerOptions WinchControllerOptions::following(const TautControlOptions& control) {
  WinchControllerOptions o;
  o.mpc.control = o.baseline.control = control;
  // The velocity-error filter and the response identification as the common options
  // have them (off by default; the mission's winch turns them on).
  o.mpc.ugv_velocity_error = control.ugv_velocity_error;
  o.mpc.ugv_response_identification = control.ugv_response_identification;
  return o;
}

void register_builtin_tether_controllers(TetherControllerRegistry& registry) {
  registry.add(
      "mpc", "taut-tether MPC on the required length's prediction",
      [](const WinchControllerSetup& s) {
        TautTetherMpc::Options o = s.own.mpc;
        o.control = s.control;
        return std::make_unique<TautTetherMpc>(o, s.model);
      },
      "MPC");
  registry.add("baseline", "feed-forward of the required length's rate plus a PID on slack",
               [](const WinchControllerSetup& s) {
                 FeedForwardPid::Options o = s.own.baseline;
                 o.control = s.control;
                 return std::make_unique<FeedForwardPid>(o, s.model);
               });
}

const TetherControllerRegistry& tether_controllers() {
  return filled_registry<TetherControllerRegistry, register_builtin_tether_controllers>();
}

std::unique_ptr<TetherController> make_tether_controller(
    std::string_view name, const TautControlOptions& options,
    std::shared_ptr<const RequiredLengthModel> model) {
  return tether_controllers().make(
      name, {options, WinchControllerOptions::following(options), std::move(model)},
      "winch controller");
}

std::vector<std::string> tether_controller_names() { return tether_controllers().names(); }

void read_mpc_options(const yaml::MapReader& r, TautTetherMpc::Options& m) {
  std::vector<std::string_view> keys = keys_of(kMpcNumbers, kMpcFlags);
  keys.push_back(kHorizon);
  r.allow_only(keys);
  m.horizon = static_cast<int>(r.get_in_range_or(kHorizon, 2, 200, m.horizon));
  if (r.has(kHorizon) && r.get<double>(kHorizon) != m.horizon)
    r.fail(kHorizon, "an integer in [2, 200]");
  read_keys(r, kMpcNumbers, kMpcFlags, m);
}

void read_baseline_options(const yaml::MapReader& r, FeedForwardPid::Options& b) {
  r.allow_only(keys_of(kBaselineNumbers, kBaselineFlags));
  read_keys(r, kBaselineNumbers, kBaselineFlags, b);
}

void read_winch_controller_options(const yaml::MapReader& r, WinchControllerOptions& o) {
  r.allow_only({"mpc", "baseline"});
  if (const auto m = r.optional_child("mpc")) read_mpc_options(*m, o.mpc);
  if (const auto b = r.optional_child("baseline")) read_baseline_options(*b, o.baseline);
}

void emit_winch_controller_options(YAML::Emitter& e, const WinchControllerOptions& o) {
  e << YAML::BeginMap;
  e << YAML::Key << "mpc" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << kHorizon << YAML::Value << o.mpc.horizon;
  emit_keys(e, kMpcNumbers, kMpcFlags, o.mpc);
  e << YAML::EndMap;
  e << YAML::Key << "baseline" << YAML::Value << YAML::BeginMap;
  emit_keys(e, kBaselineNumbers, kBaselineFlags, o.baseline);
  e << YAML::EndMap << YAML::EndMap;
}

}  // namespace ferret::tether
