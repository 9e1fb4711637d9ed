// CGAL translation unit: the local exact subtraction (see LocalSubtractor.h for the design).
#include "ExactRationalFastPaths.h"  // before any CGAL kernel: see there
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>

#include "BackgroundTask.h"
#include "CutBandCleanup.h"
#include "ExactAheadVisitor.h"
#include "LocalDefectScan.h"
#include "SideGroups.h"
#include "SplitOverTwoThreads.h"
#include "PlaneSide.h"
#include "TrianglePair.h"
#include "ToolBound.h"
#include "FacesAcross.h"
#include "reamsim/csg/ToolFacetSag.h"
#include "TriangleGrid.h"
#include "PackedTriangleGrid.h"
#include "reamsim/csg/LocalSubtractor.h"

namespace reamsim {
namespace {
using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using P = EK::Point_3;
using SM = CGAL::Surface_mesh<P>;
using VI = SM::Vertex_index;
using FI = SM::Face_index;
using HI = SM::Halfedge_index;
using EI = SM::Edge_index;
namespace PMP = CGAL::Polygon_mesh_processing;
using csg::Box3;
using csg::kInside;
using csg::kOutside;
using csg::kUndecided;
using csg::Side;

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
// Planes of the tool's bound beyond its box (csg::ToolBound): enough to hug a spherical cap to within a
// fraction of a millimetre; each costs three dot products per candidate face.
constexpr std::size_t kToolBoundPlanes = 32;
// Candidate faces per thread from which the near test is split over two threads (the second core is idle
// then; from 200, not 400, since session 43: a bundled glenoid cut's ~600 candidates are split too, ~2-4 %
// faster in paired runs).
constexpr std::size_t kParallelNearTestFaces = 200;
// A bone face this close to a tool face's plane (all three corners), where the two meet, lies on the tool's
// surface to rounding (see liesOnToolFace): a thousandth of the nudge that moves the tool off it.
constexpr double kOnToolFaceMm = 1e-9;

// Intersection points are built once by the corefinement and shared by both meshes, so their interval
// approximations are identical: looking them up by those intervals avoids exact evaluation (GMP) for
// every curve vertex; an exact comparison only settles the rare collision of equal intervals.
struct ApproxKey {
  std::array<double, 6> v;
  bool operator==(const ApproxKey& o) const { return v == o.v; }
};
// The point's own interval approximation: p.x() would allocate a lazy number for every coordinate read.
const CGAL::Interval_nt<false>& approxCoordinate(const P& p, int i) { return CGAL::approx(p).cartesian(i); }

ApproxKey approxKey(const P& p) {
  const auto &x = approxCoordinate(p, 0), &y = approxCoordinate(p, 1), &z = approxCoordinate(p, 2);
  return {{x.inf(), x.sup(), y.inf(), y.sup(), z.inf(), z.sup()}};
}
struct ApproxHash {
  std::size_t operator()(const ApproxKey& k) const {
    std::size_t h = 0;
    for (double d : k.v) h = h * 1000003u ^ std::hash<double>()(d);
    return h;
  }
};

std::uint64_t pairKey(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(a) << 32) | b;
}
std::uint64_t directedKey(std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; }

// What CGAL::to_double(p.x()) gives (the interval's midpoint when it is narrow enough, else the exact
// value's), read from the point's approximation.
double roundedCoordinate(const P& p, int i) {
  double r;
  const CGAL::Interval_nt<false>& a = approxCoordinate(p, i);
  if (CGAL::fit_in_double(a, r)) return r;
  if (CGAL::has_smaller_relative_precision(a, EK::FT::get_relative_precision_of_to_double())) return CGAL::to_double(a);
  CGAL::exact(p);  // refines the approximation
  return CGAL::to_double(approxCoordinate(p, i));
}
Vec3 rounded(const P& p) { return {roundedCoordinate(p, 0), roundedCoordinate(p, 1), roundedCoordinate(p, 2)}; }

void settle(const P& p) { CGAL::exact(p); }

void grow(Box3& b, const P& p) {
  const auto &ix = approxCoordinate(p, 0), &iy = approxCoordinate(p, 1), &iz = approxCoordinate(p, 2);
  b.lo = {std::min(b.lo[0], ix.inf()), std::min(b.lo[1], iy.inf()), std::min(b.lo[2], iz.inf())};
  b.hi = {std::max(b.hi[0], ix.sup()), std::max(b.hi[1], iy.sup()), std::max(b.hi[2], iz.sup())};
}

// 6 × signed tetra volume of (o, a, b, c): the divergence-theorem term of one face.
double volumeTerm(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c) {
  return dot(a - o, cross(b - o, c - o));
}

// Side of the face (a, b, q) near edge ab relative to a closed, outward-oriented solid whose two faces at
// that edge are (a, b, c1) and (b, a, c2). Exact. A face lying on one of the solid's faces near the edge
// gets `sameWay` when their normals agree and `oppositeWay` when they are opposed.
Side wedgeSide(const P& a, const P& b, const P& c1, const P& c2, const P& q, Side sameWay, Side oppositeWay) {
  const auto s1 = CGAL::orientation(a, b, c1, q);
  const auto s2 = CGAL::orientation(b, a, c2, q);
  if (s1 == CGAL::COPLANAR && CGAL::coplanar_orientation(a, b, c1, q) == CGAL::POSITIVE) return sameWay;
  if (s2 == CGAL::COPLANAR && CGAL::coplanar_orientation(b, a, c2, q) == CGAL::POSITIVE) return oppositeWay;
  // Convex edge (c2 not above the plane of the first face): the interior is the intersection of the
  // two lower half-spaces; reflex: their union. A face in the plane of one solid face but beyond the
  // edge is outside a convex wedge and inside a reflex one.
  const bool convex = CGAL::orientation(a, b, c1, c2) != CGAL::POSITIVE;
  if (s1 == CGAL::COPLANAR || s2 == CGAL::COPLANAR) return convex ? kOutside : kInside;
  const bool below1 = s1 == CGAL::NEGATIVE, below2 = s2 == CGAL::NEGATIVE;
  return (convex ? (below1 && below2) : (below1 || below2)) ? kInside : kOutside;
}

// Connected components of faces not crossing constrained edges.
std::vector<int> components(const SM& m, const SM::Property_map<EI, bool>& constrained, int& count) {
  std::vector<int> comp(m.number_of_faces(), -1);
  count = 0;
  std::vector<FI> stack;
  for (FI f : m.faces()) {
    if (comp[f.idx()] >= 0) continue;
    comp[f.idx()] = count;
    stack.push_back(f);
    while (!stack.empty()) {
      const FI g = stack.back();
      stack.pop_back();
      for (HI h : CGAL::halfedges_around_face(m.halfedge(g), m)) {
        if (constrained[m.edge(h)]) continue;
        const FI n = m.face(m.opposite(h));
        if (n == SM::null_face() || comp[n.idx()] >= 0) continue;
        comp[n.idx()] = count;
        stack.push_back(n);
      }
    }
    ++count;
  }
  return comp;
}

std::array<VI, 3> faceVertices(const SM& m, FI f) {
  const HI h = m.halfedge(f);
  return {m.source(h), m.target(h), m.target(m.next(h))};
}

// The bone as a triangle soup in slot order (vertex i = vertex slot i, triangle i = triangle slot i; free
// triangle slots are (0, 0, 0), without area), so that a whole-bone scan's per-face flags index slots.
TriangleMesh slotSoup(const BoneState& state) {
  TriangleMesh soup;
  soup.vertices.resize(state.vertexSlotCount());
  for (std::uint32_t v = 0; v < soup.vertices.size(); ++v) soup.vertices[v] = state.vertex(v);
  soup.triangles.resize(state.triangleSlotCount(), Triangle{0, 0, 0});
  state.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) { soup.triangles[slot] = t; });
  return soup;
}

// True when the faces `added` (a subset of the surface `kept`), with coordinates from `at`, are not
// degenerate and the faces `moved` (indices into `kept` of those of `added` with a vertex that rounding
// moves) do not intersect any face of `kept` other than along shared edges and vertices: a pair in which
// no vertex moved is a pair of the exact result, which is free of intersections. Epick: predicates only,
// exact on the given doubles. Vertex ids run below `ids`.
template <class At>
bool roundingIsSafe(const std::vector<std::array<std::uint32_t, 3>>& kept,
                    const std::vector<std::array<std::uint32_t, 3>>& added, const std::vector<std::uint32_t>& moved,
                    std::size_t ids, At&& at) {
  using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<IK::Point_3> points(ids);
  std::vector<char> known(ids, 0);
  for (const auto& t : kept)
    for (std::uint32_t uid : t)
      if (!known[uid]) {
        known[uid] = 1;
        const Vec3 v = at(uid);
        points[uid] = IK::Point_3(v.x, v.y, v.z);
      }
  auto pt = [&](std::uint32_t uid) -> const IK::Point_3& { return points[uid]; };
  for (const auto& t : added)
    if (CGAL::collinear(pt(t[0]), pt(t[1]), pt(t[2]))) return false;
  if (moved.empty()) return true;
  // A small uniform grid over the kept faces: far cheaper here than box_intersection_d's sorting, since
  // the moved faces are a thin ring and each meets a dozen neighbours.
  auto boxOf = [&](const std::array<std::uint32_t, 3>& t) {
    csg::Box3 b = csg::Box3::empty();
    for (std::uint32_t uid : t) b.add(Vec3{points[uid].x(), points[uid].y(), points[uid].z()});
    return b;
  };
  std::vector<csg::Box3> keptBoxes(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) keptBoxes[i] = boxOf(kept[i]);
  // Filed once and only queried: the packed grid (no per-cell vectors to grow; this check ~10 % shorter at
  // the bundled glenoid than with TriangleGrid's inserts).
  csg::PackedTriangleGrid grid;
  grid.build(std::move(keptBoxes), 4.0);
  // Moved faces lie side by side along the intersection curve: a pair of two moved faces is tested once,
  // from the later one (a third fewer tests at the glenoid).
  std::vector<char> isMoved(kept.size(), 0);
  for (std::uint32_t m : moved) isMoved[m] = 1;
  std::vector<std::uint32_t> near;
  for (std::uint32_t m : moved) {
    grid.query(grid.box(m), near);
    for (std::uint32_t k : near)
      if (!(isMoved[k] && k <= m) && csg::trianglesIntersectBeyondShared<IK>(kept[m], kept[k], pt)) return false;
  }
  return true;
}

// The tool's connectivity: a closed, consistently oriented surface (each directed edge once, with its twin);
// `across[t][i]` is the face across edge i of face t. Checked on indices and kept while the triangles stay
// the same (a reaming tool is one solid placed anew each step), so no exact mesh is built for it.
struct ToolTopology {
  std::size_t vertexCount = 0;
  std::vector<Triangle> triangles;
  std::vector<std::array<std::uint32_t, 3>> across;
  std::vector<std::uint32_t> boundFaces;  // faces whose planes bound the placed tool (csg::ToolBound)
  // toolFacetSagMm, which sets the clean-up's default bound, for the shape whose edge lengths are kept: the
  // same triangles may come with another shape (a reamer of another size at the same resolution, hulls
  // of different sweeps), so a rigid placement is checked, not assumed.
  double facetSagMm = -1;
  std::vector<double> shapeEdges, edgesNow;  // squared length of each triangle's first edge: kept, current
  double sagOf(const TriangleMesh& tool) {
    edgesNow.clear();
    for (const Triangle& t : tool.triangles) {
      const Vec3 e = tool.vertices[t[1]] - tool.vertices[t[0]];
      edgesNow.push_back(dot(e, e));
    }
    const bool same = facetSagMm >= 0 && std::equal(edgesNow.begin(), edgesNow.end(), shapeEdges.begin(), shapeEdges.end(),
                                                    [](double now, double kept) { return std::abs(now - kept) <= 1e-9 * (kept + 1e-12); });
    if (!same) {
      shapeEdges.swap(edgesNow);
      facetSagMm = csg::toolFacetSagMm(tool, across);  // the faces across are this tool's (checkTool)
    }
    return facetSagMm;
  }
};

const ToolTopology& checkTool(const TriangleMesh& tool, ToolTopology& cache) {
  if (signedVolume(tool) <= 0)
    throw CutError(CutError::Kind::BadTool, "tool is not a closed, outward-oriented triangle mesh");
  if (cache.vertexCount == tool.vertices.size() && cache.triangles == tool.triangles) return cache;
  cache = {};
  const std::size_t n = tool.vertices.size();
  for (const Triangle& t : tool.triangles)
    if (t[0] >= n || t[1] >= n || t[2] >= n || t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      throw CutError(CutError::Kind::BadTool, "tool has a triangle with a bad or repeated vertex index");
  csg::FacesAcross adjacency = csg::facesAcross(tool);
  if (tool.triangles.empty() || adjacency.repeatedDirectedEdge)
    throw CutError(CutError::Kind::BadTool, "tool is not an oriented 2-manifold triangle mesh");
  for (const auto& faces : adjacency.face)
    for (std::uint32_t g : faces)
      if (g == csg::kNoFaceAcross) throw CutError(CutError::Kind::BadTool, "tool is not a closed, outward-oriented triangle mesh");
  cache.vertexCount = n;
  cache.triangles = tool.triangles;
  cache.across = std::move(adjacency.face);
  cache.boundFaces = csg::ToolBound::spreadFaces(tool, kToolBoundPlanes);
  return cache;
}

// The whole tool as an exact mesh, built on first use.
const SM& exactTool(const TriangleMesh& toolMesh, std::optional<SM>& whole) {
  if (whole) return *whole;
  whole.emplace();
  std::vector<VI> v;
  v.reserve(toolMesh.vertices.size());
  for (const Vec3& p : toolMesh.vertices) v.push_back(whole->add_vertex(P(p.x, p.y, p.z)));
  for (const Triangle& t : toolMesh.triangles)
    if (whole->add_face(v[t[0]], v[t[1]], v[t[2]]) == SM::null_face())
      throw CutError(CutError::Kind::BadTool, "tool is not an oriented 2-manifold triangle mesh");
  return *whole;
}

double elapsedMs(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The k-th offset of a cut made again: 1 to 2 nm, its direction and length from low-discrepancy sequences
// (golden-ratio and plastic-number steps), so that no two offsets are alike and a moved tool does not lie
// on a surface an earlier moved tool left.
Vec3 nudge(std::uint64_t k) {
  auto frac = [](double x) { return x - std::floor(x); };
  const double kd = double(k);
  const double z = 1 - 2 * frac(kd * 0.6180339887498949), phi = 2 * M_PI * frac(kd * 0.7548776662466927);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return Vec3{r * std::cos(phi), r * std::sin(phi), z} * (1e-6 * (1 + frac(kd * 0.5698402909980532)));
}

}  // namespace

const char* toString(CutError::Kind kind) {
  switch (kind) {
    case CutError::Kind::BadTool: return "bad-tool";
    case CutError::Kind::DefectReached: return "defect-reached";
    case CutError::Kind::OpenBorderReached: return "open-border-reached";
    case CutError::Kind::Degenerate: return "degenerate-contact";
    case CutError::Kind::ToolEnclosed: return "tool-enclosed";
    case CutError::Kind::Inconsistent: return "inconsistent";
  }
  return "unknown";
}

struct LocalSubtractor::Impl {
  BoneState state;
  std::unordered_map<std::uint32_t, P> exact;  // vertex slot → exact point, when not a double triple
  csg::TriangleGrid grid;
  std::vector<std::uint8_t> defect;  // per triangle slot (DefectFlag bits), 0 for faces made by cuts
  LocalDefects defects;
  std::vector<std::uint32_t> candidates;
  BandCleanup cleanup;
  bool failRoundingChecks = false;  // tests only
  ToolTopology toolTopology;  // of the last tool checked
  std::optional<double> referenceToolSagMm;  // setReferenceTool

  // Whether vertex v's exact coordinates are not its doubles (kept in `exact`).
  bool knownExactly(std::uint32_t v) const { return !exact.empty() && exact.count(v) != 0; }
  P point(std::uint32_t v) const {
    const auto it = exact.find(v);
    if (it != exact.end()) return it->second;
    const Vec3& p = state.vertex(v);
    return P(p.x, p.y, p.z);
  }
  Box3 boxOf(const Triangle& t) const {
    Box3 b = Box3::empty();
    for (std::uint32_t v : t) {
      const auto it = exact.find(v);
      if (it != exact.end()) {
        grow(b, it->second);
      } else {
        b.add(state.vertex(v));
      }
    }
    return b;
  }
  EK::Triangle_3 triangle(std::uint32_t slot) const {
    const Triangle& t = state.triangle(slot);
    return {point(t[0]), point(t[1]), point(t[2])};
  }

  bool touchesTool(std::uint32_t slot, const SM& tool, CGAL::Side_of_triangle_mesh<SM, EK>& side) const;
  Side insideBone(const P& q);
  csg::CleanupPlan planCleanup(const std::vector<std::uint32_t>& seeds, double deviationMm);
  double commitCleanup(const csg::CleanupPlan& plan, const Vec3& origin, LocalCut& cut);
  double removedVolume6(const MeshDelta& delta, const Vec3& origin) const;
  template <class Placed>
  void commit(const MeshDelta& delta, Placed&& placed);
  // One attempt; when `mayRedo`, a tool found lying on the bone's surface is moved by a nanometre-scale
  // offset before the corefinement, and a cut whose rounding check fails is rolled back and made again
  // once with the tool so moved.
  LocalCut subtractOnce(const TriangleMesh& toolMesh, bool mayRedo);
  // The cut made with the tool moved by nudge(): after a failed rounding check (rolled back first) or when
  // the tool lies on the bone's surface where it meets it. Its time counts from `firstStart`.
  LocalCut redoWithMovedTool(const TriangleMesh& toolMesh, bool onBoneSurface,
                             std::chrono::steady_clock::time_point firstStart);
  LocalCut subtract(const TriangleMesh& toolMesh) { return subtractOnce(toolMesh, true); }
  std::uint64_t redoneCuts = 0;  // cuts made again with a moved tool (each gets its own offset)
};

// Exact: the face meets the closed tool solid (crosses its surface or lies inside it).
bool LocalSubtractor::Impl::touchesTool(std::uint32_t slot, const SM& tool,
                                        CGAL::Side_of_triangle_mesh<SM, EK>& side) const {
  const EK::Triangle_3 t = triangle(slot);
  for (int i = 0; i < 3; ++i)
    if (side(t[i]) != CGAL::ON_UNBOUNDED_SIDE) return true;
  const CGAL::Bbox_3 tb = t.bbox();
  const bool degenerate = t.is_degenerate();  // then its edges are tested (points were tested above)
  for (FI f : tool.faces()) {
    const auto v = faceVertices(tool, f);
    const EK::Triangle_3 u(tool.point(v[0]), tool.point(v[1]), tool.point(v[2]));
    if (!CGAL::do_overlap(tb, u.bbox())) continue;
    if (!degenerate) {
      if (CGAL::do_intersect(t, u)) return true;
      continue;
    }
    for (int i = 0; i < 3; ++i)
      if (t[i] != t[(i + 1) % 3] && CGAL::do_intersect(EK::Segment_3(t[i], t[(i + 1) % 3]), u)) return true;
  }
  return false;
}

// Parity of exact crossings along an axis-parallel ray through the grid; a ray that grazes an edge or a
// vertex is discarded and the next axis tried. kUndecided when all six do.
Side LocalSubtractor::Impl::insideBone(const P& q) {
  std::vector<std::uint32_t> slots;
  for (int axis = 0; axis < 3; ++axis) {
    for (int dir : {1, -1}) {
      Box3 probe = Box3::empty();
      grow(probe, q);
      constexpr double inf = std::numeric_limits<double>::infinity();
      if (dir > 0) probe.hi[axis] = inf; else probe.lo[axis] = -inf;
      grid.query(probe, slots);
      EK::Vector_3 d(axis == 0 ? dir : 0, axis == 1 ? dir : 0, axis == 2 ? dir : 0);
      const EK::Ray_3 ray(q, d);
      bool clean = true;
      std::size_t crossings = 0;
      for (std::uint32_t s : slots) {
        if (defect[s] & csg::kDegenerate) continue;  // no area: cannot be crossed
        const EK::Triangle_3 t = triangle(s);
        if (!CGAL::do_intersect(ray, t)) continue;
        for (int i = 0; i < 3 && clean; ++i)
          if (CGAL::do_intersect(ray, EK::Segment_3(t[i], t[(i + 1) % 3]))) clean = false;
        if (!clean || t.has_on(q)) {
          clean = false;
          break;
        }
        ++crossings;
      }
      if (clean) return (crossings % 2) ? kInside : kOutside;
    }
  }
  return kUndecided;
}

// The band clean-up around the faces a cut made (live slots of the current state).
csg::CleanupPlan LocalSubtractor::Impl::planCleanup(const std::vector<std::uint32_t>& seeds, double deviationMm) {
  BandCleanup options = cleanup;
  options.maxDeviationMm = deviationMm;
  std::vector<std::uint32_t> live;
  for (std::uint32_t s : seeds)
    if (s != kNone && state.isTriangleLive(s)) live.push_back(s);
  return csg::planCutBandCleanup(
      state, grid, live, [&](std::uint32_t v) { return knownExactly(v); },
      [&](std::uint32_t s) { return s < defect.size() && defect[s] != 0; }, options);
}

// Commits a clean-up as its own delta; returns its 6 × volume change (removed − added, same origin as the
// cut's bookkeeping).
double LocalSubtractor::Impl::commitCleanup(const csg::CleanupPlan& plan, const Vec3& origin, LocalCut& cut) {
  cut.cleanupCollapses = plan.collapses;
  cut.cleanupFlips = plan.flips;
  cut.cleanupReplanned = plan.retested;
  const double change6 = removedVolume6(plan.delta, origin);
  if (!plan.delta.empty()) commit(plan.delta, [](const DeltaPlacement&) {});
  cut.cleanupVolumeMm3 = change6 / 6.0;
  return change6;
}

// 6 × the volume a delta removes (removed faces − added faces, divergence theorem about `origin`), in the
// document's rounded coordinates: from the changed faces only.
double LocalSubtractor::Impl::removedVolume6(const MeshDelta& delta, const Vec3& origin) const {
  auto at = [&](std::uint32_t r) {
    return MeshDelta::isNewVertex(r) ? delta.addedVertices[MeshDelta::newVertexIndex(r)] : state.vertex(r);
  };
  double v6 = 0;
  for (std::uint32_t s : delta.removedTriangles) {
    const Triangle& t = state.triangle(s);
    v6 += volumeTerm(origin, state.vertex(t[0]), state.vertex(t[1]), state.vertex(t[2]));
  }
  for (const Triangle& t : delta.addedTriangles) v6 -= volumeTerm(origin, at(t[0]), at(t[1]), at(t[2]));
  return v6;
}

// Applies a delta and keeps the side tables in step: the exact points of freed vertices are forgotten,
// `placed(placement)` records anything about the new slots before they are gridded (the exact points
// of new vertices, which their grid boxes use), and the removed and added faces are re-gridded.
template <class Placed>
void LocalSubtractor::Impl::commit(const MeshDelta& delta, Placed&& placed) {
  DeltaPlacement placement;
  BoneState next = state.applyDelta(delta, &placement);
  for (std::uint32_t s : delta.removedTriangles) {
    for (std::uint32_t v : state.triangle(s))
      if (!next.isVertexLive(v)) exact.erase(v);
    grid.remove(s);
  }
  placed(placement);
  state = std::move(next);
  if (defect.size() < state.triangleSlotCount()) defect.resize(state.triangleSlotCount(), 0);
  for (std::uint32_t s : placement.triangleSlots) {
    defect[s] = 0;
    grid.insert(s, boxOf(state.triangle(s)));
  }
}

LocalCut LocalSubtractor::Impl::redoWithMovedTool(const TriangleMesh& toolMesh, bool onBoneSurface,
                                                  std::chrono::steady_clock::time_point firstStart) {
  const Vec3 offset = nudge(++redoneCuts);
  TriangleMesh moved = toolMesh;
  for (Vec3& p : moved.vertices) p += offset;
  LocalCut again = subtractOnce(moved, false);
  again.redoneWithOffsetMm = norm(offset);
  again.toolMovedOffBoneSurface = onBoneSurface;
  again.milliseconds = elapsedMs(firstStart);  // the first attempt's time too
  return again;
}

LocalCut LocalSubtractor::Impl::subtractOnce(const TriangleMesh& toolMesh, bool mayRedo) {
  const auto start = std::chrono::steady_clock::now();
  auto lap = [last = start]() mutable {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
    return ms;
  };
  LocalCut cut;
  cut.volumeBeforeMm3 = cut.volumeAfterMm3 = state.volume();
  cut.facesAfter = state.liveTriangleCount();

  // The tool: checked on its indices (closed, oriented, outward); its box bounds everything it can touch.
  Box3 toolBox = Box3::empty();
  for (const Vec3& p : toolMesh.vertices) {
    if (!isFinite(p)) throw CutError(CutError::Kind::BadTool, "tool has a non-finite coordinate");
    toolBox.add(p);
  }
  const ToolTopology& topology = checkTool(toolMesh, toolTopology);
  if (cleanup.enabled)
    cut.cleanupDeviationMm = cleanup.maxDeviationMm > 0
                                 ? cleanup.maxDeviationMm
                                 : std::clamp(cleanup.deviationPerToolSag *
                                                  (referenceToolSagMm ? *referenceToolSagMm : toolTopology.sagOf(toolMesh)),
                                              BandCleanup::kMinAutoDeviationMm, BandCleanup::kMaxAutoDeviationMm);
  // A margin so that faces within rounding distance of the new ones are in the patch too (see below).
  Vec3 margin;
  for (int i = 0; i < 3; ++i) {
    margin[i] = 1e-9 * (1 + std::abs(toolBox.lo[i]) + std::abs(toolBox.hi[i]));
    toolBox.lo[i] -= margin[i];
    toolBox.hi[i] += margin[i];
  }
  // The tool's faces by box (widened by the margin), as Epick triangles with their degeneracy, for the near
  // test below: built on a second thread while this one gathers the bone faces near the tool. A tool that
  // turns out to miss the bone waits for it too (~0.15 ms for the glenoid reamer); the application only cuts
  // where its collision query found the tool's solid overlapping the bone, so that case is rare.
  using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
  auto ip = [](const Vec3& v) { return IK::Point_3(v.x, v.y, v.z); };
  // Collinear corners, decided by the three projected orientations (statically filtered: CGAL's
  // Collinear_3 evaluates in interval arithmetic with a rounding-mode switch on every call).
  auto degenerate = [](const IK::Triangle_3& t) {
    const IK::Point_3 &a = t[0], &b = t[1], &c = t[2];
    return CGAL::orientation(IK::Point_2(a.x(), a.y()), IK::Point_2(b.x(), b.y()), IK::Point_2(c.x(), c.y())) == CGAL::COLLINEAR &&
           CGAL::orientation(IK::Point_2(a.y(), a.z()), IK::Point_2(b.y(), b.z()), IK::Point_2(c.y(), c.z())) == CGAL::COLLINEAR &&
           CGAL::orientation(IK::Point_2(a.z(), a.x()), IK::Point_2(b.z(), b.x()), IK::Point_2(c.z(), c.x())) == CGAL::COLLINEAR;
  };
  csg::PackedTriangleGrid toolGrid;
  std::vector<IK::Triangle_3> toolTriangles;
  std::vector<char> toolDegenerate;
  std::vector<csg::PlaneSide> toolPlanes;  // lets the near test skip the pairs a tool face's plane separates
  auto toolFaces = csg::inBackground([&] {
    std::vector<Box3> boxes;
    boxes.reserve(toolMesh.triangles.size());
    toolTriangles.reserve(toolMesh.triangles.size());
    toolDegenerate.reserve(toolMesh.triangles.size());
    toolPlanes.reserve(toolMesh.triangles.size());
    for (const Triangle& t : toolMesh.triangles) {
      toolPlanes.emplace_back(toolMesh.vertices[t[0]], toolMesh.vertices[t[1]], toolMesh.vertices[t[2]]);
      Box3 b = Box3::empty();
      for (std::uint32_t v : t) {
        b.add(toolMesh.vertices[v] - margin);
        b.add(toolMesh.vertices[v] + margin);
      }
      boxes.push_back(b);
      toolTriangles.emplace_back(ip(toolMesh.vertices[t[0]]), ip(toolMesh.vertices[t[1]]), ip(toolMesh.vertices[t[2]]));
      toolDegenerate.push_back(!toolPlanes.back().proper() && degenerate(toolTriangles.back()));
    }
    toolGrid.build(toolBox.bounds(), std::move(boxes), 4.0);
  });
  {
    // Only faces within the tool's bound can touch it (cells wholly beyond it are skipped, then faces).
    // Faces at a vertex known exactly stay (see `near`).
    double scale = 1;
    for (int i = 0; i < 3; ++i) scale = std::max({scale, std::abs(toolBox.lo[i]), std::abs(toolBox.hi[i])});
    csg::ToolBound bound;
    bound.fit(toolMesh, topology.boundFaces, 1e-6 + 1e-8 * scale);
    if (exact.empty())
      grid.query(toolBox, [&](const Box3& cell) { return bound.mayMeet(cell); }, candidates);
    else
      grid.query(toolBox, candidates);
    std::size_t kept = 0;
    for (std::uint32_t s : candidates) {
      const Triangle& t = state.triangle(s);
      if (bound.mayMeet(state.vertex(t[0]), state.vertex(t[1]), state.vertex(t[2])) || knownExactly(t[0]) ||
          knownExactly(t[1]) || knownExactly(t[2]))
        candidates[kept++] = s;
    }
    candidates.resize(kept);
    // In slot order, so that the result does not depend on how the grid found them (the patch's order
    // decides ties in the corefinement's triangulations).
    std::sort(candidates.begin(), candidates.end());
  }
  cut.candidateFaces = candidates.size();
  // No face near the tool: it misses the bone, unless it is buried inside it (then it leaves a cavity,
  // found by the ray parity below). A tool not within the bone's box cannot be buried.
  const Bounds& bb = state.bounds();
  const bool mayBeBuried = toolBox.lo[0] > bb.min.x && toolBox.lo[1] > bb.min.y && toolBox.lo[2] > bb.min.z &&
                           toolBox.hi[0] < bb.max.x && toolBox.hi[1] < bb.max.y && toolBox.hi[2] < bb.max.z;
  if (candidates.empty() && !mayBeBuried) {
    cut.milliseconds = elapsedMs(start);
    return cut;
  }

  // The whole tool as an exact closed mesh, only for the rare exact side tests.
  std::optional<SM> wholeTool;
  std::optional<CGAL::Side_of_triangle_mesh<SM, EK>> side;
  auto sideOf = [&]() -> CGAL::Side_of_triangle_mesh<SM, EK>& {
    if (!side) side.emplace(exactTool(toolMesh, wholeTool));
    return *side;
  };
  // Defect faces may stay out of the patch when they do not touch the tool (the patch only has to hold
  // every face that does); one that touches it stops the cut.
  std::vector<std::uint32_t> patchSlots;
  patchSlots.reserve(candidates.size());
  for (std::uint32_t s : candidates) {
    if (defect[s] == 0) {
      patchSlots.push_back(s);
      continue;
    }
    if (touchesTool(s, exactTool(toolMesh, wholeTool), sideOf())) {
      const char* what = (defect[s] & csg::kSelfIntersecting) ? "self-intersecting"
                         : (defect[s] & csg::kNonManifold)    ? "non-manifold"
                                                              : "degenerate";
      throw CutError(CutError::Kind::DefectReached, std::string("the tool touches a ") + what +
                                                        " bone face (slot " + std::to_string(s) +
                                                        "); the bone is unchanged");
    }
  }

  // Near and far: only bone and tool faces that meet a face of the other side can cross it; the Boolean
  // runs on those (`nearBone`, `nearTool`). A connected group of far faces lies wholly on one side of the
  // other surface and takes the side of the near faces it borders (or of one point test), so the far
  // faces are classified without being corefined: most of the patch and of the tool. Which faces meet is
  // decided exactly for each pair whose boxes meet (Epick: exact predicates on the doubles); bone faces at
  // a vertex known exactly are near without a test. Bone faces whose boxes meet a tool face's box (widened
  // by the margin) but that do not meet it are `closeBone`: the rounding check must see them.
  std::vector<char> nearBone(patchSlots.size(), 0), nearTool(toolMesh.triangles.size(), 0);
  std::vector<char> closeBone(patchSlots.size(), 0);
  toolFaces.get();
  // A bone face that meets a tool face lying all but in its plane (all three corners within kOnToolFaceMm
  // of the tool face's plane, not all exactly on it): the tool lies on the bone's surface to rounding, as
  // the walls of consecutive cuts do on a feed along a tilted axis (the same wall, moved along the axis,
  // off its old plane by the rounding of the new coordinates). The two faces cross at a grazing angle in
  // needles whose corners the corefinement evaluates slowly (~20 ms instead of ~4 at the bundled glenoid)
  // and that rounding would fold, so the cut is made with the tool moved by a nanometre (below) before it
  // is corefined. Faces exactly in one plane are left to the corefinement's coplanar case.
  auto liesOnToolFace = [&](const IK::Triangle_3& bone, std::uint32_t toolFace) {
    const Triangle& t = toolMesh.triangles[toolFace];
    const Vec3 &a = toolMesh.vertices[t[0]], &b = toolMesh.vertices[t[1]], &c = toolMesh.vertices[t[2]];
    const Vec3 n = normalized(cross(b - a, c - a));
    if (!isFinite(n)) return false;
    bool offPlane = false;
    const IK::Triangle_3& ft = toolTriangles[toolFace];
    for (int k = 0; k < 3; ++k) {
      const IK::Point_3& q = bone[k];
      if (!(std::abs(dot(n, Vec3{q.x(), q.y(), q.z()} - a)) <= kOnToolFaceMm)) return false;
      offPlane = offPlane || CGAL::orientation(ft[0], ft[1], ft[2], q) != CGAL::COPLANAR;
    }
    return offPlane;
  };
  bool toolOnBone = false;
  {
    // Each bone face against the tool faces whose boxes meet its box; the faces are split between this
    // thread and a second one (the tests are independent and read-only), each with its own tool flags.
    auto testRange = [&](std::size_t begin, std::size_t end, std::vector<char>& toolFlags, char& onTool) {
      std::vector<std::uint32_t> hits;
      for (std::size_t i = begin; i < end; ++i) {
        toolGrid.query(grid.box(patchSlots[i]), hits);
        if (hits.empty()) continue;
        const Triangle& t = state.triangle(patchSlots[i]);
        const IK::Triangle_3 bt(ip(state.vertex(t[0])), ip(state.vertex(t[1])), ip(state.vertex(t[2])));
        // Faces with a vertex known exactly are only known rounded here; degenerate ones cannot be tested.
        const Vec3 &p0 = state.vertex(t[0]), &p1 = state.vertex(t[1]), &p2 = state.vertex(t[2]);
        const csg::PlaneSide bonePlane(p0, p1, p2);
        const bool testable = !knownExactly(t[0]) && !knownExactly(t[1]) && !knownExactly(t[2]) &&
                              (bonePlane.proper() || !degenerate(bt));
        // Separated by either face's plane, proven in doubles (most pairs: a bone face micrometres beside a
        // reamer facet), the two do not meet; the others are decided exactly.
        auto apart = [&](std::uint32_t h) {
          const Triangle& f = toolMesh.triangles[h];
          return toolPlanes[h].separates(p0, p1, p2) ||
                 bonePlane.separates(toolMesh.vertices[f[0]], toolMesh.vertices[f[1]], toolMesh.vertices[f[2]]);
        };
        for (std::uint32_t h : hits)
          if (!testable || toolDegenerate[h] || (!apart(h) && CGAL::do_intersect(bt, toolTriangles[h]))) {
            nearBone[i] = toolFlags[h] = 1;
            if (mayRedo && testable && !onTool && liesOnToolFace(bt, h)) onTool = 1;  // only a first attempt acts on it
          }
        closeBone[i] = !nearBone[i];
      }
    };
    std::vector<char> secondNearTool(nearTool.size(), 0);  // the second part's tool flags
    char onTool[2] = {0, 0};
    csg::splitOverTwoThreads(patchSlots.size(), kParallelNearTestFaces, [&](std::size_t b, std::size_t e, int part) {
      testRange(b, e, part == 0 ? nearTool : secondNearTool, onTool[part]);
    });
    toolOnBone = onTool[0] || onTool[1];
    for (std::size_t h = 0; h < secondNearTool.size(); ++h) nearTool[h] |= secondNearTool[h];
    // Faces at vertices known exactly are near even when no tool box meets theirs: the rounding check must
    // see them, since new faces at such a vertex are tested in its rounded position.
    if (!exact.empty())
      for (std::size_t i = 0; i < patchSlots.size(); ++i) {
        for (std::uint32_t v : state.triangle(patchSlots[i])) nearBone[i] |= knownExactly(v);
        closeBone[i] &= !nearBone[i];
      }
  }

  if (toolOnBone && mayRedo) return redoWithMovedTool(toolMesh, true, start);

  // The patch (near bone faces, with the exact coordinates of earlier cuts) and the near tool faces.
  SM patch, tool;
  patch.set_recycle_garbage(false);  // new elements must not inherit the properties of removed ones
  auto slotOfV = patch.add_property_map<VI, std::uint32_t>("v:slot", kNone).first;
  auto origOfF = patch.add_property_map<FI, std::uint32_t>("f:orig", kNone).first;
  std::unordered_map<std::uint32_t, VI> patchVertex;  // bone vertex slot → patch vertex
  patchVertex.reserve(patchSlots.size());
  for (std::uint32_t i = 0; i < patchSlots.size(); ++i) {
    if (!nearBone[i]) continue;
    const Triangle& t = state.triangle(patchSlots[i]);
    VI v[3];
    for (int k = 0; k < 3; ++k) {
      auto [it, added] = patchVertex.try_emplace(t[k]);
      if (added) {
        it->second = patch.add_vertex(point(t[k]));
        slotOfV[it->second] = t[k];
      }
      v[k] = it->second;
    }
    const FI f = patch.add_face(v[0], v[1], v[2]);
    if (f == SM::null_face())
      throw CutError(CutError::Kind::DefectReached,
                     "the bone surface is not manifold near the cut (slot " + std::to_string(patchSlots[i]) +
                         "); the bone is unchanged");
    origOfF[f] = i;
    ++cut.patchFaces;
  }
  std::vector<VI> toolVertex(toolMesh.vertices.size(), SM::null_vertex());  // tool vertex → near-tool vertex
  for (std::uint32_t i = 0; i < toolMesh.triangles.size(); ++i) {
    if (!nearTool[i]) continue;
    VI v[3];
    for (int k = 0; k < 3; ++k) {
      VI& w = toolVertex[toolMesh.triangles[i][k]];
      if (w == SM::null_vertex()) {
        const Vec3& p = toolMesh.vertices[toolMesh.triangles[i][k]];
        w = tool.add_vertex(P(p.x, p.y, p.z));
      }
      v[k] = w;
    }
    if (tool.add_face(v[0], v[1], v[2]) == SM::null_face())
      throw CutError(CutError::Kind::BadTool, "tool is not an oriented 2-manifold triangle mesh");
    ++cut.nearToolFaces;
  }
  // Far faces grouped on a second thread while the corefinement runs: it reads the bone, the tool mesh,
  // the near flags and the vertex maps, none of which the corefinement touches (it edits only the two SMs).
  csg::FarFaceGroups<VI> farBoneGroups, farToolGroups;
  auto farGrouping = csg::inBackground([&] {
    // Far bone faces: through a map of their directed edges.
    for (std::uint32_t i = 0; i < patchSlots.size(); ++i)
      if (!nearBone[i]) farBoneGroups.faces.push_back(i);
    auto boneTriangle = [&](std::size_t j) -> const Triangle& { return state.triangle(patchSlots[farBoneGroups.faces[j]]); };
    std::unordered_map<std::uint64_t, std::uint32_t> farEdge;
    farEdge.reserve(3 * farBoneGroups.faces.size());
    for (std::uint32_t j = 0; j < farBoneGroups.faces.size(); ++j)
      for (int i = 0; i < 3; ++i) farEdge.emplace(directedKey(boneTriangle(j)[i], boneTriangle(j)[(i + 1) % 3]), j);
    auto patchVertexOf = [&](std::uint32_t slot) {
      const auto it = patchVertex.find(slot);
      return it == patchVertex.end() ? SM::null_vertex() : it->second;
    };
    farBoneGroups.group(
        [&](std::size_t j, int i) {
          const auto it = farEdge.find(directedKey(boneTriangle(j)[(i + 1) % 3], boneTriangle(j)[i]));
          return it == farEdge.end() ? kNone : it->second;
        },
        [&](std::size_t j, int i, VI& b, VI& a) {
          b = patchVertexOf(boneTriangle(j)[(i + 1) % 3]);
          a = patchVertexOf(boneTriangle(j)[i]);
          return b != SM::null_vertex() && a != SM::null_vertex();
        });
    // Far tool faces: through the tool's face adjacency.
    std::vector<std::uint32_t> farIndex(toolMesh.triangles.size(), kNone);
    for (std::uint32_t i = 0; i < toolMesh.triangles.size(); ++i)
      if (!nearTool[i]) {
        farIndex[i] = std::uint32_t(farToolGroups.faces.size());
        farToolGroups.faces.push_back(i);
      }
    farToolGroups.group(
        [&](std::size_t j, int i) { return farIndex[topology.across[farToolGroups.faces[j]][i]]; },
        [&](std::size_t j, int i, VI& b, VI& a) {
          const Triangle& t = toolMesh.triangles[farToolGroups.faces[j]];
          b = toolVertex[t[(i + 1) % 3]];
          a = toolVertex[t[i]];
          return b != SM::null_vertex() && a != SM::null_vertex();
        });
  });
  cut.phaseMilliseconds.setup = lap();
  auto conP = patch.add_property_map<EI, bool>("e:c", false).first;
  auto conT = tool.add_property_map<EI, bool>("e:c", false).first;
  if (!patch.is_empty()) {
    try {
      csg_detail::ExactAheadVisitor<SM> exactAhead;
      PMP::corefine(patch, tool, CGAL::parameters::edge_is_constrained_map(conP).visitor(exactAhead),
                    CGAL::parameters::edge_is_constrained_map(conT));
    } catch (const std::exception& e) {
      throw CutError(CutError::Kind::Inconsistent, std::string("corefinement failed: ") + e.what());
    }
  }
  cut.phaseMilliseconds.corefine = lap();

  // Intersection curve: patch vertices on it get unified ids shared with the tool's copies.
  const std::uint32_t nP = std::uint32_t(patch.number_of_vertices());
  const std::uint32_t nT = std::uint32_t(tool.number_of_vertices());
  std::unordered_multimap<ApproxKey, std::uint32_t, ApproxHash> curve;
  auto findOnCurve = [&](const P& p) -> std::uint32_t {
    const auto range = curve.equal_range(approxKey(p));
    std::uint32_t found = kNone;
    std::size_t n = 0;
    for (auto it = range.first; it != range.second; ++it, ++n) found = it->second;
    if (n <= 1) return found;
    for (auto it = range.first; it != range.second; ++it)
      if (patch.point(VI(it->second)) == p) return it->second;
    return kNone;
  };
  // The curve's edges of each side by key (sorted below; vectors, not maps: no allocation per edge).
  std::vector<std::pair<std::uint64_t, HI>> patchEdge, toolEdge;
  auto sortByKey = [](std::vector<std::pair<std::uint64_t, HI>>& edges) {
    std::stable_sort(edges.begin(), edges.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    edges.erase(std::unique(edges.begin(), edges.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
                edges.end());
  };
  std::vector<char> visitedCurve(nP, 0);
  for (EI e : patch.edges()) {
    if (!conP[e]) continue;
    const HI h = patch.halfedge(e);
    if (patch.is_border(e))
      throw CutError(CutError::Kind::OpenBorderReached,
                     "the cut reaches an open border of the bone surface; the bone is unchanged");
    for (VI v : {patch.source(h), patch.target(h)}) {
      if (CGAL::is_border(v, patch))
        throw CutError(CutError::Kind::OpenBorderReached,
                       "the cut touches an open border of the bone surface; the bone is unchanged");
      if (!visitedCurve[v.idx()]) {
        visitedCurve[v.idx()] = 1;
        curve.emplace(approxKey(patch.point(v)), std::uint32_t(v.idx()));
      }
    }
    patchEdge.emplace_back(pairKey(patch.source(h).idx(), patch.target(h).idx()), h);
  }
  sortByKey(patchEdge);
  // Unified ids: patch vertices [0, nP), near-tool vertices [nP, nP + nT) unless on the curve, other tool
  // vertices nP + nT + their index in the tool mesh.
  std::vector<std::uint32_t> toolUid(nT);
  for (VI v : tool.vertices()) toolUid[v.idx()] = nP + std::uint32_t(v.idx());
  for (EI e : tool.edges()) {
    if (!conT[e]) continue;
    const HI h = tool.halfedge(e);
    for (VI v : {tool.source(h), tool.target(h)}) {
      const std::uint32_t twin = findOnCurve(tool.point(v));
      if (twin == kNone)
        throw CutError(CutError::Kind::Inconsistent, "an intersection vertex of the tool has no bone twin");
      toolUid[v.idx()] = twin;
    }
    toolEdge.emplace_back(pairKey(toolUid[tool.source(h).idx()], toolUid[tool.target(h).idx()]), h);
  }
  sortByKey(toolEdge);
  if (toolEdge.size() != patchEdge.size())
    throw CutError(CutError::Kind::Inconsistent, "the intersection curves of bone and tool differ");
  const std::uint32_t uidCount = nP + nT + std::uint32_t(toolMesh.vertices.size());
  auto toolVertexUid = [&](std::uint32_t v) {
    return toolVertex[v] != SM::null_vertex() ? toolUid[toolVertex[v].idx()] : nP + nT + v;
  };
  auto uidPoint = [&](std::uint32_t uid) -> P {
    if (uid < nP) return patch.point(VI(uid));
    if (uid < nP + nT) return tool.point(VI(uid - nP));
    const Vec3& p = toolMesh.vertices[uid - nP - nT];
    return P(p.x, p.y, p.z);
  };

  // Classify components: at an intersection edge, the exact wedge test against the other surface.
  int nPC = 0, nTC = 0;
  const std::vector<int> pcomp = components(patch, conP, nPC);
  const std::vector<int> tcomp = components(tool, conT, nTC);
  std::vector<Side> pside(nPC, kUndecided), tside(nTC, kUndecided);
  for (std::size_t k = 0; k < patchEdge.size(); ++k) {  // the same keys in the same order, or they differ
    const HI hp0 = patchEdge[k].second;
    if (toolEdge[k].first != patchEdge[k].first)
      throw CutError(CutError::Kind::Inconsistent, "the intersection curves of bone and tool differ");
    const HI ht0 = toolEdge[k].second;
    for (HI hp : {hp0, patch.opposite(hp0)}) {  // patch faces against the tool's wedge
      const int c = pcomp[patch.face(hp).idx()];
      if (pside[c] != kUndecided) continue;
      // Orient the tool halfedge like hp (a → b) or take its opposite.
      const bool same = toolUid[tool.source(ht0).idx()] == patch.source(hp).idx();
      const HI t = same ? ht0 : tool.opposite(ht0);
      if (tool.is_border(t) || tool.is_border(tool.opposite(t)))
        throw CutError(CutError::Kind::Inconsistent, "the intersection curve reaches the border of the near tool");
      pside[c] = wedgeSide(tool.point(tool.source(t)), tool.point(tool.target(t)),
                           tool.point(tool.target(tool.next(t))),
                           tool.point(tool.target(tool.next(tool.opposite(t)))),
                           patch.point(patch.target(patch.next(hp))), kInside, kOutside);
    }
    for (HI ht : {ht0, tool.opposite(ht0)}) {  // tool faces against the bone's wedge
      const int c = tcomp[tool.face(ht).idx()];
      if (tside[c] != kUndecided) continue;
      const bool same = patch.source(hp0).idx() == toolUid[tool.source(ht).idx()];
      const HI p = same ? hp0 : patch.opposite(hp0);
      tside[c] = wedgeSide(patch.point(patch.source(p)), patch.point(patch.target(p)),
                           patch.point(patch.target(patch.next(p))),
                           patch.point(patch.target(patch.next(patch.opposite(p)))),
                           tool.point(tool.target(tool.next(ht))), kOutside, kOutside);
    }
  }
  std::vector<char> pHasCurve(nPC, 0), tHasCurve(nTC, 0);
  for (const auto& [key, hp] : patchEdge) {
    pHasCurve[pcomp[patch.face(hp).idx()]] = 1;
    pHasCurve[pcomp[patch.face(patch.opposite(hp)).idx()]] = 1;
  }
  for (const auto& [key, ht] : toolEdge) {
    tHasCurve[tcomp[tool.face(ht).idx()]] = 1;
    tHasCurve[tcomp[tool.face(tool.opposite(ht)).idx()]] = 1;
  }

  // Far faces join the components they border; groups left without a side get one point test.
  // The component of the near face with the directed edge b → a in `mesh`, or −1.
  auto nearComponent = [](const SM& mesh, const std::vector<int>& comp, VI b, VI a) {
    const auto h = CGAL::halfedge(b, a, mesh);
    return h.second && !mesh.is_border(h.first) ? comp[mesh.face(h.first).idx()] : -1;
  };
  farGrouping.get();
  farBoneGroups.joinNear(std::size_t(nPC), [&](VI b, VI a) { return nearComponent(patch, pcomp, b, a); });
  farToolGroups.joinNear(std::size_t(nTC), [&](VI b, VI a) { return nearComponent(tool, tcomp, b, a); });
  csg::SideGroups& boneGroups = farBoneGroups.groups;
  csg::SideGroups& toolGroups = farToolGroups.groups;
  const std::vector<std::uint32_t>& farBone = farBoneGroups.faces;  // patchSlots indices
  const std::vector<std::uint32_t>& farTool = farToolGroups.faces;  // tool triangle indices
  for (int c = 0; c < nPC; ++c)
    if (!boneGroups.setSide(boneGroups.near(std::size_t(c)), pside[c]))
      throw CutError(CutError::Kind::Inconsistent, "bone faces on one side of the tool were classified apart");
  for (int c = 0; c < nTC; ++c)
    if (!toolGroups.setSide(toolGroups.near(std::size_t(c)), tside[c]))
      throw CutError(CutError::Kind::Inconsistent, "tool faces on one side of the bone were classified apart");
  auto toolSideOf = [&](const P& q) {
    const auto s = sideOf()(q);
    return s == CGAL::ON_BOUNDARY ? kUndecided : s == CGAL::ON_BOUNDED_SIDE ? kInside : kOutside;
  };
  // The same for a point with double coordinates, without an exact tool: parity of the tool faces an
  // axis-parallel ray crosses, each decided by exact predicates on the doubles (Epick); a ray through an
  // edge or a vertex of a face (in projection) is dropped and the next axis tried.
  std::vector<std::uint32_t> rayHits;
  auto toolSideOfDouble = [&](const Vec3& q) -> Side {
    for (int axis = 0; axis < 3; ++axis) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) is right-handed
      auto p2 = [&](const Vec3& v) { return IK::Point_2(v[u], v[w]); };
      const IK::Point_2 q2 = p2(q);
      toolGrid.ray({q.x, q.y, q.z}, axis, 1, rayHits);
      bool clean = true;
      std::size_t crossings = 0;
      for (std::uint32_t h : rayHits) {
        const Triangle& t = toolMesh.triangles[h];
        const Vec3 &a = toolMesh.vertices[t[0]], &b = toolMesh.vertices[t[1]], &c = toolMesh.vertices[t[2]];
        const auto o2 = CGAL::orientation(p2(a), p2(b), p2(c));  // the sign of the normal's axis component
        const auto sab = CGAL::orientation(p2(a), p2(b), q2), sbc = CGAL::orientation(p2(b), p2(c), q2),
                   sca = CGAL::orientation(p2(c), p2(a), q2);
        if (o2 == CGAL::COLLINEAR) {
          // Seen edge-on: the ray can only graze it, which the faces around it decide unless q's line
          // passes along it.
          if (sab == CGAL::COLLINEAR || sbc == CGAL::COLLINEAR || sca == CGAL::COLLINEAR) clean = false;
          if (!clean) break;
          continue;
        }
        if (sab == CGAL::COLLINEAR || sbc == CGAL::COLLINEAR || sca == CGAL::COLLINEAR) {
          // Through an edge or a vertex in projection: decide with another axis, unless q misses the face.
          if ((sab == o2 || sab == CGAL::COLLINEAR) && (sbc == o2 || sbc == CGAL::COLLINEAR) &&
              (sca == o2 || sca == CGAL::COLLINEAR)) {
            clean = false;
            break;
          }
          continue;
        }
        if (sab != o2 || sbc != o2 || sca != o2) continue;  // q's line misses the face
        const auto o3 = CGAL::orientation(IK::Point_3(a.x, a.y, a.z), IK::Point_3(b.x, b.y, b.z),
                                          IK::Point_3(c.x, c.y, c.z), IK::Point_3(q.x, q.y, q.z));
        if (o3 == CGAL::COPLANAR) return kUndecided;  // q lies on the tool's surface
        // The line meets the face's plane ahead of q (along +axis) when q is below the plane as seen from
        // +axis: orientation(a, b, c, q) = sign(n · (q − a)) opposite to the sign of n's axis component.
        if (o3 != o2) ++crossings;
      }
      if (clean) return (crossings % 2) ? kInside : kOutside;
    }
    return kUndecided;
  };
  for (FI f : patch.faces()) {
    const int c = pcomp[f.idx()];
    if (pside[c] != kUndecided || pHasCurve[c]) continue;
    if ((pside[c] = boneGroups.side(boneGroups.near(std::size_t(c)))) != kUndecided) continue;
    const auto v = faceVertices(patch, f);
    boneGroups.setSide(boneGroups.near(std::size_t(c)), pside[c] = toolSideOf(CGAL::centroid(patch.point(v[0]), patch.point(v[1]), patch.point(v[2]))));
  }
  for (std::size_t j = 0; j < farBone.size(); ++j) {
    const std::size_t e = boneGroups.far(j);
    if (boneGroups.side(e) != kUndecided) continue;
    // A far face does not meet the tool's surface: all of it lies on the side of any of its points.
    const Triangle& t = state.triangle(patchSlots[farBone[j]]);
    Side side = kUndecided;
    for (int k = 0; k < 3 && side == kUndecided; ++k)
      if (!knownExactly(t[k])) side = toolSideOfDouble(state.vertex(t[k]));
    if (side == kUndecided) side = toolSideOf(CGAL::centroid(point(t[0]), point(t[1]), point(t[2])));
    boneGroups.setSide(e, side);
  }
  for (FI f : tool.faces()) {
    const int c = tcomp[f.idx()];
    if (tside[c] != kUndecided || tHasCurve[c]) continue;
    if ((tside[c] = toolGroups.side(toolGroups.near(std::size_t(c)))) != kUndecided) continue;
    const auto v = faceVertices(tool, f);
    toolGroups.setSide(toolGroups.near(std::size_t(c)), tside[c] = insideBone(CGAL::centroid(tool.point(v[0]), tool.point(v[1]), tool.point(v[2]))));
  }
  for (std::size_t j = 0; j < farTool.size(); ++j) {
    const std::size_t e = toolGroups.far(j);
    if (toolGroups.side(e) != kUndecided) continue;
    const Triangle& t = toolMesh.triangles[farTool[j]];
    toolGroups.setSide(e, insideBone(CGAL::centroid(uidPoint(nP + nT + t[0]), uidPoint(nP + nT + t[1]),
                                                     uidPoint(nP + nT + t[2]))));
  }
  auto undecided = [](const std::vector<Side>& sides) {
    return std::find(sides.begin(), sides.end(), kUndecided) != sides.end();
  };
  if (undecided(pside) || undecided(tside) || boneGroups.anyFarUndecided() || toolGroups.anyFarUndecided())
    throw CutError(CutError::Kind::Degenerate,
                   "coplanar or tangential contact between tool and bone; the bone is unchanged");

  bool anyInside = false;
  for (Side s : pside) anyInside |= s == kInside;
  for (Side s : tside) anyInside |= s == kInside;
  for (std::size_t j = 0; j < farBone.size(); ++j) anyInside |= boneGroups.side(boneGroups.far(j)) == kInside;
  for (std::size_t j = 0; j < farTool.size(); ++j) anyInside |= toolGroups.side(toolGroups.far(j)) == kInside;
  if (!anyInside) {
    cut.milliseconds = elapsedMs(start);
    return cut;
  }

  // The new surface in unified vertex ids: kept patch faces, and tool faces inside the bone reversed.
  std::vector<std::array<std::uint32_t, 3>> kept;  // all kept faces of the Boolean (for the closedness check)
  std::vector<std::array<std::uint32_t, 3>> added;
  std::vector<std::uint32_t> addedKept;  // the index in `kept` of each added face
  std::vector<std::uint32_t> removed;
  std::vector<char> origSeenUnchanged(patchSlots.size(), 0);
  const Vec3 o = {0.5 * (toolBox.lo[0] + toolBox.hi[0]), 0.5 * (toolBox.lo[1] + toolBox.hi[1]),
                  0.5 * (toolBox.lo[2] + toolBox.hi[2])};
  double piece6 = 0;
  auto pieceTerm = [&](const P& a, const P& b, const P& c) { piece6 += volumeTerm(o, rounded(a), rounded(b), rounded(c)); };
  // The rounded point of a unified id, without making an exact point for the tool's own vertices.
  auto uidRounded = [&](std::uint32_t uid) -> Vec3 {
    if (uid < nP) return rounded(patch.point(VI(uid)));
    if (uid < nP + nT) return rounded(tool.point(VI(uid - nP)));
    return toolMesh.vertices[uid - nP - nT];
  };
  for (FI f : patch.faces()) {
    const auto v = faceVertices(patch, f);
    const std::array<std::uint32_t, 3> ids = {std::uint32_t(v[0].idx()), std::uint32_t(v[1].idx()),
                                              std::uint32_t(v[2].idx())};
    if (pside[pcomp[f.idx()]] == kInside) {
      pieceTerm(patch.point(v[0]), patch.point(v[1]), patch.point(v[2]));
      continue;
    }
    kept.push_back(ids);
    const std::uint32_t orig = origOfF[f];
    if (orig != kNone) {
      const Triangle& t = state.triangle(patchSlots[orig]);
      const std::uint32_t s0 = slotOfV[v[0]], s1 = slotOfV[v[1]], s2 = slotOfV[v[2]];
      if ((s0 == t[0] && s1 == t[1] && s2 == t[2]) || (s0 == t[1] && s1 == t[2] && s2 == t[0]) ||
          (s0 == t[2] && s1 == t[0] && s2 == t[1])) {
        origSeenUnchanged[orig] = 1;
        continue;
      }
    }
    added.push_back(ids);
    addedKept.push_back(std::uint32_t(kept.size() - 1));
  }
  // Removed in slot order (the order decides which freed slots new faces reuse): near faces that did not
  // come through unchanged, and far faces inside the tool (the other far faces stay).
  for (std::uint32_t i = 0, j = 0; i < patchSlots.size(); ++i) {
    if (nearBone[i]) {
      if (!origSeenUnchanged[i]) removed.push_back(patchSlots[i]);
      continue;
    }
    if (boneGroups.side(boneGroups.far(j++)) != kInside) continue;
    const Triangle& t = state.triangle(patchSlots[i]);
    if (knownExactly(t[0]) || knownExactly(t[1]) || knownExactly(t[2]))
      pieceTerm(point(t[0]), point(t[1]), point(t[2]));
    else
      piece6 += volumeTerm(o, state.vertex(t[0]), state.vertex(t[1]), state.vertex(t[2]));
    removed.push_back(patchSlots[i]);
  }
  auto keepToolFace = [&](const std::array<std::uint32_t, 3>& ids) {
    piece6 += volumeTerm(o, uidRounded(ids[0]), uidRounded(ids[1]), uidRounded(ids[2]));
    const std::array<std::uint32_t, 3> reversed = {ids[0], ids[2], ids[1]};
    kept.push_back(reversed);
    added.push_back(reversed);
    addedKept.push_back(std::uint32_t(kept.size() - 1));
  };
  for (FI f : tool.faces()) {
    if (tside[tcomp[f.idx()]] != kInside) continue;
    const auto v = faceVertices(tool, f);
    keepToolFace({toolUid[v[0].idx()], toolUid[v[1].idx()], toolUid[v[2].idx()]});
  }
  for (std::size_t j = 0; j < farTool.size(); ++j) {
    if (toolGroups.side(toolGroups.far(j)) != kInside) continue;
    const Triangle& t = toolMesh.triangles[farTool[j]];
    keepToolFace({toolVertexUid(t[0]), toolVertexUid(t[1]), toolVertexUid(t[2])});
  }

  // Closedness check: every directed edge of the new surface is used once, and its twin is used too
  // unless it lies on the patch border (edges shared with faces outside the patch, or open borders).
  // Each use of an edge is one 64-bit key (smaller id, larger id, direction), sorted, so the uses of an edge
  // are neighbours: no map with a node per edge (that map was a third of the classification).
  {
    if (uidCount >= (std::uint32_t(1) << 31))
      throw CutError(CutError::Kind::Inconsistent, "the cut has too many vertices; the bone is unchanged");
    std::vector<std::uint64_t> uses;
    uses.reserve(3 * kept.size());
    for (const auto& t : kept)
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t a = t[i], b = t[(i + 1) % 3];
        uses.push_back((std::uint64_t(std::min(a, b)) << 33) | (std::uint64_t(std::max(a, b)) << 1) | (a > b ? 1u : 0u));
      }
    std::sort(uses.begin(), uses.end());
    if (std::adjacent_find(uses.begin(), uses.end()) != uses.end())
      throw CutError(CutError::Kind::Degenerate,
                     "the cut would leave a non-manifold edge (tangential contact); the bone is unchanged");
    for (std::size_t k = 0; k < uses.size(); ++k) {
      if (k + 1 < uses.size() && (uses[k] >> 1) == (uses[k + 1] >> 1)) {  // used both ways
        ++k;
        continue;
      }
      const std::uint32_t lo = std::uint32_t(uses[k] >> 33), hi = std::uint32_t((uses[k] >> 1) & 0xffffffffu);
      const bool reversed = (uses[k] & 1) != 0;
      const std::uint32_t a = reversed ? hi : lo, b = reversed ? lo : hi;  // the edge a → b has no twin
      bool onPatchBorder = false;
      if (a < nP && b < nP) {
        const auto h = CGAL::halfedge(VI(a), VI(b), patch);
        onPatchBorder = h.second && patch.is_border(patch.opposite(h.first));
      }
      if (!onPatchBorder)
        throw CutError(CutError::Kind::Inconsistent, "the cut would leave an open seam; the bone is unchanged");
    }
  }

  // The new faces in a canonical order, so that the same cut gives the same slots, vertex order and (through
  // the clean-up, which follows that order) the same surface in every run. CGAL's corefinement makes its
  // vertices and faces in an order that follows the addresses of its boxes where box coordinates tie
  // (Box_intersection_d's ID_FROM_BOX_ADDRESS), as they do on axis-aligned and coplanar faces: a flat
  // reamer moved sideways cut different surfaces in the first and later runs of one process (session 25).
  // Vertices rank by their old slot, else by their rounded coordinates (then exactly); each face starts at
  // its lowest-ranked vertex (orientation kept), and faces sort by their ranks.
  std::vector<Vec3> roundedOf(nP + nT);  // the new points' rounded coordinates, by unified id
  {
    std::vector<std::uint32_t> uids;
    uids.reserve(3 * added.size());
    for (const auto& t : added) uids.insert(uids.end(), t.begin(), t.end());
    std::sort(uids.begin(), uids.end());
    uids.erase(std::unique(uids.begin(), uids.end()), uids.end());
    struct Rank {
      std::uint32_t slot;  // kNone for a vertex that is not an old one
      Vec3 at;
      std::uint32_t uid;
    };
    std::vector<Rank> ranks;
    ranks.reserve(uids.size());
    for (std::uint32_t uid : uids) {
      const std::uint32_t slot = uid < nP ? slotOfV[VI(uid)] : kNone;
      if (slot == kNone && uid < nP + nT) roundedOf[uid] = rounded(uid < nP ? patch.point(VI(uid)) : tool.point(VI(uid - nP)));
      ranks.push_back({slot, slot != kNone ? Vec3{} : uid >= nP + nT ? toolMesh.vertices[uid - nP - nT] : roundedOf[uid], uid});
    }
    std::sort(ranks.begin(), ranks.end(), [&](const Rank& a, const Rank& b) {
      if (a.slot != b.slot) return a.slot < b.slot;  // old vertices first (kNone is the largest)
      if (a.slot != kNone) return false;
      if (a.at.x != b.at.x) return a.at.x < b.at.x;
      if (a.at.y != b.at.y) return a.at.y < b.at.y;
      if (a.at.z != b.at.z) return a.at.z < b.at.z;
      return CGAL::compare_xyz(uidPoint(a.uid), uidPoint(b.uid)) == CGAL::SMALLER;
    });
    std::vector<std::uint32_t> rankOf(uidCount, 0);
    for (std::uint32_t r = 0; r < ranks.size(); ++r) rankOf[ranks[r].uid] = r;
    std::vector<std::array<std::uint32_t, 4>> order;  // the face's ranks from its lowest, and its index
    order.reserve(added.size());
    for (std::uint32_t i = 0; i < added.size(); ++i) {
      auto& t = added[i];
      const std::uint32_t r0 = rankOf[t[0]], r1 = rankOf[t[1]], r2 = rankOf[t[2]];
      const int first = r0 <= r1 && r0 <= r2 ? 0 : r1 <= r2 ? 1 : 2;
      std::rotate(t.begin(), t.begin() + first, t.end());
      order.push_back({rankOf[t[0]], rankOf[t[1]], rankOf[t[2]], i});
    }
    std::sort(order.begin(), order.end());
    std::vector<std::array<std::uint32_t, 3>> sortedAdded;
    std::vector<std::uint32_t> sortedKept;
    sortedAdded.reserve(added.size());
    sortedKept.reserve(added.size());
    for (const auto& o : order) {
      sortedAdded.push_back(added[o[3]]);
      sortedKept.push_back(addedKept[o[3]]);
    }
    added.swap(sortedAdded);
    addedKept.swap(sortedKept);
  }

  // The delta: original slots for old vertices, new vertices in first-use order.
  MeshDelta delta;
  delta.removedTriangles = removed;
  std::vector<std::uint32_t> ref(uidCount, kNone);
  std::vector<std::optional<P>> newPoints;  // none for the tool's own vertices (doubles already)
  auto refOf = [&](std::uint32_t uid) {
    if (ref[uid] != kNone) return ref[uid];
    if (uid < nP && slotOfV[VI(uid)] != kNone) return ref[uid] = slotOfV[VI(uid)];
    if (uid >= nP + nT) {
      newPoints.emplace_back();
      delta.addedVertices.push_back(toolMesh.vertices[uid - nP - nT]);
    } else {
      newPoints.push_back(uidPoint(uid));  // exact values are only computed if they have to be kept (below)
      delta.addedVertices.push_back(roundedOf[uid]);
    }
    return ref[uid] = MeshDelta::newVertex(std::uint32_t(newPoints.size() - 1));
  };
  for (const auto& t : added) delta.addedTriangles.push_back({refOf(t[0]), refOf(t[1]), refOf(t[2])});

  double removed6 = removedVolume6(delta, o);
  cut.phaseMilliseconds.classify = lap();

  // New vertices are rounded to doubles when that is safe: the rounded new faces are neither degenerate
  // nor intersect each other or their kept neighbours. Then the engine forgets their exact values, which
  // keeps exact coordinates from compounding cut after cut; otherwise it keeps them (and the document's
  // rounded copy may self-intersect there, which checkInvariants reports).
  // Rounding moves the curve points and old vertices known exactly; the tool's own vertices (ids from nP
  // on, off the curve) and old double vertices stay where they are. Moved faces lie on the tool or on near
  // bone faces. Bone faces that are not near but stay are checked too when they are within the margin of
  // a tool face (`closeBone`); the others are more than the margin away from every tool face, so no moved
  // face comes near them.
  auto moves = [&](std::uint32_t uid) {
    if (uid >= nP) return false;
    const std::uint32_t s = slotOfV[VI(uid)];
    return s == kNone || knownExactly(s);
  };
  std::vector<std::uint32_t> moved;  // indices into kept
  for (std::size_t i = 0; i < added.size(); ++i) {
    const auto& t = added[i];
    if (moves(t[0]) || moves(t[1]) || moves(t[2])) moved.push_back(addedKept[i]);
  }
  // The check runs on a second thread, beside the commit and the clean-up's planning, which assume that
  // it passes (it nearly always does). If it fails, the exact points are kept after all and the clean-up
  // is planned again, since vertices known exactly must not move.
  std::vector<std::uint32_t> closeStaying;  // patchSlots indices of close bone faces outside the tool
  for (std::size_t i = 0, j = 0; i < patchSlots.size(); ++i) {
    if (nearBone[i]) continue;
    if (boneGroups.side(boneGroups.far(j++)) != kInside && closeBone[i]) closeStaying.push_back(std::uint32_t(i));
  }
  const BoneState before = state;  // the check reads old vertices while the commit replaces `state`
  const auto exactBefore = exact;   // usually empty; restored if the cut is made again (below)
  double checkMs = 0;
  auto roundingSafe = csg::inBackground([&] {
    const auto checkStart = std::chrono::steady_clock::now();
    // Close faces join `kept` (no longer needed by this thread's caller) with ids from uidCount on, unless
    // their vertices are patch vertices.
    std::vector<std::uint32_t> closeSlot;  // bone vertex slot of ids uidCount, uidCount + 1, ...
    std::unordered_map<std::uint32_t, std::uint32_t> closeId;
    auto idOf = [&](std::uint32_t slot) {
      const auto it = patchVertex.find(slot);
      if (it != patchVertex.end()) return std::uint32_t(it->second.idx());
      const auto [c, isNew] = closeId.try_emplace(slot, uidCount + std::uint32_t(closeSlot.size()));
      if (isNew) closeSlot.push_back(slot);
      return c->second;
    };
    for (std::uint32_t i : closeStaying) {
      const Triangle& t = before.triangle(patchSlots[i]);
      kept.push_back({idOf(t[0]), idOf(t[1]), idOf(t[2])});
    }
    bool safe = false;  // an exception here (out of memory) keeps the exact points: sound, never lost
    try {
      safe = roundingIsSafe(kept, added, moved, uidCount + closeSlot.size(), [&](std::uint32_t uid) {
        if (uid >= uidCount) return before.vertex(closeSlot[uid - uidCount]);
        // Every vertex of `kept` is an old slot or was given a reference with the added faces above.
        const std::uint32_t r = ref[uid] != kNone ? ref[uid] : slotOfV[VI(uid)];
        return MeshDelta::isNewVertex(r) ? delta.addedVertices[MeshDelta::newVertexIndex(r)] : before.vertex(r);
      });
    } catch (const std::exception&) {
    }
    checkMs = elapsedMs(checkStart);
    return safe;
  });

  std::vector<std::uint32_t> newFaceSlots, newVertexSlots;
  commit(delta, [&](const DeltaPlacement& placement) {
    for (std::uint32_t slot : placement.vertexSlots)
      if (slot != kNone) exact.erase(slot);  // rounded, unless the check fails (below)
    newFaceSlots = placement.triangleSlots;
    newVertexSlots = placement.vertexSlots;
  });
  cut.phaseMilliseconds.commit = lap();
  const auto cleanupStart = std::chrono::steady_clock::now();
  std::optional<csg::CleanupPlan> plan;
  if (cleanup.enabled) plan = planCleanup(newFaceSlots, cut.cleanupDeviationMm);
  double cleanupMs = elapsedMs(cleanupStart);
  lap();
  const bool keepExact = !roundingSafe.get() || failRoundingChecks;
  cut.phaseMilliseconds.rounding = lap();  // what the cut waited for the check
  cut.phaseMilliseconds.roundingCheck = checkMs;
  cut.roundingFailed = keepExact;
  if (keepExact && mayRedo && !failRoundingChecks) {
    // Rounding fails where the tool's surface lies exactly on the bone's (a flat reamer moved sideways at
    // one depth: its face on the floor it cut before, its sides on earlier walls): coplanar faces split
    // each other into slivers that rounding would fold. Kept exact, such points make every later cut there
    // slower (five 0.5 mm moves of a flat reamer went from 0.1 to 34 s a cut). The cut is rolled back and
    // made again with the tool moved by about a nanometre (nudge, never the same offset twice), which
    // leaves nothing coincident; only if that fails too are the exact points kept.
    for (std::uint32_t s : newFaceSlots) grid.remove(s);
    state = before;
    exact = exactBefore;
    for (std::uint32_t s : delta.removedTriangles) grid.insert(s, boxOf(state.triangle(s)));
    return redoWithMovedTool(toolMesh, false, start);
  }
  if (keepExact) {
    // The side table gets the exact points that rounding would have moved, and the new faces their boxes
    // from them.
    for (std::size_t i = 0; i < newPoints.size(); ++i) {
      const std::uint32_t slot = newVertexSlots[i];
      const Vec3& d = delta.addedVertices[i];
      if (slot == kNone || !newPoints[i] || P(d.x, d.y, d.z) == *newPoints[i]) continue;
      settle(*newPoints[i]);  // collapse the lazy history so later cuts do not re-evaluate it
      exact[slot] = *newPoints[i];
    }
    for (std::uint32_t s : newFaceSlots) grid.insert(s, boxOf(state.triangle(s)));
    if (plan) plan = planCleanup(newFaceSlots, cut.cleanupDeviationMm);
    cut.phaseMilliseconds.rounding += lap();
  }
  if (plan) {
    const auto commitStart = std::chrono::steady_clock::now();
    removed6 += commitCleanup(*plan, o, cut);
    cleanupMs += elapsedMs(commitStart);
  }
  cut.cleanupMilliseconds = cleanupMs;

  cut.changed = true;
  cut.removedMm3 = removed6 / 6.0;
  cut.removedPieceMm3 = piece6 / 6.0;
  cut.volumeAfterMm3 = state.volume();
  cut.facesAfter = state.liveTriangleCount();
  cut.removedFaces = removed.size();
  cut.addedFaces = delta.addedTriangles.size();
  // The patch meshes' exact points are lazy objects whose release walks their histories (~3 % of a bundled
  // glenoid cut): released on the second core, idle by now, instead of before this call returns. Their
  // representations may be shared with points kept here (reference counts are atomic) but nothing else.
  csg::startInBackground([meshes = std::make_shared<std::pair<SM, SM>>(std::move(patch), std::move(tool))] {});
  cut.milliseconds = elapsedMs(start);
  return cut;
}

LocalSubtractor::LocalSubtractor(const TriangleMesh& bone)
    : LocalSubtractor(bone.triangles.empty() ? BoneState() : BoneState::fromMesh(bone)) {}

LocalSubtractor::LocalSubtractor(const BoneState& bone) : impl_(std::make_unique<Impl>()) {
  if (bone.empty()) throw std::invalid_argument("bone mesh is empty");
  const auto start = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  m.state = bone;
  const TriangleMesh slots = slotSoup(m.state);
  const csg::DefectScan scan = csg::scanDefects(slots);
  m.defect = scan.flags;
  m.defects.borderEdges = scan.borderEdges;
  m.defects.selfIntersectingPairs = scan.selfIntersectingPairs;
  // Free slots hold (0, 0, 0): no area.
  m.grid.init(m.state.bounds(), m.state.liveTriangleCount(), 8.0, surfaceArea(slots));
  for (std::uint32_t s = 0; s < slots.triangles.size(); ++s) {
    if (!m.state.isTriangleLive(s)) {
      m.defect[s] = 0;
      continue;
    }
    const std::uint8_t f = m.defect[s];
    if (f & csg::kSelfIntersecting) ++m.defects.selfIntersectingFaces;
    if (f & csg::kNonManifold) ++m.defects.nonManifoldFaces;
    if (f & csg::kDegenerate) ++m.defects.degenerateFaces;
    m.grid.insert(s, m.boxOf(slots.triangles[s]));
  }
  m.defects.scanMilliseconds = elapsedMs(start);
}

LocalSubtractor::~LocalSubtractor() = default;
LocalSubtractor::LocalSubtractor(LocalSubtractor&&) noexcept = default;
LocalSubtractor& LocalSubtractor::operator=(LocalSubtractor&&) noexcept = default;

LocalCut LocalSubtractor::subtract(const TriangleMesh& tool) { return impl_->subtract(tool); }
void LocalSubtractor::setBandCleanup(const BandCleanup& cleanup) { impl_->cleanup = cleanup; }

void LocalSubtractor::setReferenceTool(const TriangleMesh& solid) { impl_->referenceToolSagMm = toolFacetSagMm(solid); }
void LocalSubtractor::failRoundingChecksForTesting(bool fail) { impl_->failRoundingChecks = fail; }
const BandCleanup& LocalSubtractor::bandCleanup() const { return impl_->cleanup; }
const BoneState& LocalSubtractor::state() const { return impl_->state; }
TriangleMesh LocalSubtractor::mesh() const { return impl_->state.toMesh(); }
double LocalSubtractor::volumeMm3() const { return impl_->state.volume(); }
std::size_t LocalSubtractor::faceCount() const { return impl_->state.liveTriangleCount(); }
std::size_t LocalSubtractor::exactVertexCount() const { return impl_->exact.size(); }
const LocalDefects& LocalSubtractor::defects() const { return impl_->defects; }

BoneInvariants LocalSubtractor::checkInvariants() const {
  using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
  const Impl& m = *impl_;
  SM exactMesh;
  CGAL::Surface_mesh<IK::Point_3> roundedMesh;
  std::unordered_map<std::uint32_t, std::pair<VI, CGAL::Surface_mesh<IK::Point_3>::Vertex_index>> vmap;
  bool manifold = true;
  std::vector<std::uint32_t> slotOfFace;  // the meshes' faces in the order they are added
  m.state.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    slotOfFace.push_back(slot);
    VI ve[3];
    CGAL::Surface_mesh<IK::Point_3>::Vertex_index vr[3];
    for (int k = 0; k < 3; ++k) {
      auto [it, added] = vmap.try_emplace(t[k]);
      if (added) {
        const Vec3& p = m.state.vertex(t[k]);
        it->second = {exactMesh.add_vertex(m.point(t[k])), roundedMesh.add_vertex({p.x, p.y, p.z})};
      }
      ve[k] = it->second.first;
      vr[k] = it->second.second;
    }
    if (exactMesh.add_face(ve[0], ve[1], ve[2]) == SM::null_face()) manifold = false;
    roundedMesh.add_face(vr[0], vr[1], vr[2]);
  });
  BoneInvariants inv;
  inv.inputSelfIntersectingPairs = m.defects.selfIntersectingPairs;
  if (!manifold) {
    // A non-manifold bone (a dirty input's own edges: a Surface_mesh cannot hold it) is scanned as a soup,
    // as on loading: a self-intersecting face that was not a self-intersecting defect then is new. Only the
    // rounded coordinates can be scanned; the exact ones are the same unless a vertex is kept exact.
    const csg::DefectScan scan = csg::scanDefects(slotSoup(m.state));
    bool anyNew = false;
    m.state.forEachLiveTriangle([&](std::uint32_t slot, const Triangle&) {
      const bool wasDefect = slot < m.defect.size() && (m.defect[slot] & csg::kSelfIntersecting) != 0;
      anyNew |= (scan.flags[slot] & csg::kSelfIntersecting) != 0 && !wasDefect;
    });
    inv.selfIntersectsRounded = scan.selfIntersectingPairs > 0;
    inv.newSelfIntersectionsRounded = anyNew;
    inv.selfIntersectsExact = m.exact.empty() ? inv.selfIntersectsRounded : true;
    inv.newSelfIntersectionsExact = m.exact.empty() ? anyNew : true;
    return inv;
  }
  inv.closed = CGAL::is_closed(exactMesh);
  inv.outwardOriented = inv.closed && PMP::is_outward_oriented(exactMesh);
  inv.selfIntersectsExact = PMP::does_self_intersect(exactMesh);
  inv.selfIntersectsRounded = PMP::does_self_intersect(roundedMesh);
  // Pairs the bone came with are pairs of two defect faces; any other pair is new (a cut made it).
  auto anyNewPair = [&](const auto& mesh) {
    using Face = typename std::decay_t<decltype(mesh)>::Face_index;
    std::vector<std::pair<Face, Face>> pairs;
    PMP::self_intersections(mesh, std::back_inserter(pairs));
    auto inputDefect = [&](Face f) { return (m.defect[slotOfFace[f.idx()]] & csg::kSelfIntersecting) != 0; };
    return std::any_of(pairs.begin(), pairs.end(), [&](const auto& p) { return !(inputDefect(p.first) && inputDefect(p.second)); });
  };
  const bool inputHadPairs = m.defects.selfIntersectingPairs > 0;
  inv.newSelfIntersectionsExact = inv.selfIntersectsExact && (!inputHadPairs || anyNewPair(exactMesh));
  inv.newSelfIntersectionsRounded = inv.selfIntersectsRounded && (!inputHadPairs || anyNewPair(roundedMesh));
  return inv;
}

}  // namespace reamsim
