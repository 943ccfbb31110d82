#include "cli/suite_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/isa.h"
#include "core/suggest.h"

namespace ssrt::cli {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// The keys each object of the file may hold (one place: parsing and the messages use them).
const std::vector<std::string> kSuiteKeys = {"cases"};
const std::vector<std::string> kCaseKeys = {"name",      "shot",   "render",     "frame",
                                            "reference", "layers", "alternates", "flip"};
const std::vector<std::string> kRuleKeys = {"threshold", "maxDifference", "pixels", "buckets",
                                            "hardLimit"};
const std::vector<std::string> kFlipKeys = {"mean", "max"};
const std::vector<std::string> kAlternateKeys = {"reference", "arch", "cpu"};
// `ssrt render` flags the runner itself gives a case's render.
const std::vector<std::string> kOwnedFlags = {"-o", "--output", "--compare", "--shard"};

std::string commaList(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

// Errors name the file and the JSON path of the field.
class Reader {
public:
    explicit Reader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        throw std::runtime_error(file_ + ": " + (path.empty() ? "" : path + ": ") + problem);
    }

    void object(const json& j, const std::string& path,
                const std::vector<std::string>& allowed) const {
        if (!j.is_object()) fail(path, "expected an object");
        for (const auto& item : j.items())
            if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end())
                fail(path + "." + item.key(), "unknown key" + didYouMean(item.key(), allowed) +
                                                  " (expected one of: " + commaList(allowed) + ")");
    }

    std::string string(const json& j, const std::string& path) const {
        if (!j.is_string() || j.get<std::string>().empty())
            fail(path, "expected a non-empty string");
        return j.get<std::string>();
    }

    double nonNegative(const json& j, const std::string& path) const {
        if (!j.is_number() || !std::isfinite(j.get<double>()) || j.get<double>() < 0.0)
            fail(path, "expected a finite number >= 0");
        return j.get<double>();
    }

    // N (meaning [N / 10, N]) or [lo, hi] with 0 <= lo <= hi.
    Range range(const json& j, const std::string& path) const {
        const std::string expected = "expected a number N >= 0 (the range [N/10, N]) or [lo, hi]";
        if (j.is_number()) {
            const double n = nonNegative(j, path);
            return {n / 10.0, n, true};
        }
        if (!j.is_array() || j.size() != 2) fail(path, expected);
        const Range r{nonNegative(j[0], path + "[0]"), nonNegative(j[1], path + "[1]")};
        if (r.lo > r.hi) fail(path, "expected lo <= hi");
        return r;
    }

    // A file relative to the suite's folder that must exist.
    std::string existingFile(const json& j, const std::string& path,
                             const std::string& folder) const {
        const std::string value = string(j, path);
        std::error_code ec;
        if (!fs::is_regular_file(fs::path(folder) / value, ec))
            fail(path, "no such file '" + value + "'");
        return value;
    }

private:
    std::string file_;
};

// The document, its first duplicate key an error (nlohmann-json keeps the last silently).
json parseDocument(const std::string& text, const Reader& r) {
    std::vector<std::set<std::string>> keys;
    std::optional<std::string> duplicate;
    const json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
        if (event == json::parse_event_t::object_start) keys.emplace_back();
        else if (event == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
        else if (event == json::parse_event_t::key && !keys.empty() &&
                 !keys.back().insert(parsed.get<std::string>()).second && !duplicate)
            duplicate = parsed.get<std::string>();
        return true;
    };
    json doc;
    try {
        doc = json::parse(text, callback);
    } catch (const json::exception& e) {
        std::string what = e.what();
        if (const std::size_t at = what.find("] "); at != std::string::npos)
            what = what.substr(at + 2);
        r.fail("", "not valid JSON: " + what);
    }
    if (duplicate) r.fail("", "duplicate key '" + *duplicate + "'");
    return doc;
}

LayerRule parseRule(const json& j, const std::string& path, const Reader& r) {
    LayerRule rule;
    if (j.is_string() && j.get<std::string>() == "exact") return rule;
    const auto expected = [&] {
        r.fail(path, "expected \"exact\" or an object with one or more of " + commaList(kRuleKeys));
    };
    if (!j.is_object()) expected();
    r.object(j, path, kRuleKeys);
    rule.exact = false;
    if (j.contains("threshold"))
        rule.threshold = r.nonNegative(j["threshold"], path + ".threshold");
    if (j.contains("maxDifference"))
        rule.maxDifference = r.range(j["maxDifference"], path + ".maxDifference");
    if (j.contains("pixels")) rule.pixels = r.range(j["pixels"], path + ".pixels");
    if (j.contains("hardLimit"))
        rule.hardLimit = r.nonNegative(j["hardLimit"], path + ".hardLimit");
    if (j.contains("buckets")) {
        const json& b = j["buckets"];
        if (!b.is_array() || b.empty())
            r.fail(path + ".buckets", "expected [[threshold, pixels], ...]");
        for (std::size_t i = 0; i < b.size(); ++i) {
            const std::string p = path + ".buckets[" + std::to_string(i) + "]";
            if (!b[i].is_array() || b[i].size() != 2 || !b[i][1].is_number_unsigned())
                r.fail(p, "expected [threshold, pixels], pixels an integer >= 0");
            rule.buckets.push_back({r.nonNegative(b[i][0], p + "[0]"), b[i][1].get<uint64_t>()});
        }
    }
    if (!rule.maxDifference && !rule.pixels && rule.buckets.empty() && !rule.hardLimit) expected();
    return rule;
}

FlipRule parseFlip(const json& j, const std::string& path, const Reader& r) {
    r.object(j, path, kFlipKeys);
    FlipRule rule;
    if (j.contains("mean")) rule.mean = r.range(j["mean"], path + ".mean");
    if (j.contains("max")) rule.max = r.range(j["max"], path + ".max");
    if (!rule.mean && !rule.max) r.fail(path, "expected mean and/or max");
    return rule;
}

std::vector<std::string> parseArgs(const json& j, const std::string& path, const Reader& r) {
    if (!j.is_array()) r.fail(path, "expected an array of `ssrt render` flags (strings)");
    std::vector<std::string> args;
    for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string p = path + "[" + std::to_string(i) + "]";
        if (!j[i].is_string()) r.fail(p, "expected a string");
        const std::string a = j[i].get<std::string>();
        for (const std::string& owned : kOwnedFlags)
            if (a == owned || a.rfind(owned + "=", 0) == 0)
                r.fail(p, "'" + owned + "' is the runner's (it writes the render and compares it)");
        args.push_back(a);
    }
    return args;
}

void checkName(const std::string& name, const std::string& path, const Reader& r) {
    const bool ok = std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
    });
    if (!ok || name == "." || name == "..")
        r.fail(path, "expected a name of letters, digits, '.', '_' and '-' (it names a folder)");
}

void checkReferenceFormat(const std::string& ref, const std::string& path, const Reader& r) {
    std::string ext = fs::path(ref).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext != ".exr" && ext != ".png")
        r.fail(path, "expected an .exr or .png file (the render is written in its format)");
}

SuiteCase parseCase(const json& j, const std::string& path, const std::string& folder,
                    const Reader& r) {
    r.object(j, path, kCaseKeys);
    SuiteCase c;
    if (!j.contains("name")) r.fail(path, "a case needs a name");
    c.name = r.string(j["name"], path + ".name");
    checkName(c.name, path + ".name", r);
    if (!j.contains("reference")) r.fail(path, "a case needs a reference");
    c.reference = r.string(j["reference"], path + ".reference");
    checkReferenceFormat(c.reference, path + ".reference", r);
    if (j.contains("shot")) c.shot = r.existingFile(j["shot"], path + ".shot", folder);
    if (j.contains("render")) c.args = parseArgs(j["render"], path + ".render", r);
    if (j.contains("frame")) {
        const json& f = j["frame"];
        if (!f.is_number_unsigned() || f.get<uint64_t>() > 99999)
            r.fail(path + ".frame", "expected an integer from 0 to 99999");
        c.frame = int(f.get<uint64_t>());
    }
    if (j.contains("layers")) {
        const json& layers = j["layers"];
        if (!layers.is_object()) r.fail(path + ".layers", "expected an object: layer -> rule");
        for (const auto& item : layers.items())
            c.layers[item.key()] = parseRule(item.value(), path + ".layers." + item.key(), r);
    }
    if (j.contains("flip")) c.flip = parseFlip(j["flip"], path + ".flip", r);
    if (j.contains("alternates")) {
        const json& alts = j["alternates"];
        if (!alts.is_array()) r.fail(path + ".alternates", "expected an array");
        for (std::size_t i = 0; i < alts.size(); ++i) {
            const std::string p = path + ".alternates[" + std::to_string(i) + "]";
            r.object(alts[i], p, kAlternateKeys);
            AlternateReference alt;
            if (!alts[i].contains("reference")) r.fail(p, "an alternate needs a reference");
            for (const auto& item : alts[i].items()) {
                const std::string value = r.string(item.value(), p + "." + item.key());
                if (item.key() == "reference") alt.reference = value;
                else alt.when[item.key()] = value;
            }
            checkReferenceFormat(alt.reference, p + ".reference", r);
            if (fs::path(alt.reference).extension() != fs::path(c.reference).extension())
                r.fail(p + ".reference", "expected the format of the case's reference");
            if (alt.when.empty()) r.fail(p, "expected a key it is chosen by: arch or cpu");
            c.alternates.push_back(std::move(alt));
        }
    }
    return c;
}

}  // namespace

Suite loadSuite(const std::string& path) {
    const Reader r(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) r.fail("", "cannot read the file");
    std::ostringstream text;
    text << in.rdbuf();
    const json doc = parseDocument(text.str(), r);
    r.object(doc, "", kSuiteKeys);
    Suite suite;
    suite.file = path;
    suite.folder = fs::absolute(path).parent_path().string();
    if (!doc.contains("cases") || !doc["cases"].is_array() || doc["cases"].empty())
        r.fail("cases", "expected a non-empty array of cases");
    std::set<std::string> names;
    for (std::size_t i = 0; i < doc["cases"].size(); ++i) {
        const std::string p = "cases[" + std::to_string(i) + "]";
        suite.cases.push_back(parseCase(doc["cases"][i], p, suite.folder, r));
        if (!names.insert(suite.cases.back().name).second)
            r.fail(p + ".name", "'" + suite.cases.back().name + "' names another case too");
    }
    return suite;
}

std::map<std::string, std::string> suiteMachineKeys() {
#if defined(__x86_64__)
    const std::string arch = "x86_64";
#elif defined(__aarch64__)
    const std::string arch = "aarch64";
#else
    const std::string arch = "other";
#endif
    const std::vector<Isa> isas = supportedIsas();
    return {{"arch", arch}, {"cpu", std::string(isaName(isas.back()))}};
}

std::string chosenReference(const SuiteCase& c, const std::map<std::string, std::string>& keys) {
    for (const AlternateReference& alt : c.alternates) {
        const bool matches = std::all_of(alt.when.begin(), alt.when.end(), [&](const auto& kv) {
            const auto it = keys.find(kv.first);
            return it != keys.end() && it->second == kv.second;
        });
        if (matches) return alt.reference;
    }
    return c.reference;
}

const LayerRule& ruleFor(const SuiteCase& c, const std::string& layer) {
    static const LayerRule kExact;
    if (const auto it = c.layers.find(layer); it != c.layers.end()) return it->second;
    if (const auto it = c.layers.find("*"); it != c.layers.end()) return it->second;
    return kExact;
}

std::vector<double> caseThresholds(const SuiteCase& c) {
    std::vector<double> out;
    const auto add = [&](double t) {
        if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
    };
    for (const auto& [name, rule] : c.layers) {
        add(rule.threshold);
        for (const Bucket& b : rule.buckets) add(b.threshold);
    }
    return out;
}

}  // namespace ssrt::cli
