// Small dense least squares: the step of Levenberg-Marquardt and of the Gauss-Newton
// polishing of IK candidates.
//
// damped_least_squares gives dq minimising |J dq − e|² + λ s |dq|² through the normal
// equations of the smaller side (at most 6 x 6: J has at most 6 rows), all on the stack.
// They are solved by LDLᵀ (a Cholesky factorisation without its square roots: one
// division per pivot, and multiplications by its inverse after). The normal matrix is a
// value of its own (NormalMatrix), so that a search trying several dampings at one point
// forms it once. The sizes are template parameters inside (a switch picks them), so that
// every loop is unrolled. LAPACK would add a dependency for a 6 x 6 solve.
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

//! G = Σ_p g(·, p) g(·, p)ᵀ over the m columns p of a K-row matrix given by g(i, p).
//! Each entry sums its terms in the order of p, as a dot product would.
template <int K, class Entry>
KM_HD inline void gram(const Entry& g, int m, double (&G)[6][6]) {
    #pragma GCC unroll 6
    for (int i = 0; i < K; ++i) {
        #pragma GCC unroll 6
        for (int j = 0; j <= i; ++j) G[i][j] = 0.0;
    }
    #pragma GCC unroll 6
    for (int p = 0; p < m; ++p) {
        double col[K];
        #pragma GCC unroll 6
        for (int i = 0; i < K; ++i) col[i] = g(i, p);
        #pragma GCC unroll 6
        for (int i = 0; i < K; ++i) {
            #pragma GCC unroll 6
            for (int j = 0; j <= i; ++j) G[i][j] += col[i] * col[j];
        }
    }
}

//! Solve (G + δ I) x = b, G (K x K) symmetric (lower triangle), by LDLᵀ. A pivot at or
//! below SCALE_FLOOR (round-off, or NaN) is taken as SCALE_FLOOR.
template <int K>
KM_HD inline void ldl_solve(const double (&G)[6][6], double damping, const double* b, double* x) {
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

//! Call f(std::integral_constant-like tag) with K = k in 1..6 as a compile-time size.
template <int K>
struct Size {
    static constexpr int value = K;
};
template <class F>
KM_HD inline void with_size(int k, const F& f) {
    switch (k) {
        case 1: f(Size<1>{}); break;
        case 2: f(Size<2>{}); break;
        case 3: f(Size<3>{}); break;
        case 4: f(Size<4>{}); break;
        case 5: f(Size<5>{}); break;
        default: f(Size<6>{}); break;
    }
}

}  // namespace detail

//! The normal matrix of J (r x n, row-major, 1 <= r <= 6) into N.
KM_HD inline void normal_matrix(const double* J, int r, int n, NormalMatrix& N) {
    N.wide = r <= n;
    N.k = N.wide ? r : n;
    detail::with_size(N.k, [&](auto size) {
        constexpr int K = decltype(size)::value;
        if (N.wide) {
            detail::gram<K>([&](int i, int p) { return J[i * n + p]; }, n, N.G);
        } else {
            detail::gram<K>([&](int i, int p) { return J[p * n + i]; }, r, N.G);
        }
        double trace = 0.0;
        for (int i = 0; i < K; ++i) trace += N.G[i][i];
        const double s = trace / K;
        N.scale = s > SCALE_FLOOR ? s : 1.0;
    });
}

//! dq (n) minimising |J dq − e|² + λ s |dq|², from N = normal_matrix(J): with r <= n
//! dq = Jᵀ x, (J Jᵀ + λ s I) x = e; otherwise (JᵀJ + λ s I) dq = Jᵀ e.
KM_HD inline void damped_step(const NormalMatrix& N, const double* J, int r, int n,
                              const double* e, double lam, double* dq) {
    const double damping = lam * N.scale;
    detail::with_size(N.k, [&](auto size) {
        constexpr int K = decltype(size)::value;
        if (N.wide) {
            double x[K];
            detail::ldl_solve<K>(N.G, damping, e, x);
            for (int j = 0; j < n; ++j) {
                double t = 0.0;
                for (int i = 0; i < K; ++i) t += J[i * n + j] * x[i];
                dq[j] = t;
            }
            return;
        }
        double b[K];
        for (int j = 0; j < K; ++j) {
            double t = 0.0;
            for (int i = 0; i < r; ++i) t += J[i * n + j] * e[i];
            b[j] = t;
        }
        detail::ldl_solve<K>(N.G, damping, b, dq);
    });
}

//! dq (n) minimising |J dq − e|² + λ s |dq|² for J (r x n, row-major, r <= 6), e (r).
//!
//! s is the mean diagonal of the normal matrix, so λ is relative. With r <= n (a redundant
//! or square problem) dq = Jᵀ x with (J Jᵀ + λ s I) x = e; otherwise (JᵀJ + λ s I) dq = Jᵀ e.
KM_HD inline void damped_least_squares(const double* J, int r, int n, const double* e,
                                       double lam, double* dq) {
    NormalMatrix N;
    normal_matrix(J, r, n, N);
    damped_step(N, J, r, n, e, lam, dq);
}

}  // namespace km
