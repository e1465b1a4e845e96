#include "core/atomic_file.h"

#include "core/error.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <mutex>
#include <random>
#include <unistd.h>
#include <vector>

namespace facesketch {

namespace fs = std::filesystem;

namespace {

std::mutex stagingMutex;
std::vector<fs::path> stagingFolders; // absolute, lexically normal

fs::path normalAbsolute(const fs::path& path)
{
    std::error_code ec;
    const fs::path absolute = fs::absolute(path, ec);
    return (ec ? path : absolute).lexically_normal();
}

bool isStaged(const fs::path& path)
{
    const std::lock_guard lock(stagingMutex);
    if (stagingFolders.empty())
        return false;
    const fs::path p = normalAbsolute(path);
    for (const fs::path& folder : stagingFolders) {
        const auto [end, ignored] = std::mismatch(folder.begin(), folder.end(), p.begin(), p.end());
        if (end == folder.end())
            return true;
    }
    return false;
}

} // namespace

StagingFolder::StagingFolder(fs::path folder)
    : folder_(normalAbsolute(folder))
{
    const std::lock_guard lock(stagingMutex);
    stagingFolders.push_back(folder_);
}

StagingFolder::~StagingFolder()
{
    const std::lock_guard lock(stagingMutex);
    const auto it = std::find(stagingFolders.begin(), stagingFolders.end(), folder_);
    if (it != stagingFolders.end())
        stagingFolders.erase(it);
}

void syncPath(const fs::path& path)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        fail(path.string(), ": cannot open to sync: ", std::strerror(errno));
    const int result = ::fsync(fd);
    const int error = errno;
    ::close(fd);
    if (result != 0)
        fail(path.string(), ": fsync failed: ", std::strerror(error));
}

void syncFilesystem(const fs::path& path)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        fail(path.string(), ": cannot open to sync: ", std::strerror(errno));
    const int result = ::syncfs(fd);
    const int error = errno;
    ::close(fd);
    if (result != 0)
        fail(path.string(), ": syncfs failed: ", std::strerror(error));
}

bool exchangePaths(const fs::path& a, const fs::path& b)
{
    if (::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0)
        return true;
    if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP)
        return false;
    fail(a.string(), ": cannot exchange with ", b.string(), ": ", std::strerror(errno));
}

void writeFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write)
{
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::is_directory(dir))
        fail(path.string(), ": folder ", dir.string(), " does not exist");

    // Unique per process and call, so concurrent writers never share a temporary.
    static thread_local std::mt19937_64 rng(std::random_device {}() ^ static_cast<unsigned>(getpid()));
    const fs::path tmp = dir / cat(".", path.filename().string(), ".tmp-", getpid(), "-", rng() % 1000000007u);
    const bool durable = !isStaged(path);
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
        // Without the fsync a power cut after the rename can leave the new name on an empty
        // or partial file.
        if (durable)
            syncPath(tmp);
        std::error_code ec;
        fs::rename(tmp, path, ec);
        if (ec)
            fail(path.string(), ": cannot rename temporary file into place: ", ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
    if (durable)
        syncPath(dir);
}

} // namespace facesketch
