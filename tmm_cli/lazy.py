"""Heavy scientific imports on first use (scipy.optimize costs ~0.3 s to import,
which `tmm validate` and JSON-only runs should not pay unless they need it)."""
from __future__ import annotations


def brentq(*args, **kwargs):
    """scipy.optimize.brentq, imported on first call."""
    from scipy.optimize import brentq as _brentq
    return _brentq(*args, **kwargs)
