// The PLY part of mesh/format_check: header, declared elements and every value of the body (ASCII
// and binary of either byte order), checked before OpenMesh reads the file. Cost: O(file size).
#include "mesh/format_check.h"
#include "mesh/text_scan.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

namespace rtlab::detail {

using namespace mesh_text;

namespace {

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

/// A PLY header: its format and elements, and where the body starts (byte offset, line number).
struct PlyHeader {
    PlyFormat format = PlyFormat::ascii;
    std::vector<PlyElement> elements;
    std::size_t body_offset = 0;
    std::size_t body_line = 0;  ///< number of the header's last line
};

/// One `property` line of the header (tokens tok, at `where`).
PlyProperty ply_property(const std::vector<std::string_view>& tok,
                         const std::string& what,
                         const std::string& where) {
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
    return p;
}

/// The format of a `format` line (tokens tok, three of them, at `where`).
PlyFormat ply_format(const std::vector<std::string_view>& tok,
                     const std::string& what,
                     const std::string& where) {
    PlyFormat f = PlyFormat::ascii;
    if (tok[1] == "binary_little_endian") {
        f = PlyFormat::binary_le;
    } else if (tok[1] == "binary_big_endian") {
        f = PlyFormat::binary_be;
    } else if (tok[1] != "ascii") {
        fail(what, where + ": unknown format '" + std::string(tok[1].substr(0, 32)) + "'");
    }
    // OpenMesh's reader logs other versions, and its log stream can deadlock on that (found by
    // fuzzing: tests/fuzz_regressions/ply-version.ply).
    if (tok[2] != "1.0") {
        fail(what, where + ": unsupported PLY version '" + std::string(tok[2].substr(0, 32)) +
                       "' (expected 1.0)");
    }
    return f;
}

/// The header of `bytes`, from the `ply` line through `end_header`.
PlyHeader read_ply_header(std::string_view bytes, const std::string& what) {
    LineReader lines(bytes);
    std::string_view line;
    if (!lines.next(line) || tokens_of(line) != std::vector<std::string_view>{"ply"}) {
        fail(what, "not a PLY file (first line is not 'ply')");
    }
    PlyHeader h;
    bool has_format = false;
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
            h.format = ply_format(tok, what, where);
            has_format = true;
        } else if (tok[0] == "element") {
            const std::optional<std::int64_t> n = parse_int(tok[2]);
            if (!n || *n < 0 || static_cast<std::uint64_t>(*n) > max_count) {
                fail(what, where + ": bad element count '" + std::string(tok[2]) + "'");
            }
            h.elements.push_back({std::string(tok[1]), static_cast<std::uint64_t>(*n), {}});
        } else if (tok[0] == "property" && !h.elements.empty()) {
            h.elements.back().props.push_back(ply_property(tok, what, where));
        } else {
            fail(what, where + ": unexpected '" + std::string(tok[0].substr(0, 32)) + "'");
        }
    }
    if (!ended) {
        fail(what, "PLY header has no end_header");
    }
    if (!has_format) {
        fail(what, "PLY header has no format line");
    }
    h.body_offset = lines.offset();
    h.body_line = lines.number();
    return h;
}

/// The vertex element of h (which must have scalar x, y and z), and the declared counts.
const PlyElement& ply_vertex_element(const PlyHeader& h,
                                     const std::string& what,
                                     DeclaredCounts& c) {
    const PlyElement* vertex = nullptr;
    for (const PlyElement& e : h.elements) {
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
    return *vertex;
}

/// The values of a PLY body in file order: binary scalars by byte offset, or ASCII tokens line by
/// line; each read fails with the element and item named when the file ends.
class PlyBody {
public:
    PlyBody(const PlyHeader& h, std::string_view bytes, const std::string& what)
        : body_(bytes.substr(h.body_offset))
        , lines_(body_)
        , what_(what)
        , header_(h)
        , binary_(h.format != PlyFormat::ascii)
        , big_(h.format == PlyFormat::binary_be) {}

    double next(const PlyProperty& t, const PlyElement& e, std::uint64_t item) {
        // Messages are built only on failure: this runs once per value of the file.
        const auto where = [&] { return "element '" + e.name + "' item " + std::to_string(item); };
        if (binary_) {
            if (pos_ + static_cast<std::size_t>(t.size) > body_.size()) {
                fail(what_, "truncated: " + where() + " runs past the end of the file");
            }
            const double v =
                read_scalar(reinterpret_cast<const unsigned char*>(body_.data() + pos_), t, big_);
            pos_ += static_cast<std::size_t>(t.size);
            return v;
        }
        const std::string_view tk = next_token();
        if (tk.empty()) {
            fail(what_, "truncated: " + where() + " runs past the end of the file");
        }
        const std::optional<double> v = parse_double(tk);
        if (!v) {
            fail(what_, where() + ": '" + std::string(tk.substr(0, 32)) + "' is not a number");
        }
        return *v;
    }

    /// Data after the declared elements means the header's counts are wrong (or two files were
    /// concatenated): rejected, except trailing whitespace (a final newline after binary data).
    void check_end() {
        if (binary_) {
            const std::size_t extra = body_.find_first_not_of(" \t\r\n", pos_);
            if (extra != std::string_view::npos) {
                fail(what_, std::to_string(body_.size() - pos_) +
                                " bytes of trailing data after the declared elements (byte " +
                                std::to_string(header_.body_offset + pos_) + ")");
            }
        } else if (pending_at_ < pending_.size() || !next_token().empty()) {
            fail(what_, "trailing data after the declared elements (line " +
                            std::to_string(header_.body_line + lines_.number()) + ")");
        }
    }

private:
    /// ASCII: the next token, or an empty view at the end.
    std::string_view next_token() {
        std::string_view line;
        while (pending_at_ >= pending_.size()) {
            if (!lines_.next(line)) {
                return {};
            }
            pending_ = tokens_of(line);
            pending_at_ = 0;
        }
        return pending_[pending_at_++];
    }

    std::string_view body_;
    LineReader lines_;
    const std::string& what_;
    const PlyHeader& header_;
    bool binary_;
    bool big_;
    std::size_t pos_ = 0;                    ///< binary: byte offset in the body
    std::vector<std::string_view> pending_;  ///< ASCII: tokens of the current line
    std::size_t pending_at_ = 0;
};

/// One list property of item `item` of e: its length, then its values (face vertex indices
/// checked against the vertex count).
void check_ply_list(PlyBody& body,
                    const PlyProperty& p,
                    const PlyElement& e,
                    std::uint64_t item,
                    const DeclaredCounts& c,
                    const std::string& what) {
    PlyProperty count_type;
    count_type.size = p.count_size;
    const double n = body.next(count_type, e, item);
    if (!(n >= 0) || n != std::floor(n) || n > double(max_count)) {
        fail(what, "element '" + e.name + "' item " + std::to_string(item) + ": bad list length");
    }
    const bool indices =
        e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index");
    if (indices && n < 3) {
        fail(what, "face " + std::to_string(item) + " has " + std::to_string(static_cast<int>(n)) +
                       " vertices, needs at least 3");
    }
    for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(n); ++k) {
        const double v = body.next(p, e, item);
        if (indices && !(v >= 0 && v < static_cast<double>(c.vertices))) {
            fail(what, "face " + std::to_string(item) + ": vertex index " +
                           std::to_string(static_cast<long long>(v)) + " out of range (" +
                           std::to_string(c.vertices) + " vertices)");
        }
    }
}

}  // namespace

DeclaredCounts check_ply(std::string_view bytes, const std::string& what) {
    const PlyHeader h = read_ply_header(bytes, what);
    DeclaredCounts c;
    const PlyElement& vertex = ply_vertex_element(h, what, c);
    PlyBody body(h, bytes, what);
    for (const PlyElement& e : h.elements) {
        for (std::uint64_t item = 0; item < e.count; ++item) {
            for (const PlyProperty& p : e.props) {
                if (p.is_list) {
                    check_ply_list(body, p, e, item, c, what);
                    continue;
                }
                const double v = body.next(p, e, item);
                if (&e == &vertex && !std::isfinite(v)) {
                    fail(what, "vertex " + std::to_string(item) + ": non-finite " + p.name);
                }
                if (&e == &vertex && std::abs(v) > double(std::numeric_limits<float>::max())) {
                    fail(what, "vertex " + std::to_string(item) + ": " + p.name +
                                   " is outside the float range (|v| > 3.4e38)");
                }
            }
        }
    }
    body.check_end();
    return c;
}

}  // namespace rtlab::detail
