"""What the tests share: reference computations, random robots, arms and files to test on.

``ROOT`` is the repository, ``DATA`` the tests' own files (``tests/data``): every
test finds a file through them, whatever folder it lives in.
"""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
