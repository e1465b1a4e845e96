#pragma once
// FNV-1a, 64 bits (Fowler, Noll and Vo): the checksum of our binary files and the key of
// cached results. Not cryptographic; it catches corruption and tells inputs apart.

#include <cstddef>
#include <cstdint>

namespace facesketch {

inline constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ull;

/// The hash of `size` bytes at `data`, continuing from `hash` (chain calls to hash several blocks).
inline std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t hash = kFnv1aOffset)
{
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        hash ^= bytes[i];
        hash *= 1099511628211ull;
    }
    return hash;
}

} // namespace facesketch
