#!/usr/bin/env bash
# The cutting benchmark with every peer (docs/BENCHMARKS.md): installs the npm peers (bench/peers:
# manifold-3d, csg.js) with `npm ci` when they are missing or older than the lockfile, then runs
#   reamsim-cli bench cut --bone default --peers --json [extra options]
# Extra options go to bench cut (e.g. --steps 100 --subdivide 1 --peers-budget-ms 120000; a later
# --bone MESH replaces the default).
# reamsim-cli: $REAMSIM_CLI, else build/app/cli/reamsim-cli (scripts/build.sh builds it).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
peers="$root/bench/peers"
command -v node >/dev/null || { echo "bench-peers: node not found (apt-get install nodejs npm)" >&2; exit 1; }
if [ ! -f "$peers/node_modules/.package-lock.json" ] || [ "$peers/package-lock.json" -nt "$peers/node_modules/.package-lock.json" ]; then
  (cd "$peers" && npm ci --no-audit --no-fund >&2)
fi
cli="${REAMSIM_CLI:-$root/build/app/cli/reamsim-cli}"
[ -x "$cli" ] || { echo "bench-peers: $cli not found: build it (scripts/build.sh) or set REAMSIM_CLI" >&2; exit 1; }
exec "$cli" bench cut --bone default --peers --peers-dir "$peers" --json "$@"
