#pragma once
// Shared by the ICT import tests (import_ict.cpp, import_ict_labels.cpp): where the ICT Face
// Model Light is (never part of the repository: $FACESKETCH_ICT_DIR, else
// ../shared/datasets/ict-facekit beside the source tree), skipping visibly when it is absent,
// and contour checks.
#include "core/mesh.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace facesketch::test {

inline std::filesystem::path ictDir()
{
    if (const char* dir = std::getenv("FACESKETCH_ICT_DIR"))
        return dir;
    const char* source = std::getenv("FACESKETCH_SOURCE_DIR");
    return std::filesystem::path(source ? source : ".") / ".." / "shared" / "datasets" / "ict-facekit";
}

inline bool haveIct()
{
    return std::filesystem::is_regular_file(ictDir() / "FaceXModel" / "generic_neutral_mesh.obj");
}

#define REQUIRE_ICT_OR_SKIP()                                                                                                              \
    if (!facesketch::test::haveIct()) {                                                                                                    \
        WARN("SKIPPED: no ICT-FaceKit at " << facesketch::test::ictDir().string() << " (set FACESKETCH_ICT_DIR); test not run");           \
        return;                                                                                                                            \
    }

// Contours that close on themselves (docs/dataset-format.md).
inline bool isLoop(const std::string& contour)
{
    return contour.rfind("eye_socket", 0) == 0 || contour.rfind("nostril", 0) == 0;
}

inline bool isEdgePath(const Triangles& F, const std::vector<int>& path, bool closed)
{
    std::set<std::pair<int, int>> edges;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k)
            edges.insert({ std::min(F(f, k), F(f, (k + 1) % 3)), std::max(F(f, k), F(f, (k + 1) % 3)) });
    const size_t n = path.size();
    for (size_t i = 0; i + (closed ? 0 : 1) < n; ++i) {
        const int a = path[i], b = path[(i + 1) % n];
        if (!edges.count({ std::min(a, b), std::max(a, b) }))
            return false;
    }
    return true;
}

} // namespace facesketch::test
