#!/usr/bin/env bash
# A user's own bearings of ceiling lights made by MRPT's stock simul-landmarks: 40 lights 2.5-3 m
# up, hidden IDs, a camera 0.5 m up, 0.3 m ahead of the robot and turned 30 deg, which reads
# within 6 m over a 180 deg field of view; the observations state all of it (sensorLocationOnRobot,
# fieldOfView_yaw, maxSensorDistance). omni-fastslam runs from its template with no change and
# takes the camera pose, field of view and reading range from the observations.
# Measured (simulation seed 1, --seed 1: the template's four filters, seeds 1-4, seed 1's kept):
# ATE RMSE 0.096 m against odometry's 0.526 m, the 40 lights matched among 40 mapped; with the
# camera taken as all-around and unlimited (max_abs_azimuth_deg = 180, max_cross_point_range = 0:
# the lights behind it counted as missed), 0.470 m and 10 matched of 11 mapped.
# Usage: check-omni-fastslam-ceiling-lights.sh SOURCE_DIR BUILD_DIR
# Exits 77 (skipped) without mrpt-apps' simul-landmarks and rawlog-edit.
source "$(dirname "${BASH_SOURCE[0]}")/test-setup.sh"

# share/mrpt-vslam/config/omni-fastslam/simul-landmarks-ceiling-lights.ini as shipped: 300
# readings on the 7.2 m square; 2 deg bearing noise, odometry noise 0.01 m and 0.5 deg a step
config="$src/share/mrpt-vslam/config/omni-fastslam/simul-landmarks-ceiling-lights.ini"
grep -q '^fieldOfView_deg = 180$' "$config" && grep -q '^maxSensorDistance = 6$' "$config" &&
  grep -q '^stdYaw_deg = 2$' "$config" && grep -q '^sensorDetectsIDs = false$' "$config" &&
  grep -q '^random_seed = 1$' "$config" || fail "$config is not the data this check describes"
"$src/scripts/simul-landmarks-rawlog.sh" "$config" "$scratch/lights.rawlog"

"$build/bin/omni-fastslam" "$src/share/mrpt-vslam/config/omni-fastslam/template.ini" \
  "$scratch/lights.rawlog" --out "$scratch/run" --seed 1 --quiet
python3 - "$scratch/run" <<'PY' || fail "omni-fastslam's run on the stock ceiling lights out of bounds"
import json, sys
m = json.load(open(sys.argv[1] + "/metrics.json"))
limits = json.load(open(sys.argv[1] + "/run.json"))["results"]["sensor_limits"]
e, odo, lm = m["estimate"], m["odometry"], m["landmarks"]
print("ATE RMSE %.3f m (odometry %.3f m); lights %d mapped, %d of %d matched, error mean %.3f m"
      % (e["ate_rmse_m"], odo["ate_rmse_m"], lm["estimated_landmarks"], lm["matched"],
         lm["matched"] + lm["missed"], lm["error_mean_m"]))
print("limits in use:", limits)
ok = (e["ate_rmse_m"] < 0.2 and e["ate_rmse_m"] < 0.5 * odo["ate_rmse_m"]
      and lm["matched"] >= 36 and abs(lm["estimated_landmarks"] - 40) <= 4 and lm["error_mean_m"] < 0.35
      and all(limits[k]["source"] == "observations" for k in limits)
      and abs(limits["max_abs_azimuth_deg"]["value"] - 90) < 1e-3
      and limits["min_cross_point_range"]["value"] == 0
      and abs(limits["max_cross_point_range"]["value"] - 6) < 1e-3)
sys.exit(0 if ok else 1)
PY
echo "omni-fastslam on stock ceiling lights: passed"
