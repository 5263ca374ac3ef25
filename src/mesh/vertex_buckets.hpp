// Items filed under a vertex id below n by a counting sort: the surface
// check's edges and duplicate triangles, the constraint faces' lookup
// tables. One pass counts, one files; no comparison sort of all items.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cbr::mesh {

// Where each vertex's bucket starts: entries [start[x], start[x + 1]) are
// x's. `each(file)` calls file(x) once per item.
template <class Offset, class Each>
std::vector<Offset> bucket_starts(std::size_t n, Each each) {
    std::vector<Offset> start(n + 1, 0);
    each([&](auto x) { ++start[static_cast<std::size_t>(x) + 1]; });
    for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    return start;
}

// The items of each vertex u: items[first[u], first[u + 1]), sorted.
template <class Item>
struct FiledByVertex {
    std::vector<std::size_t> first;
    std::vector<Item> items;
};

// Every item in increasing (vertex, item) order, for a fraction of one
// sort of them all (each vertex has a few). `each(file)` calls file(u,
// item) for every item, the same items in the same order on both of its
// calls.
template <class Item, class Each>
FiledByVertex<Item> file_by_vertex(std::size_t n, Each each) {
    FiledByVertex<Item> out;
    out.first = bucket_starts<std::size_t>(n, [&](auto count) { each([&](auto u, const Item&) { count(u); }); });
    out.items.resize(out.first[n]);
    std::vector<std::size_t> fill(out.first.begin(), out.first.end() - 1);
    each([&](auto u, const Item& item) { out.items[fill[static_cast<std::size_t>(u)]++] = item; });
    for (std::size_t u = 0; u < n; ++u)
        std::sort(out.items.begin() + static_cast<std::ptrdiff_t>(out.first[u]),
                  out.items.begin() + static_cast<std::ptrdiff_t>(out.first[u + 1]));
    return out;
}

}  // namespace cbr::mesh
