"""The pruned planetary search gives exactly the rows of the full enumeration (every
(z1, z2, z3) of the grid checked against every condition), in the same order, on many
random cases; the truncated ranking equals the head of the full ranking."""
from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tmm_cli.gears import planetary as P

case = st.fixed_dictionaries({
    "scheme": st.sampled_from("ABCD"),
    "req": st.one_of(st.floats(-40.0, 40.0, allow_nan=False).filter(lambda r: abs(r) > 1e-3),
                     st.sampled_from([0.1, 0.5, 1.0, 2.0, 3.24, -2.24, 12.0, 1e-6, -1e6])),
    "tol": st.sampled_from([0.0, 1e-9, 0.001, 0.01, 0.05, 0.3, 1e6]),
    "k": st.integers(1, 7),
    "z_max": st.integers(15, 110),
    "ext": st.integers(8, 30),
    "ring": st.integers(20, 95),
    "sat": st.integers(8, 30),
    "diff": st.integers(1, 12),
    "rank": st.sampled_from(P.RANKS),
})


@settings(max_examples=250, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(case)
def test_pruned_search_is_the_full_enumeration(c):
    lim = P.Limits(external=c["ext"], internal=c["ring"], satellite_in_internal=c["sat"], difference=c["diff"])
    args = (c["scheme"], c["req"], c["tol"], c["k"], lim, c["z_max"], c["rank"])
    full = P._candidates(*args, prune=False)
    fast = P._candidates(*args)
    assert fast.dtype.kind == "i" and np.array_equal(fast, full)
    for top in (1, 3, 10):
        head, best = P._candidates(*args, top=top, best=True)
        assert np.array_equal(head, full[:top])
        if len(full):
            want = float(np.min(np.abs(P.ratios_of(c["scheme"], full) - c["req"])) / abs(c["req"]))
            assert best == want
        else:
            assert best is None


def test_pruned_search_at_z_max_300_equals_the_full_one():
    """The README's cases at z_max = 300 (one full enumeration each: a few seconds)."""
    lim = P.Limits()
    for scheme, req in (("B", 12.0), ("C", -2.24), ("D", 0.1), ("C", 0.3)):
        a = P._candidates(scheme, req, 0.05, 3, lim, 300)
        b = P._candidates(scheme, req, 0.05, 3, lim, 300, prune=False)
        assert len(a) > 0 and np.array_equal(a, b)
