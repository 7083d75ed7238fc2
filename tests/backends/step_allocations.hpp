#pragma once
// Counts the heap allocations that the layer and a backend's glue make while a world steps.
// Both are linked into the test program, so an allocation counts when the code asking for it is
// in the program itself; allocations inside an engine's shared library are the engine's own (ODE's
// hash space allocates on every collide pass, as it does for any ODE user) and are not counted.
//
// Replaces the global operator new and delete: include in exactly one source file of a program.
#include <link.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace anyphys::test {

class StepAllocations {
public:
    /// Starts counting.
    static void start() {
        findProgram();
        count().store(0);
        on().store(true);
    }
    /// Stops, and returns the allocations asked for by code of this program since start().
    static std::size_t stop() {
        on().store(false);
        return count().load();
    }
    static void note(const void* caller) {
        if (!on().load(std::memory_order_relaxed)) return;
        const auto at = reinterpret_cast<std::uintptr_t>(caller);
        if (at >= low() && at < high()) count().fetch_add(1);
    }

private:
    // The address range of the program's own loaded segments (the first object listed).
    static void findProgram() {
        dl_iterate_phdr(
            [](dl_phdr_info* info, std::size_t, void*) {
                std::uintptr_t lo = UINTPTR_MAX, hi = 0;
                for (int i = 0; i < info->dlpi_phnum; ++i) {
                    const auto& segment = info->dlpi_phdr[i];
                    if (segment.p_type != PT_LOAD) continue;
                    const std::uintptr_t start = info->dlpi_addr + segment.p_vaddr;
                    lo = start < lo ? start : lo;
                    hi = start + segment.p_memsz > hi ? start + segment.p_memsz : hi;
                }
                low() = lo;
                high() = hi;
                return 1;  // the program itself comes first
            },
            nullptr);
    }
    static std::atomic<bool>& on() {
        static std::atomic<bool> value{false};
        return value;
    }
    static std::atomic<std::size_t>& count() {
        static std::atomic<std::size_t> value{0};
        return value;
    }
    static std::uintptr_t& low() {
        static std::uintptr_t value = 0;
        return value;
    }
    static std::uintptr_t& high() {
        static std::uintptr_t value = 0;
        return value;
    }
};

}  // namespace anyphys::test

// noinline: the return address must be the allocating code's, not a caller's further up. The
// replacements pair malloc with free, which GCC's new / delete matching cannot see.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
[[gnu::noinline]] void* operator new(std::size_t size) {
    anyphys::test::StepAllocations::note(__builtin_return_address(0));
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
[[gnu::noinline]] void* operator new[](std::size_t size) {
    anyphys::test::StepAllocations::note(__builtin_return_address(0));
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
// The nothrow forms too (std::stable_sort's buffer): left to the sanitizer's, their blocks came
// back through the delete above, which ASan reported as a mismatch.
[[gnu::noinline]] void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    anyphys::test::StepAllocations::note(__builtin_return_address(0));
    return std::malloc(size == 0 ? 1 : size);
}
[[gnu::noinline]] void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
    anyphys::test::StepAllocations::note(__builtin_return_address(0));
    return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop
