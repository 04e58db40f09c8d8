"""Benchmarks of the kinematics core (tmm_cli.linkage.kinematics.solve).

* ``core``: against a hand-written numpy closed form of the same central slider-crank and
  crank-rocker four-bar computing the same outputs (every point's position, first and
  second derivative in the crank angle, every link's angle and its two derivatives:
  the centres of mass S1-S3 and the ground points included), N = 36 ... 36000 positions
  (issue 12 target: <= 3x at N >= 3600), and against pylinkage's numba solver
  (``Linkage.step_fast_with_kinematics``: positions, velocities and accelerations of
  the joints A and B only; less work than tmm's) when pylinkage and numba are
  installed (``pip install .[bench]``; target: tmm faster at N >= 360). The four-bar
  also against ``four_bar_lean``, the same closed form coded for the fewest numpy calls
  in complex numbers (what numpy reaches for one linkage by hand; ``lean/pylinkage``).
  All are timed interleaved (tmm, closed form, pylinkage, tmm, ...), CPU time and wall time of
  a batch of calls, medians and spread of the per-round ratios, and the minor page faults
  per call (memory the C library handed back to the system and took again: at N >= 3600
  a large part of the time of both sides, and it depends on the process's allocation
  history -- see the README).
  ``general``: tmm's general solver (its complex-number fast path off), which answers the
  calls the fast path does not (singular and limit positions, class-III groups).
* ``sixbar``: the six-bar of tasks/forging_sixbar.yaml at 10^5 positions: wall time, CPU
  time and the peak memory traced by tracemalloc (numpy arrays are traced). Targets:
  < 0.2 s, < 200 MB.
* ``digest``: a digest of every output of ``solve`` on the linkage tasks (not timed): the
  same before and after a change that must leave the results bit-identical.

Run: python benchmarks/bench_kinematics.py [core|sixbar|digest] [--repeat 7] [--sizes 12,360,3600]
[--no-trim] [--against DIR]  (DIR: the code before, e.g. `git archive main | tar -x -C DIR`; core
then also times it interleaved, tmm/before)
"""
from __future__ import annotations

import argparse
import math
import resource
import statistics
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tmm_cli.linkage.kinematics import solve  # noqa: E402
from tmm_cli.linkage.mechanism import build_mechanism  # noqa: E402
from tmm_cli.task import load_task  # noqa: E402


# ----------------------------------------------------------------- the two linkages
SLIDER_CRANK = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.045},
              "rod": {"points": ["A", "B"], "length": 0.170},
              "piston": {"slider": "B", "guide": {"through": "O", "angle": 90}}},
    "assembly": {"B": [0, 0.16]}},
    "drive": {"link": "crank", "speed": "3000 rpm"}}
FOUR_BAR = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0], "O3": [0.30, 0]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.08},
              "coupler": {"points": ["A", "B"], "length": 0.30},
              "rocker": {"points": ["O3", "B"], "length": 0.22}},
    "assembly": {"B": [0.33, 0.21]}},
    "drive": {"link": "crank", "speed": "120 rpm"}}


# ----------------------------------------------------------------- closed forms
# Each returns what tmm's KinematicsResult holds: pos, d1, d2 of every point (N, 2 arrays)
# and angle, a1, a2 of every link (N arrays), derivatives in the crank angle phi (rad), and
# the mask of the positions where the velocity equations are singular (None where there
# are none); and, as tmm does, it stops where the linkage does not assemble. The centres
# of mass are the links' midpoints (tmm's default), S1 the crank's pivot.

def slider_crank_closed(phi_deg, r=0.045, l=0.170):
    """Central slider-crank O-A-B, the piston B on the y axis (guide through O at 90 deg):
    y_B = r sin(phi) + sqrt(l^2 - r^2 cos^2(phi)) and its two derivatives in phi."""
    N = len(phi_deg)
    f = np.radians(phi_deg)
    c, s = np.cos(f), np.sin(f)
    R2 = l * l - (r * c) ** 2
    if not (R2 >= 0).all():                                 # tmm: an assembly error
        raise ValueError("the slider-crank does not assemble")
    R = np.sqrt(R2)
    sing = ~(np.abs(R) >= 1e-10 * l)                        # tmm: the rod square to the guide
    y = r * s + R
    g = r * r * c * s / R
    y1 = r * c + g                                           # dy/dphi
    y2 = -r * s + r * r * (c * c - s * s) / R - g * g / R    # d2y/dphi2
    A = np.stack([r * c, r * s], 1)
    A1 = np.stack([-r * s, r * c], 1)
    A2 = -A
    z = np.zeros(N)
    B, B1, B2 = np.stack([z, y], 1), np.stack([z, y1], 1), np.stack([z, y2], 1)
    ux, uy = -r * c / l, (y - r * s) / l                   # unit vector A -> B
    th = np.arctan2(uy, ux)                                # rod angle, in (0, pi)
    th1 = (ux * (y1 - r * c) - uy * (r * s)) / l
    th2 = (ux * (y2 + r * s) - uy * (r * c)) / l
    O = np.zeros((N, 2))
    pos = {"O": O, "A": A, "B": B, "S1": O, "S2": 0.5 * (A + B), "S3": B}
    d1 = {"O": O, "A": A1, "B": B1, "S1": O, "S2": 0.5 * (A1 + B1), "S3": B1}
    d2 = {"O": O, "A": A2, "B": B2, "S1": O, "S2": 0.5 * (A2 + B2), "S3": B2}
    one = np.ones(N)
    angle = {"crank": f, "rod": th, "piston": np.full(N, 0.5 * np.pi)}
    a1 = {"crank": one, "rod": th1, "piston": z}
    a2 = {"crank": z, "rod": th2, "piston": z}
    return pos, d1, d2, angle, a1, a2, (sing if sing.any() else None)


def four_bar_closed(phi_deg, a=0.08, b=0.30, c=0.22, d=0.30):
    """Crank-rocker O-A-B-O3 (O3 = (d, 0)), B to the left of the line A -> O3; the velocity
    and acceleration equations of the loop A + b e(t2) = O3 + c e(t3) by Cramer's rule."""
    N = len(phi_deg)
    f = np.radians(phi_deg)
    cf, sf = np.cos(f), np.sin(f)
    A = np.stack([a * cf, a * sf], 1)
    A1 = np.stack([-a * sf, a * cf], 1)
    A2 = -A
    ACx, ACy = d - A[:, 0], -A[:, 1]
    L = np.hypot(ACx, ACy)
    cg = (b * b + L * L - c * c) / (2 * b * L)
    if not (np.abs(cg) <= 1).all():                         # tmm: an assembly error
        raise ValueError("the four-bar does not assemble")
    gam = np.arccos(cg)
    t2 = np.arctan2(ACy, ACx) + gam                        # coupler angle
    c2, s2 = np.cos(t2), np.sin(t2)
    B = A + b * np.stack([c2, s2], 1)
    t3 = np.arctan2(B[:, 1], B[:, 0] - d)                  # rocker angle
    c3, s3 = np.cos(t3), np.sin(t3)
    # A1 + w2 b (-s2, c2) = w3 c (-s3, c3)  ->  2x2 by Cramer
    det = b * c * (c2 * s3 - s2 * c3)
    sing = ~(np.abs(det) >= 1e-10 * b * c)                 # tmm: the coupler and rocker in line
    rx, ry = -A1[:, 0], -A1[:, 1]
    w2 = (rx * c * c3 + ry * c * s3) / det
    w3 = (b * c2 * rx + b * s2 * ry) / det
    B1 = np.stack([-c * w3 * s3, c * w3 * c3], 1)
    # A2 + e2 b (-s2, c2) - w2^2 b (c2, s2) = e3 c (-s3, c3) - w3^2 c (c3, s3)
    rx = -A2[:, 0] + w2 * w2 * b * c2 - w3 * w3 * c * c3
    ry = -A2[:, 1] + w2 * w2 * b * s2 - w3 * w3 * c * s3
    e2 = (rx * c * c3 + ry * c * s3) / det
    e3 = (b * c2 * rx + b * s2 * ry) / det
    B2 = np.stack([-c * e3 * s3 - c * w3 * w3 * c3, c * e3 * c3 - c * w3 * w3 * s3], 1)
    O, O3 = np.zeros((N, 2)), np.tile([d, 0.0], (N, 1))
    Z = np.zeros((N, 2))
    pos = {"O": O, "O3": O3, "A": A, "B": B, "S1": O, "S2": 0.5 * (A + B), "S3": 0.5 * (O3 + B)}
    d1 = {"O": Z, "O3": Z, "A": A1, "B": B1, "S1": Z, "S2": 0.5 * (A1 + B1), "S3": 0.5 * B1}
    d2 = {"O": Z, "O3": Z, "A": A2, "B": B2, "S1": Z, "S2": 0.5 * (A2 + B2), "S3": 0.5 * B2}
    angle = {"crank": f, "coupler": t2, "rocker": t3}
    a1 = {"crank": np.ones(N), "coupler": w2, "rocker": w3}
    a2 = {"crank": np.zeros(N), "coupler": e2, "rocker": e3}
    return pos, d1, d2, angle, a1, a2, (sing if sing.any() else None)


def four_bar_lean(phi_deg, a=0.08, b=0.30, c=0.22, d=0.30):
    """The four-bar of ``four_bar_closed`` written for the fewest numpy calls: points as
    complex numbers (an (N,) complex array is an (N, 2) float one, x and y interleaved, so
    the outputs are views of it), B by the circle intersection B = A + (A->O3) (k + i h)
    without the angles, the rotation of a vector by a complex product, the velocity and
    acceleration equations by cross products with the unit vectors e2, e3. It shows what
    numpy can reach for one linkage coded by hand (not what a solver of any linkage does)."""
    def xy(z):
        return z.view(np.float64).reshape(-1, 2)
    N = len(phi_deg)
    f = np.radians(phi_deg)
    A = np.empty(N, complex)
    Af = xy(A)
    np.cos(f, Af[:, 0])
    np.sin(f, Af[:, 1])
    A *= a
    A1 = A * 1j
    A2 = -A
    AC = d - A
    L2 = AC.real * AC.real
    L2 += AC.imag * AC.imag
    k = (b * b - c * c) / L2
    k += 1.0
    k *= 0.5
    h = b * b / L2
    h -= k * k
    if not (h >= 0).all():                                  # tmm: an assembly error
        raise ValueError("the four-bar does not assemble")
    np.sqrt(h, h)
    w = np.empty(N, complex)                                # k + i h, then times A->O3
    wf = xy(w)
    wf[:, 0] = k
    wf[:, 1] = h
    w *= AC
    B = A + w
    e2 = w / b                                              # the coupler's unit vector
    e3 = (B - d) / c                                        # the rocker's
    t2, t3 = np.angle(e2), np.angle(e3)
    e3c, e2c = e3.conjugate(), e2.conjugate()
    D = (e3c * e2).imag                                     # sin(t2 - t3)
    sing = ~(np.abs(D) >= 1e-10)                            # tmm: the coupler and rocker in line
    bD, cD = b * D, c * D
    R = A2                                                  # i A1 (= -A): w2 b e2 - w3 c e3 = i A1
    w2 = (e3c * R).imag / bD
    w3 = (e2c * R).imag / cD
    ce3 = c * e3
    B1 = ce3 * (1j * w3)
    R = (A2 - (w2 * w2 * b) * e2 + (w3 * w3) * ce3) * 1j
    e2a = (e3c * R).imag / bD
    e3a = (e2c * R).imag / cD
    B2 = ce3 * (e3a * 1j - w3 * w3)
    Z = np.zeros((N, 2))
    O3 = np.empty((N, 2))
    O3[:, 0] = d
    O3[:, 1] = 0.0
    pos = {"O": Z, "O3": O3, "A": Af, "B": xy(B), "S1": Z, "S2": xy(0.5 * (A + B)), "S3": xy(0.5 * (d + B))}
    d1 = {"O": Z, "O3": Z, "A": xy(A1), "B": xy(B1), "S1": Z, "S2": xy(0.5 * (A1 + B1)), "S3": xy(0.5 * B1)}
    d2 = {"O": Z, "O3": Z, "A": xy(A2), "B": xy(B2), "S1": Z, "S2": xy(0.5 * (A2 + B2)), "S3": xy(0.5 * B2)}
    angle = {"crank": f, "coupler": t2, "rocker": t3}
    a1 = {"crank": np.ones(N), "coupler": w2, "rocker": w3}
    a2 = {"crank": np.zeros(N), "coupler": e2a, "rocker": e3a}
    return pos, d1, d2, angle, a1, a2, (sing if sing.any() else None)


def as_result(form):
    """A closed form's outputs with the names of tmm's KinematicsResult (for check_same)."""
    from types import SimpleNamespace
    pos, d1, d2, angle, a1, a2, sing = form
    return SimpleNamespace(pos=pos, d1=d1, d2=d2, angle=angle, a1=a1, a2=a2, singular=sing)


def check_same(name: str, k, ref) -> None:
    """tmm's result and the closed form hold the same outputs, to round-off."""
    pos, d1, d2, angle, a1, a2, sing = ref
    assert (k.singular is None) == (sing is None), f"{name}: not the same singular positions"
    assert sorted(k.pos) == sorted(pos) and sorted(k.angle) == sorted(angle), f"{name}: not the same outputs"
    for p in pos:
        for what, mine, theirs in (("pos", k.pos, pos), ("d1", k.d1, d1), ("d2", k.d2, d2)):
            err = np.max(np.abs(mine[p] - theirs[p]))
            assert err < 1e-9, f"{name}: {what}[{p}] differs by {err:.3g}"
    for lk in angle:
        dth = np.mod(k.angle[lk] - angle[lk] + np.pi, 2 * np.pi) - np.pi
        for what, err in (("angle", np.max(np.abs(dth))), ("a1", np.max(np.abs(k.a1[lk] - a1[lk]))),
                          ("a2", np.max(np.abs(k.a2[lk] - a2[lk])))):
            assert err < 1e-9, f"{name}: {what}[{lk}] differs by {err:.3g}"


# ----------------------------------------------------------------- pylinkage (optional)
def pylinkage_case(name: str, n: int):
    """A callable running pylinkage's numba solver over n crank positions of one turn
    (positions, velocities, accelerations of every joint), or None without pylinkage."""
    try:
        import numba  # noqa: F401
        from pylinkage import Crank, Ground, Linkage, RRPDyad, RRRDyad
    except ImportError:
        return None
    step = 2 * math.pi / n
    O = Ground(0.0, 0.0, name="O")
    if name == "slider-crank":
        G = Ground(0.0, 1.0, name="G")
        cr = Crank(anchor=O, radius=0.045, angular_velocity=step, name="A")
        B = RRPDyad(cr.output, O, G, distance=0.170, x=0.0, y=0.2, name="B")
        lk = Linkage([O, G, cr, B], name=name)
    else:
        O3 = Ground(0.30, 0.0, name="O3")
        cr = Crank(anchor=O, radius=0.08, angular_velocity=step, name="A")
        B = RRRDyad(cr.output, O3, distance1=0.30, distance2=0.22, x=0.33, y=0.21, name="B")
        lk = Linkage([O, O3, cr, B], name=name)
    lk.set_input_velocity(cr, omega=1.0, alpha=0.0)
    run = lambda: lk.step_fast_with_kinematics(iterations=n)   # noqa: E731
    pos, vel, acc = run()                                       # compiles (numba cache) and checks
    ref = (slider_crank_closed if name == "slider-crank" else four_bar_closed)((np.arange(n) + 1.0) * 360.0 / n)
    pos, vel, acc = run()
    assert np.allclose(pos[:, 3], ref[0]["B"], atol=1e-9), f"pylinkage {name}: not the same assembly"
    assert np.allclose(acc[:, 3], ref[2]["B"], atol=1e-8), f"pylinkage {name}: accelerations differ"
    return run


# ----------------------------------------------------------------- another checkout
_KIN = ("tmm_cli.linkage.kinematics", "tmm_cli.linkage.kinematics.changepoints")


def other_checkout(root: Path):
    """(solve, build_mechanism, load_task, its kinematics modules) of another checkout of
    tmm at ``root`` (a `git archive` copy), imported beside this one's: its tmm_cli modules
    are taken out of sys.modules again, this checkout's put back. Its solve imports its
    change points lazily, by the package's name: call it through ``with_modules`` (the
    kinematics package and its change points swapped in for the call)."""
    mine = {k: v for k, v in sys.modules.items() if k == "tmm_cli" or k.startswith("tmm_cli.")}
    for k in mine:
        del sys.modules[k]
    sys.path.insert(0, str(root))
    try:
        from tmm_cli.linkage.kinematics import changepoints  # noqa: F401 -- its module, for its solve
        from tmm_cli.linkage.kinematics import solve as other_solve
        from tmm_cli.linkage.mechanism import build_mechanism as other_build
        from tmm_cli.task import load_task as other_load
        mods = {k: sys.modules[k] for k in _KIN}
    finally:
        sys.path.remove(str(root))
        for k in [k for k in sys.modules if k == "tmm_cli" or k.startswith("tmm_cli.")]:
            del sys.modules[k]
        sys.modules.update(mine)
    return other_solve, other_build, other_load, mods


def with_modules(fn, mods: dict):
    """fn with the modules ``mods`` in sys.modules while it runs (this checkout's back after)."""
    def call():
        saved = {k: sys.modules.get(k) for k in mods}
        sys.modules.update(mods)
        try:
            return fn()
        finally:
            for k, v in saved.items():
                if v is None:                  # not imported by this checkout yet
                    sys.modules.pop(k, None)
                else:
                    sys.modules[k] = v
    return call


# ----------------------------------------------------------------- timing
def _batch(fn, calls: int) -> tuple[float, float, float]:
    """(wall, cpu, minor page faults) per call of ``calls`` calls."""
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    t0, c0 = time.perf_counter(), time.process_time()
    for _ in range(calls):
        fn()
    t1, c1 = time.perf_counter(), time.process_time()
    f1 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    return (t1 - t0) / calls, (c1 - c0) / calls, (f1 - f0) / calls


def general(mech, phi):
    """tmm's general solver alone (the complex-number fast path off): what answers a call
    with a singular or limit position, a class-III group, or a dyad the fast path does not
    cover."""
    from tmm_cli.linkage.kinematics import solver as sv
    sv.FAST = False
    try:
        return solve(mech, phi, 1.0)
    finally:
        sv.FAST = True


def core(repeat: int = 7, sizes=(12, 36, 360, 3600, 36000), against: Path | None = None) -> None:
    cases = [("slider-crank", build_mechanism(load_task(SLIDER_CRANK)), slider_crank_closed, SLIDER_CRANK),
             ("four-bar", build_mechanism(load_task(FOUR_BAR)), four_bar_closed, FOUR_BAR)]
    have_pyl = pylinkage_case("four-bar", 36) is not None
    before_side = other_checkout(against) if against is not None else None
    print(f"kinematics core against the numpy closed form{' and pylinkage (numba)' if have_pyl else ''} "
          f"of the same linkage{f', and the tmm of {against} (before)' if before_side else ''}, {repeat} interleaved "
          f"rounds; per call, median [min-max] of the rounds"
          + ("" if have_pyl else "; pylinkage/numba not installed (pip install .[bench])"))
    for name, mech, closed, src in cases:
        phi = np.linspace(0.0, 360.0, 3600, endpoint=False)
        check_same(name, solve(mech, phi, 1.0), closed(phi))
        check_same(name + " (general)", general(mech, phi), closed(phi))
        before = None
        if before_side is not None:
            o_solve, o_build, o_load, mods = before_side
            o_mech = with_modules(lambda: o_build(o_load(src)), mods)()
            before = lambda: with_modules(lambda: o_solve(o_mech, phi, 1.0), mods)()   # noqa: E731
            check_same(name + " (before)", before(), closed(phi))
        for n in sizes:
            phi = np.linspace(0.0, 360.0, n, endpoint=False)
            calls = max(3, 40000 // n)
            fns = {"tmm": lambda: solve(mech, phi, 1.0), "closed": lambda: closed(phi),
                   "general": lambda: general(mech, phi)}
            if name == "four-bar":
                check_same("four-bar lean", as_result(four_bar_lean(phi)), closed(phi))
                fns["lean"] = lambda: four_bar_lean(phi)
            if before is not None:
                fns["before"] = before
            pyl = pylinkage_case(name, n)
            if pyl is not None:
                fns["pylinkage"] = pyl
            res = {k: [] for k in fns}
            for _ in range(repeat):
                for k, fn in fns.items():
                    res[k].append(_batch(fn, calls))
            cpu = {k: [c for _, c, _ in v] for k, v in res.items()}
            wall = {k: [w for w, _, _ in v] for k, v in res.items()}
            flt = {k: statistics.median(f for _, _, f in v) for k, v in res.items()}
            line = f"  {name:12s} N={n:6d}  cpu ms: " + ", ".join(
                f"{k} {statistics.median(v) * 1e3:.3f}" for k, v in cpu.items())
            for other in [k for k in fns if k != "tmm"]:
                rc = [a / b for a, b in zip(cpu["tmm"], cpu[other])]
                rw = [a / b for a, b in zip(wall["tmm"], wall[other])]
                tgt = ""
                if other == "closed" and n >= 3600:
                    tgt = " (<= 3 " + ("ok" if statistics.median(rc) <= 3 else "OVER") + ")"
                if other == "pylinkage" and n >= 360:
                    tgt = " (< 1 " + ("ok" if statistics.median(rc) < 1 else "OVER") + ")"
                line += (f" | tmm/{other} cpu {statistics.median(rc):.2f} [{min(rc):.2f}-{max(rc):.2f}]"
                         f" wall {statistics.median(rw):.2f}{tgt}")
            if "lean" in fns and "pylinkage" in fns:
                rl = [a / b for a, b in zip(cpu["lean"], cpu["pylinkage"])]
                line += f" | lean/pylinkage cpu {statistics.median(rl):.2f} [{min(rl):.2f}-{max(rl):.2f}]"
            if "before" in fns:
                rb = [a / b for a, b in zip(cpu["before"], cpu["closed"])]
                line += f" | before/closed cpu {statistics.median(rb):.2f} [{min(rb):.2f}-{max(rb):.2f}]"
            line += " | page faults/call " + ", ".join(f"{k} {v:.0f}" for k, v in flt.items())
            print(line, flush=True)


def sixbar(n: int = 100_000, repeat: int = 5) -> None:
    m = build_mechanism(load_task(ROOT / "tasks" / "forging_sixbar.yaml"))
    phi = np.linspace(0.0, 360.0, n, endpoint=False)
    solve(m, phi[:10], 5.236)                  # closures chosen once (cached per mechanism)
    walls, cpus = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        solve(m, phi, 5.236)
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    tracemalloc.start()
    solve(m, phi, 5.236)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    print(f"kinematics six-bar, {n} positions: wall best {min(walls):.3f} s (median {np.median(walls):.3f} s), "
          f"cpu best {min(cpus):.3f} s, peak traced memory {peak / 2**20:.1f} MB")


def digest() -> None:
    """A digest of every output of ``solve`` (positions, derivatives, angles, warnings, the
    singular and near-change-point masks) for each linkage task of tasks/ and the two
    linkages above, on six sets of angles (sorted, random unsorted, three, one, and sorted and
    unsorted sets of thousands, where the kinematics holds less memory): run it
    before and after a change of the kinematics to see that no bit of its results moved."""
    import glob
    import hashlib
    rng = np.random.default_rng(7)
    grids = [np.arange(720) * 0.5, rng.uniform(0.0, 360.0, 500), np.array([0.0, 180.0, 359.999]), np.array([90.0]),
             np.arange(3600) * 0.1, rng.uniform(0.0, 360.0, 2000)]      # the last two: many positions
    srcs = [(Path(f).name, f) for f in sorted(glob.glob(str(ROOT / "tasks" / "*.yaml")))]
    for name, src in srcs + [("slider-crank", SLIDER_CRANK), ("four-bar", FOUR_BAR)]:
        task = load_task(src)
        if task.synthesis is not None:       # the mechanism it generates
            from tmm_cli.linkage.synthesis import generate
            task, _ = generate(task)
        if getattr(task, "mechanism", None) is None:
            continue
        mech = build_mechanism(task)
        h = hashlib.sha256()
        for g in grids:
            try:
                k = solve(mech, g, 2.0, 0.5)
            except Exception as exc:  # noqa: BLE001 -- the error is part of the digest
                h.update(repr(exc).encode())
                continue
            for d in (k.pos, k.d1, k.d2, k.angle, k.a1, k.a2, k.undefined):
                for key in sorted(d):
                    h.update(key.encode())
                    h.update(np.ascontiguousarray(d[key]).tobytes())
            h.update(repr(k.warnings).encode())
            for mask in (k.singular, k.near):
                h.update(b"-" if mask is None else mask.tobytes())
        print(f"{name:36s} {h.hexdigest()[:24]}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("what", nargs="*", default=["sixbar", "core"], choices=["sixbar", "core", "digest"])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--sizes", default="12,36,360,3600,36000", help="core: numbers of positions (comma-separated)")
    ap.add_argument("--against", type=Path, default=None,
                    help="core: also the kinematics of another checkout of tmm (a `git archive` copy), "
                         "interleaved (tmm/before ratios)")
    ap.add_argument("--no-trim", action="store_true",
                    help="glibc: keep freed memory in the process (mallopt M_TRIM_THRESHOLD, M_MMAP_THRESHOLD), "
                         "for every side alike: the timings without the page faults")
    a = ap.parse_args()
    if a.no_trim:
        import ctypes
        libc = ctypes.CDLL("libc.so.6")
        libc.mallopt(-1, 256 << 20)            # M_TRIM_THRESHOLD
        libc.mallopt(-3, 32 << 20)             # M_MMAP_THRESHOLD
    if "digest" in a.what:
        digest()
    if "sixbar" in a.what:
        sixbar()
    if "core" in a.what:
        core(max(5, a.repeat), tuple(int(n) for n in a.sizes.split(",")), a.against)


if __name__ == "__main__":
    main()
