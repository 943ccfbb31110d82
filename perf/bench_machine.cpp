// What this machine allows, the limits a pass's bytes and gathers are set against
// (perf/README.md, "The frame against the machine"): memory read and copy bandwidth over
// buffers far past the caches, the FMA rate, and the rate of hardware gathers (AVX-512, else AVX2)
// from a table that fits L1, L2, or neither, with 1 and 2 threads (x86-64 only: NEON has no
// gather).
//
//   ./build/perf/ssrt_bench --benchmark_filter=Machine
#include <benchmark/benchmark.h>
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

#include "core/aligned.h"
#include "core/rng.h"

namespace {

using Floats = std::vector<float, ssrt::AlignedAllocator<float, 64>>;

constexpr std::size_t kStreamBytes = std::size_t(512) << 20;  // far past any last-level cache

// Runs fn(part) on `threads` threads, part = 0 .. threads-1, and waits.
template <class Fn>
void onThreads(int threads, Fn&& fn) {
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back([&, t] { fn(t); });
    fn(0);
    for (std::thread& th : pool) th.join();
}

// Integer sums, so the compiler vectorises the loop (a float sum must keep its order).
uint64_t sumWords(const uint32_t* p, std::size_t n) {
    uint64_t a = 0, b = 0, c = 0, d = 0;
    for (std::size_t i = 0; i + 4 <= n; i += 4)
        a += p[i], b += p[i + 1], c += p[i + 2], d += p[i + 3];
    return a + b + c + d;
}

#if defined(__x86_64__)
// The same read with AVX2 loads and four independent XORs a cache line: the SSE2 sum above
// widens every word and tops out near 7 GB/s a thread, under what the memory gives.
__attribute__((target("avx2"))) uint64_t xorWords(const uint32_t* p, std::size_t n) {
    __m256i a = _mm256_setzero_si256(), b = a, c = a, d = a;
    for (std::size_t i = 0; i + 32 <= n; i += 32) {
        const auto* v = reinterpret_cast<const __m256i*>(p + i);
        a = _mm256_xor_si256(a, _mm256_load_si256(v));
        b = _mm256_xor_si256(b, _mm256_load_si256(v + 1));
        c = _mm256_xor_si256(c, _mm256_load_si256(v + 2));
        d = _mm256_xor_si256(d, _mm256_load_si256(v + 3));
    }
    alignas(32) uint64_t lanes[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes),
                       _mm256_xor_si256(_mm256_xor_si256(a, b), _mm256_xor_si256(c, d)));
    return lanes[0] ^ lanes[1] ^ lanes[2] ^ lanes[3];
}
#endif

uint64_t readWords(const uint32_t* p, std::size_t n) {
#if defined(__x86_64__)
    if (__builtin_cpu_supports("avx2")) return xorWords(p, n);
#endif
    return sumWords(p, n);
}

void BM_MachineRead(benchmark::State& state) {
    const int threads = int(state.range(0));
    const std::size_t n = kStreamBytes / sizeof(uint32_t);
    std::vector<uint32_t, ssrt::AlignedAllocator<uint32_t, 64>> buffer(n, 1u);
    std::vector<uint64_t> sums(std::size_t(threads), 0);
    for (auto _ : state) {
        onThreads(threads, [&](int t) {
            const std::size_t part = n / std::size_t(threads);
            sums[std::size_t(t)] = readWords(buffer.data() + part * std::size_t(t), part);
        });
        benchmark::DoNotOptimize(sums.data());
    }
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(kStreamBytes));
}

void BM_MachineCopy(benchmark::State& state) {
    const int threads = int(state.range(0));
    const std::size_t n = kStreamBytes / 2 / sizeof(float);
    Floats from(n, 1.0f), to(n, 0.0f);
    for (auto _ : state) {
        onThreads(threads, [&](int t) {
            const std::size_t part = n / std::size_t(threads), at = part * std::size_t(t);
            std::memcpy(to.data() + at, from.data() + at, part * sizeof(float));
        });
        benchmark::ClobberMemory();
    }
    // Bytes read plus bytes written.
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(kStreamBytes));
}

// Random indices into a table of `tableFloats`, 64 Ki of them (256 KiB: they stay in L2).
std::vector<int32_t> randomIndices(std::size_t tableFloats) {
    std::vector<int32_t> idx(std::size_t(1) << 16);
    for (std::size_t i = 0; i < idx.size(); ++i)
        idx[i] = int32_t(ssrt::pcgHash(uint32_t(i)) % uint32_t(tableFloats));
    return idx;
}

#if defined(__x86_64__)
__attribute__((target("avx512f"))) float gather512(const float* table, const int32_t* idx,
                                                   std::size_t n, int rounds) {
    __m512 acc = _mm512_setzero_ps();
    for (int r = 0; r < rounds; ++r)
        for (std::size_t i = 0; i < n; i += 16)
            acc = _mm512_add_ps(
                acc, _mm512_mask_i32gather_ps(acc, 0xffff, _mm512_loadu_si512(idx + i), table, 4));
    alignas(64) float lanes[16];
    _mm512_store_ps(lanes, acc);
    return lanes[0] + lanes[15];
}

__attribute__((target("avx2"))) float gather256(const float* table, const int32_t* idx,
                                                std::size_t n, int rounds) {
    __m256 acc = _mm256_setzero_ps();
    for (int r = 0; r < rounds; ++r)
        for (std::size_t i = 0; i < n; i += 8)
            acc = _mm256_add_ps(
                acc, _mm256_i32gather_ps(
                         table, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx + i)), 4));
    alignas(32) float lanes[8];
    _mm256_store_ps(lanes, acc);
    return lanes[0] + lanes[7];
}

// The FMA rate: ten independent chains (more than an FMA's latency times the ports it issues
// on), so that the loop runs at the core's FMA throughput; items are lane FMAs.
constexpr int kFmaChains = 10;

__attribute__((target("avx512f"))) float fma512(std::int64_t rounds) {
    __m512 acc[kFmaChains];
    for (int c = 0; c < kFmaChains; ++c) acc[c] = _mm512_set1_ps(float(c));
    const __m512 a = _mm512_set1_ps(0.999f), b = _mm512_set1_ps(1e-3f);
    for (std::int64_t r = 0; r < rounds; ++r)
        for (int c = 0; c < kFmaChains; ++c) acc[c] = _mm512_fmadd_ps(acc[c], a, b);
    for (int c = 1; c < kFmaChains; ++c) acc[0] = _mm512_add_ps(acc[0], acc[c]);
    return _mm512_reduce_add_ps(acc[0]);
}

__attribute__((target("avx2,fma"))) float fma256(std::int64_t rounds) {
    __m256 acc[kFmaChains];
    for (int c = 0; c < kFmaChains; ++c) acc[c] = _mm256_set1_ps(float(c));
    const __m256 a = _mm256_set1_ps(0.999f), b = _mm256_set1_ps(1e-3f);
    for (std::int64_t r = 0; r < rounds; ++r)
        for (int c = 0; c < kFmaChains; ++c) acc[c] = _mm256_fmadd_ps(acc[c], a, b);
    for (int c = 1; c < kFmaChains; ++c) acc[0] = _mm256_add_ps(acc[0], acc[c]);
    alignas(32) float lanes[8];
    _mm256_store_ps(lanes, acc[0]);
    return lanes[0] + lanes[7];
}

// Args: threads. Items are lane FMAs (16 a vector with AVX-512, 8 with AVX2).
void BM_MachineFma(benchmark::State& state) {
    const bool avx512 = __builtin_cpu_supports("avx512f");
    if (!avx512 && !__builtin_cpu_supports("fma")) return state.SkipWithError("no FMA");
    const int threads = int(state.range(0));
    constexpr std::int64_t kRounds = 1 << 22;
    std::vector<float> sink(static_cast<std::size_t>(threads));
    for (auto _ : state) {
        onThreads(threads, [&](int t) {
            sink[std::size_t(t)] = avx512 ? fma512(kRounds) : fma256(kRounds);
        });
        benchmark::DoNotOptimize(sink.data());
    }
    const std::int64_t lanes = avx512 ? 16 : 8;
    state.SetItemsProcessed(int64_t(state.iterations()) * kRounds * kFmaChains * lanes * threads);
    state.SetLabel(avx512 ? "avx512" : "avx2");
}

// Args: table KiB, threads. Items are gathered floats.
void BM_MachineGather(benchmark::State& state) {
    const bool avx512 = __builtin_cpu_supports("avx512f");
    if (!avx512 && !__builtin_cpu_supports("avx2")) return state.SkipWithError("no AVX2");
    const std::size_t tableFloats = std::size_t(state.range(0)) * 1024 / sizeof(float);
    const int threads = int(state.range(1));
    const Floats table(tableFloats, 1.0f);
    const std::vector<int32_t> idx = randomIndices(tableFloats);
    constexpr int kRounds = 32;
    std::vector<float> sink(static_cast<std::size_t>(threads));
    for (auto _ : state) {
        onThreads(threads, [&](int t) {
            sink[std::size_t(t)] = avx512
                                       ? gather512(table.data(), idx.data(), idx.size(), kRounds)
                                       : gather256(table.data(), idx.data(), idx.size(), kRounds);
        });
        benchmark::DoNotOptimize(sink.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(idx.size()) * kRounds * threads);
    state.SetLabel(avx512 ? "avx512" : "avx2");
}
#endif

}  // namespace

BENCHMARK(BM_MachineRead)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MachineCopy)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
#if defined(__x86_64__)
BENCHMARK(BM_MachineFma)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MachineGather)
    ->ArgsProduct({{16, 512, 32768}, {1, 2}})
    ->ArgNames({"table_KiB", "threads"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
#endif
