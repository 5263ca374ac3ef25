// A C++ user of libcbr found through find_package(cbr): one tetrahedron.
#include <cbr/cbr.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

int main()
{
    const std::string expected = std::to_string(CBR_VERSION_MAJOR) + "." +
                                 std::to_string(CBR_VERSION_MINOR) + "." +
                                 std::to_string(CBR_VERSION_PATCH);
    if (expected != cbr_version()) {
        std::fprintf(stderr, "cbr_version() = %s, header says %s\n", cbr_version(),
                     expected.c_str());
        return 1;
    }

    cbr_mesh *raw = nullptr;
    if (cbr_mesh_create(&raw) != CBR_OK)
        return 1;
    std::unique_ptr<cbr_mesh, void (*)(cbr_mesh *)> mesh(raw, cbr_mesh_destroy);

    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    if (cbr_mesh_insert_points(mesh.get(), 4, xyz.data()) != CBR_OK) {
        std::fprintf(stderr, "insert: %s\n", cbr_mesh_last_error(mesh.get()));
        return 1;
    }
    if (cbr_mesh_tet_count(mesh.get()) != 1) {
        std::fprintf(stderr, "expected 1 tetrahedron, got %lld\n",
                     static_cast<long long>(cbr_mesh_tet_count(mesh.get())));
        return 1;
    }
    std::vector<int64_t> tet(4);
    if (cbr_mesh_get_tets(mesh.get(), tet.data()) != CBR_OK)
        return 1;
    std::vector<int> seen(4, 0);
    for (int64_t id : tet) {
        if (id < 0 || id > 3) {
            std::fprintf(stderr, "id %lld out of 0..3\n", static_cast<long long>(id));
            return 1;
        }
        seen[static_cast<std::size_t>(id)] = 1;
    }
    if (seen != std::vector<int>(4, 1)) {
        std::fprintf(stderr, "the tetrahedron does not use the 4 points\n");
        return 1;
    }
    std::printf("cbr_consumer: libcbr %s via find_package(cbr), 1 tetrahedron: OK\n",
                cbr_version());
    return 0;
}
