#pragma once
// The UAV's flight controller and cameras through the flight adapter protocol
// (docs/flight_adapter.md): on the M100 a small onboard program built with DJI's
// Onboard SDK implements it; the reference adapter (sim/sim_flight_adapter.hpp,
// `ferret flight-adapter serve`) implements it over the simulated M100, so the same
// client is exercised on every test run.
//
// Requests go over an RpcChannel (a TCP message stream); each call blocks for the
// adapter's reply.

#include <string>

#include "ferret/link/message_stream.hpp"
#include "ferret/uav/flight_controller.hpp"

namespace ferret {

/// The protocol version this client speaks; an adapter that answers another is refused.
inline constexpr int kFlightAdapterProtocol = 1;

/// The adapter answered, but refused the request or broke the protocol (a plain
/// link::StreamError is the connection's: lost, silent, or not a message stream).
class FlightAdapterError : public link::StreamError {
 public:
  using link::StreamError::StreamError;
};

class AdapterFlightController final : public FlightController, public UavCameras {
 public:
  /// Greets the adapter ("hello") and checks its protocol version. `backend` is what
  /// the run's first lines print ("sim" for the simulated world's adapter, "hw" for a
  /// vehicle's). Throws FlightAdapterError for an adapter that speaks another
  /// version, link::StreamError for one that does not answer.
  AdapterFlightController(link::RpcChannel& channel, std::string backend);

  [[nodiscard]] std::string backend() const override { return backend_; }
  /// What the adapter said it is in its hello ("sim", "dji-osdk", ...).
  [[nodiscard]] const std::string& adapter_name() const { return adapter_; }
  [[nodiscard]] FlightState state() const override;
  void command_takeoff(double z_m) override;
  void command_position(const Eigen::Vector3d& p_W, double yaw_rad, double speed_mps) override;
  void command_land() override;
  /// A velocity set-point (m/s in the world) with a yaw rate, held until the next
  /// command: part of the protocol for adapters and tools; the mission flies positions.
  void command_velocity(const Eigen::Vector3d& v_W, double yaw_rate_radps);

  [[nodiscard]] CameraShot<GrayImage> marker_frame() override;
  [[nodiscard]] CameraShot<DepthImageMm> depth_frame() override;

 private:
  link::RpcChannel& channel_;
  std::string backend_;
  std::string adapter_;
};

}  // namespace ferret
