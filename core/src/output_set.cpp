#include "ferret/core/output_set.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "ferret/core/error.hpp"

namespace ferret {
namespace fs = std::filesystem;

namespace {

std::string describe(fs::file_type type) {
  switch (type) {
    case fs::file_type::regular:
      return "a regular file";
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::symlink:
      return "a symbolic link";
    default:
      return "a file of unknown type";
  }
}

// The type a path has (following symbolic links: a link to a FIFO is a FIFO);
// not_found for a missing path and for one under a regular file (ENOTDIR).
fs::file_type type_of(const fs::path& p) {
  std::error_code ec;
  return fs::status(p, ec).type();
}

bool exists_type(fs::file_type t) {
  return t != fs::file_type::not_found && t != fs::file_type::none;
}

// Absolute, normalised, without a trailing separator ("out/" and "out/." are "out").
fs::path normalised(const fs::path& p) {
  fs::path abs = fs::absolute(p).lexically_normal();
  if (!abs.has_filename() && abs != abs.root_path()) abs = abs.parent_path();
  return abs;
}

// The nearest ancestor of `p` that exists (p's parent first).
fs::path nearest_existing_ancestor(const fs::path& p) {
  fs::path a = p.parent_path();
  while (!exists_type(type_of(a)) && a != a.parent_path()) a = a.parent_path();
  return a;
}

std::string for_option(std::string_view option) {
  return option.empty() ? std::string() : " for " + std::string(option);
}

void check_writable_dir(const fs::path& dir, const std::string& source) {
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw InputError(source, "", "a writable directory",
                     "'" + dir.string() + "': " + std::strerror(errno));
}

std::string unique_suffix() {
  static std::atomic<unsigned> counter{0};
  return std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

}  // namespace

fs::path check_output_target(const fs::path& target, OutputKind kind, std::string_view option) {
  if (target.empty())
    throw InputError(option.empty() ? std::string("output") : std::string(option), "",
                     "a non-empty output path", "''");
  const std::string source = target.string();
  const fs::path abs = normalised(target);
  const std::string fn = target.filename().string();
  if (kind == OutputKind::kFile && (fn.empty() || fn == "." || fn == ".."))
    throw InputError(source, "", "a regular file path" + for_option(option), "a directory path");

  const fs::file_type type = type_of(abs);
  fs::path writable_dir;  // where the staging directory goes
  if (exists_type(type)) {
    if (kind == OutputKind::kFile && type != fs::file_type::regular)
      throw InputError(source, "", "a regular file path" + for_option(option), describe(type));
    if (kind == OutputKind::kDirectory && type != fs::file_type::directory)
      throw InputError(source, "", "a directory path" + for_option(option), describe(type));
    writable_dir = kind == OutputKind::kDirectory ? abs : abs.parent_path();
  } else {
    writable_dir = nearest_existing_ancestor(abs);
    const fs::file_type t = type_of(writable_dir);
    if (t != fs::file_type::directory)
      throw InputError(source, "", "a path whose parents are directories" + for_option(option),
                       "'" + writable_dir.string() + "' is " + describe(t));
  }
  check_writable_dir(writable_dir, source);
  return target;
}

OutputSet::OutputSet(fs::path target, OutputKind kind) : target_(std::move(target)), kind_(kind) {
  check_output_target(target_, kind_);
  absolute_ = normalised(target_);
  const std::string source = target_.string();
  target_existed_ = exists_type(type_of(absolute_));

  // Create what is missing above the target, remembering it for a rollback.
  for (fs::path p = absolute_.parent_path(); !exists_type(type_of(p)) && p != p.parent_path();
       p = p.parent_path())
    created_parents_.push_back(p);
  std::error_code ec;
  if (!created_parents_.empty()) {
    fs::create_directories(absolute_.parent_path(), ec);
    if (ec) {
      rollback();
      throw InputError(source, "", "a writable directory", ec.message());
    }
  }

  const bool inside = kind_ == OutputKind::kDirectory && target_existed_;
  // (std::string appends, not operator+ chains: GCC 12 warns falsely on those.)
  std::string name = ".";
  if (inside) {
    name.append("ferret-staging-");
  } else {
    name.append(absolute_.filename().string());
    name.append(".staging-");
  }
  name.append(unique_suffix());
  staging_ = (inside ? absolute_ : absolute_.parent_path()) / name;
  if (!fs::create_directory(staging_, ec) || ec) {
    std::string why = ec ? ec.message() : staging_.string();
    if (!ec) why.append(" exists");
    staging_.clear();
    rollback();
    throw InputError(source, "", "a writable directory", why);
  }
}

OutputSet::~OutputSet() {
  if (!committed_) rollback();
}

void OutputSet::rollback() noexcept {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  // Only directories still empty: another program may have put files there meanwhile.
  for (const auto& p : created_parents_) fs::remove(p, ec);
  created_parents_.clear();
}

fs::path OutputSet::path(const fs::path& name) {
  if (committed_) throw std::logic_error("OutputSet::path after commit");
  if (kind_ == OutputKind::kFile) {
    if (!name.empty() && name != absolute_.filename())
      throw std::invalid_argument("OutputSet::path: a file target holds one file, not " +
                                  name.string());
    return staging_ / absolute_.filename();
  }
  const fs::path rel = name.lexically_normal();
  if (rel.empty() || rel.is_absolute() || !rel.has_filename() || *rel.begin() == "..")
    throw std::invalid_argument("OutputSet::path: not a relative file name: " + name.string());
  const fs::path staged = staging_ / rel;
  if (rel.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(staged.parent_path(), ec);
    if (ec) throw InputError((target_ / rel).string(), "", "a writable directory", ec.message());
  }
  return staged;
}

void OutputSet::write(const fs::path& name, const std::function<void(const fs::path&)>& writer) {
  const fs::path staged = path(name);
  writer(staged);
  if (type_of(staged) != fs::file_type::regular)
    throw InputError(kind_ == OutputKind::kFile ? target_.string() : (target_ / name).string(), "",
                     "the writer to produce a file");
}

void OutputSet::write_text(const fs::path& name, std::string_view content) {
  write(name, [&](const fs::path& staged) {
    std::ofstream out(staged, std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out)
      throw InputError(kind_ == OutputKind::kFile ? target_.string() : (target_ / name).string(),
                       "", "a writable file", std::strerror(errno));
  });
}

void OutputSet::commit() {
  if (committed_) return;
  const std::string source = target_.string();
  std::error_code ec;
  if (kind_ == OutputKind::kFile) {
    const fs::path staged = staging_ / absolute_.filename();
    if (type_of(staged) != fs::file_type::regular)
      throw InputError(source, "", "the writer to produce a file");
    // Checked again: the target may have changed while the work ran.
    const fs::file_type t = type_of(absolute_);
    if (exists_type(t) && t != fs::file_type::regular)
      throw InputError(source, "", "a regular file path", describe(t));
    fs::rename(staged, absolute_, ec);
    if (ec) throw InputError(source, "", "a writable directory", ec.message());
  } else if (!target_existed_ && !exists_type(type_of(absolute_))) {
    fs::rename(staging_, absolute_, ec);  // the whole set appears at once
    if (ec) throw InputError(source, "", "a writable directory", ec.message());
    staging_.clear();
  } else {
    // Every staged file and its destination, checked before the first one moves.
    std::vector<fs::path> files;
    for (auto it = fs::recursive_directory_iterator(staging_, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      const fs::file_type t = it->symlink_status().type();
      const fs::path rel = it->path().lexically_relative(staging_);
      const fs::path dest = absolute_ / rel;
      const fs::file_type dt = type_of(dest);
      if (t == fs::file_type::directory) {
        if (exists_type(dt) && dt != fs::file_type::directory)
          throw InputError((target_ / rel).string(), "", "a directory path (or nothing)",
                           describe(dt));
        continue;
      }
      if (t != fs::file_type::regular)
        throw InputError((target_ / rel).string(), "", "a regular file to write", describe(t));
      if (exists_type(dt) && dt != fs::file_type::regular)
        throw InputError((target_ / rel).string(), "", "a regular file path (or nothing)",
                         describe(dt));
      files.push_back(rel);
    }
    if (ec) throw InputError(source, "", "a readable staging directory", ec.message());
    for (const auto& rel : files) {
      const fs::path dest = absolute_ / rel;
      fs::create_directories(dest.parent_path(), ec);
      if (!ec) fs::rename(staging_ / rel, dest, ec);
      if (ec) throw InputError((target_ / rel).string(), "", "a writable directory", ec.message());
    }
  }
  committed_ = true;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
}

}  // namespace ferret
