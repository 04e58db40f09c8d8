"""The three force analyses of a linkage position by position (vectorised):

* group by group (docs/methods.md §3; Artobolevsky, Popov & Timofeev): from the last attached
  Assur group to the crank, each group's 3 equations per link in its unknown pair
  reactions, the reactions from later groups moved to the right-hand side; then the
  crank with the moment the drive applies to it. A balance link other than the crank
  is handled by superposition (the equations are linear): the group-by-group solution
  for the loads (L) and for a unit balancing couple / force (U) give the crank's
  moments M1(L), M1(U); with no drive moment on the crank, M_b = -M1(L) / M1(U) and
  every reaction is R(L) + M_b R(U);
* the matrix method: all equations of all links in one system A(phi) x = -q(phi),
  scaled to O(1) entries, batched solve;
* Zhukovsky's lever: forces moved to the velocity plan turned by +90 deg (point of
  a force -> the end of rot90(v)), moments of all forces about the pole, couples as
  force pairs at two points of their link; and the virtual-power balance
  M_b omega_b + sum F.v + sum M omega = 0.
"""
from __future__ import annotations

import numpy as np

from ...errors import StageError
from ...messages import Message
from ..loads import AppliedCouple, AppliedForce, Loads
from .equations import (Geometry, balance_coeffs, coeff_array, cross, joint_terms, rot90, scaled_matrix, scaling)

COND_MAX = 1e11          # scaled condition number beyond which a position is singular
CHUNK = 2048             # positions per block of the matrix method


def _group_links(mech, structure) -> list[list[int]]:
    out = []
    for g in structure.groups:
        out.append([l if isinstance(l, int) else mech.index(l) for l in g.links])
    return out


def _safe_solve(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Batched solve; rows whose matrix is singular get NaN and ok = False."""
    N = A.shape[0]
    try:
        x = np.linalg.solve(A, b[..., None])[..., 0]
        ok = np.all(np.isfinite(x), axis=1)
        return x, ok
    except np.linalg.LinAlgError:
        x = np.full(b.shape[:1] + (A.shape[2],), np.nan)
        ok = np.zeros(N, bool)
        for i in range(N):
            try:
                x[i] = np.linalg.solve(A[i], b[i])
                ok[i] = np.all(np.isfinite(x[i]))
            except np.linalg.LinAlgError:
                pass
        return x, ok


def group_by_group(mech, structure, geo: Geometry, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Reactions and the drive's moment, solved group by group.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    structure : StructureResult
        Its Assur groups.
    geo : Geometry
        The positions.
    q : numpy.ndarray
        The loads' sums (N, n+1, 3), N and N*m (:func:`.equations.load_vector`).

    Returns
    -------
    tuple of numpy.ndarray
        The reactions x (N, 2p), N (and N*m for a slider's moment), and the moment on the
        drive link (N,), N*m.  The groups are solved from the last to the crank; their
        matrices depend on the positions only and are inverted once per geometry.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: force analysis group by group (Assur
    groups), from the last group to the driving link; docs/methods.md §3.
    """
    cached = geo.__dict__.get("_group_plan")
    if cached is None or cached[0] is not structure or cached[1] is not mech:
        cached = (structure, mech, _group_plan(mech, structure, geo))
        geo.__dict__["_group_plan"] = cached
    N, p = geo.n_pos, len(mech.joints)
    # the right-hand sides and the reactions held by rows (one row of N values per
    # unknown): every copy and subtraction below runs along the positions (an (N, 3)
    # slice of a position-major array makes numpy loop 3 values at a time); the same
    # numbers, the solve on the same (N, m) array as ever
    xT = np.full((2 * p, N), np.nan)
    M1 = np.full(N, np.nan)
    for links, rows, unknown, known, inv, is_crank in cached[2]:
        bT = np.empty((3 * len(links), N))
        for l, i in rows.items():
            np.negative(q[:, l, :].T, out=bT[3 * i:3 * i + 3])
        # known reactions of the later groups on this group's links
        for k, i, cf in known:
            bT[3 * i:3 * i + 3] -= np.einsum("nij,nj->ni", cf, xT[2 * k:2 * k + 2].T).T
        # inv (N, m, m) times each position's right-hand side: einsum's loop over the
        # positions, ~2.4x numpy's batched matmul of small matrices (the same products,
        # summed in its own order)
        sol = np.einsum("nij,jn->ni", inv, bT)
        for c, k in enumerate(unknown):
            xT[2 * k:2 * k + 2] = sol[:, 2 * c:2 * c + 2].T
        if is_crank:
            M1 = sol[:, -1]
    return xT.T, M1


def _group_plan(mech, structure, geo: Geometry) -> list[tuple]:
    """Per group, from the last to the crank: (links, link -> block row, unknown joints,
    [(known joint, block row, its coefficients)], the inverse of the group's matrix (N, m, m),
    rows of a singular matrix NaN; whether it is the crank)."""
    N = geo.n_pos
    terms = [joint_terms(geo, j, k) for k, j in enumerate(mech.joints)]
    solved: set[int] = set()
    steps = [(links, False) for links in reversed(_group_links(mech, structure))]
    steps.append(([mech.drive], True))
    covered = set(l for links, _ in steps for l in links)
    missing = [lk.name for lk in mech.links if lk.index not in covered]
    if missing:
        raise StageError("kinetostatics", Message("kinetostatics.fail.no_group", links=str(missing)))
    plan = []
    for links, is_crank in steps:
        rows = {l: i for i, l in enumerate(links)}
        unknown = [k for k, j in enumerate(mech.joints)
                   if (j.a in rows or j.b in rows) and j.a not in solved and j.b not in solved]
        ncol = 2 * len(unknown) + (1 if is_crank else 0)
        if ncol != 3 * len(links):
            names = [mech.link(l).name for l in links]
            raise StageError("kinetostatics", Message("kinetostatics.fail.indeterminate", links=str(names),
                                                      equations=3 * len(links), unknowns=ncol))
        A = np.zeros((N, 3 * len(links), ncol))
        for c, k in enumerate(unknown):
            for l, tl in terms[k].items():
                if l in rows:
                    for i, u, v in tl:          # the entries coeff_array(N, tl) holds (others 0)
                        A[:, 3 * rows[l] + i, 2 * c + u] = v
        if is_crank:
            A[:, 3 * rows[mech.drive] + 2, -1] = 1.0
        known = [(k, rows[l], coeff_array(N, tl)) for k, j in enumerate(mech.joints) if k not in unknown
                 for l, tl in terms[k].items() if l in rows and (j.a in solved or j.b in solved)]
        plan.append((links, rows, unknown, known, _safe_inverse(A), is_crank))
        solved.update(links)
    return plan


def _safe_inverse(A: np.ndarray) -> np.ndarray:
    """Batched inverse; a singular matrix's rows are NaN (its position gets NaN reactions)."""
    try:
        return np.linalg.inv(A)
    except np.linalg.LinAlgError:
        out = np.full(A.shape, np.nan)
        for i in range(A.shape[0]):
            try:
                out[i] = np.linalg.inv(A[i])
            except np.linalg.LinAlgError:
                pass
        return out


def unit_balance_q(mech, geo: Geometry, balance: int) -> np.ndarray:
    """The load sums of a unit balancing unknown.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    balance : int
        The balance link.

    Returns
    -------
    numpy.ndarray
        (N, n+1, 3): a unit couple (bar) or unit force along the guide (slider) on the balance
        link.
    """
    q = np.zeros((geo.n_pos, mech.n + 1, 3))
    q[:, balance, :] = balance_coeffs(mech, geo, balance)
    return q


def matrix_method(mech, geo: Geometry, q: np.ndarray, balance: int, *, with_det: bool = True
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """All equilibrium equations solved at once.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    q : numpy.ndarray
        The loads' sums (N, n+1, 3).
    balance : int
        The balance link.
    with_det : bool
        True: the scaled determinant too.

    Returns
    -------
    tuple
        (reactions (N, 2p), N; the balancing unknown (N,), N*m or N; whether the scaled 2-norm
        condition number is below COND_MAX (N,); the scaled determinant (N,) or None).
    """
    n, p = mech.n, len(mech.joints)
    rs, cs = _checked_scaling(mech, geo, balance)
    N, m = geo.n_pos, len(cs)
    xx, well = np.empty((N, m)), np.empty(N, bool)
    det = np.empty(N) if with_det else None
    # in blocks of positions: the matrices and LAPACK's work arrays of a fine grid stay
    # small (each position is solved on its own, so the blocks change no number)
    for sl, As in _scaled_blocks(mech, geo, balance, rs, cs):
        b = -q[sl, 1:, :].reshape(-1, 3 * n) * rs[None, :]
        cert = _certified(As)
        if not cert.all():          # the SVD where the certificate is undecided
            cert[~cert] = _condition(As[~cert]) < COND_MAX
        well[sl] = cert
        if with_det:
            det[sl] = np.linalg.det(As)
        y, ok = _safe_solve(As, b)
        y = y * cs[None, :]
        y[~ok] = np.nan
        xx[sl] = y
    return xx[:, :2 * p], xx[:, 2 * p], well, det


def condition_numbers(mech, geo: Geometry, balance: int) -> np.ndarray:
    """The condition numbers of the matrix method's scaled system.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    balance : int
        The balance link.

    Returns
    -------
    numpy.ndarray
        The 2-norm condition number (N,) (inf where singular).
    """
    rs, cs = _checked_scaling(mech, geo, balance)
    cond = np.empty(geo.n_pos)
    for sl, As in _scaled_blocks(mech, geo, balance, rs, cs):
        cond[sl] = _condition(As)
    return cond


def _checked_scaling(mech, geo: Geometry, balance: int) -> tuple[np.ndarray, np.ndarray]:
    rs, cs = scaling(mech, geo.Lc, balance)
    if len(rs) != len(cs):
        raise StageError("kinetostatics", Message("kinetostatics.fail.not_square", equations=len(rs),
                                                  unknowns=len(cs)))
    return rs, cs


def _scaled_blocks(mech, geo: Geometry, balance: int, rs: np.ndarray, cs: np.ndarray):
    """(positions, the scaled matrices A (k, m, m) there), CHUNK positions at a time."""
    for i0 in range(0, geo.n_pos, CHUNK):
        sl = slice(i0, min(i0 + CHUNK, geo.n_pos))
        yield sl, scaled_matrix(mech, geo.take(sl), balance, rs, cs)


def _condition(As: np.ndarray) -> np.ndarray:
    """sigma_max / sigma_min per matrix (inf where sigma_min is 0)."""
    sv = np.linalg.svd(As, compute_uv=False)
    return np.where(sv[:, -1] > 0, sv[:, 0] / np.maximum(sv[:, -1], 1e-300), np.inf)


def _certified(As: np.ndarray) -> np.ndarray:
    """Per matrix A of the block (k, m, m): True when A provably has a 2-norm condition
    number below 1.5e6, far below COND_MAX (then no SVD is needed to say so); False when
    undecided. The proof: a Cholesky factorisation of G = fl(A^T A) - s I,
    s = 1e-12 fl(trace G) (= ||A||_F^2 to 1e-15), that completes with finite positive
    pivots means (backward error of Cholesky and of the product, each < 1e-14 ||A||_F^2
    for m <= 30, whatever the order of the sums) sigma_min(A)^2 > 0.5e-12 ||A||_F^2 >=
    0.5e-12 sigma_max(A)^2.

    Made across the matrices (each value a (k,) vector along the positions) and only
    where the block's matrices can hold a nonzero: the Gram matrix from each row's
    nonzeros, the right-looking Cholesky over the nonzeros and their fill (an entry
    zero in every matrix stays exactly zero in the dense factorisation: skipping it
    changes nothing)."""
    k, n_rows, m = As.shape
    if m > 30 or k == 0:
        return np.zeros(k, bool)
    with np.errstate(all="ignore"):         # an overflow leaves its matrix undecided
        return _cholesky_certificate(As, k, n_rows, m)


def _cholesky_certificate(As: np.ndarray, k: int, n_rows: int, m: int) -> np.ndarray:
    """See :func:`_certified`."""
    finite = np.isfinite(As).all(axis=(1, 2))
    A = np.where(finite[:, None, None], As, 0.0) if not finite.all() else As
    At = A.transpose(1, 2, 0)                       # (rows, columns, k) view
    nz = np.any(A != 0.0, axis=0)                   # (rows, columns): nonzero somewhere
    H = np.zeros((m, m, k))
    for i in range(n_rows):
        c = np.flatnonzero(nz[i])
        if len(c):
            a = At[i, c]                            # (r, k)
            H[np.ix_(c, c)] += a[:, None, :] * a[None, :, :]
    d = np.arange(m)
    H[d, d] -= 1e-12 * H[d, d].sum(axis=0)
    ok = finite.copy()
    pattern = np.any(H != 0.0, axis=2)
    pattern[d, d] = True
    for j in range(m):
        piv = H[j, j]
        ok &= (piv > 0.0) & (piv < np.inf)
        rows = j + 1 + np.flatnonzero(pattern[j + 1:, j])
        if len(rows) == 0:
            continue
        col = H[rows, j] / np.sqrt(np.where(ok, piv, 1.0))
        ok &= np.isfinite(col).all(axis=0)
        pattern[np.ix_(rows, rows)] = True
        H[np.ix_(rows, rows)] -= col[:, None, :] * col[None, :, :]
    return ok


def _pair_arms(geo: Geometry, link: int) -> tuple[np.ndarray, np.ndarray]:
    """The turned velocities (rot90(vA), rot90(vB)) of the two points of ``link`` a couple
    on it is replaced by on Zhukovsky's lever (:func:`_pair_lever`): the same for every
    couple on the link."""
    l = geo.Lc
    # a material point of the link at distance l from O_i along the current x axis
    u = np.tile([1.0, 0.0], (geo.n_pos, 1))
    pA = geo.origin[link]
    pB = pA + l * u
    return rot90(geo.point_vel(link, pA)), rot90(geo.point_vel(link, pB))


_TURNED_X = np.array([-0.0, 1.0])       # rot90 of the link's x axis (1, 0)


def _pair_lever(geo: Geometry, link: int, M: np.ndarray, arms: dict | None = None) -> np.ndarray:
    """Zhukovsky-lever moment of a couple M on ``link``: replaced by the pair of forces
    -F at O_i and F = (M / l) n at the point O_i + l u (u: any unit vector fixed on the
    link, here the direction O_i -> O_i + l x, rotated with it), n = rot90(u).
    ``arms``: link -> :func:`_pair_arms`, filled as links come (a link's couples share them)."""
    if link == 0:
        return np.zeros(geo.n_pos)
    if arms is None:
        arms = {}
    if link not in arms:
        arms[link] = _pair_arms(geo, link)
    rvA, rvB = arms[link]
    F = (M / geo.Lc)[:, None] * _TURNED_X
    return cross(rvB, F) + cross(rvA, -F)


def point_velocities(geo: Geometry, loads: Loads) -> list[np.ndarray | None]:
    """The velocity of each force's point.

    Parameters
    ----------
    geo : Geometry
        The positions.
    loads : Loads
        The loads.

    Returns
    -------
    list
        (N, 2) in m/s per force (``loads.forces`` order; None on the ground).
    """
    return [geo.point_vel(f.link, f.point) if f.link else None for f in loads.forces]


def lever_moments(mech, geo: Geometry, loads: Loads, vel: list | None = None, arms: dict | None = None
                  ) -> np.ndarray:
    """Zhukovsky's lever: the loads' moments about the pole of the turned velocity plan.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    loads : Loads
        The loads.
    vel : list or None
        :func:`point_velocities` of ``loads`` when made.
    arms : dict or None
        The pairs' lever arms when made.

    Returns
    -------
    numpy.ndarray
        The sum of the moments (N,), in W (the plan drawn at 1 m per m/s): the forces'
        cross(rot90(v), F) = -(F . v) plus the couples' lever terms.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: Zhukovsky's lever; docs/methods.md §3.
    """
    if vel is None:
        vel = point_velocities(geo, loads)
    if arms is None:
        arms = {}
    tot = np.zeros(geo.n_pos)
    for f, v in zip(loads.forces, vel):
        if f.link == 0:
            continue
        tot += cross(rot90(v), f.F)
    for c in loads.couples:
        tot += _pair_lever(geo, c.link, c.M, arms)
    return tot


def balance_lever(mech, geo: Geometry, balance: int, arms: dict | None = None) -> np.ndarray:
    """Zhukovsky's lever moment of a unit balancing unknown.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    balance : int
        The balance link.
    arms : dict or None
        The pairs' lever arms when made.

    Returns
    -------
    numpy.ndarray
        The lever moment (N,) of a unit couple (bar) or unit force along the guide (slider).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: Zhukovsky's lever; docs/methods.md §3.
    """
    lk = mech.link(balance)
    if lk.kind == "slider":
        j = next(k for k, jj in enumerate(mech.joints) if jj.kind == "P" and jj.slider == balance)
        v = geo.point_vel(balance, geo.jpoint[j])
        return cross(rot90(v), geo.jdir[j])
    return _pair_lever(geo, balance, np.ones(geo.n_pos), arms)


def powers(mech, geo: Geometry, loads: Loads, vel: list | None = None) -> tuple[np.ndarray, list[np.ndarray]]:
    """The powers of the loads.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    loads : Loads
        The loads.
    vel : list or None
        :func:`point_velocities` of ``loads`` when made.

    Returns
    -------
    tuple
        (the total power (N,), W; the power of each force and couple, in the order
        loads.forces + loads.couples, W).
    """
    if vel is None:
        vel = point_velocities(geo, loads)
    each = []
    for f, v in zip(loads.forces, vel):
        each.append(np.einsum("ij,ij->i", f.F, v) if f.link else np.zeros(geo.n_pos))
    for c in loads.couples:
        each.append(c.M * geo.omega(c.link))
    tot = np.sum(each, axis=0) if each else np.zeros(geo.n_pos)
    return tot, each


def balance_rate(mech, geo: Geometry, balance: int) -> np.ndarray:
    """The factor of the balancing unknown in the virtual power.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    balance : int
        The balance link.

    Returns
    -------
    numpy.ndarray
        omega_b (bar, rad/s) or the pin's velocity along the guide (slider, m/s), (N,).
    """
    lk = mech.link(balance)
    if lk.kind == "slider":
        j = next(k for k, jj in enumerate(mech.joints) if jj.kind == "P" and jj.slider == balance)
        return np.einsum("ij,ij->i", geo.point_vel(balance, geo.jpoint[j]), geo.jdir[j])
    return geo.omega(balance)


# ------------------------------------------------------------------ friction
def relative_motion(mech, geo: Geometry) -> np.ndarray:
    """The relative motion friction acts against, per pair.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).

    Returns
    -------
    numpy.ndarray
        (N, pairs): a pin's relative angular velocity omega_b - omega_a (rad/s), a slider's
        relative sliding velocity along its guide (m/s); the friction loads change sign where
        it does.
    """
    cached = geo.__dict__.get("_relative_motion")
    if cached is not None and cached[0] is mech:
        return cached[1]
    out = _relative_motion(mech, geo)
    geo.__dict__["_relative_motion"] = (mech, out)
    return out


def _relative_motion(mech, geo: Geometry) -> np.ndarray:
    """See :func:`relative_motion`."""
    out = np.zeros((geo.n_pos, len(mech.joints)))
    for k, j in enumerate(mech.joints):
        if j.kind == "R":
            out[:, k] = geo.omega(j.b) - geo.omega(j.a)
        else:
            s = j.slider
            g = j.a if j.b == s else j.b
            p = geo.jpoint[k]
            out[:, k] = np.einsum("ij,ij->i", geo.point_vel(s, p) - geo.point_vel(g, p), geo.jdir[k])
    return out


ZERO_MOTION = 1e-9     # a relative motion below this (rad/rad; m/rad over the size) is none


def _motion_signs(mech, geo: Geometry) -> tuple[np.ndarray, np.ndarray]:
    """(sign, |.|) of :func:`relative_motion`, each (pairs, N) (a pair's row contiguous):
    made once per geometry (the friction iteration takes them at every step)."""
    cached = geo.__dict__.get("_motion_signs")
    if cached is not None and cached[0] is mech:
        return cached[1]
    rel = np.ascontiguousarray(relative_motion(mech, geo).T)
    sign = np.sign(rel)
    # A relative motion within round-off of zero is none: the instant a pair's motion
    # reverses (the rocker's pairs at an extreme position, which the course's positions
    # include). Its sign there is round-off, and the friction with it +-f r |R| by chance;
    # the friction at that instant is the mean of its two sides, zero (as the kinematics
    # takes the mean of the two sides at a singular position).
    w = np.abs(geo.omega1) * ZERO_MOTION
    for k, j in enumerate(mech.joints):
        still = np.abs(rel[k]) <= (w if j.kind == "R" else w * geo.Lc)
        if still.any():
            sign[k][still] = 0.0
    out = (sign, np.abs(rel))
    geo.__dict__["_motion_signs"] = (mech, out)
    return out


def friction_loads(mech, geo: Geometry, x: np.ndarray, f: float, r_pin: float, f_slide: float | None = None,
                   *, losses: bool = True) -> tuple[list[AppliedForce], list[AppliedCouple], np.ndarray | None]:
    """The friction loads from the reactions.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    x : numpy.ndarray
        The reactions (N, 2p), N.
    f : float
        The pins' friction coefficient.
    r_pin : float
        The pins' radius, m.
    f_slide : float or None
        The sliders' friction coefficient (None: ``f``).
    losses : bool
        True: the friction power lost in each pair too.

    Returns
    -------
    tuple
        (forces, couples, losses): a pin's friction couple f r |R| (N*m) against the relative
        rotation, a slider's friction force f_slide |N| (N) against the relative sliding; the
        power lost in each pair (N, p), W, >= 0 (None without ``losses``).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: friction in the kinematic pairs: the
    friction circle and the friction force; docs/methods.md §3.
    """
    if f_slide is None:
        f_slide = f
    N = geo.n_pos
    forces, couples = [], []
    loss = np.zeros((N, len(mech.joints))) if losses else None
    # a singular position's reactions are not finite: no friction there (nan_to_num would turn
    # an infinite reaction into 1.8e308 and the friction couples into inf)
    xs = x if np.isfinite(x).all() else np.where(np.isfinite(x), x, 0.0)
    sign, size = _motion_signs(mech, geo)
    for k, j in enumerate(mech.joints):
        sg = sign[k]
        if j.kind == "R":
            Rm = np.hypot(xs[:, 2 * k], xs[:, 2 * k + 1])
            Mf = f * r_pin * Rm
            couples.append(AppliedCouple(j.b, f"Mf{j.a}{j.b}", -Mf * sg, "friction"))
            if j.a:
                couples.append(AppliedCouple(j.a, f"Mf{j.b}{j.a}", Mf * sg, "friction"))
            if losses:
                loss[:, k] = Mf * size[k]
        else:
            s = j.slider
            g = j.a if j.b == s else j.b
            p = geo.jpoint[k]
            e = geo.jdir[k]
            Ff = f_slide * np.abs(xs[:, 2 * k])
            F = -(Ff * sg)[:, None] * e
            forces.append(AppliedForce(s, f"Ff{g}{s}", p, F, "friction"))
            if g:
                forces.append(AppliedForce(g, f"Ff{s}{g}", p, -F, "friction"))
            if losses:
                loss[:, k] = Ff * size[k]
    return forces, couples, loss
