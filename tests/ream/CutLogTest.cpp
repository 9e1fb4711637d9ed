// Every logged step carries the wall-clock time it was committed, and the CSV/JSON files give it in UTC.
#include <gtest/gtest.h>

#include <chrono>
#include <clocale>
#include <cmath>
#include <random>
#include <string>

#include "ReamFixture.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/tools/Primitives.h"

namespace reamsim {
namespace {

TEST(CutLog, StepsCarryTheirCommitTimeIntoTheFiles) {
  test::ReamScene s(test::blockBelowZ0(), test::flatReamer20());
  const auto now = [] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
  };
  const std::int64_t before = now();
  s.controller->moveTo(Pose{{0, 0, 0.5}, {0, 0, -1}, 0});
  s.controller->moveTo(Pose{{0, 0, -0.5}, {0, 0, -1}, 0});
  const std::int64_t after = now();
  ASSERT_GE(s.log->size(), 1u);
  const CutLogEntry& e = s.log->entries().back();
  EXPECT_TRUE(e.contact);
  EXPECT_GE(e.timeUnixMs, before);
  EXPECT_LE(e.timeUnixMs, after);

  EXPECT_EQ(isoTimeUtc(1795325231325), "2026-11-22T05:27:11.325Z");
  EXPECT_EQ(isoTimeUtc(0), "");
  const std::string csv = cutLogCsv(s.log->entries());
  EXPECT_EQ(csv.rfind("step,time_utc,", 0), 0u) << csv;
  EXPECT_NE(csv.find("," + isoTimeUtc(e.timeUnixMs) + ","), std::string::npos) << csv;
  EXPECT_NE(cutLogJson(s.log->entries()).find("\"time_utc\": \"" + isoTimeUtc(e.timeUnixMs) + "\""), std::string::npos);
}


// Rows with every optional part set and unset, a reamer name the CSV has to quote, a distance not yet known.
std::vector<CutLogEntry> variedEntries() {
  CutLogEntry a;
  a.stepIndex = 0;
  a.timeUnixMs = 1795325231325;
  a.pose = Pose{{-38.125, 12.5, 101.0625}, {0.6, -0.8, 0}, 0};
  a.boxesOverlap = true;
  a.minDistanceMm = std::numeric_limits<double>::infinity();
  a.cutMs = 0.25;
  a.faces = 14998;
  a.reamer = "glenoid-36-R30";
  a.reamerDiameterMm = 36;
  a.reamerSphereRadiusMm = 30;
  a.note = "seated, \"first\" pass";
  CutLogEntry b = a;
  b.note.clear();
  b.stepIndex = 7;
  b.timeUnixMs = 0;  // not recorded
  b.contact = true;
  b.minDistanceMm = 0;
  b.removedMm3 = 12.3456789;
  b.cumulativeMm3 = 1203.04887;
  b.cutMs = 4.785;
  b.faces = 15210;
  b.contactPoint = Vec3{-40.5, 11.25, 99.875};
  b.moveContactT = 0.15;
  b.moveContactPoint = Vec3{-40.25, 11.0, 99.5};
  b.boneStateId = 42;
  b.reamer = "flat, 20 mm \"custom\"\nsecond line";
  b.reamerDiameterMm = 20;
  b.reamerSphereRadiusMm.reset();
  CutLogEntry c = b;
  c.stepIndex = 8;
  c.reamer.clear();
  c.reamerDiameterMm = 0;
  c.contactPoint.reset();
  c.moveContactT.reset();
  c.moveContactPoint.reset();
  return {a, b, c};
}

TEST(CutLog, ACsvReadsBackToTheRowsItWasWrittenFrom) {
  const std::vector<CutLogEntry> rows = variedEntries();
  const std::string csv = cutLogCsv(rows);
  const std::vector<CutLogEntry> back = cutLogFromCsv(csv, "log.csv");
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_EQ(cutLogCsv(back), csv);  // the same text again
  for (std::size_t i = 0; i < rows.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(back[i].stepIndex, rows[i].stepIndex);
    EXPECT_EQ(back[i].timeUnixMs, rows[i].timeUnixMs);
    EXPECT_EQ(back[i].pose.tip.x, rows[i].pose.tip.x);
    EXPECT_EQ(back[i].pose.axis.y, rows[i].pose.axis.y);
    EXPECT_EQ(back[i].boxesOverlap, rows[i].boxesOverlap);
    EXPECT_EQ(back[i].contact, rows[i].contact);
    EXPECT_EQ(back[i].minDistanceMm, rows[i].minDistanceMm);
    EXPECT_EQ(back[i].removedMm3, rows[i].removedMm3);
    EXPECT_EQ(back[i].cumulativeMm3, rows[i].cumulativeMm3);
    EXPECT_EQ(back[i].faces, rows[i].faces);
    EXPECT_EQ(back[i].contactPoint.has_value(), rows[i].contactPoint.has_value());
    EXPECT_EQ(back[i].moveContactT, rows[i].moveContactT);
    EXPECT_EQ(back[i].moveContactPoint.has_value(), rows[i].moveContactPoint.has_value());
    EXPECT_EQ(back[i].boneStateId, rows[i].boneStateId);
    EXPECT_EQ(back[i].reamer, rows[i].reamer);
    EXPECT_EQ(back[i].reamerDiameterMm, rows[i].reamerDiameterMm);
    EXPECT_EQ(back[i].reamerSphereRadiusMm, rows[i].reamerSphereRadiusMm);
    EXPECT_EQ(back[i].note, rows[i].note);
  }
  EXPECT_EQ(back[1].contactPoint->z, 99.875);
  EXPECT_TRUE(cutLogFromCsv(cutLogCsv({}), "empty.csv").empty());  // a header alone: no rows
  // Windows line breaks and a last line without one read the same.
  std::vector<CutLogEntry> oneLineNames = rows;
  oneLineNames[1].reamer = "flat, 20 mm";  // a line break inside a quoted field is part of the name
  const std::string plain = cutLogCsv(oneLineNames);
  std::string crlf;
  for (char ch : plain) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  EXPECT_EQ(cutLogCsv(cutLogFromCsv(crlf, "crlf.csv")), plain);
  EXPECT_EQ(cutLogCsv(cutLogFromCsv(csv.substr(0, csv.size() - 1), "cut.csv")), csv);
}

// A row's note (an educator's annotation) is any text: commas, quotes, line breaks, UTF-8. It reads back as
// written, the JSON has it, and a log written before rows had notes (no "note" column) still reads.
TEST(CutLog, NotesReadBackAndLogsWithoutTheNoteColumnStillRead) {
  std::vector<CutLogEntry> rows = variedEntries();
  rows[0].note = "Glenoid: 5° retroversion – corrected ✓";
  rows[1].note = "line one, \"quoted\"\nline two\n";
  rows[2].note = ",";
  const std::string csv = cutLogCsv(rows);
  const std::vector<CutLogEntry> back = cutLogFromCsv(csv, "notes.csv");
  ASSERT_EQ(back.size(), 3u);
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(back[i].note, rows[i].note) << i;
  // Through a Windows tool (every line break CRLF, also inside the quoted note): the same notes.
  std::string crlf;
  for (char ch : csv) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  const std::vector<CutLogEntry> windows = cutLogFromCsv(crlf, "notes_crlf.csv");
  ASSERT_EQ(windows.size(), 3u);
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(windows[i].note, rows[i].note) << i;
  const std::string json = cutLogJson(rows);
  EXPECT_NE(json.find("\"note\": \"Glenoid: 5° retroversion – corrected ✓\""), std::string::npos) << json;
  EXPECT_NE(json.find(R"("note": "line one, \"quoted\"\nline two\n")"), std::string::npos) << json;
  // A note that is not UTF-8 (a damaged file read back) does not stop the JSON.
  rows[2].note = "\xff\xfe";
  EXPECT_NE(cutLogJson(rows).find("\"note\": \"\xef\xbf\xbd\xef\xbf\xbd\""), std::string::npos);

  // The same rows as the writer wrote them before session 56 (no "undone" column) and before session 55 (no
  // "note" either): read as not undone, with no notes.
  std::vector<CutLogEntry> plain = variedEntries();
  for (CutLogEntry& e : plain) e.note.clear();
  const std::string text = cutLogCsv(plain);
  const auto older = [&text](bool withNote) {
    std::string out;
    for (std::size_t at = 0, end; at < text.size(); at = end + 1) {
      end = text.find('\n', at);
      std::string line = text.substr(at, end - at);
      if (at == 0) {
        EXPECT_EQ(line.substr(line.size() - 12), ",undone,note");
        line.resize(line.size() - 12);
        if (withNote) line += ",note";
      } else if (line.size() >= 3 && line.substr(line.size() - 3) == ",0,") {  // a record's last line
        line.resize(line.size() - 3);
        if (withNote) line += ",";
      }
      out += line + "\n";
    }
    return out;
  };
  for (const bool withNote : {true, false}) {
    const std::string old = older(withNote);
    const std::vector<CutLogEntry> oldRows = cutLogFromCsv(old, "before.csv");
    ASSERT_EQ(oldRows.size(), 3u) << withNote;
    EXPECT_EQ(cutLogCsv(oldRows), cutLogCsv(plain)) << withNote;
    // An old header with rows of the new width is refused.
    const std::string oldHeader = old.substr(0, old.find('\n') + 1);
    const std::string newRows = text.substr(text.find('\n') + 1);
    EXPECT_THROW(cutLogFromCsv(oldHeader + newRows, "mixed.csv"), InputError) << withNote;
  }
}

// A row whose cut was undone when the log was written says so, and reads back so (a saved bone reopened).
TEST(CutLog, AnUndoneRowReadsBackUndone) {
  std::vector<CutLogEntry> rows = variedEntries();
  rows[1].undone = true;
  const std::vector<CutLogEntry> back = cutLogFromCsv(cutLogCsv(rows), "undone.csv");
  ASSERT_EQ(back.size(), 3u);
  EXPECT_FALSE(back[0].undone);
  EXPECT_TRUE(back[1].undone);
  EXPECT_FALSE(back[2].undone);
}

// An export for review carries each row's version and inclination in the landmarks' frame (empty where the axis
// has none); it reads back to the same rows, and damaged angles are refused naming their column.
TEST(CutLog, AnExportWithAnglesReadsBackAndItsAnglesAreTheAxis) {
  std::vector<CutLogEntry> rows = variedEntries();
  for (CutLogEntry& e : rows) e.note = e.reamer = "one line";  // a record a line, for the look at the lines below
  const ScapularFrame frame = scapularFrame(loadDefaultLandmarks());
  const AxisAngles aimed{-7.25, 4.5};
  rows[0].pose.axis = outwardAxisFor(frame, aimed) * -1.0;  // a feed axis at known angles
  rows[2].pose.axis = frame.lateral;                        // feeding outwards: no angles
  const std::string csv = cutLogCsv(rows, frame);
  EXPECT_EQ(csv.substr(0, csv.find('\n')).rfind(",version_deg,inclination_deg"), csv.find('\n') - 28);
  std::vector<std::string> lines;
  for (std::size_t at = 0, next; at < csv.size(); at = next + 1) lines.push_back(csv.substr(at, (next = csv.find('\n', at)) - at));
  ASSERT_EQ(lines.size(), 4u);
  const std::string first = lines[1].substr(lines[1].rfind(',', lines[1].rfind(',') - 1) + 1);
  EXPECT_NEAR(std::stod(first.substr(0, first.find(','))), -7.25, 1e-6) << first;
  EXPECT_NEAR(std::stod(first.substr(first.find(',') + 1)), 4.5, 1e-6) << first;
  EXPECT_EQ(lines[3].substr(lines[3].size() - 2), ",,");
  const std::vector<CutLogEntry> back = cutLogFromCsv(csv, "angles.csv");
  EXPECT_EQ(cutLogCsv(back), cutLogCsv(rows));  // the same rows; the angles are derived, not kept
  // (Written again from the rows read back the angles move by ~1e-5 degrees: the axis columns keep 6 decimals.)
  // The JSON log has them too: on every row, null where the axis has none.
  const std::string json = cutLogJson(rows, "{}", &frame);
  std::size_t angles = 0;
  for (std::size_t at = json.find("\"version_deg\""); at != std::string::npos; at = json.find("\"version_deg\"", at + 1)) ++angles;
  EXPECT_EQ(angles, rows.size());
  EXPECT_NE(json.find("\"version_deg\": -7.2"), std::string::npos);
  EXPECT_NE(json.find("\"version_deg\": null"), std::string::npos);
  EXPECT_EQ(cutLogJson(rows).find("version_deg"), std::string::npos);
  std::string damaged = csv;
  damaged.replace(damaged.find(first), first.size(), "left,4.5");
  try {
    cutLogFromCsv(damaged, "angles.csv");
    ADD_FAILURE() << "a word where an angle goes was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("angles.csv:2: column 29 (version_deg): 'left' is not a number"), std::string::npos)
        << e.what();
  }
}

// Each damage is refused with the file, the line (of the record it is in) and the column.
TEST(CutLog, ADamagedCsvIsRefusedNamingTheLineAndTheColumn) {
  const std::string csv = cutLogCsv(variedEntries());
  auto expectRefused = [](const std::string& text, const std::string& where, const std::string& what) {
    try {
      cutLogFromCsv(text, "crash.csv");
      ADD_FAILURE() << "accepted: " << where << " " << what;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("crash.csv" + where, 0), 0u) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
    }
  };
  expectRefused("", ": ", "no header");
  expectRefused("step,time\n0,\n", ":1: ", "not a ReamSim cut log");
  // One change each to the written file: the text replaced (its first place after `after`), then the error.
  struct Damage {
    std::string after, from, to, where, what;
  };
  const std::vector<Damage> damages = {
      {"", "-38.125000", "-38,125000", ":2: ", "29 fields where the header has 28"},  // a decimal comma
      {"", "-38.125000", "-38.12x000", ":2: ", "column 3 (tip_x): '-38.12x000' is not a number"},
      {"", ",14998,", ",1.5e4,", ":2: ", "column 15 (faces): '1.5e4' is not a whole number"},
      {"", "2026-11-22T05:27:11.325Z", "2026-11-31T05:27:11.325Z", ":2: ", "column 2 (time_utc)"},
      {"\n", ",1,0,", ",1,2,", ":2: ", "column 10 (contact): '2' is not 0 or 1"},
      {"", "-40.500000", "", ":3: ", "column 16 (contact_x): empty while the point's other coordinates are given"},
      {"", "12.3456789", "inf", ":3: ", "column 12 (removed_mm3): 'inf' is not finite"},
      {"", ",inf,", ",-inf,", ":2: ", "column 11 (min_distance_mm): '-inf' is not finite"},  // only "inf"
      {"", "T05:27", "T-5:27", ":2: ", "column 2 (time_utc)"},
      {"", "2026-11-22T05:27:11.325Z", "1970-01-01T00:00:00.000Z", ":2: ", "is not after 1970"},
      {"", "step,time_utc", "\"step,time_utc\"", ":1: ", "not a ReamSim cut log"},  // a quoted header
      // The row after the reamer whose name spans two lines starts on line 5.
      {"second line", "\n8,", "\n8x,", ":5: ", "column 1 (step): '8x' is not a whole number"},
  };
  for (const Damage& d : damages) {
    std::string text = csv;
    const std::size_t at = text.find(d.from, d.after.empty() ? 0 : text.find(d.after));
    ASSERT_NE(at, std::string::npos) << d.from;
    text.replace(at, d.from.size(), d.to);
    expectRefused(text, d.where, d.what);
  }
  const std::string text = csv.substr(0, csv.rfind("second line"));  // the file ends inside a quoted field
  expectRefused(text, ":3: ", "not closed");
  EXPECT_THROW(readCutLogCsv("/nonexistent/cut_log.csv"), InputError);
}

// Damage of every kind (bytes changed, dropped, repeated; the file cut anywhere) is either refused with an
// InputError naming the file, or read as rows that write and read back the same: never a crash, never
// another exception.
TEST(CutLog, MutatedCsvFilesAreReadOrRefusedCleanly) {
  // Half the trials on an export with the angle columns (the header the reader knows with most columns).
  const std::string plainCsv = cutLogCsv(variedEntries());
  const std::string anglesCsv = cutLogCsv(variedEntries(), scapularFrame(loadDefaultLandmarks()));
  std::mt19937 rng(4711);
  const std::string alphabet = "0123456789,.-+eE\"\r\nxinfa Z:T";
  int refused = 0, read = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const std::string& csv = trial % 2 ? anglesCsv : plainCsv;
    std::string text = csv;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int k = 0; k < edits && !text.empty(); ++k) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 4) {
        case 0: text[at] = alphabet[rng() % alphabet.size()]; break;
        case 1: text.erase(at, 1 + rng() % 8); break;
        case 2: text.insert(at, text.substr(rng() % text.size(), 1 + rng() % 12)); break;
        default: text.resize(at); break;
      }
    }
    try {
      const std::vector<CutLogEntry> rows = cutLogFromCsv(text, "m.csv");
      const std::string again = cutLogCsv(rows);
      EXPECT_EQ(cutLogCsv(cutLogFromCsv(again, "again.csv")), again) << text;
      ++read;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("m.csv", 0), 0u) << e.what();
      ++refused;
    }
  }
  EXPECT_GT(refused, 10000);  // most damage is seen
  EXPECT_GT(read, 100);       // and harmless damage (a digit changed) still reads
}

// Qt sets the C library's locale from the user's environment: a decimal-comma locale must not change what
// the log file says (a comma in a number would shift every column after it).
TEST(CutLog, TheCsvIsTheSameInADecimalCommaLocale) {
  const std::string expected = cutLogCsv(variedEntries());
  const std::string previous = std::setlocale(LC_ALL, nullptr);
  if (!std::setlocale(LC_ALL, "de_DE.UTF-8") && !std::setlocale(LC_ALL, "de_DE.utf8"))
    GTEST_SKIP() << "no de_DE.UTF-8 locale here (scripts/install-deps.sh generates it)";
  char probe[16];
  std::snprintf(probe, sizeof probe, "%.1f", 1.5);
  const std::string written = cutLogCsv(variedEntries());
  std::vector<CutLogEntry> back;
  try {
    back = cutLogFromCsv(written, "de.csv");
  } catch (...) {
  }
  std::setlocale(LC_ALL, previous.c_str());
  EXPECT_EQ(std::string(probe), "1,5");  // the locale is in effect for printf
  EXPECT_EQ(written, expected);
  EXPECT_EQ(back.size(), 3u);
}

}  // namespace
}  // namespace reamsim
