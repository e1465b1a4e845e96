#pragma once
// Assets: small data files shipped with the program (the source tree's assets/, such as the
// ICT pose recipes ict-poses.json). They are installed to <prefix>/share/facesketch beside
// <prefix>/bin/facesketch, and the build copies them to <build>/share/facesketch, the same
// place relative to the binaries in <build>/app and <build>/tests; so a program finds them
// from its own executable, never by searching the source tree or the current folder.
//
// Search order, first match wins:
//   1. $FACESKETCH_ASSETS, if set and not empty: that folder alone (an override, e.g. for an
//      edited copy of the recipes);
//   2. <exe dir>/../share/facesketch (installed, and the build tree's copy);
//   3. <exe dir>/assets (a program unpacked into one folder with its assets beside it).

#include <filesystem>
#include <string>
#include <vector>

namespace facesketch {

/// The running program's executable, from /proc/self/exe (Linux); empty if that cannot be read.
std::filesystem::path executablePath();

/// The folders searched, in order, for a program at `executable` with FACESKETCH_ASSETS equal
/// to `override` (null or empty: not set).
std::vector<std::filesystem::path> assetFolders(const std::filesystem::path& executable, const char* override);

/// The regular file `name` (a path relative to the assets folder) in the first of `folders`
/// that holds it. Throws Error naming the asset, every folder searched and FACESKETCH_ASSETS
/// if none does.
std::filesystem::path findAsset(const std::string& name, const std::vector<std::filesystem::path>& folders);

/// findAsset in assetFolders(executablePath(), getenv("FACESKETCH_ASSETS")).
std::filesystem::path findAsset(const std::string& name);

} // namespace facesketch
