#pragma once
// Enumerations named in text (command lines, reports, error messages): one table of
// {value, name} rows per enumeration, read both ways, so a name and its parse cannot disagree
// and every refusal lists what is known.
//
// Thread: any (constant data).

#include "hfx/core/Error.h"

#include <cstddef>
#include <string>
#include <string_view>

namespace hfx {

template <typename E>
struct NamedValue {
    E value;
    const char* name;
};

/// The name of `value` in `table`, or "?" for a value the table lacks.
template <typename E, std::size_t N>
const char* nameOf(const NamedValue<E> (&table)[N], E value) {
    for (const NamedValue<E>& row : table)
        if (row.value == value) return row.name;
    return "?";
}

/// "a, b, c": the table's names, for help texts.
template <typename E, std::size_t N>
std::string namesOf(const NamedValue<E> (&table)[N]) {
    std::string names;
    for (const NamedValue<E>& row : table) names += (names.empty() ? "" : ", ") + std::string(row.name);
    return names;
}

/// The value named `text`; throws hfx::Error "unknown WHAT 'text' (known: a, b, c)".
template <typename E, std::size_t N>
E parseName(const NamedValue<E> (&table)[N], std::string_view text, const char* what) {
    for (const NamedValue<E>& row : table)
        if (text == row.name) return row.value;
    throw Error(str("unknown ", what, " '", text, "' (known: ", namesOf(table), ")"));
}

} // namespace hfx
