"""spherecontact deck `fenicsx-axisym`, generated from scene "@SCENE@".

Axisymmetric normal contact with DOLFINx (Debian's 0.5.2, run by /usr/bin/python3): one elastic
sphere (radius R) pressed by d = delta_n/2 against a rigid frictionless plane z = 0 (the symmetry
plane of two identical spheres). The mesh (gmsh MSH 4.1, quadratic, metres) is scaled to mm;
units mm, N, MPa. x[0] = r, x[1] = z. Tags: 1 spherical surface (contact candidate), cut face
z = H tagged 2 (axial grip: u_z = -d) or 4 (rigid grip: u_z = -d, u_r = 0), 3 axis (u_r = 0). Contact: penalty t_z = k <-(z + u_z)>_+, k = kfac E / h,
solved by Newton (semi-smooth: the derivative of max_value is a conditional).
Writes steps.csv (one row per d) and field_<k>.xdmf (u, pressure at the P2 nodes).
"""
import csv

import gmsh
import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem.petsc
import dolfinx.nls.petsc
from dolfinx import fem
from dolfinx.io import gmshio

MESH = "@MESH@"
R, E, nu = @R_MM@, @E_MPA@, @NU@
h = @H_MM@
kpen = @KFAC@ * E / h
dlist = [@D_LIST_MM@]
maxit = @MAX_ITERATIONS@
comm = MPI.COMM_WORLD

# gmshio.read_from_msh is broken in 0.5.2: merge by hand, then model_to_mesh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.merge(MESH)
msh, _, ftags = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=2)
gmsh.finalize()
msh.geometry.x[:, :2] *= 1000.0  # m -> mm

V = fem.FunctionSpace(msh, ufl.VectorElement("Lagrange", msh.ufl_cell(), 2))
V1, v1_dofs = V.sub(1).collapse()
u, v = fem.Function(V), ufl.TestFunction(V)
u.name = "u"
x = ufl.SpatialCoordinate(msh)
r = x[0]
lam = E * nu / ((1 + nu) * (1 - 2 * nu))
mu = E / (2 * (1 + nu))


def eps(w):  # axisymmetric strain (rr, zz, rz, theta-theta)
    return ufl.as_tensor([[w[0].dx(0), 0.5 * (w[0].dx(1) + w[1].dx(0)), 0],
                          [0.5 * (w[0].dx(1) + w[1].dx(0)), w[1].dx(1), 0],
                          [0, 0, w[0] / r]])


def sigma(w):
    return lam * ufl.tr(eps(w)) * ufl.Identity(3) + 2 * mu * eps(w)


ds = ufl.Measure("ds", domain=msh, subdomain_data=ftags, metadata={"quadrature_degree": 6})
dx = ufl.Measure("dx", domain=msh, metadata={"quadrature_degree": 6})
press = kpen * ufl.max_value(-(x[1] + u[1]), 0.0)
F = ufl.inner(sigma(u), eps(v)) * r * dx - press * v[1] * r * ds(1)

fdim = msh.topology.dim - 1
top_value = fem.Constant(msh, PETSc.ScalarType(0.0))
top = np.concatenate([ftags.find(2), ftags.find(4)])
fixed_r = np.concatenate([ftags.find(3), ftags.find(4)])
bcs = [fem.dirichletbc(top_value, fem.locate_dofs_topological(V.sub(1), fdim, top), V.sub(1)),
       fem.dirichletbc(PETSc.ScalarType(0.0), fem.locate_dofs_topological(V.sub(0), fdim, fixed_r), V.sub(0))]
problem = fem.petsc.NonlinearProblem(F, u, bcs=bcs)
solver = dolfinx.nls.petsc.NewtonSolver(comm, problem)
solver.rtol, solver.atol, solver.max_it = 1e-10, 1e-8, maxit
solver.convergence_criterion = "residual"
solver.error_on_nonconvergence = False
ksp = solver.krylov_solver
opts = PETSc.Options()
pre = ksp.getOptionsPrefix()
opts[f"{pre}ksp_type"], opts[f"{pre}pc_type"] = "preonly", "lu"
opts[f"{pre}pc_factor_mat_solver_type"] = "mumps"
ksp.setFromOptions()


def integrate(expr):
    return comm.allreduce(fem.assemble_scalar(fem.form(expr)), op=MPI.SUM)


# contact surface P2 nodes, sorted by r: gap, nodal penalty pressure, contact radius
surface = fem.locate_dofs_topological(V1, fdim, ftags.find(1))
X1 = V1.tabulate_dof_coordinates()
order = surface[np.argsort(X1[surface, 0])]
pressure = fem.Function(V1)
pressure.name = "pressure"

with open("steps.csv", "w", newline="") as f:
    out = csv.writer(f)
    out.writerow(["index", "d_mm", "P_contact_N", "P_top_N", "p0_MPa", "p0_method",
                  "contact_radius_mm", "iterations", "converged", "field_file"])
    for k, d in enumerate(dlist):
        top_value.value = -d
        # start: rigid translation by -d/2, active set ~ Hertz radius sqrt(R d)
        u.interpolate(lambda X: np.vstack([0 * X[0], np.full_like(X[0], -d / 2)]))
        its, converged = solver.solve(u)
        uz = u.x.array[v1_dofs]
        gap = X1[:, 1] + uz
        pressure.x.array[:] = kpen * np.maximum(-gap, 0.0)
        P_contact = 2 * np.pi * integrate(press * r * ds(1))
        P_top = -2 * np.pi * integrate(sigma(u)[1, 1] * r * (ds(2) + ds(4)))
        pole = order[0]
        p0 = float(pressure.x.array[pole]) if X1[pole, 0] < 1e-12 else float("nan")
        # contact radius: outermost zero crossing of the gap between consecutive surface nodes
        g, rr = gap[order], X1[order, 0]
        cross = np.nonzero((g[:-1] < 0) != (g[1:] < 0))[0]
        a = max((rr[i] + (rr[i + 1] - rr[i]) * g[i] / (g[i] - g[i + 1]) for i in cross), default=0.0)
        field = f"field_{k}.xdmf"
        with dolfinx.io.XDMFFile(comm, field, "w") as xf:
            xf.write_mesh(msh)
            xf.write_function(u)
            xf.write_function(pressure)
        out.writerow([k, repr(d), repr(P_contact), repr(P_top), repr(p0), "penalty-nodal-pole",
                      repr(a), its, int(bool(converged)), field])
        f.flush()
        print(f"d={d} P={P_contact} iterations={its}", flush=True)
