// Eigenvalues of a small dense real matrix, without eigenvectors: balancing, reduction to
// Hessenberg form by stabilised elementary similarities, then Francis' double-shift QR.
//
// The classic EISPACK sequence (balanc, elmhes, hqr; as in Numerical Recipes 11.5-11.6),
// for a fixed size on the stack. Eigen's EigenSolver does the same reduction and
// iteration with Householder reflectors through its block expressions: about twice the
// time at 16 x 16 and 24 x 24 (measured), where the general 6R spends most of its time.
// Balancing (exact powers of 2, no round-off) equalises row and column norms, which the
// companion matrices of the general 6R need: their entries span orders of magnitude.
#pragma once

#include <cmath>
#include <utility>

#include "config.hpp"

namespace km::eigen {

//! Francis steps per eigenvalue (or pair) before the iteration is declared failed. EISPACK
//! stops at 30; a cluster of nearly equal complex pairs (the general 6R on an arm near a
//! degenerate one) was seen to need more, so the limit is LAPACK's whole budget
//! (dlahqr: 30 per row of the matrix), and failing is kept for a true cycle.
constexpr int QR_STEPS = 30 * 24;
//! Every this many steps without a deflation an exceptional shift breaks a cycle
//! (EISPACK's and LAPACK's 10).
constexpr int EXCEPTIONAL = 10;

//! a := D⁻¹ a D for a diagonal D of powers of 2 that makes each row's and column's
//! off-diagonal norms within a factor 2 of each other (eigenvalues unchanged, exactly).
template <int N>
inline void balance(double (&a)[N][N]) {
    constexpr double RADIX = 2.0;
    bool done = false;
    while (!done) {
        done = true;
        for (int i = 0; i < N; ++i) {
            double r = 0.0, c = 0.0;
            for (int j = 0; j < N; ++j) {
                if (j == i) continue;
                c += std::fabs(a[j][i]);
                r += std::fabs(a[i][j]);
            }
            const double s = c + r;
            if (c == 0.0 || r == 0.0 || !std::isfinite(s)) continue;
            double f = 1.0;
            while (c < r / RADIX) f *= RADIX, c *= RADIX * RADIX;
            while (c > r * RADIX) f /= RADIX, c /= RADIX * RADIX;
            if ((c + r) / f < 0.95 * s) {
                done = false;
                for (int j = 0; j < N; ++j) a[i][j] /= f;
                for (int j = 0; j < N; ++j) a[j][i] *= f;
            }
        }
    }
}

//! a := an upper Hessenberg matrix similar to it (Gaussian elimination with row pivoting,
//! each elimination undone on the columns: a similarity); entries below the subdiagonal 0.
template <int N>
inline void hessenberg(double (&a)[N][N]) {
    for (int m = 1; m < N - 1; ++m) {
        double x = 0.0;
        int p = m;
        for (int j = m; j < N; ++j) {
            if (std::fabs(a[j][m - 1]) > std::fabs(x)) x = a[j][m - 1], p = j;
        }
        if (p != m) {
            for (int j = m - 1; j < N; ++j) std::swap(a[p][j], a[m][j]);
            for (int j = 0; j < N; ++j) std::swap(a[j][p], a[j][m]);
        }
        if (x == 0.0) continue;
        for (int i = m + 1; i < N; ++i) {
            const double y = a[i][m - 1] / x;
            a[i][m - 1] = 0.0;
            if (y == 0.0) continue;
            for (int j = m; j < N; ++j) a[i][j] -= y * a[m][j];
            for (int j = 0; j < N; ++j) a[j][m] += y * a[j][i];
        }
    }
}

namespace detail {
inline double with_sign(double a, double b) { return b >= 0.0 ? std::fabs(a) : -std::fabs(a); }
}  // namespace detail

//! The eigenvalues re[k] + i im[k] of the upper Hessenberg matrix h (destroyed): Francis'
//! double-shift QR on the active block, deflating a subdiagonal entry negligible next to
//! its neighbours on the diagonal. Complex pairs come out together (im of opposite signs).
//! False when an eigenvalue took more than QR_STEPS steps (re, im then incomplete).
template <int N>
inline bool hessenberg_eigenvalues(double (&h)[N][N], double* re, double* im) {
    double norm = 0.0;
    for (int i = 0; i < N; ++i)
        for (int j = (i > 0 ? i - 1 : 0); j < N; ++j) norm += std::fabs(h[i][j]);
    int nn = N - 1;   // the last row of the active block
    double shift = 0.0;  // the exceptional shifts' sum, taken out of the diagonal
    double p = 0.0, q = 0.0, r = 0.0, s = 0.0, w = 0.0, x = 0.0, y = 0.0, z = 0.0;
    while (nn >= 0) {
        int steps = 0, l = 0;
        do {
            // l: the first row of the active block (h[l][l-1] negligible)
            for (l = nn; l >= 1; --l) {
                s = std::fabs(h[l - 1][l - 1]) + std::fabs(h[l][l]);
                if (s == 0.0) s = norm;
                if (std::fabs(h[l][l - 1]) + s == s) {
                    h[l][l - 1] = 0.0;
                    break;
                }
            }
            x = h[nn][nn];
            if (l == nn) {  // one root found
                re[nn] = x + shift;
                im[nn--] = 0.0;
                continue;
            }
            y = h[nn - 1][nn - 1];
            w = h[nn][nn - 1] * h[nn - 1][nn];
            if (l == nn - 1) {  // two roots found: the 2 x 2 block's
                p = 0.5 * (y - x);
                q = p * p + w;
                z = std::sqrt(std::fabs(q));
                x += shift;
                if (q >= 0.0) {  // a real pair
                    z = p + detail::with_sign(z, p);
                    re[nn - 1] = re[nn] = x + z;
                    if (z != 0.0) re[nn] = x - w / z;
                    im[nn - 1] = im[nn] = 0.0;
                } else {  // a complex pair
                    re[nn - 1] = re[nn] = x + p;
                    im[nn - 1] = -z;
                    im[nn] = z;
                }
                nn -= 2;
                continue;
            }
            if (steps == QR_STEPS) return false;
            if (steps > 0 && steps % EXCEPTIONAL == 0) {  // exceptional shift
                shift += x;
                for (int i = 0; i <= nn; ++i) h[i][i] -= x;
                s = std::fabs(h[nn][nn - 1]) + std::fabs(h[nn - 1][nn - 2]);
                y = x = 0.75 * s;
                w = -0.4375 * s * s;
            }
            ++steps;
            // m: where two consecutive small subdiagonal entries let the step start
            int m = nn - 2;
            for (; m >= l; --m) {
                z = h[m][m];
                r = x - z;
                s = y - z;
                p = (r * s - w) / h[m + 1][m] + h[m][m + 1];
                q = h[m + 1][m + 1] - z - r - s;
                r = h[m + 2][m + 1];
                s = std::fabs(p) + std::fabs(q) + std::fabs(r);
                p /= s;
                q /= s;
                r /= s;
                if (m == l) break;
                const double u = std::fabs(h[m][m - 1]) * (std::fabs(q) + std::fabs(r));
                const double v = std::fabs(p) * (std::fabs(h[m - 1][m - 1]) + std::fabs(z) +
                                                 std::fabs(h[m + 1][m + 1]));
                if (u + v == v) break;
            }
            for (int i = m + 2; i <= nn; ++i) {
                h[i][i - 2] = 0.0;
                if (i != m + 2) h[i][i - 3] = 0.0;
            }
            // the double-shift step: a bulge chased down by 3 x 3 Householder reflectors
            for (int k = m; k <= nn - 1; ++k) {
                if (k != m) {
                    p = h[k][k - 1];
                    q = h[k + 1][k - 1];
                    r = k != nn - 1 ? h[k + 2][k - 1] : 0.0;
                    x = std::fabs(p) + std::fabs(q) + std::fabs(r);
                    if (x != 0.0) p /= x, q /= x, r /= x;
                }
                s = detail::with_sign(std::sqrt(p * p + q * q + r * r), p);
                if (s == 0.0) continue;
                if (k == m) {
                    if (l != m) h[k][k - 1] = -h[k][k - 1];
                } else {
                    h[k][k - 1] = -s * x;
                }
                p += s;
                x = p / s;
                y = q / s;
                z = r / s;
                q /= p;
                r /= p;
                for (int j = k; j <= nn; ++j) {  // rows k, k+1, k+2
                    p = h[k][j] + q * h[k + 1][j];
                    if (k != nn - 1) {
                        p += r * h[k + 2][j];
                        h[k + 2][j] -= p * z;
                    }
                    h[k + 1][j] -= p * y;
                    h[k][j] -= p * x;
                }
                const int last = nn < k + 3 ? nn : k + 3;
                for (int i = l; i <= last; ++i) {  // columns k, k+1, k+2
                    p = x * h[i][k] + y * h[i][k + 1];
                    if (k != nn - 1) {
                        p += z * h[i][k + 2];
                        h[i][k + 2] -= p * r;
                    }
                    h[i][k + 1] -= p * q;
                    h[i][k] -= p;
                }
            }
        } while (l < nn - 1);
    }
    return true;
}

//! The eigenvalues re[k] + i im[k] of a (destroyed); false when the iteration failed.
template <int N>
inline bool eigenvalues(double (&a)[N][N], double* re, double* im) {
    balance(a);
    hessenberg(a);
    return hessenberg_eigenvalues(a, re, im);
}

}  // namespace km::eigen
