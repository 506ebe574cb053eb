#pragma once
// Outputs appear whole or not at all: writers write a temporary file beside the
// target and rename it into place, so a failure never leaves a partial file.

#include <filesystem>
#include <functional>
#include <string_view>

namespace ferret {

/// Calls `write(tmp_path)` to produce the file at a temporary path in the same
/// directory, then renames it to `path`. If `write` throws, or leaves no file, the
/// temporary is removed, `path` is untouched, and the exception propagates.
/// Creates missing parent directories of `path`.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path& tmp_path)>& write);

/// Writes `content` to `path` atomically (see write_file_atomically).
void write_text_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace ferret
