#pragma once
// Atomic saves: a file is written under a temporary name beside its destination and renamed
// over it only once complete, so a crash or an error never leaves a half-written file and
// never destroys the previous version.

#include <filesystem>
#include <functional>
#include <ostream>

namespace facesketch {

/// Calls write(stream) on a temporary file in path's folder, flushes it, and renames it to
/// path. If write throws or the stream fails, the temporary is removed, path is untouched and
/// an Error naming path is thrown (or write's own exception is rethrown).
void writeFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

} // namespace facesketch
