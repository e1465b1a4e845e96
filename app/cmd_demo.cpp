// `facesketch demo`: the main job on built-in data, no input files needed. For now it
// synthesizes a standardised face dataset and draws the contour pictures the sketching
// interface reads strokes against; the interactive sketching app will take its place.

#include "commands.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "dataset/synth/synth_dataset.h"

#include <filesystem>
#include <iostream>

namespace facesketch::app {

void addDemoCommand(CLI::App& root)
{
    auto output = std::make_shared<std::string>("facesketch-demo");
    auto* cmd = root.add_subcommand("demo", "Synthesize 250 faces and draw their contours and candidate cloud (no input needed)");
    cmd->add_option("-o,--output", *output, "Folder for the dataset and the pictures")->capture_default_str();
    cmd->callback([output] {
        const std::filesystem::path folder = *output;
        std::filesystem::create_directories(folder);
        Stopwatch clock;
        dataset::SynthOptions synth;
        synth.resolution = dataset::Resolution::High;
        dataset::writeSynthDataset(folder / "faces", synth);
        std::cout << "synthesized " << synth.identities << " faces into " << (folder / "faces").string() << " in " << clock.seconds()
                  << " s\n";
        for (const char* view : { "front", "34" }) {
            ContourPictureOptions pictures;
            pictures.input = (folder / "faces").string();
            pictures.output = (folder / (std::string("contours-") + view)).string();
            pictures.view = view;
            pictures.size = 768;
            writeContourPictures(pictures);
        }
        std::cout << "open " << (folder / "contours-34-sketch.png").string() << " and its neighbours\n";
    });
}

} // namespace facesketch::app
