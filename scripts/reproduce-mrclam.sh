#!/usr/bin/env bash
# Real data: UTIAS MRCLAM dataset 7 (doc/real-data.md), landmark identities hidden from the
# filters (but in section 5).
#   1. import with mrclam2rawlog (commands delayed 0.2 s, the robots' readings of each other kept):
#      robots 1-3, 1, 2, 3, 1-2 and 1-5 with ids hidden, robots 1-3 once more with ids kept (to
#      count wrong associations; the filter reads them only in section 5); the importer's residuals
#      against Vicon and the dead reckoning's error;
#   2. multirobot-vslam (mrclam.ini), robots 1-3 jointly, several seeds: per-robot ATE of the
#      smoothed paths and of the filter's vs odometry, the particle's map and the output map
#      (landmarks matched within 0.5 m, extra landmarks), parts of paths reanchored, wrong
#      associations, the run kept of the independent filters, run time; the plots of the first
#      seed; then each filter alone (filter_runs = 1) on more seeds, with its smoothed cost;
#   3. the filter alone (no smoothing, the particles' own maps) on each robot alone, on 2 and 5
#      robots, on robots 1-3, and on robots 1-3 without the readings of robots;
#   4. robots 1-3 with known poses (the Vicon poses as odometry) and three gates D0: what the
#      association alone makes of the readings;
#   5. robots 1-3 with known correspondences (associate_by_identity): the filter's paths when
#      the association is right;
#   6. robots 1, 2 and 3 each alone from the template (range-bearing.ini), imported as a user
#      would, with their odometry and with the Vicon poses as odometry: the paths, the map and
#      the check of the sensor's pose.
# (omni-fastslam's planar mode on robot 1: scripts/reproduce-omni-fastslam.sh.)
# Writes the tables to doc/results/real-data.md (or $RESULTS) and the plots of section 2 to
# doc/results/real-data/; run folders under out/reproduce-mrclam/ (or $OUT). Builds first
# (scripts/setup.sh). Takes about 24 min on two cores (M = 2000 as shipped).
# Environment: MRPT_VSLAM_MRCLAM_DIR (required: the folder of dataset 7's .dat files, see
# doc/real-data.md), SEEDS (default 1 2 3 4 5), SINGLE_SEEDS (the seeds of the filters alone in
# section 2, default 1 to 15), OUT, RESULTS.
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DATASET="${MRPT_VSLAM_MRCLAM_DIR:-}"
if [ ! -f "$DATASET/Barcodes.dat" ]; then
  echo "reproduce-mrclam.sh: set MRPT_VSLAM_MRCLAM_DIR to the folder of UTIAS MRCLAM dataset 7" \
    "(its .dat files; doc/real-data.md says where to get it)" >&2
  exit 2
fi
source "$REPO_DIR/scripts/setup.sh"
# after the build: the results header times the runs only
source "$REPO_DIR/scripts/results-header.sh"
COMMAND="$(results_command scripts/reproduce-mrclam.sh SEEDS SINGLE_SEEDS OUT RESULTS)"

OUT="${OUT:-$REPO_DIR/out/reproduce-mrclam}"
BIN="$BUILD_DIR/bin"
CONFIGS="$REPO_DIR/share/mrpt-vslam/config"
SEEDS="$(words "${SEEDS:-1 2 3 4 5}")"
SINGLE_SEEDS="$(words "${SINGLE_SEEDS:-$(seq 1 15)}")"
RESULTS="${RESULTS:-$REPO_DIR/doc/results/real-data.md}"
PLOTS="${RESULTS%.md}"
FIRST_SEED="$(echo "$SEEDS" | awk '{print $1}')"
mkdir -p "$OUT/data" "$PLOTS"

# --- 1. import ----------------------------------------------------------------------------------
import() {  # import NAME ROBOTS COMMAND_DELAY [options...]
  local name="$1" robots="$2" delay="$3"; shift 3
  [ -f "$OUT/data/$name.rawlog" ] ||
    "$BIN/mrclam2rawlog" "$DATASET" --robots "$robots" --command-delay "$delay" \
      --out "$OUT/data/$name.rawlog" "$@" > "$OUT/data/$name.import.txt"
}
import r123 1,2,3 0.2 --keep-robot-measurements
import r123-ids 1,2,3 0.2 --keep-robot-measurements --keep-ids
import r1 1 0.2
import r2 2 0.2
import r3 3 0.2
import r12 1,2 0.2 --keep-robot-measurements
import r12345 1,2,3,4,5 0.2 --keep-robot-measurements

# run DIR RAWLOG ROBOTS [options...]: one multirobot-vslam run and its evaluation (robot Rn reads
# as id n; READINGS_OF_ROBOTS=no drops those readings); prints
# "est_1 odo_1 ... | once duplicated extra fused wrong total_s particle_map matched estimated
# error_mean" (the last four: the particle's own map, "-" without map_along_path, and vslam-eval's
# one-to-one matching of the output map within 0.5 m)
run() {
  local dir="$1" rawlog="$2" robots="$3"; shift 3
  local ids="${robots//R/}"
  [ "${READINGS_OF_ROBOTS:-yes}" = no ] && ids=""
  "$BIN/multirobot-vslam" "$CONFIGS/multirobot-vslam/mrclam.ini" "$rawlog" --out "$dir" --quiet \
    --set "MultiRobotVSLAM.robots=$robots" --set "MultiRobotVSLAM.robot_reading_ids=$ids" "$@"
  "$BIN/vslam-eval" "$dir" --ground-truth "${rawlog%.rawlog}" --landmark-cutoff 0.5 \
    > "$dir/summary.txt"
  local rmse
  rmse=$(awk '/^R[0-9]+ (estimate|odometry):/ {printf "%s ", $5}' "$dir/summary.txt")
  # json NAME: the number after "NAME": in run.json ("-" when absent)
  json() { grep -o "\"$1\": *[0-9.e+-]*" "$dir/run.json" | head -1 | awk '{print $2}' | grep . || echo -; }
  local mapped total
  mapped=$(json true_landmarks_mapped)
  total=$(json map_landmarks)
  echo "$rmse| $(json true_landmarks_mapped_once) $(json true_landmarks_duplicated)" \
    "$((total - mapped)) $(json fused_measurements) $(json fused_with_another_identity)" \
    "$(json total_s | awk '{printf "%.1f", $1}') $(json particle_map_landmarks)" \
    "$(sed -n 's/^landmarks: *[0-9]* true, \([0-9]*\) estimated: \([0-9]*\) matched.*error mean \([0-9.]*\) m.*/\2 \1 \3/p' \
      "$dir/summary.txt")"
}

{
echo "## 1. Import"
echo
echo "\`mrclam2rawlog --robots 1,2,3,4,5 --command-delay 0.2 --keep-robot-measurements\`: what it"
echo "kept and dropped, and the readings' residuals against Vicon (the reading minus the range and"
echo "bearing from the robot's Vicon pose, interpolated at the reading's time, to the landmark's"
echo "Vicon position; mean +- standard deviation, count), as the importer prints them:"
echo
echo '```'
sed -e 's/\. /.\n/g' -e "s#$REPO_DIR/##" "$OUT/data/r12345.import.txt"
echo '```'
echo
echo "Dead reckoning (the commands integrated from the Vicon pose at the start), whole dataset:"
echo "\`vslam-eval --estimate OUT.odometry_R<n>.tum --ground-truth OUT.groundtruth_R<n>.tum\`."
echo
echo "| robot | position RMSE [m] | max [m] | heading RMSE [deg] | RMSE after SE(2) alignment [m] |"
echo "|---|---|---|---|---|"
for n in 1 2 3 4 5; do
  "$BIN/vslam-eval" --estimate "$OUT/data/r12345.odometry_R$n.tum" \
    --ground-truth "$OUT/data/r12345.groundtruth_R$n.tum" --out "$OUT/odometry-R$n" > "$OUT/odometry-R$n.txt"
  # "estimate: ATE RMSE 3.982 m (max 7.679 m), heading RMSE 109.07 deg, ...", then "estimate
  # aligned: ATE RMSE ..."
  awk -v r="R$n" '/^estimate:/ {gsub(/[(),]/, ""); rmse = $4; max = $7; heading = $11}
    /^estimate aligned:/ {aligned = $5}
    END {printf "| %s | %s | %s | %.0f | %s |\n", r, rmse, max, heading, aligned}' "$OUT/odometry-R$n.txt"
done
echo

# the filter alone (sections 3-5): one filter, no map along the path, no smoothing (which needs
# it; the map along the path was chosen for robots 1-3 jointly)
FILTER_ALONE=(--set MultiRobotVSLAM.filter_runs=1 --set TeamPathSmoother.map_along_path=false
  --set TeamPathSmoother.smooth_paths=false)

# --- 2. robots 1-3 jointly ----------------------------------------------------------------------
# filter_rmse DIR RAWLOG: the position RMSE of each filter_path_R<n>.tum (the best particle's
# paths before smoothing)
filter_rmse() {
  local dir="$1" rawlog="$2" f
  for f in "$dir"/filter_path_R*.tum; do
    local r="${f##*filter_path_}"; r="${r%.tum}"
    "$BIN/vslam-eval" --estimate "$f" --ground-truth "${rawlog%.rawlog}.groundtruth_$r.tum" \
      --out "$dir/filter-$r" | awk '/ATE RMSE/ {printf "%s ", $4; exit}'
  done
}
echo "## 2. Robots 1-3 jointly (mrclam.ini), identities hidden"
echo
echo "The output paths (smoothed), the best particle's paths before smoothing (filter), dead"
echo "reckoning, and the maps; each seed a whole run of the shipped configuration: its independent"
echo "filters from the seed on, the one whose smoothed paths and map cost least kept (kept run: its"
echo "seed; each run's seed and cost)."
echo
echo "| seed | R1 smoothed [m] | R1 filter [m] | R1 odometry [m] | R2 smoothed [m] | R2 filter [m] | R2 odometry [m] | R3 smoothed [m] | R3 filter [m] | R3 odometry [m] | particle's map landmarks | output map landmarks | true landmarks matched one-to-one within 0.5 m (mean error) | extra | parts reanchored | fused readings | of another identity | kept run (seed: cost) | run [s] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
: > "$OUT/joint.txt"
for seed in $SEEDS; do
  echo "section 2, seed $seed" >&2
  res=$(run "$OUT/r123-seed$seed" "$OUT/data/r123-ids.rawlog" "R1 R2 R3" --seed "$seed")
  # the rawlog with ids gives the same estimate as the one without (ids are diagnostics only)
  if [ "$seed" = "$FIRST_SEED" ]; then
    run "$OUT/r123-hidden-seed$seed" "$OUT/data/r123.rawlog" "R1 R2 R3" --seed "$seed" > /dev/null
    for r in R1 R2 R3; do
      cmp -s "$OUT/r123-seed$seed/estimated_path_$r.tum" "$OUT/r123-hidden-seed$seed/estimated_path_$r.tum" ||
        { echo "ids changed the estimate of $r" >&2; exit 1; }
    done
  fi
  read -r -a v <<< "${res%%|*}"
  read -r _ _ _ fused wrong t particle matched total err <<< "${res##*|}"
  read -r -a f <<< "$(filter_rmse "$OUT/r123-seed$seed" "$OUT/data/r123-ids.rawlog")"
  reanchored=$(grep -o '"smoothing_reanchored": *[0-9]*' "$OUT/r123-seed$seed/run.json" |
    awk '{print $2}')
  kept=$(python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))
print(r["counts"]["kept_seed"], "(" + ", ".join("%d: %.0f" % (f["seed"], f["smoothing_cost"])
                                         for f in r["results"]["filter_runs"]) + ")")' \
    "$OUT/r123-seed$seed/run.json")
  echo "| $seed | ${v[0]} | ${f[0]} | ${v[1]} | ${v[2]} | ${f[1]} | ${v[3]} | ${v[4]} | ${f[2]} |" \
    "${v[5]} | $particle | $total | $matched ($err m) | $((total - matched)) | $reanchored |" \
    "$fused | $wrong | $kept | $t |"
  echo "${v[0]} ${v[2]} ${v[4]} ${f[0]} ${f[1]} ${f[2]}" >> "$OUT/joint.txt"
done
awk '{a += $1; b += $2; c += $3; d += $4; e += $5; f += $6; n++; m = $1; if ($2 > m) m = $2; if ($3 > m) m = $3; if (m <= 0.25) ok++}
  END {printf "mean over seeds, smoothed: R1 %.3f m, R2 %.3f m, R3 %.3f m (team mean %.3f m), every robot within 0.25 m on %d of %d seeds; filter: R1 %.3f m, R2 %.3f m, R3 %.3f m\n", a / n, b / n, c / n, (a + b + c) / (3 * n), ok, n, d / n, e / n, f / n}' "$OUT/joint.txt"

echo
cp "$OUT/r123-seed$FIRST_SEED/paths.png" "$PLOTS/r123-paths.png"
cp "$OUT/r123-seed$FIRST_SEED/errors.png" "$PLOTS/r123-errors.png"
echo "![Robots 1-3, seed $FIRST_SEED: smoothed paths and the output map](real-data/r123-paths.png)"
echo "![Robots 1-3, seed $FIRST_SEED: errors of the smoothed paths over time](real-data/r123-errors.png)"
echo
echo "### Each filter alone"
echo
echo "\`--set MultiRobotVSLAM.filter_runs=1\`, the rest as shipped: the run each seed gives alone,"
echo "one of the candidates above (seed s runs the filters of seeds s, s + 1, ...), and the cost"
echo "by which they are compared (run.json \`results.smoothing_cost\`)."
echo
echo "| seed | R1 smoothed [m] | R2 smoothed [m] | R3 smoothed [m] | output map landmarks | true landmarks matched one-to-one within 0.5 m (mean error) | smoothed cost |"
echo "|---|---|---|---|---|---|---|"
: > "$OUT/single.txt"
for seed in $SINGLE_SEEDS; do
  echo "section 2, filter alone, seed $seed" >&2
  dir="$OUT/r123-single-seed$seed"
  res=$(run "$dir" "$OUT/data/r123-ids.rawlog" "R1 R2 R3" --seed "$seed" \
    --set MultiRobotVSLAM.filter_runs=1)
  read -r -a v <<< "${res%%|*}"
  read -r _ _ _ _ _ _ _ matched total err <<< "${res##*|}"
  cost=$(grep -o '"smoothing_cost": *[0-9.e+-]*' "$dir/run.json" | awk '{printf "%.0f", $2}')
  echo "| $seed | ${v[0]} | ${v[2]} | ${v[4]} | $total | $matched ($err m) | $cost |"
  echo "${v[0]} ${v[2]} ${v[4]} $cost" >> "$OUT/single.txt"
done
awk '{m = $1; if ($2 > m) m = $2; if ($3 > m) m = $3
  if (m <= 0.25) {ok++; if (!lo1 || $4 < lo1) lo1 = $4; if ($4 > hi1) hi1 = $4}
  else {if (!lo2 || $4 < lo2) lo2 = $4; if ($4 > hi2) hi2 = $4}; n++}
  END {printf "every robot within 0.25 m on %d of %d seeds; smoothed cost %.0f-%.0f on those, ", ok, n, lo1, hi1
       if (n > ok) printf "%.0f-%.0f on the others\n", lo2, hi2; else printf "no other\n"}' "$OUT/single.txt"
echo

# --- 3. each robot alone, 2 and 5 robots --------------------------------------------------------
echo "## 3. The filter alone on other teams (mean over seeds $SEEDS)"
echo
echo "No map along the path and no smoothing, so that teams compare as filters; robots read each"
echo "other where both are in the team."
echo
echo "| team | robot | RMSE [m] | odometry [m] | landmarks mapped once | extra | run [s] |"
echo "|---|---|---|---|---|---|---|"
team() {  # team NAME RAWLOG ROBOTS
  local name="$1" rawlog="$2" robots="$3"
  echo "section 3, $name" >&2
  : > "$OUT/team.tmp"
  for seed in $SEEDS; do
    res=$(run "$OUT/$name-seed$seed" "$rawlog" "$robots" --seed "$seed" "${FILTER_ALONE[@]}")
    echo "$res" >> "$OUT/team.tmp"
  done
  local k=0
  for r in $robots; do
    awk -F'|' -v k="$k" -v r="$r" -v t="$name" '{split($1, v, " "); split($2, w, " "); e += v[2 * k + 1]; o += v[2 * k + 2]; once += w[1]; x += w[3]; s += w[6]; n++}
      END {printf "| %s | %s | %.3f | %.3f | %.1f | %.1f | %.1f |\n", t, r, e / n, o / n, once / n, x / n, s / n}' "$OUT/team.tmp"
    k=$((k + 1))
  done
  rm -f "$OUT/team.tmp"
}
team "R1 alone" "$OUT/data/r1.rawlog" "R1"
team "R2 alone" "$OUT/data/r2.rawlog" "R2"
team "R3 alone" "$OUT/data/r3.rawlog" "R3"
team "R1-R2" "$OUT/data/r12.rawlog" "R1 R2"
team "R1-R3" "$OUT/data/r123.rawlog" "R1 R2 R3"
team "R1-R5" "$OUT/data/r12345.rawlog" "R1 R2 R3 R4 R5"
READINGS_OF_ROBOTS=no team "R1-R3, readings of robots unused" "$OUT/data/r123.rawlog" "R1 R2 R3"

echo
# --- 4. the association policy alone: robots 1-3 with known poses -------------------------------
# R<n>_ODOM = the Vicon poses, motion noise near zero, 100 particles
import r123-known 1,2,3 0.2 --keep-robot-measurements --keep-ids --odometry-from-ground-truth
echo "## 4. Robots 1-3 with known poses (odometry = Vicon), mean over seeds $SEEDS"
echo
echo "\`mrclam2rawlog --odometry-from-ground-truth\`, motion noise near zero, M = 100, no map along"
echo "the path: what the gate D0 makes of the readings when the poses are right."
echo
echo "| D0 | R1 [m] | R2 [m] | R3 [m] | map landmarks | true landmarks matched one-to-one within 0.5 m |"
echo "|---|---|---|---|---|---|"
for d0 in 11.34 30 50; do
  for seed in $SEEDS; do
    dir="$OUT/r123-known-D0-$d0-seed$seed"
    res=$(run "$dir" "$OUT/data/r123-known.rawlog" "R1 R2 R3" --seed "$seed" \
      --set ParticleFilter.sampleSize=100 --set MotionModel.a1=0.01 --set MotionModel.a2=0.001 \
      --set MotionModel.a3=0.01 --set MotionModel.a4=0.01 --set MotionModel.minStdXY=0.0005 \
      --set MotionModel.minStdPHI_deg=0.05 \
      --set "MappingApplication_visualLandmarksMap_00_insertOpts.D0=$d0" "${FILTER_ALONE[@]}")
    # vslam-eval's one-to-one (Hungarian) matching within 0.5 m (run's --landmark-cutoff):
    # "landmarks: 15 true, N estimated: K matched"
    echo "${res%%|*} $(awk '/^landmarks:/ {print $4, $6}' "$dir/summary.txt")"
  done | awk -v d="$d0" '{a += $1; b += $3; c += $5; lm += $7; m += $8; n++}
    END {printf "| %s | %.3f | %.3f | %.3f | %.1f | %.1f |\n", d, a / n, b / n, c / n, lm / n, m / n}'
done

echo
# --- 5. the pose side alone: robots 1-3 with known correspondences -----------------------------
# associate_by_identity: each reading goes to its post's landmark (the ids of r123-ids), the rest
# as shipped: how well the filter localizes when the association is right (doc/real-data.md)
echo "## 5. Robots 1-3 with known correspondences (associate_by_identity = true)"
echo
echo "Every reading goes to its own post's landmark (the ids of the import with ids kept), the"
echo "rest as shipped, no map along the path: how well the filter localizes when the association"
echo "is right."
echo
echo "| seed | R1 [m] | R2 [m] | R3 [m] | map landmarks | true landmarks matched one-to-one within 0.5 m | run [s] |"
echo "|---|---|---|---|---|---|---|"
for seed in $SEEDS; do
  dir="$OUT/r123-identity-seed$seed"
  res=$(run "$dir" "$OUT/data/r123-ids.rawlog" "R1 R2 R3" --seed "$seed" \
    --set MappingApplication_visualLandmarksMap_00_insertOpts.associate_by_identity=true \
    "${FILTER_ALONE[@]}")
  read -r -a v <<< "${res%%|*}"
  read -r -a w <<< "${res##*|}"
  echo "| $seed | ${v[0]} | ${v[2]} | ${v[4]} | $(awk '/^landmarks:/ {print $4 " | " $6}' \
    "$dir/summary.txt") | ${w[5]} |"
done

echo
# --- 6. one robot from the template (range-bearing.ini) ------------------------------------------
# as a user imports one robot (no command delay, the importer's default noise) and runs the
# template; once more with the Vicon poses as odometry, to tell the readings from the odometry
for n in 1 2 3; do
  import "single-r$n" "$n" 0
  import "single-known-r$n" "$n" 0 --odometry-from-ground-truth
done
echo "## 6. One robot from the template (range-bearing.ini)"
echo
echo "\`mrclam2rawlog DATASET --robots N --out rN.rawlog\` (no command delay, the importer's noise:"
echo "0.20 m, 3.5 deg), then \`multirobot-vslam range-bearing.ini rN.rawlog --set"
echo "MultiRobotVSLAM.robots=RN\`, the template as shipped; odometry \"Vicon\": the same import with"
echo "\`--odometry-from-ground-truth\`. RMSE of the estimate, after SE(2) alignment, and of the"
echo "odometry; output map landmarks matched one-to-one within 0.5 m; and the check of the sensor's"
echo "pose (doc/multirobot.md, \"Checking the sensor poses\"): the move and turn of the camera and the"
echo "scale of its readings found (σ), and whether the run warned. The camera is at the robot's"
echo "centre (section 1: the readings against Vicon)."
echo
echo "| robot | odometry | seed | RMSE [m] | aligned [m] | odometry [m] | landmarks (matched) | move found [m] | turn found [deg] | range scale | warned |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for n in 1 2 3; do
  for variant in odometry Vicon; do
    rawlog="$OUT/data/single-r$n.rawlog"
    [ "$variant" = Vicon ] && rawlog="$OUT/data/single-known-r$n.rawlog"
    for seed in $SEEDS; do
      echo "section 6, R$n, $variant, seed $seed" >&2
      dir="$OUT/single-$variant-r$n-seed$seed"
      "$BIN/multirobot-vslam" "$CONFIGS/multirobot-vslam/range-bearing.ini" "$rawlog" --out "$dir" \
        --quiet --seed "$seed" --set "MultiRobotVSLAM.robots=R$n"
      "$BIN/vslam-eval" "$dir" --ground-truth "${rawlog%.rawlog}" --landmark-cutoff 0.5 \
        > "$dir/summary.txt"
      python3 - "$dir" "R$n" "$variant" "$seed" <<'PY'
import json, re, sys
d, robot, variant, seed = sys.argv[1:]
s = open(d + "/summary.txt").read()
ate = lambda what: re.search(robot + " " + what + r": +ATE RMSE ([0-9.]+)", s).group(1)
lm = re.search(r"landmarks: +\d+ true, (\d+) estimated: (\d+) matched", s)
run = json.load(open(d + "/run.json"))
sensor, c = next(iter(run["results"]["sensor_pose_check"].items()))
scale = ("%.2f (%.2f)" % (c["range_scale"], c["std_range_scale"])
         if c["range_scale"] is not None else "—")
print("| %s | %s | %s | %s | %s | %s | %s (%s) | %+.2f, %+.2f (%.2f, %.2f) | %+.1f (%.1f) | %s | %s |" % (
    robot, variant, seed, ate("estimate"), ate("estimate aligned"), ate("odometry"), lm.group(1),
    lm.group(2), *c["dx_dy_m"], *c["std_dx_dy_m"], c["dyaw_deg"], c["std_dyaw_deg"], scale,
    "yes" if any(w.startswith(sensor + ":") for w in run.get("warnings", [])) else "no"))
PY
    done
  done
done

} > "$RESULTS.body"
{
  results_header "Real data: UTIAS MRCLAM dataset 7" "$COMMAND"
  cat "$RESULTS.body"
} > "$RESULTS.tmp"
rm "$RESULTS.body"
mv "$RESULTS.tmp" "$RESULTS"
echo "wrote $RESULTS and its plots in $PLOTS; run folders in $OUT"
