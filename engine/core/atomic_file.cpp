#include "core/atomic_file.h"

#include "core/error.h"

#include <fstream>
#include <random>
#include <unistd.h>

namespace facesketch {

void writeFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write)
{
    namespace fs = std::filesystem;
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::is_directory(dir))
        fail(path.string(), ": folder ", dir.string(), " does not exist");

    // Unique per process and call, so concurrent writers never share a temporary.
    static thread_local std::mt19937_64 rng(std::random_device {}() ^ static_cast<unsigned>(getpid()));
    const fs::path tmp = dir / cat(".", path.filename().string(), ".tmp-", getpid(), "-", rng() % 1000000007u);
    try {
        {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            if (!out)
                fail(path.string(), ": cannot create temporary file ", tmp.string());
            write(out);
            out.flush();
            if (!out)
                fail(path.string(), ": write failed (disk full?)");
        }
        std::error_code ec;
        fs::rename(tmp, path, ec);
        if (ec)
            fail(path.string(), ": cannot rename temporary file into place: ", ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
}

} // namespace facesketch
