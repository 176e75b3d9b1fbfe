// How far a 4x4 matrix is from a rigid transform: the defects of an IK target.
#pragma once

#include <cmath>

#include "config.hpp"

namespace km {

//! The defects of a 4x4 matrix as a rigid transform.
struct PoseDefects {
    bool finite = true;     //!< every entry finite (else the others are NaN)
    double last_row = 0.0;  //!< max |last row − [0, 0, 0, 1]|
    double ortho = 0.0;     //!< max |RᵀR − I| of the rotation block
    double det = 1.0;       //!< det R
};

//! The defects of T (row-major 4x4).
KM_HD inline PoseDefects pose_defects(const double* T) {
    PoseDefects d;
    for (int i = 0; i < 16; ++i) d.finite = d.finite && std::isfinite(T[i]);
    if (!d.finite) {
        d.last_row = d.ortho = d.det = NaN;
        return d;
    }
    // every entry is finite from here: plain comparisons, not std::fmax's library calls
    const auto larger = [](double a, double b) { return b > a ? b : a; };
    d.last_row = larger(larger(std::fabs(T[12]), std::fabs(T[13])),
                        larger(std::fabs(T[14]), std::fabs(T[15] - 1.0)));
    double ortho = 0.0;
    for (int i = 0; i < 3; ++i) {
        for (int j = i; j < 3; ++j) {
            double g = T[i] * T[j] + T[4 + i] * T[4 + j] + T[8 + i] * T[8 + j];
            if (i == j) g -= 1.0;
            ortho = larger(ortho, std::fabs(g));
        }
    }
    d.ortho = ortho;
    d.det = T[0] * (T[5] * T[10] - T[6] * T[9]) - T[1] * (T[4] * T[10] - T[6] * T[8]) +
            T[2] * (T[4] * T[9] - T[5] * T[8]);
    return d;
}

}  // namespace km
