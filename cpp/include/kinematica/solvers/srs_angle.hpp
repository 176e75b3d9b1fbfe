// The arm angle ψ of a configuration of an SRS 7R arm: the parameter srs.hpp solves at.
//
// ψ is the angle, right-handed about n = (W - S)/|W - S|, from the reference half-plane
// (bounded by the line S-W, containing axis 1's direction) to the arm half-plane (bounded
// by S-W, containing the elbow point E): with r and e the parts of axis 1 and of E - S
// across n, ψ = atan2(n · (r × e), r · e), in (-π, π]. The points are placed by the
// configuration's own frames: E is fixed in frame 3 (after joint 3), W in frame 4 (after
// joint 4), S in the base (srs_build.hpp's srs_points, at q = 0).
//
// Undefined (NaN): the elbow on the line S-W (|e| within COLLINEAR_TOL of the arm's size),
// W on S (|W - S| likewise), or S-W along axis 1 (|r| within REFERENCE_TOL); and where q
// holds NaN or inf.
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "srs.hpp"
#include "srs_build.hpp"

namespace km::srs {

//! What the arm angle reads of an SRS arm (angle_geometry: about 3 µs, once per batch).
struct AngleGeometry {
    Vec3 S;           //!< the shoulder centre (base frame, m)
    Vec3 elbow;       //!< the elbow point in frame 3 (m)
    Vec3 wrist;       //!< the wrist centre in frame 4 (m)
    Vec3 ref;         //!< axis 1's direction (base frame)
    double tiny = 0;  //!< the collinearity length (m): COLLINEAR_TOL times the arm's size
};

namespace detail {

//! Records frames 3 and 4 of a walk (chain.hpp's frame indices: frame i after joint i).
struct ElbowWristFrames {
    static constexpr bool frames = true;
    static constexpr bool axes = false;
    Pose F3, F4;
    void frame(int i, const Pose& F) {
        if (i == 3) F3 = F;
        if (i == 4) F4 = F;
    }
    void axis(int, const Vec3&, const Vec3&) {}
};

//! Frames 3 and 4 of the chain at q.
inline void elbow_wrist_frames(const ChainView& ch, const double* q, ElbowWristFrames& rec) {
    double c[7], s[7];
    joint_trig(ch, q, c, s);
    walk(ch, q, c, s, rec);
}

//! F's rotation times v, plus F's origin, less o: ((R v) + p) - o, each row's products
//! summed in order.
inline Vec3 placed(const Pose& F, const Vec3& v, const Vec3& o) {
    const double x = F.x.x * v.x + F.y.x * v.y + F.z.x * v.z;
    const double y = F.x.y * v.x + F.y.y * v.y + F.z.y * v.z;
    const double z = F.x.z * v.x + F.y.z * v.y + F.z.z * v.z;
    return {(x + F.p.x) - o.x, (y + F.p.y) - o.y, (z + F.p.z) - o.z};
}

}  // namespace detail

//! The arm's AngleGeometry from its axes at q = 0, or nullopt for no SRS arm (srs_points).
inline std::optional<AngleGeometry> angle_geometry(const Chain& chain) {
    const ArmAxes A = arm_axes(chain);
    Vec3 S, E0, W0;
    if (!srs_points(A, S, E0, W0)) return std::nullopt;
    detail::ElbowWristFrames rec;
    const double zero[7] = {};
    detail::elbow_wrist_frames(chain.view(), zero, rec);
    // the points in the frames that carry them: Rᵀ (point - origin)
    const auto local = [](const Pose& F, const Vec3& point) {
        const Vec3 d = point - F.p;
        return Vec3{dot(F.x, d), dot(F.y, d), dot(F.z, d)};
    };
    AngleGeometry g;
    g.S = S;
    g.elbow = local(rec.F3, E0);
    g.wrist = local(rec.F4, W0);
    g.ref = A.h[0];
    g.tiny = COLLINEAR_TOL * A.size;
    return g;
}

//! ψ (rad, in (-π, π]) of configuration q (7 joint angles, rad) of the chain `ch` of 7
//! joints whose AngleGeometry is g (angle_geometry's); NaN where undefined.
inline double arm_angle(const ChainView& ch, const AngleGeometry& g, const double* q) {
    constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
    detail::ElbowWristFrames rec;
    detail::elbow_wrist_frames(ch, q, rec);
    const Vec3 sw = detail::placed(rec.F4, g.wrist, g.S);
    const Vec3 se = detail::placed(rec.F3, g.elbow, g.S);
    const double sw_norm = std::sqrt(sw.x * sw.x + sw.y * sw.y + sw.z * sw.z);
    if (!(sw_norm > g.tiny)) return NaN;  // W on S: S-W has no direction (or q not finite)
    const Vec3 n{sw.x / sw_norm, sw.y / sw_norm, sw.z / sw_norm};
    const double nr = n.x * g.ref.x + n.y * g.ref.y + n.z * g.ref.z;
    const Vec3 r{g.ref.x - nr * n.x, g.ref.y - nr * n.y, g.ref.z - nr * n.z};
    const double ne = se.x * n.x + se.y * n.y + se.z * n.z;
    const Vec3 e{se.x - ne * n.x, se.y - ne * n.y, se.z - ne * n.z};
    const double r_norm = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
    const double e_norm = std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z);
    if (r_norm <= REFERENCE_TOL || e_norm <= g.tiny) return NaN;
    // n · (r × e) and r · e
    const double y = n.x * (r.y * e.z - r.z * e.y) + n.y * (r.z * e.x - r.x * e.z) +
                     n.z * (r.x * e.y - r.y * e.x);
    const double x = r.x * e.x + r.y * e.y + r.z * e.z;
    return std::atan2(y, x);
}

}  // namespace km::srs
