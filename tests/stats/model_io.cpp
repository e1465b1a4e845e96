// Tests of stats/model_io: payload values read back as written, and a read past the end or a
// matrix claiming more values than the payload holds fails naming the path and the value.
#include "stats/model_io.h"

#include "core/error.h"
#include "core/random.h"
#include "test_common.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::stats;

TEST_CASE("model io: scalars, matrices, strings, indices and mixtures read back exactly")
{
    Random random(3);
    Mppca m;
    m.priors = Eigen::Vector2d(0.3, 0.7);
    for (int k = 0; k < 2; ++k)
        m.components.push_back({ random.normalMatrix(5, 1), random.normalMatrix(5, 2), 0.25 + k });
    PayloadWriter w;
    w.scalar<std::int64_t>(-42);
    w.matrix(Eigen::Matrix<std::int32_t, 2, 3>((Eigen::Matrix<std::int32_t, 2, 3>() << 1, 2, 3, 4, 5, 6).finished()));
    w.text("eye_left");
    w.indices({ 7, 8, 9 });
    w.mixture(m);
    const std::filesystem::path path = "payload";
    PayloadReader r(w.bytes(), 0, w.bytes().size(), path);
    CHECK(r.scalar<std::int64_t>("a") == -42);
    const Eigen::MatrixXi A = r.matrix<std::int32_t>("b");
    CHECK(A == (Eigen::MatrixXi(2, 3) << 1, 2, 3, 4, 5, 6).finished());
    CHECK(r.text("c") == "eye_left");
    CHECK(r.indices("d") == std::vector<int> { 7, 8, 9 });
    const Mppca back = r.mixture("e");
    CHECK(back.priors == m.priors);
    CHECK(back.components[1].W == m.components[1].W);
    CHECK(back.components[1].sigma2 == 1.25);
    CHECK(r.done());
    REQUIRE_THROWS_WITH(r.scalar<double>("the end"), Catch::Contains("payload: truncated") && Catch::Contains("the end"));
}

TEST_CASE("model io: a container round-trips its payload and refuses another kind or a flipped byte")
{
    test::TempDir dir;
    const std::array<char, 8> magic { 'F', 'S', 'K', 'T', 'E', 'S', 'T', '\0' };
    writeModelContainer(dir / "a.bin", magic, 3, "hello payload");
    CHECK(readModelContainer(dir / "a.bin", magic, 3, "test model", "redo") == "hello payload");
    REQUIRE_THROWS_WITH(readModelContainer(dir / "a.bin", magic, 4, "test model", "redo it"),
        Catch::Contains("test model format version 3") && Catch::Contains("redo it"));
    const std::array<char, 8> other { 'F', 'S', 'K', 'O', 'T', 'H', 'R', '\0' };
    REQUIRE_THROWS_WITH(readModelContainer(dir / "a.bin", other, 3, "other model", ""), Catch::Contains("no FSKOTHR header"));

    PayloadWriter w;
    w.scalar<std::uint64_t>(1000000); // rows
    w.scalar<std::uint64_t>(1000000); // cols, and no values
    PayloadReader r(w.bytes(), 0, w.bytes().size(), dir / "big");
    REQUIRE_THROWS_WITH(r.matrix<double>("the big one"), Catch::Contains("more than the file holds"));
}
