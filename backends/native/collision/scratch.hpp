#pragma once
// Per-thread, grow-only buffers for the collision routines whose working set has no fixed bound
// (a hull's faces, edges and clipped polygons; the triangles a shape meets in a mesh). Each file
// keeps its own thread_local set, so threads never share one and a routine never hands a buffer
// it is using to another. Once a thread has met its largest shapes nothing more is allocated.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace anyphys::native {

/// The first n elements of v, which grows when shorter (and never shrinks).
template <class T>
std::span<T> firstOf(std::vector<T>& v, std::size_t n) {
    if (v.size() < n) v.resize(n);
    return std::span<T>(v.data(), n);
}

/// Room for n elements: the caller's small array when it is large enough, else the scratch vector.
template <class T, std::size_t N>
std::span<T> room(std::array<T, N>& small, std::vector<T>& large, std::size_t n) {
    return n <= N ? std::span<T>(small.data(), n) : firstOf(large, n);
}

}  // namespace anyphys::native
