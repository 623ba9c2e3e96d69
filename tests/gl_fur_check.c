/* gl_fur_check.c - headless render test of examples/gl_marschner.c.
 *
 * Grows the fur on the built-in head, simulates 45 frames of the swinging
 * head (CPU only), then renders the same state three times through EGL:
 * head only (hair off: the mask of where hair is), Marschner, and the same
 * with the specular term off (diffuse + ambient). Checks:
 *   1. coverage: in the scalp region (the head's projected disc above its
 *      centre) most pixels differ from the head-only render, and those hair
 *      pixels are hair-coloured (brown: red > green > blue);
 *   2. highlight: over hair pixels, the Marschner render is brighter than
 *      the diffuse-only one somewhere by a clear margin (max luminance
 *      difference), and brighter on average;
 *   3. not uniform: the standard deviation of luminance over the image.
 * Each check also runs on negative controls (a blank image, the
 * diffuse-only render compared with itself, the head-only render as if it
 * were hair) and must reject them, so the checks are shown to be able to
 * fail every time the test runs.
 *
 * Usage: gl_fur_check [--out-dir DIR] [--sabotage blank|nospec]
 *   --out-dir DIR  also write DIR/fur_check_{spec,diffuse,head}.png
 *   --sabotage     feed a blank image / the diffuse-only render in place of
 *                  the Marschner one: the test must then FAIL (exit 1)
 * Exit 0 all checks passed, 1 a check failed, 2 "SKIP: reason" (no headless
 * GL). Build: see glex.mk (needs examples/ribbon_expand.glsl only for the
 * GPU-expansion comparison, which it skips with a note if absent). */
#define GLM_NO_MAIN
#include "../examples/gl_marschner.c"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 400, H = 300 };

static int failures = 0;

static void expect(int cond, const char *what, double value)
{
    printf("  %-64s %10.4f  %s\n", what, value, cond ? "ok" : "FAILED");
    if (!cond) failures++;
}

static double lum(const unsigned char *p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

static int differs(const unsigned char *a, const unsigned char *b)
{
    return abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2]) > 24;
}

/* The scalp region: pixels inside the head's projected disc and above its
   projected centre (screen rows are top first). */
typedef struct region { double cx, cy, r; } region;

static region project_head(const glm_app *a)
{
    region g;
    float c[3], top[3], pc[4], pt[4];
    c[0] = a->pose[3]; c[1] = a->pose[7]; c[2] = a->pose[11];
    top[0] = c[0]; top[1] = c[1] + GLM_HEAD_R; top[2] = c[2];
    glc_mat4_transform(pc, a->view_proj, c);
    glc_mat4_transform(pt, a->view_proj, top);
    g.cx = (pc[0] / pc[3] * 0.5 + 0.5) * W;
    g.cy = (1.0 - (pc[1] / pc[3] * 0.5 + 0.5)) * H;
    g.r = g.cy - (1.0 - (pt[1] / pt[3] * 0.5 + 0.5)) * H;
    return g;
}

static int in_scalp(const region *g, int x, int y)
{
    double dx = x + 0.5 - g->cx, dy = y + 0.5 - g->cy;
    return dy < -0.2 * g->r && dx * dx + dy * dy < 0.9 * 0.9 * g->r * g->r;
}

/* Check 1: fraction of scalp pixels that are hair, and that hair's hue. */
static int check_coverage(const unsigned char *img, const unsigned char *head,
                          const region *g, double *frac, double *brown)
{
    long n = 0, hair = 0, brownish = 0;
    int x, y;
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            const unsigned char *p = img + 4 * (y * W + x);
            if (!in_scalp(g, x, y)) continue;
            ++n;
            if (!differs(p, head + 4 * (y * W + x))) continue;
            ++hair;
            if (p[0] > p[1] && p[1] > p[2]) ++brownish;
        }
    *frac = n ? (double)hair / n : 0;
    *brown = hair ? (double)brownish / hair : 0;
    return n > 500 && *frac > 0.6 && *brown > 0.8;
}

/* Check 2: spec - diffuse luminance over hair pixels (hair = differs from
   the head-only render in the diffuse image). */
static int check_highlight(const unsigned char *spec, const unsigned char *diff,
                           const unsigned char *head, double *max_d,
                           double *mean_d)
{
    long n = 0, i;
    double sum = 0, mx = -1e9;
    for (i = 0; i < (long)W * H; ++i) {
        double d;
        if (!differs(diff + 4 * i, head + 4 * i)) continue;
        d = lum(spec + 4 * i) - lum(diff + 4 * i);
        sum += d;
        if (d > mx) mx = d;
        ++n;
    }
    *max_d = n ? mx : 0;
    *mean_d = n ? sum / n : 0;
    return n > 1000 && *max_d > 40.0 && *mean_d > 1.0;
}

/* Check 3: standard deviation of luminance over the whole image. */
static int check_not_uniform(const unsigned char *img, double *sd)
{
    double s = 0, s2 = 0, n = (double)W * H;
    long i;
    for (i = 0; i < (long)W * H; ++i) {
        double l = lum(img + 4 * i);
        s += l;
        s2 += l * l;
    }
    *sd = sqrt(s2 / n - (s / n) * (s / n) > 0 ? s2 / n - (s / n) * (s / n) : 0);
    return *sd > 12.0;
}

static void save(const char *dir, const char *name, const unsigned char *img)
{
    char path[1024];
    if (!dir) return;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (glc_write_png(path, img, W, H)) printf("  wrote %s\n", path);
}

int main(int argc, char **argv)
{
    const char *out_dir = NULL, *sabotage = NULL;
    glm_options o;
    static glm_app app;
    glm_app *a = &app;
    unsigned char *spec, *diff, *head, *gpu, *blank;
    region g;
    double v1, v2, t0;
    int f, i;

    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--out-dir") && i + 1 < argc) out_dir = argv[++i];
        else if (!strcmp(argv[i], "--sabotage") && i + 1 < argc) sabotage = argv[++i];
        else {
            fprintf(stderr, "usage: gl_fur_check [--out-dir DIR] "
                            "[--sabotage blank|nospec]\n");
            return 2;
        }
    }
    if (!glc_open_headless(W, H)) {
        printf("SKIP: %s\n", glc_error());
        return 2;
    }
    printf("gl_fur_check: %s | %s, %dx%d, %d samples\n",
           (const char *)glGetString(GL_RENDERER),
           (const char *)glGetString(GL_VERSION), W, H, glc_samples());
    glm_default_options(&o);
    o.headless = 1;
    o.width = W;
    o.height = H;
    o.strands = 10000;     /* llvmpipe: a frame in about a second */
    o.orbit_speed = 0.0f;
    o.azimuth = 20.0f;
    o.elevation = 15.0f;
    o.distance = 0.6f;
    glc_set_quiet(1);      /* a missing ribbon_expand.glsl is not an error */
    if (!glm_init(a, &o)) {
        printf("FAILED: glm_init\n");
        return 1;
    }
    glc_set_quiet(0);
    spec = (unsigned char *)malloc((size_t)W * H * 4 * 5);
    if (!spec) return 1;
    diff = spec + (size_t)W * H * 4;
    head = diff + (size_t)W * H * 4;
    gpu = head + (size_t)W * H * 4;
    blank = gpu + (size_t)W * H * 4;

    /* 45 frames of physics, the last one with ribbons and uploads */
    for (f = 1; f <= 45; ++f)
        if (!glm_step(a, f / 60.0, 1.0f / 60.0f, f == 45)) return 1;
    t0 = glm_now_ms();
    glm_draw(a);
    glc_read_rgba(spec);
    printf("  Marschner frame: %d strands drawn, CPU %.1f ms, draw + read "
           "%.0f ms\n", a->drawn, a->cpu_ms, glm_now_ms() - t0);
    a->o.specular = 0.0f;
    glm_draw(a);
    glc_read_rgba(diff);
    a->draw_hair = 0;
    glm_draw(a);
    glc_read_rgba(head);
    a->draw_hair = 1;
    a->o.specular = 1.0f;
    memset(blank, 0, (size_t)W * H * 4);
    save(out_dir, "fur_check_spec.png", spec);
    save(out_dir, "fur_check_diffuse.png", diff);
    save(out_dir, "fur_check_head.png", head);
    if (sabotage && !strcmp(sabotage, "blank")) {
        printf("  SABOTAGE: a blank image replaces the Marschner render\n");
        memcpy(spec, blank, (size_t)W * H * 4);
    } else if (sabotage && !strcmp(sabotage, "nospec")) {
        printf("  SABOTAGE: the diffuse-only render replaces the Marschner one\n");
        memcpy(spec, diff, (size_t)W * H * 4);
    }
    g = project_head(a);
    printf("  head at (%.0f, %.0f), radius %.0f px\n", g.cx, g.cy, g.r);

    printf("checks on the render:\n");
    i = check_coverage(spec, head, &g, &v1, &v2);
    expect(i, "scalp pixels covered by hair (fraction > 0.6)", v1);
    expect(i, "of which hair-coloured, r > g > b (fraction > 0.8)", v2);
    i = check_highlight(spec, diff, head, &v1, &v2);
    expect(i, "highlight: max lum(Marschner - diffuse) over hair > 40", v1);
    expect(i, "highlight: mean lum(Marschner - diffuse) over hair > 1", v2);
    i = check_not_uniform(spec, &v1);
    expect(i, "not uniform: std dev of luminance > 12", v1);

    printf("negative controls (each must be rejected):\n");
    expect(!check_coverage(blank, head, &g, &v1, &v2),
           "blank image: coverage check rejects it (hair-coloured)", v2);
    expect(!check_coverage(head, head, &g, &v1, &v2),
           "head-only render: coverage check rejects it", v1);
    expect(!check_highlight(diff, diff, head, &v1, &v2),
           "diffuse-only vs itself: highlight check rejects it", v1);
    expect(!check_highlight(blank, diff, head, &v1, &v2),
           "blank vs diffuse-only: highlight check rejects it", v1);
    expect(!check_not_uniform(blank, &v1), "blank image: uniformity check "
           "rejects it", v1);

    /* the GPU-expansion path draws the same picture from the same state */
    if (a->prog_gpu) {
        long n = 0, same = 0;
        a->o.gpu_expand = 1;
        if (!glm_build(a)) return 1;
        glm_draw(a);
        glc_read_rgba(gpu);
        a->o.gpu_expand = 0;
        for (i = 0; i < W * H; ++i) {
            if (!differs(spec + 4 * i, head + 4 * i) &&
                !differs(gpu + 4 * i, head + 4 * i))
                continue;
            ++n;
            same += !differs(spec + 4 * i, gpu + 4 * i);
        }
        printf("GPU expansion (hf_fur_points + ribbon_expand.glsl):\n");
        v1 = n ? (double)same / n : 0;
        expect(v1 > 0.9, "hair pixels matching the CPU-ribbon "
               "render (fraction > 0.9)", v1);
    } else {
        printf("GPU expansion: skipped (examples/ribbon_expand.glsl not found "
               "from the working directory)\n");
    }
    save(out_dir, "fur_check_gpu.png", gpu);
    glm_shutdown(a);
    glc_close();
    free(spec);
    printf("gl_fur_check: %s\n", failures ? "FAILED" : "all checks passed");
    return failures ? 1 : 0;
}
