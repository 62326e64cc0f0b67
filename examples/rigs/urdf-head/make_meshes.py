#!/usr/bin/env python3
"""Writes the urdf-head example's meshes: meshes/head.stl (binary STL, the skull) and
meshes/jaw.obj (Wavefront OBJ, the jaw). Metres, each in its URDF link's frame (x forward,
y left, z up). Run from anywhere; the files are committed, this says how they were made."""
import math
import os
import struct

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "meshes")


def skull(u, v):
    """A point of the skull at longitude u (0..2pi) and latitude v (-pi/2..pi/2): an ellipsoid,
    longer front to back, with a flatter face and a brow."""
    x = 0.085 * math.cos(v) * math.cos(u)
    y = 0.072 * math.cos(v) * math.sin(u)
    z = 0.08 * math.sin(v)
    if x > 0:
        x *= 0.85 + 0.15 * (1 - math.cos(v))  # a flatter face
    return (x + 0.015, y, z + 0.055)


def jaw(u, v):
    """The jaw: the lower half of a smaller ellipsoid, hinged at the link origin, reaching forward."""
    x = 0.07 * math.cos(v) * math.cos(u)
    y = 0.06 * math.cos(v) * math.sin(u)
    z = 0.035 * math.sin(v)
    return (x + 0.045, y, z)


def grid(surface, columns, rows, v0, v1):
    """Triangles of a surface sampled on a longitude x latitude grid, outward facing."""
    triangles = []
    for r in range(rows):
        va = v0 + (v1 - v0) * r / rows
        vb = v0 + (v1 - v0) * (r + 1) / rows
        for c in range(columns):
            ua = 2 * math.pi * c / columns
            ub = 2 * math.pi * (c + 1) / columns
            a, b, p, q = surface(ua, va), surface(ub, va), surface(ub, vb), surface(ua, vb)
            triangles.append((a, b, p))
            triangles.append((a, p, q))
    return triangles


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    ux, uy, uz = bx - ax, by - ay, bz - az
    vx, vy, vz = cx - ax, cy - ay, cz - az
    n = (uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx)
    length = math.sqrt(sum(k * k for k in n)) or 1
    return tuple(k / length for k in n)


def write_stl(path, triangles):
    with open(path, "wb") as out:
        out.write(b"avar example: urdf-head skull".ljust(80, b" "))
        out.write(struct.pack("<I", len(triangles)))
        for t in triangles:
            out.write(struct.pack("<3f", *normal(t)))
            for p in t:
                out.write(struct.pack("<3f", *p))
            out.write(struct.pack("<H", 0))


def write_obj(path, triangles):
    with open(path, "w") as out:
        out.write("# avar example: urdf-head jaw (metres, the jaw link's frame)\n")
        for t in triangles:
            for p in t:
                out.write("v %.5f %.5f %.5f\n" % p)
        for k in range(len(triangles)):
            out.write("f %d %d %d\n" % (3 * k + 1, 3 * k + 2, 3 * k + 3))


if __name__ == "__main__":
    os.makedirs(HERE, exist_ok=True)
    write_stl(os.path.join(HERE, "head.stl"), grid(skull, 28, 16, -math.pi / 2 * 0.55, math.pi / 2))
    write_obj(os.path.join(HERE, "jaw.obj"), grid(jaw, 20, 6, -math.pi / 2, 0))
