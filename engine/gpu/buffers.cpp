#include "gpu/buffers.h"

#include "core/error.h"

#include <cstring>

namespace facesketch::gpu {

std::uint32_t chooseMemoryType(
    const Device& device, std::uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred)
{
    std::int64_t fallback = -1;
    for (std::uint32_t i = 0; i < device.memory.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i)))
            continue;
        const VkMemoryPropertyFlags flags = device.memory.memoryTypes[i].propertyFlags;
        if ((flags & required) != required)
            continue;
        if ((flags & preferred) == preferred)
            return i;
        if (fallback < 0)
            fallback = i;
    }
    if (fallback < 0)
        fail("no Vulkan memory type with property flags ", required, " among type bits ", typeBits);
    return static_cast<std::uint32_t>(fallback);
}

Buffer createBuffer(Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use)
{
    if (size == 0)
        fail("createBuffer: size must be positive");
    Buffer b;
    b.size = size;
    auto info = makeStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size;
    info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(device.device, &info, nullptr, &b.buffer));

    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device.device, b.buffer, &req);
    const VkMemoryPropertyFlags hostVisible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    const std::uint32_t type = use == MemoryUse::Device
        ? chooseMemoryType(device, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, hostVisible)
        : use == MemoryUse::Upload ? chooseMemoryType(device, req.memoryTypeBits, hostVisible, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)
                                   : chooseMemoryType(device, req.memoryTypeBits, hostVisible, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);

    auto alloc = makeStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type;
    if (VkResult r = vkAllocateMemory(device.device, &alloc, nullptr, &b.memory); r != VK_SUCCESS) {
        vkDestroyBuffer(device.device, b.buffer, nullptr);
        gpuFail(cat("allocating ", size, " bytes of GPU memory (vkAllocateMemory)"), r);
    }
    VK_CHECK(vkBindBufferMemory(device.device, b.buffer, b.memory, 0));
    if ((device.memory.memoryTypes[type].propertyFlags & hostVisible) == hostVisible)
        VK_CHECK(vkMapMemory(device.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
    return b;
}

void destroyBuffer(Device& device, Buffer& b)
{
    if (b.mapped)
        vkUnmapMemory(device.device, b.memory);
    vkDestroyBuffer(device.device, b.buffer, nullptr);
    vkFreeMemory(device.device, b.memory, nullptr);
    b = Buffer {};
}

void uploadBuffer(Device& device, Buffer& buffer, const void* data, std::size_t size, VkDeviceSize offset)
{
    if (offset + size > buffer.size)
        fail("uploadBuffer: ", size, " bytes at offset ", offset, " exceed the buffer's ", buffer.size);
    if (size == 0)
        return;
    if (buffer.mapped) {
        std::memcpy(static_cast<char*>(buffer.mapped) + offset, data, size);
        return;
    }
    Buffer staging = createBuffer(device, size, 0, MemoryUse::Readback);
    std::memcpy(staging.mapped, data, size);
    try {
        submitAndWait(device, [&](VkCommandBuffer cmd) {
            VkBufferCopy region { 0, offset, size };
            vkCmdCopyBuffer(cmd, staging.buffer, buffer.buffer, 1, &region);
        });
    } catch (...) {
        destroyBuffer(device, staging); // a lost device: the staging buffer is not in use
        throw;
    }
    destroyBuffer(device, staging);
}

void readbackBuffer(Device& device, const Buffer& buffer, void* data, std::size_t size, VkDeviceSize offset)
{
    if (offset + size > buffer.size)
        fail("readbackBuffer: ", size, " bytes at offset ", offset, " exceed the buffer's ", buffer.size);
    if (size == 0)
        return;
    if (buffer.mapped) {
        std::memcpy(data, static_cast<const char*>(buffer.mapped) + offset, size);
        return;
    }
    Buffer staging = createBuffer(device, size, 0, MemoryUse::Readback);
    try {
        submitAndWait(device, [&](VkCommandBuffer cmd) {
            VkBufferCopy region { offset, 0, size };
            vkCmdCopyBuffer(cmd, buffer.buffer, staging.buffer, 1, &region);
        });
    } catch (...) {
        destroyBuffer(device, staging);
        throw;
    }
    std::memcpy(data, staging.mapped, size);
    destroyBuffer(device, staging);
}

TexelView createTexelView(Device& device, const Buffer& buffer, VkFormat format)
{
    std::uint32_t texelBytes = 0;
    switch (format) {
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R8G8B8A8_UNORM:
        texelBytes = 4;
        break;
    case VK_FORMAT_R32G32_UINT:
        texelBytes = 8;
        break;
    case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
        texelBytes = 16;
        break;
    default:
        fail("createTexelView: format ", static_cast<int>(format),
            " is not one of the texel formats every device can fetch (R32_UINT, R32G32_UINT, R32G32B32A32_UINT, R32G32B32A32_SFLOAT, "
            "R8G8B8A8_UNORM)");
    }
    if (buffer.size % texelBytes != 0)
        fail("createTexelView: a buffer of ", buffer.size, " bytes is not a whole number of ", texelBytes, "-byte texels");
    const VkDeviceSize elements = buffer.size / texelBytes;
    if (elements > device.properties.limits.maxTexelBufferElements)
        fail("createTexelView: ", elements, " texels exceed this device's maxTexelBufferElements (",
            device.properties.limits.maxTexelBufferElements, ")");
    auto info = makeStruct<VkBufferViewCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO);
    info.buffer = buffer.buffer;
    info.format = format;
    info.offset = 0;
    info.range = VK_WHOLE_SIZE;
    TexelView v;
    VK_CHECK(vkCreateBufferView(device.device, &info, nullptr, &v.view));
    v.format = format;
    v.elements = elements;
    return v;
}

void destroyTexelView(Device& device, TexelView& view)
{
    vkDestroyBufferView(device.device, view.view, nullptr);
    view = TexelView {};
}

Image createImage(Device& device, std::uint32_t width, std::uint32_t height, VkFormat format, VkImageUsageFlags usage,
    VkImageAspectFlags aspect, VkSampleCountFlagBits samples)
{
    Image image;
    image.format = format;
    image.width = width;
    image.height = height;
    auto info = makeStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = { width, height, 1 };
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = samples;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_CHECK(vkCreateImage(device.device, &info, nullptr, &image.image));

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device.device, image.image, &req);
    auto alloc = makeStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = chooseMemoryType(device, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    if (VkResult r = vkAllocateMemory(device.device, &alloc, nullptr, &image.memory); r != VK_SUCCESS) {
        vkDestroyImage(device.device, image.image, nullptr);
        gpuFail(cat("allocating a ", width, "x", height, " image (vkAllocateMemory)"), r);
    }
    VK_CHECK(vkBindImageMemory(device.device, image.image, image.memory, 0));

    auto viewInfo = makeStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    viewInfo.image = image.image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = { aspect, 0, 1, 0, 1 };
    VK_CHECK(vkCreateImageView(device.device, &viewInfo, nullptr, &image.view));
    return image;
}

void destroyImage(Device& device, Image& image)
{
    vkDestroyImageView(device.device, image.view, nullptr);
    vkDestroyImage(device.device, image.image, nullptr);
    vkFreeMemory(device.device, image.memory, nullptr);
    image = Image {};
}

} // namespace facesketch::gpu
