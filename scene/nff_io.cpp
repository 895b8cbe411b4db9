// NFF reading and writing (the format of Haines' SPD, "NFF - Neutral File Format", 1987).
#include "scene/nff_io.h"

#include "base/atomic_file.h"
#include "base/error.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <sstream>

namespace rtlab::nff {

namespace {

// Concatenates strings by appending (GCC 12 at -O3 warns falsely on "literal" + std::string).
template <class... A>
std::string cat(const A&... a) {
    std::string out;
    (out.append(a), ...);
    return out;
}

struct Token {
    std::string text;
    std::size_t line = 0;
};

// Splits text into whitespace-separated tokens with their line numbers; `#` comments a line out.
std::vector<Token> tokenize(std::string_view text) {
    std::vector<Token> out;
    std::size_t line = 1;
    std::size_t i = 0;
    bool line_start = true;
    while (i < text.size()) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            ++i;
            line_start = true;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r') {
            ++i;
            continue;
        }
        if (c == '#' && line_start) {
            while (i < text.size() && text[i] != '\n') {
                ++i;
            }
            continue;
        }
        line_start = false;
        const std::size_t b = i;
        while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\r' &&
               text[i] != '\n') {
            ++i;
        }
        out.push_back({std::string(text.substr(b, i - b)), line});
    }
    return out;
}

class Reader {
public:
    Reader(std::vector<Token> t, std::string_view what) : tokens_(std::move(t)), what_(what) {}

    bool done() const { return pos_ >= tokens_.size(); }
    const Token& peek() const { return tokens_[pos_]; }

    [[noreturn]] void fail(std::size_t line, const std::string& problem) const {
        throw Error(cat(what_, ":", std::to_string(line), ": ", problem));
    }
    std::size_t line() const {
        return done() ? (tokens_.empty() ? 1 : tokens_.back().line) : tokens_[pos_].line;
    }
    const Token& next(std::string_view expected) {
        if (done()) {
            fail(line(), cat("unexpected end of file, expected ", expected));
        }
        return tokens_[pos_++];
    }
    void keyword(std::string_view k) {
        const Token& t = next(k);
        if (t.text != k) {
            fail(t.line, cat("expected '", k, "', found '", t.text, "'"));
        }
    }
    double number(std::string_view expected) {
        const Token& t = next(expected);
        errno = 0;
        char* end = nullptr;
        const double v = std::strtod(t.text.c_str(), &end);
        if (end != t.text.c_str() + t.text.size() || t.text.empty() || !std::isfinite(v)) {
            fail(t.line, cat("expected a number (", expected, "), found '", t.text, "'"));
        }
        if (std::abs(v) > double(std::numeric_limits<float>::max())) {  // scenes are float
            fail(t.line, cat("number '", t.text, "' (", expected, ") is outside the float range"));
        }
        return v;
    }
    int integer(std::string_view expected, int lo, int hi) {
        const std::size_t l = line();
        const double v = number(expected);
        if (v != std::floor(v) || v < lo || v > hi) {
            fail(l, cat(expected, " must be an integer in [", std::to_string(lo), ", ",
                        std::to_string(hi), "]"));
        }
        return static_cast<int>(v);
    }
    Vec3d vec(std::string_view expected) {
        const double x = number(expected);
        const double y = number(expected);
        const double z = number(expected);
        return {x, y, z};
    }
    // True when the next token is on `line` (optional trailing fields of a record).
    bool more_on(std::size_t l) const { return !done() && tokens_[pos_].line == l; }

private:
    std::vector<Token> tokens_;
    std::size_t pos_ = 0;
    std::string what_;
};

View read_view(Reader& r) {
    View v;
    r.keyword("from");
    v.from = r.vec("from x y z");
    r.keyword("at");
    v.at = r.vec("at x y z");
    r.keyword("up");
    v.up = r.vec("up x y z");
    r.keyword("angle");
    const std::size_t al = r.line();
    v.angle = r.number("angle");
    if (!(v.angle > 0 && v.angle < 180)) {
        r.fail(al, "angle must be in (0, 180) degrees");
    }
    r.keyword("hither");
    v.hither = r.number("hither");
    r.keyword("resolution");
    v.width = r.integer("resolution width", 1, 16384);
    v.height = r.integer("resolution height", 1, 16384);
    return v;
}

Polygon read_polygon(Reader& r, bool patch, std::size_t line) {
    Polygon p;
    const int n = r.integer(patch ? "pp vertex count" : "p vertex count", 3, 1 << 20);
    (void)line;
    for (int i = 0; i < n; ++i) {
        p.vertices.push_back(r.vec("vertex x y z"));
        if (patch) {
            p.normals.push_back(r.vec("normal x y z"));
        }
    }
    return p;
}

Record read_record(Reader& r) {
    const Token& t = r.next("a record");
    const std::string& k = t.text;
    if (k == "v") {
        return read_view(r);
    }
    if (k == "b") {
        return Background{r.vec("b r g b")};
    }
    if (k == "l") {
        Light l;
        l.position = r.vec("l x y z");
        if (r.more_on(t.line)) {
            l.has_color = true;
            l.color = r.vec("l r g b");
        }
        return l;
    }
    if (k == "f") {
        Fill f;
        f.color = r.vec("f r g b");
        f.kd = r.number("f Kd");
        f.ks = r.number("f Ks");
        f.shine = r.number("f Shine");
        f.t = r.number("f T");
        f.ior = r.number("f index_of_refraction");
        return f;
    }
    if (k == "s") {
        Sphere s;
        s.center = r.vec("s x y z");
        s.radius = r.number("s radius");
        if (!(s.radius > 0)) {
            r.fail(t.line, "sphere radius must be > 0");
        }
        return s;
    }
    if (k == "c") {
        Cone c;
        c.base = r.vec("c base x y z");
        c.base_radius = r.number("c base radius");
        c.apex = r.vec("c apex x y z");
        c.apex_radius = r.number("c apex radius");
        if (c.base_radius < 0 || c.apex_radius < 0 || c.base == c.apex) {
            r.fail(t.line, "cone needs radii >= 0 and distinct base and apex");
        }
        return c;
    }
    if (k == "p" || k == "pp") {
        return read_polygon(r, k == "pp", t.line);
    }
    r.fail(t.line, cat("unknown record '", k, "' (expected v b l f s c p pp or # comment)"));
}

// printf's %g: what the SPD programs write.
std::string g(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string g3(const Vec3d& v) {
    return cat(g(v.x), " ", g(v.y), " ", g(v.z));
}

struct Writer {
    std::string out;
    void line(std::initializer_list<std::string_view> parts) {
        for (const std::string_view p : parts) {
            out.append(p);
        }
        out.push_back('\n');
    }
    void operator()(const View& v) {
        line({"v"});
        line({"from ", g3(v.from)});
        line({"at ", g3(v.at)});
        line({"up ", g3(v.up)});
        line({"angle ", g(v.angle)});
        line({"hither ", g(v.hither)});
        line({"resolution ", std::to_string(v.width), " ", std::to_string(v.height)});
    }
    void operator()(const Background& b) { line({"b ", g3(b.color)}); }
    void operator()(const Light& l) {
        line({"l ", g3(l.position), l.has_color ? " " : "", l.has_color ? g3(l.color) : ""});
    }
    void operator()(const Fill& f) {
        line({"f ", g3(f.color), " ", g(f.kd), " ", g(f.ks), " ", g(f.shine), " ", g(f.t), " ",
              g(f.ior)});
    }
    void operator()(const Sphere& s) { line({"s ", g3(s.center), " ", g(s.radius)}); }
    void operator()(const Cone& c) {
        line({"c ", g3(c.base), " ", g(c.base_radius), " ", g3(c.apex), " ", g(c.apex_radius)});
    }
    void operator()(const Polygon& p) {
        const bool patch = !p.normals.empty();
        line({patch ? "pp " : "p ", std::to_string(p.vertices.size())});
        for (std::size_t i = 0; i < p.vertices.size(); ++i) {
            if (patch) {
                line({g3(p.vertices[i]), " ", g3(p.normals[i])});
            } else {
                line({g3(p.vertices[i])});
            }
        }
    }
};

}  // namespace

Counts count(const Document& d) {
    Counts c;
    for (const Record& r : d.records) {
        if (std::holds_alternative<Sphere>(r)) {
            ++c.spheres;
        } else if (std::holds_alternative<Cone>(r)) {
            ++c.cones;
        } else if (const auto* p = std::get_if<Polygon>(&r)) {
            ++(p->normals.empty() ? c.polygons : c.patches);
            c.vertices += p->vertices.size();
        } else if (std::holds_alternative<Light>(r)) {
            ++c.lights;
        }
    }
    return c;
}

Document parse(std::string_view text, std::string_view what) {
    Reader r(tokenize(text), what);
    Document d;
    while (!r.done()) {
        d.records.push_back(read_record(r));
    }
    return d;
}

Document load(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error(cat(path.string(), ": cannot open"));
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse(ss.str(), path.string());
}

std::string write(const Document& d) {
    Writer w;
    for (const Record& r : d.records) {
        std::visit(w, r);
    }
    return w.out;
}

void save(const Document& d, const std::filesystem::path& path) {
    write_file_atomically(path, write(d));
}

}  // namespace rtlab::nff
