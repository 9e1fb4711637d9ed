#pragma once
// File → Import CT volume: open a volume (off the UI thread), look at three orthogonal slices with the
// threshold overlaid, watch a low-resolution surface follow the threshold, then build the bone with the
// full pipeline (off the UI thread, with progress and Cancel) and hand it to the main window, which
// replaces the bone or adds it beside (both undoable). A thin layer over reamsim::ct (docs/CT_IMPORT.md).
//
// Besides the widgets (object names in docs/CT_IMPORT.md), the slots below are the dialog's scriptable
// surface: the GUI tests call them by name through Qt's meta-object system.
#include <QDialog>
#include <QFutureWatcher>
#include <QImage>
#include <QTimer>
#include <array>
#include <atomic>
#include <functional>
#include <memory>

#include "SliceOrientation.h"
#include "VolumeJobs.h"
#include "reamsim/ui/PluginInterfaces.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QRadioButton;
class QSlider;
class QSpinBox;

namespace reamsim::ui::ct_import {

class SliceView;
class SurfacePreview;

class CtImportDialog : public QDialog {
  Q_OBJECT
  Q_PROPERTY(QString volumePath READ volumePath)
  Q_PROPERTY(bool volumeLoaded READ volumeLoaded)
  Q_PROPERTY(QString lastError READ lastError)
  Q_PROPERTY(QString status READ status)
  Q_PROPERTY(int previewFaces READ previewFaces)

 public:
  CtImportDialog(std::function<void(VolumeImportResult)> deliver, QWidget* parent = nullptr);
  ~CtImportDialog() override;

  QString volumePath() const { return path_; }
  bool volumeLoaded() const { return volume_ != nullptr; }
  QString lastError() const { return lastError_; }
  QString status() const;
  int previewFaces() const;

 public Q_SLOTS:
  void openVolume(const QString& path);  // a file or a DICOM folder; replaces the current volume
  // Processes events until nothing is loading, previewing (including a pending debounce) or importing;
  // false on timeout. True as well when the dialog closed itself after delivering an import.
  bool waitIdle(int timeoutMs);
  int maskPixels(int axis) const;   // threshold-mask pixels in the shown slice across axis 0/1/2
  QImage sliceImage(int axis) const;  // the slice as drawn (window/level + overlay), one pixel per voxel
  int sliceIndex(int axis) const { return index_[std::size_t(axis)]; }
  void setSliceIndex(int axis, int index);
  void startImport();
  void cancelWork();  // cancels a running load or import

 Q_SIGNALS:
  void stateChanged();  // something started or finished (waitIdle listens)

 protected:
  void closeEvent(QCloseEvent* e) override;

 private:
  // The Component choices, in the combo box's order.
  enum ComponentItem { kLargestRegion, kAllRegions, kRegionAtCrosshair };

  void buildUi();
  void chooseFile();
  void chooseFolder();
  void loadFinished();
  void showVolume(const LoadOutcome& loaded);
  void updateSlices();
  void updateSlice(int axis);
  void updateCrosshairs();
  void thresholdChanged();
  void applyWindow();
  void requestPreview();
  void startPreview();
  void previewFinished();
  void importFinished();
  void setBusy();
  void fail(const QString& title, const QString& message);
  bool isIdle() const;
  bool thresholdsValid() const;
  ct::ImportOptions options() const;
  ct::PatientSpace meshSpace() const;

  std::function<void(VolumeImportResult)> deliver_;
  QString path_, lastError_, status_;
  VolumePtr volume_;
  LoadOutcome loaded_;  // statistics of volume_ (its pointer is volume_)
  std::array<int, 3> index_{0, 0, 0};
  std::array<SliceKind, 3> kind_{SliceKind::Plain, SliceKind::Plain, SliceKind::Plain};

  // Workers. Each flag is true from start until its finished() handler has run.
  QFutureWatcher<LoadOutcome> loadWatcher_;
  QFutureWatcher<PreviewOutcome> previewWatcher_;
  QFutureWatcher<ImportOutcome> importWatcher_;
  bool loading_ = false, previewing_ = false, importing_ = false;
  std::shared_ptr<std::atomic<bool>> cancelLoad_, cancelImport_;
  QTimer previewTimer_;  // debounce: one preview after the threshold stops moving
  std::uint64_t previewRequested_ = 0, previewDone_ = 0;

  // Widgets
  QLabel *pathLabel_ = nullptr, *infoLabel_ = nullptr, *previewLabel_ = nullptr, *stageLabel_ = nullptr;
  QPushButton *openFile_ = nullptr, *openFolder_ = nullptr, *importButton_ = nullptr, *cancelButton_ = nullptr;
  QPushButton* closeButton_ = nullptr;
  std::array<SliceView*, 3> views_{};
  std::array<QSlider*, 3> sliders_{};
  std::array<QLabel*, 3> sliceLabels_{};
  QDoubleSpinBox *lower_ = nullptr, *upper_ = nullptr, *level_ = nullptr, *window_ = nullptr;
  QSlider* lowerSlider_ = nullptr;
  QCheckBox *upperOn_ = nullptr, *fillCavities_ = nullptr;
  QComboBox *windowPreset_ = nullptr, *component_ = nullptr, *frame_ = nullptr;
  QSpinBox *targetFaces_ = nullptr, *smoothing_ = nullptr;
  QRadioButton *replace_ = nullptr, *beside_ = nullptr;
  QProgressBar* progress_ = nullptr;
  SurfacePreview* preview_ = nullptr;
};

}  // namespace reamsim::ui::ct_import
