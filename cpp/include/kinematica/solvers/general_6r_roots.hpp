// The real roots of det M(x) for the general 6R: M(x) = A0 + A1 x + A2 x², 12 x 12.
//
// det M has degree 24, but (1 + x²)⁴ divides it: the half-angle substitution of the
// elimination (general_6r.hpp) leaves 8 roots at x = ±i that no configuration makes, and
// M(±i) has a null space of dimension 4 (a semi-simple eigenvalue: measured 4 pivots at
// round-off and the fifth 1e-4 to 1e-3 of the largest on random arms and poses). With
// C = [[0, I], [-A2⁻¹A0, -A2⁻¹A1]] the 24 x 24 companion matrix (C [v; x v] = x [v; x v]
// exactly when M(x) v = 0), the null vectors v of M(i) give C's real invariant subspace
// Z (24 x 8) of those 8 roots: the real and imaginary parts of [v; i v]. Eliminating it
// (Z's rows permuted, Z = [Z1; Z2], then T = [[Z1, 0], [Z2, I]] gives T⁻¹ C T =
// [[S, ·], [0, C22 - Z2 Z1⁻¹ C12]]) leaves a 16 x 16 matrix whose eigenvalues are the 16
// roots a configuration can make: a third of the work of the 24 x 24 eigenproblem.
//
// Some exact arms' det M has (1 + x²)^m, m > 4 (M(i)'s null space of dimension m: a
// Franka Panda held at q1, m = 6): the same deflation leaves 24 - 2m roots. Where M(i)'s
// null space is below 4 dimensions or above MAX_NULLITY (SPURIOUS_TOL), the 24 x 24
// problem is solved as it is: its roots at ±i are then no real root (REAL_ROOT_TOL).
//
// Where A2 is ill-conditioned (no companion matrix: an arm near one whose elimination
// degenerates, det M(x) ≡ 0 for the exact UR5, so that M(x) is nearly singular for every
// x), the roots are the generalized eigenvalues α/β of the 24 x 24 linearization
// x [[I, 0], [0, A2]] - [[0, I], [-A0, -A1]] by the QZ algorithm (real_roots_qz): no
// inverse is formed, and a root at x = ∞ (β = 0) is q' = shift + π. A singular pencil's
// regular eigenvalues stay well determined under a small generic perturbation (De Terán,
// Dopico and Moro, SIAM J. Matrix Anal. Appl. 2008), its other eigenvalues can be
// anywhere: those give candidates that close no loop, which the closure and the shared
// check drop (measured on calibrated UR5s: the generating root to 1e-11..1e-7).
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>

#include "../eigenvalues.hpp"

namespace km::general6r {

constexpr int SIZE = 12;      //!< the matrix M(x)
constexpr int ROOTS = 24;     //!< degree of det M(x)
constexpr int SPURIOUS = 8;   //!< roots of det M at x = ±i: 4 each
constexpr int GENUINE = ROOTS - SPURIOUS;

//! An eigenvalue x is a real root when |Im x| <= this · (1 + |x|). Generous: a double
//! root splits into a complex pair of imaginary part ~ sqrt(round-off), whose real part is
//! still a candidate the check polishes; a genuinely complex root that passes is rejected
//! by the check (its FK misses the target).
constexpr double REAL_ROOT_TOL = 1e-4;
//! A complex pair x0 ± i s with s beyond REAL_ROOT_TOL but at most this · (1 + |x|) gives
//! the two candidates x0 - s and x0 + s. Two real roots close together (two solutions
//! of nearly the same q'6: elbow up and down near a stretched arm) move by round-off over
//! their distance, and on an arm near a degenerate one (a calibrated UR: the eigenvalues
//! are good to 1e-4..1e-3 only) a pair at x0 ± s can come out as x0 ± i s, of the same
//! size s. Each candidate is taken to a solution near it or dropped by the Newton step
//! and the check (general_6r.hpp).
constexpr double SPLIT_ROOT_TOL = 1e-2;
//! M(i)'s null space is the span of its full-pivot LU's last columns from the first pivot
//! at most this times the largest (the spurious roots' null space, at round-off: 1e-16
//! measured; the pivot before it 1e-4 to 1e-3 on random arms).
constexpr double SPURIOUS_TOL = 1e-9;
//! That null space is deflated when its dimension m is 4 (every arm's (1 + x²)⁴), or up to
//! this where its first pivot is at round-off (EXTRA_NULL_TOL): some exact arms' det M has
//! (1 + x²)^m (a Franka Panda held at q1: m = 6, 12 genuine roots). Else (nullity below
//! 4: the elimination's structure lost; more, not at round-off: an arm near one whose
//! pencil is singular, a UR5 tilted by 5e-10 rad) the 24 x 24 problem is solved whole.
constexpr int MAX_NULLITY = 6;
//! A null space of M(i) beyond 4 dimensions is deflated only where its first pivot is at
//! most this times the largest: round-off (the Panda held at q1: 2e-16); a near-degenerate
//! arm's extra directions lie at about its distance from degenerate (1e-10 and more), and
//! are not an invariant subspace of the roots at ±i.
constexpr double EXTRA_NULL_TOL = 1e-13;
//! Z, the real basis of C's invariant subspace of the roots at ±i (2 columns per null
//! direction of M(i)).
using SpuriousBasis = Eigen::Matrix<double, ROOTS, 2 * MAX_NULLITY>;

using Matrix12 = Eigen::Matrix<double, SIZE, SIZE>;
using Vector12 = Eigen::Matrix<double, SIZE, 1>;

//! The computed pencil's coefficients A0, A1, A2 are taken to differ from the arm's exact
//! ones by at most this times their norms: their entries are sums of products of the
//! loop's lengths (scaled to about 1) and sines, made from grid values by fixed 3 x 3
//! maps and projected on N's rows (orthonormal), each a few tens of roundings of numbers
//! of the pencil's size; this allows 4,500 units of round-off.
constexpr double PENCIL_EPS = 1e-12;
//! det M(x) has no real root when every eigenvalue x of the pencil lies this many times
//! its error bound from the real axis (certifies): the bound is first order,
//! κ(x) (η(x) + PENCIL_EPS), and a factor of 100 leaves room for its second-order term
//! and for the estimate of κ.
constexpr double CERTIFY_MARGIN = 100.0;

//! The pencil's eigenvalues as the eigenproblem gave them (deflated: the 24 - 2m roots a
//! configuration can make, 16 for m = 4); n = 0 where they were not kept (the 24 x 24
//! problem or QZ).
struct Spectrum {
    int n = 0;
    std::complex<double> x[GENUINE];
};

//! How far an eigenvalue x of M(x) = A0 + A1 x + A2 x² lies from the real axis, in units
//! of its first-order error bound: value = |Im x| / (κ (η + PENCIL_EPS)), with
//! η = ‖M(x) v‖ / (α ‖v‖) the backward error of x with its right null vector v,
//! α = ‖A0‖ + |x| ‖A1‖ + |x|² ‖A2‖, and κ = α ‖v‖ ‖w‖ / |wᴴ M'(x) v| its condition number
//! (w the left null vector; Tisseur, Linear Algebra Appl. 309, 2000: a simple eigenvalue
//! moves by at most κ times the coefficients' relative change, to first order).
struct RootMargin {
    double value = std::numeric_limits<double>::infinity();
    double kappa = 0.0;
    double eta = 0.0;
};

//! The RootMargin of the eigenvalue x. v and w by one step of inverse iteration each from
//! M(x)'s partial-pivot LU (M(x) is singular to about the eigenvalue's error, so
//! M⁻¹ b and M⁻ᴴ b are its null vectors to about that over the next singular value, for
//! any b not orthogonal to them: b = (1, ..., 1)); η is the backward error of x with the v
//! found. value 0 for a real x, NaN where the LU breaks down (a pivot exactly 0).
inline RootMargin real_axis_margin(const Matrix12* A, std::complex<double> x) {
    using Complex = std::complex<double>;
    using ComplexMatrix = Eigen::Matrix<Complex, SIZE, SIZE>;
    using ComplexVector = Eigen::Matrix<Complex, SIZE, 1>;
    if (!(x.imag() != 0.0)) return RootMargin{0.0};
    ComplexMatrix M, slope_matrix;  // M(x) and M'(x) = A1 + 2 x A2
    const Complex x2 = x * x, twice = 2.0 * x;
    for (int c = 0; c < SIZE; ++c)
        for (int r = 0; r < SIZE; ++r) {
            M(r, c) = A[0](r, c) + x * A[1](r, c) + x2 * A[2](r, c);
            slope_matrix(r, c) = A[1](r, c) + twice * A[2](r, c);
        }
    const Eigen::PartialPivLU<ComplexMatrix> lu(M);
    const ComplexVector ones = ComplexVector::Ones();
    ComplexVector v = lu.solve(ones);
    ComplexVector w = lu.adjoint().solve(ones);  // wᴴ M ≈ 0
    v /= v.norm();
    w /= w.norm();
    const double r = std::abs(x);
    const double alpha = A[0].norm() + r * (A[1].norm() + r * A[2].norm());
    const Complex slope = w.dot(slope_matrix * v);  // wᴴ M'(x) v
    RootMargin out;
    out.eta = (M * v).norm() / alpha;
    out.kappa = alpha / std::abs(slope);
    out.value = std::fabs(x.imag()) / (out.kappa * (out.eta + PENCIL_EPS));
    return out;
}

//! The least RootMargin of the spectrum's eigenvalues (one of each conjugate pair); value
//! 0 when one is real or the pairs do not match, NaN where one's is.
inline RootMargin spectrum_margin(const Matrix12* A, const Spectrum& s) {
    int upper = 0, lower = 0;
    RootMargin least;
    for (int k = 0; k < s.n; ++k) {
        const double im = s.x[k].imag();
        if (im < 0.0) {
            ++lower;
            continue;
        }
        if (!(im > 0.0)) return RootMargin{0.0};
        ++upper;
        const RootMargin m = real_axis_margin(A, s.x[k]);
        if (!(m.value >= least.value)) least = m;  // (NaN kept)
    }
    if (upper != lower) least.value = 0.0;
    return least;
}

//! True when the margin (spectrum_margin) proves det M(x) has no real root: every
//! eigenvalue CERTIFY_MARGIN times its error bound from the real axis.
inline bool certifies(double margin) { return margin >= CERTIFY_MARGIN; }

//! An eigenvalue x of the companion matrix is taken as a real root: see REAL_ROOT_TOL.
inline bool real_root(std::complex<double> x) {
    return std::fabs(x.imag()) <= REAL_ROOT_TOL * (1.0 + std::abs(x));
}

//! The candidates of one eigenvalue α/β (β >= 0; β = 0: x = ∞) into roots from `found`:
//! a real root (REAL_ROOT_TOL), or, for the member of a nearly real pair with Im x > 0, the
//! pair's two (SPLIT_ROOT_TOL, `split` true); the new count. The tests are the companion
//! matrix's, |Im x| <= tol (1 + |x|), times β: |Im α| <= tol (β + |α|).
inline int take_root(std::complex<double> alpha, double beta, double* roots, bool* split, int found) {
    const double im = alpha.imag(), size = beta + std::abs(alpha);
    //! x of a root at infinity: q' = shift + π (tan of either sign of it)
    constexpr double INFINITE_ROOT = 1e300;
    const auto ratio = [beta](double a) {
        return std::fabs(a) < beta * INFINITE_ROOT ? a / beta : std::copysign(INFINITE_ROOT, a);
    };
    if (std::fabs(im) <= REAL_ROOT_TOL * size) {
        if (split != nullptr) split[found] = false;
        roots[found++] = ratio(alpha.real());
    } else if (im > 0.0 && im <= SPLIT_ROOT_TOL * size) {
        if (split != nullptr) split[found] = split[found + 1] = true;
        roots[found++] = ratio(alpha.real() - im);  // (its conjugate, Im < 0, is skipped)
        roots[found++] = ratio(alpha.real() + im);
    }
    return found;
}

//! The real basis Z (24 x 2m) of C's invariant subspace of the roots x = ±i, from M(i)'s
//! elimination with full pivoting (real and imaginary parts apart: std::complex's
//! products check for infinities, at several times the cost); returns m, the dimension of
//! M(i)'s null space (its pivots from the first at most SPURIOUS_TOL times the largest),
//! or 0 (Z untouched) when that is below SPURIOUS / 2, above MAX_NULLITY, or above
//! SPURIOUS / 2 with its first pivot above EXTRA_NULL_TOL. `ratios`, when
//! given: the last pivot above the tolerance and the first below it (0 when none is),
//! their moduli over the first's.
inline int spurious_subspace(const Matrix12* A, SpuriousBasis& Z, double* ratios = nullptr) {
    double re[SIZE][SIZE], im[SIZE][SIZE];  // M(i) = A0 - A2 + i A1
    for (int r = 0; r < SIZE; ++r)
        for (int c = 0; c < SIZE; ++c) {
            re[r][c] = A[0](r, c) - A[2](r, c);
            im[r][c] = A[1](r, c);
        }
    int col[SIZE];  // column k of the eliminated matrix is M(i)'s column col[k]
    for (int c = 0; c < SIZE; ++c) col[c] = c;
    double first = 0.0, last = 0.0, small = 0.0;  // squared moduli of pivots
    int rank = SIZE;
    for (int k = 0; k < SIZE; ++k) {
        int pr = k, pc = k;
        double big = -1.0;
        for (int r = k; r < SIZE; ++r)
            for (int c = k; c < SIZE; ++c) {
                const double m = re[r][c] * re[r][c] + im[r][c] * im[r][c];
                if (m > big) big = m, pr = r, pc = c;
            }
        if (k == 0) first = big;
        if (!(big > SPURIOUS_TOL * SPURIOUS_TOL * first)) {  // the null space begins here
            rank = k;
            small = big;
            break;
        }
        last = big;
        for (int c = 0; c < SIZE; ++c) std::swap(re[k][c], re[pr][c]), std::swap(im[k][c], im[pr][c]);
        for (int r = 0; r < SIZE; ++r) std::swap(re[r][k], re[r][pc]), std::swap(im[r][k], im[r][pc]);
        std::swap(col[k], col[pc]);
        // 1 / pivot
        const double ir = re[k][k] / big, ii = -im[k][k] / big;
        for (int r = k + 1; r < SIZE; ++r) {
            const double lr = re[r][k] * ir - im[r][k] * ii, li = re[r][k] * ii + im[r][k] * ir;
            for (int c = k + 1; c < SIZE; ++c) {
                re[r][c] -= lr * re[k][c] - li * im[k][c];
                im[r][c] -= lr * im[k][c] + li * re[k][c];
            }
        }
    }
    if (ratios != nullptr) {
        ratios[0] = first > 0.0 ? std::sqrt(last / first) : 0.0;
        ratios[1] = first > 0.0 ? std::sqrt(small / first) : 0.0;
    }
    const int nullity = SIZE - rank;
    if (nullity < SPURIOUS / 2 || nullity > MAX_NULLITY) return 0;
    if (nullity > SPURIOUS / 2 && !(small <= EXTRA_NULL_TOL * EXTRA_NULL_TOL * first)) return 0;
    for (int f = 0; f < nullity; ++f) {
        // the null vector with free column rank + f set to 1, the other free ones 0
        double vr[SIZE] = {}, vi[SIZE] = {};
        vr[rank + f] = 1.0;
        for (int i = rank - 1; i >= 0; --i) {
            double tr = -re[i][rank + f], ti = -im[i][rank + f];
            for (int j = i + 1; j < rank; ++j) {
                tr -= re[i][j] * vr[j] - im[i][j] * vi[j];
                ti -= re[i][j] * vi[j] + im[i][j] * vr[j];
            }
            const double d = re[i][i] * re[i][i] + im[i][i] * im[i][i];
            vr[i] = (tr * re[i][i] + ti * im[i][i]) / d;
            vi[i] = (ti * re[i][i] - tr * im[i][i]) / d;
        }
        // w = v in M(i)'s column order; [w; i w]: real part [Re w; -Im w], imaginary [Im w; Re w]
        for (int k = 0; k < SIZE; ++k) {
            const int j = col[k];
            Z(j, 2 * f) = vr[k];
            Z(SIZE + j, 2 * f) = -vi[k];
            Z(j, 2 * f + 1) = vi[k];
            Z(SIZE + j, 2 * f + 1) = vr[k];
        }
    }
    return nullity;
}

//! C with its invariant subspace Z (24 x K) eliminated: D, the (24 - K) x (24 - K) matrix
//! of C's other roots. Z = P [L1; L2] U by partial pivoting (rows `perm[0..K-1]` first);
//! then W = L2 L1⁻¹ (entries of L at most 1) and D = C22 - W C12 over the other rows and
//! columns.
template <int K>
void deflate(const double (&C)[ROOTS][ROOTS], Eigen::Matrix<double, ROOTS, K> Z,
             double (&D)[ROOTS - K][ROOTS - K]) {
    constexpr int N = ROOTS - K;
    int perm[ROOTS];
    for (int i = 0; i < ROOTS; ++i) perm[i] = i;
    for (int k = 0; k < K; ++k) {
        int p = k;
        for (int i = k + 1; i < ROOTS; ++i)
            if (std::fabs(Z(i, k)) > std::fabs(Z(p, k))) p = i;
        if (p != k) {
            Z.row(p).swap(Z.row(k));
            std::swap(perm[p], perm[k]);
        }
        for (int i = k + 1; i < ROOTS; ++i) {
            const double l = Z(i, k) / Z(k, k);
            Z(i, k) = l;
            for (int j = k + 1; j < K; ++j) Z(i, j) -= l * Z(k, j);
        }
    }
    // W (N x K) with W L1 = L2, L1 unit lower triangular: its columns from the last
    double W[N][K];
    for (int r = 0; r < N; ++r) {
        for (int k = K - 1; k >= 0; --k) {
            double t = Z(K + r, k);
            for (int j = k + 1; j < K; ++j) t -= W[r][j] * Z(j, k);
            W[r][k] = t;
        }
    }
    for (int r = 0; r < N; ++r)
        for (int c = 0; c < N; ++c) {
            double t = C[perm[K + r]][perm[K + c]];
            for (int k = 0; k < K; ++k) t -= W[r][k] * C[perm[k]][perm[K + c]];
            D[r][c] = t;
        }
}

//! The eigenvalues of C with its roots at ±i (M(i)'s null space of dimension M, basis Z)
//! deflated: 24 - 2M of them into re, im; false when the iteration failed.
template <int M>
bool deflated_eigenvalues(const double (&C)[ROOTS][ROOTS], const SpuriousBasis& Z, double* re,
                          double* im) {
    constexpr int N = ROOTS - 2 * M;
    double D[N][N];
    deflate<2 * M>(C, Z.template leftCols<2 * M>(), D);
    return eigen::eigenvalues(D, re, im);
}

//! The real roots x of det M(x) (M = A0 + A1 x + A2 x², lead: A2's LU) into roots (at
//! most 24), and the two candidates of each nearly real pair (SPLIT_ROOT_TOL: `split`
//! true); their count, or -1 when the eigenvalue iteration failed. `deflated`: whether
//! the spurious roots were eliminated first (else the 24 x 24 problem was solved);
//! `spectrum`: the 16 eigenvalues where they were.
inline int real_roots(const Matrix12* A, const Eigen::PartialPivLU<Matrix12>& lead, double* roots,
                      bool* deflated = nullptr, bool* split = nullptr, Spectrum* spectrum = nullptr) {
    double C[ROOTS][ROOTS] = {};
    const Matrix12 B0 = -lead.solve(A[0]), B1 = -lead.solve(A[1]);
    for (int i = 0; i < SIZE; ++i) {
        C[i][SIZE + i] = 1.0;
        for (int j = 0; j < SIZE; ++j) {
            C[SIZE + i][j] = B0(i, j);
            C[SIZE + i][SIZE + j] = B1(i, j);
        }
    }
    SpuriousBasis Z;
    const int nullity = spurious_subspace(A, Z);
    if (deflated != nullptr) *deflated = nullity > 0;
    double re[ROOTS], im[ROOTS];
    int n = ROOTS;
    bool solved = false;
    switch (nullity) {
        case 4: solved = deflated_eigenvalues<4>(C, Z, re, im); break;
        case 5: solved = deflated_eigenvalues<5>(C, Z, re, im); break;
        case 6: solved = deflated_eigenvalues<6>(C, Z, re, im); break;
        default: solved = eigen::eigenvalues(C, re, im); break;
    }
    if (!solved) return -1;
    if (nullity > 0) {
        n = ROOTS - 2 * nullity;
        if (spectrum != nullptr) {
            spectrum->n = n;
            for (int r = 0; r < n; ++r) spectrum->x[r] = {re[r], im[r]};
        }
    }
    int found = 0;
    for (int r = 0; r < n; ++r) found = take_root({re[r], im[r]}, 1.0, roots, split, found);
    return found;
}

using Matrix24 = Eigen::Matrix<double, ROOTS, ROOTS>;

//! The real roots x of det M(x) as real_roots gives them, without A2's inverse: the
//! generalized eigenvalues of x B - C, B = [[I, 0], [0, A2]], C = [[0, I], [-A0, -A1]]
//! (B [v; x v] x = C [v; x v] exactly when M(x) v = 0), by Eigen's real QZ decomposition
//! (fixed size: no heap). Its 8 roots at ±i are no real root; one at x = ∞ is given as
//! ±1e300. -1 when the QZ iteration failed.
//!
//! C = Q S Z and B = Q T Z with S quasi-triangular and T triangular, T diagonal on S's
//! 2 x 2 blocks: a 1 x 1 block is the eigenvalue S(r, r) / T(r, r); a 2 x 2 block the pair
//! α / β, β = a b, α the eigenvalues of the block times diag(b, a) (a, b: T's diagonal
//! there), conjugate first. These are the formulas of Eigen's GeneralizedEigenSolver, whose
//! eigenvector code (not needed) cost a third of the header's compile time; the roots are
//! the same bits (20,000 random pencils, A2 of every rank). Eigen's QZ takes a random
//! shift (std::rand) after 24 iterations without a deflation: not reached on the arms
//! measured (6,000 targets of 60 calibrated URs left std::rand's sequence untouched).
inline int real_roots_qz(const Matrix12* A, double* roots, bool* split = nullptr) {
    Matrix24 B = Matrix24::Zero(), C = Matrix24::Zero();
    B.topLeftCorner<SIZE, SIZE>().setIdentity();
    B.bottomRightCorner<SIZE, SIZE>() = A[2];
    C.topRightCorner<SIZE, SIZE>().setIdentity();
    C.bottomLeftCorner<SIZE, SIZE>() = -A[0];
    C.bottomRightCorner<SIZE, SIZE>() = -A[1];
    Eigen::RealQZ<Matrix24> qz;
    qz.compute(C, B, false);
    if (qz.info() != Eigen::Success) return -1;
    const Matrix24& S = qz.matrixS();
    const Matrix24& T = qz.matrixT();
    int found = 0;
    const auto take = [&](std::complex<double> alpha, double beta) {
        if (beta < 0.0) alpha = -alpha, beta = -beta;  // α/β with β >= 0
        found = take_root(alpha, beta, roots, split, found);
    };
    for (int r = 0; r < ROOTS;) {
        if (r == ROOTS - 1 || S(r + 1, r) == 0.0) {
            take(S(r, r), T(r, r));
            ++r;
            continue;
        }
        const double a = T(r, r), b = T(r + 1, r + 1), beta = a * b;
        const double s00 = S(r, r) * b, s01 = S(r, r + 1) * a;
        const double s10 = S(r + 1, r) * b, s11 = S(r + 1, r + 1) * a;
        const double p = 0.5 * (s00 - s11), z = std::sqrt(std::fabs(p * p + s10 * s01));
        const std::complex<double> alpha(s11 + p, beta > 0.0 ? z : -z);
        take(std::conj(alpha), beta);
        take(alpha, beta);
        r += 2;
    }
    return found;
}

}  // namespace km::general6r
