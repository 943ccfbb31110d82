// `ssrt merge -o OUT PARTS...`: assembles the files the shards of one piece of batch work
// wrote (cli/shard.h) into what the unsharded run writes.
//   OUT.csv  sweep CSVs (or their --per-frame CSVs): the parts' rows ordered by their first
//            column, `setting` (stable, so a setting's frames keep their order); every part
//            must hold exactly its own settings (i % N == K) and together they must hold
//            settings 0..M-1: every column equals the unsharded CSV's but the timings.
//   OUT.exr  `ssrt reference --shard` bands: the rows put back in place, the file written as
//            the unsharded command writes it (the same bytes); --cache-dir also stores it in
//            the reference cache under its key, for compare and sweep to find.
// The parts must be named as the shards name them (NAME.shard-K-of-N.EXT), one per K of one
// N; a missing, repeated or foreign part is an error naming it, and nothing is written.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace ssrt::cli {

struct MergeOptions {
    std::string output;
    std::vector<std::string> parts;
    std::optional<std::string> cacheDir;  // EXR: also store the reference in this cache
    bool quiet = false;
};

CLI::App* addMergeCommand(CLI::App& app, MergeOptions& options);
int runMerge(const MergeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace ssrt::cli
