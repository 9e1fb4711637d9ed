#!/usr/bin/env bash
# Every figure of the collision and cutting issues (docs/BENCHMARKS.md, docs/CSG.md, docs/COLLISION.md) in one
# run: one JSON file per benchmark in OUT_DIR, and a one-line summary of each on stdout.
#   scripts/bench-issues.sh OUT_DIR [cut|collision|all]     (default: all; ~40 min on 2 cores)
# Needs the Release build (scripts/build.sh), python3, and for the npm peers node (bench/peers is installed
# with `npm ci` when missing, as scripts/bench-peers.sh does). The refined scapulas are made in OUT_DIR/bones
# by scripts/make_scapula_variants.py; the CT skull is read from ../shared/data when it is there.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:?usage: scripts/bench-issues.sh OUT_DIR [cut|collision|all]}"
what="${2:-all}"
cli="${REAMSIM_CLI:-$root/build/app/cli/reamsim-cli}"
[ -x "$cli" ] || { echo "bench-issues: $cli not found: build it (scripts/build.sh) or set REAMSIM_CLI" >&2; exit 1; }
mkdir -p "$out/bones"
[ -f "$out/bones/scapula_405k_sqrt3x3.ply" ] || python3 "$root/scripts/make_scapula_variants.py" "$out/bones" >&2
# The "up to a million" case of issue 3 (959,872 faces: three 1:4 steps; not a target bone, the scaling's end).
[ -f "$out/bones/scapula_960k_split4x3.ply" ] || python3 "$root/scripts/make_scapula_variants.py" "$out/bones" --sqrt3 --loop 3 >&2
s45="$out/bones/scapula_45k_sqrt3x1.ply"
s405="$out/bones/scapula_405k_sqrt3x3.ply"
s960="$out/bones/scapula_960k_split4x3.ply"
skull="$root/../shared/data/bone_cranium_ct_isosurface_400k.ply"
peers="$root/bench/peers"
peerArgs=()
if command -v node >/dev/null; then
  if [ ! -f "$peers/node_modules/.package-lock.json" ]; then (cd "$peers" && npm ci --no-audit --no-fund >&2) || true; fi
  peerArgs=(--peers --peers-dir "$peers")
fi

run() {  # run NAME ARGS...: writes OUT_DIR/NAME.json and prints its summary
  local name="$1"
  shift
  echo "== $name: reamsim-cli $*" >&2
  "$cli" "$@" --json > "$out/$name.json" || echo "bench-issues: $name exited with $?" >&2
  python3 - "$out/$name.json" "$name" <<'EOF'
import json, sys
try:
    d = json.load(open(sys.argv[1]))
except Exception as e:
    print(f"{sys.argv[2]}: no JSON ({e})"); sys.exit(0)
# The machine's speed around the run (MachineSpeed.h): load latency through 256 KiB and 8 MiB, before / after.
m = d.get("machine")
machine = ("; machine load ns " + ", ".join(f"{size} " + " / ".join(f"{m[w]['load_ns'][size]:.1f}" for w in ("before", "after"))
                                           for size in ("256KiB", "8MiB"))) if m else ""
if "median_ms" in d:  # bench cut
    line = (f"{sys.argv[2]}: faces {d['faces_start']} -> {d['faces_end']}, {d['cuts']} cuts, median {d['median_ms']:.2f} "
            f"(cuts {d['median_ms_changed']:.2f}) p95 {d['p95_ms']:.2f} p99 {d['p99_ms']:.2f} ms, failures {d['failures']}, "
            f"closed {d['closed']}, SI {d['self_intersections']}, bookkeeping {d['volume_error_rel']:.1e}")
    for k, v in (d.get("peers") or {}).items():
        line += f"; {k}: " + (f"{v['median_ms']:.1f} ms ({v['ratio_to_reamsim']:.1f}x)" if "median_ms" in v else
                              str(v.get("refused") or v.get("stopped") or v.get("not_run") or v.get("error")))
    rs = d.get("reamed_surface")
    if rs:
        line += (f"; reamed surface seated {100 * rs['seated_fraction']:.1f} %, standoff {rs['standoff_min_mm']:.4f}.."
                 f"{rs['standoff_max_mm']:.4f} mm (facet sag {rs['reamer_facet_sag_mm']:.4f})")
    if "loop" in d:
        line += f"; loop step median {d['loop']['step']['median_ms']:.2f} p99 {d['loop']['step']['p99_ms']:.2f} ms"
        mp = d["loop"].get("moves_past_bone")
        if mp:
            line += (f"; moves past the bone {mp['skip_median_ms']:.2f} ms against {mp['hull_median_ms']:.2f} with the hull "
                     f"({mp['ratio']:.1f}x, {mp['moves_reaching_bone']} of {mp['moves']} reached it)")
        rd = d["loop"].get("ream_to_depth_search")
        if rd:
            line += (f"; ream-to-depth search {rd['engine_median_ms']:.3f} ms against {rd['fresh_tree_median_ms']:.1f} "
                     f"with a tree built for it ({rd['ratio']:.0f}x, max diff {rd['max_diff_mm']:.1e} mm)")
    print(line + machine)
else:  # bench collision
    q = d["queries"]
    print(f"{sys.argv[2]}: faces {d['faces']}, build {d['build_ms']:.0f} ms, update {d['update_after_cut_ms']:.3f} ms, "
          f"min distance {q['min_distance']['median_us']:.1f} us, first contact {q['first_contact']['median_us']:.1f} us "
          f"({q['first_contact'].get('within_20us', '?')} of {q['first_contact']['samples']} within 20 us), "
          f"tick {q['first_contact_haptic_tick']['median_us']:.1f} us, targets {d.get('targets')}{machine}")
    h = d.get("hand_held_path")
    if h:
        print("  hand-held path (median / p99 us): " + ", ".join(
            f"{k.replace('_', ' ')} {h[k]['median_us']:.1f} / {h[k]['p99_us']:.1f}"
            for k in ("first_contact", "min_distance", "min_distance_tracked", "penetration_depth", "overlap_any")
            if k in h))
EOF
}

if [ "$what" = cut ] || [ "$what" = all ]; then
  run cut_bundled_glenoid bench cut --steps 200 --check-every 50 "${peerArgs[@]}" --peers-budget-ms 20000 --table-5-1
  run cut_45k_glenoid bench cut --bone "$s45" --cut-site glenoid --steps 200 --check-every 100 "${peerArgs[@]}" --peers-budget-ms 60000
  run cut_405k_glenoid bench cut --bone "$s405" --cut-site glenoid --steps 100 "${peerArgs[@]}" --peers-budget-ms 120000
  # The 45k bone on the 405k row's path (100 steps: twice the feed per cut of the 200-step row): 405k / 45k
  # compares like with like from these two rows (or from the two 200-step rows).
  run cut_45k_glenoid_100 bench cut --bone "$s45" --cut-site glenoid --steps 100
  run cut_405k_top bench cut --bone "$s405" --steps 100 "${peerArgs[@]}" --peers-budget-ms 120000
  run cut_405k_glenoid_200 bench cut --bone "$s405" --cut-site glenoid --steps 200 --loop
  run cut_405k_top_200 bench cut --bone "$s405" --steps 200 --loop
  [ -f "$skull" ] && run cut_skull bench cut --bone "$skull" --units mm --steps 50 --avoid-defects "${peerArgs[@]}" --peers-budget-ms 60000
  # The skull's top as `ream` sees it after merging its strip seams (its open border stops the deeper cuts).
  [ -f "$skull" ] && run cut_skull_top_merged bench cut --bone "$skull" --units mm --steps 50 --merge-coincident --check-every 25
  run cut_960k_glenoid bench cut --bone "$s960" --cut-site glenoid --steps 100 --check-every 100 "${peerArgs[@]}" --peers-budget-ms 120000
  run cut_bundled_1000 bench cut --steps 1000 --depth 0.1 --tilt 3 --check-every 250
  run cut_soak_10000_cuts bench cut --steps 40000 --path soak --check-every 100  # 10,539 of the 40,000 steps cut bone (session 27)
  # The reamed surface against the ideal sphere as the reamer's mesh is refined (docs/CSG.md).
  run cut_bundled_reamer_192x24 bench cut --steps 200 --segments 192 --rings 24
  run cut_bundled_reamer_384x48 bench cut --steps 200 --segments 384 --rings 48
fi
if [ "$what" = collision ] || [ "$what" = all ]; then
  run collision_bundled_shipped bench collision --bone "$root/resources/bones/scapula_R_opensim.vtp" --cut-site glenoid
  run collision_bundled bench collision --bone default
  run collision_45k bench collision --bone "$s45" --cut-site glenoid
  run collision_405k bench collision --bone "$s405" --cut-site glenoid
  run collision_960k bench collision --bone "$s960" --cut-site glenoid
  [ -f "$skull" ] && run collision_skull bench collision --bone "$skull"
fi
