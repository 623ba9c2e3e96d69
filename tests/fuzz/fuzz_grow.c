/* fuzz_grow.c - maps, meshes and the grow stages on fuzz-built input:
   hf_map_validate / sample / blur, hf_mesh_validate / compute_normals,
   hf_uv_triangle_density, hf_tessellate (both passes), hf_tess_evaluate,
   hf_guides_rest, hf_place_strands (both passes), hf_strand_roots /
   lengths / colors, hf_color3d_coord / sample, hf_bind_strands.

   Contracts checked (abort() on violation): every result is HF_OK or a
   code of the table; on failure every output buffer still holds its
   sentinel and every count its old value; on success outputs are finite
   and in their documented ranges, the second pass of a two-call function
   agrees with the first, a capacity one short gives
   HF_ERROR_BUFFER_TOO_SMALL and writes nothing, the same call twice gives
   the same bytes, and every block from the allocator is freed.

   libFuzzer: clang -g -O1 -fsanitize=fuzzer,address,undefined fuzz_grow.c
              fuzz_impl.c (the header's implementation)
   replay:    gcc -O1 -g fuzz_main.c fuzz_grow.c fuzz_impl.c -lm (see the
              Makefile) */
#include "../../hairfur.h"
#include "fuzz_common.h"

#include <math.h>

#define FZ_MAX_TESS_TRIANGLES 3000
#define FZ_MAX_STRANDS 3000

static void fz_check_unit(const float *n)
{
    double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] +
                    (double)n[2] * n[2]);
    FZ_REQUIRE(fabs(l - 1.0) < 1e-3);
}

static void fuzz_maps(fz_reader *r, const hf_map *map)
{
    hf_diag diag;
    hf_result rv = hf_map_validate(map, &diag), rs;
    float out[4], u, v, sentinel[4];
    int k;
    FZ_REQUIRE(fz_known_result(rv));
    FZ_REQUIRE(diag.result == rv);
    for (k = 0; k < 4; ++k) {
        memset(out, FZ_SENTINEL, sizeof out);
        memcpy(sentinel, out, sizeof out);
        u = fz_float(r, 4.0f);
        v = fz_float(r, 4.0f);
        rs = hf_map_sample(map, u, v, out);
        FZ_REQUIRE(fz_known_result(rs));
        if (rs != HF_OK) {
            FZ_REQUIRE(memcmp(out, sentinel, sizeof out) == 0);
        } else {
            FZ_REQUIRE(rv == HF_OK);
            FZ_REQUIRE(fz_all_finite(out, 4));
            if (map->format == HF_MAP_U8) {
                int c;
                for (c = 0; c < 4; ++c)
                    FZ_REQUIRE(out[c] >= 0.0f && out[c] <= 1.0f);
            }
        }
        if (rv != HF_OK) FZ_REQUIRE(rs != HF_OK);
    }
    /* blur, with an allocator that may fail */
    if (rv == HF_OK) {
        size_t n = (size_t)map->width * (size_t)map->height *
                   (size_t)map->channels;
        float *o = (float *)fz_sentinel_alloc(n * sizeof(float));
        fz_counter cnt;
        hf_allocator a = fz_counting(&cnt, fz_chance(r, 32) ? 0 : -1,
                                     (size_t)1 << 26);
        float sigma = fz_chance(r, 200) ? fz_float_in(r, 0.0f, 6.0f)
                                        : fz_float(r, 2000.0f);
        hf_result rb = hf_map_blur(map, sigma, o, &a);
        FZ_REQUIRE(fz_known_result(rb));
        FZ_REQUIRE(cnt.live == 0);
        if (rb != HF_OK) {
            FZ_REQUIRE(fz_untouched(o, n * sizeof(float)));
        } else if (!fz_all_finite(o, n)) {
            size_t i;
            fprintf(stderr, "blur: %dx%d ch %d fmt %d wrap %d sigma %g\n",
                    map->width, map->height, map->channels, map->format,
                    map->wrap, (double)sigma);
            for (i = 0; i < n && i < 64; ++i)
                fprintf(stderr, "  in[%d] %g out %g\n", (int)i,
                        map->format == HF_MAP_F32
                            ? (double)((const float *)map->data)[i]
                            : (double)((const uint8_t *)map->data)[i],
                        (double)o[i]);
            FZ_REQUIRE(fz_all_finite(o, n));
        }
        free(o);
    }
}

typedef struct fz_tess {
    uint32_t *indices, *triangle_base;
    hf_tess_vertex *added;
    float *positions, *uvs;
    hf_tess_output out;
} fz_tess;

static void fz_tess_alloc(fz_tess *t, int tris, int added, int verts,
                          int with_uvs)
{
    memset(t, 0, sizeof *t);
    t->indices = (uint32_t *)fz_sentinel_alloc(12u * (size_t)tris);
    t->triangle_base = (uint32_t *)fz_sentinel_alloc(4u * (size_t)tris);
    t->added = (hf_tess_vertex *)fz_sentinel_alloc(16u * (size_t)added);
    t->positions = (float *)fz_sentinel_alloc(12u * (size_t)verts);
    t->uvs = with_uvs ? (float *)fz_sentinel_alloc(8u * (size_t)verts) : NULL;
    t->out.indices = t->indices;
    t->out.triangle_base = t->triangle_base;
    t->out.added = t->added;
    t->out.positions = t->positions;
    t->out.uvs = t->uvs;
    t->out.triangle_capacity = tris;
    t->out.added_capacity = added;
    t->out.vertex_capacity = verts;
    t->out.triangle_count = t->out.added_count = -7;
    t->out.vertex_count = t->out.depth = -7;
}

static int fz_tess_untouched(const fz_tess *t, int tris, int added, int verts)
{
    return fz_untouched(t->indices, 12u * (size_t)tris) &&
           fz_untouched(t->triangle_base, 4u * (size_t)tris) &&
           fz_untouched(t->added, 16u * (size_t)added) &&
           fz_untouched(t->positions, 12u * (size_t)verts) &&
           (!t->uvs || fz_untouched(t->uvs, 8u * (size_t)verts)) &&
           t->out.triangle_count == -7 && t->out.added_count == -7 &&
           t->out.vertex_count == -7 && t->out.depth == -7;
}

static void fz_tess_free(fz_tess *t)
{
    free(t->indices);
    free(t->triangle_base);
    free(t->added);
    free(t->positions);
    free(t->uvs);
}

/* Everything downstream of a successful tessellation. */
static void fuzz_downstream(fz_reader *r, const hf_mesh *base,
                            const fz_tess *t, const hf_map *density,
                            const hf_map *length_map, const hf_map *color_map)
{
    const int V = t->out.vertex_count, T = t->out.triangle_count;
    const int A = t->out.added_count;
    hf_mesh tm;
    hf_guide_params gp;
    hf_guide_output go;
    hf_place_params pp;
    hf_result rr;
    fz_counter cnt;
    hf_allocator alloc;
    float *gpoints = NULL, *glengths = NULL, *gdirs = NULL, *gnormals = NULL;
    uint32_t *gov = NULL;
    hf_strand *strands = NULL;
    int guides = 0, n_strands = -7, first, count, i;

    /* ---- hf_tess_evaluate --------------------------------------------- */
    if (A > 0) {
        float *p = (float *)fz_sentinel_alloc(12u * (size_t)A);
        float *n = (float *)fz_sentinel_alloc(12u * (size_t)A);
        float *uv = (float *)fz_sentinel_alloc(8u * (size_t)A);
        int want_n = fz_u8(r) & 1, want_uv = fz_u8(r) & 1;
        fz_range(r, A, &first, &count);
        rr = hf_tess_evaluate(base, t->added, A, first, count, p,
                              want_n ? n : NULL, want_uv ? uv : NULL);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK) {
            FZ_REQUIRE(fz_untouched(p, 12u * (size_t)A));
            FZ_REQUIRE(fz_untouched(n, 12u * (size_t)A));
            FZ_REQUIRE(fz_untouched(uv, 8u * (size_t)A));
        } else {
            /* the rest mesh gives hf_tessellate's positions bit for bit */
            FZ_REQUIRE(memcmp(p + 3 * (size_t)first,
                              t->positions + 3 * ((size_t)base->vertex_count +
                                                  (size_t)first),
                              12u * (size_t)count) == 0);
            FZ_REQUIRE(fz_all_finite(p + 3 * (size_t)first, 3u * (size_t)count));
            FZ_REQUIRE(fz_untouched(p, 12u * (size_t)first));
            FZ_REQUIRE(fz_untouched(p + 3 * ((size_t)first + (size_t)count),
                                    12u * (size_t)(A - first - count)));
            if (want_n) {
                FZ_REQUIRE(fz_all_finite(n + 3 * (size_t)first,
                                         3u * (size_t)count));
                for (i = first; i < first + count; ++i)
                    fz_check_unit(n + 3 * i);
            }
            if (want_uv)
                FZ_REQUIRE(fz_all_finite(uv + 2 * (size_t)first,
                                         2u * (size_t)count));
        }
        free(p);
        free(n);
        free(uv);
    }

    /* the tessellated mesh */
    memset(&tm, 0, sizeof tm);
    tm.positions = t->positions;
    tm.uvs = t->uvs;
    tm.vertex_count = V;
    tm.indices = t->indices;
    tm.triangle_count = T;

    /* ---- hf_guides_rest ----------------------------------------------- */
    memset(&gp, 0, sizeof gp);
    gp.points = fz_chance(r, 250) ? fz_int(r, 2, 8) : fz_int(r, -1, 300);
    gp.max_length = fz_chance(r, 240) ? fz_float_in(r, 0.01f, 2.0f)
                                      : fz_float(r, 1e3f);
    gp.length_map = (fz_u8(r) & 1) ? length_map : NULL;
    gp.comb_map = fz_chance(r, 64) ? color_map : NULL;
    if (gp.points > HF_GUIDE_MAX_POINTS) gp.points = 9999; /* refused */
#ifdef FZ_SKIP_KNOWN
    if (fz_finite(gp.max_length) && gp.max_length > 1e6f) gp.max_length = 1e6f;
#endif
    memset(&go, 0, sizeof go);
    go.guide_count = go.pure_guide_count = -7;
    alloc = fz_counting(&cnt, fz_chance(r, 16) ? fz_int(r, 0, 3) : -1,
                        (size_t)1 << 26);
    rr = hf_guides_rest(base, t->added, A, &gp, &go, &alloc);
    FZ_REQUIRE(fz_known_result(rr));
    FZ_REQUIRE(cnt.live == 0);
    if (rr != HF_OK) {
        FZ_REQUIRE(go.guide_count == -7 && go.pure_guide_count == -7);
    } else {
        hf_guide_output g2;
        int P = gp.points;
        guides = go.guide_count;
        FZ_REQUIRE(guides >= 1 && go.pure_guide_count >= 1 &&
                   go.pure_guide_count <= base->vertex_count &&
                   guides == go.pure_guide_count + A);
        gpoints = (float *)fz_sentinel_alloc(12u * (size_t)P * (size_t)guides);
        glengths = (float *)fz_sentinel_alloc(4u * (size_t)guides);
        gdirs = (float *)fz_sentinel_alloc(12u * (size_t)guides);
        gnormals = (float *)fz_sentinel_alloc(12u * (size_t)guides);
        gov = (uint32_t *)fz_sentinel_alloc(4u * (size_t)V);
        memset(&g2, 0, sizeof g2);
        g2.points = gpoints;
        g2.lengths = glengths;
        g2.directions = gdirs;
        g2.normals = gnormals;
        g2.guide_of_vertex = gov;
        g2.guide_capacity = guides - 1;
        g2.guide_count = g2.pure_guide_count = -7;
        /* one short: nothing written */
        rr = hf_guides_rest(base, t->added, A, &gp, &g2, NULL);
        FZ_REQUIRE(rr == HF_ERROR_BUFFER_TOO_SMALL);
        FZ_REQUIRE(fz_untouched(gpoints, 12u * (size_t)P * (size_t)guides) &&
                   fz_untouched(gov, 4u * (size_t)V) &&
                   g2.guide_count == -7);
        g2.guide_capacity = guides;
        alloc = fz_counting(&cnt, -1, (size_t)1 << 26);
        rr = hf_guides_rest(base, t->added, A, &gp, &g2, &alloc);
        FZ_REQUIRE(rr == HF_OK && g2.guide_count == guides);
        FZ_REQUIRE(cnt.live == 0);
        FZ_REQUIRE(fz_all_finite(gpoints, 3u * (size_t)P * (size_t)guides));
        FZ_REQUIRE(fz_all_finite(glengths, (size_t)guides));
        for (i = 0; i < guides; ++i) {
            FZ_REQUIRE(glengths[i] >= 0.0f);
            fz_check_unit(gdirs + 3 * i);
            fz_check_unit(gnormals + 3 * i);
        }
        for (i = 0; i < V; ++i) FZ_REQUIRE(gov[i] < (uint32_t)guides);
    }

    /* ---- hf_place_strands ---------------------------------------------- */
    memset(&pp, 0, sizeof pp);
    pp.strands_per_area = fz_chance(r, 230) ? fz_float_in(r, 0.0f, 60.0f)
                                            : fz_float(r, 1e4f);
    pp.total_strands = fz_chance(r, 64) ? fz_int(r, -1, 500) : 0;
    pp.estimator = fz_chance(r, 250) ? fz_int(r, 0, 2) : fz_int(r, -1, 9);
    pp.sampler = fz_chance(r, 250) ? fz_int(r, 0, 2) : fz_int(r, -1, 9);
    pp.seed = fz_u32(r);
    pp.max_strands = fz_chance(r, 16) ? fz_int(r, -1, 0)
                                      : fz_int(r, 1, FZ_MAX_STRANDS);
    pp.refuse_degenerate = fz_u8(r) & 1;
    rr = hf_place_strands(&tm, density, &pp, NULL, 0, &n_strands, NULL);
    FZ_REQUIRE(fz_known_result(rr));
    if (rr != HF_OK) {
        FZ_REQUIRE(n_strands == -7);
    } else if (n_strands <= FZ_MAX_STRANDS) {
        hf_strand *s2;
        int n2 = -7;
        FZ_REQUIRE(n_strands >= 0);
        if (pp.total_strands > 0) FZ_REQUIRE(n_strands == pp.total_strands);
        strands = (hf_strand *)fz_sentinel_alloc(sizeof(hf_strand) *
                                                 (size_t)n_strands);
        if (n_strands > 0) {
            rr = hf_place_strands(&tm, density, &pp, strands, n_strands - 1,
                                  &n2, NULL);
            FZ_REQUIRE(rr == HF_ERROR_BUFFER_TOO_SMALL && n2 == -7);
            FZ_REQUIRE(fz_untouched(strands,
                                    sizeof(hf_strand) * (size_t)n_strands));
        }
        alloc = fz_counting(&cnt, fz_chance(r, 16) ? 0 : -1, (size_t)1 << 26);
        rr = hf_place_strands(&tm, density, &pp, strands, n_strands, &n2,
                              &alloc);
        FZ_REQUIRE(cnt.live == 0);
        FZ_REQUIRE(rr == HF_OK || rr == HF_ERROR_OUT_OF_MEMORY);
        if (rr != HF_OK) {
            FZ_REQUIRE(n2 == -7 && fz_untouched(strands, sizeof(hf_strand) *
                                                             (size_t)n_strands));
            n_strands = 0;
        } else {
            FZ_REQUIRE(n2 == n_strands);
            for (i = 0; i < n_strands; ++i) {
                const hf_strand *s = strands + i;
                FZ_REQUIRE(s->triangle < (uint32_t)T);
                FZ_REQUIRE(fz_all_finite(s->bary, 2) &&
                           fz_all_finite(s->uv, 2));
                FZ_REQUIRE(s->bary[0] >= 0.0f && s->bary[1] >= 0.0f &&
                           s->bary[0] + s->bary[1] <= 1.0f + 1e-5f);
                FZ_REQUIRE(s->random >= 0.0f && s->random < 1.0f);
            }
            /* deterministic */
            s2 = (hf_strand *)malloc(sizeof(hf_strand) * (size_t)n_strands + 1);
            rr = hf_place_strands(&tm, density, &pp, s2, n_strands, &n2, NULL);
            FZ_REQUIRE(rr == HF_OK && memcmp(s2, strands, sizeof(hf_strand) *
                                                          (size_t)n_strands) == 0);
            free(s2);
        }
    } else {
        n_strands = 0;
    }

    /* ---- per-strand functions ------------------------------------------ */
    if (strands && n_strands > 0) {
        const int N = n_strands;
        float *roots = (float *)fz_sentinel_alloc(12u * (size_t)N);
        float *lens = (float *)fz_sentinel_alloc(4u * (size_t)N);
        float *rgba = (float *)fz_sentinel_alloc(16u * (size_t)N);
        hf_strand_binding *b = (hf_strand_binding *)fz_sentinel_alloc(
            sizeof(hf_strand_binding) * (size_t)N);
        float max_length = fz_chance(r, 240) ? fz_float_in(r, 0.0f, 3.0f)
                                             : fz_float(r, 1e30f);
        int ok_lens;
#ifdef FZ_SKIP_KNOWN
        /* known bug (regressions/grow-strand-lengths-overflow-inf.bin):
           max_length * map value overflows to inf */
        if (fz_finite(max_length) && max_length > 1e6f) max_length = 1e6f;
#endif

        fz_range(r, N, &first, &count);
        rr = hf_strand_roots(&tm, strands, N, first, count, roots);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK)
            FZ_REQUIRE(fz_untouched(roots, 12u * (size_t)N));
        else
            FZ_REQUIRE(fz_all_finite(roots + 3 * (size_t)first,
                                     3u * (size_t)count));

        rr = hf_strand_lengths(strands, N, 0, N,
                               (fz_u8(r) & 1) ? length_map : NULL, max_length,
                               lens);
        FZ_REQUIRE(fz_known_result(rr));
        ok_lens = rr == HF_OK;
        if (rr != HF_OK) {
            FZ_REQUIRE(fz_untouched(lens, 4u * (size_t)N));
        } else {
            FZ_REQUIRE(fz_all_finite(lens, (size_t)N));
            for (i = 0; i < N; ++i) FZ_REQUIRE(lens[i] >= 0.0f);
        }

        fz_range(r, N, &first, &count);
        rr = hf_strand_colors(strands, N, first, count, color_map, rgba);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK)
            FZ_REQUIRE(fz_untouched(rgba, 16u * (size_t)N));
        else
            FZ_REQUIRE(fz_all_finite(rgba + 4 * (size_t)first,
                                     4u * (size_t)count));

        if (gov) {
            int with_lengths = ok_lens && (fz_u8(r) & 1);
            fz_range(r, N, &first, &count);
            rr = hf_bind_strands(&tm, gov, guides, strands, N, first, count,
                                 with_lengths ? lens : NULL,
                                 with_lengths ? glengths : NULL, b);
            FZ_REQUIRE(fz_known_result(rr));
            if (rr != HF_OK) {
                FZ_REQUIRE(fz_untouched(b, sizeof(hf_strand_binding) *
                                               (size_t)N));
            } else {
                for (i = first; i < first + count; ++i) {
                    int k;
                    for (k = 0; k < 3; ++k)
                        FZ_REQUIRE(b[i].guide[k] < (uint32_t)guides);
                    FZ_REQUIRE(fz_all_finite(b[i].weight, 3) &&
                               fz_finite(b[i].length_scale));
                }
            }
        }
        free(roots);
        free(lens);
        free(rgba);
        free(b);
    }
    free(strands);
    free(gpoints);
    free(glengths);
    free(gdirs);
    free(gnormals);
    free(gov);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader r;
    fz_mesh m;
    fz_map dm, lm, cm;
    hf_map *density;
    hf_diag diag;
    hf_result rv, rr;
    hf_tess_params tp;
    hf_tess_output cnt_out;
    float *normals;
    int nv, k;

    fz_init(&r, data, size);
    fz_make_mesh(&r, &m, 16, 12, 2.0f);
    fz_make_map(&r, &dm, 8, 8, 1);
    fz_make_map(&r, &lm, 4, 4, 1);
    fz_make_map(&r, &cm, 4, 4, 1);
    density = (fz_u8(&r) & 3) ? &dm.map : NULL;
    nv = m.mesh.vertex_count > 0 ? m.mesh.vertex_count : 1;

    fuzz_maps(&r, &dm.map);
    fuzz_maps(&r, &cm.map);

    /* ---- mesh validation and normals ----------------------------------- */
    rv = hf_mesh_validate(&m.mesh, &diag);
    FZ_REQUIRE(fz_known_result(rv) && diag.result == rv);
    normals = (float *)fz_sentinel_alloc(12u * (size_t)nv);
    rr = hf_mesh_compute_normals(&m.mesh, normals);
    FZ_REQUIRE(fz_known_result(rr));
    if (rr != HF_OK) {
        FZ_REQUIRE(fz_untouched(normals, 12u * (size_t)nv));
    } else {
        FZ_REQUIRE(fz_all_finite(normals, 3u * (size_t)nv));
        for (k = 0; k < nv; ++k) fz_check_unit(normals + 3 * k);
    }
    free(normals);

    /* ---- density of UV triangles --------------------------------------- */
    for (k = 0; k < 3; ++k) {
        float uv[3][2], d = -7.0f;
        int c;
        for (c = 0; c < 3; ++c) {
            uv[c][0] = fz_float(&r, 3.0f);
            uv[c][1] = fz_float(&r, 3.0f);
        }
        int est = fz_int(&r, -1, 3);
        rr = hf_uv_triangle_density(density, uv[0], uv[1], uv[2], est, &d);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK) {
            FZ_REQUIRE(d == -7.0f);
        } else if (!(fz_finite(d) && d >= 0.0f)) {
            fprintf(stderr, "density %g: estimator %d, uv (%g %g) (%g %g) "
                    "(%g %g), map %s\n", (double)d, est, (double)uv[0][0],
                    (double)uv[0][1], (double)uv[1][0], (double)uv[1][1],
                    (double)uv[2][0], (double)uv[2][1],
                    density ? "given" : "NULL");
            if (density)
                fprintf(stderr, "  map %dx%d ch %d fmt %d wrap %d stride %d\n",
                        density->width, density->height, density->channels,
                        density->format, density->wrap, density->row_stride);
            FZ_REQUIRE(fz_finite(d) && d >= 0.0f);
        }
    }

    /* ---- color3d -------------------------------------------------------- */
    {
        float xy[2] = {-7.0f, -7.0f}, c4[4] = {-7.0f, -7.0f, -7.0f, -7.0f};
        float u = fz_float(&r, 2.0f), v = fz_float(&r, 2.0f);
        float t = fz_float(&r, 2.0f);
        rr = hf_color3d_coord(&lm.map, u, v, t, xy);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK)
            FZ_REQUIRE(xy[0] == -7.0f && xy[1] == -7.0f);
        else
            FZ_REQUIRE(xy[0] >= 0.0f && xy[0] <= 1.0f && xy[1] >= 0.0f &&
                       xy[1] <= 1.0f);
        rr = hf_color3d_sample(&lm.map, &cm.map, u, v, t, c4);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK)
            FZ_REQUIRE(c4[0] == -7.0f && c4[3] == -7.0f);
        else
            FZ_REQUIRE(fz_all_finite(c4, 4));
    }

    /* ---- tessellation: counting pass, then filling ---------------------- */
    memset(&tp, 0, sizeof tp);
    tp.factor = fz_chance(&r, 240) ? fz_float_in(&r, 0.0f, 40.0f)
                                   : fz_float(&r, 1e6f);
    tp.estimator = fz_chance(&r, 250) ? fz_int(&r, 0, 2) : fz_int(&r, -1, 9);
    tp.split = fz_chance(&r, 250) ? fz_int(&r, 0, 1) : fz_int(&r, -1, 9);
    tp.seed = fz_u32(&r);
    tp.max_depth = fz_chance(&r, 250) ? fz_int(&r, 0, 8) : fz_int(&r, -1, 40);
    tp.max_triangles = fz_chance(&r, 250) ? fz_int(&r, 1, FZ_MAX_TESS_TRIANGLES)
                                          : fz_int(&r, -1, 0);
    tp.refuse_degenerate = fz_u8(&r) & 1;
    if (tp.max_triangles == 0) tp.max_triangles = -1; /* keep runs fast */
    memset(&cnt_out, 0, sizeof cnt_out);
    cnt_out.triangle_count = cnt_out.added_count = -7;
    cnt_out.vertex_count = cnt_out.depth = -7;
    rr = hf_tessellate(&m.mesh, density, &tp, &cnt_out);
    FZ_REQUIRE(fz_known_result(rr));
    if (rr != HF_OK) {
        FZ_REQUIRE(cnt_out.triangle_count == -7 && cnt_out.added_count == -7 &&
                   cnt_out.vertex_count == -7 && cnt_out.depth == -7);
    } else {
        const int T = cnt_out.triangle_count, A = cnt_out.added_count;
        const int V = cnt_out.vertex_count, nt = m.mesh.triangle_count;
        const int with_uvs = m.mesh.uvs != NULL;
        fz_tess t, t2;
        FZ_REQUIRE(rv == HF_OK); /* a mesh that fails validation never passes */
        FZ_REQUIRE(T >= nt && T <= tp.max_triangles && A >= 0 &&
                   V == m.mesh.vertex_count + A && cnt_out.depth >= 0);
        FZ_REQUIRE(cnt_out.depth <= (tp.max_depth ? tp.max_depth
                                                  : HF_TESS_DEFAULT_MAX_DEPTH));
        /* a capacity one short: nothing written */
        fz_tess_alloc(&t, T, A, V, with_uvs);
        k = fz_int(&r, 0, 2);
        if (k == 0) t.out.triangle_capacity = T - 1;
        else if (k == 1 && A > 0) t.out.added_capacity = A - 1;
        else t.out.vertex_capacity = V - 1;
        rr = hf_tessellate(&m.mesh, density, &tp, &t.out);
        FZ_REQUIRE(rr == HF_ERROR_BUFFER_TOO_SMALL);
        FZ_REQUIRE(fz_tess_untouched(&t, T, A, V));
        fz_tess_free(&t);
        /* the fill */
        fz_tess_alloc(&t, T, A, V, with_uvs);
        rr = hf_tessellate(&m.mesh, density, &tp, &t.out);
        FZ_REQUIRE(rr == HF_OK && t.out.triangle_count == T &&
                   t.out.added_count == A && t.out.vertex_count == V &&
                   t.out.depth == cnt_out.depth);
        for (k = 0; k < 3 * T; ++k) FZ_REQUIRE(t.indices[k] < (uint32_t)V);
        for (k = 0; k < T; ++k)
            FZ_REQUIRE(t.triangle_base[k] < (uint32_t)nt);
        for (k = 0; k < A; ++k) {
            const hf_tess_vertex *a = t.added + k;
            FZ_REQUIRE(a->triangle < (uint32_t)nt);
            FZ_REQUIRE(fz_all_finite(a->bary, 3));
            FZ_REQUIRE(a->bary[0] >= 0.0f && a->bary[1] >= 0.0f &&
                       a->bary[2] >= 0.0f);
            FZ_REQUIRE(fabs((double)a->bary[0] + a->bary[1] + a->bary[2] -
                            1.0) < 1e-4);
        }
        FZ_REQUIRE(fz_all_finite(t.positions, 3u * (size_t)V));
        if (with_uvs) FZ_REQUIRE(fz_all_finite(t.uvs, 2u * (size_t)V));
        /* the same call again: the same bytes */
        fz_tess_alloc(&t2, T, A, V, with_uvs);
        rr = hf_tessellate(&m.mesh, density, &tp, &t2.out);
        FZ_REQUIRE(rr == HF_OK);
        FZ_REQUIRE(memcmp(t.indices, t2.indices, 12u * (size_t)T) == 0 &&
                   memcmp(t.added, t2.added, 16u * (size_t)A) == 0 &&
                   memcmp(t.positions, t2.positions, 12u * (size_t)V) == 0);
        fz_tess_free(&t2);

        fuzz_downstream(&r, &m.mesh, &t, density, &lm.map, &cm.map);
        fz_tess_free(&t);
    }

    fz_free_mesh(&m);
    free(dm.data);
    free(lm.data);
    free(cm.data);
    return 0;
}
