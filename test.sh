#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test: the Release build with all tests (GUI tests
# under xvfb-run), then the mesh I/O and core tests again under AddressSanitizer + UBSan.
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh
# The npm benchmark peers (bench/peers: manifold-3d, csg.js) for their runner's tests, where node is already
# installed; without node, or if the registry cannot be reached, those two tests skip.
if command -v node > /dev/null && command -v npm > /dev/null && [ ! -d bench/peers/node_modules ]; then
  if ! (cd bench/peers && timeout 300 npm ci --no-audit --no-fund > /dev/null 2>&1); then
    rm -rf bench/peers/node_modules  # a partial install must not make the tests fail instead of skip
    echo "test.sh: npm ci in bench/peers failed: the peer runner tests will skip" >&2
  fi
fi
(cd build && xvfb-run -a ctest --output-on-failure -j"$(nproc)" --timeout 1500)

# Sanitizer configuration: the I/O and document modules, with the malformed-file corpus.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DREAMSIM_IO_ONLY=ON -DREAMSIM_SANITIZE=ON > /dev/null
cmake --build build-asan -j"$(nproc)"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j"$(nproc)")
