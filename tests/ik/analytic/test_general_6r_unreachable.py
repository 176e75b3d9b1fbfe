"""The general 6R proves a target out of reach: det M(x6) without a real root.

Where none of the elimination's candidates closes the loop, every solution of the
target would make a real root of det M(x6) (general_6r.hpp), so a spectrum whose every
eigenvalue lies CERTIFY_MARGIN times its first-order error bound from the real axis
proves the target unreachable (general_6r_roots.hpp: ``real_axis_margin``). Checked
against what the solver does not compute: the condition number and backward error
from numpy's own null vectors, a multi-start damped-least-squares search
(``support.ik_search``) that finds nothing where the solver says unreachable, and the
solver's own solutions just inside the boundary.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from support.general6r import G
from support.helpers import random_7r
from support.ik_search import dls_solutions
from support.kawasaki import UNREACHED, perturbed

import kinematica as km
from kinematica.ik.analytic import general_6r as g6
from kinematica.ik.solve import closed_form

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

#: numpy's κ and η of an eigenvalue agree with the core's to this (relative): both are
#: norms of null vectors of one nearly singular matrix, found by different pivoting.
PARTS_RTOL = 1e-3


def _robot(seed: int, degenerate: bool = False) -> km.Robot:
    arm = g6.sample_arm(np.random.default_rng(seed), degenerate)
    return km.Robot.from_dh(arm.links, convention=arm.convention, base=arm.base, tool=arm.tool)


def _margin_parts(A: list[np.ndarray], x: complex) -> tuple[float, float]:
    """(κ, η) of the eigenvalue x of A0 + A1 x + A2 x² from numpy's SVD null vectors."""
    M = A[0] + x * A[1] + x * x * A[2]
    U, _, Vh = np.linalg.svd(M)
    v, w = Vh[-1].conj(), U[:, -1]  # M v ≈ 0, wᴴ M ≈ 0
    alpha = sum(abs(x) ** k * np.linalg.norm(a) for k, a in enumerate(A))
    kappa = alpha / abs(w.conj() @ (A[1] + 2.0 * x * A[2]) @ v)
    eta = np.linalg.norm(M @ v) / alpha
    return float(kappa), float(eta)


def test_the_margin_of_an_eigenvalue_is_its_distance_over_its_error_bound() -> None:
    # random 12 x 12 pencils: every eigenvalue above the real axis (numpy's, of the
    # companion matrix), its κ and η as numpy's SVD null vectors give them
    rng = np.random.default_rng(3)
    checked = 0
    for _ in range(3):
        A = [rng.normal(size=(12, 12)) for _ in range(3)]
        C = np.zeros((24, 24))
        C[:12, 12:] = np.eye(12)
        C[12:, :12] = -np.linalg.solve(A[2], A[0])
        C[12:, 12:] = -np.linalg.solve(A[2], A[1])
        for x in np.linalg.eigvals(C):
            if x.imag <= 1e-9:
                continue
            value, kappa, eta = G.real_axis_margin(*A, complex(x))
            ref_kappa, ref_eta = _margin_parts(A, complex(x))
            assert kappa == pytest.approx(ref_kappa, rel=PARTS_RTOL)
            assert eta <= 1e-13 and ref_eta <= 1e-13
            assert value == pytest.approx(x.imag / (kappa * (eta + G.PENCIL_EPS)), rel=1e-12)
            checked += 1
    assert checked >= 10
    real = [np.diag([1.0] * 12), np.zeros((12, 12)), np.eye(12)]
    real[0][0, 0] = -1.0  # x² - 1 in the first entry: the real roots ±1
    assert G.real_axis_margin(*real, 1.0 + 0j)[0] == 0.0


def _boundary(robot: km.Robot, T0: np.ndarray, d: np.ndarray) -> float:
    """How far along d from T0's position the solver's last solution lies (m, to 1e-15)."""

    def solved(t: float) -> bool:
        T = T0.copy()
        T[:3, 3] += t * d
        return str(robot.ik(T).status) in ("ok", "singular")

    lo, hi = 0.0, 0.05
    while solved(hi):
        lo, hi = hi, 1.5 * hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if solved(mid) else (lo, mid)
    return lo


def test_certify_margin_and_pencil_eps_at_their_boundary() -> None:
    # Just inside: a target beyond a random arm's workspace boundary whose least margin
    # is between CERTIFY_MARGIN and 1,000 times it (certified: unreachable, and a
    # 200-start search finds nothing there; a constant 1,000 times larger, or a
    # PENCIL_EPS 1,000 times larger, the eigenvalues' backward error far below it, would
    # leave it to the search). Just outside: the Kawasaki target no labelling reaches,
    # margin 19 (0.19 CERTIFY_MARGIN; a constant, or PENCIL_EPS, 1,000 times smaller
    # would certify it), answered not_found.
    robot = _robot(5)
    params = closed_form(robot.chain, "pose").params
    rng = np.random.default_rng(7)
    T0 = robot.fk(rng.uniform(-math.pi, math.pi, 6))
    d = rng.normal(size=3)
    d /= np.linalg.norm(d)
    edge = _boundary(robot, T0, d)
    inside = None
    for delta in np.geomspace(1e-2, 1e-8, 25):
        T = T0.copy()
        T[:3, 3] += (edge + delta) * d
        margin, _, eta = G.margin(params, T)
        if G.CERTIFY_MARGIN < margin < 1e3 * G.CERTIFY_MARGIN:
            inside = T
            assert eta < G.PENCIL_EPS / 1e3
            break
    assert inside is not None
    assert G.certifies(G.margin(params, inside)[0])
    res = robot.ik(inside)
    assert str(res.status) == "unreachable" and res.method == "analytic:general-6R"
    assert res.gap is None  # not the reach sphere's proof
    assert len(dls_solutions(robot, inside, np.random.default_rng(1))) == 0
    T = T0.copy()
    T[:3, 3] += (edge - 1e-6) * d
    assert str(robot.ik(T).status) == "ok"  # and the arm reaches just inside

    kawasaki = perturbed()
    k_params = closed_form(kawasaki.chain, "pose").params
    margin, _, eta = G.margin(k_params, np.array(UNREACHED))
    assert G.CERTIFY_MARGIN / 1e3 < margin < G.CERTIFY_MARGIN
    assert margin * (eta + G.PENCIL_EPS) / (eta + G.PENCIL_EPS / 1e3) > G.CERTIFY_MARGIN
    assert str(kawasaki.ik(np.array(UNREACHED), respect_limits=False).status) == "not_found"


@pytest.mark.parametrize("degenerate", [False, True], ids=["generic", "degenerate"])
def test_no_target_said_unreachable_is_reached_by_a_search(degenerate: bool) -> None:
    # random arms, targets of random orientation at 0.7-1.5 times an FK pose's distance
    # from the base: every "unreachable" the elimination proves (no reach gap) is one a
    # 200-start search finds no solution of
    rng = np.random.default_rng(40 + degenerate)
    proved = 0
    for seed in range(6):
        robot = _robot(100 * seed + degenerate, degenerate)
        base = robot.base[:3, 3]
        for _ in range(5):
            T = robot.fk(rng.uniform(-math.pi, math.pi, 6))
            T[:3, 3] = base + (T[:3, 3] - base) * rng.uniform(0.7, 1.5)
            q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
            T[:3, :3] = q * np.sign(np.linalg.det(q))
            res = robot.ik(T)
            assert not res.method.startswith("numeric") or str(res.status) != "unreachable"
            if str(res.status) == "unreachable" and res.gap is None:
                proved += 1
                assert len(dls_solutions(robot, T, rng, starts=100)) == 0
    assert proved >= 10


def test_a_7r_arm_held_at_any_middle_value_is_never_left_to_the_search() -> None:
    # issue 32: auto on a 7R arm with a held joint is never numeric; a middle joint held
    # at a value that leaves the target out of reach is proved so by the general 6R
    rng = np.random.default_rng(12)
    statuses = set()
    for seed in range(3):
        robot = random_7r(seed)
        for _ in range(6):
            q = rng.uniform(-math.pi, math.pi, 7)
            k = int(rng.integers(1, 6))
            res = robot.ik(robot.fk(q), fixed={k: float(rng.uniform(-math.pi, math.pi))})
            assert res.method == "analytic:general-6R", res.notes
            statuses.add(str(res.status))
    assert statuses == {"ok", "unreachable"}


def test_a_panda_held_at_q1_is_proved_out_of_reach_beside_its_twelve_roots() -> None:
    # the Panda held at q1 leaves a 6R arm whose det M has (1 + x²)⁶ (M(i) of nullity 6,
    # MAX_NULLITY): deflated to 12 genuine roots, so a target none closes is proved out of
    # reach; a 100-start search with q1 held finds none of those, and none is searched
    robot = km.load("panda")
    rng = np.random.default_rng(5)
    proved = 0
    for _ in range(16):
        T = robot.fk(rng.uniform(robot.qlim[:, 0], robot.qlim[:, 1]))
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        T[:3, :3] = q * np.sign(np.linalg.det(q))
        v = float(rng.uniform(robot.qlim[0, 0], robot.qlim[0, 1]))
        res = robot.ik(T, fixed={0: v}, respect_limits=False)
        assert res.method == "analytic:general-6R", res.notes
        if str(res.status) == "unreachable":
            proved += 1
            Q0 = rng.uniform(-math.pi, math.pi, (100, 7))
            Q0[:, 0] = v
            many = np.repeat(T[None], 100, axis=0)
            search = robot.ik(many, q0=Q0, method="numeric", fixed={0: v}, respect_limits=False)
            assert set(map(str, search.status)) == {"not_found"}
    assert proved >= 3
    params = closed_form(robot.chain.locked(0, 0.3), "pose").params
    A = G.pencil(params, T)
    assert G.spurious_pivots(*A)[0] == 6
