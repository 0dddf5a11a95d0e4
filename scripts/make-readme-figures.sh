#!/usr/bin/env bash
# Runs the demo (scripts/run-demo.sh) and copies each app's path plot to doc/img/demo-<app>.png,
# the figures the README shows.
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
DEMO_OUT="$OUT" bash "$REPO_DIR/scripts/run-demo.sh" > "$OUT/demo.log"
for app in omni-fastslam multirobot-vslam view-slam; do
  cp "$OUT/$app/paths.png" "$REPO_DIR/doc/img/demo-$app.png"
  echo "doc/img/demo-$app.png"
done
