/* fuzz_ribbons.c - hf_ribbons, hf_ribbon_points, hf_ribbon_index_count /
   hf_ribbon_indices, hf_interpolate and the LOD helpers with fuzz-built
   strands (coincident points, straight lines through the eye, huge and
   NaN coordinates), eyes (on a point, far away), view directions, widths,
   tapers, alphas, streams and ranges.

   Contracts checked (abort() on violation): every result is HF_OK or a
   table code; on failure every output stream still holds its sentinel;
   on success the range's vertices are written and nothing else, tangents
   are unit, every written value is finite (the library promises: never NaN in the
   output; see FZ_SKIP_KNOWN), and a split of the range gives the same
   bytes; a fuzz-built vertex layout gets the same bytes at the CPU's SIMD
   level as at the scalar one; indices are in range.

   libFuzzer: clang -g -O1 -fsanitize=fuzzer,address,undefined fuzz_ribbons.c
              fuzz_impl.c (the header's implementation)
   replay:    gcc -O1 -g fuzz_main.c fuzz_ribbons.c fuzz_impl.c -lm (see the
              Makefile) */
#include "../../hairfur.h"
#include "fuzz_common.h"

#include <math.h>

#define FZ_VERT_FLOATS 15 /* position 3, tangent 3, texcoord 3, color 4, c3d 2 */

static hf_ribbon_output fz_interleaved(float *v, int mask)
{
    hf_ribbon_output o;
    memset(&o, 0, sizeof o);
    if (mask & 1) { o.position.data = v; o.position.stride = 60; }
    if (mask & 2) { o.tangent.data = v + 3; o.tangent.stride = 60; }
    if (mask & 4) { o.texcoord.data = v + 6; o.texcoord.stride = 60; }
    if (mask & 8) { o.color.data = v + 9; o.color.stride = 60; }
    if (mask & 16) { o.color3d.data = v + 13; o.color3d.stride = 60; }
    return o;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader r;
    int S, P, i, k, first, count, mask;
    float *pts, *uv, *rgba, *c3x, *wid, *v, *v2, *p4;
    hf_ribbon_strands st;
    hf_ribbon_params rp;
    hf_ribbon_output o;
    hf_result rr;
    size_t nv, vbytes;

    fz_init(&r, data, size);
    S = fz_int(&r, 1, 8);
    P = fz_int(&r, 2, 12);
    pts = (float *)malloc(sizeof(float) * 3u * (size_t)S * (size_t)P);
    uv = (float *)malloc(sizeof(float) * 2u * (size_t)S);
    rgba = (float *)malloc(sizeof(float) * 4u * (size_t)S);
    c3x = (float *)malloc(sizeof(float) * (size_t)S);
    wid = (float *)malloc(sizeof(float) * (size_t)S);
    if (!pts || !uv || !rgba || !c3x || !wid) abort();
    for (i = 0; i < S * P; ++i) {
        int mode = fz_u8(&r) % 8;
        for (k = 0; k < 3; ++k) {
            if (mode == 0 && i % P > 0) /* coincident with the previous */
                pts[3 * i + k] = pts[3 * (i - 1) + k];
            else if (mode == 1 && i % P > 0) /* a straight line */
                pts[3 * i + k] = pts[3 * (i - 1) + k] + (k == 2 ? 0.1f : 0.0f);
            else
                pts[3 * i + k] = fz_float(&r, 1.0f);
        }
    }
    for (i = 0; i < 2 * S; ++i) uv[i] = fz_float_in(&r, 0.0f, 1.0f);
    for (i = 0; i < 4 * S; ++i) rgba[i] = fz_float_in(&r, 0.0f, 1.0f);
    for (i = 0; i < S; ++i) c3x[i] = fz_float_in(&r, 0.0f, 1.0f);
    for (i = 0; i < S; ++i) wid[i] = fz_float(&r, 2.0f); /* any: NaN, < 0 */
#ifdef FZ_SKIP_KNOWN
    /* known bug (regressions/ribbons-nan-points-*): points are not
       checked, so NaN / inf points give NaN vertices */
    for (i = 0; i < 3 * S * P; ++i)
        if (!fz_finite(pts[i])) pts[i] = 0.0f;
    /* the same for the per-strand root UVs, colours and 3D-colour x */
    for (i = 0; i < 2 * S; ++i) if (!fz_finite(uv[i])) uv[i] = 0.0f;
    for (i = 0; i < 4 * S; ++i)
        if (!(fabsf(rgba[i]) < 1e6f)) rgba[i] = 0.0f; /* alpha * colour */
    for (i = 0; i < S; ++i) if (!fz_finite(c3x[i])) c3x[i] = 0.0f;
#endif

    memset(&st, 0, sizeof st);
    st.points = pts;
    st.root_uv = (fz_u8(&r) & 1) ? uv : NULL;
    st.color = (fz_u8(&r) & 1) ? rgba : NULL;
    st.color3d_x = (fz_u8(&r) & 1) ? c3x : NULL;
    st.width = (fz_u8(&r) & 1) ? wid : NULL;

    memset(&rp, 0, sizeof rp);
    rp.points_per_strand = fz_chance(&r, 250) ? P : fz_int(&r, -1, P);
    k = fz_u8(&r) % 4;
    for (i = 0; i < 3; ++i) {
        /* the eye: anywhere, on a point of a strand, or far away */
        if (k == 0) rp.eye[i] = pts[3 * (fz_int(&r, 0, S * P - 1)) + i];
        else if (k == 1) rp.eye[i] = fz_float(&r, 1e20f);
        else rp.eye[i] = fz_float(&r, 3.0f);
        rp.view_dir[i] = fz_float(&r, 1.0f);
    }
    if (k == 0) /* exactly on one point */
        for (i = 0; i < 3; ++i) rp.eye[i] = pts[i];
    rp.orthographic = fz_u8(&r) & 1;
    rp.root_width = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 0.02f)
                                       : fz_float(&r, 1e30f);
    rp.tip_width = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 0.02f)
                                      : fz_float(&r, 1e30f);
    rp.taper_power = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 4.0f)
                                        : fz_float(&r, 1e30f);
    rp.width_scale = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 4.0f)
                                        : fz_float(&r, 1e30f);
    rp.alpha_root = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 1.0f)
                                       : fz_float(&r, 1e30f);
    rp.alpha_tip = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 1.0f)
                                      : fz_float(&r, 1e30f);
#ifdef FZ_SKIP_KNOWN
    /* known bug (regressions/ribbons-width-overflow-*): finite widths,
       scales and alphas whose products or differences overflow give
       inf / NaN vertices */
    if (!(fabsf(rp.root_width) < 1e6f)) rp.root_width = 1e6f;
    if (!(fabsf(rp.tip_width) < 1e6f)) rp.tip_width = 1e6f;
    if (!(fabsf(rp.width_scale) < 1e6f)) rp.width_scale = 1e6f;
    if (!(fabsf(rp.alpha_root) < 1e6f)) rp.alpha_root = 1e6f;
    if (!(fabsf(rp.alpha_tip) < 1e6f)) rp.alpha_tip = 1e6f;
    for (i = 0; i < 3 * S * P; ++i)
        if (!(fabsf(pts[i]) < 1e30f)) pts[i] = 1e30f;
#endif

    /* ---- hf_ribbons, whole range and split ---------------------------- */
    nv = 2u * (size_t)S * (size_t)P;
    vbytes = nv * FZ_VERT_FLOATS * sizeof(float);
    v = (float *)fz_sentinel_alloc(vbytes);
    v2 = (float *)fz_sentinel_alloc(vbytes);
    mask = fz_chance(&r, 240) ? fz_u8(&r) & 31 : 31;
    o = fz_interleaved(v, mask);
    if (fz_chance(&r, 4)) o.color.stride = -4; /* refused */
    fz_range_untotalled(&r, S, &first, &count);
    rr = hf_ribbons(&st, first, count, &rp, &o);
    FZ_REQUIRE(fz_known_result(rr));
    if (rr != HF_OK) {
        FZ_REQUIRE(fz_untouched(v, vbytes));
    } else {
        /* the layout follows params' P, which may be below the buffer's */
        const size_t Pr = (size_t)rp.points_per_strand;
        size_t a = 2u * (size_t)first * Pr, n = 2u * (size_t)count * Pr;
        size_t j;
        FZ_REQUIRE(fz_untouched(v, a * FZ_VERT_FLOATS * 4u));
        FZ_REQUIRE(fz_untouched(v + (a + n) * FZ_VERT_FLOATS,
                                (nv - a - n) * FZ_VERT_FLOATS * 4u));
        for (j = a; j < a + n; ++j) {
            const float *x = v + j * FZ_VERT_FLOATS;
            if (mask & 1) FZ_REQUIRE(fz_all_finite(x, 3));
            if (mask & 2) {
                double l = sqrt((double)x[3] * x[3] + (double)x[4] * x[4] +
                                (double)x[5] * x[5]);
                FZ_REQUIRE(fz_all_finite(x + 3, 3) && fabs(l - 1.0) < 1e-3);
            }
            if (mask & 4) FZ_REQUIRE(fz_all_finite(x + 6, 3));
            if (mask & 8) FZ_REQUIRE(fz_all_finite(x + 9, 4));
            if (mask & 16) FZ_REQUIRE(fz_all_finite(x + 13, 2));
        }
        /* the same range in pieces: the same bytes */
        {
            hf_ribbon_output o2 = fz_interleaved(v2, mask);
            int done = first, end = first + count;
            while (done < end) {
                int c = fz_int(&r, 1, end - done);
                rr = hf_ribbons(&st, done, c, &rp, &o2);
                FZ_REQUIRE(rr == HF_OK);
                done += c;
            }
            FZ_REQUIRE(memcmp(v, v2, vbytes) == 0);
        }
    }

    /* ---- hf_ribbons with fuzz-chosen formats, origin and scale ---------
       The streams keep their float offsets (each format is no larger), so
       the vertex is 60 bytes whatever the formats. */
    {
        static const int comps[5] = {3, 3, 3, 4, 2};
        hf_ribbon_output oc = fz_interleaved(v2, mask);
        hf_stream *sp[5];
        unsigned char *cb = (unsigned char *)v2;
        sp[0] = &oc.position; sp[1] = &oc.tangent; sp[2] = &oc.texcoord;
        sp[3] = &oc.color; sp[4] = &oc.color3d;
        for (k = 0; k < 5; ++k)
            sp[k]->format = fz_chance(&r, 240) ? fz_int(&r, 0, 5) : fz_int(&r, -2, 8);
        for (k = 0; k < 3; ++k)
            oc.position_origin[k] = fz_chance(&r, 230) ? fz_float(&r, 2.0f) : fz_float(&r, 1e30f);
        oc.position_scale = fz_chance(&r, 230) ? fz_float_in(&r, 0.0f, 4.0f) : fz_float(&r, 1e30f);
        if (fz_chance(&r, 8)) oc.tangent.stride = fz_int(&r, 0, 12); /* may be too small */
        memset(v2, FZ_SENTINEL, vbytes);
        fz_range_untotalled(&r, S, &first, &count);
        rr = hf_ribbons(&st, first, count, &rp, &oc);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK) {
            FZ_REQUIRE(fz_untouched(v2, vbytes));
        } else if (oc.tangent.stride == 60 || !(mask & 2)) {
            const size_t Pr = (size_t)rp.points_per_strand;
            size_t a = 2u * (size_t)first * Pr, n = 2u * (size_t)count * Pr, j;
            FZ_REQUIRE(fz_untouched(v2, a * 60u));
            FZ_REQUIRE(fz_untouched(cb + (a + n) * 60u, (nv - a - n) * 60u));
            /* no half float is an infinity or NaN */
            for (j = a; j < a + n; ++j)
                for (k = 0; k < 5; ++k) {
                    static const int off[5] = {0, 12, 24, 36, 52};
                    int c;
                    if (!(mask & (1 << k)) || sp[k]->format != HF_FORMAT_F16) continue;
                    for (c = 0; c < comps[k]; ++c) {
                        uint16_t h;
                        memcpy(&h, cb + j * 60u + (size_t)off[k] + 2u * (size_t)c, 2);
                        FZ_REQUIRE((h & 0x7c00u) != 0x7c00u);
                    }
                }
            /* the same range in pieces: the same bytes */
            {
                unsigned char *c2 = (unsigned char *)fz_sentinel_alloc(vbytes);
                hf_ribbon_output o3 = oc;
                hf_stream *sp3[5];
                int done = first, end = first + count;
                sp3[0] = &o3.position; sp3[1] = &o3.tangent; sp3[2] = &o3.texcoord;
                sp3[3] = &o3.color; sp3[4] = &o3.color3d;
                for (k = 0; k < 5; ++k)
                    if (sp[k]->data)
                        sp3[k]->data = c2 + ((unsigned char *)sp[k]->data - cb);
                while (done < end) {
                    int c = fz_int(&r, 1, end - done);
                    FZ_REQUIRE(hf_ribbons(&st, done, c, &rp, &o3) == HF_OK);
                    done += c;
                }
                FZ_REQUIRE(memcmp(cb + a * 60u, c2 + a * 60u, n * 60u) == 0);
                free(c2);
            }
        }
    }

    /* ---- hf_ribbons into a fuzz-built vertex ---------------------------
       Streams in a fuzz-chosen order and formats, abutting or with gaps,
       one stride with or without padding, streaming stores or not: the
       CPU's level and the scalar one give the same result and the same
       bytes, gaps and padding included (both buffers start as
       sentinels). */
    {
        static const int comps[5] = {3, 3, 3, 4, 2};
        hf_ribbon_output ol;
        hf_ribbon_params lp = rp;
        hf_stream *sl[5];
        unsigned char *la, *lb;
        size_t stride, lbytes;
        int order[5], offs[5], end = 0, lmask = fz_u8(&r) & 31, ra, rb2;
        memset(&ol, 0, sizeof ol);
        sl[0] = &ol.position; sl[1] = &ol.tangent; sl[2] = &ol.texcoord;
        sl[3] = &ol.color; sl[4] = &ol.color3d;
        for (k = 0; k < 5; ++k) order[k] = k;
        for (k = 4; k > 0; --k) {
            int j = fz_int(&r, 0, k), t = order[k];
            order[k] = order[j];
            order[j] = t;
        }
        for (k = 0; k < 5; ++k) {
            const int q = order[k];
            offs[q] = -1;
            if (!(lmask & (1 << q))) continue;
            sl[q]->format = fz_int(&r, 0, 5);
            if (!fz_chance(&r, 200)) end += fz_int(&r, 1, 3); /* a gap */
            offs[q] = end;
            end += comps[q] * hf_format_bytes(sl[q]->format);
        }
        stride = (size_t)end + (fz_chance(&r, 128) ? 0u : (size_t)fz_int(&r, 1, 4));
        lbytes = nv * stride + 1u;
        la = (unsigned char *)fz_sentinel_alloc(lbytes);
        lb = (unsigned char *)fz_sentinel_alloc(lbytes);
        for (k = 0; k < 5; ++k)
            if (offs[k] >= 0) {
                sl[k]->data = la + offs[k];
                sl[k]->stride = (int)stride;
            }
        ol.position_scale = fz_chance(&r, 128) ? 0.0f : fz_float_in(&r, 0.05f, 4.0f);
        lp.nontemporal = fz_int(&r, 0, 2);
        lp.simd = HF_SIMD_AUTO;
        fz_range_untotalled(&r, S, &first, &count);
        ra = hf_ribbons(&st, first, count, &lp, &ol);
        FZ_REQUIRE(fz_known_result(ra));
        for (k = 0; k < 5; ++k)
            if (offs[k] >= 0) sl[k]->data = lb + offs[k];
        lp.simd = HF_SIMD_SCALAR;
        rb2 = hf_ribbons(&st, first, count, &lp, &ol);
        FZ_REQUIRE(ra == rb2);
        FZ_REQUIRE(memcmp(la, lb, lbytes) == 0);
        if (ra != HF_OK) FZ_REQUIRE(fz_untouched(la, lbytes));
        free(la);
        free(lb);
    }

    /* ---- hf_ribbon_points ---------------------------------------------- */
    p4 = (float *)fz_sentinel_alloc(sizeof(float) * 4u * (size_t)S * (size_t)P);
    fz_range_untotalled(&r, S, &first, &count);
    if (fz_chance(&r, 96)) { /* compact points, their box, bad formats */
        int c;
        rp.point_format = fz_chance(&r, 200) ? HF_POINT_COMPACT
                                             : fz_int(&r, -2, 3);
        for (c = 0; c < 3; ++c) rp.point_origin[c] = fz_float(&r, 10.0f);
        rp.point_scale = fz_chance(&r, 200) ? fz_float_in(&r, 0.0f, 2.0f)
                                            : fz_float(&r, 1e20f);
    }
    rr = hf_ribbon_points(&st, first, count, &rp, p4);
    FZ_REQUIRE(fz_known_result(rr));
    if (rr != HF_OK)
        FZ_REQUIRE(fz_untouched(p4, sizeof(float) * 4u * (size_t)S * (size_t)P));
    else if (rp.point_format == HF_POINT_F32)
        FZ_REQUIRE(fz_all_finite(p4 + 4 * (size_t)first *
                                          (size_t)rp.points_per_strand,
                                 4u * (size_t)count *
                                     (size_t)rp.points_per_strand));
    free(p4);

    /* ---- indices --------------------------------------------------------- */
    {
        int topo = fz_chance(&r, 240) ? fz_int(&r, 0, 1) : fz_int(&r, -1, 4);
        int sc = fz_chance(&r, 240) ? S : fz_int(&r, -1, 0x7fffffff);
        int pp = fz_chance(&r, 240) ? P : fz_int(&r, -1, 0x7fffffff);
#ifdef FZ_SKIP_KNOWN
        /* known bug (regressions/ribbons-index-count-signed-overflow.bin):
           6 (P - 1) * strand_count overflows long long */
        if (sc > (1 << 20)) sc = 1 << 20;
#endif
        long long n = hf_ribbon_index_count(sc, pp, topo);
        FZ_REQUIRE(n >= -1 && n <= 0x7fffffffLL);
        if (n >= 0 && n < 100000) {
            uint32_t *ix = (uint32_t *)fz_sentinel_alloc(4u * (size_t)n + 4u);
            if (n > 0) {
                rr = hf_ribbon_indices(sc, pp, topo, ix, n - 1);
                FZ_REQUIRE(rr == HF_ERROR_BUFFER_TOO_SMALL);
                FZ_REQUIRE(fz_untouched(ix, 4u * (size_t)n + 4u));
            }
            rr = hf_ribbon_indices(sc, pp, topo, ix, n);
            FZ_REQUIRE(rr == HF_OK);
            for (i = 0; i < (int)n; ++i)
                FZ_REQUIRE(ix[i] == 0xffffffffu ||
                           ix[i] < 2u * (uint32_t)sc * (uint32_t)pp);
            FZ_REQUIRE(fz_untouched(ix + n, 4u));
            free(ix);
        } else if (n < 0) {
            uint32_t one = 7;
            rr = hf_ribbon_indices(sc, pp, topo, &one, 1);
            FZ_REQUIRE(rr != HF_OK && fz_known_result(rr) && one == 7);
        }
    }

    /* ---- interpolation from the strands as guides ----------------------- */
    {
        hf_strand_binding *b = (hf_strand_binding *)malloc(
            sizeof(hf_strand_binding) * (size_t)S);
        hf_interp_params ip;
        float *ipts = (float *)fz_sentinel_alloc(sizeof(float) * 3u *
                                                 (size_t)S * (size_t)P);
        if (!b) abort();
        for (i = 0; i < S; ++i) {
            float w0 = fz_float_in(&r, 0.0f, 1.0f);
            float w1 = fz_float_in(&r, 0.0f, 1.0f - (w0 < 1.0f ? w0 : 1.0f));
            for (k = 0; k < 3; ++k)
                b[i].guide[k] = fz_chance(&r, 250) ? (uint32_t)fz_int(&r, 0, S - 1)
                                                   : fz_u32(&r);
            b[i].weight[0] = w0;
            b[i].weight[1] = w1;
            b[i].weight[2] = (1.0f - w0) - w1;
            b[i].length_scale = fz_chance(&r, 240) ? fz_float_in(&r, 0.0f, 2.0f)
                                                   : fz_float(&r, 1e3f);
        }
        memset(&ip, 0, sizeof ip);
        ip.points_per_strand = fz_chance(&r, 250) ? P : fz_int(&r, -1, P);
        ip.clump = fz_chance(&r, 240) ? fz_float_in(&r, 0.0f, 1.0f)
                                      : fz_float(&r, 2.0f);
        fz_range_untotalled(&r, S, &first, &count);
        rr = hf_interpolate(pts, S, b, first, count, &ip, ipts);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK)
            FZ_REQUIRE(fz_untouched(ipts, sizeof(float) * 3u * (size_t)S *
                                              (size_t)P));
        /* (finite outputs are not promised here: huge guides times a
           huge scale may overflow; the fur object bounds both) */
        free(ipts);
        free(b);
    }

    /* ---- LOD helpers ------------------------------------------------------ */
    {
        int total = fz_int(&r, -5, 0x7fffffff);
        float lod = fz_float(&r, 1.5f);
        int n = hf_lod_strand_count(total, lod);
        float w = hf_lod_width_scale(total, fz_int(&r, -5, 0x7fffffff));
        float d = hf_lod_from_distance(fz_float(&r, 100.0f), fz_float(&r, 10.0f),
                                       fz_float(&r, 100.0f));
        FZ_REQUIRE(n >= 0 && (total <= 0 || n <= total));
        FZ_REQUIRE(fz_finite(w) && w >= 1.0f);
        FZ_REQUIRE(fz_finite(d) && d >= 0.0f && d <= 1.0f);
    }

    free(v);
    free(v2);
    free(pts);
    free(uv);
    free(rgba);
    free(c3x);
    free(wid);
    return 0;
}
