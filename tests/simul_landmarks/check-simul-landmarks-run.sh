#!/usr/bin/env bash
# A user's own range-bearing rawlog made by MRPT's stock simul-landmarks (hidden landmark IDs,
# the sensor 0.2 m ahead of the robot and turned 15 deg, both recorded in each observation):
# scripts/simul-landmarks-ground-truth.sh turns its ground truth into NAME.groundtruth.tum and
# NAME.landmarks.txt, and multirobot-vslam runs from the range-bearing template with no change,
# scored against that ground truth, on the rawlog and on its second half cut by rawlog-edit. Also
# the converter's one-line errors.
# Usage: check-simul-landmarks-run.sh SOURCE_DIR BUILD_DIR [SIM_SEED]
# Exits 77 (skipped) without mrpt-apps' simul-landmarks and rawlog-edit.
source "$(dirname "${BASH_SOURCE[0]}")/test-setup.sh"
sim_seed="${3:-1}"
convert="$src/scripts/simul-landmarks-ground-truth.sh"

# 300 readings on the 7.2 m square, 40 landmarks, medium noise (0.1 m, 2 deg)
"$src/scripts/simul-landmarks-rawlog.sh" \
  "$src/share/mrpt-vslam/config/peer-comparison/simul-landmarks-noise-medium.ini" \
  "$scratch/user.rawlog" random_seed="$sim_seed" sensorDetectsIDs=false sensorPose_x=0.2 \
  sensorPose_yaw_deg=15
poses=$(grep -vc '^#' "$scratch/user.groundtruth.tum")
[ "$poses" = 299 ] || fail "user.groundtruth.tum has $poses poses, expected 299 (300 readings, the first passed over)"
landmarks=$(grep -vc '^#' "$scratch/user.landmarks.txt")
[ "$landmarks" = 40 ] || fail "user.landmarks.txt has $landmarks landmarks, expected 40"

# check_run NAME POSES: multirobot-vslam on NAME.rawlog from the template, scored against the
# ground truth beside it over POSES poses; its first pose within 0.05 m of the nearest true one
check_run() {
  "$build/bin/multirobot-vslam" "$src/share/mrpt-vslam/config/multirobot-vslam/range-bearing.ini" \
    "$scratch/$1.rawlog" --out "$scratch/run-$1" --seed 1 --quiet
  python3 - "$scratch/run-$1/metrics.json" "$2" "$scratch/run-$1/estimated_path_R1.tum" \
    "$scratch/$1.groundtruth.tum" <<'PY' || fail "multirobot-vslam's metrics.json of $1 out of bounds"
import json, math, sys
rows = lambda f: [l.split() for l in open(f) if not l.startswith("#")]
first = rows(sys.argv[3])[0]
true = min(rows(sys.argv[4]), key=lambda r: abs(float(r[0]) - float(first[0])))
off = math.hypot(float(first[1]) - float(true[1]), float(first[2]) - float(true[2]))
print("first pose %.3f m from the true one" % off)
if off > 0.05: sys.exit(1)
m = json.load(open(sys.argv[1]))
e = m["robots"]["R1"]["estimate"] if "robots" in m else m["estimate"]
lm = m["landmarks"]
print("ATE RMSE %.3f m over %d poses; landmarks %d estimated, %d matched, error mean %.3f m"
      % (e["ate_rmse_m"], e["matched_poses"], lm["estimated_landmarks"], lm["matched"], lm["error_mean_m"]))
ok = (e["matched_poses"] >= int(sys.argv[2]) and e["ate_rmse_m"] < 0.12
      and abs(lm["estimated_landmarks"] - 40) <= 3 and lm["matched"] >= 39 and lm["error_mean_m"] < 0.12)
sys.exit(0 if ok else 1)
PY
}
check_run user 299

# the same cut by stock rawlog-edit from the action of step 151 on, beside the whole one's ground
# truth: the run starts where that puts its first step (the nearest true pose less the step's
# odometry: simul-landmarks stamps its steps microseconds apart, so many lie within 0.05 s)
rawlog-edit --cut --from-index 301 -i "$scratch/user.rawlog" -o "$scratch/cut.rawlog" -w -q \
  > "$scratch/cut.log" 2>&1 || { tail -3 "$scratch/cut.log" >&2; fail "rawlog-edit --cut failed"; }
cp "$scratch/user.groundtruth.tum" "$scratch/cut.groundtruth.tum"
cp "$scratch/user.landmarks.txt" "$scratch/cut.landmarks.txt"
check_run cut 149

# bad input: one line naming the file, exit 1, nothing written
rm "$scratch/user.groundtruth.tum" "$scratch/user.landmarks.txt" "$scratch/user.rawlog_ground_truth.txt"
if "$convert" "$scratch/user.rawlog" 2> "$scratch/err"; then fail "converted without the landmarks file"; fi
[ "$(wc -l < "$scratch/err")" = 1 ] && grep -q "user.rawlog_ground_truth.txt: missing" "$scratch/err" ||
  fail "the missing landmarks file gave: $(cat "$scratch/err")"
[ ! -e "$scratch/user.groundtruth.tum" ] || fail "a ground truth was written without the landmarks"
echo garbage > "$scratch/g.rawlog"
cp "$scratch/user.rawlog_ground_truth_robot_path.txt" "$scratch/g.rawlog_ground_truth_robot_path.txt"
echo "1 2 3 5 0 0 7" > "$scratch/g.rawlog_ground_truth.txt"
if "$convert" "$scratch/g.rawlog" 2> "$scratch/err"; then fail "converted a rawlog of garbage"; fi
[ "$(wc -l < "$scratch/err")" = 1 ] && grep -q "g.rawlog: " "$scratch/err" ||
  fail "the garbage rawlog gave: $(cat "$scratch/err")"
echo "simul-landmarks run: passed"
