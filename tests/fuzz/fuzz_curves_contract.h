/* fuzz_curves_contract.h - the contract every curve reader of
   examples/curves.h keeps, checked by fuzz_curves.c and fuzz_obj.c
   (abort() on violation): the reader returned 1 or 0; on 0 the curves are
   empty (every array NULL) and the message is not; on 1 there is at least
   one curve, every curve has at least 2 points, the point counts add up
   to the total and every coordinate is finite. Include after curves.h. */
#include <math.h>
#include <stdlib.h>

/* 1 when the read succeeded and the curves hold it, 0 when it failed
   cleanly; aborts otherwise. */
static int fz_curves_contract(int ok, const cv_curves *c, const char *err)
{
    long sum = 0;
    int i;
    if (ok != 0 && ok != 1) abort();
    if (!ok) {
        if (c->count != 0 || c->points || c->xyz || c->rgb || c->thickness ||
            c->transparency || !err[0])
            abort();
        return 0;
    }
    if (c->count < 1 || !c->points || !c->xyz) abort();
    for (i = 0; i < c->count; ++i) {
        if (c->points[i] < 2) abort();
        sum += c->points[i];
    }
    if (sum != c->total) abort();
    for (i = 0; i < 3 * c->total; ++i)
        if (!isfinite(c->xyz[i])) abort();
    return 1;
}
