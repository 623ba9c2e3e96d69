/* bench.c - the per-stage benchmark of hairfur.h: `make bench`.

   Scenes (16 points per strand, the built-in head of examples/head_mesh.h,
   swinging sideways 0.2 m peak to peak at 1 Hz, gravity on, a sphere
   collider on the head):
     S  about 367 guides, 3,670 strands (the 2010 plugin's Krystal)
     M  ten times S
     L  100,000 strands on about 1,000 guides
   Stages: roots, ropes, lod_guides, strands (interpolation, with the
   fur's default stores: streaming for M and L, whose strand points are
   larger than HF_STREAM_MIN_BYTES, ordinary for S), ribbons
   (36-byte float vertices: position, tangent, texcoord), points (the GPU
   path, 16 bytes a point), ribbons16 (the same attributes in 16 bytes:
   SNORM16 position, UNORM16 texcoord, SNORM8 tangent), points8 (the
   GPU points in 8 bytes, HF_POINT_COMPACT, streamed), interp_points
   (hf_fur_interpolate_points: strands and points in one pass, with
   streaming stores, as into a mapped GPU buffer aligned to 64 bytes),
   frame (roots to ribbons), frame16 (the same with ribbons16) and
   frame_points (roots, ropes, LOD guides and interp_points, frames of
   their own: the GPU expands the ribbons, examples/ribbon_expand.glsl).
   For each stage: the median, min and max milliseconds over FRAMES frames
   after a warm-up, the bytes the stage writes per second, and in the same
   run the write limit for the same number of bytes: the best of 16-byte
   vector stores, streaming stores and memset, all of bytes that are not
   zero, each pass into a buffer flushed from the caches (a plain store
   loop, which compiles to 4-byte stores, and memset of zeros are
   printed for reference only). 1 and 2
   threads (pthreads over (first, count) ranges, the workers spinning
   between a frame's stages as a job system's do), and the allocation
   count per frame (a counting allocator: it must be 0).

   Output: a table, then one machine line per figure:
     bench stage=NAME scene=S threads=T ms=... gbps=... limit_gbps=...
           ratio=... [limit_method=memset|vector|stream stream_gbps=...]
           [allocs=N]
   (the table names the way that set each limit beside it, and where
   that was not streaming stores, the ratio against them too)
     bench stage=write_limit method=vector|stream|memset|scalar|zeros gbps=...
   Per SIMD level (scenes M and L, one thread): strands_LEVEL,
   strands_nt_LEVEL (streaming stores), points_LEVEL and points_nt_LEVEL,
   interp_points_LEVEL, ribbons_LEVEL, ribbons_nt_LEVEL, ribbons16_LEVEL
   and ropes_LEVEL, and whole frames at the level, frame_LEVEL and
   frame_points_LEVEL; LEVEL scalar, sse2, avx2, avx512 up to what the CPU
   has.
   Last, the targets of docs/performance.md read from this run's figures
   (those of the scenes it ran), each met or NOT met:
     bench target=NAME value=... goal=... met=0|1
   Scene Mc (M's strands on a coarse head, whose tessellation adds LOD
   guides) at LOD 0.25 measures lod_guides: LOD guides interpolated from
   the pure guides instead of simulated.
   --scaling instead: how cost grows with strands and guides (bench_scaling).
   Scene V (--scene V): a character at Veilguard's scale, its head alone
   (Vh) and on a 24-proxy body (V), every stage at 1 and 2 threads, then
   the ropes and the GPU path's frame against the number of colliders
   (bench_character), and three targets of its own; then hair-hair
   interaction on V (bench_hair_grid): the grid, and what it adds to the
   ropes, with its target.
   --scene Vg: the hair-hair stage alone.
   Usage: bench [--frames N] [--scene S|M|L|Mc|V|Vg] [--scaling] */
#define _POSIX_C_SOURCE 200809L
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"
#define HEAD_MESH_IMPLEMENTATION
#include "../examples/head_mesh.h"

#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_fur.h"
#include "bench_time.h"
#define P BENCH_P
#define MAX_THREADS 2
/* the ropes' grain on two threads (struct job) */
#define BENCH_ROPE_GRAIN 256

/* ---- counting allocator ------------------------------------------------ */

static long g_allocs;
static void *c_alloc(size_t n, void *u) { (void)u; ++g_allocs; return malloc(n); }
static void *c_realloc(void *p, size_t n, void *u) { (void)u; if (!p) ++g_allocs; return realloc(p, n); }
static void c_free(void *p, void *u) { (void)u; free(p); }

/* ---- a tiny thread pool: thread 0 is the caller ------------------------ */

/* Between a frame's stages the workers spin, as a job system's do: a
   stage comes a few microseconds after the last, and waking a sleeping
   thread costs this virtual machine 30-70 us a stage (pthread barriers
   measured scene L's roots at 0.074-0.099 ms with two threads, 0.027
   with one).
   A worker that finds no stage after a while sleeps until the next. */

/* A stage's work: equal shares, one per thread, or (grain > 0) shares
   that balance themselves, as a job system's work stealing does: each
   thread walks its own share grain by grain from the front, and one that
   has finished takes grains from the back of a share still running. A
   rope's cost depends on its contacts (hair resting on a body's
   shoulders lies in one part of the guides' order), and shares walked
   this way meet only at their ends: ranges dealt to the threads in turn
   would meet at every grain, where the two cores trade the rows' cache
   lines (docs/performance.md). */
typedef struct job job;
typedef void (*job_fn)(job *j, int first, int count);
struct job {
    job_fn fn;
    int total;
    int grain;
    unsigned long long share[MAX_THREADS]; /* front | back << 32 (atomic) */
};

static job *volatile g_job;
static int g_threads = 1;
static volatile int g_quit;
static unsigned g_gen; /* stages started; a worker runs each once */
static int g_left;     /* workers still on the current stage */
static pthread_mutex_t g_mu = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t g_cv = PTHREAD_COND_INITIALIZER;
#define SPINS 20000

static void cpu_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    __asm__ __volatile__("yield");
#endif
}

/* A grain of share s: from its front (own) or its back (stolen); 0 when
   the share is used up. */
static int take_grain(job *j, int s, int own, int *first, int *count)
{
    unsigned long long v = __atomic_load_n(&j->share[s], __ATOMIC_ACQUIRE), w;
    for (;;) {
        unsigned lo = (unsigned)v, hi = (unsigned)(v >> 32), a, b;
        if (lo >= hi) return 0;
        a = own ? lo : (hi - lo > (unsigned)j->grain ? hi - j->grain : lo);
        b = own ? (hi - lo > (unsigned)j->grain ? lo + j->grain : hi) : hi;
        w = own ? (unsigned long long)b | (v & 0xffffffff00000000ull)
                : (unsigned long long)lo | (unsigned long long)a << 32;
        if (__atomic_compare_exchange_n(&j->share[s], &v, w, 0,
                                        __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
            *first = (int)a;
            *count = (int)(b - a);
            return 1;
        }
    }
}

static void run_share(job *j, int t, int n)
{
    int first = (int)((long long)j->total * t / n);
    int end = (int)((long long)j->total * (t + 1) / n), count, k;
    if (n == 1 || j->grain <= 0) {
        j->fn(j, first, end - first);
        return;
    }
    while (take_grain(j, t, 1, &first, &count)) j->fn(j, first, count);
    for (k = 1; k < n; ++k) /* then the others' backs */
        while (take_grain(j, (t + k) % n, 0, &first, &count))
            j->fn(j, first, count);
}

/* The next stage's number after `seen`: spin a while, then sleep. */
static unsigned next_stage(unsigned seen)
{
    unsigned g;
    int spins = 0;
    while ((g = __atomic_load_n(&g_gen, __ATOMIC_ACQUIRE)) == seen) {
        if (++spins < SPINS) {
            cpu_relax();
            continue;
        }
        pthread_mutex_lock(&g_mu);
        while ((g = __atomic_load_n(&g_gen, __ATOMIC_ACQUIRE)) == seen)
            pthread_cond_wait(&g_cv, &g_mu);
        pthread_mutex_unlock(&g_mu);
    }
    return g;
}

/* Start a stage (or, with g_quit set, the workers' end). */
static void start_stage(void)
{
    pthread_mutex_lock(&g_mu);
    __atomic_add_fetch(&g_gen, 1u, __ATOMIC_RELEASE);
    pthread_cond_broadcast(&g_cv);
    pthread_mutex_unlock(&g_mu);
}

static void *worker(void *arg)
{
    int t = (int)(size_t)arg;
    unsigned seen = 0;
    for (;;) {
        seen = next_stage(seen);
        if (g_quit) break;
        if (t < g_threads) run_share(g_job, t, g_threads);
        __atomic_sub_fetch(&g_left, 1, __ATOMIC_RELEASE);
    }
    return NULL;
}

static void run_job(job *j)
{
    int spins = 0;
    if (g_threads == 1) {
        run_share(j, 0, 1);
        return;
    }
    g_job = j;
    for (spins = 0; spins < g_threads; ++spins)
        j->share[spins] =
            (unsigned long long)((long long)j->total * spins / g_threads) |
            (unsigned long long)((long long)j->total * (spins + 1) /
                                 g_threads) << 32;
    spins = 0;
    __atomic_store_n(&g_left, MAX_THREADS - 1, __ATOMIC_RELAXED);
    start_stage();
    run_share(j, 0, g_threads);
    while (__atomic_load_n(&g_left, __ATOMIC_ACQUIRE) != 0)
        if (++spins < SPINS)
            cpu_relax();
        else
            sched_yield();
}

/* ---- scenes ------------------------------------------------------------ */

typedef struct scene {
    const char *name;
    int rings, segments, strands;
    hm_mesh head;
    unsigned char density[256 * 256];
    hm_vertex *skin;
    hf_fur *fur;
    hf_fur_info info;
    float *vbuf, *pbuf;
    unsigned char *cbuf; /* 16-byte compact ribbon vertices */
    hf_collider col[BENCH_MAX_COLLIDERS]; /* the head's, then a body's */
    int ncol;
    hf_mesh skinned;
    float dt;
    int frame;
} scene;

static scene *g_sc;

static void fail(const char *what, hf_result r)
{
    fprintf(stderr, "bench: %s: %s\n", what, hf_result_string(r));
    exit(1);
}

static void check(const char *what, hf_result r)
{
    if (r != HF_OK) fail(what, r);
}

static void j_roots(job *j, int f, int c) { (void)j; check("roots", hf_fur_set_roots(g_sc->fur, &g_sc->skinned, f, c)); }
static void j_ropes(job *j, int f, int c) { (void)j; check("ropes", hf_fur_simulate(g_sc->fur, f, c, g_sc->dt, g_sc->col, g_sc->ncol)); }
static void j_grid(job *j, int f, int c) { (void)j; check("grid", hf_fur_build_grid(g_sc->fur, f, c)); }
static void j_lodg(job *j, int f, int c) { (void)j; check("lod guides", hf_fur_interpolate_guides(g_sc->fur, f, c)); }
static void j_interp(job *j, int f, int c) { (void)j; check("interpolate", hf_fur_interpolate(g_sc->fur, f, c)); }

static hf_ribbon_params g_view;
static hf_ribbon_output g_out;
static void j_ribbons(job *j, int f, int c) { (void)j; check("ribbons", hf_fur_ribbons(g_sc->fur, f, c, &g_view, &g_out)); }
static void j_points(job *j, int f, int c) { (void)j; check("points", hf_fur_points(g_sc->fur, f, c, &g_view, g_sc->pbuf)); }
/* the GPU path writes a mapped (write-combined) buffer, where streaming
   stores are the right ones (hf_ribbon_params.nontemporal) */
static hf_ribbon_params g_view_gpu;
static void j_ipoints(job *j, int f, int c) { (void)j; check("interp_points", hf_fur_interpolate_points(g_sc->fur, f, c, &g_view_gpu, g_sc->pbuf)); }
static hf_ribbon_output g_out16;
static void j_ribbons16(job *j, int f, int c) { (void)j; check("ribbons16", hf_fur_ribbons(g_sc->fur, f, c, &g_view, &g_out16)); }
/* the GPU points in 8 bytes (HF_POINT_COMPACT, a 0.5 m box about the
   head), streamed as the other GPU path */
static hf_ribbon_params g_view_gpu8;
static void j_points8(job *j, int f, int c) { (void)j; check("points8", hf_fur_points(g_sc->fur, f, c, &g_view_gpu8, g_sc->pbuf)); }

/* The first ncol colliders of a character swaying dx sideways: the
   head's sphere, its body (bench_body), then two more bodies 2 m to
   either side, which no hair reaches. */
static void scene_colliders(scene *s, float dx)
{
    hf_collider all[1 + 3 * BENCH_BODY];
    int i;
    bench_collider(&all[0]);
    all[0].a[0] = dx;
    bench_body(all + 1, dx, 0.0f);
    bench_body(all + 1 + BENCH_BODY, dx + 2.0f, 0.0f);
    bench_body(all + 1 + 2 * BENCH_BODY, dx - 2.0f, 0.5f);
    for (i = 0; i < s->ncol; ++i) s->col[i] = all[i];
}

static void scene_pose(scene *s, int frame)
{
    /* sideways swing, 0.2 m peak to peak at 1 Hz */
    float dx = 0.1f * (float)sin(2.0 * 3.14159265358979 * frame / 60.0);
    int i;
    for (i = 0; i < s->head.vertex_count; ++i) {
        s->skin[i] = s->head.vertices[i];
        s->skin[i].pos[0] += dx;
    }
    scene_colliders(s, dx);
}

/* A buffer aligned as a mapped OpenGL buffer is (and the write limit's,
   so that both are measured alike). */
static void *mapped_like(size_t bytes)
{
    void *q = NULL;
    if (posix_memalign(&q, 64, bytes)) {
        fprintf(stderr, "bench: out of memory (%zu bytes)\n", bytes);
        exit(1);
    }
    return q;
}

/* the hair-hair grid of the next scene_init (0: none), and whether its
   strands keep their lengths (hf_fur_desc.keep_length) */
static int g_grid_resolution, g_keep_length;

static void scene_init(scene *s, const char *name, int rings, int segments,
                       int strands, float tess_factor, int points,
                       float length)
{
    hf_fur_desc d;
    hf_diag diag;
    hf_map density;
    hf_allocator a;
    hf_rope_params rp;
    size_t nv;
    memset(s, 0, sizeof *s);
    s->name = name;
    if (!hm_sphere(rings, segments, BENCH_HEAD_RADIUS, &s->head)) exit(1);
    hm_hairline_density(s->density, 256, 256);
    bench_fur_desc(&d, &density, &rp, &s->head, s->density, strands,
                   tess_factor);
    d.points_per_strand = points;
    d.max_length = length;
    d.grid_resolution = g_grid_resolution;
    d.keep_length = g_keep_length;
    a.alloc = c_alloc;
    a.realloc = c_realloc;
    a.free = c_free;
    a.user = NULL;
    d.allocator = &a;
    if (hf_fur_create(&d, &s->fur, &diag) != HF_OK) {
        fprintf(stderr, "bench: %s\n", diag.message);
        exit(1);
    }
    hf_fur_get_info(s->fur, &s->info);
    s->skin = (hm_vertex *)malloc(sizeof(hm_vertex) * (size_t)s->head.vertex_count);
    nv = (size_t)s->info.strand_count * (size_t)points * 2u;
    /* the vertices go to mapped buffers, which OpenGL aligns to at least
       64 bytes (GL_MIN_MAP_BUFFER_ALIGNMENT) */
    s->vbuf = (float *)mapped_like(nv * 36u);
    s->pbuf = (float *)mapped_like(nv * 8u);
    s->cbuf = (unsigned char *)mapped_like(nv * 16u);
    if (!s->skin) exit(1);
    memset(s->vbuf, 0, nv * 36u); /* fault the pages in before timing */
    memset(s->cbuf, 0, nv * 16u);
    memset(s->pbuf, 0, nv * 8u);
    s->skinned = d.mesh;
    s->skinned.positions = s->skin[0].pos;
    s->skinned.normals = s->skin[0].normal;
    s->skinned.uvs = s->skin[0].uv;
    s->ncol = 1; /* the head's sphere */
    scene_colliders(s, 0.0f);
    s->dt = 1.0f / 60.0f;
}

/* ---- the limit: ways of writing the same bytes ------------------------- */

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define HAVE_SSE2 1
#else
#define HAVE_SSE2 0
#endif

/* Each timed pass of a limit starts with its buffer out of the caches, as
   a streamed stage's output is (streaming stores leave no copy in the
   cache): otherwise a buffer smaller than the last-level cache would be
   rewritten in place and the "limit" be the cache's bandwidth. Its lines
   are flushed (clflush) before each pass. Writing 64 MiB of other bytes
   with memset, as the bench did before, left them there: glibc 2.36
   writes a memset of that size with `rep stosb`, which on this CPU left
   the cache as it was (a 19 MiB buffer then measured 46-48 GB/s with vector
   stores, 40-44 flushed; 7 MiB 39-66 against 44-46). A buffer under the
   last-level cache still writes faster than a large one, flushed or
   not: its lines are written back after the pass, for the limit and a
   stage alike. Without SSE2: 64 MiB of other bytes, one ordinary store
   a line. */
#define EVICT_BYTES ((size_t)64 << 20)
static unsigned char *g_evict;

static void evict(const void *buf, size_t bytes)
{
#if HAVE_SSE2
    const char *c = (const char *)buf;
    size_t i;
    for (i = 0; i < bytes; i += 64) _mm_clflush(c + i);
    _mm_mfence();
#else
    volatile unsigned char *e;
    size_t i;
    (void)buf;
    (void)bytes;
    if (!g_evict) g_evict = (unsigned char *)malloc(EVICT_BYTES);
    if (!g_evict) return;
    e = g_evict;
    for (i = 0; i < EVICT_BYTES; i += 64) e[i] = (unsigned char)(i >> 6);
#endif
}

static double store_gbps(float *dst, size_t bytes, int reps)
{
    size_t n = bytes / 4, i;
    double best = 1e30;
    int r;
    for (r = 0; r < reps; ++r) {
        double t0, t;
        evict(dst, bytes);
        t0 = now_ms();
        float v = (float)(r + 1); /* never zero: see memset_gbps */
        for (i = 0; i < n; ++i) dst[i] = v;
        t = now_ms() - t0;
        best = t < best ? t : best;
    }
    return bytes / best / 1e6;
}

/* The true write limit: a plain loop compiles to scalar 4-byte stores and
   measures the compiler, not the core. 16-byte vector stores, streaming
   (non-temporal) stores and memset write the same bytes; the best of them
   is the limit every stage is compared with. Without SSE2 only memset.
   Every way writes bytes that are not zero, as the stages do: some
   machines write all-zero lines far faster (this one: memset of zeros
   54-61 GB/s against 30 for any other byte, streaming stores of zeros 82
   against 28.5), which is not a rate any stage could reach. `zeros`
   writes zeros, printed for reference only. */
static double memset_gbps(float *dst, size_t bytes, int reps, int zeros)
{
    double best = 1e30;
    int r;
    for (r = 0; r < reps; ++r) {
        double t0, t;
        evict(dst, bytes);
        t0 = now_ms();
        memset(dst, zeros ? 0 : 0x41 + r, bytes);
        t = now_ms() - t0;
        best = t < best ? t : best;
    }
    return bytes / best / 1e6;
}

#if HAVE_SSE2
/* 16-byte stores, a 64-byte line per iteration, of values that change per
   line so the compiler cannot turn the loop into memset; four independent
   vectors, so the loop waits on no addition (one vector added to itself
   per store would hold it to a store per add latency: 19 GB/s here).
   `stream`: non-temporal stores from the first 16-byte boundary (then an
   sfence). The last (bytes - skip) % 64 bytes are not written. */
#define VECTOR_LINES(STORE)                                                    \
    for (i = 0; i < n; ++i) {                                                  \
        STORE(a + 16 * i, v0);                                                 \
        STORE(a + 16 * i + 4, v1);                                             \
        STORE(a + 16 * i + 8, v2);                                             \
        STORE(a + 16 * i + 12, v3);                                            \
        v0 = _mm_add_ps(v0, four);                                             \
        v1 = _mm_add_ps(v1, four);                                             \
        v2 = _mm_add_ps(v2, four);                                             \
        v3 = _mm_add_ps(v3, four);                                             \
    }
static double vector_stores_gbps(float *dst, size_t bytes, int reps,
                                 int stream)
{
    size_t skip = stream ? (16u - ((size_t)(uintptr_t)dst & 15u)) & 15u : 0;
    float *a = (float *)((unsigned char *)dst + skip);
    size_t n = (bytes - skip) / 64, i;
    const __m128 four = _mm_set1_ps(4.0f);
    double best = 1e30;
    int r;
    for (r = 0; r < reps; ++r) {
        __m128 v0 = _mm_set1_ps((float)r + 1.0f), v1 = _mm_add_ps(v0, v0),
               v2 = _mm_add_ps(v1, v0), v3 = _mm_add_ps(v1, v1);
        double t0, t;
        evict(dst, bytes);
        t0 = now_ms();
        if (stream) {
            VECTOR_LINES(_mm_stream_ps)
            _mm_sfence();
        } else {
            VECTOR_LINES(_mm_storeu_ps)
        }
        t = now_ms() - t0;
        best = t < best ? t : best;
    }
    return (double)(n * 64) / best / 1e6;
}
#undef VECTOR_LINES
#endif

/* Each way of writing `bytes` (GB/s; vector and stream 0 without SSE2)
   and the best of them, the limit of a write-bound stage, with the way
   that set it: under the last-level cache's size memset can finish
   before its lines are written back, a rate that a stage streaming to
   memory (as into a mapped GPU buffer) does not reach, so the report
   gives the ratio against streaming stores too. */
typedef struct wlimit {
    double memset, vector, stream, best;
    const char *how;
} wlimit;

static wlimit write_limit(float *dst, size_t bytes, int reps)
{
    wlimit l;
    l.memset = memset_gbps(dst, bytes, reps, 0);
    l.vector = l.stream = 0.0;
#if HAVE_SSE2
    l.vector = vector_stores_gbps(dst, bytes, reps, 0);
    l.stream = vector_stores_gbps(dst, bytes, reps, 1);
#endif
    l.best = l.memset;
    l.how = "memset";
    if (l.vector > l.best) {
        l.best = l.vector;
        l.how = "vector";
    }
    if (l.stream > l.best) {
        l.best = l.stream;
        l.how = "stream";
    }
    return l;
}

/* ---- measuring --------------------------------------------------------- */

typedef struct figure {
    double med, min, max;
} figure;

static figure stats(double *v, int n)
{
    figure f;
    qsort(v, (size_t)n, sizeof *v, cmp_d);
    f.med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    f.min = v[0];
    f.max = v[n - 1];
    return f;
}

/* The figures the targets are read from (report keeps them) */
typedef struct kept {
    char stage[32], scene[4];
    int threads;
    double ms, ratio;
} kept;
static kept g_kept[512];
static int g_nkept;
static long g_max_allocs = -1;

static const kept *find_kept(const char *stage, const char *scene_name,
                             int threads)
{
    int i;
    for (i = 0; i < g_nkept; ++i)
        if (!strcmp(g_kept[i].stage, stage) &&
            !strcmp(g_kept[i].scene, scene_name) &&
            g_kept[i].threads == threads)
            return &g_kept[i];
    return NULL;
}

/* A figure's line and machine line; with lim (its bytes' write limit),
   the bytes written per second against it */
static void report(const char *stage, const char *scene_name, int threads,
                   figure f, double bytes, const wlimit *lim, long allocs)
{
    double gbps = lim ? bytes / f.med / 1e6 : 0.0;
    if (g_nkept < (int)(sizeof g_kept / sizeof g_kept[0])) {
        kept *k = &g_kept[g_nkept++];
        snprintf(k->stage, sizeof k->stage, "%s", stage);
        snprintf(k->scene, sizeof k->scene, "%s", scene_name);
        k->threads = threads;
        k->ms = f.med;
        k->ratio = lim ? gbps / lim->best : 0.0;
    }
    if (allocs > g_max_allocs) g_max_allocs = allocs;
    printf("  %-12s %-2s %dT  median %8.3f ms  (min %7.3f, max %7.3f)", stage,
           scene_name, threads, f.med, f.min, f.max);
    if (lim) {
        printf("  %6.2f GB/s  limit %6.2f (%s) ratio %.2f", gbps, lim->best,
               lim->how, gbps / lim->best);
        if (lim->stream > 0.0 && lim->stream < lim->best)
            printf(" (streaming stores %.2f: %.2f)", lim->stream,
                   gbps / lim->stream);
    }
    if (allocs >= 0) printf("  allocs %ld", allocs);
    printf("\n");
    fprintf(stderr, "bench stage=%s scene=%s threads=%d ms=%.4f gbps=%.3f "
                    "limit_gbps=%.3f ratio=%.3f",
            stage, scene_name, threads, f.med, gbps, lim ? lim->best : 0.0,
            lim ? gbps / lim->best : 0.0);
    if (lim)
        fprintf(stderr, " limit_method=%s stream_gbps=%.3f", lim->how,
                lim->stream);
    if (allocs >= 0) fprintf(stderr, " allocs=%ld", allocs);
    fprintf(stderr, "\n");
}

enum { ST_ROOTS, ST_ROPES, ST_LODG, ST_INTERP, ST_RIBBONS, ST_POINTS,
       ST_RIBBONS16, ST_POINTS8, ST_IPOINTS, ST_FRAME, ST_FRAME16, ST_FRAMEP,
       ST_N };
static const char *st_name[ST_N] = {"roots", "ropes", "lod_guides", "strands",
                                    "ribbons", "points", "ribbons16",
                                    "points8", "interp_points", "frame",
                                    "frame16", "frame_points"};

/* Each stage's job over the whole scene (the frames' entries left empty) */
static void stage_jobs(const scene *s, job *jobs)
{
    static const job_fn fn[ST_FRAME] = {
        j_roots, j_ropes, j_lodg, j_interp, j_ribbons, j_points,
        j_ribbons16, j_points8, j_ipoints};
    int k;
    for (k = 0; k < ST_N; ++k) {
        jobs[k].fn = k < ST_FRAME ? fn[k] : NULL;
        jobs[k].grain = k == ST_ROPES ? BENCH_ROPE_GRAIN : 0;
        jobs[k].total = k == ST_ROOTS || k == ST_ROPES ? s->info.guide_count
                        : k == ST_LODG                 ? s->info.lod_guide_count
                        : k < ST_FRAME                 ? s->info.strand_count
                                                       : 0;
    }
}

/* A frame's simulation, before its strands: roots, ropes, LOD guides */
static void run_simulation(job *jobs)
{
    run_job(&jobs[ST_ROOTS]);
    run_job(&jobs[ST_ROPES]);
    run_job(&jobs[ST_LODG]);
}

static void bench_scene(scene *s, int frames, int threads, double *frame_ms_out)
{
    double *t[ST_N];
    job jobs[ST_N];
    long allocs0;
    int f, k, warm = 10;
    double bytes[ST_N];
    const double np = s->info.points_per_strand;
    g_sc = s;
    g_threads = threads;
    bench_views(&g_view, &g_view_gpu, &g_out, s->vbuf, &g_out16, s->cbuf);
    g_view_gpu8 = g_view_gpu;
    g_view_gpu8.point_format = HF_POINT_COMPACT;
    g_view_gpu8.point_scale = 0.5f;
    for (k = 0; k < ST_N; ++k)
        t[k] = (double *)malloc(sizeof(double) * (size_t)frames);
    stage_jobs(s, jobs);
    bytes[ST_ROOTS] = (double)s->info.guide_count * 36.0;
    bytes[ST_ROPES] = (double)s->info.guide_count * np * 12.0;
    bytes[ST_LODG] = (double)s->info.lod_guide_count * np * 12.0;
    bytes[ST_INTERP] = (double)s->info.strand_count * np * 12.0;
    bytes[ST_RIBBONS] = (double)s->info.strand_count * np * 2.0 * 36.0;
    bytes[ST_POINTS] = (double)s->info.strand_count * np * 16.0;
    bytes[ST_RIBBONS16] = (double)s->info.strand_count * np * 2.0 * 16.0;
    bytes[ST_POINTS8] = (double)s->info.strand_count * np * 8.0;
    bytes[ST_IPOINTS] = bytes[ST_POINTS];
    bytes[ST_FRAME] = bytes[ST_FRAME16] = bytes[ST_FRAMEP] = 0;

    allocs0 = g_allocs;
    /* the stages in their enum's order, roots to points8, each timed */
    for (f = -warm; f < frames; ++f) {
        double ts[ST_POINTS8 + 2];
        scene_pose(s, s->frame++);
        ts[0] = now_ms();
        for (k = 0; k <= ST_POINTS8; ++k) {
            run_job(&jobs[k]);
            ts[k + 1] = now_ms();
        }
        if (f < 0) continue;
        for (k = 0; k <= ST_POINTS8; ++k) t[k][f] = ts[k + 1] - ts[k];
        /* roots .. ribbons: what a frame needs; with 16-byte vertices */
        t[ST_FRAME][f] = ts[ST_RIBBONS + 1] - ts[0];
        t[ST_FRAME16][f] = (ts[ST_INTERP + 1] - ts[0]) +
                           (ts[ST_RIBBONS16 + 1] - ts[ST_RIBBONS16]);
    }
    /* The GPU path's frames on their own, as an application that draws
       that way runs them: roots, ropes, LOD guides, then strands and their
       points in one pass (nothing else writes between frames) */
    for (f = -warm; f < frames; ++f) {
        double t0, t3, t8;
        scene_pose(s, s->frame++);
        t0 = now_ms();
        run_simulation(jobs);
        t3 = now_ms();
        run_job(&jobs[ST_IPOINTS]);
        t8 = now_ms();
        if (f < 0) continue;
        t[ST_IPOINTS][f] = t8 - t3;
        t[ST_FRAMEP][f] = t8 - t0;
    }
    {
        long allocs = g_allocs - allocs0;
        size_t big = (size_t)s->info.strand_count * (size_t)np * 2u * 36u;
        float *dst = (float *)mapped_like(big);
        memset(dst, 1, big);
        for (k = 0; k < ST_N; ++k) {
            figure fg = stats(t[k], frames);
            wlimit lim;
            if (k == ST_LODG && jobs[ST_LODG].total == 0) continue;
            if (bytes[k] > 0) lim = write_limit(dst, (size_t)bytes[k], 7);
            report(st_name[k], s->name, threads, fg, bytes[k],
                   bytes[k] > 0 ? &lim : NULL, k >= ST_FRAME ? allocs : -1);
            if (k == ST_FRAME && frame_ms_out) *frame_ms_out = fg.med;
        }
        free(dst);
    }
    for (k = 0; k < ST_N; ++k) free(t[k]);
}

/* Whole frames at one level, one thread, as bench_scene times them: the
   frame with CPU ribbons (roots, ropes, LOD guides, strands and ribbons
   streamed by size) in tf, the GPU path's (roots, ropes, LOD guides, then
   strands and points in one pass) in tp: what a level buys a frame. */
static void level_frames(scene *s, int level, int frames, double *tf,
                         double *tp)
{
    job jobs[ST_N];
    int f, gpu;
    stage_jobs(s, jobs);
    g_view.simd = g_view_gpu.simd = level;
    g_view.nontemporal = 0;
    check("kernels", hf_fur_set_kernels(s->fur, level, 0));
    for (gpu = 0; gpu < 2; ++gpu)
        for (f = -5; f < frames; ++f) {
            double t0;
            scene_pose(s, s->frame++);
            t0 = now_ms();
            run_simulation(jobs);
            if (gpu) {
                run_job(&jobs[ST_IPOINTS]);
            } else {
                run_job(&jobs[ST_INTERP]);
                run_job(&jobs[ST_RIBBONS]);
            }
            if (f >= 0) (gpu ? tp : tf)[f] = now_ms() - t0;
        }
}

/* The stages with SIMD kernels, per level (hf_simd_level), one thread:
   what each level buys on this CPU, and what streaming stores buy
   (strands, points and ribbons: ordinary stores; strands_nt, points_nt
   and ribbons_nt: streaming; hf_fur_set_kernels' and
   hf_ribbon_params.nontemporal 2 and 1, where the stage rows take the
   default, 0, which streams past HF_STREAM_MIN_BYTES of strand points
   and HF_STREAM_MIN_VERTEX_BYTES of vertices or points). Levels the CPU
   lacks are skipped (they would run as the best it has). */
static const char *level_name[] = {"auto", "scalar", "sse2", "avx2",
                                   "avx512"};
enum {
    LV_STRANDS, LV_STRANDS_NT, LV_POINTS, LV_POINTS_NT, LV_RIBBONS,
    LV_RIBBONS_NT, LV_ROPES, LV_IPOINTS, LV_RIBBONS16, LV_N
};

static void bench_levels(scene *s, int frames)
{
    static const char *what[LV_N] = {"strands", "strands_nt", "points",
                                     "points_nt", "ribbons", "ribbons_nt",
                                     "ropes", "interp_points", "ribbons16"};
    /* each measure's job (jobs[]) and whether it streams (interp_points
       always does, as in its stage) */
    static const int job_of[LV_N] = {0, 0, 1, 1, 2, 2, 3, 4, 5};
    static const int nt_of[LV_N] = {0, 1, 0, 1, 0, 1, 0, 1, 0};
    job jobs[6];
    double *t[LV_N], bytes[LV_N], *tf, *tp;
    int f, level, k, best = hf_simd_resolve(HF_SIMD_AUTO);
    size_t big = (size_t)s->info.strand_count * P * 2u * 36u;
    float *dst = (float *)mapped_like(big);
    memset(jobs, 0, sizeof jobs);
    g_sc = s;
    g_threads = 1;
    jobs[0].fn = j_interp;
    jobs[1].fn = j_points;
    jobs[2].fn = j_ribbons;
    jobs[3].fn = j_ropes;
    jobs[4].fn = j_ipoints;
    jobs[5].fn = j_ribbons16;
    for (k = 0; k < 6; ++k) jobs[k].total = s->info.strand_count;
    jobs[3].total = s->info.guide_count;
    bytes[LV_STRANDS] = bytes[LV_STRANDS_NT] =
        (double)s->info.strand_count * P * 12.0;
    bytes[LV_POINTS] = bytes[LV_POINTS_NT] =
        (double)s->info.strand_count * P * 16.0;
    bytes[LV_RIBBONS] = bytes[LV_RIBBONS_NT] = (double)big;
    bytes[LV_ROPES] = (double)s->info.guide_count * P * 12.0;
    bytes[LV_IPOINTS] = bytes[LV_POINTS];
    bytes[LV_RIBBONS16] = (double)s->info.strand_count * P * 2.0 * 16.0;
    memset(dst, 1, big);
    for (k = 0; k < LV_N; ++k)
        t[k] = (double *)malloc(sizeof(double) * (size_t)frames);
    tf = (double *)malloc(sizeof(double) * (size_t)frames);
    tp = (double *)malloc(sizeof(double) * (size_t)frames);
    for (level = HF_SIMD_SCALAR; level <= best; ++level) {
        g_view.simd = g_view_gpu.simd = level;
        for (f = -5; f < frames; ++f) {
            scene_pose(s, s->frame++);
            for (k = 0; k < LV_N; ++k) {
                const int nt = nt_of[k];
                double t0;
                /* 2: ordinary stores (0 chooses by size) */
                check("kernels",
                      hf_fur_set_kernels(s->fur, level, nt ? 1 : 2));
                g_view.nontemporal = nt ? 1 : 2;
                t0 = now_ms();
                run_job(&jobs[job_of[k]]);
                if (f >= 0) t[k][f] = now_ms() - t0;
            }
        }
        for (k = 0; k < LV_N; ++k) {
            char name[32];
            sprintf(name, "%s_%s", what[k], level_name[level]);
            const wlimit lim = write_limit(dst, (size_t)bytes[k], 7);
            report(name, s->name, 1, stats(t[k], frames), bytes[k], &lim, -1);
        }
        level_frames(s, level, frames, tf, tp);
        {
            char name[32];
            sprintf(name, "frame_%s", level_name[level]);
            report(name, s->name, 1, stats(tf, frames), 0, NULL, -1);
            sprintf(name, "frame_points_%s", level_name[level]);
            report(name, s->name, 1, stats(tp, frames), 0, NULL, -1);
        }
    }
    check("kernels", hf_fur_set_kernels(s->fur, HF_SIMD_AUTO, 0));
    g_view.simd = g_view_gpu.simd = HF_SIMD_AUTO;
    g_view.nontemporal = 0;
    for (k = 0; k < LV_N; ++k) free(t[k]);
    free(tf);
    free(tp);
    free(dst);
}

static void scene_free(scene *s)
{
    hf_fur_destroy(s->fur);
    hm_free(&s->head);
    free(s->skin);
    free(s->vbuf);
    free(s->pbuf);
    free(s->cbuf);
}

/* Scene V, a character at Veilguard's scale (BENCH_V_*): every stage
   with the head's sphere alone (scene Vh) and with the head on its
   24-proxy body (scene V), 1 and 2 threads; then how the ropes and the
   GPU path's frame (roots, ropes, LOD guides, interp_points) grow with
   the colliders: none, the head's, the head and the first 7 (23)
   proxies, the whole body (25), and 64 (39 more of two bodies 2 m away,
   which no hair reaches), each after a second for the hair to settle
   on them. Machine lines:
     bench stage=colliders scene=V colliders=N threads=T ropes=..
           frame_points=..
   g_v_frame: frame_points ms by collider row and threads. */
#define V_ROWS 6
static const int v_counts[V_ROWS] = {0, 1, 8, 24, 1 + BENCH_BODY,
                                     BENCH_MAX_COLLIDERS};
static double g_v_frame[V_ROWS][MAX_THREADS + 1];
static int g_v_ran;

static void bench_character(int frames)
{
    static scene v;
    job jobs[ST_N];
    double *tr = (double *)malloc(sizeof(double) * (size_t)frames),
           *tf = (double *)malloc(sizeof(double) * (size_t)frames);
    int body, th, c, f;
    scene_init(&v, "Vh", BENCH_V_RINGS, BENCH_V_SEGMENTS, BENCH_V_STRANDS,
               0.0f, BENCH_V_POINTS, BENCH_V_LENGTH);
    printf("scene V: %d guides, %d strands, %d points each, %.2f m of hair; "
           "Vh: the head's sphere alone, V: the head on a %d-proxy body\n",
           v.info.guide_count, v.info.strand_count, v.info.points_per_strand,
           (double)BENCH_V_LENGTH, BENCH_BODY);
    for (body = 0; body < 2; ++body) {
        v.name = body ? "V" : "Vh";
        v.ncol = body ? 1 + BENCH_BODY : 1;
        check("reset", hf_fur_reset(v.fur));
        for (th = 1; th <= MAX_THREADS; ++th)
            bench_scene(&v, frames, th, NULL);
    }
    printf("  colliders on V: median ms of the ropes and of the GPU path's "
           "frame\n");
    g_sc = &v;
    stage_jobs(&v, jobs);
    for (c = 0; c < V_ROWS; ++c) {
        v.ncol = v_counts[c];
        check("reset", hf_fur_reset(v.fur));
        for (th = 1; th <= MAX_THREADS; ++th) {
            figure fr, ff;
            g_threads = th;
            for (f = -60; f < frames; ++f) {
                double t0, t1, t2;
                scene_pose(&v, v.frame++);
                t0 = now_ms();
                run_job(&jobs[ST_ROOTS]);
                t1 = now_ms();
                run_job(&jobs[ST_ROPES]);
                t2 = now_ms();
                run_job(&jobs[ST_LODG]);
                run_job(&jobs[ST_IPOINTS]);
                if (f < 0) continue;
                tr[f] = t2 - t1;
                tf[f] = now_ms() - t0;
            }
            fr = stats(tr, frames);
            ff = stats(tf, frames);
            g_v_frame[c][th] = ff.med;
            printf("    %2d colliders %dT: ropes %7.3f (min %7.3f)  frame "
                   "%7.3f (min %7.3f)\n",
                   v_counts[c], th, fr.med, fr.min, ff.med, ff.min);
            fprintf(stderr, "bench stage=colliders scene=V colliders=%d "
                            "threads=%d ropes=%.4f frame_points=%.4f\n",
                    v_counts[c], th, fr.med, ff.med);
        }
    }
    g_v_ran = 1;
    scene_free(&v);
    free(tr);
    free(tf);
}

/* Hair-hair interaction on scene V (the head on its body): the same fur
   with a grid of BENCH_GRID^3 nodes. grid: hf_fur_build_grid over its
   layers; ropes_grid: hf_fur_simulate with the grid's push (its volume
   and friction at their defaults); against V's ropes without a grid, the
   difference is what the interaction adds to the ropes. Machine line:
     bench stage=hair_grid scene=V threads=T grid=.. ropes_grid=..
           ropes=.. cost=..
   g_grid_cost: grid + the ropes' extra, one thread. */
#define BENCH_GRID 32
static double g_grid_cost = -1.0;

/* Strands that keep their lengths (hf_fur_desc.keep_length) on scene V's
   hair: hf_fur_interpolate of every strand, one thread, the fur built
   with and without it, both swinging on the head's sphere. Machine line:
     bench stage=keep_length scene=V threads=1 ms=.. plain_ms=.. */
static void bench_keep_length(int frames)
{
    static scene v[2];
    job jr, js, ji;
    double *t = (double *)malloc(sizeof(double) * 2u * (size_t)frames);
    figure fk[2];
    int k, f;
    memset(&jr, 0, sizeof jr);
    memset(&js, 0, sizeof js);
    memset(&ji, 0, sizeof ji);
    g_threads = 1;
    for (k = 0; k < 2; ++k) {
        g_keep_length = k;
        scene_init(&v[k], "V", BENCH_V_RINGS, BENCH_V_SEGMENTS,
                   BENCH_V_STRANDS, 0.0f, BENCH_V_POINTS, BENCH_V_LENGTH);
        v[k].ncol = 1;
        g_sc = &v[k];
        jr.fn = j_roots;
        jr.total = js.total = v[k].info.guide_count;
        js.fn = j_ropes;
        ji.fn = j_interp;
        ji.total = v[k].info.strand_count;
        for (f = -10; f < frames; ++f) {
            double t0;
            scene_pose(&v[k], v[k].frame++);
            run_job(&jr);
            run_job(&js);
            t0 = now_ms();
            run_job(&ji);
            if (f >= 0) t[(size_t)k * (size_t)frames + (size_t)f] = now_ms() - t0;
        }
        fk[k] = stats(t + (size_t)k * (size_t)frames, frames);
    }
    g_keep_length = 0;
    printf("strands that keep their lengths on V (%d strands of %d points), "
           "1T: %.3f ms, %.3f without (%.2f ns a point more)\n",
           v[1].info.strand_count, v[1].info.points_per_strand, fk[1].med,
           fk[0].med,
           (fk[1].med - fk[0].med) * 1e6 /
               ((double)v[1].info.strand_count * v[1].info.points_per_strand));
    fprintf(stderr, "bench stage=keep_length scene=V threads=1 ms=%.4f "
                    "plain_ms=%.4f\n", fk[1].med, fk[0].med);
    for (k = 0; k < 2; ++k) scene_free(&v[k]);
    free(t);
}

static void bench_hair_grid(int frames)
{
    static scene v[2];
    job jr, jg, js;
    double *t[3];
    int th, f, k;
    memset(&jr, 0, sizeof jr);
    memset(&jg, 0, sizeof jg);
    memset(&js, 0, sizeof js);
    for (k = 0; k < 3; ++k)
        t[k] = (double *)malloc(sizeof(double) * (size_t)frames);
    for (k = 0; k < 2; ++k) {
        g_grid_resolution = k ? BENCH_GRID : 0;
        scene_init(&v[k], k ? "Vg" : "V", BENCH_V_RINGS, BENCH_V_SEGMENTS,
                   BENCH_V_STRANDS, 0.0f, BENCH_V_POINTS, BENCH_V_LENGTH);
        v[k].ncol = 1 + BENCH_BODY;
    }
    g_grid_resolution = 0;
    printf("hair-hair interaction on V (%d guides of %d points, the body's "
           "colliders): a grid of %d^3 nodes, median ms\n",
           v[1].info.guide_count, v[1].info.points_per_strand, BENCH_GRID);
    for (th = 1; th <= MAX_THREADS; ++th) {
        figure fg, fs, f0;
        g_threads = th;
        for (k = 0; k < 2; ++k) {
            g_sc = &v[k];
            jr.fn = j_roots;
            jr.total = v[k].info.guide_count;
            jg.fn = j_grid;
            jg.total = v[k].info.grid_resolution;
            js.fn = j_ropes;
            js.total = v[k].info.guide_count;
            js.grain = BENCH_ROPE_GRAIN;
            check("reset", hf_fur_reset(v[k].fur));
            for (f = -60; f < frames; ++f) {
                double t0, t1, t2;
                scene_pose(&v[k], v[k].frame++);
                run_job(&jr);
                t0 = now_ms();
                if (k) run_job(&jg);
                t1 = now_ms();
                run_job(&js);
                t2 = now_ms();
                if (f < 0) continue;
                if (k) {
                    t[0][f] = t1 - t0;
                    t[1][f] = t2 - t1;
                } else {
                    t[2][f] = t2 - t1;
                }
            }
        }
        fg = stats(t[0], frames);
        fs = stats(t[1], frames);
        f0 = stats(t[2], frames);
        printf("  %dT: grid %7.3f  ropes with it %7.3f  ropes without %7.3f"
               "  hair-hair cost %7.3f\n", th, fg.med, fs.med, f0.med,
               fg.med + fs.med - f0.med);
        fprintf(stderr, "bench stage=hair_grid scene=V threads=%d grid=%.4f "
                        "ropes_grid=%.4f ropes=%.4f cost=%.4f\n",
                th, fg.med, fs.med, f0.med, fg.med + fs.med - f0.med);
        if (th == 1) g_grid_cost = fg.med + fs.med - f0.med;
    }
    for (k = 0; k < 2; ++k) scene_free(&v[k]);
    for (k = 0; k < 3; ++k) free(t[k]);
}

/* LOD guides interpolated instead of simulated: a coarse head whose
   tessellation adds guides (scenes S, M and L are fine enough that it adds
   none), drawn at LOD 0.25, below the default simulate threshold of 0.5. */
static void bench_lod_guides(scene *s, int frames)
{
    job jr, jg, jl;
    double *t = (double *)malloc(sizeof(double) * (size_t)frames);
    int f, th;
    g_sc = s;
    memset(&jr, 0, sizeof jr);
    memset(&jg, 0, sizeof jg);
    memset(&jl, 0, sizeof jl);
    check("lod", hf_fur_set_lod(s->fur, 0.25f));
    hf_fur_get_info(s->fur, &s->info);
    printf("scene %s: %d guides (%d pure, %d LOD guides), %d strands, "
           "LOD 0.25\n", s->name, s->info.guide_count,
           s->info.pure_guide_count, s->info.lod_guide_count,
           s->info.strand_count);
    jr.fn = j_roots;
    jr.total = s->info.guide_count;
    jg.fn = j_ropes;
    jg.total = s->info.guide_count;
    jg.grain = BENCH_ROPE_GRAIN;
    jl.fn = j_lodg;
    jl.total = s->info.lod_guide_count;
    for (th = 1; th <= MAX_THREADS; ++th) {
        double bytes = (double)s->info.lod_guide_count * P * 12.0;
        wlimit lim;
        size_t b = (size_t)bytes;
        float *dst = (float *)mapped_like(b);
        g_threads = th;
        for (f = -10; f < frames; ++f) {
            double t0;
            scene_pose(s, s->frame++);
            run_job(&jr);
            run_job(&jg);
            t0 = now_ms();
            run_job(&jl);
            if (f >= 0) t[f] = now_ms() - t0;
        }
        memset(dst, 1, b);
        lim = write_limit(dst, b, 7);
        report("lod_guides", s->name, th, stats(t, frames), bytes, &lim, -1);
        free(dst);
    }
    free(t);
}

/* How cost grows (--scaling): strands from 1,000 to 1,000,000 on about
   1,000 guides, then guides from about 100 to 100,000 under 100,000
   strands; median ms per stage over a few frames, 1 and 2 threads. One
   machine line per configuration:
     bench stage=scaling vary=strands|guides strands=N guides=G threads=T
           roots=.. ropes=.. strands_ms=.. ribbons=.. points=.. */

static void bench_scaling(int frames)
{
    static const int strands[4] = {1000, 10000, 100000, 1000000};
    /* sphere resolutions for about 100, 1,000, 10,000 and 100,000 guides */
    static const int rings[4] = {7, 26, 80, 250}, segs[4] = {12, 40, 125, 400};
    enum { K = 5 };
    job jobs[K];
    static const char *names[K] = {"roots", "ropes", "strands", "ribbons",
                                   "points"};
    void (*fns[K])(job *, int, int) = {j_roots, j_ropes, j_interp, j_ribbons,
                                       j_points};
    int vary, i, th, k, f;
    double *t = (double *)malloc(sizeof(double) * (size_t)frames * K);
    printf("scaling: median ms per stage, %d frames after 3 warm-up "
           "frames\n", frames);
    for (vary = 0; vary < 2; ++vary)
        for (i = 0; i < 4; ++i) {
            static scene sc;
            memset(&sc, 0, sizeof sc);
            if (vary == 0)
                scene_init(&sc, "scale", 26, 40, strands[i], 0.0f, P, 0.25f);
            else
                scene_init(&sc, "scale", rings[i], segs[i], 100000, 0.0f, P,
                           0.25f);
            g_sc = &sc;
            bench_views(&g_view, &g_view_gpu, &g_out, sc.vbuf, &g_out16,
                        sc.cbuf);
            memset(jobs, 0, sizeof jobs);
            for (k = 0; k < K; ++k) {
                jobs[k].fn = fns[k];
                jobs[k].grain = k == 1 ? BENCH_ROPE_GRAIN : 0;
                jobs[k].total = k < 2 ? sc.info.guide_count
                                      : sc.info.strand_count;
            }
            for (th = 1; th <= MAX_THREADS; ++th) {
                double med[K];
                g_threads = th;
                for (f = -3; f < frames; ++f) {
                    scene_pose(&sc, sc.frame++);
                    for (k = 0; k < K; ++k) {
                        double t0 = now_ms();
                        run_job(&jobs[k]);
                        if (f >= 0) t[k * frames + f] = now_ms() - t0;
                    }
                }
                for (k = 0; k < K; ++k)
                    med[k] = stats(t + k * frames, frames).med;
                printf("  %-7s strands %7d guides %6d %dT:", vary ? "guides"
                       : "strands", sc.info.strand_count,
                       sc.info.guide_count, th);
                for (k = 0; k < K; ++k) printf("  %s %8.3f", names[k], med[k]);
                printf("\n");
                fprintf(stderr, "bench stage=scaling vary=%s strands=%d "
                        "guides=%d threads=%d roots=%.4f ropes=%.4f "
                        "strands_ms=%.4f ribbons=%.4f points=%.4f\n",
                        vary ? "guides" : "strands", sc.info.strand_count,
                        sc.info.guide_count, th, med[0], med[1], med[2],
                        med[3], med[4]);
            }
            scene_free(&sc);
        }
    free(t);
}

static void bench_lut(int reps)
{
    hf_lut_params p;
    float *m = (float *)malloc(4u * 256u * 256u * sizeof(float));
    float *n = (float *)malloc(4u * 256u * 256u * sizeof(float));
    double *t = (double *)malloc(sizeof(double) * (size_t)reps);
    int r;
    hf_lut_params_init(&p);
    p.size = 256;
    for (r = 0; r < reps; ++r) {
        double t0 = now_ms();
        check("lut m", hf_lut_bake_m(&p, 0, 256, m));
        check("lut n", hf_lut_bake_n(&p, 0, 256, n));
        t[r] = now_ms() - t0;
    }
    report("lut_256", "-", 1, stats(t, reps), 0, NULL, -1);
    free(m);
    free(n);
    free(t);
}

static void bench_bandwidth(void)
{
    /* the write limit for scene L's ribbons, each way, printed on its own */
    size_t bytes = (size_t)100000 * P * 2u * 36u;
    float *dst = (float *)mapped_like(bytes);
    double sc, zs;
    wlimit l;
    memset(dst, 1, bytes);
    sc = store_gbps(dst, bytes, 7);
    zs = memset_gbps(dst, bytes, 7, 1);
    l = write_limit(dst, bytes, 7);
    printf("  write limit (%.0f MiB): vector stores %.2f GB/s, streaming "
           "stores %.2f, memset %.2f (the limit: %.2f); for reference a "
           "scalar store loop %.2f, memset of zeros %.2f (no stage writes "
           "zero lines)\n",
           bytes / 1048576.0, l.vector, l.stream, l.memset, l.best, sc, zs);
    fprintf(stderr, "bench stage=write_limit method=vector gbps=%.3f\n",
            l.vector);
    fprintf(stderr, "bench stage=write_limit method=stream gbps=%.3f\n",
            l.stream);
    fprintf(stderr, "bench stage=write_limit method=memset gbps=%.3f\n",
            l.memset);
    fprintf(stderr, "bench stage=write_limit method=scalar gbps=%.3f\n", sc);
    fprintf(stderr, "bench stage=write_limit method=zeros gbps=%.3f\n", zs);
    free(dst);
}

/* One target: its line and machine line (value against goal; below:
   the value must be under the goal, else at least it) */
static void target_line(const char *name, const char *what, double value,
                        double goal, int below)
{
    const int met = below ? value < goal : value >= goal;
    printf("  %-40s %6.3g %2s %-5g %s\n", what, value, below ? "<" : ">=",
           goal, met ? "met" : "NOT met");
    fprintf(stderr, "bench target=%s value=%.4f goal=%g met=%d\n", name, value,
            goal, met);
}

/* The targets of docs/performance.md ("Targets, and where they stand"),
   read from this run's figures (those of the scenes it ran; frame_l:
   L's frame ms by thread count, NULL when L did not run) */
static void print_targets(const double *frame_l)
{
    static const char *l_rows[4] = {"ribbons", "strands", "points",
                                    "interp_points"};
    const kept *k;
    int i;
    printf("targets (one thread unless named; this run; every run in "
           "docs/performance-log.md):\n");
    for (i = 0; i < 4; ++i)
        if ((k = find_kept(l_rows[i], "L", 1)) != NULL) {
            char what[64], name[32];
            snprintf(what, sizeof what, "%s on L (of the write limit)",
                     l_rows[i]);
            snprintf(name, sizeof name, "%s_L_ratio", l_rows[i]);
            target_line(name, what, k->ratio, 0.5, 0);
        }
    if ((k = find_kept("frame", "M", 1)) != NULL)
        target_line("frame_M_ms", "frame of M, CPU ribbons (ms)", k->ms, 4.17,
                    1);
    if ((k = find_kept("frame_points", "M", 1)) != NULL)
        target_line("frame_points_M_ms", "frame of M, GPU points (ms)", k->ms,
                    1.0, 1);
    if (frame_l)
        target_line("frame_L_2T_speedup", "frame of L, 2 threads (speed-up)",
                    frame_l[1] / frame_l[2], 1.8, 0);
    if ((k = find_kept("lut_256", "-", 1)) != NULL)
        target_line("lut_256_ms", "256 x 256 LUT bake (ms)", k->ms, 50.0, 1);
    if (g_v_ran) {
        /* rows 1 (the head's sphere), 4 (its body), 5 (64) */
        target_line("frame_points_V_body_ratio",
                    "V's frame, body / head alone (GPU points)",
                    g_v_frame[4][1] / g_v_frame[1][1], 1.3, 1);
        target_line("frame_points_V_64_ratio",
                    "V's frame, 64 colliders / head alone",
                    g_v_frame[5][1] / g_v_frame[1][1], 1.4, 1);
        target_line("frame_points_V_body_2T_ms",
                    "V's frame with the body, 2 threads (ms)",
                    g_v_frame[4][2], 1.0, 1);
    }
    if (g_grid_cost >= 0.0)
        target_line("hair_grid_V_ms", "hair-hair grid on V, 1 thread (ms)",
                    g_grid_cost, 0.25, 1);
    if (g_max_allocs >= 0)
        target_line("allocs_per_frame", "allocations in any frame",
                    (double)g_max_allocs, 1.0, 1);
    printf("  ropes against Bullet and 0.1.0: make bench-peers\n");
}

int main(int argc, char **argv)
{
    int frames = 30, i, th, scaling = 0;
    const char *only = NULL;
    static scene sc[3];
    pthread_t workers[MAX_THREADS];
    double frame_ms[3][MAX_THREADS + 1];
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--scaling")) scaling = 1;
        else if (i + 1 < argc && !strcmp(argv[i], "--frames"))
            frames = atoi(argv[++i]);
        else if (i + 1 < argc && !strcmp(argv[i], "--scene") &&
                 (!strcmp(argv[i + 1], "S") || !strcmp(argv[i + 1], "M") ||
                  !strcmp(argv[i + 1], "L") || !strcmp(argv[i + 1], "Mc") ||
                  !strcmp(argv[i + 1], "V") || !strcmp(argv[i + 1], "Vg")))
            only = argv[++i];
        else {
            int help = !strcmp(argv[i], "--help") || !strcmp(argv[i], "-h");
            if (!help)
                fprintf(stderr, "bench: %s %s: %s\n", argv[i],
                        i + 1 < argc ? argv[i + 1] : "",
                        i + 1 < argc ? "unknown option or value"
                                     : "unknown option or missing value");
            fprintf(help ? stdout : stderr,
                    "usage: bench [--frames N] [--scene S|M|L|Mc|V|Vg] "
                    "[--scaling]\n"
                    "  --frames N   frames measured after a 10-frame "
                    "warm-up (default 30, at least 3)\n"
                    "  --scene X    only scene X (default: all of them, in "
                    "this order):\n"
                    "               S, M, L: the built-in head, 3,670 to "
                    "100,000 strands;\n"
                    "               Mc: LOD guides; V: a character, its head "
                    "on a 24-proxy\n"
                    "               body, the cost of colliders and hair-hair "
                    "interaction;\n"
                    "               Vg: V's hair-hair interaction alone\n"
                    "  --scaling    how cost grows with strands and guides "
                    "instead\n"
                    "The table goes to stdout, one machine line per figure "
                    "to stderr;\nit ends with the targets of "
                    "docs/performance.md, met or NOT met, from this run.\n");
            return help ? 0 : 2;
        }
    }
    if (frames < 3) frames = 3;
    setvbuf(stdout, NULL, _IOLBF, 0);
    printf("hairfur.h %s bench: %d frames after a 10-frame warm-up, %d "
           "points per strand; SIMD level %s\n",
           hf_version_string(), frames, P,
           level_name[hf_simd_resolve(HF_SIMD_AUTO)]);
    for (i = 1; i < MAX_THREADS; ++i)
        pthread_create(&workers[i], NULL, worker, (void *)(size_t)i);

    if (scaling) {
        bench_scaling(frames < 30 ? frames : 5);
        g_quit = 1;
        start_stage();
        for (i = 1; i < MAX_THREADS; ++i) pthread_join(workers[i], NULL);
        return 0;
    }
    bench_bandwidth();
    /* sphere resolutions chosen for about 360, 3,700 and 1,000 guides */
    scene_init(&sc[0], "S", 16, 24, 3670, 0.0f, P, 0.25f); /* 362 guides */
    scene_init(&sc[1], "M", 52, 72, 36700, 0.0f, P, 0.25f); /* 3,674 */
    scene_init(&sc[2], "L", BENCH_L_RINGS, BENCH_L_SEGMENTS, BENCH_L_STRANDS,
               0.0f, P, 0.25f); /* 1,002 guides */
    for (i = 0; i < 3; ++i) {
        if (only && strcmp(only, sc[i].name)) continue;
        printf("scene %s: %d guides, %d strands, %d points each\n",
               sc[i].name, sc[i].info.guide_count, sc[i].info.strand_count,
               sc[i].info.points_per_strand);
        for (th = 1; th <= MAX_THREADS; ++th)
            bench_scene(&sc[i], frames, th, &frame_ms[i][th]);
        printf("  frame speed-up with 2 threads: %.2f\n",
               frame_ms[i][1] / frame_ms[i][2]);
        if (i > 0) bench_levels(&sc[i], frames); /* M and L */
    }
    if (!only || !strcmp(only, "Mc")) {
        static scene lodsc;
        scene_init(&lodsc, "Mc", 10, 16, 36700, 80000.0f, P, 0.25f);
        bench_lod_guides(&lodsc, frames);
        hf_fur_destroy(lodsc.fur);
    }
    if (!only || !strcmp(only, "V")) bench_character(frames);
    if (!only || !strcmp(only, "V") || !strcmp(only, "Vg"))
        bench_hair_grid(frames);
    if (!only || !strcmp(only, "V")) bench_keep_length(frames);
    bench_lut(9);
    print_targets(!only || !strcmp(only, "L") ? frame_ms[2] : NULL);

    g_quit = 1;
    start_stage();
    for (i = 1; i < MAX_THREADS; ++i) pthread_join(workers[i], NULL);
    for (i = 0; i < 3; ++i) hf_fur_destroy(sc[i].fur);
    free(g_evict);
    return 0;
}
