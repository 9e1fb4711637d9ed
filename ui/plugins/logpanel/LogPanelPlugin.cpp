#include "LogPanelPlugin.h"

#include "LogPanel.h"

namespace reamsim::ui {

QDockWidget* LogPanelPlugin::createPanel(Document& document, QWidget* parent) { return new LogPanel(document, parent); }

}  // namespace reamsim::ui
