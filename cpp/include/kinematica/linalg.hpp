// Small dense least squares: the step of Levenberg-Marquardt and of the Gauss-Newton
// polishing of IK candidates.
//
// damped_least_squares gives dq minimising |J dq − e|² + λ s |dq|² through the normal
// equations of the smaller side (at most 6 x 6: J has at most 6 rows) solved by Cholesky,
// all on the stack. LAPACK would add a dependency for a 6 x 6 solve.
#pragma once

#include <cmath>

#include "config.hpp"

namespace km {

//! Mean diagonal below which the normal matrix is treated as zero (every column blocked):
//! its damping is then taken as absolute. A pivot that round-off drives to or below zero
//! is floored to it (the step is then huge and an LM iteration rejects it).
constexpr double SCALE_FLOOR = 1e-300;

namespace detail {

//! Solve (G Gᵀ + λ s I) x = b for G (k, m) given by rows (g(i, p)), k <= 6.
template <class Rows>
KM_HD inline void cholesky_solve(const Rows& g, int k, int m, const double* b, double lam,
                                 double* x) {
    double L[6][6];
    double trace = 0.0;
    for (int i = 0; i < k; ++i) {
        for (int j = 0; j <= i; ++j) {
            double t = 0.0;
            for (int p = 0; p < m; ++p) t += g(i, p) * g(j, p);
            L[i][j] = t;
        }
        trace += L[i][i];
    }
    const double scale = trace / k;
    const double damping = lam * (scale > SCALE_FLOOR ? scale : 1.0);
    for (int j = 0; j < k; ++j) {
        double t = L[j][j] + damping;
        for (int p = 0; p < j; ++p) t -= L[j][p] * L[j][p];
        const double d = std::sqrt(t > SCALE_FLOOR ? t : SCALE_FLOOR);
        L[j][j] = d;
        for (int i = j + 1; i < k; ++i) {
            double s = L[i][j];
            for (int p = 0; p < j; ++p) s -= L[i][p] * L[j][p];
            L[i][j] = s / d;
        }
    }
    for (int i = 0; i < k; ++i) {
        double t = b[i];
        for (int p = 0; p < i; ++p) t -= L[i][p] * x[p];
        x[i] = t / L[i][i];
    }
    for (int i = k - 1; i >= 0; --i) {
        double t = x[i];
        for (int p = i + 1; p < k; ++p) t -= L[p][i] * x[p];
        x[i] = t / L[i][i];
    }
}

}  // namespace detail

//! dq (n) minimising |J dq − e|² + λ s |dq|² for J (r x n, row-major, r <= 6), e (r).
//!
//! s is the mean diagonal of the normal matrix, so λ is relative. With r <= n (a redundant
//! or square problem) dq = Jᵀ x with (J Jᵀ + λ s I) x = e; otherwise (JᵀJ + λ s I) dq = Jᵀ e.
KM_HD inline void damped_least_squares(const double* J, int r, int n, const double* e,
                                       double lam, double* dq) {
    if (r <= n) {
        double x[6];
        detail::cholesky_solve([&](int i, int p) { return J[i * n + p]; }, r, n, e, lam, x);
        for (int j = 0; j < n; ++j) {
            double t = 0.0;
            for (int i = 0; i < r; ++i) t += J[i * n + j] * x[i];
            dq[j] = t;
        }
        return;
    }
    double b[6];
    for (int j = 0; j < n; ++j) {
        double t = 0.0;
        for (int i = 0; i < r; ++i) t += J[i * n + j] * e[i];
        b[j] = t;
    }
    detail::cholesky_solve([&](int i, int p) { return J[p * n + i]; }, n, r, b, lam, dq);
}

}  // namespace km
