#!/usr/bin/env python3
"""A straightforward NumPy version of formcam-dress's simulation of forming,
timed against the Rust one in the same run (not part of CI).

    python3 scripts/dress_numpy.py [JOB.toml] [--step 0.001] [--runs 3]

The same model as the crate (crates/formcam-dress): the gothic-arch profile,
the allowance as the profile offset by `depth` (arcs cut into chords of at most
step/2), the dresser's periphery as a polyline (corner arcs as chords of at
most step/2), the same two passes and steps; per step the wheel's contour
becomes min(g, d) with the crossings inserted and the removed area is the
integral of max(0, g - d). What is "straightforward" here: every step takes
the dresser's whole width as its range, evaluates both polylines there with
np.interp, and rebuilds the contour's arrays; the dresser's faces are steep
segments 1e-9 mm wide instead of vertical ones (np.interp needs increasing x).

The script runs the Rust example `dress_time` (cargo, release) on the same job
and step, compares the step areas and prints both times and their ratio.
"""

import argparse
import math
import os
import subprocess
import sys
import time
import tomllib

import numpy as np

LEAD_IN = 0.5
BIG = 1.0e9


# --- exact pieces: ("line", x0, y0, x1, y1) or ("arc", cx, cy, r, a0, a1) ---

def point(p, t):
    if p[0] == "line":
        _, x0, y0, x1, y1 = p
        return (x0 + (x1 - x0) * t, y0 + (y1 - y0) * t)
    _, cx, cy, r, a0, a1 = p
    a = a0 + (a1 - a0) * t
    return (cx + r * math.cos(a), cy + r * math.sin(a))


def length(p):
    if p[0] == "line":
        return math.hypot(p[3] - p[1], p[4] - p[2])
    return p[3] * abs(p[5] - p[4])


def reversed_piece(p):
    if p[0] == "line":
        return ("line", p[3], p[4], p[1], p[2])
    return ("arc", p[1], p[2], p[3], p[5], p[4])


def mirrored(p):
    if p[0] == "line":
        return ("line", -p[1], p[2], -p[3], p[4])
    return ("arc", -p[1], p[2], p[3], math.pi - p[4], math.pi - p[5])


def offset_left(p, d):
    if p[0] == "line":
        dx, dy = p[3] - p[1], p[4] - p[2]
        n = math.hypot(dx, dy)
        nx, ny = -dy / n * d, dx / n * d
        return ("line", p[1] + nx, p[2] + ny, p[3] + nx, p[4] + ny)
    r = p[3] - d if p[5] >= p[4] else p[3] + d
    return None if r < 0 else ("arc", p[1], p[2], r, p[4], p[5])


def steps(length_, h):
    return max(int(math.ceil(length_ / h - 1e-9)), 1)


def arc_polyline(cx, cy, r, a0, a1, chord):
    if r > 0:
        da = 2.0 * math.asin(min(chord / (2.0 * r), 1.0))
        n = max(int(math.ceil(abs(a1 - a0) / da - 1e-9)), 1)
    else:
        n = 1
    a = a0 + (a1 - a0) * (np.arange(n + 1) / n)
    return np.column_stack((cx + r * np.cos(a), cy + r * np.sin(a)))


# --- the profile, the allowance, the dresser, the path ---

class Profile:
    def __init__(self, w):
        rs, r1, r2, width = w["ball_radius"], w["r1"], w["r2"], w["width"]
        a = math.radians(w["contact_angle_deg"])
        tilt = math.radians(w["flank_tilt_deg"])
        a2 = math.radians(w.get("arc_angle_deg", 15.0))
        o1 = ((rs - r1) * math.cos(a), (rs - r1) * math.sin(a))
        self.apex_angle = math.acos(-o1[0] / r1)
        self.apex = (o1[0] + r1 * math.cos(self.apex_angle), o1[1] + r1 * math.sin(self.apex_angle))
        o2 = (o1[0] + (r1 + r2) * math.cos(a2), o1[1] + (r1 + r2) * math.sin(a2))
        fe = 1.5 * math.pi - tilt
        c = (o2[0] + r2 * math.cos(fe), o2[1] + r2 * math.sin(fe))
        half = width / 2.0
        self.half = half
        self.tilt = tilt
        self.d = (half, c[1] - (half - c[0]) * math.tan(tilt))
        self.right = [
            ("arc", o1[0], o1[1], r1, self.apex_angle, a2),
            ("arc", o2[0], o2[1], r2, math.pi + a2, fe),
            ("line", c[0], c[1], self.d[0], self.d[1]),
        ]

    def pieces(self):
        return [reversed_piece(mirrored(p)) for p in reversed(self.right)] + list(self.right)


def offset_contour(prof, depth, chord):
    pts = []

    def push(piece):
        if piece[0] == "line":
            seg = [(piece[1], piece[2]), (piece[3], piece[4])]
        else:
            seg = [tuple(q) for q in arc_polyline(*piece[1:], chord)]
        for q in seg[1 if pts else 0:]:
            x = max(pts[-1][0], q[0]) if pts else q[0]
            pts.append((x, q[1]))

    pieces = prof.pieces()
    for i, piece in enumerate(pieces):
        if i == len(pieces) // 2:
            a = prof.apex_angle
            push(("arc", prof.apex[0], prof.apex[1], depth, math.pi - a, a))
        off = offset_left(piece, depth)
        if off is not None:
            push(off)
    p = np.array(pts)
    x0, x1 = -prof.half, prof.half
    inner = p[(p[:, 0] > x0) & (p[:, 0] < x1)]
    y0 = np.interp(x0, p[:, 0], p[:, 1])
    y1 = np.interp(x1, p[:, 0], p[:, 1])
    return np.vstack(([x0, y0], inner, [x1, y1]))


def outline(b, rr, rl, side, chord):
    flat = b - rl - rr
    if side == "right":
        cl, cr = (0.0, 0.0), (flat, rl - rr)
    else:
        cl, cr = (-flat, rr - rl), (0.0, 0.0)
    left = arc_polyline(cl[0], cl[1], rr, math.pi, 1.5 * math.pi, chord)
    right = arc_polyline(cr[0], cr[1], rl, 1.5 * math.pi, 2.0 * math.pi, chord)
    if flat <= 0:
        right = right[1:]
    return np.vstack((left, right))


def right_half(prof, r, h):
    d = prof.d
    out = [("approach", ("line", d[0] + r + LEAD_IN, d[1], d[0] + r, d[1]), None)]
    out.append(("edge", ("arc", d[0], d[1], r, 0.0, math.pi / 2 - prof.tilt),
                ("arc", d[0], d[1], 0.0, 0.0, math.pi / 2 - prof.tilt)))
    for piece in reversed(prof.right):
        inward = reversed_piece(piece)
        path = offset_left(inward, -r)
        if path is not None:
            out.append(("piece", path, inward))
    ax, ay = prof.apex
    out.append(("apex", ("arc", ax, ay, r, prof.apex_angle, math.pi / 2),
                ("arc", ax, ay, 0.0, prof.apex_angle, math.pi / 2)))
    out = [s for s in out if length(s[1]) > 1e-12]
    res = []
    for kind, path, under in out:
        n = 1 if kind == "approach" else steps(max(length(path), length(under) if under else 0.0), h)
        res.append((path, n))
    return res


def passes(prof, b, rr, rl, h):
    result = []
    for side, r in (("right", rr), ("left", rl)):
        stretches = right_half(prof, r, h)
        if side == "left":
            stretches = [(mirrored(p), n) for p, n in stretches]
        centres = []
        for path, n in stretches:
            for i in range(0 if not centres else 1, n + 1):
                centres.append(point(path, i / n))
        result.append((side, np.array(centres)))
    return result


# --- the simulation ---

def simulate(contour, passes_, outlines):
    X, Y = contour[:, 0].copy(), contour[:, 1].copy()
    areas = []
    for side, centres in passes_:
        T = outlines[side]
        for c in centres[1:]:
            tx = T[:, 0] + c[0]
            ty = T[:, 1] + c[1]
            fx = np.concatenate(([tx[0] - 1e-9], tx, [tx[-1] + 1e-9]))
            fy = np.concatenate(([BIG], ty, [BIG]))
            lo, hi = max(fx[0], X[0]), min(fx[-1], X[-1])
            if lo > hi:
                areas.append(0.0)
                continue
            i0 = np.searchsorted(X, lo, side="left")
            i1 = np.searchsorted(X, hi, side="right")
            gx = X[i0:i1]
            tsel = fx[(fx >= lo) & (fx <= hi)]
            xs = np.union1d(gx, tsel)
            gy = np.interp(xs, X, Y)
            tyv = np.interp(xs, fx, fy, left=BIG, right=BIG)
            diff = gy - tyv
            d0, d1 = diff[:-1], diff[1:]
            w = np.diff(xs)
            both = (d0 >= 0) & (d1 >= 0)
            cross = ((d0 > 0) & (d1 < 0)) | ((d0 < 0) & (d1 > 0))
            area = np.sum(0.5 * (d0 + d1)[both] * w[both])
            t = d0[cross] / (d0[cross] - d1[cross])
            wc = w[cross]
            area += np.sum(np.where(d0[cross] > 0, 0.5 * d0[cross] * t * wc,
                                    0.5 * d1[cross] * (1.0 - t) * wc))
            areas.append(float(area))
            if not np.any(diff > 0):
                continue
            xc = xs[:-1][cross] + t * wc
            yc = gy[:-1][cross] + t * (gy[1:][cross] - gy[:-1][cross])
            is_g = np.isin(xs, gx)
            is_t = np.isin(xs, tsel)
            ends = (xs == X[0]) | (xs == X[-1])
            keep = (is_g & (gy <= tyv)) | (is_t & (tyv < gy)) | ends
            nx = np.concatenate((xs[keep], xc))
            ny = np.concatenate((np.minimum(gy, tyv)[keep], yc))
            # In the order of the walk: a crossing after the breakpoint that
            # opens its interval (x alone may tie at a vertical step).
            rank = np.concatenate((np.flatnonzero(keep), np.flatnonzero(cross) + 0.5))
            order = np.argsort(rank, kind="stable")
            X = np.concatenate((X[:i0], nx[order], X[i1:]))
            Y = np.concatenate((Y[:i0], ny[order], Y[i1:]))
            # np.interp needs x increasing: a vertical step (a face's cut)
            # becomes one ulp wide.
            for i in np.flatnonzero(np.diff(X) <= 0)[::-1]:
                X[i] = np.nextafter(X[i + 1], -np.inf)
    return np.array(areas), np.column_stack((X, Y))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("job", nargs="?", default=os.path.join(root, "examples", "dress-ballscrew-nut.toml"))
    ap.add_argument("--step", type=float, default=0.001)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--no-rust", action="store_true", help="time the NumPy version only")
    args = ap.parse_args()

    with open(args.job, "rb") as f:
        job = tomllib.load(f)
    w, dr, pr = job["wheel"], job["dresser"], job["process"]
    h = args.step
    chord = h / 2.0
    t0 = time.perf_counter()
    prof = Profile(w)
    start = offset_contour(prof, pr["depth"], chord)
    b, rl, rr = dr["width"], dr["corner_radius_left"], dr["corner_radius_right"]
    outs = {s: outline(b, rr, rl, s, chord) for s in ("right", "left")}
    path = passes(prof, b, rr, rl, h)
    t_setup = time.perf_counter() - t0
    best = math.inf
    for _ in range(max(args.runs, 1)):
        t1 = time.perf_counter()
        areas, final = simulate(start, path, outs)
        best = min(best, time.perf_counter() - t1)
    base = final[:, 1].min()
    area_under = lambda c: float(np.sum(np.diff(c[:, 0]) * ((c[:-1, 1] - base) + (c[1:, 1] - base)) * 0.5))
    between = area_under(start) - area_under(final)
    numpy_s = best + t_setup
    print(f"numpy: step {h} mm, {len(areas)} steps, final contour {len(final)} vertices")
    print(f"numpy: removed {areas.sum():.12e} mm2, between the contours {between:.12e} mm2 "
          f"(rel {(areas.sum() - between) / between:.2e})")
    print(f"numpy: {numpy_s:.3f} s (setup {t_setup:.3f} s, simulation {best:.3f} s, best of {args.runs})")
    if args.no_rust:
        return 0

    areas_csv = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"dress_rust_areas_{os.getpid()}.csv")
    cmd = ["cargo", "run", "-q", "--release", "-p", "formcam-dress", "--example", "dress_time", "--",
           args.job, str(h), str(max(args.runs, 1)), areas_csv]
    out = subprocess.run(cmd, cwd=root, capture_output=True, text=True)
    if out.returncode != 0:
        print(out.stderr, file=sys.stderr)
        return 1
    fields = out.stdout.split()
    rust_s = float(fields[fields.index("rust_seconds") + 1])
    rust = np.loadtxt(areas_csv, skiprows=1)
    os.remove(areas_csv)
    if rust.shape != areas.shape:
        print(f"different step counts: rust {rust.shape}, numpy {areas.shape}", file=sys.stderr)
        return 1
    diff = np.abs(rust - areas)
    print(f"rust:  {out.stdout.strip()}")
    print(f"same simulation: step areas differ by at most {diff.max():.2e} mm2 "
          f"(largest step area {rust.max():.2e} mm2), totals by {abs(rust.sum() - areas.sum()):.2e} mm2")
    print(f"rust {rust_s:.3f} s (whole dressing: profile, path, forming, feed, program), "
          f"numpy {numpy_s:.3f} s: numpy / rust = {numpy_s / rust_s:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
