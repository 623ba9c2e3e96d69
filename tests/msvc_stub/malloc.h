/* Declarations only, for the MSVC syntax check (clang's mm_malloc.h). */
#ifndef HF_STUB_MALLOC_H
#define HF_STUB_MALLOC_H
#include <stddef.h>
void *_aligned_malloc(size_t, size_t); void _aligned_free(void *);
#endif
