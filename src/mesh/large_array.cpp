#include "mesh/large_array.hpp"

#include <cstdlib>

namespace cbr::mesh::detail {

void* allocate_huge(std::size_t bytes) {
    const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    if (rounded < bytes) throw std::bad_alloc();
    void* p = std::aligned_alloc(kHugePageBytes, rounded);
    if (p == nullptr) throw std::bad_alloc();
    advise_huge_pages(p, rounded);
    return p;
}

void release_huge(void* p) noexcept { std::free(p); }

}  // namespace cbr::mesh::detail
