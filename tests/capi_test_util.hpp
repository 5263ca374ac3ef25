// Helpers for tests that use libcbr through its C API, as a caller does.
// Include after <doctest/doctest.h>.
#pragma once

#include <cbr/cbr.h>

#include <cstdint>
#include <string>
#include <vector>

namespace cbr::test {

// A mesh handle for one test.
struct Handle {
    cbr_mesh* m = nullptr;
    Handle() { REQUIRE(cbr_mesh_create(&m) == CBR_OK); }
    ~Handle() { cbr_mesh_destroy(m); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    std::string error() const { return cbr_mesh_last_error(m); }
};

inline std::vector<std::int64_t> tets_of(const cbr_mesh* m) {
    std::vector<std::int64_t> t(4 * static_cast<std::size_t>(cbr_mesh_tet_count(m)));
    REQUIRE(cbr_mesh_get_tets(m, t.data()) == CBR_OK);
    return t;
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace cbr::test
