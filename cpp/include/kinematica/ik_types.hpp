// What an IK solver hands the shared check for one target, and what the check reports.
#pragma once

#include <cstdint>

#include "config.hpp"

namespace km {

//! Joints a free-joint mask can name: bits 0..FREE_JOINTS-1. Only closed forms name free
//! joints, on arms of at most 32 joints (arm_position.hpp's MAX_POSITION_DOF; the others
//! 7), so every free joint fits; a chain may still have up to 100 joints (the numeric
//! search), whose bits past these read as not free: a shift of a 32-bit mask by 32 or
//! more is undefined.
constexpr int FREE_JOINTS = 32;

//! Bit j of a free-joint mask: false for j outside [0, FREE_JOINTS).
KM_HD inline bool free_bit(std::uint32_t mask, int j) {
    return j >= 0 && j < FREE_JOINTS && ((mask >> j) & 1U) != 0;
}

//! What a solver knows of one target besides its candidates.
struct SolverInfo {
    bool singular = false;  //!< the solutions form a continuum; candidates are representatives
    bool near = false;      //!< near a singular set, where a closed form may lose solutions to round-off
    double gap = NaN;       //!< a lower bound of the distance to the reachable set (m); NaN: unknown
    std::uint32_t free = 0; //!< bit j: joint j is free (in a continuum); j < FREE_JOINTS

    KM_HD void set_free(int j) {
        if (j >= 0 && j < FREE_JOINTS) free |= (std::uint32_t{1} << j);
    }
    KM_HD bool is_free(int j) const { return free_bit(free, j); }
};

//! The status of an IK answer (the ik layer names them).
enum class Status : int {
    ok = 0,             //!< every solution (closed form), or one (numeric)
    singular = 1,       //!< infinitely many: the rows are representatives
    out_of_limits = 2,  //!< solutions exist, none within the joint limits
    unreachable = 3,    //!< provably no solution
    not_found = 4,      //!< none found: the target may still be reachable
    invalid = 5,        //!< a malformed target in a batch
};

//! The acceptance tolerances of a solution, for the check and the numeric search alike:
//! their defaults are written here alone (kinematica.ik.Tolerance reads them).
struct Tolerance {
    double position = 1e-10;  //!< m
    double rotation = 1e-10;  //!< rad
};

//! How candidates are judged.
struct CheckOptions {
    Tolerance tol;                //!< a solution is within it of the target
    bool respect_limits = true;   //!< solutions outside the limits are listed apart
    bool complete = false;        //!< the solver gives every solution (a closed form)
    //! m the solver's proven gap may be off the real arm's: a closed form built for an
    //! arm its family holds for only to within the line geometry's tolerance proves
    //! "unreachable" only with a gap beyond tol.position + gap_slack
    double gap_slack = 0.0;
    //! the candidates are a nearby arm's (a closed form of the family the arm belongs to
    //! only within the line geometry's tolerance): each is carried to this arm's solution
    //! by Gauss-Newton steps to round-off (check.hpp's REPAIR_STEPS), even one that already
    //! meets the tolerances, which at a near-singular solution allow a joint error of
    //! tolerance / smallest singular value
    bool repair = false;
    double weights[6] = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};  //!< of x, y, z, rx, ry, rz (0: ignored)
};

//! What the check says of one target.
struct CheckReport {
    Status status = Status::invalid;
    int count = 0;                    //!< solutions within the limits
    int out_count = 0;                //!< solutions outside them
    double gap = NaN;                 //!< for unreachable: the solver's proven gap (m), else NaN
    double nearest_position = NaN;    //!< the closest candidate that was no solution (m) ...
    double nearest_rotation = NaN;    //!< ... and its rotation error (rad)
    //! the solver's near flag, a candidate the repair lost, or two branches merged
    //! (check.hpp's MERGE_SPAN)
    bool near = false;
    std::uint32_t free = 0;           //!< the solver's free joints (bit j: joint j)
};

}  // namespace km
