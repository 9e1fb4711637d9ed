#pragma once
// Extension points of the desktop application. A plugin is a QObject implementing one or more of these
// small interfaces, built as a Qt plugin (Q_PLUGIN_METADATA) and loaded with QPluginLoader from the
// plugin folder. The application runs reduced without any of them (see docs/GUI.md).
//
// Plugins are thin adapters over the headless modules; the engines they hand out are used from the
// session's worker thread, one call at a time.
#include <QString>
#include <QStringList>
#include <QtPlugin>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "reamsim/core/PatientFrame.h"
#include "reamsim/ui/BoneFileFacts.h"
#include "reamsim/mesh/RepairProgress.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/ream/ReamBackends.h"

class QDialog;
class QDockWidget;
class QWidget;

namespace reamsim {
class Document;
}

namespace reamsim::ui {

// A bone as import produced it.
struct ImportedBone {
  TriangleMesh mesh;                              // what the document's bone starts from (repaired if asked and possible)
  std::shared_ptr<const TriangleMesh> original;   // as read, for display and comparison
  std::string report;                             // what the importer did, in words
  bool cuttable = false;                          // closed, outward, free of self-intersections
  PatientFrame frame = PatientFrame::Unspecified;  // convention of the coordinates (kept in the BoneNode)
  std::string source;                             // where it came from, in words (kept in the BoneNode)
  // What a save by ReamSim recorded in the file beside the frame (removed volume, cut log, undo history), unset
  // in any other file.
  BoneFileFacts saved;
};

class MeshImportInterface {
 public:
  virtual ~MeshImportInterface() = default;
  virtual QStringList nameFilters() const = 0;  // for file dialogs, e.g. "Meshes (*.stl *.ply)"
  virtual QStringList extensions() const = 0;   // lower case, without dot
  // Runs on a worker thread. Throws reamsim::InputError naming the file and the problem. The facts a
  // ReamSim writer stored (BoneFileFacts) are read back; in other files the frame is Unspecified. `progress` follows the
  // reading (seconds for a large text file), then the validation or the repair (minutes for a large dirty mesh),
  // and stops them by returning false (a reamsim::StageCancelled is thrown: ReadCancelled or RepairCancelled).
  virtual ImportedBone importBone(const std::string& path, bool repair, const RepairProgress& progress = {}) const = 0;
  // Format from the extension; throws reamsim::InputError. `facts` go into the file's comments.
  // May run on a worker thread. The file is replaced whole or not at all; `progress` hears the fraction
  // done and stops the write by returning false (reamsim::WriteCancelled; the file there is unchanged).
  virtual void exportMesh(const TriangleMesh& mesh, const std::string& path, const BoneFileFacts& facts,
                          const ProgressCallback& progress = {}) const = 0;
};

// What the CT import dialog hands to the main window (on the UI thread).
struct VolumeImportResult {
  ImportedBone bone;    // frame: the mesh's patient frame; source: "CT volume PATH"
  QString name;         // for the title and the history, e.g. "quarter.nhdr (CT)"
  bool beside = false;  // add as another bone of the document instead of replacing the current one
};

// CT (or other volume) import: a dialog that opens a volume, shows orthogonal slices with the threshold
// overlaid and a live surface preview, and builds the bone off the UI thread (docs/CT_IMPORT.md).
class VolumeImportInterface {
 public:
  virtual ~VolumeImportInterface() = default;
  virtual QStringList nameFilters() const = 0;  // for file dialogs (a DICOM series: any slice file, or its folder)
  // A non-modal dialog, deleted when closed. It starts loading `path` (a file or a DICOM folder) at once;
  // an empty path leaves the choice to the user in the dialog. On Import it calls `deliver` on the UI
  // thread with the bone and closes. Errors (bad volume, nothing in range) are shown in the dialog.
  virtual QDialog* createImportDialog(const QString& path, std::function<void(VolumeImportResult)> deliver,
                                      QWidget* parent) = 0;
};

class CollisionInterface {
 public:
  virtual ~CollisionInterface() = default;
  virtual QString engineName() const = 0;
  virtual std::unique_ptr<ContactBackend> createContactBackend() const = 0;
};

class CsgInterface {
 public:
  virtual ~CsgInterface() = default;
  virtual QString engineName() const = 0;
  virtual CutBackendFactory cutBackendFactory() const = 0;
};

// A dock panel over the shared document (the log panel). The panel follows the document's nodes
// itself; it must not outlive the document (the main window deletes panels first).
class PanelInterface {
 public:
  virtual ~PanelInterface() = default;
  virtual QDockWidget* createPanel(Document& document, QWidget* parent) = 0;
};

}  // namespace reamsim::ui

// 1.1: ImportedBone carries the patient frame and source; exportMesh takes the frame.
// 1.2: exportMesh takes a progress callback that can stop the write.
#define ReamSimMeshImport_iid "org.reamsim.MeshImportInterface/1.4"
#define ReamSimCollision_iid "org.reamsim.CollisionInterface/1.0"
#define ReamSimCsg_iid "org.reamsim.CsgInterface/1.0"
#define ReamSimPanel_iid "org.reamsim.PanelInterface/1.0"
#define ReamSimVolumeImport_iid "org.reamsim.VolumeImportInterface/1.0"
Q_DECLARE_INTERFACE(reamsim::ui::MeshImportInterface, ReamSimMeshImport_iid)
Q_DECLARE_INTERFACE(reamsim::ui::CollisionInterface, ReamSimCollision_iid)
Q_DECLARE_INTERFACE(reamsim::ui::CsgInterface, ReamSimCsg_iid)
Q_DECLARE_INTERFACE(reamsim::ui::PanelInterface, ReamSimPanel_iid)
Q_DECLARE_INTERFACE(reamsim::ui::VolumeImportInterface, ReamSimVolumeImport_iid)
