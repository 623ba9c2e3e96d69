/* gl_misc_test.c - the parts of gl_common.h that gl_smoke does not cover:
 * error messages (no display for a window, bad shader, bad link, missing
 * file, double open), the frame loop, the mat4 helpers, MSAA on/off.
 * Exit 0 if every check holds, 1 otherwise, 2 if headless GL is missing. */
#define GLC_IMPLEMENTATION
#include "gl_common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int fails = 0;
#define CHECK(c) do { if (!(c)) { printf("FAIL %s:%d: %s\n", __FILE__, \
    __LINE__, #c); fails++; } else printf("ok   %s\n", #c); } while (0)

static int near(float a, float b) { return fabsf(a - b) < 1e-5f; }

int main(void)
{
    const char *good_vs = "#version 330 core\nvoid main(){gl_Position=vec4(0);}\n";
    const char *bad_fs = "#version 330 core\nout vec4 o;\nvoid main(){o = vec4(undeclared);}\n";
    const char *fs_no_main = "#version 330 core\nout vec4 o;\nvoid f(){o = vec4(1);}\n";
    float m[16], a[16], b[16], r[4];
    const float eye[3] = {1, 2, 3}, ctr[3] = {1, 2, 0}, up[3] = {0, 1, 0};
    const float v[3] = {1, 2, -2};
    char info[512];
    unsigned char px[16 * 16 * 4];
    int i, ok;

    /* a window cannot open here (no DISPLAY): clean failure, named */
    ok = glc_open_window(64, 64, "test");
    printf("     glc_open_window -> %d, \"%s\"\n", ok, glc_error());
    CHECK(ok == 0 || getenv("DISPLAY") != NULL);
    if (!ok) CHECK(strstr(glc_error(), "glfwInit failed") != NULL);

    /* probe: works, and reports what it found */
    ok = glc_probe_headless(info, sizeof info);
    printf("     probe: %s\n", info);
    if (!ok) { printf("SKIP: %s\n", info); return 2; }
    CHECK(strstr(info, "|") != NULL);

    CHECK(glc_open_headless(0, 10) == 0);
    CHECK(strstr(glc_error(), "bad size") != NULL);

    /* single-sampled target; then double open refused; probe refused */
    CHECK(glc_open_headless_ex(16, 16, 1) == 1);
    CHECK(glc_samples() == 1 && glc_width() == 16 && glc_height() == 16);
    CHECK(glc_is_headless() == 1);
    CHECK(glc_open_headless(16, 16) == 0);
    CHECK(strstr(glc_error(), "already open") != NULL);
    CHECK(glc_probe_headless(info, sizeof info) == 0);

    /* shader errors: 0 and the info log in the message */
    printf("---- expected errors follow\n");
    CHECK(glc_program(good_vs, bad_fs, "bad_fs") == 0);
    CHECK(strstr(glc_error(), "fragment shader 'bad_fs' failed to compile") != NULL);
    CHECK(strstr(glc_error(), "undeclared") != NULL);
    CHECK(glc_program(good_vs, fs_no_main, "link") == 0);
    CHECK(strstr(glc_error(), "failed to link") != NULL);
    CHECK(glc_read_text_file("/nonexistent/x.glsl") == NULL);
    CHECK(strstr(glc_error(), "No such file") != NULL);
    printf("---- end of expected errors\n");
    CHECK(glc_check_gl("after errors") == 1);

    /* frame loop: headless default is one frame; limit settable */
    CHECK(glc_should_close() == 0);
    CHECK(glc_time() == 0.0);
    glc_swap();
    CHECK(glc_should_close() == 1);
    glc_set_frame_limit(10);
    for (i = 0; !glc_should_close(); i++) glc_swap();
    CHECK(i == 9 && glc_frame_index() == 10);
    CHECK(near((float)glc_time(), 10.0f / 60.0f));

    /* readback row order on a single-sampled target: clear bottom half
     * with scissor, row 0 of the image (top) must stay the other colour */
    glc_begin_frame();
    glClearColor(0, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 16, 4);   /* GL bottom 4 rows */
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    CHECK(glc_read_rgba(px) == 1);
    CHECK(px[0] == 0 && px[2] == 255);                       /* top: blue */
    CHECK(px[(15 * 16) * 4] == 255 && px[(15 * 16) * 4 + 2] == 0); /* bottom: red */
    CHECK(px[(11 * 16) * 4] == 0 && px[(12 * 16) * 4] == 255);
    glc_close();
    CHECK(glc_is_headless() == 0 && glc_width() == 0);
    glc_close(); /* twice is fine */

    /* mat4 */
    glc_mat4_identity(a);
    glc_mat4_look_at(m, eye, ctr, up); /* looks down -z from (1,2,3) */
    glc_mat4_transform(r, m, v);      /* (1,2,-2) is 5 in front */
    CHECK(near(r[0], 0) && near(r[1], 0) && near(r[2], -5) && near(r[3], 1));
    glc_mat4_mul(b, a, m);
    for (i = 0; i < 16 && b[i] == m[i]; i++) {}
    CHECK(i == 16);
    glc_mat4_perspective(a, 1.5707963f, 2.0f, 1.0f, 3.0f);
    { const float p1[3] = {0, 0, -1}, p3[3] = {0, 0, -3}, pe[3] = {2, 1, -1};
      glc_mat4_transform(r, a, p1);
      CHECK(near(r[2] / r[3], -1.0f));       /* near plane -> -1 */
      glc_mat4_transform(r, a, p3);
      CHECK(near(r[2] / r[3], 1.0f));        /* far plane -> +1 */
      glc_mat4_transform(r, a, pe);          /* 90 deg fovy, aspect 2 */
      CHECK(near(r[0] / r[3], 1.0f) && near(r[1] / r[3], 1.0f)); }
    glc_mat4_mul(b, a, m);                    /* alias-safe */
    glc_mat4_mul(a, a, m);
    CHECK(memcmp(a, b, sizeof a) == 0);
    glc_mat4_ortho(a, -2, 2, -1, 1, 0, 10);
    { const float p[3] = {2, -1, -10}; glc_mat4_transform(r, a, p);
      CHECK(near(r[0], 1) && near(r[1], -1) && near(r[2], 1) && near(r[3], 1)); }

    printf("%d failed\n", fails);
    return fails ? 1 : 0;
}
