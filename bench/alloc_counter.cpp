// Replaces the C allocator's entry points (forwarding to glibc's __libc_* functions, which is how
// glibc documents replacing malloc) and the global operator new / delete, counting every
// allocation. Part of each benchmark executable: the executable's malloc then also serves the
// shared engine libraries.
#include "alloc_counter.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <new>

#if ANYPHYS_BENCH_COUNT_ALLOCATIONS

namespace {

// Constant-initialised: the loader and libc allocate before any constructor runs.
constinit std::atomic<std::uint64_t> gAllocations{0};

void count() { gAllocations.fetch_add(1, std::memory_order_relaxed); }

bool validAlignment(std::size_t alignment) {
    return alignment >= sizeof(void*) && (alignment & (alignment - 1)) == 0;
}

}  // namespace

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void __libc_free(void* pointer);

void* malloc(std::size_t size) noexcept {
    count();
    return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
    count();
    return __libc_calloc(n, size);
}
void* realloc(void* pointer, std::size_t size) noexcept {
    count();  // a growth (or a move) is an allocation in a steady step too
    return __libc_realloc(pointer, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
    count();
    return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
    count();
    return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
    if (!validAlignment(alignment)) return EINVAL;
    count();
    void* p = __libc_memalign(alignment, size);
    if (p == nullptr) return ENOMEM;
    *out = p;
    return 0;
}
void free(void* pointer) noexcept { __libc_free(pointer); }
}  // extern "C"

// operator new through the counted malloc (so each allocation counts once).
namespace {

void* allocate(std::size_t size) {
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}

void* allocateAligned(std::size_t size, std::align_val_t alignment) {
    const auto a = std::max(static_cast<std::size_t>(alignment), sizeof(void*));
    void* p = nullptr;
    if (posix_memalign(&p, a, size == 0 ? 1 : size) == 0) return p;
    throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return std::malloc(size == 0 ? 1 : size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return std::malloc(size == 0 ? 1 : size); }
void* operator new(std::size_t size, std::align_val_t alignment) { return allocateAligned(size, alignment); }
void* operator new[](std::size_t size, std::align_val_t alignment) { return allocateAligned(size, alignment); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace anyphys::bench {
bool countingAllocations() { return true; }
std::uint64_t heapAllocations() { return gAllocations.load(std::memory_order_relaxed); }
}  // namespace anyphys::bench

#else  // a sanitizer build: its allocator stays in charge

namespace anyphys::bench {
bool countingAllocations() { return false; }
std::uint64_t heapAllocations() { return 0; }
}  // namespace anyphys::bench

#endif
