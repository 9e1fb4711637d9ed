#pragma once
// CSG plugin: exact whole-mesh subtraction from reamsim::csg (CGAL corefinement, Epeck).
#include <QObject>

#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class CsgPlugin : public QObject, public CsgInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID ReamSimCsg_iid FILE "csg.json")
  Q_INTERFACES(reamsim::ui::CsgInterface)

 public:
  QString engineName() const override { return QStringLiteral("CGAL exact corefinement (reference)"); }
  CutBackendFactory cutBackendFactory() const override { return referenceCutBackendFactory(); }
};

}  // namespace reamsim::ui
