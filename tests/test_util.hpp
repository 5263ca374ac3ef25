// Helpers shared by the tests: point generators, canonical tetrahedron
// sets, the shared-data directory, a tiny OFF reader.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace cbr::test {

inline std::vector<double> random_points(std::size_t n, std::uint64_t seed, double lo = 0.0, double hi = 1.0) {
    std::mt19937_64 rng(seed);
    std::vector<double> xyz(3 * n);
    for (double& c : xyz) c = lo + (hi - lo) * (double(rng() >> 11) * 0x1.0p-53);
    return xyz;
}

inline std::vector<double> grid_points(int n, double spacing = 1.0) {
    std::vector<double> xyz;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) xyz.insert(xyz.end(), {i * spacing, j * spacing, k * spacing});
    return xyz;
}

// Integer points exactly on the sphere x^2 + y^2 + z^2 = r2.
inline std::vector<double> integer_sphere_points(int r2) {
    std::vector<double> xyz;
    const int r = static_cast<int>(std::sqrt(double(r2))) + 1;
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            for (int z = -r; z <= r; ++z)
                if (x * x + y * y + z * z == r2) xyz.insert(xyz.end(), {double(x), double(y), double(z)});
    return xyz;
}

// Tetrahedra as sorted 4-tuples: compares triangulations regardless of the
// order of tetrahedra and of vertices within them.
using TetSet = std::set<std::array<std::int64_t, 4>>;
inline TetSet canonical(const std::vector<std::int64_t>& tets) {
    TetSet s;
    for (std::size_t i = 0; i + 3 < tets.size(); i += 4) {
        std::array<std::int64_t, 4> t = {tets[i], tets[i + 1], tets[i + 2], tets[i + 3]};
        std::sort(t.begin(), t.end());
        s.insert(t);
    }
    return s;
}

// Schonhardt's twisted prism: two triangles (points 0-2 at z = 0 and 3-5 at
// z = 1, the top turned by 30 degrees) joined by three quadrilaterals split
// by the diagonals that make the polyhedron impossible to tetrahedralize
// without a Steiner point. 8 outward triangles, 0-based.
struct Polyhedron {
    std::vector<double> xyz;
    std::vector<std::int64_t> tris;
};
inline Polyhedron schonhardt_prism() {
    const double pi = 3.14159265358979323846;
    Polyhedron p;
    for (int level = 0; level < 2; ++level)
        for (int i = 0; i < 3; ++i) {
            const double a = 2 * pi * i / 3 + (level ? pi / 6 : 0);
            p.xyz.insert(p.xyz.end(), {std::cos(a), std::sin(a), double(level)});
        }
    p.tris = {0, 2, 1, 3, 4, 5};
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        p.tris.insert(p.tris.end(), {i, j, 3 + j, i, 3 + j, 3 + i});
    }
    return p;
}

// The shared data directory (surfaces/, invalid/), or "" when absent.
inline std::string shared_data_dir() {
    const char* env = std::getenv("CBR_SHARED_DATA_DIR");
    if (env && std::filesystem::is_directory(std::string(env) + "/surfaces")) return env;
    return "";
}

struct OffSurface {
    std::vector<double> xyz;
    std::vector<std::int64_t> tris;
};

// A turn, a scale and a shift as tests/bench/rotate_surface.py applies
// them to every point p: coordinate r becomes scale * (rotation[r] . p) +
// shift[r], the dot product summed left to right. A seed's numbers written
// out (rotate_surface.transform(seed)) give the script's doubles.
struct Turn {
    double rotation[3][3];
    double scale;
    double shift[3];
};
inline constexpr Turn kRotateSurfaceSeed1{{{0.7291814484470931, 0.49710920991254126, -0.4702944276309556},
                                           {-0.40867983121920404, -0.23489142409215163, -0.8819335657761322},
                                           {-0.5488854259271619, 0.8352894422343009, 0.03188003915725375}},
                                          0.9388809398100537,
                                          {-94.84375311990932, 284.65550539709506, 542.1537025184375}};
inline constexpr Turn kRotateSurfaceSeed3{{{-0.08199866680955697, -0.7349894875293119, 0.6731022744448684},
                                           {-0.6251865069096083, -0.4880349325263164, -0.6090679241367061},
                                           {0.7761559445237908, -0.470757217528774, -0.4194872965000836}},
                                          5.679653280788985,
                                          {-4935.290880053457, -5530.0740279168995, 3833.414758588012}};
inline constexpr Turn kRotateSurfaceSeed164{{{-0.2689926522846132, 0.7851249034915506, 0.5578726009890362},
                                             {0.23360746278491962, 0.6151101241969013, -0.753038570354577},
                                             {-0.9343824197554669, -0.07223863943801839, -0.34887114042875833}},
                                            4.268727998936526,
                                            {-3236.1841496595257, -726.3207227024087, -4234.993483472944}};

inline void turn(std::vector<double>& xyz, const Turn& t) {
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
        const double p[3] = {xyz[i], xyz[i + 1], xyz[i + 2]};
        for (int r = 0; r < 3; ++r) {
            const double dot = t.rotation[r][0] * p[0] + t.rotation[r][1] * p[1] + t.rotation[r][2] * p[2];
            xyz[i + static_cast<std::size_t>(r)] = t.scale * dot + t.shift[r];
        }
    }
}

// Reads the shared data's OFF files (triangles only; '#' comment lines
// right after the OFF line, as in tests/data/io).
inline bool read_off(const std::string& path, OffSurface& s) {
    std::ifstream in(path);
    std::string magic;
    std::size_t nv = 0, nf = 0, ne = 0;
    if (!(in >> magic) || magic != "OFF") return false;
    while (in >> std::ws && in.peek() == '#') in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    if (!(in >> nv >> nf >> ne)) return false;
    s.xyz.resize(3 * nv);
    for (double& c : s.xyz)
        if (!(in >> c)) return false;
    s.tris.resize(3 * nf);
    for (std::size_t f = 0; f < nf; ++f) {
        int k = 0;
        if (!(in >> k) || k != 3) return false;
        for (int i = 0; i < 3; ++i)
            if (!(in >> s.tris[3 * f + i])) return false;
    }
    return true;
}

// main() of a doctest executable that needs the shared data: exit 77 (a
// skip for ctest) with a one-line reason when it is absent. Define
// DOCTEST_CONFIG_IMPLEMENT before including doctest in that file.
#define CBR_TEST_MAIN_NEEDING_SHARED_DATA                                                     \
    int main(int argc, char** argv) {                                                        \
        if (cbr::test::shared_data_dir().empty()) {                                          \
            std::puts("skipped: ../shared/data/surfaces not found (set CBR_SHARED_DATA_DIR)"); \
            return 77;                                                                       \
        }                                                                                    \
        doctest::Context context(argc, argv);                                                \
        return context.run();                                                                \
    }

inline std::vector<std::string> shared_surfaces() {
    std::vector<std::string> files;
    const std::string dir = shared_data_dir();
    if (dir.empty()) return files;
    for (const auto& e : std::filesystem::directory_iterator(dir + "/surfaces"))
        if (e.path().extension() == ".off") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace cbr::test
