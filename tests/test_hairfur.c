/* test_hairfur.c - the unit tests of hairfur.h, one function per behaviour.

   Build and run: make test (C and C++, -O2 and ASan+UBSan, gcc and clang),
   or make check (one build). Prints one line per failed check and ends
   with "N passed, N failed", counting the tests that ran; exits non-zero
   when anything failed. Arguments pick tests by the start of their names,
   "test_" left out or not: build/test_gcc_c99 ropes_ fur_ runs the rope
   and fur tests alone (make check T="ropes_ fur_"); --list names them.

   CONTENTS (the sections of hairfur.h, in its order; each list, right
   after its section's tests, is what main runs)

       harness               CHECK, CHECK_NEAR, CHECK_EQ_INT, RUN, the
                             counting allocator
       shared helpers        maps, meshes, tessellation, ropes, strands,
                             ribbons, LUTs, the fur scene, bad input
       1. configuration      T_CONFIG_TESTS
       2. random numbers     T_RNG_TESTS
       3. maps               T_MAP_TESTS
       4. meshes             T_MESH_TESTS
       5. grow               T_DENSITY_TESTS (5.1 estimators),
                             T_TESS_TESTS (5.2 tessellation),
                             T_GUIDES_TESTS (5.3), T_PLACE_TESTS (5.4),
                             T_STRAND_TESTS (5.5 maps on strands, 5.6
                             bindings)
       6. ropes              T_ROPES_TESTS, T_CONTACT_TESTS (collisions
                             that never stretch), T_GRID_TESTS (hair-hair
                             interaction)
       7. interpolation, LOD T_INTERP_TESTS
       8. ribbons            T_RIBBON_TESTS
       9. LUT baking         T_LUT_TESTS, T_FIBRE_TESTS (the
                             energy-conserving fibre, dual scattering)
      10. the fur object     T_FUR_TESTS
       main                  the lists above, in that order

   A new test goes into its section and onto the section's list: a test
   left off the list is an unused static function, which the strict
   warnings make an error. Each section's test_bad_* tests are its part
   of the bad-input matrix: for every public function each bad input it
   can get (NULL, zero or negative counts, out-of-range indices, NaN and
   infinite values, degenerate geometry, huge factors, bad time steps,
   the eye on a strand): the result code, outputs untouched
   (sentinel-filled and compared), no NaN; and the limits (counts near
   INT_MAX, byte sizes that would overflow size_t). */

#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"

#include <fenv.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The tests compare kernels with formulas written here and call internal
   kernels inline, so this file rounds as the implementation does: no
   a * b + c fused into an FMA, whatever -march or the language mode. */
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

/* ==== harness ============================================================= */

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

#define CHECK_EQ_STR(a, b)                                                     \
    do {                                                                       \
        const char *t_sa_ = (a), *t_sb_ = (b);                                 \
        if (strcmp(t_sa_, t_sb_) != 0) {                                       \
            printf("%s:%d: %s: CHECK_EQ_STR(%s, %s) failed: \"%s\" vs \"%s\"\n", \
                   __FILE__, __LINE__, t_current, #a, #b, t_sa_, t_sb_);       \
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

/* |x - r| <= tol * |r| */
#define CHECK_REL(x, r, tol) CHECK_NEAR((x), (r), (tol) * fabs((double)(r)))

/* Under clang each test is called through a volatile pointer, so none
   is inlined into main: clang's optimizer, with the sanitizers above all,
   spent half a minute on main as one function of every test. (gcc keeps
   the direct call: on each test alone its -Warray-bounds and
   -Wfree-nonheap-object warn on error paths that never run.) */
#if defined(__clang__)
#define T_CALL(fn)                                                             \
    do {                                                                       \
        void (*volatile t_fn_)(void) = fn;                                     \
        t_fn_();                                                               \
    } while (0)
#else
#define T_CALL(fn) fn()
#endif

/* Which tests run: every one, or (arguments) those whose names begin
   with one of the prefixes given, with or without the "test_" ("ropes_
   grid_": the rope and grid tests; "bad_" the bad-input matrix); --list
   prints the names it would run instead. */
static int t_argc, t_list;
static char **t_argv;
static int t_pick(const char *name)
{
    const char *bare = strncmp(name, "test_", 5) ? name : name + 5;
    int i, any = 0, hit = 0;
    for (i = 1; i < t_argc; ++i) {
        size_t n = strlen(t_argv[i]);
        if (!strcmp(t_argv[i], "--list")) continue;
        any = 1;
        hit |= !strncmp(bare, t_argv[i], n) || !strncmp(name, t_argv[i], n);
    }
    if (any && !hit) return 0;
    if (t_list) {
        printf("%s\n", name);
        return 0;
    }
    return 1;
}

#define RUN(fn)                                                                \
    do {                                                                       \
        if (!t_pick(#fn)) break;                                               \
        t_current = #fn;                                                       \
        t_current_failed = 0;                                                  \
        T_CALL(fn);                                                            \
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

/* ==== shared helpers ====================================================== */

/* ---- constants ----------------------------------------------------------- */

#define T_PI 3.14159265358979323846
#define T_DEG (T_PI / 180.0)

/* ---- maps: a 4 x 2 gray map, float maps, a smooth blob ------------------- */

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

static hf_map t_f32_map(const float *data, int w, int h, int channels)
{
    hf_map m;
    memset(&m, 0, sizeof m);
    m.data = data;
    m.width = w;
    m.height = h;
    m.channels = channels;
    m.format = HF_MAP_F32;
    return m;
}

/* A smooth map with values in [0.05, 1]: a gradient plus a bump. */
static float *t_blob_data(int w, int h)
{
    float *d = (float *)malloc(sizeof(float) * (size_t)w * (size_t)h);
    int x, y;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            float u = ((float)x + 0.5f) / (float)w;
            float v = ((float)y + 0.5f) / (float)h;
            float du = u - 0.3f, dv = v - 0.6f;
            float val = 0.05f + 0.45f * u +
                        0.5f * (float)exp(-(du * du + dv * dv) / 0.02);
            d[y * w + x] = val > 1.0f ? 1.0f : val;
        }
    return d;
}

/* ---- meshes: an interleaved unit quad, n x n grids, triangle areas ------- */

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

/* An n x n grid of quads over [0, size]^2 in z = 0, UV = position / size,
   two triangles per quad, counter-clockwise seen from +z. */
typedef struct t_grid {
    float *pos, *uv, *nrm;
    uint32_t *idx;
    hf_mesh mesh;
} t_grid;

static t_grid t_make_grid(int n, float size)
{
    t_grid g;
    int x, y, v = (n + 1) * (n + 1), t = 0;
    g.pos = (float *)malloc(sizeof(float) * 3 * (size_t)v);
    g.uv = (float *)malloc(sizeof(float) * 2 * (size_t)v);
    g.nrm = (float *)malloc(sizeof(float) * 3 * (size_t)v);
    g.idx = (uint32_t *)malloc(sizeof(uint32_t) * 6 * (size_t)n * (size_t)n);
    for (y = 0; y <= n; ++y)
        for (x = 0; x <= n; ++x) {
            int i = y * (n + 1) + x;
            g.uv[2 * i] = (float)x / (float)n;
            g.uv[2 * i + 1] = (float)y / (float)n;
            g.pos[3 * i] = g.uv[2 * i] * size;
            g.pos[3 * i + 1] = g.uv[2 * i + 1] * size;
            g.pos[3 * i + 2] = 0.0f;
            g.nrm[3 * i] = 0.0f;
            g.nrm[3 * i + 1] = 0.0f;
            g.nrm[3 * i + 2] = 1.0f;
        }
    for (y = 0; y < n; ++y)
        for (x = 0; x < n; ++x) {
            uint32_t a = (uint32_t)(y * (n + 1) + x), b = a + 1,
                     c = a + (uint32_t)(n + 1), d = c + 1;
            g.idx[t++] = a;
            g.idx[t++] = b;
            g.idx[t++] = d;
            g.idx[t++] = a;
            g.idx[t++] = d;
            g.idx[t++] = c;
        }
    memset(&g.mesh, 0, sizeof g.mesh);
    g.mesh.positions = g.pos;
    g.mesh.uvs = g.uv;
    g.mesh.normals = g.nrm;
    g.mesh.vertex_count = v;
    g.mesh.indices = g.idx;
    g.mesh.triangle_count = 2 * n * n;
    return g;
}

static void t_free_grid(t_grid *g)
{
    free(g->pos);
    free(g->uv);
    free(g->nrm);
    free(g->idx);
}

static double t_tri_area(const float *pos, const uint32_t *tri)
{
    return (double)hf_triangle_area(pos + 3 * tri[0], pos + 3 * tri[1],
                                    pos + 3 * tri[2]);
}

static double t_uv_area(const float *uv, const uint32_t *tri)
{
    const float *a = uv + 2 * tri[0], *b = uv + 2 * tri[1],
                *c = uv + 2 * tri[2];
    return 0.5 * fabs((double)(b[0] - a[0]) * (c[1] - a[1]) -
                      (double)(c[0] - a[0]) * (b[1] - a[1]));
}

/* ---- tessellation into allocated arrays ---------------------------------- */

/* hf_tessellate twice (count, fill) into freshly allocated arrays. */
typedef struct t_tess {
    hf_tess_output out;
    hf_result r;
} t_tess;

static t_tess t_tessellate(const hf_mesh *mesh, const hf_map *density,
                           const hf_tess_params *p)
{
    t_tess t;
    memset(&t, 0, sizeof t);
    t.r = hf_tessellate(mesh, density, p, &t.out);
    if (t.r != HF_OK) return t;
    t.out.indices =
        (uint32_t *)malloc(sizeof(uint32_t) * 3 * (size_t)t.out.triangle_count);
    t.out.triangle_base =
        (uint32_t *)malloc(sizeof(uint32_t) * (size_t)t.out.triangle_count);
    t.out.added = (hf_tess_vertex *)malloc(
        sizeof(hf_tess_vertex) * (size_t)(t.out.added_count + 1));
    t.out.positions =
        (float *)malloc(sizeof(float) * 3 * (size_t)t.out.vertex_count);
    t.out.uvs = (float *)malloc(sizeof(float) * 2 * (size_t)t.out.vertex_count);
    t.out.triangle_capacity = t.out.triangle_count;
    t.out.added_capacity = t.out.added_count;
    t.out.vertex_capacity = t.out.vertex_count;
    t.r = hf_tessellate(mesh, density, p, &t.out);
    return t;
}

static void t_free_tess(t_tess *t)
{
    free(t->out.indices);
    free(t->out.triangle_base);
    free(t->out.added);
    free(t->out.positions);
    free(t->out.uvs);
}

static hf_mesh t_tess_mesh(const t_tess *t)
{
    hf_mesh m;
    memset(&m, 0, sizeof m);
    m.positions = t->out.positions;
    m.uvs = t->out.uvs;
    m.vertex_count = t->out.vertex_count;
    m.indices = t->out.indices;
    m.triangle_count = t->out.triangle_count;
    return m;
}

/* ---- ropes: owned ropes, poses, snapshots, measures, a head sphere ------- */

/* Ropes owned by a test: the struct plus malloc'd memory. */
typedef struct tr_set {
    hf_ropes ro;
    void *mem;
    size_t size;
} tr_set;

static int tr_open(tr_set *s, int ropes, int points)
{
    memset(s, 0, sizeof *s);
    if (hf_ropes_memory_size(ropes, points, &s->size) != HF_OK) return 0;
    s->mem = malloc(s->size);
    if (!s->mem) return 0;
    return hf_ropes_init(&s->ro, ropes, points, s->mem, s->size) == HF_OK;
}

static void tr_close(tr_set *s) { free(s->mem); }

/* Straight rest pose for rope r: from root[r] along dir[r], total length
   len, written rope-major into pos. */
static void tr_straight(float *pos, int r, int points, const float *root,
                        const float *dir, float len)
{
    int j;
    for (j = 0; j < points; ++j) {
        float t = len * (float)j / (float)(points - 1);
        float *o = pos + 3 * ((size_t)r * points + j);
        o[0] = root[0] + dir[0] * t;
        o[1] = root[1] + dir[1] * t;
        o[2] = root[2] + dir[2] * t;
    }
}

/* Every particle (current and previous) finite. */
static int tr_finite(const hf_ropes *ro)
{
    size_t i, n = (size_t)ro->rope_count * ro->points;
    for (i = 0; i < n; ++i)
        if (!t_is_finite(ro->x[i]) || !t_is_finite(ro->y[i]) ||
            !t_is_finite(ro->z[i]) || !t_is_finite(ro->px[i]) ||
            !t_is_finite(ro->py[i]) || !t_is_finite(ro->pz[i]))
            return 0;
    return 1;
}

/* The same points, bytes and all (with prev: the previous ones too). */
static int tr_same(const hf_ropes *a, const hf_ropes *b, int prev)
{
    const size_t n = sizeof(float) * (size_t)a->rope_count * a->points;
    int same = memcmp(a->x, b->x, n) == 0 && memcmp(a->y, b->y, n) == 0 &&
               memcmp(a->z, b->z, n) == 0;
    if (prev)
        same = same && memcmp(a->px, b->px, n) == 0 &&
               memcmp(a->py, b->py, n) == 0 && memcmp(a->pz, b->pz, n) == 0;
    return same;
}

static void tr_snapshot(const hf_ropes *ro, float *out)
{
    hf_ropes_get_positions(ro, 0, ro->rope_count, out, 0);
}

/* Largest distance any particle moved between two snapshots. */
static double tr_max_move(const float *a, const float *b, size_t points)
{
    double m = 0.0;
    size_t i;
    for (i = 0; i < points; ++i) {
        double dx = a[3 * i] - b[3 * i], dy = a[3 * i + 1] - b[3 * i + 1],
               dz = a[3 * i + 2] - b[3 * i + 2];
        double d = sqrt(dx * dx + dy * dy + dz * dz);
        if (d > m) m = d;
    }
    return m;
}

/* Kinetic energy (unit mass per non-root point) from two snapshots. */
static double tr_kinetic(const float *a, const float *b, int ropes,
                         int points, double dt)
{
    double e = 0.0;
    int r, j;
    for (r = 0; r < ropes; ++r)
        for (j = 1; j < points; ++j) {
            size_t i = 3 * ((size_t)r * points + j);
            double vx = (a[i] - b[i]) / dt, vy = (a[i + 1] - b[i + 1]) / dt,
                   vz = (a[i + 2] - b[i + 2]) / dt;
            e += 0.5 * (vx * vx + vy * vy + vz * vz);
        }
    return e;
}

/* Rotate v about unit axis k by angle (Rodrigues), in double. */
static void tr_rotate(const double *k, double ang, const float *v, float *out)
{
    double c = cos(ang), s = sin(ang);
    double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    double cx = k[1] * v[2] - k[2] * v[1], cy = k[2] * v[0] - k[0] * v[2],
           cz = k[0] * v[1] - k[1] * v[0];
    out[0] = (float)(v[0] * c + cx * s + k[0] * kv * (1 - c));
    out[1] = (float)(v[1] * c + cy * s + k[1] * kv * (1 - c));
    out[2] = (float)(v[2] * c + cz * s + k[2] * kv * (1 - c));
}

static double tr_dist_seg(const float *p, const hf_collider *c)
{
    double ax = c->a[0], ay = c->a[1], az = c->a[2], t = 0.0;
    double ex = 0, ey = 0, ez = 0, dx, dy, dz;
    if (c->type == HF_COLLIDER_CAPSULE) {
        double l2;
        ex = c->b[0] - ax;
        ey = c->b[1] - ay;
        ez = c->b[2] - az;
        l2 = ex * ex + ey * ey + ez * ez;
        if (l2 > 0)
            t = ((p[0] - ax) * ex + (p[1] - ay) * ey + (p[2] - az) * ez) / l2;
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
    }
    dx = p[0] - (ax + ex * t);
    dy = p[1] - (ay + ey * t);
    dz = p[2] - (az + ez * t);
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* A tangent for root normal n: across it in the y-z plane (n not along
   x). */
static void tr_tangent_yz(const float *n, float *t)
{
    const float d = sqrtf(n[1] * n[1] + n[2] * n[2]);
    t[0] = 0.0f;
    t[1] = -n[2] / d;
    t[2] = n[1] / d;
}

/* The same rest shapes (rope-major, packed) and roots in the nset sets
   of s, each holding all its ropes. */
static void tr_rest_all(tr_set *s, int nset, const float *rest,
                        const float *root, const float *nrm, const float *tan)
{
    int k;
    for (k = 0; k < nset; ++k)
        CHECK_EQ_INT(hf_ropes_set_rest(&s[k].ro, 0, s[k].ro.rope_count, rest,
                                       0, root, nrm, tan, 0),
                     HF_OK);
}

/* One 1/60 s step of the same ropes in s[0] (scalar) and s[1] (the best
   level) against colliders col[0 .. ncol); from frame `watch` on, the
   largest point speed of s[0] in the step (m/s) raises *vmax and the
   deepest point inside a collider *deep (a, b: scratch for two
   snapshots). Returns whether the two sets hold the same bytes. */
static int tr_pair_step(tr_set *s, int f, int watch, hf_rope_params *p,
                        const hf_collider *col, int ncol, float *a, float *b,
                        double *vmax, double *deep)
{
    const int n = s[0].ro.rope_count * s[0].ro.points;
    int k, i, c;
    for (k = 0; k < 2; ++k) {
        p->simd = k == 0 ? HF_SIMD_SCALAR : HF_SIMD_AUTO;
        if (k == 0 && f >= watch) tr_snapshot(&s[0].ro, a);
        CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, s[k].ro.rope_count,
                                   1.0f / 60.0f, p, col, ncol),
                     HF_OK);
    }
    if (f >= watch) {
        double v;
        tr_snapshot(&s[0].ro, b);
        v = tr_max_move(a, b, (size_t)n) * 60.0;
        *vmax = v > *vmax ? v : *vmax;
        for (i = 0; i < n; ++i)
            for (c = 0; c < ncol; ++c) {
                const double in = col[c].radius - tr_dist_seg(b + 3 * i,
                                                              &col[c]);
                *deep = in > *deep ? in : *deep;
            }
    }
    return tr_same(&s[0].ro, &s[1].ro, 1);
}

/* Rope r's root on the 0.1 m head sphere at polar angle el and azimuth az:
   its direction, normal (the same), tangent (+y) and root point. */
static void tr_on_head(int r, double el, double az, float *dirs, float *nrm,
                       float *tan, float *root)
{
    float *n = dirs + 3 * r;
    int k;
    n[0] = (float)(sin(el) * cos(az));
    n[1] = (float)cos(el);
    n[2] = (float)(sin(el) * sin(az));
    for (k = 0; k < 3; ++k) {
        nrm[3 * r + k] = n[k];
        tan[3 * r + k] = k == 1 ? 1.0f : 0.0f;
        root[3 * r + k] = 0.1f * n[k];
    }
}

/* ---- strands: bent guides for interpolation and ribbons ------------------ */

enum { TP = 8 }; /* points per strand in the interpolation and ribbon tests */

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

/* ---- ribbons: interleaved vertices, view, checks, half floats ------------ */

typedef struct t_rvert {
    float pos[3], tan[3], tc[3], col[4], c3[2];
} t_rvert;

static hf_ribbon_output t_interleaved(t_rvert *v)
{
    hf_ribbon_output o;
    memset(&o, 0, sizeof o);
    o.position.data = v[0].pos;
    o.tangent.data = v[0].tan;
    o.texcoord.data = v[0].tc;
    o.color.data = v[0].col;
    o.color3d.data = v[0].c3;
    o.position.stride = o.tangent.stride = o.texcoord.stride =
        o.color.stride = o.color3d.stride = (int)sizeof(t_rvert);
    return o;
}

/* The packed 36-byte vertex: position, tangent and texcoord as floats */
static hf_ribbon_output t_packed36(void *base)
{
    unsigned char *b = (unsigned char *)base;
    hf_ribbon_output o;
    memset(&o, 0, sizeof o);
    o.position.data = b;
    o.tangent.data = b + 12;
    o.texcoord.data = b + 24;
    o.position.stride = o.tangent.stride = o.texcoord.stride = 36;
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

/* n bindings to random guides below G with random weights summing to 1;
   length scale lo, plus span times a random number where span > 0 */
static void t_random_bindings(hf_strand_binding *b, int n, int G, hf_rng *r,
                              float lo, float span)
{
    int i, k;
    for (i = 0; i < n; ++i) {
        const float a = hf_rng_float(r), c = hf_rng_float(r) * (1.0f - a);
        for (k = 0; k < 3; ++k) b[i].guide[k] = hf_rng_below(r, (uint32_t)G);
        b[i].weight[0] = a;
        b[i].weight[1] = c;
        b[i].weight[2] = (1.0f - a) - c;
        b[i].length_scale = span > 0.0f ? lo + span * hf_rng_float(r) : lo;
    }
}

static float t_len3(const float *a) { return sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* Side vectors perpendicular to tangent and view; widths exact at the ends;
   every value finite. */
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

/* Half bits to float, exactly. */
static double t_half(uint16_t h)
{
    const int e = (h >> 10) & 31, m = h & 1023;
    const double v = e == 0 ? ldexp((double)m, -24) : ldexp(1024.0 + m, e - 25);
    return (h & 0x8000) ? -v : v;
}

/* ---- LUTs: params, buffers, an independent Marschner model --------------- */

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

/* The model pieces below come straight from docs/marschner-spec.md,
   written independently of the library. Fresnel reflectance, s and p: */
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
    double inv_ctt; /* 1 / cos(theta_t) */
} t_col;

static t_col t_column(double eta, double cd, double sigma)
{
    t_col k;
    double s2 = 1.0 - cd * cd, cos_tt;
    k.eta1 = sqrt(eta * eta - s2) / cd;
    k.eta2 = eta * eta / k.eta1;
    cos_tt = sqrt(eta * eta - s2) / eta;
    k.sigma1 = sigma / cos_tt;
    k.inv_ctt = 1.0 / cos_tt;
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

static int t_lut_all_ok(const float *t, int n, int alpha_le_1)
{
    size_t i;
    for (i = 0; i < 4u * (size_t)n * (size_t)n; ++i) {
        if (!t_is_finite(t[i]) || t[i] < 0.0f) return 0;
        if (alpha_le_1 && (i & 3) == 3 && t[i] > 1.0f) return 0;
    }
    return 1;
}

/* ---- fur: a UV sphere scene, one frame of every stage -------------------- */

/* A small UV sphere with a seam column and split poles, as engines export
   it: (R + 1) * (S + 1) vertices. */
enum { FR = 6, FS = 8 };
typedef struct t_fur_scene {
    float pos[(FR + 1) * (FS + 1) * 3], nrm[(FR + 1) * (FS + 1) * 3];
    float uv[(FR + 1) * (FS + 1) * 2];
    uint32_t idx[FR * FS * 6];
    hf_fur_desc desc;
} t_fur_scene;

static void t_fur_scene_init(t_fur_scene *sc, float radius)
{
    int r, s, k = 0;
    for (r = 0; r <= FR; ++r)
        for (s = 0; s <= FS; ++s) {
            int v = r * (FS + 1) + s;
            /* exact poles: sin(pi) is 1.2e-16, and guides weld by exact
               position, as an exporter's duplicated vertices are */
            double th = 3.14159265358979 * r / FR;
            double st = (r == 0 || r == FR) ? 0.0 : sin(th);
            double ph = 2 * 3.14159265358979 * (s % FS) / FS;
            sc->nrm[3 * v] = (float)(st * cos(ph));
            sc->nrm[3 * v + 1] = (float)cos(th);
            sc->nrm[3 * v + 2] = (float)(st * sin(ph));
            sc->pos[3 * v] = radius * sc->nrm[3 * v];
            sc->pos[3 * v + 1] = radius * sc->nrm[3 * v + 1];
            sc->pos[3 * v + 2] = radius * sc->nrm[3 * v + 2];
            sc->uv[2 * v] = (float)s / FS;
            sc->uv[2 * v + 1] = (float)r / FR;
        }
    for (r = 0; r < FR; ++r)
        for (s = 0; s < FS; ++s) {
            uint32_t a = (uint32_t)(r * (FS + 1) + s), b = a + 1;
            uint32_t c = a + FS + 1, d = c + 1;
            sc->idx[k++] = a; sc->idx[k++] = b; sc->idx[k++] = c;
            sc->idx[k++] = b; sc->idx[k++] = d; sc->idx[k++] = c;
        }
    memset(&sc->desc, 0, sizeof sc->desc);
    sc->desc.mesh.positions = sc->pos;
    sc->desc.mesh.normals = sc->nrm;
    sc->desc.mesh.uvs = sc->uv;
    sc->desc.mesh.vertex_count = (FR + 1) * (FS + 1);
    sc->desc.mesh.indices = sc->idx;
    sc->desc.mesh.triangle_count = FR * FS * 2;
    sc->desc.points_per_strand = 8;
    sc->desc.max_length = 0.3f;
    sc->desc.total_strands = 500;
    sc->desc.tess_factor = 20.0f; /* some LOD guides */
    sc->desc.seed = 5;
}

/* One frame of every stage over `n` equal ranges, the mesh moved by dx. */
static void t_fur_frame(hf_fur *f, t_fur_scene *sc, float dx, int n,
                        void *vbuf, hf_result *worst)
{
    hf_fur_info info;
    hf_mesh m = sc->desc.mesh;
    float moved[(FR + 1) * (FS + 1) * 3];
    hf_collider col;
    hf_ribbon_params view;
    hf_ribbon_output out;
    int i, o;
    for (i = 0; i < (FR + 1) * (FS + 1) * 3; ++i)
        moved[i] = sc->pos[i] + (i % 3 == 0 ? dx : 0.0f);
    m.positions = moved;
    memset(&col, 0, sizeof col);
    col.type = HF_COLLIDER_SPHERE;
    col.a[0] = dx; /* dx < 0: no collider */
    col.radius = 0.95f;
    memset(&view, 0, sizeof view);
    view.eye[2] = 5.0f;
    view.root_width = 0.01f;
    view.tip_width = 0.002f;
    memset(&out, 0, sizeof out);
    out.position.data = vbuf;
    out.position.stride = 24;
    out.tangent.data = (float *)vbuf + 3;
    out.tangent.stride = 24;
    hf_fur_get_info(f, &info);
    for (o = 0; o < 6; ++o) {
        /* with a grid, its layers (stage 5) between the roots and the
           step, split too */
        static const int order[6] = {0, 5, 1, 2, 3, 4};
        const int stage = order[o];
        int total = stage < 2 ? info.guide_count
                              : stage == 2 ? info.lod_guide_count
                              : stage == 5 ? info.grid_resolution
                                           : info.drawn_strand_count;
        int first = 0;
        for (i = 0; i < n; ++i) {
            int cnt = total * (i + 1) / n - first;
            hf_result r = HF_OK;
            switch (stage) {
            case 0: r = hf_fur_set_roots(f, &m, first, cnt); break;
            case 5: r = hf_fur_build_grid(f, first, cnt); break;
            case 1: r = hf_fur_simulate(f, first, cnt, 1.0f / 60.0f, &col,
                                        dx >= 0.0f); break;
            case 2: r = hf_fur_interpolate_guides(f, first, cnt); break;
            case 3: r = hf_fur_interpolate(f, first, cnt); break;
            case 4: r = hf_fur_ribbons(f, first, cnt, &view, &out); break;
            }
            if (r != HF_OK) *worst = r;
            first += cnt;
        }
    }
}

/* ---- bad input: sentinels, NaN and inf, a packed quad, small ropes ------- */

#define TB_SENT 0xA5u
#define TB_NAN ((float)NAN)
#define TB_INF ((float)INFINITY)

static void tb_fill(void *p, size_t n) { memset(p, TB_SENT, n); }
static int tb_untouched(const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    size_t i;
    for (i = 0; i < n; ++i)
        if (b[i] != TB_SENT) return 0;
    return 1;
}
static int tb_finite(const float *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i)
        if (!t_is_finite(p[i])) return 0;
    return 1;
}

/* The result and the untouched output in one check. */
#define TB_FAILS(call, code, buf, bytes)                                       \
    do {                                                                       \
        tb_fill((buf), (bytes));                                               \
        CHECK_EQ_INT((call), (code));                                          \
        CHECK(tb_untouched((buf), (bytes)));                                   \
    } while (0)

/* t_quad in packed arrays a test may change: 4 vertices, 2 triangles */
typedef struct tb_quad {
    float pos[12], nrm[12], uv[8];
    uint32_t idx[6];
    hf_mesh mesh;
} tb_quad;

static void tb_quad_init(tb_quad *q)
{
    int i;
    for (i = 0; i < 4; ++i) {
        memcpy(q->pos + 3 * i, t_quad[i].pos, sizeof t_quad[i].pos);
        memcpy(q->nrm + 3 * i, t_quad[i].normal, sizeof t_quad[i].normal);
        memcpy(q->uv + 2 * i, t_quad[i].uv, sizeof t_quad[i].uv);
    }
    memcpy(q->idx, t_quad_idx, sizeof t_quad_idx);
    memset(&q->mesh, 0, sizeof q->mesh);
    q->mesh.positions = q->pos;
    q->mesh.normals = q->nrm;
    q->mesh.uvs = q->uv;
    q->mesh.vertex_count = 4;
    q->mesh.indices = q->idx;
    q->mesh.triangle_count = 2;
}

/* Every way a mesh can be bad, with the code the docs give it. Applied
   to every function that validates a whole mesh. */
typedef void (*tb_mesh_case_fn)(const hf_mesh *m, hf_result want,
                                const char *what);

static void tb_for_each_bad_mesh(tb_mesh_case_fn fn)
{
    tb_quad q;
    hf_mesh m;
    tb_quad_init(&q);
    m = q.mesh; m.positions = NULL; fn(&m, HF_ERROR_NULL_POINTER, "positions NULL");
    m = q.mesh; m.indices = NULL; fn(&m, HF_ERROR_NULL_POINTER, "indices NULL");
    m = q.mesh; m.vertex_count = 0; fn(&m, HF_ERROR_BAD_COUNT, "vertex_count 0");
    m = q.mesh; m.vertex_count = -1; fn(&m, HF_ERROR_BAD_COUNT, "vertex_count -1");
    m = q.mesh; m.triangle_count = 0; fn(&m, HF_ERROR_BAD_COUNT, "triangle_count 0");
    m = q.mesh; m.triangle_count = -5; fn(&m, HF_ERROR_BAD_COUNT, "triangle_count -5");
    m = q.mesh; m.position_stride = 8; fn(&m, HF_ERROR_BAD_STRIDE, "position_stride 8");
    m = q.mesh; m.position_stride = -12; fn(&m, HF_ERROR_BAD_STRIDE, "position_stride -12");
    m = q.mesh; m.uv_stride = 4; fn(&m, HF_ERROR_BAD_STRIDE, "uv_stride 4");
    m = q.mesh; m.normal_stride = -1; fn(&m, HF_ERROR_BAD_STRIDE, "normal_stride -1");
    q.idx[4] = 4; fn(&q.mesh, HF_ERROR_INDEX_OUT_OF_RANGE, "index 4 of 4");
    q.idx[4] = 0xffffffffu; fn(&q.mesh, HF_ERROR_INDEX_OUT_OF_RANGE, "index 2^32-1");
    q.idx[4] = 2;
    q.pos[4] = TB_NAN; fn(&q.mesh, HF_ERROR_NON_FINITE, "position NaN");
    q.pos[4] = TB_INF; fn(&q.mesh, HF_ERROR_NON_FINITE, "position inf");
    q.pos[4] = 0.0f;
    q.uv[3] = TB_NAN; fn(&q.mesh, HF_ERROR_NON_FINITE, "uv NaN");
    q.uv[3] = 0.0f;
    q.nrm[5] = -TB_INF; fn(&q.mesh, HF_ERROR_NON_FINITE, "normal -inf");
    q.nrm[3] = q.nrm[4] = q.nrm[5] = 0.0f;
    fn(&q.mesh, HF_ERROR_DEGENERATE, "zero-length normal");
    q.nrm[5] = 1.0f;
}

/* 3 ropes of 4 points along +y from x = 0, 1, 2; on caller memory */
typedef struct tb_ropes {
    hf_ropes r;
    void *mem;
    size_t bytes;
    float rest[3 * 4 * 3], pos[9], nrm[9], tan[9];
} tb_ropes;

static void tb_ropes_open(tb_ropes *t)
{
    int i, j;
    hf_ropes_memory_size(3, 4, &t->bytes);
    t->mem = malloc(t->bytes);
    hf_ropes_init(&t->r, 3, 4, t->mem, t->bytes);
    for (i = 0; i < 3; ++i) {
        t->pos[3 * i] = (float)i; t->pos[3 * i + 1] = 0; t->pos[3 * i + 2] = 0;
        t->nrm[3 * i] = 0; t->nrm[3 * i + 1] = 1; t->nrm[3 * i + 2] = 0;
        t->tan[3 * i] = 1; t->tan[3 * i + 1] = 0; t->tan[3 * i + 2] = 0;
        for (j = 0; j < 4; ++j) {
            float *p = t->rest + 3 * (i * 4 + j);
            p[0] = (float)i; p[1] = 0.1f * (float)j; p[2] = 0;
        }
    }
    hf_ropes_set_rest(&t->r, 0, 3, t->rest, 0, t->pos, t->nrm, t->tan, 0);
}

/* a failing call on the ropes leaves every byte as it was */
#define TB_ROPES_FAIL(t, call, code)                                           \
    do {                                                                       \
        unsigned char *snap_ = (unsigned char *)malloc((t).bytes);             \
        hf_ropes rs_ = (t).r;                                                  \
        memcpy(snap_, (t).mem, (t).bytes);                                     \
        CHECK_EQ_INT((call), (code));                                          \
        CHECK(memcmp(snap_, (t).mem, (t).bytes) == 0);                         \
        CHECK(memcmp(&rs_, &(t).r, sizeof rs_) == 0);                          \
        free(snap_);                                                           \
    } while (0)

/* ==== 1. configuration, result codes, version ============================= */

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

/* The level a build runs where no CPUID is asked (WebAssembly): the one
   the compiler targets. HF_TEST_SIMD_LEVEL, where a build defines it
   (make wasm-test: HF_SIMD_WASM128), is the level it must resolve to, so
   a build that lost its SIMD flags and compared the scalar references
   with themselves fails here. */
static void test_simd_level_of_the_target(void)
{
#if defined(__wasm__)
    CHECK(!HF__X86_DISPATCH && !HF__AVX2 && !HF__AVX512 && !HF__NEON);
    CHECK_EQ_INT(hf_simd_resolve(HF_SIMD_AUTO),
                 HF__SSE ? HF_SIMD_WASM128 : HF_SIMD_SCALAR);
#endif
#ifdef HF_TEST_SIMD_LEVEL
    CHECK_EQ_INT(hf_simd_resolve(HF_SIMD_AUTO), HF_TEST_SIMD_LEVEL);
#endif
    CHECK(hf_simd_resolve(HF_SIMD_AUTO) <= HF_SIMD_MAX ||
          hf_simd_resolve(HF_SIMD_AUTO) == HF_SIMD_SCALAR);
}

/* Every stage's kernels per width (hf__<stage>_widths): widest first,
   each narrower and at a lower level than the one before, ending with the
   scalar reference; hf__kernels_for picks the widest the level allows
   (the reference for HF_SIMD_SCALAR, whatever the build has). */
#define T_WIDTHS_CHECK(widths)                                                 \
    t_widths_check(&(widths)[0].isa, sizeof((widths)[0]),                      \
                   (int)(sizeof(widths) / sizeof((widths)[0])))
static void t_widths_check(const hf__isa *widest, size_t size, int n)
{
    const unsigned char *d = (const unsigned char *)widest;
    int i, level;
    for (i = 0; i < n; ++i) {
        const hf__isa *e = (const hf__isa *)(const void *)(d + (size_t)i * size);
        CHECK(e->name && e->name[0]);
        if (i > 0) {
            const hf__isa *w =
                (const hf__isa *)(const void *)(d + (size_t)(i - 1) * size);
            CHECK(e->lanes < w->lanes && e->level < w->level);
        }
        if (i == n - 1) {
            CHECK_EQ_INT(e->lanes, 1);
            CHECK_EQ_INT(e->level, HF_SIMD_SCALAR);
        }
    }
    CHECK_EQ_INT(hf__kernels_index(widest, size, HF_SIMD_SCALAR), n - 1);
    for (level = HF_SIMD_AUTO; level <= HF_SIMD_AVX512; ++level) {
        const int k = hf__kernels_index(widest, size, level);
        const hf__isa *e = (const hf__isa *)(const void *)(d + (size_t)k * size);
        CHECK(e->level <= hf_simd_resolve(level));
        if (k > 0)
            CHECK(((const hf__isa *)(const void *)(d + (size_t)(k - 1) * size))
                      ->level > hf_simd_resolve(level));
    }
}

static void test_dispatch_widths(void)
{
    T_WIDTHS_CHECK(hf__roots_widths);
    T_WIDTHS_CHECK(hf__copy_widths);
    T_WIDTHS_CHECK(hf__pose_widths);
    T_WIDTHS_CHECK(hf__rope_widths);
    T_WIDTHS_CHECK(hf__grid_widths);
    T_WIDTHS_CHECK(hf__interp_widths);
    T_WIDTHS_CHECK(hf__frame_widths);
    T_WIDTHS_CHECK(hf__write_widths);
    T_WIDTHS_CHECK(hf__ribbons_widths);
    T_WIDTHS_CHECK(hf__points_widths);
    T_WIDTHS_CHECK(hf__encode_widths);
    T_WIDTHS_CHECK(hf__ipoints_widths);
    T_WIDTHS_CHECK(hf__stream_widths);
    T_WIDTHS_CHECK(hf__taper_widths);
}

/* 1. configuration, result codes, version: its tests, in the order they run */
#define T_CONFIG_TESTS(X)                                                      \
    X(test_result_strings_distinct)                                            \
    X(test_version)                                                            \
    X(test_simd_level_of_the_target)                                           \
    X(test_dispatch_widths)

/* ==== 2. random numbers =================================================== */

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

/* 2. random numbers: its tests, in the order they run */
#define T_RNG_TESTS(X)                                                         \
    X(test_rng_matches_pcg32_reference)                                        \
    X(test_rng_streams_and_copies)                                             \
    X(test_rng_float_and_below_ranges)

/* ==== 3. maps ============================================================= */

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
    /* the unchecked variant gives the same bytes on a valid map */
    {
        float f[4];
        int i;
        for (i = 0; i < 50; ++i) {
            float u = -1.3f + 0.071f * (float)i, v = 2.2f - 0.09f * (float)i;
            hf_map_sample(&m, u, v, o);
            hf_map_sample_fast(&m, u, v, f);
            CHECK(memcmp(o, f, sizeof f) == 0);
        }
    }
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

static void test_bad_map_validate_sample_blur(void)
{
    unsigned char px[16] = {0};
    float fpx[4] = {0.5f, 0.5f, 0.5f, 0.5f}, out[4], blur[16];
    hf_map ok, m;
    t_counter cnt;
    hf_allocator a = t_counting(&cnt);
    hf_diag d;
    memset(&ok, 0, sizeof ok);
    ok.data = px; ok.width = 4; ok.height = 4; ok.channels = 1;
    CHECK_EQ_INT(hf_map_validate(&ok, &d), HF_OK);
    CHECK_EQ_INT(hf_map_validate(NULL, &d), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(d.result, HF_ERROR_NULL_POINTER);
    m = ok; m.data = NULL; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_NULL_POINTER);
    m = ok; m.width = 0; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_COUNT);
    m = ok; m.height = -1; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_COUNT);
    m = ok; m.width = HF_MAP_MAX_DIMENSION + 1;
    CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_COUNT);
    m = ok; m.width = 0x7fffffff; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_COUNT);
    m = ok; m.channels = 0; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_FORMAT);
    m = ok; m.channels = 5; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_FORMAT);
    m = ok; m.format = 2; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_FORMAT);
    m = ok; m.format = -1; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_FORMAT);
    m = ok; m.wrap = 2; CHECK(hf_map_validate(&m, NULL) < 0);
    m = ok; m.row_stride = 3; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_STRIDE);
    m = ok; m.row_stride = -4; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_BAD_STRIDE);
    /* float maps: NaN and inf texels */
    m = ok; m.data = fpx; m.width = 2; m.height = 2; m.format = HF_MAP_F32;
    CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_OK);
    fpx[3] = TB_NAN; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_NON_FINITE);
    fpx[3] = -TB_INF; CHECK_EQ_INT(hf_map_validate(&m, NULL), HF_ERROR_NON_FINITE);
    /* sample: out untouched on every error */
    TB_FAILS(hf_map_sample(&m, 0.5f, 0.5f, out), HF_ERROR_NON_FINITE, out, sizeof out);
    fpx[3] = 0.5f;
    TB_FAILS(hf_map_sample(NULL, 0.5f, 0.5f, out), HF_ERROR_NULL_POINTER, out, sizeof out);
    CHECK_EQ_INT(hf_map_sample(&m, 0.5f, 0.5f, NULL), HF_ERROR_NULL_POINTER);
    TB_FAILS(hf_map_sample(&m, TB_NAN, 0.5f, out), HF_ERROR_NON_FINITE, out, sizeof out);
    TB_FAILS(hf_map_sample(&m, 0.5f, TB_INF, out), HF_ERROR_NON_FINITE, out, sizeof out);
    m.channels = 9;
    TB_FAILS(hf_map_sample(&m, 0.5f, 0.5f, out), HF_ERROR_BAD_FORMAT, out, sizeof out);
    m.channels = 1;
    /* huge but finite coordinates: a finite sample */
    CHECK_EQ_INT(hf_map_sample(&m, 3e38f, -3e38f, out), HF_OK);
    CHECK(tb_finite(out, 4));
    /* blur */
    CHECK_EQ_INT(hf_map_blur(&ok, 1.0f, NULL, NULL), HF_ERROR_NULL_POINTER);
    TB_FAILS(hf_map_blur(NULL, 1.0f, blur, NULL), HF_ERROR_NULL_POINTER, blur, sizeof blur);
    TB_FAILS(hf_map_blur(&ok, -1.0f, blur, NULL), HF_ERROR_BAD_PARAMETER, blur, sizeof blur);
    TB_FAILS(hf_map_blur(&ok, TB_NAN, blur, NULL), HF_ERROR_BAD_PARAMETER, blur, sizeof blur);
    TB_FAILS(hf_map_blur(&ok, TB_INF, blur, NULL), HF_ERROR_BAD_PARAMETER, blur, sizeof blur);
    TB_FAILS(hf_map_blur(&ok, 1025.0f, blur, NULL), HF_ERROR_BAD_PARAMETER, blur, sizeof blur);
    m = ok; m.channels = 0;
    TB_FAILS(hf_map_blur(&m, 1.0f, blur, NULL), HF_ERROR_BAD_FORMAT, blur, sizeof blur);
    cnt.fail_after = 0;
    TB_FAILS(hf_map_blur(&ok, 1.0f, blur, &a), HF_ERROR_OUT_OF_MEMORY, blur, sizeof blur);
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    cnt.fail_after = -1;
    CHECK_EQ_INT(hf_map_blur(&ok, 1024.0f, blur, &a), HF_OK); /* radius capped */
    CHECK(tb_finite(blur, 16));
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    /* finite texels near FLT_MAX: validation passes them, so sampling,
       blurring and density must stay finite or validation must refuse
       them */
    {
        float big[4] = {-FLT_MAX, FLT_MAX, FLT_MAX, -FLT_MAX}, o4[4], bl[4];
        float u0[2] = {0.1f, 0.5f}, u1[2] = {0.5f, 0.5f}, u2[2] = {0.9f, 0.5f};
        float dens = -7.0f;
        hf_result rr;
        m = ok; m.data = big; m.width = 2; m.height = 2; m.format = HF_MAP_F32;
        m.wrap = HF_WRAP_CLAMP;
        rr = hf_map_sample(&m, 0.5f, 0.25f, o4);
        CHECK(rr < 0 || tb_finite(o4, 4));
        tb_fill(bl, sizeof bl);
        rr = hf_map_blur(&m, 2.0f, bl, NULL);
        CHECK(rr < 0 ? tb_untouched(bl, sizeof bl) : tb_finite(bl, 4));
        big[0] = big[1] = big[2] = big[3] = FLT_MAX;
        rr = hf_uv_triangle_density(&m, u0, u1, u2, HF_DENSITY_CORNERS, &dens);
        CHECK(rr < 0 ? dens == -7.0f : t_is_finite(dens));
    }
}

/* 3. maps: its tests, in the order they run */
#define T_MAP_TESTS(X)                                                         \
    X(test_map_sample_texel_centres_exact)                                     \
    X(test_map_sample_bilinear_midpoints)                                      \
    X(test_map_wrap_repeat_vs_clamp)                                           \
    X(test_map_f32_multichannel_row_stride)                                    \
    X(test_map_validate_errors)                                                \
    X(test_map_blur_constant_impulse_and_sum)                                  \
    X(test_map_blur_errors_and_allocator)                                      \
    X(test_bad_map_validate_sample_blur)

/* ==== 4. meshes =========================================================== */

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

static void tb_validate_case(const hf_mesh *m, hf_result want, const char *what)
{
    hf_diag d;
    hf_result r = hf_mesh_validate(m, &d);
    if (r != want) printf("  mesh case: %s\n", what);
    CHECK_EQ_INT(r, want);
    CHECK_EQ_INT(d.result, r);
    CHECK(d.message[0] != 0);
}

static void tb_normals_case(const hf_mesh *m, hf_result want, const char *what)
{
    float out[12];
    tb_fill(out, sizeof out);
    /* the mesh's own normals are ignored: their errors do not apply */
    if (strstr(what, "normal")) {
        hf_result r = hf_mesh_compute_normals(m, out);
        CHECK(r == HF_OK || r == want);
        if (r == HF_OK) CHECK(tb_finite(out, 12));
        return;
    }
    if (hf_mesh_compute_normals(m, out) != want) printf("  normals case: %s\n", what);
    CHECK(tb_untouched(out, sizeof out));
}

static void test_bad_mesh_validate_and_normals(void)
{
    tb_quad q;
    float out[12];
    tb_quad_init(&q);
    CHECK_EQ_INT(hf_mesh_validate(&q.mesh, NULL), HF_OK);
    CHECK_EQ_INT(hf_mesh_validate(NULL, NULL), HF_ERROR_NULL_POINTER);
    tb_for_each_bad_mesh(tb_validate_case);
    tb_for_each_bad_mesh(tb_normals_case);
    TB_FAILS(hf_mesh_compute_normals(NULL, out), HF_ERROR_NULL_POINTER, out, sizeof out);
    CHECK_EQ_INT(hf_mesh_compute_normals(&q.mesh, NULL), HF_ERROR_NULL_POINTER);
    /* zero-area triangles: allowed, normals (0, 0, 1), never NaN */
    memset(q.pos, 0, sizeof q.pos);
    CHECK_EQ_INT(hf_mesh_validate(&q.mesh, NULL), HF_OK);
    CHECK_EQ_INT(hf_mesh_compute_normals(&q.mesh, out), HF_OK);
    CHECK(tb_finite(out, 12) && out[2] == 1.0f);
    /* huge but finite positions: cross products overflow, normals still
       unit and finite */
    tb_quad_init(&q);
    q.pos[3] = 3e38f; q.pos[7] = 3e38f; q.pos[10] = -3e38f;
    CHECK_EQ_INT(hf_mesh_compute_normals(&q.mesh, out), HF_OK);
    CHECK(tb_finite(out, 12));
    CHECK(t_is_finite(hf_triangle_area(q.pos, q.pos + 3, q.pos + 6)) ||
          hf_triangle_area(q.pos, q.pos + 3, q.pos + 6) > 0.0f);
}

/* (Mesh counts near INT_MAX cannot be tested without the arrays they
   promise: a view of INT_MAX vertices is read element by element. The
   size limits that need no array are in the ropes, ribbon-index,
   placement and fur tests below.) */

/* A byte stride that is not a multiple of 4 would make misaligned float
   loads (undefined behaviour): validation refuses it. */
static void test_bad_odd_strides(void)
{
    static float buf[64];
    unsigned char *b = (unsigned char *)buf;
    uint32_t idx[3] = {0, 1, 2};
    hf_mesh m;
    hf_map map;
    hf_result r;
    memset(buf, 0, sizeof buf);
    memset(&m, 0, sizeof m);
    m.positions = (const float *)b;
    m.position_stride = 13;
    m.vertex_count = 3;
    m.indices = idx;
    m.triangle_count = 1;
    r = hf_mesh_validate(&m, NULL);
    CHECK_EQ_INT(r, HF_ERROR_BAD_STRIDE);
    memset(&map, 0, sizeof map);
    map.data = buf;
    map.width = 1;
    map.height = 2;
    map.channels = 1;
    map.format = HF_MAP_F32;
    map.row_stride = 5;
    r = hf_map_validate(&map, NULL);
    CHECK_EQ_INT(r, HF_ERROR_BAD_STRIDE);
}

/* ==== 5. grow ============================================================= */

/* 4. meshes: its tests, in the order they run */
#define T_MESH_TESTS(X)                                                        \
    X(test_mesh_validate_interleaved_ok)                                       \
    X(test_mesh_validate_errors)                                               \
    X(test_triangle_area_exact)                                                \
    X(test_mesh_normals_area_weighted)                                         \
    X(test_mesh_normals_degenerate_fallback)                                   \
    X(test_bad_mesh_validate_and_normals)                                      \
    X(test_bad_odd_strides)

/* ---- 5.1 density estimators ---------------------------------------------- */

static void test_grow_record_sizes(void)
{
    CHECK_EQ_INT(sizeof(hf_strand), 24);
    CHECK_EQ_INT(sizeof(hf_tess_vertex), 16);
}

static void test_density_estimators_agree_on_constant_map(void)
{
    static float f[64 * 48];
    static unsigned char u8[64 * 48];
    hf_map mf = t_f32_map(f, 64, 48, 1), mu;
    /* big, tiny (inside one texel), across the wrap seam, zero UV area */
    static const float tris[4][6] = {
        {0.1f, 0.1f, 0.9f, 0.2f, 0.3f, 0.8f},
        {0.501f, 0.501f, 0.503f, 0.501f, 0.502f, 0.504f},
        {0.9f, -0.2f, 1.3f, 0.1f, 1.0f, 0.4f},
        {0.1f, 0.1f, 0.5f, 0.5f, 0.9f, 0.9f}};
    int i, e, k;
    for (i = 0; i < 64 * 48; ++i) {
        f[i] = 0.37f;
        u8[i] = 200;
    }
    mu = mf;
    mu.data = u8;
    mu.format = HF_MAP_U8;
    for (k = 0; k < 4; ++k)
        for (e = 0; e < 3; ++e) {
            float d = -1.0f;
            const float *t = tris[k];
            CHECK_EQ_INT(hf_uv_triangle_density(&mf, t, t + 2, t + 4,
                                                e, &d),
                         HF_OK);
            CHECK_NEAR(d, 0.37, 1e-6);
            CHECK_EQ_INT(hf_uv_triangle_density(&mu, t, t + 2, t + 4,
                                                e, &d),
                         HF_OK);
            CHECK_NEAR(d, 200.0 / 255.0, 1e-6);
            CHECK_EQ_INT(hf_uv_triangle_density(NULL, t, t + 2, t + 4,
                                                e, &d),
                         HF_OK);
            CHECK(d == 1.0f);
        }
}

/* On f = d^2 / R^2 (d: distance to the centre of an equilateral triangle of
   circumradius R) the three means are known: corners 1, edges 1/2 (each
   edge: inradius^2 + half-side^2 / 3), area 1/4 (polar moment). So the
   estimators must come out in that order with those values. And on a
   linear ramp each estimator grows as the triangle moves up the ramp. */
static void test_density_estimators_order_on_gradient(void)
{
    enum { W = 256 };
    static float f[W * W], ramp[W * W];
    hf_map m = t_f32_map(f, W, W, 1), mr = t_f32_map(ramp, W, W, 1);
    const double R = 100.0, pi = 3.14159265358979;
    float uv[3][2], dc, de, da;
    int x, y, k, e;
    for (y = 0; y < W; ++y)
        for (x = 0; x < W; ++x) {
            double dx = x + 0.5 - 128.0, dy = y + 0.5 - 128.0;
            f[y * W + x] = (float)((dx * dx + dy * dy) / (R * R));
            ramp[y * W + x] = ((float)x + 0.5f) / (float)W;
        }
    for (k = 0; k < 3; ++k) {
        double a = pi / 2 + 2 * pi * k / 3;
        uv[k][0] = (float)((128.0 + R * cos(a)) / W);
        uv[k][1] = (float)((128.0 + R * sin(a)) / W);
    }
    CHECK_EQ_INT(hf_uv_triangle_density(&m, uv[0], uv[1], uv[2],
                                        HF_DENSITY_CORNERS, &dc),
                 HF_OK);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, uv[0], uv[1], uv[2],
                                        HF_DENSITY_EDGES, &de),
                 HF_OK);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, uv[0], uv[1], uv[2],
                                        HF_DENSITY_AREA, &da),
                 HF_OK);
    CHECK_NEAR(dc, 1.0, 0.01);
    CHECK_NEAR(de, 0.5, 0.02);
    CHECK_NEAR(da, 0.25, 0.005);
    CHECK(dc > de && de > da);
    for (e = 0; e < 3; ++e) {
        float last = -1.0f;
        int s;
        for (s = 0; s < 8; ++s) {
            float t[3][2] = {{0.05f, 0.1f}, {0.2f, 0.15f}, {0.1f, 0.4f}}, d;
            for (k = 0; k < 3; ++k) t[k][0] += 0.1f * (float)s;
            CHECK_EQ_INT(hf_uv_triangle_density(&mr, t[0], t[1], t[2],
                                                e, &d),
                         HF_OK);
            CHECK(d > last);
            last = d;
            /* linear map: corners and area are the centroid's value */
            if (e != HF_DENSITY_EDGES)
                CHECK_NEAR(d, (t[0][0] + t[1][0] + t[2][0]) / 3.0f,
                           1.5 / W);
        }
    }
}

/* Hand-computed: on a 2 x 2 map the UV triangle (0,0) (1,0) (0,1) covers
   texel (0,0) fully, (1,0) and (0,1) half, (1,1) not at all; Bresenham
   (clamp map) visits (0,0) (1,0) | (1,0) (1,1) | (0,1) (0,1). */
static void test_density_area_and_edges_exact(void)
{
    static const float f[4] = {0.1f, 0.5f, 0.9f, 7.0f};
    hf_map m = t_f32_map(f, 2, 2, 1);
    const float a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {0, 1};
    float d;
    m.wrap = HF_WRAP_CLAMP;
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, HF_DENSITY_AREA, &d),
                 HF_OK);
    CHECK_NEAR(d, (0.1 + 0.5 * 0.5 + 0.5 * 0.9) / 2.0, 1e-6);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, HF_DENSITY_EDGES, &d),
                 HF_OK);
    CHECK_NEAR(d, (0.1 + 0.5 + 0.5 + 7.0 + 0.9 + 0.9) / 6.0, 1e-6);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, HF_DENSITY_CORNERS, &d),
                 HF_OK);
    /* clamp: (0,0) reads texel centre value 0.1; (1,0) -> 0.5; (0,1) ->
       0.9 (clamped beyond the last texel centre) */
    CHECK_NEAR(d, (0.1 + 0.5 + 0.9) / 3.0, 1e-6);
}

static void test_density_bad_input(void)
{
    static const float f[4] = {1, 1, 1, 1};
    hf_map m = t_f32_map(f, 2, 2, 1), bad = m;
    const float a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {0, 1};
    const float far_[2] = {40.0f, 0.5f}, nan_[2] = {NAN, 0.0f};
    float d = -5.0f;
    bad.width = 0;
    CHECK_EQ_INT(hf_uv_triangle_density(&m, NULL, b, c, HF_DENSITY_AREA, &d),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, HF_DENSITY_AREA, NULL),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_uv_triangle_density(&bad, a, b, c, HF_DENSITY_AREA, &d),
                 HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, nan_, b, c, HF_DENSITY_AREA, &d),
                 HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, 3,
                                        &d),
                 HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, far_, c, HF_DENSITY_AREA, &d),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, far_, c, HF_DENSITY_EDGES, &d),
                 HF_ERROR_BAD_RANGE);
    CHECK(d == -5.0f);
    /* the corner estimator samples anywhere */
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, far_, c, HF_DENSITY_CORNERS,
                                        &d),
                 HF_OK);
    CHECK(d == 1.0f);
}

static void test_bad_uv_density(void)
{
    float a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {0, 1}, bad[2] = {TB_NAN, 0};
    float far[2] = {1000.0f, 0.0f}, d = -7.0f;
    unsigned char px[4] = {255, 255, 255, 255};
    hf_map m;
    memset(&m, 0, sizeof m);
    m.data = px; m.width = 2; m.height = 2; m.channels = 1;
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, 0, &d), HF_OK);
    CHECK(d == 1.0f);
    d = -7.0f;
    CHECK_EQ_INT(hf_uv_triangle_density(&m, NULL, b, c, 0, &d), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, 0, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, bad, c, 1, &d), HF_ERROR_NON_FINITE);
    bad[0] = 0.0f; bad[1] = -TB_INF;
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, bad, 2, &d), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, 3, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, -1, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, far, c, 1, &d), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, far, c, 2, &d), HF_ERROR_BAD_RANGE);
    m.width = 0;
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, b, c, 0, &d), HF_ERROR_BAD_COUNT);
    CHECK(d == -7.0f);
    /* zero UV area: AREA falls back to CORNERS, finite */
    m.width = 2;
    CHECK_EQ_INT(hf_uv_triangle_density(&m, a, a, a, 2, &d), HF_OK);
    CHECK(t_is_finite(d));
}

/* 5.1 density estimators: its tests, in the order they run */
#define T_DENSITY_TESTS(X)                                                     \
    X(test_grow_record_sizes)                                                  \
    X(test_density_estimators_agree_on_constant_map)                           \
    X(test_density_estimators_order_on_gradient)                               \
    X(test_density_area_and_edges_exact)                                       \
    X(test_density_bad_input)                                                  \
    X(test_bad_uv_density)

/* ---- 5.2 tessellation ---------------------------------------------------- */

static long t_ipow3(int k)
{
    long p = 1;
    while (k-- > 0) p *= 3;
    return p;
}

/* A 2 x 2 grid: 8 triangles of area 1/8. With density D and factor f the
   triangles split k times, k the least with D f / (8 3^k) <= 1: exactly
   8 * 3^k triangles, 8 (3^k - 1) / 2 added vertices, depth k. */
static void test_tess_constant_map_power_of_three(void)
{
    t_grid g = t_make_grid(2, 1.0f);
    static float half[16];
    hf_map m = t_f32_map(half, 4, 4, 1);
    int k, e, i;
    for (i = 0; i < 16; ++i) half[i] = 0.5f;
    for (k = 0; k <= 5; ++k)
        for (e = 0; e < 4; ++e) {
            hf_tess_params p;
            hf_tess_output out;
            memset(&p, 0, sizeof p);
            memset(&out, 0, sizeof out);
            p.max_depth = 8;
            /* D f A = 0.7 * 3^k: away from the 1.0 boundary */
            p.factor = 8.0f * (float)t_ipow3(k) * 0.7f;
            if (e < 3) {
                p.factor *= 2.0f; /* D = 0.5 */
                p.estimator = e;
            }
            CHECK_EQ_INT(hf_tessellate(&g.mesh, e < 3 ? &m : NULL, &p, &out),
                         HF_OK);
            CHECK_EQ_INT(out.triangle_count, 8 * t_ipow3(k));
            CHECK_EQ_INT(out.added_count, 8 * (t_ipow3(k) - 1) / 2);
            CHECK_EQ_INT(out.vertex_count, 9 + out.added_count);
            CHECK_EQ_INT(out.depth, k);
        }
    t_free_grid(&g);
}

/* Every output triangle small enough (recomputed with the public functions,
   bit-exact), area and UV area preserved, every added vertex re-evaluates
   to its position bit for bit, and to the transformed position on a
   transformed ("skinned") base mesh. */
static void test_tess_output_properties(void)
{
    t_grid g = t_make_grid(4, 2.0f);
    float *blob = t_blob_data(64, 64);
    hf_map m = t_f32_map(blob, 64, 64, 1);
    int e, s;
    double base_area = 0.0, base_uv = 0.0;
    int t;
    for (t = 0; t < g.mesh.triangle_count; ++t) {
        base_area += t_tri_area(g.pos, g.idx + 3 * t);
        base_uv += t_uv_area(g.uv, g.idx + 3 * t);
    }
    for (e = 0; e < 3; ++e)
        for (s = 0; s < 2; ++s) {
            hf_tess_params p;
            t_tess ts;
            double area = 0.0, uva = 0.0;
            float *ev, *evuv, *sk_pos, *sk_ev;
            int V = g.mesh.vertex_count, i, ok_small = 1, ok_bits = 1,
                ok_base = 1, ok_skin = 1;
            hf_mesh sk;
            memset(&p, 0, sizeof p);
            p.factor = 150.0f;
            p.estimator = e;
            p.split = s;
            p.seed = 7;
            ts = t_tessellate(&g.mesh, &m, &p);
            CHECK_EQ_INT(ts.r, HF_OK);
            if (ts.r != HF_OK) continue;
            CHECK(ts.out.triangle_count > 4 * g.mesh.triangle_count);
            for (t = 0; t < ts.out.triangle_count; ++t) {
                const uint32_t *tri = ts.out.indices + 3 * t;
                float d, a;
                CHECK(tri[0] < (uint32_t)ts.out.vertex_count &&
                      tri[1] < (uint32_t)ts.out.vertex_count &&
                      tri[2] < (uint32_t)ts.out.vertex_count);
                a = hf_triangle_area(ts.out.positions + 3 * tri[0],
                                     ts.out.positions + 3 * tri[1],
                                     ts.out.positions + 3 * tri[2]);
                CHECK_EQ_INT(hf_uv_triangle_density(
                                 &m, ts.out.uvs + 2 * tri[0],
                                 ts.out.uvs + 2 * tri[1],
                                 ts.out.uvs + 2 * tri[2], p.estimator, &d),
                             HF_OK);
                if (d * a * p.factor > 1.0f) ok_small = 0;
                area += t_tri_area(ts.out.positions, tri);
                uva += t_uv_area(ts.out.uvs, tri);
                /* added corners belong to this triangle's base triangle */
                for (i = 0; i < 3; ++i)
                    if (tri[i] >= (uint32_t)V &&
                        ts.out.added[tri[i] - V].triangle !=
                            ts.out.triangle_base[t])
                        ok_base = 0;
            }
            CHECK(ok_small);
            CHECK(ok_base);
            CHECK_NEAR(area, base_area, 1e-5 * base_area);
            CHECK_NEAR(uva, base_uv, 1e-5 * base_uv);
            CHECK(memcmp(ts.out.positions, g.pos, sizeof(float) * 3 * V) == 0);
            /* re-evaluation, bit for bit */
            ev = (float *)malloc(sizeof(float) * 3 * ts.out.added_count);
            evuv = (float *)malloc(sizeof(float) * 2 * ts.out.added_count);
            CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, ts.out.added,
                                          ts.out.added_count, 0,
                                          ts.out.added_count, ev, NULL, evuv),
                         HF_OK);
            for (i = 0; i < ts.out.added_count; ++i) {
                if (memcmp(ev + 3 * i, ts.out.positions + 3 * (V + i), 12))
                    ok_bits = 0;
                if (memcmp(evuv + 2 * i, ts.out.uvs + 2 * (V + i), 8))
                    ok_bits = 0;
                if (!(ts.out.added[i].bary[0] >= 0.0f &&
                      ts.out.added[i].bary[1] >= 0.0f &&
                      ts.out.added[i].bary[2] >= 0.0f))
                    ok_bits = 0;
            }
            CHECK(ok_bits);
            /* skinned: rotate 90 degrees about z, lift by 3 */
            sk = g.mesh;
            sk_pos = (float *)malloc(sizeof(float) * 3 * V);
            sk_ev = (float *)malloc(sizeof(float) * 3 * ts.out.added_count);
            for (i = 0; i < V; ++i) {
                sk_pos[3 * i] = -g.pos[3 * i + 1];
                sk_pos[3 * i + 1] = g.pos[3 * i];
                sk_pos[3 * i + 2] = g.pos[3 * i + 2] + 3.0f;
            }
            sk.positions = sk_pos;
            CHECK_EQ_INT(hf_tess_evaluate(&sk, ts.out.added,
                                          ts.out.added_count, 0,
                                          ts.out.added_count, sk_ev, NULL,
                                          NULL),
                         HF_OK);
            for (i = 0; i < ts.out.added_count; ++i) {
                const float *r = ev + 3 * i, *q = sk_ev + 3 * i;
                if (fabs(q[0] + r[1]) > 1e-5 || fabs(q[1] - r[0]) > 1e-5 ||
                    fabs(q[2] - 3.0) > 1e-5)
                    ok_skin = 0;
            }
            CHECK(ok_skin);
            free(ev);
            free(evuv);
            free(sk_pos);
            free(sk_ev);
            t_free_tess(&ts);
        }
    free(blob);
    t_free_grid(&g);
}

static void test_tess_evaluate_ranges_and_normals(void)
{
    t_grid g = t_make_grid(3, 1.0f);
    hf_tess_params p;
    t_tess ts;
    float *a, *b, *n;
    int N, i, ok = 1;
    hf_tess_vertex bad;
    memset(&p, 0, sizeof p);
    p.factor = 100.0f;
    ts = t_tessellate(&g.mesh, NULL, &p);
    CHECK_EQ_INT(ts.r, HF_OK);
    N = ts.out.added_count;
    a = (float *)malloc(sizeof(float) * 3 * N);
    b = (float *)malloc(sizeof(float) * 3 * N);
    n = (float *)malloc(sizeof(float) * 3 * N);
    memset(a, 0, sizeof(float) * 3 * N);
    memset(b, 0, sizeof(float) * 3 * N);
    CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, ts.out.added, N, 0, N, a, n, NULL),
                 HF_OK);
    CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, ts.out.added, N, 0, N / 3, b, NULL,
                                  NULL),
                 HF_OK);
    CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, ts.out.added, N, N / 3, N - N / 3,
                                  b, NULL, NULL),
                 HF_OK);
    CHECK(memcmp(a, b, sizeof(float) * 3 * N) == 0);
    for (i = 0; i < N; ++i)
        if (n[3 * i] != 0.0f || n[3 * i + 1] != 0.0f || n[3 * i + 2] != 1.0f)
            ok = 0;
    CHECK(ok);
    CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, ts.out.added, N, N - 1, 2, b, NULL,
                                  NULL),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, ts.out.added, N, -1, 1, b, NULL,
                                  NULL),
                 HF_ERROR_BAD_RANGE);
    bad.triangle = 999;
    bad.bary[0] = bad.bary[1] = bad.bary[2] = 1.0f / 3.0f;
    memset(b, 0x5a, sizeof(float) * 3);
    CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, &bad, 1, 0, 1, b, NULL, NULL),
                 HF_ERROR_INDEX_OUT_OF_RANGE);
    bad.triangle = 0;
    bad.bary[1] = NAN;
    CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, &bad, 1, 0, 1, b, NULL, NULL),
                 HF_ERROR_NON_FINITE);
    {
        unsigned char s[12];
        memset(s, 0x5a, 12);
        CHECK(memcmp(b, s, 12) == 0);
    }
    g.mesh.normals = NULL;
    CHECK_EQ_INT(hf_tess_evaluate(&g.mesh, ts.out.added, N, 0, N, a, n, NULL),
                 HF_ERROR_NULL_POINTER);
    free(a);
    free(b);
    free(n);
    t_free_tess(&ts);
    t_free_grid(&g);
}

static void test_tess_caps_write_nothing(void)
{
    t_grid g = t_make_grid(2, 1.0f);
    hf_tess_params p;
    hf_tess_output out, probe;
    uint32_t idx[3 * 200];
    hf_tess_vertex added[100];
    float pos[3 * 200];
    unsigned char before[sizeof idx];
    memset(&p, 0, sizeof p);
    memset(&out, 0, sizeof out);
    /* far past the caps: fails fast, from the counting pass */
    p.factor = 1e30f;
    out.triangle_count = out.added_count = out.vertex_count = -7;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out), HF_ERROR_DEPTH_CAP);
    CHECK_EQ_INT(out.triangle_count, -7);
    p.max_depth = HF_TESS_MAX_DEPTH;
    p.max_triangles = 1000;
    p.factor = 1e9f; /* 8 * 3^19 = 9e9 triangles wanted, depth 19 */
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out),
                 HF_ERROR_TRIANGLE_CAP);
    p.max_triangles = 0; /* default cap, 4M: "billions" would be refused */
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out),
                 HF_ERROR_TRIANGLE_CAP);
    CHECK_EQ_INT(out.triangle_count, -7);
    /* a base mesh over the cap */
    p.factor = 1.0f;
    p.max_triangles = 7;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out),
                 HF_ERROR_TRIANGLE_CAP);

    /* with arrays given: a cap error or a short buffer writes nothing */
    memset(idx, 0xab, sizeof idx);
    memset(before, 0xab, sizeof before);
    out.indices = idx;
    out.added = added;
    out.positions = pos;
    out.triangle_capacity = 200;
    out.added_capacity = 100;
    out.vertex_capacity = 200;
    p.max_triangles = 0;
    p.max_depth = 2;
    p.factor = 1000.0f;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out), HF_ERROR_DEPTH_CAP);
    CHECK(memcmp(idx, before, sizeof idx) == 0);
    p.factor = 8.0f * 9.0f * 0.7f; /* 72 triangles */
    memset(&probe, 0, sizeof probe);
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &probe), HF_OK);
    CHECK_EQ_INT(probe.triangle_count, 72);
    out.triangle_capacity = 71;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out),
                 HF_ERROR_BUFFER_TOO_SMALL);
    CHECK(memcmp(idx, before, sizeof idx) == 0);
    out.triangle_capacity = 72;
    out.added_capacity = probe.added_count - 1;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out),
                 HF_ERROR_BUFFER_TOO_SMALL);
    CHECK(memcmp(idx, before, sizeof idx) == 0);
    CHECK_EQ_INT(out.triangle_count, -7);
    out.added_capacity = probe.added_count;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out), HF_OK);
    CHECK_EQ_INT(out.triangle_count, 72);
    /* exact size: the 73rd index slot untouched */
    CHECK(idx[3 * 72] == 0xabababab);
    t_free_grid(&g);
}

static void test_tess_bad_input(void)
{
    t_grid g = t_make_grid(2, 1.0f);
    hf_tess_params p;
    hf_tess_output out;
    static const float one[4] = {1, 1, 1, 1};
    hf_map m = t_f32_map(one, 2, 2, 1), bad_map = m;
    float saved;
    const float bad_factors[4] = {0.0f, -1.0f, NAN, INFINITY};
    int i;
    memset(&p, 0, sizeof p);
    memset(&out, 0, sizeof out);
    out.triangle_count = -7;
    p.factor = 10.0f;
    CHECK_EQ_INT(hf_tessellate(NULL, NULL, &p, &out), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, NULL, &out),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, NULL),
                 HF_ERROR_NULL_POINTER);
    for (i = 0; i < 4; ++i) {
        p.factor = bad_factors[i];
        CHECK_EQ_INT(hf_tessellate(&g.mesh, NULL, &p, &out),
                     HF_ERROR_BAD_PARAMETER);
    }
    p.factor = 10.0f;
    p.estimator = 3;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out),
                 HF_ERROR_BAD_PARAMETER);
    p.estimator = HF_DENSITY_CORNERS;
    p.split = 2;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out),
                 HF_ERROR_BAD_PARAMETER);
    p.split = HF_SPLIT_CENTROID;
    p.max_depth = HF_TESS_MAX_DEPTH + 1;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out),
                 HF_ERROR_BAD_PARAMETER);
    p.max_depth = -1;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out),
                 HF_ERROR_BAD_PARAMETER);
    p.max_depth = 0;
    p.max_triangles = HF_TESS_MAX_TRIANGLES + 1;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out),
                 HF_ERROR_BAD_PARAMETER);
    p.max_triangles = 0;
    bad_map.width = 0;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &bad_map, &p, &out),
                 HF_ERROR_BAD_COUNT);
    g.mesh.uvs = NULL;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out), HF_ERROR_NULL_POINTER);
    g.mesh.uvs = g.uv;
    g.idx[5] = 99;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out),
                 HF_ERROR_INDEX_OUT_OF_RANGE);
    g.idx[5] = 3;
    saved = g.pos[4];
    g.pos[4] = NAN;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out), HF_ERROR_NON_FINITE);
    g.pos[4] = 3e30f; /* finite, but areas overflow */
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out), HF_ERROR_NON_FINITE);
    g.pos[4] = saved;
    /* UVs out of the rasterisers' range */
    g.uv[2 * 4] = 40.0f;
    p.estimator = HF_DENSITY_AREA;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out), HF_ERROR_BAD_RANGE);
    p.estimator = HF_DENSITY_CORNERS;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out), HF_OK);
    g.uv[2 * 4] = 0.5f;
    CHECK_EQ_INT(out.triangle_count, 8 * 3); /* D A f = 1.25: one split */
    out.triangle_count = -7;
    /* degenerate triangles: one is kept unsplit by default, refused on
       request; all of them is refused */
    g.idx[3] = g.idx[4]; /* triangle 1 = (d, d, c): zero area */
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out), HF_OK);
    CHECK_EQ_INT(out.triangle_count, 7 * 3 + 1);
    out.triangle_count = -7;
    p.refuse_degenerate = 1;
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out), HF_ERROR_DEGENERATE);
    p.refuse_degenerate = 0;
    for (i = 0; i < 8; ++i) g.idx[3 * i + 1] = g.idx[3 * i];
    CHECK_EQ_INT(hf_tessellate(&g.mesh, &m, &p, &out), HF_ERROR_DEGENERATE);
    CHECK_EQ_INT(out.triangle_count, -7);
    t_free_grid(&g);
}

static void test_tess_same_seed_same_bytes(void)
{
    t_grid g = t_make_grid(3, 1.0f);
    float *blob = t_blob_data(32, 32);
    hf_map m = t_f32_map(blob, 32, 32, 1);
    hf_tess_params p;
    t_tess a, b, c;
    memset(&p, 0, sizeof p);
    p.factor = 300.0f;
    p.split = HF_SPLIT_RANDOM;
    p.estimator = HF_DENSITY_AREA;
    p.seed = 42;
    a = t_tessellate(&g.mesh, &m, &p);
    b = t_tessellate(&g.mesh, &m, &p);
    p.seed = 43;
    c = t_tessellate(&g.mesh, &m, &p);
    CHECK_EQ_INT(a.r, HF_OK);
    CHECK_EQ_INT(a.out.triangle_count, b.out.triangle_count);
    CHECK_EQ_INT(a.out.added_count, b.out.added_count);
    CHECK(memcmp(a.out.indices, b.out.indices,
                 12 * (size_t)a.out.triangle_count) == 0);
    CHECK(memcmp(a.out.added, b.out.added,
                 sizeof(hf_tess_vertex) * (size_t)a.out.added_count) == 0);
    CHECK(memcmp(a.out.positions, b.out.positions,
                 12 * (size_t)a.out.vertex_count) == 0);
    /* another seed moves the split points */
    CHECK(c.out.added_count != a.out.added_count ||
          memcmp(a.out.added, c.out.added,
                 sizeof(hf_tess_vertex) * (size_t)a.out.added_count) != 0);
    t_free_tess(&a);
    t_free_tess(&b);
    t_free_tess(&c);
    free(blob);
    t_free_grid(&g);
}

static void tb_tess_case(const hf_mesh *m, hf_result want, const char *what)
{
    hf_tess_params p;
    hf_tess_output o;
    uint32_t idx[64];
    memset(&p, 0, sizeof p);
    p.factor = 1.0f;
    memset(&o, 0, sizeof o);
    o.indices = idx;
    o.triangle_capacity = 20;
    o.triangle_count = o.added_count = o.vertex_count = o.depth = -7;
    tb_fill(idx, sizeof idx);
    if (hf_tessellate(m, NULL, &p, &o) != want) printf("  tess case: %s\n", what);
    CHECK(tb_untouched(idx, sizeof idx));
    CHECK(o.triangle_count == -7 && o.added_count == -7 &&
          o.vertex_count == -7 && o.depth == -7);
}

static void test_bad_tessellate(void)
{
    tb_quad q;
    hf_tess_params p;
    hf_tess_output o;
    uint32_t idx[3 * 64];
    unsigned char px[4] = {0, 0, 0, 0};
    hf_map empty;
    tb_quad_init(&q);
    memset(&p, 0, sizeof p);
    p.factor = 1.0f;
    memset(&o, 0, sizeof o);
#define TB_TESS(params_expr, code)                                             \
    do {                                                                       \
        hf_tess_params pp_ = p;                                                \
        params_expr;                                                           \
        o.indices = idx;                                                       \
        o.triangle_capacity = 64;                                              \
        o.triangle_count = o.added_count = o.vertex_count = o.depth = -7;      \
        tb_fill(idx, sizeof idx);                                              \
        CHECK_EQ_INT(hf_tessellate(&q.mesh, NULL, &pp_, &o), (code));          \
        CHECK(tb_untouched(idx, sizeof idx));                                  \
        CHECK(o.triangle_count == -7 && o.vertex_count == -7);                 \
    } while (0)
    TB_TESS(pp_.factor = 0.0f, HF_ERROR_BAD_PARAMETER);
    TB_TESS(pp_.factor = -1.0f, HF_ERROR_BAD_PARAMETER);
    TB_TESS(pp_.factor = TB_NAN, HF_ERROR_BAD_PARAMETER);
    TB_TESS(pp_.factor = TB_INF, HF_ERROR_BAD_PARAMETER);
    TB_TESS(pp_.estimator = 3, HF_ERROR_BAD_PARAMETER);
    TB_TESS(pp_.split = -1, HF_ERROR_BAD_PARAMETER);
    TB_TESS(pp_.max_depth = HF_TESS_MAX_DEPTH + 1, HF_ERROR_BAD_PARAMETER);
    TB_TESS(pp_.max_triangles = HF_TESS_MAX_TRIANGLES + 1, HF_ERROR_BAD_PARAMETER);
    TB_TESS(pp_.max_triangles = -1, HF_ERROR_BAD_PARAMETER);
    /* billions of triangles: the caps, fast */
    TB_TESS(pp_.factor = 1e30f, HF_ERROR_DEPTH_CAP);
    /* with the deepest depth either cap may bind first (the counting pass
       walks depth first); both are errors and both come fast */
    {
        hf_tess_params pp_ = p;
        hf_result rr;
        pp_.factor = FLT_MAX;
        pp_.max_depth = HF_TESS_MAX_DEPTH;
        pp_.max_triangles = HF_TESS_MAX_TRIANGLES;
        o.indices = idx;
        o.triangle_count = -7;
        rr = hf_tessellate(&q.mesh, NULL, &pp_, &o);
        CHECK(rr == HF_ERROR_DEPTH_CAP || rr == HF_ERROR_TRIANGLE_CAP);
        CHECK_EQ_INT(o.triangle_count, -7);
    }
    TB_TESS((pp_.factor = 100.0f, pp_.max_triangles = 3), HF_ERROR_TRIANGLE_CAP);
    /* too small a buffer */
    TB_TESS(pp_.factor = 1000.0f, HF_ERROR_BUFFER_TOO_SMALL);
    /* a NULL out, params, mesh */
    CHECK_EQ_INT(hf_tessellate(&q.mesh, NULL, &p, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_tessellate(&q.mesh, NULL, NULL, &o), HF_ERROR_NULL_POINTER);
    tb_for_each_bad_mesh(tb_tess_case);
    /* a density map with a mesh without UVs */
    memset(&empty, 0, sizeof empty);
    empty.data = px; empty.width = 2; empty.height = 2; empty.channels = 1;
    q.mesh.uvs = NULL;
    o.indices = NULL;
    o.triangle_count = -7;
    CHECK_EQ_INT(hf_tessellate(&q.mesh, &empty, &p, &o), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(o.triangle_count, -7);
    q.mesh.uvs = q.uv;
    /* an empty map (width 0) */
    empty.width = 0;
    CHECK_EQ_INT(hf_tessellate(&q.mesh, &empty, &p, &o), HF_ERROR_BAD_COUNT);
    /* zero-area triangles: every one degenerate is refused; one of two
       with refuse_degenerate is refused */
    memset(q.pos, 0, sizeof q.pos);
    CHECK_EQ_INT(hf_tessellate(&q.mesh, NULL, &p, &o), HF_ERROR_DEGENERATE);
    tb_quad_init(&q);
    q.idx[5] = 2; /* triangle 1 = (0, 2, 2): zero area */
    p.refuse_degenerate = 1;
    CHECK_EQ_INT(hf_tessellate(&q.mesh, NULL, &p, &o), HF_ERROR_DEGENERATE);
    p.refuse_degenerate = 0;
    CHECK_EQ_INT(hf_tessellate(&q.mesh, NULL, &p, &o), HF_OK);
    /* an area that overflows float */
    tb_quad_init(&q);
    q.pos[3] = 3e38f; q.pos[10] = 3e38f; q.pos[6] = 3e38f; q.pos[7] = 3e38f;
    o.triangle_count = -7;
    CHECK_EQ_INT(hf_tessellate(&q.mesh, NULL, &p, &o), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(o.triangle_count, -7);
#undef TB_TESS
}

static void test_bad_tess_evaluate(void)
{
    tb_quad q;
    hf_tess_vertex v[2] = {{0, {0.2f, 0.3f, 0.5f}}, {1, {0.5f, 0.25f, 0.25f}}};
    float pos[6], nrm[6], uv[4];
    tb_quad_init(&q);
#define TB_EVAL(mesh, added, n, first, count, code)                            \
    do {                                                                       \
        tb_fill(pos, sizeof pos);                                              \
        tb_fill(nrm, sizeof nrm);                                              \
        tb_fill(uv, sizeof uv);                                                \
        CHECK_EQ_INT(hf_tess_evaluate((mesh), (added), (n), (first), (count), \
                                      pos, nrm, uv),                           \
                     (code));                                                  \
        CHECK(tb_untouched(pos, sizeof pos) && tb_untouched(nrm, sizeof nrm) &&  \
              tb_untouched(uv, sizeof uv));                                    \
    } while (0)
    TB_EVAL(NULL, v, 2, 0, 2, HF_ERROR_NULL_POINTER);
    TB_EVAL(&q.mesh, NULL, 2, 0, 2, HF_ERROR_NULL_POINTER);
    /* a negative array count: BAD_COUNT or BAD_RANGE (the code does the
       latter; CONVENTIONS say negative counts are refused) */
    tb_fill(pos, sizeof pos);
    {
        hf_result rr = hf_tess_evaluate(&q.mesh, v, -1, 0, 0, pos, nrm, uv);
        CHECK(rr == HF_ERROR_BAD_COUNT || rr == HF_ERROR_BAD_RANGE);
        CHECK(tb_untouched(pos, sizeof pos));
    }
    TB_EVAL(&q.mesh, v, 2, 1, 2, HF_ERROR_BAD_RANGE);
    TB_EVAL(&q.mesh, v, 2, -1, 1, HF_ERROR_BAD_RANGE);
    TB_EVAL(&q.mesh, v, 2, 1, 0x7fffffff, HF_ERROR_BAD_RANGE);
    TB_EVAL(&q.mesh, v, 2, 0x7fffffff, 1, HF_ERROR_BAD_RANGE);
    v[1].triangle = 2;
    TB_EVAL(&q.mesh, v, 2, 0, 2, HF_ERROR_INDEX_OUT_OF_RANGE);
    v[1].triangle = 1;
    q.idx[5] = 9;
    TB_EVAL(&q.mesh, v, 2, 0, 2, HF_ERROR_INDEX_OUT_OF_RANGE);
    q.idx[5] = 3;
    v[1].bary[0] = TB_NAN;
    TB_EVAL(&q.mesh, v, 2, 0, 2, HF_ERROR_NON_FINITE);
    v[1].bary[0] = 0.5f;
    q.pos[6] = TB_INF;
    TB_EVAL(&q.mesh, v, 2, 0, 2, HF_ERROR_NON_FINITE);
    q.pos[6] = 1.0f;
    q.mesh.position_stride = 4;
    TB_EVAL(&q.mesh, v, 2, 0, 2, HF_ERROR_BAD_STRIDE);
    q.mesh.position_stride = 0;
    q.mesh.normals = NULL;
    TB_EVAL(&q.mesh, v, 2, 0, 2, HF_ERROR_NULL_POINTER);
    q.mesh.normals = q.nrm;
    /* zero normals on the blend: the face normal, never NaN */
    memset(q.nrm, 0, sizeof q.nrm);
    CHECK_EQ_INT(hf_tess_evaluate(&q.mesh, v, 2, 0, 2, pos, nrm, uv), HF_OK);
    CHECK(tb_finite(pos, 6) && tb_finite(nrm, 6) && tb_finite(uv, 4));
    /* count 0 at the end is a valid empty range */
    CHECK_EQ_INT(hf_tess_evaluate(&q.mesh, v, 2, 2, 0, pos, nrm, uv), HF_OK);
#undef TB_EVAL
}

/* 5.2 tessellation: its tests, in the order they run */
#define T_TESS_TESTS(X)                                                        \
    X(test_tess_constant_map_power_of_three)                                   \
    X(test_tess_output_properties)                                             \
    X(test_tess_evaluate_ranges_and_normals)                                   \
    X(test_tess_caps_write_nothing)                                            \
    X(test_tess_bad_input)                                                     \
    X(test_tess_same_seed_same_bytes)                                          \
    X(test_bad_tessellate)                                                     \
    X(test_bad_tess_evaluate)

/* ---- 5.3 guides ---------------------------------------------------------- */

/* A cube of side 2 as an engine stores it: 24 vertices (4 per face, with
   the face normal and a face UV), 12 triangles. */
typedef struct t_cube {
    float pos[24 * 3], nrm[24 * 3], uv[24 * 2];
    uint32_t idx[36];
    hf_mesh mesh;
} t_cube;

static void t_make_cube(t_cube *c)
{
    static const int axis[6] = {0, 0, 1, 1, 2, 2};
    int f, k;
    for (f = 0; f < 6; ++f) {
        int a = axis[f], u = (a + 1) % 3, v = (a + 2) % 3;
        float s = (f & 1) ? -1.0f : 1.0f;
        for (k = 0; k < 4; ++k) {
            int i = 4 * f + k;
            float cu = (k == 1 || k == 2) ? 1.0f : -1.0f;
            float cv = (k >= 2) ? 1.0f : -1.0f;
            c->pos[3 * i + a] = s;
            c->pos[3 * i + u] = cu * s;
            c->pos[3 * i + v] = cv;
            c->nrm[3 * i + a] = s;
            c->nrm[3 * i + u] = 0.0f;
            c->nrm[3 * i + v] = 0.0f;
            c->uv[2 * i] = ((float)f + (cu + 1.0f) * 0.5f) / 6.0f;
            c->uv[2 * i + 1] = (cv + 1.0f) * 0.5f;
        }
        c->idx[6 * f + 0] = (uint32_t)(4 * f);
        c->idx[6 * f + 1] = (uint32_t)(4 * f + 1);
        c->idx[6 * f + 2] = (uint32_t)(4 * f + 2);
        c->idx[6 * f + 3] = (uint32_t)(4 * f);
        c->idx[6 * f + 4] = (uint32_t)(4 * f + 2);
        c->idx[6 * f + 5] = (uint32_t)(4 * f + 3);
    }
    memset(&c->mesh, 0, sizeof c->mesh);
    c->mesh.positions = c->pos;
    c->mesh.normals = c->nrm;
    c->mesh.uvs = c->uv;
    c->mesh.vertex_count = 24;
    c->mesh.indices = c->idx;
    c->mesh.triangle_count = 12;
}

static void test_guides_weld_and_rest_shape(void)
{
    t_cube c;
    hf_tess_params tp;
    t_tess ts;
    hf_guide_params gp;
    hf_guide_output go;
    float *pts, lengths[64], dirs[64 * 3], nrms[64 * 3], roots[12 * 3];
    uint32_t gov[64];
    float ramp[8];
    hf_map lmap;
    int i, j, G, ok = 1;
    const int N = 5;
    t_counter cnt;
    hf_allocator al = t_counting(&cnt);
    t_make_cube(&c);
    memset(&tp, 0, sizeof tp);
    tp.factor = 1.0f; /* triangle area 2: one split each */
    ts = t_tessellate(&c.mesh, NULL, &tp);
    CHECK_EQ_INT(ts.r, HF_OK);
    CHECK_EQ_INT(ts.out.added_count, 12);
    for (i = 0; i < 8; ++i) ramp[i] = 0.25f + 0.1f * (float)i;
    lmap = t_f32_map(ramp, 8, 1, 1);
    memset(&gp, 0, sizeof gp);
    gp.points = N;
    gp.max_length = 2.0f;
    gp.length_map = &lmap;
    memset(&go, 0, sizeof go);
    CHECK_EQ_INT(hf_guides_rest(&c.mesh, ts.out.added, 12, &gp, &go, &al),
                 HF_OK);
    CHECK_EQ_INT(go.pure_guide_count, 8);
    CHECK_EQ_INT(go.guide_count, 20);
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    G = go.guide_count;
    pts = (float *)malloc(sizeof(float) * 3 * N * G);
    go.points = pts;
    go.lengths = lengths;
    go.directions = dirs;
    go.normals = nrms;
    go.guide_of_vertex = gov;
    go.guide_capacity = G - 1;
    lengths[0] = -3.0f;
    CHECK_EQ_INT(hf_guides_rest(&c.mesh, ts.out.added, 12, &gp, &go, &al),
                 HF_ERROR_BUFFER_TOO_SMALL);
    CHECK(lengths[0] == -3.0f);
    go.guide_capacity = G;
    cnt.fail_after = cnt.allocs; /* next allocation fails */
    CHECK_EQ_INT(hf_guides_rest(&c.mesh, ts.out.added, 12, &gp, &go, &al),
                 HF_ERROR_OUT_OF_MEMORY);
    CHECK(lengths[0] == -3.0f);
    cnt.fail_after = -1;
    CHECK_EQ_INT(hf_guides_rest(&c.mesh, ts.out.added, 12, &gp, &go, &al),
                 HF_OK);
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    /* copies share a guide; each pure guide: the corner's diagonal normal,
       length the mean of the copies' map values */
    for (i = 0; i < 24; ++i) {
        uint32_t g = gov[i];
        int k, copies = 0;
        CHECK(g < 8);
        for (j = 0; j < 24; ++j)
            if (!memcmp(c.pos + 3 * j, c.pos + 3 * i, 12)) {
                CHECK(gov[j] == g);
                ++copies;
            }
        CHECK_EQ_INT(copies, 3);
        for (k = 0; k < 3; ++k) {
            CHECK_NEAR(nrms[3 * g + k], c.pos[3 * i + k] / sqrt(3.0), 1e-6);
            CHECK_NEAR(pts[3 * (g * N) + k], c.pos[3 * i + k], 0.0);
        }
    }
    for (i = 0; i < 8; ++i) {
        /* length = max_length * mean of the map at the copies' UVs */
        double mean = 0.0;
        int copies = 0;
        for (j = 0; j < 24; ++j)
            if (gov[j] == (uint32_t)i) {
                float s[4];
                hf_map_sample(&lmap, c.uv[2 * j], c.uv[2 * j + 1], s);
                mean += s[0];
                ++copies;
            }
        CHECK_NEAR(lengths[i], 2.0 * mean / copies, 1e-6);
    }
    /* LOD guides: root = evaluated vertex, normal = face normal here (the
       blend of three welded corner normals of one face points out of it),
       evenly spaced points */
    for (i = 0; i < 12; ++i) {
        int g = 8 + i, k;
        float root[3], uv[2], s[4], face[3];
        const hf_tess_vertex *a = &ts.out.added[i];
        CHECK_EQ_INT(gov[24 + i], g);
        hf_tess_evaluate(&c.mesh, ts.out.added, 12, i, 1, roots, NULL, NULL);
        memcpy(root, roots + 3 * i, 12);
        CHECK(memcmp(root, pts + 3 * (g * N), 12) == 0);
        memcpy(face, c.nrm + 3 * c.idx[3 * a->triangle], 12);
        CHECK(nrms[3 * g] * face[0] + nrms[3 * g + 1] * face[1] +
                  nrms[3 * g + 2] * face[2] >
              0.9);
        CHECK_NEAR(nrms[3 * g] * nrms[3 * g] + nrms[3 * g + 1] * nrms[3 * g + 1] +
                       nrms[3 * g + 2] * nrms[3 * g + 2],
                   1.0, 1e-5);
        uv[0] = ts.out.uvs[2 * (24 + i)];
        uv[1] = ts.out.uvs[2 * (24 + i) + 1];
        hf_map_sample(&lmap, uv[0], uv[1], s);
        CHECK_NEAR(lengths[g], 2.0 * s[0], 1e-6);
        for (j = 0; j < N; ++j)
            for (k = 0; k < 3; ++k)
                if (fabs(pts[3 * (g * N + j) + k] -
                         (root[k] + dirs[3 * g + k] * lengths[g] * j /
                                        (N - 1))) > 1e-5)
                    ok = 0;
    }
    CHECK(ok);
    ok = 1;
    for (i = 0; i < 3 * N * G; ++i)
        if (!t_is_finite(pts[i])) ok = 0;
    CHECK(ok);
    free(pts);
    t_free_tess(&ts);
}

static void test_guides_combing(void)
{
    t_grid g = t_make_grid(2, 1.0f);
    hf_guide_params gp;
    hf_guide_output go;
    float comb[9 * 3], dirs[9 * 3], pts[9 * 2 * 3];
    unsigned char cm[3] = {255, 128, 128};
    hf_map cmap;
    int i;
    memset(&cmap, 0, sizeof cmap);
    cmap.data = cm;
    cmap.width = cmap.height = 1;
    cmap.channels = 3;
    for (i = 0; i < 9; ++i) {
        comb[3 * i] = 0.0f;
        comb[3 * i + 1] = 3.0f;
        comb[3 * i + 2] = 0.0f;
    }
    comb[0] = comb[1] = 0.0f; /* vertex 0: zero comb -> its normal */
    memset(&gp, 0, sizeof gp);
    gp.points = 2;
    gp.max_length = 1.0f;
    gp.comb = comb;
    memset(&go, 0, sizeof go);
    go.directions = dirs;
    go.points = pts;
    go.guide_capacity = 9;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, NULL, 0, &gp, &go, NULL), HF_OK);
    CHECK_EQ_INT(go.guide_count, 9);
    CHECK(dirs[0] == 0.0f && dirs[1] == 0.0f && dirs[2] == 1.0f);
    for (i = 1; i < 9; ++i)
        CHECK(dirs[3 * i] == 0.0f && dirs[3 * i + 1] == 1.0f &&
              dirs[3 * i + 2] == 0.0f);
    CHECK_NEAR(pts[3 * 3 + 1], g.pos[3 * 1 + 1] + 1.0f, 1e-6);
    /* the map wins over per-vertex combing; 8-bit decodes as 2c - 1 */
    gp.comb_map = &cmap;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, NULL, 0, &gp, &go, NULL), HF_OK);
    for (i = 0; i < 9; ++i) CHECK(dirs[3 * i] > 0.9999f);
    t_free_grid(&g);
}

static void test_guides_bad_input(void)
{
    t_grid g = t_make_grid(2, 1.0f);
    hf_guide_params gp;
    hf_guide_output go;
    hf_tess_vertex a;
    float one = 1.0f, comb[27];
    hf_map m1 = t_f32_map(&one, 1, 1, 1);
    int i;
    memset(&gp, 0, sizeof gp);
    memset(&go, 0, sizeof go);
    go.guide_count = -7;
    gp.points = 16;
    gp.max_length = 1.0f;
    a.triangle = 0;
    a.bary[0] = a.bary[1] = a.bary[2] = 1.0f / 3.0f;
    CHECK_EQ_INT(hf_guides_rest(NULL, NULL, 0, &gp, &go, NULL),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, NULL, 1, &gp, &go, NULL),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, -1, &gp, &go, NULL),
                 HF_ERROR_BAD_COUNT);
    gp.points = 1;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_BAD_COUNT);
    gp.points = HF_GUIDE_MAX_POINTS + 1;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_BAD_COUNT);
    gp.points = 16;
    gp.max_length = 0.0f;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_BAD_PARAMETER);
    gp.max_length = NAN;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_BAD_PARAMETER);
    gp.max_length = 1.0f;
    a.triangle = 8;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_INDEX_OUT_OF_RANGE);
    a.triangle = 0;
    a.bary[2] = NAN;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_NON_FINITE);
    a.bary[2] = 1.5f;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_BAD_PARAMETER);
    a.bary[2] = 1.0f / 3.0f;
    gp.comb_map = &m1; /* one channel */
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_BAD_PARAMETER);
    gp.comb_map = NULL;
    gp.length_map = &m1;
    g.mesh.uvs = NULL;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_NULL_POINTER);
    g.mesh.uvs = g.uv;
    for (i = 0; i < 27; ++i) comb[i] = 1.0f;
    comb[13] = INFINITY;
    gp.comb = comb;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL),
                 HF_ERROR_NON_FINITE);
    gp.comb = NULL;
    CHECK_EQ_INT(go.guide_count, -7);
    /* no mesh normals: computed ones */
    g.mesh.normals = NULL;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, &a, 1, &gp, &go, NULL), HF_OK);
    CHECK_EQ_INT(go.guide_count, 10);
    t_free_grid(&g);
}

static void test_bad_guides_rest(void)
{
    tb_quad q;
    hf_guide_params gp;
    hf_guide_output go;
    float pts[4 * 3 * 4], lens[4];
    uint32_t gov[4];
    hf_tess_vertex v = {0, {0.2f, 0.3f, 0.5f}};
    t_counter cnt;
    hf_allocator a = t_counting(&cnt);
    tb_quad_init(&q);
    memset(&gp, 0, sizeof gp);
    gp.points = 4;
    gp.max_length = 0.1f;
#define TB_GUIDES(added, n, code)                                              \
    do {                                                                       \
        memset(&go, 0, sizeof go);                                             \
        go.points = pts;                                                       \
        go.lengths = lens;                                                     \
        go.guide_of_vertex = gov;                                              \
        go.guide_capacity = 4;                                                 \
        go.guide_count = go.pure_guide_count = -7;                             \
        tb_fill(pts, sizeof pts);                                              \
        tb_fill(lens, sizeof lens);                                            \
        tb_fill(gov, sizeof gov);                                              \
        CHECK_EQ_INT(hf_guides_rest(&q.mesh, (added), (n), &gp, &go, &a),      \
                     (code));                                                  \
        CHECK(tb_untouched(pts, sizeof pts) && tb_untouched(lens, sizeof lens) && \
              tb_untouched(gov, sizeof gov) && go.guide_count == -7);          \
        CHECK_EQ_INT(cnt.allocs, cnt.frees);                                   \
    } while (0)
    gp.points = 1; TB_GUIDES(NULL, 0, HF_ERROR_BAD_COUNT);
    gp.points = HF_GUIDE_MAX_POINTS + 1; TB_GUIDES(NULL, 0, HF_ERROR_BAD_COUNT);
    gp.points = 4;
    gp.max_length = 0.0f; TB_GUIDES(NULL, 0, HF_ERROR_BAD_PARAMETER);
    gp.max_length = TB_NAN; TB_GUIDES(NULL, 0, HF_ERROR_BAD_PARAMETER);
    gp.max_length = -1.0f; TB_GUIDES(NULL, 0, HF_ERROR_BAD_PARAMETER);
    gp.max_length = 0.1f;
    TB_GUIDES(NULL, 1, HF_ERROR_NULL_POINTER);
    TB_GUIDES(&v, -1, HF_ERROR_BAD_COUNT);
    v.triangle = 2; TB_GUIDES(&v, 1, HF_ERROR_INDEX_OUT_OF_RANGE);
    v.triangle = 0;
    v.bary[1] = TB_NAN; TB_GUIDES(&v, 1, HF_ERROR_NON_FINITE);
    v.bary[1] = 1.5f; TB_GUIDES(&v, 1, HF_ERROR_BAD_PARAMETER);
    v.bary[1] = 0.3f;
    /* 4 base vertices + 1 added = 5 guides > capacity 4 */
    TB_GUIDES(&v, 1, HF_ERROR_BUFFER_TOO_SMALL);
    /* out of memory */
    cnt.fail_after = 0;
    TB_GUIDES(NULL, 0, HF_ERROR_OUT_OF_MEMORY);
    cnt.fail_after = -1;
    {
        float comb[12];
        memset(comb, 0, sizeof comb);
        comb[4] = TB_INF;
        gp.comb = comb;
        TB_GUIDES(NULL, 0, HF_ERROR_NON_FINITE);
        gp.comb = NULL;
    }
    CHECK_EQ_INT(hf_guides_rest(&q.mesh, NULL, 0, NULL, &go, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_guides_rest(&q.mesh, NULL, 0, &gp, NULL, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_guides_rest(NULL, NULL, 0, &gp, &go, NULL), HF_ERROR_NULL_POINTER);
    q.nrm[0] = q.nrm[1] = q.nrm[2] = 0.0f;
    TB_GUIDES(NULL, 0, HF_ERROR_DEGENERATE);
    q.nrm[2] = 1.0f;
    /* valid: every output finite */
    memset(&go, 0, sizeof go);
    go.points = pts; go.lengths = lens; go.guide_of_vertex = gov;
    go.guide_capacity = 4;
    CHECK_EQ_INT(hf_guides_rest(&q.mesh, NULL, 0, &gp, &go, NULL), HF_OK);
    CHECK(tb_finite(pts, sizeof pts / sizeof pts[0]));
#undef TB_GUIDES
}

/* 5.3 guides: its tests, in the order they run */
#define T_GUIDES_TESTS(X)                                                      \
    X(test_guides_weld_and_rest_shape)                                         \
    X(test_guides_combing)                                                     \
    X(test_guides_bad_input)                                                   \
    X(test_bad_guides_rest)

/* ---- 5.4 placement ------------------------------------------------------- */

/* Chi-square of strand roots over the 64 equal sub-triangles of the unit
   right triangle (8 x 8 midpoint grid). */
static double t_chi_square_roots(int sampler, int n,
                                 uint64_t seed)
{
    static const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const float uv[6] = {0, 0, 1, 0, 0, 1};
    static const uint32_t idx[3] = {0, 1, 2};
    hf_mesh m;
    hf_place_params p;
    hf_strand *s = (hf_strand *)malloc(sizeof(hf_strand) * (size_t)n);
    float *r = (float *)malloc(sizeof(float) * 3 * (size_t)n);
    int lo[8][8], up[8][8], count = 0, i, j;
    double chi = 0.0, e = (double)n / 64.0;
    memset(&m, 0, sizeof m);
    m.positions = pos;
    m.uvs = uv;
    m.vertex_count = 3;
    m.indices = idx;
    m.triangle_count = 1;
    memset(&p, 0, sizeof p);
    p.total_strands = n;
    p.sampler = sampler;
    p.seed = seed;
    memset(lo, 0, sizeof lo);
    memset(up, 0, sizeof up);
    if (hf_place_strands(&m, NULL, &p, s, n, &count, NULL) != HF_OK ||
        count != n ||
        hf_strand_roots(&m, s, n, 0, n, r) != HF_OK) {
        free(s);
        free(r);
        return -1.0;
    }
    for (i = 0; i < n; ++i) {
        double x = r[3 * i] * 8.0, y = r[3 * i + 1] * 8.0;
        int cx = (int)x, cy = (int)y, upper;
        if (cx > 7) cx = 7;
        if (cy > 7) cy = 7;
        upper = (x - cx) + (y - cy) >= 1.0;
        if (cx + cy > 7) { /* on the hypotenuse, rounding */
            cy = 7 - cx;
            upper = 0;
        }
        if (upper)
            up[cy][cx]++;
        else
            lo[cy][cx]++;
    }
    /* 36 lower cells (cx + cy <= 7) and 28 upper ones (cx + cy <= 6) */
    for (j = 0; j < 8; ++j)
        for (i = 0; i < 8; ++i) {
            if (i + j <= 7) chi += (lo[j][i] - e) * (lo[j][i] - e) / e;
            if (i + j <= 6) chi += (up[j][i] - e) * (up[j][i] - e) / e;
        }
    free(s);
    free(r);
    return chi;
}

/* Uniformity: 6400 roots on one triangle, 64 equal cells, 63 degrees of
   freedom: the 0.1 % critical value is 103.4. The default sampler and the
   stratified one pass with a fixed seed; the plugin's corner-biased
   formula fails by a wide margin (so the test can fail). */
static void test_place_uniform_chi_square(void)
{
    double u = t_chi_square_roots(HF_SAMPLER_UNIFORM, 6400, 1);
    double s = t_chi_square_roots(HF_SAMPLER_STRATIFIED, 6400, 1);
    double b = t_chi_square_roots(HF_SAMPLER_CORNER_BIASED, 6400, 1);
    CHECK(u >= 0.0 && u < 103.4);
    CHECK(s >= 0.0 && s < 103.4);
    CHECK(b > 103.4);
    /* stratified is far more even than chance: chi^2 well below its dof */
    CHECK(s < 20.0);
}

/* mean nearest-neighbour distance (clumps) and the largest empty circle
   over a probe grid (holes) of n roots in the unit right triangle */
static void t_spread(int sampler, int n, double *mean_nn,
                     double *max_hole)
{
    static const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t idx[3] = {0, 1, 2};
    hf_mesh m;
    hf_place_params p;
    hf_strand *s = (hf_strand *)malloc(sizeof(hf_strand) * (size_t)n);
    float *r = (float *)malloc(sizeof(float) * 3 * (size_t)n);
    int i, j, count = 0;
    double sum = 0.0, hole = 0.0;
    memset(&m, 0, sizeof m);
    m.positions = pos;
    m.vertex_count = 3;
    m.indices = idx;
    m.triangle_count = 1;
    memset(&p, 0, sizeof p);
    p.total_strands = n;
    p.sampler = sampler;
    p.seed = 5;
    hf_place_strands(&m, NULL, &p, s, n, &count, NULL);
    hf_strand_roots(&m, s, n, 0, n, r);
    for (i = 0; i < n; ++i) {
        double best = 1e9;
        for (j = 0; j < n; ++j) {
            double dx = r[3 * i] - r[3 * j], dy = r[3 * i + 1] - r[3 * j + 1];
            double d = dx * dx + dy * dy;
            if (j != i && d < best) best = d;
        }
        sum += sqrt(best);
    }
    for (i = 0; i < 80; ++i)
        for (j = 0; i + j < 80; ++j) {
            double x = (i + 0.5) / 80.0, y = (j + 0.5) / 80.0, best = 1e9;
            int k;
            for (k = 0; k < n; ++k) {
                double dx = x - r[3 * k], dy = y - r[3 * k + 1];
                double d = dx * dx + dy * dy;
                if (d < best) best = d;
            }
            if (sqrt(best) > hole) hole = sqrt(best);
        }
    *mean_nn = sum / n;
    *max_hole = hole;
    free(s);
    free(r);
}

static void test_place_stratified_fewer_clumps_and_holes(void)
{
    double nn_u, hole_u, nn_s, hole_s;
    t_spread(HF_SAMPLER_UNIFORM, 1024, &nn_u, &hole_u);
    t_spread(HF_SAMPLER_STRATIFIED, 1024, &nn_s, &hole_s);
    /* Poisson points: mean NN distance 0.5 / sqrt(density) ~ 0.011 */
    CHECK(nn_s > 1.2 * nn_u); /* measured: 0.0144 vs 0.0110 */
    CHECK(hole_s < 0.75 * hole_u); /* measured: 0.022 vs 0.040 */
}

/* The expected total is the density integral: with the AREA estimator
   sum(D_t A_t) is exactly the integral of the (piecewise-constant) map over
   the surface, and systematic rounding puts the count within 1 of
   integral * strands_per_area (stated tolerance: 1 + 1e-4 relative, for
   float rounding). With total_strands the count is exact and each
   triangle gets floor or ceil of its share. */
static void test_place_total_matches_density_integral(void)
{
    t_grid g = t_make_grid(16, 2.0f);
    enum { W = 32 };
    static float d[W * W];
    hf_map m = t_f32_map(d, W, W, 1);
    hf_place_params p;
    double mean = 0.0, integral;
    int i, count = -1, t;
    hf_rng rng;
    hf_strand *s;
    int *per;
    hf_rng_seed(&rng, 3, 0);
    for (i = 0; i < W * W; ++i) {
        d[i] = hf_rng_float(&rng);
        mean += d[i];
    }
    mean /= W * W;
    integral = 4.0 * mean; /* area 4 */
    memset(&p, 0, sizeof p);
    p.estimator = HF_DENSITY_AREA;
    p.strands_per_area = 1000.0f;
    for (i = 0; i < 5; ++i) {
        p.seed = (uint64_t)i;
        CHECK_EQ_INT(hf_place_strands(&g.mesh, &m, &p, NULL, 0, &count, NULL),
                     HF_OK);
        CHECK_NEAR(count, integral * 1000.0, 1.0 + 1e-4 * integral * 1000.0);
    }
    /* exact total, per-triangle floor or ceil */
    p.total_strands = 5000;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, &m, &p, NULL, 0, &count, NULL),
                 HF_OK);
    CHECK_EQ_INT(count, 5000);
    s = (hf_strand *)malloc(sizeof(hf_strand) * 5000);
    per = (int *)calloc((size_t)g.mesh.triangle_count, sizeof(int));
    CHECK_EQ_INT(hf_place_strands(&g.mesh, &m, &p, s, 5000, &count, NULL),
                 HF_OK);
    for (i = 0; i < count; ++i) per[s[i].triangle]++;
    {
        double S = 0.0;
        int ok = 1;
        for (t = 0; t < g.mesh.triangle_count; ++t) {
            const uint32_t *tri = g.idx + 3 * t;
            float dd;
            hf_uv_triangle_density(&m, g.uv + 2 * tri[0], g.uv + 2 * tri[1],
                                   g.uv + 2 * tri[2], HF_DENSITY_AREA, &dd);
            S += dd * t_tri_area(g.pos, tri);
        }
        for (t = 0; t < g.mesh.triangle_count; ++t) {
            const uint32_t *tri = g.idx + 3 * t;
            float dd;
            double e;
            hf_uv_triangle_density(&m, g.uv + 2 * tri[0], g.uv + 2 * tri[1],
                                   g.uv + 2 * tri[2], HF_DENSITY_AREA, &dd);
            e = 5000.0 * dd * t_tri_area(g.pos, tri) / S;
            if (per[t] < floor(e - 1e-3) || per[t] > ceil(e + 1e-3)) ok = 0;
        }
        CHECK(ok);
    }
    free(s);
    free(per);
    t_free_grid(&g);
}

static int t_cmp_by_triangle(const void *a, const void *b)
{
    const hf_strand *x = (const hf_strand *)a, *y = (const hf_strand *)b;
    if (x->triangle != y->triangle) return x->triangle < y->triangle ? -1 : 1;
    return x->random < y->random ? -1 : (x->random > y->random ? 1 : 0);
}

/* regions (of a 10 x 10 grid over the unit square) reached by the first n
   roots, and the extreme per-region counts */
static int t_regions_reached(const hf_mesh *m, const hf_strand *s, int n,
                             int *min_c, int *max_c)
{
    int cells[100], i, reached = 0;
    float *r = (float *)malloc(sizeof(float) * 3 * (size_t)n);
    memset(cells, 0, sizeof cells);
    hf_strand_roots(m, s, n, 0, n, r);
    for (i = 0; i < n; ++i) {
        int cx = (int)(r[3 * i] * 10.0f), cy = (int)(r[3 * i + 1] * 10.0f);
        cx = cx > 9 ? 9 : cx;
        cy = cy > 9 ? 9 : cy;
        cells[cy * 10 + cx]++;
    }
    *min_c = 1 << 30;
    *max_c = 0;
    for (i = 0; i < 100; ++i) {
        reached += cells[i] > 0;
        if (cells[i] < *min_c) *min_c = cells[i];
        if (cells[i] > *max_c) *max_c = cells[i];
    }
    free(r);
    return reached;
}

/* LOD order: the first 10 % of the strands of a 5000-triangle mesh reach
   all 100 regions, each with close to its 1 % share; the same strands in
   placement (triangle) order do not, so the check can fail. */
static void test_place_lod_prefix_covers_surface(void)
{
    t_grid g = t_make_grid(50, 1.0f);
    hf_place_params p;
    hf_strand *s;
    int count = 0, mn, mx, smp;
    memset(&p, 0, sizeof p);
    p.total_strands = 50000;
    s = (hf_strand *)malloc(sizeof(hf_strand) * 50000);
    for (smp = 0; smp < 2; ++smp) {
        p.sampler = smp ? HF_SAMPLER_STRATIFIED : HF_SAMPLER_UNIFORM;
        CHECK_EQ_INT(
            hf_place_strands(&g.mesh, NULL, &p, s, 50000, &count, NULL),
            HF_OK);
        CHECK_EQ_INT(t_regions_reached(&g.mesh, s, 5000, &mn, &mx), 100);
        /* 50 expected per region; every triangle gives exactly 1 of its 10 */
        CHECK(mn >= 40 && mx <= 60);
        CHECK_EQ_INT(t_regions_reached(&g.mesh, s, 500, &mn, &mx), 100);
    }
    qsort(s, 50000, sizeof(hf_strand), t_cmp_by_triangle);
    CHECK(t_regions_reached(&g.mesh, s, 5000, &mn, &mx) < 100);
    free(s);
    t_free_grid(&g);
}

static void test_place_same_seed_same_bytes(void)
{
    t_grid g = t_make_grid(8, 1.0f);
    float *blob = t_blob_data(32, 32);
    hf_map m = t_f32_map(blob, 32, 32, 1);
    hf_place_params p;
    hf_strand *a, *b;
    int na = 0, nb = 0, smp;
    t_counter cnt;
    hf_allocator al = t_counting(&cnt);
    memset(&p, 0, sizeof p);
    p.strands_per_area = 3000.0f;
    p.seed = 99;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, &m, &p, NULL, 0, &na, &al), HF_OK);
    CHECK_EQ_INT(cnt.allocs, 0); /* counting allocates nothing */
    a = (hf_strand *)malloc(sizeof(hf_strand) * (size_t)na);
    b = (hf_strand *)malloc(sizeof(hf_strand) * (size_t)na);
    for (smp = 0; smp < 3; ++smp) {
        int i, ok = 1;
        p.sampler = smp;
        memset(a, 0, sizeof(hf_strand) * (size_t)na);
        memset(b, 0xff, sizeof(hf_strand) * (size_t)na);
        CHECK_EQ_INT(hf_place_strands(&g.mesh, &m, &p, a, na, &nb, &al),
                     HF_OK);
        CHECK_EQ_INT(nb, na);
        CHECK_EQ_INT(hf_place_strands(&g.mesh, &m, &p, b, na, &nb, NULL),
                     HF_OK);
        CHECK(memcmp(a, b, sizeof(hf_strand) * (size_t)na) == 0);
        for (i = 0; i < na; ++i) {
            const hf_strand *q = &a[i];
            float b2 = (1.0f - q->bary[0]) - q->bary[1];
            if (!(q->bary[0] >= 0.0f && q->bary[1] >= 0.0f && b2 >= 0.0f &&
                  q->random >= 0.0f && q->random < 1.0f &&
                  q->triangle < (uint32_t)g.mesh.triangle_count))
                ok = 0;
        }
        CHECK(ok);
    }
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    CHECK(cnt.allocs == 3);
    p.seed = 100;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, &m, &p, b, na, &nb, NULL), HF_OK);
    CHECK(nb != na || memcmp(a, b, sizeof(hf_strand) * (size_t)na) != 0);
    /* allocation failure: nothing written */
    p.seed = 99;
    memset(b, 0x33, sizeof(hf_strand) * (size_t)na);
    memcpy(a, b, sizeof(hf_strand) * (size_t)na);
    cnt.fail_after = cnt.allocs;
    nb = -7;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, &m, &p, b, na, &nb, &al),
                 HF_ERROR_OUT_OF_MEMORY);
    CHECK(memcmp(a, b, sizeof(hf_strand) * (size_t)na) == 0);
    CHECK_EQ_INT(nb, -7);
    free(a);
    free(b);
    free(blob);
    t_free_grid(&g);
}

static void test_place_bad_input(void)
{
    t_grid g = t_make_grid(2, 1.0f);
    hf_place_params p;
    hf_strand s[64], before[64];
    static const float zero[4] = {0, 0, 0, 0};
    hf_map mz = t_f32_map(zero, 2, 2, 1);
    int n = -7, k = -7, i;
    const float bad_spa[4] = {0.0f, -1.0f, NAN, INFINITY};
    memset(s, 0x44, sizeof s);
    memcpy(before, s, sizeof s);
    memset(&p, 0, sizeof p);
    p.strands_per_area = 40.0f;
    CHECK_EQ_INT(hf_place_strands(NULL, NULL, &p, s, 64, &n, NULL),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, NULL, s, 64, &n, NULL),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, s, 64, NULL, NULL),
                 HF_ERROR_NULL_POINTER);
    for (i = 0; i < 4; ++i) {
        p.strands_per_area = bad_spa[i];
        CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, s, 64, &n, NULL),
                     HF_ERROR_BAD_PARAMETER);
    }
    p.strands_per_area = 40.0f;
    p.total_strands = -1;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, s, 64, &n, NULL),
                 HF_ERROR_BAD_COUNT);
    p.total_strands = 0;
    p.sampler = 3;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, s, 64, &n, NULL),
                 HF_ERROR_BAD_PARAMETER);
    p.sampler = HF_SAMPLER_UNIFORM;
    /* counts that would overflow */
    p.strands_per_area = 1e30f;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, NULL, 0, &n, NULL),
                 HF_ERROR_OVERFLOW);
    p.strands_per_area = 3e9f;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, NULL, 0, &n, NULL),
                 HF_ERROR_OVERFLOW);
    p.strands_per_area = 40.0f;
    p.max_strands = 10;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, NULL, 0, &n, NULL),
                 HF_ERROR_OVERFLOW);
    p.max_strands = 0;
    CHECK_EQ_INT(n, -7);
    /* short buffer */
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, NULL, 0, &k, NULL),
                 HF_OK);
    CHECK(k == 39 || k == 40);
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, s, k - 1, &n, NULL),
                 HF_ERROR_BUFFER_TOO_SMALL);
    CHECK(memcmp(s, before, sizeof s) == 0);
    CHECK_EQ_INT(n, -7);
    /* zero density: no strands, not an error; but a total cannot be met */
    CHECK_EQ_INT(hf_place_strands(&g.mesh, &mz, &p, s, 64, &n, NULL), HF_OK);
    CHECK_EQ_INT(n, 0);
    n = -7;
    p.total_strands = 10;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, &mz, &p, s, 64, &n, NULL),
                 HF_ERROR_DEGENERATE);
    p.total_strands = 0;
    /* degenerate triangles */
    g.idx[1] = g.idx[0];
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, NULL, 0, &k, NULL),
                 HF_OK);
    p.refuse_degenerate = 1;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, s, 64, &n, NULL),
                 HF_ERROR_DEGENERATE);
    p.refuse_degenerate = 0;
    for (i = 0; i < 8; ++i) g.idx[3 * i + 2] = g.idx[3 * i];
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, s, 64, &n, NULL),
                 HF_ERROR_DEGENERATE);
    CHECK(memcmp(s, before, sizeof s) == 0);
    CHECK_EQ_INT(n, -7);
    t_free_grid(&g);
}

/* A zero-area triangle grows nothing; the rest of the mesh still grows. */
static void test_place_skips_zero_area_triangles(void)
{
    t_grid g = t_make_grid(2, 1.0f);
    hf_place_params p;
    hf_strand s[200];
    int n = 0, i, ok = 1;
    g.idx[1] = g.idx[0]; /* triangle 0 degenerate */
    memset(&p, 0, sizeof p);
    p.total_strands = 200;
    CHECK_EQ_INT(hf_place_strands(&g.mesh, NULL, &p, s, 200, &n, NULL),
                 HF_OK);
    CHECK_EQ_INT(n, 200);
    for (i = 0; i < n; ++i)
        if (s[i].triangle == 0) ok = 0;
    CHECK(ok);
    t_free_grid(&g);
}

static void test_bad_place_strands(void)
{
    tb_quad q;
    hf_place_params pp;
    hf_strand out[64];
    int n;
    t_counter cnt;
    hf_allocator a = t_counting(&cnt);
    tb_quad_init(&q);
    memset(&pp, 0, sizeof pp);
    pp.strands_per_area = 20.0f;
#define TB_PLACE(expr, cap, code)                                              \
    do {                                                                       \
        hf_place_params p_ = pp;                                               \
        expr;                                                                  \
        n = -7;                                                                \
        tb_fill(out, sizeof out);                                              \
        CHECK_EQ_INT(hf_place_strands(&q.mesh, NULL, &p_, out, (cap), &n, &a), \
                     (code));                                                  \
        CHECK(n == -7 && tb_untouched(out, sizeof out));                       \
        CHECK_EQ_INT(cnt.allocs, cnt.frees);                                   \
    } while (0)
    TB_PLACE(p_.strands_per_area = 0.0f, 64, HF_ERROR_BAD_PARAMETER);
    TB_PLACE(p_.strands_per_area = -1.0f, 64, HF_ERROR_BAD_PARAMETER);
    TB_PLACE(p_.strands_per_area = TB_NAN, 64, HF_ERROR_BAD_PARAMETER);
    TB_PLACE(p_.strands_per_area = TB_INF, 64, HF_ERROR_BAD_PARAMETER);
    TB_PLACE(p_.total_strands = -1, 64, HF_ERROR_BAD_COUNT);
    /* refused even where total_strands leaves it unused */
    TB_PLACE((p_.total_strands = 10, p_.strands_per_area = -1.0f), 64,
             HF_ERROR_BAD_PARAMETER);
    TB_PLACE((p_.total_strands = 10, p_.strands_per_area = TB_NAN), 64,
             HF_ERROR_BAD_PARAMETER);
    TB_PLACE(p_.estimator = 3, 64, HF_ERROR_BAD_PARAMETER);
    TB_PLACE(p_.sampler = 3, 64, HF_ERROR_BAD_PARAMETER);
    TB_PLACE(p_.max_strands = -1, 64, HF_ERROR_BAD_PARAMETER);
    TB_PLACE(p_.strands_per_area = 1e30f, 64, HF_ERROR_OVERFLOW);
    TB_PLACE(p_.strands_per_area = FLT_MAX, 64, HF_ERROR_OVERFLOW);
    TB_PLACE((p_.total_strands = 0x7fffffff), 64, HF_ERROR_OVERFLOW);
    TB_PLACE(p_.max_strands = 5, 64, HF_ERROR_OVERFLOW);
    TB_PLACE((void)0, 5, HF_ERROR_BUFFER_TOO_SMALL);
    cnt.fail_after = 0;
    TB_PLACE((void)0, 64, HF_ERROR_OUT_OF_MEMORY);
    cnt.fail_after = -1;
    CHECK_EQ_INT(hf_place_strands(&q.mesh, NULL, &pp, out, 64, NULL, NULL),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_place_strands(&q.mesh, NULL, NULL, out, 64, &n, NULL),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_place_strands(NULL, NULL, &pp, out, 64, &n, NULL),
                 HF_ERROR_NULL_POINTER);
    /* every triangle zero-area */
    memset(q.pos, 0, sizeof q.pos);
    TB_PLACE((void)0, 64, HF_ERROR_DEGENERATE);
    /* density zero everywhere with total_strands */
    tb_quad_init(&q);
    {
        unsigned char zero[1] = {0};
        hf_map m;
        memset(&m, 0, sizeof m);
        m.data = zero; m.width = 1; m.height = 1; m.channels = 1;
        n = -7;
        pp.total_strands = 10;
        CHECK_EQ_INT(hf_place_strands(&q.mesh, &m, &pp, out, 64, &n, NULL),
                     HF_ERROR_DEGENERATE);
        CHECK_EQ_INT(n, -7);
        pp.total_strands = 0;
    }
#undef TB_PLACE
}

/* 5.4 placement: its tests, in the order they run */
#define T_PLACE_TESTS(X)                                                       \
    X(test_place_uniform_chi_square)                                           \
    X(test_place_stratified_fewer_clumps_and_holes)                            \
    X(test_place_total_matches_density_integral)                               \
    X(test_place_lod_prefix_covers_surface)                                    \
    X(test_place_same_seed_same_bytes)                                         \
    X(test_place_bad_input)                                                    \
    X(test_place_skips_zero_area_triangles)                                    \
    X(test_bad_place_strands)

/* ---- 5.5 maps on strands, 5.6 bindings ----------------------------------- */

static void test_strand_lengths_and_colors(void)
{
    hf_strand s[3];
    float lengths[3], rgba[12], xy[2], c[4], ref[4];
    static const float len_map[2] = {0.25f, 1.0f};
    static const float rgb[3 * 4] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    static const float idx_map[1] = {0.25f};
    static const float big_idx[1] = {2.0f};
    hf_map lm = t_f32_map(len_map, 2, 1, 1), cm = t_f32_map(rgb, 2, 2, 3);
    hf_map im = t_f32_map(idx_map, 1, 1, 1), bm = t_f32_map(big_idx, 1, 1, 1);
    hf_map grey = t_f32_map(idx_map, 1, 1, 1);
    int i;
    memset(s, 0, sizeof s);
    s[0].uv[0] = 0.25f; /* texel 0 centre */
    s[0].uv[1] = 0.25f;
    s[1].uv[0] = 0.75f; /* texel 1 centre */
    s[1].uv[1] = 0.75f;
    s[2].uv[0] = 0.5f; /* between: mean */
    s[2].uv[1] = 0.5f;
    CHECK_EQ_INT(hf_strand_lengths(s, 3, 0, 3, &lm, 2.0f, lengths), HF_OK);
    CHECK_NEAR(lengths[0], 0.5, 1e-6);
    CHECK_NEAR(lengths[1], 2.0, 1e-6);
    CHECK_NEAR(lengths[2], 1.25, 1e-6);
    CHECK_EQ_INT(hf_strand_lengths(s, 3, 0, 3, NULL, 2.0f, lengths), HF_OK);
    CHECK(lengths[0] == 2.0f);
    CHECK_EQ_INT(hf_strand_colors(s, 3, 0, 3, &cm, rgba), HF_OK);
    CHECK(rgba[0] == 1.0f && rgba[1] == 0.0f && rgba[2] == 0.0f &&
          rgba[3] == 1.0f);
    CHECK(rgba[4] == 1.0f && rgba[5] == 1.0f && rgba[6] == 1.0f);
    CHECK_NEAR(rgba[8], 0.5, 1e-6);
    CHECK_EQ_INT(hf_strand_colors(s, 3, 0, 1, &grey, rgba), HF_OK);
    CHECK(rgba[0] == 0.25f && rgba[1] == 0.25f && rgba[2] == 0.25f &&
          rgba[3] == 1.0f);
    /* 3D colour: column from the index map, row from t */
    CHECK_EQ_INT(hf_color3d_coord(&im, 0.3f, 0.8f, 0.75f, xy), HF_OK);
    CHECK(xy[0] == 0.25f && xy[1] == 0.75f);
    CHECK_EQ_INT(hf_color3d_sample(&im, &cm, 0.3f, 0.8f, 0.75f, c), HF_OK);
    hf_map_sample(&cm, 0.25f, 0.75f, ref);
    for (i = 0; i < 3; ++i) CHECK(c[i] == ref[i]);
    CHECK(c[3] == 1.0f);
    CHECK_EQ_INT(hf_color3d_coord(&bm, 0.3f, 0.8f, 1.5f, xy), HF_OK);
    CHECK(xy[0] == 1.0f && xy[1] == 1.0f);
    xy[0] = -3.0f;
    CHECK_EQ_INT(hf_color3d_coord(&im, 0.3f, 0.8f, NAN, xy),
                 HF_ERROR_NON_FINITE);
    CHECK(xy[0] == -3.0f);
    CHECK_EQ_INT(hf_strand_lengths(s, 3, 2, 2, &lm, 2.0f, lengths),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_strand_lengths(s, 3, 0, 3, &lm, -1.0f, lengths),
                 HF_ERROR_BAD_PARAMETER);
    s[1].uv[0] = NAN;
    lengths[0] = -9.0f;
    CHECK_EQ_INT(hf_strand_lengths(s, 3, 0, 3, &lm, 2.0f, lengths),
                 HF_ERROR_NON_FINITE);
    CHECK(lengths[0] == -9.0f);
}

/* The whole stage end to end: tessellate, guides, place, lengths, bind,
   interpolate at rest: each strand starts at its root and is as long as
   the length map says (the guides are parallel on a flat grid). */
static void test_grow_end_to_end_bindings(void)
{
    t_grid g = t_make_grid(4, 1.0f);
    float *blob = t_blob_data(32, 32);
    hf_map m = t_f32_map(blob, 32, 32, 1);
    hf_tess_params tp;
    t_tess ts;
    hf_mesh tm;
    hf_guide_params gp;
    hf_guide_output go;
    hf_place_params pp;
    hf_interp_params ip;
    hf_strand *s;
    hf_strand_binding *b;
    float *gpts, *glen, *slen, *roots, *spts;
    uint32_t *gov;
    int n = 0, i, P = 8, ok_root = 1, ok_len = 1;
    memset(&tp, 0, sizeof tp);
    tp.factor = 60.0f;
    ts = t_tessellate(&g.mesh, &m, &tp);
    CHECK_EQ_INT(ts.r, HF_OK);
    tm = t_tess_mesh(&ts);
    memset(&gp, 0, sizeof gp);
    gp.points = P;
    gp.max_length = 0.5f;
    gp.length_map = &m;
    memset(&go, 0, sizeof go);
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, ts.out.added, ts.out.added_count,
                                &gp, &go, NULL),
                 HF_OK);
    gpts = (float *)malloc(sizeof(float) * 3 * P * go.guide_count);
    glen = (float *)malloc(sizeof(float) * go.guide_count);
    gov = (uint32_t *)malloc(sizeof(uint32_t) * ts.out.vertex_count);
    go.points = gpts;
    go.lengths = glen;
    go.guide_of_vertex = gov;
    go.guide_capacity = go.guide_count;
    CHECK_EQ_INT(hf_guides_rest(&g.mesh, ts.out.added, ts.out.added_count,
                                &gp, &go, NULL),
                 HF_OK);
    memset(&pp, 0, sizeof pp);
    pp.total_strands = 2000;
    pp.sampler = HF_SAMPLER_STRATIFIED;
    s = (hf_strand *)malloc(sizeof(hf_strand) * 2000);
    CHECK_EQ_INT(hf_place_strands(&tm, &m, &pp, s, 2000, &n, NULL), HF_OK);
    slen = (float *)malloc(sizeof(float) * n);
    roots = (float *)malloc(sizeof(float) * 3 * n);
    b = (hf_strand_binding *)malloc(sizeof(hf_strand_binding) * n);
    spts = (float *)malloc(sizeof(float) * 3 * P * n);
    CHECK_EQ_INT(hf_strand_lengths(s, n, 0, n, &m, 0.5f, slen), HF_OK);
    CHECK_EQ_INT(hf_strand_roots(&tm, s, n, 0, n, roots), HF_OK);
    CHECK_EQ_INT(hf_bind_strands(&tm, gov, go.guide_count, s, n, 0, n, slen,
                                 glen, b),
                 HF_OK);
    memset(&ip, 0, sizeof ip);
    ip.points_per_strand = P;
    CHECK_EQ_INT(hf_interpolate(gpts, go.guide_count, b, 0, n, &ip, spts),
                 HF_OK);
    for (i = 0; i < n; ++i) {
        const float *p0 = spts + 3 * P * i, *pt = p0 + 3 * (P - 1);
        double dx = pt[0] - p0[0], dy = pt[1] - p0[1], dz = pt[2] - p0[2];
        if (fabs(p0[0] - roots[3 * i]) > 1e-6 ||
            fabs(p0[1] - roots[3 * i + 1]) > 1e-6 || p0[2] != 0.0f)
            ok_root = 0;
        if (fabs(sqrt(dx * dx + dy * dy + dz * dz) - slen[i]) > 1e-5)
            ok_len = 0;
    }
    CHECK(ok_root);
    CHECK(ok_len);
    gov[0] = 999999;
    CHECK_EQ_INT(hf_bind_strands(&tm, gov, go.guide_count, s, n, 0, n, slen,
                                 glen, b),
                 HF_ERROR_INDEX_OUT_OF_RANGE);
    CHECK_EQ_INT(hf_bind_strands(&tm, gov, go.guide_count, s, n, 0, n, slen,
                                 NULL, b),
                 HF_ERROR_NULL_POINTER);
    free(gpts);
    free(glen);
    free(gov);
    free(s);
    free(slen);
    free(roots);
    free(b);
    free(spts);
    free(blob);
    t_free_tess(&ts);
    t_free_grid(&g);
}

static void test_bad_strand_functions(void)
{
    tb_quad q;
    hf_strand s[2] = {{0, {0.2f, 0.3f}, {0.5f, 0.5f}, 0.5f},
                      {1, {0.1f, 0.1f}, {0.25f, 0.75f}, 0.25f}};
    float roots[6], lens[2], rgba[8], xy[2], c4[4];
    unsigned char px[4] = {10, 20, 30, 40};
    hf_map m;
    uint32_t gov[4] = {0, 1, 2, 3};
    float glen[4] = {1, 1, 1, 1};
    hf_strand_binding b[2];
    tb_quad_init(&q);
    memset(&m, 0, sizeof m);
    m.data = px; m.width = 2; m.height = 2; m.channels = 1;
    /* roots */
    TB_FAILS(hf_strand_roots(NULL, s, 2, 0, 2, roots), HF_ERROR_NULL_POINTER, roots, sizeof roots);
    TB_FAILS(hf_strand_roots(&q.mesh, NULL, 2, 0, 2, roots), HF_ERROR_NULL_POINTER, roots, sizeof roots);
    CHECK_EQ_INT(hf_strand_roots(&q.mesh, s, 2, 0, 2, NULL), HF_ERROR_NULL_POINTER);
    tb_fill(roots, sizeof roots);
    {
        hf_result rr = hf_strand_roots(&q.mesh, s, -1, 0, 0, roots);
        CHECK(rr == HF_ERROR_BAD_COUNT || rr == HF_ERROR_BAD_RANGE);
        CHECK(tb_untouched(roots, sizeof roots));
    }
    TB_FAILS(hf_strand_roots(&q.mesh, s, 2, 1, 2, roots), HF_ERROR_BAD_RANGE, roots, sizeof roots);
    TB_FAILS(hf_strand_roots(&q.mesh, s, 2, 2, 0x7fffffff, roots), HF_ERROR_BAD_RANGE, roots, sizeof roots);
    s[1].triangle = 7;
    TB_FAILS(hf_strand_roots(&q.mesh, s, 2, 0, 2, roots), HF_ERROR_INDEX_OUT_OF_RANGE, roots, sizeof roots);
    s[1].triangle = 1;
    s[1].bary[1] = TB_NAN;
    TB_FAILS(hf_strand_roots(&q.mesh, s, 2, 0, 2, roots), HF_ERROR_NON_FINITE, roots, sizeof roots);
    s[1].bary[1] = 0.1f;
    q.pos[9] = TB_NAN; /* vertex 3, used by triangle 1 */
    TB_FAILS(hf_strand_roots(&q.mesh, s, 2, 0, 2, roots), HF_ERROR_NON_FINITE, roots, sizeof roots);
    q.pos[9] = 0.0f;
    q.mesh.position_stride = 11;
    TB_FAILS(hf_strand_roots(&q.mesh, s, 2, 0, 2, roots), HF_ERROR_BAD_STRIDE, roots, sizeof roots);
    q.mesh.position_stride = 0;
    /* lengths: finite max_length times a float map value above 1 must not
       overflow to inf */
    {
        float two[1] = {2.0f};
        hf_map fm;
        hf_result rr;
        memset(&fm, 0, sizeof fm);
        fm.data = two; fm.width = 1; fm.height = 1; fm.channels = 1;
        fm.format = HF_MAP_F32;
        tb_fill(lens, sizeof lens);
        rr = hf_strand_lengths(s, 2, 0, 2, &fm, FLT_MAX, lens);
        CHECK(rr < 0 ? tb_untouched(lens, sizeof lens) : tb_finite(lens, 2));
    }
    TB_FAILS(hf_strand_lengths(NULL, 2, 0, 2, &m, 1.0f, lens), HF_ERROR_NULL_POINTER, lens, sizeof lens);
    CHECK_EQ_INT(hf_strand_lengths(s, 2, 0, 2, &m, 1.0f, NULL), HF_ERROR_NULL_POINTER);
    TB_FAILS(hf_strand_lengths(s, 2, 0, 2, &m, -1.0f, lens), HF_ERROR_BAD_PARAMETER, lens, sizeof lens);
    TB_FAILS(hf_strand_lengths(s, 2, 0, 2, &m, TB_NAN, lens), HF_ERROR_BAD_PARAMETER, lens, sizeof lens);
    TB_FAILS(hf_strand_lengths(s, 2, 0, 2, &m, TB_INF, lens), HF_ERROR_BAD_PARAMETER, lens, sizeof lens);
    TB_FAILS(hf_strand_lengths(s, 2, 1, 2, &m, 1.0f, lens), HF_ERROR_BAD_RANGE, lens, sizeof lens);
    s[0].uv[0] = TB_NAN;
    TB_FAILS(hf_strand_lengths(s, 2, 0, 2, &m, 1.0f, lens), HF_ERROR_NON_FINITE, lens, sizeof lens);
    s[0].uv[0] = 0.5f;
    m.channels = 0;
    TB_FAILS(hf_strand_lengths(s, 2, 0, 2, &m, 1.0f, lens), HF_ERROR_BAD_FORMAT, lens, sizeof lens);
    m.channels = 1;
    /* colours */
    TB_FAILS(hf_strand_colors(s, 2, 0, 2, NULL, rgba), HF_ERROR_NULL_POINTER, rgba, sizeof rgba);
    TB_FAILS(hf_strand_colors(s, 2, -1, 1, &m, rgba), HF_ERROR_BAD_RANGE, rgba, sizeof rgba);
    s[1].uv[1] = -TB_INF;
    TB_FAILS(hf_strand_colors(s, 2, 0, 2, &m, rgba), HF_ERROR_NON_FINITE, rgba, sizeof rgba);
    s[1].uv[1] = 0.75f;
    /* 3D colour */
    TB_FAILS(hf_color3d_coord(NULL, 0.5f, 0.5f, 0.5f, xy), HF_ERROR_NULL_POINTER, xy, sizeof xy);
    TB_FAILS(hf_color3d_coord(&m, TB_NAN, 0.5f, 0.5f, xy), HF_ERROR_NON_FINITE, xy, sizeof xy);
    TB_FAILS(hf_color3d_coord(&m, 0.5f, 0.5f, TB_INF, xy), HF_ERROR_NON_FINITE, xy, sizeof xy);
    TB_FAILS(hf_color3d_sample(&m, NULL, 0.5f, 0.5f, 0.5f, c4), HF_ERROR_NULL_POINTER, c4, sizeof c4);
    TB_FAILS(hf_color3d_sample(&m, &m, 0.5f, TB_NAN, 0.5f, c4), HF_ERROR_NON_FINITE, c4, sizeof c4);
    CHECK_EQ_INT(hf_color3d_coord(&m, 0.5f, 0.5f, 1e30f, xy), HF_OK);
    CHECK(xy[1] == 1.0f);
    /* bindings */
#define TB_BIND(call, code) TB_FAILS(call, code, b, sizeof b)
    TB_BIND(hf_bind_strands(NULL, gov, 4, s, 2, 0, 2, NULL, NULL, b), HF_ERROR_NULL_POINTER);
    TB_BIND(hf_bind_strands(&q.mesh, NULL, 4, s, 2, 0, 2, NULL, NULL, b), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_bind_strands(&q.mesh, gov, 4, s, 2, 0, 2, NULL, NULL, NULL), HF_ERROR_NULL_POINTER);
    TB_BIND(hf_bind_strands(&q.mesh, gov, 4, s, 2, 0, 2, lens, NULL, b), HF_ERROR_NULL_POINTER);
    TB_BIND(hf_bind_strands(&q.mesh, gov, 0, s, 2, 0, 2, NULL, NULL, b), HF_ERROR_BAD_COUNT);
    TB_BIND(hf_bind_strands(&q.mesh, gov, 4, s, 2, 2, 1, NULL, NULL, b), HF_ERROR_BAD_RANGE);
    gov[3] = 4;
    TB_BIND(hf_bind_strands(&q.mesh, gov, 4, s, 2, 0, 2, NULL, NULL, b), HF_ERROR_INDEX_OUT_OF_RANGE);
    gov[3] = 3;
    s[0].triangle = 2;
    TB_BIND(hf_bind_strands(&q.mesh, gov, 4, s, 2, 0, 2, NULL, NULL, b), HF_ERROR_INDEX_OUT_OF_RANGE);
    s[0].triangle = 0;
    lens[0] = 1.0f; lens[1] = TB_NAN;
    TB_BIND(hf_bind_strands(&q.mesh, gov, 4, s, 2, 0, 2, lens, glen, b), HF_ERROR_NON_FINITE);
    lens[1] = 1.0f;
    glen[2] = TB_INF;
    TB_BIND(hf_bind_strands(&q.mesh, gov, 4, s, 2, 0, 2, lens, glen, b), HF_ERROR_NON_FINITE);
    glen[2] = 0.0f; glen[0] = glen[1] = glen[3] = 0.0f; /* weighted length 0: 1 */
    CHECK_EQ_INT(hf_bind_strands(&q.mesh, gov, 4, s, 2, 0, 2, lens, glen, b), HF_OK);
    CHECK(b[0].length_scale == 1.0f && t_is_finite(b[1].length_scale));
#undef TB_BIND
}

/* 5.5 maps on strands, 5.6 bindings: its tests, in the order they run */
#define T_STRAND_TESTS(X)                                                      \
    X(test_strand_lengths_and_colors)                                          \
    X(test_grow_end_to_end_bindings)                                           \
    X(test_bad_strand_functions)

/* ==== 6. ropes ============================================================ */

static void test_ropes_params_defaults_and_validation(void)
{
    hf_rope_params p, q;
    hf_diag d;
    hf_rope_params_init(&p);
    CHECK(p.gravity[0] == 0.0f && p.gravity[1] == -9.81f &&
          p.gravity[2] == 0.0f);
    CHECK(p.wind[0] == 0.0f && p.wind[1] == 0.0f && p.wind[2] == 0.0f);
    CHECK(p.turbulence == 0.0f && p.turbulence_frequency == 1.0f);
    CHECK(p.damping == 0.02f && p.time_scale == 1.0f);
    CHECK(p.substep == 1.0f / 60.0f && p.max_substeps == 8);
    CHECK(p.max_dt == 1.0f / 15.0f && p.iterations == 2);
    CHECK(p.solver == HF_ROPE_SOLVER_FTL && p.ftl_damping == 0.9f);
    CHECK(p.root_stiffness == 0.0f && p.global_stiffness_root == 0.0f &&
          p.global_stiffness_tip == 0.0f && p.local_stiffness_root == 0.0f &&
          p.local_stiffness_tip == 0.0f);
    CHECK(p.collision_margin == 0.002f && p.mode_blend_time == 0.25f);
    CHECK_EQ_INT(hf_rope_params_validate(&p, &d), HF_OK);
    CHECK_EQ_INT(hf_rope_params_validate(NULL, NULL), HF_ERROR_NULL_POINTER);

    q = p; q.damping = 1.5f;
    CHECK_EQ_INT(hf_rope_params_validate(&q, &d), HF_ERROR_BAD_PARAMETER);
    CHECK(strcmp(d.field, "damping") == 0);
    q = p; q.gravity[2] = (float)NAN;
    CHECK_EQ_INT(hf_rope_params_validate(&q, &d), HF_ERROR_NON_FINITE);
    CHECK(strcmp(d.field, "gravity") == 0);
    q = p; q.wind[0] = 2e4f;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_BAD_PARAMETER);
    q = p; q.substep = 1e-6f;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_BAD_PARAMETER);
    q = p; q.time_scale = -1.0f;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_BAD_PARAMETER);
    q = p; q.max_substeps = -1;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_BAD_PARAMETER);
    /* zero asks for the default: substep 0 is 1/60 s */
    q = p; q.substep = 0.0f;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_OK);
    q = p; q.iterations = -1;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_BAD_PARAMETER);
    q = p; q.solver = 7;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_BAD_PARAMETER);
    q = p; q.simd = HF_SIMD_AVX512 + 1;
    CHECK_EQ_INT(hf_rope_params_validate(&q, &d), HF_ERROR_BAD_PARAMETER);
    CHECK(strcmp(d.field, "simd") == 0);
    q = p; q.simd = -1;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_BAD_PARAMETER);
    q = p; q.simd = HF_SIMD_SCALAR;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_OK);
    q = p; q.global_stiffness_tip = -0.1f;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_BAD_PARAMETER);
    q = p; q.max_dt = (float)INFINITY;
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_ERROR_NON_FINITE);
    memset(&q, 0, sizeof q); /* a zeroed struct is the defaults */
    CHECK_EQ_INT(hf_rope_params_validate(&q, NULL), HF_OK);
}

static void test_ropes_memory_init_create(void)
{
    size_t size = 0, size2 = 0;
    unsigned char *mem;
    hf_ropes ro, before;
    hf_ropes *made = NULL;
    t_counter cnt;
    hf_allocator al = t_counting(&cnt);
    CHECK_EQ_INT(hf_ropes_memory_size(0, 16, &size), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_ropes_memory_size(4, 1, &size), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_ropes_memory_size(4, 16, NULL), HF_ERROR_NULL_POINTER);
    if (sizeof(size_t) == 8)
        CHECK_EQ_INT(hf_ropes_memory_size(0x7fffffff, 0x7fffffff, &size),
                     HF_ERROR_OVERFLOW);
    CHECK_EQ_INT(hf_ropes_memory_size(1000, 16, &size), HF_OK);
    /* 16 point rows (10 arrays and the glide's 6), 57 floats + 1 double +
       2 bytes per rope, padding */
    CHECK(size >= 1000u * 16u * 64u + 1000u * (57u * 4u + 10u));
    CHECK(size <= 1000u * 16u * 64u + 1000u * (57u * 4u + 10u) + 64u * 21u);
    CHECK_EQ_INT(hf_ropes_memory_size(3, 5, &size2), HF_OK);

    mem = (unsigned char *)malloc(size2 + 1);
    memset(&before, 0xab, sizeof before);
    ro = before;
    CHECK_EQ_INT(hf_ropes_init(&ro, 3, 5, mem + 1, size2 - 1),
                 HF_ERROR_BUFFER_TOO_SMALL);
    CHECK(memcmp(&ro, &before, sizeof ro) == 0);
    CHECK_EQ_INT(hf_ropes_init(&ro, 3, 5, NULL, size2),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_init(&ro, 3, 1, mem + 1, size2),
                 HF_ERROR_BAD_COUNT);
    CHECK(memcmp(&ro, &before, sizeof ro) == 0);
    /* any alignment of the memory; arrays come out 64-byte aligned */
    CHECK_EQ_INT(hf_ropes_init(&ro, 3, 5, mem + 1, size2), HF_OK);
    CHECK(((uintptr_t)ro.x & 63u) == 0 && ((uintptr_t)ro.pz & 63u) == 0);
    CHECK(((uintptr_t)ro.time & 7u) == 0);
    CHECK_EQ_INT(ro.rope_count, 3);
    CHECK_EQ_INT(ro.points, 5);
    CHECK(ro.x[14] == 0.0f && ro.mode[2] == HF_ROPE_SIMULATED);
    hf_ropes_destroy(&ro); /* not owned: must leave the memory alone */
    free(mem);

    CHECK_EQ_INT(hf_ropes_create(10, 8, &al, &made), HF_OK);
    CHECK(made != NULL);
    CHECK_EQ_INT(cnt.allocs, 1);
    if (made) {
        hf_rope_params p;
        hf_rope_params_init(&p);
        CHECK_EQ_INT(hf_ropes_step(made, 0, 10, 1.0f / 60.0f, &p, NULL, 0),
                     HF_OK);
        CHECK_EQ_INT(cnt.allocs, 1); /* the step allocates nothing */
        hf_ropes_destroy(made);
    }
    CHECK_EQ_INT(cnt.frees, 1);
    cnt.fail_after = 0;
    made = NULL;
    CHECK_EQ_INT(hf_ropes_create(10, 8, &al, &made), HF_ERROR_OUT_OF_MEMORY);
    CHECK(made == NULL);
}

/* A rope released horizontally swings down and settles, and FTL keeps it
   inextensible, with the default parameters. */
static void test_ropes_hanging_settles(void)
{
    enum { P = 17, FRAMES = 600 };
    const float root[3] = {0, 0, 0}, nrm[3] = {1, 0, 0}, tan[3] = {0, 0, 1};
    float rest[3 * P], a[3 * P], b[3 * P], st, worst = 0.0f;
    double ke, ke_peak = 0.0, ke_last_second = 0.0;
    hf_rope_params p;
    tr_set s;
    int f;
    if (!tr_open(&s, 1, P)) { CHECK(0); return; }
    hf_rope_params_init(&p);
    tr_straight(rest, 0, P, root, nrm, 0.3f);
    CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, 1, rest, 0, root, nrm, tan, 0),
                 HF_OK);
    tr_snapshot(&s.ro, a);
    for (f = 0; f < FRAMES; ++f) {
        memcpy(b, a, sizeof a);
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0),
                     HF_OK);
        tr_snapshot(&s.ro, a);
        ke = tr_kinetic(a, b, 1, P, 1.0 / 60.0);
        if (ke > ke_peak) ke_peak = ke;
        if (f >= FRAMES - 60 && ke > ke_last_second) ke_last_second = ke;
        hf_ropes_max_stretch(&s.ro, 0, 1, &st);
        if (st > worst) worst = st;
    }
    CHECK(ke_peak > 1.0);                      /* it really swung */
    CHECK(ke_last_second < 1e-6 * ke_peak);    /* and settled */
    CHECK(worst < 0.005f);                     /* the documented bound */
    CHECK(worst < 1e-4f);                      /* FTL does much better */
    /* hangs straight down from the root */
    CHECK_NEAR(a[3 * (P - 1) + 0], 0.0, 1e-3);
    CHECK_NEAR(a[3 * (P - 1) + 1], -0.3, 1e-3);
    CHECK(tr_finite(&s.ro));
    tr_close(&s);
}

/* Zero gravity and full global stiffness: the rope is its rest shape
   carried rigidly by a moving, turning root frame. */
static void test_ropes_shape_kept_by_moving_frame(void)
{
    enum { R = 3, P = 12, FRAMES = 90 };
    static float rest[3 * R * P], now[3 * R * P];
    float root0[3 * R], nrm0[3 * R], tan0[3 * R];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    double axis[3] = {1, 2, 3}, al = sqrt(14.0), worst = 0.0, control = 0.0;
    hf_rope_params p;
    tr_set s;
    int r, j, f, pass;
    axis[0] /= al; axis[1] /= al; axis[2] /= al;
    for (r = 0; r < R; ++r) {
        root0[3 * r] = 0.1f * r; root0[3 * r + 1] = 0.5f; root0[3 * r + 2] = 0;
        nrm0[3 * r] = 0; nrm0[3 * r + 1] = 1; nrm0[3 * r + 2] = 0;
        tan0[3 * r] = 1; tan0[3 * r + 1] = 0; tan0[3 * r + 2] = 0;
        for (j = 0; j < P; ++j) { /* a curl: a quarter helix */
            float t = (float)j / (P - 1);
            float *o = rest + 3 * (r * P + j);
            o[0] = root0[3 * r] + 0.05f * (1.0f - cosf(2.0f * t));
            o[1] = root0[3 * r + 1] + 0.2f * t;
            o[2] = root0[3 * r + 2] + 0.05f * sinf(2.0f * t) * (r + 1);
        }
    }
    for (pass = 0; pass < 2; ++pass) {
        if (!tr_open(&s, R, P)) { CHECK(0); return; }
        hf_rope_params_init(&p);
        p.gravity[1] = 0.0f;
        p.global_stiffness_root = p.global_stiffness_tip = pass ? 0.0f : 1.0f;
        CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root0, nrm0,
                                       tan0, 0),
                     HF_OK);
        for (f = 1; f <= FRAMES; ++f) {
            double ang = 0.05 * f, tt = f / 60.0;
            float off[3];
            off[0] = (float)(0.3 * sin(2 * T_PI * tt));
            off[1] = (float)(0.1 * tt);
            off[2] = (float)(-0.2 * tt);
            for (r = 0; r < R; ++r) {
                int k;
                for (k = 0; k < 3; ++k) root[3 * r + k] = root0[3 * r + k] + off[k];
                tr_rotate(axis, ang, nrm0 + 3 * r, nrm + 3 * r);
                tr_rotate(axis, ang, tan0 + 3 * r, tan + 3 * r);
            }
            CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0),
                         HF_OK);
            CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, NULL, 0),
                         HF_OK);
            tr_snapshot(&s.ro, now);
            for (r = 0; r < R; ++r)
                for (j = 0; j < P; ++j) {
                    float d[3], e[3];
                    const float *q = rest + 3 * (r * P + j);
                    const float *g = now + 3 * (r * P + j);
                    double err;
                    d[0] = q[0] - root0[3 * r];
                    d[1] = q[1] - root0[3 * r + 1];
                    d[2] = q[2] - root0[3 * r + 2];
                    tr_rotate(axis, ang, d, e);
                    err = sqrt(pow(g[0] - root[3 * r] - e[0], 2) +
                               pow(g[1] - root[3 * r + 1] - e[1], 2) +
                               pow(g[2] - root[3 * r + 2] - e[2], 2));
                    if (pass == 0 && err > worst) worst = err;
                    if (pass == 1 && err > control) control = err;
                }
        }
        CHECK(tr_finite(&s.ro));
        tr_close(&s);
    }
    CHECK(worst < 2e-5);    /* float rounding only */
    CHECK(control > 0.01);  /* without stiffness the shape is lost */
}

/* Two colliders swept through a bundle of hanging ropes: after every step
   no non-root point is inside either (with the margin). */
static void test_ropes_collider_sweep_never_penetrates(void)
{
    enum { G = 8, R = G * G, P = 17, FRAMES = 90 };
    static float rest[3 * R * P], now[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], worst_st = 0.0f, st;
    hf_collider col[2];
    hf_rope_params p;
    double worst = 1e9;
    long contacts = 0;
    tr_set s;
    int r, j, f, c;
    if (!tr_open(&s, R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        root[3 * r] = -0.1f + 0.2f * (r % G) / (G - 1);
        root[3 * r + 1] = 0.0f;
        root[3 * r + 2] = -0.1f + 0.2f * (r / G) / (G - 1);
        nrm[3 * r] = 0; nrm[3 * r + 1] = -1; nrm[3 * r + 2] = 0;
        tan[3 * r] = 1; tan[3 * r + 1] = 0; tan[3 * r + 2] = 0;
        tr_straight(rest, r, P, root + 3 * r, nrm + 3 * r, 0.3f);
    }
    CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0),
                 HF_OK);
    hf_rope_params_init(&p);
    memset(col, 0, sizeof col);
    col[0].type = HF_COLLIDER_SPHERE;
    col[0].radius = 0.05f;
    col[1].type = HF_COLLIDER_CAPSULE;
    col[1].radius = 0.02f;
    for (f = 0; f < FRAMES; ++f) {
        float t = (float)f / (FRAMES - 1);
        col[0].a[0] = -0.4f + 0.8f * t; /* left to right, low */
        col[0].a[1] = -0.22f;
        col[0].a[2] = 0.01f;
        col[1].a[0] = col[1].b[0] = 0.4f - 0.8f * t; /* right to left, high */
        col[1].a[1] = col[1].b[1] = -0.08f;
        col[1].a[2] = -0.3f;
        col[1].b[2] = 0.3f;
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, col, 2),
                     HF_OK);
        tr_snapshot(&s.ro, now);
        for (r = 0; r < R; ++r)
            for (j = 1; j < P; ++j)
                for (c = 0; c < 2; ++c) {
                    double d = tr_dist_seg(now + 3 * (r * P + j), col + c) -
                               col[c].radius;
                    if (d < worst) worst = d;
                    if (d < p.collision_margin * 1.01) ++contacts;
                }
        hf_ropes_max_stretch(&s.ro, 0, R, &st);
        if (st > worst_st) worst_st = st;
    }
    CHECK(contacts > 100);                        /* the sweep hit ropes */
    CHECK(worst >= p.collision_margin * 0.999);   /* and never got in */
    CHECK(worst_st < 0.05f);
    CHECK(tr_finite(&s.ro));
    tr_close(&s);
}

/* Animated -> simulated -> animated on a moving root: no particle moves in
   a frame by more than the motion of a frame. */
static void test_ropes_mode_switch_no_jump(void)
{
    enum { R = 4, P = 17, FRAMES = 120, ON = 30, OFF = 50 };
    static float rest[3 * R * P], a[3 * R * P], b[3 * R * P];
    float root[3 * R], root0[3 * R], nrm[3 * R], tan[3 * R];
    double move[FRAMES], gap = 0.0, anim_move = 0.0, sim_move = 0.0;
    hf_rope_params p;
    tr_set s;
    int r, f, j;
    if (!tr_open(&s, R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        root0[3 * r] = 0.05f * r; root0[3 * r + 1] = 0; root0[3 * r + 2] = 0;
        /* combed sideways: gravity hangs it a quarter turn off its rest */
        nrm[3 * r] = 1; nrm[3 * r + 1] = 0; nrm[3 * r + 2] = 0;
        tan[3 * r] = 0; tan[3 * r + 1] = 0; tan[3 * r + 2] = 1;
        tr_straight(rest, r, P, root0 + 3 * r, nrm + 3 * r, 0.3f);
    }
    hf_rope_params_init(&p);
    CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root0, nrm, tan, 0),
                 HF_OK);
    CHECK_EQ_INT(hf_ropes_set_mode(&s.ro, 0, R, HF_ROPE_ANIMATED), HF_OK);
    CHECK_EQ_INT(hf_ropes_set_mode(&s.ro, 0, R, 3),
                 HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_ropes_reset(&s.ro, 0, R), HF_OK);
    tr_snapshot(&s.ro, a);
    for (f = 0; f < FRAMES; ++f) {
        double tt = (f + 1) / 60.0;
        if (f == ON) hf_ropes_set_mode(&s.ro, 0, R, HF_ROPE_SIMULATED);
        if (f == OFF) {
            /* how far the simulated rope is from its animated pose: what a
               naive switch would jump */
            for (r = 0; r < R; ++r)
                for (j = 0; j < P; ++j) {
                    const float *q = a + 3 * (r * P + j);
                    double dx = q[0] - (root[3 * r] + 0.3 * j / (P - 1)),
                           dy = q[1] - root[3 * r + 1],
                           dz = q[2] - root[3 * r + 2];
                    double d = sqrt(dx * dx + dy * dy + dz * dz);
                    if (d > gap) gap = d;
                }
            hf_ropes_set_mode(&s.ro, 0, R, HF_ROPE_ANIMATED);
        }
        for (r = 0; r < R; ++r) {
            root[3 * r] = root0[3 * r];
            root[3 * r + 1] = root0[3 * r + 1];
            root[3 * r + 2] = root0[3 * r + 2] + (float)(0.1 * sin(2 * T_PI * tt));
        }
        hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0);
        memcpy(b, a, sizeof a);
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, NULL, 0),
                     HF_OK);
        tr_snapshot(&s.ro, a);
        move[f] = tr_max_move(a, b, (size_t)R * P);
        if (f < ON && move[f] > anim_move) anim_move = move[f];
        if (f > ON && f < OFF && move[f] > sim_move) sim_move = move[f];
    }
    /* the first simulated frame continues the animated motion: it moves no
       more than an animated frame, plus what gravity adds in one frame */
    CHECK(move[ON] <= anim_move * 1.02 + 9.81 / 3600.0);
    /* switching back glides along a Hermite curve: in the root frame no
       faster than 1.5 gap / blend_time plus the speed it had, so a frame
       moves at most that plus the frame's own motion (the animated one) */
    for (f = OFF; f < FRAMES; ++f)
        CHECK(move[f] <= (sim_move + anim_move + 1.5 * gap / 15.0) * 1.02);
    /* the test is meaningful: a jump to the animated pose is far bigger */
    CHECK(gap > 2.0 * sim_move);
    if (getenv("TR_VERBOSE")) {
        printf("anim_move %g sim_move %g gap %g move[ON] %g\n", anim_move,
               sim_move, gap, move[ON]);
        for (f = OFF - 2; f < OFF + 20; ++f) printf("  move[%d] = %g\n", f, move[f]);
    }
    /* and the glide ended: back on the animated pose */
    for (r = 0; r < R; ++r)
        for (j = 0; j < P; ++j) {
            const float *q = a + 3 * (r * P + j);
            CHECK_NEAR(q[0], root[3 * r] + 0.3 * j / (P - 1), 1e-5);
            CHECK_NEAR(q[2], root[3 * r + 2], 1e-5);
        }
    tr_close(&s);
}

/* The largest change of velocity (m/s) of any point across frame k of a
   swinging rope set stepped at dt, switched at frames on (to simulated),
   off (to animated) and back (to simulated, mid-glide); -1 on failure. */
static double tr_switch_dv(float dt, int on, int off, int back, int which)
{
    enum { R = 3, P = 12 };
    static float rest[3 * R * P], x0[3 * R * P], x1[3 * R * P],
        x2[3 * R * P];
    float root[3 * R], root0[3 * R], nrm[3 * R], tan[3 * R];
    hf_rope_params p;
    tr_set s;
    int r, f, i, k = which == 0 ? on : which == 1 ? off : which == 2 ? back : which;
    double dv = 0.0;
    if (!tr_open(&s, R, P)) return -1.0;
    for (r = 0; r < R; ++r) {
        root0[3 * r] = 0.05f * r; root0[3 * r + 1] = 0; root0[3 * r + 2] = 0;
        /* combed sideways: gravity hangs it a quarter turn off its rest
           pose, the gap the glide must close */
        nrm[3 * r] = 1; nrm[3 * r + 1] = 0; nrm[3 * r + 2] = 0;
        tan[3 * r] = 0; tan[3 * r + 1] = 0; tan[3 * r + 2] = 1;
        tr_straight(rest, r, P, root0 + 3 * r, nrm + 3 * r, 0.3f);
    }
    hf_rope_params_init(&p);
    hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root0, nrm, tan, 0);
    hf_ropes_set_mode(&s.ro, 0, R, HF_ROPE_ANIMATED);
    hf_ropes_reset(&s.ro, 0, R);
    for (f = 0; f <= k; ++f) {
        double tt = (f + 1) * (double)dt;
        if (f == on || f == back)
            hf_ropes_set_mode(&s.ro, 0, R, HF_ROPE_SIMULATED);
        if (f == off) hf_ropes_set_mode(&s.ro, 0, R, HF_ROPE_ANIMATED);
        for (r = 0; r < R; ++r) {
            root[3 * r] = root0[3 * r];
            root[3 * r + 1] = root0[3 * r + 1];
            root[3 * r + 2] = root0[3 * r + 2] + (float)(0.02 * sin(T_PI * tt));
        }
        hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0);
        memcpy(x0, x1, sizeof x1);
        memcpy(x1, x2, sizeof x2);
        if (hf_ropes_step(&s.ro, 0, R, dt, &p, NULL, 0) != HF_OK) dv = -1.0;
        tr_snapshot(&s.ro, x2);
    }
    /* x0, x1, x2: after frames k - 2, k - 1 and k, the first after the
       switch */
    for (i = 0; i < 3 * R * P && dv >= 0.0; i += 3) {
        double d2 = 0.0, c;
        int c3;
        for (c3 = 0; c3 < 3; ++c3) {
            c = (double)x2[i + c3] - 2.0 * x1[i + c3] + x0[i + c3];
            d2 += c * c;
        }
        if (sqrt(d2) / dt > dv) dv = sqrt(d2) / dt;
    }
    tr_close(&s);
    return dv;
}

/* Mode switches keep the velocity: the change of velocity across a switch
   is an acceleration times the frame time, so it shrinks with the frame
   time (a jump in velocity would not). Checked at 60 and 480 Hz, for the
   switch to simulation, to animation (the glide) and back mid-glide. */
static void test_ropes_mode_switch_smooth(void)
{
    int which;
    for (which = 0; which < 3; ++which) {
        /* the same moments in seconds: 0.5 s, 1.0 s, 1.1 s */
        double slow = tr_switch_dv(1.0f / 60.0f, 15, 120, 126, which);
        double fast = tr_switch_dv(1.0f / 480.0f, 120, 960, 1008, which);
        if (getenv("TR_VERBOSE"))
            printf("switch %d: dv %g m/s at 60 Hz, %g at 480 Hz\n", which,
                   slow, fast);
        CHECK(slow >= 0.0 && fast >= 0.0);
        CHECK(fast < 0.3 * slow);
    }
}

/* dt zero, negative, NaN, infinite: an error and no change; dt of a second:
   clamped to max_dt, the same bytes as a step of max_dt; never a NaN. */
static void test_ropes_bad_time_steps(void)
{
    enum { R = 5, P = 9 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    const float bad[4] = {0.0f, -1.0f / 60.0f, (float)NAN, (float)INFINITY};
    hf_rope_params p;
    tr_set s, t;
    unsigned char *copy;
    int r, i, f;
    if (!tr_open(&s, R, P) || !tr_open(&t, R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        root[3 * r] = (float)r; root[3 * r + 1] = 1; root[3 * r + 2] = 0;
        nrm[3 * r] = 1; nrm[3 * r + 1] = 0; nrm[3 * r + 2] = 0;
        tan[3 * r] = 0; tan[3 * r + 1] = 0; tan[3 * r + 2] = 1;
        tr_straight(rest, r, P, root + 3 * r, nrm + 3 * r, 0.25f);
    }
    hf_rope_params_init(&p);
    hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0);
    hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, NULL, 0); /* in motion */
    copy = (unsigned char *)malloc(s.size);
    memcpy(copy, s.mem, s.size);
    for (i = 0; i < 4; ++i) {
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, bad[i], &p, NULL, 0),
                     HF_ERROR_BAD_TIME_STEP);
        CHECK(memcmp(copy, s.mem, s.size) == 0);
    }
    /* same start in t, then one second vs max_dt */
    hf_ropes_set_rest(&t.ro, 0, R, rest, 0, root, nrm, tan, 0);
    hf_ropes_step(&t.ro, 0, R, 1.0f / 60.0f, &p, NULL, 0);
    for (f = 0; f < 20; ++f) {
        root[0] += 1.0f; /* a big jump of rope 0's root every frame */
        hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0);
        hf_ropes_set_roots(&t.ro, 0, R, root, nrm, tan, 0);
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f, &p, NULL, 0), HF_OK);
        CHECK_EQ_INT(hf_ropes_step(&t.ro, 0, R, p.max_dt, &p, NULL, 0),
                     HF_OK);
    }
    CHECK(memcmp(s.ro.x, t.ro.x, sizeof(float) * R * P) == 0);
    CHECK(memcmp(s.ro.py, t.ro.py, sizeof(float) * R * P) == 0);
    CHECK(tr_finite(&s.ro));
    /* a tiny step and a huge time scale stay finite */
    p.time_scale = 100.0f;
    CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1e-7f, &p, NULL, 0), HF_OK);
    CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f, &p, NULL, 0), HF_OK);
    CHECK(tr_finite(&s.ro));
    free(copy);
    tr_close(&s);
    tr_close(&t);
}

/* Everything on (turbulence, wind, shape, colliders, mixed modes): any
   split into ranges, in any order, gives the same bytes. */
static void test_ropes_ranges_byte_identical(void)
{
    enum { R = 37, P = 11, FRAMES = 60 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    const int cuts[] = {0, 5, 6, 6, 20, 37};
    hf_collider col[2];
    hf_rope_params p;
    tr_set s[3];
    int r, f, k, i, same = 1;
    for (k = 0; k < 3; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        float a = 0.3f * r;
        root[3 * r] = 0.1f * cosf(a); root[3 * r + 1] = 0.0f;
        root[3 * r + 2] = 0.1f * sinf(a);
        nrm[3 * r] = cosf(a); nrm[3 * r + 1] = 0.3f; nrm[3 * r + 2] = sinf(a);
        tan[3 * r] = 0; tan[3 * r + 1] = 1; tan[3 * r + 2] = 0;
        tr_straight(rest, r, P, root + 3 * r, nrm + 3 * r, 0.2f);
    }
    hf_rope_params_init(&p);
    p.wind[0] = 3.0f;
    p.turbulence = 5.0f;
    p.turbulence_frequency = 2.0f;
    p.global_stiffness_root = 0.2f;
    p.local_stiffness_root = 0.5f;
    p.local_stiffness_tip = 0.1f;
    p.root_stiffness = 0.5f;
    memset(col, 0, sizeof col);
    col[0].type = HF_COLLIDER_SPHERE;
    col[0].radius = 0.1f;
    col[1].type = HF_COLLIDER_CAPSULE;
    col[1].radius = 0.03f;
    for (k = 0; k < 3; ++k) {
        hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
        hf_ropes_set_mode(&s[k].ro, 10, 7, HF_ROPE_ANIMATED);
    }
    for (f = 0; f < FRAMES; ++f) {
        double tt = f / 60.0;
        for (r = 0; r < R; ++r) root[3 * r + 1] = (float)(0.05 * sin(7 * tt));
        col[1].a[0] = 0.3f; col[1].a[1] = -0.25f; col[1].a[2] = -0.3f;
        col[1].b[0] = -0.3f; col[1].b[1] = -0.25f; col[1].b[2] = 0.3f;
        col[1].a[1] += (float)(0.1 * sin(3 * tt));
        for (k = 0; k < 3; ++k) {
            if (f == 20) hf_ropes_set_mode(&s[k].ro, 12, 3, HF_ROPE_SIMULATED);
            if (f == 25) hf_ropes_set_mode(&s[k].ro, 30, 5, HF_ROPE_ANIMATED);
            if (f == 40) hf_ropes_reset(&s[k].ro, 2, 2);
        }
        /* s0: all at once */
        hf_ropes_set_roots(&s[0].ro, 0, R, root, nrm, tan, 0);
        CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, R, 1.0f / 60.0f, &p, col, 2),
                     HF_OK);
        /* s1: uneven ranges, including an empty one */
        for (i = 0; i + 1 < (int)(sizeof cuts / sizeof cuts[0]); ++i) {
            hf_ropes_set_roots(&s[1].ro, cuts[i], cuts[i + 1] - cuts[i], root,
                               nrm, tan, 0);
            CHECK_EQ_INT(hf_ropes_step(&s[1].ro, cuts[i], cuts[i + 1] - cuts[i],
                                       1.0f / 60.0f, &p, col, 2),
                         HF_OK);
        }
        /* s2: one rope at a time, backwards */
        for (r = R - 1; r >= 0; --r) {
            hf_ropes_set_roots(&s[2].ro, r, 1, root, nrm, tan, 0);
            hf_ropes_step(&s[2].ro, r, 1, 1.0f / 60.0f, &p, col, 2);
        }
        for (k = 1; k < 3; ++k) {
            same &= tr_same(&s[0].ro, &s[k].ro, 1);
            same &= memcmp(s[0].ro.blend, s[k].ro.blend, 4 * R) == 0;
            same &= memcmp(s[0].ro.time, s[k].ro.time, 8 * R) == 0;
        }
    }
    CHECK(same);
    CHECK(tr_finite(&s[0].ro));
    CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 30, 8, 0.01f, &p, col, 2),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_step(&s[0].ro, -1, 2, 0.01f, &p, col, 2),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, 2, 0.01f, &p, NULL, 2),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, 2, 0.01f, &p, col, -1),
                 HF_ERROR_BAD_COUNT);
    col[0].radius = -1.0f;
    CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, 2, 0.01f, &p, col, 2),
                 HF_ERROR_BAD_PARAMETER);
    col[0].radius = (float)NAN;
    CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, 2, 0.01f, &p, col, 2),
                 HF_ERROR_NON_FINITE);
    for (k = 0; k < 3; ++k) tr_close(&s[k]);
}

/* Ropes step in chunks of 256 (hf__ropes_sim_run), each with its
   broadphase: ranges that cut the chunks elsewhere give, at both solvers
   and every level, with a collider and a capsule, the same bytes as one
   call on every rope. */
static void test_ropes_chunks_byte_identical(void)
{
    enum { R = 300, P = 9, FRAMES = 30 };
    static float rest[3 * R * P];
    static float root[3 * R], nrm[3 * R], tan[3 * R];
    /* 129 and 171 ropes; 200 beside 1 and 99 (one call: 256 and 44) */
    const int cuts[2][4] = {{0, 129, 300, 300}, {0, 200, 201, 300}};
    hf_collider col[2];
    hf_rope_params p;
    tr_set s[3];
    int r, f, k, i, lv, ftl, same = 1;
    for (k = 0; k < 3; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        const float a = 0.05f * r;
        root[3 * r] = 0.1f * cosf(a); root[3 * r + 1] = 0.001f * r;
        root[3 * r + 2] = 0.1f * sinf(a);
        nrm[3 * r] = cosf(a); nrm[3 * r + 1] = 0.3f; nrm[3 * r + 2] = sinf(a);
        tan[3 * r] = 0; tan[3 * r + 1] = 1; tan[3 * r + 2] = 0;
        tr_straight(rest, r, P, root + 3 * r, nrm + 3 * r, 0.2f);
    }
    memset(col, 0, sizeof col);
    col[0].type = HF_COLLIDER_SPHERE;
    col[0].radius = 0.1f;
    col[1].type = HF_COLLIDER_CAPSULE;
    col[1].radius = 0.03f;
    col[1].a[0] = 0.3f; col[1].a[1] = -0.1f;
    col[1].b[0] = -0.3f; col[1].b[1] = -0.1f; col[1].b[2] = 0.2f;
    for (lv = HF_SIMD_SCALAR; lv <= HF_SIMD_AVX512; ++lv)
        for (ftl = 0; ftl < 2; ++ftl) {
            hf_rope_params_init(&p);
            p.wind[0] = 3.0f;
            p.local_stiffness_root = 0.5f;
            p.solver = ftl ? HF_ROPE_SOLVER_FTL : HF_ROPE_SOLVER_DISTANCE;
            p.simd = lv;
            for (k = 0; k < 3; ++k)
                hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
            for (f = 0; f < FRAMES; ++f)
                for (k = 0; k < 3; ++k) {
                    if (k == 0) {
                        CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, R, 1.0f / 60,
                                                   &p, col, 2),
                                     HF_OK);
                        continue;
                    }
                    for (i = 0; i < 3; ++i)
                        hf_ropes_step(&s[k].ro, cuts[k - 1][i],
                                      cuts[k - 1][i + 1] - cuts[k - 1][i],
                                      1.0f / 60, &p, col, 2);
                }
            for (k = 1; k < 3; ++k) same &= tr_same(&s[0].ro, &s[k].ro, 1);
        }
    CHECK(same);
    CHECK(tr_finite(&s[0].ro));
    for (k = 0; k < 3; ++k) tr_close(&s[k]);
}

/* Root frame input: bad values refused with nothing written; a tangent
   parallel to the normal, or zero, still gives a rigid frame. */
static void test_ropes_root_frames(void)
{
    enum { R = 2, P = 4 };
    float rest[3 * R * P], root[3 * R], nrm[3 * R], tan[3 * R], got[3 * R * P];
    unsigned char *copy;
    tr_set s;
    int r, i, j;
    if (!tr_open(&s, R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        root[3 * r] = 1.0f; root[3 * r + 1] = 2.0f; root[3 * r + 2] = 3.0f;
        nrm[3 * r] = 0; nrm[3 * r + 1] = 0; nrm[3 * r + 2] = 2; /* not unit */
        tan[3 * r] = 1; tan[3 * r + 1] = 0; tan[3 * r + 2] = 1; /* not perp. */
        for (j = 0; j < P; ++j) { /* a bent rest pose */
            rest[3 * (r * P + j)] = 1.0f + 0.1f * j * j;
            rest[3 * (r * P + j) + 1] = 2.0f + 0.05f * j;
            rest[3 * (r * P + j) + 2] = 3.0f + 0.1f * j;
        }
    }
    CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0),
                 HF_OK);
    /* the rest pose comes back as given (frame then inverse frame) */
    tr_snapshot(&s.ro, got);
    for (i = 0; i < 3 * R * P; ++i) CHECK_NEAR(got[i], rest[i], 2e-6);
    /* rope 0: u along the tangent made perpendicular: (1, 0, 0) */
    CHECK_NEAR(s.ro.rest_u[2 * R], 0.4f, 1e-6);
    CHECK_NEAR(s.ro.rest_v[2 * R], 0.2f, 1e-6);  /* along the normal z */
    CHECK_NEAR(s.ro.rest_w[2 * R], -0.1f, 1e-6); /* b = t x n = -y */
    CHECK_NEAR(s.ro.rest_length[0], sqrt(0.01 + 0.0025 + 0.01), 1e-7);

    copy = (unsigned char *)malloc(s.size);
    memcpy(copy, s.mem, s.size);
    nrm[3] = nrm[4] = nrm[5] = 0.0f;
    CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0),
                 HF_ERROR_DEGENERATE);
    nrm[5] = 1.0f;
    tan[0] = (float)NAN;
    CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0),
                 HF_ERROR_NON_FINITE);
    tan[0] = 1.0f;
    root[4] = 2e6f;
    CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0),
                 HF_ERROR_BAD_PARAMETER);
    root[4] = 2.0f;
    CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 8),
                 HF_ERROR_BAD_STRIDE);
    CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 1, 2, root, nrm, tan, 0),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 0, R, NULL, nrm, tan, 0),
                 HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_set_roots(NULL, 0, R, root, nrm, tan, 0),
                 HF_ERROR_NULL_POINTER);
    rest[7] = (float)NAN;
    CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0),
                 HF_ERROR_NON_FINITE);
    rest[7] = 2.0f + 0.05f * 2;
    CHECK(memcmp(copy, s.mem, s.size) == 0);
    free(copy);

    /* degenerate tangents: parallel to the normal (rope 0), zero (rope 1);
       a huge normal (no overflow) */
    tan[0] = 0; tan[1] = 0; tan[2] = -5;
    tan[3] = 0; tan[4] = 0; tan[5] = 0;
    nrm[0] = 0; nrm[1] = 0; nrm[2] = 3e38f;
    CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0), HF_OK);
    CHECK_EQ_INT(hf_ropes_reset(&s.ro, 0, R), HF_OK);
    tr_snapshot(&s.ro, got);
    for (r = 0; r < R; ++r)
        for (i = 0; i < P; ++i)
            for (j = 0; j < P; ++j) { /* rigid: all distances kept */
                const float *a = got + 3 * (r * P + i), *b = got + 3 * (r * P + j);
                const float *c = rest + 3 * (i), *d = rest + 3 * (j);
                double g = sqrt(pow(a[0] - b[0], 2) + pow(a[1] - b[1], 2) +
                                pow(a[2] - b[2], 2));
                double e = sqrt(pow(c[0] - d[0], 2) + pow(c[1] - d[1], 2) +
                                pow(c[2] - d[2], 2));
                CHECK_NEAR(g, e, 1e-5);
            }
    for (r = 0; r < R; ++r) /* v (0.05 j after the scaled normal) along z */
        CHECK_NEAR(got[3 * (r * P + 3) + 2] - 3.0f, s.ro.rest_v[3 * R + r],
                   1e-6);
    tr_close(&s);
}

/* Reset after a teleport: rest pose at the new root, at rest. */
static void test_ropes_reset_teleport(void)
{
    enum { P = 9 };
    float rest[3 * P], a[3 * P], b[3 * P];
    float root[3] = {0, 0, 0}, nrm[3] = {1, 0, 0}, tan[3] = {0, 1, 0};
    hf_rope_params p;
    tr_set s;
    int f, j;
    if (!tr_open(&s, 1, P)) { CHECK(0); return; }
    tr_straight(rest, 0, P, root, nrm, 0.4f);
    hf_ropes_set_rest(&s.ro, 0, 1, rest, 0, root, nrm, tan, 0);
    hf_rope_params_init(&p);
    for (f = 0; f < 30; ++f) hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0);
    root[0] = 10.0f; root[2] = -4.0f;
    hf_ropes_set_roots(&s.ro, 0, 1, root, nrm, tan, 0);
    CHECK_EQ_INT(hf_ropes_reset(&s.ro, 0, 1), HF_OK);
    CHECK_EQ_INT(hf_ropes_reset(&s.ro, 1, 1), HF_ERROR_BAD_RANGE);
    tr_snapshot(&s.ro, a);
    for (j = 0; j < P; ++j) {
        CHECK_NEAR(a[3 * j], 10.0 + 0.4 * j / (P - 1), 1e-6);
        CHECK_NEAR(a[3 * j + 1], 0.0, 1e-6);
        CHECK_NEAR(a[3 * j + 2], -4.0, 1e-6);
    }
    /* no velocity and no interpolation from the old root: a weightless
       step leaves it in place */
    p.gravity[1] = 0.0f;
    p.explicit_zero = HF_ROPE_ZERO_GRAVITY;
    hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0);
    tr_snapshot(&s.ro, b);
    if (getenv("TR_VERBOSE")) printf("teleport move %g\n", tr_max_move(a, b, P));
    CHECK(tr_max_move(a, b, P) < 1e-5); /* float rounding at 10 m */
    tr_close(&s);
}

/* Root and local stiffness make fur stand up against gravity. */
static void test_ropes_root_and_local_stiffness(void)
{
    enum { P = 13 };
    float rest[3 * P], a[3 * P];
    float root[3] = {0, 0, 0}, nrm[3] = {0, 1, 0}, tan[3] = {1, 0, 0};
    double first_dir[3], tip_err[3];
    hf_rope_params p;
    tr_set s;
    int pass, f;
    tr_straight(rest, 0, P, root, nrm, 0.1f);
    for (pass = 0; pass < 3; ++pass) {
        if (!tr_open(&s, 1, P)) { CHECK(0); return; }
        hf_ropes_set_rest(&s.ro, 0, 1, rest, 0, root, nrm, tan, 0);
        hf_rope_params_init(&p);
        p.root_stiffness = pass >= 1 ? 1.0f : 0.0f;
        p.local_stiffness_root = p.local_stiffness_tip = pass == 2 ? 1.0f : 0.0f;
        for (f = 0; f < 120; ++f) {
            /* a small sideways nudge so nothing balances by symmetry */
            p.wind[0] = f < 10 ? 1.0f : 0.0f;
            hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0);
        }
        tr_snapshot(&s.ro, a);
        first_dir[pass] = (a[4] - a[1]) / (0.1 / (P - 1));
        tip_err[pass] = sqrt(pow(a[3 * (P - 1)], 2) +
                             pow(a[3 * (P - 1) + 1] - 0.1, 2) +
                             pow(a[3 * (P - 1) + 2], 2));
        tr_close(&s);
    }
    CHECK(first_dir[0] < 0.0);       /* no stiffness: it flops over */
    CHECK(first_dir[1] > 0.9999);    /* root stiffness: first segment up */
    CHECK(tip_err[1] > 0.02);        /*   but the rest droops */
    CHECK(first_dir[2] > 0.9999);    /* plus local stiffness: */
    CHECK(tip_err[2] < 1e-4);        /*   the whole strand stands */
}

/* Shape stiffness that cannot hold a rope up: released from its straight
   rest pose, rising at an angle, the rope sags under gravity and comes to
   rest within 5 s (every point under 1 mm/s over the last second), with
   the bench's scene V settings (global 0.2, local 0.3, root 0.5; 0.3 m)
   and the Wuson demo's (global 0.4 to 0.2, local 0.3 to 0.05, root 0.5;
   0.3 m and 8 cm fur). Follow-the-leader's velocity correction used to
   push each parent back along its compressed child segment, a load that
   turns with the segment, and such ropes fluttered for ever at 0.05-0.6
   m/s. */
static void test_ropes_shape_stiffness_settles(void)
{
    static const struct {
        float gr, gt, lr, lt, angle, length;
        int points;
    } cs[] = {{0.2f, 0.0f, 0.3f, 0.0f, 30.0f, 0.3f, 32},
              {0.2f, 0.0f, 0.3f, 0.0f, 60.0f, 0.3f, 32},
              {0.2f, 0.0f, 0.3f, 0.0f, 135.0f, 0.3f, 32},
              {0.4f, 0.2f, 0.3f, 0.05f, 60.0f, 0.3f, 32},
              {0.4f, 0.2f, 0.3f, 0.05f, 60.0f, 0.08f, 16},
              {0.4f, 0.2f, 0.3f, 0.05f, 30.0f, 0.08f, 16}};
    enum { FRAMES = 300, PMAX = 32 };
    float rest[3 * PMAX], a[3 * PMAX], b[3 * PMAX], st;
    const float root[3] = {0, 0, 0}, tan[3] = {0, 0, 1};
    hf_rope_params p;
    tr_set s;
    size_t c;
    for (c = 0; c < sizeof cs / sizeof cs[0]; ++c) {
        const int P = cs[c].points;
        const double ang = cs[c].angle * T_PI / 180.0;
        float nrm[3], worst = 0.0f;
        double peak = 0.0, last = 0.0;
        int f;
        nrm[0] = (float)cos(ang);
        nrm[1] = (float)sin(ang);
        nrm[2] = 0.0f;
        if (!tr_open(&s, 1, P)) { CHECK(0); return; }
        tr_straight(rest, 0, P, root, nrm, cs[c].length);
        CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, 1, rest, 0, root, nrm, tan, 0),
                     HF_OK);
        hf_rope_params_init(&p);
        p.root_stiffness = 0.5f;
        p.global_stiffness_root = cs[c].gr;
        p.global_stiffness_tip = cs[c].gt;
        p.local_stiffness_root = cs[c].lr;
        p.local_stiffness_tip = cs[c].lt;
        tr_snapshot(&s.ro, a);
        for (f = 0; f < FRAMES; ++f) {
            double v;
            memcpy(b, a, sizeof a);
            CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0),
                         HF_OK);
            tr_snapshot(&s.ro, a);
            v = tr_max_move(a, b, (size_t)P) * 60.0;
            if (v > peak) peak = v;
            if (f >= FRAMES - 60 && v > last) last = v;
            hf_ropes_max_stretch(&s.ro, 0, 1, &st);
            if (st > worst) worst = st;
        }
        if (getenv("TR_VERBOSE"))
            printf("  shape settles: case %d: peak %.3g m/s, last second "
                   "%.3g m/s, stretch %.3g\n",
                   (int)c, peak, last, (double)worst);
        CHECK(peak > 0.05);  /* it sagged: the stiffness cannot hold it */
        CHECK(last < 1e-3);  /* and came to rest */
        CHECK(worst < 1e-4);
        CHECK(tr_finite(&s.ro));
        tr_close(&s);
    }
}

/* A head (sphere, r = 0.1 m) swinging 0.2 m at 1 Hz with 16-segment 0.3 m
   ropes on it: stretch stays below 0.5 % and no point enters the head. */
static void test_ropes_swinging_head(void)
{
    enum { RING = 8, ROWS = 4, R = RING * ROWS, P = 17, FRAMES = 300 };
    static float rest[3 * R * P], now[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], dirs[3 * R], worst = 0, st;
    double inside = 1e9;
    hf_collider head;
    hf_rope_params p;
    tr_set s;
    int r, f, j;
    if (!tr_open(&s, R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        double el = 0.3 + 1.2 * (r / RING) / (ROWS - 1) * 0.9; /* from top */
        double az = 2 * T_PI * (r % RING) / RING;
        tr_on_head(r, el, az, dirs, nrm, tan, root);
        tr_straight(rest, r, P, root + 3 * r, dirs + 3 * r, 0.3f);
    }
    hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0);
    hf_rope_params_init(&p);
    memset(&head, 0, sizeof head);
    head.type = HF_COLLIDER_SPHERE;
    head.radius = 0.1f;
    for (f = 0; f < FRAMES; ++f) {
        float cx = (float)(0.2 * sin(2 * T_PI * (f + 1) / 60.0));
        head.a[0] = cx;
        for (r = 0; r < R; ++r) root[3 * r] = cx + 0.1f * dirs[3 * r];
        hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0);
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, &head, 1),
                     HF_OK);
        hf_ropes_max_stretch(&s.ro, 0, R, &st);
        if (st > worst) worst = st;
        tr_snapshot(&s.ro, now);
        for (r = 0; r < R; ++r)
            for (j = 1; j < P; ++j) {
                double d = tr_dist_seg(now + 3 * (r * P + j), &head);
                if (d < inside) inside = d;
            }
    }
    CHECK(worst < 0.005f);
    CHECK(inside >= 0.1 + p.collision_margin * 0.999);
    tr_close(&s);
}

/* Stretch measurement: exact on a hand-made stretch. */
static void test_ropes_max_stretch_exact(void)
{
    enum { R = 2, P = 5 };
    float rest[3 * R * P], root[3 * R], nrm[3 * R], tan[3 * R], st = -1.0f;
    tr_set s;
    int r;
    if (!tr_open(&s, R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        root[3 * r] = 0; root[3 * r + 1] = (float)r; root[3 * r + 2] = 0;
        nrm[3 * r] = 1; nrm[3 * r + 1] = 0; nrm[3 * r + 2] = 0;
        tan[3 * r] = 0; tan[3 * r + 1] = 1; tan[3 * r + 2] = 0;
        tr_straight(rest, r, P, root + 3 * r, nrm + 3 * r, 0.4f);
    }
    hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0);
    s.ro.x[(P - 1) * R + 1] += 0.01f; /* last segment of rope 1: 0.11 m */
    s.ro.x[2 * R + 0] -= 0.02f;       /* rope 0: 0.08 and 0.12 m */
    CHECK_EQ_INT(hf_ropes_max_stretch(&s.ro, 1, 1, &st), HF_OK);
    CHECK_NEAR(st, 0.1, 1e-5);
    CHECK_EQ_INT(hf_ropes_max_stretch(&s.ro, 0, 1, &st), HF_OK);
    CHECK_NEAR(st, 0.2, 1e-5);
    CHECK_EQ_INT(hf_ropes_max_stretch(&s.ro, 0, 2, &st), HF_OK);
    CHECK_NEAR(st, 0.2, 1e-5);
    CHECK_EQ_INT(hf_ropes_max_stretch(&s.ro, 2, 0, &st), HF_OK);
    CHECK(st == 0.0f);
    st = 5.0f;
    CHECK_EQ_INT(hf_ropes_max_stretch(&s.ro, 1, 2, &st), HF_ERROR_BAD_RANGE);
    CHECK(st == 5.0f);
    CHECK_EQ_INT(hf_ropes_max_stretch(&s.ro, 0, 1, NULL),
                 HF_ERROR_NULL_POINTER);
    tr_close(&s);
}

/* Wind as an acceleration: the rope settles along gravity + wind;
   turbulence moves it, deterministically. */
static void test_ropes_wind_and_turbulence(void)
{
    enum { P = 9 };
    float rest[3 * P], a[3 * P], b[3 * P], c[3 * P];
    float root[3] = {0, 0, 0}, nrm[3] = {0, -1, 0}, tan[3] = {1, 0, 0};
    hf_rope_params p;
    tr_set s;
    int f, pass;
    double dx, dy, l;
    tr_straight(rest, 0, P, root, nrm, 0.2f);
    for (pass = 0; pass < 3; ++pass) {
        if (!tr_open(&s, 1, P)) { CHECK(0); return; }
        hf_ropes_set_rest(&s.ro, 0, 1, rest, 0, root, nrm, tan, 0);
        hf_rope_params_init(&p);
        p.wind[0] = 9.81f;
        if (pass > 0) p.turbulence = 10.0f;
        for (f = 0; f < 600; ++f)
            hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0);
        tr_snapshot(&s.ro, pass == 0 ? a : pass == 1 ? b : c);
        CHECK(tr_finite(&s.ro));
        tr_close(&s);
    }
    dx = a[3 * (P - 1)];
    dy = a[3 * (P - 1) + 1];
    l = sqrt(dx * dx + dy * dy);
    CHECK_NEAR(dx / l, sqrt(0.5), 1e-3);
    CHECK_NEAR(dy / l, -sqrt(0.5), 1e-3);
    CHECK(tr_max_move(a, b, P) > 1e-3);      /* turbulence does something */
    CHECK(memcmp(b, c, sizeof b) == 0);      /* the same twice */
}

/* Plain distance constraints: stretch falls with iterations; FTL is
   exact. */
static void test_ropes_distance_solver_iterations(void)
{
    enum { P = 17 };
    const int iters[3] = {1, 8, 2};
    float rest[3 * P], worst[3];
    float root[3] = {0, 0, 0}, nrm[3] = {1, 0, 0}, tan[3] = {0, 0, 1};
    hf_rope_params p;
    tr_set s;
    int pass, f;
    tr_straight(rest, 0, P, root, nrm, 0.3f);
    for (pass = 0; pass < 3; ++pass) {
        if (!tr_open(&s, 1, P)) { CHECK(0); return; }
        hf_ropes_set_rest(&s.ro, 0, 1, rest, 0, root, nrm, tan, 0);
        hf_rope_params_init(&p);
        p.solver = pass < 2 ? HF_ROPE_SOLVER_DISTANCE : HF_ROPE_SOLVER_FTL;
        p.iterations = iters[pass];
        worst[pass] = 0.0f;
        for (f = 0; f < 120; ++f) {
            float st;
            hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0);
            hf_ropes_max_stretch(&s.ro, 0, 1, &st);
            if (st > worst[pass]) worst[pass] = st;
        }
        CHECK(tr_finite(&s.ro));
        tr_close(&s);
    }
    CHECK(worst[0] > 0.01f);            /* one sweep: visibly stretchy */
    CHECK(worst[1] < worst[0] * 0.5f);  /* eight: much less */
    CHECK(worst[2] < 1e-4f);            /* FTL: none */
}

static void test_ropes_get_positions(void)
{
    enum { R = 3, P = 4 };
    float rest[3 * R * P], root[3 * R], nrm[3 * R], tan[3 * R];
    float out[4 * R * P];
    tr_set s;
    int r, j;
    if (!tr_open(&s, R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        root[3 * r] = (float)r; root[3 * r + 1] = 0; root[3 * r + 2] = 0;
        nrm[3 * r] = 0; nrm[3 * r + 1] = 0; nrm[3 * r + 2] = 1;
        tan[3 * r] = 1; tan[3 * r + 1] = 0; tan[3 * r + 2] = 0;
        tr_straight(rest, r, P, root + 3 * r, nrm + 3 * r, 0.3f);
    }
    hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0);
    for (j = 0; j < 4 * R * P; ++j) out[j] = -7.0f;
    CHECK_EQ_INT(hf_ropes_get_positions(&s.ro, 1, 2, out, 16), HF_OK);
    for (j = 0; j < 4 * P; ++j) CHECK(out[j] == -7.0f); /* rope 0 untouched */
    for (r = 1; r < R; ++r)
        for (j = 0; j < P; ++j) {
            size_t i = (size_t)j * R + r;
            const float *o = out + 4 * (r * P + j);
            CHECK(o[0] == s.ro.x[i] && o[1] == s.ro.y[i] && o[2] == s.ro.z[i]);
            CHECK(o[3] == -7.0f);
        }
    CHECK_EQ_INT(hf_ropes_get_positions(&s.ro, 0, R, out, 4),
                 HF_ERROR_BAD_STRIDE);
    CHECK_EQ_INT(hf_ropes_get_positions(&s.ro, 0, R + 1, out, 0),
                 HF_ERROR_BAD_RANGE);
    tr_close(&s);
}

/* The SSE path (four ropes a lane each, from the start of a range) and the
   scalar code (the rest of a range) give the same bytes: ranges of odd,
   shifting sizes put every rope now in a lane, now in a tail, and a rope
   at a time is scalar only. Hair drapes on the head sphere and meets a
   capsule, so collisions happen in lanes too; some ropes have zero-length
   segments or a first point off the root; some frames take several
   sub-steps; a last phase without forces has zero-length ropes, whose
   points coincide (the degenerate placement). */
/* One solver's run for test_ropes_simd_lanes_match_scalar: set 0 steps
   every rope at once at the best level (AVX2 groups of eight where the CPU
   has it, then four-lane groups, then the scalar tail), set 1 in ranges of
   1, 3, 5 and 7 (four-lane groups and scalar), set 2 a rope at a time (the
   scalar reference), sets 3 and 4 every rope at once at the SSE2 (NEON)
   and scalar levels. */
/* The levels the rope tests step at, each widest kernel first: the best
   the CPU has (with AVX-512: groups of sixteen, then eight, four and the
   scalar tail in one call), AVX2 (eight), SSE2 or NEON (four) and the
   scalar reference. A level the CPU lacks resolves to the best below. */
static const int tr_levels[4] = {HF_SIMD_AUTO, HF_SIMD_AVX2, HF_SIMD_SSE2,
                                 HF_SIMD_SCALAR};

static void t_ropes_lanes(int solver)
{
    enum { R = 45, P = 9, FRAMES = 90, NSET = 6 };
    static float rest[3 * R * P], pos[3][3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], dirs[3 * R];
    hf_collider col[2];
    hf_rope_params p, pl;
    tr_set s[NSET];
    int r, j, f, k, same = 1, on_surface = 0;
    for (k = 0; k < NSET; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        double el = 0.2 + 1.3 * (r + 0.5) / R, az = 2.39996 * r;
        tr_on_head(r, el, az, dirs, nrm, tan, root);
        tr_straight(rest, r, P, root + 3 * r, dirs + 3 * r, 0.2f);
        if (r % 7 == 3) /* points 4 and 5 coincide */
            for (j = 0; j < 3; ++j)
                rest[3 * ((size_t)r * P + 5) + j] =
                    rest[3 * ((size_t)r * P + 4) + j];
        if (r % 5 == 1) rest[3 * (size_t)r * P] += 0.001f;
    }
    hf_rope_params_init(&p);
    p.turbulence = 4.0f;
    p.global_stiffness_tip = 0.02f;
    p.local_stiffness_root = 0.2f;
    p.root_stiffness = 0.3f;
    p.solver = solver;
    memset(col, 0, sizeof col);
    col[0].type = HF_COLLIDER_SPHERE;
    col[0].radius = 0.097f;
    col[1].type = HF_COLLIDER_CAPSULE;
    col[1].radius = 0.02f;
    for (k = 0; k < NSET; ++k)
        hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
    for (f = 0; f < FRAMES + 5; ++f) {
        float cx = (float)(0.15 * sin(2 * T_PI * f / 60.0));
        float dt = f % 10 == 9 ? 0.05f : 1.0f / 60.0f;
        int first = 0, size = 1 + 2 * (f % 4);
        if (f == FRAMES) { /* no forces; ropes 0, 6, 12, ... of zero length */
            p.gravity[1] = 0.0f;
            p.turbulence = 0.0f;
            for (r = 0; r < R; r += 6)
                for (j = 0; j < 3 * P; ++j)
                    rest[3 * (size_t)r * P + j] = root[3 * r + j % 3];
            for (k = 0; k < NSET; ++k)
                hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
        }
        if (f < FRAMES)
            for (r = 0; r < R; ++r) root[3 * r] = cx + 0.1f * dirs[3 * r];
        col[0].a[0] = cx;
        col[1].a[0] = cx - 0.2f; col[1].a[1] = -0.12f; col[1].a[2] = 0.0f;
        col[1].b[0] = cx + 0.2f; col[1].b[1] = -0.12f; col[1].b[2] = 0.05f;
        for (k = 0; k < NSET; ++k)
            hf_ropes_set_roots(&s[k].ro, 0, R, root, nrm, tan, 0);
        CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, R, dt, &p, col, 2), HF_OK);
        while (first < R) { /* sizes 1, 3, 5, 7 in turn, shifting */
            int n = R - first < size ? R - first : size;
            CHECK_EQ_INT(hf_ropes_step(&s[1].ro, first, n, dt, &p, col, 2),
                         HF_OK);
            first += n;
            size = size == 7 ? 1 : size + 2;
        }
        for (r = 0; r < R; ++r)
            hf_ropes_step(&s[2].ro, r, 1, dt, &p, col, 2);
        for (k = 3; k < NSET; ++k) {
            pl = p;
            pl.simd = tr_levels[k - 2];
            CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, R, dt, &pl, col, 2), HF_OK);
        }
        for (k = 1; k < NSET; ++k)
            same &= tr_same(&s[0].ro, &s[k].ro, 1);
        /* the collider was met: points pushed onto its inflated surface */
        for (r = 0; r < R; ++r)
            for (j = 1; j < P; ++j) {
                size_t i = (size_t)j * R + r;
                float q[3];
                q[0] = s[0].ro.x[i]; q[1] = s[0].ro.y[i]; q[2] = s[0].ro.z[i];
                if (fabs(tr_dist_seg(q, &col[0]) - 0.099) < 1e-5) ++on_surface;
            }
    }
    CHECK(same);
    CHECK(on_surface > 20);
    CHECK(tr_finite(&s[0].ro));
    /* positions read out whole (four ropes at a time) or a rope at a time */
    memset(pos, 0, sizeof pos);
    CHECK_EQ_INT(hf_ropes_get_positions(&s[0].ro, 0, R, pos[0], 0), HF_OK);
    for (r = 0; r < R; ++r)
        hf_ropes_get_positions(&s[0].ro, r, 1, pos[1], 12);
    CHECK_EQ_INT(hf_ropes_get_positions(&s[0].ro, 1, R - 2, pos[2], 0), HF_OK);
    CHECK(memcmp(pos[0], pos[1], sizeof pos[0]) == 0);
    CHECK(memcmp(pos[0] + 3 * P, pos[2] + 3 * P,
                 sizeof(float) * 3 * P * (R - 2)) == 0);
    for (j = 0; j < 3 * P; ++j)
        CHECK(pos[2][j] == 0.0f && pos[2][3 * P * (R - 1) + j] == 0.0f);
    for (k = 0; k < NSET; ++k) tr_close(&s[k]);
}

/* The safety net: a rope with a point that is NaN or thrown beyond
   8 * length + 0.01 m of its root is reset whole, at every level and in
   every lane (groups of sixteen, eight, four, the tail); every other rope goes on
   as if nothing happened. */
/* hf_ropes_set_roots writes four ropes at a time: every lane must give
   the bytes the one-rope path gives, for normals and tangents of any
   scale, tangents zero, tiny or along the normal, and a byte stride. */
static void test_ropes_set_roots_lanes(void)
{
    enum { R = 23, P = 3, S = 7 }; /* stride S floats */
    static float rest[3 * R * P];
    float root[S * R], nrm[S * R], tan[S * R];
    tr_set s[2];
    uint32_t seed = 12345u;
    int r, k, row, same = 1, unit = 1;
#define TR_RND() \
    ((float)((seed = seed * 1664525u + 1013904223u) >> 8) * (1.0f / 16777216.0f))
    for (k = 0; k < 2; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        const float scale = r % 5 == 0 ? 1e-20f : (r % 5 == 1 ? 3e20f : 1.0f);
        for (k = 0; k < 3; ++k) {
            root[S * r + k] = 2.0f * TR_RND() - 1.0f;
            nrm[S * r + k] = scale * (2.0f * TR_RND() - 1.0f);
            tan[S * r + k] = 2.0f * TR_RND() - 1.0f;
        }
        switch (r % 6) {
        case 0: tan[S * r] = tan[S * r + 1] = tan[S * r + 2] = 0.0f; break;
        case 2: /* along the normal */
            for (k = 0; k < 3; ++k) tan[S * r + k] = -4.0f * nrm[S * r + k];
            break;
        case 4: for (k = 0; k < 3; ++k) tan[S * r + k] *= 1e-30f; break;
        case 5: /* nearly along it: about the 1e-10 cut of the basis */
            for (k = 0; k < 3; ++k)
                tan[S * r + k] = nrm[S * r + k] * (1.0f + 4e-6f * tan[S * r + k]);
            break;
        default: break;
        }
        nrm[S * r + r % 3] = r % 7 == 3 ? 0.0f : nrm[S * r + r % 3];
    }
    for (r = 0; r < R; ++r)
        for (k = 0; k < 3 * P; ++k) rest[3 * r * P + k] = root[S * r + k % 3];
    for (k = 0; k < 2; ++k)
        CHECK_EQ_INT(hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm,
                                       tan, S * 4),
                     HF_OK);
    CHECK_EQ_INT(hf_ropes_set_roots(&s[0].ro, 0, R, root, nrm, tan, S * 4),
                 HF_OK);
    for (r = R - 1; r >= 0; --r)
        CHECK_EQ_INT(hf_ropes_set_roots(&s[1].ro, r, 1, root, nrm, tan, S * 4),
                     HF_OK);
    for (row = 0; row < 12; ++row)
        same &= memcmp(s[0].ro.frame + row * R, s[1].ro.frame + row * R,
                       sizeof(float) * R) == 0;
    for (r = 0; r < R; ++r) { /* t, n, b orthonormal */
        float f[12];
        for (row = 0; row < 12; ++row) f[row] = s[0].ro.frame[row * R + r];
        for (k = 3; k < 12; k += 3) {
            const float l = f[k] * f[k] + f[k + 1] * f[k + 1] + f[k + 2] * f[k + 2];
            unit &= fabsf(l - 1.0f) < 1e-5f;
        }
        unit &= fabsf(f[3] * f[6] + f[4] * f[7] + f[5] * f[8]) < 1e-5f;
    }
#undef TR_RND
    CHECK(same);
    CHECK(unit);
    for (k = 0; k < 2; ++k) tr_close(&s[k]);
}

static void test_ropes_safety_net_resets(void)
{
    enum { R = 29, P = 6, NSET = 5 };
    static float rest[3 * R * P];
    static const int bad[] = {0, 3, 5, 9, 13, 17, 26, 28};
    float root[3 * R], nrm[3 * R], tan[3 * R], dirs[3 * R];
    hf_rope_params p;
    tr_set s[NSET];
    int r, j, k, i, same = 1, untouched = 1, near = 1;
    for (k = 0; k < NSET; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        tr_on_head(r, 0.3 + 1.2 * (r + 0.5) / R, 2.39996 * r, dirs, nrm, tan,
                   root);
        tr_straight(rest, r, P, root + 3 * r, dirs + 3 * r, 0.1f);
    }
    hf_rope_params_init(&p);
    for (k = 0; k < NSET; ++k) {
        hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
        CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, R, 1.0f / 60.0f, &p, NULL, 0),
                     HF_OK);
    }
    /* sets 0..3 broken, one per level; set 4 the run without */
    for (k = 0; k < 4; ++k)
        for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); ++i) {
            const size_t o = (size_t)(1 + i % (P - 1)) * R + (size_t)bad[i];
            if (i % 2)
                s[k].ro.y[o] = (float)NAN;
            else
                s[k].ro.x[o] += 2.0f;
        }
    for (k = 0; k < NSET; ++k) {
        hf_rope_params pl = p;
        pl.simd = tr_levels[k % 4];
        CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, R, 1.0f / 60.0f, &pl, NULL, 0),
                     HF_OK);
    }
    for (k = 1; k < 4; ++k)
        same &= tr_same(&s[0].ro, &s[k].ro, 0);
    for (r = 0; r < R; ++r) {
        int broken = 0;
        for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); ++i)
            broken |= bad[i] == r;
        for (j = 0; j < P; ++j) {
            const size_t o = (size_t)j * R + (size_t)r;
            const double dx = s[0].ro.x[o] - s[0].ro.x[r],
                         dy = s[0].ro.y[o] - s[0].ro.y[r],
                         dz = s[0].ro.z[o] - s[0].ro.z[r];
            near &= sqrt(dx * dx + dy * dy + dz * dz) < 0.11;
            if (!broken)
                untouched &= s[0].ro.x[o] == s[4].ro.x[o] &&
                             s[0].ro.y[o] == s[4].ro.y[o] &&
                             s[0].ro.z[o] == s[4].ro.z[o];
        }
    }
    CHECK(same);
    CHECK(near);
    CHECK(untouched);
    for (k = 0; k < NSET; ++k) CHECK(tr_finite(&s[k].ro));
    for (k = 0; k < NSET; ++k) tr_close(&s[k]);
}

/* Contacts at every level: ropes hanging through random spheres and
   capsules (one to four, overlapping; some roots inside; a twelve-collider
   case that takes the batched scalar walk), stepped whole at each of
   tr_levels: the same bytes. The four-lane contact
   kernel resolves the points in contact four at a time, gathered from
   the row, with every branch of the scalar kernel as a select. */
static void test_ropes_contacts_match_scalar(void)
{
    enum { R = 83, P = 8, NSET = 4, TRIALS = 40 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], dir[3];
    hf_collider col[12];
    hf_rope_params p;
    tr_set s[NSET];
    uint32_t seed = 12345u;
    int r, k, c, f, trial, same = 1, touching = 0;
    for (k = 0; k < NSET; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    hf_rope_params_init(&p);
    p.local_stiffness_root = 0.2f;
    p.collision_margin = 0.002f;
    for (trial = 0; trial < TRIALS; ++trial) {
        const int ncol = trial == TRIALS - 1 ? 12 : 1 + trial % 4;
#define T_RND()                                                                \
    ((float)((seed = seed * 1664525u + 1013904223u) >> 8) * (1.0f / 16777216.0f))
        for (r = 0; r < R; ++r) {
            root[3 * r] = 0.2f * T_RND() - 0.1f;
            root[3 * r + 1] = 0.0f;
            root[3 * r + 2] = 0.2f * T_RND() - 0.1f;
            nrm[3 * r] = 0.0f; nrm[3 * r + 1] = -1.0f; nrm[3 * r + 2] = 0.0f;
            tan[3 * r] = 1.0f; tan[3 * r + 1] = 0.0f; tan[3 * r + 2] = 0.0f;
            dir[0] = 0.6f * T_RND() - 0.3f;
            dir[1] = -1.0f;
            dir[2] = 0.6f * T_RND() - 0.3f;
            tr_straight(rest, r, P, root + 3 * r, dir, 0.12f);
        }
        memset(col, 0, sizeof col);
        for (c = 0; c < ncol; ++c) {
            /* about a random point of a random rope, so points start
               inside; the first point of a rope is its root */
            const float *q = rest + 3 * ((size_t)(seed % R) * P + seed % P);
            col[c].type = T_RND() < 0.5f ? HF_COLLIDER_SPHERE
                                         : HF_COLLIDER_CAPSULE;
            col[c].radius = 0.01f + 0.04f * T_RND();
            for (k = 0; k < 3; ++k) {
                col[c].a[k] = q[k] + 0.02f * T_RND() - 0.01f;
                col[c].b[k] = col[c].a[k] + 0.16f * T_RND() - 0.08f;
            }
        }
#undef T_RND
        tr_rest_all(s, NSET, rest, root, nrm, tan);
        for (f = 0; f < 4; ++f) {
            for (r = 0; r < R; ++r) root[3 * r] += 0.01f;
            for (k = 0; k < NSET; ++k) {
                hf_rope_params pl = p;
                pl.simd = tr_levels[k];
                hf_ropes_set_roots(&s[k].ro, 0, R, root, nrm, tan, 0);
                CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, R, 1.0f / 60.0f, &pl,
                                           col, ncol),
                             HF_OK);
            }
            for (k = 1; k < NSET; ++k)
                same &= tr_same(&s[0].ro, &s[k].ro, 0);
        }
        for (r = 0; r < R * P; ++r) /* points left on a surface */
            for (c = 0; c < ncol; ++c) {
                const float q[3] = {s[0].ro.x[r], s[0].ro.y[r], s[0].ro.z[r]};
                if (fabs(tr_dist_seg(q, &col[c]) - col[c].radius -
                         p.collision_margin) < 1e-4)
                    ++touching;
            }
    }
    CHECK(same);
    CHECK(touching > 500);
    for (k = 0; k < NSET; ++k) CHECK(tr_finite(&s[k].ro));
    for (k = 0; k < NSET; ++k) tr_close(&s[k]);
}

/* Ropes lying along their root tangent straight at a capsule's axis: the
   turn out of the capsule has no direction of its own (the rope and its
   tangent both lie along the cap's axis), so every kernel takes its rare
   fixed perpendicular, lane by lane at every width. Each level gives the
   scalar bytes; every rope in contact is turned aside, finite and out. */
static void test_ropes_contacts_degenerate_lanes(void)
{
    enum { R = 45, P = 6, NSET = 4 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    hf_collider col;
    hf_rope_params p;
    tr_set s[NSET];
    int r, k, j, same = 1, turned = 0, touching = 0;
    for (k = 0; k < NSET; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    hf_rope_params_init(&p);
    p.gravity[1] = 0.0f;
    p.explicit_zero = HF_ROPE_ZERO_GRAVITY;
    memset(&col, 0, sizeof col);
    col.type = HF_COLLIDER_CAPSULE;
    col.a[0] = col.b[0] = 0.05f;
    col.a[2] = -1.0f;
    col.b[2] = 1.0f;
    col.radius = 0.02f;
    for (r = 0; r < R; ++r) {
        /* every third rope points away: the contacts are gathered */
        const float dir[3] = {r % 3 == 2 ? -1.0f : 1.0f, 0.0f, 0.0f};
        root[3 * r] = 0.0f;
        root[3 * r + 1] = 0.0f;
        root[3 * r + 2] = 0.01f * (float)r - 0.2f;
        nrm[3 * r] = 0.0f; nrm[3 * r + 1] = 1.0f; nrm[3 * r + 2] = 0.0f;
        tan[3 * r] = 1.0f; tan[3 * r + 1] = 0.0f; tan[3 * r + 2] = 0.0f;
        tr_straight(rest, r, P, root + 3 * r, dir, 0.1f);
        touching += r % 3 != 2;
    }
    for (k = 0; k < NSET; ++k) {
        hf_rope_params pl = p;
        pl.simd = tr_levels[k];
        CHECK_EQ_INT(hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm,
                                       tan, 0),
                     HF_OK);
        CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, R, 1.0f / 60.0f, &pl, &col, 1),
                     HF_OK);
    }
    for (k = 1; k < NSET; ++k)
        same &= tr_same(&s[0].ro, &s[k].ro, 0);
    CHECK(same);
    for (r = 0; r < R; ++r) {
        const size_t o = (size_t)2 * R + (size_t)r; /* row 2: was inside */
        turned += fabsf(s[0].ro.z[o] - root[3 * r + 2]) > 1e-3f;
        for (j = 1; j < P; ++j) {
            const size_t q = (size_t)j * R + (size_t)r;
            const float x[3] = {s[0].ro.x[q], s[0].ro.y[q], s[0].ro.z[q]};
            CHECK(tr_dist_seg(x, &col) > col.radius * 0.999);
        }
    }
    CHECK_EQ_INT(turned, touching);
    for (k = 0; k < NSET; ++k) CHECK(tr_finite(&s[k].ro));
    for (k = 0; k < NSET; ++k) tr_close(&s[k]);
}

static void test_ropes_simd_lanes_match_scalar(void)
{
    t_ropes_lanes(HF_ROPE_SOLVER_FTL);
    t_ropes_lanes(HF_ROPE_SOLVER_DISTANCE);
}

static void test_defaults_zeroed_rope_params_are_init(void)
{
    /* a zeroed struct and hf_rope_params_init give the same step, bytes */
    hf_rope_params zero, init;
    tr_set a, b;
    float pos[2 * 6 * 3], root[6], nrm[6] = {0, 1, 0, 0, 1, 0};
    float tan[6] = {1, 0, 0, 1, 0, 0};
    int r, i;
    memset(&zero, 0, sizeof zero);
    hf_rope_params_init(&init);
    CHECK_EQ_INT(hf_rope_params_validate(&zero, NULL), HF_OK);
    CHECK(init.gravity[1] == -9.81f && init.damping == 0.02f &&
          init.iterations == 2 && init.collision_margin == 0.002f &&
          init.mode_blend_time == 0.25f && init.ftl_damping == 0.9f);
    CHECK(tr_open(&a, 2, 6) && tr_open(&b, 2, 6));
    for (r = 0; r < 2; ++r) {
        root[3 * r] = (float)r; root[3 * r + 1] = 0.0f; root[3 * r + 2] = 0.0f;
        tr_straight(pos, r, 6, root + 3 * r, tan + 3 * r, 0.05f);
    }
    CHECK_EQ_INT(hf_ropes_set_rest(&a.ro, 0, 2, pos, 0, root, nrm, tan, 0), HF_OK);
    CHECK_EQ_INT(hf_ropes_set_rest(&b.ro, 0, 2, pos, 0, root, nrm, tan, 0), HF_OK);
    for (i = 0; i < 10; ++i) {
        CHECK_EQ_INT(hf_ropes_step(&a.ro, 0, 2, 1.0f / 60.0f, &zero, NULL, 0), HF_OK);
        CHECK_EQ_INT(hf_ropes_step(&b.ro, 0, 2, 1.0f / 60.0f, &init, NULL, 0), HF_OK);
    }
    CHECK(memcmp(a.ro.x, b.ro.x, sizeof(float) * 12) == 0);
    CHECK(memcmp(a.ro.y, b.ro.y, sizeof(float) * 12) == 0);
    /* the ropes, laid out sideways, fell: gravity was on */
    CHECK(a.ro.y[5 * 2 + 0] < -1e-3f);
    tr_close(&a);
    tr_close(&b);
}

static void test_defaults_explicit_zero(void)
{
    /* explicit_zero makes a zero literal: no gravity, the rope stays put */
    hf_rope_params p;
    tr_set a;
    float pos[6 * 3], root[3] = {0, 0, 0}, nrm[3] = {0, 1, 0};
    float tan[3] = {1, 0, 0}, before[6 * 3], after[6 * 3];
    int i;
    memset(&p, 0, sizeof p);
    p.explicit_zero = HF_ROPE_ZERO_GRAVITY | HF_ROPE_ZERO_DAMPING;
    CHECK(tr_open(&a, 1, 6));
    tr_straight(pos, 0, 6, root, tan, 0.05f);
    CHECK_EQ_INT(hf_ropes_set_rest(&a.ro, 0, 1, pos, 0, root, nrm, tan, 0), HF_OK);
    tr_snapshot(&a.ro, before);
    for (i = 0; i < 30; ++i)
        CHECK_EQ_INT(hf_ropes_step(&a.ro, 0, 1, 1.0f / 60.0f, &p, NULL, 0), HF_OK);
    tr_snapshot(&a.ro, after);
    CHECK(tr_max_move(before, after, 6) < 1e-6);
    tr_close(&a);
}

/* Roots whose frames hold rounding noise where 0 is meant (a root on a
   mesh's plane of symmetry): the noise times the rest offsets' noise
   made subnormal floats in every sub-step, many times slower on x86.
   The frames and offsets are cleaned, so a step makes none: no
   underflow is raised (where the platform keeps the flag; making the
   roots' frames from such normals squares the noise once a root, which
   is left out). */
static void test_ropes_no_subnormals(void)
{
    enum { R = 16, P = 12 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    hf_rope_params p;
    tr_set s;
    int r, f, under = 0;
    if (!tr_open(&s, R, P)) { CHECK(0); return; }
    for (r = 0; r < R; ++r) {
        const float a = 6.2831853f * (float)r / (float)R,
                    c = (float)cos(a), sn = (float)sin(a);
        const float dir[3] = {c, 0.0f, sn};
        root[3 * r] = 0.1f * c;
        root[3 * r + 1] = 0.0f;
        root[3 * r + 2] = 0.1f * sn;
        nrm[3 * r] = c; nrm[3 * r + 1] = 3e-21f; nrm[3 * r + 2] = sn;
        tan[3 * r] = 0.0f; tan[3 * r + 1] = 1.0f; tan[3 * r + 2] = 2e-21f;
        tr_straight(rest, r, P, root + 3 * r, dir, 0.2f);
    }
    hf_rope_params_init(&p);
    p.global_stiffness_root = p.global_stiffness_tip = 0.2f;
    CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0),
                 HF_OK);
    for (f = 0; f < 30; ++f) {
        CHECK_EQ_INT(hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0),
                     HF_OK);
#ifdef FE_UNDERFLOW
        feclearexcept(FE_UNDERFLOW);
#endif
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, NULL, 0),
                     HF_OK);
#ifdef FE_UNDERFLOW
        under += fetestexcept(FE_UNDERFLOW) != 0;
#endif
    }
    CHECK(under == 0);
    CHECK(tr_finite(&s.ro));
    tr_close(&s);
}

/* 6. ropes: its tests, in the order they run */
#define T_ROPES_TESTS(X)                                                       \
    X(test_ropes_params_defaults_and_validation)                               \
    X(test_ropes_memory_init_create)                                           \
    X(test_ropes_hanging_settles)                                              \
    X(test_ropes_shape_kept_by_moving_frame)                                   \
    X(test_ropes_collider_sweep_never_penetrates)                              \
    X(test_ropes_mode_switch_no_jump)                                          \
    X(test_ropes_mode_switch_smooth)                                           \
    X(test_ropes_bad_time_steps)                                               \
    X(test_ropes_ranges_byte_identical)                                        \
    X(test_ropes_chunks_byte_identical)                                        \
    X(test_ropes_root_frames)                                                  \
    X(test_ropes_reset_teleport)                                               \
    X(test_ropes_root_and_local_stiffness)                                     \
    X(test_ropes_shape_stiffness_settles)                                      \
    X(test_ropes_swinging_head)                                                \
    X(test_ropes_max_stretch_exact)                                            \
    X(test_ropes_wind_and_turbulence)                                          \
    X(test_ropes_distance_solver_iterations)                                   \
    X(test_ropes_get_positions)                                                \
    X(test_ropes_set_roots_lanes)                                              \
    X(test_ropes_safety_net_resets)                                            \
    X(test_ropes_contacts_match_scalar)                                        \
    X(test_ropes_contacts_degenerate_lanes)                                    \
    X(test_ropes_simd_lanes_match_scalar)                                      \
    X(test_ropes_no_subnormals)                                                \
    X(test_defaults_zeroed_rope_params_are_init)                               \
    X(test_defaults_explicit_zero)

/* ---- collisions that never stretch ---- */

/* One rope hanging past a capsule: one step keeps every segment (the
   capsule turned the child onto a local ball of one axis point, and a
   radial push then cut segment 9-10 short by 5.7 %). */
static void test_ropes_capsule_keeps_length(void)
{
    enum { P = 16 };
    float pos[3 * P], now[3 * P], root[3] = {0, 0, 0}, nrm[3] = {0, -1, 0};
    float tan[3] = {1, 0, 0}, st = 1.0f;
    double deepest = -1.0;
    hf_rope_params p;
    hf_collider cap;
    tr_set s;
    int j;
    if (!tr_open(&s, 1, P)) { CHECK(0); return; }
    tr_straight(pos, 0, P, root, nrm, 0.3f);
    CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, 1, pos, 0, root, nrm, tan, 0), HF_OK);
    memset(&p, 0, sizeof p);
    memset(&cap, 0, sizeof cap);
    cap.type = HF_COLLIDER_CAPSULE;
    cap.a[0] = -0.27f; cap.a[1] = -0.25f;
    cap.b[0] = 0.13f; cap.b[1] = -0.25f;
    cap.radius = 0.06f;
    CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, &cap, 1), HF_OK);
    CHECK_EQ_INT(hf_ropes_max_stretch(&s.ro, 0, 1, &st), HF_OK);
    tr_snapshot(&s.ro, now);
    for (j = 1; j < P; ++j) {
        double in = cap.radius - tr_dist_seg(now + 3 * j, &cap);
        if (in > deepest) deepest = in;
    }
    CHECK(st <= 1e-4f);
    CHECK(deepest <= 1e-3);
    tr_close(&s);
}

/* 64 guides on the 0.1 m head swinging 0.2 m at 1 Hz; returns the worst
   stretch over 2 s with collider c, and the roots counted inside. */
static float t_head_swing(const hf_collider *c0, int *roots_inside)
{
    enum { R = 64, P = 16, FRAMES = 120 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], dirs[3 * R], worst = 0, st;
    hf_collider c = *c0;
    hf_rope_params p;
    tr_set s;
    int r, f;
    if (!tr_open(&s, R, P)) return 1e9f;
    for (r = 0; r < R; ++r) {
        tr_on_head(r, 0.2 + 2.6 * (r / 8) / 7.0, 2 * T_PI * (r % 8) / 8.0,
                   dirs, nrm, tan, root);
        tr_straight(rest, r, P, root + 3 * r, dirs + 3 * r, 0.2f);
    }
    hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0);
    memset(&p, 0, sizeof p);
    for (f = 0; f < FRAMES; ++f) {
        float cx = (float)(0.2 * sin(2 * T_PI * (f + 1) / 60.0));
        c.a[0] = c0->a[0] + cx;
        c.b[0] = c0->b[0] + cx;
        for (r = 0; r < R; ++r) root[3 * r] = cx + 0.1f * dirs[3 * r];
        hf_ropes_set_roots(&s.ro, 0, R, root, nrm, tan, 0);
        if (hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, &c, 1) != HF_OK)
            worst = 1e9f;
        hf_ropes_max_stretch(&s.ro, 0, R, &st);
        if (!(st <= worst)) worst = st;
    }
    hf_ropes_roots_inside(&s.ro, 0, R, roots_inside);
    tr_close(&s);
    return worst;
}

/* Roots inside a collider: the collider is shrunk, for those ropes, to
   the root's depth, so nothing stretches (a 0.12 m sphere: 10 % before;
   a capsule through the head: 227 %; a sphere holding every root: 809 %),
   and hf_ropes_roots_inside counts them. Roots on the surface (a collider
   the size of the head) do not count. */
static void test_ropes_roots_inside_colliders(void)
{
    hf_collider c;
    int inside = -1;
    float st;
    memset(&c, 0, sizeof c);
    c.type = HF_COLLIDER_SPHERE;
    c.radius = 0.1f;
    st = t_head_swing(&c, &inside);
    CHECK(st <= 1e-4f);
    CHECK_EQ_INT(inside, 0);
    c.radius = 0.12f;
    st = t_head_swing(&c, &inside);
    CHECK(st <= 1e-4f);
    CHECK_EQ_INT(inside, 64);
    c.radius = 0.5f;
    st = t_head_swing(&c, &inside);
    CHECK(st <= 1e-4f);
    CHECK_EQ_INT(inside, 64);
    c.type = HF_COLLIDER_CAPSULE;
    c.a[1] = -0.3f;
    c.b[1] = 0.3f;
    c.radius = 0.115f;
    st = t_head_swing(&c, &inside);
    CHECK(st <= 1e-4f);
    CHECK_EQ_INT(inside, 64);
    CHECK_EQ_INT(hf_ropes_roots_inside(NULL, 0, 1, &inside),
                 HF_ERROR_NULL_POINTER);
}

/* A seeded soak: random spheres and capsules (overlapping one another and
   the head; the head collider sometimes larger than the head, holding the
   roots), roots whipped about, dt in [1/240, 1/20]: stretch at most 1e-4,
   no NaN, no point more than 1 mm inside a collider as its rope sees it
   (shrunk to the root's depth where it holds the root deeper than the
   2 mm margin). */
static void test_ropes_collision_soak(void)
{
    enum { R = 64, P = 16, FRAMES = 150, SEEDS = 12, NC = 5 };
    static float rest[3 * R * P], now[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], dirs[3 * R], moved[3 * R];
    double worst_in = 0.0;
    float worst_st = 0.0f;
    int seed, nan_seen = 0;
    for (seed = 0; seed < SEEDS; ++seed) {
        hf_collider col[NC], base[NC];
        hf_rope_params p;
        hf_rng g;
        tr_set s;
        float off[3] = {0, 0, 0}, vel[3] = {0, 0, 0};
        int nc, r, j, c, f, k;
        if (!tr_open(&s, R, P)) { CHECK(0); return; }
        hf_rng_seed(&g, (uint64_t)seed, 9u);
        for (r = 0; r < R; ++r) {
            tr_on_head(r, T_PI * (0.05 + 0.9 * hf_rng_float(&g)),
                       2 * T_PI * hf_rng_float(&g), dirs, nrm, tan, root);
            tr_straight(rest, r, P, root + 3 * r, dirs + 3 * r, 0.25f);
        }
        hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0);
        memset(&p, 0, sizeof p);
        nc = 1 + (int)hf_rng_below(&g, NC);
        memset(col, 0, sizeof col);
        /* the head: its size, or up to 3 cm larger */
        col[0].radius = hf_rng_below(&g, 2) ? 0.1f : 0.1f + 0.03f * hf_rng_float(&g);
        for (c = 1; c < nc; ++c) {
            int ok = 0;
            while (!ok) { /* anywhere, overlapping too, but no root inside */
                col[c].type = (int)hf_rng_below(&g, 2);
                for (k = 0; k < 3; ++k) {
                    col[c].a[k] = 0.4f * (hf_rng_float(&g) - 0.5f);
                    col[c].b[k] = col[c].a[k] + 0.3f * (hf_rng_float(&g) - 0.5f);
                }
                col[c].radius = 0.03f + 0.1f * hf_rng_float(&g);
                ok = 1;
                for (r = 0; r < R && ok; ++r)
                    ok = tr_dist_seg(root + 3 * r, &col[c]) > col[c].radius + 0.003;
            }
        }
        memcpy(base, col, sizeof col);
        for (f = 0; f < FRAMES; ++f) {
            float dt = 1.0f / 240.0f + (1.0f / 20.0f - 1.0f / 240.0f) * hf_rng_float(&g);
            float st;
            for (k = 0; k < 3; ++k) { /* whipped: random accelerations */
                vel[k] = 0.98f * (vel[k] + dt * 60.0f * (hf_rng_float(&g) - 0.5f));
                off[k] += vel[k] * dt;
                if (fabsf(off[k]) > 0.5f) vel[k] = -vel[k];
            }
            for (r = 0; r < R; ++r)
                for (k = 0; k < 3; ++k) moved[3 * r + k] = root[3 * r + k] + off[k];
            for (c = 0; c < nc; ++c)
                for (k = 0; k < 3; ++k) {
                    col[c].a[k] = base[c].a[k] + off[k];
                    col[c].b[k] = base[c].b[k] + off[k];
                }
            hf_ropes_set_roots(&s.ro, 0, R, moved, nrm, tan, 0);
            CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, dt, &p, col, nc), HF_OK);
            hf_ropes_max_stretch(&s.ro, 0, R, &st);
            if (!(st <= worst_st)) worst_st = st;
            tr_snapshot(&s.ro, now);
            for (r = 0; r < R; ++r)
                for (c = 0; c < nc; ++c) {
                    const float *rp = now + 3 * (r * P);
                    const double dr = tr_dist_seg(rp, &col[c]);
                    const double eff =
                        dr < col[c].radius * 0.9999 - 0.002 - 1e-6
                            ? dr : col[c].radius;
                    for (j = 1; j < P; ++j) {
                        const float *q = now + 3 * (r * P + j);
                        double in;
                        if (!t_is_finite(q[0]) || !t_is_finite(q[1]) ||
                            !t_is_finite(q[2]))
                            nan_seen = 1;
                        in = eff - tr_dist_seg(q, &col[c]);
                        if (in > worst_in) worst_in = in;
                    }
                }
        }
        tr_close(&s);
    }
    if (getenv("TR_VERBOSE"))
        printf("collision soak: stretch %g, deepest %g m\n", worst_st, worst_in);
    CHECK(!nan_seen);
    CHECK(worst_st <= 1e-4f);
    CHECK(worst_in <= 1e-3);
}

/* hf_ropes_copy_range: a range into a buffer of exactly that range, the
   same bytes as the slice of hf_ropes_get_positions; and both, packed (the
   kernels: groups of eight and four ropes, blocks of eight and four
   points, the scalar tails) or strided (the scalar copy), the ropes'
   points exactly. */
static void test_ropes_copy_range(void)
{
    enum { R = 21, PMAX = 17 };
    static const int Ps[] = {2, 6, 8, 13, 16, 17};
    static float pos[3 * R * PMAX], whole[4 * R * PMAX], part[4 * R * PMAX];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    hf_rope_params p;
    tr_set s;
    int r, k, j, first, count, stride, pi;
    for (pi = 0; pi < (int)(sizeof Ps / sizeof Ps[0]); ++pi) {
        const int P = Ps[pi];
        if (!tr_open(&s, R, P)) { CHECK(0); return; }
        for (r = 0; r < R; ++r) {
            for (k = 0; k < 3; ++k) {
                root[3 * r + k] = k == 0 ? 0.1f * (float)r : 0.0f;
                nrm[3 * r + k] = k == 1 ? 1.0f : 0.0f;
                tan[3 * r + k] = k == 0 ? 1.0f : 0.0f;
            }
            tr_straight(pos, r, P, root + 3 * r, tan + 3 * r, 0.2f);
        }
        hf_ropes_set_rest(&s.ro, 0, R, pos, 0, root, nrm, tan, 0);
        memset(&p, 0, sizeof p);
        hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, NULL, 0);
        for (stride = 12; stride <= 16; stride += 4) {
            /* every point where it belongs, at any first rope */
            for (first = 0; first < 3; ++first) {
                memset(whole, 0, sizeof whole);
                CHECK_EQ_INT(hf_ropes_get_positions(&s.ro, first, R - first,
                                                    whole, stride),
                             HF_OK);
                for (r = first; r < R; ++r)
                    for (j = 0; j < P; ++j) {
                        const float *o =
                            (const float *)((const unsigned char *)whole +
                                            ((size_t)r * P + j) * stride);
                        const size_t i = (size_t)j * R + r;
                        CHECK(o[0] == s.ro.x[i] && o[1] == s.ro.y[i] &&
                              o[2] == s.ro.z[i]);
                    }
            }
            for (first = 0; first < R; first += 3)
                for (count = 0; first + count <= R; count += 5) {
                    memset(whole, 0, sizeof whole);
                    tb_fill(part, sizeof part);
                    CHECK_EQ_INT(hf_ropes_get_positions(&s.ro, 0, R, whole, stride), HF_OK);
                    CHECK_EQ_INT(hf_ropes_copy_range(&s.ro, first, count, part, stride), HF_OK);
                    for (k = 0; k < count * P; ++k) /* each x, y, z */
                        CHECK(memcmp((unsigned char *)part + (size_t)k * stride,
                                     (unsigned char *)whole +
                                         ((size_t)first * P + (size_t)k) * stride,
                                     12) == 0);
                    CHECK(tb_untouched((unsigned char *)part + (size_t)count * P * stride,
                                       sizeof part - (size_t)count * P * (size_t)stride));
                }
        }
        CHECK_EQ_INT(hf_ropes_copy_range(&s.ro, 5, R, part, 0), HF_ERROR_BAD_RANGE);
        CHECK_EQ_INT(hf_ropes_copy_range(&s.ro, 0, 1, NULL, 0), HF_ERROR_NULL_POINTER);
        tr_close(&s);
    }
}

/* More colliders than one batch of the collision kernel (8): a turn out
   of a collider of the second batch landed inside one of the first (16
   small colliders around a rope in a side wind, found by a review). */
static void test_ropes_many_colliders(void)
{
    static const hf_collider col[16] = {
        {0,{-0.00114607345f,0.0602713227f,-0.00918702409f},{0.00219258945f,0.048799105f,-0.0101300925f},0.00275745615f},
        {1,{0.0133525329f,0.0206072219f,-0.0066940859f},{0.0221356824f,0.0231356826f,-0.00280768611f},0.00559769012f},
        {1,{-0.0104756569f,0.0324156471f,0.00192570779f},{0.00729736593f,0.0300543979f,0.0193586573f},0.00253857579f},
        {1,{0.00909922365f,0.074978143f,-0.00146022346f},{0.00232949574f,0.0695276111f,0.0164392218f},0.00637932774f},
        {1,{0.0148187699f,0.0903722197f,0.00854090322f},{0.00897175912f,0.0886074677f,0.0279464535f},0.00316761993f},
        {1,{-0.0121075213f,0.112851292f,-0.0099619031f},{-0.0145371314f,0.104271553f,0.014845917f},0.00399725139f},
        {0,{0.0111459205f,0.116402686f,0.00520948973f},{-0.014726921f,0.101927981f,0.000386727042f},0.00389691233f},
        {1,{-0.00936847553f,0.0472339392f,-0.0137897991f},{-0.0357111916f,0.0720666423f,0.00624251924f},0.00215178984f},
        {0,{0.0133473938f,0.104479417f,-0.00609991886f},{-0.00286483858f,0.116535775f,-0.0201473664f},0.00385692576f},
        {1,{-0.0121115185f,0.097258389f,-0.0140614714f},{-0.0136744659f,0.0898384377f,0.00949841365f},0.00248470204f},
        {1,{-0.0142600965f,0.0677473694f,0.006735879f},{-0.0265186597f,0.0758847967f,0.0326705761f},0.0038475797f},
        {1,{-0.00924178865f,0.0229095351f,-0.0139756212f},{-0.0237311348f,-0.00199930184f,-0.00295278337f},0.00359659456f},
        {1,{0.0106576318f,0.0383067541f,-0.00532152969f},{0.0294966996f,0.0542080477f,0.0201537795f},0.00201514713f},
        {0,{-0.00176767912f,0.119201049f,0.0147478869f},{0.0115390038f,0.140054971f,0.0419162661f},0.00342998514f},
        {0,{-0.00104940496f,0.0510200635f,0.00362722483f},{-0.0294122025f,0.0626075044f,0.0115172351f},0.00270762667f},
        {0,{0.00116988737f,0.0982443839f,0.00289947446f},{0.0138400896f,0.0992516652f,0.0280379727f},0.00259035151f}};
    const float root[3] = {0.00206746347f, 0.00989271887f, 0.00581700169f};
    const float nrm[3] = {0, 1, 0}, tan[3] = {1, 0, 0};
    float pos[12 * 3], now[12 * 3], st;
    double worst = 0.0;
    hf_rope_params p;
    tr_set s;
    int j, c, step;
    if (!tr_open(&s, 1, 12)) { CHECK(0); return; }
    memset(&p, 0, sizeof p);
    p.wind[0] = -27.8392124f;
    p.wind[2] = -28.5135117f;
    for (j = 0; j < 12; ++j) {
        pos[3 * j] = root[0];
        pos[3 * j + 1] = root[1] + 0.01f * (float)j;
        pos[3 * j + 2] = root[2];
    }
    hf_ropes_set_rest(&s.ro, 0, 1, pos, 0, root, nrm, tan, 0);
    for (step = 0; step < 30; ++step)
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, 1, 1.0f / 60.0f, &p, col, 16), HF_OK);
    tr_snapshot(&s.ro, now);
    for (j = 1; j < 12; ++j)
        for (c = 0; c < 16; ++c) {
            double in = col[c].radius + 0.002 - tr_dist_seg(now + 3 * j, &col[c]);
            if (in > worst) worst = in;
        }
    hf_ropes_max_stretch(&s.ro, 0, 1, &st);
    CHECK(worst <= 1e-5);
    CHECK(st <= 1e-4f);
    tr_close(&s);
}

/* A 24-proxy body under the 0.1 m head sphere centred at (dx, 0, 0):
   neck, chest, back, shoulders, arms, hips and legs, overlapping at the
   joints as an engine's physics asset has them. Returns 24. */
static int tr_body(hf_collider *c, float dx)
{
    static const float caps[19][7] = {
        {0, -0.09f, -0.01f, 0, -0.17f, -0.01f, 0.055f},
        {-0.12f, -0.30f, 0, 0.12f, -0.30f, 0, 0.11f},
        {-0.10f, -0.42f, 0, 0.10f, -0.42f, 0, 0.11f},
        {-0.08f, -0.55f, 0, 0.08f, -0.55f, 0, 0.10f},
        {-0.10f, -0.70f, 0, 0.10f, -0.70f, 0, 0.11f},
        {-0.10f, -0.28f, -0.06f, 0.10f, -0.45f, -0.06f, 0.09f},
        {-0.05f, -0.19f, -0.02f, -0.17f, -0.23f, -0.02f, 0.06f},
        {0.05f, -0.19f, -0.02f, 0.17f, -0.23f, -0.02f, 0.06f},
        {-0.20f, -0.25f, 0, -0.22f, -0.52f, 0, 0.05f},
        {0.20f, -0.25f, 0, 0.22f, -0.52f, 0, 0.05f},
        {-0.22f, -0.52f, 0, -0.24f, -0.78f, 0.03f, 0.04f},
        {0.22f, -0.52f, 0, 0.24f, -0.78f, 0.03f, 0.04f},
        {-0.12f, -0.80f, 0, -0.13f, -1.20f, 0, 0.08f},
        {0.12f, -0.80f, 0, 0.13f, -1.20f, 0, 0.08f},
        {-0.13f, -1.20f, 0, -0.13f, -1.60f, 0, 0.06f},
        {0.13f, -1.20f, 0, 0.13f, -1.60f, 0, 0.06f},
        {-0.13f, -1.66f, -0.02f, -0.13f, -1.66f, 0.12f, 0.04f},
        {0.13f, -1.66f, -0.02f, 0.13f, -1.66f, 0.12f, 0.04f},
        {-0.04f, -0.30f, 0.07f, 0.04f, -0.30f, 0.07f, 0.06f}};
    static const float sph[5][4] = {{-0.19f, -0.24f, 0, 0.065f},
                                    {0.19f, -0.24f, 0, 0.065f},
                                    {-0.25f, -0.84f, 0.04f, 0.05f},
                                    {0.25f, -0.84f, 0.04f, 0.05f},
                                    {0, -0.02f, 0.09f, 0.04f}};
    int n = 0, i, k;
    for (i = 0; i < 19; ++i, ++n) {
        memset(c + n, 0, sizeof *c);
        c[n].type = HF_COLLIDER_CAPSULE;
        for (k = 0; k < 3; ++k) {
            c[n].a[k] = caps[i][k] + (k == 0 ? dx : 0.0f);
            c[n].b[k] = caps[i][3 + k] + (k == 0 ? dx : 0.0f);
        }
        c[n].radius = caps[i][6];
    }
    for (i = 0; i < 5; ++i, ++n) {
        memset(c + n, 0, sizeof *c);
        c[n].type = HF_COLLIDER_SPHERE;
        for (k = 0; k < 3; ++k) c[n].a[k] = sph[i][k] + (k == 0 ? dx : 0.0f);
        c[n].radius = sph[i][3];
    }
    return n;
}

/* Ropes of length len on a scalp cap of the 0.1 m head at (dx, 0, 0)
   (polar angles up to 110 degrees), rest poses straight out. */
static void tr_scalp(int R, int P, float len, float dx, float *rest,
                     float *root, float *nrm, float *tan)
{
    float dirs[3 * 400];
    int r;
    for (r = 0; r < R && r < 400; ++r) {
        const double el = 1.92 * sqrt((r + 0.5) / R);
        const double az = 2.39996323 * r;
        tr_on_head(r, el, az, dirs, nrm, tan, root);
        root[3 * r] += dx;
        tr_straight(rest, r, P, root + 3 * r, dirs + 3 * r, len);
    }
}

/* The head's sphere of tr_scalp's ropes (radius 0.1 m at the origin),
   a little inside their roots. */
static void tr_head_sphere(hf_collider *c)
{
    memset(c, 0, sizeof *c);
    c->type = HF_COLLIDER_SPHERE;
    c->radius = 0.097f;
}

/* Colliders far from every rope change nothing: the same ropes against
   a head and a capsule near it, and against the same two among 40
   others 3 m away (before, between and after them in the array), give
   the same bytes at every level and however the ropes are split; the
   near ones are touched. */
static void test_ropes_far_colliders_same_bytes(void)
{
    enum { R = 70, P = 10, FAR = 40, FRAMES = 40 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    hf_collider near_[2], all[FAR + 2];
    hf_rope_params p;
    tr_set s[3];
    int k, f, r, c, lv, n, same = 1, touching = 0;
    for (k = 0; k < 3; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    tr_scalp(R, P, 0.2f, 0.0f, rest, root, nrm, tan);
    memset(near_, 0, sizeof near_);
    near_[0].type = HF_COLLIDER_SPHERE;
    near_[0].radius = 0.097f;
    near_[1].type = HF_COLLIDER_CAPSULE;
    near_[1].a[0] = -0.15f; near_[1].a[1] = -0.15f; near_[1].a[2] = 0.05f;
    near_[1].b[0] = 0.15f; near_[1].b[1] = -0.15f; near_[1].b[2] = -0.05f;
    near_[1].radius = 0.06f;
    for (c = n = 0; c < FAR + 2; ++c) {
        hf_collider *o = all + c;
        if (c == 7 || c == 23) { /* the near ones, among the far */
            *o = near_[n++];
            continue;
        }
        memset(o, 0, sizeof *o);
        o->type = c % 3 ? HF_COLLIDER_CAPSULE : HF_COLLIDER_SPHERE;
        o->a[0] = 3.0f * cosf(0.3f * c);
        o->a[1] = 0.5f * sinf(0.7f * c);
        o->a[2] = 3.0f * sinf(0.3f * c);
        o->b[0] = o->a[0] + 0.3f;
        o->b[1] = o->a[1] - 0.2f;
        o->b[2] = o->a[2];
        o->radius = 0.05f + 0.01f * (c % 5);
    }
    for (lv = 0; lv < 4; ++lv) {
        hf_rope_params_init(&p);
        p.simd = tr_levels[lv];
        for (k = 0; k < 3; ++k)
            hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
        for (f = 0; f < FRAMES; ++f) {
            const float dx = 0.08f * sinf(0.2f * (float)f);
            float moved[3 * R];
            for (r = 0; r < 3 * R; ++r)
                moved[r] = root[r] + (r % 3 == 0 ? dx : 0.0f);
            for (k = 0; k < 3; ++k)
                hf_ropes_set_roots(&s[k].ro, 0, R, moved, nrm, tan, 0);
            CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, R, 1.0f / 60.0f, &p,
                                       near_, 2),
                         HF_OK);
            CHECK_EQ_INT(hf_ropes_step(&s[1].ro, 0, R, 1.0f / 60.0f, &p,
                                       all, FAR + 2),
                         HF_OK);
            hf_ropes_step(&s[2].ro, 0, 33, 1.0f / 60.0f, &p, all, FAR + 2);
            hf_ropes_step(&s[2].ro, 33, R - 33, 1.0f / 60.0f, &p, all,
                          FAR + 2);
            same &= tr_same(&s[0].ro, &s[1].ro, 1);
            same &= tr_same(&s[0].ro, &s[2].ro, 1);
        }
        for (r = 0; r < R * P; ++r)
            for (c = 0; c < 2; ++c) {
                const float q[3] = {s[0].ro.x[r], s[0].ro.y[r], s[0].ro.z[r]};
                if (r >= R && tr_dist_seg(q, &near_[c]) <
                                  near_[c].radius + p.collision_margin + 1e-4)
                    ++touching;
            }
    }
    CHECK(same);
    CHECK(touching > 40);
    for (k = 0; k < 3; ++k) CHECK(tr_finite(&s[k].ro));
    for (k = 0; k < 3; ++k) tr_close(&s[k]);
}

/* Hair on a head that swings over a 24-proxy body, its proxies
   overlapping at the joints, for 600 frames: the ropes stay inextensible,
   no point ends a step inside any proxy (but where the proxy holds the
   rope's root, and is shrunk for it), many rest on them; and for the
   first 60 frames every level gives the scalar bytes. */
static void test_ropes_body_proxies(void)
{
    enum { R = 150, P = 12, FRAMES = 600, NSET = 4 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], moved[3 * R], st, worst_st = 0;
    double worst_in = -1.0;
    hf_collider col[25];
    hf_rope_params p;
    tr_set s[NSET];
    int k, f, r, c, ncol, held = 0, same = 1, touching = 0, roots_in = 0;
    for (k = 0; k < NSET; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    tr_scalp(R, P, 0.3f, 0.0f, rest, root, nrm, tan);
    hf_rope_params_init(&p);
    p.local_stiffness_root = 0.2f;
    for (k = 0; k < NSET; ++k)
        hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
    for (f = 0; f < FRAMES; ++f) {
        /* the head (and its hair) swings 0.16 m, the body stays */
        const float dx = 0.08f * sinf(6.2831853f * (float)f / 60.0f);
        memset(col, 0, sizeof col);
        col[0].type = HF_COLLIDER_SPHERE;
        col[0].a[0] = dx;
        col[0].radius = 0.097f;
        ncol = 1 + tr_body(col + 1, 0.0f);
        for (r = 0; r < 3 * R; ++r)
            moved[r] = root[r] + (r % 3 == 0 ? dx : 0.0f);
        for (k = 0; k < (f < 60 ? NSET : 1); ++k) {
            hf_rope_params pl = p;
            pl.simd = k == 0 ? HF_SIMD_SCALAR : tr_levels[k - 1];
            hf_ropes_set_roots(&s[k].ro, 0, R, moved, nrm, tan, 0);
            CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, R, 1.0f / 60.0f, &pl, col,
                                       ncol),
                         HF_OK);
            if (k > 0) same &= tr_same(&s[0].ro, &s[k].ro, 1);
        }
        hf_ropes_max_stretch(&s[0].ro, 0, R, &st);
        worst_st = st > worst_st ? st : worst_st;
        hf_ropes_roots_inside(&s[0].ro, 0, R, &held);
        roots_in = held > roots_in ? held : roots_in;
        for (r = R; r < R * P; ++r) /* every non-root point */
            for (c = 0; c < ncol; ++c) {
                hf_ropes_roots_inside(&s[0].ro, r % R, 1, &held);
                if (held) continue;
                const float q[3] = {s[0].ro.x[r], s[0].ro.y[r], s[0].ro.z[r]};
                const double in = col[c].radius - tr_dist_seg(q, &col[c]);
                worst_in = in > worst_in ? in : worst_in;
                if (f == FRAMES - 1 && c > 0 && in > -p.collision_margin - 1e-4)
                    ++touching;
            }
    }
    CHECK(same);
    CHECK(worst_st <= 1e-4f);
    CHECK(worst_in < 0.0);
    CHECK(touching > 50);
    CHECK(roots_in < R / 10); /* a few roots on the chin's proxy */
    CHECK(tr_finite(&s[0].ro));
    for (k = 0; k < NSET; ++k) tr_close(&s[k]);
}

/* Hair draped over a joint, two capsules that overlap, comes to rest
   there: after it settles no point moves faster than 1 mm/s. */
static void test_ropes_resting_on_joint(void)
{
    enum { R = 24, P = 12 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], a[3 * R * P], b[3 * R * P];
    hf_collider col[2];
    hf_rope_params p;
    tr_set s;
    double vmax = 0.0;
    int r, f;
    if (!tr_open(&s, R, P)) { CHECK(0); return; }
    memset(col, 0, sizeof col);
    col[0].type = col[1].type = HF_COLLIDER_CAPSULE;
    col[0].a[0] = -0.25f; /* an arm, and a forearm bent down at the elbow */
    col[1].b[0] = 0.18f;
    col[1].b[1] = -0.18f;
    col[0].radius = col[1].radius = 0.05f;
    for (r = 0; r < R; ++r) {
        root[3 * r] = -0.04f + 0.08f * (float)(r % 6) / 5.0f;
        root[3 * r + 1] = 0.06f;
        root[3 * r + 2] = -0.03f + 0.06f * (float)(r / 6) / 3.0f;
        nrm[3 * r] = 0.0f; nrm[3 * r + 1] = 1.0f; nrm[3 * r + 2] = 0.0f;
        tan[3 * r] = 1.0f; tan[3 * r + 1] = 0.0f; tan[3 * r + 2] = 0.0f;
        { /* tilted, half toward each capsule, so that they fall on it */
            const float dir[3] = {r % 2 ? 0.7f : -0.7f, 0.7f, 0.14f};
            tr_straight(rest, r, P, root + 3 * r, dir, 0.25f);
        }
    }
    hf_rope_params_init(&p);
    CHECK_EQ_INT(hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0),
                 HF_OK);
    for (f = 0; f < 360; ++f) {
        if (f >= 300) tr_snapshot(&s.ro, a);
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &p, col, 2),
                     HF_OK);
        if (f >= 300) {
            double v;
            tr_snapshot(&s.ro, b);
            v = tr_max_move(a, b, (size_t)R * P) * 60.0;
            vmax = v > vmax ? v : vmax;
        }
    }
    /* it lies on both: some points touch each capsule */
    {
        int on[2] = {0, 0}, c, j;
        for (r = 0; r < R; ++r)
            for (j = 1; j < P; ++j)
                for (c = 0; c < 2; ++c)
                    if (tr_dist_seg(b + 3 * ((size_t)r * P + j), &col[c]) <
                        0.05 + 0.002 + 1e-4)
                        ++on[c];
        CHECK(on[0] > 10 && on[1] > 10);
    }
    CHECK(vmax < 1e-3);
    tr_close(&s);
}

/* More colliders within reach than the broadphase holds per tile (200
   small spheres among the ropes) and more than it lists per chunk: the
   levels agree to the byte, the ropes keep their lengths. A bad collider
   far down a long array is still refused, with nothing written. */
static void test_ropes_crowded_colliders(void)
{
    enum { R = 40, P = 8, N = 200, NSET = 4 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], st;
    static hf_collider col[N];
    hf_rope_params p;
    tr_set s[NSET];
    uint32_t seed = 99u;
    int k, f, c, same = 1;
    for (k = 0; k < NSET; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    tr_scalp(R, P, 0.15f, 0.0f, rest, root, nrm, tan);
    for (c = 0; c < N; ++c) {
#define T_RND()                                                                \
    ((float)((seed = seed * 1664525u + 1013904223u) >> 8) * (1.0f / 16777216.0f))
        memset(col + c, 0, sizeof col[c]);
        col[c].type = c % 2 ? HF_COLLIDER_CAPSULE : HF_COLLIDER_SPHERE;
        for (k = 0; k < 3; ++k) {
            col[c].a[k] = 0.5f * T_RND() - 0.25f;
            col[c].b[k] = col[c].a[k] + 0.02f * T_RND();
        }
        col[c].a[1] += 0.1f;
        col[c].b[1] += 0.1f;
        col[c].radius = 0.004f + 0.004f * T_RND();
#undef T_RND
    }
    for (k = 0; k < NSET; ++k)
        hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
    for (f = 0; f < 20; ++f)
        for (k = 0; k < NSET; ++k) {
            hf_rope_params_init(&p);
            p.simd = k == 0 ? HF_SIMD_SCALAR : tr_levels[k - 1];
            p.wind[0] = 4.0f;
            CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, R, 1.0f / 60.0f, &p, col,
                                       N),
                         HF_OK);
            if (k > 0) same &= tr_same(&s[0].ro, &s[k].ro, 1);
        }
    CHECK(same);
    hf_ropes_max_stretch(&s[0].ro, 0, R, &st);
    CHECK(st <= 1e-4f);
    CHECK(tr_finite(&s[0].ro));
    {
        const size_t bytes = s[0].size;
        unsigned char *snap = (unsigned char *)malloc(bytes);
        hf_ropes keep = s[0].ro;
        if (snap) {
            memcpy(snap, s[0].mem, bytes);
            col[N - 3].radius = -0.01f;
            CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, R, 1.0f / 60.0f, &p, col,
                                       N),
                         HF_ERROR_BAD_PARAMETER);
            col[N - 3].radius = 0.01f;
            col[N - 2].b[2] = TB_NAN;
            CHECK_EQ_INT(hf_ropes_step(&s[0].ro, 0, R, 1.0f / 60.0f, &p, col,
                                       N),
                         HF_ERROR_NON_FINITE);
            CHECK(memcmp(snap, s[0].mem, bytes) == 0);
            CHECK(memcmp(&keep, &s[0].ro, sizeof keep) == 0);
            free(snap);
        }
    }
    for (k = 0; k < NSET; ++k) tr_close(&s[k]);
}

/* Ropes rooted inside a neck capsule, at the nape, where a shoulder's
   capsule overlaps it below the head: the neck is shrunk for each rope
   to its root's distance from the axis, and the rope hangs into the
   crease that the shoulder's capsule makes with that thinner neck. At
   rest (a static body, 5 s) no point moves more than 1 mm/s (a point
   that chose between the two ends of the crease by rounding flipped
   about its parent, 2 cm in a step, for ever: 1-14 m/s), the ropes keep
   their lengths, no point is inside a collider as its rope sees it, and
   the scalar kernels and the widest agree to the byte. */
static void test_ropes_nape_crease(void)
{
    enum { R = 8, P = 32, NSET = 2 };
    static const float xz[R][2] = {
        {0.015f, -0.011f},  {0.0175f, -0.015f}, {0.02f, -0.011f},
        {0.0225f, -0.015f}, {0.025f, -0.015f},  {0.015f, -0.015f},
        {0.015f, -0.005f},  {0.02f, -0.015f}};
    static float rest[3 * R * P], a[3 * R * P], b[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], st;
    hf_collider col[3];
    hf_rope_params p;
    tr_set s[NSET];
    double vmax = 0.0, worst_in = 0.0;
    int r, f, k, c, j, same = 1;
    for (k = 0; k < NSET; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    memset(col, 0, sizeof col);
    col[0].type = HF_COLLIDER_SPHERE; /* the head, just inside its skin */
    col[0].radius = 0.097f;
    col[1].type = col[2].type = HF_COLLIDER_CAPSULE;
    col[1].a[1] = -0.09f; /* the neck */
    col[1].b[1] = -0.17f;
    col[1].a[2] = col[1].b[2] = -0.01f;
    col[1].radius = 0.055f;
    col[2].a[0] = 0.05f; /* a trapezius, deep into the neck */
    col[2].a[1] = -0.19f;
    col[2].b[0] = 0.17f;
    col[2].b[1] = -0.23f;
    col[2].a[2] = col[2].b[2] = -0.02f;
    col[2].radius = 0.06f;
    for (r = 0; r < R; ++r) {
        const float x = xz[r][0], z = xz[r][1];
        float *o = root + 3 * r, *n = nrm + 3 * r, *t = tan + 3 * r, d;
        o[0] = x; /* on the 0.1 m head, under it */
        o[1] = -sqrtf(0.01f - x * x - z * z);
        o[2] = z;
        for (k = 0; k < 3; ++k) n[k] = o[k] / 0.1f;
        t[0] = 1.0f - n[0] * n[0];
        t[1] = -n[0] * n[1];
        t[2] = -n[0] * n[2];
        d = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        for (k = 0; k < 3; ++k) t[k] /= d;
        tr_straight(rest, r, P, o, n, 0.3f);
    }
    tr_rest_all(s, NSET, rest, root, nrm, tan);
    hf_rope_params_init(&p); /* scene V's ropes */
    p.global_stiffness_root = 0.2f;
    p.local_stiffness_root = 0.3f;
    p.root_stiffness = 0.5f;
    for (f = 0; f < 360; ++f) {
        for (k = 0; k < NSET; ++k) {
            p.simd = k == 0 ? HF_SIMD_SCALAR : HF_SIMD_AUTO;
            if (k == 0 && f >= 300) tr_snapshot(&s[0].ro, a);
            CHECK_EQ_INT(hf_ropes_step(&s[k].ro, 0, R, 1.0f / 60.0f, &p, col,
                                       3),
                         HF_OK);
        }
        same &= tr_same(&s[0].ro, &s[1].ro, 1);
        tr_snapshot(&s[0].ro, b);
        if (f >= 300) {
            const double v = tr_max_move(a, b, (size_t)R * P) * 60.0;
            vmax = v > vmax ? v : vmax;
        }
        for (r = 0; r < R; ++r) /* inside a collider as the rope sees it */
            for (c = 0; c < 3; ++c) {
                const double dr = tr_dist_seg(root + 3 * r, &col[c]);
                const double rr = col[c].radius + 0.002;
                const double eff =
                    dr < col[c].radius * 0.9999 - 0.002 - 1e-6 ? dr : rr;
                for (j = 1; j < P; ++j) {
                    const double in =
                        eff - tr_dist_seg(b + 3 * (r * P + j), &col[c]);
                    worst_in = in > worst_in ? in : worst_in;
                }
            }
    }
    hf_ropes_max_stretch(&s[0].ro, 0, R, &st);
    if (getenv("TR_VERBOSE"))
        printf("nape crease: %g m/s, stretch %g, deepest %g m\n", vmax,
               (double)st, worst_in);
    CHECK(same);
    CHECK(vmax < 1e-3);
    CHECK(st <= 1e-4f);
    CHECK(worst_in <= 1e-5);
    for (k = 0; k < NSET; ++k) tr_close(&s[k]);
}

/* Hair lying in the crease between two overlapping capsules, where
   the ways out of each lead into the other: two capsules crossing, one
   lower (an X), and two rising apart from where they meet (a V, as an
   arm against the chest). Ropes fall into the crease from a grid of
   roots above it and come to rest there: under 1 mm/s over the last
   second of ten, the levels agree to the byte, no stretch, no point
   inside either capsule. */
static void test_ropes_resting_in_crease(void)
{
    enum { G = 7, R = G * G, P = 32, NSET = 2 };
    static float rest[3 * R * P], a[3 * R * P], b[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], st;
    hf_collider col[2];
    hf_rope_params p;
    tr_set s[NSET];
    int shape, r, f, k;
    for (shape = 0; shape < 2; ++shape) {
        double vmax = 0.0, worst_in = 0.0;
        int same = 1;
        for (k = 0; k < NSET; ++k)
            if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
        memset(col, 0, sizeof col);
        col[0].type = col[1].type = HF_COLLIDER_CAPSULE;
        if (shape == 0) { /* X */
            col[0].a[0] = -0.2f;
            col[0].b[0] = 0.2f;
            col[1].a[2] = -0.2f;
            col[1].b[2] = 0.2f;
            col[1].a[1] = col[1].b[1] = -0.03f;
            col[0].radius = col[1].radius = 0.05f;
        } else { /* V */
            col[0].a[0] = -0.15f;
            col[1].a[0] = 0.15f;
            col[0].a[1] = col[1].a[1] = 0.1f;
            col[0].radius = col[1].radius = 0.04f;
        }
        for (r = 0; r < R; ++r) {
            float *o = root + 3 * r, *n = nrm + 3 * r, *t = tan + 3 * r, d;
            o[0] = -0.06f + 0.12f * (float)(r % G) / (float)(G - 1);
            o[1] = 0.12f;
            o[2] = -0.06f + 0.12f * (float)(r / G) / (float)(G - 1);
            n[0] = 0.3f; /* leaning: the rope falls when let go */
            n[1] = 1.0f;
            n[2] = 0.2f;
            d = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (k = 0; k < 3; ++k) n[k] /= d;
            tr_tangent_yz(n, t);
            tr_straight(rest, r, P, o, n, 0.3f);
        }
        tr_rest_all(s, NSET, rest, root, nrm, tan);
        hf_rope_params_init(&p);
        for (f = 0; f < 600; ++f)
            same &= tr_pair_step(s, f, 540, &p, col, 2, a, b, &vmax,
                                 &worst_in);
        hf_ropes_max_stretch(&s[0].ro, 0, R, &st);
        if (getenv("TR_VERBOSE"))
            printf("crease %s: %g m/s, stretch %g, deepest %g m\n",
                   shape ? "V" : "X", vmax, (double)st, worst_in);
        CHECK(same);
        CHECK(vmax < 1e-3);
        CHECK(st <= 1e-4f);
        CHECK(worst_in <= 0.0);
        for (k = 0; k < NSET; ++k) tr_close(&s[k]);
    }
}

/* A rope grown straight through a capsule (from under a head through a
   trapezius proxy, as on scene V's body) with global stiffness 0.3:
   draped first (global stiffness off) and that pose taken as its rest
   shape (hf_ropes_rest_from_pose), it comes to rest on the capsule. With
   the grown rest shape it never does (docs/physics.md, "A rest shape
   through a collider"). Scalar and SIMD give the same bytes. */
static void test_ropes_rest_through_collider(void)
{
    enum { R = 4, P = 32, NSET = 2 };
    static float rest[3 * R * P], a[3 * R * P], b[3 * R * P];
    const float root0[3] = {-0.02539167f, -0.09609173f, -0.01102916f};
    float root[3 * R], nrm[3 * R], tan[3 * R], st;
    hf_collider col;
    hf_rope_params p;
    tr_set s[NSET];
    double vmax = 0.0, worst_in = 0.0;
    int r, f, k, same = 1;
    for (k = 0; k < NSET; ++k)
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
    memset(&col, 0, sizeof col);
    col.type = HF_COLLIDER_CAPSULE;
    col.a[0] = -0.05f;
    col.a[1] = -0.19f;
    col.a[2] = -0.02f;
    col.b[0] = -0.17f;
    col.b[1] = -0.23f;
    col.b[2] = -0.02f;
    col.radius = 0.06f;
    for (r = 0; r < R; ++r) { /* four roots 2 mm apart, radial normals */
        float *o = root + 3 * r, *n = nrm + 3 * r, *t = tan + 3 * r, d;
        for (k = 0; k < 3; ++k) o[k] = root0[k];
        o[2] -= 0.002f * (float)r;
        d = sqrtf(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
        for (k = 0; k < 3; ++k) n[k] = o[k] / d;
        tr_tangent_yz(n, t);
        tr_straight(rest, r, P, o, n, 0.3f);
    }
    tr_rest_all(s, NSET, rest, root, nrm, tan);
    hf_rope_params_init(&p);
    p.local_stiffness_root = 0.3f;
    p.root_stiffness = 0.5f;
    p.damping = 0.1f;
    for (f = 0; f < 720; ++f) {
        if (f == 120) { /* draped: the rest shape, then the stiffness */
            for (k = 0; k < NSET; ++k)
                CHECK_EQ_INT(hf_ropes_rest_from_pose(&s[k].ro, 0, R), HF_OK);
            p.global_stiffness_root = 0.3f;
            p.damping = 0.0f; /* the default */
        }
        same &= tr_pair_step(s, f, 660, &p, &col, 1, a, b, &vmax,
                             &worst_in);
    }
    hf_ropes_max_stretch(&s[0].ro, 0, R, &st);
    if (getenv("TR_VERBOSE"))
        printf("rest through a collider, draped: %g m/s, stretch %g, "
               "deepest %g m\n", vmax, (double)st, worst_in);
    CHECK(same);
    CHECK(vmax < 1e-3);
    CHECK(st <= 1e-4f);
    CHECK(worst_in <= 0.0);
    for (k = 0; k < NSET; ++k) tr_close(&s[k]);
}

/* 6. ropes: collisions that never stretch: its tests, in the order they run */
#define T_CONTACT_TESTS(X)                                                     \
    X(test_ropes_capsule_keeps_length)                                         \
    X(test_ropes_roots_inside_colliders)                                       \
    X(test_ropes_collision_soak)                                               \
    X(test_ropes_copy_range)                                                   \
    X(test_ropes_many_colliders)                                               \
    X(test_ropes_far_colliders_same_bytes)                                     \
    X(test_ropes_body_proxies)                                                 \
    X(test_ropes_resting_on_joint)                                             \
    X(test_ropes_nape_crease)                                                  \
    X(test_ropes_resting_in_crease)                                            \
    X(test_ropes_rest_through_collider)                                        \
    X(test_ropes_crowded_colliders)

/* ---- ropes: hair-hair interaction on a grid ------------------------------ */

typedef struct tg_grid {
    hf_grid g;
    void *mem;
} tg_grid;

static int tg_open(tg_grid *t, int n)
{
    size_t size;
    memset(t, 0, sizeof *t);
    if (hf_grid_memory_size(n, &size) != HF_OK) return 0;
    t->mem = malloc(size);
    return t->mem && hf_grid_init(&t->g, n, t->mem, size) == HF_OK;
}

/* The most non-root points in one cube of side `cell` (a 96^3 block
   about the origin), and the mean distance of the tips from the head's
   centre. */
static int tg_crowd(const hf_ropes *ro, float cell, double *tip_dist)
{
    enum { N = 96 };
    static unsigned short cnt[N * N * N];
    const size_t R = (size_t)ro->rope_count;
    int most = 0, j;
    size_t r;
    double d = 0.0;
    memset(cnt, 0, sizeof cnt);
    for (j = 1; j < ro->points; ++j)
        for (r = 0; r < R; ++r) {
            const size_t i = (size_t)j * R + r;
            const int x = (int)floorf(ro->x[i] / cell) + N / 2;
            const int y = (int)floorf(ro->y[i] / cell) + N / 2;
            const int z = (int)floorf(ro->z[i] / cell) + N / 2;
            if (x < 0 || y < 0 || z < 0 || x >= N || y >= N || z >= N)
                continue;
            if (++cnt[(z * N + y) * N + x] > most)
                most = cnt[(z * N + y) * N + x];
            if (j == ro->points - 1)
                d += sqrt((double)ro->x[i] * ro->x[i] +
                          (double)ro->y[i] * ro->y[i] +
                          (double)ro->z[i] * ro->z[i]);
        }
    *tip_dist = d / (double)R;
    return most;
}

/* Frames of hair on a head (a grid each frame: built, applied, stepped). */
static void tg_run(tr_set *s, tg_grid *t, const hf_rope_params *p,
                   const hf_collider *col, int frames)
{
    const int R = s->ro.rope_count;
    int f;
    for (f = 0; f < frames; ++f) {
        CHECK_EQ_INT(hf_grid_build(&t->g, &s->ro, R, 0, t->g.resolution),
                     HF_OK);
        CHECK_EQ_INT(hf_ropes_apply_grid(&s->ro, 0, R, 1.0f / 60.0f, p,
                                         &t->g),
                     HF_OK);
        CHECK_EQ_INT(hf_ropes_step(&s->ro, 0, R, 1.0f / 60.0f, p, col, 1),
                     HF_OK);
    }
}

/* Long hair falling onto a head: with volume (the default) the densest
   2 cm cells hold fewer points than without, the tips stand further out,
   and the ropes keep their lengths either way. */
static void test_grid_volume_spreads_hair(void)
{
    enum { R = 400, P = 16 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R], st[2];
    hf_collider head;
    hf_rope_params p[2];
    tr_set s[2];
    tg_grid t;
    double tips[2];
    int crowd[2], k;
    if (!tg_open(&t, 24)) { CHECK(0); return; }
    tr_scalp(R, P, 0.25f, 0.0f, rest, root, nrm, tan);
    tr_head_sphere(&head);
    for (k = 0; k < 2; ++k) {
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
        hf_rope_params_init(&p[k]);
        if (k == 1) { /* off: a literal 0 */
            p[k].volume = 0.0f;
            p[k].explicit_zero = HF_ROPE_ZERO_VOLUME;
        }
        hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
        tg_run(&s[k], &t, &p[k], &head, 120);
        crowd[k] = tg_crowd(&s[k].ro, 0.02f, &tips[k]);
        hf_ropes_max_stretch(&s[k].ro, 0, R, &st[k]);
        CHECK(tr_finite(&s[k].ro));
    }
    CHECK(crowd[0] < 0.8 * crowd[1]);
    CHECK(tips[0] > tips[1] + 0.005);
    CHECK(st[0] <= 1e-4f && st[1] <= 1e-4f);
    for (k = 0; k < 2; ++k) tr_close(&s[k]);
    free(t.mem);
}

/* Hair tossed by a turbulent wind (a random acceleration per rope): with
   friction the tips of neighbouring ropes move more alike than without. */
static void test_grid_friction_moves_hair_together(void)
{
    enum { R = 300, P = 12 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    hf_collider head;
    tr_set s[2];
    tg_grid t;
    double spread[2] = {0.0, 0.0};
    int k, f;
    if (!tg_open(&t, 16)) { CHECK(0); return; }
    tr_scalp(R, P, 0.2f, 0.0f, rest, root, nrm, tan);
    tr_head_sphere(&head);
    for (k = 0; k < 2; ++k) {
        hf_rope_params p;
        if (!tr_open(&s[k], R, P)) { CHECK(0); return; }
        hf_rope_params_init(&p);
        p.turbulence = 20.0f;
        p.turbulence_frequency = 3.0f;
        p.friction = k == 1 ? 0.0f : 0.8f;
        p.volume = 0.0f;
        p.explicit_zero = HF_ROPE_ZERO_VOLUME | HF_ROPE_ZERO_FRICTION;
        hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
        for (f = 0; f < 90; ++f) {
            tg_run(&s[k], &t, &p, &head, 1);
            if (f >= 30) { /* tip velocity against the neighbours' mean */
                const size_t base = (size_t)(P - 1) * R;
                int r;
                for (r = 1; r + 1 < R; ++r) {
                    const hf_ropes *o = &s[k].ro;
                    double d = 0.0;
                    int c;
                    for (c = 0; c < 3; ++c) {
                        const float *x = c == 0 ? o->x : c == 1 ? o->y : o->z;
                        const float *q = c == 0 ? o->px : c == 1 ? o->py : o->pz;
                        double v = x[base + r] - q[base + r];
                        double m = 0.5 * ((x[base + r - 1] - q[base + r - 1]) +
                                          (x[base + r + 1] - q[base + r + 1]));
                        d += (v - m) * (v - m);
                    }
                    spread[k] += sqrt(d);
                }
            }
        }
    }
    CHECK(spread[0] < 0.8 * spread[1]);
    for (k = 0; k < 2; ++k) tr_close(&s[k]);
    free(t.mem);
}

/* The grid's layers built in pieces, the ropes pushed and stepped in
   ranges, and every kernel level: the same bytes as one call. An odd
   count of ropes: the splat takes ropes r and r + R / 2 in turn, at
   every width, then the last one alone. */
static void test_grid_splits_same_bytes(void)
{
    enum { R = 251, P = 12, FRAMES = 30, NSET = 5 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    hf_collider head;
    tr_set s[NSET];
    tg_grid t[NSET];
    int k, f, same = 1, grids_same = 1;
    tr_scalp(R, P, 0.22f, 0.0f, rest, root, nrm, tan);
    tr_head_sphere(&head);
    for (k = 0; k < NSET; ++k) {
        if (!tr_open(&s[k], R, P) || !tg_open(&t[k], 20)) { CHECK(0); return; }
        hf_ropes_set_rest(&s[k].ro, 0, R, rest, 0, root, nrm, tan, 0);
    }
    for (f = 0; f < FRAMES; ++f) {
        float moved[3 * R];
        int r;
        for (r = 0; r < 3 * R; ++r)
            moved[r] = root[r] + (r % 3 == 0 ? 0.05f * sinf(0.3f * f) : 0.0f);
        for (k = 0; k < NSET; ++k) {
            hf_rope_params p;
            hf_rope_params_init(&p);
            p.friction = 0.5f;
            p.simd = k < 2 ? HF_SIMD_SCALAR : tr_levels[k - 2];
            t[k].g.simd = p.simd; /* the splat's kernels too */
            hf_ropes_set_roots(&s[k].ro, 0, R, moved, nrm, tan, 0);
            if (k == 1) { /* in pieces, the middle first: a piece that
                             wrote past its layers would spoil it */
                hf_grid_build(&t[k].g, &s[k].ro, R, 10, 1);
                hf_grid_build(&t[k].g, &s[k].ro, R, 0, 10);
                hf_grid_build(&t[k].g, &s[k].ro, R, 11, 9);
                hf_ropes_apply_grid(&s[k].ro, 100, R - 100, 1.0f / 60.0f, &p,
                                    &t[k].g);
                hf_ropes_apply_grid(&s[k].ro, 0, 100, 1.0f / 60.0f, &p,
                                    &t[k].g);
                hf_ropes_step(&s[k].ro, 0, 37, 1.0f / 60.0f, &p, &head, 1);
                hf_ropes_step(&s[k].ro, 37, R - 37, 1.0f / 60.0f, &p, &head,
                              1);
            } else {
                hf_grid_build(&t[k].g, &s[k].ro, R, 0, 20);
                hf_ropes_apply_grid(&s[k].ro, 0, R, 1.0f / 60.0f, &p,
                                    &t[k].g);
                hf_ropes_step(&s[k].ro, 0, R, 1.0f / 60.0f, &p, &head, 1);
            }
            if (k > 0) {
                same &= tr_same(&s[0].ro, &s[k].ro, 1);
                grids_same &= memcmp(t[0].g.node, t[k].g.node,
                                     sizeof(float) * 4u * 20u * 20u * 20u) ==
                              0;
            }
        }
    }
    CHECK(same);
    CHECK(grids_same);
    for (k = 0; k < NSET; ++k) {
        tr_close(&s[k]);
        free(t[k].mem);
    }
}

/* Bad input to the grid calls is refused with nothing written; an empty
   grid moves nothing; rest_from_pose keeps the pose. */
static void test_grid_bad_input(void)
{
    enum { R = 20, P = 6 };
    static float rest[3 * R * P];
    float root[3 * R], nrm[3 * R], tan[3 * R];
    static float before[6 * R * P], after[6 * R * P];
    hf_rope_params p;
    tr_set s;
    tg_grid t;
    size_t size;
    hf_grid *g = NULL;
    unsigned char small[64];
    int k;
    if (!tr_open(&s, R, P) || !tg_open(&t, 8)) { CHECK(0); return; }
    tr_scalp(R, P, 0.1f, 0.0f, rest, root, nrm, tan);
    hf_ropes_set_rest(&s.ro, 0, R, rest, 0, root, nrm, tan, 0);
    hf_rope_params_init(&p);
    CHECK_EQ_INT(hf_grid_memory_size(3, &size), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_grid_memory_size(HF_GRID_MAX_RESOLUTION + 1, &size),
                 HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_grid_memory_size(8, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_grid_create(2, NULL, &g), HF_ERROR_BAD_COUNT);
    CHECK(g == NULL);
    CHECK_EQ_INT(hf_grid_init(&t.g, 8, small, sizeof small),
                 HF_ERROR_BUFFER_TOO_SMALL);
    CHECK_EQ_INT(hf_grid_create(8, NULL, &g), HF_OK);
    hf_grid_destroy(g);
    hf_grid_destroy(NULL);
    /* an empty grid moves nothing */
    tr_snapshot(&s.ro, before);
    memcpy(before + 3 * R * P, s.ro.px, sizeof(float) * R * P);
    CHECK_EQ_INT(hf_ropes_apply_grid(&s.ro, 0, R, 1.0f / 60.0f, &p, &t.g),
                 HF_OK);
    CHECK(memcmp(before + 3 * R * P, s.ro.px, sizeof(float) * R * P) == 0);
    /* refused: nothing written */
    CHECK_EQ_INT(hf_grid_build(&t.g, &s.ro, R, 0, 9), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_grid_build(&t.g, &s.ro, R, -1, 2), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_grid_build(&t.g, &s.ro, R + 1, 0, 8), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_grid_build(&t.g, NULL, R, 0, 8), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_grid_build(NULL, &s.ro, R, 0, 8), HF_ERROR_NULL_POINTER);
    t.g.simd = HF_SIMD_AVX512 + 1; /* not a level */
    CHECK_EQ_INT(hf_grid_build(&t.g, &s.ro, R, 0, 8), HF_ERROR_BAD_PARAMETER);
    t.g.simd = -1;
    CHECK_EQ_INT(hf_grid_build(&t.g, &s.ro, R, 0, 8), HF_ERROR_BAD_PARAMETER);
    t.g.simd = 0;
    for (k = 0; k < 4 * 8 * 8 * 8; ++k) CHECK(t.g.node[k] == 0.0f);
    CHECK_EQ_INT(hf_grid_build(&t.g, &s.ro, R, 0, 8), HF_OK);
    {
        hf_rope_params bad = p;
        bad.volume = -1.0f;
        CHECK_EQ_INT(hf_ropes_apply_grid(&s.ro, 0, R, 1.0f / 60.0f, &bad,
                                         &t.g),
                     HF_ERROR_BAD_PARAMETER);
        bad.volume = (float)NAN;
        CHECK_EQ_INT(hf_ropes_apply_grid(&s.ro, 0, R, 1.0f / 60.0f, &bad,
                                         &t.g),
                     HF_ERROR_NON_FINITE);
        bad = p;
        bad.friction = 1.5f;
        CHECK_EQ_INT(hf_rope_params_validate(&bad, NULL),
                     HF_ERROR_BAD_PARAMETER);
        CHECK_EQ_INT(hf_ropes_apply_grid(&s.ro, 0, R, 1.0f / 60.0f, &bad,
                                         &t.g),
                     HF_ERROR_BAD_PARAMETER);
        bad = p;
        bad.volume = 101.0f;
        CHECK_EQ_INT(hf_ropes_step(&s.ro, 0, R, 1.0f / 60.0f, &bad, NULL, 0),
                     HF_ERROR_BAD_PARAMETER);
    }
    CHECK_EQ_INT(hf_ropes_apply_grid(&s.ro, 0, R, 0.0f, &p, &t.g),
                 HF_ERROR_BAD_TIME_STEP);
    CHECK_EQ_INT(hf_ropes_apply_grid(&s.ro, 0, R + 1, 1.0f / 60.0f, &p, &t.g),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_apply_grid(&s.ro, 0, R, 1.0f / 60.0f, &p, NULL),
                 HF_ERROR_NULL_POINTER);
    CHECK(memcmp(before + 3 * R * P, s.ro.px, sizeof(float) * R * P) == 0);
    /* defaults: volume 1, friction 0.2; each off with its bit */
    {
        hf_rope_params d, z;
        memset(&z, 0, sizeof z);
        hf_rope_params_init(&d);
        CHECK(d.volume == 1.0f && d.friction == 0.2f);
        z.explicit_zero = HF_ROPE_ZERO_VOLUME | HF_ROPE_ZERO_FRICTION;
        CHECK_EQ_INT(hf_rope_params_validate(&z, NULL), HF_OK);
    }
    /* the pose as rest: a step at rest changes nothing */
    CHECK_EQ_INT(hf_ropes_rest_from_pose(NULL, 0, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_rest_from_pose(&s.ro, 0, R + 1), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_rest_from_pose(&s.ro, 0, R), HF_OK);
    tr_snapshot(&s.ro, after);
    CHECK(tr_max_move(before, after, (size_t)R * P) < 1e-6);
    tr_close(&s);
    free(t.mem);
}

static void test_bad_rope_params(void)
{
    hf_rope_params p, b;
    hf_diag d;
    float *fields[19];
    int i, nf = 0;
    hf_rope_params_init(&p);
    CHECK_EQ_INT(hf_rope_params_validate(&p, &d), HF_OK);
    CHECK_EQ_INT(hf_rope_params_validate(NULL, &d), HF_ERROR_NULL_POINTER);
    b = p;
    fields[nf++] = &b.gravity[0]; fields[nf++] = &b.gravity[2];
    fields[nf++] = &b.wind[1]; fields[nf++] = &b.turbulence;
    fields[nf++] = &b.turbulence_frequency; fields[nf++] = &b.damping;
    fields[nf++] = &b.time_scale; fields[nf++] = &b.substep;
    fields[nf++] = &b.max_dt; fields[nf++] = &b.ftl_damping;
    fields[nf++] = &b.root_stiffness; fields[nf++] = &b.global_stiffness_root;
    fields[nf++] = &b.global_stiffness_tip; fields[nf++] = &b.local_stiffness_root;
    fields[nf++] = &b.local_stiffness_tip; fields[nf++] = &b.collision_margin;
    fields[nf++] = &b.mode_blend_time;
    for (i = 0; i < nf; ++i) {
        float keep = *fields[i];
        *fields[i] = TB_NAN;
        CHECK_EQ_INT(hf_rope_params_validate(&b, &d), HF_ERROR_NON_FINITE);
        CHECK(d.field != NULL);
        *fields[i] = TB_INF;
        CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_NON_FINITE);
        *fields[i] = -1e30f; /* below every range */
        CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
        *fields[i] = keep;
    }
    /* zero is the default, never an error; negative is */
    b = p; b.time_scale = 0.0f; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_OK);
    b = p; b.max_dt = 0.0f; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_OK);
    b = p; b.max_substeps = 0; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_OK);
    b = p; b.max_dt = -1.0f; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
    b = p; b.max_substeps = -3; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
    b = p; b.max_substeps = 0x7fffffff; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
    b = p; b.iterations = -1; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
    b = p; b.iterations = 0x7fffffff; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
    b = p; b.solver = 2; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
    b = p; b.gravity[1] = 2e4f; CHECK_EQ_INT(hf_rope_params_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
}

static void test_bad_ropes_memory_and_limits(void)
{
    size_t sz = 12345;
    hf_ropes r, sentinel;
    unsigned char mem[64];
    hf_ropes *out = (hf_ropes *)&sz;
    t_counter cnt;
    hf_allocator a = t_counting(&cnt);
    CHECK_EQ_INT(hf_ropes_memory_size(1, 2, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_memory_size(0, 2, &sz), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_ropes_memory_size(-1, 2, &sz), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_ropes_memory_size(1, 1, &sz), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_ropes_memory_size(1, -0x7fffffff - 1, &sz), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(sz, 12345);
    /* counts near INT_MAX: the byte size overflows size_t (64-bit: 2^31 *
       2^31 * 40 bytes) or is refused as too large, never wrapped */
    CHECK(hf_ropes_memory_size(0x7fffffff, 0x7fffffff, &sz) == HF_ERROR_OVERFLOW);
    CHECK_EQ_INT(sz, 12345);
    {
        hf_result rr = hf_ropes_memory_size(0x7fffffff, 2, &sz);
        CHECK(rr == HF_OK || rr == HF_ERROR_OVERFLOW);
        if (rr == HF_OK) CHECK(sz > (size_t)0x7fffffff * 40u);
    }
    memset(&sentinel, 0xA5, sizeof sentinel);
    r = sentinel;
    CHECK_EQ_INT(hf_ropes_init(&r, 1, 2, NULL, 1000), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_init(NULL, 1, 2, mem, sizeof mem), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_init(&r, 0, 2, mem, sizeof mem), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_ropes_init(&r, 1, 2, mem, sizeof mem), HF_ERROR_BUFFER_TOO_SMALL);
    CHECK_EQ_INT(hf_ropes_init(&r, 0x7fffffff, 0x7fffffff, mem, (size_t)-1),
                 HF_ERROR_OVERFLOW);
    CHECK(memcmp(&r, &sentinel, sizeof r) == 0);
    /* create: OOM, absurd counts, nothing leaked, *out untouched */
    cnt.fail_after = 0;
    CHECK_EQ_INT(hf_ropes_create(4, 4, &a, &out), HF_ERROR_OUT_OF_MEMORY);
    CHECK(out == (hf_ropes *)&sz);
    cnt.fail_after = -1;
    CHECK_EQ_INT(hf_ropes_create(0x7fffffff, 0x7fffffff, &a, &out), HF_ERROR_OVERFLOW);
    CHECK(out == (hf_ropes *)&sz);
    CHECK_EQ_INT(hf_ropes_create(4, 4, &a, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    hf_ropes_destroy(NULL);
}

static void test_bad_ropes_set_rest_and_roots(void)
{
    tb_ropes t;
    int k;
    tb_ropes_open(&t);
    for (k = 0; k < 2; ++k) {
        /* k = 0: hf_ropes_set_rest, k = 1: hf_ropes_set_roots */
#define TB_SET(rest, pos, nrm, tan, stride, first, count, code)                \
    TB_ROPES_FAIL(t,                                                           \
                  k == 0 ? hf_ropes_set_rest(&t.r, first, count, rest, 0, pos, \
                                             nrm, tan, stride)                 \
                         : hf_ropes_set_roots(&t.r, first, count, pos, nrm,    \
                                              tan, stride),                    \
                  code)
        TB_SET(t.rest, NULL, t.nrm, t.tan, 0, 0, 3, HF_ERROR_NULL_POINTER);
        TB_SET(t.rest, t.pos, NULL, t.tan, 0, 0, 3, HF_ERROR_NULL_POINTER);
        TB_SET(t.rest, t.pos, t.nrm, NULL, 0, 0, 3, HF_ERROR_NULL_POINTER);
        TB_SET(t.rest, t.pos, t.nrm, t.tan, 0, 1, 3, HF_ERROR_BAD_RANGE);
        TB_SET(t.rest, t.pos, t.nrm, t.tan, 0, -1, 1, HF_ERROR_BAD_RANGE);
        TB_SET(t.rest, t.pos, t.nrm, t.tan, 0, 3, 0x7fffffff, HF_ERROR_BAD_RANGE);
        TB_SET(t.rest, t.pos, t.nrm, t.tan, 8, 0, 3, HF_ERROR_BAD_STRIDE);
        TB_SET(t.rest, t.pos, t.nrm, t.tan, -12, 0, 3, HF_ERROR_BAD_STRIDE);
        t.pos[4] = TB_NAN;
        TB_SET(t.rest, t.pos, t.nrm, t.tan, 0, 0, 3, HF_ERROR_NON_FINITE);
        t.pos[4] = 2e6f; /* beyond HF_ROPE_MAX_COORD */
        TB_SET(t.rest, t.pos, t.nrm, t.tan, 0, 0, 3, HF_ERROR_BAD_PARAMETER);
        t.pos[4] = 0.0f;
        t.tan[8] = TB_INF;
        TB_SET(t.rest, t.pos, t.nrm, t.tan, 0, 0, 3, HF_ERROR_NON_FINITE);
        t.tan[8] = 0.0f;
        t.nrm[3] = t.nrm[4] = t.nrm[5] = 0.0f;
        TB_SET(t.rest, t.pos, t.nrm, t.tan, 0, 0, 3, HF_ERROR_DEGENERATE);
        t.nrm[4] = 1.0f;
        CHECK_EQ_INT(hf_ropes_set_rest(NULL, 0, 3, t.rest, 0, t.pos, t.nrm, t.tan, 0),
                     HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_ropes_set_roots(NULL, 0, 3, t.pos, t.nrm, t.tan, 0),
                     HF_ERROR_NULL_POINTER);
#undef TB_SET
    }
    /* rest positions: NULL, NaN, stride */
    TB_ROPES_FAIL(t, hf_ropes_set_rest(&t.r, 0, 3, NULL, 0, t.pos, t.nrm, t.tan, 0),
                  HF_ERROR_NULL_POINTER);
    t.rest[20] = -TB_INF;
    TB_ROPES_FAIL(t, hf_ropes_set_rest(&t.r, 0, 3, t.rest, 0, t.pos, t.nrm, t.tan, 0),
                  HF_ERROR_NON_FINITE);
    t.rest[20] = 0.0f;
    TB_ROPES_FAIL(t, hf_ropes_set_rest(&t.r, 0, 3, t.rest, 4, t.pos, t.nrm, t.tan, 0),
                  HF_ERROR_BAD_STRIDE);
    /* a tangent parallel to the normal, and zero: a deterministic
       perpendicular, no NaN */
    t.tan[0] = 0; t.tan[1] = 5; t.tan[2] = 0;
    t.tan[3] = t.tan[4] = t.tan[5] = 0;
    CHECK_EQ_INT(hf_ropes_set_roots(&t.r, 0, 3, t.pos, t.nrm, t.tan, 0), HF_OK);
    {
        hf_rope_params p;
        hf_rope_params_init(&p);
        CHECK_EQ_INT(hf_ropes_step(&t.r, 0, 3, 1.0f / 60.0f, &p, NULL, 0), HF_OK);
        CHECK(tb_finite(t.r.x, 12) && tb_finite(t.r.y, 12) && tb_finite(t.r.z, 12));
    }
    free(t.mem);
}

static void test_bad_ropes_step(void)
{
    tb_ropes t;
    hf_rope_params p;
    hf_collider c;
    float st = -7.0f;
    float out[36];
    tb_ropes_open(&t);
    hf_rope_params_init(&p);
    memset(&c, 0, sizeof c);
    c.type = HF_COLLIDER_SPHERE;
    c.a[1] = 0.2f;
    c.radius = 0.05f;
    /* time steps */
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.0f, &p, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, -0.01f, &p, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, -0.0f, &p, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, TB_NAN, &p, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, TB_INF, &p, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, -TB_INF, &p, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    /* huge: clamped to max_dt, HF_OK, finite */
    CHECK_EQ_INT(hf_ropes_step(&t.r, 0, 3, FLT_MAX, &p, &c, 1), HF_OK);
    CHECK(tb_finite(t.r.x, 12) && tb_finite(t.r.y, 12) && tb_finite(t.r.z, 12));
    CHECK_EQ_INT(hf_ropes_step(&t.r, 0, 3, 1e-30f, &p, &c, 1), HF_OK);
    CHECK(tb_finite(t.r.x, 12) && tb_finite(t.r.y, 12));
    /* the rest */
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, NULL, NULL, 0), HF_ERROR_NULL_POINTER);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, &p, NULL, 1), HF_ERROR_NULL_POINTER);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, &p, &c, -1), HF_ERROR_BAD_COUNT);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 2, 2, 0.01f, &p, NULL, 0), HF_ERROR_BAD_RANGE);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 1, 0x7fffffff, 0.01f, &p, NULL, 0), HF_ERROR_BAD_RANGE);
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, -1, 1, 0.01f, &p, NULL, 0), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_step(NULL, 0, 3, 0.01f, &p, NULL, 0), HF_ERROR_NULL_POINTER);
    p.damping = TB_NAN;
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, &p, NULL, 0), HF_ERROR_NON_FINITE);
    hf_rope_params_init(&p);
    c.radius = TB_NAN;
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, &p, &c, 1), HF_ERROR_NON_FINITE);
    c.radius = -1.0f;
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, &p, &c, 1), HF_ERROR_BAD_PARAMETER);
    c.radius = 0.05f;
    c.a[0] = TB_INF;
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, &p, &c, 1), HF_ERROR_NON_FINITE);
    c.a[0] = 2e6f;
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, &p, &c, 1), HF_ERROR_BAD_PARAMETER);
    c.a[0] = 0.0f;
    c.type = 2;
    TB_ROPES_FAIL(t, hf_ropes_step(&t.r, 0, 3, 0.01f, &p, &c, 1), HF_ERROR_BAD_PARAMETER);
    c.type = HF_COLLIDER_CAPSULE; /* a == b: a zero-length capsule */
    c.b[0] = c.a[0]; c.b[1] = c.a[1]; c.b[2] = c.a[2];
    CHECK_EQ_INT(hf_ropes_step(&t.r, 0, 3, 0.01f, &p, &c, 1), HF_OK);
    CHECK(tb_finite(t.r.x, 12) && tb_finite(t.r.y, 12) && tb_finite(t.r.z, 12));
    /* a collider centred exactly on a particle */
    c.type = HF_COLLIDER_SPHERE;
    c.a[0] = t.r.x[1 * 3 + 0]; c.a[1] = t.r.y[3]; c.a[2] = t.r.z[3];
    CHECK_EQ_INT(hf_ropes_step(&t.r, 0, 3, 0.01f, &p, &c, 1), HF_OK);
    CHECK(tb_finite(t.r.x, 12) && tb_finite(t.r.y, 12) && tb_finite(t.r.z, 12));
    /* mode, reset, stretch, positions */
    TB_ROPES_FAIL(t, hf_ropes_set_mode(&t.r, 0, 3, 2), HF_ERROR_BAD_PARAMETER);
    TB_ROPES_FAIL(t, hf_ropes_set_mode(&t.r, 0, 3, -1), HF_ERROR_BAD_PARAMETER);
    TB_ROPES_FAIL(t, hf_ropes_set_mode(&t.r, 3, 1, 0), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_set_mode(NULL, 0, 1, 0), HF_ERROR_NULL_POINTER);
    TB_ROPES_FAIL(t, hf_ropes_reset(&t.r, 0, 4), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_reset(NULL, 0, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_max_stretch(&t.r, 0, 4, &st), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_ropes_max_stretch(&t.r, 0, 3, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ropes_max_stretch(NULL, 0, 3, &st), HF_ERROR_NULL_POINTER);
    CHECK(st == -7.0f);
    CHECK_EQ_INT(hf_ropes_max_stretch(&t.r, 3, 0, &st), HF_OK);
    CHECK(st == 0.0f);
    TB_FAILS(hf_ropes_get_positions(&t.r, 0, 4, out, 0), HF_ERROR_BAD_RANGE, out, sizeof out);
    TB_FAILS(hf_ropes_get_positions(&t.r, 0, 3, out, 8), HF_ERROR_BAD_STRIDE, out, sizeof out);
    TB_FAILS(hf_ropes_get_positions(&t.r, 0, 3, out, -12), HF_ERROR_BAD_STRIDE, out, sizeof out);
    TB_FAILS(hf_ropes_get_positions(NULL, 0, 3, out, 0), HF_ERROR_NULL_POINTER, out, sizeof out);
    CHECK_EQ_INT(hf_ropes_get_positions(&t.r, 0, 3, NULL, 0), HF_ERROR_NULL_POINTER);
    free(t.mem);
}

/* 6. ropes: hair-hair interaction on a grid: its tests, in the order they run */
#define T_GRID_TESTS(X)                                                        \
    X(test_grid_volume_spreads_hair)                                           \
    X(test_grid_friction_moves_hair_together)                                  \
    X(test_grid_splits_same_bytes)                                             \
    X(test_grid_bad_input)                                                     \
    X(test_bad_rope_params)                                                    \
    X(test_bad_ropes_memory_and_limits)                                        \
    X(test_bad_ropes_set_rest_and_roots)                                       \
    X(test_bad_ropes_step)

/* ==== 7. interpolation and LOD ============================================ */

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
        b[k].length_scale = 1.0f;
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
    b[0].length_scale = b[1].length_scale = b[2].length_scale = 1.0f;
    CHECK_EQ_INT(hf_interpolate(g, 3, b, 0, 3, &ip, out), HF_OK);
    for (i = 0; i < TP * 3; ++i) {
        double direct = w1[0] * g[i] + w1[1] * g[TP * 3 + i] +
                        w1[2] * g[2 * TP * 3 + i];
        CHECK_NEAR(out[i], direct, 1e-5);
        CHECK_NEAR(out[2 * TP * 3 + i],
                   0.25 * out[i] + 0.75 * out[TP * 3 + i], 1e-5);
    }
}

static void test_interp_simd_matches_scalar_reference(void)
{
    /* The documented arithmetic, one float at a time, in the library's
       order; every SIMD level (those this CPU lacks resolve lower) must
       give the same bytes. The point counts put every remainder past the
       groups of 12 (SSE), 24 (AVX2) and 48 (AVX-512) floats, so every tail
       runs (the last vector over the end of the others, or streamed
       past them where P is a multiple of 4 but not of the group, or the
       scalar tail below one vector); clump 0 skips the clump term;
       streaming stores too, into an
       output at 64, 32, 16 and 4 bytes past a 64-byte boundary (whole
       vectors, halves or quarters, and plain stores). make test also
       builds with HF_NO_SIMD. */
    enum { QM = 40, G = 5, N = 40 };
    static const int qs[] = {2, 3, 4, 5, 8, 12, 13, 14, 15, 16, 17, 19,
                             20, 21, 24, 28, 32, 33, 40};
    static const int shifts[] = {0, 8, 4, 1};
    static float outbuf[N * QM * 3 + 32];
    int qi, level, sh;
    float g[G * QM * 3], ref[N * QM * 3], *out;
    hf_strand_binding b[N];
    hf_interp_params ip;
    hf_rng r;
    int s, i, k, Q, cl;
    hf_rng_seed(&r, 77u, 3u);
    for (i = 0; i < G * QM * 3; ++i) g[i] = hf_rng_float(&r) * 2.0f - 1.0f;
    t_random_bindings(b, N, G, &r, 0.5f, 1.0f);
    for (qi = 0; qi < (int)(sizeof qs / sizeof qs[0]); ++qi)
        for (cl = 0; cl < 2 * 5 * 2; ++cl)
        for (sh = 0; sh < (cl >= 10 ? 4 : 1); ++sh) {
            out = (float *)(void *)(((uintptr_t)outbuf + 63u) & ~(uintptr_t)63u) +
                  shifts[sh];
            Q = qs[qi];
            level = cl / 2 % 5; /* 0 (auto), scalar, SSE2, AVX2, AVX-512 */
            memset(&ip, 0, sizeof ip);
            ip.points_per_strand = Q;
            ip.simd = level;
            ip.nontemporal = cl >= 10; /* streaming stores */
            ip.clump = cl % 2 ? 0.35f : 0.0f;
            memset(out, 0, sizeof ref);
            memset(ref, 0, sizeof ref);
            CHECK_EQ_INT(hf_interpolate(g, G, b, 0, N, &ip, out), HF_OK);
            for (s = 0; s < N; ++s) {
                const float *g0 = g + b[s].guide[0] * Q * 3, *g1 = g + b[s].guide[1] * Q * 3;
                const float *g2 = g + b[s].guide[2] * Q * 3;
                const float w0 = b[s].weight[0], w1 = b[s].weight[1], w2 = b[s].weight[2];
                const float sc = b[s].length_scale;
                const float *gn = (w0 >= w1 && w0 >= w2) ? g0 : (w1 >= w2 ? g1 : g2);
                float rb[3];
                for (k = 0; k < 3; ++k)
                    rb[k] = (1.0f - sc) * (w0 * g0[k] + w1 * g1[k] + w2 * g2[k]);
                for (i = 0; i < Q * 3; ++i) {
                    float p = w0 * g0[i] + w1 * g1[i] + w2 * g2[i];
                    float c = ip.clump / (float)(Q - 1) * (float)(i / 3);
                    p = sc * p + rb[i % 3];
                    ref[s * Q * 3 + i] = ip.clump != 0.0f ? p + c * (gn[i] - p) : p;
                }
            }
            CHECK(memcmp(out, ref, sizeof ref) == 0);
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
    b[0].length_scale = 1.0f;
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

static void test_bad_interpolate_and_lod(void)
{
    float g[2 * 3 * 3], out[2 * 3 * 3];
    hf_strand_binding b[2];
    hf_interp_params ip;
    int i;
    for (i = 0; i < 18; ++i) g[i] = (float)i * 0.1f;
    for (i = 0; i < 2; ++i) {
        b[i].guide[0] = 0; b[i].guide[1] = 1; b[i].guide[2] = 1;
        b[i].weight[0] = 0.5f; b[i].weight[1] = 0.25f; b[i].weight[2] = 0.25f;
        b[i].length_scale = 1.0f;
    }
    memset(&ip, 0, sizeof ip);
    ip.points_per_strand = 3;
#define TB_INTERP(guides, gc, first, count, code)                              \
    TB_FAILS(hf_interpolate((guides), (gc), b, (first), (count), &ip, out),    \
             (code), out, sizeof out)
    TB_INTERP(NULL, 2, 0, 2, HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_interpolate(g, 2, NULL, 0, 2, &ip, out), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_interpolate(g, 2, b, 0, 2, NULL, out), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_interpolate(g, 2, b, 0, 2, &ip, NULL), HF_ERROR_NULL_POINTER);
    TB_INTERP(g, 2, -1, 1, HF_ERROR_BAD_RANGE);
    TB_INTERP(g, 2, 0, -1, HF_ERROR_BAD_RANGE);
    TB_INTERP(g, 2, 1, 0x7fffffff, HF_ERROR_BAD_RANGE);
    ip.points_per_strand = 1; TB_INTERP(g, 2, 0, 2, HF_ERROR_BAD_COUNT);
    ip.points_per_strand = HF_MAX_POINTS + 1; TB_INTERP(g, 2, 0, 2, HF_ERROR_BAD_COUNT);
    ip.points_per_strand = 3;
    TB_INTERP(g, 1, 0, 2, HF_ERROR_INDEX_OUT_OF_RANGE);
    b[1].guide[2] = 0xffffffffu; TB_INTERP(g, 2, 0, 2, HF_ERROR_INDEX_OUT_OF_RANGE);
    b[1].guide[2] = 1;
    b[1].weight[1] = TB_NAN; TB_INTERP(g, 2, 0, 2, HF_ERROR_NON_FINITE);
    b[1].weight[1] = 0.25f;
    b[0].length_scale = TB_INF; TB_INTERP(g, 2, 0, 2, HF_ERROR_NON_FINITE);
    b[0].length_scale = 1.0f;
    ip.clump = TB_NAN; TB_INTERP(g, 2, 0, 2, HF_ERROR_NON_FINITE);
    ip.clump = 1.5f; TB_INTERP(g, 2, 0, 2, HF_ERROR_BAD_PARAMETER);
    ip.clump = -0.1f; TB_INTERP(g, 2, 0, 2, HF_ERROR_BAD_PARAMETER);
    ip.clump = 0.0f;
    ip.simd = HF_SIMD_AVX512 + 1; TB_INTERP(g, 2, 0, 2, HF_ERROR_BAD_PARAMETER);
    ip.simd = -1; TB_INTERP(g, 2, 0, 2, HF_ERROR_BAD_PARAMETER);
    ip.simd = 0;
    ip.nontemporal = 3; TB_INTERP(g, 2, 0, 2, HF_ERROR_BAD_PARAMETER);
    ip.nontemporal = -1; TB_INTERP(g, 2, 0, 2, HF_ERROR_BAD_PARAMETER);
    ip.nontemporal = 0;
    /* NaN guide points: never NaN in the output */
    g[4] = TB_NAN;
    tb_fill(out, sizeof out);
    {
        hf_result r = hf_interpolate(g, 2, b, 0, 2, &ip, out);
        CHECK(r < 0 ? tb_untouched(out, sizeof out) : tb_finite(out, 18));
    }
    g[4] = 0.4f;
#undef TB_INTERP
    /* LOD helpers: total functions, never NaN */
    CHECK_EQ_INT(hf_lod_strand_count(100, TB_NAN), 0);
    CHECK_EQ_INT(hf_lod_strand_count(100, -TB_INF), 0);
    CHECK_EQ_INT(hf_lod_strand_count(100, TB_INF), 100);
    CHECK_EQ_INT(hf_lod_strand_count(-5, 0.5f), 0);
    CHECK_EQ_INT(hf_lod_strand_count(0x7fffffff, 1.0f), 0x7fffffff);
    CHECK(hf_lod_strand_count(0x7fffffff, 0.999999f) <= 0x7fffffff);
    CHECK(hf_lod_width_scale(0x7fffffff, 1) > 1.0f && t_is_finite(hf_lod_width_scale(0x7fffffff, 1)));
    CHECK(hf_lod_width_scale(-1, -1) == 1.0f);
    CHECK(hf_lod_from_distance(TB_NAN, 1.0f, 10.0f) == 1.0f);
    CHECK(hf_lod_from_distance(5.0f, TB_NAN, 10.0f) == 1.0f);
    CHECK(hf_lod_from_distance(5.0f, 1.0f, TB_INF) == 1.0f);
    CHECK(hf_lod_from_distance(-1.0f, 1.0f, 10.0f) == 1.0f);
    CHECK(t_is_finite(hf_lod_from_distance(5.0f, 0.0f, 10.0f)));
    CHECK(t_is_finite(hf_lod_from_distance(FLT_MAX, FLT_MAX, FLT_MAX)));
}

/* round(lod * total) exactly above 2^24 strands too: float arithmetic
   was off by a few and gave the whole total for lod < 1. */
static void test_lod_strand_count_exact(void)
{
    CHECK_EQ_INT(hf_lod_strand_count(100000007, 0.5f), 50000004);
    CHECK_EQ_INT(hf_lod_strand_count(2147483647, 0.99999994f), 2147483519);
    CHECK_EQ_INT(hf_lod_strand_count(16777217, 0.25f), 4194304);
    CHECK_EQ_INT(hf_lod_strand_count(33554433, 1e-30f), 1);
    CHECK_EQ_INT(hf_lod_strand_count(1000, 0.0005f), 1);
    CHECK_EQ_INT(hf_lod_strand_count(1000, 0.0015f), 2);
    CHECK_EQ_INT(hf_lod_strand_count(7, 1.0f), 7);
}

/* 7. interpolation and LOD: its tests, in the order they run */
#define T_INTERP_TESTS(X)                                                      \
    X(test_interp_on_guide_equals_guide)                                       \
    X(test_interp_linear_in_barycentrics)                                      \
    X(test_interp_simd_matches_scalar_reference)                               \
    X(test_interp_length_scale_and_clump)                                      \
    X(test_interp_errors_write_nothing)                                        \
    X(test_lod_counts_and_widths_exact)                                        \
    X(test_bad_interpolate_and_lod)                                            \
    X(test_lod_strand_count_exact)

/* ==== 8. ribbons ========================================================== */

static void test_half_widths_every_p(void)
{
    /* A call's half widths and t (hf__half_widths, four points a vector
       for the linear taper) are the scalar formula's values for every P,
       each step rounded to float as written (volatile: no contraction),
       and its cap is HF_MAX_ABS over the largest of them and 1 */
    hf_rng rng;
    int P, j, pw;
    hf_rng_seed(&rng, 5, 5);
    for (pw = 0; pw < 2; ++pw)
        for (P = 2; P <= HF_MAX_POINTS; ++P) {
            static float hw[HF_MAX_POINTS], tt[HF_MAX_POINTS];
            hf_ribbon_params p = t_rparams();
            float m = 1.0f, cap;
            p.points_per_strand = P;
            p.root_width = 4.0f * hf_rng_float(&rng);
            p.tip_width = 4.0f * hf_rng_float(&rng);
            p.width_scale = 0.1f + 2.0f * hf_rng_float(&rng);
            p.taper_power = pw ? 2.5f : 1.0f;
            cap = hf__half_widths(&p, hw, tt);
            for (j = 0; j < P; ++j) {
                volatile float t = (float)j / (float)(P - 1), f, a, b, h;
                f = pw && j < P - 1 ? (float)pow((double)t, 2.5) : t;
                a = (1.0f - f) * p.root_width;
                b = f * p.tip_width;
                h = 0.5f * p.width_scale;
                h = h * (a + b);
                CHECK(hw[j] == h && tt[j] == t);
                m = h > m ? h : m;
            }
            CHECK(cap == HF_MAX_ABS / m);
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
    /* a view_dir whose square underflows is a direction all the same: 2^-100
       times the one above gives its bytes (a power of two scales exactly) */
    {
        static t_rvert w[3 * TP * 2];
        hf_ribbon_params q = p;
        hf_ribbon_output ow = t_interleaved(w);
        float pt[TP * 4];
        int k;
        for (k = 0; k < 3; ++k) q.view_dir[k] = ldexpf(p.view_dir[k], -100);
        CHECK(hf__dot3(q.view_dir, q.view_dir) == 0.0f);
        CHECK_EQ_INT(hf_ribbons(&st, 0, 3, &q, &ow), HF_OK);
        CHECK(memcmp(w, v, sizeof(t_rvert) * 3 * TP * 2) == 0);
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, 1, &q, pt), HF_OK);
        q.view_dir[0] = q.view_dir[1] = q.view_dir[2] = 0.0f;
        CHECK_EQ_INT(hf_ribbons(&st, 0, 3, &q, &ow), HF_ERROR_DEGENERATE);
    }
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

static void test_ribbons_nonfinite_strand_collapses(void)
{
    /* strand 1 has a NaN and strand 2 an infinite point: both collapse to
       zero-width ribbons at the origin; strand 0 is untouched by them */
    float pts[3 * TP * 3], pa[3 * TP * 4];
    t_rvert v[3 * TP * 2], ref[TP * 2];
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output o = t_interleaved(v);
    int i, k;
    t_make_guides(pts, 3);
    pts[(TP + 3) * 3 + 1] = (float)NAN;
    pts[(2 * TP + 7) * 3] = (float)INFINITY;
    memset(&st, 0, sizeof st);
    st.points = pts;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &o), HF_OK);
    memcpy(ref, v, sizeof ref);
    CHECK_EQ_INT(hf_ribbons(&st, 0, 3, &p, &o), HF_OK);
    CHECK_EQ_INT(hf_ribbon_points(&st, 0, 3, &p, pa), HF_OK);
    CHECK(memcmp(ref, v, sizeof ref) == 0);
    for (i = 0; i < 3 * TP * 2; ++i)
        for (k = 0; k < 15; ++k) CHECK(t_is_finite((&v[i].pos[0])[k]));
    for (i = TP * 2; i < 3 * TP * 2; ++i)
        CHECK(v[i].pos[0] == 0.0f && v[i].pos[1] == 0.0f && v[i].pos[2] == 0.0f);
    for (i = TP * 4; i < 3 * TP * 4; ++i) CHECK(pa[i] == 0.0f);
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

/* nontemporal 0 (by size): a call that writes more than
   HF_STREAM_MIN_VERTEX_BYTES of vertices or points, or HF_STREAM_MIN_BYTES
   of strand points, streams, a smaller one does not; either way the
   bytes are those of streaming (1) and of ordinary stores (2), for
   ribbons (the 36-byte vertex, which streams through the stage), points
   and interpolation, whole and split in two calls below the threshold.
   Bytes around the output stay. */
static void test_streaming_by_size(void)
{
    enum { Q = 16, G = 40 };
    const size_t vmin = HF_STREAM_MIN_VERTEX_BYTES, smin = HF_STREAM_MIN_BYTES;
    /* strands whose output just passes the threshold, per kind */
    const int nr = (int)(vmin / (2u * Q * 36u)) + 8,
              np = (int)(vmin / (Q * 16u)) + 8, ni = (int)(smin / (Q * 12u)) + 8;
    const size_t big = (vmin > smin ? vmin : smin) + 64u * 1024u;
    float *pts = (float *)malloc(sizeof(float) * 3u * Q * (size_t)np);
    float *guides = (float *)malloc(sizeof(float) * 3u * Q * G);
    hf_strand_binding *b =
        (hf_strand_binding *)malloc(sizeof(hf_strand_binding) * (size_t)ni);
    unsigned char *buf[3], *at[3];
    hf_ribbon_strands st;
    hf_ribbon_params rp = t_rparams();
    hf_interp_params ip;
    hf_rng r;
    int i, k, kind, split;
    CHECK((size_t)nr * 2 * Q * 36 > vmin && (size_t)np * Q * 16 > vmin &&
          (size_t)ni * Q * 12 > smin);
    for (k = 0; k < 3; ++k) buf[k] = (unsigned char *)malloc(big + 128);
    if (!pts || !guides || !b || !buf[0] || !buf[1] || !buf[2]) {
        CHECK(0);
        goto done;
    }
    hf_rng_seed(&r, 23u, 0u);
    for (i = 0; i < 3 * Q * np; ++i) pts[i] = hf_rng_float(&r) - 0.5f;
    for (i = 0; i < 3 * Q * G; ++i) guides[i] = hf_rng_float(&r) - 0.5f;
    t_random_bindings(b, ni, G, &r, 0.9f, 0.0f);
    memset(&st, 0, sizeof st);
    st.points = pts;
    rp.points_per_strand = Q;
    memset(&ip, 0, sizeof ip);
    ip.points_per_strand = Q;
    for (kind = 0; kind < 3; ++kind)
        for (split = 1; split <= 2; ++split) {
            const int n = kind == 0 ? nr : kind == 1 ? np : ni;
            const size_t min = kind == 2 ? smin : vmin;
            for (k = 0; k < 3; ++k) { /* by size, streaming, ordinary */
                /* 64-byte aligned plus 4: the stage's unaligned ends */
                unsigned char *o = at[k] =
                    buf[k] + ((64u - ((uintptr_t)buf[k] & 63u)) & 63u) + 4;
                const hf_ribbon_output out = t_packed36(o);
                float *const o4 = (float *)(void *)o;
                int part;
                memset(buf[k], 0x5a, big + 128);
                rp.nontemporal = ip.nontemporal = k;
                for (part = 0; part < split; ++part) {
                    /* the whole, or its halves */
                    const int f0 = part ? n / 2 : 0,
                              c = split == 1 ? n : part ? n - n / 2 : n / 2;
                    CHECK_EQ_INT(kind == 0 ? hf_ribbons(&st, f0, c, &rp, &out)
                                 : kind == 1
                                     ? hf_ribbon_points(&st, f0, c, &rp, o4)
                                     : hf_interpolate(guides, G, b, f0, c, &ip, o4),
                                 HF_OK);
                }
            }
            /* the output (at most 9 KiB past the threshold) and 4 bytes
               before it */
            CHECK(memcmp(at[0] - 4, at[1] - 4, min + 16384u) == 0);
            CHECK(memcmp(at[0] - 4, at[2] - 4, min + 16384u) == 0);
            CHECK(at[0][-1] == 0x5a && at[0][min + 16380u] == 0x5a);
        }
done:
    for (k = 0; k < 3; ++k) free(buf[k]);
    free(pts);
    free(guides);
    free(b);
}

/* Streaming stores (hf_ribbon_params.nontemporal) give the same bytes:
   through the stage for an interleaved buffer the vertex fills exactly,
   at byte offsets 0 to 32 of a buffer aligned to 64 (the copy's
   unaligned ends, and its 32-byte stores at AVX2), at every level (the
   generic loop's stage and the AVX2 run's), across range splits;
   with ordinary stores when the streams leave a gap (no colour) or split
   into separate buffers. Bytes around the output stay. */
static void test_ribbons_nontemporal(void)
{
    enum { N = 9, V = sizeof(t_rvert), BYTES = N * TP * 2 * V };
    float *pts = (float *)malloc(sizeof(float) * N * TP * 3);
    unsigned char *a0 = (unsigned char *)malloc(BYTES + 128);
    unsigned char *b0 = (unsigned char *)malloc(BYTES + 128);
    unsigned char *a = a0 + ((64u - ((uintptr_t)a0 & 63u)) & 63u);
    unsigned char *b = b0 + ((64u - ((uintptr_t)b0 & 63u)) & 63u);
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output o;
    hf_rng r;
    int i, off, gap, split, level;
    hf_rng_seed(&r, 19u, 0u);
    for (i = 0; i < N * TP * 3; ++i) pts[i] = hf_rng_float(&r) - 0.5f;
    memset(&st, 0, sizeof st);
    st.points = pts;
    for (level = HF_SIMD_SCALAR; level <= HF_SIMD_AVX512; ++level)
        for (gap = 0; gap < 2; ++gap)
            for (off = 0; off <= 32; off += 4)
                for (split = 1; split <= 2; ++split) {
                    unsigned char *buf[2];
                    int k;
                    buf[0] = a;
                    buf[1] = b;
                    for (k = 0; k < 2; ++k) {
                        unsigned char *d = buf[k] + off;
                        memset(buf[k], 0x5a, BYTES + 64);
                        memset(&o, 0, sizeof o);
                        o.position.data = d;
                        o.tangent.data = d + 12;
                        o.texcoord.data = d + 24;
                        o.color.data = gap ? NULL : (void *)(d + 36);
                        o.color3d.data = d + 52;
                        o.position.stride = o.tangent.stride =
                            o.texcoord.stride = o.color.stride =
                                o.color3d.stride = V;
                        p.nontemporal = k ? 1 : 2; /* streaming, ordinary */
                        p.simd = level;
                        if (split == 1) {
                            CHECK_EQ_INT(hf_ribbons(&st, 0, N, &p, &o), HF_OK);
                        } else {
                            CHECK_EQ_INT(hf_ribbons(&st, 0, 4, &p, &o), HF_OK);
                            CHECK_EQ_INT(hf_ribbons(&st, 4, N - 4, &p, &o),
                                         HF_OK);
                        }
                    }
                    CHECK(memcmp(a, b, BYTES + 64) == 0);
                }
    free(pts);
    free(a0);
    free(b0);
}

/* The packed float vertex, 36 bytes (position, tangent, texcoord) or 24
   (position, tangent), at b, with an origin and scale */
static hf_ribbon_output t_packed_run(unsigned char *b, int bytes)
{
    hf_ribbon_output o = t_packed36(b);
    if (bytes == 24) {
        o.texcoord.data = NULL;
        o.position.stride = o.tangent.stride = 24;
    }
    o.position_origin[0] = 0.25f;
    o.position_scale = 2.0f;
    return o;
}

/* A packed float vertex streamed (nontemporal 1) gives the bytes of
   ordinary stores at the scalar level, at every level: whole groups of
   eight points go out as whole lines where the output is aligned to
   them (AVX-512; P a multiple of 16 with the frame in registers), the
   stage takes the rest. The 36- and 24-byte vertices, P a multiple of
   16, of 8 and neither, the output at byte offsets
   aligned to a line and not, range splits whose first strand starts a
   line and not, perspective and orthographic, strand UVs and widths,
   strands with a zero-length segment or a NaN near the root and near
   the tip. Bytes around stay. */
static void test_ribbons_streamed_lines(void)
{
    enum { N = 7, PM = 32, BYTES = N * PM * 2 * 36 };
    static const int Ps[5] = {8, 16, 24, 32, 13}, offs[4] = {0, 64, 4, 36};
    static const int cuts[3][2] = {{N, N}, {3, N}, {1, 4}};
    float *pts = (float *)malloc(sizeof(float) * N * PM * 3);
    unsigned char *ref0 = (unsigned char *)malloc(BYTES + 192);
    unsigned char *got0 = (unsigned char *)malloc(BYTES + 192);
    unsigned char *ref = ref0 + ((64u - ((uintptr_t)ref0 & 63u)) & 63u);
    unsigned char *got = got0 + ((64u - ((uintptr_t)got0 & 63u)) & 63u);
    float uv[2 * N], width[N];
    hf_ribbon_strands st;
    hf_rng r;
    int pi, oi, ci, vb, ortho, level, i;
    hf_rng_seed(&r, 23u, 0u);
    for (i = 0; i < N * PM * 3; ++i) pts[i] = hf_rng_float(&r) - 0.5f;
    for (i = 0; i < N; ++i) {
        uv[2 * i] = hf_rng_float(&r);
        uv[2 * i + 1] = hf_rng_float(&r);
        width[i] = 0.5f + hf_rng_float(&r);
    }
    memset(&st, 0, sizeof st);
    st.points = pts;
    st.root_uv = uv;
    st.width = width;
    for (pi = 0; pi < 5; ++pi) {
        const int P = Ps[pi];
        /* strand 2: a zero-length segment; strand 5: a NaN; strands 4
           and 3 the same at their tip (past the first sixteen points
           where P is 32) */
        memcpy(pts + (2 * P + 4) * 3, pts + (2 * P + 3) * 3, 12);
        pts[(5 * P + 1) * 3 + 1] = (float)NAN;
        memcpy(pts + (4 * P + P - 2) * 3, pts + (4 * P + P - 3) * 3, 12);
        pts[(3 * P + P - 1) * 3] = (float)NAN;
        for (vb = 24; vb <= 36; vb += 12)
            for (ortho = 0; ortho < 2; ++ortho)
                for (oi = 0; oi < 4; ++oi) {
                    hf_ribbon_params p = t_rparams();
                    hf_ribbon_output o = t_packed_run(ref + offs[oi], vb);
                    p.points_per_strand = P;
                    p.orthographic = ortho;
                    p.view_dir[2] = -1.0f;
                    memset(ref, 0x5a, BYTES + 128);
                    p.simd = HF_SIMD_SCALAR;
                    p.nontemporal = 2;
                    CHECK_EQ_INT(hf_ribbons(&st, 0, N, &p, &o), HF_OK);
                    p.nontemporal = 1;
                    for (ci = 0; ci < 3; ++ci)
                        for (level = HF_SIMD_SSE2; level <= HF_SIMD_AVX512;
                             ++level) {
                            const int a = cuts[ci][0], b = cuts[ci][1];
                            memset(got, 0x5a, BYTES + 128);
                            o = t_packed_run(got + offs[oi], vb);
                            p.simd = level;
                            CHECK_EQ_INT(hf_ribbons(&st, 0, a, &p, &o), HF_OK);
                            CHECK_EQ_INT(hf_ribbons(&st, a, b - a, &p, &o),
                                         HF_OK);
                            CHECK_EQ_INT(hf_ribbons(&st, b, N - b, &p, &o),
                                         HF_OK);
                            CHECK(memcmp(got, ref, BYTES + 128) == 0);
                        }
                }
    }
    free(pts);
    free(ref0);
    free(got0);
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
    /* streams that share bytes between vertices: the tangent of vertex v
       on the position of v + 1; the colour over the position array */
    {
        hf_ribbon_output x;
        float *f = &v[0].pos[0];
        int level;
        memset(&x, 0, sizeof x);
        x.position.data = f;
        x.position.stride = 12;
        x.tangent.data = f + 3;
        x.tangent.stride = 12;
        for (level = HF_SIMD_SCALAR; level <= HF_SIMD_AVX512; ++level) {
            b = p;
            b.simd = level;
            CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &b, &x), HF_ERROR_BAD_STRIDE);
        }
        x.tangent.data = NULL;
        x.color.data = f + 2 * TP; /* packed: 16 bytes a vertex */
        CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &x), HF_ERROR_BAD_STRIDE);
        CHECK(memcmp(v, keep, sizeof v) == 0);
        /* strides of 8 and 16 that interleave without sharing a byte are
           allowed; moved by two bytes they share */
        memset(&x, 0, sizeof x);
        x.color3d.data = f;
        x.color3d.format = HF_FORMAT_F16;
        x.color3d.stride = 8;
        x.texcoord.data = (unsigned char *)(void *)f + 4;
        x.texcoord.format = HF_FORMAT_UNORM8;
        x.texcoord.stride = 16;
        CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &x), HF_OK);
        memcpy(v, keep, sizeof v);
        x.texcoord.data = (unsigned char *)(void *)f + 2;
        CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &x), HF_ERROR_BAD_STRIDE);
        CHECK(memcmp(v, keep, sizeof v) == 0);
        /* strides of 1031 and 1033 bytes (coprime): the position of
           vertex 5 on the color3d of vertex 0 is refused; four bytes on,
           no two vertices meet */
        {
            static unsigned char big[24 * 1024];
            memset(&x, 0, sizeof x);
            x.position.data = big;
            x.position.stride = 1031;
            x.color3d.data = big + 5163;
            x.color3d.format = HF_FORMAT_F16;
            x.color3d.stride = 1033;
            CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &x), HF_ERROR_BAD_STRIDE);
            x.color3d.data = big + 5167;
            CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &x), HF_OK);
        }
        /* inside one vertex is allowed: the later stream's bytes win */
        memset(&x, 0, sizeof x);
        x.position.data = f;
        x.position.stride = 24;
        x.tangent.data = f + 2;
        x.tangent.stride = 24;
        CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &x), HF_OK);
        memcpy(v, keep, sizeof v);
    }
    st.points = NULL;
    CHECK_EQ_INT(hf_ribbon_points(&st, 0, 1, &p, &v[0].pos[0]),
                 HF_ERROR_NULL_POINTER);
    CHECK(memcmp(v, keep, sizeof v) == 0);
}

static void test_ribbons_leading_tangent(void)
{
    /* the first three points coincide: their tangent is the first one the
       strand has, (1, 0, 0), not the (0, 1, 0) of a strand with none */
    float pts[TP * 3];
    t_rvert v[TP * 2];
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output o = t_interleaved(v);
    int j;
    for (j = 0; j < TP; ++j) {
        pts[3 * j] = j < 3 ? 0.0f : 0.1f * (float)(j - 2);
        pts[3 * j + 1] = 0.0f;
        pts[3 * j + 2] = 0.0f;
    }
    memset(&st, 0, sizeof st);
    st.points = pts;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &o), HF_OK);
    for (j = 0; j < TP * 2; ++j)
        CHECK(v[j].tan[0] == 1.0f && v[j].tan[1] == 0.0f && v[j].tan[2] == 0.0f);
}

/* Random strands, some with the cases the SSE kernel leaves to the
   reference (coincident points, a point on the eye, a NaN). */
static void t_random_strands(float *pts, int n, int P, hf_rng *rng)
{
    int s, j, k;
    for (s = 0; s < n; ++s) {
        float *q = pts + (size_t)s * P * 3, dir[3];
        const int kind = (int)hf_rng_below(rng, 8);
        for (k = 0; k < 3; ++k) {
            q[k] = hf_rng_float(rng) * 2.0f - 1.0f;
            dir[k] = hf_rng_float(rng) - 0.5f;
        }
        for (j = 1; j < P; ++j)
            for (k = 0; k < 3; ++k)
                q[3 * j + k] = q[3 * (j - 1) + k] + 0.05f * dir[k] +
                               0.02f * (hf_rng_float(rng) - 0.5f);
        if (kind == 1) memcpy(q + 3, q, 12);             /* leading duplicate */
        if (kind == 2) memcpy(q + 3 * (P - 1), q + 3 * (P - 2), 12); /* tip */
        if (kind == 3) memcpy(q + 3 * (P / 2), q + 3 * (P / 2 - 1), 12);
        if (kind == 4) { q[3 * (P / 2)] = 0.3f; q[3 * (P / 2) + 1] = 1.0f; q[3 * (P / 2) + 2] = 5.0f; }
        if (kind == 5) q[3 * (P - 1) + 1] = (float)NAN;
    }
}

static void test_ribbons_every_level_matches_reference(void)
{
    /* Every P from 2 to 21 (partial groups of four and eight), both camera
       kinds: the four-lane (SSE2 or NEON) and AVX2 frames and every
       level's writer give the
       reference's bytes. A level the CPU or build lacks checks nothing
       more. */
    enum { NS = 40, PM = 21, PW = 19 };
    float pts[NS * PM * 3];
    hf_rng rng;
    int P, s, ortho, kind, handled[2] = {0, 0}, declined[2] = {0, 0};
    hf_rng_seed(&rng, 99, 1);
    for (P = 2; P <= PM; ++P)
        for (ortho = 0; ortho < 2; ++ortho) {
            hf_ribbon_params p = t_rparams();
            p.points_per_strand = P;
            p.orthographic = ortho;
            p.view_dir[0] = 0.1f; p.view_dir[1] = -0.2f; p.view_dir[2] = -1.0f;
            t_random_strands(pts, NS, P, &rng);
            for (s = 0; s < NS; ++s)
                for (kind = 0; kind < 2; ++kind) {
                    const float *q = pts + (size_t)s * P * 3;
                    hf__rframe a, b;
                    int finite = -1, c, j, took = -1;
                    memset(&a, 0, sizeof a);
                    memset(&b, 0, sizeof b);
                    hf__strand_frame_v1(q, P, &p, &a);
#if HF__V4
                    if (kind == 0) took = hf__strand_frame_v4(q, P, &p, &b, &finite);
#endif
#if HF__AVX2
                    if (kind == 1 && hf_simd_resolve(HF_SIMD_AVX2) == HF_SIMD_AVX2)
                        took = hf__strand_frame_v8(q, P, &p, &b, &finite);
#endif
                    if (took < 0) continue; /* not in this build or CPU */
                    if (!took) {
                        ++declined[kind];
                        continue;
                    }
                    ++handled[kind];
                    CHECK_EQ_INT(finite, 1);
                    for (c = 0; c < 3; ++c)
                        for (j = 0; j < P; ++j) {
                            CHECK(memcmp(&a.t[c][4 + j], &b.t[c][4 + j], 4) == 0);
                            CHECK(memcmp(&a.s[c][4 + j], &b.s[c][4 + j], 4) == 0);
                            CHECK(memcmp(&a.p[c][4 + j], &b.p[c][4 + j], 4) == 0);
                        }
                }
        }
    /* both paths of each kernel were exercised */
    if (HF__V4) CHECK(handled[0] > 500 && declined[0] > 50);
    if (HF__AVX2 && hf_simd_resolve(HF_SIMD_AVX2) == HF_SIMD_AVX2)
        CHECK(handled[1] > 500 && declined[1] > 50);
    /* the writers at every level: every format, interleaved streams, P = 7
       and 19 (partial groups) on random frames */
    {
        enum { STRIDE = 64 };
        static unsigned char va[PW * 2 * STRIDE], vb[PW * 2 * STRIDE];
        hf__rconst K;
        hf__rstrand S;
        hf__rout ro;
        /* streams side by side: formats rotating (offsets hold 12, 12, 12,
           16 and 8 bytes), then all floats in the two layouts the writer
           stores as one run (position, tangent and texcoord; position and
           tangent) */
        static const int offs[3][5] = {{0, 12, 24, 36, 52},
                                       {0, 12, 24, 36, 52},
                                       {0, 12, 40, 24, 52}};
        static const int Ps[2] = {7, PW};
        int fmt, q, j, pi, level;
        for (pi = 0; pi < 2; ++pi) {
            hf_ribbon_params p = t_rparams();
            P = Ps[pi];
            p.points_per_strand = P;
            p.alpha_root = 0.9f;
            p.alpha_tip = 0.1f;
            hf__rconst_init(&K, &p);
            t_random_strands(pts, 8, P, &rng);
            for (fmt = 0; fmt < 8; ++fmt)
                for (s = 0; s < 8; ++s) {
                    const int *off = offs[fmt < 6 ? 0 : fmt - 5];
                    hf__rframe fr;
                    const float *qs = pts + (size_t)s * P * 3;
                    /* as hf_ribbons: a strand with a NaN is drawn collapsed */
                    const int fin = hf__points_finite_v1(qs, 3 * P);
                    memset(&fr, 0, sizeof fr);
                    hf__strand_frame_v1(fin ? qs : hf__zero_points, P, &p, &fr);
                    S.uv[0] = hf_rng_float(&rng);
                    S.uv[1] = hf_rng_float(&rng) * 3.0f - 1.0f; /* out of range too */
                    for (j = 0; j < 4; ++j) S.rgba[j] = hf_rng_float(&rng);
                    S.c3x = hf_rng_float(&rng);
                    S.wscale = fin ? 1.0f : 0.0f;
                    memset(&ro, 0, sizeof ro);
                    for (q = 0; q < 5; ++q) {
                        ro.stride[q] = STRIDE;
                        ro.fmt[q] = fmt < 6 ? (fmt + q) % 6 : HF_FORMAT_F32;
                    }
                    ro.origin[0] = 0.1f; ro.origin[1] = -0.2f; ro.origin[2] = 0.3f;
                    ro.inv_scale = 0.5f;
                    memset(va, 0xa5, sizeof va);
                    for (q = 0; q < 5; ++q) ro.base[q] = va + off[q];
                    hf__rout_layout(&ro);
                    hf__ribbon_write_v1(&fr, P, &K, &S, &ro, 0);
                    for (level = HF_SIMD_SSE2; level <= HF_SIMD_AVX512; ++level) {
                        memset(vb, 0xa5, sizeof vb);
                        for (q = 0; q < 5; ++q) ro.base[q] = vb + off[q];
                        hf__rout_layout(&ro);
                        hf__ribbon_write(&fr, P, &K, &S, &ro, 0,
                                         hf__kernels_for(hf__write_widths, level));
                        CHECK(memcmp(va, vb, sizeof va) == 0);
                    }
                }
        }
    }
}

static void test_streams_cross_matches_brute_force(void)
{
    /* hf_ribbons refuses two streams where vertex v of one and vertex
       w != v of the other share a byte (hf__streams_cross: a closed form
       for equal strides, a family of solutions a residue otherwise):
       every answer matches a search over all pairs, for random offsets,
       strides, element sizes and vertex ranges, half of them with equal
       strides */
    hf_rng rng;
    int it, hits = 0, equal = 0;
    hf_rng_seed(&rng, 77, 3);
    for (it = 0; it < 200000; ++it) {
        const size_t sa = 1 + hf_rng_below(&rng, 24),
                     sb = hf_rng_below(&rng, 2) ? sa
                                                : 1 + hf_rng_below(&rng, 24),
                     ea = 1 + hf_rng_below(&rng, (uint32_t)sa),
                     eb = 1 + hf_rng_below(&rng, (uint32_t)sb),
                     v0 = hf_rng_below(&rng, 4), n = hf_rng_below(&rng, 8);
        const uintptr_t a = 4096 + hf_rng_below(&rng, 96),
                        b = 4096 + hf_rng_below(&rng, 96);
        size_t v, w;
        int want = 0;
        for (v = v0; v < v0 + n && !want; ++v)
            for (w = v0; w < v0 + n && !want; ++w) {
                const uintptr_t x = a + v * sa, y = b + w * sb;
                want = v != w && x < y + eb && y < x + ea;
            }
        hits += want;
        equal += sa == sb && want;
        CHECK_EQ_INT(hf__streams_cross(a, sa, ea, b, sb, eb, v0, n), want);
    }
    CHECK(hits > 1000 && equal > 500); /* both answers, both paths */
}

static void test_ribbons_run_layouts_every_level(void)
{
    /* hf_ribbons itself, at every level the CPU runs, in the layouts its
       kernels of their own take: the packed 36-byte vertex (position,
       tangent, texcoord as floats), the same run in a wider vertex with
       colours after it, position with tangent (texcoord elsewhere), and
       the compact vertex (2-byte position and texcoord, 1-byte tangent
       in 15 bytes) in each of its formats, with and without padding. P
       from 2 to 33 (partial groups of four and eight, one and several
       full groups of eight and of sixteen), both camera kinds, strands
       the frames leave to the reference (a NaN point, all points equal,
       one along the view) beside ordinary ones, optional inputs with a
       NaN among them: every level writes the scalar reference's bytes,
       however the range is split, and no byte outside the streams
       changes. */
    enum { NS = 12, PM = 33, VM = 52, NL = 8, BUF = NS * PM * 2 * VM + 64 };
    /* offset and format of position, tangent, texcoord, colour and 3D
       colour (offset -1: none), then the stride */
    static const int lay[NL][11] = {
        {0, HF_FORMAT_F32, 12, HF_FORMAT_F32, 24, HF_FORMAT_F32, -1, 0, -1, 0, 36},
        {0, HF_FORMAT_F32, 12, HF_FORMAT_F32, 24, HF_FORMAT_F32, 36, HF_FORMAT_UNORM8, 40, HF_FORMAT_UNORM8, 44},
        {0, HF_FORMAT_F32, 12, HF_FORMAT_F32, 24, HF_FORMAT_F32, 36, HF_FORMAT_F32, -1, 0, 52},
        {0, HF_FORMAT_F32, 12, HF_FORMAT_F32, 28, HF_FORMAT_F16, 24, HF_FORMAT_UNORM8, -1, 0, 40},
        {0, HF_FORMAT_SNORM16, 12, HF_FORMAT_SNORM8, 6, HF_FORMAT_UNORM16, -1, 0, -1, 0, 16},
        {0, HF_FORMAT_F16, 12, HF_FORMAT_UNORM8, 6, HF_FORMAT_F16, -1, 0, -1, 0, 20},
        {0, HF_FORMAT_UNORM16, 12, HF_FORMAT_SNORM8, 6, HF_FORMAT_SNORM16, -1, 0, -1, 0, 15},
        {4, HF_FORMAT_SNORM16, 16, HF_FORMAT_SNORM8, 10, HF_FORMAT_F16, -1, 0, -1, 0, 24}};
    static const int nc[5] = {3, 3, 3, 4, 2};
    static const int Ps[9] = {2, 7, 8, 9, 16, 17, 24, 32, PM};
    static unsigned char ref[BUF], got[BUF];
    static float pts[NS * PM * 3];
    float uv[2 * NS], col[4 * NS], c3[NS], wid[NS];
    hf_rng rng;
    int L, pi, ortho, s, j, q, level, split, levels = 0;
    hf_rng_seed(&rng, 36, 9);
    for (s = 0; s < NS; ++s) {
        uv[2 * s] = hf_rng_float(&rng);
        uv[2 * s + 1] = hf_rng_float(&rng) * 3.0f - 1.0f; /* out of range too */
        for (j = 0; j < 4; ++j) col[4 * s + j] = hf_rng_float(&rng);
        c3[s] = hf_rng_float(&rng);
        wid[s] = 0.5f + hf_rng_float(&rng);
    }
    uv[3] = NAN;
    col[9] = NAN;
    wid[4] = NAN;
    for (L = 0; L < NL; ++L)
        for (pi = 0; pi < 9; ++pi)
            for (ortho = 0; ortho < 2; ++ortho) {
                const int P = Ps[pi], st = lay[L][10];
                const size_t bytes = (size_t)NS * P * 2 * st;
                unsigned char covered[VM];
                hf_ribbon_params p = t_rparams();
                hf_ribbon_strands sv;
                hf_ribbon_output o;
                hf_stream *sm[5];
                sm[0] = &o.position;
                sm[1] = &o.tangent;
                sm[2] = &o.texcoord;
                sm[3] = &o.color;
                sm[4] = &o.color3d;
                memset(covered, 0, sizeof covered);
                for (q = 0; q < 5; ++q)
                    if (lay[L][2 * q] >= 0)
                        memset(covered + lay[L][2 * q], 1,
                               (size_t)hf_format_bytes(lay[L][2 * q + 1]) * nc[q]);
                t_random_strands(pts, NS, P, &rng);
                /* strand 1: a NaN; 2: one point; 3: along the view */
                pts[(size_t)1 * P * 3 + 3 * (P / 2) + 1] = NAN;
                for (j = 1; j < P; ++j) {
                    memcpy(pts + (size_t)2 * P * 3 + 3 * j,
                           pts + (size_t)2 * P * 3, 12);
                    pts[(size_t)3 * P * 3 + 3 * j + 0] = 0.0f;
                    pts[(size_t)3 * P * 3 + 3 * j + 1] = 0.0f;
                    pts[(size_t)3 * P * 3 + 3 * j + 2] = 4.0f - 0.1f * (float)j;
                }
                memset(pts + (size_t)3 * P * 3, 0, 8);
                pts[(size_t)3 * P * 3 + 2] = 4.0f;
                p.points_per_strand = P;
                p.orthographic = ortho;
                p.eye[0] = 1e-9f; /* strand 3 along the view */
                p.eye[1] = 0.0f;
                p.eye[2] = 6.0f;
                p.view_dir[0] = 0.0f; p.view_dir[1] = 0.0f; p.view_dir[2] = -1.0f;
                p.alpha_root = 0.8f;
                p.alpha_tip = 0.2f;
                memset(&sv, 0, sizeof sv);
                sv.points = pts;
                sv.root_uv = uv;
                sv.color = col;
                sv.color3d_x = c3;
                sv.width = wid;
                for (level = HF_SIMD_SCALAR; level <= HF_SIMD_AVX512; ++level) {
                    unsigned char *buf = level == HF_SIMD_SCALAR ? ref : got;
                    if (hf_simd_resolve(level) != level) continue;
                    for (split = 0; split < 2; ++split) {
                        unsigned char *d = buf + 16;
                        memset(buf, 0xa5, BUF);
                        memset(&o, 0, sizeof o);
                        for (q = 0; q < 5; ++q) {
                            if (lay[L][2 * q] < 0) continue;
                            sm[q]->data = d + lay[L][2 * q];
                            sm[q]->format = lay[L][2 * q + 1];
                            sm[q]->stride = st;
                        }
                        /* compact positions in a box of 2 about the origin */
                        o.position_origin[0] = 0.25f;
                        o.position_scale = 2.0f;
                        p.simd = level;
                        if (!split) {
                            CHECK_EQ_INT(hf_ribbons(&sv, 0, NS, &p, &o), HF_OK);
                        } else {
                            CHECK_EQ_INT(hf_ribbons(&sv, 0, 5, &p, &o), HF_OK);
                            CHECK_EQ_INT(hf_ribbons(&sv, 5, NS - 5, &p, &o),
                                         HF_OK);
                        }
                        if (level == HF_SIMD_SCALAR) break;
                        CHECK(memcmp(ref, got, BUF) == 0);
                        ++levels;
                    }
                    /* padding and the bytes around the vertices keep theirs */
                    for (j = 0; j < NS * P * 2; ++j)
                        for (q = 0; q < st; ++q)
                            if (!covered[q])
                                CHECK(buf[16 + (size_t)j * st + q] == 0xa5);
                    CHECK(buf[16 + bytes] == 0xa5 && buf[15] == 0xa5);
                }
            }
    /* at least SSE2 or NEON took part (every 64-bit build has it) */
    if (HF__SSE || HF__NEON) CHECK(levels > 0);
}

static void test_ribbons_table_layouts(void)
{
    /* Vertices whose streams abut or share a buffer, as compact layouts
       do: every level writes the reference's bytes, and no byte outside
       the streams (padding, gaps, the buffer around them) changes. Each
       layout is (offset, format) per stream, -1 for none, with one stride
       (0: each stream packed in its own part of the buffer). They take
       the register run (9..16 abutting bytes, with and without padding),
       widened copies (3, 6 and 12 bytes followed by a later stream's) and
       exact ones; P = 5, 19 and 40 (past one block of the writer). */
    enum { NL = 8, PM = 40, NS = 3, BUF = 2 * PM * NS * 64 };
    static const int lay[NL][11] = {
        /* pos off, fmt; tan; tex; col; c3d; stride */
        {0, HF_FORMAT_SNORM16, 12, HF_FORMAT_SNORM8, 6, HF_FORMAT_UNORM16, -1, 0, -1, 0, 16},
        {0, HF_FORMAT_F16, -1, 0, 6, HF_FORMAT_UNORM16, 12, HF_FORMAT_UNORM8, -1, 0, 16},
        {13, HF_FORMAT_SNORM8, 4, HF_FORMAT_SNORM8, 7, HF_FORMAT_UNORM16, 16, HF_FORMAT_UNORM8, 0, HF_FORMAT_F16, 20},
        {0, HF_FORMAT_F32, 16, HF_FORMAT_SNORM8, 19, HF_FORMAT_SNORM16, 12, HF_FORMAT_UNORM8, 25, HF_FORMAT_UNORM8, 28},
        {0, HF_FORMAT_F32, 12, HF_FORMAT_SNORM8, 16, HF_FORMAT_UNORM16, -1, 0, 22, HF_FORMAT_UNORM8, 24},
        {4, HF_FORMAT_SNORM16, 10, HF_FORMAT_F32, 22, HF_FORMAT_F16, 28, HF_FORMAT_F32, 44, HF_FORMAT_SNORM16, 52},
        {0, HF_FORMAT_F16, 2400, HF_FORMAT_SNORM8, 4000, HF_FORMAT_F32, -1, 0, -1, 0, 0},
        {2, HF_FORMAT_UNORM8, 5, HF_FORMAT_UNORM8, 8, HF_FORMAT_SNORM8, 11, HF_FORMAT_SNORM8, 15, HF_FORMAT_UNORM8, 19}};
    static const int Ps[3] = {5, 19, PM};
    static unsigned char va[BUF], vb[BUF];
    float pts[NS * PM * 3];
    hf_rng rng;
    int L, pi, s, j, q, level, windows = 0, widened = 0;
    hf_rng_seed(&rng, 7, 3);
    for (L = 0; L < NL; ++L)
        for (pi = 0; pi < 3; ++pi) {
            const int P = Ps[pi];
            hf_ribbon_params p = t_rparams();
            hf__rconst K;
            hf__rout ro;
            p.points_per_strand = P;
            p.alpha_root = 0.8f;
            p.alpha_tip = 0.3f;
            hf__rconst_init(&K, &p);
            t_random_strands(pts, NS, P, &rng);
            memset(&ro, 0, sizeof ro);
            for (q = 0; q < 5; ++q) {
                const int fmt = lay[L][2 * q + 1];
                ro.fmt[q] = fmt;
                ro.stride[q] = lay[L][10] ? (size_t)lay[L][10]
                                          : (size_t)(hf_format_bytes(fmt) * hf__stream_nc[q]);
            }
            ro.origin[0] = 0.05f; ro.origin[1] = 0.1f; ro.origin[2] = -0.2f;
            ro.inv_scale = 2.0f;
            for (s = 0; s < NS; ++s) {
                const float *qs = pts + (size_t)s * P * 3;
                const size_t v0 = 2u * (size_t)P * (size_t)s;
                hf__rframe fr;
                hf__rstrand S;
                /* as hf_ribbons: a strand with a NaN is drawn collapsed */
                const int fin = hf__points_finite_v1(qs, 3 * P);
                memset(&fr, 0, sizeof fr);
                hf__strand_frame_v1(fin ? qs : hf__zero_points, P, &p, &fr);
                S.uv[0] = hf_rng_float(&rng);
                S.uv[1] = hf_rng_float(&rng) * 3.0f - 1.0f;
                for (j = 0; j < 4; ++j) S.rgba[j] = hf_rng_float(&rng) * 1.2f - 0.1f;
                S.c3x = hf_rng_float(&rng);
                S.wscale = fin ? 1.0f : 0.0f;
                memset(va, 0xa5, sizeof va);
                for (q = 0; q < 5; ++q)
                    ro.base[q] = lay[L][2 * q] < 0 ? NULL : va + lay[L][2 * q];
                hf__rout_layout(&ro);
                CHECK(ro.nw > 0);
                windows += ro.wl > 0;
                for (q = 0; q < ro.nw; ++q)
                    widened += ro.wb[q] != hf_format_bytes(ro.fmt[ro.wq[q]]) *
                                               hf__stream_nc[ro.wq[q]];
                hf__ribbon_write_v1(&fr, P, &K, &S, &ro, v0);
                for (level = HF_SIMD_SSE2; level <= HF_SIMD_AVX512; ++level) {
                    memset(vb, 0xa5, sizeof vb);
                    for (q = 0; q < 5; ++q)
                        ro.base[q] = lay[L][2 * q] < 0 ? NULL : vb + lay[L][2 * q];
                    hf__rout_layout(&ro);
                    hf__ribbon_write(&fr, P, &K, &S, &ro, v0,
                                     hf__kernels_for(hf__write_widths, level));
                    CHECK(memcmp(va, vb, sizeof va) == 0);
                }
            }
        }
    /* the register run and widened copies were both taken */
    CHECK(windows >= 3 * 3 * 3);
    CHECK(widened >= 3 * 3 * 3);
    {
        /* overlapping streams in one vertex: no plan; the streaming
           stage's block only where the streams fill the vertex */
        hf__rout ro;
        memset(&ro, 0, sizeof ro);
        for (q = 0; q < 5; ++q) {
            ro.fmt[q] = HF_FORMAT_SNORM16;
            ro.stride[q] = 32;
        }
        ro.base[HF__S_POS] = va;
        ro.base[HF__S_TEX] = va + 4;
        hf__rout_layout(&ro);
        CHECK_EQ_INT(ro.nw, 0);
        ro.base[HF__S_TEX] = va + 6;
        hf__rout_layout(&ro);
        CHECK_EQ_INT(ro.nw, 2);
        CHECK_EQ_INT(ro.wl, 12);
        CHECK_EQ_INT((int)ro.tile, 0); /* 12 of 32 bytes: no whole blocks */
        ro.stride[HF__S_POS] = ro.stride[HF__S_TEX] = 12;
        hf__rout_layout(&ro);
        CHECK_EQ_INT((int)ro.tile, 12); /* the stage copies whole vertices */
    }
}

static void test_format_encoders(void)
{
    /* Scalar, SSE and NEON encoders agree bit for bit; each code is the nearest
       (ties to even) to the clamped value, and decodes within half a step. */
    static const float edge[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, -2.0f,
        65504.0f, 65519.0f, 65520.0f, 1e30f, -1e30f, 6.0e-8f, 2.9e-8f, 3.0e-8f,
        6.1035156e-05f, 6.1e-05f, 1.0009766f, 1.0004883f, 1.0014648f,
        0.00001526f, 0.5f / 32767.0f, 1.5f / 32767.0f, 0.5f / 255.0f,
        1.0f / 510.0f, 3.0f / 510.0f, 1e-40f, -1e-40f};
    const int ne = (int)(sizeof edge / sizeof edge[0]);
    hf_rng rng;
    int fmt, i, bad = 0;
    CHECK_EQ_INT(hf_format_bytes(HF_FORMAT_F32), 4);
    CHECK_EQ_INT(hf_format_bytes(HF_FORMAT_F16), 2);
    CHECK_EQ_INT(hf_format_bytes(HF_FORMAT_UNORM8), 1);
    CHECK_EQ_INT(hf_format_bytes(6), 0);
    CHECK_EQ_INT(hf_format_bytes(-1), 0);
    hf_rng_seed(&rng, 5, 5);
    for (fmt = 1; fmt < 6; ++fmt)
        for (i = 0; i < 20000 + ne; ++i) {
            float x;
            uint32_t code;
            double want, got, step;
            if (i < ne) {
                x = edge[i];
            } else { /* random bits of every magnitude, and plain values */
                uint32_t u = hf_rng_u32(&rng);
                if ((u & 0x7f800000u) == 0x7f800000u) u &= 0xbfffffffu;
                memcpy(&x, &u, 4);
                if (i & 1) x = hf_rng_float(&rng) * 2.4f - 1.2f;
            }
            code = hf__encode1(x, fmt);
#if HF__SSE
            {
                uint32_t lanes[4];
                _mm_storeu_si128((__m128i *)(void *)lanes,
                                 hf__encode_v4(_mm_set_ps(1.0f, x, -x, x), fmt));
                if (lanes[0] != code || lanes[2] != code) ++bad;
                if (lanes[1] != hf__encode1(-x, fmt)) ++bad;
            }
#endif
#if HF__NEON
            {
                const float in[4] = {x, -x, x, 1.0f};
                uint32_t lanes[4];
                vst1q_u32(lanes, hf__encode_v4(vld1q_f32(in), fmt));
                if (lanes[0] != code || lanes[2] != code) ++bad;
                if (lanes[1] != hf__encode1(-x, fmt)) ++bad;
            }
#endif
            switch (fmt) {
            case HF_FORMAT_F16: {
                const double c = x < -65504.0f ? -65504.0 : (x > 65504.0f ? 65504.0 : (double)x);
                got = t_half((uint16_t)code);
                /* the step around c */
                step = fabs(c) < ldexp(1.0, -14) ? ldexp(1.0, -24)
                                                 : ldexp(1.0, (int)floor(log2(fabs(c))) - 10);
                if (code > 0xffffu || fabs(got - c) > 0.5 * step + 1e-300) ++bad;
                if (fabs(got - c) == 0.5 * step && ((code & 1u) != 0)) ++bad; /* ties to even */
                if (signbit(got) != signbit((double)x) && got != 0.0) ++bad;
                break;
            }
            case HF_FORMAT_SNORM16:
            case HF_FORMAT_SNORM8: {
                const double sc = fmt == HF_FORMAT_SNORM16 ? 32767.0 : 127.0;
                const double c = x < -1.0f ? -1.0 : (x > 1.0f ? 1.0 : (double)x);
                const int sv = fmt == HF_FORMAT_SNORM16 ? (int)(int16_t)code : (int)(int8_t)code;
                want = c * sc;
                got = (double)sv;
                /* half a step, plus the float product's rounding */
                if (fabs(got - want) > 0.5 + sc * 1.2e-7) ++bad;
                break;
            }
            default: {
                const double sc = fmt == HF_FORMAT_UNORM16 ? 65535.0 : 255.0;
                const double c = x < 0.0f ? 0.0 : (x > 1.0f ? 1.0 : (double)x);
                want = c * sc;
                got = (double)code;
                if (code > (uint32_t)sc || fabs(got - want) > 0.5 + sc * 1.2e-7) ++bad;
                break;
            }
            }
        }
    CHECK_EQ_INT(bad, 0);
    /* spot values */
    CHECK_EQ_INT(hf__encode1(1.0f, HF_FORMAT_F16), 0x3c00);
    CHECK_EQ_INT(hf__encode1(-2.0f, HF_FORMAT_F16), 0xc000);
    CHECK_EQ_INT(hf__encode1(65504.0f, HF_FORMAT_F16), 0x7bff);
    CHECK_EQ_INT(hf__encode1(1e9f, HF_FORMAT_F16), 0x7bff); /* clamped, not inf */
    CHECK_EQ_INT(hf__encode1(5.9604645e-8f, HF_FORMAT_F16), 0x0001);
    CHECK_EQ_INT(hf__encode1(1.0004883f, HF_FORMAT_F16), 0x3c00); /* tie, even */
    CHECK_EQ_INT(hf__encode1(1.0014648f, HF_FORMAT_F16), 0x3c02); /* tie, even */
    CHECK_EQ_INT(hf__encode1(-1.0f, HF_FORMAT_SNORM16), 0x8001);
    CHECK_EQ_INT(hf__encode1(-3.0f, HF_FORMAT_SNORM8), 0x81);
    CHECK_EQ_INT(hf__encode1(1.0f, HF_FORMAT_UNORM16), 0xffff);
    CHECK_EQ_INT(hf__encode1(0.5f, HF_FORMAT_UNORM8), 128); /* 127.5: even */
}

/* GPU points at every SIMD level and with streaming stores, into buffers
   aligned to 64 bytes and 16, 32 and 48 bytes past: the same bytes as the
   documented formula, every strand length to 21 (the AVX2 and SSE loops
   leave different tails) and 32 (two sixteen-point groups), a NaN strand
   collapsed wherever its NaN sits, per-strand widths. */
static void test_points_every_level(void)
{
    enum { N = 9, QM = 32 };
    static float pts[N * QM * 3], wid[N];
    static float buf[N * QM * 4 + 32], ref[N * QM * 4];
    hf_ribbon_strands st;
    hf_ribbon_params rp;
    hf_rng r;
    int i, s, j, Q, level, nt, shift;
    hf_rng_seed(&r, 5u, 1u);
    for (i = 0; i < N * QM * 3; ++i) pts[i] = hf_rng_float(&r) - 0.5f;
    for (s = 0; s < N; ++s) wid[s] = 0.5f + hf_rng_float(&r);
    for (Q = 2; Q <= QM; Q = Q == 21 ? QM : Q + 1) {
        /* strand 4's NaN: its last float where Q is odd (the tail's
           load), else somewhere inside */
        const int nan_at = 4 * Q * 3 + (Q & 1 ? 3 * Q - 1 : (7 * Q) % (3 * Q));
        pts[nan_at] = (float)NAN;
        memset(&st, 0, sizeof st);
        st.points = pts;
        st.width = wid;
        memset(&rp, 0, sizeof rp);
        rp.points_per_strand = Q;
        rp.root_width = 0.004f;
        rp.tip_width = 0.001f;
        /* the scalar reference: xyz, the half width times the strand's,
           the NaN strand at the origin with no width */
        rp.simd = HF_SIMD_SCALAR;
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, ref), HF_OK);
        for (s = 0; s < N; ++s)
            for (j = 0; j < Q; ++j) {
                const float *q = ref + (s * Q + j) * 4;
                for (i = 0; i < 3; ++i)
                    CHECK(q[i] == (s == 4 ? 0.0f : pts[(s * Q + j) * 3 + i]));
                CHECK(s == 4 ? q[3] == 0.0f
                             : fabs(q[3] / wid[s] - ref[j * 4 + 3] / wid[0]) < 1e-7);
            }
        for (level = 0; level <= HF_SIMD_AVX512; ++level)
            for (nt = 0; nt < 3; ++nt) /* by size, streaming, ordinary */
                for (shift = 0; shift < 4; ++shift) {
                    float *o = buf + ((64u - ((uintptr_t)buf & 63u)) & 63u) / 4u +
                               4 * shift;
                    memset(buf, 0xab, sizeof buf);
                    rp.simd = level;
                    rp.nontemporal = nt;
                    CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, o), HF_OK);
                    CHECK(memcmp(o, ref, sizeof(float) * 4u * N * (size_t)Q) == 0);
                }
        pts[nan_at] = 0.25f;
    }
}

/* Compact GPU points (HF_POINT_COMPACT): within scale / 65534 of the
   float points in a box of half extent 1 m (0.1 mm asked), the half
   width to 2^-11 relative, clamped to the box outside it; the same bytes
   at every level, streamed or not, at any offset, however the strands
   are split; the fur's calls write the encoding of their float points;
   bad formats, origins and scales refused with nothing written. */
static void test_points_compact(void)
{
    enum { N = 11, QM = 20 };
    static float pts[N * QM * 3], ref4[N * QM * 4];
    static unsigned char ref[N * QM * 8], buf[N * QM * 8 + 64];
    const float org[3] = {0.3f, -1.2f, 0.05f};
    hf_ribbon_strands st;
    hf_ribbon_params rp;
    hf_rng r;
    double worst = 0.0, worst_w = 0.0;
    int i, s, j, c, Q, level, nt, shift, same = 1, clamped = 0;
    hf_rng_seed(&r, 7u, 3u);
    for (i = 0; i < N * QM * 3; ++i)
        pts[i] = org[i % 3] + 2.0f * hf_rng_float(&r) - 1.0f;
    pts[3 * 5] = org[0] + 1.7f; /* outside the box: clamped */
    memset(&st, 0, sizeof st);
    st.points = pts;
    for (Q = 2; Q <= QM; Q += Q < 9 ? 1 : 11) {
        memset(&rp, 0, sizeof rp);
        rp.points_per_strand = Q;
        rp.root_width = 0.002f;
        rp.tip_width = 0.0001f;
        rp.simd = HF_SIMD_SCALAR;
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, ref4), HF_OK);
        rp.point_format = HF_POINT_COMPACT;
        for (c = 0; c < 3; ++c) rp.point_origin[c] = org[c];
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, (float *)(void *)ref),
                     HF_OK);
        for (s = 0; s < N; ++s)
            for (j = 0; j < Q; ++j) {
                const size_t q = (size_t)s * Q + j;
                int16_t code[3];
                uint16_t h;
                memcpy(code, ref + 8 * q, 6);
                memcpy(&h, ref + 8 * q + 6, 2);
                for (c = 0; c < 3; ++c) {
                    const double x = org[c] + code[c] / 32767.0,
                                 want = ref4[4 * q + c];
                    const double lim = org[c] + (want > org[c] ? 1.0 : -1.0);
                    if (fabs(want - org[c]) > 1.0) {
                        ++clamped;
                        CHECK(fabs(x - lim) < 1e-6);
                        continue;
                    }
                    if (fabs(x - want) > worst) worst = fabs(x - want);
                }
                if (ref4[4 * q + 3] > 0.0f) {
                    const double e = fabs(t_half(h) / ref4[4 * q + 3] - 1.0);
                    if (e > worst_w) worst_w = e;
                }
            }
        for (level = 0; level <= HF_SIMD_AVX512; ++level)
            for (nt = 0; nt < 3; ++nt)
                for (shift = 0; shift < 4; ++shift) {
                    unsigned char *o =
                        buf + ((64u - ((uintptr_t)buf & 63u)) & 63u) + 8 * shift;
                    memset(buf, 0xab, sizeof buf);
                    rp.simd = level;
                    rp.nontemporal = nt;
                    if (shift == 3) { /* in two ranges, each at its own start */
                        rp.out_first = 0;
                        CHECK_EQ_INT(hf_ribbon_points(&st, 0, 4, &rp,
                                                      (float *)(void *)o),
                                     HF_OK);
                        rp.out_first = 4;
                        CHECK_EQ_INT(hf_ribbon_points(&st, 4, N - 4, &rp,
                                                      (float *)(void *)(o + 32 * Q)),
                                     HF_OK);
                        rp.out_first = 0;
                    } else {
                        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp,
                                                      (float *)(void *)o),
                                     HF_OK);
                    }
                    same &= memcmp(o, ref, 8u * N * (size_t)Q) == 0;
                }
    }
    CHECK(same);
    CHECK(worst <= 1.0 / 65534.0 + 1e-6);
    CHECK(worst < 1e-4);
    CHECK(worst_w <= 1.0 / 2048.0);
    CHECK(clamped > 0);
    { /* bad parameters: nothing written */
        unsigned char z[8 * N * QM];
        memset(buf, 0x5a, sizeof buf);
        memcpy(z, buf, sizeof z);
        rp.points_per_strand = QM;
        rp.point_format = 2;
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, (float *)(void *)buf),
                     HF_ERROR_BAD_FORMAT);
        rp.point_format = -1;
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, (float *)(void *)buf),
                     HF_ERROR_BAD_FORMAT);
        rp.point_format = HF_POINT_COMPACT;
        rp.point_origin[1] = (float)NAN;
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, (float *)(void *)buf),
                     HF_ERROR_NON_FINITE);
        rp.point_origin[1] = 3e18f;
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, (float *)(void *)buf),
                     HF_ERROR_BAD_PARAMETER);
        rp.point_origin[1] = 0.0f;
        rp.point_scale = -1.0f;
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, (float *)(void *)buf),
                     HF_ERROR_BAD_PARAMETER);
        rp.point_scale = (float)INFINITY;
        CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, (float *)(void *)buf),
                     HF_ERROR_NON_FINITE);
        CHECK(memcmp(z, buf, sizeof z) == 0);
    }
    /* the fur's calls: the encoding of their own float points */
    {
        t_fur_scene sc;
        hf_fur *f = NULL;
        hf_fur_info info;
        hf_result worst_r = HF_OK;
        hf_ribbon_params view;
        void *vbuf = calloc(24u * 2u * 16u * 500u, 1);
        float *f4;
        unsigned char *c8, *e8;
        hf__points_kit kit;
        t_fur_scene_init(&sc, 1.0f);
        sc.desc.points_per_strand = 16;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
        if (!f || !vbuf) return;
        t_fur_frame(f, &sc, 0.0f, 1, vbuf, &worst_r);
        hf_fur_get_info(f, &info);
        f4 = (float *)malloc(16u * 16u * (size_t)info.strand_count);
        c8 = (unsigned char *)malloc(8u * 16u * (size_t)info.strand_count);
        e8 = (unsigned char *)malloc(8u * 16u * (size_t)info.strand_count);
        memset(&view, 0, sizeof view);
        view.point_origin[1] = 0.1f;
        view.point_scale = 0.5f;
        CHECK_EQ_INT(hf_fur_points(f, 0, info.drawn_strand_count, &view, f4),
                     HF_OK);
        view.point_format = HF_POINT_COMPACT;
        memset(&kit, 0, sizeof kit);
        kit.origin[1] = 0.1f;
        kit.inv = 2.0f;
        hf__points_encode_v1(&kit, f4,
                             (size_t)info.drawn_strand_count * 16u, e8, 0);
        CHECK_EQ_INT(hf_fur_points(f, 0, info.drawn_strand_count, &view,
                                   (float *)(void *)c8),
                     HF_OK);
        CHECK(memcmp(c8, e8, 8u * 16u * (size_t)info.drawn_strand_count) == 0);
        memset(c8, 0, 8u * 16u * (size_t)info.drawn_strand_count);
        CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, info.drawn_strand_count,
                                               &view, (float *)(void *)c8),
                     HF_OK);
        CHECK(memcmp(c8, e8, 8u * 16u * (size_t)info.drawn_strand_count) == 0);
        free(f4);
        free(c8);
        free(e8);
        free(vbuf);
        hf_fur_destroy(f);
    }
}

/* The streamed ribbons' scratch, for every offset of its buffer in a
   page: the stage (hf__stage_in_page) inside its 8 KiB, crossing no 4
   KiB page where the strand's vertices fit in one, and where it already
   crosses none, the buffer's start; the frames (hf__frame_in_page). */
static void test_ribbon_scratch_in_page(void)
{
    static float mem[3 * 4096 / 4 + HF__RIBBON_ROOM];
    float *const page = mem + ((4096u - ((uintptr_t)mem & 4095u)) & 4095u) / 4u;
    static const size_t needs[5] = {16, 1152, 4000, 4096, 6000};
    size_t off, k, bad = 0;
    for (k = 0; k < 5; ++k)
        for (off = 0; off < 4096; off += 4) {
            float *const buf = page + off / 4;
            const size_t need = needs[k];
            float *const st = hf__stage_in_page(buf, need);
            const size_t at = (size_t)(st - buf) * 4u;
            const size_t in_page = (size_t)((uintptr_t)st & 4095u);
            if (at + need > HF__STAGE_BYTES) ++bad;
            if (need <= 4096u && in_page + need > 4096u) ++bad;
            if (off + need <= 4096u && st != buf) ++bad;
            if (need > 4096u && st != buf) ++bad;
        }
    CHECK_EQ_INT((int)bad, 0);
    /* the frames: the first at a page boundary, the second frame or the
       stage (HF__STAGE_BYTES) inside the room after it; no row of the
       first crosses a page with P = 160, one of them with P = 161 */
    for (off = 0; off < 4096; off += 4) {
        float *const room = mem + off / 4;
        const hf__rframe *const fr = hf__frame_in_page(room);
        const unsigned char *const end =
            (const unsigned char *)(room + HF__RIBBON_ROOM);
        int r, crossing160 = 0, crossing161 = 0;
        if (((uintptr_t)fr & 4095u) != 0) ++bad;
        if ((const unsigned char *)(fr + 2) > end ||
            (const unsigned char *)(fr + 1) + HF__STAGE_BYTES > end)
            ++bad;
        for (r = 0; r < 9; ++r) {
            const size_t at = (size_t)((uintptr_t)(r < 3   ? fr->p[r]
                                                   : r < 6 ? fr->t[r - 3]
                                                           : fr->s[r - 6]) &
                                       4095u);
            crossing160 += at + 4u * (160u + 12u) > 4096u;
            crossing161 += at + 4u * (161u + 12u) > 4096u;
        }
        if (crossing160 != 0 || crossing161 == 0) ++bad;
    }
    CHECK_EQ_INT((int)bad, 0);
}

/* Widths at their bounds: root and tip width, width_scale and a strand's
   multiplier may each reach HF_MAX_ABS, and their product would overflow
   float. A vertex's half width is then held to HF_MAX_ABS: no NaN (a
   side's zero component times an infinite width), the same bytes at
   every level, in float and compact positions and in GPU points; a fur's
   LOD scale on top of a view at the bound is clamped, not refused. */
static void test_widths_at_the_bound(void)
{
    enum { N = 5, PM = 19 };
    static float pts[N * PM * 3], f32[N * PM * 2 * 9], f32r[N * PM * 2 * 9];
    static short s16[N * PM * 2 * 3], s16r[N * PM * 2 * 3];
    static float g[N * PM * 4], gr[N * PM * 4];
    static const float mult[N] = {1000.0f, 1e18f, 1.0f, 0.5f, 3e-30f};
    static const int Ps[3] = {3, 16, 19};
    hf_ribbon_strands st;
    hf_ribbon_params rp;
    hf_ribbon_output o, o16;
    int pi, s, j, i, level, nt;
    for (pi = 0; pi < 3; ++pi) {
        const int P = Ps[pi];
        const size_t nv = (size_t)N * (size_t)P * 2u;
        const size_t ng = (size_t)N * (size_t)P * 4u;
        for (s = 0; s < N; ++s)
            for (j = 0; j < P; ++j) {
                float *q = pts + (s * P + j) * 3;
                /* strand 0 straight along y (its side (1, 0, 0) has two
                   zero components), the others bent */
                q[0] = s == 0 ? 0.0f : 0.01f * (float)(j * j) + 0.1f * (float)s;
                q[1] = 0.1f * (float)j;
                q[2] = s == 0 ? 0.0f : 0.02f * (float)j;
            }
        memset(&st, 0, sizeof st);
        st.points = pts;
        st.width = mult;
        memset(&rp, 0, sizeof rp);
        rp.points_per_strand = P;
        rp.eye[2] = 5.0f;
        rp.root_width = rp.tip_width = rp.width_scale = HF_MAX_ABS;
        o = t_packed36(f32);
        memset(&o16, 0, sizeof o16);
        o16.position.data = s16;
        o16.position.format = HF_FORMAT_SNORM16;
        o16.position_scale = 1e18f;
        for (level = HF_SIMD_SCALAR; level <= HF_SIMD_AVX512; ++level)
            for (nt = 0; nt < 3; ++nt) { /* by size, streaming, ordinary */
                rp.simd = level;
                rp.nontemporal = nt;
                CHECK_EQ_INT(hf_ribbons(&st, 0, N, &rp, &o), HF_OK);
                CHECK_EQ_INT(hf_ribbons(&st, 0, N, &rp, &o16), HF_OK);
                CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, g), HF_OK);
                if (level == HF_SIMD_SCALAR && nt == 0) {
                    memcpy(f32r, f32, sizeof(float) * nv * 9u);
                    memcpy(s16r, s16, sizeof(short) * nv * 3u);
                    memcpy(gr, g, sizeof(float) * ng);
                    for (i = 0, j = 0; i < (int)nv * 9; ++i)
                        j += f32[i] != f32[i]; /* NaNs: one check */
                    CHECK_EQ_INT(j, 0);
                    /* half widths held to the bound, the small ones kept */
                    for (i = 0; i < N * P; ++i)
                        CHECK(g[4 * i + 3] > 0.0f &&
                              g[4 * i + 3] <= HF_MAX_ABS * 1.000001f);
                    /* 1 and 0.5 both beyond the cap; 3e-30 below it */
                    CHECK(g[4 * 3 * P + 3] == g[4 * 2 * P + 3] &&
                          g[4 * 2 * P + 3] > 0.99f * HF_MAX_ABS);
                    CHECK(g[4 * 4 * P + 3] > 1e6f && g[4 * 4 * P + 3] < 2e6f);
                    /* the straight strand's vertices at x = -+ the width */
                    CHECK(f32[0] < -1e17f && f32[9] > 1e17f &&
                          f32[1] == 0.0f && f32[10] == 0.0f);
                    continue;
                }
                CHECK(memcmp(f32, f32r, sizeof(float) * nv * 9u) == 0);
                CHECK(memcmp(s16, s16r, sizeof(short) * nv * 3u) == 0);
                CHECK(memcmp(g, gr, sizeof(float) * ng) == 0);
            }
    }
    {
        t_fur_scene sc;
        hf_fur *f = NULL;
        hf_fur_info info;
        float *buf;
        t_fur_scene_init(&sc, 1.0f);
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
        if (!f) return;
        CHECK_EQ_INT(hf_fur_set_lod(f, 0.25f), HF_OK);
        hf_fur_get_info(f, &info);
        CHECK(info.width_scale > 1.0f);
        buf = (float *)malloc(sizeof(float) * 4u * (size_t)info.strand_count *
                              (size_t)info.points_per_strand);
        memset(&rp, 0, sizeof rp);
        rp.width_scale = HF_MAX_ABS;
        CHECK_EQ_INT(hf_fur_points(f, 0, info.strand_count, &rp, buf), HF_OK);
        CHECK(buf[3] > 0.0f && buf[3] <= HF_MAX_ABS * 1.000001f);
        rp.width_scale = 2e18f; /* beyond the bound: still refused */
        CHECK_EQ_INT(hf_fur_points(f, 0, info.strand_count, &rp, buf),
                     HF_ERROR_BAD_PARAMETER);
        free(buf);
        hf_fur_destroy(f);
    }
}

/* The wide kernels leave the upper halves of the vector registers clean
   (vzeroupper) before any SSE code runs: otherwise the SSE code after them
   runs slower (measured on Zen 4: every later stage of a frame, 2.1-2.4x),
   and nothing else shows it. XGETBV with ECX = 1 reads which state
   is in use: bit 2 the upper halves of ymm0-15, bit 6 those of zmm0-15.
   Every kernel that runs at AVX2 or AVX-512, in every layout and tail,
   and the rope step with its collisions. Not in a build for an AVX target
   (-mavx2): all its code is AVX then, the compiler's own included, and
   the state says nothing about the kernels. */
#if HF__AVX2 && defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX__)
static unsigned t_dirty_upper(void)
{
    unsigned a, b, c, d, lo, hi;
    __asm__ volatile("cpuid" : "=a"(a), "=b"(b), "=c"(c), "=d"(d) : "a"(13), "c"(1));
    if (!(a & 4u)) return 0u; /* no XGETBV1: cannot tell */
    __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(1));
    (void)hi;
    return lo & 0x44u;
}
#endif

static void test_simd_kernels_leave_upper_clean(void)
{
#if HF__AVX2 && defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX__)
    enum { N = 9, QM = 17 };
    static float pts[N * QM * 3], g[N * QM * 3], out[N * QM * 4];
    static unsigned char vb[N * QM * 2 * 64];
    hf_strand_binding bind[N];
    hf_ribbon_strands st;
    hf_ribbon_output ro;
    hf_rng r;
    int i, s, Q, level, layout, dirty = 0, runs = 0;
    if (hf_simd_resolve(HF_SIMD_AVX2) < HF_SIMD_AVX2) return; /* no AVX2 */
    hf_rng_seed(&r, 3u, 9u);
    for (i = 0; i < N * QM * 3; ++i) {
        pts[i] = hf_rng_float(&r) - 0.5f;
        g[i] = hf_rng_float(&r) - 0.5f;
    }
    for (s = 0; s < N; ++s) {
        for (i = 0; i < 3; ++i) bind[s].guide[i] = (s + i) % N;
        bind[s].weight[0] = 0.5f;
        bind[s].weight[1] = 0.3f;
        bind[s].weight[2] = 0.2f;
        bind[s].length_scale = 0.9f;
    }
    memset(&st, 0, sizeof st);
    st.points = pts;
    for (Q = 15; Q <= QM; ++Q)
        for (level = HF_SIMD_AVX2; level <= HF_SIMD_AVX512; ++level)
            for (layout = 0; layout < 3; ++layout) {
                hf_ribbon_params rp = t_rparams();
                hf_interp_params ip;
                rp.points_per_strand = Q;
                rp.simd = level;
                rp.nontemporal = layout == 2;
                ro = t_packed36(vb);
                /* the 36-byte float run, half floats, and streaming */
                if (layout == 1) ro.position.format = HF_FORMAT_F16;
                CHECK_EQ_INT(hf_ribbons(&st, 0, N, &rp, &ro), HF_OK);
                dirty |= t_dirty_upper();
                CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, out), HF_OK);
                dirty |= t_dirty_upper();
                memset(&ip, 0, sizeof ip);
                ip.points_per_strand = Q;
                ip.simd = level;
                ip.nontemporal = layout == 2;
                ip.clump = layout == 1 ? 0.3f : 0.0f;
                CHECK_EQ_INT(hf_interpolate(g, N, bind, 0, N, &ip, out), HF_OK);
                dirty |= t_dirty_upper();
                ++runs;
            }
    { /* the rope step: 21 ropes (sixteen lanes or twice eight, then four
         and one: no wider kernel after the widest to clean up for it),
         both solvers, through a sphere so the collision path runs too */
        enum { RR = 21, RP = 6 };
        static float rest[RR * RP * 3];
        float root[RR * 3], nrm[RR * 3], tng[RR * 3];
        hf_ropes *ro = NULL;
        hf_rope_params rp;
        hf_collider col;
        int solver, step;
        for (s = 0; s < RR; ++s) {
            for (i = 0; i < 3; ++i) {
                root[3 * s + i] = i == 0 ? 0.01f * (float)s : 0.0f;
                nrm[3 * s + i] = i == 1 ? 1.0f : 0.0f;
                tng[3 * s + i] = i == 0 ? 1.0f : 0.0f;
            }
            for (i = 0; i < RP; ++i) {
                rest[3 * (s * RP + i)] = root[3 * s];
                rest[3 * (s * RP + i) + 1] = 0.02f * (float)i;
                rest[3 * (s * RP + i) + 2] = 0.0f;
            }
        }
        CHECK_EQ_INT(hf_ropes_create(RR, RP, NULL, &ro), HF_OK);
        if (!ro) return;
        CHECK_EQ_INT(hf_ropes_set_rest(ro, 0, RR, rest, 0, root, nrm, tng, 0), HF_OK);
        memset(&col, 0, sizeof col);
        col.type = HF_COLLIDER_SPHERE;
        col.a[1] = 0.08f;
        col.a[2] = 0.02f;
        col.radius = 0.03f;
        for (solver = 0; solver < 2; ++solver)
            for (level = HF_SIMD_AVX2; level <= HF_SIMD_AVX512; ++level)
                for (step = 0; step < 3; ++step) {
                    hf_rope_params_init(&rp);
                    rp.solver = solver ? HF_ROPE_SOLVER_DISTANCE : HF_ROPE_SOLVER_FTL;
                    rp.local_stiffness_root = 0.3f;
                    rp.global_stiffness_root = 0.1f;
                    rp.simd = level;
                    CHECK_EQ_INT(hf_ropes_step(ro, 0, RR, 1.0f / 60.0f, &rp, &col, 1), HF_OK);
                    dirty |= t_dirty_upper();
                    ++runs;
                }
        hf_ropes_destroy(ro);
    }
    CHECK_EQ_INT((int)dirty, 0);
    CHECK(runs == 18 + 12);
#endif
}

static void test_ribbons_compact_formats(void)
{
    /* The same ribbons in compact formats decode to the float ones within
       each format's step; padding bytes stay untouched. Layout: position
       SNORM16 x3 at 0, tangent SNORM8 x3 at 6, texcoord UNORM16 x3 at 10,
       colour UNORM8 x4 at 16, 3D colour F16 x2 at 20; 28-byte vertices
       with bytes 24..27 unused. */
    enum { NS = 3, STRIDE = 28 };
    float g[NS * TP * 3];
    t_rvert v[NS * TP * 2];
    unsigned char cv[NS * TP * 2 * STRIDE];
    hf_ribbon_strands st;
    hf_ribbon_params p = t_rparams();
    hf_ribbon_output o = t_interleaved(v), c;
    static const float uv[6] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
    static const float col[12] = {1, 0, 0.3f, 1, 0, 1, 0, 1, 0.2f, 0.7f, 1, 0.5f};
    static const float c3[3] = {0.25f, 0.5f, 0.75f};
    /* the guides span x in [0, 9.4]: this box holds them */
    const float origin[3] = {4.0f, 0.3f, 0.4f}, scale = 6.0f;
    int i, k, bad = 0;
    t_make_guides(g, NS);
    memset(&st, 0, sizeof st);
    st.points = g;
    st.root_uv = uv;
    st.color = col;
    st.color3d_x = c3;
    p.alpha_root = 1.0f;
    p.alpha_tip = 0.25f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &o), HF_OK);
    memset(&c, 0, sizeof c);
    c.position.data = cv;       c.position.format = HF_FORMAT_SNORM16;
    c.tangent.data = cv + 6;    c.tangent.format = HF_FORMAT_SNORM8;
    c.texcoord.data = cv + 10;  c.texcoord.format = HF_FORMAT_UNORM16;
    c.color.data = cv + 16;     c.color.format = HF_FORMAT_UNORM8;
    c.color3d.data = cv + 20;   c.color3d.format = HF_FORMAT_F16;
    c.position.stride = c.tangent.stride = c.texcoord.stride =
        c.color.stride = c.color3d.stride = STRIDE;
    memcpy(c.position_origin, origin, sizeof origin);
    c.position_scale = scale;
    memset(cv, 0x5a, sizeof cv);
    CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &c), HF_OK);
    for (i = 0; i < NS * TP * 2; ++i) {
        const unsigned char *b = cv + (size_t)i * STRIDE;
        int16_t ps[3];
        uint16_t tc[3], h[2];
        memcpy(ps, b, 6);
        memcpy(tc, b + 10, 6);
        memcpy(h, b + 20, 4);
        for (k = 0; k < 3; ++k) {
            const double pos = origin[k] + scale * (ps[k] / 32767.0);
            if (fabs(pos - v[i].pos[k]) > scale * 0.5 / 32767.0 + 1e-6) ++bad;
            if (fabs((int8_t)b[6 + k] / 127.0 - v[i].tan[k]) > 0.5 / 127.0 + 1e-6) ++bad;
            if (fabs(tc[k] / 65535.0 - v[i].tc[k]) > 0.5 / 65535.0 + 1e-7) ++bad;
        }
        for (k = 0; k < 4; ++k)
            if (fabs(b[16 + k] / 255.0 - v[i].col[k]) > 0.5 / 255.0 + 1e-7) ++bad;
        for (k = 0; k < 2; ++k)
            if (fabs(t_half(h[k]) - v[i].c3[k]) > 1.0 / 4096.0) ++bad;
        for (k = 24; k < 28; ++k)
            if (b[k] != 0x5a) ++bad;
    }
    CHECK_EQ_INT(bad, 0);
    /* packed stride: components times their size */
    {
        int16_t packed[NS * TP * 2 * 3];
        hf_ribbon_output q;
        memset(&q, 0, sizeof q);
        q.position.data = packed;
        q.position.format = HF_FORMAT_SNORM16;
        memcpy(q.position_origin, origin, sizeof origin);
        q.position_scale = scale;
        CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &q), HF_OK);
        for (i = 0; i < NS * TP * 2; ++i)
            CHECK(memcmp(packed + 3 * i, cv + (size_t)i * STRIDE, 6) == 0);
    }
    /* refusals, nothing written */
    {
        unsigned char keep[sizeof cv];
        hf_ribbon_output b;
        memcpy(keep, cv, sizeof cv);
        b = c; b.tangent.format = 6;
        CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &b), HF_ERROR_BAD_FORMAT);
        b = c; b.color.format = -1;
        CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &b), HF_ERROR_BAD_FORMAT);
        b = c; b.position.stride = 5; /* 3 x 2 bytes do not fit */
        CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &b), HF_ERROR_BAD_STRIDE);
        b = c; b.position_scale = -1.0f;
        CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &b), HF_ERROR_BAD_PARAMETER);
        b = c; b.position_scale = 1e-30f;
        CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &b), HF_ERROR_BAD_PARAMETER);
        b = c; b.position_origin[1] = (float)NAN;
        CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &b), HF_ERROR_NON_FINITE);
        b = c; b.position_origin[2] = 1e30f;
        CHECK_EQ_INT(hf_ribbons(&st, 0, NS, &p, &b), HF_ERROR_BAD_PARAMETER);
        CHECK(memcmp(keep, cv, sizeof cv) == 0);
    }
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

static double t_dot3d(const float *a, const double *b)
{
    return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
}

/* The side never twists off the point's own tangent: within 1e-5 of
   perpendicular to tangent and view wherever they are not parallel (views
   from sin 2e-6 to 0.1 off the tangent), perpendicular to the tangent
   where it is borrowed (the eye on a point, a view along the tangent),
   never NaN. Both builds run it: SSE (with its reference fallback) and
   HF_NO_SIMD. */
static void test_ribbon_sides_never_twist(void)
{
    static const double sins[8] = {2e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.05, 0.1,
                                   0.0};
    hf_rng rng;
    float pts[TP * 3];
    hf__rframe fr;
    hf_ribbon_params p = t_rparams();
    double worst_t = 0.0, worst_v = 0.0, worst_n = 0.0;
    int trial, j, k, q, nan_seen = 0;
    hf_rng_seed(&rng, 11u, 3u);
    for (trial = 0; trial < 200; ++trial) {
        /* a smooth random strand near the origin */
        float dir[3] = {0, 1, 0}, bend = 0.4f * (hf_rng_float(&rng) - 0.5f);
        for (k = 0; k < 3; ++k) dir[k] = hf_rng_float(&rng) - 0.5f;
        for (j = 0; j < TP; ++j)
            for (k = 0; k < 3; ++k)
                pts[3 * j + k] = 0.1f * (float)j * dir[k] +
                                 (k == 1 ? bend * 0.01f * (float)(j * j) : 0.0f);
        for (q = 0; q < 8; ++q) {
            const int at = (int)hf_rng_below(&rng, TP);
            float ws;
            double t[3], a[3], v[3], len, sn = sins[q];
            hf__strand_frame(pts, TP, &p, &fr, &ws, hf__kernels_for(hf__frame_widths, 0)); /* tangents first */
            for (k = 0; k < 3; ++k) t[k] = fr.t[k][4 + at];
            /* a unit axis perpendicular to t */
            a[0] = t[1]; a[1] = -t[0]; a[2] = 0.0;
            if (fabs(t[2]) > 0.9) { a[0] = 0.0; a[1] = t[2]; a[2] = -t[1]; }
            len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
            for (k = 0; k < 3; ++k) {
                a[k] /= len;
                /* eye 1.5 away, sin `sn` off the tangent; q = 7: on p */
                v[k] = q == 7 ? 0.0
                              : 1.5 * (sqrt(1.0 - sn * sn) * t[k] + sn * a[k]);
                p.eye[k] = (float)((double)pts[3 * at + k] + v[k]);
            }
            hf__strand_frame(pts, TP, &p, &fr, &ws, hf__kernels_for(hf__frame_widths, 0));
            for (j = 0; j < TP; ++j) {
                float sj[3], tj[3];
                double dv[3], dl, st, sv, n;
                for (k = 0; k < 3; ++k) {
                    sj[k] = fr.s[k][4 + j];
                    tj[k] = fr.t[k][4 + j];
                    dv[k] = (double)p.eye[k] - (double)pts[3 * j + k];
                }
                if (!t_is_finite(sj[0]) || !t_is_finite(sj[1]) ||
                    !t_is_finite(sj[2]))
                    nan_seen = 1;
                n = fabs(sqrt((double)sj[0] * sj[0] + (double)sj[1] * sj[1] +
                              (double)sj[2] * sj[2]) - 1.0);
                st = fabs((double)sj[0] * tj[0] + (double)sj[1] * tj[1] +
                          (double)sj[2] * tj[2]);
                if (n > worst_n) worst_n = n;
                if (st > worst_t) worst_t = st;
                dl = sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
                if (dl > 0.0) {
                    double c = fabs(t_dot3d(tj, dv)) / dl;
                    /* the view's own rounding: skip views within 1e-5 of
                       parallel, where the side is borrowed */
                    if (c < 1.0 - 1e-10) {
                        sv = fabs(t_dot3d(sj, dv)) / dl;
                        if (sv > worst_v) worst_v = sv;
                    }
                }
            }
        }
    }
    if (getenv("TR_VERBOSE"))
        printf("sides: |s.t| %g |s.v| %g ||s|-1| %g\n", worst_t, worst_v,
               worst_n);
    CHECK(!nan_seen);
    CHECK(worst_t <= 1e-5);
    CHECK(worst_v <= 1e-5);
    CHECK(worst_n <= 1e-5);
    /* a straight strand seen exactly along itself: no side anywhere */
    for (j = 0; j < TP; ++j) {
        pts[3 * j] = 0.0f; pts[3 * j + 1] = 0.1f * (float)j; pts[3 * j + 2] = 0.0f;
    }
    p.orthographic = 1;
    p.view_dir[0] = 0.0f; p.view_dir[1] = -1.0f; p.view_dir[2] = 0.0f;
    {
        float ws;
        hf__strand_frame(pts, TP, &p, &fr, &ws, hf__kernels_for(hf__frame_widths, 0));
        for (j = 0; j < TP; ++j) {
            CHECK(fabsf(fr.s[1][4 + j]) <= 1e-6f);
            CHECK(fabsf(fr.s[0][4 + j] * fr.s[0][4 + j] +
                        fr.s[2][4 + j] * fr.s[2][4 + j] - 1.0f) <= 1e-5f);
        }
    }
}

static void test_bad_ribbons(void)
{
    float pts[2 * 3 * 3] = {0, 0, 0, 0, 0.1f, 0, 0, 0.2f, 0,
                            1, 0, 0, 1, 0, 0, 1, 0, 0}; /* strand 1: no length */
    float v[2 * 3 * 2 * 3], p4[2 * 3 * 4];
    hf_ribbon_strands st;
    hf_ribbon_params rp, b;
    hf_ribbon_output o;
    uint32_t ix[64];
    memset(&st, 0, sizeof st);
    st.points = pts;
    memset(&rp, 0, sizeof rp);
    rp.points_per_strand = 3;
    rp.eye[2] = 2.0f;
    rp.root_width = 0.01f;
    memset(&o, 0, sizeof o);
    o.position.data = v;
#define TB_RIB(params, first, count, code)                                     \
    do {                                                                       \
        TB_FAILS(hf_ribbons(&st, (first), (count), &(params), &o), (code), v,  \
                 sizeof v);                                                    \
        TB_FAILS(hf_ribbon_points(&st, (first), (count), &(params), p4),       \
                 (code), p4, sizeof p4);                                       \
    } while (0)
    b = rp; b.points_per_strand = 1; TB_RIB(b, 0, 2, HF_ERROR_BAD_COUNT);
    b = rp; b.points_per_strand = HF_MAX_POINTS + 1; TB_RIB(b, 0, 2, HF_ERROR_BAD_COUNT);
    TB_RIB(rp, -1, 1, HF_ERROR_BAD_RANGE);
    TB_RIB(rp, 0, -1, HF_ERROR_BAD_RANGE);
    TB_RIB(rp, 1, 0x7fffffff, HF_ERROR_BAD_RANGE);
    b = rp; b.eye[1] = TB_NAN; TB_RIB(b, 0, 2, HF_ERROR_NON_FINITE);
    b = rp; b.view_dir[0] = TB_INF; TB_RIB(b, 0, 2, HF_ERROR_NON_FINITE);
    b = rp; b.root_width = -0.01f; TB_RIB(b, 0, 2, HF_ERROR_BAD_PARAMETER);
    b = rp; b.tip_width = TB_NAN; TB_RIB(b, 0, 2, HF_ERROR_NON_FINITE);
    b = rp; b.taper_power = -1.0f; TB_RIB(b, 0, 2, HF_ERROR_BAD_PARAMETER);
    b = rp; b.width_scale = TB_INF; TB_RIB(b, 0, 2, HF_ERROR_NON_FINITE);
    b = rp; b.alpha_tip = TB_NAN; TB_RIB(b, 0, 2, HF_ERROR_NON_FINITE);
    b = rp; b.orthographic = 1; TB_RIB(b, 0, 2, HF_ERROR_DEGENERATE); /* zero view_dir */
    /* a kernel choice that is none: refused as everywhere */
    b = rp; b.simd = HF_SIMD_AVX512 + 1; TB_RIB(b, 0, 2, HF_ERROR_BAD_PARAMETER);
    b = rp; b.simd = -1; TB_RIB(b, 0, 2, HF_ERROR_BAD_PARAMETER);
    b = rp; b.nontemporal = 3; TB_RIB(b, 0, 2, HF_ERROR_BAD_PARAMETER);
    b = rp; b.nontemporal = -1; TB_RIB(b, 0, 2, HF_ERROR_BAD_PARAMETER);
    st.points = NULL; TB_RIB(rp, 0, 2, HF_ERROR_NULL_POINTER); st.points = pts;
    CHECK_EQ_INT(hf_ribbons(NULL, 0, 2, &rp, &o), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ribbons(&st, 0, 2, NULL, &o), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ribbons(&st, 0, 2, &rp, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_ribbon_points(&st, 0, 2, &rp, NULL), HF_ERROR_NULL_POINTER);
    o.position.stride = -12;
    TB_FAILS(hf_ribbons(&st, 0, 2, &rp, &o), HF_ERROR_BAD_STRIDE, v, sizeof v);
    o.position.stride = 0;
    /* the eye exactly on a strand point, and on the line of a strand:
       finite vertices */
    b = rp; b.eye[0] = 0; b.eye[1] = 0.1f; b.eye[2] = 0;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 2, &b, &o), HF_OK);
    CHECK(tb_finite(v, sizeof v / sizeof v[0]));
    b.eye[1] = 5.0f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 2, &b, &o), HF_OK);
    CHECK(tb_finite(v, sizeof v / sizeof v[0]));
    /* orthographic along the strand */
    b = rp; b.orthographic = 1; b.view_dir[1] = 1.0f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 2, &b, &o), HF_OK);
    CHECK(tb_finite(v, sizeof v / sizeof v[0]));
    /* NaN positions get a result code or a clamp, never NaN out */
    pts[4] = TB_NAN;
    tb_fill(v, sizeof v);
    {
        hf_result r = hf_ribbons(&st, 0, 2, &rp, &o);
        CHECK(r < 0 ? tb_untouched(v, sizeof v) : tb_finite(v, sizeof v / sizeof v[0]));
    }
    pts[4] = 0.1f;
    /* finite widths whose product overflows: never inf or NaN */
    b = rp; b.root_width = 1e30f; b.width_scale = 1e30f;
    tb_fill(v, sizeof v);
    {
        hf_result r = hf_ribbons(&st, 0, 2, &b, &o);
        CHECK(r < 0 ? tb_untouched(v, sizeof v) : tb_finite(v, sizeof v / sizeof v[0]));
        r = hf_ribbon_points(&st, 0, 2, &b, p4);
        CHECK(r < 0 || tb_finite(p4, sizeof p4 / sizeof p4[0]));
    }
#undef TB_RIB
    /* indices */
    CHECK(hf_ribbon_index_count(-1, 3, HF_TRIANGLES) == -1);
    CHECK(hf_ribbon_index_count(1, 1, HF_TRIANGLES) == -1);
    CHECK(hf_ribbon_index_count(1, 3, 2) == -1);
    CHECK(hf_ribbon_index_count(0x7fffffff, 0x7fffffff, HF_TRIANGLES) == -1);
    CHECK(hf_ribbon_index_count(0x7fffffff, 2, HF_STRIP_RESTART) == -1);
    CHECK(hf_ribbon_index_count(0, 3, HF_TRIANGLES) == 0);
    TB_FAILS(hf_ribbon_indices(2, 3, HF_TRIANGLES, ix, 23), HF_ERROR_BUFFER_TOO_SMALL, ix, sizeof ix);
    TB_FAILS(hf_ribbon_indices(-1, 3, HF_TRIANGLES, ix, 64), HF_ERROR_BAD_COUNT, ix, sizeof ix);
    TB_FAILS(hf_ribbon_indices(2, 1, HF_TRIANGLES, ix, 64), HF_ERROR_BAD_COUNT, ix, sizeof ix);
    TB_FAILS(hf_ribbon_indices(2, 3, 7, ix, 64), HF_ERROR_BAD_PARAMETER, ix, sizeof ix);
    TB_FAILS(hf_ribbon_indices(0x7fffffff, 0x7fffffff, HF_TRIANGLES, ix, 64),
             HF_ERROR_OVERFLOW, ix, sizeof ix);
    TB_FAILS(hf_ribbon_indices(2, 3, HF_TRIANGLES, ix, -1), HF_ERROR_BUFFER_TOO_SMALL, ix, sizeof ix);
    CHECK_EQ_INT(hf_ribbon_indices(2, 3, HF_TRIANGLES, NULL, 64), HF_ERROR_NULL_POINTER);
    /* 2 P strand_count past 2^32 while the index count fits an int: P =
       2^29, 5 strands -> 2^31 * 5 / 2^29 ... the vertex-number check */
    TB_FAILS(hf_ribbon_indices(1 << 24, 300, HF_STRIP_RESTART, ix, 64),
             hf_ribbon_index_count(1 << 24, 300, HF_STRIP_RESTART) < 0
                 ? HF_ERROR_OVERFLOW : HF_ERROR_BUFFER_TOO_SMALL,
             ix, sizeof ix);
}

static void test_defaults_zeroed_ribbon_params_draw(void)
{
    /* widths left zero draw the documented defaults, not a zero width */
    float g[3 * TP * 3], v[2 * TP * 3];
    hf_ribbon_strands st;
    hf_ribbon_params p;
    hf_ribbon_output o;
    float w0, w1;
    memset(&st, 0, sizeof st);
    memset(&p, 0, sizeof p);
    memset(&o, 0, sizeof o);
    t_make_guides(g, 3);
    st.points = g;
    p.points_per_strand = TP;
    p.eye[2] = 50.0f;
    o.position.data = v;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &o), HF_OK);
    w0 = sqrtf((v[0] - v[3]) * (v[0] - v[3]) + (v[1] - v[4]) * (v[1] - v[4]) +
               (v[2] - v[5]) * (v[2] - v[5]));
    {
        const float *a = v + 6 * (TP - 1);
        w1 = sqrtf((a[0] - a[3]) * (a[0] - a[3]) + (a[1] - a[4]) * (a[1] - a[4]) +
                   (a[2] - a[5]) * (a[2] - a[5]));
    }
    CHECK_NEAR(w0, HF_RIBBON_DEFAULT_ROOT_WIDTH, 1e-6);
    CHECK_NEAR(w1, HF_RIBBON_DEFAULT_TIP_WIDTH, 1e-6);
    /* a root width with tip 0 is taken as is: a pointed tip */
    p.root_width = 0.002f;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &p, &o), HF_OK);
    CHECK(v[6 * (TP - 1)] == v[6 * (TP - 1) + 3]);
}

static void test_ribbon_indices16(void)
{
    int P, topo;
    for (topo = 0; topo < 2; ++topo)
        for (P = 2; P <= 64; P += 7) {
            const int per = hf_ribbon_chunk_strands(P, topo);
            const long long n = hf_ribbon_index_count(per, P, topo);
            uint32_t *i32 = (uint32_t *)malloc(sizeof(uint32_t) * (size_t)n);
            uint16_t *i16 = (uint16_t *)malloc(sizeof(uint16_t) * (size_t)n);
            long long k, restarts = 0;
            /* the largest chunk: its last vertex is below 0xFFFF, one more
               strand would not be */
            CHECK(2LL * P * per <= 0xFFFF && 2LL * P * (per + 1) > 0xFFFF);
            CHECK_EQ_INT(hf_ribbon_indices(per, P, topo, i32, n), HF_OK);
            CHECK_EQ_INT(hf_ribbon_indices16(per, P, topo, i16, n), HF_OK);
            for (k = 0; k < n; ++k) {
                if (i32[k] == 0xFFFFFFFFu) {
                    ++restarts;
                    CHECK(i16[k] == 0xFFFF);
                } else {
                    CHECK(i16[k] == i32[k] && i16[k] != 0xFFFF);
                }
            }
            CHECK_EQ_INT(restarts, topo == HF_STRIP_RESTART ? per : 0);
            CHECK_EQ_INT(hf_ribbon_indices16(per + 1, P, topo, i16, n + 1000),
                         HF_ERROR_OVERFLOW);
            CHECK_EQ_INT(hf_ribbon_indices16(per, P, topo, i16, n - 1),
                         HF_ERROR_BUFFER_TOO_SMALL);
            free(i32);
            free(i16);
        }
    CHECK_EQ_INT(hf_ribbon_chunk_strands(1, HF_TRIANGLES), 0);
    CHECK_EQ_INT(hf_ribbon_chunk_strands(16, 7), 0);
    CHECK_EQ_INT(hf_ribbon_chunk_strands(16, HF_TRIANGLES), 0xFFFF / 32);
    CHECK_EQ_INT(hf_ribbon_indices16(1, 16, HF_TRIANGLES, NULL, 100),
                 HF_ERROR_NULL_POINTER);
}

static void test_out_first_interpolate_and_ribbons(void)
{
    /* strands [2, 5) written with out_first = 2 into buffers holding just
       those strands: the same bytes as the slice of a whole buffer */
    enum { G = 3, N = 6, F = 2, C = 3 };
    float g[G * TP * 3], whole[N * TP * 3], part[C * TP * 3];
    float wv[N * TP * 2 * 3], pv[C * TP * 2 * 3];
    float w4[N * TP * 4], p4[C * TP * 4];
    hf_strand_binding b[N];
    hf_interp_params ip;
    hf_ribbon_params rp = t_rparams();
    hf_ribbon_strands st;
    hf_ribbon_output o;
    int s, k;
    t_make_guides(g, G);
    for (s = 0; s < N; ++s) {
        for (k = 0; k < 3; ++k) {
            b[s].guide[k] = (uint32_t)k;
            b[s].weight[k] = k == s % 3 ? 0.5f : 0.25f;
        }
        b[s].length_scale = 1.0f - 0.05f * (float)s;
    }
    memset(&ip, 0, sizeof ip);
    ip.points_per_strand = TP;
    ip.clump = 0.3f;
    CHECK_EQ_INT(hf_interpolate(g, G, b, 0, N, &ip, whole), HF_OK);
    ip.out_first = F;
    CHECK_EQ_INT(hf_interpolate(g, G, b, F, C, &ip, part), HF_OK);
    CHECK(memcmp(part, whole + F * TP * 3, sizeof part) == 0);
    CHECK_EQ_INT(hf_interpolate(g, G, b, F - 1, C, &ip, part),
                 HF_ERROR_BAD_RANGE);

    memset(&st, 0, sizeof st);
    st.points = whole;
    memset(&o, 0, sizeof o);
    o.position.data = wv;
    CHECK_EQ_INT(hf_ribbons(&st, 0, N, &rp, &o), HF_OK);
    CHECK_EQ_INT(hf_ribbon_points(&st, 0, N, &rp, w4), HF_OK);
    rp.out_first = F;
    o.position.data = pv;
    CHECK_EQ_INT(hf_ribbons(&st, F, C, &rp, &o), HF_OK);
    CHECK(memcmp(pv, wv + F * TP * 2 * 3, sizeof pv) == 0);
    CHECK_EQ_INT(hf_ribbon_points(&st, F, C, &rp, p4), HF_OK);
    CHECK(memcmp(p4, w4 + F * TP * 4, sizeof p4) == 0);
    tb_fill(pv, sizeof pv);
    CHECK_EQ_INT(hf_ribbons(&st, F - 1, C, &rp, &o), HF_ERROR_BAD_RANGE);
    CHECK(tb_untouched(pv, sizeof pv));
    rp.out_first = -1;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 1, &rp, &o), HF_ERROR_BAD_RANGE);
}

/* 8. ribbons: its tests, in the order they run */
#define T_RIBBON_TESTS(X)                                                      \
    X(test_half_widths_every_p)                                                \
    X(test_ribbons_perpendicular_and_widths)                                   \
    X(test_ribbons_degenerate_never_nan)                                       \
    X(test_ribbons_nonfinite_strand_collapses)                                 \
    X(test_ribbons_ranges_byte_identical)                                      \
    X(test_streaming_by_size)                                                  \
    X(test_ribbons_nontemporal)                                                \
    X(test_ribbons_streamed_lines)                                             \
    X(test_ribbons_separate_streams_and_skips)                                 \
    X(test_ribbons_errors_write_nothing)                                       \
    X(test_ribbons_leading_tangent)                                            \
    X(test_ribbons_every_level_matches_reference)                              \
    X(test_streams_cross_matches_brute_force)                                  \
    X(test_ribbons_run_layouts_every_level)                                    \
    X(test_ribbons_table_layouts)                                              \
    X(test_format_encoders)                                                    \
    X(test_points_every_level)                                                 \
    X(test_points_compact)                                                     \
    X(test_ribbon_scratch_in_page)                                             \
    X(test_widths_at_the_bound)                                                \
    X(test_simd_kernels_leave_upper_clean)                                     \
    X(test_ribbons_compact_formats)                                            \
    X(test_ribbon_indices)                                                     \
    X(test_ribbon_winding_faces_camera)                                        \
    X(test_ribbon_sides_never_twist)                                           \
    X(test_bad_ribbons)                                                        \
    X(test_defaults_zeroed_ribbon_params_draw)                                 \
    X(test_ribbon_indices16)                                                   \
    X(test_out_first_interpolate_and_ribbons)

/* ==== 9. LUT baking: the Marschner M and N textures ======================= */

/* Expected numbers are the spot values, texel table and channel sums of
   docs/marschner-spec.md section 11, and closed forms / integrals written here
   independently of the library from the formulas of sections 4-6. */

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
    CHECK_EQ_INT(p.model, HF_LUT_MARSCHNER);
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
    T_BAD(beta_r_deg, -1e-300, HF_ERROR_BAD_PARAMETER, "beta_r_deg");
    T_BAD(beta_r_deg, -1.0, HF_ERROR_BAD_PARAMETER, "beta_r_deg");
    T_BAD(sigma_a, -1e-9, HF_ERROR_BAD_PARAMETER, "sigma_a");
    T_BAD(sigma_a_rgb[1], -0.5, HF_ERROR_BAD_PARAMETER, "sigma_a_rgb[1]");
    T_BAD(variant, (hf_lut_variant)2, HF_ERROR_BAD_PARAMETER, "variant");
    T_BAD(model, 2, HF_ERROR_BAD_PARAMETER, "model");
    T_BAD(size, -1, HF_ERROR_BAD_COUNT, "size");
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
        if (k == 2) {
            p.sigma_a = 0.0;
            p.explicit_zero = HF_LUT_ZERO_SIGMA_A;
        }
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
                p.explicit_zero = HF_LUT_ZERO_ALPHA_R; /* alpha 0 is 0 */
                CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n, a), HF_OK);
                if (!t_lut_all_ok(a, n, 1)) ++fails;
            }
    /* a width too narrow for float stores FLT_MAX on the exact peak */
    {
        hf_lut_params p = t_lut_defaults(3, HF_LUT_CUBIC);
        p.alpha_r_deg = 0.0;
        p.explicit_zero = HF_LUT_ZERO_ALPHA_R;
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
        case 2: p.beta_r_deg = -0.5; break;
        case 3: p.sigma_a = -1.0; break;
        case 4: p.sigma_a_rgb[0] = -1.0; break;
        case 5: p.size = -1; want = HF_ERROR_BAD_COUNT; break;
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

/* 9. LUT baking: its tests, in the order they run */
#define T_LUT_TESTS(X)                                                         \
    X(test_lut_params_init_defaults)                                           \
    X(test_lut_validate_codes)                                                 \
    X(test_lut_n_spot_values)                                                  \
    X(test_lut_n_closed_forms)                                                 \
    X(test_lut_m_spot_values)                                                  \
    X(test_lut_texels_n64)                                                     \
    X(test_lut_channel_sums_n64)                                               \
    X(test_lut_m_symmetric)                                                    \
    X(test_lut_m_unit_area)                                                    \
    X(test_lut_n_energy_identity)                                              \
    X(test_lut_n_energy_no_absorption)                                         \
    X(test_lut_n_caustic_clamp)                                                \
    X(test_lut_n_conformance)                                                  \
    X(test_lut_extremes_finite)                                                \
    X(test_lut_extremes_full_size)                                             \
    X(test_lut_invalid_writes_nothing)                                         \
    X(test_lut_row_splits_identical)                                           \
    X(test_lut_rgb_matches_scalar)                                             \
    X(test_lut_n_mirror_columns)                                               \
    X(test_lut_to_u8)                                                          \
    X(test_lut_eval_errors)                                                    \
    X(test_lut_texel_centres)

/* ---- the energy-conserving fibre, the furnace, dual scattering ----------- */

/* A reference written from docs/marschner-spec.md sections 14 to 16, apart
   from the library: d'Eon's lobe in its plain form (I0 by its power
   series, no scaling), cell means by the midpoint rule, lobe energies by
   binning a fine midpoint rule in gamma, and Zinke's formulas. */

/* I0(x) = sum (x^2 / 4)^k / (k!)^2: every term positive, double suffices
   for the x <= 250 the default lobes reach. */
static double t_i0(double x)
{
    double t = 1.0, s = 1.0, q = 0.25 * x * x;
    int k;
    for (k = 1; k < 2000 && t > 1e-18 * s; ++k) {
        t *= q / ((double)k * (double)k);
        s += t;
    }
    return s;
}

/* d'Eon et al. 2011: exp(-sin ti sin tr / v) I0(cos ti cos tr / v) /
   (2 v sinh(1 / v)), ti the shifted incident inclination */
static double t_deon(double v, double ti, double tr)
{
    return exp(-sin(ti) * sin(tr) / v) * t_i0(fabs(cos(ti)) * cos(tr) / v) /
           (2.0 * v * sinh(1.0 / v));
}

/* lobe k's shift and variance: alpha_R, -alpha_R / 2, -3 alpha_R / 2, 0;
   (2 beta)^2 with beta_R, beta_R / 2, 2 beta_R, 2 beta_R */
static void t_lobe(const hf_lut_params *p, int k, double *alpha, double *v,
                   double *beta)
{
    static const double fa[4] = {1.0, -0.5, -1.5, 0.0};
    static const double fb[4] = {1.0, 0.5, 2.0, 2.0};
    double b = fb[k] * p->beta_r_deg * T_DEG;
    *alpha = fa[k] * p->alpha_r_deg * T_DEG;
    *beta = b;
    *v = 4.0 * b * b;
}

/* The energy-conserving fibre at h = sin(g): one Fresnel factor (F_ext of
   section 6.4) at every interface, and the chord 2 cos(gamma_t) /
   cos(theta_t) that the absorption runs along (T = exp(-sigma_a e)). */
static double t_fresnel_e(const t_col *k, double g, double *e)
{
    double gt = asin(sin(g) / k->eta1);
    *e = 2.0 * cos(gt) * k->inv_ctt;
    return 0.5 * (t_rs(k->eta1, g) + t_rp(k->eta2, g));
}

/* A_p from F and T; p = 3 is the sum over p >= 3. */
static double t_atten_ft(int p, double F, double T)
{
    if (p == 0) return F;
    if (p == 3) return (1 - F) * (1 - F) * F * F * T * T * T / (1 - F * T);
    return (1 - F) * (1 - F) * pow(F, p - 1) * pow(T, p);
}

/* cos of the exit azimuth of lobe p at gamma (cubic or exact) */
static double t_cos_exit(const t_col *k, int p, double g, int exact)
{
    return cos(t_phi(k, p, g, exact) + p * T_PI);
}

/* The albedo of the fibre at cos(theta_i) = cd: 1/2 the integral over h
   of F + (1 - F)^2 T / (1 - F T) (all p summed in closed form). */
static double t_albedo_e(double eta, double cd, double sigma)
{
    t_col k = t_column(eta, cd, sigma);
    const int steps = 20000;
    double sum = 0.0;
    int i;
    for (i = 0; i < steps; ++i) {
        double g = (i + 0.5) * (T_PI / 2) / steps, e;
        double F = t_fresnel_e(&k, g, &e), T = exp(-sigma * e);
        sum += (F + (1 - F) * (1 - F) * T / (1 - F * T)) * cos(g) *
               (T_PI / 2) / steps;
    }
    return sum;
}

/* Lobe energies of one column, binned by cos(phi) into n cells
   (e[4 j + p], both signs of phi), and the p >= 3 energy in e3. */
static void t_energy_cells(const hf_lut_params *p, double cd, int n,
                           int steps, double *e, double *e3)
{
    t_col k = t_column(p->eta, cd, p->sigma_a);
    int exact = p->variant == HF_LUT_EXACT, i, c;
    for (i = 0; i < 4 * n; ++i) e[i] = 0.0;
    *e3 = 0.0;
    for (i = 0; i < steps; ++i) {
        double g = (i + 0.5) * (T_PI / 2) / steps, ee;
        double w = cos(g) * (T_PI / 2) / steps;
        double F = t_fresnel_e(&k, g, &ee), T = exp(-p->sigma_a * ee);
        for (c = 0; c < 3; ++c) {
            int j = (int)floor((t_cos_exit(&k, c, g, exact) + 1.0) * 0.5 * n);
            if (j > n - 1) j = n - 1;
            e[4 * j + c] += w * t_atten_ft(c, F, T);
        }
        *e3 += w * t_atten_ft(3, F, T);
    }
}

static float *t_dual_alloc(int n)
{
    return (float *)malloc(sizeof(float) * 12u * (size_t)n * (size_t)n);
}

static hf_lut_params t_lut_energy(int size)
{
    hf_lut_params p = t_lut_defaults(size, HF_LUT_CUBIC);
    p.model = HF_LUT_ENERGY;
    return p;
}

/* The model field: default, validation, the calls that are the paper's
   only; the paper's bytes do not move (the other tests pin them). */
static void test_lut_energy_params(void)
{
    hf_lut_params p = t_lut_energy(8);
    float *a = t_lut_alloc(8), *b = t_lut_alloc(8);
    double o[3] = {-1, -1, -1};
    hf_diag d;
    hf_lut_params z;
    memset(&z, 0, sizeof z);
    CHECK_EQ_INT(z.model, HF_LUT_MARSCHNER); /* zero: the paper's model */
    hf_lut_params_init(&z);
    CHECK_EQ_INT(z.model, HF_LUT_MARSCHNER);
    CHECK_EQ_INT(hf_lut_validate(&p, &d), HF_OK);
    p.model = 2;
    CHECK_EQ_INT(hf_lut_validate(&p, &d), HF_ERROR_BAD_PARAMETER);
    CHECK(strcmp(d.field, "model") == 0);
    p.model = -1;
    CHECK_EQ_INT(hf_lut_validate(&p, &d), HF_ERROR_BAD_PARAMETER);
    p.model = HF_LUT_ENERGY;
    CHECK_EQ_INT(hf_lut_eval_m(&p, 0.1, o), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, 1.0, o), HF_ERROR_BAD_PARAMETER);
    CHECK(o[0] == -1 && o[1] == -1 && o[2] == -1);
    {
        float *keep = t_lut_alloc(8);
        memset(keep, 0x5a, sizeof(float) * 4 * 64);
        memcpy(a, keep, sizeof(float) * 4 * 64);
        memcpy(b, keep, sizeof(float) * 4 * 64);
        CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, 0, 8, a, b), HF_ERROR_BAD_PARAMETER);
        CHECK(memcmp(a, keep, sizeof(float) * 4 * 64) == 0);
        CHECK(memcmp(b, keep, sizeof(float) * 4 * 64) == 0);
        free(keep);
    }
    free(a);
    free(b);
}

/* M of the energy-conserving fibre against the reference: every texel at
   n = 8 (cell means of the plain formula, midpoint rule). */
static void test_lut_energy_m_reference(void)
{
    const int n = 8, steps = 400;
    hf_lut_params p = t_lut_energy(n);
    float *m = t_lut_alloc(n);
    int i, j, k, s, bad = 0;
    p.alpha_r_deg = -9.0;
    p.beta_r_deg = 6.0;
    CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n, m), HF_OK);
    for (k = 0; k < 4; ++k) {
        double alpha, v, beta;
        t_lobe(&p, k, &alpha, &v, &beta);
        for (i = 0; i < n; ++i) {
            double ti = asin((2.0 * i + 1 - n) / n) - 2.0 * alpha;
            for (j = 0; j < n; ++j) {
                double t0 = asin((2.0 * j - n) / n);
                double t1 = asin((2.0 * j + 2 - n) / n), sum = 0.0, x;
                for (s = 0; s < steps; ++s) {
                    double tr = t0 + (t1 - t0) * (s + 0.5) / steps;
                    sum += t_deon(v, ti, tr) * cos(tr) * (t1 - t0) / steps;
                }
                sum /= 2.0 / n;
                x = m[4 * (j * n + i) + k];
                if (!(fabs(x - sum) <= 2e-4 * sum + 1e-9)) {
                    if (bad < 5)
                        printf("  M(%d, %d) lobe %d: %.9g, reference %.9g\n",
                               i, j, k, x, sum);
                    ++bad;
                }
            }
        }
    }
    CHECK_EQ_INT(bad, 0);
    free(m);
}

/* d'Eon's normalisation, texel by texel: for every incident column and
   lobe the cells hold a density that integrates to 1 over sin(theta_r),
   whatever the size, shift and width (to the float rounding). */
static void test_lut_energy_m_normalised(void)
{
    static const int sizes[3] = {5, 32, 64};
    static const double ab[3][2] = {{-7.5, 7.5}, {-10, 5}, {-5, 10}};
    int z, a, i, j, k;
    for (z = 0; z < 3; ++z)
        for (a = 0; a < 3; ++a) {
            int n = sizes[z];
            hf_lut_params p = t_lut_energy(n);
            float *m = t_lut_alloc(n);
            p.alpha_r_deg = ab[a][0];
            p.beta_r_deg = ab[a][1];
            CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n, m), HF_OK);
            for (i = 0; i < n; ++i)
                for (k = 0; k < 4; ++k) {
                    double sum = 0.0;
                    for (j = 0; j < n; ++j) sum += m[4 * (j * n + i) + k];
                    CHECK_NEAR(sum * 2.0 / n, 1.0, 1e-6);
                }
            free(m);
        }
}

/* N of the energy-conserving fibre against the reference: the binned
   lobe energies over the cells' widths in phi, both variants; the p >= 3
   lobe uniform; every column's cells add up to the lobe's energy, and to
   1 over all lobes when nothing is absorbed. */
static void test_lut_energy_n_reference(void)
{
    const int n = 8, steps = 60000;
    int v, a, i, j, c, bad = 0;
    double e[4 * 8], e3;
    for (v = 0; v < 2; ++v)
        for (a = 0; a < 2; ++a) {
            hf_lut_params p = t_lut_energy(n);
            float *t = t_lut_alloc(n);
            double mx = 0.0;
            p.variant = v;
            p.sigma_a = a ? 0.0 : 0.35;
            p.explicit_zero = HF_LUT_ZERO_SIGMA_A;
            CHECK_EQ_INT(hf_lut_bake_n(&p, 0, n, t), HF_OK);
            for (i = 0; i < 4 * n * n; ++i)
                if ((i & 3) != 3 && t[i] > mx) mx = t[i];
            for (i = n / 2; i < n; ++i) {
                double cd = (2.0 * i + 1 - n) / n, tot[3] = {0, 0, 0};
                double sum_all = 0.0;
                t_energy_cells(&p, cd, n, steps, e, &e3);
                for (j = 0; j < n; ++j) {
                    double dphi = acos((2.0 * j - n) / n) -
                                  acos((2.0 * j + 2 - n) / n);
                    const float *x = t + 4 * (j * n + i);
                    for (c = 0; c < 3; ++c) {
                        double r = e[4 * j + c] / (2.0 * dphi);
                        if (!(fabs(x[c] - r) <= 2e-3 * r + 2e-4 * mx)) {
                            if (bad < 5)
                                printf("  N(%d, %d).%d: %.9g, reference %.9g\n",
                                       i, j, c, x[c], r);
                            ++bad;
                        }
                        tot[c] += x[c] * 2.0 * dphi;
                    }
                    CHECK_REL(x[3], e3 / (2.0 * T_PI), 3e-6);
                    /* mirrored column */
                    CHECK(memcmp(x, t + 4 * (j * n + n - 1 - i), 16) == 0);
                }
                for (c = 0; c < 3; ++c) {
                    double want = 0.0;
                    for (j = 0; j < n; ++j) want += e[4 * j + c];
                    CHECK_NEAR(tot[c], want, 1e-6 * want + 1e-7);
                    sum_all += tot[c];
                }
                sum_all += e3;
                if (a) CHECK_NEAR(sum_all, 1.0, 1e-6);
                else CHECK_NEAR(sum_all, t_albedo_e(p.eta, cd, p.sigma_a), 1e-5);
            }
            free(t);
        }
    CHECK_EQ_INT(bad, 0);
}

/* The white furnace of the baked textures, as the shader combines them:
   the energy-conserving fibre gives 1 when nothing is absorbed, the
   reference albedo otherwise, falling as absorption rises; the paper's
   fibre scatters about twice what it receives. */
static void test_lut_furnace(void)
{
    static const double sig[3] = {0.0, 0.2, 1.0};
    static const double th[4] = {0, 30, 60, 80};
    const int n = 64;
    hf_lut_params p = t_lut_energy(n);
    float *m = t_lut_alloc(n), *t = t_lut_alloc(n);
    double alb[3][4];
    int s, k;
    CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n, m), HF_OK);
    for (s = 0; s < 3; ++s) {
        p.sigma_a = sig[s];
        p.explicit_zero = HF_LUT_ZERO_SIGMA_A;
        CHECK_EQ_INT(hf_lut_bake_n(&p, 0, n, t), HF_OK);
        for (k = 0; k < 4; ++k) {
            double ref = t_albedo_e(p.eta, cos(th[k] * T_DEG), sig[s]);
            CHECK_EQ_INT(hf_lut_furnace(&p, m, t, th[k] * T_DEG, &alb[s][k]),
                         HF_OK);
            CHECK_NEAR(alb[s][k], ref, 4e-3);
            if (s == 0) CHECK_NEAR(alb[s][k], 1.0, 2e-3);
            if (s > 0) CHECK(alb[s][k] < alb[s - 1][k] - 0.01);
            /* light from below the normal plane: the same */
            {
                double b;
                hf_lut_furnace(&p, m, t, -th[k] * T_DEG, &b);
                CHECK_NEAR(b, alb[s][k], 2e-3);
            }
        }
    }
    /* the paper's fibre: twice too bright where it absorbs nothing */
    {
        hf_lut_params q = t_lut_defaults(32, HF_LUT_CUBIC);
        double a0;
        q.sigma_a = 0.0;
        q.explicit_zero = HF_LUT_ZERO_SIGMA_A;
        hf_lut_bake_m(&q, 0, 32, m);
        hf_lut_bake_n(&q, 0, 32, t);
        CHECK_EQ_INT(hf_lut_furnace(&q, m, t, 0.0, &a0), HF_OK);
        CHECK(a0 > 1.75 && a0 < 2.0);
    }
    /* errors leave the albedo alone */
    {
        double a = -5.0;
        CHECK_EQ_INT(hf_lut_furnace(NULL, m, t, 0.0, &a), HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_lut_furnace(&p, NULL, t, 0.0, &a), HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_lut_furnace(&p, m, NULL, 0.0, &a), HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_lut_furnace(&p, m, t, 0.0, NULL), HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_lut_furnace(&p, m, t, 1.6, &a), HF_ERROR_BAD_PARAMETER);
        CHECK_EQ_INT(hf_lut_furnace(&p, m, t, HUGE_VAL, &a), HF_ERROR_NON_FINITE);
        p.eta = 0.5;
        CHECK_EQ_INT(hf_lut_furnace(&p, m, t, 0.0, &a), HF_ERROR_BAD_PARAMETER);
        p.eta = 1.55;
        m[4 * n * n - 1] = strtof("nan", NULL);
        CHECK_EQ_INT(hf_lut_furnace(&p, m, t, 0.0, &a), HF_ERROR_NON_FINITE);
        CHECK(a == -5.0);
    }
    free(m);
    free(t);
}

/* Zinke et al.'s eqs. 14, 16, 17 with the weights of section 16. */
static void t_dual_derived(double af, double ab, double mf, double mb,
                           double bf, double bb, double out[3])
{
    double q = 1 - af * af;
    out[0] = ab * af * af / q + pow(ab, 3) * af * af / pow(q, 3);
    out[1] = mb * (1 - 2 * ab * ab / (q * q)) +
             mf * (2 * q * q + 4 * af * af * ab * ab) / pow(q, 3);
    out[2] = (1 + 0.7 * af * af) *
             (ab * sqrt(2 * bf * bf + bb * bb) +
              pow(ab, 3) * sqrt(2 * bf * bf + 3 * bb * bb)) /
             (ab + pow(ab, 3));
}

/* The dual scattering tables against the reference integration: every
   texel at n = 6, both variants; a_f + a_b is the fibre's albedo. */
static void test_lut_dual_reference(void)
{
    const int n = 6, steps = 60000;
    double *F = (double *)malloc(sizeof(double) * steps);
    double *E = (double *)malloc(sizeof(double) * steps);
    double *W = (double *)malloc(sizeof(double) * steps);
    unsigned char *fw = (unsigned char *)malloc((size_t)steps);
    int v, i, j, s, c, bad = 0;
    for (v = 0; v < 2; ++v) {
        hf_lut_params p = t_lut_defaults(n, (hf_lut_variant)v);
        float *d = t_dual_alloc(n);
        const size_t P = 4u * n * n;
        p.alpha_r_deg = -8.0;
        p.beta_r_deg = 7.0;
        CHECK_EQ_INT(hf_lut_bake_dual(&p, 0, n, d), HF_OK);
        for (j = 0; j < n; ++j) {
            double cd = (j + 0.5) / n;
            t_col k = t_column(p.eta, cd, 0.0);
            /* per sample of gamma: F, the chord, the weight, and which
               lobes leave forward (cos phi < 0) */
            for (s = 0; s < steps; ++s) {
                double g = (s + 0.5) * (T_PI / 2) / steps;
                F[s] = t_fresnel_e(&k, g, &E[s]);
                W[s] = cos(g) * (T_PI / 2) / steps;
                fw[s] = 0;
                for (c = 0; c < 3; ++c)
                    if (t_cos_exit(&k, c, g, v) < 0) fw[s] |= (unsigned char)(1 << c);
            }
            for (i = 0; i < n; ++i) {
                double u = (i + 0.5) / n, sig = u / (1 - u);
                double af[4] = {0, 0, 0, 0}, ab[4] = {0, 0, 0, 0};
                double Af = 0, Ab = 0, mf = 0, mb = 0, vf = 0, vb = 0;
                double der[3], want[12];
                const size_t at = 4u * (j * n + i);
                for (s = 0; s < steps; ++s) {
                    double T = exp(-sig * E[s]), f = F[s], A[4];
                    A[0] = W[s] * f;
                    A[1] = W[s] * (1 - f) * (1 - f) * T;
                    A[2] = A[1] * f * T;
                    A[3] = A[2] * f * T / (1 - f * T);
                    for (c = 0; c < 3; ++c) {
                        if (fw[s] & (1 << c)) af[c] += A[c];
                        else ab[c] += A[c];
                    }
                    af[3] += 0.5 * A[3];
                    ab[3] += 0.5 * A[3];
                }
                for (c = 0; c < 4; ++c) {
                    double alpha, var, beta;
                    t_lobe(&p, c, &alpha, &var, &beta);
                    Af += af[c];
                    Ab += ab[c];
                    mf += af[c] * alpha;
                    mb += ab[c] * alpha;
                    vf += af[c] * beta * beta;
                    vb += ab[c] * beta * beta;
                }
                mf /= Af;
                mb /= Ab;
                vf = sqrt(vf / Af);
                vb = sqrt(vb / Ab);
                t_dual_derived(Af, Ab, mf, mb, vf, vb, der);
                want[0] = Af; want[1] = mf; want[2] = vf; want[3] = 1;
                want[4] = Ab; want[5] = mb; want[6] = vb; want[7] = 1;
                want[8] = der[0]; want[9] = der[1]; want[10] = der[2];
                want[11] = 1;
                for (c = 0; c < 12; ++c) {
                    double x = d[P * (c / 4) + at + (c & 3)];
                    double tol = (c == 0 || c == 4) ? 2e-5
                                 : c == 8 ? 1e-4 * want[c] + 1e-7
                                          : 1e-4 + 1e-3 * fabs(want[c]);
                    if (!(fabs(x - want[c]) <= tol)) {
                        if (bad < 5)
                            printf("  dual(%d, %d) channel %d: %.9g, "
                                   "reference %.9g\n", i, j, c, x, want[c]);
                        ++bad;
                    }
                }
                CHECK_NEAR(d[at] + d[P + at], t_albedo_e(p.eta, cd, sig), 1e-5);
                CHECK(d[at] > 0 && d[at] < 1 && d[P + at] > 0);
            }
        }
        /* darker hair sends back less after many bounces */
        for (j = 0; j < n; ++j)
            for (i = 1; i < n; ++i)
                CHECK(d[2 * P + 4u * (j * n + i)] <
                      d[2 * P + 4u * (j * n + i - 1)]);
        free(d);
    }
    CHECK_EQ_INT(bad, 0);
    free(F);
    free(E);
    free(W);
    free(fw);
}

/* The textures of the energy-conserving fibre and the dual tables: any
   row split gives the same bytes; errors write nothing; extremes stay
   finite. */
static void test_lut_energy_contracts(void)
{
    static const int sizes[3] = {37, 1, 70};
    hf_rng rng;
    int z, w, k;
    hf_rng_seed(&rng, 777u, 3u);
    for (z = 0; z < 3; ++z) {
        int n = sizes[z];
        size_t bytes = sizeof(float) * 12u * n * n;
        hf_lut_params p = t_lut_energy(n);
        float *whole[3], *part[3];
        p.variant = z == 2 ? HF_LUT_EXACT : HF_LUT_CUBIC;
        for (w = 0; w < 3; ++w) {
            whole[w] = t_dual_alloc(n);
            part[w] = t_dual_alloc(n);
            memset(part[w], 0x5a, bytes);
        }
        CHECK_EQ_INT(hf_lut_bake_m(&p, 0, n, whole[0]), HF_OK);
        CHECK_EQ_INT(hf_lut_bake_n(&p, 0, n, whole[1]), HF_OK);
        CHECK_EQ_INT(hf_lut_bake_dual(&p, 0, n, whole[2]), HF_OK);
        {
            int first = 0;
            while (first < n) {
                int count = 1 + (int)hf_rng_below(&rng, 23u);
                if (count > n - first) count = n - first;
                CHECK_EQ_INT(hf_lut_bake_m(&p, first, count, part[0]), HF_OK);
                CHECK_EQ_INT(hf_lut_bake_n(&p, first, count, part[1]), HF_OK);
                CHECK_EQ_INT(hf_lut_bake_dual(&p, first, count, part[2]),
                             HF_OK);
                first += count;
            }
        }
        for (w = 0; w < 3; ++w) {
            size_t b = w == 2 ? bytes : bytes / 3;
            CHECK(memcmp(whole[w], part[w], b) == 0);
            CHECK(tb_finite(whole[w], b / sizeof(float)));
            free(whole[w]);
            free(part[w]);
        }
    }
    /* errors: nothing written */
    {
        const int n = 4;
        float d[12 * 16], keep[12 * 16];
        hf_lut_params p = t_lut_energy(n), b;
        memset(keep, 0x3c, sizeof keep);
        memcpy(d, keep, sizeof d);
        b = p; b.eta = 5.0;
        CHECK_EQ_INT(hf_lut_bake_dual(&b, 0, n, d), HF_ERROR_BAD_PARAMETER);
        CHECK_EQ_INT(hf_lut_bake_m(&b, 0, n, d), HF_ERROR_BAD_PARAMETER);
        b = p; b.beta_r_deg = NAN;
        CHECK_EQ_INT(hf_lut_bake_dual(&b, 0, n, d), HF_ERROR_NON_FINITE);
        CHECK_EQ_INT(hf_lut_bake_n(&b, 0, n, d), HF_ERROR_NON_FINITE);
        b = p; b.model = 7;
        CHECK_EQ_INT(hf_lut_bake_dual(&b, 0, n, d), HF_ERROR_BAD_PARAMETER);
        b = p; b.size = HF_LUT_MAX_SIZE + 1;
        CHECK_EQ_INT(hf_lut_bake_dual(&b, 0, 1, d), HF_ERROR_BAD_COUNT);
        CHECK_EQ_INT(hf_lut_bake_dual(NULL, 0, n, d), HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_lut_bake_dual(&p, 0, n, NULL), HF_ERROR_NULL_POINTER);
        CHECK_EQ_INT(hf_lut_bake_dual(&p, -1, 2, d), HF_ERROR_BAD_RANGE);
        CHECK_EQ_INT(hf_lut_bake_dual(&p, 2, 3, d), HF_ERROR_BAD_RANGE);
        CHECK_EQ_INT(hf_lut_bake_dual(&p, 1, 0x7fffffff, d), HF_ERROR_BAD_RANGE);
        CHECK_EQ_INT(hf_lut_bake_dual(&p, n, 0, d), HF_OK); /* empty */
        CHECK(memcmp(d, keep, sizeof d) == 0);
        /* one row: exactly that row of each plane */
        CHECK_EQ_INT(hf_lut_bake_dual(&p, 1, 1, d), HF_OK);
        for (k = 0; k < 3; ++k) {
            const float *pl = d + 4 * n * n * k, *kp = keep + 4 * n * n * k;
            CHECK(memcmp(pl, kp, sizeof(float) * 4 * n) == 0);
            CHECK(memcmp(pl + 4 * n, kp + 4 * n, sizeof(float) * 4 * n) != 0);
            CHECK(memcmp(pl + 8 * n, kp + 8 * n, sizeof(float) * 8 * n) == 0);
        }
    }
    /* extremes: finite, M and N not negative */
    {
        static const double etas[2] = {1.2, 3.0};
        static const double sig[3] = {0.0, 1e-3, 1e308};
        static const double betas[4] = {1e-3, 4.9e-324, 1e308, 40.0};
        static const double alphas[3] = {0.0, 1e5, -1e308};
        float *t = t_dual_alloc(5);
        int e, s, bb, a, fails = 0;
        size_t i;
        for (e = 0; e < 2; ++e)
            for (s = 0; s < 3; ++s)
                for (bb = 0; bb < 4; ++bb)
                    for (a = 0; a < 3; ++a) {
                        hf_lut_params p = t_lut_energy(5);
                        p.eta = etas[e];
                        p.sigma_a = sig[s];
                        p.beta_r_deg = betas[bb];
                        p.alpha_r_deg = alphas[a];
                        p.variant = (e + a) & 1;
                        p.explicit_zero =
                            HF_LUT_ZERO_SIGMA_A | HF_LUT_ZERO_ALPHA_R;
                        CHECK_EQ_INT(hf_lut_bake_m(&p, 0, 5, t), HF_OK);
                        if (!t_lut_all_ok(t, 5, 0)) ++fails;
                        CHECK_EQ_INT(hf_lut_bake_n(&p, 0, 5, t), HF_OK);
                        if (!t_lut_all_ok(t, 5, 0)) ++fails;
                        CHECK_EQ_INT(hf_lut_bake_dual(&p, 0, 5, t), HF_OK);
                        for (i = 0; i < 12u * 25; ++i)
                            if (!t_is_finite(t[i])) ++fails;
                    }
        CHECK_EQ_INT(fails, 0);
        free(t);
    }
}

static void test_bad_lut(void)
{
    hf_lut_params p, b;
    float tex[4 * 4 * 4], tex2[4 * 4 * 4], sc[4];
    unsigned char q[4 * 4 * 4];
    double o3[3];
    hf_lut_params_init(&p);
    p.size = 4;
    CHECK_EQ_INT(hf_lut_validate(&p, NULL), HF_OK);
#define TB_LUT(params, first, count, code)                                     \
    do {                                                                       \
        TB_FAILS(hf_lut_bake_m(&(params), (first), (count), tex), (code), tex, \
                 sizeof tex);                                                  \
        TB_FAILS(hf_lut_bake_n(&(params), (first), (count), tex), (code), tex, \
                 sizeof tex);                                                  \
        tb_fill(tex2, sizeof tex2);                                            \
        TB_FAILS(hf_lut_bake_n_rgb(&(params), (first), (count), tex, tex2),    \
                 (code), tex, sizeof tex);                                     \
        CHECK(tb_untouched(tex2, sizeof tex2));                                \
    } while (0)
    b = p; b.eta = TB_NAN; TB_LUT(b, 0, 4, HF_ERROR_NON_FINITE);
    b = p; b.eta = 1.0; TB_LUT(b, 0, 4, HF_ERROR_BAD_PARAMETER);
    b = p; b.eta = 3.5; TB_LUT(b, 0, 4, HF_ERROR_BAD_PARAMETER);
    b = p; b.alpha_r_deg = INFINITY; TB_LUT(b, 0, 4, HF_ERROR_NON_FINITE);
    b = p; b.beta_r_deg = -1e-9; TB_LUT(b, 0, 4, HF_ERROR_BAD_PARAMETER);
    b = p; b.beta_r_deg = -1.0; TB_LUT(b, 0, 4, HF_ERROR_BAD_PARAMETER);
    b = p; b.sigma_a = -0.1; TB_LUT(b, 0, 4, HF_ERROR_BAD_PARAMETER);
    b = p; b.sigma_a = NAN; TB_LUT(b, 0, 4, HF_ERROR_NON_FINITE);
    b = p; b.sigma_a_rgb[2] = -1.0; CHECK_EQ_INT(hf_lut_validate(&b, NULL), HF_ERROR_BAD_PARAMETER);
    b = p; b.variant = 2; TB_LUT(b, 0, 4, HF_ERROR_BAD_PARAMETER);
    b = p; b.size = -1; CHECK_EQ_INT(hf_lut_validate(&b, NULL), HF_ERROR_BAD_COUNT);
    b = p; b.size = 0; CHECK_EQ_INT(hf_lut_validate(&b, NULL), HF_OK); /* 256 */
    b = p; b.size = HF_LUT_MAX_SIZE + 1; CHECK_EQ_INT(hf_lut_validate(&b, NULL), HF_ERROR_BAD_COUNT);
    b = p; b.size = 0x7fffffff; CHECK_EQ_INT(hf_lut_validate(&b, NULL), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_lut_validate(NULL, NULL), HF_ERROR_NULL_POINTER);
    TB_LUT(p, -1, 1, HF_ERROR_BAD_RANGE);
    TB_LUT(p, 0, -1, HF_ERROR_BAD_RANGE);
    TB_LUT(p, 3, 2, HF_ERROR_BAD_RANGE);
    TB_LUT(p, 1, 0x7fffffff, HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_lut_bake_m(&p, 0, 4, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_lut_bake_n_rgb(&p, 0, 4, tex, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_lut_bake_m(NULL, 0, 4, tex), HF_ERROR_NULL_POINTER);
    /* extreme but valid: finite textures */
    b = p; b.beta_r_deg = 1e-300; b.sigma_a = 1e300; b.alpha_r_deg = -1e300;
    CHECK_EQ_INT(hf_lut_bake_m(&b, 0, 4, tex), HF_OK);
    CHECK(tb_finite(tex, 64));
    CHECK_EQ_INT(hf_lut_bake_n(&b, 0, 4, tex), HF_OK);
    CHECK(tb_finite(tex, 64));
    /* to_u8 */
    CHECK_EQ_INT(hf_lut_bake_n(&p, 0, 4, tex), HF_OK);
    TB_FAILS(hf_lut_to_u8(NULL, 4, NULL, q, sc), HF_ERROR_NULL_POINTER, q, sizeof q);
    CHECK_EQ_INT(hf_lut_to_u8(tex, 4, NULL, NULL, sc), HF_ERROR_NULL_POINTER);
    TB_FAILS(hf_lut_to_u8(tex, 0, NULL, q, sc), HF_ERROR_BAD_COUNT, q, sizeof q);
    TB_FAILS(hf_lut_to_u8(tex, HF_LUT_MAX_SIZE + 1, NULL, q, sc), HF_ERROR_BAD_COUNT, q, sizeof q);
    sc[0] = 1.0f; sc[1] = 0.0f; sc[2] = 1.0f; sc[3] = 1.0f;
    {
        float scales_in[4] = {1.0f, 0.0f, 1.0f, 1.0f};
        TB_FAILS(hf_lut_to_u8(tex, 4, scales_in, q, NULL), HF_ERROR_BAD_PARAMETER, q, sizeof q);
        scales_in[1] = TB_NAN;
        TB_FAILS(hf_lut_to_u8(tex, 4, scales_in, q, NULL), HF_ERROR_BAD_PARAMETER, q, sizeof q);
    }
    tex[17] = TB_NAN;
    tb_fill(sc, sizeof sc);
    TB_FAILS(hf_lut_to_u8(tex, 4, NULL, q, sc), HF_ERROR_NON_FINITE, q, sizeof q);
    CHECK(tb_untouched(sc, sizeof sc));
    /* eval */
    o3[0] = o3[1] = o3[2] = -7.0;
    CHECK_EQ_INT(hf_lut_eval_m(&p, NAN, o3), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_lut_eval_m(&p, INFINITY, o3), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_lut_eval_m(&p, 0.1, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 2.0, 0.5, o3), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, -0.1, o3), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_lut_eval_n(&p, 0.5, 4.0, o3), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_lut_eval_n(&p, NAN, 0.5, o3), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_lut_eval_n(NULL, 0.5, 0.5, o3), HF_ERROR_NULL_POINTER);
    CHECK(o3[0] == -7.0 && o3[1] == -7.0 && o3[2] == -7.0);
    /* eval with a size that the bake refuses: size is ignored */
    b = p; b.size = 0;
    CHECK_EQ_INT(hf_lut_eval_m(&b, 0.1, o3), HF_OK);
#undef TB_LUT
}

static void test_defaults_zeroed_lut_params_are_init(void)
{
    hf_lut_params zero, init;
    float *a = t_lut_alloc(8), *b = t_lut_alloc(8);
    double m0[3], m1[3];
    memset(&zero, 0, sizeof zero);
    zero.size = 8;
    hf_lut_params_init(&init);
    init.size = 8;
    CHECK_EQ_INT(hf_lut_validate(&zero, NULL), HF_OK);
    CHECK_EQ_INT(hf_lut_bake_n(&zero, 0, 8, a), HF_OK);
    CHECK_EQ_INT(hf_lut_bake_n(&init, 0, 8, b), HF_OK);
    CHECK(memcmp(a, b, sizeof(float) * 4 * 8 * 8) == 0);
    CHECK_EQ_INT(hf_lut_bake_m(&zero, 0, 8, a), HF_OK);
    CHECK_EQ_INT(hf_lut_bake_m(&init, 0, 8, b), HF_OK);
    CHECK(memcmp(a, b, sizeof(float) * 4 * 8 * 8) == 0);
    /* alpha 0 on purpose: the R lobe peaks at theta_h 0, not at -7.5 deg */
    zero.explicit_zero = HF_LUT_ZERO_ALPHA_R;
    CHECK_EQ_INT(hf_lut_eval_m(&zero, 0.0, m0), HF_OK);
    CHECK_EQ_INT(hf_lut_eval_m(&zero, 7.5 * T_DEG, m1), HF_OK);
    CHECK(m0[0] > m1[0]);
    free(a);
    free(b);
}

/* 9. LUT baking: the energy-conserving fibre: its tests, in the order they run */
#define T_FIBRE_TESTS(X)                                                       \
    X(test_lut_energy_params)                                                  \
    X(test_lut_energy_m_reference)                                             \
    X(test_lut_energy_m_normalised)                                            \
    X(test_lut_energy_n_reference)                                             \
    X(test_lut_furnace)                                                        \
    X(test_lut_dual_reference)                                                 \
    X(test_lut_energy_contracts)                                               \
    X(test_bad_lut)                                                            \
    X(test_defaults_zeroed_lut_params_are_init)

/* ==== 10. the fur object ================================================== */

static void test_fur_create_counts_and_welding(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_diag d;
    int i, j;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_OK);
    if (!f) return;
    CHECK_EQ_INT(hf_fur_get_info(f, &info), HF_OK);
    /* seam column and split poles weld: (R - 1) * S + 2 distinct positions */
    CHECK_EQ_INT(info.pure_guide_count, (FR - 1) * FS + 2);
    CHECK(info.lod_guide_count > 0);
    CHECK_EQ_INT(info.guide_count, info.pure_guide_count + info.lod_guide_count);
    CHECK_EQ_INT(info.strand_count, 500);
    CHECK_EQ_INT(info.drawn_strand_count, 500);
    CHECK_EQ_INT(info.points_per_strand, 8);
    /* at rest, strand roots lie on the unit sphere's guide triangles and
       every strand has its own length along it */
    for (i = 0; i < info.strand_count; ++i) {
        const float *p = info.strand_points + (size_t)i * 8 * 3;
        double r0 = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), len = 0;
        CHECK(r0 <= 1.0 + 1e-5 && r0 > 0.85);
        for (j = 1; j < 8; ++j) {
            const float *a = p + 3 * (j - 1), *b = p + 3 * j;
            len += sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                        (b[2] - a[2]) * (b[2] - a[2]));
        }
        CHECK(len > 0.2 && len < 0.31);
    }
    hf_fur_destroy(f);
}

/* hf_fur_desc.comb / comb_map: every guide grows along the comb at rest
   (the map wins over the per-vertex directions); without them, along the
   normal. */
static void t_fur_guide_dirs(const hf_fur *f, double dir_out[3], double *min_dot,
                             const double want[3])
{
    hf_fur_info info;
    int g, k, P;
    *min_dot = 2.0;
    hf_fur_get_info(f, &info);
    P = info.points_per_strand;
    for (g = 0; g < info.guide_count; ++g) {
        const float *p = info.guide_points + (size_t)g * (size_t)P * 3u;
        double d[3], len = 0.0, dot = 0.0;
        for (k = 0; k < 3; ++k) {
            d[k] = p[3 * (P - 1) + k] - p[k];
            len += d[k] * d[k];
        }
        len = sqrt(len);
        for (k = 0; k < 3; ++k) {
            dir_out[k] = d[k] / len;
            dot += dir_out[k] * want[k];
        }
        if (dot < *min_dot) *min_dot = dot;
    }
}

static void test_fur_comb(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    static float comb[(FR + 1) * (FS + 1) * 3];
    unsigned char px[3] = {255, 128, 128}; /* 2c - 1: about +x */
    hf_map cmap;
    const double down[3] = {0, -1, 0}, px_dir[3] = {1, 0, 0};
    double d[3], worst;
    int i;
    t_fur_scene_init(&sc, 1.0f);
    for (i = 0; i < (FR + 1) * (FS + 1); ++i) {
        comb[3 * i] = 0.0f;
        comb[3 * i + 1] = -2.5f; /* any length */
        comb[3 * i + 2] = 0.0f;
    }
    /* no comb: along the normals, which point every way */
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    t_fur_guide_dirs(f, d, &worst, down);
    CHECK(worst < 0.0);
    hf_fur_destroy(f);
    /* per-vertex comb: all down */
    sc.desc.comb = comb;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    t_fur_guide_dirs(f, d, &worst, down);
    CHECK(worst > 1.0 - 1e-5);
    hf_fur_destroy(f);
    /* the map wins */
    memset(&cmap, 0, sizeof cmap);
    cmap.data = px;
    cmap.width = cmap.height = 1;
    cmap.channels = 3;
    sc.desc.comb_map = &cmap;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    t_fur_guide_dirs(f, d, &worst, px_dir);
    CHECK(worst > 0.9999);
    hf_fur_destroy(f);
    /* a comb map with fewer than 3 channels is refused, naming it */
    {
        hf_diag diag;
        cmap.channels = 1;
        f = NULL;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &diag), HF_ERROR_BAD_PARAMETER);
        CHECK(f == NULL);
    }
}

/* Authored guide curves: straight curves along their root normal make
   every guide straight along its own normal, of the curves' length; a bent
   curve gives every guide its length; strands take the guides' lengths. */
static void test_fur_guide_curves(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    static float pts[6 * 4 * 3];
    int npts[6], c, g, j, k;
    const float L = 0.4f;
    /* six straight curves at the poles and around the equator */
    static const float dirs[6][3] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0},
                                     {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
    t_fur_scene_init(&sc, 1.0f);
    for (c = 0; c < 6; ++c) {
        npts[c] = 4;
        for (j = 0; j < 4; ++j)
            for (k = 0; k < 3; ++k)
                pts[(c * 4 + j) * 3 + k] = dirs[c][k] * (1.0f + L * j / 3.0f);
    }
    sc.desc.guide_curves = pts;
    sc.desc.guide_curve_points = npts;
    sc.desc.guide_curve_count = 6;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    {
        double worst = 0.0;
        for (g = 0; g < info.guide_count; ++g) {
            const float *q = info.guide_points + (size_t)g * 8 * 3;
            double n[3], l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            for (k = 0; k < 3; ++k) n[k] = q[k] / l; /* unit sphere normal */
            for (j = 0; j < 8; ++j)
                for (k = 0; k < 3; ++k) {
                    double want = q[k] + n[k] * L * j / 7.0;
                    double e = fabs(q[3 * j + k] - want);
                    if (e > worst) worst = e;
                }
        }
        /* LOD guides sit on flat triangles: their normals are blends, not
           the radial direction, hence the tolerance */
        CHECK(worst < 0.02);
    }
    /* strands: their rest length is the guides' (0.4), not max_length */
    for (g = 0; g < info.strand_count; ++g)
        CHECK(fabs(info.strand_lengths[g] - L) < 1e-3);
    hf_fur_destroy(f);

    /* one bent curve: up 0.2, then sideways 0.3; every guide 0.5 long */
    {
        static const float bent[9] = {0, 1, 0, 0, 1.2f, 0, 0.3f, 1.2f, 0};
        int nb = 3;
        double worst = 0.0;
        sc.desc.guide_curves = bent;
        sc.desc.guide_curve_points = &nb;
        sc.desc.guide_curve_count = 1;
        f = NULL;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
        if (!f) return;
        hf_fur_get_info(f, &info);
        for (g = 0; g < info.guide_count; ++g) {
            const float *q = info.guide_points + (size_t)g * 8 * 3;
            double len = 0.0;
            for (j = 1; j < 8; ++j)
                len += sqrt((q[3 * j] - q[3 * j - 3]) * (q[3 * j] - q[3 * j - 3]) +
                            (q[3 * j + 1] - q[3 * j - 2]) * (q[3 * j + 1] - q[3 * j - 2]) +
                            (q[3 * j + 2] - q[3 * j - 1]) * (q[3 * j + 2] - q[3 * j - 1]));
            /* resampled evenly: the corner is cut by at most a segment */
            if (fabs(len - 0.5) > worst) worst = fabs(len - 0.5);
        }
        CHECK(worst < 0.02);
        hf_fur_destroy(f);
    }

    /* bad curves: a clear code, nothing made */
    {
        static const float two[6] = {0, 1, 0, 0, 1.5f, 0};
        static const float nan_pt[6] = {0, 1, 0, 0, NAN, 0};
        static const float flat[6] = {0, 1, 0, 0, 1, 0};
        int n2 = 2, n1 = 1;
        hf_fur *const untouched = (hf_fur *)(uintptr_t)0x10;
        hf_diag d;
        f = untouched;
        sc.desc.guide_curves = two;
        sc.desc.guide_curve_points = &n2;
        sc.desc.guide_curve_count = -1;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_COUNT);
        sc.desc.guide_curve_count = 1;
        sc.desc.guide_curves = NULL;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_NULL_POINTER);
        sc.desc.guide_curves = two;
        sc.desc.guide_curve_points = &n1;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_COUNT);
        sc.desc.guide_curve_points = &n2;
        sc.desc.guide_curves = nan_pt;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_NON_FINITE);
        CHECK(strstr(d.message, "curve 0, point 1") != NULL);
        sc.desc.guide_curves = flat;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_PARAMETER);
        CHECK(f == untouched);
    }
}

/* Styling: a curl of radius r keeps guides within 2 r of their straight
   shape and reaches near 2 r; same seed, same bytes; frizz depends on the
   seed; colour variation stays within its factor. */
static double t_max_dev_from_straight(const hf_fur_info *info, int P)
{
    double worst = 0.0;
    int g, j, k;
    for (g = 0; g < info->guide_count; ++g) {
        const float *q = info->guide_points + (size_t)g * (size_t)P * 3u;
        double n[3], l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        for (k = 0; k < 3; ++k) n[k] = q[k] / l;
        for (j = 0; j < P; ++j) {
            double d[3], t, e = 0.0;
            for (k = 0; k < 3; ++k) d[k] = q[3 * j + k] - q[k];
            t = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            for (k = 0; k < 3; ++k) e += (d[k] - t * n[k]) * (d[k] - t * n[k]);
            if (sqrt(e) > worst) worst = sqrt(e);
        }
    }
    return worst;
}

static void test_fur_styling(void)
{
    t_fur_scene sc;
    hf_fur *a = NULL, *b = NULL;
    hf_fur_info ia, ib;
    const float r = 0.03f;
    double dev;
    int i, differ = 0;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.points_per_strand = 24;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK);
    if (!a) return;
    hf_fur_get_info(a, &ia);
    CHECK(t_max_dev_from_straight(&ia, 24) < 0.02); /* LOD normals only */
    hf_fur_destroy(a);
    sc.desc.curl_radius = r;
    sc.desc.curl_turns = 3.0f;
    a = NULL;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &b, NULL), HF_OK);
    if (!a || !b) return;
    hf_fur_get_info(a, &ia);
    hf_fur_get_info(b, &ib);
    dev = t_max_dev_from_straight(&ia, 24);
    CHECK(dev > 1.5 * r && dev < 2.0 * r + 0.02);
    CHECK(memcmp(ia.guide_points, ib.guide_points,
                 sizeof(float) * 3u * 24u * (size_t)ia.guide_count) == 0);
    hf_fur_destroy(a);
    hf_fur_destroy(b);
    /* frizz: another seed, other points */
    sc.desc.curl_radius = 0.0f;
    sc.desc.frizz = 0.5f;
    a = b = NULL;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK);
    sc.desc.seed = 99;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &b, NULL), HF_OK);
    if (!a || !b) return;
    hf_fur_get_info(a, &ia);
    hf_fur_get_info(b, &ib);
    CHECK(memcmp(ia.guide_points, ib.guide_points,
                 sizeof(float) * 3u * 24u * (size_t)ia.guide_count) != 0);
    hf_fur_destroy(a);
    hf_fur_destroy(b);
    /* colour variation of white strands: factors in [0.7, 1], not all 1 */
    sc.desc.frizz = 0.0f;
    sc.desc.color_variation = 0.3f;
    a = NULL;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK);
    if (!a) return;
    hf_fur_get_info(a, &ia);
    for (i = 0; i < ia.strand_count; ++i) {
        float c = ia.strand_colors[4 * i];
        CHECK(c >= 0.7f - 1e-6f && c <= 1.0f);
        CHECK(ia.strand_colors[4 * i + 1] == c && ia.strand_colors[4 * i + 3] == 1.0f);
        differ += c < 0.99f;
    }
    CHECK(differ > ia.strand_count / 4);
    hf_fur_destroy(a);
    /* bad styling values are refused */
    {
        hf_diag d;
        a = NULL;
        sc.desc.color_variation = 1.5f;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, &d), HF_ERROR_BAD_PARAMETER);
        CHECK(strstr(d.message, "color_variation") != NULL);
        sc.desc.color_variation = 0.0f;
        sc.desc.curl_radius = NAN;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, &d), HF_ERROR_BAD_PARAMETER);
        sc.desc.curl_radius = -1.0f;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, &d), HF_ERROR_BAD_PARAMETER);
        CHECK(a == NULL);
    }
}

/* A groom without a mesh: 300 helix strands of 16 evenly spaced points on
   a patch of the unit sphere. At rest the fur's strands are the groom's
   own; moved rigidly (animated guides, no blend time), they are the
   groom's strands moved by the same matrix; ranges give the same bytes. */
#define TG_S 300
#define TG_P 16
static void t_groom_make(float *pts, int *npts)
{
    hf_rng rng;
    int s, j;
    hf_rng_seed(&rng, 11, 0);
    for (s = 0; s < TG_S; ++s) {
        double th = 0.2 + 1.2 * hf_rng_float(&rng), ph = 6.2831853 * hf_rng_float(&rng);
        double n[3], u[3], v[3], phase = 6.2831853 * hf_rng_float(&rng), l;
        n[0] = sin(th) * cos(ph); n[1] = cos(th); n[2] = sin(th) * sin(ph);
        u[0] = -sin(ph); u[1] = 0.0; u[2] = cos(ph);
        v[0] = n[1] * u[2] - n[2] * u[1];
        v[1] = n[2] * u[0] - n[0] * u[2];
        v[2] = n[0] * u[1] - n[1] * u[0];
        l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        npts[s] = TG_P;
        for (j = 0; j < TG_P; ++j) {
            /* a helix about the normal: equal chords for equal steps */
            double a = phase + 0.9 * j, r = 0.02;
            int k;
            for (k = 0; k < 3; ++k)
                pts[3 * (s * TG_P + j) + k] =
                    (float)(n[k] * (1.0 + 0.02 * j) +
                            r * (cos(a) - cos(phase)) * u[k] +
                            r * (sin(a) - sin(phase)) * v[k] / l);
        }
    }
}

/* A groom description of t_groom_make's strands, a fifth of them guides. */
static void t_groom_desc(hf_groom_desc *gd, float *pts, int *npts)
{
    t_groom_make(pts, npts);
    memset(gd, 0, sizeof *gd);
    gd->points = pts;
    gd->strand_points = npts;
    gd->strand_count = TG_S;
    gd->guide_fraction = 0.2f;
}

/* The largest distance between the fur's strands and the groom's own,
   moved by m (rows of 3x4; NULL: not moved), each matched by the nearest
   root. */
static double t_groom_worst(const hf_fur_info *info, const float *pts,
                            const float *m)
{
    static const float id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    double worst = 0.0;
    int i, j, k, s;
    if (!m) m = id;
    for (i = 0; i < info->strand_count; ++i) {
        const float *q = info->strand_points + (size_t)i * TG_P * 3, *own = pts;
        double best = 1e30;
        for (s = 0; s < TG_S; ++s) {
            const float *p = pts + 3 * s * TG_P;
            double d = 0.0;
            for (k = 0; k < 3; ++k) {
                double x = m[4 * k] * p[0] + m[4 * k + 1] * p[1] +
                           m[4 * k + 2] * p[2] + m[4 * k + 3];
                d += (x - q[k]) * (x - q[k]);
            }
            if (d < best) { best = d; own = p; }
        }
        for (j = 0; j < TG_P; ++j)
            for (k = 0; k < 3; ++k) {
                const float *p = own + 3 * j;
                double x = m[4 * k] * p[0] + m[4 * k + 1] * p[1] +
                           m[4 * k + 2] * p[2] + m[4 * k + 3];
                if (fabs(x - q[3 * j + k]) > worst) worst = fabs(x - q[3 * j + k]);
            }
    }
    return worst;
}

/* hf_fur_interpolate_points against hf_fur_interpolate then
   hf_fur_points: the same bytes at every interpolation and points level,
   with and without streaming stores, over split ranges written from
   out_first; the fur's strand points are left as they were. Returns the
   number of mismatching configurations. */
static int t_ipoints_same(hf_fur *f, const hf_ribbon_params *view0)
{
    static const int lv[3] = {HF_SIMD_AUTO, HF_SIMD_SSE2, HF_SIMD_SCALAR};
    hf_fur_info info;
    hf_ribbon_params view = *view0;
    float *ref, *got, *keep;
    size_t n4, n3;
    int a, b, nt, sp, bad = 0;
    hf_fur_get_info(f, &info);
    n4 = (size_t)info.strand_count * (size_t)info.points_per_strand * 4u;
    n3 = (size_t)info.strand_count * (size_t)info.points_per_strand * 3u;
    ref = (float *)malloc(sizeof(float) * n4);
    got = (float *)malloc(sizeof(float) * n4);
    keep = (float *)malloc(sizeof(float) * n3);
    if (!ref || !got || !keep) return 1;
    /* the reference at the fur's default kernels */
    hf_fur_set_kernels(f, HF_SIMD_AUTO, 0);
    memset(ref, 0xab, sizeof(float) * n4);
    if (hf_fur_interpolate(f, 0, info.strand_count) != HF_OK ||
        hf_fur_points(f, 0, info.strand_count, &view, ref) != HF_OK)
        ++bad;
    /* the fur's strand points stale, so that a write to them shows */
    memcpy(keep, info.strand_points, sizeof(float) * n3);
    for (a = 0; a < 4; ++a) { /* interpolation level */
        hf_fur_set_kernels(f, tr_levels[a], 0);
        for (b = 0; b < 3; ++b)     /* points level */
            for (nt = 0; nt < 2; ++nt)
                for (sp = 1; sp <= 3; sp += 2) { /* 1 and 3 ranges */
                    int k, first = 0;
                    view.simd = lv[b];
                    view.nontemporal = nt;
                    memset(got, 0xcd, sizeof(float) * n4);
                    for (k = 0; k < sp; ++k) {
                        const int cnt = info.strand_count * (k + 1) / sp - first;
                        /* each range into its own part of the buffer */
                        view.out_first = first;
                        if (hf_fur_interpolate_points(
                                f, first, cnt, &view,
                                got + (size_t)first * (size_t)info.points_per_strand * 4u) !=
                            HF_OK)
                            ++bad;
                        first += cnt;
                    }
                    if (memcmp(ref, got, sizeof(float) * n4) != 0) ++bad;
                }
    }
    if (memcmp(keep, info.strand_points, sizeof(float) * n3) != 0) ++bad;
    hf_fur_set_kernels(f, HF_SIMD_AUTO, 0);
    free(ref);
    free(got);
    free(keep);
    return bad;
}

static void test_fur_groom(void)
{
    static float pts[TG_S * TG_P * 3];
    static int npts[TG_S];
    static float whole[TG_S * TG_P * 3];
    hf_groom_desc gd;
    hf_rope_params rp;
    hf_fur *f = NULL;
    hf_fur_info info;
    double worst = 0.0;
    int i, j, k;
    /* a rotation of 40 degrees about (1, 2, 3) / |.|, then a move */
    float m[12];
    {
        double ax[3] = {1, 2, 3}, l = sqrt(14.0), c = cos(0.698), sn = sin(0.698);
        for (k = 0; k < 3; ++k) ax[k] /= l;
        for (i = 0; i < 3; ++i)
            for (j = 0; j < 3; ++j) {
                double e = (1 - c) * ax[i] * ax[j] + (i == j ? c : 0.0);
                if ((i + 1) % 3 == j) e -= sn * ax[3 - i - j];
                if ((j + 1) % 3 == i) e += sn * ax[3 - i - j];
                m[4 * i + j] = (float)e;
            }
        m[3] = 0.3f; m[7] = -0.2f; m[11] = 0.5f;
    }
    t_groom_desc(&gd, pts, npts);
    gd.seed = 3;
    hf_rope_params_init(&rp);
    rp.explicit_zero = HF_ROPE_ZERO_BLEND_TIME;
    rp.mode_blend_time = 0.0f;
    gd.rope_params = &rp;
    CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(info.strand_count, TG_S);
    CHECK_EQ_INT(info.guide_count, 60);
    CHECK_EQ_INT(info.points_per_strand, TG_P);
    /* at rest: the groom's own strands */
    worst = t_groom_worst(&info, pts, NULL);
    CHECK(worst < 2e-6);
    /* moved rigidly: the groom moved by m */
    CHECK_EQ_INT(hf_fur_set_mode(f, 0, info.guide_count, HF_ROPE_ANIMATED), HF_OK);
    CHECK_EQ_INT(hf_fur_set_transform(f, m, 0, info.guide_count), HF_OK);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0), HF_OK);
    CHECK_EQ_INT(hf_fur_interpolate(f, 0, TG_S), HF_OK);
    memcpy(whole, info.strand_points, sizeof whole);
    worst = t_groom_worst(&info, pts, m);
    CHECK(worst < 1e-5);
    /* ranges: the same bytes */
    CHECK_EQ_INT(hf_fur_interpolate(f, 0, 123), HF_OK);
    CHECK_EQ_INT(hf_fur_interpolate(f, 123, TG_S - 123), HF_OK);
    CHECK(memcmp(whole, info.strand_points, sizeof whole) == 0);
    /* its GPU path in one pass, offsets included: the same bytes */
    {
        hf_ribbon_params view;
        memset(&view, 0, sizeof view);
        view.root_width = 0.003f;
        CHECK_EQ_INT(t_ipoints_same(f, &view), 0);
    }
    /* a groom has no mesh */
    {
        t_fur_scene sc;
        t_fur_scene_init(&sc, 1.0f);
        CHECK_EQ_INT(hf_fur_set_roots(f, &sc.desc.mesh, 0, 1), HF_ERROR_BAD_PARAMETER);
    }
    CHECK_EQ_INT(hf_fur_set_transform(f, NULL, 0, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_set_transform(f, m, 50, 11), HF_ERROR_BAD_RANGE);
    hf_fur_destroy(f);
    /* bad grooms: a code, a message, nothing made */
    {
        hf_fur *const untouched = (hf_fur *)(uintptr_t)0x20;
        hf_diag d;
        float keep = pts[5];
        f = untouched;
        gd.guide_fraction = 1.5f;
        CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, &d), HF_ERROR_BAD_PARAMETER);
        CHECK(strstr(d.message, "guide_fraction") != NULL);
        gd.guide_fraction = 0.0f; /* 0 = 0.1 */
        npts[7] = 1;
        CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, &d), HF_ERROR_BAD_COUNT);
        npts[7] = TG_P;
        pts[5] = NAN;
        CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, &d), HF_ERROR_NON_FINITE);
        pts[5] = keep;
        gd.strand_count = 0;
        CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, &d), HF_ERROR_BAD_COUNT);
        CHECK_EQ_INT(hf_fur_create_groom(NULL, &f, &d), HF_ERROR_NULL_POINTER);
        CHECK(f == untouched);
        gd.strand_count = TG_S;
        CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, &d), HF_OK); /* 0.1: 30 */
        if (f != untouched) {
            hf_fur_get_info(f, &info);
            CHECK_EQ_INT(info.guide_count, 30);
            hf_fur_destroy(f);
        }
    }
}

/* Distinct strand tips (within 1e-5 m), for clumping. */
static int t_distinct_tips(const hf_fur_info *info)
{
    int i, j, n = 0, P = info->points_per_strand;
    for (i = 0; i < info->strand_count; ++i) {
        const float *a = info->strand_points + ((size_t)i * (size_t)P + (size_t)P - 1) * 3u;
        for (j = 0; j < i; ++j) {
            const float *b = info->strand_points + ((size_t)j * (size_t)P + (size_t)P - 1) * 3u;
            if (fabs(a[0] - b[0]) < 1e-5 && fabs(a[1] - b[1]) < 1e-5 &&
                fabs(a[2] - b[2]) < 1e-5)
                break;
        }
        n += j == i;
    }
    return n;
}

/* hf_fur_settle_rest drapes grown hair: its tips fall, it keeps its
   lengths, it is at rest in the new shape (stiff hair held there stays),
   and bad input is refused with nothing changed. */
static void test_fur_settle_rest(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_collider ball;
    hf_rope_params p;
    float st, *before, *settled;
    size_t n;
    double tip0 = 0.0, tip1 = 0.0, moved = 0.0;
    int g, k;
    t_fur_scene_init(&sc, 0.1f);
    sc.desc.max_length = 0.2f;
    sc.desc.grid_resolution = 16;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(info.grid_resolution, 16);
    n = (size_t)info.guide_count * 8u * 3u;
    before = (float *)malloc(n * sizeof(float));
    settled = (float *)malloc(n * sizeof(float));
    memcpy(before, info.guide_points, n * sizeof(float));
    tr_head_sphere(&ball);
    CHECK_EQ_INT(hf_fur_settle_rest(f, -1.0f, &ball, 1), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_fur_settle_rest(f, (float)NAN, &ball, 1),
                 HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_fur_settle_rest(f, 1.0f, NULL, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_settle_rest(NULL, 1.0f, NULL, 0),
                 HF_ERROR_NULL_POINTER);
    CHECK(memcmp(before, info.guide_points, n * sizeof(float)) == 0);
    CHECK_EQ_INT(hf_fur_settle_rest(f, 1.5f, &ball, 1), HF_OK);
    memcpy(settled, info.guide_points, n * sizeof(float));
    for (g = 0; g < info.guide_count; ++g) {
        tip0 += before[(g * 8 + 7) * 3 + 1] - before[(g * 8) * 3 + 1];
        tip1 += settled[(g * 8 + 7) * 3 + 1] - settled[(g * 8) * 3 + 1];
    }
    CHECK(tip1 < tip0 - 0.02 * info.guide_count); /* 2 cm lower on average */
    hf_fur_max_stretch(f, &st);
    CHECK(st <= 1e-4f);
    /* held stiffly, it stays where it settled */
    hf_rope_params_init(&p);
    p.global_stiffness_root = p.global_stiffness_tip = 1.0f;
    hf_fur_set_rope_params(f, &p);
    for (k = 0; k < 30; ++k) {
        hf_fur_build_grid(f, 0, info.grid_resolution);
        CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f,
                                     &ball, 1),
                     HF_OK);
    }
    for (k = 0; k < (int)n; ++k) {
        double d = fabs((double)info.guide_points[k] - settled[k]);
        moved = d > moved ? d : moved;
    }
    CHECK(moved < 2e-3);
    CHECK_EQ_INT(hf_fur_build_grid(f, 0, 17), HF_ERROR_BAD_RANGE);
    hf_fur_destroy(f);
    /* no grid: the empty range only; a bad resolution refused */
    sc.desc.grid_resolution = 0;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (f) {
        CHECK_EQ_INT(hf_fur_build_grid(f, 0, 0), HF_OK);
        CHECK_EQ_INT(hf_fur_build_grid(f, 0, 1), HF_ERROR_BAD_RANGE);
        CHECK_EQ_INT(hf_fur_settle_rest(f, 0.2f, NULL, 0), HF_OK);
        hf_fur_destroy(f);
    }
    sc.desc.grid_resolution = 3;
    f = NULL;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_ERROR_BAD_PARAMETER);
    CHECK(f == NULL);
    free(before);
    free(settled);
}

/* hf_fur_settle_rest on a groom (with a grid): its guides drape, their
   lengths kept. */
static void test_fur_groom_settle_rest(void)
{
    hf_fur *f = NULL;
    hf_fur_info info;
    float st;
    {
        static float pts[TG_S * TG_P * 3];
        static int npts[TG_S];
        hf_groom_desc gd;
        double drop[2] = {0.0, 0.0};
        int s2, pass;
        t_groom_desc(&gd, pts, npts);
        gd.grid_resolution = 8;
        f = NULL;
        CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, NULL), HF_OK);
        if (!f) return;
        for (pass = 0; pass < 2; ++pass) {
            hf_fur_get_info(f, &info);
            CHECK_EQ_INT(info.grid_resolution, 8);
            for (s2 = 0; s2 < info.guide_count; ++s2) {
                const float *g = info.guide_points + (size_t)s2 * TG_P * 3;
                drop[pass] += g[3 * (TG_P - 1) + 1] - g[1];
            }
            if (pass == 0)
                CHECK_EQ_INT(hf_fur_settle_rest(f, 1.0f, NULL, 0), HF_OK);
        }
        CHECK(drop[1] < drop[0] - 0.01 * info.guide_count);
        hf_fur_max_stretch(f, &st);
        CHECK(st <= 1e-4f);
        hf_fur_destroy(f);
    }
}

/* Clump leaders against a brute-force search (the library's own fields:
   this file builds the implementation): in strand order, a strand with
   no earlier leader within its radius leads, every other one follows
   the nearest earlier leader, which lies within its radius. Radii from
   no map and from a grey one (the grid's cells follow the largest radius
   in use); roots recomputed here, so distances compare within 1e-5. */
static void test_fur_clump_leaders_nearest(void)
{
    unsigned char grey = 170;
    hf_map mg;
    int pass;
    memset(&mg, 0, sizeof mg);
    mg.data = &grey;
    mg.width = mg.height = mg.channels = 1;
    for (pass = 0; pass < 2; ++pass) {
        t_fur_scene sc;
        hf_fur *f = NULL;
        hf_fur_info info;
        float *root;
        double r, r2;
        int S, P, i, j, bad = 0, leaders = 0;
        t_fur_scene_init(&sc, 1.0f);
        sc.desc.clump = 1.0f;
        sc.desc.clump_size = 0.25f;
        sc.desc.clump_size_map = pass ? &mg : NULL;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
        if (!f) return;
        hf_fur_get_info(f, &info);
        S = info.strand_count;
        P = info.points_per_strand;
        r = 0.25 * (pass ? 170.0 / 255.0 : 1.0);
        r2 = r * r;
        root = (float *)malloc(sizeof(float) * 3u * (size_t)S);
        CHECK(f->leader != NULL);
        for (i = 0; i < S && root && f->leader; ++i) {
            const hf_strand_binding *b = &f->bindings[i];
            int k;
            for (k = 0; k < 3; ++k)
                root[3 * i + k] =
                    b->weight[0] * info.guide_points[(size_t)b->guide[0] * P * 3u + k] +
                    b->weight[1] * info.guide_points[(size_t)b->guide[1] * P * 3u + k] +
                    b->weight[2] * info.guide_points[(size_t)b->guide[2] * P * 3u + k];
        }
        for (i = 0; i < S && root && f->leader; ++i) {
            const int L = (int)f->leader[i];
            double near = 1e30, dl;
#define T_D2(a, c)                                                             \
    (((double)root[3 * (a)] - root[3 * (c)]) * ((double)root[3 * (a)] - root[3 * (c)]) + \
     ((double)root[3 * (a) + 1] - root[3 * (c) + 1]) *                         \
         ((double)root[3 * (a) + 1] - root[3 * (c) + 1]) +                      \
     ((double)root[3 * (a) + 2] - root[3 * (c) + 2]) *                          \
         ((double)root[3 * (a) + 2] - root[3 * (c) + 2]))
            for (j = 0; j < i; ++j)
                if ((int)f->leader[j] == j && T_D2(i, j) < near) near = T_D2(i, j);
            if (L == i) {
                ++leaders;
                bad += near < r2 * (1.0 - 1e-5); /* a leader was within reach */
            } else {
                dl = T_D2(i, L);
                bad += L > i || (int)f->leader[L] != L || dl > r2 * (1.0 + 1e-5) ||
                       dl > near * (1.0 + 1e-5) + 1e-12;
            }
#undef T_D2
        }
        CHECK_EQ_INT(bad, 0);
        CHECK(leaders > 8 && leaders < S / 2);
        free(root);
        hf_fur_destroy(f);
    }
}

/* clump_size: with clump 1 every tip lands on its leader's, so there are
   as many distinct tips as leaders: few for large clumps, more for small
   ones; leaders are clump_size apart. Ranges give the same bytes. */
static void test_fur_clump_size(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    int big, small, guides_only;
    float *whole;
    size_t n;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.clump = 1.0f;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    guides_only = t_distinct_tips(&info); /* tips on the main guides */
    hf_fur_destroy(f);
    sc.desc.clump_size = 0.8f;
    f = NULL;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    big = t_distinct_tips(&info);
    n = (size_t)info.strand_count * (size_t)info.points_per_strand * 3u;
    whole = (float *)malloc(sizeof(float) * n);
    memcpy(whole, info.strand_points, sizeof(float) * n);
    CHECK_EQ_INT(hf_fur_interpolate(f, 0, 77), HF_OK);
    CHECK_EQ_INT(hf_fur_interpolate(f, 77, info.strand_count - 77), HF_OK);
    CHECK(memcmp(whole, info.strand_points, sizeof(float) * n) == 0);
    free(whole);
    hf_fur_destroy(f);
    sc.desc.clump_size = 0.25f;
    f = NULL;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    small = t_distinct_tips(&info);
    hf_fur_destroy(f);
    /* on a unit sphere: 0.8 m clumps are a few dozen, 0.25 m a few hundred */
    CHECK(big >= 8 && big < 60);
    CHECK(small > 2 * big && small < info.strand_count);
    CHECK(guides_only > big);
    /* refused: negative or non-finite */
    {
        hf_diag d;
        f = NULL;
        sc.desc.clump_size = -1.0f;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_PARAMETER);
        CHECK(strstr(d.message, "clump_size") != NULL);
        CHECK(f == NULL);
    }
}

/* Per-strand widths: hf_ribbon_strands.width multiplies each strand's
   ribbon (and GPU half widths); NaN or negative collapse it; a fur's
   width_variation spreads its strands' widths over [1 - v, 1 + v]. */
static void test_ribbon_strand_widths(void)
{
    float pts[3 * 4 * 3], w[3] = {1.0f, 2.5f, NAN}, v[3 * 4 * 2 * 3], g[3 * 4 * 4];
    hf_ribbon_strands st;
    hf_ribbon_params rp;
    hf_ribbon_output out;
    int s, j;
    for (s = 0; s < 3; ++s)
        for (j = 0; j < 4; ++j) {
            pts[3 * (4 * s + j)] = 0.1f * (float)s;
            pts[3 * (4 * s + j) + 1] = 0.05f * (float)j;
            pts[3 * (4 * s + j) + 2] = 0.0f;
        }
    memset(&st, 0, sizeof st);
    st.points = pts;
    st.width = w;
    memset(&rp, 0, sizeof rp);
    rp.points_per_strand = 4;
    rp.eye[2] = 5.0f;
    rp.root_width = 0.002f;
    rp.tip_width = 0.002f;
    memset(&out, 0, sizeof out);
    out.position.data = v;
    CHECK_EQ_INT(hf_ribbons(&st, 0, 3, &rp, &out), HF_OK);
    for (s = 0; s < 3; ++s) {
        const float *a = v + 3 * (8 * s), *b = a + 3;
        double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                        (a[2] - b[2]) * (a[2] - b[2]));
        double want = s == 0 ? 0.002 : s == 1 ? 0.005 : 0.0;
        CHECK(fabs(d - want) < 1e-6);
    }
    CHECK_EQ_INT(hf_ribbon_points(&st, 0, 3, &rp, g), HF_OK);
    CHECK(fabs(g[3] - 0.001f) < 1e-7 && fabs(g[16 + 3] - 0.0025f) < 1e-7 &&
          g[32 + 3] == 0.0f);
    w[2] = -1.0f;
    CHECK_EQ_INT(hf_ribbon_points(&st, 0, 3, &rp, g), HF_OK);
    CHECK(g[32 + 3] == 0.0f);
    /* a fur: the widths of its strands vary */
    {
        t_fur_scene sc;
        hf_fur *f = NULL;
        hf_fur_info info;
        float lo = 1e9f, hi = 0.0f;
        float *buf;
        int i;
        t_fur_scene_init(&sc, 1.0f);
        sc.desc.width_variation = 0.4f;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
        if (!f) return;
        hf_fur_get_info(f, &info);
        buf = (float *)malloc(sizeof(float) * 4u * (size_t)info.strand_count * 8u);
        memset(&rp, 0, sizeof rp);
        rp.root_width = rp.tip_width = 0.01f;
        CHECK_EQ_INT(hf_fur_points(f, 0, info.strand_count, &rp, buf), HF_OK);
        for (i = 0; i < info.strand_count; ++i) {
            float h = buf[(size_t)i * 8u * 4u + 3] / 0.005f;
            if (h < lo) lo = h;
            if (h > hi) hi = h;
        }
        CHECK(lo >= 0.6f - 1e-5f && hi <= 1.4f + 1e-5f && hi - lo > 0.5f);
        free(buf);
        hf_fur_destroy(f);
    }
}

/* A groom on a skinned scalp: the unit sphere of the fur tests. Moving
   the scalp rigidly moves the groom exactly as hf_fur_set_transform does;
   growing the scalp by 10 % carries the roots with the surface. */
static void test_fur_groom_scalp(void)
{
    static float pts[TG_S * TG_P * 3];
    static int npts[TG_S];
    static float moved[(FR + 1) * (FS + 1) * 3];
    t_fur_scene sc;
    hf_groom_desc gd;
    hf_rope_params rp;
    hf_mesh skinned;
    hf_fur *f = NULL;
    hf_fur_info info;
    float m[12];
    double worst = 0.0;
    int i, k, g;
    {
        double c = cos(0.5), sn = sin(0.5); /* about y, then a move */
        float mm[12] = {0};
        mm[0] = (float)c; mm[2] = (float)sn; mm[5] = 1.0f;
        mm[8] = (float)-sn; mm[10] = (float)c;
        mm[3] = 0.2f; mm[7] = 0.1f; mm[11] = -0.3f;
        memcpy(m, mm, sizeof m);
    }
    t_fur_scene_init(&sc, 1.0f);
    t_groom_desc(&gd, pts, npts);
    gd.scalp = &sc.desc.mesh;
    hf_rope_params_init(&rp);
    rp.explicit_zero = HF_ROPE_ZERO_BLEND_TIME;
    rp.mode_blend_time = 0.0f;
    gd.rope_params = &rp;
    CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(hf_fur_set_mode(f, 0, info.guide_count, HF_ROPE_ANIMATED), HF_OK);
    /* the scalp moved rigidly */
    for (i = 0; i < (FR + 1) * (FS + 1); ++i)
        for (k = 0; k < 3; ++k)
            moved[3 * i + k] = m[4 * k] * sc.pos[3 * i] + m[4 * k + 1] * sc.pos[3 * i + 1] +
                               m[4 * k + 2] * sc.pos[3 * i + 2] + m[4 * k + 3];
    skinned = sc.desc.mesh;
    skinned.positions = moved;
    skinned.normals = NULL;
    CHECK_EQ_INT(hf_fur_set_roots(f, &skinned, 0, info.guide_count), HF_OK);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0), HF_OK);
    CHECK_EQ_INT(hf_fur_interpolate(f, 0, TG_S), HF_OK);
    worst = t_groom_worst(&info, pts, m);
    CHECK(worst < 5e-5);
    /* the scalp 10 % larger: every guide root 10 % further out */
    for (i = 0; i < 3 * (FR + 1) * (FS + 1); ++i) moved[i] = 1.1f * sc.pos[i];
    CHECK_EQ_INT(hf_fur_set_roots(f, &skinned, 0, info.guide_count), HF_OK);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0), HF_OK);
    worst = 0.0;
    for (g = 0; g < info.guide_count; ++g) {
        const float *q = info.guide_points + (size_t)g * TG_P * 3;
        double r = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2]);
        if (fabs(r - 1.1) > worst) worst = fabs(r - 1.1);
    }
    CHECK(worst < 0.01); /* roots sit on the flat triangles, not the sphere */
    /* a scalp moved beyond HF_ROPE_MAX_COORD: refused, and nothing set
       (the strands interpolated again are the same bytes) */
    {
        const size_t n = (size_t)TG_S * TG_P * 3u;
        float *before = (float *)malloc(sizeof(float) * n);
        if (!before) { CHECK(0); hf_fur_destroy(f); return; }
        CHECK_EQ_INT(hf_fur_interpolate(f, 0, TG_S), HF_OK);
        memcpy(before, info.strand_points, sizeof(float) * n);
        for (i = 0; i < (FR + 1) * (FS + 1); ++i) moved[3 * i] = sc.pos[3 * i] + 2e6f;
        CHECK_EQ_INT(hf_fur_set_roots(f, &skinned, 0, info.guide_count),
                     HF_ERROR_BAD_PARAMETER);
        CHECK_EQ_INT(hf_fur_interpolate(f, 0, TG_S), HF_OK);
        CHECK(memcmp(before, info.strand_points, sizeof(float) * n) == 0);
        free(before);
    }
    /* a wrong scalp: counts checked */
    skinned.vertex_count -= 1;
    CHECK_EQ_INT(hf_fur_set_roots(f, &skinned, 0, 1), HF_ERROR_BAD_COUNT);
    hf_fur_destroy(f);
}

/* The per-strand control maps: black turns clump, colour and width
   variation off, white leaves them as the scalars say. */
static void test_fur_control_maps(void)
{
    t_fur_scene sc;
    hf_fur *a = NULL, *b = NULL;
    hf_fur_info ia, ib;
    unsigned char black = 0, white = 255;
    hf_map mb, mw;
    size_t n;
    double worst = 0.0;
    int i;
    memset(&mb, 0, sizeof mb);
    mb.data = &black;
    mb.width = mb.height = mb.channels = 1;
    mw = mb;
    mw.data = &white;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.clump = 0.9f;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK); /* no map */
    sc.desc.clump_map = &mw;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &b, NULL), HF_OK); /* white map */
    if (!a || !b) return;
    hf_fur_get_info(a, &ia);
    hf_fur_get_info(b, &ib);
    n = (size_t)ia.strand_count * (size_t)ia.points_per_strand * 3u;
    for (i = 0; i < (int)n; ++i)
        if (fabs(ia.strand_points[i] - ib.strand_points[i]) > worst)
            worst = fabs(ia.strand_points[i] - ib.strand_points[i]);
    CHECK(worst < 1e-5);
    hf_fur_destroy(a);
    hf_fur_destroy(b);
    /* black: as clump 0 */
    sc.desc.clump = 0.0f;
    sc.desc.clump_map = NULL;
    a = b = NULL;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK);
    sc.desc.clump = 0.9f;
    sc.desc.clump_map = &mb;
    sc.desc.color_variation = 0.5f;
    sc.desc.color_variation_map = &mb;
    sc.desc.width_variation = 0.5f;
    sc.desc.width_variation_map = &mb;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &b, NULL), HF_OK);
    if (!a || !b) return;
    hf_fur_get_info(a, &ia);
    hf_fur_get_info(b, &ib);
    CHECK(memcmp(ia.strand_points, ib.strand_points, sizeof(float) * n) == 0);
    for (i = 0; i < 4 * ib.strand_count; ++i) CHECK(ib.strand_colors[i] == 1.0f);
    {
        hf_ribbon_params rp;
        float *buf = (float *)malloc(sizeof(float) * 4u * (size_t)ib.strand_count * 8u);
        memset(&rp, 0, sizeof rp);
        rp.root_width = rp.tip_width = 0.01f;
        CHECK_EQ_INT(hf_fur_points(b, 0, ib.strand_count, &rp, buf), HF_OK);
        for (i = 0; i < ib.strand_count; ++i)
            CHECK(buf[(size_t)i * 32u + 3] == 0.005f);
        free(buf);
    }
    hf_fur_destroy(a);
    hf_fur_destroy(b);
    /* clump_size_map: white as no map, black as no clumping at all */
    memset(&sc.desc, 0, sizeof sc.desc);
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.clump = 0.9f;
    sc.desc.clump_size = 0.3f;
    {
        hf_fur *c = NULL;
        hf_fur_info ic;
        a = b = NULL;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK); /* no map */
        sc.desc.clump_size_map = &mw;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &b, NULL), HF_OK);
        sc.desc.clump_size_map = &mb;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &c, NULL), HF_OK);
        if (!a || !b || !c) return;
        hf_fur_get_info(a, &ia);
        hf_fur_get_info(b, &ib);
        hf_fur_get_info(c, &ic);
        CHECK(memcmp(ia.strand_points, ib.strand_points, sizeof(float) * n) == 0);
        CHECK(memcmp(ia.strand_points, ic.strand_points, sizeof(float) * n) != 0);
        hf_fur_destroy(c);
        sc.desc.clump = 0.0f;
        sc.desc.clump_size_map = NULL;
        c = NULL;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &c, NULL), HF_OK);
        if (c) {
            hf_fur_get_info(c, &ic);
            hf_fur_interpolate(c, 0, ic.strand_count);
            /* black: each strand clumps to itself, the unclumped strands */
            hf_fur_destroy(a);
            a = NULL;
            sc.desc.clump = 0.9f;
            sc.desc.clump_size_map = &mb;
            CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK);
            if (a) {
                hf_fur_get_info(a, &ia);
                hf_fur_interpolate(a, 0, ia.strand_count);
                CHECK(memcmp(ia.strand_points, ic.strand_points,
                             sizeof(float) * n) == 0);
            }
            hf_fur_destroy(c);
        }
    }
    hf_fur_destroy(a);
    hf_fur_destroy(b);
}

/* Diagnostics read back word for word: every number in them goes through
   printf (%d, %lu, %g), so a C runtime that formats one wrongly (Windows',
   under make cross-test) fails here. */
static void test_diagnostics_read_back(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_diag d;
    unsigned char px[64] = {0};
    hf_map m;
    static const float nan_curve[6] = {0, 1, 0, 0, NAN, 0};
    int two = 2;
    memset(&m, 0, sizeof m);
    m.data = px;
    m.width = 10;
    m.height = 2;
    m.channels = 3;
    m.row_stride = 20;
    CHECK_EQ_INT(hf_map_validate(&m, &d), HF_ERROR_BAD_STRIDE);
    CHECK_EQ_STR(d.message, "map.row_stride 20 is below one packed row (30 bytes)");
    CHECK_EQ_STR(d.field, "row_stride");
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.points_per_strand = 300;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_COUNT);
    CHECK_EQ_STR(d.message, "points_per_strand 300 is outside 2..256");
    sc.desc.points_per_strand = 8;
    sc.desc.strands_per_area = -1.5f;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.message, "strands_per_area -1.5 is negative or non-finite");
    sc.desc.strands_per_area = 0.0f;
    sc.desc.color_variation = 1.5f;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.message, "color_variation 1.5 is negative, non-finite or too "
                            "large (at most 1)");
    sc.desc.color_variation = 0.0f;
    sc.desc.guide_curves = nan_curve;
    sc.desc.guide_curve_points = &two;
    sc.desc.guide_curve_count = 1;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_NON_FINITE);
    CHECK_EQ_STR(d.message, "curve 0, point 1 is non-finite or too large");
    CHECK(d.index == 1);
    CHECK(f == NULL);
}

static void test_fur_no_allocation_per_frame(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    t_counter cnt;
    hf_allocator a = t_counting(&cnt);
    hf_result worst = HF_OK;
    long after_create;
    void *vbuf = malloc(24u * 2u * 8u * 500u);
    int k;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.allocator = &a;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    after_create = cnt.allocs - cnt.frees;
    CHECK(cnt.allocs > 0);
    for (k = 0; k < 10; ++k) {
        hf_fur_set_lod(f, k % 3 == 0 ? 0.2f : 1.0f);
        t_fur_frame(f, &sc, 0.02f * (float)k, 1, vbuf, &worst);
    }
    CHECK_EQ_INT(worst, HF_OK);
    CHECK_EQ_INT(cnt.allocs - cnt.frees, after_create);
    CHECK_EQ_INT(cnt.allocs, after_create + 0 + (cnt.frees)); /* no new blocks */
    hf_fur_destroy(f);
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    free(vbuf);
}

/* An allocator whose blocks start 16 bytes past a 64-byte boundary (as
   malloc's may): the fur still puts its guide and strand points on 64-byte
   boundaries, and frees what it was given (ASan checks the frees). */
static void *t_skew_alloc(size_t size, void *user)
{
    unsigned char *raw = (unsigned char *)malloc(size + 144), *p;
    (void)user;
    if (!raw) return NULL;
    p = (unsigned char *)(((uintptr_t)raw + 63) & ~(uintptr_t)63) + 80;
    memcpy(p - sizeof raw, &raw, sizeof raw);
    return p;
}
static void t_skew_free(void *p, void *user)
{
    unsigned char *raw;
    (void)user;
    if (!p) return;
    memcpy(&raw, (unsigned char *)p - sizeof raw, sizeof raw);
    free(raw);
}

static void test_fur_points_aligned(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_groom_desc gd;
    float pts[TG_S * TG_P * 3];
    int npts[TG_S];
    hf_allocator a;
    void *probe;
    a.alloc = t_skew_alloc;
    a.realloc = NULL;
    a.free = t_skew_free;
    a.user = NULL;
    probe = t_skew_alloc(16, NULL);
    CHECK(((uintptr_t)probe & 63u) == 16u);
    t_skew_free(probe, NULL);
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.allocator = &a;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (f) {
        CHECK_EQ_INT(hf_fur_get_info(f, &info), HF_OK);
        CHECK(((uintptr_t)info.guide_points & 63u) == 0);
        CHECK(((uintptr_t)info.strand_points & 63u) == 0);
        CHECK_EQ_INT(hf_fur_interpolate(f, 0, info.strand_count), HF_OK);
        hf_fur_destroy(f);
    }
    t_groom_desc(&gd, pts, npts);
    gd.allocator = &a;
    f = NULL;
    CHECK_EQ_INT(hf_fur_create_groom(&gd, &f, NULL), HF_OK);
    if (f) {
        CHECK_EQ_INT(hf_fur_get_info(f, &info), HF_OK);
        CHECK(((uintptr_t)info.guide_points & 63u) == 0);
        CHECK(((uintptr_t)info.strand_points & 63u) == 0);
        hf_fur_destroy(f);
    }
}

/* Every styling option of hf_fur_desc at once */
static void t_fur_style_all(hf_fur_desc *d)
{
    d->curl_radius = 0.02f;
    d->curl_turns = 2.0f;
    d->wave_amplitude = 0.01f;
    d->wave_count = 3.0f;
    d->frizz = 0.2f;
    d->clump = 0.5f;
    d->clump_size = 0.2f;
    d->color_variation = 0.3f;
    d->width_variation = 0.4f;
}

static void t_fur_ranges(int styled)
{
    t_fur_scene sc;
    hf_fur *f[3] = {NULL, NULL, NULL};
    int splits[3] = {1, 2, 7}, k, i;
    size_t bytes = 24u * 2u * 8u * 500u;
    unsigned char *v[3];
    hf_result worst = HF_OK;
    hf_fur_info info[3];
    t_fur_scene_init(&sc, 1.0f);
    if (styled == 1) t_fur_style_all(&sc.desc);
    if (styled == 2) sc.desc.grid_resolution = 12; /* hair-hair on */
    for (k = 0; k < 3; ++k) {
        v[k] = (unsigned char *)calloc(1, bytes);
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f[k], NULL), HF_OK);
        if (!f[k]) return;
    }
    for (i = 0; i < 8; ++i)
        for (k = 0; k < 3; ++k) {
            if (i == 4) hf_fur_set_lod(f[k], 0.3f); /* LOD guides interpolated */
            t_fur_frame(f[k], &sc, 0.05f * (float)i, splits[k], v[k], &worst);
        }
    CHECK_EQ_INT(worst, HF_OK);
    for (k = 0; k < 3; ++k) hf_fur_get_info(f[k], &info[k]);
    for (k = 1; k < 3; ++k) {
        CHECK(memcmp(v[0], v[k], bytes) == 0);
        CHECK(memcmp(info[0].guide_points, info[k].guide_points,
                     sizeof(float) * 3u * 8u * (size_t)info[0].guide_count) == 0);
    }
    /* and the motion did something */
    {
        hf_fur *g = NULL;
        hf_fur_info gi;
        hf_fur_create(&sc.desc, &g, NULL);
        hf_fur_get_info(g, &gi);
        CHECK(memcmp(gi.strand_points, info[0].strand_points,
                     sizeof(float) * 3u * 8u * 150u) != 0);
        hf_fur_destroy(g);
    }
    for (k = 0; k < 3; ++k) {
        hf_fur_destroy(f[k]);
        free(v[k]);
    }
}

/* Range splits give the same bytes, plain, with every styling on, and
   with hair-hair interaction (the grid's layers split as well). */
static void test_fur_ranges_byte_identical(void)
{
    t_fur_ranges(0);
    t_fur_ranges(1);
    t_fur_ranges(2);
}

/* The one-pass kernels against interpolation then points, on guides with
   a point that is not finite (the strands on it written collapsed, which
   hf_fur cannot reach: its guides are finite), with and without
   clumping, streaming or not, into outputs aligned to 64 and to 16
   bytes. */
static void test_interp_points_kernels(void)
{
#if HF__AVX2
    /* P: whole groups of eight and sixteen, and the last points of a
       strand written from a group that ends at its tip */
    static const int Ps[] = {8, 10, 12, 14, 16, 20, 24, 28, 32, 40};
    enum { G = 12, S = 40, PM = 40 };
    static float guides[G * PM * 3], mid[S * PM * 3];
    static float ref[S * PM * 4 + 32], got[S * PM * 4 + 32];
    float width[S], ctab[3 * HF_MAX_POINTS];
    hf_strand_binding b[S];
    hf_ribbon_strands st;
    hf_ribbon_params in, prm;
    hf__points_kit kit;
    hf__irun run;
    hf_rng r;
    int P, pi, i, clump, nt, off, wide;
    hf_rng_seed(&r, 7, 1);
    memset(&st, 0, sizeof st);
    st.width = width;
    for (i = 0; i < S; ++i) width[i] = 0.5f + hf_rng_float(&r);
    for (pi = 0; pi < (int)(sizeof Ps / sizeof Ps[0]); ++pi)
        for (wide = 0; wide < 2; ++wide) {
            P = Ps[pi];
            if (wide && (P % 4 || P < 16 ||
                         hf_simd_resolve(HF_SIMD_AVX512) < HF_SIMD_AVX512))
                continue;
            if (!wide && hf_simd_resolve(HF_SIMD_AVX2) < HF_SIMD_AVX2) continue;
            for (i = 0; i < G * P * 3; ++i) guides[i] = hf_rng_float(&r) - 0.5f;
            guides[3 * P * 3 + 3 * 5 + 1] = INFINITY; /* guide 3, point 5 */
            guides[7 * P * 3 + 3 * (P - 1)] = NAN;    /* guide 7, the tip */
            t_random_bindings(b, S, G, &r, 0.8f, 0.4f);
            memset(&in, 0, sizeof in);
            in.points_per_strand = P;
            in.root_width = 0.01f;
            in.tip_width = 0.002f;
            for (clump = 0; clump < 2; ++clump)
                for (nt = 0; nt < 2; ++nt)
                    for (off = 0; off <= 4; off += 4) {
                        int collapsed = 0;
                        in.nontemporal = nt;
                        hf__ribbon_params_resolve(&in, &prm);
                        hf__points_kit_init(&kit, &prm, S);
                        hf__irun_init(&run, guides, b, P, clump ? 0.4f : 0.0f,
                                      ctab, mid, 0, 0);
                        hf__interpolate_run(guides, b, 0, S, P,
                                            clump ? 0.4f : 0.0f, mid, 0,
                                            HF_SIMD_SCALAR, 0);
                        memset(ref, 0x11, sizeof ref);
                        memset(got, 0x22, sizeof got);
                        hf__points_run(&kit, &st, mid, 0, 0, S, 0, ref + off);
                        if (wide) {
#if HF__AVX512
                            hf__interp_points_v16(&run, &kit, &st, 0, S, 0,
                                                  got + off);
#endif
                        } else {
                            hf__interp_points_v8(&run, &kit, &st, 0, S, 0,
                                                 got + off);
                        }
                        if (nt) _mm_sfence();
                        CHECK(memcmp(ref + off, got + off,
                                     sizeof(float) * 4u * (size_t)(S * P)) == 0);
                        { /* nothing written before or past the strands */
                            const float g = got[sizeof got / sizeof *got - 1];
                            const int e = off + 4 * S * P;
                            for (i = 0; i < off; ++i) CHECK(got[i] == g);
                            for (i = e; i < e + 16; ++i) CHECK(got[i] == g);
                        }
                        for (i = 0; i < S; ++i)
                            collapsed += ref[off + 4 * i * P + 3] == 0.0f;
                        CHECK(collapsed > 0 && collapsed < S);
                    }
        }
#endif
}

/* The GPU path in one pass: on fur of 8, 16 and 6 points (the first two
   through registers, 6 through the buffer), with clumping to the main
   guide (in the kernel), to leaders and with every styling option (after
   it), thinner at a lower LOD; after the ropes moved, so the strand points
   the call leaves alone differ from what it writes. Bad input: an error
   and nothing written. */
static void test_fur_interpolate_points(void)
{
    static const int pts[3] = {8, 16, 6};
    int c;
    for (c = 0; c < 6; ++c) {
        t_fur_scene sc;
        hf_fur *f = NULL;
        hf_fur_info info;
        hf_result worst = HF_OK;
        hf_ribbon_params view;
        void *vbuf = calloc(24u * 2u * 16u * 500u, 1);
        t_fur_scene_init(&sc, 1.0f);
        sc.desc.points_per_strand = pts[c % 3];
        if (c == 3) sc.desc.clump = 0.6f;
        if (c == 4) {
            sc.desc.clump = 0.5f;
            sc.desc.clump_size = 0.2f;
        }
        if (c == 5) t_fur_style_all(&sc.desc);
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
        if (!f || !vbuf) return;
        if (c == 2) hf_fur_set_lod(f, 0.6f);
        t_fur_frame(f, &sc, 0.0f, 1, vbuf, &worst);
        t_fur_frame(f, &sc, 0.1f, 1, vbuf, &worst);
        CHECK_EQ_INT(worst, HF_OK);
        /* the ropes move on; the fur's strand points stay as they were */
        hf_fur_get_info(f, &info);
        CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f,
                                     NULL, 0), HF_OK);
        CHECK_EQ_INT(hf_fur_interpolate_guides(f, 0, info.lod_guide_count),
                     HF_OK);
        memset(&view, 0, sizeof view);
        view.root_width = 0.01f;
        view.tip_width = 0.002f;
        view.taper_power = 1.5f;
        CHECK_EQ_INT(t_ipoints_same(f, &view), 0);
        if (c == 0) { /* bad input */
            float *o = (float *)malloc(sizeof(float) * 4u * 8u * 500u);
            float *z = (float *)malloc(sizeof(float) * 4u * 8u * 500u);
            hf_ribbon_params bad = view;
            memset(o, 0x5a, sizeof(float) * 4u * 8u * 500u);
            memcpy(z, o, sizeof(float) * 4u * 8u * 500u);
            CHECK_EQ_INT(hf_fur_interpolate_points(NULL, 0, 1, &view, o),
                         HF_ERROR_NULL_POINTER);
            CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, 1, NULL, o),
                         HF_ERROR_NULL_POINTER);
            CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, 1, &view, NULL),
                         HF_ERROR_NULL_POINTER);
            CHECK_EQ_INT(hf_fur_interpolate_points(f, -1, 1, &view, o),
                         HF_ERROR_BAD_RANGE);
            CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, info.strand_count + 1,
                                                   &view, o),
                         HF_ERROR_BAD_RANGE);
            bad.out_first = 5;
            CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, 10, &bad, o),
                         HF_ERROR_BAD_RANGE);
            bad = view;
            bad.root_width = -1.0f;
            CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, 10, &bad, o),
                         HF_ERROR_BAD_PARAMETER);
            bad = view;
            bad.tip_width = (float)NAN;
            CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, 10, &bad, o),
                         HF_ERROR_NON_FINITE);
            bad = view;
            bad.simd = 9;
            CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, 10, &bad, o),
                         HF_ERROR_BAD_PARAMETER);
            CHECK(memcmp(o, z, sizeof(float) * 4u * 8u * 500u) == 0);
            CHECK_EQ_INT(hf_fur_interpolate_points(f, 3, 0, &view, o), HF_OK);
            CHECK(memcmp(o, z, sizeof(float) * 4u * 8u * 500u) == 0);
            free(o);
            free(z);
        }
        hf_fur_destroy(f);
        free(vbuf);
    }
}

static void test_fur_lod_prefix_and_width(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_result worst = HF_OK;
    float *v = (float *)calloc(6u * 2u * 8u * 500u, sizeof(float));
    float w;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    CHECK_EQ_INT(hf_fur_set_lod(f, 0.25f), HF_OK);
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(info.drawn_strand_count, 125);
    CHECK(info.width_scale == 2.0f);
    CHECK_EQ_INT(info.lod_guides_simulated, 0);
    t_fur_frame(f, &sc, 0.0f, 1, v, &worst);
    CHECK_EQ_INT(worst, HF_OK);
    /* root width = 0.01 * sqrt(500 / 125) */
    w = sqrtf((v[6] - v[0]) * (v[6] - v[0]) + (v[7] - v[1]) * (v[7] - v[1]) +
              (v[8] - v[2]) * (v[8] - v[2]));
    CHECK_NEAR(w, 0.02f, 1e-6);
    CHECK_EQ_INT(hf_fur_set_lod(f, 1.0f), HF_OK);
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(info.drawn_strand_count, 500);
    CHECK(info.width_scale == 1.0f);
    CHECK_EQ_INT(info.lod_guides_simulated, 1);
    CHECK_EQ_INT(hf_fur_set_lod(f, (float)NAN), HF_OK);
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(info.drawn_strand_count, 0);
    hf_fur_destroy(f);
    free(v);
}

static void test_fur_lod_guides_wake_without_jump(void)
{
    /* LOD guides asleep (interpolated), then woken: the first simulated
       frame moves no guide point by more than a step's motion */
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_result worst = HF_OK;
    float *v = (float *)calloc(6u * 2u * 8u * 500u, sizeof(float));
    float *before;
    double maxd = 0.0;
    int i, n;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    /* no collider: interpolated guides cut the chord of a curved collider
       and would be pushed out on waking; that is interpolation's error,
       not a jump of the switch */
    hf_fur_set_lod(f, 0.1f);
    for (i = 0; i < 600; ++i) t_fur_frame(f, &sc, -1e-9f, 1, v, &worst);
    hf_fur_get_info(f, &info);
    n = info.guide_count * 8 * 3;
    before = (float *)malloc(sizeof(float) * (size_t)n);
    memcpy(before, info.guide_points, sizeof(float) * (size_t)n);
    hf_fur_set_lod(f, 1.0f);
    t_fur_frame(f, &sc, -1e-9f, 1, v, &worst);
    CHECK_EQ_INT(worst, HF_OK);
    for (i = 0; i < n; ++i) {
        double d = fabs((double)info.guide_points[i] - before[i]);
        maxd = d > maxd ? d : maxd;
    }
    /* settled after 10 s: one step moves points by millimetres at most; a
       jump to the rest pose would move tips by tenths of the length */
    CHECK(maxd < 0.003);
    free(before);
    free(v);
    hf_fur_destroy(f);
}

static void test_fur_bad_desc_and_out_of_memory(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL, *sentinel = (hf_fur *)&sc;
    hf_diag d;
    hf_fur_desc b;
    t_counter cnt;
    hf_allocator a = t_counting(&cnt);
    long k, total;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(NULL, &f, &d), HF_ERROR_NULL_POINTER);
    b = sc.desc; b.mesh.indices = NULL;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &d), HF_ERROR_NULL_POINTER);
    b = sc.desc; b.points_per_strand = 1;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &d), HF_ERROR_BAD_COUNT);
    b = sc.desc; b.clump = -0.5f;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.field, "clump");
    b = sc.desc; b.max_length = (float)NAN;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.field, "max_length");
    /* each field named alone */
    b = sc.desc; b.lod_simulate_threshold = 2.0f;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.field, "lod_simulate_threshold");
    b = sc.desc; b.tess_factor = -5.0f;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.field, "tess_factor");
    CHECK(strstr(d.message, "-5") != NULL);
    b = sc.desc; b.simd = 9;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.field, "simd");
    CHECK(strstr(d.message, "nontemporal") == NULL);
    b = sc.desc; b.nontemporal = 3;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.field, "nontemporal");
    b = sc.desc; b.tess_factor = 1e30f; /* billions of triangles */
    f = sentinel;
    CHECK(hf_fur_create(&b, &f, &d) < 0);
    CHECK(f == sentinel);
    CHECK(strstr(d.message, "tessellation") != NULL);
    /* every allocation failing in turn: OOM, nothing leaked */
    b = sc.desc;
    b.allocator = &a;
    CHECK_EQ_INT(hf_fur_create(&b, &f, NULL), HF_OK);
    hf_fur_destroy(f);
    total = cnt.allocs;
    for (k = 0; k < total; ++k) {
        cnt.allocs = cnt.frees = 0;
        cnt.fail_after = k;
        f = sentinel;
        CHECK_EQ_INT(hf_fur_create(&b, &f, NULL), HF_ERROR_OUT_OF_MEMORY);
        CHECK(f == sentinel);
        CHECK_EQ_INT(cnt.allocs, cnt.frees);
    }
}

/* Squared distance of two points, in double. */
static double t_d2(const float *a, const float *b)
{
    const double x = (double)a[0] - b[0], y = (double)a[1] - b[1],
                 z = (double)a[2] - b[2];
    return x * x + y * y + z * z;
}

/* keep_length: after the roots turn and the guides swing apart (clumping
   strong, so the plain blend changes lengths), every drawn strand keeps
   the segment lengths it had at creation; without it they change. The
   same bytes split into ranges, and from the GPU points path. */
static double t_keep_length_worst(int keep, int check_paths)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    float *rest, *again, *pts4;
    double worst = 0.0;
    int s, j, fr, P, S;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.clump = 0.8f;
    sc.desc.keep_length = keep;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return -1.0;
    hf_fur_get_info(f, &info);
    P = info.points_per_strand;
    S = info.strand_count;
    rest = (float *)malloc(sizeof(float) * 3u * (size_t)(S * P));
    again = (float *)malloc(sizeof(float) * 3u * (size_t)(S * P));
    pts4 = (float *)malloc(sizeof(float) * 4u * (size_t)(S * P));
    if (!rest || !again || !pts4) { CHECK(0); return -1.0; }
    memcpy(rest, info.strand_points, sizeof(float) * 3u * (size_t)(S * P));
    for (fr = 0; fr < 40; ++fr) { /* turn about z and let it swing */
        const float a = 0.04f * (float)fr, c = cosf(a), sn = sinf(a);
        const float m[12] = {c, -sn, 0, 0, sn, c, 0, 0, 0, 0, 1, 0};
        CHECK_EQ_INT(hf_fur_set_transform(f, m, 0, info.guide_count), HF_OK);
        CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f,
                                     NULL, 0), HF_OK);
    }
    CHECK_EQ_INT(hf_fur_interpolate_guides(f, 0, info.lod_guide_count), HF_OK);
    CHECK_EQ_INT(hf_fur_interpolate(f, 0, S), HF_OK);
    hf_fur_get_info(f, &info);
    for (s = 0; s < S; ++s)
        for (j = 1; j < P; ++j) {
            const float *a = rest + 3 * ((size_t)s * P + j);
            const float *b = info.strand_points + 3 * ((size_t)s * P + j);
            double l0 = sqrt(t_d2(a, a - 3)), l1 = sqrt(t_d2(b, b - 3));
            double e = fabs(l1 - l0) / (l0 > 1e-9 ? l0 : 1e-9);
            if (e > worst) worst = e;
        }
    if (check_paths) {
        hf_ribbon_params view;
        memcpy(again, info.strand_points, sizeof(float) * 3u * (size_t)(S * P));
        /* split into ranges: the same bytes */
        CHECK_EQ_INT(hf_fur_interpolate(f, 0, 7), HF_OK);
        CHECK_EQ_INT(hf_fur_interpolate(f, 7, S - 7), HF_OK);
        CHECK(memcmp(again, info.strand_points,
                     sizeof(float) * 3u * (size_t)(S * P)) == 0);
        /* the GPU points: the same positions */
        memset(&view, 0, sizeof view);
        CHECK_EQ_INT(hf_fur_interpolate_points(f, 0, S, &view, pts4), HF_OK);
        for (s = 0; s < S * P; ++s)
            if (memcmp(pts4 + 4 * (size_t)s, again + 3 * (size_t)s,
                       3 * sizeof(float)) != 0) {
                CHECK(0);
                break;
            }
    }
    free(rest);
    free(again);
    free(pts4);
    hf_fur_destroy(f);
    return worst;
}

static void test_fur_keep_length(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_diag d;
    const double kept = t_keep_length_worst(1, 1);
    const double plain = t_keep_length_worst(0, 0);
    CHECK(kept >= 0.0 && kept < 2e-5);
    CHECK(plain > 1e-2);
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.keep_length = 2;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_STR(d.field, "keep_length");
    CHECK(f == NULL);
}

static void test_fur_same_seed_same_bytes(void)
{
    t_fur_scene sc;
    hf_fur *a = NULL, *b = NULL;
    hf_fur_info ia, ib;
    t_fur_scene_init(&sc, 1.0f);
    hf_fur_create(&sc.desc, &a, NULL);
    hf_fur_create(&sc.desc, &b, NULL);
    if (!a || !b) { CHECK(0); return; }
    hf_fur_get_info(a, &ia);
    hf_fur_get_info(b, &ib);
    CHECK(memcmp(ia.strands, ib.strands, sizeof(hf_strand) * 500u) == 0);
    CHECK(memcmp(ia.strand_points, ib.strand_points, sizeof(float) * 500u * 24u) == 0);
    hf_fur_destroy(b);
    sc.desc.seed = 6;
    hf_fur_create(&sc.desc, &b, NULL);
    hf_fur_get_info(b, &ib);
    CHECK(memcmp(ia.strands, ib.strands, sizeof(hf_strand) * 500u) != 0);
    hf_fur_destroy(a);
    hf_fur_destroy(b);
}

static void test_fur_errors_per_frame(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_mesh m;
    float bad[(FR + 1) * (FS + 1) * 3];
    t_fur_scene_init(&sc, 1.0f);
    hf_fur_create(&sc.desc, &f, NULL);
    if (!f) { CHECK(0); return; }
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 0.0f, NULL, 0),
                 HF_ERROR_BAD_TIME_STEP);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, (float)NAN, NULL, 0),
                 HF_ERROR_BAD_TIME_STEP);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count + 1, 0.01f, NULL, 0),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_fur_interpolate(f, -1, 3), HF_ERROR_BAD_RANGE);
    m = sc.desc.mesh;
    memcpy(bad, sc.pos, sizeof bad);
    bad[3 * 10 + 1] = (float)INFINITY;
    m.positions = bad;
    CHECK_EQ_INT(hf_fur_set_roots(f, &m, 0, info.guide_count), HF_ERROR_NON_FINITE);
    m.vertex_count -= 1;
    CHECK_EQ_INT(hf_fur_set_roots(f, &m, 0, info.guide_count), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_fur_ribbons(f, 0, 1, NULL, NULL), HF_ERROR_NULL_POINTER);
    hf_fur_destroy(f);
}

static void test_bad_fur(void)
{
    tb_quad q;
    hf_fur_desc d, b;
    hf_fur *f = NULL, *sentinel = (hf_fur *)&d;
    hf_fur_info info;
    hf_diag dg;
    t_counter cnt;
    hf_allocator a = t_counting(&cnt);
    hf_mesh m;
    hf_collider c;
    hf_ribbon_params view;
    hf_ribbon_output out;
    float st = -7.0f, nan_pos[12];
    tb_quad_init(&q);
    memset(&d, 0, sizeof d);
    d.mesh = q.mesh;
    d.points_per_strand = 4;
    d.max_length = 0.1f;
    d.total_strands = 50;
    d.tess_factor = 10.0f;
#define TB_CREATE(expr, code)                                                  \
    do {                                                                       \
        b = d;                                                                 \
        expr;                                                                  \
        f = sentinel;                                                          \
        CHECK_EQ_INT(hf_fur_create(&b, &f, &dg), (code));                      \
        CHECK(f == sentinel);                                                  \
        CHECK_EQ_INT(cnt.allocs, cnt.frees);                                   \
    } while (0)
    CHECK_EQ_INT(hf_fur_create(NULL, &f, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_create(&d, NULL, NULL), HF_ERROR_NULL_POINTER);
    TB_CREATE(b.mesh.positions = NULL, HF_ERROR_NULL_POINTER);
    TB_CREATE(b.mesh.vertex_count = -1, HF_ERROR_BAD_COUNT);
    TB_CREATE(q.pos[1] = TB_NAN, HF_ERROR_NON_FINITE);
    q.pos[1] = 0.0f;
    TB_CREATE(q.idx[2] = 77, HF_ERROR_INDEX_OUT_OF_RANGE);
    q.idx[2] = 2;
    TB_CREATE(b.points_per_strand = 1, HF_ERROR_BAD_COUNT);
    TB_CREATE(b.points_per_strand = HF_MAX_POINTS + 1, HF_ERROR_BAD_COUNT);
    TB_CREATE(b.max_length = TB_NAN, HF_ERROR_BAD_PARAMETER);
    TB_CREATE(b.max_length = -1.0f, HF_ERROR_BAD_PARAMETER);
    TB_CREATE(b.clump = 2.0f, HF_ERROR_BAD_PARAMETER);
    TB_CREATE(b.tess_factor = TB_NAN, HF_ERROR_BAD_PARAMETER);
    TB_CREATE(b.tess_factor = -1.0f, HF_ERROR_BAD_PARAMETER);
    TB_CREATE(b.total_strands = -1, HF_ERROR_BAD_COUNT);
    TB_CREATE((b.strands_per_area = TB_INF, b.total_strands = 0),
              HF_ERROR_BAD_PARAMETER);
    TB_CREATE((b.strands_per_area = TB_NAN, b.total_strands = 0),
              HF_ERROR_BAD_PARAMETER);
    TB_CREATE(b.sampler = 9, HF_ERROR_BAD_PARAMETER);
    TB_CREATE(b.lod_simulate_threshold = TB_NAN, HF_ERROR_BAD_PARAMETER);
    {
        hf_rope_params rp;
        hf_rope_params_init(&rp);
        rp.damping = TB_NAN;
        TB_CREATE(b.rope_params = &rp, HF_ERROR_NON_FINITE);
    }
    b = d; b.tess_factor = 1e30f; f = sentinel;
    CHECK(hf_fur_create(&b, &f, &dg) < 0 && f == sentinel);
    b = d; b.total_strands = 0x7fffffff; f = sentinel; b.allocator = &a;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &dg), HF_ERROR_OVERFLOW);
    CHECK(f == sentinel);
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    b = d; b.strands_per_area = 1e30f; b.total_strands = 0; f = sentinel;
    b.allocator = &a;
    CHECK_EQ_INT(hf_fur_create(&b, &f, &dg), HF_ERROR_OVERFLOW);
    CHECK(f == sentinel);
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    /* (out of memory at every allocation: test_fur_bad_desc_and_out_of_memory) */
    /* per-frame calls */
    CHECK_EQ_INT(hf_fur_create(&d, &f, NULL), HF_OK);
    if (!f) return;
    CHECK_EQ_INT(hf_fur_get_info(f, &info), HF_OK);
    CHECK_EQ_INT(hf_fur_get_info(NULL, &info), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_get_info(f, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_set_lod(NULL, 0.5f), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_set_lod(f, TB_INF), HF_OK);
    CHECK_EQ_INT(hf_fur_set_lod(f, -TB_INF), HF_OK);
    CHECK_EQ_INT(hf_fur_set_lod(f, 1.0f), HF_OK);
    m = q.mesh;
    CHECK_EQ_INT(hf_fur_set_roots(NULL, &m, 0, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_set_roots(f, NULL, 0, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_set_roots(f, &m, 0, info.guide_count + 1), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_fur_set_roots(f, &m, -1, 1), HF_ERROR_BAD_RANGE);
    m.position_stride = 4;
    CHECK_EQ_INT(hf_fur_set_roots(f, &m, 0, info.guide_count), HF_ERROR_BAD_STRIDE);
    m = q.mesh;
    memcpy(nan_pos, q.pos, sizeof nan_pos);
    nan_pos[7] = TB_NAN;
    m.positions = nan_pos;
    CHECK_EQ_INT(hf_fur_set_roots(f, &m, 0, info.guide_count), HF_ERROR_NON_FINITE);
    m = q.mesh;
    m.vertex_count = 3;
    CHECK_EQ_INT(hf_fur_set_roots(f, &m, 0, info.guide_count), HF_ERROR_BAD_COUNT);
    memset(&c, 0, sizeof c);
    c.radius = TB_NAN;
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 0.0f, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, -1.0f, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, TB_NAN, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, TB_INF, NULL, 0), HF_ERROR_BAD_TIME_STEP);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 0.01f, &c, 1), HF_ERROR_NON_FINITE);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 0.01f, NULL, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 0.01f, &c, -1), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_fur_simulate(f, 1, 0x7fffffff, 0.01f, NULL, 0), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_fur_simulate(NULL, 0, 1, 0.01f, NULL, 0), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1e30f, NULL, 0), HF_OK);
    CHECK_EQ_INT(hf_fur_interpolate_guides(f, 0, info.lod_guide_count + 1), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_fur_interpolate_guides(NULL, 0, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_interpolate(f, 0, info.strand_count + 1), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_fur_interpolate(f, -1, 1), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_fur_interpolate(NULL, 0, 1), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_interpolate(f, 0, info.strand_count), HF_OK);
    hf_fur_get_info(f, &info);
    CHECK(tb_finite(info.guide_points, (size_t)info.guide_count * 4u * 3u));
    CHECK(tb_finite(info.strand_points, (size_t)info.strand_count * 4u * 3u));
    memset(&view, 0, sizeof view);
    view.eye[2] = 3.0f;
    view.root_width = 0.01f;
    memset(&out, 0, sizeof out);
    CHECK_EQ_INT(hf_fur_ribbons(NULL, 0, 1, &view, &out), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_ribbons(f, 0, 1, NULL, &out), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_ribbons(f, 0, info.strand_count + 1, &view, &out), HF_ERROR_BAD_RANGE);
    view.eye[0] = TB_NAN;
    CHECK_EQ_INT(hf_fur_ribbons(f, 0, 1, &view, &out), HF_ERROR_NON_FINITE);
    view.eye[0] = 0.0f;
    CHECK_EQ_INT(hf_fur_points(f, 0, 1, &view, NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_points(NULL, 0, 1, &view, nan_pos), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_max_stretch(NULL, &st), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_max_stretch(f, NULL), HF_ERROR_NULL_POINTER);
    CHECK(st == -7.0f);
    CHECK_EQ_INT(hf_fur_max_stretch(f, &st), HF_OK);
    CHECK(t_is_finite(st) && st >= 0.0f);
    CHECK_EQ_INT(hf_fur_reset(NULL), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_reset(f), HF_OK);
    hf_fur_destroy(f);
    hf_fur_destroy(NULL);
#undef TB_CREATE
}

static void test_defaults_fur_strand_count_precedence(void)
{
    /* strands_per_area wins over total_strands; bad values are refused */
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_diag d;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.total_strands = 300;
    sc.desc.strands_per_area = 2000.0f; /* a 1 m sphere: ~25,000 strands */
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_OK);
    if (f) {
        hf_fur_get_info(f, &info);
        CHECK(info.strand_count > 15000);
        hf_fur_destroy(f);
    }
    sc.desc.strands_per_area = -5.0f;
    f = NULL;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_PARAMETER);
    CHECK(f == NULL);
    CHECK(strstr(d.message, "strands_per_area") != NULL);
    sc.desc.strands_per_area = (float)NAN;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_PARAMETER);
    sc.desc.strands_per_area = 0.0f;
    sc.desc.total_strands = -1;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, &d), HF_ERROR_BAD_COUNT);
    CHECK(f == NULL);
}

static void test_out_first_fur_chunks(void)
{
    /* the fur's strands drawn in 16-bit chunks: each chunk's vertices in a
       buffer of its own equal the slice of one whole buffer */
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_ribbon_params view;
    hf_ribbon_output o;
    float *whole, *chunk;
    int per, first;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.total_strands = 9000; /* more than one 16-bit chunk */
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    per = hf_ribbon_chunk_strands(info.points_per_strand, HF_TRIANGLES);
    CHECK(per > 0 && per < info.strand_count);
    whole = (float *)malloc(sizeof(float) * 3 * 2 * (size_t)info.points_per_strand *
                            (size_t)info.strand_count);
    chunk = (float *)malloc(sizeof(float) * 3 * 2 * (size_t)info.points_per_strand *
                            (size_t)per);
    memset(&view, 0, sizeof view);
    view.eye[2] = 5.0f;
    memset(&o, 0, sizeof o);
    o.position.data = whole;
    CHECK_EQ_INT(hf_fur_ribbons(f, 0, info.strand_count, &view, &o), HF_OK);
    o.position.data = chunk;
    for (first = 0; first < info.strand_count; first += per) {
        int n = info.strand_count - first < per ? info.strand_count - first : per;
        size_t floats = (size_t)n * (size_t)info.points_per_strand * 6;
        view.out_first = first;
        CHECK_EQ_INT(hf_fur_ribbons(f, first, n, &view, &o), HF_OK);
        CHECK(memcmp(chunk, whole + (size_t)first * (size_t)info.points_per_strand * 6,
                     floats * sizeof(float)) == 0);
    }
    free(whole);
    free(chunk);
    hf_fur_destroy(f);
}

/* hf_fur_info.roots_inside: every guide's root inside a collider larger
   than the body, none inside one within it; lengths kept. */
static void test_fur_roots_inside_count(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_collider c;
    float st = 1.0f;
    int frame;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    memset(&c, 0, sizeof c);
    c.type = HF_COLLIDER_SPHERE;
    c.radius = 0.5f; /* inside the coarse sphere's facets: no root in it */
    hf_fur_get_info(f, &info);
    for (frame = 0; frame < 3; ++frame)
        CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f,
                                     &c, 1), HF_OK);
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(info.roots_inside, 0);
    c.radius = 1.2f; /* 20 cm larger: every root inside */
    for (frame = 0; frame < 3; ++frame)
        CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f,
                                     &c, 1), HF_OK);
    hf_fur_get_info(f, &info);
    CHECK_EQ_INT(info.roots_inside, info.guide_count);
    CHECK_EQ_INT(hf_fur_max_stretch(f, &st), HF_OK);
    CHECK(st <= 1e-4f);
    hf_fur_destroy(f);
}

/* Rope parameters on a range: weightless guides stay at rest while the
   others sag; split calls give the bytes of one call; up to
   HF_FUR_ROPE_SETS different sets, equal ones shared. */
static void test_fur_rope_params_range(void)
{
    t_fur_scene sc;
    hf_fur *a = NULL, *b = NULL;
    hf_fur_info ia, ib;
    hf_rope_params p;
    float *rest;
    size_t n, per;
    int frame, G, half, g, k;
    double still = 0.0, sag = 0.0;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &a, NULL), HF_OK);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &b, NULL), HF_OK);
    if (!a || !b) return;
    hf_fur_get_info(a, &ia);
    hf_fur_get_info(b, &ib);
    G = ia.guide_count;
    half = G / 2;
    per = (size_t)ia.points_per_strand * 3u;
    n = (size_t)G * per;
    rest = (float *)malloc(sizeof(float) * n);
    memcpy(rest, ia.guide_points, sizeof(float) * n);
    memset(&p, 0, sizeof p);
    p.explicit_zero = HF_ROPE_ZERO_GRAVITY;
    CHECK_EQ_INT(hf_fur_set_rope_params_range(a, 0, half, &p), HF_OK);
    CHECK_EQ_INT(hf_fur_set_rope_params_range(b, 0, half, &p), HF_OK);
    for (frame = 0; frame < 20; ++frame) {
        CHECK_EQ_INT(hf_fur_simulate(a, 0, G, 1.0f / 60.0f, NULL, 0), HF_OK);
        CHECK_EQ_INT(hf_fur_simulate(b, 0, 7, 1.0f / 60.0f, NULL, 0), HF_OK);
        CHECK_EQ_INT(hf_fur_simulate(b, 7, half - 4, 1.0f / 60.0f, NULL, 0), HF_OK);
        CHECK_EQ_INT(hf_fur_simulate(b, half + 3, G - half - 3, 1.0f / 60.0f,
                                     NULL, 0), HF_OK);
    }
    for (g = 0; g < G; ++g)
        for (k = 0; k < (int)per; ++k) {
            double d = fabs((double)ia.guide_points[(size_t)g * per + (size_t)k] -
                            rest[(size_t)g * per + (size_t)k]);
            if (g < half && d > still) still = d;
            if (g >= half && d > sag) sag = d;
        }
    CHECK(still < 1e-5);
    CHECK(sag > 1e-3);
    CHECK(memcmp(ia.guide_points, ib.guide_points, sizeof(float) * n) == 0);
    /* eight sets fit (the range call shares equal ones); a ninth does not */
    for (k = 1; k < HF_FUR_ROPE_SETS; ++k) {
        memset(&p, 0, sizeof p);
        p.damping = 0.01f * (float)k;
        CHECK_EQ_INT(hf_fur_set_rope_params_range(a, k, 1, &p), HF_OK);
    }
    CHECK_EQ_INT(hf_fur_set_rope_params_range(a, 20, 1, &p), HF_OK); /* shared */
    memset(&p, 0, sizeof p);
    p.damping = 0.5f;
    CHECK_EQ_INT(hf_fur_set_rope_params_range(a, 30, 1, &p), HF_ERROR_BAD_COUNT);
    CHECK_EQ_INT(hf_fur_set_rope_params_range(a, 0, G + 1, &p), HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_fur_set_rope_params_range(NULL, 0, 1, &p), HF_ERROR_NULL_POINTER);
    p.damping = 2.0f;
    CHECK_EQ_INT(hf_fur_set_rope_params_range(a, 0, 1, &p), HF_ERROR_BAD_PARAMETER);
    /* the whole-fur call makes it one set again: the ninth fits now */
    memset(&p, 0, sizeof p);
    CHECK_EQ_INT(hf_fur_set_rope_params(a, &p), HF_OK);
    p.damping = 0.5f;
    CHECK_EQ_INT(hf_fur_set_rope_params_range(a, 30, 1, &p), HF_OK);
    free(rest);
    hf_fur_destroy(a);
    hf_fur_destroy(b);
}

/* Per-frame control: new rope parameters take effect at the next
   simulate (no gravity: the guides stay at rest), bad ones change
   nothing; guides switched to animated follow their rest shape. */
static void test_fur_set_rope_params_and_mode(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_rope_params p;
    float *rest;
    size_t n;
    int frame;
    double moved = 0.0;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    n = (size_t)info.guide_count * (size_t)info.points_per_strand * 3u;
    rest = (float *)malloc(sizeof(float) * n);
    memcpy(rest, info.guide_points, sizeof(float) * n);
    memset(&p, 0, sizeof p);
    p.explicit_zero = HF_ROPE_ZERO_GRAVITY;
    CHECK_EQ_INT(hf_fur_set_rope_params(f, &p), HF_OK);
    p.damping = 2.0f; /* refused: the weightless params stay */
    CHECK_EQ_INT(hf_fur_set_rope_params(f, &p), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_fur_set_rope_params(NULL, &p), HF_ERROR_NULL_POINTER);
    CHECK_EQ_INT(hf_fur_set_rope_params(f, NULL), HF_ERROR_NULL_POINTER);
    for (frame = 0; frame < 20; ++frame)
        CHECK_EQ_INT(hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f,
                                     NULL, 0), HF_OK);
    for (size_t i = 0; i < n; ++i) {
        double d = fabs((double)info.guide_points[i] - rest[i]);
        if (d > moved) moved = d;
    }
    CHECK(moved < 1e-5);
    /* gravity back: simulated guides sag, animated ones keep their rest */
    memset(&p, 0, sizeof p);
    CHECK_EQ_INT(hf_fur_set_rope_params(f, &p), HF_OK);
    CHECK_EQ_INT(hf_fur_set_mode(f, 0, info.guide_count, HF_ROPE_ANIMATED), HF_OK);
    CHECK_EQ_INT(hf_fur_set_mode(f, 0, info.guide_count + 1, HF_ROPE_ANIMATED),
                 HF_ERROR_BAD_RANGE);
    CHECK_EQ_INT(hf_fur_set_mode(f, 0, 1, 7), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_fur_set_mode(NULL, 0, 1, HF_ROPE_ANIMATED), HF_ERROR_NULL_POINTER);
    for (frame = 0; frame < 60; ++frame)
        hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0);
    moved = 0.0;
    for (size_t i = 0; i < n; ++i) {
        double d = fabs((double)info.guide_points[i] - rest[i]);
        if (d > moved) moved = d;
    }
    CHECK(moved < 1e-4);
    CHECK_EQ_INT(hf_fur_set_mode(f, 0, info.guide_count, HF_ROPE_SIMULATED), HF_OK);
    for (frame = 0; frame < 30; ++frame)
        hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0);
    moved = 0.0;
    for (size_t i = 0; i < n; ++i) {
        double d = fabs((double)info.guide_points[i] - rest[i]);
        if (d > moved) moved = d;
    }
    CHECK(moved > 1e-3);
    free(rest);
    hf_fur_destroy(f);
}

/* The largest change of velocity (m/s) of any guide point across each
   frame: dv[f] compares frame f's motion with frame f - 1's. */
static void t_fur_dv(const float *x0, const float *x1, const float *x2,
                     size_t n, float dt, double *dv)
{
    size_t i;
    *dv = 0.0;
    for (i = 0; i + 2 < n; i += 3) {
        double d2 = 0.0;
        int c;
        for (c = 0; c < 3; ++c) {
            double e = (double)x2[i + c] - 2.0 * x1[i + c] + x0[i + c];
            d2 += e * e;
        }
        if (sqrt(d2) / dt > *dv) *dv = sqrt(d2) / dt;
    }
}

/* Per-frame control of a fur on a moving body at frame time dt: new rope
   parameters (wind and weaker gravity), half the guides animated, then
   simulated again mid-glide. Returns the largest change of velocity of the
   first two changes' frames (less what the new acceleration gives), with
   that of ordinary frames and that of the switch back. */
static double t_fur_control_worst(float dt, double *ordinary, double *back)
{
    enum { F = 90 };
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    hf_rope_params p;
    float moved[(FR + 1) * (FS + 1) * 3];
    float *x[3];
    size_t n;
    int frame, i, k, scale = (int)(1.0f / (60.0f * dt) + 0.5f);
    double worst = 0.0, dv;
    hf_mesh m;
    *ordinary = *back = 0.0;
    t_fur_scene_init(&sc, 1.0f);
    if (hf_fur_create(&sc.desc, &f, NULL) != HF_OK) return -1.0;
    hf_fur_get_info(f, &info);
    n = (size_t)info.guide_count * (size_t)info.points_per_strand * 3u;
    for (k = 0; k < 3; ++k) x[k] = (float *)calloc(n, sizeof(float));
    m = sc.desc.mesh;
    m.positions = moved;
    for (frame = 0; frame < F * scale; ++frame) {
        const int at = frame / scale, edge = frame % scale == 0;
        const double t = (frame + 1) * (double)dt;
        if (edge && at == 40) { /* wind and half gravity */
            memset(&p, 0, sizeof p);
            hf_rope_params_init(&p);
            p.gravity[1] = -4.9f;
            p.wind[0] = 3.0f;
            hf_fur_set_rope_params(f, &p);
        }
        if (edge && at == 55)
            hf_fur_set_mode(f, 0, info.guide_count / 2, HF_ROPE_ANIMATED);
        if (edge && at == 62) /* back, mid-glide */
            hf_fur_set_mode(f, 0, info.guide_count / 2, HF_ROPE_SIMULATED);
        for (i = 0; i < (FR + 1) * (FS + 1) * 3; ++i)
            moved[i] = sc.pos[i] + (i % 3 == 2 ? (float)(0.1 * sin(2.0 * t)) : 0.0f);
        hf_fur_set_roots(f, &m, 0, info.guide_count);
        hf_fur_simulate(f, 0, info.guide_count, dt, NULL, 0);
        memcpy(x[0], x[1], n * sizeof(float));
        memcpy(x[1], x[2], n * sizeof(float));
        memcpy(x[2], info.guide_points, n * sizeof(float));
        if (frame < 3 * scale) continue;
        t_fur_dv(x[0], x[1], x[2], n, dt, &dv);
        /* the first frame after each change */
        if (frame == 40 * scale || frame == 55 * scale) {
            /* less what wind (3) and gravity (4.9) change in a frame */
            dv -= frame == 40 * scale ? 5.8 * dt : 0.0;
            if (dv > worst) worst = dv;
        } else if (frame == 62 * scale) {
            *back = dv;
        } else if (at < 40 || at > 70) {
            if (dv > *ordinary) *ordinary = dv;
        }
    }
    for (k = 0; k < 3; ++k) free(x[k]);
    hf_fur_destroy(f);
    return worst;
}

static void test_fur_controls_no_jump(void)
{
    double ord60, ord240, back60, back240;
    double at60 = t_fur_control_worst(1.0f / 60.0f, &ord60, &back60);
    double at240 = t_fur_control_worst(1.0f / 240.0f, &ord240, &back240);
    if (getenv("TR_VERBOSE"))
        printf("controls: dv %g m/s at 60 Hz (ordinary %g, back %g), %g at "
               "240 Hz (ordinary %g, back %g)\n", at60, ord60, back60, at240,
               ord240, back240);
    CHECK(at60 >= 0.0 && at240 >= 0.0);
    /* new parameters and the glide's start: like any frame */
    CHECK(at60 <= 1.5 * ord60);
    CHECK(at240 <= 1.5 * ord240);
    /* back to simulation mid-glide: the constraints take over from the
       curve, a change of acceleration, so it shrinks with the frame time
       (a jump in velocity would not) */
    CHECK(back240 < 0.5 * back60);
}

/* A mode set on LOD guides survives the LOD: put to sleep and woken
   again, guides the caller animated stay animated (they keep their rest
   pose under gravity). */
static void test_fur_mode_survives_lod(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    float *rest;
    size_t n, i;
    int frame;
    double moved = 0.0;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    CHECK(info.lod_guide_count > 0);
    n = (size_t)info.guide_count * (size_t)info.points_per_strand * 3u;
    rest = (float *)malloc(sizeof(float) * n);
    memcpy(rest, info.guide_points, sizeof(float) * n);
    CHECK_EQ_INT(hf_fur_set_mode(f, 0, info.guide_count, HF_ROPE_ANIMATED),
                 HF_OK);
    hf_fur_set_lod(f, 0.1f); /* LOD guides asleep */
    hf_fur_set_lod(f, 1.0f); /* and awake */
    for (frame = 0; frame < 30; ++frame) {
        hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0);
        hf_fur_interpolate_guides(f, 0, info.lod_guide_count);
    }
    for (i = 0; i < n; ++i) {
        double d = fabs((double)info.guide_points[i] - rest[i]);
        if (d > moved) moved = d;
    }
    CHECK(moved < 1e-4);
    /* asleep, a guide set simulated waits for the LOD to wake it */
    hf_fur_set_lod(f, 0.1f);
    CHECK_EQ_INT(hf_fur_set_mode(f, 0, info.guide_count, HF_ROPE_SIMULATED),
                 HF_OK);
    hf_fur_set_lod(f, 1.0f);
    for (frame = 0; frame < 30; ++frame)
        hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0);
    moved = 0.0;
    for (i = (size_t)info.pure_guide_count * info.points_per_strand * 3u;
         i < n; ++i) {
        double d = fabs((double)info.guide_points[i] - rest[i]);
        if (d > moved) moved = d;
    }
    CHECK(moved > 1e-3); /* the LOD guides sag now */
    free(rest);
    hf_fur_destroy(f);
}

/* Styled strands follow their guides' shapes: with curl and wave, each
   segment of a drawn strand points within a bound of the same segment of
   the guide nearest its root (measured: the blend of three guides, each
   curled the same way, stays close to each of them). */
static void test_fur_styled_strands_follow_guides(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    int s, g, j, P, segs = 0, over = 0;
    double worst = 0.0;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.points_per_strand = 16;
    sc.desc.tess_factor = 60.0f;
    sc.desc.curl_radius = 0.03f;
    sc.desc.curl_turns = 2.0f;
    sc.desc.wave_amplitude = 0.02f;
    sc.desc.wave_count = 2.0f;
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_interpolate_guides(f, 0, 0);
    hf_fur_get_info(f, &info);
    hf_fur_interpolate(f, 0, info.drawn_strand_count);
    P = info.points_per_strand;
    for (s = 0; s < info.drawn_strand_count; ++s) {
        const float *sp = info.strand_points + (size_t)s * P * 3;
        const float *gp = NULL;
        double best = 1e30;
        for (g = 0; g < info.guide_count; ++g) {
            const float *q = info.guide_points + (size_t)g * P * 3;
            double d = (q[0] - sp[0]) * (q[0] - sp[0]) +
                       (q[1] - sp[1]) * (q[1] - sp[1]) +
                       (q[2] - sp[2]) * (q[2] - sp[2]);
            if (d < best) { best = d; gp = q; }
        }
        for (j = 0; j + 1 < P; ++j) {
            double a[3], b[3], la = 0.0, lb = 0.0, dot = 0.0, ang;
            int c;
            for (c = 0; c < 3; ++c) {
                a[c] = sp[3 * (j + 1) + c] - sp[3 * j + c];
                b[c] = gp[3 * (j + 1) + c] - gp[3 * j + c];
                la += a[c] * a[c];
                lb += b[c] * b[c];
                dot += a[c] * b[c];
            }
            ang = acos(fmax(-1.0, fmin(1.0, dot / sqrt(la * lb + 1e-300)))) / T_DEG;
            if (ang > worst) worst = ang;
            if (ang > 30.0) ++over;
            ++segs;
        }
    }
    if (getenv("TR_VERBOSE"))
        printf("styled strands: worst %.1f deg, %d of %d segments over 30\n",
               worst, over, segs);
    CHECK(segs > 1000);
    CHECK(over <= segs / 100); /* 99 % within 30 degrees */
    CHECK(worst < 90.0); /* never turned back against its guide */
    hf_fur_destroy(f);
}

/* Teleport: a fur simulated a while, its root frames moved 5 m and turned
   a quarter turn by hf_fur_set_transform, then hf_fur_reset: every guide
   is its rest shape carried by the new frames (within 1e-5 m), and the
   next frame starts from rest there (it moves no more than gravity moves
   a still rope in one frame). */
static void test_fur_teleport(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL, *ref = NULL;
    hf_fur_info info, ri;
    /* x' = -z + 5, y' = y, z' = x - 2: a quarter turn about y */
    const float m[12] = {0, 0, -1, 5, 0, 1, 0, 0, 1, 0, 0, -2};
    size_t n, i;
    int frame;
    double worst = 0.0, moved = 0.0;
    float *before;
    t_fur_scene_init(&sc, 1.0f);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &ref, NULL), HF_OK);
    if (!f || !ref) return;
    hf_fur_get_info(f, &info);
    hf_fur_get_info(ref, &ri);
    n = (size_t)info.guide_count * (size_t)info.points_per_strand * 3u;
    for (frame = 0; frame < 30; ++frame)
        hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0);
    CHECK_EQ_INT(hf_fur_set_transform(f, m, 0, info.guide_count), HF_OK);
    CHECK_EQ_INT(hf_fur_reset(f), HF_OK);
    for (i = 0; i < n; i += 3) { /* ref holds the rest pose */
        const float *r = ri.guide_points + i, *q = info.guide_points + i;
        double e[3];
        e[0] = q[0] - (m[0] * r[0] + m[1] * r[1] + m[2] * r[2] + m[3]);
        e[1] = q[1] - (m[4] * r[0] + m[5] * r[1] + m[6] * r[2] + m[7]);
        e[2] = q[2] - (m[8] * r[0] + m[9] * r[1] + m[10] * r[2] + m[11]);
        e[0] = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        if (e[0] > worst) worst = e[0];
    }
    CHECK(worst < 1e-5);
    before = (float *)malloc(n * sizeof(float));
    memcpy(before, info.guide_points, n * sizeof(float));
    hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0);
    for (i = 0; i < n; ++i) {
        double d = fabs((double)info.guide_points[i] - before[i]);
        if (d > moved) moved = d;
    }
    CHECK(moved <= 9.81 / 3600.0 * 1.01);
    free(before);
    hf_fur_destroy(f);
    hf_fur_destroy(ref);
}

/* hf_fur_set_kernels: every SIMD level, with stores by size, streaming or
   ordinary, gives the fur's strands the same bytes (styled, clumped); bad
   choices are refused and change nothing, at creation with a message. */
static void test_fur_kernels_same_bytes(void)
{
    t_fur_scene sc;
    hf_fur *f = NULL;
    hf_fur_info info;
    float *ref;
    size_t n;
    int level, nt;
    t_fur_scene_init(&sc, 1.0f);
    sc.desc.clump = 0.4f;
    sc.desc.curl_radius = 0.02f;
    sc.desc.curl_turns = 2.0f;
    sc.desc.points_per_strand = 13; /* every vector tail */
    CHECK_EQ_INT(hf_fur_create(&sc.desc, &f, NULL), HF_OK);
    if (!f) return;
    hf_fur_get_info(f, &info);
    n = (size_t)info.strand_count * (size_t)info.points_per_strand * 3u;
    ref = (float *)malloc(n * sizeof(float));
    hf_fur_simulate(f, 0, info.guide_count, 1.0f / 60.0f, NULL, 0);
    CHECK_EQ_INT(hf_fur_set_kernels(f, HF_SIMD_SCALAR, 0), HF_OK);
    hf_fur_interpolate(f, 0, info.strand_count);
    memcpy(ref, info.strand_points, n * sizeof(float));
    for (level = HF_SIMD_AUTO; level <= HF_SIMD_AVX512; ++level)
        for (nt = 0; nt <= 2; ++nt) {
            memset((float *)info.strand_points, 0, n * sizeof(float));
            CHECK_EQ_INT(hf_fur_set_kernels(f, level, nt), HF_OK);
            hf_fur_interpolate(f, 0, info.strand_count);
            CHECK(memcmp(ref, info.strand_points, n * sizeof(float)) == 0);
        }
    CHECK_EQ_INT(hf_fur_set_kernels(f, 5, 0), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_fur_set_kernels(f, -1, 0), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_fur_set_kernels(f, 0, 3), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_fur_set_kernels(f, 0, -1), HF_ERROR_BAD_PARAMETER);
    CHECK_EQ_INT(hf_fur_set_kernels(NULL, 0, 0), HF_ERROR_NULL_POINTER);
    {
        hf_fur *g = NULL;
        hf_diag d;
        sc.desc.nontemporal = 3;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &g, &d), HF_ERROR_BAD_PARAMETER);
        CHECK(g == NULL && strstr(d.message, "nontemporal 3") != NULL);
        sc.desc.nontemporal = 2;
        CHECK_EQ_INT(hf_fur_create(&sc.desc, &g, &d), HF_OK);
        hf_fur_destroy(g);
        sc.desc.nontemporal = 0;
    }
    /* hf_simd_resolve: auto is the best, a request is never raised */
    CHECK(hf_simd_resolve(HF_SIMD_AUTO) >= HF_SIMD_SCALAR);
    CHECK(hf_simd_resolve(HF_SIMD_SCALAR) == HF_SIMD_SCALAR);
    CHECK(hf_simd_resolve(HF_SIMD_AVX512) <= HF_SIMD_AVX512);
    CHECK(hf_simd_resolve(HF_SIMD_AVX512) == hf_simd_resolve(HF_SIMD_AUTO));
    CHECK(hf_simd_resolve(99) == hf_simd_resolve(HF_SIMD_AUTO));
    CHECK(hf_simd_resolve(HF_SIMD_SSE2) <= HF_SIMD_SSE2);
    free(ref);
    hf_fur_destroy(f);
}

/* 10. the fur object: its tests, in the order they run */
#define T_FUR_TESTS(X)                                                         \
    X(test_fur_create_counts_and_welding)                                      \
    X(test_fur_comb)                                                           \
    X(test_fur_guide_curves)                                                   \
    X(test_fur_styling)                                                        \
    X(test_fur_groom)                                                          \
    X(test_fur_settle_rest)                                                    \
    X(test_fur_groom_settle_rest)                                              \
    X(test_fur_clump_leaders_nearest)                                          \
    X(test_fur_clump_size)                                                     \
    X(test_ribbon_strand_widths)                                               \
    X(test_fur_groom_scalp)                                                    \
    X(test_fur_control_maps)                                                   \
    X(test_diagnostics_read_back)                                              \
    X(test_fur_no_allocation_per_frame)                                        \
    X(test_fur_points_aligned)                                                 \
    X(test_fur_ranges_byte_identical)                                          \
    X(test_interp_points_kernels)                                              \
    X(test_fur_interpolate_points)                                             \
    X(test_fur_lod_prefix_and_width)                                           \
    X(test_fur_lod_guides_wake_without_jump)                                   \
    X(test_fur_bad_desc_and_out_of_memory)                                     \
    X(test_fur_same_seed_same_bytes)                                           \
    X(test_fur_keep_length)                                                    \
    X(test_fur_errors_per_frame)                                               \
    X(test_bad_fur)                                                            \
    X(test_defaults_fur_strand_count_precedence)                               \
    X(test_out_first_fur_chunks)                                               \
    X(test_fur_roots_inside_count)                                             \
    X(test_fur_rope_params_range)                                              \
    X(test_fur_set_rope_params_and_mode)                                       \
    X(test_fur_controls_no_jump)                                               \
    X(test_fur_mode_survives_lod)                                              \
    X(test_fur_styled_strands_follow_guides)                                   \
    X(test_fur_teleport)                                                       \
    X(test_fur_kernels_same_bytes)

/* ==== main: every section's list, in the order above ====================== */

#define T_RUN_ONE(fn) RUN(fn);

int main(int argc, char **argv)
{
    int i;
    t_argc = argc;
    t_argv = argv;
    for (i = 1; i < argc; ++i) t_list |= !strcmp(argv[i], "--list");
    T_CONFIG_TESTS(T_RUN_ONE)
    T_RNG_TESTS(T_RUN_ONE)
    T_MAP_TESTS(T_RUN_ONE)
    T_MESH_TESTS(T_RUN_ONE)
    T_DENSITY_TESTS(T_RUN_ONE)
    T_TESS_TESTS(T_RUN_ONE)
    T_GUIDES_TESTS(T_RUN_ONE)
    T_PLACE_TESTS(T_RUN_ONE)
    T_STRAND_TESTS(T_RUN_ONE)
    T_ROPES_TESTS(T_RUN_ONE)
    T_CONTACT_TESTS(T_RUN_ONE)
    T_GRID_TESTS(T_RUN_ONE)
    T_INTERP_TESTS(T_RUN_ONE)
    T_RIBBON_TESTS(T_RUN_ONE)
    T_LUT_TESTS(T_RUN_ONE)
    T_FIBRE_TESTS(T_RUN_ONE)
    T_FUR_TESTS(T_RUN_ONE)
    if (t_list) return 0;
    if (t_passed + t_failed == 0) {
        printf("no test's name begins with any of the prefixes given "
               "(--list lists them)\n");
        return 1;
    }
    printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}
