"""spherecontact deck `fenicsx-3d`, generated from scene "@SCENE@".

Two identical elastic spheres (Dundurs beta = 0) along a loading path, by DOLFINx (Debian's 0.5.2,
run by /usr/bin/python3, serial or under mpirun). The pressure is even and the tangential
displacement odd across the contact plane, so one sphere against its symmetry plane is exact, and
the normal and tangential contact problems decouple (the normal displacement that a tangential
traction causes is equal and opposite on the two spheres). The path shifts along x only, so half of
the sphere, y >= 0, is modelled with u_y = 0 on the plane y = 0. Units mm, N, MPa:
  body:        the half hemisphere (or cap) of the quadratic-tetrahedron gmsh mesh, P2 displacement;
               the far face is gripped rigidly: u = (t, 0, -d), d = delta_n/2, t = delta_t/2;
  normal:      frictionless penalty contact p_i = k <-(zs_i + w_i)>_+ at the candidate nodes,
               zs the sphere's height above the plane, w the node's u_z;
  tangential:  Coulomb's law with history on the contact surface (the disc |q| <= mu p), with p
               from the normal problem: stick is a penalty k on the displacement (u_x, u_y) since
               the last slip s; slip carries |T| = mu p along the trial traction.
Contact quadrature: nodal. Each 6-node contact triangle is split into its four 3-node
sub-triangles (corner, mid, mid and the middle one), and each sub-triangle's area is lumped to its
vertices: a corner node gets A/12, a midside node A/4 of the face's area A; the weights are
positive (the consistent P2 load gives corners zero) and sum to the area (P exact under a uniform
pressure). The weights are computed from the mesh file, the contact faces wholly within r_cand of
the pole being the candidates.
The stiffness is assembled and factored once (MUMPS, distributed over the MPI ranks) and condensed
onto the candidates' DOFs by multi-right-hand-side solves (u_z at every candidate; u_x, u_y where
free): the compliance C and its inverse S. Each path step then solves, on every rank alike,
  normal:      S_z (w + d) = f(w),       f_i = k om_i <-(zs_i + w_i)>_+   (active-set Newton)
  tangential:  S_t (v - v_t) = F(v),     F = return mapping of the trial -k om (v - s)
by Newton with the consistent tangent of the disc: an all-stick (elastic) predictor first at every
increment (so a reversal restarts from stick), then Newton with an Armijo line search on the
problem's convex energy, and a cap of maxit iterations (a capped increment is flagged, outcome 0).
Rank 0 writes steps.csv (one row per computed step, P and Q of the whole sphere), surface.csv
(candidate nodes of the half surface at every computed step), field_<position>.xdmf (u of the
normal and of the tangential problem) at path positions, and timing.csv (CPU and wall seconds of
the set-up and of the path).
"""
@FENICSX_COMMON@
import scipy.spatial  # noqa: E402 (after the shared block)

CONTACT, FAR, SYMMETRY = 1, 2, 3
TRIANGLE6 = 9  # gmsh's 6-node triangle


def contact_candidates():
    """Rank 0: the candidate nodes (mm) and their nodal weights from the mesh's contact faces."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = np.zeros((int(tags.max()) + 1, 3))
    xyz[tags.astype(np.int64)] = coords.reshape(-1, 3) * 1000.0  # m -> mm
    faces = []
    for entity in gmsh.model.getEntitiesForPhysicalGroup(2, CONTACT):
        types, _, nodes = gmsh.model.mesh.getElements(2, entity)
        for kind, tri in zip(types, nodes):
            assert kind == TRIANGLE6, f"{MESH}: contact faces must be 6-node triangles (gmsh type 9)"
            faces.append(tri.reshape(-1, 6).astype(np.int64))
    faces = np.concatenate(faces)
    r = np.hypot(xyz[faces, 0], xyz[faces, 1])
    faces = faces[(r <= r_cand).all(axis=1)]
    nodes, local = np.unique(faces, return_inverse=True)
    local = local.reshape(-1, 6)
    weights = np.zeros(len(nodes))
    # gmsh's 6-node triangle: corners 0 1 2, midsides 3 (0-1), 4 (1-2), 5 (2-0)
    for sub in ((0, 3, 5), (3, 1, 4), (5, 4, 2), (3, 4, 5)):
        a, b, c = (xyz[nodes[local[:, i]]] for i in sub)
        area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
        for i in sub:
            np.add.at(weights, local[:, i], area / 3.0)
    return xyz[nodes], weights, local


gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
candidates = None
if root:  # gmshio.read_from_msh is broken in 0.5.2: merge by hand, then model_to_mesh
    gmsh.merge(MESH)
    candidates = contact_candidates()
msh, _, ftags = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=3)
gmsh.finalize()
XC, om, faces = comm.bcast(candidates, root=0)
msh.geometry.x[:, :] *= 1000.0  # m -> mm
m = len(om)
rc = np.hypot(XC[:, 0], XC[:, 1])
assert m > 3 and rc.min() < 1e-9 * R, "the pole must be a candidate contact node"
zs = R - np.sqrt(R * R - rc * rc)  # the sphere's height at each candidate (exact geometry)
on_sym = np.abs(XC[:, 1]) <= 1e-9 * R
fdim = msh.topology.dim - 1
dx = ufl.Measure("dx", domain=msh, metadata={"quadrature_degree": 2})


def eps(w):
    return ufl.sym(ufl.grad(w))


def sig(w):
    return lam * ufl.tr(eps(w)) * ufl.Identity(3) + 2 * G * eps(w)


# ---------------------------------------- stiffness, factorisation ----------------------------------
V = fem.FunctionSpace(msh, ufl.VectorElement("Lagrange", msh.ufl_cell(), 2))
u, v_ = ufl.TrialFunction(V), ufl.TestFunction(V)
far = fem.locate_dofs_topological(V, fdim, ftags.find(FAR))
sym_y = fem.locate_dofs_topological(V.sub(1), fdim, ftags.find(SYMMETRY))
bcs = [fem.dirichletbc(np.zeros(3, dtype=PETSc.ScalarType), far, V),
       fem.dirichletbc(PETSc.ScalarType(0.0), sym_y, V.sub(1))]
K = fem.petsc.assemble_matrix(fem.form(ufl.inner(sig(u), eps(v_)) * dx), bcs=bcs)
K.assemble()
ksp = PETSc.KSP().create(comm)
ksp.setOperators(K)
ksp.setType("preonly")
ksp.getPC().setType("lu")
ksp.getPC().setFactorSolverType("mumps")
ksp.setUp()
ndofs = V.dofmap.index_map.size_global * 3

# ---------------------------------------- the candidates' DOFs --------------------------------------
imap = V.dofmap.index_map
owned = V.tabulate_dof_coordinates()[: imap.size_local]
dist, j_of = scipy.spatial.cKDTree(XC).query(owned, distance_upper_bound=1e-6 * h)
mine = np.flatnonzero(np.isfinite(dist))
found = comm.allgather((j_of[mine], imap.local_range[0] + mine))
node_of = np.full(m, -1, dtype=np.int64)
for js, gs in found:
    node_of[js] = gs
assert (node_of >= 0).all(), "a candidate node has no P2 DOF at its position"
# unknowns: u_z at every candidate (normal); u_x at every candidate, u_y off the symmetry plane
z_dofs = 3 * node_of + 2
ix = np.arange(m)
iy = m + np.cumsum(~on_sym) - 1
t_dofs = np.concatenate([3 * node_of, 3 * node_of[~on_sym] + 1])
n1 = len(t_dofs)
lo, hi = K.getOwnershipRange()


def compliance(dof_list, block=64):
    """C[i, j]: the displacement at dof_list[i] under a unit force at dof_list[j] (K^-1 by MUMPS,
    blocks of right-hand sides, gathered on every rank)."""
    n = len(dof_list)
    nloc = hi - lo
    C = np.zeros((n, n))
    rows = np.flatnonzero((dof_list >= lo) & (dof_list < hi))
    for start in range(0, n, block):
        cols = range(start, min(start + block, n))
        B = PETSc.Mat().createDense([(nloc, None), (None, len(cols))], comm=comm)
        B.setUp()
        for c, j in enumerate(cols):
            if lo <= dof_list[j] < hi:
                B.setValue(int(dof_list[j]), c, 1.0)
        B.assemble()
        X = PETSc.Mat().createDense([(nloc, None), (None, len(cols))], comm=comm)
        X.setUp()
        X.assemble()
        ksp.getPC().getFactorMatrix().matSolve(B, X)
        local = X.getDenseArray()
        part = np.zeros((n, len(cols)))
        part[rows] = local[dof_list[rows] - lo]
        C[:, start:start + len(cols)] = comm.allreduce(part, op=MPI.SUM)
        B.destroy()
        X.destroy()
    return 0.5 * (C + C.T)


Sz = scipy.linalg.inv(compliance(z_dofs))
St = scipy.linalg.inv(compliance(t_dofs)) if tangential else None
clock_setup, wall_setup = time.process_time(), time.perf_counter()


def spd_solve(S, D, b):
    """(S + D) x = b, S a condensed stiffness, D >= 0 the contact's tangent (a matrix, or a
    vector: its diagonal)."""
    return scipy.linalg.cho_solve(scipy.linalg.cho_factor(S + (D if D.ndim == 2 else np.diag(D))), b)


def nodal(v):
    """(u_x, u_y) at every candidate from the tangential unknowns (u_y = 0 on y = 0)."""
    out = np.zeros((m, 2))
    out[:, 0] = v[ix]
    out[~on_sym, 1] = v[iy[~on_sym]]
    return out


def unknowns(a):
    """The tangential unknowns of nodal pairs a (m x 2)."""
    return np.concatenate([a[:, 0], a[~on_sym, 1]])


def tractions(v, s, p, predictor):
    """The return mapping on the disc: traction T (m x 2) [MPa] on the body, stick flags, and the
    tangent dT/dv per node (m x 2 x 2, times -k).

    Trial (stick) traction T = -k (v - s); stick where |T| <= mu p (every touching node for the
    elastic predictor): T = trial, tangent I; slip: T = mu p trial/|trial|, tangent
    (mu p/|trial|)(I - n n^T); free nodes: T = 0, tangent 0."""
    trial = -k * (nodal(v) - nodal(s))
    norm = np.hypot(trial[:, 0], trial[:, 1])
    touching = p > 0
    stick = touching & (predictor | (norm <= mu * p))
    slip = touching & ~stick
    n = trial / np.maximum(norm, 1e-300)[:, None]
    T = np.where(stick[:, None], trial, np.where(slip[:, None], mu * p[:, None] * n, 0.0))
    ratio = np.where(slip, mu * p / np.maximum(norm, 1e-300), 0.0)
    eye = np.eye(2)[None]
    tangent = (stick[:, None, None] * eye
               + ratio[:, None, None] * (eye - n[:, :, None] * n[:, None, :]))
    return T, stick, tangent


def jacobian_of_forces(tangent):
    """k om tangent, scattered on the tangential unknowns (a dense matrix)."""
    D = np.zeros((n1, n1))
    block = k * om[:, None, None] * tangent
    D[ix, ix] += block[:, 0, 0]
    free_y = ~on_sym
    D[ix[free_y], iy[free_y]] += block[free_y, 0, 1]
    D[iy[free_y], ix[free_y]] += block[free_y, 1, 0]
    D[iy[free_y], iy[free_y]] += block[free_y, 1, 1]
    return D


def solve_tangential(t, v, s, p):
    """Coulomb with history at shift t: (v, iterations, outcome).

    With p fixed, the penalty-regularised problem minimises the convex, C1 energy
      E(v) = 1/2 (v - v_t).St (v - v_t) + sum_i om_i psi(|v_i - s_i|),
      psi(x) = k x^2/2 (k x <= mu p), mu p x - (mu p)^2/(2k) (beyond),
    whose gradient is the residual R(v) = St (v - v_t) - om T(v) and whose generalised Hessian is
    St + k om (the return mapping's tangent). Iteration 0 is the elastic predictor (every touching
    node sticks: one linear solve); then Newton: the full step where it reduces |R|, else an Armijo
    backtracking on E (a descent method on a convex function: no cycling). Outcome 1: |R| below 1e-10 of its scale; outcome 0: the cap
    maxit was hit (the increment is flagged; the last iterate is kept)."""
    v_t = unknowns(np.column_stack([np.full(m, t), np.zeros(m)]))
    scale = np.linalg.norm(St @ v_t) + np.linalg.norm(mu * p * om) + 1e-300
    tol = 1e-10 * scale
    limit = mu * np.maximum(p, 0.0)

    def residual(v, predictor):
        T, stick, tangent = tractions(v, s, p, predictor)
        return St @ (v - v_t) - unknowns(om[:, None] * T), tangent

    def energy(v):
        x = nodal(v) - nodal(s)
        norm = np.hypot(x[:, 0], x[:, 1])
        psi = np.where(k * norm <= limit, 0.5 * k * norm ** 2, limit * norm - limit ** 2 / (2 * k))
        e = v - v_t
        return 0.5 * e @ (St @ e) + (om * np.where(p > 0, psi, 0.0)).sum()

    for it in range(maxit + 1):
        res, tangent = residual(v, it == 0)
        rn = np.linalg.norm(res)
        if it > 0 and rn <= tol:
            return v, it, 1
        if it == maxit:
            break
        delta = spd_solve(St, jacobian_of_forces(tangent), res)
        if it == 0:
            v = v - delta  # the elastic predictor: a linear solve, no line search
            continue
        alpha = 1.0
        if np.linalg.norm(residual(v - delta, False)[0]) >= rn:
            # the full step does not reduce |R|: backtrack on E (near the solution E's decrease
            # falls below its round-off first, so the full step is taken whenever |R| falls)
            e0, slope = energy(v), res @ delta
            while alpha > 1e-6 and energy(v - alpha * delta) > e0 - 1e-4 * alpha * slope:
                alpha *= 0.5
        v = v - alpha * delta
    return v, maxit, 0


def full_field(dof_list, loads, name, rigid):
    """The displacement of the whole body: K^-1 (contact loads) plus the rigid motion."""
    b = K.createVecRight()
    b.set(0.0)
    owned_loads = (dof_list >= lo) & (dof_list < hi)
    b.setValues(dof_list[owned_loads].astype(np.int32), loads[owned_loads])
    b.assemble()
    w = fem.Function(V)
    ksp.solve(b, w.vector)
    w.x.scatter_forward()
    w.x.array[:] += np.tile(rigid, len(w.x.array) // 3)
    w.name = name
    return w


# ---------------------------------------- the path ----------------------------------------------
clock_path, wall_path = time.process_time(), time.perf_counter()
w = np.zeros(m)                      # u_z at the candidates
v = np.zeros(n1)                     # (u_x, u_y) at the candidates, unknowns layout
s = np.zeros(n1)                     # the history: where each node's stick spring is anchored
f = np.zeros(m)
out = nodes = None
if root:
    fs, fn = open("steps.csv", "w", newline=""), open("surface.csv", "w", newline="")
    out, nodes = csv.writer(fs), csv.writer(fn)
    out.writerow(["step", "d_mm", "t_mm", "P_contact_N", "P_top_N", "Q_N",
                  "iterations_normal", "iterations_tangential", "outcome", "field_file"])
    nodes.writerow(["step", "x_mm", "y_mm", "weight_mm2", "gap_mm", "p_MPa", "qx_MPa", "qy_MPa",
                    "stick", "slip_x_mm", "slip_y_mm"])
d_prev = None
for step, d, t, position in zip(steps, dlist, tlist, fields):
    if d != d_prev:
        w, f, its0, ok0 = solve_normal(Sz, d, w, spd_solve)
        d_prev = d
    else:
        its0, ok0 = 0, True
    p = np.maximum(-(zs + w), 0.0) * k
    P = 2 * f.sum()  # both halves y >= 0 and y <= 0
    Q, its1, outcome1 = 0.0, 0, 1
    q = np.zeros((m, 2))
    stick = p > 0
    slip = np.zeros((m, 2))
    if tangential:
        # nodes out of contact carry no force: their history follows them
        free = p <= 0
        s = unknowns(np.where(free[:, None], nodal(v), nodal(s)))
        v, its1, outcome1 = solve_tangential(t, v, s, p)
        T, stick, _ = tractions(v, s, p, False)
        # return mapping: a slipping node's history moves to where its trial traction is mu p
        slipping = (p > 0) & ~stick
        s = unknowns(np.where(slipping[:, None], nodal(v) + T / k, nodal(s)))
        q = -T                                   # the traction of the plane on the body is -T
        Q = 2 * (om * q[:, 0]).sum()             # q_y is odd in y: the halves' Q_y cancel
        slip = 2.0 * nodal(v)                    # relative displacement of the two surfaces
    field = "-"
    if position >= 0:
        field = f"field_{position}.xdmf"
        with dolfinx.io.XDMFFile(comm, field, "w") as xf:
            xf.write_mesh(msh)
            xf.write_function(full_field(z_dofs, f, "u_normal", np.array([0.0, 0.0, -d])))
            if tangential:
                T = -q
                xf.write_function(full_field(t_dofs, unknowns(om[:, None] * T), "u_tangential",
                                             np.array([t, 0.0, 0.0])))
    if root:
        out.writerow([step, repr(d), repr(t), repr(P), "", repr(Q), its0, its1,
                      outcome1 if ok0 else 0, field])
        for i in range(m):
            nodes.writerow([step, repr(XC[i, 0]), repr(XC[i, 1]), repr(om[i]), repr(zs[i] + w[i]),
                            repr(p[i]), repr(q[i, 0]), repr(q[i, 1]), int(stick[i] and p[i] > 0),
                            repr(slip[i, 0]), repr(slip[i, 1])])
if root:
    fs.close()
    fn.close()
    clock_end, wall_end = time.process_time(), time.perf_counter()
    with open("timing.csv", "w") as ft:
        ft.write(f"phase,seconds\nsetup,{clock_setup - clock_start!r}\npath,{clock_end - clock_path!r}\n"
                 f"setup_wall,{wall_setup - wall_start!r}\npath_wall,{wall_end - wall_path!r}\n"
                 f"ranks,{comm.size}\ndofs,{ndofs}\ncandidates,{m}\n")
    print(f"done: {len(steps)} steps, {m} candidates, {ndofs} DOFs, {comm.size} ranks", flush=True)
