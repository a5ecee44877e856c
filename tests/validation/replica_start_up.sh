#!/usr/bin/env bash
# Whether where replicas' windows start biases the forecasts: what a chamber's start-up leaves in
# its first seconds (issue 31; docs/design.md, "Every core for one run: replicas").
#   tests/validation/replica_start_up.sh [--case gear] [--seeds "1 2 3 4 5 6"] [--length S]
#                                        [--window W] [--starts "0.15 30 150"] [--out DIR]
#                                        [--build-dir DIR] [--md FILE]
# Per seed: one run of S s (default 240) from the scene's start at rest, without its analysis.
# Then, per start a in --starts and per seed s, the window [a, a + W) (default 15 s) of seeds s,
# s+1, s+2, s+3 (cyclically) laid end to end into one log of 4 W s, analysed as a run of that
# length (`peensim analyze --to`): windows from the replicas' measured warm-up ([0.15, 0.15 + W)
# on the shipped gear: summary.json's replicas.warm_up_s) are what `--replicas 4` logs of a 4 W s
# run; windows from 0 hold the shot's fall from their placement, which no replica logs; windows
# from later are what a chamber in steady state gives. The table: per
# start, the forecasts (whole part, everywhere, the slowest region) over the seeds, mean +- its
# standard error; then the mean normal speed of the impacts per time bin over all the runs, on
# the whole part and on the slowest region (the forecast reads the dents' sizes, and so the speeds).
# Not a timed test: about 45 s of CPU per run of 240 s and 10 s per analysis.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$root/build"
out="$root/build/validation/replica-start-up"
case_name="gear"
seeds="1 2 3 4 5 6"
length=240
window=15
starts="0.15 30 150"
md=""
while [[ $# -gt 0 ]]; do
    case "$1" in
        --case) case_name="$2"; shift ;;
        --seeds) seeds="$2"; shift ;;
        --length) length="$2"; shift ;;
        --window) window="$2"; shift ;;
        --starts) starts="$2"; shift ;;
        --out) out="$2"; shift ;;
        --build-dir) build="$2"; shift ;;
        --md) md="$2"; shift ;;
        -h|--help) sed -n 2,16p "${BASH_SOURCE[0]}"; exit 0 ;;
        *) echo "replica_start_up.sh: unknown option $1" >&2; exit 2 ;;
    esac
    shift
done
peensim="$build/peensim"
[[ -x "$peensim" ]] || { echo "replica_start_up.sh: no $peensim (build it first)" >&2; exit 1; }
mkdir -p "$out"
read -r -a seed_list <<< "$seeds"
n=${#seed_list[@]}
(( n >= 4 )) || { echo "replica_start_up.sh: at least 4 seeds (a log joins the windows of 4)" >&2; exit 2; }
for seed in "${seed_list[@]}"; do
    dir="$out/$case_name-${length}s-seed$seed"
    [[ -f "$dir/summary.json" ]] && continue
    "$peensim" run "$root/scenes/$case_name.yaml" -o "$dir" --quiet --no-render --no-analyze \
        --set process.duration="$length" --set process.seed="$seed" > /dev/null
done
# The triangles' regions, from one analysis of the first run.
first="$out/$case_name-${length}s-seed${seed_list[0]}"
[[ -f "$first/analysis/figures.json" ]] || "$peensim" analyze "$first" > /dev/null
for a in $starts; do
    for ((i = 0; i < n; ++i)); do
        dir="$out/$case_name-windows-from-${a}s-seed${seed_list[i]}"
        [[ -f "$dir/analysis/figures.json" ]] && continue
        sources=()
        for ((j = 0; j < 4; ++j)); do sources+=("$out/$case_name-${length}s-seed${seed_list[(i + j) % n]}"); done
        python3 - "$a" "$window" "$dir" "${sources[@]}" <<'PY'
import os, shutil, sys
a, w, dst, srcs = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3], sys.argv[4:]
os.makedirs(dst, exist_ok=True)
for f in ("summary.json", "scene.resolved.yaml"):
    shutil.copy(os.path.join(srcs[0], f), dst)
with open(os.path.join(dst, "impacts.csv"), "w") as out:
    for i, src in enumerate(srcs):
        with open(os.path.join(src, "impacts.csv")) as log:
            header = log.readline()
            if i == 0:
                out.write(header)
            for line in log:
                comma = line.index(",")
                t = float(line[:comma])
                if t >= a + w:
                    break
                if t >= a:
                    out.write(repr(t - a + i * w) + line[comma:])
PY
        "$peensim" analyze "$dir" --to "$((4 * window)) s" > /dev/null
    done
done
python3 - "$out" "$case_name" "$length" "$window" "$starts" "$seeds" "$md" <<'PY'
import csv, json, math, sys
out, case, length, window, starts, seeds, md = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5].split(), sys.argv[6].split(), sys.argv[7]
def stats(v):
    m = sum(v) / len(v)
    return m, math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1) / len(v))
first = f"{out}/{case}-{length:g}s-seed{seeds[0]}"
slowest = json.load(open(first + "/analysis/figures.json"))["components"][0]["slowest_region"]
rows = [f"| windows of {window:g} s from | logs | whole part: 98 % at (s) | everywhere (s) | {slowest} (s) |", "|---|---|---|---|---|"]
for a in starts:
    whole, every, region = [], [], []
    for s in seeds:
        f = json.load(open(f"{out}/{case}-windows-from-{a}s-seed{s}/analysis/figures.json"))["components"][0]
        whole.append(f["time_to_target"]["time_s"]); every.append(f["time_to_target_everywhere"]["time_s"])
        region.append(next(r["time_to_target"]["time_s"] for r in f["regions"] if r["region"] == slowest))
    cells = " | ".join("%.0f +- %.0f" % stats(v) for v in (whole, every, region))
    rows.append(f"| {a} s | {len(seeds)} | {cells} |")
# Mean normal speed per time bin over all the runs: the whole part and the slowest region.
region_of = {}
component = json.load(open(first + "/analysis/figures.json"))["components"][0]["component"]
for r in csv.DictReader(open(f"{first}/analysis/{component}_triangles.csv")):
    region_of[int(r["triangle"])] = r["region"]
edges = [e for e in (0, 2.5, 5, 10, 15, 20, 30, 60, 120, 240, 480, 960) if e < length] + [length]
sums = [[0, 0.0, 0, 0.0] for _ in edges[:-1]]
for s in seeds:
    with open(f"{out}/{case}-{length:g}s-seed{s}/impacts.csv") as log:
        log.readline()
        for line in log:
            p = line.split(",", 11)
            t, triangle, vn = float(p[0]), int(p[3]), float(p[10])
            if p[2] != component:
                continue
            b = next(i for i in range(len(edges) - 1) if t < edges[i + 1] or i == len(edges) - 2)
            sums[b][0] += 1; sums[b][1] += vn
            if region_of.get(triangle) == slowest:
                sums[b][2] += 1; sums[b][3] += vn
rows += ["", f"| time (s) | impacts | mean v_n, whole part (m/s) | impacts on {slowest} | mean v_n there (m/s) |", "|---|---|---|---|---|"]
for i, (k, v, k0, v0) in enumerate(sums):
    rows.append(f"| {edges[i]:g}-{edges[i + 1]:g} | {k} | {v / max(k, 1):.4f} | {k0} | {v0 / max(k0, 1):.4f} |")
text = "\n".join(rows)
print(text)
if md:
    open(md, "w").write(text + "\n")
PY
