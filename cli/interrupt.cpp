#include "cli/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>

#include "io/image_io.h"

namespace ssrt::cli {

namespace {

// Everything the handler touches is a lock-free atomic or a fixed buffer (io's temporaries):
// a handler may run on any thread, at any moment, and may only call async-signal-safe functions
// (kill, unlink, signal, raise).
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<pid_t>::is_always_lock_free);

std::atomic<bool> gScope{false};  // an InterruptScope is alive
std::atomic<int> gSignal{0};      // the first signal a scope caught (0: none)
std::atomic<bool> gFlag{false};   // raised after gSignal is set

// More than ssrt check's 256 jobs, each with its case's process or a --version probe.
constexpr int kMaxChildren = 512;
std::atomic<pid_t> gChildren[kMaxChildren];

void forwardToChildren(int sig) {
    for (std::atomic<pid_t>& child : gChildren)
        if (const pid_t pid = child.load(); pid > 0) ::kill(pid, sig);
}

void onSignal(int sig) {
    const int savedErrno = errno;
    forwardToChildren(sig);
    int none = 0;
    if (gScope.load() && gSignal.compare_exchange_strong(none, sig)) {
        gFlag.store(true);  // the first: the command stops at its next check
        errno = savedErrno;
        return;
    }
    // Outside a scope, or the second signal: end now, by this signal, as if it were unhandled
    // (the signal is blocked while its handler runs, so the raised one ends the process as soon
    // as the handler returns).
    removeTemporariesInFlight();
    ::signal(sig, SIG_DFL);
    ::raise(sig);
    errno = savedErrno;
}

}  // namespace

void installInterruptHandlers() {
    struct sigaction action = {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    // Restarted, not failed with EINTR: a write or a wait under way when the first signal
    // comes finishes as it would have.
    action.sa_flags = SA_RESTART;
    // A SIGINT ignored from the start stays ignored, as every program keeps it: a shell starts
    // its background jobs so, and a Ctrl-C meant for the foreground must not stop them.
    struct sigaction inherited = {};
    ::sigaction(SIGINT, nullptr, &inherited);
    if (inherited.sa_handler != SIG_IGN) ::sigaction(SIGINT, &action, nullptr);
    ::sigaction(SIGTERM, &action, nullptr);
    ::signal(SIGXFSZ, SIG_IGN);
}

InterruptScope::InterruptScope() { gScope.store(true); }

InterruptScope::~InterruptScope() { gScope.store(false); }

bool interrupted() { return gFlag.load(); }

const std::atomic<bool>* interruptFlag() { return &gFlag; }

Interrupted::Interrupted(const std::string& progress)
    : std::runtime_error("interrupted after " + progress), status_(128 + gSignal.load()) {}

void stopIfInterrupted(const std::function<std::string()>& progress) {
    if (interrupted()) throw Interrupted(progress());
}

void addChildProcess(pid_t pid) {
    for (std::atomic<pid_t>& child : gChildren) {
        pid_t empty = 0;
        if (child.compare_exchange_strong(empty, pid)) break;
    }
    // A signal that came while the child was starting, before the handler could see it.
    if (const int sig = gSignal.load(); sig != 0) ::kill(pid, sig);
}

void removeChildProcess(pid_t pid) {
    for (std::atomic<pid_t>& child : gChildren) {
        pid_t expected = pid;
        if (child.compare_exchange_strong(expected, 0)) break;
    }
}

}  // namespace ssrt::cli
