#include "cli/progress_line.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace ssrt::cli {

std::optional<double> secondsLeft(double fraction, double elapsed) {
    if (fraction >= 1.0) return 0.0;
    if (!(fraction > 0.0) || !(elapsed > 0.0)) return std::nullopt;
    return elapsed * (1.0 - fraction) / fraction;
}

std::string durationText(double seconds) {
    const long long s = std::llround(std::max(seconds, 0.0));
    char buf[64];
    if (s < 60) std::snprintf(buf, sizeof buf, "%lld s", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%lld min %02lld s", s / 60, s % 60);
    else std::snprintf(buf, sizeof buf, "%lld h %02lld min", s / 3600, (s % 3600) / 60);
    return buf;
}

std::string timeLeftText(std::optional<double> left) {
    if (!left) return {};
    return *left < 0.5 ? std::string("under 1 s left") : "about " + durationText(*left) + " left";
}

std::string progressText(const std::string& label, double fraction, std::optional<double> left) {
    std::string text = label + ": " + std::to_string(int(fraction * 100.0)) + "%";
    if (left && fraction < 1.0) text += " (" + timeLeftText(left) + ")";
    return text;
}

bool isTerminal(const std::ostream& stream) {
    if (&stream == &std::cerr || &stream == &std::clog) return isatty(STDERR_FILENO) == 1;
    if (&stream == &std::cout) return isatty(STDOUT_FILENO) == 1;
    return false;
}

namespace {

ProgressLine::Clock steadySeconds() {
    const auto start = std::chrono::steady_clock::now();
    return [start] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
}

}  // namespace

ProgressLine::ProgressLine(std::ostream& out, std::string label)
    : ProgressLine(out, std::move(label), isTerminal(out), steadySeconds()) {}

ProgressLine::ProgressLine(std::ostream& out, std::string label, bool terminal, Clock clock)
    : out_(out), label_(std::move(label)), terminal_(terminal), clock_(std::move(clock)) {}

void ProgressLine::update(double fraction) {
    const int percent = int(fraction * 100.0);
    // A terminal's line changes with each percent; a log gets a line per tenth, from 10 %.
    const int step = terminal_ ? percent : percent / 10;
    std::lock_guard lock(mutex_);
    if (step <= shown_ || (!terminal_ && step == 0)) return;
    shown_ = step;
    const std::string text = progressText(label_, fraction, secondsLeft(fraction, clock_()));
    if (terminal_) out_ << "\r" << text << "\x1b[K" << (fraction >= 1.0 ? "\n" : "") << std::flush;
    else out_ << text << "\n" << std::flush;
}

}  // namespace ssrt::cli
