// Tests of stats/model_file: an exact round trip, and a clear error for each kind of bad file.
#include "stats/model_file.h"

#include "core/error.h"
#include "core/hash.h"
#include "core/random.h"
#include "test_common.h"

#include <catch2/catch.hpp>
#include <cstring>

using namespace facesketch;
using namespace facesketch::stats;

namespace {

// A model with random contents on a 9 by 9 grid: the file format does not care whether it
// was trained.
FaceModel randomModel()
{
    Random random(51);
    const int side = 9;
    Mesh grid;
    grid.V.resize(side * side, 3);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i)
            grid.V.row(i + side * j) << i - 4.0, j - 4.0, 0.1 * (i - 4.0) * (i - 4.0);
    grid.F.resize(2 * (side - 1) * (side - 1), 3);
    for (int j = 0, f = 0; j + 1 < side; ++j)
        for (int i = 0; i + 1 < side; ++i, f += 2) {
            const int a = i + side * j;
            grid.F.row(f) << a, a + 1, a + side + 1;
            grid.F.row(f + 1) << a, a + side + 1, a + side;
        }
    SegmentationOptions so;
    so.clusters = 3;
    so.minVertices = 10;

    FaceModel model;
    model.triangles = grid.F;
    model.meanFace = random.normalMatrix(3 * side * side, 1);
    model.segmentation = segmentFace(grid, 40, so);
    auto ppca = [&](Eigen::Index d, int q) {
        Ppca p;
        p.mean = random.normalMatrix(d, 1);
        p.W = random.normalMatrix(d, q);
        p.sigma2 = 0.5 + random.uniform();
        return p;
    };
    Eigen::Index latents = 0;
    for (int s = 0; s < model.segmentation.size(); ++s) {
        const auto d = 3 * static_cast<Eigen::Index>(model.segmentation.vertices[static_cast<size_t>(s)].size());
        SegmentModel sm;
        sm.mixture.components = { ppca(d, 2), ppca(d, 2) };
        sm.mixture.priors = Eigen::Vector2d(0.25, 0.75);
        sm.cleanUp = ppca(d, 3);
        sm.logLikelihood = -123.5 * (s + 1);
        latents += 3;
        model.segments.push_back(sm);
    }
    model.correlation.components = { ppca(latents, 2) };
    model.correlation.priors = Eigen::VectorXd::Ones(1);
    return model;
}

} // namespace

TEST_CASE("model_file: a saved model loads back bit for bit")
{
    test::TempDir dir;
    const FaceModel model = randomModel();
    saveFaceModel(model, dir / "face.model");
    const FaceModel back = loadFaceModel(dir / "face.model");
    REQUIRE(back.triangles == model.triangles);
    REQUIRE(back.meanFace == model.meanFace);
    REQUIRE(back.segmentation.core == model.segmentation.core);
    REQUIRE(back.segmentation.vertices == model.segmentation.vertices);
    REQUIRE(back.segments.size() == model.segments.size());
    for (size_t s = 0; s < model.segments.size(); ++s) {
        REQUIRE(back.segmentation.weights[s] == model.segmentation.weights[s]);
        REQUIRE(back.segments[s].mixture.priors == model.segments[s].mixture.priors);
        for (size_t k = 0; k < 2; ++k) {
            REQUIRE(back.segments[s].mixture.components[k].W == model.segments[s].mixture.components[k].W);
            REQUIRE(back.segments[s].mixture.components[k].mean == model.segments[s].mixture.components[k].mean);
            REQUIRE(back.segments[s].mixture.components[k].sigma2 == model.segments[s].mixture.components[k].sigma2);
        }
        REQUIRE(back.segments[s].cleanUp.W == model.segments[s].cleanUp.W);
        REQUIRE(back.segments[s].logLikelihood == model.segments[s].logLikelihood);
    }
    REQUIRE(back.correlation.components.front().W == model.correlation.components.front().W);
    // The payload is the stored doubles plus a few bytes of sizes per matrix.
    size_t doubles = model.meanFace.size();
    for (const SegmentModel& sm : model.segments)
        doubles += 2 * (sm.mixture.components[0].W.size() + sm.mixture.components[0].mean.size()) + sm.cleanUp.W.size()
            + sm.cleanUp.mean.size();
    CHECK(std::filesystem::file_size(dir / "face.model") < 8 * doubles + 8 * model.triangles.size() + 4096);
}

TEST_CASE("model_file: wrong, old, truncated and corrupt files give clear errors")
{
    test::TempDir dir;
    saveFaceModel(randomModel(), dir / "good.model");
    const std::string good = test::readBytes(dir / "good.model");

    test::writeText(dir / "mesh.ply", "ply\nformat binary_little_endian 1.0\n");
    REQUIRE_THROWS_WITH(loadFaceModel(dir / "mesh.ply"), Catch::Contains("not a FaceSketch face model"));

    std::string old = good;
    old[8] = 7; // version 7
    test::writeText(dir / "old.model", old);
    REQUIRE_THROWS_WITH(loadFaceModel(dir / "old.model"), Catch::Contains("version 7"));

    test::writeText(dir / "short.model", good.substr(0, good.size() / 2));
    REQUIRE_THROWS_WITH(loadFaceModel(dir / "short.model"), Catch::Contains("truncated"));

    std::string flipped = good;
    flipped[good.size() / 2] ^= 0x10;
    test::writeText(dir / "flipped.model", flipped);
    REQUIRE_THROWS_WITH(loadFaceModel(dir / "flipped.model"), Catch::Contains("checksum mismatch"));

    REQUIRE_THROWS_WITH(loadFaceModel(dir / "missing.model"), Catch::Contains("missing.model"));
}

TEST_CASE("model_file: the model file keeps the head layout, and version 1 files are refused")
{
    // A one-segment, one-component model of a 4-vertex skin; the file format does not care
    // whether it was trained.
    FaceModel model;
    model.triangles.resize(2, 3);
    model.triangles << 0, 1, 2, 0, 2, 3;
    model.meanFace = Eigen::VectorXd::LinSpaced(12, 0.0, 11.0);
    model.segmentation.core = Eigen::VectorXi::Zero(4);
    model.segmentation.vertices = { { 0, 1, 2, 3 } };
    model.segmentation.weights = { Eigen::VectorXd::Ones(4) };
    SegmentModel sm;
    Ppca p;
    p.mean = model.meanFace;
    p.W = Eigen::MatrixXd::Identity(12, 2);
    p.sigma2 = 0.5;
    sm.mixture.priors = Eigen::VectorXd::Ones(1);
    sm.mixture.components = { p };
    sm.cleanUp = p;
    model.segments = { sm };
    Ppca c;
    c.mean = Eigen::VectorXd::Zero(2);
    c.W = Eigen::MatrixXd::Ones(2, 1);
    c.sigma2 = 0.1;
    model.correlation.priors = Eigen::VectorXd::Ones(1);
    model.correlation.components = { c };
    model.head.vertexCount = 6;
    model.head.skinBegin = 0;
    model.head.topology.resize(1, 3);
    model.head.topology << 3, 4, 5;
    RigidPart part;
    part.name = "eye_left";
    part.vertices = { 4, 5 };
    part.mean.resize(2, 3);
    part.mean << 1, 2, 3, 4, 5, 6;
    part.anchors = { 1, 3 };
    part.scale = false;
    model.head.parts = { part };

    test::TempDir dir;
    saveFaceModel(model, dir / "head.model");
    const FaceModel back = loadFaceModel(dir / "head.model");
    REQUIRE(back.head.vertexCount == 6);
    REQUIRE(back.head.topology == model.head.topology);
    REQUIRE(back.head.parts.size() == 1);
    CHECK(back.head.parts[0].name == "eye_left");
    CHECK(back.head.parts[0].vertices == part.vertices);
    CHECK(back.head.parts[0].mean == part.mean);
    CHECK(back.head.parts[0].anchors == part.anchors);
    CHECK(back.head.parts[0].scale == false);

    std::string bytes = test::readBytes(dir / "head.model");
    bytes[8] = 1; // the version written before the head layout existed
    test::writeText(dir / "v1.model", bytes);
    REQUIRE_THROWS_WITH(loadFaceModel(dir / "v1.model"), Catch::Contains("version 1") && Catch::Contains("retrain"));
}

namespace {

// A model file around `payload` with a valid header and checksum, so that only the payload's
// contents can be wrong.
std::string modelFileAround(const std::string& payload)
{
    std::string bytes("FSKFACE\0", 8);
    const std::uint32_t version = kFaceModelVersion;
    const std::uint64_t length = payload.size(), hash = fnv1a(payload.data(), payload.size());
    bytes.append(reinterpret_cast<const char*>(&version), 4);
    bytes.append(reinterpret_cast<const char*>(&length), 8);
    bytes += payload;
    bytes.append(reinterpret_cast<const char*>(&hash), 8);
    return bytes;
}

std::string matrixHeader(std::uint64_t rows, std::uint64_t cols)
{
    std::string bytes(16, '\0');
    std::memcpy(bytes.data(), &rows, 8);
    std::memcpy(bytes.data() + 8, &cols, 8);
    return bytes;
}

} // namespace

TEST_CASE("model_file: hostile sizes are refused before anything of their size is allocated")
{
    test::TempDir dir;
    const auto loadError = [&](const std::string& bytes) {
        test::writeText(dir / "hostile.model", bytes);
        try {
            (void)loadFaceModel(dir / "hostile.model");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    using Catch::Contains;
    // 4 billion triangles announced by a 60-byte file.
    REQUIRE_THAT(loadError(modelFileAround(matrixHeader(4000000000u, 3) + std::string(24, '\0'))),
        Contains("the triangles claims 4000000000 by 3 values at byte 16, more than the file holds"));
    // Sizes whose product overflows 64 bits (2^62 * 2^62 * 4 wraps to 0), and a matrix without
    // columns claiming 2^63 rows (Eigen's index is signed).
    REQUIRE_THAT(loadError(modelFileAround(matrixHeader(std::uint64_t(1) << 62, std::uint64_t(1) << 62))),
        Contains("claims 4611686018427387904 by 4611686018427387904 values"));
    REQUIRE_THAT(loadError(modelFileAround(matrixHeader(std::uint64_t(1) << 63, 0))), Contains("claims 9223372036854775808 by 0 values"));

    // A factor wider than tall: W^T W would be q by q for a q the file does not pay for.
    FaceModel wide = randomModel();
    wide.segments[0].cleanUp.W = Eigen::MatrixXd::Ones(wide.segments[0].cleanUp.dim(), wide.segments[0].cleanUp.dim() + 1);
    saveFaceModel(wide, dir / "wide.model");
    REQUIRE_THROWS_WITH(loadFaceModel(dir / "wide.model"), Contains("a segment clean-up model is inconsistent"));

    // A head far larger than its skin and rigid parts, which validation would allocate for.
    FaceModel head = randomModel();
    head.head.vertexCount = 100000000;
    saveFaceModel(head, dir / "head.model");
    REQUIRE_THROWS_WITH(loadFaceModel(dir / "head.model"), Contains("head of 100000000 vertices with the skin from 0"));
    head.head.vertexCount = 1000;
    saveFaceModel(head, dir / "head.model");
    REQUIRE_THROWS_WITH(
        loadFaceModel(dir / "head.model"), Contains("inconsistent model: a head of 1000 vertices from 81 skin and 0 rigid-part"));
}
