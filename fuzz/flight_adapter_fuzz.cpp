// The flight adapter protocol's two parsers on arbitrary bytes (docs/flight_adapter.md):
// the first byte picks the side.
// - Even: the bytes are a request to FlightAdapterService (an adapter's server half)
//   over a recording flight controller. Every reply is a JSON object with a boolean
//   "ok"; a refused request never reaches the controller; an accepted command carries
//   only finite numbers within the protocol's limits.
// - Odd: the bytes are every reply an adapter sends to ferret's client
//   (AdapterFlightController): hello, state, frames. The client may only throw its
//   FlightAdapterError or an InputError (a frame file that is not an image).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/uav/adapter_flight_controller.hpp"
#include "ferret/uav/flight_adapter_service.hpp"
#include "rpc_replay.hpp"

namespace {

using ferret::link::StreamMessage;

struct RecordingFlight final : ferret::FlightController {
  int commands = 0;
  std::string backend() const override { return "fuzz"; }
  ferret::FlightState state() const override { return {}; }
  void command_takeoff(double z_m) override { take(z_m); }
  void command_position(const Eigen::Vector3d& p, double yaw, double speed) override {
    take(p.x() + p.y() + p.z() + yaw + speed);
  }
  void command_land() override { ++commands; }
  void take(double v) {
    if (!std::isfinite(v) || std::abs(v) > 1e6) std::abort();  // out of the protocol's limits
    ++commands;
  }
};

struct TinyCameras final : ferret::UavCameras {
  ferret::CameraShot<ferret::GrayImage> marker_frame() override {
    return {ferret::GrayImage(2, 1), {}};
  }
  ferret::CameraShot<ferret::DepthImageMm> depth_frame() override {
    return {ferret::DepthImageMm(1, 2), {}};
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 0) {
    RecordingFlight flight;
    TinyCameras cameras;
    ferret::FlightAdapterService service(
        flight, cameras, "fuzz",
        {[&](const Eigen::Vector3d& v, double w) { flight.take(v.sum() + w); }});
    const StreamMessage reply = service.handle({text, {}});
    const auto r = nlohmann::json::parse(reply.header, nullptr, false);
    if (r.is_discarded() || !r.is_object() || !r.contains("ok") || !r["ok"].is_boolean())
      std::abort();
    if (!r["ok"].get<bool>() && flight.commands != 0) std::abort();  // refused, yet acted on
    return 0;
  }
  // The reply's blob: what follows a NUL in the text, so frames get pixels to check.
  ferret::fuzz::RpcReplay channel;
  const std::size_t nul = text.find('\0');
  channel.reply.header = text.substr(0, nul);
  if (nul != std::string::npos)
    channel.reply.blob.assign(text.begin() + static_cast<long>(nul) + 1, text.end());
  try {
    ferret::AdapterFlightController flight(channel, "hw");
    const ferret::FlightState s = flight.state();
    if (!s.p_W.allFinite() || !s.v_W.allFinite() || !std::isfinite(s.yaw_rad)) std::abort();
    const auto m = flight.marker_frame();
    if (m.image.data.size() != static_cast<std::size_t>(m.image.width_px) * m.image.height_px)
      std::abort();
    (void)flight.depth_frame();
  } catch (const ferret::FlightAdapterError&) {
  } catch (const ferret::InputError&) {
  }
  return 0;
}
