// Walks OBJ, PLY (ASCII and binary), OFF and STL (ASCII and binary) bytes and rejects what
// OpenMesh would silently misread. Cost: O(file size).
#include "mesh/format_check.h"

#include "base/error.h"
#include "mesh/text_scan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

namespace rtlab::detail {

using namespace mesh_text;

namespace {
/// A finite number or an Error naming where it was expected.
double finite_number(std::string_view t, const std::string& what, const std::string& where) {
    const std::optional<double> v = parse_double(t);
    if (!v) {
        fail(what, where + ": '" + std::string(t) + "' is not a number");
    }
    if (!std::isfinite(*v)) {
        fail(what, where + ": non-finite coordinate '" + std::string(t.substr(0, 32)) + "'");
    }
    if (std::abs(*v) > double(std::numeric_limits<float>::max())) {
        fail(what, where + ": coordinate '" + std::string(t.substr(0, 32)) +
                       "' is outside the float range (|v| > 3.4e38)");
    }
    return *v;
}

void reject_binary_text(std::string_view bytes, const std::string& what, std::string_view fmt) {
    if (bytes.find('\0') != std::string_view::npos) {
        fail(what, "contains binary data; not a text " + std::string(fmt) + " file");
    }
}

// ---- OBJ ----------------------------------------------------------------------------------------

bool known_obj_statement(std::string_view k) {
    static constexpr std::array<std::string_view, 32> known{
        "v",    "vt",    "vn",     "vp",     "f",        "l",        "p",    "g",
        "o",    "s",     "usemtl", "mtllib", "cstype",   "deg",      "bmat", "step",
        "curv", "curv2", "surf",   "parm",   "trim",     "hole",     "scrv", "sp",
        "end",  "con",   "mg",     "bevel",  "c_interp", "d_interp", "lod",  "maplib"};
    for (std::string_view s : known) {
        if (s == k) {
            return true;
        }
    }
    return false;
}

DeclaredCounts check_obj(std::string_view bytes, const std::string& what) {
    reject_binary_text(bytes, what, "OBJ");
    DeclaredCounts c;
    LineReader lines(bytes);
    std::string_view line;
    while (lines.next(line)) {
        const std::size_t hash = line.find('#');
        const std::vector<std::string_view> tok = tokens_of(line.substr(0, hash));
        if (tok.empty()) {
            continue;
        }
        const std::string where = line_at(lines.number());
        if (!known_obj_statement(tok[0])) {
            fail(what,
                 where + ": unknown OBJ statement '" + std::string(tok[0].substr(0, 32)) + "'");
        }
        if (tok[0] == "mtllib" || tok[0] == "usemtl") {
            c.ignored_materials = true;
        }
        if (tok[0] == "v") {
            if (tok.size() < 4) {
                fail(what, where + ": vertex needs 3 coordinates");
            }
            for (std::size_t i = 1; i < tok.size(); ++i) {
                finite_number(tok[i], what, where);
            }
            ++c.vertices;
        } else if (tok[0] == "f") {
            if (tok.size() < 4) {
                fail(what, where + ": face has " + std::to_string(tok.size() - 1) +
                               " vertices, needs at least 3");
            }
            std::vector<std::int64_t> seen;
            for (std::size_t i = 1; i < tok.size(); ++i) {
                const std::string_view ref = tok[i].substr(0, tok[i].find('/'));
                const std::optional<std::int64_t> idx = parse_int(ref);
                if (!idx || *idx == 0) {
                    fail(what, where + ": bad face vertex '" + std::string(tok[i]) + "'");
                }
                const auto n = static_cast<std::int64_t>(c.vertices);
                const std::int64_t resolved = *idx > 0 ? *idx : n + *idx + 1;
                if (resolved < 1 || resolved > n) {
                    fail(what, where + ": face vertex index " + std::string(ref) +
                                   " out of range (" + std::to_string(n) + " vertices so far)");
                }
                // OpenMesh's OBJ reader silently removes repeated corners (changing the fan) and
                // drops faces left with fewer than 3, so such faces are rejected here.
                if (std::find(seen.begin(), seen.end(), resolved) != seen.end()) {
                    fail(what, where + ": face repeats vertex " + std::to_string(resolved) +
                                   " (unsupported in OBJ; clean the mesh or use PLY/OFF)");
                }
                seen.push_back(resolved);
            }
            ++c.faces;
        }
    }
    return c;
}

// ---- OFF ----------------------------------------------------------------------------------------

/// The tokens of each next non-empty line (none at the end of the file), with its line number.
class TokenLines {
public:
    explicit TokenLines(std::string_view bytes) : lines_(bytes) {}
    std::vector<std::string_view> next() {
        std::string_view line;
        while (lines_.next(line)) {
            std::vector<std::string_view> tok = tokens_of(line);
            if (!tok.empty()) {
                return tok;
            }
        }
        return {};
    }
    std::size_t number() const { return lines_.number(); }

private:
    LineReader lines_;
};

/// The first line of an OFF file (tokens tok, at line `line`): plain 3-D ASCII "OFF" alone.
void check_off_magic(const std::vector<std::string_view>& tok,
                     std::size_t line,
                     const std::string& what) {
    if (tok.empty()) {
        fail(what, "empty file");
    }
    const std::string_view magic = tok[0];
    if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF") {
        fail(what, "not an OFF file (no OFF header)");
    }
    if (magic.find('4') != std::string_view::npos || magic.find('n') != std::string_view::npos) {
        fail(what, "only 3-D OFF is supported, not '" + std::string(magic) + "'");
    }
    // OpenMesh 9's OFF reader reads per-vertex attributes (COFF, NOFF, STOFF) through kernel
    // properties our importer does not have, and returned garbage counts nondeterministically in
    // our tests: accept plain OFF only.
    if (magic != "OFF") {
        fail(what, "only plain OFF is supported, not '" + std::string(magic) +
                       "' (vertex colours, normals and texture coordinates are not read)");
    }
    if (tok.size() > 1 && tok[1] == "BINARY") {
        fail(what, "binary OFF is not supported");
    }
    // OpenMesh reads the counts from the line after "OFF" and ignores the rest of the first line,
    // so counts there would be read from the wrong place (found by fuzzing:
    // tests/fuzz_regressions/off-counts-on-header-line.off, an endless read).
    if (tok.size() > 1) {
        fail(what, "line " + std::to_string(line) +
                       ": text after 'OFF' (the counts must be on their own line)");
    }
}

/// The vertex and face counts of an OFF file's second line (tokens tok).
DeclaredCounts off_counts(const std::vector<std::string_view>& tok, const std::string& what) {
    if (tok.size() < 2) {
        fail(what, "header needs vertex and face counts");
    }
    const std::optional<std::int64_t> nv = parse_int(tok[0]);
    const std::optional<std::int64_t> nf = parse_int(tok[1]);
    if (!nv || !nf || *nv < 0 || *nf < 0 || static_cast<std::uint64_t>(*nv) > max_count ||
        static_cast<std::uint64_t>(*nf) > max_count) {
        fail(what, "bad counts in header");
    }
    return {static_cast<std::size_t>(*nv), static_cast<std::size_t>(*nf), true};
}

/// One OFF face line (tokens tok, at `where`): a count of at least 3, then that many indices
/// below `vertices`.
void check_off_face(const std::vector<std::string_view>& tok,
                    const std::string& where,
                    std::size_t vertices,
                    const std::string& what) {
    const std::optional<std::int64_t> n = parse_int(tok[0]);
    if (!n || *n < 3) {
        fail(what, where + ": face needs a vertex count of at least 3");
    }
    if (tok.size() < static_cast<std::size_t>(*n) + 1) {
        fail(what, where + ": face lists fewer than " + std::to_string(*n) + " vertices");
    }
    for (std::size_t k = 1; k <= static_cast<std::size_t>(*n); ++k) {
        const std::optional<std::int64_t> idx = parse_int(tok[k]);
        if (!idx || *idx < 0 || static_cast<std::size_t>(*idx) >= vertices) {
            fail(what, where + ": face vertex index '" + std::string(tok[k]) + "' out of range (" +
                           std::to_string(vertices) + " vertices)");
        }
    }
}

DeclaredCounts check_off(std::string_view bytes, const std::string& what) {
    reject_binary_text(bytes, what, "OFF");
    // OpenMesh's OFF reader misreads comment lines (it returns an empty or garbled mesh).
    if (bytes.find('#') != std::string_view::npos) {
        fail(what, "comments ('#') in OFF files are not supported");
    }
    TokenLines lines(bytes);
    std::vector<std::string_view> tok = lines.next();
    check_off_magic(tok, lines.number(), what);
    const DeclaredCounts c = off_counts(lines.next(), what);
    for (std::size_t i = 0; i < c.vertices; ++i) {
        tok = lines.next();
        if (tok.empty()) {
            fail(what, "truncated: file ends after " + std::to_string(i) + " of " +
                           std::to_string(c.vertices) + " vertices");
        }
        const std::string where = line_at(lines.number());
        if (tok.size() < 3) {
            fail(what, where + ": vertex needs 3 coordinates");
        }
        for (const std::string_view t : tok) {
            finite_number(t, what, where);
        }
    }
    for (std::size_t i = 0; i < c.faces; ++i) {
        tok = lines.next();
        if (tok.empty()) {
            fail(what, "truncated: file ends after " + std::to_string(i) + " of " +
                           std::to_string(c.faces) + " faces");
        }
        check_off_face(tok, line_at(lines.number()), c.vertices, what);
    }
    return c;
}

// ---- STL ----------------------------------------------------------------------------------------

DeclaredCounts check_stl(std::string_view bytes, const std::string& what) {
    DeclaredCounts c;
    c.vertices_known = false;
    // OpenMesh takes a file as binary exactly when its size is 84 + 50 * (count at byte 80).
    if (bytes.size() >= 84) {
        const auto* u = reinterpret_cast<const unsigned char*>(bytes.data() + 80);
        const std::uint32_t n = u[0] | (std::uint32_t{u[1]} << 8) | (std::uint32_t{u[2]} << 16) |
                                (std::uint32_t{u[3]} << 24);
        if (bytes.size() == 84 + 50 * static_cast<std::uint64_t>(n)) {
            for (std::uint32_t i = 0; i < n; ++i) {
                for (std::size_t k = 0; k < 9; ++k) {
                    float v;
                    std::memcpy(&v, bytes.data() + 84 + 50 * std::size_t{i} + 12 + 4 * k, 4);
                    if (!std::isfinite(v)) {
                        fail(what, "triangle " + std::to_string(i) + ": non-finite coordinate");
                    }
                }
            }
            c.faces = n;
            return c;
        }
    }
    const std::size_t first = bytes.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos || bytes.substr(first, 5) != "solid" ||
        bytes.find('\0') != std::string_view::npos) {
        fail(what, bytes.size() >= 84 ? "not an STL file (binary size does not match its "
                                        "triangle count, and no ASCII 'solid' header)"
                                      : "not an STL file (too short for binary, no 'solid')");
    }
    LineReader lines(bytes);
    std::string_view line;
    std::size_t corners = 0;
    bool ended = false;
    bool first_line = true;
    while (lines.next(line)) {
        const std::vector<std::string_view> tok = tokens_of(line);
        if (tok.empty() || first_line) {
            first_line = first_line && tok.empty();
            continue;
        }
        const std::string where = line_at(lines.number());
        if (tok[0] == "vertex") {
            if (tok.size() != 4) {
                fail(what, where + ": vertex needs 3 coordinates");
            }
            for (std::size_t i = 1; i < 4; ++i) {
                finite_number(tok[i], what, where);
            }
            ++corners;
        } else if (tok[0] == "facet") {
            if (corners % 3 != 0) {
                fail(what, where + ": previous facet does not have 3 vertices");
            }
        } else if (tok[0] == "endsolid") {
            ended = true;
            break;
        } else if (tok[0] != "outer" && tok[0] != "endloop" && tok[0] != "endfacet") {
            fail(what, where + ": unexpected '" + std::string(tok[0].substr(0, 32)) + "'");
        }
    }
    if (!ended) {
        fail(what, "truncated ASCII STL: no 'endsolid'");
    }
    if (corners % 3 != 0) {
        fail(what, "last facet does not have 3 vertices");
    }
    c.faces = corners / 3;
    return c;
}

}  // namespace

DeclaredCounts check_mesh_bytes(std::string_view bytes, MeshFormat f, const std::string& what) {
    switch (f) {
    case MeshFormat::obj:
        return check_obj(bytes, what);
    case MeshFormat::ply:
        return check_ply(bytes, what);
    case MeshFormat::off:
        return check_off(bytes, what);
    case MeshFormat::stl:
        return check_stl(bytes, what);
    }
    fail(what, "unknown mesh format");
}

}  // namespace rtlab::detail
