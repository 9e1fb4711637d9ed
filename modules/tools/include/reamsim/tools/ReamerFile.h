#pragma once
// A reamer whose cutting volume comes from a mesh file (any format readMesh supports), already in the
// reamer-local frame (apex at the origin, feed along +Z).
#include <string>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Throws reamsim::InputError when the file cannot be read, is not a closed consistently-oriented
// surface, or encloses no positive volume (inward-facing normals).
TriangleMesh loadCuttingSolidFromFile(const std::string& path);

}  // namespace reamsim
