#include "reamsim/collision/FirstContact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "ContactEvents.h"
#include "QueryArguments.h"
#include "RationalMotion.h"
#include "SurfaceTouch.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim {

namespace {

using detail::Mat3;
using detail::MotionPlan;
using detail::PairContact;
using detail::SegmentMotion;

constexpr double kInf = std::numeric_limits<double>::infinity();

// An entry of the best-first search's queue.
struct ToiItem {
  enum Kind : std::uint8_t { Nodes, Triangles, BoneOnly, BoneTriangle };
  double slb;
  // Nodes: (bone node, reamer node); Triangles: (bone position, reamer slot); BoneOnly: bone node;
  // BoneTriangle: (bone position, -1 for its first window, else its bitset of offered reamer slots).
  // A bone triangle is named by its leaf position (TriangleBvh::leafPosition), where the tree keeps the
  // leaf's triangles side by side, not by its slot: read again later, it is still near its neighbours.
  std::int32_t b, r;
  Kind kind;
  // Min-heap on slb; on ties (many items start at 0 when the reamer starts near bone) bone triangles first,
  // then the deeper bone node (children follow their parent in the tree's array): depth-first among them.
  bool operator<(const ToiItem& o) const {
    if (slb != o.slb) return slb > o.slb;
    if (kind != o.kind) return kind < o.kind;
    return b < o.b;
  }
};

// Per-thread scratch: reamer node boxes rotated by R0 and reamer triangles rotated by R0, filled on first use;
// and the search's queue, stack and set of queued pairs, kept so that a query allocates nothing.
struct ToiScratch {
  std::vector<ToiItem> heap;
  std::vector<std::int32_t> rstack;
  // The reamer slots already offered to a bone triangle whose window was cut short (pairWithinWindow): one
  // bitset of `offeredWords` words per such triangle, appended as needed and dropped by the next search.
  // Only those triangles need one (a triangle's first window is the first time it meets the reamer), so
  // the common case touches no shared table at all.
  std::vector<std::uint64_t> offered;
  std::size_t offeredWords = 0;

  std::vector<std::uint32_t> nodeStamp, triStamp, planeStamp;
  std::vector<Vec3> a0lo, a0hi, rlo, rhi;
  std::vector<detail::AxisSweep> slab;
  std::vector<std::array<Vec3, 3>> q;
  std::vector<detail::AxisSweep> plane;
  std::vector<std::uint32_t> movingStamp;
  struct Moving {
    Vec3 lo, hi, rateLo, rateHi;  // the triangle's box at s = 0 and its face rates
  };
  std::vector<Moving> moving;
  std::uint32_t stamp = 0;
  void begin(std::size_t nodes, std::size_t tris) {
    if (nodeStamp.size() < nodes) {
      nodeStamp.resize(nodes, 0);
      a0lo.resize(nodes);
      a0hi.resize(nodes);
      rlo.resize(nodes);
      rhi.resize(nodes);
      slab.resize(nodes);
    }
    if (triStamp.size() < tris) {
      triStamp.resize(tris, 0);
      planeStamp.resize(tris, 0);
      movingStamp.resize(tris, 0);
      q.resize(tris);
      plane.resize(tris);
      moving.resize(tris);
    }
    if (++stamp == 0) {
      std::fill(nodeStamp.begin(), nodeStamp.end(), 0);
      std::fill(triStamp.begin(), triStamp.end(), 0);
      std::fill(planeStamp.begin(), planeStamp.end(), 0);
      std::fill(movingStamp.begin(), movingStamp.end(), 0);
      stamp = 1;
    }
  }
};
thread_local ToiScratch tlsScratch;

// Adds the counts of `b` to `a`.
void addWork(FirstContactResult::Work& a, const FirstContactResult::Work& b) {
  a.startTestNodes += b.startTestNodes;
  a.sweepPassNodes += b.sweepPassNodes;
  a.hullBounds += b.hullBounds;
  a.pairBounds += b.pairBounds;
}

// Touching at the start (time 0): `out` takes the touching pair; its counts (trianglePairs, work) stay.
void setTouchAtStart(FirstContactResult& out, const TriangleBvh& bone, const detail::TouchPair& touch) {
  const BvhTriangle& bt = bone.triangle(touch.boneSlot);
  out.hit = true;
  out.t = 0;
  out.point = touch.point;
  out.normal = normalized(cross(bt.b - bt.a, bt.c - bt.a));
  out.boneSlot = touch.boneSlot;
  out.reamerTriangle = touch.reamerTriangle;
  out.feature = ContactFeature::Initial;
}

// Best-first search for the earliest contact along one segment, on lower bounds of the time things can
// first meet; everything that cannot meet before the best contact so far is dropped, and triangle pairs
// that survive get the exact cubic events.
//
// A parametric reamer (its mesh inscribed in a convex ideal solid) is searched in two stages:
//  1. the bone tree alone against the moving ideal solid (a ball about the sphere's centre and five slabs,
//     initHull), each bone node bounded by its box and its slab, each bone triangle by its plane, box and
//     corners: only bone the cutting face can actually get to is visited, and no (bone node, reamer node)
//     pairs are formed;
//  2. each bone triangle that survives, in order of its bound s0: the reamer triangles it can meet within
//     [s0, best], found by a plain box descent of the reamer tree in the reamer's frame (pairWithinWindow),
//     then queued with their own pair bounds.
// Other reamers (a solid from a file) pair the two trees: the later of the time a bone box and a moving
// reamer box can meet (sweptBoxTime, exact for translations, the rotation's reach added) and the time the
// reamer node's slab along its own normal can reach the bone node (axisSweepTime: what keeps a tilted face
// patch thin).
class ToiSearch {
 public:
  // `untestedStart`: the pose at s = 0, when whether the reamer's body and back touch the bone there is
  // still open (see run()).
  ToiSearch(const TriangleBvh& bone, const ReamerModel& reamer, const SegmentMotion& m, FirstContactResult& out,
            const RigidTransform* untestedStart = nullptr)
      : bone_(bone), reamer_(reamer), untestedStart_(untestedStart), rtree_(reamer.solidBvh()),
        radius_(reamer.solidNodeRadius()), slabs_(reamer.solidNodeSlabs()),
        m_(m), out_(out),
        sc_(tlsScratch) {
    sc_.begin(rtree_.nodes().size(), rtree_.slotCapacity());
    sc_.offered.clear();
    sc_.offeredWords = (rtree_.slotCapacity() + 63) / 64;
    initHull(reamer);
  }

  // Whether a bone triangle may lie within the ideal solid's sweep at some s in [0, 1]: run()'s hull tests
  // with nothing found yet, asked as yes or no. No means nothing can meet the reamer on this segment, nor
  // touch it at s = 0 (the solid holds the whole reamer at every s), and the search need not run. Answered
  // depth first, nearer the solid's middle first, for kDepthFirstNodes nodes (a motion whose reamer starts
  // in or on the bone finds a triangle within them), then breadth first: proving "no" visits every node in
  // reach in any order, and taking them level by level fetches a level's nodes ahead of their tests, so
  // their cache misses overlap, where a depth-first or best-first search waits for each in turn; nor does
  // it queue anything or divide out a time (session 38: motions that meet nothing at 405k ~22 % faster in
  // all). Only for a parametric reamer (true otherwise).
  bool hullMayReachBone() {
    if (!hull_) return true;
    constexpr int kDepthFirstNodes = 24;
    Vec3 lo, hi;
    ballSweptBox(lo, hi);
    const double smallEnough = 0.5 * ball_.radius;
    const auto& bn = bone_.nodes();
    std::vector<std::int32_t>& nodes = sc_.rstack;  // a stack, then a queue; free until the search runs
    // Node b: a leaf in reach answers; an internal node in reach has its children queued (with
    // `nearerLast`, the one nearer the solid's middle last: the depth-first part takes it next).
    const auto take = [&](std::int32_t b, bool nearerLast) {
      ++out_.work.sweepPassNodes;
      const BvhNode& B = bn[b];
      if (!nodeInReach(B, b, lo, hi, smallEnough)) return false;
      if (B.isLeaf()) return leafInReach(B);
      bone_.prefetchNode(B.left, true);
      bone_.prefetchNode(B.right, true);
      bool leftLast = false;
      if (nearerLast) {
        const BvhNode& L = bn[B.left];
        const BvhNode& R = bn[B.right];
        leftLast = squaredNorm((L.lo + L.hi) * 0.5 - solidMiddle0_) <= squaredNorm((R.lo + R.hi) * 0.5 - solidMiddle0_);
      }
      nodes.push_back(leftLast ? B.right : B.left);
      nodes.push_back(leftLast ? B.left : B.right);
      return false;
    };
    nodes.assign(1, bone_.root());
    for (int visits = 0; !nodes.empty() && visits < kDepthFirstNodes; ++visits) {
      const std::int32_t b = nodes.back();
      nodes.pop_back();
      if (take(b, true)) return true;
    }
    for (std::size_t head = 0; head < nodes.size(); ++head)  // the stack's nodes are still untested
      if (take(nodes[head], false)) return true;
    return false;
  }

  bool run(double& sHit) {
    heap_.clear();
    if (hull_) {
      pushSubtreesInBallReach();
    } else {
      pushNodes(bone_.root(), rtree_.root());
    }
    const auto& bn = bone_.nodes();
    const auto& rn = rtree_.nodes();
    // The item to take next without the queue (see the bone nodes below), else the queue's first.
    bool haveNext = false;
    Item next{};
    while (haveNext || !heap_.empty()) {
      Item it;
      if (haveNext) {
        it = next;
        haveNext = false;
      } else {
        std::pop_heap(heap_.begin(), heap_.end());
        it = heap_.back();
        heap_.pop_back();
      }
      if (found_ ? it.slb >= best_ : it.slb > best_) break;  // every remaining item starts later
      if (it.kind == Item::Triangles) {
        exact(it.b, it.r, it.slb);
        continue;
      }
      // The body and back at s = 0: a bone triangle they touch is one the ideal solid reaches there, so its
      // leaf and the leaf's ancestors are bounded by 0 (boneItem rounds bounds within kStartSlack down to
      // 0), and bone nodes come before triangle pairs at equal bounds: every such leaf is taken before any
      // item with a later bound and before any pair is solved. Each is tested against them as it is taken,
      // until the first later item (session 23: rather than the whole bone at the first such leaf; ticks at
      // 400k ~6 % faster). A reamer starting clear of the bone tests nothing here.
      if (untestedStart_) {
        if (it.slb > kStartSlack) {
          untestedStart_ = nullptr;
        } else if (it.kind == Item::BoneOnly && bn[it.b].isLeaf()) {
          detail::TouchPair touch;
          if (!restAtStart_) restAtStart_.emplace(bone_, reamer_, *untestedStart_);
          if (restAtStart_->touchesSubtree(it.b, &touch)) {
            setTouchAtStart(out_, bone_, touch);
            sHit = 0;
            return true;
          }
        }
      }
      if (it.kind == Item::BoneTriangle) {
        pairWithinWindow(static_cast<std::uint32_t>(it.b), it.slb, it.r);
        continue;
      }
      if (it.kind == Item::BoneOnly) {
        const BvhNode& B = bn[it.b];
        if (B.isLeaf()) {
          const std::uint32_t first = TriangleBvh::leafPosition(B);
          const BvhTriangle* bt = bone_.leafTriangles(B);
          for (int i = 0; i < B.count; ++i) {
            const double t = std::max(it.slb, triangleHullTime(bt[i]));
            if (promising(t)) push({t, static_cast<std::int32_t>(first + i), -1, Item::BoneTriangle});
          }
        } else {
          // The child that comes first is taken next without the queue when nothing queued comes before
          // it, as a pop would: a descent then pays no push and pop per level (session 23: ~5 % at 400k).
          Item l = boneItem(B.left), r = boneItem(B.right);
          if (l < r) std::swap(l, r);
          for (const Item* c : {&l, &r}) {
            if (!promising(c->slb)) continue;
            if (!haveNext && (heap_.empty() || !(*c < heap_.front()))) {
              next = *c;
              haveNext = true;
            } else {
              push(*c);
            }
          }
        }
        continue;
      }
      const BvhNode& B = bn[it.b];
      const BvhNode& R = rn[it.r];
      if (B.isLeaf() && R.isLeaf()) {
        leafPair(B, R);
        continue;
      }
      const double sb = (B.hi.x - B.lo.x) + (B.hi.y - B.lo.y) + (B.hi.z - B.lo.z);
      const double sr = (R.hi.x - R.lo.x) + (R.hi.y - R.lo.y) + (R.hi.z - R.lo.z);
      if (R.isLeaf() || (!B.isLeaf() && sb >= sr)) {
        pushNodes(B.left, it.r);
        pushNodes(B.right, it.r);
      } else {
        pushNodes(it.b, R.left);
        pushNodes(it.b, R.right);
      }
    }
    sHit = best_;
    return found_;
  }

 private:
  // Reamer node box rotated by R0 and placed at the start tip, with the rates of its faces (cached).
  void startBox(std::int32_t r) {
    if (sc_.nodeStamp[r] == sc_.stamp) return;
    const BvhNode& R = rtree_.nodes()[r];
    Vec3 qlo, qhi;
    detail::mapBox(m_.R0, Vec3{}, R.lo, R.hi, qlo, qhi);
    sc_.a0lo[r] = qlo + m_.tip0;
    sc_.a0hi[r] = qhi + m_.tip0;
    detail::boxRates(m_, qlo, qhi, radius_[r], sc_.rlo[r], sc_.rhi[r]);
    const ReamerModel::NodeSlab& sl = slabs_[r];
    sc_.slab[r] = detail::axisSweep(m_, sl.axis, sl.lo, sl.hi, R.lo, R.hi, radius_[r]);
    sc_.nodeStamp[r] = sc_.stamp;
  }

  double bound(std::int32_t b, std::int32_t r) {
    startBox(r);
    const BvhNode& B = bone_.nodes()[b];
    const double t = detail::sweptBoxTime(sc_.a0lo[r], sc_.a0hi[r], sc_.rlo[r], sc_.rhi[r], B.lo, B.hi, best_);
    if (!promising(t)) return t;
    const detail::AxisSweep& slab = sc_.slab[r];
    double plo, phi;
    regionRange(B.lo, B.hi, bone_.slab(b), slab.axis, plo, phi);
    const double ts = std::max(t, detail::axisSweepTime(slab, plo, phi, best_));
    if (!promising(ts) || !B.isLeaf()) return ts;
    // A bone leaf: its triangles' own extent along the axis, much thinner than its box's when the patch
    // is tilted against the bone's axes (the near-contact case, where most pairs are leaves).
    const BvhTriangle* tris = bone_.leafTriangles(B);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < B.count; ++i) {
      const BvhTriangle& bt = tris[i];
      for (const Vec3* v : {&bt.a, &bt.b, &bt.c}) {
        const double d = dot(slab.axis, *v);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    }
    const double pad = 1e-12 * (std::abs(lo) + std::abs(hi)) + 1e-300;
    return std::max(ts, detail::axisSweepTime(slab, lo - pad, hi + pad, best_));
  }

  const std::array<Vec3, 3>& rotatedTriangle(std::uint32_t slot) {
    if (sc_.triStamp[slot] != sc_.stamp) {
      const BvhTriangle& t = rtree_.triangle(slot);
      sc_.q[slot] = {m_.R0 * t.a, m_.R0 * t.b, m_.R0 * t.c};
      sc_.triStamp[slot] = sc_.stamp;
    }
    return sc_.q[slot];
  }

  using Item = ToiItem;
  bool promising(double t) const { return found_ ? t < best_ : t <= best_; }
  void push(const Item& it) {
    heap_.push_back(it);
    std::push_heap(heap_.begin(), heap_.end());
  }
  void pushNodes(std::int32_t b, std::int32_t r) {
    const double t = bound(b, r);
    if (promising(t)) push({t, b, r, Item::Nodes});
  }

  // The convex ideal solid a parametric reamer's mesh lies in, moving: a ball about the sphere's centre (or
  // the flat reamer's middle) holding all of it, the slab of its length along the axis and four slabs
  // across the axis (an octagon about the cylinder). A bone node that one of them (hullTime uses the ball,
  // the axial slab and the across slab facing the node) shows cannot be reached before the best contact so
  // far is dropped whole, without pairing it with the reamer's nodes: the search visits the
  // bone only where the reamer can get to it, and a bone triangle meets the reamer tree only once it
  // comes first (pairWithinWindow).
  void initHull(const ReamerModel& reamer) {
    const ReamerModel::IdealSolid& id = reamer.idealSolid();
    if (!id.valid) return;
    hull_ = true;
    const double pad = 1e-8 * (1 + id.radius + id.sphereRadius + std::abs(id.zBack));
    const double zTop = id.flat ? 0.0 : id.sphereCentreZ + id.sphereRadius;
    const Vec3 centre{0, 0, id.flat ? 0.5 * id.zBack : id.sphereCentreZ};
    const double reach = id.flat ? std::hypot(id.radius, 0.5 * id.zBack)
                                 : std::max(id.sphereRadius, std::hypot(id.radius, id.zBack - id.sphereCentreZ));
    ball_ = detail::ballSweep(m_, centre, reach + pad);
    solidMiddle0_ = m_.tip0 + m_.R0 * Vec3{0, 0, 0.5 * (id.zBack + zTop)};
    const BvhNode& root = rtree_.nodes()[rtree_.root()];
    const double r = reamer.radius();
    hullSlabs_[0] = detail::axisSweep(m_, Vec3{0, 0, 1}, id.zBack - pad, zTop + pad, root.lo, root.hi, r);
    const double h = std::sqrt(0.5);
    const Vec3 across[4] = {{1, 0, 0}, {0, 1, 0}, {h, h, 0}, {h, -h, 0}};
    for (int i = 0; i < 4; ++i)
      hullSlabs_[1 + i] = detail::axisSweep(m_, across[i], -id.radius - pad, id.radius + pad, root.lo, root.hi, r);
  }

  // Bone node b is the region of its box and its slab (BvhSlab). The ball against the slab first: for a
  // patch of bone facing the cutting face that alone is nearly the exact time; then along the line from the
  // ball to the node, and the reamer-frame slabs: its length along the axis and, of the four across it,
  // the one that faces the node. Every one of these is a lower bound, so any subset is; this subset is the
  // one that pays: most nodes a search bounds it then opens, so every test is paid in full on them, and the
  // ball against the box and the three other across slabs cut off few of the rest (session 23, the bench's
  // 1000 motions at 405k in one process, alternating: median 24.7 -> 22.1 us against all eight tests).
  double hullTime(std::int32_t b) const {
    const BvhNode& B = bone_.nodes()[b];
    const BvhSlab& slab = bone_.slab(b);
    double t = detail::axisSweepTime(detail::ballAlong(ball_, slab.axis), slab.lo, slab.hi, best_);
    if (!promising(t)) return t;
    const BoxSlabRegion region(B.lo, B.hi, slab);
    // Along the line from the ball's start to the node: a patch the ball approaches off its own normal (the
    // cap beside a curved bone) is thin along it too (session 18: motions meeting the bone 1.8x faster at 405k).
    Vec3 u;
    double ulo, uhi;
    if (region.rangeFrom(ball_.c0, u, ulo, uhi)) {
      t = std::max(t, detail::axisSweepTime(detail::ballAlong(ball_, u), ulo, uhi, best_));
      if (!promising(t)) return t;
    }
    t = std::max(t, slabTime(hullSlabs_[0], region));
    if (!promising(t)) return t;
    return std::max(t, slabTime(hullSlabs_[acrossFacing(region.c)], region));
  }

  double slabTime(const detail::AxisSweep& sweep, const BoxSlabRegion& region) const {
    double lo, hi;
    region.range(sweep.axis, lo, hi);
    return detail::axisSweepTime(sweep, lo, hi, best_);
  }

  // The across-axis slab (hullSlabs_[1..4]) whose axis is most nearly along the line from the ball's start
  // to `p`: for bone beside the reamer, the octagon's side that faces it.
  std::size_t acrossFacing(const Vec3& p) const {
    const Vec3 lateral = p - ball_.c0;
    std::size_t best = 1;
    double bestAlong = -1;
    for (std::size_t j = 1; j < hullSlabs_.size(); ++j) {
      const double along = std::abs(dot(lateral, hullSlabs_[j].axis));
      if (along > bestAlong) {
        bestAlong = along;
        best = j;
      }
    }
    return best;
  }

  // The search's first items: the bone subtrees whose box meets the box the moving ball sweeps, found by box
  // tests alone down to nodes no wider than half the ball's radius, each then queued with its hull bound.
  // Above that size the hull bounds of a node and of its children barely differ and both children are
  // nearly always opened, so the hull bounds a search from the root paid there pruned little more than a
  // box test does, at several times its cost (session 34, no-contact motions at 405k: ~150 -> ~120 hull bounds and ~67 box tests each, median
  // -15 to -16 % over alternating runs in one process).
  void pushSubtreesInBallReach() {
    Vec3 lo, hi;
    ballSweptBox(lo, hi);
    const double smallEnough = 0.5 * ball_.radius;
    const auto& bn = bone_.nodes();
    std::vector<std::int32_t>& stack = sc_.rstack;  // free until the search's first window
    stack.assign(1, bone_.root());
    while (!stack.empty()) {
      const std::int32_t b = stack.back();
      stack.pop_back();
      const BvhNode& B = bn[b];
      if (!boxesOverlap(B.lo, B.hi, lo, hi)) continue;
      if (B.isLeaf() || std::max({B.hi.x - B.lo.x, B.hi.y - B.lo.y, B.hi.z - B.lo.z}) <= smallEnough) {
        const Item it = boneItem(b);
        if (promising(it.slb)) push(it);
        continue;
      }
      stack.push_back(B.left);
      stack.push_back(B.right);
    }
  }

  // The box the moving ball sweeps over the segment.
  void ballSweptBox(Vec3& lo, Vec3& hi) const {
    for (int i = 0; i < 3; ++i) {
      const double a = ball_.c0[i], b = ball_.c0[i] + ball_.d[i];
      const double pad = 1e-9 * (1 + std::abs(a) + std::abs(b) + ball_.radius);
      lo[i] = std::min(a, b) - ball_.radius - pad;
      hi[i] = std::max(a, b) + ball_.radius + pad;
    }
  }

  // For hullMayReachBone: node B (index b) against the ball's swept box [lo, hi], and once it is no wider
  // than smallEnough (as in pushSubtreesInBallReach) against the hull too.
  bool nodeInReach(const BvhNode& B, std::int32_t b, const Vec3& lo, const Vec3& hi, double smallEnough) const {
    if (!boxesOverlap(B.lo, B.hi, lo, hi)) return false;
    const bool small = std::max({B.hi.x - B.lo.x, B.hi.y - B.lo.y, B.hi.z - B.lo.z}) <= smallEnough;
    return !(small || B.isLeaf()) || hullReachesNode(b);
  }

  bool leafInReach(const BvhNode& leaf) const {
    const BvhTriangle* bt = bone_.leafTriangles(leaf);
    for (int i = 0; i < leaf.count; ++i)
      if (promising(triangleHullTime(bt[i]))) return true;
    return false;
  }

  // hullTime(b) <= 1 asked as yes or no, by the same tests: each sweep's span over the whole segment
  // against the node's range (an interval moving linearly meets a fixed one at some s in [0, 1] exactly when
  // the span it covers does), so no time is divided out.
  bool hullReachesNode(std::int32_t b) const {
    const BvhNode& B = bone_.nodes()[b];
    const BvhSlab& slab = bone_.slab(b);
    if (!spanMeets(detail::ballAlong(ball_, slab.axis), slab.lo, slab.hi)) return false;
    const BoxSlabRegion region(B.lo, B.hi, slab);
    Vec3 u;
    double lo, hi;
    if (region.rangeFrom(ball_.c0, u, lo, hi) && !spanMeets(detail::ballAlong(ball_, u), lo, hi)) return false;
    region.range(hullSlabs_[0].axis, lo, hi);
    if (!spanMeets(hullSlabs_[0], lo, hi)) return false;
    const std::size_t j = acrossFacing(region.c);
    region.range(hullSlabs_[j].axis, lo, hi);
    return spanMeets(hullSlabs_[j], lo, hi);
  }

  // Whether the sweep's span over s in [0, 1] meets [blo, bhi] (padded for the rounding of its sums).
  static bool spanMeets(const detail::AxisSweep& a, double blo, double bhi) {
    const double lo = std::min(a.lo0, a.lo0 + a.rateLo), hi = std::max(a.hi0, a.hi0 + a.rateHi);
    const double pad = 1e-12 * (std::abs(a.lo0) + std::abs(a.hi0) + std::abs(a.rateLo) + std::abs(a.rateHi)) + 1e-300;
    return lo - pad <= bhi && blo <= hi + pad;
  }

  // Bone node b with its bound, its children's nodes and slabs fetched ahead when it is worth opening: when
  // it is taken, they are read behind bound tests that return early, so their cache misses would not
  // overlap (no-contact motions at 400k ~25% faster over alternating runs).
  Item boneItem(std::int32_t b) const {
    ++out_.work.hullBounds;
    Item it{hullTime(b), b, -1, Item::BoneOnly};
    // While the start is untested, a bound that may be a contact at s = 0 rounded up is taken as 0 (still a
    // lower bound), so that the leaf comes before every triangle pair (see run()).
    if (untestedStart_ && it.slb <= kStartSlack) it.slb = 0;
    const BvhNode& B = bone_.nodes()[b];
    if (promising(it.slb) && !B.isLeaf()) {
      bone_.prefetchNode(B.left, true);
      bone_.prefetchNode(B.right, true);
    }
    return it;
  }

  // Triangle pairs of two leaves, queued by their own bounds so the exact events run earliest-first.
  void leafPair(const BvhNode& B, const BvhNode& R) {
    const std::uint32_t first = TriangleBvh::leafPosition(B);
    const std::uint32_t* rs = rtree_.leafSlots(R);
    for (int j = 0; j < R.count; ++j)
      for (int i = 0; i < B.count; ++i) pushTrianglePair(first + std::uint32_t(i), rs[j], 0);
  }

  // The reamer triangle at s = 0 (its box) and how fast its box's faces can move (cached per query).
  const ToiScratch::Moving& moving(std::uint32_t slot) {
    ToiScratch::Moving& mv = sc_.moving[slot];
    if (sc_.movingStamp[slot] == sc_.stamp) return mv;
    const auto& qa = rotatedTriangle(slot);
    TriangleBvh::paddedBox({m_.tip0 + qa[0], m_.tip0 + qa[1], m_.tip0 + qa[2]}, mv.lo, mv.hi);
    Vec3 qlo, qhi;
    TriangleBvh::paddedBox({qa[0], qa[1], qa[2]}, qlo, qhi);
    detail::boxRates(m_, qlo, qhi, std::max({norm(qa[0]), norm(qa[1]), norm(qa[2])}), mv.rateLo, mv.rateHi);
    sc_.movingStamp[slot] = sc_.stamp;
    return mv;
  }

  // One (bone triangle, reamer triangle) pair, queued for the exact events unless a bound shows it cannot
  // meet before the best contact so far; `floor` is a lower bound already known for the pair.
  void pushTrianglePair(std::uint32_t bonePos, std::uint32_t reamerSlot, double floor) {
    Vec3 blo, bhi;
    TriangleBvh::paddedBox(bone_.triangleAt(bonePos), blo, bhi);
    pushTrianglePair(bonePos, blo, bhi, reamerSlot, floor);
  }
  // The same with the bone triangle's padded box already at hand.
  void pushTrianglePair(std::uint32_t bonePos, const Vec3& blo, const Vec3& bhi, std::uint32_t reamerSlot, double floor) {
    ++out_.work.pairBounds;
    const BvhTriangle& bt = bone_.triangleAt(bonePos);
    const ToiScratch::Moving& mv = moving(reamerSlot);
    double t = std::max(floor, detail::sweptBoxTime(mv.lo, mv.hi, mv.rateLo, mv.rateHi, blo, bhi, best_));
    if (!promising(t)) return;
    // The reamer triangle's own plane, moving: the bone triangle's extent along its normal.
    const detail::AxisSweep& plane = planeSweep(reamerSlot);
    double hlo, hhi;
    vertexRange(bt, plane.axis, hlo, hhi);
    t = std::max(t, detail::axisSweepTime(plane, hlo, hhi, best_));
    if (!promising(t)) return;
    // Plane bound: each reamer vertex needs at least h / (its fastest approach) to reach the bone
    // triangle's plane, and the triangle cannot touch before its first vertex or edge does.
    const auto& qa = rotatedTriangle(reamerSlot);
    const Vec3 n = cross(bt.b - bt.a, bt.c - bt.a);
    const double h[3] = {dot(n, m_.tip0 + qa[0] - bt.a), dot(n, m_.tip0 + qa[1] - bt.a), dot(n, m_.tip0 + qa[2] - bt.a)};
    if ((h[0] > 0 && h[1] > 0 && h[2] > 0) || (h[0] < 0 && h[1] < 0 && h[2] < 0)) {
      const double side = h[0] > 0 ? 1.0 : -1.0;
      double tp = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        const double rate = detail::approachRate(m_, n, qa[k], side);
        if (rate > 0) tp = std::min(tp, side * h[k] / rate * (1 - 1e-12));
      }
      t = std::max(t, tp);
      if (!promising(t)) return;
    }
    push({t, static_cast<std::int32_t>(bonePos), static_cast<std::int32_t>(reamerSlot), Item::Triangles});
  }

  // A long window would gather much of the reamer: the window is cut to what moves the triangle by about
  // kWindowReachMm, and the rest of it is queued again (as the same bone triangle from s1 on), so it is
  // only looked at if no contact is found first. A reamer triangle offered once is not offered again: its
  // pair's bounds and exact events cover the rest of the segment. `offered` is the triangle's bitset of
  // reamer slots offered so far, -1 in its first window (nothing offered yet).
  void pairWithinWindow(std::uint32_t bonePos, double s0, std::int32_t offered) {
    constexpr double kWindowReachMm = 0.5;
    const BvhTriangle& bt = bone_.triangleAt(bonePos);
    const Mat3 R = m_.rotationAt(s0), Rt = R.transposed();
    const Vec3 tip = m_.tipAt(s0);
    const Vec3 p[3] = {Rt * (bt.a - tip), Rt * (bt.b - tip), Rt * (bt.c - tip)};
    Vec3 boneLo, boneHi;
    TriangleBvh::paddedBox(bt, boneLo, boneHi);
    const double speed = norm(m_.delta) + 2 * m_.tau * (std::max({norm(p[0]), norm(p[1]), norm(p[2])}) + norm(m_.delta));
    double s1 = best_;
    if (speed * (best_ - s0) > kWindowReachMm) {
      s1 = s0 + kWindowReachMm / speed;
      if (offered < 0) {
        offered = static_cast<std::int32_t>(sc_.offered.size() / sc_.offeredWords);
        sc_.offered.resize(sc_.offered.size() + sc_.offeredWords, 0);
      }
      push({s1, static_cast<std::int32_t>(bonePos), offered, Item::BoneTriangle});
    }
    std::uint64_t* bits = offered < 0 ? nullptr : sc_.offered.data() + std::size_t(offered) * sc_.offeredWords;
    const double ds = s1 - s0;
    const double turn = m_.tau == 0 ? 0.0 : m_.phi(s1) - m_.phi(s0);
    const double travel = norm(m_.delta) * ds;
    const double far = std::max({norm(p[0]), norm(p[1]), norm(p[2])}) + travel;
    const double grow = (travel + turn * far) * (1 + 1e-9) + 1e-9 * (1 + far);
    Vec3 lo, hi;
    TriangleBvh::paddedBox({p[0], p[1], p[2]}, lo, hi);
    lo -= Vec3{grow, grow, grow};
    hi += Vec3{grow, grow, grow};
    const auto& rn = rtree_.nodes();
    rstack_.clear();
    rstack_.push_back(rtree_.root());
    while (!rstack_.empty()) {
      const BvhNode& N = rn[rstack_.back()];
      rstack_.pop_back();
      if (!boxesOverlap(N.lo, N.hi, lo, hi)) continue;
      if (N.isLeaf()) {
        const std::uint32_t* rs = rtree_.leafSlots(N);
        for (int j = 0; j < N.count; ++j) {
          if (bits) {
            std::uint64_t& word = bits[rs[j] >> 6];
            const std::uint64_t bit = std::uint64_t(1) << (rs[j] & 63);
            if (word & bit) continue;
            word |= bit;
          }
          pushTrianglePair(bonePos, boneLo, boneHi, rs[j], s0);
        }
      } else {
        rstack_.push_back(N.left);
        rstack_.push_back(N.right);
      }
    }
  }

  // The ideal solid against one bone triangle: the ball against its plane and its box, the slabs against
  // its corners.
  double triangleHullTime(const BvhTriangle& bt) const {
    const Vec3 n = normalized(cross(bt.b - bt.a, bt.c - bt.a));
    double lo, hi, t = 0;
    if (isFinite(n)) {
      vertexRange(bt, n, lo, hi);
      t = detail::axisSweepTime(detail::ballAlong(ball_, n), lo, hi, best_);
      if (!promising(t)) return t;
    }
    Vec3 blo, bhi;
    TriangleBvh::paddedBox(bt, blo, bhi);
    t = std::max(t, detail::ballSweepTime(ball_, blo, bhi, best_));
    for (const detail::AxisSweep& sweep : hullSlabs_) {
      if (!promising(t)) return t;
      vertexRange(bt, sweep.axis, lo, hi);
      t = std::max(t, detail::axisSweepTime(sweep, lo, hi, best_));
    }
    return t;
  }

  // The corners' range along a unit axis, padded for rounding.
  static void vertexRange(const BvhTriangle& bt, const Vec3& axis, double& lo, double& hi) {
    const double d0 = dot(axis, bt.a), d1 = dot(axis, bt.b), d2 = dot(axis, bt.c);
    lo = std::min({d0, d1, d2});
    hi = std::max({d0, d1, d2});
    const double pad = 1e-12 * (std::abs(lo) + std::abs(hi)) + 1e-300;
    lo -= pad;
    hi += pad;
  }

  // The sweep of a reamer triangle along its own normal (cached: a triangle meets many bone leaves).
  const detail::AxisSweep& planeSweep(std::uint32_t slot) {
    if (sc_.planeStamp[slot] == sc_.stamp) return sc_.plane[slot];
    const BvhTriangle& lt = rtree_.triangle(slot);
    Vec3 n = cross(lt.b - lt.a, lt.c - lt.a);
    const double len = norm(n);
    n = len > 0 ? n / len : Vec3{0, 0, 1};
    const double d0 = dot(n, lt.a), d1 = dot(n, lt.b), d2 = dot(n, lt.c);
    const Vec3 plo{std::min({lt.a.x, lt.b.x, lt.c.x}), std::min({lt.a.y, lt.b.y, lt.c.y}),
                   std::min({lt.a.z, lt.b.z, lt.c.z})};
    const Vec3 phi{std::max({lt.a.x, lt.b.x, lt.c.x}), std::max({lt.a.y, lt.b.y, lt.c.y}),
                   std::max({lt.a.z, lt.b.z, lt.c.z})};
    const double reach = std::max({norm(lt.a), norm(lt.b), norm(lt.c)});  // rotation keeps lengths
    sc_.plane[slot] = detail::axisSweep(m_, n, std::min({d0, d1, d2}), std::max({d0, d1, d2}), plo, phi, reach);
    sc_.planeStamp[slot] = sc_.stamp;
    return sc_.plane[slot];
  }

  void exact(std::int32_t bonePos, std::int32_t reamerSlot, double slb) {
    const BvhTriangle& lt = rtree_.triangle(static_cast<std::uint32_t>(reamerSlot));
    const auto& qa = rotatedTriangle(static_cast<std::uint32_t>(reamerSlot));
    const Vec3 p[3] = {lt.a, lt.b, lt.c};
    const Vec3 q[3] = {qa[0], qa[1], qa[2]};
    ++out_.trianglePairs;
    const PairContact c =
        detail::pairFirstContact(m_, p, q, bone_.triangleAt(static_cast<std::uint32_t>(bonePos)), best_, false, slb);
    if (!c.hit || (found_ && c.s >= best_)) return;
    found_ = true;
    best_ = c.s;
    out_.point = c.point;
    out_.normal = c.normal;
    out_.feature = c.feature;
    out_.boneSlot = bone_.slotAt(static_cast<std::uint32_t>(bonePos));
    out_.reamerTriangle = static_cast<std::uint32_t>(reamerSlot);
  }

  // Bounds this close to 0 may be a contact at s = 0 rounded up.
  static constexpr double kStartSlack = 1e-12;

  const TriangleBvh& bone_;
  const ReamerModel& reamer_;
  const RigidTransform* untestedStart_;
  std::optional<detail::RestTouchSearch> restAtStart_;  // made at the first leaf tested at s = 0
  const TriangleBvh& rtree_;
  const std::vector<double>& radius_;
  const std::vector<ReamerModel::NodeSlab>& slabs_;
  const SegmentMotion m_;
  FirstContactResult& out_;
  ToiScratch& sc_;
  bool found_ = false;
  double best_ = 1;
  bool hull_ = false;
  detail::BallSweep ball_;
  Vec3 solidMiddle0_;  // the ideal solid's middle on its axis at s = 0 (hullMayReachBone looks there first)
  std::array<detail::AxisSweep, 5> hullSlabs_;
  std::vector<Item>& heap_ = sc_.heap;
  std::vector<std::int32_t>& rstack_ = sc_.rstack;
};

}  // namespace

FirstContactResult queryFirstContact(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& from,
                                     const RigidTransform& to) {
  detail::requireRigidPose(from, "queryFirstContact", "start pose");
  detail::requireRigidPose(to, "queryFirstContact", "end pose");
  FirstContactResult out;
  if (bone.empty()) return out;
  // Touching at the start: time 0 (the search below then knows the surfaces start apart). The cutting face
  // first, through its thin region; a parametric reamer's body and back only if its sweep meets bone the
  // ideal solid reaches at the start (ToiSearch::run), which a reamer starting clear of the bone does not.
  const bool sweepTestsRest = reamer.idealSolid().valid;
  detail::TouchPair touch;
  if (sweepTestsRest ? detail::faceTouchesBone(bone, reamer, from, &touch, &out.work.startTestNodes)
                     : detail::surfacesTouch(bone, reamer, from, &touch)) {
    setTouchAtStart(out, bone, touch);
    return out;
  }
  const MotionPlan plan = MotionPlan::between(from, to);
  for (int i = 0; i < plan.segments; ++i) {
    double s;
    FirstContactResult seg;
    ToiSearch search(bone, reamer, plan.segment(i), seg, i == 0 && sweepTestsRest ? &from : nullptr);
    // A segment whose sweep of the ideal solid reaches no bone triangle is skipped without the search; most
    // motions that meet nothing end here. (After the start tests: this pass would find bone at once under a
    // reamer touching at the start, and that motion would pay for it on top, session 38.)
    if (!search.hullMayReachBone()) {
      addWork(out.work, seg.work);
      continue;
    }
    if (search.run(s)) {
      seg.hit = true;
      seg.t = std::min(1.0, (i + s) / plan.segments);
      seg.trianglePairs += out.trianglePairs;
      addWork(seg.work, out.work);
      return seg;
    }
    out.trianglePairs += seg.trianglePairs;
    addWork(out.work, seg.work);
  }
  return out;
}

FirstContactResult queryFirstContact(const TriangleBvh& bone, const ReamerModel& reamer, const Pose& from,
                                     const Pose& to) {
  return queryFirstContact(bone, reamer, toTransform(from), toTransform(to));
}

RigidTransform interpolateMotion(const RigidTransform& from, const RigidTransform& to, double t) {
  return MotionPlan::between(from, to).at(t);
}

}  // namespace reamsim
