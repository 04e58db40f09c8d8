"""A cam task section for the cam stage tests, built and validated by the task model."""
from task_sections import fields, section

__all__ = ["fields", "section", "spec"]


def spec(**kw):
    """The task's ``cam`` section: a central translating roller follower, cosine laws, phases
    90/30/90/150 deg, 30 deg allowed, unless ``kw`` says otherwise."""
    d = dict(follower="translating", stroke=0.03, offset=0.0,
             phases=fields(rise=90, far_dwell=30, return_=90, near_dwell=150),
             laws=fields(rise="cosine", return_="cosine"), pressure_angle=fields(rise=30, return_=30),
             swing="auto", roller="auto", rotation="ccw")
    d.update({k: v for k, v in kw.items() if v is not None})
    return section("cam", d)
