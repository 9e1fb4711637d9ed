#pragma once
// Internal per-format entry points used by MeshIO.cpp. Readers get the whole file in memory (except VTP,
// which VTK reads itself after MeshIO.cpp has checked the file) and return geometry in file units.
#include <string>
#include <string_view>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::io {

struct RawMesh {
  TriangleMesh mesh;
  std::string format;
  std::vector<std::string> notes;
  std::vector<std::string> comments;  // PLY 'comment' lines
};

RawMesh readStl(const std::string& path, std::string_view data);
RawMesh readObj(const std::string& path, std::string_view data);
RawMesh readPly(const std::string& path, std::string_view data);
RawMesh readOff(const std::string& path, std::string_view data);
RawMesh readVtp(const std::string& path, std::string_view data);

// Writers return the file contents; MeshIO.cpp writes them (VTP writes the file itself).
std::string writeStl(const TriangleMesh& mesh, const std::string& path, bool binary);
std::string writeObj(const TriangleMesh& mesh);
std::string writePly(const TriangleMesh& mesh, const std::string& path, bool binary,
                     const std::vector<std::string>& comments);
std::string writeOff(const TriangleMesh& mesh);
void writeVtp(const TriangleMesh& mesh, const std::string& path);

}  // namespace reamsim::io
