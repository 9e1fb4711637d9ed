#pragma once
// Collision plugin: the exact BVH queries of reamsim::collision (BoneCollider), which follow the bone's cuts
// with local updates. The thesis's rays stay available to the CLI (--collision thesis) as the reference.
#include <QObject>

#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class CollisionPlugin : public QObject, public CollisionInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID ReamSimCollision_iid FILE "collision.json")
  Q_INTERFACES(reamsim::ui::CollisionInterface)

 public:
  QString engineName() const override { return QStringLiteral("BVH, exact (overlap, distance)"); }
  // The axial depth is not shown in the GUI: left out, it would cost milliseconds per move at 400k faces.
  std::unique_ptr<ContactBackend> createContactBackend() const override { return makeBvhContactBackend(false); }
};

}  // namespace reamsim::ui
