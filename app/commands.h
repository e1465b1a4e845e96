#pragma once
// Subcommands of the `facesketch` executable. Each addXxxCommand adds one subcommand to the
// root CLI11 app and sets its callback; main() parses and reports facesketch::Error as a
// one-line message with exit code 1.

#include <CLI/CLI.hpp>

namespace facesketch::app {

void addRenderCommand(CLI::App& root);
void addBenchCommand(CLI::App& root);
void addDemoCommand(CLI::App& root);

} // namespace facesketch::app
