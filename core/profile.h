// Where a render's time goes, as slices of time per thread, for `ssrt render --profile`
// (cli/profile_file.h writes them as a Chrome trace-event file). A caller sets a sink on its
// own thread (ProfileTarget); what runs on that thread opens named scopes (ProfileScope: the
// frame, each pass), and every loop over tiles started under a scope records each index it
// runs, on the thread that runs it, and one slice of the scope's name on every other thread
// that took part (core/tiles.h). So each thread's slices nest: a pass, its tiles, a tile's
// stages. Without a sink nothing is recorded and no clock is read; with one only clocks are
// read: no pixel depends on it.
#pragma once

#include <chrono>
#include <string_view>
#include <thread>

namespace ssrt {

using ProfileClock = std::chrono::steady_clock;

// Takes slices from any thread at once.
class ProfileSink {
public:
    virtual ~ProfileSink() = default;
    // A slice [begin, end) on `thread`.
    virtual void slice(std::string_view name, std::thread::id thread,
                       ProfileClock::time_point begin, ProfileClock::time_point end) = 0;
};

// The sink set on the calling thread (null: none).
ProfileSink* profileSink();
// The name of the innermost scope open on the calling thread ("" without one).
std::string_view profileScopeName();

// Sets the calling thread's sink while it lives (null: none), the one before it after.
class ProfileTarget {
public:
    explicit ProfileTarget(ProfileSink* sink);
    ~ProfileTarget();
    ProfileTarget(const ProfileTarget&) = delete;
    ProfileTarget& operator=(const ProfileTarget&) = delete;

private:
    ProfileSink* previous_;
};

// A slice on the calling thread from construction to destruction, named `name` (which must
// live as long as the scope), when the thread has a sink; the innermost scope's name names
// the loops over tiles started inside it. None inside a scope of the same name (a pass's own
// timer inside the scheduler's scope of the pass).
class ProfileScope {
public:
    explicit ProfileScope(std::string_view name);
    ~ProfileScope();
    ProfileScope(const ProfileScope&) = delete;
    ProfileScope& operator=(const ProfileScope&) = delete;

private:
    ProfileSink* sink_;
    std::string_view name_, outer_;
    ProfileClock::time_point begin_;
};

}  // namespace ssrt
