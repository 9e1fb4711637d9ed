#pragma once
// Whole-file reading and writing with InputError reporting, shared by every mesh format.
#include <cstddef>
#include <string>

namespace reamsim::io {

// Files above this size are refused before anything is read.
constexpr std::size_t kMaxMeshFileBytes = std::size_t{2} * 1024 * 1024 * 1024;

// Reads the whole file; throws InputError if it is missing, unreadable, a directory, empty or > 2 GiB.
std::string readFileBytes(const std::string& path);

// Writes (replaces) the file; throws InputError naming the file on any failure.
void writeFileBytes(const std::string& path, const std::string& bytes);

// Appends a double with full round-trip precision (%.17g).
void appendDouble(std::string& out, double value);
// Appends "a b c" with %.17g each.
void appendTriple(std::string& out, double a, double b, double c);

}  // namespace reamsim::io
