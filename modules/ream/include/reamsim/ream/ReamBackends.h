#pragma once
// The two engines the reaming loop uses, as small interfaces so the GUI can load them from plugins.
// The defaults are the Foundation's reference paths: thesis ray casts and CGAL exact corefinement.
#include <functional>
#include <memory>
#include <vector>

#include "reamsim/collision/ThesisContact.h"
#include "reamsim/csg/ReferenceSubtractor.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

class ContactBackend {
 public:
  virtual ~ContactBackend() = default;
  virtual ThesisContactResult query(const TriangleMesh& bone, const Bounds& boneBounds, const TriangleMesh& tool,
                                    const std::vector<Vec3>& probes, const Vec3& feedAxis, double stepMm) = 0;
};

// A cutting engine holding one bone (it may keep its own exact representation between cuts).
class CutBackend {
 public:
  virtual ~CutBackend() = default;
  virtual ReferenceCut subtract(const TriangleMesh& toolInBoneCoords) = 0;
  virtual TriangleMesh mesh() const = 0;
  virtual BoneInvariants checkInvariants() const = 0;
};
// Builds an engine for a bone; throws std::invalid_argument for a bone it cannot cut.
using CutBackendFactory = std::function<std::unique_ptr<CutBackend>(const TriangleMesh& bone)>;

std::unique_ptr<ContactBackend> makeThesisContactBackend();
CutBackendFactory referenceCutBackendFactory();

}  // namespace reamsim
