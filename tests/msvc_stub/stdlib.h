/* Declarations only, for the MSVC syntax check. */
#ifndef HF_STUB_STDLIB_H
#define HF_STUB_STDLIB_H
#include <stddef.h>
void *malloc(size_t); void *realloc(void *, size_t); void free(void *);
#endif
