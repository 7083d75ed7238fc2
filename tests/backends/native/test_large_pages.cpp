// LargePageAllocator (large_pages.hpp): a large array starts on a large-page boundary and is marked
// for large pages; a small one keeps its type's alignment; the contents survive growth.
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "large_pages.hpp"

namespace anyphys::native {
namespace {

std::uintptr_t addressOf(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

/// The VmFlags of the mapping that holds `address` in /proc/self/smaps; empty if none was found.
std::string mappingFlags(const void* address) {
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        std::uintptr_t begin = 0, end = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> begin >> dash >> end && dash == '-') {
            inside = begin <= addressOf(address) && addressOf(address) < end;
        } else if (inside && line.rfind("VmFlags:", 0) == 0) {
            return line;
        }
    }
    return {};
}

TEST(LargePages, LargeArrayStartsOnALargePageAndKeepsItsContents) {
    LargeVector<std::uint64_t> values;
    // Grown one element at a time through every reallocation, past two large pages.
    const std::size_t count = 2 * kLargePageBytes / sizeof(std::uint64_t) + 1;
    for (std::size_t i = 0; i < count; ++i) values.push_back(i * 2654435761u);
    EXPECT_EQ(addressOf(values.data()) % kLargePageBytes, 0u);
    for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(values[i], i * 2654435761u) << "element " << i;
}

TEST(LargePages, SmallArrayKeepsItsTypesAlignment) {
    struct alignas(64) Line {
        double x[8];
    };
    LargeVector<Line> lines(3);
    EXPECT_EQ(addressOf(lines.data()) % alignof(Line), 0u);
    LargeVector<char> bytes(100);
    EXPECT_EQ(addressOf(bytes.data()) % alignof(std::max_align_t), 0u);
}

#if defined(__linux__) && defined(MADV_HUGEPAGE)
TEST(LargePages, LargeArrayIsMarkedForLargePages) {
    // Only a kernel built with transparent huge pages can mark memory; the others refuse the hint.
    if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"))
        GTEST_SKIP() << "this kernel has no transparent huge pages: the allocator's hint is refused";
    LargeVector<double> values(kLargePageBytes / sizeof(double));
    const std::string flags = mappingFlags(values.data());
    ASSERT_FALSE(flags.empty()) << "no mapping in /proc/self/smaps holds the array";
    EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;  // hg: madvise(MADV_HUGEPAGE) took
}
#endif

}  // namespace
}  // namespace anyphys::native
