"""What ``robot.ik`` is asked, validated once: :class:`IKRequest`.

``robot.ik(target, **settings)`` reads its settings into one :class:`IKRequest`
(:meth:`IKRequest.parse`), which :func:`kinematica.ik.solve.solve` takes with the
target: the same object whether the settings came as keywords or as ``options=``.
Every setting that needs neither the arm nor the target is checked here, once (the
method, the flag, the tolerance, the mask, the seed, the workers); ``q0``, ``fixed``
and ``arm_angle`` are checked against the arm and the targets where they are used.

A request is an :class:`~kinematica.ik.options.IKOptions` whose fields hold the
checked values (``tol`` a :class:`Tolerance`, ``mask`` the weights or None), so that
``dataclasses.replace(request, tol=...)`` gives a request checked again. Requests
of hashable settings are made once and reused (:data:`MEMO`): a call with the same
keywords finds its request by one dictionary look-up.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.arguments import check_choice, check_flag
from kinematica.core import resolve_workers
from kinematica.errors import KinematicaError
from kinematica.ik.numeric import check_seed
from kinematica.ik.options import IKOptions
from kinematica.ik.targets import parse_mask
from kinematica.ik.tolerance import Tolerance, parse_tolerance

__all__ = ["KEYS", "MEMO", "HeldCall", "IKRequest", "Q0Call", "settings_key"]

#: Requests kept by their settings (past it the table is emptied and filled again).
MEMO = 64
#: The methods ``robot.ik`` takes.
_METHODS = ("auto", "analytic", "numeric")

#: Settings given numbers (:func:`settings_key`), at most.
KEYS = 4096

_requests: dict[tuple[object, ...], IKRequest] = {}
#: Requests of the keywords method, tol and respect_limits alone (:meth:`IKRequest.parse`).
_plain: dict[tuple[object, ...], IKRequest] = {}
#: Requests of ``options=``, by the options' id: ``(options, request)``.
_of: dict[int, tuple[IKOptions, IKRequest]] = {}
_keys: dict[tuple[object, ...], int] = {}
_next_key = 0
_FLOAT64 = np.dtype(np.float64)
#: The settings, in IKOptions' order.
_FIELDS = ("method", "tol", "respect_limits", "q0", "mask", "seed", "workers", "precision",
           "fixed", "arm_angle")  # fmt: skip


@dataclass(frozen=True, slots=True, eq=False)
class IKRequest(IKOptions):
    """An IK call's settings, checked (see :meth:`kinematica.Robot.ik` for each one).

    Attributes:
        tolerance: The acceptance tolerance (``tol`` read).
        key: What a solver and its check depend on (``method, tolerance,
            respect_limits, weights, seed``), as a whole number: equal settings, equal
            keys (:func:`settings_key`); None for a seed that is a Generator (drawn
            from on every call, so nothing built from it is kept).
        given: ``q0``, ``fixed`` or ``arm_angle`` is given (their values are checked
            against the arm's units: :func:`kinematica.robot.given.check_given`).
        holds: ``fixed`` or ``arm_angle`` is given: a joint or a parameter is held.
        may_hold: ``method="auto"`` without a mask: a 7-joint arm is solved with a
            joint held (:func:`kinematica.ik.door.solve`).
        bare: Neither ``q0`` nor ``arm_angle``: one target as the core reads it goes
            to the core as it is (:func:`kinematica.ik.solve.solve_ik`).
        lean: The key of the chain's plan for pose targets (:func:`~kinematica.ik.
            solvers.plan_of`) where one such target goes straight to its prepared call
            (:func:`kinematica.ik.door.solve`): nothing held, no ``q0`` in the request
            (a :class:`Q0Call`'s travels beside it); else None.
    """

    tolerance: Tolerance = field(init=False, repr=False)
    key: int | None = field(init=False, repr=False)
    given: bool = field(init=False, repr=False)
    holds: bool = field(init=False, repr=False)
    may_hold: bool = field(init=False, repr=False)
    bare: bool = field(init=False, repr=False)
    lean: int | None = field(init=False, repr=False)
    _changed: dict[tuple[object, ...], IKRequest] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        check_choice(self.method, "method", _METHODS)
        flag = check_flag(self.respect_limits, "respect_limits")
        tolerance = parse_tolerance(self.tol)
        mask = parse_mask(self.mask)
        seed = check_seed(self.seed)
        if self.workers is not None:
            resolve_workers(self.workers)  # a bad value is an error on every call
        weights = None if mask is None else tuple(mask.tolist())
        kept = seed is None or isinstance(seed, int)  # a Generator is drawn from every call
        put = object.__setattr__
        put(self, "respect_limits", flag)
        put(self, "tol", tolerance)
        put(self, "mask", mask)
        put(self, "seed", seed)
        put(self, "tolerance", tolerance)
        put(self, "_changed", {})
        # what each call asks of its settings, read once here
        put(self, "holds", self.fixed is not None or self.arm_angle is not None)
        put(self, "given", self.holds or self.q0 is not None)
        put(self, "may_hold", self.method == "auto" and mask is None)
        put(self, "bare", self.q0 is None and self.arm_angle is None)
        settings = (self.method, tolerance.position, tolerance.rotation, flag, weights, seed)
        put(self, "key", settings_key(settings) if kept else None)
        lean = self.key is not None and self.bare and self.fixed is None
        put(self, "lean", 4 * self.key if lean else None)  # type: ignore[operator]

    def but(self, **changes: Any) -> IKRequest:
        """This request with some settings changed, checked (``dataclasses.replace``, kept).

        A change of hashable values is made once per request, then found by them; a change
        of ``q0`` alone keeps every other setting as checked (``q0`` is checked where it
        is used) and is made without checking them again; changes to the values the
        request holds already (None, or numbers and words equal in value and type) are
        this request.
        """
        if len(changes) == 1 and "q0" in changes:
            return self._with_q0(changes["q0"])
        if all(_same(getattr(self, name), v) for name, v in changes.items()):
            return self
        try:  # the values' types too: True == 1
            key = (*changes.items(), *map(type, changes.values()))
            found = self._changed.get(key)
        except TypeError:  # an array (q0): made each time
            key, found = None, None
        if found is None:
            fields = {name: getattr(self, name) for name in _FIELDS}
            fields.update(changes)
            found = _made(**fields)
            if key is not None and len(self._changed) < MEMO:
                self._changed[key] = found
        return found

    def _with_q0(self, q0: Any) -> IKRequest:
        """This request with ``q0`` replaced, its other settings as checked.

        What ``q0`` decides (``given``, ``bare``, ``lean``) is read again; the copy has a
        memo of its own, in which a request without ``q0`` keeps itself: the copy's
        ``q0`` replaced by None again is this request.
        """
        if q0 is None:
            back = self if self.q0 is None else self._changed.get(_NO_Q0)
            if back is not None:
                return back
        found = object.__new__(IKRequest)
        put = object.__setattr__
        for name in _SLOTS:
            put(found, name, getattr(self, name))
        put(found, "q0", q0)
        put(found, "_changed", {_NO_Q0: self} if self.q0 is None else {})
        put(found, "given", self.holds or q0 is not None)
        put(found, "bare", q0 is None and self.arm_angle is None)
        lean = self.key is not None and found.bare and self.fixed is None
        put(found, "lean", 4 * self.key if lean else None)  # type: ignore[operator]
        return found

    @classmethod
    def of(cls, options: IKOptions) -> IKRequest:
        """``options`` checked (a request is returned as it is)."""
        if type(options) is IKRequest:
            return options
        found = _of.get(id(options))  # kept with the options: their id is theirs alone
        if found is not None and found[0] is options:
            return found[1]
        request = _made(
            options.method, options.tol, options.respect_limits, options.q0, options.mask,
            options.seed, options.workers, options.precision, options.fixed, options.arm_angle,
        )  # fmt: skip
        if _immutable(options) and request.key is not None:
            if len(_of) >= MEMO:
                _of.clear()
            _of[id(options)] = (options, request)
        return request

    @classmethod
    def parse(
        cls,
        method: object = "auto",
        tol: object = None,
        respect_limits: object = True,
        q0: Any = None,
        mask: Any = None,
        seed: Any = None,
        workers: Any = None,
        precision: Any = None,
        fixed: Any = None,
        arm_angle: Any = None,
        options: object = None,
    ) -> IKRequest | HeldCall | Q0Call:
        """The request of ``robot.ik``'s keywords, or of its ``options=`` (not both).

        A call that holds one joint (``fixed`` a dict of one entry) and gives no other
        setting but ``method``, ``tol``, ``respect_limits`` and ``q0`` is a
        :class:`HeldCall`; one that holds nothing and gives ``q0`` (a float64 vector) and
        no other setting but those three, a :class:`Q0Call`.

        Raises:
            KinematicaError: A setting that is not valid (its ``arg`` names it), or
                ``options`` given with keywords, or not an ``IKOptions``.
        """
        if options is None:
            vector = q0.__class__ is np.ndarray and q0.dtype is _FLOAT64 and q0.ndim == 1
            if (
                (q0 is None or vector)
                and mask is None
                and seed is None
                and workers is None
                and precision is None
                and arm_angle is None
            ):  # the common call: found by the three settings it gives (types too: True == 1)
                try:
                    plain = (method, method.__class__, respect_limits, respect_limits.__class__,
                             tol, tol.__class__)  # fmt: skip
                    found = _plain.get(plain)
                except TypeError:  # unhashable: a list
                    plain, found = None, None
                if found is None:
                    found = _made(method, tol, respect_limits, None, None, None, None, None,
                                  None, None)  # fmt: skip
                    if plain is not None and found.key is not None:
                        if len(_plain) >= MEMO:
                            _plain.clear()
                        _plain[plain] = found
                if fixed is None:
                    return found if q0 is None else Q0Call(found, q0)
                if fixed.__class__ is dict and len(fixed) == 1:  # one joint held: its value apart
                    ((joint, value),) = fixed.items()
                    return HeldCall(found, joint, value, fixed, q0)
            return _made(method, tol, respect_limits, q0, mask, seed, workers, precision,
                         fixed, arm_angle)  # fmt: skip
        if not isinstance(options, IKOptions):
            raise KinematicaError(
                f"options must be an IKOptions, got {type(options).__name__}", arg="options"
            )
        if not (
            method.__class__ is str
            and method == "auto"
            and respect_limits is True
            and tol is None
            and q0 is None
            and mask is None
            and seed is None
            and workers is None
            and precision is None
            and fixed is None
            and arm_angle is None
        ):
            raise KinematicaError(
                "give the IK settings either as options= or as keywords, not both",
                arg="options",
            )
        o = options
        if (
            (o.fixed.__class__ is dict or (o.fixed is None and o.q0 is not None))
            and o.mask is None
            and o.seed is None
            and o.workers is None
            and o.precision is None
            and o.arm_angle is None
        ):  # as its keywords are read (a HeldCall for one joint, a Q0Call for q0 alone)
            return cls.parse(o.method, o.tol, o.respect_limits, o.q0, fixed=o.fixed)
        return cls.of(options)


#: The key of ``but(q0=None)`` in a request's memo (:meth:`IKRequest._with_q0`).
_NO_Q0 = ("q0", None, type(None))
#: Every field of a request, checked or read from the checked ones (:meth:`IKRequest._with_q0`).
_SLOTS = tuple(f.name for f in fields(IKRequest))


class HeldCall:
    """One call holding one joint at a value: its settings but ``fixed`` and ``q0``, kept.

    It gives no setting but ``fixed`` (one joint), ``q0``, ``method``, ``tol`` and
    ``respect_limits``. The request of those settings is kept and found by them
    (:meth:`IKRequest.parse`); the joint and its value, a new one on every call, and
    ``q0`` travel beside it as given and are checked where they are solved
    (:func:`kinematica.ik.door.solve`), so that a new value makes no new request. Read
    by ``robot.ik``'s check of units as a request is (``q0``, ``fixed``, ``arm_angle``).

    Attributes:
        request: The request of the call's other settings (``fixed`` and ``q0`` None).
        joint: The joint as ``fixed`` names it (0-based index, name or ``"qN"``).
        value: Its value as given (rad or m).
        fixed: The ``fixed`` dict as given.
        q0: ``(n,)`` float64 as given (the whole arm's), or None.
    """

    __slots__ = ("fixed", "joint", "q0", "request", "value")
    given = True
    arm_angle = None

    def __init__(
        self,
        request: IKRequest,
        joint: object,
        value: object,
        fixed: dict[Any, Any],
        q0: NDArray[np.float64] | None = None,
    ):
        self.request, self.joint, self.value, self.fixed, self.q0 = request, joint, value, fixed, q0

    def full(self) -> IKRequest:
        """The call's request, ``fixed`` and ``q0`` in it (checked as every request is)."""
        return self.request.but(fixed={self.joint: self.value}, q0=self.q0)


class Q0Call:
    """One call giving ``q0``, a float64 vector: its settings but ``q0``, kept.

    It gives no setting but ``q0``, ``method``, ``tol`` and ``respect_limits``.
    As :class:`HeldCall`: the request of those settings is kept and found by them, and
    ``q0``, new on every call, travels beside it (:func:`kinematica.ik.door.solve`).

    Attributes:
        request: The request of the call's other settings (``q0`` None).
        q0: ``(n,)`` float64 as given.
    """

    __slots__ = ("q0", "request")
    given = True
    fixed = None
    arm_angle = None

    def __init__(self, request: IKRequest, q0: NDArray[np.float64]):
        self.request, self.q0 = request, q0

    def full(self) -> IKRequest:
        """The call's request, ``q0`` in it (checked as every request is)."""
        return self.request.but(q0=self.q0)


def settings_key(settings: tuple[object, ...]) -> int:
    """A whole number for these settings: the same for equal settings, never reused.

    Kept in a table of :data:`KEYS` settings; past it the table is emptied and later
    settings take new numbers (a number once given is never given to other settings).
    """
    global _next_key
    found = _keys.get(settings)
    if found is None:
        if len(_keys) >= KEYS:
            _keys.clear()
        found = _keys[settings] = _next_key
        _next_key += 1
    return found


def _same(held: object, value: object) -> bool:
    """True where a setting ``held`` already is ``value``.

    The same object, or a number or word equal in value and type (an array, a mapping
    or NaN equal to another is never taken for it).
    """
    if held is value:
        return True
    kind = type(held)
    return kind is type(value) and kind in (float, int, str, bool) and held == value


def _made(
    method: Any,
    tol: Any,
    respect_limits: Any,
    q0: Any,
    mask: Any,
    seed: Any,
    workers: Any,
    precision: Any,
    fixed: Any,
    arm_angle: Any,
) -> IKRequest:
    """The request of these settings: found by them when they are hashable, else made.

    A setting's type is part of what finds it: ``True == 1``, and only one of them is a
    valid ``respect_limits`` (or ``tol``, ``seed``, ``workers``, ``arm_angle``).
    """
    if q0 is None and mask is None and precision is None:
        try:
            memo = (
                method, method.__class__, respect_limits, respect_limits.__class__,
                tol, tol.__class__, seed, seed.__class__, workers, workers.__class__,
                arm_angle, arm_angle.__class__, None if fixed is None else _frozen(fixed),
            )  # fmt: skip
            found = _requests.get(memo)
        except TypeError:  # unhashable: an array, a list
            memo = None
            found = None
        if found is not None:
            return found
    else:
        memo = None
    if type(fixed) is dict:
        fixed = dict(fixed)  # kept: the caller's dict may change after the call
    request = IKRequest(method, tol, respect_limits, q0, mask, seed, workers, precision,
                        fixed, arm_angle)  # fmt: skip
    if memo is not None and request.key is not None and not isinstance(arm_angle, np.ndarray):
        if len(_requests) >= MEMO:
            _requests.clear()
        _requests[memo] = request
    return request


def _frozen(fixed: object) -> object:
    """A ``fixed`` mapping as a hashable key (its items, with their types), else itself."""
    if type(fixed) is dict:
        return (dict, *((k, type(k), v, type(v)) for k, v in fixed.items()))
    if not isinstance(fixed, Mapping):
        return fixed
    raise TypeError("not a plain dict: not kept")


def _immutable(options: IKOptions) -> bool:
    """Whether ``options`` hold hashable values alone (none an array, a list or a dict).

    Such options give the same request whenever they are given again (:meth:`IKRequest.of`).
    """
    if not (options.q0 is None and options.mask is None and options.precision is None
            and options.fixed is None):  # fmt: skip
        return False
    try:
        hash((options.method, options.tol, options.respect_limits, options.seed,
              options.workers, options.arm_angle))  # fmt: skip
    except TypeError:
        return False
    return True
