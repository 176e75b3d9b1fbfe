// Singular values of a small dense matrix (a Jacobian's rows: at most 6 of them), without
// the singular vectors: one-sided Jacobi (Hestenes 1958).
//
// The min(m, n) <= 6 vectors of the matrix's shorter side (its rows when m <= n, else its
// columns) are made mutually orthogonal by plane rotations, which leave the singular values
// unchanged; then those are the vectors' norms. Each rotation zeroes the inner product of
// a pair (Rutishauser's angle formula, as in Demmel & Veselić 1992, "Jacobi's method is
// more accurate than QR", SIAM J. Matrix Anal. Appl. 13(4)); cyclic sweeps over the pairs
// converge quadratically. The method is backward stable: each value is exact for a matrix
// within a few ulps (relative to the largest) of the one given, as LAPACK's bidiagonal QR
// is, and a rank-deficient matrix gets its zero values to that same round-off.
#pragma once

#include <cmath>

#include "config.hpp"

namespace km {

//! Most values singular_values returns: min(m, n) of a matrix of at most 6 rows (or columns).
constexpr int MAX_SINGULAR = 6;
//! A pair is taken as orthogonal when |a·b| <= JACOBI_TOL · L · |a| |b| (L the vectors'
//! length): the stopping rule of Demmel & Veselić (L times the unit round-off).
constexpr double JACOBI_TOL = 1.1102230246251565e-16;
//! Sweeps before giving up (quadratic convergence needs 5-8 for 6 vectors; never reached
//! in tests, a guard against a cycle).
constexpr int JACOBI_SWEEPS = 60;
//! Entries up to 2^SCALE_EXP in size are squared as they are (see singular_values).
constexpr int SCALE_EXP = 400;
//! Two Jacobians whose entries agree (up to each column's sign) within this times their
//! largest entry share their singular values (same_up_to_column_signs): the difference
//! moves each value by at most about this times σ1, below the agreement asked of them.
constexpr double SAME_COLUMNS_TOL = 1e-14;
//! Beyond this |ζ|, √(1 + ζ²) is taken as |ζ| (exact in doubles; ζ² would overflow).
constexpr double ZETA_BIG = 1e100;

namespace detail {

//! Cyclic sweeps of one-sided Jacobi over k vectors of length L (LEN: L known at compile
//! time, 0: read from L) in W; their squared norms come back in norm2.
template <int LEN>
KM_HD KM_INLINE void jacobi_sweeps(double* W, int k, int L_runtime, double* norm2) {
    const int L = LEN > 0 ? LEN : L_runtime;
    const double tol2 = (JACOBI_TOL * L) * (JACOBI_TOL * L);
    for (int sweep = 0; sweep < JACOBI_SWEEPS; ++sweep) {
        // the norms afresh each sweep: the updates below (α − t·g, β + t·g) drift by round-off
        for (int i = 0; i < k; ++i) {
            double sum = 0.0;
            for (int t = 0; t < L; ++t) sum += W[i * L + t] * W[i * L + t];
            norm2[i] = sum;
        }
        bool rotated = false;
        for (int i = 0; i + 1 < k; ++i) {
            double* a = W + i * L;
            for (int j = i + 1; j < k; ++j) {
                double* b = W + j * L;
                double g = 0.0;
                for (int t = 0; t < L; ++t) g += a[t] * b[t];
                const double alpha = norm2[i], beta = norm2[j];
                if (!(g * g > tol2 * alpha * beta)) continue;  // |g| > tol |a| |b|, squared
                rotated = true;
                // the rotation that zeroes a·b: tan of its angle t, the smaller root of
                // t² + 2ζt − 1 = 0, ζ = (β − α) / 2g
                const double zeta = (beta - alpha) / (2.0 * g);
                const double az = std::fabs(zeta);
                const double t = (zeta >= 0.0 ? 1.0 : -1.0) /
                                 (az > ZETA_BIG ? 2.0 * az : az + std::sqrt(1.0 + zeta * zeta));
                const double c = 1.0 / std::sqrt(1.0 + t * t);
                const double sn = c * t;
                for (int u = 0; u < L; ++u) {
                    const double x = a[u], y = b[u];
                    a[u] = c * x - sn * y;
                    b[u] = sn * x + c * y;
                }
                norm2[i] = alpha - t * g;
                norm2[j] = beta + t * g;
            }
        }
        if (!rotated) return;
    }
}

}  // namespace detail

//! The min(m, n) singular values of the row-major m x n matrix A into s, largest first.
//! min(m, n) <= MAX_SINGULAR. W: scratch of m·n doubles. A holding NaN/inf gives NaN values.
//! Returns min(m, n).
KM_HD inline int singular_values(const double* A, int m, int n, double* W, double* s) {
    const bool by_rows = m <= n;
    const int k = by_rows ? m : n;  // the vectors orthogonalised
    const int L = by_rows ? n : m;  // their length
    bool finite = true;
    if (by_rows) {
        for (int i = 0; i < m * n; ++i) {
            W[i] = A[i];
            finite = finite && std::isfinite(A[i]);
        }
    } else {
        for (int i = 0; i < m; ++i) {
            for (int j = 0; j < n; ++j) {
                W[j * m + i] = A[i * n + j];
                finite = finite && std::isfinite(A[i * n + j]);
            }
        }
    }
    if (!finite) {
        for (int i = 0; i < k; ++i) s[i] = NaN;
        return k;
    }
    // a matrix whose largest entry lies outside [2^-SCALE_EXP, 2^SCALE_EXP] is scaled by a
    // power of 2 (exact) to one in [1, 2): its squares neither overflow nor vanish
    double big = 0.0;
    for (int i = 0; i < k * L; ++i) big = std::fmax(big, std::fabs(W[i]));
    int e = 1;
    if (big > 0.0 && (big > std::ldexp(1.0, SCALE_EXP) || big < std::ldexp(1.0, -SCALE_EXP))) {
        std::frexp(big, &e);
        for (int i = 0; i < k * L; ++i) W[i] = std::ldexp(W[i], 1 - e);
    }
    double norm2[MAX_SINGULAR];
    if (L == 6) {  // the Jacobian of a 6-joint arm: the loops unrolled
        detail::jacobi_sweeps<6>(W, k, L, norm2);
    } else {
        detail::jacobi_sweeps<0>(W, k, L, norm2);
    }
    for (int i = 0; i < k; ++i) {  // the norms of the final vectors, not the updated ones
        double sum = 0.0;
        for (int t = 0; t < L; ++t) sum += W[i * L + t] * W[i * L + t];
        s[i] = e == 1 ? std::sqrt(sum) : std::ldexp(std::sqrt(sum), e - 1);
    }
    for (int i = 1; i < k; ++i) {  // insertion sort, largest first
        const double v = s[i];
        int j = i;
        for (; j > 0 && s[j - 1] < v; --j) s[j] = s[j - 1];
        s[j] = v;
    }
    return k;
}

//! Whether two m x n Jacobians (row-major) are equal up to the signs of their columns,
//! each entry within SAME_COLUMNS_TOL of the larger matrix's largest entry: then their
//! singular values are equal (J' = J D, D = diag(±1), has the same J Jᵀ). A spherical
//! wrist's two flips (q4 + π, −q5, q6 + π) are such a pair: column 5 changes sign.
KM_HD inline bool same_up_to_column_signs(const double* A, const double* B, int m, int n) {
    double big = 0.0;
    for (int i = 0; i < m * n; ++i) big = std::fmax(big, std::fmax(std::fabs(A[i]), std::fabs(B[i])));
    const double tol = SAME_COLUMNS_TOL * big;
    for (int j = 0; j < n; ++j) {
        double dot = 0.0;
        for (int i = 0; i < m; ++i) dot += A[i * n + j] * B[i * n + j];
        const double sign = dot < 0.0 ? -1.0 : 1.0;
        for (int i = 0; i < m; ++i) {
            if (!(std::fabs(A[i * n + j] - sign * B[i * n + j]) <= tol)) return false;
        }
    }
    return true;
}

}  // namespace km
