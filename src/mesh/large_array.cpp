#include "mesh/large_array.hpp"

#include <new>

namespace cbr::mesh::detail {

void* allocate_huge(std::size_t bytes) {
    const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    if (rounded < bytes) throw std::bad_alloc();
    void* p = ::operator new(rounded, std::align_val_t{kHugePageBytes});  // throws std::bad_alloc
    advise_huge_pages(p, rounded);
    return p;
}

void release_huge(void* p) noexcept { ::operator delete(p, std::align_val_t{kHugePageBytes}); }

}  // namespace cbr::mesh::detail
