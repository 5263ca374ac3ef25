// Input surface validation (see surface_check.hpp).
#include "recover/surface_check.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

#include "delaunay/spatial_sort.hpp"
#include "mesh/vertex_buckets.hpp"
#include "geom/intersect.hpp"
#include "geom/predicates.hpp"

namespace cbr::recover {
namespace {

using Ids = std::array<std::int64_t, 3>;

// ---------------------------------------------------------------------------
// The input, read-only.
// ---------------------------------------------------------------------------
struct Surface {
    const double* xyz;
    std::int64_t point_count;
    const std::int64_t* tris;
    std::size_t triangle_count;

    Ids ids(std::size_t t) const { return {tris[3 * t], tris[3 * t + 1], tris[3 * t + 2]}; }
    const double* point(std::int64_t id) const { return xyz + 3 * static_cast<std::size_t>(id); }
};

enum class TriState : std::uint8_t {
    Usable,      // ids valid and distinct, non-zero area: geometry is tested
    Degenerate,  // ids valid and distinct, zero area: combinatorics only
    Invalid,     // an id out of range or repeated: skipped afterwards
};

// Counts every defect of each kind and keeps the first few. Each pass adds
// its defects in the deterministic order, so "first" is well defined.
class Collector {
public:
    explicit Collector(std::size_t cap) : cap_(cap) {}

    void add(const Defect& d) {
        const auto k = static_cast<std::size_t>(d.kind);
        ++counts_[k];
        if (lists_[k].size() < cap_) lists_[k].push_back(d);
    }
    // Counts defects of `kind` that are not listed.
    void add_unlisted(DefectKind kind, std::int64_t n) {
        counts_[static_cast<std::size_t>(kind)] += n;
    }
    std::size_t cap() const { return cap_; }

    SurfaceCheckResult finish() {
        SurfaceCheckResult r;
        for (std::size_t k = 0; k < kDefectKindCount; ++k)
            r.defects.insert(r.defects.end(), lists_[k].begin(), lists_[k].end());
        r.counts = counts_;
        return r;
    }

private:
    std::size_t cap_;
    std::array<std::vector<Defect>, kDefectKindCount> lists_;
    std::array<std::int64_t, kDefectKindCount> counts_{};
};

Defect triangle_defect(DefectKind kind, std::size_t t, const Ids& ids) {
    Defect d;
    d.kind = kind;
    d.tri[0] = static_cast<std::int64_t>(t);
    d.vert = ids;
    return d;
}

// ---------------------------------------------------------------------------
// Pass 1: each triangle alone.
// ---------------------------------------------------------------------------
TriState check_triangle(const Surface& s, std::size_t t, Collector& out) {
    const Ids v = s.ids(t);
    for (const std::int64_t id : v)
        if (id < 0 || id >= s.point_count) {
            Defect d = triangle_defect(DefectKind::IdOutOfRange, t, v);
            d.value = s.point_count;
            out.add(d);
            return TriState::Invalid;
        }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
        out.add(triangle_defect(DefectKind::RepeatedId, t, v));
        return TriState::Invalid;
    }
    if (geom::collinear(s.point(v[0]), s.point(v[1]), s.point(v[2]))) {
        out.add(triangle_defect(DefectKind::ZeroArea, t, v));
        return TriState::Degenerate;
    }
    return TriState::Usable;
}

// ---------------------------------------------------------------------------
// Pass 2: the same vertex set twice. Each later copy is reported against
// the first one.
// ---------------------------------------------------------------------------
void find_duplicates(const Surface& s, const std::vector<TriState>& state, Collector& out) {
    // Each triangle with valid ids by its sorted ids, filed under the
    // smallest: copies are neighbours in their vertex's list, the first
    // triangle first.
    struct Copy {
        std::int64_t middle, largest;
        std::size_t tri;
        bool same_ids(const Copy& o) const { return middle == o.middle && largest == o.largest; }
        bool operator<(const Copy& o) const {
            return middle != o.middle ? middle < o.middle : largest != o.largest ? largest < o.largest : tri < o.tri;
        }
    };
    const mesh::FiledByVertex<Copy> filed =
        mesh::file_by_vertex<Copy>(static_cast<std::size_t>(s.point_count), [&](auto file) {
            for (std::size_t t = 0; t < s.triangle_count; ++t) {
                if (state[t] == TriState::Invalid) continue;
                Ids v = s.ids(t);
                std::sort(v.begin(), v.end());
                file(v[0], Copy{v[1], v[2], t});
            }
        });
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t u = 0; u < static_cast<std::size_t>(s.point_count); ++u)
        for (std::size_t i = filed.first[u]; i < filed.first[u + 1];) {
            std::size_t j = i + 1;
            for (; j < filed.first[u + 1] && filed.items[j].same_ids(filed.items[i]); ++j)
                pairs.emplace_back(filed.items[i].tri, filed.items[j].tri);
            i = j;
        }
    std::sort(pairs.begin(), pairs.end());
    for (const auto& [first, copy] : pairs) {
        Defect d = triangle_defect(DefectKind::DuplicateTriangle, first, s.ids(copy));
        d.tri[1] = static_cast<std::int64_t>(copy);
        out.add(d);
    }
}

// ---------------------------------------------------------------------------
// Pass 4 (information): how many triangles use each edge.
// ---------------------------------------------------------------------------
void report_edges(const Surface& s, const std::vector<TriState>& state, Collector& out) {
    // Each edge (u, v), u < v, of every triangle with valid ids, filed under
    // u, each u's edges by (v, triangle): the edges come in increasing (u,
    // v), each with its smallest triangle first.
    struct EdgeUse {
        std::int64_t v;
        std::size_t tri;
        bool operator<(const EdgeUse& o) const { return v != o.v ? v < o.v : tri < o.tri; }
    };
    const mesh::FiledByVertex<EdgeUse> filed =
        mesh::file_by_vertex<EdgeUse>(static_cast<std::size_t>(s.point_count), [&](auto file) {
            for (std::size_t t = 0; t < s.triangle_count; ++t) {
                if (state[t] == TriState::Invalid) continue;
                const Ids v = s.ids(t);
                for (int i = 0; i < 3; ++i)
                    file(std::min(v[i], v[(i + 1) % 3]), EdgeUse{std::max(v[i], v[(i + 1) % 3]), t});
            }
        });
    const auto n = static_cast<std::size_t>(s.point_count);
    for (std::size_t u = 0; u < n; ++u) {
        const auto begin = filed.items.begin() + static_cast<std::ptrdiff_t>(filed.first[u]);
        const auto end = filed.items.begin() + static_cast<std::ptrdiff_t>(filed.first[u + 1]);
        for (auto i = begin; i != end;) {
            auto j = i + 1;
            while (j != end && j->v == i->v) ++j;
            const auto count = static_cast<std::int64_t>(j - i);
            Defect d;
            d.tri[0] = static_cast<std::int64_t>(i->tri);
            d.vert = {static_cast<std::int64_t>(u), i->v, -1};
            d.value = count;
            if (count == 1) {
                d.kind = DefectKind::OpenEdge;
                out.add(d);
            }
            if (count > 2) {
                d.kind = DefectKind::NonManifoldEdge;
                out.add(d);
            }
            i = j;
        }
    }
}

// ---------------------------------------------------------------------------
// Bounding-box tree. Boxes are min/max of input coordinates, so they are
// exact and closed: triangles that touch have touching boxes, and the
// candidate pairs are a superset of the meeting pairs. The items are put in
// the order of their box centres along the Hilbert curve of the Delaunay
// insertion order (delaunay::hilbert_order, one radix sort), and each node
// splits its range in halves: nearby boxes share subtrees, as with median
// splits on the longest axis, for a fraction of the building (igea's 270k
// triangles: a median split per node moved every 56-byte item once per
// level, a fifth of the check).
// ---------------------------------------------------------------------------
struct Box {
    std::array<double, 3> lo;
    std::array<double, 3> hi;

    void expand(const Box& b) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b.lo[k]);
            hi[k] = std::max(hi[k], b.hi[k]);
        }
    }
    bool overlaps(const Box& b) const {
        for (int k = 0; k < 3; ++k)
            if (hi[k] < b.lo[k] || b.hi[k] < lo[k]) return false;
        return true;
    }
};

Box triangle_box(const Surface& s, std::size_t t) {
    const Ids v = s.ids(t);
    Box b;
    for (int k = 0; k < 3; ++k) b.lo[k] = b.hi[k] = s.point(v[0])[k];
    for (int i = 1; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
            b.lo[k] = std::min(b.lo[k], s.point(v[i])[k]);
            b.hi[k] = std::max(b.hi[k], s.point(v[i])[k]);
        }
    return b;
}

class BoxTree {
public:
    // Indexes box_of(i) for each i in `ids` (computed twice rather than
    // kept in a third array as large as the tree's).
    template <class BoxOf>
    BoxTree(const std::vector<std::size_t>& ids, BoxOf box_of) {
        if (ids.empty()) return;
        std::vector<double> centres;
        centres.reserve(3 * ids.size());
        for (const std::size_t i : ids) {
            const Box b = box_of(i);
            for (int k = 0; k < 3; ++k) centres.push_back(0.5 * b.lo[k] + 0.5 * b.hi[k]);
        }
        items_.reserve(ids.size());
        for (const std::size_t n : delaunay::hilbert_order(centres.data(), ids.size()))
            items_.push_back({box_of(ids[n]), ids[n]});
        nodes_.reserve(items_.size());  // leaves hold at least 2 items: fewer than n nodes
        build(0, items_.size());
    }

    // Calls visit(i, j) once for every pair of indexed boxes that overlap.
    template <class Visit>
    void for_each_overlapping_pair(Visit&& visit) const {
        if (!nodes_.empty()) pairs_within(0, visit);
    }

    // Calls visit(i) for every indexed box that overlaps `box`.
    template <class Visit>
    void for_each_overlapping(const Box& box, Visit&& visit) const {
        if (!nodes_.empty()) overlapping(0, box, visit);
    }

private:
    static constexpr std::size_t kLeafSize = 4;

    struct Item {
        Box box;
        std::size_t id;
    };
    struct Node {
        Box box;
        std::size_t begin, end;  // its items
        std::size_t right;       // right child, 0 for a leaf; the left child follows
                                 // its parent in nodes_
    };

    // Dual traversal: pairs inside a subtree are the pairs inside each child
    // plus the pairs across them; a pair of subtrees is explored only while
    // their boxes overlap. Recursion depth is at most twice the tree depth.
    template <class Visit>
    void pairs_within(std::size_t n, Visit& visit) const {
        const Node& node = nodes_[n];
        if (node.right == 0) {
            for (std::size_t i = node.begin; i < node.end; ++i)
                for (std::size_t j = i + 1; j < node.end; ++j) visit_if_overlap(i, j, visit);
            return;
        }
        pairs_within(n + 1, visit);
        pairs_within(node.right, visit);
        pairs_across(n + 1, node.right, visit);
    }

    template <class Visit>
    void pairs_across(std::size_t a, std::size_t b, Visit& visit) const {
        const Node& na = nodes_[a];
        const Node& nb = nodes_[b];
        if (!na.box.overlaps(nb.box)) return;
        if (na.right == 0 && nb.right == 0) {
            for (std::size_t i = na.begin; i < na.end; ++i)
                for (std::size_t j = nb.begin; j < nb.end; ++j) visit_if_overlap(i, j, visit);
        } else if (nb.right == 0 || (na.right != 0 && na.end - na.begin >= nb.end - nb.begin)) {
            pairs_across(a + 1, b, visit);  // open the larger inner node
            pairs_across(na.right, b, visit);
        } else {
            pairs_across(a, b + 1, visit);
            pairs_across(a, nb.right, visit);
        }
    }

    template <class Visit>
    void overlapping(std::size_t n, const Box& box, Visit& visit) const {
        const Node& node = nodes_[n];
        if (!node.box.overlaps(box)) return;
        if (node.right == 0) {
            for (std::size_t i = node.begin; i < node.end; ++i)
                if (items_[i].box.overlaps(box)) visit(items_[i].id);
            return;
        }
        overlapping(n + 1, box, visit);
        overlapping(node.right, box, visit);
    }

    template <class Visit>
    void visit_if_overlap(std::size_t i, std::size_t j, Visit& visit) const {
        if (items_[i].box.overlaps(items_[j].box)) visit(items_[i].id, items_[j].id);
    }

    // Node of items [begin, end): a leaf, or its two halves; its box is
    // that of its items (a leaf's) or of its children.
    std::size_t build(std::size_t begin, std::size_t end) {
        const std::size_t self = nodes_.size();
        nodes_.push_back({items_[begin].box, begin, end, 0});
        if (end - begin <= kLeafSize) {
            for (std::size_t i = begin + 1; i < end; ++i) nodes_[self].box.expand(items_[i].box);
            return self;
        }
        const std::size_t mid = begin + (end - begin) / 2;
        build(begin, mid);
        const std::size_t right = build(mid, end);
        nodes_[self].right = right;
        nodes_[self].box = nodes_[self + 1].box;
        nodes_[self].box.expand(nodes_[right].box);
        return self;
    }

    std::vector<Item> items_;
    std::vector<Node> nodes_;
};

// ---------------------------------------------------------------------------
// Pass 3: pairs of usable triangles meeting illegally.
// ---------------------------------------------------------------------------

// Moves the vertices a and b share to the front of both, in the same order;
// returns how many they share. Ids within a triangle are distinct.
int align_shared(Ids& a, Ids& b) {
    int k = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = k; j < 3; ++j)
            if (a[i] == b[j]) {
                std::swap(a[k], a[i]);
                std::swap(b[k], b[j]);
                ++k;
                break;
            }
    return k;
}

// Checks the pair (t, u), t < u; returns the defect when they meet illegally.
bool pair_meets_illegally(const Surface& s, std::size_t t, std::size_t u, Defect& d) {
    Ids a = s.ids(t);
    Ids b = s.ids(u);
    const int shared = align_shared(a, b);
    if (shared == 3) return false;  // a duplicate, reported as such
    const double* pa[3] = {s.point(a[0]), s.point(a[1]), s.point(a[2])};
    const double* pb[3] = {s.point(b[0]), s.point(b[1]), s.point(b[2])};
    if (!geom::triangles_meet_illegally(pa, pb, shared)) return false;
    d = Defect{};
    d.kind = DefectKind::Intersection;
    d.tri = {static_cast<std::int64_t>(t), static_cast<std::int64_t>(u)};
    for (int i = 0; i < shared; ++i) d.vert[i] = a[i];
    return true;
}

// The pairs come in tree order; the listed ones must be the smallest
// (t, u). A max-heap keeps the `cap` smallest seen so far.
class SmallestPairs {
public:
    explicit SmallestPairs(std::size_t cap) : cap_(cap) {}

    void add(const Defect& d) {
        ++count_;
        if (cap_ == 0) return;
        if (heap_.size() == cap_) {
            if (!by_pair(d, heap_.front())) return;
            std::pop_heap(heap_.begin(), heap_.end(), by_pair);
            heap_.pop_back();
        }
        heap_.push_back(d);
        std::push_heap(heap_.begin(), heap_.end(), by_pair);
    }

    void flush_to(Collector& out) {
        std::sort_heap(heap_.begin(), heap_.end(), by_pair);
        for (const Defect& d : heap_) out.add(d);
        out.add_unlisted(DefectKind::Intersection,
                         count_ - static_cast<std::int64_t>(heap_.size()));
    }

private:
    static bool by_pair(const Defect& a, const Defect& b) { return a.tri < b.tri; }

    std::size_t cap_;
    std::vector<Defect> heap_;
    std::int64_t count_ = 0;
};

// The pairs of usable triangles whose boxes overlap, less those of two
// known faces (SurfaceCheckOptions::known_faces): the others go into the
// tree, and each known face is looked up in it.
void find_intersections(const Surface& s, const std::vector<TriState>& state, const std::vector<char>* known_faces,
                        Collector& out) {
    std::vector<std::size_t> others, known;
    others.reserve(s.triangle_count);
    for (std::size_t t = 0; t < s.triangle_count; ++t) {
        if (state[t] != TriState::Usable) continue;
        (known_faces && (*known_faces)[t] ? known : others).push_back(t);
    }
    const BoxTree tree(others, [&s](std::size_t t) { return triangle_box(s, t); });
    SmallestPairs found(out.cap());
    const auto test = [&](std::size_t t, std::size_t u) {
        Defect d;
        if (pair_meets_illegally(s, std::min(t, u), std::max(t, u), d)) found.add(d);
    };
    tree.for_each_overlapping_pair(test);
    for (const std::size_t t : known)
        tree.for_each_overlapping(triangle_box(s, t), [&](std::size_t u) { test(t, u); });
    found.flush_to(out);
}

// ---------------------------------------------------------------------------
// Messages.
// ---------------------------------------------------------------------------
std::string id_list(const Ids& v, int base) {
    std::string r;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (i > 0) r += ", ";
        r += std::to_string(v[i] + base);
    }
    return r;
}

std::string out_of_range_message(const Defect& d, int base) {
    std::string bad;
    int n = 0;
    for (const std::int64_t id : d.vert)
        if (id < 0 || id >= d.value) bad += (n++ > 0 ? ", " : "") + std::to_string(id + base);
    const std::string range = d.value > 0 ? "valid ids are " + std::to_string(base) + " to " +
                                                std::to_string(d.value - 1 + base)
                                          : "there are no points";
    return "triangle " + std::to_string(d.tri[0] + base) +
           (n > 1 ? " uses vertex ids " : " uses vertex id ") + bad + ", out of range (" + range +
           ")";
}

std::string edge_message(const Defect& d, int base, const char* what) {
    const std::int64_t n = d.value;
    const std::string tri = std::to_string(d.tri[0] + base);
    return "edge " + std::to_string(d.vert[0] + base) + "-" + std::to_string(d.vert[1] + base) +
           " is " + what + ": used by " +
           (n == 1 ? "1 triangle (triangle " + tri + ")"
                   : std::to_string(n) + " triangles (first: triangle " + tri + ")");
}

const char* kind_noun(DefectKind kind, bool plural) {
    switch (kind) {
        case DefectKind::IdOutOfRange:
            return plural ? "triangles with ids out of range" : "triangle with an id out of range";
        case DefectKind::RepeatedId:
            return plural ? "triangles with a repeated id" : "triangle with a repeated id";
        case DefectKind::ZeroArea: return plural ? "zero-area triangles" : "zero-area triangle";
        case DefectKind::DuplicateTriangle:
            return plural ? "duplicate triangles" : "duplicate triangle";
        case DefectKind::Intersection:
            return plural ? "intersecting triangle pairs" : "intersecting triangle pair";
        case DefectKind::OpenEdge: return plural ? "open edges" : "open edge";
        case DefectKind::NonManifoldEdge:
            return plural ? "non-manifold edges" : "non-manifold edge";
    }
    return "defects";
}

}  // namespace

bool is_error(DefectKind kind) {
    return kind != DefectKind::OpenEdge && kind != DefectKind::NonManifoldEdge;
}

std::int64_t SurfaceCheckResult::error_count() const {
    std::int64_t n = 0;
    for (std::size_t k = 0; k < kDefectKindCount; ++k)
        if (is_error(static_cast<DefectKind>(k))) n += counts[k];
    return n;
}

SurfaceCheckResult check_surface(const double* xyz, std::int64_t point_count,
                                 const std::int64_t* tris, std::int64_t triangle_count,
                                 const SurfaceCheckOptions& options) {
    const Surface s{xyz, std::max<std::int64_t>(point_count, 0), tris,
                    static_cast<std::size_t>(std::max<std::int64_t>(triangle_count, 0))};
    Collector out(options.max_listed_per_kind);
    std::vector<TriState> state(s.triangle_count);
    for (std::size_t t = 0; t < s.triangle_count; ++t) state[t] = check_triangle(s, t, out);
    find_duplicates(s, state, out);
    const bool known_usable = options.known_faces && options.known_faces->size() == s.triangle_count;
    find_intersections(s, state, known_usable ? options.known_faces : nullptr, out);
    if (options.report_edges) report_edges(s, state, out);
    return out.finish();
}

std::string describe(const Defect& d, int base) {
    const std::string t0 = std::to_string(d.tri[0] + base);
    const std::string t1 = std::to_string(d.tri[1] + base);
    switch (d.kind) {
        case DefectKind::IdOutOfRange: return out_of_range_message(d, base);
        case DefectKind::RepeatedId:
            return "triangle " + t0 + " repeats a vertex id (vertices " + id_list(d.vert, base) +
                   ")";
        case DefectKind::ZeroArea:
            return "triangle " + t0 + " has zero area (vertices " + id_list(d.vert, base) +
                   " are collinear)";
        case DefectKind::DuplicateTriangle:
            return "triangles " + t0 + " and " + t1 + " are the same triangle (vertices " +
                   id_list(d.vert, base) + ")";
        case DefectKind::Intersection:
            return "triangles " + t0 + " and " + t1 +
                   " intersect (not in a shared vertex or edge)";
        case DefectKind::OpenEdge: return edge_message(d, base, "open");
        case DefectKind::NonManifoldEdge: return edge_message(d, base, "non-manifold");
    }
    return "unknown defect";
}

std::string summarize(const SurfaceCheckResult& r, int base) {
    std::string counts;
    for (std::size_t k = 0; k < kDefectKindCount; ++k) {
        const auto kind = static_cast<DefectKind>(k);
        if (!is_error(kind) || r.counts[k] == 0) continue;
        counts += (counts.empty() ? "" : ", ") + std::to_string(r.counts[k]) + " " +
                  kind_noun(kind, r.counts[k] > 1);
    }
    if (counts.empty()) return "no defect";
    const std::int64_t n = r.error_count();
    std::string out = std::to_string(n) + (n == 1 ? " error: " : " errors: ") + counts;
    const auto first = std::find_if(r.defects.begin(), r.defects.end(),
                                    [](const Defect& d) { return is_error(d.kind); });
    if (first != r.defects.end()) out += "; first: " + describe(*first, base);  // none if cap 0
    return out;
}

}  // namespace cbr::recover
