#pragma once
// Asking for memory a loop will read a few iterations later, so that the loads overlap the
// work in between. The solver's passes walk their arrays in order, but each record leads to
// others (a contact's bodies, a lane's manifold): past about 10 000 bodies those no longer fit in
// a core's cache, and without a hint every pass waited on them one record at a time (measured:
// docs/benchmarks.md, "Asking for the solver's reads ahead").
#include <cstddef>

namespace anyphys::native {

inline constexpr std::size_t kCacheLine = 64;

/// How many records ahead a pass over constraint records asks (about 2 us of work at 50 000
/// bodies: time enough for a miss to arrive, near enough to stay in L1).
inline constexpr int kRecordsAhead = 2;

/// Hints the cache lines of [at, at + bytes); `forWrite` when the loop will write them.
template <bool forWrite = false>
inline void prefetchBytes(const void* at, std::size_t bytes) {
#if defined(__GNUC__)
    const char* p = static_cast<const char*>(at);
    for (std::size_t offset = 0; offset < bytes; offset += kCacheLine) __builtin_prefetch(p + offset, forWrite ? 1 : 0);
#else
    (void)at;
    (void)bytes;
#endif
}

}  // namespace anyphys::native
