// CtImportDialog: the widgets and how they are wired (the behaviour is in CtImportDialog.cpp).
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QSlider>
#include <QSpinBox>
#include <QSplitter>
#include <QVBoxLayout>
#include <cmath>

#include "CtImportDialog.h"
#include "SliceView.h"
#include "SurfacePreview.h"

namespace reamsim::ui::ct_import {
namespace {

QDoubleSpinBox* huSpin(QWidget* parent, const QString& name, double value) {
  auto* s = new QDoubleSpinBox(parent);
  s->setObjectName(name);
  s->setDecimals(0);
  s->setRange(-100000, 100000);  // narrowed to the volume's values once one is loaded
  s->setValue(value);
  s->setKeyboardTracking(false);  // typing "1150" is one change, not four
  return s;
}

}  // namespace

void CtImportDialog::buildUi() {
  setWindowTitle(tr("Import CT volume"));
  auto* root = new QVBoxLayout(this);

  // Which volume
  auto* fileRow = new QHBoxLayout;
  pathLabel_ = new QLabel(tr("No volume: open a file (NRRD, MetaImage, NIfTI, DICOM) or a DICOM folder."), this);
  pathLabel_->setObjectName("VolumePath");
  pathLabel_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  openFile_ = new QPushButton(tr("Open file…"), this);
  openFile_->setObjectName("OpenVolumeFile");
  openFolder_ = new QPushButton(tr("Open DICOM folder…"), this);
  openFolder_->setObjectName("OpenDicomFolder");
  fileRow->addWidget(pathLabel_, 1);
  fileRow->addWidget(openFile_);
  fileRow->addWidget(openFolder_);
  root->addLayout(fileRow);
  infoLabel_ = new QLabel(this);
  infoLabel_->setObjectName("VolumeInfo");
  infoLabel_->setWordWrap(true);
  root->addWidget(infoLabel_);

  // Slices | preview
  auto* split = new QSplitter(Qt::Horizontal, this);
  auto* slices = new QWidget(split);
  auto* grid = new QGridLayout(slices);
  grid->setContentsMargins(0, 0, 0, 0);
  for (int a = 0; a < 3; ++a) {
    const int column = 2 - a;  // k (usually axial) first
    sliceLabels_[a] = new QLabel(slices);
    sliceLabels_[a]->setObjectName(QStringLiteral("SliceLabel_%1").arg(QChar("IJK"[a])));
    views_[a] = new SliceView(slices);
    views_[a]->setObjectName(QStringLiteral("SliceView_%1").arg(QChar("IJK"[a])));
    sliders_[a] = new QSlider(Qt::Horizontal, slices);
    sliders_[a]->setObjectName(QStringLiteral("SliceSlider_%1").arg(QChar("IJK"[a])));
    sliders_[a]->setEnabled(false);
    grid->addWidget(sliceLabels_[a], 0, column);
    grid->addWidget(views_[a], 1, column);
    grid->addWidget(sliders_[a], 2, column);
    grid->setColumnStretch(column, 1);
    connect(sliders_[a], &QSlider::valueChanged, this, [this, a](int v) { setSliceIndex(a, v); });
    connect(views_[a], &SliceView::picked, this, [this, a](QPoint p) {
      // The view's image columns run along the lower-numbered other axis, rows along the higher.
      const int u = (a + 1) % 3, w = (a + 2) % 3;
      setSliceIndex(std::min(u, w), p.x());
      setSliceIndex(std::max(u, w), p.y());
    });
  }
  grid->setRowStretch(1, 1);
  auto* right = new QWidget(split);
  auto* rightLayout = new QVBoxLayout(right);
  rightLayout->setContentsMargins(0, 0, 0, 0);
  preview_ = new SurfacePreview(right);
  preview_->setMinimumSize(240, 240);
  previewLabel_ = new QLabel(tr("Surface preview (low resolution)"), right);
  previewLabel_->setObjectName("PreviewStatus");
  rightLayout->addWidget(preview_, 1);
  rightLayout->addWidget(previewLabel_);
  split->addWidget(slices);
  split->addWidget(right);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 2);
  root->addWidget(split, 1);

  // Threshold and display window
  auto* threshold = new QGroupBox(tr("Threshold (bone: lower ≤ value ≤ upper)"), this);
  auto* tRow = new QHBoxLayout(threshold);
  lower_ = huSpin(threshold, "LowerThreshold", 250);
  lowerSlider_ = new QSlider(Qt::Horizontal, threshold);
  lowerSlider_->setObjectName("LowerThresholdSlider");
  lowerSlider_->setRange(-1024, 3071);
  lowerSlider_->setValue(250);
  upperOn_ = new QCheckBox(tr("upper"), threshold);
  upperOn_->setObjectName("UpperThresholdOn");
  upperOn_->setToolTip(tr("Leave out brighter voxels, e.g. metal (2000–3000 HU)"));
  upper_ = huSpin(threshold, "UpperThreshold", 3000);
  upper_->setEnabled(false);
  tRow->addWidget(new QLabel(tr("lower"), threshold));
  tRow->addWidget(lower_);
  tRow->addWidget(lowerSlider_, 1);
  tRow->addWidget(upperOn_);
  tRow->addWidget(upper_);
  tRow->addSpacing(16);
  windowPreset_ = new QComboBox(threshold);
  windowPreset_->setObjectName("WindowPreset");
  windowPreset_->addItems({tr("bone window"), tr("soft-tissue window"), tr("full range")});
  level_ = huSpin(threshold, "WindowLevel", 400);
  window_ = huSpin(threshold, "WindowWidth", 2000);
  window_->setMinimum(1);
  tRow->addWidget(new QLabel(tr("display"), threshold));
  tRow->addWidget(windowPreset_);
  tRow->addWidget(new QLabel(tr("level"), threshold));
  tRow->addWidget(level_);
  tRow->addWidget(new QLabel(tr("width"), threshold));
  tRow->addWidget(window_);
  root->addWidget(threshold);

  // Surface options and where the bone goes
  auto* options = new QGroupBox(tr("Surface"), this);
  auto* oRow = new QHBoxLayout(options);
  targetFaces_ = new QSpinBox(options);
  targetFaces_->setObjectName("TargetFaces");
  targetFaces_->setRange(0, 5000000);
  targetFaces_->setSingleStep(10000);
  targetFaces_->setValue(150000);
  targetFaces_->setSpecialValueText(tr("no decimation"));
  smoothing_ = new QSpinBox(options);
  smoothing_->setObjectName("Smoothing");
  smoothing_->setRange(0, 200);
  smoothing_->setValue(15);
  smoothing_->setSpecialValueText(tr("off"));
  smoothing_->setToolTip(tr("Windowed-sinc iterations; the volume is kept"));
  component_ = new QComboBox(options);
  component_->setObjectName("Component");
  component_->addItems({tr("largest region"), tr("all regions"), tr("region at the crosshair")});  // ComponentItem
  component_->setToolTip(tr("Which connected bone to keep. For the region at the crosshair, click the slices to put "
                            "the crosshair on the bone you want (it may be any of them, e.g. the scapula beside the "
                            "larger humerus)"));
  fillCavities_ = new QCheckBox(tr("fill cavities"), options);
  fillCavities_->setObjectName("FillCavities");
  fillCavities_->setChecked(true);
  frame_ = new QComboBox(options);
  frame_->setObjectName("MeshFrame");
  frame_->addItems({tr("LPS (DICOM)"), tr("RAS (NIfTI, Slicer)"), tr("as the file")});
  frame_->setToolTip(tr("Patient coordinate convention of the bone mesh; kept with the bone in the document"));
  oRow->addWidget(new QLabel(tr("target faces"), options));
  oRow->addWidget(targetFaces_);
  oRow->addWidget(new QLabel(tr("smoothing"), options));
  oRow->addWidget(smoothing_);
  oRow->addWidget(component_);
  oRow->addWidget(fillCavities_);
  oRow->addWidget(new QLabel(tr("coordinates"), options));
  oRow->addWidget(frame_);
  oRow->addStretch(1);
  replace_ = new QRadioButton(tr("Replace the current bone"), options);
  replace_->setObjectName("PlaceReplace");
  replace_->setChecked(true);
  beside_ = new QRadioButton(tr("Add beside the current one"), options);
  beside_->setObjectName("PlaceBeside");
  beside_->setToolTip(tr("Shown with the current bone; the reamer keeps cutting the current bone"));
  oRow->addWidget(replace_);
  oRow->addWidget(beside_);
  root->addWidget(options);

  // Progress and buttons
  auto* bottom = new QHBoxLayout;
  progress_ = new QProgressBar(this);
  progress_->setObjectName("ImportProgress");
  progress_->setRange(0, 1000);
  progress_->setTextVisible(false);
  progress_->setVisible(false);
  stageLabel_ = new QLabel(this);
  stageLabel_->setObjectName("ImportStage");
  importButton_ = new QPushButton(tr("Import"), this);
  importButton_->setObjectName("ImportButton");
  importButton_->setEnabled(false);
  importButton_->setDefault(true);
  cancelButton_ = new QPushButton(tr("Cancel"), this);
  cancelButton_->setObjectName("CancelButton");
  cancelButton_->setEnabled(false);
  closeButton_ = new QPushButton(tr("Close"), this);
  closeButton_->setObjectName("CloseButton");
  bottom->addWidget(progress_, 1);
  bottom->addWidget(stageLabel_, 1);
  bottom->addWidget(importButton_);
  bottom->addWidget(cancelButton_);
  bottom->addWidget(closeButton_);
  root->addLayout(bottom);

  connect(openFile_, &QPushButton::clicked, this, &CtImportDialog::chooseFile);
  connect(openFolder_, &QPushButton::clicked, this, &CtImportDialog::chooseFolder);
  connect(importButton_, &QPushButton::clicked, this, &CtImportDialog::startImport);
  connect(cancelButton_, &QPushButton::clicked, this, &CtImportDialog::cancelWork);
  connect(closeButton_, &QPushButton::clicked, this, &CtImportDialog::close);
  connect(lower_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this](double v) {
    const QSignalBlocker block(lowerSlider_);
    lowerSlider_->setValue(int(std::lround(v)));
    thresholdChanged();
  });
  // Dragging the slider moves the spin box (which updates the slices at once; the preview is debounced).
  connect(lowerSlider_, &QSlider::valueChanged, lower_, [this](int v) { lower_->setValue(v); });
  connect(upperOn_, &QCheckBox::toggled, this, [this](bool on) {
    upper_->setEnabled(on);
    thresholdChanged();
  });
  connect(upper_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this] {
    if (upperOn_->isChecked()) thresholdChanged();
  });
  connect(windowPreset_, qOverload<int>(&QComboBox::activated), this, [this] { applyWindow(); });
  for (QDoubleSpinBox* s : {level_, window_})
    connect(s, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this] {
      for (SliceView* v : views_) v->setWindow(level_->value(), window_->value());
    });
  connect(smoothing_, qOverload<int>(&QSpinBox::valueChanged), this, [this] { requestPreview(); });
  connect(component_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] { requestPreview(); });
  connect(fillCavities_, &QCheckBox::toggled, this, [this] { requestPreview(); });
  connect(frame_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] {
    if (volume_) preview_->setVolume(*volume_, meshSpace());
    requestPreview();
  });
  resize(1280, 860);
}

}  // namespace reamsim::ui::ct_import
