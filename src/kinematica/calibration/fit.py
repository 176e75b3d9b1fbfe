"""``calibrate``: fit a robot's kinematic parameters to measured tool poses or points.

The parameters are those of the error model (:mod:`kinematica.calibration.model`);
the ones the measurements can determine are found from the analytic identification
Jacobian at the nominal arm (:mod:`kinematica.calibration.identify`) and fitted by
scipy's ``least_squares`` with the analytic Jacobian (Levenberg-Marquardt for the
plain loss, trust-region reflective for the robust ones, named as scipy names them);
the others stay at their nominal values and are reported with their reason. Standard
errors come from the covariance ``σ² (JᵀJ)⁻¹`` at the solution, ``σ²`` the residual
variance ``2 · cost / (rows − parameters)``.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_choice
from kinematica.calibration.checks import (
    check_kind,
    check_measured,
    check_noise,
    check_readings,
)
from kinematica.calibration.export import calibrated_extraction, calibrated_urdf
from kinematica.calibration.identify import (
    Finding,
    Identification,
    correlated_pairs,
    identify,
    preference,
)
from kinematica.calibration.model import ErrorModel
from kinematica.calibration.residuals import Kind, Measurements, jacobian, pose_errors, residuals
from kinematica.errors import ArgumentError, KinematicaError

if TYPE_CHECKING:
    from kinematica.robot import DHExtraction, Robot

__all__ = [
    "DEFAULT_NOISE",
    "GENERIC_POSES",
    "LOSSES",
    "OUTLIER_LIMIT",
    "ROBUST_KNEE",
    "CalibrationResult",
    "ParameterRow",
    "calibrate",
    "identifiable",
]

FloatArray = NDArray[np.float64]

#: The measurement noise the residuals are divided by when none is given: 10 µm and
#: 10 µrad, a laser tracker's order. Only its ratio and a robust loss's knee depend on
#: it: the variance behind the standard errors is estimated from the residuals.
DEFAULT_NOISE = (1e-5, 1e-5)
#: A robust loss's knee (scipy's ``f_scale``), in standard deviations of the noise.
ROBUST_KNEE = 3.0
#: A measurement with a residual beyond this many robust standard deviations (1.4826
#: times the median absolute residual, of positions and orientations apart, and at least
#: the noise given) after the fit is reported as an outlier.
OUTLIER_LIMIT = 5.0
#: scipy ``least_squares``' losses.
LOSSES = ("linear", "soft_l1", "huber", "cauchy", "arctan")
#: Configurations (seeded, within the limits) from which the parameters a rich set of
#: measurements would determine are found: far more than any arm's count needs.
GENERIC_POSES = 64
#: The stopping tolerances handed to ``least_squares`` (ftol, xtol, gtol): far below what
#: noise of 1e-6 of the arm's size can tell.
FIT_TOL = 1e-12


@dataclass(frozen=True)
class ParameterRow:
    """One parameter of the error model, as fitted.

    Attributes:
        name: ``theta2``, ``beta3``, ``base_z``, ``tool_rx``...
        angle: True for an angle (rad), False for a length (m).
        nominal: The nominal value (the DH value it stands for; 0 for β, base, tool).
        calibrated: ``nominal + correction``.
        correction: The fitted change (0 when not fitted).
        std_error: Its standard error, NaN when not fitted.
        fitted: True when the data determined it.
    """

    name: str
    angle: bool
    nominal: float
    calibrated: float
    correction: float
    std_error: float
    fitted: bool


@dataclass(frozen=True, eq=False)
class CalibrationResult:
    """What :func:`calibrate` found.

    Attributes:
        robot: The calibrated robot: it computes with the fitted transforms
            (exactly) and carries the DH table the DH rules read off its axes.
        nominal: The robot calibrated.
        dh: The DH extraction of the calibrated arm (``dh.robot``: the table alone,
            ``dh.fk_error``: how far it is from the calibrated arm).
        urdf: The calibrated arm as URDF text (reads back exactly).
        kind: ``"pose"`` or ``"position"``.
        loss: The loss used.
        noise: ``(σ_position (m), σ_orientation (rad))`` the residuals were divided by.
        parameters: Every parameter of the model (:class:`ParameterRow`).
        identification: Rank, chosen basis, reasons, singular values.
        generic_count: How many parameters a rich set of measurements of this kind
            determines (Everett, Driels and Mooring: 4R + 2P + 6 for poses, + 3 for points).
        correlated: ``(a, b, correlation)`` of fitted pairs beyond
            :data:`~kinematica.calibration.identify.CORRELATION_LIMIT`.
        covariance: ``(r, r)`` of the fitted parameters (SI units).
        sigma: The estimated noise in units of ``noise`` (1 when it was right).
        before: ``(m, 2)`` each measurement's position error (m) and rotation
            error (rad, NaN for points) with the nominal arm.
        after: ``(m, 2)`` the same with the calibrated arm.
        outliers: Indices of the measurements whose residual after the fit lies
            beyond :data:`OUTLIER_LIMIT` robust standard deviations.
        evaluations: Model evaluations the fit took.
    """

    robot: Robot
    nominal: Robot
    dh: DHExtraction
    urdf: str = field(repr=False)
    kind: str
    loss: str
    noise: tuple[float, float]
    parameters: tuple[ParameterRow, ...] = field(repr=False)
    identification: Identification = field(repr=False)
    generic_count: int
    correlated: tuple[tuple[str, str, float], ...]
    covariance: FloatArray = field(repr=False)
    sigma: float
    before: FloatArray = field(repr=False)
    after: FloatArray = field(repr=False)
    outliers: NDArray[np.intp] = field(repr=False)
    evaluations: int

    @property
    def rank(self) -> int:
        """The identification Jacobian's rank at the nominal arm for these measurements."""
        return self.identification.rank

    @property
    def fitted(self) -> tuple[str, ...]:
        """The names of the fitted parameters."""
        return tuple(p.name for p in self.parameters if p.fitted)

    @property
    def undetermined(self) -> tuple[Finding, ...]:
        """The parameters the measurements cannot determine, each with its reason."""
        return self.identification.left_out

    @property
    def condition(self) -> float:
        """Condition number of the fitted parameters' (column-normalised) Jacobian."""
        return self.identification.condition

    @property
    def observability(self) -> dict[str, float]:
        """Sun and Hollerbach's O1..O5 of the fitted parameters (see ``identify``)."""
        return self.identification.observability(self.before.shape[0])

    def rms(self, after: bool = True, *, inliers: bool = False) -> tuple[float, float]:
        """``(position (m), orientation (rad))`` RMS errors over the measurements.

        Args:
            after: With the calibrated arm (else the nominal one).
            inliers: Over the measurements that are not :attr:`outliers` only.
        """
        e = self.after if after else self.before
        if inliers:
            e = np.delete(e, self.outliers, axis=0)
        return float(np.sqrt(np.mean(e[:, 0] ** 2))), float(np.sqrt(np.mean(e[:, 1] ** 2)))

    def max(self, after: bool = True) -> tuple[float, float]:
        """``(position (m), orientation (rad))`` largest errors over the measurements."""
        e = self.after if after else self.before
        return float(e[:, 0].max()), float(e[:, 1].max())

    def value(self, name: str) -> ParameterRow:
        """The row of parameter ``name``."""
        for p in self.parameters:
            if p.name == name:
                return p
        raise ArgumentError(f"no parameter {name!r}{_suggest(name, self.parameters)}")


def _suggest(name: str, rows: Sequence[ParameterRow] | Sequence[str]) -> str:
    names = [r if isinstance(r, str) else r.name for r in rows]
    close = difflib.get_close_matches(name, names, n=1)
    return f" (did you mean {close[0]!r}?)" if close else f"; the parameters are {', '.join(names)}"


def _errors(T: FloatArray, data: Measurements) -> FloatArray:
    dp, phi = pose_errors(T, data)
    rot = np.full(len(dp), np.nan) if phi is None else np.linalg.norm(phi, axis=1)
    return np.stack([np.linalg.norm(dp, axis=1), rot], axis=1)


def _outliers(scaled: FloatArray) -> NDArray[np.intp]:
    """The rows of ``scaled (m, k)`` (residuals in units of the noise given) that stand out.

    Position and orientation residuals each have their robust standard deviation
    (1.4826 times their median absolute value), floored at 1 (the noise given): a
    measurement is an outlier when a residual lies beyond :data:`OUTLIER_LIMIT` of them.
    """
    flagged = np.zeros(scaled.shape[0], dtype=bool)
    for part in (scaled[:, :3], scaled[:, 3:]):
        if part.size:
            sd = max(1.4826 * float(np.median(part)), 1.0)
            flagged |= part.max(axis=1) > OUTLIER_LIMIT * sd
    return np.flatnonzero(flagged)


def identifiable(
    robot: Robot, kind: str = "pose", *, params: Sequence[str] | None = None
) -> Identification:
    """Which parameters a rich set of measurements of this kind determines.

    Read from :data:`GENERIC_POSES` configurations spread within the limits (seeded):
    the structural redundancies of the model only, independent of any data.

    Args:
        robot: The robot.
        kind: ``"pose"`` or ``"position"``.
        params: The parameters that may be fitted (default all).

    Returns:
        The :class:`~kinematica.calibration.identify.Identification` (every
        parameter left out is structural).
    """
    kind = check_kind(kind)
    model = ErrorModel.of(robot.chain)
    return _identify(robot, model, kind, _candidates(model, params))


def _candidates(model: ErrorModel, params: Sequence[str] | None) -> NDArray[np.intp]:
    if params is None:
        return np.arange(model.size)
    if isinstance(params, str):
        params = [params]
    index = {n: i for i, n in enumerate(model.names)}
    out = []
    for p in params:
        if p not in index:
            raise ArgumentError(f"params: no parameter {p!r}{_suggest(str(p), model.names)}")
        out.append(index[p])
    if not out:
        raise ArgumentError("params: no parameter to fit")
    return np.array(sorted(set(out)), dtype=np.intp)


def _identify(
    robot: Robot, model: ErrorModel, kind: str, candidates: NDArray[np.intp]
) -> Identification:
    q = robot.random_q(GENERIC_POSES, seed=0)
    T = model.fk(np.zeros(model.size), q)
    data = Measurements(q, T if kind == "pose" else T[:, :3, 3], kind, (1.0, 1.0))  # type: ignore[arg-type]
    _, J = jacobian(model, np.zeros(model.size), data)
    return identify(J, model.names, preference(robot.dof), candidates)


def calibrate(
    robot: Robot,
    q: ArrayLike,
    measured: ArrayLike,
    kind: Kind = "pose",
    *,
    params: Sequence[str] | None = None,
    loss: str = "linear",
    noise: tuple[float, float] = DEFAULT_NOISE,
    convention: str | None = None,
) -> CalibrationResult:
    """Fit a robot's kinematic parameters to measured tool poses or points.

    Args:
        robot: The nominal robot (DH table, URDF, any chain kinematica reads).
        q: ``(m, n)`` the joint readings (rad, m), within the joint limits.
        measured: ``(m, 4, 4)`` measured tool poses or ``(m, 3)`` measured tool
            points (``kind``), in the measuring device's frame (m).
        kind: ``"pose"`` or ``"position"``.
        params: The parameters that may be fitted (names of
            :attr:`ErrorModel.names`: ``theta1``, ``d1``, ``a1``, ``alpha1``,
            ``beta1``, ``y1``..., ``base_x``..., ``tool_rz``); default all. Those
            the data cannot determine stay nominal and are reported.
        loss: scipy ``least_squares``' loss (:data:`LOSSES`); a robust one
            (``"soft_l1"``, ``"huber"``, ``"cauchy"``, ``"arctan"``) with its knee at
            :data:`ROBUST_KNEE` standard deviations of ``noise``.
        noise: ``(σ_position (m), σ_orientation (rad))``: what the residuals are
            divided by (their weights). The standard errors use the variance the
            residuals show, not this.
        convention: Of the calibrated robot's DH table; default the robot's.

    Returns:
        The :class:`CalibrationResult`.

    Raises:
        DimensionError: ``q`` or ``measured`` of the wrong shape, NaN or inf, a
            measured pose that is not rigid.
        ArgumentError: a reading outside its joint's limits, an unknown parameter
            or loss, too few measurements for the parameters (the message says how
            many are needed).
        KinematicaError: scipy is not installed (the ``calibration`` extra).
    """
    kind = check_kind(kind)  # type: ignore[assignment]
    loss = check_choice(loss, "loss", LOSSES)
    sigma_in = check_noise(noise)
    qa = check_readings(robot, q)
    M = check_measured(measured, kind, qa.shape[0])
    try:
        from scipy.optimize import least_squares
    except ImportError:  # pragma: no cover - the test environment has scipy
        raise KinematicaError(
            "calibration needs scipy: pip install 'kinematica[calibration]'"
        ) from None
    model = ErrorModel.of(robot.chain)
    candidates = _candidates(model, params)
    generic = _identify(robot, model, kind, candidates)
    data = Measurements(qa, M, kind, sigma_in)
    rows_needed = len(generic.chosen) + 1
    if data.count * data.per_pose < rows_needed:
        need = math.ceil(rows_needed / data.per_pose)
        raise ArgumentError(
            f"too few measurements: {len(generic.chosen)} parameters of {robot.name} can be "
            f"determined from {kind} measurements (each gives {data.per_pose} numbers), which "
            f"needs at least {need} {kind}s; got {data.count}"
        )
    zero = np.zeros(model.size)
    _, J0 = jacobian(model, zero, data)
    ident = identify(J0, model.names, preference(robot.dof), candidates, generic.chosen)
    free = ident.chosen

    def full(x: FloatArray) -> FloatArray:
        d = zero.copy()
        d[free] = x
        return d

    solution = least_squares(
        lambda x: residuals(model, full(x), data),
        np.zeros(len(free)),
        jac=lambda x: jacobian(model, full(x), data, free)[1],
        method="lm" if loss == "linear" else "trf",
        loss=loss,
        f_scale=ROBUST_KNEE,
        x_scale="jac",
        ftol=FIT_TOL,
        xtol=FIT_TOL,
        gtol=FIT_TOL,
    )
    delta = full(solution.x)
    outliers = _outliers(np.abs(residuals(model, delta, data)).reshape(data.count, -1))
    dof = max(len(solution.fun) - len(free), 1)
    variance = 2.0 * float(solution.cost) / dof
    Jw = solution.jac
    covariance = variance * np.linalg.pinv(Jw.T @ Jw)
    se = np.full(model.size, np.nan)
    se[free] = np.sqrt(np.diag(covariance))
    fitted = np.zeros(model.size, dtype=bool)
    fitted[free] = True
    rows = tuple(
        ParameterRow(
            name=model.names[k],
            angle=bool(model.is_angle[k]),
            nominal=float(model.nominal[k]),
            calibrated=float(model.nominal[k] + delta[k]),
            correction=float(delta[k]),
            std_error=float(se[k]),
            fitted=bool(fitted[k]),
        )
        for k in candidates
    )
    ext = calibrated_extraction(robot, model, delta, convention)
    table = dataclasses.replace(ext.robot, transforms=None)  # the DH table alone
    return CalibrationResult(
        robot=ext.robot,
        nominal=robot,
        dh=dataclasses.replace(ext, robot=table),
        urdf=calibrated_urdf(robot, model, delta),
        kind=kind,
        loss=loss,
        noise=sigma_in,
        parameters=rows,
        identification=ident,
        generic_count=len(generic.chosen),
        correlated=correlated_pairs(covariance, tuple(model.names[k] for k in free)),
        covariance=covariance,
        sigma=math.sqrt(variance),
        before=_errors(model.fk(zero, qa), data),
        after=_errors(model.fk(delta, qa), data),
        outliers=outliers,
        evaluations=int(solution.nfev),
    )
