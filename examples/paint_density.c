/* paint_density.c - paint a density map for a mesh from planes: density 1
   on the part of the surface in front of every plane, 0 elsewhere, with a
   soft edge. How the demo makes the human's scalp (no artist painted one):
   one plane tilted so that the hairline runs from the forehead down to the
   nape.

     paint_density --mesh FILE [--part NAME] --plane NX,NY,NZ,D
                   [--plane ...] [--soft M] [--size N] --out FILE.png

   A point p (metres, the file's pose, after the unit of --unit) has hair
   where NX*px + NY*py + NZ*pz >= D for every plane, the normal (NX, NY, NZ)
   normalised first; density ramps from 0 to 1 over --soft metres (default
   0.01) past the plane. Where triangles share texels (overlapping or
   mirrored UVs) the least density wins. The map is painted in the mesh's UV space (first
   channel), grown by two texels past every triangle so bilinear lookups
   at UV seams see the right value, and written with its top row at v = 1
   (as hf_map reads it after the flip the viewer and grow_fur do).

   Build: make examples (needs libassimp-dev and libstb-dev). */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"
#define CHARACTER_IMPLEMENTATION
#include "character.h"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PD_MAX_PLANES 8

static void usage(FILE *fp)
{
    fprintf(fp,
"usage: paint_density --mesh FILE --plane NX,NY,NZ,D [--plane ...] --out PNG\n"
"  --mesh FILE      the mesh (any format assimp reads); its first UV channel\n"
"  --part NAME      paint only this mesh of the file (default: all)\n"
"  --unit U         auto (default), m, cm, mm or metres per file unit, as the\n"
"                   viewer reads it\n"
"  --plane N,N,N,D  keep points p with dot(normalize(N), p) >= D (metres); up\n"
"                   to %d planes, all must hold\n"
"  --soft M         width of the soft edge, metres (default 0.01)\n"
"  --size N         map size in texels (default 256)\n"
"  --out FILE.png   the map: one channel, top row = v 1\n", PD_MAX_PLANES);
}

static int parse_plane(const char *v, float p[4])
{
    char *end;
    const char *s = v;
    int k;
    for (k = 0; k < 4; ++k) {
        double x = strtod(s, &end);
        if (end == s || !isfinite(x)) return 0;
        p[k] = (float)x;
        s = end;
        if (k < 3) {
            if (*s != ',') return 0;
            ++s;
        }
    }
    if (*s) return 0;
    {
        float l = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if (!(l > 0.0f)) return 0;
        for (k = 0; k < 4; ++k) p[k] /= l;
    }
    return 1;
}

static float density_at(const float *pos, const float (*planes)[4], int n,
                        float soft)
{
    float d = 1.0f;
    int i;
    for (i = 0; i < n; ++i) {
        float s = (planes[i][0] * pos[0] + planes[i][1] * pos[1] +
                   planes[i][2] * pos[2] - planes[i][3]) / soft;
        s = s < 0.0f ? 0.0f : s > 1.0f ? 1.0f : s;
        s = s * s * (3.0f - 2.0f * s);
        if (s < d) d = s;
    }
    return d;
}

/* Rasterise one triangle in UV space: each texel centre inside (grown by
   `grow` texels) takes the density at its barycentric 3D point. */
static void paint_triangle(unsigned char *px, unsigned char *set, int N,
                           const ch_vertex *v0, const ch_vertex *v1,
                           const ch_vertex *v2, const float (*planes)[4],
                           int np, float soft, float grow)
{
    float x0 = v0->uv[0] * N, y0 = v0->uv[1] * N, x1 = v1->uv[0] * N,
          y1 = v1->uv[1] * N, x2 = v2->uv[0] * N, y2 = v2->uv[1] * N;
    float area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    int xa, xb, ya, yb, x, y, k;
    if (fabsf(area) < 1e-12f) return;
    xa = (int)floorf(fminf(x0, fminf(x1, x2)) - grow);
    xb = (int)ceilf(fmaxf(x0, fmaxf(x1, x2)) + grow);
    ya = (int)floorf(fminf(y0, fminf(y1, y2)) - grow);
    yb = (int)ceilf(fmaxf(y0, fmaxf(y1, y2)) + grow);
    if (xa < 0) xa = 0;
    if (ya < 0) ya = 0;
    if (xb > N - 1) xb = N - 1;
    if (yb > N - 1) yb = N - 1;
    for (y = ya; y <= yb; ++y)
        for (x = xa; x <= xb; ++x) {
            float px_ = x + 0.5f, py_ = y + 0.5f, b[3], p[3], e = grow / 2.0f;
            b[0] = ((x1 - px_) * (y2 - py_) - (x2 - px_) * (y1 - py_)) / area;
            b[1] = ((x2 - px_) * (y0 - py_) - (x0 - px_) * (y2 - py_)) / area;
            b[2] = 1.0f - b[0] - b[1];
            /* inside, or within `grow` texels (roughly) of an edge */
            if (b[0] < -e || b[1] < -e || b[2] < -e) continue;
            for (k = 0; k < 3; ++k) {
                float w = b[k] < 0.0f ? 0.0f : b[k];
                b[k] = w;
            }
            {
                float s = b[0] + b[1] + b[2];
                int inside = b[0] > 0.0f && b[1] > 0.0f && b[2] > 0.0f;
                unsigned char val;
                for (k = 0; k < 3; ++k)
                    p[k] = (b[0] * v0->pos[k] + b[1] * v1->pos[k] +
                            b[2] * v2->pos[k]) / s;
                val = (unsigned char)(255.0f * density_at(p, planes, np, soft) + 0.5f);
                /* a texel inside a triangle wins over one grown into;
                   where triangles overlap in UV space (shared or
                   mirrored UVs) the least density wins: hair only where
                   every surface on that texel wants it */
                unsigned char *st = &set[y * N + x], *d = &px[y * N + x];
                int level = inside ? 2 : 1;
                if (*st < level) {
                    *d = val;
                    *st = (unsigned char)level;
                } else if (*st == level && val < *d) {
                    *d = val;
                }
            }
        }
}

int main(int argc, char **argv)
{
    const char *mesh = NULL, *part = NULL, *out = NULL, *unit = NULL;
    float planes[PD_MAX_PLANES][4], soft = 0.01f;
    int np = 0, N = 256, i, p, t;
    ch_character c;
    ch_vertex *v;
    unsigned char *px, *set, *flipped;
    char err[512];
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        if (!val) {
            fprintf(stderr, "paint_density: %s needs a value (--help)\n", a);
            return 2;
        }
        ++i;
        if (!strcmp(a, "--mesh")) mesh = val;
        else if (!strcmp(a, "--part")) part = val;
        else if (!strcmp(a, "--unit")) unit = val;
        else if (!strcmp(a, "--out")) out = val;
        else if (!strcmp(a, "--plane")) {
            if (np == PD_MAX_PLANES || !parse_plane(val, planes[np])) {
                fprintf(stderr, "paint_density: --plane '%s': expected "
                        "NX,NY,NZ,D with a non-zero normal (at most %d)\n",
                        val, PD_MAX_PLANES);
                return 2;
            }
            ++np;
        } else if (!strcmp(a, "--soft")) {
            char *end;
            soft = (float)strtod(val, &end);
            if (end == val || *end || !(soft > 0.0f) || !(soft < 1e6f)) {
                fprintf(stderr, "paint_density: --soft '%s': expected metres "
                        "> 0\n", val);
                return 2;
            }
        } else if (!strcmp(a, "--size")) {
            char *end;
            long n = strtol(val, &end, 10);
            if (end == val || *end || n < 2 || n > 8192) {
                fprintf(stderr, "paint_density: --size '%s': expected 2 .. "
                        "8192\n", val);
                return 2;
            }
            N = (int)n;
        } else {
            fprintf(stderr, "paint_density: unknown option %s (--help)\n", a);
            return 2;
        }
    }
    if (!mesh || !out || np == 0) {
        usage(stderr);
        return 2;
    }
    if (!ch_load(&c, mesh, unit, err, sizeof err)) {
        fprintf(stderr, "paint_density: %s\n", err);
        return 1;
    }
    if (part && ch_find_part(&c, part) < 0) {
        fprintf(stderr, "paint_density: %s has no mesh '%s'; it has:", mesh, part);
        for (p = 0; p < c.part_count; ++p) fprintf(stderr, " %s", c.parts[p].name);
        fprintf(stderr, "\n");
        ch_free(&c);
        return 1;
    }
    v = (ch_vertex *)malloc(sizeof(ch_vertex) * (size_t)c.vertex_count);
    px = (unsigned char *)calloc((size_t)N * (size_t)N, 1);
    set = (unsigned char *)calloc((size_t)N * (size_t)N, 1);
    flipped = (unsigned char *)malloc((size_t)N * (size_t)N);
    if (!v || !px || !set || !flipped) {
        fprintf(stderr, "paint_density: out of memory\n");
        return 1;
    }
    ch_pose(&c, -1, 0.0, v, NULL);
    for (p = 0; p < c.part_count; ++p) {
        const ch_part *pt = &c.parts[p];
        if (part && strcmp(pt->name, part)) continue;
        if (!pt->has_uvs) {
            fprintf(stderr, "paint_density: %s: mesh '%s' has no texture "
                    "coordinates to paint in\n", mesh, pt->name);
            return 1;
        }
        for (t = pt->first_triangle; t < pt->first_triangle + pt->triangle_count; ++t)
            paint_triangle(px, set, N, &v[c.indices[3 * t]],
                           &v[c.indices[3 * t + 1]], &v[c.indices[3 * t + 2]],
                           (const float (*)[4])planes, np, soft, 2.0f);
    }
    for (i = 0; i < N; ++i) /* row 0 is v = 0; a PNG's first row is the top */
        memcpy(flipped + (size_t)i * (size_t)N, px + (size_t)(N - 1 - i) * (size_t)N,
               (size_t)N);
    if (!stbi_write_png(out, N, N, 1, flipped, N)) {
        fprintf(stderr, "paint_density: cannot write %s\n", out);
        return 1;
    }
    {
        long hair = 0;
        for (i = 0; i < N * N; ++i) hair += set[i] && px[i] > 127;
        printf("paint_density: wrote %s (%d x %d, %ld texels with hair)\n", out,
               N, N, hair);
    }
    free(v);
    free(px);
    free(set);
    free(flipped);
    ch_free(&c);
    return 0;
}
