#include "mesh/large_array.hpp"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace cbr::mesh::detail {

void* allocate_huge(std::size_t bytes) {
    const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    if (rounded < bytes) throw std::bad_alloc();
    void* p = std::aligned_alloc(kHugePageBytes, rounded);
    if (p == nullptr) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
    // Advice only: where it is refused (THP "never", an old kernel) the
    // pages are ordinary ones.
    (void)::madvise(p, rounded, MADV_HUGEPAGE);
#endif
    return p;
}

void release_huge(void* p) noexcept { std::free(p); }

}  // namespace cbr::mesh::detail
