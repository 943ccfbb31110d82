// libFuzzer target for `ssrt check`'s suite file (cli/suite_file.h): every input either loads
// as a suite, whose cases' references, rules and thresholds are then used as the runner uses
// them (cli/suite_rules.h judging a made-up comparison), or is refused with one
// std::runtime_error naming the file. Anything else (a crash, a sanitizer report, another
// exception, a rule whose threshold the runner would not count) is a bug.
#include <cstdint>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cli/suite_file.h"
#include "cli/suite_rules.h"
#include "fuzz_files.h"

namespace {

using namespace ssrt::cli;

// A comparison of one layer as check_case.cpp hands it to judgeLayer: counted over every
// threshold of the case, its figures derived from the threshold so that each rule meets both
// sides of its ranges across inputs.
ssrt::LayerDiff madeUpDiff(const std::vector<double>& thresholds, std::size_t salt) {
    ssrt::LayerDiff d;
    d.maxError = 0.01 * double(salt % 7);
    d.identical = salt % 5 == 0;
    for (std::size_t i = 0; i < thresholds.size(); ++i)
        d.pixelsOverEach.push_back(thresholds[i] > 0.01 ? salt % 3 : 100 + salt);
    return d;
}

// What `ssrt check` does with a loaded suite short of rendering: the reference it would pick,
// and each layer's rule judged. Throws (a bug) if a rule needs a count the runner lacks.
void useSuite(const Suite& suite) {
    const std::map<std::string, std::string> other = {{"arch", "aarch64"}, {"cpu", "neon"}};
    for (const SuiteCase& c : suite.cases) {
        if (chosenReference(c, suiteMachineKeys()).empty() || chosenReference(c, other).empty())
            std::abort();  // a case without a reference must have been refused
        const std::vector<double> thresholds = caseThresholds(c);
        std::size_t salt = c.name.size();
        for (const auto& layer : c.layers)
            judgeLayer(madeUpDiff(thresholds, salt++), ruleFor(c, layer.first), thresholds);
        judgeLayer(madeUpDiff(thresholds, salt), ruleFor(c, "color"), thresholds);
        if (c.flip) judgeFlip({0.02 * double(salt % 9), 0.0, 0.1 * double(salt % 11)}, *c.flip);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // Beside it a shot file, so that a case's "shot" can name one that exists.
    static const std::string shot = ssrt::fuzz::writeFile("shot.json", "{}");
    const std::string path = ssrt::fuzz::writeFile(
        "suite.json", std::string_view(reinterpret_cast<const char*>(data), size));
    Suite suite;
    try {
        suite = loadSuite(path);
    } catch (const std::runtime_error& e) {
        // Refused: one error, naming the file.
        if (std::string_view(e.what()).rfind(path + ": ", 0) != 0) std::abort();
        return 0;
    }
    useSuite(suite);
    return 0;
}
