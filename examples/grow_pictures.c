/* grow_pictures.c - pictures of the growing stages of hairfur.h (density
   tessellation and strand placement), written as PNG for docs/grow.md.

   Build and run (Debian: apt-get install libstb-dev):

       cc -std=c99 -O2 examples/grow_pictures.c -o build/grow_pictures -lm
       build/grow_pictures docs/images

   Writes into the directory given (default "."):
       grow_tess_uv.png   the tessellated triangles in UV space over the
                          density map (dark = low density)
       grow_roots.png     strand roots over the same map
       grow_samplers.png  2000 roots on one triangle: the 2010 plugin's
                          corner-biased formula, uniform, stratified
       grow_lod.png       the first 5 %, 20 % and 100 % of the strands in LOD
                          order

   The mesh is a flat 6 x 6 grid whose positions equal its UVs, so UV space
   and world space are the same picture. */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAP = 256, IMG = 512, GRID = 6 };

typedef struct image {
    int w, h;
    unsigned char *rgb;
} image;

static image image_new(int w, int h)
{
    image im;
    im.w = w;
    im.h = h;
    im.rgb = (unsigned char *)calloc((size_t)w * (size_t)h * 3, 1);
    return im;
}

static void put(image *im, int x, int y, const unsigned char *c)
{
    unsigned char *p;
    if (x < 0 || y < 0 || x >= im->w || y >= im->h) return;
    /* flip: v = 0 at the bottom, as in a UV layout */
    p = im->rgb + 3 * ((size_t)(im->h - 1 - y) * (size_t)im->w + (size_t)x);
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
}

static void line(image *im, int x0, int y0, int x1, int y1,
                 const unsigned char *c)
{
    int dx = abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
    int dy = -abs(y1 - y0), sy = y0 < y1 ? 1 : -1, err = dx + dy;
    for (;;) {
        int e2 = 2 * err;
        put(im, x0, y0, c);
        if (x0 == x1 && y0 == y1) break;
        if (e2 >= dy) {
            err += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            err += dx;
            y0 += sy;
        }
    }
}

static void dot(image *im, float x, float y, int r, const unsigned char *c)
{
    int cx = (int)x, cy = (int)y, i, j;
    for (j = -r; j <= r; ++j)
        for (i = -r; i <= r; ++i)
            if (i * i + j * j <= r * r) put(im, cx + i, cy + j, c);
}

/* The density map: a soft gradient, two bumps and a bald ellipse. */
static void make_density(float *d)
{
    int x, y;
    for (y = 0; y < MAP; ++y)
        for (x = 0; x < MAP; ++x) {
            float u = ((float)x + 0.5f) / MAP, v = ((float)y + 0.5f) / MAP;
            float a = (u - 0.3f) * (u - 0.3f) + (v - 0.7f) * (v - 0.7f);
            float b = (u - 0.75f) * (u - 0.75f) + (v - 0.3f) * (v - 0.3f);
            float e = ((u - 0.7f) / 0.12f) * ((u - 0.7f) / 0.12f) +
                      ((v - 0.78f) / 0.08f) * ((v - 0.78f) / 0.08f);
            float val = 0.08f + 0.25f * u + 0.9f * expf(-a / 0.015f) +
                        0.6f * expf(-b / 0.03f);
            if (e < 1.0f) val = 0.0f;
            d[y * MAP + x] = val > 1.0f ? 1.0f : val;
        }
}

/* The map, darkened and tinted, as a background at IMG x IMG. */
static void draw_map(image *im, const hf_map *m, int x0, int size)
{
    int x, y;
    for (y = 0; y < size; ++y)
        for (x = 0; x < size; ++x) {
            float s[4];
            unsigned char c[3];
            hf_map_sample_fast(m, ((float)x + 0.5f) / size,
                               ((float)y + 0.5f) / size, s);
            c[0] = (unsigned char)(20 + 90 * s[0]);
            c[1] = (unsigned char)(24 + 100 * s[0]);
            c[2] = (unsigned char)(40 + 110 * s[0]);
            put(im, x0 + x, y, c);
        }
}

static int write_png(const char *dir, const char *name, const image *im)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (!stbi_write_png(path, im->w, im->h, 3, im->rgb, im->w * 3)) {
        fprintf(stderr, "cannot write %s\n", path);
        return 0;
    }
    printf("wrote %s (%d x %d)\n", path, im->w, im->h);
    return 1;
}

static int fail(const char *what, hf_result r)
{
    fprintf(stderr, "%s: %s\n", what, hf_result_string(r));
    return 1;
}

/* The LOD order: prefixes of the same array of roots (5 %, 20 % and all
   n of them) over the density map: grow_lod.png. 0, or main's exit
   code. */
static int draw_lod(const char *dir, const hf_map *dmap, const float *roots,
                    int n)
{
    static const unsigned char root_c[3] = {250, 230, 140};
    image im;
    int i;
    const float frac[3] = {0.05f, 0.2f, 1.0f};
    const int P = 340, gap = 10;
    int p;
    im = image_new(3 * P + 2 * gap, P);
    for (p = 0; p < 3; ++p) {
        int m = (int)(frac[p] * (float)n);
        draw_map(&im, dmap, p * (P + gap), P);
        for (i = 0; i < m; ++i)
            dot(&im, p * (P + gap) + roots[3 * i] * (P - 1),
                roots[3 * i + 1] * (P - 1), 1, root_c);
    }
    if (!write_png(dir, "grow_lod.png", &im)) return 1;
    free(im.rgb);
    return 0;
}

/* Three samplers on one triangle, 2,000 roots each: corner-biased,
   uniform, stratified: grow_samplers.png. 0, or main's exit code. */
static int draw_samplers(const char *dir)
{
    hf_place_params pp;
    hf_result r;
    image im;
    int i, y;
    static const float tp3[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t ti[3] = {0, 1, 2};
    static const int smp[3] = {HF_SAMPLER_CORNER_BIASED,
                                           HF_SAMPLER_UNIFORM,
                                           HF_SAMPLER_STRATIFIED};
    static const unsigned char bg[3] = {30, 34, 52},
                               pt[3] = {250, 230, 140};
    const int P = 340, gap = 10, N = 2000;
    hf_mesh one;
    hf_strand s[2000];
    float rr[2000 * 3];
    int p, j;
    memset(&one, 0, sizeof one);
    one.positions = tp3;
    one.vertex_count = 3;
    one.indices = ti;
    one.triangle_count = 1;
    im = image_new(3 * P + 2 * gap, P);
    for (p = 0; p < 3; ++p) {
        int cnt = 0;
        memset(&pp, 0, sizeof pp);
        pp.total_strands = N;
        pp.sampler = smp[p];
        pp.seed = 3;
        if ((r = hf_place_strands(&one, NULL, &pp, s, N, &cnt, NULL)) !=
            HF_OK)
            return fail("hf_place_strands (one triangle)", r);
        hf_strand_roots(&one, s, cnt, 0, cnt, rr);
        for (y = 0; y < P; ++y)
            for (j = 0; j + y < P; ++j) put(&im, p * (P + gap) + j, y, bg);
        for (i = 0; i < cnt; ++i)
            dot(&im, p * (P + gap) + rr[3 * i] * (P - 1),
                rr[3 * i + 1] * (P - 1), 1, pt);
    }
    if (!write_png(dir, "grow_samplers.png", &im)) return 1;
    free(im.rgb);
    return 0;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    static float density[MAP * MAP];
    float pos[(GRID + 1) * (GRID + 1) * 3], uv[(GRID + 1) * (GRID + 1) * 2];
    uint32_t idx[GRID * GRID * 6];
    hf_mesh mesh, tm;
    hf_map dmap;
    hf_tess_params tp;
    hf_tess_output to;
    hf_place_params pp;
    hf_strand *strands;
    float *roots;
    int x, y, t = 0, n = 0, i, k, rc;
    hf_result r;
    image im;
    static const unsigned char edge[3] = {255, 170, 60},
                               base_edge[3] = {255, 255, 255},
                               root_c[3] = {250, 230, 140};

    if (argc > 1 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        printf("usage: grow_pictures [DIR]\n"
               "  writes grow_tess_uv.png, grow_roots.png, grow_samplers.png "
               "and grow_lod.png\n"
               "  (the growing stages of docs/grow.md) into DIR, an existing "
               "directory\n"
               "  (default .)\n");
        return 0;
    }
    if (argc > 2 || (argc > 1 && argv[1][0] == '-')) {
        fprintf(stderr, "grow_pictures: unknown arguments (see --help)\n");
        return 2;
    }
    /* the mesh: positions = UVs, z = 0 */
    for (y = 0; y <= GRID; ++y)
        for (x = 0; x <= GRID; ++x) {
            int v = y * (GRID + 1) + x;
            uv[2 * v] = (float)x / GRID;
            uv[2 * v + 1] = (float)y / GRID;
            pos[3 * v] = uv[2 * v];
            pos[3 * v + 1] = uv[2 * v + 1];
            pos[3 * v + 2] = 0.0f;
        }
    for (y = 0; y < GRID; ++y)
        for (x = 0; x < GRID; ++x) {
            uint32_t a = (uint32_t)(y * (GRID + 1) + x), b = a + 1,
                     c = a + GRID + 1, d = c + 1;
            idx[t++] = a, idx[t++] = b, idx[t++] = d;
            idx[t++] = a, idx[t++] = d, idx[t++] = c;
        }
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = pos;
    mesh.uvs = uv;
    mesh.vertex_count = (GRID + 1) * (GRID + 1);
    mesh.indices = idx;
    mesh.triangle_count = GRID * GRID * 2;

    make_density(density);
    memset(&dmap, 0, sizeof dmap);
    dmap.data = density;
    dmap.width = dmap.height = MAP;
    dmap.channels = 1;
    dmap.format = HF_MAP_F32;
    dmap.wrap = HF_WRAP_CLAMP;

    /* 1. tessellate: two calls, count then fill */
    memset(&tp, 0, sizeof tp);
    tp.factor = 1500.0f; /* density-1 triangles end below 1/1500 */
    tp.estimator = HF_DENSITY_AREA;
    memset(&to, 0, sizeof to);
    if ((r = hf_tessellate(&mesh, &dmap, &tp, &to)) != HF_OK)
        return fail("hf_tessellate (count)", r);
    to.indices = (uint32_t *)malloc(sizeof(uint32_t) * 3 * to.triangle_count);
    to.positions = (float *)malloc(sizeof(float) * 3 * to.vertex_count);
    to.uvs = (float *)malloc(sizeof(float) * 2 * to.vertex_count);
    to.triangle_capacity = to.triangle_count;
    to.vertex_capacity = to.vertex_count;
    if ((r = hf_tessellate(&mesh, &dmap, &tp, &to)) != HF_OK)
        return fail("hf_tessellate", r);
    printf("tessellation: %d -> %d triangles, %d vertices added, depth %d\n",
           mesh.triangle_count, to.triangle_count, to.added_count, to.depth);

    im = image_new(IMG, IMG);
    draw_map(&im, &dmap, 0, IMG);
    for (i = 0; i < to.triangle_count; ++i)
        for (k = 0; k < 3; ++k) {
            const float *a = to.uvs + 2 * to.indices[3 * i + k];
            const float *b = to.uvs + 2 * to.indices[3 * i + (k + 1) % 3];
            line(&im, (int)(a[0] * (IMG - 1)), (int)(a[1] * (IMG - 1)),
                 (int)(b[0] * (IMG - 1)), (int)(b[1] * (IMG - 1)), edge);
        }
    for (i = 0; i < mesh.triangle_count; ++i)
        for (k = 0; k < 3; ++k) {
            const float *a = uv + 2 * idx[3 * i + k];
            const float *b = uv + 2 * idx[3 * i + (k + 1) % 3];
            line(&im, (int)(a[0] * (IMG - 1)), (int)(a[1] * (IMG - 1)),
                 (int)(b[0] * (IMG - 1)), (int)(b[1] * (IMG - 1)),
                 base_edge);
        }
    if (!write_png(dir, "grow_tess_uv.png", &im)) return 1;

    /* 2. strand roots on the tessellated mesh */
    memset(&tm, 0, sizeof tm);
    tm.positions = to.positions;
    tm.uvs = to.uvs;
    tm.vertex_count = to.vertex_count;
    tm.indices = to.indices;
    tm.triangle_count = to.triangle_count;
    memset(&pp, 0, sizeof pp);
    pp.strands_per_area = 9000.0f;
    pp.sampler = HF_SAMPLER_STRATIFIED;
    pp.estimator = HF_DENSITY_AREA;
    pp.seed = 1;
    if ((r = hf_place_strands(&tm, &dmap, &pp, NULL, 0, &n, NULL)) != HF_OK)
        return fail("hf_place_strands (count)", r);
    strands = (hf_strand *)malloc(sizeof(hf_strand) * (size_t)n);
    roots = (float *)malloc(sizeof(float) * 3 * (size_t)n);
    if ((r = hf_place_strands(&tm, &dmap, &pp, strands, n, &n, NULL)) !=
        HF_OK)
        return fail("hf_place_strands", r);
    hf_strand_roots(&tm, strands, n, 0, n, roots);
    printf("placement: %d strands (%zu bytes each)\n", n, sizeof(hf_strand));
    draw_map(&im, &dmap, 0, IMG);
    for (i = 0; i < n; ++i)
        dot(&im, roots[3 * i] * (IMG - 1), roots[3 * i + 1] * (IMG - 1), 1,
            root_c);
    if (!write_png(dir, "grow_roots.png", &im)) return 1;
    free(im.rgb);

    /* 3. the LOD order; 4. three samplers on one triangle */
    if ((rc = draw_lod(dir, &dmap, roots, n)) != 0 ||
        (rc = draw_samplers(dir)) != 0)
        return rc;
    free(strands);
    free(roots);
    free(to.indices);
    free(to.positions);
    free(to.uvs);
    return 0;
}
