#pragma once
// The CLI's view of the bundled default case (thin re-export of modules/ream), and the benches' bone argument.
#include <string>

#include "reamsim/mesh/MeshIO.h"
#include "reamsim/ream/DefaultCase.h"

namespace reamsim::cli {

// A bench's mesh argument: "default" is the bundled repaired scapula, anything else a file read as it is, in
// `units` ("auto", "mm", "m"): no repair, since a bench measures the mesh it is pointed at (the local engine
// takes dirty bones). The reader's notes go to `notes` when given.
inline TriangleMesh benchMesh(const std::string& arg, const std::string& units, std::vector<std::string>* notes = nullptr) {
  if (arg == "default") return loadDefaultBone().mesh;
  ReadOptions options;
  options.units = parseUnits(units);
  LoadedMesh m = readMesh(arg, options);
  if (notes) *notes = std::move(m.notes);
  return std::move(m.mesh);
}

}  // namespace reamsim::cli
