#pragma once
// Undo commands that put a whole bone into the document (CT import). Like CutCommand they copy no mesh:
// a replaced bone's content (history included) is held by value, and its states share storage.
#include <QUndoCommand>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Pose.h"
#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim {
class Document;
class PlanNode;
}  // namespace reamsim

namespace reamsim::ui {

class ReamSession;

// A whole bone from what an importer read (mesh, original, report, frame, source, cuttability), its history
// starting from the mesh under `label`; for a node of its own or a ReplaceBoneCommand.
BoneContent boneContentFrom(ImportedBone bone, std::string name, std::string label);

// What goes with the cut bone when another bone takes its place, and comes back with it: the plan's poses and
// feed (a plan made for one bone does not apply to another) and the reamer's pose (BoneCommands.cpp).
class CutBoneCompanions {
 public:
  // Exchanges them around `exchangeBone`, which puts the other bone in the session.
  void exchange(ReamSession& session, const std::function<void()>& exchangeBone);

 private:
  std::vector<Pose> poses_;
  std::optional<std::string> feed_;
  std::optional<Pose> reamerPose_;
  bool first_ = true;  // the first exchange (the command's first redo): the caller places the reamer
};

// Replaces the session's bone (the one that is cut) and back. The plan's poses go with the bone: a plan
// made for the previous bone does not apply to the new one, and comes back with it on undo. So does the
// reamer's pose: undo and redo put the reamer back where it was on the bone that comes back (the first redo
// leaves it to the caller, which puts it clear of the new bone).
class ReplaceBoneCommand : public QUndoCommand {
 public:
  ReplaceBoneCommand(ReamSession& session, BoneContent incoming, const QString& text);
  void redo() override { exchange(); }
  void undo() override { exchange(); }
  // The bone not in the document: the replaced one once done, the imported one once undone.
  const BoneContent& held() const { return other_; }

 private:
  void exchange();
  ReamSession& session_;
  BoneContent other_;
  CutBoneCompanions others_;  // the other bone's
};

// Makes a bone beside the one that is cut, and the cut bone one beside it; undo swaps them back. The two
// nodes keep their ids and exchange their contents (histories, cursors and cuttability included, no mesh
// copied), and the plan's poses and the reamer's pose go with the cut bone as for a replacing import.
class SwapBoneBesideCommand : public QUndoCommand {
 public:
  SwapBoneBesideCommand(ReamSession& session, NodeId beside, const QString& text);
  void redo() override { exchange(); }
  void undo() override { exchange(); }

 private:
  void exchange();
  ReamSession& session_;
  NodeId beside_;
  CutBoneCompanions others_;  // the other bone's
};

// Adds bones to the document beside the session's bone (shown, not cut), or removes them: `add` says
// which of the two redo does; undo does the other. A bone put back keeps its id (Document::add), so
// commands that name it by id (SwapBoneBesideCommand, an earlier add) still find it.
class OtherBonesCommand : public QUndoCommand {
 public:
  // Adding: `nodes` are detached nodes. Removing: `ids` are bones of the document.
  OtherBonesCommand(Document& document, std::vector<std::unique_ptr<BoneNode>> nodes, const QString& text);
  OtherBonesCommand(Document& document, const std::vector<NodeId>& ids, const QString& text);
  void redo() override { add_ ? attach() : detach(); }
  void undo() override { add_ ? detach() : attach(); }

 private:
  void attach();
  void detach();
  Document& document_;
  bool add_;
  std::vector<std::unique_ptr<BoneNode>> detached_;
  std::vector<NodeId> attached_;
};

}  // namespace reamsim::ui
