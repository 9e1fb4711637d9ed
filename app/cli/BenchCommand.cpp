// bench KIND ...: benchmarks that print one JSON object. Each kind lives in its own file.
#include <dlfcn.h>

#include "CliArgs.h"
#include "Commands.h"

namespace reamsim::cli {

std::string allocatorName() {
  // tcmalloc exports tc_malloc beside malloc; linked in (cmake/ReamSimAllocator.cmake) it serves malloc too.
  return dlsym(RTLD_DEFAULT, "tc_malloc") ? "tcmalloc_minimal" : "glibc malloc";
}

int runBench(const std::vector<std::string>& args) {
  if (args.empty()) throw UsageError("bench needs a kind: cut, collision, winding");
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "cut") return runBenchCut(rest);
  if (args[0] == "collision") return runBenchCollision(rest);
  if (args[0] == "winding") return runBenchWinding(rest);
  throw UsageError("unknown bench kind '" + args[0] + "' (known: cut, collision, winding)");
}

}  // namespace reamsim::cli
