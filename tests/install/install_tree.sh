#!/usr/bin/env bash
# `cmake --install BUILD --prefix P` into a fresh temporary P, then use the installation as a
# user would, from another directory: the CLI runs a preset, the app starts (offscreen) and
# saves a screenshot, the desktop entry validates and names an installed icon, both man pages
# render, the docs are there. Usage: install_tree.sh BUILD_DIR
set -euo pipefail
build="$1"
prefix="$(mktemp -d)"
work="$(mktemp -d)"
trap 'rm -rf "$prefix" "$work"' EXIT
fail() { echo "install_tree: FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" >"$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }
echo "install_tree: installed $(wc -l <"$work/install.log") files under $prefix"

for f in bin/stickslip-cli share/man/man1/stickslip-cli.1 share/doc/stickslip/README.md \
         share/doc/stickslip/guide.md share/doc/stickslip/img/screenshot-main.png; do
  [ -e "$prefix/$f" ] || fail "missing $f"
done

cd "$work"  # nothing from the source or build tree on the way
"$prefix/bin/stickslip-cli" --version | grep -q '^stickslip-cli ' || fail "stickslip-cli --version"
"$prefix/bin/stickslip-cli" presets | grep -q fig20 || fail "stickslip-cli presets"
"$prefix/bin/stickslip-cli" simulate --preset fig20 --cycles 2 --out run.csv || fail "stickslip-cli simulate"
[ "$(grep -vc '^#' run.csv)" -gt 100 ] || fail "simulate wrote too few rows"
MANWIDTH=100 man -l "$prefix/share/man/man1/stickslip-cli.1" 2>&1 | grep -q 'EXIT STATUS' || fail "man stickslip-cli"

if [ -x "$prefix/bin/stickslip" ] || [ -e "$build/bin/stickslip" ]; then
  for f in bin/stickslip share/applications/stickslip.desktop share/icons/hicolor/scalable/apps/stickslip.svg \
           share/icons/hicolor/48x48/apps/stickslip.png share/icons/hicolor/256x256/apps/stickslip.png \
           share/man/man1/stickslip.1; do
    [ -e "$prefix/$f" ] || fail "missing $f"
  done
  desktop="$prefix/share/applications/stickslip.desktop"
  if command -v desktop-file-validate >/dev/null; then desktop-file-validate "$desktop" || fail "desktop entry"; fi
  icon=$(sed -n 's/^Icon=//p' "$desktop")
  exe=$(sed -n 's/^Exec=\([^ ]*\).*/\1/p' "$desktop")
  [ -e "$prefix/share/icons/hicolor/scalable/apps/$icon.svg" ] || fail "Icon=$icon is not installed"
  [ -x "$prefix/bin/$exe" ] || fail "Exec=$exe is not installed"
  MANWIDTH=100 man -l "$prefix/share/man/man1/stickslip.1" 2>&1 | grep -q 'SYNOPSIS' || fail "man stickslip"
  export QT_QPA_PLATFORM=offscreen
  "$prefix/bin/stickslip" --version | grep -q 'stickslip' || fail "stickslip --version"
  timeout 120 "$prefix/bin/stickslip" --preset fig20 --screenshot shot.png || fail "installed app did not start"
  [ -s shot.png ] || fail "installed app saved no screenshot"
  echo "install_tree: the installed app started from the prefix and saved a screenshot"
fi
if compgen -G "$build/python/stickslip*.so" >/dev/null; then
  mod=$(compgen -G "$prefix/lib/python3/dist-packages/stickslip*.so" | head -1)
  [ -n "$mod" ] || fail "the Python module is built but not installed"
  PYTHONPATH="$prefix/lib/python3/dist-packages" /usr/bin/python3 -c '
import stickslip
r = stickslip.simulate(preset="fig20", cycles=2)
assert len(r["time_s"]) > 100, len(r["time_s"])
print("install_tree: python module from the prefix:", stickslip.__file__)' || fail "installed Python module"
fi
echo "install_tree: OK"
