#pragma once
// The tether length the miniUGV's pose asks for. The winch controllers take this as a
// model (an interface), so the planner's taut-tether geometry can replace the fixed
// wrap-point polyline used by scripted trajectories without touching the controllers.

#include <Eigen/Core>
#include <vector>

namespace ferret::tether {

/// Length of tether from the winch to the miniUGV when the tether is taut (paper
/// sect. III-A: l_0 from the winch to the entry point plus the path inside the
/// hidden space).
class RequiredLengthModel {
 public:
  virtual ~RequiredLengthModel() = default;
  /// @param p_WG miniUGV position in the hidden-space (world) frame, metres.
  [[nodiscard]] virtual double required_length_m(const Eigen::Vector2d& p_WG) const = 0;
};

/// An obstacle corner the tether can bend around. side +1: the tether turns
/// counter-clockwise there (the corner is on its left), -1 clockwise, 0: always bent.
struct WrapPoint {
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();
  int side = 0;
};

/// Taut tether as a polyline entry -> wrap points (given, in order) -> miniUGV: the
/// shortest path in one homotopy class when the wrap points are the obstacle corners
/// the tether bends around. A corner with a side is engaged only while the tether
/// actually turns that way at it (a string round a peg: it unwraps when the miniUGV
/// comes back), and the corners after a disengaged one are disengaged too. The
/// planner's taut-tether model is the general version of this.
class FixedWrapTether final : public RequiredLengthModel {
 public:
  /// @param entry_offset_m l_0, tether from the winch to the entry point p_WE.
  FixedWrapTether(double entry_offset_m, Eigen::Vector2d p_WE,
                  std::vector<WrapPoint> wrap_points = {});

  [[nodiscard]] double required_length_m(const Eigen::Vector2d& p_WG) const override;
  /// Number of wrap points the tether bends around with the miniUGV at p_WG.
  [[nodiscard]] std::size_t engaged_count(const Eigen::Vector2d& p_WG) const;
  /// Tether from the winch to wrap point `index` (l_0 + polyline up to it).
  [[nodiscard]] double length_to_wrap_point_m(std::size_t index) const;
  [[nodiscard]] double entry_offset_m() const { return entry_offset_m_; }
  [[nodiscard]] const Eigen::Vector2d& entry_W() const { return p_WE_; }
  [[nodiscard]] const std::vector<WrapPoint>& wrap_points() const { return wrap_points_; }

 private:
  double entry_offset_m_;
  Eigen::Vector2d p_WE_;
  std::vector<WrapPoint> wrap_points_;
  std::vector<double> cumulative_m_;  ///< l_0 + polyline length up to each wrap point
};

/// The miniUGV's state as sent over the robot link: position, desired velocity and
/// desired acceleration in the world frame.
struct UgvMotion {
  Eigen::Vector2d p_WG = Eigen::Vector2d::Zero();
  Eigen::Vector2d v_WG = Eigen::Vector2d::Zero();
  Eigen::Vector2d a_WG = Eigen::Vector2d::Zero();

  /// Extrapolation `dt_s` ahead: the desired acceleration acts for at most
  /// `acceleration_time_s` and until the speed reaches `max_speed_mps`, then the
  /// robot coasts (a desired acceleration held for a whole horizon would predict
  /// speeds the miniUGV never drives).
  [[nodiscard]] UgvMotion extrapolated(double dt_s, double max_speed_mps,
                                       double acceleration_time_s = 1e9) const;
};

/// The miniUGV's planned motion ahead, as its path follower can send it with each
/// message: knots `step_s` apart from the message on (knot 0 is the message itself),
/// each the planned displacement from its desired position at the message (relative,
/// so that its localisation error does not enter twice) and the planned velocity.
/// Between knots the motion is the cubic Hermite curve through them. Empty: no preview.
struct UgvMotionPreview {
  double step_s = 0.0;
  std::vector<Eigen::Vector2d> displacement_m;  ///< knot i at i * step_s; [0] is zero
  std::vector<Eigen::Vector2d> velocity_mps;    ///< same size

  [[nodiscard]] bool empty() const {
    return displacement_m.size() < 2 || velocity_mps.size() != displacement_m.size() ||
           !(step_s > 0.0);
  }
  /// Planned displacement `dt_s` after the message (past the last knot it continues
  /// with the last knot's velocity).
  [[nodiscard]] Eigen::Vector2d at(double dt_s) const;
  /// Planned velocity `dt_s` after the message.
  [[nodiscard]] Eigen::Vector2d velocity_at(double dt_s) const;
};

/// The miniUGV's motion `dt_s` after a message, from its (filtered) position at the
/// message and its preview: position p + displacement, velocity the preview's.
[[nodiscard]] UgvMotion planned_motion(const UgvMotion& at_message, const UgvMotionPreview& preview,
                                       double dt_s);

/// Rate of change of the required length when the miniUGV moves with v_WG (central
/// difference of the model along the velocity).
[[nodiscard]] double required_length_rate_mps(const RequiredLengthModel& model,
                                              const UgvMotion& motion);

}  // namespace ferret::tether
