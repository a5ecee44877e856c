#!/usr/bin/env bash
# LIGGGHTS reference run of the "rod" ultrasonic shot-peening scene with Hertz-Mindlin contacts
# (the reference half of the soft-sphere side-by-side comparison; see README.md beside this file).
#
#   liggghts_rod.sh OUTDIR [--duration S] [--settle S] [--seed N] [--shots N] [--dump-every K]
#                          [--delete-dumps]
#
#   --duration S     simulated time, s (default 0.35)
#   --settle S       time left out of the statistics at the start, s (default 0.15)
#   --seed N         seed of the random shot placement (default 1)
#   --shots N        number of shot (default 512)
#   --dump-every K   per-contact output interval, steps of 0.15 us (default 2; see README)
#   --delete-dumps   remove the contact dumps after a successful parse (~480 MB for the default run)
#
# Writes into OUTDIR: in.rod (the deck), meshes/*.stl, shots.data, params.json, log.liggghts,
# screen.txt, wall_contacts.dump, pair_contacts.dump, liggghts_stats.json; prints a table.
# Needs Debian's liggghts (installed here with apt-get if missing: needs root) and python3.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

usage() { sed -n '2,17p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }

[[ $# -ge 1 ]] || usage
outdir="$1"; shift
[[ "$outdir" != -* ]] || usage
duration=0.35
settle=0.15
seed=1
shots=512
dump_every=2
delete_dumps=0
while [[ $# -gt 0 ]]; do
    case "$1" in
        --duration) duration="$2"; shift 2 ;;
        --settle) settle="$2"; shift 2 ;;
        --seed) seed="$2"; shift 2 ;;
        --shots) shots="$2"; shift 2 ;;
        --dump-every) dump_every="$2"; shift 2 ;;
        --delete-dumps) delete_dumps=1; shift ;;
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
    --seed "$seed" --shots "$shots" --dump-every "$dump_every"
rm -f "$outdir/wall_contacts.dump" "$outdir/pair_contacts.dump" "$outdir/liggghts_stats.json"

# The deck uses relative paths (meshes/, shots.data, the dumps): run inside OUTDIR.
echo "liggghts_rod.sh: running LIGGGHTS in $outdir (log: log.liggghts, progress: screen.txt)" >&2
start=$(date +%s.%N)
if ! (cd "$outdir" && liggghts -in in.rod -log log.liggghts -echo none > screen.txt 2>&1); then
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
