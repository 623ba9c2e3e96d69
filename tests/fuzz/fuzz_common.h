/* fuzz_common.h - shared helpers of the hairfur.h fuzz targets.

   Each target (fuzz_grow.c, fuzz_ropes.c, fuzz_ribbons.c, fuzz_lut.c,
   fuzz_fur.c) includes this file once, after hairfur.h with
   HAIRFUR_IMPLEMENTATION. Build lines are in the Makefile.

   Bytes to input, as meshoptimizer's simplifyfuzz does: byte 0 seeds a
   PCG32 stream that fills in whatever the input runs out of, so short
   inputs still make full-sized, valid-shaped calls; counts are bounded to
   keep every run fast; indices are taken modulo the vertex count (with an
   occasional out-of-range one); floats come from a table of special values
   (0, -0, NaN, +-inf, FLT_MAX, denormals, ...), from a small-range decoder,
   or straight from four bytes, so NaN, inf and huge values all appear.

   Contract checks call abort() (via FZ_REQUIRE) so that libFuzzer records
   the input as a crash and prints which check failed. */
#ifndef FUZZ_COMMON_H
#define FUZZ_COMMON_H

#include <float.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* every helper static, and quiet where a target does not use it */
#if defined(__GNUC__) || defined(__clang__)
#define FZ_STATIC static __attribute__((unused))
#else
#define FZ_STATIC static
#endif

#define FZ_REQUIRE(cond)                                                       \
    do {                                                                       \
        if (!(cond)) {                                                         \
            fprintf(stderr, "%s:%d: contract violated: %s\n", __FILE__,        \
                    __LINE__, #cond);                                          \
            abort();                                                           \
        }                                                                      \
    } while (0)

/* ---- the byte reader ---------------------------------------------------- */

typedef struct fz_reader {
    const uint8_t *data;
    size_t size, pos;
    hf_rng rng; /* seeded from byte 0: fills in after the input ends */
    int p_special, p_raw; /* out of 256: special values, raw float bits */
} fz_reader;

FZ_STATIC void fz_init(fz_reader *r, const uint8_t *data, size_t size)
{
    r->data = data;
    r->size = size;
    r->pos = size > 0 ? 1 : 0;
    hf_rng_seed(&r->rng, size > 0 ? data[0] : 0, 0x9e3779b9u);
    /* byte 0 also picks how dirty the floats are: half the inputs clean
       enough to get past validation, the rest with NaN, inf and huge */
    switch (size > 0 ? data[0] & 3 : 0) {
    case 0: case 1: r->p_special = 1; r->p_raw = 0; break;
    case 2: r->p_special = 6; r->p_raw = 3; break;
    default: r->p_special = 24; r->p_raw = 12; break;
    }
}

FZ_STATIC uint8_t fz_u8(fz_reader *r)
{
    if (r->pos < r->size) return r->data[r->pos++];
    return (uint8_t)(hf_rng_u32(&r->rng) >> 24);
}

FZ_STATIC uint32_t fz_u32(fz_reader *r)
{
    uint32_t v = 0;
    int k;
    for (k = 0; k < 4; ++k) v |= (uint32_t)fz_u8(r) << (8 * k);
    return v;
}

/* an int in [lo, hi] */
FZ_STATIC int fz_int(fz_reader *r, int lo, int hi)
{
    uint32_t span = (uint32_t)hi - (uint32_t)lo + 1u; /* 0: all of int */
    uint32_t v = (span != 0u && span <= 256u) ? fz_u8(r) : fz_u32(r);
    uint32_t u = (uint32_t)lo + (span ? v % span : v);
    return (int)(u <= 0x7fffffffu ? (int)u : -(int)(~u) - 1);
}

/* true with probability about n / 256 */
FZ_STATIC int fz_chance(fz_reader *r, int n) { return fz_u8(r) < n; }

FZ_STATIC float fz_bits_float(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* Special values that break arithmetic. */
FZ_STATIC float fz_special(int k)
{
    switch (k % 16) {
    case 0: return 0.0f;
    case 1: return -0.0f;
    case 2: return fz_bits_float(0x7fc00000u); /* NaN */
    case 3: return fz_bits_float(0x7f800000u); /* +inf */
    case 4: return fz_bits_float(0xff800000u); /* -inf */
    case 5: return FLT_MAX;
    case 6: return -FLT_MAX;
    case 7: return FLT_MIN;
    case 8: return fz_bits_float(0x00000001u); /* smallest denormal */
    case 9: return 1e30f;
    case 10: return -1e30f;
    case 11: return 1e-30f;
    case 12: return 1.0f;
    case 13: return -1.0f;
    case 14: return 1e6f;
    default: return fz_bits_float(0xffc00001u); /* negative NaN payload */
    }
}

/* Any float: mostly "reasonable" values in [-scale, scale] so the code
   gets past validation, sometimes special values, sometimes raw bits. */
FZ_STATIC float fz_float(fz_reader *r, float scale)
{
    int sel = fz_u8(r);
    if (sel < r->p_special) return fz_special(fz_u8(r));
    if (sel < r->p_special + r->p_raw) return fz_bits_float(fz_u32(r));
    {
        int16_t v = (int16_t)((uint16_t)fz_u8(r) | ((uint16_t)fz_u8(r) << 8));
        return (float)v / 32767.0f * scale;
    }
}

/* A float that is finite and in [lo, hi] nearly always (for fields that
   would otherwise refuse almost every input), with the rare special. */
FZ_STATIC float fz_float_in(fz_reader *r, float lo, float hi)
{
    int sel = fz_u8(r);
    if (sel < r->p_special / 4 + (r->p_special > 1)) return fz_special(fz_u8(r));
    return lo + (hi - lo) * ((float)fz_u8(r) / 255.0f);
}

/* ---- checks ------------------------------------------------------------- */

FZ_STATIC int fz_finite(float x)
{
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    return (u & 0x7f800000u) != 0x7f800000u;
}

FZ_STATIC int fz_all_finite(const float *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i)
        if (!fz_finite(p[i])) return 0;
    return 1;
}

/* Every result a function may return: HF_OK or one of the table's. */
FZ_STATIC int fz_known_result(hf_result r)
{
    switch (r) {
#define FZ_CASE(name, value, message) case name:
        HF_RESULT_TABLE(FZ_CASE)
#undef FZ_CASE
        return 1;
    default:
        return 0;
    }
}

#define FZ_SENTINEL 0xA5u

/* A buffer filled with the sentinel, with a copy to compare against. */
FZ_STATIC void *fz_sentinel_alloc(size_t bytes)
{
    void *p = malloc(bytes ? bytes : 1);
    if (!p) abort();
    memset(p, FZ_SENTINEL, bytes ? bytes : 1);
    return p;
}

FZ_STATIC int fz_untouched(const void *p, size_t bytes)
{
    const uint8_t *b = (const uint8_t *)p;
    size_t i;
    for (i = 0; i < bytes; ++i)
        if (b[i] != FZ_SENTINEL) return 0;
    return 1;
}

/* ---- a counting allocator that can fail --------------------------------- */

typedef struct fz_counter {
    long attempts, allocs, frees, live;
    long fail_at;     /* fail the attempt with this number; -1 never */
    size_t max_bytes; /* refuse any single allocation larger than this */
} fz_counter;

FZ_STATIC void *fz_alloc(size_t size, void *user)
{
    fz_counter *c = (fz_counter *)user;
    void *p;
    if (c->fail_at >= 0 && c->attempts++ == c->fail_at) return NULL;
    if (size > c->max_bytes) return NULL;
    p = malloc(size ? size : 1);
    if (p) {
        ++c->allocs;
        ++c->live;
    }
    return p;
}
FZ_STATIC void *fz_realloc(void *p, size_t size, void *user)
{
    fz_counter *c = (fz_counter *)user;
    void *q;
    if (!p && c->fail_at >= 0 && c->attempts++ == c->fail_at) return NULL;
    if (size > c->max_bytes) return NULL;
    q = realloc(p, size ? size : 1);
    if (q && !p) {
        ++c->allocs;
        ++c->live;
    }
    return q;
}
FZ_STATIC void fz_free(void *p, void *user)
{
    fz_counter *c = (fz_counter *)user;
    if (!p) return;
    ++c->frees;
    --c->live;
    free(p);
}
FZ_STATIC hf_allocator fz_counting(fz_counter *c, long fail_at, size_t max_bytes)
{
    hf_allocator a;
    c->attempts = c->allocs = c->frees = c->live = 0;
    c->fail_at = fail_at;
    c->max_bytes = max_bytes;
    a.alloc = fz_alloc;
    a.realloc = fz_realloc;
    a.free = fz_free;
    a.user = c;
    return a;
}

/* (first, count) inside [0, n), sometimes out of it or overflowing */
FZ_STATIC void fz_range(fz_reader *r, int n, int *first, int *count)
{
    if (fz_chance(r, r->p_special)) {
        static const int bad[6] = {-1, 0x7fffffff, -0x7fffffff - 1, 1, 2,
                                   0x7ffffff0};
        *first = bad[fz_u8(r) % 6];
        *count = bad[fz_u8(r) % 6];
        return;
    }
    *first = fz_int(r, 0, n);
    *count = fz_int(r, 0, n - *first);
}

/* For functions that take no total (hf_ribbons, hf_interpolate): the
   caller sizes the arrays, so only ranges that are bad as ints (negative,
   or first + count past INT_MAX) can be refused. */
FZ_STATIC void fz_range_untotalled(fz_reader *r, int n, int *first, int *count)
{
    if (fz_chance(r, r->p_special)) {
        switch (fz_u8(r) % 4) {
        case 0: *first = -1; *count = 1; break;
        case 1: *first = 0; *count = -1; break;
        case 2: *first = 1; *count = 0x7fffffff; break;
        default: *first = -0x7fffffff - 1; *count = 0; break;
        }
        return;
    }
    *first = fz_int(r, 0, n);
    *count = fz_int(r, 0, n - *first);
}

/* ---- meshes and maps from bytes ----------------------------------------- */

/* Storage of a fuzz-built mesh: interleaved x y z nx ny nz u v (32 bytes)
   or separate packed arrays, chosen by the input. */
typedef struct fz_mesh {
    float *verts; /* 8 floats per vertex */
    uint32_t *idx;
    hf_mesh mesh;
} fz_mesh;

FZ_STATIC void fz_make_mesh(fz_reader *r, fz_mesh *m, int max_v, int max_t,
                         float scale)
{
    int nv = fz_int(r, 1, max_v), nt = fz_int(r, 1, max_t), i;
    int flags = fz_u8(r);
    m->verts = (float *)malloc(sizeof(float) * 8u * (size_t)nv);
    m->idx = (uint32_t *)malloc(sizeof(uint32_t) * 3u * (size_t)nt);
    if (!m->verts || !m->idx) abort();
    for (i = 0; i < nv; ++i) {
        float *v = m->verts + 8 * i;
        int k;
        for (k = 0; k < 3; ++k) v[k] = fz_float(r, scale);
        for (k = 3; k < 6; ++k) v[k] = fz_float(r, 1.0f);
        v[6] = fz_float(r, 2.0f);
        v[7] = fz_float(r, 2.0f);
    }
    for (i = 0; i < 3 * nt; ++i) {
        uint32_t x = fz_u32(r);
        /* modulo the vertex count; rarely a raw out-of-range index */
        m->idx[i] = fz_chance(r, r->p_raw / 3) ? x : x % (uint32_t)nv;
    }
    memset(&m->mesh, 0, sizeof m->mesh);
    m->mesh.positions = m->verts;
    m->mesh.position_stride = 32;
    m->mesh.normals = (flags & 1) ? m->verts + 3 : NULL;
    m->mesh.normal_stride = 32;
    m->mesh.uvs = (flags & 2) ? NULL : m->verts + 6;
    m->mesh.uv_stride = 32;
    m->mesh.vertex_count = nv;
    m->mesh.indices = m->idx;
    m->mesh.triangle_count = nt;
    if ((flags & 0xF0) == 0xF0) {
        /* bad shapes: a stride, a count, a pointer */
        switch (flags & 0x0C) {
        case 0x00:
            m->mesh.position_stride = fz_int(r, -16, 32);
#ifdef FZ_SKIP_KNOWN
            /* known bug: a stride that is not a multiple of 4 is accepted
               and read with misaligned float loads (UB) */
            if (m->mesh.position_stride > 11) m->mesh.position_stride &= ~3;
#endif
            break;
        case 0x04: m->mesh.uv_stride = fz_int(r, -8, 7); break;
        case 0x08: m->mesh.triangle_count = fz_int(r, -2, 0); break;
        default: m->mesh.vertex_count = fz_int(r, -2, 0); break;
        }
    }
}

FZ_STATIC void fz_free_mesh(fz_mesh *m)
{
    free(m->verts);
    free(m->idx);
}

typedef struct fz_map {
    void *data;
    hf_map map;
} fz_map;

/* A map of up to max_w x max_h texels; mostly valid. */
FZ_STATIC void fz_make_map(fz_reader *r, fz_map *m, int max_w, int max_h,
                        int min_channels)
{
    int w = fz_int(r, 1, max_w), h = fz_int(r, 1, max_h);
    int ch = fz_int(r, min_channels, 4), f32 = fz_chance(r, 96);
    int pad = fz_chance(r, 64) ? fz_int(r, 0, 7) : 0;
    int es = f32 ? 4 : 1, row = w * ch * es + (f32 ? 4 * (pad / 4) : pad);
    size_t bytes = (size_t)row * (size_t)h, i;
    m->data = malloc(bytes);
    if (!m->data) abort();
    if (f32) {
        float *f = (float *)m->data;
        for (i = 0; i < bytes / 4; ++i) {
            f[i] = fz_float(r, 2.0f);
#ifdef FZ_SKIP_KNOWN
            /* known bug (regressions/grow-map-f32-huge-*): finite values
               near FLT_MAX overflow in the bilinear lerp, the density
               mean and the blur sum */
            if (fz_finite(f[i]) && (f[i] > 1e30f || f[i] < -1e30f))
                f[i] = 1e30f;
#endif
        }
    } else {
        uint8_t *b = (uint8_t *)m->data;
        for (i = 0; i < bytes; ++i) b[i] = fz_u8(r);
    }
    memset(&m->map, 0, sizeof m->map);
    m->map.data = m->data;
    m->map.width = w;
    m->map.height = h;
    m->map.channels = ch;
    m->map.format = f32 ? HF_MAP_F32 : HF_MAP_U8;
    m->map.row_stride = pad ? row : 0;
    m->map.wrap = fz_u8(r) & 1;
    if (fz_chance(r, r->p_raw)) {
        /* a bad field: every one must give a result code */
        /* (never one that makes a valid map read past our buffer) */
        static const int bad_ch[4] = {-1, 0, 5, 6}, bad_fmt[3] = {-1, 2, 3};
        switch (fz_u8(r) % 6) {
        case 0: m->map.channels = bad_ch[fz_u8(r) % 4]; break;
        case 1: m->map.format = bad_fmt[fz_u8(r) % 3]; break;
        case 2: m->map.wrap = fz_int(r, -1, 3); break;
        case 3:
            m->map.row_stride = fz_int(r, -4, row);
#ifdef FZ_SKIP_KNOWN
            /* known bug (regressions/grow-map-f32-odd-row-stride-*): a
               float map's row stride that is not a multiple of 4 is
               accepted and read with misaligned float loads */
            if (f32) m->map.row_stride &= ~3;
#endif
            break;
        case 4: m->map.data = NULL; break;
        default: m->map.width = fz_int(r, -1, w); break;
        }
    }
}

#endif /* FUZZ_COMMON_H */
