#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test: the Release build with all tests (GUI tests
# under xvfb-run), then the mesh I/O and core tests again under AddressSanitizer + UBSan.
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh
(cd build && xvfb-run -a ctest --output-on-failure -j"$(nproc)" --timeout 1500)

# Sanitizer configuration: the I/O and document modules, with the malformed-file corpus.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DREAMSIM_IO_ONLY=ON -DREAMSIM_SANITIZE=ON > /dev/null
cmake --build build-asan -j"$(nproc)"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j"$(nproc)")
