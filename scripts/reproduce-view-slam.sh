#!/usr/bin/env bash
# Valiente et al. 2015 on simulated omni-views sequences (doc/view-slam.md §5): the traditional and
# the information-based view initialization side by side on the same sequences and seeds:
#   - trajectory RMSE in x, y, position and heading, against odometry;
#   - view position RMSE (each view against the true pose of its image);
#   - uncertainty sqrt(trace P_vv) (mean and final), robot NEES (mean, share of frames inside the
#     95 % chi-square bounds), number of views, run time;
#   - the policies' differences paired by seed (mean, standard error, seeds lower / higher);
#   - plots: sqrt(trace P_vv) and NEES over the frames, paths of seed 1.
# Each seed simulates its own 500-frame sequence (vslam-sim omni-views --seed S: odometry and
# pixel noise) and runs view-slam with --seed S. Writes run folders, tables (*.txt) and plots
# (*.png) under out/reproduce-view-slam/ (or $OUT) and prints markdown tables. Builds first
# (scripts/setup.sh). Takes about 15 min on one core.
# Environment: SEEDS (default 1 2 3 4 5), FRAMES (default: the scenario's 500), OUT.
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"

OUT="${OUT:-$REPO_DIR/out/reproduce-view-slam}"
BIN="$BUILD_DIR/bin"
CONFIG="$REPO_DIR/share/mrpt-vslam/config/view-slam/omni-views.ini"
SEEDS="${SEEDS:-1 2 3 4 5}"
FRAMES="${FRAMES:-}"
POLICIES="traditional information"
mkdir -p "$OUT"

# json FILE KEY: the first number after "KEY": in FILE
json() { grep -o "\"$2\": [-0-9.eE+]*" "$1" | head -1 | awk '{print $2}'; }

# axis_rmse EST GT: RMSE of x, y, position [m] and heading [deg] (same timestamps, line by line)
axis_rmse() {
  paste <(grep -v '^#' "$1") <(grep -v '^#' "$2") | awk '
    function wrap(a) { while (a > 3.14159265358979) a -= 6.28318530717959;
                       while (a < -3.14159265358979) a += 6.28318530717959; return a }
    { if ($1 - $9 > 1e-3 || $9 - $1 > 1e-3) { print "timestamps differ: " $1 " " $9 > "/dev/stderr"; exit 1 }
      dx = $2 - $10; dy = $3 - $11; dt = wrap(2 * atan2($7, $8) - 2 * atan2($15, $16));
      sx += dx * dx; sy += dy * dy; st += dt * dt; n++ }
    END { printf "%.4f %.4f %.4f %.3f", sqrt(sx / n), sqrt(sy / n), sqrt((sx + sy) / n),
                 sqrt(st / n) * 57.2957795 }'
}

echo "## view-slam: traditional vs information-based view initialization (seeds $SEEDS)"
echo
echo "| policy | seed | views | x [m] | y [m] | position [m] | heading [deg] | odometry [m] | views RMSE [m] | mean sqrt tr P_vv | final sqrt tr P_vv | NEES mean | NEES in 95 % | step [ms] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
: > "$OUT/results.txt"
for seed in $SEEDS; do
  data="$OUT/data/seed$seed/rooms"
  if [ ! -f "$data.rawlog" ]; then
    "$BIN/vslam-sim" omni-views --seed "$seed" --quiet --out "$data" ${FRAMES:+--frames "$FRAMES"}
  fi
  for policy in $POLICIES; do
    dir="$OUT/$policy-seed$seed"
    "$BIN/view-slam" "$CONFIG" "$data.rawlog" --seed "$seed" --quiet --out "$dir" \
      --set "ViewInitialization.policy=$policy"
    read -r x y pos yaw <<< "$(axis_rmse "$dir/estimated_path.tum" "$data.groundtruth.tum")"
    read -r _ _ odo _ <<< "$(axis_rmse "$dir/odometry_path.tum" "$data.groundtruth.tum")"
    views=$(json "$dir/run.json" views)
    vrmse=$(json "$dir/run.json" view_position_rmse)
    msp=$(json "$dir/run.json" mean_sqrt_trace_Pvv)
    fsp=$(json "$dir/run.json" final_sqrt_trace_Pvv)
    nees=$(json "$dir/run.json" nees_mean)
    in95=$(json "$dir/run.json" nees_in_95_bounds)
    ms=$(grep -A1 '"per_step_ms"' "$dir/run.json" | awk '/"mean"/ {gsub(",", "", $2); print $2}')
    echo "$policy $seed $views $x $y $pos $yaw $odo $vrmse $msp $fsp $nees $in95 $ms" >> "$OUT/results.txt"
    awk -v p="$policy" -v s="$seed" -v v="$views" -v x="$x" -v y="$y" -v pos="$pos" -v yaw="$yaw" \
      -v odo="$odo" -v vr="$vrmse" -v m="$msp" -v f="$fsp" -v ne="$nees" -v i="$in95" -v ms="$ms" \
      'BEGIN {printf "| %s | %s | %d | %.3f | %.3f | %.3f | %.2f | %.3f | %.3f | %.3f | %.3f | %.2f | %.2f | %.1f |\n", p, s, v, x, y, pos, yaw, odo, vr, m, f, ne, i, ms}'
  done
done
echo
echo "### Means over seeds"
echo
echo "| policy | views | x [m] | y [m] | position [m] | heading [deg] | odometry [m] | views RMSE [m] | mean sqrt tr P_vv | final sqrt tr P_vv | NEES mean | NEES in 95 % | step [ms] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for policy in $POLICIES; do
  awk -v p="$policy" '$1 == p { for (i = 3; i <= 14; i++) s[i] += $i; n++ }
    END { printf "| %s | %.1f | %.3f | %.3f | %.3f | %.2f | %.3f | %.3f | %.3f | %.3f | %.2f | %.2f | %.1f |\n",
          p, s[3] / n, s[4] / n, s[5] / n, s[6] / n, s[7] / n, s[8] / n, s[9] / n, s[10] / n,
          s[11] / n, s[12] / n, s[13] / n, s[14] / n }' "$OUT/results.txt"
done

# Paired per seed: information minus traditional, mean, its standard error, and on how many
# seeds the information policy is lower / equal / higher.
echo
echo "### Information minus traditional, paired by seed"
echo
echo "| quantity | mean difference | standard error | seeds lower | equal | higher |"
echo "|---|---|---|---|---|---|"
awk '{ k = $2; if ($1 == "traditional") { t[k, 1] = $6; t[k, 2] = $10; t[k, 3] = $11; t[k, 4] = $3 }
       else { i[k, 1] = $6; i[k, 2] = $10; i[k, 3] = $11; i[k, 4] = $3; seeds[k] = 1 } }
  END { split("position RMSE [m]|mean sqrt tr P_vv|final sqrt tr P_vv|views", name, "|")
        for (j = 1; j <= 4; j++) {
          n = s = q = lo = eq = 0
          for (k in seeds) { d = i[k, j] - t[k, j]; n++; s += d; q += d * d; lo += d < 0; eq += d == 0 }
          m = s / n; se = n > 1 ? sqrt((q - n * m * m) / (n - 1) / n) : 0
          printf "| %s | %+.4f | %.4f | %d | %d | %d |\n", name[j], m, se, lo, eq, n - lo - eq } }' \
  "$OUT/results.txt"

# Plots of the first seed: uncertainty and NEES over the frames, and the paths.
first=$(echo "$SEEDS" | awk '{print $1}')
: > "$OUT/uncertainty.txt"; : > "$OUT/nees.txt"
for policy in $POLICIES; do
  grep -v '^#' "$OUT/$policy-seed$first/steps.txt" |
    awk -v p="$policy" '{printf "%s %d %s\n", p, NR - 1, $5}' >> "$OUT/uncertainty.txt"
  grep -v '^#' "$OUT/$policy-seed$first/steps.txt" |
    awk -v p="$policy" '$6 != "nan" {printf "%s %d %s\n", p, NR - 1, $6}' >> "$OUT/nees.txt"
done
n=$(grep -v '^#' "$OUT/information-seed$first/steps.txt" | wc -l)
awk -v n="$n" 'BEGIN {printf "upper_95%% 0 9.3484\nupper_95%% %d 9.3484\nlower_95%% 0 0.2158\nlower_95%% %d 0.2158\n", n - 1, n - 1}' >> "$OUT/nees.txt"
"$BIN/vslam-plot" "$OUT/uncertainty.txt" "$OUT/uncertainty.png" --y-from-zero \
  --title "Robot uncertainty, seed $first" --x-label "frame" --y-label "sqrt(trace P_vv)"
"$BIN/vslam-plot" "$OUT/nees.txt" "$OUT/nees.png" --y-from-zero \
  --title "Robot pose NEES, seed $first (chi-square 3 dof, 95 % bounds)" --x-label "frame" \
  --y-label "NEES"
for policy in $POLICIES; do
  "$BIN/vslam-eval" "$OUT/$policy-seed$first" --ground-truth "$OUT/data/seed$first/rooms" \
    --out "$OUT/$policy-seed$first/eval" > /dev/null
done
echo
echo "Plots: $OUT/uncertainty.png, $OUT/nees.png, $OUT/*-seed$first/eval/paths.png"
