# Debian 12 packages StickSlip Lab needs, installed when missing. Sourced by scripts/test.sh
# and scripts/run.sh; the list lives here only.
# shellcheck shell=bash

STICKSLIP_DEB_PACKAGES=(
  build-essential cmake pkg-config
  qtbase5-dev libqt5svg5-dev libqwt-qt5-dev
  libeigen3-dev libceres-dev libfftw3-dev
  libcli11-dev nlohmann-json3-dev libcsv-dev
  libgtest-dev libbenchmark-dev
  pybind11-dev python3-numpy python3-pytest python3-matplotlib
  libopenmpi-dev openmpi-bin
  xvfb xauth desktop-file-utils
)

stickslip_install_deps() {
  local missing=() pkg status
  for pkg in "${STICKSLIP_DEB_PACKAGES[@]}"; do
    status=$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)
    [ "$status" = "installed" ] || missing+=("$pkg")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "deps: installing missing Debian packages: ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
      sudo=(sudo)
    else
      echo "deps: not root and no sudo; please install: ${missing[*]}" >&2
      return 1
    fi
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo[@]}" apt-get update -q
  "${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
}

stickslip_install_deps
