#pragma once
// Whole-file reading and writing with InputError reporting, shared by every mesh format.
#include <cstddef>
#include <string>

#include "reamsim/mesh/RepairProgress.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::io {

// Files above this size are refused before anything is read.
constexpr std::size_t kMaxMeshFileBytes = std::size_t{2} * 1024 * 1024 * 1024;

// Reads the whole file; throws InputError if it is missing, unreadable, a directory, empty or > 2 GiB.
// `progress` (may be null) hears the fraction read before each piece of 8 MiB (the first at 0); ReadCancelled
// when it says stop.
std::string readFileBytes(const std::string& path, const StageProgress* progress = nullptr);

// strerror(err) for an error message; "unknown error" for 0.
std::string errnoText(int err);

// Appends a double with full round-trip precision (%.17g).
void appendDouble(std::string& out, double value);
// Appends "a b c" with %.17g each.
void appendTriple(std::string& out, double a, double b, double c);
// Appends one "x y z" line per vertex, then one "3 a b c" line per triangle: the body of ASCII OFF and PLY.
void appendVertexAndTriangleLines(std::string& out, const TriangleMesh& mesh);

}  // namespace reamsim::io
