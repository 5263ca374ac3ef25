#include "cli/run_report.hpp"

#include <cbr/cbr.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <new>

#include "cli/exit_codes.hpp"
#include "cli/json_writer.hpp"

namespace cbr::cli {
namespace {

std::int64_t count(double v) { return std::isfinite(v) ? static_cast<std::int64_t>(std::llround(v)) : 0; }

void table_one(JsonWriter& j, const TableOne& t) {
    j.begin_object();
    j.key("total_vertices").integer(count(t.total_vertices));
    j.key("boundary_vertices").integer(count(t.boundary_vertices));
    j.key("missing_faces").integer(count(t.missing_faces));
    j.key("recovered_by_flips").integer(count(t.recovered_by_flips));
    j.key("conforming_points").integer(count(t.conforming_points));
    j.key("steiner_generated").integer(count(t.steiner_generated));
    j.key("steiner_remaining").integer(count(t.steiner_remaining));
    j.key("steiner_inside").integer(count(t.steiner_inside));
    j.key("region_count").integer(count(t.region_count));
    j.key("delaunay_seconds").number(t.delaunay_seconds);
    j.key("recovery_seconds").number(t.recovery_seconds);
    j.key("total_seconds").number(t.total_seconds);
    j.end_object();
}

void quality_members(JsonWriter& j, const QualityStats& s) {
    j.key("tetrahedra").integer(s.tets);
    j.key("quality_average").number(s.quality_average);
    j.key("quality_min").number(s.quality_min);
    j.key("percent_above_0_4").number(s.percent_above_0_4);
    j.key("percent_below_0_1").number(s.percent_below_0_1);
    j.key("bad_touching_steiner").integer(s.bad_touching_steiner);
    j.key("dihedral_min_degrees").number(s.dihedral_min_deg);
    j.key("dihedral_max_degrees").number(s.dihedral_max_deg);
}

void table_two(JsonWriter& j, const QualityReport& q) {
    j.begin_object();
    quality_members(j, q.all);
    j.key("regions").begin_array();
    for (const RegionQuality& r : q.regions) {
        j.begin_object();
        j.key("region").integer(r.region);
        quality_members(j, r.stats);
        j.end_object();
    }
    j.end_array();
    j.end_object();
}

// "options": what the command line asked for (run_report.hpp).
void options(JsonWriter& j, const RunDescription& run) {
    const RecoveryOptions& o = run.options;
    j.key("options").begin_object();
    j.key("keep_exterior").boolean(o.keep_exterior);
    j.key("allow_open").boolean(o.allow_open);
    j.key("triangulate").boolean(run.triangulate);
    j.key("deep_flips").boolean(o.deep_flips);
    j.key("retries").boolean(o.retries);
    j.key("threads").integer(o.threads);
    // Not given: NaN, which number() writes as null.
    constexpr double kNotGiven = std::numeric_limits<double>::quiet_NaN();
    j.key("size").number(o.size > 0 ? o.size : kNotGiven);
    j.key("growth").number(o.growth >= 0 ? o.growth : kNotGiven);
    j.end_object();
}

}  // namespace

std::string run_report_json(const RunDescription& run, const RecoveryOutcome& outcome) {
    JsonWriter j;
    j.begin_object();
    j.key("cbr_version").string(cbr_version());
    j.key("command").string(run.command);
    j.key("input").string(run.options.input);
    j.key("output");
    if (outcome.written) {
        j.string(run.options.output);
    } else {
        j.null();
    }
    options(j, run);
    j.key("status").string(exit_status_name(outcome.exit_code));
    j.key("exit_code").integer(outcome.exit_code);
    j.key("error");
    if (outcome.error.empty()) {
        j.null();
    } else {
        j.string(outcome.error);
    }
    j.key("mesh");
    if (outcome.has_quality) {
        j.begin_object();
        j.key("points").integer(static_cast<std::int64_t>(outcome.points));
        j.key("tetrahedra").integer(static_cast<std::int64_t>(outcome.tets));
        j.end_object();
    } else {
        j.null();
    }
    j.key("table_one");
    if (outcome.has_table_one) {
        table_one(j, outcome.table_one);
    } else {
        j.null();
    }
    j.key("refine");
    if (outcome.has_refine) {
        j.begin_object();
        j.key("field_points").integer(count(outcome.refine.field_points));
        j.key("flips").integer(count(outcome.refine.flips));
        j.key("oversize_tets").integer(count(outcome.refine.oversize_tets));
        j.key("seconds").number(outcome.refine.seconds);
        j.end_object();
    } else {
        j.null();
    }
    j.key("table_two");
    if (outcome.has_quality) {
        table_two(j, outcome.quality);
    } else {
        j.null();
    }
    j.end_object();
    return j.text();
}

io::Status write_run_report(const std::string& path, const RunDescription& run, const RecoveryOutcome& outcome) {
    try {
        return write_text_file(path, run_report_json(run, outcome));
    } catch (const std::bad_alloc&) {
        return io::Status::error(io::ErrorKind::out_of_memory, path + ": out of memory");
    }
}

int finish_run(const RunDescription& run, const std::string& json_path, const RecoveryOutcome& outcome, Steps& steps) {
    int code = outcome.exit_code;
    std::string json_error;
    if (!json_path.empty()) {
        steps.begin("writing the report", true);
        const io::Status st = write_run_report(json_path, run, outcome);
        steps.end();
        if (!st.ok()) {
            json_error = st.message;
            if (code == kExitOk) code = exit_code_for(st.kind);
        }
    }
    std::fflush(stdout);  // the report first, then the error lines
    if (!outcome.error.empty()) std::fprintf(stderr, "cbr %s: %s\n", run.command.c_str(), outcome.error.c_str());
    if (!json_error.empty()) std::fprintf(stderr, "cbr %s: %s\n", run.command.c_str(), json_error.c_str());
    steps.report_timing();
    return code;
}

}  // namespace cbr::cli
