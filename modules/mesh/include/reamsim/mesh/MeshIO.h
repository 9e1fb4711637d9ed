#pragma once
// Reading and writing triangle meshes: STL (ASCII/binary), OBJ, PLY (ASCII/binary LE/BE), OFF, VTP.
// Readers never trust a header: counts are checked against the file size before allocating, every
// index is range-checked, every coordinate must be finite. Problems throw reamsim::InputError.
#include <string>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

enum class Units { Auto, Millimetres, Metres };

struct ReadOptions {
  Units units = Units::Auto;  // Auto: metre-scale input (bounding box diagonal < 2 units) is scaled to mm
};

struct LoadedMesh {
  TriangleMesh mesh;                // in millimetres
  std::string format;               // "stl-ascii", "stl-binary", "obj", "ply-ascii", "ply-binary", "off", "vtp"
  double scaleToMillimetres = 1.0;  // factor applied to the file's coordinates
  std::vector<std::string> notes;   // what the reader did that the user should know (unit scaling, triangulation)
  std::vector<std::string> comments;  // the file's own comment lines (PLY 'comment'; other formats: none)
};

LoadedMesh readMesh(const std::string& path, const ReadOptions& options = {});

struct WriteOptions {
  bool binary = true;  // for STL and PLY; OBJ and OFF are always text
  // PLY only: written as header 'comment' lines (line breaks become spaces) and read back into
  // LoadedMesh::comments; e.g. the bone's patient frame. The other formats have no place for them.
  std::vector<std::string> comments;
};
// The format follows the extension (.stl .obj .ply .off .vtp); throws InputError on failure.
void writeMesh(const TriangleMesh& mesh, const std::string& path, const WriteOptions& options = {});

std::vector<std::string> supportedMeshExtensions();
Units parseUnits(const std::string& text);  // "m", "mm", "auto"; throws std::invalid_argument

}  // namespace reamsim
