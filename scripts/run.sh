#!/usr/bin/env bash
# Installs missing Debian packages, builds in build/ (Release) and starts StickSlip Lab.
# Without the GUI app, runs `stickslip-cli simulate --preset fig20` and says where the CSV
# went. Extra arguments are passed to the program.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
# shellcheck source=scripts/deps.sh
source "$here/deps.sh"

build="${STICKSLIP_BUILD_DIR:-$root/build}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSTICKSLIP_BUILD_GUI=ON
fi
cmake --build "$build" -j"$(nproc)"

app="$build/bin/stickslip"
if [ -x "$app" ]; then
  args=("$@")
  [ ${#args[@]} -eq 0 ] && args=(--preset fig20)
  if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
    exec "$app" "${args[@]}"
  fi
  echo "run: no display; starting the app under Xvfb"
  exec xvfb-run -a -s "-screen 0 1280x800x24" "$app" "${args[@]}"
fi

mkdir -p "$root/out"
out="$root/out/fig20.csv"
"$build/bin/stickslip-cli" simulate --preset fig20 --out "$out" "$@"
echo "run: the GUI app is not built; wrote the Fig. 20 run to $out"
