// Shards of batch work: `sweep`, a multi-frame `render` and `reference` split into N parts
// that run anywhere (a Slurm job array's tasks, several machines, one after another) and
// assemble, through `ssrt merge`, into exactly what the unsharded run gives. Every result of
// ssrt depends only on its inputs (the determinism contract), so a shard computes its part
// bit for bit as the whole run would; nothing is approximated at the seams.
//
// Shards count from 1, as the tools users shard with every day do (Jest, Playwright, Vitest:
// `--shard 1/2` and `--shard 2/2` are the two halves); inside, `Shard::index` counts from 0.
// Which part shard K of N takes, with k = K - 1:
//   sweep      settings i with i % N == k (round robin: the grid's costly settings, which its
//              nested lists put together, spread over the shards)
//   render     frames [k F / N, (k + 1) F / N) of F (a contiguous block), replayed from the
//              last point where the history restarts (frame 0 after its warm-up, or a camera
//              cut) without writing the frames before the block: the history they leave is
//              what the block's first frame reads, so its bits are the unsharded run's
//   reference  rows [k H / N, (k + 1) H / N) of H, in whole tiles (the renderer's tile rows)
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace ssrt::cli {

struct Shard {
    int index = 0;  // K - 1: from 0, for the arithmetic
    int count = 1;  // N; 1 is the whole work, unsharded
    bool sharded() const { return count > 1; }
    // K, from 1: what users type, read and find in file names.
    int number() const { return index + 1; }
    // "K/N", as --shard takes it.
    std::string text() const;
};

// The largest N: a sanity bound (a Slurm array holds at most MaxArraySize tasks, 1001 by
// default).
inline constexpr int kMaxShards = 100000;

// "K/N" with 1 <= K <= N <= kMaxShards; std::invalid_argument naming `option` otherwise (K = 0
// with a message that says how shards count).
Shard parseShard(const std::string& option, const std::string& text);

// The shard a command runs: --shard when given; else, inside a Slurm job array, the task's
// (shard SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN + 1 of SLURM_ARRAY_TASK_COUNT; an array
// must be contiguous, e.g. --array=0-3 or 1-4); else the whole work. Bad variables are an error, so
// a task never silently does all the work (or none). `source` is set to where it came from.
Shard shardFrom(const std::optional<std::string>& option, std::string* source = nullptr);

// Registers --shard K/N on a command; `what` says which part a shard takes.
void addShardOption(CLI::App& cmd, std::optional<std::string>& value, const std::string& what);

// The part's file: "out.csv" -> "out.shard-K-of-N.csv", K from 1 (the path unchanged when
// unsharded).
std::string shardFileName(const std::string& path, const Shard& shard);
// The shard a part's file name says (the inverse of shardFileName), or none.
std::optional<Shard> shardOfFileName(const std::string& path);

// [begin, end) of `total` items for a contiguous split: k total / N to (k + 1) total / N.
struct ItemRange {
    long long begin = 0, end = 0;
};
ItemRange shardBlock(const Shard& shard, long long total);

// "shard 2/4 (SLURM_ARRAY_TASK_ID)": for progress lines.
std::string describeShard(const Shard& shard, const std::string& source);

}  // namespace ssrt::cli
