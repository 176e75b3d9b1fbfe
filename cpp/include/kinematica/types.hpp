// Small value types: a 3-vector, and a rigid transform held as its four columns.
//
// Kept to what the kinematics needs (no general matrices): a kernel holds these in
// registers, and a CUDA build can compile them as they are.
#pragma once

#include <cmath>

#include "config.hpp"

namespace km {

struct Vec3 {
    double x = 0.0, y = 0.0, z = 0.0;

    KM_HD double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    KM_HD double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

KM_HD inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
KM_HD inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
KM_HD inline Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
KM_HD inline Vec3 operator*(double s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
KM_HD inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
KM_HD inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
//! |a × b|² (exact near parallel, unlike 1 - (a·b)² for unit vectors).
KM_HD inline double cross2(const Vec3& a, const Vec3& b) {
    const Vec3 c = cross(a, b);
    return c.x * c.x + c.y * c.y + c.z * c.z;
}
KM_HD inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

//! A rigid transform: rotation columns x, y, z and the origin p (all in the outer frame).
struct Pose {
    Vec3 x{1.0, 0.0, 0.0}, y{0.0, 1.0, 0.0}, z{0.0, 0.0, 1.0}, p{0.0, 0.0, 0.0};

    //! R v.
    KM_HD Vec3 rotate(const Vec3& v) const {
        return {x.x * v.x + y.x * v.y + z.x * v.z, x.y * v.x + y.y * v.y + z.y * v.z,
                x.z * v.x + y.z * v.y + z.z * v.z};
    }
    //! Rᵀ v.
    KM_HD Vec3 unrotate(const Vec3& v) const { return {dot(x, v), dot(y, v), dot(z, v)}; }
    //! R v + p.
    KM_HD Vec3 apply(const Vec3& v) const { return rotate(v) + p; }
    //! Row i of R.
    KM_HD Vec3 row(int i) const { return {x[i], y[i], z[i]}; }
    //! Entry (i, j) of the homogeneous matrix (rows 0-2).
    KM_HD double at(int i, int j) const {
        return j == 0 ? x[i] : (j == 1 ? y[i] : (j == 2 ? z[i] : p[i]));
    }

    //! From a row-major 4x4 (or 3x4) array; the last row is not read.
    KM_HD static Pose from_rows(const double* T) {
        Pose P;
        P.x = {T[0], T[4], T[8]};
        P.y = {T[1], T[5], T[9]};
        P.z = {T[2], T[6], T[10]};
        P.p = {T[3], T[7], T[11]};
        return P;
    }
    //! Into a row-major 4x4 array, last row [0, 0, 0, 1].
    KM_HD void to_rows(double* T) const {
        T[0] = x.x; T[1] = y.x; T[2] = z.x; T[3] = p.x;
        T[4] = x.y; T[5] = y.y; T[6] = z.y; T[7] = p.y;
        T[8] = x.z; T[9] = y.z; T[10] = z.z; T[11] = p.z;
        T[12] = 0.0; T[13] = 0.0; T[14] = 0.0; T[15] = 1.0;
    }
};

//! A matrix-like field from row-major values (for code written by `kinematica convert
//! --to cpp`, which sees a (4, 4) field as numbers only).
KM_HD inline void assign_rows(Pose& P, const double* rows) { P = Pose::from_rows(rows); }
template <int R, int C>
KM_HD inline void assign_rows(double (&a)[R][C], const double* rows) {
    for (int i = 0; i < R; ++i) {
        for (int j = 0; j < C; ++j) a[i][j] = rows[i * C + j];
    }
}

//! A · B.
KM_HD inline Pose operator*(const Pose& A, const Pose& B) {
    Pose C;
    C.x = A.rotate(B.x);
    C.y = A.rotate(B.y);
    C.z = A.rotate(B.z);
    C.p = A.apply(B.p);
    return C;
}

//! A⁻¹ of a rigid transform.
KM_HD inline Pose inverse(const Pose& A) {
    Pose C;
    C.x = A.row(0);
    C.y = A.row(1);
    C.z = A.row(2);
    C.p = -C.rotate(A.p);
    return C;
}

}  // namespace km
