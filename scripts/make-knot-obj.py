#!/usr/bin/env python3
"""Writes scenes/assets/knot.obj: a (2,3) torus knot tube with positions, uvs and
normals but no tangents (so that the loader must compute them). Kept small; rerun
only to change the asset."""
import math
import pathlib

P, Q = 2, 3            # the knot winds P times around the axis, Q times through the hole
SEGMENTS, SIDES = 128, 10
TUBE = 0.18


def curve(t):
    r = 0.6 + 0.25 * math.cos(Q * t)
    return (r * math.cos(P * t), 0.25 * math.sin(Q * t), r * math.sin(P * t))


def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
def norm(a):
    l = math.sqrt(sum(x * x for x in a))
    return tuple(x / l for x in a)


lines = ["# (2,3) torus knot, written by scripts/make-knot-obj.py"]
verts = []
for i in range(SEGMENTS + 1):
    t = 2 * math.pi * i / SEGMENTS
    c = curve(t)
    tangent = norm(sub(curve(t + 1e-4), curve(t - 1e-4)))
    radial = norm((c[0], 0.0, c[2]))
    side = norm(cross(tangent, radial))
    up = cross(side, tangent)
    for j in range(SIDES + 1):
        a = 2 * math.pi * j / SIDES
        n = tuple(math.cos(a) * up[k] + math.sin(a) * side[k] for k in range(3))
        p = tuple(c[k] + TUBE * n[k] for k in range(3))
        lines.append("v %.5f %.5f %.5f" % p)
        lines.append("vt %.5f %.5f" % (i / SEGMENTS, j / SIDES))
        lines.append("vn %.4f %.4f %.4f" % n)
row = SIDES + 1
for i in range(SEGMENTS):
    for j in range(SIDES):
        a = i * row + j + 1
        b, c, d = a + row, a + 1, a + row + 1
        for tri in ((a, d, b), (a, c, d)):  # counter-clockwise from outside
            lines.append("f " + " ".join("%d/%d/%d" % (v, v, v) for v in tri))
out = pathlib.Path(__file__).resolve().parent.parent / "scenes" / "assets" / "knot.obj"
out.write_text("\n".join(lines) + "\n")
print(out, len(lines), "lines")
