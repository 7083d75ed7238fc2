#pragma once
// Loading and storing SolverState as runs of four doubles for the wide contact passes: a lane's
// run is one load, and a transpose turns four lanes' runs into four fields of four lanes (twice,
// once per half of a wide value). Per
// lane and per field, the gather cost the 5 050-box pyramid's passes more than their arithmetic.
#include <cstddef>
#include <cstring>

#include "solver/prefetch.hpp"
#include "solver/solver_body.hpp"
#include "solver/wide.hpp"

namespace anyphys::native::wide {

/// A static or sleeping partner's lane: at rest, not turned.
inline const SolverState kStateAtRest{};

[[gnu::always_inline]] inline const SolverState& stateOf(const SolverState* states, std::int32_t index) {
    return index == kStaticBody ? kStateAtRest : states[index];
}

/// Asks for the states of a later record's bodies (`bytes` of each: the velocities' run, or the
/// whole state), so that their loads overlap this record's work (prefetch.hpp).
[[gnu::always_inline]] inline void prefetchStates(const SolverState* states, const std::int32_t* bodyA,
                                                  const std::int32_t* bodyB, std::size_t bytes) {
    for (const std::int32_t* index : {bodyA, bodyB})
        for (int k = 0; k < kLanes; ++k)
            if (index[k] != kStaticBody) prefetchBytes<true>(states + index[k], bytes);
}

/// The four doubles of `state` from byte `offset`.
[[gnu::always_inline]] inline Run4 loadRun(const SolverState& state, std::size_t offset) {
    Run4 run;
    std::memcpy(&run, reinterpret_cast<const char*>(&state) + offset, sizeof run);
    return run;
}

static_assert(kLanes == 8, "gatherRuns and scatterRuns transpose two halves of four lanes");

/// The lanes' runs at `offset` (`index`: each lane's state), as four fields of every lane.
[[gnu::always_inline]] inline void gatherRuns(const SolverState* states, const std::int32_t* index, std::size_t offset,
                                              FloatW& first, FloatW& second, FloatW& third, FloatW& fourth) {
    Run4 runs[kLanes];
    for (int k = 0; k < kLanes; ++k) runs[k] = loadRun(stateOf(states, index[k]), offset);
    transpose(runs[0], runs[1], runs[2], runs[3]);
    transpose(runs[4], runs[5], runs[6], runs[7]);
    first = join(runs[0], runs[4]);
    second = join(runs[1], runs[5]);
    third = join(runs[2], runs[6]);
    fourth = join(runs[3], runs[7]);
}

/// The inverse of gatherRuns for the lanes `write` marks, storing the first `bytes` of each run.
[[gnu::always_inline]] inline void scatterRuns(SolverState* states, const std::int32_t* index, const bool* write,
                                               std::size_t offset, std::size_t bytes, FloatW first, FloatW second,
                                               FloatW third, FloatW fourth) {
    Run4 runs[kLanes] = {lowHalf(first), lowHalf(second), lowHalf(third), lowHalf(fourth),
                         highHalf(first), highHalf(second), highHalf(third), highHalf(fourth)};
    transpose(runs[0], runs[1], runs[2], runs[3]);
    transpose(runs[4], runs[5], runs[6], runs[7]);
    for (int lane = 0; lane < kLanes; ++lane)
        if (write[lane]) std::memcpy(reinterpret_cast<char*>(&states[index[lane]]) + offset, &runs[lane], bytes);
}

constexpr std::size_t kDouble = sizeof(double);

/// Lanes either of whose bodies takes part in a bounce this step (SolverState::inBounce).
[[gnu::always_inline]] inline MaskW inBounce(const SolverState* states, const std::int32_t* a, const std::int32_t* b) {
    MaskW lanes{};
    for (int k = 0; k < kLanes; ++k)
        lanes[k] = stateOf(states, a[k]).inBounce != 0.0 || stateOf(states, b[k]).inBounce != 0.0 ? -1 : 0;
    return lanes;
}

/// Marks the bodies of `lanes` that take impulses as taking part in a bounce.
[[gnu::always_inline]] inline void markInBounce(SolverState* states, const std::int32_t* a, const bool* writeA,
                                                const std::int32_t* b, const bool* writeB, MaskW lanes) {
    for (int k = 0; k < kLanes; ++k) {
        if (!lanes[k]) continue;
        if (writeA[k]) states[a[k]].inBounce = 1.0;
        if (writeB[k]) states[b[k]].inBounce = 1.0;
    }
}

}  // namespace anyphys::native::wide
