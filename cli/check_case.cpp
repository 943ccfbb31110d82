#include "cli/check_case.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "cli/child_process.h"
#include "cli/cli.h"
#include "cli/diff_command.h"
#include "cli/render_command.h"
#include "cli/suite_rules.h"
#include "io/flip.h"
#include "io/image_compare.h"

namespace ssrt::cli {

namespace fs = std::filesystem;

namespace {

// How many failing layers a case's line names before "and N more".
constexpr int kLayersNamed = 3;

// The last non-empty line of a log (a failed render's "ssrt: error: ..." line).
std::string lastLine(const std::string& path) {
    std::ifstream in(path);
    std::string line, last;
    while (std::getline(in, line))
        if (!line.empty()) last = line;
    return last;
}

std::string hex(uint64_t h) {
    std::ostringstream s;
    s << std::hex << std::setw(16) << std::setfill('0') << h;
    return s.str();
}

std::string ruleText(const LayerRule& r) {
    if (r.exact) return "exact";
    std::string out;
    const auto add = [&](const std::string& part) { out += (out.empty() ? "" : "; ") + part; };
    const auto range = [](const Range& g) {
        return "[" + number(g.lo) + ", " + number(g.hi) + "]";
    };
    if (r.maxDifference) add("max difference " + range(*r.maxDifference));
    if (r.pixels) add("pixels over " + number(r.threshold) + " " + range(*r.pixels));
    for (const Bucket& b : r.buckets)
        add("at most " + std::to_string(b.maxPixels) + " over " + number(b.threshold));
    if (r.hardLimit) add("hard limit " + number(*r.hardLimit));
    return out;
}

// The render: its own process in the suite's folder, its output in the case's folder.
std::vector<std::string> renderArgs(const SuiteCase& c, const std::string& output) {
    std::vector<std::string> args{"render"};
    if (c.shot) args.insert(args.end(), {"--shot", *c.shot});
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.insert(args.end(), {"-o", output, "--quiet"});
    return args;
}

// A report image, written when it can be: a preview that fails leaves the page without it.
std::string preview(const std::string& image, const fs::path& png, const std::string& outDir) {
    try {
        writePreviewPng(image, png.string());
        return fs::relative(png, outDir).string();
    } catch (const std::exception&) {
        return "";
    }
}

// The layers judged into the report's rows; returns the failing and the stale ones' reasons.
void judgeLayers(const SuiteCase& c, const ImageDiff& diff, const std::vector<double>& thresholds,
                 CaseResult& r, std::vector<std::string>& failed, std::vector<std::string>& stale) {
    for (const LayerDiff& l : diff.layers) {
        const LayerRule& rule = ruleFor(c, l.name);
        LayerJudgement j = judgeLayer(l, rule, thresholds);
        // "*" covers layers nobody named: one of them being bit-identical says nothing about
        // the tolerance the others need.
        if (j.verdict == Verdict::Stale && l.identical && c.layers.count(l.name) == 0) j = {};
        const bool both = l.presence == LayerDiff::Presence::Both;
        const std::string verdict = j.verdict == Verdict::Pass
                                        ? (l.identical ? "bit-identical" : "within")
                                    : j.verdict == Verdict::Stale ? "stale: " + j.why
                                                                  : "fail: " + j.why;
        r.report.layers.push_back(
            {l.name, channelList(l.channels), both ? number(l.maxError) : "-",
             both && l.maxError > 0.0 ? "(" + std::to_string(l.maxX) + ", " +
                                            std::to_string(l.maxY) + ") " + l.maxChannel
                                      : "-",
             both ? std::to_string(l.pixelsOver) : "-", both ? hex(l.hashA) : "-", ruleText(rule),
             verdict, j.verdict != Verdict::Pass});
        if (j.verdict == Verdict::Fail) failed.push_back(l.name + ": " + j.why);
        if (j.verdict == Verdict::Stale) stale.push_back(l.name + ": " + j.why);
    }
    // A rule for a layer neither image has guards nothing: say so.
    for (const auto& [name, rule] : c.layers) {
        bool found = name == "*";
        for (const LayerDiff& l : diff.layers) found = found || l.name == name;
        if (!found) failed.push_back(name + ": a rule for a layer neither image has");
    }
}

std::string listed(const std::vector<std::string>& reasons) {
    std::string out;
    for (int i = 0; i < int(reasons.size()) && i < kLayersNamed; ++i)
        out += (out.empty() ? "" : "; ") + reasons[i];
    if (int(reasons.size()) > kLayersNamed)
        out += "; and " + std::to_string(reasons.size() - kLayersNamed) + " more";
    return out;
}

// FLIP of the colour: judged when the case has a FLIP rule, shown when the images differ.
void addFlip(const SuiteCase& c, const fs::path& dir, const std::string& outDir, CaseResult& r,
             std::vector<std::string>& failed, std::vector<std::string>& stale) {
    FlipFileOptions options;
    options.heatmap = (dir / "flip.png").string();
    options.threads = 1;  // the cases already run side by side
    try {
        const FlipResult flip = flipImages(r.rendered, r.reference, options);
        std::ostringstream line;
        line << std::fixed << std::setprecision(6) << (flip.hdr ? "HDR" : "LDR") << "-FLIP: mean "
             << flip.stats.mean << ", weighted median " << flip.stats.weightedMedian << ", max "
             << flip.stats.max;
        r.report.flipLine = line.str();
        r.report.flipImage = fs::relative(options.heatmap, outDir).string();
        if (!c.flip) return;
        const LayerJudgement j = judgeFlip(flip.stats, *c.flip);
        if (j.verdict == Verdict::Fail) failed.push_back(j.why);
        if (j.verdict == Verdict::Stale) stale.push_back(j.why);
    } catch (const std::exception& e) {
        if (c.flip) failed.push_back(std::string("FLIP: ") + e.what());
    }
}

void compareCase(const SuiteCase& c, const fs::path& dir, const std::string& outDir,
                 CaseResult& r) {
    const std::vector<double> thresholds = caseThresholds(c);
    ImageCompareOptions options;
    options.moreThresholds = thresholds;
    options.heatmap = (dir / "difference.png").string();
    ImageDiff diff;
    try {
        diff = compareImages(r.rendered, r.reference, options);
    } catch (const std::exception& e) {
        // A reference of another size or one that cannot be read: the case fails (and an
        // update rewrites it), the run goes on.
        r.status = CaseStatus::Fail;
        r.report.message = e.what();
        return;
    }
    r.report.diffImage = fs::relative(options.heatmap, outDir).string();
    std::vector<std::string> failed, stale;
    judgeLayers(c, diff, thresholds, r, failed, stale);
    if (c.flip || !diff.identical()) addFlip(c, dir, outDir, r, failed, stale);
    const int n = int(diff.layers.size());
    int identical = 0;
    for (const LayerDiff& l : diff.layers) identical += l.identical ? 1 : 0;
    if (!failed.empty()) {
        r.status = CaseStatus::Fail;
        r.report.message = listed(failed);
    } else if (!stale.empty()) {
        r.status = CaseStatus::Stale;
        r.report.message = listed(stale);
    } else {
        r.report.message = identical == n
                               ? std::to_string(n) + " layers bit-identical"
                               : std::to_string(identical) + " of " + std::to_string(n) +
                                     " layers bit-identical, the rest within their rules";
    }
}

// A render of several frames wrote rendered_0000.exr, rendered_0001.exr, ...
// (sequenceFileName): the case's frame is the one compared. Returns 0, or an exit status for a
// frame the render did not write, with the message.
int pickFrame(int frame, CaseResult& r) {
    const fs::path dir = fs::path(r.rendered).parent_path();
    const std::string stem = fs::path(r.rendered).stem().string() + "_";
    int count = 0;
    for (const auto& entry : fs::directory_iterator(dir))
        count += entry.path().filename().string().rfind(stem, 0) == 0 ? 1 : 0;
    const std::string file = sequenceFileName(r.rendered, frame, std::max(count, 2));
    if (frame >= count || !fs::exists(file)) {
        r.report.message = "the render wrote " + std::to_string(count) + " frames, no frame " +
                           std::to_string(frame);
        return kExitFailure;
    }
    r.rendered = file;
    return 0;
}

}  // namespace

const char* caseStatusName(CaseStatus status) {
    switch (status) {
        case CaseStatus::Pass: return "PASS";
        case CaseStatus::Stale: return "STALE";
        case CaseStatus::Fail: return "FAIL";
        case CaseStatus::New: return "NEW";
        case CaseStatus::Error: return "ERROR";
        case CaseStatus::Updated: return "UPDATED";
    }
    return "?";
}

CaseResult runCase(const Suite& suite, const SuiteCase& c, const CheckContext& context) {
    const auto start = std::chrono::steady_clock::now();
    CaseResult r;
    r.report.name = c.name;
    const fs::path dir = fs::path(context.outDir) / "cases" / c.name;
    std::error_code ec;
    fs::remove_all(dir, ec);  // nothing of an earlier run may pass for this one's
    fs::create_directories(dir, ec);
    const std::string refWritten = chosenReference(c, context.machine);
    r.report.reference = refWritten;
    r.reference = (fs::path(suite.folder) / refWritten).lexically_normal().string();
    r.rendered = (dir / ("rendered" + fs::path(c.reference).extension().string())).string();
    const std::vector<std::string> args = renderArgs(c, r.rendered);
    std::vector<std::string> words{context.program};
    words.insert(words.end(), args.begin(), args.end());
    r.report.command = "cd " + shellCommand({suite.folder}) + " && " + shellCommand(words);
    const std::string log = (dir / "render.log").string();
    int code = -1;
    try {
        if (ec) throw std::runtime_error("cannot make the folder '" + dir.string() + "'");
        code = runProcess(context.program, args, suite.folder, log);
    } catch (const std::exception& e) {
        r.report.message = e.what();
    }
    if (code == 0 && c.frame) code = pickFrame(*c.frame, r);
    if (code != 0) {
        r.status = CaseStatus::Error;
        r.rendered.clear();
        if (code > 0 && r.report.message.empty())
            r.report.message =
                "the render failed (exit " + std::to_string(code) + "): " + lastLine(log);
    } else {
        r.report.newImage = preview(r.rendered, dir / "new.png", context.outDir);
        if (!fs::exists(r.reference)) {
            r.status = CaseStatus::New;
            r.report.message = "no reference " + refWritten + " (--update writes it)";
        } else {
            r.report.referenceImage = preview(r.reference, dir / "reference.png", context.outDir);
            compareCase(c, dir, context.outDir, r);
        }
    }
    r.report.status = caseStatusName(r.status);
    r.report.outcome = r.status == CaseStatus::Error  ? ReportOutcome::Error
                       : r.status == CaseStatus::Pass ? ReportOutcome::Pass
                                                      : ReportOutcome::Failure;
    r.report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

}  // namespace ssrt::cli
