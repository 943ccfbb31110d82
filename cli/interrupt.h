// SIGINT and SIGTERM in the ssrt command (docs/cli.md, "Interrupts").
//
// installInterruptHandlers (main, once) handles both signals for the whole process. While no
// InterruptScope is alive, a signal ends the process at once, as the default action would,
// after removing the temporaries of the writes in flight (io/image_io.h), so no command leaves
// a `.NAME.tmp-*` file behind. While one is alive (render, reference, compare, sweep and check:
// the long commands), the first signal only raises a flag; the command checks it between its
// steps (a frame's passes, reference tiles, sweep settings, check cases), stops with every file
// it wrote whole, prints "ssrt: interrupted after N of M frames (...)" and exits 128 + the
// signal (130 for SIGINT, 143 for SIGTERM). A second signal ends the process at once, as
// outside a scope.
// Every signal is passed on to the child processes running (ssrt check's cases). A SIGINT
// ignored when the process starts (a script's background job) stays ignored.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>

namespace ssrt::cli {

// Installs the SIGINT and SIGTERM handlers, and ignores SIGXFSZ so that a write over
// `ulimit -f` fails with "File too large" (a one-line error naming the file) rather than
// killing the process with the temporary left behind.
void installInterruptHandlers();

// While alive, the first SIGINT or SIGTERM only raises the flag (see above). Not nested.
class InterruptScope {
public:
    InterruptScope();
    ~InterruptScope();
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;
};

// Whether a signal has raised the flag.
bool interrupted();
// The flag itself, for work that checks it between its own steps (ReferenceSettings::cancel).
const std::atomic<bool>* interruptFlag();

// How a command ends at an interrupt: what() is "interrupted after ..." (the progress), and
// runCli prints it as one line and exits status().
class Interrupted : public std::runtime_error {
public:
    explicit Interrupted(const std::string& progress);
    int status() const { return status_; }

private:
    int status_;
};

// Throws Interrupted("after " + progress()) when the flag is up; progress is called only then.
void stopIfInterrupted(const std::function<std::string()>& progress);

// Child processes that get every signal this process gets, for as long as they run (their
// count is bounded: ssrt check's --jobs). A child should be in a process group of its own, so
// that a terminal's Ctrl-C reaches it once, through us.
void addChildProcess(pid_t pid);
void removeChildProcess(pid_t pid);

}  // namespace ssrt::cli
