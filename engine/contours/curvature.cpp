#include "contours/curvature.h"

#include "core/error.h"
#include "geometry/normals.h"

#include <Eigen/Dense>
#include <array>
#include <cmath>

namespace facesketch {

namespace {

using V3 = Eigen::Vector3d;

// Rotates the orthonormal frame (u, v) by the smallest rotation that takes its normal u x v
// to `n` (unit), so a tensor given in (u, v) can be read in the plane normal to n.
void rotateFrame(V3& u, V3& v, const V3& n)
{
    const V3 oldNormal = u.cross(v);
    const double ndot = oldNormal.dot(n);
    if (ndot <= -1.0) {
        u = -u;
        v = -v;
        return;
    }
    const V3 perpOld = n - ndot * oldNormal;
    const V3 dperp = (oldNormal + n) / (1.0 + ndot);
    u -= dperp * perpOld.dot(u);
    v -= dperp * perpOld.dot(v);
}

// A symmetric 2-tensor (e, f, g) = [[e f] [f g]] given in frame (u, v), read in frame (ru, rv).
std::array<double, 3> projectTensor(V3 u, V3 v, const std::array<double, 3>& efg, const V3& ru, const V3& rv)
{
    rotateFrame(u, v, ru.cross(rv));
    const double u1 = ru.dot(u), v1 = ru.dot(v), u2 = rv.dot(u), v2 = rv.dot(v);
    const auto [e, f, g] = efg;
    return { e * u1 * u1 + 2 * f * u1 * v1 + g * v1 * v1, e * u1 * u2 + f * (u1 * v2 + u2 * v1) + g * v1 * v2,
        e * u2 * u2 + 2 * f * u2 * v2 + g * v2 * v2 };
}

// A symmetric 3-tensor (C111, C112, C122, C222) given in frame (u, v), read in frame (ru, rv).
std::array<double, 4> projectDerivative(V3 u, V3 v, const std::array<double, 4>& c, const V3& ru, const V3& rv)
{
    rotateFrame(u, v, ru.cross(rv));
    const double x[2] = { ru.dot(u), ru.dot(v) }, y[2] = { rv.dot(u), rv.dot(v) };
    // C(p, q, r) for coordinate pairs p, q, r in the old frame.
    auto apply = [&](const double* p, const double* q, const double* r) {
        return c[0] * p[0] * q[0] * r[0] + c[1] * (p[0] * q[0] * r[1] + p[0] * q[1] * r[0] + p[1] * q[0] * r[0])
            + c[2] * (p[0] * q[1] * r[1] + p[1] * q[0] * r[1] + p[1] * q[1] * r[0]) + c[3] * p[1] * q[1] * r[1];
    };
    return { apply(x, x, x), apply(x, x, y), apply(x, y, y), apply(y, y, y) };
}

// Voronoi (mixed, for obtuse triangles) area of each corner of triangle (p0, p1, p2).
std::array<double, 3> cornerAreas(const std::array<V3, 3>& e)
{
    const double area = 0.5 * e[0].cross(e[1]).norm();
    const double l2[3] = { e[0].squaredNorm(), e[1].squaredNorm(), e[2].squaredNorm() };
    // Barycentric weights of the circumcentre.
    const double ew[3] = { l2[0] * (l2[1] + l2[2] - l2[0]), l2[1] * (l2[2] + l2[0] - l2[1]), l2[2] * (l2[0] + l2[1] - l2[2]) };
    std::array<double, 3> corner;
    for (int i = 0; i < 3; ++i) {
        if (ew[i] > 0)
            continue;
        // Obtuse at corner i: the circumcentre is outside; split as Meyer et al. do.
        const int a = (i + 1) % 3, b = (i + 2) % 3;
        corner[a] = -0.25 * l2[b] * area / e[i].dot(e[b]);
        corner[b] = -0.25 * l2[a] * area / e[i].dot(e[a]);
        corner[i] = area - corner[a] - corner[b];
        return corner;
    }
    const double scale = 0.5 * area / (ew[0] + ew[1] + ew[2]);
    for (int i = 0; i < 3; ++i)
        corner[i] = scale * (ew[(i + 1) % 3] + ew[(i + 2) % 3]);
    return corner;
}

struct Face {
    std::array<int, 3> v;
    std::array<V3, 3> e; // e[i] is the edge opposite corner i: e[0] = p2 - p1, ...
    V3 t, b;             // in-plane frame; t x b is the face normal
    std::array<double, 3> corner;
    bool degenerate;
};

Face makeFace(const Mesh& mesh, Eigen::Index f)
{
    Face face;
    for (int i = 0; i < 3; ++i)
        face.v[i] = mesh.F(f, i);
    const V3 p[3] = { mesh.V.row(face.v[0]).transpose(), mesh.V.row(face.v[1]).transpose(), mesh.V.row(face.v[2]).transpose() };
    face.e = { p[2] - p[1], p[0] - p[2], p[1] - p[0] };
    const V3 n = face.e[0].cross(face.e[1]);
    face.degenerate = !(n.norm() > 0) || !(face.e[0].norm() > 0);
    if (face.degenerate)
        return face;
    face.t = face.e[0].normalized();
    face.b = n.normalized().cross(face.t);
    face.corner = cornerAreas(face.e);
    return face;
}

// Vertex normals weighted as Max, "Weights for Computing Vertex Normals from Facet Normals",
// JGT 1999: each corner's cross product divided by the squared lengths of its two edges,
// exact for vertices on a sphere, which the curvature fit relies on.
Vertices maxWeightedNormals(const Mesh& mesh)
{
    Vertices N = Vertices::Zero(mesh.V.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
        for (int i = 0; i < 3; ++i) {
            const int v = mesh.F(f, i);
            const V3 a = (mesh.V.row(mesh.F(f, (i + 1) % 3)) - mesh.V.row(v)).transpose();
            const V3 b = (mesh.V.row(mesh.F(f, (i + 2) % 3)) - mesh.V.row(v)).transpose();
            const double l2 = a.squaredNorm() * b.squaredNorm();
            if (l2 > 0)
                N.row(v) += (a.cross(b) / l2).transpose();
        }
    for (Eigen::Index v = 0; v < N.rows(); ++v) {
        const double len = N.row(v).norm();
        if (len > 0)
            N.row(v) /= len;
    }
    return N;
}

} // namespace

Curvature estimateCurvature(const Mesh& mesh)
{
    validateMesh(mesh, "estimateCurvature");
    const Eigen::Index nv = mesh.V.rows(), nf = mesh.F.rows();
    Curvature c;
    c.normal = maxWeightedNormals(mesh);
    c.k1 = c.k2 = c.area = Eigen::VectorXd::Zero(nv);
    c.dir1 = c.dir2 = Vertices::Zero(nv, 3);
    c.dcurv.setZero(nv, 4);

    std::vector<Face> faces(nf);
    for (Eigen::Index f = 0; f < nf; ++f)
        faces[f] = makeFace(mesh, f);

    // Initial vertex frames: the first edge out of each vertex, in F's order, made tangent.
    std::vector<bool> haveFrame(nv, false);
    for (Eigen::Index f = 0; f < nf; ++f)
        for (int i = 0; i < 3; ++i) {
            const int v = mesh.F(f, i);
            if (haveFrame[v])
                continue;
            const V3 n = c.normal.row(v).transpose();
            const V3 edge = (mesh.V.row(mesh.F(f, (i + 1) % 3)) - mesh.V.row(v)).transpose();
            const V3 tangent = edge - edge.dot(n) * n;
            if (!(tangent.norm() > 0) || !(n.norm() > 0))
                continue;
            c.dir1.row(v) = tangent.normalized().transpose();
            c.dir2.row(v) = n.cross(tangent.normalized()).transpose();
            haveFrame[v] = true;
        }

    // Second fundamental form per face, accumulated into the vertex frames.
    std::vector<std::array<double, 3>> tensor(nv, { 0, 0, 0 });
    for (const Face& face : faces) {
        if (face.degenerate)
            continue;
        Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
        Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
        for (int j = 0; j < 3; ++j) {
            const double u = face.e[j].dot(face.t), v = face.e[j].dot(face.b);
            const V3 dn = (c.normal.row(face.v[(j + 2) % 3]) - c.normal.row(face.v[(j + 1) % 3])).transpose();
            const double dnu = dn.dot(face.t), dnv = dn.dot(face.b);
            A(0, 0) += u * u;
            A(0, 1) += u * v;
            A(1, 1) += u * u + v * v;
            A(1, 2) += u * v;
            A(2, 2) += v * v;
            rhs += Eigen::Vector3d(dnu * u, dnu * v + dnv * u, dnv * v);
        }
        A(1, 0) = A(0, 1);
        A(2, 1) = A(1, 2);
        const Eigen::Vector3d efg = A.ldlt().solve(rhs);
        for (int i = 0; i < 3; ++i) {
            const int v = face.v[i];
            if (!haveFrame[v])
                continue;
            const auto t = projectTensor(face.t, face.b, { efg[0], efg[1], efg[2] }, c.dir1.row(v).transpose(), c.dir2.row(v).transpose());
            for (int k = 0; k < 3; ++k)
                tensor[v][k] += face.corner[i] * t[k];
            c.area[v] += face.corner[i];
        }
    }

    for (Eigen::Index v = 0; v < nv; ++v) {
        if (!haveFrame[v] || !(c.area[v] > 0))
            continue;
        Eigen::Matrix2d T;
        T << tensor[v][0], tensor[v][1], tensor[v][1], tensor[v][2];
        T /= c.area[v];
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(T);
        const V3 u = c.dir1.row(v).transpose(), w = c.dir2.row(v).transpose(), n = c.normal.row(v).transpose();
        const Eigen::Vector2d e1 = eig.eigenvectors().col(1);
        const V3 d1 = (e1[0] * u + e1[1] * w).normalized();
        c.k1[v] = eig.eigenvalues()[1];
        c.k2[v] = eig.eigenvalues()[0];
        c.dir1.row(v) = d1.transpose();
        c.dir2.row(v) = n.cross(d1).transpose();
    }

    // Derivative of curvature: per face, fit C to the differences of the vertex tensors.
    for (const Face& face : faces) {
        if (face.degenerate)
            continue;
        std::array<std::array<double, 3>, 3> fcurv;
        for (int i = 0; i < 3; ++i) {
            const int v = face.v[i];
            fcurv[i] = projectTensor(c.dir1.row(v).transpose(), c.dir2.row(v).transpose(), { c.k1[v], 0.0, c.k2[v] }, face.t, face.b);
        }
        Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
        Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
        for (int j = 0; j < 3; ++j) {
            const double u = face.e[j].dot(face.t), v = face.e[j].dot(face.b);
            const auto& head = fcurv[(j + 2) % 3];
            const auto& tail = fcurv[(j + 1) % 3];
            const double d[3] = { head[0] - tail[0], head[1] - tail[1], head[2] - tail[2] };
            // Rows (u v 0 0), (0 u v 0), (0 0 u v) against d[0], d[1], d[2].
            for (int r = 0; r < 3; ++r) {
                Eigen::Vector4d row = Eigen::Vector4d::Zero();
                row[r] = u;
                row[r + 1] = v;
                A += row * row.transpose();
                rhs += row * d[r];
            }
        }
        const Eigen::Vector4d C = A.ldlt().solve(rhs);
        for (int i = 0; i < 3; ++i) {
            const int v = face.v[i];
            if (!(c.area[v] > 0))
                continue;
            const auto d
                = projectDerivative(face.t, face.b, { C[0], C[1], C[2], C[3] }, c.dir1.row(v).transpose(), c.dir2.row(v).transpose());
            const double weight = face.corner[i] / c.area[v];
            for (int k = 0; k < 4; ++k)
                c.dcurv(v, k) += weight * d[k];
        }
    }
    return c;
}

RadialCurvature radialCurvature(const Curvature& c, Eigen::Index vertex, const Eigen::Vector3d& toCamera)
{
    RadialCurvature r;
    const V3 n = c.normal.row(vertex).transpose();
    r.ndotv = n.dot(toCamera);
    const V3 w = toCamera - r.ndotv * n;
    const double u = w.dot(c.dir1.row(vertex).transpose()), v = w.dot(c.dir2.row(vertex).transpose());
    const double s2 = u * u + v * v;
    if (!(s2 > 1e-24))
        return r;
    const double s = std::sqrt(s2);
    r.kr = (c.k1[vertex] * u * u + c.k2[vertex] * v * v) / s2;
    const auto& d = c.dcurv.row(vertex);
    const double cwww = (d[0] * u * u * u + 3 * d[1] * u * u * v + 3 * d[2] * u * v * v + d[3] * v * v * v) / (s2 * s);
    r.dwkr = cwww + 2 * c.k1[vertex] * c.k2[vertex] * r.ndotv / s;
    const double torsion = (c.k2[vertex] - c.k1[vertex]) * u * v / s2;
    r.rtscNumerator = s * cwww - 2 * r.ndotv * torsion * torsion;
    return r;
}

} // namespace facesketch
