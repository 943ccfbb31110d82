// One case of a golden-image suite run: rendered by its own `ssrt render` process, compared
// with its reference (io/image_compare.h, FLIP from io/flip.h), judged by its rules
// (cli/suite_rules.h), with the images a report shows.
#pragma once

#include <map>
#include <string>

#include "cli/suite_file.h"
#include "io/check_report.h"

namespace ssrt::cli {

// What every case of a run shares.
struct CheckContext {
    std::string program;  // the ssrt that renders
    std::string outDir;   // absolute; a case writes only under outDir/cases/NAME
    std::map<std::string, std::string> machine;  // suiteMachineKeys()
};

enum class CaseStatus { Pass, Stale, Fail, New, Error, Updated };

// "PASS", "STALE", "FAIL", "NEW", "ERROR", "UPDATED".
const char* caseStatusName(CaseStatus status);

struct CaseResult {
    CaseStatus status = CaseStatus::Pass;
    std::string rendered;   // the new image (absolute), when the render succeeded
    std::string reference;  // the reference used (absolute)
    ReportCase report;      // message, command, images (relative to outDir), layers
};

// Renders, compares and judges the case. Never throws for the case's own failures: a render
// that fails, an unreadable reference or images of different sizes end as Error or Fail with
// the reason in report.message.
CaseResult runCase(const Suite& suite, const SuiteCase& c, const CheckContext& context);

}  // namespace ssrt::cli
