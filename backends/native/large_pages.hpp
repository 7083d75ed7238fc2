#pragma once
// Large arrays on large pages. Past about 10 000 bodies the solver's and the contacts' arrays
// span tens of megabytes, and every pass over them walks more 4 KiB pages than the TLB holds:
// each new page costs a page-table walk on top of the cache miss. Linux backs a region with
// 2 MiB pages when asked (madvise MADV_HUGEPAGE) before the region is first touched, which is
// the moment an allocator hands it out. Measured: docs/benchmarks.md, "Large pages".
#include <cstddef>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace anyphys::native {

/// Bytes from which an array asks for large pages: one large page. Below it the array shares
/// small pages with its neighbours and gains nothing.
inline constexpr std::size_t kLargePageBytes = std::size_t{2} << 20;

/// A std::allocator that aligns allocations of at least kLargePageBytes to a large page and asks
/// the kernel to back them with large pages. Only a hint: where the kernel declines, or on another
/// system, the memory is ordinary memory.
template <class T>
struct LargePageAllocator {
    using value_type = T;

    LargePageAllocator() noexcept = default;
    template <class U>
    LargePageAllocator(const LargePageAllocator<U>&) noexcept {}  // NOLINT: rebinding, as std::allocator

    T* allocate(std::size_t n) {
        if (n > max_size()) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        void* memory = ::operator new(bytes, std::align_val_t{alignmentFor(bytes)});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        if (bytes >= kLargePageBytes) ::madvise(memory, bytes, MADV_HUGEPAGE);  // a refusal leaves small pages
#endif
        return static_cast<T*>(memory);
    }

    void deallocate(T* memory, std::size_t n) noexcept {
        ::operator delete(memory, std::align_val_t{alignmentFor(n * sizeof(T))});
    }

    static constexpr std::size_t max_size() noexcept { return ~std::size_t{0} / sizeof(T); }

    friend bool operator==(const LargePageAllocator&, const LargePageAllocator&) noexcept { return true; }
    friend bool operator!=(const LargePageAllocator&, const LargePageAllocator&) noexcept { return false; }

private:
    static constexpr std::size_t alignmentFor(std::size_t bytes) noexcept {
        return bytes >= kLargePageBytes ? kLargePageBytes : (alignof(T) > alignof(std::max_align_t) ? alignof(T)
                                                                                                   : alignof(std::max_align_t));
    }
};

/// A vector whose buffer sits on large pages once it reaches kLargePageBytes.
template <class T>
using LargeVector = std::vector<T, LargePageAllocator<T>>;

}  // namespace anyphys::native
