#!/usr/bin/env python3
"""How well planar paths explain one range-bearing rawlog's odometry and readings.

For each path given (TUM files), prints its chi-square: the squared, std-normalised residuals of
  - the odometry: each step's increment between two scored stamps against the path's, in x, y
    and heading (steps whose odometry increment is exactly zero, where the robot stands, are
    left out);
  - the readings: range and bearing of every reading at a scored stamp against those predicted
    from the path, each landmark at the position that fits that path's readings of it best
    (Levenberg-Marquardt).
The true path's chi-square is about the number of measured values; a path fitted to the data has
less. Each reading's landmark is the ID it carries or, with --ids-from, the ID of the same
reading in another listing: that of the same simulation with the IDs kept (simul-landmarks with
sensorDetectsIDs = true writes the same readings, value for value and in the same order; checked).
Readings are listed by `rawlog-edit -i NAME.rawlog --list-range-bearing --text-file-output FILE`.
Paths are looked up at the scored stamps to the microsecond. Each landmark's fit takes the best of
a few starts (see best_landmark); with --landmarks, the landmark's position in that file is one.
Output: a line per path, "PATH chi2 odometry_chi2 readings_chi2 measured_values".
"""
import argparse
import math
import sys
from collections import defaultdict
from decimal import Decimal, InvalidOperation

MICROSECOND = Decimal("0.000001")


class InputError(Exception):
    pass


def stamp_key(text, where):
    try:
        return Decimal(text).quantize(MICROSECOND)
    except InvalidOperation:
        raise InputError(f"{where}: '{text}' is not a timestamp")


def wrap(a):
    return math.remainder(a, 2 * math.pi)


def table_rows(path, comment, columns, expected, parsers):
    """(where, first column, parsed values) of each data line of a whitespace-separated table.
    Blank lines and lines starting with comment are skipped; the others need columns[0] to
    columns[1] columns (expected says which) and give the values parser(column) for each
    (index, parser) of parsers, all finite."""
    with open(path) as f:
        for n, line in enumerate(f, 1):
            cols = line.split()
            if not cols or cols[0].startswith(comment):
                continue
            where = f"{path}:{n}"
            if not columns[0] <= len(cols) <= columns[1]:
                raise InputError(f"{where}: {len(cols)} columns, expected {expected}")
            try:
                values = [parse(cols[i]) for i, parse in parsers]
            except ValueError:
                raise InputError(f"{where}: a value is not a number")
            if not all(map(math.isfinite, values)):
                raise InputError(f"{where}: a value is not finite")
            yield where, cols[0], values


def read_stamps(path):
    """The stamps in the first column of a file ('#' comments): a list, or a TUM file."""
    return [stamp_key(stamp, where)
            for where, stamp, _ in table_rows(path, "#", (1, math.inf), "a stamp first", ())]


def require_stamps(poses, stamps, name):
    """Raises unless poses has a pose at every stamp."""
    missing = [s for s in stamps if s not in poses]
    if missing:
        raise InputError(f"{name}: no pose at stamp {missing[0]} ({len(missing)} of "
                         f"{len(stamps)} scored stamps missing)")


def read_tum(path):
    """{stamp: (x, y, yaw)} of a TUM file (planar: yaw from the quaternion's z and w)."""
    return {stamp_key(stamp, where): (x, y, 2 * math.atan2(qz, qw))
            for where, stamp, (x, y, qz, qw) in table_rows(
                path, "#", (8, 8), "8 (TUM: stamp x y z qx qy qz qw)",
                ((1, float), (2, float), (6, float), (7, float)))}


def read_landmarks(path):
    """{id: (x, y)} of a landmarks file (id x y z per line, '#' comments)."""
    return {lid: (x, y) for _, _, (lid, x, y) in table_rows(
        path, "#", (3, math.inf), "id x y ...", ((0, int), (1, float), (2, float)))}


def read_readings(path):
    """[(stamp, id, range, bearing)] of rawlog-edit's --list-range-bearing output."""
    rows = []
    for where, stamp, (lid, r, yaw, pitch) in table_rows(
            path, "%", (6, 6), "6 (stamp, index, ID, range, yaw, pitch)",
            ((2, int), (3, float), (4, float), (5, float))):
        if pitch != 0:
            raise InputError(f"{where}: pitch {pitch}: only planar readings are scored")
        rows.append((stamp_key(stamp, where), lid, r, yaw))
    if not rows:
        raise InputError(f"{path}: no readings")
    return rows


def frame_sizes(readings):
    """The number of readings of each stamp, in order."""
    sizes = []
    for i, row in enumerate(readings):
        if i == 0 or row[0] != readings[i - 1][0]:
            sizes.append(0)
        sizes[-1] += 1
    return sizes


def with_ids_from(readings, name, ids_name):
    """readings with the landmark IDs of the same readings listed in ids_name."""
    labelled = read_readings(ids_name)
    if frame_sizes(readings) != frame_sizes(labelled) or \
            [row[2:] for row in readings] != [row[2:] for row in labelled]:
        raise InputError(f"{ids_name}: not the readings of {name} (frame by frame, range and "
                         "bearing)")
    return [(s, other[1], r, b) for (s, _, r, b), other in zip(readings, labelled)]


def compose(pose, offset):
    x, y, a = pose
    c, s = math.cos(a), math.sin(a)
    return (x + c * offset[0] - s * offset[1], y + s * offset[0] + c * offset[1], a + offset[2])


def increment(a, b):
    """b relative to a."""
    c, s = math.cos(a[2]), math.sin(a[2])
    dx, dy = b[0] - a[0], b[1] - a[1]
    return (c * dx + s * dy, -s * dx + c * dy, wrap(b[2] - a[2]))


def residuals(landmark, sensor, r, bearing, sr, sb):
    """Normalised range and bearing residuals and their Jacobian rows w.r.t. the landmark."""
    dx, dy = landmark[0] - sensor[0], landmark[1] - sensor[1]
    q = dx * dx + dy * dy
    if q == 0:
        raise InputError("a landmark at a sensor's position: no range or bearing to compare")
    d = math.sqrt(q)
    er = (d - r) / sr
    eb = wrap(math.atan2(dy, dx) - sensor[2] - bearing) / sb
    return er, eb, (dx / d / sr, dy / d / sr), (-dy / q / sb, dx / q / sb)


def landmark_cost(m, readings, sr, sb):
    """The chi-square of readings [(sensor, r, b)] of a landmark at m."""
    return sum(er * er + eb * eb for er, eb, _, _ in
               (residuals(m, s, r, b, sr, sb) for s, r, b in readings))


def refine_landmark(m, readings, sr, sb):
    """Levenberg-Marquardt from m: (position, chi-square), each accepted step lowering it."""
    cost = landmark_cost(m, readings, sr, sb)
    damping = 1e-3
    for _ in range(100):
        h11 = h12 = h22 = g1 = g2 = 0.0
        for s, r, b in readings:
            er, eb, jr, jb = residuals(m, s, r, b, sr, sb)
            h11 += jr[0] * jr[0] + jb[0] * jb[0]
            h12 += jr[0] * jr[1] + jb[0] * jb[1]
            h22 += jr[1] * jr[1] + jb[1] * jb[1]
            g1 += jr[0] * er + jb[0] * eb
            g2 += jr[1] * er + jb[1] * eb
        while True:
            a11, a22 = h11 * (1 + damping), h22 * (1 + damping)
            det = a11 * a22 - h12 * h12
            if not det > 0:
                return m, cost
            step = (-(a22 * g1 - h12 * g2) / det, -(a11 * g2 - h12 * g1) / det)
            trial = (m[0] + step[0], m[1] + step[1])
            trial_cost = landmark_cost(trial, readings, sr, sb)
            if trial_cost <= cost:
                m, cost, damping = trial, trial_cost, damping / 10
                break
            damping *= 10
            if damping > 1e12:
                return m, cost
        if math.hypot(*step) < 1e-9:
            break
    return m, cost


def best_landmark(readings, sr, sb, known=None):
    """The landmark position minimising the readings' chi-square, and that chi-square;
    readings: [(sensor, r, b)]. Starts, the best fit kept: the mean of the readings' end points;
    the fit of the readings farther than 3 range std; known (a position given) when not None;
    each refined with all readings. A reading of a landmark next to the sensor has a bearing that
    turns fully within a few millimetres of it, which can hold a fit from one start away from the
    best one."""
    def end_point_mean(subset):
        return (sum(s[0] + r * math.cos(s[2] + b) for s, r, b in subset) / len(subset),
                sum(s[1] + r * math.sin(s[2] + b) for s, r, b in subset) / len(subset))
    starts = [end_point_mean(readings)]
    far = [reading for reading in readings if reading[1] > 3 * sr]
    if far and len(far) < len(readings):
        starts.append(refine_landmark(end_point_mean(far), far, sr, sb)[0])
    if known is not None:
        starts.append(known)
    return min((refine_landmark(m, readings, sr, sb) for m in starts), key=lambda fit: fit[1])


def chi_square(path, name, args, stamps, odometry, frames, landmarks):
    require_stamps(path, stamps, name)
    so, sp = args.odometry_std_xy, math.radians(args.odometry_std_phi_deg)
    odo_chi2, odo_values = 0.0, 0
    for a, b in zip(stamps, stamps[1:]):
        u = increment(odometry[a], odometry[b])
        if u == (0.0, 0.0, 0.0):
            continue
        e = increment(path[a], path[b])
        odo_chi2 += ((e[0] - u[0]) / so) ** 2 + ((e[1] - u[1]) / so) ** 2 + \
            (wrap(e[2] - u[2]) / sp) ** 2
        odo_values += 3
    sr, sb = args.std_range, math.radians(args.std_bearing_deg)
    offset = (args.sensor_pose[0], args.sensor_pose[1], math.radians(args.sensor_pose[2]))
    by_landmark = defaultdict(list)
    for stamp, lid, r, b in frames:
        by_landmark[lid].append((compose(path[stamp], offset), r, b))
    readings_chi2 = 0.0
    for lid, readings in by_landmark.items():
        readings_chi2 += best_landmark(readings, sr, sb, landmarks.get(lid))[1]
    return odo_chi2, readings_chi2, odo_values + 2 * len(frames)


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--readings", required=True, help="rawlog-edit's list of the readings")
    p.add_argument("--ids-from", help="the same readings listed with their landmark IDs")
    p.add_argument("--stamps", required=True,
                   help="scored stamps: the first column ('#' comments), as in a TUM file")
    p.add_argument("--odometry", required=True, help="the odometry path (TUM)")
    p.add_argument("--std-range", type=float, required=True, help="[m] range std")
    p.add_argument("--std-bearing-deg", type=float, required=True, help="[deg] bearing std")
    p.add_argument("--odometry-std-xy", type=float, required=True,
                   help="[m] std of each step's x and y increment")
    p.add_argument("--odometry-std-phi-deg", type=float, required=True,
                   help="[deg] std of each step's heading increment")
    p.add_argument("--landmarks", help="landmarks (id x y ...) whose positions start their fits "
                   "too: the true ones of a simulation")
    p.add_argument("--sensor-pose", type=float, nargs=3, default=(0.0, 0.0, 0.0),
                   metavar=("X", "Y", "YAW_DEG"), help="[m, m, deg] sensor on the robot")
    p.add_argument("paths", nargs="+", help="paths to score (TUM)")
    args = p.parse_args()
    for key in ("std_range", "std_bearing_deg", "odometry_std_xy", "odometry_std_phi_deg"):
        value = getattr(args, key)
        if not (math.isfinite(value) and value > 0):
            p.error(f"--{key.replace('_', '-')} {value}: must be a positive number")
    if not all(map(math.isfinite, args.sensor_pose)):
        p.error(f"--sensor-pose {' '.join(map(str, args.sensor_pose))}: must be finite numbers")
    try:
        stamps = read_stamps(args.stamps)
        if len(stamps) < 2:
            raise InputError(f"{args.stamps}: fewer than two stamps")
        readings = read_readings(args.readings)
        if args.ids_from:
            readings = with_ids_from(readings, args.readings, args.ids_from)
        if any(lid < 0 for _, lid, _, _ in readings):
            raise InputError(f"{args.ids_from or args.readings}: readings without a landmark ID "
                             "(-1)")
        scored = set(stamps)
        frames = [row for row in readings if row[0] in scored]
        if not frames:
            raise InputError(f"{args.readings}: no reading at a scored stamp")
        landmarks = read_landmarks(args.landmarks) if args.landmarks else {}
        odometry = read_tum(args.odometry)
        require_stamps(odometry, stamps, args.odometry)
        for name in args.paths:
            o, z, n = chi_square(read_tum(name), name, args, stamps, odometry, frames, landmarks)
            print(f"{name} {o + z:.3f} {o:.3f} {z:.3f} {n}")
    except (InputError, OSError) as e:
        print(f"range-bearing-path-fit: {e}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
