"""The working of one position written out step by step (report section 'worked').

Every number of the rendered section (as a browser shows it: headless Chromium) is
read back and recomputed here from results.json (and, for masses and moments of
inertia, from the task file): each number carries ``data-k`` saying what it is, the
test computes that quantity by its own formula from the results (distances from the
point coordinates, omega^2 l, |eps| l, the arm |r x F| / |F|, the components of a
reaction along and across its link, the moment sum -R^t l that closes a moment
equation, the lever's P_b pa) and compares it to the precision shown; a number
without a tag fails the test.  Also: the default detail position is the first
grid position where the output moves in its working sense (from the velocities of
results.json, not from the extremes the section reads); a position that does not
exist is an input error (exit 2) naming the field and its line; the section exists
in en/ru/uk; in print (the PDF) the formulas are written as HTML, not MathML."""
from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
TASK = ROOT / "tasks" / "forging_sixbar.yaml"
NICE = (1, 1.5, 2, 2.5, 3, 4, 5, 6, 8)


def _run(task: Path, out: Path, fmt: str = "html", lang: str = "en") -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(task), "-o", str(out), "--format", fmt,
                           "--lang", lang], capture_output=True, text=True, cwd=ROOT)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("worked")
    text = TASK.read_text(encoding="utf-8").replace("kinetostatics:\n", "report: {detail_position: 2}\nkinetostatics:\n")
    task = out / "forging_detail2.yaml"
    task.write_text(text, encoding="utf-8")
    r = _run(task, out / "o")
    assert r.returncode == 0, r.stderr
    return out / "o", task


# ---------------------------------------------------------------- the independent values
class Expected:
    """The value of each data-k key, from results.json (and the task's masses)."""

    def __init__(self, res: dict, task, n: int, mu_v: float, mu_a: float):
        self.res = res
        self.task = task
        self.ke = next(e for e in res["kinematics"] if e["index"] == n)
        self.ks = next(e for e in res["kinetostatics"] if e["index"] == n)
        self.n = n
        self.mu_v, self.mu_a = mu_v, mu_a
        from tmm_cli.report.sections.kinetostatics import lever_scale
        self.mu_lev = lever_scale(self.ks, self.ke)         # the lever's own, as drawn
        self.links = {l["name"]: l for l in res["structure"]["links"]}

    def r(self, p):
        d = self.ke["points"][p]
        return np.array([d["x"], d["y"]])

    def v(self, p):
        d = self.ke["points"][p]
        return np.array([d["vx"], d["vy"]])

    def a(self, p):
        d = self.ke["points"][p]
        return np.array([d["ax"], d["ay"]])

    def dist(self, p, q):
        return float(np.hypot(*(self.r(p) - self.r(q))))

    def link_of(self, p, q):
        for name, l in self.links.items():
            pts = set(l["points"]) | {l.get("com")}
            if p in pts and q in pts:
                return name
        raise KeyError((p, q))

    def w(self, link):
        return abs(self.ke["links"][link]["omega"])

    def e(self, link):
        return abs(self.ke["links"][link]["epsilon"])

    def force(self, name):
        """(point, F) of a load or of the reaction R<i><j> (force of link i on link j)."""
        for f in self.ks["loads"]:
            if f["name"] == name:
                return np.array(f["point"]), np.array(f["F"])
        i, j = name[1], name[2:]
        key = f"R{i}{j}" if f"R{i}{j}" in self.ks["reactions"] else f"R{j}{i}"
        r = self.ks["reactions"][key]
        F = np.array([r["x"], r["y"]])
        return np.array(r.get("point") or r["pin"]), (F if key == name else -F)

    def coincident(self, c: str):
        """v, a of the point of link i under the pin P, for the name 'P<i>' (rigid body
        about any point Q of link i: v_Q + w x r, a_Q + e x r - w^2 r)."""
        pin, i = c[:-1], int(c[-1])
        link = next(l for l in self.links.values() if l["index"] == i)
        q = link["points"][0]
        w = self.ke["links"][link["name"]]["omega"]
        e = self.ke["links"][link["name"]]["epsilon"]
        r = self.r(pin) - self.r(q)
        rot = np.array([-r[1], r[0]])
        return self.v(q) + w * rot, self.a(q) + e * rot - w * w * r, link["name"], pin, w

    def slotted(self, k, a):
        vc, ac, name, pin, w = self.coincident(a[0])
        vrel = vc - self.v(pin)
        mu = self.mu_v if k in ("svc", "svcr") else self.mu_a
        if k in ("vc", "svc"):
            x = float(np.hypot(*vc))
        elif k in ("vcr", "svcr"):
            x = float(np.hypot(*(vc - self.v(a[1]))))
        elif k in ("ac", "sac"):
            x = float(np.hypot(*ac))
        elif k in ("ak", "sak"):
            x = 2 * abs(w) * float(np.hypot(*vrel))
        elif k in ("ar", "sar"):
            x = float(np.hypot(*(ac - self.a(pin) - 2 * w * np.array([-vrel[1], vrel[0]]))))
        elif k in ("anc", "sanc"):
            x = w * w * self.dist(pin, a[1])
        else:
            x = self.e(name) * self.dist(pin, a[1])
        return x / mu if k.startswith("s") else x

    def mass_props(self, name: str) -> tuple[float, float]:
        """The link's mass and J_S from the task; with balancing.apply and a counterweight on the
        link (a two-point bar, its frame from its first point, the fixed pivot, along the bar),
        a point mass m at (r cos a, r sin a) added by hand: M' = M + m, S' = (M S + m X)/M',
        J' = J + M |S - S'|^2 + m |X - S'|^2."""
        spec = self.task.mechanism.links[name]
        M, J = float(spec.mass), float(spec.J)
        bal = self.res.get("balancing") or {}
        cw = next((c for c in (bal.get("counterweights") or {}).values() if c["link"] == name), None)
        if cw is None or self.task.balancing is None or not self.task.balancing.apply:
            return M, J
        # tmm's defaults: the drive link's centre of mass at its pivot, a bar's at its middle
        com = spec.com if spec.com is not None else \
            ((0.0, 0.0) if name == self.task.drive.link else (float(spec.length) / 2, 0.0))
        S = complex(float(com[0]), float(com[1]))
        X = cw["r"] * complex(math.cos(math.radians(cw["angle"])), math.sin(math.radians(cw["angle"])))
        M2 = M + cw["m"]
        S2 = (M * S + cw["m"] * X) / M2
        return M2, J + M * abs(S - S2) ** 2 + cw["m"] * abs(X - S2) ** 2

    def value(self, key: str) -> tuple[float, bool]:
        """(value, signed)."""
        k, *a = key.split(":")
        ks = self.ks
        if k == "pos":
            return self.n, False
        if k == "phi":
            return self.ke["phi"], False
        if k == "idx":
            return self.links[a[0]]["index"], False
        if k == "zero":
            return 0.0, False
        if k == "const":
            return float(a[0]), False
        if k == "g":
            return 9.81, False
        if k == "mu_v":
            return self.mu_v, False
        if k == "mu_a":
            return self.mu_a, False
        if k == "mu_lev":
            return self.mu_lev, False
        if k == "w":
            return self.w(a[0]), False
        if k == "e":
            return self.e(a[0]), False
        if k == "l":
            return self.dist(a[0], a[1]), False
        if k == "v":
            return float(np.hypot(*self.v(a[0]))), False
        if k == "a":
            return float(np.hypot(*self.a(a[0]))), False
        if k == "vr":
            return float(np.hypot(*(self.v(a[0]) - self.v(a[1])))), False
        if k in ("sv", "svl"):
            return float(np.hypot(*self.v(a[0]))) / (self.mu_v if k == "sv" else self.mu_lev), False
        if k == "svr":
            return float(np.hypot(*(self.v(a[0]) - self.v(a[1])))) / self.mu_v, False
        if k == "sa":
            return float(np.hypot(*self.a(a[0]))) / self.mu_a, False
        if k in ("an", "san"):
            x = self.w(self.link_of(a[0], a[1])) ** 2 * self.dist(a[0], a[1])
            return (x if k == "an" else x / self.mu_a), False
        if k in ("at", "sat"):
            x = self.e(self.link_of(a[0], a[1])) * self.dist(a[0], a[1])
            return (x if k == "at" else x / self.mu_a), False
        if k in ("vc", "svc", "vcr", "svcr", "ac", "sac", "ak", "sak", "ar", "sar", "anc", "sanc", "atc", "satc"):
            return self.slotted(k, a), False
        if k in ("m", "J"):     # the task's inputs (results.json repeats them in structure.links)
            return self.mass_props(a[0])[0 if k == "m" else 1], False
        if k == "F":
            return float(np.hypot(*self.force(a[0])[1])), False
        if k == "R":
            return float(np.hypot(*self.force(a[0])[1])), False
        if k == "M":
            return abs(next(c["M"] for c in ks["couples"] if c["name"] == a[0])), False
        if k == "h":
            pt, F = self.force(a[0])
            d = pt - self.r(a[1])
            return abs(d[0] * F[1] - d[1] * F[0]) / float(np.hypot(*F)), False
        if k in ("Rm", "Mr"):                       # a force by its moment about a point: sign(M) |F|, -M
            pt, F = self.force(a[0])
            d = pt - self.r(a[1])
            m = d[0] * F[1] - d[1] * F[0]
            return (math.copysign(float(np.hypot(*F)), m) if k == "Rm" else -m), True
        if k in ("Rt", "Rn", "Mt"):
            pt, F = self.force(a[0])
            X = self.r(a[1])
            L = float(np.hypot(*(pt - X)))
            e = (pt - X) / L
            t = np.array([-e[1], e[0]])
            Rt = float(F @ t)
            return {"Rt": Rt, "Rn": float(F @ -e), "Mt": -Rt * L}[k], True
        if k == "hl":
            f = next(f for f in ks["loads"] if f["name"] == a[0])
            v, F = np.array(f["v"]), np.array(f["F"])
            return abs(-v[1] * F[1] - v[0] * F[0]) / float(np.hypot(*F)) / self.mu_lev, False
        arm = self.res["kinetostatics_info"]["arm"]
        if k == "Mb":
            return ks["balancing_moment"], True
        if k == "Mzh":
            return ks["zhukovsky_moment"], True
        if k == "Pbz":
            return ks["zhukovsky_moment"] / arm, True
        if k == "lev":
            crank = self.links[self.task.drive.link]
            pin = next(q for q in crank["points"] if q not in self.task.mechanism.ground)
            return ks["zhukovsky_moment"] / arm * float(np.hypot(*self.v(pin))) / self.mu_lev, True
        raise KeyError(key)


def _close(shown: str, true: float, signed: bool) -> bool:
    s = shown.replace("−", "-")
    x = float(s)
    if not signed:
        true = abs(true)
    dec = len(s.split(".")[1]) if "." in s else 0
    return abs(x - true) <= 0.5 * 10 ** -dec * (1 + 1e-9) + 1e-12 * abs(true)


# a digit that is not part of a name (R12, O1, ω2, the barred vector R̄34)
_UNTAGGED = re.compile(r"(?<![A-Za-zА-Яа-яЁёІіЇїЄєҐґΑ-Ωα-ωτπ¯\d.,])\d")

# (the drawing of the position with its instant centres and its caption: tests/test_worked_centres.py)
STRIP = """(root, print) => {
  const c = root.cloneNode(true);
  c.querySelectorAll(print ? 'style, figure, .mml, [data-k], .unit' : 'style, figure, .mfb, [data-k], .unit')
    .forEach(e => e.remove());
  return c.textContent; }"""


def _numbers(pg, print_: bool = False):
    """(the visible tagged numbers [(key, text)], the section's visible text without them)."""
    tagged = pg.eval_on_selector_all(
        "#worked [data-k]", "es => es.filter(e => e.checkVisibility()).map(e => [e.dataset.k, e.textContent])")
    return tagged, pg.eval_on_selector("#worked", STRIP, print_)


def _page(browser, run, media="screen"):
    out, _ = run
    pg = browser.new_page(viewport={"width": 1100, "height": 900})
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto((out / "report.html").as_uri())
    pg.emulate_media(media=media)
    assert errors == []
    return pg


def _check_section(browser, out: Path, task_path: Path, n: int, kinds: set[str]):
    from tmm_cli.task import load_task
    res = json.loads((out / "results.json").read_text())
    pg = _page(browser, (out, task_path))
    tagged, rest = _numbers(pg)
    pg.close()
    assert len(tagged) > 150                       # the whole working, every step
    assert not _UNTAGGED.findall(rest), re.findall(r".{20}\d.{5}", rest)[:10]
    d = dict((k, t) for k, t in tagged)
    assert d["pos"] == str(n)
    mu_v, mu_a = float(d["mu_v"]), float(d["mu_a"])
    # the scales: nice numbers, the crank pin's largest vector at most 100 mm (shorter where the
    # plans are drawn at a larger scale to fit the page), the very scales of the drawn plans
    vA = max(math.hypot(e["points"]["A"]["vx"], e["points"]["A"]["vy"]) for e in res["kinematics"])
    aA = max(math.hypot(e["points"]["A"]["ax"], e["points"]["A"]["ay"]) for e in res["kinematics"])
    for mu, top in ((mu_v, vA), (mu_a, aA)):
        m = mu / 10 ** math.floor(math.log10(mu))
        assert any(abs(m - s) < 1e-9 for s in NICE), mu
        assert top / mu <= 100 + 1e-9
    from tmm_cli.plans import geometry
    from tmm_cli.report.sections.kinematics import drawn_scales
    assert (mu_v, mu_a) == drawn_scales(res, geometry(res))[:2]
    ex = Expected(res, load_task(task_path), n, mu_v, mu_a)
    seen = set()
    bad = []
    for key, text in tagged:
        val, signed = ex.value(key)
        seen.add(key.split(":")[0])
        if not _close(text, val, signed):
            bad.append((key, text, val))
    assert not bad, bad[:10]
    assert kinds <= seen, kinds - seen


def test_every_number_of_the_section_is_a_result(browser, run):
    """Every step is there: velocities, accelerations, loads, moment equations, the
    polygon, the lever; every number equals its value from results.json."""
    out, task_path = run
    _check_section(browser, out, task_path, 2,
                   {"v", "vr", "sv", "svr", "w", "an", "at", "san", "sat", "e", "a", "sa", "m", "J", "F", "h",
                    "Rt", "Rn", "Mt", "R", "Mb", "hl", "lev", "Pbz", "Mzh"})


def test_slotted_lever_with_coriolis(browser, shared_once):
    """The shaper's slotted lever (RPR): the coincident point A3 of the rocker, the
    relative and Coriolis accelerations (a^k = 2 omega_3 v_A3A), the block's reaction on
    the lever from the lever's moment equation about O1, at the default position."""
    from pdf_extent import report_out

    from tmm_cli.pipeline import default_detail
    task = ROOT / "tasks" / "shaper_slotted_lever.yaml"
    out = report_out(shared_once, task.stem, "en")       # as tmm run writes it, once a session
    res = json.loads((out / "results.json").read_text())
    _check_section(browser, out, task, default_detail(res["positions"]),
                   {"vc", "svc", "vcr", "svcr", "ak", "sak", "ar", "sar", "anc", "sanc", "atc", "satc", "ac",
                    "sac", "Rm", "Mr", "h", "R", "Rt", "Rn", "Mb", "hl", "lev"})


def test_the_print_version_has_the_same_numbers(browser, run):
    """In print (the PDF is made from it) the MathML is hidden and the same formulas are
    shown as HTML: the same tagged numbers in the same order."""
    screen = _page(browser, run)
    a = screen.eval_on_selector_all("#worked .mml [data-k]", "es => es.map(e => [e.dataset.k, e.textContent])")
    assert screen.eval_on_selector_all("#worked .mml", "es => es.filter(e => e.checkVisibility()).length") > 100
    screen.close()
    pr = _page(browser, run, "print")
    assert pr.eval_on_selector_all("#worked .mml", "es => es.filter(e => e.checkVisibility()).length") == 0
    b = pr.eval_on_selector_all("#worked .mfb [data-k]", "es => es.filter(e => e.checkVisibility())"
                                ".map(e => [e.dataset.k, e.textContent])")
    rest = pr.eval_on_selector("#worked", STRIP, True)
    pr.close()
    assert a == b and len(a) > 250
    assert not _UNTAGGED.findall(rest)


def test_detail_position_named_in_the_task(run):
    out, _ = run
    html = (out / "report.html").read_text(encoding="utf-8")
    sec = html[html.index('id="worked"'):]
    assert re.search(r'data-k="pos">2<', sec)


def _working_by_velocity(res: dict) -> int:
    """The first grid position after 0 where the output slider moves in its working
    sense: its velocity along the guide (the direction from the first to the second
    extreme position of its pin) is positive."""
    pos = res["positions"]
    out = pos["output"]
    pin = next(l for l in res["structure"]["links"] if l["name"] == out)["points"][0]
    ents = {e["index"]: e for e in res["kinematics"]}
    ext = [e for e in res["kinematics"] if e["index"] == pos["extreme_index"]][0]
    start = ents[0]["points"][pin]
    end = ext["points"][pin]
    u = np.array([end["x"] - start["x"], end["y"] - start["y"]])
    for i, k in zip(pos["index"], pos["kinds"]):
        if k == "grid" and i >= 1:
            v = np.array([ents[i]["points"][pin]["vx"], ents[i]["points"][pin]["vy"]])
            if v @ u > 0:
                return i
    raise AssertionError("no working position")


@pytest.mark.parametrize("name", ["forging_sixbar", "press_offset_slider_crank", "engine_slider_crank",
                                  "shaper_slotted_lever"])
def test_default_detail_position(name):
    from tmm_cli.pipeline import run as run_pipeline
    from tmm_cli.pipeline import default_detail
    from tmm_cli.task import load_task
    res = run_pipeline(load_task(ROOT / "tasks" / f"{name}.yaml"), kinematics_curve=0)
    assert res["positions"]["kinds"][0] == "grid" and "extreme_index" in res["positions"]
    assert default_detail(res["positions"]) == _working_by_velocity(res)
    assert res["positions"]["detail_position"] == default_detail(res["positions"])
    if name == "forging_sixbar":
        assert default_detail(res["positions"]) == 1


@pytest.mark.parametrize("value,msg", [("40", "position 40 does not exist"), ("two", "valid integer"),
                                       ("-1", "greater than or equal to 0"), ("2.5", "valid integer")])
def test_bad_detail_position_is_an_input_error(tmp_path, value, msg):
    text = TASK.read_text(encoding="utf-8").replace("kinetostatics:\n", f"report:\n  detail_position: {value}\n"
                                                    "kinetostatics:\n")
    task = tmp_path / "t.yaml"
    task.write_text(text, encoding="utf-8")
    line = text.splitlines().index(f"  detail_position: {value}") + 1
    for cmd in (["validate", str(task)], ["run", str(task), "-o", str(tmp_path / "o"), "--format", "json"]):
        r = subprocess.run([sys.executable, "-m", "tmm_cli", *cmd], capture_output=True, text=True, cwd=ROOT)
        assert r.returncode == 2, (cmd, r.stderr)
        assert "Traceback" not in r.stderr
        assert f"t.yaml:{line}:" in r.stderr and "report.detail_position" in r.stderr and msg in r.stderr, r.stderr


@pytest.mark.parametrize("lang,word", [("ru", "Расчёт одного положения"), ("uk", "Розрахунок одного положення")])
def test_section_in_russian_and_ukrainian(tmp_path, lang, word):
    from tmm_cli.pipeline import run as run_pipeline
    from tmm_cli.report import render_html
    from tmm_cli.task import load_task
    task = load_task(TASK)
    html, _ = render_html(run_pipeline(task, kinematics_curve=0), task, tmp_path, lang)
    sec = html[html.index('id="worked"'):]
    sec = sec[:sec.index("</section>")]
    assert word in sec and "<math" in sec
    assert not re.search(r">[^<]*\b(the|of|from|and)\b[^<]*<", re.sub(r"<math.*?</math>", "", sec, flags=re.S))


def _section_numbers(html: str) -> list[tuple[str, str]]:
    """(key, text) of every tagged number of the print rendering (the HTML formulas)."""
    return re.findall(r'<span class="mn" data-k="([^"]+)">([^<]*)</span>', html)


@pytest.mark.parametrize("name", ["engine_slider_crank", "compressor_v_twin", "crank_rocker_fourbar",
                                  "static_gravity", "press_offset_slider_crank", "motion", "balancing_fourbar"])
def test_numbers_of_other_tasks(tmp_path, name):
    """The same check without a browser on the HTML formulas (the PDF's) of other tasks:
    a slider-crank, a V-twin (two groups on one crank), a four-bar, a static problem,
    an offset press, and the forging machine with `motion: true` (inertia loads of the
    flywheel's steady motion: their values only, the lever left to the tables)."""
    from tmm_cli.pipeline import run as run_pipeline
    from tmm_cli.report import _context, sections
    from tmm_cli.report.sections import worked
    from tmm_cli.task import load_task
    if name == "motion":
        path = tmp_path / "motion.yaml"
        path.write_text(TASK.read_text(encoding="utf-8").replace("  balance: crank\n",
                                                                 "  balance: crank\n  motion: true\n"))
    else:
        path = ROOT / "tasks" / f"{name}.yaml"
    task = load_task(path)
    res = run_pipeline(task, kinematics_curve=0)
    sections.available()                      # the sections' text tables
    html = worked.build(_context(res, task, tmp_path, "en"))
    nums = _section_numbers(html)
    d = dict(nums)
    ex = Expected(res, task, int(d["pos"]), float(d["mu_v"]), float(d["mu_a"]))
    bad = [(k, t, ex.value(k)[0]) for k, t in nums if not _close(t, *ex.value(k))]
    assert not bad, bad[:10]
    assert len(nums) > 60
    kinds = {k.split(":")[0] for k, _ in nums}
    if res.get("kinetostatics"):
        assert {"Mb", "R", "h"} <= kinds
        assert ("lev" in kinds) == (name != "motion")


def test_undefined_value_gives_a_note_not_a_crash(tmp_path):
    """A null of results.json at the detail position (next to a change point) leaves the
    section with a note saying so, and the report whole."""
    import copy
    from tmm_cli.pipeline import run as run_pipeline
    from tmm_cli.report import _context, sections
    from tmm_cli.report.sections import worked
    from tmm_cli.task import load_task
    task = load_task(TASK)
    res = copy.deepcopy(run_pipeline(task, kinematics_curve=0))
    entry = next(e for e in res["kinematics"] if e["index"] == 1)
    entry["points"]["B"]["vx"] = entry["points"]["B"]["vy"] = None
    sections.available()
    html = worked.build(_context(res, task, tmp_path, "en"))
    assert "cannot be written out" in html and "data-k=\"pos\">1<" in html


def test_position_without_kinetostatics_says_so(tmp_path):
    """`kinetostatics.positions` without the detail position: the kinematics are written
    out and a note says the kinetostatics was not computed there."""
    from tmm_cli.pipeline import run as run_pipeline
    from tmm_cli.report import _context, sections
    from tmm_cli.report.sections import worked
    from tmm_cli.task import load_task
    path = tmp_path / "sel.yaml"
    path.write_text(TASK.read_text(encoding="utf-8").replace("  positions: all\n", "  positions: [0, 3]\n"))
    task = load_task(path)
    res = run_pipeline(task, kinematics_curve=0)
    sections.available()
    html = worked.build(_context(res, task, tmp_path, "en"))
    assert "was not computed at this position" in html and 'data-k="sv:B"' in html and "Mb" not in html


@pytest.mark.parametrize("name", ["engine_slider_crank", "crank_rocker_fourbar"])
def test_every_computed_load_and_component_carries_its_unit(tmp_path, name):
    """'G2 = m2 g = 6.000 * 9.810 = 58.86;' ended without N (and the inertia forces, their
    couples and the relative accelerations' components without theirs):
    every such result in the section (MathML and the print version) is followed by its unit."""
    from tmm_cli.pipeline import run as run_pipeline
    from tmm_cli.report import _context, sections
    from tmm_cli.report.sections import worked
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / f"{name}.yaml")
    res = run_pipeline(task, kinematics_curve=0)
    sections.available()
    html = worked.build(_context(res, task, tmp_path, "en"))
    want = {"F": "N", "M": "N·m", "an": "m/s²", "at": "m/s²"}
    found = re.findall(r'<mn[^>]*data-k="((F|M|an|at):[^"]+)">[^<]*</mn>(<mspace[^>]*></mspace><mtext class="unit">'
                       r'([^<]*)</mtext>)?', html)
    assert len(found) > 5
    units: dict = {}                  # a value is written with its unit where it is found (the
    for k, kind, _, u in found:       # line that computes it), and bare where a later one uses it
        units.setdefault(k, set()).add(u)
    bad = [(k, u) for k, u in units.items() if want[k.split(":")[0]] not in u]
    assert not bad, bad[:8]
