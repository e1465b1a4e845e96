#include "gpu/compute.h"

#include "core/error.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

namespace facesketch::gpu {

void readLocalSize(ShaderCode code, std::uint32_t localSize[3])
{
    constexpr std::uint32_t opExecutionMode = 16, executionModeLocalSize = 17, spirvMagic = 0x07230203;
    const std::size_t count = code.sizeBytes / 4;
    if (count < 5 || code.words[0] != spirvMagic)
        fail("not a SPIR-V module (", code.sizeBytes, " bytes)");
    for (std::size_t i = 5; i < count;) {
        const std::uint32_t opcode = code.words[i] & 0xffff, length = code.words[i] >> 16;
        if (length == 0 || i + length > count)
            fail("malformed SPIR-V instruction at word ", i);
        if (opcode == opExecutionMode && length == 6 && code.words[i + 2] == executionModeLocalSize) {
            localSize[0] = code.words[i + 3];
            localSize[1] = code.words[i + 4];
            localSize[2] = code.words[i + 5];
            return;
        }
        i += length;
    }
    fail("SPIR-V compute shader declares no literal local_size");
}

std::vector<std::uint32_t> readSpirvFile(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path.string(), ": cannot open the SPIR-V file");
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad())
        fail(path.string(), ": read error");
    if (bytes.size() % 4 != 0)
        fail(path.string(), ": ", bytes.size(), " bytes is not a whole number of SPIR-V words");
    std::vector<std::uint32_t> words(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), bytes.size());
    try {
        std::uint32_t localSize[3];
        readLocalSize({ words.data(), bytes.size() }, localSize);
    } catch (const Error& e) {
        fail(path.string(), ": ", e.what());
    }
    return words;
}

VkShaderModule createShaderModule(Device& device, ShaderCode code)
{
    auto info = makeStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    info.codeSize = code.sizeBytes;
    info.pCode = code.words;
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(device.device, &info, nullptr, &module));
    return module;
}

namespace {
VkDescriptorType bindingType(const ComputeProgram& p, std::uint32_t binding)
{
    if ((p.texelMask >> binding) & 1u)
        return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    return (p.uniformMask >> binding) & 1u ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}
} // namespace

ComputeProgram createComputeProgram(Device& device, ShaderCode code, std::uint32_t bufferCount, std::uint32_t pushConstantSize,
    std::uint32_t uniformMask, std::uint32_t texelMask)
{
    if (uniformMask & texelMask)
        fail("createComputeProgram: bindings ", uniformMask & texelMask, " are marked both uniform and texel");
    ComputeProgram p;
    p.uniformMask = uniformMask;
    p.texelMask = texelMask;
    readLocalSize(code, p.localSize);
    p.bufferCount = bufferCount;
    p.pushConstantSize = pushConstantSize;
    p.module = createShaderModule(device, code);

    std::vector<VkDescriptorSetLayoutBinding> bindings(bufferCount);
    for (std::uint32_t i = 0; i < bufferCount; ++i)
        bindings[i] = { i, bindingType(p, i), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr };
    auto setInfo = makeStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    setInfo.bindingCount = bufferCount;
    setInfo.pBindings = bindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(device.device, &setInfo, nullptr, &p.setLayout));

    VkPushConstantRange range { VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantSize };
    auto layoutInfo = makeStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &p.setLayout;
    layoutInfo.pushConstantRangeCount = pushConstantSize ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(device.device, &layoutInfo, nullptr, &p.layout));

    auto info = makeStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage = makeStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = p.module;
    info.stage.pName = "main";
    info.layout = p.layout;
    VK_CHECK(vkCreateComputePipelines(device.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline));
    return p;
}

void destroyComputeProgram(Device& device, ComputeProgram& p)
{
    vkDestroyPipeline(device.device, p.pipeline, nullptr);
    vkDestroyPipelineLayout(device.device, p.layout, nullptr);
    vkDestroyDescriptorSetLayout(device.device, p.setLayout, nullptr);
    vkDestroyShaderModule(device.device, p.module, nullptr);
    p = ComputeProgram {};
}

namespace {
// Binds `program`, pushes its descriptors (one per binding) and constants.
void bindProgram(Device& device, VkCommandBuffer cmd, const ComputeProgram& program, std::initializer_list<Binding> buffers,
    const void* constants, std::size_t constantsSize)
{
    assert(buffers.size() == program.bufferCount);
    assert(constantsSize == program.pushConstantSize);
    std::uint32_t i = 0;
    for (const Binding& b : buffers) { // before anything is recorded
        const bool texel = (program.texelMask >> i) & 1u;
        if (texel ? !b.texel : !b.buffer)
            fail("dispatch: binding ", i, texel ? " needs a texel view" : " needs a buffer");
        ++i;
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, program.pipeline);

    std::vector<VkDescriptorBufferInfo> infos(buffers.size());
    std::vector<VkBufferView> views(buffers.size());
    std::vector<VkWriteDescriptorSet> writes;
    i = 0;
    for (const Binding& b : buffers) {
        const bool texel = (program.texelMask >> i) & 1u;
        auto w = makeStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        w.dstBinding = i;
        w.descriptorCount = 1;
        w.descriptorType = bindingType(program, i);
        if (texel) {
            views[i] = b.texel->view;
            w.pTexelBufferView = &views[i];
        } else {
            infos[i] = { b.buffer->buffer, 0, VK_WHOLE_SIZE };
            w.pBufferInfo = &infos[i];
        }
        writes.push_back(w);
        ++i;
    }
    if (!writes.empty())
        device.pushDescriptorSet(
            cmd, VK_PIPELINE_BIND_POINT_COMPUTE, program.layout, 0, static_cast<std::uint32_t>(writes.size()), writes.data());
    if (constantsSize)
        vkCmdPushConstants(cmd, program.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, static_cast<std::uint32_t>(constantsSize), constants);
}
} // namespace

void dispatchRaw(Device& device, VkCommandBuffer cmd, const ComputeProgram& program, std::uint32_t countX, std::uint32_t countY,
    std::uint32_t countZ, std::initializer_list<Binding> buffers, const void* constants, std::size_t constantsSize)
{
    bindProgram(device, cmd, program, buffers, constants, constantsSize);
    auto groups = [](std::uint32_t count, std::uint32_t local) { return (count + local - 1) / local; };
    vkCmdDispatch(cmd, groups(countX, program.localSize[0]), groups(countY, program.localSize[1]), groups(countZ, program.localSize[2]));
}

void dispatchIndirect(Device& device, VkCommandBuffer cmd, const ComputeProgram& program, const Buffer& args, VkDeviceSize offset,
    std::initializer_list<Binding> buffers, const void* constants, std::size_t constantsSize)
{
    bindProgram(device, cmd, program, buffers, constants, constantsSize);
    vkCmdDispatchIndirect(cmd, args.buffer, offset);
}

static void memoryBarrier(
    VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst, VkAccessFlags dstAccess)
{
    auto barrier = makeStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    barrier.srcAccessMask = srcAccess;
    barrier.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void computeBarrier(VkCommandBuffer cmd)
{
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

void computeToIndirectBarrier(VkCommandBuffer cmd)
{
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
        VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

void transferToComputeBarrier(VkCommandBuffer cmd)
{
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

void hostReadBarrier(VkCommandBuffer cmd)
{
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

} // namespace facesketch::gpu
