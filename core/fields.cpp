#include "core/fields.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace ssrt {

namespace {

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

bool FieldInfo::accepts(double v) const {
    switch (type) {
        case FieldType::Bool: return v == 0.0 || v == 1.0;
        case FieldType::Choice: return v >= 0.0 && v < double(choiceCount) && v == std::floor(v);
        case FieldType::Int:
            if (v != std::floor(v)) return false;
            [[fallthrough]];
        case FieldType::Float:
            return std::isfinite(v) && (range.loOpen ? v > range.lo : v >= range.lo) &&
                   (range.hiOpen ? v < range.hi : v <= range.hi);
    }
    return false;
}

std::string FieldInfo::expected() const {
    switch (type) {
        case FieldType::Bool: return "true or false";
        case FieldType::Choice: return "one of " + choiceList();
        case FieldType::Int:
            return "an integer from " + std::to_string((long long)range.lo) + " to " +
                   std::to_string((long long)range.hi);
        case FieldType::Float:
            if (range.hi == kFieldFloatMax && !range.hiOpen)
                return "a finite number " + std::string(range.loOpen ? "> " : ">= ") +
                       number(range.lo);
            return "a number in " + std::string(range.loOpen ? "(" : "[") + number(range.lo) +
                   ", " + number(range.hi) + (range.hiOpen ? ")" : "]");
    }
    return "?";
}

std::string FieldInfo::text(double v) const {
    switch (type) {
        case FieldType::Bool: return v != 0.0 ? "true" : "false";
        case FieldType::Choice: return accepts(v) ? std::string(choiceName(int(v))) : number(v);
        case FieldType::Int: {
            std::ostringstream s;
            s.precision(17);
            s << v;
            return s.str();
        }
        case FieldType::Float: {
            // The shortest text that reads back as the same float ("0.1", not "0.100000001").
            char buf[32];
            const auto end = std::to_chars(buf, buf + sizeof buf, float(v)).ptr;
            return std::string(buf, end);
        }
    }
    return "?";
}

int FieldInfo::choiceIndex(std::string_view name) const {
    for (int i = 0; i < choiceCount; ++i)
        if (choiceName(i) == name) return i;
    return -1;
}

std::string FieldInfo::choiceList() const {
    std::string out;
    for (int i = 0; i < choiceCount; ++i) out += (i ? ", " : "") + std::string(choiceName(i));
    return out;
}

}  // namespace ssrt
