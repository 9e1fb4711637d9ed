#include "CtImportPlugin.h"

#include "CtImportDialog.h"
#include "reamsim/ctimport/VolumeIO.h"

namespace reamsim::ui {

QStringList CtImportPlugin::nameFilters() const {
  QStringList patterns;
  for (const std::string& e : ct::supportedVolumeExtensions()) patterns << "*" + QString::fromStdString(e);
  return {tr("CT volumes (%1)").arg(patterns.join(' ')), tr("All files (*)")};
}

QDialog* CtImportPlugin::createImportDialog(const QString& path, std::function<void(VolumeImportResult)> deliver,
                                            QWidget* parent) {
  auto* dialog = new ct_import::CtImportDialog(std::move(deliver), parent);
  if (!path.isEmpty()) dialog->openVolume(path);
  return dialog;
}

}  // namespace reamsim::ui
