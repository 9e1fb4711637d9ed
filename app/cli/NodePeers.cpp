// Runs the node peer runner (bench/peers/run_peer.mjs) as a child process and reads its one JSON object.
#include "NodePeers.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace reamsim::cli {
namespace {

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Output {
  int exitCode = -1;
  std::string out;
};

Output capture(const std::string& command) {
  Output r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 8192> buf{};
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace

std::string defaultPeersDir() {
#ifdef REAMSIM_PEERS_DIR
  return REAMSIM_PEERS_DIR;
#else
  return "bench/peers";
#endif
}

std::string nodePeersUnavailable(const std::string& peersDir) {
  namespace fs = std::filesystem;
  const Output v = capture("node --version 2>/dev/null </dev/null");
  if (v.exitCode != 0 || v.out.empty()) return "node not found on PATH (the npm peers run with node >= 18)";
  if (!fs::exists(fs::path(peersDir) / "run_peer.mjs")) return "no run_peer.mjs in " + peersDir + " (see --peers-dir)";
  for (const char* package : {"manifold-3d", "csg"})
    if (!fs::exists(fs::path(peersDir) / "node_modules" / package / "package.json"))
      return std::string("node_modules missing (") + package + "): run npm ci in " + peersDir;
  return "";
}

nlohmann::json runNodePeer(const std::string& peersDir, const std::string& peer, const std::string& sequenceDir,
                           double budgetMs) {
  namespace fs = std::filesystem;
  const fs::path errFile = fs::temp_directory_path() / ("reamsim_peer_" + std::to_string(::getpid()) + ".err");
  const std::string command = "node " + shellQuote((fs::path(peersDir) / "run_peer.mjs").string()) + " --peer " +
                              shellQuote(peer) + " --sequence " + shellQuote(sequenceDir) + " --max-total-ms " +
                              std::to_string(static_cast<long long>(budgetMs)) + " </dev/null 2>" +
                              shellQuote(errFile.string());
  const Output r = capture(command);
  std::string err;
  {
    std::ifstream in(errFile);
    std::stringstream ss;
    ss << in.rdbuf();
    err = ss.str();
  }
  std::error_code ec;
  fs::remove(errFile, ec);
  try {
    nlohmann::json j = nlohmann::json::parse(r.out);
    if (j.is_object()) return j;
  } catch (const nlohmann::json::exception&) {
  }
  if (err.size() > 600) err = "..." + err.substr(err.size() - 600);
  return {{"error", "the runner printed no JSON (exit code " + std::to_string(r.exitCode) + "): " + err}};
}

}  // namespace reamsim::cli
