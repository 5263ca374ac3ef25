// Delaunay tetrahedralization of uniform random points: libcbr against
// CGAL's Delaunay_triangulation_3<Epick>, side by side in one run.
//
//   delaunay_bench [--seed S] [--repeat R] [N ...]      (default N: 1e5 1e6 3e6)
//
// For each N, the same N points (std::mt19937_64 with a fixed seed, mapped to
// [0,1)^3 by this file, so reproducible everywhere) are tetrahedralized by
//   libcbr: cbr_mesh_create + cbr_mesh_insert_points + cbr_mesh_tet_count,
//   CGAL:   Delaunay_triangulation_3 built from the range (it sorts it along
//           a Hilbert curve) + number_of_finite_cells.
// Each run happens in its own forked process, so that the two libraries'
// memory does not mix: the child generates the points, notes its RSS, runs
// the library (timed with steady_clock) and reports its peak RSS (VmHWM).
// The table gives points per second, the speed ratio libcbr / CGAL (> 1:
// libcbr is faster), the number of finite tetrahedra (the Delaunay
// tetrahedralization of random points is unique: both must agree) and bytes
// per tetrahedron, both of the whole process (peak RSS / tets) and of the
// library alone ((peak RSS - RSS before the call) / tets).
//
// A benchmark, not a test: nothing is asserted about time. The exit status
// is 1 only when a library failed or the tetrahedron counts disagree.
#include <cbr/cbr.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/version.h>

#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel>;

// What a child process sends back through its pipe (plain data).
struct RunResult {
    int ok = 0;              // 1 when the library succeeded
    double seconds = 0;      // the timed calls only
    int64_t tets = 0;        // finite tetrahedra
    long rss_before_kb = 0;  // VmRSS just before the timed calls
    long peak_kb = 0;        // VmHWM at the end (peak of the whole process)
    char error[256] = {};
};

// N uniform points in [0,1)^3: 53 random bits per coordinate, so every
// platform with a standard mt19937_64 gives the same doubles.
std::vector<double> random_points(int64_t n, uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::vector<double> xyz(static_cast<size_t>(3 * n));
    for (double &c : xyz)
        c = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    return xyz;
}

// A "VmXXX:  1234 kB" field of /proc/self/status, in kB; -1 if unavailable.
long proc_status_kb(const char *field)
{
    std::ifstream in("/proc/self/status");
    std::string line;
    const size_t len = std::strlen(field);
    while (std::getline(in, line))
        if (line.compare(0, len, field) == 0 && line.size() > len && line[len] == ':')
            return std::strtol(line.c_str() + len + 1, nullptr, 10);
    return -1;
}

std::string cpu_model()
{
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.compare(0, 10, "model name") == 0) {
            const size_t colon = line.find(':');
            if (colon != std::string::npos)
                return line.substr(line.find_first_not_of(" \t", colon + 1));
        }
    return "unknown (no /proc/cpuinfo model name)";
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Child side of the libcbr run. The mesh is not destroyed: the child exits
// right after, and teardown is not what is measured.
RunResult run_libcbr(int64_t n, uint64_t seed)
{
    RunResult r;
    const std::vector<double> xyz = random_points(n, seed);
    r.rss_before_kb = proc_status_kb("VmRSS");

    const Clock::time_point start = Clock::now();
    cbr_mesh *mesh = nullptr;
    int status = cbr_mesh_create(&mesh);
    if (status == CBR_OK)
        status = cbr_mesh_insert_points(mesh, n, xyz.data());
    const int64_t tets = status == CBR_OK ? cbr_mesh_tet_count(mesh) : -1;
    r.seconds = seconds_since(start);

    r.peak_kb = proc_status_kb("VmHWM");
    if (status != CBR_OK || tets < 0) {
        std::snprintf(r.error, sizeof r.error, "%s: %s", cbr_status_string(status),
                      cbr_mesh_last_error(mesh));
        return r;
    }
    r.tets = tets;
    r.ok = 1;
    return r;
}

// Child side of the CGAL run; the triangulation is not destroyed either.
RunResult run_cgal(int64_t n, uint64_t seed)
{
    RunResult r;
    std::vector<Kernel::Point_3> points;
    {
        const std::vector<double> xyz = random_points(n, seed);
        points.reserve(static_cast<size_t>(n));
        for (size_t i = 0; i < xyz.size(); i += 3)
            points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
    }
    r.rss_before_kb = proc_status_kb("VmRSS");

    const Clock::time_point start = Clock::now();
    auto *dt = new Delaunay(points.begin(), points.end());
    const auto tets = static_cast<int64_t>(dt->number_of_finite_cells());
    r.seconds = seconds_since(start);

    r.peak_kb = proc_status_kb("VmHWM");
    r.tets = tets;
    r.ok = 1;
    return r;
}

// Runs `body` in a forked child and returns what it reported.
template <class Body> RunResult in_child(Body body)
{
    RunResult r;
    int fds[2];
    if (pipe(fds) != 0) {
        std::snprintf(r.error, sizeof r.error, "pipe: %s", std::strerror(errno));
        return r;
    }
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid < 0) {
        std::snprintf(r.error, sizeof r.error, "fork: %s", std::strerror(errno));
        close(fds[0]);
        close(fds[1]);
        return r;
    }
    if (pid == 0) {
        close(fds[0]);
        RunResult child;
        try {
            child = body();
        } catch (const std::exception &e) {
            std::snprintf(child.error, sizeof child.error, "exception: %s", e.what());
        }
        const char *p = reinterpret_cast<const char *>(&child);
        size_t left = sizeof child;
        while (left > 0) {
            const ssize_t w = write(fds[1], p, left);
            if (w <= 0)
                _exit(2);
            p += w;
            left -= static_cast<size_t>(w);
        }
        _exit(0);
    }
    close(fds[1]);
    char *p = reinterpret_cast<char *>(&r);
    size_t got = 0;
    while (got < sizeof r) {
        const ssize_t n = read(fds[0], p + got, sizeof r - got);
        if (n <= 0)
            break;
        got += static_cast<size_t>(n);
    }
    close(fds[0]);
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    if (got != sizeof r) {
        r = RunResult();
        if (WIFSIGNALED(status))
            std::snprintf(r.error, sizeof r.error, "child killed by signal %d (%s)",
                          WTERMSIG(status), strsignal(WTERMSIG(status)));
        else
            std::snprintf(r.error, sizeof r.error, "child exited with status %d",
                          WEXITSTATUS(status));
    }
    if (r.peak_kb <= 0)  // no /proc: fall back on the kernel's account
        r.peak_kb = usage.ru_maxrss;
    return r;
}

// Best (shortest) of `repeat` runs; memory and counts from the first.
template <class Body> RunResult best_of(int repeat, Body body)
{
    RunResult best = in_child(body);
    for (int i = 1; i < repeat && best.ok; ++i) {
        const RunResult again = in_child(body);
        if (!again.ok)
            return again;
        best.seconds = std::min(best.seconds, again.seconds);
    }
    return best;
}

void print_row(int64_t n, const char *name, const RunResult &r)
{
    if (!r.ok) {
        std::printf("%10" PRId64 "  %-7s  FAILED: %s\n", n, name, r.error);
        return;
    }
    const double kib = 1024.0;
    const double tets = r.tets > 0 ? static_cast<double>(r.tets) : std::numeric_limits<double>::infinity();
    std::printf("%10" PRId64 "  %-7s %9.3f %10.3f %12" PRId64 " %7.2f %10.1f %10.1f %10.1f\n",
                n, name, r.seconds, static_cast<double>(n) / r.seconds / 1e6, r.tets,
                static_cast<double>(r.tets) / static_cast<double>(n),
                static_cast<double>(r.peak_kb) / kib, static_cast<double>(r.peak_kb) * kib / tets,
                static_cast<double>(r.peak_kb - r.rss_before_kb) * kib / tets);
}

[[noreturn]] void usage(const char *argv0)
{
    std::fprintf(stderr,
                 "usage: %s [--seed S] [--repeat R] [N ...]\n"
                 "  N: number of points, e.g. 1e5 (default: 1e5 1e6 3e6)\n"
                 "  --seed S    seed of std::mt19937_64 (default 20240521)\n"
                 "  --repeat R  time R runs of each library, report the fastest (default 1)\n",
                 argv0);
    std::exit(2);
}

int64_t parse_count(const char *text, const char *argv0)
{
    char *end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(v >= 4) || v > 2147483646.0 ||
        v != static_cast<double>(static_cast<int64_t>(v)))
        usage(argv0);
    return static_cast<int64_t>(v);
}

}  // namespace

int main(int argc, char **argv)
{
    uint64_t seed = 20240521;
    int repeat = 1;
    std::vector<int64_t> sizes;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--seed" && i + 1 < argc)
            seed = std::strtoull(argv[++i], nullptr, 10);
        else if (arg == "--repeat" && i + 1 < argc)
            repeat = std::max(1, std::atoi(argv[++i]));
        else if (arg == "-h" || arg == "--help" || arg.compare(0, 1, "-") == 0)
            usage(argv[0]);
        else
            sizes.push_back(parse_count(argv[i], argv[0]));
    }
    if (sizes.empty())
        sizes = {100000, 1000000, 3000000};

    std::printf("Delaunay tetrahedralization of N uniform random points in [0,1)^3\n");
    std::printf("CPU:    %s (%ld online)\n", cpu_model().c_str(), sysconf(_SC_NPROCESSORS_ONLN));
    std::printf("libcbr: %s (loaded), CGAL: %s Delaunay_triangulation_3<Epick>, "
                "range insert\n",
                cbr_version(), CGAL_VERSION_STR);
    std::printf("seed:   %" PRIu64 ", best of %d run(s), each library in its own process\n\n",
                seed, repeat);
    std::printf("%10s  %-7s %9s %10s %12s %7s %10s %10s %10s\n", "N", "library", "time [s]",
                "Mpts/s", "tets", "tets/pt", "peak [MiB]", "B/tet", "B/tet net");

    int problems = 0;
    struct Summary {
        int64_t n;
        RunResult cbr, cgal;
    };
    std::vector<Summary> summary;
    for (const int64_t n : sizes) {
        const RunResult cbr = best_of(repeat, [&] { return run_libcbr(n, seed); });
        print_row(n, "libcbr", cbr);
        const RunResult cgal = best_of(repeat, [&] { return run_cgal(n, seed); });
        print_row(n, "CGAL", cgal);
        if (!cbr.ok || !cgal.ok) {
            ++problems;
            std::printf("%10s  ratio   n/a (a run failed)\n\n", "");
            continue;
        }
        const double ratio = cgal.seconds / cbr.seconds;  // = pts/s libcbr / pts/s CGAL
        summary.push_back({n, cbr, cgal});
        const bool agree = cbr.tets == cgal.tets;
        if (!agree)
            ++problems;
        const double cbr_net = static_cast<double>(cbr.peak_kb - cbr.rss_before_kb);
        const double cgal_net = static_cast<double>(cgal.peak_kb - cgal.rss_before_kb);
        const double memory_ratio = cbr.tets > 0 && cgal_net > 0
            ? (cbr_net / static_cast<double>(cbr.tets)) /
                  (cgal_net / static_cast<double>(cgal.tets))
            : 0.0;
        std::printf("%10s  libcbr / CGAL speed: %.2fx   net bytes per tet: %.2fx   tets: %s\n\n",
                    "", ratio, memory_ratio,
                    agree ? "agree" : "MISMATCH (the Delaunay tetrahedralization is unique)");
    }
    if (!summary.empty()) {
        std::printf("Summary (net bytes per tet)\n%10s %14s %14s %12s %12s %12s  %s\n", "N",
                    "libcbr Mpts/s", "CGAL Mpts/s", "libcbr/CGAL", "libcbr B/tet",
                    "CGAL B/tet", "tets");
        for (const Summary &s : summary) {
            const auto mpts = [&](const RunResult &r) {
                return static_cast<double>(s.n) / r.seconds / 1e6;
            };
            const auto net = [](const RunResult &r) {
                return r.tets > 0 ? static_cast<double>(r.peak_kb - r.rss_before_kb) * 1024.0 /
                                        static_cast<double>(r.tets)
                                  : 0.0;
            };
            std::printf("%10" PRId64 " %14.3f %14.3f %11.2fx %12.1f %12.1f  %s\n", s.n,
                        mpts(s.cbr), mpts(s.cgal), s.cgal.seconds / s.cbr.seconds, net(s.cbr),
                        net(s.cgal), s.cbr.tets == s.cgal.tets ? "agree" : "MISMATCH");
        }
        std::printf("\n");
    }
    std::printf("B/tet = peak RSS / tets; B/tet net = (peak RSS - RSS before the call) / tets.\n"
                "Speed ratio > 1: libcbr is faster. Mpts/s counts input points per second.\n");
    if (problems != 0)
        std::printf("%d problem(s): see FAILED / MISMATCH above\n", problems);
    return problems == 0 ? 0 : 1;
}
