#include "reamsim/ream/LocalCutBackend.h"

#include "reamsim/csg/LocalSubtractor.h"

namespace reamsim {
namespace {

class LocalCutBackend final : public CutBackend {
 public:
  LocalCutBackend(const BoneState& bone, bool bandCleanup) : engine_(bone) {
    BandCleanup cleanup = engine_.bandCleanup();
    cleanup.enabled = bandCleanup;
    engine_.setBandCleanup(cleanup);
  }
  ReferenceCut subtract(const TriangleMesh& tool) override {
    const LocalCut c = engine_.subtract(tool);
    ReferenceCut r;
    r.changed = c.changed;
    r.removedMm3 = c.removedMm3;
    r.volumeBeforeMm3 = c.volumeBeforeMm3;
    r.volumeAfterMm3 = c.volumeAfterMm3;
    r.facesAfter = c.facesAfter;
    r.milliseconds = c.milliseconds;
    return r;
  }
  void setCuttingSolid(const TriangleMesh& solidLocal) override { engine_.setReferenceTool(solidLocal); }
  TriangleMesh mesh() const override { return engine_.mesh(); }
  const BoneState* state() const override { return &engine_.state(); }
  BoneInvariants checkInvariants() const override { return engine_.checkInvariants(); }

 private:
  LocalSubtractor engine_;
};

}  // namespace

CutBackendFactory localCutBackendFactory(bool bandCleanup) {
  return [bandCleanup](const BoneState& bone) -> std::unique_ptr<CutBackend> {
    return std::make_unique<LocalCutBackend>(bone, bandCleanup);
  };
}

}  // namespace reamsim
