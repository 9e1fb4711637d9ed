#pragma once
// Internal per-format entry points used by MeshIO.cpp. Readers get the whole file in memory (except VTP,
// which VTK reads itself after MeshIO.cpp has checked the file) and return geometry in file units.
#include <string>
#include <string_view>
#include <vector>

#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/RepairProgress.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::io {

struct RawMesh {
  TriangleMesh mesh;
  std::string format;
  std::vector<std::string> notes;
  // The file's comments: PLY 'comment' lines, OBJ and OFF whole-line '#' comments, the comments a ReamSim
  // binary STL header or VTP file carries (see the writers).
  std::vector<std::string> comments;
};

// The VTP field-data string array that holds the comments.
inline constexpr const char* kVtpCommentsArray = "ReamSimComments";

// What ReamSim writes into every file that has room for it, before the caller's comments.
inline constexpr const char* kWrittenByComment = "written by ReamSim";

// The comments a writer stores: "written by ReamSim", then the caller's, each on one line (a line break
// would end a comment early in every format that has them).
std::vector<std::string> commentLinesToWrite(const std::vector<std::string>& comments);

// Of `comments`, those a binary STL's header keeps (in order; each one that does not fit after those before it is
// left out).
std::vector<std::string> binaryStlCommentsKept(const std::vector<std::string>& comments);

// Asks `progress` (may be null) whether the read goes on at `fraction` of its stage; ReadCancelled naming the
// stage when it says stop. Every check of a read (the bytes, the parse, a VTP's arrays) is this one.
inline void askReadGoesOn(const StageProgress* progress, double fraction) {
  if (progress && !progress->keepGoing(fraction)) throw ReadCancelled(progress->stage);
}

// `progress` (may be null): how far into `data` the parse is, through MeshBuilder::watch.
RawMesh readStl(const std::string& path, std::string_view data, const StageProgress* progress = nullptr);
RawMesh readObj(const std::string& path, std::string_view data, const StageProgress* progress = nullptr);
RawMesh readPly(const std::string& path, std::string_view data, const StageProgress* progress = nullptr);
RawMesh readOff(const std::string& path, std::string_view data, const StageProgress* progress = nullptr);
RawMesh readVtp(const std::string& path, std::string_view data, const StageProgress* progress = nullptr);

// Writers return the file contents; MeshIO.cpp writes them (replaceFile).
// `comments` go where the format has room: PLY 'comment' lines, OBJ and OFF '#' lines, a VTP field-data
// string array, a binary STL's 80-byte header (those that fit: binaryStlCommentsKept), an ASCII STL's solid name.
std::string writeStl(const TriangleMesh& mesh, const std::string& path, bool binary,
                     const std::vector<std::string>& comments);
std::string writeObj(const TriangleMesh& mesh, const std::vector<std::string>& comments);
std::string writePly(const TriangleMesh& mesh, const std::string& path, bool binary,
                     const std::vector<std::string>& comments);
std::string writeOff(const TriangleMesh& mesh, const std::vector<std::string>& comments);
std::string writeVtp(const TriangleMesh& mesh, const std::string& path, const std::vector<std::string>& comments);

}  // namespace reamsim::io
