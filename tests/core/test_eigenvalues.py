"""The core's eigenvalues of a small dense matrix (``eigenvalues.hpp``), against LAPACK's.

Hooked through ``kinematica._core_testing.general6r.eigenvalues`` (16 x 16 and 24 x 24, the
sizes the general 6R uses); numpy's ``eigvals`` (LAPACK's dgeev) is the independent
reference. Each of the core's eigenvalues is matched to its nearest of LAPACK's, one
to one, within a bound made of the matrix's norm and the eigenvalue's condition.
"""

from __future__ import annotations

import kinematica._core_testing as _core_testing
import numpy as np
import pytest

#: Eigenvalues agree to this times ‖A‖ / (the eigenvalue's condition's reciprocal):
#: backward-stable methods both, each within a few round-offs of a nearby matrix's.
AGREE = 1e-12


def _reference(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """LAPACK's eigenvalues and their condition numbers 1 / |yᴴ x| (unit left, right vectors)."""
    w, V = np.linalg.eig(A)
    V = V / np.linalg.norm(V, axis=0)
    Y = np.linalg.inv(V).conj().T
    Y /= np.linalg.norm(Y, axis=0)
    return w, 1.0 / np.abs(np.sum(Y.conj() * V, axis=0))


def _matched(A: np.ndarray) -> None:
    re, im = _core_testing.general6r.eigenvalues(A)
    ours = re + 1j * im
    ref, cond = _reference(A)
    left = list(range(len(ours)))
    for k in np.argsort(-np.abs(ref)):
        j = min(left, key=lambda i: abs(ours[i] - ref[k]))
        bound = AGREE * np.linalg.norm(A) * cond[k]
        assert abs(ours[j] - ref[k]) <= bound, (ours[j], ref[k], bound)
        left.remove(j)
    # a real matrix's complex eigenvalues come in conjugate pairs, exactly
    pairs = im != 0.0
    assert np.sort(im[pairs]).tolist() == np.sort(-im[pairs]).tolist()


@pytest.mark.parametrize("n", [16, 24])
def test_random_matrices_match_lapack(n: int) -> None:
    rng = np.random.default_rng(n)
    for _ in range(20):
        _matched(rng.standard_normal((n, n)))


def test_badly_scaled_and_structured_matrices_match_lapack() -> None:
    rng = np.random.default_rng(5)
    # rows and columns scaled over 12 orders of magnitude: balancing undoes it exactly
    D = np.diag(10.0 ** rng.uniform(-6, 6, 24))
    _matched(D @ rng.standard_normal((24, 24)) @ np.linalg.inv(D))
    # a companion matrix (the general 6R's form), real roots known
    roots = np.concatenate([np.linspace(-3.0, 3.0, 10), [0.5, 0.5 + 1e-3]])
    c = np.poly(np.concatenate([roots, [1j, -1j, 2 + 1j, 2 - 1j]]))[1:].real
    C = np.zeros((16, 16))
    C[1:, :-1] = np.eye(15)
    C[0] = -c
    _matched(C)
    re, im = _core_testing.general6r.eigenvalues(C)
    real = np.sort(re[im == 0.0])
    np.testing.assert_allclose(real, np.sort(roots), atol=1e-9)
    # already triangular, and the zero matrix: no step needed, no division by zero
    T = np.triu(rng.standard_normal((16, 16)))
    re, im = _core_testing.general6r.eigenvalues(T)
    np.testing.assert_array_equal(np.sort(re), np.sort(np.diag(T)))
    assert not im.any()
    re, im = _core_testing.general6r.eigenvalues(np.zeros((24, 24)))
    assert not re.any() and not im.any()


def test_qr_steps_is_exported_and_a_bad_size_is_refused() -> None:
    assert _core_testing.general6r.QR_STEPS == 720  # LAPACK dlahqr's budget for 24 rows
    with pytest.raises(ValueError, match="A must have shape"):
        _core_testing.general6r.eigenvalues(np.zeros((16, 15)))
