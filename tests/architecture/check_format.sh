#!/bin/bash
# The code's one format (.clang-format, Debian's clang-format 14): every .h and .cpp under src/,
# contact/ and tests/ must be what `clang-format -i` makes of it. Prints each file that drifted
# and how to mend it, and exits 1 on any; exits 2 when clang-format is missing (.ci/install-deps
# installs it).
#   tests/architecture/check_format.sh [REPO]
repo=${1:-$(cd "$(dirname "$0")/../.." && pwd)}
command -v clang-format >/dev/null || { echo "check_format: clang-format not found: apt-get install clang-format (Debian 12: version 14)"; exit 2; }
cd "$repo" || exit 2
# One clang-format for every file (a process per file took ~35 s); its diagnostics name the files.
mapfile -d '' files < <(find src contact tests \( -name '*.h' -o -name '*.cpp' \) -print0 | sort -z)
drifted=$(clang-format --dry-run -Werror "${files[@]}" 2>&1 >/dev/null | sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error: .*/\1/p' | sort -u)
for f in $drifted; do echo "drifted from .clang-format: $f (mend: clang-format -i $f)"; done
count=$(printf '%s' "$drifted" | grep -c . || true)
echo "$count of ${#files[@]} file(s) drifted ($(clang-format --version | head -1))"
[ "$count" -eq 0 ]
