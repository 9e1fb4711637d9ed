#pragma once
// Collision plugin: the thesis's contact query from reamsim::collision.
#include <QObject>

#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class CollisionPlugin : public QObject, public CollisionInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID ReamSimCollision_iid FILE "collision.json")
  Q_INTERFACES(reamsim::ui::CollisionInterface)

 public:
  QString engineName() const override { return QStringLiteral("thesis rays (brute force)"); }
  std::unique_ptr<ContactBackend> createContactBackend() const override { return makeThesisContactBackend(); }
};

}  // namespace reamsim::ui
