#include "cli/diff_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "cli/cli.h"
#include "cli/json_output.h"
#include "cli/options.h"
#include "io/image_io.h"

namespace ssrt::cli {

namespace {

// The whole text must be a finite number in [lo, hi].
double parseNumber(const std::string& option, const std::string& text, double lo, double hi,
                   const std::string& expected) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ptr != end || ec != std::errc{} || !std::isfinite(value) || value < lo ||
        value > hi)
        badValue(option, text, expected);
    return value;
}

constexpr double kHuge = 1e300;

// "color.R" -> "R"; a dotless name stays whole.
std::string shortName(const std::string& channel) {
    const std::size_t dot = channel.rfind('.');
    return dot == std::string::npos ? channel : channel.substr(dot + 1);
}

std::string shortChannelList(const std::vector<std::string>& channels) {
    std::string out;
    for (const std::string& c : channels) out += (out.empty() ? "" : ",") + shortName(c);
    return out;
}

// One table row: layer, channels, max error, where, relMSE, pixels over, share, verdict.
std::vector<std::string> rowOf(const LayerDiff& l, const DiffThresholds& limits) {
    std::string why;
    const bool ok = withinThresholds(l, limits, &why);
    if (l.presence != LayerDiff::Presence::Both)
        return {l.name, shortChannelList(l.channels), "-", "-", "-", "-", "-", why};
    const bool differs = l.maxError > 0.0;
    const std::string where =
        differs ? "(" + std::to_string(l.maxX) + ", " + std::to_string(l.maxY) + ") " + l.maxChannel
                : "-";
    const std::string verdict = l.identical ? "bit-identical"
                                : ok        ? (differs ? "within" : "equal")
                                            : "beyond: " + why;
    return {l.name,
            shortChannelList(l.channels),
            number(l.maxError),
            where,
            number(l.relMse),
            std::to_string(l.pixelsOver),
            number(100.0 * l.shareOver) + "%",
            verdict};
}

void printTable(std::ostream& out, const std::vector<std::vector<std::string>>& rows) {
    std::vector<std::size_t> width(rows.front().size(), 0);
    for (const auto& row : rows)
        for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    for (const auto& row : rows) {
        std::string line;
        for (std::size_t c = 0; c < row.size(); ++c) {
            line += row[c];
            if (c + 1 < row.size()) line += std::string(width[c] - row[c].size() + 2, ' ');
        }
        out << line << "\n";
    }
}

// FLIP's line: which FLIP, then mean, weighted median and max with 6 decimals.
void printFlip(std::ostream& out, const FlipResult& r, const FlipFileOptions& options) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2);
    if (r.hdr)
        s << "HDR-FLIP (" << r.exposures << " exposures from " << r.startExposure << " to "
          << r.stopExposure << " stops, ";
    else s << "LDR-FLIP (";
    s << options.ppd << " pixels per degree): " << std::setprecision(6) << "mean " << r.stats.mean
      << ", weighted median " << r.stats.weightedMedian << ", max " << r.stats.max << "\n";
    if (!options.heatmap.empty())
        s << "FLIP heat map " << options.heatmap
          << ": the error per pixel on the magma map, black = 0 to pale yellow = 1\n";
    out << s.str();
}

}  // namespace

std::string channelList(const std::vector<std::string>& channels) {
    return shortChannelList(channels);
}

std::string number(double v) {
    if (std::isinf(v)) return "inf";
    std::ostringstream s;
    s << std::setprecision(4) << v;
    return s.str();
}

std::vector<CLI::Option*> addDiffFlags(CLI::App& cmd, DiffFlags& f, const std::string& group) {
    std::vector<CLI::Option*> added;
    added.push_back(cmd.add_option("--threshold", f.threshold,
                                   "Per-channel absolute difference above which a pixel counts "
                                   "as differing (0: any difference; a NaN against a number "
                                   "always does, and fails the layer)")
                        ->type_name("T")
                        ->capture_default_str());
    added.push_back(cmd.add_option_function<std::string>(
                           "--max-error", [&f](const std::string& v) { f.maxError = v; },
                           "Largest absolute difference a layer may have (default: not checked)")
                        ->type_name("E"));
    added.push_back(cmd.add_option_function<std::string>(
                           "--max-relmse", [&f](const std::string& v) { f.maxRelMse = v; },
                           "Largest relMSE a layer may have, mean of (A-B)^2/(B^2+0.01) "
                           "(default: not checked)")
                        ->type_name("R"));
    added.push_back(cmd.add_option("--max-share", f.maxShare,
                                   "Share of a layer's pixels, in [0, 1], that may differ by "
                                   "more than --threshold")
                        ->type_name("S")
                        ->capture_default_str());
    CLI::Option* heatmap =
        cmd.add_option_function<std::string>(
               "--heatmap", [&f](const std::string& v) { f.heatmap = v; },
               "Write a .png of where one layer differs (the colour unless --heatmap-layer): per "
               "pixel the largest difference over its channels, black where equal, dark red to "
               "white up to its largest or --heatmap-scale (the report gives the scale), blue "
               "for a NaN or infinity against another value")
            ->type_name("FILE.png");
    added.push_back(heatmap);
    added.push_back(cmd.add_option_function<std::string>(
                           "--heatmap-layer", [&f](const std::string& v) { f.heatmapLayer = v; },
                           "The layer the heat map shows, scaled on its own (default: color, "
                           "else a plain file's RGB, else the first layer in both files)")
                        ->type_name("NAME")
                        ->needs(heatmap));
    added.push_back(cmd.add_option_function<std::string>(
                           "--heatmap-scale", [&f](const std::string& v) { f.heatmapScale = v; },
                           "The difference the heat map draws white (a finite number > 0; "
                           "larger ones are white too): one scale for every pair of images "
                           "(default: the layer's largest difference)")
                        ->type_name("X")
                        ->needs(heatmap));
    for (CLI::Option* o : added) o->group(group);
    return added;
}

DiffSettings diffSettingsFrom(const DiffFlags& f) {
    DiffSettings s;
    s.compare.threshold =
        parseNumber("--threshold", f.threshold, 0.0, kHuge, "a finite number >= 0");
    if (f.maxError)
        s.limits.maxError =
            parseNumber("--max-error", *f.maxError, 0.0, kHuge, "a finite number >= 0");
    if (f.maxRelMse)
        s.limits.maxRelMse =
            parseNumber("--max-relmse", *f.maxRelMse, 0.0, kHuge, "a finite number >= 0");
    s.limits.maxShare = parseNumber("--max-share", f.maxShare, 0.0, 1.0, "a number in [0, 1]");
    if (f.heatmap) {
        const std::string& path = *f.heatmap;
        if (!isPngPath(path)) badValue("--heatmap", path, "a .png file");
        checkWritable(path);
        s.compare.heatmap = path;
    }
    if (f.heatmapLayer) s.compare.heatmapLayer = *f.heatmapLayer;
    if (f.heatmapScale)
        s.compare.heatmapScale =
            parseNumber("--heatmap-scale", *f.heatmapScale, 0.0, kHuge, "a finite number > 0");
    if (s.compare.heatmapScale && !(*s.compare.heatmapScale > 0.0))
        badValue("--heatmap-scale", *f.heatmapScale, "a finite number > 0");
    return s;
}

bool samePath(const std::string& a, const std::string& b) {
    std::error_code ea, eb;
    const std::filesystem::path pa = std::filesystem::weakly_canonical(a, ea);
    const std::filesystem::path pb = std::filesystem::weakly_canonical(b, eb);
    return ea || eb ? a == b : pa == pb;
}

void checkHeatmapApart(const std::string& heatmap, const std::vector<std::string>& images) {
    if (heatmap.empty()) return;
    for (const std::string& image : images)
        if (samePath(heatmap, image))
            throw std::invalid_argument("--heatmap: '" + heatmap + "' is an image being compared");
}

CLI::App* addDiffCommand(CLI::App& app, DiffOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "diff",
        "Compare an image with a reference (a golden image), layer by layer: the largest "
        "difference and where, relMSE, the pixels over a threshold; exit 1 beyond a threshold");
    cmd->add_option("A", o.a, "The image to check (EXR, PNG or any file OpenImageIO reads)")
        ->required()
        ->type_name("FILE");
    cmd->add_option("B", o.b, "The reference (golden) image, of the same size")
        ->required()
        ->type_name("FILE");
    cmd->add_option_function<std::string>(
           "--layers", [&o](const std::string& v) { o.layers = v; },
           "Compare only these layers, comma-separated (color, viewZ, ...; a plain RGB file's is "
           "RGB); default: every layer of either file")
        ->type_name("LIST");
    addDiffFlags(*cmd, o.flags, "Thresholds");
    cmd->add_flag("--flip", o.flip,
                  "Also print FLIP, a perceptual difference of the images' colour (layer color, "
                  "else R,G,B): its mean, weighted median and maximum over pixels, each in [0, 1] "
                  "(0: identical); HDR-FLIP when both files are linear (EXR), else LDR-FLIP. "
                  "Alone it sets no exit status (see --max-flip-mean)")
        ->group("FLIP");
    cmd->add_option_function<std::string>(
           "--flip-heatmap", [&o](const std::string& v) { o.flipHeatmap = v; },
           "Write FLIP's error per pixel as a .png on the magma colour map (black: 0, pale "
           "yellow: 1); implies --flip")
        ->type_name("FILE.png")
        ->group("FLIP");
    cmd->add_option_function<std::string>(
           "--max-flip-mean", [&o](const std::string& v) { o.maxFlipMean = v; },
           "Make FLIP part of the verdict: its mean above M differs (exit 1), like a layer beyond "
           "a threshold; implies --flip")
        ->type_name("M")
        ->group("FLIP");
    cmd->add_flag("--json", o.json,
                  "Print the report as one JSON document on stdout instead of the table "
                  "(docs/golden.md gives its keys); the exit status is the same");
    return cmd;
}

namespace {

// FLIP's figures and options, as printFlip prints them.
Json flipJson(const FlipResult& r, const FlipFileOptions& options,
              std::optional<double> maxFlipMean, bool beyond) {
    Json out = {{"hdr", r.hdr}, {"pixels_per_degree", options.ppd}};
    if (r.hdr) {
        out["exposures"] = r.exposures;
        out["start_exposure"] = r.startExposure;
        out["stop_exposure"] = r.stopExposure;
    }
    out["mean"] = r.stats.mean;
    out["weighted_median"] = r.stats.weightedMedian;
    out["max"] = r.stats.max;
    out["heatmap"] = options.heatmap.empty() ? Json(nullptr) : Json(options.heatmap);
    out["max_mean"] = maxFlipMean ? Json(*maxFlipMean) : Json(nullptr);
    out["beyond"] = beyond;
    return out;
}

}  // namespace

int diffImages(const std::string& a, const std::string& b, const DiffSettings& settings,
               std::ostream& out, const FlipFileOptions* flip, std::optional<double> maxFlipMean,
               Json* json) {
    const ImageDiff diff = compareImages(a, b, settings.compare);
    int beyond = 0, identical = 0;
    for (const LayerDiff& l : diff.layers) {
        beyond += withinThresholds(l, settings.limits) ? 0 : 1;
        identical += l.presence == LayerDiff::Presence::Both && l.identical ? 1 : 0;
    }
    // FLIP is a verdict only when a limit for it is given: its mean above the limit differs.
    std::optional<FlipResult> flipResult;
    if (flip) flipResult = flipImages(a, b, *flip);
    const bool flipBeyond = flipResult && maxFlipMean && !(flipResult->stats.mean <= *maxFlipMean);
    const int n = int(diff.layers.size());
    const int status = !diff.identical() && (flipBeyond || beyond > 0) ? kExitDiffer : kExitOk;

    if (json) {
        *json = {{"a", a}, {"reference", b}};
        json->update(imageDiffJson(diff, settings.limits));
        (*json)["verdict"] = diff.identical()    ? "bit-identical"
                             : status == kExitOk ? "within thresholds"
                                                 : "DIFFER";
        (*json)["layers_beyond"] = beyond;
        (*json)["layers_identical"] = identical;
        (*json)["heatmap"] = settings.compare.heatmap.empty()
                                 ? Json(nullptr)
                                 : Json({{"file", settings.compare.heatmap},
                                         {"layer", diff.heatLayer},
                                         {"scale", diff.heatScale}});
        (*json)["flip"] =
            flipResult ? flipJson(*flipResult, *flip, maxFlipMean, flipBeyond) : Json(nullptr);
        return status;
    }

    std::vector<std::vector<std::string>> rows{{"layer", "channels", "max error", "at (x, y)",
                                                "relMSE", "pixels over", "share", "verdict"}};
    for (const LayerDiff& l : diff.layers) rows.push_back(rowOf(l, settings.limits));
    printTable(out, rows);
    // A NaN or infinity against anything else is spelled out, not left to read from "inf".
    for (const LayerDiff& l : diff.layers)
        if (l.nonFinite > 0)
            out << l.name << ": " << l.nonFinite
                << (l.nonFinite == 1 ? " pixel has" : " pixels have")
                << " a NaN or infinity against a different value (max error and relMSE inf)\n";
    if (!settings.compare.heatmap.empty())
        out << "heat map " << settings.compare.heatmap << " of layer "
            << (diff.heatLayer.empty() ? std::string("-") : diff.heatLayer)
            << ": black = equal, dark red to white = a difference up to " << number(diff.heatScale)
            << (settings.compare.heatmapScale ? " (--heatmap-scale"
                                              : " (the layer's largest finite one")
            << "; any difference at least dark red), blue = a NaN or infinity against a "
               "different value\n";
    if (flipResult) {
        printFlip(out, *flipResult, *flip);
        if (flipBeyond)
            out << "FLIP mean " << number(flipResult->stats.mean) << " > --max-flip-mean "
                << number(*maxFlipMean) << "\n";
    }
    const std::string pair = a + " against " + b + " (" + std::to_string(diff.width) + "x" +
                             std::to_string(diff.height) + ", " + plural(n, "layer") + ")";
    if (diff.identical()) out << "bit-identical: " << pair << "\n";
    else if (flipBeyond)
        out << "DIFFER: " << pair << ", FLIP's mean beyond --max-flip-mean, " << beyond << " of "
            << n << " layers beyond a threshold\n";
    else if (beyond == 0)
        out << "within thresholds: " << pair << ", " << identical << " of " << n
            << " bit-identical\n";
    else out << "DIFFER: " << pair << ", " << beyond << " of " << n << " beyond a threshold\n";
    return status;
}

int runDiff(const DiffOptions& o, std::ostream& out) {
    DiffSettings settings = diffSettingsFrom(o.flags);
    checkHeatmapApart(settings.compare.heatmap, {o.a, o.b});
    if (o.layers) settings.compare.layers = splitList("--layers", *o.layers);
    std::optional<double> maxFlipMean;
    if (o.maxFlipMean)
        maxFlipMean =
            parseNumber("--max-flip-mean", *o.maxFlipMean, 0.0, 1.0, "a number in [0, 1]");
    Json json;
    Json* report = o.json ? &json : nullptr;
    const auto printed = [&](int status) {
        if (report) printJson(out, json);
        return status;
    };
    if (!o.flip && !o.flipHeatmap && !maxFlipMean)
        return printed(diffImages(o.a, o.b, settings, out, nullptr, std::nullopt, report));
    FlipFileOptions flip;
    if (o.flipHeatmap) {
        if (!isPngPath(*o.flipHeatmap)) badValue("--flip-heatmap", *o.flipHeatmap, "a .png file");
        checkWritable(*o.flipHeatmap);
        for (const std::string& image : {o.a, o.b})
            if (samePath(*o.flipHeatmap, image))
                throw std::invalid_argument("--flip-heatmap: '" + *o.flipHeatmap +
                                            "' is an image being compared");
        if (!settings.compare.heatmap.empty() && samePath(*o.flipHeatmap, settings.compare.heatmap))
            throw std::invalid_argument("--flip-heatmap: '" + *o.flipHeatmap +
                                        "' is also --heatmap");
        flip.heatmap = *o.flipHeatmap;
    }
    return printed(diffImages(o.a, o.b, settings, out, &flip, maxFlipMean, report));
}

}  // namespace ssrt::cli
