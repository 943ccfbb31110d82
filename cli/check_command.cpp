#include "cli/check_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <future>
#include <ostream>
#include <stdexcept>
#include <thread>

#include "cli/build_info.h"
#include "cli/check_case.h"
#include "cli/child_process.h"
#include "cli/cli.h"
#include "cli/interrupt.h"
#include "cli/json_output.h"
#include "cli/options.h"
#include "core/isa.h"
#include "io/check_report.h"
#include "io/image_io.h"

namespace ssrt::cli {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxJobs = 256;

// The program that renders: --ssrt, checked now, or this one.
std::string renderProgram(const CheckOptions& o) {
    if (!o.program) return thisProgram();
    if (::access(o.program->c_str(), X_OK) != 0 || fs::is_directory(*o.program))
        badValue("--ssrt", *o.program, "an ssrt program that can be run");
    return fs::absolute(*o.program).string();
}

// Every case, `jobs` at a time; `done(i, result)` called in the suite's order as each one is
// known (case 3 waits for case 2's line, never the other way). An interrupt (cli/interrupt.h,
// passed on to the cases' processes, which stop as render does) starts no further case and
// ends the run with Interrupted once the cases under way have ended, no report written.
template <class Done>
std::vector<CaseResult> runCases(const Suite& suite, const CheckContext& context, int jobs,
                                 Done done) {
    const std::size_t n = suite.cases.size();
    std::vector<std::promise<CaseResult>> promises(n);
    std::vector<std::future<CaseResult>> futures;
    for (auto& p : promises) futures.push_back(p.get_future());
    std::atomic<std::size_t> next{0};
    std::vector<std::thread> workers;
    for (int w = 0; w < std::min<int>(jobs, int(n)); ++w)
        workers.emplace_back([&] {
            for (std::size_t i; (i = next++) < n;) {
                try {
                    // After an interrupt no case starts: its empty result is never shown.
                    promises[i].set_value(interrupted() ? CaseResult{}
                                                        : runCase(suite, suite.cases[i], context));
                } catch (...) {
                    promises[i].set_exception(std::current_exception());
                }
            }
        });
    std::vector<CaseResult> results;
    try {
        for (std::size_t i = 0; i < n; ++i) {
            CaseResult result = futures[i].get();
            // A case whose process the interrupt ended (or that never started) has no result.
            stopIfInterrupted([&] {
                return std::to_string(i) + " of " + plural(int(n), "case") + " (no report written)";
            });
            results.push_back(std::move(result));
            done(results.back());
        }
    } catch (...) {
        next = n;
        for (std::thread& t : workers) t.join();
        throw;
    }
    for (std::thread& t : workers) t.join();
    return results;
}

// What a reference written now records: the renderer's version line (its own --version, so a
// --ssrt program records itself) and the ISA the case renders with.
std::vector<std::pair<std::string, std::string>> provenance(const CheckContext& context,
                                                            const SuiteCase& c) {
    const std::string log = (fs::path(context.outDir) / "version.log").string();
    runProcess(context.program, {"--version"}, context.outDir, log);
    std::ifstream in(log);
    std::string line;
    std::getline(in, line);
    const auto fields = parseVersionLine(line);
    if (fields.empty())
        throw std::runtime_error("'" + context.program + " --version' printed no ssrt version");
    std::vector<std::pair<std::string, std::string>> out(fields.begin(), fields.end());
    std::string isa = std::string(isaName(defaultIsa()));
    for (std::size_t i = 0; i < c.args.size(); ++i) {
        if (c.args[i] == "--isa" && i + 1 < c.args.size() && c.args[i + 1] != "auto")
            isa = c.args[i + 1];
        if (c.args[i].rfind("--isa=", 0) == 0 && c.args[i] != "--isa=auto")
            isa = c.args[i].substr(6);
    }
    out.emplace_back("ssrt:isa", isa);
    return out;
}

// --update: the failing and new cases' references rewritten from their renders, one by one.
void updateReferences(const Suite& suite, const CheckContext& context,
                      std::vector<CaseResult>& results, std::ostream* out) {
    for (std::size_t i = 0; i < results.size(); ++i) {
        CaseResult& r = results[i];
        if (r.status != CaseStatus::Fail && r.status != CaseStatus::New) continue;
        fs::create_directories(fs::path(r.reference).parent_path());
        copyImageWithAttributes(r.rendered, r.reference, provenance(context, suite.cases[i]));
        r.report.message = "wrote " + r.report.reference + " (was " + r.report.status + ": " +
                           r.report.message + ")";
        r.status = CaseStatus::Updated;
        r.report.status = caseStatusName(r.status);
        r.report.outcome = ReportOutcome::Pass;
        if (out) *out << "UPDATED  " << r.report.name << "  " << r.report.message << "\n";
    }
}

constexpr int kStatusCount = int(CaseStatus::Updated) + 1;

std::string summaryOf(const std::vector<CaseResult>& results) {
    int count[kStatusCount] = {};
    for (const CaseResult& r : results) ++count[int(r.status)];
    std::string s = plural(int(results.size()), "case") + ": " + std::to_string(count[0]) +
                    " passed, " + std::to_string(count[2]) + " failed, " +
                    std::to_string(count[1]) + " stale, " + std::to_string(count[3]) + " new, " +
                    plural(count[4], "error");
    if (count[5] > 0) s += ", " + std::to_string(count[5]) + " updated";
    return s;
}

// The run for --json (docs/golden.md): the cases as their lines and the report show them.
Json checkJson(const CheckReport& report, const std::string& html, const std::string& junit) {
    // {"pass": n, "stale": n, ...}: every status, from the names the lines print.
    Json counts = Json::object();
    for (int s = 0; s < kStatusCount; ++s) counts[jsonKey(caseStatusName(CaseStatus(s)))] = 0;
    Json cases = Json::array();
    for (const ReportCase& c : report.cases) {
        counts[jsonKey(c.status)] = counts[jsonKey(c.status)].get<int>() + 1;
        Json layers = Json::array();
        for (const ReportLayer& l : c.layers)
            layers.push_back({{"name", l.name},
                              {"channels", l.channels},
                              {"max_error", l.maxError},
                              {"where", l.where},
                              {"pixels_over", l.pixelsOver},
                              {"hash", l.hash},
                              {"rule", l.rule},
                              {"verdict", l.verdict},
                              {"bad", l.bad}});
        cases.push_back({{"name", c.name},
                         {"status", c.status},
                         {"message", c.message},
                         {"seconds", c.seconds},
                         {"command", c.command},
                         {"reference", c.reference},
                         {"flip", c.flipLine},
                         {"layers", std::move(layers)}});
    }
    return {{"suite", report.suite},
            {"summary", report.summary},
            {"counts", std::move(counts)},
            {"cases", std::move(cases)},
            {"report", html},
            {"junit", junit}};
}

int exitStatus(const std::vector<CaseResult>& results) {
    int status = kExitOk;
    for (const CaseResult& r : results) {
        if (r.status == CaseStatus::Error) return kExitFailure;
        if (r.status != CaseStatus::Pass && r.status != CaseStatus::Updated) status = kExitDiffer;
    }
    return status;
}

}  // namespace

CLI::App* addCheckCommand(CLI::App& app, CheckOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "check",
        "Run a golden-image suite: render each case, compare it with its reference by its "
        "rules (exact unless a layer's rule says otherwise), one line per case, an HTML report "
        "and a JUnit file; exit 1 when a case fails, is stale or has no reference, 3 when one "
        "cannot be rendered");
    cmd->add_option("SUITE", o.suite,
                    "The suite file (JSON; see docs/golden.md, \"Suites: ssrt check\")")
        ->required()
        ->type_name("FILE");
    cmd->add_option("-o,--out", o.out,
                    "Folder for report.html, junit.xml and each case's files (cases/NAME/: the "
                    "render, previews, heat maps, render.log); made if missing")
        ->type_name("DIR")
        ->capture_default_str();
    cmd->add_option("-j,--jobs", o.jobs, "Cases rendered at a time (0: one per core)")
        ->type_name("N")
        ->capture_default_str();
    cmd->add_option_function<std::string>(
           "--ssrt", [&o](const std::string& v) { o.program = v; },
           "The ssrt program that renders the cases (default: this one)")
        ->type_name("PROGRAM");
    cmd->add_flag("--update", o.update,
                  "Rewrite the references of the failing and new cases (never a passing or stale "
                  "one, never the suite's rules), each recording the commit, ISA, compiler and "
                  "ssrt version that made it (EXR header attributes, PNG text)");
    cmd->add_flag("--json", o.json,
                  "Print the run as one JSON document on stdout when it ends, instead of a line "
                  "per case and the summary (docs/golden.md gives its keys); the same exit status "
                  "and reports");
    return cmd;
}

int runCheck(const CheckOptions& o, std::ostream& out) {
    const InterruptScope interruptible;  // stops between cases (runCases)
    const int jobs = int(parseInteger("--jobs", o.jobs, 0, kMaxJobs));
    CheckContext context;
    context.program = renderProgram(o);
    const Suite suite = loadSuite(o.suite);
    std::error_code ec;
    fs::create_directories(o.out, ec);
    if (ec || !fs::is_directory(o.out))
        throw std::runtime_error("cannot make the folder '" + o.out + "'");
    context.outDir = fs::absolute(o.out).lexically_normal().string();
    context.machine = suiteMachineKeys();
    const int workers = jobs > 0 ? jobs : int(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<CaseResult> results = runCases(suite, context, workers, [&](const CaseResult& r) {
        if (o.json) return;  // (the document comes whole at the end)
        out << r.report.status << std::string(9 - r.report.status.size(), ' ') << r.report.name
            << "  " << r.report.message << "\n"
            << std::flush;
    });
    if (o.update) updateReferences(suite, context, results, o.json ? nullptr : &out);
    CheckReport report;
    report.suite = o.suite;
    report.summary = summaryOf(results);
    for (const CaseResult& r : results) report.cases.push_back(r.report);
    const std::string html = (fs::path(context.outDir) / "report.html").string();
    const std::string junit = (fs::path(context.outDir) / "junit.xml").string();
    writeHtmlReport(html, report);
    writeJunitReport(junit, report);
    if (o.json) printJson(out, checkJson(report, html, junit));
    else out << "check: " << report.summary << " (" << html << ", " << junit << ")\n";
    return exitStatus(results);
}

}  // namespace ssrt::cli
