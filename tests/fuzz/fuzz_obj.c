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
#include "fuzz_curves_contract.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cv_curves c;
    char err[1024];
    unsigned char *text;
    int ok;
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
    if (!fz_curves_contract(ok, &c, err)) return 0;
    if (c.rgb || c.thickness || c.transparency) abort(); /* none in OBJ */
    cv_free(&c);
    return 0;
}
