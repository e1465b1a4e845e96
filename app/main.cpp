// facesketch: turns pen strokes into 3D faces and poses them (see README.md).

#include "commands.h"
#include "core/error.h"

#include <iostream>

int main(int argc, char** argv)
{
    using namespace facesketch;
    CLI::App root { "FaceSketch: sketch 3D faces and pose them into expressions.", "facesketch" };
    root.set_version_flag("--version", "facesketch 0.1.0");
    root.require_subcommand(1);
    app::addDemoCommand(root);
    app::addRenderCommand(root);
    app::addContoursCommand(root);
    app::addPreviewCommand(root);
    app::addBenchCommand(root);
    app::addSynthCommand(root);
    app::addImportCommand(root);
    app::addTrainCommand(root);
    app::addEvalCommand(root);
    app::addSketchCommand(root);
    app::addStrokesCommand(root);
    app::addRegisterCommand(root);
    app::addTrainPosesCommand(root);
    app::addGuiCommand(root);
    app::addPoseCommand(root);
    app::addAnimateCommand(root);
    app::addImportScansCommand(*root.get_subcommand("import"));

    try {
        root.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return root.exit(e);
    } catch (const Error& e) {
        std::cerr << "facesketch: error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "facesketch: internal error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
