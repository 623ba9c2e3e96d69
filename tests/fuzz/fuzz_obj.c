/* fuzz_obj.c - the examples' OBJ polyline reader (examples/curves.h,
   cv_parse_obj: assimp's OBJ importer from memory, then the line
   primitives chained into polylines) on fuzz-made OBJ text.

   Contracts checked (abort() on violation): the reader returns 1 or 0; on
   0 the curves are empty and the message is not; on 1 there is at least
   one curve, every curve has at least 2 points, the point counts add up to
   the total, every coordinate is finite and no per-point attribute is set.

   `mtllib` lines are blanked before the text reaches assimp, which would
   otherwise open whatever file they name.

   libFuzzer: clang -g -O1 -fsanitize=fuzzer,address,undefined fuzz_obj.c
              -lassimp
   replay:    gcc -O1 -g fuzz_main.c fuzz_obj.c -lassimp -lm (see the
              Makefile) */
#define CURVES_IMPLEMENTATION
#include "../../examples/curves.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cv_curves c;
    char err[1024];
    unsigned char *text;
    int ok, i;
    long sum = 0;
    size_t k;
    if (size < 1) return 0;
    text = (unsigned char *)malloc(size);
    if (!text) abort();
    memcpy(text, data, size);
    for (k = 0; k + 6 <= size; ++k)
        if (!memcmp(text + k, "mtllib", 6)) text[k] = '#';
    err[0] = '\0';
    ok = cv_parse_obj(text, size, &c, err, sizeof err);
    free(text);
    if (ok != 0 && ok != 1) abort();
    if (!ok) {
        if (c.count != 0 || c.points || c.xyz || c.rgb || c.thickness ||
            c.transparency || !err[0])
            abort();
        return 0;
    }
    if (c.count < 1 || !c.points || !c.xyz || c.rgb || c.thickness ||
        c.transparency)
        abort();
    for (i = 0; i < c.count; ++i) {
        if (c.points[i] < 2) abort();
        sum += c.points[i];
    }
    if (sum != c.total) abort();
    for (i = 0; i < 3 * c.total; ++i)
        if (!isfinite(c.xyz[i])) abort();
    cv_free(&c);
    return 0;
}
