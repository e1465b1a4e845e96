// `facesketch bench stats`: micro benchmarks of the statistics core on synthetic data at the
// size of a high-resolution face (6,000 vertices, d = 18,000), fixed seeds. One line per
// measurement, "name value unit":
//   conditional_6000v_ms     one infer() on K = 3, q = 30, 15% of the vertices seen in 3D
//   conditional2d_6000v_ms   the same with every observed vertex seen in 2D only
//   face_reconstruct_6000v_ms             reconstruct() with 15% of the vertices seen:
//                                         41 segments, clean-up and correlation, blended
//   face_reconstruct_one_region_6000v_ms  the same from one region's vertices only
//   mppca_fit_6000v_ms       fitMppca on n = 200 faces, K = 3, q = 20
// Takes a few seconds on one core.
#include "bench.h"

#include "core/random.h"
#include "core/stopwatch.h"
#include "stats/conditional.h"
#include "stats/face_model.h"
#include "stats/mppca.h"

#include <cmath>
#include <vector>

namespace facesketch::app {

namespace {

using namespace facesketch::stats;

// A mixture with loadings of a few millimetres on a face of `vertices` vertices.
Mppca syntheticMixture(Random& random, Eigen::Index vertices, int K, int q)
{
    Mppca model;
    const Eigen::Index d = 3 * vertices;
    for (int k = 0; k < K; ++k) {
        Ppca c;
        c.mean = 10.0 * random.normalMatrix(d, 1);
        c.W = (3.0 / std::sqrt(static_cast<double>(q))) * random.normalMatrix(d, q);
        c.sigma2 = 0.25;
        model.components.push_back(c);
    }
    model.priors = Eigen::VectorXd::Constant(K, 1.0 / K);
    return model;
}

// Median of `repeats` timings of f, in milliseconds: the median ignores a stray context switch.
template <typename F> double medianMilliseconds(int repeats, F&& f)
{
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
        Stopwatch watch;
        f();
        times.push_back(watch.milliseconds());
    }
    return median(times);
}

// A face model with random contents on a 78 by 78 grid (6,084 vertices), 41 segments with
// two rings of overlap, K = 3 and q = 8 per segment, clean-up dimension 10, one correlation
// component: the shape of the thesis' high-resolution model.
FaceModel syntheticFaceModel(Random& random)
{
    const int side = 78;
    Mesh grid;
    grid.V.resize(side * side, 3);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const double x = (i - side / 2) * 1.5, y = (j - side / 2) * 1.5;
            grid.V.row(i + side * j) << x, y, 30.0 * std::exp(-(x * x + y * y) / 400.0);
        }
    grid.F.resize(2 * (side - 1) * (side - 1), 3);
    for (int j = 0, f = 0; j + 1 < side; ++j)
        for (int i = 0; i + 1 < side; ++i, f += 2) {
            const int a = i + side * j;
            grid.F.row(f) << a, a + 1, a + side + 1;
            grid.F.row(f + 1) << a, a + side + 1, a + side;
        }
    SegmentationOptions so;
    so.clusters = 41;
    so.minVertices = 60;
    FaceModel model;
    model.triangles = grid.F;
    model.meanFace = Eigen::Map<const Eigen::VectorXd>(grid.V.data(), 3 * grid.V.rows()); // row-major xyz
    model.segmentation = segmentFace(grid, side / 2 + side * (side / 2), so);
    Eigen::Index latents = 0;
    for (int s = 0; s < model.segmentation.size(); ++s) {
        const auto vertices = static_cast<Eigen::Index>(model.segmentation.vertices[static_cast<size_t>(s)].size());
        Mppca segment = syntheticMixture(random, vertices, 3, 8);
        SegmentModel sm;
        sm.mixture = segment;
        sm.cleanUp = syntheticMixture(random, vertices, 1, 10).components.front();
        latents += 10;
        model.segments.push_back(sm);
    }
    Ppca correlation;
    correlation.mean = random.normalMatrix(latents, 1);
    correlation.W = random.normalMatrix(latents, 10);
    correlation.sigma2 = 0.25;
    model.correlation.components = { correlation };
    model.correlation.priors = Eigen::VectorXd::Ones(1);
    return model;
}

} // namespace

void benchStatsCore(const BenchOptions&, std::ostream& out)
{
    const Eigen::Index vertices = 6000;
    Random random(2010);
    const Mppca model = syntheticMixture(random, vertices, 3, 30);
    const Eigen::VectorXd face = model.components[1].mean + model.components[1].W * random.normalMatrix(30, 1);

    Observations seen3d, seen2d;
    Eigen::Matrix<double, 2, 3> view;
    const double angle = 0.4; // a three-quarter view: rotation about the vertical axis
    view << std::cos(angle), 0.0, std::sin(angle), 0.0, 1.0, 0.0;
    for (Eigen::Index v = 0; v < vertices; ++v) {
        if (random.uniform() >= 0.15)
            continue;
        const Eigen::Vector3d p = face.segment<3>(3 * v);
        seen3d.addVertex(v, p);
        seen2d.addProjectedVertex(v, view, view * p);
    }

    double sink = 0.0;
    out << "conditional_6000v_ms " << medianMilliseconds(21, [&] { sink += infer(model, seen3d).reconstruction(0); }) << " ms\n";
    out << "conditional2d_6000v_ms " << medianMilliseconds(21, [&] { sink += infer(model, seen2d).reconstruction(0); }) << " ms\n";

    // One full reconstruction: 15% of the vertices seen, segments inferred, cleaned up and
    // correlated, then blended.
    const FaceModel faceModel = syntheticFaceModel(random);
    Observations some;
    for (Eigen::Index v = 0; v < faceModel.vertexCount(); ++v)
        if (random.uniform() < 0.15)
            some.addVertex(v, faceModel.meanFace.segment<3>(3 * v) + random.normalMatrix(3, 1));
    out << "face_reconstruct_6000v_ms " << medianMilliseconds(11, [&] { sink += reconstruct(faceModel, some).face(0); }) << " ms\n";
    Observations noseOnly;
    for (Eigen::Index v = 0; v < faceModel.vertexCount(); ++v)
        if (faceModel.segmentation.core(v) == faceModel.segmentation.core(faceModel.vertexCount() / 2))
            noseOnly.addVertex(v, faceModel.meanFace.segment<3>(3 * v));
    out << "face_reconstruct_one_region_6000v_ms " << medianMilliseconds(11, [&] { sink += reconstruct(faceModel, noseOnly).face(0); })
        << " ms\n";

    Eigen::MatrixXd faces(200, 3 * vertices);
    for (Eigen::Index i = 0; i < faces.rows(); ++i) {
        const Ppca& c = model.components[static_cast<size_t>(i % 3)];
        faces.row(i) = (c.mean + c.W * random.normalMatrix(30, 1) + 0.5 * random.normalMatrix(c.dim(), 1)).transpose();
    }
    MppcaOptions options;
    options.components = 3;
    options.latentDim = 20;
    out << "mppca_fit_6000v_ms " << medianMilliseconds(1, [&] { sink += fitMppca(faces, options).logLikelihood.back(); }) << " ms\n";
    if (!std::isfinite(sink))
        out << "bench_stats_warning non-finite 0\n";
}

} // namespace facesketch::app
