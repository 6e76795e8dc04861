#!/usr/bin/env python3
"""Writes machines/meshes/chuck-flange.stl, the mesh solid of the shipped
4-axis winder: the flange that holds the chuck on the spindle's nose.

The flange's own frame, mm, z along the spindle's axis: a disc of radius
150 from z = 0 to 30 (its face z = 30 against the chuck), a hub of radius
80 from z = -40 to 0 and eight hexagonal bolt heads (circumradius 11,
10 high) on the bolt circle of radius 118 on the disc's back face. Every
piece is convex and every triangle faces away from its piece's centre, so
the normals point out of the solid. Binary STL, 528 triangles.

    python3 scripts/chuck_flange_stl.py [OUT]
"""

import math
import struct
import sys
from pathlib import Path

SEGMENTS = 48
DISC = (150.0, 0.0, 30.0)  # radius, z from, z to
HUB = (80.0, -40.0, 0.0)
BOLTS = 8
BOLT_CIRCLE = 118.0
BOLT_RADIUS = 11.0
BOLT_HEIGHT = 10.0


def ring(radius, z, n, centre=(0.0, 0.0), phase=0.0):
    """`n` points on a circle about `centre` at height `z`."""
    return [
        (
            centre[0] + radius * math.cos(phase + 2 * math.pi * k / n),
            centre[1] + radius * math.sin(phase + 2 * math.pi * k / n),
            z,
        )
        for k in range(n)
    ]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def outward(tri, inside):
    """The triangle ordered so that its normal points away from `inside`,
    with its unit normal."""
    a, b, c = tri
    n = cross(sub(b, a), sub(c, a))
    if dot(n, sub(a, inside)) < 0:
        b, c = c, b
        n = (-n[0], -n[1], -n[2])
    length = math.sqrt(dot(n, n))
    return (a, b, c), (n[0] / length, n[1] / length, n[2] / length)


def prism(bottom, top, inside, caps=(True, True), inner=None):
    """The sides of the prism between the rings `bottom` and `top`, and its
    caps (fanned from the centre, or an annulus down to the ring `inner`
    for the bottom cap)."""
    n = len(bottom)
    tris = []
    for k in range(n):
        j = (k + 1) % n
        tris += [(bottom[k], bottom[j], top[j]), (bottom[k], top[j], top[k])]
    centre = lambda ring_: (
        sum(p[0] for p in ring_) / n,
        sum(p[1] for p in ring_) / n,
        ring_[0][2],
    )
    if caps[0]:
        if inner is None:
            c = centre(bottom)
            tris += [(c, bottom[k], bottom[(k + 1) % n]) for k in range(n)]
        else:
            for k in range(n):
                j = (k + 1) % n
                tris += [(inner[k], bottom[k], bottom[j]), (inner[k], bottom[j], inner[j])]
    if caps[1]:
        c = centre(top)
        tris += [(c, top[k], top[(k + 1) % n]) for k in range(n)]
    return [outward(t, inside) for t in tris]


def flange():
    r, z0, z1 = DISC
    disc = prism(
        ring(r, z0, SEGMENTS),
        ring(r, z1, SEGMENTS),
        (0.0, 0.0, (z0 + z1) / 2),
        inner=ring(HUB[0], z0, SEGMENTS),
    )
    r, z0, z1 = HUB
    hub = prism(
        ring(r, z0, SEGMENTS),
        ring(r, z1, SEGMENTS),
        (0.0, 0.0, (z0 + z1) / 2),
        caps=(True, False),
    )
    bolts = []
    for b in range(BOLTS):
        a = 2 * math.pi * (b + 0.5) / BOLTS
        c = (BOLT_CIRCLE * math.cos(a), BOLT_CIRCLE * math.sin(a))
        bolts += prism(
            ring(BOLT_RADIUS, DISC[1] - BOLT_HEIGHT, 6, c, a),
            ring(BOLT_RADIUS, DISC[1], 6, c, a),
            (c[0], c[1], DISC[1] - BOLT_HEIGHT / 2),
            caps=(True, False),
        )
    return disc + hub + bolts


def write_stl(path, tris):
    head = b"formcam chuck flange (scripts/chuck_flange_stl.py), mm".ljust(80, b" ")
    out = bytearray(head)
    out += struct.pack("<I", len(tris))
    for (a, b, c), n in tris:
        out += struct.pack("<12fH", *n, *a, *b, *c, 0)
    Path(path).write_bytes(bytes(out))


if __name__ == "__main__":
    root = Path(__file__).resolve().parent.parent
    out = sys.argv[1] if len(sys.argv) > 1 else root / "machines" / "meshes" / "chuck-flange.stl"
    tris = flange()
    write_stl(out, tris)
    print(f"{out}: {len(tris)} triangles")
