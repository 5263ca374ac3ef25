// VTK XML unstructured grid (.vtu), ASCII, tetrahedra only (VTK_TETRA = 10):
//
//   <VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">
//     <UnstructuredGrid><Piece NumberOfPoints=.. NumberOfCells=..>
//       <PointData>  is_steiner (UInt8)
//       <CellData>   region (Int32), quality (Float64, when given)
//       <Points>     Float64 x 3
//       <Cells>      connectivity (Int64, 0-based), offsets (4, 8, ...),
//                    types (UInt8)
// The boundary triangles are not written (ParaView extracts surfaces
// itself; mixing cell types would complicate the cell data).
#include "io/text_writer.hpp"
#include "io/writers.hpp"

namespace cbr::io::detail {

namespace {

void open_array(TextWriter& w, const char* type, const char* name, int components = 1) {
    w.put("        <DataArray type=\"").put(type).put("\"");
    if (name != nullptr) w.put(" Name=\"").put(name).put("\"");
    if (components > 1) w.put(" NumberOfComponents=\"").put_int(components).put("\"");
    w.put(" format=\"ascii\">\n");
}

void close_array(TextWriter& w) { w.put("        </DataArray>\n"); }

}  // namespace

Status write_vtu(const std::string& path, const VolumeMesh& mesh) {
    TextWriter w;
    if (auto st = w.open(path); !st) return st;
    const std::size_t np = mesh.num_points(), nt = mesh.num_tets();

    w.put("<?xml version=\"1.0\"?>\n");
    w.put("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n");
    w.put("  <UnstructuredGrid>\n");
    w.put("    <Piece NumberOfPoints=\"").put_int(static_cast<std::int64_t>(np));
    w.put("\" NumberOfCells=\"").put_int(static_cast<std::int64_t>(nt)).put("\">\n");

    w.put("      <PointData Scalars=\"is_steiner\">\n");
    open_array(w, "UInt8", "is_steiner");
    for (std::size_t i = 0; i < np; ++i) {
        w.put(!mesh.is_steiner.empty() && mesh.is_steiner[i] != 0 ? '1' : '0').put('\n');
    }
    close_array(w);
    w.put("      </PointData>\n");

    w.put("      <CellData Scalars=\"region\">\n");
    open_array(w, "Int32", "region");
    for (std::size_t t = 0; t < nt; ++t) w.put_int(mesh.tet_regions[t]).put('\n');
    close_array(w);
    if (!mesh.tet_quality.empty()) {
        open_array(w, "Float64", "quality");
        for (std::size_t t = 0; t < nt; ++t) w.put_double(mesh.tet_quality[t]).put('\n');
        close_array(w);
    }
    w.put("      </CellData>\n");

    w.put("      <Points>\n");
    open_array(w, "Float64", "Points", 3);
    for (std::size_t i = 0; i < np; ++i) {
        w.put_double(mesh.xyz[3 * i]).put(' ').put_double(mesh.xyz[3 * i + 1]).put(' ');
        w.put_double(mesh.xyz[3 * i + 2]).put('\n');
    }
    close_array(w);
    w.put("      </Points>\n");

    w.put("      <Cells>\n");
    open_array(w, "Int64", "connectivity");
    for (std::size_t t = 0; t < nt; ++t) {
        w.put_int(mesh.tets[4 * t]).put(' ').put_int(mesh.tets[4 * t + 1]).put(' ');
        w.put_int(mesh.tets[4 * t + 2]).put(' ').put_int(mesh.tets[4 * t + 3]).put('\n');
    }
    close_array(w);
    open_array(w, "Int64", "offsets");
    for (std::size_t t = 0; t < nt; ++t) w.put_int(static_cast<std::int64_t>(4 * (t + 1))).put('\n');
    close_array(w);
    open_array(w, "UInt8", "types");
    for (std::size_t t = 0; t < nt; ++t) w.put("10\n");
    close_array(w);
    w.put("      </Cells>\n");

    w.put("    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    return w.commit();
}

}  // namespace cbr::io::detail
