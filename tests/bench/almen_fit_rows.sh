#!/bin/bash
# How long `peensim almen-fit` takes on curves of 10^3 to 10^5 rows (issue 29: 10^4 rows took 15 s,
# 10^5 did not finish in 100 s). Not a test: run by hand, times printed (wall and CPU seconds).
#   tests/bench/almen_fit_rows.sh [PEENSIM_BINARY]    (default: build/peensim)
set -euo pipefail
peensim=${1:-build/peensim}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for n in 1000 10000 100000; do
    # A 2P curve (a = 0.2 mm, b = 0.5 /min) with 2 um of gauge noise, n distinct exposures.
    python3 - "$n" > "$dir/rows$n.csv" <<'PY'
import math, random, sys
n = int(sys.argv[1])
random.seed(1)
print("time_min,arc_height_mm")
for i in range(n):
    t = 0.5 + 20.0 * i / n
    print(f"{t:.6f},{0.2 * (1 - math.exp(-0.5 * t)) + random.gauss(0, 0.002):.6f}")
PY
    /usr/bin/time -f "$n rows: %e s wall, %U s CPU" "$peensim" almen-fit "$dir/rows$n.csv" > /dev/null
done
