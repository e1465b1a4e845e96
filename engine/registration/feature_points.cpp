#include "registration/feature_points.h"

#include "core/error.h"
#include "geometry/similarity.h"
#include "registration/surface_query.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

namespace facesketch::registration {

const std::vector<std::string>& landmarkNames()
{
    static const std::vector<std::string> names = { "g", "n", "s", "cs1", "prn", "sn", "al_l", "al_r", "sbal_l", "sbal_r", "en_l", "en_r",
        "ex_l", "ex_r", "ps_l", "ps_r", "pi_l", "pi_r", "os_l", "os_r", "mf_l", "mf_r", "ls", "sto", "li", "ch_l", "ch_r", "cph_l", "cph_r",
        "sl", "pg", "gn", "obs_l", "obs_r" };
    return names;
}

const std::vector<std::string>& requiredFeaturePoints()
{
    static const std::vector<std::string> names = { "prn", "sn", "en_l", "en_r", "ex_l", "ex_r", "ch_l", "ch_r", "pg" };
    return names;
}

FeaturePoints readFeaturePoints(const std::filesystem::path& path)
{
    std::ifstream in(path);
    if (!in)
        fail(path.string(), ": cannot open the feature points");
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        fail(path.string(), ": not JSON: ", e.what());
    }
    if (!doc.is_object())
        fail(path.string(), ": expected an object {name: [x, y, z]}");
    const auto& known = landmarkNames();
    FeaturePoints points;
    for (const auto& [name, value] : doc.items()) {
        if (std::find(known.begin(), known.end(), name) == known.end())
            fail(path.string(), ": ", name, ": not a landmark name of docs/dataset-format.md");
        if (!value.is_array() || value.size() != 3)
            fail(path.string(), ": ", name, ": expected [x, y, z]");
        Eigen::Vector3d p;
        for (int k = 0; k < 3; ++k) {
            if (!value[static_cast<std::size_t>(k)].is_number())
                fail(path.string(), ": ", name, "[", k, "]: not a number");
            p(k) = value[static_cast<std::size_t>(k)].get<double>();
            if (!std::isfinite(p(k)))
                fail(path.string(), ": ", name, "[", k, "]: not finite");
        }
        points[name] = p;
    }
    return points;
}

void validateFeaturePoints(
    const FeaturePoints& points, const SurfaceQuery& scan, const std::string& scanName, const FeaturePointLimits& limits)
{
    for (const auto& name : requiredFeaturePoints())
        if (!points.count(name))
            fail(scanName, ": feature point '", name, "' is missing (required: prn, sn, en_l, en_r, ex_l, ex_r, ch_l, ch_r, pg)");
    for (const auto& [name, p] : points)
        if (!p.allFinite())
            fail(scanName, ": feature point '", name, "' is not finite");
    for (auto a = points.begin(); a != points.end(); ++a)
        for (auto b = std::next(a); b != points.end(); ++b)
            if ((a->second - b->second).norm() < limits.minSeparation)
                fail(scanName, ": feature points '", a->first, "' and '", b->first, "' are at the same place (",
                    (a->second - b->second).norm(), " apart, at least ", limits.minSeparation, " expected)");
    Vertices P(static_cast<Eigen::Index>(points.size()), 3);
    Eigen::Index row = 0;
    for (const auto& [name, p] : points)
        P.row(row++) = p.transpose();
    const Eigen::MatrixX3d centred = P.rowwise() - P.colwise().mean();
    const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::MatrixX3d>(centred).singularValues();
    if (sv(1) < 1e-3 * sv(0))
        fail(scanName, ": the feature points lie on one line");
    if (sv(2) < 1e-3 * sv(0))
        fail(scanName, ": the feature points lie on one plane (the fit's affine part needs depth, e.g. prn in front of the eyes)");
    for (const auto& [name, p] : points) {
        const ClosestPoint c = scan.closest(p);
        if (c.distance > limits.maxDistanceFromSurface)
            fail(scanName, ": feature point '", name, "' (", p(0), ", ", p(1), ", ", p(2), ") is ", c.distance,
                " mm from the scan's surface (at most ", limits.maxDistanceFromSurface, " mm)");
    }
}

CompletedPoints completeFeaturePoints(const FeaturePoints& templatePoints, const FeaturePoints& scanPoints, const std::string& scanName)
{
    CompletedPoints out;
    std::vector<std::string> shared;
    for (const auto& [name, p] : templatePoints) {
        out.names.push_back(name);
        if (scanPoints.count(name))
            shared.push_back(name);
        else
            out.estimated.push_back(name);
    }
    for (const auto& [name, p] : scanPoints)
        if (!templatePoints.count(name))
            out.unused.push_back(name);
    if (shared.size() < 4)
        fail(scanName, ": only ", shared.size(), " feature points are also on the template (at least 4 needed)");
    Vertices from(static_cast<Eigen::Index>(shared.size()), 3), to(static_cast<Eigen::Index>(shared.size()), 3);
    for (std::size_t i = 0; i < shared.size(); ++i) {
        from.row(static_cast<Eigen::Index>(i)) = templatePoints.at(shared[i]).transpose();
        to.row(static_cast<Eigen::Index>(i)) = scanPoints.at(shared[i]).transpose();
    }
    const Similarity similarity = fitSimilarity(from, to);
    const auto n = static_cast<Eigen::Index>(out.names.size());
    out.templatePoints.resize(n, 3);
    out.scanPoints.resize(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
        const std::string& name = out.names[static_cast<std::size_t>(i)];
        const Eigen::Vector3d t = templatePoints.at(name);
        out.templatePoints.row(i) = t.transpose();
        const auto given = scanPoints.find(name);
        out.scanPoints.row(i) = (given != scanPoints.end() ? given->second : similarity.apply(t)).transpose();
    }
    return out;
}

} // namespace facesketch::registration
