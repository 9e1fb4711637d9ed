#pragma once
// The cut log as files: CSV (one row per step) and JSON (rows plus a summary).
#include <cstdint>
#include <string>
#include <vector>

#include "reamsim/core/CutLogEntry.h"

namespace reamsim {

// "2026-11-22T05:07:11.325Z" (UTC, milliseconds); "" for 0 (not recorded).
std::string isoTimeUtc(std::int64_t unixMs);
std::string cutLogCsv(const std::vector<CutLogEntry>& entries);
std::string cutLogJson(const std::vector<CutLogEntry>& entries, const std::string& summaryJson = "{}");
// Throws InputError naming the file when it cannot be written.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace reamsim
