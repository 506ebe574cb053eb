#pragma once
// The simulated miniUGV: a UgvBase over the simulated hidden space. Unicycle
// kinematics with the robot's limits, the IR and camera of HiddenSpaceSim, the EPM at
// the robot's rear (contact when the rear touches the object; the object follows a
// magnet that is on), and a battery that drains with time and speed. Odometry is the
// true pose (the hidden space's maps are in the robot's own frame).

#include <Eigen/Core>
#include <cstdint>

#include "ferret/sim/hidden_space_sim.hpp"
#include "ferret/ugv/path_follower.hpp"
#include "ferret/ugv/ugv_base.hpp"

namespace ferret {

struct SimUgvOptions {
  RobotOptions robot;
  /// Centre to the rear face (the EPM), m: half the miniUGV's 130 mm length.
  double rear_offset_m = 0.065;
  /// Driving time a full battery gives at full speed, s (the real one: about 18 min).
  double battery_endurance_s = 18.0 * 60.0;
  /// Share of the full-speed drain the robot draws standing still (computer, sensors).
  double idle_drain_share = 0.5;
  double initial_battery_fraction = 1.0;
  /// An object the magnet cannot hold (not ferromagnetic): contact, but no grip.
  bool object_graspable = true;
  /// The disc inside the body's footprint (half the miniUGV's 120 mm width): a blocking
  /// truth cell nearer the centre than this, by more than half a cell (the truth's
  /// raster), is a body contact, and the base does not take a step that presses the
  /// body deeper (docs/mission.md, "Body contacts"). 0: a point, which nothing stops or
  /// counts (the paper's experiment, whose controller plans for a point; the mission
  /// sets it from the URDF).
  double body_radius_m = 0.0;
};

class SimUgvBase final : public UgvBase {
 public:
  /// @param sim the sensors and the truth; must outlive the base. No object: pass a sim
  ///        whose object is far outside the map.
  SimUgvBase(HiddenSpaceSim& sim, const Pose2& start, SimUgvOptions options);

  [[nodiscard]] std::string backend() const override { return "sim"; }
  [[nodiscard]] Pose2 odometry() const override { return pose_; }
  [[nodiscard]] double speed_mps() const override { return v_mps_; }
  [[nodiscard]] RangeScan ir_scan() override { return sim_.ir_scan(pose_); }
  [[nodiscard]] CameraFrame camera_frame(double time_s) override {
    return sim_.camera_frame(pose_, time_s);
  }
  void command_velocity(double v_mps, double w_radps) override;
  void set_epm(bool on) override { epm_on_ = on; }
  [[nodiscard]] UgvStatus status() const override;

  /// Moves the robot by dt under the last command (the world's step).
  void step(double dt_s);
  /// Faults (sim/fault_plan.hpp): the battery drains `factor` times as fast from now on
  /// (1: as it should), or loses `fraction` of a full charge at once.
  void set_battery_drain_factor(double factor) { drain_factor_ = factor; }
  void sag_battery(double fraction) { battery_ = std::max(0.0, battery_ - fraction); }
  /// Ground truth, for the simulation's own bookkeeping (never for a controller).
  [[nodiscard]] const Pose2& true_pose() const { return pose_; }
  [[nodiscard]] bool object_held() const { return held_; }
  [[nodiscard]] double distance_driven_m() const { return driven_m_; }
  /// Body contacts so far (each stretch of steps against a wall counts once), and how
  /// far the deepest reached into the body disc beyond half a cell (0 unless the body
  /// started in a wall: the base stops it at the face).
  [[nodiscard]] int body_contacts() const { return contacts_; }
  [[nodiscard]] double deepest_contact_m() const { return deepest_contact_m_; }
  /// Against a wall at the last step (blocked, or inside by more than half a cell), and
  /// how far inside then.
  [[nodiscard]] bool in_contact() const { return in_contact_; }
  [[nodiscard]] double contact_depth_m() const { return contact_depth_m_; }

 private:
  [[nodiscard]] Eigen::Vector2d rear(const Pose2& pose) const;
  /// How far a blocking truth cell reaches into the body disc at p (0: none).
  [[nodiscard]] double body_penetration_m(const Eigen::Vector2d& p) const;

  HiddenSpaceSim& sim_;
  SimUgvOptions options_;
  Pose2 pose_;
  VelocityCommand command_;
  double v_mps_ = 0.0;
  bool epm_on_ = false;
  bool contact_ = false;
  bool held_ = false;
  double battery_ = 1.0;
  double drain_factor_ = 1.0;
  double driven_m_ = 0.0;
  int contacts_ = 0;
  bool in_contact_ = false;
  double deepest_contact_m_ = 0.0;
  double contact_depth_m_ = 0.0;
};

}  // namespace ferret
