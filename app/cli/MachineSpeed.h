#pragma once
// A reading of how fast this machine is at the moment, which the benchmarks print beside their own figures.
// A shared virtual machine's speed drifts by 1.5x and more within an hour (docs/BENCHMARKS.md): its neighbours
// load the caches and memory it shares with them, which the guest sees neither as steal time nor as a lower
// clock. A figure held against an absolute line (first contact <= 20 us) cannot be read without knowing on
// which stretch it was measured; a ratio to a peer in the same run can, and still moves when the two depend
// on the memory differently.
#include <nlohmann/json.hpp>

namespace reamsim::cli {

// About 0.2 s: the latency of a dependent floating-point multiply-add (the core's clock and how much of it a
// neighbour on the same physical core leaves), and of a dependent load through a random cycle of cache lines
// in 256 KiB (the core's own cache), 8 MiB (the shared last-level cache, as much of it as the neighbours
// leave) and 64 MiB (memory). {"fma_ns": ..., "load_ns": {"256KiB": ..., "8MiB": ..., "64MiB": ...},
// "probe_ms": ...}
nlohmann::json machineSpeed();

}  // namespace reamsim::cli
