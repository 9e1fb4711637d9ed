// The import pipeline's behaviour on synthetic volumes of known geometry: field-of-view caps, cavities,
// the upper threshold, component choice, threshold semantics, progress and cancellation, patient space,
// slices and preview for the GUI plugin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "Phantom.h"
#include "TestUtil.h"
#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/Preview.h"
#include "reamsim/ctimport/SelfIntersections.h"

namespace {

using namespace reamsim;
constexpr double kPi = 3.14159265358979323846;

ct::CtVolume makeVolume(const phantom::Grid& g, const std::vector<float>& values) {
  ct::CtVolume v;
  v.dims = g.dims;
  v.spacing = g.spacing;
  v.origin = g.origin;
  v.direction = g.direction;
  v.space = ct::PatientSpace::LPS;
  v.values = values;
  v.integerValued = false;
  v.valueUnit = "HU";
  v.sourcePath = "synthetic";
  v.format = "test";
  return v;
}

ct::CtVolume makeVolume(const phantom::Grid& g, const phantom::Solid& solid) {
  return makeVolume(g, phantom::sample(g, solid));
}

ct::ImportOptions midThreshold() {
  ct::ImportOptions o;
  o.lowerThreshold = 620;
  return o;
}

const phantom::Grid kGrid = phantom::gridAround({0, 0, 0}, 16, {1, 1, 1}, phantom::rotation({0, 0, 1}, 0));

TEST(Pipeline, BoneLeavingTheFieldOfViewIsClosedByCapsOnTheScanBoundary) {
  // A rod along k longer than the scan: cut at both ends.
  const ct::CtVolume v = makeVolume(kGrid, [](const Vec3& p) { return p.x * p.x + p.y * p.y < 64; });
  ct::ImportOptions o = midThreshold();
  o.smoothingIterations = 0;  // smoothing would round the rims; here the caps themselves are under test
  o.targetFaces = 0;
  const ct::ImportResult r = ct::importBone(v, o);
  EXPECT_TRUE(r.report.validation.isCleanSolid()) << ct::toText(r.report);
  EXPECT_EQ(r.report.fieldOfViewCuts, (std::vector<std::string>{"-k", "+k"}));
  // The caps lie half a voxel beyond the first and last slice centres: the length is dims × spacing.
  const double length = kGrid.dims[2] * kGrid.spacing[2];
  EXPECT_NEAR(*r.report.validation.volumeMm3 / (kPi * 64 * length), 1.0, 0.01);
  const Bounds b = computeBounds(r.mesh);
  EXPECT_NEAR(b.max.z - b.min.z, length, 1e-6);
}

TEST(Pipeline, EnclosedCavitiesAreFilledUnlessAskedNotTo) {
  const ct::CtVolume v = makeVolume(kGrid, [](const Vec3& p) { return norm(p) < 12 && norm(p) > 7; });
  ct::ImportOptions o = midThreshold();
  const ct::ImportResult filled = ct::importBone(v, o);
  EXPECT_TRUE(filled.report.validation.isCleanSolid());
  EXPECT_GT(filled.report.cavityVoxelsFilled, 1000u);
  EXPECT_EQ(filled.report.validation.topology.connectedComponents, 1u);
  EXPECT_NEAR(*filled.report.validation.volumeMm3 / (4.0 / 3 * kPi * 1728), 1.0, 0.01);

  o.fillCavities = false;
  const ct::ImportResult hollow = ct::importBone(v, o);
  EXPECT_TRUE(hollow.report.validation.isCleanSolid()) << ct::toText(hollow.report);
  EXPECT_EQ(hollow.report.validation.topology.connectedComponents, 2u);  // outer and inner wall
  EXPECT_NEAR(*hollow.report.validation.volumeMm3 / (4.0 / 3 * kPi * (1728 - 343)), 1.0, 0.015);
}

TEST(Pipeline, UpperThresholdLeavesOutMetal) {
  // Bone ball (1200 HU) pierced by a metal rod (3000 HU) that sticks out on both sides.
  const phantom::Solid ball = [](const Vec3& p) { return norm(p) < 10; };
  const phantom::Solid rod = [](const Vec3& p) { return p.x * p.x + p.y * p.y < 2.5 * 2.5 && std::abs(p.z) < 14; };
  const std::vector<float> bone = phantom::sample(kGrid, ball, 40, 1200);
  const std::vector<float> metal = phantom::sample(kGrid, rod, 0, 1, 4);  // metal fraction
  std::vector<float> hu(bone.size());
  for (std::size_t i = 0; i < hu.size(); ++i) hu[i] = bone[i] * (1 - metal[i]) + 3000 * metal[i];
  const ct::CtVolume v = makeVolume(kGrid, hu);
  ct::ImportOptions o = midThreshold();
  o.upperThreshold = 2000;  // half way between bone and metal
  const ct::ImportResult r = ct::importBone(v, o);
  EXPECT_TRUE(r.report.validation.isCleanSolid()) << ct::toText(r.report);
  const double rodInBall = 4.0 / 3 * kPi * (1000 - std::pow(100 - 6.25, 1.5));
  EXPECT_NEAR(*r.report.validation.volumeMm3 / (4.0 / 3 * kPi * 1000 - rodInBall), 1.0, 0.02);
  EXPECT_EQ(r.report.cavityVoxelsFilled, 0u);  // the bore is open at both ends: not a cavity

  const ct::ImportResult all = ct::importBone(v, midThreshold());  // without the upper bound: ball + rod
  EXPECT_NEAR(*all.report.validation.volumeMm3 / (4.0 / 3 * kPi * 1000 + kPi * 6.25 * 28 - 2 * kPi * 6.25 * std::sqrt(93.75)),
              1.0, 0.02);
}

TEST(Pipeline, LargestSeededOrAllComponents) {
  phantom::SphereAndCylinder shape;
  shape.center = {0, 0, 0};
  shape.cylinderLength = 24;
  shape.fragment = true;
  shape.fragmentCenter = {0, 17, 0};
  const phantom::Grid g = phantom::gridAround({0, 2, 0}, 23, {1, 1, 1}, phantom::rotation({1, 0, 0}, 20));
  const ct::CtVolume v = makeVolume(g, [&](const Vec3& p) { return shape.inside(p); });
  ct::ImportOptions o = midThreshold();
  o.targetFaces = 0;

  const ct::ImportResult largest = ct::importBone(v, o);
  EXPECT_EQ(largest.report.regions, 2u);
  EXPECT_NEAR(*largest.report.validation.volumeMm3 / shape.mainVolume(), 1.0, 0.01);

  o.component = ct::ComponentMode::Seed;
  o.seedWorld = shape.fragmentCenter + Vec3{0.4, 0, 0};
  const ct::ImportResult picked = ct::importBone(v, o);
  EXPECT_TRUE(picked.report.validation.isCleanSolid());
  // A 7 mm ball on a 1 mm grid: the isosurface is a few per cent small (chords of a tight curve).
  EXPECT_NEAR(*picked.report.validation.volumeMm3 / shape.fragmentVolume(), 1.0, 0.1);

  o.seedWorld = Vec3{0, 30, 30};  // nowhere near bone
  EXPECT_THROW(ct::importBone(v, o), std::invalid_argument);

  o.component = ct::ComponentMode::All;
  const ct::ImportResult all = ct::importBone(v, o);
  EXPECT_EQ(all.report.validation.topology.connectedComponents, 2u);
  EXPECT_NEAR(*all.report.validation.volumeMm3 /
                  (*largest.report.validation.volumeMm3 + *picked.report.validation.volumeMm3), 1.0, 0.002);
}

TEST(Pipeline, IntegerSamplesAtTheThresholdCountAsBone) {
  std::vector<float> hu(kGrid.voxels(), 0);
  ct::CtVolume v = makeVolume(kGrid, hu);
  v.integerValued = true;
  for (int k = 10; k < 20; ++k)
    for (int j = 10; j < 20; ++j)
      for (int i = 10; i < 20; ++i) v.values[v.index(i, j, k)] = 300;
  ct::ImportOptions o;
  o.lowerThreshold = 300;
  o.smoothingIterations = 0;
  const ct::ImportResult r = ct::importBone(v, o);
  EXPECT_EQ(r.report.voxelsInRange, 1000u);
  EXPECT_TRUE(r.report.validation.isCleanSolid()) << ct::toText(r.report);
  // Iso-value 299.5 between 0 and 300: the surface passes just outside the voxel centres (9 mm cube).
  EXPECT_NEAR(*r.report.validation.volumeMm3, 729.0, 2.0);
  o.lowerThreshold = 300.5;
  EXPECT_THROW(ct::importBone(v, o), std::runtime_error);
}

TEST(Pipeline, ProgressRisesToOneAndCancellationStopsWithTheStageName) {
  phantom::SphereAndCylinder shape;
  shape.center = {0, 0, 0};
  const phantom::Grid g = phantom::gridAround({0, 0, 0}, 24, {0.7, 0.7, 0.7}, phantom::rotation({0, 0, 1}, 0));
  const ct::CtVolume v = makeVolume(g, [&](const Vec3& p) { return shape.inside(p); });
  ct::ImportOptions o = midThreshold();
  o.targetFaces = 5000;
  std::vector<std::pair<double, std::string>> seen;
  const ct::ImportResult r = ct::importBone(v, o, [&](double f, const std::string& stage) {
    seen.emplace_back(f, stage);
    return true;
  });
  ASSERT_FALSE(seen.empty());
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i].first, seen[i - 1].first) << seen[i].second;
  EXPECT_EQ(seen.back(), (std::pair<double, std::string>{1.0, "done"}));
  for (const char* stage : {"threshold", "regions", "isosurface", "decimation", "smoothing", "validation"})
    EXPECT_TRUE(std::any_of(seen.begin(), seen.end(), [&](const auto& s) { return s.second == stage; })) << stage;
  EXPECT_TRUE(r.report.decimated);

  try {
    ct::importBone(v, o, [](double, const std::string& stage) { return stage != "decimation"; });
    ADD_FAILURE() << "not cancelled";
  } catch (const ct::ImportCancelled& e) {
    EXPECT_EQ(e.stage(), "decimation");
  }
}

TEST(Pipeline, InconsistentOptionsAreRefused) {
  const ct::CtVolume v = makeVolume(kGrid, [](const Vec3& p) { return norm(p) < 8; });
  ct::ImportOptions o = midThreshold();
  o.upperThreshold = 100;
  EXPECT_THROW(ct::importBone(v, o), std::invalid_argument);
  o = midThreshold();
  o.component = ct::ComponentMode::Seed;
  EXPECT_THROW(ct::importBone(v, o), std::invalid_argument);
  o = midThreshold();
  o.smoothingPassBand = 0;
  EXPECT_THROW(ct::importBone(v, o), std::invalid_argument);
  o = midThreshold();
  o.lowerThreshold = 5000;
  EXPECT_THROW(ct::importBone(v, o), std::runtime_error);
}

TEST(Pipeline, OutputSpaceIsConvertedAndRecorded) {
  ct::CtVolume v = makeVolume(kGrid, [](const Vec3& p) { return norm(p - Vec3{4, -3, 2}) < 7; });
  v.space = ct::PatientSpace::RAS;
  ct::ImportOptions o = midThreshold();
  o.outputSpace = std::nullopt;
  const ct::ImportResult native = ct::importBone(v, o);
  EXPECT_EQ(native.space, ct::PatientSpace::RAS);
  EXPECT_NEAR(norm(cttest::solidCentroid(native.mesh) - Vec3{4, -3, 2}), 0.0, 0.2);
  o.outputSpace = ct::PatientSpace::LPS;
  const ct::ImportResult lps = ct::importBone(v, o);
  EXPECT_EQ(lps.space, ct::PatientSpace::LPS);
  EXPECT_EQ(lps.report.outputSpace, ct::PatientSpace::LPS);
  EXPECT_NEAR(norm(cttest::solidCentroid(lps.mesh) - Vec3{-4, 3, 2}), 0.0, 0.2);
  EXPECT_TRUE(lps.report.validation.outwardOriented);  // x, y negation keeps handedness
}

TEST(Pipeline, NoisyScanStillGivesOneCleanSolid) {
  phantom::SphereAndCylinder shape;
  shape.center = {0, 0, 0};
  const phantom::Grid g = phantom::gridAround({0, 0, 0}, 24, {0.8, 0.8, 1.2}, phantom::rotation({1, 1, 0}, 40));
  std::vector<float> hu = phantom::sample(g, [&](const Vec3& p) { return shape.inside(p); });
  std::uint32_t state = 12345;
  for (float& x : hu) {  // ±150 HU of deterministic noise: specks above threshold all over the tissue
    state = state * 1664525u + 1013904223u;
    x += float(int(state >> 16) % 301 - 150);
  }
  const ct::CtVolume v = makeVolume(g, hu);
  ct::ImportOptions o;
  o.lowerThreshold = 620;
  o.volumeSmoothingSigmaMm = 0.8;
  o.targetFaces = 8000;
  const ct::ImportResult r = ct::importBone(v, o);
  EXPECT_TRUE(r.report.validation.isCleanSolid()) << ct::toText(r.report);
  EXPECT_EQ(r.report.validation.topology.connectedComponents, 1u);
  EXPECT_NEAR(*r.report.validation.volumeMm3 / shape.mainVolume(), 1.0, 0.03);
}

TEST(GuiSupport, SlicesCarryValuesMaskAndPlacement) {
  phantom::Grid g = phantom::gridAround({5, 5, 5}, 10, {0.5, 0.75, 1.25}, phantom::rotation({0, 1, 0}, 10));
  const ct::CtVolume v = makeVolume(g, [](const Vec3& p) { return norm(p - Vec3{5, 5, 5}) < 6; });
  const ct::SliceImage k = ct::extractSlice(v, ct::SliceAxis::K, 8, 620);
  EXPECT_EQ(k.width, v.dims[0]);
  EXPECT_EQ(k.height, v.dims[1]);
  EXPECT_EQ(k.values[std::size_t(3 * k.width + 5)], v.at(5, 3, 8));
  EXPECT_EQ(k.mask[std::size_t(3 * k.width + 5)], v.at(5, 3, 8) >= 620 ? 1 : 0);
  EXPECT_NEAR(norm(k.origin - v.indexToWorld(0, 0, 8)), 0.0, 1e-9);
  EXPECT_NEAR(norm(k.rowDirection - v.axis(0)), 0.0, 1e-12);
  EXPECT_EQ(k.pixelSpacing[0], 0.5);
  EXPECT_EQ(k.pixelSpacing[1], 0.75);
  const ct::SliceImage i = ct::extractSlice(v, ct::SliceAxis::I, v.dims[0] / 2, 620, 1300);
  EXPECT_EQ(i.width, v.dims[1]);
  EXPECT_EQ(i.height, v.dims[2]);
  const std::size_t centre = std::size_t(i.height / 2) * std::size_t(i.width) + std::size_t(i.width / 2);
  EXPECT_EQ(i.mask[centre], 1);
  EXPECT_EQ(i.values[centre], v.at(v.dims[0] / 2, i.width / 2, i.height / 2));
  EXPECT_THROW(ct::extractSlice(v, ct::SliceAxis::J, v.dims[1], 620), std::out_of_range);
}

TEST(GuiSupport, PreviewIsACoarseSurfaceInTheSamePlace) {
  phantom::SphereAndCylinder shape;
  const phantom::Grid g = phantom::gridAround(shape.center, 26, {0.5, 0.5, 0.5}, phantom::rotation({0, 0, 1}, 0));
  const ct::CtVolume v = makeVolume(g, [&](const Vec3& p) { return shape.inside(p); });
  const ct::CtVolume small = ct::downsample(v, 32);
  EXPECT_LE(std::max({small.dims[0], small.dims[1], small.dims[2]}), 32);
  const int f = (v.dims[0] + 31) / 32;  // block size: a block's average sits at the block's centre
  EXPECT_EQ(small.spacing[0], v.spacing[0] * f);
  EXPECT_NEAR(norm(small.indexToWorld(1, 1, 1) - v.indexToWorld(f + (f - 1) / 2.0, f + (f - 1) / 2.0, f + (f - 1) / 2.0)),
              0.0, 1e-9);
  const ct::ImportResult p = ct::previewSurface(v, midThreshold(), 32);
  const ValidationReport rep = validateMesh(p.mesh, {false});
  EXPECT_TRUE(rep.closed);
  EXPECT_LT(rep.triangles, 20000u);
  EXPECT_NEAR(*rep.volumeMm3 / shape.mainVolume(), 1.0, 0.1);
  EXPECT_NEAR(norm(cttest::solidCentroid(p.mesh) - shape.center), 0.0, 1.0);
}

}  // namespace
