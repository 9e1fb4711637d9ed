#pragma once
// The cut log as files: CSV (one row per step) and JSON (rows plus a summary).
#include <string>
#include <vector>

#include "reamsim/core/CutLogEntry.h"

namespace reamsim {

std::string cutLogCsv(const std::vector<CutLogEntry>& entries);
std::string cutLogJson(const std::vector<CutLogEntry>& entries, const std::string& summaryJson = "{}");
// Throws InputError naming the file when it cannot be written.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace reamsim
