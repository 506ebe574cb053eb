#pragma once
// What a winch controller sees each cycle: the winch's encoder and tension, and the
// miniUGV's motion as received over the link.

#include "ferret/tether_model/required_length.hpp"

namespace ferret::tether {

struct TetherObservation {
  double t_s = 0.0;
  double released_m = 0.0;       ///< l_t from the spool encoder
  double spool_speed_mps = 0.0;  ///< measured
  double winch_tension_n = 0.0;  ///< from motor current, includes the hanging weight
  UgvMotion ugv;                 ///< last message from the miniUGV
  double ugv_age_s = 0.0;        ///< how old that message is (link latency)
  UgvMotionPreview ugv_preview;  ///< the miniUGV's planned motion after the message, if sent
  /// Slack asked for beyond the reference: how much longer the real tether may be than
  /// the required-length model says (the miniUGV's bound of its tether less its
  /// estimate, where its map has not seen every corner the line can wrap).
  double slack_margin_m = 0.0;
};

}  // namespace ferret::tether
