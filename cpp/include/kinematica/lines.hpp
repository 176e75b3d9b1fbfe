// Joint axes as lines in space: the one line geometry of the package, with its one pair of
// tolerances.
//
// DH extraction, the structure classification of the IK solvers, their builders and the
// singularity analysis all ask here whether two axes are parallel, perpendicular, meet or
// coincide, so an arm is one shape to all of them. A line is a unit direction h and a point
// p on it (one frame); lengths are compared relative to the arm's size (length_tol).
//
// axis_features() reads an arm's whole structure from its axes at q = 0: consecutive
// parallel and meeting pairs, the wrist and shoulder centres, and how near the arm is to a
// degenerate one (the slack). Joint motions move every later axis rigidly, so what holds at
// q = 0 holds at every q.
#pragma once

#include <cmath>

#include "config.hpp"
#include "types.hpp"

namespace km::lines {

//! Two axis directions are parallel when the sine of their angle is at most this;
//! perpendicular when the cosine is. A closed-form solver built for parallel axes misses
//! an arm whose axes are off by ε by about ε times its size, which the check's polishing
//! absorbs while ε is this small. In DH extraction, parallel axes get the rule for
//! parallel axes (its frames off the true common normal by at most this angle); beyond it
//! the true normal is used, far away (at about offset / angle), its round-off about
//! 1e-16 · offset / angle: at this angle 1e-7 · offset, reported as the table's FK error.
constexpr double AXIS_ANGLE_TOL = 1e-9;
//! Two lines meet, a point is on a line, and parallel lines coincide when their distance
//! is at most this times 1 + size (size: the arm's, m; see length_tol). Meeting axes are
//! placed exactly either way (only the sense of x may change); coinciding axes within it
//! lose that offset.
constexpr double AXIS_LENGTH_TOL = 1e-9;
//! A relation holds exactly, not only within the tolerances above, when its sine, cosine
//! or distance / (1 + size) is at most this: the round-off of the frame arithmetic (a DH
//! twist of 90° leaves a cosine of 6e-17). An arm whose axes meet one of its relations
//! only within the tolerances is *near-degenerate*: a closed form built for the exact
//! relation is then not the whole answer.
constexpr double AXIS_EXACT_TOL = 1e-12;

//! Jacobi sweeps for the eigenvalues of a 3x3 normal matrix. Cyclic Jacobi converges
//! quadratically: 3x3 matrices settle (off-diagonal below the stopping test) in 4-6 sweeps;
//! the limit only bounds the loop.
constexpr int JACOBI_SWEEPS = 32;

//! The distance (m) below which lines meet, for an arm of this size (m):
//! AXIS_LENGTH_TOL · (1 + size), relative to the arm for arms of a metre and more,
//! AXIS_LENGTH_TOL metres for small ones (whose round-off is smaller still).
KM_HD inline double length_tol(double size) { return AXIS_LENGTH_TOL * (1.0 + size); }

//! |a × b|: the sine of the angle of unit directions a and b.
KM_HD inline double sine(const Vec3& a, const Vec3& b) { return std::sqrt(cross2(a, b)); }

//! True when unit directions a, b are parallel or anti-parallel (sine <= AXIS_ANGLE_TOL).
KM_HD inline bool lines_parallel(const Vec3& a, const Vec3& b) {
    return sine(a, b) <= AXIS_ANGLE_TOL;
}

//! True when unit directions a, b are perpendicular (|cosine| <= AXIS_ANGLE_TOL).
KM_HD inline bool lines_perpendicular(const Vec3& a, const Vec3& b) {
    return std::fabs(dot(a, b)) <= AXIS_ANGLE_TOL;
}

//! The distance (m) of point x from the line p + t h (unit h): |r − (r·h) h|, r = x − p.
KM_HD inline double point_line_distance(const Vec3& x, const Vec3& h, const Vec3& p) {
    const Vec3 r = x - p;
    return norm(r - dot(r, h) * h);
}

//! Distance (m) between the lines pa + t ha and pb + s hb (unit directions): |w·n| / |n|
//! with n = ha × hb, w = pb − pa; for parallel lines (lines_parallel) the distance of pb
//! from line a.
KM_HD inline double line_distance(const Vec3& ha, const Vec3& pa, const Vec3& hb,
                                  const Vec3& pb) {
    const Vec3 n = cross(ha, hb);
    const double s = norm(n);
    if (s <= AXIS_ANGLE_TOL) return point_line_distance(pb, ha, pa);
    return std::fabs(dot(pb - pa, n)) / s;
}

//! Where the common normal of the non-parallel lines pa + t ha, pb + s hb (unit directions)
//! meets each: fa, fb. 1 - (ha·hb)² is written as |ha × hb|² (no cancellation for nearly
//! parallel lines), as kinematica.dh.lines.normal_feet does.
KM_HD inline void normal_feet(const Vec3& ha, const Vec3& pa, const Vec3& hb, const Vec3& pb,
                              Vec3& fa, Vec3& fb) {
    const Vec3 w = cross(ha, hb);
    const double s2 = dot(w, w), r2 = std::sqrt(s2);
    const Vec3 n{w.x / r2, w.y / r2, w.z / r2};
    const Vec3 d = pb - pa;
    const Vec3 r = d - dot(d, n) * n;
    const double c = dot(ha, hb), ra = dot(r, ha), rb = dot(r, hb);
    fa = pa + ((ra - c * rb) / s2) * ha;
    fb = pb + ((c * ra - rb) / s2) * hb;
}

//! The eigenvalues of a symmetric 3x3 matrix a (row-major; only read), ascending.
//!
//! Cyclic Jacobi rotations (Rutishauser's formulas, as in Numerical Recipes 11.1), each
//! pair skipped once its off-diagonal entry is below round-off of its diagonal ones. Every
//! eigenvalue comes out to round-off of the matrix's norm (what a rank test against an
//! absolute tolerance needs), and for a positive semi-definite matrix even the small ones to
//! high relative accuracy (Demmel & Veselić 1992). The closed form (the characteristic
//! cubic's trigonometric solution) forms the cubic's coefficients with cancellation and
//! needs special cases for repeated eigenvalues (three perpendicular axes give 2 I); Jacobi
//! has none and is hardly longer.
KM_HD inline void symmetric_eigenvalues(const double (&a)[3][3], double (&out)[3]) {
    double m[3][3];
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m[i][j] = a[i][j];
    }
    constexpr double EPS = 2.220446049250313e-16;
    constexpr int PAIRS[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (int sweep = 0; sweep < JACOBI_SWEEPS; ++sweep) {
        bool rotated = false;
        for (const auto& pq : PAIRS) {
            const int p = pq[0], q = pq[1], r = 3 - p - q;
            const double apq = m[p][q];
            if (std::fabs(apq) <= EPS * std::sqrt(std::fabs(m[p][p] * m[q][q]))) continue;
            rotated = true;
            // t = tan of the rotation angle, the smaller root of t² + 2θt − 1 = 0
            const double theta = (m[q][q] - m[p][p]) / (2.0 * apq);
            const double big = std::fabs(theta);
            double t = big > 1e150 ? 0.5 / theta : 1.0 / (big + std::sqrt(theta * theta + 1.0));
            if (theta < 0.0 && big <= 1e150) t = -t;
            const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
            const double tau = s / (1.0 + c);
            m[p][p] -= t * apq;
            m[q][q] += t * apq;
            m[p][q] = m[q][p] = 0.0;
            const double arp = m[r][p], arq = m[r][q];
            m[r][p] = m[p][r] = arp - s * (arq + tau * arp);
            m[r][q] = m[q][r] = arq + s * (arp - tau * arq);
        }
        if (!rotated) break;
    }
    double d0 = m[0][0], d1 = m[1][1], d2 = m[2][2];
    if (d0 > d1) { const double v = d0; d0 = d1; d1 = v; }
    if (d1 > d2) { const double v = d1; d1 = d2; d2 = v; }
    if (d0 > d1) { const double v = d0; d0 = d1; d1 = v; }
    out[0] = d0;
    out[1] = d1;
    out[2] = d2;
}

//! x solving a x = b for a 3x3 a (row-major), by Gaussian elimination with partial
//! pivoting (LAPACK's getrf/getrs order: multipliers by division, then back substitution).
//! The caller has made sure a is not singular.
KM_HD inline Vec3 solve3(const double (&a)[3][3], const Vec3& b) {
    double m[3][4] = {{a[0][0], a[0][1], a[0][2], b.x},
                      {a[1][0], a[1][1], a[1][2], b.y},
                      {a[2][0], a[2][1], a[2][2], b.z}};
    for (int k = 0; k < 2; ++k) {
        int piv = k;
        for (int i = k + 1; i < 3; ++i) {
            if (std::fabs(m[i][k]) > std::fabs(m[piv][k])) piv = i;
        }
        if (piv != k) {
            for (int j = 0; j < 4; ++j) {
                const double v = m[k][j];
                m[k][j] = m[piv][j];
                m[piv][j] = v;
            }
        }
        for (int i = k + 1; i < 3; ++i) {
            const double f = m[i][k] / m[k][k];
            for (int j = k + 1; j < 4; ++j) m[i][j] -= f * m[k][j];
        }
    }
    Vec3 x;
    x.z = m[2][3] / m[2][2];
    x.y = (m[1][3] - m[1][2] * x.z) / m[1][1];
    x.x = (m[0][3] - m[0][1] * x.y - m[0][2] * x.z) / m[0][0];
    return x;
}

//! The point where the k lines p[i] + t h[i] (unit h) meet: the least-squares point c of
//! Σ (I − h hᵀ)(c − p) = 0, written to out; false (out untouched) when the normal matrix
//! Σ (I − h hᵀ) has rank < 3 at tolerance AXIS_ANGLE_TOL (its smallest eigenvalue, which
//! for this symmetric positive semi-definite matrix is its smallest singular value, is at
//! most that: the lines are nearly all parallel), or when a line passes farther than
//! length_tol(size) from c.
KM_HD inline bool common_point(const Vec3* h, const Vec3* p, int k, double size, Vec3& out) {
    double A[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    Vec3 b{};
    for (int i = 0; i < k; ++i) {
        // the projector orthogonal to line i, and its product with the line's point
        double P[3][3];
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) P[r][c] = (r == c ? 1.0 : 0.0) - h[i][r] * h[i][c];
        }
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) A[r][c] += P[r][c];
            b[r] += P[r][0] * p[i].x + P[r][1] * p[i].y + P[r][2] * p[i].z;
        }
    }
    double eig[3];
    symmetric_eigenvalues(A, eig);
    if (!(eig[0] > AXIS_ANGLE_TOL)) return false;
    const Vec3 c = solve3(A, b);
    const double tol = length_tol(size);
    for (int i = 0; i < k; ++i) {
        if (!(point_line_distance(c, h[i], p[i]) <= tol)) return false;
    }
    out = c;
    return true;
}

//! A centre the feature set may have (the wrist's, the shoulder's).
struct Centre {
    bool found = false;
    Vec3 at{};
};

//! What the joint axes of an arm have in common, at q = 0, besides the consecutive pairs
//! axis_features writes to its caller's arrays.
struct AxisFeatures {
    Centre wrist;     //!< where the last three axes meet: revolute, not all parallel
    Centre shoulder;  //!< where the first three meet, likewise
    //! 0 when every relation of two axes (parallel, perpendicular, meeting) and each centre
    //! holds exactly or not at all; else a bound (m) on how far an arm with those relations
    //! made exact moves the tool from this one's (near_degenerate_slack).
    double slack = 0.0;
};

//! The centre of three revolute axes first .. first + 2, if they are not all parallel and
//! meet (within length_tol(size)).
KM_HD inline Centre axes_centre(const Vec3* h, const Vec3* p, const bool* prismatic, int n,
                                int first, double size) {
    Centre out;
    if (n < 3) return out;
    for (int i = first; i < first + 3; ++i) {
        if (prismatic[i]) return out;
    }
    if (lines_parallel(h[first], h[first + 1]) && lines_parallel(h[first], h[first + 2])) {
        return out;
    }
    out.found = common_point(h + first, p + first, 3, size, out.at);
    return out;
}

//! A bound (m) on how far the relations that hold only within tolerance move the tool.
//!
//! Every pair of axes whose sine (parallel), cosine (perpendicular) or distance (meeting,
//! coinciding) lies in (AXIS_EXACT_TOL, the tolerance] (lengths: times 1 + size), and each
//! axis passing the wrist (or shoulder) centre within length_tol but not exactly, is a
//! relation a closed form takes as exact. An axis tilted by ε turns the points beyond it,
//! at most size away, by at most 2 ε size for any joint motion, a point off by δ moves them
//! by δ: the slack is the sum over the relations, 0 when there are none.
KM_HD inline double near_degenerate_slack(const Vec3* h, const Vec3* p, int n, double size,
                                          const Centre& wrist, const Centre& shoulder) {
    const double tol = length_tol(size), exact_len = AXIS_EXACT_TOL * (1.0 + size);
    double slack = 0.0;
    for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) {
            const double angles[2] = {sine(h[i], h[j]), std::fabs(dot(h[i], h[j]))};
            for (const double v : angles) {
                if (AXIS_EXACT_TOL < v && v <= AXIS_ANGLE_TOL) slack += 2.0 * v * size;
            }
            const double d = line_distance(h[i], p[i], h[j], p[j]);
            if (exact_len < d && d <= tol) slack += d;
        }
    }
    const Centre* centres[2] = {&wrist, &shoulder};
    const int firsts[2] = {n - 3, 0};
    for (int c = 0; c < 2; ++c) {
        if (!centres[c]->found) continue;
        for (int i = firsts[c]; i < firsts[c] + 3; ++i) {
            const double d = point_line_distance(centres[c]->at, h[i], p[i]);
            if (exact_len < d && d <= tol) slack += d;
        }
    }
    return slack;
}

//! An arm's structure from its n joint axes (unit directions h, points p, base frame, at
//! q = 0) and its size (m). parallel[i] (i < n − 1): axes i and i + 1 are parallel;
//! meet[i]: they are not parallel and meet (within length_tol(size)). Both caller-owned,
//! n − 1 entries (none for n = 1).
KM_HD inline AxisFeatures axis_features(const Vec3* h, const Vec3* p, const bool* prismatic,
                                        int n, double size, bool* parallel, bool* meet) {
    const double tol = length_tol(size);
    for (int i = 0; i + 1 < n; ++i) {
        parallel[i] = lines_parallel(h[i], h[i + 1]);
        meet[i] = !parallel[i] && line_distance(h[i], p[i], h[i + 1], p[i + 1]) <= tol;
    }
    AxisFeatures f;
    f.wrist = axes_centre(h, p, prismatic, n, n - 3, size);
    f.shoulder = axes_centre(h, p, prismatic, n, 0, size);
    f.slack = near_degenerate_slack(h, p, n, size, f.wrist, f.shoulder);
    return f;
}

}  // namespace km::lines
