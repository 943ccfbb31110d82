#include "cli/merge_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "cli/cli.h"
#include "cli/options.h"
#include "cli/reference_cache.h"
#include "cli/reference_command.h"
#include "cli/shard.h"
#include "io/image_io.h"
#include "io/image_limits.h"

namespace ssrt::cli {

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------
// Parts

struct Part {
    std::string path;
    Shard shard;
};

[[noreturn]] void badPart(const std::string& path, const std::string& why) {
    throw std::runtime_error("merge: '" + path + "': " + why);
}

// The file shard `index` writes, named like `part` (another shard of the same work): what a
// missing part is called.
std::string siblingPart(const Part& part, int index) {
    const fs::path p(part.path);
    const std::string name = p.filename().string();
    const std::string unsharded = name.substr(0, name.rfind(".shard-")) + p.extension().string();
    return shardFileName((p.parent_path() / unsharded).string(), Shard{index, part.shard.count});
}

// The parts in shard order, checked to be shards 1..N of one N, each once.
std::vector<Part> shardParts(const std::vector<std::string>& paths) {
    std::vector<Part> parts;
    for (const std::string& path : paths) {
        const std::optional<Shard> s = shardOfFileName(path);
        if (!s)
            badPart(path,
                    "not a shard's file (NAME.shard-K-of-N.EXT with K from 1 to N, as --shard "
                    "names it)");
        if (!parts.empty() && s->count != parts.front().shard.count)
            badPart(path, "a shard of " + std::to_string(s->count) + ", the others of " +
                              std::to_string(parts.front().shard.count));
        parts.push_back({path, *s});
    }
    std::sort(parts.begin(), parts.end(),
              [](const Part& a, const Part& b) { return a.shard.index < b.shard.index; });
    const int n = parts.front().shard.count;
    std::string missing, missingFiles;
    int missingCount = 0;
    for (int k = 0, i = 0; k < n; ++k) {
        if (i < int(parts.size()) && parts[i].shard.index == k) {
            if (i + 1 < int(parts.size()) && parts[i + 1].shard.index == k)
                badPart(parts[i + 1].path, "shard " + parts[i].shard.text() + " given twice");
            ++i;
        } else {
            missing += (missing.empty() ? "" : ", ") + std::to_string(k + 1);
            missingFiles += (missingFiles.empty() ? "" : ", ") + siblingPart(parts.front(), k);
            ++missingCount;
        }
    }
    if (missingCount > 0)
        throw std::runtime_error("merge: " + std::string(missingCount == 1 ? "shard " : "shards ") +
                                 missing + " of " + std::to_string(n) +
                                 (missingCount == 1 ? " is" : " are") + " missing (" +
                                 missingFiles + ")");
    return parts;
}

// ---------------------------------------------------------------------------------------
// CSV

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) badPart(path, "cannot be read");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// RFC 4180 records, each with its line break: a quoted field may hold commas and breaks.
std::vector<std::string> csvRecords(const std::string& text) {
    std::vector<std::string> records;
    std::string record;
    bool quoted = false;
    for (char c : text) {
        record += c;
        if (c == '"') quoted = !quoted;
        else if (c == '\n' && !quoted) records.push_back(std::move(record)), record.clear();
    }
    if (!record.empty()) records.push_back(record + "\n");
    return records;
}

// The first field of a record: the setting, a plain integer (never quoted).
long long settingOf(const std::string& path, const std::string& record) {
    const std::string first = record.substr(0, record.find_first_of(",\r\n"));
    try {
        return parseInteger("setting", first, 0, 1ll << 40);
    } catch (const std::invalid_argument&) {
        badPart(path, "a row whose setting is '" + first + "'");
    }
}

std::string mergeCsv(const std::vector<Part>& parts) {
    struct Row {
        long long setting;
        std::string record;
    };
    std::vector<Row> rows;
    std::string header;
    for (const Part& part : parts) {
        std::vector<std::string> records = csvRecords(readText(part.path));
        if (records.empty()) badPart(part.path, "empty (no header)");
        if (records[0].rfind("setting,", 0) != 0)
            badPart(part.path, "not a sweep CSV (its first column is not 'setting')");
        if (header.empty()) header = records[0];
        else if (records[0] != header) badPart(part.path, "its columns differ from the others'");
        for (std::size_t i = 1; i < records.size(); ++i) {
            const long long s = settingOf(part.path, records[i]);
            if (s % part.shard.count != part.shard.index)
                badPart(part.path, "holds setting " + std::to_string(s) + ", not shard " +
                                       part.shard.text() + "'s");
            rows.push_back({s, std::move(records[i])});
        }
    }
    // Parts are in shard order, so a stable sort keeps each setting's frames in order.
    std::stable_sort(rows.begin(), rows.end(),
                     [](const Row& a, const Row& b) { return a.setting < b.setting; });
    long long expected = 0;
    for (const Row& r : rows) {
        if (r.setting == expected) ++expected;
        else if (r.setting != expected - 1)
            throw std::runtime_error("merge: no row for setting " + std::to_string(expected) +
                                     " (a shard's file is not that sweep's)");
    }
    std::string text = header;
    for (const Row& r : rows) text += r.record;
    return text;
}

// ---------------------------------------------------------------------------------------
// Reference bands

std::pair<int, int> twoInts(const Part& part, const std::map<std::string, std::string>& attrs,
                            const char* name) {
    const auto it = attrs.find(name);
    if (it == attrs.end()) badPart(part.path, std::string("no ") + name + " attribute");
    std::istringstream s(it->second);
    int a = 0, b = 0;
    if (!(s >> a >> b)) badPart(part.path, std::string("a bad ") + name + " attribute");
    return {a, b};
}

struct ReferenceBands {
    ReferenceImage image;
    std::string cacheName;  // the cache's file name for it
};

ReferenceBands mergeReference(const std::vector<Part>& parts) {
    ReferenceBands out;
    int width = 0, height = 0, nextRow = 0;
    const std::vector<std::string> names = referenceChannelNames();
    std::vector<PlaneF*> planes;
    for (const Part& part : parts) {
        const auto attrs = readExrStringAttributes(part.path);
        const auto kind = attrs.find(kPartAttribute);
        if (kind == attrs.end() || kind->second != kReferencePart)
            badPart(part.path, "not a band of 'ssrt reference --shard'");
        const std::string shard = part.shard.text();
        const auto said = attrs.find(kShardAttribute);
        if (said == attrs.end() || said->second != shard)
            badPart(part.path, "its header says another shard than its name (" + shard + ")");
        const auto [w, h] = twoInts(part, attrs, kSizeAttribute);
        // Checked before the planes are made at that size.
        if (const std::optional<std::string> problem = imageSizeProblem(w, h))
            badPart(part.path, "its " + std::string(kSizeAttribute) + " attribute: " + *problem);
        const auto [y0, y1] = twoInts(part, attrs, kRowsAttribute);
        const auto key = attrs.find(kKeyAttribute);
        if (key == attrs.end()) badPart(part.path, "no reference key");
        if (planes.empty()) {
            width = w, height = h, out.cacheName = key->second;
            for (PlaneF* p : (planes = referencePlanes(out.image))) *p = PlaneF(w, h);
        } else if (w != width || h != height || key->second != out.cacheName) {
            badPart(part.path, "a band of another reference than '" + parts.front().path + "'");
        }
        if (y0 != nextRow || y1 <= y0 || y1 > height)
            badPart(part.path, "rows " + std::to_string(y0) + " to " + std::to_string(y1) +
                                   " do not follow row " + std::to_string(nextRow));
        int bw = 0, bh = 0;
        const std::vector<std::vector<float>> channels = readChannels(part.path, names, bw, bh);
        if (bw != width || bh != y1 - y0) badPart(part.path, "its size is not its rows'");
        for (std::size_t c = 0; c < names.size(); ++c)
            for (int y = y0; y < y1; ++y)
                std::copy_n(channels[c].data() + std::size_t(y - y0) * width, width,
                            planes[c]->row(y));
        nextRow = y1;
    }
    if (nextRow != height)
        throw std::runtime_error("merge: the bands end at row " + std::to_string(nextRow) + " of " +
                                 std::to_string(height));
    return out;
}

}  // namespace

CLI::App* addMergeCommand(CLI::App& app, MergeOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "merge",
        "Assemble the parts --shard K/N wrote (sweep CSVs, per-frame CSVs, reference bands) "
        "into what the unsharded run writes");
    cmd->add_option("-o,--output", o.output,
                    "The merged file: .csv (sweep parts) or .exr (reference bands)")
        ->type_name("FILE")
        ->required();
    cmd->add_option("parts", o.parts, "Every part: NAME.shard-K-of-N.EXT for K = 0 to N-1")
        ->type_name("PART")
        ->required();
    cmd->add_option_function<std::string>(
           "--cache-dir", [&o](const std::string& v) { o.cacheDir = v; },
           "Reference bands: also store the merged reference in this reference cache, where "
           "compare and sweep find it")
        ->type_name("DIR");
    cmd->add_flag("-q,--quiet", o.quiet, "No progress lines on stderr");
    return cmd;
}

int runMerge(const MergeOptions& o, std::ostream& /*out*/, std::ostream& err) {
    const bool csv = fs::path(o.output).extension() == ".csv";
    if (!csv && !isExrPath(o.output))
        throw std::invalid_argument("-o: '" + o.output +
                                    "': the merged file is a .csv (sweep) or .exr (reference)");
    if (csv && o.cacheDir)
        throw std::invalid_argument("--cache-dir: only reference bands (-o FILE.exr) are cached");
    for (const std::string& p : o.parts) {
        const std::string ext = fs::path(p).extension().string();
        if ((ext == ".csv") != csv)
            throw std::invalid_argument("'" + p + "': a part of another kind than -o '" + o.output +
                                        "'");
    }
    const std::vector<Part> parts = shardParts(o.parts);
    if (csv) {
        checkCsvPath("-o", o.output);
        writeTextFile(o.output, mergeCsv(parts));
    } else {
        checkWritable(o.output);
        const ReferenceBands merged = mergeReference(parts);
        writeReferenceImage(o.output, merged.image);
        if (o.cacheDir) {
            const std::string cached = writeCacheEntry(
                *o.cacheDir, referenceKeyOfCacheFileName(merged.cacheName), merged.image);
            if (!o.quiet) err << "stored " << cached << "\n";
        }
    }
    if (!o.quiet)
        err << "merged " << plural(int(parts.size()), "part") << " into " << o.output << "\n";
    return kExitOk;
}

}  // namespace ssrt::cli
