#!/usr/bin/env bash
# ThreadSanitizer run of the cutting engine's tests (docs/CSG.md: the second-thread work of a cut), or of
# another test binary (the reaming loop's: reamsim_ream_tests, whose ReamEngine tests compute steps on a
# worker thread). Too slow for test.sh (~1.5 min per CGAL unit to build cold on 2 cores, ~6 min to run the
# csg tests): meant for a nightly job or before changing the engine's threads. Exits non-zero on any test
# failure or ThreadSanitizer report.
#   scripts/tsan-csg.sh [BUILD_DIR] [TEST_TARGET] [GTEST_FILTER]
#   (defaults: build-tsan, reamsim_csg_tests, all tests; the binary is found under BUILD_DIR/tests)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:-$root/build-tsan}"
target="${2:-reamsim_csg_tests}"
filter="${3:-*}"
flags="-fsanitize=thread"
cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS="$flags" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" > /dev/null
cmake --build "$dir" -j"$(nproc)" --target "$target"
binary="$(find "$dir/tests" -type f -name "$target" -perm -u+x | head -1)"
[ -n "$binary" ] || { echo "tsan-csg: $target not found under $dir/tests" >&2; exit 1; }
log="$dir/tsan-$target.log"
TSAN_OPTIONS="halt_on_error=0 report_signal_unsafe=0 history_size=4" "$binary" --gtest_filter="$filter" 2>&1 | tee "$log"
reports=$(grep -c "WARNING: ThreadSanitizer" "$log" || true)
echo "tsan-csg: $reports ThreadSanitizer report(s) in $target; log in $log"
[ "$reports" = 0 ] && grep -q "\[  PASSED  \]" "$log" && ! grep -q "\[  FAILED  \]" "$log"
