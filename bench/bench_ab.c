/* bench_ab.c - two versions of hairfur.h in one program: `make bench-ab`.

   This machine's speed swings by a quarter between runs (and within
   one), so two builds timed one after the other cannot show a change of
   a few percent. Here both versions run in the same process on the same
   scene (scene L of bench.c: 100,000 strands of 16 points on about 1,000
   guides, or --strands and --points of the user's; each version grows
   its own fur from the same description), call
   by call: for each stage, FRAMES calls of each, the order swapped every
   call, each after a read of 64 MiB of other bytes (as in a frame, the
   stage's output has left the cache; a memset of that size, glibc's
   `rep stosb`, left the cache as it was). ab_side.c is built once with each header
   (every function static), as `base` and `new`.

   Output: a table, then a machine line per stage:
     bench_ab stage=NAME base_ms=... new_ms=... ratio=...
   (medians; ratio = new / base: below 1, the new version is faster). Run
   it with the same header on both sides (make bench-ab BASE=WORKTREE)
   to see the noise of the method itself: on this machine 0.94-1.02 a
   stage in a noisy hour (the method in a test program, ribbons only:
   1.00 in a quiet one).
   --range N runs each stage in calls of N strands (guides for the
   ropes), as an engine's jobs would, so that what a call costs beyond
   its strands shows.
   Usage: bench_ab [--frames N] [--strands N] [--points N] [--range N] */
#define _POSIX_C_SOURCE 200809L
#define HEAD_MESH_IMPLEMENTATION
#include "../examples/head_mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_ab.h"
#include "bench_fur.h"
#include "bench_time.h"


#define EVICT_BYTES ((size_t)64 << 20)
static volatile unsigned g_sink; /* keeps the eviction's reads */

int main(int argc, char **argv)
{
    static const char *names[AB_N] = {"strands", "ribbons", "ribbons16",
                                      "points", "interp_points", "ropes"};
    static unsigned char px[256 * 256];
    const ab_side *side[2] = {&ab_base, &ab_new};
    int frames = 40, strands = BENCH_L_STRANDS, points = BENCH_P, range = 0,
        i, k, f, w;
    void *scene[2];
    double *t[2];
    unsigned char *evict;
    hm_mesh head;
    for (i = 1; i < argc; ++i) {
        if (i + 1 < argc && !strcmp(argv[i], "--frames")) {
            frames = atoi(argv[++i]);
        } else if (i + 1 < argc && !strcmp(argv[i], "--strands")) {
            strands = atoi(argv[++i]);
        } else if (i + 1 < argc && !strcmp(argv[i], "--points")) {
            points = atoi(argv[++i]);
        } else if (i + 1 < argc && !strcmp(argv[i], "--range")) {
            range = atoi(argv[++i]);
        } else {
            int help = !strcmp(argv[i], "--help") || !strcmp(argv[i], "-h");
            if (!help)
                fprintf(stderr, "bench_ab: %s: unknown option or missing "
                                "value\n", argv[i]);
            fprintf(help ? stdout : stderr,
                    "usage: bench_ab [--frames N] [--strands N] "
                    "[--points N] [--range N]\n"
                    "  --frames N    calls of each version per stage "
                    "(default 40, at least 3)\n"
                    "  --strands N   strands of the scene (default "
                    "100000, at least 1)\n"
                    "  --points N    points a strand (default 16, 2 to "
                    "256)\n"
                    "  --range N     strands (guides) a call (default: "
                    "all in one call)\n"
                    "Each stage run by the base and the new hairfur.h "
                    "alternately; medians and new / base.\n");
            return help ? 0 : 2;
        }
    }
    if (frames < 3) frames = 3;
    if (strands < 1) strands = 1;
    if (!hm_sphere(BENCH_L_RINGS, BENCH_L_SEGMENTS, BENCH_HEAD_RADIUS, &head))
        return 1;
    hm_hairline_density(px, 256, 256);
    evict = (unsigned char *)malloc(EVICT_BYTES);
    t[0] = (double *)malloc(sizeof(double) * (size_t)frames);
    t[1] = (double *)malloc(sizeof(double) * (size_t)frames);
    if (!evict || !t[0] || !t[1]) return 1;
    memset(evict, 0x33, EVICT_BYTES);
    for (w = 0; w < 2; ++w)
        if (!(scene[w] = side[w]->make(&head, px, strands, points)))
            return 1;
    printf("bench_ab: base and new hairfur.h, %d strands of %d points, %d "
           "runs of each a stage", strands, points, frames);
    if (range > 0) printf(" in calls of %d strands (guides)", range);
    printf(" (medians, ms)\n");
    printf("  %-14s %9s %9s %9s\n", "stage", "base", "new", "new/base");
    for (k = 0; k < AB_N; ++k) {
        double mb, mn;
        for (f = -3; f < frames; ++f)
            for (i = 0; i < 2; ++i) {
                double t0;
                int r;
                size_t e;
                unsigned sum = 0;
                w = (f & 1) ? 1 - i : i; /* each goes first every other call */
                for (e = 0; e < EVICT_BYTES; e += 64) sum += evict[e];
                g_sink = sum;
                t0 = now_ms();
                r = side[w]->run(scene[w], k, range);
                if (r != 0) {
                    fprintf(stderr, "bench_ab: %s: error %d\n", names[k], r);
                    return 1;
                }
                if (f >= 0) t[w][f] = now_ms() - t0;
            }
        qsort(t[0], (size_t)frames, sizeof(double), cmp_d);
        qsort(t[1], (size_t)frames, sizeof(double), cmp_d);
        mb = t[0][frames / 2];
        mn = t[1][frames / 2];
        printf("  %-14s %9.3f %9.3f %9.3f\n", names[k], mb, mn, mn / mb);
        fprintf(stderr, "bench_ab stage=%s base_ms=%.4f new_ms=%.4f "
                        "ratio=%.4f\n", names[k], mb, mn, mn / mb);
    }
    for (w = 0; w < 2; ++w) side[w]->free_scene(scene[w]);
    free(evict);
    free(t[0]);
    free(t[1]);
    return 0;
}
