// The geometric Jacobian of the tool, from the joint axes of one chain walk.
//
// Rows 0-2 map joint rates to the linear velocity of the tool origin, rows 3-5 to the
// angular velocity. Column i is [z × (p − o); z] for a revolute joint with axis z through
// o, [z; 0] for a prismatic one, p the tool origin; in the base frame, or rotated into
// the tool frame on request.
#pragma once

#include "chain.hpp"

namespace km {

namespace detail {
//! Records each joint axis into J (6 x n, row-major): z into rows 3-5, o into rows 0-2.
struct AxesIntoJacobian {
    static constexpr bool frames = false;
    static constexpr bool axes = true;
    double* J;
    int n;
    KM_HD void frame(int, const Pose&) {}
    KM_HD void axis(int i, const Vec3& z, const Vec3& o) {
        J[i] = o.x;
        J[n + i] = o.y;
        J[2 * n + i] = o.z;
        J[3 * n + i] = z.x;
        J[4 * n + i] = z.y;
        J[5 * n + i] = z.z;
    }
};
}  // namespace detail

//! J (6 x n, row-major) from the axes it holds (AxesIntoJacobian) and the tool pose.
KM_HD KM_INLINE void jacobian_columns(const ChainView& ch, const Pose& T, bool tool_frame, double* J) {
    const int n = ch.n;
    for (int i = 0; i < n; ++i) {
        const Vec3 z{J[3 * n + i], J[4 * n + i], J[5 * n + i]};
        Vec3 v, w;
        if (ch.joint[i].prismatic) {
            v = z;
            w = {0.0, 0.0, 0.0};
        } else {
            const Vec3 d{T.p.x - J[i], T.p.y - J[n + i], T.p.z - J[2 * n + i]};
            v = cross(z, d);
            w = z;
        }
        if (tool_frame) {  // Rᵀ v, Rᵀ ω: the columns of R are the tool's axes
            v = T.unrotate(v);
            w = T.unrotate(w);
        }
        J[i] = v.x;
        J[n + i] = v.y;
        J[2 * n + i] = v.z;
        J[3 * n + i] = w.x;
        J[4 * n + i] = w.y;
        J[5 * n + i] = w.z;
    }
}

//! The geometric Jacobian at q into J (6 x n, row-major); the tool pose comes back.
//! c, s: the joint trigonometry of q (joint_trig; or joint_trig_rows with stride m).
KM_HD KM_INLINE Pose jacobian(const ChainView& ch, const double* q, const double* c,
                           const double* s, bool tool_frame, double* J, int stride = 1) {
    const Pose T = walk(ch, q, c, s, detail::AxesIntoJacobian{J, ch.n}, stride);
    jacobian_columns(ch, T, tool_frame, J);
    return T;
}

}  // namespace km
