# Sourced by the benchmarks that compare two peensim binaries on the shipped gear and its
# 500k-triangle version (whole_process.sh, sweep_geometry_cache.sh, speed_goals.sh): their arguments
# (BASELINE_PEENSIM NEW_PEENSIM [REPEATS]), a scratch folder removed on exit holding the fine
# gear (made by the new binary's assets/regenerate.sh --fine), and the helpers they time with.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
base="$1"
new="$2"
repeats="${3:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fine="$work/gear-fine.stl"
PEENSIM="$new" PEENSIM_ASSETS_DIR="$work" bash "$root/assets/regenerate.sh" --fine > /dev/null
# The wall time (s) of a command, its output dropped.
seconds() { /usr/bin/time -f %e "$@" 2>&1 > /dev/null | tail -1; }
# The median of the numbers on stdin, one a line.
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
