#!/usr/bin/env bash
# Runs each SLAM app on its shipped dataset (the README's commands, into a temporary folder),
# opens each run's final.3Dscene in SceneViewer3D under Xvfb and saves the window, scaled to
# half size, to doc/img/scene-<app>.png: the screenshots doc/data-formats.md shows.
# Needs Xvfb (xvfb-run), xwininfo and python3 (scripts/screenshot-x11.py).
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"

OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
BIN="$BUILD_DIR/bin"
CONFIG="$REPO_DIR/share/mrpt-vslam/config"
DATA="$REPO_DIR/datasets"

"$BIN/omni-fastslam" "$CONFIG/omni-fastslam/sports-hall.ini" "$DATA/sports-hall/hall.rawlog" \
  --out "$OUT/omni-fastslam" --seed 1
"$BIN/multirobot-vslam" "$CONFIG/multirobot-vslam/office-team-2.ini" \
  "$DATA/office-team/team2.rawlog" --out "$OUT/multirobot-vslam" --seed 1
"$BIN/view-slam" "$CONFIG/view-slam/omni-views.ini" "$DATA/omni-views/rooms.rawlog" \
  --out "$OUT/view-slam" --seed 1

# SCENE PNG: opens SCENE in SceneViewer3D on the current X display, waits for the file to be
# loaded (its name in the window title), fills the screen with the window and saves it to PNG.
shoot() {
  HOME="$OUT" SceneViewer3D "$1" >"$OUT/SceneViewer3D.log" 2>&1 &
  local viewer=$! window=""
  for _ in $(seq 60); do
    window=$(xwininfo -root -tree |
      awk '/"SceneViewer3D - Part of the MRPT project \[final.3Dscene\]"/ {print $1}')
    [ -n "$window" ] && break
    sleep 1
  done
  if [ -z "$window" ]; then
    echo "make-scene-screenshots.sh: SceneViewer3D did not open $1" >&2
    kill "$viewer"
    return 1
  fi
  local status=0
  python3 "$REPO_DIR/scripts/screenshot-x11.py" "$2" --window "$window" --scale 2 || status=$?
  kill "$viewer"
  return "$status"
}
export OUT REPO_DIR

for app in omni-fastslam multirobot-vslam view-slam; do
  # xvfb-run is a sh script: the function goes in as text, not exported
  xvfb-run -a -s "-screen 0 1280x900x24" bash -c "$(declare -f shoot); shoot \"\$@\"" shoot \
    "$OUT/$app/final.3Dscene" "$REPO_DIR/doc/img/scene-$app.png"
  echo "doc/img/scene-$app.png"
done
