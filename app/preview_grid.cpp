#include "preview_grid.h"

#include "gpu/device.h"
#include "io/png.h"

#include <algorithm>

namespace facesketch::app {

void writePreviewGrid(const std::string& path, int count, int cell, const std::function<void(Renderer& renderer, int face)>& addFace,
    const std::function<Camera(int view)>& camera, int views)
{
    const int columns = std::min(count, 8), rows = (count + columns - 1) / columns;
    Image grid;
    grid.width = columns * cell;
    grid.height = rows * views * cell;
    grid.pixels.assign(static_cast<size_t>(grid.width) * grid.height * 4, 255);
    {
        gpu::ScopedDevice device;
        Renderer renderer(*device, cell, cell, 4);
        for (int i = 0; i < count; ++i) {
            renderer.clear();
            addFace(renderer, i);
            for (int view = 0; view < views; ++view) {
                const Image image = renderer.render(camera(view));
                const int x0 = (i % columns) * cell, y0 = ((i / columns) * views + view) * cell;
                for (int y = 0; y < cell; ++y)
                    std::copy_n(image.at(0, y), 4 * cell, grid.at(x0, y0 + y));
            }
        }
    }
    writePng(path, grid);
}

} // namespace facesketch::app
