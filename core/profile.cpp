#include "core/profile.h"

namespace ssrt {

namespace {

thread_local ProfileSink* tSink = nullptr;
thread_local std::string_view tScope;

}  // namespace

ProfileSink* profileSink() { return tSink; }
std::string_view profileScopeName() { return tScope; }

ProfileTarget::ProfileTarget(ProfileSink* sink) : previous_(tSink) { tSink = sink; }
ProfileTarget::~ProfileTarget() { tSink = previous_; }

ProfileScope::ProfileScope(std::string_view name)
    : sink_(name == tScope ? nullptr : tSink), name_(name), outer_(tScope) {
    if (!sink_) return;
    tScope = name;
    begin_ = ProfileClock::now();
}

ProfileScope::~ProfileScope() {
    if (!sink_) return;
    sink_->slice(name_, std::this_thread::get_id(), begin_, ProfileClock::now());
    tScope = outer_;
}

}  // namespace ssrt
