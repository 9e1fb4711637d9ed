#pragma once
// The cut log as files: CSV (one row per step) and JSON (rows plus a summary).
#include <cstdint>
#include <string>
#include <vector>

#include "reamsim/core/BoneHistory.h"
#include "reamsim/core/CutLogEntry.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim {

// `rows` with CutLogEntry::undone set as the bone's `history` has them now: a row whose state lies past the
// history's cursor was undone. A row of no state of this history (another bone's, before an exchange; a branch
// the history left; a row read back, boneStateId 0) keeps its flag. What a saved log and a report say.
std::vector<CutLogEntry> withUndoneMarked(std::vector<CutLogEntry> rows, const BoneHistory& history);
// The same marks alone, row by row (no copy of the rows: the log panel asks at every change of the bone).
std::vector<bool> undoneRows(const std::vector<CutLogEntry>& rows, const BoneHistory& history);

// "2026-11-22T05:07:11.325Z" (UTC, milliseconds); "" for 0 (not recorded).
std::string isoTimeUtc(std::int64_t unixMs);
std::string cutLogCsv(const std::vector<CutLogEntry>& entries);
// The same with two more columns, version_deg and inclination_deg: each row's reamer axis in `frame` (as the log
// panel shows them; empty where the axis has none, e.g. pointing medially). What an export for review writes when
// the bone's landmarks give a frame; cutLogFromCsv reads it back (the angles checked as numbers, not kept).
std::string cutLogCsv(const std::vector<CutLogEntry>& entries, const ScapularFrame& frame);
// With a frame, each row also has version_deg and inclination_deg (null where the axis has none), as the CSV.
std::string cutLogJson(const std::vector<CutLogEntry>& entries, const std::string& summaryJson = "{}",
                       const ScapularFrame* frame = nullptr);
// The rows of a CSV that cutLogCsv wrote, read back (src/CutLogCsvReader.cpp): cutLogCsv of the result gives
// the same text for every row whose numbers are finite (for a file written with a frame: the same rows, the angle
// columns left out; written again with the frame they move by ~1e-5 degrees, the axis columns having 6 decimals) (min_distance_mm may also be "inf" or "nan"; a
// non-finite value anywhere else is refused). Pose::rollDeg is not in the file and reads as 0. Anything else (another header, a row with
// a missing or extra field, a value that is not a number, a flag that is not 0 or 1, a point with one
// coordinate missing, a time that is not the writer's UTC form) throws InputError naming `file`, the line
// and the column.
std::vector<CutLogEntry> cutLogFromCsv(const std::string& text, const std::string& file);
// cutLogFromCsv of a file's contents; InputError also when the file cannot be read.
std::vector<CutLogEntry> readCutLogCsv(const std::string& path);
// Replaces the file as a whole (replaceFile: a failed write leaves the file that was there); throws
// InputError naming the file when it cannot be written.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace reamsim
