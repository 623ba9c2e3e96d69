/* curves.h - hair curves in and out, for the examples: Cem Yuksel's .hair
   (read and write), AMD TressFX's .tfx (version 4, read) and OBJ polylines
   (`l` lines: written here, read through assimp). The library itself stays
   format-free; these fill the arrays hf_fur_desc.guide_curves takes.

   Every reader checks the whole file before it returns anything: a bad or
   truncated file gives 0 and a message naming the problem, never a partial
   result. Sizes are computed in 64 bits, so a header that lies gives an
   error, never a wrapped count, on 32-bit targets too. The readers work on
   memory (cv_parse_hair, cv_parse_tfx, cv_parse_obj), so they are fuzzed
   as they are (tests/fuzz/fuzz_curves.c, tests/fuzz/fuzz_obj.c) and tested
   by tests/curves_check.c.

   Define CURVES_IMPLEMENTATION in one file before including; define
   CURVES_NO_ASSIMP to leave out the OBJ reader (it needs assimp). */
#ifndef CURVES_H
#define CURVES_H

#include <stddef.h>

#define CV_MAX_CURVES (1 << 24)
#define CV_MAX_POINTS (1 << 27)

/* Per-point attributes are NULL when the format has none; a .hair file
   gives all three, from its arrays or, where an array is absent, from the
   header's default (so a file without colours reads as its default
   colour). */
typedef struct cv_curves {
    int count;           /* curves */
    int total;           /* points of all curves */
    int *points;         /* per curve: its point count (>= 2) */
    float *xyz;          /* 3 per point, curve after curve, root first */
    float *rgb;          /* NULL, or 3 per point (.hair colours, .tfx vertex
                            colours without their alpha) */
    float *thickness;    /* NULL, or 1 per point (.hair), in xyz's units */
    float *transparency; /* NULL, or 1 per point (.hair; 0 opaque) */
} cv_curves;

/* Read a file by its extension (.hair, .tfx, .obj); 1, or 0 with a
   message in err. */
int cv_read(const char *path, cv_curves *c, char *err, size_t err_size);
int cv_parse_hair(const unsigned char *data, size_t size, cv_curves *c,
                  char *err, size_t err_size);
int cv_parse_tfx(const unsigned char *data, size_t size, cv_curves *c,
                 char *err, size_t err_size);
#ifndef CURVES_NO_ASSIMP
int cv_read_obj(const char *path, cv_curves *c, char *err, size_t err_size);
int cv_parse_obj(const unsigned char *data, size_t size, cv_curves *c,
                 char *err, size_t err_size);
#endif
/* Write .hair (segments, points and whichever of thickness, transparency
   and colours c has) or OBJ `l` polylines; 1, or 0 with a message. */
int cv_write_hair(const char *path, const cv_curves *c, const char *info,
                  char *err, size_t err_size);
int cv_write_obj(const char *path, const cv_curves *c, char *err,
                 size_t err_size);
/* Scale every point (and thickness) by s (file units to metres). */
void cv_scale(cv_curves *c, float s);
void cv_free(cv_curves *c);

#endif /* CURVES_H */

#ifdef CURVES_IMPLEMENTATION
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifndef CURVES_NO_ASSIMP
#include <assimp/cimport.h>
#include <assimp/scene.h>
#endif

static int cv__fail(char *err, size_t n, const char *what)
{
    if (err && n) snprintf(err, n, "%s", what);
    return 0;
}

static uint32_t cv__u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
           (uint32_t)p[3] << 24;
}

static float cv__f32(const unsigned char *p)
{
    uint32_t u = cv__u32(p);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static void cv__put_u32(unsigned char *p, uint32_t u)
{
    p[0] = (unsigned char)u;
    p[1] = (unsigned char)(u >> 8);
    p[2] = (unsigned char)(u >> 16);
    p[3] = (unsigned char)(u >> 24);
}

static void cv__put_f32(unsigned char *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    cv__put_u32(p, u);
}

void cv_free(cv_curves *c)
{
    free(c->points);
    free(c->xyz);
    free(c->rgb);
    free(c->thickness);
    free(c->transparency);
    memset(c, 0, sizeof *c);
}

void cv_scale(cv_curves *c, float s)
{
    long i;
    for (i = 0; i < 3L * c->total; ++i) c->xyz[i] *= s;
    for (i = 0; c->thickness && i < (long)c->total; ++i) c->thickness[i] *= s;
}

#define CV__RGB 1
#define CV__THICKNESS 2
#define CV__TRANSPARENCY 4

/* Allocate count curves and total points, and the attributes asked for;
   both counts are within CV_MAX_*, so no size here wraps even in 32 bits. */
static int cv__alloc(cv_curves *c, long count, long total, int attrs,
                     char *err, size_t n)
{
    size_t t = (size_t)(total > 0 ? total : 1);
    memset(c, 0, sizeof *c);
    c->points = (int *)malloc(sizeof(int) * (size_t)(count > 0 ? count : 1));
    c->xyz = (float *)malloc(sizeof(float) * 3u * t);
    if (attrs & CV__RGB) c->rgb = (float *)malloc(sizeof(float) * 3u * t);
    if (attrs & CV__THICKNESS) c->thickness = (float *)malloc(sizeof(float) * t);
    if (attrs & CV__TRANSPARENCY) c->transparency = (float *)malloc(sizeof(float) * t);
    if (!c->points || !c->xyz || ((attrs & CV__RGB) && !c->rgb) ||
        ((attrs & CV__THICKNESS) && !c->thickness) ||
        ((attrs & CV__TRANSPARENCY) && !c->transparency)) {
        cv_free(c);
        return cv__fail(err, n, "out of memory");
    }
    c->count = (int)count;
    c->total = (int)total;
    return 1;
}

/* Points finite and not absurd (metres or centimetres). */
static int cv__finite(const cv_curves *c, char *err, size_t n)
{
    long i;
    for (i = 0; i < 3L * c->total; ++i)
        if (!isfinite(c->xyz[i]) || fabsf(c->xyz[i]) > 1e6f) {
            char m[128];
            snprintf(m, sizeof m, "point %ld is not a finite coordinate "
                     "below 1e6", i / 3);
            return cv__fail(err, n, m);
        }
    return 1;
}

/* .hair: a 128-byte little-endian header ("HAIR", uint32 strands, uint32
   points, uint32 flags: 1 segments, 2 points, 4 thickness, 8
   transparency, 16 colours; uint32 default segments, float default
   thickness, float default transparency, float[3] default colour, char[88]
   info), then the arrays present in that order. */
int cv_parse_hair(const unsigned char *d, size_t size, cv_curves *c,
                  char *err, size_t n)
{
    uint32_t strands, points, flags, defseg;
    unsigned long long need, sum = 0;
    size_t at = 128;
    long i;
    char m[200];
    memset(c, 0, sizeof *c);
    if (size < 128) return cv__fail(err, n, ".hair: shorter than its 128-byte header");
    if (memcmp(d, "HAIR", 4) != 0) return cv__fail(err, n, ".hair: no \"HAIR\" signature");
    strands = cv__u32(d + 4);
    points = cv__u32(d + 8);
    flags = cv__u32(d + 12);
    defseg = cv__u32(d + 16);
    if (!(flags & 2)) return cv__fail(err, n, ".hair: the file has no points array (flag 2)");
    if (strands == 0 || strands > CV_MAX_CURVES || points > CV_MAX_POINTS) {
        snprintf(m, sizeof m, ".hair: %lu strands, %lu points (1 .. %d strands, "
                 "at most %d points)", (unsigned long)strands,
                 (unsigned long)points, CV_MAX_CURVES, CV_MAX_POINTS);
        return cv__fail(err, n, m);
    }
    if (!(flags & 1) && (defseg < 1 || defseg > 65535))
        return cv__fail(err, n, ".hair: no segments array and a default segment "
                        "count outside 1 .. 65535");
    /* the arrays' sizes (64-bit: up to about 4.3e9 bytes here), then the
       file's */
    need = 128ull + ((flags & 1) ? 2ull * strands : 0) + 12ull * points +
           ((flags & 4) ? 4ull * points : 0) + ((flags & 8) ? 4ull * points : 0) +
           ((flags & 16) ? 12ull * points : 0);
    if ((unsigned long long)size < need) {
        snprintf(m, sizeof m, ".hair: truncated: %.0f bytes, the header promises "
                 "%.0f", (double)size, (double)need);
        return cv__fail(err, n, m);
    }
    for (i = 0; i < (long)strands; ++i) {
        unsigned long seg = (flags & 1)
                                ? (unsigned long)d[at + 2 * (size_t)i] |
                                      (unsigned long)d[at + 2 * (size_t)i + 1] << 8
                                : (unsigned long)defseg;
        if (seg < 1) {
            snprintf(m, sizeof m, ".hair: strand %ld has no segment", i);
            return cv__fail(err, n, m);
        }
        sum += seg + 1;
        if (sum > points) break; /* already wrong; and no sum grows far */
    }
    if (i < (long)strands) {
        snprintf(m, sizeof m, ".hair: the strands' segments make more than the "
                 "%lu points the header says (by strand %ld)",
                 (unsigned long)points, i);
        return cv__fail(err, n, m);
    }
    if (sum != points) {
        snprintf(m, sizeof m, ".hair: the strands' segments make %.0f points, "
                 "the header says %lu", (double)sum, (unsigned long)points);
        return cv__fail(err, n, m);
    }
    if (!cv__alloc(c, strands, points, CV__RGB | CV__THICKNESS | CV__TRANSPARENCY,
                   err, n))
        return 0;
    for (i = 0; i < (long)strands; ++i)
        c->points[i] = 1 + ((flags & 1) ? (int)(d[at + 2 * (size_t)i] |
                                                d[at + 2 * (size_t)i + 1] << 8)
                                        : (int)defseg);
    if (flags & 1) at += 2u * (size_t)strands;
    for (i = 0; i < 3L * (long)points; ++i) c->xyz[i] = cv__f32(d + at + 4 * (size_t)i);
    at += 12u * (size_t)points;
    /* each attribute from its array, else the header's default */
    for (i = 0; i < (long)points; ++i)
        c->thickness[i] = cv__f32((flags & 4) ? d + at + 4 * (size_t)i : d + 20);
    if (flags & 4) at += 4u * (size_t)points;
    for (i = 0; i < (long)points; ++i)
        c->transparency[i] = cv__f32((flags & 8) ? d + at + 4 * (size_t)i : d + 24);
    if (flags & 8) at += 4u * (size_t)points;
    for (i = 0; i < 3L * (long)points; ++i)
        c->rgb[i] = cv__f32((flags & 16) ? d + at + 4 * (size_t)i : d + 28 + 4 * (i % 3));
    if (!cv__finite(c, err, n)) {
        cv_free(c);
        return 0;
    }
    return 1;
}

/* TressFX .tfx, version 4: float version, uint32 strands, uint32 vertices
   per strand, then uint32 byte offsets (positions, strand UVs, vertex UVs,
   strand thickness, vertex colours; 0 = absent) and 32 reserved words, 160
   bytes in all; positions at byte 160 as written by TressFX's exporter,
   float4 per vertex (xyz, inverse mass), strand after strand. Every array
   present is checked to lie past the header and inside the file; positions
   and vertex colours (float4, rgb kept) are read, the rest only checked. */
#define CV__TFX_HEADER 160u
int cv_parse_tfx(const unsigned char *d, size_t size, cv_curves *c, char *err,
                 size_t n)
{
    static const char *const what[5] = {"positions", "strand UVs", "vertex UVs",
                                        "strand thicknesses", "vertex colours"};
    uint32_t strands, per, off[5];
    unsigned long long verts, bytes[5];
    float version;
    long s, j;
    int k;
    char m[200];
    memset(c, 0, sizeof *c);
    if (size < CV__TFX_HEADER)
        return cv__fail(err, n, ".tfx: shorter than its 160-byte header");
    version = cv__f32(d);
    strands = cv__u32(d + 4);
    per = cv__u32(d + 8);
    if (!(version >= 4.0f && version < 5.0f)) {
        snprintf(m, sizeof m, ".tfx: version %g; this reader knows version 4",
                 (double)version);
        return cv__fail(err, n, m);
    }
    if (strands == 0 || strands > CV_MAX_CURVES || per < 2 || per > 4096 ||
        (unsigned long long)strands * per > CV_MAX_POINTS) {
        snprintf(m, sizeof m, ".tfx: %lu strands of %lu vertices (1 .. %d "
                 "strands of 2 .. 4096, at most %d vertices)",
                 (unsigned long)strands, (unsigned long)per, CV_MAX_CURVES,
                 CV_MAX_POINTS);
        return cv__fail(err, n, m);
    }
    verts = (unsigned long long)strands * per;
    bytes[0] = 16u * verts;    /* float4 */
    bytes[1] = 8ull * strands; /* float2 */
    bytes[2] = 8u * verts;     /* float2 */
    bytes[3] = 4ull * strands; /* float */
    bytes[4] = 16u * verts;    /* float4 */
    for (k = 0; k < 5; ++k) {
        off[k] = cv__u32(d + 12 + 4 * k);
        if (off[k] == 0) {
            if (k == 0) return cv__fail(err, n, ".tfx: no positions (offset 0)");
            continue;
        }
        if (off[k] < CV__TFX_HEADER) {
            snprintf(m, sizeof m, ".tfx: the %s offset, byte %lu, is inside the "
                     "160-byte header", what[k], (unsigned long)off[k]);
            return cv__fail(err, n, m);
        }
        if ((unsigned long long)off[k] + bytes[k] > (unsigned long long)size) {
            snprintf(m, sizeof m, ".tfx: truncated: %s at byte %lu need %.0f "
                     "bytes, the file has %.0f", what[k], (unsigned long)off[k],
                     (double)bytes[k], (double)size);
            return cv__fail(err, n, m);
        }
    }
    if (!cv__alloc(c, strands, (long)verts, off[4] ? CV__RGB : 0, err, n)) return 0;
    for (s = 0; s < (long)strands; ++s) {
        c->points[s] = (int)per;
        for (j = 0; j < (long)per; ++j) {
            size_t v = (size_t)s * per + (size_t)j;
            const unsigned char *p = d + off[0] + 16u * v;
            float *o = c->xyz + 3 * v;
            o[0] = cv__f32(p);
            o[1] = cv__f32(p + 4);
            o[2] = cv__f32(p + 8);
            if (c->rgb) {
                p = d + off[4] + 16u * v;
                o = c->rgb + 3 * v;
                o[0] = cv__f32(p);
                o[1] = cv__f32(p + 4);
                o[2] = cv__f32(p + 8);
            }
        }
    }
    if (!cv__finite(c, err, n)) {
        cv_free(c);
        return 0;
    }
    return 1;
}

static unsigned char *cv__slurp(const char *path, size_t *size, char *err,
                                size_t n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *d;
    long len;
    char m[512];
    if (!f) {
        snprintf(m, sizeof m, "cannot open %s", path);
        cv__fail(err, n, m);
        return NULL;
    }
    if (fseek(f, 0, SEEK_END) != 0 || (len = ftell(f)) < 0 ||
        fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        snprintf(m, sizeof m, "cannot read %s", path);
        cv__fail(err, n, m);
        return NULL;
    }
    d = (unsigned char *)malloc((size_t)len + 1);
    if (!d || fread(d, 1, (size_t)len, f) != (size_t)len) {
        free(d);
        fclose(f);
        snprintf(m, sizeof m, "cannot read %s", path);
        cv__fail(err, n, m);
        return NULL;
    }
    fclose(f);
    *size = (size_t)len;
    return d;
}

static int cv__ends(const char *s, const char *suf)
{
    size_t a = strlen(s), b = strlen(suf), i;
    if (a < b) return 0;
    for (i = 0; i < b; ++i) {
        char x = s[a - b + i];
        if (x >= 'A' && x <= 'Z') x = (char)(x - 'A' + 'a');
        if (x != suf[i]) return 0;
    }
    return 1;
}

#ifndef CURVES_NO_ASSIMP
/* OBJ polylines from an assimp scene: line primitives only (two-index
   faces; assimp hands an `l a b c` line over as segments), so faces and
   points in the same file are left out. Consecutive segments where one
   starts at the point the previous one ended (the same position) are
   chained into one polyline, as exporters also write `l a b` per
   segment. */
static int cv__obj_scene(const struct aiScene *sc, const char *name,
                         cv_curves *c, char *err, size_t n)
{
    unsigned mi, f;
    long pass;
    char m[512];
    /* two passes: count, then fill */
    for (pass = 0; pass < 2; ++pass) {
        long ci = 0, pi = 0;
        for (mi = 0; mi < sc->mNumMeshes; ++mi) {
            const struct aiMesh *me = sc->mMeshes[mi];
            int have_end = 0;
            float end[3] = {0, 0, 0};
            if (!me || !(me->mPrimitiveTypes & aiPrimitiveType_LINE) || !me->mFaces ||
                !me->mVertices)
                continue;
            for (f = 0; f < me->mNumFaces; ++f) {
                const struct aiFace *fa = &me->mFaces[f];
                float a[3], b[3];
                if (fa->mNumIndices != 2) continue; /* a face or a point */
                if (fa->mIndices[0] >= me->mNumVertices ||
                    fa->mIndices[1] >= me->mNumVertices) {
                    have_end = 0;
                    continue;
                }
                a[0] = me->mVertices[fa->mIndices[0]].x;
                a[1] = me->mVertices[fa->mIndices[0]].y;
                a[2] = me->mVertices[fa->mIndices[0]].z;
                b[0] = me->mVertices[fa->mIndices[1]].x;
                b[1] = me->mVertices[fa->mIndices[1]].y;
                b[2] = me->mVertices[fa->mIndices[1]].z;
                if (have_end && a[0] == end[0] && a[1] == end[1] && a[2] == end[2]) {
                    /* continues the previous polyline */
                    if (pass) ++c->points[ci - 1];
                } else {
                    if (pass) {
                        c->points[ci] = 2;
                        memcpy(c->xyz + 3 * pi, a, sizeof a);
                    }
                    ++ci;
                    ++pi;
                }
                if (pass) memcpy(c->xyz + 3 * pi, b, sizeof b);
                ++pi;
                have_end = 1;
                memcpy(end, b, sizeof b);
            }
        }
        if (!pass) {
            if (ci == 0) {
                snprintf(m, sizeof m, "%s: no polylines (`l` lines) in the file", name);
                return cv__fail(err, n, m);
            }
            if (ci > CV_MAX_CURVES || pi > CV_MAX_POINTS) {
                snprintf(m, sizeof m, "%s: %ld polylines of %ld points in all (at "
                         "most %d and %d)", name, ci, pi, CV_MAX_CURVES,
                         CV_MAX_POINTS);
                return cv__fail(err, n, m);
            }
            if (!cv__alloc(c, ci, pi, 0, err, n)) return 0;
        }
    }
    if (!cv__finite(c, m, sizeof m)) {
        char m2[700];
        snprintf(m2, sizeof m2, "%s: %s", name, m);
        cv_free(c);
        return cv__fail(err, n, m2);
    }
    return 1;
}

int cv_read_obj(const char *path, cv_curves *c, char *err, size_t n)
{
    const struct aiScene *sc;
    char m[512];
    int ok;
    memset(c, 0, sizeof *c);
    if (!(sc = aiImportFile(path, 0))) {
        snprintf(m, sizeof m, "%s: %s", path, aiGetErrorString());
        return cv__fail(err, n, m);
    }
    ok = cv__obj_scene(sc, path, c, err, n);
    aiReleaseImport(sc);
    return ok;
}

/* The same from memory: the hint "obj" picks assimp's OBJ importer. */
int cv_parse_obj(const unsigned char *data, size_t size, cv_curves *c,
                 char *err, size_t n)
{
    const struct aiScene *sc;
    char m[512];
    int ok;
    memset(c, 0, sizeof *c);
    if (size == 0 || size > 0x7fffffffu)
        return cv__fail(err, n, "OBJ: empty, or larger than 2 GiB");
    if (!(sc = aiImportFileFromMemory((const char *)data, (unsigned)size, 0, "obj"))) {
        snprintf(m, sizeof m, "OBJ: %s", aiGetErrorString());
        return cv__fail(err, n, m);
    }
    ok = cv__obj_scene(sc, "OBJ", c, err, n);
    aiReleaseImport(sc);
    return ok;
}
#endif

int cv_read(const char *path, cv_curves *c, char *err, size_t n)
{
    unsigned char *d;
    size_t size = 0;
    int ok;
    char m[600];
    memset(c, 0, sizeof *c);
#ifndef CURVES_NO_ASSIMP
    if (cv__ends(path, ".obj")) return cv_read_obj(path, c, err, n);
#endif
    if (!cv__ends(path, ".hair") && !cv__ends(path, ".tfx")) {
        snprintf(m, sizeof m, "%s: curves are read from .hair, .tfx or .obj", path);
        return cv__fail(err, n, m);
    }
    if (!(d = cv__slurp(path, &size, err, n))) return 0;
    ok = cv__ends(path, ".hair") ? cv_parse_hair(d, size, c, m, sizeof m)
                                 : cv_parse_tfx(d, size, c, m, sizeof m);
    free(d);
    if (!ok) {
        char m2[700];
        snprintf(m2, sizeof m2, "%s: %s", path, m);
        return cv__fail(err, n, m2);
    }
    return 1;
}

/* count little-endian floats; 1, or 0 on a write error */
static int cv__write_f32s(FILE *f, const float *v, long count)
{
    unsigned char b[1024];
    long i = 0;
    while (i < count) {
        long k, m = count - i < 256 ? count - i : 256;
        for (k = 0; k < m; ++k) cv__put_f32(b + 4 * k, v[i + k]);
        if (fwrite(b, 4, (size_t)m, f) != (size_t)m) return 0;
        i += m;
    }
    return 1;
}

int cv_write_hair(const char *path, const cv_curves *c, const char *info,
                  char *err, size_t n)
{
    unsigned char h[128];
    FILE *f;
    long i, sum = 0;
    int ok = 1;
    char m[512];
    if (c->count < 1 || c->count > CV_MAX_CURVES || c->total > CV_MAX_POINTS)
        return cv__fail(err, n, ".hair: no strand, or too many strands or points");
    for (i = 0; i < c->count; ++i) {
        if (c->points[i] < 2 || c->points[i] > 65536)
            return cv__fail(err, n, ".hair: a strand has fewer than 2 or more "
                            "than 65536 points");
        sum += c->points[i];
        if (sum > c->total) break;
    }
    if (sum != c->total)
        return cv__fail(err, n, ".hair: the strands' point counts do not add up "
                        "to the total");
    memset(h, 0, sizeof h);
    memcpy(h, "HAIR", 4);
    cv__put_u32(h + 4, (uint32_t)c->count);
    cv__put_u32(h + 8, (uint32_t)c->total);
    cv__put_u32(h + 12, 1u | 2u | (c->thickness ? 4u : 0u) |
                            (c->transparency ? 8u : 0u) | (c->rgb ? 16u : 0u));
    cv__put_u32(h + 16, (uint32_t)(c->points[0] - 1));
    cv__put_f32(h + 20, 1.0f);  /* default thickness */
    cv__put_f32(h + 24, 0.0f);  /* default transparency */
    cv__put_f32(h + 28, 1.0f);  /* default colour */
    cv__put_f32(h + 32, 1.0f);
    cv__put_f32(h + 36, 1.0f);
    if (info) strncpy((char *)h + 40, info, 87);
    if (!(f = fopen(path, "wb"))) {
        snprintf(m, sizeof m, "cannot write %s", path);
        return cv__fail(err, n, m);
    }
    ok = fwrite(h, 1, 128, f) == 128;
    for (i = 0; ok && i < c->count; ++i) {
        unsigned char s[2];
        s[0] = (unsigned char)(c->points[i] - 1);
        s[1] = (unsigned char)((c->points[i] - 1) >> 8);
        ok = fwrite(s, 1, 2, f) == 2;
    }
    ok = ok && cv__write_f32s(f, c->xyz, 3L * c->total);
    if (c->thickness) ok = ok && cv__write_f32s(f, c->thickness, c->total);
    if (c->transparency) ok = ok && cv__write_f32s(f, c->transparency, c->total);
    if (c->rgb) ok = ok && cv__write_f32s(f, c->rgb, 3L * c->total);
    if (fclose(f) != 0) ok = 0;
    if (!ok) {
        remove(path);
        snprintf(m, sizeof m, "cannot write %s", path);
        return cv__fail(err, n, m);
    }
    return 1;
}

int cv_write_obj(const char *path, const cv_curves *c, char *err, size_t n)
{
    FILE *f = fopen(path, "w");
    long i, j, at = 1;
    int ok;
    char m[512];
    if (!f) {
        snprintf(m, sizeof m, "cannot write %s", path);
        return cv__fail(err, n, m);
    }
    ok = fprintf(f, "# hair curves: %d polylines, %d points\n", c->count,
                 c->total) > 0;
    for (i = 0; ok && i < c->total; ++i)
        ok = fprintf(f, "v %.7g %.7g %.7g\n", c->xyz[3 * i], c->xyz[3 * i + 1],
                     c->xyz[3 * i + 2]) > 0;
    for (i = 0; ok && i < c->count; ++i) {
        ok = fputc('l', f) != EOF;
        for (j = 0; ok && j < c->points[i]; ++j) ok = fprintf(f, " %ld", at + j) > 0;
        if (ok) ok = fputc('\n', f) != EOF;
        at += c->points[i];
    }
    if (fclose(f) != 0) ok = 0;
    if (!ok) {
        remove(path);
        snprintf(m, sizeof m, "cannot write %s", path);
        return cv__fail(err, n, m);
    }
    return 1;
}
#endif /* CURVES_IMPLEMENTATION */
