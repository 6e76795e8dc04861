#!/usr/bin/env python3
"""The correction of 10^6 raster nodes against a 200 x 200 grid, written
straightforwardly with NumPy/SciPy (cKDTree over facet centres, vectorised
projected Newton on the bilinear patches, one step to a neighbour facet
where the foot lands on an edge), timed in the same run as formcam's Rust
version of the same case (`cargo run --release -p formcam-correct --example
correct_1e6`). Needs numpy and scipy (pip install numpy scipy).

Both sides time the same span: from the measured grid and the nodes in
memory (building them is not timed) to every node's displacement, the
facet centres and the k-d tree included; both bilinear. Each prints its
wall time and its CPU time over that span (all threads: NumPy's one,
formcam's pool); on a machine shared with other work the CPU times are
the steadier comparison, the wall times the one a user sees.

Usage: python3 scripts/correct_numpy.py
"""
import subprocess
import time

import numpy as np
from scipy.spatial import cKDTree

N, M = 200, 1000


def height(x, y):
    return (x - 200.0) ** 2 / 2400.0 + (y - 150.0) ** 2 / 1800.0


def warp(x, y):
    return 0.4 * np.sin(np.pi * x / 400.0) * np.sin(np.pi * y / 300.0)


def case():
    j, i = np.meshgrid(np.arange(N), np.arange(N), indexing="ij")
    x = 400.0 * j / (N - 1)
    y = 300.0 * i / (N - 1)
    P = np.stack([x, y, height(x, y)], axis=-1)  # [section j, point i, 3]
    D = np.zeros_like(P)
    D[..., 2] = warp(x, y)
    k = np.arange(M)[:, None]
    ii = np.arange(M)[None, :]
    ii = np.where(k % 2 == 0, ii, M - 1 - ii)
    nx = 400.0 * (ii + 0.5) / M
    ny = np.broadcast_to(300.0 * (k + 0.5) / M, nx.shape)
    nodes = np.stack([nx, ny, height(nx, ny)], axis=-1).reshape(-1, 3)
    return P, D, nodes


def corners(A, fi, fj):
    return A[fj, fi], A[fj, fi + 1], A[fj + 1, fi], A[fj + 1, fi + 1]


def newton(P, fi, fj, p, iters=12):
    p00, p10, p01, p11 = corners(P, fi, fj)
    s = np.full(len(p), 0.5)
    t = np.full(len(p), 0.5)
    e_st = p00 - p10 - p01 + p11
    for _ in range(iters):
        e0 = p10 - p00
        e1 = p11 - p01
        f0 = p00 + s[:, None] * e0
        f1 = p01 + s[:, None] * e1
        ft = f1 - f0
        f = f0 + t[:, None] * ft
        fs = e0 + t[:, None] * (e1 - e0)
        r = f - p
        gs = np.einsum("ij,ij->i", r, fs)
        gt = np.einsum("ij,ij->i", r, ft)
        hss = np.einsum("ij,ij->i", fs, fs)
        htt = np.einsum("ij,ij->i", ft, ft)
        hst = np.einsum("ij,ij->i", fs, ft) + np.einsum("ij,ij->i", r, e_st)
        det = hss * htt - hst * hst
        ds = (-gs * htt + gt * hst) / det
        dt = (-gt * hss + gs * hst) / det
        s = np.clip(s + ds, 0.0, 1.0)
        t = np.clip(t + dt, 0.0, 1.0)
    return s, t


def correct(P, D, nodes, tree):
    nf = N - 1
    _, idx = tree.query(nodes)
    fj, fi = idx // nf, idx % nf
    s, t = newton(P, fi, fj, nodes)
    # One step to the neighbour where the foot sits on an inner edge.
    di = np.where((s <= 0) & (fi > 0), -1, np.where((s >= 1) & (fi < nf - 1), 1, 0))
    dj = np.where((t <= 0) & (fj > 0), -1, np.where((t >= 1) & (fj < nf - 1), 1, 0))
    move = (di != 0) | (dj != 0)
    if move.any():
        fi2, fj2 = fi[move] + di[move], fj[move] + dj[move]
        s2, t2 = newton(P, fi2, fj2, nodes[move])
        fi[move], fj[move], s[move], t[move] = fi2, fj2, s2, t2
    d00, d10, d01, d11 = corners(D, fi, fj)
    s, t = s[:, None], t[:, None]
    d = (1 - s) * (1 - t) * d00 + s * (1 - t) * d10 + (1 - s) * t * d01 + s * t * d11
    return -d


def main():
    P, D, nodes = case()
    t0, c0 = time.perf_counter(), time.process_time()
    nf = N - 1
    centres = 0.25 * (P[:-1, :-1] + P[:-1, 1:] + P[1:, :-1] + P[1:, 1:])
    tree = cKDTree(centres.reshape(-1, 3))
    disp = correct(P, D, nodes, tree)
    py = time.perf_counter() - t0
    py_cpu = time.process_time() - c0
    py_sum = float(disp[:, 2].sum())
    out = subprocess.run(
        ["cargo", "run", "--quiet", "--release", "-p", "formcam-correct", "--example", "correct_1e6"],
        check=True, capture_output=True, text=True,
    ).stdout.split()
    rs, rs_sum, rs_cpu = float(out[0]), float(out[1]), float(out[2])
    print(f"nodes {len(nodes)}, grid {N}x{N} ({nf * nf} facets)")
    print(f"numpy/scipy: {py:.3f} s (cpu {py_cpu:.3f} s)   checksum {py_sum:.6f}")
    print(f"formcam:     {rs:.3f} s (cpu {rs_cpu:.3f} s)   checksum {rs_sum:.6f}")
    print(
        f"ratio numpy/formcam: {py / rs:.1f}x wall, {py_cpu / rs_cpu:.1f}x cpu; "
        f"checksums differ by {abs(py_sum - rs_sum):.2e} mm"
    )


if __name__ == "__main__":
    main()
