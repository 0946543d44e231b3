# ---- the block both dolfinx decks share (crates/external/src/templates/fenicsx_common.py) ----------------
import csv
import time

import gmsh
import numpy as np
import scipy.linalg
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem.petsc
from dolfinx import fem
from dolfinx.io import gmshio

MESH = "@MESH@"
R, E, nu = @R_MM@, @E_MPA@, @NU@
h = @H_MM@
k = @KFAC@ * E / h                 # penalty [MPa/mm], normal and tangential
mu = @MU@
r_cand = @CANDIDATE_RADIUS_MM@     # contact candidates lie within r_cand of the pole
tangential = @TANGENTIAL@          # 0: normal-only path, the tangential problem is not solved
lam = E * nu / ((1 + nu) * (1 - 2 * nu))
G = E / (2 * (1 + nu))
# the computed steps (@PATH_FILE@): a count, then per step its path index, d = delta_n/2 [mm],
# t = delta_t/2 [mm] and the path position it reaches (a field file is written) or -1
with open("@PATH_FILE@") as path_file:
    path_rows = [line.split() for line in path_file.read().splitlines()[1:]]
steps = [int(row[0]) for row in path_rows]
dlist = [float(row[1]) for row in path_rows]
tlist = [float(row[2]) for row in path_rows]
fields = [int(row[3]) for row in path_rows]
maxit = @MAX_ITERATIONS@
comm = MPI.COMM_WORLD
root = comm.rank == 0
clock_start, wall_start = time.process_time(), time.perf_counter()


def factored(a, bcs):
    """The stiffness of bilinear form a with homogeneous Dirichlet rows bcs, factored (MUMPS)."""
    A = fem.petsc.assemble_matrix(fem.form(a), bcs=bcs)
    A.assemble()
    ksp = PETSc.KSP().create(comm)
    ksp.setOperators(A)
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    ksp.getPC().setFactorSolverType("mumps")
    ksp.setUp()
    return A, ksp


def solve_normal(S, d, w, spd_solve, A=None):
    """Penalty contact at approach d from the start w (u_z at the candidates, whose heights zs
    and nodal weights om the deck defines), S the condensed stiffness: (w, f, its, ok), f the
    contact forces on the candidates' u_z.

    Node j's multiplier om_j k <-g_j>_+ sees the gap g = A (zs + w) and acts as the forces
    f = A^T (om k <-g>_+); A = None is the identity (the nodal gap zs + w). Newton on
    S (w + d) = f(w) with the active set of the start: exact once the set of the solution is the
    set it was computed with. spd_solve(S, D, b) solves (S + D) x = b, D the contact's tangent
    (with A = None its diagonal, a vector)."""
    def gap(w):
        return zs + w if A is None else A @ (zs + w)

    def forces(w):
        lam = k * om * np.maximum(-gap(w), 0.0)
        return lam if A is None else A.T @ lam

    for it in range(1, maxit + 1):
        act = gap(w) < 0
        if A is None:
            D, b = k * om * act, k * om * act * zs
        else:
            DA = (k * om * act)[:, None] * A
            D, b = A.T @ DA, A.T @ (DA @ zs)
        w = spd_solve(S, D, -S @ np.full(len(w), d) - b)
        if np.array_equal(act, gap(w) < 0):
            return w, forces(w), it, True
    return w, forces(w), maxit, False
# ---- end of the shared block -----------------------------------------------------------------------
