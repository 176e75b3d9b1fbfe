// An arm's joint axes at q = 0 as lines, with what the closed forms' builders read: the
// structure (lines.hpp's axis_features), the arm's size, the tool pose at q = 0 and the
// limits solutions are held to. One walk of the chain; a builder (solvers/*_build.hpp)
// reads the rest from here, so a C++ program builds a solver from a Chain alone.
#pragma once

#include <memory>
#include <vector>

#include "chain.hpp"
#include "chain_build.hpp"
#include "lines.hpp"
#include "types.hpp"

namespace km {

//! The joint axes of a chain at q = 0 (base frame) and its structure.
struct ArmAxes {
    int n = 0;
    std::vector<Vec3> h;             //!< unit axis directions (n)
    std::vector<Vec3> p;             //!< a point on each axis (n, m)
    std::unique_ptr<bool[]> prismatic;  //!< (n) joint types
    std::unique_ptr<bool[]> parallel;   //!< (n - 1) axes i and i + 1 parallel
    std::unique_ptr<bool[]> meet;       //!< (n - 1) axes i and i + 1 meet (not parallel)
    lines::AxisFeatures features;    //!< the wrist and shoulder centres, the slack
    double size = 0.0;               //!< the arm's size (m), arm_size
    Pose home{};                     //!< M, the tool pose at q = 0
    std::vector<double> qlo, qhi;    //!< limits solutions are held to (Joint::qlo, qhi)

    //! Every joint revolute.
    bool all_revolute() const {
        for (int i = 0; i < n; ++i)
            if (prismatic[i]) return false;
        return true;
    }
    //! The distance (m) below which two of its lines meet: lines::length_tol(size).
    double length_tol() const { return lines::length_tol(size); }
};

//! A chain's axes at q = 0 and their features (one walk, one axis_features call).
inline ArmAxes arm_axes(const Chain& chain) {
    const ChainView ch = chain.view();
    ArmAxes A;
    const int n = A.n = ch.n;
    const auto N = static_cast<size_t>(n);
    A.h.resize(N);
    A.p.resize(N);
    A.qlo.resize(N);
    A.qhi.resize(N);
    A.prismatic.reset(new bool[N + 1]);
    A.parallel.reset(new bool[N + 1]);
    A.meet.reset(new bool[N + 1]);
    std::vector<double> q(N, 0.0), c(N), s(N);
    joint_trig(ch, q.data(), c.data(), s.data());
    A.home = walk(ch, q.data(), c.data(), s.data(), detail::AxesRecord{A.h.data(), A.p.data()});
    for (int i = 0; i < n; ++i) {
        A.prismatic[i] = ch.joint[i].prismatic;
        A.qlo[static_cast<size_t>(i)] = ch.joint[i].qlo;
        A.qhi[static_cast<size_t>(i)] = ch.joint[i].qhi;
    }
    A.size = arm_size(chain);
    A.features = lines::axis_features(A.h.data(), A.p.data(), A.prismatic.get(), n, A.size,
                                      A.parallel.get(), A.meet.get());
    return A;
}

}  // namespace km
