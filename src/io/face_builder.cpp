#include "io/face_builder.hpp"

namespace cbr::io::detail {

bool append_face(SurfaceMesh& mesh, const std::int64_t* ids, std::size_t n, std::int32_t label,
                 bool triangulate) {
    if (n > 3 && !triangulate) return false;
    for (std::size_t i = 1; i + 1 < n; ++i) {
        mesh.tris.push_back(ids[0]);
        mesh.tris.push_back(ids[i]);
        mesh.tris.push_back(ids[i + 1]);
        mesh.labels.push_back(label);
    }
    return true;
}

std::string polygon_rejected(std::size_t corners) {
    return "has " + std::to_string(corners) +
           " corners: only triangles are accepted (--triangulate splits a polygon into a fan "
           "of triangles)";
}

}  // namespace cbr::io::detail
