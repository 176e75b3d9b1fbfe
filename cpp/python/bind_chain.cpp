// The chain: construction, forward kinematics, Jacobians and joint axes, one configuration
// or a batch.
#include <algorithm>
#include <atomic>
#include <utility>
#include <vector>

#include "casters.hpp"
#include "common.hpp"
#include "kinematica/chain.hpp"
#include "kinematica/jacobian.hpp"
#include "interrupt.hpp"
#include "kinematica/singular.hpp"
#include "kinematica/volume.hpp"

namespace kmpy {

namespace {

using km::Chain;
using km::ChainView;
using km::Pose;
using km::QState;

//! Records every frame into rows of a (n + 1, 4, 4) array.
struct FramesInto {
    static constexpr bool frames = true;
    static constexpr bool axes = false;
    double* out;
    void frame(int i, const Pose& F) { F.to_rows(out + 16 * i); }
    void axis(int, const km::Vec3&, const km::Vec3&) {}
};

//! Records every joint axis into rows of a (n, 6) array.
struct AxesInto {
    static constexpr bool frames = false;
    static constexpr bool axes = true;
    double* out;
    void frame(int, const Pose&) {}
    void axis(int i, const km::Vec3& z, const km::Vec3& p) { put(p, put(z, out + 6 * i)); }
};

void fill_nan(double* p, npy_intp count) { std::fill_n(p, count, km::NaN); }

//! What the blocks of a batch count: configurations holding NaN/inf, beyond their own
//! limits, and with a joint beyond a full turn (km::beyond_turn), so that Python reads the
//! batch again only to name the first of them.
struct Counts {
    std::atomic<long> bad{0}, outside{0}, turns{0};
};

//! Count configuration q's state st (not ok) into bad, outside and turns.
inline void count_state(const ChainView& ch, const double* q, QState st, long& bad, long& outside,
                        long& turns) {
    bad += st == QState::not_finite;
    outside += st == QState::outside_limits;
    turns += st == QState::beyond_turn || km::beyond_turn(ch, q);
}

//! Scratch of the joint trigonometry of a block of up to Rows configurations: on the stack
//! for up to 8 joints. (Storage only: the trigonometry is computed by its users.)
template <long Rows = FK_BLOCK>
class BlockTrig {
public:
    BlockTrig(int n, long m) : size_(static_cast<size_t>(m * n)) {
        base_ = stack_;
        if (3 * size_ > sizeof(stack_) / sizeof(double)) {
            heap_.resize(3 * size_);
            base_ = heap_.data();
        }
    }
    double* c() { return base_; }
    double* s() { return base_ + size_; }
    double* angle() { return base_ + 2 * size_; }

private:
    size_t size_;
    double stack_[3 * Rows * 8];
    std::vector<double> heap_;
    double* base_;
};

//! FK of rows [b0, b1) of Q into poses (and frames, when given).
KM_CLONES void fk_block(const ChainView& ch, const double* Q, long b0, long b1, double* poses,
                        double* frames, Counts& counts) {
    const int n = ch.n;
    BlockTrig<> trig(n, b1 - b0);
    km::joint_trig_rows(ch, Q + b0 * n, static_cast<int>(b1 - b0), trig.angle(), trig.c(), trig.s());
    long bad = 0, outside = 0, turns = 0;
    for (long b = b0; b < b1; ++b) {
        const double* q = Q + b * n;
        const double* c = trig.c() + (b - b0) * n;
        const double* s = trig.s() + (b - b0) * n;
        Pose T;
        if (frames != nullptr) {
            T = km::walk(ch, q, c, s, FramesInto{frames + b * 16 * (n + 1)});
        } else {
            T = km::walk(ch, q, c, s);
        }
        T.to_rows(poses + 16 * b);
        const QState st = km::q_state(ch, q);
        if (st == QState::ok) continue;
        count_state(ch, q, st, bad, outside, turns);
        if (st == QState::not_finite) {
            fill_nan(poses + 16 * b, 16);
            if (frames != nullptr) fill_nan(frames + b * 16 * (n + 1), 16 * (n + 1));
        }
    }
    counts.bad += bad;
    counts.outside += outside;
    counts.turns += turns;
}

//! Jacobians of rows [b0, b1) of Q.
KM_CLONES void jacobian_block(const ChainView& ch, const double* Q, long b0, long b1,
                              bool tool_frame, double* J, Counts& counts) {
    const int n = ch.n;
    BlockTrig<> trig(n, b1 - b0);
    km::joint_trig_rows(ch, Q + b0 * n, static_cast<int>(b1 - b0), trig.angle(), trig.c(), trig.s());
    long bad = 0, outside = 0, turns = 0;
    for (long b = b0; b < b1; ++b) {
        const double* q = Q + b * n;
        double* Jb = J + b * 6 * n;
        km::jacobian(ch, q, trig.c() + (b - b0) * n, trig.s() + (b - b0) * n, tool_frame, Jb);
        const QState st = km::q_state(ch, q);
        if (st == QState::ok) continue;
        count_state(ch, q, st, bad, outside, turns);
        if (st == QState::not_finite) fill_nan(Jb, 6 * n);
    }
    counts.bad += bad;
    counts.turns += turns;
}

In check_q(const Chain& chain, F64 q) { return in_f64(q, "q", 1, {chain.dof()}); }

In check_batch(const Chain& chain, F64 Q) { return in_f64(Q, "Q", 2, {-1, chain.dof()}); }

//! (f's values of q (n,) in a new array of shape `dims`, NaN where q holds NaN/inf; q's
//! state): f(view, q, c, s, out) with the joint trigonometry's scratch c, s.
template <class F>
nb::tuple of_one(const Chain& chain, F64 q, std::initializer_list<npy_intp> dims, const F& f) {
    const In in = check_q(chain, q);
    const ChainView ch = chain.view();
    BlockTrig<1> trig(ch.n, 1);
    double* out;
    nb::object A = new_f64(dims, out);
    f(ch, in.data, trig.c(), trig.s(), out);
    const QState st = km::q_state(ch, in.data);
    if (st == QState::not_finite) fill_nan(out, PyArray_SIZE(reinterpret_cast<PyArrayObject*>(A.ptr())));
    return nb::make_tuple(A, static_cast<int>(st));
}

nb::tuple fk_one(const Chain& chain, F64 q) {
    return of_one(chain, q, {4, 4},
                  [](const ChainView& ch, const double* qd, double* c, double* s, double* out) {
                      km::fk(ch, qd, c, s).to_rows(out);
                  });
}

nb::tuple fk_frames_one(const Chain& chain, F64 q) {
    return of_one(chain, q, {chain.dof() + 1, 4, 4},
                  [](const ChainView& ch, const double* qd, double* c, double* s, double* out) {
                      km::joint_trig(ch, qd, c, s);
                      km::walk(ch, qd, c, s, FramesInto{out});
                  });
}

nb::tuple fk_many(const Chain& chain, F64 Qh, bool all_frames, int workers) {
    const In Q = check_batch(chain, Qh);
    const ChainView ch = chain.view();
    const int n = ch.n;
    const npy_intp B = Q.dim[0];
    double* poses;
    nb::object P = new_f64({B, 4, 4}, poses);
    double* frames = nullptr;
    nb::object F;
    if (all_frames) F = new_f64({B, n + 1, 4, 4}, frames);
    Counts counts;
    run_rows(B, FK_BLOCK, workers,
             [&](long b0, long b1) { fk_block(ch, Q.data, b0, b1, poses, frames, counts); });
    return nb::make_tuple(all_frames ? F : P, counts.bad.load(), counts.outside.load(),
                          counts.turns.load());
}

nb::tuple jacobian_one(const Chain& chain, F64 q, bool tool_frame) {
    return of_one(chain, q, {6, chain.dof()},
                  [tool_frame](const ChainView& ch, const double* qd, double* c, double* s, double* out) {
                      km::joint_trig(ch, qd, c, s);
                      km::jacobian(ch, qd, c, s, tool_frame, out);
                  });
}

nb::tuple jacobian_many(const Chain& chain, F64 Qh, bool tool_frame, int workers) {
    const In Q = check_batch(chain, Qh);
    const ChainView ch = chain.view();
    const int n = ch.n;
    const npy_intp B = Q.dim[0];
    double* out;
    nb::object J = new_f64({B, 6, n}, out);
    Counts counts;
    run_rows(B, FK_BLOCK, workers,
             [&](long b0, long b1) { jacobian_block(ch, Q.data, b0, b1, tool_frame, out, counts); });
    return nb::make_tuple(J, counts.bad.load(), counts.turns.load());
}

//! The rows of a 6-row Jacobian a bit mask names (bit r: row r), ascending; their count.
int mask_rows(int mask, int* rows) {
    if (mask < 1 || mask > 63) throw nb::value_error("rows must be a bit mask of Jacobian rows 0-5 (1-63)");
    int m = 0;
    for (int r = 0; r < 6; ++r) {
        if ((mask >> r) & 1) rows[m++] = r;
    }
    return m;
}

//! km::singular_values_lanes of SV_LANES matrices, compiled for each target of KM_CLONES (the
//! loops over lanes become AVX-512 or AVX2 instructions where the processor has them).
KM_CLONES void lanes_kernel(const double* const* in, int count, int m, int n, double* W,
                            double* const* out) {
    km::singular_values_lanes<km::SV_LANES>(in, count, m, n, W, out);
}

//! Matrices waiting for one km::singular_values_lanes call (SV_LANES side by side).
struct Lanes {
    int m, n, count = 0;
    std::vector<double> A, W;
    const double* in[km::SV_LANES];
    double* out[km::SV_LANES];
    Lanes(int m_, int n_)
        : m(m_), n(n_), A(static_cast<size_t>(m_ * n_ * km::SV_LANES)), W(A.size()) {}
    //! The next lane's matrix storage (m x n, row-major); its values go to `s` at the flush.
    double* add(double* s) {
        double* a = A.data() + static_cast<size_t>(count) * static_cast<size_t>(m * n);
        in[count] = a;
        out[count++] = s;
        return a;
    }
    bool full() const { return count == km::SV_LANES; }
    void flush() {
        if (count > 0) lanes_kernel(in, count, m, n, W.data(), out);
        count = 0;
    }
};

//! Singular values of the Jacobians (the rows of `mask`) of rows [b0, b1) of Q, into S
//! (min(m, n) a row), SV_LANES at a time; with `volume`, their product alone (one a row,
//! km::volume: a determinant, no SVD). Rows come in groups of `group` (the solutions of
//! one target): a row whose Jacobian equals an earlier one's of its group up to column
//! signs (a wrist flip) takes its values; a row holding NaN/inf gets NaN without a walk.
KM_CLONES void singular_block(const ChainView& ch, const double* Q, long b0, long b1, const int* rows,
                              int m, int group, bool volume, double* S) {
    const int n = ch.n;
    const int k = volume ? 1 : (m < n ? m : n);
    BlockTrig<> trig(n, b1 - b0);
    km::joint_trig_rows(ch, Q + b0 * n, static_cast<int>(b1 - b0), trig.angle(), trig.c(), trig.s());
    const size_t mn = static_cast<size_t>(m) * static_cast<size_t>(n);
    std::vector<double> J(6 * static_cast<size_t>(n)), A(mn * static_cast<size_t>(group));
    std::vector<long> kept(static_cast<size_t>(group));
    std::vector<std::pair<long, long>> copies;  // (row, its twin): filled once computed
    Lanes lanes(m, n);
    for (long g0 = b0; g0 < b1; g0 += group) {
        int n_kept = 0;
        for (long b = g0; b < g0 + group; ++b) {
            const double* q = Q + b * n;
            double* out = S + b * k;
            if (km::q_state(ch, q) == QState::not_finite) {
                fill_nan(out, k);
                continue;
            }
            km::jacobian(ch, q, trig.c() + (b - b0) * n, trig.s() + (b - b0) * n, false, J.data());
            double* Ab = A.data() + static_cast<size_t>(n_kept) * mn;
            for (int i = 0; i < m; ++i) {
                for (int j = 0; j < n; ++j) Ab[i * n + j] = J[static_cast<size_t>(rows[i] * n + j)];
            }
            long twin = -1;
            for (int p = 0; p < n_kept && twin < 0; ++p) {
                if (km::same_up_to_column_signs(A.data() + static_cast<size_t>(p) * mn, Ab, m, n)) {
                    twin = kept[static_cast<size_t>(p)];
                }
            }
            if (twin >= 0) {
                copies.emplace_back(b, twin);
                continue;
            }
            kept[static_cast<size_t>(n_kept++)] = b;
            if (volume) {
                out[0] = km::volume(Ab, m, n);
                continue;
            }
            double* lane = lanes.add(out);
            for (size_t e = 0; e < mn; ++e) lane[e] = Ab[e];
            if (lanes.full()) lanes.flush();
        }
    }
    lanes.flush();
    for (const auto& [row, twin] : copies) {
        for (int i = 0; i < k; ++i) S[row * k + i] = S[twin * k + i];
    }
}

F64 jacobian_singular_values(const Chain& chain, F64 Qh, int mask, int group, int workers,
                             bool volume) {
    const In Q = check_batch(chain, Qh);
    const ChainView ch = chain.view();
    int rows[6];
    const int m = mask_rows(mask, rows);
    const int k = volume ? 1 : (m < ch.n ? m : ch.n);
    const npy_intp B = Q.dim[0];
    if (group < 1 || group > km::MAX_SLOTS || B % group != 0) {
        throw nb::value_error("group must be 1-16 rows and divide the rows of Q");
    }
    double* out;
    F64 S = new_f64({B, k}, out);
    const long per_block = group * ((FK_BLOCK + group - 1) / group);  // whole groups
    run_rows(B, per_block, workers,
             [&](long b0, long b1) { singular_block(ch, Q.data, b0, b1, rows, m, group, volume, out); });
    return S;
}

//! Singular values of a batch of small matrices (B, m, n), min(m, n) <= MAX_SINGULAR.
F64 singular_values_many(F64 Ah, int workers) {
    const In A = in_f64(Ah, "A", 3);
    const npy_intp B = A.dim[0], m = A.dim[1], n = A.dim[2];
    if (m < 1 || n < 1) throw nb::value_error("A must hold matrices of at least one row and column");
    const npy_intp k = m < n ? m : n;
    if (k > km::MAX_SINGULAR || m * n > 6 * 4096) {
        throw nb::value_error("A's matrices must have at most 6 rows or 6 columns, and 24,576 entries");
    }
    double* out;
    F64 S = new_f64({B, k}, out);
    run_rows(B, FK_BLOCK, workers, [&](long b0, long b1) {
        Lanes lanes(static_cast<int>(m), static_cast<int>(n));
        for (long b = b0; b < b1; ++b) {
            double* a = lanes.add(out + b * k);
            const double* from = A.data + b * m * n;
            for (npy_intp e = 0; e < m * n; ++e) a[e] = from[e];
            if (lanes.full()) lanes.flush();
        }
        lanes.flush();
    });
    return S;
}

F64 joint_axes(const Chain& chain, F64 Qh, int workers) {
    const In Q = check_batch(chain, Qh);
    const ChainView ch = chain.view();
    const int n = ch.n;
    const npy_intp B = Q.dim[0];
    double* out;
    F64 A = new_f64({B, n, 6}, out);
    run_rows(B, FK_BLOCK, workers, [&](long b0, long b1) {
        std::vector<double> c(static_cast<size_t>(n)), s(c.size());
        for (long b = b0; b < b1; ++b) {
            const double* q = Q.data + b * n;
            km::joint_trig(ch, q, c.data(), s.data());
            km::walk(ch, q, c.data(), s.data(), AxesInto{out + b * 6 * n});
            if (km::q_state(ch, q) == QState::not_finite) fill_nan(out + b * 6 * n, 6 * n);
        }
    });
    return A;
}

//! prismatic as the core reads it: n flags (a bool vector of length n >= 1).
std::vector<char> joint_flags(Bools prismatic, npy_intp n) {
    if (n < 1) throw nb::value_error("a chain needs at least one joint");
    const npy_bool* pr = in_flags(prismatic, "prismatic", n);
    if (pr == nullptr) throw nb::type_error("prismatic must be a bool array");
    std::vector<char> p(static_cast<size_t>(n));
    for (npy_intp i = 0; i < n; ++i) p[static_cast<size_t>(i)] = pr[i] != 0;
    return p;
}

Chain from_dh(Bools prismatic, F64 theta, F64 d, F64 a, F64 alpha,
              F64 lo, F64 hi, bool modified, const Pose& base, const Pose& tool) {
    const In th = in_f64(theta, "theta", 1);
    const npy_intp n = th.dim[0];
    const std::vector<char> p = joint_flags(prismatic, n);
    const In dd = in_f64(d, "d", 1, {n}), aa = in_f64(a, "a", 1, {n}), al = in_f64(alpha, "alpha", 1, {n});
    const In l = in_f64(lo, "lo", 1, {n}), h = in_f64(hi, "hi", 1, {n});
    return Chain::from_dh(static_cast<int>(n), reinterpret_cast<const bool*>(p.data()), th.data,
                          dd.data, aa.data, al.data, l.data, h.data, modified, base, tool);
}

Chain from_transforms(const Pose& start, F64 between, const Pose& tool, F64 offsets,
                      Bools prismatic, F64 lo, F64 hi, const Pose& base) {
    const In off = in_f64(offsets, "frame_offsets", 3, {-1, 4, 4});
    const npy_intp n = off.dim[0];
    const std::vector<char> p = joint_flags(prismatic, n);
    const In btw = in_f64(between, "between", 3, {n - 1, 4, 4});
    const In l = in_f64(lo, "lo", 1, {n}), h = in_f64(hi, "hi", 1, {n});
    std::vector<Pose> B(static_cast<size_t>(n > 1 ? n - 1 : 0)), O(static_cast<size_t>(n));
    for (npy_intp i = 0; i + 1 < n; ++i) B[static_cast<size_t>(i)] = Pose::from_rows(btw.data + 16 * i);
    for (npy_intp i = 0; i < n; ++i) O[static_cast<size_t>(i)] = Pose::from_rows(off.data + 16 * i);
    return Chain::from_transforms(static_cast<int>(n), start, B.data(), tool, O.data(),
                                  reinterpret_cast<const bool*>(p.data()), l.data, h.data, base);
}

}  // namespace

void bind_chain(nb::module_& m) {
    nb::class_<Chain>(m, "Chain", "A serial chain compiled for the core (see chain.hpp).")
        .def_static("from_dh", &from_dh, nb::arg("prismatic"), nb::arg("theta"), nb::arg("d"),
                    nb::arg("a"), nb::arg("alpha"), nb::arg("lo"), nb::arg("hi"),
                    nb::arg("modified"), nb::arg("base"), nb::arg("tool"),
                    "A DH table (rows of both conventions) with base and tool.")
        .def_static("from_transforms", &from_transforms, nb::arg("start"), nb::arg("between"),
                    nb::arg("tool"), nb::arg("frame_offsets"), nb::arg("prismatic"),
                    nb::arg("lo"), nb::arg("hi"), nb::arg("base"),
                    "General transforms: T = start · Π_i [M_i(q_i) · between_i] · tool.")
        .def_prop_ro("qlim", [](const Chain& c) {
            double* out;
            F64 a = new_f64({c.dof(), 2}, out);
            for (const km::Joint& j : c.joints()) {
                *out++ = j.qlo;
                *out++ = j.qhi;
            }
            return a;
        }, "(n, 2) the limits solutions are held to: own, else (-π, π) revolute, ±inf prismatic.")
        .def_prop_ro("translations", [](const Chain& c) {
            double* out;
            F64 a = new_f64({c.dof(), 3}, out);
            for (const km::Joint& j : c.joints()) out = put(j.t, out);
            return a;
        }, "(n, 3) the translation of each joint's fixed part, in its frame (m); a DH row's (a, 0, d).")
        .def_prop_ro("fixed_parts", [](const Chain& c) {
            double* out;
            F64 a = new_f64({c.dof(), 4, 4}, out);
            for (int i = 0; i < c.dof(); ++i) c.fixed_part(i).to_rows(out + 16 * i);
            return a;
        }, "(n, 4, 4) each joint's fixed part Rz(θ) Trans(t) Rx(α), after its motion.")
        .def("locked", [](const Chain& c, int joint, double value) {
            if (c.dof() < 2) throw nb::value_error("a chain of one joint has no joint left once it is locked");
            if (joint < 0 || joint >= c.dof()) throw nb::index_error("joint out of range");
            if (!std::isfinite(value)) throw nb::value_error("the value of a locked joint must be finite");
            return c.locked(joint, value);
        }, nb::arg("joint"), nb::arg("value"), "The chain of the other joints, joint held at value.")
        .def("reversed", &Chain::reversed, "The chain of the inverse transform (chain.hpp).")
        .def_prop_ro("start", [](const Chain& c) { return c.view().start; })
        .def_prop_ro("tool", [](const Chain& c) { return c.view().tool; })
        .def("fk", &fk_one, nb::arg("q"), "(T (4, 4), state) of q (n,); state 1: NaN/inf, 2: outside own limits.")
        .def("fk_frames", &fk_frames_one, nb::arg("q"), "(frames (n + 1, 4, 4), state) of q (n,).")
        .def("fk_batch", &fk_many, nb::arg("Q"), nb::arg("all_frames"), nb::arg("workers"),
             "(poses (B, 4, 4) or frames (B, n + 1, 4, 4), bad, outside, turns) of Q (B, n).")
        .def("jacobian", &jacobian_one, nb::arg("q"), nb::arg("tool_frame"), "(J (6, n), state) of q (n,).")
        .def("jacobian_batch", &jacobian_many, nb::arg("Q"), nb::arg("tool_frame"),
             nb::arg("workers"), "(J (B, 6, n), bad, turns) of Q (B, n), counted as for fk_batch.")
        .def("jacobian_singular_values", &jacobian_singular_values, nb::arg("Q"), nb::arg("rows"),
             nb::arg("group") = 1, nb::arg("workers") = 1, nb::arg("volume") = false,
             "(B, min(m, n)) the singular values of the Jacobian rows the bit mask `rows` names.")
        .def("joint_axes", &joint_axes, nb::arg("Q"), nb::arg("workers") = 1, "(B, n, 6) axes: direction, point.");
    m.def("singular_values", &singular_values_many, nb::arg("A"), nb::arg("workers") = 1,
          "(B, min(m, n)): the singular values, largest first, of A (B, m, n), min(m, n) <= 6.");
}

}  // namespace kmpy
