#pragma once
// One function per reamsim-cli sub-command. Each returns the process exit code (see docs/CLI.md).
#include <string>
#include <vector>

namespace reamsim::cli {

enum ExitCode : int {
  kOk = 0,
  kFailed = 1,       // the operation ran but failed (e.g. a cut broke an invariant)
  kUsage = 2,        // bad command line
  kBadInput = 3,     // an input file is missing, malformed or unusable
  kWriteFailed = 4,  // an output could not be written
};

int runInfo(const std::vector<std::string>& args);
int runRepair(const std::vector<std::string>& args);
int runExport(const std::vector<std::string>& args);
int runReam(const std::vector<std::string>& args);
int runGlenoid(const std::vector<std::string>& args);
int runAxis(const std::vector<std::string>& args);  // AxisCommand.cpp
int runImportCt(const std::vector<std::string>& args);
int runBench(const std::vector<std::string>& args);     // bench KIND: dispatch (BenchCommand.cpp)
int runBenchCut(const std::vector<std::string>& args);  // bench cut (BenchCutCommand.cpp)
int runBenchCollision(const std::vector<std::string>& args);  // bench collision (BenchCollisionCommand.cpp)
int runBenchWinding(const std::vector<std::string>& args);    // bench winding (BenchWindingCommand.cpp)
// The allocator serving malloc in this process, which the benchmarks report (BenchCommand.cpp).
std::string allocatorName();

}  // namespace reamsim::cli
