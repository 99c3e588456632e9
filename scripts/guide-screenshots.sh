#!/usr/bin/env bash
# Regenerates the user guide's pictures (docs/img/guide/*.png) from the built app under Xvfb:
# the main window, every view on the preset that shows it best (the paper's figures), the
# bifurcation sweep and periodicity map as the Analysis menu computes them, the Identify panel
# and the import dialog (through their GUI tests' screenshot hooks). Usage:
#   scripts/guide-screenshots.sh [BUILD_DIR]      (default build/; builds what is missing)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/docs/img/guide"
mkdir -p "$out"
cmake --build "$build" -j"$(nproc)" --target stickslip gui_tst_identify_panel gui_tst_import_dialog >/dev/null

app="$build/bin/stickslip"
xvfb=(xvfb-run -a -s "-screen 0 1280x800x24")
unset QT_QPA_PLATFORM  # a real X server (Xvfb), as a user's desktop

shot() {  # shot NAME PRESET [app options...]
  local name="$1" preset="$2"
  shift 2
  echo "guide-screenshots: $name ($preset $*)"
  "${xvfb[@]}" timeout 300 "$app" --preset "$preset" --screenshot "$out/$name.png" "$@"
}

shot main fig20
shot parameters fig20 --screenshot-view parameters
shot timeseries fig20 --screenshot-view timeseries
shot rig fig20 --screenshot-view rig
shot loop fig17 --screenshot-view loop
shot phase fig22 --screenshot-view phase
shot poincare fig20 --session "$root/docs/sessions/fig20-irregular.json" --screenshot-view poincare
shot spectrum fig22 --screenshot-view spectrum
shot autocorrelation fig23 --screenshot-view autocorrelation
shot bifurcation fig20 --analysis sweep --screenshot-view bifurcation
shot map fig20 --analysis map --screenshot-view map

echo "guide-screenshots: identify panel"
IDENTIFY_PANEL_SHOT="$out/identify.png" "${xvfb[@]}" "$build/tests/gui_tst_identify_panel" >/dev/null
echo "guide-screenshots: import dialog"
tmp="$(mktemp -d)"
STICKSLIP_SCREENSHOT_DIR="$tmp" "${xvfb[@]}" "$build/tests/gui_tst_import_dialog" screenshot >/dev/null
cp "$tmp/import_dialog.png" "$out/import.png"
cp "$tmp/import_dialog_cleaning.png" "$out/import-cleaning.png"
rm -rf "$tmp"
ls -l "$out"
