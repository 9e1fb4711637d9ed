#pragma once
// Internal: box tests between a bone BVH node (bone/world frame) and a reamer BVH node (reamer-local frame)
// under a pose. Each node's box is mapped into the other frame (conservatively, PoseFrame.h); a pair is
// apart if it is apart in either frame, and its distance is at least the larger of the two box distances.
// Reamer boxes mapped to world are cached per query (the reamer tree is small); bone boxes are mapped on
// the fly (the bone tree can have a million nodes).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "PoseFrame.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim::detail {

class PairBoxes {
 public:
  PairBoxes(const TriangleBvh& bone, const TriangleBvh& reamer, const PoseFrame& frame)
      : bone_(bone), reamer_(reamer), frame_(frame), c_(cache()) {
    c_.begin(reamer.nodes().size(), reamer.slotCapacity());
    stamp_ = c_.stamp;
  }

  // Another PairBoxes made on this thread since (the cache is per thread) invalidates what this one
  // cached: call before using an object that outlived others.
  void resume() {
    if (c_.stamp == stamp_) return;
    c_.begin(reamer_.nodes().size(), reamer_.slotCapacity());
    stamp_ = c_.stamp;
  }

  // Reamer node box in world coordinates (conservative).
  void reamerWorld(std::int32_t r, const Vec3*& lo, const Vec3*& hi) {
    if (c_.boxStamp[r] != c_.stamp) {
      frame_.localBoxToWorld(reamer_.nodes()[r].lo, reamer_.nodes()[r].hi, c_.lo[r], c_.hi[r]);
      c_.boxStamp[r] = c_.stamp;
    }
    lo = &c_.lo[r];
    hi = &c_.hi[r];
  }
  // Reamer triangle in world coordinates with its padded world box.
  const BvhTriangle& reamerTriangle(std::uint32_t slot, const Vec3*& lo, const Vec3*& hi) {
    if (c_.triStamp[slot] != c_.stamp) {
      const BvhTriangle& t = reamer_.triangle(slot);
      c_.tri[slot] = {frame_.toWorld(t.a), frame_.toWorld(t.b), frame_.toWorld(t.c)};
      TriangleBvh::paddedBox(c_.tri[slot], c_.tlo[slot], c_.thi[slot]);
      c_.triStamp[slot] = c_.stamp;
    }
    lo = &c_.tlo[slot];
    hi = &c_.thi[slot];
    return c_.tri[slot];
  }

  bool mayOverlap(std::int32_t b, std::int32_t r) {
    const BvhNode& B = bone_.nodes()[b];
    const Vec3 *wlo, *whi;
    reamerWorld(r, wlo, whi);
    if (!boxesOverlap(B.lo, B.hi, *wlo, *whi)) return false;
    Vec3 llo, lhi;
    frame_.worldBoxToLocal(B.lo, B.hi, llo, lhi);
    return boxesOverlap(llo, lhi, reamer_.nodes()[r].lo, reamer_.nodes()[r].hi);
  }

  double lowerBound2(std::int32_t b, std::int32_t r) {
    const BvhNode& B = bone_.nodes()[b];
    const Vec3 *wlo, *whi;
    reamerWorld(r, wlo, whi);
    const double dw = boxSquaredDistance(B.lo, B.hi, *wlo, *whi);
    Vec3 llo, lhi;
    frame_.worldBoxToLocal(B.lo, B.hi, llo, lhi);
    return std::max(dw, boxSquaredDistance(llo, lhi, reamer_.nodes()[r].lo, reamer_.nodes()[r].hi));
  }

 private:
  struct Cache {
    std::vector<std::uint32_t> boxStamp, triStamp;
    std::vector<Vec3> lo, hi, tlo, thi;
    std::vector<BvhTriangle> tri;
    std::uint32_t stamp = 0;
    void begin(std::size_t nodes, std::size_t tris) {
      if (boxStamp.size() < nodes) { boxStamp.resize(nodes, 0); lo.resize(nodes); hi.resize(nodes); }
      if (triStamp.size() < tris) { triStamp.resize(tris, 0); tri.resize(tris); tlo.resize(tris); thi.resize(tris); }
      if (++stamp == 0) {
        std::fill(boxStamp.begin(), boxStamp.end(), 0);
        std::fill(triStamp.begin(), triStamp.end(), 0);
        stamp = 1;
      }
    }
  };
  static Cache& cache() {
    thread_local Cache c;
    return c;
  }

  const TriangleBvh& bone_;
  const TriangleBvh& reamer_;
  const PoseFrame& frame_;
  Cache& c_;
  std::uint32_t stamp_ = 0;
};

}  // namespace reamsim::detail
