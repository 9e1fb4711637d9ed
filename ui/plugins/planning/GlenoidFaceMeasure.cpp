#include "GlenoidFaceMeasure.h"

#include <QtConcurrent/QtConcurrentRun>
#include <utility>

namespace reamsim::ui {

GlenoidFaceMeasure::GlenoidFaceMeasure(QObject* parent) : QObject(parent) {
  connect(&watcher_, &QFutureWatcher<std::vector<Measured>>::finished, this, [this] {
    for (Measured& m : watcher_.result()) {
      openedMeasures_ += m.revision == m.openedRevision ? 1 : 0;
      keep(std::move(m));
    }
    Q_EMIT measured();
  });
}

void GlenoidFaceMeasure::keep(Measured m) {
  known_.push_front(std::move(m));
  if (known_.size() > kKept) known_.pop_back();
}

bool GlenoidFaceMeasure::touch(std::uint64_t revision, const Vec3& centre) {
  for (auto it = known_.begin(); it != known_.end(); ++it)
    if (it->revision == revision && it->centre == centre) {
      if (it != known_.begin()) {
        Measured m = std::move(*it);
        known_.erase(it);
        known_.push_front(std::move(m));
      }
      return true;
    }
  return false;
}

const GlenoidFaceMeasure::Measured* GlenoidFaceMeasure::find(std::uint64_t revision, const Vec3& centre) const {
  for (const Measured& m : known_)
    if (m.revision == revision && m.centre == centre) return &m;
  return nullptr;
}

const GlenoidFaceMeasure::Measured* GlenoidFaceMeasure::latestCut(std::uint64_t openedRevision, const Vec3& centre) const {
  // Revisions only grow: the largest is the last state committed.
  const Measured* latest = nullptr;
  for (const Measured& m : known_)
    if (m.openedRevision == openedRevision && m.revision != openedRevision && m.centre == centre &&
        (!latest || m.revision > latest->revision))
      latest = &m;
  return latest;
}

void GlenoidFaceMeasure::ask(const BoneNode& bone, const Vec3& centre) {
  const BoneHistory::Entry& opened = bone.history().entries().front();
  const std::uint64_t now = bone.currentRevision();
  // The state now last, so that the bone as opened is never the least recently asked.
  const bool openedKnown = touch(opened.revision, centre);
  const bool nowKnown = now == opened.revision || touch(now, centre);
  if ((openedKnown && nowKnown) || watcher_.isRunning()) return;  // a running job's end asks again (measured())
  std::vector<std::pair<std::uint64_t, BoneState>> missing;  // copies share the states' storage: cheap
  if (!openedKnown) missing.emplace_back(opened.revision, opened.state);
  if (!nowKnown) missing.emplace_back(now, bone.current());
  watcher_.setFuture(QtConcurrent::run([missing = std::move(missing), centre, openedRevision = opened.revision] {
    std::vector<Measured> out;
    out.reserve(missing.size());
    for (const auto& [revision, state] : missing) {
      Measured m{revision, openedRevision, centre, std::nullopt, {}};
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
