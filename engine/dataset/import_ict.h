#pragma once
// `facesketch import ict-facekit PATH`: a standardised dataset (thesis 3.1) sampled from the
// ICT Face Model Light (ICT-FaceKit, USC Institute for Creative Technologies, MIT licence:
// https://github.com/ICT-VGL/ICT-FaceKit), read in its original layout.
//
// Input. PATH is the ICT-FaceKit folder (or its FaceXModel/ folder) holding
// `FaceXModel/generic_neutral_mesh.obj` (26,719 vertices, quads, centimetres, +y up, looking
// down +z, +x the face's left), `identity000.obj`, `identity001.obj`, ... (the neutral moved one
// standard deviation along each identity mode), ARKit-named expression shapes (`jawOpen.obj`,
// `mouthSmile_L.obj`, ...) and optionally `vertex_indices.json` (its `idx_to_landmark_verts`
// gives the 68 Multi-PIE landmarks; without it the index list of ICT-FaceKit's README is used).
// Only the neutral's faces are read; every other file contributes its `v` lines only (files cut
// down to `v` lines are accepted) and must have the neutral's vertex count.
//
// Identities. Identity j is neutral + sum_i c_ji (identity_i - neutral) with c_ji ~ N(0, 1),
// drawn from core/random.h's Random seeded by splitMix64(splitMix64(seed) ^ j), with
// BoxMuller::PlusOne (portable: std::normal_distribution differs between standard libraries).
// Identity j does not depend on how many identities are drawn. Units become mm.
//
// Region. The skin is a prefix of ICT's vertex order (README "Regions"): narrow face
// [0, 6706), face [0, 9409) or head and neck [0, 11248). --with-eyes adds the eye sockets and
// eyeballs, --with-mouth the mouth socket, the gums ("gums": the rest of ICT's gums and tongue
// mesh, with the floor and the back of the mouth), the tongue ("tongue") and the upper and lower teeth. ICT's gums and tongue
// [14062, 17039) are one connected mesh; its last 428 vertices, [16611, 17039), are the tongue
// body, open at the root and sewn to the floor of the mouth by 25 edges along the frenulum. The
// split was found on the neutral by a rule that ignores the vertex order: among the jaw-borne
// gums/tongue vertices (jawOpen moves them more than 5 mm), the floor of the mouth is those with
// jaw-borne surface more than 0.5 mm directly above them, none below, and a normal not pointing
// down (n_y > -0.5); the tongue is what stays connected to the highest midline jaw-borne vertex
// when the floor is removed. That gives 426 vertices: [16611, 17039) less 4 at the frenulum seam
// plus 2 floor vertices on the seam, so the range is used as it is. Triangles are those of the
// neutral (quads split in a fan) whose three vertices are kept. Socket vertices are "excluded"
// (inside the head, never contour candidates), and so are the skin vertices inside each
// nostril rim (the cavity, seen only from below).
//
// Labels (names as docs/dataset-format.md). Landmarks come from the Multi-PIE points (0-based
// iBUG numbering; 0..16 jaw line from the face's right, 17..21 right brow, 22..26 left brow,
// 27..30 nasal bridge, 31..35 nose base, 36..41 right eye, 42..47 left eye, 48..59 outer lips,
// 60..67 inner lips) where one exists, else by geometric rules on the neutral:
//   ex/en = 36, 39, 42, 45; ch = 48, 54; ls = 51; li = 57; sto = 62; sn = 33; sbal = 31, 35;
//   cph = 50, 52; n = 27; cs1 = 29; gn = 8; obs = 0, 16 (top of the jaw line, by the ear);
//   prn = the skin vertex within 1 cm of point 30 that lies within 3 mm of the most forward
//   skin vertex for the most of 64 identities (seed 0), ties to the smaller mean distance (the
//   tip moves between people across vertices about 3 mm apart, so no fixed vertex is within
//   3 mm for every identity: one of the test's 10 faces is at 3.04 mm; forward is the face's
//   own, (ex_l - ex_r) x (n - gn), as heads are pitched differently);
//   g = the most forward midline vertex between n and 1 cm above the brows' inner ends;
//   s = the deepest (least z) midline vertex between cs1 and g;
//   pg = the most forward midline vertex between gn and 5 mm below li; sl = the deepest
//   midline vertex between pg and li;
//   ps/pi = the highest / lowest vertex of the upper / lower lid contour;
//   os = the eyebrow contour vertex nearest ps in x; mf = the vertex a third of the way along
//   the shortest path from en to the brow's inner end;
//   al = the skin vertex of greatest |x| in the alar region (y between sbal - 2 mm and prn,
//   z at least z(sbal) - 2 mm, |x| below 2.5 |x(sbal)|).
// Contours are shortest edge paths (Dijkstra over skin edges weighted by length on the
// neutral) through landmarks in order, with back-tracking cut where consecutive legs overlap so
// that no vertex repeats: eyebrows 21..17 and 22..26 (medial to lateral), eye
// socket loops (en, upper lid, ex, lower lid), outer lips ch_r..ch_l over 49..53 and 59..55,
// inner lips ch_r, 60, 61..63 or 67..65, 64, ch_l. Nostril rings (closed loops, starting at the
// vertex nearest sbal) are the rims of ICT's deep nostril cavities: take the nose base plane
// through sbal_r, sbal_l and point 30, with normal c out of the nose (down and forward); the
// apex is the skin vertex deepest above that plane among those within 2 cm of sn and between
// the midline and that side's sbal; grow the cavity from it over skin edges through vertices
// more than 4 mm above the plane, then on through vertices whose normal n has n.c < 0.3 (the
// cavity walls, out to where the skin turns to face out of the nose base); the ring is the
// boundary of the cavity's triangles (27 vertices each on ICT's neutral; the same ring for
// thresholds 4-6 mm). MPEG-4 points follow docs/dataset-format.md; the 2 lower-teeth and the 4
// tongue points need --with-mouth. 9.10: top of the lower teeth nearest the midline; 9.11: top
// of the third lower tooth on the left. 6.1: the most forward (+z) tongue vertex within 2 mm of
// the midline; with the mid depth halfway between 6.1 and the tongue's back (least z), and
// looking only at tongue vertices within 3 mm of it: 6.2 the highest within 1 mm of the
// midline; 6.3 (left) and 6.4 (right) the vertices of greatest and least x among those whose
// normal points up (the borders of the upper surface).
//
// Poses (--poses): 36 poses with the names of the synthetic set (synth/pose_recipes.h). A
// pose's recipe here is a weighted sum of ICT blendshape deltas (ICT calls its blendshape files
// "expressions": browDown_L.obj, ...), blendshape_k - neutral, added to the identity. The
// recipes live in assets/ict-poses.json: {"pose name": {"blendshape": weight, ...}, ...}.

#include "dataset/manifest.h"

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace facesketch::dataset {

enum class IctRegion { NarrowFace, Face, HeadNeck };

/// "narrow", "face", "head"; parseIctRegion is its inverse (throws Error naming the text).
const char* ictRegionName(IctRegion region);
IctRegion parseIctRegion(const std::string& text);

struct IctOptions {
    int identities = 250; ///< thesis 3.1: 182 train + 48 contour + 20 test
    std::uint64_t seed = 1;
    IctRegion region = IctRegion::Face;
    bool eyes = false;             ///< eye sockets and eyeballs
    bool mouth = false;            ///< mouth socket, gums and tongue, teeth
    bool poses = false;            ///< write the 36 poses of each posed identity
    int poseIdentities = -1;       ///< how many identities get poses (-1: all)
    int vertices = 0;              ///< > 0: simplify to about this many vertices (simplify.h)
    std::filesystem::path recipes; ///< the pose recipe file (assets/ict-poses.json); needed with poses
};

/// The pose recipes: pose name -> {ICT blendshape name -> weight}, in file order.
using IctPoseRecipes = std::vector<std::pair<std::string, std::map<std::string, double>>>;

/// Vertices of the full ICT Face Model mesh (generic_neutral_mesh.obj).
inline constexpr int kIctVertexCount = 26719;

/// Reads a recipe file; throws Error naming the file and field for bad JSON, an empty or
/// duplicate pose name, or a weight that is not a finite number. (import_ict_files.cpp)
IctPoseRecipes readIctPoseRecipes(const std::filesystem::path& path);

/// Reads ICT-FaceKit's vertex_indices.json: its `idx_to_landmark_verts`, the 68 Multi-PIE
/// landmarks as vertex indices below kIctVertexCount. Throws Error naming the file and field.
/// Both JSON readers enforce core/limits.h (file size, nesting, string length).
std::vector<int> readIctLandmarkIndices(const std::filesystem::path& file);

/// The ICT model cut to a region, in mm, with the dataset labels of that region.
struct IctModel {
    Manifest labels;                                       ///< vertexCount, topology, components, landmarks, mpeg4, contours, excluded
    Vertices neutral;                                      ///< #V by 3, mm
    Eigen::MatrixXd identityModes;                         ///< 3#V by #modes, column i = flatten(identity_i - neutral), mm
    std::map<std::string, Eigen::RowVectorXd> blendshapes; ///< name -> flatten(blendshape - neutral), 1 by 3#V, mm
};

/// Reads the model at `path` (see above) and the blendshapes named in `blendshapes`.
/// Throws Error naming the file (and line, for malformed `v` lines) on bad input.
IctModel loadIctModel(const std::filesystem::path& path, const IctOptions& options, const std::vector<std::string>& blendshapes = {});

/// The #modes coefficients of identity `index`: independent N(0, 1) draws (see above).
Eigen::VectorXd ictCoefficients(std::uint64_t seed, int index, int modes);

/// neutral + identityModes * coefficients, #V by 3, mm.
Vertices ictIdentity(const IctModel& model, const Eigen::VectorXd& coefficients);

/// The pose of `identity` that `recipe` makes: identity + sum_k weight_k * blendshapes[k];
/// throws Error if a blendshape was not loaded.
Vertices ictPose(const IctModel& model, const Vertices& identity, const std::map<std::string, double>& recipe);

/// Writes the dataset folder atomically (dataset.h writeDataset): samples "face_0000"... in
/// "faces/", roles as manifest.h splitRoles (182 : 48 : 20, train first), poses in
/// "poses/<sample>/<pose>.ply". Deterministic: equal options give byte-identical folders.
/// Returns the manifest written.
Manifest writeIctDataset(const std::filesystem::path& path, const std::filesystem::path& output, const IctOptions& options);

} // namespace facesketch::dataset
