#include "RecoveryRead.h"

#include <QFileInfo>

#include "SavedHistory.h"
#include "reamsim/core/BoneState.h"
#include "reamsim/core/HistoryJournal.h"
#include "reamsim/mesh/RepairProgress.h"

namespace reamsim::ui {
namespace {

struct Stopped {};

// The copied bone's journal, read back and checked to end, at the copy's cursor, at the copied bone (a journal
// from another copy is not this one's).
BoneHistory readHistory(const RecoveredBone& copy, const BoneState& copied) {
  BoneHistory history = readHistoryJournal(copy.historyPath.toStdString(), copy.historyRevisions, copy.historyRevisions.size() - 1);
  requireStateIsBone(history.entries()[copy.historyCursor].state, copied,
                     QFileInfo(copy.historyPath).fileName().toStdString() + ": its state at the copy is not the copied bone");
  return history;
}

}  // namespace

RecoveredRead readRecoveryCopy(const MeshImportInterface& importer, const RecoveredBone& copy,
                               const ProgressCallback& progress) {
  RecoveredRead out;
  // Between stages: the callback's answer (the import's own stages check it inside).
  const auto stage = [&progress](const std::string& what) {
    if (progress && !progress(0.0, what)) throw Stopped{};
  };
  const auto bonesStage = [&progress](const std::string& what) -> RepairProgress {
    if (!progress) return {};
    return [&progress, what](double fraction, const std::string& inner) { return progress(fraction, what + ", " + inner); };
  };
  try {
    stage("the bone");
    try {
      out.bone = importer.importBone(copy.bonePath.toStdString(), false, bonesStage("the bone"));
      if (out.bone.mesh.triangles.empty()) throw std::runtime_error(copy.bonePath.toStdString() + ": the mesh has no triangles");
    } catch (const StageCancelled&) {
      throw Stopped{};
    } catch (const std::exception& e) {
      out.error = e.what();
      return out;
    }
    if (!copy.historyPath.isEmpty()) {
      stage("the undo history");
      try {
        out.history = readHistory(copy, BoneState::fromMesh(out.bone.mesh));
      } catch (const std::exception& e) {
        out.historyError = e.what();
      }
    }
    for (const RecoveredBone::Beside& b : copy.beside) {
      stage("the bone beside, " + b.name.toStdString());
      RecoveredRead::Beside read;
      try {
        read.bone = importer.importBone(b.path.toStdString(), false, bonesStage(b.name.toStdString()));
        if (read.bone->mesh.triangles.empty()) throw std::runtime_error(b.path.toStdString() + ": the mesh has no triangles");
      } catch (const StageCancelled&) {
        throw Stopped{};
      } catch (const std::exception& e) {
        read.bone.reset();
        read.error = e.what();
      }
      out.beside.push_back(std::move(read));
    }
  } catch (const Stopped&) {
    RecoveredRead stopped;
    stopped.cancelled = true;
    return stopped;
  }
  return out;
}

}  // namespace reamsim::ui
