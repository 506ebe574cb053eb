#pragma once
// What crosses the robot link between the UAV and the miniUGV (docs/link.md). The
// paper keeps the link small: the miniUGV tells the UAV's winch where it is and how it
// means to move, the UAV tells the miniUGV what to do next. Plain structs in SI units;
// the wire format is in codec.hpp. The enums mirror the miniUGV mission's states and
// outcomes without including ugv/: the two robots meet only here.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace ferret::link {

/// The miniUGV mission's state (ugv/mini_ugv_mission.hpp's UgvMissionState).
enum class UgvMode : std::uint8_t {
  kIdle = 0,
  kExplore = 1,
  kTrack = 2,
  kTurn = 3,
  kGrasp = 4,
  kReturn = 5,
  kAwaitRetract = 6,
  kDone = 7,
};
[[nodiscard]] std::string_view to_string(UgvMode mode);

/// How the miniUGV's mission ended (UgvMissionOutcome); kNone while it runs.
enum class UgvOutcome : std::uint8_t {
  kNone = 0,
  kObjectRetrieved = 1,
  kNoObject = 2,
  kGraspFailed = 3,
  kTrackLost = 4,
  kBatteryLow = 5,
  kSearchTimeout = 6,
  kReturnFailed = 7,
  kRetractTimeout = 8,
  kAborted = 9,
  kRecalled = 10,
};
[[nodiscard]] std::string_view to_string(UgvOutcome outcome);

/// Who sent a frame. Each message type has one sender (sender_of), and the decoder
/// refuses a frame whose sender byte disagrees: a robot never accepts its own frames
/// looped back to it.
enum class Sender : std::uint8_t { kUav = 1, kUgv = 2 };
[[nodiscard]] std::string_view to_string(Sender sender);

/// One sample of the miniUGV's planned motion, `dt_s` after the telemetry's t_s.
/// float32 on the wire (a forecast good to centimetres; float32 is 2 µm at 30 m), so
/// float here: what is sent is what is received.
struct PlanSample {
  float dt_s = 0.0f;
  float x_m = 0.0f;
  float y_m = 0.0f;
  float vx_mps = 0.0f;
  float vy_mps = 0.0f;
  bool operator==(const PlanSample&) const = default;
};

/// miniUGV -> UAV at the miniUGV's control rate (20 Hz): what the winch needs to keep
/// the tether taut, and the mission's state. A state message: only the newest counts.
/// Poses are in the hidden-space frame. Fields that the winch sums into a tether length
/// (times, positions, the taut length to the anchor) are float64 on the wire; rates,
/// attitude, the doubt and the battery are float32 (the float members).
struct UgvTelemetry {
  /// The largest plan preview: the next 0.5 s at the 20 Hz control rate.
  static constexpr std::size_t kMaxPlanSamples = 10;

  double t_s = 0.0;  ///< the miniUGV's clock when it was sent
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  float vx_mps = 0.0f;  ///< desired velocity
  float vy_mps = 0.0f;
  float ax_mps2 = 0.0f;  ///< desired acceleration
  float ay_mps2 = 0.0f;
  UgvMode mode = UgvMode::kIdle;
  UgvOutcome outcome = UgvOutcome::kNone;
  float battery_fraction = 1.0f;  ///< [0, 1]
  bool epm_on = false;
  bool object_held = false;       ///< the EPM reports contact
  bool wants_retraction = false;  ///< at the entry, asking to be lifted out
  /// The taut tether: its last fixed point (the last wrap point, or the entry) and the
  /// taut length from the entry to it, so the winch can price motion between messages.
  double tether_anchor_x_m = 0.0;
  double tether_anchor_y_m = 0.0;
  double tether_to_anchor_m = 0.0;
  float tether_uncertainty_m = 0.0f;  ///< how much longer the real tether may be
  float roll_rad = 0.0f;              ///< IMU attitude (the touchdown check)
  float pitch_rad = 0.0f;
  /// The newest UAV request the miniUGV has acted on (0: none yet). The UAV reads a
  /// frame as the answer to its request only from this id on: a frame still on its way
  /// from before (the last hidden space's "done") is not the new deployment's.
  std::uint32_t last_request_id = 0;
  /// Optional: up to kMaxPlanSamples samples of the planned motion, dt_s increasing.
  std::vector<PlanSample> plan;

  bool operator==(const UgvTelemetry&) const = default;
};

/// UAV -> miniUGV, delivered reliably and in order (link_session.hpp).
struct UavRequest {
  enum class Kind : std::uint8_t {
    kStartSearch = 1,    ///< search the hidden space whose entry is entry_*
    kRecall = 2,         ///< give up the search and come back to the entry
    kRetracted = 3,      ///< the winch has lifted you out
    kReleaseObject = 4,  ///< EPM off, hanging under the UAV
    kAbort = 5,          ///< stop where you are; the mission ends
  };
  /// The longest reason on the wire; longer text is cut at a UTF-8 character boundary.
  static constexpr std::size_t kMaxReasonBytes = 63;

  std::uint32_t request_id = 0;  ///< from 1, increasing; a resend keeps its id
  Kind kind = Kind::kAbort;
  /// kStartSearch: the entry E of the hidden space and the heading into it, in the
  /// UAV's world frame (z: the floor the miniUGV stands on). Zero for other kinds.
  double entry_x_m = 0.0;
  double entry_y_m = 0.0;
  double entry_z_m = 0.0;
  double entry_yaw_rad = 0.0;
  std::string reason;  ///< for logs; UTF-8

  bool operator==(const UavRequest&) const = default;
};
[[nodiscard]] std::string_view to_string(UavRequest::Kind kind);

/// miniUGV -> UAV: the request with this id arrived (sent for every copy received).
struct Ack {
  std::uint32_t request_id = 0;
  bool operator==(const Ack&) const = default;
};

/// UAV -> miniUGV at 20 Hz, so that the miniUGV's watchdog hears the UAV when it has no
/// request to send, and knows what the UAV last heard of it. (Telemetry is the
/// miniUGV's heartbeat.)
struct Heartbeat {
  double t_s = 0.0;  ///< the UAV's clock when it was sent
  /// The `t_s` of the newest miniUGV telemetry the UAV had accepted (the miniUGV's own
  /// clock; 0: none yet): the miniUGV learns how fresh the winch's view of it is
  /// without the two clocks agreeing (docs/link.md "Watchdogs").
  double ugv_telemetry_t_s = 0.0;
  bool operator==(const Heartbeat&) const = default;
};

using Message = std::variant<UgvTelemetry, UavRequest, Ack, Heartbeat>;

/// The message type on the wire; its value is the header's type byte.
enum class MessageType : std::uint8_t { kTelemetry = 1, kRequest = 2, kAck = 3, kHeartbeat = 4 };
[[nodiscard]] std::string_view to_string(MessageType type);
[[nodiscard]] MessageType type_of(const Message& message);
[[nodiscard]] Sender sender_of(MessageType type);

}  // namespace ferret::link
