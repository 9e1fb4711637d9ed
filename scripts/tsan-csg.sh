#!/usr/bin/env bash
# ThreadSanitizer run of the cutting engine's tests (docs/CSG.md: the second-thread work of a cut). Too slow
# for test.sh (~1.5 min per CGAL unit to build cold on 2 cores, ~6 min to run): meant for a nightly job or
# before changing the engine's threads. Exits non-zero on any test failure or ThreadSanitizer report.
#   scripts/tsan-csg.sh [BUILD_DIR]     (default: build-tsan)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:-$root/build-tsan}"
flags="-fsanitize=thread"
cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS="$flags" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" > /dev/null
cmake --build "$dir" -j"$(nproc)" --target reamsim_csg_tests
log="$dir/tsan-csg.log"
TSAN_OPTIONS="halt_on_error=0 report_signal_unsafe=0 history_size=4" "$dir/tests/csg/reamsim_csg_tests" 2>&1 | tee "$log"
reports=$(grep -c "WARNING: ThreadSanitizer" "$log" || true)
echo "tsan-csg: $reports ThreadSanitizer report(s); log in $log"
[ "$reports" = 0 ] && grep -q "\[  PASSED  \]" "$log" && ! grep -q "\[  FAILED  \]" "$log"
