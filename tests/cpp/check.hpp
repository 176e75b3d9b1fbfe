// The C++ tests' assertions: CHECK(condition, format, ...) prints what failed and where,
// and counts it; main returns failures() (0: every check held; ctest reads the code).
#pragma once

#include <cmath>
#include <cstdio>

namespace kmtest {

inline int& failure_count() {
    static int count = 0;
    return count;
}

//! The exit code of a test program: 0 when every CHECK held, 1 otherwise.
inline int failures() {
    if (failure_count() > 0) std::printf("%d check(s) failed\n", failure_count());
    return failure_count() > 0 ? 1 : 0;
}

//! |a - b| wrapped to [0, π] (joint angles equal modulo 2π).
inline double angle_distance(double a, double b) { return std::fabs(std::remainder(a - b, 2.0 * M_PI)); }

}  // namespace kmtest

#define CHECK(cond, ...)                                                  \
    do {                                                                  \
        if (!(cond)) {                                                    \
            ++::kmtest::failure_count();                                  \
            std::printf("%s:%d: CHECK(%s) failed: ", __FILE__, __LINE__, #cond); \
            std::printf(__VA_ARGS__);                                     \
            std::printf("\n");                                            \
        }                                                                 \
    } while (0)
