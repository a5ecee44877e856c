#!/usr/bin/env bash
# The speed goals of issue "every core for one run" (docs/design.md, "Setup and analysis" and
# "Benchmark"), each row measured with two binaries side by side, runs interleaved, so that the
# machine's drift (up to 2.5x between days) falls on both alike: the commit the issue starts from
# (47565d1, the last commit before the session of 2026-11-27, whose brief lists the issue) and this one.
#   tests/bench/speed_goals.sh BASELINE_PEENSIM NEW_PEENSIM [REPEATS] [--liggghts] [--long]
# Prints a Markdown table, one row per goal: the baseline's figure, the new one's, their ratio, the
# goal and whether the new binary meets it (medians of REPEATS, default 3; ~4 min a repeat).
#   --liggghts  also times LIGGGHTS 3.8 (Debian's `liggghts`, installed by apt-get when missing) on
#               the rod at real stiffness, its loop alone from 0.13 to 0.15 s (the bed in steady state,
#               its contacts dumped every 10 000 steps only), for the row "rod at LIGGGHTS'
#               restitution" (~30 s)
#   --long      also runs the shipped gear until 98 % everywhere with 2 replicas (new binary only,
#               once; ~2 min)
# Each figure, and how it is taken:
# - rod, analysis share: the default `peensim run scenes/rod.yaml` (1 s) against the same run with
#   --no-analyze; the share is (default - no analysis) / default.
# - gear, setup + analysis against stepping: `peensim run scenes/gear.yaml` (5 s); stepping is
#   summary.json's wall_time_s, setup a 1 ms run without analysis less its stepping, analysis the rest.
# - 500k- against 5k-triangle gear: the same whole process with the fine gear (assets/regenerate.sh
#   --fine), divided by the shipped gear's.
# - rod at LIGGGHTS' restitution: every pair at a constant restitution 0.9 (LIGGGHTS' e; V0 far above
#   any speed), mu 0.71, f 0.1, 1 s, the stepping loop's wall time per simulated second.
# - heavy: the rod chamber with 512 shot of 1 mm at A0 80 um, 10 s, the stepping loop.
# - dense bed: 3072 shot of 1 mm at A0 80 um, 5 s, the stepping loop per simulated second.
# - soft scheme: rod-soft (0.5 s) under `peensim bench --schemes soft,event`: the soft scheme's wall time of the loop over
#   its contacts (impacts on every component and shot-shot).
repeats=3
liggghts=0
long=0
for a in "${@:3}"; do
    case "$a" in
        --liggghts) liggghts=1 ;;
        --long) long=1 ;;
        *) repeats="$a" ;;
    esac
done
# root, base, new, the scratch folder $work with the fine gear in it, seconds and median.
source "$(dirname "${BASH_SOURCE[0]}")/two_binaries_on_two_gears.sh" "$1" "$2" "$repeats"

# The stepping loop's wall time (s) of a run directory.
stepping() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['wall_time_s'])" "$1/summary.json"; }
# Records a figure: record NAME WHICH VALUE (one a line in $work/NAME.WHICH).
record() { echo "$3" >> "$work/$1.$2"; }
fig() { calc "$(median < "$work/$1.$2")"; }
calc() { awk "BEGIN { printf \"%.4g\", $1 }"; }

rod=(scenes/rod.yaml)
heavy=(--set shot.diameter="1 mm" --set "components[sonotrode].vibration.amplitude=80 um")
restitution=()
for pair in shot-shot shot-titanium shot-copper shot-steel; do
    restitution+=(--set "contacts.$pair.C0=0.9" --set "contacts.$pair.V0=1000 m/s")
    [[ "$pair" != shot-shot ]] && restitution+=(--set "contacts.$pair.mu=0.71" --set "contacts.$pair.f=0.1")
done

soft_cost() {  # wall s per simulated s and contacts per simulated s of rod-soft, 0.5 s
    local csv="$work/soft-$1.csv"
    "$2" bench "$root/scenes/rod-soft.yaml" --duration 0.5 --schemes soft,event --csv "$csv" > /dev/null
    python3 - "$csv" << 'EOF'
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["scheme"] == "soft" and r["component"] != "all logged"]
contacts = sum(float(r["impact_rate_per_s"]) for r in rows) + float(rows[0]["shot_shot_impacts_per_s"])
print(1e6 * float(rows[0]["wall_s_per_simulated_s"]) / contacts)
EOF
}

cd "$root"
for r in $(seq 1 "$repeats"); do
    for which in base new; do
        bin="$base"
        [[ "$which" == new ]] && bin="$new"
        o="$work/out-$which"
        rm -rf "$o"
        record rod_whole "$which" "$(seconds "$bin" run "${rod[@]}" -o "$o/rod" -q)"
        record rod_bare "$which" "$(seconds "$bin" run "${rod[@]}" -o "$o/rod-bare" -q --no-analyze --no-render)"
        for mesh in gear fine; do
            m="$root/assets/gear.stl"
            [[ "$mesh" == fine ]] && m="$fine"
            s=$(seconds "$bin" run scenes/gear.yaml -o "$o/$mesh-setup" -q --no-analyze --no-render \
                --set "components[gear].mesh=$m" --set "process.duration=1 ms")
            record "${mesh}_setup" "$which" "$(calc "$s - $(stepping "$o/$mesh-setup")")"
            record "${mesh}_whole" "$which" "$(seconds "$bin" run scenes/gear.yaml -o "$o/$mesh" -q --set "components[gear].mesh=$m")"
            record "${mesh}_step" "$which" "$(stepping "$o/$mesh")"
        done
        "$bin" run "${rod[@]}" -o "$o/e09" -q --no-analyze --no-render "${restitution[@]}" > /dev/null
        record e09 "$which" "$(stepping "$o/e09")"
        "$bin" run "${rod[@]}" -o "$o/heavy" -q --no-analyze --no-render "${heavy[@]}" --set process.duration=10 > /dev/null
        record heavy "$which" "$(stepping "$o/heavy")"
        "$bin" run "${rod[@]}" -o "$o/dense" -q --no-analyze --no-render "${heavy[@]}" --set shot.count=3072 --set process.duration=5 > /dev/null
        record dense "$which" "$(calc "$(stepping "$o/dense") / 5")"
        record soft "$which" "$(soft_cost "$which" "$bin")"
        rm -rf "$o"
    done
done

liggghts_s=""
if [[ "$liggghts" == 1 ]]; then
    lg="$work/liggghts"
    # The bed's energy climbs until ~0.13 s (soft_vs_liggghts/README.md): the production run from
    # there is timed, its contacts dumped every 10 000 steps only (a few frames, which the parser
    # may refuse as too few: its statistics are not used here), so its loop is LIGGGHTS' own.
    bash tests/bench/soft_vs_liggghts/liggghts_rod.sh "$lg" --duration 0.15 --settle 0.13 --dump-every 10000 --delete-dumps > /dev/null 2>&1 || true
    # "Loop time of T on 1 procs for N steps", the production run's (the second): T / (N dt) per simulated second.
    dt=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['timestep_s'])" "$lg/params.json" 2>/dev/null || true)
    loop=$(awk '/^Loop time of/ && ++k == 2 { print $4, $9 }' "$lg/screen.txt" 2>/dev/null || true)
    if [[ -n "$dt" && -n "$loop" ]]; then
        read -r t n <<< "$loop"
        liggghts_s=$(calc "$t / ($n * $dt)")
    fi
fi

echo "# speed goals (issue \"every core for one run\"), $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, medians of $repeats"
echo "| goal | figure | baseline | new | new / baseline | goal | met |"
echo "|---|---|---|---|---|---|---|"
yes_no() { awk "BEGIN { print ($1) ? \"yes\" : \"no\" }"; }
row() { printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$@"; }
share() { calc "($(fig rod_whole "$1") - $(fig rod_bare "$1")) / $(fig rod_whole "$1") * 100"; }
row "rod, 1 s: analysis <= 20 % of the run" "analysis share of the default run (%)" "$(share base)" "$(share new)" \
    "$(calc "$(share new) / $(share base)")" "<= 20" "$(yes_no "$(share new) <= 20")"
framing() { calc "($(fig gear_whole "$1") - $(fig gear_step "$1")) / $(fig gear_step "$1")"; }  # setup + analysis = whole - stepping
row "gear, 5 s: setup + analysis <= stepping" "(setup + analysis) / stepping" "$(framing base)" "$(framing new)" \
    "$(calc "$(framing new) / $(framing base)")" "<= 1" "$(yes_no "$(framing new) <= 1")"
for which in base new; do
    printf -v "gear_$which" '%s' "$(fig gear_setup "$which") s + $(calc "$(fig gear_whole "$which") - $(fig gear_setup "$which") - $(fig gear_step "$which")") s / $(fig gear_step "$which") s"
done
row "" "setup + analysis / stepping" "$gear_base" "$gear_new" "" "" ""
fine_ratio() { calc "$(fig fine_whole "$1") / $(fig gear_whole "$1")"; }
row "500k- vs 5k-triangle gear, whole process" "ratio of whole processes" "$(fine_ratio base)" "$(fine_ratio new)" \
    "$(calc "$(fine_ratio new) / $(fine_ratio base)")" "<= 1.3" "$(yes_no "$(fine_ratio new) <= 1.3")"
e09_goal="LIGGGHTS / new >= 1000"
e09_met="not measured (--liggghts)"
if [[ -n "$liggghts_s" ]]; then
    e09_goal="LIGGGHTS $liggghts_s s / new >= 1000"
    e09_met="$(yes_no "$liggghts_s / $(fig e09 new) >= 1000") ($(calc "$liggghts_s / $(fig e09 new)")x)"
fi
row "rod at LIGGGHTS' restitution (0.9, mu 0.71), 1 s" "stepping s per simulated s" "$(fig e09 base)" "$(fig e09 new)" \
    "$(calc "$(fig e09 new) / $(fig e09 base)")" "$e09_goal" "$e09_met"
row "heavy: rod chamber, 512 x 1 mm, A0 80 um, 10 s" "stepping s" "$(fig heavy base)" "$(fig heavy new)" \
    "$(calc "$(fig heavy new) / $(fig heavy base)")" "new / baseline <= 0.25" "$(yes_no "$(fig heavy new) / $(fig heavy base) <= 0.25")"
row "dense bed: 3072 x 1 mm, A0 80 um, 5 s" "stepping s per simulated s" "$(fig dense base)" "$(fig dense new)" \
    "$(calc "$(fig dense new) / $(fig dense base)")" "<= 1" "$(yes_no "$(fig dense new) <= 1")"
row "soft scheme: cost per contact halved (rod-soft, 0.5 s)" "us per contact" "$(fig soft base)" "$(fig soft new)" \
    "$(calc "$(fig soft new) / $(fig soft base)")" "new / baseline <= 0.5" "$(yes_no "$(fig soft new) / $(fig soft base) <= 0.5")"

if [[ "$long" == 1 ]]; then
    o="$work/coverage"
    w=$(seconds "$new" run scenes/gear.yaml -o "$o" -q --until-coverage 98% --replicas 2 --set "process.duration=1 h")
    row "gear to 98 % everywhere (2 replicas, whole command)" "wall s" "" "$w" "" "< 120" "$(yes_no "$w < 120")"
fi
