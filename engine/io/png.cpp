#include "io/png.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/limits.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include <ostream>

namespace facesketch {

void writePng(const std::filesystem::path& path, const Image& image)
{
    if (image.width <= 0 || image.height <= 0 || image.pixels.size() != static_cast<size_t>(image.width) * image.height * 4)
        fail(path.string(), ": image ", image.width, "x", image.height, " with ", image.pixels.size(), " bytes is not RGBA");
    writeFileAtomically(path, [&](std::ostream& out) {
        auto sink
            = [](void* context, void* data, int size) { static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size); };
        if (!stbi_write_png_to_func(sink, &out, image.width, image.height, 4, image.pixels.data(), image.width * 4))
            fail(path.string(), ": PNG encoding failed");
    });
}

Image readPng(const std::filesystem::path& path)
{
    std::string bytes = limits::readFileLimited(path, limits::kMaxImageFileBytes, "a PNG file");
    // stb_image allocates what a chunk's length field claims before reading it (2 GB for a
    // 100-byte file): check every chunk against the bytes that are there first.
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    for (size_t at = 8; at + 8 <= bytes.size();) {
        const std::uint64_t length = (std::uint64_t(data[at]) << 24) | (data[at + 1] << 16) | (data[at + 2] << 8) | data[at + 3];
        if (length + 12 > bytes.size() - at)
            fail(path.string(), ": PNG chunk at byte ", at, " claims ", length, " bytes, more than the file holds (truncated or corrupt)");
        if (bytes.compare(at + 4, 4, "IEND") == 0)
            break; // stb reads nothing after it
        // An empty IDAT is legal but adds nothing; stb copies it with memcpy from a null buffer
        // when it comes first (undefined behaviour), so it is dropped here.
        if (length == 0 && bytes.compare(at + 4, 4, "IDAT") == 0) {
            bytes.erase(at, 12);
            data = reinterpret_cast<const unsigned char*>(bytes.data());
            continue;
        }
        at += length + 12;
    }
    int w = 0, h = 0, channels = 0;
    const int size = static_cast<int>(bytes.size());
    if (!stbi_info_from_memory(data, size, &w, &h, &channels))
        fail(path.string(), ": cannot read PNG: ", stbi_failure_reason());
    // The header's size, checked before stb allocates for it.
    if (static_cast<std::int64_t>(w) * h > limits::kMaxImagePixels)
        fail(path.string(), ": PNG of ", w, " by ", h, " pixels, more than the ", limits::kMaxImagePixels,
            " pixels an image may have (docs/limits.md)");
    unsigned char* pixels = stbi_load_from_memory(data, size, &w, &h, &channels, 4);
    if (!pixels)
        fail(path.string(), ": cannot read PNG: ", stbi_failure_reason());
    Image image { w, h, std::vector<std::uint8_t>(pixels, pixels + static_cast<size_t>(w) * h * 4) };
    stbi_image_free(pixels);
    return image;
}

} // namespace facesketch
