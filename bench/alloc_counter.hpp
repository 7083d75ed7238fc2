#pragma once
// Heap allocations made by this process so far, counted by the benchmark programs' own
// replacements of malloc / calloc / realloc / the aligned allocators and of every global
// operator new (alloc_counter.cpp). Counting at malloc catches the engines' C allocations too
// (ODE, Bullet and Box2D allocate with malloc, not new). A sanitizer build keeps its own
// allocator: nothing is counted there and `countingAllocations()` is false.
#include <cstdint>

namespace anyphys::bench {

/// True when this build counts allocations.
bool countingAllocations();

/// Allocations (malloc-level, operator new included) since the process started, every thread.
std::uint64_t heapAllocations();

}  // namespace anyphys::bench
