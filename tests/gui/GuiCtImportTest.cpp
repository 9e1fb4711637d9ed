// CT import through the real window and the real ctimport plugin: a phantom volume written by the test
// (tests/ctimport/Phantom.h) is opened in the dialog, its slices follow the threshold, the preview has a
// surface, and the bone goes into the document — replacing the bone (undo restores the previous one
// exactly) or beside it (undo removes it) — with its patient frame. Bad volumes end in an error dialog;
// Cancel stops an import; the real headsq scan of ../shared/data becomes a closed mesh.
#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QImage>
#include <QMessageBox>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QSemaphore>
#include <QTemporaryDir>
#include <QThreadPool>
#include <QUndoStack>
#include <QtTest/QTest>
#include <filesystem>

#include "../ctimport/Phantom.h"
#include "GuiEnvironment.h"
#include "GuiHelpers.h"
#include "CachedBoneLayer.h"
#include "OtherBonesLayer.h"
#include "reamsim/mesh/Validation.h"

namespace reamsim::ui::test {
namespace {

constexpr int kWaitMs = 180000;  // a generous bound on waiting, not a timing check

// The phantom of the CT import tests (a sphere pierced by a cylinder of bone in soft tissue) on an oblique,
// anisotropic grid, written once per test run as an attached NRRD in LPS.
struct PhantomVolume {
  phantom::SphereAndCylinder shape;
  phantom::Grid grid;
  std::string path;
};

const PhantomVolume& phantomVolume() {
  static const PhantomVolume p = [] {
    PhantomVolume v;
    v.grid = phantom::gridAround(v.shape.center, 26, {0.9, 0.8, 1.0}, phantom::rotation({1, 2, 3}, 30));
    const auto dir = std::filesystem::temp_directory_path() / ("reamsim_gui_ct_" + std::to_string(QCoreApplication::applicationPid()));
    std::filesystem::create_directories(dir);
    v.path = (dir / "phantom.nrrd").string();
    phantom::writeNrrd(v.path, v.grid, phantom::sample(v.grid, [&](const Vec3& p) { return v.shape.inside(p); }));
    return v;
  }();
  return p;
}

bool waitIdle(QDialog* d) {
  bool idle = false;
  EXPECT_TRUE(QMetaObject::invokeMethod(d, "waitIdle", Q_RETURN_ARG(bool, idle), Q_ARG(int, kWaitMs)));
  return idle;
}

int maskPixels(QDialog* d, int axis) {
  int n = -1;
  EXPECT_TRUE(QMetaObject::invokeMethod(d, "maskPixels", Q_RETURN_ARG(int, n), Q_ARG(int, axis)));
  return n;
}

// Pixels drawn in the overlay colour (orange: red well above blue); grey pixels have r = g = b.
int overlayPixels(QDialog* d, int axis) {
  QImage image;
  EXPECT_TRUE(QMetaObject::invokeMethod(d, "sliceImage", Q_RETURN_ARG(QImage, image), Q_ARG(int, axis)));
  int n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QRgb c = image.pixel(x, y);
      if (qRed(c) > qBlue(c) + 60) ++n;
    }
  return n;
}

void setLower(QDialog* d, double hu) {
  auto* lower = d->findChild<QDoubleSpinBox*>("LowerThreshold");
  ASSERT_NE(lower, nullptr);
  lower->setValue(hu);
}

QDialog* openInDialog(MainWindow& w, const std::string& path) {
  QDialog* d = w.importVolume(QString::fromStdString(path));
  EXPECT_NE(d, nullptr) << w.lastError().toStdString();
  if (!d) return nullptr;
  EXPECT_TRUE(waitIdle(d));
  EXPECT_TRUE(d->property("volumeLoaded").toBool()) << d->property("lastError").toString().toStdString();
  return d;
}

// Clicks Import and waits until the dialog has delivered the bone (and closed) or stopped.
void clickImport(QDialog* d, bool beside) {
  auto* place = d->findChild<QRadioButton*>(beside ? "PlaceBeside" : "PlaceReplace");
  ASSERT_NE(place, nullptr);
  place->setChecked(true);
  auto* button = d->findChild<QPushButton*>("ImportButton");
  ASSERT_NE(button, nullptr);
  ASSERT_TRUE(button->isEnabled());
  QPointer<QDialog> dialog(d);
  button->click();
  if (dialog) {
    EXPECT_TRUE(waitIdle(dialog));
  }
}

// Pixels that differ between two pictures of the view (more than 1 in a channel).
int differingPixels(const QImage& a, const QImage& b) {
  if (a.size() != b.size()) return a.width() * a.height() + 1;
  const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
  int n = 0;
  for (int r = 0; r < x.height(); ++r)
    for (int c = 0; c < x.width(); ++c) {
      const QRgb p = x.pixel(c, r), q = y.pixel(c, r);
      if (std::abs(qRed(p) - qRed(q)) > 1 || std::abs(qGreen(p) - qGreen(q)) > 1 || std::abs(qBlue(p) - qBlue(q)) > 1) ++n;
    }
  return n;
}

// The view as drawn now (the bone layer may be reused, CachedBoneLayer.h) and drawn in full.
QImage cachedFrame(BoneView& view) {
  view.render();
  return view.grabFramebuffer();
}
QImage fullFrame(BoneView& view) {
  view.setBoneCacheEnabled(false);
  const QImage image = view.grabFramebuffer();
  view.setBoneCacheEnabled(true);
  return image;
}

bool sameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  if (a.vertices.size() != b.vertices.size() || a.triangles.size() != b.triangles.size()) return false;
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    if (!(a.vertices[i] == b.vertices[i])) return false;
  return a.triangles == b.triangles;
}

TEST(GuiCtImport, SlicesFollowTheThresholdAndImportReplacesTheBoneWithUndo) {
  REAMSIM_REQUIRE_DISPLAY();
  const PhantomVolume& ph = phantomVolume();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const std::uint64_t revisionBefore = s.bone()->currentRevision();
  const Pose reamerBefore = s.reamer()->pose();
  const TriangleMesh meshBefore = s.bone()->current().toMesh();
  const std::string nameBefore = s.bone()->name();
  const std::string sourceBefore = s.bone()->source();
  const QString titleBefore = w.windowTitle();
  const ScapulaLandmarks landmarksBefore = s.bone()->landmarks();
  ASSERT_TRUE(landmarksBefore.complete());  // the default case's
  EXPECT_EQ(s.bone()->patientFrame(), PatientFrame::Unspecified);
  EXPECT_TRUE(w.boneFrameText().contains("unspecified")) << w.boneFrameText().toStdString();
  ASSERT_TRUE(w.action("import_ct")->isEnabled());

  QDialog* d = openInDialog(w, ph.path);
  ASSERT_NE(d, nullptr);
  EXPECT_TRUE(d->isVisible());
  EXPECT_FALSE(d->isModal());
  // The middle slices cut through the phantom: bone under the overlay at the default 250 HU.
  const int at250 = maskPixels(d, 2);
  EXPECT_GT(at250, 50);
  EXPECT_EQ(overlayPixels(d, 2), at250);
  EXPECT_GT(d->property("previewFaces").toInt(), 100);
  setLower(d, 900);  // partial-volume voxels drop out
  const int at900 = maskPixels(d, 2);
  EXPECT_LT(at900, at250);
  EXPECT_GT(at900, 0);
  EXPECT_EQ(overlayPixels(d, 2), at900);
  auto* upperOn = d->findChild<QCheckBox*>("UpperThresholdOn");
  auto* upper = d->findChild<QDoubleSpinBox*>("UpperThreshold");
  ASSERT_TRUE(upperOn && upper);
  upper->setValue(1000);
  upperOn->setChecked(true);  // 900…1000 HU: only the partial-volume rim of the bone
  const int band = maskPixels(d, 2);
  EXPECT_GT(band, 0);
  EXPECT_LT(band, at900);
  upper->setValue(800);  // below the lower threshold: no mask, no surface, no import
  EXPECT_EQ(maskPixels(d, 2), 0);
  EXPECT_EQ(overlayPixels(d, 2), 0);
  ASSERT_TRUE(waitIdle(d));
  EXPECT_EQ(d->property("previewFaces").toInt(), 0);
  EXPECT_FALSE(d->findChild<QPushButton*>("ImportButton")->isEnabled());
  upperOn->setChecked(false);
  setLower(d, 1200);
  setLower(d, 250);  // the 1200 HU preview, if it ran, is stale: only the newest is shown
  ASSERT_TRUE(waitIdle(d));
  EXPECT_EQ(maskPixels(d, 2), at250);
  EXPECT_GT(d->property("previewFaces").toInt(), 100);
  // Half way between tissue (40 HU) and bone (1200 HU): the 50 % partial-volume surface, whose volume is
  // the phantom's (as in tests/ctimport/PhantomFormatsTest.cpp).
  setLower(d, 620);
  ASSERT_TRUE(waitIdle(d));

  clickImport(d, false);
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  const BoneNode& bone = *s.bone();
  EXPECT_EQ(bone.patientFrame(), PatientFrame::LPS);
  EXPECT_FALSE(bone.landmarks()[ScapulaLandmark::GlenoidCentre]);  // placed on the scapula, not on this bone
  EXPECT_EQ(bone.source(), "CT volume " + QDir::cleanPath(QString::fromStdString(ph.path)).toStdString());
  EXPECT_NEAR(bone.current().volume(), ph.shape.mainVolume(), 0.01 * ph.shape.mainVolume());
  const ValidationReport v = validateMesh(bone.current().toMesh());
  EXPECT_TRUE(v.closed && v.consistentlyOriented && v.outwardOriented);
  EXPECT_TRUE(s.canCut()) << s.cuttingStatus().toStdString();
  EXPECT_TRUE(w.boneFrameText().contains("LPS")) << w.boneFrameText().toStdString();
  EXPECT_TRUE(w.windowTitle().contains("phantom.nrrd (CT)")) << w.windowTitle().toStdString();
  EXPECT_EQ(w.view()->displayedTriangleCount(), bone.current().liveTriangleCount());
  ASSERT_EQ(s.undoStack()->count(), 1);
  const std::uint64_t ctRevision = bone.currentRevision();
  const double ctVolume = bone.current().volume();
  const Pose ctReamerPose = s.reamer()->pose();  // clear of the phantom
  EXPECT_FALSE(samePose(ctReamerPose, reamerBefore));

  s.undoStack()->undo();  // the previous bone, exactly
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  EXPECT_EQ(s.bone()->currentRevision(), revisionBefore);
  EXPECT_TRUE(sameMesh(s.bone()->current().toMesh(), meshBefore));
  EXPECT_EQ(s.bone()->name(), nameBefore);
  EXPECT_EQ(s.bone()->source(), sourceBefore);
  EXPECT_EQ(s.bone()->patientFrame(), PatientFrame::Unspecified);
  EXPECT_EQ(s.bone()->landmarks(), landmarksBefore);  // they come back with their bone
  EXPECT_EQ(w.windowTitle(), titleBefore);
  EXPECT_TRUE(s.canCut());
  EXPECT_EQ(w.view()->displayedTriangleCount(), meshBefore.triangles.size());
  EXPECT_TRUE(samePose(s.reamer()->pose(), reamerBefore));  // the reamer's pose comes back with its bone

  s.undoStack()->redo();
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  EXPECT_TRUE(samePose(s.reamer()->pose(), ctReamerPose));
  EXPECT_EQ(s.bone()->currentRevision(), ctRevision);
  EXPECT_EQ(s.bone()->current().volume(), ctVolume);
  EXPECT_EQ(s.bone()->patientFrame(), PatientFrame::LPS);
}

TEST(GuiCtImport, BesideAddsASecondBoneThatUndoRemoves) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const std::uint64_t revision = s.bone()->currentRevision();
  QDialog* d = openInDialog(w, phantomVolume().path);
  ASSERT_NE(d, nullptr);
  setLower(d, 620);  // the 50 % partial-volume surface (see above)
  clickImport(d, true);
  ASSERT_TRUE(s.waitIdle(kWaitMs));

  const auto bones = s.document().nodesOf<BoneNode>();
  ASSERT_EQ(bones.size(), 2u);
  EXPECT_EQ(s.bone()->currentRevision(), revision);  // the cut bone is untouched
  const BoneNode* added = bones[0] == s.bone() ? bones[1] : bones[0];
  EXPECT_EQ(added->patientFrame(), PatientFrame::LPS);
  EXPECT_NEAR(added->current().volume(), phantomVolume().shape.mainVolume(), 0.01 * phantomVolume().shape.mainVolume());
  ASSERT_NE(w.otherBones(), nullptr);
  EXPECT_EQ(w.otherBones()->shownBones(), 1u);
  EXPECT_EQ(w.otherBones()->shownTriangles(), added->current().liveTriangleCount());
  EXPECT_TRUE(w.boneFrameText().contains("1 bone beside")) << w.boneFrameText().toStdString();

  s.undoStack()->undo();
  EXPECT_EQ(s.document().nodesOf<BoneNode>().size(), 1u);
  EXPECT_EQ(w.otherBones()->shownBones(), 0u);
  s.undoStack()->redo();
  EXPECT_EQ(s.document().nodesOf<BoneNode>().size(), 2u);
  EXPECT_EQ(w.otherBones()->shownBones(), 1u);
  w.removeOtherBones();
  EXPECT_EQ(s.document().nodesOf<BoneNode>().size(), 1u);
  s.undoStack()->undo();
  EXPECT_EQ(s.document().nodesOf<BoneNode>().size(), 2u);
  EXPECT_EQ(s.bone()->currentRevision(), revision);
}

// A bone beside can be cut instead (File → Cut a bone beside instead): the two swap — each keeps its own
// history, cuttability and plan poses — and undo swaps them back exactly. The bone it was is then beside,
// shown and not cut; the log's cumulative volume starts from the newly cut bone's own.
TEST(GuiCtImport, ABoneBesideCanBeCutInsteadAndUndoSwapsThemBack) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  EXPECT_FALSE(w.action("cut_bone_beside")->isEnabled());
  EXPECT_FALSE(w.cutBoneBesideInstead());  // nothing beside
  cutOnce(s);                              // the default bone with a cut in its history
  const Pose scapulaReamerPose = s.reamer()->pose();  // seated in the scapula's cut
  const NodeId cutId = s.bone()->id();
  const std::uint64_t scapulaRevision = s.bone()->currentRevision();
  const double scapulaVolume = s.bone()->current().volume();
  const std::size_t scapulaStates = s.bone()->history().size();
  const std::vector<Pose> scapulaPlan = s.plan()->poses();
  ASSERT_FALSE(scapulaPlan.empty());
  ASSERT_TRUE(s.canCut());

  QDialog* d = openInDialog(w, phantomVolume().path);
  ASSERT_NE(d, nullptr);
  setLower(d, 620);  // the 50 % partial-volume surface, a clean closed solid
  clickImport(d, true);
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  auto besideBone = [&]() -> const BoneNode* {
    for (const BoneNode* b : s.document().nodesOf<BoneNode>())
      if (b != s.bone()) return b;
    return nullptr;
  };
  ASSERT_NE(besideBone(), nullptr);
  const NodeId besideId = besideBone()->id();
  const std::uint64_t phantomRevision = besideBone()->currentRevision();
  const double phantomVolumeMm3 = besideBone()->current().volume();
  EXPECT_TRUE(besideBone()->cuttable());
  EXPECT_TRUE(w.action("cut_bone_beside")->isEnabled());

  ASSERT_TRUE(w.cutBoneBesideInstead());
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  EXPECT_EQ(s.bone()->id(), cutId);  // the nodes stay, their contents swap
  EXPECT_EQ(s.bone()->currentRevision(), phantomRevision);
  EXPECT_EQ(s.bone()->current().volume(), phantomVolumeMm3);
  EXPECT_EQ(s.bone()->patientFrame(), PatientFrame::LPS);
  EXPECT_TRUE(s.canCut()) << s.cuttingStatus().toStdString();
  EXPECT_TRUE(s.plan()->poses().empty());  // the scapula's plan left with it
  EXPECT_NEAR(s.initialVolumeMm3(), phantomVolumeMm3, 1e-9 * phantomVolumeMm3);
  ASSERT_NE(besideBone(), nullptr);
  EXPECT_EQ(besideBone()->id(), besideId);
  EXPECT_EQ(besideBone()->currentRevision(), scapulaRevision);
  EXPECT_EQ(besideBone()->history().size(), scapulaStates);
  EXPECT_EQ(besideBone()->current().volume(), scapulaVolume);
  EXPECT_TRUE(besideBone()->landmarks().complete());  // the scapula's landmarks went beside with it
  EXPECT_FALSE(s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre]);
  EXPECT_TRUE(besideBone()->cuttable());
  EXPECT_EQ(w.otherBones()->shownTriangles(), besideBone()->current().liveTriangleCount());
  EXPECT_TRUE(w.boneFrameText().contains("LPS")) << w.boneFrameText().toStdString();
  EXPECT_FALSE(samePose(s.reamer()->pose(), scapulaReamerPose));  // put clear of the phantom
  Pose phantomReamerPose = s.reamer()->pose();
  phantomReamerPose.tip = phantomReamerPose.tip - 2.0 * phantomReamerPose.axis;  // a move on the phantom
  s.moveReamer(phantomReamerPose, true);
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  // Removing the bone beside and undoing that brings it back under its id, so the swap can still be undone.
  w.removeOtherBones();
  ASSERT_EQ(besideBone(), nullptr);
  s.undoStack()->undo();
  ASSERT_NE(besideBone(), nullptr);
  EXPECT_EQ(besideBone()->id(), besideId);

  s.undoStack()->undo();
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  EXPECT_EQ(s.bone()->currentRevision(), scapulaRevision);
  EXPECT_EQ(s.bone()->history().size(), scapulaStates);
  EXPECT_EQ(s.plan()->poses().size(), scapulaPlan.size());
  EXPECT_TRUE(s.bone()->landmarks().complete());
  EXPECT_EQ(besideBone()->currentRevision(), phantomRevision);
  EXPECT_EQ(w.otherBones()->shownTriangles(), besideBone()->current().liveTriangleCount());
  // The reamer's pose went with each bone: back in the scapula's cut, not where it was over the phantom (from
  // where the next move would have cut all the reamer overlaps), and the next move sweeps on from there.
  EXPECT_TRUE(samePose(s.reamer()->pose(), scapulaReamerPose));
  s.undoStack()->redo();
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  EXPECT_TRUE(samePose(s.reamer()->pose(), phantomReamerPose));
  s.undoStack()->undo();
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  EXPECT_TRUE(samePose(s.reamer()->pose(), scapulaReamerPose));
  const double beforeFeed = s.bone()->current().volume();
  const std::size_t cutsBefore = s.cutsCommitted();
  Pose aside = scapulaReamerPose;  // 0.3 mm across the axis
  const Vec3 across = cross(aside.axis, std::abs(aside.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
  aside.tip = aside.tip + (0.3 / norm(across)) * across;
  s.moveReamer(aside, true);
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  ASSERT_EQ(s.cutsCommitted(), cutsBefore + 1);
  EXPECT_TRUE(s.lastStepSwept()) << "the move sweeps from the returned pose";
  const double movedMm3 = beforeFeed - s.bone()->current().volume();
  EXPECT_GT(movedMm3, 0.0);
  EXPECT_LT(movedMm3, s.initialVolumeMm3() - scapulaVolume);  // a 0.3 mm crescent, less than the 0.5 mm cut
  s.undoStack()->undo();  // the move
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  // The scapula's own cut can still be undone: its history came back whole.
  s.undoStack()->undo();  // the import beside
  s.undoStack()->undo();  // the cut
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  EXPECT_EQ(s.bone()->history().cursor(), 0u);
  EXPECT_GT(s.bone()->current().volume(), scapulaVolume);
}

// Save writes the cut bone only: a bone moved beside with cuts no save wrote is asked about on close (Cancel keeps
// the window), and not once those cuts are saved (the swap back makes it the cut bone, whose save writes them).
TEST(GuiCtImport, ClosingAsksAboutABoneBesideWithUnsavedCuts) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);  // the scapula has a cut no save wrote
  QDialog* d = openInDialog(w, phantomVolume().path);
  ASSERT_NE(d, nullptr);
  setLower(d, 620);
  clickImport(d, true);
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  ASSERT_TRUE(w.cutBoneBesideInstead());
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  QTemporaryDir out;
  ASSERT_TRUE(w.saveBoneAs(out.filePath("phantom.ply")));  // the cut bone (the phantom) is saved
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_EQ(w.bonesBesideWithUnsavedCuts().size(), 1);
  QString text;
  EXPECT_FALSE(closeAnswering(w, {ModalAnswers::click("UnsavedBonesBesideDialog", "Cancel", &text)}, 1));
  EXPECT_TRUE(text.contains("Cuts that are not saved") && text.contains("(beside the cut bone)")) << text.toStdString();
  EXPECT_TRUE(w.isVisible());

  ASSERT_TRUE(w.cutBoneBesideInstead());  // the scapula is the cut bone again: its save writes its cut
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  ASSERT_TRUE(w.saveBoneAs(out.filePath("scapula.ply")));
  EXPECT_TRUE(w.bonesBesideWithUnsavedCuts().isEmpty());  // the phantom beside has no cut
  EXPECT_TRUE(closeAnswering(w, {}, 0));
}

// A bone replaced by a CT import lives on in the undo history only: its cuts, which Save does not write (it writes
// the CT bone), are asked about on close; undoing the import brings it back to be saved.
TEST(GuiCtImport, ClosingAsksAboutABoneAnImportReplacedWithUnsavedCuts) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  QDialog* d = openInDialog(w, phantomVolume().path);
  ASSERT_NE(d, nullptr);
  setLower(d, 620);
  clickImport(d, false);  // replaces the cut scapula
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  QTemporaryDir out;
  ASSERT_TRUE(w.saveBoneAs(out.filePath("phantom.ply")));
  EXPECT_TRUE(w.bonesBesideWithUnsavedCuts().isEmpty());
  ASSERT_EQ(w.replacedBonesWithUnsavedCuts().size(), 1);
  QString text;
  EXPECT_FALSE(closeAnswering(w, {ModalAnswers::click("UnsavedBonesBesideDialog", "Cancel", &text)}, 1));
  EXPECT_TRUE(text.contains("(replaced by a CT import)")) << text.toStdString();
  s.undoStack()->undo();  // the scapula with its cut is the cut bone again: the usual question covers it
  ASSERT_TRUE(s.waitIdle(kWaitMs));
  EXPECT_TRUE(w.replacedBonesWithUnsavedCuts().isEmpty());
  EXPECT_TRUE(w.hasUnsavedChanges());
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Discard)}, 1));
}

// A bone beside that is removed leaves the picture even when nothing else changes: the view reuses its
// bone layer while nothing in it is newer (CachedBoneLayer.h), and the same bone twice keeps the bounds,
// so neither the camera nor the clipping range moves.
TEST(GuiCtImport, ARemovedBoneBesideLeavesThePicture) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f(REAMSIM_GUI_PLUGIN_DIR, false);
  MainWindow& w = *f.window;
  for (bool beside : {false, true}) {
    QDialog* d = openInDialog(w, phantomVolume().path);
    ASSERT_NE(d, nullptr);
    clickImport(d, beside);
    ASSERT_TRUE(f.session().waitIdle(kWaitMs));
  }
  ASSERT_EQ(w.otherBones()->shownBones(), 1u);
  BoneView& view = *w.view();
  view.setStandardView(BoneView::StandardView::Anterior);
  const QImage both = cachedFrame(view);
  f.session().undoStack()->undo();
  ASSERT_EQ(w.otherBones()->shownBones(), 0u);
  const QImage one = cachedFrame(view);
  EXPECT_GT(differingPixels(both, one), 0);
  EXPECT_EQ(differingPixels(one, fullFrame(view)), 0);
}

TEST(GuiCtImport, BadVolumesEndInAnErrorDialogNamingTheFile) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  const std::uint64_t revision = f.session().bone()->currentRevision();
  QTemporaryDir dir;
  const std::string bytes = phantom::readBytes(phantomVolume().path);
  const QString cut = dir.filePath("cut.nrrd");
  phantom::writeBytes(cut.toStdString(), bytes.substr(0, bytes.size() - 100));
  const QString garbage = dir.filePath("garbage.nrrd");
  phantom::writeBytes(garbage.toStdString(), "NRRX" + bytes.substr(4));

  for (const auto& [path, problem] : {std::pair{cut, "file truncated"}, std::pair{garbage, "not a NRRD file"}}) {
    QDialog* d = w.importVolume(path);
    ASSERT_NE(d, nullptr);
    ASSERT_TRUE(waitIdle(d));
    EXPECT_FALSE(d->property("volumeLoaded").toBool());
    const QString error = d->property("lastError").toString();
    EXPECT_TRUE(error.contains(QFileInfo(path).fileName())) << error.toStdString();
    EXPECT_TRUE(error.contains(problem)) << error.toStdString();
    auto* box = d->findChild<QMessageBox*>("CtImportError");
    ASSERT_NE(box, nullptr);
    EXPECT_TRUE(box->isVisible());
    EXPECT_EQ(box->text(), error);
    EXPECT_FALSE(d->findChild<QPushButton*>("ImportButton")->isEnabled());
    box->close();
    d->close();
  }
  EXPECT_EQ(f.session().bone()->currentRevision(), revision);
  EXPECT_EQ(f.session().undoStack()->count(), 0);
}

// Cancel is made deterministic by holding the worker pool: the import is queued, cancelled, then let run,
// so it stops at its first progress check — no race with a fast import.
TEST(GuiCtImport, CancelStopsTheImportAndKeepsTheBone) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  const std::uint64_t revision = f.session().bone()->currentRevision();
  QDialog* d = openInDialog(w, phantomVolume().path);
  ASSERT_NE(d, nullptr);
  ASSERT_TRUE(f.session().waitIdle(kWaitMs));

  QThreadPool* pool = QThreadPool::globalInstance();
  QSemaphore release;
  const int held = pool->maxThreadCount();
  for (int i = 0; i < held; ++i) pool->start([&release] { release.acquire(); });
  d->findChild<QPushButton*>("ImportButton")->click();
  EXPECT_TRUE(d->findChild<QProgressBar*>("ImportProgress")->isVisible());
  EXPECT_FALSE(d->findChild<QPushButton*>("ImportButton")->isEnabled());
  auto* cancel = d->findChild<QPushButton*>("CancelButton");
  ASSERT_TRUE(cancel->isEnabled());
  cancel->click();
  release.release(held);
  ASSERT_TRUE(waitIdle(d));
  EXPECT_TRUE(d->property("status").toString().contains("cancelled")) << d->property("status").toString().toStdString();
  EXPECT_TRUE(d->isVisible());
  EXPECT_TRUE(d->findChild<QPushButton*>("ImportButton")->isEnabled());
  EXPECT_EQ(f.session().bone()->currentRevision(), revision);
  EXPECT_EQ(f.session().undoStack()->count(), 0);
  d->close();
}

TEST(GuiCtImport, HeadsqFromSharedDataImportsToAClosedMesh) {
  REAMSIM_REQUIRE_DISPLAY();
  const QString headsq = QStringLiteral(REAMSIM_SHARED_DATA_DIR) + "/ct_headsq/quarter.nhdr";
  if (!QFile::exists(headsq)) GTEST_SKIP() << "no " << headsq.toStdString();
  GuiFixture f(REAMSIM_GUI_PLUGIN_DIR, false);
  MainWindow& w = *f.window;
  QDialog* d = openInDialog(w, headsq.toStdString());
  ASSERT_NE(d, nullptr);
  setLower(d, 1150);  // headsq is not in HU (docs/CT_IMPORT.md)
  ASSERT_TRUE(waitIdle(d));
  EXPECT_GT(maskPixels(d, 2), 0);
  EXPECT_GT(d->property("previewFaces").toInt(), 1000);
  clickImport(d, false);
  ASSERT_TRUE(f.session().waitIdle(kWaitMs));
  const BoneNode& bone = *f.session().bone();
  EXPECT_GT(bone.current().liveTriangleCount(), 10000u);
  const ValidationReport v = validateMesh(bone.current().toMesh());
  EXPECT_TRUE(v.closed && v.consistentlyOriented && v.outwardOriented) << toText(v);
  EXPECT_EQ(v.selfIntersectingPairs, 0u);
  EXPECT_TRUE(f.session().canCut()) << f.session().cuttingStatus().toStdString();
  EXPECT_TRUE(QString::fromStdString(bone.source()).endsWith("quarter.nhdr"));
}

TEST(GuiCtImport, WithoutThePluginTheActionIsOffAndListed) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  for (const char* name : {"meshimport", "collision", "csg", "logpanel"}) {
    const QString file = QStringLiteral("libreamsim_%1.so").arg(name);
    ASSERT_TRUE(QFile::copy(QDir(REAMSIM_GUI_PLUGIN_DIR).filePath(file), dir.filePath(file)));
  }
  GuiFixture f(dir.path(), false);
  EXPECT_EQ(f.plugins->volumeImport(), nullptr);
  EXPECT_FALSE(f.window->action("import_ct")->isEnabled());
  EXPECT_FALSE(f.window->action("import_ct_dicom")->isEnabled());
  bool listed = false;
  for (const PluginRecord& r : f.plugins->records())
    if (r.name == "ctimport") listed = !r.loaded && r.detail.contains("not found");
  EXPECT_TRUE(listed) << f.plugins->summaryText().toStdString();
  EXPECT_EQ(f.window->importVolume("/nowhere/head.nrrd"), nullptr);
  EXPECT_TRUE(f.window->lastError().contains("no CT import plugin")) << f.window->lastError().toStdString();
}

// "Region at the crosshair": clicking a slice puts the crosshair on a voxel; the import then keeps the region
// there, here the small loose fragment beside the larger body (which "largest region" would keep).
TEST(GuiCtImport, RegionAtTheCrosshairKeepsTheClickedBone) {
  REAMSIM_REQUIRE_DISPLAY();
  phantom::SphereAndCylinder shape;
  shape.fragment = true;
  const phantom::Grid grid = phantom::gridAround(shape.center, 26, {0.9, 0.8, 1.0}, phantom::rotation({1, 2, 3}, 30));
  QTemporaryDir dir;
  const std::string path = dir.filePath("fragment.nrrd").toStdString();
  phantom::writeNrrd(path, grid, phantom::sample(grid, [&](const Vec3& p) { return shape.inside(p); }));
  GuiFixture f;
  MainWindow& w = *f.window;
  QDialog* d = openInDialog(w, path);
  ASSERT_NE(d, nullptr);
  setLower(d, 620);
  d->findChild<QComboBox*>("Component")->setCurrentIndex(2);
  // The fragment's centre as voxel indices (the grid's axes are orthonormal), each set as a click would.
  for (int a = 0; a < 3; ++a) {
    const int index = int(std::lround(dot(grid.axis(a), shape.fragmentCenter - grid.origin) / grid.spacing[std::size_t(a)]));
    ASSERT_TRUE(QMetaObject::invokeMethod(d, "setSliceIndex", Q_ARG(int, a), Q_ARG(int, index)));
  }
  ASSERT_TRUE(waitIdle(d));
  EXPECT_GT(d->property("previewFaces").toInt(), 0);
  clickImport(d, false);
  ASSERT_TRUE(f.session().waitIdle(kWaitMs));
  const BoneNode& bone = *f.session().bone();
  // A 3.5 mm ball on ~1 mm voxels: its 50 % surface comes out a few per cent small (the main body is 50× larger).
  EXPECT_NEAR(bone.current().volume(), shape.fragmentVolume(), 0.1 * shape.fragmentVolume());
  Vec3 centre;
  const TriangleMesh mesh = bone.current().toMesh();
  for (const Vec3& p : mesh.vertices) centre = centre + p / double(mesh.vertices.size());
  EXPECT_LT(norm(centre - shape.fragmentCenter), 0.5);
}

// The patient frame is kept through Save as in every format with room for it (PLY, OBJ and OFF comments, a
// VTP field array, a binary STL's header) and read back when the file is opened.
TEST(GuiCtImport, PatientFrameSurvivesSaveAs) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f(REAMSIM_GUI_PLUGIN_DIR, false);
  MainWindow& w = *f.window;
  QDialog* d = openInDialog(w, phantomVolume().path);
  ASSERT_NE(d, nullptr);
  d->findChild<QComboBox*>("MeshFrame")->setCurrentIndex(1);  // RAS
  clickImport(d, false);
  ASSERT_TRUE(f.session().waitIdle(kWaitMs));
  ASSERT_EQ(f.session().bone()->patientFrame(), PatientFrame::RAS);
  QTemporaryDir out;
  const QStringList names = {"bone.ply", "bone.obj", "bone.off", "bone.vtp", "bone.stl"};
  for (const QString& name : names) {
    w.saveBoneAs(out.filePath(name));
    ASSERT_TRUE(w.lastError().isEmpty()) << name.toStdString() << ": " << w.lastError().toStdString();
  }
  for (const QString& name : names) {
    w.openFile(out.filePath(name));
    w.waitImport();
    EXPECT_EQ(f.session().bone()->patientFrame(), PatientFrame::RAS) << name.toStdString();
    EXPECT_TRUE(w.boneFrameText().contains("RAS")) << name.toStdString();
  }
  w.openFile(QString(REAMSIM_TEST_DATA_DIR) + "/good/cube_quads_comments.off");  // a file without one
  w.waitImport();
  EXPECT_EQ(f.session().bone()->patientFrame(), PatientFrame::Unspecified);
}

}  // namespace
}  // namespace reamsim::ui::test
