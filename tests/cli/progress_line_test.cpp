// The progress line of long jobs (cli/progress_line.h): the time-left arithmetic, the duration
// text, and what a log and a terminal get, on a clock the test sets.
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <sstream>
#include <string>

#include "cli/progress_line.h"

using namespace ssrt::cli;

TEST_CASE("progress line: time left is the pace so far times what is left") {
    CHECK(secondsLeft(0.25, 10.0) == doctest::Approx(30.0));
    CHECK(secondsLeft(0.5, 8.0) == doctest::Approx(8.0));
    CHECK(secondsLeft(0.1, 2.0) == doctest::Approx(18.0));
    CHECK(secondsLeft(1.0, 42.0) == 0.0);
    CHECK(!secondsLeft(0.0, 5.0));  // no progress: no pace to go by
    CHECK(!secondsLeft(0.3, 0.0));  // no time passed either
}

TEST_CASE("progress line: durations to the second, then with minutes, then hours") {
    CHECK(durationText(0.4) == "0 s");
    CHECK(durationText(7.6) == "8 s");
    CHECK(durationText(59.4) == "59 s");
    CHECK(durationText(125.0) == "2 min 05 s");
    CHECK(durationText(3599.0) == "59 min 59 s");
    CHECK(durationText(3780.0) == "1 h 03 min");
    CHECK(progressText("reference", 0.4, 12.0) == "reference: 40% (about 12 s left)");
    CHECK(progressText("reference", 0.4, std::nullopt) == "reference: 40%");
    CHECK(progressText("reference", 0.9, 0.3) == "reference: 90% (under 1 s left)");
    CHECK(timeLeftText(125.0) == "about 2 min 05 s left");
    CHECK(timeLeftText(std::nullopt).empty());
    CHECK(progressText("reference", 1.0, 0.0) == "reference: 100%");
}

TEST_CASE("progress line: a log gets a plain line per tenth, with the time left") {
    std::ostringstream out;
    double now = 0.0;
    ProgressLine line(out, "reference", false, [&now] { return now; });
    // 2 s a tenth, reported every 5 %.
    for (int i = 1; i <= 20; ++i) {
        now = 1.0 * i;
        line.update(0.05 * i);
    }
    const std::string expected =
        "reference: 10% (about 18 s left)\n"
        "reference: 20% (about 16 s left)\n"
        "reference: 30% (about 14 s left)\n"
        "reference: 40% (about 12 s left)\n"
        "reference: 50% (about 10 s left)\n"
        "reference: 60% (about 8 s left)\n"
        "reference: 70% (about 6 s left)\n"
        "reference: 80% (about 4 s left)\n"
        "reference: 90% (about 2 s left)\n"
        "reference: 100%\n";
    CHECK(out.str() == expected);
    CHECK(!isTerminal(out));  // a string stream is never one
}

TEST_CASE("progress line: a terminal gets one line, rewritten per percent and ended at 100%") {
    std::ostringstream out;
    double now = 0.0;
    ProgressLine line(out, "reference", true, [&now] { return now; });
    now = 3.0;
    line.update(0.25);
    line.update(0.251);  // the same percentage: not rewritten
    now = 6.0;
    line.update(0.5);
    now = 12.0;
    line.update(1.0);
    CHECK(out.str() ==
          "\rreference: 25% (about 9 s left)\x1b[K"
          "\rreference: 50% (about 6 s left)\x1b[K"
          "\rreference: 100%\x1b[K\n");
}

#endif
