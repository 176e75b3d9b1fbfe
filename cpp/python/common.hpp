// What every binding file shares: the multiversioning marker, block sizes, the
// registration functions of module.cpp.
#pragma once

#include <nanobind/nanobind.h>

namespace kmpy {

namespace nb = nanobind;

// Batch loops are compiled three times on x86-64, for AVX-512, AVX2 and the baseline, and the
// loader picks one (no -march=native needed): the joint trigonometry of a block then
// runs as 8- or 4-wide SIMD. The results are the same bits either way (no FMA contraction).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(KM_NO_CLONES)
#define KM_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define KM_CLONES
#endif

//! Configurations per block of an FK batch: a block's trigonometry stays in L1.
constexpr int FK_BLOCK = 256;
//! Targets per block of an IK batch: each block makes its work arrays once.
constexpr int TARGET_BLOCK = 64;

void bind_chain(nb::module_& m);
void bind_ik(nb::module_& m);
void bind_spatial(nb::module_& m);
void bind_solvers(nb::module_& m);
void bind_lines(nb::module_& m);
void bind_topp(nb::module_& m);   // bind_topp.cpp: the time-optimal timing of a path
void bind_jerk(nb::module_& m);   // bind_jerk.cpp: jerk-limited segments and waypoints
void bind_reach(nb::module_& m);  // bind_reach.cpp: a 6R arm's reach bounds, checked

}  // namespace kmpy
