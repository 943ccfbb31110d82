#include "cli/suite_rules.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cli/diff_command.h"

namespace ssrt::cli {

namespace {

// The pixels of `layer` over `threshold`, counted with `thresholds` as moreThresholds.
uint64_t pixelsOver(const LayerDiff& layer, double threshold,
                    const std::vector<double>& thresholds) {
    const auto it = std::find(thresholds.begin(), thresholds.end(), threshold);
    if (it == thresholds.end() || layer.pixelsOverEach.size() != thresholds.size())
        throw std::logic_error("a rule's threshold was not counted");
    return layer.pixelsOverEach[std::size_t(it - thresholds.begin())];
}

// A measured value against a range: above hi fails, below lo is stale. Written so that a NaN
// fails.
void judgeRange(double value, const Range& range, const std::string& what, LayerJudgement& out) {
    if (!(value <= range.hi)) {
        out = {Verdict::Fail, what + " " + number(value) + " > " + number(range.hi)};
    } else if ((value < range.lo || (range.staleAtLo && value <= range.lo)) &&
               out.verdict == Verdict::Pass) {
        out = {Verdict::Stale, what + " " + number(value) + (value < range.lo ? " < " : " = ") +
                                   number(range.lo) + " (the rule's lower end: tighten it)"};
    }
}

}  // namespace

LayerJudgement judgeLayer(const LayerDiff& layer, const LayerRule& rule,
                          const std::vector<double>& thresholds) {
    if (layer.presence == LayerDiff::Presence::MissingInA)
        return {Verdict::Fail, "missing in the render"};
    if (layer.presence == LayerDiff::Presence::MissingInB)
        return {Verdict::Fail, "missing in the reference"};
    // A NaN or infinity against another value is a bug, never noise: no rule admits it.
    if (layer.nonFinite > 0)
        return {Verdict::Fail,
                std::to_string(layer.nonFinite) + " pixels NaN or inf against a value"};
    const bool identical = layer.identical && layer.hashA == layer.hashB;
    if (rule.exact)
        return identical ? LayerJudgement{}
                         : LayerJudgement{Verdict::Fail, "not bit-identical (max difference " +
                                                             number(layer.maxError) + ")"};
    LayerJudgement out;
    if (rule.hardLimit && !(layer.maxError <= *rule.hardLimit))
        return {Verdict::Fail, "max difference " + number(layer.maxError) + " > hard limit " +
                                   number(*rule.hardLimit)};
    for (const Bucket& b : rule.buckets) {
        const uint64_t n = pixelsOver(layer, b.threshold, thresholds);
        if (n > b.maxPixels)
            return {Verdict::Fail, std::to_string(n) + " pixels over " + number(b.threshold) +
                                       " > " + std::to_string(b.maxPixels)};
    }
    // Fails first, whichever range; then the first stale end.
    if (rule.maxDifference) judgeRange(layer.maxError, *rule.maxDifference, "max difference", out);
    if (rule.pixels && out.verdict != Verdict::Fail)
        judgeRange(double(pixelsOver(layer, rule.threshold, thresholds)), *rule.pixels,
                   "pixels over " + number(rule.threshold), out);
    if (out.verdict == Verdict::Pass && identical)
        return {Verdict::Stale, "bit-identical under a tolerance (make it exact)"};
    return out;
}

LayerJudgement judgeFlip(const FlipStats& stats, const FlipRule& rule) {
    LayerJudgement out;
    if (rule.mean) judgeRange(stats.mean, *rule.mean, "FLIP mean", out);
    if (rule.max && out.verdict != Verdict::Fail) judgeRange(stats.max, *rule.max, "FLIP max", out);
    return out;
}

}  // namespace ssrt::cli
