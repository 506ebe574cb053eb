// Pass 2 of the URDF loader: urdfdom builds the kinematic tree, its console messages
// captured (console_bridge) and folded into one InputError, and every link is placed
// in the base frame at zero joint positions.

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <mutex>

#include "loader_passes.hpp"

namespace ferret::internal {

namespace {

/// Collects console_bridge messages instead of printing them.
class CapturingOutput : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
           int /*line*/) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(text);
  }
  std::vector<std::string> messages;
};

std::mutex& console_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const XmlSource& src, const std::string& xml) {
  CapturingOutput output;
  urdf::ModelInterfaceSharedPtr model;
  std::string exception;
  {
    // console_bridge's handler is process-wide: one parse at a time swaps it.
    const std::lock_guard lock(console_mutex());
    console_bridge::useOutputHandler(&output);
    try {
      model = urdf::parseURDF(xml);
    } catch (const std::exception& e) {
      exception = e.what();
    }
    console_bridge::restorePreviousOutputHandler();
  }
  if (model) return model;
  std::string why = !exception.empty()        ? exception
                    : output.messages.empty() ? ""
                                              : output.messages.front();
  for (char& c : why)
    if (c == '\n' || c == '\r') c = ' ';
  throw InputError(src.source(), "robot", "a URDF that urdfdom accepts",
                   why.empty() ? "urdfdom rejected it" : "urdfdom: " + why);
}

/// X_BL of every link at zero joint positions, walking the tree from the root with an
/// explicit stack (a chain is as deep as it has links).
void place_links(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& root,
                 std::map<std::string, Pose3>& X_B) {
  std::vector<std::pair<urdf::LinkConstSharedPtr, Pose3>> stack{{root, Pose3::Identity()}};
  while (!stack.empty()) {
    const auto [link, X_BL] = stack.back();
    stack.pop_back();
    if (!X_B.emplace(link->name, X_BL).second) continue;  // urdfdom made it a tree; be sure
    for (const auto& joint : link->child_joints) {
      const auto child = model.getLink(joint->child_link_name);
      if (child) stack.emplace_back(child, X_BL * to_pose(joint->parent_to_joint_origin_transform));
    }
  }
}

}  // namespace ferret::internal
