#include "MeshImportPlugin.h"

#include <charconv>
#include <cmath>

#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/Repair.h"
#include "reamsim/mesh/Validation.h"

namespace reamsim::ui {
namespace {

// The comment lines ReamSim writes to keep a bone's facts (BoneFileFacts; docs/CT_IMPORT.md, docs/GUI.md).
constexpr std::string_view kFrameComment = "reamsim patient_frame ";
constexpr std::string_view kRemovedComment = "reamsim removed_mm3 ";
constexpr std::string_view kCutLogComment = "reamsim cut_log ";  // rows, then the last row's time in ms

// The text after `prefix` in the first comment that starts with it.
std::optional<std::string_view> factText(const std::vector<std::string>& comments, std::string_view prefix) {
  for (const std::string& c : comments)
    if (std::string_view(c).substr(0, prefix.size()) == prefix) return std::string_view(c).substr(prefix.size());
  return std::nullopt;
}

// Whole text as a number (from_chars: the same in every locale); anything else is not a fact ReamSim wrote.
template <class T>
std::optional<T> number(std::optional<std::string_view> text) {
  if (!text) return std::nullopt;
  T value{};
  const auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (ec != std::errc() || end != text->data() + text->size()) return std::nullopt;
  return value;
}

std::string numberText(double value) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, 17);
  return std::string(buf, r.ptr);
}

}  // namespace

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
  LoadedMesh loaded = readMesh(path);
  ImportedBone out;
  out.source = path;
  if (const auto frame = factText(loaded.comments, kFrameComment))
    out.frame = parsePatientFrame(*frame).value_or(PatientFrame::Unspecified);
  if (const auto removed = number<double>(factText(loaded.comments, kRemovedComment)); removed && std::isfinite(*removed))
    out.removedMm3 = *removed;
  if (const auto log = factText(loaded.comments, kCutLogComment)) {
    const std::size_t space = log->find(' ');
    const auto rows = number<std::size_t>(log->substr(0, space));
    const auto lastMs = space == std::string_view::npos ? std::nullopt : number<std::int64_t>(log->substr(space + 1));
    if (rows && lastMs) {
      out.cutLogRows = rows;
      out.cutLogLastMs = *lastMs;
    }
  }
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
    validation.progress = StageProgress{&progress, 0.0, 1.0, "validation"};
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
  options.progress = progress;
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
  if (facts.frame != PatientFrame::Unspecified)
    o.comments.push_back(std::string(kFrameComment) + std::string(toString(facts.frame)));
  if (facts.cutLogRows)
    o.comments.push_back(std::string(kCutLogComment) + std::to_string(*facts.cutLogRows) + " " +
                         std::to_string(facts.cutLogLastMs));
  if (facts.removedMm3) o.comments.push_back(std::string(kRemovedComment) + numberText(*facts.removedMm3));
  writeMesh(mesh, path, o);
}

}  // namespace reamsim::ui
