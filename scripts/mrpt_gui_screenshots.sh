#!/usr/bin/env bash
# Screenshots of MRPT's GUI programs with GASP's plugin loaded, on a virtual display (Xvfb), for
# docs/mrpt.md. Needs: xvfb, xdotool, imagemagick (apt-get install xvfb xdotool imagemagick), a build
# (default build/ci) and the files written by the install test (ctest -R install.FindPackageConsumer:
# <build>/test_tmp/install/o2m/desk9_gasp__CSuperpixelMap_00_3D.3Dscene).
#   scripts/mrpt_gui_screenshots.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build/ci}
OUT=${2:-docs/images}
PLUGIN=$BUILD/lib/libgasp_mrpt.so
SCENE=$BUILD/test_tmp/install/o2m/desk9_gasp__CSuperpixelMap_00_3D.3Dscene

for f in "$PLUGIN" "$SCENE"; do
  [[ -f $f ]] || { echo "missing $f (build, then run: ctest -R install.FindPackageConsumer)" >&2; exit 1; }
done
for tool in xvfb-run xdotool import convert; do
  command -v $tool > /dev/null || { echo "missing $tool: apt-get install xvfb xdotool imagemagick" >&2; exit 1; }
done
mkdir -p "$OUT"

# $1 = output PNG, $2 = zoom clicks (mouse wheel), $3 = crop geometry of the 1280x800 screen,
# rest = the command. Escape closes a start-up dialog (RawLogViewer's tips).
shot() {
  local png=$1 clicks=$2 crop=$3; shift 3
  xvfb-run -a -s "-screen 0 1280x800x24" bash -c '
    "$@" > /dev/null 2>&1 & pid=$!
    sleep 8
    for w in $(xdotool search --onlyvisible --name "" 2>/dev/null); do xdotool windowmove $w 0 0 windowsize $w 1270 790; done
    sleep 2; xdotool key Escape; sleep 1; xdotool mousemove 700 560
    for i in $(seq 1 '"$clicks"'); do xdotool click 4; sleep 0.05; done
    sleep 3; import -window root /tmp/gasp_shot.png; kill $pid' _ "$@"
  convert /tmp/gasp_shot.png -crop "$crop" +repage "$png"
  echo "wrote $png"
}

shot "$OUT/mrpt_sceneviewer3d_desk9.png" 30 660x420+560+400 SceneViewer3D -l "$PLUGIN" "$SCENE"
