// Asking Linux for transparent huge pages (2 MiB) for a large block of
// memory before it is first touched: one fault per 2 MiB instead of one
// per 4 KiB page, and fewer TLB misses after. Where the kernel's THP mode
// is "madvise" (this project's VM) only memory advised so gets them; under
// "always" all large blocks do anyway and under "never" none, so the
// advice changes nothing there. Header-only: the command and its I/O
// library use it on their own buffers too (mesh/large_array.hpp uses it
// for the mesh's arrays).
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace cbr::mesh {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// Advises the whole huge pages inside [p, p + bytes) (none when the block
// holds no aligned 2 MiB). Only advice: contents, and whether the call
// succeeds, change nothing but speed.
inline void advise_huge_pages(void* p, std::size_t bytes) {
#if defined(MADV_HUGEPAGE)
    const auto start = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t first = (start + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    const std::uintptr_t last = (start + bytes) / kHugePageBytes * kHugePageBytes;
    if (last > first) (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

// v.reserve(n) with its storage advised before anything is written to it
// (a std::vector or std::string about to be filled up to n).
template <class Container>
void reserve_huge(Container& v, std::size_t n) {
    v.reserve(n);
    advise_huge_pages(v.data(), v.capacity() * sizeof(typename Container::value_type));
}

// reserve_huge(v, n), then v.resize(n): a vector filled by index.
template <class Container>
void resize_huge(Container& v, std::size_t n) {
    reserve_huge(v, n);
    v.resize(n);
}

}  // namespace cbr::mesh
