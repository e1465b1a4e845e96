#include "io/gltf_export.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace facesketch {

namespace {

void requireFinite(const Vertices& V, const std::string& what)
{
    for (Eigen::Index v = 0; v < V.rows(); ++v)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(V(v, c)))
                fail(what, ": vertex ", v, " is ", V(v, c));
}

/// Appends data to the one buffer and describes it by a buffer view and an accessor.
class Writer {
public:
    explicit Writer(tinygltf::Model& model)
        : model_(model)
    {
        model_.buffers.emplace_back();
    }

    /// An accessor of `count` elements of `type` (TINYGLTF_TYPE_*) read from `values`, floats.
    int floats(const std::vector<float>& values, int type, int components, int target, bool bounds)
    {
        const int view = addView(values.data(), values.size() * sizeof(float), target);
        tinygltf::Accessor accessor;
        accessor.bufferView = view;
        accessor.byteOffset = 0;
        accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        accessor.type = type;
        accessor.count = values.size() / static_cast<std::size_t>(components);
        if (bounds) {
            // The validator compares these with the stored float32 values, so they are taken
            // from the floats, not the doubles they came from.
            accessor.minValues.assign(components, std::numeric_limits<double>::infinity());
            accessor.maxValues.assign(components, -std::numeric_limits<double>::infinity());
            for (std::size_t i = 0; i < values.size(); ++i) {
                const std::size_t c = i % static_cast<std::size_t>(components);
                accessor.minValues[c] = std::min<double>(accessor.minValues[c], values[i]);
                accessor.maxValues[c] = std::max<double>(accessor.maxValues[c], values[i]);
            }
        }
        model_.accessors.push_back(accessor);
        return static_cast<int>(model_.accessors.size()) - 1;
    }

    int vec3s(const Vertices& V, bool bounds)
    {
        std::vector<float> values(static_cast<std::size_t>(V.size()));
        for (Eigen::Index i = 0; i < V.size(); ++i)
            values[static_cast<std::size_t>(i)] = static_cast<float>(V.data()[i]);
        return floats(values, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, bounds);
    }

    int indices(const Triangles& F)
    {
        std::vector<std::uint32_t> values(static_cast<std::size_t>(F.size()));
        for (Eigen::Index i = 0; i < F.size(); ++i)
            values[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(F.data()[i]);
        const int view = addView(values.data(), values.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        tinygltf::Accessor accessor;
        accessor.bufferView = view;
        accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        accessor.type = TINYGLTF_TYPE_SCALAR;
        accessor.count = values.size();
        model_.accessors.push_back(accessor);
        return static_cast<int>(model_.accessors.size()) - 1;
    }

private:
    int addView(const void* data, std::size_t bytes, int target)
    {
        auto& buffer = model_.buffers.front().data;
        const std::size_t offset = buffer.size();
        buffer.resize(offset + bytes);
        std::memcpy(buffer.data() + offset, data, bytes);
        // Every accessor here has 4-byte components; keep each view 4-aligned.
        buffer.resize((buffer.size() + 3) / 4 * 4, 0);
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = offset;
        view.byteLength = bytes;
        view.target = target;
        model_.bufferViews.push_back(view);
        return static_cast<int>(model_.bufferViews.size()) - 1;
    }

    tinygltf::Model& model_;
};

int addMaterial(tinygltf::Model& model, const std::string& name, double r, double g, double b)
{
    tinygltf::Material material;
    material.name = name;
    material.pbrMetallicRoughness.baseColorFactor = { r, g, b, 1.0 };
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.7;
    model.materials.push_back(material);
    return static_cast<int>(model.materials.size()) - 1;
}

} // namespace

void validateGltfAnimation(const GltfAnimation& a)
{
    validateMesh(a.face, "face");
    const Eigen::Index n = a.face.vertexCount();
    if (a.face.triangleCount() == 0)
        fail("face: no triangles");
    if (a.times.empty())
        fail("times: no frames to export");
    if (a.frames.size() != a.times.size())
        fail("frames: ", a.frames.size(), " frames for ", a.times.size(), " times");
    for (std::size_t k = 0; k < a.times.size(); ++k) {
        const double t = a.times[k];
        if (!std::isfinite(t) || t < 0)
            fail("times[", k, "]: ", t, " is not a time >= 0 in seconds");
        if (k > 0 && !(static_cast<float>(t) > static_cast<float>(a.times[k - 1])))
            fail("times[", k, "]: ", t, " is not after times[", k - 1, "] ", a.times[k - 1], " (as float32)");
    }
    for (std::size_t k = 0; k < a.frames.size(); ++k) {
        if (a.frames[k].rows() != n)
            fail("frames[", k, "]: ", a.frames[k].rows(), " vertices, the face has ", n);
        requireFinite(a.frames[k], cat("frames[", k, "]"));
    }
    const bool normals = a.faceNormals.size() > 0;
    if (normals) {
        if (a.faceNormals.rows() != n)
            fail("faceNormals: ", a.faceNormals.rows(), " normals, the face has ", n, " vertices");
        requireFinite(a.faceNormals, "faceNormals");
        if (a.frameNormals.size() != a.frames.size())
            fail("frameNormals: ", a.frameNormals.size(), " frames of normals for ", a.frames.size(), " frames");
        for (std::size_t k = 0; k < a.frameNormals.size(); ++k) {
            if (a.frameNormals[k].rows() != n)
                fail("frameNormals[", k, "]: ", a.frameNormals[k].rows(), " normals, the face has ", n, " vertices");
            requireFinite(a.frameNormals[k], cat("frameNormals[", k, "]"));
        }
    } else if (!a.frameNormals.empty()) {
        fail("frameNormals: given without faceNormals");
    }
    for (std::size_t p = 0; p < a.parts.size(); ++p) {
        const GltfRigidPart& part = a.parts[p];
        const std::string where = cat("parts[", p, "] (", part.name, ")");
        validateMesh(part.rest, where);
        if (part.rest.triangleCount() == 0)
            fail(where, ": no triangles");
        if (part.normals.size() > 0) {
            if (part.normals.rows() != part.rest.vertexCount())
                fail(where, ": ", part.normals.rows(), " normals for ", part.rest.vertexCount(), " vertices");
            requireFinite(part.normals, where + ".normals");
        }
        if (part.rotation.size() != a.times.size() || part.scale.size() != a.times.size() || part.translation.size() != a.times.size())
            fail(where, ": ", part.rotation.size(), " rotations, ", part.scale.size(), " scales and ", part.translation.size(),
                " translations for ", a.times.size(), " frames");
        for (std::size_t k = 0; k < a.times.size(); ++k) {
            const double norm = part.rotation[k].norm();
            if (!std::isfinite(norm) || norm < 1e-12)
                fail(where, ".rotation[", k, "]: not a rotation (norm ", norm, ")");
            if (!std::isfinite(part.scale[k]) || part.scale[k] <= 0)
                fail(where, ".scale[", k, "]: ", part.scale[k], " is not a scale > 0");
            if (!part.translation[k].allFinite())
                fail(where, ".translation[", k, "]: not finite");
        }
    }
}

void writeGlb(const std::filesystem::path& path, const GltfAnimation& a)
{
    validateGltfAnimation(a);
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "FaceSketch";
    Writer writer(model);
    const std::size_t frameCount = a.frames.size();
    const bool normals = a.faceNormals.size() > 0;

    // The face: rest shape plus one morph target per sampled frame.
    tinygltf::Primitive face;
    face.mode = TINYGLTF_MODE_TRIANGLES;
    face.attributes["POSITION"] = writer.vec3s(a.face.V, true);
    if (normals)
        face.attributes["NORMAL"] = writer.vec3s(a.faceNormals, false);
    face.indices = writer.indices(a.face.F);
    face.material = addMaterial(model, "skin", 0.80, 0.62, 0.52);
    std::vector<tinygltf::Value> targetNames;
    for (std::size_t k = 0; k < frameCount; ++k) {
        std::map<std::string, int> target;
        // POSITION displacements need bounds (glTF 3.7.2.1); normal displacements do not.
        target["POSITION"] = writer.vec3s(a.frames[k] - a.face.V, true);
        if (normals)
            target["NORMAL"] = writer.vec3s(a.frameNormals[k] - a.faceNormals, false);
        face.targets.push_back(std::move(target));
        std::ostringstream name;
        name << "frame_" << k;
        targetNames.emplace_back(name.str());
    }
    tinygltf::Mesh faceMesh;
    faceMesh.name = "face";
    faceMesh.primitives.push_back(face);
    faceMesh.weights.assign(frameCount, 0.0);
    // three.js and Blender name morph targets from extras.targetNames.
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(targetNames);
    faceMesh.extras = tinygltf::Value(extras);
    model.meshes.push_back(faceMesh);

    tinygltf::Node root;
    root.name = "facesketch_mm";
    root.scale = { 0.001, 0.001, 0.001 };
    model.nodes.push_back(root);
    tinygltf::Node faceNode;
    faceNode.name = "face";
    faceNode.mesh = 0;
    model.nodes.push_back(faceNode);
    model.nodes[0].children.push_back(1);

    tinygltf::Animation animation;
    animation.name = a.name;
    std::vector<float> times(frameCount);
    for (std::size_t k = 0; k < frameCount; ++k)
        times[k] = static_cast<float>(a.times[k]);
    const int input = writer.floats(times, TINYGLTF_TYPE_SCALAR, 1, 0, true);
    auto addChannel = [&](int node, const char* path, int output) {
        tinygltf::AnimationSampler sampler;
        sampler.input = input;
        sampler.output = output;
        sampler.interpolation = "LINEAR";
        animation.samplers.push_back(sampler);
        tinygltf::AnimationChannel channel;
        channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
        channel.target_node = node;
        channel.target_path = path;
        animation.channels.push_back(channel);
    };
    std::vector<float> weights(frameCount * frameCount, 0.0f);
    for (std::size_t k = 0; k < frameCount; ++k)
        weights[k * frameCount + k] = 1.0f;
    addChannel(1, "weights", writer.floats(weights, TINYGLTF_TYPE_SCALAR, 1, 0, false));

    const int partMaterial = a.parts.empty() ? -1 : addMaterial(model, "part", 0.92, 0.90, 0.86);
    for (const GltfRigidPart& part : a.parts) {
        tinygltf::Primitive primitive;
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        primitive.attributes["POSITION"] = writer.vec3s(part.rest.V, true);
        if (part.normals.size() > 0)
            primitive.attributes["NORMAL"] = writer.vec3s(part.normals, false);
        primitive.indices = writer.indices(part.rest.F);
        primitive.material = partMaterial;
        tinygltf::Mesh mesh;
        mesh.name = part.name;
        mesh.primitives.push_back(primitive);
        model.meshes.push_back(mesh);

        std::vector<float> translation, rotation, scale;
        Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
        for (std::size_t k = 0; k < frameCount; ++k) {
            Eigen::Quaterniond q = part.rotation[k].normalized();
            // q and -q are one rotation; keep neighbours in one hemisphere so the slerp between
            // samples turns the short way.
            if (k > 0 && q.dot(previous) < 0)
                q.coeffs() = -q.coeffs();
            previous = q;
            for (int c = 0; c < 3; ++c)
                translation.push_back(static_cast<float>(part.translation[k](c)));
            rotation.insert(rotation.end(),
                { static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()), static_cast<float>(q.w()) });
            scale.insert(scale.end(), 3, static_cast<float>(part.scale[k]));
        }
        tinygltf::Node node;
        node.name = part.name;
        node.mesh = static_cast<int>(model.meshes.size()) - 1;
        // The node's rest transform is the first frame's, so a viewer without animation shows
        // the part where the face's first frame has it.
        node.translation = { translation[0], translation[1], translation[2] };
        node.rotation = { rotation[0], rotation[1], rotation[2], rotation[3] };
        node.scale = { scale[0], scale[1], scale[2] };
        model.nodes.push_back(node);
        const int index = static_cast<int>(model.nodes.size()) - 1;
        model.nodes[0].children.push_back(index);
        addChannel(index, "translation", writer.floats(translation, TINYGLTF_TYPE_VEC3, 3, 0, false));
        addChannel(index, "rotation", writer.floats(rotation, TINYGLTF_TYPE_VEC4, 4, 0, false));
        addChannel(index, "scale", writer.floats(scale, TINYGLTF_TYPE_VEC3, 3, 0, false));
    }
    model.animations.push_back(animation);

    model.buffers.front().name = "facesketch";
    tinygltf::Scene scene;
    scene.name = "facesketch";
    scene.nodes = { 0 };
    model.scenes.push_back(scene);
    model.defaultScene = 0;

    tinygltf::TinyGLTF gltf;
    writeFileAtomically(path, [&](std::ostream& out) {
        if (!gltf.WriteGltfSceneToStream(&model, out, false, true))
            fail(path.string(), ": tinygltf could not write the glTF document");
    });
}

} // namespace facesketch
