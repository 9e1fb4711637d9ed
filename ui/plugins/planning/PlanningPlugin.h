#pragma once
// Planning plugin: a dock for the scapular landmarks and the reamer axis's version and inclination.
#include <QObject>

#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class PlanningPlugin : public QObject, public PanelInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID ReamSimPanel_iid FILE "planning.json")
  Q_INTERFACES(reamsim::ui::PanelInterface)

 public:
  QDockWidget* createPanel(Document& document, QWidget* parent) override;
};

}  // namespace reamsim::ui
