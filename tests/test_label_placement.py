"""figures.place_labels (every label of the report's drawings and the drawing sheets)
against the one-anchor-at-a-time placement it replaced (below, as it was): the same
place for every label, and the same boxes added to the caller's ``taken``, on random
layouts (hypothesis) -- points, segments, slider boxes, taken boxes, bounds, preferred
directions, NaN coordinates -- and on every task of tasks/ (test_every_task)."""
from __future__ import annotations

import copy
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tmm_cli.report import figures
from tmm_cli.report.figures import _DIRS, _admissible, _clear_of_boxes, _MULTS, _candidates


class _Segments:
    """figures._Segments as it was (the points along the first axis, the segments along the
    second; the module's now runs the other way round): the reference's own."""

    def __init__(self, segs):
        a, b = segs[:, 0], segs[:, 1]
        d = b - a
        self.ax, self.ay = a[:, 0], a[:, 1]
        self.dx, self.dy = d[:, 0], d[:, 1]
        self.L2 = np.maximum(self.dx * self.dx + self.dy * self.dy, 1e-300)

    def dists(self, cx, cy):
        rx = cx[:, None] - self.ax
        ry = cy[:, None] - self.ay
        t = rx * self.dx
        t += ry * self.dy
        t /= self.L2
        np.minimum(np.maximum(t, 0.0, out=t), 1.0, out=t)
        rx -= self.dx * t
        ry -= self.dy * t
        rx *= rx
        ry *= ry
        rx += ry
        return np.sqrt(rx.min(axis=1))


def _point_dists(cx, cy, px, py):
    """figures._point_dists as it was (the reference's own)."""
    dx = cx[:, None] - px
    dy = cy[:, None] - py
    dx *= dx
    dy *= dy
    dx += dy
    return np.sqrt(dx.min(axis=1))


def _reference(anchors, extent: float, avoid=(), step: float | None = None, segments=None,
                 boxes=(), sizes=None, taken=(), bounds=None):
    """figures.place_labels as it was before the anchors were batched (one anchor at a
    time, every distance computed for the admissible candidates only)."""
    if step is None:
        step = 0.045 * extent
    avoid_a = np.asarray([np.asarray(a, float) for a in avoid], float).reshape(-1, 2)
    avx, avy = avoid_a[:, 0].copy(), avoid_a[:, 1].copy()
    if isinstance(segments, figures._Segments):
        # made once by figures.segment_set for several calls (a panel's letters and force
        # names): the same parts, as the reference lays them out
        seg = _Segments.__new__(_Segments)
        seg.ax, seg.ay, seg.dx, seg.dy, seg.L2 = (v[:, 0] for v in (segments.ax, segments.ay, segments.dx,
                                                                     segments.dy, segments.L2))
    else:
        segs = np.asarray(segments, float).reshape(-1, 2, 2) if segments is not None and len(segments) else None
        seg = _Segments(segs) if segs is not None else None
    offs, offx, offy, ring, dirs = _candidates(step, sizes is not None)
    taken = taken if isinstance(taken, list) else list(taken)
    # the taken boxes as centres and half sizes (x, y), grown as labels are placed
    tb = np.asarray(taken, float).reshape(-1, 4)
    nt = len(tb)
    tcx, tcy, thx, thy = np.empty((4, nt + (len(anchors) if sizes is not None else 0)))
    tcx[:nt], tcy[:nt] = (tb[:, 0] + tb[:, 2]) / 2, (tb[:, 1] + tb[:, 3]) / 2
    thx[:nt], thy[:nt] = (tb[:, 2] - tb[:, 0]) / 2, (tb[:, 3] - tb[:, 1]) / 2
    box_tests = [(np.asarray(bc, float), np.asarray(bu, float), np.array([-bu[1], bu[0]], float), hw, hh)
                 for (bc, bu, hw, hh) in boxes]
    plx, ply = np.empty((2, len(anchors)))
    out = []
    big = 9 * step
    ncand = len(offx)
    every = np.arange(ncand)
    lim_l, lim_a, lim_s = 2.2 * step, 1.2 * step, 0.8 * step
    n_near = len(_DIRS) * len(_MULTS)          # the nearer rings' candidates come first
    # the most a candidate of a farther ring can score (without the preferred direction's
    # term), with a margin for rounding
    far_top = lim_l + lim_a + lim_s - float(ring[n_near]) + 1e-9 * step if n_near < ncand else np.inf
    if bounds is not None:
        bx0, by0, bx1, by1 = bounds
    for k_a, (x, y, pref) in enumerate(anchors):
        # the candidates x + offx, y + offy (the same sums as (x, y) + offs)
        cx, cy = x + offx, y + offy
        ok = _clear_of_boxes(x, y, offs, box_tests, step)
        half = None
        if sizes is not None:
            half = True
            h0, h1 = float(sizes[k_a][0]) / 2, float(sizes[k_a][1]) / 2
            if nt:
                free = ~((np.abs(cx[:, None] - tcx[:nt]) < h0 + thx[:nt])
                         & (np.abs(cy[:, None] - tcy[:nt]) < h1 + thy[:nt])).any(axis=1)
                if bounds is not None:
                    free &= (cx - h0 >= bx0) & (cx + h0 <= bx1) & (cy - h1 >= by0) & (cy + h1 <= by1)
            elif bounds is not None:
                free = (cx - h0 >= bx0) & (cx + h0 <= bx1) & (cy - h1 >= by0) & (cy + h1 <= by1)
            else:
                free = None
            ok = _admissible(ok, free)
        if ok is None:
            idx, sx, sy = every, cx, cy
        else:
            idx = ok.nonzero()[0]
            sx, sy = cx[idx], cy[idx]
        best = None
        n_ok = len(idx)
        if n_ok:
            lean = None
            if pref is not None:
                n = math.hypot(*pref)
                if n > 0:
                    lean = 0.5 * step * (dirs[idx] @ (np.asarray(pref, float) / n))

            def scores(hi):
                # each candidate's score depends on that candidate alone: the first hi
                # score as in the whole
                qx, qy = sx[:hi], sy[:hi]
                dl = _point_dists(qx, qy, plx[:k_a], ply[:k_a]) if k_a else np.full(hi, big)
                da = _point_dists(qx, qy, avx, avy) if len(avx) else np.full(hi, big)
                ds = seg.dists(qx, qy) if seg is not None else np.full(hi, np.inf)
                sc = np.minimum(dl, lim_l) + np.minimum(da, lim_a) + np.minimum(ds, lim_s) - ring[idx[:hi]]
                return sc if lean is None else sc + lean[:hi]

            # the nearer rings first: when one of them scores above the most a farther
            # one can, the farther ones are not scored (the same choice: the first best)
            score = None
            n_in = n_ok if n_near >= ncand else (n_near if ok is None else int(np.count_nonzero(ok[:n_near])))
            if 0 < n_in < n_ok:
                near = scores(n_in)
                if near.max() > (far_top if lean is None else far_top + 0.5 * step):
                    score = near
            if score is None:
                score = scores(n_ok)
            k = int(score.argmax())
            if math.isfinite(score[k]):
                best = (float(sx[k]), float(sy[k]))
        if best is None:
            b = np.array([x, y], float) + _DIRS[4] * step * 2.5
            best = (float(b[0]), float(b[1]))
        plx[k_a], ply[k_a] = best
        if half is not None:
            box = (best[0] - h0, best[1] - h1, best[0] + h0, best[1] + h1)
            taken.append(box)
            tcx[nt], tcy[nt] = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
            thx[nt], thy[nt] = (box[2] - box[0]) / 2, (box[3] - box[1]) / 2
            nt += 1
        out.append(best)
    return out




coord = st.floats(-50, 50, allow_nan=False)
grid = st.integers(-20, 20).map(lambda k: k * 2.5)          # on a grid: ties and touching boxes
num = st.one_of(coord, grid)
point = st.tuples(num, num)
pref = st.one_of(st.none(), st.tuples(st.floats(-1, 1), st.floats(-1, 1)), st.just((0.0, 0.0)))


@st.composite
def layouts(draw):
    n = draw(st.integers(1, 12))
    anchors = [(x, y, draw(pref)) for x, y in draw(st.lists(point, min_size=n, max_size=n))]
    if draw(st.booleans()) and draw(st.integers(0, 9)) == 0:
        k = draw(st.integers(0, n - 1))
        anchors[k] = (math.nan, anchors[k][1], anchors[k][2])
    step = draw(st.sampled_from([1.6, 2.5, 2.6, 3.6, draw(st.floats(0.5, 6))]))
    kw = {"avoid": draw(st.lists(point, max_size=8)), "step": step}
    if draw(st.booleans()):
        kw["segments"] = [(p, q) for p, q in draw(st.lists(st.tuples(point, point), max_size=12))]
    if draw(st.booleans()):
        kw["boxes"] = [(np.array(c, float), np.array([math.cos(a), math.sin(a)]), hw, hh)
                       for c, a, hw, hh in draw(st.lists(st.tuples(point, st.floats(0, 6.3), st.floats(0.5, 5),
                                                                    st.floats(0.5, 3)), max_size=3))]
    if draw(st.booleans()):
        kw["sizes"] = [(draw(st.sampled_from([2.0, 3.2, 4.4, draw(st.floats(0.5, 12))])),
                        draw(st.sampled_from([2.9, draw(st.floats(0.5, 5))]))) for _ in range(n)]
        if draw(st.booleans()):
            kw["taken"] = [(x, y, x + w, y + h) for (x, y), w, h in
                           draw(st.lists(st.tuples(point, st.floats(0, 30), st.floats(0, 10)), max_size=6))]
        if draw(st.booleans()):
            x0, y0 = draw(point)
            kw["bounds"] = (x0, y0, x0 + draw(st.floats(5, 120)), y0 + draw(st.floats(5, 90)))
    return anchors, kw


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(layouts())
def test_same_places_as_one_anchor_at_a_time(layout):
    anchors, kw = layout
    kw_ref = copy.deepcopy(kw)
    with warnings.catch_warnings():
        # no warning either (numpy's deprecation of a positional out for np.minimum was
        # one, silenced but costly: each warning looks up its line, ~50k instructions)
        warnings.simplefilter("error")
        got = figures.place_labels(anchors, 60.0, **kw)
    want = _reference(anchors, 60.0, **kw_ref)
    assert repr(got) == repr(want)                        # (NaN as NaN: a NaN anchor's place)
    assert repr(kw.get("taken")) == repr(kw_ref.get("taken"))     # the boxes appended for the caller


def test_taken_list_is_extended_in_place():
    taken = [(0.0, 0.0, 1.0, 1.0)]
    pos = figures.place_labels([(0.0, 0.0, None), (0.5, 0.5, (1.0, 0.0))], 60.0, step=2.0,
                               sizes=[(2.0, 1.0), (3.0, 1.0)], taken=taken)
    assert len(taken) == 3
    for (x, y), (w, h), box in zip(pos, [(2.0, 1.0), (3.0, 1.0)], taken[1:]):
        assert box == (x - w / 2, y - h / 2, x + w / 2, y + h / 2)
    assert figures.place_labels([], 60.0) == []


TASKS = sorted(p.stem for p in (Path(__file__).resolve().parents[1] / "tasks").glob("*.yaml"))


# one test per task and language (each a report or sheets of its own: the suite's workers
# share them out instead of one worker rendering all 31 reports in a row)
_CASES = ([("en", t, ("html",)) for t in TASKS]
          + [("en", t, ("sheets",)) for t in ["forging_sixbar", "synthesis_shaper", "gears_shifted"]]
          + [("ru", t, ("html", "sheets")) for t in ["forging_sixbar", "shaper_slotted_lever"]]
          + [("uk", t, ("html", "sheets")) for t in ["compressor_v_twin", "press_drive_train"]])


# the reports that place no label (a cam's, a gear pair's, a planetary or differential
# train's, an impact rotor's): the others place from 26 to 197 in their report
_UNLABELLED = ("cam_", "gears_", "planetary_", "differential_", "impact_")


@pytest.mark.parametrize("lang, task, formats", _CASES, ids=[f"{lg}-{t}-{'+'.join(f)}" for lg, t, f in _CASES])
def test_tasks(lang, task, formats, tmp_path, monkeypatch, shared_once):
    """Every call the reports and the drawing sheets of the tasks make: the same places
    (every task's report and sheets in en, ru and uk were checked so when the anchors were
    batched: 6462 calls, 37,821 labels).  The English reports' calls as `tmm run --format
    html,pdf` made them (recorded once per test session: tests/pdf_extent.py), the others'
    as made here."""
    if formats == ("html",):
        from pdf_extent import recorded
        calls = recorded(shared_once, task, lang)["placements"]
    else:
        from figure_record import record_placements
        from tmm_cli import orchestrate
        monkeypatch.setenv("TMM_REPORT_JOBS", "1")
        calls = record_placements(monkeypatch)
        root = Path(__file__).resolve().parents[1] / "tasks"
        orchestrate.process(root / f"{task}.yaml", tmp_path / task, set(formats), lang)
    for anchors, extent, kw, got, taken in calls:
        kw_ref = copy.deepcopy(kw)
        assert got == _reference(anchors, extent, **kw_ref)
        assert taken == kw_ref.get("taken")
    if formats == ("html",) and task.startswith(_UNLABELLED):
        return              # a report with no labelled plan or polygon: any call it makes is compared all the same
    assert len(calls) > (0 if task == "gears_shifted" else 3)       # a gear sheet: one labelled drawing


def test_segment_set_has_the_parts_of_the_segments():
    """figures.segment_set (made once for several calls) holds the parts the reference
    computes from the segments themselves; none for no segments; given back as it is."""
    rng = np.random.default_rng(5)
    segs = rng.normal(size=(7, 2, 2)) * 40
    got, ref = figures.segment_set(segs.tolist()), _Segments(segs)
    for name in ("ax", "ay", "dx", "dy", "L2"):
        assert np.array_equal(getattr(got, name)[:, 0], getattr(ref, name))
    cx, cy = rng.normal(size=(2, 50)) * 40
    assert np.array_equal(got.dists(cx, cy), ref.dists(cx, cy))
    assert figures.segment_set([]) is None and figures.segment_set(None) is None
    assert figures.segment_set(got) is got
