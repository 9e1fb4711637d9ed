// bench winding: the remesh's inside/outside test (reamsim/mesh/WindingNumber.h) on a mesh, the direct sum
// over every triangle against the tree of clusters (FastWindingNumber) at beta 2 (what the remesh uses) and
// beta 8 (its second look at points near ½), on the same points: time a point, terms a point, agreement.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>

#include "BenchStats.h"
#include "CliArgs.h"
#include "Commands.h"
#include "DefaultCase.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/WindingNumber.h"

namespace reamsim::cli {
namespace {
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

// Half the points anywhere in the mesh's box grown by a quarter, half within 1 mm of a random surface point
// (the remesh's band lies within 1.75 voxels of the surface).
std::vector<Vec3> samplePoints(const TriangleMesh& mesh, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const Bounds b = computeBounds(mesh);
  const Vec3 grow = (b.max - b.min) * 0.25;
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 p;
    if (i % 2 == 0) {
      for (int k = 0; k < 3; ++k) p[k] = b.min[k] - grow[k] + u(rng) * (b.max[k] - b.min[k] + 2 * grow[k]);
    } else {
      const Triangle& t = mesh.triangles[std::min(mesh.triangles.size() - 1, std::size_t(u(rng) * double(mesh.triangles.size())))];
      const double s = u(rng), r = u(rng) * (1 - s);
      p = mesh.vertices[t[0]] + (mesh.vertices[t[1]] - mesh.vertices[t[0]]) * s + (mesh.vertices[t[2]] - mesh.vertices[t[0]]) * r +
          Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5} * 2.0;
    }
    points.push_back(p);
  }
  return points;
}

json timesJson(const std::vector<double>& us) {
  return {{"median_us", percentile(us, 0.5)}, {"p99_us", percentile(us, 0.99)}, {"samples", us.size()}};
}

}  // namespace

int runBenchWinding(const std::vector<std::string>& args) {
  CliArgs a(args, {"mesh", "units", "points", "seed"}, {"json"});
  if (!a.positionals().empty()) throw UsageError("unexpected argument '" + a.positionals()[0] + "'");
  const std::string meshArg = a.required("mesh");
  const std::size_t n = static_cast<std::size_t>(a.number("points", 500));
  if (n < 10) throw UsageError("--points must be at least 10");
  std::vector<std::string> notes;
  const TriangleMesh mesh = benchMesh(meshArg, a.value("units", "auto"), &notes);
  for (const std::string& note : notes) std::fprintf(stderr, "note: %s: %s\n", meshArg.c_str(), note.c_str());
  if (mesh.triangles.empty()) throw InputError(meshArg, "the mesh has no triangles");
  const std::vector<Vec3> points = samplePoints(mesh, n, static_cast<std::uint64_t>(a.number("seed", 1)));

  const auto t0 = Clock::now();
  const FastWindingNumber tree(mesh);
  const double buildMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();

  std::vector<double> directUs, tree2Us, tree8Us;
  std::size_t terms2 = 0, terms8 = 0, signs2 = 0, signs8 = 0;
  double maxError2 = 0, maxError8 = 0;
  for (const Vec3& p : points) {  // the three evaluations of a point in turn, so that they share its caches' state
    auto s = Clock::now();
    const double direct = windingNumber(mesh, p);
    directUs.push_back(std::chrono::duration<double, std::micro>(Clock::now() - s).count());
    s = Clock::now();
    const double w2 = tree.evaluate(p, 2.0, &terms2);
    tree2Us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - s).count());
    s = Clock::now();
    const double w8 = tree.evaluate(p, 8.0, &terms8);
    tree8Us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - s).count());
    maxError2 = std::max(maxError2, std::abs(w2 - direct));
    maxError8 = std::max(maxError8, std::abs(w8 - direct));
    // A sign the remesh would take differently, where the direct sum is clear of ½.
    if (std::abs(direct - 0.5) > 0.1) {
      signs2 += (w2 >= 0.5) != (direct >= 0.5);
      signs8 += (w8 >= 0.5) != (direct >= 0.5);
    }
  }
  json j;
  j["bench"] = "winding";
  j["mesh"] = meshArg;
  j["triangles"] = mesh.triangles.size();
  j["points"] = n;
  j["tree_build_ms"] = buildMs;
  j["tree_nodes"] = tree.nodeCount();
  j["direct"] = timesJson(directUs);
  j["direct"]["terms_per_point"] = mesh.triangles.size();
  const auto treeJson = [&](const std::vector<double>& us, std::size_t terms, double maxError, std::size_t signs) {
    json t = timesJson(us);
    t["terms_per_point"] = double(terms) / double(n);
    t["max_abs_error"] = maxError;
    t["sign_disagreements"] = signs;
    t["speedup_median"] = percentile(directUs, 0.5) / std::max(1e-3, percentile(us, 0.5));
    return t;
  };
  j["tree_beta2"] = treeJson(tree2Us, terms2, maxError2, signs2);
  j["tree_beta8"] = treeJson(tree8Us, terms8, maxError8, signs8);
  if (a.has("json")) {
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("%s: %zu triangles, %zu points; tree built in %.1f ms\n", meshArg.c_str(), mesh.triangles.size(), n, buildMs);
    std::printf("direct sum: median %.1f us a point\n", j["direct"]["median_us"].get<double>());
    for (const char* k : {"tree_beta2", "tree_beta8"})
      std::printf("%s: median %.2f us a point (%.0fx), %.0f terms, max error %.2g, %zu sign disagreements\n", k,
                  j[k]["median_us"].get<double>(), j[k]["speedup_median"].get<double>(), j[k]["terms_per_point"].get<double>(),
                  j[k]["max_abs_error"].get<double>(), j[k]["sign_disagreements"].get<std::size_t>());
  }
  return kOk;
}

}  // namespace reamsim::cli
