// Yoshikawa's manipulability without the singular values: the volume σ1·σ2···σk of a small
// matrix's ellipsoid, k = min(m, n), from a determinant.
//
// For a square A the product of its singular values is |det A|; for a wide one (m < n) it is
// √det(A Aᵀ), for a tall one √det(AᵀA) (the Gram matrix of the shorter side, whose
// eigenvalues are the σᵢ²). The determinant comes from Gaussian elimination with partial
// pivoting (the LU factorisation, about k³/3 multiplications: a tenth of a one-sided Jacobi
// SVD of the same matrix), backward stable as LAPACK's getrf is.
#pragma once

#include <cmath>

#include "config.hpp"

namespace km {

//! Largest side of a matrix abs_determinant and volume take (a Jacobian's rows: at most 6).
constexpr int MAX_VOLUME_SIDE = 6;

//! |det A| of the k x k matrix A (row-major, k <= MAX_VOLUME_SIDE), by Gaussian elimination
//! with partial pivoting on a copy; A is not changed. NaN if A holds NaN; 0 exactly where a
//! column has no non-zero pivot left.
KM_HD inline double abs_determinant(const double* A, int k) {
    double U[MAX_VOLUME_SIDE * MAX_VOLUME_SIDE];
    for (int i = 0; i < k * k; ++i) U[i] = A[i];
    double det = 1.0;
    for (int c = 0; c < k; ++c) {
        int pivot = c;
        for (int r = c + 1; r < k; ++r) {
            if (std::fabs(U[r * k + c]) > std::fabs(U[pivot * k + c])) pivot = r;
        }
        const double p = U[pivot * k + c];
        if (std::isnan(p)) return NaN;
        if (p == 0.0) return 0.0;
        if (pivot != c) {
            for (int j = c; j < k; ++j) {
                const double t = U[c * k + j];
                U[c * k + j] = U[pivot * k + j];
                U[pivot * k + j] = t;
            }
        }
        det *= p;
        for (int r = c + 1; r < k; ++r) {
            const double f = U[r * k + c] / p;
            for (int j = c + 1; j < k; ++j) U[r * k + j] -= f * U[c * k + j];
        }
    }
    return std::fabs(det);
}

//! σ1·σ2···σk, k = min(m, n), of the m x n matrix A (row-major, m, n <= MAX_VOLUME_SIDE):
//! |det A| when square, else √det of the Gram matrix of its shorter side.
KM_HD inline double volume(const double* A, int m, int n) {
    if (m == n) return abs_determinant(A, m);
    const bool wide = m < n;
    const int k = wide ? m : n, len = wide ? n : m;
    double G[MAX_VOLUME_SIDE * MAX_VOLUME_SIDE];
    for (int i = 0; i < k; ++i) {
        for (int j = 0; j <= i; ++j) {
            double dot = 0.0;
            for (int t = 0; t < len; ++t) {
                dot += wide ? A[i * n + t] * A[j * n + t] : A[t * n + i] * A[t * n + j];
            }
            G[i * k + j] = G[j * k + i] = dot;
        }
    }
    return std::sqrt(abs_determinant(G, k));
}

}  // namespace km
