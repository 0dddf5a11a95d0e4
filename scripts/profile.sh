#!/usr/bin/env bash
# Where the time goes: perf's sampling profile of the shipped whole runs on one thread, the
# functions with the largest share of samples each (self time, inlined code counted in its
# caller). Writes doc/results/profile.md (or $RESULTS); the speed work in doc/ starts from it.
# Builds first (scripts/setup.sh); installs perf (Debian's linux-perf) if missing. About 3 min.
# Environment: RESULTS, OUT (default out/profile), TOP (functions per run, default 12).
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"
install_missing_packages linux-perf
source "$REPO_DIR/scripts/results-header.sh"
COMMAND="$(results_command scripts/profile.sh OUT TOP RESULTS)"

RESULTS="${RESULTS:-$REPO_DIR/doc/results/profile.md}"
OUT="${OUT:-$REPO_DIR/out/profile}"
TOP="${TOP:-12}"
BIN="$BUILD_DIR/bin"
CONFIGS="$REPO_DIR/share/mrpt-vslam/config"
DATA="$REPO_DIR/datasets"
mkdir -p "$OUT" "$(dirname "$RESULTS")"

# profile NAME APP ARGS...: one run on one thread under perf; a table of the TOP functions
profile() {
  local name="$1" app="$2"
  shift 2
  echo "profile: $name" >&2
  perf record -q -F 999 -o "$OUT/$name.data" -- "$BIN/$app" "$@" --threads 1 --quiet \
    --out "$OUT/$name" 2> "$OUT/$name.perf.log"
  echo
  echo "### $name"
  echo
  echo "\`$app $(echo "$@" | sed "s|$REPO_DIR/||g")\` (run: $(python3 -c \
    "import json; print(round(json.load(open('$OUT/$name/run.json'))['timing']['total_s'], 1))") s)"
  echo
  echo "| share of samples | function | object |"
  echo "|---|---|---|"
  perf report -q -i "$OUT/$name.data" --no-children --sort dso,symbol --field-separator=';' \
    --stdio 2> /dev/null |
    awk -F';' -v top="$TOP" 'NR <= top {
      share = $1; dso = $2; sym = $3; gsub(/ /, "", share); gsub(/ +$/, "", dso);
      sub(/^\[[^]]*\] /, "", sym); sub(/ +$/, "", sym); gsub(/\|/, "\\|", sym);
      if (length(sym) > 90) sym = substr(sym, 1, 87) "...";
      printf "| %s | `%s` | %s |\n", share, sym, dso }'
}

{
  echo "Self time of each function as a share of the run's samples (perf record -F 999, one"
  echo "thread); file reading, writing and the evaluation are part of the run."
  profile multirobot-mrclam multirobot-vslam "$CONFIGS/multirobot-vslam/mrclam.ini" \
    "$DATA/utias-mrclam/mrclam7-r123-0-300.rawlog" --seed 1
  profile multirobot-team3 multirobot-vslam "$CONFIGS/multirobot-vslam/office-team-3.ini" \
    "$DATA/office-team/team3.rawlog" --seed 1
  profile omni-fastslam-M1000 omni-fastslam "$CONFIGS/omni-fastslam/sports-hall.ini" \
    "$DATA/sports-hall/hall.rawlog" --seed 1 --set ParticleFilter.sampleSize=1000
  profile view-slam view-slam "$CONFIGS/view-slam/omni-views.ini" \
    "$DATA/omni-views/rooms.rawlog" --seed 1
} > "$RESULTS.body"
{
  results_header "Profiles" "$COMMAND"
  cat "$RESULTS.body"
} > "$RESULTS.tmp"
rm "$RESULTS.body"
mv "$RESULTS.tmp" "$RESULTS"
echo "wrote $RESULTS; perf data in $OUT"
