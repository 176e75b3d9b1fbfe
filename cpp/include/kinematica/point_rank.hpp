// Whether joints 1-3 of a chain move a point in three independent directions: the
// conditioning of the point's 3 x 3 Jacobian, which the decoupled solvers' builders ask
// before they take an arm (kinematica.ik.analytic.arm_point.places_point).
#pragma once

#include <cmath>

#include "jacobian.hpp"
#include "lines.hpp"

namespace km {

//! σmin / σmax of the Jacobian of a point with respect to joints 1-3, at q (n >= 3 joints).
//!
//! The point is fixed in the tool frame at c_tool; column j of its Jacobian is v_j + ω_j × r
//! (the tool origin's linear velocity and the angular velocity of joint j, r the point
//! relative to the tool origin, base frame). Its singular values are the square roots of
//! the eigenvalues of its Gram matrix (lines::symmetric_eigenvalues, accurate to round-off
//! of the largest: a ratio down to about 1e-8 is resolved). 0 for a zero Jacobian.
//! c, s: scratch of n each; J: scratch of 6 n.
KM_HD inline double point_rank_ratio(const ChainView& ch, const double* q, const Vec3& c_tool,
                                     double* c, double* s, double* J) {
    const int n = ch.n;
    joint_trig(ch, q, c, s);
    const Pose T = jacobian(ch, q, c, s, false, J);
    const Vec3 r = T.rotate(c_tool);
    Vec3 col[3];
    for (int j = 0; j < 3; ++j) {
        const Vec3 v{J[j], J[n + j], J[2 * n + j]};
        const Vec3 w{J[3 * n + j], J[4 * n + j], J[5 * n + j]};
        col[j] = v + cross(w, r);
    }
    double G[3][3];
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) G[i][j] = dot(col[i], col[j]);
    }
    double eig[3];
    lines::symmetric_eigenvalues(G, eig);
    if (!(eig[2] > 0.0)) return 0.0;
    return std::sqrt(std::fmax(eig[0], 0.0) / eig[2]);
}

}  // namespace km
