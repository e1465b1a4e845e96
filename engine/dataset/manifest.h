#pragma once
// The manifest of a standardised face dataset (thesis Ch. 3, 3.1): many meshes sharing one
// vertex topology, plus everything the later chapters need to know about that topology:
// named components, craniofacial landmarks (thesis Table 3.1), the 46 MPEG-4 feature points
// used for posing (thesis 5.2), the manually labelled contours (thesis 4.3.3), vertices never
// used as contour candidates, and the list of samples and poses. The file format is
// documented in docs/dataset-format.md.
//
// All vertex indices are 0-based into the shared vertex list of vertexCount vertices.
// Readers validate every field; a bad field throws facesketch::Error whose message starts
// with the file and names the field, e.g.
//   "data/manifest.json: landmarks.prn: vertex 9000 outside [0, 6000)".

#include "core/mesh.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace facesketch::dataset {

/// What a sample is for (thesis 3.1: 182 faces fit the model, 48 help map contours).
enum class Role { Train, Contour, Test };

/// "train", "contour", "test".
const char* roleName(Role role);
/// Inverse of roleName; throws Error naming `text` otherwise.
Role parseRole(const std::string& text);

/// Roles of `identities` samples in order: the thesis' 182 : 48 : 20 split scaled to the count
/// (exactly 182, 48, 20 for 250; contour and test rounded), train first, then contour, then
/// test. Used by `synth` and both importers. Throws Error if identities < 1.
std::vector<Role> splitRoles(int identities);

/// A named, half-open range [begin, end) of vertex indices, e.g. "skin" or "eye_left".
struct Component {
    std::string name;
    int begin = 0;
    int end = 0;

    int size() const { return end - begin; }
    bool contains(int vertex) const { return vertex >= begin && vertex < end; }
};

/// One identity in its neutral pose. `file` is relative to the dataset folder.
struct Sample {
    std::string name;
    std::filesystem::path file;
    Role role = Role::Train;
};

/// One pose of the sample called `identity`: a named expression or viseme of that identity,
/// stored as one mesh. (How a pose is made, e.g. from FaceActions or ICT blendshape weights, is
/// its recipe: synth/pose_recipes.h, import_ict.h.) Not a head rotation. Written to disk as an
/// entry of the manifest's "poses" array (docs/dataset-format.md); the key keeps that name.
struct Pose {
    std::string identity;
    std::string name;
    std::filesystem::path file;
};

struct Manifest {
    std::string units = "mm";                         ///< "mm", "cm" or "m"
    std::string up = "+y";                            ///< one of +x -x +y -y +z -z
    std::string forward = "+z";                       ///< the direction the face looks; not parallel to `up`
    int vertexCount = 0;                              ///< #V of every mesh in the dataset
    Triangles topology;                               ///< #F by 3, shared by every mesh, counter-clockwise from outside
    std::vector<Component> components;                ///< disjoint vertex ranges, "skin" required
    std::map<std::string, int> landmarks;             ///< craniofacial name ("prn", "ex_l") -> vertex
    std::map<std::string, int> mpeg4;                 ///< FDP name ("8.3") -> vertex
    std::map<std::string, std::vector<int>> contours; ///< name -> ordered vertex path (>= 2)
    std::vector<int> excluded;                        ///< never contour candidates (thesis 4.3.3)
    std::vector<Sample> samples;
    std::vector<Pose> poses;

    /// The component called `name`, or nullptr.
    const Component* component(const std::string& name) const;
    /// Samples with the given role, in manifest order.
    std::vector<const Sample*> samplesWithRole(Role role) const;
};

/// Checks every field (index ranges, duplicate names, component overlap, pose identities,
/// file names that stay inside the folder) and throws Error "<where>: <field>: <problem>".
/// Does not touch the file system.
void validateManifest(const Manifest& manifest, const std::string& where);

/// Millimetres per unit of the manifest units "mm", "cm" or "m" (datasets, scans and their
/// points all declare one of these). Throws Error "<what>: units '<units>' are not mm, cm or m".
double millimetresPer(const std::string& units, const std::string& what);

/// Reads and validates a manifest.json. Throws Error naming the file and field.
Manifest readManifest(const std::filesystem::path& path);
/// Validates, then writes pretty-printed JSON atomically (core/atomic_file.h). Keys are sorted,
/// so the same manifest always gives the same bytes.
void writeManifest(const std::filesystem::path& path, const Manifest& manifest);

/// Sets the MPEG-4 feature points that are anthropometric landmarks (ISO/IEC 14496-2 Annex C,
/// thesis 5.2): 2.1 gn, 2.10 pg, 3.1 / 3.2 ps_l / ps_r, 3.3 / 3.4 pi_l / pi_r, 3.7 / 3.12
/// ex_l / ex_r, 3.11 / 3.8 en_l / en_r. Every source labels the rest its own way. Throws Error
/// naming the first of these landmarks the manifest lacks.
void labelMpeg4FromLandmarks(Manifest& manifest);

} // namespace facesketch::dataset
