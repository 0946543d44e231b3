# spherecontact @SOLVER@: YADE along the path of scene.json, written to history.csv
# (the scene file and History CSV of docs/own-solver.md). Run as `yade -n -x`.
#
# Two spheres driven kinematically, one YADE step per path increment:
#  - sphere 0 sits at the origin, sphere 1 on the z axis at z = R0 + R1 - delta_n (set directly
#    before each step, velocity 0);
#  - the tangential displacement comes from spinning sphere 0 about y: its surface at the contact
#    moves by omega R0 dt in x in the step, while the line of centres stays on z, so the contact
#    normal never turns and the overlap is exactly delta_n;
#  - quasi-static: both bodies are non-dynamic (fixed=True: no forces integrated, no inertia) and
#    the law has no damping (betan = betas = 0 by default), so forces depend only on the overlap
#    and the accumulated shear, never on the rate.
import json
import math
import sys

from yade import *  # noqa: F401,F403 (YADE's scripting namespace: O, sphere, engines, laws)
from yade import Vector3

LAW = @LAW@
DT = @DT@
# How far YADE's own penetration depth may be from the path's delta_n, relative to the largest
# |delta_n| (positions ~R carry ulp(R) ~ 3e-17 m: 2e-12 of a 17 um approach).
DELTA_N_MATCH = 1e-9

scene = json.load(open("scene.json"))
b0, b1 = scene["body1"], scene["body2"]
if b0["radius"] is None or b1["radius"] is None:
    sys.exit("a flat is not modelled")
r0, r1 = b0["radius"], b1["radius"]
mu = scene["friction"]
for b in (b0, b1):
    O.materials.append(FrictMat(young=b["young"], poisson=b["poisson"], frictionAngle=math.atan(mu), density=1000))
steps = scene["steps"]
z = lambda dn: r0 + r1 - dn
O.bodies.append([
    sphere((0, 0, 0), r0, fixed=True, material=0),
    sphere((0, 0, z(steps[0]["delta_n"])), r1, fixed=True, material=1),
])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_MindlinPhys()], [LAW()]),
    NewtonIntegrator(damping=0, gravity=(0, 0, 0)),
]
O.dt = DT
scale = max(abs(s["delta_n"]) for s in steps)
rows = []
previous = steps[0]
for s in steps:
    O.bodies[1].state.pos = Vector3(0, 0, z(s["delta_n"]))
    O.bodies[1].state.vel = Vector3(0, 0, 0)
    O.bodies[0].state.angVel = Vector3(0, (s["delta_t"] - previous["delta_t"]) / (r0 * DT), 0)
    O.step()
    if O.interactions.has(0, 1) and O.interactions[0, 1].isReal:
        depth = O.interactions[0, 1].geom.penetrationDepth
        if abs(depth - s["delta_n"]) > DELTA_N_MATCH * scale:
            sys.exit("step %d: YADE's penetration depth %r is not the path's delta_n %r" % (s["step"], depth, s["delta_n"]))
    f = O.forces.f(0)
    # P = -fz and Q = -fx on sphere 0 (pushed down, dragged against its slip).
    rows.append((s, -f[2], -f[0]))
    previous = s

with open(scene["history_file"], "w") as out:
    out.write("step,position,delta_n,delta_t,normal_force,tangential_force\n")
    for s, p, q in rows:
        position = "" if s["position"] is None else s["position"]
        out.write("%d,%s,%r,%r,%r,%r\n" % (s["step"], position, s["delta_n"], s["delta_t"], p + 0.0, q + 0.0))
json.dump({"version": "YADE " + version, "warnings": ["contact radius and peak pressure are not output (empty)"]}, open("metadata.json", "w"))
