/* bake_luts.c - bake the Marschner M and N lookup textures to PNG files.

   Shows: hf_lut_params_init, hf_lut_bake_m / hf_lut_bake_n /
   hf_lut_bake_n_rgb, hf_lut_to_u8. The textures and the shader that uses
   them are described in docs/luts.md.

   Build:  cc -O2 -std=c99 bake_luts.c -o bake_luts -lm
           (stb_image_write.h from Debian's libstb-dev, /usr/include/stb)
   Usage:  bake_luts [--size N] [--eta F] [--absorption F |
                      --absorption-rgb R,G,B] [--alpha-r DEG] [--beta-r DEG]
                     [--exact] [--out DIR] [--raw] [--channels]

   Writes, in DIR (default "."):
     marschner_m.png, marschner_n.png  8-bit RGBA, each channel divided by
                          its scale (section 9 of docs/marschner-spec.md)
     marschner_scales.txt one line per PNG: file name, then the R G B A
                          scales; the shader multiplies the sampled unorm
                          value by them (lines starting with # are comments)
     with --absorption-rgb also marschner_n_tt_rgb.png and
                          marschner_n_trt_rgb.png (per-RGB TT and TRT, alpha
                          N_R) and their scale lines
     with --raw           marschner_m.f32, marschner_n.f32 (and the rgb
                          ones): float32 little-endian RGBA, n * n texels,
                          row 0 first, no header
     with --channels      one 8-bit grayscale PNG per colour channel
                          (marschner_m_r.png ... marschner_m_a.png,
                          marschner_n_r.png ... marschner_n_b.png), each
                          divided by its 99.9th percentile, clipped and
                          shown with display gamma 1/2.2 so that small
                          values stay visible: for looking at, not for
                          rendering

   Which way up: row 0 of a texture (v = 0, texture coordinate t = 0) is
   the FIRST row of each PNG, which image viewers show at the TOP. So
   stbi_load() + glTexImage2D() with no flip gives the layout the shader
   expects; a viewer shows v growing downwards. */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(void)
{
    fprintf(stderr,
            "usage: bake_luts [--size N] [--eta F] [--absorption F | "
            "--absorption-rgb R,G,B] [--alpha-r DEG] [--beta-r DEG] "
            "[--exact] [--out DIR] [--raw] [--channels]\n");
}

static int parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    *out = strtod(s, &end);
    return end != s && *end == 0 && errno == 0;
}

static int parse_rgb(const char *s, double out[3])
{
    char *end;
    int k;
    for (k = 0; k < 3; ++k) {
        errno = 0;
        out[k] = strtod(s, &end);
        if (end == s || errno != 0) return 0;
        if (k < 2) {
            if (*end != ',') return 0;
            s = end + 1;
        }
    }
    return *end == 0;
}

static int path(char *buf, size_t size, const char *dir, const char *name)
{
    int len = snprintf(buf, size, "%s/%s", dir, name);
    return len > 0 && (size_t)len < size;
}

/* float32 little-endian whatever the host's byte order */
static int write_f32(const char *file, const float *data, size_t count)
{
    FILE *f = fopen(file, "wb");
    size_t i;
    int ok;
    if (!f) return 0;
    for (i = 0; i < count; ++i) {
        unsigned char b[4];
        uint32_t u;
        memcpy(&u, &data[i], 4);
        b[0] = (unsigned char)(u & 0xffu);
        b[1] = (unsigned char)((u >> 8) & 0xffu);
        b[2] = (unsigned char)((u >> 16) & 0xffu);
        b[3] = (unsigned char)(u >> 24);
        if (fwrite(b, 1, 4, f) != 4) break;
    }
    ok = i == count;
    return fclose(f) == 0 && ok;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* One grayscale PNG per channel (the first `nc`), divided by its 99.9th
   percentile, with display gamma 1/2.2. */
static int write_channels(const char *dir, const char *stem, const float *t,
                          int n, int nc, float *tmp, unsigned char *gray)
{
    static const char names[4] = {'r', 'g', 'b', 'a'};
    size_t count = (size_t)n * (size_t)n, i;
    int c;
    for (c = 0; c < nc; ++c) {
        char name[64], file[4096];
        float p;
        for (i = 0; i < count; ++i) tmp[i] = t[4 * i + (size_t)c];
        qsort(tmp, count, sizeof(float), cmp_float);
        p = tmp[(size_t)(0.999 * (double)(count - 1))];
        if (!(p > 0.0f)) p = 1.0f;
        for (i = 0; i < count; ++i) {
            double y = t[4 * i + (size_t)c] / (double)p;
            y = y > 1.0 ? 1.0 : (y > 0.0 ? pow(y, 1.0 / 2.2) : 0.0);
            gray[i] = (unsigned char)(255.0 * y + 0.5);
        }
        snprintf(name, sizeof name, "%s_%c.png", stem, names[c]);
        if (!path(file, sizeof file, dir, name) ||
            !stbi_write_png(file, n, n, 1, gray, n)) {
            fprintf(stderr, "bake_luts: cannot write %s/%s\n", dir, name);
            return 0;
        }
        printf("  %s: channel %c / %g (99.9th percentile), gamma 1/2.2\n",
               name,
               names[c], (double)p);
    }
    return 1;
}

/* PNG (and optionally .f32) of one texture; appends its scale line. */
static int save(const char *dir, const char *stem, const float *t, int n,
                int raw, unsigned char *rgba8, FILE *scales)
{
    char name[64], file[4096];
    float sc[4];
    hf_result r = hf_lut_to_u8(t, n, NULL, rgba8, sc);
    if (r != HF_OK) {
        fprintf(stderr, "bake_luts: hf_lut_to_u8: %s\n", hf_result_string(r));
        return 0;
    }
    snprintf(name, sizeof name, "%s.png", stem);
    if (!path(file, sizeof file, dir, name) ||
        !stbi_write_png(file, n, n, 4, rgba8, 4 * n)) {
        fprintf(stderr, "bake_luts: cannot write %s/%s\n", dir, name);
        return 0;
    }
    fprintf(scales, "%s %.9g %.9g %.9g %.9g\n", name, (double)sc[0],
            (double)sc[1], (double)sc[2], (double)sc[3]);
    printf("  %s  scales R %.9g  G %.9g  B %.9g  A %.9g\n", name,
           (double)sc[0], (double)sc[1], (double)sc[2], (double)sc[3]);
    if (raw) {
        snprintf(name, sizeof name, "%s.f32", stem);
        if (!path(file, sizeof file, dir, name) ||
            !write_f32(file, t, 4 * (size_t)n * (size_t)n)) {
            fprintf(stderr, "bake_luts: cannot write %s/%s\n", dir, name);
            return 0;
        }
        printf("  %s\n", name);
    }
    return 1;
}

int main(int argc, char **argv)
{
    hf_lut_params p;
    const char *dir = ".";
    int raw = 0, rgb = 0, channels = 0, i, n, ok = 1;
    char file[4096];
    float *m, *nn, *tt, *trt, *tmp;
    unsigned char *rgba8;
    FILE *scales;
    hf_result r;

    hf_lut_params_init(&p);
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        double d;
        if (strcmp(a, "--exact") == 0) {
            p.variant = HF_LUT_EXACT;
            continue;
        }
        if (strcmp(a, "--raw") == 0) {
            raw = 1;
            continue;
        }
        if (strcmp(a, "--channels") == 0) {
            channels = 1;
            continue;
        }
        if (!v) {
            usage();
            return 2;
        }
        ++i;
        if (strcmp(a, "--out") == 0) {
            dir = v;
        } else if (strcmp(a, "--absorption-rgb") == 0) {
            if (!parse_rgb(v, p.sigma_a_rgb)) {
                usage();
                return 2;
            }
            p.explicit_zero |= HF_LUT_ZERO_SIGMA_A_RGB; /* 0 is no absorption */
            rgb = 1;
        } else if (!parse_double(v, &d)) {
            usage();
            return 2;
        } else if (strcmp(a, "--size") == 0) {
            if (!(d >= -2147483647.0 && d <= 2147483647.0) ||
                d != (double)(int)d) {
                usage();
                return 2;
            }
            p.size = (int)d;
        } else if (strcmp(a, "--eta") == 0) {
            p.eta = d;
        } else if (strcmp(a, "--absorption") == 0) {
            p.sigma_a = d;
            p.sigma_a_rgb[0] = p.sigma_a_rgb[1] = p.sigma_a_rgb[2] = d;
            if (d == 0.0)
                p.explicit_zero |= HF_LUT_ZERO_SIGMA_A | HF_LUT_ZERO_SIGMA_A_RGB;
        } else if (strcmp(a, "--alpha-r") == 0) {
            p.alpha_r_deg = d;
            if (d == 0.0) p.explicit_zero |= HF_LUT_ZERO_ALPHA_R;
        } else if (strcmp(a, "--beta-r") == 0) {
            p.beta_r_deg = d;
        } else {
            usage();
            return 2;
        }
    }
    for (i = 1; i < argc; ++i) /* the two absorption options exclude */
        if (rgb && strcmp(argv[i], "--absorption") == 0) {
            usage();
            return 2;
        }
    r = hf_lut_validate(&p, NULL);
    if (r != HF_OK) {
        fprintf(stderr, "bake_luts: %s\n", hf_result_string(r));
        return 1;
    }

    n = p.size;
    m = (float *)malloc(sizeof(float) * 4 * (size_t)n * (size_t)n);
    nn = (float *)malloc(sizeof(float) * 4 * (size_t)n * (size_t)n);
    tt = (float *)malloc(sizeof(float) * 4 * (size_t)n * (size_t)n);
    trt = (float *)malloc(sizeof(float) * 4 * (size_t)n * (size_t)n);
    tmp = (float *)malloc(sizeof(float) * (size_t)n * (size_t)n);
    rgba8 = (unsigned char *)malloc(4 * (size_t)n * (size_t)n);
    if (!m || !nn || !tt || !trt || !tmp || !rgba8) {
        fprintf(stderr, "bake_luts: out of memory\n");
        return 1;
    }
    if ((r = hf_lut_bake_m(&p, 0, n, m)) != HF_OK ||
        (r = hf_lut_bake_n(&p, 0, n, nn)) != HF_OK ||
        (rgb && (r = hf_lut_bake_n_rgb(&p, 0, n, tt, trt)) != HF_OK)) {
        fprintf(stderr, "bake_luts: %s\n", hf_result_string(r));
        return 1;
    }

    if (!path(file, sizeof file, dir, "marschner_scales.txt") ||
        !(scales = fopen(file, "w"))) {
        fprintf(stderr, "bake_luts: cannot write %s/marschner_scales.txt\n",
                dir);
        return 1;
    }
    fprintf(scales,
            "# bake_luts: size %d, eta %g, alpha_R %g deg, beta_R %g deg, "
            "sigma_a %g (rgb %g %g %g), %s\n"
            "# file  scale_R scale_G scale_B scale_A: texel value = "
            "unorm value (0..1) * scale\n",
            n, p.eta, p.alpha_r_deg, p.beta_r_deg, p.sigma_a,
            p.sigma_a_rgb[0], p.sigma_a_rgb[1], p.sigma_a_rgb[2],
            p.variant == HF_LUT_EXACT ? "exact" : "cubic");
    printf("bake_luts: %d x %d, eta %g, alpha_R %g, beta_R %g, sigma_a %g, "
           "%s -> %s\n",
           n, n, p.eta, p.alpha_r_deg, p.beta_r_deg, p.sigma_a,
           p.variant == HF_LUT_EXACT ? "exact" : "cubic", dir);
    ok = save(dir, "marschner_m", m, n, raw, rgba8, scales) &&
         save(dir, "marschner_n", nn, n, raw, rgba8, scales) &&
         (!rgb || (save(dir, "marschner_n_tt_rgb", tt, n, raw, rgba8,
                        scales) &&
                   save(dir, "marschner_n_trt_rgb", trt, n, raw, rgba8,
                        scales)));
    if (fclose(scales) != 0) ok = 0;
    if (ok) printf("  marschner_scales.txt\n");
    if (ok && channels)
        ok = write_channels(dir, "marschner_m", m, n, 4, tmp, rgba8) &&
             write_channels(dir, "marschner_n", nn, n, 3, tmp, rgba8);
    free(m);
    free(nn);
    free(tt);
    free(trt);
    free(tmp);
    free(rgba8);
    return ok ? 0 : 1;
}
