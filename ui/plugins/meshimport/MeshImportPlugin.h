#pragma once
// Mesh import/export plugin: reamsim::mesh readers and writers plus repair on import (mesh_repair).
#include <QObject>

#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class MeshImportPlugin : public QObject, public MeshImportInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID ReamSimMeshImport_iid FILE "meshimport.json")
  Q_INTERFACES(reamsim::ui::MeshImportInterface)

 public:
  QStringList nameFilters() const override;
  QStringList extensions() const override;
  ImportedBone importBone(const std::string& path, bool repair, const RepairProgress& progress = {}) const override;
  void exportMesh(const TriangleMesh& mesh, const std::string& path, const BoneFileFacts& facts,
                  const ProgressCallback& progress = {}) const override;
};

}  // namespace reamsim::ui
