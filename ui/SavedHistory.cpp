#include "SavedHistory.h"

#include <QFile>
#include <QFileInfo>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "BoneCommands.h"
#include "CutCommand.h"
#include "reamsim/core/HistoryJournal.h"
#include "reamsim/mesh/FileReplace.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::ui {

QString historyPathBeside(const QString& bonePath) { return bonePath + ".history.rsj"; }

bool keepsExactCoordinates(const QString& bonePath) { return QFileInfo(bonePath).suffix().toLower() != "stl"; }

std::vector<BoneHistory::Entry> statesToSave(const BoneHistory& history, const QUndoStack& stack) {
  std::size_t redoable = 0;
  for (int i = stack.index(); i < stack.count(); ++i) {
    const QUndoCommand* c = stack.command(i);
    if (dynamic_cast<const CutCommand*>(c)) {
      ++redoable;
      continue;
    }
    if (dynamic_cast<const ReplaceBoneCommand*>(c) || dynamic_cast<const SwapBoneBesideCommand*>(c)) break;
  }
  const std::size_t keep = std::min(history.size(), history.cursor() + 1 + redoable);
  return {history.entries().begin(), history.entries().begin() + std::ptrdiff_t(keep)};
}

namespace {

// The file a path names through symbolic links (a link there stays a link: its target is written, as replaceFile
// writes the bone file).
QString throughLinks(QString path) {
  for (int hops = 0; hops < 40 && QFileInfo(path).isSymLink(); ++hops) path = QFileInfo(path).symLinkTarget();
  return path;
}

}  // namespace

QString writeSavedHistoryPart(const QString& linkedPath, const std::vector<BoneHistory::Entry>& states,
                              const QString& bonePath) {
  const QString path = throughLinks(linkedPath);
  const QString part = path + ".partial";  // a journal appends: a fresh one, renamed over when the save is whole
  const std::string file = part.toStdString();
  if (QFileInfo::exists(part) && !QFile::remove(part))
    throw InputError(file, "cannot remove what an earlier save left there");
  try {
    HistoryJournalWriter(file).append(states);
  } catch (...) {
    QFile::remove(part);
    throw;
  }
  // A patient's bone: the history is as closed to others as what it replaces, or as the bone file.
  const QString model = QFileInfo::exists(path) ? path : bonePath;
  if (QFileInfo::exists(model)) keepFileAttributes(model.toStdString(), file);
  return part;
}

void commitSavedHistory(const QString& part, const QString& linkedPath, const QString& bonePath) {
  const QString path = throughLinks(linkedPath);
  // A first save: the bone file has just been written (its attributes those of the file it replaced, if any).
  if (!QFileInfo::exists(path)) keepFileAttributes(bonePath.toStdString(), part.toStdString());
  if (std::rename(part.toStdString().c_str(), path.toStdString().c_str()) != 0) {
    QFile::remove(part);
    throw InputError(path.toStdString(), "cannot replace the file with the new undo history");
  }
}

void discardSavedHistory(const QString& part) {
  if (!part.isEmpty()) QFile::remove(part);
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
  requireStateIsBone(history.entries()[saved.historyCursor].state, opened,
                     file + ": its state at the save is not the bone in the file");
  return {std::move(history), revisions};
}

void requireStateIsBone(const BoneState& state, const BoneState& bone, const std::string& problem) {
  const double volume = bone.volume();
  if (state.liveTriangleCount() != bone.liveTriangleCount() ||
      std::abs(state.volume() - volume) > 1e-9 * (1.0 + std::abs(volume)))
    throw SavedHistoryAtAnotherBone(problem + " (" + std::to_string(state.liveTriangleCount()) + " faces, " +
                                    std::to_string(state.volume()) + " mm³, against " +
                                    std::to_string(bone.liveTriangleCount()) + " faces, " + std::to_string(volume) +
                                    " mm³)");
}

}  // namespace reamsim::ui
