"""spherecontact deck `fenicsx-axisym`, generated from scene "@SCENE@".

Two identical elastic spheres (Dundurs beta = 0) along a loading path, by DOLFINx (Debian's 0.5.2,
run by /usr/bin/python3). The pressure is even and the tangential displacement odd across the
contact plane, so one sphere against its symmetry plane is exact, and the problem splits into two
axisymmetric Fourier modes on the meridian (x[0] = r, x[1] = z; units mm, N, MPa):
  n = 0, normal:     u_r(r,z), u_z(r,z); the far face z = R approaches the plane by d = delta_n/2;
                     frictionless penalty contact p = k <-(zs(r) + u_z)>_+ on the spherical surface,
                     zs(r) = R - sqrt(R^2 - r^2) the sphere's height above the plane.
  n = 1, tangential: u_r = (A+B) cos th, u_th = -(A-B) sin th, u_z = W cos th; the far face shifts
                     by t = delta_t/2 along x (A = t, B = W = 0), the axis is regular (B = W = 0).
                     Coulomb's law with history on the contact line, with p(r) from n = 0
                     (Mindlin: the traction is parallel to x): stick is a penalty k on the
                     displacement A, B since the last slip; slip carries |T_A| = mu p, T_B = 0.
Both stiffnesses are assembled and factored once (P2 on the quadratic gmsh mesh, MUMPS). Contact
terms use nodal (Gauss-Lobatto) quadrature, so they act on the contact-line nodes only, and each
mode is condensed onto its candidate nodes (r <= r_c) by one solve per candidate DOF: the compliance
C and its inverse S. Each path step then solves the small contact problems
  n = 0:  S0 (w + d) = f(w),            f_i = k om_i <-(zs_i + w_i)>_+      (semi-smooth Newton)
  n = 1:  S1 (v - v_t) = F(v),          F = return mapping of the trial -k om1 (v - s)
by semi-smooth Newton: an all-stick (elastic) predictor first at every increment, then Newton with
a backtracking line search on |R|, a cycle guard, and a cap of maxit iterations (a capped increment
is flagged). History s (per contact node) follows free nodes, and is updated by the return mapping
at slip. Writes steps.csv (one row per computed step), surface.csv (candidate nodes at every
computed step), field_<position>.xdmf (u, u1 and the surface fields) at path positions, and
timing.csv (CPU seconds of the set-up and of the path).
"""
@FENICSX_COMMON@
grip_radial = @GRIP_RADIAL@        # 1: u_r = 0 on the far face in n = 0 (rigid grip); 0: free

# gmshio.read_from_msh is broken in 0.5.2: merge by hand, then model_to_mesh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.merge(MESH)
msh, _, ftags = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=2)
gmsh.finalize()
msh.geometry.x[:, :2] *= 1000.0  # m -> mm
fdim = msh.topology.dim - 1
x = ufl.SpatialCoordinate(msh)
r = x[0]
dx = ufl.Measure("dx", domain=msh, metadata={"quadrature_degree": 6})
# nodal contact quadrature: 3-point Gauss-Lobatto (Simpson) on the P2 contact edges
dsc = ufl.Measure("ds", domain=msh, subdomain_data=ftags,
                  metadata={"quadrature_rule": "GLL", "quadrature_degree": 3})
CONTACT, TOP, AXIS = 1, @FAR_TAG@, 3   # the far face's tag carries the grip (2 axial, 4 rigid)


def eps0(w):  # n = 0 strains (rr, zz, rz, theta-theta)
    return ufl.as_tensor([[w[0].dx(0), 0.5 * (w[0].dx(1) + w[1].dx(0)), 0],
                          [0.5 * (w[0].dx(1) + w[1].dx(0)), w[1].dx(1), 0],
                          [0, 0, w[0] / r]])


def sig0(w):
    return lam * ufl.tr(eps0(w)) * ufl.Identity(3) + 2 * G * eps0(w)


def strains1(w):  # n = 1 strain amplitudes: rr, tt, zz, rz, rt, tz (U = A + B, V = A - B)
    A, B, W = w[0], w[1], w[2]
    U, V = A + B, A - B
    return (U.dx(0), 2 * B / r, W.dx(1), U.dx(1) + W.dx(0), V.dx(0) + 2 * B / r, V.dx(1) + W / r)


def a1(w, v):
    e, f = strains1(w), strains1(v)
    tr_e, tr_f = e[0] + e[1] + e[2], f[0] + f[1] + f[2]
    return (lam * tr_e * tr_f + 2 * G * (e[0] * f[0] + e[1] * f[1] + e[2] * f[2])
            + G * (e[3] * f[3] + e[4] * f[4] + e[5] * f[5]))


def dofs(space, tag):
    return fem.locate_dofs_topological(space, fdim, ftags.find(tag))


# ---------------------------------------- spaces, candidates, nodal weights ------------------------
S = fem.FunctionSpace(msh, ("Lagrange", 2))
XS = S.tabulate_dof_coordinates()
surface = dofs(S, CONTACT)
cand = surface[XS[surface, 0] <= r_cand]
cand = cand[np.argsort(XS[cand, 0])]
m = len(cand)
assert m > 2 and XS[cand[0], 0] < 1e-9 * R, "the pole must be a candidate contact node"
rc = XS[cand, 0].copy()
rc[0] = 0.0  # the pole, exactly (the mm scaling leaves round-off of 1e-18 there)
zs = R - np.sqrt(R * R - rc * rc)  # the sphere's height at each candidate (exact geometry)
v_s = ufl.TestFunction(S)
omega_all = fem.petsc.assemble_vector(fem.form(r * v_s * dsc(CONTACT)))
om = omega_all.array[cand].copy()  # om_i = int N_i r ds (nodal rule): contact force per radian f = om p
om[0] = 0.0  # r = 0 at the pole


def collapse_map(space, component):
    """Indices in `space` of component `component` at the scalar dofs of S (same P2 layout)."""
    sub, sub_map = space.sub(component).collapse()
    assert np.allclose(sub.tabulate_dof_coordinates(), XS)
    return np.asarray(sub_map)


def green(ksp, A, dof_list):
    """Compliance at dof_list: column j is K^-1 e_j read at dof_list (one multi-RHS solve)."""
    n, nc = A.getSize()[0], len(dof_list)
    B = PETSc.Mat().createDense([n, nc], comm=comm)
    B.setUp()
    for j, d in enumerate(dof_list):
        B.setValue(int(d), j, 1.0)
    B.assemble()
    X = PETSc.Mat().createDense([n, nc], comm=comm)
    X.setUp()
    X.assemble()
    ksp.getPC().getFactorMatrix().matSolve(B, X)
    full = X.getDenseArray()
    return full[np.asarray(dof_list), :].copy()


# ---------------------------------------- n = 0: normal mode ----------------------------------------
V0 = fem.FunctionSpace(msh, ufl.VectorElement("Lagrange", msh.ufl_cell(), 2))
u0, t0 = ufl.TrialFunction(V0), ufl.TestFunction(V0)
bcs0 = [fem.dirichletbc(PETSc.ScalarType(0.0), dofs(V0.sub(1), TOP), V0.sub(1)),
        fem.dirichletbc(PETSc.ScalarType(0.0), dofs(V0.sub(0), AXIS), V0.sub(0))]
if grip_radial:
    bcs0.append(fem.dirichletbc(PETSc.ScalarType(0.0), dofs(V0.sub(0), TOP), V0.sub(0)))
K0, ksp0 = factored(ufl.inner(sig0(u0), eps0(t0)) * r * dx, bcs0)
u_react = fem.Function(V0)
react_form = fem.form(ufl.inner(sig0(u_react), eps0(t0)) * r * dx)
top_z = dofs(V0.sub(1), TOP)
z_of = collapse_map(V0, 1)
zdofs = z_of[cand]
C0 = green(ksp0, K0, zdofs)
C0 = 0.5 * (C0 + C0.T)
S0 = scipy.linalg.inv(C0)


FACTORS = {}  # Cholesky factors of S + diag(D) by (S, D): the two least recently used per S


def spd_solve(S, D, b):
    """(S + diag(D)) x = b, S a condensed stiffness, D >= 0 the penalties of the contact set.

    The predictor's and the iteration's contact sets recur from step to step: their factors are
    kept (the last two per S), each new one an O(n^3) Cholesky factorisation."""
    key = (id(S), D.tobytes())
    if key in FACTORS:
        FACTORS[key] = FACTORS.pop(key)  # the most recently used last
    else:
        mine = [kk for kk in FACTORS if kk[0] == id(S)]
        if len(mine) >= 2:
            del FACTORS[mine[0]]
        FACTORS[key] = scipy.linalg.cho_factor(S + np.diag(D))
    return scipy.linalg.cho_solve(FACTORS[key], b)


# ---------------------------------------- n = 1: tangential mode ------------------------------------
if tangential:
    V1 = fem.FunctionSpace(msh, ufl.VectorElement("Lagrange", msh.ufl_cell(), 2, dim=3))
    u1, t1 = ufl.TrialFunction(V1), ufl.TestFunction(V1)
    bcs1 = [fem.dirichletbc(PETSc.ScalarType(0.0), dofs(V1.sub(c), TOP), V1.sub(c)) for c in range(3)]
    bcs1 += [fem.dirichletbc(PETSc.ScalarType(0.0), dofs(V1.sub(c), AXIS), V1.sub(c)) for c in (1, 2)]
    K1, ksp1 = factored(a1(u1, t1) * r * dx, bcs1)
    A_of, B_of = collapse_map(V1, 0), collapse_map(V1, 1)
    axis_b = set(np.asarray(dofs(V1.sub(1), AXIS)).tolist())
    # unknowns: A at every candidate, B where it is free (not on the axis)
    hasB = np.array([B_of[c] not in axis_b for c in cand])
    iA = np.arange(m)
    iB = m + np.cumsum(hasB) - 1
    dofs1 = np.concatenate([A_of[cand], B_of[cand][hasB]])
    n1 = len(dofs1)
    C1 = green(ksp1, K1, dofs1)
    C1 = 0.5 * (C1 + C1.T)
    S1 = scipy.linalg.inv(C1)
    om1 = 2.0 * om  # the n = 1 contact work is 2 int (T_A A + T_B B) r ds: F = om1 T
    om1_dof = np.concatenate([om1, om1[hasB]])

    def expand(node_values_A, node_values_B):
        v = np.empty(n1)
        v[iA] = node_values_A
        v[iB[hasB]] = node_values_B[hasB]
        return v

    def nodal(v):
        """(A, B) at every candidate from the unknowns (B = 0 on the axis)."""
        return v[iA], np.where(hasB, v[np.where(hasB, iB, 0)], 0.0)

    def tractions(v, s, p, predictor):
        """The return mapping: tractions (T_A, T_B) [MPa] on the body, stick and slip signs.

        Trial (stick) traction T = -k (v - s); stick where |T_A| <= mu p (every touching node
        for the elastic predictor); slip: T_A = mu p sign(trial), T_B = 0; free nodes: 0."""
        (A, B), (sA, sB) = nodal(v), nodal(s)
        trial = -k * (A - sA)
        touching = p > 0
        stick = touching & (predictor | (np.abs(trial) <= mu * p))
        slip = touching & ~stick
        TA = np.where(stick, trial, np.where(slip, mu * p * np.sign(trial), 0.0))
        TB = np.where(stick, -k * (B - sB), 0.0)
        return TA, TB, stick, np.sign(trial) * slip

    def forces(v, s, p, predictor):
        """Generalised contact forces F = om1 T, stick flags, slip signs, Jacobian diagonal."""
        TA, TB, stick, sign = tractions(v, s, p, predictor)
        diag = np.where(stick, k, 0.0)
        return expand(om1 * TA, om1 * TB), stick, sign, expand(diag, diag) * om1_dof

    def solve_tangential(t, v, s, p):
        """Coulomb with history at shift t: (v, stick, iterations, outcome).

        Iteration 0 is the elastic predictor (every touching node sticks: one linear solve);
        then semi-smooth Newton on R(v) = S1 (v - v_t) - F(v) with a backtracking line search on
        |R|. Outcome 1: |R| at round-off, or the stick set and slip signs repeat after a full
        step (R is piecewise linear: the step was exact). Outcome 2: the iteration cycles
        between states (a node at the stick edge whose B traction switches off when it slips
        has no consistent state); the iterate of the cycle with the least |R| is kept.
        Outcome 0: the cap maxit was hit (the increment is flagged)."""
        v_t = expand(np.full(m, t), np.zeros(m))
        tol = 1e-10 * (np.linalg.norm(S1 @ v_t) + np.linalg.norm(mu * p * om1) + 1e-300)
        full_step, seen = False, []
        for it in range(maxit + 1):
            F, stick, sign, diag = forces(v, s, p, it == 0)
            res = S1 @ (v - v_t) - F
            rn = np.linalg.norm(res)
            key = (stick.tobytes(), sign.tobytes())
            if it > 0:
                if rn <= tol or (full_step and key == seen[-1][0]):
                    return v, stick, it, 1
                earlier = [j for j, e in enumerate(seen[1:-1], 1) if e[0] == key]
                if earlier and key != seen[-1][0]:
                    cycle = seen[earlier[0]:] + [(key, rn, v, stick)]
                    best = min(cycle, key=lambda e: e[1])
                    return best[2], best[3], it, 2
            if it == maxit:
                break
            seen.append((key, rn, v, stick))
            delta = spd_solve(S1, diag, res)
            if it == 0:
                v = v - delta  # the elastic predictor: a linear solve, no line search
                continue
            for alpha in (1.0, 0.5, 0.25, 0.125, 0.0625):
                trial_v = v - alpha * delta
                F2, _, _, _ = forces(trial_v, s, p, False)
                if np.linalg.norm(S1 @ (trial_v - v_t) - F2) <= max(rn, tol):
                    break
            full_step = alpha == 1.0
            v = trial_v
        return v, forces(v, s, p, False)[1], maxit, 0


# ---------------------------------------- fields at path positions ----------------------------------
def full_field(ksp, A, space, dof_list, loads, rigid):
    """The displacement of the whole body: K^-1 (contact loads) plus the rigid motion."""
    b = A.createVecRight()
    b.set(0.0)
    b.setValues(np.asarray(dof_list, dtype=np.int32), loads)
    b.assemble()
    u = fem.Function(space)
    ksp.solve(b, u.vector)
    u.x.scatter_forward()
    rigid(u)
    return u


def scalar(name, values):
    f = fem.Function(S)
    f.name = name
    f.x.array[:] = 0.0
    f.x.array[cand] = values
    return f


# ---------------------------------------- the path ----------------------------------------------
clock_path = time.process_time()
w = np.zeros(m)                 # u_z at the candidates
v = np.zeros(n1) if tangential else None
s = np.zeros(n1) if tangential else None
with open("steps.csv", "w", newline="") as fs, open("surface.csv", "w", newline="") as fn:
    out, nodes = csv.writer(fs), csv.writer(fn)
    out.writerow(["step", "d_mm", "t_mm", "P_contact_N", "P_top_N", "Q_N",
                  "iterations_normal", "iterations_tangential", "outcome", "field_file"])
    nodes.writerow(["step", "r_mm", "weight_mm2", "gap_mm", "p_MPa", "qx_MPa", "stick", "slip_mm"])
    d_prev = None
    for step, d, t, position in zip(steps, dlist, tlist, fields):
        if d != d_prev:
            w, f, its0, ok0 = solve_normal(S0, d, w, spd_solve)
            d_prev = d
        else:
            its0, ok0 = 0, True
        p = np.maximum(-(zs + w), 0.0) * k
        P = 2 * np.pi * f.sum()
        Q, its1, outcome1 = 0.0, 0, 1
        qx = np.zeros(m)
        stick = p > 0
        slip = np.zeros(m)
        if tangential:
            v, stick, its1, outcome1 = solve_tangential(t, v, s, p)
            TA, TB, stick, _ = tractions(v, s, p, False)
            F = expand(om1 * TA, om1 * TB)
            (A, B), (sA, sB) = nodal(v), nodal(s)
            # return mapping: a slipping node's history moves to where its trial traction is mu p
            slipping = (p > 0) & ~stick
            # a node out of contact carries no force and its history follows it, at the end of the
            # increment: a node that comes into contact at the next one sticks from where it
            # stood at that increment's start (its slip is measured over the increment)
            free = p <= 0
            s = expand(np.where(slipping | free, A + TA / k, sA), np.where(slipping | free, B, sB))
            Q = -2 * np.pi * (om * TA).sum()        # Q = -2 pi int T_A r dr
            qx = -(TA + TB)                        # q_x on the x axis: -(T_A + T_B) = -T_r
            slip = 2.0 * (A + B)                   # relative displacement of the surfaces along x
        field = "-"
        P_top = ""
        if position >= 0:
            field = f"field_{position}.xdmf"
            un = full_field(ksp0, K0, V0, zdofs, f, lambda u: u.x.array.__setitem__(z_of, u.x.array[z_of] - d))
            un.name = "u"
            # the reaction on the far face: the internal forces K u at its u_z DOFs (the
            # variational reaction; integrating sigma_zz there misses the clamped corner)
            u_react.x.array[:] = un.x.array
            internal = fem.petsc.assemble_vector(react_form)
            P_top = -2 * np.pi * comm.allreduce(internal.array[top_z].sum(), op=MPI.SUM)
            with dolfinx.io.XDMFFile(comm, field, "w") as xf:
                xf.write_mesh(msh)
                xf.write_function(un)
                if tangential:
                    ut = full_field(ksp1, K1, V1, dofs1, F,
                                    lambda u: u.x.array.__setitem__(A_of, u.x.array[A_of] + t))
                    ut.name = "u1"
                    xf.write_function(ut)
                for name, values in (("pressure", p), ("qx", qx), ("stick", (stick & (p > 0)) * 1.0),
                                     ("slip", slip)):
                    xf.write_function(scalar(name, values))
        out.writerow([step, repr(d), repr(t), repr(P), P_top if P_top == "" else repr(P_top), repr(Q), its0, its1,
                      outcome1 if ok0 else 0, field])
        for i in range(m):
            nodes.writerow([step, repr(rc[i]), repr(om[i]), repr(zs[i] + w[i]), repr(p[i]), repr(qx[i]),
                            int(stick[i] and p[i] > 0), repr(slip[i])])
with open("timing.csv", "w") as ft:
    ft.write(f"phase,seconds\nsetup,{clock_path - clock_start!r}\npath,{time.process_time() - clock_path!r}\n")
print(f"done: {len(steps)} steps, {m} candidates", flush=True)
