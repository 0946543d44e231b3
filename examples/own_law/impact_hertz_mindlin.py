#!/usr/bin/env python3
"""The user's own law (incremental_hertz_mindlin.py) in an impact, checked by spherecontact.

    python3 impact_hertz_mindlin.py SCENE HISTORY [--no-rescale]

Reads the impact scene file the harness writes (SCENE: `{scene}`, one variant of an impact
case's sweep, docs/impact.md "Your own law in an impact") and writes the sweep table (HISTORY:
`{history}`): one row per sweep point, the scene's `columns`.

Each impact is integrated here, as a DEM code would: velocity Verlet (kick-drift-kick) on the
normal approach, both bodies' tangential velocities and spins, the law of
incremental_hertz_mindlin.py (`Law`) giving P and Q at each step's new approach and tangential
increment; for a prescribed restitution e < 1 the scene's `damping` (Tsuji's form, the
harness's rule: P_total = max(0, P + c δn^(1/4) dδn/dt), friction bounded by the elastic P),
so that the result is compared with the exact reference `mdr` on equal terms. Forces: P pushes
body 1 along +z; Q acts on body 1 along -x and on body 2 along +x at the contact points
(I1 dω1/dt = -R1 Q, I2 dω2/dt = +R2 Q). The contact starts at first touch and ends when the
approach returns to zero (the end time interpolated within the last step).
"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from incremental_hertz_mindlin import Law  # noqa: E402  (the same law as along the path)


def inverse(value):
    """1/value, 0 for a rigid flat (no mass given)."""
    return 0.0 if value is None else 1.0 / value


def body_inertia(body):
    """(1/m, 1/I, lever arm) of a body: zeros for a rigid flat."""
    if body["rigid_flat"]:
        return 0.0, 0.0, 0.0
    radius = body["radius"]
    mass = body["density"] * 4.0 / 3.0 * math.pi * radius**3
    return 1.0 / mass, 1.0 / (0.4 * mass * radius**2), radius


def impact(point, friction, steps_per_contact, rescale):
    """The outcome of one impact: duration, max P, max overlap, e_n, e_t, ω1 after, angle."""
    effective = point["effective"]
    law = Law(effective["modulus"], effective["radius"], effective["mindlin_shear_modulus"], friction, rescale)
    damping = point["damping"]
    h = point["hertz"]["contact_duration"] / steps_per_contact
    b1, b2 = point["body1"], point["body2"]
    (inv_m1, inv_i1, r1), (inv_m2, inv_i2, r2) = body_inertia(b1), body_inertia(b2)
    # velocities: [vx, vz, spin] per body
    v1 = [b1["velocity"][0], b1["velocity"][1], b1["spin"]]
    v2 = [b2["velocity"][0], b2["velocity"][1], b2["spin"]]

    def approach_rate(a, b):
        return b[1] - a[1]

    def slip(a, b):
        return (a[0] + r1 * a[2]) - (b[0] + r2 * b[2])

    def accelerations(p, q):
        return ([-q * inv_m1, p * inv_m1, -r1 * q * inv_i1], [q * inv_m2, -p * inv_m2, r2 * q * inv_i2])

    def kick(v, acc, dt):
        return [v[k] + acc[k] * dt for k in range(3)]

    approach, slip_before = approach_rate(v1, v2), slip(v1, v2)
    acc1, acc2 = accelerations(0.0, 0.0)
    overlap, time, max_p, max_overlap = 0.0, 0.0, 0.0, 0.0
    for _ in range(20 * steps_per_contact):
        half1, half2 = kick(v1, acc1, 0.5 * h), kick(v2, acc2, 0.5 * h)
        previous = overlap
        overlap += approach_rate(half1, half2) * h
        time += h
        if overlap > 0.0:
            p, q = law.step(overlap, slip(half1, half2) * h)
            if damping is not None:
                # the rate at the step's end, predicted with the old accelerations
                predicted = approach_rate(kick(half1, acc1, 0.5 * h), kick(half2, acc2, 0.5 * h))
                p = max(0.0, p + damping["coefficient"] * overlap**0.25 * predicted)
        else:
            law.release()
            p, q = 0.0, 0.0
        acc1, acc2 = accelerations(p, q)
        v1, v2 = kick(half1, acc1, 0.5 * h), kick(half2, acc2, 0.5 * h)
        max_p, max_overlap = max(max_p, p), max(max_overlap, overlap)
        if overlap <= 0.0 and previous > 0.0:
            time -= h * (-overlap) / (previous - overlap)  # the exit, interpolated
            break
    else:
        raise RuntimeError("the contact did not end within 20 contact durations")
    separation, slip_after = -approach_rate(v1, v2), slip(v1, v2)
    tangential = slip_after / slip_before if abs(slip_before) > 1e-12 * approach else None
    angle = math.atan2(slip_after, separation) if (slip_after != 0.0 or separation != 0.0) else None
    return [time, max_p, max_overlap, separation / approach, tangential, v1[2], angle]


def main(argv):
    rescale = "--no-rescale" not in argv
    scene_file, history = [a for a in argv if a != "--no-rescale"]
    scene = json.load(open(scene_file))
    with open(history, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(scene["columns"])
        for point in scene["points"]:
            values = impact(point, scene["friction"], scene["steps_per_contact"], rescale)
            cells = ["" if v is None else repr(v) for v in values]
            value = "" if point["value"] is None else repr(point["value"])
            out.writerow([scene["sweep"], value] + cells)


if __name__ == "__main__":
    main(sys.argv[1:])
