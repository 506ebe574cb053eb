#pragma once
// The miniUGV as the UAV's mission sees it over the robot link (docs/link.md): each
// UgvLink call is a request, delivered reliably and in order; report() is the newest
// telemetry, read as the answer to a search only once the miniUGV says it acted on the
// request that started it (a frame from the last hidden space may still arrive late).
// The caller moves the datagrams (session()): a UdpLink on the robot, a LossyChannel
// in simulation.

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "ferret/core/clock.hpp"
#include "ferret/link/link_session.hpp"
#include "ferret/uav/flight_controller.hpp"

namespace ferret {

class LinkedUgv final : public UgvLink {
 public:
  explicit LinkedUgv(const Clock& clock, link::UavLinkOptions options = {});

  void deploy(const Eigen::Vector3d& p_WE, double entry_yaw_rad) override;
  void retracted() override;
  void release_object() override;
  void abort(const std::string& reason) override;
  void recall(const std::string& reason) override;
  /// The newest telemetry. Until the miniUGV has acted on the last deploy(): not running,
  /// not done, at the entry (its attitude and magnet as they are). link_ok is false
  /// while it has been silent past the link's timeout (the winch then holds).
  [[nodiscard]] UgvReport report() const override;

  [[nodiscard]] link::UavLinkSession& session() { return session_; }
  [[nodiscard]] const link::UavLinkSession& session() const { return session_; }
  /// The request whose answer report() waits for (the last deploy), 0 before any.
  [[nodiscard]] std::uint32_t awaited_request() const { return awaited_; }
  /// The id of the last request made, 0 before any.
  [[nodiscard]] std::uint32_t last_request() const { return last_; }

 private:
  std::uint32_t send(link::UavRequest::Kind kind, const std::string& reason);

  link::UavLinkSession session_;
  std::uint32_t awaited_ = 0, last_ = 0;
  Eigen::Vector2d entry_W_ = Eigen::Vector2d::Zero();
};

}  // namespace ferret
