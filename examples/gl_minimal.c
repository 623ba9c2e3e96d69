/* gl_minimal.c - the smallest complete integration of hairfur.h with OpenGL.

   Shows what an engine has to do, and nothing more: a GL 3.3 core context
   (a GLFW window, or headless through EGL), an hf_fur grown once on the
   built-in head (examples/head_mesh.h), and every frame
       skin the mesh -> hf_fur_set_roots -> hf_fur_simulate ->
       hf_fur_interpolate_guides -> hf_fur_interpolate -> hf_fur_ribbons ->
       glBufferSubData -> glDrawElements
   with one flat colour for the hair and another for the head. The index
   buffer is made once (hf_ribbon_indices): the topology never changes.

   Build: make build/gl_minimal   (see the Makefile), or by hand from the repo root:
     make build/glad/gl.o
     gcc -std=c99 -O2 -Ibuild/glad/include -Iexamples -I. examples/gl_minimal.c \
         build/glad/gl.o -o build/gl_minimal -lglfw -lEGL -lm
   Run:  build/gl_minimal                       (window; Esc quits)
         build/gl_minimal --headless --frames 60 --out out/minimal.png */
#define GLC_IMPLEMENTATION
#include "gl_common.h"
#define HAIRFUR_IMPLEMENTATION
#include "hairfur.h"
#define HEAD_MESH_IMPLEMENTATION
#include "head_mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *vs_src =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a_pos;\n"
    "uniform mat4 u_view_proj;\n"
    "void main() { gl_Position = u_view_proj * vec4(a_pos, 1.0); }\n";
static const char *fs_src =
    "#version 330 core\n"
    "uniform vec3 u_color;\n"
    "out vec4 o_color;\n"
    "void main() { o_color = vec4(u_color, 1.0); }\n";

/* The head swings sideways and turns, so the physics has something to do:
   a rigid transform, rows of 3x4. */
static void head_pose(double t, float m[12])
{
    double yaw = 0.436 * sin(3.14159265358979 * t);
    double dx = 0.05 * sin(2.0 * 3.14159265358979 * t);
    float c = (float)cos(yaw), s = (float)sin(yaw);
    float r[12] = {0};
    r[0] = c; r[2] = s; r[3] = (float)dx; r[5] = 1; r[8] = -s; r[10] = c;
    memcpy(m, r, sizeof r);
}

static void xform(const float m[12], const float *p, float w, float *o)
{
    int k;
    for (k = 0; k < 3; ++k)
        o[k] = m[4 * k] * p[0] + m[4 * k + 1] * p[1] + m[4 * k + 2] * p[2] +
               m[4 * k + 3] * w;
}

/* What the program holds: the head, the fur, the CPU and GL buffers. */
typedef struct gm_app {
    hm_mesh head;
    hm_vertex *skin;      /* the head this frame: roots and drawing */
    unsigned char density_px[128 * 128], length_px[128 * 128];
    hf_map density, length;
    hf_rope_params rope;
    hf_fur_desc desc;
    hf_fur *fur;
    hf_fur_info info;
    hf_mesh skinned;
    float *ribbon_pos;    /* one position per ribbon vertex */
    uint32_t *indices;
    long long n_idx;
    GLuint prog, vao[2], vbo[2], ibo[2];
    float view_proj[16];
} gm_app;

static const float gm_eye[3] = {0.0f, 0.06f, 0.55f};

/* Grow once: the built-in head with its hairline and bangs maps. */
static int grow(gm_app *a)
{
    hf_fur_desc *desc = &a->desc;
    hf_diag diag;
    if (!hm_sphere(24, 32, 0.1f, &a->head)) return 0;
    hm_hairline_density(a->density_px, 128, 128);
    hm_bangs_length(a->length_px, 128, 128);
    memset(&a->density, 0, sizeof a->density);
    a->density.data = a->density_px; a->density.width = a->density.height = 128;
    a->density.channels = 1;
    a->length = a->density;
    a->length.data = a->length_px;
    memset(desc, 0, sizeof *desc);
    desc->mesh.positions = a->head.vertices[0].pos;
    desc->mesh.position_stride = (int)sizeof(hm_vertex);
    desc->mesh.normals = a->head.vertices[0].normal;
    desc->mesh.normal_stride = (int)sizeof(hm_vertex);
    desc->mesh.uvs = a->head.vertices[0].uv;
    desc->mesh.uv_stride = (int)sizeof(hm_vertex);
    desc->mesh.vertex_count = a->head.vertex_count;
    desc->mesh.indices = a->head.indices;
    desc->mesh.triangle_count = a->head.triangle_count;
    desc->density_map = &a->density;
    desc->length_map = &a->length;
    desc->max_length = 0.12f;
    desc->total_strands = 20000;
    desc->clump = 0.2f;
    hf_rope_params_init(&a->rope); /* a little stiffness: strands do not fold */
    a->rope.local_stiffness_root = 0.3f;
    a->rope.local_stiffness_tip = 0.05f;
    a->rope.root_stiffness = 0.5f;
    desc->rope_params = &a->rope;
    if (hf_fur_create(desc, &a->fur, &diag) != HF_OK) {
        fprintf(stderr, "gl_minimal: %s\n", diag.message);
        return 0;
    }
    hf_fur_get_info(a->fur, &a->info);
    return 1;
}

/* CPU buffers: the skinned mesh, one position per ribbon vertex, and the
   index buffer, made once (the topology never changes). */
static int make_buffers(gm_app *a)
{
    const hf_fur_info *info = &a->info;
    a->skin = (hm_vertex *)malloc(sizeof(hm_vertex) * (size_t)a->head.vertex_count);
    a->ribbon_pos = (float *)malloc(sizeof(float) * 6u * (size_t)info->strand_count *
                                    (size_t)info->points_per_strand);
    a->n_idx = hf_ribbon_index_count(info->strand_count, info->points_per_strand,
                                     HF_TRIANGLES);
    a->indices = (uint32_t *)malloc(sizeof(uint32_t) * (size_t)a->n_idx);
    if (!a->skin || !a->ribbon_pos || !a->indices ||
        hf_ribbon_indices(info->strand_count, info->points_per_strand,
                          HF_TRIANGLES, a->indices, a->n_idx) != HF_OK)
        return 0;
    memcpy(a->skin, a->head.vertices, sizeof(hm_vertex) * (size_t)a->head.vertex_count);
    a->skinned = a->desc.mesh;
    a->skinned.positions = a->skin[0].pos;
    a->skinned.normals = a->skin[0].normal;
    return 1;
}

/* GL objects: [0] the hair (streamed positions, static indices), [1] the
   head (the same skinned vertices the roots come from); the camera. */
static int make_gl_objects(gm_app *a)
{
    const hf_fur_info *info = &a->info;
    const float at[3] = {0.0f, -0.01f, 0.0f}, up[3] = {0.0f, 1.0f, 0.0f};
    float proj[16], view[16];
    a->prog = glc_program(vs_src, fs_src, "flat");
    if (!a->prog) return 0;
    glGenVertexArrays(2, a->vao);
    glGenBuffers(2, a->vbo);
    glGenBuffers(2, a->ibo);
    glBindVertexArray(a->vao[0]);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo[0]);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6u *
                 (size_t)info->strand_count * (size_t)info->points_per_strand),
                 NULL, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, (void *)0);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo[0]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(4 * a->n_idx), a->indices,
                 GL_STATIC_DRAW);
    glBindVertexArray(a->vao[1]);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo[1]);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(hm_vertex) *
                 (size_t)a->head.vertex_count), NULL, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, (GLsizei)sizeof(hm_vertex),
                          (void *)0);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, a->ibo[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(12 * a->head.triangle_count),
                 a->head.indices, GL_STATIC_DRAW);
    glc_mat4_perspective(proj, 0.7f, 640.0f / 480.0f, 0.05f, 10.0f);
    glc_mat4_look_at(view, gm_eye, at, up);
    glc_mat4_mul(a->view_proj, proj, view);
    glEnable(GL_DEPTH_TEST);
    return 1;
}

/* One frame on the CPU: skin the head, then roots, ropes, guides, strands
   and ribbons into ribbon_pos. */
static hf_result step(gm_app *a)
{
    float m[12];
    hf_collider col;
    hf_ribbon_params rp;
    hf_ribbon_output ro;
    const int n = a->info.drawn_strand_count;
    hf_result r;
    int i;
    head_pose((glc_frame_index() + 1) / 60.0, m);
    for (i = 0; i < a->head.vertex_count; ++i) {
        xform(m, a->head.vertices[i].pos, 1.0f, a->skin[i].pos);
        xform(m, a->head.vertices[i].normal, 0.0f, a->skin[i].normal);
    }
    /* the skull, a little outside the drawn skin so that hair lying on
       the scalp is not buried in the sphere's flat triangles */
    memset(&col, 0, sizeof col);
    col.type = HF_COLLIDER_SPHERE;
    col.a[0] = m[3];
    col.radius = 0.1015f;
    memset(&rp, 0, sizeof rp);
    memcpy(rp.eye, gm_eye, sizeof rp.eye);
    rp.root_width = 0.0012f; /* metres: the head is 0.1 m */
    rp.tip_width = 0.0003f;
    memset(&ro, 0, sizeof ro);
    ro.position.data = a->ribbon_pos;
    r = hf_fur_set_roots(a->fur, &a->skinned, 0, a->info.guide_count);
    if (!r) r = hf_fur_simulate(a->fur, 0, a->info.guide_count, 1.0f / 60.0f, &col, 1);
    if (!r) r = hf_fur_interpolate_guides(a->fur, 0, a->info.lod_guide_count);
    if (!r) r = hf_fur_interpolate(a->fur, 0, n);
    if (!r) r = hf_fur_ribbons(a->fur, 0, n, &rp, &ro);
    return r;
}

/* Draw the frame: the head's skinned vertices and the ribbons uploaded,
   each drawn in its flat colour. */
static void draw(const gm_app *a)
{
    const int n = a->info.drawn_strand_count;
    glc_begin_frame();
    glClearColor(0.16f, 0.17f, 0.20f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(a->prog);
    glUniformMatrix4fv(glGetUniformLocation(a->prog, "u_view_proj"), 1,
                       GL_FALSE, a->view_proj);
    glBindVertexArray(a->vao[1]);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo[1]);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(hm_vertex) *
                    (size_t)a->head.vertex_count), a->skin);
    glUniform3f(glGetUniformLocation(a->prog, "u_color"), 0.80f, 0.62f, 0.52f);
    glDrawElements(GL_TRIANGLES, 3 * a->head.triangle_count, GL_UNSIGNED_INT, 0);
    glBindVertexArray(a->vao[0]);
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo[0]);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(float) * 6u *
                    (size_t)n * (size_t)a->info.points_per_strand), a->ribbon_pos);
    glUniform3f(glGetUniformLocation(a->prog, "u_color"), 0.36f, 0.22f, 0.12f);
    glDrawElements(GL_TRIANGLES, (GLsizei)(6 * (a->info.points_per_strand - 1) * n),
                   GL_UNSIGNED_INT, 0);
}

int main(int argc, char **argv)
{
    const char *out = NULL;
    int headless = 0, frames = 0, i;
    static gm_app app; /* static: its maps' pixels are 32 KB */
    gm_app *a = &app;

    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--headless")) {
            headless = 1;
        } else if (!strcmp(argv[i], "--frames") && i + 1 < argc) {
            char *end;
            long v = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || v < 1 || v > 1000000) {
                fprintf(stderr, "gl_minimal: --frames wants a whole number "
                                "in [1, 1000000], not '%s'\n", argv[i]);
                return 2;
            }
            frames = (int)v;
        } else if (!strcmp(argv[i], "--out") && i + 1 < argc) {
            out = argv[++i];
        } else {
            int help = !strcmp(argv[i], "--help") || !strcmp(argv[i], "-h");
            fprintf(help ? stdout : stderr,
                    "usage: gl_minimal [--headless] [--frames N] "
                    "[--out FILE.png]\n"
                    "  the built-in head's fur, simulated and drawn in flat "
                    "colours (640 x 480)\n"
                    "  --headless    no window: render through EGL "
                    "(one frame unless --frames)\n"
                    "  --frames N    stop after N frames (default: until "
                    "the window closes)\n"
                    "  --out F.png   write the last of the N frames to F.png "
                    "(needs --frames\n"
                    "                or --headless; default: no file)\n");
            return help ? 0 : 2;
        }
    }
    if (out && !headless && frames < 1) {
        fprintf(stderr, "gl_minimal: --out writes the last of --frames N; "
                        "give --frames or --headless\n");
        return 2;
    }
    if (headless ? !glc_open_headless(640, 480)
                 : !glc_open_window(640, 480, "hairfur gl_minimal"))
        return 1;
    if (headless && frames < 1) frames = 1;
    if (frames > 0) glc_set_frame_limit(frames);
    if (!grow(a) || !make_buffers(a) || !make_gl_objects(a)) return 1;

    while (!glc_should_close()) {
        hf_result r = step(a);
        if (r) {
            fprintf(stderr, "gl_minimal: %s\n", hf_result_string(r));
            return 1;
        }
        draw(a);
        /* the last frame of --frames N goes to the PNG */
        if (out && glc_frame_index() + 1 == frames && !glc_save_png(out))
            return 1;
        glc_swap();
    }
    if (out) printf("gl_minimal: %ld frames, %d strands; wrote %s\n",
                    glc_frame_index(), a->info.drawn_strand_count, out);
    hf_fur_destroy(a->fur);
    hm_free(&a->head);
    free(a->skin);
    free(a->ribbon_pos);
    free(a->indices);
    glc_close();
    return 0;
}
