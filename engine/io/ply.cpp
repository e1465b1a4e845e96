// Stanford PLY (Turk 1994; thesis appendix A.2), ASCII and binary, our own reader and writer:
// Debian packages no PLY library, and we need errors that name the line or the element.

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/limits.h"
#include "io/mesh_io.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace facesketch {

namespace {

enum class Format { Ascii, BinaryLittle, BinaryBig };

enum class Scalar { None, Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

Scalar parseScalar(const std::string& type)
{
    if (type == "char" || type == "int8")
        return Scalar::Int8;
    if (type == "uchar" || type == "uint8")
        return Scalar::UInt8;
    if (type == "short" || type == "int16")
        return Scalar::Int16;
    if (type == "ushort" || type == "uint16")
        return Scalar::UInt16;
    if (type == "int" || type == "int32")
        return Scalar::Int32;
    if (type == "uint" || type == "uint32")
        return Scalar::UInt32;
    if (type == "float" || type == "float32")
        return Scalar::Float32;
    if (type == "double" || type == "float64")
        return Scalar::Float64;
    return Scalar::None;
}

int scalarSize(Scalar s)
{
    switch (s) {
    case Scalar::Int8:
    case Scalar::UInt8:
        return 1;
    case Scalar::Int16:
    case Scalar::UInt16:
        return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32:
        return 4;
    case Scalar::Float64:
        return 8;
    default:
        return 0;
    }
}

struct Property {
    std::string name;
    Scalar type = Scalar::None;      // scalar type, or the item type of a list
    Scalar countType = Scalar::None; // not None for lists
    bool isList() const { return countType != Scalar::None; }
};

struct Element {
    std::string name;
    long count = 0;
    std::vector<Property> properties;
};

// Binary values from the body of the file, read into memory at once (a per-value stream read
// made loading a 230-face dataset take seconds).
class BinaryReader {
public:
    BinaryReader(std::istream& in, Format format, const std::string& file)
        : swap_(needSwap(format))
        , file_(file)
    {
        if (format == Format::Ascii)
            return;
        body_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }

    template <typename Context> double read(Scalar type, const Context& context)
    {
        const int n = scalarSize(type);
        if (position_ + n > body_.size())
            fail(file_, ": file ends inside ", context(), " (truncated?)");
        unsigned char bytes[8];
        std::memcpy(bytes, body_.data() + position_, n);
        position_ += n;
        if (swap_)
            std::reverse(bytes, bytes + n);
        auto as = [&](auto value) {
            std::memcpy(&value, bytes, sizeof(value));
            return static_cast<double>(value);
        };
        switch (type) {
        case Scalar::Int8:
            return as(std::int8_t {});
        case Scalar::UInt8:
            return as(std::uint8_t {});
        case Scalar::Int16:
            return as(std::int16_t {});
        case Scalar::UInt16:
            return as(std::uint16_t {});
        case Scalar::Int32:
            return as(std::int32_t {});
        case Scalar::UInt32:
            return as(std::uint32_t {});
        case Scalar::Float32:
            return as(float {});
        default:
            return as(double {});
        }
    }

private:
    static bool needSwap(Format f) { return (f == Format::BinaryBig) == (std::endian::native == std::endian::little); }
    bool swap_;
    const std::string& file_;
    std::vector<char> body_;
    size_t position_ = 0;
};

} // namespace

Mesh readPly(const std::filesystem::path& path)
{
    const std::string file = path.string();
    const std::uint64_t fileBytes = limits::checkFileSize(path, limits::kMaxMeshFileBytes, "a mesh file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(file, ": cannot open");

    long line = 0;
    std::string text;
    auto nextLine = [&]() -> bool {
        if (!std::getline(in, text))
            return false;
        ++line;
        if (!text.empty() && text.back() == '\r')
            text.pop_back();
        return true;
    };
    if (!nextLine() || text != "ply")
        fail(file, ":1: not a PLY file (first line must be 'ply')");

    Format format = Format::Ascii;
    bool haveFormat = false;
    std::vector<Element> elements;
    for (;;) {
        if (!nextLine())
            fail(file, ":", line, ": header ends without 'end_header'");
        std::istringstream words(text);
        std::string keyword;
        words >> keyword;
        auto where = [&] { return cat(file, ":", line, ": "); };
        if (keyword == "end_header")
            break;
        if (keyword == "comment" || keyword == "obj_info" || keyword.empty())
            continue;
        if (keyword == "format") {
            std::string name, version;
            words >> name >> version;
            if (name == "ascii")
                format = Format::Ascii;
            else if (name == "binary_little_endian")
                format = Format::BinaryLittle;
            else if (name == "binary_big_endian")
                format = Format::BinaryBig;
            else
                fail(where(), "unknown format '", name, "'");
            haveFormat = true;
        } else if (keyword == "element") {
            Element e;
            if (!(words >> e.name >> e.count) || e.count < 0)
                fail(where(), "bad element line '", text, "'");
            if (e.count > limits::kMaxPlyElementCount)
                fail(where(), "element '", e.name, "' declares ", e.count, " instances, more than the ", limits::kMaxPlyElementCount,
                    " a PLY element may have (docs/limits.md)");
            elements.push_back(e);
        } else if (keyword == "property") {
            if (elements.empty())
                fail(where(), "property before any element");
            Property p;
            std::string type;
            words >> type;
            if (type == "list") {
                std::string countType, itemType;
                words >> countType >> itemType >> p.name;
                p.countType = parseScalar(countType);
                p.type = parseScalar(itemType);
                if (p.countType == Scalar::None || p.type == Scalar::None || p.name.empty())
                    fail(where(), "bad list property '", text, "'");
            } else {
                p.type = parseScalar(type);
                words >> p.name;
                if (p.type == Scalar::None || p.name.empty())
                    fail(where(), "bad property '", text, "'");
            }
            elements.back().properties.push_back(p);
        } else {
            fail(where(), "unknown header keyword '", keyword, "'");
        }
    }
    if (!haveFormat)
        fail(file, ": header has no 'format' line");

    const Element* vertexElement = nullptr;
    const Element* faceElement = nullptr;
    int xyz[3] = { -1, -1, -1 };
    int indexProperty = -1;
    for (const Element& e : elements) {
        if (e.name == "vertex") {
            vertexElement = &e;
            for (size_t i = 0; i < e.properties.size(); ++i)
                for (int c = 0; c < 3; ++c)
                    if (e.properties[i].name == std::string(1, "xyz"[c]) && !e.properties[i].isList())
                        xyz[c] = static_cast<int>(i);
        } else if (e.name == "face") {
            faceElement = &e;
            for (size_t i = 0; i < e.properties.size(); ++i)
                if (!!e.properties[i].isList() && (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
                    indexProperty = static_cast<int>(i);
        }
    }
    if (!vertexElement)
        fail(file, ": no 'vertex' element");
    if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
        fail(file, ": 'vertex' element lacks scalar x, y and z properties");
    if (faceElement && indexProperty < 0)
        fail(file, ": 'face' element lacks a vertex_indices list");

    if (vertexElement->count > limits::kMaxMeshVertices)
        fail(file, ": declares ", vertexElement->count, " vertices, more than the ", limits::kMaxMeshVertices,
            " a mesh may have (docs/limits.md)");
    // The header's counts must fit in the bytes that follow it before anything is allocated for
    // them: every instance takes at least one line (ASCII) or its fixed-size properties and list
    // counts (binary). Counts are at most 2^28 and sizes at most 2^7 per instance, so nothing overflows.
    const std::streamoff headerBytes = in.tellg();
    const std::uint64_t bodyBytes
        = headerBytes < 0 ? 0 : fileBytes - std::min<std::uint64_t>(fileBytes, static_cast<std::uint64_t>(headerBytes));
    std::uint64_t neededBytes = 0;
    for (const Element& e : elements) {
        std::uint64_t instanceBytes = 0;
        for (const Property& p : e.properties)
            instanceBytes += static_cast<std::uint64_t>(scalarSize(p.isList() ? p.countType : p.type));
        if (format == Format::Ascii)
            instanceBytes = 1;
        neededBytes += static_cast<std::uint64_t>(e.count) * instanceBytes;
    }
    if (neededBytes > bodyBytes + (format == Format::Ascii ? 1 : 0))
        fail(file, ": the header declares elements that need at least ", neededBytes, " bytes, but only ", bodyBytes,
            " follow it (truncated, or a hostile header)");

    Mesh mesh;
    mesh.V.resize(vertexElement->count, 3);
    std::vector<std::array<std::int32_t, 3>> triangles;
    const long vertexCount = vertexElement->count;
    BinaryReader binary(in, format, file);

    // Buffers reused for every element instance: this loop runs once per vertex and face.
    std::vector<double> scalars;
    std::vector<long> indices;
    std::istringstream words;
    std::string token;
    for (const Element& e : elements) {
        const bool isVertex = &e == vertexElement, isFace = &e == faceElement;
        scalars.assign(e.properties.size(), 0.0);
        // A binary element without properties takes no bytes: nothing to read, however many.
        if (format != Format::Ascii && e.properties.empty())
            continue;
        for (long k = 0; k < e.count; ++k) {
            indices.clear();
            if (format == Format::Ascii) {
                if (!nextLine())
                    fail(file, ":", line + 1, ": file ends at ", e.name, " ", k, " of ", e.count, " (truncated?)");
                words.clear();
                words.str(text);
            }
            // "FILE:LINE: " for ASCII, "FILE: " for binary (whose messages name the element).
            auto where = [&] { return format == Format::Ascii ? cat(file, ":", line, ": ") : cat(file, ": "); };
            auto readValue = [&](Scalar type, const std::string& name, bool count) -> double {
                auto what = [&] { return count ? name + " count" : name; };
                if (format != Format::Ascii)
                    return binary.read(type, [&] { return cat(e.name, " ", k, " ", what()); });
                if (!(words >> token))
                    fail(where(), e.name, " ", k, " has too few values (missing ", what(), ")");
                char* end = nullptr;
                const double value = std::strtod(token.c_str(), &end);
                if (*end != '\0')
                    fail(where(), e.name, " ", k, ": ", what(), " '", token, "' is not a number");
                return value;
            };
            for (size_t i = 0; i < e.properties.size(); ++i) {
                const Property& p = e.properties[i];
                if (!p.isList()) {
                    scalars[i] = readValue(p.type, p.name, false);
                    continue;
                }
                const double n = readValue(p.countType, p.name, true);
                if (!(n >= 0) || n != std::floor(n) || n > static_cast<double>(limits::kMaxPolygonCorners))
                    fail(where(), e.name, " ", k, ": list length ", n, " is invalid (at most ", limits::kMaxPolygonCorners, ")");
                for (long j = 0; j < static_cast<long>(n); ++j) {
                    const double value = readValue(p.type, p.name, false);
                    if (isFace && static_cast<int>(i) == indexProperty) {
                        // Range-checked as a double: converting 1e30 to an integer is undefined.
                        if (!(value >= 0 && value < static_cast<double>(vertexCount)) || value != std::floor(value))
                            fail(where(), "face ", k, " has vertex index ", value, " outside [0, ", vertexCount, ")");
                        indices.push_back(static_cast<long>(value));
                    }
                }
            }
            if (isVertex) {
                for (int c = 0; c < 3; ++c) {
                    const double value = scalars[xyz[c]];
                    if (!std::isfinite(value))
                        fail(where(), "vertex ", k, " has non-finite ", "xyz"[c], " = ", value);
                    mesh.V(k, c) = value;
                }
            } else if (isFace) {
                if (indices.size() < 3)
                    fail(where(), "face ", k, " has ", indices.size(), " vertices, at least 3 needed");
                for (const long index : indices)
                    if (index < 0 || index >= vertexCount)
                        fail(where(), "face ", k, " has vertex index ", index, " outside [0, ", vertexCount, ")");
                if (static_cast<std::int64_t>(triangles.size() + indices.size() - 2) > limits::kMaxMeshTriangles)
                    fail(where(), "face ", k, ": more than the ", limits::kMaxMeshTriangles, " triangles a mesh may have (docs/limits.md)");
                for (size_t j = 1; j + 1 < indices.size(); ++j)
                    triangles.push_back({ static_cast<std::int32_t>(indices[0]), static_cast<std::int32_t>(indices[j]),
                        static_cast<std::int32_t>(indices[j + 1]) });
            }
            if (format == Format::Ascii && words >> token)
                fail(where(), e.name, " ", k, " has more values than its ", e.properties.size(), " properties");
        }
    }

    mesh.F.resize(static_cast<Eigen::Index>(triangles.size()), 3);
    for (size_t t = 0; t < triangles.size(); ++t)
        mesh.F.row(static_cast<Eigen::Index>(t)) << triangles[t][0], triangles[t][1], triangles[t][2];
    validateMesh(mesh, file);
    return mesh;
}

void writePly(const std::filesystem::path& path, const Mesh& mesh, PlyEncoding encoding)
{
    validateMesh(mesh, path.string());
    const bool ascii = encoding == PlyEncoding::Ascii;
    writeFileAtomically(path, [&](std::ostream& out) {
        out << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian") << " 1.0\n"
            << "comment FaceSketch mesh\n"
            << "element vertex " << mesh.V.rows() << "\nproperty float x\nproperty float y\nproperty float z\n"
            << "element face " << mesh.F.rows() << "\nproperty list uchar int vertex_indices\nend_header\n";
        if (ascii) {
            out.precision(9);
            for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
                out << static_cast<float>(mesh.V(v, 0)) << ' ' << static_cast<float>(mesh.V(v, 1)) << ' '
                    << static_cast<float>(mesh.V(v, 2)) << '\n';
            for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
                out << "3 " << mesh.F(t, 0) << ' ' << mesh.F(t, 1) << ' ' << mesh.F(t, 2) << '\n';
            return;
        }
        static_assert(std::endian::native == std::endian::little, "the binary PLY writer assumes a little-endian host");
        std::vector<float> xyz(static_cast<size_t>(mesh.V.rows()) * 3);
        for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
            for (int c = 0; c < 3; ++c)
                xyz[3 * v + c] = static_cast<float>(mesh.V(v, c));
        out.write(reinterpret_cast<const char*>(xyz.data()), static_cast<std::streamsize>(xyz.size() * sizeof(float)));
        std::vector<char> faces(static_cast<size_t>(mesh.F.rows()) * 13);
        for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
            faces[13 * t] = 3;
            std::memcpy(&faces[13 * t + 1], &mesh.F(t, 0), 12);
        }
        out.write(faces.data(), static_cast<std::streamsize>(faces.size()));
    });
}

} // namespace facesketch
