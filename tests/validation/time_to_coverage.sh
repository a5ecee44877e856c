#!/usr/bin/env bash
# Time to coverage, forecast against brute force (issue 27; docs/design.md, "How long to peen: the forecast against running to coverage").
#   tests/validation/time_to_coverage.sh --case gear|rotating-gear|grooved-shaft [--seeds "1 2 ..."]
#                                        [--out DIR] [--build-dir DIR] [--lengths "5 20 60"]
#   tests/validation/time_to_coverage.sh --table [--out DIR] [--md FILE]
#
# Per seed: one run peened until every counted region reaches 98 % (`peensim run --until-coverage
# 98%`, capped), the truth: when the whole part, each region and all of them ("everywhere")
# reached it, counted by `peensim analyze` over the whole run; then the forecast a user gets from
# a run of 5, 20 and 60 s, `peensim analyze --to T` of the same log (the engine is deterministic:
# the first T s of the long run are the T s run; a rotating part's window ends at its last whole
# turn, as the analysis of a T s run does). A finished run directory is reused (runs take minutes
# to half an hour each: the static gear needs about 1900 s of peening everywhere); a killed one
# resumes from its checkpoint.
# --table reads every case in DIR and prints the validation table (markdown; --md also writes it):
# per case and run length, how often the 95 % interval holds the truth (whole part, everywhere,
# regions), the forecasts that said "too short", and the errors of the 60 s forecasts.
# Not a timed test: hours of CPU for 10 seeds of the three cases. docs/design.md shows its table.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
here="$root/tests/validation"
build="$root/build"
out="$root/build/validation/time-to-coverage"
case_name=""
seeds="1 2 3 4 5 6 7 8 9 10"
lengths="5 20 60"
table=0
md=""
while [[ $# -gt 0 ]]; do
    case "$1" in
        --case) case_name="$2"; shift ;;
        --seeds) seeds="$2"; shift ;;
        --out) out="$2"; shift ;;
        --build-dir) build="$2"; shift ;;
        --lengths) lengths="$2"; shift ;;
        --table) table=1 ;;
        --md) md="$2"; shift ;;
        -h|--help) sed -n 2,20p "${BASH_SOURCE[0]}"; exit 0 ;;
        *) echo "time_to_coverage.sh: unknown option $1" >&2; exit 2 ;;
    esac
    shift
done
if [[ $table == 1 ]]; then
    exec python3 "$here/time_to_coverage_table.py" "$out" ${md:+--md "$md"}
fi
peensim="$build/peensim"
[[ -x "$peensim" ]] || { echo "time_to_coverage.sh: no $peensim (build it first)" >&2; exit 1; }

# The case: its scene, the cap on the run (s) and any --set it needs.
extra=()
case "$case_name" in
    gear) scene="$root/scenes/gear.yaml"; cap=3600 ;;
    rotating-gear) scene="$root/scenes/rotating-gear.yaml"; cap=3000 ;;
    grooved-shaft)
        scene="$here/grooved-shaft.yaml"; cap=900
        mkdir -p "$out"
        python3 "$here/grooved_shaft_stl.py" "$out/grooved-shaft.stl"
        extra=(--set "components[shaft].mesh=$out/grooved-shaft.stl") ;;
    *) echo "time_to_coverage.sh: --case gear, rotating-gear or grooved-shaft" >&2; exit 2 ;;
esac

json() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))$2)" "$1"; }

for seed in $seeds; do
    dir="$out/$case_name-s$seed"
    if [[ ! -f "$dir/summary.json" ]] || [[ "$(json "$dir/summary.json" "['finished']")" != True ]]; then
        resume=()
        [[ -f "$dir/checkpoint.bin" ]] && resume=(--resume)
        echo "[$case_name s$seed] peening until 98 % everywhere (at most $cap s)"
        "$peensim" run "$scene" -o "$dir" "${extra[@]}" --set "process.seed=$seed" --set "process.duration=$cap s" \
            --until-coverage "98 %" --no-render --no-analyze --quiet "${resume[@]}"
    fi
    simulated="$(json "$dir/summary.json" "['simulated_time_s']")"
    # The truth: the whole log (--to: every impact, a rotating part's last part-turn included).
    if [[ ! -f "$dir/truth.json" ]]; then
        "$peensim" analyze "$dir" --to "$simulated s" > /dev/null
        cp "$dir/analysis/figures.json" "$dir/truth.json"
    fi
    for T in $lengths; do
        [[ -f "$dir/forecast-$T.json" ]] && continue
        # What a T s run's own analysis uses: its last whole turn for a rotating part.
        to="$(python3 -c "
import json, math, sys
turn = json.load(open(sys.argv[1]))['window']['turn_s']
T = float(sys.argv[2])
n = math.floor(T / turn * (1 + 1e-12)) if turn else 0
print(repr(n * turn if n >= 1 else T))" "$dir/truth.json" "$T")"
        "$peensim" analyze "$dir" --to "$to s" > /dev/null
        cp "$dir/analysis/figures.json" "$dir/forecast-$T.json"
        echo "[$case_name s$seed] forecast from $T s (window $to s) done"
    done
done
