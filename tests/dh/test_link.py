"""The dh layer: link matrices, rows, conventions, table conversion, the core's FK.

Every expected value comes from the slides' formulas typed in here or from the
reference product of four elementary matrices in ``support/helpers.py``.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given
from support.helpers import (
    PROPERTY,
    JointSpec,
    RobotSpec,
    assert_transform_close,
    random_q,
    ref_link,
    robot_specs,
    rot_x,
    seeds,
    tras_x,
)

from kinematica.core import Chain
from kinematica.dh import (
    Prismatic,
    Revolute,
    check_convention,
    convert_table,
    link_matrix,
)
from kinematica.errors import KinematicaError

CONVENTIONS = ["standard", "modified"]
BATCHES = [(), (1,), (3, 2)]
TWISTS = [0.0, math.pi / 2, -math.pi / 2, math.pi, -math.pi]


def seed000_link(theta: float, d: float, a: float, alpha: float) -> np.ndarray:
    """The link matrix exactly as seed 000 (rule 14) prints it."""
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array(
        [
            [ct, -ca * st, sa * st, a * ct],
            [st, ca * ct, -sa * ct, a * st],
            [0.0, sa, ca, d],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )


def craig_link(alpha: float, a: float, theta: float, d: float) -> np.ndarray:
    """Craig's link transform (Introduction to Robotics, eq. 3.6), a(i-1), α(i-1), θi, di."""
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array(
        [
            [ct, -st, 0.0, a],
            [st * ca, ct * ca, -sa, -sa * d],
            [st * sa, ct * sa, ca, ca * d],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )


def random_params(n: int, seed: int) -> tuple[np.ndarray, ...]:
    """``n`` random (theta, d, a, alpha), a third of the twists special angles."""
    rng = np.random.default_rng(seed)
    theta = rng.uniform(-math.pi, math.pi, n)
    d, a = rng.uniform(-1.0, 1.0, (2, n))
    alpha = rng.uniform(-math.pi, math.pi, n)
    alpha[::3] = rng.choice(TWISTS, size=alpha[::3].shape)
    return theta, d, a, alpha


# ------------------------------------------------------------------ link_matrix
@pytest.mark.parametrize("convention", CONVENTIONS)
def test_link_matrix_equals_reference_product(convention: str) -> None:
    theta, d, a, alpha = random_params(200, seed=1)
    expected = np.array([ref_link(*p, convention) for p in zip(theta, d, a, alpha, strict=True)])
    assert_transform_close(link_matrix(theta, d, a, alpha, convention), expected, atol=1e-15)


def test_standard_link_matrix_equals_seed000_closed_form() -> None:
    theta, d, a, alpha = random_params(100, seed=2)
    expected = np.array([seed000_link(*p) for p in zip(theta, d, a, alpha, strict=True)])
    assert_transform_close(link_matrix(theta, d, a, alpha, "standard"), expected, atol=1e-15)
    # ... and the reference product is that same matrix (rule 14 of seed 000).
    reference = np.array([ref_link(*p, "standard") for p in zip(theta, d, a, alpha, strict=True)])
    assert_transform_close(reference, expected, atol=1e-15)


def test_modified_link_matrix_equals_craig_closed_form() -> None:
    theta, d, a, alpha = random_params(100, seed=3)
    expected = np.array(
        [craig_link(al, aa, th, dd) for th, dd, aa, al in zip(theta, d, a, alpha, strict=True)]
    )
    assert_transform_close(link_matrix(theta, d, a, alpha, "modified"), expected, atol=1e-15)


def test_link_matrix_default_convention_is_standard() -> None:
    assert_transform_close(link_matrix(0.3, 0.2, 0.1, 1.0), seed000_link(0.3, 0.2, 0.1, 1.0))


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("alpha", TWISTS)
def test_link_matrix_special_twists(convention: str, alpha: float) -> None:
    theta, d, a, _ = random_params(20, seed=4)
    expected = np.array(
        [ref_link(t, dd, aa, alpha, convention) for t, dd, aa in zip(theta, d, a, strict=True)]
    )
    assert_transform_close(link_matrix(theta, d, a, alpha, convention), expected, atol=1e-15)


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("batch", BATCHES)
def test_link_matrix_batch_shapes(convention: str, batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(5)
    theta, d = rng.uniform(-1, 1, (2, *batch))
    A = link_matrix(theta, d, 0.25, -0.5, convention)  # scalars broadcast
    assert A.shape == (*batch, 4, 4)
    flat_t, flat_d = np.ravel(theta), np.ravel(d)
    expected = np.array(
        [ref_link(t, dd, 0.25, -0.5, convention) for t, dd in zip(flat_t, flat_d, strict=True)]
    )
    assert_transform_close(A, expected.reshape(*batch, 4, 4), atol=1e-15)


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_link_matrix_is_a_rigid_transform(convention: str) -> None:
    A = link_matrix(*random_params(100, seed=6), convention)
    R = A[..., :3, :3]
    np.testing.assert_allclose(
        R @ np.swapaxes(R, -1, -2), np.broadcast_to(np.eye(3), R.shape), atol=1e-15
    )
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=1e-14)
    np.testing.assert_array_equal(
        A[..., 3, :], np.broadcast_to([0.0, 0.0, 0.0, 1.0], A[..., 3, :].shape)
    )


def test_link_matrix_unknown_convention() -> None:
    with pytest.raises(KinematicaError, match=r"unknown DH convention 'paulx'.*standard.*modified"):
        link_matrix(0, 0, 0, 0, "paulx")  # type: ignore[arg-type]


# ------------------------------------------------------------- conventions, rows
@pytest.mark.parametrize(
    ("name", "canonical"),
    [
        ("standard", "standard"),
        ("DH", "standard"),
        ("paul", "standard"),
        (" Distal ", "standard"),
        ("modified", "modified"),
        ("MDH", "modified"),
        ("craig", "modified"),
        ("proximal", "modified"),
    ],
)
def test_check_convention_aliases(name: str, canonical: str) -> None:
    assert check_convention(name) == canonical


def test_rows_expose_their_constant_parts() -> None:
    r = Revolute(d=0.1, a=0.2, alpha=0.3, offset=0.4, qlim=(-1, 2), name="j1")
    assert (r.type, r.theta, r.d, r.a, r.alpha, r.qlim) == ("R", 0.4, 0.1, 0.2, 0.3, (-1.0, 2.0))
    p = Prismatic(theta=0.5, a=0.2, alpha=0.3, offset=0.7)
    assert (p.type, p.theta, p.d, p.a, p.alpha, p.qlim) == ("P", 0.5, 0.7, 0.2, 0.3, None)


@pytest.mark.parametrize("key", ["d", "a", "alpha", "offset"])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_revolute_rejects_non_finite_parameters(key: str, value: float) -> None:
    with pytest.raises(KinematicaError, match=f"DH parameter {key} must be a finite number"):
        Revolute(**{key: value})


@pytest.mark.parametrize("key", ["theta", "a", "alpha", "offset"])
def test_prismatic_rejects_non_finite_parameters(key: str) -> None:
    with pytest.raises(KinematicaError, match=f"DH parameter {key} must be a finite number"):
        Prismatic(**{key: math.nan})


@pytest.mark.parametrize("qlim", [(1.0, -1.0), (0.5, 0.5), (math.nan, 1.0), (0.0, math.nan)])
def test_rows_reject_bad_limits(qlim: tuple[float, float]) -> None:
    with pytest.raises(KinematicaError, match="joint limits must be two numbers lo < hi"):
        Revolute(qlim=qlim)
    with pytest.raises(KinematicaError, match="joint limits must be two numbers lo < hi"):
        Prismatic(qlim=qlim)


# ---------------------------------------------------------------- convert_table
def spec_from_table(
    joints: tuple[Revolute | Prismatic, ...], base: np.ndarray, tool: np.ndarray, convention: str
) -> RobotSpec:
    """A plain spec from converted rows, so the reference product can check them."""
    rows = tuple(
        JointSpec(
            kind=j.type,
            const=j.d if isinstance(j, Revolute) else j.theta,
            a=j.a,
            alpha=j.alpha,
            offset=j.offset,
            qlim=j.qlim,
        )
        for j in joints
    )
    return RobotSpec(rows, convention, base, tool)


def canonical(
    joints: tuple[Revolute | Prismatic, ...], base: np.ndarray, tool: np.ndarray, convention: str
) -> tuple[tuple[Revolute | Prismatic, ...], np.ndarray, np.ndarray]:
    """The table with the pair no other convention can hold moved into base or tool.

    A modified table has no slot for a standard table's last (a_n, α_n), nor a
    standard table for a modified table's first (a_0, α_0): a round trip moves
    that pair into the tool (resp. base). Moving it there here on both sides
    makes tables that describe the same robot compare equal.
    """
    rows = list(joints)
    if convention == "standard":
        last = rows[-1]
        tool = rot_x(last.alpha) @ tras_x(last.a) @ tool
        rows[-1] = dataclasses.replace(last, a=0.0, alpha=0.0)
    else:
        first = rows[0]
        base = base @ rot_x(first.alpha) @ tras_x(first.a)
        rows[0] = dataclasses.replace(first, a=0.0, alpha=0.0)
    return tuple(rows), base, tool


def assert_same_table(
    got: tuple[tuple[Revolute | Prismatic, ...], np.ndarray, np.ndarray],
    want: tuple[tuple[Revolute | Prismatic, ...], np.ndarray, np.ndarray],
) -> None:
    assert len(got[0]) == len(want[0])
    for i, (g, w) in enumerate(zip(got[0], want[0], strict=True), start=1):
        assert type(g) is type(w), f"joint {i}: {g} vs {w}"
        assert (g.qlim, g.name) == (w.qlim, w.name), f"joint {i}"
        np.testing.assert_allclose(
            [g.theta, g.d, g.a, g.alpha, g.offset],
            [w.theta, w.d, w.a, w.alpha, w.offset],
            atol=1e-15,
            err_msg=f"joint {i}",
        )
    assert_transform_close(got[1], want[1], atol=1e-15, err_msg="base")
    assert_transform_close(got[2], want[2], atol=1e-15, err_msg="tool")


def _table(spec: RobotSpec) -> tuple[tuple[Revolute | Prismatic, ...], np.ndarray, np.ndarray]:
    base = np.eye(4) if spec.base is None else spec.base
    tool = np.eye(4) if spec.tool is None else spec.tool
    return tuple(j.build() for j in spec.joints), base, tool


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_convert_table_keeps_fk(spec: RobotSpec, seed: int) -> None:
    joints, base, tool = _table(spec)
    other = "modified" if spec.convention == "standard" else "standard"
    converted = spec_from_table(*convert_table(joints, spec.convention, other, base, tool), other)  # type: ignore[arg-type]
    rng = np.random.default_rng(seed)
    for q in random_q(spec, rng, (4,)):
        assert_transform_close(converted.ref_fk(q), spec.ref_fk(q), atol=1e-12)


@PROPERTY
@given(spec=robot_specs())
def test_convert_table_round_trip_gives_the_same_table(spec: RobotSpec) -> None:
    joints, base, tool = _table(spec)
    other = "modified" if spec.convention == "standard" else "standard"
    there = convert_table(joints, spec.convention, other, base, tool)  # type: ignore[arg-type]
    back = convert_table(*there[:1], other, spec.convention, *there[1:])  # type: ignore[arg-type]
    # Rows 1..n-1 (standard) or 2..n (modified) come back exactly ...
    inner = slice(0, -1) if spec.convention == "standard" else slice(1, None)
    assert back[0][inner] == joints[inner]
    # ... and the whole table does, once the unrepresentable pair sits in tool/base.
    assert_same_table(
        canonical(*back, spec.convention),
        canonical(joints, base, tool, spec.convention),
    )


def test_convert_table_standard_to_modified_by_hand() -> None:
    # Standard rows (a_i, α_i) move one row down; the last pair goes into the tool.
    rows = (Revolute(d=0.1, a=0.2, alpha=0.3), Prismatic(theta=0.4, a=0.5, alpha=0.6))
    new, base, tool = convert_table(rows, "standard", "modified", np.eye(4), np.eye(4))
    assert new == (
        Revolute(d=0.1, a=0.0, alpha=0.0),
        Prismatic(theta=0.4, a=0.2, alpha=0.3),
    )
    assert_transform_close(base, np.eye(4), atol=0)
    assert_transform_close(tool, rot_x(0.6) @ tras_x(0.5), atol=1e-16)


def test_convert_table_same_convention_is_identity() -> None:
    rows = (Revolute(d=0.1, a=0.2, alpha=0.3),)
    base, tool = rot_x(0.2), tras_x(0.3)
    new, b, t = convert_table(rows, "craig", "modified", base, tool)
    assert new == rows
    assert_transform_close(b, base, atol=0)
    assert_transform_close(t, tool, atol=0)


# ------------------------------------------------------------- the compiled chain
def _chain(spec: RobotSpec) -> Chain:
    joints, base, tool = _table(spec)
    return Chain.from_dh(joints, spec.convention, base, tool)  # type: ignore[arg-type]


def kfk(chain: Chain, q: np.ndarray, all_frames: bool = False) -> tuple[np.ndarray, int, int, int]:
    return chain.fk(q, all_frames)


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_core_chain_equals_reference_product(spec: RobotSpec, seed: int) -> None:
    chain = _chain(spec)
    q = random_q(spec, np.random.default_rng(seed), (5,))
    expected = np.array([spec.ref_frames(qi) for qi in q])
    assert_transform_close(kfk(chain, q)[0], expected[:, -1], atol=1e-12)
    assert_transform_close(kfk(chain, q, True)[0], expected, atol=1e-12)
    for qi, Ti in zip(q, expected[:, -1], strict=True):
        assert_transform_close(kfk(chain, qi)[0], Ti, atol=1e-12)


def test_chain_batches_larger_than_one_block() -> None:
    # More configurations than one cache block: every block must be written.
    spec = RobotSpec(
        (JointSpec("R", 0.1, 0.2, 0.3, 0.4), JointSpec("P", 0.5, 0.6, 0.7, 0.8)),
        "standard",
    )
    chain = _chain(spec)
    q = random_q(spec, np.random.default_rng(7), (2500,))
    T = kfk(chain, q)[0]
    for k in (0, 1023, 1024, 2047, 2048, 2499):
        assert_transform_close(T[k], spec.ref_fk(q[k]), atol=1e-14, err_msg=f"row {k}")


# ----------------------------------------------------------------- snapped twists
@pytest.mark.parametrize("convention", CONVENTIONS)
def test_special_twists_equal_reference_product(convention: str) -> None:
    # Twists of 0, ±90° and 180° run through the exact branches of the core's chain.
    rng = np.random.default_rng(8)
    for alphas in [
        (0.0, math.pi / 2, -math.pi / 2, math.pi),
        (math.pi, -math.pi / 2, 0.0, math.pi / 2),
    ]:
        spec = RobotSpec(
            tuple(
                JointSpec(kind, const, a, alpha, offset)
                for kind, const, a, alpha, offset in zip(
                    "RPRR",
                    (0.3, math.pi / 2, -0.2, 0.1),
                    (0.4, -0.3, 0.0, 0.2),
                    alphas,
                    (0.5, 0.1, -0.4, 0.0),
                    strict=True,
                )
            ),
            convention,
        )
        chain = _chain(spec)
        q = random_q(spec, rng, (10,))
        expected = np.array([spec.ref_frames(qi) for qi in q])
        assert_transform_close(kfk(chain, q, True)[0], expected, atol=1e-15)
        for qi, Ti in zip(q, expected[:, -1], strict=True):
            assert_transform_close(kfk(chain, qi)[0], Ti, atol=1e-15)


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("special", TWISTS)
@pytest.mark.parametrize("eps", [-1e-15, -4e-16, 1e-16, 5e-16, 1e-15, 2e-15, 1e-12, 3e-8, -3e-8])
def test_snapping_near_special_twists_is_harmless(
    convention: str, special: float, eps: float
) -> None:
    # cos/sin within 1e-15 of 0 or ±1 are replaced by the exact value; for angles
    # just off a special one the core must still agree with the product at 1e-14.
    alpha = special + eps
    spec = RobotSpec(
        (
            JointSpec("R", 0.7, 0.9, alpha, 0.0),
            JointSpec("P", alpha, -0.8, alpha, 0.3),
            JointSpec("R", -0.6, 1.0, alpha, alpha),
        ),
        convention,
    )
    chain = _chain(spec)
    q = random_q(spec, np.random.default_rng(9), (10,))
    expected = np.array([spec.ref_frames(qi) for qi in q])
    assert_transform_close(kfk(chain, q, True)[0], expected, atol=1e-14)
    for qi, Ti in zip(q, expected[:, -1], strict=True):
        assert_transform_close(kfk(chain, qi)[0], Ti, atol=1e-14)
