// The miniUGV base protocol's two parsers on arbitrary bytes (docs/robots.md, "The base
// protocol"): the first byte picks the side.
// - Even: the bytes are a request to UgvBaseService over a recording base. Every reply
//   is a JSON object with a boolean "ok"; a refused request never reaches the base; an
//   accepted command carries only finite numbers within the protocol's limits.
// - Odd: the bytes are every reply a server sends to RemoteUgvBase: hello, odometry,
//   speed, scan, frame, status. The client may only throw its UgvBaseProtocolError, and
//   what it returns is finite and within the protocol's counts.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "ferret/ugv/remote_ugv_base.hpp"
#include "rpc_replay.hpp"

namespace {

using ferret::link::StreamMessage;

struct RecordingBase final : ferret::UgvBase {
  int commands = 0;
  std::string backend() const override { return "fuzz"; }
  ferret::Pose2 odometry() const override { return {}; }
  double speed_mps() const override { return 0.0; }
  ferret::RangeScan ir_scan() override { return {}; }
  ferret::CameraFrame camera_frame(double time_s) override {
    if (!std::isfinite(time_s)) std::abort();
    return {};
  }
  void command_velocity(double v, double w) override {
    if (!std::isfinite(v) || !std::isfinite(w) || std::abs(v) > 100 || std::abs(w) > 100)
      std::abort();
    ++commands;
  }
  void set_epm(bool) override { ++commands; }
  ferret::UgvStatus status() const override { return {}; }
};

void check_scan(const ferret::RangeScan& s) {
  if (s.beams.size() > ferret::kMaxRemoteBeams || !(s.max_range_m > 0) ||
      !std::isfinite(s.X_WS.yaw_rad))
    std::abort();
  for (const auto& b : s.beams)
    if (!std::isfinite(b.bearing_rad) || std::isnan(b.range_m) || b.range_m < 0) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 0) {
    RecordingBase base;
    ferret::UgvBaseService service(base, "fuzz");
    const StreamMessage reply = service.handle({text, {}});
    const auto r = nlohmann::json::parse(reply.header, nullptr, false);
    if (r.is_discarded() || !r.is_object() || !r.contains("ok") || !r["ok"].is_boolean())
      std::abort();
    if (!r["ok"].get<bool>() && base.commands != 0) std::abort();  // refused, yet acted on
    return 0;
  }
  ferret::fuzz::RpcReplay channel;
  channel.reply.header = text;
  try {
    ferret::RemoteUgvBase base(channel, "sim");
    const ferret::Pose2 p = base.odometry();
    if (!std::isfinite(p.x_m) || !std::isfinite(p.y_m) || !std::isfinite(p.yaw_rad)) std::abort();
    if (!std::isfinite(base.speed_mps())) std::abort();
    check_scan(base.ir_scan());
    const ferret::CameraFrame f = base.camera_frame(1.0);
    check_scan(f.view);
    if (f.detections.size() > ferret::kMaxRemoteDetections) std::abort();
    for (const auto& d : f.detections)
      if (!(d.distance_m > 0) || !std::isfinite(d.distance_m) || !std::isfinite(d.confidence))
        std::abort();
    if (!std::isfinite(base.status().battery_fraction)) std::abort();
    base.command_velocity(0.1, 0.2);
    base.set_epm(true);
  } catch (const ferret::UgvBaseProtocolError&) {
  }
  return 0;
}
