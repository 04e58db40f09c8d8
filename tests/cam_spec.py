"""A cam task section for the cam stage tests, as the stage reads it (SI, degrees)."""
from types import SimpleNamespace as NS


def spec(**kw):
    d = dict(follower="translating", stroke=0.03, rocker_length=None, offset=0.0,
             phases=NS(rise=90, far_dwell=30, return_=90, near_dwell=150),
             laws=NS(rise="cosine", return_="cosine"), pressure_angle=NS(rise=30, return_=30),
             swing="auto", roller="auto", rotation="ccw", speed=None)
    d.update(kw)
    return NS(**d)
