#include "pose/minimal_poses.h"

#include "core/assets.h"
#include "core/error.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

namespace facesketch::pose {

namespace {

bool looksLikeFdp(const std::string& name)
{
    const auto dot = name.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == name.size())
        return false;
    return std::all_of(name.begin(), name.end(), [](char c) { return c == '.' || (c >= '0' && c <= '9'); })
        && std::count(name.begin(), name.end(), '.') == 1;
}

} // namespace

std::vector<MinimalPose> readMinimalPoses(const std::filesystem::path& path)
{
    std::ifstream in(path);
    if (!in)
        fail(path.string(), ": cannot open the minimal-pose table");
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        fail(path.string(), ": not JSON: ", e.what());
    }
    if (!doc.is_object() || !doc.contains("poses") || !doc["poses"].is_object())
        fail(path.string(), ": expected {\"poses\": {pose name: [FDP names]}}");
    std::vector<MinimalPose> out;
    for (const auto& [pose, list] : doc["poses"].items()) {
        const std::string where = path.string() + ": poses." + pose;
        if (!list.is_array() || list.empty())
            fail(where, ": expected a non-empty list of FDP names");
        MinimalPose entry { pose, {} };
        std::set<std::string> seen;
        for (const auto& item : list) {
            if (!item.is_string())
                fail(where, ": ", item.dump(), " is not a string");
            const std::string name = item.get<std::string>();
            if (!looksLikeFdp(name))
                fail(where, ": '", name, "' is not an FDP name of the form group.point (e.g. 8.3)");
            if (!seen.insert(name).second)
                fail(where, ": '", name, "' appears twice");
            entry.fps.push_back(name);
        }
        out.push_back(std::move(entry));
    }
    std::sort(out.begin(), out.end(), [](const MinimalPose& a, const MinimalPose& b) { return a.pose < b.pose; });
    return out;
}

std::vector<MinimalPose> loadMinimalPoses()
{
    return readMinimalPoses(findAsset("minimal-poses.json"));
}

} // namespace facesketch::pose
