#pragma once
// Fiducial marker families and their bitmaps. Two detectors read markers (uav/): the
// AprilTag 3 library (family names as the library spells them: tag36h11, tag25h9,
// tag16h5, tagStandard41h12 ...) and OpenCV's ArUco module (dictionaries by their
// OpenCV names: DICT_4X4_50 ... DICT_APRILTAG_36h11). The simulator draws the same
// bitmaps into its frames.

#include <string>
#include <vector>

#include "ferret/perception/image.hpp"

namespace ferret {

enum class MarkerFamily { kAruco, kAprilTag };
[[nodiscard]] const char* to_string(MarkerFamily family);  ///< "aruco" / "apriltag"

/// A family and one of its dictionaries.
struct MarkerDictionary {
  MarkerFamily family = MarkerFamily::kAruco;
  std::string name = "DICT_4X4_50";  ///< OpenCV dictionary name or AprilTag family name
};

/// Parses "aruco" / "apriltag"; throws InputError(source, field, ...) otherwise.
[[nodiscard]] MarkerFamily parse_marker_family(const std::string& text, const std::string& source,
                                               const std::string& field);
/// Throws InputError(source, field, ...) unless the dictionary exists for its family
/// (the message lists the names that do).
void check_marker_dictionary(const MarkerDictionary& dictionary, const std::string& source,
                             const std::string& field);
/// The dictionary names a family knows.
[[nodiscard]] const std::vector<std::string>& marker_dictionary_names(MarkerFamily family);
/// How many ids the dictionary holds (ids are 0 .. count - 1).
[[nodiscard]] int marker_id_count(const MarkerDictionary& dictionary);
/// A marker's bitmap, one pixel per cell (0 black, 255 white). `size_m` of a marker
/// is the side of its black square (ArUco's and AprilTag's tag-size convention): for
/// ArUco and the classic AprilTag families the bitmap is that square (ArUco 4x4 with
/// its border: 6 cells; tag36h11: 8); AprilTag 3's newer layouts (tagStandard41h12,
/// tagCircle21h7 ...) have cells outside it, so the bitmap is larger than the square.
struct MarkerBitmap {
  GrayImage cells;              ///< total_cells x total_cells
  int black_square_cells = 0;   ///< side of the black square, in cells (what size_m measures)
  int black_square_offset = 0;  ///< cells from the bitmap's edge to the black square
};
/// Throws InputError when the id is outside the dictionary.
[[nodiscard]] MarkerBitmap marker_bitmap(const MarkerDictionary& dictionary, int id);

}  // namespace ferret
