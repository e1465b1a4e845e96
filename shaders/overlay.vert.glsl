#version 450
// One triangle that covers the viewport (vertices at clip (-1,-1), (3,-1), (-1,3)); the fragment
// shader reads the overlay image at each pixel.

void main()
{
    vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
