#include "GlenoidFaceMeasure.h"

#include <QtConcurrent/QtConcurrentRun>
#include <utility>

namespace reamsim::ui {

GlenoidFaceMeasure::GlenoidFaceMeasure(QObject* parent) : QObject(parent) {
  connect(&watcher_, &QFutureWatcher<std::vector<Measured>>::finished, this, [this] {
    for (Measured& m : watcher_.result()) {
      known_.push_front(std::move(m));
      if (known_.size() > kKept) known_.pop_back();
    }
    Q_EMIT measured();
  });
}

const GlenoidFaceMeasure::Measured* GlenoidFaceMeasure::find(std::uint64_t revision, const Vec3& centre) const {
  for (const Measured& m : known_)
    if (m.revision == revision && m.centre == centre) return &m;
  return nullptr;
}

void GlenoidFaceMeasure::ask(const BoneNode& bone, const Vec3& centre) {
  if (watcher_.isRunning()) return;  // measured() comes when it ends, and the dock asks again
  std::vector<std::pair<std::uint64_t, BoneState>> missing;  // copies share the states' storage: cheap
  const BoneHistory::Entry& opened = bone.history().entries().front();
  if (!find(opened.revision, centre)) missing.emplace_back(opened.revision, opened.state);
  if (bone.currentRevision() != opened.revision && !find(bone.currentRevision(), centre))
    missing.emplace_back(bone.currentRevision(), bone.current());
  if (missing.empty()) return;
  watcher_.setFuture(QtConcurrent::run([missing = std::move(missing), centre] {
    std::vector<Measured> out;
    for (const auto& [revision, state] : missing) {
      Measured m{revision, centre, std::nullopt, {}};
      try {
        m.face = measureGlenoidFace(state, centre);
      } catch (const std::exception& e) {
        m.error = e.what();
      }
      out.push_back(std::move(m));
    }
    return out;
  }));
}

}  // namespace reamsim::ui
