// rtlab sweep run: runs a sweep's shards on this machine, N at a time, each in a child process
// (`rtlab sweep run ... --shard K`, so a crash loses one case, not the sweep), with a progress bar
// and ETA; or one shard in this process with --shard (what Slurm array tasks run).
#include "apps/sweep_commands.h"
#include "base/error.h"
#include "sweep/shard_runner.h"
#include "sweep/sweep_dir.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <fmt/format.h>
#include <iostream>
#include <map>
#include <memory>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace rtlab::app {

namespace {

namespace fs = std::filesystem;

struct RunArgs {
    std::string file;
    std::string out;
    std::size_t jobs = 1;
    std::size_t shards = 0;
    long shard = -1;
    int cpus = 0;
};

volatile std::sig_atomic_t interrupted = 0;
extern "C" void on_signal(int) {
    interrupted = 1;
}

std::string clock_text(double s) {
    const auto t = static_cast<long>(s + 0.5);
    return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60)
                     : fmt::format("{}:{:02}", t / 60, t % 60);
}

// Starts `rtlab sweep run FILE -o DIR --shard k --cpus c` with output into DIR/logs/shard-k.log.
pid_t spawn_shard(const sweep::Planned& p, std::size_t k, int cpus) {
    const std::string exe = fs::read_symlink("/proc/self/exe").string();
    fs::create_directories(p.dir / "logs");
    const std::string log = (p.dir / "logs" / fmt::format("shard-{:04}.log", k)).string();
    std::vector<std::string> args{exe,       "sweep",
                                  "run",     (p.dir / "sweep.json").string(),
                                  "-o",      p.dir.string(),
                                  "--shard", std::to_string(k),
                                  "--cpus",  std::to_string(cpus)};
    std::vector<char*> argv;
    for (std::string& a : args) {
        argv.push_back(a.data());
    }
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    // O_NOFOLLOW: a link planted in the folder (e.g. to /etc/passwd) is never appended through.
    posix_spawn_file_actions_addopen(&fa, 1, log.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        throw Error(fmt::format("sweep run: cannot start {} with its log {} ({})", exe, log,
                                std::strerror(rc)));
    }
    return pid;
}

// Cases of the pending shards finished during this run (a result ending after `since`).
struct Progress {
    std::size_t finished = 0;
    std::size_t failed = 0;
};

Progress progress_since(const sweep::Planned& p, double since) {
    Progress pr;
    for (const auto& [id, j] : sweep::read_results(p.dir)) {
        const double end = j.value("provenance", nlohmann::json::object()).value("end_unix", 0.0);
        if (end >= since) {
            ++pr.finished;
            pr.failed += j.value("status", "") == "done" ? 0 : 1;
        }
    }
    return pr;
}

class Bar {
public:
    explicit Bar(std::size_t total) : total_(total), tty_(isatty(2) != 0) {}
    void show(const Progress& pr, double elapsed, bool last) {
        if (pr.finished == shown_ && !last) {
            return;
        }
        const std::size_t step = std::max<std::size_t>(1, total_ / 10);
        if (!tty_ && !last && pr.finished / step == shown_ / step) {
            return;
        }
        shown_ = pr.finished;
        const double frac = total_ > 0 ? static_cast<double>(pr.finished) / total_ : 1.0;
        const auto filled = static_cast<std::size_t>(frac * 30);
        std::string eta = "?";
        if (pr.finished > 0) {
            eta = clock_text(elapsed / pr.finished *
                             static_cast<double>(total_ - std::min(total_, pr.finished)));
        }
        std::cerr << fmt::format("{}[{}{}] {}/{} cases, {} failed, {} elapsed, ETA {}{}",
                                 tty_ ? "\r" : "", std::string(filled, '#'),
                                 std::string(30 - filled, '.'), pr.finished, total_, pr.failed,
                                 clock_text(elapsed), eta, tty_ && !last ? "" : "\n")
                  << std::flush;
    }

private:
    std::size_t total_;
    bool tty_;
    std::size_t shown_ = SIZE_MAX;
};

int run_one_shard(const RunArgs& a) {
    const sweep::Planned p = sweep::plan_into(a.file, a.out, a.shards);
    sweep::ShardOptions opt;
    opt.cpus = a.cpus;
    opt.log = &std::cerr;
    const sweep::ShardOutcome o = sweep::run_shard(p, static_cast<std::size_t>(a.shard), opt);
    std::cerr << fmt::format("[shard {}] {} measured, {} failed, {} already done\n", a.shard,
                             o.done, o.failed, o.skipped);
    return 0;
}

// Shards with a case that is not done, and how many such cases there are (`todo`).
std::vector<std::size_t> pending_shards(const sweep::Planned& p, std::size_t& todo) {
    const auto results = sweep::read_results(p.dir);
    std::vector<std::size_t> pending;
    todo = 0;
    for (std::size_t k = 0; k < p.shards.size(); ++k) {
        std::size_t n = 0;
        for (const std::size_t i : p.shards[k]) {
            const auto it = results.find(p.cases[i].id);
            n += it == results.end() || it->second.value("status", "") != "done" ? 1 : 0;
        }
        if (n > 0) {
            pending.push_back(k);
            todo += n;
        }
    }
    return pending;
}

// A line for a shard child that did not end with exit code 0.
std::string crash_line(const sweep::Planned& p, std::size_t k, int wstatus) {
    return fmt::format("shard {} ended with {} {} (see {}/logs/shard-{:04}.log)", k,
                       WIFSIGNALED(wstatus) ? "signal" : "exit code",
                       WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : WEXITSTATUS(wstatus),
                       p.dir.string(), k);
}

int run_local(const RunArgs& a) {
    const sweep::Planned p = sweep::plan_into(a.file, a.out, a.shards);
    const auto before = sweep::status_of(p, sweep::read_results(p.dir));
    std::size_t todo = 0;
    const std::vector<std::size_t> pending = pending_shards(p, todo);
    std::cerr << fmt::format(
        "sweep '{}' -> {}: {} cases in {} shards; {} already done, {} to run in {} shards, {} at "
        "a time\n",
        p.sweep.name, p.dir.string(), p.cases.size(), p.shards.size(), before.done, todo,
        pending.size(), a.jobs);
    const int cpus =
        a.cpus > 0 ? a.cpus : std::max(1, sweep::default_cpus() / static_cast<int>(a.jobs));

    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);

    const double start =
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    const auto t0 = std::chrono::steady_clock::now();
    Bar bar(todo);
    std::map<pid_t, std::size_t> running;
    std::size_t next = 0;
    std::vector<std::string> crashed;
    while ((next < pending.size() || !running.empty()) && interrupted == 0) {
        while (running.size() < a.jobs && next < pending.size()) {
            running.emplace(spawn_shard(p, pending[next], cpus), pending[next]);
            ++next;
        }
        int wstatus = 0;
        const pid_t done = waitpid(-1, &wstatus, WNOHANG);
        if (done > 0) {
            const auto it = running.find(done);
            if (it != running.end() && !(WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0) &&
                interrupted == 0) {
                crashed.push_back(crash_line(p, it->second, wstatus));
            }
            running.erase(done);
            continue;
        }
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        bar.show(progress_since(p, start), elapsed, false);
        std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
    if (interrupted != 0) {
        for (const auto& [pid, k] : running) {
            kill(pid, SIGINT);
        }
        for (const auto& [pid, k] : running) {
            waitpid(pid, nullptr, 0);
        }
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    bar.show(progress_since(p, start), elapsed, true);
    for (const std::string& c : crashed) {
        std::cerr << "rtlab sweep run: " << c << "\n";
    }
    const sweep::Status st = sweep::status_of(p, sweep::read_results(p.dir));
    if (interrupted != 0) {
        std::cerr << fmt::format(
            "rtlab sweep run: interrupted; {} of {} cases done, each shard file complete; run the "
            "same command again to finish\n",
            st.done, p.cases.size());
        return 130;
    }
    std::cerr << fmt::format(
        "sweep '{}': {} done, {} failed, {} missing (rtlab sweep status {}; "
        "rtlab sweep merge {})\n",
        p.sweep.name, st.done, st.failed, st.missing, p.dir.string(), p.dir.string());
    return st.failed + st.missing > 0 ? 1 : 0;
}

}  // namespace

SweepCommand add_sweep_run(CLI::App& sweep) {
    auto a = std::make_shared<RunArgs>();
    CLI::App* sub = sweep.add_subcommand(
        "run",
        "Run a sweep on this machine: every shard not yet complete, N at a time (default one "
        "shard at a time with all cores, so timings do not disturb each other), with a progress "
        "bar and ETA; results per shard in DIR/results, resumable (finished cases are skipped)");
    sub->add_option("file", a->file, "Sweep file (JSON, docs/sweeps.md)")->required();
    sub->add_option("-o,--output", a->out, "Sweep folder (default out/sweep-<file name>)");
    sub->add_option("--jobs", a->jobs,
                    "Shards run at once, each with cores/N threads (default 1: one shard at a "
                    "time with all cores, undisturbed timings)")
        ->check(CLI::Range(1, 1024));
    sub->add_option("--shards", a->shards,
                    "Number of shards for a new folder (default: one per scene)");
    sub->add_option("--shard", a->shard,
                    "Run only shard K, in this process (what each Slurm array task runs)")
        ->check(CLI::Range(0L, 1000000L));
    sub->add_option("--cpus", a->cpus,
                    "Threads for cases asking for all cores (default: SLURM_CPUS_PER_TASK, else "
                    "every core / --jobs)")
        ->check(CLI::Range(1, 1024));
    return {sub, [a] {
                if (a->out.empty()) {
                    a->out = fmt::format("out/sweep-{}", fs::path(a->file).stem().string());
                }
                return a->shard >= 0 ? run_one_shard(*a) : run_local(*a);
            }};
}

}  // namespace rtlab::app
