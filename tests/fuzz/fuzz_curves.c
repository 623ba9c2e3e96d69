/* fuzz_curves.c - the examples' curve readers (examples/curves.h) on
   fuzz-made files: byte 0 picks the format (even: .hair, odd: TressFX
   .tfx), the rest is the file.

   Contracts checked (abort() on violation): a reader returns 1 or 0; on 0
   the curves are empty (every array NULL) and the message is not; on 1
   there is at least one curve, every curve has at least 2 points, the
   point counts add up to the total, every coordinate is finite, a .hair
   result has colours, thickness and transparency (from the file or the
   header's defaults) and a .tfx result has neither thickness nor
   transparency. The OBJ reader has its own target, fuzz_obj.c.

   libFuzzer: clang -g -O1 -fsanitize=fuzzer,address,undefined fuzz_curves.c
   replay:    gcc -O1 -g fuzz_main.c fuzz_curves.c -lm (see the Makefile) */
#define CURVES_IMPLEMENTATION
#define CURVES_NO_ASSIMP
#include "../../examples/curves.h"
#include "fuzz_curves_contract.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cv_curves c;
    char err[256];
    int ok;
    if (size < 1) return 0;
    err[0] = '\0';
    ok = (data[0] & 1) ? cv_parse_tfx(data + 1, size - 1, &c, err, sizeof err)
                       : cv_parse_hair(data + 1, size - 1, &c, err, sizeof err);
    if (!fz_curves_contract(ok, &c, err)) return 0;
    if ((data[0] & 1) ? (c.thickness || c.transparency)
                      : (!c.rgb || !c.thickness || !c.transparency))
        abort();
    cv_free(&c);
    return 0;
}
