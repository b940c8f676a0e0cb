#!/usr/bin/env python3
"""Writes scenes/pile/things.xml: 100 boxes of 0.1 m and 50 spheres dropped on the ground.

Layers of a 5 x 5 grid with a little deterministic jitter in position and yaw, so that the
objects tumble into a pile instead of stacking. A placement that would overlap (or come within
CLEARANCE of) an object already placed is drawn again: the pile measures contact, so it must
not start with bodies inside one another. Run from the repository root."""
import math
import random

rng = random.Random(2026)
spacing = 0.16
CLEARANCE = 0.005  # m
HALF = 0.05  # half the box's side, and the spheres' radius


def rotation(x_deg, y_deg, z_deg):
    """SimTwo's rot_deg: R = Rz(z) Ry(y) Rx(x) (kernel/src/scene/rotation.cpp), rows."""
    cx, sx = math.cos(math.radians(x_deg)), math.sin(math.radians(x_deg))
    cy, sy = math.cos(math.radians(y_deg)), math.sin(math.radians(y_deg))
    cz, sz = math.cos(math.radians(z_deg)), math.sin(math.radians(z_deg))
    rz = ((cz, -sz, 0), (sz, cz, 0), (0, 0, 1))
    ry = ((cy, 0, sy), (0, 1, 0), (-sy, 0, cy))
    rx = ((1, 0, 0), (0, cx, -sx), (0, sx, cx))

    def mul(a, b):
        return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3))
                     for i in range(3))
    return mul(mul(rz, ry), rx)


def axes(r):
    return [tuple(r[i][j] for i in range(3)) for j in range(3)]  # the box's axes: columns


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def boxes_apart(ca, ra, cb, rb, gap):
    """Separating-axis test of two cubes of half side HALF grown by gap / 2 each."""
    ua, ub = axes(ra), axes(rb)
    d = tuple(q - p for p, q in zip(ca, cb))
    candidates = ua + ub + [(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                             a[0] * b[1] - a[1] * b[0]) for a in ua for b in ub]
    h = HALF + gap / 2
    for axis in candidates:
        length = math.sqrt(dot(axis, axis))
        if length < 1e-9:
            continue
        n = tuple(x / length for x in axis)
        reach = h * sum(abs(dot(n, u)) for u in ua) + h * sum(abs(dot(n, u)) for u in ub)
        if abs(dot(d, n)) > reach:
            return True
    return False


def sphere_box_apart(cs, cb, rb, gap):
    local = [dot(tuple(q - p for p, q in zip(cb, cs)), u) for u in axes(rb)]
    nearest = [max(-HALF, min(HALF, x)) for x in local]
    return math.dist(local, nearest) > HALF + gap


placed = []  # (kind, centre, rotation)


def free(kind, centre, r):
    for other_kind, other_centre, other_r in placed:
        if kind == "box" and other_kind == "box":
            if not boxes_apart(centre, r, other_centre, other_r, CLEARANCE):
                return False
        elif kind == "sphere" and other_kind == "sphere":
            if math.dist(centre, other_centre) <= 2 * HALF + CLEARANCE:
                return False
        else:
            s, b, rb = (centre, other_centre, other_r) if kind == "sphere" else (other_centre,
                                                                                    centre, r)
            if not sphere_box_apart(s, b, rb, CLEARANCE):
                return False
    return True


lines = ["<?xml version='1.0' ?>", "<!-- Made by scripts/make-pile-scene.py; do not edit. -->",
         "<things>"]
count = 0
for layer in range(6):
    for i in range(5):
        for j in range(5):
            kind = "box" if layer < 4 else "sphere"
            for attempt in range(1000):
                x = (i - 2) * spacing + rng.uniform(-0.02, 0.02)
                y = (j - 2) * spacing + rng.uniform(-0.02, 0.02)
                z = 0.08 + layer * spacing
                rot = (rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(0, 90))
                if free(kind, (x, y, z), rotation(*rot) if kind == "box" else None):
                    break
            else:
                raise SystemExit(f"no free place for object {count}")
            placed.append((kind, (x, y, z), rotation(*rot) if kind == "box" else None))
            if kind == "box":
                lines += [
                    "  <cuboid>",
                    f"    <ID value='box{count}'/>",
                    "    <mass value='0.5'/>",
                    "    <size x='0.1' y='0.1' z='0.1'/>",
                    f"    <pos x='{x:.4f}' y='{y:.4f}' z='{z:.4f}'/>",
                    f"    <rot_deg x='{rot[0]:.2f}' y='{rot[1]:.2f}' z='{rot[2]:.2f}'/>",
                    f"    <color_rgb r='{rng.randint(80, 230)}' g='{rng.randint(80, 230)}' b='60'/>",
                    "  </cuboid>"]
            else:
                lines += [
                    "  <sphere>",
                    f"    <ID value='ball{count}'/>",
                    "    <mass value='0.3'/>",
                    "    <radius value='0.05'/>",
                    f"    <pos x='{x:.4f}' y='{y:.4f}' z='{z:.4f}'/>",
                    f"    <color_rgb r='60' g='{rng.randint(80, 230)}' b='{rng.randint(80, 230)}'/>",
                    "  </sphere>"]
            count += 1
lines.append("</things>")
with open("scenes/pile/things.xml", "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"wrote {count} things")
