#include "cli/shard.h"

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <stdexcept>

#include "cli/options.h"

namespace ssrt::cli {

namespace fs = std::filesystem;

namespace {

// A Slurm variable as an integer, or none when unset; a set but malformed one is an error.
std::optional<long long> slurmVariable(const char* name) {
    const char* v = std::getenv(name);
    if (!v || !*v) return std::nullopt;
    try {
        return parseInteger(name, v, 0, 4294967295ll);
    } catch (const std::invalid_argument&) {
        throw std::invalid_argument(std::string("environment variable ") + name + "='" + v +
                                    "' is not a whole number");
    }
}

}  // namespace

std::string Shard::text() const { return std::to_string(number()) + "/" + std::to_string(count); }

Shard parseShard(const std::string& option, const std::string& text) {
    const std::size_t slash = text.find('/');
    if (slash == std::string::npos) badValue(option, text, "K/N, shard K (from 1) of N, e.g. 1/4");
    Shard s;
    s.count = int(parseInteger(option, text.substr(slash + 1), 1, kMaxShards));
    const std::string k = text.substr(0, slash), n = std::to_string(s.count);
    if (k == "0")
        badValue(option, text,
                 "K/N with K from 1 to N: shards count from 1, so 1/" + n + " is the first of " +
                     n + " and " + n + "/" + n + " the last");
    s.index = int(parseInteger(option, k, 1, s.count)) - 1;
    return s;
}

Shard shardFrom(const std::optional<std::string>& option, std::string* source) {
    if (option) {
        if (source) *source = "--shard";
        return parseShard("--shard", *option);
    }
    const std::optional<long long> id = slurmVariable("SLURM_ARRAY_TASK_ID");
    const std::optional<long long> count = slurmVariable("SLURM_ARRAY_TASK_COUNT");
    if (!id && !count) return Shard{};
    if (!id || !count)
        throw std::invalid_argument(
            "SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT must be set together (or give "
            "--shard K/N)");
    const long long min = slurmVariable("SLURM_ARRAY_TASK_MIN").value_or(0);
    const long long k = *id - min;
    if (*count < 1 || *count > kMaxShards || k < 0 || k >= *count)
        throw std::invalid_argument(
            "the Slurm array task " + std::to_string(*id) + " (min " + std::to_string(min) + ", " +
            std::to_string(*count) +
            " tasks) is not one of a contiguous array (submit with --array=0-N or give "
            "--shard K/N)");
    if (source) *source = "SLURM_ARRAY_TASK_ID";
    return Shard{int(k), int(*count)};
}

void addShardOption(CLI::App& cmd, std::optional<std::string>& value, const std::string& what) {
    cmd.add_option("--shard", value,
                   "Do part K (from 1) of N of the work and write it to NAME.shard-K-of-N.EXT (" +
                       what +
                       "); 'ssrt merge' assembles the parts. Inside a Slurm job array the "
                       "task's SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT give it")
        ->type_name("K/N")
        ->group("Batch");
}

std::string shardFileName(const std::string& path, const Shard& shard) {
    if (!shard.sharded()) return path;
    const fs::path p(path);
    std::string name = p.stem().string();
    name.append(".shard-")
        .append(std::to_string(shard.number()))
        .append("-of-")
        .append(std::to_string(shard.count))
        .append(p.extension().string());
    return (p.parent_path() / name).string();
}

std::optional<Shard> shardOfFileName(const std::string& path) {
    static const std::regex pattern(R"(.*\.shard-([0-9]{1,6})-of-([0-9]{1,6})\.[^.]*)");
    std::smatch m;
    const std::string name = fs::path(path).filename().string();
    if (!std::regex_match(name, m, pattern)) return std::nullopt;
    const int k = std::stoi(m[1]), n = std::stoi(m[2]);
    if (n < 2 || n > kMaxShards || k < 1 || k > n) return std::nullopt;
    return Shard{k - 1, n};
}

ItemRange shardBlock(const Shard& shard, long long total) {
    return {total * shard.index / shard.count, total * (shard.index + 1) / shard.count};
}

std::string describeShard(const Shard& shard, const std::string& source) {
    return "shard " + shard.text() +
           (source == "--shard" || source.empty() ? std::string() : " (" + source + ")");
}

}  // namespace ssrt::cli
