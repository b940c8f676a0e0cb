#!/usr/bin/env python3
"""Writes scenes/pile/things.xml: 100 boxes of 0.1 m and 50 spheres dropped on the ground.

Layers of a 5 x 5 grid with a little deterministic jitter in position and yaw, so that the
objects tumble into a pile instead of stacking. Run from the repository root."""
import math
import random

rng = random.Random(2026)
spacing = 0.16
lines = ["<?xml version='1.0' ?>", "<!-- Made by scripts/make-pile-scene.py; do not edit. -->",
         "<things>"]
count = 0
for layer in range(6):
    for i in range(5):
        for j in range(5):
            x = (i - 2) * spacing + rng.uniform(-0.02, 0.02)
            y = (j - 2) * spacing + rng.uniform(-0.02, 0.02)
            z = 0.08 + layer * spacing
            if layer < 4:
                lines += [
                    "  <cuboid>",
                    f"    <ID value='box{count}'/>",
                    "    <mass value='0.5'/>",
                    "    <size x='0.1' y='0.1' z='0.1'/>",
                    f"    <pos x='{x:.4f}' y='{y:.4f}' z='{z:.4f}'/>",
                    f"    <rot_deg x='{rng.uniform(-10, 10):.2f}' y='{rng.uniform(-10, 10):.2f}' "
                    f"z='{rng.uniform(0, 90):.2f}'/>",
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
