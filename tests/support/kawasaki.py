"""A Kawasaki RS007N 2.7e-8 from its spherical wrist: the general 6R's hard case.

The one failure of the perturbed-arm audits (docs/ik-audit.md), held by the tests of the
general 6R's alternates and of its proof of unreachability.
"""

from __future__ import annotations

import numpy as np

import kinematica as km
from kinematica.dh.joints import Revolute

#: The Kawasaki RS007N of tests/data/makers (kawasaki_rs007n.urdf) as ``robot.to_dh()``
#: gives it (standard convention), every d, a and α moved by ±ε, ε = 2.6688060984301035e-08:
#: perturbed arm #104 of seed 4 of ``benchmarks/audit_makers.py --arms kawasaki_rs007n
#: --poses 0 --perturbed 105 --perturbed-poses 10 --numeric 0 --seed 4``; rows (d, a, α, θ0).
ROWS = (
    (2.6688060984301035e-08, -2.6688060984301035e-08, 1.5707963001068355, -1.5707963267948966),
    (2.6688060984301035e-08, 0.35500002668806097, 3.141592626901732, -1.5707963267948966),
    (-2.6688060984301035e-08, 2.6688060984301035e-08, 1.5707963001068355, 1.5707963267948966),
    (0.375000026688061, 2.6688060984301035e-08, -1.5707963001068355, 0.0),
    (2.6688060984301035e-08, 2.6688060984301035e-08, 1.5707963534829577, 0.0),
    (0.07800002668806098, -2.6688060984301035e-08, 2.6688060984301035e-08, 1.5707963267948966),
)
#: Its base (the tool is the identity).
BASE = ((1.0, 0.0, 0.0, 0.0), (0.0, -1.0, 0.0, 0.0), (0.0, 0.0, -1.0, 0.36), (0.0, 0.0, 0.0, 1.0))
#: The audit's 5th pose of that arm: the configuration that made it (σmin/σmax 1.1e-4).
Q_GEN = (
    -2.6945290346991,
    -2.3261842550000775,
    1.5747727446732322,
    0.32600734513149865,
    2.0179896792214285,
    1.6181778883127667,
)

#: A target of that arm no labelling reaches (an FK position, a random orientation): the
#: chosen labelling's pencil there has A2's reciprocal condition 6.3e-4.
UNREACHED = (
    (0.1932430292812577, 0.12898802778309998, 0.9726351938537023, -0.26701614047858),
    (0.69996244125036, -0.7127894032385291, -0.04454040266654119, 0.039937121647117296),
    (0.6875388806991494, 0.689415227072544, -0.22802835834052093, -0.3685225533729993),
    (0.0, 0.0, 0.0, 1.0),
)


def perturbed() -> km.Robot:
    """The perturbed Kawasaki RS007N (ROWS, BASE)."""
    rows = [Revolute(d=d, a=a, alpha=al, offset=th) for d, a, al, th in ROWS]
    return km.Robot.from_dh(rows, convention="standard", base=np.array(BASE))
