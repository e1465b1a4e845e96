#pragma once
// The parameters of stroke reading (sketch/mapper.h), by name: every sigma and threshold of the
// mappers, set one at a time from the command line (`--mapper-param NAME=VALUE`) or from what a
// session recorded (docs/session-format.md, `mapper_params`). No GPU or geometry here, so that
// the session file's reader can check a session's parameters on its own.

#include <map>
#include <string>
#include <utility>

namespace facesketch::sketch {

/// Every sigma and threshold of stroke reading. Defaults are the thesis' values where it gives
/// one (section named), and otherwise the value chosen here (said so).
struct MapperParams {
    // --- projection (4.1.1) ---
    /// Consecutive points further apart than this (pixels) get cardinal-spline points between
    /// them. The thesis says "a certain threshold"; 4 px here.
    double densifyGapPx = 4.0;
    /// Cardinal spline tension in [0, 1] (0: Catmull-Rom). Not given by the thesis.
    double splineTension = 0.0;

    // --- candidates (4.4, 4.8.5.2) ---
    /// tau: the screen-space coefficient of 4.8.5.2, "the screen distance between two fixed
    /// vertices" of the face. Here the screen length of tauMm millimetres at the face's centre,
    /// parallel to the view plane: it grows with zoom as the thesis' does, but does not depend
    /// on the topology or shrink when the two vertices line up with the view ray.
    double tauMm = 5.0;
    /// A point's candidates lie within this many tau of it on screen (4.4's "variable threshold
    /// screen distance"). The thesis gives no value; 2 tau (= sigma_d).
    double candidateRadiusTau = 2.0;
    /// ... and within this distance (mm) of the point's projected depth along the view axis
    /// (4.4's "fixed world distance"). Not given by the thesis; 40 mm keeps the front and back
    /// of a face apart but not a nose from its cheek. 15 mm helps a profile view (the HMM 0.587
    /// -> 0.540 of the mean face's error, synthetic high set, 10 test faces) but costs the front
    /// and 34 views and every view of an ICT import (docs/sketching.md, 2 December).
    double depthToleranceMm = 40.0;
    /// At most this many candidates per point, the nearest on screen (bounds m in O(n m^2)).
    /// Not given by the thesis. 96 (48 before 2 December): with the contours of 230 training
    /// faces stacked, 48 candidates cover a disc of a pixel or two, too small to hold the right
    /// vertex as often as it could (`eval strokes`, 8 test faces, 1 px noise: the HMM's
    /// observations within 1 mm of their vertex's true image 0.46 -> 0.53 in the front view).
    int maxCandidatesPerPoint = 96;
    /// Silhouette candidates (not labelled) on vertices fewer than this many rings from the
    /// mesh's open border are dropped: a face mask's border seen edge-on is a silhouette of
    /// the mask, not of the face (issue 12's suspect). 0 keeps them all (the thesis).
    int borderRings = 0;
    /// The suggestive contours' filter of the candidate cloud (contours/candidates.h): false,
    /// FaceSketch's vertex strength (D_w k_r l^2 > 0.02 at the vertex); true, rtsc's test at the
    /// zero crossing (tan(theta) D_w k_r l^2 > rtscThreshold, as DeCarlo and Rusinkiewicz's
    /// reference implementation draws them). Measured in docs/sketching.md ("Suggestive
    /// contours as rtsc draws them").
    bool rtscSuggestive = false;
    double rtscThreshold = 0.01; ///< rtsc's sug_thresh
    /// The current face's own contour candidates join the training faces' cloud (mesh index
    /// = the number of candidate faces). Beyond the thesis: as the face approaches the sketched
    /// one, its own contours carry the right vertex where other faces offer a neighbour's
    /// (evaluation/contour_eval.h does the same in its refinements). Costs the curvature of the
    /// face around the stroke's box per reading (contours/region_candidates.h).
    bool ownContours = false;
    /// Observations pin only the image of the vertex in the view (its depth is left to the
    /// model) instead of the candidate's depth adapted to the stroke (4.6.2). On by default
    /// (with acrossStrokeOnly): the candidate's depth is another face's; thesis() turns it off.
    bool viewPlaneOnly = true;
    /// Observations pin a vertex only across the stroke in the view plane (and its depth,
    /// unless viewPlaneOnly), not along it (VertexObservation::acrossStroke). Beyond the
    /// thesis, whose 4.6.2 pins the stroke point itself: which vertex of a contour lies under
    /// which point is the least certain part of a mapping (a mapped vertex is typically a
    /// neighbour along the line), and pinning it there drags the contour's vertices along the
    /// stroke into each other's places. On by default: with viewPlaneOnly, `eval strokes`
    /// (1 px noise, 4 test faces) takes the HMM from 0.73 / 0.76 / 0.70 / 0.56 of the mean face's
    /// error (front / profile / 34 / all views) to 0.65 / 0.60 / 0.54 / 0.44 on the synthetic
    /// high set, and from 0.82 / 0.78 / 0.94 / 0.71 to 0.83 / 0.57 / 0.78 / 0.56 on an ICT
    /// import (docs/sketching.md); thesis() turns it off.
    bool acrossStrokeOnly = true;
    /// When positive, only the candidates of this many training faces count: those nearest the
    /// current face (mean squared vertex distance). 0: every face (the thesis' cloud). Once the
    /// face approaches the sketched one (after earlier strokes, or on a second reading of the
    /// same stroke), the faces most like it place each vertex nearest where the sketched face
    /// has it, so the vertex under a stroke point is more often the right one.
    /// 80 (0 before 2 December, evening): with the tracking model's noisy rows and robust
    /// passes it helps the HMM on the fitting faces (`eval strokes --faces contour`, 12 faces,
    /// 1 px noise, front / profile / 34 / all): synthetic high set 0.504 / 0.526 / 0.486 /
    /// 0.302 -> 0.469 / 0.529 / 0.391 / 0.221, ICT import 0.730 / 0.554 / 0.582 / 0.506 ->
    /// 0.686 / 0.521 / 0.545 / 0.454 (60 and 110 faces were within 0.04 on the synthetic set).
    /// 100 since 5 December, refitted on all 48 fitting faces of synthetic high v18 (182 faces
    /// in their cloud; `eval strokes --faces contour`, HMM, 1 px, front / profile / 34 / all,
    /// mean of seeds 1 and 2): 80 0.615 / 0.434 / 0.488 / 0.292, 100 0.593 / 0.433 / 0.479 /
    /// 0.285, 120 0.583 / 0.436 / 0.479 / 0.286; ICT import's fitting faces 80 0.660 / 0.478 /
    /// 0.457 / 0.377, 100 0.639 / 0.478 / 0.462 / 0.376. Fewer faces leave out the few whose
    /// line lies where an unusual face has it (the lips' misreads, docs/sketching.md).
    int similarFaces = 100;

    // --- HMM (4.8.5) ---
    double sigmaS = 0.4; ///< initial probability, eq. 4.45
    /// Emission, eq. 4.47: sigma_d = sigmaDTau x tau. The thesis' 2 tau (thesis()) is nearly
    /// flat over a point's candidates, which then lie within a few pixels: the transitions
    /// alone choose. 0.3 tau (1.5 mm at the face's centre) lets the distance to the stroke
    /// count; with 96 candidates per point it takes the HMM from 0.530 / 0.651 / 0.433 / 0.390
    /// of the mean face's error to 0.491 / 0.603 / 0.390 / 0.361 (front / profile / 34 / all,
    /// synthetic high set, 8 test faces, 1 px noise) and from 0.961 / 0.597 / 0.818 / 0.607
    /// to 0.914 / 0.577 / 0.751 / 0.567 on an ICT import (docs/sketching.md).
    double sigmaDTau = 0.3;
    double sigmaC = 3.0;             ///< connectivity, eq. 4.48 (hops in the k-ring map)
    double sigmaStroke = 0.5;        ///< stroke ratio, eq. 4.50
    double sigmaSkelTau = 1.0 / 6.5; ///< skeleton, eq. 4.52: sigma_skel = sigmaSkelTau x tau
    /// Hops charged to a transition between vertices more than k = 4 rings apart (4.8.4 calls
    /// such transitions infeasible; a finite charge keeps a stroke readable across a gap in the
    /// candidates). Not given by the thesis.
    double unreachableHops = 8.0;
    bool useConnectivity = true; ///< gamma_1 (4.48) on; off for the thesis' comparison of 4.9
    bool useStroke = true;       ///< gamma_2 (4.50)
    bool useSkeleton = true;     ///< gamma_3 (4.52)
    /// Between two labelled-line candidates, the depth in 4.49's c' is their change in depth
    /// beyond the current face's own between the same two vertices, not their change alone.
    /// The thesis wants "equal displacement with minimum change in depth", which holds for lines
    /// facing the camera; a line that recedes in depth (the eye's slit or the eyebrow seen from
    /// the side) moves far in depth between stroke points a few pixels apart, and the thesis'
    /// term kept the HMM on a few of its vertices (tests/sketch/mapper.cpp: 4-5 vertices, 0.4 of
    /// the slit covered; now all of it). Labelled lines only: applied to every candidate, the
    /// ICT import's front view lost 0.043. A silhouette's vertices differ from face to face,
    /// and there the charge on depth probably keeps a path from jumping between a cheek's and
    /// an ear's silhouette (kept to labelled lines, that view gains 0.009 instead). HMM, 1 px,
    /// front / profile / 34 / all, the thesis' term -> this: 48 fitting faces of synthetic
    /// high v18 0.617 / 0.447 / 0.495 / 0.297 -> 0.625 / 0.430 / 0.489 / 0.296; ICT import
    /// 0.629 / 0.462 / 0.459 / 0.364 -> 0.620 / 0.465 / 0.436 / 0.363; v18's 20 test faces
    /// 0.563 / 0.426 / 0.397 / 0.296 -> 0.562 / 0.409 / 0.399 / 0.301 (docs/sketching.md).
    /// false in thesis().
    bool strokeDepthFromFace = true;
    /// What the user already drew in this view (StrokeReader::read's `drawn`): a candidate whose
    /// vertex an earlier stroke of a similar view constrains is charged, in its emission, for
    /// the screen distance from the stroke point to that vertex on the current face, as a
    /// Gaussian of drawnSigmaTau x tau (0: off). The current face passes near what was drawn, so
    /// a stroke is not read onto a line the user already put elsewhere. Not in the thesis,
    /// which read every stroke against the candidates alone (4.8.5); why: docs/sketching.md,
    /// "What was drawn before". Off in thesis().
    double drawnSigmaTau = 0.5;

    // --- heuristic (4.6.1) ---
    double lambda = 1.0; ///< weight of the endpoint term of eq. 4.29 (in tau units)
    double alpha = 0.5;  ///< weight of s1 (4.36); alpha + beta = 1
    double beta = 0.5;   ///< weight of s2 (4.37)
    /// Multiply the grade's error by (1 + hops) between the previous and the candidate vertex
    /// (4.9's "heuristic approach with connectivity", which the thesis found much better than
    /// 4.29 alone; here too: on the lip test, 0.9 of the vertices on or next to the lip with it,
    /// 0.5 without). false gives 4.6's grade alone.
    bool heuristicConnectivity = true;
    /// The endpoint term chooses among the end point's candidates within this many tau (and
    /// always the nearest): 4.30-4.31 pick the box's extreme, which over the whole candidate
    /// radius overshoots the stroke's end. Not in the thesis (its radius was one threshold).
    double heuristicEndpointRadiusTau = 0.5;

    /// The thesis' values: the defaults, but observations pinning the stroke point in 3D
    /// (4.6.2: the candidate adapted to the stroke, with its depth) instead of across the stroke
    /// in the view plane, sigma_d = 2 tau (4.8.5.2), the 48 candidates per point used before
    /// 2 December and 4.49's depth as the candidates' own.
    static MapperParams thesis()
    {
        MapperParams p;
        p.sigmaDTau = 2.0;
        p.maxCandidatesPerPoint = 48;
        p.viewPlaneOnly = false;
        p.acrossStrokeOnly = false;
        p.strokeDepthFromFace = false;
        p.drawnSigmaTau = 0.0;
        return p;
    }
    /// Throws Error naming the first field that is not positive/finite where it must be.
    void validate() const;
};

/// Sets one field of `params` from "NAME=VALUE" (NAME a MapperParams field as spelled above,
/// VALUE a number; booleans 0 or 1, integers whole), for studies from the command line. Throws
/// Error naming an unknown field or a value that does not parse, leaving params unchanged; the
/// value's range is checked by validate() when the parameters are used.
void setMapperParam(MapperParams& params, const std::string& assignment);
/// "NAME=VALUE" split into the name and the number, as setMapperParam reads it (the name not
/// checked); Error for text without '=' or a value that is not a number.
std::pair<std::string, double> parseMapperParam(const std::string& assignment);
/// The same with the name and value apart (a session's recorded parameters; a flag is 0 or 1).
void setMapperParam(MapperParams& params, const std::string& name, double value);

/// Every parameter setMapperParam knows, by name, with its value in `params` (flags 0 or 1):
/// what a session records so that a stroke is read again with the parameters it was read with.
std::map<std::string, double> mapperParamValues(const MapperParams& params);

/// The defaults with each of `values` set (setMapperParam), then validated: a session's recorded
/// parameters. Names left out keep the defaults. Throws Error naming an unknown parameter, a
/// value of the wrong kind or one validate() refuses.
MapperParams mapperParamsFrom(const std::map<std::string, double>& values);

} // namespace facesketch::sketch
