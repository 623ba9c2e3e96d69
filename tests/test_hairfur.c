/* test_hairfur.c - the unit tests of hairfur.h, one function per behaviour.

   Build and run: make test (C and C++, -O2 and ASan+UBSan, gcc and clang).
   Prints one line per failed check and ends with "N passed, N failed";
   exits non-zero when anything failed. */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- harness ------------------------------------------------------------ */

static int t_passed, t_failed, t_current_failed;
static const char *t_current;

#define CHECK(cond)                                                            \
    do {                                                                       \
        if (!(cond)) {                                                         \
            printf("%s:%d: %s: CHECK(%s) failed\n", __FILE__, __LINE__,        \
                   t_current, #cond);                                          \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

/* |a - b| <= tol, printing both values when it fails */
#define CHECK_NEAR(a, b, tol)                                                  \
    do {                                                                       \
        double t_a_ = (double)(a), t_b_ = (double)(b);                         \
        if (!(fabs(t_a_ - t_b_) <= (double)(tol))) {                           \
            printf("%s:%d: %s: CHECK_NEAR(%s, %s, %s) failed: %.9g vs %.9g\n", \
                   __FILE__, __LINE__, t_current, #a, #b, #tol, t_a_, t_b_);   \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

#define CHECK_EQ_INT(a, b)                                                     \
    do {                                                                       \
        long long t_a_ = (long long)(a), t_b_ = (long long)(b);                \
        if (t_a_ != t_b_) {                                                    \
            printf("%s:%d: %s: CHECK_EQ_INT(%s, %s) failed: %lld vs %lld\n",   \
                   __FILE__, __LINE__, t_current, #a, #b, t_a_, t_b_);         \
            t_current_failed = 1;                                              \
        }                                                                      \
    } while (0)

#define RUN(fn)                                                                \
    do {                                                                       \
        t_current = #fn;                                                       \
        t_current_failed = 0;                                                  \
        fn();                                                                  \
        if (t_current_failed)                                                  \
            ++t_failed;                                                        \
        else                                                                   \
            ++t_passed;                                                        \
    } while (0)

static int t_is_finite(float x) { return x == x && x - x == 0.0f; }

/* A counting allocator: tests prove "no allocation" with it. */
typedef struct t_counter {
    long allocs, frees;
    long fail_after; /* -1: never fail; else fail once allocs reaches it */
} t_counter;

static void *t_alloc(size_t size, void *user)
{
    t_counter *c = (t_counter *)user;
    if (c->fail_after >= 0 && c->allocs >= c->fail_after) return NULL;
    ++c->allocs;
    return malloc(size);
}
static void *t_realloc(void *p, size_t size, void *user)
{
    t_counter *c = (t_counter *)user;
    if (!p) ++c->allocs;
    return realloc(p, size);
}
static void t_free(void *p, void *user)
{
    t_counter *c = (t_counter *)user;
    if (p) ++c->frees;
    free(p);
}
static hf_allocator t_counting(t_counter *c)
{
    hf_allocator a;
    c->allocs = c->frees = 0;
    c->fail_after = -1;
    a.alloc = t_alloc;
    a.realloc = t_realloc;
    a.free = t_free;
    a.user = c;
    return a;
}

