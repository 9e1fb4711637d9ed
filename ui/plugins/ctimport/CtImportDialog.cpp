#include "CtImportDialog.h"

#include <QLocale>
#include <QCheckBox>
#include <QCloseEvent>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QEventLoop>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMessageBox>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QSlider>
#include <QSpinBox>
#include <QtConcurrent/QtConcurrentRun>
#include <cmath>

#include "SliceView.h"
#include "SurfacePreview.h"
#include "reamsim/ctimport/VolumeIO.h"

namespace reamsim::ui::ct_import {
namespace {

constexpr int kPreviewDebounceMs = 150;

PatientFrame toFrame(ct::PatientSpace s) {
  switch (s) {
    case ct::PatientSpace::LPS: return PatientFrame::LPS;
    case ct::PatientSpace::RAS: return PatientFrame::RAS;
    case ct::PatientSpace::Unspecified: break;
  }
  return PatientFrame::Unspecified;
}

QString number(double v) { return QLocale().toString(v, 'g', 4); }  // shown: the user's decimal sign

}  // namespace

CtImportDialog::CtImportDialog(std::function<void(VolumeImportResult)> deliver, QWidget* parent)
    : QDialog(parent), deliver_(std::move(deliver)) {
  setObjectName("CtImportDialog");
  setAttribute(Qt::WA_DeleteOnClose);
  setModal(false);  // the main window (and the tests) keep running while the user looks at slices
  buildUi();
  previewTimer_.setSingleShot(true);
  previewTimer_.setInterval(kPreviewDebounceMs);
  connect(&previewTimer_, &QTimer::timeout, this, &CtImportDialog::startPreview);
  connect(&loadWatcher_, &QFutureWatcher<LoadOutcome>::finished, this, &CtImportDialog::loadFinished);
  connect(&previewWatcher_, &QFutureWatcher<PreviewOutcome>::finished, this, &CtImportDialog::previewFinished);
  connect(&importWatcher_, &QFutureWatcher<ImportOutcome>::finished, this, &CtImportDialog::importFinished);
}

CtImportDialog::~CtImportDialog() {
  // Workers hold the volume and the cancel flags by shared_ptr; their progress updates are queued to
  // this object and dropped with it. Stop what can stop, then wait: nothing outlives the dialog.
  if (cancelLoad_) cancelLoad_->store(true);
  if (cancelImport_) cancelImport_->store(true);
  for (QFutureWatcherBase* w : std::initializer_list<QFutureWatcherBase*>{&loadWatcher_, &previewWatcher_, &importWatcher_}) {
    w->disconnect(this);
    w->waitForFinished();
  }
}

// --- volume ----------------------------------------------------------------------------------------------

void CtImportDialog::chooseFile() {
  QStringList patterns;
  for (const std::string& e : ct::supportedVolumeExtensions()) patterns << "*" + QString::fromStdString(e);
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Open CT volume"), QFileInfo(path_).absolutePath(),
      tr("CT volumes (%1);;All files (*)").arg(patterns.join(' ')));
  if (!path.isEmpty()) openVolume(path);
}

void CtImportDialog::chooseFolder() {
  const QString dir = QFileDialog::getExistingDirectory(this, tr("Open a DICOM series folder"), QFileInfo(path_).absolutePath());
  if (!dir.isEmpty()) openVolume(dir);
}

void CtImportDialog::openVolume(const QString& path) {
  if (importing_) {
    fail(tr("Import CT"), tr("An import is running; cancel it before opening another volume."));
    return;
  }
  if (loading_) {  // the newer choice wins; the older read stops at its next slice
    cancelLoad_->store(true);
    loadWatcher_.waitForFinished();
  }
  path_ = QDir::cleanPath(path);
  pathLabel_->setText(QDir::toNativeSeparators(path_));
  status_ = tr("reading…");
  stageLabel_->setText(tr("reading %1…").arg(QFileInfo(path_).fileName()));
  progress_->setValue(0);
  progress_->setVisible(true);
  cancelLoad_ = std::make_shared<std::atomic<bool>>(false);
  const ct::ProgressCallback progress = progressRelay(
      this, [this](double f, const QString&) { progress_->setValue(int(std::lround(f * 1000))); }, cancelLoad_);
  loading_ = true;
  setBusy();
  const QString file = path_;
  loadWatcher_.setFuture(QtConcurrent::run([file, progress] { return loadVolume(file, progress); }));
  Q_EMIT stateChanged();
}

void CtImportDialog::loadFinished() {
  loading_ = false;
  progress_->setVisible(false);
  stageLabel_->clear();
  LoadOutcome out = loadWatcher_.result();
  if (out.cancelled) {
    status_ = tr("reading cancelled");
  } else if (!out.error.isEmpty()) {
    // The reader's message names the file; the title names it too, whatever the reader said.
    fail(tr("Cannot read %1").arg(QFileInfo(path_).fileName()),
         tr("Cannot read the volume %1:\n\n%2").arg(QDir::toNativeSeparators(path_), out.error));
  } else {
    showVolume(out);
  }
  setBusy();
  Q_EMIT stateChanged();
}

void CtImportDialog::showVolume(const LoadOutcome& loaded) {
  loaded_ = loaded;
  volume_ = loaded.volume;
  lastError_.clear();
  const ct::CtVolume& v = *volume_;
  QString info = tr("%1 · %2 × %3 × %4 voxels · %5 × %6 × %7 mm · %8 · values %9 … %10%11")
                     .arg(QString::fromStdString(v.format))
                     .arg(v.dims[0]).arg(v.dims[1]).arg(v.dims[2])
                     .arg(number(v.spacing[0]), number(v.spacing[1]), number(v.spacing[2]))
                     .arg(v.space == ct::PatientSpace::Unspecified ? tr("no patient frame") : tr("%1 frame").arg(ct::toString(v.space)))
                     .arg(number(loaded.minValue), number(loaded.maxValue))
                     .arg(v.valueUnit.empty() ? QString() : " " + QString::fromStdString(v.valueUnit));
  if (!loaded.looksLikeHu) info += tr(" — no air near −1000: probably not Hounsfield units; choose the threshold on the slices");
  for (const std::string& n : v.notes) info += "\n" + tr("note: %1").arg(QString::fromStdString(n));
  infoLabel_->setText(info);
  status_ = tr("loaded");

  // Threshold controls over the volume's values; the threshold itself is kept (default 250 HU).
  const int lo = int(std::floor(loaded.minValue)), hi = int(std::ceil(loaded.maxValue));
  {
    const QSignalBlocker b1(lower_), b2(upper_), b3(lowerSlider_);
    lower_->setRange(lo, hi);
    upper_->setRange(lo, hi);
    lowerSlider_->setRange(lo, hi);
    lowerSlider_->setValue(int(std::lround(lower_->value())));
  }
  windowPreset_->setCurrentIndex(loaded.looksLikeHu ? 0 : 2);
  applyWindow();
  for (int a = 0; a < 3; ++a) {
    kind_[a] = sliceKind(v, a);
    sliceLabels_[a]->setText(sliceKindName(kind_[a], a));
    index_[a] = v.dims[a] / 2;
    const QSignalBlocker block(sliders_[a]);
    sliders_[a]->setRange(0, v.dims[a] - 1);
    sliders_[a]->setValue(index_[a]);
    sliders_[a]->setEnabled(true);
  }
  // Without a patient frame there is nothing to convert: the mesh keeps the file's coordinates.
  frame_->setEnabled(v.space != ct::PatientSpace::Unspecified);
  frame_->setToolTip(frame_->isEnabled() ? tr("Patient coordinate convention of the bone mesh; kept with the bone")
                                         : tr("The volume names no patient frame: the mesh keeps the file's coordinates"));
  updateSlices();
  preview_->setVolume(v, meshSpace());
  requestPreview();
  previewTimer_.stop();
  startPreview();  // the first preview needs no debounce
}

// --- slices ----------------------------------------------------------------------------------------------

void CtImportDialog::setSliceIndex(int axis, int index) {
  if (!volume_ || axis < 0 || axis > 2) return;
  index = std::clamp(index, 0, volume_->dims[std::size_t(axis)] - 1);
  if (index == index_[std::size_t(axis)]) return;
  index_[std::size_t(axis)] = index;
  {
    const QSignalBlocker block(sliders_[std::size_t(axis)]);
    sliders_[std::size_t(axis)]->setValue(index);
  }
  updateSlice(axis);
  updateCrosshairs();
  if (component_->currentIndex() == kRegionAtCrosshair) requestPreview();  // the kept region follows the crosshair
}

void CtImportDialog::updateSlices() {
  for (int a = 0; a < 3; ++a) updateSlice(a);
  updateCrosshairs();
}

void CtImportDialog::updateSlice(int a) {
  if (!volume_) return;
  const ct::ImportOptions o = options();
  ct::SliceImage s = ct::extractSlice(*volume_, ct::SliceAxis(a), index_[std::size_t(a)], o.lowerThreshold, o.upperThreshold);
  const SliceOrientation orientation = sliceOrientation(s, kind_[std::size_t(a)]);
  views_[std::size_t(a)]->setSlice(std::move(s), orientation);
  sliceLabels_[std::size_t(a)]->setText(tr("%1 %2 / %3")
                                            .arg(sliceKindName(kind_[std::size_t(a)], a))
                                            .arg(index_[std::size_t(a)] + 1)
                                            .arg(volume_->dims[std::size_t(a)]));
}

void CtImportDialog::updateCrosshairs() {
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, w = (a + 2) % 3;
    views_[std::size_t(a)]->setCrosshair({index_[std::size_t(std::min(u, w))], index_[std::size_t(std::max(u, w))]});
  }
}

int CtImportDialog::maskPixels(int axis) const { return axis >= 0 && axis < 3 ? views_[std::size_t(axis)]->maskPixels() : -1; }

QImage CtImportDialog::sliceImage(int axis) const {
  return axis >= 0 && axis < 3 ? views_[std::size_t(axis)]->composed() : QImage();
}

void CtImportDialog::applyWindow() {
  double level = 400, width = 2000;  // bone window
  switch (windowPreset_->currentIndex()) {
    case 1: level = 40; width = 400; break;  // soft tissue
    case 2:
      if (volume_) {
        level = (loaded_.lowPercentile + loaded_.highPercentile) / 2;
        width = std::max(1.0, double(loaded_.highPercentile - loaded_.lowPercentile));
      }
      break;
    default: break;
  }
  const QSignalBlocker b1(level_), b2(window_);
  level_->setValue(level);
  window_->setValue(width);
  for (SliceView* v : views_) v->setWindow(level_->value(), window_->value());
}

void CtImportDialog::thresholdChanged() {
  updateSlices();  // the overlay follows at once
  requestPreview();  // the surface once the threshold rests
  setBusy();
}

bool CtImportDialog::thresholdsValid() const { return !upperOn_->isChecked() || upper_->value() >= lower_->value(); }

ct::PatientSpace CtImportDialog::meshSpace() const {
  if (!volume_ || volume_->space == ct::PatientSpace::Unspecified) return ct::PatientSpace::Unspecified;
  const std::optional<ct::PatientSpace> out = options().outputSpace;
  return out ? *out : volume_->space;
}

ct::ImportOptions CtImportDialog::options() const {
  ct::ImportOptions o;
  o.lowerThreshold = lower_->value();
  if (upperOn_->isChecked()) o.upperThreshold = upper_->value();
  o.targetFaces = std::size_t(targetFaces_->value());
  o.smoothingIterations = smoothing_->value();
  switch (component_->currentIndex()) {
    case kAllRegions: o.component = ct::ComponentMode::All; break;
    case kRegionAtCrosshair:
      // The voxel at the crosshair (the three slices' indices), in the volume's own space as the pipeline takes it.
      o.component = ct::ComponentMode::Seed;
      if (volume_) o.seedWorld = volume_->indexToWorld(index_[0], index_[1], index_[2]);
      break;
    default: o.component = ct::ComponentMode::Largest; break;
  }
  o.fillCavities = fillCavities_->isChecked();
  switch (frame_->currentIndex()) {
    case 0: o.outputSpace = ct::PatientSpace::LPS; break;
    case 1: o.outputSpace = ct::PatientSpace::RAS; break;
    default: o.outputSpace = std::nullopt; break;  // the volume's own
  }
  return o;
}

// --- preview ---------------------------------------------------------------------------------------------

// Every change asks for a new preview; only the newest request is ever shown. The debounce keeps a
// dragged slider from queueing work, and a result that is no longer the newest is dropped.
void CtImportDialog::requestPreview() {
  if (!volume_) return;
  ++previewRequested_;
  previewTimer_.start();
  Q_EMIT stateChanged();
}

void CtImportDialog::startPreview() {
  if (!volume_ || previewing_) return;  // a running one restarts this when it finishes
  const std::uint64_t generation = previewRequested_;
  if (!thresholdsValid()) {
    previewDone_ = generation;
    preview_->clearSurface();
    previewLabel_->setText(tr("Upper threshold below the lower one"));
    setBusy();
    Q_EMIT stateChanged();
    return;
  }
  previewing_ = true;
  previewLabel_->setText(tr("Computing the preview…"));
  const VolumePtr volume = volume_;
  const ct::ImportOptions o = options();
  previewWatcher_.setFuture(QtConcurrent::run([volume, o, generation] { return computePreview(volume, o, generation); }));
  Q_EMIT stateChanged();
}

void CtImportDialog::previewFinished() {
  previewing_ = false;
  const PreviewOutcome out = previewWatcher_.result();
  if (out.generation == previewRequested_) {
    previewDone_ = out.generation;
    if (out.error.isEmpty()) {
      preview_->setSurface(out.mesh);
      previewLabel_->setText(tr("Preview: %1 faces (low resolution; Import builds the full surface)").arg(out.mesh.triangles.size()));
    } else {
      preview_->clearSurface();
      previewLabel_->setText(tr("No surface: %1").arg(out.error));
    }
  } else if (!previewTimer_.isActive()) {
    startPreview();  // stale: the settings changed while it ran
  }
  setBusy();
  Q_EMIT stateChanged();
}

int CtImportDialog::previewFaces() const { return int(preview_->faces()); }

// --- import ----------------------------------------------------------------------------------------------

void CtImportDialog::startImport() {
  if (!volume_ || importing_ || loading_) return;
  if (!thresholdsValid()) {
    fail(tr("Import CT"), tr("The upper threshold (%1) is below the lower one (%2).").arg(upper_->value()).arg(lower_->value()));
    return;
  }
  cancelImport_ = std::make_shared<std::atomic<bool>>(false);
  const ct::ProgressCallback progress = progressRelay(
      this,
      [this](double f, const QString& stage) {
        progress_->setValue(int(std::lround(f * 1000)));
        stageLabel_->setText(stage);
      },
      cancelImport_);
  importing_ = true;
  status_ = tr("importing…");
  progress_->setValue(0);
  progress_->setVisible(true);
  stageLabel_->setText(tr("starting…"));
  setBusy();
  const VolumePtr volume = volume_;
  const ct::ImportOptions o = options();
  importWatcher_.setFuture(QtConcurrent::run([volume, o, progress] { return runImport(volume, o, progress); }));
  Q_EMIT stateChanged();
}

void CtImportDialog::cancelWork() {
  if (importing_ && cancelImport_) cancelImport_->store(true);
  if (loading_ && cancelLoad_) cancelLoad_->store(true);
  stageLabel_->setText(tr("cancelling…"));
}

void CtImportDialog::importFinished() {
  importing_ = false;
  progress_->setVisible(false);
  ImportOutcome out = importWatcher_.result();
  if (!out.cancelledStage.isEmpty()) {
    status_ = tr("import cancelled during %1").arg(out.cancelledStage);
    stageLabel_->setText(status_);
  } else if (!out.error.isEmpty()) {
    stageLabel_->clear();
    fail(tr("Import failed"), tr("%1:\n\n%2").arg(QDir::toNativeSeparators(path_), out.error));
  } else {
    VolumeImportResult r;
    const ct::ImportReport& report = out.result.report;
    r.bone.original = std::make_shared<const TriangleMesh>(out.result.mesh);
    r.bone.mesh = std::move(out.result.mesh);
    r.bone.cuttable = report.validation.isCleanSolid();
    r.bone.frame = toFrame(out.result.space);
    r.bone.source = "CT volume " + path_.toStdString();
    r.bone.report = ct::toText(report);
    if (!r.bone.cuttable) r.bone.report += "not a clean closed solid: shown, cutting disabled\n";
    r.name = tr("%1 (CT)").arg(QFileInfo(path_).fileName());
    r.beside = beside_->isChecked();
    status_ = tr("imported");
    setBusy();
    Q_EMIT stateChanged();
    deliver_(std::move(r));
    close();  // deleted later (WA_DeleteOnClose)
    return;
  }
  setBusy();
  Q_EMIT stateChanged();
}

// --- state -----------------------------------------------------------------------------------------------

void CtImportDialog::setBusy() {
  const bool haveVolume = volume_ != nullptr;
  importButton_->setEnabled(haveVolume && !importing_ && !loading_ && thresholdsValid());
  cancelButton_->setEnabled(importing_ || loading_);
  cancelButton_->setText(importing_ ? tr("Cancel import") : tr("Cancel"));
  openFile_->setEnabled(!importing_);
  openFolder_->setEnabled(!importing_);
}

bool CtImportDialog::isIdle() const {
  return !loading_ && !importing_ && !previewing_ && !previewTimer_.isActive() &&
         (!volume_ || previewDone_ == previewRequested_);
}

QString CtImportDialog::status() const { return status_; }

bool CtImportDialog::waitIdle(int timeoutMs) {
  if (isIdle()) return true;
  QPointer<CtImportDialog> self(this);
  QEventLoop loop;
  connect(this, &CtImportDialog::stateChanged, &loop, [&] {
    if (isIdle()) loop.quit();
  });
  connect(this, &QObject::destroyed, &loop, &QEventLoop::quit);
  QTimer::singleShot(timeoutMs, &loop, &QEventLoop::quit);
  loop.exec();
  return !self || isIdle();  // closed after delivering: nothing left to wait for
}

void CtImportDialog::fail(const QString& title, const QString& message) {
  lastError_ = message;
  status_ = tr("error");
  stageLabel_->setText(message.section('\n', 0, 0));
  // Window-modal, opened (not exec'd): the event loop, the workers and the tests keep running.
  auto* box = new QMessageBox(QMessageBox::Critical, title, message, QMessageBox::Ok, this);
  box->setObjectName("CtImportError");
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->open();
}

// Close, Esc and the window's close button all end here or in reject(): the dialog is deleted, and its
// destructor cancels and waits for the workers.
void CtImportDialog::closeEvent(QCloseEvent* e) {
  cancelWork();
  QDialog::closeEvent(e);
}

}  // namespace reamsim::ui::ct_import
