#!/usr/bin/env bash
# The two figures that sit at their lines on this machine (docs/BENCHMARKS.md "Where the targets stand"),
# measured ROUNDS times in turn, so that a note can say on how many runs each line held instead of quoting one
# run of a machine whose speed drifts by 1.5x and more within an hour (2.4x in session 45):
#   - issue 3: first contact and min distance medians at 405k faces (bench collision --cut-site glenoid
#     --no-baselines --hand-held-approaches 0; target <= 20 us each);
#   - issue 4: ReamSim against manifold-3d on the bundled scapula (scripts/bench-peers.sh --cut-site glenoid
#     --steps 200; target >= 5x; the CGAL reference runs too, csg.js gets 5 s).
#   scripts/bench-lines.sh OUT_DIR [ROUNDS] [--summary-only]      (default 8 rounds, about a minute each)
# Writes OUT_DIR/collision_<i>.json and OUT_DIR/peers_<i>.json, one line per round and a summary on stdout
# (OUT_DIR/summary.json): each figure's range, on how many rounds it met its line, and how it followed the
# machine's load latency through 256 KiB and 8 MiB read around its run (`machine` in the JSON, MachineSpeed.h;
# Pearson's r over the rounds). --summary-only summarises the rounds already in OUT_DIR.
# Needs the Release build (scripts/build.sh), python3 and node (bench/peers); the 405k scapula is made in
# OUT_DIR/bones by scripts/make_scapula_variants.py when missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:?usage: scripts/bench-lines.sh OUT_DIR [ROUNDS] [--summary-only]}"
rounds="${2:-8}"
summaryOnly="${3:-}"
cli="${REAMSIM_CLI:-$root/build/app/cli/reamsim-cli}"
[ -x "$cli" ] || { echo "bench-lines: $cli not found: build it (scripts/build.sh) or set REAMSIM_CLI" >&2; exit 1; }
mkdir -p "$out/bones"
bone="$out/bones/scapula_405k_sqrt3x3.ply"
[ -f "$bone" ] || python3 "$root/scripts/make_scapula_variants.py" "$out/bones" >&2

[ "$summaryOnly" = --summary-only ] && rounds_to_run=0 || rounds_to_run="$rounds"
for i in $(seq 1 "$rounds_to_run"); do
  "$cli" bench collision --bone "$bone" --cut-site glenoid --no-baselines --hand-held-approaches 0 --json \
    > "$out/collision_$i.json" || echo "bench-lines: bench collision exited with $?" >&2
  REAMSIM_CLI="$cli" "$root/scripts/bench-peers.sh" --cut-site glenoid --steps 200 --peers-budget-ms 5000 \
    > "$out/peers_$i.json" || echo "bench-lines: bench-peers exited with $?" >&2
  python3 - "$out" "$i" <<'EOF'
import json, sys
out, i = sys.argv[1], sys.argv[2]
try:
    collision = json.load(open(f"{out}/collision_{i}.json"))
    c, cm = collision["queries"], collision["machine"]
    p = json.load(open(f"{out}/peers_{i}.json"))
    m = p["peers"]["manifold_3d"]
    load = lambda r: ", ".join(f"{size} " + " / ".join(f"{r[w]['load_ns'][size]:.1f}" for w in ("before", "after"))
                               for size in ("256KiB", "8MiB"))
    print(f"round {i}: first contact {c['first_contact']['median_us']:.1f} us ({c['first_contact']['within_20us']} of "
          f"{c['first_contact']['samples']} within 20 us), min distance {c['min_distance']['median_us']:.1f} us "
          f"[load ns {load(cm)}]; cut {p['median_ms']:.2f} ms, manifold-3d {m.get('median_ms', float('nan')):.2f} ms "
          f"({m.get('ratio_to_reamsim', float('nan')):.2f}x) [load ns {load(p['machine'])}]", flush=True)
except Exception as e:
    print(f"round {i}: no figures ({e})", flush=True)
EOF
done

python3 - "$out" "$rounds" <<'EOF'
import json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
rows = {"first contact (us)": [], "min distance (us)": [], "cut (ms)": [], "manifold-3d (ms)": [], "manifold-3d / cut": [],
        "256 KiB load around the collision run (ns)": [], "8 MiB load around the collision run (ns)": [],
        "256 KiB load around the cut (ns)": [], "8 MiB load around the cut (ns)": []}
# The machine's reading (MachineSpeed.h) around each run: the mean of the one before and the one after.
around = lambda m, size: 0.5 * (m["before"]["load_ns"][size] + m["after"]["load_ns"][size])
for i in range(1, rounds + 1):
    try:  # a round counts whole or not at all, so that the rows stay paired
        c = json.load(open(f"{out}/collision_{i}.json"))
        p = json.load(open(f"{out}/peers_{i}.json"))
        m = p["peers"]["manifold_3d"]
        values = [c["queries"]["first_contact"]["median_us"], c["queries"]["min_distance"]["median_us"], p["median_ms"],
                  m["median_ms"], m["ratio_to_reamsim"], around(c["machine"], "256KiB"), around(c["machine"], "8MiB"),
                  around(p["machine"], "256KiB"), around(p["machine"], "8MiB")]
    except Exception:
        continue
    for v, row in zip(values, rows.values()):
        row.append(v)
lines = {"first contact (us)": ("<=", 20), "min distance (us)": ("<=", 20), "manifold-3d / cut": (">=", 5)}
summary = {}
for name, v in rows.items():
    if not v:
        continue
    s = {"runs": len(v), "min": min(v), "median": statistics.median(v), "max": max(v)}
    if name in lines:
        op, x = lines[name]
        s["met"] = sum(1 for y in v if (y <= x if op == "<=" else y >= x))
        s["line"] = f"{op} {x}"
    summary[name] = s
    met = f", {s['met']} of {s['runs']} runs {s['line']}" if "met" in s else ""
    print(f"{name}: min {s['min']:.2f}, median {s['median']:.2f}, max {s['max']:.2f}{met}")
# Does the figure follow the machine's memory latency from round to round? (Pearson's r over the rounds.)
def r(x, y):
    if len(x) < 3 or statistics.pstdev(x) == 0 or statistics.pstdev(y) == 0:
        return None
    mx, my = statistics.mean(x), statistics.mean(y)
    return sum((a - mx) * (b - my) for a, b in zip(x, y)) / (len(x) * statistics.pstdev(x) * statistics.pstdev(y))
for name, run in (("first contact (us)", "collision run"), ("min distance (us)", "collision run"),
                  ("cut (ms)", "cut"), ("manifold-3d (ms)", "cut"), ("manifold-3d / cut", "cut")):
    for size in ("256 KiB", "8 MiB"):
        load = f"{size} load around the {run} (ns)"
        c = r(rows[name], rows[load])
        if c is not None:
            summary.setdefault(name, {})[f"r_with_{size.replace(' ', '')}_load"] = c
            print(f"{name} against the {load}: r = {c:.2f}")
json.dump(summary, open(f"{out}/summary.json", "w"), indent=1)
EOF
