#pragma once
// Enumerations that users type by name (--resolution high, --correlation joint): one function
// gives each value's name, and parsing looks the text up among all values, so the two never
// disagree and every bad value gets the same kind of message.

#include "core/error.h"

#include <array>
#include <cstddef>
#include <string>

namespace facesketch {

/// The value v of `all` with name(v) == text. Throws Error "<what> '<text>' is not one of a, b, c".
template <typename E, std::size_t N>
E parseName(const std::string& text, const std::array<E, N>& all, const char* (*name)(E), const char* what)
{
    std::string names;
    for (E value : all) {
        if (text == name(value))
            return value;
        names += (names.empty() ? "" : ", ") + std::string(name(value));
    }
    fail(what, " '", text, "' is not one of ", names);
}

} // namespace facesketch
