// The table of stability cases: a new case is one <name>_case.cpp plus one row here.
#include "stability/cases.h"
#include "stability/stability.h"

#include <array>

namespace rtlab::stab {

namespace {

// One row per case, in report order (a plain array: adding a row changes no other line).
const Case all_cases[] = {
    {"watertight",
     "Rays from inside a closed, vertex-perturbed sphere mesh (random directions, exactly at "
     "vertices, at shared-edge points) must all hit: leaks per triangle method, structure and "
     "traversal (float), and per structure in exact mode (certified hits, which must also equal "
     "exact brute force's).",
     &run_watertight},
    {"adversarial",
     "Rays that must all hit, generated to find each structure's weak spots: from the kernel of "
     "closed UV spheres with vertex radii jittered by 10-45 % (6 meshes, 168 to 2,976 "
     "triangles) at vertices, shared-edge points and points on the built structure's own planes "
     "(kd split planes, grid cell boundaries, BVH box faces; inside, on edges, at corners), and "
     "starting on or one float beside such a plane, nearly or exactly parallel to it, and from "
     "10 to 1e4 radii away into the kernel: leaks per "
     "triangle method, structure and traversal (float), and per structure in exact mode.",
     &run_adversarial},
    {"intgrid",
     "Axis-aligned rays whose origins lie on the lattice lines of the intgrid mesh (closed cube "
     "[-4, 4]^3) pass exactly through shared edges, vertices and square diagonals; all must hit. "
     "On the lattice one of the two triangles at an edge computes its zero barycentric exactly, "
     "so no method leaks here (unlike the perturbed sphere of the watertight case); exact mode "
     "per structure as well.",
     &run_intgrid},
    {"degenerate",
     "Axis-aligned and degenerate rays on the intgrid cube [-2, 2]^3: zero and denormal direction "
     "components and origins on box faces or split planes must give the box-free answer; zero, "
     "NaN and inf rays must be rejected without visiting a node.",
     &run_degenerate},
    {"grazing",
     "Rays nearly tangent to spheres, nearly parallel to triangle planes and to box faces "
     "(relative offset or angle log-uniform in 1e-8..1e-1) against exact rational answers: "
     "false hits and misses, relative t error and ns per test, per method and precision.",
     &run_grazing},
    {"far_small",
     "A sphere of radius r (or a triangle of size s) at distance D, D/r from 1e3 to 1e8, and the "
     "Earth (r = 6.4e6 m) under a camera 1-100 m up: false misses and hits, t error against the "
     "exact root (rationals + MPFR), per method and precision.",
     &run_far_small},
    {"centres",
     "Rays through sphere centres, from origins rounded onto sphere surfaces (near root at t ~ 0, "
     "windows from 0 and from 1e-4 r) and from inside spheres (the far root, exactly once).",
     &run_centres},
    {"self_intersection",
     "Reflection and shadow rays from hit points on triangles and spheres with coordinates and "
     "sizes log-uniform in 1e-8..1e8, and on the sphere flake's tangent contacts: "
     "re-intersections of the starting surface per offset policy (none, epsilon, ulp).",
     &run_self_intersection},
    {"needles",
     "Needles of aspect ratio 1 to 1e6, zero-area and duplicate-vertex triangles: non-finite hits, "
     "hits on zero-area triangles, disagreement with the exact answer and between methods.",
     &run_needles},
    {"implicit",
     "Rays exactly tangent to a torus (double roots), grazing it, along and parallel to its axis, "
     "and random: missed roots and t error of closed form, Newton and Laguerre with run time.",
     &run_implicit},
    {"cone",
     "Cones and cylinders (open and capped): rays in a tangent plane moved off the surface by "
     "1e-12..1e-2 radii, parallel to the cone's axis near its wall, along coordinate axes on "
     "axis-aligned cylinders, thin needles (radius/height 1e-6..1e-2), small far cones (D/r "
     "1e3..1e7) and random rays against the exact answer (rationals + MPFR): false misses and "
     "hits, t error and run time of every cone method.",
     &run_cone},
    {"structures",
     "Every structure (robust and plain) against a box-free loop over all primitives: a hit "
     "beyond the first cell or leaf a primitive overlaps, the stadium and scales scenes, and "
     "squares lying on integer split planes. Failures: misses, false hits and hits more than 1e-4 "
     "relative away in t.",
     &run_structures},
};

}  // namespace

std::span<const Case> cases() {
    return all_cases;
}

const Case* find_case(std::string_view name) {
    for (const Case& c : all_cases) {
        if (c.name == name) {
            return &c;
        }
    }
    return nullptr;
}

}  // namespace rtlab::stab
