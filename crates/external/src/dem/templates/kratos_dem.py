# spherecontact @SOLVER@: Kratos DEMApplication along the path of scene.json, written to
# history.csv (the scene file and History CSV of docs/own-solver.md). Run by the Python of the
# project's Kratos environment (scripts/setup.sh), in its own run folder, OMP_NUM_THREADS=1.
#
# Two spheres driven kinematically, one Kratos step per path increment, every velocity degree of
# freedom fixed (no force is integrated: no inertia, and the law has no damping at restitution 1):
#  - sphere 1 sits at the origin, sphere 2 on the z axis at z = R1 + R2 - delta_n, moved to the
#    next position by a fixed VELOCITY_Z = dz / DT during the step;
#  - the tangential displacement comes from spinning sphere 1 about y: Kratos turns its contact
#    arm (R1 - delta_n E2/(E1 + E2), spheric_particle.cpp) by ANGULAR_VELOCITY_Y DT, so the arm's
#    end moves by the path's increment in x while the line of centres stays on z: the contact
#    normal never turns and the overlap is exactly delta_n;
#  - a Kratos step computes the forces at the positions it starts from and then moves the spheres
#    (explicit_solver_strategy): step k's forces belong to position k, and its move goes to k + 1.
# Every number comes from scene.json (JSON, parsed here); nothing of the case is pasted as code.
import json
import math
import os
import sys

import KratosMultiphysics as KM
import KratosMultiphysics.DEMApplication as DEM
from KratosMultiphysics.DEMApplication.DEM_analysis_stage import DEMAnalysisStage

LAW = "@LAW@"
DT = @DT@
PROBLEM = "spherecontact"
# How far Kratos' overlap (from its own positions) may be from the path's delta_n, relative to the
# largest |delta_n|: positions ~R carry ulp(R) ~ 3e-17 m per move, summed over the steps.
DELTA_N_MATCH = 1e-9

scene = json.load(open("scene.json"))
b1, b2 = scene["body1"], scene["body2"]
if b1["radius"] is None or b2["radius"] is None:
    sys.exit("a flat is not modelled")
r1, r2 = float(b1["radius"]), float(b2["radius"])
mu = float(scene["friction"])
steps = scene["steps"]
z = lambda dn: r1 + r2 - float(dn)

KM.Logger.GetDefaultOutput().SetSeverity(KM.Logger.Severity.WARNING)

with open(PROBLEM + "DEM.mdpa", "w") as mdpa:
    mdpa.write("Begin ModelPartData\nEnd ModelPartData\nBegin Properties 1\nEnd Properties\n"
               "Begin Properties 2\nEnd Properties\n")
    mdpa.write("Begin Nodes\n 1 0.0 0.0 0.0\n 2 0.0 0.0 %r\nEnd Nodes\n" % z(steps[0]["delta_n"]))
    for element, props in ((1, 1), (2, 2)):
        mdpa.write("Begin Elements SphericParticle3D\n %d %d %d\nEnd Elements\n" % (element, props, element))
    mdpa.write("Begin NodalData RADIUS\n 1 0 %r\n 2 0 %r\nEnd NodalData\n" % (r1, r2))
    for part, node in (("Parts_one", 1), ("Parts_two", 2)):
        mdpa.write("Begin SubModelPart %s\n Begin SubModelPartNodes\n %d\n End SubModelPartNodes\n"
                   " Begin SubModelPartElements\n %d\n End SubModelPartElements\n"
                   " Begin SubModelPartConditions\n End SubModelPartConditions\nEnd SubModelPart\n" % (part, node, node))

material = lambda name, ident, b: {"material_name": name, "material_id": ident, "Variables": {
    "PARTICLE_DENSITY": 1000.0, "YOUNG_MODULUS": float(b["young"]), "POISSON_RATIO": float(b["poisson"])}}
relation = lambda a, b: {"material_names_list": [a, b], "material_ids_list": [int(a[1]), int(b[1])], "Variables": {
    # Restitution 1: DAMPING_GAMMA = 0, no viscous force; static = dynamic friction: no decay.
    "COEFFICIENT_OF_RESTITUTION": 1.0, "STATIC_FRICTION": mu, "DYNAMIC_FRICTION": mu, "FRICTION_DECAY": 0.0,
    "ROLLING_FRICTION": 0.0, "ROLLING_FRICTION_WITH_WALLS": 0.0,
    "DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME": LAW}}
json.dump({"materials": [material("m1", 1, b1), material("m2", 2, b2)],
           "material_relations": [relation("m1", "m1"), relation("m1", "m2"), relation("m2", "m2")],
           "material_assignation_table": [["SpheresPart.Parts_one", "m1"], ["SpheresPart.Parts_two", "m2"]]},
          open("materials.json", "w"))

FINAL = DT * (len(steps) - 0.5)
parameters = {
    "Dimension": 3, "PeriodicDomainOption": False, "BoundingBoxOption": False, "AutomaticBoundingBoxOption": False,
    "dem_inlet_option": False, "GravityX": 0.0, "GravityY": 0.0, "GravityZ": 0.0, "RotationOption": True,
    "CleanIndentationsOption": False,
    "solver_settings": {"RemoveBallsInitiallyTouchingWalls": False, "strategy": "sphere_strategy",
                        "material_import_settings": {"materials_filename": "materials.json"}},
    "VirtualMassCoefficient": 1.0, "RollingFrictionOption": False, "GlobalDamping": 0.0, "ContactMeshOption": False,
    "OutputFileType": "Binary", "Multifile": "multiple_files", "ElementType": "SphericPartDEMElement3D",
    "TranslationalIntegrationScheme": "Symplectic_Euler", "RotationalIntegrationScheme": "Direct_Integration",
    "MaxTimeStep": DT, "FinalTime": FINAL, "NeighbourSearchFrequency": 1,
    # Graphs and post files never written: their periods past the end (finite: Kratos divides them by the step).
    "GraphExportFreq": 10 * FINAL, "VelTrapGraphExportFreq": 10 * FINAL, "OutputTimeStep": 10 * FINAL,
    "problem_name": PROBLEM,
}
FIXED = (KM.VELOCITY_X, KM.VELOCITY_Y, KM.VELOCITY_Z,
         KM.ANGULAR_VELOCITY_X, KM.ANGULAR_VELOCITY_Y, KM.ANGULAR_VELOCITY_Z)


class Path(DEMAnalysisStage):
    def Initialize(self):
        super().Initialize()
        self.step, self.rows = 0, []
        for node in self.spheres_model_part.Nodes:
            for dof in FIXED:
                node.Fix(dof)
                node.SetSolutionStepValue(dof, 0.0)

    def InitializeSolutionStep(self):
        super().InitializeSolutionStep()
        here, there = steps[self.step], steps[min(self.step + 1, len(steps) - 1)]
        one, two = self.spheres_model_part.GetNode(1), self.spheres_model_part.GetNode(2)
        two.SetSolutionStepValue(KM.VELOCITY_Z, (z(there["delta_n"]) - z(here["delta_n"])) / DT)
        e1, e2 = float(b1["young"]), float(b2["young"])
        arm = r1 - float(there["delta_n"]) * e2 / (e1 + e2)
        one.SetSolutionStepValue(KM.ANGULAR_VELOCITY_Y, (float(there["delta_t"]) - float(here["delta_t"])) / (arm * DT))

    def FinalizeSolutionStep(self):
        super().FinalizeSolutionStep()
        s = steps[self.step]
        one, two = self.spheres_model_part.GetNode(1), self.spheres_model_part.GetNode(2)
        # The move of this step has been made: Kratos' overlap at the forces' positions is the one
        # before it, z(two) - VELOCITY_Z DT.
        depth = r1 + r2 - (two.Z - two.GetSolutionStepValue(KM.VELOCITY_Z) * DT)
        if depth > 0 and abs(depth - float(s["delta_n"])) > DELTA_N_MATCH * scale:
            sys.exit("step %d: Kratos' overlap %r is not the path's delta_n %r" % (s["step"], depth, s["delta_n"]))
        f = one.GetSolutionStepValue(DEM.ELASTIC_FORCES)
        # P = -fz and Q = -fx on sphere 1 (pushed down, dragged against its slip).
        self.rows.append((s, -f[2] + 0.0, -f[0] + 0.0))
        self.step += 1


scale = max(abs(float(s["delta_n"])) for s in steps) or 1.0
stage = Path(KM.Model(), KM.Parameters(json.dumps(parameters)))
stage.Run()
if len(stage.rows) != len(steps):
    sys.exit("Kratos made %d steps for a path of %d" % (len(stage.rows), len(steps)))

with open(scene["history_file"], "w") as out:
    out.write("step,position,delta_n,delta_t,normal_force,tangential_force\n")
    for s, p, q in stage.rows:
        position = "" if s["position"] is None else s["position"]
        out.write("%d,%s,%r,%r,%r,%r\n" % (s["step"], position, s["delta_n"], s["delta_t"], p, q))
from importlib.metadata import version
json.dump({"version": "Kratos " + version("KratosDEMApplication"),
           "warnings": ["contact radius and peak pressure are not output (empty)"]}, open("metadata.json", "w"))
