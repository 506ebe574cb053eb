#pragma once
// The strict, iterative check every URDF passes before a recursive parser (TinyXML,
// urdfdom's TinyXML-based one) sees it: well-formed XML 1.0, UTF-8, no DOCTYPE, and
// bounded size, nesting and element count (docs/configuration.md, "Limits").

#include <cstddef>
#include <string>

namespace ferret::internal {

inline constexpr std::size_t kMaxUrdfBytes = std::size_t{16} << 20;  ///< 16 MiB
inline constexpr int kMaxXmlDepth = 32;                              ///< the root is level 1
inline constexpr std::size_t kMaxXmlElements = 100000;

/// Throws InputError(source, "line L column C", expected, got) on the first fault.
void check_well_formed_xml(const std::string& text, const std::string& source);

/// `text` with line breaks and tabs as spaces and every byte that is not printable
/// ASCII or a shown UTF-8 character written as \xNN: what a one-line message may
/// quote from a hostile file.
std::string printable(const std::string& text);

}  // namespace ferret::internal
