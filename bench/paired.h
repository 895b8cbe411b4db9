#pragma once
// Paired timing for the targets suite's rows that compare two runs of the same work on a shared
// machine (ours against Embree medium, one thread against two): the two sides alternate within each
// benchmark iteration, the order swapped from pair to pair, and the row reports the median of the
// per-pair ratios with its quartiles. A load burst slows both halves of a pair, so the paired
// ratio holds still where medians timed minutes apart drift.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <tbb/global_control.h>
#include <utility>
#include <vector>

namespace rtlab::bench {

/// Wall seconds one call of f takes.
template <class F>
double seconds_once(const F& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Wall seconds of `passes` calls of f, after one untimed call (the other side's sample has just
/// filled the caches with its own data).
template <class F>
double seconds_of(int passes, const F& f) {
    f();
    return seconds_once([&] {
        for (int p = 0; p < passes; ++p) {
            f();
        }
    });
}

/// How many passes of `one` seconds make a sample of at least min_seconds (at least one).
inline int passes_for(double min_seconds, double one) {
    return std::max(1, static_cast<int>(std::ceil(min_seconds / std::max(one, 1e-9))));
}

/// The seconds of the two samples of one pair.
struct PairTimes {
    double first;
    double second;
};

/// One pair per iteration of state: first() and second(), each returning its sample's seconds,
/// first() ahead in even pairs and second() in odd ones; the iteration time is their sum.
template <class A, class B>
std::vector<PairTimes> alternate(benchmark::State& state, const A& first, const B& second) {
    std::vector<PairTimes> out;
    for (auto _ : state) {
        PairTimes p{};
        if (out.size() % 2 == 0) {
            p.first = first();
            p.second = second();
        } else {
            p.second = second();
            p.first = first();
        }
        state.SetIterationTime(p.first + p.second);
        out.push_back(p);
    }
    return out;
}

/// The median and quartiles (nearest rank) of the per-pair ratios, and their count, as the row's
/// counters ratio, ratio_q1, ratio_q3 and pairs.
inline void set_ratio_counters(benchmark::State& state, std::vector<double> ratios) {
    if (ratios.empty()) {
        return;
    }
    std::sort(ratios.begin(), ratios.end());
    const auto at = [&](double q) {
        const auto last = static_cast<double>(ratios.size() - 1);
        return ratios[static_cast<std::size_t>(std::lround(q * last))];
    };
    state.counters["ratio"] = at(0.5);
    state.counters["ratio_q1"] = at(0.25);
    state.counters["ratio_q3"] = at(0.75);
    state.counters["pairs"] = static_cast<double>(ratios.size());
}

/// A two-thread / one-thread row: sample() (returning its seconds) with TBB limited to one thread
/// and to two, in alternation; ratio is the median over the pairs of the one-thread time over the
/// two-thread time (the speed-up).
template <class F>
void time_scaling(benchmark::State& state, const F& sample) {
    const auto on = [&](std::size_t threads) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return sample();
    };
    std::vector<double> ratios;
    for (const PairTimes& p : alternate(
             state, [&] { return on(1); }, [&] { return on(2); })) {
        ratios.push_back(p.first / p.second);
    }
    set_ratio_counters(state, std::move(ratios));
}

/// time_scaling for a pass over rays (pass() runs it): each sample is one untimed pass and then as
/// many timed ones as make the one-thread sample last at least min_seconds.
template <class F>
void time_scaling_passes(benchmark::State& state, double min_seconds, const F& pass) {
    double one = 0;
    {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = seconds_of(1, pass);
    }
    const int passes = passes_for(min_seconds, one);
    time_scaling(state, [&] { return seconds_of(passes, pass); });
    state.counters["passes"] = passes;
}

}  // namespace rtlab::bench
