#include "gltf_fixture.h"

#include "geometry/normals.h"
#include "geometry/primitives.h"

#include "core/error.h"

#include <cmath>
#include <cstring>
#include <numbers>

namespace facesketch::test {

GltfAnimation makeGltfTestAnimation()
{
    GltfAnimation a;
    a.name = "test timeline";
    a.face = makeIcosphere(50.0, 3);
    a.faceNormals = vertexNormals(a.face);
    for (int k = 0; k < 12; ++k) {
        a.times.push_back(k / 24.0);
        Mesh frame = a.face;
        for (Eigen::Index v = 0; v < frame.vertexCount(); ++v) {
            const Eigen::Vector3d p = a.face.V.row(v);
            const double bulge = 1.0 + 0.08 * std::sin(0.6 * k + p.x() / 15.0) * std::cos(p.y() / 20.0);
            frame.V.row(v) = bulge * p.transpose();
            frame.V(v, 1) += 4.0 * std::sin(0.4 * k) * std::exp(-p.z() * p.z() / 800.0);
        }
        a.frames.push_back(frame.V);
        a.frameNormals.push_back(vertexNormals(frame));
    }
    GltfRigidPart eye;
    eye.name = "eye";
    eye.rest = makeIcosphere(8.0, 1);
    eye.normals = vertexNormals(eye.rest);
    for (int k = 0; k < 12; ++k) {
        eye.rotation.emplace_back(Eigen::AngleAxisd(0.4 * k, Eigen::Vector3d(0.3, 1.0, 0.2).normalized()));
        eye.scale.push_back(1.0 + 0.05 * k);
        eye.translation.emplace_back(20.0 + k, 10.0, 40.0 - 2.0 * k);
    }
    a.parts.push_back(eye);
    return a;
}

Similarity partMotion(const GltfAnimation& a, std::size_t part, std::size_t k)
{
    const GltfRigidPart& p = a.parts.at(part);
    Similarity s;
    s.rotation = p.rotation.at(k).normalized().toRotationMatrix();
    s.scale = p.scale.at(k);
    s.translation = p.translation.at(k);
    return s;
}

nlohmann::json gltfExpectations(const GltfAnimation& a)
{
    nlohmann::json checks = nlohmann::json::array();
    auto add = [&](double time, const std::string& node, Eigen::Index vertex, const Eigen::Vector3d& p) {
        checks.push_back({ { "time", static_cast<double>(static_cast<float>(time)) }, { "node", node }, { "vertex", vertex },
            { "position", { p.x(), p.y(), p.z() } } });
    };
    for (std::size_t k : { 3u, 5u, 10u }) {
        const Eigen::VectorXd moved = (a.frames[k] - a.face.V).rowwise().norm();
        std::vector<Eigen::Index> order(static_cast<std::size_t>(moved.size()));
        for (std::size_t i = 0; i < order.size(); ++i)
            order[i] = static_cast<Eigen::Index>(i);
        std::partial_sort(
            order.begin(), order.begin() + 3, order.end(), [&](Eigen::Index x, Eigen::Index y) { return moved(x) > moved(y); });
        for (int i = 0; i < 3; ++i)
            add(a.times[k], "face", order[static_cast<std::size_t>(i)], a.frames[k].row(order[static_cast<std::size_t>(i)]).transpose());
        for (std::size_t part = 0; part < a.parts.size(); ++part)
            for (Eigen::Index v : { Eigen::Index(0), a.parts[part].rest.vertexCount() - 1 })
                add(a.times[k], a.parts[part].name, v, partMotion(a, part, k).apply(Eigen::Vector3d(a.parts[part].rest.V.row(v))));
    }
    return { { "toleranceMm", 0.01 }, { "mmPerUnit", 1000.0 }, { "checks", checks } };
}

/// An accessor's float values, read from the loaded buffer (tightly packed, as writeGlb writes).
std::vector<float> floatsOf(const tinygltf::Model& model, int accessorIndex)
{
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(accessorIndex));
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        fail("accessor ", accessorIndex, " does not hold floats");
    const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
    const auto& data = model.buffers.at(static_cast<std::size_t>(view.buffer)).data;
    const std::size_t count
        = accessor.count * static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)));
    if (view.byteOffset + accessor.byteOffset + count * sizeof(float) > data.size())
        fail("accessor ", accessorIndex, " runs past its buffer");
    std::vector<float> values(count);
    std::memcpy(values.data(), data.data() + view.byteOffset + accessor.byteOffset, count * sizeof(float));
    return values;
}

Vertices asRows(const std::vector<float>& values)
{
    Vertices V(static_cast<Eigen::Index>(values.size() / 3), 3);
    for (std::size_t i = 0; i < values.size(); ++i)
        V.data()[i] = values[i];
    return V;
}

int nodeNamed(const tinygltf::Model& model, const std::string& name)
{
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        if (model.nodes[i].name == name)
            return static_cast<int>(i);
    fail("no node named ", name);
}

const tinygltf::AnimationSampler& samplerFor(const tinygltf::Model& model, int node, const std::string& path)
{
    const tinygltf::Animation& animation = model.animations.at(0);
    for (const auto& channel : animation.channels)
        if (channel.target_node == node && channel.target_path == path)
            return animation.samplers.at(static_cast<std::size_t>(channel.sampler));
    fail("no ", path, " channel for node ", node);
}

Vertices morphedFace(const tinygltf::Model& model, std::size_t k, double a)
{
    const int node = nodeNamed(model, "face");
    const tinygltf::Primitive& primitive
        = model.meshes.at(static_cast<std::size_t>(model.nodes[static_cast<std::size_t>(node)].mesh)).primitives.at(0);
    const Vertices V = asRows(floatsOf(model, primitive.attributes.at("POSITION")));
    const std::vector<float> weights = floatsOf(model, samplerFor(model, node, "weights").output);
    const std::size_t n = primitive.targets.size();
    if (n == 0 || weights.size() % n != 0)
        fail("the weights do not match the ", n, " morph targets");
    Vertices result = V;
    for (std::size_t j = 0; j < n; ++j) {
        double w = (1 - a) * weights[k * n + j];
        if (a > 0)
            w += a * weights[(k + 1) * n + j];
        if (w != 0)
            result += w * asRows(floatsOf(model, primitive.targets[j].at("POSITION")));
    }
    return result;
}

tinygltf::Model loadGlb(const std::filesystem::path& path)
{
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error, warning;
    if (!loader.LoadBinaryFromFile(&model, &error, &warning, path.string()) || !error.empty() || !warning.empty())
        fail(path.string(), ": tinygltf: ", error, warning);
    return model;
}

} // namespace facesketch::test
