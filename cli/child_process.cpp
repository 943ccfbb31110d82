#include "cli/child_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "cli/interrupt.h"

extern char** environ;

namespace ssrt::cli {

namespace {

// posix_spawn's file actions, released on every path out.
struct FileActions {
    posix_spawn_file_actions_t actions;
    FileActions() { posix_spawn_file_actions_init(&actions); }
    ~FileActions() { posix_spawn_file_actions_destroy(&actions); }
};

// posix_spawn's attributes, likewise.
struct SpawnAttributes {
    posix_spawnattr_t attributes;
    SpawnAttributes() { posix_spawnattr_init(&attributes); }
    ~SpawnAttributes() { posix_spawnattr_destroy(&attributes); }
};

}  // namespace

int runProcess(const std::string& program, const std::vector<std::string>& args,
               const std::string& folder, const std::string& log) {
    std::vector<std::string> words{program};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    FileActions fa;
    posix_spawn_file_actions_addopen(&fa.actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa.actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawn_file_actions_addopen(&fa.actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addchdir_np(&fa.actions, folder.c_str());
    // A process group of its own: a terminal's Ctrl-C reaches it once, passed on by our
    // handler (cli/interrupt.h), not a second time from the terminal (which would end it at once).
    SpawnAttributes sa;
    posix_spawnattr_setflags(&sa.attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&sa.attributes, 0);
    pid_t pid = 0;
    const int started =
        posix_spawn(&pid, program.c_str(), &fa.actions, &sa.attributes, argv.data(), environ);
    if (started != 0)
        throw std::runtime_error("cannot run '" + program + "': " + std::strerror(started));
    addChildProcess(pid);
    // Waited for without reaping first, so that its pid is no one else's while a signal may
    // still be passed on to it.
    siginfo_t info = {};
    while (waitid(P_PID, id_t(pid), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
    }
    removeChildProcess(pid);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw std::runtime_error("cannot wait for '" + program + "'");
    if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
    return WEXITSTATUS(status);
}

std::string shellCommand(const std::vector<std::string>& words) {
    std::string out;
    for (const std::string& w : words) {
        const bool plain = !w.empty() && std::all_of(w.begin(), w.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_./=:,+@%", c);
        });
        std::string q = w;
        if (!plain) {
            q = "'";
            for (char c : w) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
            q += "'";
        }
        out += (out.empty() ? "" : " ") + q;
    }
    return out;
}

std::string thisProgram() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

}  // namespace ssrt::cli
