#include "contours/culling_gpu.h"

#include <algorithm>
#include <cmath>

namespace facesketch {

namespace {
// Words of the sign-lock bit set: one bit per (mesh, vertex), at least one word.
size_t signLockWords(std::uint32_t meshCount, Eigen::Index vertexCount)
{
    return std::max<size_t>(1, (size_t(meshCount) * size_t(vertexCount) + 31) / 32);
}
} // namespace

GpuCulling::GpuCulling(gpu::Device& device, const GpuCurvature& curvature)
    : device_(device)
    , positionsVersion_(curvature.positionsVersion() - 1)
    , shapesVersion_(curvature.shapesVersion() - 1)
    , rings_(buildNeighbours(curvature.hostWedges()))
{
    update(curvature);
}

GpuCulling::~GpuCulling()
{
    vkDeviceWaitIdle(device_.device);
    if (signLocks_.buffer) {
        gpu::destroyTexelView(device_, signLockTexels_);
        gpu::destroyBuffer(device_, signLocks_);
    }
}

bool GpuCulling::update(const GpuCurvature& curvature)
{
    const bool positions = curvature.positionsVersion() != positionsVersion_, shapes = curvature.shapesVersion() != shapesVersion_;
    if (positions)
        setBounds(curvature);
    if (shapes)
        setConesAndLocks(curvature);
    positionsVersion_ = curvature.positionsVersion();
    shapesVersion_ = curvature.shapesVersion();
    return positions || shapes;
}

void GpuCulling::setBounds(const GpuCurvature& curvature)
{
    const std::uint32_t meshCount = curvature.meshCount();
    const auto nv = static_cast<size_t>(curvature.vertexCount());
    vertexBounds_.clear();
    if (meshCount == 0)
        return;
    // The positions as uploaded (floats, batch layout): the centre is their mean over the
    // meshes, summed in mesh order, and the radius the farthest of them.
    std::vector<float> batch(4 * size_t(meshCount) * nv);
    gpu::readbackBuffer(device_, curvature.positions(), batch.data(), batch.size() * sizeof(float));
    vertexBounds_.assign(nv, { 0, 0, 0, 0 });
    for (size_t v = 0; v < nv; ++v) {
        std::array<double, 4>& b = vertexBounds_[v];
        const float* p = &batch[4 * v * meshCount];
        for (size_t m = 0; m < meshCount; ++m)
            for (int c = 0; c < 3; ++c)
                b[c] += p[4 * m + c] / double(meshCount);
        for (size_t m = 0; m < meshCount; ++m) {
            double d2 = 0;
            for (int c = 0; c < 3; ++c)
                d2 += std::pow(p[4 * m + c] - b[c], 2);
            b[3] = std::max(b[3], std::sqrt(d2));
        }
    }
}

void GpuCulling::setConesAndLocks(const GpuCurvature& curvature)
{
    const std::uint32_t meshCount = curvature.meshCount();
    const size_t nv = rings_.offsets.size() - 1;
    const size_t words = signLockWords(meshCount, curvature.vertexCount());
    if (signLocks_.size != words * sizeof(std::uint32_t)) {
        vkDeviceWaitIdle(device_.device);
        if (signLocks_.buffer) {
            gpu::destroyTexelView(device_, signLockTexels_);
            gpu::destroyBuffer(device_, signLocks_);
        }
        signLocks_ = gpu::createBuffer(
            device_, words * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
        signLockTexels_ = gpu::createTexelView(device_, signLocks_, VK_FORMAT_R32_UINT);
    }
    std::vector<std::uint32_t> locks(words, 0);
    normalCones_.clear();
    if (!curvature.hasShapes()) { // nothing known: nothing locked, no cones
        gpu::uploadBuffer(device_, signLocks_, locks.data(), locks.size() * sizeof(std::uint32_t));
        return;
    }
    std::vector<std::uint32_t> shapes(4 * size_t(meshCount) * nv);
    gpu::readbackBuffer(device_, curvature.shapes(), shapes.data(), shapes.size() * sizeof(std::uint32_t));
    // Sign locks: the sign of k1 where k1 and k2 share it (0 where they do not, or no plane).
    std::vector<signed char> sign(shapes.size() / 4, 0);
    for (size_t i = 0; i < sign.size(); ++i) {
        const std::uint32_t* s = &shapes[4 * i];
        const float k1 = halfToFloat(static_cast<std::uint16_t>(s[2] & 0xffff)), k2 = halfToFloat(static_cast<std::uint16_t>(s[2] >> 16));
        const bool plane = s[0] != 0 || s[1] != 0;
        sign[i] = plane && k1 * k2 > 0 ? (k1 > 0 ? 1 : -1) : 0;
    }
    for (size_t v = 0; v < nv; ++v)
        for (size_t m = 0; m < meshCount; ++m) {
            const size_t i = v * meshCount + m;
            bool locked = sign[i] != 0;
            for (std::uint32_t k = rings_.offsets[v]; locked && k < rings_.offsets[v + 1]; ++k) {
                const size_t j = rings_.vertices[k] * size_t(meshCount) + m;
                const std::uint32_t* s = &shapes[4 * j];
                locked = (s[0] == 0 && s[1] == 0) || sign[j] == sign[i]; // a neighbour without a plane is never read
            }
            if (locked)
                locks[i / 32] |= 1u << (i % 32);
        }
    gpu::uploadBuffer(device_, signLocks_, locks.data(), locks.size() * sizeof(std::uint32_t));

    // The axis is the normalised mean normal, the half-angle the widest normal's angle to it
    // plus 1e-4 rad, far more than the float rounding between this decoder and the kernels'.
    normalCones_.assign(nv, { 0, 0, 1, M_PI });
    std::vector<Eigen::Vector3d> normals(meshCount);
    for (size_t v = 0; v < nv; ++v) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        size_t count = 0;
        for (size_t m = 0; m < meshCount; ++m) {
            const std::uint32_t* s = &shapes[4 * (v * meshCount + m)];
            if (s[0] == 0 && s[1] == 0) // no tangent plane: never a candidate
                continue;
            normals[count] = octDecode(s[0]);
            sum += normals[count++];
        }
        const double length = sum.norm();
        if (count == 0 || !(length > 1e-9 * double(count)))
            continue;
        const Eigen::Vector3d axis = sum / length;
        double halfAngle = 0;
        for (size_t k = 0; k < count; ++k)
            halfAngle = std::max(halfAngle, std::atan2(normals[k].cross(axis).norm(), normals[k].dot(axis))); // exact near 0, unlike acos
        normalCones_[v] = { axis.x(), axis.y(), axis.z(), std::min(M_PI, halfAngle + 1e-4) };
    }
}

} // namespace facesketch
