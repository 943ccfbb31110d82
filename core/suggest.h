// "Did you mean ...?": the known name nearest a mistyped one, for error messages (options,
// commands, scenes, settings keys). One rule everywhere: the fewest single-character edits
// (insert, delete, replace, or swap two neighbours: optimal string alignment), ignoring case,
// and only within a third of the typed name's length (at least 1, at most 3), so that a name
// unlike every known one suggests nothing.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace ssrt {

// The edits between a and b, case ignored (ASCII).
int editDistance(std::string_view a, std::string_view b);

// The known name nearest `typed` within the rule above (the first of equals, in `known`'s
// order), or empty.
std::string nearestName(std::string_view typed, const std::vector<std::string>& known);

// "; did you mean NAME?" for the nearest name, or empty: for the end of a message's clause.
std::string didYouMean(std::string_view typed, const std::vector<std::string>& known);

}  // namespace ssrt
