#pragma once
// How the objects of the search look to a camera: they are painted one known saturated
// colour, which the object detector (ugv/) looks for and the simulator paints them in.

#include <array>
#include <cstdint>

namespace ferret {

/// The objects' paint (sRGB, 8 bit): a saturated orange, far in hue from the greys,
/// browns and sky of the worlds (hue ~26 degrees, saturation 1).
inline constexpr std::array<std::uint8_t, 3> kObjectColourRgb{255, 110, 0};

}  // namespace ferret
