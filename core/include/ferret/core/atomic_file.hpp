#pragma once
// One-file outputs appear whole or not at all: an OutputSet (output_set.hpp) of one
// file, staged beside the target and renamed into place.

#include <filesystem>
#include <functional>
#include <string_view>

namespace ferret {

/// Calls `write(tmp_path)` to produce the file at a temporary path (same extension) in a
/// staging directory beside `path`, then renames it to `path`. If `write` throws, or
/// leaves no file, the staging directory is removed, `path` is untouched, and the
/// exception propagates. Creates missing parent directories of `path`; InputError for
/// a path that is empty, a directory, a FIFO, a device or under a regular file.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path& tmp_path)>& write);

/// Writes `content` to `path` atomically (see write_file_atomically).
void write_text_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace ferret
