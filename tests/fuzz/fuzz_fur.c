/* fuzz_fur.c - the fur object on fuzz-built input: hf_fur_create from a
   fuzz mesh, maps and description (zero fields, bad fields, a failing or
   counting allocator), then a few frames of every per-frame call with
   fuzz ranges, skinned roots and colliders (some holding the roots);
   growth directions per vertex and from a map, authored guide curves and
   styling (curl, wave, frizz, colour variation); a groom made from the
   same curves, moved rigidly and stepped.

   Contracts checked (abort() on violation): every result is HF_OK or a
   code of the table; a failed create leaves *out_fur as it was and frees
   every block it took; on success the counts are consistent, the whole
   first frame's outputs are finite, the guides keep their segment lengths
   (stretch at most 1e-3, follow-the-leader with colliders), and
   hf_fur_info's roots_inside is within [0, guide_count]; destroy frees
   everything.

   libFuzzer: clang -g -O1 -fsanitize=fuzzer,address,undefined fuzz_fur.c
              fuzz_impl.c (the header's implementation)
   replay:    gcc -O1 -g fuzz_main.c fuzz_fur.c fuzz_impl.c -lm (see the
              Makefile) */
#include "../../hairfur.h"
#include "fuzz_common.h"

#include <math.h>

#define FZ_FUR_MAX_STRANDS 1500
#define FZ_FUR_MAX_TRIANGLES 4000

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader r;
    fz_mesh m;
    fz_map density, length, color, comb_map;
    fz_counter counter;
    hf_allocator alloc;
    hf_fur_desc desc;
    hf_rope_params rope;
    hf_fur *fur = (hf_fur *)(uintptr_t)0x1234, *const untouched = fur;
    hf_diag diag;
    hf_result rv;
    float *skinned = NULL, *vbuf = NULL, *pbuf = NULL, *pbuf2 = NULL, *comb = NULL;
    float *curves = NULL;
    int curve_points[6] = {0, 0, 0, 0, 0, 0}, curve_total = 0, curve_n = 0;
    int has_density, has_length, has_color, has_comb_map, frame, k;

    fz_init(&r, data, size);
    fz_make_mesh(&r, &m, 24, 24, 1.0f);
    has_density = fz_chance(&r, 128);
    has_length = fz_chance(&r, 96);
    has_color = fz_chance(&r, 96);
    if (has_density) fz_make_map(&r, &density, 8, 8, 1);
    if (has_length) fz_make_map(&r, &length, 8, 8, 1);
    if (has_color) fz_make_map(&r, &color, 8, 8, 1);
    /* growth directions: per vertex (any floats: zero, huge, non-finite)
       and a map (sometimes with too few channels) */
    if (fz_chance(&r, 64) && m.mesh.vertex_count > 0) { /* it may be bad */
        comb = (float *)malloc(sizeof(float) * 3u * (size_t)m.mesh.vertex_count);
        if (comb)
            for (k = 0; k < 3 * m.mesh.vertex_count; ++k)
                comb[k] = fz_float(&r, 2.0f);
    }
    has_comb_map = fz_chance(&r, 48);
    if (has_comb_map) fz_make_map(&r, &comb_map, 4, 4, fz_chance(&r, 200) ? 3 : 1);

    /* the description: zero fields are defaults; some fields fuzzed,
       mostly in range, sometimes bad */
    memset(&desc, 0, sizeof desc);
    desc.mesh = m.mesh;
    desc.density_map = has_density ? &density.map : NULL;
    desc.length_map = has_length ? &length.map : NULL;
    desc.color_map = has_color ? &color.map : NULL;
    desc.comb = comb;
    desc.comb_map = has_comb_map ? &comb_map.map : NULL;
    /* authored guide curves: 1..6 curves of 0..7 points, any floats */
    if (fz_chance(&r, 64)) {
        int c, n = curve_n = fz_int(&r, 1, 6);
        for (c = 0; c < n; ++c) {
            curve_points[c] = fz_chance(&r, 240) ? fz_int(&r, 2, 7) : fz_int(&r, -1, 1);
            if (curve_points[c] > 0) curve_total += curve_points[c];
        }
        curves = (float *)malloc(sizeof(float) * 3u * (size_t)(curve_total + 1));
        if (curves) {
            for (k = 0; k < 3 * curve_total; ++k) curves[k] = fz_float(&r, 1.5f);
            desc.guide_curves = fz_chance(&r, 250) ? curves : NULL;
            desc.guide_curve_points = curve_points;
            desc.guide_curve_count = fz_chance(&r, 250) ? n : -n;
        }
    }
    /* styling, mostly in range */
    if (fz_chance(&r, 96)) {
        desc.curl_radius = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 0.05f) : fz_float(&r, 1.0f);
        desc.curl_turns = fz_float_in(&r, 0.0f, 8.0f);
        desc.wave_amplitude = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 0.05f) : fz_float(&r, 1.0f);
        desc.wave_count = fz_float_in(&r, 0.0f, 8.0f);
        desc.frizz = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 1.0f) : fz_float(&r, 1.0f);
        desc.color_variation = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 1.0f) : fz_float(&r, 2.0f);
        desc.clump_size = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 0.5f) : fz_float(&r, 2.0f);
        desc.width_variation = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 1.0f) : fz_float(&r, 2.0f);
        if (has_length && fz_chance(&r, 128)) desc.clump_map = &length.map;
        if (has_length && fz_chance(&r, 128)) desc.clump_size_map = &length.map;
        if (has_density && fz_chance(&r, 128)) desc.color_variation_map = &density.map;
        if (has_length && fz_chance(&r, 128)) desc.width_variation_map = &length.map;
    }
    /* kernels: every level and streaming gives the same bytes; bad
       values are refused */
    desc.simd = fz_chance(&r, 230) ? fz_int(&r, 0, 4) : fz_int(&r, -3, 9);
    desc.nontemporal = fz_chance(&r, 230) ? fz_int(&r, 0, 2) : fz_int(&r, -2, 4);
    desc.points_per_strand = fz_chance(&r, 200) ? fz_int(&r, 0, 24)
                                                : fz_int(&r, -2, 300);
    desc.max_length = fz_chance(&r, 220) ? fz_float_in(&r, 0.0f, 0.5f)
                                         : fz_float(&r, 10.0f);
    desc.tess_factor = fz_chance(&r, 128) ? 0.0f
                       : fz_chance(&r, 220) ? fz_float_in(&r, 0.0f, 200.0f)
                                            : fz_float(&r, 1e4f);
    desc.tess_max_triangles = FZ_FUR_MAX_TRIANGLES;
    desc.tess_estimator = fz_int(&r, 0, 2);
    desc.tess_split = fz_int(&r, 0, 1);
    if (fz_chance(&r, 128))
        desc.strands_per_area = fz_chance(&r, 220) ? fz_float_in(&r, 0.0f, 500.0f)
                                                   : fz_float(&r, 1e6f);
    desc.total_strands = fz_chance(&r, 230) ? fz_int(&r, 0, FZ_FUR_MAX_STRANDS)
                                            : fz_int(&r, -3, 3);
    desc.sampler = fz_int(&r, 0, 2);
    desc.seed = fz_u32(&r);
    desc.clump = fz_chance(&r, 220) ? fz_float_in(&r, 0.0f, 1.0f)
                                    : fz_float(&r, 2.0f);
    desc.lod_simulate_threshold = fz_float_in(&r, 0.0f, 1.0f);
    /* hair-hair interaction: mostly none, some grids, some bad sizes */
    desc.grid_resolution = fz_chance(&r, 160) ? 0
                           : fz_chance(&r, 200) ? fz_int(&r, 4, 12)
                                                : fz_int(&r, -5, 200);
    /* strands that keep their lengths: mostly off, some bad values */
    desc.keep_length = fz_chance(&r, 160) ? 0 : fz_int(&r, -1, 2);
    memset(&rope, 0, sizeof rope);
    if (fz_chance(&r, 128)) {
        rope.gravity[1] = fz_float(&r, 30.0f);
        rope.damping = fz_float_in(&r, 0.0f, 1.0f);
        rope.collision_margin = fz_float_in(&r, 0.0f, 0.01f);
        rope.local_stiffness_root = fz_float_in(&r, 0.0f, 1.0f);
        rope.volume = fz_float(&r, 3.0f);
        rope.friction = fz_float(&r, 1.0f);
        rope.explicit_zero = fz_int(&r, 0, 255) & ~HF_ROPE_ZERO_ITERATIONS;
        desc.rope_params = &rope;
    }
    alloc = fz_counting(&counter, fz_chance(&r, 16) ? fz_int(&r, 0, 40) : -1,
                        (size_t)64 << 20);
    desc.allocator = &alloc;

    rv = hf_fur_create(&desc, &fur, &diag);
    FZ_REQUIRE(fz_known_result(rv));
    FZ_REQUIRE(diag.result == rv);
    if (rv != HF_OK) {
        FZ_REQUIRE(fur == untouched);
        FZ_REQUIRE(counter.live == 0);
        goto done;
    }
    {
        hf_fur_info info;
        hf_collider col[3];
        size_t nvb;
        int nc;
        FZ_REQUIRE(hf_fur_get_info(fur, &info) == HF_OK);
        FZ_REQUIRE(info.guide_count == info.pure_guide_count + info.lod_guide_count);
        FZ_REQUIRE(info.strand_count >= 0 && info.drawn_strand_count == info.strand_count);
        FZ_REQUIRE(info.points_per_strand >= 2);
        if (info.strand_count > 200000) { /* strands_per_area can ask a lot */
            hf_fur_destroy(fur);
            goto done;
        }
        nvb = (size_t)(info.strand_count ? info.strand_count : 1) *
              (size_t)info.points_per_strand;
        vbuf = (float *)malloc(sizeof(float) * 6u * nvb);
        pbuf = (float *)malloc(sizeof(float) * 4u * nvb);
        pbuf2 = (float *)malloc(sizeof(float) * 4u * nvb);
        skinned = (float *)malloc(sizeof(float) * 8u * (size_t)m.mesh.vertex_count);
        if (!vbuf || !pbuf || !pbuf2 || !skinned) abort();
        nc = fz_int(&r, 0, 3);
        for (k = 0; k < nc; ++k) {
            int c;
            memset(&col[k], 0, sizeof col[k]);
            col[k].type = fz_int(&r, 0, 1);
            for (c = 0; c < 3; ++c) {
                /* around a vertex of the mesh: sometimes holding roots */
                col[k].a[c] = m.verts[8 * fz_int(&r, 0, m.mesh.vertex_count - 1) + c] +
                              fz_float(&r, 0.3f);
                col[k].b[c] = col[k].a[c] + fz_float(&r, 0.5f);
            }
            col[k].radius = fz_float_in(&r, 0.0f, 0.6f);
        }
        for (frame = 0; frame < 3; ++frame) {
            hf_mesh sk = m.mesh;
            hf_ribbon_params view;
            hf_ribbon_output out;
            hf_result rs;
            float lod = fz_chance(&r, 200) ? 1.0f : fz_float_in(&r, 0.0f, 1.0f);
            float dt = fz_chance(&r, 220) ? 1.0f / 60.0f : fz_float(&r, 0.2f);
            float shift[3];
            int first, count, i;
            for (k = 0; k < 3; ++k) shift[k] = fz_float(&r, 0.2f);
            memcpy(skinned, m.verts, sizeof(float) * 8u * (size_t)m.mesh.vertex_count);
            for (i = 0; i < m.mesh.vertex_count; ++i)
                for (k = 0; k < 3; ++k) skinned[8 * i + k] += shift[k];
            sk.positions = skinned;
            sk.normals = m.mesh.normals ? skinned + 3 : NULL;
            sk.uvs = m.mesh.uvs ? skinned + 6 : NULL;
            FZ_REQUIRE(hf_fur_set_lod(fur, lod) == HF_OK);
            FZ_REQUIRE(hf_fur_get_info(fur, &info) == HF_OK);
            /* every stage over the whole range, and once a fuzz range */
            rs = hf_fur_set_roots(fur, &sk, 0, info.guide_count);
            FZ_REQUIRE(fz_known_result(rs));
            FZ_REQUIRE(hf_fur_build_grid(fur, 0, info.grid_resolution) == HF_OK);
            if (frame == 1 && fz_chance(&r, 64)) { /* drape, briefly */
                float sec = fz_chance(&r, 200) ? fz_float_in(&r, 0.0f, 0.1f)
                                               : fz_float(&r, 1000.0f);
                if (sec > 0.1f && sec <= 600.0f) sec = 0.1f; /* quick */
                rs = hf_fur_settle_rest(fur, sec, nc ? col : NULL, nc);
                FZ_REQUIRE(fz_known_result(rs));
                FZ_REQUIRE(fz_all_finite(info.guide_points,
                                         3u * (size_t)info.guide_count *
                                             (size_t)info.points_per_strand));
            }
            rs = hf_fur_simulate(fur, 0, info.guide_count, dt, nc ? col : NULL, nc);
            FZ_REQUIRE(fz_known_result(rs));
            if (rs == HF_OK && dt > 0.0f && info.lod_guides_simulated &&
                (!desc.rope_params || desc.rope_params->explicit_zero == 0)) {
                /* inextensible guides, to float resolution: checked
                   where every segment is long against its coordinates */
                float st = -1.0f;
                double big = 0.0, shortest = 1e30;
                size_t g, n = (size_t)info.guide_count *
                              (size_t)info.points_per_strand;
                FZ_REQUIRE(hf_fur_max_stretch(fur, &st) == HF_OK);
                FZ_REQUIRE(fz_finite(st));
                for (g = 0; g < n; ++g) {
                    const float *q = info.guide_points + 3 * g;
                    double a = fabs((double)q[0]) + fabs((double)q[1]) +
                               fabs((double)q[2]);
                    if (a > big) big = a;
                    if ((g + 1) % (size_t)info.points_per_strand) {
                        double dx = (double)q[3] - q[0], dy = (double)q[4] - q[1],
                               dz = (double)q[5] - q[2];
                        double l = sqrt(dx * dx + dy * dy + dz * dz);
                        if (l < shortest) shortest = l;
                    }
                }
                if (shortest > 1e-3 * (1.0 + big)) FZ_REQUIRE(st <= 1e-3f);
            }
            FZ_REQUIRE(hf_fur_interpolate_guides(fur, 0, info.lod_guide_count) == HF_OK);
            FZ_REQUIRE(hf_fur_interpolate(fur, 0, info.drawn_strand_count) == HF_OK);
            memset(&view, 0, sizeof view);
            view.eye[2] = fz_float_in(&r, -5.0f, 5.0f);
            if (!fz_finite(view.eye[2])) view.eye[2] = 5.0f;
            memset(&out, 0, sizeof out);
            out.position.data = vbuf;
            FZ_REQUIRE(hf_fur_ribbons(fur, 0, info.drawn_strand_count, &view, &out) == HF_OK);
            FZ_REQUIRE(fz_all_finite(vbuf, 6u * (size_t)info.drawn_strand_count *
                                               (size_t)info.points_per_strand));
            fz_range(&r, info.drawn_strand_count, &first, &count);
            view.out_first = fz_chance(&r, 128) ? first : 0;
            rs = hf_fur_points(fur, first, count, &view, pbuf);
            FZ_REQUIRE(fz_known_result(rs));
            if (rs == HF_OK) {
                const size_t at = (size_t)(first - view.out_first) *
                                  (size_t)info.points_per_strand * 4u,
                             n4 = (size_t)count * (size_t)info.points_per_strand * 4u;
                FZ_REQUIRE(fz_all_finite(pbuf + at, n4));
                /* the one-pass path: the same bytes, at any kernels,
                   for the strands interpolated this frame (the drawn
                   ones; hf_fur_points reads the others as they were
                   last interpolated) */
                view.nontemporal = fz_int(&r, 0, 2);
                hf_fur_set_kernels(fur, fz_int(&r, 0, 4), fz_int(&r, 0, 2));
                FZ_REQUIRE(hf_fur_interpolate_points(fur, first, count, &view,
                                                     pbuf2) == HF_OK);
                if (first + count <= info.drawn_strand_count)
                    FZ_REQUIRE(memcmp(pbuf + at, pbuf2 + at,
                                      sizeof(float) * n4) == 0);
            }
            FZ_REQUIRE(hf_fur_get_info(fur, &info) == HF_OK);
            FZ_REQUIRE(info.roots_inside >= 0 && info.roots_inside <= info.guide_count);
        }
        hf_fur_destroy(fur);
    }
    /* a groom from the same curves (when there are any): created or
       refused cleanly, then a rigid move and a frame */
    if (curves && curve_total > 0) {
        hf_groom_desc gd;
        hf_fur *g = untouched;
        const int n = curve_n;
        memset(&gd, 0, sizeof gd);
        gd.points = curves;
        gd.strand_points = curve_points;
        gd.strand_count = fz_chance(&r, 240) ? n : fz_int(&r, -2, n);
        gd.points_per_strand = fz_chance(&r, 200) ? 0 : fz_int(&r, 0, 40);
        gd.keep_length = fz_chance(&r, 200) ? 0 : fz_int(&r, -1, 2);
        gd.guide_fraction = fz_chance(&r, 200) ? fz_float_in(&r, 0.0f, 1.0f)
                                               : fz_float(&r, 2.0f);
        gd.seed = fz_u32(&r);
        gd.allocator = &alloc;
        gd.scalp = fz_chance(&r, 128) ? &m.mesh : NULL; /* may be a bad mesh */
        rv = hf_fur_create_groom(&gd, &g, &diag);
        FZ_REQUIRE(fz_known_result(rv));
        if (rv != HF_OK) {
            FZ_REQUIRE(g == untouched);
        } else {
            float mm[12];
            hf_fur_info gi;
            for (k = 0; k < 12; ++k) mm[k] = fz_float(&r, 2.0f);
            FZ_REQUIRE(hf_fur_get_info(g, &gi) == HF_OK);
            FZ_REQUIRE(gi.guide_count >= 1 && gi.guide_count <= gi.strand_count);
            FZ_REQUIRE(fz_all_finite(gi.strand_points, 3u * (size_t)gi.strand_count *
                                                           (size_t)gi.points_per_strand));
            rv = hf_fur_set_transform(g, mm, 0, gi.guide_count);
            FZ_REQUIRE(fz_known_result(rv));
            if (gd.scalp) { /* the scalp moved a little: roots follow it */
                hf_mesh sk = m.mesh;
                float *moved = (float *)malloc(sizeof(float) * 8u *
                                               (size_t)m.mesh.vertex_count);
                if (moved) {
                    for (k = 0; k < 8 * m.mesh.vertex_count; ++k)
                        moved[k] = m.verts[k] + 0.01f * (float)(k % 5);
                    sk.positions = moved;
                    rv = hf_fur_set_roots(g, &sk, 0, gi.guide_count);
                    FZ_REQUIRE(fz_known_result(rv));
                    free(moved);
                }
            }
            if (rv == HF_OK &&
                hf_fur_simulate(g, 0, gi.guide_count, 1.0f / 60.0f, NULL, 0) == HF_OK)
                FZ_REQUIRE(hf_fur_interpolate(g, 0, gi.strand_count) == HF_OK);
            hf_fur_destroy(g);
        }
    }
done:
    FZ_REQUIRE(counter.live == 0);
    free(skinned);
    free(vbuf);
    free(pbuf);
    free(pbuf2);
    if (has_density) free(density.data);
    if (has_length) free(length.data);
    if (has_color) free(color.data);
    if (has_comb_map) free(comb_map.data);
    free(comb);
    free(curves);
    fz_free_mesh(&m);
    return 0;
}
