#!/usr/bin/env bash
# Gil et al. 2010, Sec. 6 on the shipped office-team datasets (doc/multirobot.md):
#   1. Fig. 3 / Fig. 6: 2 robots (M = 500, B = 8) and 3 robots (M = 3000, B = 20), several seeds:
#      per-robot RMSE vs odometry, merged vs duplicated shared landmarks, step time; paths.png and
#      errors.png of each run (vslam-eval);
#   2. Fig. 4(a): RMSE vs M in {1, 10, 50, 100, 200, 500, 1000, 1500, 2500} (2 robots, B = 8);
#   3. Fig. 4(b): RMSE vs B in {1, 5, 10, 20} (2 robots, M = 500), with the nearest B kept (as
#      shipped) and with a random B (observation_selection = random);
#   4. the paper's proposal (pfStandardProposal) vs the shipped pfOptimalProposal, descriptor
#      threshold E0 (0.25 vs 0.7) and the paper's R_t pixel sigmas (1, 10, 10) vs ours on team2,
#      and RMSE vs B with the paper's sigmas, nearest and random B;
#   5. team3 without resample_per_robot, with the optimal proposal, and with the paper's sigmas.
# The tables go to doc/results/multirobot.md (or $RESULTS), the plots (Fig. 3, 4 and 6) to
# doc/results/multirobot/; run folders and the series (*.txt) under out/reproduce-multirobot/ (or
# $OUT). Builds first (scripts/setup.sh). Takes about 15 min on 2 cores.
# Environment: SEEDS (default 1 2 3 4 5), SWEEP_SEEDS for sections 2 and 3 (default 1 to 10), OUT,
# RESULTS.
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"
# after the build: the results header times the runs only
source "$REPO_DIR/scripts/results-header.sh"
COMMAND="$(results_command scripts/reproduce-multirobot.sh OUT SEEDS SWEEP_SEEDS RESULTS)"

OUT="${OUT:-$REPO_DIR/out/reproduce-multirobot}"
BIN="$BUILD_DIR/bin"
DATA="$REPO_DIR/datasets/office-team"
CONFIGS="$REPO_DIR/share/mrpt-vslam/config/multirobot-vslam"
SEEDS="$(words "${SEEDS:-1 2 3 4 5}")"
SWEEP_SEEDS="$(words "${SWEEP_SEEDS:-1 2 3 4 5 6 7 8 9 10}")"
MAP_OPTS="MappingApplication_visualLandmarksMap_00_insertOpts"
RESULTS="${RESULTS:-$REPO_DIR/doc/results/multirobot.md}"
PLOTS="${RESULTS%.md}"
mkdir -p "$OUT" "$PLOTS"

# run DIR CONFIG RAWLOG [multirobot-vslam options...]: one run and its evaluation; prints
# "est_1 odo_1 est_2 odo_2 [...] | merged shared step_ms" (RMSE in m).
run() {
  local dir="$1" config="$2" rawlog="$3"; shift 3
  "$BIN/multirobot-vslam" "$config" "$rawlog" --out "$dir" --quiet "$@"
  "$BIN/vslam-eval" "$dir" --ground-truth "${rawlog%.rawlog}" > "$dir/summary.txt"
  local rmse merged shared ms
  rmse=$(awk '/^R[0-9]+ (estimate|odometry):/ {printf "%s ", $5}' "$dir/summary.txt")
  merged=$(grep -o '"of_those_merged": [0-9]*' "$dir/run.json" | awk '{print $2}')
  shared=$(grep -o '"true_landmarks_seen_by_several_robots": [0-9]*' "$dir/run.json" | awk '{print $2}')
  ms=$(grep -A1 '"per_step_ms"' "$dir/run.json" | awk '/"mean"/ {gsub(",", "", $2); printf "%.1f", $2}')
  echo "$rmse| $merged $shared $ms"
}

# mean_rmse "est_1 odo_1 est_2 odo_2 ... | ...": mean of the robots' estimate RMSE
mean_rmse() { echo "$1" | awk -F'|' '{n = split($1, v, " "); s = 0; for (i = 1; i < n; i += 2) s += v[i]; printf "%.4f", s / (n / 2)}'; }

# mean_sd FILE: mean and sample standard deviation of a column of numbers
mean_sd() { awk '{s += $1; q += $1 * $1; n++} END {m = s / n; v = n > 1 ? (q - n * m * m) / (n - 1) : 0; printf "%.4f %.4f", m, (v > 0 ? sqrt(v) : 0)}' "$1"; }

# --- 1. Fig. 3 and Fig. 6: the shipped configurations, several seeds -------------------------
team_table() {
  local name="$1" config="$2" rawlog="$3" robots="$4"
  echo
  echo "### $name ($(basename "$config"))"
  echo
  local header="| seed |" rule="|---|"
  for r in $(seq 1 "$robots"); do header+=" R$r RMSE [m] | R$r odometry [m] | R$r ratio |"; rule+="---|---|---|"; done
  echo "$header merged / shared | step [ms] |"
  echo "$rule---|---|"
  : > "$OUT/$name-rmse.txt"
  for seed in $SEEDS; do
    local res line
    res=$(run "$OUT/$name-seed$seed" "$config" "$rawlog" --seed "$seed")
    line="| $seed |"
    read -r -a v <<< "${res%%|*}"
    for r in $(seq 0 $((robots - 1))); do
      line+=$(awk -v e="${v[$((2 * r))]}" -v o="${v[$((2 * r + 1))]}" 'BEGIN {printf " %.3f | %.3f | %.2f |", e, o, e / o}')
      echo "R$((r + 1)) ${v[$((2 * r))]} ${v[$((2 * r + 1))]}" >> "$OUT/$name-rmse.txt"
    done
    read -r merged shared ms <<< "${res##*|}"
    echo "$line $merged / $shared | $ms |"
  done
  for r in $(seq 1 "$robots"); do
    awk -v r="R$r" '$1 == r {e += $2; o += $3; n++} END {printf "R%s mean over seeds: RMSE %.3f m, odometry %.3f m, ratio %.2f\n", substr(r, 2), e / n, o / n, e / o}' "$OUT/$name-rmse.txt"
  done
}
{
echo "Position RMSE: vslam-eval's ATE of each robot, unaligned; step: the mean time" \
  "of a filter step (run.json), one core. Merged / shared: of the true landmarks seen by several" \
  "robots, how many are one landmark of the final map."
echo "## 1. The shipped configurations (Fig. 3 and Fig. 6)" >&2
team_table team2 "$CONFIGS/office-team-2.ini" "$DATA/team2.rawlog" 2
team_table team3 "$CONFIGS/office-team-3.ini" "$DATA/team3.rawlog" 3

echo
echo "![team2, seed 1: paths and map (Fig. 3)](multirobot/team2-paths.png)"
echo "![team2, seed 1: errors over time](multirobot/team2-errors.png)"
echo "![team3, seed 1: paths and map (Fig. 6)](multirobot/team3-paths.png)"
echo "![team3, seed 1: errors over time](multirobot/team3-errors.png)"
for t in team2 team3; do
  for f in paths errors; do cp "$OUT/$t-seed1/$f.png" "$PLOTS/$t-$f.png"; done
done

# --- 2./3. Fig. 4: RMSE (mean of both robots) vs M and vs B, both proposals --------------------
# sweep NAME KEY PROPOSAL VALUES...: one series of rmse-vs-NAME.txt (SWEEP_RAWLOG: team2 if unset;
# SWEEP_SET: one more --set for every run)
sweep() {
  local name="$1" key="$2" proposal="$3"; shift 3
  local rawlog="${SWEEP_RAWLOG:-$DATA/team2.rawlog}"
  echo
  echo "### RMSE vs $name, $proposal ($(basename "$(dirname "$rawlog")")/$(basename "$rawlog"); mean of both robots; mean ± sd over seeds $SWEEP_SEEDS)"
  echo
  echo "| $name | mean RMSE [m] | sd [m] | step [ms] |"
  echo "|---|---|---|---|"
  for value in "$@"; do
    : > "$OUT/sweep.tmp"
    local ms_sum=0
    for seed in $SWEEP_SEEDS; do
      local res
      res=$(run "$OUT/$proposal-$name$value-seed$seed" "$CONFIGS/office-team-2.ini" \
        "$rawlog" --seed "$seed" --set "$key=$value" \
        --set "ParticleFilter.PF_algorithm=$proposal" ${SWEEP_SET:+--set "$SWEEP_SET"})
      mean_rmse "$res" >> "$OUT/sweep.tmp"; echo >> "$OUT/sweep.tmp"
      ms_sum=$(awk -v a="$ms_sum" -v b="${res##* }" 'BEGIN {print a + b}')
    done
    read -r m sd <<< "$(mean_sd "$OUT/sweep.tmp")"
    local ms
    ms=$(awk -v s="$ms_sum" -v n="$(echo "$SWEEP_SEEDS" | wc -w)" 'BEGIN {printf "%.1f", s / n}')
    echo "| $value | $m | $sd | $ms |"
    awk -v p="$proposal" -v x="$value" -v m="$m" -v sd="$sd" 'BEGIN {printf "%s %s %s %.4f %.4f\n", p, x, m, m - sd, m + sd}' >> "$OUT/rmse-vs-$name.txt"
  done
  rm -f "$OUT/sweep.tmp"
}
: > "$OUT/rmse-vs-M.txt"
: > "$OUT/rmse-vs-B.txt"
for proposal in pfOptimalProposal pfStandardProposal; do
  sweep M ParticleFilter.sampleSize "$proposal" 1 10 50 100 200 500 1000 1500 2500
  sweep B MultiRobotVSLAM.max_observations_per_robot "$proposal" 1 5 10 20
done
echo "## 2-3. RMSE vs M and B (Fig. 4)" >&2
"$BIN/vslam-plot" "$OUT/rmse-vs-M.txt" "$PLOTS/rmse-vs-M.png" --log-x --y-from-zero \
  --title "RMSE vs number of particles M (B = 8, mean ± sd over seeds)" \
  --x-label "M" --y-label "position RMSE [m]"
"$BIN/vslam-plot" "$OUT/rmse-vs-B.txt" "$PLOTS/rmse-vs-B.png" --y-from-zero \
  --title "RMSE vs observations per robot and step B (M = 500, mean ± sd over seeds)" \
  --x-label "B" --y-label "position RMSE [m]"
# the same with B measurements drawn at random instead of the B nearest (the paper does not say)
: > "$OUT/rmse-vs-B-random.txt"
for proposal in pfOptimalProposal pfStandardProposal; do
  SWEEP_SET=MultiRobotVSLAM.observation_selection=random sweep B-random \
    MultiRobotVSLAM.max_observations_per_robot "$proposal" 1 5 10 20
done
"$BIN/vslam-plot" "$OUT/rmse-vs-B-random.txt" "$PLOTS/rmse-vs-B-random.png" --y-from-zero \
  --title "RMSE vs B, B measurements drawn at random (M = 500, mean ± sd over seeds)" \
  --x-label "B" --y-label "position RMSE [m]"

echo
echo "![RMSE vs M (Fig. 4a)](multirobot/rmse-vs-M.png)"
echo "![RMSE vs B, the nearest B (Fig. 4b)](multirobot/rmse-vs-B.png)"
echo "![RMSE vs B, B drawn at random](multirobot/rmse-vs-B-random.png)"

# --- 4. E0 and the paper's R_t ------------------------------------------------------------------
echo "## 4. Variants on team2" >&2
echo
echo "### Variants (team2, seeds $SEEDS): mean RMSE of both robots, merged / shared landmarks"
echo
echo "| variant | mean RMSE [m] | sd [m] | merged / shared (sum) |"
echo "|---|---|---|---|"
variant() {  # variant NAME DIR RAWLOG [options...]
  local name="$1" dir="$2" rawlog="$3"; shift 3
  : > "$OUT/variant.tmp"
  local merged=0 shared=0
  for seed in $SEEDS; do
    local res mg sh
    res=$(run "$OUT/$dir-seed$seed" "$CONFIGS/office-team-2.ini" "$rawlog" --seed "$seed" "$@")
    mean_rmse "$res" >> "$OUT/variant.tmp"; echo >> "$OUT/variant.tmp"
    read -r mg sh _ <<< "${res##*|}"
    merged=$((merged + mg)); shared=$((shared + sh))
  done
  read -r m sd <<< "$(mean_sd "$OUT/variant.tmp")"
  echo "| $name | $m | $sd | $merged / $shared |"
  rm -f "$OUT/variant.tmp"
}
variant "shipped (pfOptimalProposal, E0 = 0.7, sigma 0.5/3/3)" shipped "$DATA/team2.rawlog"
variant "pfStandardProposal (the paper's)" standard "$DATA/team2.rawlog" \
  --set ParticleFilter.PF_algorithm=pfStandardProposal
variant "E0 = 0.25" E0-0.25 "$DATA/team2.rawlog" --set "$MAP_OPTS.E0=0.25"
# the paper's sigmas need the landmarks extracted again from the stereo images
paper_sigma_rawlog() {  # paper_sigma_rawlog NAME ROBOTS: simulates and extracts once
  if [ ! -f "$OUT/paper-sigma/$1.rawlog" ]; then
    "$BIN/vslam-sim" office-team --robots "$2" --seed 1 --quiet --out "$OUT/stereo/$1"
    sed -e 's/^sigma_disparity = .*/sigma_disparity = 1/' -e 's/^sigma_row = .*/sigma_row = 10/' \
      -e 's/^sigma_col = .*/sigma_col = 10/' "$CONFIGS/stereo-frontend.ini" > "$OUT/paper-sigma.ini"
    "$BIN/stereo-frontend" "$OUT/paper-sigma.ini" "$OUT/stereo/$1.rawlog" --quiet \
      --out "$OUT/paper-sigma/$1"
  fi
}
paper_sigma_rawlog team2 2
variant "paper sigma 1/10/10" paper-sigma-run "$OUT/paper-sigma/team2.rawlog"
# Fig. 4(b) once more with the paper's R_t, where one measurement carries less information
: > "$OUT/rmse-vs-B-paper-sigma.txt"
for proposal in pfOptimalProposal pfStandardProposal; do
  SWEEP_RAWLOG="$OUT/paper-sigma/team2.rawlog" sweep B-paper-sigma \
    MultiRobotVSLAM.max_observations_per_robot "$proposal" 1 5 10 20
done
# and with the B drawn at random: the paper's R_t, proposal and (presumably) selection
: > "$OUT/rmse-vs-B-paper-sigma-random.txt"
for proposal in pfOptimalProposal pfStandardProposal; do
  SWEEP_RAWLOG="$OUT/paper-sigma/team2.rawlog" SWEEP_SET=MultiRobotVSLAM.observation_selection=random \
    sweep B-paper-sigma-random MultiRobotVSLAM.max_observations_per_robot "$proposal" 1 5 10 20
done
"$BIN/vslam-plot" "$OUT/rmse-vs-B-paper-sigma-random.txt" "$PLOTS/rmse-vs-B-paper-sigma-random.png" \
  --y-from-zero --x-label "B" --y-label "position RMSE [m]" \
  --title "RMSE vs B, the paper's R_t, B drawn at random (M = 500, mean ± sd over seeds)"

echo
echo "![RMSE vs B, the paper's R_t, B drawn at random](multirobot/rmse-vs-B-paper-sigma-random.png)"

# --- 5. team3 with the paper's R_t sigmas (1, 10, 10), and without resample_per_robot --------
echo "## 5. Variants on team3" >&2
paper_sigma_rawlog team3 3
echo
echo "### team3 variants (seeds $SEEDS): mean RMSE per robot"
echo
echo "| variant | R1 [m] | R2 [m] | R3 [m] |"
echo "|---|---|---|---|"
team3_variant() {  # team3_variant NAME DIR RAWLOG [options...]
  local name="$1" dir="$2" rawlog="$3"; shift 3
  : > "$OUT/team3-variant.tmp"
  for seed in $SEEDS; do
    res=$(run "$OUT/$dir-seed$seed" "$CONFIGS/office-team-3.ini" "$rawlog" --seed "$seed" "$@")
    echo "${res%%|*}" >> "$OUT/team3-variant.tmp"
  done
  awk -v v="$name" '{a += $1; b += $3; c += $5; n++} END {printf "| %s | %.3f | %.3f | %.3f |\n", v, a / n, b / n, c / n}' "$OUT/team3-variant.tmp"
  rm -f "$OUT/team3-variant.tmp"
}
team3_variant "resample_per_robot = false" team3-no-rpr "$DATA/team3.rawlog" \
  --set MultiRobotVSLAM.resample_per_robot=false
team3_variant "pfOptimalProposal" team3-optimal "$DATA/team3.rawlog" \
  --set ParticleFilter.PF_algorithm=pfOptimalProposal
team3_variant "paper sigma 1/10/10" team3-paper-sigma "$OUT/paper-sigma/team3.rawlog"
} > "$RESULTS.body"
{
  results_header "Multi-robot visual SLAM on the shipped office-team datasets" "$COMMAND"
  cat "$RESULTS.body"
} > "$RESULTS.tmp"
rm "$RESULTS.body"
mv "$RESULTS.tmp" "$RESULTS"
echo "wrote $RESULTS and its plots in $PLOTS; run folders and series in $OUT"
