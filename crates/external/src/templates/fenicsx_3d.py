"""spherecontact deck `fenicsx-3d`, generated from scene "@SCENE@".

Two identical elastic spheres (Dundurs beta = 0) along a loading path, by DOLFINx (Debian's 0.5.2,
run by /usr/bin/python3, serial or under mpirun). The pressure is even and the tangential
displacement odd across the contact plane, so one sphere against its symmetry plane is exact, and
the normal and tangential contact problems decouple (the normal displacement that a tangential
traction causes is equal and opposite on the two spheres). The path shifts along x only, so half of
the sphere, y >= 0, is modelled with u_y = 0 on the plane y = 0. Units mm, N, MPa:
  body:        the half hemisphere (or cap) of the quadratic-tetrahedron gmsh mesh, P2 displacement;
               the far face is gripped rigidly: u = (t, 0, -d), d = delta_n/2, t = delta_t/2;
  normal:      frictionless penalty contact p_j = k <-(A (zs + w))_j>_+ at the candidate nodes,
               zs the sphere's height above the plane, w the nodes' u_z, A the averaging below;
  tangential:  Coulomb's law with history on the contact surface (the disc |q| <= mu p), with p
               from the normal problem: stick is a penalty k on the displacement (u_x, u_y) since
               the last slip s; slip carries |T| = mu p along the trial traction.
Contact rule (fem-3d's default, Rule::Corners in crates/solvers/src/fem/solid3d/surface.rs): the multipliers
live at the corners of the 6-node contact triangles and are linear on each face (hats L_j). Corner
j's multiplier lambda_j = om_j p_j, om_j = int L_j dA > 0 (A/3 of each face's area A around it),
acts on the body as the DOF forces A^T lambda and sees the averaged displacement A u,
A_jk = int L_j N_k dA / om_j (N_k the P2 shape functions): rows of A sum to one, so
P = sum lambda, and a uniform pressure gives the consistent P2 load (corners zero). A multiplier
space one order below the displacements' is stable: multipliers at every node oscillate from node
to node, and plain nodal lumping lets the corner nodes lift off inside the contact. The faces are
read from the mesh file (rank 0, gmsh API); candidates are the nodes of the contact faces wholly
within r_cand of the pole (their DOFs are condensed), the contact points their corners.
The stiffness is assembled and factored once (MUMPS, distributed over the MPI ranks) and condensed
onto the candidates' DOFs by multi-right-hand-side solves (u_z at every candidate; u_x, u_y where
free): the compliance C and its inverse S. Each path step then solves, on every rank alike,
  normal:      S_z (w + d) = A^T k om <-A (zs + w)>_+                  (active-set Newton)
  tangential:  S_t (v - v_t) = A^T om T, T = return mapping of the trial -k (A v - s)
by Newton with the consistent tangent of the disc: an all-stick (elastic) predictor first at every
increment (so a reversal restarts from stick), then Newton with an Armijo line search on the
problem's convex energy, and a cap of maxit iterations (a capped increment is flagged, outcome 0).
Rank 0 writes steps.csv (one row per computed step, P and Q of the whole sphere), surface.csv
(the contact points of the half surface at every computed step), triangles.csv (the faces, as
contact points), field_<position>.xdmf (u of the
normal and of the tangential problem) at path positions, and timing.csv (CPU and wall seconds of
the set-up and of the path).
"""
@FENICSX_COMMON@
import scipy.spatial  # noqa: E402 (after the shared block)

CONTACT, FAR, SYMMETRY = 1, 2, 3
TRIANGLE6 = 9  # gmsh's 6-node triangle


def contact_candidates():
    """Rank 0, from the mesh's contact faces: the candidate nodes (mm), the contact points (the
    faces' corners, mm), their weights om, the averaging A (points x nodes) and the faces as
    triangles of points."""
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
    corners, corner_of = np.unique(faces[:, :3], return_inverse=True)
    corner_of = corner_of.reshape(-1, 3)
    area = np.zeros(len(local))  # the curved face's area from its four flat sub-triangles
    for sub in ((0, 3, 5), (3, 1, 4), (5, 4, 2), (3, 4, 5)):
        a, b, c = (xyz[nodes[local[:, i]]] for i in sub)
        area += 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    coupling = np.zeros((len(corners), len(nodes)))
    for face, points, face_area in zip(local, corner_of, area):
        coupling[np.ix_(points, face)] += 2.0 * face_area * REFERENCE_COUPLING
    weights = coupling.sum(axis=1)
    return xyz[nodes], xyz[corners], weights, coupling / weights[:, None], corner_of


def reference_coupling():
    """M[j, k] = int L_j N_k over the reference triangle (area 1/2): L_j the linear hat of corner
    j, N_k the P2 shape functions (a 6-point degree-4 rule: exact for the cubic products)."""
    def shapes(x):
        l0, l1, l2 = 1 - x[0] - x[1], x[0], x[1]
        return np.array([l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1),
                         4 * l0 * l1, 4 * l1 * l2, 4 * l2 * l0])

    a, b = 0.445948490915965, 0.091576213509771
    rule = [((a, a, 1 - 2 * a), 0.223381589678011), ((b, b, 1 - 2 * b), 0.109951743655322)]
    M = np.zeros((3, 6))
    for (l0, l1, l2), weight in rule:
        for bary in ((l0, l1, l2), (l1, l2, l0), (l2, l0, l1)):
            M += 0.5 * weight * np.outer(bary, shapes(bary[1:]))
    return M


# gmsh's 6-node triangle: corners 0 1 2, midsides 3 (0-1), 4 (1-2), 5 (2-0)
REFERENCE_COUPLING = reference_coupling()


gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
candidates = None
if root:  # gmshio.read_from_msh is broken in 0.5.2: merge by hand, then model_to_mesh
    gmsh.merge(MESH)
    candidates = contact_candidates()
msh, _, ftags = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=3)
gmsh.finalize()
XC, XP, om, Avg, faces = comm.bcast(candidates, root=0)
msh.geometry.x[:, :] *= 1000.0  # m -> mm
m, npt = len(XC), len(XP)  # candidate nodes, contact points
rc = np.hypot(XC[:, 0], XC[:, 1])
assert npt > 3 and np.hypot(XP[:, 0], XP[:, 1]).min() < 1e-9 * R, "the pole must be a contact point"
zs = R - np.sqrt(R * R - rc * rc)  # the sphere's height at each candidate (exact geometry)
on_sym = np.abs(XC[:, 1]) <= 1e-9 * R      # candidate nodes on y = 0 (u_y = 0)
on_sym_p = np.abs(XP[:, 1]) <= 1e-9 * R    # contact points on y = 0 (q_y = 0 by symmetry)
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
K, ksp = factored(ufl.inner(sig(u), eps(v_)) * dx, bcs)
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


def averaged(v):
    """The averaged displacement (A u_x, A u_y) that each contact point's multiplier sees; its y
    part is zero on the symmetry plane, where q_y vanishes by symmetry."""
    out = Avg @ nodal(v)
    out[on_sym_p, 1] = 0.0
    return out


def nodal_forces(T):
    """The DOF forces A^T (om T) of the points' tractions T (npt x 2), in the unknowns' layout."""
    return unknowns(Avg.T @ (om[:, None] * T))


def unknowns(a):
    """The tangential unknowns of nodal pairs a (m x 2)."""
    return np.concatenate([a[:, 0], a[~on_sym, 1]])


def tractions(v, s, p, predictor):
    """The return mapping on the disc: traction T (npt x 2) [MPa] on the body, stick flags, and
    the tangent dT/dv per contact point (npt x 2 x 2, times -k).

    Trial (stick) traction T = -k (v - s); stick where |T| <= mu p (every touching node for the
    elastic predictor): T = trial, tangent I; slip: T = mu p trial/|trial|, tangent
    (mu p/|trial|)(I - n n^T); free nodes: T = 0, tangent 0."""
    trial = -k * (averaged(v) - s)
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
    """B^T (k om tangent) B, B the map from the unknowns to the averaged pairs (dense)."""
    block = k * om[:, None, None] * tangent
    block[on_sym_p, 1, :] = 0.0
    block[on_sym_p, :, 1] = 0.0
    D = np.zeros((2 * npt, 2 * npt))
    for a in range(2):
        for b in range(2):
            D[a * npt:(a + 1) * npt, b * npt:(b + 1) * npt] = np.diag(block[:, a, b])
    return B.T @ D @ B


# B: the tangential unknowns -> the points' averaged pairs, x block then y block (y zero on y = 0)
B = np.zeros((2 * npt, n1))
B[:npt, ix] = Avg
B[npt:, iy[~on_sym]] = Avg[:, ~on_sym]
B[npt + np.flatnonzero(on_sym_p), :] = 0.0


def solve_tangential(t, v, s, p):
    """Coulomb with history at shift t: (v, iterations, outcome).

    With p fixed, the penalty-regularised problem minimises the convex, C1 energy
      E(v) = 1/2 (v - v_t).St (v - v_t) + sum_i om_i psi(|v_i - s_i|),
      psi(x) = k x^2/2 (k x <= mu p), mu p x - (mu p)^2/(2k) (beyond),
    whose gradient is the residual R(v) = St (v - v_t) - om T(v) and whose generalised Hessian is
    St + k om (the return mapping's tangent). Iteration 0 is the elastic predictor (every touching
    node sticks: one linear solve); then Newton: the full step where it reduces |R| without raising
    E (beyond E's round-off), else an Armijo backtracking on E (a descent method on a convex
    function: no cycling; accepting full steps on |R| alone let the iterates wander and hit the
    cap at 0.5 um increments with the averaged rule). Outcome 1: |R| below 1e-10 of its scale; outcome 0: the cap
    maxit was hit (the increment is flagged; the last iterate is kept)."""
    v_t = unknowns(np.column_stack([np.full(m, t), np.zeros(m)]))
    scale = np.linalg.norm(St @ v_t) + np.linalg.norm(mu * p * om) + 1e-300
    tol = 1e-10 * scale
    limit = mu * np.maximum(p, 0.0)

    def residual(v, predictor):
        T, stick, tangent = tractions(v, s, p, predictor)
        return St @ (v - v_t) - nodal_forces(T), tangent

    def energy(v):
        x = averaged(v) - s
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
        e0 = energy(v)
        if (np.linalg.norm(residual(v - delta, False)[0]) >= rn
                or energy(v - delta) > e0 + 1e-12 * abs(e0)):
            # the full step raises |R| or E: backtrack on E (near the solution E's changes fall
            # below its round-off, 1e-12 of E, so there the full step is taken whenever |R| falls)
            slope = res @ delta
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
s = np.zeros((npt, 2))               # the history: where each point's stick spring is anchored
f = np.zeros(m)
out = nodes = None
if root:
    with open("triangles.csv", "w", newline="") as ft:  # the faces (p is linear on each), as
        # indices of surface.csv's rows (the contact points) within a step
        csv.writer(ft).writerows([["a", "b", "c"]] + faces.tolist())
    fs, fn = open("steps.csv", "w", newline=""), open("surface.csv", "w", newline="")
    out, nodes = csv.writer(fs), csv.writer(fn)
    out.writerow(["step", "d_mm", "t_mm", "P_contact_N", "P_top_N", "Q_N",
                  "iterations_normal", "iterations_tangential", "outcome", "field_file"])
    nodes.writerow(["step", "x_mm", "y_mm", "weight_mm2", "gap_mm", "p_MPa", "qx_MPa", "qy_MPa",
                    "stick", "slip_x_mm", "slip_y_mm"])
d_prev = None
for step, d, t, position in zip(steps, dlist, tlist, fields):
    if d != d_prev:
        w, f, its0, ok0 = solve_normal(Sz, d, w, spd_solve, Avg)
        d_prev = d
    else:
        its0, ok0 = 0, True
    gap = Avg @ (zs + w)
    p = np.maximum(-gap, 0.0) * k
    P = 2 * f.sum()  # both halves y >= 0 and y <= 0 (the rows of A sum to one: sum f = sum om p)
    Q, its1, outcome1 = 0.0, 0, 1
    q = np.zeros((npt, 2))
    stick = p > 0
    slip = np.zeros((npt, 2))
    if tangential:
        v, its1, outcome1 = solve_tangential(t, v, s, p)
        T, stick, _ = tractions(v, s, p, False)
        # return mapping: a slipping node's history moves to where its trial traction is mu p; a
        # node out of contact carries no force (T = 0) and its history follows it, at the end of
        # the increment: a node that comes into contact at the next one sticks from where it
        # stood at that increment's start (its slip is measured over the increment)
        moved = ~stick
        s = np.where(moved[:, None], averaged(v) + T / k, s)
        q = -T                                   # the traction of the plane on the body is -T
        Q = 2 * (om * q[:, 0]).sum()             # q_y is odd in y: the halves' Q_y cancel
        slip = 2.0 * averaged(v)                 # relative displacement of the two surfaces
    field = "-"
    if position >= 0:
        field = f"field_{position}.xdmf"
        with dolfinx.io.XDMFFile(comm, field, "w") as xf:
            xf.write_mesh(msh)
            xf.write_function(full_field(z_dofs, f, "u_normal", np.array([0.0, 0.0, -d])))
            if tangential:
                T = -q
                xf.write_function(full_field(t_dofs, nodal_forces(T), "u_tangential",
                                             np.array([t, 0.0, 0.0])))
    if root:
        out.writerow([step, repr(d), repr(t), repr(P), "", repr(Q), its0, its1,
                      outcome1 if ok0 else 0, field])
        for i in range(npt):
            nodes.writerow([step, repr(XP[i, 0]), repr(XP[i, 1]), repr(om[i]), repr(gap[i]),
                            repr(p[i]), repr(q[i, 0]), repr(q[i, 1]), int(stick[i] and p[i] > 0),
                            repr(slip[i, 0]), repr(slip[i, 1])])
if root:
    fs.close()
    fn.close()
    clock_end, wall_end = time.process_time(), time.perf_counter()
    with open("timing.csv", "w") as ft:
        ft.write(f"phase,seconds\nsetup,{clock_setup - clock_start!r}\npath,{clock_end - clock_path!r}\n"
                 f"setup_wall,{wall_setup - wall_start!r}\npath_wall,{wall_end - wall_path!r}\n"
                 f"ranks,{comm.size}\ndofs,{ndofs}\ncandidates,{m}\npoints,{npt}\n")
    print(f"done: {len(steps)} steps, {m} candidates, {npt} contact points, {ndofs} DOFs, "
          f"{comm.size} ranks", flush=True)
