// tests/thread_counts.h: the thread counts a bit-identity case compares, narrowed under an
// emulator (single) or ThreadSanitizer (parallel), and an unknown mode refused.
#include "thread_counts.h"

#include <doctest/doctest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// Sets SSRT_TEST_THREADS for one scope and puts back what was there.
class ThreadsMode {
public:
    explicit ThreadsMode(const char* mode) {
        if (const char* old = std::getenv("SSRT_TEST_THREADS")) old_ = old, had_ = true;
        if (mode) setenv("SSRT_TEST_THREADS", mode, 1);
        else unsetenv("SSRT_TEST_THREADS");
    }
    ~ThreadsMode() {
        if (had_) setenv("SSRT_TEST_THREADS", old_.c_str(), 1);
        else unsetenv("SSRT_TEST_THREADS");
    }

private:
    std::string old_;
    bool had_ = false;
};

}  // namespace

TEST_CASE("thread counts: every count named, one under an emulator, those over 1 under TSan") {
    {
        const ThreadsMode mode(nullptr);
        CHECK(testThreadCounts({1, 2, 8}) == std::vector<int>{1, 2, 8});
    }
    {
        const ThreadsMode mode("");
        CHECK(testThreadCounts({1, 3}) == std::vector<int>{1, 3});
    }
    {
        const ThreadsMode mode("single");
        CHECK(testThreadCounts({1, 2, 8}) == std::vector<int>{1});
        CHECK(testThreadCounts({2, 8}) == std::vector<int>{2});
    }
    {
        const ThreadsMode mode("parallel");
        CHECK(testThreadCounts({1, 2, 8}) == std::vector<int>{2, 8});
        CHECK(testThreadCounts({1, 3}) == std::vector<int>{3});
        CHECK(testThreadCounts({1}) == std::vector<int>{1});
    }
    {
        const ThreadsMode mode("Single");
        CHECK_THROWS_AS(testThreadCounts({1, 2}), std::invalid_argument);
    }
}
