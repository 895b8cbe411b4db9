// Markdown and JSON writers of the stability report.
#include "stability/report.h"

#include "base/atomic_file.h"

#include <cmath>
#include <cstdio>
#include <string_view>

namespace rtlab::stab {

namespace {

/// A relative error in short scientific form; "-" when not measured, "0" when exact.
std::string sci(double x) {
    if (std::isnan(x)) {
        return "-";
    }
    if (x == 0) {
        return "0";
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1e", x);
    return buf;
}

/// ns per ray with sensible digits; "-" when not measured.
std::string ns(double x) {
    if (std::isnan(x)) {
        return "-";
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, x < 10 ? "%.2f" : (x < 1000 ? "%.1f" : "%.0f"), x);
    return buf;
}

/// Markdown table cells must not contain a bare '|'.
std::string cell(std::string_view s) {
    std::string out;
    for (const char c : s) {
        if (c == '|') {
            out += "\\|";
        } else if (c == '\n') {
            out += ' ';
        } else {
            out += c;
        }
    }
    return out;
}

/// A JSON string literal.
std::string quote(std::string_view s) {
    std::string out = "\"";
    for (const char c : s) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\t':
            out += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
                out += buf;
            } else {
                out += c;
            }
        }
    }
    return out + "\"";
}

/// A JSON number; null for NaN or infinity.
std::string number(double x) {
    if (!std::isfinite(x)) {
        return "null";
    }
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

}  // namespace

std::string compiler_description() {
#ifdef __clang__
    std::string c = "clang ";
#else
    std::string c = "g++ ";
#endif
    c += __VERSION__;
#ifdef NDEBUG
    c += ", release (NDEBUG)";
#else
    c += ", debug";
#endif
    return c;
}

namespace {

// Why each structure's robust traversal offers every primitive the exact ray meets; the
// `adversarial` case aims rays at each structure's weak spot named here.
constexpr std::string_view conservative_traversal_notes =
    "## Why robust traversal leaks no ray, per structure\n\n"
    "*Robust* traversal must offer the leaf callback every primitive that the exact ray (its float "
    "values taken as exact) meets in its window; a leak on a closed mesh with the watertight "
    "method "
    "is then impossible, and the leak cases classify a ray lost by a robust structure as a defect "
    "(the tests fail on it). The argument per structure, and the weak spot the `adversarial` case "
    "aims at:\n\n"
    "- **Brute force, binary, pair and wide BVHs (`bvh:*`, `bvh4`, `bvh8`, `bvh16`).** A box is "
    "the float union of its primitives' boxes, so it contains them exactly. Each slab distance "
    "`(plane - org) * inv_dir` is within gamma(3) of the exact one; the robust slab test widens "
    "near and far distances outward by 2 gamma(3), sign-aware (Ize 2013; pbrt-v4 uses the same "
    "bound), so its interval contains the exact ray's. Weak spot: rays at node box faces, their "
    "edges and corners, and rays starting one float beside a face, nearly parallel to it.\n"
    "- **`bvh8q`.** Child boxes are quantised per node with outward rounding, so each decoded box "
    "contains the exact child box, and the robust slab test above runs on it. Weak spot: the "
    "decoded faces (the case reads them from the built nodes); a test checks that decoded boxes "
    "enclose extreme child boxes.\n"
    "- **`bounds=dop14`.** Robust traversal tests the boxes only (the diagonal slabs are for plain "
    "traversal), so the BVH argument applies unchanged; a test checks that robust traversal with "
    "slabs returns the closest hit of the same tree without them, bit for bit, on adversarial "
    "rays.\n"
    "- **`bvh:sbvh` and kd-tree builds.** A primitive cut by a spatial or perfect split is "
    "referenced by every side its exact part meets: `clip_triangle_bounds` (trace/clip.h) clips "
    "against the cell widened by 2^-17 of the triangle's largest coordinate per axis and widens "
    "every coordinate it computed by the same, more than the few ulps per plane that float "
    "clipping can move a vertex (tests/clip_test.cpp checks it against an exact clip); without a "
    "clip the box is cut at the plane, which is exact. Weak spot: thin cells "
    "(split planes at coordinates of 1e-17 beside vertices at 0.25).\n"
    "- **kd-tree, t-value walk.** The split distance is within gamma(3) of the exact one; the near "
    "child's window ends 2 gamma(3) after it and the far child's starts 2 gamma(3) before it; a "
    "ray lying in the plane (NaN distance) visits both children. Rays with a zero or subnormal "
    "direction component always take this walk.\n"
    "- **kd-tree, entry/exit-point walk (Havran's TA^B_rec).** Entry and exit points are kept "
    "at computed (never lowered) distances, so every coordinate is within `havran_pad`, gamma(6) "
    "of |org| + |dir t|, of the exact ray's point; a child is skipped only when both points lie "
    "beyond the plane by more than that; the stop test compares the next entry lowered by "
    "2 gamma(3) with the closest hit (the full argument is in accel/kdtree/havran.h). Weak spot: "
    "splits through one vertex on two or three axes, nested in the tree, crossed by a ray from "
    "the exact centre at one t (the walk lost rays there until the points stopped carrying "
    "lowered distances), and corners of split faces. Two tests aim there: rays from the exact "
    "centre at every vertex and split-face corner, and Moller-Trumbore (which leaks by itself, "
    "so it reaches hits the watertight method does not) on adversarial meshes where the old walk "
    "lost 31, 32 and 2 of 20,000 rays.\n"
    "- **Uniform and two-level grids.** The grid box is clipped with the robust slab test, so "
    "the walk's window starts no later and ends no earlier than the exact ray's. The robust "
    "3D-DDA then runs in double: per axis, the cell it holds at each t is the exact point's cell "
    "or a neighbour across a plane the point lies within 2^-50 (|org| + |x|) of, and it walks "
    "every t of the window (an index that would leave the grid stays in its last cell). Builders "
    "list every primitive in each cell its box reaches once widened by 1e-4 of a cell plus 4 "
    "ulps of the grid's coordinates, cell indices computed in double (accel/grid/cell_map.h), "
    "both levels alike. The rounding stays inside that padding while the origin lies within "
    "about 10^10 cells of the grid; farther out the walk visits every cell (the full argument is "
    "in accel/grid/dda.h). Weak spot: rays from far away, where float rounding of the entry point "
    "and crossing times spans cells (a test traces them from 10^2 to 10^11 radii; the float walk "
    "lost rays there), and rays at cell boundaries, edges and corners of both levels.\n";

}  // namespace

std::string to_markdown(const ReportHeader& h, std::span<const CaseResult> results) {
    std::string md;
    md += "# Numerical stability of rtlab\n\n";
    md += "Generated by `" + h.command + "`; do not edit by hand.\n\n";
    md += "| | |\n|---|---|\n";
    md += "| git revision | `" + cell(h.revision) + "` |\n";
    md += "| compiler | " + cell(h.compiler) + " |\n";
    md += "| CPU | " + cell(h.cpu) + " |\n";
    md += "| rays per subject | " + std::to_string(h.options.rays) + " |\n";
    md += "| seed | " + std::to_string(h.options.seed) + " |\n\n";
    md +=
        "Each row is one subject (method, structure, traversal, offset policy, ...) in one "
        "precision. *failures* counts rays that broke the case's property (their kind in "
        "brackets); relative t errors are against the case's reference (exact CGAL/GMP answer "
        "or a reference method; `-` when not measured); ns/ray is single-threaded wall time "
        "(debug builds are much slower).\n\n";
    md += "Cases:";
    for (const CaseResult& r : results) {
        md += " [" + r.name + "](#" + r.name + ")";
    }
    md += "\n\n";
    md += conservative_traversal_notes;
    for (const CaseResult& r : results) {
        md += "\n## " + r.name + "\n\n";
        md += r.description + "\n\n";
        std::size_t failures = 0;
        for (const Row& row : r.rows) {
            failures += row.failures;
        }
        char buf[96];
        std::snprintf(buf, sizeof buf, "%zu rows, %zu failures in all, %.1f s.\n\n", r.rows.size(),
                      failures, r.seconds);
        md += buf;
        md +=
            "| subject | precision | rays | failures | max rel t err | median rel t err | "
            "ns/ray | note |\n";
        md += "|---|---|---:|---:|---:|---:|---:|---|\n";
        for (const Row& row : r.rows) {
            std::string sub = row.subject;
            if (!row.case_name.empty() && row.case_name != r.name) {
                sub = row.case_name + ": " + sub;
            }
            md += "| " + cell(sub) + " | " + cell(row.precision) + " | " +
                  std::to_string(row.rays) + " | " + std::to_string(row.failures) +
                  (row.failure_kind.empty() ? "" : " (" + cell(row.failure_kind) + ")") + " | " +
                  sci(row.max_rel_t_err) + " | " + sci(row.median_rel_t_err) + " | " +
                  ns(row.ns_per_ray) + " | " + cell(row.note) + " |\n";
        }
    }
    return md;
}

std::string to_json(const ReportHeader& h, std::span<const CaseResult> results) {
    std::string j = "{\"header\":{";
    j += "\"command\":" + quote(h.command);
    j += ",\"revision\":" + quote(h.revision);
    j += ",\"compiler\":" + quote(h.compiler);
    j += ",\"cpu\":" + quote(h.cpu);
    j += ",\"rays\":" + std::to_string(h.options.rays);
    j += ",\"seed\":" + std::to_string(h.options.seed);
    j += "},\"cases\":[";
    for (std::size_t c = 0; c < results.size(); ++c) {
        const CaseResult& r = results[c];
        j += c ? ",{" : "{";
        j += "\"name\":" + quote(r.name);
        j += ",\"description\":" + quote(r.description);
        j += ",\"seconds\":" + number(r.seconds);
        j += ",\"rows\":[";
        for (std::size_t i = 0; i < r.rows.size(); ++i) {
            const Row& row = r.rows[i];
            j += i ? ",{" : "{";
            j += "\"case\":" + quote(row.case_name);
            j += ",\"subject\":" + quote(row.subject);
            j += ",\"precision\":" + quote(row.precision);
            j += ",\"rays\":" + std::to_string(row.rays);
            j += ",\"failures\":" + std::to_string(row.failures);
            j += ",\"failure_kind\":" + quote(row.failure_kind);
            j += ",\"max_rel_t_err\":" + number(row.max_rel_t_err);
            j += ",\"median_rel_t_err\":" + number(row.median_rel_t_err);
            j += ",\"ns_per_ray\":" + number(row.ns_per_ray);
            j += ",\"note\":" + quote(row.note);
            j += "}";
        }
        j += "]}";
    }
    j += "]}\n";
    return j;
}

void write_report(const std::filesystem::path& file, const std::string& text) {
    write_file_atomically(file, text);
}

}  // namespace rtlab::stab
