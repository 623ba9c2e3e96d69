/* curves.h - hair curves in and out, for the examples: Cem Yuksel's .hair
   (read and write), AMD TressFX's .tfx (version 4, read) and OBJ polylines
   (`l` lines: written here, read through assimp). The library itself stays
   format-free; these fill the arrays hf_fur_desc.guide_curves takes.

   Every reader checks the whole file before it returns anything: a bad or
   truncated file gives 0 and a message naming the problem, never a partial
   result. The .hair and .tfx readers work on memory (cv_parse_hair,
   cv_parse_tfx), so they are fuzzed as they are (tests/fuzz/fuzz_curves.c).

   Define CURVES_IMPLEMENTATION in one file before including; define
   CURVES_NO_ASSIMP to leave out the OBJ reader (it needs assimp). */
#ifndef CURVES_H
#define CURVES_H

#include <stddef.h>

#define CV_MAX_CURVES (1 << 24)
#define CV_MAX_POINTS (1 << 27)

typedef struct cv_curves {
    int count;        /* curves */
    int total;        /* points of all curves */
    int *points;      /* per curve: its point count (>= 2) */
    float *xyz;       /* 3 per point, curve after curve, root first */
    float *rgb;       /* NULL, or 3 per point (.hair colours) */
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
#endif
/* Write .hair (segments, points and, if c->rgb, colours) or OBJ `l`
   polylines; 1, or 0 with a message. */
int cv_write_hair(const char *path, const cv_curves *c, const char *info,
                  char *err, size_t err_size);
int cv_write_obj(const char *path, const cv_curves *c, char *err,
                 size_t err_size);
/* Scale every point by s (file units to metres). */
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
    memset(c, 0, sizeof *c);
}

void cv_scale(cv_curves *c, float s)
{
    long i;
    for (i = 0; i < 3L * c->total; ++i) c->xyz[i] *= s;
}

/* Allocate count curves and total points (rgb too if asked). */
static int cv__alloc(cv_curves *c, long count, long total, int rgb, char *err,
                     size_t n)
{
    memset(c, 0, sizeof *c);
    c->points = (int *)malloc(sizeof(int) * (size_t)(count > 0 ? count : 1));
    c->xyz = (float *)malloc(sizeof(float) * 3u * (size_t)(total > 0 ? total : 1));
    if (rgb) c->rgb = (float *)malloc(sizeof(float) * 3u * (size_t)(total > 0 ? total : 1));
    if (!c->points || !c->xyz || (rgb && !c->rgb)) {
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
    size_t need, at = 128;
    long i, sum = 0;
    char m[160];
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
    /* the arrays' sizes, then the file's */
    need = 128 + ((flags & 1) ? 2u * strands : 0) + 12u * (size_t)points +
           ((flags & 4) ? 4u * (size_t)points : 0) +
           ((flags & 8) ? 4u * (size_t)points : 0) +
           ((flags & 16) ? 12u * (size_t)points : 0);
    if (size < need) {
        snprintf(m, sizeof m, ".hair: truncated: %lu bytes, the header promises "
                 "%lu", (unsigned long)size, (unsigned long)need);
        return cv__fail(err, n, m);
    }
    for (i = 0; i < (long)strands; ++i) {
        long seg = (flags & 1) ? (long)(d[at + 2 * i] | d[at + 2 * i + 1] << 8)
                               : (long)defseg;
        if (seg < 1) {
            snprintf(m, sizeof m, ".hair: strand %ld has no segment", i);
            return cv__fail(err, n, m);
        }
        sum += seg + 1;
    }
    if (sum != (long)points) {
        snprintf(m, sizeof m, ".hair: the strands' segments make %ld points, the "
                 "header says %lu", sum, (unsigned long)points);
        return cv__fail(err, n, m);
    }
    if (!cv__alloc(c, strands, points, (flags & 16) != 0, err, n)) return 0;
    for (i = 0; i < (long)strands; ++i)
        c->points[i] = 1 + ((flags & 1) ? (int)(d[at + 2 * i] | d[at + 2 * i + 1] << 8)
                                        : (int)defseg);
    if (flags & 1) at += 2u * strands;
    for (i = 0; i < 3L * points; ++i) c->xyz[i] = cv__f32(d + at + 4 * i);
    at += 12u * (size_t)points;
    if (flags & 4) at += 4u * (size_t)points;
    if (flags & 8) at += 4u * (size_t)points;
    if (flags & 16)
        for (i = 0; i < 3L * points; ++i) c->rgb[i] = cv__f32(d + at + 4 * i);
    if (!cv__finite(c, err, n)) {
        cv_free(c);
        return 0;
    }
    return 1;
}

/* TressFX .tfx, version 4: float version, uint32 strands, uint32 vertices
   per strand, then uint32 byte offsets (positions, strand UVs, vertex UVs,
   strand thickness, vertex colours; 0 = absent) and 32 reserved words:
   positions at byte 160 as written by TressFX's exporter, float4 per
   vertex (xyz, inverse mass), strand after strand. */
int cv_parse_tfx(const unsigned char *d, size_t size, cv_curves *c, char *err,
                 size_t n)
{
    uint32_t strands, per, off;
    float version;
    size_t bytes;
    long s, j;
    char m[160];
    memset(c, 0, sizeof *c);
    if (size < 32) return cv__fail(err, n, ".tfx: shorter than its header");
    version = cv__f32(d);
    strands = cv__u32(d + 4);
    per = cv__u32(d + 8);
    off = cv__u32(d + 12);
    if (!(version >= 4.0f && version < 5.0f)) {
        snprintf(m, sizeof m, ".tfx: version %g; this reader knows version 4",
                 (double)version);
        return cv__fail(err, n, m);
    }
    if (strands == 0 || strands > CV_MAX_CURVES || per < 2 || per > 4096 ||
        (unsigned long long)strands * per > CV_MAX_POINTS) {
        snprintf(m, sizeof m, ".tfx: %lu strands of %lu vertices (1 .. %d "
                 "strands of 2 .. 4096)", (unsigned long)strands,
                 (unsigned long)per, CV_MAX_CURVES);
        return cv__fail(err, n, m);
    }
    if (off == 0) return cv__fail(err, n, ".tfx: no positions (offset 0)");
    bytes = 16u * (size_t)strands * per;
    if (off > size || size - off < bytes) {
        snprintf(m, sizeof m, ".tfx: truncated: positions at byte %lu need %lu "
                 "bytes, the file has %lu", (unsigned long)off,
                 (unsigned long)bytes, (unsigned long)size);
        return cv__fail(err, n, m);
    }
    if (!cv__alloc(c, strands, (long)strands * per, 0, err, n)) return 0;
    for (s = 0; s < (long)strands; ++s) {
        c->points[s] = (int)per;
        for (j = 0; j < (long)per; ++j) {
            const unsigned char *p = d + off + 16u * ((size_t)s * per + (size_t)j);
            float *o = c->xyz + 3 * ((size_t)s * per + (size_t)j);
            o[0] = cv__f32(p);
            o[1] = cv__f32(p + 4);
            o[2] = cv__f32(p + 8);
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
/* OBJ polylines through assimp: every line primitive; consecutive
   two-point lines where one starts at the point the previous one ended
   (the same position) are chained into one polyline: assimp hands an
   `l a b c` line over as segments, and exporters write `l a b` per
   segment. */
int cv_read_obj(const char *path, cv_curves *c, char *err, size_t n)
{
    const struct aiScene *sc = aiImportFile(path, 0);
    unsigned mi, f;
    long curves = 0, total = 0, pass;
    char m[512];
    memset(c, 0, sizeof *c);
    if (!sc) {
        snprintf(m, sizeof m, "%s: %s", path, aiGetErrorString());
        return cv__fail(err, n, m);
    }
    /* two passes: count, then fill */
    for (pass = 0; pass < 2; ++pass) {
        long ci = 0, pi = 0;
        for (mi = 0; mi < sc->mNumMeshes; ++mi) {
            const struct aiMesh *me = sc->mMeshes[mi];
            int have_end = 0;
            struct aiVector3D last_end = {0, 0, 0};
            if (!(me->mPrimitiveTypes & aiPrimitiveType_LINE)) continue;
            for (f = 0; f < me->mNumFaces; ++f) {
                const struct aiFace *fa = &me->mFaces[f];
                unsigned k, first = 0;
                if (fa->mNumIndices < 2 || fa->mIndices[0] >= me->mNumVertices ||
                    fa->mIndices[fa->mNumIndices - 1] >= me->mNumVertices)
                    continue;
                if (fa->mNumIndices == 2 && have_end && ci > 0 &&
                    me->mVertices[fa->mIndices[0]].x == last_end.x &&
                    me->mVertices[fa->mIndices[0]].y == last_end.y &&
                    me->mVertices[fa->mIndices[0]].z == last_end.z) {
                    first = 1; /* continues the previous polyline */
                } else {
                    if (pass) c->points[ci] = 0;
                    ++ci;
                }
                for (k = first; k < fa->mNumIndices; ++k) {
                    unsigned v = fa->mIndices[k];
                    if (v >= me->mNumVertices) continue;
                    if (pass) {
                        c->xyz[3 * pi] = me->mVertices[v].x;
                        c->xyz[3 * pi + 1] = me->mVertices[v].y;
                        c->xyz[3 * pi + 2] = me->mVertices[v].z;
                        ++c->points[ci - 1];
                    }
                    ++pi;
                }
                have_end = 1;
                last_end = me->mVertices[fa->mIndices[fa->mNumIndices - 1]];
            }
        }
        if (!pass) {
            curves = ci;
            total = pi;
            if (curves == 0) {
                aiReleaseImport(sc);
                snprintf(m, sizeof m, "%s: no polylines (`l` lines) in the file", path);
                return cv__fail(err, n, m);
            }
            if (curves > CV_MAX_CURVES || total > CV_MAX_POINTS) {
                aiReleaseImport(sc);
                return cv__fail(err, n, "too many polylines or points");
            }
            if (!cv__alloc(c, curves, total, 0, err, n)) {
                aiReleaseImport(sc);
                return 0;
            }
        }
    }
    aiReleaseImport(sc);
    {
        long i;
        for (i = 0; i < c->count; ++i)
            if (c->points[i] < 2) {
                snprintf(m, sizeof m, "%s: polyline %ld has %d point", path, i,
                         c->points[i]);
                cv_free(c);
                return cv__fail(err, n, m);
            }
    }
    if (!cv__finite(c, err, n)) {
        cv_free(c);
        return 0;
    }
    return 1;
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

int cv_write_hair(const char *path, const cv_curves *c, const char *info,
                  char *err, size_t n)
{
    unsigned char h[128];
    FILE *f;
    long i;
    int ok = 1;
    char m[512];
    for (i = 0; i < c->count; ++i)
        if (c->points[i] < 2 || c->points[i] > 65536)
            return cv__fail(err, n, ".hair: a strand has fewer than 2 or more "
                            "than 65536 points");
    memset(h, 0, sizeof h);
    memcpy(h, "HAIR", 4);
    cv__put_u32(h + 4, (uint32_t)c->count);
    cv__put_u32(h + 8, (uint32_t)c->total);
    cv__put_u32(h + 12, 1u | 2u | (c->rgb ? 16u : 0u));
    cv__put_u32(h + 16, (uint32_t)(c->count ? c->points[0] - 1 : 1));
    cv__put_f32(h + 20, 1.0f);  /* default thickness */
    cv__put_f32(h + 24, 0.0f);  /* default transparency */
    cv__put_f32(h + 28, 1.0f);
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
    for (i = 0; ok && i < 3L * c->total; ++i) {
        unsigned char b[4];
        cv__put_f32(b, c->xyz[i]);
        ok = fwrite(b, 1, 4, f) == 4;
    }
    for (i = 0; ok && c->rgb && i < 3L * c->total; ++i) {
        unsigned char b[4];
        cv__put_f32(b, c->rgb[i]);
        ok = fwrite(b, 1, 4, f) == 4;
    }
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
