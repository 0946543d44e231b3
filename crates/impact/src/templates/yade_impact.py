# spherecontact yade-mindlin: an impact sweep, every point of points.json (generated from the
# impact case), one after the other in this one YADE process (`yade -n -x`).
#
# Body 1 above body 2 on the z axis, half a step of approach apart; a rigid flat is a fixed sphere
# of 1e6 x R1 (non-dynamic: it does not move and the damping's mass is body 1's). Both bodies have
# the one material (E', nu') that carries the pair's E* and Mindlin's G*, their own densities.
# Law2_ScGeom_MindlinPhys_Mindlin: Hertz, incremental spring 8G*a, Coulomb cap; when a restitution
# e < 1 is prescribed, YADE's own damping en = e (Thornton et al.'s beta) and no shear damping
# (es = 1). NewtonIntegrator without numerical damping or gravity.
#
# Each point writes point-<i>.txt: per step, before the step's motion, the step, both centres
# (x z), the velocities (vx vz) and spins (omega_y) after it, and the contact force on body 1 the
# step computed; it stops at the step where the bodies have separated (delta < 0 after touching).
import json
import math

from yade import *  # noqa: F401,F403 (YADE's scripting namespace: O, sphere, engines, laws)
from yade import Vector3

for p in json.load(open("points.json")):
    O.reset()
    mats = [
        O.materials.append(FrictMat(young=p["young"], poisson=p["poisson"], frictionAngle=math.atan(p["friction"]), density=rho))
        for rho in p["density"]
    ]
    (r1, r2), (c1, c2) = p["radius"], p["centre"]
    O.bodies.append([
        sphere((c1[0], 0, c1[1]), r1, material=mats[0]),
        sphere((c2[0], 0, c2[1]), r2, fixed=p["fixed"], material=mats[1]),
    ])
    for body, v, w in zip(O.bodies, p["velocity"], p["spin_y"]):
        body.state.vel = Vector3(v[0], 0, v[1])
        body.state.angVel = Vector3(0, w, 0)
    if p["restitution"] < 1:
        physics = Ip2_FrictMat_FrictMat_MindlinPhys(
            en=MatchMaker(algo="val", val=p["restitution"]), es=MatchMaker(algo="val", val=1.0))
    else:
        physics = Ip2_FrictMat_FrictMat_MindlinPhys()
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [physics], [Law2_ScGeom_MindlinPhys_Mindlin()]),
        NewtonIntegrator(damping=0, gravity=(0, 0, 0)),
    ]
    O.dt = p["step"]
    b1, b2 = O.bodies[0].state, O.bodies[1].state
    with open("point-%d.txt" % p["index"], "w") as out:
        out.write("# step x1 z1 x2 z2 vx1 vz1 wy1 vx2 vz2 wy2 fx1 fz1\n")
        for k in range(p["max_steps"] + 1):
            x1, x2 = Vector3(b1.pos), Vector3(b2.pos)
            O.step()
            f = O.forces.f(0)
            row = (x1[0], x1[2], x2[0], x2[2], b1.vel[0], b1.vel[2], b1.angVel[1], b2.vel[0], b2.vel[2], b2.angVel[1], f[0], f[2])
            out.write("%d %s\n" % (k, " ".join(repr(float(v)) for v in row)))
            if k > 2 and r1 + r2 - (x1 - x2).norm() < 0:
                break
