// CBR_PARAM_THREADS: the passes that only read the whole mesh, cut into
// chunks (mesh/chunks.hpp), give the answer of one pass, bit for bit,
// whatever the number of threads: the validity check (its listed problems
// in slot order and its counts), the lookup of triangles among the faces,
// the Table II of cbr_mesh_refine. The smoothing sweeps move the vertices
// of two halves at once (refine/vertex_halves.hpp): the split is checked
// here, the same mesh with any number of threads in test_refine.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/ball_shell.hpp"
#include "mesh/chunks.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh_test_util.hpp"
#include "recover/constraint_faces.hpp"
#include "refine/quality_stats.hpp"
#include "refine/vertex_halves.hpp"
#include "test_util.hpp"

namespace {

using cbr::mesh::TetId;
using cbr::mesh::TetMesh;
using cbr::mesh::VertexId;

// A Delaunay mesh of random points with several chunks' worth of slots.
TetMesh large_mesh() {
    TetMesh m = cbr::test::delaunay_mesh(cbr::test::random_points(12000, 49));
    REQUIRE(m.slot_count() > 4 * cbr::mesh::kMinChunk);
    return m;
}

void check_same(const cbr::mesh::CheckReport& one, const cbr::mesh::CheckReport& other) {
    CHECK(other.error_count == one.error_count);
    CHECK(other.errors == one.errors);
}

const int kThreadCounts[] = {2, 3, 8};

// Every row of two Table II tables equal, bit for bit.
void check_same_table(const cbr::refine::QualityTable& a, const cbr::refine::QualityTable& b) {
    CHECK(a.tets == b.tets);
    CHECK(a.average == b.average);  // summed in slot order
    CHECK(a.minimum == b.minimum);
    CHECK(a.percent_above_0_4 == b.percent_above_0_4);
    CHECK(a.percent_below_0_1 == b.percent_below_0_1);
    CHECK(a.bad_touching_steiner == b.bad_touching_steiner);
    CHECK(a.dihedral_min_deg == b.dihedral_min_deg);
    CHECK(a.dihedral_max_deg == b.dihedral_max_deg);
}

}  // namespace

TEST_CASE("threads: chunks cover the items once, in order, and only when large enough") {
    CHECK(cbr::mesh::chunk_count(0, 8) == 1);
    CHECK(cbr::mesh::chunk_count(cbr::mesh::kMinChunk * 10, 1) == 1);
    CHECK(cbr::mesh::chunk_count(cbr::mesh::kMinChunk * 10, 0) == 1);
    CHECK(cbr::mesh::chunk_count(cbr::mesh::kMinChunk - 1, 8) == 1);
    CHECK(cbr::mesh::chunk_count(cbr::mesh::kMinChunk * 3, 8) == 3);
    CHECK(cbr::mesh::chunk_count(cbr::mesh::kMinChunk * 10, 4) == 4);
    const std::size_t count = 100003;
    for (std::size_t chunks : {1, 2, 3, 7}) {
        CAPTURE(chunks);
        std::vector<int> visits(count, 0);
        std::vector<std::size_t> begins(chunks), ends(chunks);
        cbr::mesh::run_chunks(count, chunks, [&](std::size_t k, std::size_t begin, std::size_t end) {
            begins[k] = begin;
            ends[k] = end;
            for (std::size_t i = begin; i < end; ++i) ++visits[i];
        });
        CHECK(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; }));
        CHECK(begins.front() == 0);
        CHECK(ends.back() == count);
        for (std::size_t k = 1; k < chunks; ++k) CHECK(begins[k] == ends[k - 1]);
    }
}

TEST_CASE("threads: an exception of a chunk comes back after every chunk has run") {
    std::atomic<int> ran{0};
    const auto throwing = [&](std::size_t k, std::size_t, std::size_t) {
        ++ran;
        if (k == 2) throw std::runtime_error("chunk 2");
        if (k == 3) throw std::logic_error("chunk 3");
    };
    CHECK_THROWS_WITH_AS(cbr::mesh::run_chunks(1000, 4, throwing), "chunk 2", std::runtime_error);
    CHECK(ran == 4);
}

TEST_CASE("threads: the validity check lists the same problems, counts the same") {
    TetMesh m = large_mesh();
    const cbr::mesh::CheckReport valid = cbr::mesh::check_mesh(m, 1);
    REQUIRE(valid.ok());
    for (int threads : kThreadCounts) {
        CAPTURE(threads);
        // Every vertex used and the hull closed only with every chunk's
        // marks together.
        check_same(valid, cbr::mesh::check_mesh(m, threads));
    }
    // Inverted tetrahedra spread over every chunk (more than the report
    // lists: the first ones in slot order are listed), and a broken link.
    std::size_t inverted = 0;
    for (TetId t = 7; t < m.slot_count(); t += m.slot_count() / 25) {
        if (m.is_free(t) || m.is_ghost(t)) continue;
        const VertexId* v = m.vertices(t);
        m.set_vertices(t, v[1], v[0], v[2], v[3]);
        ++inverted;
    }
    REQUIRE(inverted > 12);
    TetId last = m.slot_count() - 1;
    while (m.is_free(last)) --last;
    m.set_neighbor(last, 0, m.neighbor(last, 1));
    const cbr::mesh::CheckReport broken = cbr::mesh::check_mesh(m, 1);
    REQUIRE(broken.error_count > broken.errors.size());
    for (int threads : kThreadCounts) {
        CAPTURE(threads);
        check_same(broken, cbr::mesh::check_mesh(m, threads));
    }
}

TEST_CASE("threads: the triangles are found at the same facets") {
    const TetMesh m = large_mesh();
    // Every third face of the mesh, some twice, a few that are not faces.
    std::vector<cbr::recover::Triangle> tris;
    for (TetId t = 0; t < m.slot_count(); t += 3) {
        if (m.is_free(t) || m.is_ghost(t)) continue;
        const cbr::test::Key3 k = cbr::test::face_key(m, t, static_cast<int>(t % 4));
        tris.push_back({k[0], k[2], k[1]});
        if (t % 9 == 0) tris.push_back({k[1], k[0], k[2]});
    }
    for (VertexId a = 0; a < 30; ++a) tris.push_back({a, a + 1000, a + 2000});
    const std::vector<cbr::mesh::FacetRef> one = cbr::recover::facets_of_mesh(m, tris, 1);
    REQUIRE(std::count(one.begin(), one.end(), cbr::recover::kNoFacet) == 30);  // the made-up ones
    for (int threads : kThreadCounts) {
        CAPTURE(threads);
        CHECK(cbr::recover::facets_of_mesh(m, tris, threads) == one);
    }
}

TEST_CASE("threads: Table II of the refined mesh, bit for bit, and of each region") {
    const TetMesh m = large_mesh();
    std::vector<std::int32_t> region(m.slot_count(), 0);
    for (TetId t = 0; t < m.slot_count(); ++t) region[t] = t % 5 == 0 ? 0 : 1 + static_cast<std::int32_t>(t % 3);
    std::vector<VertexId> steiner;
    for (VertexId v = 0; v < m.vertex_count(); v += 97) steiner.push_back(v);
    std::vector<cbr::refine::QualityTable> by_region;
    const cbr::refine::QualityTable one = cbr::refine::measure_quality(m, region, steiner, 1, &by_region);
    REQUIRE(one.tets > 3 * cbr::mesh::kMinChunk);
    REQUIRE(one.bad_touching_steiner > 0);
    REQUIRE(by_region.size() == 4);
    CHECK(by_region[0].tets == 0);  // the exterior is not measured
    CHECK(by_region[1].tets + by_region[2].tets + by_region[3].tets == one.tets);
    // Each region's table is the table of that region alone.
    for (std::int32_t r = 1; r <= 3; ++r) {
        CAPTURE(r);
        std::vector<std::int32_t> only(region.size());
        for (std::size_t t = 0; t < region.size(); ++t) only[t] = region[t] == r ? r : 0;
        check_same_table(by_region[static_cast<std::size_t>(r)], cbr::refine::measure_quality(m, only, steiner, 1));
    }
    for (int threads : kThreadCounts) {
        CAPTURE(threads);
        std::vector<cbr::refine::QualityTable> other_by_region;
        check_same_table(cbr::refine::measure_quality(m, region, steiner, threads, &other_by_region), one);
        REQUIRE(other_by_region.size() == by_region.size());
        for (std::size_t r = 0; r < by_region.size(); ++r) check_same_table(other_by_region[r], by_region[r]);
    }
}

TEST_CASE("threads: the smoothing halves: no edge joins inner vertices of both, every vertex once") {
    const TetMesh m = large_mesh();
    const cbr::mesh::VertexBalls balls(m);
    std::vector<VertexId> moving;  // every other vertex: the others stay, as surface vertices do
    for (VertexId v = 0; v < m.vertex_count(); v += 2)
        if (!balls.empty(v)) moving.push_back(v);
    const cbr::refine::VertexHalves halves = cbr::refine::split_in_halves(m, moving);
    // Each list in increasing id order; together, `moving` once each.
    std::vector<VertexId> all;
    for (const std::vector<VertexId>* list : {&halves.inner[0], &halves.inner[1], &halves.border}) {
        CHECK(std::is_sorted(list->begin(), list->end()));
        all.insert(all.end(), list->begin(), list->end());
    }
    std::sort(all.begin(), all.end());
    CHECK(all == moving);
    // No tetrahedron has a corner in each half's inner vertices; a vertex
    // that does not move may join them.
    std::vector<int> side(m.vertex_count(), -1);
    for (int h = 0; h < 2; ++h)
        for (VertexId v : halves.inner[static_cast<std::size_t>(h)]) side[v] = h;
    std::size_t joining = 0;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        bool has[2] = {false, false};
        for (int i = 0; i < 4; ++i) {
            const VertexId u = m.vertex(t, i);
            if (u != cbr::mesh::kGhostVertex && side[u] >= 0) has[side[u]] = true;
        }
        joining += has[0] && has[1];
    }
    CHECK(joining == 0);
    // The split: half the moving vertices each (median_halves), every
    // one of the first at or below every one of the second along one
    // axis; a border vertex has a tetrahedron with a moving corner in
    // each half (so the border is no wider than it must be), an inner
    // one none.
    const std::vector<std::uint8_t> half = cbr::refine::median_halves(m, moving);
    std::size_t in_first = 0, misplaced = 0;
    for (VertexId v = 0; v < m.vertex_count(); ++v) {
        misplaced += (half[v] != cbr::refine::kNoHalf) != std::binary_search(moving.begin(), moving.end(), v);
        in_first += half[v] == 0;
    }
    CHECK(misplaced == 0);
    CHECK(in_first == moving.size() / 2);
    bool some_axis_splits = false;
    for (int k = 0; k < 3; ++k) {
        double top_of_first = -HUGE_VAL, bottom_of_second = HUGE_VAL;
        for (VertexId v : moving) {
            if (half[v] == 0) top_of_first = std::max(top_of_first, m.point(v)[k]);
            else bottom_of_second = std::min(bottom_of_second, m.point(v)[k]);
        }
        some_axis_splits = some_axis_splits || top_of_first <= bottom_of_second;
    }
    CHECK(some_axis_splits);
    std::vector<char> reaches_both(m.vertex_count(), 0);
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        bool has[2] = {false, false};
        for (int i = 0; i < 4; ++i) {
            const VertexId u = m.vertex(t, i);
            if (u != cbr::mesh::kGhostVertex && half[u] < 2) has[half[u]] = true;
        }
        if (has[0] && has[1])
            for (int i = 0; i < 4; ++i)
                if (m.vertex(t, i) != cbr::mesh::kGhostVertex) reaches_both[m.vertex(t, i)] = 1;
    }
    std::size_t border_without_reach = 0, inner_with_reach = 0;
    for (VertexId v : halves.border) border_without_reach += !reaches_both[v];
    for (const std::vector<VertexId>& inner : halves.inner)
        for (VertexId v : inner) inner_with_reach += reaches_both[v];
    CHECK(border_without_reach == 0);
    CHECK(inner_with_reach == 0);
    // Split at the median, through the middle of a cube of points: halves
    // of equal work, and a thin border between them.
    const std::size_t half0 = halves.inner[0].size(), half1 = halves.inner[1].size();
    CHECK(half0 > moving.size() / 3);
    CHECK(half1 > moving.size() / 3);
    CHECK(halves.border.size() > 0);
    CHECK(halves.border.size() < moving.size() / 5);
    // Nothing to split.
    const cbr::refine::VertexHalves none = cbr::refine::split_in_halves(m, {});
    CHECK(none.inner[0].empty());
    CHECK(none.inner[1].empty());
    CHECK(none.border.empty());
}
