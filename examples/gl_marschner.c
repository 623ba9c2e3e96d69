/* gl_marschner.c - hairfur.h fur and hair on any mesh, lit with the
   Marschner model in GLSL 330: the viewer.

   Shows a complete engine-style integration, on the built-in head
   (examples/head_mesh.h) or on any mesh assimp reads (--mesh):
     - a mesh's skin animated on the CPU every frame from its bones and
       animation keys (examples/character.h: linear blend skinning), the
       fur's roots following it (hf_fur_set_roots), and a capsule collider
       per bone fitted to the vertices it moves, following it too;
     - everything that depends on the model's size (camera, ribbon width
       from the strand spacing, LOD distances, guide count, shadow
       strength) measured from it, and the file's unit found from its
       size, so a model in centimetres gives the picture it gives in
       metres;
     - the M and N lookup textures of the energy-conserving Marschner
       fibre and the dual scattering tables baked in-process
       (hf_lut_bake_m / hf_lut_bake_n with HF_LUT_ENERGY, hf_lut_bake_dual;
       RGBA32F, GL_LINEAR, clamp to edge) and combined in the fragment
       shader as docs/luts.md says (--no-dual: single scattering only),
       plus ambient light; Kajiya-Kay as a switch;
     - self-shadowing: deep opacity maps of the hair from the light (three
       layers of opacity behind the first hair, Yuksel and Keyser 2008)
       and the body's depth, read by hair and body alike; --shadows
       single: one shadow map read as an approximate deep shadow map
       (light falls off with the depth of hair in front);
     - hair colour from the 2D colour map (per-vertex colour stream of
       hf_fur_ribbons) or the 3D colour scheme (color3d stream sampling a
       ramp texture with dyed tips);
     - an orbiting camera and LOD by distance (hf_lod_from_distance), the
       drawn strand count in the window title;
     - two ways to feed the GPU: CPU ribbons (hf_fur_ribbons, the dynamic
       position + tangent streams only) or GPU expansion (hf_fur_points into
       a GL_RGBA32F texture buffer, expanded by examples/ribbon_expand.glsl),
       both drawn with the same hf_ribbon_indices buffer, and both
       written straight into the mapped GL buffer with streaming stores
       (--copy: written into our memory, then glBufferSubData; --staging:
       into a mapped staging buffer, then copied on the GPU);
     - compact CPU ribbons (--compact): 16-byte vertices, position SNORM16
       around the camera target, texcoord UNORM16, tangent SNORM8, read by
       GL as normalized integers (docs/rendering.md "Compact vertices").

   Build: make build/gl_marschner (needs libglfw3-dev, libegl-dev,
   libstb-dev, libassimp-dev, python3-glad: make deps).
   Run from the repo root (the hair's shading is read from
   examples/hair_shading.glsl, the GPU path's from
   examples/ribbon_expand.glsl):
     build/gl_marschner                       the head, in a window
     build/gl_marschner --mesh /usr/share/assimp/models/X/Testwuson.X \
         --anim Wuson_Walk --hair-length 0.08 --stiffness 0.4
     build/gl_marschner --headless --frames 60 --out out/fur.png
   gl_marschner --help lists every option with its unit and default, and
   the keys (K Kajiya-Kay, G GPU expansion, C 3D colour, V colliders,
   O shadows, S specular, H motion, space orbit, +/- distance, arrows).
   At the end it prints the worst stretch of a guide, the count of
   non-finite coordinates, how far the guide roots are from the skinned
   mesh, the roots inside a collider and the milliseconds of each stage.

   Define GLM_NO_MAIN to include this file in a test (tests/gl_fur_check.c)
   and drive glm_init / glm_step / glm_draw yourself. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#define GLC_IMPLEMENTATION
#include "gl_common.h"
#define HAIRFUR_IMPLEMENTATION
#include "hairfur.h"
#define HEAD_MESH_IMPLEMENTATION
#include "head_mesh.h"
#define CHARACTER_IMPLEMENTATION
#include "character.h"
#define CURVES_IMPLEMENTATION
#include "curves.h"
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#ifndef GLM_NO_MAIN
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define GLM_PI 3.14159265358979f
#define GLM_HEAD_R 0.1f          /* head_mesh.h sphere radius, metres */
/* Everything the scene's size sets is a multiple of the framing distance
   (1.588 bounding-box diagonals of the grown mesh: 0.55 m for the head):
   LOD 1 up to 1.09 of it, no hair beyond 54.5 of it. */
#define GLM_FRAME_DIAG 1.588f
#define GLM_FULL_DETAIL 1.09f
#define GLM_CULL 54.5f
#define GLM_HEAD_COLLIDERS 3
#define GLM_SHADOW_SIZE 1024     /* shadow map texels a side */
/* Deep opacity maps: the three layers behind the first hair from the
   light end at these fractions of the hair length past it (the last
   layer takes everything further), and a fibre's opacity, as a fraction
   of a shadow-map texel it covers, becomes transmittance
   exp(-GLM_OPACITY_K * opacity). */
#define GLM_LAYER_1 0.08f
#define GLM_LAYER_2 0.2f
#define GLM_LAYER_3 0.5f
#define GLM_OPACITY_K 1.0f
#define GLM_WIDTH_SPACING 0.66f  /* root width / mean strand spacing */
/* Ribbons are drawn at least this many pixels wide, their alpha scaled
   by the width they lost (GLM_COVERAGE_GLSL; --min-width). */
#define GLM_MIN_PX 1.0f
/* Each strand fades in from alpha 0 at its root over GLM_ROOT_FADE root
   widths, at most GLM_ROOT_FADE_LEN of the hair length (GLM_ROOT_GLSL): a
   hairline blends into the skin, and short fur keeps its roots. */
#define GLM_ROOT_FADE 8.0f
#define GLM_ROOT_FADE_LEN 0.04f
/* OIT's depth weight grows e times every GLM_OIT_FALLOFF of the framing
   distance nearer (8 mm on the head, framed at 0.55 m), so the outer
   layer of hair outweighs the hair a centimetre under it by 3.5 times
   and hides the far side of the head; float32 targets hold its range. */
#define GLM_OIT_FALLOFF 0.015f

/* How each frame's strands reach the GL buffer they are drawn from:
   written straight into it, mapped (the default); into our memory, then
   glBufferSubData (--copy); into a mapped staging buffer, then copied on
   the GPU with glCopyBufferSubData (--staging), so that the buffer drawn
   from is never mapped and the driver may keep it in GPU memory. */
enum { GLM_MAPPED, GLM_COPY, GLM_STAGING };

typedef struct glm_options {
    int width, height, headless, frames, strands, lut_size;
    const char *out, *expand_shader, *shading_shader;
    int kajiya, gpu_expand, color3d, colliders, still, a2c, draw_all;
    int compact;      /* CPU ribbons as glm_compact vertices */
    int upload;       /* how the strands reach the GL buffers: GLM_MAPPED,
                         GLM_COPY or GLM_STAGING */
    float specular;   /* 1 = on; 0 = diffuse + ambient only */
    float distance;   /* camera distance to the head centre (m) */
    float lod;        /* < 0: from the distance */
    float azimuth, elevation, orbit_speed; /* degrees, degrees/s */
    /* a mesh instead of the built-in head */
    const char *mesh, *anim, *grow_on, *unit;
    const char *density_path, *length_path, *color_path;
    int no_shadows;     /* 1: no self-shadowing */
    int single_shadow;  /* 1: one depth map, exp(-k d) (--shadows single);
                           0: deep opacity maps */
    int no_dual;        /* 1: no dual scattering (single scattering only) */
    int no_hair;        /* 1: the body alone (a control picture) */
    float min_px;       /* ribbons drawn at least this wide (pixels), their
                           alpha scaled by the width lost; 0: as built */
    float root_fade;    /* root widths each strand fades in over, its depth
                           lifted (GLM_ROOT_GLSL); 0: roots as built */
    int no_oit;         /* 1: the hair blended in draw order with depth
                           writes (--no-oit); 0: weighted blended
                           order-independent transparency */
    int save_every;     /* > 0: write every Nth frame to out (a %d pattern) */
    float hair_length;  /* metres; 0 = 0.14 on the head, else 5 % of the
                           grown mesh's bounding-box diagonal */
    float hair_color[3];/* sRGB, without a colour map */
    float stiffness;    /* global shape stiffness [0, 1] */
    float comb[3];      /* world direction hair is combed in, its length
                           the strength (0: along the normal) */
    float settle;       /* seconds simulated at the first pose, first */
    float rest_gravity; /* seconds draped before the rest shape is taken */
    float volume, friction; /* hair-hair: 0 = off */
    int grid;           /* nodes along each axis of the hair-hair grid */
    int keep_length;    /* hf_fur_desc.keep_length */
    const char *guides_path; /* authored guide curves (.hair, .tfx, .obj) */
    const char *groom_path;  /* a groom: its strands drawn, some simulated */
    float guide_fraction;    /* of the groom's strands; 0 = 0.1 */
    float curl[2], wave[2];  /* radius and turns; amplitude and count */
    float frizz, color_variation, width_variation;
    float clump[2];          /* strength, size (0: clumps around guides) */
    int guides;         /* guide target; 0 = strands / 10, at most 2,000 */
} glm_options;

static void glm_default_options(glm_options *o)
{
    memset(o, 0, sizeof *o);
    o->width = 640;
    o->height = 480;
    o->strands = 20000;
    o->lut_size = 256;
    o->specular = 1.0f;
    o->lod = -1.0f;
    o->hair_color[0] = 0.42f;
    o->hair_color[1] = 0.27f;
    o->hair_color[2] = 0.16f;
    o->clump[0] = 0.25f;
    o->azimuth = 30.0f;
    o->elevation = 12.0f;
    o->orbit_speed = 12.0f;
    o->volume = 1.0f; /* the library's defaults */
    o->friction = 0.2f;
    o->grid = 32;
    o->min_px = GLM_MIN_PX;
    o->root_fade = GLM_ROOT_FADE;
}

/* Interleaved per-vertex layouts. The dynamic stream is rewritten every
   frame; the static one (texcoord, colour with the tip fade, 3D-colour
   coordinates) depends only on the strand and the point, so it is written
   once for all strands: 24 instead of 60 bytes a vertex go over the bus. */
typedef struct glm_dyn { float pos[3], tan[3]; } glm_dyn;
typedef struct glm_static { float uv_t[3], rgba[4], c3d[2]; } glm_static;

/* --compact: the 16-byte vertex of bench/bench.c, in place of glm_dyn.
   Position SNORM16 in a GLM_COMPACT_SCALE box around the head centre
   (scale / 32767 = 15 um steps), texcoord UNORM16, tangent SNORM8 (the
   shader renormalises it); one pad byte keeps the stride a multiple of 4.
   The texcoord never changes, so it is written once at init and each frame
   writes only position and tangent into the same array: 16 instead of 24
   bytes a vertex go over the bus. Colour and 3D colour stay in glm_static. */
typedef struct glm_compact {
    int16_t pos[3];
    uint16_t uv_t[3];
    int8_t tan[3];
    uint8_t pad;
} glm_compact;
#define GLM_COMPACT_SCALE 0.5f /* m: holds the head and its hair, swinging;
                                  a mesh: its size and twice its hair */

typedef struct glm_app {
    glm_options o;
    /* the body: the built-in head or a mesh file (ch.vertex_count > 0) */
    ch_character ch;
    int anim;             /* ch's animation, -1 none */
    int nv, nt, nt_grown; /* vertices; triangles, the grown ones first */
    ch_vertex *rest, *skin;
    uint32_t *body_idx;   /* the triangles as drawn: grown ones first */
    int grow_first, grow_count; /* the grown mesh's vertex range */
    uint32_t *grow_idx;   /* its triangles, relative to grow_first */
    hf_mesh skinned;
    float size;           /* bounding-box diagonal of the grown mesh (m) */
    float ch_diag;        /* and of the whole body */
    float frame_dist;     /* the framing distance: GLM_FRAME_DIAG * size */
    float target0[3], centroid0[3]; /* camera target and grown centroid at
                                       rest: a mesh's camera follows it */
    float hair_len, root_width, shadow_k;
    double hair_area;     /* grown area weighted by density (m^2) */
    float *rest_len;      /* per guide: its length at rest */
    float *rest_root;     /* per guide: its root at creation, so the report
                             can find where on the mesh it belongs */
    long nonfinite;       /* guide coordinates not finite, over all frames */
    int stretch_nan;      /* a guide's stretch was NaN in some frame */
    float *comb_dir;      /* per grown vertex: growth direction (--comb) */
    cv_curves curves;     /* --guides or --groom, in metres */
    int groom;            /* --groom: roots follow the body rigidly */
    float *groom_rgb;     /* per groom strand: --hair-color */
    double stretch_max, stretch_sum;
    long stretch_frames;
    double ms_skin, ms_sim, ms_build, ms_upload, ms_draw; /* sums */
    double ms_roots, ms_ropes; /* parts of ms_sim (roots: with the grid) */
    long ms_frames, build_frames;
    unsigned char *density_px, *length_px, *color_px, *index_px;
    hf_map density, length, color, index;
    int have_density, have_length;
    hf_fur *fur;
    hf_fur_info info;
    int P;
    glm_dyn *dyn;       /* CPU-ribbon stream, all strands */
    glm_compact *cdyn;  /* the same, --compact */
    float corigin[3], cscale; /* what cdyn's positions were written
                                 relative to, for the shader to undo */
    float *points4;     /* GPU-expansion stream, all strands */
    hf_collider *col, *all_col; /* the colliders used; all the bones' */
    int *col_keep, ncol, max_col;
    float pose[12];
    float eye[3], target[3], view_proj[16];
    float lod;
    int drawn;
    double t;           /* simulated time */
    double cpu_ms, draw_ms;
    int draw_hair;      /* tests switch the hair off to get a mask */
    /* GL */
    GLuint prog_cpu, prog_cpu16, prog_gpu, prog_head, prog_line;
    GLuint depth_cpu, depth_cpu16, depth_gpu, depth_head; /* shadow pass */
    GLuint shadow_fbo, tex_shadow;
    GLuint opacity_fbo, tex_opacity; /* deep opacity maps: 3 layers + body */
    GLuint opacity_cpu, opacity_cpu16, opacity_gpu, opacity_head;
    float layers[3], opacity_texel; /* layer ends (m); a fibre's coverage */
    double shadow_ms, ms_shadow;    /* the shadow passes, glFinish-timed */
    float light_view_proj[16], shadow_depth; /* light's clip, depth range (m) */
    GLuint vao_cpu, vao_cpu16, vao_gpu, vao_head, vao_line;
    GLuint vbo_dyn, vbo_dyn16, vbo_static, vbo_points, tbo_points;
    GLuint vbo_stage;   /* --staging: the mapped buffer copied from */
    size_t stage_bytes; /* its size */
    GLuint vbo_uv, tbo_uv;
    GLuint vbo_scolor, tbo_scolor, vbo_c3x, tbo_c3x, ibo_hair;
    GLuint vbo_head, ibo_head, vbo_line;
    GLuint tex_m, tex_n, tex_ramp, tex_density;
    GLuint tex_dual[HF_LUT_DUAL_PLANES]; /* hf_lut_bake_dual's planes */
    GLuint tbo_pair, tbo_pair16; /* vbo_dyn, vbo_dyn16 as texture buffers:
                                    the other side of a ribbon vertex */
    int min_width;      /* the texture buffers fit: the 1-pixel clamp */
    /* weighted blended OIT: accumulated colour (and the revealage in its
       alpha) and the weights' sum, sharing the target's depth */
    GLuint oit_fbo, tex_accum, tex_weight, prog_oit, vao_empty;
    int oit_ok, oit_samples;
    float *line_buf;
    int line_count;
} glm_app;

static double glm_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* ---- shaders ------------------------------------------------------------ */

/* Strands narrower than a pixel (GLM_COVERAGE_GLSL, in every hair vertex
   shader): a ribbon drawn narrower than u_min_px pixels on screen is
   widened about its centre line to u_min_px, and its alpha scaled by
   true width / drawn width, so a thin strand fades by its coverage
   instead of breaking into the dotted line that rasterising a sliver
   gives. p is this vertex, q the other vertex of its pair (the two
   sides of one strand point); u_min_px 0 (the shadow passes) leaves
   the ribbon as it is. */
#define GLM_COVERAGE_GLSL                                                    \
    "uniform vec2 u_viewport;   // target size, pixels\n"                    \
    "uniform float u_min_px;    // 0: as built\n"                            \
    "// widens p (its pair's other side q) to u_min_px on screen;\n"         \
    "// returns the coverage, true width / drawn width\n"                   \
    "float min_width(inout vec3 p, vec3 q) {\n"                              \
    "    if (u_min_px <= 0.0) return 1.0;\n"                                 \
    "    vec4 a = u_view_proj * vec4(p, 1.0), b = u_view_proj * vec4(q, 1.0);\n" \
    "    if (a.w <= 0.0 || b.w <= 0.0) return 1.0;\n"                        \
    "    float px = length((a.xy / a.w - b.xy / b.w) * 0.5 * u_viewport);\n" \
    "    if (px >= u_min_px) return 1.0;\n"                                  \
    "    vec3 c = 0.5 * (p + q);\n"                                          \
    "    p = c + (p - c) * (u_min_px / max(px, 1e-3 * u_min_px));\n"        \
    "    return px / u_min_px;\n"                                            \
    "}\n"

/* The hairline (GLM_ROOT_GLSL, in every hair vertex shader, after
   u_eye and u_view_proj). A ribbon is a flat stand-in for a fibre whose
   near side is half its width nearer the eye; at the root, where the
   fibre leaves the skin, the flat ribbon dips into it, and the body's
   depth cuts it into jagged pieces. u_lift 1 (the picture; 0 in the
   shadow passes) moves the depth, not the pixel, of each vertex half the
   strand's width along its ray towards the eye. v_root, metres from the
   strand's root point, lets the fragment shaders fade the first
   u_root_fade metres (glm_root_fade): where roots stand over bare skin
   they blend into it, as a real hairline's thin hairs do, instead of
   ending in an opaque ribbon-wide edge. */
#define GLM_ROOT_GLSL                                                        \
    "uniform float u_lift;      // 1: depth half a width nearer the eye\n"  \
    "out float v_root;          // metres from the root point\n"            \
    "// gl_Position of p, a point of a strand hw (half its width) wide\n"   \
    "vec4 hair_clip(vec3 p, float hw) {\n"                                  \
    "    vec3 e = u_eye - p;\n"                                             \
    "    float l = length(e);\n"                                            \
    "    if (u_lift > 0.0 && l > 2.0 * hw) p += e * (hw / l);\n"            \
    "    return u_view_proj * vec4(p, 1.0);\n"                              \
    "}\n"

/* The root fade, in the hair and the opacity fragment shaders. */
#define GLM_ROOT_FADE_GLSL                                                   \
    "in float v_root;\n"                                                    \
    "uniform float u_root_fade; // metres; 0: none\n"                       \
    "float root_fade() {\n"                                                 \
    "    return u_root_fade > 0.0 ? smoothstep(0.0, u_root_fade, v_root)\n" \
    "                             : 1.0;\n"                                 \
    "}\n"

/* CPU-ribbon vertex shader: everything comes from hf_fur_ribbons. The
   pair's other vertex (gl_VertexID ^ 1: hf_ribbon_indices numbers a
   point's two sides 2k and 2k + 1) is read from the same buffer, bound
   as a GL_RG32F texture buffer (glm_dyn: 3 texels a vertex, x y | z). */
static const char *glm_vs_cpu =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a_pos;\n"
    "layout(location = 1) in vec3 a_tangent;\n"
    "layout(location = 2) in vec3 a_texcoord;\n"
    "layout(location = 3) in vec4 a_color;\n"
    "layout(location = 4) in vec2 a_color3d;\n"
    "uniform mat4 u_view_proj;\n"
    "uniform vec3 u_eye;\n"
    "uniform int u_points_per_strand;\n"
    "uniform samplerBuffer u_pair;   // the dynamic buffer, GL_RG32F\n"
    GLM_COVERAGE_GLSL
    GLM_ROOT_GLSL
    "out vec3 v_position, v_tangent, v_texcoord;\n"
    "out vec4 v_color;\n"
    "out vec2 v_c3d;\n"
    "vec3 vertex(int i) {\n"
    "    return vec3(texelFetch(u_pair, 3 * i).xy, texelFetch(u_pair, 3 * i + 1).x);\n"
    "}\n"
    "void main() {\n"
    "    vec3 p = a_pos, q = vertex(gl_VertexID ^ 1);\n"
    "    int r = gl_VertexID - gl_VertexID % (2 * u_points_per_strand);\n"
    "    v_root = 0.5 * length(p + q - vertex(r) - vertex(r + 1));\n"
    "    float hw = 0.5 * length(p - q);\n"
    "    float cov = min_width(p, q);\n"
    "    v_position = p; v_tangent = a_tangent; v_texcoord = a_texcoord;\n"
    "    v_color = vec4(a_color.rgb, a_color.a * cov); v_c3d = a_color3d;\n"
    "    gl_Position = hair_clip(p, hw);\n"
    "}\n";

/* --compact: the same, with the position undone from SNORM16 (GL gives
   a_pos in [-1, 1]) and the SNORM8 tangent renormalised, so the fragment
   shader sees what glm_vs_cpu gives it. The pair's other vertex comes
   from the 16-byte buffer bound as GL_RGBA16I (2 texels a vertex). */
static const char *glm_vs_cpu16 =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a_pos;      // (p - origin) / scale\n"
    "layout(location = 1) in vec3 a_tangent;  // |a_tangent| ~ 1 +- 1/127\n"
    "layout(location = 2) in vec3 a_texcoord;\n"
    "layout(location = 3) in vec4 a_color;\n"
    "layout(location = 4) in vec2 a_color3d;\n"
    "uniform mat4 u_view_proj;\n"
    "uniform vec3 u_pos_origin;\n"
    "uniform float u_pos_scale;\n"
    "uniform vec3 u_eye;\n"
    "uniform int u_points_per_strand;\n"
    "uniform isamplerBuffer u_pair;  // the 16-byte buffer, GL_RGBA16I\n"
    GLM_COVERAGE_GLSL
    GLM_ROOT_GLSL
    "out vec3 v_position, v_tangent, v_texcoord;\n"
    "out vec4 v_color;\n"
    "out vec2 v_c3d;\n"
    "vec3 vertex(int i) {\n"
    "    vec3 q = vec3(texelFetch(u_pair, 2 * i).xyz);\n"
    "    return u_pos_origin + u_pos_scale * max(q / 32767.0, vec3(-1.0));\n"
    "}\n"
    "void main() {\n"
    "    vec3 p = u_pos_origin + u_pos_scale * a_pos, q = vertex(gl_VertexID ^ 1);\n"
    "    int r = gl_VertexID - gl_VertexID % (2 * u_points_per_strand);\n"
    "    v_root = 0.5 * length(p + q - vertex(r) - vertex(r + 1));\n"
    "    float hw = 0.5 * length(p - q);\n"
    "    float cov = min_width(p, q);\n"
    "    v_position = p; v_tangent = normalize(a_tangent);\n"
    "    v_texcoord = a_texcoord; v_c3d = a_color3d;\n"
    "    v_color = vec4(a_color.rgb, a_color.a * cov);\n"
    "    gl_Position = hair_clip(p, hw);\n"
    "}\n";

/* Appended to ribbon_expand.glsl (whose main is renamed): the per-strand
   colour and 3D-colour x come from two more texture buffers, the fade from
   t, so both paths feed the fragment shader the same values; a ribbon
   narrower than a pixel is widened as the CPU ribbons are (its other
   side mirrored about the strand point). */
static const char *glm_vs_gpu_tail =
    "\nuniform samplerBuffer u_strand_color; // rgba per strand\n"
    "uniform samplerBuffer u_strand_c3x;     // 3D-colour x per strand\n"
    "uniform vec2 u_alpha;                   // alpha at root, tip\n"
    GLM_COVERAGE_GLSL
    GLM_ROOT_GLSL
    "out vec4 v_color;\n"
    "out vec2 v_c3d;\n"
    "void main() {\n"
    "    ribbon_expand_main();\n"
    "    int s = (gl_VertexID >> 1) / u_points_per_strand;\n"
    "    vec4 c = texelFetch(u_strand_color, s);\n"
    "    float t = v_texcoord.z;\n"
    "    vec4 m = hf_point(gl_VertexID >> 1);\n"
    "    v_root = length(m.xyz - hf_point(s * u_points_per_strand).xyz);\n"
    "    float cov = min_width(v_position, 2.0 * m.xyz - v_position);\n"
    "    gl_Position = hair_clip(v_position, m.w);\n"
    "    v_color = vec4(c.rgb, c.a * mix(u_alpha.x, u_alpha.y, t) * cov);\n"
    "    v_c3d = vec2(texelFetch(u_strand_c3x, s).r, t);\n"
    "}\n";

/* The hair's fragment shader and the self-shadowing it shares with the
   body: examples/hair_shading.glsl (--shading-shader; the web page
   builds the same file in), read at run time and put after a prelude,
   "#version 330 core" for the hair; the body's with
   HAIR_SHADING_SHADOW_ONLY defined, between its declarations and its
   main(). Returns malloc'd pre + text + post, or NULL. */
static char *glm_shading_source(const char *pre, const char *text,
                                const char *post)
{
    char *out = (char *)malloc(strlen(pre) + strlen(text) + strlen(post) + 1);
    if (out) {
        strcpy(out, pre);
        strcat(out, text);
        strcat(out, post);
    }
    return out;
}

static const char *glm_vs_head =
    "#version 330 core\n"
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

/* Skin, with the scalp painted in a dark hair colour where the density
   map has hair (u_scalp_on: on the grown triangles), as games do, so gaps
   between ribbons do not show skin; shadowed by the hair (hair_shadow:
   examples/hair_shading.glsl between these two, glm_shading_source). */
static const char *glm_fs_head_decls =
    "#version 330 core\n"
    "#define HAIR_SHADING_SHADOW_ONLY\n"
    "in vec3 v_position, v_normal;\n"
    "in vec2 v_uv;\n"
    "uniform sampler2D u_density;\n"
    "uniform vec3 u_light_dir, u_light_color, u_ambient, u_scalp;\n"
    "uniform float u_scalp_on;\n";
static const char *glm_fs_head_main =
    "out vec4 o_color;\n"
    "void main() {\n"
    "    vec3 n = normalize(v_normal);\n"
    "    vec3 skin = pow(vec3(0.85, 0.66, 0.55), vec3(2.2));\n"
    "    float d = u_scalp_on * smoothstep(0.1, 0.6, texture(u_density, v_uv).r);\n"
    "    vec3 albedo = mix(skin, u_scalp, d);\n"
    "    float lit = max(dot(n, u_light_dir), 0.0);\n"
    "    if (lit > 0.0) lit *= hair_shadow(v_position);\n"
    "    vec3 c = albedo * (u_ambient + u_light_color * lit);\n"
    "    o_color = vec4(pow(c, vec3(1.0 / 2.2)), 1.0);\n"
    "}\n";

static const char *glm_vs_line =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a_pos;\n"
    "uniform mat4 u_view_proj;\n"
    "void main() { gl_Position = u_view_proj * vec4(a_pos, 1.0); }\n";
/* The shadow pass writes depth only. */
static const char *glm_fs_depth =
    "#version 330 core\n"
    "void main() {}\n";

/* The deep opacity pass, drawn with additive blending (alpha: the
   minimum) into an RGBA16F target cleared to (0, 0, 0, 1): each hair
   fragment adds its opacity, its alpha times the fraction of a texel the
   strand covers, to the layer its depth falls in past z0 (the depth
   pass's nearest hair or skin at this texel); beyond the last layer's end
   it goes into the last. */
static const char *glm_fs_opacity_hair =
    "#version 330 core\n"
    "in vec4 v_color;\n"
    GLM_ROOT_FADE_GLSL
    "uniform sampler2D u_shadow;\n"
    "uniform float u_shadow_depth, u_opacity_texel;\n"
    "uniform vec3 u_layers;\n"
    "out vec4 o_color;\n"
    "void main() {\n"
    "    float z0 = texelFetch(u_shadow, ivec2(gl_FragCoord.xy), 0).r;\n"
    "    float d = (gl_FragCoord.z - z0) * u_shadow_depth;\n"
    "    vec3 k = d < u_layers.x ? vec3(1.0, 0.0, 0.0)\n"
    "           : d < u_layers.y ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0);\n"
    "    o_color = vec4(k * v_color.a * root_fade() * u_opacity_texel, 1.0);\n"
    "}\n";

/* ... and the body: no opacity, its depth into alpha (the minimum). */
static const char *glm_fs_opacity_body =
    "#version 330 core\n"
    "out vec4 o_color;\n"
    "void main() { o_color = vec4(0.0, 0.0, 0.0, gl_FragCoord.z); }\n";

/* Weighted blended OIT's resolve: a triangle over the screen; the
   accumulated colour over the weights' sum, over what is there by the
   revealage (accum.a: the product of 1 - alpha). Per sample, then
   averaged, where the targets are multisampled (GLM_OIT_MS). */
static const char *glm_vs_screen =
    "#version 330 core\n"
    "void main() {\n"
    "    vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
    "    gl_Position = vec4(p, 0.0, 1.0);\n"
    "}\n";
static const char *glm_fs_oit =
    "#if GLM_OIT_MS\n"
    "uniform sampler2DMS u_accum, u_weight;\n"
    "#else\n"
    "uniform sampler2D u_accum, u_weight;\n"
    "#endif\n"
    "uniform int u_samples;\n"
    "out vec4 o_color;\n"
    "void main() {\n"
    "    ivec2 p = ivec2(gl_FragCoord.xy);\n"
    "    vec3 c = vec3(0.0);\n"
    "    float r = 0.0;\n"
    "    for (int i = 0; i < u_samples; ++i) {\n"
    "        vec4 a = texelFetch(u_accum, p, i);\n"
    "        float w = texelFetch(u_weight, p, i).r;\n"
    "        c += a.rgb / max(w, 1e-20) * (1.0 - a.a);\n"
    "        r += a.a;\n"
    "    }\n"
    "    r /= float(u_samples);\n"
    "    if (r >= 1.0) discard;   // no hair here\n"
    "    o_color = vec4(c / float(u_samples), 1.0 - r); // premultiplied\n"
    "}\n";

static const char *glm_fs_line =
    "#version 330 core\n"
    "uniform vec4 u_color;\n"
    "out vec4 o_color;\n"
    "void main() { o_color = u_color; }\n";

/* ribbon_expand.glsl with its main() renamed, then glm_vs_gpu_tail: the
   shipped shader is used as it is (compact: HF_POINTS_COMPACT defined
   after its #version line). Returns malloc'd source or NULL. */
static char *glm_gpu_vs_source(const char *path, int compact)
{
    char *src = glc_read_text_file(path), *at, *ver, *out;
    size_t n;
    const char *from = "void main()", *to = "void ribbon_expand_main()";
    const char *def = compact ? "#define HF_POINTS_COMPACT 1\n" : "";
    if (!src) return NULL;
    at = strstr(src, from);
    ver = strncmp(src, "#version", 8) ? strstr(src, "\n#version") : src;
    if (!at || !ver || ver > at || !strchr(ver + 1, '\n')) {
        fprintf(stderr, "gl_marschner: no #version line and main() in %s\n",
                path);
        free(src);
        return NULL;
    }
    ver = strchr(ver + 1, '\n') + 1; /* after the #version line */
    n = strlen(src) + strlen(def) + strlen(to) + strlen(glm_vs_gpu_tail) + 1;
    out = (char *)malloc(n);
    if (out) {
        memcpy(out, src, (size_t)(ver - src));
        strcpy(out + (ver - src), def);
        strncat(out, ver, (size_t)(at - ver));
        strcat(out, to);
        strcat(out, at + strlen(from));
        strcat(out, glm_vs_gpu_tail);
    }
    free(src);
    return out;
}

/* ---- scene: maps, motion, colliders, camera ------------------------------ */

/* The 3D-colour index map: soft streaks around the head (x of the ramp). */
static void glm_index_map(unsigned char *px, int w, int h)
{
    int x, y;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double u = (x + 0.5) / w, v = (y + 0.5) / h;
            double s = 0.5 + 0.5 * sin(u * 2.0 * GLM_PI * 5.0 + v * 4.0) *
                                 cos(u * 2.0 * GLM_PI * 2.0 - v * 3.0);
            px[y * w + x] = (unsigned char)(255.0 * s + 0.5);
        }
}

/* The ramp: x picks a natural shade (dark brown .. honey blonde), y = t
   along the strand; the last third of each strand is dyed (violet to
   pink). 8-bit sRGB, as an artist would paint it. */
static void glm_ramp(unsigned char *rgba, int w, int h)
{
    static const float dark[3] = {0.20f, 0.12f, 0.07f},
                       blond[3] = {0.80f, 0.62f, 0.36f},
                       dye0[3] = {0.45f, 0.16f, 0.70f},
                       dye1[3] = {0.98f, 0.35f, 0.60f};
    int x, y, k;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            float u = (x + 0.5f) / (float)w, t = (y + 0.5f) / (float)h;
            float dye = (t - 0.6f) / 0.25f;
            unsigned char *p = rgba + 4 * (y * w + x);
            dye = dye < 0 ? 0 : dye > 1 ? 1 : dye;
            dye = dye * dye * (3 - 2 * dye);
            for (k = 0; k < 3; ++k) {
                float nat = dark[k] + (blond[k] - dark[k]) * u;
                float dyed = dye0[k] + (dye1[k] - dye0[k]) * u;
                float c = (nat * (0.85f + 0.15f * t)) * (1 - dye) + dyed * dye;
                p[k] = (unsigned char)(255.0f * (c > 1 ? 1 : c) + 0.5f);
            }
            p[3] = 255;
        }
}

/* Colliders in head space, moved by the pose: the skull (the drawn
   sphere: the 2 mm collision margin keeps hair lying on the scalp off its
   flat triangles), the neck (it overlaps the underside of the head, so the
   roots there sit inside it) and the shoulders. */
static void glm_head_colliders(const float m[12], hf_collider *col)
{
    static const float a[3][3] = {{0, 0, 0}, {0, -0.06f, -0.01f},
                                  {-0.19f, -0.25f, -0.01f}},
                       b[3][3] = {{0, 0, 0}, {0, -0.21f, -0.01f},
                                  {0.19f, -0.25f, -0.01f}};
    static const float r[3] = {GLM_HEAD_R, 0.05f, 0.065f};
    int i;
    for (i = 0; i < 3; ++i) {
        memset(&col[i], 0, sizeof col[i]);
        col[i].type = i == 0 ? HF_COLLIDER_SPHERE : HF_COLLIDER_CAPSULE;
        hm_xform(m, a[i], 1.0f, col[i].a);
        hm_xform(m, b[i], 1.0f, col[i].b);
        col[i].radius = r[i];
    }
}

/* Line segments of a capsule (a sphere when a == b): meridians, parallels,
   and the side lines. Writes 6 floats per segment, returns the count. */
static int glm_capsule_lines(const hf_collider *c, float *out)
{
    int n = 0, i, k, cap;
    float axis[3], e1[3], e2[3], len;
    const float *end[2];
    end[0] = c->a;
    end[1] = c->type == HF_COLLIDER_CAPSULE ? c->b : c->a;
    for (k = 0; k < 3; ++k) axis[k] = end[1][k] - end[0][k];
    len = sqrtf(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (len < 1e-6f) { axis[0] = 0; axis[1] = 1; axis[2] = 0; }
    else for (k = 0; k < 3; ++k) axis[k] /= len;
    /* a basis around the axis */
    e1[0] = axis[1]; e1[1] = -axis[0]; e1[2] = 0;
    if (fabsf(axis[2]) > 0.9f) { e1[0] = 0; e1[1] = axis[2]; e1[2] = -axis[1]; }
    {
        float l = sqrtf(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        for (k = 0; k < 3; ++k) e1[k] /= l;
    }
    e2[0] = axis[1] * e1[2] - axis[2] * e1[1];
    e2[1] = axis[2] * e1[0] - axis[0] * e1[2];
    e2[2] = axis[0] * e1[1] - axis[1] * e1[0];
    /* each hemisphere: 8 meridian half-arcs and 3 parallels, 16 steps */
    for (cap = 0; cap < 2; ++cap) {
        float sgn = cap ? 1.0f : -1.0f;
        int m, step;
        for (m = 0; m < 8; ++m)
            for (step = 0; step < 8; ++step) {
                float ph = 2 * GLM_PI * m / 8;
                for (i = 0; i < 2; ++i) {
                    float th = GLM_PI * 0.5f * (step + i) / 8; /* from equator */
                    for (k = 0; k < 3; ++k)
                        out[6 * n + 3 * i + k] =
                            end[cap][k] + c->radius *
                            (cosf(th) * (cosf(ph) * e1[k] + sinf(ph) * e2[k]) +
                             sgn * sinf(th) * axis[k]);
                }
                ++n;
            }
        for (m = 0; m < 3; ++m)
            for (step = 0; step < 16; ++step) {
                float th = GLM_PI * 0.5f * m / 3;
                for (i = 0; i < 2; ++i) {
                    float ph = 2 * GLM_PI * (step + i) / 16;
                    for (k = 0; k < 3; ++k)
                        out[6 * n + 3 * i + k] =
                            end[cap][k] + c->radius *
                            (cosf(th) * (cosf(ph) * e1[k] + sinf(ph) * e2[k]) +
                             sgn * sinf(th) * axis[k]);
                }
                ++n;
            }
    }
    if (c->type == HF_COLLIDER_CAPSULE)
        for (i = 0; i < 8; ++i) {
            float ph = 2 * GLM_PI * i / 8;
            for (k = 0; k < 3; ++k) {
                float rim = c->radius * (cosf(ph) * e1[k] + sinf(ph) * e2[k]);
                out[6 * n + k] = end[0][k] + rim;
                out[6 * n + 3 + k] = end[1][k] + rim;
            }
            ++n;
        }
    return n;
}
#define GLM_LINES_PER_COLLIDER (2 * (64 + 48) + 8)

/* Camera on an orbit around the grown mesh (a mesh's camera follows
   its grown part's centroid); LOD from its distance. */
static void glm_camera(glm_app *a)
{
    float proj[16], view[16];
    const float up[3] = {0, 1, 0};
    float az = a->o.azimuth * GLM_PI / 180.0f,
          el = a->o.elevation * GLM_PI / 180.0f;
    int k;
    for (k = 0; k < 3; ++k) a->target[k] = a->target0[k];
    if (a->ch.vertex_count > 0 && a->skin) {
        double c[3] = {0, 0, 0};
        int i;
        for (i = a->grow_first; i < a->grow_first + a->grow_count; ++i)
            for (k = 0; k < 3; ++k) c[k] += a->skin[i].pos[k];
        for (k = 0; k < 3; ++k)
            a->target[k] += (float)(c[k] / a->grow_count) - a->centroid0[k];
    }
    a->eye[0] = a->target[0] + a->o.distance * sinf(az) * cosf(el);
    a->eye[1] = a->target[1] + a->o.distance * sinf(el);
    a->eye[2] = a->target[2] + a->o.distance * cosf(az) * cosf(el);
    glc_mat4_perspective(proj, 0.7f, (float)a->o.width / (float)a->o.height,
                         0.036f * a->frame_dist, 180.0f * a->frame_dist);
    glc_mat4_look_at(view, a->eye, a->target, up);
    glc_mat4_mul(a->view_proj, proj, view);
}


/* ---- the body: the built-in head or a mesh file ------------------------- */

/* A map read from a PNG (anything stb_image reads). hf_map's row 0 is
   v = 0 and a PNG stores its top row first: the rows are flipped on load,
   so the PNG's top row is v = 1, as in OpenGL and the mesh loaders. */
static int glm_load_map(const char *path, int channels, unsigned char **px,
                        hf_map *map)
{
    int w, h, n;
    stbi_set_flip_vertically_on_load(1);
    *px = stbi_load(path, &w, &h, &n, channels);
    if (!*px) {
        fprintf(stderr, "gl_marschner: cannot read %s: %s\n", path,
                stbi_failure_reason());
        return 0;
    }
    memset(map, 0, sizeof *map);
    map->data = *px;
    map->width = w;
    map->height = h;
    map->channels = channels;
    return 1;
}

/* The built-in head: a sphere of radius 0.1 with its own maps. */
static int glm_load_head(glm_app *a)
{
    hm_mesh head;
    int i;
    if (!hm_sphere(24, 32, GLM_HEAD_R, &head)) return 0;
    a->nv = a->grow_count = head.vertex_count;
    a->nt = a->nt_grown = head.triangle_count;
    a->anim = -1;
    a->rest = (ch_vertex *)malloc(sizeof(ch_vertex) * (size_t)a->nv);
    a->body_idx = (uint32_t *)malloc(12u * (size_t)a->nt);
    a->grow_idx = (uint32_t *)malloc(12u * (size_t)a->nt);
    if (!a->rest || !a->body_idx || !a->grow_idx) {
        hm_free(&head);
        return 0;
    }
    for (i = 0; i < a->nv; ++i) {
        memcpy(a->rest[i].pos, head.vertices[i].pos, sizeof a->rest[i].pos);
        memcpy(a->rest[i].normal, head.vertices[i].normal,
               sizeof a->rest[i].normal);
        memcpy(a->rest[i].uv, head.vertices[i].uv, sizeof a->rest[i].uv);
    }
    memcpy(a->body_idx, head.indices, 12u * (size_t)a->nt);
    memcpy(a->grow_idx, head.indices, 12u * (size_t)a->nt);
    hm_free(&head);
    a->max_col = GLM_HEAD_COLLIDERS;
    return 1;
}

/* Is `name` one of the comma-separated names in `list`? */
static int glm_listed(const char *list, const char *name)
{
    size_t n = strlen(name);
    const char *s = list;
    while (*s) {
        const char *e = strchr(s, ',');
        size_t len = e ? (size_t)(e - s) : strlen(s);
        if (len == n && !strncmp(s, name, n)) return 1;
        s += len + (e ? 1 : 0);
    }
    return 0;
}

/* A mesh file: the first pose of the animation is the rest pose; the
   grown parts (--grow-on, default all) come first in the drawn triangles
   and make the grown mesh, over the vertex range they span. */
static int glm_load_mesh(glm_app *a)
{
    const glm_options *o = &a->o;
    char err[512];
    int p, t, k, lo = INT_MAX, hi = 0, any, n = 0;
    ch_character *c = &a->ch;
    if (!ch_load(c, o->mesh, o->unit, err, sizeof err)) {
        fprintf(stderr, "gl_marschner: %s\n", err);
        return 0;
    }
    a->anim = ch_find_animation(c, o->anim);
    if (o->anim && a->anim < 0) {
        fprintf(stderr, "gl_marschner: %s has no animation '%s'; it has:",
                o->mesh, o->anim);
        for (k = 0; k < c->animation_count; ++k)
            fprintf(stderr, " %s", c->animation_name[k]);
        fprintf(stderr, "%s\n", c->animation_count ? "" : " none");
        return 0;
    }
    if (o->grow_on) { /* every name must be a part */
        const char *s = o->grow_on;
        while (*s) {
            const char *e = strchr(s, ',');
            size_t len = e ? (size_t)(e - s) : strlen(s);
            for (p = 0; p < c->part_count; ++p)
                if (strlen(c->parts[p].name) == len &&
                    !strncmp(c->parts[p].name, s, len)) break;
            if (p == c->part_count) {
                fprintf(stderr, "gl_marschner: --grow-on: %s has no mesh "
                        "'%.*s'; it has:", o->mesh, (int)len, s);
                for (p = 0; p < c->part_count; ++p)
                    fprintf(stderr, " %s", c->parts[p].name);
                fprintf(stderr, "\n");
                return 0;
            }
            s += len + (e ? 1 : 0);
        }
    }
    a->nv = c->vertex_count;
    a->nt = c->triangle_count;
    a->rest = (ch_vertex *)malloc(sizeof(ch_vertex) * (size_t)a->nv);
    a->body_idx = (uint32_t *)malloc(12u * (size_t)a->nt);
    a->grow_idx = (uint32_t *)malloc(12u * (size_t)a->nt);
    a->all_col = (hf_collider *)calloc((size_t)c->capsule_count + 1,
                                       sizeof(hf_collider));
    a->col_keep = (int *)calloc((size_t)c->capsule_count + 1, sizeof(int));
    if (!a->rest || !a->body_idx || !a->grow_idx || !a->all_col ||
        !a->col_keep)
        return 0;
    ch_pose(c, a->anim, 0.0, a->rest, a->all_col);
    for (p = 0; p < c->part_count; ++p) {
        const ch_part *pt = &c->parts[p];
        if (o->grow_on && !glm_listed(o->grow_on, pt->name)) continue;
        if ((o->density_path || o->length_path || o->color_path) &&
            !pt->has_uvs) {
            fprintf(stderr, "gl_marschner: %s: mesh '%s' has no texture "
                    "coordinates, so the maps cannot be read on it\n",
                    o->mesh, pt->name);
            return 0;
        }
        if (pt->first_vertex < lo) lo = pt->first_vertex;
        if (pt->first_vertex + pt->vertex_count > hi)
            hi = pt->first_vertex + pt->vertex_count;
    }
    a->grow_first = lo;
    a->grow_count = hi - lo;
    /* a grown part (hair on a head) gets a sphere inside it as well, so
       draped hair rests on its crown (all_col has room for it) */
    if (o->grow_on && ch_fit_sphere(c, lo, hi - lo))
        ch_pose(c, a->anim, 0.0, a->rest, a->all_col);
    /* the grown triangles first, then the rest */
    for (any = 0; any < 2; ++any)
        for (p = 0; p < c->part_count; ++p) {
            const ch_part *pt = &c->parts[p];
            int grown = !o->grow_on || glm_listed(o->grow_on, pt->name);
            if (grown == any) continue;
            for (t = pt->first_triangle;
                 t < pt->first_triangle + pt->triangle_count; ++t, ++n)
                for (k = 0; k < 3; ++k) {
                    uint32_t v = c->indices[3 * (size_t)t + (size_t)k];
                    a->body_idx[3 * (size_t)n + (size_t)k] = v;
                    if (!any)
                        a->grow_idx[3 * (size_t)n + (size_t)k] = v - (uint32_t)lo;
                }
            if (!any) a->nt_grown = n;
        }
    a->max_col = c->capsule_count;
    return 1;
}

static float glm_polyline_length(const float *p, int n)
{
    float len = 0.0f;
    int i;
    for (i = 1; i < n; ++i) {
        float dx = p[3 * i] - p[3 * i - 3], dy = p[3 * i + 1] - p[3 * i - 2],
              dz = p[3 * i + 2] - p[3 * i - 1];
        len += sqrtf(dx * dx + dy * dy + dz * dz);
    }
    return len;
}

/* Size, framing, hair length, ribbon width, shadow strength and a mesh's
   colliders from the body at rest, so that a model in centimetres (read
   as metres by ch_load) gives the picture it gives in metres. */
static void glm_measure(glm_app *a)
{
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    double area = 0.0, c[3] = {0, 0, 0};
    int i, k, n = 0;
    /* the grown part's centroid (the camera follows it); the box of the
       grown part, or of a groom's points */
    for (i = a->grow_first; i < a->grow_first + a->grow_count; ++i, ++n)
        for (k = 0; k < 3; ++k) {
            float x = a->rest[i].pos[k];
            if (!a->groom && x < lo[k]) lo[k] = x;
            if (!a->groom && x > hi[k]) hi[k] = x;
            c[k] += x;
        }
    if (a->groom) {
        const float *p = a->curves.xyz;
        for (i = 0; i < a->curves.total; ++i)
            for (k = 0; k < 3; ++k) {
                if (p[3 * i + k] < lo[k]) lo[k] = p[3 * i + k];
                if (p[3 * i + k] > hi[k]) hi[k] = p[3 * i + k];
            }
    }
    a->size = sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) +
                    (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (!(a->size > 0.0f)) a->size = 1.0f;
    a->frame_dist = GLM_FRAME_DIAG * a->size;
    for (k = 0; k < 3; ++k) {
        a->target0[k] = 0.5f * (lo[k] + hi[k]);
        a->centroid0[k] = (float)(c[k] / n);
    }
    if (a->ch.vertex_count == 0) /* the head: a little below the middle */
        a->target0[1] -= 0.0866f * a->size;
    a->hair_len = a->o.hair_length > 0.0f ? a->o.hair_length
                : a->ch.vertex_count > 0 ? 0.05f * a->size : 0.14f;
    if (a->curves.count > 0) { /* guide curves: the longest of them */
        const float *p = a->curves.xyz;
        float longest = 0.0f;
        for (i = 0; i < a->curves.count; ++i) {
            float len = glm_polyline_length(p, a->curves.points[i]);
            if (len > longest) longest = len;
            p += 3 * a->curves.points[i];
        }
        a->hair_len = longest;
    }
    /* the hair's area: triangles weighted by the density at their corners;
       for a groom, about half the surface of its roots' box */
    if (a->groom) {
        float rl[3] = {1e30f, 1e30f, 1e30f}, rh[3] = {-1e30f, -1e30f, -1e30f};
        const float *p = a->curves.xyz;
        for (i = 0; i < a->curves.count; p += 3 * a->curves.points[i++])
            for (k = 0; k < 3; ++k) {
                if (p[k] < rl[k]) rl[k] = p[k];
                if (p[k] > rh[k]) rh[k] = p[k];
            }
        area = (double)(rh[0] - rl[0]) * (rh[1] - rl[1]) +
               (double)(rh[1] - rl[1]) * (rh[2] - rl[2]) +
               (double)(rh[2] - rl[2]) * (rh[0] - rl[0]);
    }
    for (i = 0; i < (a->groom ? 0 : a->nt_grown); ++i) {
        const float *p0 = a->rest[a->grow_first + a->grow_idx[3 * i]].pos,
                    *p1 = a->rest[a->grow_first + a->grow_idx[3 * i + 1]].pos,
                    *p2 = a->rest[a->grow_first + a->grow_idx[3 * i + 2]].pos;
        float e1[3], e2[3], n[3], d = 1.0f;
        for (k = 0; k < 3; ++k) { e1[k] = p1[k] - p0[k]; e2[k] = p2[k] - p0[k]; }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        if (a->have_density) {
            float v[4];
            d = 0.0f;
            for (k = 0; k < 3; ++k) {
                const float *uv = a->rest[a->grow_first + a->grow_idx[3 * i + k]].uv;
                if (hf_map_sample(&a->density, uv[0], uv[1], v) == HF_OK)
                    d += v[0] / 3.0f;
            }
        }
        area += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * d;
    }
    /* ribbons two thirds of the mean strand spacing wide: the hair covers
       the skin without reading as a sheet (1.1 mm on the head) */
    a->hair_area = area;
    a->root_width = GLM_WIDTH_SPACING * sqrtf((float)(area / a->o.strands));
    if (!(a->root_width > 0.0f)) a->root_width = 0.001f * a->size;
    /* light falls to exp(-5) through a hair length of hair */
    a->shadow_k = 5.0f / a->hair_len;
    for (k = 0; k < 3; ++k) { lo[k] = 1e30f; hi[k] = -1e30f; }
    for (i = 0; i < a->nv; ++i)
        for (k = 0; k < 3; ++k) {
            if (a->rest[i].pos[k] < lo[k]) lo[k] = a->rest[i].pos[k];
            if (a->rest[i].pos[k] > hi[k]) hi[k] = a->rest[i].pos[k];
        }
    a->ch_diag = sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) +
                       (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    /* a mesh's colliders: the bones' capsules that hair can reach (near
       the grown part's box at rest), leaving out the tiny ones (fingers,
       lips) */
    a->ncol = a->ch.vertex_count > 0 ? 0 : GLM_HEAD_COLLIDERS;
    if (a->ch.vertex_count > 0) {
        float glo[3], ghi[3];
        for (k = 0; k < 3; ++k) { glo[k] = 1e30f; ghi[k] = -1e30f; }
        for (i = a->grow_first; i < a->grow_first + a->grow_count; ++i)
            for (k = 0; k < 3; ++k) {
                const float *q = a->rest[i].pos;
                if (q[k] < glo[k]) glo[k] = q[k];
                if (q[k] > ghi[k]) ghi[k] = q[k];
            }
        for (i = 0; i < a->ch.capsule_count; ++i) {
            const hf_collider *cp = &a->all_col[i];
            float best = 1e30f;
            int j;
            if (cp->radius < 0.004f * a->ch_diag) continue;
            for (j = 0; j <= 8; ++j) { /* points along the axis to the box */
                float d2 = 0.0f;
                for (k = 0; k < 3; ++k) {
                    float x = cp->a[k] + (cp->b[k] - cp->a[k]) * (float)j / 8.0f;
                    float e = x < glo[k] ? glo[k] - x : x > ghi[k] ? x - ghi[k] : 0.0f;
                    d2 += e * e;
                }
                if (d2 < best) best = d2;
            }
            if (sqrtf(best) <= cp->radius + a->hair_len)
                a->col_keep[a->ncol++] = i;
        }
    }
}

/* ---- GL setup ------------------------------------------------------------ */

static GLuint glm_texture2d(GLenum internal, int w, int h, GLenum format,
                            GLenum type, const void *data, GLenum wrap)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, type, data);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, (GLint)wrap);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, (GLint)wrap);
    return t;
}

/* A texture buffer over a new buffer object of `bytes` bytes. */
static void glm_tbo(GLuint *buf, GLuint *tex, GLenum format, size_t bytes,
                    const void *data, GLenum usage)
{
    glGenBuffers(1, buf);
    glBindBuffer(GL_TEXTURE_BUFFER, *buf);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)bytes, data, usage);
    glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_BUFFER, *tex);
    glTexBuffer(GL_TEXTURE_BUFFER, format, *buf);
}

static void glm_ribbon_view(const glm_app *a, hf_ribbon_params *v)
{
    memset(v, 0, sizeof *v);
    memcpy(v->eye, a->eye, sizeof v->eye);
    v->root_width = a->root_width; /* from the strand spacing */
    v->tip_width = 0.227f * a->root_width;
    v->taper_power = 1.5f;   /* keep the width longer, then thin quickly */
    v->alpha_root = 1.0f;
    v->alpha_tip = 0.2f;     /* tips fade */
}

/* Weighted blended OIT's targets, at the output's size and sample count,
   on the output's depth buffer (the body's depth tests the hair; the
   hair writes none). Core GL 3.2 (float colour targets, blending into
   them, multisampled textures); where the driver cannot make them,
   a->oit_ok stays 0 and the hair is blended in draw order, as with
   --no-oit. */
static void glm_oit_init(glm_app *a)
{
    static const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    GLint type = 0, depth = 0, samples = 0;
    const int w = glc_width(), h = glc_height();
    char fs[2048];
    int k;
    glBindFramebuffer(GL_FRAMEBUFFER, glc_target_fbo());
    glGetFramebufferAttachmentParameteriv(
        GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
        GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    glGetFramebufferAttachmentParameteriv(
        GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
        GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &depth);
    if (type != GL_RENDERBUFFER || depth == 0) {
        printf("gl_marschner: no order-independent transparency (the "
               "output has no depth renderbuffer to share); the hair is "
               "blended in draw order\n");
        return;
    }
    glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)depth);
    glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES,
                                 &samples);
    a->oit_samples = samples > 1 ? samples : 1;
    glGenTextures(1, &a->tex_accum);
    glGenTextures(1, &a->tex_weight);
    for (k = 0; k < 2; ++k) {
        const GLuint t = k ? a->tex_weight : a->tex_accum;
        const GLenum f = k ? GL_R32F : GL_RGBA32F;
        if (samples > 1) {
            glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t);
            glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, f, w,
                                    h, GL_TRUE);
        } else {
            glBindTexture(GL_TEXTURE_2D, t);
            glTexImage2D(GL_TEXTURE_2D, 0, (GLint)f, w, h, 0,
                         k ? GL_RED : GL_RGBA, GL_FLOAT, NULL);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
    }
    glGenFramebuffers(1, &a->oit_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, a->oit_fbo);
    for (k = 0; k < 2; ++k)
        glFramebufferTexture2D(GL_FRAMEBUFFER, bufs[k],
                               samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE
                                           : GL_TEXTURE_2D,
                               k ? a->tex_weight : a->tex_accum, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
                              GL_RENDERBUFFER, (GLuint)depth);
    glDrawBuffers(2, bufs);
    snprintf(fs, sizeof fs, "#version 330 core\n#define GLM_OIT_MS %d\n%s",
             samples > 1, glm_fs_oit);
    a->prog_oit = glc_program(glm_vs_screen, fs, "OIT resolve");
    glGenVertexArrays(1, &a->vao_empty);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
        !a->prog_oit || !glc_check_gl("OIT targets")) {
        printf("gl_marschner: no order-independent transparency (its "
               "targets cannot be made here); the hair is blended in draw "
               "order\n");
        return;
    }
    a->oit_ok = 1;
}

/* The dual scattering tables' size a side (about 0.1 s to bake at 256). */
#define GLM_DUAL_SIZE 64

/* glm_init's phases, in the order they run. Each returns 1, or 0 with a
   message (those that cannot fail return nothing); a->o holds the options
   (only its distance changes, in glm_init_curves). */

/* The body (the mesh file or the built-in head) and its skinning,
   collider and index-map arrays. */
static int glm_init_body(glm_app *a)
{
    const glm_options *o = &a->o;
    if (!(o->mesh ? glm_load_mesh(a) : glm_load_head(a))) return 0;
    a->skin = (ch_vertex *)malloc(sizeof(ch_vertex) * (size_t)a->nv);
    a->col = (hf_collider *)calloc((size_t)a->max_col + 1, sizeof(hf_collider));
    a->index_px = (unsigned char *)malloc(128 * 128);
    if (!a->skin || !a->col || !a->index_px) return 0;
    memcpy(a->skin, a->rest, sizeof(ch_vertex) * (size_t)a->nv);
    return 1;
}

/* The maps: from files, else the head's own, else none (density and
   length 1) and one colour; the 3D-colour index map always. */
static int glm_init_maps(glm_app *a)
{
    const glm_options *o = &a->o;
    int i;
    if (o->density_path) {
        if (!glm_load_map(o->density_path, 1, &a->density_px, &a->density))
            return 0;
    } else if (!o->mesh) {
        a->density_px = (unsigned char *)malloc(256 * 256);
        if (!a->density_px) return 0;
        hm_hairline_density(a->density_px, 256, 256);
        a->density.data = a->density_px;
        a->density.width = a->density.height = 256;
        a->density.channels = 1;
    }
    a->have_density = a->density_px != NULL;
    if (o->length_path) {
        if (!glm_load_map(o->length_path, 1, &a->length_px, &a->length))
            return 0;
    } else if (!o->mesh) {
        a->length_px = (unsigned char *)malloc(256 * 256);
        if (!a->length_px) return 0;
        hm_bangs_length(a->length_px, 256, 256);
        a->length.data = a->length_px;
        a->length.width = a->length.height = 256;
        a->length.channels = 1;
    }
    a->have_length = a->length_px != NULL;
    if (o->color_path) {
        if (!glm_load_map(o->color_path, 3, &a->color_px, &a->color)) return 0;
    } else {
        int n = o->mesh ? 1 : 64;
        a->color_px = (unsigned char *)malloc((size_t)(n * n * 3));
        if (!a->color_px) return 0;
        if (o->mesh)
            for (i = 0; i < 3; ++i)
                a->color_px[i] = (unsigned char)(255.0f * o->hair_color[i] + 0.5f);
        else
            hm_hair_color(a->color_px, 64, 64);
        a->color.data = a->color_px;
        a->color.width = a->color.height = n;
        a->color.channels = 3;
    }
    glm_index_map(a->index_px, 128, 128);
    a->index.data = a->index_px;
    a->index.width = a->index.height = 128;
    a->index.channels = 1;
    return 1;
}

/* The guide curves or the groom, when a file gives them, then the
   measures (size, hair length, camera distance) that take them in. */
static int glm_init_curves(glm_app *a)
{
    const glm_options *o = &a->o;
    if (o->guides_path && o->groom_path) {
        fprintf(stderr, "gl_marschner: give --guides or --groom, not both\n");
        return 0;
    }
    if (o->guides_path || o->groom_path) {
        char err[700];
        a->groom = o->groom_path != NULL;
        if (!cv_read(a->groom ? o->groom_path : o->guides_path, &a->curves, err,
                     sizeof err)) {
            fprintf(stderr, "gl_marschner: --%s %s\n",
                    a->groom ? "groom" : "guides", err);
            return 0;
        }
        /* in the mesh file's units, like the mesh */
        if (a->ch.vertex_count > 0) cv_scale(&a->curves, a->ch.unit);
    }
    glm_measure(a);
    if (a->o.distance <= 0.0f) a->o.distance = a->frame_dist;
    return 1;
}

/* --comb: each grown vertex's growth direction, the normal tilted towards
   the comb's part along the surface, tan(tilt) = the comb's length, the
   same everywhere; the normal where the comb is the normal. */
static int glm_comb_directions(glm_app *a)
{
    const float *comb = a->o.comb;
    float len = sqrtf(comb[0] * comb[0] + comb[1] * comb[1] +
                      comb[2] * comb[2]);
    int i;
    a->comb_dir = (float *)malloc(sizeof(float) * 3u * (size_t)a->grow_count);
    if (!a->comb_dir) return 0;
    for (i = 0; i < a->grow_count; ++i) {
        const float *n = a->rest[a->grow_first + i].normal;
        float cn = comb[0] * n[0] + comb[1] * n[1] + comb[2] * n[2];
        float t[3], tl;
        int k;
        for (k = 0; k < 3; ++k) t[k] = comb[k] - cn * n[k];
        tl = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        for (k = 0; k < 3; ++k)
            a->comb_dir[3 * i + k] =
                n[k] + (tl > 1e-6f * len ? len * t[k] / tl : 0.0f);
    }
    return 1;
}

/* The growth description: the grown vertex range at rest, the maps, the
   comb, the guide curves, the strands' shape and the guide target. */
static int glm_fur_desc(glm_app *a, hf_fur_desc *desc)
{
    const glm_options *o = &a->o;
    int i;
    memset(desc, 0, sizeof *desc);
    desc->mesh.positions = a->rest[a->grow_first].pos;
    desc->mesh.position_stride = (int)sizeof(ch_vertex);
    desc->mesh.normals = a->rest[a->grow_first].normal;
    desc->mesh.normal_stride = (int)sizeof(ch_vertex);
    desc->mesh.uvs = a->rest[a->grow_first].uv;
    desc->mesh.uv_stride = (int)sizeof(ch_vertex);
    desc->mesh.vertex_count = a->grow_count;
    desc->mesh.indices = a->grow_idx;
    desc->mesh.triangle_count = a->nt_grown;
    for (i = 0; i < a->grow_count; ++i) { /* the library refuses them */
        const float *n = a->rest[a->grow_first + i].normal;
        if (!(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.0f)) break;
    }
    if (i < a->grow_count) {
        printf("gl_marschner: %s: vertex %d has no normal; the library's "
               "area-weighted normals are used\n", o->mesh ? o->mesh : "mesh",
               i);
        desc->mesh.normals = NULL;
        desc->mesh.normal_stride = 0;
    }
    desc->density_map = a->have_density ? &a->density : NULL;
    desc->length_map = a->have_length ? &a->length : NULL;
    desc->color_map = &a->color;
    desc->color3d_index_map = &a->index;
    if (o->comb[0] != 0.0f || o->comb[1] != 0.0f || o->comb[2] != 0.0f) {
        if (!glm_comb_directions(a)) return 0;
        desc->comb = a->comb_dir;
    }
    if (o->guides_path) {
        desc->guide_curves = a->curves.xyz;
        desc->guide_curve_points = a->curves.points;
        desc->guide_curve_count = a->curves.count;
    }
    desc->curl_radius = o->curl[0];
    desc->curl_turns = o->curl[1];
    desc->wave_amplitude = o->wave[0];
    desc->wave_count = o->wave[1];
    desc->frizz = o->frizz;
    desc->color_variation = o->color_variation;
    desc->width_variation = o->width_variation;
    desc->points_per_strand = 16;
    desc->max_length = a->hair_len;
    desc->total_strands = o->strands;
    desc->sampler = HF_SAMPLER_STRATIFIED;
    desc->seed = 7;
    desc->clump = o->clump[0];
    desc->clump_size = o->clump[1];
    if (!o->mesh && !o->guides) {
        desc->tess_factor = 25000.0f; /* about 2,000 guides on the head */
    } else {
        /* LOD guides to make up the guide target: about one per 1 /
           tess_factor of (density-weighted) area; none when the mesh's
           vertices (the pure guides) are already that many */
        int target = o->guides > 0 ? o->guides : o->strands / 10;
        if (!o->guides && target > 2000) target = 2000;
        if (target > a->grow_count && a->hair_area > 0.0)
            desc->tess_factor =
                (float)((target - a->grow_count) / a->hair_area);
    }
    return 1;
}

/* The ropes' parameters, and the grid of hair-hair interaction in desc. */
static void glm_rope_params(const glm_app *a, hf_rope_params *rp,
                            hf_fur_desc *desc)
{
    const glm_options *o = &a->o;
    hf_rope_params_init(rp);
    /* some local stiffness keeps strands from folding, the root one lifts
       them off the scalp a little; the global (rest-pose) stiffness, 0 by
       default, holds fur up: hair with it looks like a helmet */
    rp->local_stiffness_root = 0.3f;
    rp->local_stiffness_tip = 0.05f;
    rp->root_stiffness = 0.5f;
    rp->global_stiffness_root = o->stiffness;
    rp->global_stiffness_tip = 0.5f * o->stiffness;
    /* hair-hair interaction; 0 on the command line is off */
    rp->volume = o->volume;
    rp->friction = o->friction;
    rp->explicit_zero = (o->volume == 0.0f ? HF_ROPE_ZERO_VOLUME : 0) |
                        (o->friction == 0.0f ? HF_ROPE_ZERO_FRICTION : 0);
    desc->grid_resolution =
        o->volume > 0.0f || o->friction > 0.0f ? o->grid : 0;
    desc->keep_length = o->keep_length;
    desc->rope_params = rp;
}

/* The fur: grown on the mesh, or the groom's own strands (a fraction of
   them simulated); then its info and the skinned mesh the roots follow. */
static int glm_init_fur(glm_app *a)
{
    const glm_options *o = &a->o;
    hf_fur_desc desc;
    hf_rope_params rp;
    hf_diag diag;
    hf_result r;
    int i;
    if (!glm_fur_desc(a, &desc)) return 0;
    glm_rope_params(a, &rp, &desc);
    if (a->groom) {
        hf_groom_desc gd;
        a->groom_rgb = (float *)malloc(sizeof(float) * 3u * (size_t)a->curves.count);
        if (!a->groom_rgb) return 0;
        for (i = 0; i < 3 * a->curves.count; ++i)
            a->groom_rgb[i] = o->hair_color[i % 3]; /* sRGB, as maps */
        memset(&gd, 0, sizeof gd);
        gd.points = a->curves.xyz;
        gd.strand_points = a->curves.points;
        gd.strand_count = a->curves.count;
        gd.colors = a->groom_rgb;
        gd.points_per_strand = 16;
        gd.guide_fraction = o->guide_fraction;
        gd.seed = 7;
        gd.rope_params = &rp;
        gd.grid_resolution = desc.grid_resolution;
        gd.keep_length = desc.keep_length;
        /* on a mesh, the roots follow the skinned grown part */
        gd.scalp = a->ch.vertex_count > 0 ? &desc.mesh : NULL;
        r = hf_fur_create_groom(&gd, &a->fur, &diag);
    } else {
        r = hf_fur_create(&desc, &a->fur, &diag);
    }
    if (r != HF_OK) {
        fprintf(stderr, "gl_marschner: %s\n", diag.message);
        return 0;
    }
    hf_fur_get_info(a->fur, &a->info);
    a->P = a->info.points_per_strand;
    a->skinned = desc.mesh;
    a->skinned.positions = a->skin[a->grow_first].pos;
    if (desc.mesh.normals) a->skinned.normals = a->skin[a->grow_first].normal;
    return 1;
}

/* Two ribbon vertices per strand point, every strand. */
static size_t glm_ribbon_vertices(const glm_app *a)
{
    return 2u * (size_t)a->info.strand_count * (size_t)a->P;
}

/* The CPU-side arrays: each guide's length and root at rest (for the
   stretch figure) and the per-frame vertex and point arrays. */
static int glm_init_arrays(glm_app *a)
{
    const int S = a->info.strand_count;
    const size_t nv = glm_ribbon_vertices(a);
    int i;
    a->rest_len = (float *)malloc(sizeof(float) * (size_t)a->info.guide_count);
    if (!a->rest_len) return 0;
    for (i = 0; i < a->info.guide_count; ++i)
        a->rest_len[i] = glm_polyline_length(a->info.guide_points +
                                             3 * (size_t)i * (size_t)a->P, a->P);
    a->rest_root = (float *)malloc(sizeof(float) * 3u * (size_t)a->info.guide_count);
    if (!a->rest_root) return 0;
    for (i = 0; i < a->info.guide_count; ++i)
        memcpy(a->rest_root + 3 * i,
               a->info.guide_points + 3 * (size_t)i * (size_t)a->P,
               sizeof(float) * 3u);
    a->dyn = (glm_dyn *)malloc(sizeof(glm_dyn) * nv);
    /* zeroed: the pad bytes are uploaded too */
    a->cdyn = (glm_compact *)calloc(nv, sizeof(glm_compact));
    a->points4 = (float *)malloc(sizeof(float) * 4u * (size_t)S * (size_t)a->P);
    a->line_buf = (float *)malloc(sizeof(float) * 6u * (size_t)(a->max_col + 1) *
                                  GLM_LINES_PER_COLLIDER);
    if (!a->dyn || !a->cdyn || !a->points4 || !a->line_buf) return 0;
    return 1;
}

/* The programs: hair, body and lines, their shadow and deep opacity
   variants, and the GPU-expansion ones where its shader is found. */
static int glm_init_programs(glm_app *a)
{
    const glm_options *o = &a->o;
    char *gpu_src = NULL, *text, *fs_hair, *fs_head;
    const char *path = o->expand_shader ? o->expand_shader
                                        : "examples/ribbon_expand.glsl";
    const char *shading = o->shading_shader ? o->shading_shader
                                            : "examples/hair_shading.glsl";
    text = glc_read_text_file(shading);
    if (!text) {
        fprintf(stderr, "gl_marschner: cannot read the hair shader %s; run "
                "from the repository root or pass --shading-shader\n",
                shading);
        return 0;
    }
    fs_hair = glm_shading_source("#version 330 core\n", text, "");
    fs_head = glm_shading_source(glm_fs_head_decls, text, glm_fs_head_main);
    free(text);
    if (!fs_hair || !fs_head) {
        free(fs_hair);
        free(fs_head);
        return 0;
    }
    a->prog_cpu = glc_program(glm_vs_cpu, fs_hair, "hair (CPU ribbons)");
    a->prog_cpu16 = glc_program(glm_vs_cpu16, fs_hair,
                                "hair (compact CPU ribbons)");
    a->prog_head = glc_program(glm_vs_head, fs_head, "head");
    free(fs_head);
    a->prog_line = glc_program(glm_vs_line, glm_fs_line, "lines");
    a->depth_cpu = glc_program(glm_vs_cpu, glm_fs_depth, "shadow (CPU ribbons)");
    a->depth_cpu16 = glc_program(glm_vs_cpu16, glm_fs_depth,
                                 "shadow (compact CPU ribbons)");
    a->depth_head = glc_program(glm_vs_head, glm_fs_depth, "shadow (body)");
    a->opacity_cpu = glc_program(glm_vs_cpu, glm_fs_opacity_hair,
                                 "deep opacity (CPU ribbons)");
    a->opacity_cpu16 = glc_program(glm_vs_cpu16, glm_fs_opacity_hair,
                                   "deep opacity (compact CPU ribbons)");
    a->opacity_head = glc_program(glm_vs_head, glm_fs_opacity_body,
                                  "deep opacity (body)");
    if (!a->prog_cpu || !a->prog_cpu16 || !a->prog_head || !a->prog_line ||
        !a->depth_cpu || !a->depth_cpu16 || !a->depth_head ||
        !a->opacity_cpu || !a->opacity_cpu16 || !a->opacity_head) {
        free(fs_hair);
        return 0;
    }
    gpu_src = glm_gpu_vs_source(path, o->compact);
    if (gpu_src) {
        a->prog_gpu = glc_program(gpu_src, fs_hair, "hair (GPU expansion)");
        a->depth_gpu = glc_program(gpu_src, glm_fs_depth,
                                   "shadow (GPU expansion)");
        a->opacity_gpu = glc_program(gpu_src, glm_fs_opacity_hair,
                                     "deep opacity (GPU expansion)");
        free(gpu_src);
    }
    free(fs_hair);
    if (!a->prog_gpu) {
        fprintf(stderr, "gl_marschner: no GPU-expansion path (%s); run "
                "from the repository root or pass --expand-shader\n", path);
        if (o->gpu_expand) return 0;
    }
    return 1;
}

/* The textures the shaders read: the LUTs of the energy-conserving
   fibre, without absorption (the shader absorbs per channel), the dual
   scattering tables, the colour ramp and the density map. */
static int glm_init_textures(glm_app *a)
{
    static const unsigned char full = 255; /* no map: hair everywhere */
    hf_lut_params lp;
    hf_result r;
    float *lut;
    unsigned char ramp[64 * 32 * 4];
    size_t side; /* the buffer holds the largest tables */
    int k;
    hf_lut_params_init(&lp);
    lp.size = a->o.lut_size;
    lp.model = HF_LUT_ENERGY;
    lp.sigma_a = 0.0;
    lp.explicit_zero = HF_LUT_ZERO_SIGMA_A;
    side = (size_t)(lp.size > GLM_DUAL_SIZE ? lp.size : GLM_DUAL_SIZE);
    lut = (float *)malloc(sizeof(float) * 4u * HF_LUT_DUAL_PLANES * side *
                          side);
    if (!lut) return 0;
    if ((r = hf_lut_bake_m(&lp, 0, lp.size, lut)) != HF_OK) {
        fprintf(stderr, "gl_marschner: LUT: %s\n", hf_result_string(r));
        free(lut);
        return 0;
    }
    a->tex_m = glm_texture2d(GL_RGBA32F, lp.size, lp.size, GL_RGBA, GL_FLOAT,
                             lut, GL_CLAMP_TO_EDGE);
    hf_lut_bake_n(&lp, 0, lp.size, lut);
    a->tex_n = glm_texture2d(GL_RGBA32F, lp.size, lp.size, GL_RGBA, GL_FLOAT,
                             lut, GL_CLAMP_TO_EDGE);
    lp.size = GLM_DUAL_SIZE;
    hf_lut_bake_dual(&lp, 0, lp.size, lut);
    for (k = 0; k < HF_LUT_DUAL_PLANES; ++k)
        a->tex_dual[k] = glm_texture2d(
            GL_RGBA32F, lp.size, lp.size, GL_RGBA, GL_FLOAT,
            lut + 4u * (size_t)lp.size * (size_t)lp.size * (size_t)k,
            GL_CLAMP_TO_EDGE);
    free(lut);
    glm_ramp(ramp, 64, 32);
    a->tex_ramp = glm_texture2d(GL_RGBA8, 64, 32, GL_RGBA, GL_UNSIGNED_BYTE,
                                ramp, GL_CLAMP_TO_EDGE);
    a->tex_density = a->have_density
        ? glm_texture2d(GL_R8, a->density.width, a->density.height, GL_RED,
                        GL_UNSIGNED_BYTE, a->density_px, GL_REPEAT)
        : glm_texture2d(GL_R8, 1, 1, GL_RED, GL_UNSIGNED_BYTE, &full,
                        GL_REPEAT);
    return 1;
}

/* The light's targets: the shadow map (a depth texture the shaders read
   as a float) and the deep opacity maps (three layers and the body's
   depth, half floats, blended); then OIT's targets, and back to the
   output's framebuffer. */
static int glm_init_light_targets(glm_app *a)
{
    a->tex_shadow = glm_texture2d(GL_DEPTH_COMPONENT24, GLM_SHADOW_SIZE,
                                  GLM_SHADOW_SIZE, GL_DEPTH_COMPONENT,
                                  GL_UNSIGNED_INT, NULL, GL_CLAMP_TO_EDGE);
    glGenFramebuffers(1, &a->shadow_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, a->shadow_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D,
                           a->tex_shadow, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        fprintf(stderr, "gl_marschner: the shadow map framebuffer is "
                "incomplete; run with --no-shadows\n");
        return 0;
    }
    a->tex_opacity = glm_texture2d(GL_RGBA16F, GLM_SHADOW_SIZE, GLM_SHADOW_SIZE,
                                   GL_RGBA, GL_FLOAT, NULL, GL_CLAMP_TO_EDGE);
    glGenFramebuffers(1, &a->opacity_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, a->opacity_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                           a->tex_opacity, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        fprintf(stderr, "gl_marschner: the deep opacity framebuffer is "
                "incomplete; run with --shadows single or --no-shadows\n");
        return 0;
    }
    a->layers[0] = GLM_LAYER_1 * a->hair_len;
    a->layers[1] = GLM_LAYER_2 * a->hair_len;
    a->layers[2] = GLM_LAYER_3 * a->hair_len;
    glm_oit_init(a);
    glc_begin_frame(); /* back to the output's framebuffer */
    return 1;
}

/* The hair's index buffer: once, for every strand; a LOD draws a
   prefix. */
static int glm_init_hair_indices(glm_app *a)
{
    const int S = a->info.strand_count;
    long long n_idx = hf_ribbon_index_count(S, a->P, HF_TRIANGLES);
    uint32_t *idx = (uint32_t *)malloc(sizeof(uint32_t) * (size_t)n_idx);
    if (!idx || hf_ribbon_indices(S, a->P, HF_TRIANGLES, idx, n_idx) != HF_OK)
        return 0;
    glGenBuffers(1, &a->ibo_hair);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo_hair);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(4 * n_idx), idx,
                 GL_STATIC_DRAW);
    free(idx);
    return 1;
}

/* The CPU path's vertex array: a dynamic (position, tangent) buffer and
   a static one (texcoord, colour, 3D colour); the compact path's
   texcoords are written here too, once. */
static int glm_init_cpu_buffers(glm_app *a)
{
    const int S = a->info.strand_count;
    const size_t nv = glm_ribbon_vertices(a);
    /* the static streams need strand points only to be finite: the fur's
       shape at creation serves */
    glm_static *st;
    hf_ribbon_params v;
    hf_ribbon_output out;
    hf_result r;
    glGenVertexArrays(1, &a->vao_cpu);
    glBindVertexArray(a->vao_cpu);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo_hair);
    glGenBuffers(1, &a->vbo_stage); /* sized by its first use */
    glGenBuffers(1, &a->vbo_dyn);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_dyn);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(glm_dyn) * nv), NULL,
                 GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm_dyn), (void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(glm_dyn),
                          (void *)offsetof(glm_dyn, tan));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    st = (glm_static *)malloc(sizeof(glm_static) * nv);
    if (!st) return 0;
    glm_camera(a);
    glm_ribbon_view(a, &v);
    memset(&out, 0, sizeof out);
    out.texcoord.data = st[0].uv_t;
    out.texcoord.stride = sizeof(glm_static);
    out.color.data = st[0].rgba;
    out.color.stride = sizeof(glm_static);
    out.color3d.data = st[0].c3d;
    out.color3d.stride = sizeof(glm_static);
    if ((r = hf_fur_interpolate(a->fur, 0, S)) == HF_OK &&
        (r = hf_fur_ribbons(a->fur, 0, S, &v, &out)) == HF_OK) {
        /* --compact: the texcoords of the 16-byte vertices, once too */
        memset(&out, 0, sizeof out);
        out.texcoord.data = a->cdyn[0].uv_t;
        out.texcoord.stride = sizeof(glm_compact);
        out.texcoord.format = HF_FORMAT_UNORM16;
        r = hf_fur_ribbons(a->fur, 0, S, &v, &out);
    }
    if (r != HF_OK) {
        fprintf(stderr, "gl_marschner: %s\n", hf_result_string(r));
        free(st);
        return 0;
    }
    glGenBuffers(1, &a->vbo_static);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_static);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(glm_static) * nv), st,
                 GL_STATIC_DRAW);
    free(st);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(glm_static),
                          (void *)0);
    glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, sizeof(glm_static),
                          (void *)offsetof(glm_static, rgba));
    glVertexAttribPointer(4, 2, GL_FLOAT, GL_FALSE, sizeof(glm_static),
                          (void *)offsetof(glm_static, c3d));
    glEnableVertexAttribArray(2);
    glEnableVertexAttribArray(3);
    glEnableVertexAttribArray(4);
    return 1;
}

/* --compact's vertex array: position, texcoord and tangent from the
   16-byte stream as normalized integers (GL divides by 32767, 65535 and
   127, the encoding hf_ribbons uses; the shader undoes origin and
   scale), colour and 3D colour from the static buffer as above. */
static void glm_init_compact_buffers(glm_app *a)
{
    const size_t nv = glm_ribbon_vertices(a);
    int i;
    glGenVertexArrays(1, &a->vao_cpu16);
    glBindVertexArray(a->vao_cpu16);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo_hair);
    glGenBuffers(1, &a->vbo_dyn16);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_dyn16);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(glm_compact) * nv), NULL,
                 GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_SHORT, GL_TRUE, sizeof(glm_compact),
                          (void *)offsetof(glm_compact, pos));
    glVertexAttribPointer(1, 3, GL_BYTE, GL_TRUE, sizeof(glm_compact),
                          (void *)offsetof(glm_compact, tan));
    glVertexAttribPointer(2, 3, GL_UNSIGNED_SHORT, GL_TRUE, sizeof(glm_compact),
                          (void *)offsetof(glm_compact, uv_t));
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_static);
    glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, sizeof(glm_static),
                          (void *)offsetof(glm_static, rgba));
    glVertexAttribPointer(4, 2, GL_FLOAT, GL_FALSE, sizeof(glm_static),
                          (void *)offsetof(glm_static, c3d));
    for (i = 0; i < 5; ++i) glEnableVertexAttribArray((GLuint)i);
}

/* The two dynamic buffers as texture buffers too, where they fit: each
   ribbon vertex reads its pair's other side (the 1-pixel clamp); glm_dyn
   is 3 RG32F texels, glm_compact 2 RGBA16I. */
static void glm_init_pair_textures(glm_app *a)
{
    const size_t nv = glm_ribbon_vertices(a);
    GLint most = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &most);
    a->min_width = (double)most >= 3.0 * (double)nv;
    if (a->min_width) {
        glGenTextures(1, &a->tbo_pair);
        glBindTexture(GL_TEXTURE_BUFFER, a->tbo_pair);
        glTexBuffer(GL_TEXTURE_BUFFER, GL_RG32F, a->vbo_dyn);
        glGenTextures(1, &a->tbo_pair16);
        glBindTexture(GL_TEXTURE_BUFFER, a->tbo_pair16);
        glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA16I, a->vbo_dyn16);
    } else {
        printf("gl_marschner: %.0f ribbon vertices are more than a "
               "texture buffer holds here (%d texels): strands are not "
               "widened to a pixel\n", (double)nv, (int)most);
    }
}

/* The GPU path: points (streamed), root UV, colour and 3D-colour x per
   strand (static). hf_fur_info has no 3D-colour x, so it is computed the
   way hf_fur_create does, from the strand's root UV. */
static int glm_init_gpu_buffers(glm_app *a)
{
    const int S = a->info.strand_count;
    float *tmp, *c3x;
    int i;
    glGenVertexArrays(1, &a->vao_gpu);
    glBindVertexArray(a->vao_gpu);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo_hair);
    /* compact points: 8 bytes, read as RGBA16I (ribbon_expand.glsl) */
    glm_tbo(&a->vbo_points, &a->tbo_points,
            a->o.compact ? GL_RGBA16I : GL_RGBA32F,
            (a->o.compact ? 8u : 16u) * (size_t)S * (size_t)a->P, NULL,
            GL_STREAM_DRAW);
    tmp = (float *)malloc(sizeof(float) * 2u * (size_t)S);
    c3x = (float *)malloc(sizeof(float) * (size_t)S);
    if (!tmp || !c3x) return 0;
    for (i = 0; i < S; ++i) {
        float xy[2];
        tmp[2 * i] = a->info.strands[i].uv[0];
        tmp[2 * i + 1] = a->info.strands[i].uv[1];
        hf_color3d_coord(&a->index, tmp[2 * i], tmp[2 * i + 1], 0.0f, xy);
        c3x[i] = xy[0];
    }
    glm_tbo(&a->vbo_uv, &a->tbo_uv, GL_RG32F, sizeof(float) * 2u * (size_t)S,
            tmp, GL_STATIC_DRAW);
    glm_tbo(&a->vbo_c3x, &a->tbo_c3x, GL_R32F, sizeof(float) * (size_t)S,
            c3x, GL_STATIC_DRAW);
    free(tmp);
    free(c3x);
    glm_tbo(&a->vbo_scolor, &a->tbo_scolor, GL_RGBA32F,
            sizeof(float) * 4u * (size_t)S, a->info.strand_colors, GL_STATIC_DRAW);
    return 1;
}

/* The body's vertex array: the skinned vertices, streamed, and its
   triangles. */
static void glm_init_body_buffers(glm_app *a)
{
    glGenVertexArrays(1, &a->vao_head);
    glBindVertexArray(a->vao_head);
    glGenBuffers(1, &a->vbo_head);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_head);
    glBufferData(GL_ARRAY_BUFFER,
                 (GLsizeiptr)(sizeof(ch_vertex) * (size_t)a->nv),
                 NULL, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(ch_vertex), (void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(ch_vertex),
                          (void *)offsetof(ch_vertex, normal));
    glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof(ch_vertex),
                          (void *)offsetof(ch_vertex, uv));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glEnableVertexAttribArray(2);
    glGenBuffers(1, &a->ibo_head);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo_head);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(12 * (size_t)a->nt),
                 a->body_idx, GL_STATIC_DRAW);
}

/* The collider lines' vertex array, streamed. */
static void glm_init_line_buffers(glm_app *a)
{
    glGenVertexArrays(1, &a->vao_line);
    glBindVertexArray(a->vao_line);
    glGenBuffers(1, &a->vbo_line);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_line);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6u *
                 (size_t)(a->max_col + 1) * GLM_LINES_PER_COLLIDER), NULL,
                 GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, (void *)0);
    glEnableVertexAttribArray(0);
}

/* Returns 1, or 0 with a message. The GL context must be current. */
static int glm_init(glm_app *a, const glm_options *o)
{
    double t0 = glm_now_ms();
    memset(a, 0, sizeof *a);
    a->o = *o;
    a->draw_hair = !o->no_hair;
    if (!glm_init_body(a) || !glm_init_maps(a) || !glm_init_curves(a) ||
        !glm_init_fur(a) || !glm_init_arrays(a) || !glm_init_programs(a) ||
        !glm_init_textures(a) || !glm_init_light_targets(a) ||
        !glm_init_hair_indices(a) || !glm_init_cpu_buffers(a))
        return 0;
    glm_init_compact_buffers(a);
    glm_init_pair_textures(a);
    if (!glm_init_gpu_buffers(a)) return 0;
    glm_init_body_buffers(a);
    glm_init_line_buffers(a);
    glBindVertexArray(0);
    if (!glc_check_gl("glm_init")) return 0;
    printf("gl_marschner: %s: %d strands of %d points, %d guides, hair "
           "%.3g m, %d colliders, size %.3g m; grown, LUTs baked (%d x %d, "
           "dual scattering %d x %d) and buffers made in %.0f ms\n",
           o->mesh ? o->mesh : "built-in head", a->info.strand_count, a->P,
           a->info.guide_count, a->hair_len, a->ncol, a->size, o->lut_size,
           o->lut_size, GLM_DUAL_SIZE, GLM_DUAL_SIZE, glm_now_ms() - t0);
    return 1;
}

/* ---- per frame ------------------------------------------------------------ */

/* Advance the simulation to time t (dt since the last step): camera, LOD,
   skinning, colliders, roots, ropes, LOD guides. Returns 1, or 0 with a
   message. */
static int glm_simulate(glm_app *a, double t, float dt)
{
    hf_result r;
    float lod;
    int i;
    double t0 = glm_now_ms(), t1;
    a->t = t;
    /* the body at time t: a mesh is skinned from its bones, the head
       moved rigidly; the colliders follow */
    if (a->ch.vertex_count > 0) {
        ch_pose(&a->ch, a->anim, a->o.still ? 0.0 : t, a->skin, a->all_col);
        for (i = 0; i < a->ncol; ++i) a->col[i] = a->all_col[a->col_keep[i]];
    } else {
        hm_pose(t, a->o.still, a->pose);
        for (i = 0; i < a->nv; ++i) {
            hm_xform(a->pose, a->rest[i].pos, 1.0f, a->skin[i].pos);
            hm_xform(a->pose, a->rest[i].normal, 0.0f, a->skin[i].normal);
        }
        glm_head_colliders(a->pose, a->col);
    }
    t1 = glm_now_ms();
    a->ms_skin += t1 - t0;
    glm_camera(a);
    lod = a->o.lod >= 0.0f ? a->o.lod
                           : hf_lod_from_distance(a->o.distance,
                                                  GLM_FULL_DETAIL * a->frame_dist,
                                                  GLM_CULL * a->frame_dist);
    if (lod != a->lod || a->drawn == 0) {
        hf_fur_set_lod(a->fur, lod);
        hf_fur_get_info(a->fur, &a->info);
        a->lod = lod;
    }
    a->drawn = a->info.drawn_strand_count;
    /* a groom on the head rides on its rigid motion; on a mesh, on the
       skinned grown part, as fur does */
    {
        double tr0 = glm_now_ms(), tr1;
        r = a->groom && a->ch.vertex_count == 0
                ? hf_fur_set_transform(a->fur, a->pose, 0, a->info.guide_count)
                : hf_fur_set_roots(a->fur, &a->skinned, 0,
                                   a->info.guide_count);
        if (!r) r = hf_fur_build_grid(a->fur, 0, a->info.grid_resolution);
        tr1 = glm_now_ms();
        if (!r)
            r = hf_fur_simulate(a->fur, 0, a->info.guide_count, dt, a->col,
                                a->ncol);
        a->ms_roots += tr1 - tr0;
        a->ms_ropes += glm_now_ms() - tr1;
    }
    if (!r) r = hf_fur_interpolate_guides(a->fur, 0, a->info.lod_guide_count);
    if (r != HF_OK) {
        fprintf(stderr, "gl_marschner: simulate at t = %.3f: %s\n", t,
                hf_result_string(r));
        return 0;
    }
    a->ms_sim += glm_now_ms() - t1;
    ++a->ms_frames;
    a->cpu_ms = glm_now_ms() - t0;
    { /* the worst stretch of a guide this frame (ropes keep their length);
         NaN fails every comparison, so it is counted apart, not lost */
        double worst = 0.0;
        for (i = 0; i < a->info.guide_count; ++i) {
            const float *p = a->info.guide_points + 3 * (size_t)i * (size_t)a->P;
            double e;
            int k;
            for (k = 0; k < 3 * a->P; ++k) a->nonfinite += !isfinite(p[k]);
            /* guides under 1 mm (a length map near 0) are left out: their
               lengths are a few float steps of the coordinates, and a
               relative error of those says nothing about the ropes */
            if (!(a->rest_len[i] >= 1e-3f)) continue;
            e = glm_polyline_length(p, a->P) / a->rest_len[i] - 1.0;
            if (isnan(e)) a->stretch_nan = 1;
            else if (e > worst) worst = e;
        }
        if (worst > a->stretch_max) a->stretch_max = worst;
        a->stretch_sum += worst;
        ++a->stretch_frames;
    }
    return 1;
}

/* The GL buffer this frame's strands go to (bound), its size for every
   strand, and the bytes of the drawn prefix. */
static GLenum glm_stream_buffer(glm_app *a, size_t *all, size_t *bytes)
{
    const size_t n = (size_t)a->drawn * (size_t)a->P,
                 S = (size_t)a->info.strand_count * (size_t)a->P;
    const size_t vsize = a->o.gpu_expand ? (a->o.compact ? 8u : 16u)
                         : a->o.compact  ? 2u * sizeof(glm_compact)
                                         : 2u * sizeof(glm_dyn);
    const GLenum target =
        a->o.gpu_expand ? GL_TEXTURE_BUFFER : GL_ARRAY_BUFFER;
    glBindBuffer(target, a->o.gpu_expand ? a->vbo_points
                         : a->o.compact  ? a->vbo_dyn16
                                         : a->vbo_dyn);
    *all = vsize * S;
    *bytes = vsize * n;
    return target;
}

/* The drawn strands of this frame: interpolation, then CPU ribbons, or
   GPU points straight from the guides (hf_fur_interpolate_points), and
   the upload. Only frames that are drawn need it. They are written
   straight into the mapped GL buffer with streaming stores (the stores
   for write-combined memory), and nothing is copied; with --staging into
   a mapped staging buffer the same way, then copied on the GPU; with
   --copy, or where a buffer cannot be mapped, into memory of our own,
   then glBufferSubData. */
/* The box compact positions are written in this frame (corigin, cscale):
   it follows the head, so the hair stays well inside it however far the
   head moves. */
static void glm_compact_box(glm_app *a)
{
    memcpy(a->corigin, a->target, sizeof a->corigin);
    a->cscale = a->ch.vertex_count > 0 ? 0.6f * a->ch_diag + 2.0f * a->hair_len
                                       : GLM_COMPACT_SCALE;
}

static int glm_build(glm_app *a)
{
    hf_ribbon_params v;
    hf_result r;
    const int n = a->drawn;
    /* the map and the unmap or copy count as the upload, the library's
       calls between them as the strands */
    const double tu = glm_now_ms();
    double t0, t1;
    unsigned char *map = NULL;
    size_t all, bytes;
    GLenum target = 0;
    glm_ribbon_view(a, &v);
    if (a->o.upload != GLM_COPY) {
        /* the whole buffer invalidated: the driver need not wait for the
           GPU to finish reading last frame's data */
        target = glm_stream_buffer(a, &all, &bytes);
        if (a->o.upload == GLM_STAGING) {
            target = GL_COPY_READ_BUFFER;
            glBindBuffer(target, a->vbo_stage);
            if (a->stage_bytes < all) {
                glBufferData(target, (GLsizeiptr)all, NULL, GL_STREAM_DRAW);
                a->stage_bytes = all;
            }
        }
        if (bytes > 0)
            map = (unsigned char *)glMapBufferRange(
                target, 0, (GLsizeiptr)bytes,
                GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
        if (bytes > 0 && !map) {
            fprintf(stderr, "gl_marschner: glMapBufferRange failed (GL "
                    "error 0x%x): the strands are copied from now on, as "
                    "with --copy\n", (unsigned)glGetError());
            a->o.upload = GLM_COPY;
            a->stage_bytes = 0; /* its storage may not have been made */
        }
        v.nontemporal = map != NULL;
    }
    t0 = glm_now_ms();
    if (a->o.gpu_expand) {
        if (a->o.compact) { /* 8-byte points in the compact box */
            glm_compact_box(a);
            v.point_format = HF_POINT_COMPACT;
            memcpy(v.point_origin, a->corigin, sizeof v.point_origin);
            v.point_scale = a->cscale;
        }
        r = hf_fur_interpolate_points(a->fur, 0, n, &v,
                                      map ? (float *)(void *)map
                                          : a->points4);
    } else if ((r = hf_fur_interpolate(a->fur, 0, n)) == HF_OK &&
               a->o.compact) {
        /* position and tangent only: the texcoords from init stay in
           cdyn (a mapped buffer is invalidated: they are written too) */
        glm_compact *c = map ? (glm_compact *)(void *)map : a->cdyn;
        hf_ribbon_output out;
        memset(&out, 0, sizeof out);
        glm_compact_box(a);
        out.position.data = c[0].pos;
        out.position.stride = sizeof(glm_compact);
        out.position.format = HF_FORMAT_SNORM16;
        out.tangent.data = c[0].tan;
        out.tangent.stride = sizeof(glm_compact);
        out.tangent.format = HF_FORMAT_SNORM8;
        if (map) {
            out.texcoord.data = c[0].uv_t;
            out.texcoord.stride = sizeof(glm_compact);
            out.texcoord.format = HF_FORMAT_UNORM16;
        }
        memcpy(out.position_origin, a->corigin, sizeof a->corigin);
        out.position_scale = a->cscale;
        r = hf_fur_ribbons(a->fur, 0, n, &v, &out);
    } else if (r == HF_OK) {
        glm_dyn *d = map ? (glm_dyn *)(void *)map : a->dyn;
        hf_ribbon_output out;
        memset(&out, 0, sizeof out);
        out.position.data = d[0].pos;
        out.position.stride = sizeof(glm_dyn);
        out.tangent.data = d[0].tan;
        out.tangent.stride = sizeof(glm_dyn);
        r = hf_fur_ribbons(a->fur, 0, n, &v, &out);
    }
    t1 = glm_now_ms();
    if (map && glUnmapBuffer(target) != GL_TRUE && r == HF_OK) {
        /* the contents were lost (a display mode switch): this frame
           may draw wrongly, the next one writes them again */
        fprintf(stderr, "gl_marschner: glUnmapBuffer: the "
                "buffer's contents were lost this frame\n");
    }
    if (r != HF_OK) {
        fprintf(stderr, "gl_marschner: strands: %s\n", hf_result_string(r));
        return 0;
    }
    a->cpu_ms += t1 - t0;
    a->ms_build += t1 - t0;
    ++a->build_frames;
    if (!map) {
        /* orphan, then write the drawn prefix: the driver need not wait
           for the GPU to finish reading last frame's data */
        target = glm_stream_buffer(a, &all, &bytes);
        glBufferData(target, (GLsizeiptr)all, NULL, GL_STREAM_DRAW);
        glBufferSubData(target, 0, (GLsizeiptr)bytes,
                        a->o.gpu_expand ? (const void *)a->points4
                        : a->o.compact  ? (const void *)a->cdyn
                                        : (const void *)a->dyn);
    } else if (a->o.upload == GLM_STAGING) {
        /* orphaned as above, then the drawn prefix copied on the GPU */
        target = glm_stream_buffer(a, &all, &bytes);
        glBufferData(target, (GLsizeiptr)all, NULL, GL_DYNAMIC_COPY);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, target, 0, 0,
                            (GLsizeiptr)bytes);
    }
    a->ms_upload += (glm_now_ms() - t1) + (t0 - tu);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo_head);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(ch_vertex) *
                    (size_t)a->nv), a->skin);
    return 1;
}

static int glm_step(glm_app *a, double t, float dt, int build)
{
    return glm_simulate(a, t, dt) && (!build || glm_build(a));
}

/* Texture `tex` on unit `unit`, and the shader's sampler `name` on it. */
static void glm_sampler(GLuint prog, int unit, GLenum target, GLuint tex,
                        const char *name)
{
    glActiveTexture((GLenum)(GL_TEXTURE0 + unit));
    glBindTexture(target, tex);
    glUniform1i(glGetUniformLocation(prog, name), unit);
}

/* The key light, from the upper front right. */
static void glm_light_dir(float L[3])
{
    float l;
    L[0] = 0.55f; L[1] = 0.75f; L[2] = 0.45f;
    l = sqrtf(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
    L[0] /= l; L[1] /= l; L[2] /= l;
}

static void glm_lights(GLuint prog, const glm_app *a)
{
    /* the key light, a cool ambient, the shadow map */
    float L[3];
    glm_light_dir(L);
    glUniform3f(glGetUniformLocation(prog, "u_light_dir"), L[0], L[1], L[2]);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_light_view_proj"), 1,
                       GL_FALSE, a->light_view_proj);
    glUniform1f(glGetUniformLocation(prog, "u_shadow_on"),
                a->o.no_shadows ? 0.0f : 1.0f);
    glUniform1f(glGetUniformLocation(prog, "u_shadow_k"), a->shadow_k);
    glUniform1f(glGetUniformLocation(prog, "u_shadow_depth"), a->shadow_depth);
    glUniform1f(glGetUniformLocation(prog, "u_shadow_bias"),
                3.0f * a->shadow_depth / GLM_SHADOW_SIZE);
    glUniform1f(glGetUniformLocation(prog, "u_deep"),
                a->o.single_shadow ? 0.0f : 1.0f);
    glUniform1f(glGetUniformLocation(prog, "u_opacity_k"), GLM_OPACITY_K);
    glUniform3fv(glGetUniformLocation(prog, "u_layers"), 1, a->layers);
    glm_sampler(prog, 10, GL_TEXTURE_2D, a->tex_opacity, "u_opacity");
    glm_sampler(prog, 7, GL_TEXTURE_2D, a->tex_shadow, "u_shadow");
    glActiveTexture(GL_TEXTURE0);
    glUniform3f(glGetUniformLocation(prog, "u_light_color"), 1.9f, 1.8f, 1.65f);
    glUniform3f(glGetUniformLocation(prog, "u_ambient"), 0.22f, 0.24f, 0.30f);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE,
                       a->view_proj);
}

/* The hair's draw call with `prog` (a hair or a shadow program of the
   current path): its inputs, then the triangles of the drawn strands. */
static void glm_draw_hair(glm_app *a, GLuint prog, const float eye[3],
                          int orthographic, const float view_dir[3])
{
    glUniform3fv(glGetUniformLocation(prog, "u_eye"), 1, eye);
    glUniform1i(glGetUniformLocation(prog, "u_points_per_strand"), a->P);
    glUniform1f(glGetUniformLocation(prog, "u_root_fade"),
                fminf(a->o.root_fade * a->root_width,
                      GLM_ROOT_FADE_LEN * a->hair_len));
    if (a->o.gpu_expand && a->prog_gpu) {
        glm_sampler(prog, 3, GL_TEXTURE_BUFFER, a->tbo_points, "u_points");
        glm_sampler(prog, 4, GL_TEXTURE_BUFFER, a->tbo_uv, "u_root_uv");
        glm_sampler(prog, 5, GL_TEXTURE_BUFFER, a->tbo_scolor, "u_strand_color");
        glm_sampler(prog, 6, GL_TEXTURE_BUFFER, a->tbo_c3x, "u_strand_c3x");
        glUniform3fv(glGetUniformLocation(prog, "u_point_origin"), 1, a->corigin);
        glUniform1f(glGetUniformLocation(prog, "u_point_scale"), a->cscale);
        glUniform1i(glGetUniformLocation(prog, "u_orthographic"), orthographic);
        glUniform3fv(glGetUniformLocation(prog, "u_view_dir"), 1, view_dir);
        glBindVertexArray(a->vao_gpu);
    } else if (a->o.compact) {
        glUniform3fv(glGetUniformLocation(prog, "u_pos_origin"), 1, a->corigin);
        glUniform1f(glGetUniformLocation(prog, "u_pos_scale"), a->cscale);
        glm_sampler(prog, 11, GL_TEXTURE_BUFFER, a->tbo_pair16, "u_pair");
        glBindVertexArray(a->vao_cpu16);
    } else {
        glm_sampler(prog, 11, GL_TEXTURE_BUFFER, a->tbo_pair, "u_pair");
        glBindVertexArray(a->vao_cpu);
    }
    glActiveTexture(GL_TEXTURE0);
    glDrawElements(GL_TRIANGLES, (GLsizei)(6 * (a->P - 1) * a->drawn),
                   GL_UNSIGNED_INT, 0);
}

/* The shadow map: body and hair from the light, orthographic around the
   whole body and its hair as they are now. */
static void glm_shadow_pass(glm_app *a)
{
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    float c[3], L[3], eye[3], view[16], proj[16], r = 0.0f, dir[3];
    const float up[3] = {0, 1, 0};
    int i, k;
    GLuint prog;
    for (i = 0; i < a->nv; ++i)
        for (k = 0; k < 3; ++k) {
            if (a->skin[i].pos[k] < lo[k]) lo[k] = a->skin[i].pos[k];
            if (a->skin[i].pos[k] > hi[k]) hi[k] = a->skin[i].pos[k];
        }
    for (k = 0; k < 3; ++k) {
        c[k] = 0.5f * (lo[k] + hi[k]);
        r += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    r = sqrtf(r) + 1.05f * a->hair_len;
    glm_light_dir(L);
    for (k = 0; k < 3; ++k) {
        eye[k] = c[k] + 2.0f * r * L[k];
        dir[k] = -L[k];
    }
    glc_mat4_look_at(view, eye, c, up);
    glc_mat4_ortho(proj, -r, r, -r, r, r, 3.0f * r);
    glc_mat4_mul(a->light_view_proj, proj, view);
    a->shadow_depth = 2.0f * r;
    if (a->o.no_shadows) return;
    glBindFramebuffer(GL_FRAMEBUFFER, a->shadow_fbo);
    glViewport(0, 0, GLM_SHADOW_SIZE, GLM_SHADOW_SIZE);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_CULL_FACE);
    glUseProgram(a->depth_head);
    glUniformMatrix4fv(glGetUniformLocation(a->depth_head, "u_view_proj"), 1,
                       GL_FALSE, a->light_view_proj);
    glBindVertexArray(a->vao_head);
    glDrawElements(GL_TRIANGLES, 3 * a->nt, GL_UNSIGNED_INT, 0);
    if (a->draw_hair && a->drawn > 0) {
        prog = a->o.gpu_expand && a->prog_gpu ? a->depth_gpu
             : a->o.compact ? a->depth_cpu16 : a->depth_cpu;
        glUseProgram(prog);
        glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1,
                           GL_FALSE, a->light_view_proj);
        /* CPU ribbons face the camera; the GPU path faces the light */
        glm_draw_hair(a, prog, eye, 1, dir);
    }
    if (!a->o.single_shadow) {
        /* the deep opacity maps: everything drawn, added up per layer
           (alpha: the body's nearest depth) */
        glBindFramebuffer(GL_FRAMEBUFFER, a->opacity_fbo);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendEquationSeparate(GL_FUNC_ADD, GL_MIN);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(a->opacity_head);
        glUniformMatrix4fv(glGetUniformLocation(a->opacity_head, "u_view_proj"),
                           1, GL_FALSE, a->light_view_proj);
        glBindVertexArray(a->vao_head);
        glDrawElements(GL_TRIANGLES, 3 * a->nt, GL_UNSIGNED_INT, 0);
        if (a->draw_hair && a->drawn > 0) {
            prog = a->o.gpu_expand && a->prog_gpu ? a->opacity_gpu
                 : a->o.compact ? a->opacity_cpu16 : a->opacity_cpu;
            glUseProgram(prog);
            glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1,
                               GL_FALSE, a->light_view_proj);
            glUniform1f(glGetUniformLocation(prog, "u_shadow_depth"),
                        a->shadow_depth);
            glUniform3fv(glGetUniformLocation(prog, "u_layers"), 1, a->layers);
            /* a strand's width over a texel's: the fraction it covers */
            a->opacity_texel = a->root_width * GLM_SHADOW_SIZE / (2.0f * r);
            if (a->opacity_texel > 1.0f) a->opacity_texel = 1.0f;
            glUniform1f(glGetUniformLocation(prog, "u_opacity_texel"),
                        a->opacity_texel);
            if (prog == a->opacity_gpu) {
                hf_ribbon_params v;
                glm_ribbon_view(a, &v);
                glUniform2f(glGetUniformLocation(prog, "u_alpha"),
                            v.alpha_root, v.alpha_tip);
            }
            glm_sampler(prog, 7, GL_TEXTURE_2D, a->tex_shadow, "u_shadow");
            glActiveTexture(GL_TEXTURE0);
            glm_draw_hair(a, prog, eye, 1, dir);
        }
        glBlendEquation(GL_FUNC_ADD);
        glDisable(GL_BLEND);
    }
    glBindVertexArray(0);
}

/* Is the hair drawn with order-independent transparency this frame? */
static int glm_oit_on(const glm_app *a)
{
    return a->oit_ok && !a->o.no_oit && !a->o.a2c;
}

/* The body: the grown triangles with the scalp colour, then the rest. */
static void glm_draw_body(glm_app *a)
{
    glUseProgram(a->prog_head);
    glm_lights(a->prog_head, a);
    {
        float sc[3];
        int k;
        for (k = 0; k < 3; ++k) /* the hair colour, darkened, linear */
            sc[k] = 0.25f * powf(a->o.mesh && !a->o.color_path
                                     ? a->o.hair_color[k]
                                     : (k == 0 ? 0.2f : k == 1 ? 0.1f : 0.05f),
                                 2.2f);
        glUniform3fv(glGetUniformLocation(a->prog_head, "u_scalp"), 1, sc);
    }
    glm_sampler(a->prog_head, 0, GL_TEXTURE_2D, a->tex_density, "u_density");
    glBindVertexArray(a->vao_head);
    /* a groom has no density map to say where the scalp is */
    glUniform1f(glGetUniformLocation(a->prog_head, "u_scalp_on"),
                a->groom && !a->have_density ? 0.0f : 1.0f);
    glDrawElements(GL_TRIANGLES, 3 * a->nt_grown, GL_UNSIGNED_INT, 0);
    glUniform1f(glGetUniformLocation(a->prog_head, "u_scalp_on"), 0.0f);
    if (a->nt > a->nt_grown)
        glDrawElements(GL_TRIANGLES, 3 * (a->nt - a->nt_grown), GL_UNSIGNED_INT,
                       (void *)(12u * (size_t)a->nt_grown));
}

static void glm_draw(glm_app *a)
{
    const int n = a->drawn;
    double t0, ts;
    glFinish(); /* the shadow passes timed alone */
    t0 = glm_now_ms();
    glm_shadow_pass(a);
    glFinish();
    ts = glm_now_ms();
    a->shadow_ms = ts - t0;
    glc_begin_frame();
    glClearColor(0.13f, 0.14f, 0.17f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_CULL_FACE);

    glm_draw_body(a);

    /* the hair: no culling (camera-facing ribbons have no back to cull;
       the GPU path's fallback side at a degenerate point may flip the
       winding). By default, weighted blended order-independent
       transparency (McGuire and Bavoil 2013): every hair fragment in
       front of the body adds its weighted colour and multiplies the
       revealage, in any order, without depth writes; a resolve then lays
       the result over the body. --no-oit: alpha blending in draw order
       with depth writes on, where a faded tip hides the strands drawn
       after it behind it. On llvmpipe either looked smoother than alpha
       to coverage (--a2c), whose 4 coverage levels need the dithering in
       the shader and then show its pattern. */
    if (a->draw_hair && n > 0) {
        GLuint prog = a->o.gpu_expand && a->prog_gpu ? a->prog_gpu
                    : a->o.compact ? a->prog_cpu16 : a->prog_cpu;
        const int oit = glm_oit_on(a);
        glUseProgram(prog);
        glm_lights(prog, a);
        glUniform1i(glGetUniformLocation(prog, "u_kajiya"), a->o.kajiya);
        glUniform1i(glGetUniformLocation(prog, "u_color3d"), a->o.color3d);
        glUniform1f(glGetUniformLocation(prog, "u_spec"), a->o.specular);
        glUniform1f(glGetUniformLocation(prog, "u_dither"),
                    a->o.a2c ? 0.25f : 0.0f);
        glm_sampler(prog, 0, GL_TEXTURE_2D, a->tex_m, "u_lut_m");
        glm_sampler(prog, 1, GL_TEXTURE_2D, a->tex_n, "u_lut_n");
        glm_sampler(prog, 2, GL_TEXTURE_2D, a->tex_ramp, "u_ramp");
        glUniform1f(glGetUniformLocation(prog, "u_dual"),
                    a->o.no_dual ? 0.0f : 1.0f);
        glm_sampler(prog, 8, GL_TEXTURE_2D, a->tex_dual[0], "u_dual0");
        glm_sampler(prog, 9, GL_TEXTURE_2D, a->tex_dual[2], "u_dual2");
        glActiveTexture(GL_TEXTURE0);
        if (prog == a->prog_gpu) {
            hf_ribbon_params v;
            glm_ribbon_view(a, &v);
            glUniform2f(glGetUniformLocation(prog, "u_alpha"), v.alpha_root,
                        v.alpha_tip);
        }
        glUniform2f(glGetUniformLocation(prog, "u_viewport"),
                    (float)a->o.width, (float)a->o.height);
        glUniform1f(glGetUniformLocation(prog, "u_min_px"),
                    a->min_width ? a->o.min_px : 0.0f);
        glUniform1f(glGetUniformLocation(prog, "u_lift"),
                    a->o.root_fade > 0.0f ? 1.0f : 0.0f);
        glUniform1f(glGetUniformLocation(prog, "u_oit"), (float)oit);
        /* the weight's reference: about the front of the grown mesh */
        glUniform1f(glGetUniformLocation(prog, "u_oit_ref"),
                    a->o.distance - 0.5f * a->size);
        glUniform1f(glGetUniformLocation(prog, "u_oit_scale"),
                    GLM_OIT_FALLOFF * a->frame_dist);
        if (oit) {
            static const float accum0[4] = {0, 0, 0, 1}, weight0[4] = {0};
            glBindFramebuffer(GL_FRAMEBUFFER, a->oit_fbo);
            glClearBufferfv(GL_COLOR, 0, accum0); /* revealage 1 */
            glClearBufferfv(GL_COLOR, 1, weight0);
            glDepthMask(GL_FALSE);
            glEnable(GL_BLEND);
            /* colours and weights add up; alpha: revealage *= 1 - a */
            glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO,
                                GL_ONE_MINUS_SRC_ALPHA);
        } else if (a->o.a2c && glc_samples() > 1) {
            glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
        } else {
            glEnable(GL_BLEND);
            glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        }
        /* alpha is coverage, not colour: keep the target opaque (a PNG
           with the fade in its alpha channel looks washed out) */
        if (!oit) glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
        glm_draw_hair(a, prog, a->eye, 0, a->eye);
        if (oit) { /* the resolve, over the body */
            glDepthMask(GL_TRUE);
            glc_begin_frame();
            glDisable(GL_DEPTH_TEST);
            glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA); /* premultiplied */
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
            glUseProgram(a->prog_oit);
            glm_sampler(a->prog_oit, 0, a->oit_samples > 1
                        ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D,
                        a->tex_accum, "u_accum");
            glm_sampler(a->prog_oit, 1, a->oit_samples > 1
                        ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D,
                        a->tex_weight, "u_weight");
            glUniform1i(glGetUniformLocation(a->prog_oit, "u_samples"),
                        a->oit_samples);
            glBindVertexArray(a->vao_empty);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glEnable(GL_DEPTH_TEST);
        }
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
        glDisable(GL_BLEND);
        glActiveTexture(GL_TEXTURE0);
    }

    /* colliders: wireframes, bright where visible, faint where hidden */
    if (a->o.colliders) {
        int c, nl = 0;
        for (c = 0; c < a->ncol; ++c)
            nl += glm_capsule_lines(&a->col[c], a->line_buf + 6 * nl);
        glUseProgram(a->prog_line);
        glUniformMatrix4fv(glGetUniformLocation(a->prog_line, "u_view_proj"), 1,
                           GL_FALSE, a->view_proj);
        glBindVertexArray(a->vao_line);
        glBindBuffer(GL_ARRAY_BUFFER, a->vbo_line);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(float) * 6u *
                        (size_t)nl), a->line_buf);
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glDepthMask(GL_FALSE);
        glDisable(GL_DEPTH_TEST);
        glUniform4f(glGetUniformLocation(a->prog_line, "u_color"), 0.3f, 0.9f, 1.0f, 0.25f);
        glDrawArrays(GL_LINES, 0, 2 * nl);
        glEnable(GL_DEPTH_TEST);
        glUniform4f(glGetUniformLocation(a->prog_line, "u_color"), 0.3f, 0.9f, 1.0f, 0.9f);
        glDrawArrays(GL_LINES, 0, 2 * nl);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
    }
    glBindVertexArray(0);
    glFinish(); /* so draw_ms is the GPU's time, not the queueing */
    a->draw_ms = glm_now_ms() - t0;
}

static void glm_shutdown(glm_app *a)
{
    GLuint bufs[12], texs[10], vaos[5], progs[13];
    int i;
    bufs[0] = a->vbo_dyn; bufs[1] = a->vbo_static; bufs[2] = a->vbo_points;
    bufs[3] = a->vbo_uv; bufs[4] = a->vbo_scolor; bufs[5] = a->vbo_c3x;
    bufs[6] = a->ibo_hair; bufs[7] = a->vbo_head; bufs[8] = a->ibo_head;
    bufs[9] = a->vbo_line; bufs[10] = a->vbo_dyn16; bufs[11] = a->vbo_stage;
    texs[0] = a->tex_m; texs[1] = a->tex_n; texs[2] = a->tex_ramp;
    texs[3] = a->tex_density; texs[4] = a->tbo_points; texs[5] = a->tbo_uv;
    texs[6] = a->tbo_scolor; texs[7] = a->tbo_c3x; texs[8] = a->tex_shadow;
    texs[9] = a->tex_opacity;
    vaos[0] = a->vao_cpu; vaos[1] = a->vao_gpu; vaos[2] = a->vao_head;
    vaos[3] = a->vao_line; vaos[4] = a->vao_cpu16;
    progs[0] = a->prog_cpu; progs[1] = a->prog_cpu16; progs[2] = a->prog_gpu;
    progs[3] = a->prog_head; progs[4] = a->prog_line; progs[5] = a->depth_cpu;
    progs[6] = a->depth_cpu16; progs[7] = a->depth_gpu; progs[8] = a->depth_head;
    progs[9] = a->opacity_cpu; progs[10] = a->opacity_cpu16;
    progs[11] = a->opacity_gpu; progs[12] = a->opacity_head;
    if (glc_width() > 0) {
        glDeleteBuffers(12, bufs);
        glDeleteTextures(10, texs);
        glDeleteTextures(HF_LUT_DUAL_PLANES, a->tex_dual);
        glDeleteVertexArrays(5, vaos);
        glDeleteFramebuffers(1, &a->shadow_fbo);
        glDeleteFramebuffers(1, &a->opacity_fbo);
        for (i = 0; i < 13; ++i) glDeleteProgram(progs[i]);
        texs[0] = a->tbo_pair; texs[1] = a->tbo_pair16;
        texs[2] = a->tex_accum; texs[3] = a->tex_weight;
        glDeleteTextures(4, texs);
        glDeleteFramebuffers(1, &a->oit_fbo);
        glDeleteVertexArrays(1, &a->vao_empty);
        glDeleteProgram(a->prog_oit);
    }
    hf_fur_destroy(a->fur);
    if (a->ch.vertex_count > 0) ch_free(&a->ch);
    free(a->rest);
    free(a->skin);
    free(a->body_idx);
    free(a->grow_idx);
    free(a->col);
    free(a->all_col);
    free(a->col_keep);
    free(a->rest_len);
    free(a->rest_root);
    free(a->comb_dir);
    free(a->groom_rgb);
    cv_free(&a->curves);
    /* maps from files came from stb_image's malloc, the others from ours */
    free(a->density_px);
    free(a->length_px);
    free(a->color_px);
    free(a->index_px);
    free(a->dyn);
    free(a->cdyn);
    free(a->points4);
    free(a->line_buf);
    memset(a, 0, sizeof *a);
}

#ifndef GLM_NO_MAIN
/* One list for --help and the window's start, so they cannot drift. */
#define GLM_KEYS \
"Keys (window): K Kajiya-Kay/Marschner, G GPU expansion, C 3D colour,\n" \
"  V colliders, O shadows, S specular, T transparency (OIT), H body\n" \
"  motion, space orbit,\n" \
"  +/- or scroll distance, arrows orbit, Esc quits\n"

static void glm_usage(FILE *fp)
{
    fprintf(fp,
"usage: gl_marschner [options]: fur or hair on the built-in head or any mesh,\n"
"lit with the Marschner model, in a window or headless to PNG. Lengths are in\n"
"metres; a mesh file's unit is found from its size (see --unit).\n"
"The body\n"
"  --mesh FILE        a mesh any format assimp reads, skinned and animated\n"
"                     from its bones (default: the built-in head, a sphere of\n"
"                     radius 0.1 m with its own maps, swinging and turning)\n"
"  --anim NAME        the animation to play (default: the file's first)\n"
"  --grow-on A,B      grow only on these meshes of the file (default: all)\n"
"  --unit U           auto (default: a box diagonal up to 20 is metres, up to\n"
"                     2000 centimetres, else millimetres), m, cm, mm, or\n"
"                     metres per file unit\n"
"  --still            the body does not move (first frame of the animation)\n"
"The hair\n"
"  --density PNG      density map, channel 0 (default: none, density 1; the\n"
"                     head: its hairline); PNG top row = v 1, as in OpenGL\n"
"  --length PNG       length map, channel 0, x --hair-length (default: none)\n"
"  --color PNG        colour map, RGB (default: --hair-color)\n"
"  --hair-color R,G,B sRGB in [0, 1] without a colour map (0.42,0.27,0.16)\n"
"  --hair-length M    longest strand, metres (default: 0.14 on the head, 5 %%\n"
"                     of the grown mesh's bounding-box diagonal on a mesh)\n"
"  --strands N        strands (default 20000)\n"
"  --guides N         guides (default: strands / 10, at most 2000; the\n"
"                     mesh's vertices are guides, LOD guides make up the rest)\n"
"  --guides FILE      authored guide curves (.hair, .tfx, .obj polylines), in\n"
"                     the mesh's units and pose: their shapes become the\n"
"                     guides' (lengths from the curves)\n"
"  --stiffness S      hold to the rest shape, [0, 1] (default 0: hair falls;\n"
"                     0.3-0.6 for fur)\n"
"  --comb X,Y,Z       comb the hair in this world direction: the growth\n"
"                     direction tilts from the normal towards it along the\n"
"                     surface, tan(tilt) = its length (default 0,0,0: the\n"
"                     normal)\n"
"  --settle S         seconds simulated at the first pose before frame 1, so\n"
"                     hair starts hanging (default 0)\n"
        );
    fprintf(fp, /* in parts: C99 compilers need only take 4095 bytes */
"  --rest-from-gravity S  seconds the hair hangs at the first pose (under\n"
"                     gravity, the colliders and the grid) before the draped\n"
"                     shape becomes the rest shape that --stiffness holds,\n"
"                     [0, 600] (default 0: the grown shape); give it (1 s\n"
"                     is enough) when grown hair passes through a collider,\n"
"                     as long hair does through a body's: the stiffness\n"
"                     pulls such hair into it and it never rests\n"
"  --volume F         hair-hair repulsion, so hair keeps a volume: F times\n"
"                     gravity's pull where the density changes by the\n"
"                     typical density across a grid cell, [0, 100]\n"
"                     (default 1; 0 = off)\n"
"  --friction F       hair-hair friction, so hair moves as a mass: the\n"
"                     fraction of a point's velocity difference to the hair\n"
"                     around it removed per 1/60 s, [0, 1] (default 0.2;\n"
"                     0 = off)\n"
"  --grid N           nodes along each axis of the hair-hair grid, 4..128\n"
"                     (default 32; none when --volume and --friction are 0)\n"
"  --keep-length N    1: each drawn strand keeps the segment lengths of its\n"
"                     grown shape, which blending guides that part and\n"
"                     clumping change (hf_fur_desc.keep_length; about 2.5 ns\n"
"                     a point a frame); 0: the plain blend (default 0)\n"
"  --groom FILE       a groom (.hair, .tfx, .obj polylines): its own strands\n"
"                     are drawn, a fraction of them simulated; its roots\n"
"                     follow the skinned --grow-on meshes (or the head)\n"
"  --guide-fraction F of the groom's strands simulated, (0, 1] (default 0.1)\n"
"  --curl R,TURNS     curl: helix radius (metres), turns along a strand\n"
"  --wave A,COUNT     wave: amplitude (metres), periods along a strand\n"
"  --frizz F          random offset per point, a fraction of a segment\n"
"  --clump S,SIZE     clumping: strength [0, 1] (tips on the clump at 1) and\n"
"                     clump size in metres (0: around the guides) (0.25,0)\n"
"  --color-variation V  each strand's colour times [1 - V, 1 + V]\n"
"  --width-variation V  each strand's width times [1 - V, 1 + V]\n"
        );
    fprintf(fp,
"Drawing\n"
"  --kajiya           Kajiya-Kay instead of Marschner\n"
"  --no-shadows       no self-shadowing (default: deep opacity maps)\n"
"  --shadows MODE     deep (default): deep opacity maps, three layers of\n"
"                     the hair's opacity behind the first hair from the\n"
"                     light; single: one depth map, light falling off as\n"
"                     exp(-k d) with the depth d behind it (the web page's)\n"
"  --no-dual          no dual scattering: single scattering only (default:\n"
"                     Zinke's dual scattering from hf_lut_bake_dual)\n"
"  --no-specular      diffuse and ambient only\n"
"  --gpu-expand       ribbons expanded on the GPU from hf_fur_interpolate_points\n"
"  --compact          CPU ribbons in the 16-byte vertex; with --gpu-expand,\n"
"                     GPU points in 8 bytes (HF_POINT_COMPACT)\n"
"  --copy             strands written into memory of the program's, then\n"
"                     copied (glBufferSubData); default: straight into the\n"
"                     mapped GL buffers, with streaming stores\n"
"  --staging          strands written into a mapped staging buffer, then\n"
"                     copied on the GPU (glCopyBufferSubData) into the\n"
"                     buffers drawn from, which are never mapped\n"
"  --color3d          the 3D colour scheme (a ramp with dyed tips)\n"
"  --colliders        draw the colliders\n"
"  --no-hair          draw the body alone (hair still simulated): a control\n"
"                     picture\n"
"  --no-oit           blend the hair in draw order, with depth writes\n"
"                     (default: weighted blended order-independent\n"
"                     transparency, McGuire and Bavoil 2013, where the GL\n"
"                     can make its float targets)\n"
"  --a2c              alpha to coverage instead of blending (no OIT)\n"
"  --min-width PX     strands narrower than PX pixels on screen are drawn\n"
"                     PX wide and faded by true width / PX (default 1;\n"
"                     0: drawn as built, thin ones alias)\n"
"  --root-fade N      strands fade in over their first N root widths (at\n"
"                     most 4 %% of the hair length), their depth half a\n"
"                     width nearer the eye (default 8; 0: roots as built)\n"
"  --lut-size N       Marschner LUT size (default 256)\n"
"  --expand-shader F  the GPU expansion shader (examples/ribbon_expand.glsl)\n"
"  --shading-shader F the hair's fragment shader and self-shadowing\n"
"                     (examples/hair_shading.glsl)\n"
"Camera (the default frames the grown mesh, whatever its size)\n"
"  --distance D       metres from the target (default: 1.588 bounding-box\n"
"                     diagonals of the grown mesh)\n"
"  --lod F            level of detail [0, 1] (default: from the distance)\n"
"  --azimuth DEG      (default 30)   --elevation DEG (default 12)\n"
"  --orbit DEG_PER_S  camera orbit speed (default 12)\n"
"Output\n"
"  --headless         no window: render off-screen (EGL)\n"
"  --frames N         frames of 1/60 s (default headless: 60; window: forever)\n"
"  --out FILE.png     write the last frame; with --save-every N, FILE holds a\n"
"                     %%d (e.g. out/f_%%03d.png) and every Nth frame is written\n"
"  --save-every N     see --out\n"
"  --draw-all         draw every headless frame, not only the written ones\n"
"  --width W --height H  image size (default 640 x 480)\n"
GLM_KEYS);
}

/* Strict numbers: the whole string, finite, in [lo, hi]. */
static int glm_real(const char *opt, const char *v, double lo, double hi,
                    float *out)
{
    char *end;
    double x = strtod(v, &end);
    if (end == v || *end || !isfinite(x) || x < lo || x > hi) {
        fprintf(stderr, "gl_marschner: %s '%s': expected a number in "
                "[%g, %g]\n", opt, v, lo, hi);
        return 0;
    }
    *out = (float)x;
    return 1;
}

/* n comma-separated numbers, each in [lo, hi]. */
static int glm_reals(const char *opt, const char *v, double lo, double hi,
                     int n, float *out)
{
    char buf[128], *p = buf, *e;
    int k;
    snprintf(buf, sizeof buf, "%s", v);
    for (k = 0; k < n; ++k) {
        e = strchr(p, ',');
        if ((k < n - 1) != (e != NULL)) {
            fprintf(stderr, "gl_marschner: %s '%s': expected %d numbers "
                    "separated by commas\n", opt, v, n);
            return 0;
        }
        if (e) *e = '\0';
        if (!glm_real(opt, p, lo, hi, &out[k])) return 0;
        p = e ? e + 1 : p;
    }
    return 1;
}
#define glm_real3(opt, v, lo, hi, out) glm_reals(opt, v, lo, hi, 3, out)
#define glm_real2(opt, v, lo, hi, out) glm_reals(opt, v, lo, hi, 2, out)

static int glm_int(const char *opt, const char *v, long lo, long hi, int *out)
{
    char *end;
    long x = strtol(v, &end, 10);
    if (end == v || *end || x < lo || x > hi) {
        fprintf(stderr, "gl_marschner: %s '%s': expected a whole number in "
                "[%ld, %ld]\n", opt, v, lo, hi);
        return 0;
    }
    *out = (int)x;
    return 1;
}

/* Is `p` a file name with exactly one %d (flags 0 and a width allowed)
   and no other conversion ("%%" is a %)? Then it is safe for snprintf. */
static int glm_frame_pattern(const char *p)
{
    int n = 0;
    for (; *p; ++p) {
        if (*p != '%') continue;
        if (p[1] == '%') { ++p; continue; }
        ++p;
        while (*p >= '0' && *p <= '9') ++p;
        if (*p != 'd') return 0;
        ++n;
    }
    return n == 1;
}

/* Parse the command line into o: 1, 0 on a bad argument (with a message),
   -1 for --help. */
static int glm_parse(int argc, char **argv, glm_options *o)
{
    int i, ok = 1;
    for (i = 1; i < argc && ok; ++i) {
        const char *s = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(s, "--help") || !strcmp(s, "-h")) return -1;
        else if (!strcmp(s, "--headless")) o->headless = 1;
        else if (!strcmp(s, "--kajiya")) o->kajiya = 1;
        else if (!strcmp(s, "--gpu-expand")) o->gpu_expand = 1;
        else if (!strcmp(s, "--color3d")) o->color3d = 1;
        else if (!strcmp(s, "--colliders")) o->colliders = 1;
        else if (!strcmp(s, "--still")) o->still = 1;
        else if (!strcmp(s, "--a2c")) o->a2c = 1;
        else if (!strcmp(s, "--draw-all")) o->draw_all = 1;
        else if (!strcmp(s, "--compact")) o->compact = 1;
        else if (!strcmp(s, "--copy") || !strcmp(s, "--staging")) {
            const int u = s[2] == 'c' ? GLM_COPY : GLM_STAGING;
            if (o->upload != GLM_MAPPED && o->upload != u) {
                fprintf(stderr, "gl_marschner: --copy and --staging are two "
                        "ways to upload the strands: give one\n");
                return 0;
            }
            o->upload = u;
        }
        else if (!strcmp(s, "--no-specular")) o->specular = 0.0f;
        else if (!strcmp(s, "--no-shadows")) o->no_shadows = 1;
        else if (!strcmp(s, "--no-dual")) o->no_dual = 1;
        else if (!strcmp(s, "--no-hair")) o->no_hair = 1;
        else if (!strcmp(s, "--no-oit")) o->no_oit = 1;
        else if (!strncmp(s, "--no-oit=", 9) || !strncmp(s, "--oit", 5)) {
            fprintf(stderr, "gl_marschner: %s: order-independent "
                    "transparency is on by default; --no-oit (no value) "
                    "turns it off\n", s);
            return 0;
        }
        else if (!v) {
            fprintf(stderr, "gl_marschner: unknown option or %s without its "
                    "value (--help lists them)\n", s);
            return 0;
        } else {
            ++i;
            if (!strcmp(s, "--frames")) ok = glm_int(s, v, 1, 1000000, &o->frames);
            else if (!strcmp(s, "--out")) o->out = v;
            else if (!strcmp(s, "--shadows")) {
                if (!strcmp(v, "single")) o->single_shadow = 1;
                else if (!strcmp(v, "deep")) o->single_shadow = 0;
                else {
                    fprintf(stderr, "gl_marschner: --shadows takes deep or "
                            "single, not %s\n", v);
                    ok = 0;
                }
            }
            else if (!strcmp(s, "--save-every")) ok = glm_int(s, v, 1, 1000000, &o->save_every);
            else if (!strcmp(s, "--width")) ok = glm_int(s, v, 16, 8192, &o->width);
            else if (!strcmp(s, "--height")) ok = glm_int(s, v, 16, 8192, &o->height);
            else if (!strcmp(s, "--strands")) ok = glm_int(s, v, 1, 10000000, &o->strands);
            else if (!strcmp(s, "--lut-size")) ok = glm_int(s, v, 2, HF_LUT_MAX_SIZE, &o->lut_size);
            else if (!strcmp(s, "--distance")) ok = glm_real(s, v, 1e-3, 1e6, &o->distance);
            else if (!strcmp(s, "--min-width")) ok = glm_real(s, v, 0.0, 64.0, &o->min_px);
            else if (!strcmp(s, "--root-fade")) ok = glm_real(s, v, 0.0, 1e3, &o->root_fade);
            else if (!strcmp(s, "--lod")) ok = glm_real(s, v, 0.0, 1.0, &o->lod);
            else if (!strcmp(s, "--azimuth")) ok = glm_real(s, v, -1e6, 1e6, &o->azimuth);
            else if (!strcmp(s, "--elevation")) ok = glm_real(s, v, -89.0, 89.0, &o->elevation);
            else if (!strcmp(s, "--orbit")) ok = glm_real(s, v, -1e4, 1e4, &o->orbit_speed);
            else if (!strcmp(s, "--hair-length")) ok = glm_real(s, v, 1e-6, 1e4, &o->hair_length);
            else if (!strcmp(s, "--stiffness")) ok = glm_real(s, v, 0.0, 1.0, &o->stiffness);
            else if (!strcmp(s, "--settle")) ok = glm_real(s, v, 0.0, 60.0, &o->settle);
            else if (!strcmp(s, "--rest-from-gravity")) ok = glm_real(s, v, 0.0, 600.0, &o->rest_gravity);
            else if (!strcmp(s, "--volume")) ok = glm_real(s, v, 0.0, 100.0, &o->volume);
            else if (!strcmp(s, "--friction")) ok = glm_real(s, v, 0.0, 1.0, &o->friction);
            else if (!strcmp(s, "--grid")) ok = glm_int(s, v, 4, HF_GRID_MAX_RESOLUTION, &o->grid);
            else if (!strcmp(s, "--keep-length")) ok = glm_int(s, v, 0, 1, &o->keep_length);
            else if (!strcmp(s, "--hair-color")) ok = glm_real3(s, v, 0.0, 1.0, o->hair_color);
            else if (!strcmp(s, "--comb")) ok = glm_real3(s, v, -100.0, 100.0, o->comb);
            else if (!strcmp(s, "--guides")) {
                /* a count, or a file of curves */
                if (strspn(v, "0123456789") == strlen(v))
                    ok = glm_int(s, v, 1, 10000000, &o->guides);
                else
                    o->guides_path = v;
            }
            else if (!strcmp(s, "--groom")) o->groom_path = v;
            else if (!strcmp(s, "--guide-fraction")) ok = glm_real(s, v, 1e-6, 1.0, &o->guide_fraction);
            else if (!strcmp(s, "--curl")) ok = glm_real2(s, v, 0.0, 1e3, o->curl);
            else if (!strcmp(s, "--wave")) ok = glm_real2(s, v, 0.0, 1e3, o->wave);
            else if (!strcmp(s, "--frizz")) ok = glm_real(s, v, 0.0, 10.0, &o->frizz);
            else if (!strcmp(s, "--clump")) {
                ok = glm_real2(s, v, 0.0, 1e3, o->clump);
                if (ok && o->clump[0] > 1.0f) {
                    fprintf(stderr, "gl_marschner: --clump '%s': the strength "
                            "is at most 1\n", v);
                    ok = 0;
                }
            }
            else if (!strcmp(s, "--color-variation")) ok = glm_real(s, v, 0.0, 1.0, &o->color_variation);
            else if (!strcmp(s, "--width-variation")) ok = glm_real(s, v, 0.0, 1.0, &o->width_variation);
            else if (!strcmp(s, "--expand-shader")) o->expand_shader = v;
            else if (!strcmp(s, "--shading-shader")) o->shading_shader = v;
            else if (!strcmp(s, "--mesh")) o->mesh = v;
            else if (!strcmp(s, "--anim")) o->anim = v;
            else if (!strcmp(s, "--grow-on")) o->grow_on = v;
            else if (!strcmp(s, "--unit")) o->unit = v;
            else if (!strcmp(s, "--density")) o->density_path = v;
            else if (!strcmp(s, "--length")) o->length_path = v;
            else if (!strcmp(s, "--color")) o->color_path = v;
            else {
                fprintf(stderr, "gl_marschner: unknown option %s (--help "
                        "lists them)\n", s);
                return 0;
            }
        }
    }
    if (ok && o->save_every > 0 && (!o->out || !glm_frame_pattern(o->out))) {
        fprintf(stderr, "gl_marschner: --save-every needs --out with one "
                "%%d (or %%03d ...) in the name and no other %%\n");
        return 0;
    }
    return ok;
}

static glm_app glm_the_app; /* for the GLFW callbacks */

static void glm_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    glm_options *o = &glm_the_app.o;
    float f = glm_the_app.frame_dist;
    (void)scancode;
    (void)mods;
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    case GLFW_KEY_K: o->kajiya = !o->kajiya; break;
    case GLFW_KEY_G:
        if (glm_the_app.prog_gpu) o->gpu_expand = !o->gpu_expand;
        break;
    case GLFW_KEY_C: o->color3d = !o->color3d; break;
    case GLFW_KEY_V: o->colliders = !o->colliders; break;
    case GLFW_KEY_O: o->no_shadows = !o->no_shadows; break;
    case GLFW_KEY_H: o->still = !o->still; break;
    case GLFW_KEY_S: o->specular = o->specular > 0 ? 0.0f : 1.0f; break;
    case GLFW_KEY_T: o->no_oit = !o->no_oit; break;
    case GLFW_KEY_SPACE: o->orbit_speed = o->orbit_speed != 0 ? 0.0f : 12.0f; break;
    case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: o->distance /= 1.15f; break;
    case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: o->distance *= 1.15f; break;
    case GLFW_KEY_LEFT: o->azimuth -= 5; break;
    case GLFW_KEY_RIGHT: o->azimuth += 5; break;
    case GLFW_KEY_UP: o->elevation += 5; break;
    case GLFW_KEY_DOWN: o->elevation -= 5; break;
    default: break;
    }
    if (o->distance < 0.45f * f) o->distance = 0.45f * f;
    if (o->distance > 70.0f * f) o->distance = 70.0f * f;
    if (o->elevation > 89.0f) o->elevation = 89.0f;
    if (o->elevation < -89.0f) o->elevation = -89.0f;
}

static void glm_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)w;
    (void)dx;
    glm_the_app.o.distance *= (float)pow(1.1, -dy);
    glm_key(w, GLFW_KEY_UNKNOWN, 0, GLFW_PRESS, 0); /* clamp */
}

/* Do the guide roots follow the skinned mesh? Each guide's root at
   creation is found on a rest triangle of the grown mesh (barycentric),
   that point is taken on the same skinned triangle, and its distance to
   the root now is measured. A root that is not finite, or lies on no rest
   triangle, is missing. A linear scan with a box test: run once, at the
   end. */
static void glm_root_check(const glm_app *a, int *missing, double *worst)
{
    const ch_vertex *rv = a->rest + a->grow_first;
    const ch_vertex *sv = a->skin + a->grow_first;
    const double eps = 1e-4 * a->size; /* off the surface: missing */
    int g, t, k;
    *missing = 0;
    *worst = 0.0;
    for (g = 0; g < a->info.guide_count; ++g) {
        const float *p = a->rest_root + 3 * g;
        const float *now = a->info.guide_points + 3 * (size_t)g * (size_t)a->P;
        double best = eps, bw[3] = {0, 0, 0}, q[3], d2 = 0.0;
        int bt = -1;
        if (!isfinite(now[0]) || !isfinite(now[1]) || !isfinite(now[2])) {
            ++*missing;
            continue;
        }
        for (t = 0; t < a->nt_grown; ++t) {
            const uint32_t *ix = a->grow_idx + 3 * (size_t)t;
            const float *A = rv[ix[0]].pos, *B = rv[ix[1]].pos, *C = rv[ix[2]].pos;
            double e1[3], e2[3], d[3], d11 = 0, d12 = 0, d22 = 0, p1 = 0,
                   p2 = 0, den, u, v, w, r2 = 0.0;
            for (k = 0; k < 3; ++k) {
                float lo = A[k] < B[k] ? A[k] : B[k], hi = A[k] > B[k] ? A[k] : B[k];
                lo = C[k] < lo ? C[k] : lo;
                hi = C[k] > hi ? C[k] : hi;
                if (p[k] < lo - eps || p[k] > hi + eps) break;
            }
            if (k < 3) continue;
            for (k = 0; k < 3; ++k) {
                e1[k] = (double)B[k] - A[k];
                e2[k] = (double)C[k] - A[k];
                d[k] = (double)p[k] - A[k];
                d11 += e1[k] * e1[k];
                d12 += e1[k] * e2[k];
                d22 += e2[k] * e2[k];
                p1 += d[k] * e1[k];
                p2 += d[k] * e2[k];
            }
            den = d11 * d22 - d12 * d12;
            if (!(den > 0.0)) continue; /* degenerate: no barycentrics */
            v = (d22 * p1 - d12 * p2) / den;
            w = (d11 * p2 - d12 * p1) / den;
            u = 1.0 - v - w;
            if (u < -1e-4 || v < -1e-4 || w < -1e-4) continue;
            for (k = 0; k < 3; ++k) {
                double r = d[k] - v * e1[k] - w * e2[k];
                r2 += r * r;
            }
            if (sqrt(r2) < best) {
                best = sqrt(r2);
                bt = t;
                bw[0] = u;
                bw[1] = v;
                bw[2] = w;
            }
        }
        if (bt < 0) {
            ++*missing;
            continue;
        }
        for (k = 0; k < 3; ++k) {
            const uint32_t *ix = a->grow_idx + 3 * (size_t)bt;
            q[k] = bw[0] * sv[ix[0]].pos[k] + bw[1] * sv[ix[1]].pos[k] +
                   bw[2] * sv[ix[2]].pos[k] - now[k];
            d2 += q[k] * q[k];
        }
        if (sqrt(d2) > *worst) *worst = sqrt(d2);
    }
}

/* The per-run figures a user checks: stretch, non-finite points, roots on
   the skinned mesh, roots inside colliders and the milliseconds per
   stage. */
static void glm_report(const glm_app *a, int drawn_frames)
{
    hf_fur_info info;
    long bad_strand = 0, q;
    int unread = 0;
    int missing;
    double worst;
    hf_fur_get_info(a->fur, &info);
    printf("gl_marschner: %s, %s, %s, %dx%d, distance %.3g m, LOD %.3f: %d "
           "of %d strands drawn, %d guides, %d colliders\n",
           a->o.kajiya ? "Kajiya-Kay" : "Marschner",
           a->o.gpu_expand ? "GPU expansion"
           : a->o.compact ? "compact CPU ribbons" : "CPU ribbons",
           glm_oit_on(a) ? "order-independent transparency"
           : a->o.a2c    ? "alpha to coverage" : "blended in draw order",
           a->o.width, a->o.height, a->o.distance, a->lod, a->drawn,
           a->info.strand_count, info.guide_count, a->ncol);
    printf("gl_marschner: stretch (longest guide / its rest length - 1, "
           "guides of 1 mm and longer): "
           "worst %.2e, mean of the per-frame worst %.2e over %ld frames; "
           "%d of %d guide roots inside a collider\n",
           a->stretch_nan ? (double)NAN : a->stretch_max,
           a->stretch_nan ? (double)NAN
           : a->stretch_frames ? a->stretch_sum / a->stretch_frames : 0.0,
           a->stretch_frames, info.roots_inside, info.guide_count);
    if (info.roots_inside > 0)
        printf("gl_marschner: (for those guides the collider is shrunk to "
               "the root's depth; if a proxy is larger than the body there, "
               "shrink it)\n");
    /* the drawn strands of the last built frame (with --gpu-expand only
       its points were written; without --copy into a GL buffer, so
       they are written again into points4 here for the check) */
    if (a->o.gpu_expand && (a->o.upload != GLM_COPY || a->o.compact)) {
        hf_ribbon_params v; /* float points, whatever was drawn */
        glm_ribbon_view(a, &v);
        if (hf_fur_interpolate_points(a->fur, 0, a->drawn, &v, a->points4))
            unread = 1; /* none to look at: every one counted */
    }
    for (q = 0; q < 3L * a->drawn * a->P; ++q)
        bad_strand += unread || (a->o.gpu_expand
                                     ? !isfinite(a->points4[q / 3 * 4 + q % 3])
                                     : !isfinite(info.strand_points[q]));
    printf("gl_marschner: non-finite coordinates: %ld in the guides over "
           "every simulated frame, %ld in the %d drawn strands of the last "
           "frame\n", a->nonfinite, bad_strand, a->drawn);
    if (a->groom && a->ch.vertex_count == 0) {
        printf("gl_marschner: roots: a groom on the head moves rigidly, "
               "not checked against the mesh\n");
    } else {
        glm_root_check(a, &missing, &worst);
        printf("gl_marschner: roots: %d of %d guide roots missing (not "
               "finite, or on no triangle at rest); the others at most "
               "%.2e m (%.2e of the mesh size) from their point on the "
               "skinned mesh\n", missing, info.guide_count, worst,
               worst / a->size);
    }
    if (a->ms_frames > 0)
        printf("gl_marschner: ropes: %.3f ms a frame for %d guides with %d "
               "colliders%s (roots%s + ropes %.3f us a guide)\n",
               a->ms_ropes / a->ms_frames, info.guide_count, a->ncol,
               info.grid_resolution ? " and hair-hair interaction" : "",
               info.grid_resolution ? " + grid" : "",
               1000.0 * (a->ms_roots + a->ms_ropes) / a->ms_frames /
                   (info.guide_count > 0 ? info.guide_count : 1));
    if (a->ms_frames > 0)
        printf("gl_marschner: ms per frame: skin and colliders %.2f, roots + "
               "ropes + LOD guides %.2f, strands + %s %.2f%s and upload "
               "%.2f (%ld drawn frames), GL draw %.1f (of it the shadow "
               "passes %.2f: %s)\n",
               a->ms_skin / a->ms_frames, a->ms_sim / a->ms_frames,
               a->o.gpu_expand ? "GPU points" : "ribbons",
               a->build_frames ? a->ms_build / a->build_frames : 0.0,
               a->o.upload == GLM_COPY      ? ""
               : a->o.upload == GLM_STAGING ? " (into a mapped staging buffer)"
                                            : " (into the mapped buffer)",
               a->build_frames ? a->ms_upload / a->build_frames : 0.0,
               a->build_frames, drawn_frames ? a->ms_draw / drawn_frames : 0.0,
               drawn_frames ? a->ms_shadow / drawn_frames : 0.0,
               a->o.no_shadows      ? "none"
               : a->o.single_shadow ? "depth map, glFinish-timed"
                                    : "depth + deep opacity, glFinish-timed");
}

int main(int argc, char **argv)
{
    glm_options o;
    glm_app *a = &glm_the_app;
    double last = 0, title_at = -1;
    int drawn_frames = 0, ok = 1, pr, saved = 0;
    long f0 = 0;
    glm_default_options(&o);
    pr = glm_parse(argc, argv, &o);
    if (pr <= 0) {
        glm_usage(pr < 0 ? stdout : stderr);
        return pr < 0 ? 0 : 2;
    }
    if (o.headless ? !glc_open_headless(o.width, o.height)
                   : !glc_open_window(o.width, o.height, "hairfur gl_marschner"))
        return 1;
    if (o.headless && o.frames < 1) o.frames = 60;
    if (!glm_init(a, &o)) return 1;
    /* hair grows straight out of the skin: let it fall at the first pose */
    {
        int k, n = (int)(a->o.settle * 60.0f + 0.5f);
        for (k = 0; k < n && ok; ++k) ok = glm_simulate(a, 0.0, 1.0f / 60.0f);
        if (ok && a->o.rest_gravity > 0.0f) {
            /* the roots and colliders at the first pose, then the drape */
            hf_result r;
            double t0;
            if (n == 0) ok = glm_simulate(a, 0.0, 1.0f / 60.0f);
            t0 = glm_now_ms();
            r = hf_fur_settle_rest(a->fur, a->o.rest_gravity, a->col,
                                   a->ncol);
            if (r != HF_OK) {
                fprintf(stderr, "gl_marschner: --rest-from-gravity: %s\n",
                        hf_result_string(r));
                ok = 0;
            } else {
                printf("gl_marschner: rest from gravity: %g s of draping in "
                       "%.0f ms\n", (double)a->o.rest_gravity,
                       glm_now_ms() - t0);
            }
        }
        a->stretch_max = a->stretch_sum = 0.0;
        a->stretch_frames = a->ms_frames = 0;
        a->ms_skin = a->ms_sim = 0.0;
    }
    f0 = glc_frame_index();
    if (o.frames > 0) glc_set_frame_limit(f0 + o.frames);
    if (!o.headless) {
        fputs(GLM_KEYS, stdout);
        fflush(stdout);
        glfwSetKeyCallback((GLFWwindow *)glc_window(), glm_key);
        glfwSetScrollCallback((GLFWwindow *)glc_window(), glm_scroll);
    }
    while (ok && !glc_should_close()) {
        /* headless: a fixed 60 Hz clock; window: the wall clock, dt capped */
        long f = glc_frame_index() - f0;
        int last_frame = o.frames > 0 && f + 1 == o.frames;
        int save = a->o.out && (a->o.save_every > 0
                                    ? (f + 1) % a->o.save_every == 0
                                    : last_frame);
        int draw = !a->o.headless || a->o.draw_all || save || last_frame;
        double now = a->o.headless ? (f + 1) / 60.0 : glc_time();
        float dt = a->o.headless ? 1.0f / 60.0f : (float)(now - last);
        if (dt <= 0.0f) dt = 1.0f / 60.0f;
        if (dt > 0.05f) dt = 0.05f;
        last = now;
        a->o.azimuth += a->o.orbit_speed * dt;
        ok = glm_step(a, now, dt, draw);
        if (ok && draw) {
            glm_draw(a);
            a->ms_draw += a->draw_ms;
            a->ms_shadow += a->shadow_ms;
            ++drawn_frames;
        }
        if (ok && save) {
            char path[1024];
            if (a->o.save_every > 0)
                snprintf(path, sizeof path, a->o.out, (int)(f + 1));
            else
                snprintf(path, sizeof path, "%s", a->o.out);
            ok = glc_save_png(path);
            if (ok) ++saved;
            if (ok && (a->o.save_every == 0 || last_frame))
                printf("gl_marschner: wrote %s%s\n", path,
                       saved > 1 ? " (and the frames before it)" : "");
        }
        if (!a->o.headless && now - title_at > 0.25) {
            /* each key with what it switches (the full list is printed
               at start and in --help) */
            char title[512];
            snprintf(title, sizeof title,
                     "hairfur gl_marschner - %s, %s%s%s%s - %.2f m, LOD %.2f: "
                     "%d of %d strands - CPU %.1f ms, draw %.1f ms (shadows "
                     "%.1f) - keys: "
                     "K Kajiya-Kay, G GPU, C 3D colour, V colliders, "
                     "O shadows, S specular, T OIT, H motion, space orbit, "
                     "+/- distance, arrows, Esc",
                     a->o.kajiya ? "Kajiya-Kay" : "Marschner",
                     a->o.gpu_expand ? "GPU expansion"
                     : a->o.compact ? "compact CPU ribbons" : "CPU ribbons",
                     a->o.color3d ? ", 3D colour" : "",
                     a->o.no_shadows      ? ""
                     : a->o.single_shadow ? ", single shadow map"
                                          : ", deep opacity maps",
                     glm_oit_on(a) ? ", OIT" : "",
                     a->o.distance, a->lod,
                     a->drawn, a->info.strand_count, a->cpu_ms, a->draw_ms,
                     a->shadow_ms);
            glfwSetWindowTitle((GLFWwindow *)glc_window(), title);
            title_at = now;
        }
        glc_swap();
    }
    if (ok) glm_report(a, drawn_frames);
    glm_shutdown(a);
    glc_close();
    return ok ? 0 : 1;
}
#endif /* GLM_NO_MAIN */
