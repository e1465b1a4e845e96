#pragma once
// Buffers, images and host<->device copies. One VkDeviceMemory per resource: FaceSketch holds
// tens of resources, not thousands, so a sub-allocator would only add failure modes.
// Plain structs with createX/destroyX pairs; destroy in reverse order of creation.

#include "gpu/device.h"

#include <cstddef>

namespace facesketch::gpu {

enum class MemoryUse {
    Device,   ///< GPU-local; mapped too when the device shares memory with the host (lavapipe, UMA)
    Readback, ///< host-visible, cached when possible: the GPU writes, the CPU reads
    Upload,   ///< host-visible (always mapped), device-local when possible: the CPU writes, the GPU reads
};

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr; ///< non-null when the memory is host-visible (persistently mapped)
};

/// A buffer of `size` bytes (> 0). Transfer source/destination usage is always added.
Buffer createBuffer(Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use = MemoryUse::Device);
void destroyBuffer(Device& device, Buffer& buffer);

/// Copies `size` bytes from host `data` to `buffer` at `offset`: by memcpy when the buffer is
/// mapped, otherwise through a staging buffer and a queue submission. Waits until done.
void uploadBuffer(Device& device, Buffer& buffer, const void* data, std::size_t size, VkDeviceSize offset = 0);
/// Copies `size` bytes of `buffer` at `offset` to host `data`. The GPU writes to it must have
/// finished and been made visible to the host: submitAndWait waits on the fence of its own
/// submission, so record hostReadBarrier at the end of the commands that wrote it. Nothing here
/// waits for the queue, so a window's frames in flight are never stalled by a readback.
void readbackBuffer(Device& device, const Buffer& buffer, void* data, std::size_t size, VkDeviceSize offset = 0);

/// A typed view of a buffer, bound as a uniform texel buffer (GLSL `samplerBuffer`,
/// `usamplerBuffer`; texelFetch). For data every invocation reads at its own address: a CPU
/// implementation such as lavapipe fetches texels with one vector gather per SIMD row, where
/// a storage-buffer load at a per-invocation address is a scalar loop over the row's lanes
/// with two branches per lane (Mesa 22.3). The buffer needs VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT.
struct TexelView {
    VkBufferView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkDeviceSize elements = 0; ///< texels in the view
};

/// A view of all of `buffer` as texels of `format`: one of R32_UINT, R32G32_UINT,
/// R32G32B32A32_UINT, R32G32B32A32_SFLOAT and R8G8B8A8_UNORM (RGBA bytes), which every device
/// can fetch from. Throws Error for another format, a buffer that is not a whole number of texels,
/// or more texels than the device's maxTexelBufferElements.
TexelView createTexelView(Device& device, const Buffer& buffer, VkFormat format);
void destroyTexelView(Device& device, TexelView& view);

struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    std::uint32_t width = 0, height = 0;
};

/// A 2D device-local image with one mip level and a view of `aspect`.
Image createImage(Device& device, std::uint32_t width, std::uint32_t height, VkFormat format, VkImageUsageFlags usage,
    VkImageAspectFlags aspect, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);
void destroyImage(Device& device, Image& image);

/// Index of a memory type allowed by `typeBits` with all `required` flags, preferring one that
/// also has `preferred`; throws Error when none exists.
std::uint32_t chooseMemoryType(
    const Device& device, std::uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred);

} // namespace facesketch::gpu
