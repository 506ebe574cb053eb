#pragma once
// Colour to grey, one rule for every frame ferret turns grey: ITU-R BT.601 luma
// (0.299 R + 0.587 G + 0.114 B), OpenCV's COLOR_RGB2GRAY and libjpeg's, so a frame gives
// the same grey whether it arrives as RGB in memory, a colour PNG or a colour JPEG.

#include "ferret/perception/image.hpp"

namespace ferret {

[[nodiscard]] GrayImage to_gray(const RgbImage& rgb);

}  // namespace ferret
