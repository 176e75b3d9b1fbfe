// The core's hand-written small linear algebra against Eigen's (issue 33): ns per call of
// the damped 6x6 LDLT solve of the numeric search (linalg.hpp), the 3x3 symmetric
// eigenvalues by Jacobi (lines.hpp) and the 3x3 solve (lines.hpp), each on 1,024 random
// matrices, best of 7 passes. Build and run by hand (Eigen from the venv's cmeel-eigen):
//
//     g++ -std=c++17 -O3 -ffp-contract=off -fno-math-errno -DNDEBUG -I cpp/include \
//         -I .venv/lib/python3.11/site-packages/cmeel.prefix/include/eigen3 \
//         benchmarks/cpp/linalg_eigen.cpp -o /tmp/linalg_eigen && /tmp/linalg_eigen
//
// Measured 2026-12-07 on the shared 2-core machine (two runs): LDLT hand 23-43 ns, Eigen
// LDLT 139-271 ns, LLT 150-251 ns; Jacobi 237 ns, Eigen's SelfAdjointEigenSolver 263 ns
// (computeDirect 41 ns, the closed-form cubic lines.hpp declines for its accuracy on small
// eigenvalues); 3x3 solve hand 28-29 ns, Eigen partialPivLu 50-52 ns. The hand-written
// ones are kept: faster or as fast, and usable where Eigen is not (KM_HD device code, the
// headers a C++ program includes without Eigen).
#include <Eigen/Dense>
#include <chrono>
#include <cstdio>
#include <random>
#include "kinematica/linalg.hpp"
#include "kinematica/lines.hpp"

template <class F> double ns_per(F&& f, int reps) {
    double best = 1e300;
    for (int r = 0; r < 7; ++r) {
        auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < reps; ++i) f(i);
        auto t1 = std::chrono::steady_clock::now();
        best = std::min(best, std::chrono::duration<double, std::nano>(t1 - t0).count() / reps);
    }
    return best;
}
int main() {
    constexpr int M = 1024;
    std::mt19937_64 g(1);
    std::normal_distribution<double> N;
    static double G6[M][6][6], b6[M][6], A3[M][3][3], S3[M][3][3];
    static Eigen::Matrix<double, 6, 6> E6[M]; static Eigen::Matrix3d E3[M], ES3[M];
    for (int k = 0; k < M; ++k) {
        double J[6][6]; for (auto& r : J) for (double& v : r) v = N(g);
        for (int i = 0; i < 6; ++i) { b6[k][i] = N(g); for (int j = 0; j < 6; ++j) { double s = 0; for (int p = 0; p < 6; ++p) s += J[p][i] * J[p][j]; G6[k][i][j] = s; E6[k](i, j) = s; } }
        for (int i = 0; i < 3; ++i) for (int j = 0; j < 3; ++j) { A3[k][i][j] = N(g); E3[k](i, j) = A3[k][i][j]; }
        for (int i = 0; i < 3; ++i) for (int j = 0; j < 3; ++j) { double s = 0; for (int p = 0; p < 3; ++p) s += A3[k][p][i] * A3[k][p][j]; S3[k][i][j] = s; ES3[k](i, j) = s; }
    }
    volatile double sink = 0;
    const int R = 200000;
    double x[6];
    double t_ldl = ns_per([&](int i) { int k = i & (M - 1); km::detail::ldl_solve<6>(G6[k], 1e-9, b6[k], x); sink = sink + x[0]; }, R);
    double t_eldlt = ns_per([&](int i) { int k = i & (M - 1); Eigen::Matrix<double,6,6> A = E6[k]; A.diagonal().array() += 1e-9;
        Eigen::Matrix<double,6,1> v = A.ldlt().solve(Eigen::Map<const Eigen::Matrix<double,6,1>>(b6[k])); sink = sink + v(0); }, R);
    double t_ellt = ns_per([&](int i) { int k = i & (M - 1); Eigen::Matrix<double,6,6> A = E6[k]; A.diagonal().array() += 1e-9;
        Eigen::Matrix<double,6,1> v = A.llt().solve(Eigen::Map<const Eigen::Matrix<double,6,1>>(b6[k])); sink = sink + v(0); }, R);
    double ev[3];
    double t_jac = ns_per([&](int i) { int k = i & (M - 1); km::lines::symmetric_eigenvalues(S3[k], ev); sink = sink + ev[0]; }, R);
    double t_esa = ns_per([&](int i) { int k = i & (M - 1); Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> s(ES3[k], Eigen::EigenvaluesOnly); sink = sink + s.eigenvalues()(0); }, R);
    double t_edir = ns_per([&](int i) { int k = i & (M - 1); Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> s; s.computeDirect(ES3[k], Eigen::EigenvaluesOnly); sink = sink + s.eigenvalues()(0); }, R);
    double t_s3 = ns_per([&](int i) { int k = i & (M - 1); km::Vec3 r = km::lines::solve3(A3[k], km::Vec3{b6[k][0], b6[k][1], b6[k][2]}); sink = sink + r.x; }, R);
    double t_elu = ns_per([&](int i) { int k = i & (M - 1); Eigen::Vector3d r = E3[k].partialPivLu().solve(Eigen::Map<const Eigen::Vector3d>(b6[k])); sink = sink + r(0); }, R);
    std::printf("6x6 damped LDLT solve: hand %.1f ns, Eigen LDLT %.1f ns, Eigen LLT %.1f ns\n", t_ldl, t_eldlt, t_ellt);
    std::printf("3x3 symmetric eigenvalues: hand Jacobi %.1f ns, Eigen SelfAdjoint (QL) %.1f ns, Eigen computeDirect %.1f ns\n", t_jac, t_esa, t_edir);
    std::printf("3x3 solve: hand %.1f ns, Eigen partialPivLu %.1f ns\n", t_s3, t_elu);
    // agreement
    double worst = 0; for (int k = 0; k < M; ++k) { km::lines::symmetric_eigenvalues(S3[k], ev); Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> s(ES3[k], Eigen::EigenvaluesOnly); for (int j = 0; j < 3; ++j) worst = std::max(worst, std::fabs(ev[j] - s.eigenvalues()(j)) / s.eigenvalues()(2)); }
    std::printf("eigenvalues agree to %.2g (relative to the largest)\n", worst);
}
