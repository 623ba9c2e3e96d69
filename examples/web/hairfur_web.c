/* hairfur_web.c - hairfur.h in a web page: fur on the built-in head
   (examples/head_mesh.h), grown, simulated and expanded into ribbons on
   the CPU in WebAssembly every frame, drawn with WebGL2.

   The scene is gl_marschner's built-in head (examples/gl_marschner.c,
   with no options): the same maps, fur description, rope parameters,
   motion, colliders, camera, light, shadow map and shaders (in GLSL ES
   3.00; the hair's shading and shadows are the same file,
   examples/hair_shading.glsl, which make web builds in), so that make
   web-check can compare the page's picture with gl_marschner's headless
   render. What differs is what WebGL2 lacks or
   a page needs: the shadow map is read with NEAREST filtering (WebGL2
   filters no depth texture), the strands are copied into the GL buffer
   (no mapped buffers), and the controls (LOD, wind, stiffness, motion,
   orbit, SIMD level) come from the page.

   Build: make web (Debian's emscripten; writes build/web/index.html,
   index.js and index.wasm from this file and examples/web/shell.html).
   Serve build/web over http (make web-serve) and open it.

   The page passes its URL query as arguments:
     frames=N   run N steps of 1/60 s (time (f + 1) / 60 at step f, as
                gl_marschner --headless), draw the last one, check the
                picture, write the result into the page and stop (make
                web-check); 0 or none: run in real time
     seed=S     the fur's seed (7, as gl_marschner)
     strands=N  strands to grow (20,000, as gl_marschner)
     bench=N    measure N real-time frames after 5, write the means into
                the page and stop (make web-bench)
     simd=L     the SIMD level of the fur and ribbons (hf_simd_level: 0
                the best this build has, 1 scalar) */
#define HAIRFUR_IMPLEMENTATION
#include "hairfur.h"
#define HEAD_MESH_IMPLEMENTATION
#include "head_mesh.h"

#include <emscripten.h>
#include <emscripten/html5.h>
#include <GLES3/gl3.h>

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* gl_marschner's constants for the built-in head */
#define HW_PI 3.14159265358979f
#define HW_HEAD_R 0.1f       /* head_mesh.h sphere radius, metres */
#define HW_FRAME_DIAG 1.588f /* framing distance / grown mesh diagonal */
#define HW_FULL_DETAIL 1.09f /* LOD 1 up to this many framing distances */
#define HW_CULL 54.5f        /* no hair beyond this many */
#define HW_SHADOW_SIZE 1024  /* shadow map texels a side */
#define HW_WIDTH_SPACING 0.66f /* root width / mean strand spacing */
#define HW_NCOL 3            /* skull, neck, shoulders */
#define HW_STATS_MS 500.0    /* the on-page figures: means over this long */

typedef struct hw_dyn { float pos[3], tan[3]; } hw_dyn;
typedef struct hw_static { float uv_t[3], rgba[4], c3d[2]; } hw_static;

/* the stages timed, as gl_marschner reports them */
enum { ST_SKIN, ST_ROPES, ST_STRANDS, ST_UPLOAD, ST_DRAW, ST_FRAME, ST_N };

typedef struct hw_app {
    /* options (the URL query) and controls (the page) */
    int frames, seed, strands;
    long bench_frames; /* > 0: measure that many real-time frames */
    float lod_control;   /* < 0: from the distance, as gl_marschner */
    float wind, stiffness;
    int motion, orbit, simd;
    /* the head */
    hm_mesh head;
    hm_vertex *skin;
    hf_mesh skinned;
    unsigned char *density_px, *length_px, *color_px;
    hf_map density, length, color;
    float size, frame_dist, target[3], hair_len, root_width, shadow_k;
    float distance, azimuth, elevation;
    hf_rope_params rp;
    /* the fur */
    hf_fur *fur;
    hf_fur_info info;
    int P, drawn;
    float lod, pose[12];
    hf_collider col[HW_NCOL];
    hw_dyn *dyn;
    double t, last_now;
    long frame;
    float eye[3], view_proj[16], light_view_proj[16], shadow_depth;
    /* timings: sums since the last report, and the last means; a bench
       run's sums after its warm-up */
    double sum[ST_N], mean[ST_N], bench_sum[ST_N];
    long sum_frames;
    double sum_since, bench_since;
    /* GL */
    EMSCRIPTEN_WEBGL_CONTEXT_HANDLE ctx;
    int width, height;
    GLuint prog_hair, prog_head, depth_hair, depth_head;
    GLuint vao_hair, vao_head, vbo_dyn, vbo_static, ibo_hair, vbo_head,
        ibo_head;
    GLuint tex_m, tex_n, tex_dual0, tex_dual2, tex_density, tex_shadow,
        shadow_fbo;
    size_t dyn_bytes;
    /* the outcome */
    char status[2048];
    int errors;
} hw_app;

static hw_app g_app;

/* An error: counted, kept in the status and printed (the page shows the
   status and counts the console's errors). */
static void hw_error(hw_app *a, const char *what)
{
    size_t n = strlen(a->status);
    ++a->errors;
    fprintf(stderr, "hairfur web: %s\n", what);
    snprintf(a->status + n, sizeof a->status - n, "%serror: %s",
             n ? "; " : "", what);
}

/* ---- mat4, column-major (as glUniformMatrix4fv with GL_FALSE) ---------- */

static void hw_mat4_mul(float out[16], const float a[16], const float b[16])
{
    float r[16];
    int c, row, k;
    for (c = 0; c < 4; c++)
        for (row = 0; row < 4; row++) {
            float s = 0.0f;
            for (k = 0; k < 4; k++) s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    memcpy(out, r, sizeof r);
}

static void hw_mat4_perspective(float out[16], float fovy, float aspect,
                                float znear, float zfar)
{
    float f = 1.0f / (float)tan(0.5 * (double)fovy);
    memset(out, 0, 16 * sizeof *out);
    out[0] = f / aspect;
    out[5] = f;
    out[10] = (zfar + znear) / (znear - zfar);
    out[11] = -1.0f;
    out[14] = 2.0f * zfar * znear / (znear - zfar);
}

static void hw_mat4_ortho(float out[16], float l, float r, float b, float t,
                          float n, float f)
{
    memset(out, 0, 16 * sizeof *out);
    out[0] = 2.0f / (r - l);
    out[5] = 2.0f / (t - b);
    out[10] = -2.0f / (f - n);
    out[12] = -(r + l) / (r - l);
    out[13] = -(t + b) / (t - b);
    out[14] = -(f + n) / (f - n);
    out[15] = 1.0f;
}

static void hw_normalize3(float v[3])
{
    float l = (float)sqrt((double)(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    if (l > 0.0f) {
        v[0] /= l;
        v[1] /= l;
        v[2] /= l;
    }
}

static void hw_mat4_look_at(float out[16], const float eye[3],
                            const float center[3], const float up[3])
{
    float f[3], s[3], u[3];
    int k;
    for (k = 0; k < 3; ++k) f[k] = center[k] - eye[k];
    hw_normalize3(f);
    s[0] = f[1] * up[2] - f[2] * up[1];
    s[1] = f[2] * up[0] - f[0] * up[2];
    s[2] = f[0] * up[1] - f[1] * up[0];
    hw_normalize3(s);
    u[0] = s[1] * f[2] - s[2] * f[1];
    u[1] = s[2] * f[0] - s[0] * f[2];
    u[2] = s[0] * f[1] - s[1] * f[0];
    out[0] = s[0]; out[4] = s[1]; out[8] = s[2];
    out[1] = u[0]; out[5] = u[1]; out[9] = u[2];
    out[2] = -f[0]; out[6] = -f[1]; out[10] = -f[2];
    out[3] = 0.0f; out[7] = 0.0f; out[11] = 0.0f;
    out[12] = -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
    out[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    out[14] = f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2];
    out[15] = 1.0f;
}

/* ---- shaders: gl_marschner's, in GLSL ES 3.00 -------------------------- */

#define HW_GLSL_HEADER                                                       \
    "#version 300 es\n"                                                      \
    "precision highp float;\n"                                               \
    "precision highp int;\n"                                                 \
    "precision highp sampler2D;\n"

/* the CPU ribbons: everything comes from hf_fur_ribbons */
static const char *hw_vs_hair =
    HW_GLSL_HEADER
    "layout(location = 0) in vec3 a_pos;\n"
    "layout(location = 1) in vec3 a_tangent;\n"
    "layout(location = 2) in vec3 a_texcoord;\n"
    "layout(location = 3) in vec4 a_color;\n"
    "uniform mat4 u_view_proj;\n"
    "out vec3 v_position, v_tangent, v_texcoord;\n"
    "out vec4 v_color;\n"
    "out vec2 v_c3d;   // hair_shading.glsl's, unused: no 3D colour\n"
    "out float v_root; // ... and no root fade\n"
    "void main() {\n"
    "    v_position = a_pos; v_tangent = a_tangent; v_texcoord = a_texcoord;\n"
    "    v_color = a_color;\n"
    "    v_c3d = vec2(0.0);\n"
    "    v_root = 0.0;\n"
    "    gl_Position = u_view_proj * vec4(a_pos, 1.0);\n"
    "}\n";

/* The hair's fragment shader and the self-shadowing the head shares:
   gl_marschner's, examples/hair_shading.glsl, built in by make web as
   hw_hair_shading_glsl (build/web/hair_shading_glsl.h) and put after
   HW_GLSL_HEADER. Its settings are gl_marschner's defaults but for the
   shadows (u_deep 0: one depth map, the approximate deep shadow map) and
   the blending (no OIT). */
#include "hair_shading_glsl.h"

/* pre, the shared text and post, joined; malloc'd (NULL: out of memory) */
static char *hw_shading_source(const char *pre, const char *post)
{
    const char *text = hw_hair_shading_glsl;
    char *out = (char *)malloc(strlen(pre) + strlen(text) + strlen(post) + 1);
    if (out) {
        strcpy(out, pre);
        strcat(out, text);
        strcat(out, post);
    }
    return out;
}

static const char *hw_vs_head =
    HW_GLSL_HEADER
    "layout(location = 0) in vec3 a_pos;\n"
    "layout(location = 1) in vec3 a_normal;\n"
    "layout(location = 2) in vec2 a_uv;\n"
    "uniform mat4 u_view_proj;\n"
    "out vec3 v_position, v_normal;\n"
    "out vec2 v_uv;\n"
    "void main() {\n"
    "    v_position = a_pos; v_normal = a_normal; v_uv = a_uv;\n"
    "    gl_Position = u_view_proj * vec4(a_pos, 1.0);\n"
    "}\n";

/* skin, the scalp painted dark where the density map has hair; shadowed
   by the hair (hair_shading.glsl between these two) */
static const char *hw_fs_head_decls =
    HW_GLSL_HEADER
    "#define HAIR_SHADING_SHADOW_ONLY\n"
    "in vec3 v_position, v_normal;\n"
    "in vec2 v_uv;\n"
    "uniform sampler2D u_density;\n"
    "uniform vec3 u_light_dir, u_light_color, u_ambient, u_scalp;\n";
static const char *hw_fs_head_main =
    "out vec4 o_color;\n"
    "void main() {\n"
    "    vec3 n = normalize(v_normal);\n"
    "    vec3 skin = pow(vec3(0.85, 0.66, 0.55), vec3(2.2));\n"
    "    float d = smoothstep(0.1, 0.6, texture(u_density, v_uv).r);\n"
    "    vec3 albedo = mix(skin, u_scalp, d);\n"
    "    float lit = max(dot(n, u_light_dir), 0.0);\n"
    "    if (lit > 0.0) lit *= hair_shadow(v_position);\n"
    "    vec3 c = albedo * (u_ambient + u_light_color * lit);\n"
    "    o_color = vec4(pow(c, vec3(1.0 / 2.2)), 1.0);\n"
    "}\n";

/* the shadow pass writes depth only */
static const char *hw_fs_depth =
    HW_GLSL_HEADER
    "void main() {}\n";

static GLuint hw_shader(hw_app *a, GLenum type, const char *src,
                        const char *name)
{
    GLuint sh = glCreateShader(type);
    GLint ok = 0;
    glShaderSource(sh, 1, &src, NULL);
    glCompileShader(sh);
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024], msg[1200];
        log[0] = '\0';
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        snprintf(msg, sizeof msg, "%s %s shader: %s", name,
                 type == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
        hw_error(a, msg);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

static GLuint hw_program(hw_app *a, const char *vs, const char *fs,
                         const char *name)
{
    GLuint v = hw_shader(a, GL_VERTEX_SHADER, vs, name),
           f = hw_shader(a, GL_FRAGMENT_SHADER, fs, name), p;
    GLint ok = 0;
    if (!v || !f) return 0;
    p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024], msg[1200];
        log[0] = '\0';
        glGetProgramInfoLog(p, sizeof log, NULL, log);
        snprintf(msg, sizeof msg, "%s program: %s", name, log);
        hw_error(a, msg);
        return 0;
    }
    return p;
}

static GLuint hw_texture(GLenum internal, int w, int h, GLenum format,
                         GLenum type, const void *data, GLenum filter,
                         GLenum wrap)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, type,
                 data);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, (GLint)filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, (GLint)filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, (GLint)wrap);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, (GLint)wrap);
    return t;
}

static int hw_gl_ok(hw_app *a, const char *where)
{
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        char msg[160];
        snprintf(msg, sizeof msg, "GL error 0x%x in %s", (unsigned)e, where);
        hw_error(a, msg);
        return 0;
    }
    return 1;
}

/* ---- the scene: gl_marschner's built-in head ---------------------------- */

/* skull, neck and shoulders, moved by the pose (glm_head_colliders) */
static void hw_colliders(const float m[12], hf_collider *col)
{
    static const float a[3][3] = {{0, 0, 0}, {0, -0.06f, -0.01f},
                                  {-0.19f, -0.25f, -0.01f}},
                       b[3][3] = {{0, 0, 0}, {0, -0.21f, -0.01f},
                                  {0.19f, -0.25f, -0.01f}};
    static const float r[3] = {HW_HEAD_R, 0.05f, 0.065f};
    int i;
    for (i = 0; i < 3; ++i) {
        memset(&col[i], 0, sizeof col[i]);
        col[i].type = i == 0 ? HF_COLLIDER_SPHERE : HF_COLLIDER_CAPSULE;
        hm_xform(m, a[i], 1.0f, col[i].a);
        hm_xform(m, b[i], 1.0f, col[i].b);
        col[i].radius = r[i];
    }
}

/* the sizes gl_marschner measures from the head (glm_measure) */
static void hw_measure(hw_app *a)
{
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    double area = 0.0;
    int i, k;
    for (i = 0; i < a->head.vertex_count; ++i)
        for (k = 0; k < 3; ++k) {
            float x = a->head.vertices[i].pos[k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    a->size = sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) +
                    (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
    a->frame_dist = HW_FRAME_DIAG * a->size;
    for (k = 0; k < 3; ++k) a->target[k] = 0.5f * (lo[k] + hi[k]);
    a->target[1] -= 0.0866f * a->size; /* a little below the middle */
    a->hair_len = 0.14f;
    /* the hair's area: triangles weighted by the density at their corners */
    for (i = 0; i < a->head.triangle_count; ++i) {
        const uint32_t *t = a->head.indices + 3 * i;
        const float *p0 = a->head.vertices[t[0]].pos,
                    *p1 = a->head.vertices[t[1]].pos,
                    *p2 = a->head.vertices[t[2]].pos;
        float e1[3], e2[3], n[3], d = 0.0f, v[4];
        for (k = 0; k < 3; ++k) {
            e1[k] = p1[k] - p0[k];
            e2[k] = p2[k] - p0[k];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        for (k = 0; k < 3; ++k) {
            const float *uv = a->head.vertices[t[k]].uv;
            if (hf_map_sample(&a->density, uv[0], uv[1], v) == HF_OK)
                d += v[0] / 3.0f;
        }
        area += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * d;
    }
    a->root_width = HW_WIDTH_SPACING * sqrtf((float)(area / a->strands));
    if (!(a->root_width > 0.0f)) a->root_width = 0.001f * a->size;
    a->shadow_k = 5.0f / a->hair_len;
    a->distance = a->frame_dist;
}

static void hw_rope_params(hw_app *a)
{
    hf_rope_params_init(&a->rp);
    a->rp.local_stiffness_root = 0.3f;
    a->rp.local_stiffness_tip = 0.05f;
    a->rp.root_stiffness = 0.5f;
    a->rp.global_stiffness_root = a->stiffness;
    a->rp.global_stiffness_tip = 0.5f * a->stiffness;
    /* the page's wind: along +x, with gusts (turbulence) half as strong */
    a->rp.wind[0] = a->wind;
    a->rp.turbulence = 0.5f * a->wind;
    a->rp.simd = a->simd;
}

static void hw_camera(hw_app *a)
{
    float proj[16], view[16];
    const float up[3] = {0, 1, 0};
    float az = a->azimuth * HW_PI / 180.0f, el = a->elevation * HW_PI / 180.0f;
    a->eye[0] = a->target[0] + a->distance * sinf(az) * cosf(el);
    a->eye[1] = a->target[1] + a->distance * sinf(el);
    a->eye[2] = a->target[2] + a->distance * cosf(az) * cosf(el);
    hw_mat4_perspective(proj, 0.7f, (float)a->width / (float)a->height,
                        0.036f * a->frame_dist, 180.0f * a->frame_dist);
    hw_mat4_look_at(view, a->eye, a->target, up);
    hw_mat4_mul(a->view_proj, proj, view);
}

static void hw_ribbon_view(const hw_app *a, hf_ribbon_params *v)
{
    memset(v, 0, sizeof *v);
    memcpy(v->eye, a->eye, sizeof v->eye);
    v->root_width = a->root_width;
    v->tip_width = 0.227f * a->root_width;
    v->taper_power = 1.5f;
    v->alpha_root = 1.0f;
    v->alpha_tip = 0.2f;
    v->simd = a->simd;
}

/* hw_init's phases, in the order they run. Those that can fail return 1,
   or 0 with the error in the status. */

/* The head (a sphere), its skinned copy and its maps. */
static int hw_init_head(hw_app *a)
{
    if (!hm_sphere(24, 32, HW_HEAD_R, &a->head)) {
        hw_error(a, "out of memory (head)");
        return 0;
    }
    a->skin = (hm_vertex *)malloc(sizeof(hm_vertex) *
                                  (size_t)a->head.vertex_count);
    a->density_px = (unsigned char *)malloc(256 * 256);
    a->length_px = (unsigned char *)malloc(256 * 256);
    a->color_px = (unsigned char *)malloc(64 * 64 * 3);
    if (!a->skin || !a->density_px || !a->length_px || !a->color_px) {
        hw_error(a, "out of memory (maps)");
        return 0;
    }
    memcpy(a->skin, a->head.vertices,
           sizeof(hm_vertex) * (size_t)a->head.vertex_count);
    hm_hairline_density(a->density_px, 256, 256);
    hm_bangs_length(a->length_px, 256, 256);
    hm_hair_color(a->color_px, 64, 64);
    a->density.data = a->density_px;
    a->density.width = a->density.height = 256;
    a->density.channels = 1;
    a->length.data = a->length_px;
    a->length.width = a->length.height = 256;
    a->length.channels = 1;
    a->color.data = a->color_px;
    a->color.width = a->color.height = 64;
    a->color.channels = 3;
    hw_measure(a);
    return 1;
}

/* Two ribbon vertices per strand point, every strand. */
static size_t hw_ribbon_vertices(const hw_app *a)
{
    return 2u * (size_t)a->info.strand_count * (size_t)a->P;
}

/* The fur, grown on the head at rest as gl_marschner grows it; its info,
   the skinned mesh its roots follow and the per-frame vertex array. */
static int hw_init_fur(hw_app *a)
{
    hf_fur_desc desc;
    hf_diag diag;
    hf_result r;
    char msg[400];
    memset(&desc, 0, sizeof desc);
    desc.mesh.positions = a->head.vertices[0].pos;
    desc.mesh.position_stride = (int)sizeof(hm_vertex);
    desc.mesh.normals = a->head.vertices[0].normal;
    desc.mesh.normal_stride = (int)sizeof(hm_vertex);
    desc.mesh.uvs = a->head.vertices[0].uv;
    desc.mesh.uv_stride = (int)sizeof(hm_vertex);
    desc.mesh.vertex_count = a->head.vertex_count;
    desc.mesh.indices = a->head.indices;
    desc.mesh.triangle_count = a->head.triangle_count;
    desc.density_map = &a->density;
    desc.length_map = &a->length;
    desc.color_map = &a->color;
    desc.points_per_strand = 16;
    desc.max_length = a->hair_len;
    desc.total_strands = a->strands;
    desc.sampler = HF_SAMPLER_STRATIFIED;
    desc.seed = (uint32_t)a->seed;
    desc.clump = 0.25f;
    desc.tess_factor = 25000.0f; /* about 2,000 guides on the head */
    desc.grid_resolution = 32; /* hair-hair interaction, as gl_marschner */
    hw_rope_params(a);
    desc.rope_params = &a->rp;
    r = hf_fur_create(&desc, &a->fur, &diag);
    if (r != HF_OK) {
        snprintf(msg, sizeof msg, "hf_fur_create: %s", diag.message);
        hw_error(a, msg);
        return 0;
    }
    if (a->simd != 0) hf_fur_set_kernels(a->fur, a->simd, 0);
    hf_fur_get_info(a->fur, &a->info);
    a->P = a->info.points_per_strand;
    a->skinned = desc.mesh;
    a->skinned.positions = a->skin[0].pos;
    a->skinned.normals = a->skin[0].normal;
    a->dyn = (hw_dyn *)malloc(sizeof(hw_dyn) * hw_ribbon_vertices(a));
    if (!a->dyn) {
        hw_error(a, "out of memory (vertices)");
        return 0;
    }
    return 1;
}

/* The programs: hair and head, and their shadow variants. */
static int hw_init_programs(hw_app *a)
{
    char *fs_hair = hw_shading_source(HW_GLSL_HEADER, "");
    char *fs_head = hw_shading_source(hw_fs_head_decls, hw_fs_head_main);
    if (!fs_hair || !fs_head) {
        free(fs_hair);
        free(fs_head);
        hw_error(a, "out of memory for the shaders");
        return 0;
    }
    a->prog_hair = hw_program(a, hw_vs_hair, fs_hair, "hair");
    a->prog_head = hw_program(a, hw_vs_head, fs_head, "head");
    free(fs_hair);
    free(fs_head);
    a->depth_hair = hw_program(a, hw_vs_hair, hw_fs_depth, "hair shadow");
    a->depth_head = hw_program(a, hw_vs_head, hw_fs_depth, "head shadow");
    return a->prog_hair && a->prog_head && a->depth_hair && a->depth_head;
}

/* The LUTs, baked here in wasm as gl_marschner bakes them (the
   energy-conserving fibre without absorption, the dual scattering tables
   at 64): RGBA32F where the browser filters float textures, else RGBA16F
   (filtered everywhere in WebGL2). */
static int hw_init_luts(hw_app *a)
{
    hf_lut_params lp;
    hf_result r;
    float *lut;
    GLenum internal;
    char msg[400];
    hf_lut_params_init(&lp);
    lp.size = 256;
    lp.model = HF_LUT_ENERGY;
    lp.sigma_a = 0.0;
    lp.explicit_zero = HF_LUT_ZERO_SIGMA_A;
    lut = (float *)malloc(sizeof(float) * 4u * (size_t)lp.size *
                          (size_t)lp.size);
    if (!lut) {
        hw_error(a, "out of memory (LUTs)");
        return 0;
    }
    internal = emscripten_webgl_enable_extension(a->ctx,
                                                 "OES_texture_float_linear")
                   ? GL_RGBA32F
                   : GL_RGBA16F;
    if ((r = hf_lut_bake_m(&lp, 0, lp.size, lut)) != HF_OK) {
        snprintf(msg, sizeof msg, "LUT: %s", hf_result_string(r));
        hw_error(a, msg);
        free(lut);
        return 0;
    }
    a->tex_m = hw_texture(internal, lp.size, lp.size, GL_RGBA, GL_FLOAT, lut,
                          GL_LINEAR, GL_CLAMP_TO_EDGE);
    hf_lut_bake_n(&lp, 0, lp.size, lut);
    a->tex_n = hw_texture(internal, lp.size, lp.size, GL_RGBA, GL_FLOAT, lut,
                          GL_LINEAR, GL_CLAMP_TO_EDGE);
    lp.size = 64; /* 3 planes of 64 x 64 fit in the 256 x 256 buffer */
    hf_lut_bake_dual(&lp, 0, lp.size, lut);
    a->tex_dual0 = hw_texture(internal, lp.size, lp.size, GL_RGBA, GL_FLOAT,
                              lut, GL_LINEAR, GL_CLAMP_TO_EDGE);
    a->tex_dual2 = hw_texture(internal, lp.size, lp.size, GL_RGBA, GL_FLOAT,
                              lut + 2u * 4u * 64u * 64u, GL_LINEAR,
                              GL_CLAMP_TO_EDGE);
    free(lut);
    return 1;
}

/* The density texture and the shadow map (WebGL2 filters no depth
   texture, so NEAREST) with its framebuffer. */
static int hw_init_shadow(hw_app *a)
{
    GLenum none = GL_NONE;
    a->tex_density = hw_texture(GL_R8, 256, 256, GL_RED, GL_UNSIGNED_BYTE,
                                a->density_px, GL_LINEAR, GL_REPEAT);
    a->tex_shadow = hw_texture(GL_DEPTH_COMPONENT24, HW_SHADOW_SIZE,
                               HW_SHADOW_SIZE, GL_DEPTH_COMPONENT,
                               GL_UNSIGNED_INT, NULL, GL_NEAREST,
                               GL_CLAMP_TO_EDGE);
    glGenFramebuffers(1, &a->shadow_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, a->shadow_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D,
                           a->tex_shadow, 0);
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        hw_error(a, "the shadow map framebuffer is incomplete");
        return 0;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return 1;
}

/* The hair's vertex array: indices once, for every strand (a LOD draws a
   prefix), and position and tangent, rewritten every frame. */
static int hw_init_hair_buffers(hw_app *a)
{
    const int S = a->info.strand_count;
    long long n_idx = hf_ribbon_index_count(S, a->P, HF_TRIANGLES);
    uint32_t *idx = (uint32_t *)malloc(sizeof(uint32_t) * (size_t)n_idx);
    if (!idx || hf_ribbon_indices(S, a->P, HF_TRIANGLES, idx, n_idx) != HF_OK) {
        free(idx);
        hw_error(a, "ribbon indices");
        return 0;
    }
    glGenVertexArrays(1, &a->vao_hair);
    glBindVertexArray(a->vao_hair);
    glGenBuffers(1, &a->ibo_hair);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo_hair);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(4 * n_idx), idx,
                 GL_STATIC_DRAW);
    free(idx);
    a->dyn_bytes = sizeof(hw_dyn) * hw_ribbon_vertices(a);
    glGenBuffers(1, &a->vbo_dyn);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_dyn);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)a->dyn_bytes, NULL,
                 GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(hw_dyn), (void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(hw_dyn),
                          (void *)offsetof(hw_dyn, tan));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    return 1;
}

/* The hair's static streams, into its vertex array: texcoord and colour
   depend only on the strand and the point, so they are written once, for
   every strand (the fur's shape at creation). */
static int hw_init_static_buffer(hw_app *a)
{
    const int S = a->info.strand_count;
    const size_t nv = hw_ribbon_vertices(a);
    hw_static *st = (hw_static *)malloc(sizeof(hw_static) * nv);
    hf_ribbon_params v;
    hf_ribbon_output out;
    hf_result r;
    char msg[400];
    if (!st) {
        hw_error(a, "out of memory (static vertices)");
        return 0;
    }
    hw_camera(a);
    hw_ribbon_view(a, &v);
    memset(&out, 0, sizeof out);
    out.texcoord.data = st[0].uv_t;
    out.texcoord.stride = sizeof(hw_static);
    out.color.data = st[0].rgba;
    out.color.stride = sizeof(hw_static);
    out.color3d.data = st[0].c3d;
    out.color3d.stride = sizeof(hw_static);
    if ((r = hf_fur_interpolate(a->fur, 0, S)) != HF_OK ||
        (r = hf_fur_ribbons(a->fur, 0, S, &v, &out)) != HF_OK) {
        snprintf(msg, sizeof msg, "static vertices: %s", hf_result_string(r));
        hw_error(a, msg);
        free(st);
        return 0;
    }
    glGenBuffers(1, &a->vbo_static);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_static);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(hw_static) * nv), st,
                 GL_STATIC_DRAW);
    free(st);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(hw_static),
                          (void *)0);
    glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, sizeof(hw_static),
                          (void *)offsetof(hw_static, rgba));
    glEnableVertexAttribArray(2);
    glEnableVertexAttribArray(3);
    return 1;
}

/* The head's vertex array: its vertices moved every frame, its triangles
   once. */
static void hw_init_head_buffers(hw_app *a)
{
    int i;
    glGenVertexArrays(1, &a->vao_head);
    glBindVertexArray(a->vao_head);
    glGenBuffers(1, &a->vbo_head);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_head);
    glBufferData(GL_ARRAY_BUFFER,
                 (GLsizeiptr)(sizeof(hm_vertex) * (size_t)a->head.vertex_count),
                 NULL, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(hm_vertex),
                          (void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(hm_vertex),
                          (void *)offsetof(hm_vertex, normal));
    glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof(hm_vertex),
                          (void *)offsetof(hm_vertex, uv));
    for (i = 0; i < 3; ++i) glEnableVertexAttribArray((GLuint)i);
    glGenBuffers(1, &a->ibo_head);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo_head);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 (GLsizeiptr)(12 * (size_t)a->head.triangle_count),
                 a->head.indices, GL_STATIC_DRAW);
}

/* Grow the fur, bake the LUTs, make the GL objects. Returns 1, or 0 with
   the error in the status. */
static int hw_init(hw_app *a)
{
    if (!hw_init_head(a) || !hw_init_fur(a) || !hw_init_programs(a) ||
        !hw_init_luts(a) || !hw_init_shadow(a) || !hw_init_hair_buffers(a) ||
        !hw_init_static_buffer(a))
        return 0;
    hw_init_head_buffers(a);
    glBindVertexArray(0);
    return hw_gl_ok(a, "init");
}

/* ---- per frame ---------------------------------------------------------- */

/* The head and its fur at time t: pose, colliders, camera, LOD, roots,
   ropes, LOD guides (glm_simulate). */
static int hw_simulate(hw_app *a, double t, float dt)
{
    hf_result r;
    float lod;
    int i;
    double t0 = emscripten_get_now(), t1;
    a->t = t;
    hm_pose(t, !a->motion, a->pose);
    for (i = 0; i < a->head.vertex_count; ++i) {
        hm_xform(a->pose, a->head.vertices[i].pos, 1.0f, a->skin[i].pos);
        hm_xform(a->pose, a->head.vertices[i].normal, 0.0f,
                 a->skin[i].normal);
    }
    hw_colliders(a->pose, a->col);
    t1 = emscripten_get_now();
    a->sum[ST_SKIN] += t1 - t0;
    hw_camera(a);
    lod = a->lod_control >= 0.0f
              ? a->lod_control
              : hf_lod_from_distance(a->distance,
                                     HW_FULL_DETAIL * a->frame_dist,
                                     HW_CULL * a->frame_dist);
    if (lod != a->lod || a->drawn == 0) {
        hf_fur_set_lod(a->fur, lod);
        hf_fur_get_info(a->fur, &a->info);
        a->lod = lod;
    }
    a->drawn = a->info.drawn_strand_count;
    r = hf_fur_set_roots(a->fur, &a->skinned, 0, a->info.guide_count);
    if (!r) r = hf_fur_build_grid(a->fur, 0, a->info.grid_resolution);
    if (!r)
        r = hf_fur_simulate(a->fur, 0, a->info.guide_count, dt, a->col,
                            HW_NCOL);
    if (!r) r = hf_fur_interpolate_guides(a->fur, 0, a->info.lod_guide_count);
    a->sum[ST_ROPES] += emscripten_get_now() - t1;
    if (r != HF_OK) {
        char msg[200];
        snprintf(msg, sizeof msg, "simulate at t = %.3f: %s", t,
                 hf_result_string(r));
        hw_error(a, msg);
        return 0;
    }
    return 1;
}

/* 2D texture `tex` on unit `unit`, and the shader's sampler `name` on
   it. */
static void hw_sampler(GLuint prog, int unit, GLuint tex, const char *name)
{
    glActiveTexture((GLenum)(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(glGetUniformLocation(prog, name), unit);
}

/* The drawn strands: interpolation and ribbons into our memory, then
   copied into the GL buffer (WebGL2 maps no buffer). */
static int hw_build(hw_app *a)
{
    hf_ribbon_params v;
    hf_ribbon_output out;
    hf_result r;
    double t0 = emscripten_get_now(), t1;
    const int n = a->drawn;
    hw_ribbon_view(a, &v);
    memset(&out, 0, sizeof out);
    out.position.data = a->dyn[0].pos;
    out.position.stride = sizeof(hw_dyn);
    out.tangent.data = a->dyn[0].tan;
    out.tangent.stride = sizeof(hw_dyn);
    r = hf_fur_interpolate(a->fur, 0, n);
    if (r == HF_OK) r = hf_fur_ribbons(a->fur, 0, n, &v, &out);
    t1 = emscripten_get_now();
    a->sum[ST_STRANDS] += t1 - t0;
    if (r != HF_OK) {
        char msg[200];
        snprintf(msg, sizeof msg, "strands: %s", hf_result_string(r));
        hw_error(a, msg);
        return 0;
    }
    /* orphan, then the drawn prefix */
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_dyn);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)a->dyn_bytes, NULL,
                 GL_STREAM_DRAW);
    glBufferSubData(GL_ARRAY_BUFFER, 0,
                    (GLsizeiptr)(sizeof(hw_dyn) * 2u * (size_t)n *
                                 (size_t)a->P),
                    a->dyn);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_head);
    glBufferSubData(GL_ARRAY_BUFFER, 0,
                    (GLsizeiptr)(sizeof(hm_vertex) *
                                 (size_t)a->head.vertex_count),
                    a->skin);
    a->sum[ST_UPLOAD] += emscripten_get_now() - t1;
    return 1;
}

static void hw_light_dir(float L[3])
{
    L[0] = 0.55f; L[1] = 0.75f; L[2] = 0.45f;
    hw_normalize3(L);
}

static void hw_lights(hw_app *a, GLuint prog)
{
    float L[3];
    hw_light_dir(L);
    glUniform3f(glGetUniformLocation(prog, "u_light_dir"), L[0], L[1], L[2]);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_light_view_proj"), 1,
                       GL_FALSE, a->light_view_proj);
    /* hair_shading.glsl's settings: shadows from the one depth map;
       Marschner with dual scattering (the hair's only) */
    glUniform1f(glGetUniformLocation(prog, "u_shadow_on"), 1.0f);
    glUniform1f(glGetUniformLocation(prog, "u_deep"), 0.0f);
    glUniform1f(glGetUniformLocation(prog, "u_spec"), 1.0f);
    glUniform1f(glGetUniformLocation(prog, "u_dual"), 1.0f);
    glUniform1f(glGetUniformLocation(prog, "u_shadow_k"), a->shadow_k);
    glUniform1f(glGetUniformLocation(prog, "u_shadow_depth"), a->shadow_depth);
    glUniform1f(glGetUniformLocation(prog, "u_shadow_bias"),
                3.0f * a->shadow_depth / HW_SHADOW_SIZE);
    hw_sampler(prog, 7, a->tex_shadow, "u_shadow");
    glActiveTexture(GL_TEXTURE0);
    glUniform3f(glGetUniformLocation(prog, "u_light_color"), 1.9f, 1.8f, 1.65f);
    glUniform3f(glGetUniformLocation(prog, "u_ambient"), 0.22f, 0.24f, 0.30f);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                       a->view_proj);
}

static void hw_draw_hair(hw_app *a, GLuint prog, const float eye[3])
{
    glUniform3fv(glGetUniformLocation(prog, "u_eye"), 1, eye);
    glBindVertexArray(a->vao_hair);
    glDrawElements(GL_TRIANGLES, (GLsizei)(6 * (a->P - 1) * a->drawn),
                   GL_UNSIGNED_INT, 0);
}

/* the shadow map: head and hair from the light, orthographic around the
   head and its hair (glm_shadow_pass) */
static void hw_shadow_pass(hw_app *a)
{
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    float c[3], L[3], eye[3], view[16], proj[16], r = 0.0f;
    const float up[3] = {0, 1, 0};
    int i, k;
    for (i = 0; i < a->head.vertex_count; ++i)
        for (k = 0; k < 3; ++k) {
            if (a->skin[i].pos[k] < lo[k]) lo[k] = a->skin[i].pos[k];
            if (a->skin[i].pos[k] > hi[k]) hi[k] = a->skin[i].pos[k];
        }
    for (k = 0; k < 3; ++k) {
        c[k] = 0.5f * (lo[k] + hi[k]);
        r += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    r = sqrtf(r) + 1.05f * a->hair_len;
    hw_light_dir(L);
    for (k = 0; k < 3; ++k) eye[k] = c[k] + 2.0f * r * L[k];
    hw_mat4_look_at(view, eye, c, up);
    hw_mat4_ortho(proj, -r, r, -r, r, r, 3.0f * r);
    hw_mat4_mul(a->light_view_proj, proj, view);
    a->shadow_depth = 2.0f * r;
    glBindFramebuffer(GL_FRAMEBUFFER, a->shadow_fbo);
    glViewport(0, 0, HW_SHADOW_SIZE, HW_SHADOW_SIZE);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_CULL_FACE);
    glUseProgram(a->depth_head);
    glUniformMatrix4fv(glGetUniformLocation(a->depth_head, "u_view_proj"), 1,
                       GL_FALSE, a->light_view_proj);
    glBindVertexArray(a->vao_head);
    glDrawElements(GL_TRIANGLES, 3 * a->head.triangle_count, GL_UNSIGNED_INT,
                   0);
    if (a->drawn > 0) {
        glUseProgram(a->depth_hair);
        glUniformMatrix4fv(glGetUniformLocation(a->depth_hair, "u_view_proj"),
                           1, GL_FALSE, a->light_view_proj);
        hw_draw_hair(a, a->depth_hair, eye);
    }
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static void hw_draw(hw_app *a)
{
    double t0 = emscripten_get_now();
    float sc[3];
    hw_shadow_pass(a);
    glViewport(0, 0, a->width, a->height);
    glClearColor(0.13f, 0.14f, 0.17f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_CULL_FACE);
    /* the head, its scalp the hair colour, darkened */
    glUseProgram(a->prog_head);
    hw_lights(a, a->prog_head);
    sc[0] = 0.25f * powf(0.2f, 2.2f);
    sc[1] = 0.25f * powf(0.1f, 2.2f);
    sc[2] = 0.25f * powf(0.05f, 2.2f);
    glUniform3fv(glGetUniformLocation(a->prog_head, "u_scalp"), 1, sc);
    hw_sampler(a->prog_head, 0, a->tex_density, "u_density");
    glBindVertexArray(a->vao_head);
    glDrawElements(GL_TRIANGLES, 3 * a->head.triangle_count, GL_UNSIGNED_INT,
                   0);
    /* the hair, tips faded by blending; the target stays opaque */
    if (a->drawn > 0) {
        glUseProgram(a->prog_hair);
        hw_lights(a, a->prog_hair);
        hw_sampler(a->prog_hair, 0, a->tex_m, "u_lut_m");
        hw_sampler(a->prog_hair, 1, a->tex_n, "u_lut_n");
        hw_sampler(a->prog_hair, 4, a->tex_dual0, "u_dual0");
        hw_sampler(a->prog_hair, 5, a->tex_dual2, "u_dual2");
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
        hw_draw_hair(a, a->prog_hair, a->eye);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDisable(GL_BLEND);
        glActiveTexture(GL_TEXTURE0);
    }
    glBindVertexArray(0);
    a->sum[ST_DRAW] += emscripten_get_now() - t0;
}

#define HW_BENCH_WARMUP 5 /* frames a bench run leaves out first */

/* The page's figures: each stage's mean over the last HW_STATS_MS; a
   bench run's means over its frames after the warm-up, into the status
   when they are done. */
static void hw_account(hw_app *a, double now)
{
    int k;
    if (a->bench_frames > 0) {
        if (a->frame == HW_BENCH_WARMUP) a->bench_since = now;
        if (a->frame > HW_BENCH_WARMUP)
            for (k = 0; k < ST_N; ++k) a->bench_sum[k] += a->sum[k];
        if (a->frame == HW_BENCH_WARMUP + a->bench_frames) {
            double n = (double)a->bench_frames;
            size_t len = strlen(a->status);
            snprintf(a->status + len, sizeof a->status - len,
                     "%sbench: %ld frames after %d, %d of %d strands, SIMD "
                     "level %d: skin and colliders %.2f, ropes and LOD "
                     "guides %.2f, strands and ribbons %.2f, upload %.2f, "
                     "GL calls %.2f, frame %.2f ms",
                     len ? "; " : "", a->bench_frames, HW_BENCH_WARMUP,
                     a->drawn, a->info.strand_count, hf_simd_resolve(a->simd),
                     a->bench_sum[ST_SKIN] / n, a->bench_sum[ST_ROPES] / n,
                     a->bench_sum[ST_STRANDS] / n, a->bench_sum[ST_UPLOAD] / n,
                     a->bench_sum[ST_DRAW] / n, (now - a->bench_since) / n);
            emscripten_cancel_main_loop();
            emscripten_run_script(
                "if (Module.hairfurDone) Module.hairfurDone();");
        }
    }
    ++a->sum_frames;
    if (now - a->sum_since < HW_STATS_MS) return;
    for (k = 0; k < ST_N; ++k) {
        a->mean[k] = a->sum[k] / (double)a->sum_frames;
        a->sum[k] = 0.0;
    }
    a->mean[ST_FRAME] = (now - a->sum_since) / (double)a->sum_frames;
    a->sum_frames = 0;
    a->sum_since = now;
}

/* one frame in real time (requestAnimationFrame) */
static void hw_frame(void)
{
    hw_app *a = &g_app;
    double now = emscripten_get_now();
    float dt = (float)((now - a->last_now) * 1e-3);
    if (dt <= 0.0f) dt = 1.0f / 60.0f;
    if (dt > 0.05f) dt = 0.05f;
    a->last_now = now;
    if (a->orbit) a->azimuth += 12.0f * dt; /* gl_marschner's 12 deg/s */
    if (!hw_simulate(a, a->t + dt, dt) || !hw_build(a)) {
        emscripten_cancel_main_loop();
        return;
    }
    hw_draw(a);
    hw_gl_ok(a, "frame");
    hw_account(a, now);
    ++a->frame;
}

/* The test run: a->frames steps of 1/60 s, the last one drawn, then the
   picture checked: not blank (hair-coloured pixels where the hair is), no
   GL error. The result goes into the status; the page reads it. */
static void hw_run_fixed(hw_app *a)
{
    long f;
    int ok = 1;
    unsigned char *px;
    for (f = 0; f < a->frames && ok; ++f) {
        float dt = 1.0f / 60.0f;
        if (a->orbit) a->azimuth += 12.0f * dt;
        ok = hw_simulate(a, (double)(f + 1) / 60.0, dt);
    }
    if (ok) ok = hw_build(a);
    if (ok) {
        hw_draw(a);
        ok = hw_gl_ok(a, "draw");
    }
    px = (unsigned char *)malloc(4u * (size_t)a->width * (size_t)a->height);
    if (ok && px) {
        /* pixels off the clear colour (0.13, 0.14, 0.17: 33, 36, 43) by
           more than 24 in a channel, as png_diff --stats counts them */
        long off = 0, i, n = (long)a->width * a->height;
        glReadPixels(0, 0, a->width, a->height, GL_RGBA, GL_UNSIGNED_BYTE, px);
        for (i = 0; i < n; ++i) {
            const unsigned char *p = px + 4 * i;
            off += abs(p[0] - 33) > 24 || abs(p[1] - 36) > 24 ||
                   abs(p[2] - 43) > 24;
        }
        snprintf(a->status + strlen(a->status),
                 sizeof a->status - strlen(a->status),
                 "%s%ld steps of 1/60 s, the last drawn: %d of %d "
                 "strands, SIMD level %d; picture: %.1f %% off the "
                 "background",
                 a->status[0] ? "; " : "", (long)a->frames, a->drawn,
                 a->info.strand_count, hf_simd_resolve(a->simd),
                 100.0 * off / n);
        if (off < n / 20) hw_error(a, "blank picture");
        ok = hw_gl_ok(a, "readback");
    }
    free(px);
    (void)ok;
}

/* ---- the page's calls --------------------------------------------------- */

/* exported under their C names (shell.html calls Module._web_...), also
   when this file is built as C++ */
#ifdef __cplusplus
#define HW_EXPORT extern "C" EMSCRIPTEN_KEEPALIVE
#else
#define HW_EXPORT EMSCRIPTEN_KEEPALIVE
#endif

HW_EXPORT void web_set_lod(float lod) { g_app.lod_control = lod; }
HW_EXPORT void web_set_motion(int on) { g_app.motion = on; }
HW_EXPORT void web_set_orbit(int on) { g_app.orbit = on; }

/* wind (m/s^2 along +x) and global stiffness, into the fur's ropes */
HW_EXPORT void web_set_ropes(float wind, float stiffness)
{
    g_app.wind = wind;
    g_app.stiffness = stiffness;
    hw_rope_params(&g_app);
    if (g_app.fur && hf_fur_set_rope_params(g_app.fur, &g_app.rp) != HF_OK)
        hw_error(&g_app, "hf_fur_set_rope_params refused the controls");
}

/* 0: the best level this build has (wasm SIMD128), 1: the scalar one */
HW_EXPORT void web_set_simd(int level)
{
    g_app.simd = level;
    g_app.rp.simd = level;
    if (g_app.fur) hf_fur_set_kernels(g_app.fur, level, 0);
}

/* The on-page figures, one line each, and the status. */
HW_EXPORT const char *web_stats(void)
{
    static char s[1024];
    const hw_app *a = &g_app;
    int level = hf_simd_resolve(a->simd);
    snprintf(s, sizeof s,
             "%d of %d strands (LOD %.2f), %d guides, %d points each\n"
             "SIMD: %s\n"
             "skin, colliders   %6.2f ms\n"
             "ropes, LOD guides %6.2f ms\n"
             "strands, ribbons  %6.2f ms\n"
             "upload            %6.2f ms\n"
             "GL calls          %6.2f ms\n"
             "frame             %6.2f ms (%.1f fps)\n",
             a->drawn, a->info.strand_count, a->lod, a->info.guide_count, a->P,
             level == HF_SIMD_WASM128 ? "WebAssembly SIMD128 (the SSE2 kernels)"
             : level == HF_SIMD_SCALAR ? "scalar"
                                       : "?",
             a->mean[ST_SKIN], a->mean[ST_ROPES], a->mean[ST_STRANDS],
             a->mean[ST_UPLOAD], a->mean[ST_DRAW], a->mean[ST_FRAME],
             a->mean[ST_FRAME] > 0.0 ? 1000.0 / a->mean[ST_FRAME] : 0.0);
    return s;
}

HW_EXPORT const char *web_status(void) { return g_app.status; }
HW_EXPORT int web_errors(void) { return g_app.errors; }

/* ---- main ---------------------------------------------------------------- */

static long hw_arg(int argc, char **argv, const char *name, long def,
                   long lo, long hi)
{
    int i;
    for (i = 1; i + 1 < argc; ++i)
        if (!strcmp(argv[i], name)) {
            char *end;
            long v = strtol(argv[i + 1], &end, 10);
            if (*end || v < lo || v > hi) {
                char msg[200];
                snprintf(msg, sizeof msg, "%s %s: not in %ld..%ld", name,
                         argv[i + 1], lo, hi);
                hw_error(&g_app, msg);
                return def;
            }
            return v;
        }
    return def;
}

int main(int argc, char **argv)
{
    hw_app *a = &g_app;
    EmscriptenWebGLContextAttributes attr;
    a->frames = (int)hw_arg(argc, argv, "--frames", 0, 0, 100000);
    a->bench_frames = hw_arg(argc, argv, "--bench", 0, 0, 100000);
    a->seed = (int)hw_arg(argc, argv, "--seed", 7, 0, 2147483647L);
    a->strands = (int)hw_arg(argc, argv, "--strands", 20000, 1, 1000000);
    a->simd = (int)hw_arg(argc, argv, "--simd", 0, 0, 4);
    a->lod_control = -1.0f;
    a->motion = a->orbit = 1;
    a->azimuth = 30.0f;
    a->elevation = 12.0f;
    a->width = 640;
    a->height = 480;
    emscripten_set_canvas_element_size("#canvas", a->width, a->height);
    emscripten_webgl_init_context_attributes(&attr);
    attr.majorVersion = 2;
    attr.minorVersion = 0;
    attr.alpha = 0;
    attr.antialias = 1;
    attr.depth = 1;
    /* the test run's picture stays for the screenshot */
    attr.preserveDrawingBuffer = a->frames > 0;
    a->ctx = emscripten_webgl_create_context("#canvas", &attr);
    if (a->ctx <= 0 || emscripten_webgl_make_context_current(a->ctx) !=
                           EMSCRIPTEN_RESULT_SUCCESS) {
        hw_error(a, "no WebGL2 context");
    } else if (hw_init(a)) {
        a->last_now = a->sum_since = emscripten_get_now();
        if (a->frames > 0) {
            hw_run_fixed(a);
        } else {
            /* the page's controls apply from here on */
            emscripten_run_script(
                "if (Module.hairfurReady) Module.hairfurReady();");
            emscripten_set_main_loop(hw_frame, 0, 0);
            return 0;
        }
    }
    emscripten_run_script("if (Module.hairfurDone) Module.hairfurDone();");
    return 0;
}
