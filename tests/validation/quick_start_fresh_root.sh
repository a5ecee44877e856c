#!/usr/bin/env bash
# Times the README's quick start command 1 (install, build, run the default scene) in a fresh
# Debian 12 root, as a new machine would run it: `debootstrap --variant=minbase bookworm` once,
# then for each run a copy of that root, the repository cloned into it, and the command timed in a
# chroot. Prints one line per run: the commit, the seconds of the whole command and of its parts.
#   usage (as root): tests/validation/quick_start_fresh_root.sh [RUNS] [WORKDIR]
# Needs debootstrap and the network to Debian's mirror. WORKDIR (default /tmp/peensim-qs) holds the
# pristine root and the copies (about 1.5 GB while a run lasts).
set -euo pipefail
runs=${1:-1}
work=${2:-/tmp/peensim-qs}
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
commit=$(git -C "$repo" rev-parse --short HEAD)
mkdir -p "$work"
if [ ! -x "$work/pristine/usr/bin/apt-get" ]; then
  rm -rf "$work/pristine"
  debootstrap --variant=minbase bookworm "$work/pristine" http://deb.debian.org/debian > "$work/debootstrap.log"
fi
for run in $(seq 1 "$runs"); do
  root="$work/run"
  umount -R "$root/proc" "$root/dev" 2> /dev/null || true
  rm -rf "$root"
  cp -a "$work/pristine" "$root"
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  git clone -q "$repo" "$root/root/peensim"
  mount -t proc proc "$root/proc"
  mount --rbind /dev "$root/dev"
  # The command, word for word from the README, with the time of each part (s).
  cat > "$root/root/quick_start.sh" << 'EOF'
set -euo pipefail
cd /root/peensim
ms() { echo $(( $(date +%s%N) / 1000000 )); }
t0=$(ms)
bash .ci/install-deps --main
t1=$(ms)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
t2=$(ms)
cmake --build build -j2 --target peensim > /dev/null
t3=$(ms)
build/peensim run scenes/gear.yaml > /dev/null
t4=$(ms)
echo "whole $(( (t4 - t0) / 1000 )) s: install $(( (t1 - t0) / 1000 )) s, configure $(( (t2 - t1) / 1000 )) s, build $(( (t3 - t2) / 1000 )) s, main job $(( (t4 - t3) / 1000 )) s"
EOF
  result=$(chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 bash /root/quick_start.sh)
  echo "$commit run $run of $runs ($(date -u +%FT%TZ)): $result"
  umount -R "$root/proc" "$root/dev"
done
rm -rf "$work/run"
