// One progress line per long job (a reference render): on a terminal, one line rewritten in
// place with the share done and the time left; elsewhere (a log, a pipe, a test's stream)
// plain lines, one per tenth of the job. Only the message depends on the clock: nothing the
// job computes reads it.
#pragma once

#include <functional>
#include <iosfwd>
#include <mutex>
#include <optional>
#include <string>

namespace ssrt::cli {

// Seconds left of a job `fraction` (in [0, 1]) done after `elapsed` seconds, at the pace so far:
// elapsed * (1 - fraction) / fraction. Nothing before any progress to go by (fraction or
// elapsed not above 0); 0 once done.
std::optional<double> secondsLeft(double fraction, double elapsed);

// A duration as a person reads it, to the second below a minute, then to the second with
// minutes, then to the minute with hours: "7 s", "2 min 05 s", "1 h 03 min".
std::string durationText(double seconds);

// "about 12 s left" ("under 1 s left" below half a second), or empty when `left` is unknown.
std::string timeLeftText(std::optional<double> left);

// "reference: 40%", with " (about 12 s left)" (timeLeftText) when `left` is known and the job
// not done.
std::string progressText(const std::string& label, double fraction, std::optional<double> left);

// Whether `stream` is std::cerr (or std::clog) on a terminal, or std::cout on one.
bool isTerminal(const std::ostream& stream);

class ProgressLine {
public:
    // Seconds since the job started; the default reads std::chrono::steady_clock.
    using Clock = std::function<double()>;

    // Progress of the job `label` to `out`, rewritten in place when `out` is a terminal.
    ProgressLine(std::ostream& out, std::string label);
    // The same with the choice and the clock given (for tests).
    ProgressLine(std::ostream& out, std::string label, bool terminal, Clock clock);

    // The job is `fraction` done (rising, ending at 1). On a terminal the line is rewritten
    // ('\r', the text, then clear to the line's end) when the whole percentage changes, and
    // ended with a line break at 1; elsewhere a line is written at each tenth passed (10%,
    // 20%, ..., 100%). Safe to call from several threads.
    void update(double fraction);

private:
    std::ostream& out_;
    std::string label_;
    bool terminal_;
    Clock clock_;
    std::mutex mutex_;
    int shown_ = -1;  // the last percentage (terminal) or tenth (elsewhere) written
};

}  // namespace ssrt::cli
