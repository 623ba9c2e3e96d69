/* plot_ropes.c - stretch and settling of a hanging rope, plotted to a PNG.

   A 0.3 m rope of 17 points (16 segments) is released horizontally from a
   fixed root and falls under gravity for 4 s (1/60 s frames, default
   parameters otherwise). It runs with plain Gauss-Seidel distance
   constraints at 1, 2, 4 and 8 iterations and with follow-the-leader
   (FTL, one pass), and plots, per frame, the largest relative stretch of
   any segment (top) and the kinetic energy (bottom), both on log scales.

   Build and run (from examples/):
       cc -O2 plot_ropes.c -o plot_ropes -lm && ./plot_ropes ropes_stretch.png

   With --decay instead, how lively the ropes are at the default
   parameters: a patch of 100 ropes (0.25 to 0.35 m, 17 points, 1 cm
   apart) released horizontally swings for 12 s, and the half-life of its
   swing's energy (kinetic, plus potential above where it comes to rest:
   the envelope of the kinetic energy) is printed for each solver with
   and without hair-hair interaction (a 16^3 grid, volume and friction at
   their defaults), and for FTL at other velocity-correction dampings:
       decay solver=ftl ftl_damping=0.9 grid=off half_life=S
   Needs stb_image_write.h and stb_easy_font.h (Debian: libstb-dev). */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#include <stb/stb_easy_font.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 900, H = 700, P = 17, FRAMES = 240, CURVES = 5 };

static unsigned char img[H][W][3];

static void px(int x, int y, const unsigned char *c)
{
    if (x < 0 || y < 0 || x >= W || y >= H) return;
    memcpy(img[y][x], c, 3);
}

/* Bresenham, 2 pixels thick; `dash` > 0 leaves gaps. */
static void line(int x0, int y0, int x1, int y1, const unsigned char *c,
                 int dash)
{
    int dx = abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
    int dy = -abs(y1 - y0), sy = y0 < y1 ? 1 : -1, e = dx + dy, n = 0;
    for (;;) {
        if (!dash || (n / dash) % 2 == 0) {
            px(x0, y0, c);
            px(x0, y0 + 1, c);
        }
        ++n;
        if (x0 == x1 && y0 == y1) break;
        {
            int e2 = 2 * e; /* once, before either update */
            if (e2 >= dy) { e += dy; x0 += sx; }
            if (e2 <= dx) { e += dx; y0 += sy; }
        }
    }
}

static void box(int x0, int y0, int x1, int y1, const unsigned char *c)
{
    int x, y;
    for (y = y0; y < y1; ++y)
        for (x = x0; x < x1; ++x) px(x, y, c);
}

/* Text with stb_easy_font (quads, axis-aligned), scaled 2x. */
static void text(int x, int y, const char *s, const unsigned char *c)
{
    static char buf[60000];
    int q, n = stb_easy_font_print(0, 0, (char *)s, NULL, buf, sizeof buf);
    for (q = 0; q < n; ++q) {
        const float *v = (const float *)(buf + q * 64); /* 4 vertices x 16 B */
        box(x + (int)(2 * v[0]), y + (int)(2 * v[1]), x + (int)(2 * v[8]),
            y + (int)(2 * v[9]), c);
    }
}

typedef struct panel {
    int x0, y0, x1, y1; /* pixels */
    double lo, hi;      /* log10 range */
} panel;

static int py(const panel *p, double v)
{
    double l = log10(v > 1e-30 ? v : 1e-30);
    if (l < p->lo) l = p->lo;
    if (l > p->hi) l = p->hi;
    return p->y1 - (int)((l - p->lo) / (p->hi - p->lo) * (p->y1 - p->y0));
}

static void axes(const panel *p, const char *title)
{
    static const unsigned char grey[3] = {200, 200, 200}, ink[3] = {0, 0, 0};
    char lab[32];
    int d, s;
    for (d = (int)p->lo; d <= (int)p->hi; ++d) {
        int y = py(p, pow(10.0, d));
        line(p->x0, y, p->x1, y, grey, 0);
        snprintf(lab, sizeof lab, "1e%d", d);
        text(p->x0 - 50, y - 7, lab, ink);
    }
    for (s = 0; s <= FRAMES / 60; ++s) {
        int x = p->x0 + s * 60 * (p->x1 - p->x0) / FRAMES;
        line(x, p->y0, x, p->y1, grey, 0);
        snprintf(lab, sizeof lab, "%d s", s);
        text(x - 8, p->y1 + 8, lab, ink);
    }
    line(p->x0, p->y0, p->x0, p->y1, ink, 0);
    line(p->x0, p->y1, p->x1, p->y1, ink, 0);
    text(p->x0 + 10, p->y0 - 22, title, ink);
}

static double stretch[CURVES][FRAMES], energy[CURVES][FRAMES];

static void simulate(int curve, int solver, int iterations)
{
    const float root[3] = {0, 0, 0}, nrm[3] = {1, 0, 0}, tan[3] = {0, 0, 1};
    float rest[3 * P], a[3 * P], b[3 * P];
    size_t size;
    void *mem;
    hf_ropes ro;
    hf_rope_params p;
    int j, f;
    if (hf_ropes_memory_size(1, P, &size) != HF_OK) exit(1);
    mem = malloc(size);
    if (!mem || hf_ropes_init(&ro, 1, P, mem, size) != HF_OK) exit(1);
    for (j = 0; j < P; ++j) {
        rest[3 * j] = 0.3f * j / (P - 1);
        rest[3 * j + 1] = rest[3 * j + 2] = 0.0f;
    }
    hf_ropes_set_rest(&ro, 0, 1, rest, 0, root, nrm, tan, 0);
    hf_rope_params_init(&p);
    p.solver = solver;
    p.iterations = iterations;
    hf_ropes_get_positions(&ro, 0, 1, a, 0);
    for (f = 0; f < FRAMES; ++f) {
        float st;
        double e = 0.0;
        memcpy(b, a, sizeof a);
        hf_ropes_step(&ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0);
        hf_ropes_get_positions(&ro, 0, 1, a, 0);
        hf_ropes_max_stretch(&ro, 0, 1, &st);
        for (j = 1; j < P; ++j) { /* unit mass per point */
            double vx = (a[3 * j] - b[3 * j]) * 60.0,
                   vy = (a[3 * j + 1] - b[3 * j + 1]) * 60.0,
                   vz = (a[3 * j + 2] - b[3 * j + 2]) * 60.0;
            e += 0.5 * (vx * vx + vy * vy + vz * vz);
        }
        stretch[curve][f] = st;
        energy[curve][f] = e;
    }
    free(mem);
}

/* --decay: one configuration's energy half-life, seconds: the patch
   hangs at rest, its roots swing 0.1 m sideways and back over 0.5 s, then
   hold still; from there, the time its swing's energy takes to fall to
   an eighth, over three. */
enum { DN = 10, DR = DN * DN, DFRAMES = 780, DSWING = 30 };
static double decay_half_life(int solver, float ftl_damping, int grid)
{
    const float nrm[3] = {0, -1, 0}, tan[3] = {1, 0, 0};
    static float rest[3 * DR * P], root[3 * DR], moved[3 * DR];
    static float nrms[3 * DR], tans[3 * DR];
    static double e[DFRAMES];
    size_t size, gsize = 0;
    void *mem, *gmem = NULL;
    hf_ropes ro;
    hf_grid g;
    hf_rope_params p;
    double floor_e, e0, tb = -1.0;
    int r, j, f, k;
    if (hf_ropes_memory_size(DR, P, &size) != HF_OK) exit(1);
    mem = malloc(size);
    if (!mem || hf_ropes_init(&ro, DR, P, mem, size) != HF_OK) exit(1);
    if (grid) {
        if (hf_grid_memory_size(16, &gsize) != HF_OK) exit(1);
        gmem = malloc(gsize);
        if (!gmem || hf_grid_init(&g, 16, gmem, gsize) != HF_OK) exit(1);
    }
    for (r = 0; r < DR; ++r) {
        const float len = 0.25f + 0.1f * (float)((r * 37) % DR) / (DR - 1);
        root[3 * r] = 0.01f * (float)(r / DN);
        root[3 * r + 1] = 0.0f;
        root[3 * r + 2] = 0.01f * (float)(r % DN);
        for (k = 0; k < 3; ++k) {
            nrms[3 * r + k] = nrm[k];
            tans[3 * r + k] = tan[k];
        }
        for (j = 0; j < P; ++j) {
            float *q = rest + 3 * ((size_t)r * P + (size_t)j);
            q[0] = root[3 * r];
            q[1] = -len * (float)j / (P - 1);
            q[2] = root[3 * r + 2];
        }
    }
    hf_ropes_set_rest(&ro, 0, DR, rest, 0, root, nrms, tans, 0);
    hf_rope_params_init(&p);
    p.solver = solver;
    p.ftl_damping = ftl_damping;
    if (ftl_damping == 0.0f) p.explicit_zero |= HF_ROPE_ZERO_FTL_DAMPING;
    for (f = -120; f < DFRAMES; ++f) { /* 2 s to settle (the grid spreads
                                          the patch), then the swing */
        const size_t n = (size_t)DR * P;
        const int sf = f; /* frames since the swing began */
        const float dx = sf >= 0 && sf < DSWING
                             ? 0.1f * sinf(3.14159265f * (float)(sf + 1) /
                                           (float)DSWING)
                             : 0.0f;
        size_t i;
        double ek = 0.0, ep = 0.0;
        for (r = 0; r < 3 * DR; ++r) moved[r] = root[r] + (r % 3 == 0 ? dx : 0.0f);
        hf_ropes_set_roots(&ro, 0, DR, moved, nrms, tans, 0);
        if (grid) {
            hf_grid_build(&g, &ro, DR, 0, 16);
            hf_ropes_apply_grid(&ro, 0, DR, 1.0f / 60.0f, &p, &g);
        }
        hf_ropes_step(&ro, 0, DR, 1.0f / 60.0f, &p, NULL, 0);
        if (f < 0) continue; /* (the energy is measured from frame 0) */
        for (i = (size_t)DR; i < n; ++i) { /* unit mass a point, roots out */
            double vx = (ro.x[i] - ro.px[i]) * 60.0,
                   vy = (ro.y[i] - ro.py[i]) * 60.0,
                   vz = (ro.z[i] - ro.pz[i]) * 60.0;
            ek += 0.5 * (vx * vx + vy * vy + vz * vz);
            ep += 9.81 * ro.y[i];
        }
        e[f] = ek + ep;
    }
    /* at rest again: the lowest of the last second; a patch that never
       comes to rest (too little damping for the forces) ends above half
       the swing's energy, and has no half-life */
    floor_e = e[DFRAMES - 1];
    for (f = DFRAMES - 60; f < DFRAMES; ++f)
        if (e[f] < floor_e) floor_e = e[f];
    if (floor_e >= e[DSWING] || floor_e > e[0] + 0.5 * (e[DSWING] - e[0])) {
        free(mem);
        free(gmem);
        return -1.0;
    }
    e0 = e[DSWING] - floor_e;
    for (f = DSWING; f < DFRAMES && tb < 0.0; ++f)
        if (e[f] - floor_e <= 0.125 * e0) tb = (f - DSWING) / 60.0;
    free(mem);
    free(gmem);
    return tb >= 0.0 ? tb / 3.0 : -1.0;
}

static int decay(void)
{
    static const struct { int solver; float damping; } cfg[] = {
        {HF_ROPE_SOLVER_FTL, 0.9f}, {HF_ROPE_SOLVER_FTL, 0.5f},
        {HF_ROPE_SOLVER_FTL, 0.0f}, {HF_ROPE_SOLVER_DISTANCE, 0.9f}};
    int c, grid;
    for (c = 0; c < 4; ++c)
        for (grid = 0; grid < 2; ++grid) {
            const int ftl = cfg[c].solver == HF_ROPE_SOLVER_FTL;
            double h = decay_half_life(cfg[c].solver, cfg[c].damping, grid);
            char hl[32];
            if (h >= 0.0) snprintf(hl, sizeof hl, "%.2f s", h);
            else snprintf(hl, sizeof hl, "none (never at rest)");
            printf("decay solver=%s ftl_damping=%s grid=%s half_life=%s\n",
                   ftl ? "ftl" : "distance",
                   ftl ? (cfg[c].damping == 0.9f ? "0.9" : cfg[c].damping == 0.5f ? "0.5" : "0")
                       : "-",
                   grid ? "on" : "off", hl);
        }
    return 0;
}

int main(int argc, char **argv)
{
    static const unsigned char col[CURVES][3] = {
        {220, 30, 30}, {240, 150, 0}, {30, 160, 60}, {40, 80, 230}, {0, 0, 0}};
    static const char *name[CURVES] = {"distance x1", "distance x2",
                                       "distance x4", "distance x8",
                                       "FTL (1 pass)"};
    const char *out = argc > 1 ? argv[1] : "ropes_stretch.png";
    panel top = {90, 50, W - 30, 330, -7.0, 1.0};
    panel bot = {90, 390, W - 30, 640, -6.0, 2.0};
    int c, f;
    if (argc > 1 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        printf("usage: plot_ropes [OUT.png]   stretch and kinetic energy of a "
               "falling rope,\n"
               "                               plotted into OUT.png "
               "(default ropes_stretch.png)\n"
               "       plot_ropes --decay     the half-life of a patch of "
               "ropes' swing, per solver,\n"
               "                               with and without hair-hair "
               "interaction (printed)\n");
        return 0;
    }
    if (argc > 1 && !strcmp(argv[1], "--decay")) return decay();
    if (argc > 2 || (argc > 1 && argv[1][0] == '-')) {
        fprintf(stderr, "plot_ropes: unknown arguments (see --help)\n");
        return 2;
    }
    for (c = 0; c < 4; ++c) simulate(c, HF_ROPE_SOLVER_DISTANCE, 1 << c);
    simulate(4, HF_ROPE_SOLVER_FTL, 1);
    memset(img, 255, sizeof img);
    axes(&top, "max relative stretch (log10)");
    axes(&bot, "kinetic energy, J per kg-point (log10)");
    for (c = 0; c < CURVES; ++c) {
        for (f = 1; f < FRAMES; ++f) {
            int x0 = top.x0 + (f - 1) * (top.x1 - top.x0) / FRAMES;
            int x1 = top.x0 + f * (top.x1 - top.x0) / FRAMES;
            line(x0, py(&top, stretch[c][f - 1]), x1, py(&top, stretch[c][f]),
                 col[c], 0);
            line(x0, py(&bot, energy[c][f - 1]), x1, py(&bot, energy[c][f]),
                 col[c], c == 4 ? 6 : 0);
        }
        /* the legend between the distance solver's curves and FTL's */
        box(top.x1 - 200, top.y0 + 120 + 22 * c, top.x1 - 184,
            top.y0 + 136 + 22 * c, col[c]);
        text(top.x1 - 176, top.y0 + 120 + 22 * c, name[c], col[4]);
        printf("%-14s stretch after 1 frame %.3g, after 1 s %.3g; energy at 4 s %.3g "
               "J\n",
               name[c], stretch[c][0] > 0 ? stretch[c][0] : 0.0,
               stretch[c][60], energy[c][FRAMES - 1]);
    }
    {   /* worst stretch over the run, per curve */
        for (c = 0; c < CURVES; ++c) {
            double m = 0.0;
            for (f = 0; f < FRAMES; ++f)
                if (stretch[c][f] > m) m = stretch[c][f];
            printf("%-14s worst stretch over 4 s: %.3g\n", name[c], m);
        }
    }
    if (!stbi_write_png(out, W, H, 3, img, W * 3)) return 1;
    printf("wrote %s\n", out);
    return 0;
}
