#!/usr/bin/env bash
# Installs missing Debian packages, configures and builds in build/ (Release), runs ctest.
# A second run only rebuilds and re-runs what changed. Extra arguments go to ctest.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
# shellcheck source=scripts/deps.sh
source "$here/deps.sh"

build="${STICKSLIP_BUILD_DIR:-$root/build}"
jobs="$(nproc)"
gui=OFF
if dpkg-query -W -f='${db:Status-Status}' qtbase5-dev 2>/dev/null | grep -q '^installed$'; then gui=ON; fi

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSTICKSLIP_BUILD_GUI="$gui"
fi
cmake --build "$build" -j"$jobs"

export QT_QPA_PLATFORM=offscreen
cd "$build"
ctest --output-on-failure -j"$jobs" "$@"
