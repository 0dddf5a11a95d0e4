#!/usr/bin/env bash
# Gamallo et al. 2013, Sec. IV on the shipped sports-hall dataset: the default run (Table I
# equivalent and errors over time, Fig. 6) and 10 seeds with Hungarian vs maximum-likelihood
# association (Fig. 7/8). Writes every run folder, metrics.json and plots under
# out/reproduce-omni-fastslam/ (or $OUT) and prints a markdown table of the seeds. Builds first
# (scripts/setup.sh).
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"

OUT="${OUT:-$REPO_DIR/out/reproduce-omni-fastslam}"
BIN="$BUILD_DIR/bin"
DATA="$REPO_DIR/datasets/sports-hall/hall"
CONFIG="$REPO_DIR/share/mrpt-vslam/config/omni-fastslam/sports-hall.ini"
SEEDS="${SEEDS:-1 2 3 4 5 6 7 8 9 10}"

# One run + evaluation; prints "ate ate_max heading_share matched false dup missed lm_mean lm_max time"
run() {
  local dir="$1"; shift
  "$BIN/omni-fastslam" "$CONFIG" "$DATA.rawlog" --out "$dir" --quiet "$@"
  "$BIN/vslam-eval" "$dir" --ground-truth "$DATA" > "$dir/summary.txt"
  local traj lm
  traj=$(sed -n 's/^estimate: *ATE RMSE \([0-9.]*\) m (max \([0-9.]*\) m).* \([0-9]*\)% of frames.*/\1 \2 \3%/p' "$dir/summary.txt")
  lm=$(sed -n 's/^landmarks: .*estimated: \([0-9]*\) matched, \([0-9]*\) false (\([0-9]*\) duplicated), \([0-9]*\) missed; error mean \([0-9.]*\) m, max \([0-9.]*\) m/\1 \2 \3 \4 \5 \6/p' "$dir/summary.txt")
  echo -n "$traj $lm"
  grep -o '"total_s": *[0-9.e-]*' "$dir/run.json" | awk '{printf " %s\n", $2}'
}

echo "| association | seed | ATE RMSE [m] | ATE max [m] | heading < 5° | matched | false | dup | missed | landmark mean [m] | landmark max [m] | run [s] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for method in hungarian ml; do
  for seed in $SEEDS; do
    read -r ate atemax share matched fals dup missed lmmean lmmax t < <(run "$OUT/$method-seed$seed" \
      --seed "$seed" --set "MappingApplication_ceilingLightsMap_00_insertOpts.association_method=$method")
    echo "| $method | $seed | $ate | $atemax | $share | $matched | $fals | $dup | $missed | $lmmean | $lmmax | $t |"
  done
done
echo
echo "Run folders (map.txt, metrics.json with the per-light table, paths.png, errors.png) in $OUT"
