#!/usr/bin/env bash
# Rebuilds the shipped meshes of assets/ (binary STL, millimetres) with `peensim generate`.
#
#   assets/regenerate.sh          rewrite every shipped asset in assets/
#   assets/regenerate.sh --fine   write only the ~500k-triangle gear to build/assets/gear-fine.stl
#                                 (25 MB: too large to commit; the benchmark's fine gear)
#
# PEENSIM=/path/to/peensim overrides the binary (default: build/peensim of this checkout);
# PEENSIM_ASSETS_DIR=/some/dir writes there instead (the tests compare that with assets/).
# Rod case (reference): a 60 x 30 x 40 mm chamber (x, y, z) whose floor is the sonotrode (top
# face at z = 0) and a 10 mm rod along y across the full width, its axis 20 mm above the floor.
# Gear case (our sizes): a two-section round chamber, a 29.9 mm sonotrode disk closing its
# lower section, a module-2, 20-tooth gear on an axle (the scene places the gear at z = 42 mm).
# Almen strip: an SAE type A strip for scenes/almen.yaml.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
peensim="${PEENSIM:-$root/build/peensim}"
if [[ ! -x "$peensim" ]]; then
    echo "regenerate.sh: no peensim binary at $peensim (build it, or set PEENSIM)" >&2
    exit 1
fi

# The gear, shared by the shipped coarse version and the fine benchmark version.
gear=(--module-mm 2 --teeth 20 --pressure-angle-deg 20 --face-width-mm 10 --bore-radius-mm 5 --axis y)

if [[ "${1:-}" == "--fine" ]]; then
    fine_out="${PEENSIM_ASSETS_DIR:-$root/build/assets}"
    mkdir -p "$fine_out"
    "$peensim" generate gear "$fine_out/gear-fine.stl" "${gear[@]}" --triangles 500000
    exit 0
elif [[ $# -gt 0 ]]; then
    echo "usage: assets/regenerate.sh [--fine]" >&2
    exit 2
fi

out="${PEENSIM_ASSETS_DIR:-$root/assets}"
mkdir -p "$out"

# Rod case. The chamber has no floor (the sonotrode is the floor); its normals face the cavity.
"$peensim" generate box "$out/rod-chamber.stl" --size-x-mm 60 --size-y-mm 30 --size-z-mm 45 \
    --center-z-mm 17.5 --open-face -z --facing inward
"$peensim" generate box "$out/rod-sonotrode.stl" --size-x-mm 60 --size-y-mm 30 --size-z-mm 5 \
    --center-z-mm -2.5
"$peensim" generate cylinder "$out/rod.stl" --radius-mm 5 --height-mm 30 --axis y --center-z-mm 20 \
    --segments 96 --axial-subdivisions 30 --cap-rings 3

# Gear case. Rings on the flat faces keep the fan triangles from all meeting at one point.
"$peensim" generate chamber "$out/gear-chamber.stl" --lower-radius-mm 30 --upper-radius-mm 40 \
    --bottom-z-mm -10 --step-z-mm 15 --lid-z-mm 75 --segments 128 \
    --lower-layers 5 --upper-layers 12 --step-rings 2 --lid-rings 8
"$peensim" generate cylinder "$out/gear-sonotrode.stl" --radius-mm 29.9 --height-mm 10 --axis z \
    --center-z-mm -5 --segments 128 --cap-rings 6
"$peensim" generate gear "$out/gear.stl" "${gear[@]}" --triangles 5000
# 4.95 mm, not 5: the axle must not coincide with the bore surface.
"$peensim" generate cylinder "$out/axle.stl" --radius-mm 4.95 --height-mm 78 --axis y \
    --segments 64 --axial-subdivisions 16 --cap-rings 2

# SAE J442 Almen strip, type A (76.2 x 19.0 x 1.29 mm): peened face up (+z), back face at z = 0.
"$peensim" generate box "$out/almen-strip-a.stl" --size-x-mm 76.2 --size-y-mm 19 --size-z-mm 1.29 \
    --center-z-mm 0.645

# A flat steel target for conventional peening (scenes/nozzle-study.yaml): 24 x 24 x 4 mm, peened
# face up at z = 0, in 0.25 mm squares (smaller than a dent, for the impact-history law's memory).
"$peensim" generate box "$out/steel-plate.stl" --size-x-mm 24 --size-y-mm 24 --size-z-mm 4 \
    --divisions-x 96 --divisions-y 96 --center-z-mm -2
