/* bench_time.h - the benchmarks' clock and sort order (bench.c,
   bench_ab.c). Needs _POSIX_C_SOURCE 200809L before the first system
   header, for clock_gettime. */
#ifndef BENCH_TIME_H
#define BENCH_TIME_H

#include <time.h>

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* qsort order of doubles, for medians */
static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#endif
