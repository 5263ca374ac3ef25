// The report of `cbr check`: what was found, as rows of a table (a count
// and the first few instances, with file ids), printed on stdout, and a
// one-line summary of the errors for stderr.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace cbr::cli {

// One kind of defect: how many, and the first few, described.
struct ReportRow {
    std::string label;  // plural noun, e.g. "open edges"
    std::string one;    // singular noun, e.g. "open edge"
    std::int64_t count = 0;
    std::vector<std::string> listed;
    bool error = false;  // stops a recovery (then the exit code is 2)
    std::string note;    // after the count, e.g. "(allowed by --allow-open)"
};

struct CheckReport {
    std::string path;
    std::int64_t points = 0, triangles = 0;
    std::string bounding_box;     // "[x0, x1] x [y0, y1] x [z0, z1]"
    std::string merge_note;       // non-empty when duplicate points were merged
    std::vector<ReportRow> rows;  // errors first
    std::string orientation;      // one line
    std::int64_t components = 0;
    std::int64_t unreferenced_points = 0;
    std::string closest_points;     // one line (surface_margins.hpp)
    std::string flattest_triangle;  // one line
    std::string degenerate_note;    // non-empty when either is nearly degenerate

    std::int64_t error_count() const;
};

// Prints the report (every row, its first `max_lines` instances).
void print_report(std::FILE* out, const CheckReport& report, std::size_t max_lines);

// "7 intersecting triangle pairs, 4 open edges; first: triangles 3 and 9
// intersect", or "" when there is no error.
std::string error_summary(const CheckReport& report);

}  // namespace cbr::cli
