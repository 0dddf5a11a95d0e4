#!/usr/bin/env bash
# Speed, in one table: every Google Benchmark of tests/bench (CPU time per iteration) and the
# whole-run timings of the shipped configurations on their shipped datasets and on the
# simulator's 500-frame omni-views sequence, made in $OUT (run.json: wall
# clock of the run and time per filter step, median of RUNS runs). Writes doc/results/speed.md
# (or $RESULTS) with the machine's CPU, core count and load; the documentation quotes only that
# file. Builds first (scripts/setup.sh). Takes about 20 min on this project's 2-core machines.
# Run it on an otherwise idle machine: the header records the load average at the start and end.
# Environment: RESULTS, OUT (run folders, default out/bench), RUNS (default 3), MIN_TIME (Google
# Benchmark's minimum time per benchmark in seconds, default 0.5), BENCH_FILTER (a regular
# expression on the benchmark programs' names, default all), MRPT_VSLAM_MRCLAM_DIR (with it, the
# whole of UTIAS MRCLAM dataset 7 is timed too).
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"
# after the build: the results header times the runs only
source "$REPO_DIR/scripts/results-header.sh"
COMMAND="$(results_command scripts/bench.sh RUNS MIN_TIME BENCH_FILTER OUT RESULTS)"

RESULTS="${RESULTS:-$REPO_DIR/doc/results/speed.md}"
OUT="${OUT:-$REPO_DIR/out/bench}"
RUNS="${RUNS:-3}"
MIN_TIME="${MIN_TIME:-0.5}"
BENCH_FILTER="${BENCH_FILTER:-.}"
BIN="$BUILD_DIR/bin"
CONFIGS="$REPO_DIR/share/mrpt-vslam/config"
DATA="$REPO_DIR/datasets"
mkdir -p "$OUT" "$(dirname "$RESULTS")"

# --- whole runs -----------------------------------------------------------------------------
# whole NAME APP CONFIG RAWLOG [OPTION...] (RAWLOG under datasets/ or $OUT; OPTIONs to the app):
# RUNS runs with seeds 1..RUNS on one thread and on every core; per thread count one table row
# with the medians of run.json's total_s, of the process's wall clock (written beside run.json as
# process_s) and of the per-step mean, and the data's duration (the span of its ground truth)
# over the run's
whole() {
  local name="$1" app="$2" config="$3" rawlog="$4" seed threads start run_dir
  shift 4
  local data="$DATA"
  [ -f "$data/$rawlog" ] || data="$OUT"
  for threads in $( (echo 1; nproc) | uniq); do
    echo "whole run: $name, $threads thread(s)" >&2
    for seed in $(seq 1 "$RUNS"); do
      run_dir="$OUT/$name-t$threads-seed$seed"
      start="$(date +%s.%N)"
      "$BIN/$app" "$CONFIGS/$config" "$data/$rawlog" --out "$run_dir" \
        --seed "$seed" --threads "$threads" --quiet "$@"
      echo "$start $(date +%s.%N)" | awk '{ printf "%.3f\n", $2 - $1 }' > "$run_dir/process_s"
    done
    whole_row "$name-t$threads" "$threads" "$config${*:+ $*}" "$rawlog" "$data"
  done
}

# whole_row NAME THREADS CONFIG RAWLOG DATA_DIR: the table row of the runs NAME-seed*
whole_row() {
  python3 - "$@" "$OUT" "$RUNS" <<'EOF_PY'
import glob, json, statistics, sys
name, threads, config, rawlog, data, out, runs = sys.argv[1:8]
times = [float(line.split()[0]) for f in glob.glob(f"{data}/{rawlog[:-len('.rawlog')]}.groundtruth*.tum")
         for line in open(f) if line.strip() and not line.startswith("#")]
data_s = max(times) - min(times)
docs = [json.load(open(f"{out}/{name}-seed{s}/run.json")) for s in range(1, int(runs) + 1)]
total = statistics.median(d["timing"]["total_s"] for d in docs)
process = statistics.median(float(open(f"{out}/{name}-seed{s}/process_s").read())
                            for s in range(1, int(runs) + 1))
step = statistics.median(d["timing"]["per_step_ms"]["mean"] for d in docs)
steps = docs[0]["timing"]["steps"]
rt = f"{data_s / total:.0f}×"
print(f"| `{config}` | `{rawlog}` | {threads} | {steps} | {total:.2f} | {process:.2f} | {step:.2f} | {rt} |")
EOF_PY
}

{
  echo "## Whole runs of the shipped configurations"
  echo
  echo "Wall clock of the app's run (run.json \`timing.total_s\`: reading, filtering, writing), of"
  echo "its whole process (process: from start to exit, with the loading of its libraries and the"
  echo "evaluation against the ground truth) and the mean time per filter step, each the median of"
  echo "$RUNS run(s) with seeds 1 to $RUNS; real time: the data's duration (its ground truth's time"
  echo "span; simulated data too) over the run's."
  echo
  echo "| config | rawlog | threads | steps | run [s] | process [s] | per step [ms] | real time |"
  echo "|---|---|---|---|---|---|---|---|"
  whole omni-fastslam omni-fastslam omni-fastslam/sports-hall.ini sports-hall/hall.rawlog
  whole multirobot-2 multirobot-vslam multirobot-vslam/office-team-2.ini office-team/team2.rawlog
  whole multirobot-3 multirobot-vslam multirobot-vslam/office-team-3.ini office-team/team3.rawlog
  whole multirobot-mrclam multirobot-vslam multirobot-vslam/mrclam.ini \
    utias-mrclam/mrclam7-r123-0-300.rawlog
  whole omni-fastslam-m1000 omni-fastslam omni-fastslam/sports-hall.ini sports-hall/hall.rawlog \
    --set ParticleFilter.sampleSize=1000
  whole view-slam view-slam view-slam/omni-views.ini omni-views/rooms.rawlog
  # the simulator's whole omni-views sequence (500 frames), made here
  [ -f "$OUT/omni-views-500/ov.rawlog" ] ||
    "$BIN/vslam-sim" omni-views --seed 1 --out "$OUT/omni-views-500/ov" > /dev/null
  whole view-slam-500 view-slam view-slam/omni-views.ini omni-views-500/ov.rawlog
  # the whole of UTIAS MRCLAM dataset 7, robots 1-3, imported as doc/real-data.md does
  if [ -f "${MRPT_VSLAM_MRCLAM_DIR:-}/Barcodes.dat" ]; then
    [ -f "$OUT/mrclam7-r123.rawlog" ] ||
      "$BIN/mrclam2rawlog" "$MRPT_VSLAM_MRCLAM_DIR" --robots 1,2,3 --command-delay 0.2 \
        --keep-robot-measurements --out "$OUT/mrclam7-r123.rawlog" --quiet
    whole multirobot-mrclam-full multirobot-vslam multirobot-vslam/mrclam.ini mrclam7-r123.rawlog
  fi
  echo

  # --- benchmarks ---------------------------------------------------------------------------
  echo "## Benchmarks (Google Benchmark, tests/bench)"
  echo
  echo "Wall-clock time per iteration (on T threads where the benchmark says T: 0 = every core;"
  echo "otherwise one), at least $MIN_TIME s per benchmark."
  echo
  echo "| program | benchmark | time | iterations |"
  echo "|---|---|---|---|"
  for bench in "$BUILD_DIR"/bench/bench_*; do
    [ -x "$bench" ] || continue
    name="$(basename "$bench")"
    [[ "$name" =~ $BENCH_FILTER ]] || continue
    echo "benchmark: $name" >&2
    "$bench" --benchmark_min_time="$MIN_TIME" --benchmark_format=json \
      --benchmark_out="$OUT/$name.json" --benchmark_out_format=json > /dev/null
    python3 - "$name" "$OUT/$name.json" <<'EOF_PY'
import json, sys
name, file = sys.argv[1:3]
scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
for b in json.load(open(file))["benchmarks"]:
    if b.get("run_type", "iteration") != "iteration":
        continue
    ms = b["real_time"] * scale[b["time_unit"]]
    text = f"{ms * 1e3:.2f} µs" if ms < 1 else f"{ms:.2f} ms" if ms < 1e3 else f"{ms / 1e3:.2f} s"
    print(f"| {name} | `{b['name']}` | {text} | {b['iterations']} |")
EOF_PY
  done
} > "$RESULTS.body"
{
  results_header "Speed" "$COMMAND"
  cat "$RESULTS.body"
} > "$RESULTS.tmp"
rm "$RESULTS.body"
mv "$RESULTS.tmp" "$RESULTS"
echo "wrote $RESULTS; run folders and the benchmarks' JSON in $OUT"
