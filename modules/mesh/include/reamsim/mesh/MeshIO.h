#pragma once
// Reading and writing triangle meshes: STL (ASCII/binary), OBJ, PLY (ASCII/binary LE/BE), OFF, VTP.
// Readers never trust a header: counts are checked against the file size before allocating, every
// index is range-checked, every coordinate must be finite. Problems throw reamsim::InputError.
#include <string>
#include <vector>

#include "reamsim/mesh/FileReplace.h"  // WriteCancelled
#include "reamsim/mesh/RepairProgress.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

enum class Units { Auto, Millimetres, Metres };

struct ReadOptions {
  Units units = Units::Auto;  // Auto: metre-scale input (bounding box diagonal < 2 units) is scaled to mm
  // Hears the fraction done at "reading" (the file's bytes, in pieces of 8 MiB) and "parsing" (how far into
  // them the parser is, every 32768 vertices, faces and other things parsed); returning false stops the read with
  // ReadCancelled.
  // Seconds at millions of faces in a text format: an import's Cancel does not wait for them.
  ProgressCallback progress;
};

// Thrown when a read's progress callback asked to stop.
class ReadCancelled : public StageCancelled {
 public:
  explicit ReadCancelled(const std::string& stage) : StageCancelled("reading cancelled during " + stage, stage) {}
};

struct LoadedMesh {
  TriangleMesh mesh;                // in millimetres
  std::string format;               // "stl-ascii", "stl-binary", "obj", "ply-ascii", "ply-binary", "off", "vtp"
  double scaleToMillimetres = 1.0;  // factor applied to the file's coordinates
  std::vector<std::string> notes;   // what the reader did that the user should know (unit scaling, triangulation)
  // The file's comment lines: PLY 'comment' lines, OBJ and OFF whole-line '#' comments, a VTP's ReamSimComments
  // field array, the comments in a binary STL header ReamSim wrote (ASCII STL: none). docs/FORMATS.md.
  std::vector<std::string> comments;
};

LoadedMesh readMesh(const std::string& path, const ReadOptions& options = {});

struct WriteOptions {
  bool binary = true;  // for STL and PLY; OBJ and OFF are always text
  // Written where the format has room, after "written by ReamSim" (line breaks become spaces), and read back
  // into LoadedMesh::comments; e.g. the bone's patient frame. PLY, OBJ, OFF, VTP and ASCII STL keep them all,
  // binary STL those that fit in its 80-byte header (commentsKept says which).
  std::vector<std::string> comments;
  // Hears the fraction done and the stage ("checking", "encoding", "writing", "flushing"); returning false
  // stops the write before the file is replaced, with WriteCancelled (reamsim/mesh/FileReplace.h).
  ProgressCallback progress;
};
// The format follows the extension (.stl .obj .ply .off .vtp); throws InputError on failure. The file is
// replaced whole or not at all (replaceFile).
void writeMesh(const TriangleMesh& mesh, const std::string& path, const WriteOptions& options = {});

// Of options.comments, those a writeMesh to `path` with `options` stores (line breaks as spaces): all of them,
// except in a binary STL, whose header keeps those that fit.
std::vector<std::string> commentsKept(const std::string& path, const WriteOptions& options);

std::vector<std::string> supportedMeshExtensions();
Units parseUnits(const std::string& text);  // "m", "mm", "auto"; throws std::invalid_argument

}  // namespace reamsim
