/* hairfur.h - v0.1.0 - real-time hair and fur for game engines, on the CPU
   Public domain or MIT, your choice: see the end of this file and LICENSE.

   hairfur.h turns a triangle mesh and a few UV maps (density, length, colour)
   into hair or fur geometry every frame, and leaves drawing to the host engine.
   It has no dependencies beyond the C standard library.

   DO THIS ONCE

       In exactly one C or C++ file of your program:

           #define HAIRFUR_IMPLEMENTATION
           #include "hairfur.h"

       Everywhere else, include "hairfur.h" without the define.

   QUICK START (the building blocks so far)

       hf_mesh mesh = {0};
       mesh.positions = my_vertex_buffer;          // float x, y, z
       mesh.position_stride = sizeof(my_vertex);   // 0 = packed floats
       mesh.uvs = &my_vertex_buffer[0].u;           // optional
       mesh.uv_stride = sizeof(my_vertex);
       mesh.vertex_count = n_vertices;
       mesh.indices = my_indices;                   // 3 uint32 per triangle
       mesh.triangle_count = n_triangles;

       hf_diag diag;
       hf_result r = hf_mesh_validate(&mesh, &diag);
       if (r != HF_OK) printf("bad mesh: %s\n", diag.message);

       float *normals = malloc(12 * n_vertices);
       hf_mesh_compute_normals(&mesh, normals);     // area-weighted

       hf_map density = {0};
       density.data = pixels; density.width = 256; density.height = 256;
       density.channels = 1;                        // 8-bit unorm by default
       float d[4];
       hf_map_sample(&density, 0.25f, 0.5f, d);     // bilinear, d[0] in [0, 1]

   CONFIGURATION MACROS (define before the #include that has
   HAIRFUR_IMPLEMENTATION, unless marked "everywhere")

       HAIRFUR_STATIC       everywhere: make every function static (private
                            copy per translation unit).
       HFDEF                everywhere: the linkage of every public function,
                            if HAIRFUR_STATIC is not enough (e.g. dllexport).
       HF_MALLOC(size, ctx), HF_REALLOC(ptr, size, ctx), HF_FREE(ptr, ctx)
                            all three or none: the default allocator; ctx is
                            the user pointer of the hf_allocator in use (NULL
                            when none is given). Every function that allocates
                            also takes an optional runtime hf_allocator.
       HF_ASSERT(x)         the library's own invariants (default: assert).
                            Never used on caller input: that gets a result.
       HF_SQRTF, HF_SQRT, HF_EXP, HF_SIN, HF_COS, HF_ASIN, HF_ACOS, HF_FABS,
       HF_FLOORF, HF_CBRT, HF_MEMCPY, HF_MEMSET
                            replace the libm / libc functions used.

   CONVENTIONS

       - Every function that can fail returns hf_result: HF_OK (0) or a
         negative code; hf_result_string() gives a message. On failure no
         output has been written.
       - Counts are int; negative or zero counts where one is needed are
         refused. Byte strides of 0 mean "packed".
       - Every stochastic stage takes a seed and uses hf_rng (PCG32): no
         rand(), no global state. Same inputs and seed, same bytes.
       - No function keeps state between calls; the per-frame functions take
         a (first, count) range and never allocate, so an engine can spread a
         frame over its own threads.

   SECTIONS (in the order the data flows)

       1. configuration, result codes, version
       2. random numbers (hf_rng)
       3. maps (hf_map): validation, bilinear sampling, Gaussian blur
       4. meshes (hf_mesh): validation, normals, triangle area

   VERSION HISTORY

       0.1.0 (2026-11-22)  foundation: result codes, rng, mesh and map views.
*/

#ifndef HAIRFUR_H
#define HAIRFUR_H

#include <stddef.h>
#include <stdint.h>

#define HAIRFUR_VERSION_MAJOR 0
#define HAIRFUR_VERSION_MINOR 1
#define HAIRFUR_VERSION_PATCH 0
#define HAIRFUR_VERSION_STRING "0.1.0"
/* major * 10000 + minor * 100 + patch, comparable with hf_version(). */
#define HAIRFUR_VERSION_NUMBER                                                 \
    (HAIRFUR_VERSION_MAJOR * 10000 + HAIRFUR_VERSION_MINOR * 100 +            \
     HAIRFUR_VERSION_PATCH)

#ifndef HFDEF
#ifdef HAIRFUR_STATIC
#if defined(__GNUC__) || defined(__clang__)
#define HFDEF static __attribute__((unused)) /* idle functions: no warning */
#else
#define HFDEF static
#endif
#else
#define HFDEF extern
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 1. Configuration, result codes, version                                  */
/* ======================================================================== */

/* Every result code with its message, in one table. 0 is success; errors are
   negative so that `if (r < 0)` also works. */
#define HF_RESULT_TABLE(X)                                                     \
    X(HF_OK, 0, "success")                                                     \
    X(HF_ERROR_NULL_POINTER, -1, "a required pointer is NULL")                \
    X(HF_ERROR_BAD_COUNT, -2,                                                  \
      "a count or size is zero, negative, or larger than supported")          \
    X(HF_ERROR_BAD_STRIDE, -3,                                                 \
      "a byte stride is smaller than the element it steps over, or negative") \
    X(HF_ERROR_INDEX_OUT_OF_RANGE, -4,                                         \
      "an index is not less than the count of the array it indexes")          \
    X(HF_ERROR_NON_FINITE, -5, "an input value is NaN or infinite")           \
    X(HF_ERROR_BAD_FORMAT, -6,                                                 \
      "unsupported map format or channel count (1 to 4 channels, u8 or f32)") \
    X(HF_ERROR_BAD_PARAMETER, -7,                                              \
      "a parameter lies outside its documented range")                        \
    X(HF_ERROR_DEGENERATE, -8,                                                 \
      "a triangle has zero area or a direction has zero length")              \
    X(HF_ERROR_OVERFLOW, -9, "a size computation would overflow")             \
    X(HF_ERROR_OUT_OF_MEMORY, -10, "the allocator returned NULL")             \
    X(HF_ERROR_BUFFER_TOO_SMALL, -11,                                          \
      "an output buffer is smaller than the size the call requires")          \
    X(HF_ERROR_BAD_RANGE, -12,                                                 \
      "a (first, count) range lies outside the array it selects from")        \
    X(HF_ERROR_BAD_TIME_STEP, -13,                                             \
      "the time step is zero, negative, NaN or infinite")                     \
    X(HF_ERROR_DEPTH_CAP, -14,                                                 \
      "tessellation reached its depth cap before every triangle was small "    \
      "enough")                                                                \
    X(HF_ERROR_TRIANGLE_CAP, -15,                                              \
      "tessellation would exceed its triangle cap")

typedef enum hf_result {
#define HF__RESULT_ENUM(name, value, message) name = value,
    HF_RESULT_TABLE(HF__RESULT_ENUM)
#undef HF__RESULT_ENUM
    HF_RESULT_FORCE_INT32 = 0x7fffffff
} hf_result;

/* A static, never-NULL message for a result code ("unknown result code" for
   a value that is not in the table). */
HFDEF const char *hf_result_string(hf_result result);

/* Optional detail on a failure: which field and which element. Validation
   functions take a `hf_diag *` that may be NULL. On success diag->result is
   HF_OK and message is empty. */
typedef struct hf_diag {
    hf_result result;
    const char *field; /* static string naming the input, e.g. "indices" */
    long long index;   /* element index within it, or -1 */
    char message[192]; /* e.g. "indices[7] = 12 is not less than ..." */
} hf_diag;

/* Runtime allocator. A NULL `hf_allocator *` anywhere means the compile-time
   default (HF_MALLOC / HF_REALLOC / HF_FREE, which default to the C library).
   `user` is passed back to each callback. */
typedef struct hf_allocator {
    void *(*alloc)(size_t size, void *user);
    void *(*realloc)(void *ptr, size_t size, void *user);
    void (*free)(void *ptr, void *user);
    void *user;
} hf_allocator;

/* HAIRFUR_VERSION_NUMBER of the compiled implementation, and its string. */
HFDEF int hf_version(void);
HFDEF const char *hf_version_string(void);

/* ======================================================================== */
/* 2. Random numbers                                                        */
/* ======================================================================== */

/* PCG32 (O'Neill, pcg-random.org): 64-bit state, 32-bit output, period 2^64,
   independent streams. Plain value type: copy it to fork a sequence. */
typedef struct hf_rng {
    uint64_t state;
    uint64_t inc;
} hf_rng;

/* Seed a generator. Different `stream` values give independent sequences
   for the same seed. */
HFDEF void hf_rng_seed(hf_rng *rng, uint64_t seed, uint64_t stream);
/* The next 32 random bits. */
HFDEF uint32_t hf_rng_u32(hf_rng *rng);
/* Uniform in [0, 1): 24 random bits, so every value is exact in float. */
HFDEF float hf_rng_float(hf_rng *rng);
/* Uniform integer in [0, bound), without modulo bias; 0 when bound is 0. */
HFDEF uint32_t hf_rng_below(hf_rng *rng, uint32_t bound);

/* ======================================================================== */
/* 3. Maps                                                                  */
/* ======================================================================== */

typedef enum hf_map_format {
    HF_MAP_U8 = 0, /* 8-bit unorm: 0..255 reads as 0..1 (the default) */
    HF_MAP_F32 = 1 /* 32-bit float, read as is */
} hf_map_format;

typedef enum hf_map_wrap {
    HF_WRAP_REPEAT = 0, /* u and v wrap around (the default) */
    HF_WRAP_CLAMP = 1   /* u and v clamp to the edge texels */
} hf_map_wrap;

/* A view of an image the caller owns: nothing is copied. Enum-valued fields
   are plain ints so that any value a caller stores is defined behaviour and
   gets a result code, in C and C++ alike. Texel (x, y) starts
   at byte y * row_stride + x * channels * element_size of `data`; row 0 is
   v = 0. Texel centres sit at ((x + 0.5) / width, (y + 0.5) / height). */
typedef struct hf_map {
    const void *data;
    int width, height;
    int channels;         /* 1 to 4 */
    int format;           /* hf_map_format; 0 = HF_MAP_U8 */
    int row_stride;       /* bytes between rows; 0 = width*channels*size */
    int wrap;             /* hf_map_wrap; 0 = HF_WRAP_REPEAT */
} hf_map;

/* Check a map view: data not NULL, width and height >= 1 and at most
   HF_MAP_MAX_DIMENSION, 1 to 4 channels, a known format, a row stride at
   least one packed row, no size overflow, and (for HF_MAP_F32) every value
   finite. Returns HF_OK or the code of the first problem found; `diag` (may
   be NULL) names it. */
#define HF_MAP_MAX_DIMENSION 65536
HFDEF hf_result hf_map_validate(const hf_map *map, hf_diag *diag);

/* Bilinear sample at (u, v) with the map's wrap mode. Writes `channels`
   floats to out (8-bit maps give 0..1) and sets the remaining ones of
   out[0..3] to 0. Errors: NULL pointers, an invalid map (as validate), a
   non-finite u or v; out is untouched then. For hot loops, validate once
   and use hf_map_sample_fast. */
HFDEF hf_result hf_map_sample(const hf_map *map, float u, float v,
                              float out[4]);
/* The same sample without any check: the map must have passed
   hf_map_validate, and u, v must be finite. */
HFDEF void hf_map_sample_fast(const hf_map *map, float u, float v,
                              float out[4]);

/* Separable Gaussian blur (the plugin blurred density maps before use).
   Writes width * height * channels floats to `out`, packed rows, the same
   layout as an HF_MAP_F32 map with row_stride 0; edges follow the map's
   wrap mode. The kernel has standard deviation `sigma` texels and radius
   ceil(3 sigma), capped at the map size. sigma == 0 copies (as floats).
   Uses one temporary buffer of max(width, height) * channels floats from
   `alloc` (NULL = default). Errors: as hf_map_validate, NULL out,
   HF_ERROR_BAD_PARAMETER for sigma < 0 or non-finite or above 1024,
   HF_ERROR_OUT_OF_MEMORY; out is untouched on any error. */
HFDEF hf_result hf_map_blur(const hf_map *map, float sigma, float *out,
                            const hf_allocator *alloc);

/* ======================================================================== */
/* 4. Meshes                                                                */
/* ======================================================================== */

/* A view of a triangle mesh the caller owns: nothing is copied. Strides are
   in bytes (0 = packed), so an interleaved engine vertex buffer is passed by
   pointing each attribute at its first element with the vertex size as the
   stride. */
typedef struct hf_mesh {
    const float *positions; /* x, y, z per vertex (required) */
    int position_stride;    /* 0 = 12 */
    const float *normals;   /* x, y, z per vertex, or NULL: computed */
    int normal_stride;      /* 0 = 12 */
    const float *uvs;       /* u, v per vertex, or NULL: maps unusable */
    int uv_stride;          /* 0 = 8 */
    int vertex_count;
    const uint32_t *indices; /* 3 per triangle, packed (required) */
    int triangle_count;
} hf_mesh;

/* Check a mesh view: positions and indices not NULL, vertex and triangle
   counts >= 1, strides 0 or at least the element size (and positive), every
   index < vertex_count, every position, normal and UV finite, every given
   normal of non-zero length, and no byte offset that overflows. Zero-area
   triangles are allowed here (they grow nothing); the stages that need area
   say so. Returns HF_OK or the first problem; `diag` (may be NULL) names it:
   field and element. */
HFDEF hf_result hf_mesh_validate(const hf_mesh *mesh, hf_diag *diag);

/* Area-weighted vertex normals: each vertex gets the normalised sum of the
   unnormalised face normals (cross products) of its triangles, which weighs
   each face by its area. A vertex whose sum is zero (unused, or only in
   zero-area triangles) gets (0, 0, 1). Writes 3 * vertex_count floats to
   out_normals (packed). The mesh's own normals, if any, are ignored. Errors:
   as hf_mesh_validate, NULL out_normals; out untouched then. */
HFDEF hf_result hf_mesh_compute_normals(const hf_mesh *mesh,
                                        float *out_normals);

/* Area of the triangle (a, b, c): half the length of the cross product. */
HFDEF float hf_triangle_area(const float a[3], const float b[3],
                             const float c[3]);

#ifdef __cplusplus
}
#endif

#endif /* HAIRFUR_H */

/* ======================================================================== */
/*                            IMPLEMENTATION                                */
/* ======================================================================== */

#if defined(HAIRFUR_IMPLEMENTATION) && !defined(HAIRFUR_IMPLEMENTATION_DONE)
#define HAIRFUR_IMPLEMENTATION_DONE

#include <math.h>
#include <stdarg.h> /* diagnostics */
#include <stdio.h>  /* vsnprintf for diagnostics */
#include <string.h> /* memcpy, memset */

#if defined(HF_MALLOC) && defined(HF_REALLOC) && defined(HF_FREE)
/* all three given */
#elif !defined(HF_MALLOC) && !defined(HF_REALLOC) && !defined(HF_FREE)
#include <stdlib.h>
#define HF_MALLOC(size, ctx) ((void)(ctx), malloc(size))
#define HF_REALLOC(ptr, size, ctx) ((void)(ctx), realloc(ptr, size))
#define HF_FREE(ptr, ctx) ((void)(ctx), free(ptr))
#else
#error "hairfur.h: define all of HF_MALLOC, HF_REALLOC and HF_FREE, or none"
#endif

#ifndef HF_ASSERT
#include <assert.h>
#define HF_ASSERT(x) assert(x)
#endif

#ifndef HF_SQRTF
#define HF_SQRTF(x) sqrtf(x)
#endif
#ifndef HF_SQRT
#define HF_SQRT(x) sqrt(x)
#endif
#ifndef HF_EXP
#define HF_EXP(x) exp(x)
#endif
#ifndef HF_SIN
#define HF_SIN(x) sin(x)
#endif
#ifndef HF_COS
#define HF_COS(x) cos(x)
#endif
#ifndef HF_ASIN
#define HF_ASIN(x) asin(x)
#endif
#ifndef HF_ACOS
#define HF_ACOS(x) acos(x)
#endif
#ifndef HF_FABS
#define HF_FABS(x) fabs(x)
#endif
#ifndef HF_FLOORF
#define HF_FLOORF(x) floorf(x)
#endif
#ifndef HF_CBRT
#define HF_CBRT(x) cbrt(x)
#endif
#ifndef HF_MEMCPY
#define HF_MEMCPY(d, s, n) memcpy(d, s, n)
#endif
#ifndef HF_MEMSET
#define HF_MEMSET(d, v, n) memset(d, v, n)
#endif

#if defined(__GNUC__) || defined(__clang__)
#define HF__UNUSED __attribute__((unused))
#define HF__PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define HF__UNUSED
#define HF__PRINTF(f, a)
#endif
/* Internal helpers are static and may sit idle in a given build. */
#define HF__PRIVATE static HF__UNUSED

#ifdef __cplusplus
extern "C" {
#endif

/* ---- 1. configuration, result codes, version ---------------------------- */

HFDEF const char *hf_result_string(hf_result result)
{
    switch (result) {
#define HF__RESULT_CASE(name, value, message)                                  \
    case name:                                                                 \
        return message;
        HF_RESULT_TABLE(HF__RESULT_CASE)
#undef HF__RESULT_CASE
    default:
        return "unknown result code";
    }
}

HFDEF int hf_version(void) { return HAIRFUR_VERSION_NUMBER; }
HFDEF const char *hf_version_string(void) { return HAIRFUR_VERSION_STRING; }

/* Fill diag (if any) and return the code, so a check reads
   `return hf__fail(diag, CODE, "field", i, "fmt", ...)`. */
HF__PRIVATE hf_result hf__fail(hf_diag *diag, hf_result code,
                               const char *field, long long index,
                               const char *fmt, ...) HF__PRINTF(5, 6);
HF__PRIVATE hf_result hf__fail(hf_diag *diag, hf_result code,
                               const char *field, long long index,
                               const char *fmt, ...)
{
    if (diag) {
        va_list ap;
        diag->result = code;
        diag->field = field;
        diag->index = index;
        va_start(ap, fmt);
        vsnprintf(diag->message, sizeof diag->message, fmt, ap);
        va_end(ap);
    }
    return code;
}

HF__PRIVATE void hf__ok(hf_diag *diag)
{
    if (diag) {
        diag->result = HF_OK;
        diag->field = "";
        diag->index = -1;
        diag->message[0] = 0;
    }
}

/* Finite test on the bits, so it survives -ffast-math. */
HF__PRIVATE int hf__finitef(float x)
{
    uint32_t u;
    HF_MEMCPY(&u, &x, sizeof u);
    return (u & 0x7f800000u) != 0x7f800000u;
}

HF__PRIVATE void *hf__alloc(const hf_allocator *a, size_t size)
{
    if (a && a->alloc) return a->alloc(size, a->user);
    return HF_MALLOC(size, a ? a->user : NULL);
}

HF__PRIVATE void hf__free(const hf_allocator *a, void *ptr)
{
    if (!ptr) return;
    if (a && a->free) {
        a->free(ptr, a->user);
        return;
    }
    HF_FREE(ptr, a ? a->user : NULL);
}

/* a * b without wrap-around: returns 0 and leaves *out alone on overflow. */
HF__PRIVATE int hf__mul_size(size_t a, size_t b, size_t *out)
{
    if (a != 0 && b > (size_t)-1 / a) return 0;
    *out = a * b;
    return 1;
}

/* ---- small vector helpers ----------------------------------------------- */

HF__PRIVATE void hf__sub3(float *o, const float *a, const float *b)
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}

HF__PRIVATE void hf__cross3(float *o, const float *a, const float *b)
{
    float x = a[1] * b[2] - a[2] * b[1];
    float y = a[2] * b[0] - a[0] * b[2];
    float z = a[0] * b[1] - a[1] * b[0];
    o[0] = x;
    o[1] = y;
    o[2] = z;
}

HF__PRIVATE float hf__dot3(const float *a, const float *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* ---- 2. random numbers -------------------------------------------------- */

HFDEF uint32_t hf_rng_u32(hf_rng *rng)
{
    uint64_t old = rng->state;
    uint32_t xorshifted, rot;
    rng->state = old * 6364136223846793005ULL + rng->inc;
    xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

HFDEF void hf_rng_seed(hf_rng *rng, uint64_t seed, uint64_t stream)
{
    rng->state = 0u;
    rng->inc = (stream << 1u) | 1u;
    hf_rng_u32(rng);
    rng->state += seed;
    hf_rng_u32(rng);
}

HFDEF float hf_rng_float(hf_rng *rng)
{
    return (float)(hf_rng_u32(rng) >> 8) * (1.0f / 16777216.0f);
}

HFDEF uint32_t hf_rng_below(hf_rng *rng, uint32_t bound)
{
    /* Lemire's multiply-and-reject: unbiased, one multiply in the common
       case. */
    uint64_t m;
    uint32_t low, threshold;
    if (bound == 0) return 0;
    m = (uint64_t)hf_rng_u32(rng) * bound;
    low = (uint32_t)m;
    if (low < bound) {
        threshold = (0u - bound) % bound;
        while (low < threshold) {
            m = (uint64_t)hf_rng_u32(rng) * bound;
            low = (uint32_t)m;
        }
    }
    return (uint32_t)(m >> 32);
}

/* ---- 3. maps ------------------------------------------------------------ */

HF__PRIVATE int hf__map_elem_size(int f)
{
    return f == HF_MAP_F32 ? 4 : 1;
}

HF__PRIVATE size_t hf__map_row_stride(const hf_map *m)
{
    return m->row_stride
               ? (size_t)m->row_stride
               : (size_t)m->width * (size_t)m->channels *
                     (size_t)hf__map_elem_size(m->format);
}

HFDEF hf_result hf_map_validate(const hf_map *map, hf_diag *diag)
{
    size_t packed_row, total;
    if (!map)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "map", -1,
                        "map is NULL");
    if (!map->data)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "data", -1,
                        "map.data is NULL");
    if (map->width < 1 || map->height < 1 ||
        map->width > HF_MAP_MAX_DIMENSION ||
        map->height > HF_MAP_MAX_DIMENSION)
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "width", -1,
                        "map size %d x %d is outside 1..%d", map->width,
                        map->height, HF_MAP_MAX_DIMENSION);
    if (map->format != HF_MAP_U8 && map->format != HF_MAP_F32)
        return hf__fail(diag, HF_ERROR_BAD_FORMAT, "format", -1,
                        "map.format %d is neither HF_MAP_U8 nor HF_MAP_F32",
                        (int)map->format);
    if (map->channels < 1 || map->channels > 4)
        return hf__fail(diag, HF_ERROR_BAD_FORMAT, "channels", -1,
                        "map.channels %d is outside 1..4", map->channels);
    if (map->wrap != HF_WRAP_REPEAT && map->wrap != HF_WRAP_CLAMP)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "wrap", -1,
                        "map.wrap %d is neither HF_WRAP_REPEAT nor "
                        "HF_WRAP_CLAMP",
                        (int)map->wrap);
    /* width <= 65536 and channels * size <= 16, so this cannot overflow */
    packed_row = (size_t)map->width * (size_t)map->channels *
                 (size_t)hf__map_elem_size(map->format);
    if (map->row_stride < 0 ||
        (map->row_stride != 0 && (size_t)map->row_stride < packed_row))
        return hf__fail(diag, HF_ERROR_BAD_STRIDE, "row_stride", -1,
                        "map.row_stride %d is below one packed row (%zu "
                        "bytes)",
                        map->row_stride, packed_row);
    if (!hf__mul_size(hf__map_row_stride(map), (size_t)map->height, &total))
        return hf__fail(diag, HF_ERROR_OVERFLOW, "row_stride", -1,
                        "map.row_stride * height overflows size_t");
    if (map->format == HF_MAP_F32) {
        int x, y, c;
        size_t stride = hf__map_row_stride(map);
        for (y = 0; y < map->height; ++y) {
            const float *row =
                (const float *)((const unsigned char *)map->data +
                                (size_t)y * stride);
            for (x = 0; x < map->width; ++x)
                for (c = 0; c < map->channels; ++c)
                    if (!hf__finitef(row[x * map->channels + c]))
                        return hf__fail(
                            diag, HF_ERROR_NON_FINITE, "data",
                            (long long)y * map->width + x,
                            "map texel (%d, %d) channel %d is not finite", x,
                            y, c);
        }
    }
    hf__ok(diag);
    return HF_OK;
}

/* Texel coordinate i of an axis of n texels, with the map's wrap. */
HF__PRIVATE int hf__wrap_index(int i, int n, int wrap)
{
    if (wrap == HF_WRAP_CLAMP) return i < 0 ? 0 : (i >= n ? n - 1 : i);
    i %= n;
    return i < 0 ? i + n : i;
}

HF__PRIVATE void hf__map_texel(const hf_map *m, int x, int y, float *out)
{
    const unsigned char *row =
        (const unsigned char *)m->data + (size_t)y * hf__map_row_stride(m);
    int c;
    if (m->format == HF_MAP_F32) {
        const float *p = (const float *)row + (size_t)x * (size_t)m->channels;
        for (c = 0; c < m->channels; ++c) out[c] = p[c];
    } else {
        const unsigned char *p = row + (size_t)x * (size_t)m->channels;
        for (c = 0; c < m->channels; ++c) out[c] = (float)p[c] / 255.0f;
    }
}

/* Map a finite coordinate to a texel index and fraction. Far-out
   coordinates are reduced first so the float-to-int conversion cannot
   overflow (repeat: modulo one period; clamp: pinned to the edge). */
HF__PRIVATE void hf__axis(float t, int n, int wrap, int *i0, int *i1,
                          float *f)
{
    float x, fl;
    if (wrap == HF_WRAP_REPEAT)
        t -= HF_FLOORF(t);
    else
        t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    x = t * (float)n - 0.5f;
    fl = HF_FLOORF(x);
    *f = x - fl;
    *i0 = hf__wrap_index((int)fl, n, wrap);
    *i1 = hf__wrap_index((int)fl + 1, n, wrap);
}

HFDEF void hf_map_sample_fast(const hf_map *map, float u, float v,
                              float out[4])
{
    int x0, x1, y0, y1, c;
    float fx, fy, a[4], b[4], d[4], e[4];
    hf__axis(u, map->width, map->wrap, &x0, &x1, &fx);
    hf__axis(v, map->height, map->wrap, &y0, &y1, &fy);
    hf__map_texel(map, x0, y0, a);
    hf__map_texel(map, x1, y0, b);
    hf__map_texel(map, x0, y1, d);
    hf__map_texel(map, x1, y1, e);
    for (c = 0; c < 4; ++c) {
        if (c < map->channels) {
            float top = a[c] + (b[c] - a[c]) * fx;
            float bot = d[c] + (e[c] - d[c]) * fx;
            out[c] = top + (bot - top) * fy;
        } else {
            out[c] = 0.0f;
        }
    }
}

HFDEF hf_result hf_map_sample(const hf_map *map, float u, float v,
                              float out[4])
{
    hf_result r;
    if (!out) return HF_ERROR_NULL_POINTER;
    r = hf_map_validate(map, NULL);
    if (r != HF_OK) return r;
    if (!hf__finitef(u) || !hf__finitef(v)) return HF_ERROR_NON_FINITE;
    hf_map_sample_fast(map, u, v, out);
    return HF_OK;
}

/* One 1D Gaussian pass over `n` samples of `channels` floats spaced `step`
   floats apart in `data`, through `tmp` (n * channels floats). */
HF__PRIVATE void hf__blur_line(float *data, size_t step, int n, int channels,
                               const float *kernel, int radius,
                               int wrap, float *tmp)
{
    int i, k, c;
    for (i = 0; i < n; ++i)
        for (c = 0; c < channels; ++c)
            tmp[i * channels + c] = data[(size_t)i * step + (size_t)c];
    for (i = 0; i < n; ++i)
        for (c = 0; c < channels; ++c) {
            float s = 0.0f;
            for (k = -radius; k <= radius; ++k)
                s += kernel[k + radius] *
                     tmp[hf__wrap_index(i + k, n, wrap) * channels + c];
            data[(size_t)i * step + (size_t)c] = s;
        }
}

HFDEF hf_result hf_map_blur(const hf_map *map, float sigma, float *out,
                            const hf_allocator *alloc)
{
    enum { HF__MAX_RADIUS = 3072 };
    float kernel[2 * HF__MAX_RADIUS + 1];
    float *tmp, sum = 0.0f;
    int radius, k, x, y, w, h, ch, longest;
    size_t row;
    hf_result r;
    if (!out) return HF_ERROR_NULL_POINTER;
    r = hf_map_validate(map, NULL);
    if (r != HF_OK) return r;
    if (!hf__finitef(sigma) || sigma < 0.0f || sigma > 1024.0f)
        return HF_ERROR_BAD_PARAMETER;
    w = map->width;
    h = map->height;
    ch = map->channels;
    longest = w > h ? w : h;
    radius = (int)(3.0f * sigma + 0.999f);
    if (radius > longest) radius = longest;
    if (sigma == 0.0f) radius = 0;
    tmp = (float *)hf__alloc(alloc, (size_t)longest * (size_t)ch *
                                        sizeof(float));
    if (!tmp) return HF_ERROR_OUT_OF_MEMORY;

    for (k = -radius; k <= radius; ++k) {
        float g = radius ? (float)HF_EXP(-(double)k * k /
                                         (2.0 * (double)sigma * sigma))
                         : 1.0f;
        kernel[k + radius] = g;
        sum += g;
    }
    for (k = 0; k <= 2 * radius; ++k) kernel[k] /= sum;

    row = (size_t)w * (size_t)ch;
    for (y = 0; y < h; ++y) {
        float texel[4];
        for (x = 0; x < w; ++x) {
            hf__map_texel(map, x, y, texel);
            HF_MEMCPY(out + (size_t)y * row + (size_t)x * ch, texel,
                      sizeof(float) * (size_t)ch);
        }
        hf__blur_line(out + (size_t)y * row, (size_t)ch, w, ch, kernel,
                      radius, map->wrap, tmp);
    }
    for (x = 0; x < w; ++x)
        hf__blur_line(out + (size_t)x * ch, row, h, ch, kernel, radius,
                      map->wrap, tmp);
    hf__free(alloc, tmp);
    return HF_OK;
}

/* ---- 4. meshes ---------------------------------------------------------- */

/* Strided attribute access; strides were validated. */
HF__PRIVATE const float *hf__attr(const float *base, int stride, int packed,
                                  int i)
{
    return (const float *)((const unsigned char *)base +
                           (size_t)i * (size_t)(stride ? stride : packed));
}

HF__PRIVATE const float *hf__mesh_pos(const hf_mesh *m, int i)
{
    return hf__attr(m->positions, m->position_stride, 12, i);
}

HF__PRIVATE hf_result hf__check_stride(hf_diag *diag, const char *field,
                                       int stride, int size)
{
    if (stride != 0 && stride < size)
        return hf__fail(diag, HF_ERROR_BAD_STRIDE, field, -1,
                        "%s %d is below the element size %d (and not 0 for "
                        "packed)",
                        field, stride, size);
    return HF_OK;
}

/* Every float of an optional attribute finite, and (for normals) not zero
   length. */
HF__PRIVATE hf_result hf__check_attr(hf_diag *diag, const char *field,
                                     const float *base, int stride,
                                     int packed, int n, int dims,
                                     int need_length)
{
    int i, d;
    for (i = 0; i < n; ++i) {
        const float *p = hf__attr(base, stride, packed, i);
        for (d = 0; d < dims; ++d)
            if (!hf__finitef(p[d]))
                return hf__fail(diag, HF_ERROR_NON_FINITE, field, i,
                                "%s[%d] component %d is NaN or infinite",
                                field, i, d);
        if (need_length && hf__dot3(p, p) == 0.0f)
            return hf__fail(diag, HF_ERROR_DEGENERATE, field, i,
                            "%s[%d] has zero length", field, i);
    }
    return HF_OK;
}

HFDEF hf_result hf_mesh_validate(const hf_mesh *mesh, hf_diag *diag)
{
    hf_result r;
    size_t n_index, dummy;
    int t;
    if (!mesh)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "mesh", -1,
                        "mesh is NULL");
    if (mesh->vertex_count < 1)
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "vertex_count", -1,
                        "mesh.vertex_count %d is below 1",
                        mesh->vertex_count);
    if (mesh->triangle_count < 1)
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "triangle_count", -1,
                        "mesh.triangle_count %d is below 1",
                        mesh->triangle_count);
    if (!mesh->positions)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "positions", -1,
                        "mesh.positions is NULL with %d vertices",
                        mesh->vertex_count);
    if (!mesh->indices)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "indices", -1,
                        "mesh.indices is NULL with %d triangles",
                        mesh->triangle_count);
    if ((r = hf__check_stride(diag, "position_stride", mesh->position_stride,
                              12)) != HF_OK ||
        (r = hf__check_stride(diag, "normal_stride", mesh->normal_stride,
                              12)) != HF_OK ||
        (r = hf__check_stride(diag, "uv_stride", mesh->uv_stride, 8)) !=
            HF_OK)
        return r;
    /* the last byte addressed must fit in size_t (32-bit hosts) */
    if (!hf__mul_size((size_t)mesh->vertex_count,
                      (size_t)(mesh->position_stride > 12
                                   ? mesh->position_stride
                                   : 12),
                      &dummy) ||
        !hf__mul_size((size_t)mesh->triangle_count, 3u * sizeof(uint32_t),
                      &n_index))
        return hf__fail(diag, HF_ERROR_OVERFLOW, "vertex_count", -1,
                        "mesh byte size overflows size_t");
    for (t = 0; t < mesh->triangle_count; ++t) {
        int k;
        for (k = 0; k < 3; ++k) {
            uint32_t v = mesh->indices[3 * (size_t)t + (size_t)k];
            if (v >= (uint32_t)mesh->vertex_count)
                return hf__fail(diag, HF_ERROR_INDEX_OUT_OF_RANGE, "indices",
                                3LL * t + k,
                                "indices[%lld] = %u is not less than "
                                "vertex_count %d",
                                3LL * t + k, (unsigned)v,
                                mesh->vertex_count);
        }
    }
    if ((r = hf__check_attr(diag, "positions", mesh->positions,
                            mesh->position_stride, 12, mesh->vertex_count, 3,
                            0)) != HF_OK)
        return r;
    if (mesh->normals &&
        (r = hf__check_attr(diag, "normals", mesh->normals,
                            mesh->normal_stride, 12, mesh->vertex_count, 3,
                            1)) != HF_OK)
        return r;
    if (mesh->uvs &&
        (r = hf__check_attr(diag, "uvs", mesh->uvs, mesh->uv_stride, 8,
                            mesh->vertex_count, 2, 0)) != HF_OK)
        return r;
    hf__ok(diag);
    return HF_OK;
}

HFDEF float hf_triangle_area(const float a[3], const float b[3],
                             const float c[3])
{
    float e1[3], e2[3], n[3];
    hf__sub3(e1, b, a);
    hf__sub3(e2, c, a);
    hf__cross3(n, e1, e2);
    return 0.5f * HF_SQRTF(hf__dot3(n, n));
}

HFDEF hf_result hf_mesh_compute_normals(const hf_mesh *mesh,
                                        float *out_normals)
{
    hf_result r;
    int t, i;
    if (!out_normals) return HF_ERROR_NULL_POINTER;
    r = hf_mesh_validate(mesh, NULL);
    if (r != HF_OK) return r;
    HF_MEMSET(out_normals, 0,
              sizeof(float) * 3u * (size_t)mesh->vertex_count);
    for (t = 0; t < mesh->triangle_count; ++t) {
        const uint32_t *tri = mesh->indices + 3 * (size_t)t;
        float e1[3], e2[3], n[3];
        int k;
        const float *a = hf__mesh_pos(mesh, (int)tri[0]);
        hf__sub3(e1, hf__mesh_pos(mesh, (int)tri[1]), a);
        hf__sub3(e2, hf__mesh_pos(mesh, (int)tri[2]), a);
        hf__cross3(n, e1, e2);
        for (k = 0; k < 3; ++k) {
            float *o = out_normals + 3 * (size_t)tri[k];
            o[0] += n[0];
            o[1] += n[1];
            o[2] += n[2];
        }
    }
    for (i = 0; i < mesh->vertex_count; ++i) {
        float *o = out_normals + 3 * (size_t)i;
        float len2 = hf__dot3(o, o);
        /* a sum that is zero, denormal-small or overflowed to inf has no
           usable direction */
        if (len2 > 1e-30f && hf__finitef(len2)) {
            float s = 1.0f / HF_SQRTF(len2);
            o[0] *= s;
            o[1] *= s;
            o[2] *= s;
        } else {
            o[0] = 0.0f;
            o[1] = 0.0f;
            o[2] = 1.0f;
        }
    }
    return HF_OK;
}

#ifdef __cplusplus
}
#endif

#endif /* HAIRFUR_IMPLEMENTATION */

/*
------------------------------------------------------------------------------
This software is available under 2 licenses -- choose whichever you prefer.
------------------------------------------------------------------------------
ALTERNATIVE A - MIT License
Copyright (c) 2026 the hairfur.h authors
Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:
The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.
THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
------------------------------------------------------------------------------
ALTERNATIVE B - Public Domain (www.unlicense.org)
This is free and unencumbered software released into the public domain.
Anyone is free to copy, modify, publish, use, compile, sell, or distribute this
software, either in source code form or as a compiled binary, for any purpose,
commercial or non-commercial, and by any means.
In jurisdictions that recognize copyright laws, the author or authors of this
software dedicate any and all copyright interest in the software to the public
domain. We make this dedication in perpetuity for the benefit of the public at
large and to the detriment of our heirs and successors. We intend this
dedication to be an overt act of relinquishment in perpetuity of all present
and future rights to this software under copyright law.
THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER LIABILITY, WHETHER IN AN
ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM, OUT OF OR IN CONNECTION
WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE SOFTWARE.
------------------------------------------------------------------------------
*/
