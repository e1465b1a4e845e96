#include "sketch/mapper_params.h"

#include "core/error.h"

#include <cmath>
#include <stdexcept>

namespace facesketch::sketch {

void MapperParams::validate() const
{
    auto positive = [](const char* name, double v) {
        if (!std::isfinite(v) || !(v > 0))
            fail("mapper parameter ", name, " = ", v, " must be positive and finite");
    };
    auto nonNegative = [](const char* name, double v) {
        if (!std::isfinite(v) || !(v >= 0))
            fail("mapper parameter ", name, " = ", v, " must be non-negative and finite");
    };
    positive("densifyGapPx", densifyGapPx);
    if (!std::isfinite(splineTension) || splineTension < 0 || splineTension > 1)
        fail("mapper parameter splineTension = ", splineTension, " must be in [0, 1]");
    positive("tauMm", tauMm);
    positive("candidateRadiusTau", candidateRadiusTau);
    positive("depthToleranceMm", depthToleranceMm);
    nonNegative("rtscThreshold", rtscThreshold);
    if (borderRings < 0 || borderRings > 16)
        fail("mapper parameter borderRings = ", borderRings, " must be in [0, 16]");
    if (similarFaces < 0)
        fail("mapper parameter similarFaces = ", similarFaces, " must be at least 0");
    if (maxCandidatesPerPoint < 1)
        fail("mapper parameter maxCandidatesPerPoint = ", maxCandidatesPerPoint, " must be at least 1");
    positive("sigmaS", sigmaS);
    positive("sigmaDTau", sigmaDTau);
    positive("sigmaC", sigmaC);
    positive("sigmaStroke", sigmaStroke);
    positive("sigmaSkelTau", sigmaSkelTau);
    nonNegative("unreachableHops", unreachableHops);
    nonNegative("drawnSigmaTau", drawnSigmaTau);
    nonNegative("lambda", lambda);
    nonNegative("alpha", alpha);
    nonNegative("beta", beta);
    nonNegative("heuristicEndpointRadiusTau", heuristicEndpointRadiusTau);
}

namespace {

// Every parameter setMapperParam knows, by its field's name.
struct ParamTable {
    std::map<std::string, double*> reals;
    std::map<std::string, int*> integers;
    std::map<std::string, bool*> flags;
};

ParamTable paramTable(MapperParams& params)
{
    return { { { "densifyGapPx", &params.densifyGapPx }, { "splineTension", &params.splineTension }, { "tauMm", &params.tauMm },
                 { "candidateRadiusTau", &params.candidateRadiusTau }, { "depthToleranceMm", &params.depthToleranceMm },
                 { "sigmaS", &params.sigmaS }, { "sigmaDTau", &params.sigmaDTau }, { "sigmaC", &params.sigmaC },
                 { "sigmaStroke", &params.sigmaStroke }, { "sigmaSkelTau", &params.sigmaSkelTau },
                 { "unreachableHops", &params.unreachableHops }, { "lambda", &params.lambda }, { "alpha", &params.alpha },
                 { "beta", &params.beta }, { "heuristicEndpointRadiusTau", &params.heuristicEndpointRadiusTau },
                 { "rtscThreshold", &params.rtscThreshold }, { "drawnSigmaTau", &params.drawnSigmaTau } },
        { { "maxCandidatesPerPoint", &params.maxCandidatesPerPoint }, { "borderRings", &params.borderRings },
            { "similarFaces", &params.similarFaces } },
        { { "ownContours", &params.ownContours }, { "viewPlaneOnly", &params.viewPlaneOnly },
            { "acrossStrokeOnly", &params.acrossStrokeOnly }, { "useConnectivity", &params.useConnectivity },
            { "useStroke", &params.useStroke }, { "strokeDepthFromFace", &params.strokeDepthFromFace },
            { "useSkeleton", &params.useSkeleton }, { "heuristicConnectivity", &params.heuristicConnectivity },
            { "rtscSuggestive", &params.rtscSuggestive } } };
}

} // namespace

void setMapperParam(MapperParams& params, const std::string& name, double value)
{
    const ParamTable table = paramTable(params);
    if (const auto r = table.reals.find(name); r != table.reals.end()) {
        *r->second = value;
    } else if (const auto i = table.integers.find(name); i != table.integers.end()) {
        if (value != std::floor(value) || std::abs(value) > 1e9)
            fail("mapper parameter ", name, " = ", value, " must be a whole number");
        *i->second = static_cast<int>(value);
    } else if (const auto f = table.flags.find(name); f != table.flags.end()) {
        if (value != 0 && value != 1)
            fail("mapper parameter ", name, " = ", value, " must be 0 or 1");
        *f->second = value == 1;
    } else {
        fail("mapper parameter '", name, "' is unknown (see MapperParams in sketch/mapper_params.h)");
    }
}

std::pair<std::string, double> parseMapperParam(const std::string& assignment)
{
    const std::size_t eq = assignment.find('=');
    if (eq == std::string::npos)
        fail("mapper parameter '", assignment, "' is not NAME=VALUE");
    const std::string name = assignment.substr(0, eq), text = assignment.substr(eq + 1);
    double value = 0;
    try {
        std::size_t used = 0;
        value = std::stod(text, &used);
        if (used != text.size())
            throw std::invalid_argument(text);
    } catch (const std::exception&) {
        fail("mapper parameter ", name, ": '", text, "' is not a number");
    }
    return { name, value };
}

void setMapperParam(MapperParams& params, const std::string& assignment)
{
    const auto [name, value] = parseMapperParam(assignment);
    setMapperParam(params, name, value);
}

std::map<std::string, double> mapperParamValues(const MapperParams& params)
{
    MapperParams copy = params; // the table points into a writable object
    const ParamTable table = paramTable(copy);
    std::map<std::string, double> out;
    for (const auto& [name, value] : table.reals)
        out[name] = *value;
    for (const auto& [name, value] : table.integers)
        out[name] = *value;
    for (const auto& [name, value] : table.flags)
        out[name] = *value ? 1.0 : 0.0;
    return out;
}

MapperParams mapperParamsFrom(const std::map<std::string, double>& values)
{
    MapperParams params;
    for (const auto& [name, value] : values)
        setMapperParam(params, name, value);
    params.validate();
    return params;
}

} // namespace facesketch::sketch
