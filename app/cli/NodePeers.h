#pragma once
// The npm peers of `bench cut --peers` (bench/peers: manifold-3d and csg.js), run with node on an
// exported sequence. See docs/BENCHMARKS.md.
#include <nlohmann/json.hpp>
#include <string>

namespace reamsim::cli {

// The bench/peers directory built in (REAMSIM_PEERS_DIR, the source tree's), used without --peers-dir.
std::string defaultPeersDir();

// Why the node peers cannot run ("node not found on PATH", "node_modules missing: run npm ci in DIR",
// ...), or "" when they can.
std::string nodePeersUnavailable(const std::string& peersDir);

// Runs `node DIR/run_peer.mjs --peer PEER --sequence SEQ --max-total-ms BUDGET` and returns the JSON it
// prints; on a runner that prints no JSON, {"error": ...} with its exit code and the end of its stderr.
nlohmann::json runNodePeer(const std::string& peersDir, const std::string& peer, const std::string& sequenceDir,
                           double budgetMs);

}  // namespace reamsim::cli
