#include "core/limits.h"

#include "core/error.h"

#include <fstream>
#include <system_error>

namespace facesketch::limits {

std::uint64_t checkFileSize(const std::filesystem::path& path, std::uint64_t maxBytes, const char* what)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        fail(path.string(), ": cannot open (", ec ? ec.message() : "not a regular file", ")");
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    if (ec)
        fail(path.string(), ": cannot open (", ec.message(), ")");
    if (size > maxBytes)
        fail(path.string(), ": ", size, " bytes, more than the ", maxBytes, " bytes ", what, " may have (docs/limits.md)");
    return size;
}

std::string readFileLimited(const std::filesystem::path& path, std::uint64_t maxBytes, const char* what)
{
    const std::uint64_t size = checkFileSize(path, maxBytes, what);
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path.string(), ": cannot open");
    std::string bytes(static_cast<size_t>(size), '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    // The file may have shrunk since it was measured; keep what was read, never more than the limit.
    bytes.resize(static_cast<size_t>(in.gcount()));
    if (in.bad())
        fail(path.string(), ": read error");
    return bytes;
}

void checkJsonLimits(std::string_view text, const std::string& where)
{
    int depth = 0;
    bool inString = false;
    size_t stringStart = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i; // the escaped character cannot end the string
            else if (c == '"')
                inString = false;
            if (i - stringStart > kMaxJsonStringBytes)
                fail(where, ": byte ", stringStart, ": a string longer than ", kMaxJsonStringBytes, " bytes (docs/limits.md)");
            continue;
        }
        if (c == '"') {
            inString = true;
            stringStart = i;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                fail(where, ": byte ", i, ": arrays and objects nested more than ", kMaxJsonDepth, " deep (docs/limits.md)");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

} // namespace facesketch::limits
