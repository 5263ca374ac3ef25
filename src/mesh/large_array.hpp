// Storage for the arrays as large as the mesh (one entry per tetrahedron
// slot or per vertex): std::vector with an allocator that asks Linux for
// transparent huge pages (2 MiB) once an array reaches that size.
//
// Why: a fresh 4 KiB page costs a page fault on first touch, and an array
// of the mesh's size is touched all over at once (a copy, a fill, the
// Delaunay insertion appending tetrahedra). On a virtual machine a fault
// costs several microseconds: `cbr recover` on nefertiti took 17,600
// faults, 0.1 s of its 0.6 s. Where the kernel's THP mode is "madvise"
// (Debian's default on many machines, this project's 2-core VM), memory
// gets huge pages only where the program asks; in mode "always" it gets
// them anyway and in "never" not at all, so the request changes nothing
// there. Huge pages also spare the TLB misses of the random accesses of
// flips and walks over a large mesh.
//
// Contents and results do not depend on the allocator: only where the
// bytes live. An array below kHugePageBytes comes from operator new as
// before (rounding it up to 2 MiB would waste memory).
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <vector>

namespace cbr::mesh {

namespace detail {
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
// `bytes` rounded up to whole huge pages, aligned to one, with the kernel
// asked for huge pages (Linux; elsewhere aligned memory alone). Throws
// std::bad_alloc. Freed by release_huge.
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
        if (bytes >= detail::kHugePageBytes) return static_cast<T*>(detail::allocate_huge(bytes));
        return std::allocator<T>().allocate(n);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) >= detail::kHugePageBytes) detail::release_huge(p);
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
