#pragma once
// What ReamSim keeps in a bone file beside the surface, in its comments (docs/FORMATS.md "What a bone file says
// of itself"): the patient frame of the coordinates and, written by a save, the cut log saved beside it (its
// rows and its last row's time, so that reopening the bone continues that log and tells another log from it)
// and the bone removed before this state (the log's cumulative volume at it), and the undo history saved beside
// it (its states and where in them this one is, since session 57). A binary STL's 80-byte header
// holds what fits, in that order (reamsim::commentsKept). Header-only: the mesh-import plugin writes and reads
// them, the window checks what a save kept.
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "reamsim/core/PatientFrame.h"

namespace reamsim::ui {

struct BoneFileFacts {
  PatientFrame frame = PatientFrame::Unspecified;
  std::optional<double> removedMm3;
  std::optional<std::size_t> cutLogRows;
  std::int64_t cutLogLastMs = 0;  // the last row's time_utc (ms since 1970), 0 without rows
  std::optional<std::size_t> historyStates;  // the undo history saved beside: its states (2 or more)...
  std::size_t historyCursor = 0;             // ...and which of them this bone is (0-based)

  static BoneFileFacts ofFrame(PatientFrame frame) {  // the frame alone (a crash copy's bones)
    BoneFileFacts facts;
    facts.frame = frame;
    return facts;
  }
};

namespace bone_file_facts {
inline constexpr std::string_view kFrame = "reamsim patient_frame ";
inline constexpr std::string_view kCutLog = "reamsim cut_log ";  // rows, then the last row's time in ms
inline constexpr std::string_view kRemoved = "reamsim removed_mm3 ";
inline constexpr std::string_view kHistory = "reamsim undo_history ";  // states, then this one's index

// The text after `prefix` in the first comment that starts with it.
inline std::optional<std::string_view> text(const std::vector<std::string>& comments, std::string_view prefix) {
  for (const std::string& c : comments)
    if (std::string_view(c).substr(0, prefix.size()) == prefix) return std::string_view(c).substr(prefix.size());
  return std::nullopt;
}

// Whole text as a number (from_chars: the same in every locale); anything else is not a fact ReamSim wrote.
template <class T>
std::optional<T> number(std::optional<std::string_view> text) {
  if (!text) return std::nullopt;
  T value{};
  const auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (ec != std::errc() || end != text->data() + text->size()) return std::nullopt;
  return value;
}

inline std::string cutLogComment(std::size_t rows, std::int64_t lastMs) {
  return std::string(kCutLog) + std::to_string(rows) + " " + std::to_string(lastMs);
}
}  // namespace bone_file_facts

// The comments that say `facts`, most needed first (a binary STL keeps what fits, in this order).
inline std::vector<std::string> factComments(const BoneFileFacts& facts) {
  using namespace bone_file_facts;
  std::vector<std::string> out;
  if (facts.frame != PatientFrame::Unspecified) out.push_back(std::string(kFrame) + std::string(toString(facts.frame)));
  if (facts.cutLogRows) out.push_back(cutLogComment(*facts.cutLogRows, facts.cutLogLastMs));
  if (facts.removedMm3) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, *facts.removedMm3, std::chars_format::general, 17);
    out.push_back(std::string(kRemoved) + std::string(buf, r.ptr));
  }
  if (facts.historyStates)
    out.push_back(std::string(kHistory) + std::to_string(*facts.historyStates) + " " + std::to_string(facts.historyCursor));
  return out;
}

// The facts a file's comments say; what is not there, or does not parse whole, stays unset.
inline BoneFileFacts factsFromComments(const std::vector<std::string>& comments) {
  using namespace bone_file_facts;
  BoneFileFacts out;
  if (const auto frame = text(comments, kFrame)) out.frame = parsePatientFrame(*frame).value_or(PatientFrame::Unspecified);
  if (const auto log = text(comments, kCutLog)) {
    const std::size_t space = log->find(' ');
    const auto rows = number<std::size_t>(log->substr(0, space));
    const auto lastMs = space == std::string_view::npos ? std::nullopt : number<std::int64_t>(log->substr(space + 1));
    if (rows && lastMs) {
      out.cutLogRows = rows;
      out.cutLogLastMs = *lastMs;
    }
  }
  if (const auto removed = number<double>(text(comments, kRemoved)); removed && std::isfinite(*removed))
    out.removedMm3 = *removed;
  if (const auto history = text(comments, kHistory)) {
    const std::size_t space = history->find(' ');
    const auto states = number<std::size_t>(history->substr(0, space));
    const auto cursor = space == std::string_view::npos ? std::nullopt : number<std::size_t>(history->substr(space + 1));
    if (states && cursor && *states >= 2 && *cursor < *states) {
      out.historyStates = states;
      out.historyCursor = *cursor;
    }
  }
  return out;
}

}  // namespace reamsim::ui
