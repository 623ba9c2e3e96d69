// ribbon_expand.glsl - GLSL 330 vertex shader: the GPU-expansion path of
// hairfur.h. The CPU writes each strand point once with hf_ribbon_points(),
// as (x, y, z, half width) in a GL_RGBA32F texture buffer: 16 bytes a point
// instead of the 2 vertices of hf_ribbons(). This shader rebuilds the same
// camera-facing ribbon as hf_ribbons() (same tangents, same side vector,
// same vertex numbering), so the index buffer of hf_ribbon_indices() draws
// it unchanged: draw with no vertex attributes bound, gl_VertexID is the
// ribbon vertex number (s * P + j) * 2 + side.
//
//   glBindBuffer(GL_TEXTURE_BUFFER, points_vbo);
//   glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, points_vbo);
//   glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, 0);
//
// Compact points (hf_ribbon_params.point_format = HF_POINT_COMPACT, 8
// bytes a point: half the upload): define HF_POINTS_COMPACT after the
// #version line, make the texture buffer GL_RGBA16I, and set
// u_point_origin and u_point_scale to the call's point_origin and
// point_scale (the box the positions are stored in).
#version 330 core

#ifdef HF_POINTS_COMPACT
uniform isamplerBuffer u_points;  // x, y, z SNORM16; half width F16 bits
uniform vec3 u_point_origin;
uniform float u_point_scale;

// An IEEE half from its bits (GLSL 3.30 has no unpackHalf2x16).
float hf_half(int h)
{
    int e = (h >> 10) & 31;
    float m = float(h & 1023);
    float v = e == 0 ? m * exp2(-24.0) : (m + 1024.0) * exp2(float(e - 25));
    return (h & 0x8000) != 0 ? -v : v;
}

vec4 hf_point(int i)
{
    ivec4 c = texelFetch(u_points, i);
    vec3 q = max(vec3(c.xyz) / 32767.0, vec3(-1.0)); // GL's SNORM rule
    return vec4(u_point_origin + u_point_scale * q, hf_half(c.w & 0xffff));
}
#else
uniform samplerBuffer u_points;   // (x, y, z, half width) per point

vec4 hf_point(int i) { return texelFetch(u_points, i); }
#endif
uniform samplerBuffer u_root_uv;  // (u, v) per strand, GL_RG32F
uniform int u_points_per_strand;  // P
uniform vec3 u_eye;               // perspective eye, world space
uniform int u_orthographic;       // 1: use u_view_dir instead of the eye
uniform vec3 u_view_dir;          // direction the camera looks
uniform mat4 u_view_proj;

out vec3 v_tangent;   // unit, root to tip
out vec3 v_texcoord;  // root u, root v, t along the strand
out vec3 v_position;  // world space

void main()
{
    int P = u_points_per_strand;
    int point = gl_VertexID >> 1;
    int s = point / P;
    int j = point - s * P;
    int base = s * P;
    vec4 p = hf_point(point);
    // central difference, one-sided at the ends (as hf_ribbons)
    vec3 a = hf_point(base + max(j - 1, 0)).xyz;
    vec3 b = hf_point(base + min(j + 1, P - 1)).xyz;
    vec3 d = b - a;
    vec3 t = dot(d, d) > 1e-30 ? normalize(d) : vec3(0.0, 1.0, 0.0);
    vec3 view = u_orthographic != 0 ? -u_view_dir : u_eye - p.xyz;
    vec3 side = cross(t, view);
    float l2 = dot(side, side);
    // parallel view or eye on the point: any perpendicular of t, so the
    // ribbon collapses to a line instead of producing NaN (hf_ribbons
    // borrows the neighbour's side here; a vertex shader cannot see it)
    if (!(l2 > 1e-12 * dot(view, view)) || !(l2 > 1e-30)) {
        vec3 axis = abs(t.x) <= abs(t.y) && abs(t.x) <= abs(t.z) ? vec3(1, 0, 0)
                  : (abs(t.y) <= abs(t.z) ? vec3(0, 1, 0) : vec3(0, 0, 1));
        side = cross(t, axis);
        l2 = dot(side, side);
    }
    side *= inversesqrt(l2);
    float sign_ = (gl_VertexID & 1) == 0 ? -1.0 : 1.0;
    vec3 world = p.xyz + sign_ * side * p.w;
    v_tangent = t;
    v_texcoord = vec3(texelFetch(u_root_uv, s).xy, float(j) / float(P - 1));
    v_position = world;
    gl_Position = u_view_proj * vec4(world, 1.0);
}
