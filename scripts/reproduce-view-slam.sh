#!/usr/bin/env bash
# Valiente et al. 2015 on simulated omni-views sequences (doc/results/view-slam.md): the
# traditional and the information-based view initialization side by side on the same sequences
# and seeds:
#   - trajectory RMSE in x, y (from the TUM files), position and heading (metrics.json), against
#     odometry's;
#   - view position RMSE (each view against the true pose of its image), uncertainty
#     sqrt(trace P_vv) (mean and final), robot NEES (mean, share of frames inside the 95 %
#     chi-square bounds), number of views, accepted view observations per frame (run.json,
#     steps.txt);
#   - timings: mean and median step, and the whole run (run.json);
#   - the policies' differences paired by seed (mean, standard error, seeds lower / higher);
#   - plots: sqrt(trace P_vv) and NEES over the frames, paths and errors of the first seed.
# Each seed simulates its own sequence (vslam-sim omni-views --seed S: odometry and pixel noise)
# and runs view-slam with --seed S, one run after the other. Writes the tables to
# doc/results/view-slam.md (or $RESULTS) and the plots to doc/results/view-slam/*.png (the folder
# named like $RESULTS without .md); run folders, rawlogs and the raw tables (*.txt) under
# out/reproduce-view-slam/ (or $OUT). Builds the four programs it runs first (scripts/setup.sh).
# Takes about 4 min on 2 cores at the default SEEDS.
# Environment: SEEDS (default 1 2 3 4 5), FRAMES (default: the scenario's 500), OUT, RESULTS.
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# builds only what it runs (BUILD_TARGETS="" builds everything)
BUILD_TARGETS="${BUILD_TARGETS-view-slam vslam-sim vslam-eval vslam-plot}"
source "$REPO_DIR/scripts/setup.sh"
# after the build: the results header times the runs only
source "$REPO_DIR/scripts/results-header.sh"
COMMAND="$(results_command scripts/reproduce-view-slam.sh SEEDS FRAMES OUT RESULTS)"

OUT="${OUT:-$REPO_DIR/out/reproduce-view-slam}"
BIN="$BUILD_DIR/bin"
CONFIG="$REPO_DIR/share/mrpt-vslam/config/view-slam/omni-views.ini"
SEEDS="$(words "${SEEDS:-1 2 3 4 5}")"
FRAMES="${FRAMES:-}"
RESULTS="${RESULTS:-$REPO_DIR/doc/results/view-slam.md}"
POLICIES="traditional information"
mkdir -p "$OUT" "$(dirname "$RESULTS")"
OUT="$(cd "$OUT" && pwd)"
PLOTS="${RESULTS%.md}"
mkdir -p "$PLOTS"
# the two-sided 95 % bounds of chi-square with 3 dof (libs/apps/src/ViewSLAMApp.cpp)
NEES_LOW=0.2158
NEES_HIGH=9.3484

# jget FILE KEY.KEY...: the value at that path of a JSON file pretty-printed with two spaces per
# level (run.json, metrics.json), "-" when absent or null
jget() {
  awk -v want="$2" '
    match($0, /^ *"[^"]*":/) {
      ind = (match($0, /[^ ]/) - 1) / 2; key = $0
      sub(/^ *"/, "", key); sub(/".*/, "", key); path[ind] = key
      p = path[1]; for (i = 2; i <= ind; i++) p = p "." path[i]
      if (p == want) { v = $0; sub(/^[^:]*: */, "", v); sub(/,$/, "", v); found = 1; exit } }
    END { print (found && v != "null" && v != "{" && v != "[") ? v : "-" }' "$1"
}

# axis_rmse EST GT: RMSE of x and y [m] (same timestamps, line by line)
axis_rmse() {
  paste <(grep -v '^#' "$1") <(grep -v '^#' "$2") | awk '
    { if ($1 - $9 > 1e-3 || $9 - $1 > 1e-3) { print "timestamps differ: " $1 " " $9 > "/dev/stderr"; exit 1 }
      dx = $2 - $10; dy = $3 - $11; sx += dx * dx; sy += dy * dy; n++ }
    END { printf "%.4f %.4f", sqrt(sx / n), sqrt(sy / n) }'
}

# path_length TUM: length of the path [m]
path_length() {
  grep -v '^#' "$1" | awk 'NR > 1 { s += sqrt(($2 - x) ^ 2 + ($3 - y) ^ 2) } { x = $2; y = $3 }
    END { printf "%.1f", s }'
}

# --- runs ---------------------------------------------------------------------------------------
# results.txt, one line per run: policy seed views x y position heading odometry odometry_heading
# views_rmse mean_sqrt_tr final_sqrt_tr nees_mean nees_in_95 observed_per_frame step_mean_ms
# step_median_ms total_s
: > "$OUT/results.txt"
for seed in $SEEDS; do
  data="$OUT/data/seed$seed/rooms"
  if [ ! -f "$data.rawlog" ]; then
    "$BIN/vslam-sim" omni-views --seed "$seed" --quiet --out "$data" ${FRAMES:+--frames "$FRAMES"}
  fi
  for policy in $POLICIES; do
    dir="$OUT/$policy-seed$seed"
    echo "view-slam: $policy policy, seed $seed" >&2
    "$BIN/view-slam" "$CONFIG" "$data.rawlog" --seed "$seed" --quiet --out "$dir" \
      --set "ViewInitialization.policy=$policy"
    read -r x y <<< "$(axis_rmse "$dir/estimated_path.tum" "$data.groundtruth.tum")"
    m="$dir/metrics.json" r="$dir/run.json"
    observed=$(grep -v '^#' "$dir/steps.txt" | awk '{ s += $9; n++ } END { printf "%.3f", s / n }')
    echo "$policy $seed $(jget "$r" counts.views) $x $y" \
      "$(jget "$m" estimate.ate_rmse_m) $(jget "$m" estimate.heading_rmse_deg)" \
      "$(jget "$m" odometry.ate_rmse_m) $(jget "$m" odometry.heading_rmse_deg)" \
      "$(jget "$r" results.view_position_rmse) $(jget "$r" results.mean_sqrt_trace_Pvv)" \
      "$(jget "$r" results.final_sqrt_trace_Pvv) $(jget "$r" results.nees_mean)" \
      "$(jget "$r" results.nees_in_95_bounds) $observed $(jget "$r" timing.per_step_ms.mean)" \
      "$(jget "$r" timing.per_step_ms.median) $(jget "$r" timing.total_s)" >> "$OUT/results.txt"
  done
done

# --- plots of the first seed: uncertainty and NEES over the frames, paths and errors -----------
first="${SEEDS%% *}"
: > "$OUT/uncertainty.txt"; : > "$OUT/nees.txt"
for policy in $POLICIES; do
  grep -v '^#' "$OUT/$policy-seed$first/steps.txt" |
    awk -v p="$policy" '{printf "%s %d %s\n", p, NR - 1, $5}' >> "$OUT/uncertainty.txt"
  grep -v '^#' "$OUT/$policy-seed$first/steps.txt" |
    awk -v p="$policy" '$6 != "nan" {printf "%s %d %s\n", p, NR - 1, $6}' >> "$OUT/nees.txt"
done
n=$(grep -v '^#' "$OUT/information-seed$first/steps.txt" | wc -l)
awk -v n="$n" -v lo="$NEES_LOW" -v hi="$NEES_HIGH" 'BEGIN {
  printf "upper_95%% 0 %s\nupper_95%% %d %s\nlower_95%% 0 %s\nlower_95%% %d %s\n", hi, n - 1, hi, lo, n - 1, lo }' \
  >> "$OUT/nees.txt"
"$BIN/vslam-plot" "$OUT/uncertainty.txt" "$PLOTS/uncertainty-seed$first.png" --y-from-zero \
  --title "Robot uncertainty, seed $first" --x-label "frame" --y-label "sqrt(trace P_vv)"
"$BIN/vslam-plot" "$OUT/nees.txt" "$PLOTS/nees-seed$first.png" --y-from-zero \
  --title "Robot pose NEES, seed $first (chi-square 3 dof, 95 % bounds)" --x-label "frame" \
  --y-label "NEES"
for policy in $POLICIES; do
  "$BIN/vslam-eval" "$OUT/$policy-seed$first" --ground-truth "$OUT/data/seed$first/rooms" \
    --out "$OUT/$policy-seed$first/eval" > /dev/null
  cp "$OUT/$policy-seed$first/eval/paths.png" "$PLOTS/paths-$policy-seed$first.png"
  cp "$OUT/$policy-seed$first/eval/errors.png" "$PLOTS/errors-$policy-seed$first.png"
done

# --- results file --------------------------------------------------------------------------------
rel() { realpath --relative-to="$(dirname "$RESULTS")" "$1"; }
{
  results_header "view-slam: traditional vs information-based view initialization" "$COMMAND"
  echo "Seeds: $SEEDS; the runs one at a time."
  echo
  echo "Data: \`vslam-sim omni-views --seed S$([ -n "$FRAMES" ] && echo " --frames $FRAMES")\` for each" \
    "seed S (the same rooms and path, each seed its own odometry and pixel noise):" \
    "$(grep -vc '^#' "$OUT/data/seed$first/rooms.groundtruth.tum") frames," \
    "$(path_length "$OUT/data/seed$first/rooms.groundtruth.tum") m of path. Each sequence is run" \
    "with both policies (\`--set ViewInitialization.policy=...\`), \`--seed S\` and" \
    "share/mrpt-vslam/config/view-slam/omni-views.ini otherwise. Trajectory errors: the EKF" \
    "estimate after each frame against the truth, unaligned (the filter starts from the true" \
    "pose); x, y: per axis; position and heading: \`metrics.json\` (\`ate_rmse_m\`," \
    "\`heading_rmse_deg\`); odometry: dead reckoning from the same start. Views RMSE: each view's" \
    "position against the true pose of its image. √tr P_vv: the root of the trace of the robot" \
    "pose covariance (x, y in m, yaw in rad), mean over the frames and after the last. NEES: the" \
    "robot pose's, mean over the frames, and the share of frames inside the two-sided 95 % bounds" \
    "of χ²₃ ($NEES_LOW to $NEES_HIGH). Observed: accepted view observations per frame. Timings:" \
    "\`run.json\`'s per-step mean and median (one frame: features, matching, RANSAC, updates," \
    "decision) and the run's total wall time (reading the images and writing the outputs included)."
  echo
  echo "## Per run"
  echo
  echo "| policy | seed | views | x [m] | y [m] | position [m] | heading [deg] | odometry position [m] | odometry heading [deg] | views RMSE [m] | mean √tr P_vv | final √tr P_vv | NEES mean | NEES in 95 % | observed per frame | step mean [ms] | step median [ms] | run [s] |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk '{ printf "| %s | %s | %d | %.3f | %.3f | %.3f | %.2f | %.3f | %.2f | %.3f | %.4f | %.4f | %.2f | %.3f | %.2f | %.1f | %.1f | %.1f |\n",
         $1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16, $17, $18 }' \
    "$OUT/results.txt"
  echo
  echo "## Means over the seeds"
  echo
  echo "| policy | views | x [m] | y [m] | position [m] | heading [deg] | odometry position [m] | odometry heading [deg] | views RMSE [m] | mean √tr P_vv | final √tr P_vv | NEES mean | NEES in 95 % | observed per frame | step mean [ms] | step median [ms] | run [s] |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for policy in $POLICIES; do
    awk -v p="$policy" '$1 == p { for (i = 3; i <= 18; i++) s[i] += $i; n++ }
      END { for (i = 3; i <= 18; i++) s[i] /= n
            printf "| %s | %.1f | %.3f | %.3f | %.4f | %.2f | %.3f | %.2f | %.3f | %.4f | %.4f | %.2f | %.3f | %.2f | %.1f | %.1f | %.1f |\n",
              p, s[3], s[4], s[5], s[6], s[7], s[8], s[9], s[10], s[11], s[12], s[13], s[14],
              s[15], s[16], s[17], s[18] }' "$OUT/results.txt"
  done
  echo
  echo "## Information minus traditional, paired by seed"
  echo
  echo "Mean of the per-seed differences (information − traditional), its standard error, and on" \
    "how many seeds the information policy's figure is lower, equal or higher."
  echo
  echo "| quantity | mean difference | standard error | seeds lower | equal | higher |"
  echo "|---|---|---|---|---|---|"
  awk '{ k = $2; if ($1 == "traditional") { for (j = 3; j <= 15; j++) t[k, j] = $j }
         else { for (j = 3; j <= 15; j++) v[k, j] = $j; seeds[k] = 1 } }
    END { split("3:views:%+.1f:%.1f|6:position RMSE [m]:%+.4f:%.4f|7:heading RMSE [deg]:%+.2f:%.2f|10:views RMSE [m]:%+.4f:%.4f|11:mean √tr P_vv:%+.4f:%.4f|12:final √tr P_vv:%+.4f:%.4f|13:NEES mean:%+.2f:%.2f|15:observed per frame:%+.2f:%.2f", q, "|")
          for (r = 1; r in q; r++) {
            split(q[r], f, ":"); j = f[1]
            n = s = ss = lo = eq = 0
            for (k in seeds) { d = v[k, j] - t[k, j]; n++; s += d; ss += d * d; lo += d < 0; eq += d == 0 }
            m = s / n; se = n > 1 ? sqrt((ss - n * m * m) / (n - 1) / n) : 0
            printf "| %s | " f[3] " | " f[4] " | %d | %d | %d |\n", f[2], m, se, lo, eq, n - lo - eq } }' \
    "$OUT/results.txt"
  echo
  echo "## Plots (seed $first)"
  echo
  echo "![robot uncertainty over the frames, both policies]($(rel "$PLOTS/uncertainty-seed$first.png"))"
  echo
  echo "![robot pose NEES over the frames, both policies, with the 95 % bounds]($(rel "$PLOTS/nees-seed$first.png"))"
  for policy in $POLICIES; do
    echo
    echo "![paths and views, $policy policy]($(rel "$PLOTS/paths-$policy-seed$first.png"))"
    echo
    echo "![position and heading errors, $policy policy]($(rel "$PLOTS/errors-$policy-seed$first.png"))"
  done
} > "$RESULTS"
cat "$RESULTS"
echo
echo "Run folders and data in $OUT; plots in $PLOTS"
