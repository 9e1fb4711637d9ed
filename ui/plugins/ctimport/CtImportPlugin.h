#pragma once
// CT import plugin: the import dialog over reamsim::ct (readers, importBone, slices and preview).
#include <QObject>

#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class CtImportPlugin : public QObject, public VolumeImportInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID ReamSimVolumeImport_iid FILE "ctimport.json")
  Q_INTERFACES(reamsim::ui::VolumeImportInterface)

 public:
  QStringList nameFilters() const override;
  QDialog* createImportDialog(const QString& path, std::function<void(VolumeImportResult)> deliver,
                              QWidget* parent) override;
};

}  // namespace reamsim::ui
