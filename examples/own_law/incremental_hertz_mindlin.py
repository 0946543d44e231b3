#!/usr/bin/env python3
"""A user's own DEM contact law, checked by spherecontact: incremental Hertz–Mindlin in Python.

    python3 incremental_hertz_mindlin.py SCENE [HISTORY] [--no-rescale]

Reads the scene file the harness writes (SCENE: `{scene}`, docs/own-solver.md) and writes the
History CSV (HISTORY: `{history}`; default the scene's `history_file`), one row per step, and
`metadata.json` beside it (version, model, resolution: shown in the reports):

- normal force: Hertz, P = 4/3 E* a δn with a = √(R* δn);
- tangential spring stiffness k_t = 8 G* a, force updated incrementally: Q ← Q + k_t Δδt;
- on unloading (a < a_prev) the stored Q is first scaled by a/a_prev, as LAMMPS' tangential model
  `mindlin_rescale/force` does (`--no-rescale` leaves it out: then the law is the no-slip spring
  of YADE's Mindlin law, spherecontact's built-in `hertz-mindlin-spring`);
- Coulomb cap |Q| ≤ μP;
- an open gap (δn ≤ 0) gives zero force and clears the history; the contact that closes it starts
  with Q = 0 (it had zero radius, hence zero stiffness, at the increment's start).

Run by cases/own-law.toml and by the README's own example (tests/suite/own_law_journey.rs).
"""
import csv
import json
import math
import os
import sys


class Law:
    """The law, one increment at a time: along a path here, in an impact in impact_hertz_mindlin.py."""

    def __init__(self, e_star, r_star, g_star, mu, rescale):
        self.e_star, self.r_star, self.g_star, self.mu, self.rescale = e_star, r_star, g_star, mu, rescale
        self.release()

    def release(self):
        """The gap is open: no force, no history."""
        self.q, self.a, self.touching = 0.0, 0.0, False

    def step(self, dn, ddt):
        """P and Q at approach dn after the tangential increment ddt."""
        if dn <= 0.0:
            self.release()
            return 0.0, 0.0
        a_prev, a = self.a, math.sqrt(self.r_star * dn)
        p = 4.0 / 3.0 * self.e_star * a * dn
        if not self.touching:
            self.q = 0.0  # the increment that closes the gap starts the contact at rest
        else:
            if self.rescale and a < a_prev:
                self.q *= a / a_prev  # unloading: the stored force shrinks with the contact
            self.q += 8.0 * self.g_star * a * ddt
            self.q = min(max(self.q, -self.mu * p), self.mu * p)  # Coulomb
        self.a, self.touching = a, True
        return p, self.q


def contact(scene, rescale):
    """The rows (step, P, Q, a) of the law along the scene's steps."""
    effective = scene["effective"]  # E*, R*, Mindlin's G*: the harness's own constants
    law = Law(effective["modulus"], effective["radius"], effective["mindlin_shear_modulus"], scene["friction"], rescale)
    previous_dt = 0.0
    for s in scene["steps"]:
        p, q = law.step(s["delta_n"], s["delta_t"] - previous_dt)
        previous_dt = s["delta_t"]
        yield s, p, q, law.a


def main(argv):
    rescale = "--no-rescale" not in argv
    args = [a for a in argv if a != "--no-rescale"]
    scene = json.load(open(args[0] if args else "scene.json"))
    history = args[1] if len(args) > 1 else scene["history_file"]
    with open(history, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["step", "position", "delta_n", "delta_t", "normal_force", "tangential_force", "contact_radius"])
        for s, p, q, a in contact(scene, rescale):
            position = "" if s["position"] is None else s["position"]
            # repr: the shortest text that reads back as the same double (round-trip exact)
            out.writerow([s["step"], position, repr(s["delta_n"]), repr(s["delta_t"]), repr(p), repr(q), repr(a)])
    # Optional: what the reports show of the program (its version, model and resolution).
    unloading = "Q scaled by a/a_prev on unloading" if rescale else "no rescale on unloading"
    metadata = {
        "version": "1.0",
        "model": f"incremental Hertz-Mindlin: k_t = 8G*a, {unloading}, Coulomb cap",
        "resolution": f"{len(scene['steps']) - 1} increments",
    }
    with open(os.path.join(os.path.dirname(os.path.abspath(history)), "metadata.json"), "w") as f:
        json.dump(metadata, f)


if __name__ == "__main__":
    main(sys.argv[1:])
