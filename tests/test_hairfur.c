/* test_hairfur.c - the unit tests of hairfur.h, one function per behaviour.

   Build and run: make test (C and C++, -O2 and ASan+UBSan, gcc and clang).
   Prints one line per failed check and ends with "N passed, N failed";
   exits non-zero when anything failed. */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- harness ------------------------------------------------------------ */

static int t_passed, t_failed, t_current_failed;
static const char *t_current;

#define CHECK(cond)                                                            \
    do {                                                                       \
        if (!(cond)) {                                                         \
            printf("%s:%d: %s: CHECK(%s) failed\n", __FILE__, __LINE__,        \
                   t_current, #cond);                                          \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

/* |a - b| <= tol, printing both values when it fails */
#define CHECK_NEAR(a, b, tol)                                                  \
    do {                                                                       \
        double t_a_ = (double)(a), t_b_ = (double)(b);                         \
        if (!(fabs(t_a_ - t_b_) <= (double)(tol))) {                           \
            printf("%s:%d: %s: CHECK_NEAR(%s, %s, %s) failed: %.9g vs %.9g\n", \
                   __FILE__, __LINE__, t_current, #a, #b, #tol, t_a_, t_b_);   \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

#define CHECK_EQ_INT(a, b)                                                     \
    do {                                                                       \
        long long t_a_ = (long long)(a), t_b_ = (long long)(b);                \
        if (t_a_ != t_b_) {                                                    \
            printf("%s:%d: %s: CHECK_EQ_INT(%s, %s) failed: %lld vs %lld\n",   \
                   __FILE__, __LINE__, t_current, #a, #b, t_a_, t_b_);         \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

#define RUN(fn)                                                                \
    do {                                                                       \
        t_current = #fn;                                                       \
        t_current_failed = 0;                                                  \
        fn();                                                                  \
        if (t_current_failed)                                                  \
            ++t_failed;                                                        \
        else                                                                   \
            ++t_passed;                                                        \
    } while (0)

static int t_is_finite(float x) { return x == x && x - x == 0.0f; }

/* A counting allocator: tests prove "no allocation" with it. */
typedef struct t_counter {
    long allocs, frees;
    long fail_after; /* -1: never fail; else fail once allocs reaches it */
} t_counter;

static void *t_alloc(size_t size, void *user)
{
    t_counter *c = (t_counter *)user;
    if (c->fail_after >= 0 && c->allocs >= c->fail_after) return NULL;
    ++c->allocs;
    return malloc(size);
}
static void *t_realloc(void *p, size_t size, void *user)
{
    t_counter *c = (t_counter *)user;
    if (!p) ++c->allocs;
    return realloc(p, size);
}
static void t_free(void *p, void *user)
{
    t_counter *c = (t_counter *)user;
    if (p) ++c->frees;
    free(p);
}
static hf_allocator t_counting(t_counter *c)
{
    hf_allocator a;
    c->allocs = c->frees = 0;
    c->fail_after = -1;
    a.alloc = t_alloc;
    a.realloc = t_realloc;
    a.free = t_free;
    a.user = c;
    return a;
}

/* ======================================================================== */
/* 1. result codes, version                                                 */
/* ======================================================================== */

static void test_result_strings_distinct(void)
{
    static const hf_result codes[] = {
#define T_CODE(name, value, message) name,
        HF_RESULT_TABLE(T_CODE)
#undef T_CODE
    };
    int n = (int)(sizeof codes / sizeof codes[0]), i, j;
    CHECK(n >= 16);
    CHECK_EQ_INT(HF_OK, 0);
    CHECK(strcmp(hf_result_string(HF_OK), "success") == 0);
    for (i = 0; i < n; ++i) {
        const char *s = hf_result_string(codes[i]);
        CHECK(s != NULL && strlen(s) > 5);
        if (i > 0) CHECK(codes[i] < 0);
        for (j = 0; j < i; ++j) {
            CHECK(codes[i] != codes[j]);
            CHECK(strcmp(s, hf_result_string(codes[j])) != 0);
        }
    }
    CHECK(strcmp(hf_result_string((hf_result)-9999), "unknown result code") ==
          0);
}

static void test_version(void)
{
    char buf[32];
    CHECK_EQ_INT(hf_version(), HAIRFUR_VERSION_NUMBER);
    snprintf(buf, sizeof buf, "%d.%d.%d", HAIRFUR_VERSION_MAJOR,
             HAIRFUR_VERSION_MINOR, HAIRFUR_VERSION_PATCH);
    CHECK(strcmp(buf, hf_version_string()) == 0);
}

/* ======================================================================== */
/* 2. random numbers                                                        */
/* ======================================================================== */

static void test_rng_matches_pcg32_reference(void)
{
    /* pcg32-demo from pcg-random.org: pcg32_srandom(42, 54) */
    static const uint32_t expect[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u,
                                       0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    hf_rng r;
    int i;
    hf_rng_seed(&r, 42u, 54u);
    for (i = 0; i < 6; ++i) CHECK_EQ_INT(hf_rng_u32(&r), expect[i]);
}

static void test_rng_streams_and_copies(void)
{
    hf_rng a, b, c;
    int i, same = 0;
    hf_rng_seed(&a, 7u, 1u);
    hf_rng_seed(&b, 7u, 2u);
    c = a;
    for (i = 0; i < 100; ++i) {
        uint32_t x = hf_rng_u32(&a);
        same += x == hf_rng_u32(&b);
        CHECK_EQ_INT(x, hf_rng_u32(&c));
    }
    CHECK(same < 3);
}

static void test_rng_float_and_below_ranges(void)
{
    hf_rng r;
    int i, hist[10] = {0};
    float lo = 1.0f, hi = 0.0f;
    hf_rng_seed(&r, 1u, 0u);
    for (i = 0; i < 100000; ++i) {
        float f = hf_rng_float(&r);
        uint32_t k = hf_rng_below(&r, 10u);
        lo = f < lo ? f : lo;
        hi = f > hi ? f : hi;
        CHECK(k < 10u);
        if (k < 10u) ++hist[k];
    }
    CHECK(lo >= 0.0f && lo < 0.001f);
    CHECK(hi < 1.0f && hi > 0.999f);
    for (i = 0; i < 10; ++i) CHECK(hist[i] > 9500 && hist[i] < 10500);
    CHECK_EQ_INT(hf_rng_below(&r, 0u), 0);
    CHECK_EQ_INT(hf_rng_below(&r, 1u), 0);
}

/* ======================================================================== */
/* 3. maps                                                                  */
/* ======================================================================== */

/* 4 x 2 gray map: row 0 = 0, 51, 102, 153; row 1 = 255, 204, 153, 102 */
static const unsigned char t_map_px[8] = {0, 51, 102, 153, 255, 204, 153, 102};

static hf_map t_gray_map(int wrap)
{
    hf_map m;
    memset(&m, 0, sizeof m);
    m.data = t_map_px;
    m.width = 4;
    m.height = 2;
    m.channels = 1;
    m.wrap = wrap;
    return m;
}

static void test_map_sample_texel_centres_exact(void)
{
    hf_map m = t_gray_map(HF_WRAP_CLAMP);
    float o[4];
    int x, y;
    for (y = 0; y < 2; ++y)
        for (x = 0; x < 4; ++x) {
            CHECK_EQ_INT(hf_map_sample(&m, (x + 0.5f) / 4, (y + 0.5f) / 2, o),
                         HF_OK);
            CHECK(o[0] == (float)t_map_px[y * 4 + x] / 255.0f);
            CHECK(o[1] == 0.0f && o[2] == 0.0f && o[3] == 0.0f);
        }
}

static void test_map_sample_bilinear_midpoints(void)
{
    hf_map m = t_gray_map(HF_WRAP_CLAMP);
    float o[4];
    /* halfway between texels (0,0) and (1,0): (0 + 51) / 2 / 255 = 0.1 */
    hf_map_sample(&m, 0.25f, 0.25f, o);
    CHECK_NEAR(o[0], 0.1f, 1e-6);
    /* centre of the 2x2 block (1..2, 0..1): (51+102+204+153)/4/255 = 0.5 */
    hf_map_sample(&m, 0.5f, 0.5f, o);
    CHECK_NEAR(o[0], 0.5f, 1e-6);
}

static void test_map_wrap_repeat_vs_clamp(void)
{
    hf_map c = t_gray_map(HF_WRAP_CLAMP), r = t_gray_map(HF_WRAP_REPEAT);
    float oc[4], orr[4];
    /* u = 0: clamp gives texel 0 of row 0 exactly (v at row 0's centre);
       repeat blends texel 3 and texel 0: (153 + 0) / 2 / 255 = 0.3 */
    hf_map_sample(&c, 0.0f, 0.25f, oc);
    hf_map_sample(&r, 0.0f, 0.25f, orr);
    CHECK(oc[0] == 0.0f);
    CHECK_NEAR(orr[0], 0.3f, 1e-6);
    /* repeat is periodic, even far away; clamp pins far-out values */
    hf_map_sample(&r, 0.25f + 1000.0f, 0.25f - 3.0f, orr);
    CHECK_NEAR(orr[0], 0.1f, 1e-4);
    hf_map_sample(&c, 1e30f, -1e30f, oc);
    CHECK(oc[0] == 153.0f / 255.0f);
}

static void test_map_f32_multichannel_row_stride(void)
{
    /* 2 x 2, 3 channels, rows padded to 32 bytes */
    float buf[16];
    hf_map m;
    float o[4];
    int i;
    for (i = 0; i < 16; ++i) buf[i] = -100.0f; /* padding */
    buf[0] = 1; buf[1] = 2; buf[2] = 3; buf[3] = 5; buf[4] = 6; buf[5] = 7;
    buf[8] = 9; buf[9] = 10; buf[10] = 11; buf[11] = 13; buf[12] = 14;
    buf[13] = 15;
    memset(&m, 0, sizeof m);
    m.data = buf;
    m.width = 2;
    m.height = 2;
    m.channels = 3;
    m.format = HF_MAP_F32;
    m.row_stride = 32;
    m.wrap = HF_WRAP_CLAMP;
    CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_OK);
    hf_map_sample(&m, 0.75f, 0.75f, o);
    CHECK(o[0] == 13 && o[1] == 14 && o[2] == 15 && o[3] == 0);
    hf_map_sample(&m, 0.5f, 0.5f, o);
    CHECK(o[0] == 7 && o[1] == 8 && o[2] == 9);
}

static void test_map_validate_errors(void)
{
    hf_map m = t_gray_map(HF_WRAP_REPEAT), b;
    hf_diag d;
    float nan_px[4] = {0, 0, 0, 0};
    float o[4] = {42, 42, 42, 42};
    CHECK_EQ_INT(hf_map_validate(&m, &d), HF_OK);
    CHECK(d.result == HF_OK && d.message[0] == 0);
    CHECK_EQ_INT(hf_map_validate(NULL, &d), HF_ERROR_NULL_POINTER);
    b = m; b.data = NULL;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_NULL_POINTER);
    CHECK(strcmp(d.field, "data") == 0);
    b = m; b.width = 0;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_COUNT);
    b = m; b.height = -3;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_COUNT);
    CHECK(strstr(d.message, "-3") != NULL);
    b = m; b.width = HF_MAP_MAX_DIMENSION + 1;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_COUNT);
    b = m; b.channels = 5;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_FORMAT);
    b = m; b.channels = 0;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_FORMAT);
    b = m; b.format = 7;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_FORMAT);
    b = m; b.wrap = 3;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_PARAMETER);
    b = m; b.row_stride = 3;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_STRIDE);
    CHECK(strcmp(d.field, "row_stride") == 0);
    b = m; b.row_stride = -4;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_BAD_STRIDE);
    b = m; b.width = HF_MAP_MAX_DIMENSION; b.height = HF_MAP_MAX_DIMENSION;
    b.row_stride = 0x7fffffff;
    if (sizeof(size_t) == 4)
        CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_OVERFLOW);
    /* a NaN texel in a float map, found at its index */
    nan_px[3] = (float)NAN;
    b = m; b.data = nan_px; b.format = HF_MAP_F32; b.width = 2;
    CHECK_EQ_INT(hf_map_validate(&b, &d), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(d.index, 3);
    /* sample refuses the same, and a non-finite uv, writing nothing */
    CHECK_EQ_INT(hf_map_sample(&b, 0.5f, 0.5f, o), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_map_sample(&m, (float)NAN, 0.5f, o), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_map_sample(&m, 0.5f, (float)INFINITY, o),
                 HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_map_sample(&m, 0.5f, 0.5f, NULL), HF_ERROR_NULL_POINTER);
    CHECK(o[0] == 42 && o[1] == 42 && o[2] == 42 && o[3] == 42);
}

static void test_map_blur_constant_impulse_and_sum(void)
{
    enum { W = 16, H = 8 };
    unsigned char px[W * H];
    float out[W * H], sum = 0.0f;
    hf_map m;
    int i;
    memset(&m, 0, sizeof m);
    m.data = px;
    m.width = W;
    m.height = H;
    m.channels = 1;
    /* constant map stays constant */
    memset(px, 200, sizeof px);
    CHECK_EQ_INT(hf_map_blur(&m, 2.0f, out, NULL), HF_OK);
    for (i = 0; i < W * H; ++i) CHECK_NEAR(out[i], 200.0f / 255.0f, 1e-6);
    /* an impulse spreads symmetrically and (repeat) keeps its sum */
    memset(px, 0, sizeof px);
    px[4 * W + 8] = 255;
    CHECK_EQ_INT(hf_map_blur(&m, 1.0f, out, NULL), HF_OK);
    for (i = 0; i < W * H; ++i) sum += out[i];
    CHECK_NEAR(sum, 1.0f, 1e-5);
    CHECK(out[4 * W + 8] > out[4 * W + 9]);
    CHECK(out[4 * W + 7] == out[4 * W + 9]);
    CHECK(out[3 * W + 8] == out[5 * W + 8]);
    /* peak of a 2D Gaussian sampled at sigma 1 over radius 3:
       (1 / sum_k exp(-k^2/2), k = -3..3)^2 */
    {
        double s1 = 0.0;
        int k;
        for (k = -3; k <= 3; ++k) s1 += exp(-0.5 * k * k);
        CHECK_NEAR(out[4 * W + 8], 1.0 / (s1 * s1), 1e-6);
    }
    /* sigma 0 copies */
    CHECK_EQ_INT(hf_map_blur(&m, 0.0f, out, NULL), HF_OK);
    CHECK(out[4 * W + 8] == 1.0f && out[4 * W + 9] == 0.0f);
}

static void test_map_blur_errors_and_allocator(void)
{
    unsigned char px[4] = {1, 2, 3, 4};
    float out[4] = {-1, -1, -1, -1};
    hf_map m;
    t_counter cnt;
    hf_allocator a = t_counting(&cnt);
    memset(&m, 0, sizeof m);
    m.data = px;
    m.width = 2;
    m.height = 2;
    m.channels = 1;
    CHECK_EQ_INT(hf_map_blur(&m, -1.0f, out, &a), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_map_blur(&m, (float)NAN, out, &a), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_map_blur(&m, 1e6f, out, &a), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_map_blur(&m, 1.0f, NULL, &a), HF_ERROR_NULL_POINTER);
    cnt.fail_after = 0;
    CHECK_EQ_INT(hf_map_blur(&m, 1.0f, out, &a), HF_ERROR_OUT_OF_MEMORY);
    CHECK(out[0] == -1 && out[1] == -1 && out[2] == -1 && out[3] == -1);
    CHECK_EQ_INT(cnt.allocs, 0);
    cnt.fail_after = -1;
    CHECK_EQ_INT(hf_map_blur(&m, 1.0f, out, &a), HF_OK);
    CHECK_EQ_INT(cnt.allocs, 1);
    CHECK_EQ_INT(cnt.frees, 1);
}

/* ======================================================================== */
/* 4. meshes                                                                */
/* ======================================================================== */

/* An engine-style interleaved vertex: the mesh view points into it. */
typedef struct t_vertex {
    float pos[3];
    float normal[3];
    float uv[2];
    unsigned color;
} t_vertex;

static hf_mesh t_mesh_view(const t_vertex *v, int nv, const uint32_t *idx,
                           int nt)
{
    hf_mesh m;
    memset(&m, 0, sizeof m);
    m.positions = v[0].pos;
    m.position_stride = (int)sizeof(t_vertex);
    m.normals = v[0].normal;
    m.normal_stride = (int)sizeof(t_vertex);
    m.uvs = v[0].uv;
    m.uv_stride = (int)sizeof(t_vertex);
    m.vertex_count = nv;
    m.indices = idx;
    m.triangle_count = nt;
    return m;
}

/* unit quad in the xy plane, two triangles */
static const t_vertex t_quad[4] = {{{0, 0, 0}, {0, 0, 1}, {0, 0}, 0},
                                   {{1, 0, 0}, {0, 0, 1}, {1, 0}, 0},
                                   {{1, 1, 0}, {0, 0, 1}, {1, 1}, 0},
                                   {{0, 1, 0}, {0, 0, 1}, {0, 1}, 0}};
static const uint32_t t_quad_idx[6] = {0, 1, 2, 0, 2, 3};

static void test_mesh_validate_interleaved_ok(void)
{
    hf_mesh m = t_mesh_view(t_quad, 4, t_quad_idx, 2);
    hf_diag d;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_OK);
    CHECK(d.result == HF_OK);
    /* optional streams may be absent */
    m.normals = NULL;
    m.uvs = NULL;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_OK);
}

static void test_mesh_validate_errors(void)
{
    t_vertex v[4];
    uint32_t idx[6];
    hf_mesh m, b;
    hf_diag d;
    memcpy(v, t_quad, sizeof v);
    memcpy(idx, t_quad_idx, sizeof idx);
    m = t_mesh_view(v, 4, idx, 2);
    CHECK_EQ_INT(hf_mesh_validate(NULL, &d), HF_ERROR_NULL_POINTER);
    b = m; b.positions = NULL;
    CHECK_EQ_INT(hf_mesh_validate(&b, &d), HF_ERROR_NULL_POINTER);
    CHECK(strcmp(d.field, "positions") == 0);
    b = m; b.indices = NULL;
    CHECK_EQ_INT(hf_mesh_validate(&b, &d), HF_ERROR_NULL_POINTER);
    CHECK(strcmp(d.field, "indices") == 0);
    b = m; b.vertex_count = 0;
    CHECK_EQ_INT(hf_mesh_validate(&b, &d), HF_ERROR_BAD_COUNT);
    b = m; b.triangle_count = -1;
    CHECK_EQ_INT(hf_mesh_validate(&b, &d), HF_ERROR_BAD_COUNT);
    CHECK(strcmp(d.field, "triangle_count") == 0);
    b = m; b.position_stride = 8;
    CHECK_EQ_INT(hf_mesh_validate(&b, &d), HF_ERROR_BAD_STRIDE);
    CHECK(strcmp(d.field, "position_stride") == 0);
    b = m; b.uv_stride = -8;
    CHECK_EQ_INT(hf_mesh_validate(&b, &d), HF_ERROR_BAD_STRIDE);
    b = m; b.normal_stride = 4;
    CHECK_EQ_INT(hf_mesh_validate(&b, &d), HF_ERROR_BAD_STRIDE);
    /* index out of range, found at its position */
    idx[4] = 4;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_ERROR_INDEX_OUT_OF_RANGE);
    CHECK_EQ_INT(d.index, 4);
    CHECK(strstr(d.message, "indices[4] = 4") != NULL);
    idx[4] = 0xffffffffu;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_ERROR_INDEX_OUT_OF_RANGE);
    idx[4] = 2;
    /* non-finite position, normal, uv; zero-length normal */
    v[2].pos[1] = (float)NAN;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_ERROR_NON_FINITE);
    CHECK(strcmp(d.field, "positions") == 0 && d.index == 2);
    v[2].pos[1] = 1.0f;
    v[1].normal[0] = (float)INFINITY;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_ERROR_NON_FINITE);
    CHECK(strcmp(d.field, "normals") == 0 && d.index == 1);
    v[1].normal[0] = 0.0f;
    v[3].uv[0] = -(float)INFINITY;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_ERROR_NON_FINITE);
    CHECK(strcmp(d.field, "uvs") == 0 && d.index == 3);
    v[3].uv[0] = 0.0f;
    v[0].normal[2] = 0.0f;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_ERROR_DEGENERATE);
    CHECK(strcmp(d.field, "normals") == 0 && d.index == 0);
    v[0].normal[2] = 1.0f;
    CHECK_EQ_INT(hf_mesh_validate(&m, &d), HF_OK);
}

static void test_triangle_area_exact(void)
{
    float a[3] = {0, 0, 0}, b[3] = {4, 0, 0}, c[3] = {0, 3, 0};
    float d[3] = {1, 1, 1}, e[3] = {2, 2, 2}, f[3] = {3, 3, 3};
    CHECK(hf_triangle_area(a, b, c) == 6.0f);
    CHECK(hf_triangle_area(c, b, a) == 6.0f);
    CHECK(hf_triangle_area(d, e, f) == 0.0f); /* collinear */
}

static void test_mesh_normals_area_weighted(void)
{
    /* Vertex 0 is shared by a big triangle in the xy plane (area 50, normal
       +z) and a small one in the xz plane (area 0.5, normal -y). The
       area-weighted normal is normalize(0, -1, 100) (cross-product sums). */
    static const float pos[5 * 3] = {0, 0, 0, 10, 0, 0, 0, 10, 0,
                                     0, 0, 1, 1, 0, 0};
    static const uint32_t idx[6] = {0, 1, 2, 0, 4, 3};
    float n[15];
    hf_mesh m;
    float want = 100.0f / sqrtf(10001.0f);
    memset(&m, 0, sizeof m);
    m.positions = pos;
    m.vertex_count = 5;
    m.indices = idx;
    m.triangle_count = 2;
    CHECK_EQ_INT(hf_mesh_compute_normals(&m, n), HF_OK);
    CHECK_NEAR(n[0], 0.0f, 1e-7);
    CHECK_NEAR(n[1], -1.0f / sqrtf(10001.0f), 1e-7);
    CHECK_NEAR(n[2], want, 1e-7);
    /* vertices of only one triangle get that face's normal */
    CHECK(n[3] == 0.0f && n[4] == 0.0f && n[5] == 1.0f);
    CHECK(n[12] == 0.0f && n[13] == -1.0f && n[14] == 0.0f);
}

static void test_mesh_normals_degenerate_fallback(void)
{
    /* a collinear triangle and an unused vertex: (0, 0, 1), never NaN */
    static const float pos[4 * 3] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 5, 5, 5};
    static const uint32_t idx[3] = {0, 1, 2};
    float n[12], sentinel[12];
    hf_mesh m;
    int i;
    memset(&m, 0, sizeof m);
    m.positions = pos;
    m.vertex_count = 4;
    m.indices = idx;
    m.triangle_count = 1;
    CHECK_EQ_INT(hf_mesh_compute_normals(&m, n), HF_OK);
    for (i = 0; i < 12; ++i) CHECK(t_is_finite(n[i]));
    for (i = 0; i < 4; ++i)
        CHECK(n[3 * i] == 0.0f && n[3 * i + 1] == 0.0f &&
              n[3 * i + 2] == 1.0f);
    /* errors leave the output alone */
    for (i = 0; i < 12; ++i) n[i] = sentinel[i] = 7.0f;
    m.vertex_count = 2; /* index 2 now out of range */
    CHECK_EQ_INT(hf_mesh_compute_normals(&m, n),
                 HF_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(memcmp(n, sentinel, sizeof n) == 0);
    CHECK_EQ_INT(hf_mesh_compute_normals(&m, NULL), HF_ERROR_NULL_POINTER);
}

/* ======================================================================== */
/* 9. interpolation and LOD                                                 */
/* ======================================================================== */

enum { TP = 8 }; /* points per strand in these tests */

/* three bent guides with distinct shapes */
static void t_make_guides(float *g, int n)
{
    int i, j;
    for (i = 0; i < n; ++i)
        for (j = 0; j < TP; ++j) {
            float *p = g + (i * TP + j) * 3;
            p[0] = (float)i + 0.05f * (float)j * (float)j * (float)(i + 1);
            p[1] = 0.1f * (float)j;
            p[2] = (float)(i * i) * 0.3f - 0.02f * (float)j;
        }
}

static void test_interp_on_guide_equals_guide(void)
{
    float g[3 * TP * 3], out[3 * TP * 3];
    hf_strand_binding b[3];
    hf_interp_params ip;
    int k;
    t_make_guides(g, 3);
    memset(b, 0, sizeof b);
    memset(&ip, 0, sizeof ip);
    ip.points_per_strand = TP;
    for (k = 0; k < 3; ++k) {
        b[k].guide[0] = 0; b[k].guide[1] = 1; b[k].guide[2] = 2;
        b[k].weight[k] = 1.0f;
    }
    CHECK_EQ_INT(hf_interpolate(g, 3, b, 0, 3, &ip, out), HF_OK);
    CHECK(memcmp(out, g, sizeof g) == 0);
    /* clumping does not move a strand that sits on its guide */
    ip.clump = 0.7f;
    CHECK_EQ_INT(hf_interpolate(g, 3, b, 0, 3, &ip, out), HF_OK);
    CHECK(memcmp(out, g, sizeof g) == 0);
}

static void test_interp_linear_in_barycentrics(void)
{
    float g[3 * TP * 3], out[3 * TP * 3];
    hf_strand_binding b[3];
    hf_interp_params ip;
    static const float w1[3] = {0.2f, 0.3f, 0.5f}, w2[3] = {0.6f, 0.1f, 0.3f};
    int k, i;
    t_make_guides(g, 3);
    memset(b, 0, sizeof b);
    memset(&ip, 0, sizeof ip);
    ip.points_per_strand = TP;
    for (k = 0; k < 3; ++k) {
        b[0].guide[k] = b[1].guide[k] = b[2].guide[k] = (uint32_t)k;
        b[0].weight[k] = w1[k];
        b[1].weight[k] = w2[k];
        b[2].weight[k] = 0.25f * w1[k] + 0.75f * w2[k];
    }
    CHECK_EQ_INT(hf_interpolate(g, 3, b, 0, 3, &ip, out), HF_OK);
    for (i = 0; i < TP * 3; ++i) {
        double direct = w1[0] * g[i] + w1[1] * g[TP * 3 + i] +
                        w1[2] * g[2 * TP * 3 + i];
        CHECK_NEAR(out[i], direct, 1e-5);
        CHECK_NEAR(out[2 * TP * 3 + i],
                   0.25 * out[i] + 0.75 * out[TP * 3 + i], 1e-5);
    }
}

static void test_interp_length_scale_and_clump(void)
{
    float g[3 * TP * 3], out[2 * TP * 3];
    hf_strand_binding b[2];
    hf_interp_params ip;
    int k, j;
    t_make_guides(g, 3);
    memset(b, 0, sizeof b);
    memset(&ip, 0, sizeof ip);
    ip.points_per_strand = TP;
    for (k = 0; k < 3; ++k) b[0].guide[k] = b[1].guide[k] = (uint32_t)k;
    b[0].weight[0] = 0.5f; b[0].weight[1] = 0.25f; b[0].weight[2] = 0.25f;
    b[1] = b[0];
    b[1].length_scale = 0.5f;
    CHECK_EQ_INT(hf_interpolate(g, 3, b, 0, 2, &ip, out), HF_OK);
    /* same root; half the offset from it at every point */
    for (j = 0; j < TP; ++j)
        for (k = 0; k < 3; ++k)
            CHECK_NEAR(out[TP * 3 + j * 3 + k] - out[k],
                       0.5 * (out[j * 3 + k] - out[k]), 1e-5);
    /* full clump: the tip is on the heaviest guide's tip, the root stays */
    ip.clump = 1.0f;
    CHECK_EQ_INT(hf_interpolate(g, 3, b, 0, 1, &ip, out + TP * 3), HF_OK);
    for (k = 0; k < 3; ++k) {
        CHECK_NEAR(out[TP * 3 + (TP - 1) * 3 + k], g[(TP - 1) * 3 + k], 1e-5);
        CHECK(out[TP * 3 + k] == out[k]);
    }
}

static void test_interp_errors_write_nothing(void)
{
    float g[3 * TP * 3], out[TP * 3], keep[TP * 3];
    hf_strand_binding b;
    hf_interp_params ip;
    t_make_guides(g, 3);
    memset(&b, 0, sizeof b);
    memset(&ip, 0, sizeof ip);
    memset(out, 0x5a, sizeof out);
    memcpy(keep, out, sizeof out);
    ip.points_per_strand = TP;
    b.weight[0] = 1.0f;
    b.guide[2] = 3;
    CHECK_EQ_INT(hf_interpolate(g, 3, &b, 0, 1, &ip, out),
                 HF_ERROR_INDEX_OUT_OF_RANGE);
    b.guide[2] = 2;
    b.weight[1] = (float)NAN;
    CHECK_EQ_INT(hf_interpolate(g, 3, &b, 0, 1, &ip, out), HF_ERROR_NON_FINITE);
    b.weight[1] = 0.0f;
    ip.clump = 1.5f;
    CHECK_EQ_INT(hf_interpolate(g, 3, &b, 0, 1, &ip, out),
                 HF_ERROR_BAD_PARAMETER);
    ip.clump = 0.0f;
    ip.points_per_strand = 1;
    CHECK_EQ_INT(hf_interpolate(g, 3, &b, 0, 1, &ip, out), HF_ERROR_BAD_COUNT);
    ip.points_per_strand = TP;
    CHECK_EQ_INT(hf_interpolate(g, 3, &b, -1, 1, &ip, out), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_interpolate(g, 3, &b, 5, 0x7fffffff, &ip, out),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_interpolate(NULL, 3, &b, 0, 1, &ip, out),
                 HF_ERROR_NULL_POINTER);
    CHECK(memcmp(out, keep, sizeof out) == 0);
    /* an empty range is fine and writes nothing */
    CHECK_EQ_INT(hf_interpolate(g, 3, &b, 0, 0, &ip, out), HF_OK);
    CHECK(memcmp(out, keep, sizeof out) == 0);
}

static void test_lod_counts_and_widths_exact(void)
{
    CHECK_EQ_INT(hf_lod_strand_count(100, 1.0f), 100);
    CHECK_EQ_INT(hf_lod_strand_count(100, 0.25f), 25);
    CHECK_EQ_INT(hf_lod_strand_count(3670, 0.1f), 367);
    CHECK_EQ_INT(hf_lod_strand_count(100, 0.0f), 0);
    CHECK_EQ_INT(hf_lod_strand_count(100, -1.0f), 0);
    CHECK_EQ_INT(hf_lod_strand_count(100, (float)NAN), 0);
    CHECK_EQ_INT(hf_lod_strand_count(100, 1e-9f), 1);
    CHECK_EQ_INT(hf_lod_strand_count(100, 7.0f), 100);
    CHECK_EQ_INT(hf_lod_strand_count(0, 0.5f), 0);
    CHECK(hf_lod_width_scale(100, 25) == 2.0f);
    CHECK(hf_lod_width_scale(3670, 367) == (float)sqrt(3670.0 / 367.0));
    CHECK(hf_lod_width_scale(100, 100) == 1.0f);
    CHECK(hf_lod_width_scale(100, 0) == 1.0f);
    CHECK(hf_lod_from_distance(1.0f, 2.0f, 50.0f) == 1.0f);
    CHECK(hf_lod_from_distance(4.0f, 2.0f, 50.0f) == 0.25f);
    CHECK(hf_lod_from_distance(50.0f, 2.0f, 50.0f) == 0.0f);
    CHECK(hf_lod_from_distance((float)NAN, 2.0f, 50.0f) == 1.0f);
}

/* ======================================================================== */
/* 10. ribbons                                                              */
/* ======================================================================== */

typedef struct t_rvert {
    float pos[3], tan[3], tc[3], col[4], c3[2];
} t_rvert;

static hf_ribbon_output t_interleaved(t_rvert *v)
{
    hf_ribbon_output o;
    o.position.data = v[0].pos;
    o.tangent.data = v[0].tan;
    o.texcoord.data = v[0].tc;
    o.color.data = v[0].col;
    o.color3d.data = v[0].c3;
    o.position.stride = o.tangent.stride = o.texcoord.stride =
        o.color.stride = o.color3d.stride = (int)sizeof(t_rvert);
    return o;
}

static hf_ribbon_params t_rparams(void)
{
    hf_ribbon_params p;
    memset(&p, 0, sizeof p);
    p.points_per_strand = TP;
    p.eye[0] = 0.3f; p.eye[1] = 1.0f; p.eye[2] = 5.0f;
    /* wide enough that the side recovered from the float vertices is exact
       to 1e-6 relative: the tests measure the library, not float rounding */
    p.root_width = 0.4f;
    p.tip_width = 0.1f;
    return p;
}

static float t_len3(const float *a) { return sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* Side vectors perpendicular to tangent and view; widths exact at the ends;
   every value finite. Returns the number of failed properties. */
static void t_check_ribbon(const t_rvert *v, const float *pts, int strands,
                           const hf_ribbon_params *p, int check_perp)
{
    int s, j, k;
    for (s = 0; s < strands; ++s)
        for (j = 0; j < TP; ++j) {
            const t_rvert *a = &v[(s * TP + j) * 2], *b = a + 1;
            const float *pt = pts + (s * TP + j) * 3;
            float side[3], view[3], w, sl, vl;
            for (k = 0; k < 3; ++k) {
                side[k] = b->pos[k] - a->pos[k];
                view[k] = p->orthographic ? -p->view_dir[k] : p->eye[k] - pt[k];
            }
            for (k = 0; k < 15; ++k) CHECK(t_is_finite((&a->pos[0])[k]));
            w = t_len3(side);
            sl = w > 0 ? w : 1;
            vl = t_len3(view);
            CHECK_NEAR(t_len3(a->tan), 1.0f, 1e-6);
            if (check_perp) {
                CHECK(fabs((side[0] * a->tan[0] + side[1] * a->tan[1] + side[2] * a->tan[2]) / sl) < 1e-5);
                if (vl > 0)
                    CHECK(fabs((side[0] * view[0] + side[1] * view[1] + side[2] * view[2]) / (sl * vl)) < 1e-5);
            }
            /* exact up to the rounding of the two float vertex positions */
            if (j == 0) CHECK_NEAR(w, p->root_width, 3e-7 * (1.0 + t_len3(pt)));
            if (j == TP - 1) CHECK_NEAR(w, p->tip_width, 3e-7 * (1.0 + t_len3(pt)));
            /* the vertices straddle the point */
            for (k = 0; k < 3; ++k) CHECK_NEAR(0.5f * (a->pos[k] + b->pos[k]), pt[k], 1e-6);
        }
}

static void test_ribbons_perpendicular_and_widths(void)
{
    float g[3 * TP * 3];
    t_rvert v[3 * TP * 2];
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output o = t_interleaved(v);
    static const float uv[6] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
    static const float col[12] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 0.5f};
    static const float c3[3] = {0.25f, 0.5f, 0.75f};
    t_make_guides(g, 3);
    memset(&st, 0, sizeof st);
    st.points = g;
    st.root_uv = uv;
    st.color = col;
    st.color3d_x = c3;
    p.alpha_root = 1.0f;
    p.alpha_tip = 0.25f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 3, &p, &o), HF_OK);
    t_check_ribbon(v, g, 3, &p, 1);
    /* per-vertex attributes */
    CHECK(v[(1 * TP + 3) * 2 + 1].tc[0] == 0.3f && v[(1 * TP + 3) * 2].tc[1] == 0.4f);
    CHECK(v[(1 * TP + 7) * 2].tc[2] == 1.0f && v[(1 * TP) * 2].tc[2] == 0.0f);
    CHECK(v[(2 * TP + 2) * 2].col[2] == 1.0f && v[(2 * TP + 2) * 2].col[0] == 0.0f);
    CHECK(v[(1 * TP) * 2].col[3] == 1.0f && v[(1 * TP + 7) * 2 + 1].col[3] == 0.25f);
    CHECK(v[(2 * TP) * 2].col[3] == 0.5f && v[(2 * TP + 7) * 2 + 1].col[3] == 0.125f);
    CHECK(v[(2 * TP + 7) * 2].c3[0] == 0.75f && v[(2 * TP + 7) * 2].c3[1] == 1.0f);
    /* LOD width scale multiplies both ends */
    p.width_scale = 2.0f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 3, &p, &o), HF_OK);
    p.root_width *= 2.0f;
    p.tip_width *= 2.0f;
    p.width_scale = 1.0f;
    t_check_ribbon(v, g, 3, &p, 1);
    /* orthographic */
    p.orthographic = 1;
    p.view_dir[0] = 0.2f; p.view_dir[1] = -0.3f; p.view_dir[2] = -1.0f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 3, &p, &o), HF_OK);
    t_check_ribbon(v, g, 3, &p, 1);
}

static void test_ribbons_degenerate_never_nan(void)
{
    /* strand 0: eye exactly on point 3; strand 1: duplicate points (zero-
       length segments) including the root; strand 2: points straight at
       the eye (tangent parallel to view); strand 3: all points equal */
    float pts[4 * TP * 3];
    t_rvert v[4 * TP * 2];
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output o = t_interleaved(v);
    int j, s;
    for (j = 0; j < TP; ++j) {
        float *a = pts + j * 3, *b = pts + (TP + j) * 3;
        float *c = pts + (2 * TP + j) * 3, *d = pts + (3 * TP + j) * 3;
        a[0] = 0.01f * j; a[1] = 0.1f * j; a[2] = 0.0f;
        b[0] = 1.0f; b[1] = 0.1f * (float)(j / 3); b[2] = 0.0f;
        c[0] = 0.3f; c[1] = 1.0f; c[2] = 5.0f - 0.1f * (float)(TP - j);
        d[0] = 2.0f; d[1] = 2.0f; d[2] = 2.0f;
    }
    p.eye[0] = pts[9]; p.eye[1] = pts[10]; p.eye[2] = pts[11];
    memset(&st, 0, sizeof st);
    st.points = pts;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 4, &p, &o), HF_OK);
    t_check_ribbon(v, pts, 4, &p, 0);
    /* away from the degenerate points the usual properties still hold */
    for (s = 0; s < 4; ++s)
        for (j = 0; j < TP * 2; ++j) {
            int k;
            for (k = 0; k < 15; ++k) CHECK(t_is_finite((&v[s * TP * 2 + j].pos[0])[k]));
        }
    /* strand 3 has no length: tangent (0, 1, 0), a fixed perpendicular side */
    CHECK(v[3 * TP * 2].tan[1] == 1.0f);
    /* strand 1's leading duplicate points share the tangent that follows */
    CHECK(memcmp(v[TP * 2].tan, v[(TP + 2) * 2].tan, 12) == 0);
}

static void test_ribbons_ranges_byte_identical(void)
{
    enum { N = 23 };
    float *pts = (float *)malloc(sizeof(float) * N * TP * 3);
    t_rvert *a = (t_rvert *)calloc(N * TP * 2, sizeof(t_rvert));
    t_rvert *b = (t_rvert *)calloc(N * TP * 2, sizeof(t_rvert));
    float *pa = (float *)calloc(N * TP * 4, sizeof(float));
    float *pb = (float *)calloc(N * TP * 4, sizeof(float));
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output oa = t_interleaved(a), ob = t_interleaved(b);
    hf_rng r;
    int i, splits[3] = {1, 2, 7}, k;
    hf_rng_seed(&r, 9u, 0u);
    for (i = 0; i < N * TP * 3; ++i) pts[i] = hf_rng_float(&r) - 0.5f;
    memset(&st, 0, sizeof st);
    st.points = pts;
    CHECK_EQ_INT(hf_ribbons(&st, 0, N, &p, &oa), HF_OK);
    CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &p, pa), HF_OK);
    for (k = 0; k < 3; ++k) {
        int n = splits[k], first = 0;
        memset(b, 0, sizeof(t_rvert) * N * TP * 2);
        memset(pb, 0, sizeof(float) * N * TP * 4);
        for (i = 0; i < n; ++i) {
            int cnt = N * (i + 1) / n - first;
            CHECK_EQ_INT(hf_ribbons(&st, first, cnt, &p, &ob), HF_OK);
            CHECK_EQ_INT(hf_ribbon_points(&st, first, cnt, &p, pb), HF_OK);
            first += cnt;
        }
        CHECK(memcmp(a, b, sizeof(t_rvert) * N * TP * 2) == 0);
        CHECK(memcmp(pa, pb, sizeof(float) * N * TP * 4) == 0);
    }
    /* points: xyz copied, w = half width, exact at the ends */
    CHECK(pa[0] == pts[0] && pa[4 * (TP + 1) + 2] == pts[3 * (TP + 1) + 2]);
    CHECK(pa[3] == 0.2f && pa[4 * (TP - 1) + 3] == 0.05f);
    free(pts); free(a); free(b); free(pa); free(pb);
}

static void test_ribbons_separate_streams_and_skips(void)
{
    float g[TP * 3], pos[TP * 2 * 3], tanb[TP * 2 * 4];
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output o;
    t_rvert v[TP * 2];
    hf_ribbon_output oi = t_interleaved(v);
    int i;
    t_make_guides(g, 1);
    memset(&st, 0, sizeof st);
    st.points = g;
    memset(&o, 0, sizeof o);
    o.position.data = pos;              /* packed */
    o.tangent.data = tanb;
    o.tangent.stride = 16;              /* padded */
    for (i = 0; i < TP * 2 * 4; ++i) tanb[i] = -7.0f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &o), HF_OK);
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &oi), HF_OK);
    for (i = 0; i < TP * 2; ++i) {
        CHECK(memcmp(pos + 3 * i, v[i].pos, 12) == 0);
        CHECK(memcmp(tanb + 4 * i, v[i].tan, 12) == 0);
        CHECK(tanb[4 * i + 3] == -7.0f); /* padding untouched */
    }
}

static void test_ribbons_errors_write_nothing(void)
{
    float g[TP * 3];
    t_rvert v[TP * 2], keep[TP * 2];
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams(), b;
    hf_ribbon_output o = t_interleaved(v);
    t_make_guides(g, 1);
    memset(&st, 0, sizeof st);
    st.points = g;
    memset(v, 0x3c, sizeof v);
    memcpy(keep, v, sizeof v);
    b = p; b.eye[1] = (float)NAN;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &b, &o), HF_ERROR_NON_FINITE);
    b = p; b.root_width = -1.0f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &b, &o), HF_ERROR_BAD_PARAMETER);
    b = p; b.tip_width = (float)INFINITY;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &b, &o), HF_ERROR_NON_FINITE);
    b = p; b.orthographic = 1;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &b, &o), HF_ERROR_DEGENERATE);
    b = p; b.points_per_strand = HF_MAX_POINTS + 1;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &b, &o), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_ribbons(&st, -2, 1, &p, &o), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, NULL), HF_ERROR_NULL_POINTER);
    o.color.stride = -16;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &o), HF_ERROR_BAD_STRIDE);
    st.points = NULL;
    CHECK_EQ_INT(hf_ribbon_points(&st, 0, 1, &p, &v[0].pos[0]),
                 HF_ERROR_NULL_POINTER);
    CHECK(memcmp(v, keep, sizeof v) == 0);
}

static void test_ribbon_indices(void)
{
    uint32_t idx[64];
    CHECK_EQ_INT(hf_ribbon_index_count(2, 3, HF_TRIANGLES), 24);
    CHECK_EQ_INT(hf_ribbon_index_count(2, 3, HF_STRIP_RESTART), 14);
    CHECK_EQ_INT(hf_ribbon_index_count(0x7fffffff, 16, HF_TRIANGLES), -1);
    CHECK_EQ_INT(hf_ribbon_index_count(2, 1, HF_TRIANGLES), -1);
    CHECK_EQ_INT(hf_ribbon_indices(2, 3, HF_TRIANGLES, idx, 23),
                 HF_ERROR_BUFFER_TOO_SMALL);
    CHECK_EQ_INT(hf_ribbon_indices(2, 3, HF_TRIANGLES, idx, 64), HF_OK);
    /* strand 1 starts at vertex 6; its second quad is 8, 9, 10 / 10, 9, 11 */
    CHECK_EQ_INT(idx[0], 0); CHECK_EQ_INT(idx[1], 1); CHECK_EQ_INT(idx[2], 2);
    CHECK_EQ_INT(idx[3], 2); CHECK_EQ_INT(idx[4], 1); CHECK_EQ_INT(idx[5], 3);
    CHECK_EQ_INT(idx[18], 8); CHECK_EQ_INT(idx[19], 9); CHECK_EQ_INT(idx[20], 10);
    CHECK_EQ_INT(idx[21], 10); CHECK_EQ_INT(idx[22], 9); CHECK_EQ_INT(idx[23], 11);
    CHECK_EQ_INT(hf_ribbon_indices(2, 3, HF_STRIP_RESTART, idx, 64), HF_OK);
    CHECK_EQ_INT(idx[5], 5); CHECK(idx[6] == 0xffffffffu);
    CHECK_EQ_INT(idx[7], 6); CHECK_EQ_INT(idx[12], 11); CHECK(idx[13] == 0xffffffffu);
    CHECK_EQ_INT(hf_ribbon_indices(2, 3, 5, idx, 64),
                 HF_ERROR_BAD_PARAMETER);
}

static void test_ribbon_winding_faces_camera(void)
{
    /* the first triangle's normal (b - a) x (c - a) points at the eye */
    float g[TP * 3];
    t_rvert v[TP * 2];
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output o = t_interleaved(v);
    uint32_t idx[6 * (TP - 1)];
    float e1[3], e2[3], n[3], view[3];
    int k;
    t_make_guides(g, 1);
    memset(&st, 0, sizeof st);
    st.points = g;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &o), HF_OK);
    CHECK_EQ_INT(hf_ribbon_indices(1, TP, HF_TRIANGLES, idx, 6 * (TP - 1)), HF_OK);
    for (k = 0; k < 3; ++k) {
        e1[k] = v[idx[1]].pos[k] - v[idx[0]].pos[k];
        e2[k] = v[idx[2]].pos[k] - v[idx[0]].pos[k];
        view[k] = p.eye[k] - v[idx[0]].pos[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    CHECK(n[0] * view[0] + n[1] * view[1] + n[2] * view[2] > 0.0f);
}

/* ======================================================================== */

int main(void)
{
    RUN(test_result_strings_distinct);
    RUN(test_version);
    RUN(test_rng_matches_pcg32_reference);
    RUN(test_rng_streams_and_copies);
    RUN(test_rng_float_and_below_ranges);
    RUN(test_map_sample_texel_centres_exact);
    RUN(test_map_sample_bilinear_midpoints);
    RUN(test_map_wrap_repeat_vs_clamp);
    RUN(test_map_f32_multichannel_row_stride);
    RUN(test_map_validate_errors);
    RUN(test_map_blur_constant_impulse_and_sum);
    RUN(test_map_blur_errors_and_allocator);
    RUN(test_mesh_validate_interleaved_ok);
    RUN(test_mesh_validate_errors);
    RUN(test_triangle_area_exact);
    RUN(test_mesh_normals_area_weighted);
    RUN(test_mesh_normals_degenerate_fallback);
    RUN(test_interp_on_guide_equals_guide);
    RUN(test_interp_linear_in_barycentrics);
    RUN(test_interp_length_scale_and_clump);
    RUN(test_interp_errors_write_nothing);
    RUN(test_lod_counts_and_widths_exact);
    RUN(test_ribbons_perpendicular_and_widths);
    RUN(test_ribbons_degenerate_never_nan);
    RUN(test_ribbons_ranges_byte_identical);
    RUN(test_ribbons_separate_streams_and_skips);
    RUN(test_ribbons_errors_write_nothing);
    RUN(test_ribbon_indices);
    RUN(test_ribbon_winding_faces_camera);
    printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}
