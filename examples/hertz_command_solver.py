#!/usr/bin/env python3
"""A command solver for spherecontact in a few lines: Hertz normal contact from the scene file.

Reads scene.json (docs/own-solver.md; every key: docs/case-files.md), writes history.csv with one row per step.
Run by cases/command-solver.toml; its check against the built-in `hertz` passes at round-off.
"""
import csv
import json
import math
import sys

scene = json.load(open(sys.argv[1] if len(sys.argv) > 1 else "scene.json"))
bodies = (scene["body1"], scene["body2"])
# E* = [(1 - nu1^2)/E1 + (1 - nu2^2)/E2]^-1, R* = [1/R1 + 1/R2]^-1 (a flat has radius null).
e_star = 1 / sum((1 - b["poisson"] ** 2) / b["young"] for b in bodies)
r_star = 1 / sum(0 if b["radius"] is None else 1 / b["radius"] for b in bodies)

with open(scene["history_file"], "w", newline="") as f:
    out = csv.writer(f)
    out.writerow(["step", "position", "delta_n", "delta_t", "normal_force", "contact_radius", "peak_pressure"])
    for s in scene["steps"]:
        d = max(s["delta_n"], 0.0)
        c = math.sqrt(r_star * d)  # contact radius
        p = 4 / 3 * e_star * math.sqrt(r_star) * d**1.5  # normal force
        p0 = 3 * p / (2 * math.pi * c * c) if c > 0 else 0.0  # peak pressure
        position = "" if s["position"] is None else s["position"]
        out.writerow([s["step"], position, repr(s["delta_n"]), repr(s["delta_t"]), repr(p), repr(c), repr(p0)])
