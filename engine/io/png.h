#pragma once
// PNG output through stb_image_write, written atomically.

#include <cstdint>
#include <filesystem>
#include <vector>

namespace facesketch {

/// An 8-bit RGBA image, rows top to bottom, pixel (x, y) at pixels[4 * (y * width + x)].
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;

    std::uint8_t* at(int x, int y) { return &pixels[4 * (static_cast<size_t>(y) * width + x)]; }
    const std::uint8_t* at(int x, int y) const { return &pixels[4 * (static_cast<size_t>(y) * width + x)]; }
};

void writePng(const std::filesystem::path& path, const Image& image);
/// Reads any PNG as RGBA (for tests and previews); throws Error naming the file if unreadable.
Image readPng(const std::filesystem::path& path);

} // namespace facesketch
