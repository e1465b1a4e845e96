#pragma once
// glTF 2.0 export of an animated face (issue 13, thesis 5.5): the face, its rigid parts and an
// animation reproducing the frames FaceSketch sampled from its timeline, as one binary .glb,
// written with Debian's tinygltf (libtinygltf-dev).
//
// Why here (engine/io) and not engine/pose: this is a file format of meshes, like OBJ and PLY;
// it needs no statistics, cameras or poses, only vertices per frame, so anything that samples
// frames (the pose timeline, a future blendshape rig) can export them, and io stays below pose.
// Normals are the caller's (geometry/normals.h lives above io).
//
// What is written, and why it reproduces the sampled frames exactly:
// - One morph target per sampled frame k: the displacement frame_k - face.V (and, if normals
//   are given, frameNormals_k - faceNormals). The face's rest shape is `face`; the mesh's
//   default weights are all 0, so a viewer without animation shows the rest face.
// - One weights channel, LINEAR, keyed at the sample times, whose value at time t_k is the unit
//   vector e_k. glTF blends morph targets linearly, base + sum_j w_j d_j, so at t_k the mesh is
//   face.V + (frame_k - face.V) = frame_k exactly (up to float32 storage: about 1e-5 mm at
//   100 mm), and between two samples it is the straight blend of their two frames, which is
//   what linear interpolation of any per-vertex quantity between samples gives.
//   The alternative, one target per keyframe, cannot do this: frames between keyframes come
//   from a cardinal spline in feature-point space rebuilt by a nonlinear mapping (a mixture,
//   thesis 5.4.1), so they are not linear combinations of the keyframe meshes. One target per
//   frame costs #frames x #V x 12 bytes (x2 with normals): 7 MB for 100 frames of 6,000
//   vertices.
// - Each rigid part (an eyeball, the teeth) is its own node and mesh, at rest, moved by a
//   translation, rotation and uniform scale per frame (LINEAR, so again exact at the samples;
//   rotations are written with consistent signs so the slerp between samples takes the short
//   way). A part moved by the similarity s R x + t is exactly glTF's T * R * S.
// - Coordinates stay in millimetres (FaceSketch's unit) inside a root node named
//   "facesketch_mm" scaled by 0.001, so the scene is in glTF's metres and a vertex read in the
//   face node's frame is in mm.
//
// The export is checked by real clients (tests/io/gltf_export.cmake): the Khronos glTF validator
// reports 0 errors and 0 warnings, and three.js in headless Chromium, played to a sample time,
// puts a vertex within 0.01 mm of the frame FaceSketch sampled there.

#include "core/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

namespace facesketch {

/// A part that moves as one body: its shape at rest and, per sampled frame, the similarity
/// x -> scale * rotation * x + translation that places it in that frame.
struct GltfRigidPart {
    std::string name;
    Mesh rest;                                ///< #P by 3 vertices (mm) and #T by 3 triangles, at rest
    Vertices normals;                         ///< #P by 3 unit normals at rest, or empty (no NORMAL attribute)
    std::vector<Eigen::Quaterniond> rotation; ///< per frame; normalised on export, must not be 0
    std::vector<double> scale;                ///< per frame, > 0
    std::vector<Eigen::Vector3d> translation; ///< per frame, mm
};

/// What writeGlb exports: a face at rest, its frames at their times, and its rigid parts.
struct GltfAnimation {
    std::string name = "timeline";      ///< the animation's name
    Mesh face;                          ///< #V by 3 rest vertices (mm), #F by 3 triangles
    Vertices faceNormals;               ///< #V by 3 unit normals at rest, or empty (no normals)
    std::vector<double> times;          ///< seconds, >= 0, strictly increasing (also as float32)
    std::vector<Vertices> frames;       ///< per time, #V by 3 vertices (mm)
    std::vector<Vertices> frameNormals; ///< per time #V by 3 unit normals; empty iff faceNormals is
    std::vector<GltfRigidPart> parts;
};

/// Throws Error naming the field (e.g. "frames[3]: vertex 17 is nan", "times[2]: 0.5 is not
/// after times[1] 0.5") if the animation cannot be exported: no frames, sizes that disagree,
/// a non-finite value, times negative or not strictly increasing once stored as float32, a
/// bad face (validateMesh), a zero rotation or a non-positive scale.
void validateGltfAnimation(const GltfAnimation& animation);

/// Writes `animation` as a binary glTF 2.0 file (.glb) atomically (core/atomic_file.h), after
/// validateGltfAnimation; nothing is written if it throws.
void writeGlb(const std::filesystem::path& path, const GltfAnimation& animation);

} // namespace facesketch
