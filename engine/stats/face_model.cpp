#include "stats/face_model.h"

#include "core/error.h"
#include "core/names.h"
#include "core/parallel.h"
#include "stats/check.h"

#include <Eigen/QR>

#include <algorithm>
#include <atomic>
#include <iomanip>
#include <sstream>

namespace facesketch::stats {

namespace {

// The vertex-to-segment-position map of one segment: local[v] = i if the segment's i-th
// vertex is v, -1 otherwise.
std::vector<int> localIndex(const Segmentation& seg, int s, Eigen::Index vertices)
{
    std::vector<int> local(static_cast<size_t>(vertices), -1);
    const auto& members = seg.vertices[static_cast<size_t>(s)];
    for (size_t i = 0; i < members.size(); ++i)
        local[static_cast<size_t>(members[i])] = static_cast<int>(i);
    return local;
}

// Thesis 4.2.4: the closest point of the segment's clean-up subspace.
Eigen::VectorXd cleanUpSegment(const SegmentModel& sm, const Eigen::VectorXd& part)
{
    const Eigen::VectorXd centred = part - sm.cleanUp.mean;
    return sm.cleanUp.mean + sm.cleanUpBasis * (sm.cleanUpBasis.transpose() * centred);
}

} // namespace

FaceModel trainFaceModel(
    const Eigen::MatrixXd& faces, const Triangles& triangles, int noseTip, const FaceModelOptions& options, const TrainProgress& progress)
{
    requireFinite(faces, "trainFaceModel: faces");
    const Eigen::Index n = faces.rows();
    if (n < 4)
        fail("trainFaceModel: ", n, " faces, need at least 4");
    if (faces.cols() % 3 != 0 || faces.cols() == 0)
        fail("trainFaceModel: faces have ", faces.cols(), " columns, expected 3 per vertex");
    if (options.folds < 2 || options.folds > n)
        fail("trainFaceModel: folds = ", options.folds, " outside [2, ", n, "]");
    if (!(options.cleanUpVariance > 0 && options.cleanUpVariance <= 1))
        fail("trainFaceModel: cleanUpVariance = ", options.cleanUpVariance, " outside (0, 1]");
    auto report = [&](const std::string& what, double fraction) {
        if (progress)
            progress(what, fraction);
    };

    FaceModel model;
    model.triangles = triangles;
    model.meanFace = faces.colwise().mean().transpose();
    Mesh mean;
    mean.V.resize(faces.cols() / 3, 3);
    for (Eigen::Index v = 0; v < mean.V.rows(); ++v)
        mean.V.row(v) = model.meanFace.segment<3>(3 * v).transpose();
    mean.F = triangles;
    report("segmenting", 0.0);
    model.segmentation = segmentFace(mean, noseTip, options.segmentation);

    // The smallest training set cross-validation sees; each component needs more samples than
    // its latent dimension plus one, or its noise variance collapses.
    const Eigen::Index foldTrain = n - (n + options.folds - 1) / options.folds;
    // The segments' models are independent of each other (each reads only its own columns and
    // seeds its own restarts), so they are fitted on all threads, each into its own slot.
    const int segments = model.segmentation.size();
    model.segments.resize(static_cast<size_t>(segments));
    std::atomic<int> fitted { 0 };
    parallelFor(
        segments, options.threads,
        [&](int s) {
            const std::vector<Eigen::Index> coords = segmentCoordinates(model.segmentation, s);
            const Eigen::MatrixXd Xs = faces(Eigen::all, coords);
            const auto d = static_cast<Eigen::Index>(coords.size());
            MppcaOptions o = options.mppca;
            o.latentDim = static_cast<int>(std::clamp<Eigen::Index>(options.latentDim, 1, std::min(d - 1, foldTrain - 2)));
            std::vector<int> candidates;
            for (int K : options.components)
                if (K >= 1 && foldTrain / K > o.latentDim + 1)
                    candidates.push_back(K);
            if (candidates.empty())
                candidates.push_back(1);
            o.components = candidates.size() == 1 ? candidates.front() : chooseComponents(Xs, candidates, o, options.folds).best;
            const MppcaFit fit = fitMppca(Xs, o);
            SegmentModel& sm = model.segments[static_cast<size_t>(s)];
            sm.mixture = fit.model;
            sm.logLikelihood = fit.logLikelihood.back() / static_cast<double>(n);
            int cleanUpDim = static_cast<int>(std::clamp<Eigen::Index>(options.cleanUpDim, 1, std::min(d - 1, n - 2)));
            if (options.cleanUpVariance < 1)
                cleanUpDim = std::clamp(dimensionHolding(Xs, options.cleanUpVariance), 1, cleanUpDim);
            sm.cleanUp = fitPpca(Xs, cleanUpDim);
            ++fitted;
        },
        [&](int) {
            const int done = fitted.load();
            report("segment " + std::to_string(done) + " of " + std::to_string(segments), static_cast<double>(done) / (segments + 1.0));
        });

    // Correlation (4.2.5): one row of concatenated clean-up latents per training face.
    Eigen::Index total = 0;
    for (const SegmentModel& sm : model.segments)
        total += sm.cleanUp.latentDim();
    Eigen::MatrixXd L(n, total);
    Eigen::Index offset = 0;
    for (int s = 0; s < segments; ++s) {
        const Ppca& p = model.segments[static_cast<size_t>(s)].cleanUp;
        L.middleCols(offset, p.latentDim()) = latent(p, faces(Eigen::all, segmentCoordinates(model.segmentation, s)));
        offset += p.latentDim();
    }
    if (total >= 2) {
        MppcaOptions o = options.mppca;
        o.latentDim = static_cast<int>(std::clamp<Eigen::Index>(options.correlationLatentDim, 1, std::min(total - 1, n - 2)));
        o.components = static_cast<int>(std::clamp<Eigen::Index>(options.correlationComponents, 1, n / (o.latentDim + 2)));
        model.correlation = fitMppca(L, o).model;
    }
    deriveFaceModel(model);
    report("done", 1.0);
    return model;
}

Mppca composeCorrelation(const FaceModel& model)
{
    const Segmentation& seg = model.segmentation;
    const size_t segments = model.segments.size();
    Mppca joint;
    joint.priors = model.correlation.priors;
    for (const Ppca& c : model.correlation.components) {
        std::vector<Eigen::VectorXd> means(segments);
        std::vector<Eigen::MatrixXd> loadings(segments);
        double noise = 0, coordinates = 0;
        Eigen::Index offset = 0;
        for (size_t s = 0; s < segments; ++s) {
            const Ppca& p = model.segments[s].cleanUp;
            const Eigen::Index q = p.latentDim();
            // The decoder of eq. 4.20, t = mu + D x with D = W (W^T W)^+ M, as fromLatent.
            const Eigen::MatrixXd D = fromLatent(p, Eigen::MatrixXd::Identity(q, q)).transpose().colwise() - p.mean;
            means[s] = p.mean + D * c.mean.segment(offset, q);
            loadings[s] = D * c.W.middleRows(offset, q);
            noise += static_cast<double>(p.dim()) * p.sigma2 + c.sigma2 * D.squaredNorm();
            coordinates += static_cast<double>(p.dim());
            offset += q;
        }
        Ppca face;
        face.mean = blendSegments(seg, means);
        face.W.resize(face.mean.size(), c.latentDim());
        std::vector<Eigen::VectorXd> column(segments);
        for (Eigen::Index j = 0; j < c.latentDim(); ++j) {
            for (size_t s = 0; s < segments; ++s)
                column[s] = loadings[s].col(j);
            face.W.col(j) = blendSegments(seg, column);
        }
        face.sigma2 = noise / coordinates;
        joint.components.push_back(std::move(face));
    }
    return joint;
}

void deriveFaceModel(FaceModel& model)
{
    model.joint = composeCorrelation(model);
    for (SegmentModel& sm : model.segments) {
        const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(sm.cleanUp.W);
        // A W of rank 0 (no columns, or all zero, as a model file may hold) spans nothing; Eigen
        // would apply the reflections to an empty matrix through a null pointer.
        if (qr.rank() == 0)
            sm.cleanUpBasis.resize(sm.cleanUp.dim(), 0);
        else
            sm.cleanUpBasis = qr.householderQ() * Eigen::MatrixXd::Identity(sm.cleanUp.dim(), qr.rank());
    }
}

const char* correlationName(Correlation correlation)
{
    switch (correlation) {
    case Correlation::Off:
        return "off";
    case Correlation::Thesis:
        return "thesis";
    case Correlation::Joint:
        return "joint";
    }
    return "?";
}

Correlation parseCorrelation(const std::string& text)
{
    return parseName(text, std::array { Correlation::Off, Correlation::Thesis, Correlation::Joint }, correlationName, "correlation");
}

std::string describe(const FaceModel& model)
{
    std::ostringstream out;
    out << std::setw(8) << "segment" << std::setw(10) << "vertices" << std::setw(12) << "components" << std::setw(8) << "latent"
        << std::setw(10) << "clean-up" << std::setw(22) << "log-likelihood/face"
        << "\n";
    for (size_t s = 0; s < model.segments.size(); ++s) {
        const SegmentModel& sm = model.segments[s];
        out << std::setw(8) << s + 1 << std::setw(10) << model.segmentation.vertices[s].size() << std::setw(12) << sm.mixture.size()
            << std::setw(8) << (sm.mixture.size() > 0 ? sm.mixture.components.front().latentDim() : 0) << std::setw(10)
            << sm.cleanUp.latentDim() << std::setw(22) << std::fixed << std::setprecision(1) << sm.logLikelihood << "\n";
    }
    out << "correlation: " << model.correlation.size() << " components over " << model.correlation.dim() << " latents\n";
    out << "joint model: " << model.joint.size() << " components over " << model.joint.dim() << " coordinates, "
        << (model.joint.size() > 0 ? model.joint.components.front().latentDim() : 0) << " latents\n";
    return out.str();
}

Reconstruction reconstruct(const FaceModel& model, const Observations& observations, const ReconstructOptions& options)
{
    const Eigen::Index vertices = model.vertexCount();
    observations.validate(3 * vertices);
    const Segmentation& seg = model.segmentation;
    const int segments = seg.size();
    Reconstruction result;

    // Joint: all measurements condition the whole-face mixture at once.
    if (options.correlation == Correlation::Joint && model.joint.size() > 0) {
        const Inference joint = infer(model.joint, observations);
        result.jointWinner = joint.winner;
        std::vector<Eigen::VectorXd> parts(static_cast<size_t>(segments));
        for (int s = 0; s < segments; ++s) {
            const SegmentModel& sm = model.segments[static_cast<size_t>(s)];
            const Eigen::VectorXd part = joint.reconstruction(segmentCoordinates(seg, s));
            parts[static_cast<size_t>(s)] = options.cleanUp ? cleanUpSegment(sm, part) : part;
            Eigen::Index best = 0;
            componentLogLikelihoods(sm.mixture, parts[static_cast<size_t>(s)].transpose()).row(0).maxCoeff(&best);
            result.winners.push_back(static_cast<int>(best));
        }
        result.face = blendSegments(seg, parts);
        return result;
    }

    // Step 1: infer every measured segment from its own measurements.
    result.winners.assign(static_cast<size_t>(segments), -1);
    std::vector<Eigen::VectorXd> parts(static_cast<size_t>(segments));
    bool anyMeasured = false, anyUnmeasured = false;
    for (int s = 0; s < segments; ++s) {
        const Observations local = observations.restrict(localIndex(seg, s, vertices));
        const SegmentModel& sm = model.segments[static_cast<size_t>(s)];
        if (local.empty()) {
            anyUnmeasured = true;
            continue;
        }
        anyMeasured = true;
        const Inference inference = infer(sm.mixture, local);
        result.winners[static_cast<size_t>(s)] = inference.winner;
        parts[static_cast<size_t>(s)] = options.cleanUp ? cleanUpSegment(sm, inference.reconstruction) : inference.reconstruction;
    }

    // Steps 2-4 of thesis 4.2.5: the measured segments' latents are the known part of a
    // latent vector; the correlation mixture fills in the rest, rebuilt by eq. 4.20.
    Eigen::VectorXd latents;
    if (options.correlation != Correlation::Off && anyMeasured && anyUnmeasured && model.correlation.size() > 0) {
        Observations known;
        Eigen::Index offset = 0;
        for (int s = 0; s < segments; ++s) {
            const Ppca& p = model.segments[static_cast<size_t>(s)].cleanUp;
            if (result.winners[static_cast<size_t>(s)] >= 0) {
                const Eigen::VectorXd z = latent(p, parts[static_cast<size_t>(s)].transpose()).transpose();
                for (Eigen::Index j = 0; j < z.size(); ++j)
                    known.addCoordinate(offset + j, z(j));
            }
            offset += p.latentDim();
        }
        latents = infer(model.correlation, known).reconstruction;
    }
    Eigen::Index offset = 0;
    for (int s = 0; s < segments; ++s) {
        const Ppca& p = model.segments[static_cast<size_t>(s)].cleanUp;
        if (result.winners[static_cast<size_t>(s)] < 0)
            parts[static_cast<size_t>(s)] = latents.size() > 0
                ? Eigen::VectorXd(fromLatent(p, latents.segment(offset, p.latentDim()).transpose()).transpose())
                : Eigen::VectorXd(model.meanFace(segmentCoordinates(seg, s)));
        offset += p.latentDim();
    }
    result.face = blendSegments(seg, parts);
    return result;
}

Eigen::VectorXd reconstructAt(
    const FaceModel& model, const Observations& observations, const std::vector<int>& vertices, const ReconstructOptions& options)
{
    const Eigen::Index nv = model.vertexCount();
    std::vector<int> local(static_cast<size_t>(nv), -1);
    for (size_t i = 0; i < vertices.size(); ++i) {
        if (vertices[i] < 0 || vertices[i] >= nv)
            fail("reconstructAt: vertex ", vertices[i], " outside [0, ", nv, ")");
        local[static_cast<size_t>(vertices[i])] = static_cast<int>(i);
    }
    Eigen::VectorXd out(3 * static_cast<Eigen::Index>(vertices.size()));
    if (options.correlation != Correlation::Joint || model.joint.size() == 0) {
        const Eigen::VectorXd face = reconstruct(model, observations, options).face;
        for (size_t i = 0; i < vertices.size(); ++i)
            out.segment<3>(3 * static_cast<Eigen::Index>(i)) = face.segment<3>(3 * vertices[i]);
        return out;
    }
    // The winner as infer() picks it (condition() validates the measurements), then its conditional mean on the rows of `vertices`
    // only: a PPCA restricted to some coordinates is the same PPCA's rows there.
    const Inference inference = inferComponents(model.joint, observations);
    const auto winner = static_cast<size_t>(inference.winner);
    const Ppca& p = model.joint.components[winner];
    Ppca rows;
    rows.sigma2 = p.sigma2;
    rows.mean.resize(out.size());
    rows.W.resize(out.size(), p.latentDim());
    for (size_t i = 0; i < vertices.size(); ++i) {
        const Eigen::Index at = 3 * static_cast<Eigen::Index>(i);
        rows.mean.segment<3>(at) = p.mean.segment<3>(3 * vertices[i]);
        rows.W.middleRows<3>(at) = p.W.middleRows<3>(3 * vertices[i]);
    }
    return conditionalMean(rows, observations.restrict(local), inference.components[winner]);
}

} // namespace facesketch::stats
