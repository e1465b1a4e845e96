#pragma once
// Subcommands of the `facesketch` executable. Each addXxxCommand adds one subcommand to the
// root CLI11 app and sets its callback; main() parses and reports facesketch::Error as a
// one-line message with exit code 1.

#include "contours/candidates.h"

#include <CLI/CLI.hpp>
#include <string>

namespace facesketch::app {

void addRenderCommand(CLI::App& root);
void addBenchCommand(CLI::App& root);
void addDemoCommand(CLI::App& root);
void addContoursCommand(CLI::App& root);
void addPreviewCommand(CLI::App& root);
void addSynthCommand(CLI::App& root);
void addImportCommand(CLI::App& root);
void addTrainCommand(CLI::App& root);
void addEvalCommand(CLI::App& root);
void addSketchCommand(CLI::App& root);
void addStrokesCommand(CLI::App& root);
void addRegisterCommand(CLI::App& root);
/// `facesketch train-poses` (cmd_train_poses.cpp): the pose model of a posed dataset.
void addTrainPosesCommand(CLI::App& root);
/// `facesketch gui`, the interactive app (gui/cmd_gui.cpp).
void addGuiCommand(CLI::App& root);
/// `facesketch pose` and `facesketch animate` (cmd_pose.cpp).
void addPoseCommand(CLI::App& root);
void addAnimateCommand(CLI::App& root);
/// `facesketch import scans`, a subcommand of `import` (cmd_import.cpp creates `import`).
void addImportScansCommand(CLI::App& import);

/// `facesketch eval contours`, a subcommand of `eval` (cmd_eval.cpp creates `eval`).
void addEvalContoursCommand(CLI::App& eval);
/// `facesketch eval strokes` (cmd_eval_strokes.cpp).
void addEvalStrokesCommand(CLI::App& eval);
/// `facesketch eval poses` (cmd_eval_poses.cpp).
void addEvalPosesCommand(CLI::App& eval);
/// `facesketch eval realism` (cmd_eval_realism.cpp).
void addEvalRealismCommand(CLI::App& eval);

/// What `facesketch contours` draws (also used by `facesketch demo`).
struct ContourPictureOptions {
    std::string input;               ///< dataset folder or mesh file
    std::string output = "contours"; ///< prefix of the PNGs
    std::string view = "front";
    int size = 1024;
    int maxFaces = 230;
    double suggestive = ContourParams {}.suggestiveThreshold;
    double rtsc = -1;       ///< >= 0: suggestive contours by rtsc's filter with this threshold instead
    double silhouette = -1; ///< negative: the resolution-dependent default
    bool perspective = false;
    bool noCache = false; ///< compute the curvature even if a cache file holds it
};
/// Writes PREFIX-face.png, -sketch.png, -cloud.png and -density.png; prints a summary.
void writeContourPictures(const ContourPictureOptions& options);

} // namespace facesketch::app
