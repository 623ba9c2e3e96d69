/* grow_fur.c - grow fur on a mesh, swing it, and export the ribbons.

   Shows the whole CPU pipeline through the hf_fur object: growth at
   creation (tessellation, guides, placement, maps), then per frame roots
   from the "skinned" mesh, rope simulation with colliders, LOD, guide and
   strand interpolation, and camera-facing ribbons with their index buffer.

   Usage (grow_fur --help lists every option with its unit and default):
     grow_fur [--mesh FILE] [--density PNG] [--length PNG] [--color PNG]
              [--estimator area|edges|corners]
              [--strands N] [--guides N | --tess-factor F] [--points N]
              [--length-max M] [--frames N] [--lod F] [--seed N]
              [--stiffness F] [--volume F] [--friction F] [--grid N]
              [--rest-from-gravity S]
              [--collider none|auto|sphere:X,Y,Z,R|capsule:X0,Y0,Z0,X1,Y1,Z1,R]...
              [--eye x,y,z]
              [--guides FILE.hair|.tfx|.obj]
              [--groom FILE.hair|.tfx|.obj [--guide-fraction F]]
              [--out FILE.obj [--curves] | FILE.ply | FILE.hair]

   Without --mesh it grows on the built-in head (examples/head_mesh.h: a
   sphere of radius 0.1 with a procedural hairline density map and a bangs
   length map). --mesh loads any format assimp reads (OBJ, glTF, FBX, ...)
   through examples/character.h: all its meshes are merged, posed at the
   first frame of its animation (node transforms, skinned meshes by their
   bones, as gl_marschner shows the file) in the file's units, its smooth
   normals (from the file, or made by assimp) are passed on, and the maps
   need its first UV channel (a map on a mesh without UVs is refused).
   Maps are PNG (or anything stb_image reads): density and length use
   their first channel, colour its RGB; the
   PNG's top row is v = 1, as in OpenGL (rows are flipped on load, since
   hf_map's row 0 is v = 0). --guides sets the LOD guide density from the
   mesh's area (see docs/grow.md). The head swings sideways (0.05 m at 1 Hz) and
   turns (+-25 degrees) for --frames frames of 1/60 s (after
   --rest-from-gravity seconds of draping at rest, if given), the guides
   pushed apart and dragged together by the hair around them (--volume,
   --friction: a grid of --grid^3 nodes each frame); the colliders
   (--collider, repeatable: spheres and capsules) follow the head. The last frame's ribbons, seen from
   --eye (default: in front of the mesh's bounding box), are
   written as OBJ (positions, texture coordinates (root u, root v) and
   faces) or binary PLY (positions, tangents as normals, colours),
   both of which Blender opens.

   Build: make examples (needs libassimp-dev and libstb-dev: make deps). */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"
#define HEAD_MESH_IMPLEMENTATION
#include "head_mesh.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image.h>
#define CURVES_IMPLEMENTATION
#include "curves.h"
#define CHARACTER_IMPLEMENTATION
#include "character.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <fcntl.h>  /* open: --out checked before the run */
#include <unistd.h> /* sysconf: the machine's memory */

/* a mesh vertex: position, normal, uv (examples/character.h's, which
   poses a file's meshes straight into them) */
typedef ch_vertex vtx;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n ? v[n / 2] : 0.0;
}

#define GF_DEFAULT_STRANDS 20000
#define GF_MAX_DEFAULT_GUIDES 2000
#define GF_MAX_COUNT (1 << 28)
#define GF_MAX_COLLIDERS 64
/* the ribbon buffer's floats a point: two vertices of position and
   tangent (24 bytes each, as run_frames writes them) */
#define GF_VBUF_FLOATS 12

/* One line per option: its unit and default. */
static void usage(FILE *fp)
{
    fprintf(fp,
"usage: grow_fur [options]; every option but --curves takes one value.\n"
"Lengths are in metres; a --mesh file's coordinates are read as metres\n"
"(\"mesh units\").\n"
"  --mesh FILE        mesh to grow on, any format assimp reads, all its meshes\n"
"                     merged, posed at the first frame of its animation (or\n"
"                     as its node tree has it) (default: the built-in head,\n"
"                     a sphere of radius 0.1 m with its own density, length\n"
"                     and colour maps)\n"
"  --density PNG      density map, channel 0, 0..255 = 0..1 (default: none,\n"
"                     density 1 everywhere; needs mesh UVs)\n"
"  --length PNG       length map, channel 0: strand length = map x --length-max\n"
"                     (default: none, every strand --length-max; needs UVs)\n"
"  --color PNG        colour map, RGB (default: none, white; needs UVs)\n"
"                     maps: PNG top row = v 1, as in OpenGL (bottom row = v 0)\n"
"  --estimator E      how a triangle's density is read from --density: area\n"
"                     (the exact mean of the texels it covers), edges (the\n"
"                     texels along its edges) or corners (3 bilinear samples:\n"
"                     fast, blind inside big triangles; UVs any range)\n"
"                     (default area)\n"
"  --strands N        strands grown, a count (default %d)\n"
"  --guides N         target guide count (pure guides at the mesh's welded\n"
"                     vertices + LOD guides); sets tess_factor from the mesh's\n"
"                     area (default: a tenth of --strands, at most %d)\n"
"  --groom FILE       a groom (.hair, .tfx, .obj polylines): its own strands\n"
"                     are drawn (--strands and the maps do not apply), a\n"
"                     --guide-fraction of them simulated; its roots move with\n"
"                     the head's motion\n"
"  --guide-fraction F of the groom's strands simulated, (0, 1] (default 0.1)\n"
"  --guides FILE      guide curves (.hair, .tfx, .obj polylines; in the\n"
"                     mesh's coordinates): their shapes become the guides'\n"
"                     rest shapes (lengths from the curves); a value that is\n"
"                     not a whole number is a file\n"
"  --tess-factor F    raw tess_factor instead of --guides, per square mesh unit:\n"
"                     triangles split while density x area x F > 1; 0 = pure\n"
"                     guides only (default: derived from --guides)\n"
"  --points N         points per strand, 2..%d (default 16)\n"
"  --length-max M     longest strand, metres (mesh units) (default 0.12)\n"
"  --frames N         frames simulated, 1/60 s each (default 120)\n"
"  --lod F            level of detail, (0, 1] (hf_fur_set_lod; 1 = every\n"
"                     strand drawn) (default 1)\n"
"  --seed N           random seed, a count >= 0 (default 1)\n",
            GF_DEFAULT_STRANDS, GF_MAX_DEFAULT_GUIDES, HF_MAX_POINTS);
    /* in two parts: ISO C's longest string literal is 4095 characters */
    fprintf(fp,
"  --stiffness F      how firmly the guides hold their rest shape: the global\n"
"                     shape stiffness at the root, [0, 1] per 1/60 s (F/15\n"
"                     at the tip) (default 0.3; 0: hair falls freely)\n"
"  --volume F         hair-hair repulsion, so hair keeps a volume: points\n"
"                     pushed from dense toward sparse hair at F g where the\n"
"                     density changes by the typical density across a grid\n"
"                     cell, [0, 100] (default 1; 0 = off)\n"
"  --friction F       hair-hair friction, so hair moves as a mass: the\n"
"                     fraction of a point's velocity difference to the hair\n"
"                     around it removed per 1/60 s, [0, 1] (default 0.2;\n"
"                     0 = off)\n"
"  --grid N           nodes along each axis of the hair-hair grid, 4..%d\n"
"                     (default 32; not made when --volume and --friction\n"
"                     are both 0)\n"
"  --keep-length N    1: every drawn strand keeps the segment lengths of its\n"
"                     grown shape, which blending guides that part and\n"
"                     clumping change (hf_fur_desc.keep_length); 0: the\n"
"                     plain blend (default 1)\n"
"  --rest-from-gravity S  seconds the hair hangs under gravity and the\n"
"                     colliders (the grid too) before the first frame; the\n"
"                     draped shape becomes the rest shape the stiffness\n"
"                     holds, [0, 600] (default 0: the grown shape); give\n"
"                     it (1 s is enough) when grown hair passes through a\n"
"                     collider, as long hair does through a body's: the\n"
"                     stiffness pulls such hair into it and it never rests\n"
"  --collider C       a collider the head carries, mesh units (metres);\n"
"                     repeat it for several (at most %d):\n"
"                       none     no collider (alone)\n"
"                       auto     a sphere at the bounding box centre, radius\n"
"                                0.97 x a quarter of the box's x width (the\n"
"                                built-in head: 0.97 x 0.1 at the origin)\n"
"                       sphere:X,Y,Z,R         centre, radius (X,Y,Z,R too)\n"
"                       capsule:X0,Y0,Z0,X1,Y1,Z1,R  segment ends, radius\n"
"                     (default: auto)\n"
"  --eye x,y,z        camera the ribbons face, mesh units (default: bounding\n"
"                     box centre + (0, 0, 2.5 x half the box diagonal))\n"
"  --out FILE         the last frame: .obj or .ply ribbons, or .hair curves\n"
"                     (the drawn strands with their colours; default fur.obj)\n"
"  --curves           with --out F.obj: the strands as OBJ polylines (`l`)\n"
"                     instead of ribbons\n"
"  --help             this list\n"
"Counts (N) accept 20000, 2e4 or 20k (k = 1000). Exit code 2: bad arguments.\n",
            HF_GRID_MAX_RESOLUTION, GF_MAX_COLLIDERS);
}

/* A count: an integer written as 20000, 2e4 or 20k (k = 1000), the whole
   string, in [lo, hi]. Prints a message naming the option and returns 0
   otherwise. */
static int parse_count(const char *opt, const char *v, long long lo,
                       long long hi, long long *out)
{
    char buf[64], *end;
    size_t n = strlen(v);
    double x, mult = 1.0;
    if (n == 0 || n >= sizeof buf || isspace((unsigned char)v[0])) goto bad;
    memcpy(buf, v, n + 1);
    if (buf[n - 1] == 'k' || buf[n - 1] == 'K') {
        mult = 1000.0;
        buf[--n] = '\0';
        if (n == 0) goto bad;
    }
    x = strtod(buf, &end);
    if (end == buf || *end != '\0' || !isfinite(x)) goto bad;
    x *= mult;
    if (x != floor(x)) {
        fprintf(stderr, "grow_fur: %s '%s': not a whole number\n", opt, v);
        return 0;
    }
    if (x < (double)lo || x > (double)hi) {
        fprintf(stderr, "grow_fur: %s '%s': out of range %lld..%lld\n", opt,
                v, lo, hi);
        return 0;
    }
    *out = (long long)x;
    return 1;
bad:
    fprintf(stderr,
            "grow_fur: %s '%s': not a count (write 20000, 2e4 or 20k)\n", opt,
            v);
    return 0;
}

/* A finite real number, the whole string, in [lo, hi]. */
static int parse_real(const char *opt, const char *v, double lo, double hi,
                      float *out)
{
    char *end;
    double x;
    if (!*v || isspace((unsigned char)v[0])) goto bad;
    x = strtod(v, &end);
    if (end == v || *end != '\0' || !isfinite(x)) goto bad;
    if (x < lo || x > hi) {
        fprintf(stderr, "grow_fur: %s '%s': out of range %g..%g\n", opt, v,
                lo, hi);
        return 0;
    }
    *out = (float)x;
    return 1;
bad:
    fprintf(stderr, "grow_fur: %s '%s': not a number\n", opt, v);
    return 0;
}

/* n comma-separated finite numbers within +-limit, from p to the end of
   the option's value v. The message names the field that is wrong, so a
   typo is found at once. */
static int parse_reals(const char *opt, const char *v, const char *p, int n,
                       double limit, float *out, const char *form)
{
    int k;
    for (k = 0; k < n; ++k) {
        size_t len = strcspn(p, ",");
        char buf[64], *end;
        double x;
        if (len == 0 || len >= sizeof buf) {
            fprintf(stderr, "grow_fur: %s '%s': field %d is %s "
                            "(expected %d numbers: %s)\n", opt, v, k + 1,
                    len ? "too long" : "empty", n, form);
            return 0;
        }
        memcpy(buf, p, len);
        buf[len] = '\0';
        x = strtod(buf, &end);
        if (isspace((unsigned char)buf[0]) || end == buf || *end != '\0' ||
            !isfinite(x)) {
            fprintf(stderr, "grow_fur: %s '%s': '%s' is not a number\n", opt,
                    v, buf);
            return 0;
        }
        if (fabs(x) > limit) {
            fprintf(stderr, "grow_fur: %s '%s': '%s' is beyond +-%g\n", opt,
                    v, buf, limit);
            return 0;
        }
        out[k] = (float)x;
        p += len;
        if (k + 1 < n) {
            if (*p != ',') {
                fprintf(stderr, "grow_fur: %s '%s': %d numbers given, %d "
                                "expected (%s)\n", opt, v, k + 1, n, form);
                return 0;
            }
            ++p;
        }
    }
    if (*p != '\0') {
        fprintf(stderr, "grow_fur: %s '%s': more than %d numbers (%s)\n",
                opt, v, n, form);
        return 0;
    }
    return 1;
}

/* One --collider shape: sphere:X,Y,Z,R, capsule:X0,Y0,Z0,X1,Y1,Z1,R or
   X,Y,Z,R (a sphere), within the ropes' coordinate range. */
static int parse_collider(const char *v, hf_collider *c)
{
    const char *form = "none, auto, sphere:X,Y,Z,R or "
                       "capsule:X0,Y0,Z0,X1,Y1,Z1,R";
    const char *p = v;
    float f[7];
    int n;
    memset(c, 0, sizeof *c);
    if (!strncmp(v, "capsule:", 8)) {
        c->type = HF_COLLIDER_CAPSULE;
        n = 7;
        p += 8;
    } else {
        c->type = HF_COLLIDER_SPHERE;
        n = 4;
        if (!strncmp(v, "sphere:", 7)) p += 7;
        else if (strchr(v, ':') || !strchr(v, ',')) {
            fprintf(stderr, "grow_fur: --collider '%s': unknown collider "
                            "(expected %s)\n", v, form);
            return 0;
        }
    }
    if (!parse_reals("--collider", v, p, n, HF_ROPE_MAX_COORD, f, form))
        return 0;
    memcpy(c->a, f, sizeof c->a);
    if (n == 7) memcpy(c->b, f + 3, sizeof c->b);
    c->radius = f[n - 1];
    if (!(c->radius > 0.0f)) {
        fprintf(stderr, "grow_fur: --collider '%s': the radius '%g' must be "
                        "positive\n", v, (double)c->radius);
        return 0;
    }
    return 1;
}

/* Every mesh of the scene merged into one interleaved buffer, posed at
   the first frame of its first animation, or as the file's node tree has
   it (examples/character.h: node transforms, skinned meshes by their
   bones, as gl_marschner shows the file), in the file's units.
   *has_normals and *has_uvs: every merged mesh had normals (assimp's
   smooth ones where the file has none) / texture coordinates (channel
   0); *uvless counts the meshes without. Refused, saying why: no
   triangles, a position that is not finite, no area. */
static int load_mesh(const char *path, vtx **out_v, uint32_t **out_i,
                     int *nv, int *nt, int *has_normals, int *has_uvs,
                     int *uvless, int *mesh_count)
{
    ch_character c;
    char err[600];
    double area = 0.0;
    int i, k;
    *out_v = NULL;
    *out_i = NULL;
    if (!ch_load(&c, path, "1", err, sizeof err)) { /* 1 m a file unit */
        fprintf(stderr, "grow_fur: cannot load %s\n", err);
        return 0;
    }
    *out_v = (vtx *)malloc(sizeof(vtx) * (size_t)c.vertex_count);
    *out_i = (uint32_t *)malloc(sizeof(uint32_t) * 3u *
                                (size_t)c.triangle_count);
    if (!*out_v || !*out_i) {
        fprintf(stderr, "grow_fur: out of memory loading %s\n", path);
        goto fail;
    }
    /* the first frame of the first animation, as make_hairstyle poses
       the curves it writes (the file's pose without one) */
    ch_pose(&c, ch_find_animation(&c, NULL), 0.0, *out_v, NULL);
    for (i = 0; i < c.vertex_count; ++i)
        for (k = 0; k < 3; ++k)
            if (!isfinite((*out_v)[i].pos[k])) {
                fprintf(stderr, "grow_fur: %s: vertex %d's position is not "
                                "finite\n", path, i);
                goto fail;
            }
    memcpy(*out_i, c.indices, sizeof(uint32_t) * 3u * (size_t)c.triangle_count);
    for (i = 0; i < c.triangle_count; ++i)
        area += hf_triangle_area((*out_v)[(*out_i)[3 * i]].pos,
                                 (*out_v)[(*out_i)[3 * i + 1]].pos,
                                 (*out_v)[(*out_i)[3 * i + 2]].pos);
    if (!(area > 0.0) || !isfinite(area)) {
        fprintf(stderr, "grow_fur: %s has no usable triangles (their area is "
                        "%g)\n", path, area);
        goto fail;
    }
    *has_normals = *has_uvs = 1; /* assimp made the missing normals */
    *uvless = 0;
    for (i = 0; i < c.part_count; ++i)
        if (!c.parts[i].has_uvs) {
            *has_uvs = 0;
            ++*uvless;
        }
    *mesh_count = c.part_count;
    *nv = c.vertex_count;
    *nt = c.triangle_count;
    ch_free(&c);
    return 1;
fail:
    free(*out_v);
    free(*out_i);
    *out_v = NULL;
    *out_i = NULL;
    ch_free(&c);
    return 0;
}

static int load_map(const char *path, int channels, hf_map *map)
{
    int w, h, n;
    unsigned char *px;
    /* hf_map's row 0 is v = 0 (OpenGL); a PNG stores its top row first:
       flip, so that the PNG's top row is v = 1 */
    stbi_set_flip_vertically_on_load(1);
    px = stbi_load(path, &w, &h, &n, channels);
    if (!px) {
        fprintf(stderr, "grow_fur: cannot read %s: %s\n", path,
                stbi_failure_reason());
        return 0;
    }
    memset(map, 0, sizeof *map);
    map->data = px;
    map->width = w;
    map->height = h;
    map->channels = channels;
    return 1;
}

/* A map from `path`, or, with no path and `builtin` set, `size` x `size`
   pixels made by `gen`; *have says whether there is one. The pixels are
   malloc'd (stb_image uses malloc): free map->data. 0 on failure. */
static int get_map(const char *path, int channels, int builtin,
                   void (*gen)(unsigned char *, int, int), int size,
                   hf_map *map, int *have)
{
    unsigned char *px;
    *have = 0;
    if (path) {
        if (!load_map(path, channels, map)) return 0;
        *have = 1;
        return 1;
    }
    if (!builtin) return 1;
    px = (unsigned char *)malloc((size_t)size * (size_t)size * (size_t)channels);
    if (!px) return 0;
    gen(px, size, size);
    memset(map, 0, sizeof *map);
    map->data = px;
    map->width = map->height = size;
    map->channels = channels;
    *have = 1;
    return 1;
}

static int ends_with(const char *s, const char *suf)
{
    size_t a = strlen(s), b = strlen(suf);
    return a >= b && strcmp(s + a - b, suf) == 0;
}

static const vtx *g_sort_v; /* for cmp_pos */
static int cmp_pos(const void *a, const void *b)
{
    const float *p = g_sort_v[*(const int *)a].pos;
    const float *q = g_sort_v[*(const int *)b].pos;
    int k;
    for (k = 0; k < 3; ++k)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    return 0;
}

/* The pure guide count hf_fur_create will make: vertices used by a
   triangle, welded by exact position. -1 without memory. */
static int welded_count(const vtx *v, int nv, const uint32_t *idx, int nt)
{
    int *order = (int *)malloc(sizeof(int) * (size_t)nv);
    unsigned char *used = (unsigned char *)calloc((size_t)nv, 1);
    int i, n = 0, count = 0;
    if (!order || !used) {
        free(order);
        free(used);
        return -1;
    }
    for (i = 0; i < 3 * nt; ++i) used[idx[i]] = 1;
    for (i = 0; i < nv; ++i)
        if (used[i]) order[n++] = i;
    g_sort_v = v;
    qsort(order, (size_t)n, sizeof(int), cmp_pos);
    for (i = 0; i < n; ++i)
        if (i == 0 || cmp_pos(&order[i - 1], &order[i]) != 0) ++count;
    free(order);
    free(used);
    return count;
}

/* LOD guides (added vertices) that tess_factor `factor` makes: the counting
   pass of hf_tessellate, as hf_fur_create runs it. -1 past the
   tessellation caps. */
static long long lod_guides_for(const hf_mesh *mesh, const hf_map *density,
                                int estimator, float factor)
{
    hf_tess_params tp;
    hf_tess_output to;
    if (!(factor > 0.0f)) return 0;
    memset(&tp, 0, sizeof tp);
    memset(&to, 0, sizeof to);
    tp.factor = factor;
    tp.estimator = estimator;
    if (hf_tessellate(mesh, density, &tp, &to) != HF_OK) return -1;
    return to.added_count;
}

/* The tess_factor whose LOD guides come nearest `target`: starts at
   target / area (a triangle of density 1 splits while A * factor > 1, so
   about one added vertex per 1 / factor of area), then bisects on the
   counting pass (the count grows with the factor). */
static float fit_tess_factor(const hf_mesh *mesh, const hf_map *density,
                             int estimator, double area, long long target)
{
    double lo = 0.0, hi = 0.0, f, best_f = 0.0;
    long long best_err = target, n;
    int it;
    if (target <= 0 || !(area > 0.0)) return 0.0f;
    f = (double)target / area;
    for (it = 0; it < 40; ++it) {
        if (!(f < 1e30)) break;
        n = lod_guides_for(mesh, density, estimator, (float)f);
        if (n >= 0 && llabs(n - target) < best_err) {
            best_err = llabs(n - target);
            best_f = f;
        }
        if (n >= 0 && llabs(n - target) * 50 <= target) break; /* 2 % */
        if (n < 0 || n > target) hi = f;
        else lo = f;
        f = hi > 0.0 ? (lo > 0.0 ? sqrt(lo * hi) : hi * 0.25) : f * 4.0;
        if (hi > 0.0 && lo > 0.0 && hi / lo < 1.0001) break;
    }
    return (float)best_f;
}

/* The command line: every option's value, the defaults where not given. */
typedef struct gf_options {
    const char *mesh_path, *density_path, *length_path, *color_path,
        *out_path, *curves_path;
    int curves_out;         /* --curves: OBJ polylines instead of ribbons */
    const char *groom_path; /* --groom: a groom, no growth */
    float guide_fraction;   /* of the groom's strands; 0 = 0.1 */
    int strands, points, frames;
    long long seed, guides;
    float lod, max_length, tess_factor;
    /* the ropes: shape stiffness, hair-hair interaction, draping */
    float stiffness, volume, friction, settle;
    long long grid;
    long long keep_length; /* --keep-length: 0 or 1 */
    /* --collider: the shapes at rest; the auto one is filled in once the
       mesh's box is known. No --collider at all means auto. */
    hf_collider cols[GF_MAX_COLLIDERS];
    int ncol, auto_col, no_col;
    float eye[3];
    int have_eye;
    /* area: a map's feature inside a big triangle still counts (corners
       would read only the three corner samples, so a bald patch grows) */
    int estimator;
} gf_options;

/* The mesh at rest, and what the run measures of it. */
typedef struct gf_mesh {
    vtx *rest;
    uint32_t *idx;
    int nv, nt;
    int has_normals, has_uvs, uvless, mesh_count;
    float lo[3], hi[3], box_radius;
    double area;
} gf_mesh;

/* Each stage's milliseconds, one entry per frame. */
typedef struct gf_times {
    double *roots, *grid, *sim, *guides, *interp, *ribbons;
} gf_times;

/* The built-in head: a sphere of this radius at the origin. */
#define GF_HEAD_RADIUS 0.1f

static void options_init(gf_options *o)
{
    memset(o, 0, sizeof *o);
    o->out_path = "fur.obj";
    o->strands = GF_DEFAULT_STRANDS;
    o->points = 16;
    o->frames = 120;
    o->seed = 1;
    o->guides = -1;
    o->lod = 1.0f;
    o->max_length = 0.12f;
    o->tess_factor = -1.0f;
    o->stiffness = 0.3f;
    o->volume = 1.0f;
    o->friction = 0.2f;
    o->grid = 32;
    o->keep_length = 1;
    o->auto_col = -1;
    o->estimator = HF_DENSITY_AREA;
}

/* One option with its value v; 0 when refused (said why). */
static int parse_option(gf_options *o, const char *a, const char *v)
{
    long long cnt;
    int ok = 1;
    if (!strcmp(a, "--mesh")) o->mesh_path = v;
    else if (!strcmp(a, "--density")) o->density_path = v;
    else if (!strcmp(a, "--length")) o->length_path = v;
    else if (!strcmp(a, "--color")) o->color_path = v;
    else if (!strcmp(a, "--out")) o->out_path = v;
    else if (!strcmp(a, "--strands")) {
        ok = parse_count(a, v, 1, GF_MAX_COUNT, &cnt);
        o->strands = (int)cnt;
    } else if (!strcmp(a, "--guides")) {
        /* a guide count, or a file of guide curves */
        if (strspn(v, "0123456789+") == strlen(v))
            ok = parse_count(a, v, 1, GF_MAX_COUNT, &o->guides);
        else
            o->curves_path = v;
    }
    else if (!strcmp(a, "--groom")) o->groom_path = v;
    else if (!strcmp(a, "--guide-fraction"))
        ok = parse_real(a, v, 1e-6, 1.0, &o->guide_fraction);
    else if (!strcmp(a, "--tess-factor"))
        ok = parse_real(a, v, 0.0, 1e30, &o->tess_factor);
    else if (!strcmp(a, "--points")) {
        ok = parse_count(a, v, 2, HF_MAX_POINTS, &cnt);
        o->points = (int)cnt;
    } else if (!strcmp(a, "--frames")) {
        ok = parse_count(a, v, 1, 100000000, &cnt);
        o->frames = (int)cnt;
    } else if (!strcmp(a, "--seed"))
        ok = parse_count(a, v, 0, 9007199254740992LL, &o->seed);
    else if (!strcmp(a, "--lod"))
        ok = parse_real(a, v, 0.0, 1.0, &o->lod);
    else if (!strcmp(a, "--length-max"))
        /* tips within the library's coordinate range (+-1e6) */
        ok = parse_real(a, v, 1e-9, 1e5, &o->max_length);
    else if (!strcmp(a, "--stiffness"))
        ok = parse_real(a, v, 0.0, 1.0, &o->stiffness);
    else if (!strcmp(a, "--volume"))
        ok = parse_real(a, v, 0.0, 100.0, &o->volume);
    else if (!strcmp(a, "--friction"))
        ok = parse_real(a, v, 0.0, 1.0, &o->friction);
    else if (!strcmp(a, "--grid"))
        ok = parse_count(a, v, 4, HF_GRID_MAX_RESOLUTION, &o->grid);
    else if (!strcmp(a, "--keep-length"))
        ok = parse_count(a, v, 0, 1, &o->keep_length);
    else if (!strcmp(a, "--rest-from-gravity"))
        ok = parse_real(a, v, 0.0, 600.0, &o->settle);
    else if (!strcmp(a, "--collider")) {
        if (!strcmp(v, "none")) {
            o->no_col = 1;
        } else if (o->ncol == GF_MAX_COLLIDERS) {
            fprintf(stderr, "grow_fur: --collider '%s': at most %d "
                            "colliders\n", v, GF_MAX_COLLIDERS);
            ok = 0;
        } else if (!strcmp(v, "auto")) {
            if (o->auto_col >= 0) {
                fprintf(stderr, "grow_fur: --collider auto given "
                                "twice\n");
                ok = 0;
            }
            o->auto_col = o->ncol++;
        } else {
            ok = parse_collider(v, &o->cols[o->ncol++]);
        }
    } else if (!strcmp(a, "--estimator")) {
        if (!strcmp(v, "area")) o->estimator = HF_DENSITY_AREA;
        else if (!strcmp(v, "edges")) o->estimator = HF_DENSITY_EDGES;
        else if (!strcmp(v, "corners")) o->estimator = HF_DENSITY_CORNERS;
        else {
            fprintf(stderr, "grow_fur: --estimator '%s': expected area, "
                            "edges or corners\n", v);
            ok = 0;
        }
    } else if (!strcmp(a, "--eye")) {
        ok = parse_reals(a, v, v, 3, 1e30, o->eye, "x,y,z");
        o->have_eye = 1;
    } else {
        fprintf(stderr, "grow_fur: unknown option '%s' (--help lists "
                        "the options)\n", a);
        return 0;
    }
    return ok;
}

/* The command line into *o: -1 to go on, else the exit code (0 after
   --help, 2 for a bad argument, said why). */
static int parse_args(int argc, char **argv, gf_options *o)
{
    int i;
    options_init(o);
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        if (!strcmp(a, "--curves")) { /* the one option without a value */
            o->curves_out = 1;
            continue;
        }
        if (strncmp(a, "--", 2) != 0 || !strcmp(a, "--")) {
            fprintf(stderr, "grow_fur: unexpected argument '%s' (--help "
                            "lists the options)\n", a);
            return 2;
        }
        if (!v) {
            fprintf(stderr, "grow_fur: %s needs a value (--help lists the "
                            "options)\n", a);
            return 2;
        }
        if (!parse_option(o, a, v)) return 2;
        ++i;
    }
    return -1;
}

/* The options against each other, and the curve file read into *curves:
   -1 to go on, else the exit code. */
static int check_args(gf_options *o, cv_curves *curves)
{
    const char *out_path = o->out_path;
    if (!(ends_with(out_path, ".obj") || ends_with(out_path, ".ply") ||
          ends_with(out_path, ".hair"))) {
        fprintf(stderr, "grow_fur: --out '%s': the name must end in .obj, "
                        ".ply or .hair\n", out_path);
        return 2;
    }
    {
        const char *base = strrchr(out_path, '/');
        base = base ? base + 1 : out_path;
        if (!strcmp(base, ".obj") || !strcmp(base, ".ply") ||
            !strcmp(base, ".hair")) {
            fprintf(stderr, "grow_fur: --out '%s': the name needs a stem "
                            "before its extension\n", out_path);
            return 2;
        }
    }
    if (!(o->lod > 0.0f)) {
        fprintf(stderr, "grow_fur: --lod 0 draws no strand: give a level "
                        "in (0, 1]\n");
        return 2;
    }
    if (o->curves_out && !ends_with(out_path, ".obj")) {
        fprintf(stderr, "grow_fur: --curves writes OBJ polylines: --out must "
                        "end in .obj (.hair is always curves)\n");
        return 2;
    }
    memset(curves, 0, sizeof *curves);
    if (o->curves_path && o->groom_path) {
        fprintf(stderr, "grow_fur: give --guides FILE or --groom FILE, not "
                        "both\n");
        return 2;
    }
    if (o->curves_path || o->groom_path) {
        char err[700];
        const char *cp = o->groom_path ? o->groom_path : o->curves_path;
        if (!cv_read(cp, curves, err, sizeof err)) {
            fprintf(stderr, "grow_fur: --%s %s\n",
                    o->groom_path ? "groom" : "guides", err);
            return 1;
        }
        printf("%s: %d curves, %d points from %s\n",
               o->groom_path ? "groom" : "guides", curves->count,
               curves->total, cp);
    }
    if (o->no_col && o->ncol > 0) {
        fprintf(stderr, "grow_fur: --collider none with other colliders: "
                        "give none alone\n");
        return 2;
    }
    if (!o->no_col && o->ncol == 0) o->auto_col = o->ncol++;
    if (o->guides >= 0 && o->tess_factor >= 0.0f) {
        fprintf(stderr, "grow_fur: give --guides or --tess-factor, not "
                        "both\n");
        return 2;
    }
    if (o->guides < 0 && o->tess_factor < 0.0f) {
        o->guides = o->strands / 10;
        if (o->guides > GF_MAX_DEFAULT_GUIDES) o->guides = GF_MAX_DEFAULT_GUIDES;
        if (o->guides < 1) o->guides = 1;
    }
    { /* what the frames hold a point: its strand point and the ribbon
         buffer's floats; a groom draws its own strands */
        const int strands = o->groom_path ? curves->count : o->strands;
        const double gb = (double)strands * o->points *
                          (double)sizeof(float) * (3 + GF_VBUF_FLOATS) / 1e9;
        const double have = (double)sysconf(_SC_PHYS_PAGES) *
                            (double)sysconf(_SC_PAGESIZE) / 1e9;
        if (have > 0.0 && gb > have) {
            fprintf(stderr, "grow_fur: %d strands of --points %d need about "
                            "%.1f GB, more than this machine's %.1f GB\n",
                    strands, o->points, gb, have);
            return 2;
        }
    }
    { /* --out writable before the run, not after it, and nothing of the
         user's changed: a new file made and removed again, an existing
         one opened to append (a name that leads nowhere, such as a
         dangling link, is refused) */
        int fd = open(out_path, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0) {
            close(fd);
            unlink(out_path);
        } else if (errno != EEXIST ||
                   (fd = open(out_path, O_WRONLY | O_APPEND)) < 0) {
            fprintf(stderr, "grow_fur: --out '%s': cannot write it: %s\n",
                    out_path, strerror(errno));
            return 1;
        } else {
            close(fd);
        }
    }
    return -1;
}

/* Smooth normals from assimp: pass them on, but only if every one is
   usable (finite, non-zero length; hf_mesh_validate refuses others); a
   bad one is replaced by the library's area-weighted normal. */
static void repair_normals(gf_mesh *g)
{
    int i, bad = 0;
    for (i = 0; i < g->nv; ++i) {
        const float *n = g->rest[i].normal;
        double l2 = (double)n[0] * n[0] + (double)n[1] * n[1] +
                    (double)n[2] * n[2];
        if (!isfinite(l2) || !(l2 > 1e-20)) ++bad;
    }
    if (bad) {
        hf_mesh m;
        float *nn = (float *)malloc(sizeof(float) * 3u * (size_t)g->nv);
        memset(&m, 0, sizeof m);
        m.positions = g->rest[0].pos;
        m.position_stride = (int)sizeof(vtx);
        m.vertex_count = g->nv;
        m.indices = g->idx;
        m.triangle_count = g->nt;
        if (!nn || hf_mesh_compute_normals(&m, nn) != HF_OK) {
            g->has_normals = 0;
        } else {
            for (i = 0; i < g->nv; ++i) {
                float *n = g->rest[i].normal;
                double l2 = (double)n[0] * n[0] + (double)n[1] * n[1] +
                            (double)n[2] * n[2];
                if (!isfinite(l2) || !(l2 > 1e-20))
                    memcpy(n, nn + 3 * i, sizeof(float) * 3u);
            }
            printf("normals: %d of %d mesh normals were zero or not "
                   "finite: replaced by area-weighted ones\n", bad, g->nv);
        }
        free(nn);
    }
}

/* The mesh: a file through assimp, or the built-in head; then its normals,
   bounding box and area. 0 on failure (said why). */
static int load_rest_mesh(const gf_options *o, gf_mesh *g)
{
    int i, k;
    memset(g, 0, sizeof *g);
    g->has_normals = g->has_uvs = g->mesh_count = 1;
    if (o->mesh_path) {
        if (!load_mesh(o->mesh_path, &g->rest, &g->idx, &g->nv, &g->nt,
                       &g->has_normals, &g->has_uvs, &g->uvless,
                       &g->mesh_count))
            return 0;
    } else {
        hm_mesh head;
        if (!hm_sphere(24, 32, GF_HEAD_RADIUS, &head)) return 0;
        g->nv = head.vertex_count;
        g->nt = head.triangle_count;
        g->rest = (vtx *)malloc(sizeof(vtx) * (size_t)g->nv);
        if (!g->rest) return 0;
        memcpy(g->rest, head.vertices, sizeof(vtx) * (size_t)g->nv);
        g->idx = head.indices;
        head.indices = NULL;
        hm_free(&head);
    }
    /* maps need UVs: refuse rather than read one texel everywhere */
    if (!g->has_uvs && (o->density_path || o->length_path || o->color_path)) {
        const char *what = o->density_path ? "--density" : o->length_path ? "--length" : "--color";
        const char *map = o->density_path ? o->density_path : o->length_path ? o->length_path : o->color_path;
        fprintf(stderr,
                "grow_fur: %s %s needs texture coordinates, but %s has none "
                "(%d of its %d triangle meshes lack UV channel 0): give the "
                "mesh UVs, or leave the maps out\n",
                what, map, o->mesh_path, g->uvless, g->mesh_count);
        return 0;
    }
    if (o->mesh_path && g->has_normals) repair_normals(g);
    printf("mesh: %s, %d vertices, %d triangles, normals %s, UVs %s\n",
           o->mesh_path ? o->mesh_path : "built-in head", g->nv, g->nt,
           g->has_normals ? "from the mesh" : "computed by hairfur",
           g->has_uvs ? "yes" : "none");
    for (k = 0; k < 3; ++k) {
        g->lo[k] = 1e30f;
        g->hi[k] = -1e30f;
    }
    for (i = 0; i < g->nv; ++i)
        for (k = 0; k < 3; ++k) {
            g->lo[k] = g->rest[i].pos[k] < g->lo[k] ? g->rest[i].pos[k] : g->lo[k];
            g->hi[k] = g->rest[i].pos[k] > g->hi[k] ? g->rest[i].pos[k] : g->hi[k];
        }
    for (i = 0; i < g->nt; ++i)
        g->area += hf_triangle_area(g->rest[g->idx[3 * i]].pos,
                                    g->rest[g->idx[3 * i + 1]].pos,
                                    g->rest[g->idx[3 * i + 2]].pos);
    g->box_radius = 0.5f * sqrtf((g->hi[0] - g->lo[0]) * (g->hi[0] - g->lo[0]) +
                                 (g->hi[1] - g->lo[1]) * (g->hi[1] - g->lo[1]) +
                                 (g->hi[2] - g->lo[2]) * (g->hi[2] - g->lo[2]));
    printf("bounding box (mesh units): (%g, %g, %g) .. (%g, %g, %g); "
           "area %g square mesh units\n",
           (double)g->lo[0], (double)g->lo[1], (double)g->lo[2],
           (double)g->hi[0], (double)g->hi[1], (double)g->hi[2], g->area);
    return 1;
}

/* The auto collider and the eye from the mesh's box, and both said. */
static void place_colliders_and_eye(gf_options *o, const gf_mesh *g)
{
    int i;
    /* auto: the mesh's bounding sphere, shrunk so roots sit on it (the
       built-in head: its own sphere) */
    if (o->auto_col >= 0) {
        hf_collider *c = &o->cols[o->auto_col];
        float center[3] = {0, 0, 0}, radius = GF_HEAD_RADIUS;
        int k;
        if (o->mesh_path) {
            for (k = 0; k < 3; ++k) center[k] = 0.5f * (g->lo[k] + g->hi[k]);
            radius = 0.5f * 0.5f * (g->hi[0] - g->lo[0]); /* a conservative inner ball */
        }
        memset(c, 0, sizeof *c);
        c->type = HF_COLLIDER_SPHERE;
        memcpy(c->a, center, sizeof c->a);
        c->radius = 0.97f * radius;
    }
    if (o->ncol == 0) printf("collider: none\n");
    for (i = 0; i < o->ncol; ++i) {
        const hf_collider *c = &o->cols[i];
        if (c->type == HF_COLLIDER_CAPSULE)
            printf("collider: given capsule, (%g, %g, %g) - (%g, %g, %g), "
                   "radius %g (mesh units, at rest)\n", (double)c->a[0],
                   (double)c->a[1], (double)c->a[2], (double)c->b[0],
                   (double)c->b[1], (double)c->b[2], (double)c->radius);
        else
            printf("collider: %s sphere, centre (%g, %g, %g), radius %g "
                   "(mesh units, at rest)\n",
                   i == o->auto_col ? "auto" : "given", (double)c->a[0],
                   (double)c->a[1], (double)c->a[2], (double)c->radius);
    }
    if (!o->have_eye) {
        o->eye[0] = 0.5f * (g->lo[0] + g->hi[0]);
        o->eye[1] = 0.5f * (g->lo[1] + g->hi[1]);
        o->eye[2] = 0.5f * (g->lo[2] + g->hi[2]) + 2.5f * g->box_radius;
    }
    printf("eye: (%g, %g, %g)%s\n", (double)o->eye[0], (double)o->eye[1],
           (double)o->eye[2], o->have_eye ? "" : " (box centre + (0, 0, 2.5 x half "
                                                "the box diagonal))");
}

/* What hf_fur_create grows from: the mesh, the maps, the guide curves,
   the ropes' parameters (into *rp) and the tessellation factor that
   reaches the guide target. 0 on failure. */
static int fill_desc(const gf_options *o, const gf_mesh *g,
                     const cv_curves *curves, const hf_map *density,
                     const hf_map *length, const hf_map *color,
                     hf_rope_params *rp, hf_fur_desc *desc)
{
    int pure_guides;
    memset(desc, 0, sizeof *desc);
    desc->mesh.positions = g->rest[0].pos;
    desc->mesh.position_stride = (int)sizeof(vtx);
    /* the mesh's smooth normals where it has them, else hairfur computes
       area-weighted ones; UVs only where there are some */
    desc->mesh.normals = g->has_normals ? g->rest[0].normal : NULL;
    desc->mesh.normal_stride = (int)sizeof(vtx);
    desc->mesh.uvs = g->has_uvs ? g->rest[0].uv : NULL;
    desc->mesh.uv_stride = (int)sizeof(vtx);
    desc->mesh.vertex_count = g->nv;
    desc->mesh.indices = g->idx;
    desc->mesh.triangle_count = g->nt;
    desc->density_map = density;
    desc->length_map = length;
    desc->color_map = color;
    desc->points_per_strand = o->points;
    desc->max_length = o->max_length;
    desc->total_strands = o->strands;
    desc->sampler = HF_SAMPLER_STRATIFIED;
    desc->tess_estimator = o->estimator;
    desc->seed = (uint64_t)o->seed;
    desc->clump = 0.2f;
    if (curves->count > 0 && !o->groom_path) {
        desc->guide_curves = curves->xyz;
        desc->guide_curve_points = curves->points;
        desc->guide_curve_count = curves->count;
    }
    /* LOD guides where the mesh is coarse. A triangle of density D and
       area A is split while D * A * tess_factor > 1, so a factor of about
       lod_guides / area gives that many added vertices (LOD guides); the
       counting pass of hf_tessellate then tunes it. Pure guides sit at the
       welded vertices, so a target below their count means no LOD
       guides. */
    pure_guides = welded_count(g->rest, g->nv, g->idx, g->nt);
    if (pure_guides < 0) return 0;
    if (o->tess_factor >= 0.0f) {
        desc->tess_factor = o->tess_factor;
        printf("guides: --tess-factor %g per square mesh unit\n",
               (double)o->tess_factor);
    } else {
        long long want = o->guides - pure_guides;
        desc->tess_factor =
            want > 0 ? fit_tess_factor(&desc->mesh, desc->density_map,
                                       desc->tess_estimator, g->area, want)
                     : 0.0f;
        printf("guides: target %lld = %d pure (welded vertices) + %lld LOD "
               "-> tess_factor %g per square mesh unit (first guess %g)\n",
               o->guides, pure_guides, want > 0 ? want : 0,
               (double)desc->tess_factor, want > 0 ? (double)want / g->area : 0.0);
        if (want <= 0)
            printf("guides: the mesh's %d welded vertices already reach the "
                   "target of %lld: no LOD guides\n", pure_guides, o->guides);
    }
    hf_rope_params_init(rp);
    rp->global_stiffness_root = o->stiffness;
    rp->global_stiffness_tip = o->stiffness / 15.0f;
    rp->local_stiffness_root = 0.5f;
    rp->local_stiffness_tip = 0.1f;
    rp->root_stiffness = 0.8f;
    /* 0 on the command line is off: a literal 0 for the library */
    rp->volume = o->volume;
    rp->friction = o->friction;
    rp->explicit_zero = (o->volume == 0.0f ? HF_ROPE_ZERO_VOLUME : 0) |
                        (o->friction == 0.0f ? HF_ROPE_ZERO_FRICTION : 0);
    desc->rope_params = rp;
    desc->grid_resolution =
        o->volume > 0.0f || o->friction > 0.0f ? (int)o->grid : 0;
    desc->keep_length = (int)o->keep_length;
    return 1;
}

/* The fur: grown from *desc, or made from the groom's own strands (their
   roots ride on the head); then its level of detail, and the draping.
   NULL on failure (said why). */
static hf_fur *create_fur(const gf_options *o, const gf_mesh *g,
                          const cv_curves *curves, const hf_fur_desc *desc)
{
    hf_fur *fur = NULL;
    hf_fur_info info;
    hf_diag diag;
    hf_result r;
    double t0 = now_ms();
    if (o->groom_path) {
        hf_groom_desc gd;
        memset(&gd, 0, sizeof gd);
        gd.points = curves->xyz;
        gd.strand_points = curves->points;
        gd.strand_count = curves->count;
        gd.points_per_strand = o->points;
        gd.guide_fraction = o->guide_fraction;
        gd.seed = (uint64_t)o->seed;
        gd.rope_params = desc->rope_params;
        gd.grid_resolution = desc->grid_resolution;
        gd.keep_length = desc->keep_length;
        r = hf_fur_create_groom(&gd, &fur, &diag);
    } else {
        r = hf_fur_create(desc, &fur, &diag);
    }
    if (r != HF_OK) {
        fprintf(stderr, "grow_fur: %s\n", diag.message);
        if (r == HF_ERROR_BAD_RANGE && o->estimator != HF_DENSITY_CORNERS)
            fprintf(stderr, "grow_fur: (UVs spanning many map periods: "
                            "--estimator corners reads any)\n");
        return NULL;
    }
    hf_fur_get_info(fur, &info);
    if (o->groom_path)
        printf("groom made in %.1f ms: %d strands of %d points, %d of them "
               "simulated guides\n", now_ms() - t0, info.strand_count,
               info.points_per_strand, info.guide_count);
    else
        printf("grown in %.1f ms: %d vertices, %d triangles -> %d guide "
               "triangles; %d guides (%d pure, %d LOD); %d strands of %d "
               "points\n",
               now_ms() - t0, g->nv, g->nt, info.triangle_count,
               info.guide_count, info.pure_guide_count, info.lod_guide_count,
               info.strand_count, info.points_per_strand);
    if (o->guides >= 0)
        printf("guides: %d of a target of %lld (%.2f x)\n", info.guide_count,
               o->guides, (double)info.guide_count / (double)o->guides);
    hf_fur_set_lod(fur, o->lod);
    if (o->settle > 0.0f) {
        /* the head's first pose (frame 0 of the swing is the rest pose),
           so the draped shape is the rest shape in the roots' frames */
        hf_collider moved[GF_MAX_COLLIDERS];
        int i;
        t0 = now_ms();
        for (i = 0; i < o->ncol; ++i) moved[i] = o->cols[i];
        r = hf_fur_settle_rest(fur, o->settle, o->ncol ? moved : NULL, o->ncol);
        if (r != HF_OK) {
            fprintf(stderr, "grow_fur: --rest-from-gravity: %s\n",
                    hf_result_string(r));
            hf_fur_destroy(fur);
            return NULL;
        }
        printf("rest from gravity: %g s of draping in %.1f ms\n",
               (double)o->settle, now_ms() - t0);
    }
    return fur;
}

/* --frames frames of the swinging head: skin, roots, grid, simulate,
   interpolate, ribbons into vbuf (two 24-byte vertices a point), each
   stage timed into *t. 0 on failure (said why). */
static int run_frames(const gf_options *o, const gf_mesh *g, hf_fur *fur,
                      const hf_mesh *rest_mesh, float *vbuf, gf_times *t)
{
    hf_collider moved[GF_MAX_COLLIDERS];
    hf_fur_info info;
    hf_mesh skinned;
    hf_result r;
    int f, i;
    vtx *skin = (vtx *)malloc(sizeof(vtx) * (size_t)g->nv);
    if (!skin) return 0;
    hf_fur_get_info(fur, &info);
    skinned = *rest_mesh;
    skinned.positions = skin[0].pos;
    skinned.normals = skin[0].normal;
    skinned.uvs = g->has_uvs ? skin[0].uv : NULL;
    for (f = 0; f < o->frames; ++f) {
        float m[12];
        hf_ribbon_params view;
        hf_ribbon_output out;
        double t0, t1, t1g, t2, t3, t4, t5;
        hm_pose((f + 1) / 60.0, 0, m);
        for (i = 0; i < g->nv; ++i) {
            hm_xform(m, g->rest[i].pos, 1.0f, skin[i].pos);
            hm_xform(m, g->rest[i].normal, 0.0f, skin[i].normal);
            skin[i].uv[0] = g->rest[i].uv[0];
            skin[i].uv[1] = g->rest[i].uv[1];
        }
        if (!g->has_normals) skinned.normals = NULL; /* face normals */
        for (i = 0; i < o->ncol; ++i) {
            moved[i] = o->cols[i];
            hm_xform(m, o->cols[i].a, 1.0f, moved[i].a);
            hm_xform(m, o->cols[i].b, 1.0f, moved[i].b);
        }

        memset(&view, 0, sizeof view);
        memcpy(view.eye, o->eye, sizeof view.eye);
        view.root_width = 0.0012f;
        view.tip_width = 0.0003f;
        view.alpha_root = 1.0f;
        view.alpha_tip = 0.3f;
        memset(&out, 0, sizeof out);
        out.position.data = vbuf;
        out.position.stride = 24;
        out.tangent.data = vbuf + 3;
        out.tangent.stride = 24;

        t0 = now_ms();
        r = o->groom_path ? hf_fur_set_transform(fur, m, 0, info.guide_count)
                          : hf_fur_set_roots(fur, &skinned, 0, info.guide_count);
        t1 = now_ms();
        if (r == HF_OK) r = hf_fur_build_grid(fur, 0, info.grid_resolution);
        t1g = now_ms();
        if (r == HF_OK)
            r = hf_fur_simulate(fur, 0, info.guide_count, 1.0f / 60.0f,
                                o->ncol ? moved : NULL, o->ncol);
        t2 = now_ms();
        if (r == HF_OK)
            r = hf_fur_interpolate_guides(fur, 0, info.lod_guide_count);
        t3 = now_ms();
        if (r == HF_OK) r = hf_fur_interpolate(fur, 0, info.drawn_strand_count);
        t4 = now_ms();
        if (r == HF_OK)
            r = hf_fur_ribbons(fur, 0, info.drawn_strand_count, &view, &out);
        t5 = now_ms();
        if (r != HF_OK) {
            fprintf(stderr, "grow_fur: frame %d: %s\n", f, hf_result_string(r));
            free(skin);
            return 0;
        }
        t->roots[f] = t1 - t0;
        t->grid[f] = t1g - t1;
        t->sim[f] = t2 - t1g;
        t->guides[f] = t3 - t2;
        t->interp[f] = t4 - t3;
        t->ribbons[f] = t5 - t4;
    }
    free(skin);
    return 1;
}

/* The frames' medians, the stretch, and the roots inside a collider. */
static void report_frames(const gf_options *o, const hf_fur *fur,
                          gf_times *t)
{
    hf_fur_info info;
    float stretch = 0.0f;
    int frames = o->frames;
    hf_fur_get_info(fur, &info);
    hf_fur_max_stretch(fur, &stretch);
    printf("%d frames at lod %.2f (%d of %d strands drawn), median ms: "
           "roots %.3f, grid %.3f (%d^3 nodes), ropes %.3f (%d guides, "
           "%d colliders), LOD "
           "guides %.3f, strands %.3f, ribbons %.3f; max stretch %.3f "
           "%%\n",
           frames, (double)info.lod, info.drawn_strand_count,
           info.strand_count, median(t->roots, frames),
           median(t->grid, frames), info.grid_resolution,
           median(t->sim, frames), info.guide_count, o->ncol,
           median(t->guides, frames), median(t->interp, frames),
           median(t->ribbons, frames), 100.0 * stretch);
    printf("collider: %d of %d guide roots inside it at the last frame"
           "%s\n", info.roots_inside, info.guide_count,
           o->ncol > 1 ? " (any of the colliders)" : "");
    if (info.roots_inside > 0)
        printf("%d of %d guide roots sit inside the collider (for "
               "those guides it is shrunk to the root's depth); if the "
               "proxy is larger than the body there, shrink it\n",
               info.roots_inside, info.guide_count);
}

/* The last frame's drawn strands as curves, with their colours (.hair),
   or as OBJ polylines. 0 on failure (said why). */
static int write_curves(const char *out_path, const hf_fur_info *info)
{
    cv_curves o;
    char err[600];
    int P = info->points_per_strand, S = info->drawn_strand_count, k;
    long q;
    memset(&o, 0, sizeof o);
    o.count = S;
    o.total = S * P;
    o.points = (int *)malloc(sizeof(int) * (size_t)(S > 0 ? S : 1));
    o.xyz = (float *)malloc(sizeof(float) * 3u * (size_t)(S > 0 ? S * P : 1));
    o.rgb = (float *)malloc(sizeof(float) * 3u * (size_t)(S > 0 ? S * P : 1));
    if (!o.points || !o.xyz || !o.rgb) {
        fprintf(stderr, "grow_fur: out of memory writing %s\n", out_path);
        cv_free(&o);
        return 0;
    }
    for (k = 0; k < S; ++k) o.points[k] = P;
    memcpy(o.xyz, info->strand_points, sizeof(float) * 3u * (size_t)S * (size_t)P);
    for (q = 0; q < (long)S * P; ++q)
        memcpy(o.rgb + 3 * q, info->strand_colors + 4 * (q / P), 3 * sizeof(float));
    if (!(ends_with(out_path, ".hair")
              ? cv_write_hair(out_path, &o, "hairfur grow_fur", err, sizeof err)
              : cv_write_obj(out_path, &o, err, sizeof err))) {
        fprintf(stderr, "grow_fur: %s\n", err);
        cv_free(&o);
        return 0;
    }
    printf("wrote %s: %d curves of %d points\n", out_path, S, P);
    cv_free(&o);
    return 1;
}

/* The last frame's ribbons as OBJ: positions, (root u, root v), faces. */
static void write_obj(FILE *fp, const hf_fur_info *info, const float *vbuf,
                      long long nvert, const uint32_t *ibuf, long long n_idx)
{
    long long k;
    fprintf(fp, "# hairfur.h grow_fur: %d strands, %d points each, "
                "2 vertices per point\n",
            info->drawn_strand_count, info->points_per_strand);
    for (k = 0; k < nvert; ++k)
        fprintf(fp, "v %.6f %.6f %.6f\n", vbuf[6 * k], vbuf[6 * k + 1],
                vbuf[6 * k + 2]);
    for (k = 0; k < nvert; ++k) {
        /* vt: root uv of the strand (hairfur stores it per strand) */
        const float *uv = info->strands[k / (2 * info->points_per_strand)].uv;
        fprintf(fp, "vt %.6f %.6f\n", uv[0], uv[1]);
    }
    for (k = 0; k < n_idx; k += 3)
        fprintf(fp, "f %u/%u %u/%u %u/%u\n", ibuf[k] + 1, ibuf[k] + 1,
                ibuf[k + 1] + 1, ibuf[k + 1] + 1, ibuf[k + 2] + 1,
                ibuf[k + 2] + 1);
}

/* The last frame's ribbons as binary PLY: positions, tangents as normals,
   the strands' colours. */
static void write_ply(FILE *fp, const hf_fur_info *info, const float *vbuf,
                      long long nvert, const uint32_t *ibuf, long long n_idx)
{
    long long k;
    fprintf(fp,
            "ply\nformat binary_little_endian 1.0\n"
            "comment hairfur.h grow_fur ribbons\n"
            "element vertex %lld\nproperty float x\nproperty float y\n"
            "property float z\nproperty float nx\nproperty float ny\n"
            "property float nz\nproperty uchar red\nproperty uchar "
            "green\nproperty uchar blue\n"
            "element face %lld\nproperty list uchar uint "
            "vertex_indices\nend_header\n",
            nvert, n_idx / 3);
    for (k = 0; k < nvert; ++k) {
        const float *c =
            info->strand_colors + 4 * (k / (2 * info->points_per_strand));
        unsigned char rgb[3];
        int q;
        for (q = 0; q < 3; ++q)
            rgb[q] = (unsigned char)(255.0f * (c[q] < 0 ? 0 : c[q] > 1 ? 1 : c[q]) + 0.5f);
        fwrite(vbuf + 6 * k, 4, 6, fp); /* little-endian hosts */
        fwrite(rgb, 1, 3, fp);
    }
    for (k = 0; k < n_idx; k += 3) {
        unsigned char three = 3;
        fwrite(&three, 1, 1, fp);
        fwrite(ibuf + k, 4, 3, fp);
    }
}

/* The last frame into --out: curves (.hair, or .obj with --curves), or
   ribbons with their index buffer (.obj, .ply). 0 on failure. */
static int export_last_frame(const gf_options *o, const hf_fur *fur,
                             const float *vbuf)
{
    const char *out_path = o->out_path;
    hf_fur_info info;
    uint32_t *ibuf;
    long long n_idx, nvert;
    FILE *fp;
    hf_result r;
    hf_fur_get_info(fur, &info);
    if (ends_with(out_path, ".hair") || o->curves_out)
        return write_curves(out_path, &info); /* no index buffer */
    n_idx = hf_ribbon_index_count(info.drawn_strand_count,
                                  info.points_per_strand, HF_TRIANGLES);
    if (n_idx < 0) {
        fprintf(stderr, "grow_fur: %s: %d strands of %d points have more "
                        "indices than an int counts\n", out_path,
                info.drawn_strand_count, info.points_per_strand);
        return 0;
    }
    ibuf = (uint32_t *)malloc(sizeof(uint32_t) * (size_t)(n_idx ? n_idx : 1));
    if (!ibuf) {
        fprintf(stderr, "grow_fur: out of memory writing %s\n", out_path);
        return 0;
    }
    if ((r = hf_ribbon_indices(info.drawn_strand_count,
                               info.points_per_strand, HF_TRIANGLES, ibuf,
                               n_idx)) != HF_OK) {
        fprintf(stderr, "grow_fur: %s: hf_ribbon_indices: %s\n", out_path,
                hf_result_string(r));
        free(ibuf);
        return 0;
    }
    fp = fopen(out_path, "wb");
    nvert = 2LL * info.drawn_strand_count * info.points_per_strand;
    if (!fp) {
        fprintf(stderr, "grow_fur: cannot write %s: %s\n", out_path,
                strerror(errno));
        free(ibuf);
        return 0;
    }
    if (ends_with(out_path, ".obj"))
        write_obj(fp, &info, vbuf, nvert, ibuf, n_idx);
    else
        write_ply(fp, &info, vbuf, nvert, ibuf, n_idx);
    free(ibuf);
    /* a write that failed (a full disk) leaves no half file */
    if (ferror(fp) | (fclose(fp) != 0)) {
        fprintf(stderr, "grow_fur: error writing %s (a full disk?): "
                        "removed\n", out_path);
        remove(out_path);
        return 0;
    }
    printf("wrote %s: %lld vertices, %lld triangles\n", out_path, nvert,
           n_idx / 3);
    return 1;
}

int main(int argc, char **argv)
{
    gf_options o;
    gf_mesh g;
    cv_curves curves;
    hf_map density, length, color;
    int have_density = 0, have_length = 0, have_color = 0, rc;
    hf_fur_desc desc;
    hf_rope_params rp;
    hf_fur *fur;
    hf_fur_info info;
    gf_times t;
    float *vbuf;

    if ((rc = parse_args(argc, argv, &o)) >= 0) return rc;
    if ((rc = check_args(&o, &curves)) >= 0) return rc;
    if (!load_rest_mesh(&o, &g)) return 1;
    place_colliders_and_eye(&o, &g);
    /* the maps: files, or the built-in ones for the built-in head */
    if (!get_map(o.density_path, 1, !o.mesh_path, hm_hairline_density, 256,
                 &density, &have_density) ||
        !get_map(o.length_path, 1, !o.mesh_path, hm_bangs_length, 256, &length,
                 &have_length) ||
        !get_map(o.color_path, 3, !o.mesh_path, hm_hair_color, 64, &color,
                 &have_color))
        return 1;
    if (!fill_desc(&o, &g, &curves, have_density ? &density : NULL,
                   have_length ? &length : NULL, have_color ? &color : NULL,
                   &rp, &desc))
        return 1;
    if (!(fur = create_fur(&o, &g, &curves, &desc))) return 1;

    /* per frame: measured apart from what is written afterwards */
    hf_fur_get_info(fur, &info);
    vbuf = (float *)malloc(sizeof(float) * GF_VBUF_FLOATS *
                           (size_t)info.strand_count *
                           (size_t)info.points_per_strand);
    t.roots = (double *)malloc(sizeof(double) * 6u * (size_t)o.frames);
    if (!vbuf || !t.roots) {
        fprintf(stderr, "grow_fur: out of memory: the ribbons of %d strands "
                        "of %d points take %.1f GB\n", info.strand_count,
                info.points_per_strand,
                (double)sizeof(float) * GF_VBUF_FLOATS *
                    info.strand_count * info.points_per_strand / 1e9);
        return 1;
    }
    t.sim = t.roots + o.frames;
    t.guides = t.sim + o.frames;
    t.interp = t.guides + o.frames;
    t.ribbons = t.interp + o.frames;
    t.grid = t.roots + 5 * o.frames;
    if (!run_frames(&o, &g, fur, &desc.mesh, vbuf, &t)) return 1;
    report_frames(&o, fur, &t);
    if (!export_last_frame(&o, fur, vbuf)) return 1;

    hf_fur_destroy(fur);
    cv_free(&curves);
    free(g.rest);
    free(g.idx);
    free(vbuf);
    free(t.roots);
    /* stb_image's buffers come from malloc too (no STBI_MALLOC here) */
    if (have_density) free((void *)density.data);
    if (have_length) free((void *)length.data);
    if (have_color) free((void *)color.data);
    return 0;
}
