// Pass-based quadric edge collapse (see QuadricDecimation.h for why not a global queue).
#include "reamsim/ctimport/QuadricDecimation.h"

#include <tbb/parallel_for.h>

#include "TriangleIntersection.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace reamsim::ct {
namespace {

// Symmetric 4×4 error quadric, upper triangle: a00 a01 a02 a03 a11 a12 a13 a22 a23 a33.
struct Quadric {
  std::array<double, 10> m{};
  static Quadric plane(const Vec3& n, double d, double w) {
    Quadric q;
    q.m = {n.x * n.x, n.x * n.y, n.x * n.z, n.x * d, n.y * n.y, n.y * n.z, n.y * d, n.z * n.z, n.z * d, d * d};
    for (double& v : q.m) v *= w;
    return q;
  }
  Quadric operator+(const Quadric& o) const {
    Quadric q;
    for (int i = 0; i < 10; ++i) q.m[i] = m[i] + o.m[i];
    return q;
  }
  double error(const Vec3& p) const {
    return m[0] * p.x * p.x + 2 * m[1] * p.x * p.y + 2 * m[2] * p.x * p.z + 2 * m[3] * p.x + m[4] * p.y * p.y +
           2 * m[5] * p.y * p.z + 2 * m[6] * p.y + m[7] * p.z * p.z + 2 * m[8] * p.z + m[9];
  }
  // Minimiser of the error, if the 3×3 part is well conditioned.
  bool optimum(Vec3& p) const {
    const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[7];
    const double det = a * (d * f - e * e) - b * (b * f - c * e) + c * (b * e - c * d);
    const double scale = std::max({std::abs(a), std::abs(d), std::abs(f)});
    if (!(std::abs(det) > 1e-9 * scale * scale * scale)) return false;
    const Vec3 r{-m[3], -m[6], -m[8]};
    p.x = (r.x * (d * f - e * e) - b * (r.y * f - e * r.z) + c * (r.y * e - d * r.z)) / det;
    p.y = (a * (r.y * f - e * r.z) - r.x * (b * f - c * e) + c * (b * r.z - r.y * c)) / det;
    p.z = (a * (d * r.z - r.y * e) - b * (b * r.z - r.y * c) + r.x * (b * e - c * d)) / det;
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  }
};

double quality(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double l = std::max({squaredNorm(b - a), squaredNorm(c - b), squaredNorm(a - c)});
  return l > 0 ? norm(cross(b - a, c - a)) / l : 0.0;
}

// Faces by grid cell, for the self-intersection guard. Rebuilt every pass (cell size follows the growing
// faces); faces changed during a pass are appended to the cells of their new box, stale entries are
// filtered by box overlap at query time.
class FaceGrid {
 public:
  static constexpr double kCellScale = 2.0;  // cell edge / mean face extent
  void build(const std::vector<Triangle>& tri, const std::vector<Vec3>& pos, const std::vector<std::uint8_t>& deleted) {
    lo_ = Vec3{HUGE_VAL, HUGE_VAL, HUGE_VAL};
    Vec3 hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double extent = 0;
    std::size_t n = 0;
    for (std::size_t t = 0; t < tri.size(); ++t) {
      if (deleted[t]) continue;
      const Bounds b = box(tri[t], pos);
      lo_ = Vec3{std::min(lo_.x, b.min.x), std::min(lo_.y, b.min.y), std::min(lo_.z, b.min.z)};
      hi = Vec3{std::max(hi.x, b.max.x), std::max(hi.y, b.max.y), std::max(hi.z, b.max.z)};
      extent += std::max({b.size().x, b.size().y, b.size().z});
      ++n;
    }
    const double margin = n ? 4 * extent / double(n) + 1e-9 : 1.0;  // vertices may move a little outside
    lo_ -= Vec3{margin, margin, margin};
    hi += Vec3{margin, margin, margin};
    h_ = std::max(kCellScale * extent / double(std::max<std::size_t>(n, 1)), 1e-9);
    for (;;) {
      for (int d = 0; d < 3; ++d) g_[d] = long((hi[d] - lo_[d]) / h_) + 1;
      if (double(g_[0]) * double(g_[1]) * double(g_[2]) <= 4.0 * double(n) + 1024) break;
      h_ *= 1.25;
    }
    head_.assign(std::size_t(g_[0] * g_[1] * g_[2]), kNone);
    pool_.clear();
    pool_.reserve(n * 4);
    for (std::size_t t = 0; t < tri.size(); ++t)
      if (!deleted[t]) insert(std::uint32_t(t), box(tri[t], pos));
  }

  void insert(std::uint32_t face, const Bounds& b) {
    forCells(b, [&](std::size_t c) {
      pool_.push_back({face, head_[c]});
      head_[c] = std::uint32_t(pool_.size() - 1);
    });
  }

  template <class Fn>
  void query(const Bounds& b, Fn&& fn) const {
    forCells(b, [&](std::size_t c) {
      for (std::uint32_t e = head_[c]; e != kNone; e = pool_[e].second) fn(pool_[e].first);
    });
  }

  static Bounds box(const Triangle& t, const std::vector<Vec3>& pos) {
    Bounds b;
    for (std::uint32_t v : t) b.add(pos[v]);
    return b;
  }

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;
  long cell(double x, int d) const { return std::clamp(long(std::floor((x - lo_[d]) / h_)), 0L, g_[d] - 1); }
  template <class Fn>
  void forCells(const Bounds& b, Fn&& fn) const {
    const long x0 = cell(b.min.x, 0), x1 = cell(b.max.x, 0), y0 = cell(b.min.y, 1), y1 = cell(b.max.y, 1),
               z0 = cell(b.min.z, 2), z1 = cell(b.max.z, 2);
    for (long z = z0; z <= z1; ++z)
      for (long y = y0; y <= y1; ++y)
        for (long x = x0; x <= x1; ++x) fn(std::size_t((z * g_[1] + y) * g_[0] + x));
  }

  Vec3 lo_;
  double h_ = 1;
  long g_[3] = {1, 1, 1};
  std::vector<std::uint32_t> head_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pool_;  // (face, next)
};

class Decimator {
 public:
  Decimator(const TriangleMesh& mesh, const DecimationOptions& o) : opt_(o), pos_(mesh.vertices), tri_(mesh.triangles) {
    const std::size_t nv = pos_.size(), nt = tri_.size();
    locked_.assign(nv, 0);
    if (o.lockedVertices && o.lockedVertices->size() == nv) locked_ = *o.lockedVertices;
    q_.assign(nv, Quadric{});
    for (const Triangle& t : tri_) {
      const Vec3 n = cross(pos_[t[1]] - pos_[t[0]], pos_[t[2]] - pos_[t[0]]);
      const double area2 = norm(n);
      if (area2 <= 0) continue;
      const Vec3 u = n / area2;
      const Quadric pq = Quadric::plane(u, -dot(u, pos_[t[0]]), area2 * 0.5);  // area-weighted
      for (int k = 0; k < 3; ++k) q_[t[k]] = q_[t[k]] + pq;
    }
    deleted_.assign(nt, 0);
    dirty_.assign(nt, 0);
    mark_.assign(nv, 0);
    err_.assign(nt, {});
    if (o.guardedVertices && o.guardedVertices->size() == nv) {
      guarded_ = *o.guardedVertices;
      guarding_ = o.preventSelfIntersections && std::find(guarded_.begin(), guarded_.end(), 1) != guarded_.end();
    } else {
      guarding_ = o.preventSelfIntersections;
    }
    alive_ = nt;
  }

  void run(DecimationStats& stats, const std::function<bool()>& keepGoing) {
    const std::size_t target = std::max<std::size_t>(opt_.targetFaces, 4);
    buildRefs();
    tbb::parallel_for(std::size_t{0}, tri_.size(), [&](std::size_t t) { updateErrors(t); });
    double fraction = 0.3, boost = 1;
    int idle = 0;
    for (int pass = 0; pass < 200 && alive_ > target; ++pass) {
      if (keepGoing && !keepGoing()) break;
      if (pass > 0) {
        compact();
        buildRefs();
        // Errors of the faces changed in the last pass, all at once and in parallel.
        tbb::parallel_for(std::size_t{0}, tri_.size(), [&](std::size_t t) {
          if (dirty_[t]) updateErrors(t);
        });
      }
      ++stats.passes;
      if (guarding_) {
        grid_.build(tri_, pos_, deleted_);
        seen_.assign(tri_.size(), 0);
        fan_.assign(tri_.size(), 0);
      }
      // Threshold: the error below which about `k` of the live faces lie.
      std::vector<double> e;
      e.reserve(tri_.size());
      for (const auto& x : err_) e.push_back(x[3]);
      const std::size_t needed = alive_ - target;
      // About twice the faces still to remove (most candidates share a neighbourhood or are refused),
      // at most `fraction` of all faces so that cheap collapses go first.
      std::size_t k = std::min<std::size_t>(e.size() - 1, std::max<std::size_t>(
          std::size_t(2048 * boost),
          std::min<std::size_t>(std::size_t(2 * boost * double(needed)), std::size_t(fraction * double(e.size())))));
      std::nth_element(e.begin(), e.begin() + k, e.end());
      const double threshold = e[k];
      std::fill(dirty_.begin(), dirty_.end(), 0);
      const std::size_t before = alive_;
      for (std::size_t t = 0; t < tri_.size() && alive_ > target; ++t) {
        if (deleted_[t] || dirty_[t] || err_[t][3] > threshold) continue;
        for (int j = 0; j < 3; ++j) {
          if (err_[t][j] > threshold) continue;
          if (tryCollapse(tri_[t][j], tri_[t][(j + 1) % 3])) break;
        }
      }
      if (alive_ == before) {
        // Nothing collapsible below this threshold: widen the candidate set, give up once it is everything.
        if (k + 1 >= e.size() || ++idle > 3) break;
        fraction = std::min(1.0, fraction * 2);
        boost *= 4;
      } else {
        idle = 0;
      }
    }
    compact();
    stats.reachedTarget = alive_ <= target;
  }

  TriangleMesh result(std::vector<std::uint32_t>& source) const {
    TriangleMesh out;
    source.clear();
    std::vector<std::uint32_t> remap(pos_.size(), UINT32_MAX);
    for (std::size_t t = 0; t < tri_.size(); ++t) {
      if (deleted_[t]) continue;
      Triangle n;
      for (int k = 0; k < 3; ++k) {
        std::uint32_t& r = remap[tri_[t][k]];
        if (r == UINT32_MAX) {
          r = std::uint32_t(out.vertices.size());
          out.vertices.push_back(pos_[tri_[t][k]]);
          source.push_back(tri_[t][k]);
        }
        n[k] = r;
      }
      out.triangles.push_back(n);
    }
    return out;
  }

 private:
  // Vertex → (face << 2 | corner) lists; collapses append new lists at the end.
  void buildRefs() {
    const std::size_t nv = pos_.size();
    start_.assign(nv, 0);
    count_.assign(nv, 0);
    for (std::size_t t = 0; t < tri_.size(); ++t)
      for (int k = 0; k < 3; ++k) ++count_[tri_[t][k]];
    std::uint32_t s = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      start_[v] = s;
      s += count_[v];
      count_[v] = 0;
    }
    refs_.assign(s, 0);
    refs_.reserve(std::size_t(s) * 2);
    for (std::size_t t = 0; t < tri_.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = tri_[t][k];
        refs_[start_[v] + count_[v]++] = std::uint32_t(t << 2 | std::size_t(k));
      }
  }

  void compact() {
    std::size_t w = 0;
    for (std::size_t t = 0; t < tri_.size(); ++t) {
      if (deleted_[t]) continue;
      tri_[w] = tri_[t];
      err_[w] = err_[t];
      ++w;
    }
    tri_.resize(w);
    err_.resize(w);
    for (std::size_t t = 0, r = 0; t < deleted_.size(); ++t)
      if (!deleted_[t]) dirty_[r++] = dirty_[t];  // changed faces keep their mark across the compaction
    dirty_.resize(w);
    deleted_.assign(w, 0);
  }

  double edgeError(std::uint32_t a, std::uint32_t b, Vec3& p) const {
    const Quadric q = q_[a] + q_[b];
    const Vec3 mid = (pos_[a] + pos_[b]) * 0.5;
    if (q.optimum(p) && squaredNorm(p - mid) <= 4 * squaredNorm(pos_[a] - pos_[b])) return q.error(p);
    double best = q.error(mid);
    p = mid;
    for (const Vec3& c : {pos_[a], pos_[b]}) {
      const double e = q.error(c);
      if (e < best) {
        best = e;
        p = c;
      }
    }
    return best;
  }

  void updateErrors(std::size_t t) {
    Vec3 p;
    auto& e = err_[t];
    for (int j = 0; j < 3; ++j) {
      const std::uint32_t a = tri_[t][j], b = tri_[t][(j + 1) % 3];
      e[j] = (locked_[a] || locked_[b]) ? HUGE_VAL : edgeError(a, b, p);
    }
    e[3] = std::min({e[0], e[1], e[2]});
  }

  template <class Fn>
  void forFaces(std::uint32_t v, Fn&& fn) const {
    for (std::uint32_t i = 0; i < count_[v]; ++i) {
      const std::uint32_t r = refs_[start_[v] + i];
      if (!deleted_[r >> 2]) fn(r >> 2, int(r & 3));
    }
  }

  // True if moving `v` to `p` (with `other` merged into it) keeps every surviving face of `v` sound.
  bool facesStaySound(std::uint32_t v, std::uint32_t other, const Vec3& p) const {
    bool ok = true;
    forFaces(v, [&](std::uint32_t t, int c) {
      if (!ok) return;
      const std::uint32_t b = tri_[t][(c + 1) % 3], d = tri_[t][(c + 2) % 3];
      if (b == other || d == other) return;  // removed by the collapse
      const Vec3 nOld = cross(pos_[b] - pos_[v], pos_[d] - pos_[v]);
      const Vec3 nNew = cross(pos_[b] - p, pos_[d] - p);
      const double lo = norm(nOld), ln = norm(nNew);
      if (ln <= 0 || lo <= 0 || dot(nOld, nNew) < opt_.minNormalCosine * lo * ln) {
        ok = false;
        return;
      }
      const double qn = quality(p, pos_[b], pos_[d]);
      if (qn < opt_.minTriangleQuality && qn < quality(pos_[v], pos_[b], pos_[d])) ok = false;
    });
    return ok;
  }

  // Link condition: the neighbours shared by a and b must be exactly the two opposite vertices (and the
  // merged vertex must keep at least 3 neighbours). Stamps avoid clearing a mark array per test.
  bool linkConditionHolds(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t sa = ++stamp_, sb = ++stamp_;
    std::size_t onlyA = 0, common = 0, onlyB = 0;
    forFaces(a, [&](std::uint32_t t, int) {
      for (std::uint32_t v : tri_[t])
        if (v != a && v != b && mark_[v] != sa) {
          mark_[v] = sa;
          ++onlyA;
        }
    });
    forFaces(b, [&](std::uint32_t t, int) {
      for (std::uint32_t v : tri_[t]) {
        if (v == a || v == b || mark_[v] == sb) continue;
        if (mark_[v] == sa) ++common;
        else ++onlyB;
        mark_[v] = sb;
      }
    });
    return common == 2 && onlyA + onlyB >= 4;
  }

  bool tryCollapse(std::uint32_t a, std::uint32_t b) {
    if (locked_[a] || locked_[b]) return false;
    Vec3 p;
    edgeError(a, b, p);
    if (!linkConditionHolds(a, b)) return false;
    if (!facesStaySound(a, b, p) || !facesStaySound(b, a, p)) return false;
    if (guarding_ && (guarded_.empty() || guarded_[a] || guarded_[b]) && !staysFreeOfIntersections(a, b, p))
      return false;

    pos_[a] = p;
    q_[a] = q_[a] + q_[b];
    if (!guarded_.empty()) guarded_[a] = guarded_[a] | guarded_[b];
    const std::uint32_t newStart = std::uint32_t(refs_.size());
    forFaces(a, [&](std::uint32_t t, int c) {
      if (tri_[t][0] == b || tri_[t][1] == b || tri_[t][2] == b) {
        deleted_[t] = 1;
        --alive_;
        return;
      }
      refs_.push_back(t << 2 | std::uint32_t(c));
    });
    forFaces(b, [&](std::uint32_t t, int c) {
      tri_[t][c] = a;
      refs_.push_back(t << 2 | std::uint32_t(c));
    });
    start_[a] = newStart;
    count_[a] = std::uint32_t(refs_.size()) - newStart;
    count_[b] = 0;
    forFaces(a, [&](std::uint32_t t, int c) {
      dirty_[t] = 1;  // its errors are recomputed before the next pass
      if (guarding_) grid_.insert(t, FaceGrid::box(tri_[t], pos_));
    });
    return true;
  }

  // The faces the collapse of b into a (moved to p) creates must not meet any other face, nor each other
  // (the rest of the mesh is unchanged and was clean before).
  bool staysFreeOfIntersections(std::uint32_t a, std::uint32_t b, const Vec3& p) {
    const std::uint32_t fanStamp = ++faceStamp_;
    newFaces_.clear();
    const auto collect = [&](std::uint32_t v) {
      forFaces(v, [&](std::uint32_t t, int) {
        fan_[t] = fanStamp;
        Triangle ids = tri_[t];
        if (ids[0] == (v == a ? b : a) || ids[1] == (v == a ? b : a) || ids[2] == (v == a ? b : a)) return;
        detail::Corners c;
        for (int k = 0; k < 3; ++k) {
          if (ids[std::size_t(k)] == b) ids[std::size_t(k)] = a;
          c[std::size_t(k)] = ids[std::size_t(k)] == a ? p : pos_[ids[std::size_t(k)]];
        }
        newFaces_.push_back({ids, c});
      });
    };
    collect(a);
    collect(b);
    // One walk over the cells under all new faces; then each new face against the candidates.
    Bounds all;
    std::vector<Bounds>& boxes = newBoxes_;
    boxes.clear();
    for (const auto& nf : newFaces_) {
      Bounds b;
      for (const Vec3& x : nf.second) b.add(x);
      boxes.push_back(b);
      all.add(b);
    }
    candidates_.clear();
    const std::uint32_t queryStamp = ++faceStamp_;
    grid_.query(all, [&](std::uint32_t g) {
      if (seen_[g] == queryStamp || fan_[g] == fanStamp || deleted_[g]) return;
      seen_[g] = queryStamp;
      const Bounds gb = FaceGrid::box(tri_[g], pos_);
      if (gb.overlaps(all)) candidates_.push_back({g, gb});
    });
    for (std::size_t i = 0; i < newFaces_.size(); ++i) {
      const auto& [ids, c] = newFaces_[i];
      for (std::size_t j = i + 1; j < newFaces_.size(); ++j)
        if (boxes[i].overlaps(boxes[j]) &&
            detail::trianglesIntersect(ids, c, newFaces_[j].first, newFaces_[j].second))
          return false;
      for (const auto& [g, gb] : candidates_) {
        if (!gb.overlaps(boxes[i])) continue;
        const Triangle& gt = tri_[g];
        if (detail::trianglesIntersect(ids, c, gt, {pos_[gt[0]], pos_[gt[1]], pos_[gt[2]]})) return false;
      }
    }
    return true;
  }

  const DecimationOptions& opt_;
  std::vector<Vec3> pos_;
  std::vector<Triangle> tri_;
  std::vector<std::uint8_t> locked_;
  std::vector<Quadric> q_;
  std::vector<std::uint8_t> deleted_, dirty_;
  std::vector<std::array<double, 4>> err_;
  std::vector<std::uint32_t> start_, count_, refs_;
  std::vector<std::uint32_t> mark_;
  std::uint32_t stamp_ = 0;
  bool guarding_ = false;
  std::vector<std::uint8_t> guarded_;  // empty: guard every collapse
  FaceGrid grid_;
  std::vector<std::uint32_t> seen_, fan_;  // per face: last query / collapse that visited it
  std::uint32_t faceStamp_ = 0;
  std::vector<std::pair<Triangle, detail::Corners>> newFaces_;
  std::vector<Bounds> newBoxes_;
  std::vector<std::pair<std::uint32_t, Bounds>> candidates_;
  std::size_t alive_ = 0;
};

}  // namespace

TriangleMesh decimateQuadric(const TriangleMesh& mesh, const DecimationOptions& options, DecimationStats* stats,
                             const std::function<bool()>& keepGoing) {
  DecimationStats local;
  DecimationStats& s = stats ? *stats : local;
  s = DecimationStats{};
  s.facesBefore = mesh.triangles.size();
  if (options.targetFaces >= mesh.triangles.size()) {
    s.facesAfter = s.facesBefore;
    s.reachedTarget = true;
    s.sourceVertex.resize(mesh.vertices.size());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) s.sourceVertex[v] = std::uint32_t(v);
    return mesh;
  }
  Decimator d(mesh, options);
  d.run(s, keepGoing);
  TriangleMesh out = d.result(s.sourceVertex);
  s.facesAfter = out.triangles.size();
  return out;
}

}  // namespace reamsim::ct
