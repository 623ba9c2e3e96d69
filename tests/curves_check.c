/* curves_check.c - the examples' curve files (examples/curves.h): .hair
   written and read back for several flag combinations, .hair and .tfx built
   byte by byte here (from the layouts in docs/hair.md), cut short at every
   length and given lying headers, OBJ polylines written and read back, and
   OBJ faces next to lines.

   Build and run: make curves-check (gcc, ASan + UBSan, with assimp; a
   32-bit build without the OBJ part too, where gcc -m32 works), part of
   make test. Usage: curves_check [DIR] (scratch files go to DIR, by
   default the program's own directory). Prints one line per failed check and ends with "N passed, N
   failed"; exits non-zero when anything failed. */
#define CURVES_IMPLEMENTATION
#include "curves.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ==== harness ============================================================= */

static int t_passed, t_failed, t_current_failed;
static const char *t_current;
static char t_dir[1024] = ".";

#define CHECK(cond)                                                            \
    do {                                                                       \
        if (!(cond)) {                                                         \
            printf("%s:%d: %s: CHECK(%s) failed\n", __FILE__, __LINE__,        \
                   t_current, #cond);                                          \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

/* a reader's result is 0 with a message naming the problem (containing
   what) and empty curves */
#define CHECK_REFUSED(ok, c, err, what)                                        \
    do {                                                                       \
        if ((ok) != 0 || (c).count != 0 || (c).points || (c).xyz ||            \
            (c).rgb || (c).thickness || (c).transparency || !(err)[0] ||       \
            !strstr((err), (what))) {                                          \
            printf("%s:%d: %s: expected a refusal naming \"%s\": ok %d, "      \
                   "count %d, message \"%s\"\n", __FILE__, __LINE__,           \
                   t_current, (what), (ok), (c).count, (err));                 \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

#define CHECK_READ(ok, err)                                                    \
    do {                                                                       \
        if (!(ok)) {                                                           \
            printf("%s:%d: %s: read failed: %s\n", __FILE__, __LINE__,         \
                   t_current, (err));                                          \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

static void run(void (*fn)(void), const char *name)
{
    t_current = name;
    t_current_failed = 0;
    fn();
    if (t_current_failed) ++t_failed;
    else ++t_passed;
}
#define RUN(fn) run(fn, #fn)

static const char *scratch(const char *name)
{
    static char path[4][2048];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", t_dir, name);
    return path[k];
}

/* ==== helpers ============================================================= */

static uint32_t rng_state = 12345u;
static uint32_t rng_u32(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return rng_state >> 8;
}
/* in [-1, 1), with a few exactly representable oddities */
static float rng_f(void)
{
    uint32_t r = rng_u32();
    if (r % 37 == 0) return -0.0f;
    if (r % 41 == 0) return 1.0e-38f; /* near the smallest normal */
    return (float)(r & 0xffffu) / 32768.0f - 1.0f;
}

/* A little-endian byte buffer that grows. */
typedef struct buf {
    unsigned char *d;
    size_t n, cap;
} buf;

static void put(buf *b, const void *p, size_t k)
{
    if (b->n + k > b->cap) {
        b->cap = (b->n + k) * 2 + 64;
        b->d = (unsigned char *)realloc(b->d, b->cap);
        if (!b->d) abort();
    }
    memcpy(b->d + b->n, p, k);
    b->n += k;
}
static void put_u32(buf *b, uint32_t u)
{
    unsigned char q[4];
    q[0] = (unsigned char)u;
    q[1] = (unsigned char)(u >> 8);
    q[2] = (unsigned char)(u >> 16);
    q[3] = (unsigned char)(u >> 24);
    put(b, q, 4);
}
static void put_u16(buf *b, unsigned u)
{
    unsigned char q[2];
    q[0] = (unsigned char)u;
    q[1] = (unsigned char)(u >> 8);
    put(b, q, 2);
}
static void put_f32(buf *b, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put_u32(b, u);
}
static void set_u32(buf *b, size_t at, uint32_t u)
{
    b->d[at] = (unsigned char)u;
    b->d[at + 1] = (unsigned char)(u >> 8);
    b->d[at + 2] = (unsigned char)(u >> 16);
    b->d[at + 3] = (unsigned char)(u >> 24);
}

static int same_floats(const float *a, const float *b, long n)
{
    return n == 0 || (a && b && memcmp(a, b, sizeof(float) * (size_t)n) == 0);
}

static int write_file(const char *path, const unsigned char *d, size_t n)
{
    FILE *f = fopen(path, "wb");
    int ok;
    if (!f) return 0;
    ok = fwrite(d, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

/* A whole .hair file as the format describes it: header (with these
   defaults), then the arrays flags asks for. segs[i] is strand i's
   segment count; with flags & 1 clear they must all be defseg. */
typedef struct hair_src {
    uint32_t flags, defseg;
    float defthick, deftransp, defrgb[3];
    int strands;
    const unsigned *segs;
    const float *xyz, *thick, *transp, *rgb;
} hair_src;

static void build_hair(buf *b, const hair_src *h)
{
    int i, total = 0;
    char info[88];
    for (i = 0; i < h->strands; ++i) total += (int)h->segs[i] + 1;
    b->n = 0;
    put(b, "HAIR", 4);
    put_u32(b, (uint32_t)h->strands);
    put_u32(b, (uint32_t)total);
    put_u32(b, h->flags);
    put_u32(b, h->defseg);
    put_f32(b, h->defthick);
    put_f32(b, h->deftransp);
    for (i = 0; i < 3; ++i) put_f32(b, h->defrgb[i]);
    memset(info, 0, sizeof info);
    strcpy(info, "curves_check");
    put(b, info, 88);
    if (h->flags & 1)
        for (i = 0; i < h->strands; ++i) put_u16(b, h->segs[i]);
    for (i = 0; i < 3 * total; ++i) put_f32(b, h->xyz[i]);
    if (h->flags & 4)
        for (i = 0; i < total; ++i) put_f32(b, h->thick[i]);
    if (h->flags & 8)
        for (i = 0; i < total; ++i) put_f32(b, h->transp[i]);
    if (h->flags & 16)
        for (i = 0; i < 3 * total; ++i) put_f32(b, h->rgb[i]);
}

/* The source's per-point attribute k (0 thickness, 1 transparency, 2..4
   rgb) as a reader must give it: from the array, else the default. */
static float hair_expect(const hair_src *h, int k, long i)
{
    switch (k) {
    case 0: return (h->flags & 4) ? h->thick[i] : h->defthick;
    case 1: return (h->flags & 8) ? h->transp[i] : h->deftransp;
    default: return (h->flags & 16) ? h->rgb[3 * i + (k - 2)] : h->defrgb[k - 2];
    }
}

/* c read from h: every count, point and attribute exactly */
static int hair_matches(const cv_curves *c, const hair_src *h)
{
    long i, total = 0;
    if (c->count != h->strands || !c->points || !c->xyz || !c->rgb ||
        !c->thickness || !c->transparency)
        return 0;
    for (i = 0; i < h->strands; ++i) {
        if (c->points[i] != (int)h->segs[i] + 1) return 0;
        total += c->points[i];
    }
    if (c->total != total || !same_floats(c->xyz, h->xyz, 3 * total)) return 0;
    for (i = 0; i < total; ++i) {
        float e0 = hair_expect(h, 0, i), e1 = hair_expect(h, 1, i);
        int k;
        if (memcmp(&c->thickness[i], &e0, 4) || memcmp(&c->transparency[i], &e1, 4))
            return 0;
        for (k = 0; k < 3; ++k) {
            float e = hair_expect(h, 2 + k, i);
            if (memcmp(&c->rgb[3 * i + k], &e, 4)) return 0;
        }
    }
    return 1;
}

static int same_curves(const cv_curves *a, const cv_curves *b)
{
    long t = a->total;
    return a->count == b->count && a->total == b->total &&
           memcmp(a->points, b->points, sizeof(int) * (size_t)a->count) == 0 &&
           same_floats(a->xyz, b->xyz, 3 * t) &&
           !a->rgb == !b->rgb && (!a->rgb || same_floats(a->rgb, b->rgb, 3 * t)) &&
           !a->thickness == !b->thickness &&
           (!a->thickness || same_floats(a->thickness, b->thickness, t)) &&
           !a->transparency == !b->transparency &&
           (!a->transparency || same_floats(a->transparency, b->transparency, t));
}

/* Parse data[0 .. n) from a buffer of exactly n bytes, so that ASan sees
   any read past the end. */
static int parse_exact(int (*parse)(const unsigned char *, size_t, cv_curves *,
                                    char *, size_t),
                       const unsigned char *data, size_t n, cv_curves *c,
                       char *err, size_t en)
{
    unsigned char *copy = (unsigned char *)malloc(n ? n : 1);
    int ok;
    if (!copy) abort();
    if (n) memcpy(copy, data, n);
    err[0] = '\0';
    ok = parse(copy, n, c, err, en);
    free(copy);
    return ok;
}

/* A sample source: 5 strands of 2 .. 9 points (or all defseg + 1). */
#define HS_STRANDS 5
static unsigned hs_segs[HS_STRANDS];
static float hs_xyz[3 * 64], hs_thick[64], hs_transp[64], hs_rgb[3 * 64];

static hair_src sample_hair(uint32_t flags)
{
    hair_src h;
    int i;
    memset(&h, 0, sizeof h);
    h.flags = flags;
    h.defseg = 4;
    h.defthick = 0.25f;
    h.deftransp = 0.125f;
    h.defrgb[0] = 0.5f;
    h.defrgb[1] = 0.25f;
    h.defrgb[2] = 0.75f;
    h.strands = HS_STRANDS;
    for (i = 0; i < HS_STRANDS; ++i)
        hs_segs[i] = (flags & 1) ? 1u + (unsigned)(rng_u32() % 8u) : h.defseg;
    for (i = 0; i < 3 * 64; ++i) {
        hs_xyz[i] = rng_f();
        hs_rgb[i] = 0.5f * rng_f() + 0.5f;
    }
    for (i = 0; i < 64; ++i) {
        hs_thick[i] = 0.01f * (rng_f() + 1.0f);
        hs_transp[i] = 0.5f * (rng_f() + 1.0f);
    }
    h.segs = hs_segs;
    h.xyz = hs_xyz;
    h.thick = hs_thick;
    h.transp = hs_transp;
    h.rgb = hs_rgb;
    return h;
}

static const uint32_t hair_flag_sets[] = {2,     3,         3 | 4,      3 | 8,
                                          3 | 16, 3 | 4 | 8 | 16, 2 | 16, 2 | 4 | 8};
#define N_FLAG_SETS (int)(sizeof hair_flag_sets / sizeof hair_flag_sets[0])

/* ==== .hair =============================================================== */

/* Built per the format, parsed, written with cv_write_hair, read back
   from the file: equal, attributes from the arrays or the defaults. */
static void test_hair_round_trip(void)
{
    int s;
    buf b = {NULL, 0, 0};
    for (s = 0; s < N_FLAG_SETS; ++s) {
        hair_src h = sample_hair(hair_flag_sets[s]);
        cv_curves a, r;
        char err[512];
        int ok;
        const char *path = scratch("curves_check_rt.hair");
        build_hair(&b, &h);
        ok = parse_exact(cv_parse_hair, b.d, b.n, &a, err, sizeof err);
        CHECK_READ(ok, err);
        if (!ok) continue;
        if (!hair_matches(&a, &h))
            printf("  (flags %u: the parsed curves differ from the file)\n",
                   (unsigned)h.flags);
        CHECK(hair_matches(&a, &h));
        ok = cv_write_hair(path, &a, "curves_check", err, sizeof err);
        CHECK_READ(ok, err);
        ok = ok && cv_read(path, &r, err, sizeof err);
        CHECK_READ(ok, err);
        if (ok) {
            if (!same_curves(&a, &r))
                printf("  (flags %u: written and read back differs)\n",
                       (unsigned)h.flags);
            CHECK(same_curves(&a, &r));
            CHECK(hair_matches(&r, &h));
            cv_free(&r);
        }
        cv_free(&a);
        remove(path);
    }
    free(b.d);
}

/* Curves made in memory (with and without colours, as grow_fur and
   make_hairstyle write them) written and read back exactly. */
static void test_hair_write_read(void)
{
    int with;
    for (with = 0; with < 4; ++with) {
        cv_curves a, r;
        int i, pts[3] = {2, 7, 65536};
        long t = 2 + 7 + 65536;
        char err[512];
        const char *path = scratch("curves_check_wr.hair");
        memset(&a, 0, sizeof a);
        a.count = 3;
        a.total = (int)t;
        a.points = pts;
        a.xyz = (float *)malloc(sizeof(float) * 3u * (size_t)t);
        a.rgb = (with & 1) ? (float *)malloc(sizeof(float) * 3u * (size_t)t) : NULL;
        a.thickness = (with & 2) ? (float *)malloc(sizeof(float) * (size_t)t) : NULL;
        if (!a.xyz || ((with & 1) && !a.rgb) || ((with & 2) && !a.thickness)) abort();
        for (i = 0; i < 3 * t; ++i) a.xyz[i] = 100.0f * rng_f();
        for (i = 0; a.rgb && i < 3 * t; ++i) a.rgb[i] = rng_f();
        for (i = 0; a.thickness && i < t; ++i) a.thickness[i] = rng_f();
        CHECK_READ(cv_write_hair(path, &a, "x", err, sizeof err), err);
        if (cv_read(path, &r, err, sizeof err)) {
            CHECK(r.count == 3 && r.total == t);
            CHECK(r.count == 3 && !memcmp(r.points, pts, sizeof pts));
            CHECK(same_floats(r.xyz, a.xyz, 3 * t));
            /* absent arrays read as the writer's defaults */
            CHECK(r.rgb && (a.rgb ? same_floats(r.rgb, a.rgb, 3 * t)
                                  : r.rgb[0] == 1.0f && r.rgb[3 * t - 1] == 1.0f));
            CHECK(r.thickness &&
                  (a.thickness ? same_floats(r.thickness, a.thickness, t)
                               : r.thickness[t - 1] == 1.0f));
            CHECK(r.transparency && r.transparency[0] == 0.0f &&
                  r.transparency[t - 1] == 0.0f);
            cv_free(&r);
        } else {
            CHECK_READ(0, err);
        }
        free(a.xyz);
        free(a.rgb);
        free(a.thickness);
        remove(path);
    }
}

/* A file with no colour array reads as its header's default colour; and
   cv_scale scales thickness with the points. */
static void test_hair_defaults(void)
{
    hair_src h = sample_hair(3);
    buf b = {NULL, 0, 0};
    cv_curves c;
    char err[512];
    build_hair(&b, &h);
    if (parse_exact(cv_parse_hair, b.d, b.n, &c, err, sizeof err)) {
        CHECK(c.rgb && c.rgb[0] == 0.5f && c.rgb[1] == 0.25f && c.rgb[2] == 0.75f);
        CHECK(c.rgb && c.rgb[3 * c.total - 1] == 0.75f);
        CHECK(c.thickness && c.thickness[c.total - 1] == 0.25f);
        CHECK(c.transparency && c.transparency[0] == 0.125f);
        cv_scale(&c, 2.0f);
        CHECK(c.thickness && c.thickness[0] == 0.5f);
        CHECK(c.xyz[0] == 2.0f * h.xyz[0]);
        cv_free(&c);
    } else {
        CHECK_READ(0, err);
    }
    free(b.d);
}

/* Cut short at every length: refused with a message, never read past. */
static void test_hair_truncated(void)
{
    int s;
    buf b = {NULL, 0, 0};
    for (s = 0; s < N_FLAG_SETS; ++s) {
        hair_src h = sample_hair(hair_flag_sets[s]);
        size_t len;
        build_hair(&b, &h);
        for (len = 0; len < b.n; ++len) {
            cv_curves c;
            char err[512];
            int ok = parse_exact(cv_parse_hair, b.d, len, &c, err, sizeof err);
            CHECK_REFUSED(ok, c, err,
                          len < 128 ? ".hair: shorter than its 128-byte header"
                                    : ".hair: truncated");
            if (ok) {
                printf("  (flags %u, %lu of %lu bytes read)\n", (unsigned)h.flags,
                       (unsigned long)len, (unsigned long)b.n);
                cv_free(&c);
                break;
            }
        }
    }
    free(b.d);
}

/* Headers that lie: counts bigger than the file, segments that do not add
   up, sizes that wrap 32-bit arithmetic. */
static void test_hair_lying(void)
{
    hair_src h = sample_hair(3 | 16);
    buf b = {NULL, 0, 0};
    cv_curves c;
    char err[512];
    int ok;
    uint32_t total;
    build_hair(&b, &h);
    total = (uint32_t)b.d[8] | (uint32_t)b.d[9] << 8;

#define TRY_HAIR(what)                                                         \
    do {                                                                       \
        ok = parse_exact(cv_parse_hair, b.d, b.n, &c, err, sizeof err);        \
        CHECK_REFUSED(ok, c, err, what);                                       \
        if (ok) cv_free(&c);                                                   \
        build_hair(&b, &h);                                                    \
    } while (0)

    set_u32(&b, 4, 1000); /* more strands than the file holds */
    TRY_HAIR("truncated");
    set_u32(&b, 4, 0xffffffffu);
    TRY_HAIR("strands");
    set_u32(&b, 4, 0);
    TRY_HAIR("strands");
    set_u32(&b, 8, total + 1000); /* more points than the file holds */
    TRY_HAIR("truncated");
    set_u32(&b, 8, 0xffffffffu);
    TRY_HAIR("points");
    set_u32(&b, 8, total - 1); /* segments add up to more than that */
    TRY_HAIR("segments make");
    set_u32(&b, 12, 1 | 16); /* no points */
    TRY_HAIR("no points");
    b.d[0] = 'h';
    TRY_HAIR("signature");
    b.d[128] = 0; /* strand 0 with no segment */
    b.d[129] = 0;
    TRY_HAIR("no segment");
    /* segments add up to fewer points than the header says, the file long
       enough for all of them */
    set_u32(&b, 8, total + 1);
    {
        size_t k;
        unsigned char z[16];
        memset(z, 0, sizeof z);
        for (k = 0; k < 16; ++k) put(&b, z, 16);
    }
    TRY_HAIR("segments make");
    /* no segments array and a default of 0 or 65536 segments */
    set_u32(&b, 12, 2);
    set_u32(&b, 16, 0);
    TRY_HAIR("default segment");
    set_u32(&b, 12, 2);
    set_u32(&b, 16, 65536);
    TRY_HAIR("default segment");
    /* a point that is not finite */
    set_u32(&b, 128 + 2 * HS_STRANDS + 4, 0x7fc00000u);
    TRY_HAIR("not a finite");
#undef TRY_HAIR

    /* 2^24 strands of 7 segments and 2^27 points with every array: the
       arrays need 4328521856 bytes, which wraps to 33554560 in 32 bits; a
       file of that wrapped size must be refused, not read */
    {
        size_t n = 128u + 2u * (1u << 24);
        unsigned char *d = (unsigned char *)calloc(n, 1);
        size_t i;
        if (!d) abort();
        memcpy(d, b.d, 128);
        memcpy(d, "HAIR", 4);
        d[4] = 0; d[5] = 0; d[6] = 0; d[7] = 1;   /* 2^24 strands */
        d[8] = 0; d[9] = 0; d[10] = 0; d[11] = 8; /* 2^27 points */
        d[12] = 31;
        for (i = 128; i < n; i += 2) d[i] = 7;
        err[0] = '\0';
        ok = cv_parse_hair(d, n, &c, err, sizeof err);
        CHECK_REFUSED(ok, c, err, "4328521856");
        if (ok) cv_free(&c);
        /* 2^24 strands of 65535 segments make 2^40 points, 0 in 32 bits:
           a header saying 0 points must not match */
        for (i = 128; i < n; ++i) d[i] = 0xff;
        d[8] = 0; d[9] = 0; d[10] = 0; d[11] = 0;
        d[12] = 3;
        err[0] = '\0';
        ok = cv_parse_hair(d, n, &c, err, sizeof err);
        CHECK_REFUSED(ok, c, err, "segments make");
        if (ok) cv_free(&c);
        free(d);
    }
    free(b.d);
}

/* ==== .tfx ================================================================ */

/* A version 4 file: the 160-byte header, positions at byte 160, then
   whichever of strand UVs, vertex UVs, strand thickness and vertex
   colours present (bit k of arrays: offset k + 1). Returns the byte where
   the header's offsets are. */
static void build_tfx(buf *b, uint32_t strands, uint32_t per, int arrays,
                      const float *xyzw, const float *rgba)
{
    uint32_t v = strands * per, i, at;
    b->n = 0;
    put_f32(b, 4.0f);
    put_u32(b, strands);
    put_u32(b, per);
    for (i = 0; i < 5 + 32; ++i) put_u32(b, 0);
    at = 160;
    set_u32(b, 12, at);
    for (i = 0; i < 4 * v; ++i) put_f32(b, xyzw[i]);
    at += 16 * v;
    if (arrays & 1) { /* strand UVs */
        set_u32(b, 16, at);
        for (i = 0; i < 2 * strands; ++i) put_f32(b, 0.5f);
        at += 8 * strands;
    }
    if (arrays & 2) { /* vertex UVs */
        set_u32(b, 20, at);
        for (i = 0; i < 2 * v; ++i) put_f32(b, 0.25f);
        at += 8 * v;
    }
    if (arrays & 4) { /* strand thickness */
        set_u32(b, 24, at);
        for (i = 0; i < strands; ++i) put_f32(b, 1.0f);
        at += 4 * strands;
    }
    if (arrays & 8) { /* vertex colours */
        set_u32(b, 28, at);
        for (i = 0; i < 4 * v; ++i) put_f32(b, rgba[i]);
    }
}

static float tx_xyzw[4 * 3 * 8], tx_rgba[4 * 3 * 8];
static void fill_tfx_sample(void)
{
    int i;
    for (i = 0; i < 4 * 3 * 8; ++i) {
        tx_xyzw[i] = (i % 4 == 3) ? 1.0f : 10.0f * rng_f();
        tx_rgba[i] = 0.5f * rng_f() + 0.5f;
    }
}

static void test_tfx_read(void)
{
    int arrays;
    buf b = {NULL, 0, 0};
    fill_tfx_sample();
    for (arrays = 0; arrays < 16; ++arrays) {
        cv_curves c;
        char err[512];
        int ok, i;
        build_tfx(&b, 3, 8, arrays, tx_xyzw, tx_rgba);
        ok = parse_exact(cv_parse_tfx, b.d, b.n, &c, err, sizeof err);
        CHECK_READ(ok, err);
        if (!ok) continue;
        CHECK(c.count == 3 && c.total == 24);
        for (i = 0; i < c.count && i < 3; ++i) CHECK(c.points[i] == 8);
        for (i = 0; i < 24 && c.total == 24; ++i) {
            CHECK(!memcmp(c.xyz + 3 * i, tx_xyzw + 4 * i, 12));
            if (arrays & 8) CHECK(c.rgb && !memcmp(c.rgb + 3 * i, tx_rgba + 4 * i, 12));
        }
        if (!(arrays & 8)) CHECK(!c.rgb);
        CHECK(!c.thickness && !c.transparency);
        cv_free(&c);
    }
    /* through cv_read, from a file */
    {
        cv_curves c;
        char err[512];
        const char *path = scratch("curves_check.tfx");
        build_tfx(&b, 3, 8, 0, tx_xyzw, tx_rgba);
        CHECK(write_file(path, b.d, b.n));
        if (cv_read(path, &c, err, sizeof err)) {
            CHECK(c.count == 3 && c.total == 24 && !memcmp(c.xyz + 3, tx_xyzw + 4, 12));
            cv_free(&c);
        } else {
            CHECK_READ(0, err);
        }
        remove(path);
    }
    free(b.d);
}

static void test_tfx_truncated(void)
{
    int arrays;
    buf b = {NULL, 0, 0};
    fill_tfx_sample();
    for (arrays = 0; arrays < 16; arrays += 5) {
        size_t len;
        build_tfx(&b, 3, 8, arrays | 8, tx_xyzw, tx_rgba);
        for (len = 0; len < b.n; ++len) {
            cv_curves c;
            char err[512];
            int ok = parse_exact(cv_parse_tfx, b.d, len, &c, err, sizeof err);
            CHECK_REFUSED(ok, c, err,
                          len < 160 ? ".tfx: shorter than its 160-byte header"
                                    : ".tfx: truncated");
            if (ok) {
                printf("  (arrays %d, %lu of %lu bytes read)\n", arrays | 8,
                       (unsigned long)len, (unsigned long)b.n);
                cv_free(&c);
                break;
            }
        }
    }
    free(b.d);
}

static void test_tfx_lying(void)
{
    buf b = {NULL, 0, 0};
    cv_curves c;
    char err[512];
    int ok, k;
    static const char *const what[5] = {"positions", "strand UVs", "vertex UVs",
                                        "strand thicknesses", "vertex colours"};
    fill_tfx_sample();
    build_tfx(&b, 3, 8, 15, tx_xyzw, tx_rgba);

#define TRY_TFX(what)                                                          \
    do {                                                                       \
        ok = parse_exact(cv_parse_tfx, b.d, b.n, &c, err, sizeof err);         \
        CHECK_REFUSED(ok, c, err, what);                                       \
        if (ok) cv_free(&c);                                                   \
        build_tfx(&b, 3, 8, 15, tx_xyzw, tx_rgba);                             \
    } while (0)

    /* every offset: inside the header, past the end, wrapping 32 bits */
    for (k = 0; k < 5; ++k) {
        char m[96];
        set_u32(&b, 12 + 4 * (size_t)k, 16);
        snprintf(m, sizeof m, "the %s offset, byte 16, is inside", what[k]);
        TRY_TFX(m);
        set_u32(&b, 12 + 4 * (size_t)k, 159);
        TRY_TFX("inside the 160-byte header");
        set_u32(&b, 12 + 4 * (size_t)k, (uint32_t)b.n);
        snprintf(m, sizeof m, "truncated: %s at byte %lu", what[k], (unsigned long)b.n);
        TRY_TFX(m);
        set_u32(&b, 12 + 4 * (size_t)k, (uint32_t)b.n - 4);
        TRY_TFX(what[k]);
        set_u32(&b, 12 + 4 * (size_t)k, 0xfffffff0u);
        TRY_TFX(what[k]);
    }
    set_u32(&b, 12, 0);
    TRY_TFX("no positions");
    /* counts larger than the file, or than the limits */
    set_u32(&b, 4, 100);
    TRY_TFX("truncated: positions");
    set_u32(&b, 8, 100);
    TRY_TFX("truncated: positions");
    set_u32(&b, 4, 0xffffffffu);
    TRY_TFX("strands");
    set_u32(&b, 4, 0);
    TRY_TFX("strands");
    set_u32(&b, 8, 1);
    TRY_TFX("strands");
    set_u32(&b, 8, 0xffffffffu);
    TRY_TFX("strands");
    set_u32(&b, 4, 1u << 24); /* 2^24 strands of 4096: too many vertices */
    set_u32(&b, 8, 4096);
    TRY_TFX("strands");
    /* 2^20 strands of 128 vertices: positions alone 2^31 bytes */
    set_u32(&b, 4, 1u << 20);
    set_u32(&b, 8, 128);
    TRY_TFX("truncated: positions");
    /* the strand UVs' end, 0xfffffff8 + 24, wraps to 16 in 32 bits */
    set_u32(&b, 16, 0xfffffff8u);
    TRY_TFX("truncated: strand UVs");
    set_u32(&b, 0, 0x40400000u); /* 3.0f */
    TRY_TFX("version 3");
    set_u32(&b, 0, 0x40a00000u); /* 5.0f */
    TRY_TFX("version 5");
    set_u32(&b, 160 + 4, 0x7f800000u); /* +inf y */
    TRY_TFX("not a finite");
#undef TRY_TFX
    free(b.d);
}

/* ==== OBJ ================================================================= */

#ifndef CURVES_NO_ASSIMP
static int obj_near(const cv_curves *a, const cv_curves *b)
{
    long i;
    if (a->count != b->count || a->total != b->total ||
        memcmp(a->points, b->points, sizeof(int) * (size_t)a->count) != 0)
        return 0;
    /* %.7g keeps about 7 significant digits: a relative 1e-6 */
    for (i = 0; i < 3L * a->total; ++i)
        if (!(fabs((double)a->xyz[i] - b->xyz[i]) <=
              1e-6 * fabs((double)a->xyz[i]) + 1e-30))
            return 0;
    return 1;
}

static void test_obj_round_trip(void)
{
    static const int pts[] = {2, 3, 16, 2, 40, 5};
    cv_curves a, r;
    char err[512];
    long i, t = 0;
    const char *path = scratch("curves_check.obj");
    memset(&a, 0, sizeof a);
    a.count = (int)(sizeof pts / sizeof pts[0]);
    for (i = 0; i < a.count; ++i) t += pts[i];
    a.total = (int)t;
    a.points = (int *)malloc(sizeof pts);
    a.xyz = (float *)malloc(sizeof(float) * 3u * (size_t)t);
    if (!a.points || !a.xyz) abort();
    memcpy(a.points, pts, sizeof pts);
    for (i = 0; i < 3 * t; ++i) a.xyz[i] = 50.0f * rng_f() + (i % 3 == 1 ? 200.0f : 0.0f);
    CHECK_READ(cv_write_obj(path, &a, err, sizeof err), err);
    if (cv_read(path, &r, err, sizeof err)) {
        CHECK(obj_near(&a, &r));
        CHECK(!r.rgb && !r.thickness && !r.transparency);
        cv_free(&r);
    } else {
        CHECK_READ(0, err);
    }
    /* the same bytes from memory */
    {
        FILE *f = fopen(path, "rb");
        unsigned char d[65536];
        size_t n = f ? fread(d, 1, sizeof d, f) : 0;
        if (f) fclose(f);
        CHECK(n > 0 && n < sizeof d);
        if (parse_exact(cv_parse_obj, d, n, &r, err, sizeof err)) {
            CHECK(obj_near(&a, &r));
            cv_free(&r);
        } else {
            CHECK_READ(0, err);
        }
    }
    cv_free(&a);
    remove(path);
}

/* Faces and points next to lines are left out; a file of faces only has
   no polylines. */
static void test_obj_faces_ignored(void)
{
    static const char *const mixed[] = {
        /* faces before the line, one object */
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 2\nv 0 0 3\n"
        "f 1 2 3\nf 1 3 4\nl 4 5 6\n",
        /* the line first, then a quad and a point */
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 2\nv 0 0 3\n"
        "l 4 5 6\nf 1 2 3 4\np 2\n",
        /* the line split into segments, faces between them */
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 2\nv 0 0 3\n"
        "l 4 5\nf 1 2 3\nl 5 6\n"};
    static const float want[9] = {0, 0, 1, 0, 0, 2, 0, 0, 3};
    size_t k;
    for (k = 0; k < sizeof mixed / sizeof mixed[0]; ++k) {
        cv_curves c;
        char err[512];
        int ok = parse_exact(cv_parse_obj, (const unsigned char *)mixed[k],
                             strlen(mixed[k]), &c, err, sizeof err);
        CHECK_READ(ok, err);
        if (!ok) continue;
        if (!(c.count == 1 && c.total == 3 && same_floats(c.xyz, want, 9)))
            printf("  (file %lu: %d curves of %d points)\n", (unsigned long)k,
                   c.count, c.total);
        CHECK(c.count == 1 && c.total == 3 && same_floats(c.xyz, want, 9));
        cv_free(&c);
    }
    {
        static const char faces[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        cv_curves c;
        char err[512];
        int ok = parse_exact(cv_parse_obj, (const unsigned char *)faces,
                             strlen(faces), &c, err, sizeof err);
        CHECK_REFUSED(ok, c, err, "no polylines");
        if (ok) cv_free(&c);
    }
}

/* Bad OBJ text: refused with a message, or (where assimp makes something
   of it) whole curves; never a crash. */
static void test_obj_bad(void)
{
    static const char *const bad[] = {
        "", "l 1 2\n", "v 0 0 0\nl 1 9\n", "v 0 0\nv 1 1 1\nl 1 2\n",
        "v nan 0 0\nv 1 1 1\nl 1 2\n", "v 1e30 0 0\nv 1 1 1\nl 1 2\n",
        "v 0 0 0\nv 1 1 1\nl 1\n", "v 0 0 0\nv 1 1 1\nl -1 -2\n"};
    size_t k;
    for (k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        cv_curves c;
        char err[512];
        int ok = parse_exact(cv_parse_obj, (const unsigned char *)bad[k],
                             strlen(bad[k]), &c, err, sizeof err);
        if (!ok) {
            CHECK_REFUSED(ok, c, err, "OBJ");
        } else {
            long i, sum = 0;
            for (i = 0; i < c.count; ++i) sum += c.points[i] >= 2 ? c.points[i] : -1000;
            CHECK(c.count >= 1 && sum == c.total);
            for (i = 0; i < 3L * c.total; ++i) CHECK(isfinite(c.xyz[i]));
            cv_free(&c);
        }
    }
}
#endif

/* ==== cv_read's dispatch ================================================== */

static void test_read_errors(void)
{
    cv_curves c;
    char err[512];
    int ok;
    ok = cv_read(scratch("no_such_file.hair"), &c, err, sizeof err);
    CHECK_REFUSED(ok, c, err, "cannot open");
    ok = cv_read("curves.ply", &c, err, sizeof err);
    CHECK_REFUSED(ok, c, err, "curves are read from");
    /* an empty .hair file names the path and the problem */
    CHECK(write_file(scratch("curves_check_empty.hair"), (const unsigned char *)"", 0));
    ok = cv_read(scratch("curves_check_empty.hair"), &c, err, sizeof err);
    CHECK_REFUSED(ok, c, err, "curves_check_empty.hair: .hair: shorter");
    remove(scratch("curves_check_empty.hair"));
}

int main(int argc, char **argv)
{
    if (argc > 1) {
        snprintf(t_dir, sizeof t_dir, "%s", argv[1]);
    } else if (argc == 1 && strrchr(argv[0], '/')) {
        /* next to the program (build/), not in the working directory */
        size_t k = (size_t)(strrchr(argv[0], '/') - argv[0]);
        snprintf(t_dir, sizeof t_dir, "%.*s", (int)(k < 1000 ? k : 1000), argv[0]);
    }
    RUN(test_hair_round_trip);
    RUN(test_hair_write_read);
    RUN(test_hair_defaults);
    RUN(test_hair_truncated);
    RUN(test_hair_lying);
    RUN(test_tfx_read);
    RUN(test_tfx_truncated);
    RUN(test_tfx_lying);
#ifndef CURVES_NO_ASSIMP
    RUN(test_obj_round_trip);
    RUN(test_obj_faces_ignored);
    RUN(test_obj_bad);
#endif
    RUN(test_read_errors);
    printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}
