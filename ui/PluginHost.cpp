#include "PluginHost.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <QJsonObject>
#include <QLibrary>
#include <QPluginLoader>

namespace reamsim::ui {

QString PluginHost::defaultPluginDir() {
  const QString env = qEnvironmentVariable("REAMSIM_PLUGIN_DIR");
  if (!env.isEmpty()) return env;
  const QDir exe(QCoreApplication::applicationDirPath());
  if (exe.exists("plugins")) return exe.filePath("plugins");
  return QDir::cleanPath(exe.filePath("../lib/reamsim/plugins"));
}

void PluginHost::loadFrom(const QString& dir) {
  dir_ = dir;
  QStringList found;
  const QFileInfoList files = QDir(dir).entryInfoList(QDir::Files, QDir::Name);
  for (const QFileInfo& file : files) {
    if (!QLibrary::isLibrary(file.fileName())) continue;
    PluginRecord r;
    r.file = file.absoluteFilePath();
    r.name = file.completeBaseName();
    // The loader is kept alive by Qt's plugin cache; instances live until the application exits.
    QPluginLoader loader(r.file);
    const QJsonObject meta = loader.metaData().value("MetaData").toObject();
    if (meta.contains("name")) r.name = meta.value("name").toString();
    found << r.name;
    QObject* instance = loader.instance();
    if (!instance) {
      r.detail = loader.errorString();
      records_.push_back(r);
      continue;
    }
    QStringList provides;
    if (auto* p = qobject_cast<MeshImportInterface*>(instance)) { meshImport_ = p; provides << "mesh import"; }
    if (auto* p = qobject_cast<CollisionInterface*>(instance)) { collision_ = p; provides << "collision"; }
    if (auto* p = qobject_cast<CsgInterface*>(instance)) { csg_ = p; provides << "CSG subtraction"; }
    if (auto* p = qobject_cast<PanelInterface*>(instance)) { panels_.push_back(p); provides << "panel"; }
    if (auto* p = qobject_cast<VolumeImportInterface*>(instance)) { volumeImport_ = p; provides << "CT import"; }
    r.loaded = !provides.isEmpty();
    r.provides = provides.join(", ");
    r.detail = r.loaded ? meta.value("description").toString() : QStringLiteral("implements no ReamSim interface");
    if (!r.loaded) loader.unload();
    records_.push_back(r);
  }
  for (const QString& name : expectedPlugins())
    if (!found.contains(name)) records_.push_back({name, {}, false, {}, QStringLiteral("not found in %1").arg(dir)});
}

QString PluginHost::summaryText() const {
  QStringList lines;
  for (const PluginRecord& r : records_)
    lines << QStringLiteral("%1: %2%3 — %4")
                 .arg(r.name, r.loaded ? QStringLiteral("loaded") : QStringLiteral("FAILED"),
                      r.provides.isEmpty() ? QString() : " (" + r.provides + ")", r.detail);
  return lines.join('\n');
}

}  // namespace reamsim::ui
