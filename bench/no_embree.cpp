// Built instead of embree_*.cpp when CMake does not find Embree 3: the baseline registers nothing.
#include "bench/benchmarks.h"

void rtlab::bench::register_embree_benchmarks() {}

void rtlab::bench::register_targets_embree_benchmarks() {}
