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

int main(int argc, char **argv)
{
    const char *out = NULL;
    int headless = 0, frames = 0, i;
    hm_mesh head;
    hm_vertex *skin;
    unsigned char density_px[128 * 128], length_px[128 * 128];
    hf_map density, length;
    hf_fur_desc desc;
    hf_rope_params rope;
    hf_fur *fur;
    hf_fur_info info;
    hf_diag diag;
    hf_mesh skinned;
    float *ribbon_pos;
    uint32_t *indices;
    long long n_idx;
    GLuint prog, vao[2], vbo[2], ibo[2];
    const float eye[3] = {0.0f, 0.06f, 0.55f}, at[3] = {0.0f, -0.01f, 0.0f},
                up[3] = {0.0f, 1.0f, 0.0f};
    float proj[16], view[16], view_proj[16];

    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--headless")) headless = 1;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else {
            fprintf(stderr, "usage: gl_minimal [--headless] [--frames N] [--out FILE.png]\n");
            return 2;
        }
    }
    if (headless ? !glc_open_headless(640, 480)
                 : !glc_open_window(640, 480, "hairfur gl_minimal"))
        return 1;
    if (headless && frames < 1) frames = 1;
    if (frames > 0) glc_set_frame_limit(frames);

    /* grow once: the built-in head with its hairline and bangs maps */
    if (!hm_sphere(24, 32, 0.1f, &head)) return 1;
    hm_hairline_density(density_px, 128, 128);
    hm_bangs_length(length_px, 128, 128);
    memset(&density, 0, sizeof density);
    density.data = density_px; density.width = density.height = 128;
    density.channels = 1;
    length = density;
    length.data = length_px;
    memset(&desc, 0, sizeof desc);
    desc.mesh.positions = head.vertices[0].pos;
    desc.mesh.position_stride = (int)sizeof(hm_vertex);
    desc.mesh.normals = head.vertices[0].normal;
    desc.mesh.normal_stride = (int)sizeof(hm_vertex);
    desc.mesh.uvs = head.vertices[0].uv;
    desc.mesh.uv_stride = (int)sizeof(hm_vertex);
    desc.mesh.vertex_count = head.vertex_count;
    desc.mesh.indices = head.indices;
    desc.mesh.triangle_count = head.triangle_count;
    desc.density_map = &density;
    desc.length_map = &length;
    desc.max_length = 0.12f;
    desc.total_strands = 20000;
    desc.clump = 0.2f;
    hf_rope_params_init(&rope); /* a little stiffness: strands do not fold */
    rope.local_stiffness_root = 0.3f;
    rope.local_stiffness_tip = 0.05f;
    rope.root_stiffness = 0.5f;
    desc.rope_params = &rope;
    if (hf_fur_create(&desc, &fur, &diag) != HF_OK) {
        fprintf(stderr, "gl_minimal: %s\n", diag.message);
        return 1;
    }
    hf_fur_get_info(fur, &info);

    /* CPU buffers: the skinned mesh and one position per ribbon vertex */
    skin = (hm_vertex *)malloc(sizeof(hm_vertex) * (size_t)head.vertex_count);
    ribbon_pos = (float *)malloc(sizeof(float) * 6u * (size_t)info.strand_count *
                                 (size_t)info.points_per_strand);
    n_idx = hf_ribbon_index_count(info.strand_count, info.points_per_strand,
                                  HF_TRIANGLES);
    indices = (uint32_t *)malloc(sizeof(uint32_t) * (size_t)n_idx);
    if (!skin || !ribbon_pos || !indices ||
        hf_ribbon_indices(info.strand_count, info.points_per_strand,
                          HF_TRIANGLES, indices, n_idx) != HF_OK)
        return 1;
    memcpy(skin, head.vertices, sizeof(hm_vertex) * (size_t)head.vertex_count);
    skinned = desc.mesh;
    skinned.positions = skin[0].pos;
    skinned.normals = skin[0].normal;

    /* GL objects: [0] the hair (streamed positions, static indices),
       [1] the head (the same skinned vertices the roots come from) */
    prog = glc_program(vs_src, fs_src, "flat");
    if (!prog) return 1;
    glGenVertexArrays(2, vao);
    glGenBuffers(2, vbo);
    glGenBuffers(2, ibo);
    glBindVertexArray(vao[0]);
    glBindBuffer(GL_ARRAY_BUFFER, vbo[0]);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6u *
                 (size_t)info.strand_count * (size_t)info.points_per_strand),
                 NULL, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, (void *)0);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo[0]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(4 * n_idx), indices,
                 GL_STATIC_DRAW);
    glBindVertexArray(vao[1]);
    glBindBuffer(GL_ARRAY_BUFFER, vbo[1]);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(hm_vertex) *
                 (size_t)head.vertex_count), NULL, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, (GLsizei)sizeof(hm_vertex),
                          (void *)0);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(12 * head.triangle_count),
                 head.indices, GL_STATIC_DRAW);
    glc_mat4_perspective(proj, 0.7f, 640.0f / 480.0f, 0.05f, 10.0f);
    glc_mat4_look_at(view, eye, at, up);
    glc_mat4_mul(view_proj, proj, view);
    glEnable(GL_DEPTH_TEST);

    while (!glc_should_close()) {
        float m[12];
        hf_collider col;
        hf_ribbon_params rp;
        hf_ribbon_output ro;
        const int n = info.drawn_strand_count;
        hf_result r;
        head_pose((glc_frame_index() + 1) / 60.0, m);
        for (i = 0; i < head.vertex_count; ++i) {
            xform(m, head.vertices[i].pos, 1.0f, skin[i].pos);
            xform(m, head.vertices[i].normal, 0.0f, skin[i].normal);
        }
        /* the skull, a little outside the drawn skin so that hair lying on
           the scalp is not buried in the sphere's flat triangles */
        memset(&col, 0, sizeof col);
        col.type = HF_COLLIDER_SPHERE;
        col.a[0] = m[3];
        col.radius = 0.1015f;
        memset(&rp, 0, sizeof rp);
        memcpy(rp.eye, eye, sizeof rp.eye);
        rp.root_width = 0.0012f; /* metres: the head is 0.1 m */
        rp.tip_width = 0.0003f;
        memset(&ro, 0, sizeof ro);
        ro.position.data = ribbon_pos;
        r = hf_fur_set_roots(fur, &skinned, 0, info.guide_count);
        if (!r) r = hf_fur_simulate(fur, 0, info.guide_count, 1.0f / 60.0f, &col, 1);
        if (!r) r = hf_fur_interpolate_guides(fur, 0, info.lod_guide_count);
        if (!r) r = hf_fur_interpolate(fur, 0, n);
        if (!r) r = hf_fur_ribbons(fur, 0, n, &rp, &ro);
        if (r) {
            fprintf(stderr, "gl_minimal: %s\n", hf_result_string(r));
            return 1;
        }
        glc_begin_frame();
        glClearColor(0.16f, 0.17f, 0.20f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glUseProgram(prog);
        glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1,
                           GL_FALSE, view_proj);
        glBindVertexArray(vao[1]);
        glBindBuffer(GL_ARRAY_BUFFER, vbo[1]);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(hm_vertex) *
                        (size_t)head.vertex_count), skin);
        glUniform3f(glGetUniformLocation(prog, "u_color"), 0.80f, 0.62f, 0.52f);
        glDrawElements(GL_TRIANGLES, 3 * head.triangle_count, GL_UNSIGNED_INT, 0);
        glBindVertexArray(vao[0]);
        glBindBuffer(GL_ARRAY_BUFFER, vbo[0]);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(float) * 6u *
                        (size_t)n * (size_t)info.points_per_strand), ribbon_pos);
        glUniform3f(glGetUniformLocation(prog, "u_color"), 0.36f, 0.22f, 0.12f);
        glDrawElements(GL_TRIANGLES, (GLsizei)(6 * (info.points_per_strand - 1) * n),
                       GL_UNSIGNED_INT, 0);
        /* the last frame of --frames N goes to the PNG */
        if (out && glc_frame_index() + 1 == frames && !glc_save_png(out))
            return 1;
        glc_swap();
    }
    if (out) printf("gl_minimal: %ld frames, %d strands; wrote %s\n",
                    glc_frame_index(), info.drawn_strand_count, out);
    hf_fur_destroy(fur);
    hm_free(&head);
    free(skin);
    free(ribbon_pos);
    free(indices);
    glc_close();
    return 0;
}
