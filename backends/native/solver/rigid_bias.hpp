#pragma once
// A rigid contact row's velocity bias, shared by the 3D and planar solve kernels. Always inlined,
// as is everything the kernels call with a wide value: an out-of-line call passes a 32-byte vector
// one way from the AVX2 kernels and another from the baseline ones (the build has -Wno-psabi), so
// a lambda the compiler chose not to inline would read garbage.
#include "solver/wide.hpp"

namespace anyphys::native::wide {

/// The pass's constants for rigidBias (all lanes alike).
struct RigidBias {
    FloatW invH;       // 1 / substep
    FloatW maxPush;    // minus the fastest push out of overlap
    FloatW baumgarte;  // PGS: the fraction of overlap pushed out per substep, over the substep
    FloatW slop;       // overlap left alone (linearSlop)
    bool useBias;      // false in the relax pass: no push
};

/// The bias of a rigid row (the relax pass; PGS) from the point's separation s: a speculative point
/// closes its gap this substep; with bias, overlap beyond linearSlop is pushed out by a Baumgarte
/// fraction, no faster than the push cap.
[[gnu::always_inline]] inline FloatW rigidBias(const RigidBias& r, FloatW s) {
    const FloatW push = r.useBias ? max(r.baumgarte * min(zero(), s + r.slop), r.maxPush) : zero();
    return select(s > zero(), s * r.invH, push);
}

}  // namespace anyphys::native::wide
