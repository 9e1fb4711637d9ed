#!/usr/bin/env bash
# Fuzzes the file readers under ASan + UBSan (docs/CT_IMPORT.md, "Fuzzing"): configures build-asan with the
# fuzz driver, builds it, writes small seeds, and runs scripts/fuzz-readers.py for each mode.
#   scripts/fuzz-readers.sh [MUTATIONS_PER_SEED] [MODE...]      modes: volume dicom mesh plan presets landmarks
#   e.g. scripts/fuzz-readers.sh 1000 volume dicom
# Findings (inputs that crash, hang, trip a sanitizer, give a FINDING or an error not naming the file) go to
# $FUZZ_OUT (default /tmp/reamsim-fuzz/findings); the exit status is 1 if there are any.
set -euo pipefail
cd "$(dirname "$0")/.."
mutations=${1:-200}
shift || true
modes=("$@")
[ ${#modes[@]} -gt 0 ] || modes=(volume dicom mesh plan presets landmarks)
out=${FUZZ_OUT:-/tmp/reamsim-fuzz}
jobs=${FUZZ_JOBS:-2}

cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DREAMSIM_IO_ONLY=ON -DREAMSIM_SANITIZE=ON \
  -DREAMSIM_FUZZ_DRIVER=ON > /dev/null
cmake --build build-asan -j"$jobs" --target reader_fuzz_driver
driver=build-asan/tests/fuzz/reader_fuzz_driver

rm -rf "$out/seeds"
ASAN_OPTIONS=detect_leaks=0 "$driver" seeds "$out/seeds"
mkdir -p "$out/seeds/landmarks" && cp resources/bones/scapula_R_landmarks.json "$out/seeds/landmarks/"
# A recorded path's extras (placements, notes, times: docs/PLAN_FORMAT.md) beside the bundled plans.
mkdir -p "$out/seeds/plan" && cat > "$out/seeds/plan/recorded_path.json" <<'JSON'
{"reamer": "glenoid-36-R30", "poses": [
  {"tip": [-38.1, 12.5, 101.0], "axis": [-0.6, 0.04, -0.8], "placed": true, "t_ms": 0, "note": "seat, \"then\" feed\n2 mm"},
  {"tip": [-38.2, 12.5, 100.9], "axis": [-0.6, 0.04, -0.8], "t_ms": 812.5},
  {"tip": [-38.3, 12.5, 100.8], "axis": [-0.6, 0.04, -0.8], "t_ms": 1650, "note": "5° – done ✓"}]}
JSON
shared=../shared/data  # real volumes, where present (not on every machine)

status=0
for mode in "${modes[@]}"; do
  seeds=()
  case $mode in
    volume)
      seeds=(--seeds "$out/seeds/volume")
      [ -d "$shared/ct_headsq" ] && seeds+=(--seeds "$shared/ct_headsq")
      [ -f "$shared/ct_cranium_invesalius_256x256x108.mha" ] && seeds+=(--seeds "$shared")
      ;;
    dicom) seeds=(--seeds "$out/seeds/dicom") ;;
    mesh) seeds=(--seeds tests/data/good) ;;
    plan) seeds=(--seeds resources/plans --seeds "$out/seeds/plan") ;;
    presets) seeds=(--seeds resources) ;;
    landmarks) seeds=(--seeds "$out/seeds/landmarks") ;;
    *) echo "unknown mode $mode" >&2; exit 2 ;;
  esac
  scripts/fuzz-readers.py --driver "$driver" --mode "$mode" "${seeds[@]}" --out "$out/findings" \
    --mutations "$mutations" || status=1
done
exit $status
