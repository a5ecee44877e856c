#!/usr/bin/env bash
# A run until coverage as replicas against one trajectory (issue 31; docs/design.md, "Every core
# for one run", "Until coverage: rounds").
#   tests/validation/replicas_until_coverage.sh [--cases "gear rotating-gear"] [--seeds "1 2 ..."]
#        [--replicas K] [--target "98 %"] [--cap S] [--out DIR] [--build-dir DIR] [--md FILE]
# Per case and seed: `peensim run --until-coverage` (every region of the part, capped at S s,
# default 4000) as one trajectory and as K replicas (default 2), one after the other on an idle
# machine, each analysed. The table gives when the whole part (the analysis) and every region
# (the run's own end) reached the target, against the brute-force truth of docs/design.md ("How
# long to peen"), and the wall time: the simulation's (summary.json) and the whole command's.
# Finished run directories are reused. Not a timed test: 2-7 min a run on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$root/build"
out="$root/build/validation/replicas-until-coverage"
cases="gear rotating-gear"
seeds="1 2 3"
replicas=2
target="98 %"
cap=4000
md=""
while [[ $# -gt 0 ]]; do
    case "$1" in
        --cases) cases="$2"; shift ;;
        --seeds) seeds="$2"; shift ;;
        --replicas) replicas="$2"; shift ;;
        --target) target="$2"; shift ;;
        --cap) cap="$2"; shift ;;
        --out) out="$2"; shift ;;
        --build-dir) build="$2"; shift ;;
        --md) md="$2"; shift ;;
        -h|--help) sed -n 2,12p "${BASH_SOURCE[0]}"; exit 0 ;;
        *) echo "replicas_until_coverage.sh: unknown option $1" >&2; exit 2 ;;
    esac
    shift
done
peensim="$build/peensim"
[[ -x "$peensim" ]] || { echo "replicas_until_coverage.sh: no $peensim (build it first)" >&2; exit 1; }
mkdir -p "$out"
for c in $cases; do
    for seed in $seeds; do
        for k in 1 "$replicas"; do
            dir="$out/$c-k$k-seed$seed"
            [[ -f "$dir/analysis/figures.json" && -f "$dir.whole_s" ]] && continue
            start=$(date +%s.%N)
            "$peensim" run "$root/scenes/$c.yaml" -o "$dir" --quiet --no-render --replicas "$k" --until-coverage "$target" \
                --set process.duration="$cap" --set process.seed="$seed" > /dev/null
            python3 -c "import sys; print(float(sys.argv[2]) - float(sys.argv[1]))" "$start" "$(date +%s.%N)" > "$dir.whole_s"
        done
    done
done
python3 - "$out" "$replicas" "$cases" "$seeds" "$md" <<'PY'
import json, math, sys
out, k, cases, seeds, md = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(), sys.argv[4].split(), sys.argv[5]
# The truth at 98 %: when the whole part and every region reached it in runs peened until they
# did (docs/design.md, "How long to peen": 10 and 9 seeds, min-max).
truth = {"gear": ("1322-1334", "1850-1898"), "rotating-gear": ("1207-1220", "1223-1253")}
def stats(v):
    m = sum(v) / len(v)
    se = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1) / len(v)) if len(v) > 1 else float("nan")
    return m, se
rows = ["| case | run | seeds | whole part reached (s) | everywhere reached (s) | truth: whole, everywhere (s) | simulation wall (s) | whole command (s) | speed-up |",
        "|---|---|---|---|---|---|---|---|---|"]
for c in cases:
    base = None
    for kk in (1, k):
        whole, every, wall, command = [], [], [], []
        for seed in seeds:
            d = f"{out}/{c}-k{kk}-seed{seed}"
            s = json.load(open(d + "/summary.json"))
            if kk > 1 and "replicas" not in s:
                sys.exit(f"{d}: ran as one replica")
            if not s["until_coverage"]["reached"]:
                sys.exit(f"{d}: did not reach the target")
            f = json.load(open(d + "/analysis/figures.json"))["components"][0]["time_to_target"]
            whole.append(f["time_s"])
            every.append(max(a["reached_at_s"] for a in s["until_coverage"]["areas"]))
            wall.append(s["wall_time_s"])
            command.append(float(open(d + ".whole_s").read()))
        w, e, t, cmd = stats(whole), stats(every), stats(wall), stats(command)
        if kk == 1: base = t[0]
        name = "one trajectory" if kk == 1 else f"{kk} replicas"
        fmt = lambda v, st: f"{st[0]:.0f} +- {st[1]:.0f} ({min(v):.0f}-{max(v):.0f})"
        tw, te = truth.get(c, ("-", "-"))
        rows.append(f"| {c} | {name} | {len(seeds)} | {fmt(whole, w)} | {fmt(every, e)} | {tw}, {te} | {t[0]:.1f} | {cmd[0]:.1f} | {base / t[0]:.2f}x |")
text = "\n".join(rows)
print(text)
if md:
    open(md, "w").write(text + "\n")
PY
