"""Kinematic calibration: fit an arm's parameters to measured tool poses or points.

A real arm is never its nominal table. :func:`calibrate` fits the parameters of an
error model that stays well-conditioned on any arm (a small rigid transform in every
link, named after the DH values it changes and Hayati's β, see
:mod:`kinematica.calibration.model`) to joint readings and measured poses or points,
says which parameters the measurements determine and why the others are left out,
and returns the calibrated robot (exact, with every IK solution as any kinematica
robot) with its URDF and DH table. :func:`next_poses` plans the measurements,
:func:`simulate` makes them for teaching and testing. Needs the ``calibration``
extra (scipy)::

    import kinematica as km
    from kinematica import calibration

    res = calibration.calibrate(km.load("puma560"), q, measured, kind="pose")
    res.robot.ik(T)           # every solution on the calibrated arm
    res.undetermined          # what the data cannot see, and why
"""

from kinematica.calibration.checks import ROTATION_TOL
from kinematica.calibration.fit import (
    DEFAULT_NOISE,
    LOSSES,
    OUTLIER_LIMIT,
    ROBUST_KNEE,
    CalibrationResult,
    ParameterRow,
    calibrate,
    identifiable,
)
from kinematica.calibration.identify import (
    CORRELATION_LIMIT,
    RANK_RTOL,
    REASON_SHARE,
    Finding,
    Identification,
)
from kinematica.calibration.model import ErrorModel
from kinematica.calibration.plan import next_poses, simulate

__all__ = [
    "CORRELATION_LIMIT",
    "DEFAULT_NOISE",
    "LOSSES",
    "OUTLIER_LIMIT",
    "RANK_RTOL",
    "REASON_SHARE",
    "ROBUST_KNEE",
    "ROTATION_TOL",
    "CalibrationResult",
    "ErrorModel",
    "Finding",
    "Identification",
    "ParameterRow",
    "calibrate",
    "identifiable",
    "next_poses",
    "simulate",
]
