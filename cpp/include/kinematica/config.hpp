// Build settings every header shares: the host/device marker and the limits of one target.
#pragma once

#include <limits>

// Marks functions a CUDA build may also compile for the device. Empty on the host.
#if defined(__CUDACC__)
#define KM_HD __host__ __device__
#else
#define KM_HD
#endif

// Forces inlining where a batch loop must see the code to vectorise it: a function the
// compiler keeps out of line would be compiled for the baseline target only, not for the
// AVX2 / AVX-512 copies of the loop that calls it.
#if defined(__GNUC__) || defined(__clang__)
#define KM_INLINE inline __attribute__((always_inline))
#else
#define KM_INLINE inline
#endif

namespace km {

//! Candidate slots one target may have (a general 6R arm has up to 16 solutions).
constexpr int MAX_SLOTS = 16;

constexpr double PI = 3.14159265358979323846;
constexpr double TWO_PI = 2.0 * PI;
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
constexpr double INF = std::numeric_limits<double>::infinity();

}  // namespace km
