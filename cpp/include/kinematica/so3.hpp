// Rotation errors: wrap, the SO(3) log (rotation vector), the angle between two
// rotations, the pose error and the inverse right Jacobian of SO(3).
//
// The only copies in kinematica of these formulas: kinematica.spatial calls them.
#pragma once

#include <cmath>

#include "config.hpp"
#include "types.hpp"

namespace km {

//! Below this rotation angle (rad) θ/2 · cot(θ/2) is evaluated by its series: the
//! closed form loses digits to cancellation there.
constexpr double SERIES_ANGLE = 1e-2;
//! atan x rounds to x for |x| below this (x - atan x ≈ x³/3 is under half an ulp of x up
//! to about 1.8e-8): the angle between two nearly equal rotations is then one division.
constexpr double ATAN_LINEAR = 1e-8;

//! a mod b with the sign of b (Python's %): in [0, b) for b > 0.
KM_HD inline double floor_mod(double a, double b) {
    double r = std::fmod(a, b);
    if (r != 0.0) {
        if ((b < 0.0) != (r < 0.0)) r += b;
    } else {
        r = std::copysign(0.0, b);
    }
    return r;
}

//! An angle (rad) in (-π, π], unchanged when it already is; NaN and inf give NaN.
KM_HD inline double wrap(double v) {
    if (-PI < v && v <= PI) return v;
    double w;
    if (PI < v && v <= 3.0 * PI) {  // one turn off (the usual case): no fmod call
        w = v - TWO_PI;
    } else if (-3.0 * PI < v && v <= -PI) {
        w = v + TWO_PI;
    } else if (std::isfinite(v)) {
        w = floor_mod(v + PI, TWO_PI) - PI;  // in [-π, π)
    } else {
        return NaN;  // NaN (a branch without a solution) or inf
    }
    return w <= -PI ? PI : w;
}

//! Rotation vector (rad) of a rotation matrix given by its rows; `angle` gets its norm.
//!
//! atan2 of the sine and cosine of the angle: exact near 0; near π the axis comes from
//! the column of the symmetric part with the largest diagonal,
//! (M + Mᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ, its sign from the skew part (at exactly π,
//! where the skew part vanishes, the column's own sign).
KM_HD inline Vec3 rotvec(double m00, double m01, double m02, double m10, double m11,
                         double m12, double m20, double m21, double m22, double& angle) {
    const double v0 = 0.5 * (m21 - m12);
    const double v1 = 0.5 * (m02 - m20);
    const double v2 = 0.5 * (m10 - m01);
    const double sin = std::sqrt(v0 * v0 + v1 * v1 + v2 * v2);
    const double cos = 0.5 * (m00 + m11 + m22 - 1.0);
    angle = std::atan2(sin, cos);
    if (cos >= 0.0) {
        const double ratio = sin > 0.0 ? angle / sin : 1.0;
        return {v0 * ratio, v1 * ratio, v2 * ratio};
    }
    const double s00 = m00 - cos, s11 = m11 - cos, s22 = m22 - cos;
    double n0, n1, n2;
    if (s00 >= s11 && s00 >= s22) {
        n0 = s00; n1 = 0.5 * (m10 + m01); n2 = 0.5 * (m20 + m02);
    } else if (s11 >= s22) {
        n0 = 0.5 * (m01 + m10); n1 = s11; n2 = 0.5 * (m21 + m12);
    } else {
        n0 = 0.5 * (m02 + m20); n1 = 0.5 * (m12 + m21); n2 = s22;
    }
    double nn = std::sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    if (n0 * v0 + n1 * v1 + n2 * v2 < 0.0) nn = -nn;
    const double k = angle / nn;
    return {n0 * k, n1 * k, n2 * k};
}

//! Angle (rad) of Rtᵀ R for the rotations of T and Tt (exact near 0).
KM_HD inline double angle_between(const Pose& T, const Pose& Tt) {
    double tr = 0.0, vx = 0.0, vy = 0.0, vz = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double r0 = T.x[i], r1 = T.y[i], r2 = T.z[i];
        const double t0 = Tt.x[i], t1 = Tt.y[i], t2 = Tt.z[i];
        tr += t0 * r0 + t1 * r1 + t2 * r2;
        vx += t2 * r1 - t1 * r2;
        vy += t0 * r2 - t2 * r0;
        vz += t1 * r0 - t0 * r1;
    }
    const double sin = 0.5 * std::sqrt(vx * vx + vy * vy + vz * vz);
    const double cos = 0.5 * (tr - 1.0);
    if (cos > 0.0 && sin <= ATAN_LINEAR * cos) return sin / cos;  // the usual case: tiny
    return std::atan2(sin, cos);
}

//! The 6-vector (p_t − p, rotation vector of R_t Rᵀ): m then rad, base frame.
struct Twist {
    double e[6];
};

KM_HD inline Twist pose_error(const Pose& T, const Pose& Tt) {
    // (Rt Rᵀ)[i, j] = row i of Rt · row j of R
    auto rr = [&](int i, int j) { return dot(Tt.row(i), T.row(j)); };
    double angle;
    const Vec3 w = rotvec(rr(0, 0), rr(0, 1), rr(0, 2), rr(1, 0), rr(1, 1), rr(1, 2), rr(2, 0),
                          rr(2, 1), rr(2, 2), angle);
    return {{Tt.p.x - T.p.x, Tt.p.y - T.p.y, Tt.p.z - T.p.z, w.x, w.y, w.z}};
}

//! J_r⁻¹(φ) of SO(3) at the rotation vector φ, row-major into A[9].
KM_HD inline void inverse_right_jacobian(double x, double y, double z, double* A) {
    const double th2 = x * x + y * y + z * z;
    const double half = 0.5 * std::sqrt(th2);
    double alpha, c;
    if (half < 0.5 * SERIES_ANGLE) {
        alpha = 1.0 - th2 / 12.0 - th2 * th2 / 720.0;
        c = 1.0 / 12.0 + th2 / 720.0 + th2 * th2 / 30240.0;
    } else {
        alpha = half / std::tan(half);
        c = (1.0 - alpha) / th2;
    }
    const double hx = 0.5 * x, hy = 0.5 * y, hz = 0.5 * z;
    A[0] = alpha + c * x * x; A[1] = c * x * y - hz;     A[2] = c * x * z + hy;
    A[3] = c * y * x + hz;    A[4] = alpha + c * y * y;  A[5] = c * y * z - hx;
    A[6] = c * z * x - hy;    A[7] = c * z * y + hx;     A[8] = alpha + c * z * z;
}

}  // namespace km
