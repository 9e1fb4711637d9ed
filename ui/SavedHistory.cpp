#include "SavedHistory.h"

#include <QFileInfo>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "reamsim/core/HistoryJournal.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::ui {

QString historyPathBeside(const QString& bonePath) { return bonePath + ".history.rsj"; }

void writeSavedHistory(const QString& path, const BoneHistory& history) {
  const std::string target = path.toStdString();
  const std::string partial = target + ".partial";  // a journal appends: a fresh one, renamed over when whole
  std::remove(partial.c_str());
  try {
    HistoryJournalWriter(partial).append(history.entries());
  } catch (...) {
    std::remove(partial.c_str());
    throw;
  }
  if (std::rename(partial.c_str(), target.c_str()) != 0) {
    std::remove(partial.c_str());
    throw InputError(target, "cannot replace the file with the new undo history");
  }
}

SavedHistoryRead readSavedHistory(const QString& path, const BoneFileFacts& saved, const BoneState& opened) {
  const std::string file = path.toStdString();
  const std::size_t states = saved.historyStates.value_or(0);
  if (!QFileInfo::exists(path)) throw std::runtime_error(file + ": not found");
  const std::vector<std::uint64_t> revisions = journalRevisions(file);
  if (revisions.size() != states)
    throw std::runtime_error(file + ": not the undo history saved with the bone (" + std::to_string(revisions.size()) +
                             " states; saved: " + std::to_string(states) + ")");
  BoneHistory history = readHistoryJournal(file, revisions, revisions.size() - 1);
  const BoneState& atSave = history.entries()[saved.historyCursor].state;
  const double volume = opened.volume();
  if (atSave.liveTriangleCount() != opened.liveTriangleCount() ||
      std::abs(atSave.volume() - volume) > 1e-9 * (1.0 + std::abs(volume)))
    throw std::runtime_error(file + ": its state at the save is not the bone in the file (" +
                             std::to_string(atSave.liveTriangleCount()) + " faces, " + std::to_string(atSave.volume()) +
                             " mm³, against " + std::to_string(opened.liveTriangleCount()) + " faces, " +
                             std::to_string(volume) + " mm³)");
  return {std::move(history), revisions};
}

}  // namespace reamsim::ui
