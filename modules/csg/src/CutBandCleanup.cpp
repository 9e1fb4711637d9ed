// CGAL translation unit (predicates only): the clean-up of the cut band (see CutBandCleanup.h).
#include "CutBandCleanup.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

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

class Cleanup {
 public:
  Cleanup(const BoneState& state, TriangleGrid& grid, const std::function<bool(std::uint32_t)>& frozenVertex,
          const std::function<bool(std::uint32_t)>& frozenFace, const BandCleanup& options)
      : state_(state), boneGrid_(grid), frozenVertex_(frozenVertex), frozenFace_(frozenFace), opt_(options),
        minAngle_(options.minAngleDeg * kPi / 180) {}

  CleanupPlan run(const std::vector<std::uint32_t>& seeds) {
    CleanupPlan plan;
    // Most cuts leave nothing to clean: decide that before gathering the region.
    bool anyBad = false;
    for (std::uint32_t s : seeds) {
      const Triangle& t = state_.triangle(s);
      if ((anyBad = bad({t[0], t[1], t[2]}))) break;
    }
    if (!anyBad) return plan;
    gather(seeds);
    std::vector<int> work;
    for (std::uint32_t s : seeds) {
      const auto it = localOfSlot_.find(s);
      if (it != localOfSlot_.end()) work.push_back(it->second);
    }
    std::size_t ops = 0;
    while (!work.empty() && ops < kMaxOperations) {
      const int f = work.back();
      work.pop_back();
      if (!faces_[f].alive || !bad(f)) continue;
      std::vector<int> made;
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
    return plan;
  }

 private:
  // The local region: every bone face whose box meets the seeds' box (grown a little). A face that could
  // meet a new face lying inside that box is among them.
  void gather(const std::vector<std::uint32_t>& seeds) {
    region_ = boneGrid_.box(seeds.front());
    for (std::uint32_t s : seeds) {
      const Box3& b = boneGrid_.box(s);
      for (int i = 0; i < 3; ++i) {
        region_.lo[i] = std::min(region_.lo[i], b.lo[i]);
        region_.hi[i] = std::max(region_.hi[i], b.hi[i]);
      }
    }
    const double margin = std::max(1.0, 10 * opt_.minEdgeMm);
    for (int i = 0; i < 3; ++i) {
      region_.lo[i] -= margin;
      region_.hi[i] += margin;
    }
    std::vector<std::uint32_t> slots;
    boneGrid_.query(region_, slots);
    local_.init(region_.bounds(), slots.size(), 2.0);
    std::unordered_map<std::uint32_t, std::uint32_t> localUse;
    localUse.reserve(slots.size());
    localOfSlot_.reserve(slots.size());
    star_.reserve(slots.size());
    for (std::uint32_t s : slots) {
      const Triangle& t = state_.triangle(s);
      const int id = static_cast<int>(faces_.size());
      const bool frozen = frozenFace_(s);
      faces_.push_back({{t[0], t[1], t[2]}, s, true, frozen,
                        frozenVertex_(t[0]) || frozenVertex_(t[1]) || frozenVertex_(t[2])});
      localOfSlot_[s] = id;
      local_.insert(static_cast<std::uint32_t>(id), boneGrid_.box(s));
      for (std::uint32_t v : t) {
        star_[v].push_back(id);
        ++localUse[v];
        if (frozen) frozen_.insert(v);
      }
    }
    for (const auto& [v, n] : localUse)
      if (n == state_.vertexUseCount(v) && !frozenVertex_(v) && !frozen_.count(v)) movable_.insert(v);
  }

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
  bool insideRegion(const Box3& b) const {
    for (int i = 0; i < 3; ++i)
      if (b.lo[i] < region_.lo[i] || b.hi[i] > region_.hi[i]) return false;
    return true;
  }
  double angleOf(const Tri& t) const { return smallestAngle(at(t[0]), at(t[1]), at(t[2])); }
  Vec3 normalOf(const Tri& t) const { return cross(at(t[1]) - at(t[0]), at(t[2]) - at(t[0])); }

  bool bad(int f) const { return bad(faces_[f].v); }
  bool bad(const Tri& t) const {
    for (int i = 0; i < 3; ++i)
      if (norm(at(t[(i + 1) % 3]) - at(t[i])) < opt_.minEdgeMm) return true;
    return angleOf(t) < minAngle_;
  }

  const std::vector<int>& aliveStar(std::uint32_t v) {
    std::vector<int>& s = star_[v];
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
  // The vertices next to v, sorted, each once.
  std::vector<std::uint32_t> neighbours(const std::vector<int>& star, std::uint32_t v) const {
    std::vector<std::uint32_t> out;
    out.reserve(2 * star.size());
    for (int f : star)
      for (std::uint32_t w : faces_[f].v)
        if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  // A replacement face: not degenerate, turned by less than ~45 degrees from `was`, inside the region.
  bool acceptableFace(const Tri& t, const Vec3& was) const {
    if (CGAL::collinear(kp(t[0]), kp(t[1]), kp(t[2]))) return false;
    const Vec3 n = normalOf(t);
    if (dot(n, was) <= kNormalAgreement * norm(n) * norm(was)) return false;
    return insideRegion(boxOf(t));
  }
  // Distance of point p from the plane of t.
  double planeDistance(const Vec3& p, const Tri& t) const {
    const Vec3 n = normalOf(t);
    return std::abs(dot(n, p - at(t[0]))) / norm(n);
  }

  // The new faces meet no face that stays (other than along shared vertices and edges), nor each other.
  bool intersectionFree(const std::vector<Tri>& made, const std::vector<int>& dying) {
    for (std::size_t i = 0; i < made.size(); ++i) {
      for (std::size_t j = i + 1; j < made.size(); ++j)
        if (trianglesIntersectBeyondShared<K>(made[i], made[j], [&](std::uint32_t v) { return kp(v); })) return false;
      const Box3 b = boxOf(made[i]);
      hits_.clear();
      local_.query(b, hits_);
      for (std::uint32_t g : hits_) {
        const LocalFace& lf = faces_[g];
        if (!lf.alive || std::find(dying.begin(), dying.end(), int(g)) != dying.end()) continue;
        // A face with an exact (non-double) vertex is only known here rounded, and a defect face may be
        // degenerate (the intersection tests require proper triangles): stay away from both.
        if (lf.frozen || lf.exactVertex) return false;
        if (trianglesIntersectBeyondShared<K>(made[i], lf.v, [&](std::uint32_t v) { return kp(v); })) return false;
      }
    }
    return true;
  }

  void replace(const std::vector<int>& dying, const std::vector<Tri>& made, std::vector<int>& ids) {
    for (int f : dying) {
      faces_[f].alive = false;
      local_.remove(static_cast<std::uint32_t>(f));
    }
    for (const Tri& t : made) {
      const int id = static_cast<int>(faces_.size());
      faces_.push_back({t, kNone, true});
      local_.insert(static_cast<std::uint32_t>(id), boxOf(t));
      for (std::uint32_t v : t) star_[v].push_back(id);
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

  // Half-edge collapse: v moves onto u.
  bool collapse(std::uint32_t v, std::uint32_t u, std::vector<int>& made) {
    if (!movable_.count(v) || !movable_.count(u) || !closedFan(v) || !closedFan(u)) return false;
    const std::vector<int> sv = aliveStar(v), su = aliveStar(u);
    if (sv.size() < 3 || su.size() < 3) return false;
    std::vector<std::uint32_t> opposite;
    for (int f : sv) {
      const Tri& t = faces_[f].v;
      if (std::find(t.begin(), t.end(), u) == t.end()) continue;
      for (std::uint32_t w : t)
        if (w != u && w != v) opposite.push_back(w);
    }
    if (opposite.size() != 2 || opposite[0] == opposite[1]) return false;
    // Link condition: u and v share exactly the two neighbours across the edge.
    const auto nu = neighbours(su, u), nv = neighbours(sv, v);
    std::size_t common = 0;
    for (std::size_t i = 0, j = 0; i < nu.size() && j < nv.size();) {
      if (nu[i] < nv[j]) ++i;
      else if (nv[j] < nu[i]) ++j;
      else ++common, ++i, ++j;
    }
    if (common != 2) return false;

    std::vector<Tri> newFaces;
    double oldQuality = std::numeric_limits<double>::infinity(), newQuality = oldQuality;
    for (int f : sv) {
      Tri t = faces_[f].v;
      oldQuality = std::min(oldQuality, angleOf(t));
      if (std::find(t.begin(), t.end(), u) != t.end()) continue;
      const Vec3 was = normalOf(t);
      for (std::uint32_t& w : t) {
        if (w == v) w = u;
        if (frozenVertex_(w)) return false;  // only known rounded here
      }
      if (!acceptableFace(t, was) || planeDistance(at(v), t) > opt_.maxDeviationMm) return false;
      // A closed piece as small as a tetrahedron would fold onto one of u's faces.
      if (duplicates(t, u, sv)) return false;
      newQuality = std::min(newQuality, angleOf(t));
      newFaces.push_back(t);
    }
    if (newQuality < std::min(oldQuality, minAngle_)) return false;
    if (!intersectionFree(newFaces, sv)) return false;
    replace(sv, newFaces, made);
    movable_.erase(v);
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
    if (!movable_.count(a) || !movable_.count(b) || !movable_.count(c)) return false;
    if (!closedFan(a) || !closedFan(b)) return false;
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
    if (g < 0 || d == c || !movable_.count(d)) return false;
    const auto nc = neighbours(aliveStar(c), c);
    if (std::binary_search(nc.begin(), nc.end(), d)) return false;  // the edge c-d exists already
    const Tri tf = faces_[f].v, tg = faces_[g].v;
    if (planeDistance(at(d), tf) > opt_.maxDeviationMm || planeDistance(at(c), tg) > opt_.maxDeviationMm)
      return false;
    const std::vector<Tri> newFaces = {{c, a, d}, {d, b, c}};
    const Vec3 was = normalOf(tf) / norm(normalOf(tf)) + normalOf(tg) / norm(normalOf(tg));
    for (const Tri& n : newFaces)
      if (!acceptableFace(n, was)) return false;
    const double oldQuality = std::min(angleOf(tf), angleOf(tg));
    const double newQuality = std::min(angleOf(newFaces[0]), angleOf(newFaces[1]));
    if (!(newQuality > oldQuality * (1 + 1e-6))) return false;
    const std::vector<int> dying = {f, g};
    if (!intersectionFree(newFaces, dying)) return false;
    replace(dying, newFaces, made);
    return true;
  }

  const BoneState& state_;
  TriangleGrid& boneGrid_;
  const std::function<bool(std::uint32_t)> frozenVertex_;
  const std::function<bool(std::uint32_t)> frozenFace_;
  const BandCleanup opt_;
  const double minAngle_;

  Box3 region_;
  TriangleGrid local_;  // local face index -> box
  std::vector<LocalFace> faces_;
  std::unordered_map<std::uint32_t, int> localOfSlot_;
  std::unordered_map<std::uint32_t, std::vector<int>> star_;  // vertex -> local faces (dead ones pruned lazily)
  std::unordered_set<std::uint32_t> movable_;  // whole star local, double coordinates, not a defect
  std::unordered_set<std::uint32_t> frozen_;
  std::vector<std::uint32_t> hits_;
  std::vector<std::uint32_t> ring_;  // scratch for closedFan
};

}  // namespace

CleanupPlan planCutBandCleanup(const BoneState& state, TriangleGrid& grid, const std::vector<std::uint32_t>& seeds,
                               const std::function<bool(std::uint32_t)>& frozenVertex,
                               const std::function<bool(std::uint32_t)>& frozenFace, const BandCleanup& options) {
  return Cleanup(state, grid, frozenVertex, frozenFace, options).run(seeds);
}

}  // namespace reamsim::csg
