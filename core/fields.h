// Field tables: a settings struct described once, as Mitsuba 3's traverse() and pbrt-v4's
// ParameterDictionary describe a plugin's parameters. Each entry names one member (its key,
// the member itself, its range, its help text and where it appears), and that one list
// drives the command-line flags, the shot-file keys, validate(), the reference cache key and
// --help. The default is the default-constructed struct's value.
//
// Every value travels as a double: the members are bools, enums, 32-bit integers and floats,
// each exact in one. The tables live beside their structs (trace/march_fields.h,
// renderer/settings_fields.h); fieldCount<S>() lets each table prove at compile time that it
// covers every member of its struct.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace ssrt {

enum class FieldType { Bool, Int, Float, Choice };

// Where a field appears (bits).
enum FieldUse : unsigned {
    kFieldCli = 1u,   // a command-line flag
    kFieldShot = 2u,  // a key of a shot file's "render" object
    kFieldKey = 4u,   // hashed into the reference cache key (it shapes the reference image)
};

// The values a number may take: [lo, hi], either end open. Floats without an upper bound use
// the largest float, so that every accepted value is finite.
struct FieldRange {
    double lo = 0.0, hi = 0.0;
    bool loOpen = false, hiOpen = false;
};

inline constexpr double kFieldFloatMax = std::numeric_limits<float>::max();

// A field without its member: what the places that parse, check and print need.
struct FieldInfo {
    std::string_view key;   // camelCase: the shot key ("shadowMapSize"); the flag derives from it
    std::string_view help;  // one line, without the range (the places that print it add that)
    FieldType type = FieldType::Int;
    unsigned uses = 0;  // FieldUse bits
    FieldRange range;   // Int and Float
    // Choice: the enum's values are 0 .. choiceCount - 1, named by choiceName.
    int choiceCount = 0;
    std::string_view (*choiceName)(int) = nullptr;
    std::string_view flag;      // given where the derived one will not do ("-j,--threads")
    std::string_view typeName;  // --help's placeholder; default INT, FLOAT or NAME

    bool has(unsigned use) const { return (uses & use) != 0; }
    // Whether `value` is one this field takes (NaN never is).
    bool accepts(double value) const;
    // What it takes, as the messages say it: "an integer from 1 to 8192", "a finite number > 0",
    // "a number in (0, 0.5]", "one of linear, dda, hiz", "true or false".
    std::string expected() const;
    // A value as text: "1280", "0.1", "hiz", "true".
    std::string text(double value) const;
    // The index of the choice named `name`, or -1.
    int choiceIndex(std::string_view name) const;
    // "linear, dda, hiz".
    std::string choiceList() const;
};

template <class S>
struct Field : FieldInfo {
    double (*get)(const S&) = nullptr;
    void (*set)(S&, double) = nullptr;
    const void* (*address)(const S&) = nullptr;  // the member's bytes (the cache key hashes them)
    std::size_t size = 0;                        // ... and how many

    // Builders, for tables that read as a list.
    constexpr Field ints(double lo, double hi) const {
        Field f = *this;
        f.range = {lo, hi, false, false};
        return f;
    }
    constexpr Field floats(double lo, bool loOpen, double hi = kFieldFloatMax,
                           bool hiOpen = false) const {
        Field f = *this;
        f.range = {lo, hi, loOpen, hiOpen};
        return f;
    }
    constexpr Field choices(int count, std::string_view (*name)(int)) const {
        Field f = *this;
        f.choiceCount = count;
        f.choiceName = name;
        return f;
    }
    constexpr Field withFlag(std::string_view flag) const {
        Field f = *this;
        f.flag = flag;
        return f;
    }
    constexpr Field withTypeName(std::string_view name) const {
        Field f = *this;
        f.typeName = name;
        return f;
    }
};

namespace fields_detail {

template <class M>
struct MemberOf;
template <class S, class T>
struct MemberOf<T S::*> {
    using Struct = S;
    using Type = T;
};

// Converts to anything: counts an aggregate's members by how many it initialises.
struct Any {
    template <class T>
    constexpr operator T() const {
        return T{};
    }
};
template <class T, std::size_t... I>
constexpr bool initialisesWith(std::index_sequence<I...>) {
    return requires { T{(void(I), Any{})...}; };
}

}  // namespace fields_detail

// The number of members of aggregate S (a nested struct counts as one).
template <class S, std::size_t N = 0>
constexpr std::size_t fieldCount() {
    if constexpr (!fields_detail::initialisesWith<S>(std::make_index_sequence<N + 1>{})) return N;
    else return fieldCount<S, N + 1>();
}

// The entry for member M: field<&MarchSettings::maxSteps>("maxSteps", uses, "help").ints(..).
template <auto M>
constexpr auto field(std::string_view key, unsigned uses, std::string_view help) {
    using S = typename fields_detail::MemberOf<decltype(M)>::Struct;
    using T = typename fields_detail::MemberOf<decltype(M)>::Type;
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    Field<S> f;
    f.key = key;
    f.help = help;
    f.uses = uses;
    f.type = std::is_same_v<T, bool> ? FieldType::Bool
             : std::is_enum_v<T>     ? FieldType::Choice
             : std::is_integral_v<T> ? FieldType::Int
                                     : FieldType::Float;
    if constexpr (std::is_same_v<T, bool>) f.range = {0, 1};
    if constexpr (std::is_enum_v<T>) {
        f.get = [](const S& s) { return double(static_cast<int>(s.*M)); };
        f.set = [](S& s, double v) { s.*M = static_cast<T>(static_cast<int>(v)); };
    } else {
        f.get = [](const S& s) { return double(s.*M); };
        f.set = [](S& s, double v) { s.*M = static_cast<T>(v); };
    }
    f.address = [](const S& s) -> const void* { return &(s.*M); };
    f.size = sizeof(T);
    return f;
}

namespace fields_detail {

template <auto Outer, const auto& Inner, std::size_t I>
constexpr auto lift() {
    using S = typename MemberOf<decltype(Outer)>::Struct;
    Field<S> f;
    static_cast<FieldInfo&>(f) = Inner[I];
    f.get = [](const S& s) { return Inner[I].get(s.*Outer); };
    f.set = [](S& s, double v) { Inner[I].set(s.*Outer, v); };
    f.address = [](const S& s) { return Inner[I].address(s.*Outer); };
    f.size = Inner[I].size;
    return f;
}

template <auto Outer, const auto& Inner, std::size_t... I>
constexpr auto liftAll(std::index_sequence<I...>) {
    using S = typename MemberOf<decltype(Outer)>::Struct;
    return std::array<Field<S>, sizeof...(I)>{lift<Outer, Inner, I>()...};
}

}  // namespace fields_detail

// The table of a nested struct's member, as fields of the outer struct (same keys).
template <auto Outer, const auto& Inner>
constexpr auto nestedFields() {
    return fields_detail::liftAll<Outer, Inner>(std::make_index_sequence<Inner.size()>{});
}

// Tables one after the other.
template <class S, std::size_t... N>
constexpr auto concatFields(const std::array<Field<S>, N>&... tables) {
    std::array<Field<S>, (N + ... + 0)> out{};
    std::size_t i = 0;
    ((std::copy(tables.begin(), tables.end(), out.begin() + i), i += N), ...);
    return out;
}

// Throws std::invalid_argument "<what>.<key>: expected <range> (got <value>)" for the first
// field of `table` whose value in `s` is out of its range.
template <class S, std::size_t N>
void checkFields(const std::array<Field<S>, N>& table, const S& s, std::string_view what) {
    for (const Field<S>& f : table) {
        const double v = f.get(s);
        if (!f.accepts(v))
            throw std::invalid_argument(std::string(what) + "." + std::string(f.key) +
                                        ": expected " + f.expected() + " (got " + f.text(v) + ")");
    }
}

}  // namespace ssrt
