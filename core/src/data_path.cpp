#include "ferret/core/data_path.hpp"

#include <dlfcn.h>

#include <array>
#include <cstdlib>
#include <string>
#include <utility>

#include "ferret/core/error.hpp"

namespace ferret {
namespace fs = std::filesystem;
namespace {

// The file this function was loaded from: libferret_core.so, or the executable when
// ferret is linked statically.
fs::path loaded_object() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&loaded_object), &info) == 0 || info.dli_fname == nullptr)
    return {};
  std::error_code ec;
  const fs::path p = fs::canonical(info.dli_fname, ec);
  return ec ? fs::path(info.dli_fname) : p;
}

fs::path canonical_or_self(const fs::path& p) {
  std::error_code ec;
  const fs::path c = fs::canonical(p, ec);
  return ec ? p.lexically_normal() : c;
}

// <prefix>/<libdir>/libferret_core.so -> <prefix>: as many levels up as libdir has
// parts (lib, lib64, lib/x86_64-linux-gnu).
fs::path install_prefix(const fs::path& library_dir) {
  fs::path prefix = library_dir;
  const fs::path libdir(FERRET_INSTALL_LIBDIR);
  if (libdir.is_absolute()) return fs::path(FERRET_INSTALL_PREFIX);
  for (auto it = libdir.begin(); it != libdir.end(); ++it) prefix = prefix.parent_path();
  return prefix;
}

}  // namespace

DataDir data_dir() {
  if (const char* env = std::getenv("FERRET_DATA_DIR"); env != nullptr && *env != '\0')
    return {env, false};
  const fs::path object = loaded_object();
  const fs::path dir = object.parent_path();
  // Only the library the build wrote (at its build-tree path) is a build-tree library;
  // the same file installed anywhere else, even below the build directory, is not.
  if (!dir.empty() && dir == canonical_or_self(FERRET_BUILD_LIBRARY_DIR))
    return {FERRET_SOURCE_TREE, true};
#ifndef FERRET_SHARED_CORE
  // Static: the object is the executable; a build-tree program has no installed data.
  std::error_code ec;
  const fs::path installed = install_prefix(dir) / FERRET_INSTALL_DATADIR / "ferret";
  const auto build_dir = canonical_or_self(FERRET_BUILD_DIR).string();
  if (!fs::is_directory(installed, ec) && object.string().rfind(build_dir + "/", 0) == 0)
    return {FERRET_SOURCE_TREE, true};
  return {installed, false};
#else
  return {install_prefix(dir) / FERRET_INSTALL_DATADIR / "ferret", false};
#endif
}

fs::path data_path(std::string_view relative) {
  const DataDir d = data_dir();
  const fs::path rel(relative);
  fs::path path = d.root / rel;
  if (d.build_tree) {
    // The installed layout's folders as they lie in the source tree.
    static constexpr std::array<std::pair<std::string_view, std::string_view>, 4> kSourceFolders{
        {{"models", "urdf/models"},
         {"worlds", "examples/worlds"},
         {"plans", "examples/plans"},
         {"config", "config"}}};
    const std::string first = rel.begin() == rel.end() ? std::string() : rel.begin()->string();
    path = d.root / "examples" / rel;  // plot_experiment.py and anything else under examples/
    for (const auto& [installed, source] : kSourceFolders)
      if (first == installed) path = d.root / source / rel.lexically_relative(installed);
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(
        std::string(relative), "",
        std::string("a file shipped with ferret, at ") + path.string() +
            (d.build_tree ? " (the source tree of this build)" : " (the installed data)"),
        "not found");
  // Below the working directory: relative to it, so what a command prints and records
  // (a plan's robot_model, config --dump's source) reads the same in any checkout.
  const fs::path relative_to_cwd =
      canonical_or_self(path).lexically_relative(canonical_or_self(fs::current_path(ec)));
  if (!ec && !relative_to_cwd.empty() && *relative_to_cwd.begin() != "..") return relative_to_cwd;
  return path;
}

}  // namespace ferret
