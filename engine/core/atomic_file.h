#pragma once
// Atomic saves: a file is written under a temporary name beside its destination, flushed to
// disk (fsync) and renamed over it only once complete, and the rename itself is made durable
// (fsync of the folder). A crash, a SIGKILL or an error at any moment leaves either the whole
// previous file or the whole new one, never a torn one, and never destroys the previous version
// (tests/cli/kill_during_save.sh kills `facesketch` mid-save to check it). A crash may leave
// a temporary `.<name>.tmp-<pid>-<n>` beside the file; it is never read.
//
// Folders of many files (datasets, dataset/dataset.h writeDataset) are written into a staging
// folder, made durable at once and then swapped into place: see StagingFolder.

#include <filesystem>
#include <functional>
#include <ostream>

namespace facesketch {

/// Calls write(stream) on a temporary file in path's folder, flushes and fsyncs it, renames it
/// to path and fsyncs the folder. If write throws or the stream fails, the temporary is
/// removed, path is untouched and an Error naming path is thrown (or write's own exception is
/// rethrown). Inside a live StagingFolder the two fsyncs are left to its owner.
void writeFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

/// Marks a folder that is being filled before it is published whole: while the object lives,
/// writeFileAtomically skips its fsyncs for files under `folder` (any thread), because the owner
/// calls syncFilesystem(folder) once before publishing. A dataset of 9,000 meshes would
/// otherwise wait for 9,000 fsyncs (about 10 ms each on an ext4 disk).
class StagingFolder {
public:
    explicit StagingFolder(std::filesystem::path folder);
    ~StagingFolder();
    StagingFolder(const StagingFolder&) = delete;
    StagingFolder& operator=(const StagingFolder&) = delete;

private:
    std::filesystem::path folder_;
};

/// Flushes everything written to the file system that holds `path` (syncfs). Throws Error
/// naming path.
void syncFilesystem(const std::filesystem::path& path);

/// fsync of the file or folder at path (a folder: its entries, e.g. after a rename into it).
/// Throws Error naming path.
void syncPath(const std::filesystem::path& path);

/// Swaps two existing paths (files or folders) in one atomic step (Linux renameat2
/// RENAME_EXCHANGE): at every moment each name holds one of the two complete versions. Returns
/// false, changing nothing, if the file system cannot exchange; throws Error naming both paths
/// on any other failure.
bool exchangePaths(const std::filesystem::path& a, const std::filesystem::path& b);

} // namespace facesketch
