// Sine and cosine of one angle, written so that a loop over angles vectorises.
//
// The C library's sin and cos take one value at a time (about 25 ns for both on the
// development machine) and no vector maths library is available without -ffast-math,
// which would break NaN handling and the 1e-12 agreement with the references. This is
// fdlibm's scheme instead: reduce the angle by a multiple n of π/2 (π/2 split in three
// parts, Cody-Waite, so that n·P1 and n·P2 are exact for |n| < 2^20), evaluate the
// minimax polynomials of __kernel_sin and __kernel_cos on [-π/4, π/4], then choose the
// quadrant's sign without a branch. n is rounded with the 1.5·2^52 trick, whose low
// bits are n mod 4: no floor call, no integer conversion, so a loop over angles becomes
// SIMD code (about 2 ns for both with AVX2). Within 1 ulp of the C library for |x| < 10
// (joint angles) and 2 ulps up to REDUCTION_LIMIT (the reduced angle's rounding tail,
// which fdlibm carries on, is dropped); beyond it sincos() falls back to the C library.
// At a tie of the reduction (x·2/π = k + 1/2) n is rounded to even, as the C library
// reduces, not up.
// The results do not depend on the vector width: every step is one IEEE operation
// (the core is built with -ffp-contract=off).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include "config.hpp"

namespace km {

//! Largest |x| the three-part reduction handles exactly (|n| < 2^20).
constexpr double REDUCTION_LIMIT = 1.0e6;

namespace detail {
constexpr double TWO_OVER_PI = 6.36619772367581382433e-01;
// π/2 = P1 + P2 + P3 (fdlibm's pio2_1, pio2_2, pio2_2t): P1 and P2 have 33 significant bits.
constexpr double P1 = 1.57079632673412561417e00;
constexpr double P2 = 6.07710050630396597660e-11;
constexpr double P3 = 2.02226624879595063154e-21;
constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                 S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                 S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                 C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                 C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
//! Adding 1.5·2^52 rounds a double of magnitude below 2^51 to an integer (to nearest).
constexpr double ROUND_SHIFT = 6755399441055744.0;
}  // namespace detail

//! (sin x, cos x) for |x| <= REDUCTION_LIMIT, branch-free; NaN and inf give NaN.
KM_HD KM_INLINE void sincos_reduced(double x, double& s, double& c) {
    using namespace detail;
    const double t = x * TWO_OVER_PI + ROUND_SHIFT;
    const double n = t - ROUND_SHIFT;
    std::int64_t bits;
    std::memcpy(&bits, &t, sizeof bits);  // the low mantissa bits of t are n mod 2^k
    const double r = ((x - n * P1) - n * P2) - n * P3;
    const double z = r * r;
    const double sv = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    const double hz = 0.5 * z;
    const double w = 1.0 - hz;
    const double cv =
        w + (((1.0 - w) - hz) + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))));
    const bool swap = (bits & 1) != 0;
    const double so = swap ? cv : sv;
    const double co = swap ? sv : cv;
    s = (bits & 2) != 0 ? -so : so;
    c = ((bits + 1) & 2) != 0 ? -co : co;
}

//! (sin x, cos x) for any x (the C library beyond REDUCTION_LIMIT).
KM_HD KM_INLINE void sincos(double x, double& s, double& c) {
    if (std::fabs(x) <= REDUCTION_LIMIT) {
        sincos_reduced(x, s, c);
    } else {
        s = std::sin(x);
        c = std::cos(x);
    }
}

//! sincos() of count angles: one loop the compiler vectorises, then the rare large ones.
KM_HD KM_INLINE void sincos_block(const double* x, double* s, double* c, int count) {
    for (int t = 0; t < count; ++t) sincos_reduced(x[t], s[t], c[t]);
    for (int t = 0; t < count; ++t) {
        if (!(std::fabs(x[t]) <= REDUCTION_LIMIT)) {
            s[t] = std::sin(x[t]);
            c[t] = std::cos(x[t]);
        }
    }
}

}  // namespace km
