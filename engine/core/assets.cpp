#include "core/assets.h"

#include "core/error.h"

#include <cstdlib>
#include <system_error>

namespace facesketch {

namespace fs = std::filesystem;

fs::path executablePath()
{
    std::error_code error;
    fs::path exe = fs::read_symlink("/proc/self/exe", error);
    return error ? fs::path() : exe;
}

std::vector<fs::path> assetFolders(const fs::path& executable, const char* override)
{
    if (override && *override)
        return { fs::path(override) };
    if (executable.empty())
        return {};
    const fs::path dir = executable.parent_path();
    return { (dir / ".." / "share" / "facesketch").lexically_normal(), dir / "assets" };
}

fs::path findAsset(const std::string& name, const std::vector<fs::path>& folders)
{
    std::string searched;
    for (const fs::path& folder : folders) {
        const fs::path candidate = folder / name;
        std::error_code error;
        if (fs::is_regular_file(candidate, error))
            return candidate;
        searched += (searched.empty() ? "" : ", ") + folder.string();
    }
    fail("cannot find the asset ", name, " (searched: ", searched.empty() ? "nothing, the executable's path is unknown" : searched,
        "); it is installed with the program in share/facesketch, or set FACESKETCH_ASSETS to the folder holding it");
}

fs::path findAsset(const std::string& name)
{
    return findAsset(name, assetFolders(executablePath(), std::getenv("FACESKETCH_ASSETS")));
}

} // namespace facesketch
