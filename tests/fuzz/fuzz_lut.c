/* fuzz_lut.c - the Marschner LUT baker with fuzz-built parameters (eta,
   shifts, widths down to denormals, absorption up to huge, variants,
   sizes), row ranges, hf_lut_to_u8 scales and hf_lut_eval_m / _n points.

   Contracts checked (abort() on violation): every result is HF_OK or a
   table code; validate and bake agree; on failure the texture still holds
   its sentinel; on success exactly the asked rows are written, every
   texel is finite (the library promises: never NaN), M.a and N.a lie in [0, 1], the
   densities are >= 0, and the same rows baked in pieces give the same
   bytes; hf_lut_to_u8 writes everything or nothing; eval writes finite
   values or nothing. Then (from the bytes left) the energy-conserving
   fibre's M and N and the dual scattering tables with the same
   parameters: finite, M and N not negative, the same bytes in pieces,
   nothing written on failure, and the model's calls that refuse it.

   libFuzzer: clang -g -O1 -fsanitize=fuzzer,address,undefined fuzz_lut.c
              fuzz_impl.c (the header's implementation)
   replay:    gcc -O1 -g fuzz_main.c fuzz_lut.c fuzz_impl.c -lm (see the
              Makefile) */
#include "../../hairfur.h"
#include "fuzz_common.h"

#define FZ_LUT_MAX 12 /* texture side: the bake is O(n^2) transcendental */

static double fz_double(fz_reader *r, double lo, double hi)
{
    int sel = fz_u8(r);
    if (sel < r->p_special + 2) return (double)fz_special(fz_u8(r));
    if (sel < r->p_special + r->p_raw + 4) {
        uint64_t u = (uint64_t)fz_u32(r) | ((uint64_t)fz_u32(r) << 32);
        double d;
        memcpy(&d, &u, sizeof d);
        return d;
    }
    return lo + (hi - lo) * ((double)fz_u32(r) / 4294967295.0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader r;
    hf_lut_params p;
    hf_result rv, rr;
    int n, which, first, count, k;
    size_t texels, bytes;
    float *a, *b, *a2, *b2;

    fz_init(&r, data, size);
    hf_lut_params_init(&p);
    if (fz_u8(&r) & 1) p.eta = fz_double(&r, 1.2, 3.0);
    if (fz_u8(&r) & 1) p.alpha_r_deg = fz_double(&r, -90.0, 90.0);
    if (fz_u8(&r) & 1) p.beta_r_deg = fz_chance(&r, 32) ? fz_double(&r, 0.0, 1e-30)
                                                        : fz_double(&r, 0.0, 60.0);
    if (fz_u8(&r) & 1) p.sigma_a = fz_double(&r, 0.0, 50.0);
    for (k = 0; k < 3; ++k)
        if (fz_u8(&r) & 1) p.sigma_a_rgb[k] = fz_double(&r, 0.0, 50.0);
    if (fz_chance(&r, 128)) p.variant = fz_chance(&r, 250) ? 1 : fz_int(&r, -1, 5);
    p.size = fz_chance(&r, 250) ? fz_int(&r, 1, FZ_LUT_MAX) : fz_int(&r, -1, 0);
    if (fz_chance(&r, 2)) p.size = 0x7fffffff;
    if (fz_chance(&r, 32)) p.explicit_zero = fz_int(&r, 0, 7);

    {
        hf_diag d;
        rv = hf_lut_validate(&p, &d);
        FZ_REQUIRE(fz_known_result(rv) && d.result == rv);
        if (p.size == 0) {
            /* 0 is the default size, 256: too big to bake per input, so
               it is validated only, then baked at a small size */
            FZ_REQUIRE(rv != HF_ERROR_BAD_COUNT);
            p.size = 1 + fz_u8(&r) % FZ_LUT_MAX;
            rv = hf_lut_validate(&p, NULL);
        }
    }
    n = p.size >= 1 && p.size <= FZ_LUT_MAX ? p.size : 1;
    texels = (size_t)n * (size_t)n;
    bytes = texels * 4u * sizeof(float);
    a = (float *)fz_sentinel_alloc(bytes);
    b = (float *)fz_sentinel_alloc(bytes);
    a2 = (float *)fz_sentinel_alloc(bytes);
    b2 = (float *)fz_sentinel_alloc(bytes);

    which = fz_u8(&r) % 3;
    fz_range(&r, n, &first, &count);
    if (which == 0) rr = hf_lut_bake_m(&p, first, count, a);
    else if (which == 1) rr = hf_lut_bake_n(&p, first, count, a);
    else rr = hf_lut_bake_n_rgb(&p, first, count, a, b);
    FZ_REQUIRE(fz_known_result(rr));
    if (rv != HF_OK) FZ_REQUIRE(rr == rv || rr == HF_ERROR_BAD_RANGE);
    if (rr != HF_OK) {
        FZ_REQUIRE(fz_untouched(a, bytes) && fz_untouched(b, bytes));
    } else {
        size_t t0 = (size_t)first * (size_t)n, tn = (size_t)count * (size_t)n, t;
        FZ_REQUIRE(rv == HF_OK && p.size == n);
        FZ_REQUIRE(fz_untouched(a, t0 * 16u));
        FZ_REQUIRE(fz_untouched(a + 4 * (t0 + tn), (texels - t0 - tn) * 16u));
        if (which != 2) FZ_REQUIRE(fz_untouched(b, bytes));
        for (t = t0; t < t0 + tn; ++t) {
            const float *x = a + 4 * t;
            FZ_REQUIRE(fz_all_finite(x, 4));
            FZ_REQUIRE(x[0] >= 0.0f && x[1] >= 0.0f && x[2] >= 0.0f);
            FZ_REQUIRE(x[3] >= 0.0f && x[3] <= 1.0f);
            if (which == 2) {
                FZ_REQUIRE(fz_all_finite(b + 4 * t, 4));
                FZ_REQUIRE(b[4 * t + 3] == x[3]); /* both carry N_R */
            }
        }
        /* the same rows in pieces: the same bytes */
        {
            int done = first, end = first + count;
            while (done < end) {
                int c = fz_int(&r, 1, end - done);
                if (which == 0) rr = hf_lut_bake_m(&p, done, c, a2);
                else if (which == 1) rr = hf_lut_bake_n(&p, done, c, a2);
                else rr = hf_lut_bake_n_rgb(&p, done, c, a2, b2);
                FZ_REQUIRE(rr == HF_OK);
                done += c;
            }
            FZ_REQUIRE(memcmp(a, a2, bytes) == 0);
            if (which == 2) FZ_REQUIRE(memcmp(b, b2, bytes) == 0);
        }
        /* the full texture: quantise */
        if (first == 0 && count == n) {
            unsigned char *q = (unsigned char *)fz_sentinel_alloc(4u * texels);
            float scales[4] = {-7.0f, -7.0f, -7.0f, -7.0f}, sin_[4];
            int given = fz_u8(&r) & 1;
            for (k = 0; k < 4; ++k) sin_[k] = fz_float(&r, 10.0f);
            rr = hf_lut_to_u8(a, n, given ? sin_ : NULL, q, scales);
            FZ_REQUIRE(fz_known_result(rr));
            if (rr != HF_OK) {
                FZ_REQUIRE(fz_untouched(q, 4u * texels) && scales[0] == -7.0f);
            } else {
                FZ_REQUIRE(fz_all_finite(scales, 4));
                for (k = 0; k < 4; ++k) FZ_REQUIRE(scales[k] > 0.0f);
            }
            free(q);
            if (which == 0) {
                /* M is symmetric */
                int i, j;
                for (i = 0; i < n; ++i)
                    for (j = 0; j < n; ++j)
                        FZ_REQUIRE(memcmp(a + 4 * ((size_t)j * n + i),
                                          a + 4 * ((size_t)i * n + j), 16) == 0);
            }
        }
    }

    /* ---- eval at fuzz points ------------------------------------------- */
    for (k = 0; k < 2; ++k) {
        double out[3] = {-7.0, -7.0, -7.0};
        double x = fz_double(&r, -4.0, 4.0), y = fz_double(&r, -1.0, 4.0);
        rr = k == 0 ? hf_lut_eval_m(&p, x, out) : hf_lut_eval_n(&p, x, y, out);
        FZ_REQUIRE(fz_known_result(rr));
        if (rr != HF_OK) {
            FZ_REQUIRE(out[0] == -7.0 && out[1] == -7.0 && out[2] == -7.0);
        } else {
            int c;
            for (c = 0; c < 3; ++c)
                FZ_REQUIRE(out[c] == out[c] && out[c] - out[c] == 0.0 &&
                           out[c] >= 0.0);
        }
    }

    /* ---- the energy-conserving fibre, the dual tables ----------------- */
    {
        float *d = (float *)fz_sentinel_alloc(3u * bytes);
        float *d2 = (float *)fz_sentinel_alloc(3u * bytes);
        hf_result rd;
        int w = fz_u8(&r) % 3, f, c;
        p.model = fz_chance(&r, 250) ? HF_LUT_ENERGY : fz_int(&r, -1, 3);
        rv = hf_lut_validate(&p, NULL);
        fz_range(&r, n, &f, &c);
        rd = w == 0   ? hf_lut_bake_m(&p, f, c, d)
             : w == 1 ? hf_lut_bake_n(&p, f, c, d)
                      : hf_lut_bake_dual(&p, f, c, d);
        FZ_REQUIRE(fz_known_result(rd));
        if (rv != HF_OK && w != 2) FZ_REQUIRE(rd != HF_OK);
        if (rd != HF_OK) {
            FZ_REQUIRE(fz_untouched(d, 3u * bytes));
        } else {
            size_t planes = w == 2 ? 3u : 1u, pl, t;
            for (pl = 0; pl < planes; ++pl) {
                const float *x = d + pl * texels * 4u;
                size_t t0 = (size_t)f * (size_t)n, tn = (size_t)c * (size_t)n;
                FZ_REQUIRE(fz_untouched(x, t0 * 16u));
                for (t = t0; t < t0 + tn; ++t) {
                    FZ_REQUIRE(fz_all_finite(x + 4 * t, 4));
                    if (w != 2)
                        FZ_REQUIRE(x[4 * t] >= 0.0f && x[4 * t + 1] >= 0.0f &&
                                   x[4 * t + 2] >= 0.0f && x[4 * t + 3] >= 0.0f);
                }
            }
            {
                int done = f, end = f + c;
                while (done < end) {
                    int k2 = fz_int(&r, 1, end - done);
                    rd = w == 0   ? hf_lut_bake_m(&p, done, k2, d2)
                         : w == 1 ? hf_lut_bake_n(&p, done, k2, d2)
                                  : hf_lut_bake_dual(&p, done, k2, d2);
                    FZ_REQUIRE(rd == HF_OK);
                    done += k2;
                }
                if (c > 0)
                    FZ_REQUIRE(memcmp(d, d2, (w == 2 ? 3u : 1u) * bytes) == 0);
            }
        }
        if (rv == HF_OK && p.model == HF_LUT_ENERGY) {
            double out[3] = {-7.0, -7.0, -7.0};
            FZ_REQUIRE(hf_lut_eval_m(&p, 0.1, out) == HF_ERROR_BAD_PARAMETER);
            FZ_REQUIRE(out[0] == -7.0);
        }
        free(d);
        free(d2);
    }

    free(a);
    free(b);
    free(a2);
    free(b2);
    return 0;
}
