#!/usr/bin/env bash
# The whole process of the README's main job, setup and analysis included, on the shipped gear and
# on a 500k-triangle version of it (issue "every core for one run", item 3: setup and analysis cost
# less than the simulation they frame). Two binaries side by side, runs interleaved, so that the
# machine's drift falls on both alike (docs/design.md, "Setup and analysis").
#   tests/bench/whole_process.sh BASELINE_PEENSIM NEW_PEENSIM [REPEATS]
# Prints, per binary and mesh, the median of REPEATS (default 3) of: the whole `peensim run` (s),
# its stepping (summary.json's wall_time_s), setup (a run of 1 ms without analysis, less its
# stepping) and the analysis (whole less setup and stepping), and checks that both binaries
# wrote the same analysis tables (*_triangles.csv, *_coverage.csv, *_histograms.csv).
source "$(dirname "${BASH_SOURCE[0]}")/two_binaries_on_two_gears.sh" "$@"
stepping() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['wall_time_s'])" "$1/summary.json"; }
echo "# whole process, $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, medians of $repeats"
echo "| binary | mesh | whole s | setup s | stepping s | analysis s |"
echo "|---|---|---|---|---|---|"
for mesh in "$root/assets/gear.stl" "$fine"; do
    label=$(basename "$mesh" .stl)
    for r in $(seq 1 "$repeats"); do
        for which in base new; do
            bin="$base"
            [[ "$which" == new ]] && bin="$new"
            out="$work/$which-$label"
            rm -rf "$out" "$out-setup"
            setup_whole=$(seconds "$bin" run "$root/scenes/gear.yaml" -o "$out-setup" -q --no-analyze --no-render \
                --set "components[gear].mesh=$mesh" --set "process.duration=1 ms")
            setup=$(awk -v a="$setup_whole" -v b="$(stepping "$out-setup")" 'BEGIN { print a - b }')
            whole=$(seconds "$bin" run "$root/scenes/gear.yaml" -o "$out" -q --set "components[gear].mesh=$mesh")
            step=$(stepping "$out")
            echo "$whole $setup $step" >> "$work/$which-$label.times"
        done
        for f in "$work/base-$label"/analysis/*_triangles.csv "$work/base-$label"/analysis/*_coverage.csv "$work/base-$label"/analysis/*_histograms.csv; do
            cmp -s "$f" "$work/new-$label/analysis/$(basename "$f")" || echo "DIFFERS: $label $(basename "$f")"
        done
    done
    for which in base new; do
        t="$work/$which-$label.times"
        w=$(cut -d' ' -f1 "$t" | median)
        s=$(cut -d' ' -f2 "$t" | median)
        p=$(cut -d' ' -f3 "$t" | median)
        a=$(awk -v w="$w" -v s="$s" -v p="$p" 'BEGIN { printf "%.2f", w - s - p }')
        printf '| %s | %s | %.2f | %.2f | %.2f | %s |\n' "$which" "$label" "$w" "$s" "$p" "$a"
    done
done
