// How a golden-image suite's case is judged: one layer's comparison (io/image_compare.h)
// against its rule (cli/suite_file.h), and FLIP's statistics against the case's FLIP rule.
#pragma once

#include <string>
#include <vector>

#include "cli/suite_file.h"

namespace ssrt::cli {

enum class Verdict { Pass, Stale, Fail };

// One layer judged: the verdict, and for Stale or Fail why ("max difference 0.03 > 0.01").
struct LayerJudgement {
    Verdict verdict = Verdict::Pass;
    std::string why;
};

// Judges `layer`, compared with ImageCompareOptions::moreThresholds = `thresholds`.
LayerJudgement judgeLayer(const LayerDiff& layer, const LayerRule& rule,
                          const std::vector<double>& thresholds);

// Judges FLIP's statistics against the rule.
LayerJudgement judgeFlip(const FlipStats& stats, const FlipRule& rule);

}  // namespace ssrt::cli
