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
With --most-probable, also the path and landmarks of least chi-square, the pose at the first scored
stamp held at the first path's (the true start, for the true path) and the robot standing where
its odometry increment is exactly zero: the most probable path given the data and the
associations (PathProblem), written as a TUM file and scored after the others.
Output: a line per path, "PATH chi2 odometry_chi2 readings_chi2 measured_values".
"""
import argparse
import math
import os
import sys
from collections import defaultdict, namedtuple
from decimal import Decimal, InvalidOperation

MICROSECOND = Decimal("0.000001")


class InputError(Exception):
    pass


class SingularSystem(ArithmeticError):
    """Normal equations that are not positive definite (to rounding)."""


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


NoiseModel = namedtuple("NoiseModel", "so sp sr sb offset")  # m, rad; offset: sensor on robot


def noise_model(args):
    """The odometry and reading std and the sensor pose of the command line, in m and rad."""
    return NoiseModel(args.odometry_std_xy, math.radians(args.odometry_std_phi_deg),
                      args.std_range, math.radians(args.std_bearing_deg),
                      (args.sensor_pose[0], args.sensor_pose[1], math.radians(args.sensor_pose[2])))


def odometry_residuals(a, b, u, so, sp):
    """Normalised x, y and heading residuals of the increment from pose a to b against u."""
    e = increment(a, b)
    return (e[0] - u[0]) / so, (e[1] - u[1]) / so, wrap(e[2] - u[2]) / sp


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


def mat_mul(a, b):
    """a b of matrices as lists of rows."""
    cols = list(zip(*b))
    return [[sum(x * y for x, y in zip(row, col)) for col in cols] for row in a]


def mat_sub(a, b):
    return [[x - y for x, y in zip(ra, rb)] for ra, rb in zip(a, b)]


def transpose(a):
    return [list(col) for col in zip(*a)]


def cholesky_solve(a, b):
    """x with a x = b, a symmetric positive definite (lists)."""
    n = len(a)
    low = [[0.0] * n for _ in range(n)]
    for i in range(n):
        for j in range(i + 1):
            v = a[i][j] - sum(low[i][k] * low[j][k] for k in range(j))
            if i == j:
                if not v > 0:
                    raise SingularSystem()
                low[i][i] = math.sqrt(v)
            else:
                low[i][j] = v / low[j][j]
    y = []
    for i in range(n):
        y.append((b[i] - sum(low[i][k] * y[k] for k in range(i))) / low[i][i])
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (y[i] - sum(low[k][i] * x[k] for k in range(i + 1, n))) / low[i][i]
    return x


def inverse3(m):
    (a, b, c), (d, e, f), (g, h, i) = m
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    if not abs(det) > 0:
        raise SingularSystem()
    return [[(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
            [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
            [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det]]


class PathProblem:
    """The path and landmarks that minimise the chi-square of chi_square(), the pose at the first
    scored stamp held at its start value and the poses of steps whose odometry is exactly zero
    tied to the pose before (the robot stands). Gauss-Newton with Levenberg-Marquardt damping;
    the normal equations are solved by eliminating the poses, whose block is block-tridiagonal
    (odometry ties consecutive poses only), then the landmarks."""

    def __init__(self, model, stamps, odometry, frames):
        self.so, self.sp, self.sr, self.sb, self.offset = model
        self.group = {stamps[0]: -1}  # pose variable of each stamp; -1: held at the start
        self.steps = []  # (group before, group after, odometry increment)
        groups = 0
        for a, b in zip(stamps, stamps[1:]):
            u = increment(odometry[a], odometry[b])
            if u == (0.0, 0.0, 0.0):
                self.group[b] = self.group[a]
            else:
                self.group[b] = groups
                self.steps.append((self.group[a], groups, u))
                groups += 1
        self.poses = groups
        self.ids = sorted({lid for _, lid, _, _ in frames})  # landmark variable j: ids[j]
        point = {lid: j for j, lid in enumerate(self.ids)}
        self.readings = [(self.group[s], point[lid], r, b) for s, lid, r, b in frames]

    @staticmethod
    def pose_of(group, start, poses):
        """The pose of a pose variable (self.group's values): the start for -1."""
        return start if group < 0 else poses[group]

    def cost(self, start, poses, points):
        pose = lambda g: self.pose_of(g, start, poses)
        total = 0.0
        for ga, gb, u in self.steps:
            total += sum(v * v for v in odometry_residuals(pose(ga), pose(gb), u, self.so,
                                                            self.sp))
        for g, j, r, b in self.readings:
            er, eb, _, _ = residuals(points[j], compose(pose(g), self.offset), r, b, self.sr,
                                     self.sb)
            total += er * er + eb * eb
        return total

    def normal_equations(self, start, poses, points):
        """Diagonal and super-diagonal 3x3 blocks of the poses, the pose-landmark blocks
        {(pose, landmark): 3x2}, the landmarks' 2x2 blocks, and the gradient (poses, landmarks)."""
        n, m = self.poses, len(points)
        diag = [[[0.0] * 3 for _ in range(3)] for _ in range(n)]
        upper = [[[0.0] * 3 for _ in range(3)] for _ in range(n)]
        cross = defaultdict(lambda: [[0.0] * 2 for _ in range(3)])
        lm = [[[0.0] * 2 for _ in range(2)] for _ in range(m)]
        gp = [[0.0] * 3 for _ in range(n)]
        gl = [[0.0] * 2 for _ in range(m)]
        pose = lambda g: self.pose_of(g, start, poses)
        w = (1 / self.so, 1 / self.so, 1 / self.sp)
        for ga, gb, u in self.steps:
            a, b = pose(ga), pose(gb)
            res = odometry_residuals(a, b, u, self.so, self.sp)
            c, s = math.cos(a[2]), math.sin(a[2])
            dx, dy = b[0] - a[0], b[1] - a[1]
            ja = [[-c * w[0], -s * w[0], (-s * dx + c * dy) * w[0]],
                  [s * w[1], -c * w[1], (-c * dx - s * dy) * w[1]], [0.0, 0.0, -w[2]]]
            jb = [[c * w[0], s * w[0], 0.0], [-s * w[1], c * w[1], 0.0], [0.0, 0.0, w[2]]]
            for g, jac in ((ga, ja), (gb, jb)):
                if g < 0:
                    continue
                for r in range(3):
                    gp[g][r] += sum(jac[k][r] * res[k] for k in range(3))
                    for q in range(3):
                        diag[g][r][q] += sum(jac[k][r] * jac[k][q] for k in range(3))
            if ga >= 0:  # gb = ga + 1
                for r in range(3):
                    for q in range(3):
                        upper[ga][r][q] += sum(ja[k][r] * jb[k][q] for k in range(3))
        ox, oy, _ = self.offset
        for g, j, r, b in self.readings:
            p = pose(g)
            sensor = compose(p, self.offset)
            er, eb, jr, jb = residuals(points[j], sensor, r, b, self.sr, self.sb)
            res = (er, eb)
            jl = (jr, jb)
            c, s = math.cos(p[2]), math.sin(p[2])
            dsx, dsy = -s * ox - c * oy, c * ox - s * oy  # sensor position w.r.t. heading
            jp = ((-jr[0], -jr[1], -jr[0] * dsx - jr[1] * dsy),
                  (-jb[0], -jb[1], -jb[0] * dsx - jb[1] * dsy - 1 / self.sb))
            for q in range(2):
                gl[j][q] += jl[0][q] * res[0] + jl[1][q] * res[1]
                for t in range(2):
                    lm[j][q][t] += jl[0][q] * jl[0][t] + jl[1][q] * jl[1][t]
            if g < 0:
                continue
            block = cross[(g, j)]
            for q in range(3):
                gp[g][q] += jp[0][q] * res[0] + jp[1][q] * res[1]
                for t in range(3):
                    diag[g][q][t] += jp[0][q] * jp[0][t] + jp[1][q] * jp[1][t]
                for t in range(2):
                    block[q][t] += jp[0][q] * jl[0][t] + jp[1][q] * jl[1][t]
        return diag, upper, cross, lm, gp, gl

    def step(self, equations, damping):
        """The damped Gauss-Newton step (poses, landmarks)."""
        diag, upper, cross, lm, gp, gl = equations
        n, m = self.poses, len(lm)
        width = 2 * m + 1  # columns: the pose-landmark blocks, then the gradient
        rhs = [[[0.0] * width for _ in range(3)] for _ in range(n)]
        for (g, j), block in cross.items():
            for q in range(3):
                rhs[g][q][2 * j:2 * j + 2] = block[q]
        for g in range(n):
            for q in range(3):
                rhs[g][q][-1] = gp[g][q]
        damped = [[[v * (1 + damping) if q == t else v for t, v in enumerate(row)]
                   for q, row in enumerate(d)] for d in diag]
        # block-tridiagonal elimination: x = poses⁻¹ rhs
        inv, red = [None] * n, [None] * n
        for g in range(n):
            d, r = damped[g], rhs[g]
            if g > 0:
                lower = transpose(upper[g - 1])
                li = mat_mul(lower, inv[g - 1])
                d = mat_sub(d, mat_mul(li, upper[g - 1]))
                r = mat_sub(r, mat_mul(li, red[g - 1]))
            inv[g], red[g] = inverse3(d), r
        x = [None] * n
        for g in reversed(range(n)):
            r = red[g]
            if g + 1 < n:
                r = mat_sub(r, mat_mul(upper[g], x[g + 1]))
            x[g] = mat_mul(inv[g], r)
        # the landmarks' reduced system
        size = 2 * m
        s = [[0.0] * size for _ in range(size)]
        b = [0.0] * size
        for j in range(m):
            for q in range(2):
                for t in range(2):
                    s[2 * j + q][2 * j + t] = lm[j][q][t] * ((1 + damping) if q == t else 1)
                b[2 * j + q] = -gl[j][q]
        for (g, j), block in cross.items():
            for q in range(2):
                row = s[2 * j + q]
                for k in range(3):
                    v = block[k][q]
                    if v:
                        xr = x[g][k]
                        for col in range(size):
                            row[col] -= v * xr[col]
                        b[2 * j + q] += v * xr[-1]
        dl = cholesky_solve(s, b)
        dp = [[-x[g][q][-1] - sum(x[g][q][c] * dl[c] for c in range(size)) for q in range(3)]
              for g in range(n)]
        return dp, [(dl[2 * j], dl[2 * j + 1]) for j in range(m)]

    def solve(self, start, poses, points):
        """Levenberg-Marquardt from poses (one per pose variable) and points: the minimum's
        (poses, points, chi-square)."""
        cost = self.cost(start, poses, points)
        damping = 1e-4
        for _ in range(100):
            equations = self.normal_equations(start, poses, points)
            while True:
                try:
                    dp, dl = self.step(equations, damping)
                    trial_poses = [(p[0] + d[0], p[1] + d[1], wrap(p[2] + d[2]))
                                   for p, d in zip(poses, dp)]
                    trial_points = [(p[0] + d[0], p[1] + d[1]) for p, d in zip(points, dl)]
                    trial_cost = self.cost(start, trial_poses, trial_points)
                except SingularSystem:  # rounding, e.g. a landmark at the sensor: damp more
                    trial_cost = math.inf
                if trial_cost < cost:
                    break
                damping *= 10
                if damping > 1e8:
                    return poses, points, cost
            poses, points, decrease = trial_poses, trial_points, cost - trial_cost
            cost, damping = trial_cost, max(damping / 10, 1e-9)
            if decrease < 1e-10 * cost:
                break
        return poses, points, cost


def landmark_fits(path, model, frames, landmarks):
    """Each landmark's best_landmark fit (point, chi-square) to its readings from path."""
    by_landmark = defaultdict(list)
    for stamp, lid, r, b in frames:
        by_landmark[lid].append((compose(path[stamp], model.offset), r, b))
    return {lid: best_landmark(readings, model.sr, model.sb, landmarks.get(lid))
            for lid, readings in by_landmark.items()}


def chi_square(path, name, model, stamps, odometry, frames, landmarks):
    require_stamps(path, stamps, name)
    so, sp = model.so, model.sp
    odo_chi2, odo_values = 0.0, 0
    for a, b in zip(stamps, stamps[1:]):
        u = increment(odometry[a], odometry[b])
        if u == (0.0, 0.0, 0.0):
            continue
        odo_chi2 += sum(v * v for v in odometry_residuals(path[a], path[b], u, so, sp))
        odo_values += 3
    readings_chi2 = sum(fit[1] for fit in landmark_fits(path, model, frames, landmarks).values())
    return odo_chi2, readings_chi2, odo_values + 2 * len(frames)


def write_most_probable(args, model, stamps, odometry, frames, landmarks):
    """PathProblem's path started from the first path given and each landmark's fit along it,
    written to args.most_probable (TUM, a pose per scored stamp)."""
    first = read_tum(args.paths[0])
    require_stamps(first, stamps, args.paths[0])
    problem = PathProblem(model, stamps, odometry, frames)
    poses = [None] * problem.poses
    for stamp in stamps:
        g = problem.group[stamp]
        if g >= 0 and poses[g] is None:
            poses[g] = first[stamp]
    fits = landmark_fits(first, model, frames, landmarks)
    points = [fits[lid][0] for lid in problem.ids]
    start = first[stamps[0]]
    poses, _, _ = problem.solve(start, poses, points)
    tmp = args.most_probable + ".tmp"
    with open(tmp, "w") as f:
        f.write("# timestamp x y z qx qy qz qw\n")
        for stamp in stamps:
            x, y, a = problem.pose_of(problem.group[stamp], start, poses)
            f.write(f"{stamp} {x:.9f} {y:.9f} 0 0 0 {math.sin(a / 2):.9f} {math.cos(a / 2):.9f}\n")
    os.replace(tmp, args.most_probable)


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
    p.add_argument("--most-probable", metavar="OUT.tum",
                   help="also write the path of least chi-square, its pose at the first scored "
                   "stamp held at the first path's and the poses of steps whose odometry is "
                   "zero at the pose before, started from the first path (TUM), and score it")
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
        model = noise_model(args)
        names = list(args.paths)
        if args.most_probable:
            write_most_probable(args, model, stamps, odometry, frames, landmarks)
            names.append(args.most_probable)
        for name in names:
            o, z, n = chi_square(read_tum(name), name, model, stamps, odometry, frames, landmarks)
            print(f"{name} {o + z:.3f} {o:.3f} {z:.3f} {n}")
    except (InputError, OSError) as e:
        print(f"range-bearing-path-fit: {e}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
