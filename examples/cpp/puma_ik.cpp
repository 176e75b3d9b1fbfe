// Forward kinematics and every inverse-kinematics solution of the PUMA 560, in C++, with
// kinematica's core alone (its headers include nothing from Python).
//
// The chain and the solver filled for this arm come from a header kinematica writes:
//
//     kinematica convert puma560 --to cpp -o puma560_ik.hpp
//     c++ -std=c++17 -O2 -I cpp/include -I . examples/cpp/puma_ik.cpp -o puma_ik
//     ./puma_ik 0.1 -0.5 0.3 0.7 0.4 -0.2        # joint values (rad); these by default
//
// It prints the tool pose at those joint values, then each solution of that pose with
// its branch and its residuals, checked by forward kinematics as robot.ik checks them.
#include <cstdio>
#include <cstdlib>

#include "kinematica/chain.hpp"
#include "kinematica/ik.hpp"
#include "puma560_ik.hpp"

int main(int argc, char** argv) {
    double q[6] = {0.1, -0.5, 0.3, 0.7, 0.4, -0.2};
    for (int i = 0; i < 6 && i + 1 < argc; ++i) q[i] = std::atof(argv[i + 1]);

    const km::Chain chain = puma_560::chain();
    const km::ChainView ch = chain.view();
    double c[6], s[6];
    const km::Pose T = km::fk(ch, q, c, s);
    std::printf("T =\n");
    for (int i = 0; i < 3; ++i) {
        std::printf("  %12.9f %12.9f %12.9f %12.9f\n", T.x[i], T.y[i], T.z[i], T.p[i]);
    }

    const puma_560::Solver params = puma_560::solver();
    const km::ClosedForm<puma_560::Solver> solver{params};
    km::IKWork<km::ClosedForm<puma_560::Solver>> work(solver, 6);
    km::CheckOptions options;
    options.complete = true;  // a closed form: every solution, and a proof when there is none
    double Q[8 * 6], residuals[8 * 2];
    int slot[8];
    const km::CheckReport report =
        km::solve_ik(solver, ch, T, options, nullptr, work, km::CheckOut{Q, slot, residuals});

    std::printf("status %d, %d solutions (%d more outside the joint limits)\n",
                static_cast<int>(report.status), report.count, report.out_count);
    for (int r = 0; r < report.count; ++r) {
        std::printf("%-44s", puma_560::labels[slot[r]]);
        for (int j = 0; j < 6; ++j) std::printf(" %12.9f", Q[6 * r + j]);
        std::printf("   %.1e m %.1e rad\n", residuals[2 * r], residuals[2 * r + 1]);
    }
    return report.count > 0 ? 0 : 1;
}
