// Shared by curvature.comp and curvature_derivative.comp: the tensor algebra of Rusinkiewicz 2004
// (see engine/contours/curvature.h, the CPU reference these follow line for line).

vec4 loadBatch(uint v, uint mesh)
{
    return texelFetch(positions, int(v * meshCount + mesh));
}

// Smallest rotation of the frame (u, v) that takes its normal u x v to n.
void rotateFrame(inout vec3 u, inout vec3 v, vec3 n)
{
    vec3 oldNormal = cross(u, v);
    float ndot = dot(oldNormal, n);
    if (ndot <= -1.0) {
        u = -u;
        v = -v;
        return;
    }
    vec3 perpOld = n - ndot * oldNormal;
    vec3 dperp = (oldNormal + n) / (1.0 + ndot);
    u -= dperp * dot(perpOld, u);
    v -= dperp * dot(perpOld, v);
}

// Symmetric 2-tensor (e, f, g) in frame (u, v), read in frame (ru, rv).
vec3 projectTensor(vec3 u, vec3 v, vec3 efg, vec3 ru, vec3 rv)
{
    rotateFrame(u, v, cross(ru, rv));
    float u1 = dot(ru, u), v1 = dot(ru, v), u2 = dot(rv, u), v2 = dot(rv, v);
    return vec3(efg.x * u1 * u1 + 2.0 * efg.y * u1 * v1 + efg.z * v1 * v1,
                efg.x * u1 * u2 + efg.y * (u1 * v2 + u2 * v1) + efg.z * v1 * v2,
                efg.x * u2 * u2 + 2.0 * efg.y * u2 * v2 + efg.z * v2 * v2);
}

// Voronoi (mixed) areas of the corners of a triangle with edges e0, e1, e2 (e_i opposite corner i).
vec3 cornerAreas(vec3 e0, vec3 e1, vec3 e2)
{
    float area = 0.5 * length(cross(e0, e1));
    vec3 l2 = vec3(dot(e0, e0), dot(e1, e1), dot(e2, e2));
    vec3 ew = vec3(l2.x * (l2.y + l2.z - l2.x), l2.y * (l2.z + l2.x - l2.y), l2.z * (l2.x + l2.y - l2.z));
    vec3 corner;
    if (ew.x <= 0.0) {
        corner.y = -0.25 * l2.z * area / dot(e0, e2);
        corner.z = -0.25 * l2.y * area / dot(e0, e1);
        corner.x = area - corner.y - corner.z;
    } else if (ew.y <= 0.0) {
        corner.z = -0.25 * l2.x * area / dot(e1, e0);
        corner.x = -0.25 * l2.z * area / dot(e1, e2);
        corner.y = area - corner.z - corner.x;
    } else if (ew.z <= 0.0) {
        corner.x = -0.25 * l2.y * area / dot(e2, e1);
        corner.y = -0.25 * l2.x * area / dot(e2, e0);
        corner.z = area - corner.x - corner.y;
    } else {
        float scale = 0.5 * area / (ew.x + ew.y + ew.z);
        corner = scale * vec3(ew.y + ew.z, ew.z + ew.x, ew.x + ew.y);
    }
    return corner;
}

