/* grow_fur.c - grow fur on a mesh, swing it, and export the ribbons.

   Shows the whole CPU pipeline through the hf_fur object: growth at
   creation (tessellation, guides, placement, maps), then per frame roots
   from the "skinned" mesh, rope simulation with colliders, LOD, guide and
   strand interpolation, and camera-facing ribbons with their index buffer.

   Usage:
     grow_fur [--mesh FILE] [--density PNG] [--length PNG] [--color PNG]
              [--strands N] [--points N] [--length-max F] [--frames N]
              [--lod F] [--seed N] [--out FILE.obj | FILE.ply]

   Without --mesh it grows on the built-in head (examples/head_mesh.h: a
   sphere of radius 0.1 with a procedural hairline density map and a bangs
   length map). --mesh loads any format assimp reads (OBJ, glTF, FBX, ...);
   all its meshes are merged, and the maps need its first UV channel. Maps
   are PNG (or anything stb_image reads): density and length use their first
   channel, colour its RGB. The head swings sideways (0.05 m at 1 Hz) and
   turns (+-25 degrees) for --frames frames of 1/60 s; a sphere collider
   follows the head. The last frame's ribbons, seen from the front, are
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

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct vtx {
    float pos[3], normal[3], uv[2];
} vtx;

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

static void usage(void)
{
    fprintf(stderr,
            "usage: grow_fur [--mesh FILE] [--density PNG] [--length PNG] "
            "[--color PNG] [--strands N] [--points N] [--length-max F] "
            "[--frames N] [--lod F] [--seed N] [--out FILE.obj|FILE.ply]\n");
}

/* Every mesh of the scene merged into one interleaved buffer. */
static int load_mesh(const char *path, vtx **out_v, uint32_t **out_i,
                     int *nv, int *nt)
{
    const struct aiScene *sc = aiImportFile(
        path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                  aiProcess_GenSmoothNormals | aiProcess_SortByPType);
    unsigned m, i;
    size_t v_total = 0, t_total = 0, vo = 0, to = 0;
    if (!sc) {
        fprintf(stderr, "grow_fur: cannot load %s: %s\n", path,
                aiGetErrorString());
        return 0;
    }
    for (m = 0; m < sc->mNumMeshes; ++m) {
        const struct aiMesh *me = sc->mMeshes[m];
        if (!(me->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        v_total += me->mNumVertices;
        t_total += me->mNumFaces;
    }
    if (v_total == 0 || t_total == 0 || v_total > 0x7fffffff ||
        t_total > 0x7fffffff / 3) {
        fprintf(stderr, "grow_fur: %s has no usable triangles\n", path);
        aiReleaseImport(sc);
        return 0;
    }
    *out_v = (vtx *)calloc(v_total, sizeof(vtx));
    *out_i = (uint32_t *)calloc(t_total * 3, sizeof(uint32_t));
    if (!*out_v || !*out_i) {
        aiReleaseImport(sc);
        return 0;
    }
    for (m = 0; m < sc->mNumMeshes; ++m) {
        const struct aiMesh *me = sc->mMeshes[m];
        if (!(me->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        for (i = 0; i < me->mNumVertices; ++i) {
            vtx *v = &(*out_v)[vo + i];
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
        }
        for (i = 0; i < me->mNumFaces; ++i) {
            const struct aiFace *f = &me->mFaces[i];
            if (f->mNumIndices != 3) continue;
            (*out_i)[3 * to] = (uint32_t)vo + f->mIndices[0];
            (*out_i)[3 * to + 1] = (uint32_t)vo + f->mIndices[1];
            (*out_i)[3 * to + 2] = (uint32_t)vo + f->mIndices[2];
            ++to;
        }
        vo += me->mNumVertices;
    }
    *nv = (int)vo;
    *nt = (int)to;
    aiReleaseImport(sc);
    return 1;
}

static int load_map(const char *path, int channels, hf_map *map)
{
    int w, h, n;
    unsigned char *px = stbi_load(path, &w, &h, &n, channels);
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

/* The scripted head motion at time t: a rigid transform (rotation about y
   by `yaw`, then a sideways offset). */
static void head_pose(double t, float m[12])
{
    double yaw = 0.436 * sin(2.0 * 3.14159265358979 * 0.5 * t);
    double dx = 0.05 * sin(2.0 * 3.14159265358979 * 1.0 * t);
    double c = cos(yaw), s = sin(yaw);
    /* rows: x' = m0 x + m1 y + m2 z + m3 ... */
    m[0] = (float)c;  m[1] = 0; m[2] = (float)s;  m[3] = (float)dx;
    m[4] = 0;         m[5] = 1; m[6] = 0;         m[7] = 0;
    m[8] = (float)-s; m[9] = 0; m[10] = (float)c; m[11] = 0;
}

static void xform(const float m[12], const float *p, float w, float *o)
{
    int r;
    for (r = 0; r < 3; ++r)
        o[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] +
               m[4 * r + 3] * w;
}

static int ends_with(const char *s, const char *suf)
{
    size_t a = strlen(s), b = strlen(suf);
    return a >= b && strcmp(s + a - b, suf) == 0;
}

int main(int argc, char **argv)
{
    const char *mesh_path = NULL, *density_path = NULL, *length_path = NULL,
               *color_path = NULL, *out_path = "fur.obj";
    int strands = 20000, points = 16, frames = 120, seed = 1, i, f;
    float lod = 1.0f, max_length = 0.12f;
    vtx *rest = NULL, *skin = NULL;
    uint32_t *idx = NULL;
    int nv = 0, nt = 0;
    hm_mesh head;
    hf_map density, length, color;
    int have_density = 0, have_length = 0, have_color = 0;
    hf_fur_desc desc;
    hf_fur *fur = NULL;
    hf_fur_info info;
    hf_diag diag;
    hf_result r;
    hf_mesh skinned;
    hf_rope_params rp;
    double *t_roots, *t_sim, *t_guides, *t_interp, *t_ribbons;
    float *vbuf = NULL;
    uint32_t *ibuf = NULL;
    long long n_idx;
    float center[3] = {0, 0, 0}, radius = 0.1f;

    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage();
            return 0;
        }
        if (!v) {
            usage();
            return 2;
        }
        if (!strcmp(a, "--mesh")) mesh_path = v;
        else if (!strcmp(a, "--density")) density_path = v;
        else if (!strcmp(a, "--length")) length_path = v;
        else if (!strcmp(a, "--color")) color_path = v;
        else if (!strcmp(a, "--out")) out_path = v;
        else if (!strcmp(a, "--strands")) strands = atoi(v);
        else if (!strcmp(a, "--points")) points = atoi(v);
        else if (!strcmp(a, "--frames")) frames = atoi(v);
        else if (!strcmp(a, "--seed")) seed = atoi(v);
        else if (!strcmp(a, "--lod")) lod = (float)atof(v);
        else if (!strcmp(a, "--length-max")) max_length = (float)atof(v);
        else {
            usage();
            return 2;
        }
        ++i;
    }
    if (strands < 1 || frames < 1 || points < 2 || points > HF_MAX_POINTS ||
        !(max_length > 0) || !(ends_with(out_path, ".obj") ||
                              ends_with(out_path, ".ply"))) {
        usage();
        return 2;
    }

    /* the mesh: a file through assimp, or the built-in head */
    if (mesh_path) {
        if (!load_mesh(mesh_path, &rest, &idx, &nv, &nt)) return 1;
    } else {
        if (!hm_sphere(24, 32, radius, &head)) return 1;
        nv = head.vertex_count;
        nt = head.triangle_count;
        rest = (vtx *)malloc(sizeof(vtx) * (size_t)nv);
        if (!rest) return 1;
        memcpy(rest, head.vertices, sizeof(vtx) * (size_t)nv);
        idx = head.indices;
        head.indices = NULL;
        hm_free(&head);
    }
    /* the collider: the mesh's bounding sphere, shrunk so roots sit on it */
    if (mesh_path) {
        float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
        int k;
        for (i = 0; i < nv; ++i)
            for (k = 0; k < 3; ++k) {
                lo[k] = rest[i].pos[k] < lo[k] ? rest[i].pos[k] : lo[k];
                hi[k] = rest[i].pos[k] > hi[k] ? rest[i].pos[k] : hi[k];
            }
        for (k = 0; k < 3; ++k) center[k] = 0.5f * (lo[k] + hi[k]);
        radius = 0.5f * 0.5f * (hi[0] - lo[0]); /* a conservative inner ball */
    }

    /* the maps: files, or the built-in ones for the built-in head */
    if (!get_map(density_path, 1, !mesh_path, hm_hairline_density, 256,
                 &density, &have_density) ||
        !get_map(length_path, 1, !mesh_path, hm_bangs_length, 256, &length,
                 &have_length) ||
        !get_map(color_path, 3, !mesh_path, hm_hair_color, 64, &color,
                 &have_color))
        return 1;

    /* grow */
    memset(&desc, 0, sizeof desc);
    desc.mesh.positions = rest[0].pos;
    desc.mesh.position_stride = (int)sizeof(vtx);
    desc.mesh.normals = mesh_path ? NULL : rest[0].normal;
    desc.mesh.normal_stride = (int)sizeof(vtx);
    desc.mesh.uvs = rest[0].uv;
    desc.mesh.uv_stride = (int)sizeof(vtx);
    desc.mesh.vertex_count = nv;
    desc.mesh.indices = idx;
    desc.mesh.triangle_count = nt;
    desc.density_map = have_density ? &density : NULL;
    desc.length_map = have_length ? &length : NULL;
    desc.color_map = have_color ? &color : NULL;
    desc.points_per_strand = points;
    desc.max_length = max_length;
    desc.total_strands = strands;
    desc.sampler = HF_SAMPLER_STRATIFIED;
    desc.seed = (uint64_t)seed;
    desc.clump = 0.2f;
    /* LOD guides where the mesh is coarse: about 4 cm^2 per guide triangle
       at full density */
    desc.tess_factor = 25000.0f;
    hf_rope_params_init(&rp);
    rp.global_stiffness_root = 0.3f;
    rp.global_stiffness_tip = 0.02f;
    rp.local_stiffness_root = 0.5f;
    rp.local_stiffness_tip = 0.1f;
    rp.root_stiffness = 0.8f;
    desc.rope_params = &rp;
    {
        double t0 = now_ms();
        r = hf_fur_create(&desc, &fur, &diag);
        if (r != HF_OK) {
            fprintf(stderr, "grow_fur: %s\n", diag.message);
            return 1;
        }
        hf_fur_get_info(fur, &info);
        printf("grown in %.1f ms: %d vertices, %d triangles -> %d guide "
               "triangles; %d guides (%d pure, %d LOD); %d strands of %d "
               "points\n",
               now_ms() - t0, nv, nt, info.triangle_count, info.guide_count,
               info.pure_guide_count, info.lod_guide_count,
               info.strand_count, info.points_per_strand);
    }
    hf_fur_set_lod(fur, lod);
    hf_fur_get_info(fur, &info);

    /* per frame: skin, roots, simulate, interpolate, ribbons */
    skin = (vtx *)malloc(sizeof(vtx) * (size_t)nv);
    vbuf = (float *)malloc(sizeof(float) * 12u * 2u * (size_t)info.strand_count *
                           (size_t)info.points_per_strand);
    t_roots = (double *)malloc(sizeof(double) * 5u * (size_t)frames);
    if (!skin || !vbuf || !t_roots) return 1;
    t_sim = t_roots + frames;
    t_guides = t_sim + frames;
    t_interp = t_guides + frames;
    t_ribbons = t_interp + frames;
    skinned = desc.mesh;
    skinned.positions = skin[0].pos;
    skinned.normals = skin[0].normal;
    skinned.uvs = skin[0].uv;
    for (f = 0; f < frames; ++f) {
        float m[12];
        hf_collider col;
        hf_ribbon_params view;
        hf_ribbon_output out;
        double t0, t1, t2, t3, t4, t5;
        head_pose((f + 1) / 60.0, m);
        for (i = 0; i < nv; ++i) {
            xform(m, rest[i].pos, 1.0f, skin[i].pos);
            xform(m, rest[i].normal, 0.0f, skin[i].normal);
            skin[i].uv[0] = rest[i].uv[0];
            skin[i].uv[1] = rest[i].uv[1];
        }
        if (mesh_path) skinned.normals = NULL; /* face normals from the mesh */
        memset(&col, 0, sizeof col);
        col.type = HF_COLLIDER_SPHERE;
        xform(m, center, 1.0f, col.a);
        col.radius = radius * 0.97f;

        memset(&view, 0, sizeof view);
        view.eye[2] = 0.6f;
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
        r = hf_fur_set_roots(fur, &skinned, 0, info.guide_count);
        t1 = now_ms();
        if (r == HF_OK)
            r = hf_fur_simulate(fur, 0, info.guide_count, 1.0f / 60.0f, &col, 1);
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
            return 1;
        }
        t_roots[f] = t1 - t0;
        t_sim[f] = t2 - t1;
        t_guides[f] = t3 - t2;
        t_interp[f] = t4 - t3;
        t_ribbons[f] = t5 - t4;
    }
    {
        float stretch = 0.0f;
        hf_fur_max_stretch(fur, &stretch);
        printf("%d frames at lod %.2f (%d of %d strands drawn), median ms: "
               "roots %.3f, ropes %.3f, LOD guides %.3f, strands %.3f, "
               "ribbons %.3f; max stretch %.3f %%\n",
               frames, (double)info.lod, info.drawn_strand_count,
               info.strand_count, median(t_roots, frames),
               median(t_sim, frames), median(t_guides, frames),
               median(t_interp, frames), median(t_ribbons, frames),
               100.0 * stretch);
        hf_fur_get_info(fur, &info);
        if (info.roots_inside > 0)
            printf("%d of %d guide roots sit inside the collider (for "
                   "those guides it is shrunk to the root's depth); if the "
                   "proxy is larger than the body there, shrink it\n",
                   info.roots_inside, info.guide_count);
    }

    /* export the last frame */
    n_idx = hf_ribbon_index_count(info.drawn_strand_count,
                                  info.points_per_strand, HF_TRIANGLES);
    ibuf = (uint32_t *)malloc(sizeof(uint32_t) * (size_t)n_idx);
    if (!ibuf ||
        hf_ribbon_indices(info.drawn_strand_count, info.points_per_strand,
                          HF_TRIANGLES, ibuf, n_idx) != HF_OK)
        return 1;
    {
        FILE *fp = fopen(out_path, "wb");
        long long nvert = 2LL * info.drawn_strand_count * info.points_per_strand;
        long long k;
        const float *uv;
        if (!fp) {
            fprintf(stderr, "grow_fur: cannot write %s\n", out_path);
            return 1;
        }
        if (ends_with(out_path, ".obj")) {
            fprintf(fp, "# hairfur.h grow_fur: %d strands, %d points each, "
                        "2 vertices per point\n",
                    info.drawn_strand_count, info.points_per_strand);
            for (k = 0; k < nvert; ++k)
                fprintf(fp, "v %.6f %.6f %.6f\n", vbuf[6 * k], vbuf[6 * k + 1],
                        vbuf[6 * k + 2]);
            for (k = 0; k < nvert; ++k) {
                /* vt: root uv of the strand (hairfur stores it per strand) */
                uv = info.strands[k / (2 * info.points_per_strand)].uv;
                fprintf(fp, "vt %.6f %.6f\n", uv[0], uv[1]);
            }
            for (k = 0; k < n_idx; k += 3)
                fprintf(fp, "f %u/%u %u/%u %u/%u\n", ibuf[k] + 1, ibuf[k] + 1,
                        ibuf[k + 1] + 1, ibuf[k + 1] + 1, ibuf[k + 2] + 1,
                        ibuf[k + 2] + 1);
        } else {
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
                    info.strand_colors + 4 * (k / (2 * info.points_per_strand));
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
        if (fclose(fp) != 0) {
            fprintf(stderr, "grow_fur: error writing %s\n", out_path);
            return 1;
        }
        printf("wrote %s: %lld vertices, %lld triangles\n", out_path, nvert,
               n_idx / 3);
    }

    hf_fur_destroy(fur);
    free(rest);
    free(skin);
    free(idx);
    free(vbuf);
    free(ibuf);
    free(t_roots);
    /* stb_image's buffers come from malloc too (no STBI_MALLOC here) */
    if (have_density) free((void *)density.data);
    if (have_length) free((void *)length.data);
    if (have_color) free((void *)color.data);
    return 0;
}
