#!/usr/bin/env bash
# Peer comparison on range-bearing data made by MRPT's own tools (doc/results/range-bearing.md):
#   1. stock simul-landmarks (share/mrpt-vslam/config/peer-comparison/simul-landmarks-noise-*.ini)
#      writes one robot's rawlog (action / sensory-frame pairs: CActionRobotMovement2D +
#      CObservationBearingRange) per noise level (low, medium, high range and bearing std) with
#      landmark IDs kept and hidden (ID -1): 300 steps on a 7.2 m square, 40 landmarks, one world
#      per simulation seed;
#      its ground truth becomes NAME.groundtruth.tum and NAME.landmarks.txt beside NAME.rawlog
#      (scripts/simul-landmarks-ground-truth.sh);
#   2. stock kf-slam (EKF, CRangeBearingKFSLAM2D, kf-slam-2d.ini with the rawlog's sensor noise;
#      readings with an ID are associated by it, the others to the nearest landmark within a
#      Mahalanobis gate) on each rawlog, timed; its printed poses and final 3D scene become a run
#      folder (estimated_path.tum, map.txt); where it diverges (NaN poses), diverged.txt instead;
#   3. multirobot-vslam (multirobot-vslam/range-bearing.ini) on each rawlog, per seed, timed;
#   4. with IDs hidden, how well each tool's path and the true one fit the rawlog's odometry and
#      readings (their chi-square, scripts/range-bearing-path-fit.py), and the most probable path
#      given them and the true associations, a run folder evaluated as the tools' are;
#   5. vslam-eval on every run folder, and the table of both to doc/results/range-bearing.md (or
#      $RESULTS): position RMSE (unaligned and SE(2)-aligned), landmarks mapped vs true, landmark
#      error mean (one-to-one matching within vslam-eval's 1.5 m), run time (wall clock of the
#      process), and the turn of each path's best alignment to the truth; the figures of both
#      tools' RMSE per rawlog beside it (doc/results/range-bearing/).
# Writes rawlogs, run folders (metrics.json, paths.png, ...) and logs under
# out/reproduce-range-bearing/ (or $OUT). Builds first (scripts/setup.sh). Takes about 9 min
# (120 rawlogs; each tool about a second or less per rawlog at the default SEEDS).
# Environment: OUT, SIM_SEEDS (simulation seeds, default 1 to 20: one rawlog per noise level,
# IDs kept or hidden and seed; twenty worlds, because which tool is the more accurate on a
# single world changes from one world to the next), SEEDS (multirobot-vslam seeds, default 1;
# several: the table has their mean),
# NOISE_LEVELS (default "low medium high"), TOOLS (default "kf-slam multirobot-vslam"), RESULTS.
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"
# after the build: the results header times the runs only
source "$REPO_DIR/scripts/results-header.sh"
COMMAND="$(results_command scripts/reproduce-range-bearing.sh OUT SIM_SEEDS SEEDS NOISE_LEVELS TOOLS RESULTS)"

OUT="${OUT:-$REPO_DIR/out/reproduce-range-bearing}"
BIN="$BUILD_DIR/bin"
CONFIGS="$REPO_DIR/share/mrpt-vslam/config"
PEER="$CONFIGS/peer-comparison"
MRV_CONFIG="$CONFIGS/multirobot-vslam/range-bearing.ini"
SEEDS="$(words "${SEEDS:-1}")"
SIM_SEEDS="$(words "${SIM_SEEDS:-$(seq 1 20)}")"
NOISE_LEVELS="$(words "${NOISE_LEVELS:-low medium high}")"
TOOLS="$(words "${TOOLS:-kf-slam multirobot-vslam}")"
RESULTS="${RESULTS:-$REPO_DIR/doc/results/range-bearing.md}"
PLOTS="${RESULTS%.md}"
OUT="$(mkdir -p "$OUT" && cd "$OUT" && pwd)"
DATA="$OUT/data"
mkdir -p "$DATA"

# ini_value FILE KEY: the value of KEY (first occurrence, comments and spaces stripped)
ini_value() {
  awk -v k="$2" -F= '$1 ~ "^[ \t]*" k "[ \t]*$" { v = $2; sub(/\/\/.*/, "", v); gsub(/^[ \t]+|[ \t]+$/, "", v)
    print v; exit }' "$1"
}

# --- 1. simulate: NAME.rawlog, NAME.groundtruth.tum, NAME.landmarks.txt, NAME.stamps.txt and ----
# NAME.readings.txt (rawlog-edit's list of the readings, for section 4)
# The rawlog is CSensoryFrame, CActionCollection, CSensoryFrame, ... (simul-landmarks writes each
# step's reading before the step's motion). Readers of pairs (kf-slam's
# CRawlog::readActionObservationPair, rawlog-edit) skip the first frame and pair the motion of
# step k with the reading of step k + 1: nSteps - 1 steps, the robot's true pose at reading k + 1
# being row k + 1 of NAME.rawlog_ground_truth_robot_path.txt (x y z yaw pitch roll, one row per
# reading). multirobot-vslam also takes the first frame, taken before any motion, as a step
# standing at the start (doc/app-conventions.md). simul-landmarks 2.5.8 stamps the readings with
# the clock at simulation time (a few microseconds apart): the ground truth has rawlog-edit's list
# of them from the second reading on (6 decimals, as our TUM files), NAME.stamps.txt holds them
# for kf-slam's path, and the estimates use them too. Both tools are scored on those readings
# only: they are at least 10 µs apart, the first reading about 0.2 ms before the second, and the
# estimates carry the stamps to the microsecond, so a time tolerance of 5 µs pairs equal stamps
# and nothing else.
EVAL_TIME_TOLERANCE=0.000005
simulate() {  # simulate NAME NOISE IDS(true|false) SIM_SEED
  local name="$1" noise="$2" ids="$3" sim_seed="$4"
  "$REPO_DIR/scripts/simul-landmarks-rawlog.sh" "$PEER/simul-landmarks-noise-$noise.ini" \
    "$DATA/$name.rawlog" sensorDetectsIDs="$ids" random_seed="$sim_seed"
  rawlog-edit -i "$DATA/$name.rawlog" --list-range-bearing \
    --text-file-output "$DATA/$name.readings.txt" -q > "$DATA/$name.rawlog-edit.log" 2>&1 ||
    { echo "rawlog-edit could not list the readings of $DATA/$name.rawlog:" >&2
      tail -5 "$DATA/$name.rawlog-edit.log" >&2; exit 1; }
  awk '!/^#/ { print $1 }' "$DATA/$name.groundtruth.tum" > "$DATA/$name.stamps.txt"
  local steps expected
  steps=$(wc -l < "$DATA/$name.stamps.txt")
  expected=$(( $(ini_value "$DATA/$name.simul-landmarks.ini" nSteps) - 1 ))
  [ "$steps" = "$expected" ] || { echo "$name: $steps readings stamped, expected $expected" >&2; exit 1; }
}

# estimate_value DIR KEY...: a value of the one robot's "estimate" block of DIR/metrics.json
# (kf-slam's run folder has one robot, multirobot-vslam's robot R1), "-" without metrics.json
estimate_value() {
  [ -f "$1/metrics.json" ] || { echo -; return; }
  python3 -c 'import json, sys
m = json.load(open(sys.argv[1]))
v = m["estimate"] if "estimate" in m else m["robots"]["R1"]["estimate"]
for key in sys.argv[2:]:
    v = v[key]
print(v)' "$1/metrics.json" "${@:2}"
}

# evaluate DIR NAME [ARGS]: vslam-eval's summary of run folder DIR against NAME's ground truth,
# checking that every pose of the ground truth was scored
evaluate() {
  local dir="$1" name="$2"; shift 2
  "$BIN/vslam-eval" "$dir" --time-tolerance "$EVAL_TIME_TOLERANCE" "$@" > "$dir/summary.txt"
  local scored expected
  scored=$(estimate_value "$dir" matched_poses)
  expected=$(grep -vc '^#' "$DATA/$name.groundtruth.tum")
  [ "$scored" = "$expected" ] || {
    echo "$dir: $scored poses scored, the ground truth has $expected" >&2; exit 1; }
}

# --- 2. kf-slam --------------------------------------------------------------------------------
# map.txt from kf-slam's last kf_state_N.3Dscene (gzip-compressed MRPT serialization): one
# CEllipsoid2D per landmark, named by its index in the state vector, the robot's unnamed; each
# starts with the CRenderizable header (0xFF, flags, u16 name length, name, RGBA, then the pose as
# 6 little-endian float32: x y z yaw pitch roll). The covariances come from full_cov_N.txt (the
# full state covariance, landmark i at rows 3 + 2i, 4 + 2i).
SCENE_TO_MAP='
use strict; use warnings;
my ($scene, $cov) = @ARGV;
open(my $fh, "-|", "gzip", "-dc", $scene) or die "$scene: $!\n";
binmode $fh; my $d = do { local $/; <$fh> }; close $fh or die "$scene: cannot decompress\n";
my $tag = "\x9amrpt::opengl::CEllipsoid2D";
my @lm; my $pos = 0;
while (($pos = index($d, $tag, $pos)) >= 0) {
  my $p = $pos + length($tag); $pos = $p;
  my ($ver, $magic, $flags, $nlen) = unpack("C C C v", substr($d, $p, 5));
  die "$scene: unexpected CRenderizable header at byte $p\n" unless $magic == 0xFF && ($flags & 0x80);
  $p += 5; my $name = substr($d, $p, $nlen); $p += $nlen + 4;
  my ($x, $y) = unpack("f< f<", substr($d, $p, 8));
  next if $name eq "";
  die "$scene: landmark ellipse \"$name\" out of order\n" unless $name eq scalar(@lm);
  push @lm, [$x, $y];
}
open(my $ch, "<", $cov) or die "$cov: $!\n";
my @C = map { [split] } grep { /\S/ && !/^%/ } <$ch>;
die sprintf("%s: %d rows, expected 3 + 2 x %d landmarks\n", $cov, scalar(@C), scalar(@lm))
  unless @C == 3 + 2 * @lm;
print "# id x y z cxx cxy cxz cyy cyz czz\n";
for my $i (0 .. $#lm) {
  my $k = 3 + 2 * $i;
  printf "%d %.6f %.6f 0 %.9g %.9g 0 %.9g 0 0\n", $i, @{$lm[$i]}, $C[$k][$k], $C[$k][$k + 1],
    $C[$k + 1][$k + 1];
}'

run_kf_slam() {  # run_kf_slam NAME NOISE
  local name="$1" noise="$2"
  local dir="$OUT/kf-slam/$name" sim="$PEER/simul-landmarks-noise-$noise.ini"
  local steps=$(( $(ini_value "$sim" nSteps) - 1 ))
  mkdir -p "$dir"
  rm -f "$dir"/*.tum "$dir/map.txt" "$dir/metrics.json" "$dir/summary.txt" "$dir/diverged.txt"
  "$REPO_DIR/scripts/ini-set.sh" "$PEER/kf-slam-2d.ini" "$dir/kf-slam.ini" logOutput_dir="$dir/kf-slam-out" \
    SAVE_LOG_FREQUENCY=$(( steps - 1 )) std_sensor_range="$(ini_value "$sim" stdRange)" \
    std_sensor_yaw_deg="$(ini_value "$sim" stdYaw_deg)"
  local t0=$EPOCHREALTIME
  kf-slam "$dir/kf-slam.ini" "$DATA/$name.rawlog" < /dev/null > "$dir/kf-slam.log" 2>&1
  local t1=$EPOCHREALTIME
  grep -q 'KF-SLAM finished' "$dir/kf-slam.log" ||
    { echo "kf-slam did not finish on $name:" >&2; tail -5 "$dir/kf-slam.log" >&2; exit 1; }
  # estimated path: the "Mean pose: (x,y,phideg)" line printed after each step (1 mm, 0.01 deg),
  # step k at the stamp of reading k + 1
  grep -o 'Mean pose: ([^)]*)' "$dir/kf-slam.log" |
    sed 's/^Mean pose: (\([^,]*\),\([^,]*\),\(.*\)deg)$/\1 \2 \3/' |
    awk 'NR == FNR { t[++n] = $1; next }
         { a = $3 * 3.14159265358979 / 360
           printf "%s %s %s 0 0 0 %.9f %.9f\n", t[++k], $1, $2, sin(a), cos(a) }
         END { if (k != n) { print "kf-slam printed " k " poses for " n " steps" > "/dev/stderr"; exit 1 } }' \
      "$DATA/$name.stamps.txt" - | { echo "# timestamp x y z qx qy qz qw"; cat; } \
      > "$dir/estimated_path.tum"
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f\n", b - a }' > "$dir/wall_s.txt"
  printf '{"app": "kf-slam", "config": "%s", "rawlog": "%s", "ground_truth": "%s"}\n' \
    "$dir/kf-slam.ini" "$DATA/$name.rawlog" "$DATA/$name.rawlog" > "$dir/run.json"
  # a filter that diverged prints NaN poses from then on: diverged.txt holds the first such
  # step, and there is nothing to evaluate
  local diverged
  diverged=$(awk 'NR > 1 && tolower($0) ~ /nan/ { print NR - 2; exit }' "$dir/estimated_path.tum")
  if [ -n "$diverged" ]; then
    echo "$diverged" > "$dir/diverged.txt"
    echo "kf-slam diverged on $name: NaN poses from step $diverged" >&2
    return
  fi
  local last
  last=$(printf '%05d' $(( steps - 1 )))
  perl -e "$SCENE_TO_MAP" "$dir/kf-slam-out/kf_state_$last.3Dscene" \
    "$dir/kf-slam-out/full_cov_$last.txt" > "$dir/map.txt"
  evaluate "$dir" "$name" --ground-truth "$DATA/$name.rawlog"
}

# --- 3. multirobot-vslam -----------------------------------------------------------------------
run_multirobot_vslam() {  # run_multirobot_vslam NAME SEED
  local name="$1" seed="$2"
  local dir="$OUT/multirobot-vslam/$name-seed$seed"
  local t0=$EPOCHREALTIME
  "$BIN/multirobot-vslam" "$MRV_CONFIG" "$DATA/$name.rawlog" \
    --seed "$seed" --out "$dir" --quiet
  local t1=$EPOCHREALTIME
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f\n", b - a }' > "$dir/wall_s.txt"
  evaluate "$dir" "$name"
}

# --- 4. fit to the data -------------------------------------------------------------------------
# path_fit NAME NOISE: "truth kf-slam multirobot-vslam most-probable values", the chi-square of
# the true path, kf-slam's, multirobot-vslam's (the mean over its seeds) and the most probable
# path's given the odometry and readings of hidden-ID rawlog NAME (scripts/range-bearing-path-fit.py;
# each reading's landmark from its IDs-kept twin), and the number of measured values; "- - - - -"
# where kf-slam diverged. The odometry is that of multirobot-vslam's first run folder (the
# rawlog's increments, composed). The most probable path (started from the true one, its first
# pose held at the truth's) becomes run folder OUT/most-probable/NAME, evaluated as the tools' are.
path_fit() {
  local name="$1" noise="$2"
  local sim="$PEER/simul-landmarks-noise-$noise.ini" kf="$OUT/kf-slam/$name" fit
  [ -f "$kf/diverged.txt" ] && { echo "- - - - -"; return; }
  local dirs mp="$OUT/most-probable/$name"
  mapfile -t dirs < <(mrv_dirs "$name")
  mkdir -p "$mp"
  rm -f "$mp/metrics.json" "$mp/summary.txt"
  fit="$("$REPO_DIR/scripts/range-bearing-path-fit.py" --readings "$DATA/$name.readings.txt" \
    --most-probable "$mp/estimated_path.tum" \
    --ids-from "$DATA/${name/-ids-hidden-/-ids-kept-}.readings.txt" \
    --stamps "$DATA/$name.stamps.txt" --landmarks "$DATA/$name.landmarks.txt" \
    --odometry "${dirs[0]}/odometry_path_R1.tum" \
    --std-range "$(ini_value "$sim" stdRange)" --std-bearing-deg "$(ini_value "$sim" stdYaw_deg)" \
    --odometry-std-xy "$(ini_value "$sim" odometryNoiseXY_std)" \
    --odometry-std-phi-deg "$(ini_value "$sim" odometryNoisePhi_std_deg)" \
    --sensor-pose "$(ini_value "$sim" sensorPose_x)" "$(ini_value "$sim" sensorPose_y)" \
      "$(ini_value "$sim" sensorPose_yaw_deg)" \
    "$DATA/$name.groundtruth.tum" "$kf/estimated_path.tum" \
    "${dirs[@]/%//estimated_path_R1.tum}")"
  printf '{"app": "range-bearing-path-fit", "rawlog": "%s", "ground_truth": "%s"}\n' \
    "$DATA/$name.rawlog" "$DATA/$name.rawlog" > "$mp/run.json"
  evaluate "$mp" "$name" --ground-truth "$DATA/$name.rawlog"
  awk '{ c[NR] = $2; n = $5 } END { for (i = 3; i < NR; i++) m += c[i]
    printf "%.1f %.1f %.1f %.1f %d\n", c[1], c[2], m / (NR - 3), c[NR], n }' <<< "$fit"
}

# --- 5. table ----------------------------------------------------------------------------------
# metrics DIR: "rmse aligned_rmse estimated true matched error_mean" from vslam-eval's summary
# ("-" if absent)
metrics() {
  local s="$1/summary.txt" rmse="-" aligned="-" lm="- - - -"
  if [ -f "$s" ]; then
    rmse=$(sed -n 's/.*estimate: *ATE RMSE \([0-9.]*\) m.*/\1/p' "$s" | head -1)
    aligned=$(sed -n 's/.*estimate aligned: *ATE RMSE \([0-9.]*\) m.*/\1/p' "$s" | head -1)
    lm=$(sed -n 's/^landmarks: *\([0-9]*\) true, \([0-9]*\) estimated: \([0-9]*\) matched.*error mean \([0-9.]*\) m.*/\2 \1 \3 \4/p' "$s")
  fi
  echo "${rmse:--} ${aligned:--} ${lm:-- - - -}"
}

# mrv_dirs NAME: multirobot-vslam's run folders of rawlog NAME, one per seed
mrv_dirs() {
  local seed
  for seed in $SEEDS; do echo "$OUT/multirobot-vslam/$1-seed$seed"; done
}

# mrv_cells NAME: cells of multirobot-vslam's run folders on rawlog NAME
mrv_cells() {
  local dirs
  mapfile -t dirs < <(mrv_dirs "$1")
  cells "${dirs[@]}"
}

# cells DIR...: " RMSE | aligned RMSE | landmarks | error | time |" of one tool (mean over the run
# folders when several; "-" where a run has no number)
cells() {
  local d
  for d in "$@"; do
    echo "$(metrics "$d") $(cat "$d/wall_s.txt" 2>/dev/null || echo -)"
  done | awk '{ for (i = 1; i <= 7; i++) if ($i != "-") { s[i] += $i; c[i]++ } }
    END { for (i = 1; i <= 7; i++) v[i] = (NR > 0 && c[i] == NR) ? s[i] / NR : "-"
          lm = v[3] == "-" ? "-" : sprintf("%.4g / %d (%.4g matched)", v[3], v[4], v[5])
          printf " %s | %s | %s | %s | %s |", v[1] == "-" ? "-" : sprintf("%.3f", v[1]),
            v[2] == "-" ? "-" : sprintf("%.3f", v[2]), lm,
            v[6] == "-" ? "-" : sprintf("%.3f", v[6]), v[7] == "-" ? "-" : sprintf("%.2f", v[7]) }'
}

# kf_cells NAME: cells() of kf-slam's run on rawlog NAME, or, where it diverged, the step its
# poses became NaN in the RMSE cell
kf_cells() {
  local d="$OUT/kf-slam/$1"
  if [ -f "$d/diverged.txt" ]; then
    echo " diverged: NaN from step $(cat "$d/diverged.txt") | - | - | - | $(cat "$d/wall_s.txt") |"
  else
    cells "$d"
  fi
}

# mrv_figures NAME: "rmse aligned_rmse error_mean" of multirobot-vslam on rawlog NAME, as its
# table cells show them (mean over the seeds, rounded)
mrv_figures() {
  mrv_cells "$1" | tr -d '|' | awk '{ print $1, $2, $8 }'
}

# both_tools: whether TOOLS runs kf-slam and multirobot-vslam (the comparisons need both)
both_tools() { [[ " $TOOLS " == *" kf-slam "* && " $TOOLS " == *" multirobot-vslam "* ]]; }

# figure_label KIND: what a figure of KIND (rmse, aligned-rmse) shows
figure_label() {
  if [ "$1" = aligned-rmse ]; then echo "aligned position RMSE"; else echo "position RMSE"; fi
}

# awk function mm(v): v [m] in whole millimetres, the resolution the tables compare tools at
MM_AWK='function mm(v) { return int(v * 1000 + 0.5) }'

# --- run -----------------------------------------------------------------------------------------
NAMES=()
for noise in $NOISE_LEVELS; do
  for ids in kept hidden; do
    for sim in $SIM_SEEDS; do
      name="range-bearing-ids-$ids-noise-$noise-sim$sim"
      NAMES+=("$name:$noise:$ids:$sim")
      simulate "$name" "$noise" "$([ "$ids" = kept ] && echo true || echo false)" "$sim"
    done
  done
done

for entry in "${NAMES[@]}"; do
  IFS=: read -r name noise ids sim <<< "$entry"
  for tool in $TOOLS; do
    case "$tool" in
      kf-slam) run_kf_slam "$name" "$noise" ;;
      multirobot-vslam) for seed in $SEEDS; do run_multirobot_vslam "$name" "$seed"; done ;;
      *) echo "TOOLS: unknown tool $tool" >&2; exit 2 ;;
    esac
  done
done

if both_tools; then
  mkdir -p "$OUT/path-fit"
  for entry in "${NAMES[@]}"; do
    IFS=: read -r name noise ids sim <<< "$entry"
    if [ "$ids" = hidden ]; then path_fit "$name" "$noise" > "$OUT/path-fit/$name.txt"; fi
  done
fi

mkdir -p "$(dirname "$RESULTS")"
# figures: per IDs setting, kf-slam's RMSE (unaligned and aligned) against multirobot-vslam's, a
# series per noise level, one point per rawlog where kf-slam finished
if both_tools; then
  mkdir -p "$PLOTS"
  for ids in hidden kept; do
    for noise in $NOISE_LEVELS; do
      for sim in $SIM_SEEDS; do
        name="range-bearing-ids-$ids-noise-$noise-sim$sim"
        echo "$noise $(metrics "$OUT/kf-slam/$name" | cut -d' ' -f1,2) $(mrv_figures "$name" | cut -d' ' -f1,2)"
      done
    done | awk -v rmse="$OUT/rmse-ids-$ids.txt" -v aligned="$OUT/aligned-rmse-ids-$ids.txt" '
      BEGIN { printf "" > rmse; printf "" > aligned }
      $2 != "-" && $4 != "-" { print $1, $2, $4 > rmse }
      $3 != "-" && $5 != "-" { print $1, $3, $5 > aligned }'
    for kind in rmse aligned-rmse; do
      "$BIN/vslam-plot" "$OUT/$kind-ids-$ids.txt" "$PLOTS/$kind-ids-$ids.png" --points \
        --diagonal --log-x --log-y --title "IDs $ids: $(figure_label $kind) per rawlog, by noise level" \
        --x-label "kf-slam [m]" --y-label "multirobot-vslam [m]"
    done
  done
fi
{
  results_header "Range-bearing peer comparison: stock kf-slam and multirobot-vslam" "$COMMAND"
  echo "Tools run: $TOOLS (stock kf-slam of mrpt-apps" \
    "$(dpkg-query -W -f='${Version}' mrpt-apps 2>/dev/null || echo '?')); multirobot-vslam with" \
    "${MRV_CONFIG#"$REPO_DIR"/} (filter_runs = $(ini_value "$MRV_CONFIG" filter_runs): that many" \
    "filters from each seed on, the one whose smoothed solution costs least kept), seeds: $SEEDS."
  echo
  first="$PEER/simul-landmarks-noise-${NOISE_LEVELS%% *}.ini"
  echo "Data: stock simul-landmarks (share/mrpt-vslam/config/peer-comparison/), one robot," \
    "$(ini_value "$first" nSteps) readings on a" \
    "square path with $(awk -v n="$(ini_value "$first" squarePathLength)" 'BEGIN { print (n - 4) * 0.2 }') m" \
    "sides (0.2 m per step, 4 steps per 90° turn)," \
    "$(ini_value "$first" nLandmarks) landmarks, range ≤ $(ini_value "$first" maxSensorDistance) m," \
    "$(ini_value "$first" fieldOfView_deg)° field of view, odometry noise" \
    "$(ini_value "$first" odometryNoiseXY_std) m and $(ini_value "$first" odometryNoisePhi_std_deg)° per" \
    "step, simulation seeds $SIM_SEEDS (each its own landmarks, odometry and reading noise)." \
    "kf-slam filters the last $(( $(ini_value "$first" nSteps) - 1 )) readings: like MRPT's readers" \
    "of action / frame pairs, it passes over the first, read before any motion; multirobot-vslam" \
    "filters all $(ini_value "$first" nSteps), the first as a step standing at the start. Both are" \
    "scored on the last $(( $(ini_value "$first" nSteps) - 1 )). IDs kept: every reading carries its" \
    "landmark's ID; hidden: ID −1, so each tool associates by itself (kf-slam: nearest neighbour" \
    "within a $(ini_value "$PEER/kf-slam-2d.ini" data_assoc_IC_chi2_thres) Mahalanobis gate," \
    "kf-slam-2d.ini says why). Position RMSE: vslam-eval's ATE, unaligned, and after the SE(2)" \
    "alignment to the truth that fits best (both tools start at the true pose, yet both paths" \
    "come out turned by about the same angle: the aligned figure compares their shapes). Landmarks:" \
    "mapped /" \
    "true (matched one-to-one within 1.5 m); error: mean over the matched ones. Time: wall" \
    "clock of the tool's process (reading, filtering, writing)."
  if both_tools; then
    echo
    echo "## Over the simulation seeds"
    echo
    echo "Means over the simulation seeds ($SIM_SEEDS) where kf-slam finished, and on how many" \
      "rawlogs multirobot-vslam's figure is at most kf-slam's (the RMSE to the millimetre; where" \
      "kf-slam diverged, multirobot-vslam's figure counts as at most kf-slam's). Largest excess:" \
      "the most by which multirobot-vslam's RMSE exceeds kf-slam's on one rawlog (none: on no" \
      "rawlog)."
    echo
    echo "| IDs | noise | kf-slam diverged | kf-slam RMSE [m] | multirobot-vslam RMSE [m] | RMSE ≤ kf-slam's | largest excess [m] | kf-slam aligned RMSE [m] | multirobot-vslam aligned RMSE [m] | aligned RMSE ≤ kf-slam's | kf-slam landmark error [m] | multirobot-vslam landmark error [m] | landmark error ≤ kf-slam's |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    for noise in $NOISE_LEVELS; do
      for ids in kept hidden; do
        for sim in $SIM_SEEDS; do
          name="range-bearing-ids-$ids-noise-$noise-sim$sim"
          echo "$(metrics "$OUT/kf-slam/$name") $(mrv_figures "$name")"
        done | awk -v ids="$ids" -v noise="$noise" "$MM_AWK"'
          # kf-slam: rmse aligned est true matched error ("-": diverged); multirobot-vslam: rmse
          # aligned error
          { n++; have = $7 != "-" && $8 != "-" && $9 != "-" }
          $1 == "-" { dv++; wr += have; wa += have; we += have; next }
          { m++; kr += $1; ka += $2; ke += $6; mr += $7; ma += $8; me += $9
            if (have) { wr += mm($7) <= mm($1); wa += mm($8) <= mm($2); we += mm($9) <= mm($6)
                        if (mm($7) - mm($1) > ex) ex = mm($7) - mm($1) } }
          function mean(v) { return m ? sprintf("%.3f", v / m) : "-" }
          END { printf "| %s | %s | %d of %d | %s | %s | %d of %d | %s | %s | %s | %d of %d | %s | %s | %d of %d |\n",
                  ids, noise, dv, n, mean(kr), mean(mr), wr, n,
                  (ex > 0 ? sprintf("%.3f", ex / 1000) : "none"), mean(ka), mean(ma), wa, n,
                  mean(ke), mean(me), we, n }'
      done
    done
    echo
    for ids in hidden kept; do
      for kind in rmse aligned-rmse; do
        echo "![IDs $ids: $(figure_label $kind) per rawlog]($(basename "$PLOTS")/$kind-ids-$ids.png)"
      done
    done
    echo
    echo "Each point is one rawlog (kf-slam's figure across, multirobot-vslam's up; logarithmic" \
      "axes): below the dashed line y = x, multirobot-vslam's is the smaller."
    echo
    echo "## What one rawlog says"
    echo
    echo "Given every reading's landmark (IDs kept), a tool can only associate better; yet on a" \
      "single rawlog its position RMSE can come out above that of kf-slam without the IDs: how" \
      "far a whole path turns (the last table) depends on the data's draws more than on the tool." \
      "Counted to the millimetre, per noise level, on the worlds where kf-slam finished with and" \
      "without the IDs:"
    echo
    echo "| noise | worlds | kf-slam with IDs above kf-slam without | multirobot-vslam with IDs above kf-slam without | multirobot-vslam without IDs above kf-slam without |"
    echo "|---|---|---|---|---|"
    for noise in $NOISE_LEVELS; do
      for sim in $SIM_SEEDS; do
        kept="range-bearing-ids-kept-noise-$noise-sim$sim"
        hidden="range-bearing-ids-hidden-noise-$noise-sim$sim"
        echo "$(metrics "$OUT/kf-slam/$kept" | cut -d' ' -f1) $(metrics "$OUT/kf-slam/$hidden" | cut -d' ' -f1)" \
          "$(mrv_figures "$kept" | cut -d' ' -f1) $(mrv_figures "$hidden" | cut -d' ' -f1)"
      done | awk -v noise="$noise" "$MM_AWK"'
        # RMSE of kf-slam kept, kf-slam hidden, multirobot-vslam kept, multirobot-vslam hidden
        $1 == "-" || $2 == "-" || $3 == "-" || $4 == "-" { next }
        { n++; kk += mm($1) > mm($2); mk += mm($3) > mm($2); mh += mm($4) > mm($2) }
        END { printf "| %s | %d | %d | %d | %d |\n", noise, n, kk, mk, mh }'
    done
    echo
    echo "## Which path the data favour"
    echo
    echo "Nearer the truth is not the same as a better fit to the data. The χ² of a path is what it" \
      "leaves unexplained of the rawlog: the odometry of every step that moves (x, y and heading" \
      "increments, at the simulation's odometry std) and every reading (range and bearing, at the" \
      "sensor std), each landmark placed where it fits that path's readings best, on the scored" \
      "readings (scripts/range-bearing-path-fit.py). With IDs hidden, neither tool knows which" \
      "landmark a reading is of; the χ² takes it from the same reading of the IDs-kept twin, so" \
      "both paths are scored with the true association. The true path's χ² is about the number" \
      "of measured values; a path fitted to the data has less (kf-slam prints its poses to the" \
      "millimetre and 0.01°: rounding a path so changes its χ² by a few units). IDs hidden, per" \
      "noise level, on the rawlogs where kf-slam finished:"
    echo
    echo "| noise | rawlogs | measured values (mean) | χ² of the true path (mean) | multirobot-vslam's χ² < kf-slam's | multirobot-vslam's χ² < the true path's | kf-slam's RMSE < multirobot-vslam's | of those, multirobot-vslam's χ² < kf-slam's | smallest χ² margin there |"
    echo "|---|---|---|---|---|---|---|---|---|"
    fits=""
    for noise in $NOISE_LEVELS; do
      for sim in $SIM_SEEDS; do
        name="range-bearing-ids-hidden-noise-$noise-sim$sim"
        fits+="$name $noise $(metrics "$OUT/kf-slam/$name" | cut -d' ' -f1)"
        fits+=" $(mrv_figures "$name" | cut -d' ' -f1)"
        fits+=" $(metrics "$OUT/most-probable/$name" | cut -d' ' -f1) $(cat "$OUT/path-fit/$name.txt")"$'\n'
      done
    done
    # rawlog, noise, RMSE of kf-slam, multirobot-vslam and the most probable path, chi-square of
    # the true path, kf-slam, multirobot-vslam and the most probable path, measured values
    fits="$(awk "$MM_AWK"'$3 != "-" && $4 != "-" && $6 != "-" { print $0, mm($3) < mm($4) ? "closer" : "-" }' \
      <<< "$fits")"
    for noise in $NOISE_LEVELS; do
      awk -v noise="$noise" '$2 == noise { n++; v += $10; t += $6; mt += $8 < $7; mu += $8 < $6
          if ($11 == "closer") { c++; mc += $8 < $7; d = $7 - $8; if (c == 1 || d < md) md = d } }
        END { printf "| %s | %d | %.0f | %.0f | %d of %d | %d of %d | %d of %d | %d of %d | %s |\n",
                noise, n, n ? v / n : 0, n ? t / n : 0, mt, n, mu, n, c, n, mc, c,
                c ? sprintf("%.0f", md) : "-" }' <<< "$fits"
    done
    echo
    echo "The rawlogs where kf-slam's path is the nearer to the truth (RMSE to the millimetre):"
    echo
    echo "| rawlog | kf-slam RMSE [m] | multirobot-vslam RMSE [m] | χ² true path | χ² kf-slam | χ² multirobot-vslam | measured values |"
    echo "|---|---|---|---|---|---|---|"
    awk '$11 == "closer" { printf "| %s | %.3f | %.3f | %.1f | %.1f | %.1f | %d |\n", $1, $3, $4, $6, $7, $8, $10 }' \
      <<< "$fits"
    echo
    echo "## The most probable path"
    echo
    echo "The χ² does not see where a whole path lies: moving or turning a path and its landmarks" \
      "together leaves it unchanged, and such a turn about the start is most of the unaligned" \
      "RMSE (the last section). The most probable path sees it: the path and landmarks of least" \
      "χ², the pose at the first scored reading held at the true start and the robot standing" \
      "where its odometry is exactly zero, each reading's landmark from the IDs-kept twin" \
      "(scripts/range-bearing-path-fit.py --most-probable; exact range-bearing model," \
      "Levenberg-Marquardt from the true path and landmarks). It has what neither tool has, the" \
      "true associations, and it takes the data at their true noise; per rawlog, it is the" \
      "estimate the data support best. IDs hidden, per noise level, on the rawlogs where kf-slam" \
      "finished (RMSE to the millimetre):"
    echo
    echo "| noise | rawlogs | kf-slam RMSE [m] (mean) | multirobot-vslam RMSE [m] (mean) | most probable path RMSE [m] (mean) | kf-slam's RMSE < multirobot-vslam's | kf-slam's RMSE < the most probable path's | multirobot-vslam's χ² above the most probable path's (mean, largest) |"
    echo "|---|---|---|---|---|---|---|---|"
    for noise in $NOISE_LEVELS; do
      awk -v noise="$noise" "$MM_AWK"'$2 == noise && $5 != "-" { n++; k += $3; o += $4; p += $5
          ko += mm($3) < mm($4); kp += mm($3) < mm($5); d = $8 - $9; dd += d
          if (n == 1 || d > dmax) dmax = d }
        END { if (n) printf "| %s | %d | %.3f | %.3f | %.3f | %d of %d | %d of %d | %.1f, %.1f |\n",
                noise, n, k / n, o / n, p / n, ko, n, kp, n, dd / n, dmax }' <<< "$fits"
    done
    echo
    echo "The rawlogs where kf-slam's path is nearer to the truth than the most probable path:"
    echo
    echo "| rawlog | kf-slam RMSE [m] | multirobot-vslam RMSE [m] | most probable path RMSE [m] |"
    echo "|---|---|---|---|"
    awk "$MM_AWK"'$5 != "-" && mm($3) < mm($5) { printf "| %s | %.3f | %.3f | %.3f |\n", $1, $3, $4, $5 }' \
      <<< "$fits"
  fi
  echo
  echo "## Per rawlog"
  echo
  echo "| rawlog | IDs | noise (σ range, σ bearing) | simulation seed | kf-slam RMSE [m] | kf-slam aligned RMSE [m] | kf-slam landmarks | kf-slam landmark error [m] | kf-slam time [s] | multirobot-vslam RMSE [m] | multirobot-vslam aligned RMSE [m] | multirobot-vslam landmarks | multirobot-vslam landmark error [m] | multirobot-vslam time [s] |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for entry in "${NAMES[@]}"; do
    IFS=: read -r name noise ids sim <<< "$entry"
    s="$PEER/simul-landmarks-noise-$noise.ini"
    echo "| $name | $ids | $noise ($(ini_value "$s" stdRange) m, $(ini_value "$s" stdYaw_deg)°) | $sim |$(kf_cells "$name")$(mrv_cells "$name")"
  done
  if both_tools; then
    echo
    echo "## The turn about the start"
    echo
    echo "The angle [deg] of the SE(2) alignment that fits each path best to the truth (vslam-eval's" \
      '`aligned_se2.alignment.yaw_deg`; multirobot-vslam: the mean over its seeds). Both tools' \
      "start at the true pose; what turns a whole path is the heading the data leave uncertain." \
      "What ties the map's heading to the start is what the robot reads there." \
      "simul-landmarks' robot stands for its first few readings: the first comes before any" \
      "action, the next ones after odometry increments of exactly zero that the rawlog still gives" \
      "$(ini_value "$first" odometryNoisePhi_std_deg)° std each. multirobot-vslam reads the first" \
      "as a step of its own and its smoothing ties the others to it (zero_odometry_stands_still," \
      "doc/multirobot.md); kf-slam passes over the first and takes the increments as steps of that" \
      "noise. After them, each step's odometry has that noise." \
      "Where the two tools turn the same way, by amounts of the same order, the turn is the data's," \
      "and it is most of the unaligned RMSE (compare the aligned RMSE)."
    echo
    turns="$(for entry in "${NAMES[@]}"; do
      IFS=: read -r name noise ids sim <<< "$entry"
      echo "$name $(estimate_value "$OUT/kf-slam/$name" aligned_se2 alignment yaw_deg)" \
        "$(for d in $(mrv_dirs "$name"); do estimate_value "$d" aligned_se2 alignment yaw_deg; done |
          tr '\n' ' ')"
    done | awk '
      # rawlog, kf-slam turn, multirobot-vslam turn per seed ("-": no metrics)
      function cell(v) { return v == "-" ? "-" : sprintf("%+.2f", v) }
      { mr = 0; for (i = 3; i <= NF; i++) { if ($i == "-") { mr = "-"; break } mr += $i }
        if (mr != "-") mr /= NF - 2
        same = ($2 == "-" || mr == "-") ? "-" : ($2 * mr > 0 ? "yes" : "no")
        printf "| %s | %s | %s | %s |\n", $1, cell($2), cell(mr), same }')"
    echo "The same sign on $(grep -c '| yes |$' <<< "$turns") of the" \
      "$(grep -c -E '\| (yes|no) \|$' <<< "$turns") rawlogs both tools finished."
    echo
    echo "| rawlog | kf-slam turn [deg] | multirobot-vslam turn [deg] | same sign |"
    echo "|---|---|---|---|"
    echo "$turns"
  fi
} > "$RESULTS.tmp"
mv "$RESULTS.tmp" "$RESULTS"
cat "$RESULTS"
echo
echo "Rawlogs and ground truth in $DATA; run folders in $OUT/kf-slam, $OUT/multirobot-vslam and $OUT/most-probable"
