// Printing the report of `cbr check` (see check_report.hpp).
#include "cli/check_report.hpp"

namespace cbr::cli {
namespace {

constexpr int kLabelWidth = 32;

void print_row(std::FILE* out, const ReportRow& row, std::size_t max_lines) {
    std::fprintf(out, "  %-*s %lld%s%s\n", kLabelWidth, row.label.c_str(), static_cast<long long>(row.count),
                 row.note.empty() ? "" : "  ", row.note.c_str());
    std::size_t shown = 0;
    for (; shown < row.listed.size() && shown < max_lines; ++shown)
        std::fprintf(out, "      %s\n", row.listed[shown].c_str());
    const auto more = static_cast<long long>(row.count) - static_cast<long long>(shown);
    if (shown > 0 && more > 0) std::fprintf(out, "      ... and %lld more\n", more);
}

void print_line(std::FILE* out, const char* label, const std::string& value) {
    std::fprintf(out, "  %-*s %s\n", kLabelWidth, label, value.c_str());
}

}  // namespace

std::int64_t CheckReport::error_count() const {
    std::int64_t n = 0;
    for (const ReportRow& row : rows) n += row.error ? row.count : 0;
    return n;
}

void print_report(std::FILE* out, const CheckReport& r, std::size_t max_lines) {
    std::fprintf(out, "cbr check %s\n", r.path.c_str());
    std::fprintf(out, "  %lld points, %lld triangles (ids below are 0-based, in file order)\n",
                 static_cast<long long>(r.points), static_cast<long long>(r.triangles));
    if (!r.merge_note.empty()) std::fprintf(out, "  note: %s\n", r.merge_note.c_str());
    std::fprintf(out, "\nerrors (each one stops a boundary recovery):\n");
    for (const ReportRow& row : r.rows)
        if (row.error) print_row(out, row, max_lines);
    std::fprintf(out, "\nsurface:\n");
    for (const ReportRow& row : r.rows)
        if (!row.error) print_row(out, row, max_lines);
    print_line(out, "orientation", r.orientation);
    print_line(out, "connected components", std::to_string(r.components));
    print_line(out, "points used by no triangle", std::to_string(r.unreferenced_points));
    print_line(out, "bounding box", r.bounding_box);
    print_line(out, "closest points", r.closest_points);
    print_line(out, "flattest triangle", r.flattest_triangle);
    if (!r.degenerate_note.empty()) std::fprintf(out, "  note: %s\n", r.degenerate_note.c_str());
    const std::string summary = error_summary(r);
    std::fprintf(out, "\nresult: %s\n",
                 summary.empty() ? "ok, usable for boundary recovery" : ("NOT usable: " + summary).c_str());
}

std::string error_summary(const CheckReport& r) {
    std::string counts, first;
    for (const ReportRow& row : r.rows) {
        if (!row.error || row.count == 0) continue;
        counts += (counts.empty() ? "" : ", ") + std::to_string(row.count) + " ";
        counts += row.count == 1 ? row.one : row.label;
        if (first.empty() && !row.listed.empty()) first = row.listed.front();
    }
    if (counts.empty()) return "";
    return first.empty() ? counts : counts + "; first: " + first;
}

}  // namespace cbr::cli
