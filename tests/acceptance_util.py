"""Independent reference solver for the acceptance tests of the linkage stages.

Written from SPEC.md / METHODS.md only, without reading tmm_cli: it shares no code
and no algorithm with the tool.

* Positions: every moving pair point is an unknown (x, y); each bar gives one
  distance equation, each slider one "pin on the guide line" equation; extra points
  of a bar are derived from its two points.  The whole system is solved by Newton's
  method (numerical Jacobian), marching from the user's assembly guess at crank angle
  0 in 4-degree steps (so the closure is followed continuously).
* Velocities / accelerations: 9-point (8th order) central differences of the
  positions in the crank angle (h = 0.01 rad), times dphi/dt = +-omega1.
* Forces: one global Newton-Euler system (3 equations per moving link, all pair
  reactions + the balancing unknown), solved by least squares; the balancing moment is
  also cross-checked by the virtual power balance.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

G = 9.81
D1 = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
D2 = np.array([-1 / 560, 8 / 315, -1 / 5, 8 / 5, -205 / 72, 8 / 5, -1 / 5, 8 / 315, -1 / 560])
OFFS = np.arange(-4, 5)
H = 0.01  # rad


def rpm(n):
    return n * math.pi / 30.0


def wrap360(a):
    a = math.fmod(a, 360.0)
    if a < 0:
        a += 360.0
    if a >= 360.0:  # fmod(-1e-17) + 360
        a -= 360.0
    return a


def angdiff(a, b):
    """a - b in degrees, wrapped to (-180, 180]."""
    d = math.fmod(a - b, 360.0)
    if d > 180:
        d -= 360
    if d <= -180:
        d += 360
    return d


@dataclass
class Linkage:
    """A linkage described like a tmm task (plain dict), solved independently."""

    task: dict
    ground: dict = field(init=False)
    links: dict = field(init=False)
    names: list = field(init=False)

    def __post_init__(self):
        mech = self.task["mechanism"]
        self.ground = {k: np.array(v, float) for k, v in mech["ground"].items()}
        self.links = mech["links"]
        self.names = list(self.links)
        drive = self.task["drive"]
        self.crank = drive["link"]
        sp = drive["speed"]
        self.omega = rpm(float(sp.split()[0])) if isinstance(sp, str) else float(sp)
        self.sign = 1.0 if drive.get("direction", "ccw") == "ccw" else -1.0
        cl = self.links[self.crank]
        p, q = cl["points"]
        assert p in self.ground
        self.O, self.A, self.r = p, q, float(cl["length"])
        # derived (extra) points and unknown points
        self.derived = {}
        for name, l in self.links.items():
            for pt, uv in l.get("extra", {}).items():
                self.derived[pt] = (name, np.array(uv, float))
        allpts = []
        for name, l in self.links.items():
            pts = list(l["points"]) if "points" in l else [l["slider"]]
            for pt in pts:
                if pt not in allpts:
                    allpts.append(pt)
        self.unknown = [
            p for p in allpts if p not in self.ground and p != self.A and p not in self.derived
        ]
        self._cache = {}
        # the geometry in plain floats (_points_f): the ground points, the derived points in an
        # order where each one's two points come first (found in up to three passes)
        self._ground_f = {k: (float(v[0]), float(v[1])) for k, v in self.ground.items()}
        known = set(self.ground) | {self.A} | set(self.unknown)
        self._derived_order = []
        for _ in range(3):
            for pt, (ln, uv) in self.derived.items():
                a, b = self.links[ln]["points"]
                if pt not in known and a in known and b in known:
                    self._derived_order.append((pt, a, b, float(uv[0]), float(uv[1])))
                    known.add(pt)
        hints = self.task["mechanism"]["assembly"]
        x0 = np.concatenate([np.array(hints[p], float) for p in self.unknown])
        self._grid = {}  # phi (deg, int multiple of 4) -> solution
        x = self._newton(x0, 0.0)
        self._grid[0] = x
        for k in range(1, 91):
            x = self._newton(x, math.radians(4 * k))
            self._grid[k] = x

    # --- geometry -----------------------------------------------------------
    def _points(self, x, phi):
        """Every point {name: array [x, y]} at crank angle phi (rad) for the unknowns x
        (:meth:`_points_f`'s, as arrays)."""
        return {k: np.array(v) for k, v in self._points_f(x, phi).items()}

    def guide_line(self, P, name):
        """(point on line, unit direction) of the guide of slider `name`, as arrays."""
        T, u = self._guide_f(P, name)
        return np.array(T, float), np.array(u, float)

    def _points_f(self, x, phi):
        """Every point {name: (x, y)} at crank angle phi (rad) for the unknowns x, in plain floats
        (Newton's residuals call it thousands of times a position: numpy's two-element arrays
        cost more than their arithmetic). A derived (extra) point from its link's two points."""
        P = dict(self._ground_f)
        ox, oy = P[self.O]
        P[self.A] = (ox + self.r * math.cos(phi), oy + self.r * math.sin(phi))
        for i, p in enumerate(self.unknown):
            P[p] = (float(x[2 * i]), float(x[2 * i + 1]))
        for pt, a, b, u0, u1 in self._derived_order:
            (ax, ay), (bx, by) = P[a], P[b]
            n = math.hypot(bx - ax, by - ay)
            ux, uy = (bx - ax) / n, (by - ay) / n
            P[pt] = (ax + u0 * ux - u1 * uy, ay + u0 * uy + u1 * ux)
        return P

    def _guide_f(self, P, name):
        """(point on line, unit direction) of the guide of slider `name` as float pairs, on the
        points ``P`` (float pairs or arrays)."""
        g = self.links[name]["guide"]
        if "link" in g:
            a, b = self.links[g["link"]]["points"]
            (ax, ay), (bx, by) = P[a], P[b]
            n = math.hypot(bx - ax, by - ay)
            vx, vy = (bx - ax) / n, (by - ay) / n
            ang = math.radians(g.get("angle", 0.0))
            c, s = math.cos(ang), math.sin(ang)
            ux, uy = c * vx - s * vy, s * vx + c * vy
            off = g.get("offset", 0.0)
            return (ax - off * uy, ay + off * ux), (ux, uy)
        t = g["through"]
        T = self._ground_f[t] if isinstance(t, str) else (float(t[0]), float(t[1]))
        ang = math.radians(g["angle"])
        return T, (math.cos(ang), math.sin(ang))

    def _resid(self, x, phi):
        P = self._points_f(x, phi)
        res = []
        for name, l in self.links.items():
            if name == self.crank:
                continue
            if "points" in l:
                a, b = l["points"]
                res.append(math.hypot(P[b][0] - P[a][0], P[b][1] - P[a][1]) - l["length"])
            else:
                T, u = self._guide_f(P, name)
                sx, sy = P[l["slider"]]
                res.append(u[0] * (sy - T[1]) - u[1] * (sx - T[0]))
        return np.array(res)

    def _newton(self, x, phi):
        x = np.array(x, float)
        for it in range(60):
            f = self._resid(x, phi)
            if it < 2:  # then the chord method (converges fast enough from here)
                J = np.empty((len(f), len(x)))
                for k in range(len(x)):
                    e = np.zeros_like(x)
                    e[k] = 1e-7
                    J[:, k] = (self._resid(x + e, phi) - self._resid(x - e, phi)) / 2e-7
            dx = np.linalg.solve(J, -f)
            x = x + dx
            if np.max(np.abs(dx)) < 1e-15 and it > 1:
                break
        assert np.max(np.abs(self._resid(x, phi))) < 1e-12, "does not assemble"
        return x

    def solve(self, phi_deg):
        phi_deg = float(phi_deg) % 360.0
        k = int(round(phi_deg / 4.0)) % 90
        return self._newton(self._grid[k], math.radians(phi_deg))

    def state(self, phi_deg):
        """Points and link angles (deg, unwrapped near the centre) at a crank angle."""
        x = self.solve(phi_deg)
        return self._state_x(x, math.radians(phi_deg))

    def _state_x(self, x, phi):
        P = self._points(x, phi)
        ang = {}
        for name, l in self.links.items():
            if "points" in l:
                a, b = l["points"]
                d = P[b] - P[a]
                ang[name] = math.degrees(math.atan2(d[1], d[0]))
            else:
                _, u = self.guide_line(P, name)
                ang[name] = math.degrees(math.atan2(u[1], u[0]))
        for i, name in enumerate(self.names, 1):
            P[f"S{i}"] = self.com(P, name)
        return P, ang

    def com(self, P, name):
        l = self.links[name]
        c = l.get("com")
        if "points" not in l:
            return P[c] if isinstance(c, str) else P[l["slider"]]
        a, b = l["points"]
        if c is None:
            return P[a] if name == self.crank else 0.5 * (P[a] + P[b])
        if isinstance(c, str):
            return P[c]
        d = P[b] - P[a]
        u = d / np.hypot(*d)
        return P[a] + c[0] * u + c[1] * np.array([-u[1], u[0]])

    def kin(self, phi_deg):
        """Positions, velocities, accelerations of all points and links at phi (deg).

        Returns (pts, links): pts[name] = (x, y, vx, vy, ax, ay);
        links[name] = (angle in [0,360), omega, epsilon).
        """
        phi_deg = float(phi_deg) % 360.0
        key = round(phi_deg, 12)
        if key in self._cache:
            return self._cache[key]
        x0 = self.solve(phi_deg)
        samples = []
        for o in OFFS:
            ph = math.radians(phi_deg) + o * H
            x = self._newton(x0, ph)
            samples.append(self._state_x(x, ph))
        Pc, Ac = samples[4]
        w = self.sign * self.omega  # dphi/dt
        pts = {}
        for p in Pc:
            arr = np.array([s[0][p] for s in samples])  # 9 x 2
            d1 = D1 @ arr / H
            d2 = D2 @ arr / H**2
            pts[p] = (Pc[p][0], Pc[p][1], w * d1[0], w * d1[1], w * w * d2[0], w * w * d2[1])
        links = {}
        for n in Ac:
            arr = np.array([Ac[n] + angdiff(s[1][n], Ac[n]) for s in samples])
            arr = np.radians(arr)
            links[n] = (wrap360(Ac[n]), w * (D1 @ arr) / H, w * w * (D2 @ arr) / H**2)
        self._cache[key] = (pts, links)
        return pts, links

    def _coord_x(self, name, x, phi_deg):
        P, ang = self._state_x(x, math.radians(phi_deg))
        l = self.links[name]
        if "points" in l:
            return math.radians(ang[name])
        T, u = self.guide_line(P, name)
        return float((P[l["slider"]] - T) @ u)

    def coord(self, name, phi_deg):
        """Output coordinate: slider displacement along its (fixed) guide, or link angle."""
        return self._coord_x(name, self.solve(phi_deg), phi_deg)

    def coord_rate(self, name, phi_deg):
        """d(coord)/d(phi) by the 8th-order stencil."""
        x0 = self.solve(phi_deg)
        vals = []
        for o in OFFS:
            p = phi_deg + math.degrees(o * H)
            vals.append(self._coord_x(name, self._newton(x0, math.radians(p)), p))
        vals = np.array(vals)
        if "points" in self.links[name]:
            vals = vals[4] + np.array([math.atan2(math.sin(v - vals[4]), math.cos(v - vals[4])) for v in vals])
        return float(D1 @ vals / H)

    # --- forces --------------------------------------------------------------
    def pairs(self):
        """Revolute pairs (i, j, point) and prismatic pairs (i, j, slider name), i < j."""
        idx = {n: i for i, n in enumerate(self.names, 1)}
        owners = {}
        for n, l in self.links.items():
            pts = list(l["points"]) + list(l.get("extra", {})) if "points" in l else [l["slider"]]
            for p in pts:
                owners.setdefault(p, []).append(idx[n])
        rev = []
        for p, o in owners.items():
            if p in self.ground:
                o = [0] + o
            if len(o) == 2:
                rev.append((min(o), max(o), p))
            else:
                assert len(o) == 1, f"compound hinge {p} not supported"
        pri = []
        for n, l in self.links.items():
            if "guide" in l:
                g = l["guide"]
                gi = idx[g["link"]] if "link" in g else 0
                pri.append((min(gi, idx[n]), max(gi, idx[n]), n))
        return rev, pri

    def forces(self, phi_deg, balance=None, inertia=True, gravity=False, ext=None):
        """Newton-Euler solution at one crank angle.

        ext(phi_deg, pts, links) -> list of (link name, point name or (xy, vxy), force xy,
        couple).
        Returns dict with 'Mb' (or 'Pb'), reactions {'Rij': (x, y)} and the virtual
        power value of the balancing unknown.
        """
        balance = balance or self.crank
        pts, lk = self.kin(phi_deg)
        idx = {n: i for i, n in enumerate(self.names, 1)}
        P = {p: np.array(v[:2]) for p, v in pts.items()}
        loads = []  # (link, point, F, M)
        vel = {p: np.array(v[2:4]) for p, v in pts.items()}
        for i, n in enumerate(self.names, 1):
            l = self.links[n]
            m = float(l.get("mass", 0.0))
            J = float(l.get("J", 0.0))
            S = f"S{i}"
            if gravity and m:
                loads.append((n, P[S], np.array([0.0, -m * G]), 0.0, vel[S]))
            if inertia:
                a = np.array(pts[S][4:6])
                loads.append((n, P[S], -m * a, -J * lk[n][2], vel[S]))
        if ext:
            for (n, p, F, M) in ext(phi_deg, pts, lk):
                if isinstance(p, str):
                    loads.append((n, P[p], np.array(F, float), M, vel[p]))
                else:  # (position, velocity) of the point of application
                    loads.append((n, np.array(p[0], float), np.array(F, float), M, np.array(p[1], float)))
        rev, pri = self.pairs()
        nl = len(self.names)
        cols = []
        labels = []
        for (i, j, p) in rev:
            for comp in range(2):
                c = np.zeros(3 * nl)
                F = np.zeros(2)
                F[comp] = 1.0
                mom = P[p][0] * F[1] - P[p][1] * F[0]
                for (k, s) in ((j, 1.0), (i, -1.0)):
                    if k:
                        c[3 * (k - 1) : 3 * k] += s * np.array([F[0], F[1], mom])
                cols.append(c)
            labels.append(("R", i, j, p))
        Pfull = {p: P[p] for p in P}
        for (i, j, s) in pri:
            T, u = self.guide_line(Pfull, s)
            nrm = np.array([-u[1], u[0]])
            pin = P[self.links[s]["slider"]]
            # normal force N*nrm applied at the pin on j, plus a couple C
            c = np.zeros(3 * nl)
            mom = pin[0] * nrm[1] - pin[1] * nrm[0]
            for (k, sg) in ((j, 1.0), (i, -1.0)):
                if k:
                    c[3 * (k - 1) : 3 * k] += sg * np.array([nrm[0], nrm[1], mom])
            cols.append(c)
            c = np.zeros(3 * nl)
            for (k, sg) in ((j, 1.0), (i, -1.0)):
                if k:
                    c[3 * (k - 1) + 2] += sg
            cols.append(c)
            labels.append(("P", i, j, nrm))
        b = idx[balance]
        c = np.zeros(3 * nl)
        bl = self.links[balance]
        if "points" in bl:
            c[3 * (b - 1) + 2] = 1.0
            bal_rate = lk[balance][1]
        else:
            T, u = self.guide_line(Pfull, balance)
            pin = P[bl["slider"]]
            c[3 * (b - 1) : 3 * b] = [u[0], u[1], pin[0] * u[1] - pin[1] * u[0]]
            bal_rate = float(vel[bl["slider"]] @ u)
        cols.append(c)
        A = np.array(cols).T
        rhs = np.zeros(3 * nl)
        power = 0.0
        for (n, xy, F, M, v) in loads:
            k = idx[n]
            rhs[3 * (k - 1) : 3 * k] -= np.array([F[0], F[1], xy[0] * F[1] - xy[1] * F[0] + M])
            power += float(F @ v) + M * lk[n][1]
        cond = np.linalg.cond(A)
        sol = np.linalg.solve(A, rhs)
        out = {"bal": sol[-1], "cond": cond, "reactions": {}, "power_bal": -power / bal_rate if bal_rate else None}
        col = 0
        for lab in labels:
            if lab[0] == "R":
                out["reactions"][f"R{lab[1]}{lab[2]}"] = (sol[col], sol[col + 1])
            else:
                nrm = lab[3]
                out["reactions"][f"R{lab[1]}{lab[2]}"] = (sol[col] * nrm[0], sol[col] * nrm[1])
            col += 2
        return out


def rate_roots(L, name, step=6.0):
    """Crank angles in [0, 360) where d(coord of `name`)/d(phi) = 0 (brentq, 1e-12 deg)."""
    from scipy.optimize import brentq

    grid = np.arange(0.0, 360.0 + step / 2, step)
    vals = [L.coord_rate(name, p) for p in grid]
    roots = []
    for i in range(len(grid) - 1):
        if vals[i] == 0.0:
            roots.append(grid[i])
        elif vals[i] * vals[i + 1] < 0:
            roots.append(brentq(lambda p: L.coord_rate(name, p), grid[i], grid[i + 1], xtol=1e-12))
    return sorted({round(wrap360(r), 9) for r in roots})
