// The cut log CSV read back: the inverse of cutLogCsv (CutLogIO.cpp), for a log kept on disk (crash
// recovery) to return to the log panel. Strict: a file this program did not write, or one damaged on the
// way, is refused with the line and column, never half read.
#include <charconv>
#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>

#include "CutLogCsvHeader.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/CutLogIO.h"

namespace reamsim {
namespace {

// RFC 4180 records: fields split at commas, quoted fields may hold commas, quotes ("") and line breaks.
struct Record {
  long line = 0;  // where the record starts (1-based)
  std::vector<std::string> fields;
};

std::vector<Record> records(const std::string& text, const std::string& file) {
  std::vector<Record> out;
  Record r;
  std::string field;
  long line = 1;
  r.line = line;
  bool quoted = false, fieldStarted = false;
  auto endRecord = [&] {
    r.fields.push_back(std::move(field));
    out.push_back(std::move(r));
    r = Record{};
    field.clear();
    fieldStarted = false;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
          if (i + 1 < text.size() && text[i + 1] != ',' && text[i + 1] != '\n' && text[i + 1] != '\r')
            throw InputError(file, line, "a quoted field is followed by text before the next comma");
        }
      } else if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') {
        continue;  // a line break inside a field, as a Windows tool writes it: read as the writer's '\n'
      } else {
        if (c == '\n') ++line;
        field += c;
      }
      continue;
    }
    if (c == '"' && !fieldStarted && field.empty()) {
      quoted = fieldStarted = true;
    } else if (c == ',') {
      r.fields.push_back(std::move(field));
      field.clear();
      fieldStarted = false;
    } else if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') {
      continue;  // CRLF: the '\n' ends the record
    } else if (c == '\n') {
      endRecord();
      r.line = ++line;
    } else {
      if (c == '"') throw InputError(file, line, "a quote inside an unquoted field");
      field += c;
      fieldStarted = true;
    }
  }
  if (quoted) throw InputError(file, r.line, "a quoted field is not closed before the end of the file");
  if (!r.fields.empty() || !field.empty()) endRecord();  // a last line without its line break
  return out;
}

const std::vector<std::string>& columnNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    std::stringstream header(detail::kCutLogCsvHeaderWithAngles);  // every column any header has
    for (std::string name; std::getline(header, name, ',');) v.push_back(name);
    return v;
  }();
  return names;
}

// One record's fields, each read as its column's type; errors name the file, the record's line and the column.
class RowReader {
 public:
  RowReader(const Record& r, const std::string& file) : r_(r), file_(file) {}

  [[noreturn]] void fail(std::size_t column, const std::string& problem) const {
    throw InputError(file_, r_.line,
                     "column " + std::to_string(column + 1) + " (" + columnNames()[column] + "): " + problem);
  }
  const std::string& text(std::size_t c) const { return r_.fields[c]; }

  // A finite number; with `infOrNan`, also the writer's "inf" and "nan" (no other spelling of them).
  double number(std::size_t c, bool infOrNan = false) const {
    const std::string& s = text(c);
    if (infOrNan && (s == "inf" || s == "nan")) return s == "inf" ? HUGE_VAL : std::nan("");
    double v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
      fail(c, "'" + s + "' is not a number");
    if (!std::isfinite(v)) fail(c, "'" + s + "' is not finite");
    return v;
  }
  std::optional<double> optionalNumber(std::size_t c) const {
    return text(c).empty() ? std::nullopt : std::optional<double>(number(c));
  }
  std::uint64_t count(std::size_t c) const {
    const std::string& s = text(c);
    std::uint64_t v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
      fail(c, "'" + s + "' is not a whole number");
    return v;
  }
  bool flag(std::size_t c) const {
    if (text(c) != "0" && text(c) != "1") fail(c, "'" + text(c) + "' is not 0 or 1");
    return text(c) == "1";
  }
  // Three columns from `c`: all empty (no point) or all numbers.
  std::optional<Vec3> point(std::size_t c) const {
    const bool empty[3] = {text(c).empty(), text(c + 1).empty(), text(c + 2).empty()};
    if (empty[0] && empty[1] && empty[2]) return std::nullopt;
    for (std::size_t k = 0; k < 3; ++k)
      if (empty[k]) fail(c + k, "empty while the point's other coordinates are given");
    return Vec3{number(c), number(c + 1), number(c + 2)};
  }
  // "2026-11-22T05:27:11.325Z" as isoTimeUtc writes it; empty for a time not recorded (0).
  std::int64_t time(std::size_t c) const {
    const std::string& s = text(c);
    if (s.empty()) return 0;
    int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0, ms = 0;
    const bool shaped = s.size() == 24 && s[4] == '-' && s[7] == '-' && s[10] == 'T' && s[13] == ':' &&
                        s[16] == ':' && s[19] == '.' && s[23] == 'Z';
    auto digits = [&](std::size_t at, std::size_t n, int& out) {
      out = 0;
      for (std::size_t i = at; i < at + n; ++i) {
        if (s[i] < '0' || s[i] > '9') return false;
        out = out * 10 + (s[i] - '0');
      }
      return true;
    };
    if (!shaped || !digits(0, 4, y) || !digits(5, 2, mo) || !digits(8, 2, d) || !digits(11, 2, h) ||
        !digits(14, 2, mi) || !digits(17, 2, sec) || !digits(20, 3, ms) || y < 1970 || mo < 1 || mo > 12 ||
        d < 1 || d > 31 || h > 23 || mi > 59 || sec > 59)
      fail(c, "'" + s + "' is not a UTC time like 2026-11-22T05:27:11.325Z");
    std::tm t{};
    t.tm_year = y - 1900;
    t.tm_mon = mo - 1;
    t.tm_mday = d;
    t.tm_hour = h;
    t.tm_min = mi;
    t.tm_sec = sec;
    const std::time_t seconds = timegm(&t);
    if (t.tm_mday != d) fail(c, "'" + s + "' names a day the month does not have");  // timegm normalised it
    const std::int64_t unixMs = static_cast<std::int64_t>(seconds) * 1000 + ms;
    if (unixMs <= 0) fail(c, "'" + s + "' is not after 1970-01-01T00:00:00.000Z (an unrecorded time is empty)");
    return unixMs;
  }

 private:
  const Record& r_;
  const std::string& file_;
};

}  // namespace

std::vector<CutLogEntry> cutLogFromCsv(const std::string& text, const std::string& file) {
  const std::vector<Record> rows = records(text, file);
  if (rows.empty()) throw InputError(file, "empty: not a cut log (no header line)");
  std::string header = text.substr(0, text.find('\n'));  // as written: no field quoted
  if (!header.empty() && header.back() == '\r') header.pop_back();
  const bool withAngles = header == detail::kCutLogCsvHeaderWithAngles;
  const bool withUndone = withAngles || header == detail::kCutLogCsvHeader;
  const bool withNotes = withUndone || header == detail::kCutLogCsvHeaderWithoutUndone;
  if (!withNotes && header != detail::kCutLogCsvHeaderWithoutNotes)
    throw InputError(file, 1,
                     "not a ReamSim cut log: the header is not \"" + std::string(detail::kCutLogCsvHeader) + "\"");
  const std::size_t columns = columnNames().size() - (withAngles ? 0 : withUndone ? 2 : withNotes ? 3 : 4);
  std::vector<CutLogEntry> out;
  out.reserve(rows.size() - 1);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const Record& r = rows[i];
    if (r.fields.size() != columns)
      throw InputError(file, r.line, std::to_string(r.fields.size()) + " fields where the header has " +
                                         std::to_string(columns));
    const RowReader f(r, file);
    CutLogEntry e;
    e.stepIndex = f.count(0);
    e.timeUnixMs = f.time(1);
    e.pose.tip = {f.number(2), f.number(3), f.number(4)};
    e.pose.axis = {f.number(5), f.number(6), f.number(7)};
    e.boxesOverlap = f.flag(8);
    e.contact = f.flag(9);
    e.minDistanceMm = f.number(10, true);  // infinite while no distance is known
    e.removedMm3 = f.number(11);
    e.cumulativeMm3 = f.number(12);
    e.cutMs = f.number(13);
    e.faces = f.count(14);
    e.contactPoint = f.point(15);
    e.boneStateId = f.count(18);
    e.moveContactT = f.optionalNumber(19);
    e.moveContactPoint = f.point(20);
    e.reamer = f.text(23);
    e.reamerDiameterMm = f.optionalNumber(24).value_or(0.0);
    e.reamerSphereRadiusMm = f.optionalNumber(25);
    if (withUndone) e.undone = f.flag(26);
    if (withNotes) e.note = f.text(withUndone ? 27 : 26);
    if (withAngles) {  // derived from the axis and the landmarks of the export: checked, not kept
      f.optionalNumber(28);
      f.optionalNumber(29);
    }
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<CutLogEntry> readCutLogCsv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the cut log for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "read error");
  return cutLogFromCsv(text.str(), path);
}

}  // namespace reamsim
