// Octahedral unit vectors (Cigolle et al., "A Survey of Efficient Representations for
// Independent Unit Vectors", JCGT 2014): the sphere folded onto [-1, 1]^2, stored as two snorm16.
// The C++ decoder is engine/contours/curvature_gpu.cpp (octDecode).

vec2 octEncode(vec3 n)
{
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    if (n.z < 0.0) {
        vec2 s = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
        return (1.0 - abs(n.yx)) * s;
    }
    return n.xy;
}

vec3 octDecode(vec2 f)
{
    vec3 n = vec3(f, 1.0 - abs(f.x) - abs(f.y));
    float t = max(-n.z, 0.0);
    n.x += n.x >= 0.0 ? -t : t;
    n.y += n.y >= 0.0 ? -t : t;
    return normalize(n);
}
