#pragma once
// The planning dock (docs/PLANNING.md): the scapular landmarks of the bone (placed by clicking on the bone,
// or read from a file), the version and inclination of the reamer's axis in the scapular frame as the
// reamer moves, and the reamer aimed through the glenoid centre at the version and inclination asked for.
//
// It works on the document alone: a landmark is placed by asking for it (InteractionNode::setPlaceRequest;
// the view places it on the cut bone, the document's first BoneNode, at the next click on it) and the reamer is aimed by asking for a placement
// (ReamerNode::requestPlacement; the reaming loop places it), so the dock needs no handle on the view or
// the loop.
#include <QDockWidget>
#include <array>

#include "reamsim/core/Document.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/InteractionNode.h"
#include "reamsim/core/ReamerNode.h"
#include "reamsim/ream/ScapularFrame.h"
#include "GlenoidFaceMeasure.h"

class QComboBox;
class QDoubleSpinBox;
class QGridLayout;
class QLabel;
class QPushButton;

namespace reamsim::ui {

class PlanningPanel : public QDockWidget {
  Q_OBJECT
  // For tests: how many times the glenoid face of the bone as opened has been measured (GlenoidFaceMeasure).
  Q_PROPERTY(int glenoidOpenedMeasures READ glenoidOpenedMeasures)
 public:
  PlanningPanel(Document& document, QWidget* parent);

  QString axisReport() const;  // what the dock says of the reamer's axis now
  QString planText() const;    // what it says of the planned axis
  QString glenoidFaceText() const;  // what it says of the glenoid face, as opened and now
  int glenoidOpenedMeasures() const { return faceMeasure_.openedMeasures(); }

 public Q_SLOTS:
  // Plans the axis at the dock's version and inclination through the glenoid centre (BoneNode::plannedAxis) and
  // asks for the reamer on it, its tip the clearance out; returns why not, empty when asked.
  QString aimReamer();
  // The reamer's present angles into the aim fields (so that a small change starts from where it is).
  void takeReamerAngles();
  // The glenoid face's own angles, measured on the bone as opened, into the aim fields (reaming along the
  // glenoid's own axis; a correction starts from there).
  void takeGlenoidAngles();
  // Landmark files (docs/PLANNING.md); each returns an error message naming the file, empty on success.
  QString loadLandmarksFrom(const QString& path);
  QString saveLandmarksTo(const QString& path);

 private:
  void buildLandmarkRows(QGridLayout* grid);
  void sync();
  // The glenoid face's angles in the landmarks' frame, of the bone as opened (`now` false) or as it is now;
  // nullopt while measured, or when there is no face or frame (`why` says which). With `updating`, the state now
  // while measured is answered by the last cut's (and `updating` says so).
  std::optional<AxisAngles> glenoidAngles(bool now, QString* why = nullptr, bool* updating = nullptr) const;
  BoneNode* bone() const;  // the cut bone: the document's first
  InteractionNode* interaction() const;
  ReamerNode* reamer() const;

  Document& document_;
  Subscription subscription_;
  QComboBox* side_ = nullptr;
  std::array<QLabel*, 3> pointLabels_{};
  std::array<QPushButton*, 3> placeButtons_{};
  QLabel* report_ = nullptr;
  QLabel* glenoid_ = nullptr;
  GlenoidFaceMeasure faceMeasure_;
  QDoubleSpinBox* version_ = nullptr;
  QDoubleSpinBox* inclination_ = nullptr;
  QDoubleSpinBox* clearance_ = nullptr;
  QPushButton* aim_ = nullptr;
  QPushButton* take_ = nullptr;
  QPushButton* takeGlenoid_ = nullptr;
  QPushButton* clearPlan_ = nullptr;
  QLabel* plan_ = nullptr;
};

}  // namespace reamsim::ui
