#!/usr/bin/env bash
# The extremes matrix (issue 10, "Trust at the extremes"; docs/design.md, "Extremes matrix").
#   tests/extremes/run.sh [--quick | --full] [--jobs N] [--md FILE] [--out DIR] [--cases REGEX]
#                         [--build-dir DIR] [--no-build]
#
# A base case (rod chamber, 512 shot of 2 mm, A0 25 um, static rod) varied one factor at a time
# over every level of the issue (shot 0.3 / 1 / 3 mm; A0 0 / 100 um; the part a 128-facet cylinder
# at 300 / 1000 rpm or the gear static / 300 / 1000 rpm; N 1 / 3072), plus the hard corners, and the
# stress cases (issue 28): a thin, twisted, sharp-edged blade (`peensim generate blade`) still and
# at 300 / 1000 / 3000 rpm, with 2 mm shot, 3 mm at A0 100 um, and 1500 x 0.3 mm at A0 100 um (the
# blade stall's report, three seeds), each
# run with both schemes by `peensim run`; then the tube against the exact 1D reference
# (EngineTubeLong in build/tests/peensim_tests). Per case one row: wall seconds per simulated
# second and the event scheme's speed-up, impact rate and mean normal speed on the logged part,
# lost shot, deep penetrations, unresolved contacts, impacts from inside the part, the event scheme's
# search fallbacks (counted, not a failure), and whether the two schemes agree within noise; every
# run within a wall-time bound per simulated second. The last line is PASS or FAIL; exit 1 on any
# failed assertion.
#
# Simulated time: --full the issue's (60 s; 10 s for the 3072-shot and the blade's 0.3 mm cases;
# tube 3000 s: hours); default a tenth (6 s, 1 s; tube 300 s); --quick a hundredth (0.6 s, 0.1 s; the tube's short
# run of the normal test suite), a smoke test.
# --jobs N runs N cases at once (default 1; wall times are only comparable with 1).
# --cases REGEX runs only the cases whose name matches (and skips the tube unless 'tube' matches).
# --build-dir DIR: where peensim and peensim_tests are (default build/); --no-build uses them as
# they are (the normal test suite runs a subset so: tests/CMakeLists.txt).
# --out DIR keeps every run's summary.json there; without it a temporary directory is used and
# removed when everything passed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
here="$root/tests/extremes"
build="${PEENSIM_BUILD_DIR:-$root/build}"

mode=default
do_build=1
jobs=1
md=""
out=""
only=""
while [[ $# -gt 0 ]]; do
    case "$1" in
        --quick) mode=quick ;;
        --full) mode=full ;;
        --jobs) jobs="$2"; shift ;;
        --md) md="$2"; shift ;;
        --out) out="$2"; shift ;;
        --cases) only="$2"; shift ;;
        --build-dir) build="$2"; shift ;;
        --no-build) do_build=0 ;;
        -h|--help) sed -n '2,26p' "${BASH_SOURCE[0]}"; exit 0 ;;
        *) echo "run.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: --jobs needs a positive integer" >&2; exit 2; }
case "$mode" in
    full) d_normal=60; d_large=10; tube_seconds=3000; to_full=1; tube_to_full=1 ;;
    default) d_normal=6; d_large=1; tube_seconds=300; to_full=10; tube_to_full=10 ;;
    quick) d_normal=0.6; d_large=0.1; tube_seconds=""; to_full=100; tube_to_full=1500 ;;
esac
[[ -n "$md" && "$md" != /* ]] && md="$PWD/$md"

if (( do_build )); then
    echo "# run.sh: building peensim and peensim_tests in $build"
    cmake --build "$build" -j2 --target peensim peensim_tests >/dev/null
fi
peensim="$build/peensim"
tests_bin="$build/tests/peensim_tests"
[[ -x "$peensim" && -x "$tests_bin" ]] || { echo "run.sh: $peensim or $tests_bin missing: build them first" >&2; exit 2; }

work="${out:-$(mktemp -d -t peensim-extremes.XXXXXX)}"
mkdir -p "$work"
rows="$work/rows.jsonl"
: > "$rows"
cyl="$work/cylinder-128.stl"
"$peensim" generate cylinder "$cyl" --radius-mm 5 --height-mm 30 --segments 128 --axis y --center-z-mm 20 >/dev/null

# The base every case starts from (the shipped rod scene's own values, written out).
base=("shot.count=512" "shot.diameter=2 mm" "components[sonotrode].vibration.amplitude=25 um")
cyl_motion() { echo "components[rod].motion={type: rotating, axis_point: [0, 0, 20 mm], axis_direction: [0, 1, 0], speed: $1 rpm}"; }
gear_motion() { echo "components[gear].motion={type: rotating, axis_point: [0, 0, 42 mm], axis_direction: [0, 1, 0], speed: $1 rpm}"; }
amp() { echo "components[sonotrode].vibration.amplitude=$1 um"; }
# A lone shot dropped on the flat sonotrode bounces on one vertical line between flat faces for
# ever (no impact on the rod, nothing to compare): thrown in a random upward direction instead.
throw() { echo "shot.initial_speed=1 m/s"; }
cylinder=("components[rod].mesh=$cyl")

# The stress cases' part (issue 28): a thin, twisted, sharp-edged blade turning in the gear chamber
# (tests/extremes/blade.yaml says how it is made).
blade="$work/blade.stl"
"$peensim" generate blade "$blade" --chord-mm 12 --span-mm 34 --thickness-mm 0.8 --twist-deg 40 --axis x --center-z-mm 42 >/dev/null
blade_at() { echo "components[blade].mesh=$blade|components[blade].motion.speed=$1 rpm"; }
stall=("shot.count=1500" "shot.diameter=0.3 mm" "$(amp 100)")  # the blade stall's report: 1500 x 0.3 mm, A0 100 um
stall_sets=$(IFS='|'; echo "${stall[*]}")

# Every run has a wall-time bound: wall_per_simulated_second s of wall time per simulated second
# (time stepping, the slow scheme, takes 39 on 3072 x 1 mm and 90-330 on the blade's 1500 x 0.3 mm,
# its first 0.1 s the slowest), plus the start-up: a stall, which never ends, fails its row. A run
# beyond it is stopped (SIGTERM: it checkpoints) and fails its row.
wall_per_simulated_second=600
wall_startup=30

# name | scene (a shipped scene's name, or a path from the repository's root without .yaml) |
# duration (n: normal, l: large: 3072 shot, or the blade's 1500 small shot) | part check (cyl96: the shipped rod, 96 facets;
# cyl128: the generated cylinder; gear: closed part, the deep_penetrations counter) | what | overrides ('|'-separated)
cases=(
    "base|rod|n|cyl96|rod chamber, 512 x 2 mm, A0 25 um, static rod|"
    "shot-0.3mm|rod|n|cyl96|shot 0.3 mm|shot.diameter=0.3 mm"
    "shot-1mm|rod|n|cyl96|shot 1 mm|shot.diameter=1 mm"
    "shot-3mm|rod|n|cyl96|shot 3 mm|shot.diameter=3 mm"
    "A0-0|rod|n|cyl96|sonotrode still|$(amp 0)"
    "A0-100um|rod|n|cyl96|A0 100 um|$(amp 100)"
    "cyl-300rpm|rod|n|cyl128|128-facet cylinder at 300 rpm|${cylinder[0]}|$(cyl_motion 300)"
    "cyl-1000rpm|rod|n|cyl128|128-facet cylinder at 1000 rpm|${cylinder[0]}|$(cyl_motion 1000)"
    "gear-static|gear|n|gear|gear chamber, gear static|"
    "gear-300rpm|gear|n|gear|gear at 300 rpm|$(gear_motion 300)"
    "gear-1000rpm|gear|n|gear|gear at 1000 rpm|$(gear_motion 1000)"
    "N-1|rod|n|cyl96|one shot, thrown at 1 m/s|shot.count=1|$(throw)"
    "N-3072|rod|l|cyl96|3072 shot|shot.count=3072"
    "0.3mm-100um-cyl1000|rod|n|cyl128|0.3 mm, A0 100 um, cylinder at 1000 rpm|shot.diameter=0.3 mm|$(amp 100)|${cylinder[0]}|$(cyl_motion 1000)"
    "3mm-100um-gear1000|gear|n|gear|3 mm, A0 100 um, gear at 1000 rpm|shot.diameter=3 mm|$(amp 100)|$(gear_motion 1000)"
    "3072x1mm-80um|rod|l|cyl96|3072 x 1 mm, A0 80 um|shot.count=3072|shot.diameter=1 mm|$(amp 80)"
    "3072x1mm-100um|rod|l|cyl96|3072 x 1 mm, A0 100 um|shot.count=3072|shot.diameter=1 mm|$(amp 100)"
    "N1-0.3mm-100um|rod|n|cyl96|1 shot of 0.3 mm, A0 100 um, thrown|shot.count=1|$(throw)|shot.diameter=0.3 mm|$(amp 100)"
    "N1-1mm-100um|rod|n|cyl96|1 shot of 1 mm, A0 100 um, thrown|shot.count=1|$(throw)|shot.diameter=1 mm|$(amp 100)"
    "N1-2mm-100um|rod|n|cyl96|1 shot of 2 mm, A0 100 um, thrown|shot.count=1|$(throw)|$(amp 100)"
    "N1-3mm-100um|rod|n|cyl96|1 shot of 3 mm, A0 100 um, thrown|shot.count=1|$(throw)|shot.diameter=3 mm|$(amp 100)"
    "blade-static|tests/extremes/blade|n|gear|thin twisted blade, still, 140 x 2 mm|$(blade_at 0)"
    "blade-300rpm|tests/extremes/blade|n|gear|blade at 300 rpm|$(blade_at 300)"
    "blade-1000rpm|tests/extremes/blade|n|gear|blade at 1000 rpm|$(blade_at 1000)"
    "blade-3000rpm|tests/extremes/blade|n|gear|blade at 3000 rpm|$(blade_at 3000)"
    "blade-3000rpm-3mm-100um|tests/extremes/blade|n|gear|blade at 3000 rpm, 60 x 3 mm, A0 100 um|$(blade_at 3000)|shot.count=60|shot.diameter=3 mm|$(amp 100)"
    "blade-1000rpm-0.3mm-s1|tests/extremes/blade|l|gear|blade at 1000 rpm, 1500 x 0.3 mm, A0 100 um (the stall's)|$(blade_at 1000)|$stall_sets"
    "blade-1000rpm-0.3mm-s2|tests/extremes/blade|l|gear|the same, seed 2|$(blade_at 1000)|$stall_sets|process.seed=2"
    "blade-1000rpm-0.3mm-s3|tests/extremes/blade|l|gear|the same, seed 3|$(blade_at 1000)|$stall_sets|process.seed=3"
    "blade-3000rpm-0.3mm|tests/extremes/blade|l|gear|blade at 3000 rpm, 1500 x 0.3 mm, A0 100 um|$(blade_at 3000)|$stall_sets"
)

run_case() {
    local spec="$1" name scene size check what
    IFS='|' read -r name scene size check what _ <<<"$spec"
    local rest="${spec#*|*|*|*|*|}"
    local duration=$d_normal
    [[ "$size" == l ]] && duration=$d_large
    local sets=()
    local o
    for o in "${base[@]}" "process.duration=$duration"; do sets+=(--set "$o"); done
    if [[ -n "$rest" ]]; then
        local extra
        IFS='|' read -r -a extra <<<"$rest"
        for o in "${extra[@]}"; do [[ -n "$o" ]] && sets+=(--set "$o"); done
    fi
    local scene_file="$root/scenes/$scene.yaml"
    [[ "$scene" == */* ]] && scene_file="$root/$scene.yaml"
    local bound
    bound=$(python3 -c "import math; print(math.ceil($wall_per_simulated_second * $duration + $wall_startup))")
    local codes=() scheme
    for scheme in step event; do
        local dir="$work/$name/$scheme"
        mkdir -p "$dir"
        set +e
        timeout --signal=TERM --kill-after=10 "$bound" "$peensim" run "$scene_file" -o "$dir" --scheme "$scheme" --quiet --no-analyze --no-render \
            "${sets[@]}" >"$dir/stdout.txt" 2>"$dir/stderr.txt"
        codes+=($?)
        set -e
    done
    local args=(row --case "$name" --what "$what" --duration "$duration" --step "$work/$name/step" --event "$work/$name/event"
                --step-exit "${codes[0]}" --event-exit "${codes[1]}" --wall-bound "$bound" --out "$rows")
    case "$check" in
        cyl96) args+=(--cylinder 96) ;;
        cyl128) args+=(--cylinder 128) ;;
        gear) args+=(--closed-part) ;;
    esac
    python3 "$here/extremes.py" "${args[@]}"
    rm -f "$work/$name"/*/impacts.csv  # large; summary.json and the run's stdout/stderr stay
}

# One tube case (both schemes in one process: they share the reference, most of the cost) as a
# job; its log, exit code and wall seconds go to $work/tube-CASE.*.
run_tube() {
    local tube="$1" t0 code
    t0=$(date +%s)
    set +e
    PEENSIM_TUBE_SECONDS="${tube_seconds:-}" "$tests_bin" --gtest_filter="*TubeLong*/${tube}_*" >"$work/tube-$tube.log" 2>&1
    code=$?
    set -e
    echo "$code" >"$work/tube-$tube.exit"
    echo $(( $(date +%s) - t0 )) >"$work/tube-$tube.wall"
}
tubes=(Shot2mmA25umGap30mm Shot1mmA80umGap20mm Shot03mmA100umGap20mm)
run_tubes=0
[[ -z "$only" || "tube" =~ $only ]] && run_tubes=1

# Runs "$@" as one job of the pool (at most --jobs at once), or in the foreground with --jobs 1.
submit() {
    if (( jobs > 1 )); then
        while (( $(jobs -rp | wc -l) >= jobs )); do wait -n || true; done
        "$@" &
    else
        "$@"
    fi
}

start=$(date +%s)
echo "# extremes matrix, $mode mode ($d_normal s; $d_large s for 3072 shot and 1500 x 0.3 mm), $(date -u +%Y-%m-%d), $(nproc) cores, --jobs $jobs; work dir $work"
python3 "$here/extremes.py" header
# The tube first: its cases are the longest jobs.
if (( run_tubes )); then
    echo "# tube against the exact reference: EngineTubeLong, ${tube_seconds:-2 (the short run of the test suite)} s"
    for tube in "${tubes[@]}"; do submit run_tube "$tube"; done
fi
order=()
for spec in "${cases[@]}"; do
    name="${spec%%|*}"
    [[ -n "$only" && ! "$name" =~ $only ]] && continue
    order+=("$name")
    submit run_case "$spec"
done
wait

tube_args=()
if (( run_tubes )); then
    tube_wall=0
    for tube in "${tubes[@]}"; do
        tube_args+=(--tube "$work/tube-$tube.log" --tube-exit "$(cat "$work/tube-$tube.exit" 2>/dev/null || echo 255)")
        tube_wall=$(( tube_wall + $(cat "$work/tube-$tube.wall" 2>/dev/null || echo 0) ))
    done
    tube_args+=(--tube-wall "$tube_wall")
fi

wall=$(( $(date +%s) - start ))
order_csv=$(IFS=,; echo "${order[*]}")
echo "# report"
status=0
python3 "$here/extremes.py" report "$rows" --order "$order_csv" "${tube_args[@]}" \
    --mode "$mode mode ($d_normal s of peening, $d_large s for 3072 shot and 1500 x 0.3 mm; tube ${tube_seconds:-2} s), $(date -u +%Y-%m-%d)" \
    --wall "$wall" --to-full "$to_full" --tube-to-full "$tube_to_full" ${md:+--md "$md"} || status=$?
if [[ -z "$out" ]]; then
    if (( status == 0 )); then rm -rf "$work"; else echo "# the runs' summaries: $work"; fi
fi
exit "$status"
