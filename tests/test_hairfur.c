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
    printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}
