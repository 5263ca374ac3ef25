// Storage for the arrays as large as the mesh (one entry per tetrahedron
// slot or per vertex): a std::vector whose allocator, from 2 MiB on,
// aligns the block to a huge page and advises it (mesh/huge_pages.hpp),
// so that every byte of it gets huge pages, also when the vector grows
// or is copied (recovery's checkpoints copy the whole mesh).
//
// Why: such an array is touched all over at once (a copy, a fill, the
// Delaunay insertion appending tetrahedra), one page fault per 4 KiB page,
// and on a virtual machine a fault costs several microseconds: `cbr
// recover` on nefertiti took 17,600 faults, about 0.1 s of its 0.6 s.
// Huge pages also spare the TLB misses of the flips' and walks' random
// accesses over a large mesh.
//
// Contents and results do not depend on the allocator, only where the
// bytes live. A smaller array comes from std::allocator (rounding it up to
// 2 MiB would waste memory).
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <vector>

#include "mesh/huge_pages.hpp"

namespace cbr::mesh {

namespace detail {
// `bytes` rounded up to whole huge pages, aligned to one, with the kernel
// asked for huge pages (advise_huge_pages). Throws std::bad_alloc. Freed
// by release_huge.
void* allocate_huge(std::size_t bytes);
void release_huge(void* p) noexcept;
}  // namespace detail

template <class T>
struct LargeArrayAllocator {
    using value_type = T;

    LargeArrayAllocator() = default;
    template <class U>
    LargeArrayAllocator(const LargeArrayAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (bytes >= kHugePageBytes) return static_cast<T*>(detail::allocate_huge(bytes));
        return std::allocator<T>().allocate(n);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) >= kHugePageBytes) detail::release_huge(p);
        else std::allocator<T>().deallocate(p, n);
    }

    template <class U>
    bool operator==(const LargeArrayAllocator<U>&) const noexcept { return true; }
    template <class U>
    bool operator!=(const LargeArrayAllocator<U>&) const noexcept { return false; }
};

// A vector whose storage may get huge pages (see above).
template <class T>
using LargeArray = std::vector<T, LargeArrayAllocator<T>>;

}  // namespace cbr::mesh
