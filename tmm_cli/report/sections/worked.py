"""Report section 'worked': the working of one position written out step by step, as a
student's explanatory note does (docs/methods.md §3.4).

For the position ``positions.detail_position`` of the results (the task's
``report.detail_position``, default the first working-stroke position after 0: chosen by
the pipeline, ``tmm_cli.pipeline.default_detail``):

* velocities: the crank pin v_A = omega_1 l_OA and the scale mu_v = v_A / pa; for each
  Assur group (in the order of attachment) the vector equations of its inner point
  (v_B = v_A + v_BA, v_BA perpendicular to AB; v_D parallel to the guide), the
  segments of the plan and the values (v = segment * mu_v), omega = v_rel / l, and
  the other points of its links by similarity;
* accelerations: the same with the normal (omega^2 l, along the link), tangential
  (perpendicular, eps = a^t / l) and, on a slotted lever, Coriolis (2 omega v_rel) and
  relative components;
* kinetostatics: for each group from the last attached, the loads, the moment
  equation of each link about the group's inner pair (sum M_B = 0) giving the
  tangential component of the outer reaction, the force polygon giving the normal
  components, the inner reaction; then the input link (sum M_O = 0 -> M_b);
* Zhukovsky's lever: the moment equation about the pole with each arm (mm on the
  plan turned by 90 deg), P_b and M_b.

Every number is either a value of results.json at that position (the masses and
moments of inertia are its ``structure.links``), or computed here from those by the formula
written next to it; each carries ``data-k`` naming what it is, so that a test can
recompute it (tests/test_worked.py).  Formulas are MathML in report.html and the
same formulas as HTML with sub/superscripts in the PDF (report.pdf is translated from
the print copy): each formula is written twice, ``.mml`` shown on screen, ``.mfb`` in print.

Groups handled step by step: two links with a revolute inner pair whose outer pairs
are revolute or a prismatic pair on a fixed guide (RRR, RRP) -- kinematics and
kinetostatics; the slotted lever RPR (a block on the guide of a hinged link: the
coincident point A3, v_A3 = v_A + v_A3A, the Coriolis a^k = 2 omega v_A3A and the
relative a^r) -- kinematics.  Other groups (and the kinetostatics of RPR) are given with
their results (a note says so).
"""
from __future__ import annotations


import numpy as np
from markupsafe import Markup, escape

from ... import locales
from ...numfmt import num
from ...plans import SUB, geometry as plan_geometry, plan_label
from .kinematics import drawn_scales
from .structure import group_kind

I18N = locales.table("worked", "words")

UNITS = locales.table("worked", "units")


# ====================================================================== formulas
# A formula is a tree of tuples, rendered twice: MathML (screen) and HTML (print).
def mi(x):                      # an italic symbol
    return ("mi", str(x))


def mt(x):                      # upright text
    return ("mt", str(x))


def mo(x):                      # an operator
    return ("mo", str(x))


def unit(x):                    # a unit after a number
    return ("unit", str(x))


def words(x):                   # words inside a formula line
    return ("text", str(x))


def sb(base, s):                # subscript (point / link names: upright)
    return ("sub", _node(base), mt(s))


def sp(base, s):
    if s == "2":                # a square: the exponent is a number of the formula
        return ("sup", _node(base), ("mn", "2", "const:2"))
    return ("sup", _node(base), mt(s))


def sbp(base, s, p):
    return ("subsup", _node(base), mt(s), mt(p))


def vec(base):                  # a vector: the symbol with a bar over it
    return ("vec", _node(base))


def vq(sym, *pts, sup=None):
    """A vector quantity: the bar over the symbol only (v̄ with subscript BA)."""
    s = "".join(pts)
    return sbp(vec(mi(sym)), s, sup) if sup else sb(vec(mi(sym)), s)


def brk():                      # a place where a long line may wrap
    return ("brk",)


def frac(a, b):
    return ("frac", _node(a), _node(b))


def row(*items):
    return ("row", [_node(i) for i in items])


def _node(x):
    return mi(x) if isinstance(x, str) else x


def mathml(n) -> str:
    k = n[0]
    if k == "mi":
        return f"<mi>{escape(n[1])}</mi>"
    if k == "mt":
        return f'<mi mathvariant="normal">{escape(n[1])}</mi>' if n[1] else "<mrow></mrow>"
    if k == "mo":
        st = ' stretchy="false"' if n[1] in "()" else ""
        return f"<mo{st}>{escape(n[1])}</mo>"
    if k == "unit":
        return f'<mspace width="0.25em"></mspace><mtext class="unit">{escape(n[1])}</mtext>'
    if k == "text":
        return f'<mtext>\u00a0{escape(n[1])}</mtext>'

    if k == "mn":
        return f'<mn data-k="{escape(n[2])}">{escape(n[1])}</mn>'
    if k == "sub":
        return f"<msub>{mathml(n[1])}{mathml(n[2])}</msub>"
    if k == "sup":
        return f"<msup>{mathml(n[1])}{mathml(n[2])}</msup>"
    if k == "subsup":
        return f"<msubsup>{mathml(n[1])}{mathml(n[2])}{mathml(n[3])}</msubsup>"
    if k == "vec":
        return f'<mover accent="true">{mathml(n[1])}<mo>¯</mo></mover>'
    if k == "frac":
        return f"<mfrac>{mathml(n[1])}{mathml(n[2])}</mfrac>"
    if k == "row":
        return "<mrow>" + "".join(mathml(c) for c in n[1]) + "</mrow>"
    if k == "sqrt":
        return f"<msqrt>{mathml(n[1])}</msqrt>"
    raise ValueError(k)


def html(n) -> str:
    k = n[0]
    if k == "mi":
        return f"<i>{escape(n[1])}</i>"
    if k == "mt":
        return str(escape(n[1]))
    if k == "mo":
        return f'<span class="mo">{escape(n[1])}</span>'
    if k == "unit":
        return f'\u00a0<span class="unit">{escape(n[1])}</span>'
    if k == "text":
        return f"\u00a0{escape(n[1])}"
    if k == "mn":
        return f'<span class="mn" data-k="{escape(n[2])}">{escape(n[1])}</span>'
    if k == "sub":
        return f"{html(n[1])}<sub>{html(n[2])}</sub>"
    if k == "sup":
        return f"{html(n[1])}<sup>{html(n[2])}</sup>"
    if k == "subsup":
        return (f'{html(n[1])}<span class="ss"><sup>{html(n[3])}</sup>'
                f"<sub>{html(n[2])}</sub></span>")
    if k == "vec":
        return f'<span class="vec">{html(n[1])}</span>'
    if k == "frac":
        return f'<span class="frac"><span class="num">{html(n[1])}</span><span class="den">{html(n[2])}</span></span>'
    if k == "row":
        return "".join(html(c) for c in n[1])
    if k == "sqrt":
        return f'√<span class="rad">{html(n[1])}</span>'
    raise ValueError(k)


def formula(*items) -> Markup:
    """One line of formulas: MathML for the screen, the same as HTML for print; split
    at each ';' into pieces that wrap as words do (a MathML formula does not break)."""
    pieces, cur = [], []
    for it in items:
        if it == mo(";") or it == brk():
            pieces.append((cur, it == mo(";")))
            cur = []
        else:
            cur.append(it)
    pieces.append((cur, False))
    out = []
    for pc, semi in pieces:
        if not pc:
            continue
        n = row(*pc)
        sep = '<span class="sep">;</span> ' if semi else " "
        out.append(f'<span class="mml"><math displaystyle="true">{mathml(n)}</math></span>'
                   f'<span class="mfb">{html(n)}</span>{sep}')
    return Markup('<div class="wf">' + "".join(out) + "</div>")


# ====================================================================== numbers
class Num:
    """Formats numbers and tags each with what it is (``data-k``)."""

    def __init__(self, ctx):
        self.ctx = ctx

    def __call__(self, value, key: str, digits: int = 4, signed: bool = False):
        v = float(value)
        if not signed:
            v = abs(v)
        return ("mn", self.ctx.fmt(v, digits).replace("-", "−"), key)

    def mm(self, value, key: str):
        return ("mn", self.ctx.fmt_fixed(abs(float(value)), 2), key)

    def exact(self, value, key: str):
        return ("mn", num(float(value), "g"), key)


def _xy(d, a="x", b="y"):
    return np.array([float(d[a]), float(d[b])])


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _rot(v):
    return np.array([-v[1], v[0]])


def _pname(p):
    """Point name -> (letter, subscript digits): 'O1' -> ('O', '1')."""
    i = len(p)
    while i > 0 and p[i - 1].isdigit():
        i -= 1
    return (p[:i], p[i:]) if 0 < i < len(p) else (p, "")


def P(p):
    """A point name as a formula node (O1 -> O with subscript 1)."""
    a, b = _pname(p)
    return sb(mt(a), b) if b else mt(a)


def qty(sym, *pts, sup=None):
    """v_BA -> v with the subscript 'BA' (point names joined)."""
    s = "".join(pts)
    return sbp(sym, s, sup) if sup else sb(sym, s)


def seg(*pts):
    """A plan segment: 'p', 'b' -> 'pb' (upright, lower case with subscripts)."""
    return mt("".join(pts))


def detail_position(ctx) -> int | None:
    """The position to write out: results ``positions.detail_position`` (the task's
    ``report.detail_position`` or the first working-stroke position after 0, chosen by
    the pipeline: ``tmm_cli.pipeline.default_detail``)."""
    return (ctx.results.get("positions") or {}).get("detail_position")


# ====================================================================== the section
class _Writer:
    def __init__(self, ctx, n: int):
        self.ctx = ctx
        self.t = ctx.t
        self.u = UNITS.get(ctx.lang, UNITS["en"])
        from ...drawings.words import balance_sub
        self.b = balance_sub(ctx.lang)     # the balancing moment's subscript: M_b, in ru and uk the course's
        self.num = Num(ctx)
        self.n = n
        res = ctx.results
        self.geom = plan_geometry(res)
        kin = res.get("kinematics") or []
        self.ke = next(e for e in kin if e["index"] == n)
        self.mu_v, self.mu_a, _, _ = drawn_scales(res, self.geom)     # the plans' as drawn
        self.pts = self.ke["points"]
        self.lk = self.ke["links"]
        self.w1 = float(res["drive"]["omega"])     # the crank's ω₁ (signed), as the results give it
        self.names = {l.index: l.name for l in self.geom.links}
        self.names[0] = "ground"
        self.blocks: list = []          # ('h', text) | ('p', text) | ('f', Markup)

    # ------------------------------------------------------------------ helpers
    def pt(self, key, **kw) -> Markup:
        """A translated paragraph whose arguments may be tagged numbers (("mn", text, key))."""
        marks = {}
        for k, v in list(kw.items()):
            if isinstance(v, tuple):
                marks[f"\u0002{k}\u0002"] = html(v)
                kw[k] = f"\u0002{k}\u0002"
        text = str(escape(self.t(key, **kw)))
        for m, h in marks.items():
            text = text.replace(m, h)
        return Markup(text)

    def h(self, text):
        self.blocks.append(("h", text))

    def p(self, text):
        self.blocks.append(("p", text))

    def f(self, *items):
        self.blocks.append(("f", formula(*items)))

    def r(self, p):
        return _xy(self.pts[p])

    def v(self, p):
        return _xy(self.pts[p], "vx", "vy")

    def a(self, p):
        return _xy(self.pts[p], "ax", "ay")

    def l(self, p, q):
        return float(np.hypot(*(self.r(p) - self.r(q))))

    def lval(self, p, q):
        return self.num(self.l(p, q), f"l:{p}:{q}")

    def w(self, name):
        return float(self.lk[name]["omega"] or 0.0)

    def e(self, name):
        return float(self.lk[name]["epsilon"] or 0.0)

    def sense(self, x):
        return self.t("worked.ccw") if x > 0 else self.t("worked.cw")

    def lab(self, p):
        return "p" if p in self.geom.ground else plan_label(p)

    def alab(self, p):
        return "π" if p in self.geom.ground else plan_label(p)

    def omega_sym(self, idx):
        return sb("ω", str(idx))

    # ------------------------------------------------------------------ groups
    def groups(self):
        """[(type, [link indices], inner joint, [outer joints])] in the order of attachment."""
        st = self.ctx.results.get("structure") or {}
        idx = {l.name: l.index for l in self.geom.links}
        out = []
        for g in st.get("groups") or []:
            G = [idx[n] for n in g["links"]]
            inner = [j for j in self.geom.joints if j.a in G and j.b in G]
            k = self.geom.order.get(G[0], 0)
            # outer pairs: to the frame and to the links attached before this group
            outer = [j for j in self.geom.joints if (j.a in G) != (j.b in G)
                     and self.geom.order.get(j.b if j.a in G else j.a, -1) < k]
            out.append((g.get("type") or "", G, inner, outer))
        return out

    def supported(self, G, inner, outer):
        """RRR, RRP (fixed guide): velocities, accelerations and kinetostatics."""
        if len(G) != 2 or len(inner) != 1 or len(outer) != 2:
            return False
        if inner[0].kind == "R":
            return all(j.kind == "R" or j.a == 0 for j in outer)
        return False

    def slotted(self, G, inner, outer):
        """RPR (a block on a guide of the other link, both hinged outside): (block, guide
        link, pin, the guide link's hinge) for the velocities and accelerations, else None."""
        if len(G) != 2 or len(inner) != 1 or len(outer) != 2 or inner[0].kind != "P":
            return None
        if not all(j.kind == "R" for j in outer):
            return None
        j = inner[0]
        s = self.geom.link(j.b) if self.geom.link(j.b).kind == "slider" else self.geom.link(j.a)
        g = self.geom.link(j.a if s.index == j.b else j.b)
        if s.kind != "slider" or g.kind != "bar" or not s.points:
            return None
        pin = s.points[0]
        hinge = next((jj.point for jj in outer if g.index in (jj.a, jj.b)), None)
        if hinge is None or not any(s.index in (jj.a, jj.b) and jj.point == pin for jj in outer):
            return None
        return s, g, pin, hinge

    def coincident(self, g, pin, hinge):
        """Velocity and acceleration of the guide link's point under the pin."""
        w, e = self.w(g.name), self.e(g.name)
        r = self.r(pin) - self.r(hinge)
        v = self.v(hinge) + w * _rot(r)
        a = self.a(hinge) + e * _rot(r) - w * w * r
        return v, a

    def slotted_velocity(self, G, sl):
        num = self.num
        s, g, pin, hinge = sl
        c = f"{pin}{g.index}"
        cl = plan_label(c)
        vc, _ = self.coincident(g, pin, hinge)
        self.p(self.t("worked.eq", p=c))
        line = hinge + next(p for p in g.points if p != hinge)
        self.f(vq("v", c), mo("="), vq("v", pin), mo("+"), vq("v", c, pin), mo(";"), vq("v", c, pin),
               mo(self.t("worked.par")), mt(line))
        extra = [mo(";"), vq("v", hinge), mo("="), ("mn", "0", "zero")] if hinge in self.geom.ground else []
        self.f(vq("v", c), mo("="), vq("v", hinge), mo("+"), vq("v", c, hinge), mo(";"), vq("v", c, hinge),
               mo(self.t("worked.perp")), mt(hinge + pin), *extra)
        self.p(self.t("worked.measured"))
        vcm = float(np.hypot(*vc))
        vr = float(np.hypot(*(vc - self.v(pin))))
        vh = float(np.hypot(*(vc - self.v(hinge))))
        self.f(qty("v", c), mo("="), seg("p", cl), mo("·"), sb("μ", "v"), mo("="), num.mm(vcm / self.mu_v, f"svc:{c}"),
               mo("·"), num.exact(self.mu_v, "mu_v"), mo("="), num(vcm, f"vc:{c}"), unit(self.u["m/s"]))
        self.f(qty("v", c, pin), mo("="), seg(plan_label(pin), cl), mo("·"), sb("μ", "v"), mo("="),
               num.mm(vr / self.mu_v, f"svcr:{c}:{pin}"), mo("·"), num.exact(self.mu_v, "mu_v"), mo("="),
               num(vr, f"vcr:{c}:{pin}"), unit(self.u["m/s"]))
        w = self.w(g.name)
        self.f(self.omega_sym(g.index), mo("="), frac(qty("v", c, hinge), qty("l", hinge, pin)), mo("="),
               frac(num(vh, f"vcr:{c}:{hinge}"), self.lval(hinge, pin)), mo("="), num(w, f"w:{g.name}"),
               unit(self.u["1/s"] + ", " + self.sense(w)))
        known = {g.index: hinge}
        self.similar_velocity(G, pin, known)
        return known

    def slotted_acceleration(self, G, sl, known):
        num = self.num
        s, g, pin, hinge = sl
        c = f"{pin}{g.index}"
        cl = plan_label(c)
        vc, ac = self.coincident(g, pin, hinge)
        line = hinge + next(p for p in g.points if p != hinge)
        w, e = self.w(g.name), self.e(g.name)
        L = self.l(hinge, pin)
        self.p(self.t("worked.eq", p=c))
        self.f(vq("a", c), mo("="), vq("a", pin), mo("+"), vq("a", c, pin, sup="k"), mo("+"),
               vq("a", c, pin, sup="r"), mo(";"), vq("a", c, pin, sup="k"), mo(self.t("worked.perp")), mt(line),
               mo(";"), vq("a", c, pin, sup="r"), mo(self.t("worked.par")), mt(line))
        first = [] if hinge in self.geom.ground else [vq("a", hinge), mo("+")]
        self.f(vq("a", c), mo("="), *first, vq("a", c, hinge, sup="n"), mo("+"), vq("a", c, hinge, sup="τ"), mo(";"),
               vq("a", c, hinge, sup="n"), mo(self.t("worked.par")), mt(hinge + pin),
               words("(" + self.t("worked.toward", a=pin, b=hinge) + ")"), mo(";"),
               vq("a", c, hinge, sup="τ"), mo(self.t("worked.perp")), mt(hinge + pin))
        self.p(self.t("worked.measured"))
        vr = float(np.hypot(*(vc - self.v(pin))))
        ak = 2.0 * abs(w) * vr
        kl = plan_label(pin) + "k"
        self.f(qty("a", c, pin, sup="k"), mo("="), ("mn", "2", "const:2"), mo("·"), self.omega_sym(g.index), mo("·"),
               qty("v", c, pin), mo("="), ("mn", "2", "const:2"), mo("·"), num(w, f"w:{g.name}"), mo("·"),
               num(vr, f"vcr:{c}:{pin}"), mo("="), num(ak, f"ak:{c}:{pin}"), unit(self.u["m/s2"]), mo(";"),
               seg(kl), mo("="), frac(num(ak, f"ak:{c}:{pin}"), num.exact(self.mu_a, "mu_a")), mo("="),
               num.mm(ak / self.mu_a, f"sak:{c}:{pin}"), unit(self.u["mm"]))
        an = w * w * L
        nl = f"n{g.index}".translate(SUB)
        self.f(qty("a", c, hinge, sup="n"), mo("="), sp(self.omega_sym(g.index), "2"), mo("·"), qty("l", hinge, pin),
               mo("="), sp(num(w, f"w:{g.name}"), "2"), mo("·"), self.lval(hinge, pin), mo("="),
               num(an, f"anc:{c}:{hinge}"), unit(self.u["m/s2"]), mo(";"), seg(self.alab(hinge), nl), mo("="),
               frac(num(an, f"anc:{c}:{hinge}"), num.exact(self.mu_a, "mu_a")), mo("="),
               num.mm(an / self.mu_a, f"sanc:{c}:{hinge}"), unit(self.u["mm"]))
        at = abs(e) * L
        self.f(qty("a", c, hinge, sup="τ"), mo("="), seg(nl, cl), mo("·"), sb("μ", "a"), mo("="),
               num.mm(at / self.mu_a, f"satc:{c}:{hinge}"), mo("·"), num.exact(self.mu_a, "mu_a"), mo("="),
               num(at, f"atc:{c}:{hinge}"), unit(self.u["m/s2"]), mo(";"), sb("ε", str(g.index)), mo("="),
               frac(qty("a", c, hinge, sup="τ"), qty("l", hinge, pin)), mo("="),
               frac(num(at, f"atc:{c}:{hinge}"), self.lval(hinge, pin)), mo("="), num(e, f"e:{g.name}"),
               unit(self.u["1/s2"] + ", " + self.sense(e)))
        ar = float(np.hypot(*(ac - self.a(pin) - 2.0 * w * _rot(vc - self.v(pin)))))
        self.f(qty("a", c, pin, sup="r"), mo("="), seg("k", cl), mo("·"), sb("μ", "a"), mo("="),
               num.mm(ar / self.mu_a, f"sar:{c}:{pin}"), mo("·"), num.exact(self.mu_a, "mu_a"), mo("="),
               num(ar, f"ar:{c}:{pin}"), unit(self.u["m/s2"]))
        acm = float(np.hypot(*ac))
        self.f(qty("a", c), mo("="), seg("π", cl), mo("·"), sb("μ", "a"), mo("="), num.mm(acm / self.mu_a, f"sac:{c}"),
               mo("·"), num.exact(self.mu_a, "mu_a"), mo("="), num(acm, f"ac:{c}"), unit(self.u["m/s2"]))
        self.similar_acceleration(G, pin, known)

    def group_title(self, typ, G):
        """The heading of a group, its link numbers tagged (``data-k="idx:<link>"``)."""
        a, _, b = self.t("worked.group", type=group_kind(typ, self.ctx.lang), links="\u0001").partition("\u0001")
        nums = ", ".join(f'<span class="mn" data-k="idx:{escape(self.names[i])}">{i}</span>' for i in G)
        return Markup(escape(a)) + Markup(nums) + Markup(escape(b))

    def ordered(self, outer, G):
        """Outer pairs: through a moving point first, then the frame, then a fixed guide."""
        def rank(j):
            Y = self.outer_point(j, G)[1]
            return 2 if Y is None else (1 if Y in self.geom.ground else 0)
        return sorted(outer, key=rank)

    def outer_point(self, j, G):
        """(link of the group, its known point or None for a fixed guide)."""
        l = j.b if j.b in G else j.a
        return l, (j.point if j.kind == "R" else None)

    # ------------------------------------------------------------------ velocities
    def crank_velocity(self):
        g = self.geom
        dl = g.link(g.drive)
        O, A = dl.points[0], dl.points[1]
        if O not in g.ground:
            O, A = A, O
        self.O, self.A = O, A
        w1 = self.w1
        num = self.num
        self.h(self.t("worked.crank") + f" {O}{A}")
        vA = float(np.hypot(*self.v(A)))
        self.f(qty("v", A), mo("="), self.omega_sym(dl.index), mo("·"), qty("l", O, A), mo("="),
               num(w1, f"w:{dl.name}"), mo("·"), self.lval(O, A), mo("="), num(vA, f"v:{A}"), unit(self.u["m/s"]),
               mo(";"), vq("v", A), mo(self.t("worked.perp")), mt(O + A))
        self.p(self.t("worked.scale_v"))
        self.f(sb("μ", "v"), mo("="), frac(qty("v", A), seg("p", plan_label(A))), mo("="),
               frac(num(vA, f"v:{A}"), num.mm(vA / self.mu_v, f"sv:{A}")), mo("="),
               num.exact(self.mu_v, "mu_v"), unit(self.u["mu_v"]))

    def group_velocity(self, typ, G, inner, outer):
        num = self.num
        X = inner[0].point
        self.p(self.t("worked.eq", p=X))
        known = {}
        for j in self.ordered(outer, G):
            l, Y = self.outer_point(j, G)
            if Y is None:
                self.f(vq("v", X), mo(self.t("worked.par")), words(self.t("worked.guide")))
            else:
                rhs = [vq("v", Y), mo("+"), vq("v", X, Y)]
                extra = [mo(";"), vq("v", Y), mo("="), ("mn", "0", "zero")] if Y in self.geom.ground else []
                self.f(vq("v", X), mo("="), *rhs, mo(";"), vq("v", X, Y), mo(self.t("worked.perp")),
                       mt(X + Y), *extra)
                known[l] = Y
        self.p(self.t("worked.measured"))
        vX = float(np.hypot(*self.v(X)))
        self.f(qty("v", X), mo("="), seg("p", plan_label(X)), mo("·"), sb("μ", "v"), mo("="),
               num.mm(vX / self.mu_v, f"sv:{X}"), mo("·"), num.exact(self.mu_v, "mu_v"), mo("="),
               num(vX, f"v:{X}"), unit(self.u["m/s"]))
        for l, Y in known.items():
            vr = float(np.hypot(*(self.v(X) - self.v(Y))))
            if Y not in self.geom.ground:
                self.f(qty("v", X, Y), mo("="), seg(self.lab(Y), plan_label(X)), mo("·"), sb("μ", "v"), mo("="),
                       num.mm(vr / self.mu_v, f"svr:{X}:{Y}"), mo("·"), num.exact(self.mu_v, "mu_v"), mo("="),
                       num(vr, f"vr:{X}:{Y}"), unit(self.u["m/s"]))
        for l, Y in known.items():
            name = self.names[l]
            vr = float(np.hypot(*(self.v(X) - self.v(Y))))
            w = self.w(name)
            self.f(self.omega_sym(l), mo("="), frac(qty("v", X, Y), qty("l", X, Y)), mo("="),
                   frac(num(vr, f"vr:{X}:{Y}"), self.lval(X, Y)), mo("="), num(w, f"w:{name}"),
                   unit(self.u["1/s"] + ", " + self.sense(w)))
        self.similar_velocity(G, X, known)
        return known

    def others(self, G, X, known):
        """(link index, point Q, base point) for the other points of the group's links."""
        out = []
        for l in G:
            lg = self.geom.link(l)
            if lg.kind != "bar":
                continue
            base = known.get(l, X)
            for q in lg.points + ([lg.com] if lg.com else []):
                if q in (X, base) or q in self.geom.ground or q not in self.pts:
                    continue
                out.append((l, q, base))
        return out

    def similar_velocity(self, G, X, known):
        rows = self.others(G, X, known)
        if not rows:
            return
        num = self.num
        self.p(self.t("worked.similar"))
        for l, q, base in rows:
            name = self.names[l]
            w = self.w(name)
            vr = abs(w) * self.l(q, base)
            vq = float(np.hypot(*self.v(q)))
            self.f(qty("v", q, base), mo("="), self.omega_sym(l), mo("·"), qty("l", q, base), mo("="),
                   num(w, f"w:{name}"), mo("·"), self.lval(q, base), mo("="), num(vr, f"vr:{q}:{base}"),
                   unit(self.u["m/s"]), mo(";"), qty("v", q), mo("="), seg("p", plan_label(q)), mo("·"), sb("μ", "v"), mo("="),
                   num.mm(vq / self.mu_v, f"sv:{q}"), mo("·"), num.exact(self.mu_v, "mu_v"), mo("="),
                   num(vq, f"v:{q}"), unit(self.u["m/s"]))

    # ------------------------------------------------------------------ accelerations
    def crank_acceleration(self):
        num = self.num
        g = self.geom
        dl = g.link(g.drive)
        O, A = self.O, self.A
        self.h(self.t("worked.crank") + f" {O}{A}")
        w1, e1 = self.w1, self.e(dl.name)
        an = w1 * w1 * self.l(O, A)
        at = abs(e1) * self.l(O, A)
        aA = float(np.hypot(*self.a(A)))
        self.f(vq("a", A), mo("="), vq("a", A, sup="n"), mo("+"), vq("a", A, sup="τ"), mo(";"),
               qty("a", A, sup="n"), mo("="), sp(self.omega_sym(dl.index), "2"), mo("·"), qty("l", O, A), mo("="),
               sp(num(w1, f"w:{dl.name}"), "2"), mo("·"), self.lval(O, A), mo("="), num(an, f"an:{A}:{O}"),
               unit(self.u["m/s2"]), mo(";"), qty("a", A, sup="τ"), mo("="), sb("ε", str(dl.index)), mo("·"),
               qty("l", O, A), mo("="), num(at, f"at:{A}:{O}"), unit(self.u["m/s2"]))
        self.p(self.t("worked.scale_a"))
        self.f(sb("μ", "a"), mo("="), frac(qty("a", A), seg("π", plan_label(A))), mo("="),
               frac(num(aA, f"a:{A}"), num.mm(aA / self.mu_a, f"sa:{A}")), mo("="),
               num.exact(self.mu_a, "mu_a"), unit(self.u["mu_a"]))

    def group_acceleration(self, typ, G, inner, outer, known):
        num = self.num
        X = inner[0].point
        self.p(self.t("worked.eq", p=X))
        for j in self.ordered(outer, G):
            l, Y = self.outer_point(j, G)
            if Y is None:
                self.f(vq("a", X), mo(self.t("worked.par")), words(self.t("worked.guide")))
                continue
            first = [] if Y in self.geom.ground else [vq("a", Y), mo("+")]
            self.f(vq("a", X), mo("="), *first, vq("a", X, Y, sup="n"), mo("+"),
                   vq("a", X, Y, sup="τ"), mo(";"), vq("a", X, Y, sup="n"), mo(self.t("worked.par")),
                   mt(X + Y), words("(" + self.t("worked.toward", a=X, b=Y) + ")"), mo(";"),
                   vq("a", X, Y, sup="τ"), mo(self.t("worked.perp")), mt(X + Y))
        self.p(self.t("worked.measured"))
        for l, Y in known.items():
            name = self.names[l]
            w, e = self.w(name), self.e(name)
            L = self.l(X, Y)
            an, at = w * w * L, abs(e) * L
            nl = f"n{l}".translate(SUB)
            self.f(qty("a", X, Y, sup="n"), mo("="), sp(self.omega_sym(l), "2"), mo("·"), qty("l", X, Y), mo("="),
                   sp(num(w, f"w:{name}"), "2"), mo("·"), self.lval(X, Y), mo("="), num(an, f"an:{X}:{Y}"),
                   unit(self.u["m/s2"]), mo(";"), seg(self.alab(Y), nl), mo("="),
                   frac(num(an, f"an:{X}:{Y}"), num.exact(self.mu_a, "mu_a")), mo("="),
                   num.mm(an / self.mu_a, f"san:{X}:{Y}"), unit(self.u["mm"]))
            self.f(qty("a", X, Y, sup="τ"), mo("="), seg(nl, plan_label(X)), mo("·"), sb("μ", "a"), mo("="),
                   num.mm(at / self.mu_a, f"sat:{X}:{Y}"), mo("·"), num.exact(self.mu_a, "mu_a"), mo("="),
                   num(at, f"at:{X}:{Y}"), unit(self.u["m/s2"]), mo(";"), sb("ε", str(l)), mo("="),
                   frac(qty("a", X, Y, sup="τ"), qty("l", X, Y)), mo("="),
                   frac(num(at, f"at:{X}:{Y}"), self.lval(X, Y)), mo("="), num(e, f"e:{name}"),
                   unit(self.u["1/s2"] + ", " + self.sense(e)))
        aX = float(np.hypot(*self.a(X)))
        self.f(qty("a", X), mo("="), seg("π", plan_label(X)), mo("·"), sb("μ", "a"), mo("="),
               num.mm(aX / self.mu_a, f"sa:{X}"), mo("·"), num.exact(self.mu_a, "mu_a"), mo("="),
               num(aX, f"a:{X}"), unit(self.u["m/s2"]))
        self.similar_acceleration(G, X, known)

    def similar_acceleration(self, G, X, known):
        num = self.num
        rows = self.others(G, X, known)
        if rows:
            self.p(self.t("worked.similar_a"))
        for l, q, base in rows:
            name = self.names[l]
            w, e = self.w(name), self.e(name)
            L = self.l(q, base)
            aq = float(np.hypot(*self.a(q)))
            self.f(vq("a", q), mo("="), vq("a", base), mo("+"), vq("a", q, base, sup="n"),
                   mo("+"), vq("a", q, base, sup="τ"), mo(";"), qty("a", q, base, sup="n"), mo("="),
                   sp(num(w, f"w:{name}"), "2"), mo("·"), self.lval(q, base), mo("="),
                   num(w * w * L, f"an:{q}:{base}"), unit(self.u["m/s2"]), mo(";"), qty("a", q, base, sup="τ"),
                   mo("="), num(e, f"e:{name}"), mo("·"), self.lval(q, base), mo("="),
                   num(abs(e) * L, f"at:{q}:{base}"), unit(self.u["m/s2"]), mo(";"), qty("a", q), mo("="),
                   seg("π", plan_label(q)), mo("·"), sb("μ", "a"), mo("="),
                   num.mm(aq / self.mu_a, f"sa:{q}"), mo("·"), num.exact(self.mu_a, "mu_a"), mo("="),
                   num(aq, f"a:{q}"), unit(self.u["m/s2"]))

    # ------------------------------------------------------------------ kinetostatics
    def kst_setup(self):
        res = self.ctx.results
        ks = next((e for e in res.get("kinetostatics") or [] if e["index"] == self.n), None)
        info = res.get("kinetostatics_info")
        if ks is None or info is None or "loads" not in ks or info.get("balance_kind") != "moment":
            return None
        return ks, info

    def load_items(self, ks, link_name):
        """[(name, point (2,), F (2,))] of the loads on a link (nonzero)."""
        return [(f["name"], np.array(f["point"], float), np.array(f["F"], float)) for f in ks["loads"]
                if f["link"] == link_name and float(np.hypot(*f["F"])) > 0]

    def couples_of(self, ks, link_name):
        return [(c["name"], float(c["M"])) for c in ks.get("couples", [])
                if c["link"] == link_name and c.get("M") is not None and abs(float(c["M"])) > 0]

    def reaction_on(self, ks, j, link):
        """(name, point, F) of the reaction of pair j acting on ``link``."""
        key = f"R{j.a}{j.b}"
        r = ks["reactions"][key]
        F = np.array([r["x"], r["y"]], float)
        pt = np.array(r.get("point") or r.get("pin"), float)
        if j.b == link:
            return key, f"R{j.a}{j.b}", pt, F
        return key, f"R{j.b}{j.a}", pt, -F

    def vfsym(self, name):
        from ...drawings.forces import label_parts
        sym, sub = label_parts(name, self.ctx.lang)
        return sb(vec(mi(sym)), sub) if sub else vec(mi(sym))

    def fsym(self, name):
        from ...drawings.forces import label_parts
        s, sub = label_parts(name, self.ctx.lang)
        return sb(s, sub) if sub else mi(s)

    def loads_block(self, ks, G):
        num = self.num
        links = {l["name"]: l for l in (self.ctx.results.get("structure") or {}).get("links") or []}
        # with `motion: true` the inertia loads follow the flywheel's omega(phi), eps(phi), not the
        # constant-speed accelerations of the kinematics: their values only, no substitution
        steady = (self.ctx.results.get("kinetostatics_info") or {}).get("motion") != "steady"
        # with balancing.apply a counterweighted link's mass, centre of mass and J are the applied
        # ones (results balancing.applied); its centre of mass is not a point of the kinematics:
        # the inertia loads' values only, no substitution
        applied = (self.ctx.results.get("balancing") or {}).get("applied") or {}
        self.p(self.t("worked.loads"))
        for l in G:
            name = self.names[l]
            spec = applied.get(name) or links.get(name)
            mass, J = (spec.get("mass"), spec.get("J")) if spec else (None, None)
            moved = name in applied
            items = []
            for f in ks["loads"]:
                if f["link"] != name:
                    continue
                Fm = float(np.hypot(*f["F"]))
                if f["kind"] == "gravity" and mass and Fm > 0:
                    items += [self.fsym(f["name"]), mo("="), sb("m", str(l)), mo("·"), mi("g"), mo("="),
                              num(mass, f"m:{name}"), mo("·"), num(9.81, "g"), mo("="),
                              num(Fm, f"F:{f['name']}"), unit(self.u["N"]), mo(";")]
                elif f["kind"] == "inertia" and mass and Fm > 0 and steady and not moved:
                    s = f"S{l}"
                    aS = float(np.hypot(*self.a(s))) if s in self.pts else None
                    if aS is None:
                        continue
                    items += [self.fsym(f["name"]), mo("="), sb("m", str(l)), mo("·"), qty("a", s), mo("="),
                              num(mass, f"m:{name}"), mo("·"), num(aS, f"a:{s}"), mo("="),
                              num(Fm, f"F:{f['name']}"), unit(self.u["N"]), mo(";")]
                elif Fm > 0:
                    items += [self.fsym(f["name"]), mo("="), num(Fm, f"F:{f['name']}"), unit(self.u["N"]), mo(";")]
            for c in ks.get("couples", []):
                if c["link"] != name or not c.get("M"):
                    continue
                if c["kind"] == "inertia" and J and steady:
                    items += [self.fsym(c["name"]), mo("="), sb("J", f"S{l}"), mo("·"), sb("ε", str(l)), mo("="),
                              num(J, f"J:{name}"), mo("·"), num(self.e(name), f"e:{name}"), mo("="),
                              num(c["M"], f"M:{c['name']}"), unit(self.u["Nm"]), mo(";")]
                else:
                    items += [self.fsym(c["name"]), mo("="), num(c["M"], f"M:{c['name']}"), unit(self.u["Nm"]),
                              mo(";")]
            if items:
                self.f(*items[:-1])

    def moment_terms(self, forces, couples, X):
        """Terms ±F·h (arms about X) and ±M of a moment equation; -> (nodes, total)."""
        num = self.num
        nodes, total = [], 0.0
        rX = self.r(X)
        for name, pt, F in forces:
            m = _cross(pt - rX, F)
            Fm = float(np.hypot(*F))
            if abs(m) <= 1e-12 * max(Fm, 1e-300) * max(self.scale_len, 1e-300):
                continue
            total += m
            nodes += [brk(), mo("+" if m > 0 else "−"), num(Fm, f"F:{name}" if not name.startswith("R") else
                                                      f"R:{name}"), mo("·"),
                      num(abs(m) / Fm, f"h:{name}:{X}")]
        for name, M in couples:
            total += M
            nodes += [brk(), mo("+" if M > 0 else "−"), num(M, f"M:{name}")]
        return nodes, total

    def group_kinetostatics(self, ks, typ, G, inner, outer, later):
        """later: pairs to links attached after this group (their reactions are known)."""
        num = self.num
        X = inner[0].point
        self.loads_block(ks, G)
        unknown_t = []
        for j in outer:
            l, Y = self.outer_point(j, G)
            if Y is None:
                continue
            name = self.names[l]
            key, rname, pt, F = self.reaction_on(ks, j, l)
            forces = self.load_items(ks, name)
            for jj in later:
                if l in (jj.a, jj.b):
                    _, rn, p2, F2 = self.reaction_on(ks, jj, l)
                    forces.append((rn, p2, F2))
            couples = self.couples_of(ks, name)
            L = self.l(X, Y)
            e = (self.r(Y) - self.r(X)) / L
            Rt = float(np.dot(F, _rot(e)))
            terms, total = self.moment_terms(forces, couples, X)
            tsym = sbp("R", rname[1:], "τ")
            self.p(self.pt("worked.moment_eq", link=("mn", str(l), f"idx:{name}"), p=X, r=rname))
            self.f(mi("Σ"), sb("M", X), mo("("), ("mn", str(l), f"idx:{name}"), mo(")"), mo("="), tsym, mo("·"), qty("l", X, Y), *terms,
                   mo("="), ("mn", "0", "zero"))
            self.f(tsym, mo("="), mo("−"), frac(row(mi("Σ"), sb("M", X)), qty("l", X, Y)), mo("="),
                   frac(row(mo("−"), mo("("), num(total, f"Mt:{rname}:{X}", signed=True), mo(")")), self.lval(X, Y)),
                   mo("="),
                   num(Rt, f"Rt:{rname}:{X}", signed=True), unit(self.u["N"]))
            unknown_t.append((j, l, Y, rname, tsym, F, e, Rt, L))
        # the polygon
        self.p(self.t("worked.polygon"))
        chain = []
        for j, l, Y, rname, tsym, F, e, Rt, L in unknown_t[:1]:
            chain += [sbp(vec(mi("R")), rname[1:], "n"), mo("+"), sbp(vec(mi("R")), rname[1:], "τ"), mo("+")]
        for l in G:
            for name, _, _ in self.load_items(ks, self.names[l]):
                chain += [self.vfsym(name), mo("+"), brk()]
            for jj in later:
                if l in (jj.a, jj.b):
                    _, rn, _, _ = self.reaction_on(ks, jj, l)
                    chain += [self.vfsym(rn), mo("+")]
        lastname = None
        for j, l, Y, rname, tsym, F, e, Rt, L in unknown_t[1:]:
            chain += [sbp(vec(mi("R")), rname[1:], "τ"), mo("+"), sbp(vec(mi("R")), rname[1:], "n"), mo("+")]
        for j in outer:
            if j.kind == "P":
                l = j.b if j.b in G else j.a
                key, rname, pt, F = self.reaction_on(ks, j, l)
                chain += [self.vfsym(rname), mo("+")]
                lastname = rname
        self.f(*chain[:-1], mo("="), ("mn", "0", "zero"))
        for j, l, Y, rname, tsym, F, e, Rt, L in unknown_t:
            Rn = float(np.dot(F, -e))
            Rm = float(np.hypot(*F))
            self.f(sbp("R", rname[1:], "n"), mo("="), num(Rn, f"Rn:{rname}:{X}", signed=True), unit(self.u["N"]),
                   mo(";"), self.fsym(rname), mo("="),
                   ("sqrt", row(sp(row(mo("("), num(Rn, f"Rn:{rname}:{X}", signed=True), mo(")")), "2"), mo("+"),
                                sp(row(mo("("), num(Rt, f"Rt:{rname}:{X}", signed=True), mo(")")), "2"))),
                   mo("="), num(Rm, f"R:{rname}"), unit(self.u["N"]))
        for j in outer:
            if j.kind == "P":
                l = j.b if j.b in G else j.a
                key, rname, pt, F = self.reaction_on(ks, j, l)
                self.f(self.fsym(rname), mo("="), num(np.hypot(*F), f"R:{rname}"), unit(self.u["N"]),
                       mo(";"), self.vfsym(rname), mo(self.t("worked.perp")), words(self.t("worked.guide")))
        # inner reaction from the first link of the group
        l1 = G[0]
        jin = inner[0]
        key, rin, pin_, Fin = self.reaction_on(ks, jin, l1)
        self.p(self.t("worked.order_p" if lastname else "worked.order", inner=rin))
        self.p(self.pt("worked.inner", link=("mn", str(l1), f"idx:{self.names[l1]}")))
        parts = []
        for j in outer:
            if l1 in (j.a, j.b):
                _, rn, _, _ = self.reaction_on(ks, j, l1)
                parts += [self.vfsym(rn), mo("+")]
        for name, _, _ in self.load_items(ks, self.names[l1]):
            parts += [self.vfsym(name), mo("+")]
        for jj in later:
            if l1 in (jj.a, jj.b):
                _, rn, _, _ = self.reaction_on(ks, jj, l1)
                parts += [self.vfsym(rn), mo("+")]
        self.f(self.vfsym(rin), mo("="), mo("−"), mo("("), *parts[:-1], mo(")"), mo(";"), self.fsym(rin), mo("="),
               num(np.hypot(*Fin), f"R:{rin}"), unit(self.u["N"]))

    def slotted_kinetostatics(self, ks, G, sl, inner, outer, later):
        """RPR: the reaction of the block on the guide link (perpendicular to the guide)
        from the guide link's moment equation about its hinge, then the polygons of the
        block and of the guide link."""
        num = self.num
        s, g, pin, hinge = sl
        self.loads_block(ks, G)
        _, rsg, pt, F = self.reaction_on(ks, inner[0], g.index)
        forces = self.load_items(ks, g.name)
        for jj in later:
            if g.index in (jj.a, jj.b):
                _, rn, p2, F2 = self.reaction_on(ks, jj, g.index)
                forces.append((rn, p2, F2))
        terms, total = self.moment_terms(forces, self.couples_of(ks, g.name), hinge)
        m = _cross(pt - self.r(hinge), F)
        Fm = float(np.hypot(*F))
        h = abs(m) / Fm
        self.p(self.pt("worked.moment_eq_p", link=("mn", str(g.index), f"idx:{g.name}"), p=hinge, r=rsg))
        self.f(mi("Σ"), sb("M", hinge), mo("("), ("mn", str(g.index), f"idx:{g.name}"), mo(")"), mo("="),
               self.fsym(rsg), mo("·"), sb("h", rsg[1:]), *terms, mo("="), ("mn", "0", "zero"), mo(";"),
               vq("R", rsg[1:]), mo(self.t("worked.perp")), words(self.t("worked.guide")))
        self.f(self.fsym(rsg), mo("="), mo("−"), frac(row(mi("Σ"), sb("M", hinge)), sb("h", rsg[1:])), mo("="),
               frac(row(mo("−"), mo("("), num(total, f"Mr:{rsg}:{hinge}", signed=True), mo(")")),
                    num(h, f"h:{rsg}:{hinge}")), mo("="), num(m / h, f"Rm:{rsg}:{hinge}", signed=True),
               unit(self.u["N"]))
        self.p(self.pt("worked.order_rpr", r=rsg, kind=self.ctx.link_kind_word(s.name) or "",
                       block=("mn", str(s.index), f"idx:{s.name}"), bname=s.name,
                       link=("mn", str(g.index), f"idx:{g.name}"), lname=g.name))
        for lk in (s, g):
            own = [j for j in outer if lk.index in (j.a, j.b)][0]
            _, rn, _, Fo = self.reaction_on(ks, own, lk.index)
            parts = []
            for name, _, _ in self.load_items(ks, lk.name):
                parts += [self.vfsym(name), mo("+")]
            for jj in later + [inner[0]]:
                if lk.index in (jj.a, jj.b):
                    _, r2, _, _ = self.reaction_on(ks, jj, lk.index)
                    parts += [self.vfsym(r2), mo("+")]
            self.f(self.vfsym(rn), mo("="), mo("−"), mo("("), *parts[:-1], mo(")"), mo(";"), self.fsym(rn), mo("="),
                   num(np.hypot(*Fo), f"R:{rn}"), unit(self.u["N"]))

    def crank_kinetostatics(self, ks):
        num = self.num
        g = self.geom
        dl = g.link(g.drive)
        O = self.O
        forces = self.load_items(ks, dl.name)
        pairs = [j for j in g.joints if dl.index in (j.a, j.b) and not (j.a == 0 and j.point == O)]
        for j in pairs:
            _, rn, pt, F = self.reaction_on(ks, j, dl.index)
            forces.append((rn, pt, F))
        couples = self.couples_of(ks, dl.name)
        self.h(self.t("worked.crank") + f" {O}{self.A}")
        self.p(self.t("worked.crank_eq"))
        self.loads_block(ks, [dl.index])
        terms, total = self.moment_terms(forces, couples, O)
        self.f(mi("Σ"), sb("M", O), mo("="), sb("M", self.b), *terms, mo("="), ("mn", "0", "zero"), mo(";"),
               sb("M", self.b), mo("="), num(ks["balancing_moment"], "Mb", signed=True), unit(self.u["Nm"]),
               words("(" + self.sense(ks["balancing_moment"]) + ")"))
        j0 = next(j for j in g.joints if j.a == 0 and dl.index == j.b)
        key, rn0, _, F0 = self.reaction_on(ks, j0, dl.index)
        parts = []
        for name, _, _ in forces:
            parts += [self.vfsym(name), mo("+")]
        self.f(self.vfsym(rn0), mo("="), mo("−"), mo("("), *parts[:-1], mo(")"), mo(";"), self.fsym(rn0),
               mo("="), num(np.hypot(*F0), f"R:{rn0}"), unit(self.u["N"]))

    def lever(self, ks, info):
        num = self.num
        A = self.A
        vA = float(np.hypot(*self.v(A)))
        sgn = 1.0 if self.w1 > 0 else -1.0
        from .kinetostatics import lever_scale
        mu = lever_scale(ks, self.ke)               # the lever's as drawn for this position
        self.h(self.t("worked.lever"))
        self.p(self.pt("worked.lever_text", pin=A, crank=self.O + A, pinl=plan_label(A), deg=("mn", "90", "const:90")))
        self.f(sb("μ", "v"), mo("="), num.exact(mu, "mu_lev"), unit(self.u["mu_v"]))
        terms, total = [], 0.0
        for f in ks["loads"]:
            F = np.array(f["F"], float)
            v = np.array(f["v"], float)
            Fm = float(np.hypot(*F))
            m = sgn * _cross(_rot(v), F) / mu          # N*mm on the plan, with the crank's sense
            if Fm <= 0 or abs(m) <= 1e-12 * Fm * max(vA, 1e-300) / mu:
                continue
            total += m
            terms += [brk(), mo("+" if m > 0 else "−"), num(Fm, f"F:{f['name']}"), mo("·"),
                      num.mm(abs(m) / Fm, f"hl:{f['name']}")]
        for c in ks.get("couples", []):
            M, w = c.get("M"), c.get("omega")
            if not M or not w:
                continue
            m = -sgn * float(M) * float(w) / mu
            total += m
            terms += [brk(), mo("+" if m > 0 else "−"), num(M, f"M:{c['name']}"), mo("·"),
                      num(w, f"w:{c['link']}"), mo("/"), num.exact(mu, "mu_lev")]
        Pb = total / (vA / mu)
        self.f(sb("P", self.b), mo("·"), seg("p", plan_label(A)), mo("="), *terms, mo("="),
               num(total, "lev", signed=True), mo(";"),
               sb("P", self.b), mo("="), frac(num(total, "lev", signed=True), num.mm(vA / mu, f"svl:{A}")), mo("="),
               num(Pb, "Pbz", signed=True), unit(self.u["N"]))
        self.f(sb("M", self.b), mo("="), sb("P", self.b), mo("·"), qty("l", self.O, A), mo("="),
               num(Pb, "Pbz", signed=True), mo("·"), self.lval(self.O, A), mo("="),
               num(ks["zhukovsky_moment"], "Mzh", signed=True), unit(self.u["Nm"]))
        self.blocks.append(("pn", self.t("worked.vs", mb="\u0001"), num(ks["balancing_moment"], "Mb", signed=True)))

    # ------------------------------------------------------------------ all
    def build(self):
        self.scale_len = max((self.l(p, q) for p in self.pts for q in self.pts
                              if not p.startswith("S") and not q.startswith("S")), default=1.0)
        groups = self.groups()
        self.h(self.t("worked.vel"))
        self.crank_velocity()
        known = {}
        for typ, G, inner, outer in groups:
            self.h(self.group_title(typ, G))
            sl = self.slotted(G, inner, outer)
            if self.supported(G, inner, outer):
                known[tuple(G)] = self.group_velocity(typ, G, inner, outer)
            elif sl is not None:
                known[tuple(G)] = self.slotted_velocity(G, sl)
            else:
                self.p(self.t("worked.unsupported", type=group_kind(typ, self.ctx.lang)))
        self.h(self.t("worked.acc"))
        self.crank_acceleration()
        for typ, G, inner, outer in groups:
            self.h(self.group_title(typ, G))
            sl = self.slotted(G, inner, outer)
            if tuple(G) in known and sl is not None:
                self.slotted_acceleration(G, sl, known[tuple(G)])
            elif tuple(G) in known:
                self.group_acceleration(typ, G, inner, outer, known[tuple(G)])
            else:
                self.p(self.t("worked.unsupported", type=group_kind(typ, self.ctx.lang)))
        kst = self.kst_setup()
        if kst is None:
            info = self.ctx.results.get("kinetostatics_info") or {}
            if self.ctx.results.get("kinetostatics"):
                self.h(self.t("worked.kst"))
                self.p(self.t("worked.kst_force" if info.get("balance_kind") == "force" else "worked.kst_absent"))
            return
        ks, info = kst
        self.h(self.t("worked.kst"))
        solved: list[int] = []
        for typ, G, inner, outer in reversed(groups):
            self.h(self.group_title(typ, G))
            later = [j for j in self.geom.joints if (j.a in G and j.b in solved) or (j.b in G and j.a in solved)]
            sl = self.slotted(G, inner, outer)
            if self.supported(G, inner, outer):
                self.group_kinetostatics(ks, typ, G, inner, outer, later)
            elif sl is not None:
                self.slotted_kinetostatics(ks, G, sl, inner, outer, later)
            else:
                self.p(self.t("worked.unsupported_kst", type=group_kind(typ, self.ctx.lang)))
            solved += G
        self.crank_kinetostatics(ks)
        if info.get("motion") == "steady":
            # the lever needs the velocities of the steady motion, which results.json keeps
            # only for the loads: its value is in the kinetostatics section's table
            self.h(self.t("worked.lever"))
            self.p(self.t("worked.lever_motion"))
            return
        self.lever(ks, info)


# ====================================================================== instant centres
CENTRE_COLOR = "#b03060"        # the circles of the instant centres
CENTRE_R = 1.5                  # mm
CENTRE_ROOM = 0.5               # a centre within this fraction of the mechanism's size beyond
                                # its box is drawn; one farther is listed with its coordinates


def centre_key(key: str) -> tuple[int, int]:
    """'0-2' -> (0, 2): the two links (0 the frame) of an entry of ``instant_centres``."""
    i, j = key.split("-")
    return int(i), int(j)


def centres_split(entry, lo, hi):
    """The instant centres of a kinematics entry: (drawn [(i, j, xy)], far [(i, j, xy)],
    at infinity [(i, j)]); drawn: within CENTRE_ROOM of the size of the box lo..hi beyond it."""
    span = float(np.max(np.asarray(hi, float) - np.asarray(lo, float)))
    room = CENTRE_ROOM * span
    drawn, far, inf = [], [], []
    for key, xy in sorted((entry.get("instant_centres") or {}).items(), key=lambda kv: centre_key(kv[0])):
        i, j = centre_key(key)
        if xy is None:
            inf.append((i, j))
            continue
        q = np.asarray(xy, float)
        if np.all(q >= np.asarray(lo) - room) and np.all(q <= np.asarray(hi) + room):
            drawn.append((i, j, q))
        else:
            far.append((i, j, q))
    return drawn, far, inf


def centres_svg(ctx, geom, entries, entry, width_mm=150.0):
    """The mechanism at the worked position with its instant centres P_ij (small circles,
    labelled as the course writes them); the centres beyond the drawing's box are not drawn
    (the caption lists them). Returns (svg, far, at infinity) or None without centres."""
    from .. import figures as F
    if not entry.get("instant_centres"):
        return None
    lo, hi = F.mechanism_extent([entry])
    ranges = F.slider_ranges(entries, geom)
    for a, b in ranges.values():
        lo, hi = np.minimum(lo, np.minimum(a, b)), np.maximum(hi, np.maximum(a, b))
    drawn, far, inf = centres_split(entry, lo, hi)
    for _, _, q in drawn:
        lo, hi = np.minimum(lo, q), np.maximum(hi, q)
    view, unit, title = F.figure_for_box(lo, hi, width_mm, min_h=45.0, max_h=140.0, margin_mm=10.0,
                                         lang=ctx.lang)
    taken: list = []
    F.draw_mechanism(view, geom, entry, unit, ranges=ranges, taken=[title], placed=taken)
    P = entry["points"]
    segs = []
    for l in geom.links:
        pts = [np.array([float(P[p]["x"]), float(P[p]["y"])]) for p in l.points if p in P]
        segs += [(pts[k], pts[k + 1]) for k in range(len(pts) - 1)]
    for _, _, q in drawn:
        view.circle(q, CENTRE_R * unit, face="none", edge=CENTRE_COLOR, lw=0.8, z=6)
    if drawn:
        size = 7.0
        fs_mm = size / F.PT_PER_MM
        sizes = [tuple(unit * np.array(F.text_size("P", fs_mm, sub=f"{i}{j}"))) for i, j, _ in drawn]
        x0, y0 = view.origin
        x1, y1 = view.origin + unit * np.array([view.cv.w, view.cv.h])
        pad = 0.5 * unit
        pos = F.place_labels([(q[0], q[1], None) for _, _, q in drawn], 50.0 * unit,
                             avoid=[q for _, _, q in drawn], step=3.0 * unit, segments=segs, sizes=sizes,
                             taken=taken, bounds=(x0 + pad, y0 + pad, x1 - pad, y1 - pad))
        for (i, j, _), (x, y) in zip(drawn, pos):
            view.text((x, y), "P", size=size, z=8, italic=True, color=CENTRE_COLOR, sub=f"{i}{j}")
    return ctx.svg(view, F.pos_name("centres", entry["index"])), far, inf


def centres_caption(ctx, far, inf) -> Markup:
    """The figure's caption: what P_ij is, the centres at infinity and those beyond the box."""
    def name(i, j):
        return Markup("<i>P</i><sub>{}{}</sub>").format(i, j)
    a, b = ctx.t("worked.centres_caption", p="\u0001").split("\u0001")
    out = Markup(escape(a)) + Markup("<i>P</i><sub><i>ij</i></sub>") + Markup(escape(b))
    if inf:
        out += Markup(" ") + Markup(escape(ctx.t("worked.centres_inf"))) + Markup(" ") + \
            Markup(", ").join(name(i, j) for i, j in inf) + Markup(".")
    if far:
        out += Markup(" ") + Markup(escape(ctx.t("worked.centres_far"))) + Markup(" ") + Markup("; ").join(
            name(i, j) + Markup(" ({}; {})").format(ctx.fmt(q[0]), ctx.fmt(q[1])) for i, j, q in far) + Markup(".")
    return out


def build(ctx) -> str | None:
    kin = ctx.results.get("kinematics") or []
    if not kin or not (ctx.results.get("structure") or {}).get("links"):
        return None
    n = detail_position(ctx)
    if n is None or not any(e["index"] == n for e in kin):
        return None
    w = _Writer(ctx, n)
    if w.geom is None:
        return None
    try:
        w.build()
    except (TypeError, ValueError, ZeroDivisionError):
        # a value of this position is undefined (null in results.json: next to a change
        # point or a singular position): the working cannot be written with numbers
        w.blocks = [("p", ctx.t("worked.undefined"))]
    num = w.num
    e = w.ke
    head = ("row", [mt(ctx.t("worked.position") + " "), num.exact(n, "pos"), mo(","), mi("φ"), mo("="),
                    ("mn", ctx.fmt_fixed(e["phi"], 2), "phi"), mt("°")])
    blocks = []
    for b in w.blocks:
        if b[0] == "pn":
            text, nn = b[1], b[2]
            a, c = text.split("\u0001")
            blocks.append(("p", Markup(escape(a)) + Markup(html(nn)) + Markup(escape(c))))
        else:
            blocks.append(b)
    fig = centres_svg(ctx, w.geom, kin, e)
    fig_centres, centres_note = (fig[0], centres_caption(ctx, fig[1], fig[2])) if fig else (None, None)
    return ctx.render("sections/worked.html.j2", blocks=blocks, head=Markup(html(head)),
                      fig_centres=fig_centres, centres_note=centres_note,
                      intro=ctx.t("worked.intro", i="\u0001").split("\u0001"), n=Markup(html(num.exact(n, "pos"))))
