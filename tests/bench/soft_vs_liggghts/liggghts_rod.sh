#!/usr/bin/env bash
# LIGGGHTS reference run of the "rod" ultrasonic shot-peening scene with Hertz-Mindlin contacts
# (the reference half of the soft-sphere side-by-side comparison; see README.md beside this file);
# with --scene plate the "plate" scene (a flat plate hung under the lid in place of the rod).
#
#   liggghts_rod.sh OUTDIR [--duration S] [--settle S] [--seed N] [--shots N] [--dump-every K]
#                          [--delete-dumps] [--scene rod|plate] [--restitution E] [--friction F]
#                          [--friction-shot-shot F]
#
#   --duration S     simulated time, s (default 0.35)
#   --settle S       time left out of the statistics at the start, s (default 0.15)
#   --seed N         seed of the random shot placement (default 1)
#   --shots N        number of shot (default 512; plate 300)
#   --dump-every K   per-contact output interval, steps of 0.15 us (default 2; see README)
#   --delete-dumps   remove the contact dumps after a successful parse (~480 MB for the default run)
#   --scene S        rod (default) or plate
#   --restitution E  every pair (default 0.9; plate 0.8)
#   --friction F     Coulomb's coefficient, every pair (default 0.1; plate 0.3)
#   --friction-shot-shot F   the shot-shot pair's alone (default: --friction's)
#
# Writes into OUTDIR: in.rod or in.plate (the deck), meshes/*.stl, shots.data, params.json, log.liggghts,
# screen.txt, wall_contacts.dump, pair_contacts.dump, liggghts_stats.json; prints a table.
# Needs Debian's liggghts (installed here with apt-get if missing: needs root) and python3.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

usage() { sed -n '2,23p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }

[[ $# -ge 1 ]] || usage
outdir="$1"; shift
[[ "$outdir" != -* ]] || usage
duration=0.35
settle=0.15
seed=1
shots=
dump_every=2
delete_dumps=0
scene=rod
material=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --duration) duration="$2"; shift 2 ;;
        --settle) settle="$2"; shift 2 ;;
        --seed) seed="$2"; shift 2 ;;
        --shots) shots="$2"; shift 2 ;;
        --dump-every) dump_every="$2"; shift 2 ;;
        --delete-dumps) delete_dumps=1; shift ;;
        --scene) scene="$2"; shift 2 ;;
        --restitution|--friction|--friction-shot-shot) material+=("$1" "$2"); shift 2 ;;
        -h|--help) usage ;;
        *) echo "liggghts_rod.sh: unknown option $1" >&2; usage ;;
    esac
done

# Debian ships the serial LIGGGHTS 3.8 as /usr/bin/liggghts (package liggghts; the manual, with
# the compute pair/gran/local page this relies on, is in liggghts-doc).
if ! command -v liggghts >/dev/null 2>&1; then
    echo "liggghts_rod.sh: installing Debian's liggghts" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq liggghts liggghts-doc >/dev/null
fi

mkdir -p "$outdir"
outdir="$(cd "$outdir" && pwd)"
python3 "$here/liggghts_rod.py" setup "$outdir" --duration "$duration" --settle "$settle" \
    --seed "$seed" ${shots:+--shots "$shots"} --dump-every "$dump_every" --scene "$scene" ${material[@]+"${material[@]}"}
rm -f "$outdir/wall_contacts.dump" "$outdir/pair_contacts.dump" "$outdir/liggghts_stats.json"

# The deck uses relative paths (meshes/, shots.data, the dumps): run inside OUTDIR.
echo "liggghts_rod.sh: running LIGGGHTS in $outdir (log: log.liggghts, progress: screen.txt)" >&2
start=$(date +%s.%N)
if ! (cd "$outdir" && liggghts -in "in.$scene" -log log.liggghts -echo none > screen.txt 2>&1); then
    echo "liggghts_rod.sh: LIGGGHTS failed; the end of its output:" >&2
    tail -n 20 "$outdir/screen.txt" >&2
    exit 1
fi
end=$(date +%s.%N)
wall=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')
echo "liggghts_rod.sh: LIGGGHTS took $wall s of wall time" >&2

python3 "$here/liggghts_rod.py" parse "$outdir" --wall-time "$wall"

if [[ "$delete_dumps" == 1 ]]; then
    rm -f "$outdir/wall_contacts.dump" "$outdir/pair_contacts.dump"
fi
