// reamsim-cli: the headless face of ReamSim. Every command is a thin adapter over modules/*.
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "CliArgs.h"
#include "Commands.h"
#include "reamsim/mesh/MeshError.h"

namespace {

const char* kUsageText =
    "usage: reamsim-cli COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  info MESH [--units m|mm|auto] [--json] [--no-self-intersections]\n"
    "      validation report: counts, closed, boundary/non-manifold edges, orientation,\n"
    "      self-intersections, degenerate faces, volume, bounds\n"
    "  repair MESH --out FILE [--units ...] [--voxel MM] [--target-faces N] [--json]\n"
    "      repair on import (merge, clean, orient, close holes; volumetric remesh when needed)\n"
    "  export MESH|default --out FILE [--units ...] [--repair] [--ascii]\n"
    "      convert between STL, OBJ, PLY, OFF and VTP (the format follows the extension)\n"
    "  ream --bone MESH|default --reamer PRESET|MESH --plan PLAN.json|default --out DIR [--json]\n"
    "       [--engine local|reference] (cutting engine, default local; see docs/CSG.md)\n"
    "       [--collision bvh|thesis] (collision engine, default bvh; see docs/COLLISION.md)\n"
    "       [--no-cleanup] (the local engine without its band clean-up: the exact Boolean alone)\n"
    "      run a reaming plan; prints one row per step and writes DIR/log.csv, DIR/log.json and\n"
    "      the final bone mesh\n"
    "  bench cut [--bone default|MESH [--units ...] [--merge-coincident] [--avoid-defects]] [--subdivide N] [--steps N]\n"
    "            [--peers [--peers-dir DIR] [--peers-budget-ms N]] [--path jitter|soak] [--cut-site glenoid|top]\n"
    "            [--depth MM] [--tilt DEG] [--reamer PRESET] [--segments N] [--rings N] [--no-cleanup]\n"
    "            [--cleanup-deviation-mm MM] [--cleanup-min-edge-mm MM] [--cleanup-min-angle-deg DEG]\n"
    "            [--check-every N] [--table-5-1] [--loop] [--export-sequence DIR] [--json]\n"
    "      time the local CSG engine on a reaming path; one JSON object (docs/BENCHMARKS.md)\n"
    "  bench winding --mesh MESH|default [--units ...] [--points N] [--seed S] [--json]\n"
    "  bench collision --bone MESH|default [--reamer PRESET|MESH [--solid-only]] [--segments N --rings M] [--poses N] [--cut-site glenoid|random] [--json]\n"
    "      time the collision queries vs the thesis brute force and CGAL AABB_tree; one JSON object (docs/COLLISION.md)\n"
    "\n"
    "  glenoid MESH [--units ...] [--out FILE.json]\n"
    "      find the glenoid (centre, outward axis, best-fit sphere) of a scapula in the OpenSim frame\n"
    "  axis [--landmarks FILE|default] [--axis X,Y,Z | --plan PLAN.json|default]\n"
    "      version and inclination of reaming axes in the scapular frame (default: the default plan's)\n"
    "  axis [--landmarks FILE|default] --version DEG --inclination DEG [--clearance MM]\n"
    "       [--plan-out PLAN.json [--reamer PRESET] [--step MM] [--count N]]\n"
    "      the reamer aimed through the glenoid centre at these angles, and a feed plan along it\n"
    "      (docs/PLANNING.md)\n"
    "  axis ... --bone MESH|default [--units ...] [--glenoid-radius MM]\n"
    "      also the glenoid face's own version and inclination (its surface within MM, default 10, of the\n"
    "      glenoid centre), and what each axis corrects of them\n"
    "  import-ct VOLUME --out MESH [--threshold HU] [--upper-threshold HU] [--target-faces N] [--smooth N] [--json]\n"
    "      CT volume (DICOM dir, .nrrd/.nhdr, .mha/.mhd, .nii/.nii.gz) to a closed bone mesh; see docs/CT_IMPORT.md\n"
    "\n"
    "exit codes: 0 ok, 1 operation failed, 2 usage error, 3 bad input file, 4 output not written\n"
    "see docs/CLI.md\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace reamsim::cli;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(kUsageText, args.empty() ? stderr : stdout);
    return args.empty() ? kUsage : kOk;
  }
  const std::map<std::string, std::function<int(const std::vector<std::string>&)>> commands = {
      {"info", runInfo}, {"repair", runRepair}, {"export", runExport}, {"ream", runReam}, {"glenoid", runGlenoid}, {"axis", runAxis}, {"import-ct", runImportCt}, {"bench", runBench}};
  const auto it = commands.find(args[0]);
  if (it == commands.end()) {
    std::fprintf(stderr, "reamsim-cli: unknown command '%s'\n\n%s", args[0].c_str(), kUsageText);
    return kUsage;
  }
  try {
    return it->second(std::vector<std::string>(args.begin() + 1, args.end()));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "reamsim-cli %s: %s\n", args[0].c_str(), e.what());
    return kUsage;
  } catch (const reamsim::InputError& e) {
    std::fprintf(stderr, "reamsim-cli %s: error: %s\n", args[0].c_str(), e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reamsim-cli %s: error: %s\n", args[0].c_str(), e.what());
    return kFailed;
  }
}
