"""Path generation: the coupler point of the generated crank-rocker, computed here from the
reported lengths, pivots and coupler point by a closed-form circle intersection, passes each
target within its reported deviation; a known crank-rocker's own coupler points are recovered;
the crank turns (Grashof) and the transmission angle (law of cosines, crank along the frame)
stays above gamma_min; the same task gives the same linkage; the errors a student meets."""
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from tmm_cli import load_task, run
from tmm_cli.cli import app

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()


def _coupler(O, O1, a, b, c, uv, phi_deg, near_B):
    """A, B, M of a four-bar at crank angle phi (deg, absolute): B where the circles about A
    (radius b) and O1 (radius c) meet, the one nearer ``near_B``; M = A + u e + v n."""
    f = math.radians(phi_deg)
    A = np.array([O[0] + a * math.cos(f), O[1] + a * math.sin(f)])
    D = np.asarray(O1) - A
    L = float(np.hypot(*D))
    k = (b * b - c * c + L * L) / (2 * L)
    h = math.sqrt(max(b * b - k * k, 0.0))
    Bs = [A + (k * D + s * h * np.array([-D[1], D[0]])) / L for s in (1, -1)]
    B = min(Bs, key=lambda q: float(np.hypot(*(q - near_B))))
    e = (B - A) / b
    return A, B, A + uv[0] * e + uv[1] * np.array([-e[1], e[0]])


def _trace(r, phis):
    """M along the turn, each B the nearer to the last (the assembly branch of position 1)."""
    m = r["mechanism"]
    O, O1 = m["ground"]["O"], m["ground"]["O1"]
    L = r["lengths"]
    B = np.asarray(m["assembly"]["B"])
    out = []
    for p in phis:
        _, B, M = _coupler(O, O1, L["crank"], L["coupler"], L["rocker"], r["M"], p, B)
        out.append(M)
    return np.array(out)


@pytest.fixture(scope="module")
def example_results():
    return run(load_task(ROOT / "tasks" / "synthesis_path.yaml"))


@pytest.fixture(scope="module")
def example(example_results):
    return example_results["synthesis"]


def test_coupler_point_passes_within_the_reported_deviations(example):
    r = example
    T = np.asarray(r["points"])
    # from the first point's crank angle on, each point's crank angle in turn (continuous branch)
    start = r["crank_angles"][0]
    turn = sorted(range(len(T)), key=lambda j: (r["crank_angles"][j] - start) % 360.0)
    phis = [start + (r["crank_angles"][j] - start) % 360.0 for j in turn]
    dense = np.arange(start, start + 360.0, 0.05)
    Ms = _trace(r, dense)
    M_at = _trace(r, phis)
    for j, M in zip(turn, M_at):
        d = float(np.hypot(*(M - T[j])))
        assert d == pytest.approx(r["deviations"][j], rel=1e-6, abs=1e-12)
        # nothing on the curve is nearer (the optimum is the foot of the perpendicular)
        assert float(np.min(np.hypot(*(Ms - T[j]).T))) >= d - 1e-9
    assert r["max_deviation"] == pytest.approx(max(r["deviations"]), rel=1e-15)
    # the points were read off a crank-rocker's curve to the millimetre: within half a millimetre
    assert r["max_deviation"] < 5e-4


def test_a_crank_rocker_whose_transmission_angle_stays_above_the_limit(example):
    L = example["lengths"]
    a, b, c, d = L["crank"], L["coupler"], L["rocker"], L["frame"]
    s, *mid, l_ = sorted((a, b, c, d))
    assert s == a and s + l_ < sum(mid)          # Grashof, the crank the shortest
    # the angle between the coupler and the rocker with the crank along the frame line
    mus = [math.degrees(math.acos((b * b + c * c - (d - a) ** 2) / (2 * b * c))),
           math.degrees(math.acos((b * b + c * c - (d + a) ** 2) / (2 * b * c)))]
    gamma = min(min(m, 180 - m) for m in mus)
    assert gamma >= 30.0
    assert example["gamma_min"] == pytest.approx(gamma, abs=1e-6)
    assert example["grashof"] == "crank-rocker"
    assert math.dist(example["fixed_pivots"]["O"], example["fixed_pivots"]["O1"]) == pytest.approx(d, rel=1e-12)


def test_a_known_crank_rockers_own_points_recovered():
    # O (0.02, 0.01), frame along +x, a 0.1, b 0.35, c 0.3, d 0.3, M at u 0.15, v 0.2: ten points
    O, O1 = (0.02, 0.01), (0.32, 0.01)
    B = np.array([0.3, 0.3])
    pts = []
    for p in np.arange(0.0, 360.0, 36.0):
        _, B, M = _coupler(O, O1, 0.1, 0.35, 0.3, (0.15, 0.2), p, B)
        pts.append([float(M[0]), float(M[1])])
    task = load_task({"schema": "tmm/1", "synthesis": {"type": "path", "points": pts},
                      "drive": {"link": "crank", "speed": 6.0}})
    r = run(task)["synthesis"]
    extent = float(np.max(np.ptp(np.asarray(pts), axis=0)))
    assert r["max_deviation"] < 1e-4 * extent


def test_reproducible(example, monkeypatch):
    from tmm_cli.linkage import synthesis_path
    synthesis_path._FOUND.clear()               # searched anew, not the remembered answer
    monkeypatch.setenv(synthesis_path.CACHE_ENV, "off")     # nor the one kept on disk
    again = run(load_task(ROOT / "tasks" / "synthesis_path.yaml"))["synthesis"]
    assert again["lengths"] == example["lengths"] and again["deviations"] == example["deviations"]


@pytest.mark.parametrize("points, words", [
    ("[[0, 0], [1, 1], [2, 0], [3, 1]]", "at least 5"),
    ("5", "a list of 5 to 20 points"),
    ("[[0.1, 0.2], [0.1, 0.2], [0.1, 0.2], [0.1, 0.2], [0.1, 0.2]]", "all coincide"),
])
def test_bad_points_exit_2(tmp_path, points, words):
    f = tmp_path / "t.yaml"
    f.write_text(f"schema: tmm/1\nsynthesis:\n  type: path\n  points: {points}\ndrive: {{link: crank, speed: 6}}\n")
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 2 and "t.yaml:4" in res.output and "Traceback" not in res.output
    assert words in res.output


def test_starter_validates(tmp_path):
    res = runner.invoke(app, ["new", "synthesis_path"])
    assert res.exit_code == 0 and "type: path" in res.output


# ---------------------------------------------------------------- points far from any coupler curve: a warning
def test_deviation_warning_on_both_sides_of_the_limit():
    from tmm_cli.linkage.synthesis_path import DEVIATION_WARN, deviation_warnings
    T = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.5], [0.5, 1.0], [1.5, 1.5]]      # extent 2 m (the larger side)
    assert deviation_warnings(T, [0.0, 0.01, (DEVIATION_WARN - 1e-6) * 2.0, 0.0, 0.0]) == []
    got = deviation_warnings(T, [0.0, 0.01, (DEVIATION_WARN + 1e-6) * 2.0, 0.0, 0.0])
    assert [m.code for m in got] == ["synthesis.path_far"]
    assert got[0].params["point"] == 3 and got[0].params["extent"] == 2.0
    assert got[0].params["share"] == pytest.approx(DEVIATION_WARN + 1e-6)


def test_shipped_example_does_not_warn(example_results):
    assert not [m for m in example_results["messages"] if m["code"] == "synthesis.path_far"]
    s = example_results["synthesis"]
    assert "warnings" not in s                          # the section's keys as before
    ext = float(np.max(np.ptp(np.asarray(s["points"]), axis=0)))
    assert s["max_deviation"] < 0.01 * ext              # far below the limit (5 %)


def test_random_points_far_from_the_curve_warn():
    # the student's trial: 20 random points over 2 m; before, a largest deviation of ~0.4 m passed silently
    from tmm_cli.messages import localize
    rng = np.random.default_rng(7)
    P = (rng.random((20, 2)) * 2.0).round(3).tolist()
    r = run(load_task({"schema": "tmm/1", "synthesis": {"type": "path", "points": P},
                       "drive": {"link": "crank", "speed": 6}}))
    far = [m for m in r["messages"] if m["code"] == "synthesis.path_far"]
    assert len(far) == 1 and far[0]["text"] in r["warnings"]
    s = r["synthesis"]
    ext = float(np.max(np.ptp(np.asarray(P), axis=0)))
    assert s["max_deviation"] > 0.05 * ext
    assert far[0]["params"]["dev"] == pytest.approx(s["max_deviation"], rel=1e-15)
    assert far[0]["params"]["point"] == int(np.argmax(s["deviations"])) + 1
    for lang in ("ru", "uk"):                           # catalogued: no English left
        text = localize(far[0], lang)
        assert "coupler" not in text and "`max_deviation`" in text


def _search_counted(monkeypatch):
    """synthesis_path.search replaced by a stand-in that counts its calls and answers as a
    search does -- (x: 10 float64, phi: one per point, e: a float) -- with values made from the
    points that a kept copy must give back bit for bit (a negative zero, a subnormal, the last
    bits of a long fraction); this run's memory of answers emptied. (The kept answers' tests
    are about keeping, not about searching: the real search is test_reproducible's.)"""
    from tmm_cli.linkage import synthesis_path as S
    calls = []

    def stand_in(T, gamma_min, seed=S.SEED):
        calls.append((T, gamma_min, seed))
        rng = np.random.default_rng(abs(hash((np.asarray(T).tobytes(), gamma_min, seed))))
        x = rng.normal(size=10)
        x[3], x[7] = -0.0, 5e-324
        return x, rng.uniform(0, 2 * np.pi, len(T)), float(rng.random()) / 3.0
    monkeypatch.setattr(S, "search", stand_in)
    monkeypatch.setattr(S, "_FOUND", {})
    return S, calls


def test_an_answer_kept_on_disk_is_the_searched_one_bit_for_bit(tmp_path, monkeypatch):
    """A second run (a new process: its memory of answers empty) reads the answer the first
    kept in TMM_CACHE_DIR instead of searching: the same arrays, bit for bit, and the same
    results; TMM_CACHE_DIR=off searches and keeps nothing."""
    S, calls = _search_counted(monkeypatch)
    monkeypatch.setenv(S.CACHE_ENV, str(tmp_path))
    T = np.array(load_task(ROOT / "tasks" / "synthesis_path.yaml").synthesis.points, float)
    first = S.searched(T, 30.0)
    assert len(calls) == 1 and len(list((tmp_path / "path-synthesis").glob("*.npz"))) == 1
    S._FOUND.clear()
    again = S.searched(T, 30.0)
    assert len(calls) == 1                                             # read, not searched
    assert again[0].tobytes() == first[0].tobytes() and again[1].tobytes() == first[1].tobytes()
    assert type(again[2]) is float and again[2] == first[2]
    # another limit of the transmission angle is another answer
    S._FOUND.clear()
    S.searched(T, 35.0)
    assert len(calls) == 2
    monkeypatch.setenv(S.CACHE_ENV, "off")
    S._FOUND.clear()
    S.searched(T, 30.0)
    assert len(calls) == 3 and len(list((tmp_path / "path-synthesis").glob("*.npz"))) == 2


def test_a_broken_or_stale_kept_answer_is_searched_again(tmp_path, monkeypatch):
    """A kept file cut short or not an answer is searched again and written anew; an answer
    kept by another version of the search (its stamp: the module's source, numpy's and scipy's
    versions) is never read; a folder that cannot be written costs only the next search."""
    S, calls = _search_counted(monkeypatch)
    monkeypatch.setenv(S.CACHE_ENV, str(tmp_path))
    T = np.array([[0.0, 0.0], [1.0, 0.2], [1.5, 1.0], [0.8, 1.6], [-0.2, 1.0]])
    want = S.searched(T, 30.0)
    (f,) = (tmp_path / "path-synthesis").glob("*.npz")
    for junk in (f.read_bytes()[:40], b"not an answer", b""):
        f.write_bytes(junk)
        S._FOUND.clear()
        got = S.searched(T, 30.0)
        assert got[0].tobytes() == want[0].tobytes()
        assert S._kept(f, len(T))[0].tobytes() == want[0].tobytes()   # written anew
    # files numpy reads whose arrays are not such an answer: searched again too
    n = len(calls)
    for bad in ({"x": want[0], "phi": want[1][:-1], "e": np.float64(want[2])},         # a point short
                {"x": want[0], "phi": want[1], "e": np.complex128(want[2])},          # e not a float
                {"x": np.full(10, np.nan), "phi": want[1], "e": np.float64(want[2])},  # no numbers
                {"x": want[0].astype(np.float32), "phi": want[1], "e": np.float64(want[2])}):
        with open(f, "wb") as fh:
            np.savez(fh, **bad)
        S._FOUND.clear()
        assert S.searched(T, 30.0)[0].tobytes() == want[0].tobytes()
    assert len(calls) == n + 4
    n = len(calls)
    monkeypatch.setattr(S, "_stamp", lambda: b"another version of the search")
    S._FOUND.clear()
    S.searched(T, 30.0)
    assert len(calls) == n + 1 and len(list((tmp_path / "path-synthesis").glob("*.npz"))) == 2
    (tmp_path / "file").write_text("x")
    monkeypatch.setenv(S.CACHE_ENV, str(tmp_path / "file"))        # its folder cannot be made
    S._FOUND.clear()
    assert S.searched(T, 30.0)[0].tobytes() == want[0].tobytes()


def test_no_linkage_found_is_kept_too(tmp_path, monkeypatch):
    """A search that finds no linkage (None) is kept as such: the next run says the same
    without searching."""
    S, calls = _search_counted(monkeypatch)
    monkeypatch.setenv(S.CACHE_ENV, str(tmp_path))
    monkeypatch.setattr(S, "_stamp", lambda: b"a search that finds nothing")
    monkeypatch.setattr(S, "search", lambda *a, **k: (calls.append(a), None)[1])
    T = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [4.0, 0.1]])
    assert S.searched(T, 30.0) is None
    S._FOUND.clear()
    assert S.searched(T, 30.0) is None and len(calls) == 1


def test_kept_answers_are_told_apart_by_points_and_by_the_searchs_version(tmp_path, monkeypatch):
    """Two sets of points, two files; the same points under another source of the search
    module, or another numpy or scipy, another file (the stamp: the module's source as
    imported, the versions this process runs)."""
    import scipy

    S, calls = _search_counted(monkeypatch)
    monkeypatch.setenv(S.CACHE_ENV, str(tmp_path))
    A = np.array([[0.0, 0.0], [1.0, 0.2], [1.5, 1.0], [0.8, 1.6], [-0.2, 1.0]])
    B = A.copy()
    B[2, 1] += 1e-9
    names = {S._cache_file(A, 30.0, S.SEED).name, S._cache_file(B, 30.0, S.SEED).name,
             S._cache_file(A, 30.0, S.SEED + 1).name}
    assert len(names) == 3
    stamp = S._stamp().decode()
    assert stamp.split("|")[:3] == [S._SOURCE, np.__version__, scipy.__version__]
    import hashlib
    assert S._SOURCE == hashlib.sha256(Path(S.__file__).read_bytes()).hexdigest()
    try:
        monkeypatch.setattr(S, "_SOURCE", "0" * 64)           # the module edited
        S._stamp.cache_clear()
        edited = S._cache_file(A, 30.0, S.SEED).name
        monkeypatch.setattr(np, "__version__", "0.0")           # and another numpy
        S._stamp.cache_clear()
        assert len(names | {edited, S._cache_file(A, 30.0, S.SEED).name}) == 5
    finally:
        monkeypatch.undo()
        S._stamp.cache_clear()                                  # this process's own again
