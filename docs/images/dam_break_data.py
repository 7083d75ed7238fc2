#!/usr/bin/env python3
"""Writes the data files of dam_break.gp from `anyphys run docs/images/dam_break.json --steps 60
--out states.csv --particles particles.csv` (run in the current folder): p<step>.dat holds each
particle's x, y and speed, c<step>.dat each crate's outline (half extent 0.08 m, turned by its
angle about Z), for steps 0, 24 and 48 (0, 0.4 and 0.8 s at 60 Hz)."""
import csv
import math

STEPS = (0, 24, 48)
HALF = 0.08
particles = list(csv.DictReader(open("particles.csv")))
states = list(csv.DictReader(open("states.csv")))
for step in STEPS:
    with open(f"p{step}.dat", "w") as out:
        for r in particles:
            if int(r["step"]) == step:
                out.write(f"{r['px']} {r['py']} {math.hypot(float(r['vx']), float(r['vy']))}\n")
    with open(f"c{step}.dat", "w") as out:
        for r in states:
            if int(r["step"]) != step or not r["body"].startswith("crate"):
                continue
            x, y = float(r["px"]), float(r["py"])
            angle = 2 * math.atan2(float(r["qz"]), float(r["qw"]))
            c, s = math.cos(angle), math.sin(angle)
            for cx, cy in ((-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF), (-HALF, -HALF)):
                out.write(f"{x + cx * c - cy * s} {y + cx * s + cy * c}\n")
            out.write("\n")
