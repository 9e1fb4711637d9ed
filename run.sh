#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job: the default reaming plan on the bundled
# scapula, printing one row per step (removed volume and time of each cut).
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh
mkdir -p out
./build/app/cli/reamsim-cli ream --bone default --reamer glenoid-36-R30 --plan default --out out/default-run
