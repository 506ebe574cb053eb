#include "ferret/core/atomic_file.hpp"

#include "ferret/core/output_set.hpp"

namespace ferret {
namespace fs = std::filesystem;

// One-file outputs are output sets of one file, so they get the same checks (special
// files refused, parents not regular files) and the same cleanup.
void write_file_atomically(const fs::path& path,
                           const std::function<void(const fs::path&)>& write) {
  OutputSet set(path, OutputKind::kFile);
  set.write({}, write);
  set.commit();
}

void write_text_atomically(const fs::path& path, std::string_view content) {
  OutputSet set(path, OutputKind::kFile);
  set.write_text({}, content);
  set.commit();
}

}  // namespace ferret
