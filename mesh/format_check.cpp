// Walks OBJ, PLY (ASCII and binary), OFF and STL (ASCII and binary) bytes and rejects what
// OpenMesh would silently misread. Cost: O(file size).
#include "mesh/format_check.h"

#include "base/error.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

namespace rtlab::detail {

namespace {

/// Largest element count we accept: ids are 32-bit and a count this size is a corrupt header.
constexpr std::uint64_t max_count = 0x7fffffffu;

[[noreturn]] void fail(const std::string& what, const std::string& problem) {
    throw Error(what + ": " + problem);
}

bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/// Splits a line into whitespace-separated tokens.
std::vector<std::string_view> tokens_of(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) {
            ++i;
        }
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i])) {
            ++i;
        }
        if (i > start) {
            out.push_back(line.substr(start, i - start));
        }
    }
    return out;
}

/// Iterates lines (without the terminator), counting them from 1.
class LineReader {
public:
    explicit LineReader(std::string_view s) : s_(s) {}
    bool next(std::string_view& line) {
        if (pos_ >= s_.size()) {
            return false;
        }
        const std::size_t end = std::min(s_.find('\n', pos_), s_.size());
        line = s_.substr(pos_, end - pos_);
        pos_ = end + 1;
        ++number_;
        return true;
    }
    std::size_t number() const { return number_; }
    std::size_t offset() const { return std::min(pos_, s_.size()); }

private:
    std::string_view s_;
    std::size_t pos_ = 0;
    std::size_t number_ = 0;
};

std::optional<double> parse_double(std::string_view t) {
    double v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size()) {
        return std::nullopt;
    }
    return v;
}

std::optional<std::int64_t> parse_int(std::string_view t) {
    if (!t.empty() && t.front() == '+') {
        t.remove_prefix(1);
    }
    std::int64_t v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size()) {
        return std::nullopt;
    }
    return v;
}

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

std::string line_at(std::size_t n) {
    return "line " + std::to_string(n);
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

DeclaredCounts check_off(std::string_view bytes, const std::string& what) {
    reject_binary_text(bytes, what, "OFF");
    // OpenMesh's OFF reader misreads comment lines (it returns an empty or garbled mesh).
    if (bytes.find('#') != std::string_view::npos) {
        fail(what, "comments ('#') in OFF files are not supported");
    }
    LineReader lines(bytes);
    std::string_view line;
    // Next non-empty, non-comment line as tokens; empty at end of file.
    auto next_tokens = [&]() {
        while (lines.next(line)) {
            std::vector<std::string_view> tok = tokens_of(line);
            if (!tok.empty()) {
                return tok;
            }
        }
        return std::vector<std::string_view>{};
    };
    std::vector<std::string_view> tok = next_tokens();
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
        fail(what, "line " + std::to_string(lines.number()) +
                       ": text after 'OFF' (the counts must be on their own line)");
    }
    tok = next_tokens();
    if (tok.size() < 2) {
        fail(what, "header needs vertex and face counts");
    }
    const std::optional<std::int64_t> nv = parse_int(tok[0]);
    const std::optional<std::int64_t> nf = parse_int(tok[1]);
    if (!nv || !nf || *nv < 0 || *nf < 0 || static_cast<std::uint64_t>(*nv) > max_count ||
        static_cast<std::uint64_t>(*nf) > max_count) {
        fail(what, "bad counts in header");
    }
    DeclaredCounts c{static_cast<std::size_t>(*nv), static_cast<std::size_t>(*nf), true};
    for (std::size_t i = 0; i < c.vertices; ++i) {
        tok = next_tokens();
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
        tok = next_tokens();
        if (tok.empty()) {
            fail(what, "truncated: file ends after " + std::to_string(i) + " of " +
                           std::to_string(c.faces) + " faces");
        }
        const std::string where = line_at(lines.number());
        const std::optional<std::int64_t> n = parse_int(tok[0]);
        if (!n || *n < 3) {
            fail(what, where + ": face needs a vertex count of at least 3");
        }
        if (tok.size() < static_cast<std::size_t>(*n) + 1) {
            fail(what, where + ": face lists fewer than " + std::to_string(*n) + " vertices");
        }
        for (std::size_t k = 1; k <= static_cast<std::size_t>(*n); ++k) {
            const std::optional<std::int64_t> idx = parse_int(tok[k]);
            if (!idx || *idx < 0 || static_cast<std::size_t>(*idx) >= c.vertices) {
                fail(what, where + ": face vertex index '" + std::string(tok[k]) +
                               "' out of range (" + std::to_string(c.vertices) + " vertices)");
            }
        }
    }
    return c;
}

// ---- PLY ----------------------------------------------------------------------------------------

enum class PlyFormat { ascii, binary_le, binary_be };

struct PlyProperty {
    std::string name;
    int size = 0;           ///< scalar size, or the list's item size
    bool is_float = false;  ///< scalar (or item) type is float/double
    bool is_signed = false;
    bool is_list = false;
    int count_size = 0;  ///< list: size of the count
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> props;
};

/// Size, float-ness and signedness of a PLY scalar type name; size 0 when unknown.
PlyProperty ply_type(std::string_view t) {
    PlyProperty p;
    if (t == "char" || t == "int8") {
        p.size = 1, p.is_signed = true;
    } else if (t == "uchar" || t == "uint8") {
        p.size = 1;
    } else if (t == "short" || t == "int16") {
        p.size = 2, p.is_signed = true;
    } else if (t == "ushort" || t == "uint16") {
        p.size = 2;
    } else if (t == "int" || t == "int32") {
        p.size = 4, p.is_signed = true;
    } else if (t == "uint" || t == "uint32") {
        p.size = 4;
    } else if (t == "float" || t == "float32") {
        p.size = 4, p.is_float = true, p.is_signed = true;
    } else if (t == "double" || t == "float64") {
        p.size = 8, p.is_float = true, p.is_signed = true;
    }
    return p;
}

/// Reads one binary scalar as double (integers exactly up to 2^53).
double read_scalar(const unsigned char* p, const PlyProperty& t, bool big_endian) {
    std::array<unsigned char, 8> b{};
    // Sizes are 1, 2, 4 or 8 (ply_type); the clamp makes that evident to the optimiser.
    const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(t.size), b.size());
    std::memcpy(b.data(), p, n);
    if (big_endian != (std::endian::native == std::endian::big)) {
        for (std::size_t i = 0; i < n / 2; ++i) {
            std::swap(b[i], b[n - 1 - i]);
        }
    }
    if (t.is_float) {
        if (t.size == 4) {
            float f;
            std::memcpy(&f, b.data(), 4);
            return static_cast<double>(f);
        }
        double d;
        std::memcpy(&d, b.data(), 8);
        return d;
    }
    std::uint64_t u = 0;
    std::memcpy(&u, b.data(), n);  // little-endian host layout
    if (t.is_signed) {
        const int shift = 64 - 8 * t.size;
        return static_cast<double>(static_cast<std::int64_t>(u << shift) >> shift);
    }
    return static_cast<double>(u);
}

DeclaredCounts check_ply(std::string_view bytes, const std::string& what) {
    LineReader lines(bytes);
    std::string_view line;
    if (!lines.next(line) || tokens_of(line) != std::vector<std::string_view>{"ply"}) {
        fail(what, "not a PLY file (first line is not 'ply')");
    }
    std::optional<PlyFormat> format;
    std::vector<PlyElement> elements;
    bool ended = false;
    while (!ended && lines.next(line)) {
        const std::vector<std::string_view> tok = tokens_of(line);
        const std::string where = "header " + line_at(lines.number());
        if (tok.empty() || tok[0] == "comment" || tok[0] == "obj_info") {
            continue;
        }
        if (tok[0] == "end_header") {
            ended = true;
        } else if ((tok[0] == "format" || tok[0] == "element") && tok.size() != 3) {
            fail(what, where + ": malformed '" + std::string(tok[0]) + "' line");
        } else if (tok[0] == "format") {
            if (tok[1] == "ascii") {
                format = PlyFormat::ascii;
            } else if (tok[1] == "binary_little_endian") {
                format = PlyFormat::binary_le;
            } else if (tok[1] == "binary_big_endian") {
                format = PlyFormat::binary_be;
            } else {
                fail(what, where + ": unknown format '" + std::string(tok[1].substr(0, 32)) + "'");
            }
            // OpenMesh's reader logs other versions, and its log stream can deadlock on that
            // (found by fuzzing: tests/fuzz_regressions/ply-version.ply).
            if (tok[2] != "1.0") {
                fail(what, where + ": unsupported PLY version '" +
                               std::string(tok[2].substr(0, 32)) + "' (expected 1.0)");
            }
        } else if (tok[0] == "element") {
            const std::optional<std::int64_t> n = parse_int(tok[2]);
            if (!n || *n < 0 || static_cast<std::uint64_t>(*n) > max_count) {
                fail(what, where + ": bad element count '" + std::string(tok[2]) + "'");
            }
            elements.push_back({std::string(tok[1]), static_cast<std::uint64_t>(*n), {}});
        } else if (tok[0] == "property" && !elements.empty()) {
            PlyProperty p;
            if (tok.size() == 5 && tok[1] == "list") {
                const PlyProperty ct = ply_type(tok[2]);
                p = ply_type(tok[3]);
                if (ct.size == 0 || ct.is_float || p.size == 0) {
                    fail(what, where + ": bad list property types");
                }
                p.is_list = true;
                p.count_size = ct.size;
                p.name = std::string(tok[4]);
            } else if (tok.size() == 3) {
                p = ply_type(tok[1]);
                if (p.size == 0) {
                    fail(what, where + ": unknown property type '" + std::string(tok[1]) + "'");
                }
                p.name = std::string(tok[2]);
            } else {
                fail(what, where + ": malformed property");
            }
            elements.back().props.push_back(p);
        } else {
            fail(what, where + ": unexpected '" + std::string(tok[0].substr(0, 32)) + "'");
        }
    }
    if (!ended) {
        fail(what, "PLY header has no end_header");
    }
    if (!format) {
        fail(what, "PLY header has no format line");
    }
    DeclaredCounts c;
    const PlyElement* vertex = nullptr;
    for (const PlyElement& e : elements) {
        if (e.name == "vertex") {
            vertex = &e;
            c.vertices = e.count;
        } else if (e.name == "face") {
            c.faces = e.count;
        }
    }
    if (vertex == nullptr) {
        fail(what, "PLY has no vertex element");
    }
    for (const char* axis : {"x", "y", "z"}) {
        bool found = false;
        for (const PlyProperty& p : vertex->props) {
            found = found || (p.name == axis && !p.is_list);
        }
        if (!found) {
            fail(what, std::string("PLY vertex element has no scalar property '") + axis + "'");
        }
    }

    const std::string_view body = bytes.substr(lines.offset());
    const bool binary = *format != PlyFormat::ascii;
    const bool big = *format == PlyFormat::binary_be;
    std::size_t pos = 0;  // binary: byte offset; ascii: token cursor below
    LineReader body_lines(body);
    std::vector<std::string_view> pending;
    std::size_t pending_at = 0;
    // ASCII: next token of the body, or an empty view at the end.
    auto next_token = [&]() -> std::string_view {
        while (pending_at >= pending.size()) {
            if (!body_lines.next(line)) {
                return {};
            }
            pending = tokens_of(line);
            pending_at = 0;
        }
        return pending[pending_at++];
    };
    // Next value of type t; fails with the element/item named when the file ends.
    auto next_value = [&](const PlyProperty& t, const PlyElement& e, std::uint64_t item) {
        // Messages are built only on failure: this runs once per value of the file.
        const auto where = [&] { return "element '" + e.name + "' item " + std::to_string(item); };
        if (binary) {
            if (pos + static_cast<std::size_t>(t.size) > body.size()) {
                fail(what, "truncated: " + where() + " runs past the end of the file");
            }
            const double v =
                read_scalar(reinterpret_cast<const unsigned char*>(body.data() + pos), t, big);
            pos += static_cast<std::size_t>(t.size);
            return v;
        }
        const std::string_view tk = next_token();
        if (tk.empty()) {
            fail(what, "truncated: " + where() + " runs past the end of the file");
        }
        const std::optional<double> v = parse_double(tk);
        if (!v) {
            fail(what, where() + ": '" + std::string(tk.substr(0, 32)) + "' is not a number");
        }
        return *v;
    };
    for (const PlyElement& e : elements) {
        const bool is_vertex = &e == vertex;
        const bool is_face = e.name == "face";
        for (std::uint64_t item = 0; item < e.count; ++item) {
            for (const PlyProperty& p : e.props) {
                if (!p.is_list) {
                    const double v = next_value(p, e, item);
                    if (is_vertex && !std::isfinite(v)) {
                        fail(what, "vertex " + std::to_string(item) + ": non-finite " + p.name);
                    }
                    if (is_vertex && std::abs(v) > double(std::numeric_limits<float>::max())) {
                        fail(what, "vertex " + std::to_string(item) + ": " + p.name +
                                       " is outside the float range (|v| > 3.4e38)");
                    }
                    continue;
                }
                PlyProperty count_type;
                count_type.size = p.count_size;
                const double n = next_value(count_type, e, item);
                if (!(n >= 0) || n != std::floor(n) || n > double(max_count)) {
                    fail(what, "element '" + e.name + "' item " + std::to_string(item) +
                                   ": bad list length");
                }
                const bool indices =
                    is_face && (p.name == "vertex_indices" || p.name == "vertex_index");
                if (indices && n < 3) {
                    fail(what, "face " + std::to_string(item) + " has " +
                                   std::to_string(static_cast<int>(n)) +
                                   " vertices, needs at least 3");
                }
                for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(n); ++k) {
                    const double v = next_value(p, e, item);
                    if (indices && !(v >= 0 && v < static_cast<double>(c.vertices))) {
                        fail(what, "face " + std::to_string(item) + ": vertex index " +
                                       std::to_string(static_cast<long long>(v)) +
                                       " out of range (" + std::to_string(c.vertices) +
                                       " vertices)");
                    }
                }
            }
        }
    }
    // Data after the declared elements means the header's counts are wrong (or two files were
    // concatenated): rejected, except trailing whitespace (a final newline after binary data).
    if (binary) {
        const std::size_t extra = body.find_first_not_of(" \t\r\n", pos);
        if (extra != std::string_view::npos) {
            fail(what, std::to_string(body.size() - pos) +
                           " bytes of trailing data after the declared elements (byte " +
                           std::to_string(lines.offset() + pos) + ")");
        }
    } else if (pending_at < pending.size() || !next_token().empty()) {
        fail(what, "trailing data after the declared elements (line " +
                       std::to_string(lines.number() + body_lines.number()) + ")");
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
