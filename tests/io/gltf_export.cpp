#include "io/gltf_export.h"
#include "core/error.h"
#include "gltf_fixture.h"
#include "test_common.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>

using namespace facesketch;

namespace {

using test::asRows;
using test::floatsOf;
using test::morphedFace;
using test::nodeNamed;
using test::samplerFor;

/// The part node's vertices at key k (its TRS channels applied to its mesh).
Vertices movedPart(const tinygltf::Model& model, const std::string& name, std::size_t k)
{
    const int node = nodeNamed(model, name);
    const tinygltf::Primitive& primitive
        = model.meshes.at(static_cast<std::size_t>(model.nodes[static_cast<std::size_t>(node)].mesh)).primitives.at(0);
    const Vertices rest = asRows(floatsOf(model, primitive.attributes.at("POSITION")));
    const auto t = floatsOf(model, samplerFor(model, node, "translation").output);
    const auto r = floatsOf(model, samplerFor(model, node, "rotation").output);
    const auto s = floatsOf(model, samplerFor(model, node, "scale").output);
    const Eigen::Quaterniond q(r[4 * k + 3], r[4 * k], r[4 * k + 1], r[4 * k + 2]);
    REQUIRE(s[3 * k] == s[3 * k + 1]);
    Similarity motion;
    motion.rotation = q.normalized().toRotationMatrix();
    motion.scale = s[3 * k];
    motion.translation = Eigen::Vector3d(t[3 * k], t[3 * k + 1], t[3 * k + 2]);
    return motion.apply(rest);
}

} // namespace

TEST_CASE("gltf export: every sampled frame is what a client shows at its time, and halfway between two is their blend")
{
    test::TempDir dir;
    const GltfAnimation animation = test::makeGltfTestAnimation();
    writeGlb(dir / "a.glb", animation);
    const tinygltf::Model model = test::loadGlb(dir / "a.glb");
    REQUIRE(model.animations.size() == 1);
    REQUIRE(model.animations[0].name == animation.name);
    const std::vector<float> times = floatsOf(model, model.animations[0].samplers[0].input);
    REQUIRE(times.size() == animation.times.size());
    // float32 storage of positions about 50 mm from the origin: a few 1e-6 mm.
    const double tolerance = 1e-4;
    for (std::size_t k = 0; k < animation.frames.size(); ++k) {
        INFO("frame " << k);
        REQUIRE(times[k] == static_cast<float>(animation.times[k]));
        REQUIRE((morphedFace(model, k, 0.0) - animation.frames[k]).cwiseAbs().maxCoeff() < tolerance);
        const Vertices expected = test::partMotion(animation, 0, k).apply(animation.parts[0].rest.V);
        REQUIRE((movedPart(model, "eye", k) - expected).cwiseAbs().maxCoeff() < tolerance);
        if (k + 1 < animation.frames.size()) {
            const Vertices half = 0.5 * (animation.frames[k] + animation.frames[k + 1]);
            REQUIRE((morphedFace(model, k, 0.5) - half).cwiseAbs().maxCoeff() < tolerance);
        }
    }
    // The frames really differ (else the comparison above proves little).
    REQUIRE((animation.frames[3] - animation.face.V).cwiseAbs().maxCoeff() > 1.0);
    // A viewer without the animation shows the rest face.
    const tinygltf::Mesh& mesh = model.meshes.at(0);
    REQUIRE(mesh.weights == std::vector<double>(animation.frames.size(), 0.0));
    REQUIRE(mesh.primitives.at(0).targets.size() == animation.frames.size());
    REQUIRE(mesh.primitives.at(0).attributes.count("NORMAL") == 1);
}

TEST_CASE("gltf export: bad animations fail naming the field and write nothing")
{
    test::TempDir dir;
    const GltfAnimation good = test::makeGltfTestAnimation();
    auto rejects = [&](const GltfAnimation& a, const std::string& message) {
        REQUIRE_THROWS_WITH(writeGlb(dir / "bad.glb", a), Catch::Contains(message));
        REQUIRE_FALSE(std::filesystem::exists(dir / "bad.glb"));
    };
    GltfAnimation a = good;
    a.frames[2](7, 1) = std::nan("");
    rejects(a, "frames[2]: vertex 7 is nan");
    a = good;
    a.times[4] = a.times[3];
    rejects(a, "times[4]");
    a = good;
    a.times[0] = -1;
    rejects(a, "times[0]: -1");
    a = good;
    a.frames.pop_back();
    rejects(a, "frames: 11 frames for 12 times");
    a = good;
    a.frames[1].conservativeResize(10, 3);
    rejects(a, "frames[1]: 10 vertices, the face has 642");
    a = good;
    a.parts[0].scale[6] = 0;
    rejects(a, "parts[0] (eye).scale[6]");
    a = good;
    a.parts[0].rotation[2] = Eigen::Quaterniond(0, 0, 0, 0);
    rejects(a, "parts[0] (eye).rotation[2]");
    a = good;
    a.times.clear();
    a.frames.clear();
    a.frameNormals.clear();
    rejects(a, "times: no frames");
    a = good;
    a.frameNormals.pop_back();
    rejects(a, "frameNormals");
}
