// The sweep of a held end joint: the first of a grid of values, nearest a start, at which
// the target moved by the value has a solution (kinematica.ik.nearest_value: `auto` on a 7R
// arm held at its first or last joint). Values the reach bounds prove out of reach
// (reach_bounds.hpp) are not solved.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "moved.hpp"
#include "reach_bounds.hpp"
#include "types.hpp"

namespace km {

//! How a held end joint's value moves the target (moved_pose's arguments).
struct HeldMove {
    const double* parts;  //!< the move's parts A0, A1, A2 (4x4 rows each)
    bool after;           //!< the joint comes after the target (the last), else before
    bool slides;          //!< the joint slides, else turns
};

//! The reach bounds' screen of a moved target: dropped where its violation of the bounds
//! (nullptr: none) with the tolerance (position m, rotation rad) is above slack.
struct ReachScreen {
    const reach::Bounds* bounds;
    double position, rotation, slack;
    bool limits;  //!< q1 and q6 held within their limits
};

//! The index in grid (G values) of the first value v, in the order of |v - start| (of two
//! as near, the lower index), other than skip, not screened out, at which solve(pose of
//! the target t (16 values, rows) moved by v) is true; -1 where none is. order: scratch.
template <class Solve>
long first_held_value(const double* grid, long G, double start, double skip, const double* t,
                      const HeldMove& move, const ReachScreen& screen, std::vector<long>& order,
                      Solve&& solve) {
    order.resize(static_cast<size_t>(G));
    for (long j = 0; j < G; ++j) order[static_cast<size_t>(j)] = j;
    std::stable_sort(order.begin(), order.end(), [&](long a, long c) {
        return std::fabs(grid[a] - start) < std::fabs(grid[c] - start);
    });
    for (const long j : order) {
        const double v = grid[j];
        if (v == skip) continue;
        double moved[16];
        moved_pose(move.parts, v, move.after, move.slides, t, moved);
        const Pose pose = Pose::from_rows(moved);
        if (screen.bounds != nullptr &&
            reach::violation(*screen.bounds, pose, screen.position, screen.rotation, screen.limits) >
                screen.slack) {
            continue;
        }
        if (solve(pose)) return j;
    }
    return -1;
}

}  // namespace km
