#!/usr/bin/env python3
"""Writes assets/uv-sphere.obj: a unit UV sphere of 20 segments and 10 rings (360 triangles),
the small input the firmware remeshes. Its poles carry valence-20 fans of slivers, its
rings uneven edge lengths: what isotropic remeshing exists to fix.

    python3 scripts/uv-sphere.py > assets/uv-sphere.obj
"""
import math

SEGMENTS, RINGS = 20, 10


def ring(i, j):
    """Vertex index (0-based) of ring i (1..RINGS-1), segment j (wraps)."""
    return 1 + (i - 1) * SEGMENTS + j % SEGMENTS


vertices = [(0.0, 1.0, 0.0)]
for i in range(1, RINGS):
    theta = math.pi * i / RINGS
    for j in range(SEGMENTS):
        phi = 2 * math.pi * j / SEGMENTS
        vertices.append((math.sin(theta) * math.cos(phi), math.cos(theta),
                         math.sin(theta) * math.sin(phi)))
vertices.append((0.0, -1.0, 0.0))
south = len(vertices) - 1

# Counter-clockwise seen from outside.
faces = [(0, ring(1, j + 1), ring(1, j)) for j in range(SEGMENTS)]
for i in range(1, RINGS - 1):
    for j in range(SEGMENTS):
        a, b = ring(i, j), ring(i, j + 1)
        c, d = ring(i + 1, j), ring(i + 1, j + 1)
        faces += [(a, b, d), (a, d, c)]
faces += [(south, ring(RINGS - 1, j), ring(RINGS - 1, j + 1)) for j in range(SEGMENTS)]

print(f"# unit UV sphere, {SEGMENTS} segments x {RINGS} rings: written by scripts/uv-sphere.py")
for v in vertices:
    print("v %.6f %.6f %.6f" % v)
for f in faces:
    print("f %d %d %d" % tuple(k + 1 for k in f))
