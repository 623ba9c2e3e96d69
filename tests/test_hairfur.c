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
/* 11. LUT baking (Marschner M and N textures; docs/marschner-spec.md)               */
/* ======================================================================== */

/* Expected numbers are the spot values, texel table and channel sums of
   docs/marschner-spec.md section 11, and closed forms / integrals written here
   independently of the library from the formulas of sections 4-6. */

#define T_PI 3.14159265358979323846
#define T_DEG (T_PI / 180.0)

static hf_lut_params t_lut_defaults(int size, hf_lut_variant v)
{
    hf_lut_params p;
    hf_lut_params_init(&p);
    p.size = size;
    p.variant = v;
    return p;
}

static float *t_lut_alloc(int n)
{
    return (float *)malloc(sizeof(float) * 4u * (size_t)n * (size_t)n);
}

/* |x - r| <= tol * |r| */
#define CHECK_REL(x, r, tol) CHECK_NEAR((x), (r), (tol) * fabs((double)(r)))

/* ---- independent model pieces, straight from docs/marschner-spec.md ---- */

static double t_rs(double n, double x)
{
    double s = sin(x) / n, ci, ct, r;
    if (s * s >= 1.0) return 1.0;
    ci = fabs(cos(x));
    ct = sqrt(1.0 - s * s);
    r = (ci - n * ct) / (ci + n * ct);
    return r * r;
}

static double t_rp(double n, double x)
{
    double s = sin(x) / n, ci, ct, r;
    if (s * s >= 1.0) return 1.0;
    ci = fabs(cos(x));
    ct = sqrt(1.0 - s * s);
    r = (n * ci - ct) / (n * ci + ct);
    return r * r;
}

typedef struct t_col {
    double eta1, eta2, sigma1, c;
} t_col;

static t_col t_column(double eta, double cd, double sigma)
{
    t_col k;
    double s2 = 1.0 - cd * cd, cos_tt;
    k.eta1 = sqrt(eta * eta - s2) / cd;
    k.eta2 = eta * eta / k.eta1;
    cos_tt = sqrt(eta * eta - s2) / eta;
    k.sigma1 = sigma / cos_tt;
    k.c = asin(1.0 / k.eta1);
    return k;
}

/* A(p, h) of section 6.4 */
static double t_atten(const t_col *k, int p, double h)
{
    double g = asin(h), gt = asin(h / k->eta1);
    double f_ext = 0.5 * (t_rs(k->eta1, g) + t_rp(k->eta2, g));
    double f_int = 0.5 * (t_rs(1.0 / k->eta1, gt) + t_rp(1.0 / k->eta2, gt));
    double T = exp(-2.0 * k->sigma1 * (1.0 + cos(2.0 * gt)));
    if (p == 0) return f_ext;
    return (1.0 - f_ext) * (1.0 - f_ext) * pow(f_int, p - 1) * pow(T, p);
}

/* Phi(p, g) - p pi and its derivative, cubic (6.2) or exact (6.5) */
static double t_phi(const t_col *k, int p, double g, int exact)
{
    if (exact) return 2.0 * p * asin(sin(g) / k->eta1) - 2.0 * g;
    return (6.0 * p * k->c / T_PI - 2.0) * g -
           8.0 * p * k->c / (T_PI * T_PI * T_PI) * g * g * g;
}

static double t_dphi(const t_col *k, int p, double g, int exact)
{
    if (exact)
        return 2.0 * p * cos(g) / sqrt(k->eta1 * k->eta1 - sin(g) * sin(g)) -
               2.0;
    return (6.0 * p * k->c / T_PI - 2.0) -
           24.0 * p * k->c / (T_PI * T_PI * T_PI) * g * g;
}

/* Reference N(p): brute-force root search (a fine grid split at the fold,
   bisection to 1e-14) and the sum of section 6.1 with clamp j_min. */
static double t_ref_n(int p, double eta, double cd, double phi, double sigma,
                      int exact, double j_min)
{
    t_col k = t_column(eta, cd < 1e-4 ? 1e-4 : cd, sigma);
    double t = phi - p * T_PI, brk[4], sum = 0.0;
    int nb = 0, b, s;
    const int steps = 512;
    while (t >= T_PI) t -= 2.0 * T_PI;
    while (t < -T_PI) t += 2.0 * T_PI;
    brk[nb++] = -T_PI / 2;
    if (p == 2 && k.eta1 < 2.0) {
        double gc = exact ? asin(sqrt((4.0 - k.eta1 * k.eta1) / 3.0))
                          : sqrt((6.0 * 2 * k.c / T_PI - 2.0) /
                                 (3.0 * 16.0 * k.c / (T_PI * T_PI * T_PI)));
        brk[nb++] = -gc;
        brk[nb++] = gc;
    }
    brk[nb++] = T_PI / 2;
    for (b = 0; b + 1 < nb; ++b)
        for (s = 0; s < steps; ++s) {
            double x0 = brk[b] + (brk[b + 1] - brk[b]) * s / steps;
            double x1 = brk[b] + (brk[b + 1] - brk[b]) * (s + 1) / steps;
            double f0 = t_phi(&k, p, x0, exact) - t;
            double f1 = t_phi(&k, p, x1, exact) - t, x, jac;
            int it;
            if (!(f0 < 0.0 && f1 >= 0.0) && !(f0 > 0.0 && f1 <= 0.0)) continue;
            for (it = 0; it < 200 && x1 - x0 > 1e-14; ++it) {
                double xm = 0.5 * (x0 + x1), fm = t_phi(&k, p, xm, exact) - t;
                if ((fm < 0.0) == (f0 < 0.0)) {
                    x0 = xm;
                    f0 = fm;
                } else {
                    x1 = xm;
                }
            }
            x = 0.5 * (x0 + x1);
            jac = 2.0 * fabs(t_dphi(&k, p, x, exact)) / cos(x);
            if (jac < j_min) jac = j_min;
            sum += t_atten(&k, p, sin(x)) / jac;
        }
    return sum;
}

/* ---- tests ---- */

static void test_lut_params_init_defaults(void)
{
    hf_lut_params p;
    memset(&p, 0xff, sizeof p);
    hf_lut_params_init(&p);
    CHECK(p.eta == 1.55);
    CHECK(p.alpha_r_deg == -7.5);
    CHECK(p.beta_r_deg == 7.5);
    CHECK(p.sigma_a == 0.2);
    CHECK(p.sigma_a_rgb[0] == 0.2 && p.sigma_a_rgb[1] == 0.2 &&
          p.sigma_a_rgb[2] == 0.2);
    CHECK_EQ_INT(p.variant, HF_LUT_CUBIC);
    CHECK_EQ_INT(p.size, 256);
    CHECK_EQ_INT(hf_lut_validate(&p, NULL), HF_OK);
    hf_lut_params_init(NULL); /* ignored, no crash */
}

static void test_lut_validate_codes(void)
{
    hf_lut_params p;
    hf_diag d;
    double nan = strtod("nan", NULL), inf = HUGE_VAL;
    p = t_lut_defaults(64, HF_LUT_CUBIC);
    CHECK_EQ_INT(hf_lut_validate(NULL, &d), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(d.result, HF_ERROR_NULL_POINTER);
#define T_BAD(member, value, code, name)                                        \
    do {                                                                       \
        p = t_lut_defaults(64, HF_LUT_CUBIC);                                  \
        p.member = value;                                                      \
        CHECK_EQ_INT(hf_lut_validate(&p, &d), code);                           \
        CHECK(strcmp(d.field, name) == 0);                                     \
    } while (0)
    T_BAD(eta, nan, HF_ERROR_NON_FINITE, "eta");
    T_BAD(eta, inf, HF_ERROR_NON_FINITE, "eta");
    T_BAD(alpha_r_deg, -inf, HF_ERROR_NON_FINITE, "alpha_r_deg");
    T_BAD(beta_r_deg, nan, HF_ERROR_NON_FINITE, "beta_r_deg");
    T_BAD(sigma_a, inf, HF_ERROR_NON_FINITE, "sigma_a");
    T_BAD(sigma_a_rgb[2], nan, HF_ERROR_NON_FINITE, "sigma_a_rgb[2]");
    T_BAD(eta, 1.19, HF_ERROR_BAD_PARAMETER, "eta");
    T_BAD(eta, 3.0001, HF_ERROR_BAD_PARAMETER, "eta");
    T_BAD(beta_r_deg, 0.0, HF_ERROR_BAD_PARAMETER, "beta_r_deg");
    T_BAD(beta_r_deg, -1.0, HF_ERROR_BAD_PARAMETER, "beta_r_deg");
    T_BAD(sigma_a, -1e-9, HF_ERROR_BAD_PARAMETER, "sigma_a");
    T_BAD(sigma_a_rgb[1], -0.5, HF_ERROR_BAD_PARAMETER, "sigma_a_rgb[1]");
    T_BAD(variant, (hf_lut_variant)2, HF_ERROR_BAD_PARAMETER, "variant");
    T_BAD(size, 0, HF_ERROR_BAD_COUNT, "size");
    T_BAD(size, -3, HF_ERROR_BAD_COUNT, "size");
    T_BAD(size, HF_LUT_MAX_SIZE + 1, HF_ERROR_BAD_COUNT, "size");
#undef T_BAD
    /* the ends of every range are accepted; zero alpha and sigma mean zero */
    p = t_lut_defaults(1, HF_LUT_EXACT);
    p.eta = 1.2;
    p.alpha_r_deg = 0.0;
    p.beta_r_deg = 4.9e-324; /* the smallest positive double */
    p.sigma_a = 0.0;
    p.sigma_a_rgb[0] = 0.0;
    CHECK_EQ_INT(hf_lut_validate(&p, &d), HF_OK);
    CHECK_EQ_INT(d.result, HF_OK);
    p.eta = 3.0;
    p.size = HF_LUT_MAX_SIZE;
    p.sigma_a = 1e308;
    CHECK_EQ_INT(hf_lut_validate(&p, NULL), HF_OK);
}

/* docs/marschner-spec.md section 11, spot values of N (relative 1e-6). */
static void test_lut_n_spot_values(void)
{
    static const double tab[9][7] = {
        /* theta_d, phi, N_R, N_TT, N_TRT, N_TT exact, N_TRT exact */
        {0, 0, 0.0116301423, 0, 0.0146400229, 0, 0.0159208016},
        {0, 10, 0.0115861399, 0, 0.0162159349, 0, 0.0183590316},
        {0, 90, 0.0101271203, 0.00215181849, 0, 0.002155831, 0},
        {0, 150, 0.0169424516, 0.191360086, 0, 0.198805406, 0},
        {0, 180, 0, 0.309119078, 0, 0.287803512, 0},
        {30, 0, 0.0120349806, 0, 0.0261347193, 0, 0.0282730792},
        {30, 120, 0.0151205258, 0.0728765391, 0, 0.0741551627, 0},
        {60, 45, 0.0252658074, 0, 0.00460915656, 0, 0.00439109368},
        {60, 150, 0.0532672193, 0.109243772, 0, 0.109835742, 0},
    };
    int k, c;
    for (k = 0; k < 9; ++k) {
        hf_lut_params p = t_lut_defaults(64, HF_LUT_CUBIC);
        double cub[3], ex[3], want[5];
        double cd = cos(tab[k][0] * T_DEG), phi = tab[k][1] * T_DEG;
        CHECK_EQ_INT(hf_lut_eval_n(&p, cd, phi, cub), HF_OK);
        p.variant = HF_LUT_EXACT;
        CHECK_EQ_INT(hf_lut_eval_n(&p, cd, phi, ex), HF_OK);
        want[0] = tab[k][2];
        want[1] = tab[k][3];
        want[2] = tab[k][4];
        want[3] = tab[k][5];
        want[4] = tab[k][6];
        for (c = 0; c < 5; ++c) {
            double got = c < 3 ? cub[c] : ex[c - 2];
            if (want[c] == 0.0)
                CHECK(got >= 0.0 && got < 1e-16);
            else
                CHECK_REL(got, want[c], 1e-6);
        }
        CHECK(ex[0] == cub[0]); /* p = 0 is exact in both variants */
    }
}

/* The closed forms of section 11, computed here from eta alone. */
static void test_lut_n_closed_forms(void)
{
    hf_lut_params p = t_lut_defaults(64, HF_LUT_CUBIC);
    double eta = 1.55, f0 = (eta - 1) * (eta - 1) / ((eta + 1) * (eta + 1));
    double o[3], c = asin(1.0 / eta), cd = cos(45.0 * T_DEG);
    double s2 = 1.0 - cd * cd, e1 = sqrt(eta * eta - s2) / cd,
           e2 = eta * eta / e1;
    CHECK_EQ_INT(hf_lut_eval_n(&p, 1.0, 0.0, o), HF_OK);
    CHECK_REL(o[0], f0 / 4.0, 1e-12);
    CHECK_EQ_INT(hf_lut_eval_n(&p, cd, 0.0, o), HF_OK);
    CHECK_REL(o[0],
              (((1 - e1) / (1 + e1)) * ((1 - e1) / (1 + e1)) +
               ((e2 - 1) / (e2 + 1)) * ((e2 - 1) / (e2 + 1))) /
                  8.0,
              1e-12);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 1.0, T_PI, o), HF_OK);
    CHECK_REL(o[1],
              (1 - f0) * (1 - f0) * exp(-4 * 0.2) /
                  (2 * fabs(6 * c / T_PI - 2)),
              1e-12);
    p.variant = HF_LUT_EXACT;
    CHECK_EQ_INT(hf_lut_eval_n(&p, 1.0, T_PI, o), HF_OK);
    CHECK_REL(o[1], (1 - f0) * (1 - f0) * exp(-4 * 0.2) / (2 * fabs(2 / eta - 2)),
              1e-12);
    /* negative cos(theta_d) reads as its absolute value */
    {
        double a[3], b[3];
        p.variant = HF_LUT_CUBIC;
        hf_lut_eval_n(&p, -0.3, 1.0, a);
        hf_lut_eval_n(&p, 0.3, 1.0, b);
        CHECK(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
    }
}

/* M_p table of section 11. */
static void test_lut_m_spot_values(void)
{
    static const double tab[4][4] = {
        {-7.5, 3.04769452, 0.0677136559, 0.697668115},
        {0, 1.84852017, 3.69704034, 1.15026026},
        {3.75, 0.989441547, 6.09538905, 1.34479049},
        {11.25, 0.133906352, 0.824921203, 1.52384726},
    };
    hf_lut_params p = t_lut_defaults(64, HF_LUT_CUBIC);
    int k, c;
    for (k = 0; k < 4; ++k) {
        double o[3];
        CHECK_EQ_INT(hf_lut_eval_m(&p, tab[k][0] * T_DEG, o), HF_OK);
        for (c = 0; c < 3; ++c) CHECK_REL(o[c], tab[k][1 + c], 1e-6);
    }
}

/* n = 64 texel table of section 11 (texel (i, j) = column i, row j). */
static void test_lut_texels_n64(void)
{
    static const double tm[2][6] = {
        {10, 40, 2.23569326, 0.000174263232, 0.394765236, 0.876239249},
        {50, 20, 0.454858505, 4.06208962, 1.46739609, 0.88138348},
    };
    static const double tn[5][6] = {
        {63, 0, 0.0136095099, 0.282123539, 0, 1},
        {63, 63, 0.0115929779, 0, 0.0170660254, 1},
        {40, 5, 0.0648186586, 0.0613788117, 0, 1},
        {50, 60, 0.0194998832, 0, 0.0069082188, 1},
        {20, 10, 0.0816353301, 0.0699912053, 0, 1},
    };
    hf_lut_params p = t_lut_defaults(64, HF_LUT_CUBIC);
    float *m = t_lut_alloc(64), *n = t_lut_alloc(64);
    int k, c;
    CHECK_EQ_INT(hf_lut_bake_m(&p, 0, 64, m), HF_OK);
    CHECK_EQ_INT(hf_lut_bake_n(&p, 0, 64, n), HF_OK);
    for (k = 0; k < 2; ++k) {
        const float *t = m + 4 * ((int)tm[k][1] * 64 + (int)tm[k][0]);
        for (c = 0; c < 4; ++c) CHECK_REL(t[c], tm[k][2 + c], 1e-6);
    }
    for (k = 0; k < 5; ++k) {
        const float *t = n + 4 * ((int)tn[k][1] * 64 + (int)tn[k][0]);
        for (c = 0; c < 4; ++c) {
            if (tn[k][2 + c] == 0.0)
                CHECK(t[c] == 0.0f);
            else
                CHECK_REL(t[c], tn[k][2 + c], 1e-6);
        }
    }
    free(m);
    free(n);
}

static void t_lut_sums(const float *tex, int n, double s[4])
{
    size_t i;
    s[0] = s[1] = s[2] = s[3] = 0.0;
    for (i = 0; i < 4u * (size_t)n * (size_t)n; ++i) s[i & 3] += tex[i];
}

/* Channel sums of section 11 at n = 64 (relative 1e-4). */
static void test_lut_channel_sums_n64(void)
{
    static const double want[4][4] = {
        {3029.294099, 3167.915798, 2719.564272, 3642.132394}, /* M */
        {239.6066785, 117.5968426, 2.975681226, 4096},        /* N */
        {239.6066785, 266.8080906, 17.71475517, 4096},        /* sigma 0 */
        {239.6066785, 117.7537789, 2.919141302, 4096},        /* exact */
    };
    float *t = t_lut_alloc(64);
    double s[4];
    int k, c;
    for (k = 0; k < 4; ++k) {
        hf_lut_params p = t_lut_defaults(64, k == 3 ? HF_LUT_EXACT
                                                    : HF_LUT_CUBIC);
        if (k == 2) p.sigma_a = 0.0;
        CHECK_EQ_INT(k == 0 ? hf_lut_bake_m(&p, 0, 64, t)
                            : hf_lut_bake_n(&p, 0, 64, t),
                     HF_OK);
        t_lut_sums(t, 64, s);
        for (c = 0; c < 4; ++c) CHECK_REL(s[c], want[k][c], 1e-4);
    }
    free(t);
}

/* M is symmetric bit for bit, also for odd n; its alpha is cos(theta_d)
   with 1 on the diagonal. */
static void test_lut_m_symmetric(void)
{
    static const int sizes[3] = {64, 37, 1};
    int s;
    for (s = 0; s < 3; ++s) {
        int n = sizes[s], i, j;
        hf_lut_params p = t_lut_defaults(n, HF_LUT_CUBIC);
        float *m = t_lut_alloc(n);
        CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n, m), HF_OK);
        for (j = 0; j < n; ++j)
            for (i = 0; i < n; ++i) {
                CHECK(memcmp(m + 4 * (j * n + i), m + 4 * (i * n + j),
                             4 * sizeof(float)) == 0);
                if (i == j) CHECK(m[4 * (j * n + i) + 3] == 1.0f);
            }
        free(m);
    }
}

/* Each M_p integrates over theta_h in [-pi/2, pi/2] to the truncated
   Gaussian area of section 4 (Simpson's rule, 20000 intervals). */
static void test_lut_m_unit_area(void)
{
    static const double ab[3][2] = {{-7.5, 7.5}, {-10, 5}, {-5, 10}};
    int k, c, i;
    const int steps = 20000;
    for (k = 0; k < 3; ++k) {
        hf_lut_params p = t_lut_defaults(64, HF_LUT_CUBIC);
        double sum[3] = {0, 0, 0}, alpha[3], beta[3];
        double hstep = T_PI / steps;
        p.alpha_r_deg = ab[k][0];
        p.beta_r_deg = ab[k][1];
        alpha[0] = ab[k][0] * T_DEG;
        alpha[1] = -alpha[0] / 2;
        alpha[2] = -3 * alpha[0] / 2;
        beta[0] = ab[k][1] * T_DEG;
        beta[1] = beta[0] / 2;
        beta[2] = 2 * beta[0];
        for (i = 0; i <= steps; ++i) {
            double o[3], w = (i == 0 || i == steps) ? 1 : (i & 1 ? 4 : 2);
            hf_lut_eval_m(&p, -T_PI / 2 + i * hstep, o);
            for (c = 0; c < 3; ++c) sum[c] += w * o[c];
        }
        for (c = 0; c < 3; ++c) {
            double area = 0.5 * (erf((T_PI / 2 - alpha[c]) / (beta[c] * sqrt(2.0))) -
                                 erf((-T_PI / 2 - alpha[c]) /
                                     (beta[c] * sqrt(2.0))));
            CHECK_NEAR(sum[c] * hstep / 3, area, 1e-9);
            CHECK(area >= 0.99991);
        }
    }
}

/* 2 * integral over [0, pi] of N_p(phi) without the Jacobian clamp, and
   1/2 * integral over [-1, 1] of A(p, h) (midpoint rules). N_TRT has an
   integrable 1/sqrt spike at the caustic azimuth phi_c; the substitution
   phi = phi_c -+ s^2 on either side of it makes every integrand smooth. */
static void t_lut_energies(const hf_lut_params *p, double cd, int steps,
                           double n_int[3], double a_int[3])
{
    t_col k = t_column(p->eta, cd, p->sigma_a);
    double phi_c = T_PI / 2;
    int i, c, side;
    if (k.eta1 < 2.0) { /* the TRT fold exists: Phi(2, g_c) - 2 pi */
        int exact = p->variant == HF_LUT_EXACT;
        double gc = exact ? asin(sqrt((4.0 - k.eta1 * k.eta1) / 3.0))
                          : sqrt((12.0 * k.c / T_PI - 2.0) /
                                 (48.0 * k.c / (T_PI * T_PI * T_PI)));
        phi_c = fabs(t_phi(&k, 2, gc, exact));
    }
    for (c = 0; c < 3; ++c) n_int[c] = a_int[c] = 0.0;
    for (side = 0; side < 2; ++side) {
        double smax = sqrt(side ? T_PI - phi_c : phi_c), ds = smax / steps;
        for (i = 0; i < steps; ++i) {
            double o[3], sv = (i + 0.5) * ds;
            double phi = side ? phi_c + sv * sv : phi_c - sv * sv;
            hf__lut_eval_n_clamp(p, cd, phi, 0.0, o);
            for (c = 0; c < 3; ++c) n_int[c] += 2.0 * o[c] * 2.0 * sv * ds;
        }
    }
    for (i = 0; i < 2 * steps; ++i) {
        double h = -1.0 + (i + 0.5) / steps;
        for (c = 0; c < 3; ++c)
            a_int[c] += 0.5 * t_atten(&k, c, h) / steps;
    }
}

/* Section 11: for every theta_d, the integral of N_p over phi equals half
   the integral of A(p, h) over h (any smooth Phi; both variants). */
static void test_lut_n_energy_identity(void)
{
    static const double td_deg[4] = {0, 30, 60, 80};
    int v, k, c;
    for (v = 0; v < 2; ++v)
        for (k = 0; k < 4; ++k) {
            hf_lut_params p = t_lut_defaults(64, (hf_lut_variant)v);
            double ni[3], ai[3];
            t_lut_energies(&p, cos(td_deg[k] * T_DEG), 20000, ni, ai);
            for (c = 0; c < 3; ++c) {
                CHECK_NEAR(ni[c], ai[c], 1e-5 * ai[c]);
                CHECK(ai[c] > 0.0);
            }
        }
}

/* sigma_a = 0, theta_d = 0: lobe energies 0.074955, 0.861791, 0.055672;
   TT below the constant-Fresnel estimate (1 - F0)^2 = 0.909123. */
static void test_lut_n_energy_no_absorption(void)
{
    static const double want[3] = {0.074955, 0.861791, 0.055672};
    int v, c;
    for (v = 0; v < 2; ++v) {
        hf_lut_params p = t_lut_defaults(64, (hf_lut_variant)v);
        double ni[3], ai[3];
        p.sigma_a = 0.0;
        t_lut_energies(&p, 1.0, 20000, ni, ai);
        for (c = 0; c < 3; ++c) {
            CHECK_NEAR(ai[c], want[c], 1e-6);
            CHECK_NEAR(ni[c], want[c], 1e-6);
        }
        CHECK(ni[1] < 0.909123);
    }
}

/* Section 6.6: next to the TRT fold the two merging roots are both kept
   and each contributes A / J_MIN (2 |dPhi/dh| is far below 0.02 there).
   Just beyond the fold (theta_d = 0) the cubic has no root left; the exact
   Phi keeps one near-grazing root (Phi(2, -pi/2) - 2 pi = 19.29 deg lies
   above its fold at 18.62 deg) whose contribution is tiny. */
static void test_lut_n_caustic_clamp(void)
{
    int v;
    for (v = 0; v < 2; ++v) {
        hf_lut_params p = t_lut_defaults(64, (hf_lut_variant)v);
        t_col k = t_column(p.eta, 1.0, p.sigma_a);
        double gc = v ? asin(sqrt((4.0 - k.eta1 * k.eta1) / 3.0))
                      : sqrt((12.0 * k.c / T_PI - 2.0) /
                             (48.0 * k.c / (T_PI * T_PI * T_PI)));
        double phi_c = t_phi(&k, 2, gc, v), o[3];
        double peak = 2.0 * t_atten(&k, 2, sin(gc)) / 0.02;
        CHECK(phi_c > (v ? 18.5 : 20.4) * T_DEG &&
              phi_c < (v ? 18.7 : 20.6) * T_DEG); /* section 13 */
        CHECK_EQ_INT(hf_lut_eval_n(&p, 1.0, phi_c - 1e-9, o), HF_OK);
        CHECK(o[2] >= peak * 0.999 && o[2] <= peak * 1.001 + 0.05);
        CHECK_EQ_INT(hf_lut_eval_n(&p, 1.0, phi_c + 1e-6, o), HF_OK);
        CHECK(v ? (o[2] > 0.0 && o[2] < 1e-5) : o[2] == 0.0);
    }
}

/* Every texel of a bake against the brute-force reference, with the
   conformance rule of section 11 (including its 3 x 3 neighbourhood for
   texels next to the TRT fold or the total-reflection edge). */
static void test_lut_n_conformance(void)
{
    const int n = 24;
    int v;
    for (v = 0; v < 2; ++v) {
        hf_lut_params p = t_lut_defaults(n, (hf_lut_variant)v);
        float *t = t_lut_alloc(n);
        double *ref = (double *)malloc(sizeof(double) * 3 * n * n), mx[3];
        int i, j, c, bad = 0;
        CHECK_EQ_INT(hf_lut_bake_n(&p, 0, n, t), HF_OK);
        for (j = 0; j < n; ++j)
            for (i = 0; i < n; ++i)
                for (c = 0; c < 3; ++c)
                    ref[3 * (j * n + i) + c] = t_ref_n(
                        c, p.eta, fabs((2.0 * i + 1 - n) / n),
                        acos((2.0 * j + 1 - n) / n), p.sigma_a, v, 0.02);
        for (c = 0; c < 3; ++c) { /* max stands in for the 99.9th pct */
            mx[c] = 0.0;
            for (i = 0; i < n * n; ++i)
                if (ref[3 * i + c] > mx[c]) mx[c] = ref[3 * i + c];
        }
        for (j = 0; j < n; ++j)
            for (i = 0; i < n; ++i)
                for (c = 0; c < 3; ++c) {
                    double x = t[4 * (j * n + i) + c], r = ref[3 * (j * n + i) + c];
                    double tol = 1e-5 * mx[c] + 1e-3 * fabs(r);
                    CHECK(t_is_finite((float)x));
                    if (fabs(x - r) > tol) {
                        double lo = 1e300, hi = -1e300, d = 2e-6;
                        int a, b;
                        for (a = -1; a <= 1; ++a)
                            for (b = -1; b <= 1; ++b) {
                                double u = (i + 0.5) / n + a * d;
                                double w = (j + 0.5) / n + b * d;
                                double cv = 2 * w - 1;
                                double y;
                                cv = cv < -1 ? -1 : (cv > 1 ? 1 : cv);
                                y = t_ref_n(c, p.eta, fabs(2 * u - 1), acos(cv),
                                            p.sigma_a, v, 0.02);
                                if (y < lo) lo = y;
                                if (y > hi) hi = y;
                            }
                        if (x < lo - tol || x > hi + tol) ++bad;
                    }
                }
        CHECK_EQ_INT(bad, 0);
        free(t);
        free(ref);
    }
}

static int t_lut_all_ok(const float *t, int n, int alpha_le_1)
{
    size_t i;
    for (i = 0; i < 4u * (size_t)n * (size_t)n; ++i) {
        if (!t_is_finite(t[i]) || t[i] < 0.0f) return 0;
        if (alpha_le_1 && (i & 3) == 3 && t[i] > 1.0f) return 0;
    }
    return 1;
}

/* No NaN, inf or negative value anywhere over the ends of every range. */
static void test_lut_extremes_finite(void)
{
    static const double etas[2] = {1.2, 3.0};
    static const double sigmas[4] = {0.0, 1e-3, 1e30, 1e308};
    static const double betas[6] = {5, 10, 1e-3, 1e-40, 4.9e-324, 1e308};
    static const double alphas[5] = {-10, -5, 0, 1e5, -1e308};
    static const int sizes[6] = {1, 2, 3, 5, 17, 64};
    float *a = t_lut_alloc(64), *b = t_lut_alloc(64);
    int e, s, z, v, k, fails = 0;
    for (z = 0; z < 6; ++z)
        for (v = 0; v < 2; ++v)
            for (e = 0; e < 2; ++e)
                for (s = 0; s < 4; ++s) {
                    int n = sizes[z];
                    hf_lut_params p = t_lut_defaults(n, (hf_lut_variant)v);
                    p.eta = etas[e];
                    p.sigma_a = sigmas[s];
                    p.sigma_a_rgb[0] = sigmas[s];
                    p.sigma_a_rgb[1] = 0.0;
                    p.sigma_a_rgb[2] = sigmas[3 - s];
                    CHECK_EQ_INT(hf_lut_bake_n(&p, 0, n, a), HF_OK);
                    if (!t_lut_all_ok(a, n, 1)) ++fails;
                    for (k = 0; k < n * n; ++k)
                        if (a[4 * k + 3] != 1.0f) ++fails;
                    CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, 0, n, a, b), HF_OK);
                    if (!t_lut_all_ok(a, n, 0) || !t_lut_all_ok(b, n, 0))
                        ++fails;
                }
    for (z = 0; z < 6; ++z)
        for (s = 0; s < 6; ++s)
            for (e = 0; e < 5; ++e) {
                int n = sizes[z];
                hf_lut_params p = t_lut_defaults(n, HF_LUT_CUBIC);
                p.beta_r_deg = betas[s];
                p.alpha_r_deg = alphas[e];
                CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n, a), HF_OK);
                if (!t_lut_all_ok(a, n, 1)) ++fails;
            }
    /* a width too narrow for float stores FLT_MAX on the exact peak */
    {
        hf_lut_params p = t_lut_defaults(3, HF_LUT_CUBIC);
        p.alpha_r_deg = 0.0;
        p.beta_r_deg = 1e-300;
        CHECK_EQ_INT(hf_lut_bake_m(&p, 0, 3, a), HF_OK);
        CHECK(a[4 * (1 * 3 + 1) + 0] == FLT_MAX); /* theta_h = 0 */
        CHECK(a[4 * (0 * 3 + 0) + 0] == 0.0f);
    }
    CHECK_EQ_INT(fails, 0);
    free(a);
    free(b);
}

/* N at full size for the extreme indices: finite, non-negative, and the
   caustic clamp bounds each root's TRT contribution by A / J_MIN <= 50. */
static void test_lut_extremes_full_size(void)
{
    static const double etas[2] = {1.2, 3.0};
    float *a = t_lut_alloc(256);
    int e, v;
    size_t i;
    for (e = 0; e < 2; ++e)
        for (v = 0; v < 2; ++v) {
            hf_lut_params p = t_lut_defaults(256, (hf_lut_variant)v);
            p.eta = etas[e];
            p.sigma_a = 0.0;
            CHECK_EQ_INT(hf_lut_bake_n(&p, 0, 256, a), HF_OK);
            CHECK(t_lut_all_ok(a, 256, 1));
            for (i = 0; i < 4u * 256 * 256; i += 4) CHECK(a[i + 2] <= 150.0f);
        }
    free(a);
}

/* Every refused call leaves the output bytes as they were. */
static void test_lut_invalid_writes_nothing(void)
{
    const int n = 16;
    size_t bytes = sizeof(float) * 4u * n * n;
    float *a = t_lut_alloc(n), *b = t_lut_alloc(n);
    unsigned char *keep = (unsigned char *)malloc(bytes);
    hf_lut_params p;
    double nan = strtod("nan", NULL);
    int k;
    memset(keep, 0xab, bytes);
    memset(a, 0xab, bytes);
    memset(b, 0xab, bytes);
    for (k = 0; k < 9; ++k) {
        hf_result want = HF_ERROR_BAD_PARAMETER;
        p = t_lut_defaults(n, HF_LUT_CUBIC);
        switch (k) {
        case 0: p.eta = nan; want = HF_ERROR_NON_FINITE; break;
        case 1: p.eta = 1.0; break;
        case 2: p.beta_r_deg = 0.0; break;
        case 3: p.sigma_a = -1.0; break;
        case 4: p.sigma_a_rgb[0] = -1.0; break;
        case 5: p.size = 0; want = HF_ERROR_BAD_COUNT; break;
        case 6: p.variant = (hf_lut_variant)5; break;
        case 7: p.alpha_r_deg = HUGE_VAL; want = HF_ERROR_NON_FINITE; break;
        default: p.size = 5000; want = HF_ERROR_BAD_COUNT; break;
        }
        CHECK_EQ_INT(hf_lut_bake_m(&p, 0, 1, a), want);
        CHECK_EQ_INT(hf_lut_bake_n(&p, 0, 1, a), want);
        CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, 0, 1, a, b), want);
    }
    p = t_lut_defaults(n, HF_LUT_CUBIC);
    CHECK_EQ_INT(hf_lut_bake_m(NULL, 0, n, a), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_lut_bake_n(&p, 0, n, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, 0, n, a, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, 0, n, NULL, b), HF_ERROR_NULL_POINTER);
    /* bad ranges, including one whose end overflows int */
    CHECK_EQ_INT(hf_lut_bake_m(&p, -1, 2, a), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_lut_bake_m(&p, 0, -1, a), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n + 1, a), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_lut_bake_n(&p, n - 2, 3, a), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_lut_bake_n(&p, n + 1, 0, a), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, 1, 0x7fffffff, a, b),
                 HF_ERROR_BAD_RANGE);
    /* empty ranges are valid and write nothing */
    CHECK_EQ_INT(hf_lut_bake_m(&p, n, 0, a), HF_OK);
    CHECK_EQ_INT(hf_lut_bake_n(&p, 3, 0, a), HF_OK);
    CHECK(memcmp(a, keep, bytes) == 0);
    CHECK(memcmp(b, keep, bytes) == 0);
    /* a valid range writes exactly its rows */
    CHECK_EQ_INT(hf_lut_bake_n(&p, 3, 2, a), HF_OK);
    CHECK(memcmp(a, keep, sizeof(float) * 4u * 3 * n) == 0);
    CHECK(memcmp((unsigned char *)a + sizeof(float) * 4u * 5 * n,
                 keep + sizeof(float) * 4u * 5 * n,
                 bytes - sizeof(float) * 4u * 5 * n) == 0);
    CHECK(memcmp((unsigned char *)a + sizeof(float) * 4u * 3 * n, keep,
                 sizeof(float) * 4u * 2 * n) != 0);
    free(a);
    free(b);
    free(keep);
}

/* Splitting the rows over calls (as threads would) changes no byte. */
static void test_lut_row_splits_identical(void)
{
    static const int sizes[3] = {37, 64, 1};
    int s, v, w;
    hf_rng rng;
    hf_rng_seed(&rng, 12345u, 7u);
    for (s = 0; s < 3; ++s)
        for (v = 0; v < 2; ++v) {
            int n = sizes[s];
            size_t bytes = sizeof(float) * 4u * n * n;
            hf_lut_params p = t_lut_defaults(n, (hf_lut_variant)v);
            float *whole[4], *part[4];
            for (w = 0; w < 4; ++w) {
                whole[w] = t_lut_alloc(n);
                part[w] = t_lut_alloc(n);
                memset(part[w], 0x5a, bytes);
            }
            p.sigma_a_rgb[0] = 0.05;
            p.sigma_a_rgb[2] = 1.5;
            hf_lut_bake_m(&p, 0, n, whole[0]);
            hf_lut_bake_n(&p, 0, n, whole[1]);
            hf_lut_bake_n_rgb(&p, 0, n, whole[2], whole[3]);
            {
                int first = 0;
                while (first < n) {
                    int count = 1 + (int)hf_rng_below(&rng, 9u);
                    if (count > n - first) count = n - first;
                    CHECK_EQ_INT(hf_lut_bake_n(&p, first, count, part[1]), HF_OK);
                    CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, first, count, part[2],
                                                   part[3]),
                                 HF_OK);
                    first += count;
                }
                /* M in reverse single rows */
                for (first = n - 1; first >= 0; --first)
                    CHECK_EQ_INT(hf_lut_bake_m(&p, first, 1, part[0]), HF_OK);
            }
            for (w = 0; w < 4; ++w) {
                CHECK(memcmp(whole[w], part[w], bytes) == 0);
                free(whole[w]);
                free(part[w]);
            }
        }
}

/* Section 8: each per-RGB channel is bit for bit the scalar bake with that
   sigma_a; alpha holds N_R. */
static void test_lut_rgb_matches_scalar(void)
{
    const int n = 33;
    int v, k, i;
    for (v = 0; v < 2; ++v) {
        hf_lut_params p = t_lut_defaults(n, (hf_lut_variant)v);
        float *tt = t_lut_alloc(n), *trt = t_lut_alloc(n), *s = t_lut_alloc(n);
        int diff = 0;
        p.sigma_a_rgb[0] = 0.0;
        p.sigma_a_rgb[1] = 0.37;
        p.sigma_a_rgb[2] = 2.5;
        CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, 0, n, tt, trt), HF_OK);
        for (k = 0; k < 3; ++k) {
            p.sigma_a = p.sigma_a_rgb[k];
            CHECK_EQ_INT(hf_lut_bake_n(&p, 0, n, s), HF_OK);
            for (i = 0; i < n * n; ++i) {
                diff += memcmp(&tt[4 * i + k], &s[4 * i + 1], 4) != 0;
                diff += memcmp(&trt[4 * i + k], &s[4 * i + 2], 4) != 0;
                diff += memcmp(&tt[4 * i + 3], &s[4 * i + 0], 4) != 0;
                diff += memcmp(&trt[4 * i + 3], &s[4 * i + 0], 4) != 0;
            }
        }
        CHECK_EQ_INT(diff, 0);
        /* absorption dims TT where it exists (row 0: phi near pi) */
        CHECK(tt[4 * (n - 1) + 0] > tt[4 * (n - 1) + 1]);
        CHECK(tt[4 * (n - 1) + 1] > tt[4 * (n - 1) + 2]);
        CHECK(tt[4 * (n - 1) + 2] > 0.0f);
        free(tt);
        free(trt);
        free(s);
    }
}

/* N: columns i and n-1-i hold |cos theta_d| alike; alpha is 1. */
static void test_lut_n_mirror_columns(void)
{
    const int n = 40;
    hf_lut_params p = t_lut_defaults(n, HF_LUT_CUBIC);
    float *t = t_lut_alloc(n);
    int i, j, diff = 0;
    CHECK_EQ_INT(hf_lut_bake_n(&p, 0, n, t), HF_OK);
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            diff += memcmp(t + 4 * (j * n + i), t + 4 * (j * n + n - 1 - i),
                           4 * sizeof(float)) != 0;
            diff += t[4 * (j * n + i) + 3] != 1.0f;
        }
    CHECK_EQ_INT(diff, 0);
    free(t);
}

/* Section 9: scales are the channel maxima (1 for an all-zero channel,
   exactly 1 for M.a and N.a), q = floor(255 clamp(x / s, 0, 1) + 0.5). */
static void test_lut_to_u8(void)
{
    const int n = 32;
    size_t count = 4u * n * n, i;
    hf_lut_params p = t_lut_defaults(n, HF_LUT_CUBIC);
    float *m = t_lut_alloc(n), *nn = t_lut_alloc(n), sc[4], mx[4];
    unsigned char *q = (unsigned char *)malloc(count), *q2 =
        (unsigned char *)malloc(count);
    int k, c, wrong = 0;
    hf_lut_bake_m(&p, 0, n, m);
    hf_lut_bake_n(&p, 0, n, nn);
    for (k = 0; k < 2; ++k) {
        const float *t = k ? nn : m;
        CHECK_EQ_INT(hf_lut_to_u8(t, n, NULL, q, sc), HF_OK);
        for (c = 0; c < 4; ++c) mx[c] = 0.0f;
        for (i = 0; i < count; ++i)
            if (t[i] > mx[i & 3]) mx[i & 3] = t[i];
        for (c = 0; c < 4; ++c) CHECK(sc[c] == mx[c]);
        CHECK(sc[3] == 1.0f);
        for (i = 0; i < count; ++i) {
            double y = t[i] / (double)sc[i & 3];
            int want = (int)floor(255.0 * (y > 1 ? 1 : y) + 0.5);
            wrong += q[i] != want;
        }
        CHECK_EQ_INT(wrong, 0);
        /* the maximum texel of each channel maps to 255 */
        for (c = 0; c < 4; ++c) {
            int seen = 0;
            for (i = (size_t)c; i < count; i += 4) seen |= q[i] == 255;
            CHECK(seen);
        }
    }
    /* given scales: values above clip; scales_out may be NULL */
    {
        float given[4] = {0.5f, 1.0f, 2.0f, 4.0f};
        CHECK_EQ_INT(hf_lut_to_u8(m, n, given, q, NULL), HF_OK);
        for (i = 0; i < count; ++i) {
            double y = m[i] / (double)given[i & 3];
            int want = (int)floor(255.0 * (y > 1 ? 1 : y) + 0.5);
            wrong += q[i] != want;
        }
        CHECK_EQ_INT(wrong, 0);
    }
    /* rounding at the half-way points, an all-zero channel, negatives */
    {
        float t[4 * 4], s4[4];
        unsigned char o[16];
        for (i = 0; i < 16; ++i) t[i] = 0.0f;
        t[0] = 1.0f;                /* R max */
        t[4] = 0.5f / 255.0f;       /* exactly between 0 and 1: rounds up */
        t[8] = 0.49f / 255.0f;      /* below: 0 */
        t[12] = 127.5f / 255.0f;    /* 127.5 -> 128 */
        t[5] = -1.0f;               /* G: only a negative -> scale 1, code 0 */
        t[7] = 0.25f;               /* A max 0.25 */
        CHECK_EQ_INT(hf_lut_to_u8(t, 2, NULL, o, s4), HF_OK);
        CHECK(s4[0] == 1.0f && s4[1] == 1.0f && s4[2] == 1.0f &&
              s4[3] == 0.25f);
        CHECK_EQ_INT(o[0], 255);
        CHECK_EQ_INT(o[4], 1);
        CHECK_EQ_INT(o[8], 0);
        CHECK_EQ_INT(o[12], 128);
        CHECK_EQ_INT(o[5], 0);
        CHECK_EQ_INT(o[7], 255);
    }
    /* errors write nothing */
    {
        float bad_scale[4] = {1.0f, 0.0f, 1.0f, 1.0f};
        float sc_keep[4] = {-7.0f, -7.0f, -7.0f, -7.0f};
        memset(q, 0xcd, count);
        memcpy(q2, q, count);
        memcpy(sc, sc_keep, sizeof sc);
        CHECK_EQ_INT(hf_lut_to_u8(NULL, n, NULL, q, sc), HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_lut_to_u8(m, n, NULL, NULL, sc), HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_lut_to_u8(m, 0, NULL, q, sc), HF_ERROR_BAD_COUNT);
        CHECK_EQ_INT(hf_lut_to_u8(m, HF_LUT_MAX_SIZE + 1, NULL, q, sc),
                     HF_ERROR_BAD_COUNT);
        CHECK_EQ_INT(hf_lut_to_u8(m, n, bad_scale, q, sc),
                     HF_ERROR_BAD_PARAMETER);
        bad_scale[1] = strtof("nan", NULL);
        CHECK_EQ_INT(hf_lut_to_u8(m, n, bad_scale, q, sc),
                     HF_ERROR_BAD_PARAMETER);
        m[count - 2] = strtof("inf", NULL); /* the very last texel */
        CHECK_EQ_INT(hf_lut_to_u8(m, n, NULL, q, sc), HF_ERROR_NON_FINITE);
        CHECK(memcmp(q, q2, count) == 0);
        CHECK(memcmp(sc, sc_keep, sizeof sc) == 0);
    }
    free(m);
    free(nn);
    free(q);
    free(q2);
}

static void test_lut_eval_errors(void)
{
    hf_lut_params p = t_lut_defaults(64, HF_LUT_CUBIC);
    double o[3] = {-1, -1, -1}, nan = strtod("nan", NULL);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 1.5, 1.0, o), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, -0.01, o), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, 3.2, o), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_lut_eval_n(&p, nan, 1.0, o), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, HUGE_VAL, o), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, 1.0, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_lut_eval_m(&p, nan, o), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_lut_eval_m(NULL, 0.0, o), HF_ERROR_NULL_POINTER);
    p.eta = 5.0;
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, 1.0, o), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_lut_eval_m(&p, 0.0, o), HF_ERROR_BAD_PARAMETER);
    CHECK(o[0] == -1 && o[1] == -1 && o[2] == -1);
    /* size is not checked by the evaluators */
    p = t_lut_defaults(0, HF_LUT_CUBIC);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, 1.0, o), HF_OK);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.0, T_PI, o), HF_OK); /* both ends */
    CHECK(o[0] >= 0.0 && o[1] >= 0.0 && o[2] >= 0.0);
}

/* The texture samples texel centres: texel (i, j) of the bake equals the
   evaluators at u_i = (i + 0.5) / n, v_j = (j + 0.5) / n. */
static void test_lut_texel_centres(void)
{
    const int n = 8;
    hf_lut_params p = t_lut_defaults(n, HF_LUT_CUBIC);
    float *m = t_lut_alloc(n), *t = t_lut_alloc(n);
    int i, j, c;
    hf_lut_bake_m(&p, 0, n, m);
    hf_lut_bake_n(&p, 0, n, t);
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            double u = (i + 0.5) / n, v = (j + 0.5) / n, o[3];
            double ti = asin(2 * u - 1), tr = asin(2 * v - 1);
            hf_lut_eval_m(&p, 0.5 * (ti + tr), o);
            for (c = 0; c < 3; ++c)
                CHECK_NEAR(m[4 * (j * n + i) + c], o[c], 1e-6 * o[c] + 1e-30);
            CHECK_NEAR(m[4 * (j * n + i) + 3], cos(0.5 * (tr - ti)), 1e-7);
            hf_lut_eval_n(&p, 2 * u - 1, acos(2 * v - 1), o);
            for (c = 0; c < 3; ++c)
                CHECK_NEAR(t[4 * (j * n + i) + c], o[c], 1e-6 * o[c] + 1e-30);
        }
    free(m);
    free(t);
}

static void run_lut_tests(void)
{
    RUN(test_lut_params_init_defaults);
    RUN(test_lut_validate_codes);
    RUN(test_lut_n_spot_values);
    RUN(test_lut_n_closed_forms);
    RUN(test_lut_m_spot_values);
    RUN(test_lut_texels_n64);
    RUN(test_lut_channel_sums_n64);
    RUN(test_lut_m_symmetric);
    RUN(test_lut_m_unit_area);
    RUN(test_lut_n_energy_identity);
    RUN(test_lut_n_energy_no_absorption);
    RUN(test_lut_n_caustic_clamp);
    RUN(test_lut_n_conformance);
    RUN(test_lut_extremes_finite);
    RUN(test_lut_extremes_full_size);
    RUN(test_lut_invalid_writes_nothing);
    RUN(test_lut_row_splits_identical);
    RUN(test_lut_rgb_matches_scalar);
    RUN(test_lut_n_mirror_columns);
    RUN(test_lut_to_u8);
    RUN(test_lut_eval_errors);
    RUN(test_lut_texel_centres);
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
    run_lut_tests();
    printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}
