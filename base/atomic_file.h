#pragma once
// Writing output files completely or not at all, and never replacing a file that is not a regular
// file of rtlab's own making (rtlab runs as root on shared machines):
//  - a new file, or a regular file rtlab wrote before (it carries the extended attribute
//    user.rtlab.output, which every output gets), is written to a uniquely named temporary file in
//    the target's folder, which is renamed over the target when complete (atomic within one file
//    system) and removed on any error, and on SIGINT/SIGTERM (see install_interrupt_cleanup);
//  - a FIFO, character or block device (e.g. /dev/null, /dev/stdout on a terminal or pipe), also
//    through a symbolic link, is written into directly: it is never replaced or removed;
//  - anything else is refused with an error naming the output: a regular file rtlab did not write
//    (a user's file, a file copied without its attributes), a symbolic link to a regular file or
//    to nothing (writing through it would replace or create a file the link's owner chose), a
//    folder, a socket.
// check_output_path() runs the same checks before any work starts, so an unwritable output fails
// in the first second rather than after an hour of computation.

#include "base/error.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <string_view>
#include <sys/stat.h>
#include <sys/xattr.h>
#include <system_error>
#include <unistd.h>

namespace rtlab {

namespace detail {

/// Temporary files currently being written, for the signal handler (fixed size, lock-free, so
/// the handler only reads plain memory and calls unlink, which is async-signal-safe).
struct TemporarySlot {
    std::atomic<int> state{0};  ///< 0 free, 1 being filled in, 2 holds a path to remove
    std::array<char, 4096> path{};
};
inline constexpr std::size_t max_temporaries = 64;
inline std::array<TemporarySlot, max_temporaries> temporary_slots;
inline std::array<char, 64> interrupt_program{'r', 't', 'l', 'a', 'b', '\0'};
inline std::atomic<bool> interrupt_installed{false};

inline void write_stderr(const char* s) {
    std::size_t n = std::strlen(s);
    while (n > 0) {
        const ssize_t w = ::write(STDERR_FILENO, s, n);
        if (w <= 0) {
            return;
        }
        s += w;
        n -= static_cast<std::size_t>(w);
    }
}

extern "C" inline void on_interrupt(int sig) {
    for (TemporarySlot& slot : temporary_slots) {
        if (slot.state.load(std::memory_order_acquire) == 2) {
            ::unlink(slot.path.data());
        }
    }
    write_stderr(interrupt_program.data());
    write_stderr(sig == SIGINT ? ": interrupted by SIGINT; unfinished output removed\n"
                               : ": terminated by SIGTERM; unfinished output removed\n");
    ::_exit(128 + sig);
}

/// Registers a temporary file for removal on SIGINT/SIGTERM; returns its slot, or
/// max_temporaries when it cannot be tracked (path too long, too many at once): such a file is
/// still removed on errors, only not on a signal.
inline std::size_t register_temporary(const std::filesystem::path& tmp) {
    const std::string s = tmp.string();
    if (s.size() >= TemporarySlot{}.path.size()) {
        return max_temporaries;
    }
    for (std::size_t i = 0; i < max_temporaries; ++i) {
        TemporarySlot& slot = temporary_slots[i];
        int expected = 0;
        if (slot.state.compare_exchange_strong(expected, 1, std::memory_order_acquire)) {
            std::memcpy(slot.path.data(), s.c_str(), s.size() + 1);
            slot.state.store(2, std::memory_order_release);
            return i;
        }
    }
    return max_temporaries;
}

inline void unregister_temporary(std::size_t i) {
    if (i < max_temporaries) {
        temporary_slots[i].state.store(0, std::memory_order_release);
    }
}

}  // namespace detail

/// The extended attribute every output rtlab writes carries: the mark of a regular file of its own
/// making, which a later run may replace.
inline constexpr const char* output_mark = "user.rtlab.output";

/// True when the regular file `file` carries output_mark.
inline bool has_output_mark(const std::filesystem::path& file) {
    return ::getxattr(file.c_str(), output_mark, nullptr, 0) >= 0;
}

/// Marks `file` as rtlab's own output (for outputs another library wrote, e.g. Google
/// Benchmark's --benchmark_out); without user extended attributes it stays unmarked.
inline void mark_output(const std::filesystem::path& file) {
    ::setxattr(file.c_str(), output_mark, "1", 1, 0);
}

/// Where an output goes: `file` itself, and whether it is a special file (FIFO or device, also
/// reached through a symbolic link) that is written into rather than replaced.
struct OutputTarget {
    std::filesystem::path file;
    bool special = false;
};

/// Resolves an output path; throws Error naming `file` when rtlab may not write there (see the
/// top of this header).
inline OutputTarget resolve_output(const std::filesystem::path& file) {
    if (file.empty()) {
        throw Error("output file name is empty");
    }
    namespace fs = std::filesystem;
    const auto is_special = [](fs::file_type t) {
        return t == fs::file_type::fifo || t == fs::file_type::character ||
               t == fs::file_type::block;
    };
    OutputTarget t{file, false};
    std::error_code ec;
    const fs::file_type own = fs::symlink_status(file, ec).type();
    if (own == fs::file_type::symlink) {
        if (!is_special(fs::status(file, ec).type())) {
            throw Error(file.string() +
                        ": is a symbolic link; rtlab does not write through links (give the file "
                        "it points to, or remove the link)");
        }
        t.special = true;
        return t;
    }
    if (is_special(own)) {
        t.special = true;
        return t;
    }
    switch (own) {
    case fs::file_type::not_found:
        return t;
    case fs::file_type::regular:
        if (!has_output_mark(file)) {
            throw Error(file.string() + ": exists and was not written by rtlab (no " +
                        std::string(output_mark) + " attribute); remove it or choose another name");
        }
        return t;
    case fs::file_type::directory:
        throw Error(file.string() + ": is a folder, not an output file");
    default:
        throw Error(file.string() +
                    ": cannot write to this kind of file (not a regular file, FIFO "
                    "or device)");
    }
}

/// SIGINT and SIGTERM remove every temporary file being written, print "<program>: interrupted
/// by SIGINT; unfinished output removed" and exit 130 (SIGINT) or 143 (SIGTERM); SIGPIPE is
/// ignored so that writing into a FIFO whose reader went away is an error, not a silent death.
/// Idempotent; write_atomically calls it, a program calls it first to also cover its work phase.
inline void install_interrupt_cleanup(std::string_view program = "rtlab") {
    const std::size_t n = std::min(program.size(), detail::interrupt_program.size() - 1);
    std::memcpy(detail::interrupt_program.data(), program.data(), n);
    detail::interrupt_program[n] = '\0';
    if (detail::interrupt_installed.exchange(true)) {
        return;
    }
    struct sigaction sa {};
    sa.sa_handler = detail::on_interrupt;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    std::signal(SIGPIPE, SIG_IGN);
}

/// A uniquely named, empty temporary file beside `target` (".<stem>.rtlab-tmp-<pid>-<n><ext>",
/// keeping the extension for writers that choose the format by it), removed on destruction unless
/// commit() renamed it over the target.
class TemporaryOutput {
public:
    explicit TemporaryOutput(const std::filesystem::path& target, const std::string& what)
        : target_(target), what_(what) {
        const std::filesystem::path dir =
            target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
        std::error_code ec;
        if (!std::filesystem::is_directory(dir, ec)) {
            throw Error(what + ": folder " + dir.string() + " does not exist");
        }
        static std::atomic<std::uint64_t> counter{0};
        for (int attempt = 0; attempt < 100; ++attempt) {
            const std::uint64_t n = counter.fetch_add(1);  // pid + counter: unique on a host
            // Appended piecewise: GCC 12 at -O3 trips -Wrestrict on "literal" + std::string.
            std::string name(".");
            name += target.stem().string();
            name += ".rtlab-tmp-";
            name += std::to_string(::getpid());
            name += '-';
            name += std::to_string(n);
            name += target.extension().string();
            std::filesystem::path tmp = dir / name;
            // Registered for the signal handler only once created by us (O_EXCL), so a signal
            // can never remove a file of the same name that is not ours.
            const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd >= 0) {
                slot_ = detail::register_temporary(tmp);
                struct stat st {};
                if (::stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
                    ::fchmod(fd, st.st_mode & 07777);  // a replaced file keeps its permissions
                }
                ::close(fd);
                path_ = std::move(tmp);
                return;
            }
            const int err = errno;
            if (err != EEXIST) {
                throw Error(what + ": cannot create a file in " + dir.string() + " (" +
                            std::strerror(err) + ")");
            }
        }
        throw Error(what + ": cannot find a free temporary name in " + dir.string());
    }
    TemporaryOutput(const TemporaryOutput&) = delete;
    TemporaryOutput& operator=(const TemporaryOutput&) = delete;
    ~TemporaryOutput() {
        if (!committed_) {
            ::unlink(path_.c_str());
        }
        detail::unregister_temporary(slot_);
    }
    const std::filesystem::path& path() const { return path_; }
    /// Renames the temporary over the target; throws Error naming the output on failure.
    /// Marks the temporary as rtlab's own output (output_mark; where the file system has no user
    /// extended attributes the output stays unmarked, so a later run will not replace it).
    void commit() {
        mark_output(path_);
        std::error_code ec;
        std::filesystem::rename(path_, target_, ec);
        if (ec) {
            throw Error(what_ + ": cannot write (" + ec.message() + ")");
        }
        committed_ = true;
    }

private:
    std::filesystem::path target_;
    std::string what_;
    std::filesystem::path path_;
    std::size_t slot_ = detail::max_temporaries;
    bool committed_ = false;
};

/// Checks, before any work, that `file` can be written: not a folder, its folder exists and
/// accepts a new file (probed by creating and removing a temporary), or it is a writable FIFO or
/// device. Throws Error naming `file`.
inline void check_output_path(const std::filesystem::path& file) {
    const OutputTarget t = resolve_output(file);
    if (t.special) {
        if (::access(t.file.c_str(), W_OK) != 0) {
            throw Error(file.string() + ": cannot write (" + std::strerror(errno) + ")");
        }
        return;
    }
    const TemporaryOutput probe(t.file, file.string());
}

/// Calls write(path) with the path to write to and makes the result appear at `file` completely
/// or not at all (see the top of this header): for a regular or new file, path is a temporary
/// renamed over the target when write returns; for a FIFO or device, path is the target itself.
/// On an exception the temporary is removed, the target is left untouched, and the exception
/// passes on.
inline void write_atomically(const std::filesystem::path& file,
                             const std::function<void(const std::filesystem::path&)>& write) {
    install_interrupt_cleanup();
    const OutputTarget t = resolve_output(file);
    if (t.special) {
        write(t.file);
        return;
    }
    TemporaryOutput tmp(t.file, file.string());
    write(tmp.path());
    tmp.commit();
}

/// Writes `bytes` to `file` completely or not at all; throws rtlab::Error naming the file.
inline void write_file_atomically(const std::filesystem::path& file, std::string_view bytes) {
    write_atomically(file, [&](const std::filesystem::path& path) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        if (!out) {
            throw Error(file.string() + ": cannot open for writing");
        }
        constexpr std::size_t chunk = std::size_t{1} << 20;
        for (std::size_t at = 0; at < bytes.size() && out; at += chunk) {
            const std::size_t n = std::min(chunk, bytes.size() - at);
            out.write(bytes.data() + at, static_cast<std::streamsize>(n));
        }
        out.close();
        if (!out) {
            throw Error(file.string() + ": write failed (disk full?)");
        }
    });
}

}  // namespace rtlab
