#include "model/regions.h"

#include "core/error.h"
#include "model/head_model.h"

#include <map>
#include <set>

namespace facesketch::model {

namespace {

struct Seeds {
    std::vector<std::string> landmarks; // a trailing '*' stands for _l and _r
    std::vector<std::string> contours;
};

const std::map<std::string, Seeds>& regionSeeds()
{
    static const std::map<std::string, Seeds> seeds = {
        { "nose", { { "prn", "al*", "sbal*", "sn", "cs1" }, { "nostril*" } } },
        { "mouth",
            { { "ls", "li", "sto", "ch*", "cph*" }, { "lip_upper_outer", "lip_lower_outer", "lip_upper_inner", "lip_lower_inner" } } },
        { "chin", { { "pg", "gn", "sl" }, {} } },
        { "eyes", { { "en*", "ex*", "ps*", "pi*" }, { "eye_socket*" } } },
        { "brows", { { "os*", "mf*", "g" }, { "eyebrow*" } } },
    };
    return seeds;
}

std::vector<std::string> expand(const std::string& name)
{
    if (!name.empty() && name.back() == '*') {
        const std::string stem = name.substr(0, name.size() - 1);
        return { stem + "_l", stem + "_r" };
    }
    return { name };
}

} // namespace

std::vector<std::string> featureRegionNames()
{
    return { "nose", "mouth", "chin", "eyes", "brows", "mouth_chin", "eyes_brows" };
}

std::vector<int> featureRegion(const dataset::Manifest& manifest, const stats::FaceModel& model, const std::string& name, double radius)
{
    const Eigen::Index S = model.vertexCount();
    if (name.rfind("segment:", 0) == 0) {
        int s = -1;
        try {
            size_t used = 0;
            s = std::stoi(name.substr(8), &used);
            if (used != name.size() - 8)
                s = -1;
        } catch (const std::exception&) {
        }
        if (s < 1 || s > model.segmentation.size())
            fail("region ", name, ": the model has segments 1 to ", model.segmentation.size());
        std::vector<int> out;
        for (Eigen::Index v = 0; v < S; ++v)
            if (model.segmentation.core(v) == s - 1)
                out.push_back(static_cast<int>(v));
        return out;
    }
    std::vector<std::string> parts = { name };
    if (name == "mouth_chin")
        parts = { "mouth", "chin" };
    else if (name == "eyes_brows")
        parts = { "eyes", "brows" };
    const dataset::Component* skin = manifest.component("skin");
    if (!skin || skin->size() != S)
        fail("region ", name, ": the dataset's skin does not match the model's ", S, " vertices");

    std::set<int> seeds; // skin vertices, model numbering
    for (const std::string& part : parts) {
        const auto it = regionSeeds().find(part);
        if (it == regionSeeds().end())
            fail("unknown region '", name, "' (nose, mouth, chin, eyes, brows, mouth_chin, eyes_brows or segment:N)");
        for (const std::string& l : it->second.landmarks)
            for (const std::string& e : expand(l)) {
                const auto found = manifest.landmarks.find(e);
                if (found != manifest.landmarks.end() && skin->contains(found->second))
                    seeds.insert(found->second - skin->begin);
            }
        for (const std::string& c : it->second.contours)
            for (const std::string& e : expand(c)) {
                const auto found = manifest.contours.find(e);
                if (found != manifest.contours.end())
                    for (int v : found->second)
                        if (skin->contains(v))
                            seeds.insert(v - skin->begin);
            }
    }
    if (seeds.empty())
        fail("region ", name, ": the dataset has none of its landmarks or contours");
    std::vector<int> out;
    const double r2 = radius * radius;
    for (Eigen::Index v = 0; v < S; ++v)
        for (int s : seeds)
            if ((model.meanFace.segment<3>(3 * v) - model.meanFace.segment<3>(3 * s)).squaredNorm() <= r2) {
                out.push_back(static_cast<int>(v));
                break;
            }
    return out;
}

} // namespace facesketch::model
