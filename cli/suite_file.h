// A golden-image suite file (`ssrt check SUITE.json`): its cases, each a render (a shot file
// and/or `ssrt render` flags), its reference image and a rule per layer; and how one layer's
// comparison (io/image_compare.h) is judged against its rule.
//
// Exact is the default: a layer passes only when it is bit-identical to the reference (its
// hashes equal). Every other rule is an exception someone wrote down, and it is two-sided: a
// range [lo, hi] for the largest difference and for the count of pixels over a threshold.
// Above hi fails; below lo passes but is reported STALE (the tolerance is looser than what it
// is measured to need; WPT's fuzzy reftests fail it too). One number N in the file means
// [N / 10, N] with N / 10 itself stale: a tolerance ten or more times what the images need is
// stale.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/flip.h"
#include "io/image_compare.h"

namespace ssrt::cli {

// A two-sided range; see the header.
struct Range {
    double lo = 0.0, hi = 0.0;
    bool staleAtLo = false;  // the one-number form: a result equal to lo is stale too
};

// At most `maxPixels` pixels may differ by more than `threshold` (WebRender's buckets: many
// slightly-off pixels and a few far-off ones bounded separately).
struct Bucket {
    double threshold = 0.0;
    uint64_t maxPixels = 0;
};

// One layer's rule. exact: bit-identical; otherwise every part given must hold.
struct LayerRule {
    bool exact = true;
    double threshold = 0.0;              // a pixel is "over" when a channel differs by more
    std::optional<Range> maxDifference;  // the largest difference of any value
    std::optional<Range> pixels;         // the count of pixels over `threshold`
    std::vector<Bucket> buckets;
    std::optional<double> hardLimit;  // no value may differ by more (OpenImageIO's -hardfail)
};

// FLIP (io/flip.h) of the case's colour, as ranges on its mean and maximum.
struct FlipRule {
    std::optional<Range> mean, max;
};

// Another reference where what truly differs says so: every key in `when` must match this
// machine (suiteMachineKeys()).
struct AlternateReference {
    std::map<std::string, std::string> when;
    std::string reference;  // as written in the file
};

struct SuiteCase {
    std::string name;                 // [A-Za-z0-9._-]+, unique in the suite
    std::optional<std::string> shot;  // as written (relative to the suite's folder)
    std::vector<std::string> args;    // `ssrt render` flags
    // For a render of several frames (a shot's "frames", --frames): the index of the one frame
    // compared (0 is the first), which the other frames' history leads up to.
    std::optional<int> frame;
    std::string reference;  // as written
    std::vector<AlternateReference> alternates;
    std::map<std::string, LayerRule> layers;  // by layer name; "*" for every other layer
    std::optional<FlipRule> flip;
};

struct Suite {
    std::string file;    // the suite file's path
    std::string folder;  // its folder: the cases' paths are relative to it, renders run in it
    std::vector<SuiteCase> cases;
};

// Reads and checks a suite file. Throws std::runtime_error, one line naming the file and the
// JSON path of the field ("suite.json: cases[2].layers.color.pixels: expected ..."), for a file
// that cannot be read or is not a valid suite (unknown or duplicate keys, wrong types, bad
// ranges, a name used twice, render flags that `check` owns: -o, --compare).
Suite loadSuite(const std::string& path);

// The keys an alternate reference may be chosen by, with this machine's values:
//   arch  the processor architecture ssrt was built for (x86_64, aarch64, ...)
//   cpu   the best ISA this CPU runs (scalar, sse2, sse42, avx2, avx512): Embree chooses its
//         kernels by it, so truth layers made on one CPU kind may differ from another's
std::map<std::string, std::string> suiteMachineKeys();

// The reference a case uses on a machine with `keys`: the first alternate whose every key
// matches, else the case's own; a path as written.
std::string chosenReference(const SuiteCase& c, const std::map<std::string, std::string>& keys);

// The rule for a layer: its own, else "*", else exact.
const LayerRule& ruleFor(const SuiteCase& c, const std::string& layer);

// Every threshold the case's rules count pixels over besides 0 (for
// ImageCompareOptions::moreThresholds), and where a rule's counts are in LayerDiff's lists.
std::vector<double> caseThresholds(const SuiteCase& c);

}  // namespace ssrt::cli
