#include "reamsim/mesh/VolumetricRemesh.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <stdexcept>
#include <string>

#include "DistanceOracle.h"
#include "MarchingTetrahedra.h"
#include "ScalarGrid.h"
#include "reamsim/mesh/WindingNumber.h"

namespace reamsim {
namespace {

enum : std::uint8_t { kFar = 0, kBand = 1 };

// Inside where the winding number is at least ½. The tree's value (beta 2) was within 0.04 of the direct sum
// on the meshes measured (tests/mesh/test_winding_number.cpp: boxes, dirty boxes, the bundled scapula);
// where it lies within kAmbiguous of ½ (near holes and overlaps) the point is decided again: by the direct
// sum on meshes small enough for it to be cheap (the decision is then the direct sum's wherever the tree is
// within 0.1 of it), otherwise by the tree at beta 8 (within 0.005 on the scapula). `terms` counts the work
// (solid angles and cluster expansions).
constexpr double kAmbiguous = 0.1;
constexpr std::size_t kDirectSumTriangles = 20'000;
bool insideSoup(const FastWindingNumber& winding, const TriangleMesh& soup, const Vec3& p, std::size_t* terms = nullptr) {
  const double w = winding.evaluate(p, 2.0, terms);
  if (std::abs(w - 0.5) >= kAmbiguous) return w >= 0.5;
  if (soup.triangles.size() <= kDirectSumTriangles) {
    if (terms) *terms += soup.triangles.size();
    return windingNumber(soup, p) >= 0.5;
  }
  return winding.evaluate(p, 8.0, terms) >= 0.5;
}

// "the mesh spans 65536 x 10 x 10 mm, at a 0.5 mm grid": what an error about the grid's size should say.
std::string extentText(const Bounds& b, double voxelMm) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "the mesh spans %.6g x %.6g x %.6g mm, at a %.3g mm grid", b.max.x - b.min.x,
                b.max.y - b.min.y, b.max.z - b.min.z, voxelMm);
  return buf;
}

ScalarGrid makeGrid(const TriangleMesh& soup, double voxelMm, const RemeshOptions& options) {
  if (!(voxelMm > 0) || !std::isfinite(voxelMm))
    throw std::invalid_argument("remesh voxel size must be a positive number of mm");
  const Bounds bounds = computeBounds(soup);
  ScalarGrid grid;
  grid.h = voxelMm;
  const double pad = 3 * grid.h;  // room for the band and an all-outside border
  grid.origin = bounds.min - Vec3{pad, pad, pad};
  double points = 1;
  for (int a = 0; a < 3; ++a) {
    grid.n[a] = int(std::ceil((bounds.max[a] - bounds.min[a] + 2 * pad) / grid.h)) + 1;
    points *= grid.n[a];
  }
  if (points > double(options.maxGridPoints))
    throw std::invalid_argument("remesh grid of " + std::to_string(grid.n[0]) + "x" + std::to_string(grid.n[1]) + "x" +
                                std::to_string(grid.n[2]) + " points exceeds the limit of " +
                                std::to_string(options.maxGridPoints) + " (" + extentText(bounds, grid.h) +
                                "); check the mesh's units, or use a larger voxel size");
  return grid;  // values not allocated yet: the band's size is checked first
}

// Marks the grid points whose box around a triangle could lie within `width` of it.
std::vector<std::uint8_t> candidateBand(const TriangleMesh& soup, const ScalarGrid& grid, double width) {
  std::vector<std::uint8_t> mark(grid.size(), kFar);
  for (const Triangle& t : soup.triangles) {
    Bounds b;
    for (std::uint32_t v : t) b.add(soup.vertices[v]);
    b = b.expanded(width);
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(0, int(std::floor((b.min[a] - grid.origin[a]) / grid.h)));
      hi[a] = std::min(grid.n[a] - 1, int(std::ceil((b.max[a] - grid.origin[a]) / grid.h)));
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) mark[grid.index(i, j, k)] = kBand;
  }
  return mark;
}

// The grid at `voxelMm` and the candidate band near the surface: every grid edge (up to a cell diagonal,
// h√3) that the surface crosses has both ends in it.
struct Banded {
  ScalarGrid grid;
  std::vector<std::uint8_t> mark;
  std::size_t size = 0;
  double width = 0;
};
Banded bandAt(const TriangleMesh& soup, double voxelMm, const RemeshOptions& options) {
  Banded b;
  b.grid = makeGrid(soup, voxelMm, options);
  b.width = b.grid.h * 1.75;
  b.mark = candidateBand(soup, b.grid, b.width);
  for (std::uint8_t m : b.mark) b.size += m == kBand;
  return b;
}

// Labels each 6-connected region of far points with the winding number at its first point.
void signFarRegions(const FastWindingNumber& winding, const TriangleMesh& soup, ScalarGrid& grid,
                    const std::vector<std::uint8_t>& mark, double farValue, const StageProgress& progress) {
  std::vector<std::uint8_t> seen(grid.size(), 0);
  std::deque<std::size_t> queue;
  const std::size_t stride[3] = {1, std::size_t(grid.n[0]), std::size_t(grid.n[0]) * grid.n[1]};
  // Steps: every seed scanned and every point flooded (each once), checked every 4M: the first flood alone
  // usually takes most of the grid.
  std::size_t steps = 0;
  const auto step = [&] {
    if (steps++ % (std::size_t(1) << 22) == 0) progress.check(double(steps) / (2.0 * double(grid.size())));
  };
  for (std::size_t seed = 0; seed < grid.size(); ++seed) {
    step();
    if (mark[seed] != kFar || seen[seed]) continue;
    const double value = insideSoup(winding, soup, grid.point(seed)) ? -farValue : farValue;
    seen[seed] = 1;
    queue.push_back(seed);
    while (!queue.empty()) {
      const std::size_t p = queue.front();
      queue.pop_front();
      step();
      grid.value[p] = value;
      const int c[3] = {int(p % grid.n[0]), int((p / grid.n[0]) % grid.n[1]), int(p / stride[2])};
      for (int a = 0; a < 3; ++a)
        for (int dir = -1; dir <= 1; dir += 2) {
          const int q = c[a] + dir;
          if (q < 0 || q >= grid.n[a]) continue;
          const std::size_t nb = dir < 0 ? p - stride[a] : p + stride[a];
          if (mark[nb] == kFar && !seen[nb]) { seen[nb] = 1; queue.push_back(nb); }
        }
    }
  }
}

}  // namespace

RemeshResult volumetricRemesh(const TriangleMesh& soup, const RemeshOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (soup.empty()) throw std::invalid_argument("cannot remesh an empty mesh");
  for (const Vec3& p : soup.vertices)
    if (!isFinite(p)) throw std::invalid_argument("cannot remesh a mesh with non-finite coordinates");

  Banded banded = bandAt(soup, options.voxelMm, options);
  const std::size_t requestedBand = banded.size;
  // Checked before any distance is taken (that pass costs microseconds a point; the grid's own limit lets a
  // long thin mesh through, whose band is nearly all of it), and at the grid asked for, before any
  // coarsening: a band this large means wrong units or a stray vertex far away, which a coarser grid would hide.
  if (requestedBand > options.maxBandPoints)
    throw std::invalid_argument("remesh band of " + std::to_string(requestedBand) + " grid points near the surface exceeds the limit of " +
                                std::to_string(options.maxBandPoints) + " (" + extentText(computeBounds(soup), banded.grid.h) +
                                "); check the mesh's units, or use a larger voxel size");
  // A band beyond the budget asks for a coarser grid: it grows as the surface's area over h², and the
  // output (about two triangles a band point) with it.
  for (int attempt = 0; options.coarsenAboveBandPoints > 0 && banded.size > options.coarsenAboveBandPoints && attempt < 8;
       ++attempt)
    banded = bandAt(soup, banded.grid.h * std::sqrt(double(banded.size) / double(options.coarsenAboveBandPoints)) * 1.02,
                    options);
  ScalarGrid& grid = banded.grid;
  std::vector<std::uint8_t>& mark = banded.mark;
  const std::size_t bandSize = banded.size;
  const double bandWidth = banded.width;
  std::vector<std::size_t> band;
  band.reserve(bandSize);
  for (std::size_t i = 0; i < mark.size(); ++i)
    if (mark[i] == kBand) band.push_back(i);

  // The winding number's cost a point depends on the mesh's shape (how much of it is near), so it is
  // measured on a sample of the band before the band is evaluated.
  reportRepairProgress(options.progress, 0.0, "remesh: winding-number tree");
  const FastWindingNumber winding(soup);
  std::size_t sampledTerms = 0, sampled = 0;
  const std::size_t step = std::max<std::size_t>(1, band.size() / 512);
  for (std::size_t b = 0; b < band.size(); b += step, ++sampled) (void)insideSoup(winding, soup, grid.point(band[b]), &sampledTerms);
  const double termsPerPoint = sampled ? double(sampledTerms) / double(sampled) : 0.0;
  const double terms = termsPerPoint * double(band.size());
  if (terms > options.maxWindingTerms) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "remesh would sum about %.3g winding-number terms (%zu grid points near the surface, %.0f terms a "
                  "point over %zu triangles), over the limit of %.3g: use a larger voxel size, or repair the mesh "
                  "elsewhere",
                  terms, band.size(), termsPerPoint, soup.triangles.size(), options.maxWindingTerms);
    throw std::invalid_argument(buf);
  }
  grid.value.assign(grid.size(), 0.0);

  const auto bandStart = std::chrono::steady_clock::now();
  reportRepairProgress(options.progress, 0.0, "remesh: distance tree");
  DistanceOracle oracle(soup);
  auto sample = [&](std::size_t b) {
    const std::size_t idx = band[b];
    const Vec3 p = grid.point(idx);
    const double d = oracle.distance(p);
    if (d > bandWidth) { mark[idx] = kFar; return; }  // the box test was conservative
    const bool inside = insideSoup(winding, soup, p);
    // Never exactly zero: the zero set must not pass through grid points.
    const double magnitude = std::max(d, 1e-9 * grid.h);
    grid.value[idx] = inside ? -magnitude : magnitude;
  };
  // In slices, so that a cancel is seen within a fraction of a second (a slice at 400k: ~0.5 s on two cores).
  constexpr std::size_t kSlice = std::size_t(1) << 16;
  for (std::size_t first = 0; first < band.size(); first += kSlice) {
    reportRepairProgress(options.progress, 0.6 * double(first) / double(band.size()),
                         "remesh: inside and outside near the surface");
    tbb::parallel_for(first, std::min(band.size(), first + kSlice), sample);
  }
  const auto stage = [&](double begin, double end, const char* name) {
    return StageProgress{&options.progress, begin, end, name};
  };
  signFarRegions(winding, soup, grid, mark, 2 * bandWidth, stage(0.6, 0.65, "remesh: inside and outside away from the surface"));

  RemeshResult result;
  RemeshStats& s = result.stats;
  s.windingMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - bandStart).count();
  result.mesh = marchingTetrahedra(grid, stage(0.65, 0.75, "remesh: marching tetrahedra"));
  s.voxelMm = grid.h;
  s.requestedVoxelMm = options.voxelMm;
  s.requestedBandPoints = requestedBand;
  s.windingTermsPerPoint = termsPerPoint;
  for (int a = 0; a < 3; ++a) s.grid[a] = grid.n[a];
  s.bandPoints = 0;
  for (std::uint8_t m : mark) s.bandPoints += m == kBand;
  s.trianglesBeforeDecimation = result.mesh.triangles.size();
  if (options.targetTriangles > 0 && options.targetTriangles < result.mesh.triangles.size()) {
    decimateWithoutSelfIntersections(result.mesh, options.targetTriangles, stage(0.75, 0.85, "remesh: decimation"));
  }
  s.trianglesAfter = result.mesh.triangles.size();
  surfaceDistance(result.mesh, soup, s.maxOutputToInputMm, s.meanOutputToInputMm,
                  stage(0.85, 0.92, "remesh: distance to the input"));
  surfaceDistance(soup, result.mesh, s.maxInputToOutputMm, s.meanInputToOutputMm,
                  stage(0.92, 1.0, "remesh: distance to the input"));
  reportRepairProgress(options.progress, 1.0, "remesh: done");
  s.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace reamsim
