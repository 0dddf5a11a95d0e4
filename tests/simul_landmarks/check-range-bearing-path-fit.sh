#!/usr/bin/env bash
# scripts/range-bearing-path-fit.py on rawlogs of MRPT's stock simul-landmarks (the sensor 0.2 m
# ahead of the robot and turned 15 deg):
#   - without noise, the true path explains odometry and readings exactly (chi-square ~ 0);
#   - with medium noise, the true path's chi-square is the chi-square of the measured values less
#     the landmarks' two coordinates each (within 4 std), the odometry path's odometry part is 0,
#     and multirobot-vslam's path, fitted to the data, has a lower chi-square than the truth;
#   - the most probable path (--most-probable): without noise, the truth (to 1e-5: rawlog-edit
#     lists the readings to 1e-6 m and rad); with medium noise, the same from the truth and from
#     multirobot-vslam's path, its first pose the truth's and its chi-square below every path
#     scored;
#   - readings that are not those of the IDs-kept twin give one line and exit 1.
# Usage: check-range-bearing-path-fit.sh SOURCE_DIR BUILD_DIR
# Exits 77 (skipped) without mrpt-apps' simul-landmarks and rawlog-edit.
source "$(dirname "${BASH_SOURCE[0]}")/test-setup.sh"
fit="$src/scripts/range-bearing-path-fit.py"

# simulate NAME IDS(true|false) STD_RANGE STD_YAW_DEG ODOMETRY_STD_XY ODOMETRY_STD_PHI_DEG:
# NAME.rawlog, its ground truth and NAME.readings.txt in $scratch (300 readings, 40 landmarks)
simulate() {
  "$src/scripts/simul-landmarks-rawlog.sh" \
    "$src/share/mrpt-vslam/config/peer-comparison/simul-landmarks-noise-medium.ini" \
    "$scratch/$1.rawlog" random_seed=3 sensorDetectsIDs="$2" sensorPose_x=0.2 \
    sensorPose_yaw_deg=15 stdRange="$3" stdYaw_deg="$4" odometryNoiseXY_std="$5" \
    odometryNoisePhi_std_deg="$6"
  rawlog-edit -i "$scratch/$1.rawlog" --list-range-bearing --text-file-output "$scratch/$1.readings.txt" \
    -q > /dev/null 2>&1 || fail "rawlog-edit could not list the readings of $1.rawlog"
}

# score NAME STD_RANGE STD_YAW_DEG ODOMETRY_STD_XY ODOMETRY_STD_PHI_DEG PATH...: the fit's lines
score() {
  local name="$1"
  "$fit" --readings "$scratch/$name-hidden.readings.txt" --ids-from "$scratch/$name-kept.readings.txt" \
    --stamps "$scratch/$name-hidden.groundtruth.tum" --odometry "$scratch/run-$name/odometry_path_R1.tum" \
    --std-range "$2" --std-bearing-deg "$3" --odometry-std-xy "$4" --odometry-std-phi-deg "$5" \
    --sensor-pose 0.2 0 15 "${@:6}"
}

run() {  # run NAME [ARGS]: multirobot-vslam from the template on NAME-hidden.rawlog
  "$build/bin/multirobot-vslam" "$src/share/mrpt-vslam/config/multirobot-vslam/range-bearing.ini" \
    "$scratch/$1-hidden.rawlog" --out "$scratch/run-$1" --seed 1 --quiet "${@:2}" > /dev/null
}

# without noise (the fit's std only scale the residuals: 1 m, 1 deg)
simulate exact-kept true 0 0 0 0
simulate exact-hidden false 0 0 0 0
run exact --set MultiRobotVSLAM.range_bearing_std_range=0.01 \
  --set MultiRobotVSLAM.range_bearing_std_bearing_deg=0.1
out="$(score exact 1 1 1 1 "$scratch/exact-hidden.groundtruth.tum")"
echo "without noise, the true path: $out"
awk '{ exit !($2 < 1e-3) }' <<< "$out" || fail "the true path does not explain noise-free data: $out"
out="$(score exact 1 1 1 1 --most-probable "$scratch/exact-most-probable.tum" \
  "$scratch/run-exact/estimated_path_R1.tum")"
echo "without noise, from multirobot-vslam's path (its chi2, then the most probable path's):"
echo "$out"
# largest_difference A.tum B.tum: the largest |x|, |y| or |yaw| difference of two paths, pose by pose
largest_difference() {
  awk '/^#/ { next } NR == FNR { p[$1] = $2 " " $3 " " $7 " " $8; next }
    { split(p[$1], q, " "); if (!($1 in p)) { print "no pose at " $1; exit 1 }
      d = atan2(q[3], q[4]) - atan2($7, $8); d = sin(d) ^ 2
      for (i = 1; i <= 2; i++) { e = (q[i] - $(i + 1)) ^ 2; if (e > d) d = e }
      if (d > m) m = d }
    END { printf "%.3g\n", sqrt(m) }' "$1" "$2"
}
difference=$(largest_difference "$scratch/exact-hidden.groundtruth.tum" "$scratch/exact-most-probable.tum")
echo "without noise, against the truth: multirobot-vslam's path $(largest_difference \
  "$scratch/exact-hidden.groundtruth.tum" "$scratch/run-exact/estimated_path_R1.tum"), the most" \
  "probable path $difference (rawlog-edit lists readings to 1e-6 m and rad)"
awk -v d="$difference" 'NR == 2 { exit !($2 < 1e-6 && d < 1e-5) }' <<< "$out" ||
  fail "the most probable path of noise-free data is not the truth"

# medium noise: 0.1 m, 2 deg; odometry 0.01 m, 0.5 deg
simulate medium-kept true 0.1 2 0.01 0.5
simulate medium-hidden false 0.1 2 0.01 0.5
run medium
out="$(score medium 0.1 2 0.01 0.5 "$scratch/medium-hidden.groundtruth.tum" \
  "$scratch/run-medium/odometry_path_R1.tum" "$scratch/run-medium/estimated_path_R1.tum")"
echo "medium noise (path chi2 odometry readings values):"
echo "$out"
landmarks=$(grep -vc '^#' "$scratch/medium-hidden.landmarks.txt")
awk -v landmarks="$landmarks" 'NR == 1 { dof = $5 - 2 * landmarks; truth = $2
    if ((truth - dof) ^ 2 > 16 * 2 * dof) { print "the true path: chi2 " truth ", expected " dof " +- " 4 * sqrt(2 * dof); bad = 1 } }
  NR == 2 && $3 != 0 { print "the odometry path: odometry chi2 " $3 ", expected 0"; bad = 1 }
  NR == 3 && !($2 < truth) { print "multirobot-vslam: chi2 " $2 ", not below the true path " truth; bad = 1 }
  END { exit bad || NR != 3 }' <<< "$out" || fail "medium noise"
for start in truth ours; do
  first="$scratch/medium-hidden.groundtruth.tum"
  [ $start = ours ] && first="$scratch/run-medium/estimated_path_R1.tum"
  score medium 0.1 2 0.01 0.5 --most-probable "$scratch/most-probable-$start.tum" "$first" |
    tail -1 > "$scratch/most-probable-$start.txt"
done
echo "medium noise, the most probable path from the truth and from multirobot-vslam's path:"
cat "$scratch/most-probable-truth.txt" "$scratch/most-probable-ours.txt" | tee "$scratch/most-probable.txt"
least=$(awk 'NR == 1 || $2 < m { m = $2 } END { print m }' <<< "$out")
awk -v least="$least" 'NR == 1 { chi2 = $2
    if (!(chi2 < least)) { print "chi2 " chi2 ", not below the least of the paths, " least; bad = 1 } }
  NR == 2 && (chi2 - $2) ^ 2 > (1e-6 * chi2) ^ 2 { print "from the truth " chi2 ", from multirobot-vslam " $2; bad = 1 }
  END { exit bad || NR != 2 }' "$scratch/most-probable.txt" || fail "medium noise: the most probable path"
awk '!/^#/ { print; exit }' "$scratch/medium-hidden.groundtruth.tum" > "$scratch/first-truth.tum"
awk '!/^#/ { print; exit }' "$scratch/most-probable-truth.tum" > "$scratch/first-most-probable.tum"
difference=$(largest_difference "$scratch/first-truth.tum" "$scratch/first-most-probable.tum")
awk -v d="$difference" 'BEGIN { exit !(d < 1e-6) }' ||
  fail "medium noise: the most probable path starts $difference from the truth's first pose"

# readings of another simulation: one line naming the file, exit 1
awk '!/^%/ && !done { $4 = $4 + 0.5; done = 1 } { print }' "$scratch/medium-kept.readings.txt" \
  > "$scratch/other.readings.txt"
if "$fit" --readings "$scratch/medium-hidden.readings.txt" --ids-from "$scratch/other.readings.txt" \
    --stamps "$scratch/medium-hidden.groundtruth.tum" --odometry "$scratch/run-medium/odometry_path_R1.tum" \
    --std-range 0.1 --std-bearing-deg 2 --odometry-std-xy 0.01 --odometry-std-phi-deg 0.5 \
    "$scratch/medium-hidden.groundtruth.tum" 2> "$scratch/err"; then
  fail "scored with the readings of another rawlog"
fi
[ "$(wc -l < "$scratch/err")" = 1 ] && grep -q "other.readings.txt: not the readings of" "$scratch/err" ||
  fail "other readings gave: $(cat "$scratch/err")"
echo "range-bearing path fit: passed"
