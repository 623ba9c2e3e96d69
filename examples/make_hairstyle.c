/* make_hairstyle.c - author a hairstyle as guide curves on a mesh, the way
   a groom starts in a DCC tool, and save it as .hair or OBJ polylines.

   Roots are --curves points spread over the mesh's triangles by area
   (seeded), kept in front of every --plane (the scalp, as paint_density
   paints it). Each curve
   leaves the scalp along the normal, turns towards --fall (back and down
   for hair combed back; where that points into the head, its part along
   the head) over its first eighth, stays --lift above a sphere
   fitted to the grown part (so it lies over the head instead of through
   it), and waves sideways with --wave amplitude. The curves are written in
   the file's own units and pose (the first frame of --anim), so they fit
   the mesh they were made on: the viewer reads them back with --guides.

     make_hairstyle --mesh FILE --part NAME --plane NX,NY,NZ,D
                    [--anim NAME] [--curves N] [--length M] [--fall X,Y,Z]
                    [--lift M] [--wave M] [--points N] --out FILE.hair|.obj

   Build: make examples (needs libassimp-dev). */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"
#define CHARACTER_IMPLEMENTATION
#include "character.h"
#define CURVES_IMPLEMENTATION
#include "curves.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MH_MAX_PLANES 8

static void usage(FILE *fp)
{
    fprintf(fp,
"usage: make_hairstyle --mesh FILE --plane NX,NY,NZ,D --out FILE.hair|.obj\n"
"  --mesh FILE      the mesh (any format assimp reads)\n"
"  --part NAME      grow on this mesh of the file (default: all)\n"
"  --anim NAME      pose: the first frame of this animation (default: the\n"
"                   file's first animation, as the viewer grows on it)\n"
"  --unit U         auto (default), m, cm, mm or metres per file unit\n"
"  --plane N,N,N,D  roots where dot(normalize(N), p) >= D (metres); up to %d\n"
"  --curves N       about this many curves (default 400)\n"
"  --length M       curve length, metres (default 0.3)\n"
"  --fall X,Y,Z     direction the hair turns to (default 0,-0.5,-1: back,\n"
"                   down; the face is +z)\n"
"  --lift M         distance kept above the head's sphere (default 0.012)\n"
"  --wave M         sideways wave amplitude, metres (default 0.006)\n"
"  --points N       points per curve (default 24)\n"
"  --out FILE       .hair (Cem Yuksel's format) or .obj (polylines)\n",
            MH_MAX_PLANES);
}

static int parse_floats(const char *v, int n, float *out)
{
    const char *s = v;
    char *end;
    int k;
    for (k = 0; k < n; ++k) {
        double x = strtod(s, &end);
        if (end == s || !isfinite(x)) return 0;
        out[k] = (float)x;
        s = end;
        if (k < n - 1) {
            if (*s != ',') return 0;
            ++s;
        }
    }
    return *s == '\0';
}

static int parse_pos(const char *v, double lo, double hi, float *out)
{
    char *end;
    double x = strtod(v, &end);
    if (end == v || *end || !isfinite(x) || x < lo || x > hi) return 0;
    *out = (float)x;
    return 1;
}

static void norm3(float *v)
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0f) { v[0] /= l; v[1] /= l; v[2] /= l; }
}

/* The command line: every option's value, the defaults where not given. */
typedef struct mh_options {
    const char *mesh, *part, *anim, *unit, *out;
    float planes[MH_MAX_PLANES][4], fall[3];
    float want, length, lift, wave, P;
    int np;
} mh_options;

/* The command line into *m: -1 to go on, else the exit code (0 after
   --help, 2 for a bad argument, said why). */
static int parse_args(int argc, char **argv, mh_options *m)
{
    int i, k;
    memset(m, 0, sizeof *m);
    m->fall[1] = -0.5f;
    m->fall[2] = -1.0f;
    m->want = 400;
    m->length = 0.3f;
    m->lift = 0.012f;
    m->wave = 0.006f;
    m->P = 24;
    for (i = 1; i < argc; ++i) {
        const char *o = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        int ok = 1;
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
            usage(stdout);
            return 0;
        }
        if (!val) {
            fprintf(stderr, "make_hairstyle: %s needs a value (--help)\n", o);
            return 2;
        }
        ++i;
        if (!strcmp(o, "--mesh")) m->mesh = val;
        else if (!strcmp(o, "--part")) m->part = val;
        else if (!strcmp(o, "--anim")) m->anim = val;
        else if (!strcmp(o, "--unit")) m->unit = val;
        else if (!strcmp(o, "--out")) m->out = val;
        else if (!strcmp(o, "--plane")) {
            float *pl = m->planes[m->np];
            ok = m->np < MH_MAX_PLANES && parse_floats(val, 4, pl);
            if (ok) {
                float l = sqrtf(pl[0] * pl[0] + pl[1] * pl[1] + pl[2] * pl[2]);
                ok = l > 0.0f;
                for (k = 0; ok && k < 4; ++k) pl[k] /= l;
                ++m->np;
            }
        } else if (!strcmp(o, "--fall")) ok = parse_floats(val, 3, m->fall);
        else if (!strcmp(o, "--curves")) ok = parse_pos(val, 1, 1e6, &m->want);
        else if (!strcmp(o, "--length")) ok = parse_pos(val, 1e-4, 100, &m->length);
        else if (!strcmp(o, "--lift")) ok = parse_pos(val, 0, 10, &m->lift);
        else if (!strcmp(o, "--wave")) ok = parse_pos(val, 0, 10, &m->wave);
        else if (!strcmp(o, "--points")) ok = parse_pos(val, 2, 1000, &m->P);
        else {
            fprintf(stderr, "make_hairstyle: unknown option %s (--help)\n", o);
            return 2;
        }
        if (!ok) {
            fprintf(stderr, "make_hairstyle: %s '%s': not a valid value "
                    "(--help)\n", o, val);
            return 2;
        }
    }
    if (!m->mesh || !m->out || m->np == 0) {
        usage(stderr);
        return 2;
    }
    norm3(m->fall);
    return -1;
}

/* The grown part's sphere: centroid and mean distance of its vertices
   (part p, or the whole mesh for -1). */
static void part_sphere(const ch_character *c, int p, const ch_vertex *v,
                        double centre[3], double *radius)
{
    int lo = p >= 0 ? c->parts[p].first_vertex : 0;
    int hi = p >= 0 ? lo + c->parts[p].vertex_count : c->vertex_count;
    int i, k, counted = 0;
    for (i = lo; i < hi; ++i, ++counted)
        for (k = 0; k < 3; ++k) centre[k] += v[i].pos[k];
    for (k = 0; k < 3; ++k) centre[k] /= counted;
    for (i = lo; i < hi; ++i) {
        double d = 0.0;
        for (k = 0; k < 3; ++k)
            d += (v[i].pos[k] - centre[k]) * (v[i].pos[k] - centre[k]);
        *radius += sqrt(d) / counted;
    }
}

/* The roots: --curves points spread over the part's triangles by area
   (seeded), kept where they are in front of every plane; their count,
   or -1 when out of memory. */
static int place_roots(const mh_options *m, const ch_character *c, int p,
                       const ch_vertex *v, float *rootpos, float *rootnrm)
{
    const int t0 = p >= 0 ? c->parts[p].first_triangle : 0;
    const int nt = p >= 0 ? c->parts[p].triangle_count : c->triangle_count;
    double *cum = (double *)malloc(sizeof(double) * (size_t)(nt + 1));
    long tries = 0, max_tries = 50L * (long)m->want + 1000;
    int t, k, roots = 0, n = (int)m->want;
    hf_rng rng;
    if (!cum) return -1;
    cum[0] = 0.0;
    for (t = 0; t < nt; ++t) {
        const float *A = v[c->indices[3 * (t0 + t)]].pos,
                    *B = v[c->indices[3 * (t0 + t) + 1]].pos,
                    *C = v[c->indices[3 * (t0 + t) + 2]].pos;
        double e1[3], e2[3], x0, y0, z0;
        for (k = 0; k < 3; ++k) { e1[k] = B[k] - A[k]; e2[k] = C[k] - A[k]; }
        x0 = e1[1] * e2[2] - e1[2] * e2[1];
        y0 = e1[2] * e2[0] - e1[0] * e2[2];
        z0 = e1[0] * e2[1] - e1[1] * e2[0];
        cum[t + 1] = cum[t] + 0.5 * sqrt(x0 * x0 + y0 * y0 + z0 * z0);
    }
    hf_rng_seed(&rng, 1, 0);
    while (roots < n && tries++ < max_tries && cum[nt] > 0.0) {
        double x = hf_rng_float(&rng) * cum[nt];
        int lo2 = 0, hi2 = nt, in = 1;
        float b0 = hf_rng_float(&rng), b1 = hf_rng_float(&rng), q[3], nn[3];
        const ch_vertex *A, *B, *C;
        while (hi2 - lo2 > 1) { /* the triangle holding x */
            int mid = (lo2 + hi2) / 2;
            if (cum[mid] <= x) lo2 = mid; else hi2 = mid;
        }
        if (b0 + b1 > 1.0f) { b0 = 1.0f - b0; b1 = 1.0f - b1; }
        A = &v[c->indices[3 * (t0 + lo2)]];
        B = &v[c->indices[3 * (t0 + lo2) + 1]];
        C = &v[c->indices[3 * (t0 + lo2) + 2]];
        for (k = 0; k < 3; ++k) {
            q[k] = A->pos[k] + b0 * (B->pos[k] - A->pos[k]) +
                   b1 * (C->pos[k] - A->pos[k]);
            nn[k] = A->normal[k] + b0 * (B->normal[k] - A->normal[k]) +
                    b1 * (C->normal[k] - A->normal[k]);
        }
        for (k = 0; k < m->np && in; ++k)
            in = m->planes[k][0] * q[0] + m->planes[k][1] * q[1] +
                 m->planes[k][2] * q[2] >= m->planes[k][3];
        if (!in) continue;
        norm3(nn);
        memcpy(rootpos + 3 * roots, q, sizeof q);
        memcpy(rootnrm + 3 * roots, nn, sizeof nn);
        ++roots;
    }
    free(cum);
    return roots;
}

/* One curve of P points from root x along normal rn, combed towards the
   fall, waved sideways, and lifted over the part's sphere. */
static void comb_curve(const mh_options *m, const double centre[3],
                       double radius, const float *root, const float *rn,
                       float *xyz)
{
    const float P = m->P, *fall = m->fall;
    float x[3], d[3], side[3];
    int j, k;
    memcpy(x, root, sizeof x);
    memcpy(d, rn, sizeof d);
    /* sideways: across the fall direction, for the wave */
    side[0] = d[1] * fall[2] - d[2] * fall[1];
    side[1] = d[2] * fall[0] - d[0] * fall[2];
    side[2] = d[0] * fall[1] - d[1] * fall[0];
    norm3(side);
    for (j = 0; j < (int)P; ++j) {
        float *o = xyz + 3 * (size_t)j;
        float t = (float)j / (P - 1), w = m->wave * sinf(t * 18.85f) * t;
        double r2 = 0.0, r;
        for (k = 0; k < 3; ++k) o[k] = x[k] + w * side[k];
        if (j + 1 == (int)P) break;
        /* turn towards the fall over the first eighth; where the fall
           points into the head, towards its part along the head (so hair
           over the forehead goes up and back over the top, as combed,
           instead of down over the face) */
        {
            float s = t * 8.0f > 1.0f ? 1.0f : t * 8.0f, nd[3], f[3], rh[3], fr;
            for (k = 0; k < 3; ++k) rh[k] = (float)(x[k] - centre[k]);
            norm3(rh);
            fr = fall[0] * rh[0] + fall[1] * rh[1] + fall[2] * rh[2];
            for (k = 0; k < 3; ++k)
                f[k] = fall[k] - (fr < 0.0f ? fr : 0.0f) * rh[k];
            norm3(f);
            for (k = 0; k < 3; ++k) nd[k] = (1.0f - s) * rn[k] + s * f[k];
            norm3(nd);
            for (k = 0; k < 3; ++k) d[k] = 0.5f * d[k] + 0.5f * nd[k];
            norm3(d);
        }
        for (k = 0; k < 3; ++k) x[k] += d[k] * m->length / (P - 1);
        /* over the head, not through it */
        for (k = 0; k < 3; ++k) r2 += (x[k] - centre[k]) * (x[k] - centre[k]);
        r = sqrt(r2);
        if (r < radius + m->lift && r > 0.0)
            for (k = 0; k < 3; ++k)
                x[k] = (float)(centre[k] + (x[k] - centre[k]) *
                                               (radius + m->lift) / r);
    }
}

int main(int argc, char **argv)
{
    mh_options m;
    int i, p, a, roots, rc;
    float *rootpos, *rootnrm;
    ch_character c;
    ch_vertex *v;
    cv_curves cv;
    char err[512];
    double centre[3] = {0, 0, 0}, radius = 0.0;
    const char *out;

    if ((rc = parse_args(argc, argv, &m)) >= 0) return rc;
    out = m.out;
    if (!ch_load(&c, m.mesh, m.unit, err, sizeof err)) {
        fprintf(stderr, "make_hairstyle: %s\n", err);
        return 1;
    }
    p = m.part ? ch_find_part(&c, m.part) : -1;
    if (m.part && p < 0) {
        fprintf(stderr, "make_hairstyle: %s has no mesh '%s'\n", m.mesh, m.part);
        return 1;
    }
    a = ch_find_animation(&c, m.anim);
    if (m.anim && a < 0) {
        fprintf(stderr, "make_hairstyle: %s has no animation '%s'\n", m.mesh,
                m.anim);
        return 1;
    }
    v = (ch_vertex *)malloc(sizeof(ch_vertex) * (size_t)c.vertex_count);
    if (!v) return 1;
    ch_pose(&c, a, 0.0, v, NULL);
    part_sphere(&c, p, v, centre, &radius);
    rootpos = (float *)malloc(sizeof(float) * 3u * (size_t)(int)m.want);
    rootnrm = (float *)malloc(sizeof(float) * 3u * (size_t)(int)m.want);
    if (!rootpos || !rootnrm) return 1;
    if ((roots = place_roots(&m, &c, p, v, rootpos, rootnrm)) < 0) return 1;
    if (roots == 0) {
        fprintf(stderr, "make_hairstyle: no point of %s is in front of "
                "every plane\n", m.part ? m.part : m.mesh);
        return 1;
    }
    memset(&cv, 0, sizeof cv);
    cv.count = roots;
    cv.total = roots * (int)m.P;
    cv.points = (int *)malloc(sizeof(int) * (size_t)roots);
    cv.xyz = (float *)malloc(sizeof(float) * 3u * (size_t)cv.total);
    if (!cv.points || !cv.xyz) return 1;
    for (i = 0; i < roots; ++i) {
        cv.points[i] = (int)m.P;
        comb_curve(&m, centre, radius, rootpos + 3 * i, rootnrm + 3 * i,
                   cv.xyz + 3 * (size_t)i * (size_t)m.P);
    }
    cv_scale(&cv, 1.0f / c.unit); /* back to the file's units */
    if (!(strlen(out) > 4 && !strcmp(out + strlen(out) - 4, ".obj")
              ? cv_write_obj(out, &cv, err, sizeof err)
              : cv_write_hair(out, &cv, "hairfur make_hairstyle", err, sizeof err))) {
        fprintf(stderr, "make_hairstyle: %s\n", err);
        return 1;
    }
    printf("make_hairstyle: wrote %s: %d curves of %d points, %.3g m long\n",
           out, cv.count, (int)m.P, (double)m.length);
    cv_free(&cv);
    free(v);
    free(rootpos);
    free(rootnrm);
    ch_free(&c);
    return 0;
}
