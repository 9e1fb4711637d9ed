#include "reamsim/ream/CutLogIO.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <optional>
#include <nlohmann/json.hpp>

#include "CutLogCsvHeader.h"
#include "reamsim/mesh/FileReplace.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim {
namespace {
// A number as printf writes it in the "C" locale ("%.6f", "%.3f" or "%.9g"), whatever the C library's
// locale: Qt sets that from the user's environment, and a decimal comma would split the CSV field.
enum class NumberStyle { Fixed6, Fixed3, Significant9 };
std::string num(double v, NumberStyle style = NumberStyle::Fixed6) {
  if (!std::isfinite(v)) return v > 0 ? "inf" : "nan";
  char buf[400];  // %.6f of 1e308 is 316 characters
  const int fixedDigits = style == NumberStyle::Fixed3 ? 3 : 6;
  const auto r = style == NumberStyle::Significant9
                     ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 9)
                     : std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, fixedDigits);
  return std::string(buf, r.ptr);
}
nlohmann::json finiteOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
// A text field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}
// A point's three CSV fields (each after a comma), empty when there is none.
std::string pointCsv(const std::optional<Vec3>& p) {
  return p ? "," + num(p->x) + "," + num(p->y) + "," + num(p->z) : std::string(",,,");
}
nlohmann::json pointOrNull(const std::optional<Vec3>& p) {
  return p ? nlohmann::json{p->x, p->y, p->z} : nlohmann::json(nullptr);
}
}  // namespace

std::string isoTimeUtc(std::int64_t unixMs) {
  if (unixMs <= 0) return "";
  const std::time_t seconds = static_cast<std::time_t>(unixMs / 1000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char buf[40];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &utc);
  char out[48];
  std::snprintf(out, sizeof out, "%s.%03dZ", buf, static_cast<int>(unixMs % 1000));
  return out;
}

std::vector<bool> undoneRows(const std::vector<CutLogEntry>& rows, const BoneHistory& history) {
  std::unordered_map<std::uint64_t, bool> undoneOf;  // this history's states: past the cursor or not
  for (std::size_t k = 0; k < history.size(); ++k) undoneOf[history.entries()[k].revision] = k > history.cursor();
  std::vector<bool> out;
  out.reserve(rows.size());
  for (const CutLogEntry& e : rows) {
    const auto it = e.boneStateId != 0 ? undoneOf.find(e.boneStateId) : undoneOf.end();
    out.push_back(it != undoneOf.end() ? it->second : e.undone);
  }
  return out;
}

std::vector<CutLogEntry> withUndoneMarked(std::vector<CutLogEntry> rows, const BoneHistory& history) {
  const std::vector<bool> undone = undoneRows(rows, history);
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i].undone = undone[i];
  return rows;
}

namespace {

// The header, then each row, `extra(row)` appended to its line (before the line break).
template <class Extra>
std::string cutLogCsvWith(const std::vector<CutLogEntry>& entries, const char* header, Extra extra) {
  std::string out = std::string(header) + "\n";
  for (const CutLogEntry& e : entries) {
    out += std::to_string(e.stepIndex) + "," + isoTimeUtc(e.timeUnixMs);
    for (double v : {e.pose.tip.x, e.pose.tip.y, e.pose.tip.z, e.pose.axis.x, e.pose.axis.y, e.pose.axis.z})
      out += "," + num(v);
    out += std::string(",") + (e.boxesOverlap ? "1" : "0") + "," + (e.contact ? "1" : "0");
    out += "," + num(e.minDistanceMm) + "," + num(e.removedMm3, NumberStyle::Significant9) + "," +
           num(e.cumulativeMm3, NumberStyle::Significant9) + "," + num(e.cutMs, NumberStyle::Fixed3) + "," +
           std::to_string(e.faces);
    out += pointCsv(e.contactPoint) + "," + std::to_string(e.boneStateId);
    out += (e.moveContactT ? "," + num(*e.moveContactT, NumberStyle::Significant9) : std::string(",")) +
           pointCsv(e.moveContactPoint);
    out += "," + csvField(e.reamer) + "," +
           (e.reamerDiameterMm > 0 ? num(e.reamerDiameterMm, NumberStyle::Significant9) : std::string()) + "," +
           (e.reamerSphereRadiusMm ? num(*e.reamerSphereRadiusMm, NumberStyle::Significant9) : std::string()) + "," +
           (e.undone ? "1" : "0") + "," + csvField(e.note) + extra(e) + "\n";
  }
  return out;
}

}  // namespace

std::string cutLogCsv(const std::vector<CutLogEntry>& entries) {
  return cutLogCsvWith(entries, detail::kCutLogCsvHeader, [](const CutLogEntry&) { return std::string(); });
}

std::string cutLogCsv(const std::vector<CutLogEntry>& entries, const ScapularFrame& frame) {
  return cutLogCsvWith(entries, detail::kCutLogCsvHeaderWithAngles, [&frame](const CutLogEntry& e) {
    try {
      const AxisAngles a = feedAxisAngles(frame, e.pose.axis);
      return "," + num(a.versionDeg, NumberStyle::Significant9) + "," + num(a.inclinationDeg, NumberStyle::Significant9);
    } catch (const std::invalid_argument&) {  // no angles for this axis
      return std::string(",,");
    }
  });
}

std::string cutLogJson(const std::vector<CutLogEntry>& entries, const std::string& summaryJson,
                       const ScapularFrame* frame) {
  nlohmann::json rows = nlohmann::json::array();
  for (const CutLogEntry& e : entries) {
    nlohmann::json r = {{"step", e.stepIndex},
                        {"time_utc", isoTimeUtc(e.timeUnixMs)},
                        {"tip", {e.pose.tip.x, e.pose.tip.y, e.pose.tip.z}},
                        {"axis", {e.pose.axis.x, e.pose.axis.y, e.pose.axis.z}},
                        {"boxes_overlap", e.boxesOverlap},
                        {"contact", e.contact},
                        {"min_distance_mm", finiteOrNull(e.minDistanceMm)},
                        {"removed_mm3", e.removedMm3},
                        {"cumulative_mm3", e.cumulativeMm3},
                        {"cut_ms", e.cutMs},
                        {"faces", e.faces},
                        {"bone_state", e.boneStateId}};
    r["contact_point"] = pointOrNull(e.contactPoint);
    r["move_contact_t"] = e.moveContactT ? nlohmann::json(*e.moveContactT) : nlohmann::json(nullptr);
    r["move_contact_point"] = pointOrNull(e.moveContactPoint);
    r["reamer"] = e.reamer.empty() ? nlohmann::json(nullptr)
                                   : nlohmann::json{{"name", e.reamer},
                                                    {"diameter_mm", e.reamerDiameterMm},
                                                    {"sphere_radius_mm", e.reamerSphereRadiusMm ? nlohmann::json(*e.reamerSphereRadiusMm)
                                                                                                : nlohmann::json(nullptr)}};
    r["note"] = e.note;
    if (frame) try {  // as the CSV's version_deg and inclination_deg: null where the axis has none
        const AxisAngles a = feedAxisAngles(*frame, e.pose.axis);
        r["version_deg"] = a.versionDeg;
        r["inclination_deg"] = a.inclinationDeg;
      } catch (const std::invalid_argument&) {
        r["version_deg"] = r["inclination_deg"] = nullptr;
      }
    rows.push_back(r);
  }
  nlohmann::json j = {{"summary", nlohmann::json::parse(summaryJson)}, {"steps", rows}};
  // A note read from a damaged file may not be UTF-8: replaced (U+FFFD), never a reason to lose the log.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

void writeTextFile(const std::string& path, const std::string& text) { replaceFile(path, text); }

}  // namespace reamsim
