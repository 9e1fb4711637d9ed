#pragma once
// Internal: the branch-and-bound search behind query 2 (minimum distance between the reamer's cutting face
// and the bone), shared by queryFaceDistance (one pose) and FaceDistanceTracker (a sequence of poses).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "FaceRegionBounds.h"
#include "PoseFrame.h"
#include "reamsim/collision/DistanceQuery.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim::detail {

// The search over the bone tree. Bone nodes and triangles are bounded against the face's world box and the
// thin region holding the face (FaceRegionBounds); a bone triangle that survives is measured against the
// face's own BVH in the reamer frame, where its boxes are tight, with a plane bound before each exact test.
class FaceDistanceSearch {
 public:
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  FaceDistanceSearch(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, double max2,
                     DistanceResult& out)
      : bone_(bone), reamer_(reamer), face_(reamer.faceBvh()), frame_(pose), region_(reamer, frame_), best2_(max2),
        out_(out) {
    frame_.localBoxToWorld(face_.nodes()[face_.root()].lo, face_.nodes()[face_.root()].hi, faceLo_, faceHi_);
    heap_.reserve(256);
    frontier_.reserve(256);
    fstack_.reserve(64);
  }

  // Phase 1: a face triangle touching or crossing a bone triangle (distance 0). Only bone geometry meeting
  // the face region can cross the face, which keeps this to the bone along the region's boundary. What it
  // does not open (bounds above 0) and the triangles it tested are kept: they are where phase 2 starts.
  bool findCrossing(bool keepFrontier) {
    crossing_ = true;
    keysArePositions_ = true;
    keepFrontier_ = keepFrontier;
    frontier_.clear();
    heap_.clear();
    push(bone_.root(), rootBound(), false);
    search([&](double lb) { return lb > 0; });
    crossing_ = keepFrontier_ = false;
    return found_ && best2_ == 0;
  }

  // Phase 2: the nearest pair (no pair crosses), best-first from phase 1's frontier: the nodes bounded
  // there need not be bounded again (on a reamer hovering over the bone, about a fifth of them).
  void nearest() {
    heap_.clear();
    for (const Item& it : frontier_)
      if (!skipNode(it.lb)) heap_.push_back(it);
    std::make_heap(heap_.begin(), heap_.end());
    search([&](double lb) { return skipNode(lb); });
  }

  // Phase 2 that also collects every bone triangle whose lower bound lies below (d + margin)^2, d the
  // distance found: no triangle left out is nearer the face than d + margin (FaceDistanceTracker's proof).
  // Slower than nearest(): the search goes on past d.
  void nearestCollecting(double marginMm, std::vector<std::uint32_t>& collected) {
    margin_ = marginMm;
    collecting_ = true;
    popped_.clear();
    updateReach();
    nearest();
    collecting_ = false;
    // The reach only fell as the search went: what was popped beyond its final value is left out.
    collected.clear();
    for (const Item& it : popped_)
      if (it.lb < reach2_) collected.push_back(bone_.slotAt(static_cast<std::uint32_t>(it.b)));
  }
  double reachMm() const { return std::sqrt(reach2_); }  // after nearestCollecting: d + margin

  // The given bone triangles only (no tree), nearest first: FaceDistanceTracker's query between searches.
  // The caller has proved that none of them crosses the face.
  void nearestAmong(const std::vector<std::uint32_t>& slots) {
    keysArePositions_ = false;
    heap_.clear();  // used as a plain list here, sorted by bound
    for (std::uint32_t s : slots) heap_.push_back({triangleBound(bone_.triangle(s)), static_cast<std::int32_t>(s), true});
    std::sort(heap_.begin(), heap_.end(), [](const Item& a, const Item& b) { return a.lb < b.lb; });
    for (const Item& it : heap_) {
      if (skip(it.lb)) break;
      measure(static_cast<std::uint32_t>(it.b), bone_.triangle(static_cast<std::uint32_t>(it.b)));
    }
  }

  // Does bone triangle `slot` cross face triangle `faceSlot` (face BVH slot)? If so the result is that
  // pair at distance 0. FaceDistanceTracker's first try while the face stays in the bone.
  bool crossesAt(std::uint32_t slot, std::uint32_t faceSlot) {
    keysArePositions_ = false;
    ++out_.trianglePairs;
    return recordIfCrossing(slot, faceSlot, face_.triangle(faceSlot), localTriangle(bone_.triangle(slot)));
  }

  // Writes the distance found (if any) into the result; the pair is already there.
  void finish() {
    if (!found_) return;
    out_.found = true;
    out_.distanceMm = std::sqrt(best2_);
  }

  bool found() const { return found_; }
  double best2() const { return best2_; }
  std::uint32_t bestFaceSlot() const { return bestFaceSlot_; }  // the face BVH slot of the pair found

 private:
  // A bone node's lower bound: its box against the face's world box, and its region bound (box and slab,
  // FaceRegionBounds::nodes): with boxes alone a reamer seated in the glenoid opened ~1,000 nodes a distance
  // query, and the crossing search (also the start test of first contact and overlap) had twice the tail on
  // a hand-held path (docs/COLLISION.md, session 18).
  double nodeBound(const BvhNode& N, double region) const {
    return std::max(boxSquaredDistance(N.lo, N.hi, faceLo_, faceHi_), region);
  }
  double triangleBound(const BvhTriangle& bt) const {
    Vec3 blo, bhi;
    TriangleBvh::paddedBox(bt, blo, bhi);
    return std::max(boxSquaredDistance(blo, bhi, faceLo_, faceHi_), region_.triangle(bt));
  }
  double rootBound() const {
    const BvhNode& B = bone_.nodes()[bone_.root()];
    return nodeBound(B, region_.node(B.lo, B.hi, bone_.slab(bone_.root())));
  }
  // Both children of an opened node, their region bounds computed together.
  void childBounds(const BvhNode& B, double& lbL, double& lbR) const {
    const BvhNode& L = bone_.nodes()[B.left];
    const BvhNode& R = bone_.nodes()[B.right];
    double region[2];
    region_.nodes(L.lo, L.hi, bone_.slab(B.left), R.lo, R.hi, bone_.slab(B.right), region);
    lbL = nodeBound(L, region[0]);
    lbR = nodeBound(R, region[1]);
  }

  // Best-first over the bone tree (a min-heap on the lower bound), so the first triangles measured are the
  // likely closest and the best distance drops early; everything whose bound reaches it is then dropped.
  // The crossing search only needs some crossing, not the nearest: plain depth-first order (no heap).
  void push(std::int32_t b, double lb, bool triangle) {
    const Item item{lb, b, triangle};
    if (skipNode(lb)) {
      if (keepFrontier_) frontier_.push_back(item);
      return;
    }
    if (!triangle) {  // its children are read when it is taken: fetch them now (see prefetchNode)
      const BvhNode& N = bone_.nodes()[b];
      if (!N.isLeaf()) {
        bone_.prefetchNode(N.left, true);
        bone_.prefetchNode(N.right, true);
      }
    }
    heap_.push_back(item);
    if (!crossing_) std::push_heap(heap_.begin(), heap_.end());
  }

  template <class Prune>
  void search(Prune&& prune) {
    const auto& bn = bone_.nodes();
    while (!heap_.empty()) {
      if (!crossing_) std::pop_heap(heap_.begin(), heap_.end());
      const Item it = heap_.back();
      heap_.pop_back();
      if (prune(it.lb)) {
        if (!crossing_) return;  // min-heap: everything left is at least as far
        continue;
      }
      if (it.triangle) {
        if (keepFrontier_) frontier_.push_back(it);  // tested for a crossing only: phase 2 measures it
        if (collecting_) {
          popped_.push_back(it);
          if (skip(it.lb)) continue;  // within reach, not nearer than the best: collected, not measured
        }
        measure(static_cast<std::uint32_t>(it.b), bone_.triangleAt(static_cast<std::uint32_t>(it.b)));
        if (found_ && best2_ == 0) return;
        continue;
      }
      const BvhNode& B = bn[it.b];
      ++out_.nodesOpened;
      if (B.isLeaf()) {
        // Queued by leaf position, not slot: the leaf's triangles lie side by side (TriangleBvh::leafTriangles).
        const std::uint32_t first = TriangleBvh::leafPosition(B);
        const BvhTriangle* bt = bone_.leafTriangles(B);
        for (int i = 0; i < B.count; ++i) push(static_cast<std::int32_t>(first + i), triangleBound(bt[i]), true);
        continue;
      }
      double lbL, lbR;
      childBounds(B, lbL, lbR);
      if (crossing_ && region_.nearerToSurface(bn[B.left], bn[B.right])) {
        // Depth-first: the child whose centre lies nearer the face region's surface goes on top.
        push(B.right, lbR, false);
        push(B.left, lbL, false);
      } else {
        push(B.left, lbL, false);
        push(B.right, lbR, false);
      }
    }
  }

  // A pair that could beat the best by less than kRelativeTolerance is not evaluated: ties (a fan of face
  // triangles around the closest vertex) would otherwise all be measured for nothing.
  bool skip(double lb) const { return crossing_ ? lb > 0 : (lb > best2_ || (found_ && lb >= best2_ * kTie)); }
  // A node or triangle the tree search drops: as skip(), or, when collecting (phase 2 only), beyond reach.
  bool skipNode(double lb) const { return collecting_ ? lb >= reach2_ : skip(lb); }
  void updateReach() {
    if (!collecting_) return;
    const double r = std::sqrt(best2_) + margin_;
    reach2_ = r * r;
  }

  // Squared lower bound on the distance from triangle p (unit normal n, centroid pc) to triangle q, given q's
  // distance `rise` from p's plane: along n and a unit v in p's plane, |x - y|^2 >= (n.(x-y))^2 + (v.(x-y))^2,
  // the first term at least rise^2 and the second the triangles' separation along v, v pointing from p
  // towards q. Where the bone runs parallel to the face, the face triangles beside the nearest one pass the
  // box bound (their boxes are thick where the cap is tilted) and the plane bound (their planes are nearly
  // p's); this drops them before the exact distance.
  static double acrossBound(const Vec3& n, double rise, const BvhTriangle& p, const Vec3& pc, const BvhTriangle& q) {
    const Vec3 g = (q.a + q.b + q.c) * (1.0 / 3) - pc;
    Vec3 v = g - n * dot(n, g);
    const double len2 = squaredNorm(v);
    if (!(len2 > 0)) return 0;
    v = v / std::sqrt(len2);
    const double gap = std::min({dot(v, q.a), dot(v, q.b), dot(v, q.c)}) - std::max({dot(v, p.a), dot(v, p.b), dot(v, p.c)});
    return gap > 0 ? sq(rise) + sq(gap) : 0;
  }

  BvhTriangle localTriangle(const BvhTriangle& bt) const {
    return {frame_.toLocal(bt.a), frame_.toLocal(bt.b), frame_.toLocal(bt.c)};
  }

  // Bone triangle l (reamer frame) against face triangle rt: if they touch or cross, the pair is recorded at
  // distance 0.
  bool recordIfCrossing(std::uint32_t key, std::uint32_t faceSlot, const BvhTriangle& rt, const BvhTriangle& l) {
    if (!trianglesIntersect(rt.a, rt.b, rt.c, l.a, l.b, l.c)) return false;
    record(key, faceSlot, closestTriangleTriangle(rt.a, rt.b, rt.c, l.a, l.b, l.c), true);
    return true;
  }

  // One bone triangle against the face BVH (reamer frame).
  void measure(std::uint32_t key, const BvhTriangle& bt) {
    const BvhTriangle l = localTriangle(bt);
    Vec3 llo, lhi;
    TriangleBvh::paddedBox(l, llo, lhi);
    const Vec3 bn = normalized(cross(l.b - l.a, l.c - l.a));
    const double bo = dot(bn, l.a);
    const Vec3 lc = (l.a + l.b + l.c) * (1.0 / 3);
    const auto& fn = face_.nodes();
    const auto& normals = reamer_.faceUnitNormals();
    const auto& faceBoxes = reamer_.faceBoxes();
    fstack_.clear();
    fstack_.push_back(face_.root());
    while (!fstack_.empty()) {
      const BvhNode& R = fn[fstack_.back()];
      fstack_.pop_back();
      if (!R.isLeaf()) {
        const double dl = boxSquaredDistance(llo, lhi, fn[R.left].lo, fn[R.left].hi);
        const double dr = boxSquaredDistance(llo, lhi, fn[R.right].lo, fn[R.right].hi);
        const bool leftFirst = dl <= dr;
        if (!skip(leftFirst ? dr : dl)) fstack_.push_back(leftFirst ? R.right : R.left);
        if (!skip(leftFirst ? dl : dr)) fstack_.push_back(leftFirst ? R.left : R.right);
        continue;
      }
      const std::uint32_t* rs = face_.leafSlots(R);
      for (int j = 0; j < R.count; ++j) {
        const ReamerModel::Box& rb = faceBoxes[rs[j]];
        if (skip(boxSquaredDistance(llo, lhi, rb.lo, rb.hi))) continue;
        const BvhTriangle& rt = face_.triangle(rs[j]);
        // Plane bounds: one triangle wholly on one side of the other's plane (whichever is flatter there
        // gives the tight bound, so both are tried; the bone triangle's plane, with the bound across it, drops
        // most pairs, so it goes first).
        const double rise = planeGap(dot(bn, rt.a) - bo, dot(bn, rt.b) - bo, dot(bn, rt.c) - bo);
        if (skip(sq(rise))) continue;
        if (skip(acrossBound(bn, rise, l, lc, rt))) continue;
        const Vec3& n = normals[rs[j]];
        const double o = dot(n, rt.a);
        if (skip(sq(planeGap(dot(n, l.a) - o, dot(n, l.b) - o, dot(n, l.c) - o)))) continue;
        ++out_.trianglePairs;
        if (crossing_) {
          if (recordIfCrossing(key, rs[j], rt, l)) return;
          continue;
        }
        if (record(key, rs[j], closestDisjointTriangles(rt.a, rt.b, rt.c, l.a, l.b, l.c), false) && best2_ == 0) return;
      }
    }
  }

  // Keeps the pair (reamer frame) if it beats the best; a crossing pair is at distance 0.
  bool record(std::uint32_t key, std::uint32_t faceSlot, ClosestPair cp, bool crossing) {
    if (crossing) cp.squaredDistance = 0;
    if (!(cp.squaredDistance < best2_ || (!found_ && cp.squaredDistance <= best2_))) return false;
    best2_ = cp.squaredDistance;
    found_ = true;
    updateReach();
    out_.onReamer = frame_.toWorld(cp.onA);
    out_.onBone = frame_.toWorld(cp.onB);
    out_.boneSlot = keysArePositions_ ? bone_.slotAt(key) : key;
    out_.reamerTriangle = reamer_.faceTriangles()[faceSlot];
    bestFaceSlot_ = faceSlot;
    return true;
  }

  // Distance from a plane of three signed heights when all lie on one side, else 0.
  static double planeGap(double s0, double s1, double s2) {
    if (s0 > 0 && s1 > 0 && s2 > 0) return std::min({s0, s1, s2});
    if (s0 < 0 && s1 < 0 && s2 < 0) return -std::max({s0, s1, s2});
    return 0;
  }
  static double sq(double x) { return x * x; }
  static constexpr double kTie = 1 - 2 * kDistanceRelativeTolerance;  // on squared distances

  struct Item {
    double lb;
    // Node, or bone triangle when `triangle`: its leaf position in the tree searches, its slot in
    // nearestAmong (keysArePositions_).
    std::int32_t b;
    bool triangle;
    bool operator<(const Item& o) const { return lb > o.lb; }  // min-heap
  };
  const TriangleBvh& bone_;
  const ReamerModel& reamer_;
  const TriangleBvh& face_;
  PoseFrame frame_;
  FaceRegionBounds region_;
  Vec3 faceLo_, faceHi_;
  double best2_;
  bool found_ = false, crossing_ = false, keepFrontier_ = false;
  bool keysArePositions_ = true;  // what a bone triangle's key is: a leaf position (tree searches) or a slot
  DistanceResult& out_;
  std::vector<Item> heap_, frontier_;  // frontier_: phase 1's unopened nodes and tested triangles
  std::vector<std::int32_t> fstack_;
  // Collecting (nearestCollecting): the triangles popped with their bounds, and the reach (d + margin)^2.
  bool collecting_ = false;
  std::vector<Item> popped_;
  double margin_ = 0, reach2_ = kInf;
  std::uint32_t bestFaceSlot_ = 0;
};

}  // namespace reamsim::detail
