// CGAL translation unit (predicates only): the clean-up of the cut band (see CutBandCleanup.h).
#include "CutBandCleanup.h"

#include "ExactRationalFastPaths.h"  // before any CGAL kernel: see there
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "PackedTriangleGrid.h"
#include "PlaneSide.h"
#include "SplitOverTwoThreads.h"
#include "TrianglePair.h"

namespace reamsim::csg {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tri = std::array<std::uint32_t, 3>;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr double kNormalAgreement = 0.7;  // cos of the largest turn a replaced face may take (~45 degrees)
constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kMaxOperations = 20000;  // per cut: a bound on the work, far above what cuts need

struct LocalFace {
  Tri v;
  std::uint32_t slot;  // the bone slot, kNone for faces made here
  bool alive = true;
  bool frozen = false;  // a defect face: never changed, and no new face may come near it
  bool exactVertex = false;  // has a vertex known exactly (only rounded here): no new face may come near it
};

// What the clean-up knows about a vertex, gathered the first time it is needed.
struct VertexStar {
  std::vector<int> faces;  // local faces about the vertex (dead ones pruned lazily)
  bool gathered = false;   // the bone's faces about it have been added
  bool movable = false;    // double coordinates, no defect face about it, all its faces found, not collapsed
};

// Local face ids by bone slot: a flat array kept between cuts (one per thread), valid where its stamp is
// the current cut's, so that a cut neither clears nor hashes (the outcome test looks up every face its
// boxes meet).
class SlotIndex {
 public:
  void begin() {
    if (++epoch_ == 0) {
      std::fill(stamp_.begin(), stamp_.end(), 0);
      epoch_ = 1;
    }
  }
  int find(std::uint32_t slot) const { return slot < stamp_.size() && stamp_[slot] == epoch_ ? id_[slot] : -1; }
  // The id of `slot`, or `id` given to it now; `added` says which.
  int insert(std::uint32_t slot, int id, bool& added) {
    if (slot >= stamp_.size()) {
      stamp_.resize(std::size_t(slot) + 1 + slot / 2, 0);
      id_.resize(stamp_.size());
    }
    added = stamp_[slot] != epoch_;
    if (added) {
      stamp_[slot] = epoch_;
      id_[slot] = id;
    }
    return id_[slot];
  }

 private:
  std::vector<std::uint32_t> stamp_;
  std::vector<int> id_;
  std::uint32_t epoch_ = 0;
};
thread_local SlotIndex tlsSlotIndex;

class Cleanup {
 public:
  // checkEachOperation: every operation is tested for self-intersections before it is taken; otherwise the
  // operations are taken on the local tests alone and finalSurfaceIsIntersectionFree() tests the result.
  Cleanup(const BoneState& state, TriangleGrid& grid, const std::function<bool(std::uint32_t)>& frozenVertex,
          const std::function<bool(std::uint32_t)>& frozenFace, const BandCleanup& options, bool checkEachOperation)
      : checkEach_(checkEachOperation), state_(state), boneGrid_(grid), frozenVertex_(frozenVertex), frozenFace_(frozenFace), opt_(options),
        minAngle_(options.minAngleDeg * kPi / 180), cosMinAngle_(std::cos(minAngle_)) {
    localOfSlot_.begin();
  }

  CleanupPlan run(const std::vector<std::uint32_t>& seeds) {
    CleanupPlan plan;
    // Most cuts leave nothing to clean: decide that before anything is gathered.
    bool anyBad = false;
    for (std::uint32_t s : seeds) {
      const Triangle& t = state_.triangle(s);
      if ((anyBad = bad({t[0], t[1], t[2]}))) break;
    }
    if (!anyBad) return plan;
    // The bone's faces and vertices are looked at only where an operation is tried (through the engine's
    // grid). Testing each operation also needs the faces made so far by box: a grid of their own, kept only
    // then (the outcome test files the faces that are left once).
    if (checkEach_) {
      Box3 domain = Box3::empty();
      for (std::uint32_t s : seeds)
        for (std::uint32_t v : state_.triangle(s)) domain.add(at(v));
      made_.init(domain.bounds(), seeds.size(), 2.0);
    }
    // Sized for the faces and vertices a cut's band looks at, so that the maps are not rehashed as they grow.
    star_.reserve(2 * seeds.size());
    faces_.reserve(4 * seeds.size());
    std::vector<int> work, made;
    for (std::uint32_t s : seeds) work.push_back(localFace(s));
    std::size_t ops = 0;
    while (!work.empty() && ops < kMaxOperations) {
      const int f = work.back();
      work.pop_back();
      if (!faces_[f].alive || !bad(f)) continue;
      made.clear();
      if (tryCollapseShortest(f, made)) {
        ++plan.collapses;
      } else if (tryFlipLongest(f, made)) {
        ++plan.flips;
      } else {
        continue;
      }
      ++ops;
      work.insert(work.end(), made.begin(), made.end());
    }
    for (const LocalFace& lf : faces_) {
      if (lf.slot != kNone && !lf.alive) plan.delta.removedTriangles.push_back(lf.slot);
      if (lf.slot == kNone && lf.alive) plan.delta.addedTriangles.push_back({lf.v[0], lf.v[1], lf.v[2]});
    }
    // In a canonical order, so that the same surface gives the same slots (and volume sums) however the
    // faces were found.
    std::sort(plan.delta.removedTriangles.begin(), plan.delta.removedTriangles.end());
    std::sort(plan.delta.addedTriangles.begin(), plan.delta.addedTriangles.end());
    return plan;
  }

  // Whether the surface after run() is free of self-intersections and keeps away from frozen faces, as
  // the per-operation test would have ensured: a pair of faces that the clean-up did not make was a pair
  // of the surface before it (free of self-intersections), so only the faces made here are tested, against
  // every face their boxes meet. Slivers nearly never make the tests fail, so testing the outcome once
  // costs a fraction of testing every operation (which made and then replaced most of these faces).
  bool finalSurfaceIsIntersectionFree() const {
    std::vector<int> made;
    for (std::size_t id = 0; id < faces_.size(); ++id)
      if (faces_[id].slot == kNone && faces_[id].alive) made.push_back(int(id));
    // The faces left, filed once (most faces made were replaced again within the plan: keeping a grid of
    // them up to date as they came and went cost a tenth of the clean-up).
    std::vector<Box3> boxes(made.size());
    for (std::size_t i = 0; i < made.size(); ++i) boxes[i] = boxOf(faces_[made[i]].v);
    PackedTriangleGrid madeGrid;
    madeGrid.build(std::move(boxes), 2.0);
    // Read-only work over the faces made, so it is split over two threads: at the glenoid of the 405k
    // scapula 1.7 ms, run when the rounding check (the cut's other thread) has usually finished.
    std::atomic<bool> failed{false};
    splitOverTwoThreads(made.size(), kParallelOutcomeFaces, [&](std::size_t begin, std::size_t end, int) {
      std::vector<std::uint32_t> hits;
      for (std::size_t i = begin; i < end && !failed.load(std::memory_order_relaxed); ++i)
        if (!madeFaceIsClear(i, made, madeGrid, hits)) failed.store(true, std::memory_order_relaxed);
    });
    return !failed.load();
  }

 private:
  // Faces made per thread from which the outcome test is split over two threads: by the time it runs the
  // rounding check (the cut's other thread) has usually finished, so from 64 (300 before session 43; a
  // bundled glenoid cut makes ~165).
  static constexpr std::size_t kParallelOutcomeFaces = 64;

  // Whether the made face made[i] meets no face it must not: an alive bone face, another face left made
  // (one later in `made`: each pair once), or any frozen face. Const (the grids' shared queries keep no
  // stamps).
  bool madeFaceIsClear(std::size_t i, const std::vector<int>& made, const PackedTriangleGrid& madeGrid,
                       std::vector<std::uint32_t>& hits) const {
    const LocalFace& m = faces_[made[i]];
    const Box3& b = madeGrid.box(std::uint32_t(i));
    boneGrid_.queryShared(b, hits);
    for (std::uint32_t s : hits) {
      const int local = localOfSlot_.find(s);
      if (local >= 0) {
        const LocalFace& lf = faces_[local];
        if (!lf.alive) continue;
        if (lf.frozen || lf.exactVertex || meets(m.v, lf.v)) return false;
        continue;
      }
      const Triangle& t = state_.triangle(s);
      if (frozenFace_(s) || frozenVertex_(t[0]) || frozenVertex_(t[1]) || frozenVertex_(t[2])) return false;
      if (meets(m.v, {t[0], t[1], t[2]})) return false;
    }
    madeGrid.query(b, hits);
    for (std::uint32_t g : hits)
      if (g > i && meets(m.v, faces_[made[g]].v)) return false;
    return true;
  }

  // The local face of a bone slot, made on first use.
  int localFace(std::uint32_t slot) {
    bool added = false;
    const int id = localOfSlot_.insert(slot, static_cast<int>(faces_.size()), added);
    if (added) {
      const Triangle& t = state_.triangle(slot);
      faces_.push_back({{t[0], t[1], t[2]}, slot, true, frozenFace_(slot),
                        frozenVertex_(t[0]) || frozenVertex_(t[1]) || frozenVertex_(t[2])});
    }
    return id;
  }

  // The faces about v: the bone's (each face with v has a grid box holding v's position), gathered on first
  // use, and those made here. A vertex moves only when all the bone's faces about it were found and none
  // of them is a defect.
  VertexStar& star(std::uint32_t v) {
    VertexStar& st = star_[v];
    if (st.gathered) return st;
    st.gathered = true;
    if (frozenVertex_(v)) return st;  // known exactly: never moved, so its faces are never looked at
    // Every face with corner v has a box that holds v's position, so it is filed in that position's cell.
    std::uint32_t found = 0;
    bool frozen = false;
    for (std::uint32_t s : boneGrid_.slotsInCellOf(at(v))) {
      const Triangle& t = state_.triangle(s);
      if (t[0] != v && t[1] != v && t[2] != v) continue;
      ++found;
      const int id = localFace(s);
      frozen |= faces_[id].frozen;
      if (faces_[id].alive) st.faces.push_back(id);
    }
    st.movable = !frozen && found == state_.vertexUseCount(v);
    return st;
  }
  bool movable(std::uint32_t v) { return star(v).movable; }

  const Vec3& at(std::uint32_t v) const { return state_.vertex(v); }
  K::Point_3 kp(std::uint32_t v) const {
    const Vec3& p = at(v);
    return {p.x, p.y, p.z};
  }
  Box3 boxOf(const Tri& t) const {
    Box3 b = Box3::empty();
    for (std::uint32_t v : t) b.add(at(v));
    return b;
  }
  double angleOf(const Tri& t) const { return smallestAngle(at(t[0]), at(t[1]), at(t[2])); }
  Vec3 normalOf(const Tri& t) const { return cross(at(t[1]) - at(t[0]), at(t[2]) - at(t[0])); }

  // The two faces meet other than along the vertices and edges they share (exact predicates).
  bool meets(const Tri& a, const Tri& b) const {
    return trianglesIntersectBeyondShared<K>(a, b, [&](std::uint32_t v) { return kp(v); });
  }

  bool bad(int f) const { return bad(faces_[f].v); }
  // An edge shorter than minEdgeMm or an angle under minAngleDeg (its cosine above the bound's: no atan2).
  bool bad(const Tri& t) const {
    const Vec3 e[3] = {at(t[1]) - at(t[0]), at(t[2]) - at(t[1]), at(t[0]) - at(t[2])};
    const double l[3] = {norm(e[0]), norm(e[1]), norm(e[2])};
    for (int i = 0; i < 3; ++i)
      if (l[i] < opt_.minEdgeMm) return true;
    for (int i = 0; i < 3; ++i)  // the angle at vertex i, between −e[i−1] and e[i]
      if (-dot(e[(i + 2) % 3], e[i]) > cosMinAngle_ * l[(i + 2) % 3] * l[i]) return true;
    return false;
  }

  const std::vector<int>& aliveStar(std::uint32_t v) {
    std::vector<int>& s = star(v).faces;
    s.erase(std::remove_if(s.begin(), s.end(), [&](int f) { return !faces_[f].alive; }), s.end());
    return s;
  }
  // The faces about v close up (each neighbour on exactly two of them): not on an open border of the bone
  // and not a pinched vertex. Moving such a vertex, or changing the faces about it, keeps the surface
  // manifold; a border vertex could be joined to another border.
  bool closedFan(std::uint32_t v) {
    const std::vector<int>& star = aliveStar(v);
    ring_.clear();
    for (int f : star)
      for (std::uint32_t w : faces_[f].v)
        if (w != v) ring_.push_back(w);
    std::sort(ring_.begin(), ring_.end());
    if (ring_.size() != 2 * star.size()) return false;
    for (std::size_t i = 0; i < ring_.size(); i += 2)
      if (ring_[i] != ring_[i + 1] || (i + 2 < ring_.size() && ring_[i + 2] == ring_[i])) return false;
    return true;
  }
  // Whether some live face of u other than `except` has the same three vertices as t.
  bool duplicates(const Tri& t, std::uint32_t u, const std::vector<int>& except) {
    Tri a = t;
    std::sort(a.begin(), a.end());
    for (int f : aliveStar(u)) {
      if (std::find(except.begin(), except.end(), f) != except.end()) continue;
      Tri b = faces_[f].v;
      std::sort(b.begin(), b.end());
      if (a == b) return true;
    }
    return false;
  }
  // The vertices next to v, sorted, each once, into `out`.
  void neighbours(const std::vector<int>& star, std::uint32_t v, std::vector<std::uint32_t>& out) const {
    out.clear();
    for (int f : star)
      for (std::uint32_t w : faces_[f].v)
        if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
  // A replacement face: not degenerate, turned by less than ~45 degrees from `was`.
  bool acceptableFace(const Tri& t, const Vec3& was) const {
    // The turn first, in doubles; then non-degenerate, proven in doubles where it can be, else exactly.
    const PlaneSide plane(at(t[0]), at(t[1]), at(t[2]));
    const Vec3& n = plane.normal();  // normalOf(t)
    if (!(dot(n, was) > kNormalAgreement * norm(n) * norm(was))) return false;
    return plane.proper() || !CGAL::collinear(kp(t[0]), kp(t[1]), kp(t[2]));
  }
  // Distance of point p from the plane of t.
  double planeDistance(const Vec3& p, const Tri& t) const {
    const Vec3 n = normalOf(t);
    return std::abs(dot(n, p - at(t[0]))) / norm(n);
  }

  // The new faces meet no face that stays (other than along shared vertices and edges), nor each other:
  // the bone's faces whose grid boxes meet a new face's box, and the faces made here. One grid query for
  // all the new faces together; each face found is tested against those new faces whose boxes it meets.
  bool intersectionFree(const std::vector<Tri>& made, const std::vector<int>& dying) {
    auto isDying = [&](int f) { return std::find(dying.begin(), dying.end(), f) != dying.end(); };
    madeBoxes_.clear();
    Box3 all = Box3::empty();
    for (std::size_t i = 0; i < made.size(); ++i) {
      for (std::size_t j = i + 1; j < made.size(); ++j)
        if (meets(made[i], made[j])) return false;
      madeBoxes_.push_back(boxOf(made[i]));
      for (int a = 0; a < 3; ++a) {
        all.lo[a] = std::min(all.lo[a], madeBoxes_.back().lo[a]);
        all.hi[a] = std::max(all.hi[a], madeBoxes_.back().hi[a]);
      }
    }
    auto meetsAnyBox = [&](const Box3& b) {
      for (const Box3& m : madeBoxes_)
        if (b.overlaps(m)) return true;
      return false;
    };
    boneGrid_.query(all, hits_);
    for (std::uint32_t s : hits_) {
      const Box3& b = boneGrid_.box(s);
      if (!meetsAnyBox(b)) continue;
      const int f = localFace(s);
      const LocalFace& lf = faces_[f];
      if (!lf.alive || isDying(f)) continue;
      // A face with an exact (non-double) vertex is only known here rounded, and a defect face may be
      // degenerate (the intersection tests require proper triangles): stay away from both.
      if (lf.frozen || lf.exactVertex) return false;
      for (std::size_t i = 0; i < made.size(); ++i)
        if (b.overlaps(madeBoxes_[i]) && meets(made[i], lf.v)) return false;
    }
    made_.query(all, hits_);
    for (std::uint32_t g : hits_) {
      if (!faces_[g].alive || isDying(int(g))) continue;
      const Box3& b = made_.box(g);
      for (std::size_t i = 0; i < made.size(); ++i)
        if (b.overlaps(madeBoxes_[i]) && meets(made[i], faces_[g].v)) return false;
    }
    return true;
  }

  void replace(const std::vector<int>& dying, const std::vector<Tri>& made, std::vector<int>& ids) {
    for (int f : dying) {
      faces_[f].alive = false;
      if (checkEach_) made_.remove(static_cast<std::uint32_t>(f));  // a no-op for the bone's faces
    }
    for (const Tri& t : made) {
      const int id = static_cast<int>(faces_.size());
      faces_.push_back({t, kNone, true});
      if (checkEach_) made_.insert(static_cast<std::uint32_t>(id), boxOf(t));
      for (std::uint32_t v : t) star_[v].faces.push_back(id);  // before or after its bone faces are gathered
      ids.push_back(id);
    }
  }

  bool tryCollapseShortest(int f, std::vector<int>& made) {
    const Tri t = faces_[f].v;
    int e = 0;
    double shortest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
      const double l = norm(at(t[(i + 1) % 3]) - at(t[i]));
      if (l < shortest) {
        shortest = l;
        e = i;
      }
    }
    const std::uint32_t a = t[e], b = t[(e + 1) % 3];
    return collapse(a, b, made) || collapse(b, a, made);
  }

  // Half-edge collapse: v moves onto u. The geometric tests come first, cheapest first: most candidates fail
  // them (three in four at the 405k glenoid), and they need only v's faces.
  bool collapse(std::uint32_t v, std::uint32_t u, std::vector<int>& made) {
    if (!movable(v) || !movable(u)) return false;
    // A reference into the star map (its nodes do not move); nothing below changes v's faces before
    // replace() retires them.
    const std::vector<int>& sv = aliveStar(v);
    if (sv.size() < 3) return false;
    std::uint32_t opposite[2];
    int opposites = 0;
    for (int f : sv) {
      const Tri& t = faces_[f].v;
      if (std::find(t.begin(), t.end(), u) == t.end()) continue;
      for (std::uint32_t w : t)
        if (w != u && w != v) {
          if (opposites == 2) return false;
          opposite[opposites++] = w;
        }
    }
    if (opposites != 2 || opposite[0] == opposite[1]) return false;

    std::vector<Tri>& newFaces = newFaces_;
    newFaces.clear();
    for (int f : sv) {
      Tri t = faces_[f].v;
      if (std::find(t.begin(), t.end(), u) != t.end()) continue;
      const Vec3 was = normalOf(t);
      for (std::uint32_t& w : t) {
        if (w == v) w = u;
        if (frozenVertex_(w)) return false;  // only known rounded here
      }
      // The deviation first: it is cheap and rejects most candidates (three in four at the glenoid).
      if (planeDistance(at(v), t) > opt_.maxDeviationMm || !acceptableFace(t, was)) return false;
      newFaces.push_back(t);
    }
    // The smallest angle may not drop below the old one or the threshold, whichever is lower; the old one
    // is needed only when the new one is under the threshold.
    double newQuality = std::numeric_limits<double>::infinity();
    for (const Tri& t : newFaces) newQuality = std::min(newQuality, angleOf(t));
    if (newQuality < minAngle_) {
      double oldQuality = std::numeric_limits<double>::infinity();
      for (int f : sv) oldQuality = std::min(oldQuality, angleOf(faces_[f].v));
      if (newQuality < oldQuality) return false;
    }

    if (!closedFan(v) || !closedFan(u)) return false;
    const std::vector<int>& su = aliveStar(u);
    if (su.size() < 3) return false;
    // Link condition: u and v share exactly the two neighbours across the edge.
    std::vector<std::uint32_t>&nu = nu_, &nv = nv_;
    neighbours(su, u, nu);
    neighbours(sv, v, nv);
    std::size_t common = 0;
    for (std::size_t i = 0, j = 0; i < nu.size() && j < nv.size();) {
      if (nu[i] < nv[j]) ++i;
      else if (nv[j] < nu[i]) ++j;
      else ++common, ++i, ++j;
    }
    if (common != 2) return false;
    // A closed piece as small as a tetrahedron would fold onto one of u's faces.
    for (const Tri& t : newFaces)
      if (duplicates(t, u, sv)) return false;
    if (checkEach_ && !intersectionFree(newFaces, sv)) return false;
    replace(sv, newFaces, made);
    star_[v].movable = false;  // gone
    return true;
  }

  // Flips the edge opposite the face's largest angle when the two faces across it are nearly coplanar.
  bool tryFlipLongest(int f, std::vector<int>& made) {
    const Tri t = faces_[f].v;
    int e = 0;
    double longest = -1;
    for (int i = 0; i < 3; ++i) {
      const double l = norm(at(t[(i + 1) % 3]) - at(t[i]));
      if (l > longest) {
        longest = l;
        e = i;
      }
    }
    const std::uint32_t a = t[e], b = t[(e + 1) % 3], c = t[(e + 2) % 3];
    // All tests must pass; the cheap geometric ones run first (nineteen in twenty tries fail).
    if (!movable(a)) return false;
    int g = -1;
    std::uint32_t d = kNone;
    for (int h : aliveStar(a)) {
      if (h == f) continue;
      const Tri& s = faces_[h].v;
      for (int i = 0; i < 3; ++i)
        if (s[i] == b && s[(i + 1) % 3] == a) {
          if (g >= 0) return false;  // not a manifold edge
          g = h;
          d = s[(i + 2) % 3];
        }
    }
    // A neighbour across a-b running the same way would break orientation; such faces are flagged as
    // defects (frozen vertices are not movable), so only the consistent twin b->a is looked for.
    if (g < 0 || d == c) return false;
    const Tri tf = faces_[f].v, tg = faces_[g].v;
    if (planeDistance(at(d), tf) > opt_.maxDeviationMm || planeDistance(at(c), tg) > opt_.maxDeviationMm)
      return false;
    if (!movable(b) || !movable(c) || !movable(d)) return false;
    if (!closedFan(a) || !closedFan(b)) return false;
    std::vector<std::uint32_t>& nc = nu_;
    neighbours(aliveStar(c), c, nc);
    if (std::binary_search(nc.begin(), nc.end(), d)) return false;  // the edge c-d exists already
    const std::vector<Tri> newFaces = {{c, a, d}, {d, b, c}};
    const Vec3 was = normalOf(tf) / norm(normalOf(tf)) + normalOf(tg) / norm(normalOf(tg));
    for (const Tri& n : newFaces)
      if (!acceptableFace(n, was)) return false;
    const double oldQuality = std::min(angleOf(tf), angleOf(tg));
    const double newQuality = std::min(angleOf(newFaces[0]), angleOf(newFaces[1]));
    if (!(newQuality > oldQuality * (1 + 1e-6))) return false;
    const std::vector<int> dying = {f, g};
    if (checkEach_ && !intersectionFree(newFaces, dying)) return false;
    replace(dying, newFaces, made);
    return true;
  }

  const bool checkEach_;
  const BoneState& state_;
  TriangleGrid& boneGrid_;
  const std::function<bool(std::uint32_t)> frozenVertex_;
  const std::function<bool(std::uint32_t)> frozenFace_;
  const BandCleanup opt_;
  const double minAngle_;

  const double cosMinAngle_;

  std::vector<LocalFace> faces_;  // bone faces looked at (by localFace) and faces made here
  SlotIndex& localOfSlot_ = tlsSlotIndex;  // this thread's; begun anew by the constructor
  std::unordered_map<std::uint32_t, VertexStar> star_;
  TriangleGrid made_;  // the faces made here (local ids), by box: only when each operation is tested
  std::vector<std::uint32_t> hits_;
  std::vector<Box3> madeBoxes_;      // scratch for intersectionFree
  std::vector<std::uint32_t> ring_;  // scratch for closedFan
  std::vector<std::uint32_t> nu_, nv_;  // scratch for neighbours
  std::vector<Tri> newFaces_;         // scratch for collapse
};

}  // namespace

CleanupPlan planCutBandCleanup(const BoneState& state, TriangleGrid& grid, const std::vector<std::uint32_t>& seeds,
                               const std::function<bool(std::uint32_t)>& frozenVertex,
                               const std::function<bool(std::uint32_t)>& frozenFace, const BandCleanup& options) {
  // Optimistic first: operations on their local tests, the outcome tested once. In the rare case that it
  // fails, the plan is made again with every operation tested before it is taken.
  if (!options.testEachOperation) {
    Cleanup optimistic(state, grid, frozenVertex, frozenFace, options, false);
    CleanupPlan plan = optimistic.run(seeds);
    if (plan.delta.empty() || optimistic.finalSurfaceIsIntersectionFree()) return plan;
  }
  CleanupPlan plan = Cleanup(state, grid, frozenVertex, frozenFace, options, true).run(seeds);
  plan.retested = !options.testEachOperation;
  return plan;
}

}  // namespace reamsim::csg
