#include "core/suggest.h"

#include <algorithm>
#include <cctype>

namespace ssrt {

namespace {

char lower(char c) { return char(std::tolower(static_cast<unsigned char>(c))); }

}  // namespace

int editDistance(std::string_view a, std::string_view b) {
    // Three rows of the dynamic programme: i - 2, i - 1, i.
    const std::size_t n = b.size();
    std::vector<int> before(n + 1), last(n + 1), row(n + 1);
    for (std::size_t j = 0; j <= n; ++j) last[j] = int(j);
    for (std::size_t i = 1; i <= a.size(); ++i) {
        row[0] = int(i);
        for (std::size_t j = 1; j <= n; ++j) {
            const bool same = lower(a[i - 1]) == lower(b[j - 1]);
            row[j] = std::min({last[j] + 1, row[j - 1] + 1, last[j - 1] + (same ? 0 : 1)});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1]))
                row[j] = std::min(row[j], before[j - 2] + 1);
        }
        std::swap(before, last);
        std::swap(last, row);
    }
    return last[n];
}

std::string nearestName(std::string_view typed, const std::vector<std::string>& known) {
    const int reach = std::clamp(int(typed.size()) / 3, 1, 3);
    std::string best;
    int bestDistance = reach + 1;
    for (const std::string& name : known) {
        const int d = editDistance(typed, name);
        if (d < bestDistance) best = name, bestDistance = d;
    }
    return best;
}

std::string didYouMean(std::string_view typed, const std::vector<std::string>& known) {
    const std::string name = nearestName(typed, known);
    return name.empty() ? std::string() : "; did you mean " + name + "?";
}

}  // namespace ssrt
