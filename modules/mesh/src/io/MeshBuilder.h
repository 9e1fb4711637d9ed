#pragma once
// Collects vertices and polygons from any reader and applies the shared policy: coordinates must be
// finite, indices must be in range, polygons with > 3 vertices are fan-triangulated (and counted for a
// note), polygons with < 3 vertices are an error, and a file without triangles is an error.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "reamsim/mesh/RepairProgress.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::io {

class MeshBuilder {
 public:
  // indexBase: how the format numbers vertices and faces in messages (OBJ: 1, others: 0).
  MeshBuilder(std::string file, int indexBase = 0) : file_(std::move(file)), base_(indexBase) {}

  // Reserve only counts already checked against the file size.
  void reserve(std::size_t vertices, std::size_t triangles);

  // Every 32768 vertices, faces and steps (step()), tells `progress` (may be null) how far into the file's `size`
  // bytes the parser is (`offset()`), and throws ReadCancelled when it says stop.
  void watch(const StageProgress* progress, std::function<std::size_t()> offset, std::size_t size) {
    progress_ = progress;
    offset_ = std::move(offset);
    size_ = size;
  }

  std::size_t vertexCount() const { return mesh_.vertices.size(); }
  std::size_t triangleCount() const { return mesh_.triangles.size(); }

  // A piece of the file parsed that adds nothing to the mesh (an OBJ texture line, a PLY value of another
  // element, a long index list): counted with the vertices and faces, so that such stretches are checked too.
  void step() { tick(); }

  // How far into the file the parse is, as watch() measures it (0 without a watch).
  // Never lower than before: a caller that reads it between steps (a VTP's arrays) may not see it go back.
  double fraction() const {
    if (offset_) highest_ = std::max(highest_, std::min(1.0, double(offset_()) / double(size_)));
    return highest_;
  }

  // Appends a vertex (throws if a coordinate is NaN/Inf). line: 0 for binary data.
  std::uint32_t addVertex(const Vec3& p, long line);
  // For soup formats (STL): reuses an earlier vertex with identical coordinates. `where()` names the
  // corner for messages (e.g. "triangle 5 corner 1"); it is called only when there is a problem.
  template <class WhereFn>
  std::uint32_t addWeldedVertex(const Vec3& p, long line, WhereFn&& where) {
    tick();
    if (!isFinite(p)) checkFinite(p, line, where());
    return weld(p, line);
  }

  // Adds a polygon by indices as written in the file, already converted to 0-based, each checked
  // against `indexLimit` (the number of vertices the file has). `faceNumber` is 0-based.
  void addPolygon(const std::vector<std::int64_t>& indices, std::uint64_t indexLimit, long line,
                  std::size_t faceNumber);
  void addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    tick();
    mesh_.triangles.push_back({a, b, c});
  }

  // Checks the result has triangles, adds the triangulation note; leaves the builder empty.
  TriangleMesh finish(std::vector<std::string>& notes);

 private:
  [[noreturn]] void fail(long line, const std::string& problem) const;
  void checkFinite(const Vec3& p, long line, const std::string& what) const;
  std::uint32_t weld(const Vec3& p, long line);
  void tick() {
    if (progress_ && (++added_ & 32767) == 0) report();
  }
  void report() const;

  std::string file_;
  int base_;
  TriangleMesh mesh_;
  std::size_t polygonsTriangulated_ = 0;
  std::unordered_map<Vec3, std::uint32_t, Vec3PositionHash> weld_;
  const StageProgress* progress_ = nullptr;
  std::function<std::size_t()> offset_;
  std::size_t size_ = 1;
  std::size_t added_ = 0;
  mutable double highest_ = 0;
};

}  // namespace reamsim::io
