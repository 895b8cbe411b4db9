// Needle and degenerate triangles: needles of aspect ratio (longest edge / height) 1 to 1e6,
// exactly collinear (zero-area) triangles and triangles with duplicate vertices. Every triangle
// method in float and double must return no non-finite hit, must never hit a zero-area triangle
// (prepare() collapses it), and where the exact answer (Cramer's rule over Q, crosscheck/exact.h)
// is defined - the ray crosses the plane away from the edges - should agree with it.
#include "crosscheck/exact.h"
#include "intersect/triangle/methods.h"
#include "stability/cases.h"
#include "stability/exact_judge.h"

#include <cmath>
#include <string>
#include <vector>

namespace rtlab::stab {

namespace {

/// One kind of triangle: its label and how to make one (rounded to T, stored in double).
enum class Kind { needle, collinear, duplicate, single_point };

/// A triangle of the kind (aspect for needles) and a ray aimed near it; both rounded to T.
template <class T>
void make_sample(Kind kind, double aspect, Sampler& rng, Triangled& tri, Rayd& ray) {
    const auto round = [](const Vec3d& v) { return Vec3d(Vec3<T>(v)); };
    Vec3d aim;
    double len = 1;
    if (kind == Kind::needle) {
        const Vec3d c{rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)};
        len = std::pow(10.0, rng.uniform(-1, 1));
        const Vec3d u = rng.unit();
        const Vec3d w = normalize(cross(u, rng.unit()));
        const double h = len / aspect;
        tri = {round(c), round(c + u * len), round(c + u * (len * rng.uniform(0, 1)) + w * h)};
        // Aim into the box around the needle: about half the rays hit.
        aim = c + u * (len * rng.uniform(-0.1, 1.1)) + w * (h * rng.uniform(-0.5, 1.5));
    } else {
        // Integer vertices, so collinear and repeated vertices are exact in float and double.
        const auto ipoint = [&]() {
            return Vec3d{std::round(rng.uniform(-1000, 1000)), std::round(rng.uniform(-1000, 1000)),
                         std::round(rng.uniform(-1000, 1000))};
        };
        const Vec3d p0 = ipoint();
        const Vec3d p1 = ipoint();
        if (kind == Kind::collinear) {
            const double k = static_cast<double>(static_cast<int>(rng.index(5)) - 2);  // -2..2
            tri = {p0, p1, p0 + (p1 - p0) * k};
            aim = p0 + (p1 - p0) * (std::round(rng.uniform(0, 8)) / 8);  // exactly on the line
        } else if (kind == Kind::duplicate) {
            tri = {p0, p0, p1};
            aim = p0 + (p1 - p0) * rng.uniform(0, 1);
        } else {
            tri = {p0, p0, p0};
            aim = p0;
        }
        len = std::max(1.0, length(p1 - p0));
    }
    const Vec3d org = aim + rng.unit() * (len * rng.uniform(1, 3));
    ray = {round(org), round(aim - org)};
}

template <class T>
void run_kind(Kind kind,
              double aspect,
              const std::string& label,
              const Options& opt,
              std::uint64_t stream,
              std::vector<Row>& rows) {
    Sampler rng(opt.seed, stream);
    std::vector<Triangled> tris(opt.rays);
    std::vector<Rayd> rays_d(opt.rays);
    for (std::size_t i = 0; i < opt.rays; ++i) {
        make_sample<T>(kind, aspect, rng, tris[i], rays_d[i]);
    }
    const std::vector<ExactTruth> truth = exact_truths(
        opt.rays, [&](std::size_t i) { return xcheck::exact_triangle_hit(tris[i], rays_d[i]); });
    const std::vector<Ray<T>> rays = rays_in<T>(rays_d);
    const bool degenerate = kind != Kind::needle;
    std::vector<std::vector<char>> answers;
    for_each_triangle_method<T>([&]<class M>() {
        answers.emplace_back();
        MethodTally t = judge<M>(
            rays, truth,
            [&](std::size_t i) {
                return Triangle<T>{Vec3<T>(tris[i].p0), Vec3<T>(tris[i].p1), Vec3<T>(tris[i].p2)};
            },
            &answers.back());
        if (degenerate) {
            // Zero area: the only right answer is a miss (and the exact det is 0, so every ray is
            // "undefined" for the comparison above).
            std::size_t hits = 0;
            for (char a : answers.back()) {
                hits += a ? 1 : 0;
            }
            Row r = make_row("needles/" + label, std::string(M::name), precision_of<T>(), t.rays,
                             hits + t.nan, "hits on zero-area triangles + non-finite hits", t.ns,
                             "zero-area triangles must never hit");
            rows.push_back(r);
        } else {
            rows.push_back(tally_row("needles/" + label, std::string(M::name), precision_of<T>(), t,
                                     IntersectionMethod<M> ? "" : "hit/miss only"));
        }
    });
    // Consistency: rays with a defined exact answer on which the methods do not all agree.
    std::size_t defined = 0, split = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (!truth[i].defined && !degenerate) {
            continue;
        }
        ++defined;
        for (const std::vector<char>& a : answers) {
            if (a[i] != answers.front()[i]) {
                ++split;
                break;
            }
        }
    }
    rows.push_back(make_row("needles/" + label, "all methods agree", precision_of<T>(), defined,
                            split, "rays where the methods disagree",
                            std::numeric_limits<double>::quiet_NaN(),
                            "rays with a defined exact answer (degenerate kinds: all rays)"));
}

template <class T>
void run_precision(const Options& opt, std::vector<Row>& rows) {
    const std::uint64_t base = std::is_same_v<T, float> ? 700 : 800;
    for (int k = 0; k <= 6; k += 2) {
        run_kind<T>(Kind::needle, std::pow(10.0, k), "aspect=1e" + std::to_string(k), opt,
                    base + static_cast<unsigned>(k), rows);
    }
    run_kind<T>(Kind::collinear, 1, "zero_area", opt, base + 10, rows);
    run_kind<T>(Kind::duplicate, 1, "duplicate_vertex", opt, base + 11, rows);
    run_kind<T>(Kind::single_point, 1, "single_point", opt, base + 12, rows);
}

}  // namespace

std::vector<Row> run_needles(const Options& opt) {
    std::vector<Row> rows;
    run_precision<float>(opt, rows);
    run_precision<double>(opt, rows);
    return rows;
}

}  // namespace rtlab::stab
