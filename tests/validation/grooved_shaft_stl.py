#!/usr/bin/env python3
"""The validation's own part: a stepped shaft with a groove narrower than the shot, written as a
binary STL in millimetres (python3's standard library only).

    python3 grooved_shaft_stl.py OUT.stl

The shaft lies along x, centred at the origin: radius 5 mm from x = -25 to 10 mm with a groove
1.6 mm wide and 1.5 mm deep at x = 0 (a 2 mm shot touches neither its bottom nor the lower part
of its walls), a shoulder at x = 10 mm, radius 7 mm to x = 25 mm. 96 segments around; flat ends.
"""
import math
import struct
import sys

SEGMENTS = 96
# The profile (x, r) in mm, from the left end's centre to the right end's; the triangles are wound
# so that their normals point out of the solid (a positive volume: 4990 mm3).
PROFILE = [(-25.0, 0.0), (-25.0, 5.0), (-0.8, 5.0), (-0.8, 3.5), (0.8, 3.5), (0.8, 5.0), (10.0, 5.0), (10.0, 7.0), (25.0, 7.0), (25.0, 0.0)]
# Long spans are split so that no triangle is much longer than it is wide (2 mm steps).
STEP_MM = 2.0


def refined(profile):
    points = [profile[0]]
    for (x0, r0), (x1, r1) in zip(profile, profile[1:]):
        n = max(1, math.ceil(math.hypot(x1 - x0, r1 - r0) / STEP_MM))
        points += [(x0 + (x1 - x0) * k / n, r0 + (r1 - r0) * k / n) for k in range(1, n + 1)]
    return points


def ring(x, r, k):
    a = 2.0 * math.pi * k / SEGMENTS
    return (x, r * math.cos(a), r * math.sin(a))


def triangles():
    profile = refined(PROFILE)
    for (x0, r0), (x1, r1) in zip(profile, profile[1:]):
        for k in range(SEGMENTS):
            a, b = ring(x0, r0, k), ring(x0, r0, k + 1)
            c, d = ring(x1, r1, k), ring(x1, r1, k + 1)
            if r0 > 0.0:
                yield (a, b, c)
            if r1 > 0.0:
                yield (b, d, c)


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    return tuple(x / length for x in n)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    tris = list(triangles())
    with open(sys.argv[1], "wb") as f:
        f.write(b"grooved shaft (peensim validation), mm".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", *normal(*t)))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


if __name__ == "__main__":
    main()
