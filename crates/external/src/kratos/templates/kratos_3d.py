# spherecontact kratos-3d: Kratos' ContactStructuralMechanicsApplication on both spheres along the
# path. Run it by hand in this folder with the project's Kratos environment (scripts/setup.sh):
#     OMP_NUM_THREADS=1 /opt/spherecontact/venv/bin/python kratos_3d.py
# It reads ProjectParameters.json (solver, contact process), materials.json, spheres.mdpa (the
# mesh, mm) and path.txt (the computed steps: index, d = delta_n/2 [mm], t = delta_t/2 [mm],
# position), and writes
#   steps.csv   one row per computed step: whether Kratos' Newton iteration converged, its
#               iterations, the norm of the residual left (Kratos' BuildRHS on the final state:
#               forces [N] on the free degrees of freedom and weighted gaps [mm] of the contact),
#               P and Q from the reactions of both far faces (a half model's doubled), the
#               step's wall time;
#   surface.csv the slave nodes of Reported (those with y >= 0) at every step: the augmented contact pressure and tangential
#               traction [MPa] (Kratos' AUGMENTED_*_CONTACT_PRESSURE), its ACTIVE and SLIP flags,
#               the node's displacement u_z [mm] and its slip against its mirror image on sphere 2
#               (the same node of the conforming mesh: u_x, u_y of sphere 1 less sphere 2's) [mm].
# Kratos' AnalysisStage discards the converged flag that its solver returns (RunSolutionLoop calls
# SolveSolutionStep and ignores the result): this driver keeps it, with the iterations, per step.
#
# Frame: contact plane z = 0, sphere 1 in z >= 0, sphere 2 its mirror image; the bodies are the
# halves y >= 0 (frictionless) or whole (under friction). At each step the far face of sphere 1
# (sub-model-part Far1) is held at u = (t, 0, -d) and that of sphere 2 (Far2) at (-t, 0, d); the
# nodes of Symmetry (the plane y = 0 of the halves, empty on whole bodies) at u_y = 0. Nothing here comes from the
# case's text: every number is read from path.txt, the rest is fixed.
import sys
import time

import KratosMultiphysics as KM
import KratosMultiphysics.StructuralMechanicsApplication  # noqa: F401 (registers the elements)
import KratosMultiphysics.ContactStructuralMechanicsApplication as CSMA
from KratosMultiphysics.StructuralMechanicsApplication.structural_mechanics_analysis import (
    StructuralMechanicsAnalysis,
)


def read_path(name="path.txt"):
    lines = open(name).read().split("\n")
    count = int(lines[0])
    steps = []
    for line in lines[1:1 + count]:
        index, d, t, position = line.split()
        steps.append((int(index), float(d), float(t), int(position)))
    if len(steps) != count:
        sys.exit("%s lists %d steps, not %d" % (name, len(steps), count))
    return steps


STEPS = read_path()
DISPLACEMENT = (KM.DISPLACEMENT_X, KM.DISPLACEMENT_Y, KM.DISPLACEMENT_Z)


def norm(vector):
    return sum(vector[i] ** 2 for i in range(vector.Size())) ** 0.5


def total_reaction(part):
    force = [0.0, 0.0, 0.0]
    for node in part.Nodes:
        r = node.GetSolutionStepValue(KM.REACTION)
        force = [force[k] + r[k] for k in range(3)]
    return force


class Path(StructuralMechanicsAnalysis):
    """The structural analysis, one step per computed path step, its convergence kept."""

    def Initialize(self):
        super().Initialize()
        self.k = 0
        self.steps = open("steps.csv", "w")
        self.steps.write("step,converged,iterations,residual,P1_N,Q1_N,P2_N,Q2_N,wall_s\n")
        self.surface = open("surface.csv", "w")
        self.surface.write("step,node,p_MPa,qx_MPa,qy_MPa,active,slip,uz_mm,slip_x_mm,slip_y_mm\n")
        self.structure = self.model["Structure"]
        # Sphere 2's node i + half is the mirror image of sphere 1's node i (spheres.mdpa).
        self.half = self.structure.GetSubModelPart("Solid").NumberOfNodes() // 2
        # The halves' forces are doubled for the whole spheres.
        self.factor = 2.0 if self.structure.GetSubModelPart("Symmetry").NumberOfNodes() > 0 else 1.0

    def ApplyBoundaryConditions(self):
        super().ApplyBoundaryConditions()
        _, d, t, _ = STEPS[self.k]
        for name, sign in (("Far1", 1.0), ("Far2", -1.0)):
            for node in self.structure.GetSubModelPart(name).Nodes:
                for variable, value in zip(DISPLACEMENT, (sign * t, 0.0, -sign * d)):
                    node.Fix(variable)
                    node.SetSolutionStepValue(variable, value)
        for node in self.structure.GetSubModelPart("Symmetry").Nodes:
            node.Fix(KM.DISPLACEMENT_Y)
            node.SetSolutionStepValue(KM.DISPLACEMENT_Y, 0.0)

    def SolveSolutionStep(self):
        start = time.time()
        converged = self._GetSolver().SolveSolutionStep()
        iterations = self.structure.ProcessInfo[KM.NL_ITERATION_NUMBER]
        self.outcome = (bool(converged), iterations, self.residual(), time.time() - start)
        return converged

    def residual(self):
        """The norm of the residual on the final state (free degrees of freedom)."""
        solver = self._GetSolver()
        rhs = KM.Vector(solver._GetSolutionStrategy().GetSystemVector().Size())
        KM.UblasSparseSpace().SetToZeroVector(rhs)
        solver._GetBuilderAndSolver().BuildRHS(solver._GetScheme(), self.structure, rhs)
        return norm(rhs)

    def FinalizeSolutionStep(self):
        super().FinalizeSolutionStep()
        index = STEPS[self.k][0]
        converged, iterations, residual, wall = self.outcome
        one = total_reaction(self.structure.GetSubModelPart("Far1"))
        two = total_reaction(self.structure.GetSubModelPart("Far2"))
        # P pushes sphere 1 up (its far face's reaction along -z), Q drags it along x.
        f = self.factor
        p1, q1, p2, q2 = -f * one[2], f * one[0], f * two[2], -f * two[0]
        self.steps.write("%d,%d,%d,%r,%r,%r,%r,%r,%r\n"
                         % (index, converged, iterations, residual, p1, q1, p2, q2, wall))
        self.steps.flush()
        for node in self.structure.GetSubModelPart("Reported").Nodes:
            p = -node.GetValue(CSMA.AUGMENTED_NORMAL_CONTACT_PRESSURE)
            q = [0.0, 0.0, 0.0]
            if node.Has(CSMA.AUGMENTED_TANGENT_CONTACT_PRESSURE):
                q = node.GetValue(CSMA.AUGMENTED_TANGENT_CONTACT_PRESSURE)
            u = node.GetSolutionStepValue(KM.DISPLACEMENT)
            v = self.structure.GetNode(node.Id + self.half).GetSolutionStepValue(KM.DISPLACEMENT)
            self.surface.write("%d,%d,%r,%r,%r,%d,%d,%r,%r,%r\n" % (
                index, node.Id, p + 0.0, q[0] + 0.0, q[1] + 0.0, node.Is(KM.ACTIVE), node.Is(KM.SLIP),
                u[2] + 0.0, u[0] - v[0] + 0.0, u[1] - v[1] + 0.0))
        self.surface.flush()
        self.k += 1

    def Finalize(self):
        super().Finalize()
        self.steps.close()
        self.surface.close()
        if self.k != len(STEPS):
            sys.exit("Kratos made %d steps for the %d of path.txt" % (self.k, len(STEPS)))


with open("ProjectParameters.json") as parameters:
    Path(KM.Model(), KM.Parameters(parameters.read())).Run()
