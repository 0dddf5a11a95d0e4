#!/usr/bin/env bash
# The ground truth of a rawlog written by MRPT's simul-landmarks, in the form the apps and
# vslam-eval read (doc/data-formats.md): for each NAME.rawlog given, writes beside it
#   NAME.groundtruth.tum  the robot's true pose at each reading, at the reading's stamp, from
#                         NAME.rawlog_ground_truth_robot_path.txt (x y z yaw pitch roll per reading);
#   NAME.landmarks.txt    the true landmarks (id x y z), from NAME.rawlog_ground_truth.txt.
# The stamps are those rawlog-edit lists (--list-timestamps): it reads the rawlog as action /
# frame pairs and so passes over the first reading, taken before any motion; that reading's pose
# (the start, which the next readings share while the robot stands) has no line.
# Usage: scripts/simul-landmarks-ground-truth.sh NAME.rawlog [NAME2.rawlog ...]
# Then: multirobot-vslam share/mrpt-vslam/config/multirobot-vslam/range-bearing.ini NAME.rawlog
# starts from the true start pose and writes metrics.json (doc/your-own-data.md).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/command-usage.sh" "$@"
command -v rawlog-edit > /dev/null ||
  { echo "rawlog-edit not found: install mrpt-apps (scripts/setup.sh does)" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

convert() {
  local rawlog="$1"
  local name="${rawlog%.rawlog}" path="$rawlog"_ground_truth_robot_path.txt
  local landmarks="$rawlog"_ground_truth.txt
  [[ "$rawlog" == *.rawlog ]] || { echo "$rawlog: not a .rawlog file name" >&2; exit 1; }
  local f
  for f in "$rawlog" "$path" "$landmarks"; do
    [ -s "$f" ] || { echo "$f: missing or empty (simul-landmarks writes it beside the rawlog)" >&2
      exit 1; }
  done
  rawlog-edit -i "$rawlog" --list-timestamps --text-file-output "$tmp/stamps.txt" -q \
    > "$tmp/rawlog-edit.log" 2>&1 && [ -s "$tmp/stamps.txt" ] ||
    { echo "$rawlog: rawlog-edit lists no timestamps (not a rawlog of action / frame pairs?)" >&2
      exit 1; }
  awk -v f="$rawlog" 'NR > 1 && $1 <= p { print f ": stamps not increasing at reading " NR + 1 > "/dev/stderr"; exit 1 }
       { p = $1 }' "$tmp/stamps.txt"
  # reading k >= 1 at stamp k; planar path: q = (0, 0, sin(yaw/2), cos(yaw/2))
  awk -v f="$path" 'NR == FNR { t[++n] = $1; next }
       /^%/ || NF == 0 { next }
       NF != 6 { print f ": line " FNR " has " NF " fields, expected x y z yaw pitch roll" > "/dev/stderr"
                 bad = 1; exit 1 }
       $5 != 0 || $6 != 0 { print f ": line " FNR " has pitch or roll: a 6D path, and the apps need a planar one" > "/dev/stderr"
                 bad = 1; exit 1 }
       { if (++r > 1) printf "%s %.9f %.9f %.9f 0 0 %.9f %.9f\n", t[r - 1], $1, $2, $3, sin($4 / 2), cos($4 / 2) }
       END { if (!bad && r - 1 != n) { print f ": " r " poses, the rawlog has " n + 1 " readings" > "/dev/stderr"; exit 1 } }' \
    "$tmp/stamps.txt" "$path" | { echo "# timestamp x y z qx qy qz qw"; cat; } > "$tmp/groundtruth.tum"
  # CLandmarksMap::saveToTextFile: x y z, three other fields, the ID in column 7
  awk -v f="$landmarks" 'BEGIN { print "# id x y z" }
       /^%/ || NF == 0 { next }
       NF < 7 { print f ": line " FNR " has " NF " fields, expected x y z and the ID in column 7" > "/dev/stderr"; exit 1 }
       { printf "%d %s %s %s\n", $7, $1, $2, $3 }' "$landmarks" > "$tmp/landmarks.txt"
  mv "$tmp/groundtruth.tum" "$name.groundtruth.tum"
  mv "$tmp/landmarks.txt" "$name.landmarks.txt"
}

for rawlog in "$@"; do convert "$rawlog"; done
