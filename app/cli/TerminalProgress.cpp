#include "TerminalProgress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

namespace reamsim::cli {

RepairProgress terminalProgress(const char* command) {
  if (!::isatty(STDERR_FILENO)) return {};
  struct Line {
    std::string stage;
    int percent = -1;
  };
  auto line = std::make_shared<Line>();
  return [line, name = std::string(command)](double fraction, const std::string& stage) {
    const int percent = int(std::floor(fraction * 100));
    if (stage == line->stage && percent == line->percent) return true;
    line->stage = stage;
    line->percent = percent;
    if (stage == "done") std::fprintf(stderr, "\r\033[K");  // the report follows on a clean line
    else std::fprintf(stderr, "\r\033[K%s: %s  %d %%", name.c_str(), stage.c_str(), percent);
    std::fflush(stderr);
    return true;
  };
}

}  // namespace reamsim::cli
