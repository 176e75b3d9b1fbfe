// Building a Chain: from a DH table, and from general transforms (URDF joints).
#pragma once

#include <cmath>
#include <vector>

#include "chain.hpp"

namespace km {

namespace detail {

inline double snap(double v) {
    if (std::fabs(v) < SNAP_TOL) return 0.0;
    if (std::fabs(std::fabs(v) - 1.0) < SNAP_TOL) return std::copysign(1.0, v);
    return v;
}

inline Pose rot_x(double c, double s) {
    Pose P;
    P.y = {0.0, c, s};
    P.z = {0.0, -s, c};
    return P;
}

inline Pose rot_z(double c, double s) {
    Pose P;
    P.x = {c, s, 0.0};
    P.y = {-s, c, 0.0};
    return P;
}

inline Pose trans(const Vec3& t) {
    Pose P;
    P.p = t;
    return P;
}

inline void set_limits(Joint& J, double lo, double hi) {
    J.lo = lo;
    J.hi = hi;
    const bool own = std::isfinite(lo) || std::isfinite(hi) || J.prismatic;
    J.qlo = own ? lo : -PI;
    J.qhi = own ? hi : PI;
    J.turn = own ? INF : TWO_PI;
}

//! R = Rz(θ) Rx(α) Rz(δ) (ZXZ angles), accurate as a product however small sin α is.
//!
//! θ + δ (or θ − δ where cos α < 0) comes from the 2x2 block, exact to round-off; θ from
//! the third column, whose error ε / sin α is then taken back by δ: the product is off by
//! about ε sin α.
inline void zxz(const Pose& R, double& theta, double& ca, double& sa, double& delta) {
    // entries R[i][j]: row i, column j
    const double r00 = R.x.x, r10 = R.x.y, r01 = R.y.x, r11 = R.y.y;
    const double r02 = R.z.x, r12 = R.z.y, r22 = R.z.z;
    const double s = std::hypot(r02, r12);
    const double len = std::hypot(s, r22);
    ca = r22 / len;
    sa = s / len;
    theta = s > 0.0 ? std::atan2(r02, -r12) : 0.0;
    if (r22 >= 0.0) {
        const double sum = std::atan2(r10 - r01, r00 + r11);
        delta = sum - theta;
    } else {
        const double diff = std::atan2(r10 + r01, r00 - r11);
        delta = theta - diff;
    }
}

}  // namespace detail

inline Chain Chain::from_dh(int n, const bool* prismatic, const double* theta, const double* d,
                            const double* a, const double* alpha, const double* lo,
                            const double* hi, bool modified, const Pose& base, const Pose& tool) {
    Chain ch;
    ch.joints_.resize(static_cast<size_t>(n));
    ch.base_ = base;
    ch.tool_ = tool;
    ch.frames_ = modified ? FrameAt::middle : FrameAt::after;
    ch.start_ = base;
    if (modified && n > 0) {
        const Pose first = detail::rot_x(detail::snap(std::cos(alpha[0])), detail::snap(std::sin(alpha[0]))) *
                           detail::trans({a[0], 0.0, 0.0});
        ch.start_ = base * first;
    }
    for (int i = 0; i < n; ++i) {
        Joint& J = ch.joints_[static_cast<size_t>(i)];
        const int row = modified ? i + 1 : i;
        const double ai = row < n ? a[row] : 0.0;
        const double al = row < n ? alpha[row] : 0.0;
        J.prismatic = prismatic[i];
        J.theta = theta[i];
        J.ct = detail::snap(std::cos(theta[i]));
        J.st = detail::snap(std::sin(theta[i]));
        J.t = {ai, 0.0, d[i]};
        J.ca = detail::snap(std::cos(al));
        J.sa = detail::snap(std::sin(al));
        detail::set_limits(J, lo[i], hi[i]);
    }
    return ch;
}

inline Chain Chain::from_transforms(int n, const Pose& start, const Pose* between,
                                    const Pose& tool, const Pose* frame_offset,
                                    const bool* prismatic, const double* lo, const double* hi,
                                    const Pose& base) {
    Chain ch;
    ch.joints_.resize(static_cast<size_t>(n));
    ch.base_ = base;
    ch.start_ = start;
    ch.frames_ = FrameAt::custom;
    // carry: the rotation about z the compiled frames are turned by from the true ones
    // (compiled = true · carry); it commutes with every joint's motion.
    Pose carry{};
    for (int i = 0; i < n; ++i) {
        Joint& J = ch.joints_[static_cast<size_t>(i)];
        J.prismatic = prismatic[i];
        detail::set_limits(J, lo[i], hi[i]);
        const Pose carry_inv = inverse(carry);
        Pose next_carry = carry;  // after the last joint, the tool takes the carry
        if (i < n - 1) {
            // the fixed part after joint i, in the compiled frame: E = carry⁻¹ F = P_i Rz(δ)
            const Pose E = carry_inv * between[i];
            double th, ca, sa, delta;
            detail::zxz(E, th, ca, sa, delta);
            J.theta = th;
            J.ct = std::cos(th);
            J.st = std::sin(th);
            J.t = detail::rot_z(J.ct, -J.st).rotate(E.p);  // Rz(-θ) p: Rz(q) Trans(p) Rz(θ) = Rz(q + θ) Trans(t)
            J.ca = ca;
            J.sa = sa;
            next_carry = detail::rot_z(std::cos(delta), -std::sin(delta));  // Rz(-δ)
        }
        // frame i = (right after M_i) · offset = middle_i · Tz(-t_z) Rz(-θ) carry⁻¹ offset
        J.frame = detail::trans({0.0, 0.0, -J.t.z}) * detail::rot_z(J.ct, -J.st) * carry_inv *
                  frame_offset[i];
        carry = next_carry;
    }
    ch.tool_ = inverse(carry) * tool;
    return ch;
}

namespace detail {

//! Records each joint's axis (direction, point) of a walk.
struct AxesRecord {
    static constexpr bool frames = false;
    static constexpr bool axes = true;
    Vec3* h;
    Vec3* p;
    void frame(int, const Pose&) {}
    void axis(int i, const Vec3& z, const Vec3& o) {
        h[i] = z;
        p[i] = o;
    }
};

}  // namespace detail

//! The arm's size is measured along its axes (walked_size) where that is below this
//! fraction of the size of its frames (frame_size): a DH table of nearly parallel axes
//! puts its frames at the foot of their common normal (the Kinova Gen3 Lite's `to_dh()`:
//! d2, d3 = -38 km, 76 km of frames for an arm of 0.85 m); a length tolerance in units of
//! that would call axes 0.15 mm apart met, and a loop of that size loses its lengths to
//! round-off.
constexpr double WALK_SIZE_RATIO = 0.1;

//! |tool offset| + Σ |fixed translations| of the joints (m; a slide's travel not counted).
inline double frame_size(const Chain& chain) {
    double joints = 0.0;
    for (const Joint& J : chain.joints()) {
        joints += std::fabs(J.t.x);
        joints += std::fabs(J.t.y);
        joints += std::fabs(J.t.z);
    }
    return norm(chain.view().tool.p) + joints;
}

//! The size of n axes (unit directions h, points p) measured along them (m): each
//! axis's point replaced, in p, by the one nearest the previous axis's point (axis 1's
//! own kept), |p[i] - p[i-1]| summed with the tool point's distance from the last. A
//! joint turns the axes after it about its own, which keeps every distance from a point
//! on it: for a revolute chain this is the same at every configuration, and a chain's
//! representation cannot make it larger than the geometry.
inline double walked_size(const Vec3* h, Vec3* p, int n, const Vec3& tool) {
    double size = 0.0;
    for (int i = 1; i < n; ++i) {
        p[i] = p[i] + dot(p[i - 1] - p[i], h[i]) * h[i];
        size += norm(p[i] - p[i - 1]);
    }
    return size + norm(tool - p[n - 1]);
}

//! The arm's size (m), the scale of the line geometry's length tolerance (lines.hpp):
//! frame_size, or for a revolute chain whose size along its axes is below
//! WALK_SIZE_RATIO of that, walked_size at q = 0.
inline double arm_size(const Chain& chain) {
    const double frames = frame_size(chain);
    const ChainView ch = chain.view();
    if (ch.n == 0) return frames;
    for (int i = 0; i < ch.n; ++i)
        if (ch.joint[i].prismatic) return frames;
    const auto N = static_cast<size_t>(ch.n);
    std::vector<double> q(N, 0.0), c(N), s(N);
    std::vector<Vec3> h(N), p(N);
    joint_trig(ch, q.data(), c.data(), s.data());
    const Pose M = walk(ch, q.data(), c.data(), s.data(), detail::AxesRecord{h.data(), p.data()});
    const double walked = walked_size(h.data(), p.data(), ch.n, M.p);
    return walked < WALK_SIZE_RATIO * frames ? walked : frames;
}

inline Pose Chain::fixed_part(int i) const {
    const Joint& J = joints_[static_cast<size_t>(i)];
    return detail::rot_z(J.ct, J.st) * detail::trans(J.t) * detail::rot_x(J.ca, J.sa);
}

inline Chain Chain::locked(int k, double value) const {
    const int n = dof();
    // T = G_0 M_0 G_1 M_1 ... M_(n-1) G_n: locking joint k merges G_k M_k G_(k+1)
    std::vector<Pose> G(static_cast<size_t>(n + 1));
    G[0] = start_;
    for (int i = 1; i < n; ++i) G[static_cast<size_t>(i)] = fixed_part(i - 1);
    G[static_cast<size_t>(n)] = fixed_part(n - 1) * tool_;
    const Joint& J = joints_[static_cast<size_t>(k)];
    const Pose motion = J.prismatic ? detail::trans({0.0, 0.0, value})
                                    : detail::rot_z(std::cos(value), std::sin(value));
    std::vector<Pose> parts;
    std::vector<char> prismatic;
    std::vector<double> lo, hi;
    for (int i = 0; i <= n; ++i) {
        if (i == k + 1) continue;  // merged into part k
        parts.push_back(i == k ? G[static_cast<size_t>(k)] * motion * G[static_cast<size_t>(k + 1)]
                               : G[static_cast<size_t>(i)]);
    }
    for (int i = 0; i < n; ++i) {
        if (i == k) continue;
        const Joint& Ji = joints_[static_cast<size_t>(i)];
        prismatic.push_back(Ji.prismatic);
        lo.push_back(Ji.lo);
        hi.push_back(Ji.hi);
    }
    const std::vector<Pose> offsets(static_cast<size_t>(n - 1));
    return from_transforms(n - 1, parts.front(), parts.data() + 1, parts.back(), offsets.data(),
                           reinterpret_cast<const bool*>(prismatic.data()), lo.data(), hi.data(),
                           base_);
}

inline Chain Chain::reversed() const {
    const int n = dof();
    std::vector<Pose> between, offsets(static_cast<size_t>(n));
    for (int i = n - 2; i >= 0; --i) between.push_back(inverse(fixed_part(i)));
    std::vector<char> prismatic;
    std::vector<double> lo, hi;
    for (int i = n - 1; i >= 0; --i) {
        const Joint& J = joints_[static_cast<size_t>(i)];
        prismatic.push_back(J.prismatic);
        lo.push_back(-J.hi);
        hi.push_back(-J.lo);
    }
    return from_transforms(n, inverse(tool_) * inverse(fixed_part(n - 1)), between.data(),
                           inverse(start_), offsets.data(),
                           reinterpret_cast<const bool*>(prismatic.data()), lo.data(), hi.data(),
                           Pose{});
}

}  // namespace km
