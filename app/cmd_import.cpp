// `facesketch import`: real data as standardised datasets (issue 3 section 3): a folder of
// meshes in correspondence, the ICT Face Model Light, and the shared-topology simplification
// (--vertices) of either or of any existing dataset.
#include "commands.h"

#include "core/assets.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "dataset/import_ict.h"
#include "dataset/import_meshes.h"
#include "dataset/simplify.h"

#include <cstdlib>
#include <iostream>

namespace facesketch::app {

namespace {

namespace fs = std::filesystem;
using namespace facesketch::dataset;

// The pose recipes: --recipes, else the ict-poses.json installed with the program
// (core/assets.h).
fs::path findRecipes(const std::string& given)
{
    return given.empty() ? findAsset("ict-poses.json") : fs::path(given);
}

} // namespace

void addImportCommand(CLI::App& root)
{
    auto* cmd = root.add_subcommand("import", "Turn real face data into a standardised dataset (meshes, ICT-FaceKit)");
    cmd->require_subcommand(1);

    // import meshes DIR
    {
        struct Options {
            std::string folder, output;
            MeshImportOptions o;
            std::string labels;
        };
        auto o = std::make_shared<Options>();
        auto* sub = cmd->add_subcommand("meshes",
            "A folder of .obj/.ply meshes sharing one topology becomes a dataset.\n"
            "Optional DIR/landmarks.json gives units, landmarks, mpeg4, contours,\n"
            "components, excluded (see engine/dataset/import_meshes.h).");
        sub->add_option("DIR", o->folder, "Folder of meshes in correspondence (same vertex count and triangles)")->required();
        sub->add_option("-o,--output", o->output, "Dataset folder to write (replaced atomically if it is a dataset)")->required();
        sub->add_option("--labels", o->labels, "Labels file (default: DIR/landmarks.json if present)");
        sub->add_option("--seed", o->o.seed, "Seed of the shuffle that assigns train/contour/test roles")->capture_default_str();
        sub->add_option("--vertices", o->o.vertices, "Simplify to about N vertices, keeping every labelled vertex (0: keep all)")
            ->capture_default_str()
            ->check(CLI::Range(0, 10000000));
        sub->callback([o] {
            o->o.labels = o->labels;
            Stopwatch clock;
            const Manifest m = importMeshes(o->folder, o->output, o->o);
            std::cout << "wrote " << o->output << ": " << m.samples.size() << " faces, " << m.vertexCount << " vertices ("
                      << clock.seconds() << " s)\n";
        });
    }

    // import ict-facekit PATH
    {
        struct Options {
            std::string path, output, region = "face", recipes;
            IctOptions o;
        };
        auto o = std::make_shared<Options>();
        auto* sub = cmd->add_subcommand("ict-facekit",
            "Sample identities (and poses) from the ICT Face Model Light in its original layout\n"
            "(PATH/FaceXModel/*.obj); units become mm (see engine/dataset/import_ict.h).");
        sub->add_option("PATH", o->path, "ICT-FaceKit folder (holding FaceXModel/) or the FaceXModel folder")->required();
        sub->add_option("-o,--output", o->output, "Dataset folder to write (replaced atomically if it is a dataset)")->required();
        sub->add_option("--identities", o->o.identities, "Number of faces (split train/contour/test as 182:48:20)")
            ->capture_default_str()
            ->check(CLI::Range(1, 100000));
        sub->add_option("--seed", o->o.seed, "Random seed of the identity coefficients; equal seeds give identical datasets")
            ->capture_default_str();
        sub->add_option("--region", o->region, "Skin region: narrow (narrow face), face, head (head and neck)")
            ->capture_default_str()
            ->check(CLI::IsMember({ "narrow", "face", "head" }));
        sub->add_flag("--with-eyes", o->o.eyes, "Also the eye sockets and eyeballs");
        sub->add_flag("--with-mouth", o->o.mouth, "Also the mouth socket, gums and tongue, and teeth");
        sub->add_flag("--poses", o->o.poses, "Also write the 36 poses (recipes in assets/ict-poses.json)");
        sub->add_option("--pose-identities", o->o.poseIdentities, "Only the first N identities get poses (default: all)")
            ->check(CLI::Range(0, 100000));
        sub->add_option("--recipes", o->recipes, "Pose recipe file (default: the project's assets/ict-poses.json)");
        sub->add_option("--vertices", o->o.vertices, "Simplify to about N vertices, keeping every labelled vertex (0: keep all)")
            ->capture_default_str()
            ->check(CLI::Range(0, 10000000));
        sub->callback([o] {
            o->o.region = parseIctRegion(o->region);
            if (o->o.poses)
                o->o.recipes = findRecipes(o->recipes);
            Stopwatch clock;
            const Manifest m = writeIctDataset(o->path, o->output, o->o);
            std::cout << "wrote " << o->output << ": " << m.samples.size() << " ICT faces (" << o->region << ", " << m.vertexCount
                      << " vertices), " << m.poses.size() << " poses, seed " << o->o.seed << " (" << clock.seconds() << " s)\n";
        });
    }

    // import dataset DIR --vertices N
    {
        struct Options {
            std::string input, output;
            int vertices = 0;
        };
        auto o = std::make_shared<Options>();
        auto* sub = cmd->add_subcommand("dataset", "Simplify an existing dataset to a coarser shared topology");
        sub->add_option("DIR", o->input, "Dataset folder to read")->required();
        sub->add_option("-o,--output", o->output, "Dataset folder to write")->required();
        sub->add_option("--vertices", o->vertices, "About N vertices; every labelled vertex is kept")
            ->required()
            ->check(CLI::Range(4, 10000000));
        sub->callback([o] {
            Stopwatch clock;
            const int n = simplifyDataset(o->input, o->output, o->vertices);
            std::cout << "wrote " << o->output << ": " << n << " vertices (" << clock.seconds() << " s)\n";
        });
    }
}

} // namespace facesketch::app
