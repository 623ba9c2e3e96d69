/* fuzz_impl.c - hairfur.h's implementation for the fuzz targets of the
   library that use its API alone (fuzz_grow, fuzz_ribbons, fuzz_lut,
   fuzz_fur), which include the header for its declarations: the Makefile
   compiles this once and links it into each. */
#define HAIRFUR_IMPLEMENTATION
#include "../../hairfur.h"
