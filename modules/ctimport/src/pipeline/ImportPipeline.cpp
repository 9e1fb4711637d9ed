// Runs the stages of CtImport.h in order, with timing, progress and cancellation, and fills the report.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "Stages.h"
#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/SelfIntersections.h"
#include "reamsim/mesh/Repair.h"

namespace reamsim::ct {
namespace {

using Clock = std::chrono::steady_clock;

void checkOptions(const CtVolume& v, const ImportOptions& o) {
  if (!std::isfinite(o.lowerThreshold)) throw std::invalid_argument("the threshold must be a finite number");
  if (o.upperThreshold && !std::isfinite(*o.upperThreshold))
    throw std::invalid_argument("the upper threshold must be a finite number");
  if (o.upperThreshold && *o.upperThreshold < o.lowerThreshold)
    throw std::invalid_argument("the upper threshold is below the lower threshold");
  if (!(o.volumeSmoothingSigmaMm >= 0) || o.volumeSmoothingSigmaMm > 20)
    throw std::invalid_argument("volume smoothing sigma must be between 0 and 20 mm");
  if (o.smoothingIterations < 0 || o.smoothingIterations > 1000)
    throw std::invalid_argument("smoothing iterations must be between 0 and 1000");
  if (!(o.smoothingPassBand > 0 && o.smoothingPassBand < 2))
    throw std::invalid_argument("the smoothing pass band must be in (0, 2)");
  if (o.component == ComponentMode::Seed && !o.seedWorld)
    throw std::invalid_argument("picking a component needs a seed point");
  if (v.values.size() != v.voxelCount() || v.voxelCount() == 0) throw std::invalid_argument("the volume holds no data");
}

// Progress bookkeeping: each stage owns a slice of [0,1]; a callback returning false cancels.
class Stages {
 public:
  Stages(const ProgressCallback& cb, ImportReport& report) : cb_(cb), report_(report) {}

  template <class Fn>
  auto run(const std::string& name, double from, double to, Fn&& fn) {
    report(name, from);
    const detail::Tick tick = [&](double f) { report(name, from + (to - from) * std::clamp(f, 0.0, 1.0)); };
    const Clock::time_point t0 = Clock::now();
    struct Record {
      Stages* self;
      const std::string& name;
      Clock::time_point t0;
      ~Record() {
        self->report_.stages.push_back({name, std::chrono::duration<double, std::milli>(Clock::now() - t0).count()});
      }
    } record{this, name, t0};
    return fn(tick);
  }

  void report(const std::string& stage, double fraction) {
    if (cb_ && !cb_(fraction, stage)) throw ImportCancelled(stage);
  }

 private:
  const ProgressCallback& cb_;
  ImportReport& report_;
};

std::string fmt(const char* f, double x) {
  char b[96];
  std::snprintf(b, sizeof b, f, x);
  return b;
}

}  // namespace

ImportResult importBone(const CtVolume& volume, const ImportOptions& o, const ProgressCallback& progress) {
  checkOptions(volume, o);
  const Clock::time_point start = Clock::now();
  ImportResult result;
  ImportReport& rep = result.report;
  rep.source = volume.sourcePath;
  rep.format = volume.format;
  rep.valueUnit = volume.valueUnit;
  rep.volumeSpace = volume.space;
  rep.dims = volume.dims;
  rep.spacing = volume.spacing;
  rep.lowerThreshold = o.lowerThreshold;
  rep.upperThreshold = o.upperThreshold;
  rep.volumeSmoothingSigmaMm = o.volumeSmoothingSigmaMm;
  rep.notes = volume.notes;
  const auto [mn, mx] = std::minmax_element(volume.values.begin(), volume.values.end());
  rep.minValue = *mn;
  rep.maxValue = *mx;
  if (volume.valueUnit != "HU" && rep.minValue > -500)
    rep.notes.push_back("values range " + fmt("%.0f", rep.minValue) + ".." + fmt("%.0f", rep.maxValue) +
                        " with no air near -1000: probably not Hounsfield units; the threshold " +
                        fmt("%g", o.lowerThreshold) + " is taken in the file's own units");
  Stages stages(progress, rep);

  detail::PaddedField field = stages.run("threshold", 0.0, 0.08, [&](const detail::Tick& t) {
    return detail::buildField(volume, o, t);
  });

  std::optional<std::array<int, 3>> seed;
  if (o.component == ComponentMode::Seed) {
    const Vec3 idx = volume.worldToIndex(*o.seedWorld);
    seed = std::array<int, 3>{int(std::lround(idx.x)) + 1, int(std::lround(idx.y)) + 1, int(std::lround(idx.z)) + 1};
    for (int a = 0; a < 3; ++a)
      if ((*seed)[std::size_t(a)] < 0 || (*seed)[std::size_t(a)] >= field.dims[std::size_t(a)])
        throw std::invalid_argument("the seed point lies outside the volume");
  }
  const detail::RegionStats regions = stages.run("regions", 0.08, 0.18, [&](const detail::Tick& t) {
    return detail::keepRegions(field, o.component, seed, o.fillCavities, t);
  });
  rep.voxelsInRange = regions.inRange;
  rep.regions = regions.regions;
  rep.keptVoxels = regions.kept;
  rep.cavityVoxelsFilled = regions.cavities;
  static const char* kFaces[6] = {"-i", "+i", "-j", "+j", "-k", "+k"};
  for (int s = 0; s < 6; ++s)
    if (regions.touches[std::size_t(s)]) rep.fieldOfViewCuts.push_back(kFaces[s]);
  if (!rep.fieldOfViewCuts.empty()) {
    std::string faces;
    for (const std::string& f : rep.fieldOfViewCuts) faces += (faces.empty() ? "" : ", ") + f;
    rep.notes.push_back("the bone leaves the field of view at the volume face(s) " + faces +
                        "; the surface is closed there by a flat cap on the scan boundary");
  }

  TriangleMesh iso = stages.run("isosurface", 0.18, 0.3, [&](const detail::Tick& t) {
    return detail::extractIsosurface(field, volume, t);
  });
  field.values = {};  // release ~4 bytes per voxel before the surface stages
  rep.isosurfaceFaces = iso.triangles.size();
  rep.isosurfaceVolumeMm3 = signedVolume(iso);

  // Decimation first, then smoothing (as 3D Slicer's segmentation-to-model does): the exact
  // self-intersection searches then run on the decimated mesh, not on the 3-4 times larger isosurface.
  TriangleMesh mesh;
  std::optional<SelfIntersectionResult> check;  // an exact search of `mesh` as it is now, if one was made
  if (o.targetFaces > 0 && iso.triangles.size() > o.targetFaces) {
    detail::DecimationOutcome d = stages.run("decimation", 0.3, 0.7, [&](const detail::Tick& t) {
      return detail::decimateWithoutIntersections(iso, o.targetFaces, rep.isosurfaceVolumeMm3, t);
    });
    rep.decimated = d.decimated;
    rep.decimationAttempts = d.attempts;
    rep.decimationGuardedVertices = d.guardedVertices;
    if (!d.decimated)
      rep.notes.push_back("decimation to " + std::to_string(o.targetFaces) + " faces kept self-intersecting after " +
                          std::to_string(d.attempts) + " attempts; the undecimated mesh is used");
    else if (d.attempts > 1)
      rep.notes.push_back("decimation re-run " + std::to_string(d.attempts - 1) + " time(s), guarded against " +
                          "self-intersections around " + std::to_string(d.guardedVertices) + " vertices");
    mesh = std::move(d.mesh);
    if (d.decimated) check = std::move(d.check);
  } else {
    mesh = std::move(iso);
  }
  iso = {};

  if (o.smoothingIterations > 0) {
    const TriangleMesh unsmoothed = mesh;  // free of self-intersections: the isosurface or checked decimation
    mesh = stages.run("smoothing", 0.7, 0.8, [&](const detail::Tick& t) {
      TriangleMesh s = detail::windowedSincSmooth(unsmoothed, o.smoothingIterations, o.smoothingPassBand, t);
      rep.smoothingVolumeCorrectionMm = detail::restoreVolume(s, rep.isosurfaceVolumeMm3);
      return s;
    });
    stages.run("smoothing self-intersections", 0.8, 0.9, [&](const detail::Tick& t) {
      bool everything = false;
      check.emplace();
      rep.smoothingRestoredVertices = detail::restoreWhereSelfIntersecting(mesh, unsmoothed, everything, *check, t);
      if (everything) rep.notes.push_back("smoothing kept creating self-intersections; the unsmoothed surface is used");
      else if (rep.smoothingRestoredVertices)
        rep.notes.push_back(std::to_string(rep.smoothingRestoredVertices) +
                            " vertices left unsmoothed where smoothing made the surface self-intersect");
      return 0;
    });
  }

  // Patient space of the output (negating x and y is exact: `check` stays valid).
  result.space = volume.space;
  if (o.outputSpace && *o.outputSpace != volume.space) {
    if (volume.space == PatientSpace::Unspecified) {
      rep.notes.push_back(std::string("the volume names no patient space; coordinates are not converted to ") +
                          toString(*o.outputSpace));
    } else {
      for (Vec3& p : mesh.vertices) p = convertPoint(p, volume.space, *o.outputSpace);
      result.space = *o.outputSpace;
    }
  }
  rep.outputSpace = result.space;

  stages.run("validation", 0.9, 1.0, [&](const detail::Tick&) {
    ValidationOptions vo;
    vo.checkSelfIntersections = o.cgalSelfIntersectionCheck;
    rep.validation = validateMesh(mesh, vo);
    const SelfIntersectionResult own = check ? std::move(*check) : findSelfIntersections(mesh, vo.maxSelfIntersectionPairs);
    if (o.cgalSelfIntersectionCheck) {
      rep.selfIntersectionCheck = "CGAL self_intersections (Foundation validateMesh)";
      if (*rep.validation.selfIntersectingPairs != own.pairs.size() + own.degenerateFaces.size())
        rep.notes.push_back("the fast self-intersection search found " + std::to_string(own.pairs.size()) +
                            " pairs, CGAL " + std::to_string(*rep.validation.selfIntersectingPairs));
    } else {
      rep.validation.selfIntersectingPairs = own.pairs.size() + (own.truncated ? 1 : 0);
      rep.selfIntersectionCheck = "exact grid search (ctimport findSelfIntersections, CGAL predicates)";
    }
    return 0;
  });

  if (!rep.validation.isCleanSolid()) {
    stages.run("repair", 1.0, 1.0, [&](const detail::Tick&) {
      // The repair is rare here (the pipeline's own surface is closed) and has no share of the bar, so its
      // progress shows as the stage's name ("repair: remesh: …"); a cancel throws ImportCancelled from it.
      RepairOptions repairOptions = importRepairOptions();
      repairOptions.progress = [&stages](double, const std::string& stage) {
        stages.report("repair: " + stage, 1.0);
        return true;
      };
      RepairResult r = repairMesh(mesh, repairOptions);
      rep.repaired = true;
      rep.notes.push_back("the mesh was not a clean solid; repairMesh: " +
                          (r.report.actions.empty() ? std::string("no action") : r.report.actions.back()));
      mesh = std::move(r.mesh);
      rep.validation = r.report.after;
      rep.selfIntersectionCheck = "CGAL self_intersections (Foundation repairMesh)";
      return 0;
    });
  }
  result.mesh = std::move(mesh);
  rep.totalMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  if (progress) progress(1.0, "done");  // informational: there is nothing left to cancel
  return result;
}

}  // namespace reamsim::ct
