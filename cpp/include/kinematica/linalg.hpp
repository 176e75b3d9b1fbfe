// Small dense least squares: the step of Levenberg-Marquardt and of the Gauss-Newton
// polishing of IK candidates.
//
// damped_least_squares gives dq minimising |J dq − e|² + λ s |dq|² through the normal
// equations of the smaller side (at most 6 x 6: J has at most 6 rows), all on the stack.
// They are solved by LDLᵀ (a Cholesky factorisation without its square roots: one
// division per pivot, and multiplications by its inverse after). The normal matrix is a
// value of its own (NormalMatrix), so that a search trying several dampings at one point
// forms it once. The sizes are template parameters inside (a switch picks them), so that
// every loop is unrolled; everything is inlined into its caller, so that the AVX2 and
// AVX-512 copies of a solver's entry point (KM_CLONES) hold their own copy of it. LAPACK
// would add a dependency for a 6 x 6 solve.
#pragma once

#include <cmath>

#include "config.hpp"

namespace km {

//! Mean diagonal below which the normal matrix is treated as zero (every column blocked):
//! its damping is then taken as absolute. A pivot that round-off drives to or below zero
//! is floored to it (the step is then huge and an LM iteration rejects it).
constexpr double SCALE_FLOOR = 1e-300;

//! The normal matrix of a least-squares problem J dq ≈ e, J (r x n, r <= 6), on its
//! smaller side: G = J Jᵀ (r x r) when r <= n, else Jᵀ J (n x n); lower triangle.
struct NormalMatrix {
    int k = 0;            //!< its size: min(r, n)
    bool wide = true;     //!< r <= n: G = J Jᵀ (the step is Jᵀ x)
    double scale = 1.0;   //!< its mean diagonal s (1 where below SCALE_FLOOR)
    double G[6][6] = {};  //!< lower triangle
};

namespace detail {

//! G = Σ_p g_p g_pᵀ over the m columns g_p of a K-row matrix, entry (i, p) at
//! A[i * row + p * col]. Each entry sums its terms in the order of p, as a dot product.
template <int K>
KM_HD KM_INLINE void gram(const double* A, int row, int col, int m, double (&G)[6][6]) {
    #pragma GCC unroll 6
    for (int i = 0; i < K; ++i) {
        #pragma GCC unroll 6
        for (int j = 0; j <= i; ++j) G[i][j] = 0.0;
    }
    for (int p = 0; p < m; ++p) {
        double g[K];
        #pragma GCC unroll 6
        for (int i = 0; i < K; ++i) g[i] = A[i * row + p * col];
        #pragma GCC unroll 6
        for (int i = 0; i < K; ++i) {
            #pragma GCC unroll 6
            for (int j = 0; j <= i; ++j) G[i][j] += g[i] * g[j];
        }
    }
}

//! Solve (G + δ I) x = b, G (K x K) symmetric (lower triangle), by LDLᵀ. A pivot at or
//! below SCALE_FLOOR (round-off, or NaN) is taken as SCALE_FLOOR.
template <int K>
KM_HD KM_INLINE void ldl_solve(const double (&G)[6][6], double damping, const double* b, double* x) {
    double L[K][K];  // L[i][p] (p < i): the unit lower factor; L[i][i]: 1 / D_i
    double LD[K][K];  // L[i][p] D_p
    #pragma GCC unroll 6
    for (int j = 0; j < K; ++j) {
        double t = G[j][j] + damping;
        #pragma GCC unroll 6
        for (int p = 0; p < j; ++p) t -= LD[j][p] * L[j][p];
        const double inv = 1.0 / (t > SCALE_FLOOR ? t : SCALE_FLOOR);
        L[j][j] = inv;
        #pragma GCC unroll 6
        for (int i = j + 1; i < K; ++i) {
            double s = G[i][j];
            #pragma GCC unroll 6
            for (int p = 0; p < j; ++p) s -= LD[i][p] * L[j][p];
            LD[i][j] = s;
            L[i][j] = s * inv;
        }
    }
    double y[K];
    #pragma GCC unroll 6
    for (int i = 0; i < K; ++i) {
        double t = b[i];
        #pragma GCC unroll 6
        for (int p = 0; p < i; ++p) t -= L[i][p] * y[p];
        y[i] = t;
    }
    #pragma GCC unroll 6
    for (int i = K - 1; i >= 0; --i) {
        double t = y[i] * L[i][i];
        #pragma GCC unroll 6
        for (int p = i + 1; p < K; ++p) t -= L[p][i] * x[p];
        x[i] = t;
    }
}

//! normal_matrix for a normal matrix of K x K.
template <int K>
struct NormalOf {
    KM_HD KM_INLINE static void run(const double* J, int r, int n, NormalMatrix& N) {
        if (N.wide) {
            gram<K>(J, n, 1, n, N.G);
        } else {
            gram<K>(J, 1, n, r, N.G);
        }
        double trace = 0.0;
        for (int i = 0; i < K; ++i) trace += N.G[i][i];
        const double s = trace / K;
        N.scale = s > SCALE_FLOOR ? s : 1.0;
    }
};

//! damped_step for a normal matrix of K x K.
template <int K>
struct StepOf {
    KM_HD KM_INLINE static void run(const NormalMatrix& N, const double* J, int r, int n,
                                    const double* e, double damping, double* dq) {
        if (N.wide) {
            double x[K];
            ldl_solve<K>(N.G, damping, e, x);
            for (int j = 0; j < n; ++j) {
                double t = 0.0;
                #pragma GCC unroll 6
                for (int i = 0; i < K; ++i) t += J[i * n + j] * x[i];
                dq[j] = t;
            }
            return;
        }
        double b[K];
        #pragma GCC unroll 6
        for (int j = 0; j < K; ++j) {
            double t = 0.0;
            for (int i = 0; i < r; ++i) t += J[i * n + j] * e[i];
            b[j] = t;
        }
        ldl_solve<K>(N.G, damping, b, dq);
    }
};

//! Op<k>::run(args...) for a size k in 1..6 known at run time only: each size compiled
//! apart, its loops unrolled.
template <template <int> class Op, class... Args>
KM_HD KM_INLINE void with_size(int k, Args&&... args) {
    switch (k) {
        case 1: Op<1>::run(args...); break;
        case 2: Op<2>::run(args...); break;
        case 3: Op<3>::run(args...); break;
        case 4: Op<4>::run(args...); break;
        case 5: Op<5>::run(args...); break;
        default: Op<6>::run(args...); break;
    }
}

}  // namespace detail

//! The normal matrix of J (r x n, row-major, 1 <= r <= 6) into N.
KM_HD KM_INLINE void normal_matrix(const double* J, int r, int n, NormalMatrix& N) {
    N.wide = r <= n;
    N.k = N.wide ? r : n;
    detail::with_size<detail::NormalOf>(N.k, J, r, n, N);
}

//! dq (n) minimising |J dq − e|² + λ s |dq|², from N = normal_matrix(J): with r <= n
//! dq = Jᵀ x, (J Jᵀ + λ s I) x = e; otherwise (JᵀJ + λ s I) dq = Jᵀ e.
KM_HD KM_INLINE void damped_step(const NormalMatrix& N, const double* J, int r, int n,
                                 const double* e, double lam, double* dq) {
    detail::with_size<detail::StepOf>(N.k, N, J, r, n, e, lam * N.scale, dq);
}

//! dq (n) minimising |J dq − e|² + λ s |dq|² for J (r x n, row-major, r <= 6), e (r).
//!
//! s is the mean diagonal of the normal matrix, so λ is relative. With r <= n (a redundant
//! or square problem) dq = Jᵀ x with (J Jᵀ + λ s I) x = e; otherwise (JᵀJ + λ s I) dq = Jᵀ e.
KM_HD KM_INLINE void damped_least_squares(const double* J, int r, int n, const double* e,
                                          double lam, double* dq) {
    NormalMatrix N;
    normal_matrix(J, r, n, N);
    damped_step(N, J, r, n, e, lam, dq);
}

}  // namespace km
