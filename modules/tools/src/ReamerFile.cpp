#include "reamsim/tools/ReamerFile.h"

#include <filesystem>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/tools/MeshClosure.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim {

TriangleMesh loadCuttingSolidFromFile(const std::string& path) {
  TriangleMesh mesh = readMesh(path).mesh;
  if (mesh.empty()) throw InputError(path, "reamer mesh has no triangles");
  // The cutting volume is subtracted from bone, so it must bound a volume with outward normals.
  const ClosureReport closure = checkClosure(mesh);
  if (!closure.closed())
    throw InputError(path, "reamer mesh is not a closed, consistently oriented surface (" + closure.describe() +
                               "); repair it before using it as a cutting volume");
  const double volume = signedVolume(mesh);
  if (!(volume > 0))
    throw InputError(path, "reamer mesh encloses a non-positive volume (" + std::to_string(volume) +
                               " mm^3): its normals probably point inwards");
  return mesh;
}

ReamerSpec meshReamerSpec(const std::string& path) {
  ReamerSpec spec;
  spec.name = std::filesystem::path(path).filename().string();
  spec.meshFile = path;
  return spec;
}

ReamerSpec reamerFromArgument(const std::string& arg, const std::string& presetsJsonPath) {
  return std::filesystem::is_regular_file(arg) ? meshReamerSpec(arg) : loadPreset(arg, presetsJsonPath);
}

TriangleMesh cuttingSolidFor(const ReamerSpec& spec) {
  return spec.meshFile.empty() ? buildCuttingSolid(spec) : loadCuttingSolidFromFile(spec.meshFile);
}

}  // namespace reamsim
