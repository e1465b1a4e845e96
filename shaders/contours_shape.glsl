// The packed shape of one (mesh, vertex) pair as the contour tests see it from the view, for
// contours_radial.comp.glsl and contours.comp.glsl. Needs the `positions`, `shapes` and
// `shapesC23` texel buffers, contours_view.glsl and octahedral.glsl included before it.
struct ViewedShape {
    bool plane;   // has a tangent plane (a normal and dir1 were stored)
    float ndotv;  // n . v
    float u, t;   // v's coordinates along dir1 and dir2: those of w, v projected on the tangent plane
    float s2;     // |w|^2 = sin^2(theta), at least 1e-30
    vec2 k;       // k1, k2
    vec4 c;       // C111, C112, C122, C222 (contours/curvature.h)
};

ViewedShape viewedShape(int index)
{
    vec3 p = texelFetch(positions, index).xyz;
    uvec4 shape = texelFetch(shapes, index);
    vec3 n = octDecode(unpackSnorm2x16(shape.x));
    vec3 view = toCamera(p);
    ViewedShape s;
    s.plane = (shape.x | shape.y) != 0u;
    s.ndotv = dot(n, view);
    // dir1 and dir2 are tangent, so w's coordinates are view's.
    vec3 d1 = octDecode(unpackSnorm2x16(shape.y));
    s.u = dot(view, d1);
    s.t = dot(view, cross(n, d1));
    s.s2 = max(s.u * s.u + s.t * s.t, 1e-30);
    s.k = unpackHalf2x16(shape.z);
    s.c = vec4(unpackHalf2x16(shape.w), unpackHalf2x16(texelFetch(shapesC23, index).x));
    return s;
}

// C(w, w, w) / |w|^3: the derivative of the normal curvature along w.
float cwww(ViewedShape s)
{
    float u = s.u, t = s.t;
    return (s.c.x * u * u * u + 3.0 * s.c.y * u * u * t + 3.0 * s.c.z * u * t * t + s.c.w * t * t * t) / (s.s2 * sqrt(s.s2));
}
