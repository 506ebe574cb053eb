#pragma once
// Shared by the harnesses: the input as text, and a per-process scratch folder for the
// parsers that only read from a path (the harness writes the input there and calls the
// same loader the CLI calls, so there is one code path, never a second parser).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace ferret::fuzz {

[[nodiscard]] inline std::string as_string(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// A folder of its own for this process (libFuzzer's -jobs runs several processes),
/// removed at exit.
class ScratchDir {
 public:
  [[nodiscard]] static ScratchDir& instance();
  [[nodiscard]] const std::filesystem::path& path() const { return dir_; }
  /// Writes `bytes` to `name` in the folder (replacing it) and returns its path.
  std::filesystem::path write(std::string_view name, std::string_view bytes) const;
  std::filesystem::path write(std::string_view name, const std::uint8_t* data,
                              std::size_t size) const {
    return write(name, std::string_view(reinterpret_cast<const char*>(data), size));
  }

  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir();

 private:
  ScratchDir();
  std::filesystem::path dir_;
};

}  // namespace ferret::fuzz
