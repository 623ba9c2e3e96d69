/* bake_luts.c - bake the Marschner M and N lookup textures to PNG files.

   Shows: hf_lut_params_init, hf_lut_bake_m / hf_lut_bake_n /
   hf_lut_bake_n_rgb, hf_lut_to_u8, hf_lut_furnace, hf_lut_bake_dual. The
   textures and the shader that uses them are described in docs/luts.md.

   Build:  cc -O2 -std=c99 bake_luts.c -o bake_luts -lm
           (stb_image_write.h from Debian's libstb-dev, /usr/include/stb)
   Usage:  bake_luts [--size N] [--eta F] [--absorption F |
                      --absorption-rgb R,G,B] [--alpha-r DEG] [--beta-r DEG]
                     [--exact] [--model marschner|energy] [--out DIR]
                     [--raw] [--channels] [--dual] [--furnace] [--help]

   --model energy bakes the energy-conserving fibre instead of the paper's
   (its files are named energy_* instead of marschner_*).
   --furnace writes nothing: it bakes the energy-conserving fibre (or the
   --model given) and prints its white-furnace albedo, one line per
   absorption (0, 0.2, 1 and --absorption if given) and incident angle
   (0, 30, 60, 80 degrees):
       furnace sigma_a=S theta_i=DEG albedo=A
   --dual adds dual_scattering.f32 and dual_scattering.txt (below).

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
     with --dual          dual_scattering.f32: hf_lut_bake_dual's tables,
                          float32 little-endian, no header: 3 planes, each
                          N x N RGBA, plane 0 first, row 0 first; column i
                          is sigma_a = u / (1 - u), u = (i + 0.5) / N, row
                          j is cos(theta_i) = (j + 0.5) / N; plane 0 =
                          a_f, alpha_f, beta_f, 1; plane 1 = a_b, alpha_b,
                          beta_b, 1; plane 2 = A_b, delta_b, sigma_b, 1
                          (angles in radians); dual_scattering.txt says
                          the same with the parameters

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

#define USAGE                                                                  \
    "usage: bake_luts [--size N] [--eta F] [--absorption F | "                \
    "--absorption-rgb R,G,B] [--alpha-r DEG] [--beta-r DEG] [--exact] "        \
    "[--model marschner|energy] [--out DIR] [--raw] [--channels] [--dual] "    \
    "[--furnace] [--help]\n"

static void usage(void) { fprintf(stderr, USAGE); }

static void help(void)
{
    printf(USAGE
           "\n"
           "Bakes the Marschner lookup textures (docs/luts.md) into DIR:\n"
           "  PREFIX_m.png, PREFIX_n.png    8-bit RGBA, each channel divided "
           "by its scale\n"
           "  PREFIX_scales.txt             one line per PNG: name, R G B A "
           "scales\n"
           "  PREFIX is marschner (the paper's fibre, the default) or energy "
           "(--model\n"
           "  energy: the energy-conserving fibre, M = M_R, M_TT, M_TRT, "
           "M_p>=3 per unit\n"
           "  sin(theta_r); N = N_R, N_TT, N_TRT, N_p>=3 by (cos theta_i, "
           "cos phi)).\n"
           "  --absorption-rgb R,G,B  also marschner_n_tt_rgb.png and "
           "marschner_n_trt_rgb.png\n"
           "  --raw        each texture also as PREFIX_*.f32: float32 "
           "little-endian RGBA,\n"
           "               N x N texels, row 0 first, no header\n"
           "  --channels   grayscale previews of each channel (not for "
           "rendering)\n"
           "  --dual       dual_scattering.f32 (and .txt): the dual "
           "scattering tables of\n"
           "               the energy-conserving fibre (hf_lut_bake_dual), "
           "float32\n"
           "               little-endian, no header: 3 planes of N x N RGBA, "
           "plane 0 first,\n"
           "               row 0 first. Column i: sigma_a = u / (1 - u), "
           "u = (i + 0.5) / N;\n"
           "               row j: cos(theta_i) = (j + 0.5) / N. Plane 0: "
           "a_f, alpha_f,\n"
           "               beta_f, 1; plane 1: a_b, alpha_b, beta_b, 1; "
           "plane 2: A_b,\n"
           "               delta_b, sigma_b, 1 (angles in radians of "
           "theta_h)\n"
           "  --furnace    write nothing; print the white-furnace albedo of "
           "the baked\n"
           "               energy-conserving fibre (or of --model), "
           "integrated from the\n"
           "               textures as the shader combines them, one line "
           "per absorption\n"
           "               (0, 0.2, 1, and --absorption) and angle (0, 30, "
           "60, 80 degrees):\n"
           "               furnace sigma_a=S theta_i=DEG albedo=A\n"
           "Defaults: --size 256 --eta 1.55 --absorption 0.2 --alpha-r -7.5 "
           "--beta-r 7.5,\n"
           "cubic exit angle (--exact: the exact one), --out .\n");
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

/* --furnace: bake M once and N per absorption, print the albedo. */
static int furnace(hf_lut_params p, int model_given, double extra)
{
    static const double angles[4] = {0.0, 30.0, 60.0, 80.0};
    double sig[4] = {0.0, 0.2, 1.0, 0.0};
    int ns = 3, n, s, k;
    float *m, *t;
    hf_result r;
    if (!model_given) p.model = HF_LUT_ENERGY;
    if (extra >= 0.0 && extra != 0.0 && extra != 0.2 && extra != 1.0) {
        /* in order */
        for (k = 3; k > 0 && sig[k - 1] > extra; --k) sig[k] = sig[k - 1];
        sig[k] = extra;
        ns = 4;
    }
    n = p.size;
    m = (float *)malloc(sizeof(float) * 4 * (size_t)n * (size_t)n);
    t = (float *)malloc(sizeof(float) * 4 * (size_t)n * (size_t)n);
    if (!m || !t) {
        fprintf(stderr, "bake_luts: out of memory\n");
        free(m);
        free(t);
        return 1;
    }
    if ((r = hf_lut_bake_m(&p, 0, n, m)) != HF_OK) goto fail;
    for (s = 0; s < ns; ++s) {
        p.sigma_a = sig[s];
        p.explicit_zero |= HF_LUT_ZERO_SIGMA_A;
        if ((r = hf_lut_bake_n(&p, 0, n, t)) != HF_OK) goto fail;
        for (k = 0; k < 4; ++k) {
            double albedo;
            r = hf_lut_furnace(&p, m, t, angles[k] * 3.14159265358979323846 /
                                             180.0, &albedo);
            if (r != HF_OK) goto fail;
            printf("furnace sigma_a=%g theta_i=%g albedo=%.6f\n", sig[s],
                   angles[k], albedo);
        }
    }
    free(m);
    free(t);
    return 0;
fail:
    fprintf(stderr, "bake_luts: %s\n", hf_result_string(r));
    free(m);
    free(t);
    return 1;
}

/* --dual: dual_scattering.f32 and its description. */
static int save_dual(const char *dir, const hf_lut_params *p)
{
    int n = p->size;
    size_t count = 12u * (size_t)n * (size_t)n;
    float *d = (float *)malloc(sizeof(float) * count);
    char file[4096];
    FILE *f;
    hf_result r;
    int ok;
    if (!d) {
        fprintf(stderr, "bake_luts: out of memory\n");
        return 0;
    }
    if ((r = hf_lut_bake_dual(p, 0, n, d)) != HF_OK) {
        fprintf(stderr, "bake_luts: %s\n", hf_result_string(r));
        free(d);
        return 0;
    }
    ok = path(file, sizeof file, dir, "dual_scattering.f32") &&
         write_f32(file, d, count);
    free(d);
    if (!ok || !path(file, sizeof file, dir, "dual_scattering.txt") ||
        !(f = fopen(file, "w"))) {
        fprintf(stderr, "bake_luts: cannot write %s/dual_scattering.*\n", dir);
        return 0;
    }
    fprintf(f,
            "# dual_scattering.f32: hf_lut_bake_dual, the energy-conserving "
            "fibre\n"
            "# eta %g, alpha_R %g deg, beta_R %g deg, %s, d_b %g\n"
            "# float32 little-endian, no header: 3 planes of %d x %d RGBA, "
            "plane 0 first,\n"
            "# row 0 first; float c of texel (i, j) of plane k at "
            "4 * (%d * %d * k + j * %d + i) + c\n"
            "# column i: sigma_a = u / (1 - u), u = (i + 0.5) / %d "
            "(per fibre radius, chord)\n"
            "# row j: cos(theta_i) = (j + 0.5) / %d\n"
            "# plane 0: a_f alpha_f beta_f 1\n"
            "# plane 1: a_b alpha_b beta_b 1\n"
            "# plane 2: A_b delta_b sigma_b 1\n"
            "# angles in radians of theta_h; docs/luts.md has the formulas\n"
            "size %d\nplanes 3\n",
            p->eta, p->alpha_r_deg, p->beta_r_deg,
            p->variant == HF_LUT_EXACT ? "exact" : "cubic", HF_LUT_DUAL_DB, n,
            n, n, n, n, n, n, n);
    if (fclose(f) != 0) return 0;
    printf("  dual_scattering.f32 (%d x %d x 3 planes RGBA float32), "
           "dual_scattering.txt\n",
           n, n);
    return 1;
}

/* The command line: every option's value, the defaults where not given. */
typedef struct bl_options {
    hf_lut_params p;
    const char *dir;
    int raw, rgb, channels, dual, furn, model_given;
    double absorption; /* -1: not given */
} bl_options;

/* The command line into *o: -1 to go on, else the exit code (0 after
   --help, 2 for a bad argument). */
static int parse_args(int argc, char **argv, bl_options *o)
{
    int i;
    memset(o, 0, sizeof *o);
    o->dir = ".";
    o->absorption = -1.0;
    hf_lut_params_init(&o->p);
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        double d;
        if (strcmp(a, "--exact") == 0) {
            o->p.variant = HF_LUT_EXACT;
            continue;
        }
        if (strcmp(a, "--raw") == 0) {
            o->raw = 1;
            continue;
        }
        if (strcmp(a, "--channels") == 0) {
            o->channels = 1;
            continue;
        }
        if (strcmp(a, "--dual") == 0) {
            o->dual = 1;
            continue;
        }
        if (strcmp(a, "--furnace") == 0) {
            o->furn = 1;
            continue;
        }
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            help();
            return 0;
        }
        if (!v) {
            usage();
            return 2;
        }
        ++i;
        if (strcmp(a, "--out") == 0) {
            o->dir = v;
        } else if (strcmp(a, "--model") == 0) {
            if (strcmp(v, "marschner") == 0)
                o->p.model = HF_LUT_MARSCHNER;
            else if (strcmp(v, "energy") == 0)
                o->p.model = HF_LUT_ENERGY;
            else {
                usage();
                return 2;
            }
            o->model_given = 1;
        } else if (strcmp(a, "--absorption-rgb") == 0) {
            if (!parse_rgb(v, o->p.sigma_a_rgb)) {
                usage();
                return 2;
            }
            o->p.explicit_zero |= HF_LUT_ZERO_SIGMA_A_RGB; /* 0 is no absorption */
            o->rgb = 1;
        } else if (!parse_double(v, &d)) {
            usage();
            return 2;
        } else if (strcmp(a, "--size") == 0) {
            if (!(d >= 1.0 && d <= (double)HF_LUT_MAX_SIZE) ||
                d != (double)(int)d) {
                fprintf(stderr, "bake_luts: --size %s is not a whole number "
                                "in [1, %d]\n", v, HF_LUT_MAX_SIZE);
                return 2;
            }
            o->p.size = (int)d;
        } else if (strcmp(a, "--eta") == 0) {
            o->p.eta = d;
        } else if (strcmp(a, "--absorption") == 0) {
            o->absorption = d;
            o->p.sigma_a = d;
            o->p.sigma_a_rgb[0] = o->p.sigma_a_rgb[1] = o->p.sigma_a_rgb[2] = d;
            if (d == 0.0)
                o->p.explicit_zero |= HF_LUT_ZERO_SIGMA_A | HF_LUT_ZERO_SIGMA_A_RGB;
        } else if (strcmp(a, "--alpha-r") == 0) {
            o->p.alpha_r_deg = d;
            if (d == 0.0) o->p.explicit_zero |= HF_LUT_ZERO_ALPHA_R;
        } else if (strcmp(a, "--beta-r") == 0) {
            o->p.beta_r_deg = d;
        } else {
            usage();
            return 2;
        }
    }
    for (i = 1; i < argc; ++i) /* the two absorption options exclude */
        if (o->rgb && strcmp(argv[i], "--absorption") == 0) {
            usage();
            return 2;
        }
    return -1;
}

int main(int argc, char **argv)
{
    bl_options o;
    hf_lut_params p;
    const char *dir, *prefix;
    int raw, rgb, channels, dual, n, ok = 1, rc;
    char file[4096], name[64];
    float *m, *nn, *tt, *trt, *tmp;
    unsigned char *rgba8;
    FILE *scales;
    hf_result r;

    if ((rc = parse_args(argc, argv, &o)) >= 0) return rc;
    p = o.p; /* the names the steps below use */
    dir = o.dir;
    raw = o.raw;
    rgb = o.rgb;
    channels = o.channels;
    dual = o.dual;
    {
        /* the option behind each field hf_lut_validate can name (a
           component of sigma_a_rgb is named with its index) */
        static const char *const opt[][2] = {
            {"eta", "--eta"},           {"alpha_r_deg", "--alpha-r"},
            {"beta_r_deg", "--beta-r"}, {"sigma_a", "--absorption"}};
        hf_diag dg;
        size_t k;
        r = hf_lut_validate(&p, &dg);
        if (r != HF_OK) {
            const char *o_name = NULL;
            if (dg.field && !strncmp(dg.field, "sigma_a_rgb", 11))
                o_name = "--absorption-rgb";
            for (k = 0; !o_name && dg.field && k < sizeof opt / sizeof opt[0];
                 ++k)
                if (!strcmp(dg.field, opt[k][0])) o_name = opt[k][1];
            fprintf(stderr, "bake_luts: %s%s%s (%s)\n", o_name ? o_name : "",
                    o_name ? ": " : "", dg.message, hf_result_string(r));
            return 1;
        }
    }
    if (o.furn) return furnace(p, o.model_given, o.absorption);
    prefix = p.model == HF_LUT_ENERGY ? "energy" : "marschner";

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

    snprintf(name, sizeof name, "%s_scales.txt", prefix);
    if (!path(file, sizeof file, dir, name) || !(scales = fopen(file, "w"))) {
        fprintf(stderr, "bake_luts: cannot write %s/%s\n", dir, name);
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
    if (p.model == HF_LUT_ENERGY)
        fprintf(scales, "# the energy-conserving fibre (--model energy)\n");
    printf("bake_luts: %d x %d, eta %g, alpha_R %g, beta_R %g, sigma_a %g, "
           "%s%s -> %s\n",
           n, n, p.eta, p.alpha_r_deg, p.beta_r_deg, p.sigma_a,
           p.variant == HF_LUT_EXACT ? "exact" : "cubic",
           p.model == HF_LUT_ENERGY ? ", energy-conserving" : "", dir);
    {
        char sm[64], sn[64];
        snprintf(sm, sizeof sm, "%s_m", prefix);
        snprintf(sn, sizeof sn, "%s_n", prefix);
        ok = save(dir, sm, m, n, raw, rgba8, scales) &&
             save(dir, sn, nn, n, raw, rgba8, scales);
    }
    ok = ok &&
         (!rgb || (save(dir, "marschner_n_tt_rgb", tt, n, raw, rgba8,
                        scales) &&
                   save(dir, "marschner_n_trt_rgb", trt, n, raw, rgba8,
                        scales)));
    if (fclose(scales) != 0) ok = 0;
    if (ok) printf("  %s\n", name);
    if (ok && channels) {
        char sm[64], sn[64];
        snprintf(sm, sizeof sm, "%s_m", prefix);
        snprintf(sn, sizeof sn, "%s_n", prefix);
        ok = write_channels(dir, sm, m, n, 4, tmp, rgba8) &&
             write_channels(dir, sn, nn, n,
                            p.model == HF_LUT_ENERGY ? 4 : 3, tmp, rgba8);
    }
    if (ok && dual) ok = save_dual(dir, &p);
    free(m);
    free(nn);
    free(tt);
    free(trt);
    free(tmp);
    free(rgba8);
    return ok ? 0 : 1;
}
