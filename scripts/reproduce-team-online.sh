#!/usr/bin/env bash
# Online team mapping (doc/team-online.md): multirobot-vslam --listen with one vslam-robot-node
# per robot, all on loopback, on the shipped data:
#   1. office-team (2 and 3 robots) and the MRCLAM window (3 robots): the offline run (seed 1),
#      then live at --rate 1 and at the highest rate the mapper keeps up with (the data's duration
#      over the offline run's wall clock, times 0.6): whether the paths and the map are the
#      offline run's byte for byte, readings taken, late readings, reorder-window expiries, and
#      the latency from a reading's send to the end of its filter step (mean and p95);
#   2. office-team, 2 robots, --rate 1, seeds 1-6: R2's node killed KILL_AT s into the run and
#      started again GAP s later: readings taken per robot, late ones, and each robot's position
#      RMSE after R2's last late reading, against the offline runs of seeds 1-10 over the same
#      span.
# The runs at rate 1 (mostly waiting) run side by side on their own ports; the faster ones alone.
# Tables to doc/results/team-online.md (or $RESULTS); run folders and logs under
# out/reproduce-team-online/ (or $OUT). Builds first (scripts/setup.sh). About 10 min, most of
# it the runs at real time.
# Environment: OUT, RESULTS, PORT (first loopback port, default 5600), KILL_AT (default 60),
# GAP (default 10).
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$REPO_DIR/scripts/setup.sh"
source "$REPO_DIR/scripts/results-header.sh"
COMMAND="$(results_command scripts/reproduce-team-online.sh OUT RESULTS PORT KILL_AT GAP)"

OUT="${OUT:-$REPO_DIR/out/reproduce-team-online}"
RESULTS="${RESULTS:-$REPO_DIR/doc/results/team-online.md}"
PORT="${PORT:-5600}"
KILL_AT="${KILL_AT:-60}"
GAP="${GAP:-10}"
BIN="$BUILD_DIR/bin"
CONFIGS="$REPO_DIR/share/mrpt-vslam/config/multirobot-vslam"
DATA="$REPO_DIR/datasets"
rm -rf "$OUT"
mkdir -p "$OUT" "$(dirname "$RESULTS")"

# offline NAME CONFIG PREFIX [SEED]: the run from the rawlog
offline() {
  "$BIN/multirobot-vslam" "$2" "$3.rawlog" --seed "${4:-1}" --quiet --out "$OUT/$1"
}

# live NAME PORT CONFIG PREFIX RATE SEED KILL ROBOTS...: the mapper on loopback port PORT and one
# node per robot at RATE; KILL "R2" kills R2's node KILL_AT s in and starts it again GAP s later
live() {
  local name="$1" at="tcp://127.0.0.1:$2" config="$3" prefix="$4" rate="$5" seed="$6" kill="$7"
  local pid r
  shift 7
  echo "live: $name at rate $rate" >&2
  "$BIN/multirobot-vslam" "$config" --listen "$at" --ground-truth "$prefix" --seed "$seed" \
    --quiet --out "$OUT/$name" > "$OUT/$name.mapper.log" 2>&1 &
  local mapper=$!
  for r in "$@"; do
    "$BIN/vslam-robot-node" "$prefix.rawlog" --robot "$r" --connect "$at" --rate "$rate" \
      --quiet > "$OUT/$name.$r.log" 2>&1 &
    [ "$r" != "$kill" ] || pid=$!
  done
  if [ -n "$kill" ]; then
    sleep "$KILL_AT"
    kill -9 "$pid"
    wait "$pid" 2> /dev/null || true
    sleep "$GAP"
    "$BIN/vslam-robot-node" "$prefix.rawlog" --robot "$kill" --connect "$at" --rate "$rate" \
      --quiet > "$OUT/$name.$kill.restart.log" 2>&1
  fi
  wait "$mapper" || { cat "$OUT/$name.mapper.log" >&2; exit 1; }
  wait
}

# highest_rate NAME PREFIX: 0.6 x the data's duration over the offline run's wall clock
highest_rate() {
  python3 - "$OUT/$1/run.json" "$2" <<'EOF_PY'
import glob, json, sys
times = [float(l.split()[0]) for f in glob.glob(sys.argv[2] + ".groundtruth_*.tum")
         for l in open(f) if l.strip() and not l.startswith("#")]
total = json.load(open(sys.argv[1]))["timing"]["total_s"]
print(max(1, int(0.6 * (max(times) - min(times)) / total)))
EOF_PY
}

TEAMS=(
  "office-team-2|$CONFIGS/office-team-2.ini|$DATA/office-team/team2|R1 R2"
  "office-team-3|$CONFIGS/office-team-3.ini|$DATA/office-team/team3|R1 R2 R3"
  "mrclam-window|$CONFIGS/mrclam.ini|$DATA/utias-mrclam/mrclam7-r123-0-300|R1 R2 R3"
)
: > "$OUT/live-runs.txt"
for team in "${TEAMS[@]}"; do
  IFS='|' read -r name config prefix robots <<< "$team"
  offline "$name-offline" "$config" "$prefix"
done
for seed in $(seq 1 10); do
  offline "office-team-2-offline-seed$seed" "$CONFIGS/office-team-2.ini" "$DATA/office-team/team2" "$seed"
done
# at rate 1, side by side: the teams and the killed node with seeds 1-3, then seeds 4-6
for team in "${TEAMS[@]}"; do
  IFS='|' read -r name config prefix robots <<< "$team"
  # shellcheck disable=SC2086  # robots is a list
  live "$name-live-rate1" "$PORT" "$config" "$prefix" 1 1 "" $robots &
  PORT=$((PORT + 1))
  echo "$name $prefix 1" >> "$OUT/live-runs.txt"
done
for seed in $(seq 1 6); do
  live "office-team-2-gap-seed$seed" "$PORT" "$CONFIGS/office-team-2.ini" "$DATA/office-team/team2" \
    1 "$seed" R2 R1 R2 &
  PORT=$((PORT + 1))
  [ "$seed" != 3 ] || wait
done
wait
# the highest rates, one at a time
for team in "${TEAMS[@]}"; do
  IFS='|' read -r name config prefix robots <<< "$team"
  rate=$(highest_rate "$name-offline" "$prefix")
  # shellcheck disable=SC2086  # robots is a list
  live "$name-live-rate$rate" "$PORT" "$config" "$prefix" "$rate" 1 "" $robots
  PORT=$((PORT + 1))
  echo "$name $prefix $rate" >> "$OUT/live-runs.txt"
done

BIN="$BIN" KILL_AT="$KILL_AT" GAP="$GAP" python3 - "$OUT" > "$OUT/tables.md" <<'EOF_PY'
import glob, json, os, statistics, subprocess, sys
out = sys.argv[1]

def run(name):
    return json.load(open(f"{out}/{name}/run.json"))

def span(prefix):
    t = [float(l.split()[0]) for f in glob.glob(prefix + ".groundtruth_*.tum")
         for l in open(f) if l.strip() and not l.startswith("#")]
    return max(t) - min(t)

def same(a, b):
    files = [os.path.basename(f) for f in glob.glob(f"{out}/{a}/estimated_path_*.tum")] + ["map.txt"]
    return all(open(f"{out}/{a}/{f}", "rb").read() == open(f"{out}/{b}/{f}", "rb").read()
               for f in files)

print("## Live runs against the offline run")
print()
print("Seed 1. Rate: times real time (the nodes' `--rate`); the highest is 0.6 × the data's "
      "duration over the offline run's wall clock. Same: the estimated paths and `map.txt` equal "
      "the offline run's byte for byte. Latency: from a reading's send (node) to the end of the "
      "filter step that fused it (mapper), the worst robot's mean and 95th percentile.")
print()
print("| data | robots | data [s] | offline run [s] | rate | live run [s] | same as offline "
      "| readings | late | window expiries | latency mean [s] | latency p95 [s] |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
runs = [line.split() for line in open(f"{out}/live-runs.txt")]
for name, prefix, rate in sorted(runs, key=lambda r: (r[0], int(r[2]))):
    off = run(f"{name}-offline")
    live = run(f"{name}-live-rate{rate}")
    link = live["results"]["team_link"]
    robots = link["robots"].values()
    print(f"| {os.path.relpath(prefix, os.path.dirname(os.path.dirname(prefix)))} | {len(link['robots'])} | {span(prefix):.0f} "
          f"| {off['timing']['total_s']:.1f} | {rate} | {live['timing']['total_s']:.1f} "
          f"| {'yes' if same(f'{name}-offline', f'{name}-live-rate{rate}') else 'no'} "
          f"| {sum(r['readings'] for r in robots)} | {sum(r['late'] for r in robots)} "
          f"| {link['window_expiries']} | {max(r['latency_mean_s'] for r in robots):.3f} "
          f"| {max(r['latency_p95_s'] for r in robots):.3f} |")

def rmse_after(run_dir, robot, prefix, after):
    """Position RMSE of one robot's path after time `after` (vslam-eval --after)."""
    ev = f"{out}/eval-after/{run_dir}-{after:.6f}"
    if not os.path.exists(f"{ev}/metrics.json"):
        subprocess.run([f"{os.environ['BIN']}/vslam-eval", f"{out}/{run_dir}", "--ground-truth",
                        prefix, "--after", repr(after), "--out", ev],
                       check=True, stdout=subprocess.DEVNULL)
    e = json.load(open(f"{ev}/metrics.json"))["robots"][robot]["estimate"]
    return e["ate_rmse_m"], e["matched_poses"]

gaps = [run(f"office-team-2-gap-seed{k}") for k in range(1, 7)]
prefix = gaps[0]["ground_truth"]
start = min(float(l.split()[0]) for l in open(prefix + ".groundtruth_R2.tum")
            if l.strip() and not l.startswith("#"))

print()
print("## A node killed and restarted")
print()
print(f"office-team, 2 robots, rate 1, seeds 1-6: R2's node killed {os.environ.get('KILL_AT', '60')} s "
      f"into the run and started again {os.environ.get('GAP', '10')} s later. The mapper went on "
      "without R2 after its reorder window (R2 standing still); R2's readings of the gap came late "
      "and were stamped after the stream's time (R1 standing still). RMSE after the gap: over the "
      "poses after R2's last late reading (late until, data time from the start); the offline runs "
      "of seeds 1-10 over the same span.")
print()
print("| seed | robot | readings | connections | late | late until [s] | window expiries "
      "| live RMSE after the gap [m] | offline RMSE, same span: mean [m] | min - max [m] |")
print("|---|---|---|---|---|---|---|---|---|---|")
summary = {}  # robot: per live run, (its RMSE, the offline runs' RMSEs over the same span)
for k, gap in enumerate(gaps, 1):
    link = gap["results"]["team_link"]
    after = link["robots"]["R2"]["late_until"]
    for robot, s in link["robots"].items():
        live_rmse, n = rmse_after(f"office-team-2-gap-seed{k}", robot, prefix, after)
        off = [rmse_after(f"office-team-2-offline-seed{j}", robot, prefix, after)[0]
               for j in range(1, 11)]
        print(f"| {k} | {robot} | {s['readings']} | {s['connections']} | {s['late']} "
              f"| {after - start:.1f} | {link['window_expiries']} | {live_rmse:.3f} ({n} poses) "
              f"| {statistics.mean(off):.3f} | {min(off):.3f} - {max(off):.3f} |")
        summary.setdefault(robot, []).append((live_rmse, off))

print()
print("Live against offline, per robot: the mean RMSE after the gap over the live seeds and over "
      "the offline seeds, and how many live runs fall outside the offline runs' range (a run drawn "
      "from the same spread falls outside the range of 10 others with probability 2/11).")
print()
print("| robot | live mean [m] | offline mean [m] | live runs outside the offline range | "
      "expected if the same spread |")
print("|---|---|---|---|---|")
for robot, rows in summary.items():
    outside = sum(not min(off) <= live <= max(off) for live, off in rows)
    print(f"| {robot} | {statistics.mean(live for live, _ in rows):.3f} "
          f"| {statistics.mean(statistics.mean(off) for _, off in rows):.3f} "
          f"| {outside} of {len(rows)} | {len(rows) * 2 / (len(rows[0][1]) + 1):.1f} |")
EOF_PY

{
  results_header "Online team mapping: live runs over ZeroMQ against offline runs" "$COMMAND"
  cat "$OUT/tables.md"
} > "$RESULTS"
echo "wrote $RESULTS" >&2
