// The default backends: thin adapters over the collision and csg modules. Kept in their own unit so a
// program that brings its own backends (the GUI's plugins) does not link CGAL through this library.
#include "reamsim/ream/ReamBackends.h"

#include "reamsim/collision/ThesisContact.h"

namespace reamsim {
namespace {

class ThesisContactBackend final : public ContactBackend {
 public:
  ContactResult query(const ContactInput& in) override {
    return thesisContactQuery(*in.boneMesh, in.boneBounds, in.tool, in.probes, in.feedAxis, in.stepMm);
  }
  bool needsMesh() const override { return true; }
};

class ReferenceCutBackend final : public CutBackend {
 public:
  explicit ReferenceCutBackend(const TriangleMesh& bone) : engine_(bone) {}
  ReferenceCut subtract(const TriangleMesh& tool) override { return engine_.subtract(tool); }
  TriangleMesh mesh() const override { return engine_.mesh(); }
  BoneInvariants checkInvariants() const override { return engine_.checkInvariants(); }

 private:
  ReferenceSubtractor engine_;
};

}  // namespace

std::unique_ptr<ContactBackend> makeThesisContactBackend() { return std::make_unique<ThesisContactBackend>(); }

CutBackendFactory referenceCutBackendFactory() {
  return [](const BoneState& bone) -> std::unique_ptr<CutBackend> {
    return std::make_unique<ReferenceCutBackend>(bone.toMesh());
  };
}

}  // namespace reamsim
