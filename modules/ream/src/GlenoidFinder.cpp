#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/Glenoid.h"

namespace reamsim {
namespace {

std::vector<Vec3> vertexNormals(const TriangleMesh& m) {
  std::vector<Vec3> n(m.vertices.size());
  for (const Triangle& t : m.triangles) {
    const Vec3 area = cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
    for (std::uint32_t v : t) n[v] += area;
  }
  for (Vec3& v : n) v = normalized(v);
  return n;
}

struct Sphere {
  Vec3 centre;
  double radius = 0;
  double rms = 0;
};

// Algebraic least-squares sphere: x² + y² + z² + a x + b y + c z + d = 0, solved by normal equations
// on coordinates relative to the patch centroid (keeps the 4×4 system well conditioned).
std::optional<Sphere> fitSphere(const std::vector<Vec3>& pts) {
  if (pts.size() < 10) return std::nullopt;
  Vec3 c0{};
  for (const Vec3& p : pts) c0 += p;
  c0 = c0 / double(pts.size());
  double A[4][5] = {};
  for (const Vec3& q : pts) {
    const Vec3 p = q - c0;
    const double row[4] = {p.x, p.y, p.z, 1.0};
    const double rhs = -squaredNorm(p);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) A[i][j] += row[i] * row[j];
      A[i][4] += row[i] * rhs;
    }
  }
  for (int col = 0; col < 4; ++col) {  // Gaussian elimination with partial pivoting
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::abs(A[r][col]) > std::abs(A[pivot][col])) pivot = r;
    if (std::abs(A[pivot][col]) < 1e-12) return std::nullopt;
    std::swap(A[col], A[pivot]);
    for (int r = 0; r < 4; ++r) {
      if (r == col) continue;
      const double f = A[r][col] / A[col][col];
      for (int k = col; k < 5; ++k) A[r][k] -= f * A[col][k];
    }
  }
  const double a = A[0][4] / A[0][0], b = A[1][4] / A[1][1], c = A[2][4] / A[2][2], d = A[3][4] / A[3][3];
  Sphere s;
  const Vec3 centreLocal{-a / 2, -b / 2, -c / 2};
  const double r2 = squaredNorm(centreLocal) - d;
  if (!(r2 > 0)) return std::nullopt;
  s.centre = centreLocal + c0;
  s.radius = std::sqrt(r2);
  double sum = 0;
  for (const Vec3& p : pts) sum += std::pow(norm(p - s.centre) - s.radius, 2);
  s.rms = std::sqrt(sum / pts.size());
  return s;
}

}  // namespace

GlenoidFrame findGlenoid(const TriangleMesh& bone, const GlenoidSearchOptions& o) {
  const Vec3 lateral = normalized(o.lateral);
  const std::vector<Vec3> normals = vertexNormals(bone);
  double mostLateral = -INFINITY;
  for (const Vec3& p : bone.vertices) mostLateral = std::max(mostLateral, dot(p, lateral));

  std::optional<GlenoidFrame> best;
  double bestScore = INFINITY;
  for (std::size_t i = 0; i < bone.vertices.size(); ++i) {
    const Vec3& seed = bone.vertices[i];
    if (dot(seed, lateral) < mostLateral - o.lateralBandMm) continue;
    if (dot(normals[i], lateral) < o.minFacingLateral) continue;
    // The patch: nearby vertices on the same side of the bone (normals agree), so the far side of a
    // thin part does not join it.
    std::vector<Vec3> patch;
    Vec3 normalSum{};
    for (std::size_t j = 0; j < bone.vertices.size(); ++j) {
      if (squaredNorm(bone.vertices[j] - seed) > o.patchRadiusMm * o.patchRadiusMm) continue;
      if (dot(normals[j], normals[i]) < 0.5) continue;
      patch.push_back(bone.vertices[j]);
      normalSum += normals[j];
    }
    const auto sphere = fitSphere(patch);
    if (!sphere || sphere->radius < o.minSphereRadiusMm || sphere->radius > o.maxSphereRadiusMm) continue;
    const Vec3 outward = normalized(normalSum);
    // Concave: the sphere's centre lies outside the bone, in front of the patch.
    if (dot(sphere->centre - seed, outward) <= 0) continue;
    // Prefer spherical (small residual) patches that face laterally.
    const double score = sphere->rms / std::max(1e-6, dot(outward, lateral));
    if (score < bestScore) {
      bestScore = score;
      GlenoidFrame g;
      g.outwardAxis = normalized(sphere->centre - seed);
      g.centre = sphere->centre - g.outwardAxis * sphere->radius;  // seed projected onto the sphere
      g.sphereRadiusMm = sphere->radius;
      g.rmsResidualMm = sphere->rms;
      g.patchVertices = patch.size();
      best = g;
    }
  }
  if (!best) throw std::runtime_error("no concave, laterally facing, near-spherical patch was found");
  // The best patch need not be centred on the fossa: grow it to every nearby vertex that lies on the
  // fitted sphere and faces its centre, and take the centre of that region on the sphere.
  const Vec3 sphereCentre = best->centre + best->outwardAxis * best->sphereRadiusMm;
  Vec3 sum{};
  std::size_t count = 0;
  for (std::size_t j = 0; j < bone.vertices.size(); ++j) {
    const Vec3 toCentre = sphereCentre - bone.vertices[j];
    if (std::abs(norm(toCentre) - best->sphereRadiusMm) > o.onSphereToleranceMm) continue;
    if (norm(bone.vertices[j] - best->centre) > o.fossaRadiusMm) continue;
    if (dot(normals[j], normalized(toCentre)) < 0.7) continue;
    sum += bone.vertices[j];
    ++count;
  }
  if (count >= best->patchVertices) {
    best->outwardAxis = normalized(sphereCentre - sum / double(count));
    best->centre = sphereCentre - best->outwardAxis * best->sphereRadiusMm;
    best->patchVertices = count;
  }
  return *best;
}

std::string glenoidToJson(const GlenoidFrame& g, const std::string& method) {
  nlohmann::json j = {{"centre_mm", {g.centre.x, g.centre.y, g.centre.z}},
                      {"outward_axis", {g.outwardAxis.x, g.outwardAxis.y, g.outwardAxis.z}},
                      {"sphere_radius_mm", g.sphereRadiusMm},
                      {"rms_residual_mm", g.rmsResidualMm},
                      {"patch_vertices", g.patchVertices},
                      {"method", method}};
  return j.dump(2);
}

GlenoidFrame loadGlenoid(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the glenoid file");
  std::stringstream text;
  text << in.rdbuf();
  try {
    const auto j = nlohmann::json::parse(text.str());
    GlenoidFrame g;
    for (int i = 0; i < 3; ++i) {
      g.centre[i] = j.at("centre_mm").at(i).get<double>();
      g.outwardAxis[i] = j.at("outward_axis").at(i).get<double>();
    }
    g.outwardAxis = normalized(g.outwardAxis);
    g.sphereRadiusMm = j.value("sphere_radius_mm", 0.0);
    g.rmsResidualMm = j.value("rms_residual_mm", 0.0);
    g.patchVertices = j.value("patch_vertices", std::size_t(0));
    return g;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("malformed glenoid file: ") + e.what());
  }
}

}  // namespace reamsim
