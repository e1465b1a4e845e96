#pragma once
// Errors for bad input. Every message names what was wrong and where: the file and line for files, the field for documents,
// the index and value for arrays. Code that detects a bad input throws facesketch::Error; nothing already built is modified
// before the throw. GPU or driver failures (a lost device, too little memory) throw the subclass gpu::GpuError (gpu/error.h).

#include <sstream>
#include <stdexcept>
#include <string>

namespace facesketch {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Concatenates its arguments with operator<< (GCC 12 has no <format>).
template <typename... Args> std::string cat(const Args&... args)
{
    std::ostringstream out;
    out.precision(9);
    (out << ... << args);
    return out.str();
}

/// Throws Error(cat(args...)).
template <typename... Args> [[noreturn]] void fail(const Args&... args)
{
    throw Error(cat(args...));
}

} // namespace facesketch
