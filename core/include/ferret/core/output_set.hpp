#pragma once
// A command's outputs appear all together or not at all. A command declares its target
// (one file, or one directory), writes every file into a staging directory on the same
// filesystem, and commits once all of them were written; an exception before the commit
// leaves nothing behind (the destructor removes the staging directory, and any parent
// directories the set created). Targets are checked before any work is done, so a long
// run does not end in a write error, and special files (FIFOs, devices, sockets) are
// refused instead of being replaced by a regular file.

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace ferret {

enum class OutputKind {
  kFile,       ///< one file; replaced if it exists
  kDirectory,  ///< a directory of files; created if missing, unrelated files left alone
};

/// Checks that `target` can receive an output of `kind`, before any work is done:
/// the path is non-empty; a file target is not an existing directory, FIFO, socket or
/// device; a directory target is not an existing non-directory; the nearest existing
/// ancestor is a writable directory (not a regular file). Throws
/// InputError(target, "", expected, got), or InputError(option, ...) for an empty path;
/// `option` ("--out") is named in the expectation when not empty. Returns `target`.
std::filesystem::path check_output_target(const std::filesystem::path& target, OutputKind kind,
                                          std::string_view option = {});

class OutputSet {
 public:
  /// Checks the target (check_output_target) and creates the staging directory: beside
  /// the target for a file or a directory that does not exist yet (committed by one
  /// rename), inside an existing directory target (its files are moved in one by one,
  /// after all of them were written). Missing parents are created (removed again on
  /// rollback). Throws InputError when any of it is impossible.
  OutputSet(std::filesystem::path target, OutputKind kind);
  /// Without commit(): removes the staging directory and the parents the set created.
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  [[nodiscard]] const std::filesystem::path& staging_dir() const { return staging_; }

  /// Where to write the file `name`: for a file target the staged file (`name` empty, or
  /// the target's file name; it keeps the target's extension, which some writers use to
  /// choose the format); for a directory target staging_dir() / name, with `name` a
  /// relative path without ".." (its parent directories are created).
  [[nodiscard]] std::filesystem::path path(const std::filesystem::path& name = {});

  /// Calls `writer(path(name))`; InputError if it produced no file.
  void write(const std::filesystem::path& name,
             const std::function<void(const std::filesystem::path& staged)>& writer);
  /// Writes `content` to path(name).
  void write_text(const std::filesystem::path& name, std::string_view content);

  /// Moves every staged file into place (also those written into staging_dir() by other
  /// programs). For a directory target, every destination is checked first (none may be
  /// a directory or a special file), so a refused file leaves the target untouched.
  /// Throws InputError when a destination is refused or a rename fails.
  void commit();

 private:
  void rollback() noexcept;

  std::filesystem::path target_;    ///< as given (used in messages)
  std::filesystem::path absolute_;  ///< absolute, without a trailing separator
  OutputKind kind_;
  bool target_existed_ = false;
  bool committed_ = false;
  std::filesystem::path staging_;
  std::vector<std::filesystem::path> created_parents_;  ///< deepest first
};

}  // namespace ferret
