#include "MeshBuilder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "Formats.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {
namespace {

constexpr std::uint64_t kMaxVertices = std::numeric_limits<std::uint32_t>::max();

std::string coordText(double v) {
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}

}  // namespace

void MeshBuilder::reserve(std::size_t vertices, std::size_t triangles) {
  mesh_.vertices.reserve(vertices);
  mesh_.triangles.reserve(triangles);
}

void MeshBuilder::fail(long line, const std::string& problem) const { throw InputError(file_, line, problem); }

void MeshBuilder::checkFinite(const Vec3& p, long line, const std::string& what) const {
  const char* axis = nullptr;
  double bad = 0;
  if (!std::isfinite(p.x)) axis = "x", bad = p.x;
  else if (!std::isfinite(p.y)) axis = "y", bad = p.y;
  else if (!std::isfinite(p.z)) axis = "z", bad = p.z;
  if (axis) fail(line, what + " has a non-finite coordinate (" + axis + " = " + coordText(bad) + ")");
}

void MeshBuilder::report() const { askReadGoesOn(progress_, fraction()); }

std::uint32_t MeshBuilder::addVertex(const Vec3& p, long line) {
  tick();
  const std::size_t n = mesh_.vertices.size();
  checkFinite(p, line, "vertex " + std::to_string(n + static_cast<std::size_t>(base_)));
  if (n >= kMaxVertices) fail(line, "too many vertices (more than 2^32 - 1)");
  mesh_.vertices.push_back(p);
  return static_cast<std::uint32_t>(n);
}

std::uint32_t MeshBuilder::weld(const Vec3& p, long line) {
  const auto it = weld_.find(p);
  if (it != weld_.end()) return it->second;
  const std::size_t n = mesh_.vertices.size();
  if (n >= kMaxVertices) fail(line, "too many vertices (more than 2^32 - 1)");
  mesh_.vertices.push_back(p);
  weld_.emplace(p, static_cast<std::uint32_t>(n));
  return static_cast<std::uint32_t>(n);
}

void MeshBuilder::addPolygon(const std::vector<std::int64_t>& indices, std::uint64_t indexLimit, long line,
                             std::size_t faceNumber) {
  tick();
  const std::string face = "face " + std::to_string(faceNumber + static_cast<std::size_t>(base_));
  if (indices.size() < 3)
    fail(line, face + " has only " + std::to_string(indices.size()) + " vertices (at least 3 needed)");
  for (std::int64_t i : indices) {
    if (i < 0 || static_cast<std::uint64_t>(i) >= indexLimit || static_cast<std::uint64_t>(i) >= kMaxVertices)
      fail(line, face + ": vertex index " + std::to_string(i + base_) + " is out of range (the file has " +
                     std::to_string(indexLimit) + " vertices)");
  }
  if (indices.size() > 3) ++polygonsTriangulated_;
  for (std::size_t k = 1; k + 1 < indices.size(); ++k)
    mesh_.triangles.push_back({static_cast<std::uint32_t>(indices[0]), static_cast<std::uint32_t>(indices[k]),
                               static_cast<std::uint32_t>(indices[k + 1])});
}

TriangleMesh MeshBuilder::finish(std::vector<std::string>& notes) {
  if (mesh_.triangles.empty()) fail(0, "the file contains no triangles");
  if (polygonsTriangulated_ > 0)
    notes.push_back(std::to_string(polygonsTriangulated_) + " polygons with >3 vertices were triangulated");
  weld_.clear();
  polygonsTriangulated_ = 0;
  return std::move(mesh_);
}

}  // namespace reamsim::io
