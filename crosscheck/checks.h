#pragma once
// One checker per primitive kind; each lives in its own <kind>_check.cpp.

#include "crosscheck/crosscheck.h"

namespace rtlab::xcheck {

std::vector<std::string> triangle_methods();
std::vector<Row> check_triangles(const Options& opt);
std::vector<std::string> polygon_methods();
std::vector<Row> check_polygons(const Options& opt);
std::vector<std::string> aabb_methods();
std::vector<Row> check_aabbs(const Options& opt);
std::vector<std::string> obb_methods();
std::vector<Row> check_obbs(const Options& opt);
std::vector<std::string> sphere_methods();
std::vector<Row> check_spheres(const Options& opt);
std::vector<std::string> implicit_methods();
std::vector<Row> check_implicits(const Options& opt);
std::vector<std::string> cone_methods();
std::vector<Row> check_cones(const Options& opt);

}  // namespace rtlab::xcheck
