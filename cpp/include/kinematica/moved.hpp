// A pose of a whole arm as the target of the arm its first or last joint's lock leaves:
// the held joint's value moves the target, so the locked arm is built once (kinematica.ik.moved).
#pragma once

#include <cmath>

namespace km {

//! `out` (16 values, rows): T (16 values, rows) as the target of the arm locked at 0 at its
//! first joint (M(v) T, `after` false) or its last (T M(v)), M(v) = A0 + f1 A1 + f2 A2 with
//! f = (cos v, sin v) for a turn, (-v, 0) for a slide; A: the move's parts, 48 values (three
//! 4x4, rows), made once per arm by kinematica.ik.moved.
inline void moved_pose(const double* A, double v, bool after, bool slides, const double* T, double* out) {
    const double f1 = slides ? -v : std::cos(v);
    const double f2 = slides ? 0.0 : std::sin(v);
    double M[16];
    for (int i = 0; i < 16; ++i) M[i] = A[i] + f1 * A[16 + i] + f2 * A[32 + i];
    const double* left = after ? T : M;
    const double* right = after ? M : T;
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
            double sum = 0.0;
            for (int k = 0; k < 4; ++k) sum += left[4 * r + k] * right[4 * k + c];
            out[4 * r + c] = sum;
        }
    }
}

}  // namespace km
