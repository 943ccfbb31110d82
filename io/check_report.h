// The reports of a golden-image suite's run (`ssrt check`): an HTML page a person reads and a
// JUnit XML file a CI reads. They take plain text and image paths, not the runner's types, so
// io/ stays below cli/ (DESIGN.md's module table).
#pragma once

#include <string>
#include <vector>

namespace ssrt {

// One row of a case's per-layer table, as printed.
struct ReportLayer {
    std::string name, channels, maxError, where, pixelsOver, hash, rule, verdict;
    bool bad = false;  // failed or stale: highlighted
};

// How a case ended, for the reports' order and JUnit: Failure is a failed test, Error one that
// could not run.
enum class ReportOutcome { Pass, Failure, Error };

struct ReportCase {
    std::string name;
    std::string status;  // PASS, FAIL, STALE, NEW, ERROR, UPDATED
    ReportOutcome outcome = ReportOutcome::Pass;
    std::string message;    // what the one-line result says after the name
    std::string command;    // the shell command that rendered it
    std::string reference;  // the reference file, as the suite names it
    // Images, relative to the report's folder (empty: none): the render and the reference as
    // display PNGs, the difference heat map (io/image_compare.h), FLIP's (io/flip.h).
    std::string newImage, referenceImage, diffImage, flipImage;
    std::string flipLine;  // FLIP's mean, weighted median and maximum, or empty
    std::vector<ReportLayer> layers;
    double seconds = 0.0;
};

struct CheckReport {
    std::string suite;              // the suite file
    std::string summary;            // the run's summary line
    std::vector<ReportCase> cases;  // in the suite's order
};

// The page: the summary, then every case with its status, the command that rendered it, the
// new image over the reference (the reference shows while the pointer is on it), the
// reference, the heat maps and the per-layer table. Failed, erroring, stale and new cases come
// first, then the rest, each in the suite's order. Images are linked beside the page (the
// folder works offline, copied as a whole). A small script records in the body's attributes
// how many images loaded and which did not (data-images, data-images-failed) and any script
// error (data-errors), for a headless browser's check. Written whole or not at all.
void writeHtmlReport(const std::string& path, const CheckReport& report);

// JUnit XML: one <testsuite> named after the suite, a <testcase> per case with a <failure> or
// <error> carrying its message. Written whole or not at all.
void writeJunitReport(const std::string& path, const CheckReport& report);

// A display PNG of an image file, for a report: its display.R/G/B layers (ssrt's EXRs), else
// its plain R, G, B (a PNG's), else color.R/G/B clamped to [0, 1], else a grey first channel.
// Throws std::runtime_error naming the file when it cannot be read.
void writePreviewPng(const std::string& image, const std::string& png);

}  // namespace ssrt
