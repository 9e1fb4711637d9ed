#include "MeshImportPlugin.h"

#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/Repair.h"
#include "reamsim/mesh/Validation.h"

namespace reamsim::ui {

QStringList MeshImportPlugin::extensions() const {
  QStringList out;
  for (const std::string& e : supportedMeshExtensions()) out << QString::fromStdString(e).remove('.').toLower();
  return out;
}

QStringList MeshImportPlugin::nameFilters() const {
  QStringList patterns;
  for (const QString& e : extensions()) patterns << "*." + e;
  return {QStringLiteral("Meshes (%1)").arg(patterns.join(' ')), QStringLiteral("All files (*)")};
}

ImportedBone MeshImportPlugin::importBone(const std::string& path, bool repair, const RepairProgress& progress) const {
  // One bar for the whole import: the read ("reading", "parsing": Cancel does not wait for a large text file) its
  // first tenth, the validation or the repair the rest.
  constexpr double kReadShare = 0.1;
  const auto share = [&progress](double from, double to) -> ProgressCallback {
    if (!progress) return {};
    return [&progress, from, to](double f, const std::string& stage) { return progress(from + f * (to - from), stage); };
  };
  ReadOptions reading;
  reading.progress = share(0.0, kReadShare);
  LoadedMesh loaded = readMesh(path, reading);
  ImportedBone out;
  out.source = path;
  out.saved = factsFromComments(loaded.comments);
  out.frame = out.saved.frame;
  for (const std::string& n : loaded.notes) out.report += "note: " + n + "\n";
  if (out.frame != PatientFrame::Unspecified)
    out.report += std::string("patient frame from the file: ") + toString(out.frame) + "\n";
  out.original = std::make_shared<const TriangleMesh>(loaded.mesh);
  if (!repair) {
    // Taken as read. A closed, outward surface is offered to the cutting engine even with a few
    // self-intersections: the local engine cuts away from defects and refuses a cut that reaches one. The
    // validation reports its progress and stops on a cancel (its self-intersection count takes ~20 s at
    // millions of triangles).
    ValidationOptions validation;
    validation.progress = StageProgress{&progress, kReadShare, 1.0, "validation"};
    const ValidationReport v = validateMesh(loaded.mesh, validation);
    out.mesh = std::move(loaded.mesh);
    out.cuttable = v.closed && v.outwardOriented && v.topology.degenerateFaces == 0;
    const std::size_t si = v.selfIntersectingPairs.value_or(0);
    if (out.cuttable)
      out.report += "loaded without repair: closed and outward" +
                    (si ? ", " + std::to_string(si) + " self-intersecting face pairs (cuts that reach them are refused)"
                        : std::string()) +
                    "\n";
    else
      out.report += "loaded without repair: not a closed, outward surface (" + toText(v) +
                    "); shown as read, cutting disabled\n";
    return out;
  }
  RepairOptions options = importRepairOptions();
  options.progress = share(kReadShare, 1.0);
  RepairResult r = repairMesh(loaded.mesh, options);
  out.report += toText(r.report);
  out.cuttable = r.report.success();
  out.mesh = out.cuttable ? std::move(r.mesh) : std::move(loaded.mesh);
  if (!out.cuttable) out.report += "could not be repaired into a closed solid: shown as read, cutting disabled\n";
  return out;
}

void MeshImportPlugin::exportMesh(const TriangleMesh& mesh, const std::string& path, const BoneFileFacts& facts,
                                  const ProgressCallback& progress) const {
  WriteOptions o;
  o.progress = progress;
  o.comments = factComments(facts);
  writeMesh(mesh, path, o);
}

}  // namespace reamsim::ui
