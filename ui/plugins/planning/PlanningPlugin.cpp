#include "PlanningPlugin.h"

#include "PlanningPanel.h"

namespace reamsim::ui {

QDockWidget* PlanningPlugin::createPanel(Document& document, QWidget* parent) { return new PlanningPanel(document, parent); }

}  // namespace reamsim::ui
