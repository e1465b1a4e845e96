// The ICT-FaceKit importer's JSON readers (import_ict.h): the pose recipes and
// vertex_indices.json. Kept apart from the import itself so that the fuzz targets
// (tests/fuzz/) link them without the geometry and the dataset writer.
#include "core/error.h"
#include "core/limits.h"
#include "dataset/import_ict.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace facesketch::dataset {

namespace fs = std::filesystem;

namespace {

template <typename Json> Json parseLimited(const fs::path& path, const char* what)
{
    const std::string text = limits::readFileLimited(path, limits::kMaxJsonFileBytes, what);
    limits::checkJsonLimits(text, path.string());
    try {
        return Json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        fail(path.string(), ": not valid JSON: ", e.what());
    }
}

} // namespace

std::vector<int> readIctLandmarkIndices(const fs::path& file)
{
    const nlohmann::json doc = parseLimited<nlohmann::json>(file, "vertex_indices.json");
    if (!doc.is_object() || !doc.contains("idx_to_landmark_verts") || !doc["idx_to_landmark_verts"].is_array())
        fail(file.string(), ": idx_to_landmark_verts: missing or not an array");
    const auto& list = doc["idx_to_landmark_verts"];
    if (list.size() != 68)
        fail(file.string(), ": idx_to_landmark_verts: has ", list.size(), " entries, expected the 68 Multi-PIE points");
    std::vector<int> out;
    for (size_t i = 0; i < list.size(); ++i) {
        if (!list[i].is_number_integer() || list[i].get<long>() < 0 || list[i].get<long>() >= kIctVertexCount)
            fail(file.string(), ": idx_to_landmark_verts[", i, "]: '", list[i].dump(), "' is not a vertex index below ", kIctVertexCount);
        out.push_back(list[i].get<int>());
    }
    return out;
}

IctPoseRecipes readIctPoseRecipes(const fs::path& path)
{
    if (!fs::is_regular_file(path))
        fail(path.string(), ": cannot open the pose recipe file");
    const nlohmann::ordered_json doc = parseLimited<nlohmann::ordered_json>(path, "a pose recipe file");
    if (!doc.is_object() || doc.empty())
        fail(path.string(), ": expected an object {\"pose\": {\"blendshape\": weight}}");
    IctPoseRecipes out;
    std::set<std::string> names;
    for (const auto& [name, shapes] : doc.items()) {
        if (name.empty() || name.find_first_of("/\\") != std::string::npos || name[0] == '.')
            fail(path.string(), ": pose name '", name, "' is empty or not file-name safe");
        if (!names.insert(name).second)
            fail(path.string(), ": ", name, ": duplicate pose");
        if (!shapes.is_object())
            fail(path.string(), ": ", name, ": expected an object {\"blendshape\": weight}");
        std::map<std::string, double> recipe;
        for (const auto& [shape, weight] : shapes.items()) {
            if (!weight.is_number() || !std::isfinite(weight.get<double>()))
                fail(path.string(), ": ", name, ".", shape, ": weight '", weight.dump(), "' is not a finite number");
            recipe[shape] = weight.get<double>();
        }
        out.push_back({ name, recipe });
    }
    return out;
}

} // namespace facesketch::dataset
