#include "ferret/core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <string>
#include <system_error>

#include "ferret/core/error.hpp"

namespace ferret {
namespace fs = std::filesystem;

void write_file_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  if (path.empty()) throw InputError("output", "", "a non-empty output path");
  const fs::path parent = path.parent_path();
  std::error_code ec;
  if (!parent.empty()) {
    fs::create_directories(parent, ec);
    if (ec) throw InputError(path.string(), "", "a writable output directory", ec.message());
  }
  // The temporary keeps the target's extension: some writers (OpenCV, OctoMap)
  // choose the format from it.
  static std::atomic<unsigned> counter{0};
  fs::path tmp = path;
  std::string name(".");
  name += path.stem().string();
  name += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  name += path.extension().string();
  tmp.replace_filename(name);
  try {
    write(tmp);
    if (!fs::exists(tmp)) throw InputError(path.string(), "", "the writer to produce a file");
    fs::rename(tmp, path);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

void write_text_atomically(const fs::path& path, std::string_view content) {
  write_file_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) throw InputError(path.string(), "", "a writable file");
  });
}

}  // namespace ferret
