#!/usr/bin/env bash
# A rawlog made by MRPT's stock simul-landmarks (mrpt-apps), with its ground truth in the form
# the apps and vslam-eval read: runs simul-landmarks on a copy of CONFIG with outFile and outDir
# set to write DIR/NAME.rawlog and each KEY set to VALUE (scripts/ini-set.sh: every KEY must
# occur once in CONFIG), then scripts/simul-landmarks-ground-truth.sh on the rawlog. Writes in
# DIR: NAME.simul-landmarks.ini (the copy), NAME.simul-landmarks.log, NAME.rawlog,
# NAME.rawlog_ground_truth.txt, NAME.rawlog_ground_truth_robot_path.txt, NAME.groundtruth.tum
# and NAME.landmarks.txt. simul-landmarks exits 0 after an error: a file it did not write gives
# one line, exit status 1 and no rawlog.
# Usage: scripts/simul-landmarks-rawlog.sh CONFIG DIR/NAME.rawlog [KEY=VALUE ...]
# CONFIG: share/mrpt-vslam/config/peer-comparison/simul-landmarks-noise-*.ini (point landmarks,
# range and bearing) or share/mrpt-vslam/config/omni-fastslam/simul-landmarks-ceiling-lights.ini.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/command-usage.sh" "$@"
[ $# -ge 2 ] || { usage >&2; exit 2; }
config="$1" rawlog="$2"; shift 2
[[ "$rawlog" == *.rawlog ]] || { echo "$rawlog: not a .rawlog file name" >&2; exit 1; }
command -v simul-landmarks > /dev/null ||
  { echo "simul-landmarks not found: install mrpt-apps (scripts/setup.sh does)" >&2; exit 2; }
scripts="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="$(dirname "$rawlog")" name="$(basename "$rawlog" .rawlog)"
mkdir -p "$dir"
"$scripts/ini-set.sh" "$config" "$dir/$name.simul-landmarks.ini" outFile="$name.rawlog" outDir=. "$@"
written=("$dir/$name.rawlog" "$dir/$name.rawlog_ground_truth.txt"
  "$dir/$name.rawlog_ground_truth_robot_path.txt")
rm -f "${written[@]}"
(cd "$dir" && simul-landmarks "$name.simul-landmarks.ini" < /dev/null > "$name.simul-landmarks.log" 2>&1)
for f in "${written[@]}"; do
  [ -s "$f" ] || { tail -5 "$dir/$name.simul-landmarks.log" >&2; rm -f "${written[@]}"
    echo "simul-landmarks wrote no $f (its log: $dir/$name.simul-landmarks.log)" >&2; exit 1; }
done
"$scripts/simul-landmarks-ground-truth.sh" "$rawlog"
