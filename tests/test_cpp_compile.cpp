// test_cpp_compile.cpp - compiles the whole implementation as C++, with the
// configuration macros a C++ engine is likely to set: static linkage, its own
// allocator and assert. Built by `make test`; running it checks the overrides.
#include <cstdio>
#include <cstdlib>

static int g_allocs = 0;
static void *my_malloc(size_t n, void *) { ++g_allocs; return std::malloc(n); }
static void *my_realloc(void *p, size_t n, void *) { return std::realloc(p, n); }
static void my_free(void *p, void *) { std::free(p); }

#define HAIRFUR_STATIC
#define HF_MALLOC(size, ctx) my_malloc(size, ctx)
#define HF_REALLOC(ptr, size, ctx) my_realloc(ptr, size, ctx)
#define HF_FREE(ptr, ctx) my_free(ptr, ctx)
#define HF_ASSERT(x) ((void)0)
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"
#include "../hairfur.h" // a second include must be harmless

int main()
{
    unsigned char px[4] = {0, 255, 255, 0};
    float out[4];
    (void)my_realloc; // not called by the library yet
    hf_map m = hf_map();
    m.data = px;
    m.width = 2;
    m.height = 2;
    m.channels = 1;
    if (hf_map_blur(&m, 1.0f, out, NULL) != HF_OK || g_allocs != 1) {
        std::printf("C++ build: HF_MALLOC override not used (%d)\n", g_allocs);
        return 1;
    }
    std::printf("C++ compile check: ok (version %s)\n", hf_version_string());
    return 0;
}
