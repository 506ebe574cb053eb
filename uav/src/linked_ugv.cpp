#include "ferret/uav/linked_ugv.hpp"

#include <cmath>

namespace ferret {

LinkedUgv::LinkedUgv(const Clock& clock, link::UavLinkOptions options) : session_(clock, options) {}

std::uint32_t LinkedUgv::send(link::UavRequest::Kind kind, const std::string& reason) {
  link::UavRequest r;
  r.kind = kind;
  r.reason = reason;  // encode() cuts it to the wire's 63 bytes
  return last_ = session_.request(std::move(r));
}

void LinkedUgv::deploy(const Eigen::Vector3d& p_WE, double entry_yaw_rad) {
  link::UavRequest r;
  r.kind = link::UavRequest::Kind::kStartSearch;
  r.entry_x_m = p_WE.x();
  r.entry_y_m = p_WE.y();
  r.entry_z_m = p_WE.z();
  r.entry_yaw_rad = std::remainder(entry_yaw_rad, 2.0 * M_PI);
  r.reason = "search the hidden space";
  awaited_ = last_ = session_.request(std::move(r));
  entry_W_ = p_WE.head<2>();
}

void LinkedUgv::retracted() { (void)send(link::UavRequest::Kind::kRetracted, "lifted out"); }
void LinkedUgv::release_object() {
  (void)send(link::UavRequest::Kind::kReleaseObject, "over the drop zone");
}
void LinkedUgv::abort(const std::string& reason) {
  (void)send(link::UavRequest::Kind::kAbort, reason);
}
void LinkedUgv::recall(const std::string& reason) {
  (void)send(link::UavRequest::Kind::kRecall, reason);
}

UgvReport LinkedUgv::report() const {
  UgvReport r;
  r.link_ok = !session_.peer_silent();
  const auto& t = session_.telemetry();
  if (!t) {
    r.p_WG = r.tether_anchor_W = entry_W_;
    return r;
  }
  r.roll_rad = t->roll_rad;
  r.pitch_rad = t->pitch_rad;
  r.object_held = t->object_held;
  r.battery_fraction = t->battery_fraction;
  if (t->last_request_id < awaited_) {  // the search not started yet, as far as the UAV knows
    r.p_WG = r.tether_anchor_W = entry_W_;
    return r;
  }
  r.running = t->mode != link::UgvMode::kIdle && t->mode != link::UgvMode::kDone;
  r.done = t->mode == link::UgvMode::kDone;
  r.wants_retraction = t->wants_retraction;
  if (t->outcome != link::UgvOutcome::kNone) r.outcome = std::string(link::to_string(t->outcome));
  r.p_WG = {t->x_m, t->y_m};
  r.v_WG = {t->vx_mps, t->vy_mps};
  r.tether_anchor_W = {t->tether_anchor_x_m, t->tether_anchor_y_m};
  r.tether_to_anchor_m = t->tether_to_anchor_m;
  r.tether_uncertainty_m = t->tether_uncertainty_m;
  return r;
}

}  // namespace ferret
