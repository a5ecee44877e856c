#!/usr/bin/env bash
# A what-if sweep with and without its runs sharing the parts' coverage geometry (issue "every core
# for one run", item 3: cache what can be cached between the runs of a sweep). Two binaries side by
# side, sweeps interleaved, so that the machine's drift falls on both alike (docs/design.md,
# "Setup and analysis: the whole process").
#   tests/bench/sweep_geometry_cache.sh BASELINE_PEENSIM NEW_PEENSIM [REPEATS]
# The sweep: the README's gear (5 s), the sonotrode's amplitude 20, 25 and 30 um x 2 seeds = 6
# runs, 2 at once; and the same on the 500k-triangle gear with 2 amplitudes x 2 seeds. Prints the
# median wall time of each sweep (s) over REPEATS (default 3), the new binary's "geometry:" line,
# and checks that both sweeps wrote the same comparison.csv and the same analysis tables.
source "$(dirname "${BASH_SOURCE[0]}")/two_binaries_on_two_gears.sh" "$@"
echo "# sweep with the geometry cache, $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, medians of $repeats"
echo "| binary | part | runs | sweep wall s |"
echo "|---|---|---|---|"
for mesh in "$root/assets/gear.stl" "$fine"; do
    label=$(basename "$mesh" .stl)
    vary="components[sonotrode].vibration.amplitude=20 um,25 um,30 um"
    seeds=2
    if [[ "$mesh" == "$fine" ]]; then
        vary="components[sonotrode].vibration.amplitude=20 um,30 um"
    fi
    for r in $(seq 1 "$repeats"); do
        for which in base new; do
            bin="$base"
            [[ "$which" == new ]] && bin="$new"
            out="$work/$which-$label"
            rm -rf "$out"
            seconds "$bin" sweep "$root/scenes/gear.yaml" -o "$out" --jobs 2 --vary "$vary" --seeds "$seeds" \
                --set "components[gear].mesh=$mesh" >> "$work/$which-$label.times"
        done
        cmp -s "$work/base-$label/sweep/comparison.csv" "$work/new-$label/sweep/comparison.csv" || echo "DIFFERS: $label comparison.csv"
        for f in "$work/base-$label"/*/s*/analysis/*_triangles.csv "$work/base-$label"/*/s*/analysis/*_coverage.csv; do
            cmp -s "$f" "$work/new-$label/${f#"$work/base-$label/"}" || echo "DIFFERS: $label ${f#"$work/base-$label/"}"
        done
    done
    runs=$(find "$work/new-$label" -name summary.json | wc -l)
    for which in base new; do
        printf '| %s | %s | %s | %.2f |\n' "$which" "$label" "$runs" "$(median < "$work/$which-$label.times")"
    done
    "$new" sweep "$root/scenes/gear.yaml" -o "$work/new-$label" --jobs 2 --vary "$vary" --seeds "$seeds" \
        --set "components[gear].mesh=$mesh" | grep "^geometry:" | sed "s|$work/||"
done
