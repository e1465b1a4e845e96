#include "dataset/manifest.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/limits.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

namespace facesketch::dataset {

using nlohmann::json;

std::vector<Role> splitRoles(int identities)
{
    if (identities < 1)
        fail("roles: --identities ", identities, " must be at least 1");
    const int contour = static_cast<int>(std::lround(identities * 48.0 / 250.0));
    const int test = static_cast<int>(std::lround(identities * 20.0 / 250.0));
    const int train = identities - contour - test;
    std::vector<Role> roles(static_cast<size_t>(train), Role::Train);
    roles.insert(roles.end(), static_cast<size_t>(contour), Role::Contour);
    roles.insert(roles.end(), static_cast<size_t>(test), Role::Test);
    return roles;
}

const char* roleName(Role role)
{
    switch (role) {
    case Role::Train:
        return "train";
    case Role::Contour:
        return "contour";
    case Role::Test:
        return "test";
    }
    return "?";
}

Role parseRole(const std::string& text)
{
    if (text == "train")
        return Role::Train;
    if (text == "contour")
        return Role::Contour;
    if (text == "test")
        return Role::Test;
    fail("role '", text, "' is not one of train, contour, test");
}

const Component* Manifest::component(const std::string& name) const
{
    for (const Component& c : components)
        if (c.name == name)
            return &c;
    return nullptr;
}

std::vector<const Sample*> Manifest::samplesWithRole(Role role) const
{
    std::vector<const Sample*> out;
    for (const Sample& s : samples)
        if (s.role == role)
            out.push_back(&s);
    return out;
}

namespace {

bool isAxis(const std::string& s)
{
    return s.size() == 2 && (s[0] == '+' || s[0] == '-') && (s[1] == 'x' || s[1] == 'y' || s[1] == 'z');
}

void checkVertex(const std::string& where, const std::string& field, long long v, int count)
{
    if (v < 0 || v >= count)
        fail(where, ": ", field, ": vertex ", v, " outside [0, ", count, ")");
}

// A file name must stay inside the dataset folder so a manifest cannot point elsewhere.
void checkFile(const std::string& where, const std::string& field, const std::filesystem::path& file)
{
    if (file.empty())
        fail(where, ": ", field, ": empty file name");
    if (file.is_absolute())
        fail(where, ": ", field, ": '", file.string(), "' must be relative to the dataset folder");
    for (const auto& part : file)
        if (part == "..")
            fail(where, ": ", field, ": '", file.string(), "' leaves the dataset folder");
}

void checkName(const std::string& where, const std::string& field, const std::string& name)
{
    if (name.empty())
        fail(where, ": ", field, ": empty name");
}

} // namespace

double millimetresPer(const std::string& units, const std::string& what)
{
    if (units == "mm")
        return 1.0;
    if (units == "cm")
        return 10.0;
    if (units == "m")
        return 1000.0;
    fail(what, ": units '", units, "' are not mm, cm or m");
}

void validateManifest(const Manifest& m, const std::string& where)
{
    if (m.units != "mm" && m.units != "cm" && m.units != "m")
        fail(where, ": units: '", m.units, "' is not one of mm, cm, m");
    if (!isAxis(m.up))
        fail(where, ": up: '", m.up, "' is not one of +x -x +y -y +z -z");
    if (!isAxis(m.forward))
        fail(where, ": forward: '", m.forward, "' is not one of +x -x +y -y +z -z");
    if (m.up[1] == m.forward[1])
        fail(where, ": forward: '", m.forward, "' is parallel to up '", m.up, "'");
    if (m.vertexCount <= 0)
        fail(where, ": vertex_count: ", m.vertexCount, " must be positive");
    if (m.vertexCount > limits::kMaxMeshVertices)
        fail(where, ": vertex_count: ", m.vertexCount, " is more than the ", limits::kMaxMeshVertices,
            " vertices a mesh may have (docs/limits.md)");
    const int n = m.vertexCount;

    if (m.topology.rows() == 0)
        fail(where, ": topology: no triangles");
    for (Eigen::Index f = 0; f < m.topology.rows(); ++f) {
        for (int k = 0; k < 3; ++k)
            checkVertex(where, cat("topology[", f, "]"), m.topology(f, k), n);
        const auto t = m.topology.row(f);
        if (t(0) == t(1) || t(1) == t(2) || t(0) == t(2))
            fail(where, ": topology[", f, "]: repeats a vertex (", t(0), ", ", t(1), ", ", t(2), ")");
    }

    std::set<std::string> names;
    for (size_t i = 0; i < m.components.size(); ++i) {
        const Component& c = m.components[i];
        const std::string field = cat("components.", c.name);
        checkName(where, cat("components[", i, "]"), c.name);
        if (!names.insert(c.name).second)
            fail(where, ": ", field, ": duplicate component");
        if (c.begin < 0 || c.end > n || c.begin >= c.end)
            fail(where, ": ", field, ": range [", c.begin, ", ", c.end, ") is empty or outside [0, ", n, ")");
        for (size_t j = 0; j < i; ++j) {
            const Component& o = m.components[j];
            if (c.begin < o.end && o.begin < c.end)
                fail(where, ": ", field, ": range [", c.begin, ", ", c.end, ") overlaps components.", o.name, " [", o.begin, ", ", o.end,
                    ")");
        }
    }
    if (!m.component("skin"))
        fail(where, ": components.skin: missing (every dataset needs a skin component)");

    for (const auto& [name, v] : m.landmarks) {
        checkName(where, "landmarks", name);
        checkVertex(where, "landmarks." + name, v, n);
    }
    for (const auto& [name, v] : m.mpeg4) {
        // FDP names are "group.point" (MPEG-4 Annex C), e.g. "8.3".
        const auto dot = name.find('.');
        const bool ok = dot != std::string::npos && dot > 0 && dot + 1 < name.size()
            && name.find_first_not_of("0123456789.") == std::string::npos && name.find('.', dot + 1) == std::string::npos;
        if (!ok)
            fail(where, ": mpeg4.", name, ": not an FDP name of the form group.point (e.g. 8.3)");
        checkVertex(where, "mpeg4." + name, v, n);
    }
    for (const auto& [name, path] : m.contours) {
        checkName(where, "contours", name);
        if (path.size() < 2)
            fail(where, ": contours.", name, ": has ", path.size(), " vertices, needs at least 2");
        for (size_t i = 0; i < path.size(); ++i)
            checkVertex(where, cat("contours.", name, "[", i, "]"), path[i], n);
    }
    std::set<int> seen;
    for (size_t i = 0; i < m.excluded.size(); ++i) {
        checkVertex(where, cat("excluded[", i, "]"), m.excluded[i], n);
        if (!seen.insert(m.excluded[i]).second)
            fail(where, ": excluded[", i, "]: vertex ", m.excluded[i], " listed twice");
    }

    std::set<std::string> sampleNames;
    std::set<std::filesystem::path> files;
    for (size_t i = 0; i < m.samples.size(); ++i) {
        const Sample& s = m.samples[i];
        const std::string field = cat("samples[", i, "]");
        checkName(where, field + ".name", s.name);
        if (!sampleNames.insert(s.name).second)
            fail(where, ": ", field, ".name: duplicate sample '", s.name, "'");
        checkFile(where, field + ".file", s.file);
        if (!files.insert(s.file.lexically_normal()).second)
            fail(where, ": ", field, ".file: '", s.file.string(), "' is used twice");
    }
    std::set<std::pair<std::string, std::string>> poseNames;
    for (size_t i = 0; i < m.poses.size(); ++i) {
        const Pose& p = m.poses[i];
        const std::string field = cat("poses[", i, "]");
        if (!sampleNames.count(p.identity))
            fail(where, ": ", field, ".identity: '", p.identity, "' is not a sample name");
        checkName(where, field + ".name", p.name);
        if (!poseNames.insert({ p.identity, p.name }).second)
            fail(where, ": ", field, ".name: duplicate pose '", p.name, "' of '", p.identity, "'");
        checkFile(where, field + ".file", p.file);
        if (!files.insert(p.file.lexically_normal()).second)
            fail(where, ": ", field, ".file: '", p.file.string(), "' is used twice");
    }
}

namespace {

// Typed access that names the field on failure.
struct Reader {
    std::string where;

    const json& member(const json& object, const std::string& key, const std::string& field) const
    {
        if (!object.is_object())
            fail(where, ": ", field.empty() ? "(top level)" : field, ": expected an object");
        auto it = object.find(key);
        if (it == object.end())
            fail(where, ": ", field.empty() ? key : field + "." + key, ": missing");
        return *it;
    }
    std::string string(const json& value, const std::string& field) const
    {
        if (!value.is_string())
            fail(where, ": ", field, ": expected a string, found ", value.dump());
        return value.get<std::string>();
    }
    long long integer(const json& value, const std::string& field) const
    {
        if (!value.is_number_integer())
            fail(where, ": ", field, ": expected an integer, found ", value.dump());
        if (value.is_number_unsigned() && value.get<unsigned long long>() >= (1ull << 31))
            fail(where, ": ", field, ": ", value.get<unsigned long long>(), " is out of range");
        const long long v = value.get<long long>();
        if (v < -(1ll << 31) || v >= (1ll << 31))
            fail(where, ": ", field, ": ", v, " is out of range");
        return v;
    }
    const json& array(const json& value, const std::string& field) const
    {
        if (!value.is_array())
            fail(where, ": ", field, ": expected an array");
        return value;
    }
    const json& object(const json& value, const std::string& field) const
    {
        if (!value.is_object())
            fail(where, ": ", field, ": expected an object");
        return value;
    }
};

} // namespace

Manifest readManifest(const std::filesystem::path& path)
{
    const std::string where = path.string();
    const std::string text = limits::readFileLimited(path, limits::kMaxJsonFileBytes, "a manifest");
    limits::checkJsonLimits(text, where);
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        // parse_error, or out_of_range for a number too large for a double (1e999).
        fail(where, ": not valid JSON: ", e.what());
    }
    const Reader r { where };
    r.object(doc, "(top level)");

    Manifest m;
    m.units = r.string(r.member(doc, "units", ""), "units");
    m.up = r.string(r.member(doc, "up", ""), "up");
    m.forward = r.string(r.member(doc, "forward", ""), "forward");
    m.vertexCount = static_cast<int>(r.integer(r.member(doc, "vertex_count", ""), "vertex_count"));
    if (m.vertexCount <= 0)
        fail(where, ": vertex_count: ", m.vertexCount, " must be positive");

    const json& topo = r.array(r.member(doc, "topology", ""), "topology");
    m.topology.resize(static_cast<Eigen::Index>(topo.size()), 3);
    for (size_t f = 0; f < topo.size(); ++f) {
        const std::string field = cat("topology[", f, "]");
        if (!topo[f].is_array() || topo[f].size() != 3)
            fail(where, ": ", field, ": expected 3 vertex indices, found ", topo[f].dump());
        for (int k = 0; k < 3; ++k) {
            const long long v = r.integer(topo[f][k], field);
            checkVertex(where, field, v, m.vertexCount);
            m.topology(static_cast<Eigen::Index>(f), k) = static_cast<std::int32_t>(v);
        }
    }

    for (const auto& [name, range] : r.object(r.member(doc, "components", ""), "components").items()) {
        const std::string field = "components." + name;
        if (!range.is_array() || range.size() != 2)
            fail(where, ": ", field, ": expected [begin, end], found ", range.dump());
        m.components.push_back({ name, static_cast<int>(r.integer(range[0], field)), static_cast<int>(r.integer(range[1], field)) });
    }
    // Components are listed in index order so the vertex layout reads top to bottom.
    std::sort(m.components.begin(), m.components.end(), [](const Component& a, const Component& b) { return a.begin < b.begin; });

    for (const char* key : { "landmarks", "mpeg4" }) {
        auto& target = std::string(key) == "landmarks" ? m.landmarks : m.mpeg4;
        for (const auto& [name, v] : r.object(r.member(doc, key, ""), key).items())
            target[name] = static_cast<int>(r.integer(v, cat(key, ".", name)));
    }
    for (const auto& [name, list] : r.object(r.member(doc, "contours", ""), "contours").items()) {
        const std::string field = "contours." + name;
        std::vector<int>& path = m.contours[name];
        for (size_t i = 0; i < r.array(list, field).size(); ++i)
            path.push_back(static_cast<int>(r.integer(list[i], cat(field, "[", i, "]"))));
    }
    const json& excluded = r.array(r.member(doc, "excluded", ""), "excluded");
    for (size_t i = 0; i < excluded.size(); ++i)
        m.excluded.push_back(static_cast<int>(r.integer(excluded[i], cat("excluded[", i, "]"))));

    const json& samples = r.array(r.member(doc, "samples", ""), "samples");
    for (size_t i = 0; i < samples.size(); ++i) {
        const std::string field = cat("samples[", i, "]");
        Sample s;
        s.name = r.string(r.member(samples[i], "name", field), field + ".name");
        s.file = r.string(r.member(samples[i], "file", field), field + ".file");
        const std::string role = r.string(r.member(samples[i], "role", field), field + ".role");
        try {
            s.role = parseRole(role);
        } catch (const Error& e) {
            fail(where, ": ", field, ".role: ", e.what());
        }
        m.samples.push_back(std::move(s));
    }
    if (doc.contains("poses")) {
        const json& poses = r.array(doc["poses"], "poses");
        for (size_t i = 0; i < poses.size(); ++i) {
            const std::string field = cat("poses[", i, "]");
            Pose p;
            p.identity = r.string(r.member(poses[i], "identity", field), field + ".identity");
            p.name = r.string(r.member(poses[i], "name", field), field + ".name");
            p.file = r.string(r.member(poses[i], "file", field), field + ".file");
            m.poses.push_back(std::move(p));
        }
    }
    validateManifest(m, where);
    return m;
}

void writeManifest(const std::filesystem::path& path, const Manifest& m)
{
    validateManifest(m, path.string());
    // Hand-laid JSON: one triangle, sample or pose per line keeps large manifests readable and
    // diffable, which json::dump(2) (one number per line) would not.
    writeFileAtomically(path, [&](std::ostream& out) {
        out << "{\n";
        out << "  \"format\": \"facesketch-dataset\",\n  \"version\": 1,\n";
        out << "  \"units\": " << json(m.units).dump() << ",\n";
        out << "  \"up\": " << json(m.up).dump() << ",\n";
        out << "  \"forward\": " << json(m.forward).dump() << ",\n";
        out << "  \"vertex_count\": " << m.vertexCount << ",\n";
        json components = json::object();
        for (const Component& c : m.components)
            components[c.name] = { c.begin, c.end };
        out << "  \"components\": " << components.dump() << ",\n";
        out << "  \"landmarks\": " << json(m.landmarks).dump() << ",\n";
        out << "  \"mpeg4\": " << json(m.mpeg4).dump() << ",\n";
        out << "  \"contours\": {";
        bool first = true;
        for (const auto& [name, list] : m.contours) {
            out << (first ? "\n    " : ",\n    ") << json(name).dump() << ": " << json(list).dump();
            first = false;
        }
        out << "\n  },\n";
        out << "  \"excluded\": " << json(m.excluded).dump() << ",\n";
        out << "  \"samples\": [";
        for (size_t i = 0; i < m.samples.size(); ++i) {
            const Sample& s = m.samples[i];
            json item = { { "name", s.name }, { "file", s.file.generic_string() }, { "role", roleName(s.role) } };
            out << (i ? ",\n    " : "\n    ") << item.dump();
        }
        out << "\n  ],\n  \"poses\": [";
        for (size_t i = 0; i < m.poses.size(); ++i) {
            const Pose& p = m.poses[i];
            json item = { { "identity", p.identity }, { "name", p.name }, { "file", p.file.generic_string() } };
            out << (i ? ",\n    " : "\n    ") << item.dump();
        }
        out << "\n  ],\n  \"topology\": [";
        for (Eigen::Index f = 0; f < m.topology.rows(); ++f)
            out << (f ? ",\n    [" : "\n    [") << m.topology(f, 0) << "," << m.topology(f, 1) << "," << m.topology(f, 2) << "]";
        out << "\n  ]\n}\n";
    });
}

void labelMpeg4FromLandmarks(Manifest& manifest)
{
    static const std::pair<const char*, const char*> fromLandmark[]
        = { { "2.1", "gn" }, { "2.10", "pg" }, { "3.1", "ps_l" }, { "3.2", "ps_r" }, { "3.3", "pi_l" }, { "3.4", "pi_r" },
              { "3.7", "ex_l" }, { "3.12", "ex_r" }, { "3.11", "en_l" }, { "3.8", "en_r" } };
    for (const auto& [point, landmark] : fromLandmark) {
        const auto it = manifest.landmarks.find(landmark);
        if (it == manifest.landmarks.end())
            fail("MPEG-4 point ", point, ": the manifest has no landmark '", landmark, "'");
        manifest.mpeg4[point] = it->second;
    }
}

} // namespace facesketch::dataset
