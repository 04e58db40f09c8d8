"""Benchmark: cam synthesis (exact smallest cam) plus the 1-degree profile.

Target (issue 5): under 50 ms per cam, synthesis + profile + results dict.
Run:  python benchmarks/bench_cam.py      (median of 20 runs per case)
"""
from __future__ import annotations

import statistics
import time
from types import SimpleNamespace as NS

from tmm_cli.cam import synthesize

TARGET = 0.050


def spec(**kw):
    d = dict(follower="translating", stroke=0.03, rocker_length=None, offset=0.0,
             phases=NS(rise=90, far_dwell=30, return_=90, near_dwell=150),
             laws=NS(rise="cosine", return_="cosine"), pressure_angle=NS(rise=30, return_=30),
             swing="auto", roller="auto", rotation="ccw", speed=10.0)
    d.update(kw)
    return NS(**d)


CASES = {
    "translating, central": spec(),
    "translating, offset auto": spec(offset="auto", laws=NS(rise="sine", return_="poly345"),
                                     pressure_angle=NS(rise=25, return_=40)),
    "rocker, swing given": spec(follower="rocker", stroke=20.0, rocker_length=0.1, swing="with",
                                pressure_angle=NS(rise=40, return_=50)),
    "rocker, swing auto (two solves)": spec(follower="rocker", stroke=20.0, rocker_length=0.1,
                                            pressure_angle=NS(rise=40, return_=50)),
}


def main() -> None:
    synthesize(spec())            # warm-up (imports)
    print(f"{'case':34s} {'median, ms':>11s} {'target, ms':>11s}")
    for name, sp in CASES.items():
        times = []
        for _ in range(20):
            t0 = time.perf_counter()
            synthesize(sp).to_dict()
            times.append(time.perf_counter() - t0)
        t = statistics.median(times)
        print(f"{name:34s} {t * 1000:11.1f} {TARGET * 1000:11.0f}  {'ok' if t <= TARGET else 'SLOW'}")


if __name__ == "__main__":
    main()
