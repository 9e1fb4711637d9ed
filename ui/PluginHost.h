#pragma once
// Loads the application's plugins with QPluginLoader from one folder and records, for Help → Plugins,
// what loaded and what failed and why. Missing plugins are not errors: the application runs reduced.
#include <QObject>
#include <QString>
#include <QStringList>
#include <vector>

#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

struct PluginRecord {
  QString name;      // from the plugin's metadata, or the expected name for a missing one
  QString file;      // empty for a missing plugin
  bool loaded = false;
  QString provides;  // interfaces, e.g. "mesh import"
  QString detail;    // description, or why it failed
};

class PluginHost {
 public:
  // The plugins the application is built with; a missing one is listed as "not found".
  static QStringList expectedPlugins() { return {"meshimport", "collision", "csg", "logpanel", "ctimport", "planning"}; }
  // $REAMSIM_PLUGIN_DIR, then <exe>/plugins (build tree), then <exe>/../lib/reamsim/plugins (installed).
  static QString defaultPluginDir();

  void loadFrom(const QString& dir);

  const QString& directory() const { return dir_; }
  const std::vector<PluginRecord>& records() const { return records_; }
  QString summaryText() const;  // one line per plugin, for the dialog and the log

  MeshImportInterface* meshImport() const { return meshImport_; }
  CollisionInterface* collision() const { return collision_; }
  CsgInterface* csg() const { return csg_; }
  const std::vector<PanelInterface*>& panels() const { return panels_; }
  VolumeImportInterface* volumeImport() const { return volumeImport_; }

 private:
  QString dir_;
  std::vector<PluginRecord> records_;
  MeshImportInterface* meshImport_ = nullptr;
  CollisionInterface* collision_ = nullptr;
  CsgInterface* csg_ = nullptr;
  std::vector<PanelInterface*> panels_;
  VolumeImportInterface* volumeImport_ = nullptr;
};

}  // namespace reamsim::ui
