// `facesketch synth` datasets: roles, determinism (byte-identical), a valid dataset on disk.
#include "dataset/synth/synth_dataset.h"
#include "core/error.h"
#include "dataset/dataset.h"
#include "test_common.h"

#include <fstream>
#include <iostream>
#include <sstream>

using namespace facesketch;
using namespace facesketch::dataset;
namespace fs = std::filesystem;

namespace {

std::string bytes(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST_CASE("synth_dataset: same seed gives byte-identical datasets whatever the thread count")
{
    test::TempDir dir;
    SynthOptions o;
    o.identities = 6;
    o.resolution = Resolution::High;
    o.poses = true;
    o.poseIdentities = 1;
    o.seed = 77;
    o.threads = 1;
    writeSynthDataset(dir / "a", o);
    o.threads = 3;
    writeSynthDataset(dir / "b", o);
    o.seed = 78;
    o.poses = false;
    writeSynthDataset(dir / "c", o);
    const Dataset a = openDataset(dir / "a");
    REQUIRE(a.manifest.samples.size() == 6);
    REQUIRE(a.manifest.poses.size() == 36);
    REQUIRE(bytes(dir / "a" / "manifest.json") == bytes(dir / "b" / "manifest.json"));
    int files = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir / "a")) {
        if (!e.is_regular_file())
            continue;
        const fs::path rel = fs::relative(e.path(), dir / "a");
        INFO(rel);
        REQUIRE(bytes(e.path()) == bytes(dir / "b" / rel));
        ++files;
    }
    REQUIRE(files == 1 + 6 + 36);
    REQUIRE(bytes(dir / "a" / "faces" / "face_0003.ply") != bytes(dir / "c" / "faces" / "face_0003.ply"));
    // Poses share the neutral's topology and the neutral pose equals the identity.
    const Mesh neutral = loadMesh(a, a.manifest.poses[0].file);
    REQUIRE(a.manifest.poses[0].name == "neutral");
    REQUIRE(neutral.V == loadMesh(a, a.manifest.samples[0].file).V);
    REQUIRE(loadShapes(a, Role::Train, "skin").cols() == 3 * a.manifest.component("skin")->size());
}

TEST_CASE("synth_dataset: a full 250-identity dataset opens and loads by role")
{
    test::TempDir dir;
    SynthOptions o;
    o.threads = 2;
    writeSynthDataset(dir / "low", o); // its time: `facesketch bench synth`
    const Dataset d = openDataset(dir / "low");
    REQUIRE(loadShapes(d, Role::Train).rows() == 182);
    REQUIRE(loadShapes(d, Role::Contour).rows() == 48);
    REQUIRE(loadShapes(d, Role::Test).rows() == 20);
}
