/* gl_ribbon_check.c - compile/link examples/ribbon_expand.glsl on a real
 * GL 3.3 core context, then check it against the CPU path: transform
 * feedback captures v_position / v_tangent / v_texcoord for every ribbon
 * vertex (glDrawArrays(GL_POINTS) with rasterizer discard, so gl_VertexID
 * is the ribbon vertex number) and compares them with hf_ribbons() on the
 * same strands. Finally draws the ribbons with hf_ribbon_indices() and
 * writes a PNG.
 *   usage: gl_ribbon_check path/to/ribbon_expand.glsl [out.png]
 * Exit 0 ok, 1 failed, 2 no headless GL (reason printed). */
#define GLC_IMPLEMENTATION
#include "gl_common.h"
#define HAIRFUR_IMPLEMENTATION
#include "hairfur.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { S = 5, P = 16, NV = S * P * 2 };

static const char *fs_src =
    "#version 330 core\n"
    "in vec3 v_tangent;\n"
    "in vec3 v_texcoord;\n"
    "in vec3 v_position;\n"
    "out vec4 o_color;\n"
    "void main() {\n"
    "    vec3 base = mix(vec3(0.35, 0.2, 0.1), vec3(0.95, 0.8, 0.5),\n"
    "                    v_texcoord.z);\n"
    "    float shade = 0.75 + 0.25 * abs(v_tangent.x);\n"
    "    float tint = 0.9 + 0.1 * fract(v_texcoord.x * 7.0 + v_position.z);\n"
    "    o_color = vec4(base * shade * tint, 1.0);\n"
    "}\n";

static void make_strands(float *pts, float *uv)
{
    int s, j;
    for (s = 0; s < S; s++) {
        float x0 = -0.8f + 0.4f * (float)s;
        uv[2 * s] = (float)s / (float)(S - 1);
        uv[2 * s + 1] = 0.5f;
        for (j = 0; j < P; j++) {
            float t = (float)j / (float)(P - 1);
            float *p = pts + 3 * (s * P + j);
            switch (s) {
            case 0: /* straight, vertical */
                p[0] = x0; p[1] = -0.8f + 1.6f * t; p[2] = 0.0f; break;
            case 1: /* wave in the image plane */
                p[0] = x0 + 0.12f * sinf(6.0f * t); p[1] = -0.8f + 1.6f * t;
                p[2] = 0.0f; break;
            case 2: /* helix: the side vector turns */
                p[0] = x0 + 0.1f * cosf(9.0f * t); p[1] = -0.8f + 1.6f * t;
                p[2] = 0.1f * sinf(9.0f * t); break;
            case 3: /* leans towards the camera */
                p[0] = x0; p[1] = -0.8f + 1.2f * t; p[2] = 0.8f * t; break;
            default: /* droops: curls over */
                p[0] = x0 + 0.3f * t; p[1] = -0.8f + 1.4f * sinf(2.2f * t);
                p[2] = -0.2f * t; break;
            }
        }
    }
}

static GLuint link_tf(const char *vs, const char *fs)
{
    static const char *vary[3] = { "v_position", "v_tangent", "v_texcoord" };
    GLuint v = glc_compile_shader(GL_VERTEX_SHADER, vs, "ribbon_expand.glsl");
    GLuint f = glc_compile_shader(GL_FRAGMENT_SHADER, fs, "ribbon test fs");
    GLuint p;
    GLint ok = 0;
    char log[4096];
    if (!v || !f) return 0;
    p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glTransformFeedbackVaryings(p, 3, vary, GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        glGetProgramInfoLog(p, sizeof log, NULL, log);
        printf("transform-feedback link failed:\n%s\n", log);
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

static void set_uniforms(GLuint prog, const hf_ribbon_params *rp,
                         const float *vp)
{
    glUseProgram(prog);
    glUniform1i(glGetUniformLocation(prog, "u_points"), 0);
    glUniform1i(glGetUniformLocation(prog, "u_root_uv"), 1);
    glUniform1i(glGetUniformLocation(prog, "u_points_per_strand"), P);
    glUniform3fv(glGetUniformLocation(prog, "u_eye"), 1, rp->eye);
    glUniform1i(glGetUniformLocation(prog, "u_orthographic"),
                rp->orthographic);
    glUniform3fv(glGetUniformLocation(prog, "u_view_dir"), 1, rp->view_dir);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1,
                       GL_FALSE, vp);
}

/* Run the shader through transform feedback and compare with hf_ribbons. */
static int compare(GLuint tfprog, const hf_ribbon_strands *st,
                   const hf_ribbon_params *rp, const float *vp,
                   const char *label)
{
    static float cpu_pos[NV * 3], cpu_tan[NV * 3], cpu_tc[NV * 3];
    static float gpu[NV * 9];
    hf_ribbon_output out;
    GLuint tfb, q;
    GLuint prim = 0;
    double dp = 0, dt = 0, dc = 0;
    int i, k, worst = 0;
    memset(&out, 0, sizeof out);
    out.position.data = cpu_pos;
    out.tangent.data = cpu_tan;
    out.texcoord.data = cpu_tc;
    if (hf_ribbons(st, 0, S, rp, &out) != HF_OK) {
        printf("  %s: hf_ribbons failed\n", label);
        return 0;
    }
    set_uniforms(tfprog, rp, vp);
    glGenBuffers(1, &tfb);
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb);
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, sizeof gpu, NULL,
                 GL_STATIC_READ);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, tfb);
    glGenQueries(1, &q);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, q);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, NV);
    glEndTransformFeedback();
    glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    glDisable(GL_RASTERIZER_DISCARD);
    glGetQueryObjectuiv(q, GL_QUERY_RESULT, &prim);
    glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, sizeof gpu, gpu);
    glDeleteQueries(1, &q);
    glDeleteBuffers(1, &tfb);
    if (!glc_check_gl("transform feedback")) return 0;
    for (i = 0; i < NV; i++)
        for (k = 0; k < 3; k++) {
            double a = fabs((double)gpu[9 * i + k] - cpu_pos[3 * i + k]);
            double b = fabs((double)gpu[9 * i + 3 + k] - cpu_tan[3 * i + k]);
            double c = fabs((double)gpu[9 * i + 6 + k] - cpu_tc[3 * i + k]);
            if (a > dp) { dp = a; worst = i; }
            if (b > dt) dt = b;
            if (c > dc) dc = c;
        }
    printf("  %-34s %u vertices captured; max |gpu - cpu|: position %.2e "
           "(vertex %d), tangent %.2e, texcoord %.2e\n", label, prim, dp,
           worst, dt, dc);
    return prim == (GLuint)NV && dp < 1e-5 && dt < 1e-5 && dc < 1e-6;
}

int main(int argc, char **argv)
{
    const char *glsl_path = argc > 1 ? argv[1] : "examples/ribbon_expand.glsl";
    const char *png = argc > 2 ? argv[2] : "out/ribbons.png";
    static float pts[S * P * 3], uv[S * 2], pts4[S * P * 4];
    static uint32_t idx[S * 6 * (P - 1)];
    float proj[16], view[16], vp[16];
    const float eye[3] = {0.3f, 0.2f, 3.0f}, ctr[3] = {0, 0, 0},
                up[3] = {0, 1, 0};
    hf_ribbon_strands st;
    hf_ribbon_params rp;
    char *vs;
    GLuint prog, tfprog, vao, pbuf, uvbuf, tex[2], ebo;
    long long nidx = hf_ribbon_index_count(S, P, HF_TRIANGLES);
    int ok = 1, good;
    unsigned char *img;
    long covered = 0;
    int i;

    if (!glc_open_headless(320, 320)) {
        printf("SKIP: %s\n", glc_error());
        return 2;
    }
    printf("GL_RENDERER = %s, GL_VERSION = %s\n",
           (const char *)glGetString(GL_RENDERER),
           (const char *)glGetString(GL_VERSION));
    vs = glc_read_text_file(glsl_path);
    if (!vs) return 1;

    prog = glc_program(vs, fs_src, glsl_path);
    printf("%s + trivial fragment shader: %s\n", glsl_path,
           prog ? "compiles and links" : "FAILED");
    if (!prog) return 1;
    {
        GLint n = 0, len = 0;
        glGetProgramiv(prog, GL_ACTIVE_UNIFORMS, &n);
        printf("  active uniforms: %d;", (int)n);
        for (i = 0; i < n; i++) {
            char name[64];
            GLint sz;
            GLenum ty;
            glGetActiveUniform(prog, (GLuint)i, sizeof name, &len, &sz, &ty,
                               name);
            printf(" %s", name);
        }
        printf("\n");
    }
    tfprog = link_tf(vs, fs_src);
    if (!tfprog) return 1;

    make_strands(pts, uv);
    memset(&st, 0, sizeof st);
    st.points = pts;
    st.root_uv = uv;
    memset(&rp, 0, sizeof rp);
    rp.points_per_strand = P;
    memcpy(rp.eye, eye, sizeof eye);
    rp.root_width = 0.06f;
    rp.tip_width = 0.01f;
    rp.taper_power = 1.5f;
    if (hf_ribbon_points(&st, 0, S, &rp, pts4) != HF_OK ||
        hf_ribbon_indices(S, P, HF_TRIANGLES, idx, nidx) != HF_OK) {
        printf("hairfur call failed\n");
        return 1;
    }

    glGenVertexArrays(1, &vao); /* no attributes: gl_VertexID only */
    glBindVertexArray(vao);
    glGenBuffers(1, &pbuf);
    glBindBuffer(GL_TEXTURE_BUFFER, pbuf);
    glBufferData(GL_TEXTURE_BUFFER, sizeof pts4, pts4, GL_STREAM_DRAW);
    glGenBuffers(1, &uvbuf);
    glBindBuffer(GL_TEXTURE_BUFFER, uvbuf);
    glBufferData(GL_TEXTURE_BUFFER, sizeof uv, uv, GL_STATIC_DRAW);
    glGenTextures(2, tex);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_BUFFER, tex[0]);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, pbuf);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_BUFFER, tex[1]);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RG32F, uvbuf);

    glc_mat4_perspective(proj, 0.9f, 1.0f, 0.1f, 10.0f);
    glc_mat4_look_at(view, eye, ctr, up);
    glc_mat4_mul(vp, proj, view);

    printf("shader vs hf_ribbons on %d strands x %d points:\n", S, P);
    good = compare(tfprog, &st, &rp, vp, "perspective");
    printf("    -> %s\n", good ? "match" : "MISMATCH");
    ok &= good;
    rp.orthographic = 1;
    rp.view_dir[0] = -0.2f; rp.view_dir[1] = -0.1f; rp.view_dir[2] = -1.0f;
    good = compare(tfprog, &st, &rp, vp, "orthographic");
    printf("    -> %s\n", good ? "match" : "MISMATCH");
    ok &= good;
    rp.orthographic = 0;

    /* draw for real with the index buffer of hf_ribbon_indices */
    glGenBuffers(1, &ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(nidx * 4), idx,
                 GL_STATIC_DRAW);
    glc_begin_frame();
    glClearColor(0.12f, 0.14f, 0.18f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    set_uniforms(prog, &rp, vp);
    glDrawElements(GL_TRIANGLES, (GLsizei)nidx, GL_UNSIGNED_INT, (void *)0);
    glc_swap();
    ok &= glc_check_gl("drawing ribbons");
    img = (unsigned char *)malloc(320 * 320 * 4);
    if (!img || !glc_read_rgba(img)) return 1;
    for (i = 0; i < 320 * 320; i++)
        if (img[4 * i] != 31 || img[4 * i + 1] != 36 || img[4 * i + 2] != 46)
            covered++;
    printf("drew %lld indices: %ld of %d pixels covered\n", nidx, covered,
           320 * 320);
    ok &= covered > 500;
    /* winding: hf_ribbon_indices says counter-clockwise towards the camera,
     * so culling back faces must not lose any pixel */
    {
        long culled = 0;
        unsigned char *img2 = (unsigned char *)malloc(320 * 320 * 4);
        glc_begin_frame();
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glFrontFace(GL_CCW);
        glDrawElements(GL_TRIANGLES, (GLsizei)nidx, GL_UNSIGNED_INT,
                       (void *)0);
        glDisable(GL_CULL_FACE);
        if (!img2 || !glc_read_rgba(img2)) return 1;
        for (i = 0; i < 320 * 320; i++)
            if (img2[4 * i] != 31 || img2[4 * i + 1] != 36 ||
                img2[4 * i + 2] != 46)
                culled++;
        printf("with GL_CULL_FACE(GL_BACK), GL_CCW front: %ld pixels "
               "covered (%s)\n", culled,
               culled == covered ? "same: all triangles face the camera"
                                 : "DIFFERENT: some triangles face away");
        ok &= culled == covered;
        free(img2);
    }
    if (glc_write_png(png, img, 320, 320)) printf("wrote %s\n", png);
    free(img);
    free(vs);
    glc_close();
    printf("%s\n", ok ? "gl_ribbon_check: ok" : "gl_ribbon_check: FAILED");
    return ok ? 0 : 1;
}
