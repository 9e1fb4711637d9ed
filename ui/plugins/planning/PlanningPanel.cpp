#include "PlanningPanel.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QMessageBox>
#include <QPushButton>
#include <QVBoxLayout>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/ui/PointText.h"

namespace reamsim::ui {
namespace {

constexpr double kDefaultClearanceMm = 10;  // clear of the glenoid rim for tilts up to ~25 degrees

QString degreesText(double deg) { return QLocale().toString(deg, 'f', 1) + QStringLiteral("°"); }

QString versionText(const AxisAngles& a) {
  return PlanningPanel::tr("version %1 (%2), inclination %3 (%4)")
      .arg(degreesText(a.versionDeg),
           a.versionDeg < 0 ? PlanningPanel::tr("retroversion")
                            : (a.versionDeg > 0 ? PlanningPanel::tr("anteversion") : PlanningPanel::tr("neutral")),
           degreesText(a.inclinationDeg),
           a.inclinationDeg < 0 ? PlanningPanel::tr("inferior")
                                : (a.inclinationDeg > 0 ? PlanningPanel::tr("superior") : PlanningPanel::tr("neutral")));
}

QString signedDegreesText(double deg) { return (deg > 0 ? QStringLiteral("+") : QString()) + degreesText(deg); }

QString capitalised(const char* text) {
  QString s = QString::fromUtf8(text);
  if (!s.isEmpty()) s[0] = s[0].toUpper();
  return s;
}

QDoubleSpinBox* angleBox(const QString& name, QWidget* parent) {
  auto* box = new QDoubleSpinBox(parent);
  box->setObjectName(name);
  box->setRange(-89, 89);  // outwardAxisFor's range
  box->setDecimals(1);
  box->setSingleStep(0.5);
  box->setSuffix(QStringLiteral("°"));
  return box;
}

}  // namespace

PlanningPanel::PlanningPanel(Document& document, QWidget* parent)
    : QDockWidget(tr("Planning"), parent), document_(document) {
  setObjectName("PlanningPanel");
  auto* body = new QWidget(this);
  auto* layout = new QVBoxLayout(body);

  auto* marksBox = new QGroupBox(tr("Scapular landmarks"), body);
  auto* grid = new QGridLayout(marksBox);
  buildLandmarkRows(grid);
  layout->addWidget(marksBox);

  glenoid_ = new QLabel(body);
  glenoid_->setObjectName("GlenoidFace");
  glenoid_->setWordWrap(true);
  glenoid_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  glenoid_->setToolTip(tr("The bone's surface within %1 mm of the glenoid centre, facing its way: the sum of its "
                          "triangles' areas along their normals, i.e. the plane of its rim")
                           .arg(GlenoidFaceOptions{}.radiusMm));
  layout->addWidget(glenoid_);

  report_ = new QLabel(body);
  report_->setObjectName("AxisAngles");
  report_->setWordWrap(true);
  report_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(report_);

  plan_ = new QLabel(body);
  plan_->setObjectName("PlannedAxis");
  plan_->setWordWrap(true);
  plan_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(plan_);

  auto* aimBox = new QGroupBox(tr("Aim the reamer through the glenoid centre"), body);
  auto* form = new QFormLayout(aimBox);
  version_ = angleBox("AimVersion", aimBox);
  version_->setToolTip(tr("Positive: anteversion; negative: retroversion"));
  inclination_ = angleBox("AimInclination", aimBox);
  inclination_->setToolTip(tr("Positive: superior tilt; negative: inferior tilt"));
  clearance_ = new QDoubleSpinBox(aimBox);
  clearance_->setObjectName("AimClearance");
  clearance_->setRange(0, 100);
  clearance_->setDecimals(1);
  clearance_->setValue(kDefaultClearanceMm);
  clearance_->setSuffix(tr(" mm"));
  clearance_->setToolTip(tr("How far out from the glenoid centre the reamer's tip is placed; then ream to depth"));
  form->addRow(tr("Version"), version_);
  form->addRow(tr("Inclination"), inclination_);
  form->addRow(tr("Tip out from the centre"), clearance_);
  auto* aimButtons = new QHBoxLayout;
  take_ = new QPushButton(tr("Take the reamer's"), aimBox);
  take_->setObjectName("TakeReamerAngles");
  take_->setToolTip(tr("Fill in the version and inclination the reamer has now"));
  takeGlenoid_ = new QPushButton(tr("Take the glenoid's"), aimBox);
  takeGlenoid_->setObjectName("TakeGlenoidAngles");
  takeGlenoid_->setToolTip(tr("Fill in the glenoid face's own version and inclination, as the bone was opened"));
  aim_ = new QPushButton(tr("Aim"), aimBox);
  aim_->setObjectName("AimReamer");
  aim_->setToolTip(tr("Plan this axis through the glenoid centre and place the reamer on it, clear of the bone"));
  clearPlan_ = new QPushButton(tr("Clear the plan"), aimBox);
  clearPlan_->setObjectName("ClearPlannedAxis");
  aimButtons->addWidget(take_);
  aimButtons->addWidget(takeGlenoid_);
  aimButtons->addWidget(aim_);
  aimButtons->addWidget(clearPlan_);
  form->addRow(aimButtons);
  layout->addWidget(aimBox);
  layout->addStretch(1);
  setWidget(body);

  connect(take_, &QPushButton::clicked, this, &PlanningPanel::takeReamerAngles);
  connect(takeGlenoid_, &QPushButton::clicked, this, &PlanningPanel::takeGlenoidAngles);
  connect(&faceMeasure_, &GlenoidFaceMeasure::measured, this, &PlanningPanel::sync);
  connect(clearPlan_, &QPushButton::clicked, this, [this] {
    if (BoneNode* b = bone()) b->setPlannedAxis(std::nullopt);
  });
  connect(aim_, &QPushButton::clicked, this, [this] {
    const QString why = aimReamer();
    if (!why.isEmpty()) QMessageBox::warning(this, tr("Aim the reamer"), why);
  });
  subscription_ = document_.subscribe([this](const DocumentEvent& e) {
    if (e.id.kind() == NodeKind::Interaction || e.id.kind() == NodeKind::Reamer || e.id.kind() == NodeKind::Bone) sync();
  });
  sync();
}

void PlanningPanel::buildLandmarkRows(QGridLayout* grid) {
  QWidget* box = grid->parentWidget();
  grid->addWidget(new QLabel(tr("Side"), box), 0, 0);
  side_ = new QComboBox(box);
  side_->setObjectName("LandmarkSide");
  side_->addItem(tr("not given"), int(BodySide::Unspecified));
  side_->addItem(tr("right scapula"), int(BodySide::Right));
  side_->addItem(tr("left scapula"), int(BodySide::Left));
  grid->addWidget(side_, 0, 1, 1, 2);
  connect(side_, qOverload<int>(&QComboBox::activated), this, [this](int index) {
    if (BoneNode* b = bone()) b->setLandmarkSide(BodySide(side_->itemData(index).toInt()));
  });
  for (ScapulaLandmark which : kScapulaLandmarks) {
    const int row = 1 + int(which);
    const QString key = QString::fromUtf8(jsonKey(which));
    grid->addWidget(new QLabel(capitalised(displayName(which)), box), row, 0);
    QLabel*& point = pointLabels_[std::size_t(which)];
    point = new QLabel(box);
    point->setObjectName("LandmarkPoint_" + key);
    point->setTextInteractionFlags(Qt::TextSelectableByMouse);
    grid->addWidget(point, row, 1);
    QPushButton*& place = placeButtons_[std::size_t(which)];
    place = new QPushButton(tr("Place"), box);
    place->setObjectName("PlaceLandmark_" + key);
    place->setCheckable(true);
    place->setToolTip(tr("Then click on the bone where the %1 is").arg(QString::fromUtf8(displayName(which))));
    grid->addWidget(place, row, 2);
    connect(place, &QPushButton::clicked, this, [this, which](bool on) {
      if (InteractionNode* i = interaction()) i->setPlaceRequest(on ? std::optional<ScapulaLandmark>(which) : std::nullopt);
    });
  }
  auto* files = new QHBoxLayout;
  auto* load = new QPushButton(tr("Open…"), box);
  load->setObjectName("LoadLandmarks");
  auto* save = new QPushButton(tr("Save…"), box);
  save->setObjectName("SaveLandmarks");
  files->addStretch(1);
  files->addWidget(load);
  files->addWidget(save);
  grid->addLayout(files, 4, 0, 1, 3);
  const QString filter = tr("Landmarks (*.json)");
  connect(load, &QPushButton::clicked, this, [this, filter] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Open landmarks"), {}, filter);
    if (path.isEmpty()) return;
    const QString error = loadLandmarksFrom(path);
    if (!error.isEmpty()) QMessageBox::warning(this, tr("Open landmarks"), error);
  });
  connect(save, &QPushButton::clicked, this, [this, filter] {
    const QString path = QFileDialog::getSaveFileName(this, tr("Save landmarks"), QStringLiteral("landmarks.json"), filter);
    if (path.isEmpty()) return;
    const QString error = saveLandmarksTo(path);
    if (!error.isEmpty()) QMessageBox::warning(this, tr("Save landmarks"), error);
  });
}

BoneNode* PlanningPanel::bone() const { return document_.firstOf<BoneNode>(); }
InteractionNode* PlanningPanel::interaction() const { return document_.firstOf<InteractionNode>(); }
ReamerNode* PlanningPanel::reamer() const { return document_.firstOf<ReamerNode>(); }

QString PlanningPanel::axisReport() const { return report_->text(); }

void PlanningPanel::sync() {
  const BoneNode* node = bone();
  const ScapulaLandmarks marks = node ? node->landmarks() : ScapulaLandmarks{};
  std::optional<ScapulaLandmark> asked;
  if (interaction()) asked = interaction()->placeRequest();
  {
    const QSignalBlocker block(side_);
    side_->setCurrentIndex(side_->findData(int(marks.side)));
  }
  for (ScapulaLandmark which : kScapulaLandmarks) {
    const std::size_t i = std::size_t(which);
    const std::optional<Vec3>& p = marks[which];
    const bool asking = asked.has_value() && *asked == which;
    pointLabels_[i]->setText(p ? pointText(*p, 1) : tr("not placed"));
    placeButtons_[i]->setChecked(asking);
    placeButtons_[i]->setText(asking ? tr("Click on the bone…") : (p ? tr("Place again") : tr("Place")));
    placeButtons_[i]->setEnabled(node != nullptr && interaction() != nullptr);
  }
  side_->setEnabled(node != nullptr);

  QString text;
  bool framed = false;
  try {
    const ScapularFrame frame = scapularFrame(marks);
    framed = true;
    const ReamerNode* r = reamer();
    if (!r || !r->cuttingVolume()) {
      text = tr("No reamer to measure.");
    } else {
      text = tr("Reamer axis: %1").arg(versionText(feedAxisAngles(frame, r->pose().axis)));
    }
  } catch (const std::invalid_argument& e) {
    text = framed ? tr("Reamer axis: %1.").arg(QString::fromStdString(e.what()))
                  : tr("Version and inclination need the landmarks: %1.").arg(QString::fromStdString(e.what()));
  }
  report_->setText(text);
  if (node && marks[ScapulaLandmark::GlenoidCentre]) faceMeasure_.ask(*node, *marks[ScapulaLandmark::GlenoidCentre]);
  glenoid_->setText(glenoidFaceText());
  takeGlenoid_->setEnabled(glenoidAngles(false).has_value());
  plan_->setText(planText());
  clearPlan_->setEnabled(node && node->plannedAxis());
  aim_->setEnabled(framed && reamer());
  take_->setEnabled(framed && reamer());
}

std::optional<AxisAngles> PlanningPanel::glenoidAngles(bool now, QString* why, bool* updating) const {
  auto say = [why](const QString& text) {
    if (why) *why = text;
    return std::nullopt;
  };
  if (updating) *updating = false;
  const BoneNode* node = bone();
  if (!node) return say(tr("there is no bone"));
  const std::optional<Vec3>& centre = node->landmarks()[ScapulaLandmark::GlenoidCentre];
  if (!centre) return say(tr("place the glenoid centre to measure it"));
  const std::uint64_t opened = node->history().entries().front().revision;
  const GlenoidFaceMeasure::Measured* m = faceMeasure_.find(now ? node->currentRevision() : opened, *centre);
  if (!m && now && updating) {  // while the cut just made is measured, the last cut's answer
    m = faceMeasure_.latestCut(opened, *centre);
    *updating = m != nullptr;
  }
  if (!m) return say(tr("measuring"));
  if (!m->face) return say(QString::fromStdString(m->error));
  ScapularFrame frame;
  try {
    frame = scapularFrame(node->landmarks());
  } catch (const std::invalid_argument& e) {
    return say(tr("its version and inclination need the landmarks (%1)").arg(QString::fromStdString(e.what())));
  }
  try {
    return axisAngles(frame, m->face->outward);
  } catch (const std::invalid_argument& e) {  // an inside-out surface faces medially
    return say(tr("it faces medially, as a surface turned inside out would (%1)").arg(QString::fromStdString(e.what())));
  }
}

// As opened and, once the bone is cut, as reamed now: what a plan corrects, and what the reaming has made of it.
QString PlanningPanel::glenoidFaceText() const {
  QString why;
  const std::optional<AxisAngles> opened = glenoidAngles(false, &why);
  if (!opened) return tr("Glenoid face (central %1 mm): %2.").arg(GlenoidFaceOptions{}.radiusMm).arg(why);
  QString text = tr("Glenoid face (central %1 mm) as opened: %2").arg(GlenoidFaceOptions{}.radiusMm).arg(versionText(*opened));
  const BoneNode* node = bone();
  if (node->currentRevision() != node->history().entries().front().revision) {
    bool updating = false;
    const std::optional<AxisAngles> now = glenoidAngles(true, &why, &updating);
    text += now ? tr("; as it is now: %1").arg(versionText(*now)) + (updating ? tr(" (updating)") : QString())
                : tr("; as it is now: %1").arg(why);
  }
  return text + ".";
}

// The planned axis in the frame, and how far the reamer's axis is off it (the angle between the two axes).
QString PlanningPanel::planText() const {
  const BoneNode* node = bone();
  if (!node || !node->plannedAxis()) return tr("No axis planned: Aim plans one.");
  const Pose& planned = *node->plannedAxis();
  QString text = tr("Planned axis");
  try {
    const AxisAngles a = feedAxisAngles(scapularFrame(node->landmarks()), planned.axis);
    text += tr(": version %1, inclination %2").arg(degreesText(a.versionDeg), degreesText(a.inclinationDeg));
    if (const std::optional<AxisAngles> glenoid = glenoidAngles(false))
      text += tr(" (from the glenoid face as opened: %1 of version, %2 of inclination)")
                  .arg(signedDegreesText(a.versionDeg - glenoid->versionDeg),
                       signedDegreesText(a.inclinationDeg - glenoid->inclinationDeg));
  } catch (const std::invalid_argument&) {  // landmarks changed since: the axis stays, its angles do not
  }
  if (const ReamerNode* r = reamer(); r && r->cuttingVolume())
    text += tr("; the reamer is %1 off it").arg(degreesText(axisDeviationDeg(planned.axis, r->pose().axis)));
  return text + ".";
}

QString PlanningPanel::aimReamer() {
  ReamerNode* r = reamer();
  if (!r || !bone()) return tr("There is no reamer or no bone in the document.");
  try {
    const ScapularFrame frame = scapularFrame(bone()->landmarks());
    const AxisAngles angles{version_->value(), inclination_->value()};
    const Pose placed = aimedReamerPose(frame, angles, clearance_->value());
    bone()->setPlannedAxis(Pose{frame.origin, placed.axis, 0});
    r->requestPlacement(placed, true);  // clear of the bone: placed further out where the rim is in the way
    return {};
  } catch (const std::invalid_argument& e) {
    return tr("The reamer cannot be aimed: %1.").arg(QString::fromStdString(e.what()));
  }
}

void PlanningPanel::takeReamerAngles() {
  if (!reamer() || !bone()) return;
  try {
    const AxisAngles a = feedAxisAngles(scapularFrame(bone()->landmarks()), reamer()->pose().axis);
    version_->setValue(a.versionDeg);
    inclination_->setValue(a.inclinationDeg);
  } catch (const std::invalid_argument&) {  // the report above says why
  }
}

void PlanningPanel::takeGlenoidAngles() {
  if (const std::optional<AxisAngles> a = glenoidAngles(false)) {
    version_->setValue(a->versionDeg);
    inclination_->setValue(a->inclinationDeg);
  }
}

QString PlanningPanel::loadLandmarksFrom(const QString& path) {
  BoneNode* node = bone();
  if (!node) return tr("There is no bone to place landmarks on.");
  try {
    applyPlanning(*node, loadPlanning(path.toStdString()));
    return {};
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
}

QString PlanningPanel::saveLandmarksTo(const QString& path) {
  const BoneNode* node = bone();
  if (!node) return tr("There are no landmarks to save.");
  try {
    writeTextFile(path.toStdString(), planningToJson(planningOf(*node), "placed in ReamSim"));
    return {};
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
}

}  // namespace reamsim::ui
