#pragma once
// Compute programs and the dispatch helpers (direct and indirect, one binding path). A program
// is a SPIR-V compute shader whose bindings 0..N-1 in set 0 are storage buffers, or uniform
// buffers where `uniformMask` has bit i set (small per-dispatch parameters: implementations
// treat them as uniform, which a CPU implementation such as lavapipe turns into one scalar load
// instead of a load per invocation), or uniform texel buffers where `texelMask` has bit i set
// (large read-only data each invocation reads at its own address: see TexelView in
// gpu/buffers.h), with an optional push-constant block.
// The workgroup size is read from the SPIR-V (OpExecutionMode LocalSize), so the shader is the
// single source of truth for it.

#include "gpu/buffers.h"
#include "gpu/device.h"

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <vector>

namespace facesketch::gpu {

/// SPIR-V words embedded at build time (shaders/CMakeLists.txt makes `<name>_<stage>` arrays).
struct ShaderCode {
    const std::uint32_t* words = nullptr;
    std::size_t sizeBytes = 0;
};

template <std::size_t N> ShaderCode shaderCode(const std::uint32_t (&words)[N])
{
    return { words, sizeof(words) };
}

/// A SPIR-V module read from a file (glslangValidator -V output), for kernel variants measured
/// against the embedded ones. Throws Error naming the file if it cannot be read or its words
/// are not a SPIR-V module with a literal LocalSize.
std::vector<std::uint32_t> readSpirvFile(const std::filesystem::path& path);

/// The LocalSize of a compute shader's entry point; throws Error if the SPIR-V has none.
void readLocalSize(ShaderCode code, std::uint32_t localSize[3]);

VkShaderModule createShaderModule(Device& device, ShaderCode code);

struct ComputeProgram {
    VkShaderModule module = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    std::uint32_t localSize[3] = { 1, 1, 1 };
    std::uint32_t bufferCount = 0;
    std::uint32_t pushConstantSize = 0;
    std::uint32_t uniformMask = 0;
    std::uint32_t texelMask = 0;
};

/// What one binding of a dispatch refers to: a whole buffer (storage or uniform) or a texel
/// view, as the program's masks say. Converts from either pointer, so `{&a, &view, &b}` works.
struct Binding {
    Binding(const Buffer* b)
        : buffer(b)
    {
    }
    Binding(const TexelView* t)
        : texel(t)
    {
    }
    const Buffer* buffer = nullptr;
    const TexelView* texel = nullptr;
};

ComputeProgram createComputeProgram(Device& device, ShaderCode code, std::uint32_t bufferCount, std::uint32_t pushConstantSize,
    std::uint32_t uniformMask = 0, std::uint32_t texelMask = 0);
void destroyComputeProgram(Device& device, ComputeProgram& program);

/// Binds `program` and `buffers` (binding i = buffers[i]: a whole buffer, or a texel view where
/// the program's texelMask says so; a mismatch throws Error), pushes `constants`
/// and dispatches enough workgroups to cover countX x countY x countZ invocations. The shader
/// must bounds-check. Put the barrier that consumes the result at the call site.
void dispatchRaw(Device& device, VkCommandBuffer cmd, const ComputeProgram& program, std::uint32_t countX, std::uint32_t countY,
    std::uint32_t countZ, std::initializer_list<Binding> buffers, const void* constants, std::size_t constantsSize);

/// As dispatchRaw, with the workgroup counts read by the device from `args` at `offset`
/// (VkDispatchIndirectCommand: three uints), written earlier by a shader: for work whose size
/// only the GPU knows. `args` needs VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT; put
/// computeToIndirectBarrier between the writes and this call.
void dispatchIndirect(Device& device, VkCommandBuffer cmd, const ComputeProgram& program, const Buffer& args, VkDeviceSize offset,
    std::initializer_list<Binding> buffers, const void* constants, std::size_t constantsSize);

template <typename Constants>
void dispatch(Device& device, VkCommandBuffer cmd, const ComputeProgram& program, std::uint32_t countX, std::uint32_t countY,
    std::uint32_t countZ, std::initializer_list<Binding> buffers, const Constants& constants)
{
    assert(program.pushConstantSize == sizeof(constants));
    dispatchRaw(device, cmd, program, countX, countY, countZ, buffers, &constants, sizeof(constants));
}

/// Shader writes before the barrier are visible to later shader reads/writes and transfers.
void computeBarrier(VkCommandBuffer cmd);
/// As computeBarrier, and the writes are visible to a later dispatchIndirect's argument read.
void computeToIndirectBarrier(VkCommandBuffer cmd);
/// Transfer writes (fills, copies) before the barrier are visible to later shader access.
void transferToComputeBarrier(VkCommandBuffer cmd);
/// Shader and transfer writes are visible to the host (before a readback of mapped memory).
void hostReadBarrier(VkCommandBuffer cmd);

} // namespace facesketch::gpu
