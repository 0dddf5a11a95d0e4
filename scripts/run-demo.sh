#!/usr/bin/env bash
# Installs what is missing, builds into build/, then runs omni-fastslam on the shipped
# sports-hall dataset, multirobot-vslam on the shipped 2-robot office-team dataset and view-slam on
# the shipped omni-views sequence; each app evaluates its run against ground truth (metrics.json,
# its figures printed at the end) and vslam-eval draws the PNG plots.
# Results go to out/demo/ (or $DEMO_OUT).
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"

OUT="${DEMO_OUT:-$REPO_DIR/out/demo}"
BIN="$BUILD_DIR/bin"
DATA="$REPO_DIR/datasets/sports-hall/hall.rawlog"

# each app prints its figures at the end; vslam-eval (its own summary silenced) draws the plots
"$BIN/omni-fastslam" "$REPO_DIR/share/mrpt-vslam/config/omni-fastslam/sports-hall.ini" "$DATA" \
  --out "$OUT/omni-fastslam" --seed 1
"$BIN/vslam-eval" "$OUT/omni-fastslam" --ground-truth "${DATA%.rawlog}" >/dev/null

TEAM="$REPO_DIR/datasets/office-team/team2.rawlog"
echo
"$BIN/multirobot-vslam" "$REPO_DIR/share/mrpt-vslam/config/multirobot-vslam/office-team-2.ini" \
  "$TEAM" --out "$OUT/multirobot-vslam" --seed 1
"$BIN/vslam-eval" "$OUT/multirobot-vslam" --ground-truth "${TEAM%.rawlog}" >/dev/null

ROOMS="$REPO_DIR/datasets/omni-views/rooms.rawlog"
echo
"$BIN/view-slam" "$REPO_DIR/share/mrpt-vslam/config/view-slam/omni-views.ini" "$ROOMS" \
  --out "$OUT/view-slam" --seed 1
"$BIN/vslam-eval" "$OUT/view-slam" --ground-truth "${ROOMS%.rawlog}" >/dev/null

echo
echo "Demo results in $OUT/omni-fastslam, $OUT/multirobot-vslam and $OUT/view-slam:"
echo "  estimated_path*.tum, map.txt, metrics.json, run.json, paths.png, errors.png, landmark_errors.png"
echo "  final.3Dscene (open with: SceneViewer3D $OUT/omni-fastslam/final.3Dscene)"
