#pragma once
// Checks the `machine` reading the benchmarks print beside their figures (app/cli/MachineSpeed.h), as the
// tests of `bench collision` and `bench cut` both ask of it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace reamsim::test {

// `machine` = {"before": reading, "after": reading}. A dependent load through 64 MiB waits for memory,
// through 256 KiB for the core's own cache: a walk the prefetchers or the compiler could shortcut would not
// show the difference. Read with at(): a missing key throws, which the test reports as a failure.
inline void expectMachineReading(const nlohmann::json& machine) {
  for (const char* when : {"before", "after"}) {
    const auto& m = machine.at(when);
    EXPECT_GT(m.at("fma_ns").get<double>(), 0.0) << when;
    const double near = m.at("load_ns").at("256KiB").get<double>(), far = m.at("load_ns").at("64MiB").get<double>();
    EXPECT_GT(near, 0.0) << when;
    EXPECT_GT(m.at("load_ns").at("8MiB").get<double>(), 0.0) << when;
    EXPECT_GT(far, 2 * near) << when << ": " << m.dump();
    EXPECT_GT(m.at("probe_ms").get<double>(), 0.0) << when;
  }
}

}  // namespace reamsim::test
