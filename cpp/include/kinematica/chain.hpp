// A serial chain and its forward kinematics: one walk along the chain, for every use.
//
// The chain is general: each joint is a fixed transform followed by a rotation about, or
// a translation along, its z axis. DH rows of both conventions and URDF joints compile to
// it exactly (Chain::from_dh, Chain::from_transforms). Inside, every fixed transform is
// held in the form the walk applies cheapest, with the rotations about z that commute
// with the joints moved into them (exactly, as the DH rules do):
//
//     T = start · Π_i [M_i(q_i) · Rz(θ_i) · Trans(t_i) · Rx(α_i)] · tool
//
// M_i a rotation Rz(q_i) (merged with Rz(θ_i): one sine and cosine of q_i + θ_i) or a
// slide Tz(q_i). The walk turns the running frame's columns x, y, z, p in place, no 4x4
// products: x' = c x + s y, w = c y − s x, p += t_z z + t_x x' + t_y w,
// y' = cα w + sα z, z' = cα z − sα w. For a DH row t = (a, 0, d): the classical
// regrouped product Rz(θ) Tz(d) Tx(a) Rx(α).
#pragma once

#include <cmath>
#include <type_traits>
#include <vector>

#include "config.hpp"
#include "trig.hpp"
#include "types.hpp"

namespace km {

//! Where the robot's frame i sits along joint i's factor (for "every frame" outputs).
enum class FrameAt {
    after = 0,   //!< after the whole factor (standard DH: frame i = 0A1 ... i-1Ai)
    middle = 1,  //!< after Rz and the z translation (modified DH: before Tx(a) Rx(α) of the next row)
    custom = 2,  //!< middle · G_i (a chain compiled from general transforms: URDF link frames)
};

//! One joint and the fixed part after it.
struct Joint {
    bool prismatic = false;
    double theta = 0.0;        //!< constant angle about z after the motion (rad)
    double ct = 1.0, st = 0.0; //!< its cosine and sine (used as they are by a prismatic joint)
    Vec3 t{};                  //!< translation after Rz(θ) (m)
    double ca = 1.0, sa = 0.0; //!< cosine and sine of the twist α about the new x
    double lo = -INF, hi = INF;        //!< the joint's own limits (rad or m), ±inf where none
    double qlo = -INF, qhi = INF;      //!< limits solutions are held to: own, else (-π, π) revolute
    double turn = INF;                 //!< |q| beyond this is implausible: 2π for a revolute
                                       //!< joint with no limits (degrees given for radians?)
    Pose frame{};              //!< G_i of FrameAt::custom
};

//! What one configuration is: fine, holding NaN/inf, beyond some joint's own limits, or
//! with a joint that has none beyond a full turn (computed all the same; said so).
enum class QState { ok = 0, not_finite = 1, outside_limits = 2, beyond_turn = 3 };

//! A chain's data as the algorithms read it (no ownership: a device copy can point here too).
struct ChainView {
    const Joint* joint = nullptr;
    int n = 0;
    Pose start{}, tool{}, base{};
    FrameAt frames = FrameAt::after;
    bool tool_identity = false;  //!< the tool is exactly the identity: its product is skipped
    bool tool_translation = false;  //!< the tool's rotation is exactly the identity (a flange)
};

//! The chain, owning its joints. Build with from_dh or from_transforms.
class Chain {
public:
    //! A DH table (standard: Paul, distal; modified: Craig, proximal) with base and tool.
    //!
    //! Both conventions are one product once the factors are regrouped (Tras(x) and
    //! Rot(x) commute, as do Rot(z) and Tras(z)): standard: start = base, (a*, α*) of row
    //! i are its own; modified: start = base · Rx(α_1) Tx(a_1), (a*, α*) of row i are row
    //! i+1's (zero after the last). |cos| or |sin| of a constant angle below SNAP_TOL is
    //! taken as exactly 0 (cos(π/2) evaluates to 6.1e-17): twists of 0/±90/180 degrees
    //! keep frames exactly orthonormal.
    //!
    //! Args: prismatic, theta, d, a, alpha (n each; the constant part of the joint
    //! variable's own parameter is the offset), own limits lo, hi (±inf where none), the
    //! convention, base and tool.
    static Chain from_dh(int n, const bool* prismatic, const double* theta, const double* d,
                         const double* a, const double* alpha, const double* lo,
                         const double* hi, bool modified, const Pose& base, const Pose& tool);

    //! A chain of general transforms: T = start · Π_i [M_i(q_i) · F_i] · F_n (F_n: the tool),
    //! frame i = (the frame right after M_i) · frame_offset_i, frame 0 = base.
    //!
    //! Args: start (before the first joint's motion), n - 1 fixed transforms between
    //! motions, the tool after the last motion, the frame offsets (n), prismatic flags,
    //! own limits, base (frame 0).
    static Chain from_transforms(int n, const Pose& start, const Pose* between, const Pose& tool,
                                 const Pose* frame_offset, const bool* prismatic,
                                 const double* lo, const double* hi, const Pose& base);

    //! The chain of the other joints, joint k (0-based) held at value: its motion folded
    //! into the neighbouring fixed transforms (the first joint's into start, the last's into
    //! the tool). Its FK at q without entry k is this chain's at q, to round-off; its frames
    //! are those right after each motion; the base is kept. Needs n >= 2.
    Chain locked(int k, double value) const;
    //! The chain of the inverse transform: joints in reverse order, variables negated.
    //!
    //! With T(q) = start · Π_i [M_i(q_i) F_i] · tool (F_i: fixed_part(i)),
    //! T(q)⁻¹ = (tool⁻¹ F_n⁻¹) · M_n(-q_n) F_(n-1)⁻¹ ··· M_2(-q_2) F_1⁻¹ · M_1(-q_1) · start⁻¹:
    //! its fk(q') at q'_j = -q_(n+1-j) is fk(q)⁻¹. Its own limits are the joints' mapped
    //! likewise ([-hi, -lo]), its frames those of its motions, its base the identity.
    Chain reversed() const;
    //! Joint i's fixed part F_i = Rz(θ_i) Trans(t_i) Rx(α_i), after its motion.
    Pose fixed_part(int i) const;

    int dof() const { return static_cast<int>(joints_.size()); }
    const std::vector<Joint>& joints() const { return joints_; }
    ChainView view() const {
        const bool rotation = tool_.x.x == 1.0 && tool_.x.y == 0.0 && tool_.x.z == 0.0 &&
                              tool_.y.x == 0.0 && tool_.y.y == 1.0 && tool_.y.z == 0.0 &&
                              tool_.z.x == 0.0 && tool_.z.y == 0.0 && tool_.z.z == 1.0;
        const bool identity =
            rotation && tool_.p.x == 0.0 && tool_.p.y == 0.0 && tool_.p.z == 0.0;
        return {joints_.data(), dof(), start_, tool_, base_, frames_, identity, rotation};
    }

private:
    std::vector<Joint> joints_;
    Pose start_{}, tool_{}, base_{};
    FrameAt frames_ = FrameAt::after;
};

//! |cos| or |sin| of a constant DH angle below this is exactly 0 (and the other ±1).
constexpr double SNAP_TOL = 1e-15;

//! The cosines and sines the walk needs for q (revolute: of q_i + θ_i, prismatic: θ_i's).
KM_HD KM_INLINE void joint_trig(const ChainView& ch, const double* q, double* c, double* s) {
    double angle[64];
    for (int i0 = 0; i0 < ch.n; i0 += 64) {  // chunks keep the scratch on the stack
        const int m = ch.n - i0 < 64 ? ch.n - i0 : 64;
        for (int k = 0; k < m; ++k) {
            const Joint& J = ch.joint[i0 + k];
            angle[k] = J.prismatic ? 0.0 : q[i0 + k] + J.theta;
        }
        sincos_block(angle, s + i0, c + i0, m);
    }
    for (int i = 0; i < ch.n; ++i) {
        if (ch.joint[i].prismatic) {
            c[i] = ch.joint[i].ct;
            s[i] = ch.joint[i].st;
        }
    }
}

//! joint_trig of m configurations Q (m x n, row-major) in one pass over all their angles
//! (it vectorises even for a few candidates of a 6-joint arm); angle: m n scratch.
KM_HD KM_INLINE void joint_trig_rows(const ChainView& ch, const double* Q, int m, double* angle,
                                  double* c, double* s) {
    const int n = ch.n;
    int big = 0;  // an angle beyond the reduction's range (or inf) somewhere
    for (int k = 0; k < m; ++k) {
        for (int i = 0; i < n; ++i) {
            const Joint& J = ch.joint[i];
            const double v = J.prismatic ? 0.0 : Q[k * n + i] + J.theta;
            angle[k * n + i] = v;
            big |= static_cast<int>(std::fabs(v) > REDUCTION_LIMIT);
        }
    }
    const int count = m * n;
    if (big == 0) {  // NaN (a branch without a solution) stays NaN this way too
        for (int t = 0; t < count; ++t) sincos_reduced(angle[t], s[t], c[t]);
    } else {
        for (int t = 0; t < count; ++t) sincos(angle[t], s[t], c[t]);
    }
    for (int i = 0; i < n; ++i) {
        const Joint& J = ch.joint[i];
        if (!J.prismatic) continue;
        for (int k = 0; k < m; ++k) {
            c[k * n + i] = J.ct;
            s[k * n + i] = J.st;
        }
    }
}

//! What a walk records besides the tool pose: nothing (the default), or, through an
//! observer with the same members, every joint axis and every frame.
struct NoRecord {
    static constexpr bool frames = false;  //!< true: frame(i, F) gets frames 0..n
    static constexpr bool axes = false;    //!< true: axis(i, z, p) gets each joint's axis
    KM_HD void frame(int, const Pose&) {}
    KM_HD void axis(int, const Vec3&, const Vec3&) {}
};

//! The running frame of a walk between two joints: its columns x, y, z and origin p
//! (base frame).
struct WalkFrame {
    Vec3 x{}, y{}, z{}, p{};
};

//! walk() resumed at joint `first` from the running frame F after joint first - 1 (the
//! chain's start for 0): the same operations on the same values, so the same bits as a
//! walk from the base. saved (or nullptr): saved[i] gets the running frame after joint i,
//! for each i >= first.
template <class Record = NoRecord>
KM_HD KM_INLINE Pose walk_from(const ChainView& ch, const double* q, const double* c,
                               const double* s, Record&& rec, int stride, int first,
                               const WalkFrame& F, WalkFrame* saved) {
    using R = typename std::remove_reference<Record>::type;
    // The running frame's columns stay in locals (registers): stores to the outputs do
    // not force reloads, as they would through a pointer that might alias them.
    Vec3 x = F.x, y = F.y, z = F.z, p = F.p;
    const int n = ch.n;
    for (int i = first; i < n; ++i) {
        const Joint& J = ch.joint[i];
        if constexpr (R::axes) rec.axis(i, z, p);
        const double ci = c[i * stride], si = s[i * stride];
        const Vec3 nx{ci * x.x + si * y.x, ci * x.y + si * y.y, ci * x.z + si * y.z};
        const Vec3 w{ci * y.x - si * x.x, ci * y.y - si * x.y, ci * y.z - si * x.z};
        // A zero offset or a twist of 0 or ±90° (most DH rows) costs no multiplies: the
        // products by 0 and ±1 it skips are exact (only the sign of an exact zero may differ).
        double d = J.t.z;
        if (J.prismatic) d += q[i];
        if (d != 0.0) {
            p.x += d * z.x;
            p.y += d * z.y;
            p.z += d * z.z;
        }
        if constexpr (R::frames) {
            if (i < n - 1 && ch.frames == FrameAt::middle) rec.frame(i + 1, Pose{nx, w, z, p});
            if (i < n - 1 && ch.frames == FrameAt::custom) rec.frame(i + 1, Pose{nx, w, z, p} * J.frame);
        }
        if (J.t.x != 0.0) {
            p.x += J.t.x * nx.x;
            p.y += J.t.x * nx.y;
            p.z += J.t.x * nx.z;
        }
        if (J.t.y != 0.0) {  // 0 for every DH row
            p.x += J.t.y * w.x;
            p.y += J.t.y * w.y;
            p.z += J.t.y * w.z;
        }
        const double ca = J.ca, sa = J.sa;
        x = nx;
        if (sa == 0.0 && ca == 1.0) {
            y = w;
        } else if (ca == 0.0 && (sa == 1.0 || sa == -1.0)) {
            const Vec3 zs = z;
            y = sa == 1.0 ? zs : Vec3{-zs.x, -zs.y, -zs.z};
            z = sa == 1.0 ? Vec3{-w.x, -w.y, -w.z} : w;
        } else {
            y = {ca * w.x + sa * z.x, ca * w.y + sa * z.y, ca * w.z + sa * z.z};
            z = {ca * z.x - sa * w.x, ca * z.y - sa * w.y, ca * z.z - sa * w.z};
        }
        if constexpr (R::frames) {
            if (i < n - 1 && ch.frames == FrameAt::after) rec.frame(i + 1, Pose{x, y, z, p});
        }
        if (saved != nullptr) saved[i] = WalkFrame{x, y, z, p};
    }
    Pose T{x, y, z, p};
    if (ch.tool_translation && !ch.tool_identity) {  // products by 0 and 1 skipped, as above
        const Vec3& e = ch.tool.p;
        T.p = {p.x + x.x * e.x + y.x * e.y + z.x * e.z, p.y + x.y * e.x + y.y * e.y + z.y * e.z,
               p.z + x.z * e.x + y.z * e.y + z.z * e.z};
    } else if (!ch.tool_identity) {
        const Pose& E = ch.tool;
        T.x = {x.x * E.x.x + y.x * E.x.y + z.x * E.x.z, x.y * E.x.x + y.y * E.x.y + z.y * E.x.z,
               x.z * E.x.x + y.z * E.x.y + z.z * E.x.z};
        T.y = {x.x * E.y.x + y.x * E.y.y + z.x * E.y.z, x.y * E.y.x + y.y * E.y.y + z.y * E.y.z,
               x.z * E.y.x + y.z * E.y.y + z.z * E.y.z};
        T.z = {x.x * E.z.x + y.x * E.z.y + z.x * E.z.z, x.y * E.z.x + y.y * E.z.y + z.y * E.z.z,
               x.z * E.z.x + y.z * E.z.y + z.z * E.z.z};
        T.p = {p.x + x.x * E.p.x + y.x * E.p.y + z.x * E.p.z,
               p.y + x.y * E.p.x + y.y * E.p.y + z.y * E.p.z,
               p.z + x.z * E.p.x + y.z * E.p.y + z.z * E.p.z};
    }
    if constexpr (R::frames) {
        rec.frame(0, ch.base);
        rec.frame(n, T);
    }
    return T;
}

//! Walk the chain at q with its trigonometry c[i stride], s[i stride] (joint_trig, or
//! joint_trig_rows with stride m); the tool pose comes back.
//!
//! rec.axis(i, z, p): joint i's axis as a unit direction and a point on it (base frame).
//! rec.frame(i, F): 0T0 (base), 0T1, ..., 0Tn (with tool).
template <class Record = NoRecord>
KM_HD KM_INLINE Pose walk(const ChainView& ch, const double* q, const double* c, const double* s,
                          Record&& rec = Record{}, int stride = 1) {
    const WalkFrame start{ch.start.x, ch.start.y, ch.start.z, ch.start.p};
    return walk_from(ch, q, c, s, static_cast<Record&&>(rec), stride, 0, start, nullptr);
}

//! QState of configuration q against the joints' own limits (and a full turn where none).
KM_HD KM_INLINE QState q_state(const ChainView& ch, const double* q) {
    bool finite = true, inside = true, plausible = true;
    for (int i = 0; i < ch.n; ++i) {
        const double v = q[i];
        finite = finite && std::isfinite(v);
        inside = inside && ch.joint[i].lo <= v && v <= ch.joint[i].hi;
        plausible = plausible && std::fabs(v) <= ch.joint[i].turn;
    }
    if (!finite) return QState::not_finite;
    if (!inside) return QState::outside_limits;
    return plausible ? QState::ok : QState::beyond_turn;
}

//! True when a finite joint value of q lies beyond a full turn (a revolute joint with no
//! limits of its own): what q_state says when nothing else is wrong, asked apart for a
//! configuration that is also outside limits or holds NaN/inf.
KM_HD KM_INLINE bool beyond_turn(const ChainView& ch, const double* q) {
    bool beyond = false;
    for (int i = 0; i < ch.n; ++i) {
        beyond = beyond || (std::isfinite(q[i]) && std::fabs(q[i]) > ch.joint[i].turn);
    }
    return beyond;
}

//! The tool pose at q (joint_trig, then walk), with c, s scratch of n each.
KM_HD KM_INLINE Pose fk(const ChainView& ch, const double* q, double* c, double* s) {
    joint_trig(ch, q, c, s);
    return walk(ch, q, c, s);
}

}  // namespace km

#include "chain_build.hpp"
