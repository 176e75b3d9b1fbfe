// Closed-form IK of SRS 7R arms (KUKA iiwa type) at a given arm angle: all 8 solutions.
//
// Axes 1, 2, 3 meet at the shoulder S (fixed in the base), axes 5, 6, 7 at the wrist W
// (fixed in the tool), and axis 4, the elbow, passes through neither. In
// product-of-exponentials form (T(q) = e1 ... e7 M, axes at q = 0) the target wrist centre
// is W_t = T M⁻¹ W0 and, with E0 the foot of the perpendicular from S onto axis 4 (the
// elbow point, fixed after joint 3) and the vectors se = E0 - S, ew = W0 - E0 at q = 0,
//
//     W_t - S = R1 R2 R3 (se + R4 ew).
//
// * Elbow: |W_t - S| = D fixes q4 (joints 1-3 keep lengths): |se + R4 ew|² is largest at
//   q4 = `stretched` (d_max) and smallest half a turn away (d_min), and q4 = stretched ± β
//   with tan(β/2) = sqrt((d_max² - D²) / (D² - d_min²)), both factors written as
//   (d - D)(d + D) so that a target at the fold keeps its accuracy (the branches "elbow
//   bent positive" and "elbow bent negative").
// * Arm angle ψ (the parameter): the angle, right-handed about n = (W - S)/|W - S|, from the
//   reference half-plane (bounded by the line S-W, containing the direction `ref`, axis 1)
//   to the arm half-plane (bounded by S-W, containing the elbow point E). This is the
//   "conventional SEW angle" of Elias and Wen (IK-Geo, 2022) with reference vector axis 1.
//   On the iiwa its reference plane is Shimizu et al.'s (2008), the plane S-E-W of the
//   solution with q3 = 0 (axes 2 and 4 are then parallel: the plane contains axis 1), and
//   ψ = 0 is the half-plane on the side axis 1 points to (elbow up). The triangle S, E, W
//   has sides |se|, |ew| (E is on axis 4, which W turns about) and D, so ψ puts E at one
//   point: its part across n is along m_t = cos ψ r + sin ψ (n × r), r the unit part of
//   `ref` across n.
// * Shoulder: R1 R2 R3 is the rotation taking (n3, m3) to (n, m_t), n3 and m3 the same
//   directions of the arm at q1 = q2 = q3 = 0 (W and E seen from S); it is split into
//   rotations about the three meeting axes as a spherical wrist is (two branches,
//   "shoulder no-flip" and "flip": SphericalWristParams::wrist on axes 1, 2, 3).
// * Wrist: R5 R6 R7 = (R1 R2 R3 R4)ᵀ R_target R_Mᵀ, split likewise ("wrist no-flip", "flip").
//
// Slots: 8 = elbow (2) × shoulder (2) × wrist (2), slot 4 e + 2 s + w.
//
// At the edges (flagged singular, with the joints free along the continuum):
// * the elbow on the line S-W (stretched or folded, possible when the perpendiculars from S
//   and W onto axis 4 have the same foot, as on the iiwa), or W on S (folded, equal links):
//   the arm plane and ψ are undefined; any turn of the arm about S-W solves (joints 1-3
//   and 5-7 free): one representative per branch;
// * S-W along the reference (axis 1): ψ's reference is undefined; turning the whole arm
//   about axis 1 solves (q1 and the wrist free), a representative measured from `ref_alt`;
// * the shoulder's or the wrist's first and last axes aligned (q1 + q3, or q5 + q7, only).
// Targets with D outside [d_min, d_max] are unreachable with that proven gap.
#pragma once

#include <cmath>

#include "../config.hpp"
#include "../geometry.hpp"
#include "../ik_types.hpp"
#include "../trig.hpp"
#include "../types.hpp"
#include "spherical_wrist.hpp"

namespace km::srs {

//! The elbow point within this distance (times the arm's size) of the line S-W is on it:
//! the arm plane, and with it the arm angle, is undefined. Far below the position
//! tolerance (1e-10 m): any turn of the arm about S-W then reaches the target.
constexpr double COLLINEAR_TOL = 1e-12;
//! S-W within this sine of the reference direction (axis 1) leaves the arm angle without
//! a reference (the same measure as COLLINEAR_TOL, on unit vectors).
constexpr double REFERENCE_TOL = 1e-12;

//! An orthonormal right-handed basis (n, m, n × m).
struct Basis {
    Vec3 n{}, m{}, k{};

    //! Components of v on the basis.
    KM_HD Vec3 coords(const Vec3& v) const { return {dot(n, v), dot(m, v), dot(k, v)}; }
    //! The vector of components c.
    KM_HD Vec3 vector(const Vec3& c) const { return c.x * n + c.y * m + c.z * k; }
};

//! An SRS arm: its vectors at q = 0 in the base frame, and the arm angle to solve at.
struct SRSParams {
    //! Axes 1, 2, 3 as a three-axis decomposition (its h4, h5 and h6 are axes 1, 2, 3;
    //! q4/q6 limits are q1's/q3's): splits R1 R2 R3.
    decoupled::SphericalWristParams shoulder{};
    //! Axes 5, 6, 7 likewise (lh = R_Mᵀ h7, lx = R_Mᵀ x7): splits R5 R6 R7.
    decoupled::SphericalWristParams wrist{};
    Vec3 s{};        //!< the shoulder centre S (m)
    Vec3 w_tool{};   //!< the wrist centre in the tool frame, M⁻¹ W0 (m)
    Vec3 se{};       //!< E0 - S: shoulder to elbow point at q = 0 (m)
    Vec3 ew{};       //!< W0 - E0: elbow point to wrist centre at q = 0 (m)
    Vec3 h4{};       //!< the elbow axis
    Vec3 ref{};      //!< the arm angle's reference direction (axis 1)
    Vec3 ref_alt{};  //!< a unit vector normal to ref: the reference when S-W is along ref
    double stretched = 0.0;  //!< q4 (rad) where |W - S| is largest
    double d_max = 0.0;      //!< the largest |W - S| (m)
    double d_min = 0.0;      //!< the least |W - S| (m)
    double scale = 1.0;      //!< the arm's size (m), for tolerances
    double psi = 0.0;        //!< the arm angle to solve at (rad)

    KM_HD int slots() const { return 8; }
    KM_HD int dof() const { return 7; }

    //! The unit vector of v, or `fallback` when |v| <= tiny.
    KM_HD static Vec3 unit_or(const Vec3& v, double tiny, const Vec3& fallback) {
        const double r = norm(v);
        return r > tiny ? (1.0 / r) * v : fallback;
    }

    //! T moved along the line from the shoulder centre S to its wrist centre W until |W - S|
    //! is the elbow's at q4 = `q4`: a target this arm reaches with q4 there all along its
    //! self-motion. kinematica.ik.held_neighbour aims a nearby arm's targets so (its
    //! shoulder-wrist distance differs from this arm's by about its offsets).
    Pose aimed(const Pose& T, double q4) const {
        const double c = std::cos(q4), sn = std::sin(q4);
        const Vec3 turned = c * ew + sn * cross(h4, ew) + ((1.0 - c) * dot(h4, ew)) * h4;
        const double want = norm(se + turned);
        const Vec3 sw = T.apply(w_tool) - s;
        const double d = norm(sw);
        Pose out = T;
        if (d > 0.0) out.p = out.p + ((want - d) / d) * sw;
        return out;
    }

    //! (q4 of the elbow bent positive, of the elbow bent negative) for |W - S| = D; false
    //! beyond [d_min, d_max] (gap > 0 then). A fold (β = 0 or π) within round-off is a
    //! double root and raises `near`.
    KM_HD bool elbow(double D, double q4[2], double& gap, bool& near) const {
        using decoupled::clamped_root;
        gap = decoupled::py_max(0.0, decoupled::py_max(D - d_max, d_min - D));
        const double sin_half = clamped_root(d_max - D, d_max + D, d_max + D, scale, near);
        const double cos_half = clamped_root(D - d_min, D + d_min, D + d_min, scale, near);
        if (std::isnan(sin_half + cos_half)) return false;
        const double beta = 2.0 * std::atan2(sin_half, cos_half);
        q4[0] = wrap(stretched + beta);
        q4[1] = wrap(stretched - beta);
        return true;
    }

    //! The basis (n, m_t): n along S-W, m_t the arm half-plane's direction at the arm
    //! angle `angle`. `undefined` is raised when S-W is along ref (within REFERENCE_TOL).
    KM_HD Basis target_basis(const Vec3& n, double angle, bool& undefined, bool& near) const {
        Vec3 r = ref - dot(ref, n) * n;
        const double across = norm(r);
        if (across < decoupled::NEAR_SET_TOL) near = true;
        if (across <= REFERENCE_TOL) {
            undefined = true;
            r = ref_alt - dot(ref_alt, n) * n;
        }
        r = (1.0 / norm(r)) * r;
        const Vec3 nr = cross(n, r);
        double sp, cp;
        sincos(angle, sp, cp);
        Basis B;
        B.n = n;
        B.m = cp * r + sp * nr;
        B.k = cross(n, B.m);
        return B;
    }

    //! The basis (n3, m3) of the arm at q1 = q2 = q3 = 0 and this q4: n3 along S-W, m3 the
    //! elbow's direction across it. `collinear` is raised when the elbow is on S-W (a
    //! representative direction normal to n3 is taken).
    KM_HD Basis arm_basis(double s4, double c4, bool& collinear, bool& near) const {
        const double tiny = decoupled::SINGULAR_TOL * scale;
        const Vec3 w3 = se + rotate_about(h4, c4, s4, ew);
        const Vec3 n3 = unit_or(w3, tiny, ref_alt);
        Vec3 m3 = se - dot(se, n3) * n3;
        const double across = norm(m3);
        if (across < decoupled::NEAR_SET_TOL * scale) near = true;
        if (across <= COLLINEAR_TOL * scale) {
            collinear = true;
            // any direction across n3 will do: ref and ref_alt are orthogonal, so one of
            // them is at least 45 degrees off n3
            m3 = cross(h4, n3);
            if (norm(m3) < 0.5) m3 = cross(ref_alt, n3);
            if (norm(m3) < 0.5) m3 = cross(ref, n3);
        }
        Basis B;
        B.n = n3;
        B.m = (1.0 / norm(m3)) * m3;
        B.k = cross(n3, B.m);
        return B;
    }

    //! Candidates for one pose T (base frame) at the arm angle psi into Q (8 x 7).
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info) const {
        solve_at(T, psi, Q, info);
    }

    //! Candidates for one pose T (base frame) at the arm angle `angle` (rad) into Q (8 x 7):
    //! slot 4 e + 2 s + w (elbow bent positive/negative, shoulder no-flip/flip, wrist
    //! no-flip/flip), NaN rows where a branch has none.
    KM_HD void solve_at(const Pose& T, double angle, double* Q, SolverInfo& info) const {
        for (int i = 0; i < 8 * 7; ++i) Q[i] = NaN;
        const Vec3 d = T.apply(w_tool) - s;
        const double D = norm(d);
        bool near = false;
        double q4[2];
        double gap = 0.0;
        if (!(D < decoupled::HUGE_REACH) || !elbow(D, q4, gap, near)) {
            info.gap = D >= decoupled::HUGE_REACH ? D - d_max : gap;
            if (!(info.gap > 0.0)) info.gap = NaN;
            info.near = near || std::isnan(D);
            return;
        }
        const double tiny = decoupled::SINGULAR_TOL * scale;
        bool no_reference = false, collinear = false, shoulder_singular = false,
             wrist_singular = false;
        const Vec3 W0 = T.rotate(wrist.lh);  // the target's axis 7
        const Vec3 Y0 = T.rotate(wrist.lx);  // and its x7
        for (int e = 0; e < 2; ++e) {
            double s4, c4;
            sincos(q4[e], s4, c4);
            const Basis A = arm_basis(s4, c4, collinear, near);
            // W on S (a folded arm of equal links): S-W has no direction, no arm plane;
            // any will do
            if (!(D > tiny)) collinear = true;
            const Vec3 n = D > tiny ? (1.0 / D) * d : A.n;
            const Basis B = target_basis(n, angle, no_reference, near);
            // R123 v = B.vector(A.coords(v)); R123ᵀ v = A.vector(B.coords(v))
            const Vec3 w1 = B.vector(A.coords(shoulder.lh));
            const Vec3 y1 = B.vector(A.coords(shoulder.x6));
            decoupled::WristAngles sh[2];
            shoulder_singular |= shoulder.wrist(w1, y1, sh[0], sh[1], near);
            const Vec3 w5 = rotate_about(h4, c4, -s4, A.vector(B.coords(W0)));
            const Vec3 y5 = rotate_about(h4, c4, -s4, A.vector(B.coords(Y0)));
            decoupled::WristAngles wr[2];
            wrist_singular |= wrist.wrist(w5, y5, wr[0], wr[1], near);
            for (int a = 0; a < 2; ++a) {
                for (int b = 0; b < 2; ++b) {
                    double* r = Q + (4 * e + 2 * a + b) * 7;
                    const double row[7] = {sh[a].q4, sh[a].q5, sh[a].q6, q4[e],
                                           wr[b].q4, wr[b].q5, wr[b].q6};
                    double sum = 0.0;
                    for (int j = 0; j < 7; ++j) sum += row[j];
                    if (std::isnan(sum)) continue;  // a singular decomposition's twin slot
                    for (int j = 0; j < 7; ++j) r[j] = row[j];
                }
            }
        }
        if (collinear) {  // the arm turns about S-W: all but the elbow move
            for (const int j : {0, 1, 2, 4, 5, 6}) info.set_free(j);
        }
        if (no_reference) {  // the arm turns about axis 1: q1 and the wrist move
            for (const int j : {0, 4, 5, 6}) info.set_free(j);
        }
        if (shoulder_singular) {
            info.set_free(0);
            info.set_free(2);
        }
        if (wrist_singular) {
            info.set_free(4);
            info.set_free(6);
        }
        info.singular = collinear || no_reference || shoulder_singular || wrist_singular;
        info.near = near;
        info.gap = gap > 0.0 ? gap : NaN;
    }
};

}  // namespace km::srs
