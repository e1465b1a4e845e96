// `facesketch synth`: the built-in synthetic face generator (issue 3 section 2) and its
// preview grid (front and profile of each face, rendered offscreen).
#include "commands.h"
#include "preview_grid.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "dataset/synth/pose_recipes.h"
#include "dataset/synth/synth_dataset.h"

#include <iostream>
#include <map>
#include <set>

namespace facesketch::app {

namespace {

using namespace facesketch::dataset;

// The triangles of one component as a mesh of its own (vertices renumbered from 0).
Mesh componentMesh(const Vertices& V, const Manifest& m, const Component& c)
{
    Mesh out;
    out.V = V.middleRows(c.begin, c.size());
    std::vector<Eigen::Index> keep;
    for (Eigen::Index f = 0; f < m.topology.rows(); ++f)
        if (c.contains(m.topology(f, 0)))
            keep.push_back(f);
    out.F.resize(static_cast<Eigen::Index>(keep.size()), 3);
    for (size_t i = 0; i < keep.size(); ++i)
        out.F.row(static_cast<Eigen::Index>(i)) = m.topology.row(keep[i]).array() - c.begin;
    return out;
}

glm::vec4 componentColour(const std::string& name)
{
    if (name.rfind("eye", 0) == 0)
        return { 0.93f, 0.93f, 0.9f, 1 };
    if (name.rfind("teeth", 0) == 0)
        return { 0.95f, 0.93f, 0.85f, 1 };
    if (name == "tongue")
        return { 0.8f, 0.42f, 0.42f, 1 };
    return { 0.82f, 0.68f, 0.6f, 1 };
}

// Preview colours of the skin: lips between the outer lip contours, eyebrows along theirs.
std::vector<glm::vec4> skinColours(const FaceTopology& t, glm::vec4 skin)
{
    std::vector<glm::vec4> colours(t.skin.size(), skin);
    const auto& C = t.labels.contours;
    std::map<int, std::pair<int, int>> lipRows; // column -> (upper outer row, lower outer row)
    for (int v : C.at("lip_upper_outer"))
        lipRows[t.skin[static_cast<size_t>(v)].col].first = t.skin[static_cast<size_t>(v)].row;
    for (int v : C.at("lip_lower_outer"))
        lipRows[t.skin[static_cast<size_t>(v)].col].second = t.skin[static_cast<size_t>(v)].row;
    std::set<std::pair<int, int>> brows; // (row, col) on an eyebrow
    for (const char* name : { "eyebrow_l", "eyebrow_r" })
        for (int v : C.at(name))
            brows.insert({ t.skin[static_cast<size_t>(v)].row, t.skin[static_cast<size_t>(v)].col });
    const int browRows = (t.rowKnot[2] - t.rowKnot[1]) / 3; // 0 at low resolution: rows are tall
    for (size_t i = 0; i < t.skin.size(); ++i) {
        const SkinVertex& sv = t.skin[i];
        auto it = lipRows.find(sv.col);
        if (it != lipRows.end() && sv.row >= it->second.first && sv.row <= it->second.second)
            colours[i] = { 0.72f, 0.42f, 0.40f, 1 };
        for (int dr = 0; dr <= browRows; ++dr) // the brow row and those just above it
            if (brows.count({ sv.row + dr, sv.col }))
                colours[i] = { 0.35f, 0.26f, 0.2f, 1 };
    }
    return colours;
}

// The preview grid (preview_grid.h) of `faces`, coloured by component, with the skin's lips and
// brows and the eyes' iris and pupil, in one fixed frame for every face so sizes compare.
void writePreview(const std::string& path, const FaceTopology& topology, const std::vector<Vertices>& faces, int cell)
{
    auto addFace = [&](Renderer& renderer, int i) {
        for (const Component& c : topology.labels.components) {
            MeshStyle style;
            style.color = componentColour(c.name);
            const Mesh part = componentMesh(faces[static_cast<size_t>(i)], topology.labels, c);
            std::vector<glm::vec4> colours;
            if (c.name == "skin")
                colours = skinColours(topology, style.color);
            if (c.name.rfind("eye", 0) == 0) {
                // Iris and pupil: eyeball vertices facing forward, so the eyes read as eyes.
                const Eigen::RowVector3d centre = part.V.colwise().mean();
                for (Eigen::Index v = 0; v < part.V.rows(); ++v) {
                    const Eigen::RowVector3d d = (part.V.row(v) - centre).normalized();
                    colours.push_back(d.z() > 0.97 ? glm::vec4(0.08f, 0.06f, 0.05f, 1)
                            : d.z() > 0.88         ? glm::vec4(0.33f, 0.22f, 0.12f, 1)
                                                   : style.color);
                }
            }
            renderer.addMesh(part, style, colours);
        }
    };
    auto camera = [&](int view) {
        return frameSphere(
            { 0, -35, view ? 20 : 40 }, 105, view ? ViewAngles { 90, 0 } : ViewAngles { 0, 0 }, cell, cell, Projection::Orthographic, 0.02);
    };
    writePreviewGrid(path, static_cast<int>(faces.size()), cell, addFace, camera);
}

} // namespace

void addSynthCommand(CLI::App& root)
{
    struct Options {
        SynthOptions synth;
        std::string output, resolution = "low", preview;
        int previewCount = 8, previewSize = 320;
        bool previewPoses = false;
    };
    auto o = std::make_shared<Options>();
    auto* cmd = root.add_subcommand("synth", "Generate a standardised dataset of synthetic adult faces (and their poses)");
    cmd->add_option("-o,--output", o->output, "Dataset folder to write (replaced atomically if it is a dataset)");
    cmd->add_option("--identities", o->synth.identities, "Number of faces (split train/contour/test as 182:48:20)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--resolution", o->resolution, "low (~900 vertices), high (~6,000) or ultra (~25,000)")
        ->capture_default_str()
        ->check(CLI::IsMember({ "low", "high", "ultra" }));
    cmd->add_option("--seed", o->synth.seed, "Random seed; equal seeds give byte-identical datasets")->capture_default_str();
    cmd->add_flag("--poses", o->synth.poses, "Also write the 36 poses (neutral, 21 expressions, 14 visemes)");
    cmd->add_option("--pose-identities", o->synth.poseIdentities, "Only the first N identities get poses (default: all)")
        ->check(CLI::Range(0, 100000));
    cmd->add_option("--threads", o->synth.threads, "Worker threads (0: all hardware threads)")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    cmd->add_option("--preview", o->preview, "PNG grid of faces, front above profile");
    cmd->add_option("--preview-count", o->previewCount, "Faces in the preview")->capture_default_str()->check(CLI::Range(1, 64));
    cmd->add_option("--preview-size", o->previewSize, "Pixels per preview cell")->capture_default_str()->check(CLI::Range(64, 2048));
    cmd->add_flag("--preview-poses", o->previewPoses, "Preview the 36 poses of the first face instead of several faces");
    cmd->callback([o] {
        if (o->output.empty() && o->preview.empty())
            fail("synth: nothing to do; give -o DIR and/or --preview FILE.png");
        o->synth.resolution = parseResolution(o->resolution);
        if (!o->output.empty()) {
            Stopwatch clock;
            writeSynthDataset(o->output, o->synth);
            const int poses = o->synth.poses
                ? 36 * (o->synth.poseIdentities < 0 ? o->synth.identities : std::min(o->synth.poseIdentities, o->synth.identities))
                : 0;
            std::cout << "wrote " << o->output << ": " << o->synth.identities << " " << o->resolution << " faces, " << poses
                      << " poses, seed " << o->synth.seed << " (" << clock.seconds() << " s)\n";
        }
        if (!o->preview.empty()) {
            const FaceTopology topology = buildFaceTopology(o->synth.resolution);
            std::vector<Vertices> faces;
            if (o->previewPoses) {
                const FaceParams params = sampleFaceParams(o->synth.seed, 0);
                for (const PoseRecipe& r : poseRecipes())
                    faces.push_back(synthesizeFace(topology, params, r.actions));
            } else {
                for (int i = 0; i < o->previewCount; ++i)
                    faces.push_back(synthesizeFace(topology, sampleFaceParams(o->synth.seed, i)));
            }
            writePreview(o->preview, topology, faces, o->previewSize);
            std::cout << "wrote " << o->preview << " (" << faces.size() << " faces)\n";
        }
    });
}

} // namespace facesketch::app
