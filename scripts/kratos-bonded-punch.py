# A check of kratos-3d's meshes without contact (docs/external-decks.md, "Kratos 3D: known
# failures", the bricks at c_max/4): sphere 1 alone as a bonded flat punch. Run it in a folder
# `spherecontact deck write CASE --solver kratos-3d DIR` wrote, with the project's Kratos:
#     cd DIR && OMP_NUM_THREADS=1 /opt/spherecontact/venv/bin/python kratos-bonded-punch.py
# It takes the deck's ProjectParameters.json without its contact (Kratos' structural Static
# solver, residual criterion, linear), holds the slave nodes (the contact candidates) and sphere
# 2 at u = 0 and sphere 1's far face at u = (0, 0, -5 µm), and prints whether the step converged,
# the far face's and the patch's reactions (a half model's doubled; equal at equilibrium), and the
# smallest and largest corner angles and the largest warp of the slave faces. Writes nothing.
import json
import math

import KratosMultiphysics as KM
import KratosMultiphysics.StructuralMechanicsApplication  # noqa: F401 (registers the elements)
from KratosMultiphysics.StructuralMechanicsApplication.structural_mechanics_analysis import (
    StructuralMechanicsAnalysis,
)

D = 0.005  # mm
XYZ = (KM.DISPLACEMENT_X, KM.DISPLACEMENT_Y, KM.DISPLACEMENT_Z)

parameters = json.load(open("ProjectParameters.json"))
parameters["solver_settings"].pop("contact_settings", None)
parameters["solver_settings"]["convergence_criterion"] = "residual_criterion"
parameters["solver_settings"]["analysis_type"] = "linear"
parameters["processes"]["contact_process_list"] = []
parameters["output_processes"] = {}
parameters["problem_data"]["end_time"] = parameters["problem_data"]["start_time"] + 1.0  # one step


def hold(part, values):
    for node in part.Nodes:
        for variable, value in zip(XYZ, values):
            node.Fix(variable)
            node.SetSolutionStepValue(variable, value)


def reaction_z(part):
    return sum(node.GetSolutionStepValue(KM.REACTION)[2] for node in part.Nodes)


def minus(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def face_shape(part):
    """Smallest and largest corner angle [degrees], largest warp / mean edge of the faces (the
    distance between a quadrangle's two diagonals; 0 for a triangle)."""
    angles, warps = [], []
    for condition in part.Conditions:
        p = [(n.X0, n.Y0, n.Z0) for n in condition.GetNodes()]
        k = len(p)
        edges = [minus(p[(i + 1) % k], p[i]) for i in range(k)]
        for i in range(k):
            a, b = edges[i], edges[i - 1]  # the corner p[i] between p[i + 1] and p[i - 1]
            angles.append(math.degrees(math.acos(-dot(a, b) / math.sqrt(dot(a, a) * dot(b, b)))))
        if k == 4:
            normal = cross(minus(p[2], p[0]), minus(p[3], p[1]))
            edge = sum(math.sqrt(dot(e, e)) for e in edges) / 4
            warps.append(abs(dot(edges[0], normal)) / math.sqrt(dot(normal, normal)) / edge)
    return min(angles), max(angles), max(warps, default=0.0)


class Punch(StructuralMechanicsAnalysis):
    def ApplyBoundaryConditions(self):
        super().ApplyBoundaryConditions()
        structure = self.model["Structure"]
        hold(structure.GetSubModelPart("Far1"), (0.0, 0.0, -D))
        for name in ("Slave", "Master", "Far2"):
            hold(structure.GetSubModelPart(name), (0.0, 0.0, 0.0))
        for node in structure.GetSubModelPart("Symmetry").Nodes:
            node.Fix(KM.DISPLACEMENT_Y)
            node.SetSolutionStepValue(KM.DISPLACEMENT_Y, 0.0)

    def SolveSolutionStep(self):
        converged = self._GetSolver().SolveSolutionStep()
        structure = self.model["Structure"]
        factor = 2.0 if structure.GetSubModelPart("Symmetry").NumberOfNodes() > 0 else 1.0
        slave = structure.GetSubModelPart("Slave")
        print("converged %s; P far face %.2f N, P patch %.2f N (%d patch nodes); faces: angles %.1f to %.1f deg, warp %.1e" % (
            converged, -factor * reaction_z(structure.GetSubModelPart("Far1")), factor * reaction_z(slave),
            slave.NumberOfNodes(), *face_shape(slave)))
        return converged


Punch(KM.Model(), KM.Parameters(json.dumps(parameters))).Run()
