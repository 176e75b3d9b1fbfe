// Closed-form IK of arms with a spherical wrist: 6R, and RRP (Stanford type).
//
// The last three axes meet at the wrist centre c, which only joints 1-3 move (the lecture
// notes' "hipótesis de la muñeca esférica"). In product-of-exponentials form
// (T(q) = e1 e2 ... e6 M with the axes at q = 0) the target wrist centre is the point
// fixed in the tool frame that sits at c at q = 0:
//
//     c_t = T_target · M⁻¹ · c
//
// and joints 1-3 put c there (ArmPoint, arm_point.hpp: up to four branches). The wrist
// then supplies the rotation left over, R4 R5 R6 = (R1 R2 R3)ᵀ · R_target · R_Mᵀ (the
// lecture notes' R36 = (R03)ᵀ R06), about wrist axes meeting at any angles:
//
// * w = R4 R5 R6 h6 (the target's axis 6, turned back by joints 1-3): the vector
//   c' = R4ᵀ w = R5 h6 has h4ᵀc' = h4ᵀw, h5ᵀc' = h5ᵀh6 and unit length, so
//   c' = α h4 + β h5 ± γ (h4 × h5) (SP2): "no-flip" and "flip";
// * q4 turns c' onto w about h4, q5 turns h6 onto c' about h5 (SP1 each), and q6 turns
//   x6 onto R5ᵀ R4ᵀ R x6 about h6: computed last, it absorbs the round-off of q4 and q5
//   (near the wrist singularity q4 is ill-determined, their combination is not).
//
// When h5 ⟂ h4 and h6 ∥ h4 at q = 0 (the usual wrist, within TWIN_TOL),
// R(h4, π) R(h5, -q5) R(h4, π) = R(h5, q5) makes the flip (q4 + π, -q5, q6 + π): no
// second set of angles to solve for.
//
// "No-flip" bends the wrist the way it is bent at q = 0 (or, when q = 0 is itself
// singular, the way q5 > 0 bends it from there): on the PUMA, sin q5 > 0. Slots:
// 4 position × 2 wrist, slot 2 k + w.
//
// At the edges (each a continuum, flagged singular with its free joints):
//
// * wrist singular (w within WRIST_SINGULAR_TOL of ±h4: axes 4 and 6 aligned): only
//   q4 ± q6 is determined; the no-flip slot holds the representative with q4 = 0, the
//   flip slot (the same family) is NaN;
// * wrist centre on axis 1 (q1 free) or on axis 2 (q2 free): the first two position
//   slots turn the free joint so that the arm faces the tool (axis 4 turned towards the
//   target's axis 6: the wrist is least bent), the last two hold it at 0 (where the
//   shoulder branches merge, as they do at these points for shoulders in closed form,
//   that is one representative of each).
#pragma once

#include <cmath>
#include <cstring>

#include "../config.hpp"
#include "../geometry.hpp"
#include "../ik_types.hpp"
#include "../so3.hpp"
#include "../trig.hpp"
#include "../types.hpp"
#include "arm_point.hpp"

namespace km::decoupled {

//! The wrist's flip is the no-flip's twin (q4 + π, -q5, q6 + π) when h4ᵀh5, h5ᵀh6 and
//! |h4 × h6| at q = 0 are all below this: the identity then holds to about this (far
//! below 1e-10), where the flip's own solution would cost three more atan2.
constexpr double TWIN_TOL = 1e-13;
//! The wrist is singular (axes 4 and 6 aligned) when the sine of the angle between h4
//! and w is below this: the representative q4 = 0 then reproduces the rotation to about
//! twice this (far below 1e-10 rad).
constexpr double WRIST_SINGULAR_TOL = 1e-12;
//! The target is near the wrist singularity (`near`) when that sine is below this: the
//! wrist's solutions there form a continuum within the tolerances (turning q4 by t and q6
//! back by t moves the tool by about t times the sine: an arc of 1e-3 rad within 1e-10
//! at this sine), and q4 and q6 carry the round-off of joints 1-3 over the sine (up to
//! 1e-5 rad measured at 1e-7 on the PUMA 560 where joints 1-3 are ill-conditioned too).
//! docs/inverse-kinematics.md promises the flag to this sine.
constexpr double NEAR_ALIGNED_TOL = 1e-7;

//! The wrist's three angles on one branch.
struct WristAngles {
    double q4 = NaN, q5 = NaN, q6 = NaN;
};

//! A spherical-wrist arm (6R or RRP), its vectors at q = 0 in the base frame.
struct SphericalWristParams {
    ArmPoint arm{};       //!< joints 1-3 placing the wrist centre
    Vec3 c_tool{};        //!< wrist centre in the tool frame (M⁻¹ c)
    Vec3 lh{};            //!< R_Mᵀ h6: the target's axis 6 is R_target times this
    Vec3 lx{};            //!< R_Mᵀ x6
    Vec3 h4{}, h5{};      //!< wrist axes 4 and 5
    Vec3 x6{}, y6{};      //!< a unit vector normal to h6, and h6 × x6
    Vec3 ea{}, eb{};      //!< unit part of h5 normal to h4; eb = h4 × ea
    double k45 = 0.0;     //!< h4ᵀh5
    double s45 = 1.0;     //!< |h4 × h5|
    double k56 = 0.0;     //!< h5ᵀh6
    Vec3 n56{};           //!< h5 × h6 in the frame (h4, ea, eb)
    Vec3 h6f{};           //!< h6 in that frame
    double flip = 1.0;    //!< sign of γ on the no-flip branch
    //! Limits of q4 and q6 (rad): where a singular wrist's representative goes.
    double q4_lo = -INF, q4_hi = INF, q6_lo = -INF, q6_hi = INF;
    //! h5 ⟂ h4 and h6 ∥ h4 at q = 0: flip = (q4 + π, -q5, q6 + π).
    bool twin = false;

    KM_HD int slots() const { return 8; }
    KM_HD int dof() const { return 6; }

    //! The target wrist centre T M⁻¹ c of a pose T.
    KM_HD Vec3 wrist_centre(const Pose& T) const {
        double ct[3];
        for (int i = 0; i < 3; ++i) {
            ct[i] = T.p[i];
            ct[i] += T.x[i] * c_tool.x;
            ct[i] += T.y[i] * c_tool.y;
            ct[i] += T.z[i] * c_tool.z;
        }
        return {ct[0], ct[1], ct[2]};
    }

    //! Two vectors v, u turned back by joint 1 at angle q1 (NaN: none yet).
    struct TurnedBack {
        double q1 = NaN;
        Vec3 v{}, u{};
    };

    //! R3ᵀ R2ᵀ R1ᵀ of two vectors v and u: joints 1-3 of a placement turned back (a
    //! slide: joints 1, 2); one sine and cosine of each joint for both. first holds R1ᵀ v,
    //! R1ᵀ u of the placement before: placements of one shoulder branch share q1 (its
    //! bits), and its turn is not made again.
    KM_HD void undo(const double* q3, const Vec3& v, const Vec3& u, TurnedBack& first,
                    Vec3& v_out, Vec3& u_out) const {
        if (std::memcmp(&q3[0], &first.q1, sizeof first.q1) != 0) {
            double s, c;
            sincos(q3[0], s, c);
            first = {q3[0], rotate_about(arm.h1, c, -s, v), rotate_about(arm.h1, c, -s, u)};
        }
        v_out = first.v;
        u_out = first.u;
        const Vec3 axes[3] = {arm.h1, arm.h2, arm.h3};
        for (int j = 1; j < (arm.prismatic ? 2 : 3); ++j) {
            double s, c;
            sincos(q3[j], s, c);
            v_out = rotate_about(axes[j], c, -s, v_out);
            u_out = rotate_about(axes[j], c, -s, u_out);
        }
    }

    //! q6 turning x6 onto z = R5ᵀ R4ᵀ y about h6 (absorbs q4's, q5's round-off).
    //!
    //! q4 = atan2(y4, x4), q5 = atan2(y5, x5): their cosines and sines come from those
    //! arguments, not from the angles. (The arguments are of the order of 1 and, off the
    //! wrist singularity, above WRIST_SINGULAR_TOL: sqrt of the sum of squares neither
    //! overflows nor underflows.)
    KM_HD double q6_of(double y4, double x4, double y5, double x5, const Vec3& y) const {
        const double r4 = std::sqrt(x4 * x4 + y4 * y4);
        const double r5 = std::sqrt(x5 * x5 + y5 * y5);
        const double c4 = r4 > 0.0 ? x4 / r4 : 1.0;
        const double s4 = r4 > 0.0 ? y4 / r4 : 0.0;
        const double c5 = r5 > 0.0 ? x5 / r5 : 1.0;
        const double s5 = r5 > 0.0 ? y5 / r5 : 0.0;
        Vec3 z = rotate_about(h4, c4, -s4, y);
        z = rotate_about(h5, c5, -s5, z);
        return std::atan2(dot(y6, z), dot(x6, z));
    }

    //! The singular wrist's representative (0, q5, q6) moved along its family into the
    //! limits: (q4, q6).
    //!
    //! With w = ±h4 (w4 = ±1) turning q4 by t turns q6 by -t w4: the family is
    //! (t, q5, q6 - t w4). When q4 = 0 puts q6 outside its limits, t is chosen to put q6
    //! mid-window, then kept within q4's limits, so that a family with members within
    //! the limits is not reported out of them.
    KM_HD void within_limits(double w4, double q6, double& q4_out, double& q6_out) const {
        const bool inside = (q6_lo <= q6 && q6 <= q6_hi) ||
                            (q6_lo <= q6 + TWO_PI && q6 + TWO_PI <= q6_hi) ||
                            (q6_lo <= q6 - TWO_PI && q6 - TWO_PI <= q6_hi);
        if (inside || !(std::isfinite(q6_lo) && std::isfinite(q6_hi))) {
            q4_out = 0.0;
            q6_out = q6;
            return;
        }
        const double sign = w4 > 0.0 ? 1.0 : -1.0;
        double t = sign * wrap(q6 - 0.5 * (q6_lo + q6_hi));
        if (std::isfinite(q4_lo) && std::isfinite(q4_hi)) t = py_min(py_max(t, q4_lo), q4_hi);
        q4_out = t;
        q6_out = q6 - sign * t;
    }

    //! (q4, q5, q6) putting c' = (w4, ca, cb) (frame h4, ea, eb) where it must go.
    //!
    //! q4 turns c' onto w about h4 (their parts off h4, in the frame ea, eb); q5 turns h6
    //! onto c' about h5; q6 absorbs the rest.
    KM_HD WristAngles branch(double w4, double wa, double wb, double ca, double cb,
                             const Vec3& y) const {
        const double y4 = ca * wb - cb * wa;
        const double x4 = ca * wa + cb * wb;
        const double cw = w4 * n56.x + ca * n56.y + cb * n56.z;
        const double ch = w4 * h6f.x + ca * h6f.y + cb * h6f.z - k56 * k56;
        return {std::atan2(y4, x4), std::atan2(cw, ch), q6_of(y4, x4, cw, ch, y)};
    }

    //! (q4, q5, q6) of no-flip, then of flip; true when the wrist is singular.
    //!
    //! w is the target's axis 6 with joints 1-3 turned back, y its x6 likewise. NaN where
    //! the wrist cannot make the rotation (a singular wrist: the flip, the same family, is
    //! NaN). `near` is raised within NEAR_ALIGNED_TOL of the wrist singularity, or at a fold.
    KM_HD bool wrist(const Vec3& w, const Vec3& y, WristAngles& no_flip, WristAngles& flipped,
                     bool& near) const {
        const double w4 = dot(h4, w);
        const double wa = dot(ea, w);
        const double wb = dot(eb, w);
        const double off2 = wa * wa + wb * wb;  // |w × h4|², exact (no 1 - cos² cancellation)
        if (off2 < NEAR_ALIGNED_TOL * NEAR_ALIGNED_TOL) near = true;
        if (off2 < WRIST_SINGULAR_TOL * WRIST_SINGULAR_TOL) {
            // q4 free: c' = w; q5 turns h6 onto w about h5; q6 absorbs the rest
            const double cw = w4 * n56.x + wa * n56.y + wb * n56.z;
            const double ch = w4 * h6f.x + wa * h6f.y + wb * h6f.z - k56 * k56;
            within_limits(w4, q6_of(0.0, 1.0, cw, ch, y), no_flip.q4, no_flip.q6);
            no_flip.q5 = std::atan2(cw, ch);
            flipped = WristAngles{};
            return true;
        }
        const double beta = (k56 - k45 * w4) / (s45 * s45);
        const double off = std::sqrt(off2) / s45;  // γ² = off² - β²
        const double gam0 =
            clamped_root(off - std::fabs(beta), off + std::fabs(beta), off + std::fabs(beta), 1.0, near);
        const double ca = beta * s45;
        const double cb = gam0 * s45 * flip;
        no_flip = branch(w4, wa, wb, ca, cb, y);
        if (twin) {  // R(h4, π) R(h5, -q5) R(h4, π) = R(h5, q5): the flip for free
            flipped = {wrap(no_flip.q4 + PI), -no_flip.q5, wrap(no_flip.q6 + PI)};
        } else {
            flipped = branch(w4, wa, wb, ca, -cb, y);
        }
        return false;
    }

    //! Set a free q2, then a free q1, of a placement q3 (in place): axis 4 turned towards
    //! the target's axis 6 (w0).
    KM_HD void face(double* q3, const Vec3& w0, const ArmState& st) const {
        Vec3 kv = h4;  // axis 4 as joints 3, then 2 turn it
        if (!arm.prismatic) {
            double s3, c3;
            sincos(q3[2], s3, c3);
            kv = rotate_about(arm.h3, c3, s3, kv);
        }
        if (st.free[1]) {  // turned about axis 2 towards R1ᵀ h6_target
            double s1, c1;
            sincos(q3[0], s1, c1);
            const Vec3 back = rotate_about(arm.h1, c1, -s1, w0);
            q3[1] = subproblem1(kv, back, arm.h2);
        }
        double s2, c2;
        sincos(q3[1], s2, c2);
        const Vec3 turned = rotate_about(arm.h2, c2, s2, kv);
        if (st.free[0]) q3[0] = subproblem1(turned, w0, arm.h1);
    }

    //! Candidates for one pose T (base frame) into Q (8 x 6): slot 2 k + w (position
    //! branch k, wrist no-flip or flip), NaN rows where the branch has no real solution.
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info) const {
        double Q3[4][3];
        ArmState st;
        arm.place(wrist_centre(T), Q3, st);
        const Vec3 W0 = T.rotate(lh);  // the target's axis 6
        const Vec3 Y0 = T.rotate(lx);  // and its x6
        bool real = false;
        bool wrist_singular = false;
        const bool free = st.free[0] || st.free[1];
        TurnedBack first;  // the target's axes turned back by the last q1
        for (int k = 0; k < 4; ++k) {
            double* row = Q + 2 * k * 6;
            if (std::isnan(Q3[k][0])) {  // no placement: both wrist rows NaN
                for (int i = 0; i < 12; ++i) row[i] = NaN;
                continue;
            }
            if (k < 2 && free) face(Q3[k], W0, st);
            Vec3 w, y;
            undo(Q3[k], W0, Y0, first, w, y);
            WristAngles branches[2];
            wrist_singular |= wrist(w, y, branches[0], branches[1], st.near);
            for (int j = 0; j < 2; ++j) {
                double* r = row + 6 * j;
                const WristAngles& b = branches[j];
                const bool ok = !std::isnan(b.q4 + b.q5 + b.q6);
                real |= ok;
                for (int i = 0; i < 3; ++i) r[i] = ok ? Q3[k][i] : NaN;
                r[3] = ok ? b.q4 : NaN;
                r[4] = ok ? b.q5 : NaN;
                r[5] = ok ? b.q6 : NaN;
            }
        }
        for (int i = 0; i < 3; ++i) {
            if (st.free[i]) info.set_free(i);
        }
        if (wrist_singular) {
            info.set_free(3);
            info.set_free(5);
        }
        info.singular = wrist_singular || st.free[0] || st.free[1] || st.free[2];
        info.near = st.near;
        // a target outside the shell has no solution, whatever a clamped double root says
        info.gap = !real || st.gap > 0.0 ? st.gap : NaN;
    }
};

}  // namespace km::decoupled
