"""Test-suite settings: property tests are reproducible run to run.

Every hypothesis test draws its examples from a fixed seed (``derandomize``)
and keeps no example database in the repository: a failure in CI is a
failure here, on the same examples.
"""

from hypothesis import settings

settings.register_profile("kinematica", derandomize=True, database=None, deadline=None)
settings.load_profile("kinematica")
