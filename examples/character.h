/* character.h - a mesh from any file assimp reads, skinned and animated on
   the CPU, with capsule colliders that follow its bones. For the examples
   (the library itself knows nothing of files, bones or animation).

   What it does, in the order a frame needs it:
     ch_load       every triangle mesh of the file merged into one vertex
                   array (position, normal, first UV channel), in metres
                   (a unit picked from the size, or given); bone weights
                   (at most 4 a vertex); the node tree; a capsule per bone
                   fitted to the vertices that bone moves most.
     ch_pose       the node tree at time t of an animation (keys
                   interpolated: positions and scales linearly, rotations
                   by slerp), then linear blend skinning of every vertex
                   and normal, and the capsules moved by their bones.
   Meshes without bones follow their node. A file without animations (or
   no animation chosen) is posed as the file's node tree has it.

   Define CHARACTER_IMPLEMENTATION in one file before including. Needs
   assimp (libassimp-dev) and hairfur.h (for hf_collider). */
#ifndef CHARACTER_H
#define CHARACTER_H

#include <stddef.h>
#include <stdint.h>

#define CH_MAX_INFLUENCES 4
#define CH_NAME 64

typedef struct ch_vertex {
    float pos[3], normal[3], uv[2];
} ch_vertex;

/* One mesh of the file: a contiguous range of vertices and triangles. */
typedef struct ch_part {
    char name[CH_NAME];
    int first_vertex, vertex_count, first_triangle, triangle_count;
    int has_uvs, has_bones;
} ch_part;

/* A capsule in the file's mesh space at bind, moved by one bone's skin
   matrix. A sphere when a == b. */
typedef struct ch_capsule {
    int bone;
    float a[3], b[3], radius; /* file units */
} ch_capsule;

typedef struct ch_character {
    int vertex_count, triangle_count, part_count;
    ch_vertex *raw;      /* the file's vertices, file units, mesh space */
    uint32_t *indices;   /* 3 per triangle, into the merged array */
    ch_part *parts;
    /* per vertex: matrix indices (bones, then one per node for meshes
       without bones) and weights summing to 1 */
    int (*vmat)[CH_MAX_INFLUENCES];
    float (*vweight)[CH_MAX_INFLUENCES];
    int node_count, bone_count;
    char (*node_name)[CH_NAME];
    int *node_parent;            /* parents come before their children */
    float (*node_local)[12];     /* the file's transform, rows of 3x4 */
    int *bone_node;
    float (*bone_offset)[12];    /* mesh space -> bone space at bind */
    float (*global)[12];         /* scratch: node transforms at a pose */
    float (*skin)[12];           /* scratch: bone_count + node_count */
    int capsule_count;
    ch_capsule *capsules;
    int animation_count;
    char (*animation_name)[CH_NAME];
    int *channel_node;           /* per animation channel: node (-1) */
    int channel_stride;          /* channels of animation a start at
                                    a * channel_stride */
    double *anim_ticks_per_s, *anim_duration;
    float unit;                  /* metres per file unit */
    const void *scene;           /* the assimp scene, kept for the keys */
} ch_character;

/* Load `path`. unit: "auto" (or NULL) picks metres, centimetres or
   millimetres from the size (a bind-pose box diagonal up to 20 is metres,
   up to 2,000 centimetres, else millimetres), "m", "cm", "mm" or a number
   of metres per file unit. Returns 1, or 0 with a message in err. */
int ch_load(ch_character *c, const char *path, const char *unit, char *err,
            size_t err_size);
void ch_free(ch_character *c);
/* The animation called `name` (NULL or "": the first), -1 if none. */
int ch_find_animation(const ch_character *c, const char *name);
/* Length of animation `anim` in seconds (0 for none). */
double ch_animation_seconds(const ch_character *c, int anim);
/* Pose at `seconds` into animation `anim` (-1: the file's pose; the time
   wraps around the animation's length): out (vertex_count, metres) and,
   if cols is not NULL, capsule_count colliders in metres. */
void ch_pose(ch_character *c, int anim, double seconds, ch_vertex *out,
             void *cols /* hf_collider *, capsule_count of them */);
/* The part called `name`, -1 if none. */
int ch_find_part(const ch_character *c, const char *name);
/* One more collider, a sphere inside vertices [first, first + count) (a
   part such as a head, which the bones' capsules cover only along the
   bone): centred in their box, radius 0.9 of the 25th percentile of their
   distance from there, moved by the bone that moves most of them. Bone
   capsules follow a bone's axis and stop short of its ends, so hair
   draped over a skull would fall through its crown. Returns 1 if added
   (once per character; 0 for fewer than 12 vertices). */
int ch_fit_sphere(ch_character *c, int first, int count);

#endif /* CHARACTER_H */

#ifdef CHARACTER_IMPLEMENTATION
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void ch__from_ai(const struct aiMatrix4x4 *m, float o[12])
{
    o[0] = m->a1; o[1] = m->a2; o[2] = m->a3; o[3] = m->a4;
    o[4] = m->b1; o[5] = m->b2; o[6] = m->b3; o[7] = m->b4;
    o[8] = m->c1; o[9] = m->c2; o[10] = m->c3; o[11] = m->c4;
}

/* o = a * b for 3x4 affine matrices (o may alias neither). */
static void ch__mul(const float a[12], const float b[12], float o[12])
{
    int r, k;
    for (r = 0; r < 3; ++r) {
        for (k = 0; k < 4; ++k)
            o[4 * r + k] = a[4 * r] * b[k] + a[4 * r + 1] * b[4 + k] +
                           a[4 * r + 2] * b[8 + k];
        o[4 * r + 3] += a[4 * r + 3];
    }
}

static void ch__xform(const float m[12], const float *p, float w, float *o)
{
    int r;
    for (r = 0; r < 3; ++r)
        o[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] +
               m[4 * r + 3] * w;
}

static void ch__copy_name(char *dst, const struct aiString *s)
{
    size_t n = s->length < CH_NAME - 1 ? s->length : CH_NAME - 1;
    memcpy(dst, s->data, n);
    dst[n] = '\0';
}

/* Nodes in parent-first order. Some importers (RAW) leave NULL children
   or no root: those are skipped. */
static int ch__count_nodes(const struct aiNode *n)
{
    unsigned i;
    int k = 1;
    if (!n) return 0;
    for (i = 0; i < n->mNumChildren; ++i)
        if (n->mChildren) k += ch__count_nodes(n->mChildren[i]);
    return k;
}

static void ch__flatten(ch_character *c, const struct aiNode *n, int parent,
                        int *at, const struct aiNode **nodes)
{
    int me;
    unsigned i;
    if (!n) return;
    me = (*at)++;
    nodes[me] = n;
    ch__copy_name(c->node_name[me], &n->mName);
    c->node_parent[me] = parent;
    ch__from_ai(&n->mTransformation, c->node_local[me]);
    for (i = 0; i < n->mNumChildren && n->mChildren; ++i)
        ch__flatten(c, n->mChildren[i], me, at, nodes);
}

static int ch__find_node(const ch_character *c, const char *name)
{
    int i;
    for (i = 0; i < c->node_count; ++i)
        if (!strcmp(c->node_name[i], name)) return i;
    return -1;
}

static int ch__cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Where bone b's origin is in mesh space at bind: the offset matrix
   inverted, applied to 0. */
static void ch__bone_origin(const ch_character *c, int b, double o[3])
{
    const float *m = c->bone_offset[b];
    double a[9], det, inv[9];
    int k;
    for (k = 0; k < 9; ++k) a[k] = m[4 * (k / 3) + k % 3];
    inv[0] = a[4] * a[8] - a[5] * a[7];
    inv[1] = a[2] * a[7] - a[1] * a[8];
    inv[2] = a[1] * a[5] - a[2] * a[4];
    inv[3] = a[5] * a[6] - a[3] * a[8];
    inv[4] = a[0] * a[8] - a[2] * a[6];
    inv[5] = a[2] * a[3] - a[0] * a[5];
    inv[6] = a[3] * a[7] - a[4] * a[6];
    inv[7] = a[1] * a[6] - a[0] * a[7];
    inv[8] = a[0] * a[4] - a[1] * a[3];
    det = a[0] * inv[0] + a[1] * inv[3] + a[2] * inv[6];
    if (det == 0.0) det = 1.0;
    for (k = 0; k < 3; ++k)
        o[k] = -(inv[3 * k] * m[3] + inv[3 * k + 1] * m[7] +
                 inv[3 * k + 2] * m[11]) / det;
}

/* The direction from bone b's origin to the mean origin of the bones
   whose nodes are its node's children (mesh space at bind); 0 if it has
   none or they sit on it. */
static int ch__bone_axis(const ch_character *c, int b, double ax[3])
{
    double o[3], q[3], sum[3] = {0, 0, 0}, len;
    int j, k, n = 0;
    ch__bone_origin(c, b, o);
    for (j = 0; j < c->bone_count; ++j) {
        if (c->node_parent[c->bone_node[j]] != c->bone_node[b]) continue;
        ch__bone_origin(c, j, q);
        for (k = 0; k < 3; ++k) sum[k] += q[k];
        ++n;
    }
    if (n == 0) return 0;
    for (k = 0; k < 3; ++k) ax[k] = sum[k] / n - o[k];
    len = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    if (!(len > 1e-9)) return 0;
    for (k = 0; k < 3; ++k) ax[k] /= len;
    return 1;
}

/* The capsule of bone `b`: along the bone (towards its children; the
   principal axis of its vertices for a bone without) through the mean of
   the vertices it moves most (mesh space at bind), from the 10th to the 90th percentile
   of their spread along it, radius 0.8 of the 30th percentile of their
   distance to that axis, so that it stays inside the body there (roots
   that still end up inside it are handled by the library). 0 when the
   bone moves fewer than 12 vertices. */
static int ch__fit_capsule(const ch_character *c, int b, float *tmp,
                           ch_capsule *out)
{
    double mean[3] = {0, 0, 0}, cov[9] = {0}, ax[3] = {1, 1, 1}, len;
    int i, k, j, n = 0, it;
    float lo = 0.0f, hi = 0.0f, r = 0.0f;
    for (i = 0; i < c->vertex_count; ++i) {
        int best = 0;
        for (k = 1; k < CH_MAX_INFLUENCES; ++k)
            if (c->vweight[i][k] > c->vweight[i][best]) best = k;
        if (c->vmat[i][best] != b || c->vweight[i][best] <= 0.0f) continue;
        for (k = 0; k < 3; ++k) mean[k] += c->raw[i].pos[k];
        ++n;
    }
    if (n < 12) return 0;
    for (k = 0; k < 3; ++k) mean[k] /= n;
    for (i = 0; i < c->vertex_count; ++i) {
        int best = 0;
        double d[3];
        for (k = 1; k < CH_MAX_INFLUENCES; ++k)
            if (c->vweight[i][k] > c->vweight[i][best]) best = k;
        if (c->vmat[i][best] != b || c->vweight[i][best] <= 0.0f) continue;
        for (k = 0; k < 3; ++k) d[k] = c->raw[i].pos[k] - mean[k];
        for (k = 0; k < 3; ++k)
            for (j = 0; j < 3; ++j) cov[3 * k + j] += d[k] * d[j];
    }
    if (ch__bone_axis(c, b, ax)) it = 64; /* along the bone when it has one */
    else it = 0;
    for (; it < 64; ++it) { /* power iteration: the largest axis */
        double nx[3];
        for (k = 0; k < 3; ++k)
            nx[k] = cov[3 * k] * ax[0] + cov[3 * k + 1] * ax[1] +
                    cov[3 * k + 2] * ax[2];
        len = sqrt(nx[0] * nx[0] + nx[1] * nx[1] + nx[2] * nx[2]);
        if (!(len > 0.0)) { ax[0] = 1; ax[1] = ax[2] = 0; break; }
        for (k = 0; k < 3; ++k) ax[k] = nx[k] / len;
    }
    /* spread along the axis, then distance to it */
    for (j = 0; j < 2; ++j) {
        int m = 0;
        for (i = 0; i < c->vertex_count; ++i) {
            int best = 0;
            double d[3], t;
            for (k = 1; k < CH_MAX_INFLUENCES; ++k)
                if (c->vweight[i][k] > c->vweight[i][best]) best = k;
            if (c->vmat[i][best] != b || c->vweight[i][best] <= 0.0f) continue;
            for (k = 0; k < 3; ++k) d[k] = c->raw[i].pos[k] - mean[k];
            t = d[0] * ax[0] + d[1] * ax[1] + d[2] * ax[2];
            if (j == 0) tmp[m++] = (float)t;
            else {
                for (k = 0; k < 3; ++k) d[k] -= t * ax[k];
                tmp[m++] = (float)sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            }
        }
        qsort(tmp, (size_t)m, sizeof *tmp, ch__cmp_float);
        if (j == 0) {
            lo = tmp[m / 10];
            hi = tmp[m - 1 - m / 10];
        } else {
            r = 0.8f * tmp[(3 * m) / 10];
        }
    }
    if (!(r > 0.0f)) return 0;
    /* the caps end where the spread does */
    if (hi - lo > 2.0f * r) { lo += r; hi -= r; }
    else lo = hi = 0.5f * (lo + hi);
    out->bone = b;
    out->radius = r;
    for (k = 0; k < 3; ++k) {
        out->a[k] = (float)(mean[k] + lo * ax[k]);
        out->b[k] = (float)(mean[k] + hi * ax[k]);
    }
    return 1;
}

static void ch__err(char *err, size_t n, const char *path, const char *why)
{
    if (err && n) snprintf(err, n, "%s: %s", path, why);
}

static float ch__unit(const char *unit, double diag, int *ok)
{
    char *end;
    double u;
    *ok = 1;
    if (!unit || !*unit || !strcmp(unit, "auto"))
        return diag <= 20.0 ? 1.0f : diag <= 2000.0 ? 0.01f : 0.001f;
    if (!strcmp(unit, "m")) return 1.0f;
    if (!strcmp(unit, "cm")) return 0.01f;
    if (!strcmp(unit, "mm")) return 0.001f;
    u = strtod(unit, &end);
    if (end == unit || *end || !(u > 0.0) || !(u < 1e6)) *ok = 0;
    return (float)u;
}

/* Every array of *c sized from the scene (nv vertices, nt triangles,
   max_ch channels per animation), zeroed, and *nodes, the scene's nodes
   in flattened order; 0 when out of memory. */
static int ch__alloc(ch_character *c, const struct aiScene *sc, size_t nv,
                     size_t nt, int max_ch, const struct aiNode ***nodes)
{
    unsigned m;
    c->raw = (ch_vertex *)calloc(nv, sizeof *c->raw);
    c->indices = (uint32_t *)calloc(3 * nt, sizeof *c->indices);
    c->parts = (ch_part *)calloc((size_t)c->part_count, sizeof *c->parts);
    c->vmat = (int (*)[CH_MAX_INFLUENCES])calloc(nv, sizeof *c->vmat);
    c->vweight = (float (*)[CH_MAX_INFLUENCES])calloc(nv, sizeof *c->vweight);
    c->node_name = (char (*)[CH_NAME])calloc((size_t)c->node_count, CH_NAME);
    c->node_parent = (int *)calloc((size_t)c->node_count, sizeof(int));
    c->node_local = (float (*)[12])calloc((size_t)c->node_count, sizeof *c->node_local);
    c->global = (float (*)[12])calloc((size_t)c->node_count, sizeof *c->global);
    *nodes = (const struct aiNode **)calloc((size_t)c->node_count, sizeof **nodes);
    c->animation_name = (char (*)[CH_NAME])calloc((size_t)c->animation_count + 1, CH_NAME);
    c->channel_node = (int *)calloc((size_t)(c->animation_count * max_ch) + 1, sizeof(int));
    c->anim_ticks_per_s = (double *)calloc((size_t)c->animation_count + 1, sizeof(double));
    c->anim_duration = (double *)calloc((size_t)c->animation_count + 1, sizeof(double));
    for (m = 0; m < sc->mNumMeshes; ++m) c->bone_count += (int)sc->mMeshes[m]->mNumBones;
    c->bone_node = (int *)calloc((size_t)c->bone_count + 1, sizeof(int));
    c->bone_offset = (float (*)[12])calloc((size_t)c->bone_count + 1, sizeof *c->bone_offset);
    c->skin = (float (*)[12])calloc((size_t)(c->bone_count + c->node_count), sizeof *c->skin);
    c->capsules = (ch_capsule *)calloc((size_t)c->bone_count + 1, sizeof *c->capsules);
    return c->raw && c->indices && c->parts && c->vmat && c->vweight &&
           c->node_name && c->node_parent && c->node_local && c->global &&
           *nodes && c->animation_name && c->channel_node &&
           c->anim_ticks_per_s && c->anim_duration && c->bone_node &&
           c->bone_offset && c->skin && c->capsules;
}

/* Mesh m of the scene as the next part: its vertices from *vo, its
   triangles from *to, its bones from *b (each advanced past them), and
   the weights they give its vertices. */
static void ch__read_mesh(ch_character *c, const struct aiScene *sc,
                          unsigned m, const struct aiNode **nodes,
                          size_t *vo, size_t *to, int *b)
{
    const struct aiMesh *me = sc->mMeshes[m];
    ch_part *p = &c->parts[c->part_count++];
    int owner = 0, k;
    unsigned i, bi, w;
    ch__copy_name(p->name, &me->mName);
    p->first_vertex = (int)*vo;
    p->vertex_count = (int)me->mNumVertices;
    p->first_triangle = (int)*to;
    p->has_uvs = me->mTextureCoords[0] != NULL;
    p->has_bones = me->mNumBones > 0;
    /* a mesh without bones follows the (first) node that holds it */
    for (k = 0; k < c->node_count; ++k) {
        unsigned j;
        for (j = 0; j < nodes[k]->mNumMeshes && nodes[k]->mMeshes; ++j)
            if (nodes[k]->mMeshes[j] == m) { owner = k; break; }
        if (owner) break;
    }
    for (i = 0; i < me->mNumVertices; ++i) {
        ch_vertex *v = &c->raw[*vo + i];
        v->pos[0] = me->mVertices[i].x;
        v->pos[1] = me->mVertices[i].y;
        v->pos[2] = me->mVertices[i].z;
        if (me->mNormals) {
            v->normal[0] = me->mNormals[i].x;
            v->normal[1] = me->mNormals[i].y;
            v->normal[2] = me->mNormals[i].z;
        }
        if (me->mTextureCoords[0]) {
            v->uv[0] = me->mTextureCoords[0][i].x;
            v->uv[1] = me->mTextureCoords[0][i].y;
        }
        if (!p->has_bones) {
            c->vmat[*vo + i][0] = c->bone_count + owner;
            c->vweight[*vo + i][0] = 1.0f;
        }
    }
    for (bi = 0; bi < me->mNumBones; ++bi, ++*b) {
        const struct aiBone *bone = me->mBones[bi];
        char name[CH_NAME];
        ch__copy_name(name, &bone->mName);
        c->bone_node[*b] = ch__find_node(c, name);
        if (c->bone_node[*b] < 0) c->bone_node[*b] = 0;
        ch__from_ai(&bone->mOffsetMatrix, c->bone_offset[*b]);
        for (w = 0; w < bone->mNumWeights; ++w) {
            unsigned vid = bone->mWeights[w].mVertexId;
            float wt = bone->mWeights[w].mWeight;
            float *ws;
            int slot = 0;
            if (vid >= me->mNumVertices || !(wt > 0.0f)) continue;
            ws = c->vweight[*vo + vid];
            for (k = 1; k < CH_MAX_INFLUENCES; ++k)
                if (ws[k] < ws[slot]) slot = k;
            if (wt > ws[slot]) {
                ws[slot] = wt;
                c->vmat[*vo + vid][slot] = *b;
            }
        }
    }
    for (i = 0; i < me->mNumFaces; ++i) {
        const struct aiFace *f = &me->mFaces[i];
        if (f->mNumIndices != 3) continue;
        for (k = 0; k < 3; ++k)
            c->indices[3 * *to + (size_t)k] = (uint32_t)*vo + f->mIndices[k];
        ++*to;
    }
    p->triangle_count = (int)*to - p->first_triangle;
    *vo += me->mNumVertices;
}

/* Weights sum to 1; a skinned vertex no bone holds stays where it is (the
   first bone's matrix, weight 0, would collapse it). */
static void ch__normalize_weights(ch_character *c)
{
    int i, k;
    for (i = 0; i < c->vertex_count; ++i) {
        float s = 0.0f;
        for (k = 0; k < CH_MAX_INFLUENCES; ++k) s += c->vweight[i][k];
        if (s > 0.0f)
            for (k = 0; k < CH_MAX_INFLUENCES; ++k) c->vweight[i][k] /= s;
        else {
            c->vmat[i][0] = c->bone_count; /* the root node: static */
            c->vweight[i][0] = 1.0f;
        }
    }
}

/* The animations: names, timing, and which node each channel moves. */
static void ch__read_animations(ch_character *c, const struct aiScene *sc,
                                int max_ch)
{
    unsigned a, ch;
    for (a = 0; a < sc->mNumAnimations; ++a) {
        const struct aiAnimation *an = sc->mAnimations[a];
        ch__copy_name(c->animation_name[a], &an->mName);
        if (!c->animation_name[a][0])
            snprintf(c->animation_name[a], CH_NAME, "animation%u", a);
        c->anim_ticks_per_s[a] = an->mTicksPerSecond > 0 ? an->mTicksPerSecond : 25.0;
        c->anim_duration[a] = an->mDuration;
        for (ch = 0; ch < an->mNumChannels; ++ch) {
            char name[CH_NAME];
            ch__copy_name(name, &an->mChannels[ch]->mNodeName);
            c->channel_node[(int)a * max_ch + (int)ch] = ch__find_node(c, name);
        }
    }
}

/* The diagonal of the box of the file's pose, in file units, into *diag;
   0 when out of memory. */
static int ch__pose_diagonal(ch_character *c, double *diag)
{
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
    ch_vertex *v = (ch_vertex *)malloc(sizeof(ch_vertex) * (size_t)c->vertex_count);
    int i, k;
    if (!v) return 0;
    ch_pose(c, -1, 0.0, v, NULL);
    for (i = 0; i < c->vertex_count; ++i)
        for (k = 0; k < 3; ++k) {
            if (v[i].pos[k] < lo[k]) lo[k] = v[i].pos[k];
            if (v[i].pos[k] > hi[k]) hi[k] = v[i].pos[k];
        }
    free(v);
    *diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                 (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return 1;
}

int ch_load(ch_character *c, const char *path, const char *unit, char *err,
            size_t err_size)
{
    const struct aiScene *sc;
    const struct aiNode **nodes = NULL;
    unsigned m, a;
    size_t nv = 0, nt = 0, vo = 0, to = 0;
    int at = 0, b, ok, max_ch = 0;
    float *tmp;
    double diag;

    memset(c, 0, sizeof *c);
    sc = aiImportFile(path, aiProcess_Triangulate |
                                aiProcess_JoinIdenticalVertices |
                                aiProcess_GenSmoothNormals |
                                aiProcess_LimitBoneWeights |
                                aiProcess_SortByPType);
    if (!sc) {
        ch__err(err, err_size, path, aiGetErrorString());
        return 0;
    }
    c->scene = sc;
    for (m = 0; m < sc->mNumMeshes; ++m) {
        const struct aiMesh *me = sc->mMeshes[m];
        if (!(me->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        nv += me->mNumVertices;
        nt += me->mNumFaces;
        ++c->part_count;
    }
    if (nv == 0 || nt == 0 || nv > 0x7fffffff || nt > 0x7fffffff / 3) {
        ch__err(err, err_size, path, "no triangle mesh in the file");
        ch_free(c);
        return 0;
    }
    c->node_count = ch__count_nodes(sc->mRootNode);
    if (c->node_count < 1) {
        ch__err(err, err_size, path, "no node tree in the file");
        ch_free(c);
        return 0;
    }
    for (a = 0; a < sc->mNumAnimations; ++a)
        if ((int)sc->mAnimations[a]->mNumChannels > max_ch)
            max_ch = (int)sc->mAnimations[a]->mNumChannels;
    c->animation_count = (int)sc->mNumAnimations;
    c->channel_stride = max_ch;
    ok = ch__alloc(c, sc, nv, nt, max_ch, &nodes);
    tmp = (float *)malloc(sizeof(float) * nv);
    if (!ok || !tmp) {
        ch__err(err, err_size, path, "out of memory");
        free(nodes);
        free(tmp);
        ch_free(c);
        return 0;
    }
    ch__flatten(c, sc->mRootNode, -1, &at, nodes);

    /* vertices, triangles and weights, mesh by mesh */
    c->part_count = 0;
    b = 0;
    for (m = 0; m < sc->mNumMeshes; ++m)
        if (sc->mMeshes[m]->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)
            ch__read_mesh(c, sc, m, nodes, &vo, &to, &b);
    c->vertex_count = (int)vo;
    c->triangle_count = (int)to;
    ch__normalize_weights(c);
    ch__read_animations(c, sc, max_ch);

    /* the unit, from the box of the file's pose */
    c->unit = 1.0f;
    if (!ch__pose_diagonal(c, &diag)) {
        ch__err(err, err_size, path, "out of memory");
        free(nodes);
        free(tmp);
        ch_free(c);
        return 0;
    }
    c->unit = ch__unit(unit, diag, &ok);
    if (!ok || !(diag > 0.0) || !isfinite(diag)) {
        ch__err(err, err_size, path, !ok ? "bad --unit (auto, m, cm, mm or "
                "metres per file unit)" : "the mesh has no extent, or a "
                "position that is not finite");
        free(nodes);
        free(tmp);
        ch_free(c);
        return 0;
    }

    for (b = 0; b < c->bone_count; ++b)
        c->capsule_count += ch__fit_capsule(c, b, tmp, &c->capsules[c->capsule_count]);
    free(nodes);
    free(tmp);
    return 1;
}

int ch_fit_sphere(ch_character *c, int first, int count)
{
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    float centre[3], *d;
    int *votes, i, k, best = 0;
    if (count < 12 || c->capsule_count > c->bone_count || c->bone_count < 1)
        return 0;
    d = (float *)malloc(sizeof(float) * (size_t)count);
    votes = (int *)calloc((size_t)c->bone_count, sizeof(int));
    if (!d || !votes) { free(d); free(votes); return 0; }
    for (i = first; i < first + count; ++i) {
        int m = 0;
        for (k = 0; k < 3; ++k) {
            if (c->raw[i].pos[k] < lo[k]) lo[k] = c->raw[i].pos[k];
            if (c->raw[i].pos[k] > hi[k]) hi[k] = c->raw[i].pos[k];
        }
        for (k = 1; k < CH_MAX_INFLUENCES; ++k)
            if (c->vweight[i][k] > c->vweight[i][m]) m = k;
        if (c->vmat[i][m] < c->bone_count) ++votes[c->vmat[i][m]];
    }
    for (k = 1; k < c->bone_count; ++k)
        if (votes[k] > votes[best]) best = k;
    for (k = 0; k < 3; ++k) centre[k] = 0.5f * (lo[k] + hi[k]);
    for (i = 0; i < count; ++i) {
        const float *q = c->raw[first + i].pos;
        d[i] = sqrtf((q[0] - centre[0]) * (q[0] - centre[0]) +
                     (q[1] - centre[1]) * (q[1] - centre[1]) +
                     (q[2] - centre[2]) * (q[2] - centre[2]));
    }
    qsort(d, (size_t)count, sizeof *d, ch__cmp_float);
    if (votes[best] > 0 && d[count / 4] > 0.0f) {
        ch_capsule *o = &c->capsules[c->capsule_count++];
        o->bone = best;
        o->radius = 0.9f * d[count / 4];
        for (k = 0; k < 3; ++k) o->a[k] = o->b[k] = centre[k];
    } else {
        best = -1;
    }
    free(d);
    free(votes);
    return best >= 0;
}

void ch_free(ch_character *c)
{
    if (c->scene) aiReleaseImport((const struct aiScene *)c->scene);
    free(c->raw); free(c->indices); free(c->parts); free(c->vmat);
    free(c->vweight); free(c->node_name); free(c->node_parent);
    free(c->node_local); free(c->global); free(c->bone_node);
    free(c->bone_offset); free(c->skin); free(c->capsules);
    free(c->animation_name); free(c->channel_node);
    free(c->anim_ticks_per_s); free(c->anim_duration);
    memset(c, 0, sizeof *c);
}

int ch_find_animation(const ch_character *c, const char *name)
{
    int a;
    if (c->animation_count == 0) return -1;
    if (!name || !*name) return 0;
    for (a = 0; a < c->animation_count; ++a)
        if (!strcmp(c->animation_name[a], name)) return a;
    return -1;
}

double ch_animation_seconds(const ch_character *c, int anim)
{
    if (anim < 0 || anim >= c->animation_count) return 0.0;
    return c->anim_duration[anim] / c->anim_ticks_per_s[anim];
}

int ch_find_part(const ch_character *c, const char *name)
{
    int p;
    for (p = 0; p < c->part_count; ++p)
        if (!strcmp(c->parts[p].name, name)) return p;
    return -1;
}

/* Index of the last key at or before `t` (keys sorted by time). */
#define CH__KEY(keys, n, t, out)                                          \
    do {                                                                  \
        unsigned lo_ = 0, hi_ = (n);                                      \
        while (hi_ - lo_ > 1) {                                           \
            unsigned mid_ = (lo_ + hi_) / 2;                              \
            if ((keys)[mid_].mTime <= (t)) lo_ = mid_; else hi_ = mid_;   \
        }                                                                 \
        (out) = lo_;                                                      \
    } while (0)

static double ch__frac(double t0, double t1, double t)
{
    double f = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
    return f < 0.0 ? 0.0 : f > 1.0 ? 1.0 : f;
}

/* The local transform of a channel at tick t: T * R * S. */
static void ch__channel(const struct aiNodeAnim *na, double t, float o[12])
{
    double p[3] = {0, 0, 0}, s[3] = {1, 1, 1}, q[4] = {1, 0, 0, 0};
    unsigned k;
    if (na->mNumPositionKeys) {
        const struct aiVectorKey *ks = na->mPositionKeys;
        unsigned n = na->mNumPositionKeys, j;
        double f;
        CH__KEY(ks, n, t, k);
        j = k + 1 < n ? k + 1 : k;
        f = ch__frac(ks[k].mTime, ks[j].mTime, t);
        p[0] = ks[k].mValue.x + f * (ks[j].mValue.x - ks[k].mValue.x);
        p[1] = ks[k].mValue.y + f * (ks[j].mValue.y - ks[k].mValue.y);
        p[2] = ks[k].mValue.z + f * (ks[j].mValue.z - ks[k].mValue.z);
    }
    if (na->mNumScalingKeys) {
        const struct aiVectorKey *ks = na->mScalingKeys;
        unsigned n = na->mNumScalingKeys, j;
        double f;
        CH__KEY(ks, n, t, k);
        j = k + 1 < n ? k + 1 : k;
        f = ch__frac(ks[k].mTime, ks[j].mTime, t);
        s[0] = ks[k].mValue.x + f * (ks[j].mValue.x - ks[k].mValue.x);
        s[1] = ks[k].mValue.y + f * (ks[j].mValue.y - ks[k].mValue.y);
        s[2] = ks[k].mValue.z + f * (ks[j].mValue.z - ks[k].mValue.z);
    }
    if (na->mNumRotationKeys) {
        const struct aiQuatKey *ks = na->mRotationKeys;
        unsigned n = na->mNumRotationKeys, j;
        double f, a[4], b[4], d, w0, w1, len;
        CH__KEY(ks, n, t, k);
        j = k + 1 < n ? k + 1 : k;
        f = ch__frac(ks[k].mTime, ks[j].mTime, t);
        a[0] = ks[k].mValue.w; a[1] = ks[k].mValue.x;
        a[2] = ks[k].mValue.y; a[3] = ks[k].mValue.z;
        b[0] = ks[j].mValue.w; b[1] = ks[j].mValue.x;
        b[2] = ks[j].mValue.y; b[3] = ks[j].mValue.z;
        d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
        if (d < 0) { d = -d; b[0] = -b[0]; b[1] = -b[1]; b[2] = -b[2]; b[3] = -b[3]; }
        if (d > 0.9995) { w0 = 1 - f; w1 = f; } /* nearly equal: lerp */
        else {
            double th = acos(d), sn = sin(th);
            w0 = sin((1 - f) * th) / sn;
            w1 = sin(f * th) / sn;
        }
        for (k = 0; k < 4; ++k) q[k] = w0 * a[k] + w1 * b[k];
        len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (k = 0; k < 4; ++k) q[k] /= len > 0 ? len : 1;
    }
    {
        double w = q[0], x = q[1], y = q[2], z = q[3];
        double r[9];
        int i2, j2;
        r[0] = 1 - 2 * (y * y + z * z); r[1] = 2 * (x * y - w * z); r[2] = 2 * (x * z + w * y);
        r[3] = 2 * (x * y + w * z); r[4] = 1 - 2 * (x * x + z * z); r[5] = 2 * (y * z - w * x);
        r[6] = 2 * (x * z - w * y); r[7] = 2 * (y * z + w * x); r[8] = 1 - 2 * (x * x + y * y);
        for (i2 = 0; i2 < 3; ++i2) {
            for (j2 = 0; j2 < 3; ++j2) o[4 * i2 + j2] = (float)(r[3 * i2 + j2] * s[j2]);
            o[4 * i2 + 3] = (float)p[i2];
        }
    }
}

void ch_pose(ch_character *c, int anim, double seconds, ch_vertex *out,
             void *cols)
{
    const struct aiScene *sc = (const struct aiScene *)c->scene;
    const struct aiAnimation *an = NULL;
    double tick = 0.0;
    int n, b, i, k;
    float (*local)[12] = c->skin; /* scratch before the skin matrices */
    if (anim >= 0 && anim < c->animation_count) {
        double d = c->anim_duration[anim];
        an = sc->mAnimations[anim];
        tick = seconds * c->anim_ticks_per_s[anim];
        if (d > 0.0) tick = fmod(tick, d);
        if (tick < 0.0) tick += d;
    }
    for (n = 0; n < c->node_count; ++n)
        memcpy(local[n], c->node_local[n], sizeof local[n]);
    if (an)
        for (i = 0; i < (int)an->mNumChannels; ++i) {
            int node = c->channel_node[anim * c->channel_stride + i];
            if (node >= 0) ch__channel(an->mChannels[i], tick, local[node]);
        }
    for (n = 0; n < c->node_count; ++n) {
        if (c->node_parent[n] < 0) memcpy(c->global[n], local[n], sizeof local[n]);
        else ch__mul(c->global[c->node_parent[n]], local[n], c->global[n]);
    }
    /* skin matrices, scaled to metres: bones, then the nodes themselves */
    for (b = 0; b < c->bone_count; ++b)
        ch__mul(c->global[c->bone_node[b]], c->bone_offset[b], c->skin[b]);
    for (n = 0; n < c->node_count; ++n)
        memcpy(c->skin[c->bone_count + n], c->global[n], sizeof c->global[n]);
    for (b = 0; b < c->bone_count + c->node_count; ++b)
        for (k = 0; k < 12; ++k) c->skin[b][k] *= c->unit;
    for (i = 0; i < c->vertex_count; ++i) {
        const ch_vertex *r = &c->raw[i];
        ch_vertex *o = &out[i];
        float p[3] = {0, 0, 0}, q[3] = {0, 0, 0}, t[3], len;
        for (k = 0; k < CH_MAX_INFLUENCES; ++k) {
            float w = c->vweight[i][k];
            int j;
            if (w == 0.0f) continue;
            ch__xform(c->skin[c->vmat[i][k]], r->pos, 1.0f, t);
            for (j = 0; j < 3; ++j) p[j] += w * t[j];
            ch__xform(c->skin[c->vmat[i][k]], r->normal, 0.0f, t);
            for (j = 0; j < 3; ++j) q[j] += w * t[j];
        }
        len = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        for (k = 0; k < 3; ++k) {
            o->pos[k] = p[k];
            o->normal[k] = len > 0.0f ? q[k] / len : 0.0f;
        }
        o->uv[0] = r->uv[0];
        o->uv[1] = r->uv[1];
    }
    if (cols) {
        hf_collider *col = (hf_collider *)cols;
        for (i = 0; i < c->capsule_count; ++i) {
            const ch_capsule *cp = &c->capsules[i];
            const float *m = c->skin[cp->bone];
            /* the radius scales with the matrix's first column: the unit,
               and any uniform scale in the bones */
            float s = sqrtf(m[0] * m[0] + m[4] * m[4] + m[8] * m[8]);
            memset(&col[i], 0, sizeof col[i]);
            col[i].type = HF_COLLIDER_CAPSULE;
            ch__xform(m, cp->a, 1.0f, col[i].a);
            ch__xform(m, cp->b, 1.0f, col[i].b);
            col[i].radius = cp->radius * s;
        }
    }
}
#endif /* CHARACTER_IMPLEMENTATION */
