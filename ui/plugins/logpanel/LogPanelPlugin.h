#pragma once
// Log panel plugin: a dock listing the cut log of the shared document.
#include <QObject>

#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class LogPanelPlugin : public QObject, public PanelInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID ReamSimPanel_iid FILE "logpanel.json")
  Q_INTERFACES(reamsim::ui::PanelInterface)

 public:
  QDockWidget* createPanel(Document& document, QWidget* parent) override;
};

}  // namespace reamsim::ui
