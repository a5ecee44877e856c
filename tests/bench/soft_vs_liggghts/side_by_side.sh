#!/usr/bin/env bash
# The soft-sphere side by side: the rod scene with Hertz-Mindlin contacts run by LIGGGHTS 3.8
# (liggghts_rod.sh, the reference) and by peensim's soft scheme on the same geometry, material data
# and time window; prints impact rates per surface, the rod's normal-speed statistics, each with its
# standard error, their differences in standard errors, and the wall time per simulated second of
# each (README.md beside this file). --case plate does the same on the "plate" scene (the rod
# replaced by a flat plate hung under the lid; 300 shot, e 0.8, f 0.3; plate-soft.yaml).
#
#   side_by_side.sh OUTDIR [--case rod|plate] [--duration S] [--settle S] [--liggghts-runs K] [--peensim-runs K]
#                          [--reuse-liggghts] [--restitution E] [--friction F] [--friction-shot-shot F]
#
#   --case C            rod (default) or plate
#   --duration S        simulated time, s (default 0.35; plate 0.75)
#   --settle S          time left out of the statistics at the start, s (default 0.15; plate 0.45: LIGGGHTS's
#                       shot start at rest in the air and its bed is still warming up before, docs/design.md)
#   --liggghts-runs K   LIGGGHTS runs, seeds 1..K (default 3: ~1.5 min each)
#   --peensim-runs K    peensim runs, seeds 1..K (default 8: ~1 s each)
#   --reuse-liggghts    keep OUTDIR/liggghts-*/liggghts_stats.json where they are there
#   --restitution E     every pair, both codes (default: the case's, rod 0.9, plate 0.8)
#   --friction F        Coulomb's coefficient, every pair, both codes (default: rod 0.1, plate 0.3)
#   --friction-shot-shot F   the shot-shot pair's alone, both codes (default: --friction's)
#
# peensim is build/peensim of this checkout (built with `cmake --build build --target peensim` if
# missing), or $PEENSIM. Writes OUTDIR/liggghts/ (the reference), OUTDIR/peensim/ (the scene, its
# meshes and runs) and OUTDIR/side_by_side.json.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../../.." && pwd)"

usage() { sed -n '2,25p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }

[[ $# -ge 1 ]] || usage
outdir="$1"; shift
[[ "$outdir" != -* ]] || usage
duration=""
settle=""
liggghts_runs=3
peensim_runs=8
reuse=0
case_name=rod
material=()
peensim_material=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --duration) duration="$2"; shift 2 ;;
        --settle) settle="$2"; shift 2 ;;
        --liggghts-runs) liggghts_runs="$2"; shift 2 ;;
        --peensim-runs) peensim_runs="$2"; shift 2 ;;
        --reuse-liggghts) reuse=1; shift ;;
        --case) case_name="$2"; shift 2 ;;
        --restitution) material+=("$1" "$2"); peensim_material+=(--set "contacts.default.e=$2"); shift 2 ;;
        --friction) material+=("$1" "$2"); peensim_material+=(--set "contacts.default.f=$2"); shift 2 ;;
        --friction-shot-shot) material+=("$1" "$2"); fss="$2"; shift 2 ;;
        -h|--help) usage ;;
        *) echo "side_by_side.sh: unknown option $1" >&2; usage ;;
    esac
done
[[ "$case_name" == rod || "$case_name" == plate ]] || usage
if [[ "$case_name" == plate ]]; then : "${duration:=0.75}" "${settle:=0.45}"; else : "${duration:=0.35}" "${settle:=0.15}"; fi
if [[ -n "${fss:-}" ]]; then
    # the shot-shot pair's own entry: the case's restitution unless given
    e_default=$([[ "$case_name" == rod ]] && echo 0.9 || echo 0.8)
    e_ss=$(printf '%s\n' "${material[@]}" | awk 'p { print; exit } $0 == "--restitution" { p = 1 }')
    peensim_material+=(--set "contacts.shot-shot={law: hertz-mindlin, e: ${e_ss:-$e_default}, f: $fss}")
fi

peensim="${PEENSIM:-$root/build/peensim}"
if [[ ! -x "$peensim" ]]; then
    echo "side_by_side.sh: building peensim" >&2
    cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$root/build" -j2 --target peensim >/dev/null
fi

mkdir -p "$outdir/peensim"
outdir="$(cd "$outdir" && pwd)"

# The reference: each run's dumps parsed, then deleted.
for seed in $(seq 1 "$liggghts_runs"); do
    if [[ "$reuse" == 1 && -f "$outdir/liggghts-$seed/liggghts_stats.json" ]]; then
        echo "side_by_side.sh: reusing $outdir/liggghts-$seed/liggghts_stats.json" >&2
    else
        "$here/liggghts_rod.sh" "$outdir/liggghts-$seed" --duration "$duration" --settle "$settle" --seed "$seed" --delete-dumps \
            --scene "$case_name" ${material[@]+"${material[@]}"}
    fi
done

# peensim on the same geometry: the rod scene's chamber and sonotrode (60 x 30 x 40 mm, the plate
# the whole floor), the rod faceted as LIGGGHTS's (48 facets around, 10 segments along), every body
# E 200 GPa and nu 0.3, e 0.9 and f 0.1 for every pair (scenes/rod-soft.yaml with that rod).
p="$outdir/peensim"
if [[ "$case_name" == rod ]]; then
    "$peensim" generate cylinder "$p/rod48.stl" --radius-mm 5 --height-mm 30 --axis y --center-z-mm 20 \
        --segments 48 --axial-subdivisions 10 >/dev/null
    sed -e "s|\.\./assets/rod\.stl|$p/rod48.stl|" -e "s|\.\./assets/|$root/assets/|" \
        -e "s|^  log: \[rod\]|  log: [sonotrode, chamber, rod]|" "$root/scenes/rod-soft.yaml" > "$p/rod-liggghts.yaml"
else
    # The plate as LIGGGHTS's: 40 x 20 x 4 mm, centred in x and y, top face in the lid's plane.
    "$peensim" generate box "$p/plate.stl" --size-x-mm 40 --size-y-mm 20 --size-z-mm 4 --center-z-mm 38 >/dev/null
    sed -e "s|\.\./\.\./\.\./assets/|$root/assets/|" -e "s|mesh: plate\.stl|mesh: $p/plate.stl|" \
        "$here/plate-soft.yaml" > "$p/plate-liggghts.yaml"
fi
# Per seed two runs: the shot-shot impacts of the window are the difference of their counts
# (peensim logs impacts on components; shot-shot ones it counts).
for seed in $(seq 1 "$peensim_runs"); do
    "$peensim" run "$p/$case_name-liggghts.yaml" -o "$p/seed-$seed/settle" --quiet --no-analyze \
        --set process.duration="$settle s" --set process.seed="$seed" ${peensim_material[@]+"${peensim_material[@]}"}
    "$peensim" run "$p/$case_name-liggghts.yaml" -o "$p/seed-$seed/run" --quiet --no-analyze \
        --set process.duration="$duration s" --set process.seed="$seed" ${peensim_material[@]+"${peensim_material[@]}"}
done

python3 "$here/side_by_side.py" "$outdir" --duration "$duration" --settle "$settle" --case "$case_name"
