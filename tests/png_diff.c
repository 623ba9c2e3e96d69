/* png_diff.c - how much two PNGs of the same size differ: prints the
   fraction of pixels with a channel off by more than a threshold (default
   24 of 255) and the mean absolute difference, and exits 0 when the
   fraction is below a limit (default 0.02), 1 when not, 2 on bad input.
   With --stats, how much of one PNG is not background: the fraction of
   pixels with a channel off the top-left pixel's colour (the clear colour
   of a render) by more than the threshold, exit 0 when it is at least the
   limit (default 0.02), 1 when not: an empty picture fails.
   For tests/viewer_check.sh.

     png_diff A.png B.png [THRESHOLD [LIMIT]]
     png_diff --stats A.png [THRESHOLD [LIMIT]] */
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Pixels of a (w x h, RGB) off b (another image, or one colour when
   b_step is 0) by more than thr in some channel; *sum gets the sum of
   the absolute differences. */
static long count_off(const unsigned char *a, const unsigned char *b,
                      int b_step, long n, int thr, double *sum)
{
    long off = 0, i;
    *sum = 0.0;
    for (i = 0; i < n; ++i) {
        int k, worst = 0;
        for (k = 0; k < 3; ++k) {
            int d = abs(a[3 * i + k] - b[b_step * i + k]);
            *sum += d;
            if (d > worst) worst = d;
        }
        off += worst > thr;
    }
    return off;
}

int main(int argc, char **argv)
{
    /* THRESHOLD and LIMIT are argv[3] and argv[4] in both forms */
    int stats = argc > 1 && !strcmp(argv[1], "--stats");
    int wa, ha, wb, hb, n, thr = argc > 3 ? atoi(argv[3]) : 24;
    double limit = argc > 4 ? atof(argv[4]) : 0.02, sum, frac;
    long off;
    unsigned char *a, *b;
    if (argc < 3) {
        fprintf(stderr, "usage: png_diff A.png B.png [THRESHOLD [LIMIT]]\n"
                        "       png_diff --stats A.png [THRESHOLD [LIMIT]]\n");
        return 2;
    }
    if (stats) {
        unsigned char bg[3];
        a = stbi_load(argv[2], &wa, &ha, &n, 3);
        if (!a) {
            fprintf(stderr, "png_diff: cannot read %s\n", argv[2]);
            return 2;
        }
        memcpy(bg, a, sizeof bg);
        off = count_off(a, bg, 0, (long)wa * ha, thr, &sum);
        frac = (double)off / ((double)wa * ha);
        printf("png_diff: %.4f of pixels off the background (%d, %d, %d) by "
               "more than %d\n", frac, bg[0], bg[1], bg[2], thr);
        stbi_image_free(a);
        return frac >= limit ? 0 : 1;
    }
    a = stbi_load(argv[1], &wa, &ha, &n, 3);
    b = stbi_load(argv[2], &wb, &hb, &n, 3);
    if (!a || !b || wa != wb || ha != hb) {
        fprintf(stderr, "png_diff: cannot read both, or sizes differ\n");
        return 2;
    }
    off = count_off(a, b, 3, (long)wa * ha, thr, &sum);
    frac = (double)off / ((double)wa * ha);
    printf("png_diff: %.4f of pixels off by more than %d, mean |a - b| %.3f\n",
           frac, thr, sum / (3.0 * wa * ha));
    stbi_image_free(a);
    stbi_image_free(b);
    return frac < limit ? 0 : 1;
}
