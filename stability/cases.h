#pragma once
// The run functions of the stability cases, one per stability/<name>_case.cpp, listed in
// registry.cpp.

#include "stability/stability.h"

#include <vector>

namespace rtlab::stab {

// Cases are declared here as they are added, e.g.
// std::vector<Row> run_watertight(const Options& opt);

/// Rays from inside a closed perturbed sphere: leaks per triangle method, structure and traversal.
std::vector<Row> run_watertight(const Options& opt);

/// Far and small spheres and triangles (D/r 1e3..1e8) and the Earth under a low camera: false
/// misses and t error of every sphere and triangle method against the exact root.
std::vector<Row> run_far_small(const Options& opt);

/// Rays through sphere centres, from origins rounded onto sphere surfaces and from inside spheres.
std::vector<Row> run_centres(const Options& opt);

/// Secondary rays from hit points on log-scaled triangles and spheres and on the sphere flake's
/// tangent contacts: re-intersections of the starting surface per offset policy.
std::vector<Row> run_self_intersection(const Options& opt);

/// Needle, zero-area and duplicate-vertex triangles: non-finite hits and disagreement with the
/// exact answer per triangle method.
std::vector<Row> run_needles(const Options& opt);

/// Tangent, grazing and axial rays on a torus: missed roots and t error of the implicit methods.
std::vector<Row> run_implicit(const Options& opt);

/// Rays from inside strongly jittered closed meshes at their vertices and edges and at the built
/// structure's own planes, and within rounding of those planes: leaks.
std::vector<Row> run_adversarial(const Options& opt);

/// Axis-aligned rays through the edges and vertices of the intgrid mesh: leaks.
std::vector<Row> run_intgrid(const Options& opt);

/// Zero, denormal, NaN and inf ray components, origins on box faces and split planes.
std::vector<Row> run_degenerate(const Options& opt);

/// Every structure against a box-free loop on constructed and stress scenes.
std::vector<Row> run_structures(const Options& opt);

/// Grazing, axis-parallel, coordinate-axis, thin and far rays on cones and cylinders: false
/// misses and hits and t error of every cone method against the exact answer.
std::vector<Row> run_cone(const Options& opt);

/// Rays nearly tangent to spheres and nearly parallel to triangles and box faces vs exact answers.
std::vector<Row> run_grazing(const Options& opt);

}  // namespace rtlab::stab
