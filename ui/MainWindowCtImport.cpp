// MainWindow: bones from CT volumes (the ctimport plugin's dialog) into the document — replacing the
// cut bone or beside it, both undoable — and the patient frame and source of the bone in the status
// bar and in File → Bone information.
#include <QAction>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QPlainTextEdit>
#include <QStatusBar>
#include <QUndoStack>
#include <QVBoxLayout>

#include "BoneCommands.h"
#include "BonePlacement.h"
#include "MainWindow.h"
#include "OtherBonesLayer.h"
#include "PluginHost.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim::ui {
namespace {

std::vector<BoneNode*> otherBonesOf(const ReamSession& session, Document& document) {
  std::vector<BoneNode*> out;
  for (BoneNode* b : document.nodesOf<BoneNode>())
    if (b != session.bone()) out.push_back(b);
  return out;
}

QString describe(const BoneNode& b) {
  return QObject::tr("%1\n  source: %2\n  patient frame: %3\n  faces: %L4, volume: %L5 mm³")
      .arg(QString::fromStdString(b.name()), QString::fromStdString(b.source().empty() ? "—" : b.source()),
           toString(b.patientFrame()))
      .arg(b.current().liveTriangleCount())
      .arg(b.current().volume(), 0, 'f', 1);
}

}  // namespace

void MainWindow::buildVolumeImport() {
  // File menu: after "Open without repair", before "Open recent" (the menu owns its actions).
  auto* file = qobject_cast<QMenu*>(action("open_no_repair")->parent());
  QAction* before = recentMenu_->menuAction();
  VolumeImportInterface* ct = plugins_.volumeImport();
  auto add = [&](const QString& name, const QString& text, auto slot) {
    auto* a = new QAction(text, file);
    a->setObjectName(name);
    file->insertAction(before, a);
    connect(a, &QAction::triggered, this, slot);
    return a;
  };
  const QString noPlugin = tr("No CT import plugin is loaded (Help → Plugins).");
  QAction* importFile = add("import_ct", tr("Import &CT volume…"), [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Import CT volume"), {},
                                                      plugins_.volumeImport()->nameFilters().join(";;"));
    if (!path.isEmpty()) importVolume(path);
  });
  QAction* importDicom = add("import_ct_dicom", tr("Import CT from a DICOM &folder…"), [this] {
    const QString dir = QFileDialog::getExistingDirectory(this, tr("Import CT: DICOM series folder"));
    if (!dir.isEmpty()) importVolume(dir);
  });
  for (QAction* a : {importFile, importDicom}) {
    a->setEnabled(ct != nullptr);  // reduced start: listed in Help → Plugins as not found
    if (!ct) a->setToolTip(noPlugin);
  }
  add("cut_bone_beside", tr("C&ut a bone beside instead"), [this] { cutBoneBesideInstead(); });
  add("remove_other_bones", tr("Remove the bones &beside"), [this] { removeOtherBones(); });
  add("bone_info", tr("Bone &information…"), [this] { showBoneInfo(); });
  file->insertSeparator(before);

  frameLabel_ = new QLabel(this);
  frameLabel_->setObjectName("BoneFrameLabel");
  statusBar()->insertPermanentWidget(0, frameLabel_);
  otherBones_ = std::make_unique<OtherBonesLayer>(session_->document(), session_->bone()->id(), *view_);
  boneFrameSubscription_ = session_->document().subscribe([this](const DocumentEvent& e) {
    if (e.id.kind() == NodeKind::Bone) updateBoneFrame();
  });
  // An undo or redo of a replacement swaps the bone: the title follows the bone's name.
  connect(session_.get(), &ReamSession::boneReplaced, this, [this] {
    boneName_ = QString::fromStdString(session_->bone()->name());
    savedPath_.clear();  // another bone: Save asks where (also when an undo brings the saved one back)
    ++boneGeneration_;
    updateTitle();
    updateStatus();
  });
  updateBoneFrame();
}

QDialog* MainWindow::importVolume(const QString& path) {
  VolumeImportInterface* ct = plugins_.volumeImport();
  if (!ct) {
    showError(tr("Import CT"), tr("Cannot import %1: no CT import plugin is loaded (Help → Plugins).").arg(path));
    return nullptr;
  }
  QDialog* dialog = ct->createImportDialog(
      path, [this](VolumeImportResult r) { placeImportedVolume(std::move(r)); }, this);
  dialog->show();
  dialog->raise();
  return dialog;
}

void MainWindow::placeImportedVolume(VolumeImportResult r) {
  if (r.bone.mesh.triangles.empty()) {
    showError(tr("Import CT"), tr("%1: the imported surface has no triangles").arg(r.name));
    return;
  }
  BoneContent content = boneContentFrom(std::move(r.bone), r.name.toStdString(), "import");
  const Bounds bounds = content.history.current().bounds();

  if (r.beside) {
    auto node = std::make_unique<BoneNode>(content.name);
    node->swapContent(content);  // a detached node: nothing is notified
    std::vector<std::unique_ptr<BoneNode>> nodes;
    nodes.push_back(std::move(node));
    session_->undoStack()->push(new OtherBonesCommand(session_->document(), std::move(nodes),
                                                      tr("Add %1 beside").arg(r.name)));
    otherBones_->fitViewToAll();
    statusBar()->showMessage(tr("Added %1 beside the bone (shown, not cut)").arg(r.name), 5000);
    return;
  }
  session_->undoStack()->push(new ReplaceBoneCommand(*session_, std::move(content), tr("Import %1").arg(r.name)));
  if (!session_->reamer()->cuttingVolume()) {
    try {
      session_->setReamer(loadPreset(kDefaultReamerPreset, reamerPresetsPath()));
    } catch (const std::exception& e) {
      showError(tr("Import CT"), QString::fromStdString(e.what()));
    }
  }
  session_->moveReamer(startPoseFor(bounds));
  statusBar()->showMessage(tr("Imported %1 (%2)").arg(r.name, toString(r.bone.frame)), 5000);
}

void MainWindow::removeOtherBones() {
  std::vector<NodeId> ids;
  for (BoneNode* b : otherBonesOf(*session_, session_->document())) ids.push_back(b->id());
  if (ids.empty()) return;
  session_->undoStack()->push(
      new OtherBonesCommand(session_->document(), ids, ids.size() == 1 ? tr("Remove the bone beside") : tr("Remove %1 bones beside").arg(ids.size())));
}

bool MainWindow::cutBoneBesideInstead(int index) {
  const std::vector<BoneNode*> others = otherBonesOf(*session_, session_->document());
  if (index < 0 && others.size() > 1) {
    QStringList names;
    for (std::size_t i = 0; i < others.size(); ++i)
      names << tr("%1. %2 (%L3 faces)").arg(i + 1).arg(QString::fromStdString(others[i]->name())).arg(others[i]->current().liveTriangleCount());
    bool ok = false;
    const QString picked = QInputDialog::getItem(this, tr("Cut a bone beside instead"),
                                                 tr("The bone to cut (the one cut now goes beside it):"), names, 0, false, &ok);
    if (!ok) return false;
    index = static_cast<int>(names.indexOf(picked));
  }
  if (index < 0 && others.size() == 1) index = 0;
  if (index < 0 || std::size_t(index) >= others.size()) return false;
  const BoneNode& beside = *others[std::size_t(index)];
  const QString name = QString::fromStdString(beside.name());
  session_->undoStack()->push(new SwapBoneBesideCommand(*session_, beside.id(), tr("Cut %1 instead").arg(name)));
  // As after an import that replaces the bone: the reamer starts clear of the bone it is now to cut.
  session_->moveReamer(startPoseFor(session_->bone()->current().bounds()));
  statusBar()->showMessage(session_->canCut() ? tr("Cutting %1; the previous bone is beside it (shown, not cut)").arg(name)
                                              : tr("%1: %2").arg(name, session_->cuttingStatus()),
                           5000);
  return true;
}

QString MainWindow::boneFrameText() const { return frameLabel_->text(); }

void MainWindow::updateBoneFrame() {
  const BoneNode& bone = *session_->bone();
  QString text = tr("patient frame: %1").arg(toString(bone.patientFrame()));
  const std::size_t others = otherBonesOf(*session_, session_->document()).size();
  if (others > 0) text += others == 1 ? tr(" · 1 bone beside") : tr(" · %1 bones beside").arg(others);
  frameLabel_->setText(text);
  frameLabel_->setToolTip(bone.source().empty() ? QString() : tr("source: %1").arg(QString::fromStdString(bone.source())));
  if (QAction* remove = action("remove_other_bones")) remove->setEnabled(others > 0);
  if (QAction* swap = action("cut_bone_beside")) swap->setEnabled(others > 0);
}

void MainWindow::showBoneInfo() {
  auto* dialog = new QDialog(this);
  dialog->setObjectName("BoneInfoDialog");
  dialog->setWindowTitle(tr("Bone information"));
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  auto* layout = new QVBoxLayout(dialog);
  const BoneNode& bone = *session_->bone();
  QString text = tr("Cut bone: ") + describe(bone) + "\n";
  text += tr("  history: %1 state(s), at %2; cutting: %3\n")
              .arg(bone.history().size())
              .arg(bone.history().cursor())
              .arg(session_->canCut() ? tr("on") : session_->cuttingStatus());
  for (BoneNode* other : otherBonesOf(*session_, session_->document()))
    text += "\n" + tr("Beside (shown, not cut): ") + describe(*other) + "\n" +
            (other->cuttable() ? tr("  can be cut (Cut a bone beside instead)\n")
                               : tr("  not a clean closed solid: it could be shown, not cut\n"));
  text += "\n" + tr("Import report:") + "\n" + QString::fromStdString(bone.importReport());
  auto* body = new QPlainTextEdit(text, dialog);
  body->setObjectName("BoneInfoText");
  body->setReadOnly(true);
  layout->addWidget(body);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  layout->addWidget(buttons);
  dialog->resize(720, 520);
  dialog->open();
}

}  // namespace reamsim::ui
