#!/usr/bin/env bash
# Benchmark: prints what a step costs on the shipped scenes (see docs/design.md, "Benchmark").
#   tests/bench/run.sh [--quick | --long]
# Needs a Release build in build/ (the README's quick start makes one). --quick runs every case for a
# tenth of its simulated time (for a smoke test; the figures of docs/design.md come from full runs); --long
# adds the published model's long case (3072 shot, 60 s: ~7 min).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
bench="$root/build/peensim_bench"
[[ -x "$bench" ]] || { echo "run.sh: build first (cmake --build build --target peensim_bench)" >&2; exit 1; }
scale=1
[[ "${1:-}" == "--quick" ]] && scale=0.1
dur() { awk -v d="$1" -v s="$scale" 'BEGIN { printf "%g s", d * s }'; }

echo "# peensim benchmark, $(date -u +%Y-%m-%d), $(nproc) cores, single thread"

# schemes side by side: peensim bench
# Every shipped scene with time stepping and with the event-driven scheme: speed ratio and the
# difference of the impact statistics (docs/design.md, "Benchmark"). --quick runs a tenth of each scene's
# own process.duration (read from `peensim check`). A failure is reported and the other sections
# still run.
peensim="$root/build/peensim"
[[ -x "$peensim" ]] || { echo "run.sh: build first (cmake --build build --target peensim)" >&2; exit 1; }
echo "# schemes side by side: peensim bench, step against event on every shipped scene"
if [[ "$scale" == 1 ]]; then
    "$peensim" bench || echo "run.sh: peensim bench failed (exit $?)" >&2
else
    for scene in scenes/*.yaml; do
        d=$("$peensim" check "$scene" | awk '/^process:/ {p = 1; next} /^[^ #]/ {p = 0} p && $1 == "duration:" {print $2; exit}')
        "$peensim" bench "$scene" --duration "$(dur "$d")" || echo "run.sh: peensim bench $scene failed (exit $?)" >&2
    done
fi
echo
for scheme in event step; do
    echo "# $scheme scheme"
    "$bench" scenes/rod.yaml --set accuracy.scheme=$scheme --set process.duration="$(dur 1)" --label "rod: 512 shot of 2 mm, A0 25 um, $(dur 1), $scheme"
    "$bench" scenes/rod.yaml --set accuracy.scheme=$scheme --set process.duration="$(dur 10)" --set shot.diameter="1 mm" \
        --set "components[sonotrode].vibration.amplitude=80 um" --label "heavy: rod chamber, 512 shot of 1 mm, A0 80 um, $(dur 10), $scheme"
    "$bench" scenes/gear.yaml --set accuracy.scheme=$scheme --set process.duration="$(dur 5)" --label "gear, 4960-triangle gear, $(dur 5), $scheme"
    fine="$root/build/assets/gear-fine.stl"
    [[ -f "$fine" ]] || PEENSIM="$root/build/peensim" bash assets/regenerate.sh --fine >/dev/null
    mid="$root/build/assets/gear-200k.stl"
    [[ -f "$mid" ]] || "$root/build/peensim" generate gear "$mid" --module-mm 2 --teeth 20 --pressure-angle-deg 20 \
        --face-width-mm 10 --bore-radius-mm 5 --axis y --triangles 200000 >/dev/null
    "$bench" scenes/gear.yaml --set accuracy.scheme=$scheme --set process.duration="$(dur 5)" --set "components[gear].mesh=$mid" \
        --label "gear, 198720-triangle gear, $(dur 5), $scheme"
    "$bench" scenes/gear.yaml --set accuracy.scheme=$scheme --set process.duration="$(dur 5)" --set "components[gear].mesh=$fine" \
        --label "gear, 500480-triangle gear, $(dur 5), $scheme"
done
if [[ "${1:-}" == "--long" ]]; then
    echo "# the published model's long case: 3072 shot of 1 mm, A0 80 um, 60 s (event-driven; ~7 min)"
    "$bench" scenes/rod.yaml --set process.duration=60 --set shot.count=3072 --set shot.diameter="1 mm" \
        --set "components[sonotrode].vibration.amplitude=80 um" --label "3072 shot of 1 mm, A0 80 um, rod chamber, 60 s"
fi

echo
echo "# accuracy knob of time stepping: accuracy.travel_fraction on the rod scene ($(dur 1)); 0.025 is the converged reference"
for f in 0.5 0.25 0.1 0.05 0.025; do
    "$bench" scenes/rod.yaml --set accuracy.scheme=step --set process.duration="$(dur 1)" --set accuracy.travel_fraction=$f --label "rod, travel_fraction $f"
done

echo
echo "# rendering: gear scene with 512 shot, $(dur 0.2) simulated, 1280x720 frames at 30 fps of 20 ms per video second (1500 frames per simulated s)"
render_dir="$(mktemp -d /tmp/peensim-render-bench-XXXXXX)"
"$bench" scenes/gear.yaml --set process.duration="$(dur 0.2)" --set shot.count=512 --label "gear, 512 shot, no rendering"
"$bench" scenes/gear.yaml --set process.duration="$(dur 0.2)" --set shot.count=512 --label "gear, 512 shot, rendering" --render "$render_dir"
rm -rf "$render_dir"
if [[ -x "$root/build/peensim_render_bench" ]]; then "$root/build/peensim_render_bench"; fi

echo
impacts=$(awk -v s="$scale" 'BEGIN { printf "%d", 10000000 * s }')
echo "# analysis: peensim analyze on $impacts synthetic gear impacts (10 M: ~1-2 min, ~2 GB in /tmp, deleted after)"
if [[ -x "$root/build/peensim_analysis_bench" ]]; then
    "$root/build/peensim_analysis_bench" "$impacts"
else
    echo "run.sh: build peensim_analysis_bench for these figures (cmake --build build --target peensim_analysis_bench)"
fi
