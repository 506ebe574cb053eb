#include "ferret/uav/flight_adapter_check.hpp"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "ferret/uav/adapter_flight_controller.hpp"

namespace ferret {
namespace {

using nlohmann::json;

// A request the adapter must refuse (ok: false with an error text) without acting on it.
std::string refusal_problem(link::RpcChannel& channel, const std::string& request) {
  const link::StreamMessage m = channel.call(request);
  const json r = json::parse(m.header, nullptr, false);
  if (r.is_discarded() || !r.is_object()) return "the reply is not a JSON object";
  if (!r.contains("ok") || !r["ok"].is_boolean()) return "the reply has no boolean 'ok'";
  if (r["ok"].get<bool>()) return "accepted";
  if (!r.contains("error") || !r["error"].is_string() || r["error"].get<std::string>().empty())
    return "refused without an 'error' text";
  return "";
}

}  // namespace

std::vector<AdapterCheck> check_flight_adapter(link::RpcChannel& channel) {
  std::vector<AdapterCheck> checks;
  std::string broken;  // the channel's error once it broke
  const auto run = [&](const std::string& name, const std::function<std::string()>& body) {
    AdapterCheck c{name, false, {}};
    if (!broken.empty()) {
      c.detail = "not run: " + broken;
    } else {
      try {
        c.detail = body();
        c.passed = true;
      } catch (const FlightAdapterError& e) {
        c.detail = e.what();  // the adapter's answer was wrong: the next check may pass
      } catch (const link::StreamError& e) {
        c.detail = e.what();  // lost or silent: nothing more can be asked
        broken = e.what();
      } catch (const std::exception& e) {
        c.detail = e.what();
      }
    }
    checks.push_back(std::move(c));
  };

  std::unique_ptr<AdapterFlightController> flight;
  run("hello", [&] {
    flight = std::make_unique<AdapterFlightController>(channel, "hw");
    return fmt::format("protocol {}, adapter '{}'", kFlightAdapterProtocol, flight->adapter_name());
  });
  if (!flight && broken.empty()) broken = "no hello";  // every later check needs one
  FlightState before;
  run("state", [&] {
    before = flight->state();
    if (!(before.battery_fraction >= 0.0 && before.battery_fraction <= 1.0))
      throw std::runtime_error(
          fmt::format("'battery' {} is not in [0, 1]", before.battery_fraction));
    return fmt::format("p_W ({:.2f}, {:.2f}, {:.2f}), yaw {:.3f} rad, {}, battery {:.2f}{}",
                       before.p_W.x(), before.p_W.y(), before.p_W.z(), before.yaw_rad,
                       before.on_ground ? "on the ground" : "flying", before.battery_fraction,
                       before.rc_override ? ", RC override" : "");
  });
  const auto frame_check = [&](const auto& shot, const char* what) {
    const Eigen::Matrix4d& m = shot.X_WC.matrix();
    const Eigen::Matrix3d R = m.template topLeftCorner<3, 3>();
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 ||
        std::abs(R.determinant() - 1.0) > 1e-6 || m.row(3) != Eigen::RowVector4d(0, 0, 0, 1))
      throw std::runtime_error(std::string("'X_WC' of the ") + what + " is not a rigid transform");
    return fmt::format("{} x {} px, camera at ({:.2f}, {:.2f}, {:.2f})", shot.image.width_px,
                       shot.image.height_px, m(0, 3), m(1, 3), m(2, 3));
  };
  run("marker_frame", [&] { return frame_check(flight->marker_frame(), "marker frame"); });
  run("depth_frame", [&] { return frame_check(flight->depth_frame(), "depth frame"); });
  const auto refusal = [&](const std::string& name, const std::string& request) {
    run(name, [&, request] {
      if (const std::string p = refusal_problem(channel, request); !p.empty())
        throw std::runtime_error(request + ": " + p);
      return request + ": refused";
    });
  };
  refusal("refuses unknown op", R"({"op":"self_destruct"})");
  refusal("refuses a missing field", R"({"op":"takeoff"})");
  refusal("refuses malformed JSON", R"({"op":"takeoff","z_m":)");
  refusal("refuses another protocol", R"({"op":"hello","protocol":999})");
  run("refusals left the vehicle alone", [&] {
    const FlightState after = flight->state();
    if (after.on_ground != before.on_ground || (after.p_W - before.p_W).norm() > 0.5)
      throw std::runtime_error("the vehicle changed state during the refused requests");
    return std::string("state unchanged");
  });
  return checks;
}

}  // namespace ferret
