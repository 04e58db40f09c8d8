"""Test configuration: hypothesis runs derandomized, so CI sees the same examples on
every run (a property test must not pass or fail by the luck of the draw); set
HYPOTHESIS_PROFILE=explore locally to search with fresh random examples."""
import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
