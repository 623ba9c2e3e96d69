/* png_diff.c - how much two PNGs of the same size differ: prints the
   fraction of pixels with a channel off by more than a threshold (default
   24 of 255) and the mean absolute difference, and exits 0 when the
   fraction is below a limit (default 0.02), 1 when not, 2 on bad input.
   For tests/viewer_check.sh.

     png_diff A.png B.png [THRESHOLD [LIMIT]] */
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    int wa, ha, wb, hb, n, thr = argc > 3 ? atoi(argv[3]) : 24;
    double limit = argc > 4 ? atof(argv[4]) : 0.02, sum = 0.0;
    long off = 0, i;
    unsigned char *a, *b;
    if (argc < 3) {
        fprintf(stderr, "usage: png_diff A.png B.png [THRESHOLD [LIMIT]]\n");
        return 2;
    }
    a = stbi_load(argv[1], &wa, &ha, &n, 3);
    b = stbi_load(argv[2], &wb, &hb, &n, 3);
    if (!a || !b || wa != wb || ha != hb) {
        fprintf(stderr, "png_diff: cannot read both, or sizes differ\n");
        return 2;
    }
    for (i = 0; i < (long)wa * ha; ++i) {
        int k, worst = 0;
        for (k = 0; k < 3; ++k) {
            int d = abs(a[3 * i + k] - b[3 * i + k]);
            sum += d;
            if (d > worst) worst = d;
        }
        off += worst > thr;
    }
    printf("png_diff: %.4f of pixels off by more than %d, mean |a - b| %.3f\n",
           (double)off / ((double)wa * ha), thr, sum / (3.0 * wa * ha));
    stbi_image_free(a);
    stbi_image_free(b);
    return (double)off / ((double)wa * ha) < limit ? 0 : 1;
}
