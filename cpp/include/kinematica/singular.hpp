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
//! Entries within [2^-SCALE_EXP, 2^SCALE_EXP] are used as they are (see singular_values):
//! the convergence test multiplies four of them, which must neither overflow nor vanish.
constexpr int SCALE_EXP = 200;
//! Two Jacobians whose entries agree (up to each column's sign) within this times their
//! largest entry share their singular values (same_up_to_column_signs): the difference
//! moves each value by at most about this times σ1, below the agreement asked of them.
constexpr double SAME_COLUMNS_TOL = 1e-14;

//! Matrices one call of singular_values_lanes works on side by side (one AVX-512 register
//! of doubles, two AVX2 ones): the same operations on every lane, so the compiler turns
//! the loops over lanes into vector instructions.
constexpr int SV_LANES = 8;

namespace detail {

//! One round-robin pair (a, b) of every lane (a[t·LANES + l]): rotated so that a·b = 0
//! where the squared test of JACOBI_TOL fails, left exactly as it is elsewhere (the
//! rotation there is the identity: c = 1, s = 0). With d = β − α and h = √(d² + 4g²)
//! (g = a·b, α, β the squared norms) the rotation's tangent is t = 2g·sign(d) / (|d| + h),
//! the smaller root of t² + 2ζt − 1 = 0, ζ = d / 2g (Rutishauser); its cosine and sine are
//! u/r and v/r, u = |d| + h, v = 2g·sign(d), r = √(u² + v²) = √(2hu). The squared norms
//! are those of the new vectors. Returns whether any lane rotated.
template <int LANES, int LEN>
KM_HD KM_INLINE bool rotate_pair(double* a, double* b, int L_runtime, double tol2, double* alpha,
                                 double* beta) {
    const int L = LEN > 0 ? LEN : L_runtime;
    double g[LANES], c[LANES], sn[LANES];
    for (int l = 0; l < LANES; ++l) g[l] = 0.0;
    for (int t = 0; t < L; ++t) {
        for (int l = 0; l < LANES; ++l) g[l] += a[t * LANES + l] * b[t * LANES + l];
    }
    bool any = false;
    for (int l = 0; l < LANES; ++l) {
        const bool rot = g[l] * g[l] > tol2 * alpha[l] * beta[l];  // |g| > tol |a| |b|
        const double d = beta[l] - alpha[l];
        const double h = rot ? std::sqrt(d * d + 4.0 * g[l] * g[l]) : 0.5;
        const double u = rot ? std::fabs(d) + h : 1.0;  // 2hu = 1: the identity
        const double v = rot ? (d >= 0.0 ? 2.0 * g[l] : -2.0 * g[l]) : 0.0;
        const double inv = 1.0 / std::sqrt(2.0 * h * u);
        c[l] = u * inv;
        sn[l] = v * inv;
        any |= rot;
    }
    if (!any) return false;  // every lane's pair is orthogonal already: nothing to turn
    double na[LANES], nb[LANES];
    for (int l = 0; l < LANES; ++l) na[l] = nb[l] = 0.0;
    for (int t = 0; t < L; ++t) {
        for (int l = 0; l < LANES; ++l) {
            const double x = a[t * LANES + l], y = b[t * LANES + l];
            const double x2 = c[l] * x - sn[l] * y, y2 = sn[l] * x + c[l] * y;
            a[t * LANES + l] = x2;
            b[t * LANES + l] = y2;
            na[l] += x2 * x2;
            nb[l] += y2 * y2;
        }
    }
    for (int l = 0; l < LANES; ++l) {  // an unrotated lane keeps its (identical) norms
        alpha[l] = na[l];
        beta[l] = nb[l];
    }
    return any;
}

//! Squared norms of the k vectors of length L of every lane into norm2[i·LANES + l].
template <int LANES, int LEN>
KM_HD KM_INLINE void squared_norms(const double* W, int k, int L_runtime, double* norm2) {
    const int L = LEN > 0 ? LEN : L_runtime;
    for (int i = 0; i < k; ++i) {
        double* n2 = norm2 + i * LANES;
        for (int l = 0; l < LANES; ++l) n2[l] = 0.0;
        for (int t = 0; t < L; ++t) {
            for (int l = 0; l < LANES; ++l) n2[l] += W[(i * L + t) * LANES + l] * W[(i * L + t) * LANES + l];
        }
    }
}

//! Sweeps of one-sided Jacobi over k <= MAX_SINGULAR vectors of length L in every lane of
//! W (W[(i·L + t)·LANES + l]: entry t of vector i of lane l; LEN: L known at compile time,
//! 0: read from L), pairs in round-robin order (the pairs of a round are disjoint: their
//! rotations do not wait for each other), until a sweep rotates no lane. A lane done
//! earlier goes through the further sweeps unchanged, so every lane ends as it would alone.
template <int LANES, int LEN>
KM_HD KM_INLINE void jacobi_sweeps(double* W, int k, int L_runtime, double* norm2) {
    const int L = LEN > 0 ? LEN : L_runtime;
    const double tol2 = (JACOBI_TOL * L) * (JACOBI_TOL * L);
    const int K = k + (k & 1);  // players of the round robin (an odd k gets a bye)
    squared_norms<LANES, LEN>(W, k, L, norm2);  // kept those of the vectors as they turn
    for (int sweep = 0; sweep < JACOBI_SWEEPS; ++sweep) {
        bool rotated = false;
        for (int round = 0; round + 1 < K; ++round) {
            for (int p = 0; p < K / 2; ++p) {  // the circle method: K − 1 fixed, others turn
                int i = p == 0 ? K - 1 : (round + p) % (K - 1);
                int j = p == 0 ? round : (round + K - 1 - p) % (K - 1);
                if (i > j) {
                    const int swap = i;
                    i = j;
                    j = swap;
                }
                if (j >= k) continue;  // the bye
                rotated |= rotate_pair<LANES, LEN>(W + i * L * LANES, W + j * L * LANES, L, tol2,
                                                   norm2 + i * LANES, norm2 + j * LANES);
            }
        }
        if (!rotated) return;
    }
}

}  // namespace detail

//! The min(m, n) singular values of up to LANES row-major m x n matrices A[0..count) into
//! s[l] (largest first), side by side. min(m, n) <= MAX_SINGULAR; W: scratch of
//! m·n·LANES doubles. A matrix holding NaN/inf gives NaN values. Every matrix's values are
//! those it gets alone (LANES = 1), bit for bit. Returns min(m, n).
template <int LANES>
KM_HD KM_INLINE int singular_values_lanes(const double* const* A, int count, int m, int n, double* W,
                                       double* const* s) {
    const bool by_rows = m <= n;
    const int k = by_rows ? m : n;  // the vectors orthogonalised
    const int L = by_rows ? n : m;  // their length
    bool finite[LANES];
    int e[LANES];
    for (int l = 0; l < LANES; ++l) {
        finite[l] = true;
        e[l] = 1;
        const double* a = l < count ? A[l] : nullptr;
        // entry (i, j) of the matrix is entry t of vector v: (v, t) = (i, j) by rows, (j, i)
        for (int i = 0; i < m; ++i) {
            for (int j = 0; j < n; ++j) {
                const double x = a != nullptr ? a[i * n + j] : 0.0;  // an unused lane: 0
                const int v = by_rows ? i : j, t = by_rows ? j : i;
                W[(v * L + t) * LANES + l] = x;
                finite[l] = finite[l] && std::isfinite(x);
            }
        }
        // a matrix whose largest entry lies outside [2^-SCALE_EXP, 2^SCALE_EXP] is scaled by
        // a power of 2 (exact) to one in [1, 2): the test's products neither overflow nor vanish
        double big = 0.0;
        for (int i = 0; i < k * L; ++i) big = std::fmax(big, std::fabs(W[i * LANES + l]));
        if (finite[l] && big > 0.0 &&
            (big > std::ldexp(1.0, SCALE_EXP) || big < std::ldexp(1.0, -SCALE_EXP))) {
            std::frexp(big, &e[l]);
            for (int i = 0; i < k * L; ++i) W[i * LANES + l] = std::ldexp(W[i * LANES + l], 1 - e[l]);
        }
        if (!finite[l]) {
            for (int i = 0; i < k * L; ++i) W[i * LANES + l] = 0.0;  // kept out of the sweeps
        }
    }
    double norm2[MAX_SINGULAR * LANES];
    if (L == 6) {  // the Jacobian of a 6-joint arm: the loops unrolled
        detail::jacobi_sweeps<LANES, 6>(W, k, L, norm2);
    } else {
        detail::jacobi_sweeps<LANES, 0>(W, k, L, norm2);
    }
    for (int l = 0; l < count; ++l) {
        double* out = s[l];
        for (int i = 0; i < k; ++i) {
            const double r = std::sqrt(norm2[i * LANES + l]);
            out[i] = !finite[l] ? NaN : e[l] == 1 ? r : std::ldexp(r, e[l] - 1);
        }
        for (int i = 1; i < k; ++i) {  // insertion sort, largest first
            const double v = out[i];
            int j = i;
            for (; j > 0 && out[j - 1] < v; --j) out[j] = out[j - 1];
            out[j] = v;
        }
    }
    return k;
}

//! The min(m, n) singular values of the row-major m x n matrix A into s, largest first
//! (singular_values_lanes with one lane). W: scratch of m·n doubles.
KM_HD inline int singular_values(const double* A, int m, int n, double* W, double* s) {
    const double* const a[1] = {A};
    double* const out[1] = {s};
    return singular_values_lanes<1>(a, 1, m, n, W, out);
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
