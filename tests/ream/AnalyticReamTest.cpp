// A flat and a spherical-cap reamer fed through the whole reaming loop into a block of known size:
// removed volume against the closed form. The figures are printed so that the closing note can quote
// them, with the share due to tool faceting (inscribed polygons) separated from the rest.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ReamFixture.h"
#include "reamsim/tools/Primitives.h"

namespace reamsim {
namespace {

// Top face at z = 0; the reamer feeds along -Z from 1 mm above it.
TriangleMesh block() { return test::blockBelowZ0(); }

double capVolume(double R, double d) { return M_PI * d * d * (3 * R - d) / 3; }

struct FeedResult {
  double removed = 0;
  double worstBookkeeping = 0;
};

FeedResult feed(const ReamerSpec& spec, double depth, int steps) {
  test::ReamScene scene(block(), spec);
  FeedResult r;
  const double start = 1.0, step = (start + depth) / steps;
  for (int i = 1; i <= steps; ++i) {
    const ReamStepOutcome out = scene.controller->moveTo(Pose{{0, 0, start - i * step}, {0, 0, -1}, 0});
    r.removed += out.entry.removedMm3;
    r.worstBookkeeping = std::max(r.worstBookkeeping, out.volumeBookkeepingError / std::max(1.0, out.cut.removedMm3));
    EXPECT_FALSE(scene.controller->checkBone().selfIntersectsExact);
  }
  EXPECT_NEAR(scene.log->entries().back().cumulativeMm3, r.removed, 1e-9 * r.removed);
  return r;
}

void report(const char* what, const ReamerSpec& spec, double removed, double closedForm) {
  const double toolFaceting = 1 - signedVolume(buildCuttingSolid(spec)) / idealCuttingVolume(spec);
  std::printf("[analytic] %-34s removed %.4f mm3, closed form %.4f mm3, error %+.4f %%; whole-tool faceting %.4f %%\n",
              what, removed, closedForm, 100 * (removed - closedForm) / closedForm, 100 * toolFaceting);
}

TEST(AnalyticReam, FlatReamerIntoBlock) {
  ReamerSpec spec;
  spec.name = "flat-20";
  spec.diameterMm = 20;
  spec.bodyLengthMm = 10;
  const double depth = 2.0;
  const FeedResult r = feed(spec, depth, 12);
  const double closedForm = M_PI * 100 * depth;
  // The faceted disc is the inscribed 96-gon: area ratio sin(2π/n)/(2π/n).
  const double faceted = closedForm * std::sin(2 * M_PI / spec.segments) / (2 * M_PI / spec.segments);
  report("flat D20, 2 mm deep", spec, r.removed, closedForm);
  EXPECT_NEAR(r.removed, faceted, faceted * 1e-9);  // exact up to faceting
  EXPECT_LT(std::abs(r.removed - closedForm) / closedForm, 0.005);
  EXPECT_LT(r.worstBookkeeping, 1e-6);
}

TEST(AnalyticReam, SphericalReamerWithinTheCap) {
  ReamerSpec spec;
  spec.name = "cap-36-R30";
  spec.diameterMm = 36;
  spec.sphereRadiusMm = 30;
  // Within the cap the removed volume is dominated by the facets near the apex: 36 rings keep the
  // faceting under 0.1 % (the test prints the measured error; docs/BENCHMARKS.md quotes it).
  spec.segments = 128;
  spec.rings = 36;
  const double depth = 3.0;  // cap height is 6 mm
  const FeedResult r = feed(spec, depth, 8);
  const double closedForm = capVolume(30, depth);
  report("spherical D36 R30, 3 mm deep (128x36)", spec, r.removed, closedForm);
  EXPECT_LT(std::abs(r.removed - closedForm) / closedForm, 0.005);
  EXPECT_LT(r.worstBookkeeping, 1e-6);
}

TEST(AnalyticReam, SphericalReamerPastTheCap) {
  ReamerSpec spec;
  spec.name = "cap-36-R30";
  spec.diameterMm = 36;
  spec.sphereRadiusMm = 30;
  spec.segments = 128;
  spec.rings = 16;
  const double h = 30 - std::sqrt(30.0 * 30 - 18.0 * 18), depth = 8.0;
  const FeedResult r = feed(spec, depth, 6);
  const double closedForm = capVolume(30, h) + M_PI * 18 * 18 * (depth - h);
  report("spherical D36 R30, 8 mm deep (128x16)", spec, r.removed, closedForm);
  EXPECT_LT(std::abs(r.removed - closedForm) / closedForm, 0.005);
  EXPECT_LT(r.worstBookkeeping, 1e-6);
}

}  // namespace
}  // namespace reamsim
