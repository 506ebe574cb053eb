// ROS camera_info YAML -> CameraModel; a file that parses is written again and must
// parse back to the same numbers, bit for bit (camera_info_yaml's promise).
#include <bit>
#include <cstdint>
#include <cstdlib>

#include "ferret/core/error.hpp"
#include "ferret/perception/camera_info.hpp"
#include "fuzz_support.hpp"

namespace {

bool same(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ferret::CameraModel m;
  try {
    m = ferret::parse_camera_info(ferret::fuzz::as_string(data, size), "fuzz.yaml");
  } catch (const ferret::InputError&) {
    return 0;
  }
  // Not caught: a model that parsed must write and read back (an InputError here is a
  // defect of the writer, and aborts the run).
  const ferret::CameraModel back = ferret::parse_camera_info(ferret::camera_info_yaml(m), "again");
  bool ok = back.name == m.name && back.width_px == m.width_px && back.height_px == m.height_px &&
            same(back.fx_px, m.fx_px) && same(back.fy_px, m.fy_px) && same(back.cx_px, m.cx_px) &&
            same(back.cy_px, m.cy_px) && same(back.skew, m.skew) &&
            back.has_distortion() == m.has_distortion();
  for (int i = 0; i < 5 && m.distortion == ferret::DistortionModel::kPlumbBob; ++i)
    ok = ok && same(back.distortion_coefficients[i], m.distortion_coefficients[i]);
  for (int i = 0; i < 9; ++i)
    ok = ok && same(back.rectification(i / 3, i % 3), m.rectification(i / 3, i % 3));
  for (int i = 0; i < 12; ++i)
    ok = ok && same(back.projection(i / 4, i % 4), m.projection(i / 4, i % 4));
  if (!ok) std::abort();
  // What every consumer does next: rays through the corners and back.
  for (const double u : {-0.5, m.width_px - 0.5})
    for (const double v : {-0.5, m.height_px - 0.5}) (void)m.project(m.ray({u, v}));
  return 0;
}
