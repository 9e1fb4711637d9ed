#pragma once
// A reamer whose cutting volume comes from a mesh file (any format readMesh supports), already in the
// reamer-local frame (apex at the origin, feed along +Z).
#include <string>

#include "reamsim/core/ReamerSpec.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Throws reamsim::InputError when the file cannot be read, is not a closed consistently-oriented
// surface, or encloses no positive volume (inward-facing normals).
TriangleMesh loadCuttingSolidFromFile(const std::string& path);

// A reamer read from the mesh at `path`, named after the file.
ReamerSpec meshReamerSpec(const std::string& path);
// A reamer as a command line or a plan names it: the mesh file if there is one at `arg`, otherwise the preset of
// that name in `presetsJsonPath` (InputError, as loadPreset, when there is none).
ReamerSpec reamerFromArgument(const std::string& arg, const std::string& presetsJsonPath);
// The cutting solid of a reamer: read from its mesh file (loadCuttingSolidFromFile), else built from its
// parameters (buildCuttingSolid).
TriangleMesh cuttingSolidFor(const ReamerSpec& spec);

}  // namespace reamsim
