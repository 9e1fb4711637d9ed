#pragma once
// CSG plugin: the local exact engine of reamsim::csg (LocalSubtractor: patch-local, exact predicates and
// constructions; it also cuts open or dirty bones away from their defects). The CGAL whole-mesh reference
// stays available to the CLI (reamsim-cli ream --engine reference).
#include <QObject>

#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class CsgPlugin : public QObject, public CsgInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID ReamSimCsg_iid FILE "csg.json")
  Q_INTERFACES(reamsim::ui::CsgInterface)

 public:
  QString engineName() const override { return QStringLiteral("local exact subtraction (LocalSubtractor)"); }
  CutBackendFactory cutBackendFactory() const override { return localCutBackendFactory(); }
};

}  // namespace reamsim::ui
