#include "reamsim/ream/Resources.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace reamsim {
namespace fs = std::filesystem;

std::string resourceDir() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("REAMSIM_RESOURCE_DIR")) candidates.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share" / "reamsim" / "resources");
  candidates.emplace_back(REAMSIM_SOURCE_RESOURCE_DIR);
  std::string tried;
  for (const fs::path& c : candidates) {
    if (fs::exists(c / "reamers.json", ec)) return c.string();
    tried += " " + c.string();
  }
  throw std::runtime_error("ReamSim resources not found (looked in:" + tried + "); set REAMSIM_RESOURCE_DIR");
}

std::string resourcePath(const std::string& relative) { return (fs::path(resourceDir()) / relative).string(); }

}  // namespace reamsim
