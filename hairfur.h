/* hairfur.h - v0.2.0 - real-time hair and fur for game engines, on the CPU
   Public domain or MIT, your choice: see the end of this file and LICENSE.

   hairfur.h turns a triangle mesh and a few UV maps (density, length, colour)
   into hair or fur geometry every frame, and leaves drawing to the host engine.
   It has no dependencies beyond the C standard library. It descends from
   furmesh, the 2010 fur plugin of the Crystal Space engine (Bullet ropes,
   about 8 frames a second for 3,670 strands); "the Crystal Space plugin"
   below means that code (docs/history.md).

   DO THIS ONCE

       In exactly one C or C++ file of your program:

           #define HAIRFUR_IMPLEMENTATION
           #include "hairfur.h"

       Everywhere else, include "hairfur.h" without the define. Under
       another file name, define HF_HEADER_FILENAME beside the
       implementation too (CONFIGURATION MACROS).

   QUICK START (README.md has it as a complete program, built by make test)

       hf_fur_desc desc = {0};              // C++: = {}; zero = default
       desc.mesh.positions = &verts[0].x;   // your vertex buffer, strided
       desc.mesh.position_stride = sizeof verts[0];
       desc.mesh.vertex_count = n_verts;
       desc.mesh.indices = indices;       desc.mesh.triangle_count = n_tris;
       desc.total_strands = 20000;
       hf_fur *fur;  hf_diag diag;  hf_fur_info info;
       if (hf_fur_create(&desc, &fur, &diag) != HF_OK)
           printf("%s\n", diag.message);  // names the stage and the problem

       // per frame (each call takes a (first, count) range for threads):
       hf_fur_set_lod(fur, hf_lod_from_distance(dist, 1.0f, 30.0f));
       hf_fur_get_info(fur, &info);
       hf_fur_set_roots(fur, &skinned_mesh, 0, info.guide_count);
       hf_fur_simulate(fur, 0, info.guide_count, dt, colliders, n);
       hf_fur_interpolate_guides(fur, 0, info.lod_guide_count);
       hf_fur_interpolate(fur, 0, info.drawn_strand_count);
       hf_fur_ribbons(fur, 0, info.drawn_strand_count, &view, &streams);
       ...
       hf_fur_destroy(fur);

   FUNCTIONS BY TASK

       Fur on a mesh, or a groom, all stages in one object (section 10):
           hf_fur_create, hf_fur_create_groom, hf_fur_destroy,
           hf_fur_get_info, hf_fur_set_lod, hf_fur_set_roots,
           hf_fur_set_transform, hf_fur_build_grid (hair-hair interaction),
           hf_fur_simulate, hf_fur_settle_rest (draped rest shapes),
           hf_fur_interpolate_guides,
           hf_fur_interpolate, hf_fur_ribbons, hf_fur_points,
           hf_fur_interpolate_points (the GPU path in one pass),
           hf_fur_max_stretch, hf_fur_reset, hf_fur_set_rope_params,
           hf_fur_set_rope_params_range, hf_fur_set_mode, hf_fur_set_kernels
       Drawing (section 8): hf_ribbon_index_count, hf_ribbon_indices,
           hf_ribbon_chunk_strands, hf_ribbon_indices16 (16-bit chunks),
           hf_format_bytes; over your own strands: hf_ribbons,
           hf_ribbon_points (GPU expansion)
       Level of detail (section 7): hf_lod_from_distance,
           hf_lod_strand_count, hf_lod_width_scale
       Growing, stage by stage (section 5): hf_tessellate,
           hf_tess_evaluate, hf_guides_rest, hf_place_strands,
           hf_strand_roots, hf_strand_lengths, hf_strand_colors,
           hf_color3d_coord, hf_color3d_sample, hf_bind_strands,
           hf_uv_triangle_density
       Simulating ropes of your own (section 6): hf_rope_params_init,
           hf_rope_params_validate, hf_ropes_memory_size, hf_ropes_init,
           hf_ropes_create, hf_ropes_destroy, hf_ropes_set_rest,
           hf_ropes_set_roots, hf_ropes_step, hf_ropes_set_mode,
           hf_ropes_reset, hf_ropes_max_stretch, hf_ropes_roots_inside,
           hf_ropes_get_positions, hf_ropes_copy_range,
           hf_ropes_rest_from_pose; hair-hair interaction:
           hf_grid_memory_size, hf_grid_init, hf_grid_create,
           hf_grid_destroy, hf_grid_build, hf_ropes_apply_grid
       Interpolating strands of your own (section 7): hf_interpolate
       Shading: the Marschner lookup textures (section 9):
           hf_lut_params_init, hf_lut_validate, hf_lut_bake_m,
           hf_lut_bake_n, hf_lut_bake_n_rgb, hf_lut_to_u8, hf_lut_eval_m,
           hf_lut_eval_n, hf_lut_furnace (white furnace of baked
           textures), hf_lut_bake_dual (dual scattering tables)
       Inputs (sections 3, 4): hf_map_validate, hf_map_sample,
           hf_map_sample_fast, hf_map_blur, hf_mesh_validate,
           hf_mesh_compute_normals, hf_triangle_area
       Results, versions, random numbers (sections 1, 2):
           hf_result_string, hf_version, hf_version_string, hf_simd_resolve,
           hf_rng_seed,
           hf_rng_u32, hf_rng_float, hf_rng_below

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
       HF_NO_SIMD           use only the scalar references; results are
                            identical. Otherwise SSE2 where the compiler
                            targets it, and on gcc and clang for x86 also
                            AVX2 and AVX-512 kernels, chosen at run time
                            by CPUID (hf_simd_resolve); on WebAssembly
                            the SSE2 kernels with emscripten's -msimd128
                            -msse2 (HF_SIMD_WASM128).
       HF_SIMD_MAX          an hf_simd_level: the highest level used
                            (e.g. HF_SIMD_SSE2 keeps the wide kernels out
                            of use).
       HF_HEADER_FILENAME   the header's own file name, quoted; default
                            "hairfur.h". The implementation includes
                            itself by it, once for each SIMD width of its
                            kernel texts (found beside it, as #include
                            "..." searches the including file's directory
                            first): define it, e.g. "hairfur-0.2.h", where
                            the file has another name.
       HF_STREAM_MIN_BYTES  strand points larger than this (a call's, or
                            a fur's drawn strands') are written with
                            streaming stores by default (nontemporal
                            0); default 4 MiB.
       HF_STREAM_MIN_VERTEX_BYTES  the same for ribbon vertices or GPU
                            points; default 8 MiB.
       HF_ASSERT(x)         the library's own invariants (default: assert).
                            Never used on caller input: that gets a result.
       HF_SQRTF, HF_FLOORF, HF_SQRT, HF_EXP, HF_POW, HF_SIN, HF_COS,
       HF_ASIN, HF_ACOS, HF_FABS, HF_FLOOR, HF_CEIL, HF_CBRT, HF_MEMCPY,
       HF_MEMSET            replace the libm / libc functions used (float
                            ones in the per-frame code, double ones in
                            growth and LUT baking).

   COMPILERS AND PLATFORMS

       gcc and clang: C99 and C++11, the strict warnings as errors, on
       x86-64 (SSE2), ARM64, 32-bit x86 with SSE2 math (x87 math changes
       results: use -msse2 -mfpmath=sse), Windows x64 through mingw-w64
       (make cross-test runs each) and WebAssembly through emscripten
       (make wasm-test, under node): built with -msimd128 -msse2, the SSE2
       kernels are compiled to WebAssembly SIMD128 by emscripten's SSE2
       headers and are the level chosen at compile time (HF_SIMD_WASM128;
       no CPUID there); without -msse2 the scalar references run. MSVC:
       the header keeps every compiler-specific word behind its own
       macros, with an _MSC_VER
       branch: HF__INLINE is static __forceinline, HF__NOINLINE
       __declspec(noinline), HF__RESTRICT __restrict, HF__UNUSED and
       HF__PRINTF empty; SSE2 is used when _M_X64 is defined or
       _M_IX86_FP >= 2 (<emmintrin.h>, unaligned loads and stores only, so
       no alignment attribute is needed); the AVX2 and AVX-512 kernels
       need no attribute there (MSVC compiles any intrinsic anywhere) and
       are chosen at run time from __cpuid, __cpuidex and _xgetbv, as gcc
       and clang do with __builtin_cpu_supports. Contraction of a * b + c
       into FMA is off in the implementation (pragmas for gcc and clang;
       MSVC does not contract unless /fp:contract or /fp:fast).
       tests/msvc_check.sh parses that branch with clang as MSVC; MSVC
       itself is not run here (unverified).

   CONVENTIONS

       - Units: metres, seconds and radians, right-handed, gravity -9.81
         along y by default. Every field's unit is given beside it. An
         engine in other units either converts its positions to metres
         on the way in and out (scale by s = 0.01 for centimetres), or
         keeps its units and scales, by its metres-to-units factor k
         (100 for centimetres):
           lengths, times k: hf_fur_desc max_length, curl_radius,
             wave_amplitude, clump_size; hf_ribbon_params root_width,
             tip_width; hf_rope_params collision_margin; colliders' a, b
             and radius; the distances given to hf_lod_from_distance;
           accelerations (m/s^2), times k: gravity, wind, turbulence;
           per area (1/m^2), divided by k^2: tess_factor,
             strands_per_area.
         Times (dt, max_dt, mode_blend_time, turbulence_frequency),
         angles, stiffnesses, damping, fractions (frizz, clump, LOD) and
         counts have no length in them and stay as they are. Positions
         are accepted up to HF_ROPE_MAX_COORD (1e6) in any unit.
       - One rule for every struct: zero-initialise it, set what you need;
         a zero field means the default documented beside it. Where 0 is a
         meaningful value whose default is not 0 (no gravity, no damping),
         set the field's bit in the struct's explicit_zero. The _init()
         functions write the defaults themselves.
       - Every function that can fail returns hf_result: HF_OK (0) or a
         negative code; hf_result_string() gives a message. On failure no
         output has been written.
       - Counts are int; negative or zero counts where one is needed are
         refused. Byte strides of 0 mean "packed".
       - Every stochastic stage takes a seed and uses hf_rng (PCG32): no
         rand(), no global state. Same inputs and seed, same bytes.
       - No function keeps state between calls (MSVC builds keep one fact,
         the CPU's SIMD level, read once); the per-frame functions take
         a (first, count) range and never allocate, so an engine can spread a
         frame over its own threads. Inputs are indexed by absolute strand
         (or rope) index; outputs too, unless out_first (interpolation,
         ribbons, points) moves the start of the output buffer to strand
         out_first, so that a range can go into a buffer that holds
         exactly that range (hf_ropes_copy_range for rope positions; the
         growth-time range outputs are indexed absolutely).
       - Stack (gcc, x86-64, -fcallgraph-info=su, callees added, at -O2
         and at -O0): hf_ribbons and hf_fur_ribbons about 38 KiB (two
         strands' rows sized for HF_MAX_POINTS, the second sharing an
         8 KiB stage for streaming stores, and up to 4 KiB to start the
         first at a page boundary), hf_fur_interpolate_points 18
         KiB (23 at -O0; 24 and 27 for compact points, through a 4 KiB
         stage), hf_ropes_step and hf_fur_simulate about 41 KiB with the
         AVX-512 kernel (60 at -O0: a chunk's broadphase, 8 KiB, a
         row's contacts grouped by their colliders, 19 KiB, and the
         contact kernel's rounds, 25 KiB), the other
         per-frame calls under 16 KiB: size worker and fiber stacks for
         it. Kernels are forced inline only
         where the compiler optimizes, so a debug build needs no more.
         make test runs its native builds on a 256 KiB stack.

   SECTIONS (in the order the data flows)

       Every section and subsection opens with one anchor line, a
       comment that reads "---- 6.5 the broadphase ----": grep for
       "---- 6\." to list section 6, or "---- 6.5 " for one subsection.
       A section's anchor stands twice, over its declarations and over
       its implementation; a subsection's over its declarations too
       where they split (5.1 to 5.6, 6.9, 8.9).

       1. configuration, result codes, version
          1.1 defaults: what every zero field means, in one place
          1.2 small vector helpers
       2. random numbers (hf_rng)
       3. maps (hf_map): validation, bilinear sampling, Gaussian blur
       4. meshes (hf_mesh): validation, normals, triangle area
       5. grow: tessellation, guides, placement, maps, bindings
          5.1 density of a UV triangle      5.4 strand placement
          5.2 density tessellation          5.5 maps on strands
          5.3 guides                        5.6 binding strands to guides
       6. ropes: Verlet ropes with follow-the-leader constraints, shape
          stiffness, colliders, animation-only mode
          6.1 memory                        6.6 the simulated rope step
          6.2 frames                        6.7 the rope kernels (a text)
          6.3 rest pose, roots, modes       6.8 the kernels per width,
          6.4 the step                          their dispatch, the call
          6.5 the broadphase                6.9 hair-hair interaction
                                            6.10 the grid's splat and push
       7. interpolation and LOD
          7.1 interpolation at 8 and 16 lanes (a kernel text)
          7.2 the interpolation kernels per width, hf_interpolate
          7.3 level of detail
       8. ribbons: camera-facing vertices, the GPU point path, indices
          8.1 inputs: checks, widths       8.6 the whole-call loops
          8.2 the strand frame             8.7 hf_ribbons: the call
          8.3 vertex formats: encoding     8.8 GPU points (with their
          8.4 the writers                      kernel text)
          8.5 streaming stores: the stage  8.9 indices
       9. LUT baking: the Marschner M and N textures
          9.1 M: three Gaussians           9.4 white furnace
          9.2 N: roots of Phi, Fresnel     9.5 dual scattering tables
          9.3 the energy-conserving fibre  9.6 8-bit conversion
      10. the fur object (hf_fur): all of the above, per frame
          10.1 grooms

       The implementation follows the same order, after one prologue,
       section 0 (0.1 the overridable macros, 0.2 the SIMD levels, 0.3
       the compiler words, 0.4 the four-lane operations, 0.5 kernel
       texts); 1.1 is the one place where every struct's zero fields get
       their defaults. Every kernel is named by its width, whatever the
       instruction set: hf__<name>_v1 the scalar reference, _v4 (SSE2 or
       NEON), _v8 (AVX2), _v16 (AVX-512); each SIMD kernel gives its
       reference's bytes. Every stage dispatches one way (1, "The
       dispatch"): its kernels stand in a const array of descriptors,
       hf__<stage>_widths, one a width, widest first down to the
       reference, each naming its instruction set and the level it needs;
       a call resolves its level once (hf__kernels_for: the widest the
       level asked for and the CPU allow), and what a width does not take
       goes to a narrower one. One kernel written once for any width
       (the rope step's contacts and rows, interpolation into strands and
       into GPU points, the grid's splat and push) is a kernel text,
       compiled once per width by the header including itself
       (HF_HEADER_FILENAME). Each copy is a function with the text's own
       lines, so a debugger stops in the AVX2 rope kernel at "break
       hf__ropes_ftl_row_v8" (more in 0.5, "Kernel texts").

   VERSION HISTORY

       next (unreleased)   any number of colliders at SIMD speed: a
                           broadphase per 16 ropes (the colliders within
                           reach of their roots, row by row), contacts
                           against each point's relevant colliders, a
                           quick answer first; ropes stepped in chunks of
                           256 (bytes change where a rope touches a
                           collider); compact GPU points, 8 bytes
                           (hf_point_format, hf_ribbon_params.
                           point_format, point_origin, point_scale);
                           hair-hair interaction on a grid (hf_grid,
                           hf_grid_build, hf_ropes_apply_grid,
                           hf_rope_params.volume and friction,
                           hf_fur_desc.grid_resolution, hf_fur_build_grid,
                           hf_grid.simd);
                           gravity-settled rest shapes
                           (hf_ropes_rest_from_pose, hf_fur_settle_rest);
                           FTL's velocity correction damps a compressed
                           segment's bend instead of pushing its parent
                           (stiff ropes come to rest; bytes change where
                           a segment is compressed); one dispatch shape
                           (kernels named by width, hf__<stage>_widths);
                           hf_place_strands refuses a negative or
                           non-finite strands_per_area even beside a
                           total_strands; hf_fur_create's diagnostics
                           name each field alone; strands that keep
                           their lengths (hf_fur_desc.keep_length,
                           hf_groom_desc.keep_length).
       0.2.0 (2026-11-23)  one convention: every struct zero-initialised
                           means its defaults (hf_rope_params and
                           hf_lut_params too, with explicit_zero bits for a
                           literal 0; ribbon widths default to 1 mm and
                           0.25 mm); out_first writes a range into a buffer
                           of exactly that range (hf_interp_params,
                           hf_ribbon_params); 16-bit index chunks
                           (hf_ribbon_chunk_strands, hf_ribbon_indices16);
                           hf_fur_create refuses a negative or non-finite
                           strands_per_area or a negative total_strands, and
                           strands_per_area wins over total_strands as
                           documented; the implementation as named steps
                           with one SIMD layout (the same bytes as 0.1.0);
                           FTL collisions that clear every collider at the
                           rest length, roots inside a collider
                           (hf_ropes_roots_inside), ribbon sides
                           perpendicular to their tangent (these change
                           bytes where a collider is touched or a view is
                           within half a degree of a tangent); exact
                           hf_lod_strand_count; hf_ropes_copy_range,
                           hf_fur_set_rope_params, hf_fur_set_mode;
                           in hf_fur_desc: growth directions (comb,
                           comb_stride, comb_map), authored guide curves
                           (guide_curves, guide_curve_points,
                           guide_curve_count) and styling (curl, wave,
                           frizz with their maps, colour variation);
                           grooms without a mesh (hf_fur_create_groom,
                           hf_groom_desc) and rigid root frames for any
                           fur (hf_fur_set_transform); rope parameters
                           on a range (hf_fur_set_rope_params_range);
                           clumps of a chosen size (clump_size); per-strand
                           widths (hf_ribbon_strands.width,
                           width_variation); maps for clump, clump size,
                           colour and width variation; mode switches
                           without a jump in velocity (a Hermite glide;
                           the rope memory holds 6 more point rows), the
                           mode kept per guide through LOD; SIMD levels
                           chosen at run time (hf_simd_level,
                           hf_simd_resolve, HF_SIMD_MAX, the simd fields,
                           hf_fur_set_kernels) with AVX2 and AVX-512
                           interpolation, AVX2 points and ribbons (CPUID
                           on gcc, clang and MSVC), NEON on ARM64 for
                           every per-frame stage (interpolation, points,
                           ribbons in every format, ropes), the same
                           bytes at every level, FMA contraction off in
                           the implementation whatever the flags;
                           streaming stores (nontemporal) for outputs
                           past HF_STREAM_MIN_BYTES (strand points) and
                           HF_STREAM_MIN_VERTEX_BYTES (vertices, points)
                           by default.
       0.1.0 (2026-11-22)  first release: maps and meshes, density
                           tessellation, guides, placement, Verlet ropes,
                           interpolation, LOD, ribbons, Marschner LUTs,
                           the hf_fur object.
*/

#ifndef HAIRFUR_H
#define HAIRFUR_H

#include <stddef.h>
#include <stdint.h>

#define HAIRFUR_VERSION_MAJOR 0
#define HAIRFUR_VERSION_MINOR 2
#define HAIRFUR_VERSION_PATCH 0
#define HAIRFUR_VERSION_STRING "0.2.0"
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

/* ---- 1. configuration, result codes, version ---------------------------- */

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
      "unsupported format: a map's (1 to 4 channels, u8 or f32) or a "         \
      "vertex stream's (an hf_format value)")                                  \
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

/* The largest magnitude accepted where the library multiplies inputs
   (map values, lengths, widths, interpolation inputs): products of two such
   values stay finite in float. */
#define HF_MAX_ABS 1e18f

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

/* SIMD levels of the per-frame kernels (interpolation, LOD guides, GPU
   points, ribbons, the rope step). Every level gives the same bytes; they
   differ only in speed. */
typedef enum hf_simd_level {
    HF_SIMD_AUTO = 0,   /* the best this CPU and build run (the default) */
    HF_SIMD_SCALAR = 1, /* the scalar references */
    HF_SIMD_SSE2 = 2,   /* 4 lanes: SSE2, the x86-64 baseline, or NEON */
    HF_SIMD_NEON = 2,   /* on ARM64 (always there), the same level */
    HF_SIMD_WASM128 = 2, /* on WebAssembly (emscripten -msimd128 -msse2):
                            the SSE2 kernels in SIMD128, the same level */
    HF_SIMD_AVX2 = 3,   /* 8 lanes */
    HF_SIMD_AVX512 = 4  /* 16 lanes (AVX-512F and BW) */
} hf_simd_level;

/* The level a kernel runs at when `requested` is asked for: 0 (auto) gives
   the best this CPU supports in this build (CPUID on x86; what the
   compiler targets elsewhere; HF_NO_SIMD: scalar;
   HF_SIMD_MAX caps it); a higher request than that is lowered to it, so
   asking for a level is always safe. Unknown values count as auto. The
   CPU is asked once a process (by libgcc or compiler-rt when the program
   loads; on MSVC at the first call), so every call gives the same
   answer. */
HFDEF int hf_simd_resolve(int requested);


/* ---- 2. random numbers -------------------------------------------------- */

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

/* ---- 3. maps ------------------------------------------------------------ */

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
   v = 0, as in OpenGL's textures and the UVs most exporters write (v up).
   Image files store their top row first (PNG; stb_image unless
   stbi_set_flip_vertically_on_load(1)): flip those rows, or a map reads
   upside down. Texel centres sit at ((x + 0.5) / width,
   (y + 0.5) / height). */
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
   least one packed row, no size overflow, and for HF_MAP_F32: data 4-byte
   aligned, a row stride that is a multiple of 4 (HF_ERROR_BAD_STRIDE), and
   every value finite (HF_ERROR_NON_FINITE) and within +-HF_MAP_MAX_VALUE
   (HF_ERROR_BAD_PARAMETER). Returns HF_OK or the code of the first problem found; `diag` (may
   be NULL) names it. */
#define HF_MAP_MAX_DIMENSION 65536
#define HF_MAP_MAX_VALUE HF_MAX_ABS
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

/* Separable Gaussian blur (the Crystal Space plugin blurred density maps
   before use).
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

/* ---- 4. meshes ---------------------------------------------------------- */

/* A view of a triangle mesh the caller owns: nothing is copied. Strides are
   in bytes (0 = packed; otherwise a multiple of 4, with 4-byte aligned
   arrays, so every float read is aligned), so an interleaved engine vertex
   buffer is passed by pointing each attribute at its first element with the
   vertex size as the stride. */
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
   counts >= 1, strides 0 or a multiple of 4 of at least the element size
   and 4-byte aligned arrays (HF_ERROR_BAD_STRIDE), every
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

/* ---- 5. grow: tessellation, guides, placement, maps, bindings ----------- */

/* The growing stages run once, when a fur is created (or its maps change):

       base mesh + density map --hf_tessellate--> guide triangles
                                                  (+ added vertices, each a
                                                  base triangle + barycentric)
       guide triangles --hf_guides_rest--> pure guides (welded base vertices)
                                           + LOD guides (added vertices)
       guide triangles + density map --hf_place_strands--> strand records in
                                                           LOD order
       strand records + length / colour maps --> per-strand length, colour

   Every function fills arrays the caller owns. Those whose output size is
   not known in advance follow the two-call pattern: call once with NULL
   output arrays to get the exact counts, allocate, call again. On any error
   nothing is written, counts included. The maps are sampled on channel 0
   (density, length, 3D-colour index); density and length values below 0
   read as 0. A NULL density map means density 1 everywhere; a NULL length
   map means length 1 (times max_length) everywhere. */

/* ---- 5.1 density of a UV triangle --------------------------------------- */

/* How the density D of a triangle is read from the density map (enum
   values; the fields and arguments that hold them are int, as everywhere
   in hairfur.h). All three
   see the map as its texels (bilinear for CORNERS, texel values for the
   other two) and give the same value on a constant map. */
typedef enum hf_density_estimator {
    /* mean of the bilinear samples at the three corner UVs: fast; right for
       small triangles on a smooth (blurred) map, blind to a feature that
       lies inside a big triangle */
    HF_DENSITY_CORNERS = 0,
    /* mean of the texels that Bresenham lines visit along the three edges in
       texel space (texel of a UV: floor(u * width), floor(v * height)); each
       texel on the outline counts once per visit */
    HF_DENSITY_EDGES = 1,
    /* exact mean over the UV triangle: every texel it touches weighted by
       the area of the triangle inside that texel (a coverage rasteriser).
       A triangle with zero UV area falls back to CORNERS. */
    HF_DENSITY_AREA = 2
} hf_density_estimator;

/* EDGES and AREA visit every texel under the triangle, so its UVs are
   bounded: with HF_WRAP_REPEAT the triangle (moved by whole periods) may
   span at most this many map periods along u and along v; with
   HF_WRAP_CLAMP every u and v must lie in [-SPAN, 1 + SPAN]. */
#define HF_DENSITY_MAX_UV_SPAN 16

/* Density of the UV triangle (uv0, uv1, uv2) by `estimator`, >= 0, written
   to *out_density (1 when `density` is NULL). Errors: HF_ERROR_NULL_POINTER
   (a uv or out NULL), the map's validation error, HF_ERROR_NON_FINITE (a uv
   component), HF_ERROR_BAD_PARAMETER (unknown estimator), HF_ERROR_BAD_RANGE
   (UVs beyond HF_DENSITY_MAX_UV_SPAN for EDGES or AREA). Validates the map
   on every call (an HF_MAP_F32 map is scanned): for many triangles use the
   stages below, which validate once. */
HFDEF hf_result hf_uv_triangle_density(const hf_map *density,
                                       const float uv0[2], const float uv1[2],
                                       const float uv2[2],
                                       int estimator, float *out_density);

/* ---- 5.2 density tessellation ------------------------------------------- */

typedef enum hf_split_point {
    /* split at the centroid: deterministic, each child gets exactly 1/3 of
       the area */
    HF_SPLIT_CENTROID = 0,
    /* split at a seeded random point, uniform over the middle triangle (the
       triangle shrunk by 1/2 about its centroid): every child keeps at least
       1/6 of the area, so no sliver is born (the Crystal Space plugin drew
       over the whole triangle, which made needle-thin children) */
    HF_SPLIT_RANDOM = 1
} hf_split_point;

#define HF_TESS_DEFAULT_MAX_DEPTH 12
#define HF_TESS_MAX_DEPTH 32
#define HF_TESS_DEFAULT_MAX_TRIANGLES (1 << 22)
#define HF_TESS_MAX_TRIANGLES (1 << 28)

/* Zero-initialise, then set `factor`. Every other zero field is a default. */
typedef struct hf_tess_params {
    float factor; /* required, > 0 and finite (0, negative, NaN, infinite:
                     HF_ERROR_BAD_PARAMETER). A triangle of world area A and
                     density D is split while D * A * factor > 1, so 1 /
                     factor is the area a triangle of density 1 ends with
                     at most. */
    int estimator; /* hf_density_estimator; 0 = HF_DENSITY_CORNERS */
    int split;     /* hf_split_point; 0 = HF_SPLIT_CENTROID */
    uint64_t seed;                  /* for HF_SPLIT_RANDOM */
    int max_depth;     /* splits of one base triangle in a row; 0 = 12, at
                          most HF_TESS_MAX_DEPTH */
    int max_triangles; /* output triangles; 0 = 1 << 22, at most 1 << 28 */
    int refuse_degenerate; /* 0: a zero-area base triangle is kept as is
                              (never split; it grows no strands);
                              1: HF_ERROR_DEGENERATE instead */
} hf_tess_params;

/* A vertex that tessellation added: the base-mesh triangle it lies in and
   its barycentric weights of that triangle's corners (indices[3t+0..2]).
   16 bytes. hf_tess_evaluate turns it into a position on the (skinned)
   base mesh. */
typedef struct hf_tess_vertex {
    uint32_t triangle;
    float bary[3];
} hf_tess_vertex;

/* Output of hf_tessellate. The caller sets the array pointers (each may be
   NULL: that stream is skipped; all NULL: only count) and their
   capacities; the call sets the four counts. The tessellated mesh's vertex
   list is the base vertices 0 .. V-1 followed by the added vertices V ..
   V + added_count - 1 (V = mesh->vertex_count). */
typedef struct hf_tess_output {
    uint32_t *indices;       /* 3 * triangle_count, into the vertex list */
    uint32_t *triangle_base; /* triangle_count: base triangle of each */
    hf_tess_vertex *added;   /* added_count */
    float *positions;        /* 3 * vertex_count (base copied, added
                                evaluated as hf_tess_evaluate does) */
    float *uvs;              /* 2 * vertex_count; the mesh needs UVs */
    int triangle_capacity;   /* entries indices / triangle_base hold */
    int added_capacity;      /* entries added holds */
    int vertex_capacity;     /* vertices positions / uvs hold */
    /* written on success: */
    int triangle_count;
    int added_count;
    int vertex_count; /* V + added_count */
    int depth;        /* deepest split level of any output triangle */
} hf_tess_output;

/* Density tessellation (stage 1): each base triangle is split, recursively,
   at its centroid or a random point into three (a, b, Y), (b, c, Y),
   (c, a, Y) until D * A * factor <= 1 for every triangle, where A is the
   world area of the triangle's positions (hf_triangle_area) and D its
   density (params->estimator) on its UV triangle. Children keep the
   winding; output triangles come base triangle by base triangle.

   Two calls: with every array of `out` NULL, sets the counts; then with
   arrays of at least those sizes, fills them. `density` may be NULL
   (density 1 everywhere); with a map the mesh needs UVs. Allocates nothing.
   Deterministic: same input and seed, same bytes. Zero-area triangles: see
   refuse_degenerate; a mesh whose triangles all have zero area is refused.

   Errors (nothing written): HF_ERROR_NULL_POINTER (mesh, params, out, or
   mesh UVs with a density map or uvs output), the mesh's or map's
   validation error, HF_ERROR_BAD_PARAMETER (factor, estimator, split, a
   cap out of range), HF_ERROR_NON_FINITE (a triangle whose area overflows
   float), HF_ERROR_DEGENERATE, HF_ERROR_BAD_RANGE (see
   HF_DENSITY_MAX_UV_SPAN), HF_ERROR_DEPTH_CAP (a triangle still too big at
   max_depth), HF_ERROR_TRIANGLE_CAP (more than max_triangles),
   HF_ERROR_OVERFLOW (vertex count beyond INT_MAX), HF_ERROR_BUFFER_TOO_SMALL
   (a capacity below its count). The cap errors come from the counting pass,
   so a factor that would make billions of triangles fails fast. */
HFDEF hf_result hf_tessellate(const hf_mesh *mesh, const hf_map *density,
                              const hf_tess_params *params,
                              hf_tess_output *out);

/* Re-evaluate added vertices first .. first + count - 1 of the array
   `added` (added_count entries) on `mesh` (e.g. skinned this frame):
   position = b0 * P0 + b1 * P1 + b2 * P2 of the base triangle, with the
   exact arithmetic hf_tessellate used, so the rest mesh gives its
   positions bit for bit; normal = the normalised blend of the mesh's vertex
   normals (the face normal where the blend cancels, (0, 0, 1) where that is
   zero too); uv = the blend of the UVs. Each output may be NULL (skipped);
   element i goes to out_positions[3 i], out_normals[3 i], out_uvs[2 i]
   (absolute index), so ranges may be split across threads. No allocation.
   Checks only what it touches (the records and their triangles).
   Errors: HF_ERROR_NULL_POINTER (mesh, its positions or indices, added;
   normals or uvs asked for and the mesh has none), HF_ERROR_BAD_COUNT,
   HF_ERROR_BAD_STRIDE, HF_ERROR_BAD_RANGE, HF_ERROR_INDEX_OUT_OF_RANGE (a
   record's triangle or that triangle's indices), HF_ERROR_NON_FINITE (a
   weight, or an input position / normal / uv it reads). */
HFDEF hf_result hf_tess_evaluate(const hf_mesh *mesh,
                                 const hf_tess_vertex *added, int added_count,
                                 int first, int count, float *out_positions,
                                 float *out_normals, float *out_uvs);

/* ---- 5.3 guides --------------------------------------------------------- */

/* the same cap as HF_MAX_POINTS of the interpolation section */
#define HF_GUIDE_MAX_POINTS 256

/* Zero-initialise, then set points and max_length. */
typedef struct hf_guide_params {
    int points;               /* control points per guide, 2 ..
                                 HF_GUIDE_MAX_POINTS (16 is typical) */
    float max_length;         /* > 0 and finite */
    const hf_map *length_map; /* NULL = 1; guide length = max_length *
                                 length_map(uv) */
    const float *comb;        /* optional combing direction per base vertex
                                 (object space, any length; zero = none) */
    int comb_stride;          /* bytes; 0 = 12 */
    const hf_map *comb_map;   /* optional combing direction map, >= 3
                                 channels, object space; 8-bit texels decode
                                 as 2 c - 1 (like a normal map), float as
                                 is. Wins over `comb`. */
} hf_guide_params;

/* Output of hf_guides_rest; as hf_tess_output: caller arrays (NULL =
   skipped; all NULL = count only), the call sets the counts. Guides
   0 .. pure_guide_count - 1 are the pure guides (one per distinct base
   position, in order of first appearance), then one LOD guide per added
   vertex: guide pure_guide_count + i grows from added vertex i. */
typedef struct hf_guide_output {
    float *points;      /* 3 * params->points * guide_count: point j of
                           guide g at [3 (g * points + j)], root first */
    float *lengths;     /* guide_count */
    float *directions;  /* 3 * guide_count: unit growth direction */
    float *normals;     /* 3 * guide_count: unit (welded) surface normal */
    uint32_t *guide_of_vertex; /* vertex_count + added_count: the guide of
                                  each vertex of the tessellated mesh */
    int guide_capacity; /* guides the per-guide arrays hold */
    /* written on success: */
    int guide_count;
    int pure_guide_count;
} hf_guide_output;

/* Rest shapes of the guides (stage 2). `mesh` is the base mesh at rest,
   `added` / `added_count` the added vertices from hf_tessellate (0 and NULL
   for none). Base vertices are welded by exact position (bitwise, -0 ==
   +0): all copies of a position split at a UV seam or hard edge share one
   pure guide, whose normal is the normalised sum of the copies' normals
   (mesh normals, or hf_mesh_compute_normals when the mesh has none) and
   whose length is the mean of max_length * length_map at the copies' UVs.
   A LOD guide's normal is the normalised barycentric blend of its base
   triangle's welded guide normals, its root hf_tess_evaluate's position, its
   length max_length * length_map(its uv). The growth direction is the
   combing direction (map, else per vertex; welded and blended the same
   way) or the normal where there is none or it has zero length. Point j =
   root + direction * length * j / (points - 1).
   Scratch memory from `alloc` (NULL = default): at most 68 bytes per base
   vertex, freed before returning.
   Errors (nothing written): HF_ERROR_NULL_POINTER (mesh, params, out; a map
   given and the mesh has no UVs; added NULL with added_count > 0),
   validation errors of the mesh and maps, HF_ERROR_BAD_COUNT
   (added_count < 0, or points out of range), HF_ERROR_BAD_PARAMETER
   (max_length; a comb map with < 3 channels; an added weight outside
   [0, 1]), HF_ERROR_INDEX_OUT_OF_RANGE (an added triangle),
   HF_ERROR_NON_FINITE (comb directions, added weights),
   HF_ERROR_OVERFLOW, HF_ERROR_BUFFER_TOO_SMALL (guide_capacity),
   HF_ERROR_OUT_OF_MEMORY. */
HFDEF hf_result hf_guides_rest(const hf_mesh *mesh,
                               const hf_tess_vertex *added, int added_count,
                               const hf_guide_params *params,
                               hf_guide_output *out,
                               const hf_allocator *alloc);

/* ---- 5.4 strand placement ----------------------------------------------- */

typedef enum hf_root_sampler {
    /* uniform over each triangle: s = sqrt(r1), weights (1 - s, s (1 - r2),
       s r2) */
    HF_SAMPLER_UNIFORM = 0,
    /* stratified: point k of a triangle is point k of a 2D Sobol (0,2)
       sequence, digitally shifted per triangle, mapped to the triangle by
       Heitz's area-preserving low-distortion square-to-triangle map: fewer
       clumps and holes inside a triangle, and every prefix of a triangle's
       points is itself spread out */
    HF_SAMPLER_STRATIFIED = 1,
    /* the Crystal Space plugin's formula, bA = r1, bB = r2 (1 - bA): NOT
       uniform, it crowds strands toward corner A. Only for comparison and
       tests. */
    HF_SAMPLER_CORNER_BIASED = 2
} hf_root_sampler;

/* One strand: 24 bytes (static-asserted in the implementation). Its three
   guides are those of the corners of guide triangle `triangle`: corner k
   is vertex indices[3 triangle + k] of the mesh given to hf_place_strands
   (the tessellated mesh), whose guide is guide_of_vertex of that vertex. */
typedef struct hf_strand {
    uint32_t triangle; /* guide triangle */
    float bary[2];     /* weights of corners 0 and 1; corner 2 has
                          (1 - bary[0]) - bary[1], computed in that order */
    float uv[2];       /* root UV: blend of the corner UVs (0, 0 without) */
    float random;      /* uniform in [0, 1), per strand (for variation) */
} hf_strand;

#define HF_MAX_STRANDS (1 << 28)

/* Zero-initialise, then set strands_per_area or total_strands. */
typedef struct hf_place_params {
    float strands_per_area; /* 1/m^2: expected strands per square metre
                               where the density is 1; > 0 unless
                               total_strands is set; negative or non-finite
                               refused */
    int total_strands;      /* > 0: exactly this many strands, distributed
                               in proportion to density * area (then
                               strands_per_area is not used: total_strands
                               wins here, the opposite of hf_fur_desc, where
                               a strands_per_area > 0 wins); 0: use
                               strands_per_area */
    int estimator; /* hf_density_estimator; 0 = HF_DENSITY_CORNERS */
    int sampler;   /* hf_root_sampler; 0 = HF_SAMPLER_UNIFORM */
    uint64_t seed;
    int max_strands;       /* refuse more than this; 0 = HF_MAX_STRANDS */
    int refuse_degenerate; /* as in hf_tess_params */
} hf_place_params;

/* Strand placement (stage 3) on the triangles of `mesh` (normally the
   tessellated mesh: positions and UVs from hf_tessellate's output).
   Triangle t expects e_t = D_t * A_t * strands_per_area strands (scaled so
   the e_t sum to total_strands when that is set). The counts are rounded by
   systematic sampling with one seeded offset u: triangle t gets
   floor(C_t + u) - floor(C_{t-1} + u), C_t the running sum of e; so each
   triangle gets floor(e_t) or ceil(e_t), E[count] = e_t exactly, and the
   total is floor(sum e + u) (within 1 of the density integral), or exactly
   total_strands. Zero-area triangles get none.
   LOD order: strand k (in sampler order) of a triangle with n strands has
   key (k + u_t) / n, u_t random per triangle, and the array is sorted by
   key (stable, radix). So the first fraction f of the array holds
   floor or ceil of f * n strands of every triangle: any prefix covers the
   whole surface in proportion to density, and with the stratified sampler
   each triangle's share is itself spread out.

   Two calls: with out NULL, sets *out_count; then with out holding
   capacity >= that many records, fills them and sets *out_count.
   Scratch memory: 16 bytes per strand from `alloc` (NULL = default), freed
   before returning; the counting call allocates nothing.
   Errors (nothing written): HF_ERROR_NULL_POINTER (mesh, params,
   out_count; mesh UVs with a density map), mesh / map validation errors,
   HF_ERROR_BAD_PARAMETER (strands_per_area, estimator, sampler,
   max_strands), HF_ERROR_BAD_COUNT (total_strands < 0),
   HF_ERROR_NON_FINITE (an area overflows), HF_ERROR_DEGENERATE (see
   refuse_degenerate; every triangle zero-area; total_strands asked of a
   mesh whose density * area is zero everywhere), HF_ERROR_BAD_RANGE (UV
   span, see HF_DENSITY_MAX_UV_SPAN), HF_ERROR_OVERFLOW (the count would
   exceed max_strands), HF_ERROR_BUFFER_TOO_SMALL, HF_ERROR_OUT_OF_MEMORY. */
HFDEF hf_result hf_place_strands(const hf_mesh *mesh, const hf_map *density,
                                 const hf_place_params *params,
                                 hf_strand *out, int capacity,
                                 int *out_count, const hf_allocator *alloc);

/* Root positions of strands first .. first + count - 1 (of strand_count)
   on `mesh` (the guide mesh, e.g. re-evaluated this frame):
   b0 P0 + b1 P1 + b2 P2 of the strand's triangle, 3 floats per strand at
   out_positions[3 i] (absolute index). No allocation. Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_COUNT, HF_ERROR_BAD_STRIDE,
   HF_ERROR_BAD_RANGE, HF_ERROR_INDEX_OUT_OF_RANGE (a strand's triangle or
   its indices), HF_ERROR_NON_FINITE (weights or positions read). */
HFDEF hf_result hf_strand_roots(const hf_mesh *mesh, const hf_strand *strands,
                                int strand_count, int first, int count,
                                float *out_positions);

/* ---- 5.5 maps on strands ------------------------------------------------ */

/* Per-strand length max_length * length_map(root uv) (max_length at most
   HF_MAP_MAX_VALUE, so the product stays finite; channel 0, negative
   read as 0; NULL map = max_length) for strands first .. first + count - 1,
   to out_lengths[i]. Errors: HF_ERROR_NULL_POINTER, map validation,
   HF_ERROR_BAD_PARAMETER (max_length < 0 or not finite),
   HF_ERROR_BAD_RANGE, HF_ERROR_NON_FINITE (a strand's uv). */
HFDEF hf_result hf_strand_lengths(const hf_strand *strands, int strand_count,
                                  int first, int count,
                                  const hf_map *length_map, float max_length,
                                  float *out_lengths);

/* Per-strand colour from a 2D colour map at the root UV, 4 floats per strand
   at out_rgba[4 i]: 1 channel = grey (g, g, g, 1), 2 = grey and alpha,
   3 = (r, g, b, 1), 4 = rgba. Errors as hf_strand_lengths. */
HFDEF hf_result hf_strand_colors(const hf_strand *strands, int strand_count,
                                 int first, int count,
                                 const hf_map *color_map, float *out_rgba);

/* The "3D" colour scheme: a greyscale UV map (`index_map`, channel 0) picks
   the column and the position t along the strand (0 root, 1 tip) picks the
   row of a second texture (the colour ramp, e.g. dyed tips, stripes).
   Writes out_xy = (clamp(index_map(u, v), 0, 1), clamp(t, 0, 1)): the
   texture coordinate at which to sample the ramp. A shader does the same:

       vec2 c = vec2(clamp(texture(index_map, uv).r, 0.0, 1.0),
                     clamp(t, 0.0, 1.0));
       vec4 color = texture(ramp, c);  // ramp: GL_LINEAR, GL_CLAMP_TO_EDGE

   (hf_map bilinear sampling has GL's texel-centre convention, so CPU and
   GPU agree.) Errors: NULL pointers, map validation, HF_ERROR_NON_FINITE. */
HFDEF hf_result hf_color3d_coord(const hf_map *index_map, float u, float v,
                                 float t, float out_xy[2]);

/* hf_color3d_coord, then the bilinear sample of `ramp` at those
   coordinates, expanded to rgba as hf_strand_colors does. */
HFDEF hf_result hf_color3d_sample(const hf_map *index_map, const hf_map *ramp,
                                  float u, float v, float t, float out[4]);

/* ---- 5.6 binding strands to guides -------------------------------------- */

/* How one strand follows three guides: indices into the guide array, the
   barycentric weights of its root in the guide triangle (summing to 1), and
   the ratio of the strand's own length to the weighted guide length. Made
   once at growth; 28 bytes. */
typedef struct hf_strand_binding {
    uint32_t guide[3];
    float weight[3];
    float length_scale; /* taken literally: 0 collapses the strand */
} hf_strand_binding;

/* For strands first .. first + count - 1, the binding that
   hf_interpolate reads: guide[k] = guide_of_vertex[indices[3 triangle + k]]
   of `guide_mesh` (the mesh given to hf_place_strands; guide_of_vertex has
   its vertex_count entries, from hf_guides_rest), weight = (bary[0],
   bary[1], (1 - bary[0]) - bary[1]), and length_scale = strand length /
   (weights . guide lengths) when both length arrays are given (strand
   lengths from hf_strand_lengths, indexed like strands; guide lengths from
   hf_guides_rest), else 1. Guides of weighted length 0 give 1. Writes out[i] (absolute
   index). No allocation. Errors: HF_ERROR_NULL_POINTER (guide_lengths NULL
   with strand_lengths given, and the required pointers),
   HF_ERROR_BAD_COUNT (guide_count < 1), HF_ERROR_BAD_RANGE,
   HF_ERROR_INDEX_OUT_OF_RANGE (triangle, vertex, or guide index),
   HF_ERROR_NON_FINITE (weights, lengths). */
HFDEF hf_result hf_bind_strands(const hf_mesh *guide_mesh,
                                const uint32_t *guide_of_vertex,
                                int guide_count, const hf_strand *strands,
                                int strand_count, int first, int count,
                                const float *strand_lengths,
                                const float *guide_lengths,
                                hf_strand_binding *out);

/* ---- 6. ropes: Verlet ropes for guide hairs, or any rope ---------------- */

/* A set of ropes that all have the same number of points (>= 2), simulated
   with position Verlet and position-based constraints. Per frame:

       hf_ropes_set_roots(ropes, 0, n, pos, nrm, tan, 0);  // skinned roots
       hf_ropes_step(ropes, 0, n, dt, &params, colliders, n_colliders);
       // read ropes->x/y/z (or hf_ropes_get_positions)

   Every per-frame call takes a (first, count) range of ropes, touches only
   the state of those ropes, never allocates, and gives byte-identical
   results however the ropes are split into ranges (each rope's update reads
   only its own state, the shared params and the colliders).

   LAYOUT. State is structure-of-arrays and point-major: point j of rope r is
   element [j * rope_count + r] of x, y, z (current) and px, py, pz
   (previous). Point-major lets the solver, which walks each rope from root
   to tip, run one rope per SIMD lane. Point 0 is the root.

   ROOT FRAME. Each rope has a root frame: a position, a normal and a
   tangent. The library builds an orthonormal basis from them: the normal is
   normalised, the tangent is made perpendicular to it and normalised (a
   tangent that is zero or parallel to the normal is replaced by a
   deterministic perpendicular), and the bitangent is cross(tangent,
   normal). The rest pose is stored in this frame's coordinates (u along
   the tangent, v along the normal, w along the bitangent), so a rope
   carried by its frame keeps its shape. Guides grown along the normal have
   their rest pose on the v axis. */

/* Maximum |coordinate| accepted for positions, roots and colliders (m). */
#define HF_ROPE_MAX_COORD 1.0e6f
/* Maximum |component| of gravity and wind, and maximum turbulence
   amplitude (m/s^2). */
#define HF_ROPE_MAX_ACCEL 1.0e4f

typedef enum hf_rope_mode {
    HF_ROPE_SIMULATED = 0, /* Verlet simulation (the default) */
    HF_ROPE_ANIMATED = 1   /* rest shape carried rigidly by the root frame */
} hf_rope_mode;

typedef enum hf_rope_solver {
    /* follow-the-leader (Mueller, Kim, Chentanez 2012): each pass places
       every point at its rest distance from its parent, root to tip, so
       the rope is inextensible after one pass; velocities get Mueller's
       correction scaled by ftl_damping. The default. */
    HF_ROPE_SOLVER_FTL = 0,
    /* plain Gauss-Seidel distance constraints, equal masses, pinned root;
       stretch falls with the iteration count. For comparison. */
    HF_ROPE_SOLVER_DISTANCE = 1
} hf_rope_solver;

/* Fields of hf_rope_params whose 0 is meant literally (bits for
   `explicit_zero`): a zero field otherwise asks for its default. */
typedef enum hf_rope_zero {
    HF_ROPE_ZERO_GRAVITY = 1 << 0,     /* no gravity: gravity = (0, 0, 0) */
    HF_ROPE_ZERO_DAMPING = 1 << 1,     /* damping 0 */
    HF_ROPE_ZERO_ITERATIONS = 1 << 2,  /* iterations 0: no solver pass */
    HF_ROPE_ZERO_FTL_DAMPING = 1 << 3, /* ftl_damping 0 */
    HF_ROPE_ZERO_MARGIN = 1 << 4,      /* collision_margin 0 */
    HF_ROPE_ZERO_BLEND_TIME = 1 << 5,  /* mode_blend_time 0: switch at once */
    HF_ROPE_ZERO_VOLUME = 1 << 6,      /* volume 0: no hair-hair repulsion */
    HF_ROPE_ZERO_FRICTION = 1 << 7     /* friction 0: no hair-hair friction */
} hf_rope_zero;

/* Simulation parameters. Zero-initialise and set what you need: every zero
   field means the default written beside it (gravity: all three zero). To
   mean a literal 0 where the default is not 0, set the field's bit in
   explicit_zero. hf_rope_params_init() writes the defaults themselves, for
   reading or for changing one. The defaults and units: */
typedef struct hf_rope_params {
    float gravity[3];  /* (0, -9.81, 0) m/s^2 */
    float wind[3];     /* (0, 0, 0) m/s^2: a constant extra acceleration */
    float turbulence;  /* 0 m/s^2: amplitude of a smooth per-rope random
                          acceleration added to the wind (value noise of
                          the rope index and the rope's simulated time) */
    float turbulence_frequency; /* 1 Hz: how often the turbulence changes,
                          (0, 1000] */
    float damping;     /* 0.02: fraction of velocity lost per 1/60 s of
                          simulated time, [0, 1] */
    float time_scale;  /* 1: simulated seconds per real second, (0, 100];
                          the Crystal Space plugin ran Bullet at 2 */
    float substep;     /* 1/60 s: the longest sub-step, [1e-5, 1]; one a
                          frame at 60 Hz, as TressFX steps; smaller for
                          stiffer settings or faster motion */
    int max_substeps;  /* 8: cap on sub-steps per call, [1, 1000]; when the
                          cap binds, sub-steps get longer (no time lost) */
    float max_dt;      /* 1/15 s: a longer dt is clamped to this, (0, 1] */
    int iterations;    /* 2: solver passes per sub-step, [0, 1000]; each
                          pass is a distance pass then a collision pass.
                          FTL is exact after one and does one. 0 (with
                          HF_ROPE_ZERO_ITERATIONS): no pass, so nothing
                          holds the segment lengths. */
    int solver;        /* hf_rope_solver: HF_ROPE_SOLVER_FTL */
    float ftl_damping; /* 0.9: Mueller's s_damping, [0, 1] */
    float root_stiffness; /* 0: pull of point 1 toward its rest place in
                          the root frame (along the root normal for a
                          guide), fraction of the gap closed per 1/60 s,
                          [0, 1]; 1 holds the first segment rigidly */
    float global_stiffness_root; /* 0: pull of each point toward the rest */
    float global_stiffness_tip;  /* 0: pose carried by the root frame, per
                          1/60 s, [0, 1], linear from root to tip (TressFX
                          global shape constraint) */
    float local_stiffness_root;  /* 0: pull of each segment toward its rest */
    float local_stiffness_tip;   /* 0: direction relative to its parent
                          segment, per 1/60 s, [0, 1], linear from root to
                          tip (TressFX local shape constraint) */
    float collision_margin; /* 0.002 m: particles end at least this far
                          outside every collider, [0, 1000] */
    float mode_blend_time;  /* 0.25 s: a simulated rope switched to
                          animated glides to its rest pose over this much
                          simulated time, [0, 1000]; at once needs
                          HF_ROPE_ZERO_BLEND_TIME */
    /* Hair-hair interaction, where a grid is given (hf_ropes_apply_grid,
       hf_fur_desc.grid_resolution); without one they do nothing. */
    float volume;   /* 1: repulsion, so hair keeps a volume: each point is
                       pushed from dense toward sparse hair with this many
                       times the gravity's pull (9.81 m/s^2 with no
                       gravity) where the density changes by the typical
                       density (that around the average point) across one
                       grid cell, [0, 100]; off needs HF_ROPE_ZERO_VOLUME */
    float friction; /* 0.2: hair-hair friction, so hair moves as a mass:
                       the fraction of the difference between a point's
                       velocity and that of the hair around it removed per
                       1/60 s (as much less as the hair around is sparser
                       than typical), [0, 1]; off needs
                       HF_ROPE_ZERO_FRICTION */
    int explicit_zero;      /* 0: hf_rope_zero bits, fields whose 0 is
                               literal */
    int simd; /* 0: hf_simd_level of the rope step, 0 = the best the CPU
                 runs (SSE2 or NEON, AVX2, AVX-512);
                 every level gives the same bytes. A fur uses its own
                 (hf_fur_desc.simd, hf_fur_set_kernels) */
} hf_rope_params;

/* Fill params with the defaults listed above (what a zeroed struct means).
   NULL is ignored. */
HFDEF void hf_rope_params_init(hf_rope_params *params);

/* Check every field, after the zero-means-default rule, against its
   documented range: HF_OK,
   HF_ERROR_NULL_POINTER, HF_ERROR_NON_FINITE or HF_ERROR_BAD_PARAMETER;
   diag (may be NULL) names the field. hf_ropes_step calls it. */
HFDEF hf_result hf_rope_params_validate(const hf_rope_params *params,
                                        hf_diag *diag);

typedef enum hf_collider_type {
    HF_COLLIDER_SPHERE = 0, /* centre a, radius */
    HF_COLLIDER_CAPSULE = 1 /* segment a-b, radius */
} hf_collider_type;

/* A collider in world space; the caller moves it every frame. */
typedef struct hf_collider {
    int type; /* hf_collider_type */
    float a[3], b[3];
    float radius; /* m, [0, HF_ROPE_MAX_COORD] */
} hf_collider;

/* The rope set. The caller owns the struct and the memory behind it
   (hf_ropes_init) or gets both from hf_ropes_create. Read the public
   arrays freely between calls; write them only if you know what the
   solver expects (e.g. tests). Fields marked private may change. */
typedef struct hf_ropes {
    int rope_count;
    int points;          /* per rope, >= 2 */
    float *x, *y, *z;    /* current positions, [j * rope_count + r] */
    float *px, *py, *pz; /* positions one sub-step earlier */
    float *rest_u, *rest_v, *rest_w; /* rest pose in root-frame coordinates */
    float *rest_length;  /* segment j (points j, j+1): [j * rope_count + r],
                            j < points - 1 */
    /* private */
    float *frame;   /* 24 rows of rope_count: current frame, previous one */
    float *scratch; /* per-call temporaries, rows of rope_count */
    float *last_h, *blend, *length;
    float *longest; /* each rope's longest rest segment */
    double *time;
    unsigned char *mode;
    float *glide; /* 6 point rows: a glide's start pose and velocity */
    unsigned char *root_inside; /* 1: the root sat inside a collider */
    hf_allocator allocator; /* hf_ropes_create only */
    int owned;
} hf_ropes;

/* Bytes of memory hf_ropes_init needs for rope_count ropes of `points`
   points (about 64 bytes per point plus 234 per rope). Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_COUNT (rope_count < 1 or points < 2),
   HF_ERROR_OVERFLOW. */
HFDEF hf_result hf_ropes_memory_size(int rope_count, int points,
                                     size_t *out_size);

/* Set up `ropes` on caller memory of memory_size bytes (any alignment; at
   least hf_ropes_memory_size). The memory must outlive the ropes; nothing
   is allocated, and there is nothing to free but the memory. Every rope
   starts as a zero-length rope at the origin with an identity root frame
   (tangent x, normal y), simulated: call hf_ropes_set_rest next. The
   memory holds the ropes' state and the `scratch` rows, temporaries of one
   call: after a step the state is the same bytes however the ropes were
   split into ranges, the scratch rows are not (the SIMD lanes and the
   scalar tail keep different temporaries there). Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_COUNT, HF_ERROR_OVERFLOW,
   HF_ERROR_BUFFER_TOO_SMALL; *ropes is untouched then. */
HFDEF hf_result hf_ropes_init(hf_ropes *ropes, int rope_count, int points,
                              void *memory, size_t memory_size);

/* The same, with the struct and its memory in one block from `alloc`
   (NULL = default); free it with hf_ropes_destroy. *out_ropes is set only
   on success. Errors: as hf_ropes_init, HF_ERROR_OUT_OF_MEMORY. */
HFDEF hf_result hf_ropes_create(int rope_count, int points,
                                const hf_allocator *alloc,
                                hf_ropes **out_ropes);
/* Free what hf_ropes_create returned (NULL is ignored). Ropes set up with
   hf_ropes_init are left alone: their memory is the caller's. */
HFDEF void hf_ropes_destroy(hf_ropes *ropes);

/* Give ropes [first, first + count) their rest pose and root frame. Point j
   of rope r is read at byte ((size_t)r * points + j) * position_stride of
   `positions` (world space, rope-major, 0 = 12); root r at byte
   r * root_stride (0 = 12) of root_pos, root_normal and root_tangent. Arrays
   are indexed by the absolute rope index, so pass the same pointers for
   every range. Stores the rest pose in root-frame coordinates (a
   coordinate below 2^-40 m as 0, as a root frame's components below 2^-40:
   rounding noise whose products would be slow subnormal floats) and the
   rest segment lengths (zero-length segments are allowed), and puts the
   rope at rest (as hf_ropes_reset). Errors: HF_ERROR_NULL_POINTER,
   HF_ERROR_BAD_RANGE, HF_ERROR_BAD_STRIDE, HF_ERROR_NON_FINITE,
   HF_ERROR_BAD_PARAMETER (a coordinate beyond HF_ROPE_MAX_COORD),
   HF_ERROR_DEGENERATE (a zero normal); nothing is written then. */
HFDEF hf_result hf_ropes_set_rest(hf_ropes *ropes, int first, int count,
                                  const float *positions, int position_stride,
                                  const float *root_pos,
                                  const float *root_normal,
                                  const float *root_tangent, int root_stride);

/* Set this frame's root frames of ropes [first, first + count), read as in
   hf_ropes_set_rest. The next hf_ropes_step moves each root from the frame
   it ended the last step with to this one across its sub-steps, so a fast
   root does not yank its rope in one sub-step. Calling it twice before a
   step keeps the last. Errors: HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE,
   HF_ERROR_BAD_STRIDE, HF_ERROR_NON_FINITE, HF_ERROR_BAD_PARAMETER,
   HF_ERROR_DEGENERATE (zero normal); nothing is written then. */
HFDEF hf_result hf_ropes_set_roots(hf_ropes *ropes, int first, int count,
                                   const float *root_pos,
                                   const float *root_normal,
                                   const float *root_tangent, int root_stride);

/* Advance ropes [first, first + count) by dt seconds (times
   params->time_scale). dt above params->max_dt is clamped to it (HF_OK);
   dt zero, negative, NaN or infinite returns HF_ERROR_BAD_TIME_STEP and
   changes nothing. count 0 is a valid empty range. `colliders` may be NULL
   when collider_count is 0. When the call returns, every non-root point of
   a simulated rope is at least radius + collision_margin from every
   collider, provided the colliders inflated by the margin do not overlap
   one another, and every segment keeps its rest length (the follow-the-
   leader solver turns a point about its parent until it clears every
   collider; where no direction clears them all, the direction with the
   least penetration wins, length kept). The root point sits on the skin
   and is exempt; a collider that holds a rope's root (deeper than the
   margin) is shrunk, for that rope, to the root's distance from its axis (hf_ropes_roots_inside
   counts such ropes). The distance solver pushes points straight out, as
   before, and with iterations 0 (HF_ROPE_ZERO_ITERATIONS) nothing holds
   the lengths. Animated ropes ignore colliders. A rope that an unstable setting throws further than
   8 * length + 0.01 m from its root is reset to its rest pose, so no
   output is ever NaN. Errors: HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE,
   HF_ERROR_BAD_COUNT (collider_count < 0), HF_ERROR_BAD_TIME_STEP,
   HF_ERROR_NON_FINITE / HF_ERROR_BAD_PARAMETER (params or colliders);
   nothing is written then. No allocation. */
HFDEF hf_result hf_ropes_step(hf_ropes *ropes, int first, int count,
                              float dt, const hf_rope_params *params,
                              const hf_collider *colliders,
                              int collider_count);

/* Switch ropes [first, first + count) between simulation and animation on
   the fly, without a jump in position or velocity. To HF_ROPE_SIMULATED:
   immediate; the rope keeps the velocity it has (an animated rope that of
   its animated motion, a gliding one that of its glide). To
   HF_ROPE_ANIMATED: the rope glides, kinematically (no colliders), over
   params->mode_blend_time: each point follows, in root-frame coordinates,
   the cubic Hermite curve from the pose and velocity it had to its rest
   place, reached at rest, the rope kept at its rest lengths; so its
   velocity turns smoothly from the simulation's to the animation's; then
   it is carried rigidly. The same mode again changes nothing. `mode` is an
   hf_rope_mode (an int so that a bad value is defined in C++). Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE, HF_ERROR_BAD_PARAMETER
   (unknown mode). */
HFDEF hf_result hf_ropes_set_mode(hf_ropes *ropes, int first, int count,
                                  int mode);

/* Teleport ropes [first, first + count): put every point at its rest place
   in the current root frame, with zero velocity; the next step starts from
   there (no interpolation from an old frame). Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE. */
HFDEF hf_result hf_ropes_reset(hf_ropes *ropes, int first, int count);

/* How many ropes of [first, first + count) had their root inside a
   collider (deeper than collision_margin below its surface) at their
   last hf_ropes_step. Such a collider is, for that rope, shrunk to the
   root's distance from its axis, so the rope stays inextensible and grows
   out of the proxy; a count above 0 usually means a proxy larger than the
   body it stands for: shrink it. Errors: HF_ERROR_NULL_POINTER,
   HF_ERROR_BAD_RANGE. */
HFDEF hf_result hf_ropes_roots_inside(const hf_ropes *ropes, int first,
                                      int count, int *out_count);

/* The largest relative length error |length - rest| / rest over every
   segment of ropes [first, first + count) with a non-zero rest length
   (0.005 = 0.5 %); 0 for an empty range. Errors: HF_ERROR_NULL_POINTER,
   HF_ERROR_BAD_RANGE; *out_stretch untouched then. */
HFDEF hf_result hf_ropes_max_stretch(const hf_ropes *ropes, int first,
                                     int count, float *out_stretch);

/* Copy the current positions of ropes [first, first + count) to `out`,
   rope-major: point j of rope r goes to byte
   ((size_t)r * points + j) * stride (0 = 12), absolute rope index. Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE, HF_ERROR_BAD_STRIDE. */
HFDEF hf_result hf_ropes_get_positions(const hf_ropes *ropes, int first,
                                       int count, float *out, int stride);
/* The same into a buffer that holds exactly ropes [first, first + count):
   point j of rope first + i goes to byte ((size_t)i * points + j) * stride
   (0 = 12). Same errors. */
HFDEF hf_result hf_ropes_copy_range(const hf_ropes *ropes, int first,
                                    int count, float *out, int stride);

/* Take the current pose of ropes [first, first + count) as their rest
   pose, in their current root frames (the frame of their last step), and
   put them at rest there: the way to keep a shape gravity settled (step
   the ropes for a while, then call this), so shape stiffness holds the
   draped shape instead of the grown one. Rest lengths are kept. Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE. */
HFDEF hf_result hf_ropes_rest_from_pose(hf_ropes *ropes, int first,
                                        int count);

/* ---- 6.9 hair-hair interaction: the grid -------------------------------- */

/* A grid of resolution^3 nodes over the ropes' points, rebuilt every
   frame from where the points are (hf_grid_build) and read by
   hf_ropes_apply_grid before the step: each node holds the points near it
   (trilinear weights) and their momentum. It gives each point the
   density and the velocity of the hair around it (its own share taken
   out), for a repulsion from dense toward sparse hair (volume) and a
   friction toward the hair's common motion (friction), the grid methods
   of Petrovic et al. 2005 and McAdams et al. 2009 at one grid a frame.
   The grid is a cube over the roots grown by each rope's length, so
   resolution 32 on a head with 0.3 m hair gives cells of about 2.5 cm.
   The caller owns the struct and its memory (hf_grid_init) or gets both
   from hf_grid_create. Fields marked private may change. */
typedef struct hf_grid {
    int resolution;  /* nodes along each axis, [4, HF_GRID_MAX_RESOLUTION] */
    float *node;     /* 4 floats a node (x fastest, then y, then z): the
                        points' weight, then their momentum (weight x
                        velocity, m/s) */
    int simd;        /* hf_grid_build's kernels: HF_SIMD_* (0 = the best
                        the CPU has); every level gives the same bytes */
    /* private */
    float *slab;     /* per z layer: the cube (origin, spacing) and the
                        sums of the weight and of its square */
    hf_allocator allocator; /* hf_grid_create only */
    int owned;
} hf_grid;

#define HF_GRID_MAX_RESOLUTION 128

/* Bytes of memory hf_grid_init needs for a grid of resolution^3 nodes
   (16 per node plus 24 per layer). Errors: HF_ERROR_NULL_POINTER,
   HF_ERROR_BAD_COUNT (resolution outside [4, HF_GRID_MAX_RESOLUTION]). */
HFDEF hf_result hf_grid_memory_size(int resolution, size_t *out_size);
/* Set up an empty grid (one that moves nothing) on caller memory of at
   least hf_grid_memory_size bytes (any alignment). Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_COUNT, HF_ERROR_BUFFER_TOO_SMALL;
   *grid untouched then. */
HFDEF hf_result hf_grid_init(hf_grid *grid, int resolution, void *memory,
                             size_t memory_size);
/* The same, the struct and its memory in one block from `alloc` (NULL =
   default); free it with hf_grid_destroy. Errors: as hf_grid_init,
   HF_ERROR_OUT_OF_MEMORY. */
HFDEF hf_result hf_grid_create(int resolution, const hf_allocator *alloc,
                               hf_grid **out_grid);
/* Free what hf_grid_create returned (NULL is ignored). */
HFDEF void hf_grid_destroy(hf_grid *grid);

/* Rebuild z layers [first, first + count) of the grid (0 .. resolution -
   1) from the points of ropes [0, rope_count) as they are now: call it
   after the roots are set and before hf_ropes_apply_grid, every frame.
   Each call reads every one of those ropes' points and writes only its
   own layers, so layers built on several threads give the same bytes as
   one call. Points outside the cube (a rope stretched beyond its length)
   are left out. Errors: HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE (the
   layers, or rope_count outside [0, ropes->rope_count]); nothing is
   written then, as for HF_ERROR_BAD_PARAMETER (grid->simd not a level).
   No allocation. */
HFDEF hf_result hf_grid_build(hf_grid *grid, const hf_ropes *ropes,
                              int rope_count, int first, int count);

/* Before hf_ropes_step of ropes [first, first + count), change the
   velocity of their simulated points (the root excepted) by the hair-hair
   forces of params->volume and params->friction over dt (clamped and
   scaled as hf_ropes_step does), from a grid built this frame with every
   layer (hf_grid_build). The ropes stay inextensible: the step's solver
   keeps their lengths. A grid that is empty, or points outside it, get
   no force. Errors: HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE,
   HF_ERROR_BAD_TIME_STEP, HF_ERROR_NON_FINITE / HF_ERROR_BAD_PARAMETER
   (params); nothing is written then. No allocation. */
HFDEF hf_result hf_ropes_apply_grid(hf_ropes *ropes, int first, int count,
                                    float dt, const hf_rope_params *params,
                                    const hf_grid *grid);

/* ---- 7. interpolation and LOD ------------------------------------------- */

/* Every strand and every guide has the same number of points P, 2 <= P <=
   HF_MAX_POINTS, stored as packed x, y, z: point j of strand s is at floats
   (s * P + j) * 3. (The cap lets per-frame kernels keep per-point scratch on
   the stack instead of allocating.) */
#define HF_MAX_POINTS 256


typedef struct hf_interp_params {
    int points_per_strand; /* P, >= 2 (required) */
    /* Clumping toward the guide of largest weight (the look of TressFX's
       follow hairs): point j moves by clump * j / (P - 1) of the way to
       that guide's point, so roots stay and tips gather. 0 = none (the
       term is skipped, not multiplied by 0), 1 = tips on the guide. */
    float clump;
    /* The strand out_points starts at: strand s is written at
       out_points + (s - out_first) * P * 3. 0: absolute strand index; set
       it to `first` to write a range into a buffer that holds exactly that
       range (first < out_first is HF_ERROR_BAD_RANGE). */
    int out_first;
    int simd; /* hf_simd_level (0..4); 0 = the best the CPU runs (same
                 bytes) */
    /* The stores: 0 = by size, streaming (non-temporal) stores, which
       skip the cache, where the call writes more than
       HF_STREAM_MIN_BYTES (4 MiB): ordinary stores would read each line
       in first and push the guides out (measured, into 64-byte aligned
       buffers: 1.7x faster for 36,700 strands of 16 points, 2x for
       100,000; 3 % slower for 3,670; a frame split into small calls:
       set 1 or 2); 1 = streaming; 2 = ordinary stores. Streaming
       needs P a multiple of 4 (every strand 16-byte aligned, with
       out_points), else the stores are ordinary. Same bytes either way.
       Another value, or a simd outside 0..4, is HF_ERROR_BAD_PARAMETER. */
    int nontemporal;
} hf_interp_params;

/* Interpolate strands [first, first + count) from guide points. Point j of
   strand s is
       root + scale * (sum_k w_k g_k[j] - root),   root = sum_k w_k g_k[0]
   so the strand keeps its own root on the guide triangle (the surface) and
   its own length (scale) while its guides stay alike (guides that part
   make the blend shorter: hf_fur_desc.keep_length restores the lengths),
   and equals guide k exactly when w_k = 1 and scale = 1; then clumping. Writes P * 3 floats per strand at
   out_points + (s - out_first) * P * 3 and nothing else, so ranges can run on separate
   threads. Use the same call for LOD guides that are not simulated: their
   bindings name pure guides, and out_points may be the guide array itself
   (the LOD guides' part of it) as long as no binding names a guide inside
   the written range. No allocation. Errors: NULL pointers, P < 2, count <
   0, first < 0, a guide index >= guide_count (HF_ERROR_INDEX_OUT_OF_RANGE),
   non-finite weights, scale, clump or guide point (HF_ERROR_NON_FINITE),
   clump outside [0, 1], a scale or guide coordinate beyond +-HF_MAX_ABS, or
   a simd or nontemporal that is not one (HF_ERROR_BAD_PARAMETER), first <
   out_first (HF_ERROR_BAD_RANGE);
   nothing written then. The caller sizes out_points for strand
   first + count - 1 - out_first. */
HFDEF hf_result hf_interpolate(const float *guide_points, int guide_count,
                               const hf_strand_binding *bindings, int first,
                               int count, const hf_interp_params *params,
                               float *out_points);

/* Level of detail. `lod` in [0, 1] draws a prefix of the strands (they are
   stored in LOD order): round(lod * total) (halves up, exact for every
   int total), at least 1 when lod > 0 and total > 0; 0 for lod <= 0 or
   NaN; total for lod >= 1. */
HFDEF int hf_lod_strand_count(int total, float lod);
/* Ribbon width multiplier that keeps coverage constant: sqrt(total / drawn);
   1 when drawn <= 0 or drawn >= total. */
HFDEF float hf_lod_width_scale(int total, int drawn);
/* Camera distance to a LOD value: 1 up to full_detail_distance, then
   (full_detail_distance / distance)^2 (strands per projected area stay
   constant), and 0 from cull_distance on. Non-finite or negative input
   gives 1 (draw everything rather than nothing). */
HFDEF float hf_lod_from_distance(float distance, float full_detail_distance,
                                 float cull_distance);

/* ---- 8. ribbons --------------------------------------------------------- */

/* How a stream stores each component. The compact formats halve or
   quarter the bytes a frame writes, which is most of a ribbon's cost; GL
   reads them with glVertexAttribPointer(type, normalized): GL_HALF_FLOAT,
   GL_SHORT/GL_UNSIGNED_SHORT or GL_BYTE/GL_UNSIGNED_BYTE, normalized
   GL_TRUE for the *NORM formats. Values outside a format's range are
   clamped to it, so no vertex gets an infinity. */
typedef enum hf_format {
    HF_FORMAT_F32 = 0,     /* float (the default) */
    HF_FORMAT_F16 = 1,     /* IEEE half, round to nearest even, |x| <= 65504 */
    HF_FORMAT_SNORM16 = 2, /* int16 round(x * 32767), x clamped to [-1, 1] */
    HF_FORMAT_UNORM16 = 3, /* uint16 round(x * 65535), x clamped to [0, 1] */
    HF_FORMAT_SNORM8 = 4,  /* int8 round(x * 127), x clamped to [-1, 1] */
    HF_FORMAT_UNORM8 = 5   /* uint8 round(x * 255), x clamped to [0, 1] */
} hf_format;

/* Bytes per component of a format (4, 2 or 1); 0 for an unknown one. */
HFDEF int hf_format_bytes(int format /* hf_format */);

/* One output attribute: `data` points at the attribute of vertex 0, `stride`
   is the byte step between vertices (0 = packed: components times
   hf_format_bytes). data = NULL skips the attribute. Interleaved vertices:
   every stream points into one buffer with the vertex size as stride.
   Separate buffers: one per stream. Components are written in native byte
   order, with no alignment required. */
typedef struct hf_stream {
    void *data;
    int stride;
    int format; /* hf_format; 0 = HF_FORMAT_F32 */
} hf_stream;

/* Where ribbon vertices go. Strand s, point j, side k (0 = -side, 1 = +side)
   is vertex (s * P + j) * 2 + k (s counted from hf_ribbon_params'
   out_first). Zero-initialise it, then set the streams you want. */
typedef struct hf_ribbon_output {
    hf_stream position; /* x, y, z: (p - position_origin) / position_scale */
    hf_stream tangent;  /* x, y, z: unit, root to tip */
    hf_stream texcoord; /* u, v, t: root UV of the strand, and t =
                           j / (P - 1) along it (0 root, 1 tip) */
    hf_stream color;    /* r, g, b, a: strand colour (white when
                           none is given), alpha = the strand's alpha times
                           the root-to-tip fade */
    hf_stream color3d;  /* x, y: the "3D colour" coordinates: x = the
                           strand's value in the grayscale index map, y = t */
    /* Positions are written relative to an origin and in units of a scale
       (0 means 1): the defaults write world positions. For a compact
       position format, set the origin to the hair's centre and the scale
       to a radius that holds it (SNORM16 then keeps scale / 32767, 15 um
       for 0.5 m; F16 keeps 11 bits relative), and undo both in the vertex
       shader. The origin is finite and within +-HF_MAX_ABS; the scale is 0
       or within [1 / HF_MAX_ABS, HF_MAX_ABS]. */
    float position_origin[3];
    float position_scale;
} hf_ribbon_output;

/* Per-strand inputs, all optional (NULL = the default in brackets). Index s
   is the absolute strand index, as for points. */
typedef struct hf_ribbon_strands {
    const float *points;     /* P * 3 floats per strand (required) */
    const float *root_uv;    /* 2 per strand [0, 0] */
    const float *color;      /* 4 per strand, r g b a [1, 1, 1, 1] (the
                                layout hf_strand_colors writes) */
    const float *color3d_x;  /* 1 per strand [0] */
    const float *width;      /* 1 per strand: a width multiplier [1];
                                negative or non-finite reads as 0, and
                                a vertex's half width (times the
                                multiplier) is at most HF_MAX_ABS */
} hf_ribbon_strands;

/* How the GPU points (hf_ribbon_points, hf_fur_points,
   hf_fur_interpolate_points) store a point. */
typedef enum hf_point_format {
    HF_POINT_F32 = 0,    /* x, y, z, half width: 4 floats, 16 bytes */
    HF_POINT_COMPACT = 1 /* 8 bytes: x, y, z as SNORM16 of
                            (p - point_origin) / point_scale, then the half
                            width as an IEEE half (F16); in GL an RGBA16I
                            texture buffer, see examples/ribbon_expand.glsl.
                            Position error at most point_scale / 65534 (15
                            um for a 1 m box: scale 1), half width 11 bits
                            relative */
} hf_point_format;

typedef struct hf_ribbon_params {
    int points_per_strand; /* P, >= 2 (required) */
    /* Camera: by default perspective from `eye`; orthographic != 0 uses the
       direction the camera looks, `view_dir` (need not be unit). */
    float eye[3];
    int orthographic;
    float view_dir[3];
    /* Full ribbon width at root and tip, in metres, and the taper
       curve width(t) = root + (tip - root) * t^taper_power. Widths must be
       finite and >= 0; both 0 means HF_RIBBON_DEFAULT_ROOT_WIDTH and
       HF_RIBBON_DEFAULT_TIP_WIDTH (a pointed tip: a root width and tip 0);
       taper_power 0 means 1 (linear). */
    float root_width, tip_width;
    float taper_power;
    float width_scale; /* multiplier, e.g. hf_lod_width_scale; 0 means 1 */
    /* alpha at root and tip in [0, 1], linear in t; both 0 means 1 and 1
       (opaque). Widths and width_scale are at most HF_MAX_ABS. */
    float alpha_root, alpha_tip;
    /* The strand the output buffers start at: strand s is written as if
       it were strand s - out_first (vertex ((s - out_first) * P + j) * 2
       + k, point (s - out_first) * P + j). 0: outputs indexed by absolute
       strand. Set it to `first` to write a range into a buffer that holds
       exactly that range; first < out_first is HF_ERROR_BAD_RANGE. */
    int out_first;
    /* The stores: streaming (non-temporal) stores skip the cache, the
       right stores for write-combined memory (a mapped GPU buffer, where
       vertices usually go) and for outputs far larger than the cache.
       0 = by size: streaming where the call writes more than
       HF_STREAM_MIN_VERTEX_BYTES (8 MiB), ordinary stores below, which
       leave a smaller output in the cache (the hf_fur_* calls: where the
       fur's drawn strands would, so every range of a split frame
       chooses alike; for hf_ribbons and hf_ribbon_points split into
       small calls, set 1 or 2); 1 = streaming (set it for a mapped
       buffer whatever the size); 2 = ordinary stores.
       hf_ribbon_points can always stream; hf_ribbons when its streams
       are one interleaved buffer whose vertex they fill exactly (the
       usual layout: position, tangent, texcoord) and a strand's
       vertices take at most 8 KiB and start 16-byte aligned (the
       buffer aligned so, and 2 P vertices a multiple of 16 bytes: P
       even for 36-byte vertices), else it uses ordinary stores. Same
       bytes either way. Another value, or a simd outside 0..4, is
       HF_ERROR_BAD_PARAMETER. */
    int nontemporal;
    /* hf_simd_level of hf_ribbons and hf_ribbon_points; 0 = the best
       the CPU runs (same bytes). Ribbons: SSE2 or NEON; AVX2 for every
       layout whose streams do not overlap inside a vertex, else SSE2;
       the AVX-512 level runs AVX2 but for streamed float vertices of
       36 or 24 bytes (position, tangent and texcoord, or the first two)
       in a buffer aligned to 64 bytes with points_per_strand a multiple
       of 8, which it writes in whole 64-byte lines (with a multiple of
       16, their frames sixteen points at a time), and for the compact
       16-byte vertex (16-bit position and texcoord, 8-bit tangent) with
       a multiple of 16, frames and vertices sixteen points at a time.
       GPU points: SSE2 or NEON; AVX2, eight points a group where
       points_per_strand is a multiple of 8 (else two a vector); AVX-512,
       sixteen a group with a multiple of 16, else AVX2. */
    int simd;
    /* GPU points only: hf_point_format, 0 = HF_POINT_F32; for
       HF_POINT_COMPACT the box the positions are stored in: origin
       (finite, within +-HF_MAX_ABS) and half extent point_scale (0 means
       1, else within [1 / HF_MAX_ABS, HF_MAX_ABS]); a point outside the
       box is clamped to its surface. Compact points go through a 4 KiB
       stage on the stack and are encoded from there (SSE2, AVX2 or NEON):
       the same bytes at every level. Another format is
       HF_ERROR_BAD_FORMAT. */
    int point_format;
    float point_origin[3];
    float point_scale;
} hf_ribbon_params;

/* Ribbon widths a zeroed hf_ribbon_params gets, in metres: fur on a head
   seen from a metre or two. */
#define HF_RIBBON_DEFAULT_ROOT_WIDTH 0.001f
#define HF_RIBBON_DEFAULT_TIP_WIDTH 0.00025f

/* Camera-facing ribbons for strands [first, first + count). For point j
   with unit tangent t_j (central difference, one-sided at the ends) and
   view vector v_j (eye - p_j, or -view_dir), the side is
   s_j = normalize(cross(t_j, v_j)) and the vertices are p_j -/+ s_j * w_j / 2.
   Never NaN: a zero-length segment reuses the previous tangent (points
   before the first that has one take that one; a strand with no length
   uses (0, 1, 0)). The side is perpendicular to t_j and v_j within 1e-5
   wherever they are not parallel (views within about half a degree of
   the tangent are computed in double); where t_j is parallel to v_j (to 1e-6) or the
   eye sits on p_j, the side of the previous point is reused (before the
   first point that has one: the next point's), made perpendicular to t_j
   and renormalised; a strand with no side anywhere uses a fixed
   perpendicular of its tangent. A strand with a NaN or infinite point is
   written collapsed: every vertex at the origin with zero width, so it
   draws nothing. Writes exactly 2 * P vertices per strand
   into each non-NULL stream, in its format; no allocation. Errors: NULL
   params, points or out, P < 2, first < 0, count < 0, negative or
   non-finite widths, non-finite eye, view_dir, scale or alpha, a zero
   view_dir in orthographic mode, a simd or nontemporal that is not one,
   first < out_first (those as for every call); an unknown
   stream format (HF_ERROR_BAD_FORMAT), a negative stride or one smaller
   than the stream's element, or two streams that share a byte between
   different vertices of the call (HF_ERROR_BAD_STRIDE; sharing inside a
   vertex is allowed, the later stream's bytes win in the order position,
   tangent, texcoord, color, color3d), a bad position origin or scale;
   nothing written then. */
HFDEF hf_result hf_ribbons(const hf_ribbon_strands *strands, int first,
                           int count, const hf_ribbon_params *params,
                           const hf_ribbon_output *out);

/* The GPU-expansion path: instead of 2 * P vertices, write each point once
   as (x, y, z, half width) in 4 floats, a third of the bytes of a minimal
   ribbon; examples/ribbon_expand.glsl builds the same ribbons in a vertex
   shader. Point j of strand s goes to out4 + ((s - out_first) * P + j) *
   4, or with params->point_format HF_POINT_COMPACT in 8 bytes, at byte
   ((s - out_first) * P + j) * 8 of out4 (half the bytes). Same
   parameters and errors as hf_ribbons (the camera fields are unused). */
HFDEF hf_result hf_ribbon_points(const hf_ribbon_strands *strands, int first,
                                 int count, const hf_ribbon_params *params,
                                 float *out4);

typedef enum hf_topology {
    HF_TRIANGLES = 0,     /* 6 (P - 1) indices per strand */
    HF_STRIP_RESTART = 1  /* 2 P indices and one 0xFFFFFFFF per strand:
                             draw with primitive restart on */
} hf_topology;

/* ---- 8.9 indices -------------------------------------------------------- */

/* The number of indices for `strand_count` strands of P points, or -1 if
   it does not fit in an int (or P < 2, strand_count < 0, bad topology). */
HFDEF long long hf_ribbon_index_count(int strand_count, int points_per_strand,
                                      int topology /* hf_topology */);
/* Index buffer for strands [0, strand_count), matching the vertex numbering
   of hf_ribbons, counter-clockwise seen from the side the +side vector and
   the tangent span towards the camera. The topology does not change per
   frame: call once. `capacity` is the size of out in indices. Errors
   (nothing written): HF_ERROR_NULL_POINTER (out NULL, even for no
   strands), HF_ERROR_BAD_COUNT (strand_count < 0 or P < 2),
   HF_ERROR_BAD_PARAMETER (not an hf_topology), HF_ERROR_BUFFER_TOO_SMALL
   (capacity below hf_ribbon_index_count), HF_ERROR_OVERFLOW (vertex
   numbers beyond 32 bits). */
HFDEF hf_result hf_ribbon_indices(int strand_count, int points_per_strand,
                                  int topology /* hf_topology */,
                                  uint32_t *out, long long capacity);

/* 16-bit indices, for hosts that draw 16-bit index buffers (WebGL 1, many
   mobile paths): draw the strands in chunks of at most
   hf_ribbon_chunk_strands strands, each chunk's vertices written into a
   buffer of their own (hf_ribbon_params.out_first = the chunk's first
   strand). Every chunk then uses the same index buffer, made once by
   hf_ribbon_indices16 for the largest chunk (a shorter last chunk draws a
   prefix of it: hf_ribbon_index_count of its strands).
   hf_ribbon_chunk_strands gives the most strands whose vertices fit 16-bit
   numbers below 0xFFFF (the restart index, which no vertex takes); 0 for
   P outside 2 .. HF_MAX_POINTS or a bad topology. */
HFDEF int hf_ribbon_chunk_strands(int points_per_strand,
                                  int topology /* hf_topology */);
/* As hf_ribbon_indices, into uint16_t: the restart index is 0xFFFF; more
   strands than hf_ribbon_chunk_strands is HF_ERROR_OVERFLOW. */
HFDEF hf_result hf_ribbon_indices16(int strand_count, int points_per_strand,
                                    int topology /* hf_topology */,
                                    uint16_t *out, long long capacity);

/* ---- 9. LUT baking ------------------------------------------------------ */
/* Marschner M and N lookup textures. */

/* Bakes, on the CPU, the two lookup textures of the Marschner hair shader
   (Marschner et al. 2003, in the two-texture layout of the Nalu demo):

     M (n x n RGBA float), indexed by u = sin(theta_i) * 0.5 + 0.5,
       v = sin(theta_r) * 0.5 + 0.5:  R = M_R, G = M_TT, B = M_TRT (Gaussian
       densities per radian of theta_h), A = cos(theta_d).
     N (n x n RGBA float), indexed by u = cos(theta_d) * 0.5 + 0.5,
       v = cos(phi) * 0.5 + 0.5:  R = N_R, G = N_TT, B = N_TRT, A = 1.

   The shader then computes
       S = (M.r * N.r + M.g * N.g + M.b * N.b) / max(M.a * M.a, cos2Min)
   with uv(N) = (M.a, cosPhi) * 0.5 + 0.5 (docs/luts.md has the GLSL).

   Layout: texel (i, j) is column i (u), row j (v), and samples the texel
   centre ((i + 0.5) / n, (j + 0.5) / n). Float c of texel (i, j) is at
   index 4 * (j * n + i) + c; row 0 (v = 0) comes first, as glTexImage2D
   expects it. Sample with linear filtering and clamp-to-edge. Every value
   is computed in double precision and rounded to float once. The exact
   model (the "contract": roots, Fresnel terms, absorption, clamps) is
   docs/marschner-spec.md; the TRT lobe is the simplified one (no caustic fade or
   glints), with its caustic spike bounded by clamping 2|dPhi/dh| >= 0.02.

   The bake functions take a row range (first_row, row_count) and write only
   those rows of the full texture, so several threads can fill one buffer;
   the bytes do not depend on how the rows are split. They allocate
   nothing. Cost: about n^2 texels at a few dozen transcendental calls each
   (docs/luts.md has timings); per call there is also O(n) setup, so pass
   large row ranges rather than one row at a time.

   Two fibres (hf_lut_params.model). HF_LUT_MARSCHNER, the default, is the
   paper's model above, byte for byte as before. HF_LUT_ENERGY is an
   energy-conserving fibre: a longitudinal function normalised for every
   incident direction (d'Eon et al. 2011, the Bessel-function lobe, with
   the paper's shifts and widths), the azimuthal terms computed from the
   incident inclination theta_i (as Chiang et al. 2016 and pbrt do), and
   the light of every longer path (p >= 3: TRRT, ...) as a fourth lobe.
   A fibre that absorbs nothing scatters exactly the light it receives;
   hf_lut_furnace integrates baked textures to show it. Its textures:

     M (n x n RGBA float), indexed as above: R, G, B, A = M_R, M_TT,
       M_TRT, M_p>=3, densities per unit of sin(theta_r);
     N (n x n RGBA float), indexed by u = cos(theta_i) * 0.5 + 0.5,
       v = cos(phi) * 0.5 + 0.5: R, G, B, A = N_R, N_TT, N_TRT, N_p>=3;
     S = dot(M, N) / max(cos(theta_r), 1e-2).

   Along v each texel of these two holds the mean of its lobe over the
   texel's cell (not the value at its centre), so the baked tables carry
   the fibre's energy exactly at any size: the TRT caustic becomes a
   finite bump. hf_lut_bake_dual bakes Zinke et al.'s (2008) dual
   scattering tables of the energy-conserving fibre. The exact formulas:
   docs/marschner-spec.md sections 14 to 16. */

/* Which fibre the textures describe. */
typedef enum hf_lut_model {
    HF_LUT_MARSCHNER = 0, /* the paper's model (default) */
    HF_LUT_ENERGY = 1     /* energy-conserving: M normalised per direction,
                             N from theta_i, a p >= 3 lobe */
} hf_lut_model;

/* How the azimuthal exit angle Phi(p, gamma) is computed. */
typedef enum hf_lut_variant {
    HF_LUT_CUBIC = 0, /* the paper's cubic approximation of gamma_t (default) */
    HF_LUT_EXACT = 1  /* the exact Phi, roots refined to 1e-12 rad */
} hf_lut_variant;

#define HF_LUT_MAX_SIZE 4096 /* largest accepted texture size n */

/* Fields of hf_lut_params whose 0 is meant literally (bits for
   `explicit_zero`). */
typedef enum hf_lut_zero {
    HF_LUT_ZERO_ALPHA_R = 1 << 0,    /* alpha_r_deg 0: no longitudinal shift */
    HF_LUT_ZERO_SIGMA_A = 1 << 1,    /* sigma_a 0: no absorption */
    HF_LUT_ZERO_SIGMA_A_RGB = 1 << 2 /* a zero sigma_a_rgb component is 0 */
} hf_lut_zero;

/* Parameters of the bake. Zero-initialise and set what you need: every
   zero field means the default in brackets; to mean a literal 0 where the
   default is not 0, set the field's bit in explicit_zero.
   hf_lut_params_init() writes the defaults themselves. Angles are in
   degrees, as in the paper's Table 1; the TT and TRT shifts and widths are
   derived (alpha_TT = -alpha_R / 2, alpha_TRT = -3 alpha_R / 2, beta_TT =
   beta_R / 2, beta_TRT = 2 beta_R). The fields are double because the
   bake is computed in double: 1.55f is 1.5499999523, which moves some N
   values by up to 8e-7 relative. */
typedef struct hf_lut_params {
    double eta;            /* index of refraction, 1.2 .. 3 (1.55) */
    double alpha_r_deg;    /* longitudinal shift of R, any finite (-7.5) */
    double beta_r_deg;     /* longitudinal width of R, > 0 (7.5) */
    double sigma_a;        /* absorption per fibre radius, >= 0 (0.2) */
    double sigma_a_rgb[3]; /* per-channel absorption, only for
                              hf_lut_bake_n_rgb, each >= 0 (sigma_a) */
    int variant; /* hf_lut_variant: HF_LUT_CUBIC (0) or HF_LUT_EXACT */
    int size;             /* n, both textures n x n, 1 .. 4096 (256) */
    int explicit_zero;    /* hf_lut_zero bits (0) */
    int model;            /* hf_lut_model: HF_LUT_MARSCHNER (0) or
                             HF_LUT_ENERGY */
} hf_lut_params;

/* Fill `p` with the defaults above (what a zeroed struct means: eta 1.55,
   alpha_R -7.5, beta_R 7.5, sigma_a 0.2, sigma_a_rgb 0.2 each, cubic, size
   256, the paper's model). NULL is ignored. */
HFDEF void hf_lut_params_init(hf_lut_params *p);

/* Check a parameter block. Returns HF_OK, or: HF_ERROR_NULL_POINTER (p is
   NULL), HF_ERROR_NON_FINITE (a float field is NaN or infinite),
   HF_ERROR_BAD_PARAMETER (eta outside [1.2, 3], beta_r_deg <= 0, sigma_a or
   a sigma_a_rgb component < 0, unknown variant or model),
   HF_ERROR_BAD_COUNT (size outside [1, HF_LUT_MAX_SIZE]). `diag` (may be
   NULL) names the field. */
HFDEF hf_result hf_lut_validate(const hf_lut_params *p, hf_diag *diag);

/* Bake rows [first_row, first_row + row_count) of the M texture into
   `out`, which is the caller's FULL texture of 4 * size * size floats;
   other rows are not touched. row_count 0 is a valid empty range. Errors
   (nothing written): as hf_lut_validate, HF_ERROR_NULL_POINTER for a NULL
   out, HF_ERROR_BAD_RANGE for first_row < 0, row_count < 0 or
   first_row + row_count > size. M is symmetric: texel (i, j) == (j, i).
   A density that would exceed FLT_MAX (only for beta_r_deg below about
   1e-37) is stored as FLT_MAX. With model HF_LUT_ENERGY: the M texture of
   that fibre (RGBA = M_R, M_TT, M_TRT, M_p>=3, each texel the mean over
   its cell of sin(theta_r)), not symmetric; it costs 30 to 50 times the
   paper's M (about 0.1 s at 256: a Bessel function per quadrature node). */
HFDEF hf_result hf_lut_bake_m(const hf_lut_params *p, int first_row,
                              int row_count, float *out);

/* The same for the N texture (R = N_R, G = N_TT, B = N_TRT, A = 1),
   absorption sigma_a. Same buffer size, range rules and errors. With
   model HF_LUT_ENERGY: that fibre's N (u = cos(theta_i) * 0.5 + 0.5,
   RGBA = N_R, N_TT, N_TRT, N_p>=3, each texel the mean over its cell of
   cos(phi); absorption along the chord, 2 cos(gamma_t) / cos(theta_t)
   fibre radii, so a sigma_a absorbs about half what it does in the
   paper's model). */
HFDEF hf_result hf_lut_bake_n(const hf_lut_params *p, int first_row,
                              int row_count, float *out);

/* Per-RGB absorption (for coloured hair): rows of two extra textures with
   the layout and texel positions of N,
       out_tt_rgb  = (N_TT(sr),  N_TT(sg),  N_TT(sb),  N_R)
       out_trt_rgb = (N_TRT(sr), N_TRT(sg), N_TRT(sb), N_R)
   where (sr, sg, sb) = p->sigma_a_rgb and N_x(s) is bit for bit the
   channel hf_lut_bake_n writes with sigma_a = s. Shader:
       S_rgb = (M.r * NTT.a + M.g * NTT.rgb + M.b * NTRT.rgb)
               / max(M.a * M.a, cos2Min).
   Both outputs are full textures of 4 * size * size floats each and must
   not overlap. Errors as hf_lut_bake_n (either output NULL), and
   HF_ERROR_BAD_PARAMETER for model HF_LUT_ENERGY, whose four lobes do not
   fit two textures: bake its N once per channel (hf_lut_bake_n with
   sigma_a set to each). */
HFDEF hf_result hf_lut_bake_n_rgb(const hf_lut_params *p, int first_row,
                                  int row_count, float *out_tt_rgb,
                                  float *out_trt_rgb);

/* Quantise an n x n RGBA float texture to 8-bit unorm for hosts without
   float textures. Per channel c, scale_c = scales_in[c] if scales_in is
   given (each must be finite and > 0; values above it clip), else the
   channel's maximum over all texels (1 if that maximum is not > 0); then
       q = floor(255 * clamp(x / scale_c, 0, 1) + 0.5)
   and the shader multiplies the sampled unorm value by scale_c. M.a and
   N.a always get scale 1 (their maximum is 1). Writes 4 * n * n bytes to
   out_rgba8 and, if scales_out is not NULL, the four scales used.
   Errors (nothing written): HF_ERROR_NULL_POINTER (rgba or out_rgba8),
   HF_ERROR_BAD_COUNT (n outside [1, HF_LUT_MAX_SIZE]),
   HF_ERROR_NON_FINITE (a texel value), HF_ERROR_BAD_PARAMETER (a given
   scale not finite or not > 0). Note: N_TRT's maximum comes from a rare
   caustic texel, so most of that channel uses only the low codes; prefer
   float or half-float textures where available. */
HFDEF hf_result hf_lut_to_u8(const float *rgba, int n,
                             const float *scales_in,
                             unsigned char *out_rgba8, float scales_out[4]);

/* Evaluate the model at one point, in double precision, exactly as the
   bake does (p->size is ignored). hf_lut_eval_m writes M_R, M_TT, M_TRT at
   half angle theta_h (radians, any finite value). hf_lut_eval_n writes
   N_R, N_TT, N_TRT (absorption sigma_a) at cos(theta_d) = cos_theta_d
   (in [-1, 1]; its absolute value is used, clamped below at 1e-4 as in the
   texture) and relative azimuth phi (radians, in [0, pi]). For tests,
   reference values and CPU renderers. Errors (out untouched): as
   hf_lut_validate except that size is not checked, HF_ERROR_NULL_POINTER
   for out, HF_ERROR_NON_FINITE / HF_ERROR_BAD_PARAMETER for an input that
   is NaN, infinite or outside its range; HF_ERROR_BAD_PARAMETER for model
   HF_LUT_ENERGY (the paper's model only). */
HFDEF hf_result hf_lut_eval_m(const hf_lut_params *p, double theta_h,
                              double out[3]);
HFDEF hf_result hf_lut_eval_n(const hf_lut_params *p, double cos_theta_d,
                              double phi, double out[3]);

/* White furnace: the albedo of baked textures m and n (of p->size, baked
   with p) as the shader combines them, for light at inclination theta_i
   (radians, in [-pi/2, pi/2]):
       albedo = integral over all outgoing directions of
                S(theta_i, theta_r, phi) cos(theta_r) dw_r,
       dw_r = cos(theta_r) dtheta_r dphi,
   with S the model's shader combination (HF_LUT_MARSCHNER:
   dot(M.rgb, N.rgb) / max(M.a^2, 1e-2), N read at (M.a, cos phi);
   HF_LUT_ENERGY: dot(M, N) / max(cos theta_r, 1e-2), N read at
   (cos theta_i, cos phi)) and every texture read as GL_LINEAR with
   clamp-to-edge reads it (in double). Midpoint rule over sin(theta_r) in
   (-1, 1) and phi in (0, pi) (S is even in phi), max(1024, 4 size) steps
   each. An energy-conserving fibre that absorbs nothing gives 1 (within
   2e-4 at size 256, 1.1e-3 at 64); the paper's gives 1.90 at theta_i = 0.
   Cost: HF_LUT_ENERGY about 8 size texture reads; HF_LUT_MARSCHNER
   (max(1024, 4 size))^2 (0.02 s at 256). Errors (albedo untouched): as
   hf_lut_validate, HF_ERROR_NULL_POINTER (m, n or albedo),
   HF_ERROR_NON_FINITE (theta_i or a texel), HF_ERROR_BAD_PARAMETER
   (theta_i outside [-pi/2, pi/2]). */
HFDEF hf_result hf_lut_furnace(const hf_lut_params *p, const float *m,
                               const float *n, double theta_i,
                               double *albedo);

/* Dual scattering (Zinke, Yuksel, Weber and Keyser 2008): per absorption
   and incident inclination, the averages of the energy-conserving fibre
   (always HF_LUT_ENERGY: the paper's fibre scatters up to twice the light
   it receives, and the series behind A_b need a_f < 1) that the
   approximation needs. Three planes, each an n x n RGBA float texture
   (n = p->size; plane k starts at out + 4 * n * n * k; float c of texel
   (i, j) of plane k at out[4 * (n * n * k + j * n + i) + c]):

     column i: absorption sigma_a = u / (1 - u), u = (i + 0.5) / n (the
       shader reads u = sigma_a / (1 + sigma_a)); row j: incident
       inclination, cos(theta_i) = (j + 0.5) / n (read v = cos(theta_i));
     plane 0, forward:  a_f, alpha_f, beta_f, 1
     plane 1, backward: a_b, alpha_b, beta_b, 1
     plane 2, multiple back scattering: A_b, delta_b, sigma_b, 1

   a_f (a_b): the fraction of the light arriving at theta_i that the fibre
   scatters into the forward (backward) half of the azimuths, |phi| > pi/2
   (< pi/2), over all theta_r; alpha and beta: the lobes' shifts and widths
   (radians of theta_h, as the paper's alpha_R, beta_R) averaged with the
   lobes' share of a_f or a_b as weights (beta as a root mean square);
   A_b, delta_b, sigma_b: Zinke's eqs. 14, 16 and 17, with d_b =
   HF_LUT_DUAL_DB (docs/marschner-spec.md section 16 has every formula).
   p->sigma_a, sigma_a_rgb and model are not used (the absorption is the
   table's column); eta, alpha_r_deg, beta_r_deg, variant and size are.
   Writes rows [first_row, first_row + row_count) of all three planes into
   out, 12 * n * n floats; other rows are not touched; the bytes do not
   depend on the split. Cost: about n^2 * 200 exponentials (0.1 s at 256,
   8 ms at 64, which is plenty for a shader). Errors (nothing written): as
   hf_lut_bake_m. */
#define HF_LUT_DUAL_PLANES 3 /* RGBA planes hf_lut_bake_dual writes */
#define HF_LUT_DUAL_DB 0.7   /* Zinke's backward density factor d_b */
HFDEF hf_result hf_lut_bake_dual(const hf_lut_params *p, int first_row,
                                 int row_count, float *out);

/* ---- 10. the fur object ------------------------------------------------- */

/* hf_fur composes every stage: created once from a zero-initialised
   description (it grows everything then), it owns the guides, strands and
   rope state, and exposes the per-frame calls. It allocates only in
   hf_fur_create; every per-frame call takes a (first, count) range and
   allocates nothing. Per frame, in this order (a barrier between steps
   when ranges run on several threads):

       hf_fur_set_lod(fur, lod);                            // one thread
       hf_fur_set_roots(fur, &skinned_mesh, 0, info.guide_count);
       hf_fur_build_grid(fur, 0, info.grid_resolution);    // with a grid
       hf_fur_simulate(fur, 0, info.guide_count, dt, colliders, n);
       hf_fur_interpolate_guides(fur, 0, info.lod_guide_count);
       hf_fur_interpolate(fur, 0, info.drawn_strand_count);
       hf_fur_ribbons(fur, 0, info.drawn_strand_count, &view, &out);

   Guides 0 .. pure_guide_count - 1 are the pure guides (one per welded base
   vertex, always simulated); the rest are LOD guides (one per vertex that
   tessellation added), simulated only while the LOD is at or above
   lod_simulate_threshold and otherwise interpolated from the pure guides. */
typedef struct hf_fur hf_fur;

/* Every zero field means the default written beside it. */
typedef struct hf_fur_desc {
    hf_mesh mesh; /* the base mesh at rest (required); UVs are needed when
                     any map is given; no normals: area-weighted ones */
    const hf_map *density_map;       /* NULL: density 1 everywhere */
    const hf_map *length_map;        /* NULL: every strand max_length */
    const hf_map *color_map;         /* NULL: white strands */
    const hf_map *color3d_index_map; /* NULL: 3D-colour x = 0 */
    const float *comb;      /* NULL: guides grow along the normal; else a
                               growth direction per base vertex (object
                               space, any length; zero = the normal), as
                               hf_guide_params.comb */
    int comb_stride;        /* bytes; 0 = 12 */
    const hf_map *comb_map; /* NULL, or growth directions in UV space, >= 3
                               channels (8-bit: 2 c - 1); wins over comb */
    /* Authored guides: polylines whose shapes become the guides' rest
       shapes. Each guide takes the shapes of the (up to) 3 curves whose
       first points are nearest its root, weighted by 1 / distance^2, each
       rotated from the surface normal at that curve's root (the normal of
       the guide rooted nearest it) to the guide's own normal, and resampled
       to points_per_strand points evenly along its length. The shape is
       then carried by the guide's root frame, so a style survives
       skinning. Lengths come from the curves (max_length, length_map and
       comb are then not used); strands follow the guides as always.
       Cost at creation: guides x curves distance tests. */
    const float *guide_curves;     /* xyz of every point, curve after curve,
                                      root first; NULL with count 0 */
    const int *guide_curve_points; /* per curve: its points, >= 2 */
    int guide_curve_count;         /* 0 = straight guides */
    /* Styling of the guides' rest shapes, deterministic from the seed;
       0 = none. Each is a scalar; its map, when given, multiplies it by
       the map's first channel at the guide's root. The effects grow from
       nothing at the root to full strength at a fifth of the length. */
    float curl_radius;      /* helix radius, m */
    float curl_turns;       /* turns of the helix along a whole guide */
    float wave_amplitude;   /* planar wave, m */
    float wave_count;       /* wave periods along a whole guide */
    float frizz;            /* random offset of each point, a fraction of
                               the segment length, growing to the tip */
    const hf_map *curl_map, *wave_map, *frizz_map; /* NULL = 1 */
    /* maps of the per-strand controls, read at each strand's root UV:
       their first channel multiplies clump, color_variation and
       width_variation there (NULL = 1) */
    const hf_map *clump_map, *color_variation_map, *width_variation_map;
    float color_variation;  /* [0, 1]: each strand's colour times a random
                               factor in [1 - v, 1 + v] (clamped to 1) */
    float width_variation;  /* [0, 1]: each strand's ribbon width times a
                               random factor in [1 - v, 1 + v] */
    int points_per_strand;  /* 0 = 16; 2 .. HF_MAX_POINTS. A multiple
                               of 16 (or 8) takes every kernel's whole
                               groups: P = 12 costs up to 2.2x P = 16's
                               time a point (docs/performance.md) */
    float max_length;       /* 0 = 0.05 m */
    float tess_factor;      /* 1/m^2; 0 = no tessellation: pure guides
                               only. Else triangles split while
                               D * A * factor > 1 (about a guide per
                               1/factor m^2 where the density is 1) */
    int tess_estimator;     /* hf_density_estimator; 0 = corners */
    int tess_split;         /* hf_split_point; 0 = centroid */
    int tess_max_triangles; /* 0 = HF_TESS_DEFAULT_MAX_TRIANGLES */
    float strands_per_area; /* 1/m^2: expected strands per square metre at
                               density 1; > 0 wins over total_strands (the
                               opposite of hf_place_params, where
                               total_strands > 0 wins); 0 = use
                               total_strands; negative or NaN refused */
    int total_strands;      /* exact strand count when strands_per_area is
                               0; both 0 = 10000; negative refused */
    int sampler;            /* hf_root_sampler; 0 = uniform */
    uint64_t seed;          /* every stochastic stage; 0 is a fine seed */
    float clump;            /* 0 = none; [0, 1], see hf_interp_params */
    float clump_size;       /* 0: each strand clumps to its main guide;
                               > 0: strands gather into clumps about this
                               wide (m) around leader strands
                               that far apart, whatever the guide spacing */
    const hf_map *clump_size_map; /* NULL = 1: its first channel, clamped
                               to [0, 1] at each strand's root UV, scales
                               clump_size there (0: the strand stands
                               alone, follows and leads no clump); where
                               it makes clumps far smaller than the
                               largest, at most 16 lead in a cell of the
                               largest size and the rest stand alone */
    int simd;               /* hf_simd_level of the rope step and the
                               interpolation; 0 = the best the CPU runs
                               (every level gives the same bytes);
                               hf_fur_set_kernels changes it */
    int nontemporal;        /* the stores of the fur's strand points
                               (hf_interp_params.nontemporal): 0 = by
                               size, streaming where the drawn strands'
                               (hf_fur_set_lod) are larger than
                               HF_STREAM_MIN_BYTES (4 MiB), which they
                               outgrow the cache at; 1 = streaming;
                               2 = ordinary stores */
    float lod_simulate_threshold; /* 0 = 0.5: LOD guides simulated at
                                     lod >= this */
    int grid_resolution;    /* 0 = no hair-hair interaction; else the
                               nodes along each axis of the fur's grid
                               (hf_grid, [4, HF_GRID_MAX_RESOLUTION]; 32
                               is a good start), rebuilt each frame by
                               hf_fur_build_grid, its strengths volume
                               and friction of hf_rope_params */
    int keep_length;        /* 0 = off; 1 = the drawn strands keep the
                               segment lengths of their shape at creation:
                               a blend of guides that part shortens a
                               strand, clumping to a far guide lengthens
                               it, so after both (and a groom's offsets)
                               each segment is scaled back to its rest
                               length along its own direction, in
                               hf_fur_interpolate and the GPU points.
                               Costs (P - 1) floats a strand and a pass
                               a frame, about 2.5 ns a point on one core
                               (docs/hair.md) */
    const hf_rope_params *rope_params; /* NULL = hf_rope_params_init */
    const hf_allocator *allocator;     /* NULL = default; copied */
} hf_fur_desc;

/* Sizes and state of a fur, for sizing buffers and splitting ranges. The
   pointers stay valid until hf_fur_destroy. */
typedef struct hf_fur_info {
    int points_per_strand;
    int guide_count, pure_guide_count, lod_guide_count;
    int strand_count;        /* all strands, in LOD order */
    int drawn_strand_count;  /* the prefix the current LOD draws */
    int lod_guides_simulated;
    float lod, width_scale;  /* current LOD and its width multiplier */
    int triangle_count;      /* guide (tessellated) triangles */
    int roots_inside;        /* guides whose root sat inside a collider at
                                their last hf_fur_simulate (see
                                hf_ropes_roots_inside): shrink that proxy */
    int grid_resolution;     /* the grid's layers (hf_fur_build_grid's
                                range); 0 without a grid */
    const float *guide_points;  /* guide_count * P * 3 */
    const float *strand_points; /* strand_count * P * 3 */
    const hf_strand *strands;   /* strand_count records */
    const float *strand_lengths; /* strand_count */
    const float *strand_colors;  /* 4 per strand (rgba from color_map) */
    const float *strand_uv;      /* 2 per strand: root UV, packed */
    const float *strand_color3d_x; /* 1 per strand: index-map value */
} hf_fur_info;

/* Grow a fur: validate, tessellate, make guides, place strands, read the
   maps, set up the ropes. *out_fur is set only on success. Errors: any of
   the building blocks' (mesh and map validation, HF_ERROR_BAD_PARAMETER
   for an out-of-range field, the tessellation caps, ...) and
   HF_ERROR_OUT_OF_MEMORY; nothing is leaked on failure. `diag` (may be
   NULL) says which stage failed. */
HFDEF hf_result hf_fur_create(const hf_fur_desc *desc, hf_fur **out_fur,
                              hf_diag *diag);
/* Free a fur and everything it allocated (NULL is ignored). */
HFDEF void hf_fur_destroy(hf_fur *fur);

/* A groom: strands without a mesh (an artist's groom from TressFX, .hair
   or a DCC tool). Zero-initialise, then set the strands. */
typedef struct hf_groom_desc {
    const float *points;       /* xyz of every point, strand after strand,
                                  root first (required) */
    const int *strand_points;  /* per strand: its points, >= 2 (required) */
    int strand_count;          /* >= 1 */
    const float *colors;       /* NULL: white; else rgb per strand, [0, 1] */
    int points_per_strand;     /* 0 = 16; each strand is resampled to P
                                  points evenly along its length */
    float guide_fraction;      /* 0 = 0.1: round(fraction * strands) of the
                                  strands, at least 1, are simulated guides;
                                  (0, 1] */
    uint64_t seed;             /* the LOD order (a shuffle) */
    const hf_mesh *scalp;      /* NULL: roots follow hf_fur_set_transform;
                                  else the surface the groom grows from, at
                                  rest (positions and triangles are read):
                                  each guide root is bound to its nearest
                                  point on it, and hf_fur_set_roots with the
                                  skinned scalp moves the roots */
    int grid_resolution;       /* as hf_fur_desc.grid_resolution */
    int keep_length;           /* as hf_fur_desc.keep_length */
    const hf_rope_params *rope_params; /* NULL = hf_rope_params_init */
    const hf_allocator *allocator;     /* NULL = default; copied */
} hf_groom_desc;

/* Make a fur from a groom. Its drawn strands are the groom's own strands
   (resampled), in a shuffled LOD order; the first guide_fraction of them
   are also its guides, simulated as ropes whose root frame is the
   strand's root and first segment; every other strand follows its three
   nearest guides (by root, weights 1 / distance^2) and keeps its own rest
   offset from their blend, carried by their root frames. So at rest, and
   when the roots move rigidly (hf_fur_set_transform), every strand is the
   groom's own strand to float precision; under simulation it follows its
   guides. Roots follow a rigid transform (hf_fur_set_transform) or, given
   a scalp, the skinned scalp (hf_fur_set_roots: each guide's root frame
   turns and moves with the frame of the scalp triangle it is bound to;
   without a scalp it returns HF_ERROR_BAD_PARAMETER). hf_fur_info: no
   triangles, strand UVs 0. Cost at creation: strands x guides and guides
   x scalp triangles distance tests. Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_COUNT (counts, points per strand),
   HF_ERROR_NON_FINITE (a point or colour), HF_ERROR_BAD_PARAMETER (a
   zero-length strand, guide_fraction, rope parameters, a coordinate
   beyond HF_ROPE_MAX_COORD), HF_ERROR_OVERFLOW, HF_ERROR_OUT_OF_MEMORY;
   *out_fur is set only on success, and `diag` says what failed. */
HFDEF hf_result hf_fur_create_groom(const hf_groom_desc *desc,
                                    hf_fur **out_fur, hf_diag *diag);
/* Fill *info. Errors: HF_ERROR_NULL_POINTER. */
HFDEF hf_result hf_fur_get_info(const hf_fur *fur, hf_fur_info *info);

/* Choose the level of detail, lod in [0, 1] (see hf_lod_strand_count; NaN
   counts as 0): the drawn prefix, the width multiplier, and whether LOD
   guides are simulated. LOD guides switched on start from their current
   (interpolated) shape at rest velocity, so nothing jumps. Not a range
   call: run it on one thread between frames. */
HFDEF hf_result hf_fur_set_lod(hf_fur *fur, float lod);

/* Root frames of guides [first, first + count) from the skinned base mesh
   (same vertex count and triangles as at creation; only positions,
   optional normals and their strides are read): a pure guide takes the
   position and normal of its vertex, a LOD guide the barycentric blend on
   its base triangle (hf_tess_evaluate); without normals, the face normal
   of a triangle of the vertex. The tangent is the direction of a fixed
   mesh edge at the root. Errors: HF_ERROR_NULL_POINTER, HF_ERROR_BAD_COUNT
   (vertex or triangle count differs from the rest mesh's),
   HF_ERROR_BAD_RANGE, HF_ERROR_BAD_STRIDE, HF_ERROR_NON_FINITE (a position
   or normal read), HF_ERROR_BAD_PARAMETER (a root beyond
   HF_ROPE_MAX_COORD, or a groom without a scalp: hf_fur_set_transform
   moves those); nothing set then. */
HFDEF hf_result hf_fur_set_roots(hf_fur *fur, const hf_mesh *skinned,
                                 int first, int count);

/* Root frames of guides [first, first + count) moved rigidly from their
   rest frames (at creation) by `m`, rows of a 3x4 matrix (rotation and
   uniform scale, then translation): the way a groom's roots follow a head,
   and, with hf_fur_reset, a teleport of any fur. Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE, HF_ERROR_NON_FINITE; nothing
   set then. */
HFDEF hf_result hf_fur_set_transform(hf_fur *fur, const float m[12],
                                     int first, int count);

/* Step the ropes of guides [first, first + count) by dt (see
   hf_ropes_step: clamped above max_dt, HF_ERROR_BAD_TIME_STEP for zero,
   negative or non-finite) with the given colliders, and copy their points
   into the guide array. LOD guides are skipped while not simulated. On
   several threads, give each one contiguous range a frame: neighbouring
   ranges stepped at once touch the same rows' cache lines at their edge
   (docs/frame.md). */
HFDEF hf_result hf_fur_simulate(hf_fur *fur, int first, int count, float dt,
                                const hf_collider *colliders,
                                int collider_count);

/* With a grid (hf_fur_desc.grid_resolution), rebuild its z layers
   [first, first + count) of info.grid_resolution from the simulated
   guides as they are (hf_grid_build): every frame after the roots are
   set and before hf_fur_simulate, which then pushes and drags each
   guide's points by the hair around them (hf_ropes_apply_grid: volume
   and friction of the rope parameters). Layers may be built on several
   threads (same bytes); every layer must be built before any guide is
   simulated. A grid not rebuilt acts from where the hair was when it
   was. Without a grid: HF_OK for the empty range. Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE. */
HFDEF hf_result hf_fur_build_grid(hf_fur *fur, int first, int count);

/* Drape the hair: simulate every guide (LOD guides too) for `seconds` of
   simulated time in 1/60 s steps at its current roots, under gravity and
   the colliders (the grid rebuilt each step where there is one), then
   take the result as the guides' rest shapes (hf_ropes_rest_from_pose),
   at rest. Shape stiffness then holds the draped shape rather than the
   grown one. While settling, the fur's rope parameters hold except that
   the global shape stiffness is off (the local one still shapes the hair
   near its roots), wind and turbulence are off, and damping is at least
   0.1, so the hair falls and comes to rest; 1 s is enough for most
   hair. Not a range call; it allocates a byte per guide, freed before it
   returns. Errors: HF_ERROR_NULL_POINTER,
   HF_ERROR_BAD_PARAMETER (seconds NaN or outside [0, 600]), the
   colliders' errors (as hf_ropes_step), HF_ERROR_OUT_OF_MEMORY; nothing
   changes then. */
HFDEF hf_result hf_fur_settle_rest(hf_fur *fur, float seconds,
                                   const hf_collider *colliders,
                                   int collider_count);

/* While LOD guides are not simulated, interpolate LOD guides [first, first
   + count) (0-based among the LOD guides) from the pure guides of their
   base triangle; a no-op (HF_OK) while they are simulated. Needs every
   pure guide simulated first. */
HFDEF hf_result hf_fur_interpolate_guides(hf_fur *fur, int first, int count);

/* Interpolate strands [first, first + count) from the guides (see
   hf_interpolate), into the fur's strand points. Needs every guide
   updated first. */
HFDEF hf_result hf_fur_interpolate(hf_fur *fur, int first, int count);

/* Ribbons of strands [first, first + count) into `out` (see hf_ribbons),
   with the strand UVs, colours and 3D-colour coordinates of the fur. The
   fur's LOD width multiplier multiplies view->width_scale (0 = 1);
   view->points_per_strand is ignored (the fur's is used). */
HFDEF hf_result hf_fur_ribbons(const hf_fur *fur, int first, int count,
                               const hf_ribbon_params *view,
                               const hf_ribbon_output *out);
/* The GPU-expansion path of strands [first, first + count): see
   hf_ribbon_points; widths as hf_fur_ribbons. */
HFDEF hf_result hf_fur_points(const hf_fur *fur, int first, int count,
                              const hf_ribbon_params *view, float *out4);
/* hf_fur_interpolate and hf_fur_points of strands [first, first + count)
   in one pass, for the GPU-expansion path: the same bytes in out4 as the
   two calls, without writing the strands' points to the fur and reading
   them back (about 18 KiB of stack). The fur's strand points
   (hf_fur_info.strand_points) are left as they were. Needs every guide updated first; errors as
   hf_fur_points, nothing written then. */
HFDEF hf_result hf_fur_interpolate_points(const hf_fur *fur, int first,
                                          int count,
                                          const hf_ribbon_params *view,
                                          float *out4);

/* The largest relative segment stretch of the simulated guides (see
   hf_ropes_max_stretch). Errors: HF_ERROR_NULL_POINTER. */
HFDEF hf_result hf_fur_max_stretch(const hf_fur *fur, float *out_stretch);

/* Teleport: every guide to its rest shape in its current root frame (call
   hf_fur_set_roots with the new pose first). */
HFDEF hf_result hf_fur_reset(hf_fur *fur);

/* Per-frame control. hf_fur_set_rope_params replaces the rope parameters
   (gravity, wind and turbulence, damping, stiffness, margin, ...) from the
   next hf_fur_simulate on; zero fields mean the defaults, as everywhere.
   Errors: HF_ERROR_NULL_POINTER, HF_ERROR_NON_FINITE,
   HF_ERROR_BAD_PARAMETER (as hf_rope_params_validate); nothing changes
   then. Not a range call: run it between frames. */
HFDEF hf_result hf_fur_set_rope_params(hf_fur *fur,
                                       const hf_rope_params *params);
/* The same for guides [first, first + count) only (wind on one side, a
   stiffer fringe, ...). A fur holds up to HF_FUR_ROPE_SETS different
   parameter sets at once; equal sets are shared. Errors: as
   hf_fur_set_rope_params, HF_ERROR_BAD_RANGE, and HF_ERROR_BAD_COUNT when
   a new set would be the ninth in use; nothing changes then. Not a range
   call in the threading sense: run it between frames. */
#define HF_FUR_ROPE_SETS 8
HFDEF hf_result hf_fur_set_rope_params_range(hf_fur *fur, int first,
                                             int count,
                                             const hf_rope_params *params);
/* Switch guides [first, first + count) between simulation and animation
   (hf_rope_mode) without a jump, as hf_ropes_set_mode. The choice is kept
   per guide: LOD guides put to sleep by hf_fur_set_lod (animated, drawn
   interpolated) take it when they wake, and an animated one stays
   animated then. Errors:
   HF_ERROR_NULL_POINTER, HF_ERROR_BAD_RANGE, HF_ERROR_BAD_PARAMETER. */
HFDEF hf_result hf_fur_set_mode(hf_fur *fur, int first, int count, int mode);
/* The kernels of the fur's rope step, grid and interpolation: the SIMD
   level (hf_simd_level; 0 = the best the CPU runs; it replaces the simd of
   the fur's rope parameters and grid) and the stores of the interpolation
   (nontemporal: 0 by size, 1 streaming, 2 ordinary, as
   hf_fur_desc.nontemporal). Every choice gives the same bytes; for tests,
   benchmarks and tuning. Ribbons and points take theirs from
   hf_ribbon_params; hf_fur_interpolate_points runs at the lower of the
   two levels. Errors: HF_ERROR_NULL_POINTER, HF_ERROR_BAD_PARAMETER
   (not an hf_simd_level, or nontemporal not 0, 1 or 2). */
HFDEF hf_result hf_fur_set_kernels(hf_fur *fur, int simd, int nontemporal);

#ifdef __cplusplus
}
#endif

#endif /* HAIRFUR_H */

/* ---- 0. the implementation: its prologue -------------------------------- */

/* The implementation, and its kernel passes: a kernel text, written once
   for any SIMD width, is built by including this file again once per
   width, with HF__PASS naming the text (see "Kernel texts" after the
   SIMD words); a pass compiles that text alone. */
#if (defined(HAIRFUR_IMPLEMENTATION) &&                                        \
     !defined(HAIRFUR_IMPLEMENTATION_DONE)) ||                                 \
    defined(HF__PASS)
#ifndef HF__PASS
#define HAIRFUR_IMPLEMENTATION_DONE

#include <math.h>
#include <stdarg.h> /* diagnostics */
#include <stdio.h>  /* vsnprintf for diagnostics */
#include <string.h> /* memcpy, memset */

/* ---- 0.1 overridable macros: allocator, assert, file name, libm --------- */

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

/* The name this file includes itself by, once per SIMD width of each
   kernel text (see CONFIGURATION MACROS) */
#ifndef HF_HEADER_FILENAME
#define HF_HEADER_FILENAME "hairfur.h"
#endif

/* libm and libc, each replaceable (see CONFIGURATION MACROS at the top). */
#ifndef HF_SQRTF
#define HF_SQRTF(x) sqrtf(x)
#endif
#ifndef HF_FLOORF
#define HF_FLOORF(x) floorf(x)
#endif
#ifndef HF_SQRT
#define HF_SQRT(x) sqrt(x)
#endif
#ifndef HF_EXP
#define HF_EXP(x) exp(x)
#endif
#ifndef HF_POW
#define HF_POW(x, y) pow(x, y)
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
#ifndef HF_FLOOR
#define HF_FLOOR(x) floor(x)
#endif
#ifndef HF_CEIL
#define HF_CEIL(x) ceil(x)
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

/* ---- 0.2 SIMD levels ---------------------------------------------------- */

/* SIMD levels. A kernel is named by its lanes: hf__<name>_v4 (SSE2 or
   NEON), _v8 (AVX2) or _v16 (AVX-512), written for its instruction set
   or built from a kernel text (see "Kernel texts" below); each follows
   its scalar reference hf__<name>_v1 (an _in after the width: an inline
   body of the kernel). Every level uses the same IEEE operations in the
   same order (no FMA), so all give the same bytes (in the default
   rounding mode: the vector encoders of normalized formats convert by
   the mode, the scalar one adds and takes away 1.5 * 2^23; and with
   x86's flush-to-zero and denormals-are-zero clear: under either, a
   subnormal that one kernel copies and another adds 0 to becomes two
   values, and compilers fold such operations as the default mode
   allows). Each
   stage's descriptors (one a width, with its instruction set) and the
   one resolver that picks among them by the level hf_simd_resolve gives
   are in 1, "The dispatch".
   SSE2 is the baseline wherever the compiler targets it, NEON on ARM64.
   AVX2 and AVX-512 kernels are compiled into any x86 build (target
   attributes on gcc and clang, none needed on MSVC) and picked at run
   time by CPUID (the AVX-512 level needs AVX-512F and BW, which every
   AVX-512 CPU but the Xeon Phi has; there AVX2 runs). HF_NO_SIMD forces
   the scalar references; HF_SIMD_MAX (an hf_simd_level) caps the level
   at compile time. */
#if !defined(HF_NO_SIMD) &&                                                    \
    (defined(__SSE2__) || defined(_M_X64) ||                                   \
     (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#define HF__SSE 1
#include <emmintrin.h>
#else
#define HF__SSE 0
#endif
/* ARM64 always has NEON (Advanced SIMD): its 4-lane kernels are chosen
   at compile time and answer for the SSE2 level (HF_SIMD_NEON). */
#if !defined(HF_NO_SIMD) && !HF__SSE &&                                        \
    (defined(__aarch64__) || defined(_M_ARM64))
#define HF__NEON 1
#include <arm_neon.h>
#else
#define HF__NEON 0
#endif
#if HF__SSE && (defined(__GNUC__) || defined(__clang__)) &&                    \
    (defined(__x86_64__) || defined(__i386__))
#define HF__X86_DISPATCH 1 /* kernels by target attribute, CPUID */
#define HF__AVX2 1
#define HF__AVX512 1
/* Every AVX kernel ends with _mm256_zeroupper: SSE code that runs while
   the upper halves of the vector registers are dirty ran 2.1-2.4x slower
   on the Zen 4 measured here (all of it, the caller's too; Intel cores
   have their own penalty), and gcc leaves them dirty below -O2. */
#define HF__TARGET_AVX2 __attribute__((target("avx2")))
#define HF__TARGET_AVX512 __attribute__((target("avx512f,avx512bw")))
#elif HF__SSE && defined(_MSC_VER) && (defined(_M_X64) || defined(_M_IX86))
/* MSVC compiles any intrinsic in any function: the kernels need no
   attribute, and hf__cpu_simd asks CPUID (__cpuid, __cpuidex, _xgetbv) */
#define HF__X86_DISPATCH 1
#define HF__AVX2 1
#define HF__AVX512 1
#define HF__TARGET_AVX2
#define HF__TARGET_AVX512
#include <intrin.h>
#else
/* no CPUID: the level is what the compiler targets. On WebAssembly that
   is SSE2 at most (emscripten's -msimd128 -msse2 translate it into
   SIMD128; its wider x86 headers are not used) */
#define HF__X86_DISPATCH 0
#if HF__SSE && defined(__AVX2__) && !defined(__wasm__)
#define HF__AVX2 1
#else
#define HF__AVX2 0
#endif
#if HF__SSE && defined(__AVX512F__) && defined(__AVX512BW__) &&                \
    !defined(__wasm__)
#define HF__AVX512 1
#else
#define HF__AVX512 0
#endif
#define HF__TARGET_AVX2
#define HF__TARGET_AVX512
#endif
#if HF__AVX2 || HF__AVX512
#include <immintrin.h>
#endif
#ifndef HF_SIMD_MAX
#define HF_SIMD_MAX HF_SIMD_AVX512
#endif
#ifndef HF_STREAM_MIN_BYTES
#define HF_STREAM_MIN_BYTES ((size_t)4 << 20)
#endif
#ifndef HF_STREAM_MIN_VERTEX_BYTES
#define HF_STREAM_MIN_VERTEX_BYTES ((size_t)8 << 20)
#endif

/* ---- 0.3 FMA contraction and compiler words ----------------------------- */

/* Every kernel gives its scalar reference's bytes only where no compiler
   fuses a * b + c into one FMA (one rounding instead of two), and a range
   split sends different strands through different kernels: contraction
   is off for the whole implementation, whatever -ffp-contract, -march or
   the language mode (gcc fuses by default in GNU C and C++) says, and is
   restored after it. clang's -ffp-contract=fast ignores the pragma (its
   fast-honor-pragmas does not); MSVC fuses only with /fp:contract or
   /fp:fast, which the header does not override. */
#if defined(__clang__) /* the standard pragma: every clang version */
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif

/* Compiler words, each with a plain fallback:
   HF__UNUSED, HF__PRINTF  attributes that silence idle helpers and check
                           diagnostic formats;
   HF__PRIVATE             every internal function: static, maybe idle;
   HF__INLINE              small kernels whose arguments must stay in
                           registers (forced inline where the compiler
                           optimizes: at -O0 each inlined copy kept its
                           own stack slots, and hf_ribbons took 2.5 MB);
   HF__NOINLINE            cold paths kept out of a hot loop;
   HF__RESTRICT            the rope kernels' non-aliasing rows;
   HF__UNROLL              before a kernel's short loop (x, y, z, a cell's
                           corners, a vector's lanes: 16 at most): gcc -O2
                           unrolls a loop only where the code does not
                           grow, and a loop kept leaves its vectors on the
                           stack (the rope contacts ran 1.3x slower, the
                           grid's push 1.35x). */
#if defined(__GNUC__) || defined(__clang__)
#define HF__UNUSED __attribute__((unused))
#define HF__PRINTF(f, a) __attribute__((format(printf, f, a)))
#if defined(__OPTIMIZE__)
#define HF__INLINE static __inline__ __attribute__((always_inline, unused))
#else
#define HF__INLINE static __inline__ __attribute__((unused))
#endif
#define HF__NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define HF__UNUSED
#define HF__PRINTF(f, a)
#define HF__INLINE static __forceinline
#define HF__NOINLINE __declspec(noinline)
#else
#define HF__UNUSED
#define HF__PRINTF(f, a)
#define HF__INLINE static
#define HF__NOINLINE
#endif
#define HF__PRIVATE static HF__UNUSED
#if defined(__clang__)
#define HF__UNROLL _Pragma("unroll")
#elif defined(__GNUC__) && __GNUC__ >= 8
#define HF__UNROLL _Pragma("GCC unroll 16")
#else
#define HF__UNROLL
#endif
#if defined(__GNUC__) || defined(__clang__) || defined(_MSC_VER)
#define HF__RESTRICT __restrict
#else
#define HF__RESTRICT
#endif

#if HF__SSE
/* a where m is set, else b: how the SSE kernels take a branch per lane */
HF__INLINE __m128 hf__sel_sse(__m128 m, __m128 a, __m128 b)
{
    return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b));
}
#endif

/* ---- 0.4 the four-lane operations --------------------------------------- */

/* The four-lane operations, for SSE2 and NEON: hf__v4 holds four floats,
   a mask is a vector whose lanes have every bit set or clear, HF__MASK
   gives bit i for lane i. Each is the IEEE operation of the scalar code,
   so both ISAs give its bytes; HF__MAX is SSE's maxps, x > y ? x : y (y
   when either is NaN). Each macro argument is used once. The kernel
   texts use them at four lanes (as HF__VLD, ...: see "Kernel texts"). */
#define HF__V4 (HF__SSE || HF__NEON)
#if HF__SSE
typedef __m128 hf__v4;
#define HF__LD(p) _mm_loadu_ps(p)
#define HF__ST(p, v) _mm_storeu_ps(p, v)
#define HF__SET1(x) _mm_set1_ps(x)
#define HF__ADD(x, y) _mm_add_ps(x, y)
#define HF__SUB(x, y) _mm_sub_ps(x, y)
#define HF__MUL(x, y) _mm_mul_ps(x, y)
#define HF__DIV(x, y) _mm_div_ps(x, y)
#define HF__SQRT(x) _mm_sqrt_ps(x)
#define HF__MAX(x, y) _mm_max_ps(x, y)
#define HF__GT(x, y) _mm_cmpgt_ps(x, y)
#define HF__LT(x, y) _mm_cmplt_ps(x, y)
#define HF__EQ(x, y) _mm_cmpeq_ps(x, y)
#define HF__LE(x, y) _mm_cmple_ps(x, y)
#define HF__AND(x, y) _mm_and_ps(x, y)
#define HF__SEL(m, a, b) hf__sel_sse(m, a, b)
#define HF__MASK(m) _mm_movemask_ps(m)
#define HF__SET4(a, b, c, d) _mm_setr_ps(a, b, c, d) /* lanes 0..3 */
#define HF__PREFETCH(p) _mm_prefetch((const char *)(p), _MM_HINT_T0)
#elif HF__NEON
typedef float32x4_t hf__v4;
#define HF__LD(p) vld1q_f32(p)
#define HF__ST(p, v) vst1q_f32(p, v)
#define HF__SET1(x) vdupq_n_f32(x)
#define HF__ADD(x, y) vaddq_f32(x, y)
#define HF__SUB(x, y) vsubq_f32(x, y)
#define HF__MUL(x, y) vmulq_f32(x, y)
#define HF__DIV(x, y) vdivq_f32(x, y)
#define HF__SQRT(x) vsqrtq_f32(x)
#define HF__MAX(x, y) hf__max_neon(x, y)
#define HF__GT(x, y) vreinterpretq_f32_u32(vcgtq_f32(x, y))
#define HF__LT(x, y) vreinterpretq_f32_u32(vcltq_f32(x, y))
#define HF__EQ(x, y) vreinterpretq_f32_u32(vceqq_f32(x, y))
#define HF__LE(x, y) vreinterpretq_f32_u32(vcleq_f32(x, y))
#define HF__AND(x, y)                                                          \
    vreinterpretq_f32_u32(                                                     \
        vandq_u32(vreinterpretq_u32_f32(x), vreinterpretq_u32_f32(y)))
#define HF__SEL(m, a, b) vbslq_f32(vreinterpretq_u32_f32(m), a, b)
#define HF__MASK(m) hf__mask_neon(m)
#define HF__SET4(a, b, c, d) hf__set4_neon(a, b, c, d)
#if defined(__GNUC__) || defined(__clang__)
#define HF__PREFETCH(p) __builtin_prefetch(p)
#else
#define HF__PREFETCH(p) ((void)(p))
#endif
HF__INLINE float32x4_t hf__max_neon(float32x4_t x,
                                                   float32x4_t y)
{
    return vbslq_f32(vcgtq_f32(x, y), x, y);
}
HF__INLINE float32x4_t hf__set4_neon(float a, float b, float c, float d)
{
    float32x4_t v = vdupq_n_f32(a);
    v = vsetq_lane_f32(b, v, 1);
    v = vsetq_lane_f32(c, v, 2);
    return vsetq_lane_f32(d, v, 3);
}
HF__INLINE int hf__mask_neon(float32x4_t m)
{
    static const uint32_t bit[4] = {1u, 2u, 4u, 8u};
    return (int)vaddvq_u32(vandq_u32(vreinterpretq_u32_f32(m), vld1q_u32(bit)));
}
#endif
#if HF__V4
/* a x + b y + c z, added left to right as the scalar code does; o = a x b
   on three rows of lanes, in hf__cross3's order; o + a x + b y + c z,
   likewise. The _OF forms take the operations (a kernel text's too:
   HF__VDOT3, ...). */
#define HF__DOT3_OF(add, mul, a, b, c, x, y, z)                                \
    add(add(mul(a, x), mul(b, y)), mul(c, z))
#define HF__CROSS3_OF(sub, mul, o, a, b)                                       \
    do {                                                                       \
        (o)[0] = sub(mul((a)[1], (b)[2]), mul((a)[2], (b)[1]));                \
        (o)[1] = sub(mul((a)[2], (b)[0]), mul((a)[0], (b)[2]));                \
        (o)[2] = sub(mul((a)[0], (b)[1]), mul((a)[1], (b)[0]));                \
    } while (0)
#define HF__POSE_OF(add, mul, o, a, b, c, x, y, z)                             \
    add(add(add(o, mul(a, x)), mul(b, y)), mul(c, z))
#define HF__DOT3(a, b, c, x, y, z)                                             \
    HF__DOT3_OF(HF__ADD, HF__MUL, a, b, c, x, y, z)
#define HF__CROSS3(o, a, b) HF__CROSS3_OF(HF__SUB, HF__MUL, o, a, b)
#define HF__POSE(o, a, b, c, x, y, z)                                          \
    HF__POSE_OF(HF__ADD, HF__MUL, o, a, b, c, x, y, z)
/* All bits set in lane l where bit l of mask is. */
HF__INLINE hf__v4 hf__lanes_v4(int mask)
{
#if HF__SSE
    return _mm_castsi128_ps(_mm_setr_epi32(-(mask & 1), -(mask >> 1 & 1),
                                           -(mask >> 2 & 1),
                                           -(mask >> 3 & 1)));
#else
    const uint32_t b[4] = {(uint32_t)-(mask & 1), (uint32_t)-(mask >> 1 & 1),
                           (uint32_t)-(mask >> 2 & 1),
                           (uint32_t)-(mask >> 3 & 1)};
    return vreinterpretq_f32_u32(vld1q_u32(b));
#endif
}
#endif

/* ---- 0.5 kernel texts: their words at each width ------------------------ */

/* Kernel texts. The kernels written once for any SIMD width (the rope
   step's contacts and rows and the grid's splat and push at 4, 8 and 16
   lanes, interpolation into strands and into GPU points at 8 and 16) are
   ordinary lines of this file, each where the data flow puts it, between
       #if defined(HF__PASS) && HF__PASS == HF__PASS_<TEXT>
   and its #endif, which the implementation skips. After the text it
   includes this file once per width the build has, with HF__PASS and
   HF__W (the lanes) set:
       #define HF__PASS HF__PASS_ROPES
       #define HF__W 8
       #include HF_HEADER_FILENAME
   That pass compiles the text alone (the declarations, already seen,
   and the rest of the implementation are skipped) in its width's words
   (below), and undefines them, HF__PASS and HF__W as it ends. Each
   width's copy of a function is thus a function of its own, named by its
   width (_v4: SSE2 or NEON, _v8: AVX2, _v16: AVX-512), with the text's
   own lines in the debug information. In gdb, "break
   hf__ropes_ftl_row_v8" stops in the rope step's AVX2 FTL row, and
   "break hairfur.h:LINE" at a line of a text stops in every width's copy;
   both also find the small kernels that HF__INLINE inlines where the
   compiler optimizes. */
#define HF__PASS_ROPES 1  /* the rope step's contact kernels and rows */
#define HF__PASS_INTERP 2 /* interpolation at 8 and 16 lanes */
#define HF__PASS_POINTS 3 /* interpolation into GPU points, likewise */
#define HF__PASS_GRID 4   /* the hair-hair grid's splat and push, likewise */
#if HF__AVX2
/* hf__lanes_v4 for eight lanes */
HF__TARGET_AVX2 HF__INLINE __m256 hf__lanes_v8(int mask)
{
    return _mm256_castsi256_ps(
        _mm256_setr_epi32(-(mask & 1), -(mask >> 1 & 1), -(mask >> 2 & 1),
                          -(mask >> 3 & 1), -(mask >> 4 & 1),
                          -(mask >> 5 & 1), -(mask >> 6 & 1),
                          -(mask >> 7 & 1)));
}
#endif
#if HF__AVX512
/* Sixteen lanes' words: a mask stays a vector of all-set or all-clear
   lanes, as the texts expect, so a compare's mask register is widened to
   one (hf__m16), and a select is a bitwise one (vpternlogd). */
HF__TARGET_AVX512 HF__INLINE __m512 hf__m16(__mmask16 k)
{
    return _mm512_castsi512_ps(_mm512_maskz_set1_epi32(k, -1));
}
HF__TARGET_AVX512 HF__INLINE __m512 hf__and16(__m512 x, __m512 y)
{
    return _mm512_castsi512_ps(
        _mm512_and_si512(_mm512_castps_si512(x), _mm512_castps_si512(y)));
}
HF__TARGET_AVX512 HF__INLINE __m512 hf__sel16(__m512 m, __m512 a, __m512 b)
{
    /* 0xCA: m ? a : b, bit by bit */
    return _mm512_castsi512_ps(_mm512_ternarylogic_epi32(
        _mm512_castps_si512(m), _mm512_castps_si512(a),
        _mm512_castps_si512(b), 0xCA));
}
HF__TARGET_AVX512 HF__INLINE int hf__mask16(__m512 m)
{
    /* the sign bits, as movemask */
    return (int)_mm512_cmplt_epi32_mask(_mm512_castps_si512(m),
                                        _mm512_setzero_si512());
}
#endif
#else /* HF__PASS: a kernel text's words at HF__W lanes */
/* HF__KN(name): the width's copy of a function or type of the text
   (name_v4, name_v8, name_v16); HF__VEC: its vector of HF__W floats;
   HF__VTARGET: its functions' target attribute; HF__VZEROUPPER(): the
   registers readied for SSE or scalar code after AVX (see
   HF__TARGET_AVX2); HF__VGATHER(row, idx): row[idx[0 .. HF__W)] in a
   vector; HF__VLANES(m): every bit of lane l set where bit l of m is;
   HF__VALL: every lane's bit, as HF__VMASK gives them.
   HF__VLD ... HF__VMASK mean what the four-lane operations
   without the V mean (HF__LD, ...), the same IEEE operation at every
   width, so every width gives the scalar code's bytes (the compares
   false on NaN, HF__VMAX maxps's order). */
#if HF__W == 4
#define HF__KN(name) name##_v4
#define HF__VEC hf__v4
#define HF__VTARGET
#define HF__VZEROUPPER() ((void)0)
#define HF__VGATHER(row, idx)                                                  \
    HF__SET4((row)[(idx)[0]], (row)[(idx)[1]], (row)[(idx)[2]], (row)[(idx)[3]])
#define HF__VLD HF__LD
#define HF__VST HF__ST
#define HF__VSET1 HF__SET1
#define HF__VADD HF__ADD
#define HF__VSUB HF__SUB
#define HF__VMUL HF__MUL
#define HF__VDIV HF__DIV
#define HF__VSQRT HF__SQRT
#define HF__VMAX HF__MAX
#define HF__VGT HF__GT
#define HF__VLT HF__LT
#define HF__VEQ HF__EQ
#define HF__VLE HF__LE
#define HF__VAND HF__AND
#define HF__VSEL HF__SEL
#define HF__VMASK HF__MASK
#define HF__VLANES(m) hf__lanes_v4(m)
#elif HF__W == 8
#define HF__KN(name) name##_v8
#define HF__VEC __m256
#define HF__VTARGET HF__TARGET_AVX2
#define HF__VZEROUPPER() _mm256_zeroupper()
#define HF__VGATHER(row, idx)                                                  \
    _mm256_setr_ps((row)[(idx)[0]], (row)[(idx)[1]], (row)[(idx)[2]],         \
                   (row)[(idx)[3]], (row)[(idx)[4]], (row)[(idx)[5]],         \
                   (row)[(idx)[6]], (row)[(idx)[7]])
#define HF__VLD(p) _mm256_loadu_ps(p)
#define HF__VST(p, v) _mm256_storeu_ps(p, v)
#define HF__VSET1(x) _mm256_set1_ps(x)
#define HF__VADD(x, y) _mm256_add_ps(x, y)
#define HF__VSUB(x, y) _mm256_sub_ps(x, y)
#define HF__VMUL(x, y) _mm256_mul_ps(x, y)
#define HF__VDIV(x, y) _mm256_div_ps(x, y)
#define HF__VSQRT(x) _mm256_sqrt_ps(x)
#define HF__VMAX(x, y) _mm256_max_ps(x, y)
#define HF__VGT(x, y) _mm256_cmp_ps(x, y, _CMP_GT_OQ)
#define HF__VLT(x, y) _mm256_cmp_ps(x, y, _CMP_LT_OQ)
#define HF__VEQ(x, y) _mm256_cmp_ps(x, y, _CMP_EQ_OQ)
#define HF__VLE(x, y) _mm256_cmp_ps(x, y, _CMP_LE_OQ)
#define HF__VAND(x, y) _mm256_and_ps(x, y)
#define HF__VSEL(m, a, b) _mm256_blendv_ps(b, a, m)
#define HF__VMASK(m) _mm256_movemask_ps(m)
#define HF__VLANES(m) hf__lanes_v8(m)
#elif HF__W == 16
#define HF__KN(name) name##_v16
#define HF__VEC __m512
#define HF__VTARGET HF__TARGET_AVX512
#define HF__VZEROUPPER() _mm256_zeroupper()
/* a hardware gather: steadier here than sixteen scalar loads (3 % faster,
   where code placement made those 0.089-0.101 ms a step; at eight lanes
   the scalar loads win); the masked form, as HF__VSQRT */
#define HF__VGATHER(row, idx)                                                  \
    _mm512_mask_i32gather_ps(_mm512_setzero_ps(), 0xffff,                     \
                             _mm512_loadu_si512((const void *)(idx)), (row), 4)
#define HF__VLD(p) _mm512_loadu_ps(p)
#define HF__VST(p, v) _mm512_storeu_ps(p, v)
#define HF__VSET1(x) _mm512_set1_ps(x)
#define HF__VADD(x, y) _mm512_add_ps(x, y)
#define HF__VSUB(x, y) _mm512_sub_ps(x, y)
#define HF__VMUL(x, y) _mm512_mul_ps(x, y)
#define HF__VDIV(x, y) _mm512_div_ps(x, y)
/* the masked forms: gcc's plain ones leave lanes "undefined", which its
   C++ front end warns about */
#define HF__VSQRT(x) _mm512_maskz_sqrt_ps(0xffff, x)
#define HF__VMAX(x, y) _mm512_maskz_max_ps(0xffff, x, y)
#define HF__VGT(x, y) hf__m16(_mm512_cmp_ps_mask(x, y, _CMP_GT_OQ))
#define HF__VLT(x, y) hf__m16(_mm512_cmp_ps_mask(x, y, _CMP_LT_OQ))
#define HF__VEQ(x, y) hf__m16(_mm512_cmp_ps_mask(x, y, _CMP_EQ_OQ))
#define HF__VLE(x, y) hf__m16(_mm512_cmp_ps_mask(x, y, _CMP_LE_OQ))
#define HF__VAND(x, y) hf__and16(x, y)
#define HF__VSEL(m, a, b) hf__sel16(m, a, b)
#define HF__VMASK(m) hf__mask16(m)
#define HF__VLANES(m) hf__m16((__mmask16)(m))
#else
#error "hairfur.h: a kernel pass is built at 4, 8 or 16 lanes (HF__W)"
#endif
#define HF__VALL ((1 << HF__W) - 1)
#define HF__VOR(a, b) HF__VSEL(a, a, b) /* masks only */
#define HF__VDOT3(a, b, c, x, y, z)                                            \
    HF__DOT3_OF(HF__VADD, HF__VMUL, a, b, c, x, y, z)
#define HF__VCROSS3(o, a, b) HF__CROSS3_OF(HF__VSUB, HF__VMUL, o, a, b)
#define HF__VPOSE(o, a, b, c, x, y, z)                                         \
    HF__POSE_OF(HF__VADD, HF__VMUL, o, a, b, c, x, y, z)
#endif /* HF__PASS */

#ifndef HF__PASS /* the implementation's text; a kernel pass skips it */

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

#if HF__X86_DISPATCH && defined(_MSC_VER) && !defined(__clang__) &&          \
    !defined(__GNUC__)
#define HF__MSVC_CPUID 1
/* What CPUID says: the ISA bits (leaf 7: EBX bit 5 AVX2, bits 16 and 30
   AVX-512F and BW) count only where the OS saves the registers (XCR0:
   bits 1-2 for 256 bits, and 5-7 as well for 512). */
HF__PRIVATE int hf__cpuid_simd(void)
{
    int r[4];
    unsigned long long xcr0 = 0;
    __cpuid(r, 0);
    if (r[0] < 7) return HF_SIMD_SSE2;
    __cpuid(r, 1);
    if (((r[2] >> 27) & 1) == 0) return HF_SIMD_SSE2; /* no OSXSAVE */
    xcr0 = _xgetbv(0);
    __cpuidex(r, 7, 0);
    if ((r[1] >> 16 & 1) && (r[1] >> 30 & 1) && (xcr0 & 0xe6) == 0xe6)
        return HF_SIMD_AVX512;
    if ((r[1] >> 5 & 1) && (xcr0 & 6) == 6) return HF_SIMD_AVX2;
    return HF_SIMD_SSE2;
}
#else
#define HF__MSVC_CPUID 0
#endif

/* The best level the CPU runs in this build. */
HF__PRIVATE int hf__cpu_simd(void)
{
#if HF__MSVC_CPUID
    /* CPUID once a process, as libgcc reads it once for gcc: where Windows
       runs under a hypervisor (virtualisation-based security), every
       CPUID exits to it, microseconds that every call would pay. A thread
       that finds 0 asks and stores the same answer; x86 reads and writes
       an aligned long whole. */
    static volatile long level;
    long v = level;
    if (v == 0) level = v = hf__cpuid_simd();
    return (int)v;
#elif HF__X86_DISPATCH
    /* libgcc (or compiler-rt) reads CPUID and XCR0 at load time, so this
       also knows whether the OS saves the wide registers */
    if (__builtin_cpu_supports("avx512f") &&
        __builtin_cpu_supports("avx512bw"))
        return HF_SIMD_AVX512;
    if (__builtin_cpu_supports("avx2")) return HF_SIMD_AVX2;
    return HF_SIMD_SSE2;
#elif HF__AVX512
    return HF_SIMD_AVX512;
#elif HF__AVX2
    return HF_SIMD_AVX2;
#elif HF__SSE || HF__NEON
    return HF_SIMD_SSE2;
#else
    return HF_SIMD_SCALAR;
#endif
}

/* An hf_simd_level and a choice of stores (0 by size, 1 streaming, 2
   ordinary): every kernel choice (the simd and nontemporal fields,
   hf_fur_set_kernels) is checked here, and anything else is
   HF_ERROR_BAD_PARAMETER. */
HF__PRIVATE int hf__kernels_ok(int simd, int nontemporal)
{
    return simd >= HF_SIMD_AUTO && simd <= HF_SIMD_AVX512 &&
           nontemporal >= 0 && nontemporal <= 2;
}

/* Streaming stores for an output of `bytes`: asked for (1), or by size
   (0), past `min`: there the cache does not keep an output for whatever
   reads it next (the GPU, the next stage), and ordinary stores would read
   each line in first; below it they leave the lines in the cache to be
   written back later. Measured (make bench, one core of a Zen 5 and of a
   Xeon, streaming against ordinary stores): strand points 1.7x faster
   for 7 MB (Zen 4), 3 % slower for 0.7 MB (HF_STREAM_MIN_BYTES); 36-byte
   ribbons 1.04-1.10x and 1.8x faster for 42 and 115 MB, 1.4-1.5x slower
   for 4.2 MB, GPU points 1.4x and 1.15x faster for 9.4 MB
   (HF_STREAM_MIN_VERTEX_BYTES, between those). */
HF__PRIVATE int hf__streaming(int nontemporal, size_t bytes, size_t min)
{
    return nontemporal == 1 || (nontemporal == 0 && bytes > min);
}

HFDEF int hf_simd_resolve(int requested)
{
    int best = hf__cpu_simd();
    if (best > HF_SIMD_MAX) best = HF_SIMD_MAX < 1 ? 1 : HF_SIMD_MAX;
    if (requested < HF_SIMD_SCALAR || requested > HF_SIMD_AVX512)
        return best;
    return requested < best ? requested : best;
}

/* The dispatch, one shape for every stage. A stage's kernels stand in a
   const array of descriptors beside them, hf__<stage>_widths, one a
   width, widest first, ending with the scalar reference (width 1, which
   every build has). Each descriptor opens with its hf__isa: the lanes,
   the hf_simd_level it needs and the instruction set its kernels use (a
   kernel is named by its width, hf__<name>_v1, _v4, _v8 or _v16, not by
   its ISA: _v4 is SSE2 or NEON, whichever the build targets). A call
   resolves its level once, hf__kernels_for(widths, level): the widest
   descriptor whose level is at most the one asked for (0: the best) and
   the CPU runs. From there a stage either calls one kernel for its whole
   range, or walks down the array: a kernel does what its width can (whole
   groups of its lanes, or the data shapes it is built for) and returns
   where it stopped, the narrower ones take the rest, and the scalar one
   finishes. */
typedef struct hf__isa {
    int lanes;        /* 1, 4, 8 or 16 */
    int level;        /* the hf_simd_level its kernels need */
    const char *name; /* the instruction set: "scalar", "SSE2", ... */
} hf__isa;
/* a descriptor's hf__isa, between braces: {{HF__ISA_V4}, kernels...} */
#define HF__ISA_V1 1, HF_SIMD_SCALAR, "scalar"
#if HF__SSE
#define HF__ISA_V4 4, HF_SIMD_SSE2, "SSE2"
#else
#define HF__ISA_V4 4, HF_SIMD_NEON, "NEON"
#endif
#define HF__ISA_V8 8, HF_SIMD_AVX2, "AVX2"
#define HF__ISA_V16 16, HF_SIMD_AVX512, "AVX-512"

/* The index in a stage's widths (first descriptor widest, `size` bytes
   each) of the one hf__kernels_for picks for the requested level. */
HF__PRIVATE int hf__kernels_index(const hf__isa *widest, size_t size,
                                  int requested)
{
    const int level = hf_simd_resolve(requested);
    const unsigned char *d = (const unsigned char *)widest;
    int i = 0;
    while (((const hf__isa *)(const void *)(d + (size_t)i * size))->level >
           level)
        ++i;
    return i;
}
#define hf__kernels_for(widths, requested)                                     \
    ((widths) +                                                                \
     hf__kernels_index(&(widths)[0].isa, sizeof((widths)[0]), (requested)))

/* ---- 1.1 defaults: what every zero field means, in one place ------------ */

/* Every public struct follows one rule: a zero field means the default
   documented beside it. Each entry point resolves its struct here into a
   local copy, then validates and uses only that copy. A NaN is not zero,
   so it reaches validation. */
HF__PRIVATE float hf__def_f(float v, float def) { return v != 0.0f ? v : def; }
HF__PRIVATE double hf__def_d(double v, double def)
{
    return v != 0.0 ? v : def;
}
HF__PRIVATE int hf__def_i(int v, int def) { return v != 0 ? v : def; }

HF__PRIVATE void hf__rope_params_resolve(const hf_rope_params *in,
                                         hf_rope_params *p)
{
    const int z = in->explicit_zero;
    *p = *in;
    if (!(z & HF_ROPE_ZERO_GRAVITY) && p->gravity[0] == 0.0f &&
        p->gravity[1] == 0.0f && p->gravity[2] == 0.0f)
        p->gravity[1] = -9.81f;
    p->turbulence_frequency = hf__def_f(p->turbulence_frequency, 1.0f);
    if (!(z & HF_ROPE_ZERO_DAMPING)) p->damping = hf__def_f(p->damping, 0.02f);
    p->time_scale = hf__def_f(p->time_scale, 1.0f);
    p->substep = hf__def_f(p->substep, 1.0f / 60.0f);
    p->max_substeps = hf__def_i(p->max_substeps, 8);
    p->max_dt = hf__def_f(p->max_dt, 1.0f / 15.0f);
    if (!(z & HF_ROPE_ZERO_ITERATIONS))
        p->iterations = hf__def_i(p->iterations, 2);
    if (!(z & HF_ROPE_ZERO_FTL_DAMPING))
        p->ftl_damping = hf__def_f(p->ftl_damping, 0.9f);
    if (!(z & HF_ROPE_ZERO_MARGIN))
        p->collision_margin = hf__def_f(p->collision_margin, 0.002f);
    if (!(z & HF_ROPE_ZERO_BLEND_TIME))
        p->mode_blend_time = hf__def_f(p->mode_blend_time, 0.25f);
    if (!(z & HF_ROPE_ZERO_VOLUME)) p->volume = hf__def_f(p->volume, 1.0f);
    if (!(z & HF_ROPE_ZERO_FRICTION))
        p->friction = hf__def_f(p->friction, 0.2f);
}

HF__PRIVATE void hf__lut_params_resolve(const hf_lut_params *in,
                                        hf_lut_params *p)
{
    const int z = in->explicit_zero;
    int k;
    *p = *in;
    p->eta = hf__def_d(p->eta, 1.55);
    if (!(z & HF_LUT_ZERO_ALPHA_R))
        p->alpha_r_deg = hf__def_d(p->alpha_r_deg, -7.5);
    p->beta_r_deg = hf__def_d(p->beta_r_deg, 7.5);
    if (!(z & HF_LUT_ZERO_SIGMA_A)) p->sigma_a = hf__def_d(p->sigma_a, 0.2);
    if (!(z & HF_LUT_ZERO_SIGMA_A_RGB))
        for (k = 0; k < 3; ++k)
            p->sigma_a_rgb[k] = hf__def_d(p->sigma_a_rgb[k], p->sigma_a);
    p->size = hf__def_i(p->size, 256);
}

HF__PRIVATE void hf__ribbon_params_resolve(const hf_ribbon_params *in,
                                           hf_ribbon_params *p)
{
    *p = *in;
    if (p->root_width == 0.0f && p->tip_width == 0.0f) {
        p->root_width = HF_RIBBON_DEFAULT_ROOT_WIDTH;
        p->tip_width = HF_RIBBON_DEFAULT_TIP_WIDTH;
    }
    p->taper_power = hf__def_f(p->taper_power, 1.0f);
    p->width_scale = hf__def_f(p->width_scale, 1.0f);
    if (p->alpha_root == 0.0f && p->alpha_tip == 0.0f)
        p->alpha_root = p->alpha_tip = 1.0f;
    p->point_scale = hf__def_f(p->point_scale, 1.0f);
}

HF__PRIVATE void hf__tess_params_resolve(const hf_tess_params *in,
                                         hf_tess_params *p)
{
    *p = *in;
    p->max_depth = hf__def_i(p->max_depth, HF_TESS_DEFAULT_MAX_DEPTH);
    p->max_triangles =
        hf__def_i(p->max_triangles, HF_TESS_DEFAULT_MAX_TRIANGLES);
}

HF__PRIVATE void hf__place_params_resolve(const hf_place_params *in,
                                          hf_place_params *p)
{
    *p = *in;
    p->max_strands = hf__def_i(p->max_strands, HF_MAX_STRANDS);
}

/* The fur description; rope_params is resolved into *rope. */
HF__PRIVATE void hf__fur_desc_resolve(const hf_fur_desc *in, hf_fur_desc *d,
                                      hf_rope_params *rope)
{
    hf_rope_params zero;
    *d = *in;
    d->points_per_strand = hf__def_i(d->points_per_strand, 16);
    d->max_length = hf__def_f(d->max_length, 0.05f);
    if (d->strands_per_area == 0.0f && d->total_strands == 0)
        d->total_strands = 10000;
    d->lod_simulate_threshold = hf__def_f(d->lod_simulate_threshold, 0.5f);
    HF_MEMSET(&zero, 0, sizeof zero);
    hf__rope_params_resolve(in->rope_params ? in->rope_params : &zero, rope);
    d->rope_params = rope;
}

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

/* Arrays the wide kernels stream through, on 64-byte boundaries (a cache
   line, a sixteen-float vector: no load or store split across two lines)
   whatever the allocator's alignment: the byte before the array says how
   far it was moved. */
HF__PRIVATE void *hf__alloc64(const hf_allocator *a, size_t size)
{
    unsigned char *p;
    size_t k;
    if (size > (size_t)-1 - 64) return NULL;
    p = (unsigned char *)hf__alloc(a, size + 64);
    if (!p) return NULL;
    k = 64u - ((uintptr_t)p & 63u); /* 1 .. 64 */
    p += k;
    p[-1] = (unsigned char)k;
    return p;
}

HF__PRIVATE void hf__free64(const hf_allocator *a, void *ptr)
{
    unsigned char *p = (unsigned char *)ptr;
    if (p) hf__free(a, p - p[-1]);
}

/* first >= 0, count >= 0 and first + count representable */
HF__PRIVATE int hf__range_ok(int first, int count)
{
    return first >= 0 && count >= 0 && count <= 0x7fffffff - first;
}

/* A float array with a byte stride: the stride 0 (packed) or at least the
   element and a multiple of 4, and the pointer 4-byte aligned, so that
   every float read is an aligned load (anything else is undefined
   behaviour on strict targets). */
HF__PRIVATE int hf__stride_ok(const void *ptr, int stride, int elem)
{
    if (ptr && ((uintptr_t)ptr & 3u) != 0) return 0;
    return stride == 0 || (stride >= elem && (stride & 3) == 0);
}

/* a * b without wrap-around: returns 0 and leaves *out alone on overflow. */
HF__PRIVATE int hf__mul_size(size_t a, size_t b, size_t *out)
{
    if (a != 0 && b > (size_t)-1 / a) return 0;
    *out = a * b;
    return 1;
}

/* ---- 1.2 small vector helpers ------------------------------------------- */

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
                        "map.row_stride %d is below one packed row (%lu "
                        "bytes)",
                        map->row_stride, (unsigned long)packed_row);
    if (!hf__mul_size(hf__map_row_stride(map), (size_t)map->height, &total))
        return hf__fail(diag, HF_ERROR_OVERFLOW, "row_stride", -1,
                        "map.row_stride * height overflows size_t");
    if (map->format == HF_MAP_F32 && !hf__stride_ok(map->data, map->row_stride, 4))
        return hf__fail(diag, HF_ERROR_BAD_STRIDE, "row_stride", -1,
                        "a float map needs 4-byte aligned data and a row "
                        "stride that is a multiple of 4 (row_stride %d)",
                        map->row_stride);
    if (map->format == HF_MAP_F32) {
        int x, y, c;
        size_t stride = hf__map_row_stride(map);
        for (y = 0; y < map->height; ++y) {
            const float *row =
                (const float *)((const unsigned char *)map->data +
                                (size_t)y * stride);
            for (x = 0; x < map->width; ++x)
                for (c = 0; c < map->channels; ++c) {
                    const float v = row[x * map->channels + c];
                    if (!hf__finitef(v))
                        return hf__fail(
                            diag, HF_ERROR_NON_FINITE, "data",
                            (long long)y * map->width + x,
                            "map texel (%d, %d) channel %d is not finite", x,
                            y, c);
                    /* a bound that keeps every sum, mean and product the
                       stages take of map values finite */
                    if (v > HF_MAP_MAX_VALUE || v < -HF_MAP_MAX_VALUE)
                        return hf__fail(
                            diag, HF_ERROR_BAD_PARAMETER, "data",
                            (long long)y * map->width + x,
                            "map texel (%d, %d) channel %d = %g is beyond "
                            "+-%g",
                            x, y, c, (double)v, (double)HF_MAP_MAX_VALUE);
                }
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
                                       const void *ptr, int stride, int size)
{
    if (!hf__stride_ok(ptr, stride, size))
        return hf__fail(diag, HF_ERROR_BAD_STRIDE, field, -1,
                        "%s %d is not 0 or a multiple of 4 of at least the "
                        "element size %d, or its array is not 4-byte "
                        "aligned",
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
    if ((r = hf__check_stride(diag, "position_stride", mesh->positions,
                              mesh->position_stride, 12)) != HF_OK ||
        (r = hf__check_stride(diag, "normal_stride", mesh->normals,
                              mesh->normal_stride, 12)) != HF_OK ||
        (r = hf__check_stride(diag, "uv_stride", mesh->uvs, mesh->uv_stride,
                              8)) != HF_OK)
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
                                "indices[%.0f] = %u is not less than "
                                "vertex_count %d",
                                (double)(3LL * t + k), (unsigned)v,
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

/* ---- 5. grow: tessellation, guides, placement, maps, bindings ----------- */


/* The record sizes the documentation promises. */
typedef char hf__strand_is_24_bytes[sizeof(hf_strand) == 24 ? 1 : -1];
typedef char hf__tess_vertex_is_16_bytes[sizeof(hf_tess_vertex) == 16 ? 1
                                                                       : -1];

HF__PRIVATE const float *hf__mesh_uv(const hf_mesh *m, int i)
{
    return hf__attr(m->uvs, m->uv_stride, 8, i);
}

HF__PRIVATE const float *hf__mesh_nrm(const hf_mesh *m, int i)
{
    return hf__attr(m->normals, m->normal_stride, 12, i);
}

/* w0 a + w1 b + w2 c in one fixed order of operations. The tessellator and
   every re-evaluation (hf_tess_evaluate, hf_guides_rest, hf_strand_roots)
   go through these two functions, and keeping them out of line means the
   compiler cannot contract or reorder them differently at each call site:
   that is what makes re-evaluation bit-exact. */
HF__PRIVATE HF__NOINLINE void hf__blend3(float *o, const float *a,
                                         const float *b, const float *c,
                                         const float *w)
{
    float x = (w[0] * a[0] + w[1] * b[0]) + w[2] * c[0];
    float y = (w[0] * a[1] + w[1] * b[1]) + w[2] * c[1];
    float z = (w[0] * a[2] + w[1] * b[2]) + w[2] * c[2];
    o[0] = x;
    o[1] = y;
    o[2] = z;
}

HF__PRIVATE HF__NOINLINE void hf__blend2(float *o, const float *a,
                                         const float *b, const float *c,
                                         const float *w)
{
    float x = (w[0] * a[0] + w[1] * b[0]) + w[2] * c[0];
    float y = (w[0] * a[1] + w[1] * b[1]) + w[2] * c[1];
    o[0] = x;
    o[1] = y;
}

/* Normalise in place; 0 (and v untouched) when v has no usable length. */
HF__PRIVATE int hf__normalize3(float *v)
{
    float len2 = hf__dot3(v, v), s;
    if (!(len2 > 1e-30f) || !hf__finitef(len2)) return 0;
    s = 1.0f / HF_SQRTF(len2);
    v[0] *= s;
    v[1] *= s;
    v[2] *= s;
    return 1;
}

/* Unit normal of triangle (a, b, c), or (0, 0, 1) when it has none. */
HF__PRIVATE void hf__face_normal(float *o, const float *a, const float *b,
                                 const float *c)
{
    float e1[3], e2[3];
    hf__sub3(e1, b, a);
    hf__sub3(e2, c, a);
    hf__cross3(o, e1, e2);
    if (!hf__normalize3(o)) {
        o[0] = 0.0f;
        o[1] = 0.0f;
        o[2] = 1.0f;
    }
}

HF__PRIVATE int hf__all_finite(const float *v, int n)
{
    int i;
    for (i = 0; i < n; ++i)
        if (!hf__finitef(v[i])) return 0;
    return 1;
}

HF__PRIVATE float hf__clamp0(float x) { return x > 0.0f ? x : 0.0f; }

HF__PRIVATE float hf__clamp01(float x)
{
    return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
}

/* ---- 5.1 density of a UV triangle --------------------------------------- */

/* Channel 0 of texel (x, y), any integer x, y (the map's wrap applies),
   read as 0 when negative. */
HF__PRIVATE float hf__texel0(const hf_map *m, int x, int y)
{
    const unsigned char *row;
    size_t i;
    x = hf__wrap_index(x, m->width, m->wrap);
    y = hf__wrap_index(y, m->height, m->wrap);
    row = (const unsigned char *)m->data + (size_t)y * hf__map_row_stride(m);
    i = (size_t)x * (size_t)m->channels;
    if (m->format == HF_MAP_F32) return hf__clamp0(((const float *)row)[i]);
    return (float)row[i] / 255.0f;
}

HF__PRIVATE float hf__sample0(const hf_map *m, float u, float v)
{
    float s[4];
    hf_map_sample_fast(m, u, v, s);
    return hf__clamp0(s[0]);
}

/* The UV triangle in texel units (x = u * width, y = v * height), moved by
   whole periods on a repeating map so it starts in period 0; refuses a
   triangle beyond HF_DENSITY_MAX_UV_SPAN (the rasterisers' cost and int
   range depend on it). */
HF__PRIVATE hf_result hf__texel_space(const hf_map *m, const float *a,
                                      const float *b, const float *c,
                                      double *x, double *y)
{
    double u[3], v[3];
    const double lo = -(double)HF_DENSITY_MAX_UV_SPAN;
    const double hi = 1.0 + (double)HF_DENSITY_MAX_UV_SPAN;
    int k;
    u[0] = a[0];
    u[1] = b[0];
    u[2] = c[0];
    v[0] = a[1];
    v[1] = b[1];
    v[2] = c[1];
    if (m->wrap == HF_WRAP_REPEAT) {
        double su = u[0], sv = v[0];
        for (k = 1; k < 3; ++k) {
            if (u[k] < su) su = u[k];
            if (v[k] < sv) sv = v[k];
        }
        su = HF_FLOOR(su);
        sv = HF_FLOOR(sv);
        for (k = 0; k < 3; ++k) {
            u[k] -= su;
            v[k] -= sv;
        }
    }
    for (k = 0; k < 3; ++k) {
        if (!(u[k] >= lo && u[k] <= hi && v[k] >= lo && v[k] <= hi))
            return HF_ERROR_BAD_RANGE;
        x[k] = u[k] * (double)m->width;
        y[k] = v[k] * (double)m->height;
    }
    return HF_OK;
}

/* Texels of the Bresenham line from (x0, y0) to (x1, y1), the end texel
   excluded (it starts the next edge), the start included even when the
   line is a single texel. */
HF__PRIVATE void hf__bresenham(const hf_map *m, int x0, int y0, int x1,
                               int y1, double *sum, double *n)
{
    int dx = x1 > x0 ? x1 - x0 : x0 - x1, sx = x0 < x1 ? 1 : -1;
    int dy = -(y1 > y0 ? y1 - y0 : y0 - y1), sy = y0 < y1 ? 1 : -1;
    int err = dx + dy, e2;
    if (x0 == x1 && y0 == y1) {
        *sum += hf__texel0(m, x0, y0);
        *n += 1.0;
        return;
    }
    while (x0 != x1 || y0 != y1) {
        *sum += hf__texel0(m, x0, y0);
        *n += 1.0;
        e2 = 2 * err;
        if (e2 >= dy) {
            err += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            err += dx;
            y0 += sy;
        }
    }
}

/* Sutherland-Hodgman against one axis-aligned line: keeps the part with
   p[axis] >= value (above != 0) or <= value. At most 2 n points out. */
HF__PRIVATE int hf__clip_half(const double *in, int n, double *out, int axis,
                              double value, int above)
{
    int i, m = 0;
    for (i = 0; i < n; ++i) {
        const double *p = in + 2 * i;
        const double *q = in + 2 * ((i + 1) % n);
        double dp = above ? p[axis] - value : value - p[axis];
        double dq = above ? q[axis] - value : value - q[axis];
        if (dp >= 0.0) {
            out[2 * m] = p[0];
            out[2 * m + 1] = p[1];
            ++m;
        }
        if ((dp >= 0.0) != (dq >= 0.0)) {
            double t = dp / (dp - dq);
            out[2 * m] = p[0] + t * (q[0] - p[0]);
            out[2 * m + 1] = p[1] + t * (q[1] - p[1]);
            ++m;
        }
    }
    return m;
}

HF__PRIVATE double hf__poly_area(const double *p, int n)
{
    double s = 0.0;
    int i;
    for (i = 0; i < n; ++i) {
        const double *a = p + 2 * i, *b = p + 2 * ((i + 1) % n);
        s += a[0] * b[1] - b[0] * a[1];
    }
    return 0.5 * HF_FABS(s);
}

/* Exact coverage rasteriser: the triangle is clipped to each texel row,
   then each row piece to each texel of the row; every texel's value is
   weighted by the area inside it. Returns the weight sum (0: no area). */
HF__PRIVATE double hf__area_mean(const hf_map *m, const double *x,
                                 const double *y, double *mean)
{
    /* 3 points clipped by 4 lines: at most 48 (2 n per clip) */
    double tri[6], a[96], row[96], b[96], cell[96];
    double ymin = y[0], ymax = y[0], sum = 0.0, wsum = 0.0;
    int k, j, j0, j1;
    for (k = 0; k < 3; ++k) {
        tri[2 * k] = x[k];
        tri[2 * k + 1] = y[k];
        if (y[k] < ymin) ymin = y[k];
        if (y[k] > ymax) ymax = y[k];
    }
    j0 = (int)HF_FLOOR(ymin);
    j1 = (int)HF_CEIL(ymax);
    if (j1 <= j0) j1 = j0 + 1;
    for (j = j0; j < j1; ++j) {
        int n = hf__clip_half(tri, 3, a, 1, (double)j, 1), i, i0, i1;
        double xmin, xmax;
        n = n >= 3 ? hf__clip_half(a, n, row, 1, (double)j + 1.0, 0) : 0;
        if (n < 3) continue;
        xmin = xmax = row[0];
        for (k = 1; k < n; ++k) {
            if (row[2 * k] < xmin) xmin = row[2 * k];
            if (row[2 * k] > xmax) xmax = row[2 * k];
        }
        i0 = (int)HF_FLOOR(xmin);
        i1 = (int)HF_CEIL(xmax);
        if (i1 <= i0) i1 = i0 + 1;
        for (i = i0; i < i1; ++i) {
            int c = hf__clip_half(row, n, b, 0, (double)i, 1);
            double w;
            c = c >= 3 ? hf__clip_half(b, c, cell, 0, (double)i + 1.0, 0) : 0;
            if (c < 3) continue;
            w = hf__poly_area(cell, c);
            if (w > 0.0) {
                sum += w * (double)hf__texel0(m, i, j);
                wsum += w;
            }
        }
    }
    *mean = wsum > 0.0 ? sum / wsum : 0.0;
    return wsum;
}

/* Density of a UV triangle; `m` validated or NULL (density 1). */
HF__PRIVATE hf_result hf__density(const hf_map *m, const float *a,
                                  const float *b, const float *c,
                                  int est, float *out)
{
    double x[3], y[3];
    hf_result r;
    if (!m) {
        *out = 1.0f;
        return HF_OK;
    }
    if (est != HF_DENSITY_CORNERS) {
        r = hf__texel_space(m, a, b, c, x, y);
        if (r != HF_OK) return r;
        if (est == HF_DENSITY_EDGES) {
            double sum = 0.0, n = 0.0;
            int xi[3], yi[3], k;
            for (k = 0; k < 3; ++k) {
                xi[k] = (int)HF_FLOOR(x[k]);
                yi[k] = (int)HF_FLOOR(y[k]);
            }
            for (k = 0; k < 3; ++k)
                hf__bresenham(m, xi[k], yi[k], xi[(k + 1) % 3],
                              yi[(k + 1) % 3], &sum, &n);
            *out = (float)(sum / n);
            return HF_OK;
        } else {
            double mean;
            if (hf__area_mean(m, x, y, &mean) > 0.0) {
                *out = (float)mean;
                return HF_OK;
            }
            /* zero UV area: no interior to average, use the corners */
        }
    }
    *out = (hf__sample0(m, a[0], a[1]) + hf__sample0(m, b[0], b[1]) +
            hf__sample0(m, c[0], c[1])) /
           3.0f;
    return HF_OK;
}

HFDEF hf_result hf_uv_triangle_density(const hf_map *density,
                                       const float uv0[2], const float uv1[2],
                                       const float uv2[2],
                                       int estimator, float *out_density)
{
    hf_result r;
    float d;
    if (!uv0 || !uv1 || !uv2 || !out_density) return HF_ERROR_NULL_POINTER;
    if (density && (r = hf_map_validate(density, NULL)) != HF_OK) return r;
    if (!hf__all_finite(uv0, 2) || !hf__all_finite(uv1, 2) ||
        !hf__all_finite(uv2, 2))
        return HF_ERROR_NON_FINITE;
    if (estimator < 0 || estimator > 2)
        return HF_ERROR_BAD_PARAMETER;
    r = hf__density(density, uv0, uv1, uv2, estimator, &d);
    if (r != HF_OK) return r;
    *out_density = d;
    return HF_OK;
}

/* ---- 5.2 density tessellation ------------------------------------------- */

typedef struct hf__tess_corner {
    uint32_t ref;  /* index in the output vertex list */
    float bary[3]; /* in the base triangle */
    float pos[3];
    float uv[2];
} hf__tess_corner;

typedef struct hf__tess_item {
    hf__tess_corner c[3];
    int depth;
} hf__tess_item;

typedef struct hf__tess_ctx {
    const hf_mesh *mesh;
    const hf_map *density;
    float factor;
    int estimator, split;
    uint64_t seed;
    int max_depth, max_triangles, refuse_degenerate;
    /* results of a run */
    long long triangles, added;
    int depth;
} hf__tess_ctx;

/* One pass over every base triangle: counts (out NULL) or fills the
   arrays of out that are not NULL. Both passes make the same decisions
   from the same arithmetic, so the fill pass writes exactly what the
   count pass counted. */
HF__PRIVATE hf_result hf__tess_run(hf__tess_ctx *c, hf_tess_output *out)
{
    const hf_mesh *m = c->mesh;
    /* depth-first: at most 2 siblings wait per level, plus the current */
    hf__tess_item stack[2 * HF_TESS_MAX_DEPTH + 2];
    long long tris = m->triangle_count, added = 0, emitted = 0;
    const uint32_t V = (uint32_t)m->vertex_count;
    int t, depth = 0, any_area = 0;
    if (tris > c->max_triangles) return HF_ERROR_TRIANGLE_CAP;
    for (t = 0; t < m->triangle_count; ++t) {
        const uint32_t *tri = m->indices + 3 * (size_t)t;
        const float *P[3];
        const float *UV[3];
        static const float zero_uv[2] = {0.0f, 0.0f};
        hf_rng rng;
        int sp = 0, k;
        float area;
        hf__tess_item *root = &stack[sp++];
        for (k = 0; k < 3; ++k) {
            hf__tess_corner *q = &root->c[k];
            P[k] = hf__mesh_pos(m, (int)tri[k]);
            UV[k] = m->uvs ? hf__mesh_uv(m, (int)tri[k]) : zero_uv;
            q->ref = tri[k];
            q->bary[0] = k == 0 ? 1.0f : 0.0f;
            q->bary[1] = k == 1 ? 1.0f : 0.0f;
            q->bary[2] = k == 2 ? 1.0f : 0.0f;
            HF_MEMCPY(q->pos, P[k], sizeof q->pos);
            HF_MEMCPY(q->uv, UV[k], sizeof q->uv);
        }
        root->depth = 0;
        area = hf_triangle_area(P[0], P[1], P[2]);
        if (!hf__finitef(area)) return HF_ERROR_NON_FINITE;
        if (area > 0.0f)
            any_area = 1;
        else if (c->refuse_degenerate)
            return HF_ERROR_DEGENERATE;
        /* one stream per base triangle: independent of the others */
        hf_rng_seed(&rng, c->seed, (uint64_t)t);
        while (sp > 0) {
            hf__tess_item it = stack[--sp];
            hf__tess_corner y;
            float w[3], d = 1.0f;
            int split = 0;
            area = hf_triangle_area(it.c[0].pos, it.c[1].pos, it.c[2].pos);
            if (area > 0.0f) {
                hf_result r = hf__density(c->density, it.c[0].uv,
                                          it.c[1].uv, it.c[2].uv,
                                          c->estimator, &d);
                if (r != HF_OK) return r;
                split = d * area * c->factor > 1.0f;
            }
            if (!split) {
                if (out && out->indices)
                    for (k = 0; k < 3; ++k)
                        out->indices[3 * (size_t)emitted + (size_t)k] =
                            it.c[k].ref;
                if (out && out->triangle_base)
                    out->triangle_base[emitted] = (uint32_t)t;
                ++emitted;
                if (it.depth > depth) depth = it.depth;
                continue;
            }
            if (it.depth >= c->max_depth) return HF_ERROR_DEPTH_CAP;
            tris += 2;
            if (tris > c->max_triangles) return HF_ERROR_TRIANGLE_CAP;
            if (c->split == HF_SPLIT_RANDOM) {
                /* uniform point of the triangle, pulled half way to the
                   centroid: every weight >= 1/6 */
                float s = HF_SQRTF(hf_rng_float(&rng)), r2 = hf_rng_float(&rng);
                w[0] = 0.5f * (1.0f - s) + (1.0f / 6.0f);
                w[1] = 0.5f * (s * (1.0f - r2)) + (1.0f / 6.0f);
            } else {
                w[0] = 1.0f / 3.0f;
                w[1] = 1.0f / 3.0f;
            }
            w[2] = (1.0f - w[0]) - w[1];
            hf__blend3(y.bary, it.c[0].bary, it.c[1].bary, it.c[2].bary, w);
            hf__blend3(y.pos, P[0], P[1], P[2], y.bary);
            hf__blend2(y.uv, UV[0], UV[1], UV[2], y.bary);
            y.ref = V + (uint32_t)added;
            if (out) {
                size_t vi = (size_t)V + (size_t)added;
                if (out->added) {
                    out->added[added].triangle = (uint32_t)t;
                    HF_MEMCPY(out->added[added].bary, y.bary, sizeof y.bary);
                }
                if (out->positions)
                    HF_MEMCPY(out->positions + 3 * vi, y.pos, sizeof y.pos);
                if (out->uvs) HF_MEMCPY(out->uvs + 2 * vi, y.uv, sizeof y.uv);
            }
            ++added;
            /* children (a, b, Y), (b, c, Y), (c, a, Y): pushed in reverse
               so they come out in that order */
            for (k = 2; k >= 0; --k) {
                hf__tess_item *ch = &stack[sp++];
                ch->c[0] = it.c[k];
                ch->c[1] = it.c[(k + 1) % 3];
                ch->c[2] = y;
                ch->depth = it.depth + 1;
            }
        }
    }
    if (!any_area) return HF_ERROR_DEGENERATE;
    HF_ASSERT(emitted == tris);
    c->triangles = tris;
    c->added = added;
    c->depth = depth;
    return HF_OK;
}

HFDEF hf_result hf_tessellate(const hf_mesh *mesh, const hf_map *density,
                              const hf_tess_params *in,
                              hf_tess_output *out)
{
    hf__tess_ctx c;
    hf_tess_params prm;
    const hf_tess_params *params = &prm;
    hf_result r;
    long long vertices;
    int writing;
    if (!mesh || !in || !out) return HF_ERROR_NULL_POINTER;
    hf__tess_params_resolve(in, &prm);
    if ((r = hf_mesh_validate(mesh, NULL)) != HF_OK) return r;
    if (density && (r = hf_map_validate(density, NULL)) != HF_OK) return r;
    if ((density || out->uvs) && !mesh->uvs) return HF_ERROR_NULL_POINTER;
    if (!hf__finitef(params->factor) || !(params->factor > 0.0f) ||
        params->estimator < 0 || params->estimator > 2 ||
        params->split < 0 || params->split > 1 ||
        params->max_depth < 1 || params->max_depth > HF_TESS_MAX_DEPTH ||
        params->max_triangles < 1 ||
        params->max_triangles > HF_TESS_MAX_TRIANGLES)
        return HF_ERROR_BAD_PARAMETER;
    c.mesh = mesh;
    c.density = density;
    c.factor = params->factor;
    c.estimator = params->estimator;
    c.split = params->split;
    c.seed = params->seed;
    c.max_depth = params->max_depth;
    c.max_triangles = params->max_triangles;
    c.refuse_degenerate = params->refuse_degenerate != 0;
    /* the counting pass: every error, caps included, comes from here */
    if ((r = hf__tess_run(&c, NULL)) != HF_OK) return r;
    vertices = (long long)mesh->vertex_count + c.added;
    if (vertices > 0x7fffffffLL) return HF_ERROR_OVERFLOW;
    writing = out->indices || out->triangle_base || out->added ||
              out->positions || out->uvs;
    if (writing) {
        hf__tess_ctx fill = c;
        if (((out->indices || out->triangle_base) &&
             out->triangle_capacity < c.triangles) ||
            (out->added && out->added_capacity < c.added) ||
            ((out->positions || out->uvs) && out->vertex_capacity < vertices))
            return HF_ERROR_BUFFER_TOO_SMALL;
        r = hf__tess_run(&fill, out);
        HF_ASSERT(r == HF_OK && fill.triangles == c.triangles &&
                  fill.added == c.added);
        (void)r;
        if (out->positions || out->uvs) {
            int i;
            for (i = 0; i < mesh->vertex_count; ++i) {
                if (out->positions)
                    HF_MEMCPY(out->positions + 3 * (size_t)i,
                              hf__mesh_pos(mesh, i), 3 * sizeof(float));
                if (out->uvs)
                    HF_MEMCPY(out->uvs + 2 * (size_t)i, hf__mesh_uv(mesh, i),
                              2 * sizeof(float));
            }
        }
    }
    out->triangle_count = (int)c.triangles;
    out->added_count = (int)c.added;
    out->vertex_count = (int)vertices;
    out->depth = c.depth;
    return HF_OK;
}

/* The checks a per-frame function needs on a mesh view, without reading
   every element (hf_mesh_validate does that, once, at creation). */
HF__PRIVATE hf_result hf__mesh_shape_ok(const hf_mesh *m)
{
    if (!m || !m->positions || !m->indices) return HF_ERROR_NULL_POINTER;
    if (m->vertex_count < 1 || m->triangle_count < 1) return HF_ERROR_BAD_COUNT;
    if (!hf__stride_ok(m->positions, m->position_stride, 12) ||
        !hf__stride_ok(m->normals, m->normal_stride, 12) ||
        !hf__stride_ok(m->uvs, m->uv_stride, 8))
        return HF_ERROR_BAD_STRIDE;
    return HF_OK;
}

/* (first, count) inside an array of `total`. */
HF__PRIVATE hf_result hf__span_ok(int total, int first, int count)
{
    if (total < 0 || first < 0 || count < 0 || first > total - count)
        return HF_ERROR_BAD_RANGE;
    return HF_OK;
}

/* A triangle index and its three vertex indices in range. */
HF__PRIVATE hf_result hf__tri_ok(const hf_mesh *m, uint32_t t)
{
    const uint32_t *tri;
    if (t >= (uint32_t)m->triangle_count) return HF_ERROR_INDEX_OUT_OF_RANGE;
    tri = m->indices + 3 * (size_t)t;
    if (tri[0] >= (uint32_t)m->vertex_count ||
        tri[1] >= (uint32_t)m->vertex_count ||
        tri[2] >= (uint32_t)m->vertex_count)
        return HF_ERROR_INDEX_OUT_OF_RANGE;
    return HF_OK;
}

/* Blend of the corner normals, each normalised first (skinning may scale
   them); the face normal where the blend cancels. */
HF__PRIVATE void hf__blend_normal(float *o, const hf_mesh *m,
                                  const uint32_t *tri, const float *w)
{
    float n[3][3];
    int k;
    for (k = 0; k < 3; ++k) {
        HF_MEMCPY(n[k], hf__mesh_nrm(m, (int)tri[k]), sizeof n[k]);
        hf__normalize3(n[k]);
    }
    hf__blend3(o, n[0], n[1], n[2], w);
    if (!hf__normalize3(o))
        hf__face_normal(o, hf__mesh_pos(m, (int)tri[0]),
                        hf__mesh_pos(m, (int)tri[1]),
                        hf__mesh_pos(m, (int)tri[2]));
}

HFDEF hf_result hf_tess_evaluate(const hf_mesh *mesh,
                                 const hf_tess_vertex *added, int added_count,
                                 int first, int count, float *out_positions,
                                 float *out_normals, float *out_uvs)
{
    hf_result r;
    int i, k;
    if ((r = hf__mesh_shape_ok(mesh)) != HF_OK) return r;
    if ((r = hf__span_ok(added_count, first, count)) != HF_OK) return r;
    if (count == 0) return HF_OK;
    if (!added) return HF_ERROR_NULL_POINTER;
    if ((out_normals && !mesh->normals) || (out_uvs && !mesh->uvs))
        return HF_ERROR_NULL_POINTER;
    /* check everything this range reads before writing anything */
    for (i = first; i < first + count; ++i) {
        const hf_tess_vertex *a = &added[i];
        const uint32_t *tri;
        if ((r = hf__tri_ok(mesh, a->triangle)) != HF_OK) return r;
        if (!hf__all_finite(a->bary, 3)) return HF_ERROR_NON_FINITE;
        tri = mesh->indices + 3 * (size_t)a->triangle;
        for (k = 0; k < 3; ++k) {
            if (!hf__all_finite(hf__mesh_pos(mesh, (int)tri[k]), 3))
                return HF_ERROR_NON_FINITE;
            if (out_normals &&
                !hf__all_finite(hf__mesh_nrm(mesh, (int)tri[k]), 3))
                return HF_ERROR_NON_FINITE;
            if (out_uvs && !hf__all_finite(hf__mesh_uv(mesh, (int)tri[k]), 2))
                return HF_ERROR_NON_FINITE;
        }
    }
    for (i = first; i < first + count; ++i) {
        const hf_tess_vertex *a = &added[i];
        const uint32_t *tri = mesh->indices + 3 * (size_t)a->triangle;
        if (out_positions)
            hf__blend3(out_positions + 3 * (size_t)i,
                       hf__mesh_pos(mesh, (int)tri[0]),
                       hf__mesh_pos(mesh, (int)tri[1]),
                       hf__mesh_pos(mesh, (int)tri[2]), a->bary);
        if (out_normals)
            hf__blend_normal(out_normals + 3 * (size_t)i, mesh, tri, a->bary);
        if (out_uvs)
            hf__blend2(out_uvs + 2 * (size_t)i, hf__mesh_uv(mesh, (int)tri[0]),
                       hf__mesh_uv(mesh, (int)tri[1]),
                       hf__mesh_uv(mesh, (int)tri[2]), a->bary);
    }
    return HF_OK;
}

/* ---- 5.3 guides --------------------------------------------------------- */

/* Position bits with -0 folded onto +0, so welding compares values. */
HF__PRIVATE void hf__pos_key(const float *p, uint32_t *k)
{
    int i;
    for (i = 0; i < 3; ++i) {
        float x = p[i] == 0.0f ? 0.0f : p[i];
        HF_MEMCPY(&k[i], &x, 4);
    }
}

HF__PRIVATE uint32_t hf__hash3(const uint32_t *k)
{
    uint32_t h = k[0] * 0x9E3779B1u;
    h ^= (k[1] + 0x7F4A7C15u) * 0x85EBCA77u;
    h ^= h >> 15;
    h ^= (k[2] + 0x165667B1u) * 0xC2B2AE3Du;
    h ^= h >> 13;
    h *= 0x27D4EB2Fu;
    h ^= h >> 16;
    return h;
}

/* Combing direction from the map at uv (>= 3 channels): 8-bit as 2c - 1. */
HF__PRIVATE void hf__comb_from_map(const hf_map *m, const float *uv,
                                   float *o)
{
    float s[4];
    int k;
    hf_map_sample_fast(m, uv[0], uv[1], s);
    for (k = 0; k < 3; ++k)
        o[k] = m->format == HF_MAP_U8 ? 2.0f * s[k] - 1.0f : s[k];
}

/* The welded pure guides of hf_guides_rest, in one scratch block. */
typedef struct hf__weld {
    int pure;         /* pure guides so far */
    size_t cap;       /* hash table slots, a power of two >= 2 V */
    uint32_t *table;  /* slot -> pure guide, 0xffffffff empty */
    uint32_t *gov;    /* per base vertex: its pure guide */
    uint32_t *rep;    /* per pure guide: its first vertex */
    uint32_t *copies; /* per pure guide: vertices welded into it */
    float *nrm;       /* computed vertex normals (mesh without), or NULL */
    float *gn, *gd;   /* per pure guide: normal and comb sums, then unit */
    float *gl;        /* per pure guide: length sum, then the mean length */
    unsigned char *block;
} hf__weld;

/* Everything hf_guides_rest reads, before anything is allocated. */
HF__PRIVATE hf_result hf__guides_check(const hf_mesh *mesh,
                                       const hf_tess_vertex *added,
                                       int added_count,
                                       const hf_guide_params *params)
{
    const hf_map *lmap = params->length_map, *cmap = params->comb_map;
    const int V = mesh->vertex_count, T = mesh->triangle_count;
    hf_result r;
    int i, k;
    if (added_count < 0) return HF_ERROR_BAD_COUNT;
    if (added_count > 0 && !added) return HF_ERROR_NULL_POINTER;
    if (params->points < 2 || params->points > HF_GUIDE_MAX_POINTS)
        return HF_ERROR_BAD_COUNT;
    if (!hf__finitef(params->max_length) || !(params->max_length > 0.0f) ||
        params->max_length > HF_MAP_MAX_VALUE)
        return HF_ERROR_BAD_PARAMETER;
    if (lmap && (r = hf_map_validate(lmap, NULL)) != HF_OK) return r;
    if (cmap && (r = hf_map_validate(cmap, NULL)) != HF_OK) return r;
    if (cmap && cmap->channels < 3) return HF_ERROR_BAD_PARAMETER;
    if ((lmap || cmap) && !mesh->uvs) return HF_ERROR_NULL_POINTER;
    if (params->comb) {
        if (!hf__stride_ok(params->comb, params->comb_stride, 12))
            return HF_ERROR_BAD_STRIDE;
        for (i = 0; i < V; ++i)
            if (!hf__all_finite(
                    hf__attr(params->comb, params->comb_stride, 12, i), 3))
                return HF_ERROR_NON_FINITE;
    }
    for (i = 0; i < added_count; ++i) {
        if (added[i].triangle >= (uint32_t)T)
            return HF_ERROR_INDEX_OUT_OF_RANGE;
        if (!hf__all_finite(added[i].bary, 3)) return HF_ERROR_NON_FINITE;
        for (k = 0; k < 3; ++k)
            if (!(added[i].bary[k] >= 0.0f && added[i].bary[k] <= 1.0f))
                return HF_ERROR_BAD_PARAMETER;
    }
    if ((long long)V + added_count > 0x7fffffffLL) return HF_ERROR_OVERFLOW;
    return HF_OK;
}

/* The scratch block: table (cap), gov, rep, copies (V each), normals (3V,
   when the mesh has none), gn, gd (3V each), gl (V). */
HF__PRIVATE hf_result hf__weld_alloc(hf__weld *w, const hf_mesh *mesh,
                                     const hf_allocator *alloc)
{
    const size_t n_v = (size_t)mesh->vertex_count;
    size_t bytes = 0;
    hf_result r;
    HF_MEMSET(w, 0, sizeof *w);
    w->cap = 1;
    while (w->cap < 2 * n_v) w->cap <<= 1;
    if (!hf__mul_size(n_v, (mesh->normals ? 3u : 6u) + 3u + 1u, &bytes) ||
        !hf__mul_size(bytes, 4u, &bytes) ||
        bytes + 4u * w->cap + 12u * n_v < bytes)
        return HF_ERROR_OVERFLOW;
    bytes += 4u * w->cap + 12u * n_v;
    w->block = (unsigned char *)hf__alloc(alloc, bytes);
    if (!w->block) return HF_ERROR_OUT_OF_MEMORY;
    w->gn = (float *)w->block;
    w->gd = w->gn + 3 * n_v;
    w->gl = w->gd + 3 * n_v;
    w->nrm = mesh->normals ? NULL : w->gl + n_v;
    w->table = (uint32_t *)(w->nrm ? w->nrm + 3 * n_v : w->gl + n_v);
    w->gov = w->table + w->cap;
    w->rep = w->gov + n_v;
    w->copies = w->rep + n_v;
    if (w->nrm) {
        r = hf_mesh_compute_normals(mesh, w->nrm);
        HF_ASSERT(r == HF_OK);
        (void)r;
    }
    HF_MEMSET(w->table, 0xff, 4u * w->cap);
    return HF_OK;
}

/* Weld base vertices by exact position: open addressing, linear
   probing. */
HF__PRIVATE void hf__weld_positions(hf__weld *w, const hf_mesh *mesh)
{
    int i;
    for (i = 0; i < mesh->vertex_count; ++i) {
        uint32_t key[3], h;
        hf__pos_key(hf__mesh_pos(mesh, i), key);
        h = hf__hash3(key) & (uint32_t)(w->cap - 1);
        for (;;) {
            uint32_t g = w->table[h];
            if (g == 0xffffffffu) {
                g = (uint32_t)w->pure++;
                w->table[h] = g;
                w->rep[g] = (uint32_t)i;
                w->copies[g] = 0;
                w->gl[g] = 0.0f;
                HF_MEMSET(w->gn + 3 * (size_t)g, 0, 12);
                HF_MEMSET(w->gd + 3 * (size_t)g, 0, 12);
                w->gov[i] = g;
                break;
            } else {
                uint32_t k2[3];
                hf__pos_key(hf__mesh_pos(mesh, (int)w->rep[g]), k2);
                if (k2[0] == key[0] && k2[1] == key[1] && k2[2] == key[2]) {
                    w->gov[i] = g;
                    break;
                }
            }
            h = (h + 1u) & (uint32_t)(w->cap - 1);
        }
    }
}

/* Accumulate the copies of each pure guide (normals, combing, length),
   then make them unit normals, unit directions and mean lengths. */
HF__PRIVATE void hf__weld_accumulate(hf__weld *w, const hf_mesh *mesh,
                                     const hf_guide_params *params)
{
    const hf_map *lmap = params->length_map, *cmap = params->comb_map;
    int i, k;
    for (i = 0; i < mesh->vertex_count; ++i) {
        uint32_t g = w->gov[i];
        float n[3], d[3];
        HF_MEMCPY(n, w->nrm ? w->nrm + 3 * (size_t)i : hf__mesh_nrm(mesh, i),
                  12);
        hf__normalize3(n);
        for (k = 0; k < 3; ++k) w->gn[3 * g + k] += n[k];
        if (cmap)
            hf__comb_from_map(cmap, hf__mesh_uv(mesh, i), d);
        else if (params->comb)
            HF_MEMCPY(d, hf__attr(params->comb, params->comb_stride, 12, i),
                      12);
        else
            d[0] = d[1] = d[2] = 0.0f;
        if (hf__normalize3(d))
            for (k = 0; k < 3; ++k) w->gd[3 * g + k] += d[k];
        w->gl[g] += lmap ? hf__sample0(lmap, hf__mesh_uv(mesh, i)[0],
                                       hf__mesh_uv(mesh, i)[1])
                         : 1.0f;
        w->copies[g] += 1u;
    }
    for (i = 0; i < w->pure; ++i) {
        float *n = w->gn + 3 * (size_t)i, *d = w->gd + 3 * (size_t)i;
        if (!hf__normalize3(n)) {
            /* opposite copies cancel: keep the first copy's */
            uint32_t v = w->rep[i];
            HF_MEMCPY(n,
                      w->nrm ? w->nrm + 3 * (size_t)v
                             : hf__mesh_nrm(mesh, (int)v),
                      12);
            if (!hf__normalize3(n)) n[0] = n[1] = 0.0f, n[2] = 1.0f;
        }
        if (!hf__normalize3(d)) HF_MEMCPY(d, n, 12);
        w->gl[i] = params->max_length * (w->gl[i] / (float)w->copies[i]);
    }
}

/* Root, normal, direction and length of LOD guide `a`: the blend on its
   base triangle of the welded guides, maps read at its blended UV. */
HF__PRIVATE void hf__lod_guide_frame(const hf__weld *w, const hf_mesh *mesh,
                                     const hf_guide_params *params,
                                     const hf_tess_vertex *a, float *root,
                                     float *n, float *d, float *len)
{
    const hf_map *lmap = params->length_map, *cmap = params->comb_map;
    const uint32_t *tri = mesh->indices + 3 * (size_t)a->triangle;
    const uint32_t g0 = w->gov[tri[0]], g1 = w->gov[tri[1]],
                   g2 = w->gov[tri[2]];
    float uv[2];
    hf__blend3(root, hf__mesh_pos(mesh, (int)tri[0]),
               hf__mesh_pos(mesh, (int)tri[1]),
               hf__mesh_pos(mesh, (int)tri[2]), a->bary);
    hf__blend3(n, w->gn + 3 * (size_t)g0, w->gn + 3 * (size_t)g1,
               w->gn + 3 * (size_t)g2, a->bary);
    if (!hf__normalize3(n))
        hf__face_normal(n, hf__mesh_pos(mesh, (int)tri[0]),
                        hf__mesh_pos(mesh, (int)tri[1]),
                        hf__mesh_pos(mesh, (int)tri[2]));
    uv[0] = uv[1] = 0.0f;
    if (mesh->uvs)
        hf__blend2(uv, hf__mesh_uv(mesh, (int)tri[0]),
                   hf__mesh_uv(mesh, (int)tri[1]),
                   hf__mesh_uv(mesh, (int)tri[2]), a->bary);
    if (cmap)
        hf__comb_from_map(cmap, uv, d);
    else if (params->comb)
        hf__blend3(d, w->gd + 3 * (size_t)g0, w->gd + 3 * (size_t)g1,
                   w->gd + 3 * (size_t)g2, a->bary);
    else
        HF_MEMCPY(d, n, 12);
    if (!hf__normalize3(d)) HF_MEMCPY(d, n, 12);
    *len = params->max_length * (lmap ? hf__sample0(lmap, uv[0], uv[1]) : 1.0f);
}

/* Every guide's outputs: pure guides from the weld, LOD guides blended. */
HF__PRIVATE void hf__guides_write(const hf__weld *w, const hf_mesh *mesh,
                                  const hf_tess_vertex *added,
                                  int added_count,
                                  const hf_guide_params *params,
                                  hf_guide_output *out)
{
    const int points = params->points, guides = w->pure + added_count;
    const int V = mesh->vertex_count;
    int i, j;
    for (i = 0; i < guides; ++i) {
        float root[3], n[3], d[3], len;
        if (i < w->pure) {
            HF_MEMCPY(root, hf__mesh_pos(mesh, (int)w->rep[i]), 12);
            HF_MEMCPY(n, w->gn + 3 * (size_t)i, 12);
            HF_MEMCPY(d, w->gd + 3 * (size_t)i, 12);
            len = w->gl[i];
        } else {
            hf__lod_guide_frame(w, mesh, params, &added[i - w->pure], root, n,
                                d, &len);
        }
        if (out->points)
            for (j = 0; j < points; ++j) {
                float *o = out->points + 3 * ((size_t)i * (size_t)points +
                                              (size_t)j);
                float s = len * ((float)j / (float)(points - 1));
                o[0] = root[0] + d[0] * s;
                o[1] = root[1] + d[1] * s;
                o[2] = root[2] + d[2] * s;
            }
        if (out->lengths) out->lengths[i] = len;
        if (out->directions)
            HF_MEMCPY(out->directions + 3 * (size_t)i, d, 12);
        if (out->normals) HF_MEMCPY(out->normals + 3 * (size_t)i, n, 12);
    }
    if (out->guide_of_vertex) {
        for (i = 0; i < V; ++i) out->guide_of_vertex[i] = w->gov[i];
        for (i = 0; i < added_count; ++i)
            out->guide_of_vertex[V + i] = (uint32_t)(w->pure + i);
    }
}

HFDEF hf_result hf_guides_rest(const hf_mesh *mesh,
                               const hf_tess_vertex *added, int added_count,
                               const hf_guide_params *params,
                               hf_guide_output *out,
                               const hf_allocator *alloc)
{
    hf__weld w;
    hf_result r;
    if (!mesh || !params || !out) return HF_ERROR_NULL_POINTER;
    if ((r = hf_mesh_validate(mesh, NULL)) != HF_OK) return r;
    if ((r = hf__guides_check(mesh, added, added_count, params)) != HF_OK)
        return r;
    if ((r = hf__weld_alloc(&w, mesh, alloc)) != HF_OK) return r;
    hf__weld_positions(&w, mesh);
    hf__weld_accumulate(&w, mesh, params);
    if ((out->points || out->lengths || out->directions || out->normals) &&
        out->guide_capacity < w.pure + added_count) {
        hf__free(alloc, w.block);
        return HF_ERROR_BUFFER_TOO_SMALL;
    }
    if (out->points || out->lengths || out->directions || out->normals ||
        out->guide_of_vertex)
        hf__guides_write(&w, mesh, added, added_count, params, out);
    out->guide_count = w.pure + added_count;
    out->pure_guide_count = w.pure;
    hf__free(alloc, w.block);
    return HF_OK;
}

/* ---- 5.4 strand placement ----------------------------------------------- */

HF__PRIVATE uint32_t hf__reverse_bits(uint32_t x)
{
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
}

/* Second dimension of the Sobol sequence (Kollig and Keller 2002). */
HF__PRIVATE uint32_t hf__sobol2(uint32_t i)
{
    uint32_t r = 0, v;
    for (v = 1u << 31; i; i >>= 1, v ^= v >> 1)
        if (i & 1u) r ^= v;
    return r;
}

HF__PRIVATE float hf__u32_to_unit(uint32_t x)
{
    return (float)(x >> 8) * (1.0f / 16777216.0f);
}

typedef struct hf__place_ctx {
    const hf_mesh *mesh;
    const hf_map *density;
    int estimator, refuse_degenerate;
} hf__place_ctx;

/* Weight density * area of triangle t (0 for zero area). */
HF__PRIVATE hf_result hf__place_weight(const hf__place_ctx *c, int t,
                                       float *w, int *has_area)
{
    const hf_mesh *m = c->mesh;
    const uint32_t *tri = m->indices + 3 * (size_t)t;
    float area = hf_triangle_area(hf__mesh_pos(m, (int)tri[0]),
                                  hf__mesh_pos(m, (int)tri[1]),
                                  hf__mesh_pos(m, (int)tri[2]));
    float d = 1.0f;
    if (!hf__finitef(area)) return HF_ERROR_NON_FINITE;
    *has_area = area > 0.0f;
    if (!(area > 0.0f)) {
        *w = 0.0f;
        return c->refuse_degenerate ? HF_ERROR_DEGENERATE : HF_OK;
    }
    if (c->density) {
        hf_result r = hf__density(c->density, hf__mesh_uv(m, (int)tri[0]),
                                  hf__mesh_uv(m, (int)tri[1]),
                                  hf__mesh_uv(m, (int)tri[2]), c->estimator,
                                  &d);
        if (r != HF_OK) return r;
    }
    *w = d * area;
    return HF_OK;
}

/* Stable LSD radix sort of 64-bit items by their high 32 bits (4 passes of
   8 bits); the result ends in `a`. */
HF__PRIVATE void hf__radix_hi32(uint64_t *a, uint64_t *tmp, size_t n)
{
    size_t count[256], i;
    int pass;
    for (pass = 0; pass < 4; ++pass) {
        int shift = 32 + 8 * pass;
        size_t sum = 0;
        uint64_t *t;
        HF_MEMSET(count, 0, sizeof count);
        for (i = 0; i < n; ++i) ++count[(a[i] >> shift) & 255u];
        for (i = 0; i < 256; ++i) {
            size_t c = count[i];
            count[i] = sum;
            sum += c;
        }
        for (i = 0; i < n; ++i) tmp[count[(a[i] >> shift) & 255u]++] = a[i];
        t = a;
        a = tmp;
        tmp = t;
    }
}

/* How many strands, from the counting pass: the density integral (sum
   of density * area), the expected count X (scaled to total_strands when
   that is set), the seeded offset u0 of systematic rounding and the count
   floor(X + u0). */
typedef struct hf__place_plan {
    double density_sum, expected, u0;
    long long count;
} hf__place_plan;

HF__PRIVATE hf_result hf__place_count(const hf__place_ctx *c,
                                      const hf_place_params *params,
                                      hf__place_plan *plan)
{
    hf_result r;
    hf_rng rng;
    int t, any_area = 0;
    plan->density_sum = 0.0;
    for (t = 0; t < c->mesh->triangle_count; ++t) {
        float w;
        int has_area;
        if ((r = hf__place_weight(c, t, &w, &has_area)) != HF_OK) return r;
        any_area |= has_area;
        plan->density_sum += (double)w;
    }
    if (!any_area) return HF_ERROR_DEGENERATE;
    if (params->total_strands > 0) {
        if (!(plan->density_sum > 0.0)) return HF_ERROR_DEGENERATE;
        plan->expected = (double)params->total_strands;
    } else {
        plan->expected = plan->density_sum * (double)params->strands_per_area;
    }
    hf_rng_seed(&rng, params->seed, 0u);
    plan->u0 = (double)hf_rng_float(&rng);
    /* finite and no more than max_strands (X + u0 < max + 1) */
    if (!(plan->expected + plan->u0 < (double)params->max_strands + 1.0))
        return HF_ERROR_OVERFLOW;
    plan->count = (long long)HF_FLOOR(plan->expected + plan->u0);
    return HF_OK;
}

/* Barycentric weights of corners 0 and 1 for strand k of a triangle, by
   the sampler (sx, sy: the triangle's digital shift; trng its generator). */
HF__PRIVATE void hf__place_sample(int sampler, uint32_t k, uint32_t sx,
                                  uint32_t sy, hf_rng *trng, float b[3])
{
    if (sampler == HF_SAMPLER_STRATIFIED) {
        /* Heitz 2019: area-preserving, low distortion */
        float x = hf__u32_to_unit(hf__reverse_bits(k) ^ sx);
        float y = hf__u32_to_unit(hf__sobol2(k) ^ sy);
        if (y > x) {
            x *= 0.5f;
            y -= x;
        } else {
            y *= 0.5f;
            x -= y;
        }
        b[0] = x;
        b[1] = y;
    } else if (sampler == HF_SAMPLER_CORNER_BIASED) {
        float r1 = hf_rng_float(trng), r2 = hf_rng_float(trng);
        b[0] = r1;
        b[1] = r2 * (1.0f - r1);
    } else {
        float r1 = hf_rng_float(trng), r2 = hf_rng_float(trng);
        float sq = HF_SQRTF(r1);
        b[0] = 1.0f - sq;
        b[1] = sq * (1.0f - r2);
    }
    if (b[0] < 0.0f) b[0] = 0.0f;
    if (b[1] < 0.0f) b[1] = 0.0f;
    if (b[0] + b[1] > 1.0f) b[1] = 1.0f - b[0];
    b[2] = (1.0f - b[0]) - b[1];
}

/* The fill pass: the same weights and running sum as the count, rounded
   systematically per triangle; every strand gets its LOD key (k + u_t) / n
   in the high half of keys[i] and its index in the low half. */
HF__PRIVATE void hf__place_fill(const hf__place_ctx *c,
                                const hf_place_params *params,
                                const hf__place_plan *plan, hf_strand *out,
                                uint64_t *keys)
{
    static const float zero_uv[2] = {0.0f, 0.0f};
    const hf_mesh *mesh = c->mesh;
    const int T = mesh->triangle_count;
    const double X = plan->expected, u0 = plan->u0;
    double cum = 0.0, prev_floor = HF_FLOOR(u0);
    size_t done = 0;
    int t;
    for (t = 0; t < T; ++t) {
        const uint32_t *tri = mesh->indices + 3 * (size_t)t;
        const float *uv0 = mesh->uvs ? hf__mesh_uv(mesh, (int)tri[0]) : zero_uv;
        const float *uv1 = mesh->uvs ? hf__mesh_uv(mesh, (int)tri[1]) : zero_uv;
        const float *uv2 = mesh->uvs ? hf__mesh_uv(mesh, (int)tri[2]) : zero_uv;
        float w, ut;
        double C, fl;
        uint32_t nt, k, sx, sy;
        int has_area;
        hf_rng trng;
        hf_result r = hf__place_weight(c, t, &w, &has_area);
        HF_ASSERT(r == HF_OK);
        (void)r;
        cum += (double)w;
        C = t == T - 1 ? X : X * (cum / plan->density_sum);
        fl = HF_FLOOR(C + u0);
        nt = (uint32_t)(fl - prev_floor);
        prev_floor = fl;
        if (nt == 0) continue;
        HF_ASSERT(done + nt <= (size_t)plan->count);
        hf_rng_seed(&trng, params->seed, (uint64_t)t + 1u);
        ut = hf_rng_float(&trng);
        sx = hf_rng_u32(&trng);
        sy = hf_rng_u32(&trng);
        for (k = 0; k < nt; ++k) {
            hf_strand *s = &out[done];
            float b[3];
            double key;
            uint32_t q;
            hf__place_sample(params->sampler, k, sx, sy, &trng, b);
            s->triangle = (uint32_t)t;
            s->bary[0] = b[0];
            s->bary[1] = b[1];
            hf__blend2(s->uv, uv0, uv1, uv2, b);
            s->random = hf_rng_float(&trng);
            key = ((double)k + (double)ut) / (double)nt;
            q = key >= 1.0 ? 0xffffffffu : (uint32_t)(key * 4294967296.0);
            keys[done] = ((uint64_t)q << 32) | (uint64_t)done;
            ++done;
        }
    }
    HF_ASSERT(done == (size_t)plan->count);
}

/* LOD order: stable sort by key, then apply the permutation in place
   (position p takes the record that was at perm[p]). */
HF__PRIVATE void hf__place_lod_order(hf_strand *out, uint64_t *keys,
                                     uint64_t *tmp, size_t n)
{
    uint32_t *perm = (uint32_t *)tmp;
    size_t p;
    hf__radix_hi32(keys, tmp, n);
    for (p = 0; p < n; ++p) perm[p] = (uint32_t)keys[p];
    for (p = 0; p < n; ++p) {
        size_t s = p, q;
        hf_strand hold;
        if (perm[p] == (uint32_t)p) continue;
        hold = out[s];
        for (;;) {
            q = perm[s];
            perm[s] = (uint32_t)s;
            if (q == p) {
                out[s] = hold;
                break;
            }
            out[s] = out[q];
            s = q;
        }
    }
}

HFDEF hf_result hf_place_strands(const hf_mesh *mesh, const hf_map *density,
                                 const hf_place_params *in,
                                 hf_strand *out, int capacity,
                                 int *out_count, const hf_allocator *alloc)
{
    hf__place_ctx c;
    hf__place_plan plan;
    hf_place_params prm;
    const hf_place_params *params = &prm;
    hf_result r;
    uint64_t *keys;
    size_t n, bytes;
    if (!mesh || !in || !out_count) return HF_ERROR_NULL_POINTER;
    hf__place_params_resolve(in, &prm);
    if ((r = hf_mesh_validate(mesh, NULL)) != HF_OK) return r;
    if (density && (r = hf_map_validate(density, NULL)) != HF_OK) return r;
    if (density && !mesh->uvs) return HF_ERROR_NULL_POINTER;
    if (params->total_strands < 0) return HF_ERROR_BAD_COUNT;
    if (params->estimator < 0 || params->estimator > 2 ||
        params->sampler < 0 || params->sampler > 2 ||
        params->max_strands < 1 || params->max_strands > HF_MAX_STRANDS)
        return HF_ERROR_BAD_PARAMETER;
    /* a negative or non-finite density is refused even when
       total_strands leaves it unused, as hf_fur_create does */
    if (!hf__finitef(params->strands_per_area) ||
        params->strands_per_area < 0.0f ||
        (params->total_strands == 0 && !(params->strands_per_area > 0.0f)))
        return HF_ERROR_BAD_PARAMETER;
    c.mesh = mesh;
    c.density = density;
    c.estimator = params->estimator;
    c.refuse_degenerate = params->refuse_degenerate != 0;
    if ((r = hf__place_count(&c, params, &plan)) != HF_OK) return r;
    if (!out) {
        *out_count = (int)plan.count;
        return HF_OK;
    }
    if (capacity < plan.count) return HF_ERROR_BUFFER_TOO_SMALL;
    if (plan.count == 0) {
        *out_count = 0;
        return HF_OK;
    }
    n = (size_t)plan.count;
    if (!hf__mul_size(n, 2u * sizeof(uint64_t), &bytes))
        return HF_ERROR_OVERFLOW;
    keys = (uint64_t *)hf__alloc(alloc, bytes);
    if (!keys) return HF_ERROR_OUT_OF_MEMORY;
    hf__place_fill(&c, params, &plan, out, keys);
    hf__place_lod_order(out, keys, keys + n, n);
    hf__free(alloc, keys);
    *out_count = (int)plan.count;
    return HF_OK;
}

/* Strand records in [first, first + count): triangle in range for `m`
   (when given) and weights and uv finite. */
HF__PRIVATE hf_result hf__strands_ok(const hf_strand *s, int strand_count,
                                     int first, int count, const hf_mesh *m)
{
    hf_result r;
    int i;
    if ((r = hf__span_ok(strand_count, first, count)) != HF_OK) return r;
    if (count > 0 && !s) return HF_ERROR_NULL_POINTER;
    for (i = first; i < first + count; ++i) {
        if (m && (r = hf__tri_ok(m, s[i].triangle)) != HF_OK) return r;
        if (!hf__all_finite(s[i].bary, 2) || !hf__all_finite(s[i].uv, 2))
            return HF_ERROR_NON_FINITE;
    }
    return HF_OK;
}

HFDEF hf_result hf_strand_roots(const hf_mesh *mesh, const hf_strand *strands,
                                int strand_count, int first, int count,
                                float *out_positions)
{
    hf_result r;
    int i, k;
    if (!out_positions) return HF_ERROR_NULL_POINTER;
    if ((r = hf__mesh_shape_ok(mesh)) != HF_OK) return r;
    if ((r = hf__strands_ok(strands, strand_count, first, count, mesh)) !=
        HF_OK)
        return r;
    for (i = first; i < first + count; ++i) {
        const uint32_t *tri = mesh->indices + 3 * (size_t)strands[i].triangle;
        for (k = 0; k < 3; ++k)
            if (!hf__all_finite(hf__mesh_pos(mesh, (int)tri[k]), 3))
                return HF_ERROR_NON_FINITE;
    }
    for (i = first; i < first + count; ++i) {
        const hf_strand *s = &strands[i];
        const uint32_t *tri = mesh->indices + 3 * (size_t)s->triangle;
        float w[3];
        w[0] = s->bary[0];
        w[1] = s->bary[1];
        w[2] = (1.0f - s->bary[0]) - s->bary[1];
        hf__blend3(out_positions + 3 * (size_t)i,
                   hf__mesh_pos(mesh, (int)tri[0]),
                   hf__mesh_pos(mesh, (int)tri[1]),
                   hf__mesh_pos(mesh, (int)tri[2]), w);
    }
    return HF_OK;
}

/* ---- 5.5 maps on strands ------------------------------------------------ */

HFDEF hf_result hf_strand_lengths(const hf_strand *strands, int strand_count,
                                  int first, int count,
                                  const hf_map *length_map, float max_length,
                                  float *out_lengths)
{
    hf_result r;
    int i;
    if (!out_lengths) return HF_ERROR_NULL_POINTER;
    if (length_map && (r = hf_map_validate(length_map, NULL)) != HF_OK)
        return r;
    if (!hf__finitef(max_length) || max_length < 0.0f ||
        max_length > HF_MAP_MAX_VALUE)
        return HF_ERROR_BAD_PARAMETER;
    if ((r = hf__strands_ok(strands, strand_count, first, count, NULL)) !=
        HF_OK)
        return r;
    for (i = first; i < first + count; ++i)
        out_lengths[i] =
            max_length * (length_map ? hf__sample0(length_map, strands[i].uv[0],
                                                   strands[i].uv[1])
                                     : 1.0f);
    return HF_OK;
}

/* A sample of `channels` channels expanded to rgba (grey, grey + alpha,
   rgb, rgba). */
HF__PRIVATE void hf__expand_rgba(int channels, const float *s, float *o)
{
    switch (channels) {
    case 1:
        o[0] = o[1] = o[2] = s[0];
        o[3] = 1.0f;
        break;
    case 2:
        o[0] = o[1] = o[2] = s[0];
        o[3] = s[1];
        break;
    case 3:
        o[0] = s[0];
        o[1] = s[1];
        o[2] = s[2];
        o[3] = 1.0f;
        break;
    default:
        o[0] = s[0];
        o[1] = s[1];
        o[2] = s[2];
        o[3] = s[3];
        break;
    }
}

HFDEF hf_result hf_strand_colors(const hf_strand *strands, int strand_count,
                                 int first, int count,
                                 const hf_map *color_map, float *out_rgba)
{
    hf_result r;
    int i;
    if (!out_rgba || !color_map) return HF_ERROR_NULL_POINTER;
    if ((r = hf_map_validate(color_map, NULL)) != HF_OK) return r;
    if ((r = hf__strands_ok(strands, strand_count, first, count, NULL)) !=
        HF_OK)
        return r;
    for (i = first; i < first + count; ++i) {
        float s[4];
        hf_map_sample_fast(color_map, strands[i].uv[0], strands[i].uv[1], s);
        hf__expand_rgba(color_map->channels, s, out_rgba + 4 * (size_t)i);
    }
    return HF_OK;
}

HFDEF hf_result hf_color3d_coord(const hf_map *index_map, float u, float v,
                                 float t, float out_xy[2])
{
    hf_result r;
    float s[4];
    if (!index_map || !out_xy) return HF_ERROR_NULL_POINTER;
    if ((r = hf_map_validate(index_map, NULL)) != HF_OK) return r;
    if (!hf__finitef(u) || !hf__finitef(v) || !hf__finitef(t))
        return HF_ERROR_NON_FINITE;
    hf_map_sample_fast(index_map, u, v, s);
    out_xy[0] = hf__clamp01(s[0]);
    out_xy[1] = hf__clamp01(t);
    return HF_OK;
}

HFDEF hf_result hf_color3d_sample(const hf_map *index_map, const hf_map *ramp,
                                  float u, float v, float t, float out[4])
{
    hf_result r;
    float xy[2], s[4];
    if (!ramp || !out) return HF_ERROR_NULL_POINTER;
    if ((r = hf_map_validate(ramp, NULL)) != HF_OK) return r;
    if ((r = hf_color3d_coord(index_map, u, v, t, xy)) != HF_OK) return r;
    hf_map_sample_fast(ramp, xy[0], xy[1], s);
    hf__expand_rgba(ramp->channels, s, out);
    return HF_OK;
}

/* ---- 5.6 binding strands to guides -------------------------------------- */

HFDEF hf_result hf_bind_strands(const hf_mesh *guide_mesh,
                                const uint32_t *guide_of_vertex,
                                int guide_count, const hf_strand *strands,
                                int strand_count, int first, int count,
                                const float *strand_lengths,
                                const float *guide_lengths,
                                hf_strand_binding *out)
{
    hf_result r;
    int i, k;
    if (!guide_of_vertex || !out) return HF_ERROR_NULL_POINTER;
    if (strand_lengths && !guide_lengths) return HF_ERROR_NULL_POINTER;
    if (guide_count < 1) return HF_ERROR_BAD_COUNT;
    if ((r = hf__mesh_shape_ok(guide_mesh)) != HF_OK) return r;
    if ((r = hf__strands_ok(strands, strand_count, first, count,
                            guide_mesh)) != HF_OK)
        return r;
    for (i = first; i < first + count; ++i) {
        const uint32_t *tri =
            guide_mesh->indices + 3 * (size_t)strands[i].triangle;
        for (k = 0; k < 3; ++k) {
            uint32_t g = guide_of_vertex[tri[k]];
            if (g >= (uint32_t)guide_count)
                return HF_ERROR_INDEX_OUT_OF_RANGE;
            if (guide_lengths && !hf__finitef(guide_lengths[g]))
                return HF_ERROR_NON_FINITE;
        }
        if (strand_lengths && !hf__finitef(strand_lengths[i]))
            return HF_ERROR_NON_FINITE;
    }
    for (i = first; i < first + count; ++i) {
        const hf_strand *s = &strands[i];
        const uint32_t *tri = guide_mesh->indices + 3 * (size_t)s->triangle;
        hf_strand_binding *b = &out[i];
        b->weight[0] = s->bary[0];
        b->weight[1] = s->bary[1];
        b->weight[2] = (1.0f - s->bary[0]) - s->bary[1];
        for (k = 0; k < 3; ++k) b->guide[k] = guide_of_vertex[tri[k]];
        b->length_scale = 1.0f;
        if (strand_lengths) {
            float gl = b->weight[0] * guide_lengths[b->guide[0]] +
                       b->weight[1] * guide_lengths[b->guide[1]] +
                       b->weight[2] * guide_lengths[b->guide[2]];
            float sc = gl > 0.0f ? strand_lengths[i] / gl : 1.0f;
            b->length_scale = hf__finitef(sc) && sc >= 0.0f ? sc : 1.0f;
        }
    }
    return HF_OK;
}

/* ---- 6. ropes: Verlet ropes for guide hairs, or any rope ---------------- */


/* Scratch rows (each rope_count floats), rewritten by every step. */
enum {
    HF__RS_F = 0,   /* rows 0..11: root frame of this sub-step: p, t, n, b */
    HF__RS_G = 12,  /* rows 12..23: animated ropes: frame one sub-step back */
    HF__RS_A = 24,  /* rows 24..26: acceleration * h^2 of this sub-step */
    HF__RS_VF = 27, /* velocity factor: damping and the dt-change ratio */
    HF__RS_KB = 28, /* per-rope temporary */
    HF__RS_ROWS = 29
};

/* Ropes of up to this many points get their per-point stiffness from a
   table made once per call (hf__rope_k calls pow); longer ones compute it
   row by row, as before. */
#define HF__ROPE_KTAB 64

/* A collider ready for the row kernels (hf__collider_prep): base point,
   capsule axis e and 1 / |e|^2 (0 for a sphere or a zero-length capsule:
   a point, so a sphere), the radius grown by the margin, and the distance
   from the axis below which a rope's root counts as inside: deeper than
   the margin below the surface (and 1e-4 of the radius, for rounding), so
   roots on a proxy that hugs the skin a little outside it keep the
   margin. id: its index in the call's array (the order every kernel
   resolves them in); row: the first point row of its tile that can reach
   it (hf__bp_build). */
typedef struct hf__col_prep {
    float a[3], e[3], inv, rr, inner;
    float ball; /* a radius about a + e / 2 that holds it, and room */
    int id, row;
} hf__col_prep;

/* A point resolves against at most this many colliders at once (the
   ones within reach of its segment, hf__ftl_relevant); more, and it
   walks them in batches of this many (hf__ftl_collide_one). */
#define HF__FTL_NEAR 8

struct hf__pose_kernels; /* the kernels per width: 6.4, 6.8 */
struct hf__rope_rows;

/* Resolved per-call constants. */
typedef struct hf__rope_step {
    int n;             /* sub-steps */
    float h;           /* sub-step length (s, simulated) */
    float keep;        /* velocity kept per sub-step */
    float k_root;      /* root stiffness per sub-step */
    int iterations;    /* effective passes */
    int ftl;
    float ftl_damping;
    float margin;
    float g[3];        /* gravity + wind */
    float turbulence, turbulence_frequency;
    float blend_time;
    float gs_root, gs_tip, ls_root, ls_tip; /* per 1/60 s */
    int global_on, local_on;
    int ktab; /* kg, kl hold hf__rope_kg, hf__rope_kl */
    int level; /* hf_simd_resolve(params->simd) */
    /* its kernels (hf__kernels_for): the pose rows, the rows of a
       sub-step */
    const struct hf__pose_kernels *pose;
    const struct hf__rope_rows *rows;
    float kg[HF__ROPE_KTAB], kl[HF__ROPE_KTAB];
} hf__rope_step;

HFDEF void hf_rope_params_init(hf_rope_params *p)
{
    hf_rope_params zero;
    if (!p) return;
    HF_MEMSET(&zero, 0, sizeof zero);
    hf__rope_params_resolve(&zero, p);
}

/* A float field in [lo, hi]. */
HF__PRIVATE hf_result hf__rope_check_f(hf_diag *diag, const char *field,
                                       float v, float lo, float hi)
{
    if (!hf__finitef(v))
        return hf__fail(diag, HF_ERROR_NON_FINITE, field, -1,
                        "params.%s is NaN or infinite", field);
    if (!(v >= lo && v <= hi))
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, field, -1,
                        "params.%s = %g is outside [%g, %g]", field,
                        (double)v, (double)lo, (double)hi);
    return HF_OK;
}

/* Check resolved parameters (hf__rope_params_resolve). */
HF__PRIVATE hf_result hf__rope_params_check(const hf_rope_params *p,
                                            hf_diag *diag)
{
    hf_result r;
    const float A = HF_ROPE_MAX_ACCEL;
    int k;
    for (k = 0; k < 3; ++k) {
        if ((r = hf__rope_check_f(diag, "gravity", p->gravity[k], -A, A)) !=
                HF_OK ||
            (r = hf__rope_check_f(diag, "wind", p->wind[k], -A, A)) != HF_OK)
            return r;
    }
    if ((r = hf__rope_check_f(diag, "turbulence", p->turbulence, 0.0f, A)) ||
        (r = hf__rope_check_f(diag, "turbulence_frequency",
                              p->turbulence_frequency, 0.0f, 1000.0f)) ||
        (r = hf__rope_check_f(diag, "damping", p->damping, 0.0f, 1.0f)) ||
        (r = hf__rope_check_f(diag, "time_scale", p->time_scale, 1e-30f,
                              100.0f)) ||
        (r = hf__rope_check_f(diag, "substep", p->substep, 1e-5f, 1.0f)) ||
        (r = hf__rope_check_f(diag, "max_dt", p->max_dt, 1e-30f, 1.0f)) ||
        (r = hf__rope_check_f(diag, "ftl_damping", p->ftl_damping, 0.0f,
                              1.0f)) ||
        (r = hf__rope_check_f(diag, "root_stiffness", p->root_stiffness,
                              0.0f, 1.0f)) ||
        (r = hf__rope_check_f(diag, "global_stiffness_root",
                              p->global_stiffness_root, 0.0f, 1.0f)) ||
        (r = hf__rope_check_f(diag, "global_stiffness_tip",
                              p->global_stiffness_tip, 0.0f, 1.0f)) ||
        (r = hf__rope_check_f(diag, "local_stiffness_root",
                              p->local_stiffness_root, 0.0f, 1.0f)) ||
        (r = hf__rope_check_f(diag, "local_stiffness_tip",
                              p->local_stiffness_tip, 0.0f, 1.0f)) ||
        (r = hf__rope_check_f(diag, "collision_margin", p->collision_margin,
                              0.0f, 1000.0f)) ||
        (r = hf__rope_check_f(diag, "mode_blend_time", p->mode_blend_time,
                              0.0f, 1000.0f)) ||
        (r = hf__rope_check_f(diag, "volume", p->volume, 0.0f, 100.0f)) ||
        (r = hf__rope_check_f(diag, "friction", p->friction, 0.0f, 1.0f)))
        return r;
    if (p->max_substeps < 1 || p->max_substeps > 1000)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "max_substeps", -1,
                        "params.max_substeps = %d is outside [1, 1000]",
                        p->max_substeps);
    if (p->iterations < 0 || p->iterations > 1000)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "iterations", -1,
                        "params.iterations = %d is outside [0, 1000]",
                        p->iterations);
    if (p->solver != HF_ROPE_SOLVER_FTL &&
        p->solver != HF_ROPE_SOLVER_DISTANCE)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "solver", -1,
                        "params.solver = %d is not a hf_rope_solver",
                        p->solver);
    if (!hf__kernels_ok(p->simd, 0))
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "simd", -1,
                        "params.simd = %d is not an hf_simd_level (0..4)",
                        p->simd);
    hf__ok(diag);
    return HF_OK;
}

HFDEF hf_result hf_rope_params_validate(const hf_rope_params *params,
                                        hf_diag *diag)
{
    hf_rope_params p;
    if (!params)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "params", -1,
                        "params is NULL");
    hf__rope_params_resolve(params, &p);
    return hf__rope_params_check(&p, diag);
}

/* ---- 6.1 memory --------------------------------------------------------- */

/* Array sizes in bytes, in layout order: 10 point arrays (x, y, z, px, py,
   pz, rest_u, rest_v, rest_w, rest_length), frame, scratch, last_h, blend,
   length, time, mode, root_inside, glide (6 point rows), longest. Each
   starts on a 64-byte boundary. */
enum { HF__ROPE_ARRAYS = 20 };

HF__PRIVATE hf_result hf__ropes_layout(int rope_count, int points,
                                       size_t sizes[HF__ROPE_ARRAYS],
                                       size_t *total)
{
    size_t n, pt, t = 64, R;
    int i;
    if (rope_count < 1 || points < 2) return HF_ERROR_BAD_COUNT;
    R = (size_t)rope_count;
    if (!hf__mul_size(R, (size_t)points, &n) ||
        !hf__mul_size(n, sizeof(float), &pt))
        return HF_ERROR_OVERFLOW;
    for (i = 0; i < 10; ++i) sizes[i] = pt;
    if (!hf__mul_size(R, 24 * sizeof(float), &sizes[10]) ||
        !hf__mul_size(R, HF__RS_ROWS * sizeof(float), &sizes[11]) ||
        !hf__mul_size(R, sizeof(double), &sizes[15]) ||
        !hf__mul_size(pt, 6, &sizes[18]))
        return HF_ERROR_OVERFLOW;
    sizes[12] = sizes[13] = sizes[14] = sizes[19] = R * sizeof(float);
    sizes[16] = sizes[17] = R;
    for (i = 0; i < HF__ROPE_ARRAYS; ++i) {
        size_t s = sizes[i] + 63u;
        if (s < sizes[i] || t + s < t) return HF_ERROR_OVERFLOW;
        t += s & ~(size_t)63u;
    }
    *total = t;
    return HF_OK;
}

HFDEF hf_result hf_ropes_memory_size(int rope_count, int points,
                                     size_t *out_size)
{
    size_t sizes[HF__ROPE_ARRAYS], total;
    hf_result r;
    if (!out_size) return HF_ERROR_NULL_POINTER;
    r = hf__ropes_layout(rope_count, points, sizes, &total);
    if (r == HF_OK) *out_size = total;
    return r;
}

HFDEF hf_result hf_ropes_init(hf_ropes *ropes, int rope_count, int points,
                              void *memory, size_t memory_size)
{
    size_t sizes[HF__ROPE_ARRAYS], total, R, k;
    unsigned char *base, *at;
    void *arr[HF__ROPE_ARRAYS];
    hf_result r;
    int i;
    if (!ropes || !memory) return HF_ERROR_NULL_POINTER;
    r = hf__ropes_layout(rope_count, points, sizes, &total);
    if (r != HF_OK) return r;
    if (memory_size < total) return HF_ERROR_BUFFER_TOO_SMALL;
    HF_MEMSET(memory, 0, total);
    base = (unsigned char *)memory;
    at = base + ((64u - (size_t)((uintptr_t)base & 63u)) & 63u);
    for (i = 0; i < HF__ROPE_ARRAYS; ++i) {
        arr[i] = at;
        at += (sizes[i] + 63u) & ~(size_t)63u;
    }
    HF_MEMSET(ropes, 0, sizeof *ropes);
    ropes->rope_count = rope_count;
    ropes->points = points;
    ropes->x = (float *)arr[0];
    ropes->y = (float *)arr[1];
    ropes->z = (float *)arr[2];
    ropes->px = (float *)arr[3];
    ropes->py = (float *)arr[4];
    ropes->pz = (float *)arr[5];
    ropes->rest_u = (float *)arr[6];
    ropes->rest_v = (float *)arr[7];
    ropes->rest_w = (float *)arr[8];
    ropes->rest_length = (float *)arr[9];
    ropes->frame = (float *)arr[10];
    ropes->scratch = (float *)arr[11];
    ropes->last_h = (float *)arr[12];
    ropes->blend = (float *)arr[13];
    ropes->length = (float *)arr[14];
    ropes->time = (double *)arr[15];
    ropes->mode = (unsigned char *)arr[16];
    ropes->root_inside = (unsigned char *)arr[17];
    ropes->glide = (float *)arr[18];
    ropes->longest = (float *)arr[19];
    /* identity frames (tangent x, normal y, bitangent cross(t, n) = z),
       current and previous */
    R = (size_t)rope_count;
    for (k = 0; k < R; ++k) {
        ropes->frame[3 * R + k] = 1.0f;
        ropes->frame[7 * R + k] = 1.0f;
        ropes->frame[11 * R + k] = 1.0f;
        ropes->frame[15 * R + k] = 1.0f;
        ropes->frame[19 * R + k] = 1.0f;
        ropes->frame[23 * R + k] = 1.0f;
        ropes->time[k] = 0.0;
    }
    return HF_OK;
}

HFDEF hf_result hf_ropes_create(int rope_count, int points,
                                const hf_allocator *alloc,
                                hf_ropes **out_ropes)
{
    size_t need, head = (sizeof(hf_ropes) + 63u) & ~(size_t)63u;
    hf_ropes *ro;
    hf_result r;
    if (!out_ropes) return HF_ERROR_NULL_POINTER;
    r = hf_ropes_memory_size(rope_count, points, &need);
    if (r != HF_OK) return r;
    if (need + head < need) return HF_ERROR_OVERFLOW;
    ro = (hf_ropes *)hf__alloc(alloc, need + head);
    if (!ro) return HF_ERROR_OUT_OF_MEMORY;
    r = hf_ropes_init(ro, rope_count, points, (unsigned char *)ro + head,
                      need);
    HF_ASSERT(r == HF_OK);
    if (alloc) ro->allocator = *alloc;
    ro->owned = alloc ? 2 : 1;
    *out_ropes = ro;
    return HF_OK;
}

HFDEF void hf_ropes_destroy(hf_ropes *ropes)
{
    if (!ropes || !ropes->owned) return;
    if (ropes->owned == 2) {
        hf_allocator a = ropes->allocator;
        hf__free(&a, ropes);
    } else {
        hf__free(NULL, ropes);
    }
}

/* ---- 6.2 frames --------------------------------------------------------- */

HF__PRIVATE int hf__ropes_range(const hf_ropes *ro, int first, int count)
{
    return first >= 0 && count >= 0 && first <= ro->rope_count &&
           count <= ro->rope_count - first;
}

HF__PRIVATE int hf__ropes_ok(const hf_ropes *ro)
{
    return ro && ro->x && ro->rope_count >= 1 && ro->points >= 2;
}

/* Unit vector perpendicular to unit n, chosen from n alone: the axis that n
   leans on least, made perpendicular. */
HF__PRIVATE void hf__rope_perp(const float *n, float *out)
{
    float ax = HF_FABS(n[0]), ay = HF_FABS(n[1]), az = HF_FABS(n[2]);
    float e[3] = {0.0f, 0.0f, 0.0f}, d, l2;
    e[(ax <= ay && ax <= az) ? 0 : (ay <= az ? 1 : 2)] = 1.0f;
    d = hf__dot3(n, e);
    out[0] = e[0] - n[0] * d;
    out[1] = e[1] - n[1] * d;
    out[2] = e[2] - n[2] * d;
    l2 = hf__dot3(out, out); /* >= 2/3 for a unit n */
    d = 1.0f / HF_SQRTF(l2);
    out[0] *= d;
    out[1] *= d;
    out[2] *= d;
}

/* The largest |v[k]|; hf__rope_unit takes v as zero where it is not above
   1e-30. */
HF__PRIVATE float hf__rope_absmax(const float *v)
{
    float m = HF_FABS(v[0]);
    if (HF_FABS(v[1]) > m) m = HF_FABS(v[1]);
    if (HF_FABS(v[2]) > m) m = HF_FABS(v[2]);
    return m;
}

/* Normalise v (finite) into out, scaling first so no square overflows.
   Returns 0 (out untouched) for a zero vector. */
HF__PRIVATE int hf__rope_unit(const float *v, float *out)
{
    const float m = hf__rope_absmax(v);
    float s[3], l2;
    if (!(m > 1e-30f)) return 0;
    s[0] = v[0] / m;
    s[1] = v[1] / m;
    s[2] = v[2] / m;
    l2 = hf__dot3(s, s);
    l2 = 1.0f / HF_SQRTF(l2);
    out[0] = s[0] * l2;
    out[1] = s[1] * l2;
    out[2] = s[2] * l2;
    return 1;
}

/* Orthonormal frame f[12] = p, t, n, b from a position, a unit normal and
   any tangent (made perpendicular; a degenerate one replaced). */
HF__PRIVATE void hf__rope_basis(const float *p, const float *n,
                                const float *t_in, float *f)
{
    float t[3], d = hf__dot3(n, t_in), l2;
    t[0] = t_in[0] - n[0] * d;
    t[1] = t_in[1] - n[1] * d;
    t[2] = t_in[2] - n[2] * d;
    l2 = hf__dot3(t, t);
    if (l2 > 1e-10f) {
        l2 = 1.0f / HF_SQRTF(l2);
        t[0] *= l2;
        t[1] *= l2;
        t[2] *= l2;
    } else {
        hf__rope_perp(n, t);
    }
    f[0] = p[0];
    f[1] = p[1];
    f[2] = p[2];
    f[3] = t[0];
    f[4] = t[1];
    f[5] = t[2];
    f[6] = n[0];
    f[7] = n[1];
    f[8] = n[2];
    hf__cross3(f + 9, t, n);
}

/* Rounding noise below 2^-40 in a root frame or a rest offset (a root on
   a mesh's plane of symmetry has components that should be 0), made 0:
   products of two such values are subnormal, and every rope row that
   multiplies them then runs many times slower. */
#define HF__ROPE_TINY (1.0f / 1099511627776.0f)

HF__PRIVATE float hf__rope_clean(float x)
{
    return HF_FABS(x) < HF__ROPE_TINY ? 0.0f : x;
}

HF__PRIVATE const float *hf__rope_at(const float *base, int stride, size_t i)
{
    return (const float *)((const unsigned char *)base +
                           i * (size_t)(stride ? stride : 12));
}

HF__PRIVATE int hf__rope_coord_ok(const float *v)
{
    int k;
    for (k = 0; k < 3; ++k)
        if (!(HF_FABS(v[k]) <= HF_ROPE_MAX_COORD)) return 0;
    return 1;
}

/* Validate the root frames of a range (nothing written). */
HF__PRIVATE hf_result hf__ropes_check_roots(int first, int count,
                                            const float *pos,
                                            const float *nrm,
                                            const float *tan, int stride)
{
    int r, k;
    if (!pos || !nrm || !tan) return HF_ERROR_NULL_POINTER;
    if (!hf__stride_ok(pos, stride, 12) || !hf__stride_ok(nrm, stride, 12) ||
        !hf__stride_ok(tan, stride, 12))
        return HF_ERROR_BAD_STRIDE;
    for (r = first; r < first + count; ++r) {
        const float *p = hf__rope_at(pos, stride, (size_t)r);
        const float *n = hf__rope_at(nrm, stride, (size_t)r);
        const float *t = hf__rope_at(tan, stride, (size_t)r);
        HF__UNROLL for (k = 0; k < 3; ++k)
            if (!hf__finitef(p[k]) || !hf__finitef(n[k]) ||
                !hf__finitef(t[k]))
                return HF_ERROR_NON_FINITE;
        if (!hf__rope_coord_ok(p)) return HF_ERROR_BAD_PARAMETER;
        /* hf__rope_unit's zero test, without its divisions */
        if (!(hf__rope_absmax(n) > 1e-30f)) return HF_ERROR_DEGENERATE;
    }
    return HF_OK;
}

/* Store frame f[12] in rows [row0, row0 + 12) of the frame array (its
   noise made 0: hf__rope_clean). */
HF__PRIVATE void hf__rope_put_frame(hf_ropes *ro, int row0, int r,
                                    const float *f)
{
    size_t R = (size_t)ro->rope_count;
    int k;
    for (k = 0; k < 12; ++k)
        ro->frame[(size_t)(row0 + k) * R + r] = hf__rope_clean(f[k]);
}

HF__PRIVATE void hf__rope_get_frame(const hf_ropes *ro, int row0, int r,
                                    float *f)
{
    size_t R = (size_t)ro->rope_count;
    int k;
    for (k = 0; k < 12; ++k) f[k] = ro->frame[(size_t)(row0 + k) * R + r];
}

#if HF__V4
/* |x| on four lanes (a -0 stays -0: only a compare sees it) */
HF__PRIVATE hf__v4 hf__rope_abs_v4(hf__v4 x)
{
    const hf__v4 zero = HF__SET1(0.0f);
    return HF__SEL(HF__LT(x, zero), HF__SUB(zero, x), x);
}

/* hf__rope_unit on four vectors; returns the lanes it returns 1 for (the
   others: anything in out) */
HF__PRIVATE hf__v4 hf__rope_unit_v4(const hf__v4 *v, hf__v4 *out)
{
    hf__v4 a[3], m, l2;
    int k;
    HF__UNROLL for (k = 0; k < 3; ++k) a[k] = hf__rope_abs_v4(v[k]);
    m = a[0];
    m = HF__SEL(HF__GT(a[1], m), a[1], m);
    m = HF__SEL(HF__GT(a[2], m), a[2], m);
    HF__UNROLL for (k = 0; k < 3; ++k) out[k] = HF__DIV(v[k], m);
    l2 = HF__DIV(HF__SET1(1.0f),
                 HF__SQRT(HF__DOT3(out[0], out[1], out[2], out[0], out[1],
                                   out[2])));
    HF__UNROLL for (k = 0; k < 3; ++k) out[k] = HF__MUL(out[k], l2);
    return HF__GT(m, HF__SET1(1e-30f));
}

/* hf__rope_clean on four lanes */
HF__PRIVATE hf__v4 hf__rope_clean_v4(hf__v4 x)
{
    return HF__SEL(HF__LT(hf__rope_abs_v4(x), HF__SET1(HF__ROPE_TINY)),
                   HF__SET1(0.0f), x);
}

/* hf__ropes_write_roots_v1 for ropes [r, r + 4): the same operations lane
   by lane, so the same bytes; a degenerate tangent, rare, through
   hf__rope_perp lane by lane. */
HF__PRIVATE void hf__ropes_write_roots4(hf_ropes *ro, int r, const float *pos,
                                        const float *nrm, const float *tan,
                                        int stride)
{
    const size_t R = (size_t)ro->rope_count;
    const hf__v4 zero = HF__SET1(0.0f);
    const float *in[3][4];
    float g[6][4];
    hf__v4 p[3], n[3], t[3], v[3], d, l2, ok;
    int i, k, lanes;
    HF__UNROLL for (i = 0; i < 4; ++i) {
        in[0][i] = hf__rope_at(pos, stride, (size_t)(r + i));
        in[1][i] = hf__rope_at(nrm, stride, (size_t)(r + i));
        in[2][i] = hf__rope_at(tan, stride, (size_t)(r + i));
    }
#define HF__ROOT4(a, k)                                                        \
    HF__SET4(in[a][0][k], in[a][1][k], in[a][2][k], in[a][3][k])
    HF__UNROLL for (k = 0; k < 3; ++k) {
        p[k] = HF__ROOT4(0, k);
        v[k] = HF__ROOT4(1, k);
    }
    hf__rope_unit_v4(v, n); /* checked: not zero */
    HF__UNROLL for (k = 0; k < 3; ++k) v[k] = HF__ROOT4(2, k);
#undef HF__ROOT4
    ok = hf__rope_unit_v4(v, t);
    HF__UNROLL for (k = 0; k < 3; ++k) t[k] = HF__AND(ok, t[k]);
    /* hf__rope_basis */
    d = HF__DOT3(n[0], n[1], n[2], t[0], t[1], t[2]);
    HF__UNROLL for (k = 0; k < 3; ++k) t[k] = HF__SUB(t[k], HF__MUL(n[k], d));
    l2 = HF__DOT3(t[0], t[1], t[2], t[0], t[1], t[2]);
    ok = HF__GT(l2, HF__SET1(1e-10f));
    l2 = HF__DIV(HF__SET1(1.0f), HF__SQRT(l2));
    HF__UNROLL for (k = 0; k < 3; ++k)
        t[k] = HF__SEL(ok, HF__MUL(t[k], l2), zero);
    lanes = HF__MASK(ok) ^ 15;
    if (lanes) {
        for (k = 0; k < 3; ++k) {
            HF__ST(g[k], n[k]);
            HF__ST(g[3 + k], t[k]);
        }
        for (i = 0; i < 4; ++i)
            if ((lanes >> i) & 1) {
                float nl[3], tl[3];
                for (k = 0; k < 3; ++k) nl[k] = g[k][i];
                hf__rope_perp(nl, tl);
                for (k = 0; k < 3; ++k) g[3 + k][i] = tl[k];
            }
        for (k = 0; k < 3; ++k) t[k] = HF__LD(g[3 + k]);
    }
    HF__CROSS3(v, t, n); /* f = p, t, n, t x n */
    HF__UNROLL for (k = 0; k < 3; ++k) {
        HF__ST(ro->frame + (size_t)k * R + (size_t)r, hf__rope_clean_v4(p[k]));
        HF__ST(ro->frame + (size_t)(3 + k) * R + (size_t)r,
               hf__rope_clean_v4(t[k]));
        HF__ST(ro->frame + (size_t)(6 + k) * R + (size_t)r,
               hf__rope_clean_v4(n[k]));
        HF__ST(ro->frame + (size_t)(9 + k) * R + (size_t)r,
               hf__rope_clean_v4(v[k]));
    }
}

/* The root frames of ropes [a, b), whole groups of four; returns where
   they end. */
HF__PRIVATE int hf__ropes_write_roots_v4(hf_ropes *ro, int a, int b,
                                         const float *pos, const float *nrm,
                                         const float *tan, int stride)
{
    for (; a + 4 <= b; a += 4)
        hf__ropes_write_roots4(ro, a, pos, nrm, tan, stride);
    return a;
}
#endif

/* The root frames of ropes [a, b) from their roots' positions, normals
   and tangents: the reference. */
HF__PRIVATE int hf__ropes_write_roots_v1(hf_ropes *ro, int a, int b,
                                         const float *pos, const float *nrm,
                                         const float *tan, int stride)
{
    int r;
    for (r = a; r < b; ++r) {
        float n[3], t[3], f[12];
        const float *tin = hf__rope_at(tan, stride, (size_t)r);
        hf__rope_unit(hf__rope_at(nrm, stride, (size_t)r), n);
        if (!hf__rope_unit(tin, t)) t[0] = t[1] = t[2] = 0.0f;
        hf__rope_basis(hf__rope_at(pos, stride, (size_t)r), n, t, f);
        hf__rope_put_frame(ro, 0, r, f);
    }
    return b;
}

typedef struct hf__roots_kernels {
    hf__isa isa;
    int (*write)(hf_ropes *, int, int, const float *, const float *,
                 const float *, int);
} hf__roots_kernels;

static const hf__roots_kernels hf__roots_widths[] = {
#if HF__V4
    {{HF__ISA_V4}, hf__ropes_write_roots_v4},
#endif
    {{HF__ISA_V1}, hf__ropes_write_roots_v1}};

/* The dispatch of the root frames at SIMD level `simd` (hf__roots_widths). */
HF__PRIVATE void hf__ropes_write_roots(hf_ropes *ro, int first, int count,
                                       const float *pos, const float *nrm,
                                       const float *tan, int stride, int simd)
{
    const hf__roots_kernels *k = hf__kernels_for(hf__roots_widths, simd);
    int a = first;
    for (; a < first + count; ++k)
        a = k->write(ro, a, first + count, pos, nrm, tan, stride);
}

/* The root frame at fraction alpha of the way from the previous frame to
   the current one: lerped position, nlerped normal and tangent,
   re-orthonormalised. alpha >= 1 is the current frame, bit for bit. */
HF__PRIVATE void hf__rope_frame_at(const hf_ropes *ro, int r, float alpha,
                                   float *f)
{
    float c[12], p[12], n[3], t[3], pos[3], l2;
    int k;
    hf__rope_get_frame(ro, 0, r, c);
    if (alpha >= 1.0f) {
        for (k = 0; k < 12; ++k) f[k] = c[k];
        return;
    }
    hf__rope_get_frame(ro, 12, r, p);
    for (k = 0; k < 3; ++k) {
        pos[k] = p[k] * (1.0f - alpha) + c[k] * alpha;
        t[k] = p[3 + k] * (1.0f - alpha) + c[3 + k] * alpha;
        n[k] = p[6 + k] * (1.0f - alpha) + c[6 + k] * alpha;
    }
    l2 = hf__dot3(n, n);
    if (l2 > 1e-6f) { /* a normal flipped by 180 degrees has no midpoint */
        l2 = 1.0f / HF_SQRTF(l2);
        n[0] *= l2;
        n[1] *= l2;
        n[2] *= l2;
    } else {
        n[0] = c[6];
        n[1] = c[7];
        n[2] = c[8];
    }
    hf__rope_basis(pos, n, t, f);
}

/* ---- 6.3 rest pose, roots, modes ---------------------------------------- */

/* Particles of rope r at its rest pose in the current frame, at rest. */
HF__PRIVATE void hf__rope_reset_one(hf_ropes *ro, int r)
{
    size_t R = (size_t)ro->rope_count, i;
    float f[12];
    int j;
    hf__rope_get_frame(ro, 0, r, f);
    hf__rope_put_frame(ro, 12, r, f);
    for (j = 0; j < ro->points; ++j) {
        float u, v, w;
        i = (size_t)j * R + (size_t)r;
        u = ro->rest_u[i];
        v = ro->rest_v[i];
        w = ro->rest_w[i];
        ro->x[i] = ro->px[i] = f[0] + f[3] * u + f[6] * v + f[9] * w;
        ro->y[i] = ro->py[i] = f[1] + f[4] * u + f[7] * v + f[10] * w;
        ro->z[i] = ro->pz[i] = f[2] + f[5] * u + f[8] * v + f[11] * w;
    }
    ro->last_h[r] = 0.0f;
    ro->blend[r] = ro->mode[r] == HF_ROPE_ANIMATED ? 1.0f : 0.0f;
}

/* hf_ropes_set_rest with the root frames' kernels at SIMD level simd (the
   fur's: hf_fur_set_kernels) */
HF__PRIVATE hf_result hf__ropes_set_rest(
    hf_ropes *ropes, int first, int count, const float *positions,
    int position_stride, const float *root_pos, const float *root_normal,
    const float *root_tangent, int root_stride, int simd)
{
    size_t P, R;
    hf_result res;
    int r, j, k;
    if (!hf__ropes_ok(ropes) || !positions) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    if (!hf__stride_ok(positions, position_stride, 12))
        return HF_ERROR_BAD_STRIDE;
    res = hf__ropes_check_roots(first, count, root_pos, root_normal,
                                root_tangent, root_stride);
    if (res != HF_OK) return res;
    P = (size_t)ropes->points;
    R = (size_t)ropes->rope_count;
    for (r = first; r < first + count; ++r)
        for (j = 0; j < (int)P; ++j) {
            const float *q =
                hf__rope_at(positions, position_stride, (size_t)r * P + j);
            for (k = 0; k < 3; ++k)
                if (!hf__finitef(q[k])) return HF_ERROR_NON_FINITE;
            if (!hf__rope_coord_ok(q)) return HF_ERROR_BAD_PARAMETER;
        }
    hf__ropes_write_roots(ropes, first, count, root_pos, root_normal,
                          root_tangent, root_stride, simd);
    for (r = first; r < first + count; ++r) {
        float f[12], total = 0.0f, longest = 0.0f;
        hf__rope_get_frame(ropes, 0, r, f);
        for (j = 0; j < (int)P; ++j) {
            const float *q =
                hf__rope_at(positions, position_stride, (size_t)r * P + j);
            size_t i = (size_t)j * R + (size_t)r;
            float d[3];
            hf__sub3(d, q, f);
            ropes->rest_u[i] = hf__rope_clean(hf__dot3(d, f + 3));
            ropes->rest_v[i] = hf__rope_clean(hf__dot3(d, f + 6));
            ropes->rest_w[i] = hf__rope_clean(hf__dot3(d, f + 9));
            if (j + 1 < (int)P) {
                const float *q1 = hf__rope_at(positions, position_stride,
                                              (size_t)r * P + j + 1);
                float e[3];
                double l;
                hf__sub3(e, q1, q);
                l = HF_SQRT((double)e[0] * e[0] + (double)e[1] * e[1] +
                            (double)e[2] * e[2]);
                ropes->rest_length[i] = (float)l;
                total += (float)l;
                longest = (float)l > longest ? (float)l : longest;
            } else {
                ropes->rest_length[i] = 0.0f;
            }
        }
        ropes->length[r] = total;
        ropes->longest[r] = longest;
        hf__rope_reset_one(ropes, r);
    }
    return HF_OK;
}

HFDEF hf_result hf_ropes_set_rest(hf_ropes *ropes, int first, int count,
                                  const float *positions, int position_stride,
                                  const float *root_pos,
                                  const float *root_normal,
                                  const float *root_tangent, int root_stride)
{
    return hf__ropes_set_rest(ropes, first, count, positions, position_stride,
                              root_pos, root_normal, root_tangent, root_stride,
                              HF_SIMD_AUTO);
}

/* hf_ropes_set_roots at SIMD level simd (the fur's) */
HF__PRIVATE hf_result hf__ropes_set_roots(hf_ropes *ropes, int first, int count,
                                          const float *root_pos,
                                          const float *root_normal,
                                          const float *root_tangent,
                                          int root_stride, int simd)
{
    hf_result res;
    if (!hf__ropes_ok(ropes)) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    res = hf__ropes_check_roots(first, count, root_pos, root_normal,
                                root_tangent, root_stride);
    if (res != HF_OK) return res;
    hf__ropes_write_roots(ropes, first, count, root_pos, root_normal,
                          root_tangent, root_stride, simd);
    return HF_OK;
}

HFDEF hf_result hf_ropes_set_roots(hf_ropes *ropes, int first, int count,
                                   const float *root_pos,
                                   const float *root_normal,
                                   const float *root_tangent, int root_stride)
{
    return hf__ropes_set_roots(ropes, first, count, root_pos, root_normal,
                               root_tangent, root_stride, HF_SIMD_AUTO);
}

/* Rope r starts gliding to animation: its pose, in the coordinates of the
   frame it was computed in (the last step's, held in the previous-frame
   rows), and its velocity per second in those axes (the frame's own
   motion is taken off at the glide's first sub-step, when it is known). */
HF__PRIVATE void hf__glide_start(hf_ropes *ro, int r)
{
    const size_t R = (size_t)ro->rope_count, n = R * (size_t)ro->points;
    const float iv = ro->last_h[r] > 0.0f ? 1.0f / ro->last_h[r] : 0.0f;
    float f[12];
    int j, k;
    hf__rope_get_frame(ro, 12, r, f);
    for (j = 0; j < ro->points; ++j) {
        size_t i = (size_t)j * R + (size_t)r;
        float d[3], v[3];
        d[0] = ro->x[i] - f[0];
        d[1] = ro->y[i] - f[1];
        d[2] = ro->z[i] - f[2];
        v[0] = (ro->x[i] - ro->px[i]) * iv;
        v[1] = (ro->y[i] - ro->py[i]) * iv;
        v[2] = (ro->z[i] - ro->pz[i]) * iv;
        for (k = 0; k < 3; ++k) {
            ro->glide[(size_t)k * n + i] = hf__dot3(d, f + 3 + 3 * k);
            ro->glide[(size_t)(3 + k) * n + i] = hf__dot3(v, f + 3 + 3 * k);
        }
    }
    ro->blend[r] = 0.0f;
}

HFDEF hf_result hf_ropes_set_mode(hf_ropes *ropes, int first, int count,
                                  int mode)
{
    int r;
    if (!hf__ropes_ok(ropes)) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    if (mode != HF_ROPE_SIMULATED && mode != HF_ROPE_ANIMATED)
        return HF_ERROR_BAD_PARAMETER;
    for (r = first; r < first + count; ++r) {
        /* x and px are world positions in every mode (a glide keeps
           them so too), so a switch to simulation keeps position and
           velocity; a glide toward animation starts from both */
        if (mode == HF_ROPE_ANIMATED && ropes->mode[r] == HF_ROPE_SIMULATED)
            hf__glide_start(ropes, r);
        if (mode == HF_ROPE_SIMULATED) ropes->blend[r] = 0.0f;
        ropes->mode[r] = (unsigned char)mode;
    }
    return HF_OK;
}

HFDEF hf_result hf_ropes_reset(hf_ropes *ropes, int first, int count)
{
    int r;
    if (!hf__ropes_ok(ropes)) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    for (r = first; r < first + count; ++r) hf__rope_reset_one(ropes, r);
    return HF_OK;
}

HFDEF hf_result hf_ropes_rest_from_pose(hf_ropes *ropes, int first,
                                        int count)
{
    const size_t R = ropes ? (size_t)ropes->rope_count : 0u;
    int r, j;
    if (!hf__ropes_ok(ropes)) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    for (r = first; r < first + count; ++r) {
        float f[12];
        /* the frame the points were computed in */
        hf__rope_get_frame(ropes, 12, r, f);
        for (j = 0; j < ropes->points; ++j) {
            const size_t i = (size_t)j * R + (size_t)r;
            float d[3];
            d[0] = ropes->x[i] - f[0];
            d[1] = ropes->y[i] - f[1];
            d[2] = ropes->z[i] - f[2];
            ropes->rest_u[i] = hf__rope_clean(hf__dot3(d, f + 3));
            ropes->rest_v[i] = hf__rope_clean(hf__dot3(d, f + 6));
            ropes->rest_w[i] = hf__rope_clean(hf__dot3(d, f + 9));
        }
        hf__rope_reset_one(ropes, r);
    }
    return HF_OK;
}

HFDEF hf_result hf_ropes_max_stretch(const hf_ropes *ropes, int first,
                                     int count, float *out_stretch)
{
    size_t R;
    float m = 0.0f;
    int j, r;
    if (!hf__ropes_ok(ropes) || !out_stretch) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    R = (size_t)ropes->rope_count;
    for (j = 0; j + 1 < ropes->points; ++j) {
        const float *x0 = ropes->x + (size_t)j * R, *x1 = x0 + R;
        const float *y0 = ropes->y + (size_t)j * R, *y1 = y0 + R;
        const float *z0 = ropes->z + (size_t)j * R, *z1 = z0 + R;
        const float *L = ropes->rest_length + (size_t)j * R;
        for (r = first; r < first + count; ++r) {
            double dx = (double)x1[r] - x0[r], dy = (double)y1[r] - y0[r],
                   dz = (double)z1[r] - z0[r], e;
            if (!(L[r] > 0.0f)) continue;
            e = HF_FABS(HF_SQRT(dx * dx + dy * dy + dz * dz) - L[r]) / L[r];
            if (e > m) m = (float)e;
        }
    }
    *out_stretch = m;
    return HF_OK;
}

/* Rope-major copies of points [j0, P) of ropes [a, b) into `out`, which
   starts at rope `base` (a for a buffer of exactly the range, 0 for
   absolute indexing), at any stride: the reference, and the kernels'
   tails where their blocks of points end. */
HF__PRIVATE void hf__ropes_copy_points(const hf_ropes *ro, int a, int b,
                                       size_t j0, float *out, size_t stride,
                                       int base)
{
    const size_t R = (size_t)ro->rope_count, P = (size_t)ro->points;
    size_t j;
    int r;
    for (r = a; r < b; ++r)
        for (j = j0; j < P; ++j) {
            const size_t i = j * R + (size_t)r;
            float *o = (float *)((unsigned char *)out +
                                 ((size_t)(r - base) * P + j) * stride);
            o[0] = ro->x[i];
            o[1] = ro->y[i];
            o[2] = ro->z[i];
        }
}

#if HF__SSE
/* The rows of points [j, j + n) of ropes from r, in the order they go out:
   x, y, z of point j, of point j + 1, ... Read n at a time across the
   ropes, every n consecutive rows are a square block whose transpose is n
   consecutive output floats of each rope: no shuffle beyond the
   transposes. */
HF__INLINE void hf__ropes_out_rows(const hf_ropes *ro, size_t j, int n,
                                   int r, const float **row)
{
    const size_t R = (size_t)ro->rope_count;
    size_t o = j * R + (size_t)r;
    int k;
    for (k = 0; k < n; ++k, o += R) {
        row[3 * k] = ro->x + o;
        row[3 * k + 1] = ro->y + o;
        row[3 * k + 2] = ro->z + o;
    }
}

/* Ropes [r, r + 4) into packed output that starts at rope `base`: four
   points at a time, three 4 x 4 transposes (hf__ropes_out_rows). */
HF__PRIVATE void hf__ropes_copy4(const hf_ropes *ro, int r, float *out,
                                 int base)
{
    const size_t P = (size_t)ro->points;
    size_t j, i;
    int g;
    for (j = 0; j + 4 <= P; j += 4) {
        const float *row[12];
        hf__ropes_out_rows(ro, j, 4, r, row);
        for (g = 0; g < 3; ++g) {
            __m128 v0 = _mm_loadu_ps(row[4 * g]),
                   v1 = _mm_loadu_ps(row[4 * g + 1]),
                   v2 = _mm_loadu_ps(row[4 * g + 2]),
                   v3 = _mm_loadu_ps(row[4 * g + 3]);
            _MM_TRANSPOSE4_PS(v0, v1, v2, v3);
            /* vk: floats 4 g .. 4 g + 3 of rope r + k's points j.. */
            i = ((size_t)(r - base) * P + j) * 3u + 4u * (size_t)g;
            _mm_storeu_ps(out + i, v0);
            _mm_storeu_ps(out + i + 3 * P, v1);
            _mm_storeu_ps(out + i + 6 * P, v2);
            _mm_storeu_ps(out + i + 9 * P, v3);
        }
    }
    hf__ropes_copy_points(ro, r, r + 4, j, out, 12, base);
}
#endif

#if HF__AVX2
/* Rows q[0..8) of ropes [h, h + 4) transposed: rope h + k's eight floats
   at o + k step. Rows k and k + 4 sit side by side in the 128-bit lanes,
   so two 4 x 4 transposes in the lanes make the 8 x 4 one. */
HF__TARGET_AVX2 HF__INLINE void hf__ropes_t8x4(const float *const *q,
                                               size_t h, float *o,
                                               size_t step)
{
#define HF__PAIR(k)                                                            \
    _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(q[k] + h)),       \
                         _mm_loadu_ps(q[k + 4] + h), 1)
    const __m256 t0 = HF__PAIR(0), t1 = HF__PAIR(1), t2 = HF__PAIR(2),
                 t3 = HF__PAIR(3);
#undef HF__PAIR
    const __m256 a0 = _mm256_unpacklo_ps(t0, t1),
                 a1 = _mm256_unpackhi_ps(t0, t1),
                 a2 = _mm256_unpacklo_ps(t2, t3),
                 a3 = _mm256_unpackhi_ps(t2, t3);
    _mm256_storeu_ps(o, _mm256_shuffle_ps(a0, a2, 0x44));
    _mm256_storeu_ps(o + step, _mm256_shuffle_ps(a0, a2, 0xee));
    _mm256_storeu_ps(o + 2 * step, _mm256_shuffle_ps(a1, a3, 0x44));
    _mm256_storeu_ps(o + 3 * step, _mm256_shuffle_ps(a1, a3, 0xee));
}

/* hf__ropes_copy4 for ropes [r, r + 8), eight points at a time: three
   8 x 8 transposes (hf__ropes_out_rows). */
HF__TARGET_AVX2 HF__PRIVATE void hf__ropes_copy8(const hf_ropes *ro, int r,
                                                 float *out, int base)
{
    const size_t P = (size_t)ro->points;
    size_t j;
    for (j = 0; j + 8 <= P; j += 8) {
        const float *row[24];
        float *o = out + ((size_t)(r - base) * P + j) * 3u;
        hf__ropes_out_rows(ro, j, 8, r, row);
        hf__ropes_t8x4(row, 0, o, 3 * P);
        hf__ropes_t8x4(row, 4, o + 12 * P, 3 * P);
        hf__ropes_t8x4(row + 8, 0, o + 8, 3 * P);
        hf__ropes_t8x4(row + 8, 4, o + 8 + 12 * P, 3 * P);
        hf__ropes_t8x4(row + 16, 0, o + 16, 3 * P);
        hf__ropes_t8x4(row + 16, 4, o + 16 + 12 * P, 3 * P);
    }
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
    hf__ropes_copy_points(ro, r, r + 8, j, out, 12, base);
}

/* Ropes [a, b), whole groups of eight, packed output only; returns where
   they end. */
HF__PRIVATE int hf__ropes_copy_v8(const hf_ropes *ro, int a, int b, float *out,
                                  size_t stride, int base)
{
    if (stride == 12)
        for (; a + 8 <= b; a += 8) hf__ropes_copy8(ro, a, out, base);
    return a;
}
#endif

#if HF__SSE
/* hf__ropes_copy_v8 in groups of four */
HF__PRIVATE int hf__ropes_copy_v4(const hf_ropes *ro, int a, int b, float *out,
                                  size_t stride, int base)
{
    if (stride == 12)
        for (; a + 4 <= b; a += 4) hf__ropes_copy4(ro, a, out, base);
    return a;
}
#endif

/* Ropes [a, b) at any stride: the reference; returns b. */
HF__PRIVATE int hf__ropes_copy_v1(const hf_ropes *ro, int a, int b, float *out,
                                  size_t stride, int base)
{
    hf__ropes_copy_points(ro, a, b, 0, out, stride, base);
    return b;
}

typedef struct hf__copy_kernels {
    hf__isa isa;
    int (*copy)(const hf_ropes *, int, int, float *, size_t, int);
} hf__copy_kernels;

static const hf__copy_kernels hf__copy_widths[] = {
#if HF__AVX2
    {{HF__ISA_V8}, hf__ropes_copy_v8},
#endif
#if HF__SSE
    {{HF__ISA_V4}, hf__ropes_copy_v4},
#endif
    {{HF__ISA_V1}, hf__ropes_copy_v1}};

/* The dispatch of the rope-major copies at SIMD level `simd`
   (hf__copy_widths): the widest kernel the level runs takes what it can,
   the narrower ones the rest. */
HF__PRIVATE void hf__ropes_copy(const hf_ropes *ro, int a, int b, float *out,
                                size_t stride, int base, int simd)
{
    const hf__copy_kernels *k = hf__kernels_for(hf__copy_widths, simd);
    for (; a < b; ++k) a = k->copy(ro, a, b, out, stride, base);
}

HFDEF hf_result hf_ropes_get_positions(const hf_ropes *ropes, int first,
                                       int count, float *out, int stride)
{
    if (!hf__ropes_ok(ropes) || !out) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    if (!hf__stride_ok(out, stride, 12)) return HF_ERROR_BAD_STRIDE;
    hf__ropes_copy(ropes, first, first + count, out,
                   (size_t)(stride ? stride : 12), 0, HF_SIMD_AUTO);
    return HF_OK;
}

HFDEF hf_result hf_ropes_copy_range(const hf_ropes *ropes, int first,
                                    int count, float *out, int stride)
{
    if (!hf__ropes_ok(ropes) || !out) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    if (!hf__stride_ok(out, stride, 12)) return HF_ERROR_BAD_STRIDE;
    hf__ropes_copy(ropes, first, first + count, out,
                   (size_t)(stride ? stride : 12), first, HF_SIMD_AUTO);
    return HF_OK;
}

/* ---- 6.4 the step ------------------------------------------------------- */

/* Deterministic value noise in [-1, 1] of (rope, cell, axis): a hash, not
   a generator, so a rope's turbulence does not depend on which other ropes
   were stepped before it. */
HF__PRIVATE float hf__rope_hash(uint32_t rope, int64_t cell, uint32_t axis)
{
    uint64_t h = (uint64_t)cell * 0x9E3779B97F4A7C15ULL ^
                 ((uint64_t)rope << 2 | axis) * 0xC2B2AE3D27D4EB4FULL;
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDULL;
    h ^= h >> 33;
    h *= 0xC4CEB9FE1A85EC53ULL;
    h ^= h >> 33;
    return (float)(uint32_t)(h >> 40) * (2.0f / 16777216.0f) - 1.0f;
}

HF__PRIVATE float hf__rope_noise(uint32_t rope, double t, uint32_t axis)
{
    double c = HF_FLOOR(t);
    float f = (float)(t - c), s = f * f * (3.0f - 2.0f * f);
    int64_t i = (int64_t)c;
    float a = hf__rope_hash(rope, i, axis), b = hf__rope_hash(rope, i + 1,
                                                              axis);
    return a + (b - a) * s;
}

/* Fraction of a gap closed per sub-step of h seconds for a stiffness k
   given per 1/60 s. */
HF__PRIVATE float hf__rope_k(float k, float h)
{
    if (k <= 0.0f) return 0.0f;
    if (k >= 1.0f) return 1.0f;
    return 1.0f - (float)HF_POW(1.0 - (double)k, (double)h * 60.0);
}

/* Pull of point j (>= 1) of P toward its rest place in the frame, per
   sub-step: global shape, and for point 1 the root stiffness too. */
HF__PRIVATE float hf__rope_kg(const hf__rope_step *st, int j, int P)
{
    float t = (float)j / (float)(P - 1);
    float kg = hf__rope_k(st->gs_root + (st->gs_tip - st->gs_root) * t, st->h);
    if (j == 1) kg = 1.0f - (1.0f - kg) * (1.0f - st->k_root);
    return kg;
}

/* Local shape pull of point j + 1 (j >= 1) of P, per sub-step. */
HF__PRIVATE float hf__rope_kl(const hf__rope_step *st, int j, int P)
{
    float t = (float)(j + 1) / (float)(P - 1);
    return hf__rope_k(st->ls_root + (st->ls_tip - st->ls_root) * t, st->h);
}

/* Row `row` of a point-major array of `stride` (the rope count) floats a
   row. */
#define HF__ROW(base, row, stride) ((base) + (size_t)(row) * (stride))

/* Follow-the-leader's velocity correction where segment j - 1 -> j
   (j >= 2) of rope r was shorter than its rest length before its
   placement. Where the segment was longer, FTL pulled the child back
   toward its parent and Mueller's correction moves the parent's previous
   position by s_damping times that (a pull on the parent, as a tension
   would give). Where it was shorter, FTL pushed the child out, and the
   same correction would push the parent back along the child's segment:
   a compressive load that turns with the segment, which makes a rope
   that its shape stiffness cannot hold up flutter for ever (it keeps
   feeding the motion the energy the damping takes). There the parent is
   left alone and the child's velocity relative to the rigid motion of
   its parent segment (the child's previous offset turned by the smallest
   rotation that takes the parent segment's previous direction to its
   current one, as the local shape turns its rest offset) loses the
   fraction cb: a bend damped, while a rope that swings or turns as a
   whole keeps its motion. Reads rows j - 2 .. j after row j's placement
   and writes row j's previous position; the SIMD kernels do the same
   operations (hf__ftl_bend_turn_v<W>, then hf__ftl_bend_damp_v<W>).
   Rodrigues without trigonometry, as the local shape: with a and b the
   parent segment's previous and current offsets, n = |a| |b| (one square
   root of a2 b2), c = a.b and k = a x b, the rotation taking a's
   direction to b's turns q to
       (q c + k x q) / n + k (k.q) / (n (n + c)),
   both quotients from one division, t = 1 / (n m) with m = n + c
   (clamped at 1e-6 n where a and b are nearly opposite): 1 / n = m t.
   The identity where a or b is under 3e-8 m long (a2 or b2 <= 1e-15,
   which also keeps n m a normal float). */
HF__PRIVATE void hf__ftl_bend_damp(hf_ropes *ro, int j, int r, float cb)
{
    const size_t R = (size_t)ro->rope_count, o = (size_t)j * R + (size_t)r,
                 o1 = o - R, o2 = o1 - R;
    const float ax = ro->px[o1] - ro->px[o2], ay = ro->py[o1] - ro->py[o2],
                az = ro->pz[o1] - ro->pz[o2];
    const float bx = ro->x[o1] - ro->x[o2], by = ro->y[o1] - ro->y[o2],
                bz = ro->z[o1] - ro->z[o2];
    const float qx = ro->px[o] - ro->px[o1], qy = ro->py[o] - ro->py[o1],
                qz = ro->pz[o] - ro->pz[o1];
    const float a2 = ax * ax + ay * ay + az * az,
                b2 = bx * bx + by * by + bz * bz,
                c = ax * bx + ay * by + az * bz;
    const float kx = ay * bz - az * by, ky = az * bx - ax * bz,
                kz = ax * by - ay * bx;
    const int ok = a2 > 1e-15f && b2 > 1e-15f;
    const float n = HF_SQRTF(a2 * b2), e = 1e-6f * n;
    float m = n + c, t, s, kd, rx, ry, rz;
    m = m > e ? m : e;
    t = 1.0f / (ok ? n * m : 1.0f);
    s = m * t;
    kd = (kx * qx + ky * qy + kz * qz) * t;
    rx = (qx * c + (ky * qz - kz * qy)) * s + kx * kd;
    ry = (qy * c + (kz * qx - kx * qz)) * s + ky * kd;
    rz = (qz * c + (kx * qy - ky * qx)) * s + kz * kd;
    rx = ok ? rx : qx;
    ry = ok ? ry : qy;
    rz = ok ? rz : qz;
    ro->px[o] += cb * (ro->x[o] - ro->x[o1] - rx);
    ro->py[o] += cb * (ro->y[o] - ro->y[o1] - ry);
    ro->pz[o] += cb * (ro->z[o] - ro->z[o1] - rz);
}


/* The 12 rows of a frame block (position, tangent, normal, bitangent;
   x, y, z each), `stride` floats apart. */
HF__PRIVATE void hf__frame_rows(const float *fr, size_t stride,
                                const float *rows[12])
{
    int k;
    for (k = 0; k < 12; ++k) rows[k] = HF__ROW(fr, k, stride);
}

/* Point row j of ropes [a, b) at frame rows fr (12 rows) times rest:
   the scalar reference, the four-lane kernel (whole groups from a), each
   returning where it stopped, and their dispatch. */
HF__PRIVATE int hf__rope_pose_row_v1(const hf_ropes *ro, int j, int a, int b,
                                     const float *fr, float *HF__RESTRICT ox,
                                     float *HF__RESTRICT oy,
                                     float *HF__RESTRICT oz)
{
    const size_t R = (size_t)ro->rope_count;
    const float *u = HF__ROW(ro->rest_u, j, R), *v = HF__ROW(ro->rest_v, j, R),
                *w = HF__ROW(ro->rest_w, j, R);
    const float *f[12];
    int r;
    hf__frame_rows(fr, R, f);
    for (r = a; r < b; ++r) {
        ox[r] = f[0][r] + f[3][r] * u[r] + f[6][r] * v[r] + f[9][r] * w[r];
        oy[r] = f[1][r] + f[4][r] * u[r] + f[7][r] * v[r] + f[10][r] * w[r];
        oz[r] = f[2][r] + f[5][r] * u[r] + f[8][r] * v[r] + f[11][r] * w[r];
    }
    return b;
}

#if HF__V4
HF__PRIVATE int
hf__rope_pose_row_v4(const hf_ropes *ro, int j, int a, int b, const float *fr,
                     float *HF__RESTRICT ox, float *HF__RESTRICT oy,
                     float *HF__RESTRICT oz)
{
    const size_t R = (size_t)ro->rope_count;
    const float *u = HF__ROW(ro->rest_u, j, R), *v = HF__ROW(ro->rest_v, j, R),
                *w = HF__ROW(ro->rest_w, j, R);
    const float *f[12];
    int r = a;
    hf__frame_rows(fr, R, f);
    for (; r + 4 <= b; r += 4) {
        const hf__v4 uu = HF__LD(u + r), vv = HF__LD(v + r), ww = HF__LD(w + r);
        HF__ST(ox + r,
               HF__POSE(HF__LD(f[0] + r), HF__LD(f[3] + r), HF__LD(f[6] + r),
                        HF__LD(f[9] + r), uu, vv, ww));
        HF__ST(oy + r,
               HF__POSE(HF__LD(f[1] + r), HF__LD(f[4] + r), HF__LD(f[7] + r),
                        HF__LD(f[10] + r), uu, vv, ww));
        HF__ST(oz + r,
               HF__POSE(HF__LD(f[2] + r), HF__LD(f[5] + r), HF__LD(f[8] + r),
                        HF__LD(f[11] + r), uu, vv, ww));
    }
    return r;
}
#endif

typedef struct hf__pose_kernels {
    hf__isa isa;
    int (*row)(const hf_ropes *, int, int, int, const float *, float *, float *,
               float *);
} hf__pose_kernels;

static const hf__pose_kernels hf__pose_widths[] = {
#if HF__V4
    {{HF__ISA_V4}, hf__rope_pose_row_v4},
#endif
    {{HF__ISA_V1}, hf__rope_pose_row_v1}};

/* The dispatch of a pose row with the kernels st->pose (hf__pose_widths,
   resolved by hf__rope_step_setup). */
HF__PRIVATE void hf__rope_pose_row(const hf_ropes *ro, int j, int a, int b,
                                   const float *fr, float *HF__RESTRICT ox,
                                   float *HF__RESTRICT oy,
                                   float *HF__RESTRICT oz,
                                   const hf__rope_step *st)
{
    const hf__pose_kernels *k = st->pose;
    for (; a < b; ++k) a = k->row(ro, j, a, b, fr, ox, oy, oz);
}

/* Animated ropes [a, b): rest pose carried by the current frame; previous
   positions one sub-step back, so that switching to simulation continues
   the rigid motion's velocity. */
HF__PRIVATE void hf__ropes_animated_run(hf_ropes *ro, int a, int b,
                                        const hf__rope_step *st)
{
    size_t R = (size_t)ro->rope_count;
    float *F = HF__ROW(ro->scratch, HF__RS_F, R),
          *G = HF__ROW(ro->scratch, HF__RS_G, R);
    float back = (float)(st->n - 1) / (float)st->n, f[12];
    int r, j, k;
    for (r = a; r < b; ++r) {
        hf__rope_frame_at(ro, r, 1.0f, f);
        for (k = 0; k < 12; ++k) F[(size_t)k * R + r] = f[k];
        hf__rope_frame_at(ro, r, back, f);
        for (k = 0; k < 12; ++k) G[(size_t)k * R + r] = f[k];
        ro->last_h[r] = st->h;
        ro->time[r] += (double)st->h * st->n;
    }
    for (j = 0; j < ro->points; ++j) {
        hf__rope_pose_row(ro, j, a, b, F, HF__ROW(ro->x, j, R),
                          HF__ROW(ro->y, j, R), HF__ROW(ro->z, j, R), st);
        hf__rope_pose_row(ro, j, a, b, G, HF__ROW(ro->px, j, R),
                          HF__ROW(ro->py, j, R), HF__ROW(ro->pz, j, R), st);
    }
}

/* Collider c of the call's array `col`, prepared. */
HF__PRIVATE hf__col_prep hf__collider_prep(const hf_collider *col, int id,
                                           float margin)
{
    const hf_collider *c = col + id;
    hf__col_prep k;
    int i;
    float l2;
    for (i = 0; i < 3; ++i) {
        k.a[i] = c->a[i];
        k.e[i] = c->type == HF_COLLIDER_CAPSULE ? c->b[i] - c->a[i] : 0.0f;
    }
    l2 = k.e[0] * k.e[0] + k.e[1] * k.e[1] + k.e[2] * k.e[2];
    k.inv = l2 > 1e-20f ? 1.0f / l2 : 0.0f;
    k.rr = c->radius + margin;
    k.inner = c->radius * 0.9999f - margin - 1e-6f;
    k.ball = (0.5f * HF_SQRTF(l2) + k.rr) * 1.001f + 1e-6f;
    k.id = id;
    k.row = 0; /* any row, the root's included: the broadphase narrows it */
    return k;
}

/* The point c of the collider's axis closest to (x, y, z) (the centre a
   for a point axis: a sphere, or a capsule of zero length), and the offset
   d = p - c; returns |d|^2. One definition for every collision kernel, so
   they agree to the bit. */
HF__PRIVATE float hf__col_closest(const hf__col_prep *k, float x, float y,
                                  float z, float *c, float *d)
{
    if (k->e[0] == 0.0f && k->e[1] == 0.0f && k->e[2] == 0.0f) {
        c[0] = k->a[0];
        c[1] = k->a[1];
        c[2] = k->a[2];
    } else {
        float t = ((x - k->a[0]) * k->e[0] + (y - k->a[1]) * k->e[1] +
                   (z - k->a[2]) * k->e[2]) *
                  k->inv;
        t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
        c[0] = k->a[0] + k->e[0] * t;
        c[1] = k->a[1] + k->e[1] * t;
        c[2] = k->a[2] + k->e[2] * t;
    }
    d[0] = x - c[0];
    d[1] = y - c[1];
    d[2] = z - c[2];
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

/* A point inside the collider goes straight out to its surface: along
   the offset from the closest axis point, or at the very axis along the
   root normal n (any fixed choice; this one is the rope's). */
HF__PRIVATE void hf__col_push_out(const hf__col_prep *k, float *x, float *y,
                                  float *z, float nx, float ny, float nz)
{
    float c[3], d[3];
    const float d2 = hf__col_closest(k, *x, *y, *z, c, d), rr = k->rr;
    if (!(d2 < rr * rr)) return;
    if (d2 > 1e-24f) {
        const float s = rr / HF_SQRTF(d2);
        *x = c[0] + d[0] * s;
        *y = c[1] + d[1] * s;
        *z = c[2] + d[2] * s;
    } else {
        *x = c[0] + nx * rr;
        *y = c[1] + ny * rr;
        *z = c[2] + nz * rr;
    }
}

/* Follow-the-leader collisions: a point inside a collider turns about its
   parent, keeping its distance L, onto the nearest direction that clears
   every collider. Against the ball of radius rr around a point c (the
   closest axis point to the child), with m = (p - c) / |p - c| and
   rho = |p - c|, the child p + L d is outside iff
       d . m >= (rr^2 - rho^2 - L^2) / (2 L rho) = cmin,
   so d is turned onto the cone d . m = cmin. A capsule is the union of
   such balls along its axis: the turn is repeated with the new closest
   point, collider after collider, until no collider holds the point
   (HF__FTL_ROUNDS at most). Where no direction clears them all
   (overlapping proxies, a pinched gap) the length is kept and the
   direction seen with the least penetration wins. A collider that holds
   the rope's root is, for that rope, shrunk to the root's distance from
   its axis, so a root inside a proxy neither stretches nor throws its
   rope. */
#define HF__FTL_ROUNDS 8
#define HF__FTL_QUICK 8

/* The radius collider k has for a rope whose root is at `root`: rr, or
   the root's distance from the axis where the root is more than the
   margin inside the collider. */
HF__PRIVATE float hf__col_radius_for(const hf__col_prep *k, const float *root)
{
    float c[3], d[3];
    const float d2 = hf__col_closest(k, root[0], root[1], root[2], c, d);
    return k->inner > 0.0f && d2 < k->inner * k->inner ? HF_SQRTF(d2) : k->rr;
}

/* The cap of directions d that the ball (c, rr) forbids to a child at
   distance l from parent p: d . m < cmin (see above). A parent on the
   axis takes the root normal n for m. */
HF__PRIVATE void hf__ftl_cap(const float *p, float l, const float *c, float rr,
                             const float *n, float *m, float *cmin)
{
    float rho2, rho;
    int k;
    for (k = 0; k < 3; ++k) m[k] = p[k] - c[k];
    rho2 = hf__dot3(m, m);
    if (rho2 > 1e-24f) {
        rho = HF_SQRTF(rho2);
        for (k = 0; k < 3; ++k) m[k] /= rho;
    } else {
        rho = 0.0f;
        for (k = 0; k < 3; ++k) m[k] = n[k];
    }
    /* aim a hair outside the ball, so rounding does not leave the point a
       float step inside */
    rr += 1e-6f * (rr + l);
    *cmin = rho > 0.0f ? (rr * rr - rho * rho - l * l) / (2.0f * l * rho)
                       : 1.0f;
    *cmin = *cmin > 1.0f ? 1.0f : (*cmin < -1.0f ? -1.0f : *cmin);
}

/* v minus its component along unit m, twice (a v that is mostly
   rounding noise keeps a tilt after one pass); returns |v|^2. */
HF__PRIVATE float hf__perp_part(float *v, const float *m)
{
    int pass, k;
    for (pass = 0; pass < 2; ++pass) {
        const float vm = hf__dot3(v, m);
        for (k = 0; k < 3; ++k) v[k] -= m[k] * vm;
    }
    return hf__dot3(v, v);
}

/* A fixed perpendicular of unit m: m crossed with the axis least aligned
   with it, in v; returns |v|^2. */
HF__PRIVATE float hf__perp_fixed(const float *m, float *v)
{
    const float ax = HF_FABS(m[0]), ay = HF_FABS(m[1]), az = HF_FABS(m[2]);
    float e[3] = {0.0f, 0.0f, 0.0f};
    e[(ax <= ay && ax <= az) ? 0 : (ay <= az ? 1 : 2)] = 1.0f;
    hf__cross3(v, m, e);
    return hf__perp_part(v, m);
}

/* The unit direction nearest u on the cap's edge d . m = cmin: u's
   sideways part kept; where u has none (to 1e-4), the root tangent t's;
   where t has none either, a fixed perpendicular of m. */
HF__PRIVATE void hf__ftl_onto_cap(const float *u, const float *m, float cmin,
                                  const float *t, float *d)
{
    float v[3], v2, s;
    int k;
    for (k = 0; k < 3; ++k) v[k] = u[k];
    v2 = hf__perp_part(v, m);
    if (v2 < 1e-8f) {
        for (k = 0; k < 3; ++k) v[k] = t[k];
        v2 = hf__perp_part(v, m);
        if (v2 < 1e-8f) v2 = hf__perp_fixed(m, v);
    }
    s = HF_SQRTF(1.0f - cmin * cmin) / HF_SQRTF(v2);
    for (k = 0; k < 3; ++k) d[k] = m[k] * cmin + v[k] * s;
}

/* Where the edges of two caps cross: up to two unit directions d with
   d . m1 = c1 and d . m2 = c2. Returns how many. */
HF__PRIVATE int hf__ftl_cap_pair(const float *m1, float c1, const float *m2,
                                 float c2, float *d)
{
    const float mu = hf__dot3(m1, m2), det = 1.0f - mu * mu;
    float x[3], al, be, g2, h2;
    int k;
    if (!(det > 1e-8f)) return 0;
    al = (c1 - mu * c2) / det;
    be = (c2 - mu * c1) / det;
    hf__cross3(x, m1, m2);
    h2 = al * al + be * be + 2.0f * al * be * mu;
    g2 = (1.0f - h2) / det;
    if (!(g2 >= 0.0f)) return 0;
    g2 = HF_SQRTF(g2);
    for (k = 0; k < 3; ++k) {
        d[k] = al * m1[k] + be * m2[k] + g2 * x[k];
        d[3 + k] = al * m1[k] + be * m2[k] - g2 * x[k];
    }
    /* unit again: near-parallel edges lose bits in al and be, and the
       child must stay exactly l from its parent */
    for (k = 0; k < 2; ++k) {
        float *dk = d + 3 * k, n2 = hf__dot3(dk, dk);
        if (!(n2 > 0.25f && n2 < 4.0f)) return 0;
        n2 = 1.0f / HF_SQRTF(n2);
        dk[0] *= n2;
        dk[1] *= n2;
        dk[2] *= n2;
    }
    return 2;
}

/* Of two crossings d[0..5], the one on the side of the point's last
   place (v: that place minus the parent) first in d, and how many to try:
   1, or 2 where v is square to the crease (both, in order). */
HF__PRIVATE int hf__ftl_last_side(float *d, const float *v)
{
    float dd[3], s;
    int w;
    for (w = 0; w < 3; ++w) dd[w] = d[w] - d[3 + w];
    s = hf__dot3(dd, v);
    if (s < 0.0f) {
        for (w = 0; w < 3; ++w) d[w] = d[3 + w];
        return 1;
    }
    return s > 0.0f ? 1 : 2;
}

/* The deepest penetration of q into the colliders (radii for this rope),
   0 when outside all; *deepest: that collider, -1 when none. */
HF__PRIVATE float hf__ftl_penetration(const hf__col_prep *k, const float *rr,
                                      int ncol, const float *q, int *deepest)
{
    float worst = 0.0f;
    int c;
    *deepest = -1;
    for (c = 0; c < ncol; ++c) {
        float cc[3], dd[3];
        const float d2 = hf__col_closest(k + c, q[0], q[1], q[2], cc, dd);
        if (d2 < rr[c] * rr[c]) {
            const float pen = rr[c] - HF_SQRTF(d2);
            if (*deepest < 0 || pen > worst) {
                worst = pen;
                *deepest = c;
            }
        }
    }
    return worst;
}

/* One point after its FTL placement, against colliders k[0 .. ncol) (at
   most HF__FTL_NEAR, the ones relevant to it: hf__ftl_collide_one walks
   longer lists in batches). Each round makes the caps of the colliders near the best
   point so far (a capsule's from its axis point closest to that point),
   then tries every direction that can be nearest and clear: u turned
   onto each cap's edge, and the crossings of every two edges; the one
   with the least penetration, then the nearest to u, wins. Two edges
   cross either way along the crease of their colliders: the rounds
   first try only the crossing on the side of the point's last place
   (v: that place minus the parent; both where v is square to the
   crease), and only where that leaves the point inside do they run
   again with both. Where u points straight into a crease the two are
   equally near it, and a choice made by rounding flipped the point
   about its parent to the crease's other end, step after step. */
HF__PRIVATE void hf__ftl_collide_point(float *x, float *y, float *z,
                                       const float *p, float l,
                                       const float *root, const float *n,
                                       const float *t, const float *v,
                                       const hf__col_prep *k, int ncol)
{
    float q[3], best[3], u[3], rr[HF__FTL_NEAR];
    float m[2 * HF__FTL_NEAR][3], cmin[2 * HF__FTL_NEAR], best_pen, best_dot;
    int c, e, round, deepest, ncap, pass, phase;
    q[0] = *x;
    q[1] = *y;
    q[2] = *z;
    for (c = 0; c < ncol; ++c) rr[c] = hf__col_radius_for(k + c, root);
    best_pen = hf__ftl_penetration(k, rr, ncol, q, &deepest);
    if (deepest < 0 || !(l > 0.0f)) return; /* outside; or a zero segment */
    for (c = 0; c < 3; ++c) u[c] = q[c] - p[c];
    best_dot = hf__dot3(u, u);
    if (best_dot > 1e-24f) {
        best_dot = 1.0f / HF_SQRTF(best_dot);
        for (c = 0; c < 3; ++c) u[c] *= best_dot;
    } else {
        for (c = 0; c < 3; ++c) u[c] = n[c];
    }
    HF_MEMCPY(best, q, sizeof q);
    best_dot = -2.0f;
    {
        /* the quick answer: out of the deepest collider's ball about its
           axis point nearest q, onto the edge of that ball's cap nearest
           u. Every direction that clears the colliders lies outside that
           ball, so where this one clears them all, no other is nearer u
           and the rounds are not needed (half the contacts end here).
           Where the point is still inside (a capsule's next ball along
           its axis, most often), the same again from there, at most
           HF__FTL_QUICK times, before the rounds; but only out of the
           same collider. Where the way out of one ends inside another,
           the point is in their crease: it goes where the edges of the
           two balls cross, on the side of its last place (as in the
           rounds); where that is inside one of the two further along,
           the same from their balls nearest it (walking along the
           crease), at most HF__FTL_QUICK times; where a third holds it,
           or the edges do not cross, the rounds decide. Ways out of each
           in turn had left it on either side of the crease, one side a
           step, and a rope lying along a crease zigzagged across it for
           ever. */
        float from[3], at[3], cc[3], dd[3], mq[3], cq, d[3], cand[3];
        int w, it, was, dq = deepest;
        HF_MEMCPY(from, u, sizeof from);
        HF_MEMCPY(at, q, sizeof at);
        for (it = 0; it < HF__FTL_QUICK; ++it) {
            hf__col_closest(k + dq, at[0], at[1], at[2], cc, dd);
            hf__ftl_cap(p, l, cc, rr[dq], n, mq, &cq);
            hf__ftl_onto_cap(from, mq, cq, t, d);
            for (w = 0; w < 3; ++w) cand[w] = p[w] + l * d[w];
            was = dq;
            if (!(hf__ftl_penetration(k, rr, ncol, cand, &dq) > 0.0f)) {
                HF_MEMCPY(best, cand, sizeof cand);
                best_pen = 0.0f;
                break;
            }
            if (dq != was) { /* a crease: along it */
                const int ca = was, cb = dq;
                float m2[3], c2, d2[6];
                int nd, i, walk;
                hf__col_closest(k + cb, cand[0], cand[1], cand[2], cc, dd);
                hf__ftl_cap(p, l, cc, rr[cb], n, m2, &c2);
                for (walk = 0; walk < HF__FTL_QUICK; ++walk) {
                    nd = hf__ftl_cap_pair(mq, cq, m2, c2, d2);
                    if (nd != 2) break;
                    nd = hf__ftl_last_side(d2, v);
                    for (i = 0; i < nd; ++i) {
                        for (w = 0; w < 3; ++w)
                            cand[w] = p[w] + l * d2[3 * i + w];
                        if (!(hf__ftl_penetration(k, rr, ncol, cand, &dq) >
                              0.0f)) {
                            HF_MEMCPY(best, cand, sizeof cand);
                            best_pen = 0.0f;
                            break;
                        }
                    }
                    /* done, both tried, or held by a third: the rounds */
                    if (i < nd || nd == 2 || (dq != ca && dq != cb)) break;
                    /* inside one of the two further along: their balls
                       nearest the crossing */
                    hf__col_closest(k + ca, cand[0], cand[1], cand[2], cc, dd);
                    hf__ftl_cap(p, l, cc, rr[ca], n, mq, &cq);
                    hf__col_closest(k + cb, cand[0], cand[1], cand[2], cc, dd);
                    hf__ftl_cap(p, l, cc, rr[cb], n, m2, &c2);
                }
                break;
            }
            HF_MEMCPY(from, d, sizeof d);
            HF_MEMCPY(at, cand, sizeof cand);
        }
    }
    for (phase = 0; phase < 2 && best_pen > 0.0f; ++phase)
    for (round = 0; round < HF__FTL_ROUNDS && best_pen > 0.0f; ++round) {
        float from[3];
        const float pen0 = best_pen;
        /* the current best direction: turning it, not u, walks along a
           capsule instead of back into the part it left; in the first
           round the best is q itself, whose direction is u */
        for (c = 0; c < 3; ++c)
            from[c] = round == 0 ? u[c] : (best[c] - p[c]) / l;
        ncap = 0;
        for (c = 0; c < ncol; ++c) {
            float cc[3], dd[3];
            hf__col_closest(k + c, best[0], best[1], best[2], cc, dd);
            hf__ftl_cap(p, l, cc, rr[c], n, m[ncap], &cmin[ncap]);
            ++ncap;
            if (k[c].inv > 0.0f) {
                /* a capsule: also the ball at the axis point nearest the
                   parent, the one that bounds a child close to it */
                hf__col_closest(k + c, p[0], p[1], p[2], cc, dd);
                hf__ftl_cap(p, l, cc, rr[c], n, m[ncap], &cmin[ncap]);
                ++ncap;
            }
        }
        for (pass = 0; pass < 2; ++pass) {
            /* the projections onto every edge; the crossings of two only
               where none of them clears every collider */
            if (pass == 1 && !(best_pen > 0.0f)) break;
            for (c = 0; c < ncap; ++c)
            for (e = pass ? c + 1 : c; e < (pass ? ncap : c + 1); ++e) {
                float d[6];
                int nd, i, w;
                if (e == c) { /* from, and u where it differs */
                    hf__ftl_onto_cap(from, m[c], cmin[c], t, d);
                    nd = 1;
                    if (round > 0) {
                        hf__ftl_onto_cap(u, m[c], cmin[c], t, d + 3);
                        nd = 2;
                    }
                } else {
                    nd = hf__ftl_cap_pair(m[c], cmin[c], m[e], cmin[e], d);
                    if (nd == 2 && phase == 0) nd = hf__ftl_last_side(d, v);
                }
                for (i = 0; i < nd; ++i) {
                    float cand[3], pen, dot;
                    for (w = 0; w < 3; ++w) cand[w] = p[w] + l * d[3 * i + w];
                    pen = hf__ftl_penetration(k, rr, ncol, cand, &deepest);
                    dot = hf__dot3(d + 3 * i, u);
                    if (pen < best_pen || (pen == best_pen && dot > best_dot)) {
                        best_pen = pen;
                        best_dot = dot;
                        HF_MEMCPY(best, cand, sizeof cand);
                    }
                }
            }
        }
        if (!(best_pen < pen0)) break; /* no progress */
    }
    *x = best[0];
    *y = best[1];
    *z = best[2];
}

/* Whether collider k can matter to a child at distance l from its
   parent p: the parent nearer its axis than rr + l, with 1e-4 of that to
   spare so that rounding never decides it. A collider that is not
   relevant can neither hold the child nor bound a direction it may take,
   so the contact kernels resolve a point against the relevant ones alone,
   in the order of the call's array, and any list that holds those (a
   tile's, a group's, the whole array) gives the same bytes. The SIMD
   kernels compute it with the same operations. */
HF__INLINE int hf__ftl_relevant(const hf__col_prep *k, const float *p, float l)
{
    float c[3], d[3], lim;
    const float d2 = hf__col_closest(k, p[0], p[1], p[2], c, d);
    lim = k->rr + l;
    lim = lim + 1e-4f * lim;
    return d2 < lim * lim;
}

/* ---- 6.5 the broadphase ------------------------------------------------- */

/* Ropes are simulated in chunks of up to HF__BP_TILES tiles of
   HF__BP_TILE neighbouring ropes, each chunk taking every sub-step before
   the next (which also keeps a chunk's rows in the core's own cache, and
   two threads' neighbouring ranges apart in time). Before its sub-steps a
   chunk learns which colliders each tile can touch this call: a rope
   point cannot leave the ball of the rope's rest length so far (row by
   row) around its root, and the root moves between the last frame's
   place and this one's, so a collider whose box (grown by radius and
   margin) is farther from the box of the tile's roots than that is kept
   out of the tile's list; one that is nearer is kept, with the first
   point row that can reach it. Contact tests then see only the tile's
   colliders that the row reaches. The cost: a box test per collider and
   chunk, one per candidate and tile, then per point the colliders its
   tile can reach; a collider far from every rope costs next to nothing.
   The tiles' prepared colliders share HF__BP_SLOTS slots; a chunk ends
   at the tile that does not fit, and a tile alone over them tests the
   whole array (exact, slower). */
#define HF__BP_TILE 16
#define HF__BP_TILES 16
#define HF__BP_SLOTS 160
#define HF__BP_CAND 128
#define HF__ROPE_CHUNK (HF__BP_TILES * HF__BP_TILE)

typedef struct hf__bp {
    int a;     /* the chunk's first rope: tile t is ropes a + 16 t .. */
    int tiles; /* tiles in the chunk */
    const hf_collider *col; /* the call's colliders */
    int ncol;
    float margin;
    int start[HF__BP_TILES + 1]; /* tile t: k[start[t] .. start[t + 1]) */
    unsigned char all[HF__BP_TILES]; /* 1: the whole array, prepared on use */
    hf__col_prep k[HF__BP_SLOTS];
    /* the union of the tiles' lists (hf__bp_union), in the array's order:
       k[u[i]], reached from row urow[i] on; where all[0], the array */
    int nu;
    short u[HF__BP_SLOTS], urow[HF__BP_SLOTS];
} hf__bp;

/* The colliders a tile may touch: n prepared ones from k, or, where k is
   NULL, the whole array raw[0 .. n), prepared on use. */
typedef struct hf__cols {
    const hf__col_prep *k;
    const hf_collider *raw;
    int n;
    float margin;
} hf__cols;

HF__INLINE void hf__bp_tile(const hf__bp *bp, int r, hf__cols *cl)
{
    const int t = (r - bp->a) / HF__BP_TILE;
    cl->margin = bp->margin;
    if (bp->all[t]) {
        cl->k = NULL;
        cl->raw = bp->col;
        cl->n = bp->ncol;
    } else {
        cl->k = bp->k + bp->start[t];
        cl->raw = NULL;
        cl->n = bp->start[t + 1] - bp->start[t];
    }
}

HF__INLINE const hf__col_prep *hf__cols_at(const hf__cols *cl, int i,
                                           hf__col_prep *spare)
{
    if (cl->k) return cl->k + i;
    *spare = hf__collider_prep(cl->raw, i, cl->margin);
    return spare;
}

/* Collider c's box, grown by its radius and margin (and 1e-3 of them). */
HF__INLINE void hf__col_box(const hf_collider *c, float margin, float *lo,
                            float *hi)
{
    const float g = (c->radius + margin) * 1.001f;
    int k;
    for (k = 0; k < 3; ++k) {
        const float b = c->type == HF_COLLIDER_CAPSULE ? c->b[k] : c->a[k];
        lo[k] = (c->a[k] < b ? c->a[k] : b) - g;
        hi[k] = (c->a[k] < b ? b : c->a[k]) + g;
    }
}

/* The distance between boxes (lo, hi) and (blo, bhi), 0 where they meet. */
HF__INLINE float hf__box_gap(const float *lo, const float *hi,
                             const float *blo, const float *bhi)
{
    float g2 = 0.0f;
    int k;
    for (k = 0; k < 3; ++k) {
        const float g = blo[k] > hi[k] ? blo[k] - hi[k]
                                       : (lo[k] > bhi[k] ? lo[k] - bhi[k]
                                                         : 0.0f);
        g2 += g * g;
    }
    return HF_SQRTF(g2);
}

/* Rope r's root's offset from its frame position (its rest row 0). */
HF__INLINE float hf__root_offset(const hf_ropes *ro, int r)
{
    const float u = ro->rest_u[r], v = ro->rest_v[r], w = ro->rest_w[r];
    return HF_SQRTF(u * u + v * v + w * w);
}

/* The index of x's lowest set bit (x != 0). */
HF__INLINE int hf__lowest_bit(unsigned x)
{
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctz(x);
#else
    int i = 0;
    for (; !(x & 1u); x >>= 1) ++i;
    return i;
#endif
}

#if HF__V4
/* The least of x and v's four lanes (greatest: the greatest), compared
   as the scalar loops compare: the same float whatever the order */
HF__INLINE float hf__v4_fold(hf__v4 v, float x, int greatest)
{
    float g[4];
    int i;
    HF__ST(g, v);
    for (i = 0; i < 4; ++i)
        x = greatest ? (g[i] > x ? g[i] : x) : (g[i] < x ? g[i] : x);
    return x;
}
#endif

/* Tile [x, e): the box of its roots over the call (the frame position
   this frame and last, between which the sub-steps move it, and where
   the root is now), and how far
   a point can be from it: reach[0] for the root, reach[1] for row 1 and
   reach[2] for the tip (the root's rest offset plus the rest lengths
   before the row, the most of any rope of the tile, grown by 1e-3 and by
   1e-4 of the coordinates, for rounding: hf__bp_reach); m: the largest
   root offset, segment and rope (offset plus length), for the rows
   between (hf__bp_reach). */
HF__PRIVATE void hf__bp_tile_box(const hf_ropes *ro, int x, int e, float *lo,
                                 float *hi, float *big, float *reach, float *m)
{
    const size_t R = (size_t)ro->rope_count;
    float m0 = 0.0f, m1 = 0.0f, mt = 0.0f, ms = 0.0f;
    int r, k;
    *big = 0.0f;
    for (k = 0; k < 3; ++k) lo[k] = hi[k] = ro->frame[(size_t)k * R + x];
    r = x;
#if HF__V4
    if (e - x >= 4) { /* four ropes a lane: the same minima and maxima */
        hf__v4 vlo[3], vhi[3], v0 = HF__SET1(0.0f), v1 = v0, vt = v0, vs = v0;
        for (k = 0; k < 3; ++k) vlo[k] = vhi[k] = HF__SET1(lo[k]);
        for (; r + 4 <= e; r += 4) {
            const hf__v4 u = HF__LD(ro->rest_u + r), v = HF__LD(ro->rest_v + r),
                         w = HF__LD(ro->rest_w + r),
                         o = HF__SQRT(HF__ADD(
                             HF__ADD(HF__MUL(u, u), HF__MUL(v, v)),
                             HF__MUL(w, w)));
            HF__UNROLL for (k = 0; k < 3; ++k) {
                const hf__v4 c = HF__LD(ro->frame + (size_t)k * R + r),
                             pv = HF__LD(ro->frame + (size_t)(12 + k) * R + r),
                             q = HF__LD((k == 0   ? ro->x
                                         : k == 1 ? ro->y
                                                  : ro->z) +
                                        r);
                vlo[k] = HF__SEL(HF__LT(c, vlo[k]), c, vlo[k]);
                vhi[k] = HF__SEL(HF__GT(c, vhi[k]), c, vhi[k]);
                vlo[k] = HF__SEL(HF__LT(pv, vlo[k]), pv, vlo[k]);
                vhi[k] = HF__SEL(HF__GT(pv, vhi[k]), pv, vhi[k]);
                vlo[k] = HF__SEL(HF__LT(q, vlo[k]), q, vlo[k]);
                vhi[k] = HF__SEL(HF__GT(q, vhi[k]), q, vhi[k]);
            }
            v0 = HF__MAX(o, v0);
            v1 = HF__MAX(HF__ADD(o, HF__LD(ro->rest_length + r)), v1);
            vt = HF__MAX(HF__ADD(o, HF__LD(ro->length + r)), vt);
            vs = HF__MAX(HF__LD(ro->longest + r), vs);
        }
        for (k = 0; k < 3; ++k) {
            lo[k] = hf__v4_fold(vlo[k], lo[k], 0);
            hi[k] = hf__v4_fold(vhi[k], hi[k], 1);
        }
        m0 = hf__v4_fold(v0, m0, 1);
        m1 = hf__v4_fold(v1, m1, 1);
        mt = hf__v4_fold(vt, mt, 1);
        ms = hf__v4_fold(vs, ms, 1);
    }
#endif
    for (; r < e; ++r) {
        const float o = hf__root_offset(ro, r);
        for (k = 0; k < 3; ++k) {
            const float c = ro->frame[(size_t)k * R + r],
                        p = ro->frame[(size_t)(12 + k) * R + r];
            lo[k] = c < lo[k] ? c : lo[k];
            hi[k] = c > hi[k] ? c : hi[k];
            lo[k] = p < lo[k] ? p : lo[k];
            hi[k] = p > hi[k] ? p : hi[k];
        }
        for (k = 0; k < 3; ++k) { /* where the root is: a rope that glides
                                     or is animated need not be at its
                                     frame, and hf__ropes_mark_roots
                                     tests it there */
            const float q = (k == 0 ? ro->x : k == 1 ? ro->y : ro->z)[r];
            lo[k] = q < lo[k] ? q : lo[k];
            hi[k] = q > hi[k] ? q : hi[k];
        }
        m0 = o > m0 ? o : m0;
        m1 = o + ro->rest_length[r] > m1 ? o + ro->rest_length[r] : m1;
        mt = o + ro->length[r] > mt ? o + ro->length[r] : mt;
        ms = ro->longest[r] > ms ? ro->longest[r] : ms;
    }
    for (k = 0; k < 3; ++k) {
        const float a = HF_FABS(lo[k]) > HF_FABS(hi[k]) ? HF_FABS(lo[k])
                                                        : HF_FABS(hi[k]);
        *big = a > *big ? a : *big;
    }
    /* the tip's bound from the ropes' lengths: their sums of the same
       rest lengths in the same order, so the same floats as row P - 1's */
    reach[0] = m0 * 1.001f + 1e-4f * (1.0f + *big + m0);
    reach[1] = m1 * 1.001f + 1e-4f * (1.0f + *big + m1);
    reach[2] = mt * 1.001f + 1e-4f * (1.0f + *big + mt);
    m[0] = m0;
    m[1] = ms;
    m[2] = mt;
}

/* reach[j] for every row j of a tile: at most its largest root offset
   plus j of its longest segments, and at most its longest rope (m, from
   hf__bp_tile_box), grown as hf__bp_tile_box's bounds. A bound from three
   numbers, where the rows' own sums would read every row of the tile's
   rest lengths, a cache miss each. */
HF__PRIVATE void hf__bp_reach(const float *m, int points, float big,
                              float *reach)
{
    int j;
    for (j = 0; j < points; ++j) {
        float c = m[0] + (float)j * m[1];
        c = c < m[2] ? c : m[2];
        reach[j] = c * 1.001f + 1e-4f * (1.0f + big + c);
    }
}

/* The tile lists of the chunk that starts at rope a (of a run that ends
   at b): fills bp, returns where the chunk ends. */
HF__PRIVATE int hf__bp_lists(const hf_ropes *ro, int a, int b,
                             const hf_collider *col, int ncol, float margin,
                             hf__bp *bp)
{
    float tlo[HF__BP_TILES][3], thi[HF__BP_TILES][3], tr[HF__BP_TILES][3],
        tm[HF__BP_TILES][3];
    float big[HF__BP_TILES], reach[HF_MAX_POINTS];
    float clo[3], chi[3], box[HF__BP_CAND][6];
    int cand[HF__BP_CAND], slot[HF__BP_CAND], nc = 0, t, x, e, c, k, n = 0;
    bp->a = a;
    bp->col = col;
    bp->ncol = ncol;
    bp->margin = margin;
    /* the chunk's tiles and their reach, then the colliders near any */
    for (t = 0, x = a; t < HF__BP_TILES && x < b; ++t, x = e) {
        e = b - x > HF__BP_TILE ? x + HF__BP_TILE : b;
        hf__bp_tile_box(ro, x, e, tlo[t], thi[t], &big[t], tr[t], tm[t]);
        for (k = 0; k < 3; ++k) {
            clo[k] = t == 0 || tlo[t][k] - tr[t][2] < clo[k]
                         ? tlo[t][k] - tr[t][2]
                         : clo[k];
            chi[k] = t == 0 || thi[t][k] + tr[t][2] > chi[k]
                         ? thi[t][k] + tr[t][2]
                         : chi[k];
        }
    }
    bp->tiles = t;
    /* the candidates and their boxes, once for every tile */
    for (c = 0; c < ncol && nc <= HF__BP_CAND; ++c) {
        float lo[3], hi[3];
        hf__col_box(col + c, margin, lo, hi);
        if (hf__box_gap(clo, chi, lo, hi) > 0.0f) continue;
        if (nc < HF__BP_CAND) {
            cand[nc] = c;
            slot[nc] = -1; /* prepared in no tile yet */
            for (k = 0; k < 3; ++k) {
                box[nc][k] = lo[k];
                box[nc][3 + k] = hi[k];
            }
        }
        ++nc; /* HF__BP_CAND + 1: too many, every tile tests them all */
    }
    for (t = 0, x = a; t < bp->tiles; ++t, x += HF__BP_TILE) {
        const int m = nc > HF__BP_CAND ? ncol : nc;
        int i, got = 0;
        bp->start[t] = n;
        bp->all[t] = 0;
        for (i = 0; i < m; ++i) {
            float lo[3], hi[3], gap;
            int j = 1;
            if (nc > HF__BP_CAND) {
                c = i;
                hf__col_box(col + c, margin, lo, hi);
            } else {
                c = cand[i];
                for (k = 0; k < 3; ++k) {
                    lo[k] = box[i][k];
                    hi[k] = box[i][3 + k];
                }
            }
            gap = hf__box_gap(tlo[t], thi[t], lo, hi);
            if (!(gap < tr[t][2])) continue;
            if (n == HF__BP_SLOTS) break;
            if (gap < tr[t][0]) /* a root may sit inside */
                j = 0;
            else if (!(gap < tr[t][1])) { /* beyond row 1: which row */
                if (!got) {
                    hf__bp_reach(tm[t], ro->points, big[t], reach);
                    got = 1;
                }
                /* the first row that reaches it: reach grows row by row */
                {
                    int hi = ro->points - 1;
                    while (j < hi) {
                        const int mid = j + (hi - j) / 2;
                        if (gap < reach[mid])
                            hi = mid;
                        else
                            j = mid + 1;
                    }
                }
            }
            if (nc > HF__BP_CAND) {
                bp->k[n] = hf__collider_prep(col, c, margin);
            } else { /* prepared once, copied to the next tiles */
                if (slot[i] < 0)
                    bp->k[n] = hf__collider_prep(col, c, margin);
                else
                    bp->k[n] = bp->k[slot[i]];
                slot[i] = n;
            }
            bp->k[n++].row = j;
        }
        if (i < m) { /* out of slots */
            if (t > 0) { /* the chunk ends before this tile */
                bp->tiles = t;
                return x;
            }
            bp->all[0] = 1;
            bp->start[1] = 0;
            bp->tiles = 1;
            return b - a > HF__BP_TILE ? a + HF__BP_TILE : b;
        }
        bp->start[t + 1] = n;
    }
    return b - a > bp->tiles * HF__BP_TILE ? a + bp->tiles * HF__BP_TILE : b;
}

/* The union of the chunk's tile lists, each in the array's order, by
   merging them: every collider once, with the least row of its tiles.
   A row's contacts (hf__ftl_flush) test it once for all their tiles. */
HF__PRIVATE void hf__bp_union(hf__bp *bp)
{
    int pos[HF__BP_TILES], t, n = 0;
    bp->nu = bp->ncol;
    if (bp->all[0]) return;
    for (t = 0; t < bp->tiles; ++t) pos[t] = bp->start[t];
    for (;;) {
        int id = -1, row = 0, at = 0;
        for (t = 0; t < bp->tiles; ++t) {
            const hf__col_prep *k = bp->k + pos[t];
            if (pos[t] == bp->start[t + 1]) continue;
            if (id < 0 || k->id < id) {
                id = k->id;
                row = k->row;
                at = pos[t];
            } else if (k->id == id && k->row < row) {
                row = k->row;
            }
        }
        if (id < 0) break;
        for (t = 0; t < bp->tiles; ++t)
            if (pos[t] < bp->start[t + 1] && bp->k[pos[t]].id == id) ++pos[t];
        bp->u[n] = (short)at;
        bp->urow[n++] = (short)row;
    }
    bp->nu = n;
}

/* Collider i of the chunk's union (its row: hf__bp_union_row). */
HF__INLINE const hf__col_prep *hf__bp_union_at(const hf__bp *bp, int i,
                                               hf__col_prep *spare)
{
    if (!bp->all[0]) return bp->k + bp->u[i];
    *spare = hf__collider_prep(bp->col, i, bp->margin);
    return spare;
}

/* The first row that reaches collider i of the union: its tiles' least. */
HF__INLINE int hf__bp_union_row(const hf__bp *bp, int i)
{
    return bp->all[0] ? 0 : bp->urow[i];
}

/* The broadphase of the chunk that starts at rope a (of a run that ends
   at b): its tile lists and their union; returns where the chunk ends. */
HF__PRIVATE int hf__bp_build(const hf_ropes *ro, int a, int b,
                             const hf_collider *col, int ncol, float margin,
                             hf__bp *bp)
{
    const int e = hf__bp_lists(ro, a, b, col, ncol, margin, bp);
    hf__bp_union(bp);
    return e;
}

/* root_inside of the chunk's ropes [a, b) after its step: whether the
   root sits inside one of its tile's colliders (deeper than the margin
   below its surface), which is when the collisions shrink that collider
   for the rope. A collider that holds a root is always in its tile's
   list, at row 0 (the rest cannot reach a root). */
HF__PRIVATE void hf__ropes_mark_roots(hf_ropes *ro, int a, int b,
                                      const hf__bp *bp)
{
    hf__cols cl;
    hf__col_prep spare;
    int r, i;
    for (r = a; r < b; ++r) {
        const float root[3] = {ro->x[r], ro->y[r], ro->z[r]};
        ro->root_inside[r] = 0;
        if (!bp) continue;
        hf__bp_tile(bp, r, &cl);
        for (i = 0; i < cl.n; ++i) {
            const hf__col_prep *k = hf__cols_at(&cl, i, &spare);
            if (k->row > 0) continue;
            if (hf__col_radius_for(k, root) < k->rr) {
                ro->root_inside[r] = 1;
                break;
            }
        }
    }
}

/* Point row j (>= 1) of rope r right after its FTL placement, against the
   colliders of its tile list that are relevant to it, HF__FTL_NEAR at a
   time: with more, the batches are walked again until a walk moves
   nothing (a turn out of a later batch can land in an earlier one). */
HF__PRIVATE void hf__ftl_collide_one(hf_ropes *ro, const float *F, int j,
                                     int r, const hf__cols *cl)
{
    const size_t R = (size_t)ro->rope_count;
    const size_t o = (size_t)j * R + (size_t)r, o0 = o - R;
    const float p[3] = {ro->x[o0], ro->y[o0], ro->z[o0]};
    const float root[3] = {ro->x[r], ro->y[r], ro->z[r]};
    const float n[3] = {F[6 * R + r], F[7 * R + r], F[8 * R + r]};
    const float t[3] = {F[3 * R + r], F[4 * R + r], F[5 * R + r]};
    const float l = ro->rest_length[o0];
    const float v[3] = {ro->px[o] - p[0], ro->py[o] - p[1], ro->pz[o] - p[2]};
    hf__col_prep near_[HF__FTL_NEAR], spare;
    int i, nn, walk, more;
    for (walk = 0; walk < HF__FTL_ROUNDS; ++walk) {
        const float before[3] = {ro->x[o], ro->y[o], ro->z[o]};
        nn = more = 0;
        for (i = 0; i < cl->n; ++i) {
            const hf__col_prep *k = hf__cols_at(cl, i, &spare);
            if (k->row > j || !hf__ftl_relevant(k, p, l)) continue;
            if (nn == HF__FTL_NEAR) {
                hf__ftl_collide_point(ro->x + o, ro->y + o, ro->z + o, p, l,
                                      root, n, t, v, near_, nn);
                nn = 0;
                more = 1;
            }
            near_[nn++] = *k;
        }
        if (nn)
            hf__ftl_collide_point(ro->x + o, ro->y + o, ro->z + o, p, l, root,
                                  n, t, v, near_, nn);
        if (!more || (ro->x[o] == before[0] && ro->y[o] == before[1] &&
                      ro->z[o] == before[2]))
            break;
    }
}

/* Every collider against point row j (>= 1) of ropes [a, b) right after
   an FTL placement; F: the frame rows of the sub-step. */
HF__PRIVATE void hf__ropes_collide_ftl_row(hf_ropes *ro, const float *F,
                                           int j, int a, int b,
                                           const hf__bp *bp)
{
    hf__cols cl;
    int r;
    for (r = a; r < b; ++r) {
        hf__bp_tile(bp, r, &cl);
        hf__ftl_collide_one(ro, F, j, r, &cl);
    }
}

/* The distance solver's collisions (after each pass): every point of
   ropes [a, b) pushed straight out of each collider in turn, with the
   sub-step's kernels k (hf__rope_widths). */
HF__PRIVATE void hf__ropes_collide(hf_ropes *ro, const float *F, int a, int b,
                                   const hf__bp *bp,
                                   const struct hf__rope_rows *k);

/* Ropes [a, b) gliding from simulation to animation: kinematic, no
   constraints, no colliders. In root-frame coordinates each point follows
   the cubic Hermite curve from the pose and velocity it had at the switch
   to its rest place, reached at rest (moving with the frame) after
   blend_time: no jump in position or velocity at either end. A blend of
   two poses is shorter than either, so the rope is rebuilt from the root
   out along the curve's segments at their rest lengths; the curve is a
   function of time alone, so that keeps it smooth (for poses less than a
   half turn apart: a rope exactly reversed has no smooth way round). At
   w = 1 the rope is exactly animated. x and px stay world positions (px
   the last sub-step's place), so switching back to simulation mid-glide
   keeps the velocity. */
HF__PRIVATE void hf__ropes_safety_net(hf_ropes *ro, int a, int b,
                                      const hf__rope_step *st);

HF__PRIVATE void hf__ropes_glide_run(hf_ropes *ro, int a, int b,
                                     const hf__rope_step *st)
{
    const size_t R = (size_t)ro->rope_count, n = R * (size_t)ro->points;
    const float T = st->blend_time, h = st->h;
    int r, j, s, k;
    for (r = a; r < b; ++r) {
        float w = ro->blend[r], f0[12], f1[12];
        /* the tangent's reach: twice the rope's length */
        const float vmax2 = (2.0f * ro->length[r] + 0.01f) *
                            (2.0f * ro->length[r] + 0.01f);
        hf__rope_frame_at(ro, r, 0.0f, f0);
        for (s = 0; s < st->n; ++s) {
            const float u = T > 0.0f && w + h / T < 1.0f ? w + h / T : 1.0f;
            const float h00 = (2.0f * u - 3.0f) * u * u + 1.0f;
            const float h10 = ((u - 2.0f) * u + 1.0f) * u * T;
            const float h01 = (3.0f - 2.0f * u) * u * u;
            float gp[3] = {0.0f, 0.0f, 0.0f}, hp[3] = {0.0f, 0.0f, 0.0f};
            hf__rope_frame_at(ro, r, (float)(s + 1) / (float)st->n, f1);
            for (j = 0; j < ro->points; ++j) {
                const size_t i = (size_t)j * R + (size_t)r;
                float *G = ro->glide + i, g[3], d[3];
                g[0] = ro->rest_u[i];
                g[1] = ro->rest_v[i];
                g[2] = ro->rest_w[i];
                if (w == 0.0f && s == 0) {
                    /* the glide's first sub-step: take the frame's own
                       motion at the point off the start velocity, and
                       bound what it can carry the point over the glide
                       (a wild velocity, or a NaN, must not throw it) */
                    float m[3], v2;
                    for (k = 0; k < 3; ++k)
                        m[k] = f1[k] - f0[k] +
                               (f1[3 + k] - f0[3 + k]) * G[0] +
                               (f1[6 + k] - f0[6 + k]) * G[n] +
                               (f1[9 + k] - f0[9 + k]) * G[2 * n];
                    for (k = 0; k < 3; ++k)
                        G[(3 + k) * n] -= hf__dot3(m, f0 + 3 + 3 * k) / h;
                    v2 = (G[3 * n] * G[3 * n] + G[4 * n] * G[4 * n] +
                          G[5 * n] * G[5 * n]) * T * T;
                    if (!(v2 <= vmax2)) { /* NaN too */
                        const float c = v2 > 0.0f && hf__finitef(v2)
                                            ? HF_SQRTF(vmax2 / v2) : 0.0f;
                        for (k = 3; k < 6; ++k) G[(size_t)k * n] *= c;
                    }
                }
                if (u < 1.0f) {
                    for (k = 0; k < 3; ++k) {
                        const float c = h00 * G[k * n] +
                                        h10 * G[(3 + k) * n] + h01 * g[k];
                        d[k] = c - hp[k]; /* the curve's own segment */
                        hp[k] = c;
                        g[k] = c;
                    }
                    if (j > 0) {
                        const float l2 = hf__dot3(d, d);
                        if (l2 > 1e-24f) {
                            const float sc =
                                ro->rest_length[i - R] / HF_SQRTF(l2);
                            for (k = 0; k < 3; ++k) g[k] = gp[k] + d[k] * sc;
                        }
                    }
                }
                for (k = 0; k < 3; ++k) gp[k] = g[k];
                ro->px[i] = ro->x[i];
                ro->py[i] = ro->y[i];
                ro->pz[i] = ro->z[i];
                ro->x[i] = f1[0] + f1[3] * g[0] + f1[6] * g[1] + f1[9] * g[2];
                ro->y[i] = f1[1] + f1[4] * g[0] + f1[7] * g[1] + f1[10] * g[2];
                ro->z[i] = f1[2] + f1[5] * g[0] + f1[8] * g[1] + f1[11] * g[2];
            }
            w = u;
            for (k = 0; k < 12; ++k) f0[k] = f1[k];
        }
        ro->blend[r] = w;
        ro->last_h[r] = h;
        ro->time[r] += (double)h * st->n;
    }
    hf__ropes_safety_net(ro, a, b, st); /* never an output that is NaN */
}

/* ---- 6.6 the simulated rope step: one driver, named steps --------------- */

/* Per rope, before sub-step s of n: the frame rows of the sub-step (at
   alpha 1 the current frame itself, what hf__rope_frame_at gives, bit for
   bit), the acceleration times h^2 and the velocity factor. Returns the
   frame rows the sub-step uses. */
HF__PRIVATE const float *hf__ropes_substep_prep(hf_ropes *ro, int a, int b,
                                                const hf__rope_step *st,
                                                int s)
{
    const size_t R = (size_t)ro->rope_count;
    float *scratch = ro->scratch;
    float *FS = HF__ROW(scratch, HF__RS_F, R);
    float *AX = HF__ROW(scratch, HF__RS_A, R),
          *AY = HF__ROW(scratch, HF__RS_A + 1, R),
          *AZ = HF__ROW(scratch, HF__RS_A + 2, R),
          *VF = HF__ROW(scratch, HF__RS_VF, R);
    const float h = st->h, h2 = h * h;
    float alpha = s + 1 == st->n ? 1.0f : (float)(s + 1) / (float)st->n;
    int r;
    /* per rope: frame, acceleration, velocity factor */
    for (r = a; r < b; ++r) {
        float f[12], gx = st->g[0], gy = st->g[1], gz = st->g[2], vf;
        int k;
        if (alpha < 1.0f) {
            hf__rope_frame_at(ro, r, alpha, f);
            for (k = 0; k < 12; ++k) FS[(size_t)k * R + r] = f[k];
        }
        if (st->turbulence > 0.0f) {
            double tt = ro->time[r] * (double)st->turbulence_frequency;
            gx += st->turbulence * hf__rope_noise((uint32_t)r, tt, 0);
            gy += st->turbulence * hf__rope_noise((uint32_t)r, tt, 1);
            gz += st->turbulence * hf__rope_noise((uint32_t)r, tt, 2);
        }
        AX[r] = gx * h2;
        AY[r] = gy * h2;
        AZ[r] = gz * h2;
        vf = st->keep;
        /* time-corrected Verlet: x - px spans the previous sub-step;
           capped so a tiny previous step cannot amplify rounding */
        if (s == 0 && ro->last_h[r] > 0.0f) {
            float q = h / ro->last_h[r];
            vf *= q < 4.0f ? q : 4.0f;
        }
        VF[r] = vf;
        ro->time[r] += (double)h;
    }
    return alpha >= 1.0f ? ro->frame : FS;
}

/* Position Verlet for points 1.. of ropes [a, b), then the root pinned to
   the frame F. */
HF__PRIVATE void hf__ropes_integrate_v1(hf_ropes *ro, const float *F, int a,
                                        int b)
{
    const size_t R = (size_t)ro->rope_count;
    const int P = ro->points;
    const float *VF = HF__ROW(ro->scratch, HF__RS_VF, R),
                *AX = HF__ROW(ro->scratch, HF__RS_A, R),
                *AY = HF__ROW(ro->scratch, HF__RS_A + 1, R),
                *AZ = HF__ROW(ro->scratch, HF__RS_A + 2, R);
    int j, r;
    /* integrate points 1.. (position Verlet) */
    for (j = 1; j < P; ++j) {
        float *HF__RESTRICT X = HF__ROW(ro->x, j, R);
        float *HF__RESTRICT Y = HF__ROW(ro->y, j, R);
        float *HF__RESTRICT Z = HF__ROW(ro->z, j, R);
        float *HF__RESTRICT PX = HF__ROW(ro->px, j, R);
        float *HF__RESTRICT PY = HF__ROW(ro->py, j, R);
        float *HF__RESTRICT PZ = HF__ROW(ro->pz, j, R);
        for (r = a; r < b; ++r) {
            float vx = (X[r] - PX[r]) * VF[r];
            float vy = (Y[r] - PY[r]) * VF[r];
            float vz = (Z[r] - PZ[r]) * VF[r];
            PX[r] = X[r];
            PY[r] = Y[r];
            PZ[r] = Z[r];
            X[r] += vx + AX[r];
            Y[r] += vy + AY[r];
            Z[r] += vz + AZ[r];
        }
    }
    /* pin the root to the frame */
    for (r = a; r < b; ++r) {
        ro->px[r] = ro->x[r];
        ro->py[r] = ro->y[r];
        ro->pz[r] = ro->z[r];
    }
    hf__rope_pose_row_v1(ro, 0, a, b, F, ro->x, ro->y, ro->z);
}

/* Shape: the root segment and the global pose, each point pulled toward
   its rest place in the frame F. */
HF__PRIVATE void hf__ropes_global_shape_v1(hf_ropes *ro, const float *F, int a,
                                           int b, const hf__rope_step *st)
{
    const size_t R = (size_t)ro->rope_count;
    const int P = ro->points;
    int j, r;
    for (j = 1; j < P; ++j) {
        float tgx, tgy, tgz;
        const float kg = st->ktab ? st->kg[j] : hf__rope_kg(st, j, P);
        float *HF__RESTRICT X = HF__ROW(ro->x, j, R);
        float *HF__RESTRICT Y = HF__ROW(ro->y, j, R);
        float *HF__RESTRICT Z = HF__ROW(ro->z, j, R);
        const float *u = HF__ROW(ro->rest_u, j, R),
                    *v = HF__ROW(ro->rest_v, j, R),
                    *w = HF__ROW(ro->rest_w, j, R);
        if (kg <= 0.0f) continue;
        for (r = a; r < b; ++r) {
            const float k = kg;
            tgx = F[r] + F[3 * R + r] * u[r] + F[6 * R + r] * v[r] +
                  F[9 * R + r] * w[r];
            tgy = F[R + r] + F[4 * R + r] * u[r] +
                  F[7 * R + r] * v[r] + F[10 * R + r] * w[r];
            tgz = F[2 * R + r] + F[5 * R + r] * u[r] +
                  F[8 * R + r] * v[r] + F[11 * R + r] * w[r];
            X[r] += k * (tgx - X[r]);
            Y[r] += k * (tgy - Y[r]);
            Z[r] += k * (tgz - Z[r]);
        }
    }
}

/* Local shape: each segment toward its rest direction relative to its
   parent segment (the rest offset turned by the smallest rotation that
   takes the parent's rest direction to its current one). */
HF__PRIVATE void hf__ropes_local_shape_v1(hf_ropes *ro, const float *F, int a,
                                          int b, const hf__rope_step *st)
{
    const size_t R = (size_t)ro->rope_count;
    const int P = ro->points;
    int j, r;
    for (j = 1; j + 1 < P; ++j) {
        const float kl = st->ktab ? st->kl[j] : hf__rope_kl(st, j, P);
        const float *X0 = HF__ROW(ro->x, j - 1, R),
                    *Y0 = HF__ROW(ro->y, j - 1, R),
                    *Z0 = HF__ROW(ro->z, j - 1, R);
        const float *X1 = HF__ROW(ro->x, j, R), *Y1 = HF__ROW(ro->y, j, R),
                    *Z1 = HF__ROW(ro->z, j, R);
        float *HF__RESTRICT X2 = HF__ROW(ro->x, j + 1, R);
        float *HF__RESTRICT Y2 = HF__ROW(ro->y, j + 1, R);
        float *HF__RESTRICT Z2 = HF__ROW(ro->z, j + 1, R);
        const float *u0 = HF__ROW(ro->rest_u, j - 1, R),
                    *v0 = HF__ROW(ro->rest_v, j - 1, R),
                    *w0 = HF__ROW(ro->rest_w, j - 1, R);
        const float *u1 = HF__ROW(ro->rest_u, j, R),
                    *v1 = HF__ROW(ro->rest_v, j, R),
                    *w1 = HF__ROW(ro->rest_w, j, R);
        const float *u2 = HF__ROW(ro->rest_u, j + 1, R),
                    *v2 = HF__ROW(ro->rest_v, j + 1, R),
                    *w2 = HF__ROW(ro->rest_w, j + 1, R);
        const float *L = HF__ROW(ro->rest_length, j - 1, R);
        if (kl <= 0.0f) continue;
        for (r = a; r < b; ++r) {
            /* rest directions in world: parent p, child q */
            float pu = u1[r] - u0[r], pv = v1[r] - v0[r],
                  pw = w1[r] - w0[r];
            float qu = u2[r] - u1[r], qv = v2[r] - v1[r],
                  qw = w2[r] - w1[r];
            float px_ = F[3 * R + r] * pu + F[6 * R + r] * pv +
                        F[9 * R + r] * pw;
            float py_ = F[4 * R + r] * pu + F[7 * R + r] * pv +
                        F[10 * R + r] * pw;
            float pz_ = F[5 * R + r] * pu + F[8 * R + r] * pv +
                        F[11 * R + r] * pw;
            float qx = F[3 * R + r] * qu + F[6 * R + r] * qv +
                       F[9 * R + r] * qw;
            float qy = F[4 * R + r] * qu + F[7 * R + r] * qv +
                       F[10 * R + r] * qw;
            float qz = F[5 * R + r] * qu + F[8 * R + r] * qv +
                       F[11 * R + r] * qw;
            float bx = X1[r] - X0[r], by = Y1[r] - Y0[r],
                  bz = Z1[r] - Z0[r];
            float b2 = bx * bx + by * by + bz * bz;
            float ok = (L[r] > 1e-12f && b2 > 1e-24f) ? 1.0f : 0.0f;
            float ia = ok > 0.0f ? 1.0f / L[r] : 0.0f;
            float ib = ok > 0.0f ? 1.0f / HF_SQRTF(b2) : 0.0f;
            float cc, kx, ky, kz, kd, den, rx, ry, rz;
            px_ *= ia;
            py_ *= ia;
            pz_ *= ia;
            bx *= ib;
            by *= ib;
            bz *= ib;
            /* Rodrigues without trigonometry: the rotation taking
               unit p to unit b, applied to q; identity when either
               direction is undefined */
            cc = ok > 0.0f ? px_ * bx + py_ * by + pz_ * bz : 1.0f;
            kx = py_ * bz - pz_ * by;
            ky = pz_ * bx - px_ * bz;
            kz = px_ * by - py_ * bx;
            kd = kx * qx + ky * qy + kz * qz;
            den = 1.0f + cc;
            den = kd / (den > 1e-6f ? den : 1e-6f);
            rx = qx * cc + (ky * qz - kz * qy) + kx * den;
            ry = qy * cc + (kz * qx - kx * qz) + ky * den;
            rz = qz * cc + (kx * qy - ky * qx) + kz * den;
            X2[r] += kl * (X1[r] + rx - X2[r]);
            Y2[r] += kl * (Y1[r] + ry - Y2[r]);
            Z2[r] += kl * (Z1[r] + rz - Z2[r]);
        }
    }
}

/* The solver passes, each a distance pass with its collisions (by the
   kernels k: the scalar reference's). */
HF__PRIVATE void hf__ropes_solve_v1(hf_ropes *ro, const float *F, int a, int b,
                                    const hf__rope_step *st, const hf__bp *bp,
                                    const struct hf__rope_rows *k)
{
    const size_t R = (size_t)ro->rope_count;
    const int P = ro->points;
    const float *nx = HF__ROW(F, 6, R), *ny = HF__ROW(F, 7, R),
                *nz = HF__ROW(F, 8, R);
    int j, r, it;
        for (it = 0; it < st->iterations; ++it) {
        for (j = 1; j < P; ++j) {
            float *HF__RESTRICT X0 = HF__ROW(ro->x, j - 1, R);
            float *HF__RESTRICT Y0 = HF__ROW(ro->y, j - 1, R);
            float *HF__RESTRICT Z0 = HF__ROW(ro->z, j - 1, R);
            float *HF__RESTRICT X1 = HF__ROW(ro->x, j, R);
            float *HF__RESTRICT Y1 = HF__ROW(ro->y, j, R);
            float *HF__RESTRICT Z1 = HF__ROW(ro->z, j, R);
            float *HF__RESTRICT PX0 = HF__ROW(ro->px, j - 1, R);
            float *HF__RESTRICT PY0 = HF__ROW(ro->py, j - 1, R);
            float *HF__RESTRICT PZ0 = HF__ROW(ro->pz, j - 1, R);
            const float *L = HF__ROW(ro->rest_length, j - 1, R);
            /* Mueller's velocity fix goes to the parent; never to the
               pinned root */
            const float sd = j >= 2 ? st->ftl_damping : 0.0f;
            if (st->ftl || j == 1) {
                for (r = a; r < b; ++r) {
                    float dx = X1[r] - X0[r], dy = Y1[r] - Y0[r],
                          dz = Z1[r] - Z0[r];
                    float d2 = dx * dx + dy * dy + dz * dz, sc, ox, oy,
                          oz;
                    /* shorter than its rest length: FTL pushes the child
                       out (compression), see hf__ftl_bend_damp */
                    const int comp = d2 < L[r] * L[r];
                    /* coincident points: grow along the root normal */
                    int deg = d2 < 1e-24f;
                    dx = deg ? nx[r] : dx;
                    dy = deg ? ny[r] : dy;
                    dz = deg ? nz[r] : dz;
                    d2 = deg ? 1.0f : d2;
                    sc = L[r] / HF_SQRTF(d2);
                    ox = X1[r];
                    oy = Y1[r];
                    oz = Z1[r];
                    X1[r] = X0[r] + dx * sc;
                    Y1[r] = Y0[r] + dy * sc;
                    Z1[r] = Z0[r] + dz * sc;
                    if (st->ftl && (j < 2 || !comp)) {
                        PX0[r] += sd * (X1[r] - ox);
                        PY0[r] += sd * (Y1[r] - oy);
                        PZ0[r] += sd * (Z1[r] - oz);
                    } else if (st->ftl) {
                        hf__ftl_bend_damp(ro, j, r, 0.5f * sd);
                    }
                }
                /* FTL never moves a parent again, so colliding each
                   point right after placing it leaves the whole rope
                   outside when the pass ends */
                if (st->ftl && bp)
                    hf__ropes_collide_ftl_row(ro, F, j, a, b, bp);
            } else {
                for (r = a; r < b; ++r) {
                    float dx = X1[r] - X0[r], dy = Y1[r] - Y0[r],
                          dz = Z1[r] - Z0[r];
                    float d2 = dx * dx + dy * dy + dz * dz;
                    /* half the error to each end (equal masses) */
                    float e = d2 > 1e-24f
                                  ? 0.5f - 0.5f * L[r] / HF_SQRTF(d2)
                                  : 0.0f;
                    X0[r] += dx * e;
                    Y0[r] += dy * e;
                    Z0[r] += dz * e;
                    X1[r] -= dx * e;
                    Y1[r] -= dy * e;
                    Z1[r] -= dz * e;
                }
            }
        }
        if (!st->ftl && bp) hf__ropes_collide(ro, F, a, b, bp, k);
    }
    if (st->iterations == 0 && bp) hf__ropes_collide(ro, F, a, b, bp, k);
}

/* One sub-step of simulated ropes [a, b), the scalar reference (k: the
   width-1 entry of hf__rope_widths); returns b. */
HF__PRIVATE int hf__ropes_substep_v1(hf_ropes *ro, const float *F, int a, int b,
                                     const hf__rope_step *st, const hf__bp *bp,
                                     const struct hf__rope_rows *k)
{
    hf__ropes_integrate_v1(ro, F, a, b);
    if (st->k_root > 0.0f || st->global_on)
        hf__ropes_global_shape_v1(ro, F, a, b, st);
    if (st->local_on) hf__ropes_local_shape_v1(ro, F, a, b, st);
    hf__ropes_solve_v1(ro, F, a, b, st, bp, k);
    return b;
}

/* Marks (VF[r] = 1) the ropes of [a, b) whose point row j lies beyond the
   squared distance KB[r] from the root, or is NaN. */
HF__PRIVATE void hf__ropes_mark_far_row(const hf_ropes *ro, int j, int a, int b,
                                        const float *KB, float *VF)
{
    const size_t R = (size_t)ro->rope_count;
    const float *X = HF__ROW(ro->x, j, R), *Y = HF__ROW(ro->y, j, R),
                *Z = HF__ROW(ro->z, j, R);
    int r;
    for (r = a; r < b; ++r) {
        float dx = X[r] - ro->x[r], dy = Y[r] - ro->y[r],
              dz = Z[r] - ro->z[r];
        float d2 = dx * dx + dy * dy + dz * dz;
        /* false for NaN too */
        VF[r] = (d2 <= KB[r]) ? VF[r] : 1.0f;
    }
}

#if HF__V4

/* A row's points in contact, listed for the kernel (they are independent:
   a point's collision moves nothing the row reads again): as many as a
   chunk has ropes, so that a row's contacts are grouped once, the more
   of a signature the fuller its groups (a power of two: the grouping's
   hash table masks with it). */
#define HF__FTL_HITS HF__ROPE_CHUNK
typedef struct hf__ftl_hits {
    int n, r[HF__FTL_HITS];
} hf__ftl_hits;

/* Prefetch of what row j's integration and local shape read, for the 16
   ropes (a cache line) from r. */
HF__INLINE void hf__ropes_prefetch_row(const hf_ropes *ro, int j, int r)
{
    const size_t R = (size_t)ro->rope_count, o = (size_t)j * R + (size_t)r;
    HF__PREFETCH(ro->x + o);
    HF__PREFETCH(ro->y + o);
    HF__PREFETCH(ro->z + o);
    HF__PREFETCH(ro->px + o);
    HF__PREFETCH(ro->py + o);
    HF__PREFETCH(ro->pz + o);
    HF__PREFETCH(ro->rest_u + o);
    HF__PREFETCH(ro->rest_v + o);
    HF__PREFETCH(ro->rest_w + o);
    HF__PREFETCH(ro->rest_length + o - R);
}
#endif
/* ---- 6.7 the rope kernels: a kernel text, at any width ------------------ */

#endif /* !HF__PASS */

#if defined(HF__PASS) && HF__PASS == HF__PASS_ROPES
/* The follow-the-leader collision of hf__ftl_collide_point on W ropes at
   once, the same operations in the same order per lane, so every lane
   gets the scalar kernel's bytes: the steps that branch in the scalar code
   run on every lane and a select keeps each lane's own branch; a lane
   whose point is outside, or done, keeps its value. Points in contact are
   a few percent of a row, but each costs the scalar kernel a chain of
   some twenty square roots and divisions, so W at a time pays.

   These kernels are a kernel text, written once for W = HF__W lanes
   and built at four below (SSE2, NEON), at eight (AVX2) and sixteen
   (AVX-512) after hf__ropes_collide; HF__VZEROUPPER() readies the
   registers for the scalar code of the rare paths. */

/* Prepared colliders, one a lane (the same in every lane, or each lane
   its own: hf__col_lanes), rr^2, the lanes whose axis is a point (pm: e
   == 0, a sphere or a zero-length capsule) and those that are capsules
   (cm); point: every lane's axis a point; some_point, capsule, shrink:
   some lane's, or a lane's collider that can shrink for a root. */
typedef struct HF__KN(hf__col) {
    HF__VEC a[3], e[3], inv, rr2, rr, inner, pm, cm;
    int point, some_point, capsule, shrink;
} HF__KN(hf__col);

HF__VTARGET HF__INLINE void HF__KN(hf__col_prep)(const hf__col_prep *k,
                                                 HF__KN(hf__col) *v)
{
    const HF__VEC zero = HF__VSET1(0.0f), all = HF__VEQ(zero, zero);
    int i;
    for (i = 0; i < 3; ++i) {
        v->a[i] = HF__VSET1(k->a[i]);
        v->e[i] = HF__VSET1(k->e[i]);
    }
    v->inv = HF__VSET1(k->inv);
    v->rr2 = HF__VSET1(k->rr * k->rr);
    v->rr = HF__VSET1(k->rr);
    v->inner = HF__VSET1(k->inner);
    v->point = v->some_point =
        k->e[0] == 0.0f && k->e[1] == 0.0f && k->e[2] == 0.0f;
    v->capsule = k->inv > 0.0f;
    v->shrink = k->inner > 0.0f;
    v->pm = v->point ? all : zero;
    v->cm = v->capsule ? all : zero;
}

/* Lane l's own collider id[l] of the chunk's union (a whole number, as
   a float), in each lane: each collider prepared once, for the lanes
   that share it (neighbouring ropes mostly do), taken where they are by
   selects. */
HF__VTARGET HF__INLINE void HF__KN(hf__col_lanes)(const hf__bp *bp,
                                                  HF__VEC id,
                                                  HF__KN(hf__col) *v)
{
    const int all = HF__VALL;
    float f[HF__W];
    hf__col_prep spare;
    HF__KN(hf__col) w;
    int todo = all, pb = 0, cb = 0, i;
    HF__VST(f, id);
    while (todo) {
        const float c = f[hf__lowest_bit((unsigned)todo)];
        const HF__VEC m = HF__VEQ(id, HF__VSET1(c));
        const int bits = HF__VMASK(m);
        HF__KN(hf__col) *d = todo == all ? v : &w;
        HF__KN(hf__col_prep)(hf__bp_union_at(bp, (int)c, &spare), d);
        if (bits == all) return; /* one collider in every lane */
        if (d == &w) {
            HF__UNROLL for (i = 0; i < 3; ++i) {
                v->a[i] = HF__VSEL(m, w.a[i], v->a[i]);
                v->e[i] = HF__VSEL(m, w.e[i], v->e[i]);
            }
            v->inv = HF__VSEL(m, w.inv, v->inv);
            v->rr2 = HF__VSEL(m, w.rr2, v->rr2);
            v->rr = HF__VSEL(m, w.rr, v->rr);
            v->inner = HF__VSEL(m, w.inner, v->inner);
            v->shrink |= w.shrink;
        }
        if (d->point) pb |= bits;
        if (d->capsule) cb |= bits;
        todo &= ~bits;
    }
    v->point = pb == all;
    v->some_point = pb != 0;
    v->capsule = cb != 0;
    v->pm = HF__VLANES(pb);
    v->cm = HF__VLANES(cb);
}

/* hf__col_closest on W points */
HF__VTARGET HF__INLINE HF__VEC
HF__KN(hf__col_closest)(const HF__KN(hf__col) *k, const HF__VEC *x, HF__VEC *c)
{
    const HF__VEC zero = HF__VSET1(0.0f), one = HF__VSET1(1.0f);
    HF__VEC t, d[3];
    int i;
    if (k->point) {
        HF__UNROLL for (i = 0; i < 3; ++i) c[i] = k->a[i];
    } else {
        t = HF__VMUL(HF__VDOT3(HF__VSUB(x[0], k->a[0]), HF__VSUB(x[1], k->a[1]),
                               HF__VSUB(x[2], k->a[2]), k->e[0], k->e[1],
                               k->e[2]),
                     k->inv);
        /* t < 0 ? 0 : (t > 1 ? 1 : t), NaN and -0 kept as the scalar does */
        t = HF__VSEL(HF__VLT(t, zero), zero, HF__VSEL(HF__VGT(t, one), one, t));
        HF__UNROLL for (i = 0; i < 3; ++i)
            c[i] = HF__VADD(k->a[i], HF__VMUL(k->e[i], t));
        if (k->some_point) /* the point axes' lanes: the centre itself */
            HF__UNROLL for (i = 0; i < 3; ++i)
                c[i] = HF__VSEL(k->pm, k->a[i], c[i]);
    }
    HF__UNROLL for (i = 0; i < 3; ++i) d[i] = HF__VSUB(x[i], c[i]);
    return HF__VDOT3(d[0], d[1], d[2], d[0], d[1], d[2]);
}

/* Which of W points hf__col_closest finds inside radius rr (bit i: lane
   i), from its |d|^2: the kernels run the scalar code on exactly the
   points it would act on, and skip the rest (most points, most steps). */
HF__VTARGET HF__INLINE int HF__KN(hf__col_hits)(const HF__KN(hf__col) *k,
                                                const HF__VEC *x)
{
    HF__VEC d2;
    if (k->point) { /* hf__col_closest without its c */
        const HF__VEC dx = HF__VSUB(x[0], k->a[0]),
                      dy = HF__VSUB(x[1], k->a[1]),
                      dz = HF__VSUB(x[2], k->a[2]);
        d2 = HF__VDOT3(dx, dy, dz, dx, dy, dz);
    } else {
        HF__VEC c[3];
        d2 = HF__KN(hf__col_closest)(k, x, c);
    }
    return HF__VMASK(HF__VLT(d2, k->rr2));
}

/* Which of W points (in one tile) some collider of the tile's list that
   row j reaches holds (bit i: lane i). A collider whose bounding ball
   holds none of them is passed over: most of a tile's colliders are near
   none of a row's points. */
HF__VTARGET HF__INLINE int HF__KN(hf__col_any)(const hf__cols *cl, int j,
                                               const HF__VEC *xyz)
{
    hf__col_prep spare;
    HF__KN(hf__col) v;
    int i, m = 0;
    for (i = 0; i < cl->n && m != HF__VALL; ++i) {
        const hf__col_prep *k = hf__cols_at(cl, i, &spare);
        HF__VEC d[3];
        int w;
        if (k->row > j) continue;
        HF__UNROLL for (w = 0; w < 3; ++w)
            d[w] = HF__VSUB(xyz[w], HF__VSET1(k->a[w] + 0.5f * k->e[w]));
        if (!HF__VMASK(HF__VLT(HF__VDOT3(d[0], d[1], d[2], d[0], d[1], d[2]),
                               HF__VSET1(k->ball * k->ball))))
            continue;
        HF__KN(hf__col_prep)(k, &v);
        m |= HF__KN(hf__col_hits)(&v, xyz);
    }
    return m;
}

/* hf__ftl_relevant on W parents p with segments l */
HF__VTARGET HF__INLINE HF__VEC
HF__KN(hf__ftl_relevant)(const HF__KN(hf__col) *k, const HF__VEC *p, HF__VEC l)
{
    HF__VEC cc[3], lim;
    const HF__VEC d2 = HF__KN(hf__col_closest)(k, p, cc);
    lim = HF__VADD(k->rr, l);
    lim = HF__VADD(lim, HF__VMUL(HF__VSET1(1e-4f), lim));
    return HF__VLT(d2, HF__VMUL(lim, lim));
}

/* hf__ftl_penetration on W points; *any: the lanes some collider holds;
   cw, rw and cn (unless cw is NULL): the deepest one's axis point nearest
   the point, its radius and its index (as a float) */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__ftl_penetration)(
    const HF__KN(hf__col) *k, const HF__VEC *rr, int ncol, const HF__VEC *q,
    HF__VEC *any, HF__VEC *cw, HF__VEC *rw, HF__VEC *cn)
{
    HF__VEC worst = HF__VSET1(0.0f), hit_any = HF__VLT(worst, worst), c3[3];
    int c, i;
    for (c = 0; c < ncol; ++c) {
        const HF__VEC d2 = HF__KN(hf__col_closest)(k + c, q, c3);
        const HF__VEC hit = HF__VLT(d2, HF__VMUL(rr[c], rr[c]));
        const HF__VEC pen = HF__VSUB(rr[c], HF__VSQRT(d2));
        const HF__VEC up =
            HF__VSEL(hit_any, HF__VAND(hit, HF__VGT(pen, worst)), hit);
        worst = HF__VSEL(up, pen, worst);
        hit_any = HF__VOR(hit, hit_any);
        if (cw) {
            HF__UNROLL for (i = 0; i < 3; ++i)
                cw[i] = HF__VSEL(up, c3[i], cw[i]);
            *rw = HF__VSEL(up, rr[c], *rw);
            *cn = HF__VSEL(up, HF__VSET1((float)c), *cn);
        }
    }
    *any = hit_any;
    return worst;
}

/* hf__ftl_cap on W lanes */
HF__VTARGET HF__INLINE void HF__KN(hf__ftl_cap)(const HF__VEC *p, HF__VEC l,
                                                const HF__VEC *c, HF__VEC rr,
                                                const HF__VEC *n, HF__VEC *m,
                                                HF__VEC *cmin)
{
    const HF__VEC zero = HF__VSET1(0.0f), one = HF__VSET1(1.0f);
    HF__VEC rho2, rho, big, cm;
    int k;
    HF__UNROLL for (k = 0; k < 3; ++k) m[k] = HF__VSUB(p[k], c[k]);
    rho2 = HF__VDOT3(m[0], m[1], m[2], m[0], m[1], m[2]);
    big = HF__VGT(rho2, HF__VSET1(1e-24f));
    rho = HF__VSEL(big, HF__VSQRT(rho2), zero);
    HF__UNROLL for (k = 0; k < 3; ++k)
        m[k] = HF__VSEL(big, HF__VDIV(m[k], rho), n[k]);
    rr = HF__VADD(rr, HF__VMUL(HF__VSET1(1e-6f), HF__VADD(rr, l)));
    cm = HF__VDIV(HF__VSUB(HF__VSUB(HF__VMUL(rr, rr), HF__VMUL(rho, rho)),
                           HF__VMUL(l, l)),
                  HF__VMUL(HF__VMUL(HF__VSET1(2.0f), l), rho));
    cm = HF__VSEL(HF__VGT(rho, zero), cm, one);
    *cmin =
        HF__VSEL(HF__VGT(cm, one), one,
                 HF__VSEL(HF__VLT(cm, HF__VSET1(-1.0f)), HF__VSET1(-1.0f), cm));
}

/* hf__perp_part on W lanes */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__perp_part)(HF__VEC *v,
                                                     const HF__VEC *m)
{
    int pass, k;
    HF__UNROLL for (pass = 0; pass < 2; ++pass) {
        const HF__VEC vm = HF__VDOT3(v[0], v[1], v[2], m[0], m[1], m[2]);
        HF__UNROLL for (k = 0; k < 3; ++k)
            v[k] = HF__VSUB(v[k], HF__VMUL(m[k], vm));
    }
    return HF__VDOT3(v[0], v[1], v[2], v[0], v[1], v[2]);
}

/* hf__ftl_onto_cap on W lanes; the fixed perpendicular, rare, lane by
   lane through the scalar code */
HF__VTARGET HF__INLINE void
HF__KN(hf__ftl_onto_cap)(const HF__VEC *u, const HF__VEC *m, HF__VEC cmin,
                         const HF__VEC *t, HF__VEC *d)
{
    const HF__VEC tiny = HF__VSET1(1e-8f);
    HF__VEC v[3], w[3], v2, w2, low, s;
    int k, lanes;
    HF__UNROLL for (k = 0; k < 3; ++k) v[k] = u[k];
    v2 = HF__KN(hf__perp_part)(v, m);
    low = HF__VLT(v2, tiny);
    if (HF__VMASK(low)) {
        HF__UNROLL for (k = 0; k < 3; ++k) w[k] = t[k];
        w2 = HF__KN(hf__perp_part)(w, m);
        HF__UNROLL for (k = 0; k < 3; ++k) v[k] = HF__VSEL(low, w[k], v[k]);
        v2 = HF__VSEL(low, w2, v2);
        lanes = HF__VMASK(HF__VAND(low, HF__VLT(w2, tiny)));
        if (lanes) {
            float mm[3][HF__W], vv[3][HF__W], vv2[HF__W], ml[3], vl[3];
            int i;
            for (k = 0; k < 3; ++k) {
                HF__VST(mm[k], m[k]);
                HF__VST(vv[k], v[k]);
            }
            HF__VST(vv2, v2);
            for (i = 0; i < HF__W; ++i)
                if ((lanes >> i) & 1) {
                    for (k = 0; k < 3; ++k) ml[k] = mm[k][i];
                    HF__VZEROUPPER();
                    vv2[i] = hf__perp_fixed(ml, vl);
                    for (k = 0; k < 3; ++k) vv[k][i] = vl[k];
                }
            for (k = 0; k < 3; ++k) v[k] = HF__VLD(vv[k]);
            v2 = HF__VLD(vv2);
        }
    }
    s = HF__VDIV(HF__VSQRT(HF__VSUB(HF__VSET1(1.0f), HF__VMUL(cmin, cmin))),
                 HF__VSQRT(v2));
    HF__UNROLL for (k = 0; k < 3; ++k)
        d[k] = HF__VADD(HF__VMUL(m[k], cmin), HF__VMUL(v[k], s));
}

/* hf__ftl_cap_pair's crossings d = al m1 + be m2 +- g m1 x m2, where g^2
   = (1 - h^2) / det is not negative (the lanes returned). Apart, as
   hf__ftl_cap_pair_unit. */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__ftl_cap_pair_d)(
    const HF__VEC *m1, const HF__VEC *m2, HF__VEC mu, HF__VEC det, HF__VEC al,
    HF__VEC be, HF__VEC *d)
{
    HF__VEC x[3], h2, g2, ok;
    int k;
    HF__VCROSS3(x, m1, m2);
    h2 = HF__VADD(HF__VADD(HF__VMUL(al, al), HF__VMUL(be, be)),
                  HF__VMUL(HF__VMUL(HF__VMUL(HF__VSET1(2.0f), al), be), mu));
    g2 = HF__VDIV(HF__VSUB(HF__VSET1(1.0f), h2), det);
    ok = HF__VLE(HF__VSET1(0.0f), g2);
    g2 = HF__VSQRT(g2);
    HF__UNROLL for (k = 0; k < 3; ++k) {
        const HF__VEC b = HF__VADD(HF__VMUL(al, m1[k]), HF__VMUL(be, m2[k]));
        d[k] = HF__VADD(b, HF__VMUL(g2, x[k]));
        d[3 + k] = HF__VSUB(b, HF__VMUL(g2, x[k]));
    }
    return ok;
}

/* hf__ftl_cap_pair's last step: both crossings d[0..5] unit again, ok
   where both were near unit. Apart, so that a debug build's stack (every
   temporary its own slot) holds this step's or the crossings'. */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__ftl_cap_pair_unit)(HF__VEC *d,
                                                             HF__VEC ok)
{
    const HF__VEC one = HF__VSET1(1.0f);
    int k;
    HF__UNROLL for (k = 0; k < 2; ++k) {
        HF__VEC *dk = d + 3 * k,
                n2 = HF__VDOT3(dk[0], dk[1], dk[2], dk[0], dk[1], dk[2]);
        ok = HF__VAND(ok, HF__VAND(HF__VGT(n2, HF__VSET1(0.25f)),
                                   HF__VLT(n2, HF__VSET1(4.0f))));
        n2 = HF__VDIV(one, HF__VSQRT(n2));
        dk[0] = HF__VMUL(dk[0], n2);
        dk[1] = HF__VMUL(dk[1], n2);
        dk[2] = HF__VMUL(dk[2], n2);
    }
    return ok;
}

/* hf__ftl_cap_pair on W lanes: both crossings in d[0..5]; returns the
   lanes where the scalar code returns 2 */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__ftl_cap_pair)(const HF__VEC *m1,
                                                        HF__VEC c1,
                                                        const HF__VEC *m2,
                                                        HF__VEC c2, HF__VEC *d)
{
    const HF__VEC mu = HF__VDOT3(m1[0], m1[1], m1[2], m2[0], m2[1], m2[2]);
    const HF__VEC det = HF__VSUB(HF__VSET1(1.0f), HF__VMUL(mu, mu));
    const HF__VEC al = HF__VDIV(HF__VSUB(c1, HF__VMUL(mu, c2)), det),
                  be = HF__VDIV(HF__VSUB(c2, HF__VMUL(mu, c1)), det);
    const HF__VEC ok = HF__KN(hf__ftl_cap_pair_d)(m1, m2, mu, det, al, be, d);
    return HF__KN(hf__ftl_cap_pair_unit)(
        d, HF__VAND(ok, HF__VGT(det, HF__VSET1(1e-8f))));
}

/* hf__ftl_last_side's measure on W lanes: which of two crossings d[0..5]
   lies on the side of the point's last motion v (s < 0: the second, s >
   0: the first, 0: neither) */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__ftl_side)(const HF__VEC *d,
                                                    const HF__VEC *v)
{
    return HF__VDOT3(HF__VSUB(d[0], d[3]), HF__VSUB(d[1], d[4]),
                     HF__VSUB(d[2], d[5]), v[0], v[1], v[2]);
}

/* A step of hf__ftl_crease: of the crossings d2 (both, on the lanes of
   go), the one on the side of the last place, and where that is square
   both in order; a lane that clears gets its point in best. Returns the
   lanes to go on with: held further along by ca or cb (*held: which;
   cand: where), not square. Apart from hf__ftl_crease, so that a debug
   build's stack holds its temporaries or those of hf__ftl_cap_pair, not
   both. */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__ftl_crease_try)(
    const HF__KN(hf__col) *k, const HF__VEC *rr, int ncol, const HF__VEC *p,
    HF__VEC l, const HF__VEC *v, HF__VEC ca, HF__VEC cb, HF__VEC go,
    const HF__VEC *d2, HF__VEC *cand, HF__VEC *best, HF__VEC *best_pen)
{
    const HF__VEC zero = HF__VSET1(0.0f);
    HF__VEC s, side, sq, pen, ok, hold, held = zero, cw[3], rw = zero;
    int i;
    s = HF__KN(hf__ftl_side)(d2, v);
    side = HF__VOR(HF__VLT(s, zero), HF__VGT(s, zero));
    sq = HF__VSEL(side, zero, go);
    HF__UNROLL for (i = 0; i < 3; ++i) {
        cw[i] = zero;
        cand[i] = HF__VADD(
            p[i], HF__VMUL(l, HF__VSEL(HF__VLT(s, zero), d2[3 + i], d2[i])));
    }
    pen = HF__KN(hf__ftl_penetration)(k, rr, ncol, cand, &hold, cw, &rw,
                                      &held);
    ok = HF__VAND(go, HF__VLE(pen, zero));
    HF__UNROLL for (i = 0; i < 3; ++i) best[i] = HF__VSEL(ok, cand[i], best[i]);
    *best_pen = HF__VSEL(ok, zero, *best_pen);
    sq = HF__VSEL(ok, zero, sq);
    if (HF__VMASK(sq)) { /* square: the second crossing */
        HF__VEC c2[3];
        HF__UNROLL for (i = 0; i < 3; ++i)
            c2[i] = HF__VADD(p[i], HF__VMUL(l, d2[3 + i]));
        pen = HF__KN(hf__ftl_penetration)(k, rr, ncol, c2, &hold, NULL, NULL,
                                          NULL);
        sq = HF__VAND(sq, HF__VLE(pen, zero));
        HF__UNROLL for (i = 0; i < 3; ++i) best[i] = HF__VSEL(sq, c2[i], best[i]);
        *best_pen = HF__VSEL(sq, zero, *best_pen);
    }
    go = HF__VSEL(ok, zero, HF__VAND(go, side));
    return HF__VAND(go, HF__VOR(HF__VEQ(held, ca), HF__VEQ(held, cb)));
}

/* The caps of ca and cb (per lane) at their balls nearest x. */
HF__VTARGET HF__INLINE void HF__KN(hf__ftl_crease_caps)(
    const HF__KN(hf__col) *k, const HF__VEC *rr, int ncol, const HF__VEC *p,
    HF__VEC l, const HF__VEC *n, HF__VEC ca, HF__VEC cb, const HF__VEC *x,
    HF__VEC *m1, HF__VEC *c1, HF__VEC *m2, HF__VEC *c2)
{
    const HF__VEC zero = HF__VSET1(0.0f);
    HF__VEC pa[3], pb[3], ra = zero, rb = zero, cc[3];
    int i, c;
    HF__UNROLL for (i = 0; i < 3; ++i) pa[i] = pb[i] = zero;
    for (c = 0; c < ncol; ++c) {
        const HF__VEC ci = HF__VSET1((float)c), ia = HF__VEQ(ca, ci),
                      ib = HF__VEQ(cb, ci);
        HF__KN(hf__col_closest)(k + c, x, cc);
        HF__UNROLL for (i = 0; i < 3; ++i) {
            pa[i] = HF__VSEL(ia, cc[i], pa[i]);
            pb[i] = HF__VSEL(ib, cc[i], pb[i]);
        }
        ra = HF__VSEL(ia, rr[c], ra);
        rb = HF__VSEL(ib, rr[c], rb);
    }
    HF__KN(hf__ftl_cap)(p, l, pa, ra, n, m1, c1);
    HF__KN(hf__ftl_cap)(p, l, pb, rb, n, m2, c2);
}

/* hf__ftl_collide_point's crease, on the lanes of `go`: ca's cap (ma,
   qa) and cb's ball nearest the point (cbw, rb), where the way out of ca
   ended inside cb; a lane that clears gets its point in best. */
HF__VTARGET HF__INLINE void HF__KN(hf__ftl_crease)(
    const HF__KN(hf__col) *k, const HF__VEC *rr, int ncol, const HF__VEC *p,
    HF__VEC l, const HF__VEC *n, const HF__VEC *v, HF__VEC ca, HF__VEC cb,
    const HF__VEC *ma, HF__VEC qa, const HF__VEC *cbw, HF__VEC rb,
    HF__VEC go, HF__VEC *best, HF__VEC *best_pen)
{
    HF__VEC m1[3], c1, m2[3], c2, d2[6], cand[3];
    int i, walk;
    HF__UNROLL for (i = 0; i < 3; ++i) m1[i] = ma[i];
    c1 = qa;
    HF__KN(hf__ftl_cap)(p, l, cbw, rb, n, m2, &c2);
    for (walk = 0; walk < HF__FTL_QUICK; ++walk) {
        go = HF__VAND(go, HF__KN(hf__ftl_cap_pair)(m1, c1, m2, c2, d2));
        go = HF__KN(hf__ftl_crease_try)(k, rr, ncol, p, l, v, ca, cb, go, d2,
                                        cand, best, best_pen);
        if (!HF__VMASK(go)) break;
        /* inside one of the two further along: their balls nearest it */
        HF__KN(hf__ftl_crease_caps)(k, rr, ncol, p, l, n, ca, cb, cand, m1,
                                    &c1, m2, &c2);
    }
}

/* hf__ftl_collide_point's rounds on W lanes, for the lanes of act still
   inside after the quick answer (best, best_pen: where it left them).
   Apart from the quick answer, so that a debug build's stack (every
   temporary its own slot) holds the rounds' or the crease's. */
HF__VTARGET HF__INLINE void HF__KN(hf__ftl_rounds)(
    const HF__KN(hf__col) *k, const HF__VEC *rr, int ncol, const HF__VEC *p,
    HF__VEC l, const HF__VEC *n, const HF__VEC *t, const HF__VEC *u,
    const HF__VEC *v, HF__VEC act, HF__VEC *best, HF__VEC *out_pen)
{
    const HF__VEC zero = HF__VSET1(0.0f), act0 = act;
    /* cv: the lanes a cap is theirs (a capsule's second one, only the
       lanes whose collider is one) */
    HF__VEC m[2 * HF__FTL_NEAR][3], cmin[2 * HF__FTL_NEAR],
        cv[2 * HF__FTL_NEAR], best_pen = *out_pen,
        best_dot = HF__VSET1(-2.0f);
    int c, e, i, w, round, ncap, pass, phase;
    for (phase = 0; phase < 2; ++phase)
    for (round = 0; round < HF__FTL_ROUNDS; ++round) {
        HF__VEC from[3];
        const HF__VEC pen0 = best_pen;
        if (phase == 1 && round == 0) act = act0; /* the lanes still in */
        act = HF__VAND(act, HF__VGT(best_pen, zero));
        if (!HF__VMASK(act)) break;
        HF__UNROLL for (i = 0; i < 3; ++i)
            from[i] = round == 0 ? u[i] : HF__VDIV(HF__VSUB(best[i], p[i]), l);
        ncap = 0;
        for (c = 0; c < ncol; ++c) {
            HF__VEC cc[3];
            HF__KN(hf__col_closest)(k + c, best, cc);
            HF__KN(hf__ftl_cap)(p, l, cc, rr[c], n, m[ncap], &cmin[ncap]);
            cv[ncap++] = HF__VEQ(zero, zero);
            if (k[c].capsule) {
                HF__KN(hf__col_closest)(k + c, p, cc);
                HF__KN(hf__ftl_cap)(p, l, cc, rr[c], n, m[ncap], &cmin[ncap]);
                cv[ncap++] = k[c].cm;
            }
        }
        for (pass = 0; pass < 2; ++pass) {
            HF__VEC need = act; /* pass 1: the lanes no projection cleared */
            if (pass == 1) {
                need = HF__VAND(act, HF__VGT(best_pen, zero));
                if (!HF__VMASK(need)) break;
            }
            for (c = 0; c < ncap; ++c)
            for (e = pass ? c + 1 : c; e < (pass ? ncap : c + 1); ++e) {
                HF__VEC d[6], valid = HF__VAND(cv[c], cv[e]), keep[2];
                int nd;
                keep[0] = keep[1] = valid;
                if (e == c) {
                    HF__KN(hf__ftl_onto_cap)(from, m[c], cmin[c], t, d);
                    nd = 1;
                    if (round > 0) {
                        HF__KN(hf__ftl_onto_cap)(u, m[c], cmin[c], t, d + 3);
                        nd = 2;
                    }
                } else {
                    valid =
                        HF__VAND(valid,
                                 HF__KN(hf__ftl_cap_pair)(m[c], cmin[c], m[e],
                                                          cmin[e], d));
                    if (!HF__VMASK(HF__VAND(need, valid))) continue;
                    nd = 2;
                    if (phase == 0) { /* the crease's side of the last place */
                        const HF__VEC s = HF__KN(hf__ftl_side)(d, v);
                        keep[0] = HF__VSEL(HF__VLT(s, zero), zero, keep[0]);
                        keep[1] = HF__VSEL(HF__VGT(s, zero), zero, keep[1]);
                    }
                }
                for (i = 0; i < nd; ++i) {
                    const HF__VEC *di = d + 3 * i;
                    HF__VEC cand[3], pen, dot, up, hold;
                    HF__UNROLL for (w = 0; w < 3; ++w)
                        cand[w] = HF__VADD(p[w], HF__VMUL(l, di[w]));
                    pen = HF__KN(hf__ftl_penetration)(k, rr, ncol, cand, &hold,
                                                      NULL, NULL, NULL);
                    dot = HF__VDOT3(di[0], di[1], di[2], u[0], u[1], u[2]);
                    up = HF__VOR(HF__VLT(pen, best_pen),
                                 HF__VAND(HF__VEQ(pen, best_pen),
                                          HF__VGT(dot, best_dot)));
                    up = HF__VAND(HF__VAND(need, valid),
                                  HF__VAND(keep[i], up));
                    best_pen = HF__VSEL(up, pen, best_pen);
                    best_dot = HF__VSEL(up, dot, best_dot);
                    HF__UNROLL for (w = 0; w < 3; ++w)
                        best[w] = HF__VSEL(up, cand[w], best[w]);
                }
            }
        }
        act = HF__VAND(act, HF__VLT(best_pen, pen0)); /* no progress: done */
    }
    *out_pen = best_pen;
}

/* hf__ftl_collide_one for point row j of ropes idx[0 .. W) (any ropes:
   the points in contact, gathered) against colliders k[0 .. ncol), ncol
   <= HF__FTL_NEAR, in the order of the call's array: the colliders
   relevant to every lane's point (hf__ftl_flush groups the points so), so
   each lane gets the bytes of its own point's scalar kernel. */
HF__VTARGET HF__INLINE void
HF__KN(hf__ftl_collide_in)(hf_ropes *ro, const float *F, int j, const int *idx,
                           const HF__KN(hf__col) *k, int ncol)
{
    const size_t R = (size_t)ro->rope_count, o0 = (size_t)(j - 1) * R;
    const HF__VEC zero = HF__VSET1(0.0f);
    float g[3][HF__W];
    HF__VEC l, p[3], q[3], root[3], n[3], t[3], u[3], v[3], best[3],
        rr[HF__FTL_NEAR], act, best_pen, bd, big, cw[3], rw, cn;
    int c, i, round;
    HF__UNROLL for (c = 0; c < 3; ++c) {
        const float *X = c == 0 ? ro->x : c == 1 ? ro->y : ro->z;
        p[c] = HF__VGATHER(X + o0, idx);
        q[c] = HF__VGATHER(X + o0 + R, idx);
        root[c] = HF__VGATHER(X, idx);
        t[c] = HF__VGATHER(F + (size_t)(3 + c) * R, idx);
        n[c] = HF__VGATHER(F + (size_t)(6 + c) * R, idx);
        v[c] = HF__VSUB(HF__VGATHER((c == 0   ? ro->px
                                     : c == 1 ? ro->py
                                              : ro->pz) +
                                        o0 + R,
                                    idx),
                        p[c]);
    }
    l = HF__VGATHER(ro->rest_length + o0, idx);
    /* hf__col_radius_for */
    for (c = 0; c < ncol; ++c) {
        HF__VEC cc[3];
        const HF__VEC d2 = HF__KN(hf__col_closest)(k + c, root, cc);
        rr[c] = k[c].rr;
        if (k[c].shrink)
            rr[c] = HF__VSEL(HF__VAND(HF__VGT(k[c].inner, zero),
                                      HF__VLT(d2, HF__VMUL(k[c].inner,
                                                           k[c].inner))),
                             HF__VSQRT(d2), rr[c]);
    }
    cn = rw = cw[0] = cw[1] = cw[2] = zero; /* set for ncol >= 1 */
    best_pen =
        HF__KN(hf__ftl_penetration)(k, rr, ncol, q, &act, cw, &rw, &cn);
    act = HF__VAND(act, HF__VGT(l, zero));
    if (!HF__VMASK(act)) return;
    HF__UNROLL for (i = 0; i < 3; ++i) u[i] = HF__VSUB(q[i], p[i]);
    bd = HF__VDOT3(u[0], u[1], u[2], u[0], u[1], u[2]);
    big = HF__VGT(bd, HF__VSET1(1e-24f));
    bd = HF__VDIV(HF__VSET1(1.0f), HF__VSQRT(bd));
    HF__UNROLL for (i = 0; i < 3; ++i) {
        u[i] = HF__VSEL(big, HF__VMUL(u[i], bd), n[i]);
        best[i] = q[i];
    }
    { /* hf__ftl_collide_point's quick answer */
        HF__VEC from[3], mq[3], cq, d[3], cand[3], hold, crease, go = act;
        HF__UNROLL for (i = 0; i < 3; ++i) from[i] = u[i];
        for (round = 0; round < HF__FTL_QUICK && HF__VMASK(go); ++round) {
            HF__VEC pen, ok;
            const HF__VEC was = cn;
            HF__KN(hf__ftl_cap)(p, l, cw, rw, n, mq, &cq);
            HF__KN(hf__ftl_onto_cap)(from, mq, cq, t, d);
            HF__UNROLL for (i = 0; i < 3; ++i)
                cand[i] = HF__VADD(p[i], HF__VMUL(l, d[i]));
            /* cw, rw: the next ball, where the point is still inside */
            pen = HF__KN(hf__ftl_penetration)(k, rr, ncol, cand, &hold, cw,
                                              &rw, &cn);
            ok = HF__VAND(go, HF__VLE(pen, zero));
            HF__UNROLL for (i = 0; i < 3; ++i) {
                best[i] = HF__VSEL(ok, cand[i], best[i]);
                from[i] = d[i];
            }
            best_pen = HF__VSEL(ok, zero, best_pen);
            go = HF__VAND(go, HF__VGT(pen, zero));
            crease = HF__VSEL(HF__VEQ(cn, was), zero, go);
            if (HF__VMASK(crease)) /* along the crease */
                HF__KN(hf__ftl_crease)(k, rr, ncol, p, l, n, v, was, cn, mq,
                                       cq, cw, rw, crease, best, &best_pen);
            /* the lanes in a crease: done here or in the rounds */
            go = HF__VAND(go, HF__VEQ(cn, was));
        }
    }
    if (HF__VMASK(HF__VAND(act, HF__VGT(best_pen, zero))))
        HF__KN(hf__ftl_rounds)(k, rr, ncol, p, l, n, t, u, v, act, best,
                               &best_pen);
    HF__UNROLL for (c = 0; c < 3; ++c) HF__VST(g[c], best[c]);
    for (i = 0; i < HF__W; ++i) {
        const size_t o = o0 + R + (size_t)idx[i];
        ro->x[o] = g[0][i];
        ro->y[o] = g[1][i];
        ro->z[o] = g[2][i];
    }
}

/* The points of row j in contact, resolved when the list fills and when
   the row ends. Each point's relevant colliders (hf__ftl_relevant, in the
   order of the call's array) are the ones it goes through the contact
   kernel against, W points at a time, each lane with its own (the
   kernel's cost grows with the cube of their count, so a group takes
   points with as many as its own: most have one or two). A point with
   more than HF__FTL_NEAR goes alone through the scalar kernel, which
   walks them in batches. One and two colliders, the common cases, as
   constants, so the compiler unrolls the collider loops. */
HF__VTARGET HF__PRIVATE void HF__KN(hf__ftl_flush)(hf_ropes *ro, const float *F,
                                                   int j, hf__ftl_hits *h,
                                                   const hf__bp *bp)
{
    const size_t R = (size_t)ro->rope_count, o0 = (size_t)(j - 1) * R;
    const HF__VEC zero = HF__VSET1(0.0f), one = HF__VSET1(1.0f);
    /* the points' parents x, y, z and segments; their relevant colliders
       (indices into the union, as floats) and how many */
    float pl[4][HF__FTL_HITS], sl[HF__FTL_NEAR][HF__FTL_HITS],
        nl[HF__FTL_HITS];
    int list[HF__FTL_HITS], top;
    HF__KN(hf__col) k[HF__FTL_NEAR];
    HF__VEC had[HF__FTL_NEAR]; /* the colliders k holds, as sl */
    hf__cols cl;
    /* each W's greatest count, and the greatest (HF__FTL_NEAR + 1: more) */
    unsigned char most[HF__FTL_HITS / HF__W];
    const int huge = bp->nu >= (1 << 24);
    int g, i, m, c, n, hi, idx[HF__W];
    /* The relevant colliders: the points' parents and segments gathered
       once (the last lane repeated), then each collider of the chunk's
       union that the row reaches prepared once and tested against them,
       W at a time, each lane keeping its first HF__FTL_NEAR in the
       array's order by selects. A collider relevant to a point is in its
       tile's list, at a row it reaches: the broadphase keeps every
       collider a rope can reach. (A union too large for a float's whole
       numbers, beyond any body, goes through the scalar kernel.) */
    for (g = 0; g < h->n; g += HF__W) {
        for (i = 0; i < HF__W; ++i)
            idx[i] = h->r[g + i < h->n ? g + i : h->n - 1];
        HF__VST(pl[0] + g, HF__VGATHER(ro->x + o0, idx));
        HF__VST(pl[1] + g, HF__VGATHER(ro->y + o0, idx));
        HF__VST(pl[2] + g, HF__VGATHER(ro->z + o0, idx));
        HF__VST(pl[3] + g, HF__VGATHER(ro->rest_length + o0, idx));
        HF__VST(nl + g, huge ? HF__VSET1(HF__FTL_NEAR + 1) : zero);
        for (i = 0; i < HF__FTL_NEAR; ++i) HF__VST(sl[i] + g, zero);
        most[g / HF__W] = (unsigned char)(huge ? HF__FTL_NEAR + 1 : 0);
    }
    for (c = 0; c < bp->nu && !huge; ++c) {
        const HF__VEC cf = HF__VSET1((float)c);
        HF__KN(hf__col) v;
        hf__col_prep spare;
        if (hf__bp_union_row(bp, c) > j) continue;
        HF__KN(hf__col_prep)(hf__bp_union_at(bp, c, &spare), &v);
        for (g = 0; g < h->n; g += HF__W) {
            const HF__VEC p[3] = {HF__VLD(pl[0] + g), HF__VLD(pl[1] + g),
                                  HF__VLD(pl[2] + g)};
            const HF__VEC rel =
                HF__KN(hf__ftl_relevant)(&v, p, HF__VLD(pl[3] + g));
            HF__VEC cn;
            int s;
            if (!HF__VMASK(rel)) continue;
            cn = HF__VLD(nl + g);
            for (s = 0; s <= most[g / HF__W] && s < HF__FTL_NEAR; ++s) {
                const HF__VEC at = HF__VAND(rel, HF__VEQ(cn, HF__VSET1(s)));
                if (HF__VMASK(at))
                    HF__VST(sl[s] + g, HF__VSEL(at, cf, HF__VLD(sl[s] + g)));
            }
            if (most[g / HF__W] <= HF__FTL_NEAR) ++most[g / HF__W];
            HF__VST(nl + g, HF__VADD(cn, HF__VAND(rel, one)));
        }
    }
    for (c = 0; c < HF__FTL_NEAR; ++c) had[c] = HF__VSET1(-1.0f);
    for (g = hi = 0; g < h->n; g += HF__W)
        hi = most[g / HF__W] > hi ? most[g / HF__W] : hi;
    /* a point with more than HF__FTL_NEAR: the scalar kernel */
    for (g = 0; g < h->n && hi > HF__FTL_NEAR; g += HF__W) {
        unsigned bits = (unsigned)HF__VMASK(
            HF__VGT(HF__VLD(nl + g), HF__VSET1(HF__FTL_NEAR)));
        if (h->n - g < HF__W) bits &= (1u << (h->n - g)) - 1u;
        for (; bits; bits &= bits - 1u) {
            const int r = h->r[g + hf__lowest_bit(bits)];
            HF__VZEROUPPER();
            hf__bp_tile(bp, r, &cl);
            hf__ftl_collide_one(ro, F, j, r, &cl);
        }
    }
    /* the points of each count n, W at a time (the last lane repeated),
       each lane with its own colliders */
    for (n = 1; n <= HF__FTL_NEAR && n <= hi; ++n) {
        const HF__VEC nv = HF__VSET1((float)n);
        for (g = top = 0; g < h->n; g += HF__W) {
            unsigned bits = (unsigned)HF__VMASK(HF__VEQ(HF__VLD(nl + g), nv));
            if (h->n - g < HF__W) bits &= (1u << (h->n - g)) - 1u;
            for (; bits; bits &= bits - 1u) list[top++] = g + hf__lowest_bit(bits);
        }
        for (m = 0; m < top; m += HF__W) {
            const int got = top - m < HF__W ? top - m : HF__W;
            int e;
            for (e = 0; e < HF__W; ++e)
                idx[e] = list[m + (e < got ? e : got - 1)];
            for (c = 0; c < n; ++c) { /* the last group's, where the same */
                const HF__VEC id = HF__VGATHER(sl[c], idx);
                if (HF__VMASK(HF__VEQ(id, had[c])) != HF__VALL)
                    HF__KN(hf__col_lanes)(bp, id, k + c);
                had[c] = id;
            }
            for (e = 0; e < HF__W; ++e) idx[e] = h->r[idx[e]];
            if (n == 1)
                HF__KN(hf__ftl_collide_in)(ro, F, j, idx, k, 1);
            else if (n == 2)
                HF__KN(hf__ftl_collide_in)(ro, F, j, idx, k, 2);
            else
                HF__KN(hf__ftl_collide_in)(ro, F, j, idx, k, n);
        }
    }
    h->n = 0;
}

/* Row j's points r + i for the bits i of m, which some collider holds:
   onto the list, flushed when full. */
HF__VTARGET HF__INLINE void HF__KN(hf__ftl_list)(hf_ropes *ro, const float *F,
                                                 int j, int r, int m,
                                                 hf__ftl_hits *h,
                                                 const hf__bp *bp)
{
    int i;
    for (i = r; m; ++i, m >>= 1) {
        if (!(m & 1)) continue;
        h->r[h->n++] = i;
        if (h->n == HF__FTL_HITS) HF__KN(hf__ftl_flush)(ro, F, j, h, bp);
    }
}

/* The sub-step's row kernels (ropes [a, b), b - a a multiple of W, a rope
   per lane), each with the operations of its scalar reference, written
   once like the contact kernels, with the safety net's test of every
   point row (hf__ropes_mark_far_v<W>, whole groups from a).
   HF__VZEROUPPER() ends each (see HF__TARGET_AVX2). */
/* The root pinned to the frame F (hf__ropes_integrate_v1's last loop). */
HF__VTARGET HF__PRIVATE void
HF__KN(hf__ropes_pin_root)(hf_ropes *ro, const float *F, int a, int b)
{
    const size_t R = (size_t)ro->rope_count;
    const float *f[12];
    int r;
    hf__frame_rows(F, R, f);
    for (r = a; r < b; r += HF__W) {
        const HF__VEC u = HF__VLD(ro->rest_u + r), v = HF__VLD(ro->rest_v + r),
                      w = HF__VLD(ro->rest_w + r);
        HF__VST(ro->px + r, HF__VLD(ro->x + r));
        HF__VST(ro->py + r, HF__VLD(ro->y + r));
        HF__VST(ro->pz + r, HF__VLD(ro->z + r));
        HF__VST(ro->x + r,
                HF__VPOSE(HF__VLD(f[0] + r), HF__VLD(f[3] + r),
                          HF__VLD(f[6] + r), HF__VLD(f[9] + r), u, v, w));
        HF__VST(ro->y + r,
                HF__VPOSE(HF__VLD(f[1] + r), HF__VLD(f[4] + r),
                          HF__VLD(f[7] + r), HF__VLD(f[10] + r), u, v, w));
        HF__VST(ro->z + r,
                HF__VPOSE(HF__VLD(f[2] + r), HF__VLD(f[5] + r),
                          HF__VLD(f[8] + r), HF__VLD(f[11] + r), u, v, w));
    }
    HF__VZEROUPPER();
}

/* Row j: Verlet integration and the global pull toward the rest place. */
HF__VTARGET HF__PRIVATE void
HF__KN(hf__ropes_integrate_row)(hf_ropes *ro, const float *F, int j, int a,
                                int b, const hf__rope_step *st)
{
    const size_t R = (size_t)ro->rope_count;
    const int P = ro->points;
    const float *AX = HF__ROW(ro->scratch, HF__RS_A, R),
                *AY = HF__ROW(ro->scratch, HF__RS_A + 1, R),
                *AZ = HF__ROW(ro->scratch, HF__RS_A + 2, R),
                *VF = HF__ROW(ro->scratch, HF__RS_VF, R);
    const float *f[12];
    float *X = HF__ROW(ro->x, j, R), *Y = HF__ROW(ro->y, j, R),
          *Z = HF__ROW(ro->z, j, R);
    float *PX = HF__ROW(ro->px, j, R), *PY = HF__ROW(ro->py, j, R),
          *PZ = HF__ROW(ro->pz, j, R);
    const float *u = HF__ROW(ro->rest_u, j, R),
                *v = HF__ROW(ro->rest_v, j, R),
                *w = HF__ROW(ro->rest_w, j, R);
    const float kgj = st->ktab ? st->kg[j] : hf__rope_kg(st, j, P);
    const int pull = (st->k_root > 0.0f || st->global_on) && !(kgj <= 0.0f);
    const HF__VEC kg = HF__VSET1(kgj);
    int r;
    hf__frame_rows(F, R, f);
    for (r = a; r < b; r += HF__W) {
        const HF__VEC vf = HF__VLD(VF + r);
        HF__VEC x = HF__VLD(X + r), y = HF__VLD(Y + r), z = HF__VLD(Z + r);
        const HF__VEC vx = HF__VMUL(HF__VSUB(x, HF__VLD(PX + r)), vf),
                      vy = HF__VMUL(HF__VSUB(y, HF__VLD(PY + r)), vf),
                      vz = HF__VMUL(HF__VSUB(z, HF__VLD(PZ + r)), vf);
        HF__VST(PX + r, x);
        HF__VST(PY + r, y);
        HF__VST(PZ + r, z);
        x = HF__VADD(x, HF__VADD(vx, HF__VLD(AX + r)));
        y = HF__VADD(y, HF__VADD(vy, HF__VLD(AY + r)));
        z = HF__VADD(z, HF__VADD(vz, HF__VLD(AZ + r)));
        if (pull) {
            const HF__VEC uu = HF__VLD(u + r), vv = HF__VLD(v + r),
                          ww = HF__VLD(w + r);
            HF__VEC g;
            g = HF__VPOSE(HF__VLD(f[0] + r), HF__VLD(f[3] + r),
                          HF__VLD(f[6] + r), HF__VLD(f[9] + r), uu, vv, ww);
            x = HF__VADD(x, HF__VMUL(kg, HF__VSUB(g, x)));
            g = HF__VPOSE(HF__VLD(f[1] + r), HF__VLD(f[4] + r),
                          HF__VLD(f[7] + r), HF__VLD(f[10] + r), uu, vv, ww);
            y = HF__VADD(y, HF__VMUL(kg, HF__VSUB(g, y)));
            g = HF__VPOSE(HF__VLD(f[2] + r), HF__VLD(f[5] + r),
                          HF__VLD(f[8] + r), HF__VLD(f[11] + r), uu, vv, ww);
            z = HF__VADD(z, HF__VMUL(kg, HF__VSUB(g, z)));
        }
        HF__VST(X + r, x);
        HF__VST(Y + r, y);
        HF__VST(Z + r, z);
    }
    HF__VZEROUPPER();
}

/* Row j's local shape: segment m = j - 1's world rest direction into the
   scratch rows Q[m & 1] (the child direction q of point j + 1's turn, the
   parent direction p of point j + 2's), then point j turned as in
   hf__ropes_local_shape_v1 at its j = m; the next row is prefetched. */
HF__VTARGET HF__PRIVATE void
HF__KN(hf__ropes_local_row)(hf_ropes *ro, const float *F, int j, int a, int b,
                            const hf__rope_step *st, float *Q[2][3])
{
    const size_t R = (size_t)ro->rope_count;
    const int P = ro->points;
    const float *f[12];
    const float *u = HF__ROW(ro->rest_u, j, R),
                *v = HF__ROW(ro->rest_v, j, R),
                *w = HF__ROW(ro->rest_w, j, R);
    float *X = HF__ROW(ro->x, j, R), *Y = HF__ROW(ro->y, j, R),
          *Z = HF__ROW(ro->z, j, R);
    const HF__VEC one = HF__VSET1(1.0f);
    const int m = j - 1;
    const float klm = m < 1      ? 0.0f
                      : st->ktab ? st->kl[m]
                                 : hf__rope_kl(st, m, P);
    int r;
    hf__frame_rows(F, R, f);
    {
        /* q of segment m */
        const float *u1 = HF__ROW(ro->rest_u, m, R),
                    *v1 = HF__ROW(ro->rest_v, m, R),
                    *w1 = HF__ROW(ro->rest_w, m, R);
        float *QX = Q[m & 1][0], *QY = Q[m & 1][1], *QZ = Q[m & 1][2];
        for (r = a; r < b; r += HF__W) {
            const HF__VEC qu = HF__VSUB(HF__VLD(u + r), HF__VLD(u1 + r)),
                          qv = HF__VSUB(HF__VLD(v + r), HF__VLD(v1 + r)),
                          qw = HF__VSUB(HF__VLD(w + r), HF__VLD(w1 + r));
            HF__VST(QX + r, HF__VDOT3(HF__VLD(f[3] + r), HF__VLD(f[6] + r),
                                      HF__VLD(f[9] + r), qu, qv, qw));
            HF__VST(QY + r, HF__VDOT3(HF__VLD(f[4] + r), HF__VLD(f[7] + r),
                                      HF__VLD(f[10] + r), qu, qv, qw));
            HF__VST(QZ + r, HF__VDOT3(HF__VLD(f[5] + r), HF__VLD(f[8] + r),
                                      HF__VLD(f[11] + r), qu, qv, qw));
        }
    }
    if (m >= 1 && !(klm <= 0.0f)) {
        /* the local shape of hf__ropes_sim_run at its j = m */
        const float *X0 = HF__ROW(ro->x, m - 1, R),
                    *Y0 = HF__ROW(ro->y, m - 1, R),
                    *Z0 = HF__ROW(ro->z, m - 1, R);
        const float *X1 = HF__ROW(ro->x, m, R), *Y1 = HF__ROW(ro->y, m, R),
                    *Z1 = HF__ROW(ro->z, m, R);
        const float *L = HF__ROW(ro->rest_length, m - 1, R);
        const float *QX = Q[m & 1][0], *QY = Q[m & 1][1], *QZ = Q[m & 1][2];
        const float *PX_ = Q[(m + 1) & 1][0], *PY_ = Q[(m + 1) & 1][1],
                    *PZ_ = Q[(m + 1) & 1][2];
        const HF__VEC kl = HF__VSET1(klm);
        const int pf = j + 1 < P;
        for (r = a; r < b; r += HF__W) {
            const HF__VEC x1 = HF__VLD(X1 + r), y1 = HF__VLD(Y1 + r),
                          z1 = HF__VLD(Z1 + r), l = HF__VLD(L + r);
            const HF__VEC qx = HF__VLD(QX + r), qy = HF__VLD(QY + r),
                          qz = HF__VLD(QZ + r);
            HF__VEC px_, py_, pz_, bx, by, bz, b2, ok, ia, ib, cc, kx, ky, kz,
                kd, den, rx, ry, rz, x2, y2, z2;
            int all_ok;
            if (pf && ((r - a) & 15) == 0) /* the next row */
                hf__ropes_prefetch_row(ro, j + 1, r);
            bx = HF__VSUB(x1, HF__VLD(X0 + r));
            by = HF__VSUB(y1, HF__VLD(Y0 + r));
            bz = HF__VSUB(z1, HF__VLD(Z0 + r));
            b2 = HF__VDOT3(bx, by, bz, bx, by, bz);
            ok = HF__VAND(HF__VGT(l, HF__VSET1(1e-12f)),
                          HF__VGT(b2, HF__VSET1(1e-24f)));
            all_ok = HF__VMASK(ok) == HF__VALL;
            ia = HF__VDIV(one, l);
            ib = HF__VDIV(one, HF__VSQRT(b2));
            if (!all_ok) { /* the scalar's 0 (lanes may divide by 0) */
                ia = HF__VAND(ok, ia);
                ib = HF__VAND(ok, ib);
            }
            px_ = HF__VMUL(HF__VLD(PX_ + r), ia);
            py_ = HF__VMUL(HF__VLD(PY_ + r), ia);
            pz_ = HF__VMUL(HF__VLD(PZ_ + r), ia);
            bx = HF__VMUL(bx, ib);
            by = HF__VMUL(by, ib);
            bz = HF__VMUL(bz, ib);
            cc = HF__VDOT3(px_, py_, pz_, bx, by, bz);
            if (!all_ok) cc = HF__VSEL(ok, cc, one);
            kx = HF__VSUB(HF__VMUL(py_, bz), HF__VMUL(pz_, by));
            ky = HF__VSUB(HF__VMUL(pz_, bx), HF__VMUL(px_, bz));
            kz = HF__VSUB(HF__VMUL(px_, by), HF__VMUL(py_, bx));
            kd = HF__VDOT3(kx, ky, kz, qx, qy, qz);
            /* maxps(a, b) is a > b ? a : b, NaN included: the scalar's */
            den = HF__VDIV(kd, HF__VMAX(HF__VADD(one, cc), HF__VSET1(1e-6f)));
            /* r = q cc + k x q + k den, turned q */
            rx =
                HF__VADD(HF__VADD(HF__VMUL(qx, cc),
                                  HF__VSUB(HF__VMUL(ky, qz), HF__VMUL(kz, qy))),
                         HF__VMUL(kx, den));
            ry =
                HF__VADD(HF__VADD(HF__VMUL(qy, cc),
                                  HF__VSUB(HF__VMUL(kz, qx), HF__VMUL(kx, qz))),
                         HF__VMUL(ky, den));
            rz =
                HF__VADD(HF__VADD(HF__VMUL(qz, cc),
                                  HF__VSUB(HF__VMUL(kx, qy), HF__VMUL(ky, qx))),
                         HF__VMUL(kz, den));
            x2 = HF__VLD(X + r);
            y2 = HF__VLD(Y + r);
            z2 = HF__VLD(Z + r);
            x2 = HF__VADD(x2, HF__VMUL(kl, HF__VSUB(HF__VADD(x1, rx), x2)));
            y2 = HF__VADD(y2, HF__VMUL(kl, HF__VSUB(HF__VADD(y1, ry), y2)));
            z2 = HF__VADD(z2, HF__VMUL(kl, HF__VSUB(HF__VADD(z1, rz), z2)));
            HF__VST(X + r, x2);
            HF__VST(Y + r, y2);
            HF__VST(Z + r, z2);
        }
    }
    HF__VZEROUPPER();
}

/* hf__ftl_bend_damp on the W ropes from r (rows j - 2 .. j, j >= 2), in
   two halves so that the row's placement runs between them: first
   (before row j is placed, as it reads only rows j - 2 and j - 1 and row
   j's previous positions) q turned by the parent segment's rotation, tq,
   and row j's previous positions, pj; c1 and p1 are row j - 1's
   positions and previous positions (before this row's correction), x,
   y, z each. */
HF__VTARGET HF__INLINE void HF__KN(hf__ftl_bend_turn)(const hf_ropes *ro,
                                                      int j, int r,
                                                      const HF__VEC *c1,
                                                      const HF__VEC *p1,
                                                      HF__VEC *tq, HF__VEC *pj)
{
    const size_t R = (size_t)ro->rope_count, o = (size_t)j * R + (size_t)r,
                 o2 = o - 2 * R;
    const HF__VEC one = HF__VSET1(1.0f), tiny = HF__VSET1(1e-15f);
    HF__VEC a[3], b[3], k[3], q[3], kq[3], a2, b2, c, ok, n, m, t, s, kd;
    int i;
    HF__UNROLL for (i = 0; i < 3; ++i) {
        const float *P = i == 0 ? ro->px : i == 1 ? ro->py : ro->pz;
        const float *X = i == 0 ? ro->x : i == 1 ? ro->y : ro->z;
        a[i] = HF__VSUB(p1[i], HF__VLD(P + o2));
        b[i] = HF__VSUB(c1[i], HF__VLD(X + o2));
        pj[i] = HF__VLD(P + o);
        q[i] = HF__VSUB(pj[i], p1[i]);
    }
    a2 = HF__VDOT3(a[0], a[1], a[2], a[0], a[1], a[2]);
    b2 = HF__VDOT3(b[0], b[1], b[2], b[0], b[1], b[2]);
    c = HF__VDOT3(a[0], a[1], a[2], b[0], b[1], b[2]);
    ok = HF__VAND(HF__VGT(a2, tiny), HF__VGT(b2, tiny));
    n = HF__VSQRT(HF__VMUL(a2, b2));
    m = HF__VMAX(HF__VADD(n, c), HF__VMUL(HF__VSET1(1e-6f), n));
    t = HF__VDIV(one, HF__VSEL(ok, HF__VMUL(n, m), one));
    s = HF__VMUL(m, t);
    HF__VCROSS3(k, a, b);
    HF__VCROSS3(kq, k, q);
    kd = HF__VMUL(HF__VDOT3(k[0], k[1], k[2], q[0], q[1], q[2]), t);
    /* (q c + k x q) s + k kd: the scalar reference's operations */
    HF__UNROLL for (i = 0; i < 3; ++i)
        tq[i] = HF__VSEL(ok,
                         HF__VADD(HF__VMUL(HF__VADD(HF__VMUL(q[i], c), kq[i]),
                                           s),
                                  HF__VMUL(k[i], kd)),
                         q[i]);
}

/* The second half, once row j is placed at c2: the lanes of comp get the
   new previous positions of row j, the others keep theirs. */
HF__VTARGET HF__INLINE void HF__KN(hf__ftl_bend_damp)(hf_ropes *ro, int j,
                                                      int r, HF__VEC cb,
                                                      HF__VEC comp,
                                                      const HF__VEC *c1,
                                                      const HF__VEC *c2,
                                                      const HF__VEC *tq,
                                                      const HF__VEC *pj)
{
    const size_t R = (size_t)ro->rope_count, o = (size_t)j * R + (size_t)r;
    float *const p[3] = {ro->px + o, ro->py + o, ro->pz + o};
    int k;
    HF__UNROLL
    for (k = 0; k < 3; ++k)
        HF__VST(p[k],
                HF__VSEL(comp,
                         HF__VADD(pj[k],
                                  HF__VMUL(cb, HF__VSUB(HF__VSUB(c2[k], c1[k]),
                                                        tq[k]))),
                         pj[k]));
}

/* Row j's follow-the-leader placement (or, for the distance solver, the
   root segment), then its collisions: the points some collider holds are
   listed, and resolved W at a time by the contact kernel. */
HF__VTARGET HF__PRIVATE void
HF__KN(hf__ropes_ftl_row)(hf_ropes *ro, const float *F, int j, int a, int b,
                          const hf__rope_step *st, const hf__bp *bp)
{
    const size_t R = (size_t)ro->rope_count;
    const float *f[12];
    float *X0 = HF__ROW(ro->x, j - 1, R), *Y0 = HF__ROW(ro->y, j - 1, R),
          *Z0 = HF__ROW(ro->z, j - 1, R);
    float *X1 = HF__ROW(ro->x, j, R), *Y1 = HF__ROW(ro->y, j, R),
          *Z1 = HF__ROW(ro->z, j, R);
    float *PX0 = HF__ROW(ro->px, j - 1, R), *PY0 = HF__ROW(ro->py, j - 1, R),
          *PZ0 = HF__ROW(ro->pz, j - 1, R);
    const float *L = HF__ROW(ro->rest_length, j - 1, R);
    const HF__VEC one = HF__VSET1(1.0f);
    const HF__VEC sd = HF__VSET1(j >= 2 ? st->ftl_damping : 0.0f),
                  cb = HF__VSET1(0.5f * (j >= 2 ? st->ftl_damping : 0.0f));
    hf__ftl_hits hits;
    hf__cols cl;
    int r;
    hf__frame_rows(F, R, f);
    hits.n = 0;
    cl.n = 0;
    for (r = a; r < b; r += HF__W) {
        const HF__VEC x0 = HF__VLD(X0 + r), y0 = HF__VLD(Y0 + r),
                      z0 = HF__VLD(Z0 + r);
        const HF__VEC ox = HF__VLD(X1 + r), oy = HF__VLD(Y1 + r),
                      oz = HF__VLD(Z1 + r);
        const HF__VEC l = HF__VLD(L + r);
        const HF__VEC p0[3] = {HF__VLD(PX0 + r), HF__VLD(PY0 + r),
                               HF__VLD(PZ0 + r)};
        HF__VEC dx = HF__VSUB(ox, x0), dy = HF__VSUB(oy, y0),
                dz = HF__VSUB(oz, z0), d2, deg, sc, comp, xyz[3];
        HF__VEC c0[3], tq[3], pj[3];
        int bend;
        d2 = HF__VDOT3(dx, dy, dz, dx, dy, dz);
        /* shorter than its rest length: FTL pushes the child out, and
           Mueller's correction is replaced by hf__ftl_bend_damp, whose
           turn (its square root and division) goes before the
           placement's own */
        comp = HF__VLT(d2, HF__VMUL(l, l));
        bend = st->ftl && j >= 2 && HF__VMASK(comp);
        c0[0] = x0;
        c0[1] = y0;
        c0[2] = z0;
        if (bend) HF__KN(hf__ftl_bend_turn)(ro, j, r, c0, p0, tq, pj);
        /* coincident points: grow along the root normal */
        deg = HF__VLT(d2, HF__VSET1(1e-24f));
        if (HF__VMASK(deg)) { /* rare: the selects */
            dx = HF__VSEL(deg, HF__VLD(f[6] + r), dx);
            dy = HF__VSEL(deg, HF__VLD(f[7] + r), dy);
            dz = HF__VSEL(deg, HF__VLD(f[8] + r), dz);
            d2 = HF__VSEL(deg, one, d2);
        }
        sc = HF__VDIV(l, HF__VSQRT(d2));
        xyz[0] = HF__VADD(x0, HF__VMUL(dx, sc));
        xyz[1] = HF__VADD(y0, HF__VMUL(dy, sc));
        xyz[2] = HF__VADD(z0, HF__VMUL(dz, sc));
        HF__VST(X1 + r, xyz[0]);
        HF__VST(Y1 + r, xyz[1]);
        HF__VST(Z1 + r, xyz[2]);
        if (!st->ftl) continue;
        {
            /* Mueller's correction on the parent where the segment was
               longer than its rest length; where it was shorter, the
               child's bend damped instead */
            HF__VEC p[3];
            p[0] = HF__VADD(p0[0], HF__VMUL(sd, HF__VSUB(xyz[0], ox)));
            p[1] = HF__VADD(p0[1], HF__VMUL(sd, HF__VSUB(xyz[1], oy)));
            p[2] = HF__VADD(p0[2], HF__VMUL(sd, HF__VSUB(xyz[2], oz)));
            if (bend) {
                HF__KN(hf__ftl_bend_damp)(ro, j, r, cb, comp, c0, xyz, tq,
                                          pj);
                p[0] = HF__VSEL(comp, p0[0], p[0]);
                p[1] = HF__VSEL(comp, p0[1], p[1]);
                p[2] = HF__VSEL(comp, p0[2], p[2]);
            }
            HF__VST(PX0 + r, p[0]);
            HF__VST(PY0 + r, p[1]);
            HF__VST(PZ0 + r, p[2]);
        }
        if (bp) {
            int m;
            if (((r - bp->a) & (HF__BP_TILE - 1)) == 0 || r == a)
                hf__bp_tile(bp, r, &cl); /* a new tile */
            m = HF__KN(hf__col_any)(&cl, j, xyz);
            if (m) HF__KN(hf__ftl_list)(ro, F, j, r, m, &hits, bp);
        }
    }
    if (st->ftl && bp) HF__KN(hf__ftl_flush)(ro, F, j, &hits, bp);
    HF__VZEROUPPER();
}

/* Row j of a distance pass: half the error to each end (equal masses). */
HF__VTARGET HF__PRIVATE void HF__KN(hf__ropes_distance_row)(hf_ropes *ro, int j,
                                                            int a, int b)
{
    const size_t R = (size_t)ro->rope_count;
    float *X0 = HF__ROW(ro->x, j - 1, R), *Y0 = HF__ROW(ro->y, j - 1, R),
          *Z0 = HF__ROW(ro->z, j - 1, R);
    float *X1 = HF__ROW(ro->x, j, R), *Y1 = HF__ROW(ro->y, j, R),
          *Z1 = HF__ROW(ro->z, j, R);
    const float *L = HF__ROW(ro->rest_length, j - 1, R);
    const HF__VEC half = HF__VSET1(0.5f);
    int r;
    for (r = a; r < b; r += HF__W) {
        const HF__VEC x0 = HF__VLD(X0 + r), y0 = HF__VLD(Y0 + r),
                      z0 = HF__VLD(Z0 + r), x1 = HF__VLD(X1 + r),
                      y1 = HF__VLD(Y1 + r), z1 = HF__VLD(Z1 + r);
        const HF__VEC dx = HF__VSUB(x1, x0), dy = HF__VSUB(y1, y0),
                      dz = HF__VSUB(z1, z0);
        const HF__VEC d2 = HF__VDOT3(dx, dy, dz, dx, dy, dz);
        const HF__VEC e =
            HF__VAND(HF__VGT(d2, HF__VSET1(1e-24f)),
                     HF__VSUB(half, HF__VDIV(HF__VMUL(half, HF__VLD(L + r)),
                                             HF__VSQRT(d2))));
        HF__VST(X0 + r, HF__VADD(x0, HF__VMUL(dx, e)));
        HF__VST(Y0 + r, HF__VADD(y0, HF__VMUL(dy, e)));
        HF__VST(Z0 + r, HF__VADD(z0, HF__VMUL(dz, e)));
        HF__VST(X1 + r, HF__VSUB(x1, HF__VMUL(dx, e)));
        HF__VST(Y1 + r, HF__VSUB(y1, HF__VMUL(dy, e)));
        HF__VST(Z1 + r, HF__VSUB(z1, HF__VMUL(dz, e)));
    }
    HF__VZEROUPPER();
}

/* hf__ropes_mark_far_row for every point row, on whole groups of W ropes
   from a; returns where the groups end. */
HF__VTARGET HF__PRIVATE int HF__KN(hf__ropes_mark_far)(const hf_ropes *ro,
                                                       int a, int b,
                                                       const float *KB,
                                                       float *VF)
{
    const size_t R = (size_t)ro->rope_count;
    int r = a, j;
    for (; r + HF__W <= b; r += HF__W) {
        const HF__VEC x0 = HF__VLD(ro->x + r), y0 = HF__VLD(ro->y + r),
                      z0 = HF__VLD(ro->z + r), kb = HF__VLD(KB + r);
        HF__VEC in =
            HF__VEQ(kb, kb); /* each row's d2 <= KB: false for NaN too */
        for (j = 1; j < ro->points; ++j) {
            const size_t o = (size_t)j * R + (size_t)r;
            const HF__VEC dx = HF__VSUB(HF__VLD(ro->x + o), x0),
                          dy = HF__VSUB(HF__VLD(ro->y + o), y0),
                          dz = HF__VSUB(HF__VLD(ro->z + o), z0);
            in = HF__VAND(in, HF__VLE(HF__VDOT3(dx, dy, dz, dx, dy, dz), kb));
        }
        HF__VST(VF + r, HF__VSEL(in, HF__VLD(VF + r), HF__VSET1(1.0f)));
    }
    HF__VZEROUPPER();
    return r;
}
#endif /* HF__PASS_ROPES */

#ifndef HF__PASS

/* ---- 6.8 the kernels per width, their dispatch, hf_ropes_step ----------- */
/* The rope kernels of one SIMD width (hf__rope_widths): a sub-step of
   ropes [a, b) (returns where it stopped: whole groups of its lanes, or
   all of them at width 1) and the safety net's test (likewise), and the
   row kernels that hf__ropes_substep_rows fuses into a sub-step (none at
   width 1: the scalar reference, hf__ropes_substep_v1, is a sub-step of
   its own). */
typedef struct hf__rope_rows {
    hf__isa isa;
    int (*substep)(hf_ropes *, const float *, int, int, const hf__rope_step *,
                   const hf__bp *, const struct hf__rope_rows *);
    int (*mark_far)(const hf_ropes *, int, int, const float *, float *);
    /* the distance solver's pushes out of a collider (hf__ropes_collide):
       row points [r, e) with their frame's normals; returns where it
       stopped (four lanes at every width above one) */
    int (*push)(const hf__col_prep *, float *, float *, float *, const float *,
                const float *, const float *, int, int);
    void (*pin_root)(hf_ropes *, const float *, int, int);
    void (*integrate)(hf_ropes *, const float *, int, int, int,
                      const hf__rope_step *);
    void (*local)(hf_ropes *, const float *, int, int, int,
                  const hf__rope_step *, float *[2][3]);
    void (*ftl)(hf_ropes *, const float *, int, int, int,
                const hf__rope_step *, const hf__bp *);
    void (*distance)(hf_ropes *, int, int, int);
} hf__rope_rows;

#if HF__V4
/* the rope kernels at four lanes (at eight and sixteen after
   hf__ropes_collide) */
#define HF__PASS HF__PASS_ROPES
#define HF__W 4
#include HF_HEADER_FILENAME

/* One sub-step with the row kernels k (ropes [a, b), whole groups of the
   kernels' width): what hf__ropes_substep_v1 does, with the same
   operations per rope. Loops still run across ropes (a chain of dependent
   square roots and divisions per rope, point after point, leaves no
   parallelism otherwise), but rows are fused where the order between them
   does not matter: the root pin first (rows 1.. never read row 0 before
   the local shape); then per row, integration with the global pull, and
   the local shape of the point before, which reads rows up to j only;
   each FTL placement, then its collisions (the non-FTL ones through the
   four-lane kernel at every width). Returns where the whole groups end. */
HF__PRIVATE int hf__ropes_substep_rows(hf_ropes *ro, const float *F, int a,
                                       int b, const hf__rope_step *st,
                                       const hf__bp *bp, const hf__rope_rows *k)
{
    const size_t R = (size_t)ro->rope_count;
    const int P = ro->points;
    float *Q[2][3];
    int j, it;
    b = a + (b - a) / k->isa.lanes * k->isa.lanes;
    if (b == a) return a;
    for (j = 0; j < 3; ++j) { /* scratch rows G: unused by simulated ropes */
        Q[0][j] = HF__ROW(ro->scratch, HF__RS_G + j, R);
        Q[1][j] = HF__ROW(ro->scratch, HF__RS_G + 3 + j, R);
    }
    k->pin_root(ro, F, a, b);
    for (j = 1; j < P; ++j) {
        k->integrate(ro, F, j, a, b, st);
        if (st->local_on) k->local(ro, F, j, a, b, st, Q);
    }
    for (it = 0; it < st->iterations; ++it) {
        for (j = 1; j < P; ++j)
            if (st->ftl || j == 1)
                k->ftl(ro, F, j, a, b, st, bp);
            else
                k->distance(ro, j, a, b);
        if (!st->ftl && bp) hf__ropes_collide(ro, F, a, b, bp, k);
    }
    if (st->iterations == 0 && bp) hf__ropes_collide(ro, F, a, b, bp, k);
    return b;
}
#endif

#if HF__V4
/* A collider's pushes on row points [r, e) (X, Y, Z, the frame's normals
   nx, ny, nz), four lanes tested at once, each hit pushed by the scalar
   code (the same bytes); returns where the whole groups end. */
HF__PRIVATE int hf__ropes_push_v4(const hf__col_prep *kp, float *X, float *Y,
                                  float *Z, const float *nx, const float *ny,
                                  const float *nz, int r, int e)
{
    hf__col_v4 kv;
    if (e - r < 4) return r;
    hf__col_prep_v4(kp, &kv);
    for (; r + 4 <= e; r += 4) {
        hf__v4 xyz[3];
        int m, i;
        xyz[0] = HF__LD(X + r);
        xyz[1] = HF__LD(Y + r);
        xyz[2] = HF__LD(Z + r);
        m = hf__col_hits_v4(&kv, xyz);
        for (i = 0; m; ++i, m >>= 1)
            if (m & 1)
                hf__col_push_out(kp, X + r + i, Y + r + i, Z + r + i, nx[r + i],
                                 ny[r + i], nz[r + i]);
    }
    return r;
}
#endif

/* The same, point by point: the reference; returns e. */
HF__PRIVATE int hf__ropes_push_v1(const hf__col_prep *kp, float *X, float *Y,
                                  float *Z, const float *nx, const float *ny,
                                  const float *nz, int r, int e)
{
    for (; r < e; ++r)
        hf__col_push_out(kp, X + r, Y + r, Z + r, nx[r], ny[r], nz[r]);
    return e;
}

/* The distance solver's collisions for ropes [a, b): per tile, the box
   of its points, and the colliders in order that meet it or the box of
   one kept before (a push leaves a point on the surface of the collider
   it left, inside that collider's box); each kept collider pushes every
   point of the tile it holds straight out, by the kernels kr and the
   narrower ones (push). */
HF__PRIVATE void hf__ropes_collide(hf_ropes *ro, const float *F, int a, int b,
                                   const hf__bp *bp, const hf__rope_rows *kr)
{
    const size_t R = (size_t)ro->rope_count;
    const float *nx = HF__ROW(F, 6, R), *ny = HF__ROW(F, 7, R),
                *nz = HF__ROW(F, 8, R);
    int x, e, j, r, c, k;
    for (x = a; x < b; x = e) {
        float lo[3], hi[3];
        e = b - x > HF__BP_TILE ? x + HF__BP_TILE : b;
        for (k = 0; k < 3; ++k) {
            const float *X = k == 0 ? ro->x : k == 1 ? ro->y : ro->z;
            lo[k] = hi[k] = X[R + (size_t)x];
            for (j = 1; j < ro->points; ++j)
                for (r = x; r < e; ++r) {
                    const float v = X[(size_t)j * R + (size_t)r];
                    lo[k] = v < lo[k] ? v : lo[k];
                    hi[k] = v > hi[k] ? v : hi[k];
                }
        }
        for (c = 0; c < bp->ncol; ++c) {
            float clo[3], chi[3];
            hf__col_prep kp;
            hf__col_box(bp->col + c, bp->margin, clo, chi);
            if (hf__box_gap(lo, hi, clo, chi) > 0.0f) continue;
            for (k = 0; k < 3; ++k) {
                lo[k] = clo[k] < lo[k] ? clo[k] : lo[k];
                hi[k] = chi[k] > hi[k] ? chi[k] : hi[k];
            }
            kp = hf__collider_prep(bp->col, c, bp->margin);
            for (j = 1; j < ro->points; ++j) {
                float *X = HF__ROW(ro->x, j, R), *Y = HF__ROW(ro->y, j, R),
                      *Z = HF__ROW(ro->z, j, R);
                const hf__rope_rows *kk;
                for (r = x, kk = kr; r < e; ++kk)
                    r = kk->push(&kp, X, Y, Z, nx, ny, nz, r, e);
            }
        }
    }
}

#if HF__AVX2
/* The rope kernels at eight lanes (AVX2), then sixteen (AVX-512): the
   same operations per rope, so the same bytes. */
#define HF__PASS HF__PASS_ROPES
#define HF__W 8
#include HF_HEADER_FILENAME
#if HF__AVX512
#define HF__PASS HF__PASS_ROPES
#define HF__W 16
#include HF_HEADER_FILENAME
#endif

#endif

/* hf__ropes_mark_far_row for every point row of ropes [a, b): the
   reference; returns b. */
HF__PRIVATE int hf__ropes_mark_far_v1(const hf_ropes *ro, int a, int b,
                                      const float *KB, float *VF)
{
    int j;
    for (j = 1; j < ro->points; ++j)
        hf__ropes_mark_far_row(ro, j, a, b, KB, VF);
    return b;
}

/* The rope kernels per width, widest first. The rows eight (sixteen)
   ropes a vector are each a function of its own, so no SSE code runs
   between them with the upper halves dirty. */
#define HF__ROPE_ROWS_AT(W)                                                    \
    hf__ropes_substep_rows, hf__ropes_mark_far_v##W, hf__ropes_push_v4,        \
        hf__ropes_pin_root_v##W, hf__ropes_integrate_row_v##W,                 \
        hf__ropes_local_row_v##W, hf__ropes_ftl_row_v##W,                      \
        hf__ropes_distance_row_v##W
static const hf__rope_rows hf__rope_widths[] = {
#if HF__AVX512
    {{HF__ISA_V16}, HF__ROPE_ROWS_AT(16)},
#endif
#if HF__AVX2
    {{HF__ISA_V8}, HF__ROPE_ROWS_AT(8)},
#endif
#if HF__V4
    {{HF__ISA_V4}, HF__ROPE_ROWS_AT(4)},
#endif
    {{HF__ISA_V1}, hf__ropes_substep_v1, hf__ropes_mark_far_v1,
     hf__ropes_push_v1, NULL, NULL, NULL, NULL, NULL}};
#undef HF__ROPE_ROWS_AT

/* The dispatch of a sub-step with the kernels st->rows (hf__rope_widths,
   resolved by hf__rope_step_setup): each width takes whole groups of its
   lanes from where the wider ones stopped, the scalar reference the
   rest. */
HF__PRIVATE void hf__ropes_substep(hf_ropes *ro, const float *F, int a, int b,
                                   const hf__rope_step *st, const hf__bp *bp)
{
    const hf__rope_rows *k;
    for (k = st->rows; a < b; ++k) a = k->substep(ro, F, a, b, st, bp, k);
}

/* The safety net's test of ropes [a, b), likewise. */
HF__PRIVATE void hf__ropes_mark_far(const hf_ropes *ro, int a, int b,
                                    const float *KB, float *VF,
                                    const hf__rope_step *st)
{
    const hf__rope_rows *k;
    for (k = st->rows; a < b; ++k) a = k->mark_far(ro, a, b, KB, VF);
}

/* After the sub-steps: remember the sub-step length, and reset a rope
   that an unstable setting threw further than 8 * length + 0.01 m from
   its root (the safety net that keeps every output finite). */
HF__PRIVATE void hf__ropes_safety_net(hf_ropes *ro, int a, int b,
                                      const hf__rope_step *st)
{
    const size_t R = (size_t)ro->rope_count;
    const float h = st->h;
    float *VF = HF__ROW(ro->scratch, HF__RS_VF, R),
          *KB = HF__ROW(ro->scratch, HF__RS_KB, R);
    int r;
    for (r = a; r < b; ++r) {
        float lim = 8.0f * ro->length[r] + 0.01f;
        ro->last_h[r] = h;
        KB[r] = lim * lim; /* reuse the row: squared limit */
        VF[r] = 0.0f;      /* reuse: 1 if the rope went bad */
    }
    hf__ropes_mark_far(ro, a, b, KB, VF, st);
    for (r = a; r < b; ++r)
        if (VF[r] != 0.0f) {
            float keep = ro->blend[r];
            hf__rope_reset_one(ro, r);
            ro->blend[r] = keep;
        }
}

/* Simulated ropes [a, b) (a run of one parameter set and mode), chunk
   by chunk (the broadphase's, hf__bp_build): every sub-step, the safety
   net and the roots' contacts of one chunk before the next. A chunk's
   rows stay in the core's cache across its sub-steps, and two threads'
   neighbouring ranges meet only where one has finished (two ranges swept
   row by row at once trade the cache lines at their edge every row).
   The bytes are those of any split. */
HF__PRIVATE void hf__ropes_sim_run(hf_ropes *ro, int a, int b,
                                   const hf__rope_step *st,
                                   const hf_collider *col, int ncol)
{
    hf__bp bp;
    int s, x, e;
    for (x = a; x < b; x = e) {
        if (ncol > 0)
            e = hf__bp_build(ro, x, b, col, ncol, st->margin, &bp);
        else
            e = b - x > HF__ROPE_CHUNK ? x + HF__ROPE_CHUNK : b;
        for (s = 0; s < st->n; ++s) {
            const float *F = hf__ropes_substep_prep(ro, x, e, st, s);
            hf__ropes_substep(ro, F, x, e, st, ncol > 0 ? &bp : NULL);
        }
        hf__ropes_safety_net(ro, x, e, st);
        hf__ropes_mark_roots(ro, x, e, ncol > 0 ? &bp : NULL);
    }
}

/* The roots' contacts of ropes [a, b) that are not simulated (they
   ignore colliders, but hf_ropes_roots_inside counts them too). */
HF__PRIVATE void hf__ropes_mark_roots_run(hf_ropes *ro, int a, int b,
                                          const hf__rope_step *st,
                                          const hf_collider *col, int ncol)
{
    hf__bp bp;
    int x, e;
    for (x = a; x < b; x = e) {
        if (ncol > 0)
            e = hf__bp_build(ro, x, b, col, ncol, st->margin, &bp);
        else
            e = b;
        hf__ropes_mark_roots(ro, x, e, ncol > 0 ? &bp : NULL);
    }
}

HF__PRIVATE int hf__rope_kind(const hf_ropes *ro, int r)
{
    if (ro->mode[r] != HF_ROPE_ANIMATED) return 0;
    return ro->blend[r] >= 1.0f ? 2 : 1;
}

/* Colliders: finite, a known type, coordinates and radius in range. */
HF__PRIVATE hf_result hf__colliders_check(const hf_collider *colliders,
                                          int collider_count)
{
    int c, k;
    if (collider_count < 0) return HF_ERROR_BAD_COUNT;
    if (collider_count > 0 && !colliders) return HF_ERROR_NULL_POINTER;
    for (c = 0; c < collider_count; ++c) {
        const hf_collider *o = colliders + c;
        for (k = 0; k < 3; ++k)
            if (!hf__finitef(o->a[k]) || !hf__finitef(o->b[k]))
                return HF_ERROR_NON_FINITE;
        if (!hf__finitef(o->radius)) return HF_ERROR_NON_FINITE;
        if ((o->type != HF_COLLIDER_SPHERE &&
             o->type != HF_COLLIDER_CAPSULE) ||
            !hf__rope_coord_ok(o->a) ||
            (o->type == HF_COLLIDER_CAPSULE && !hf__rope_coord_ok(o->b)) ||
            !(o->radius >= 0.0f && o->radius <= HF_ROPE_MAX_COORD))
            return HF_ERROR_BAD_PARAMETER;
    }
    return HF_OK;
}

/* The per-call constants of a step from resolved parameters: dt clamped
   and scaled, split into equal sub-steps, rates per sub-step. */
/* The sub-steps of a call of dt (resolved params): their count *n and
   length, returned; n * length is dt clamped and scaled. */
HF__PRIVATE float hf__rope_substeps(const hf_rope_params *params, float dt,
                                    int *n)
{
    float sdt, q;
    if (dt > params->max_dt) dt = params->max_dt;
    sdt = dt * params->time_scale;
    q = sdt / params->substep;
    *n = q >= (float)params->max_substeps ? params->max_substeps : (int)q;
    if ((float)*n < q * 0.9999f && *n < params->max_substeps) ++*n;
    if (*n < 1) *n = 1;
    return sdt / (float)*n;
}

HF__PRIVATE void hf__rope_step_setup(hf__rope_step *st,
                                     const hf_rope_params *params, float dt,
                                     int points)
{
    int k;
    st->h = hf__rope_substeps(params, dt, &st->n);
    st->keep = 1.0f - hf__rope_k(params->damping, st->h);
    st->k_root = hf__rope_k(params->root_stiffness, st->h);
    st->ftl = params->solver == HF_ROPE_SOLVER_FTL;
    st->iterations = params->iterations;
    /* FTL with colliders folded into its sweep is exact after one pass */
    if (st->ftl && st->iterations > 1) st->iterations = 1;
    st->ftl_damping = params->ftl_damping;
    st->margin = params->collision_margin;
    for (k = 0; k < 3; ++k) st->g[k] = params->gravity[k] + params->wind[k];
    st->turbulence = params->turbulence;
    st->turbulence_frequency = params->turbulence_frequency;
    st->blend_time = params->mode_blend_time;
    st->gs_root = params->global_stiffness_root;
    st->gs_tip = params->global_stiffness_tip;
    st->ls_root = params->local_stiffness_root;
    st->ls_tip = params->local_stiffness_tip;
    st->global_on = st->gs_root > 0.0f || st->gs_tip > 0.0f;
    st->local_on = st->ls_root > 0.0f || st->ls_tip > 0.0f;
    st->level = hf_simd_resolve(params->simd);
    st->pose = hf__kernels_for(hf__pose_widths, st->level);
    st->rows = hf__kernels_for(hf__rope_widths, st->level);
    st->ktab = points <= HF__ROPE_KTAB;
    if (st->ktab)
        for (k = 1; k < points; ++k) {
            st->kg[k] = hf__rope_kg(st, k, points);
            st->kl[k] = hf__rope_kl(st, k, points);
        }
}

HFDEF hf_result hf_ropes_roots_inside(const hf_ropes *ropes, int first,
                                      int count, int *out_count)
{
    int r, n = 0;
    if (!hf__ropes_ok(ropes) || !out_count) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    for (r = first; r < first + count; ++r) n += ropes->root_inside[r] != 0;
    *out_count = n;
    return HF_OK;
}

HFDEF hf_result hf_ropes_step(hf_ropes *ropes, int first, int count,
                              float dt, const hf_rope_params *params,
                              const hf_collider *colliders,
                              int collider_count)
{
    hf__rope_step st;
    hf_rope_params prm;
    hf_result res;
    int r, k, end;
    if (!hf__ropes_ok(ropes) || !params) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    if ((res = hf__colliders_check(colliders, collider_count)) != HF_OK)
        return res;
    if (!hf__finitef(dt) || !(dt > 0.0f)) return HF_ERROR_BAD_TIME_STEP;
    hf__rope_params_resolve(params, &prm);
    if ((res = hf__rope_params_check(&prm, NULL)) != HF_OK) return res;
    if (count == 0) return HF_OK;
    hf__rope_step_setup(&st, &prm, dt, ropes->points);

    /* runs of ropes of one kind, each with its kernel; the kinds depend
       only on each rope's own state, so any split gives the same bytes */
    end = first + count;
    for (r = first; r < end;) {
        int kind = hf__rope_kind(ropes, r), b = r + 1;
        while (b < end && hf__rope_kind(ropes, b) == kind) ++b;
        if (kind == 0) {
            hf__ropes_sim_run(ropes, r, b, &st, colliders, collider_count);
        } else {
            if (kind == 2)
                hf__ropes_animated_run(ropes, r, b, &st);
            else
                hf__ropes_glide_run(ropes, r, b, &st);
            hf__ropes_mark_roots_run(ropes, r, b, &st, colliders,
                                     collider_count);
        }
        r = b;
    }
    /* this frame becomes the start of the next step's interpolation */
    for (k = 0; k < 12; ++k)
        HF_MEMCPY(ropes->frame + (size_t)(12 + k) * (size_t)ropes->rope_count +
                      first,
                  ropes->frame + (size_t)k * (size_t)ropes->rope_count + first,
                  (size_t)count * sizeof(float));
    return HF_OK;
}

/* ---- 6.9 hair-hair interaction: the grid -------------------------------- */

/* Floats per z layer in hf_grid.slab: the cube (origin xyz, spacing), the
   point stride, then the layer's sums of the node weights and of their
   squares. Every layer holds the same cube and stride, so a reader takes
   layer 0's. */
enum { HF__GRID_SLAB = 7 };

HF__PRIVATE hf_result hf__grid_layout(int n, size_t *node_bytes,
                                      size_t *total)
{
    if (n < 4 || n > HF_GRID_MAX_RESOLUTION) return HF_ERROR_BAD_COUNT;
    /* 128^3 nodes x 16 bytes: 32 MiB, far from size_t's limit */
    *node_bytes = (size_t)n * (size_t)n * (size_t)n * 4u * sizeof(float);
    *total = 64u + *node_bytes + (size_t)n * HF__GRID_SLAB * sizeof(float);
    return HF_OK;
}

HFDEF hf_result hf_grid_memory_size(int resolution, size_t *out_size)
{
    size_t node_bytes, total;
    hf_result r;
    if (!out_size) return HF_ERROR_NULL_POINTER;
    r = hf__grid_layout(resolution, &node_bytes, &total);
    if (r == HF_OK) *out_size = total;
    return r;
}

HFDEF hf_result hf_grid_init(hf_grid *grid, int resolution, void *memory,
                             size_t memory_size)
{
    size_t node_bytes, total;
    unsigned char *at;
    hf_result r;
    if (!grid || !memory) return HF_ERROR_NULL_POINTER;
    r = hf__grid_layout(resolution, &node_bytes, &total);
    if (r != HF_OK) return r;
    if (memory_size < total) return HF_ERROR_BUFFER_TOO_SMALL;
    HF_MEMSET(memory, 0, total);
    at = (unsigned char *)memory;
    at += (64u - (size_t)((uintptr_t)at & 63u)) & 63u;
    HF_MEMSET(grid, 0, sizeof *grid);
    grid->resolution = resolution;
    grid->node = (float *)at;
    grid->slab = (float *)(at + node_bytes);
    return HF_OK;
}

HFDEF hf_result hf_grid_create(int resolution, const hf_allocator *alloc,
                               hf_grid **out_grid)
{
    size_t need, head = (sizeof(hf_grid) + 63u) & ~(size_t)63u;
    hf_grid *g;
    hf_result r;
    if (!out_grid) return HF_ERROR_NULL_POINTER;
    r = hf_grid_memory_size(resolution, &need);
    if (r != HF_OK) return r;
    g = (hf_grid *)hf__alloc(alloc, need + head);
    if (!g) return HF_ERROR_OUT_OF_MEMORY;
    r = hf_grid_init(g, resolution, (unsigned char *)g + head, need);
    HF_ASSERT(r == HF_OK);
    if (alloc) g->allocator = *alloc;
    g->owned = alloc ? 2 : 1;
    *out_grid = g;
    return HF_OK;
}

HFDEF void hf_grid_destroy(hf_grid *grid)
{
    if (!grid || !grid->owned) return;
    if (grid->owned == 2) {
        hf_allocator a = grid->allocator;
        hf__free(&a, grid);
    } else {
        hf__free(NULL, grid);
    }
}

/* The cube over ropes [0, rc) and the point stride: their roots where the
   points were computed (the previous-frame rows) grown by each rope's
   length (and 1 % and 0.1 mm for rounding), its largest side over
   resolution - 1 cells; every k-th point of each rope stands for the k
   from it (k points apart is about a cell, to the nearest point, on the
   rope of longest segments: the grid sees nothing finer). Every layer's
   call computes the same floats. */
HF__PRIVATE void hf__grid_cube(const hf_ropes *ro, int rc, int n,
                               float cube[5])
{
    const size_t R = (size_t)ro->rope_count;
    const float *cx = ro->frame + 12u * R, *cy = cx + R, *cz = cy + R;
    float lo[3], hi[3], side = 0.0f, longest = 0.0f, k;
    /* the bounds in six variables, not arrays: gcc kept the arrays in
       memory, each rope's minimum waiting for the last one's store */
    float lx = HF_ROPE_MAX_COORD * 16.0f, ly = lx, lz = lx;
    float hx = -lx, hy = -lx, hz = -lx;
    int r = 0, i;
#if HF__V4
    /* four ropes a step, each lane's bounds as the scalar loop's, then
       the lanes' (the smallest and largest of the same values: a minimum
       is one of them whatever the order, the compares skip NaN as the
       scalar ones do) */
    if (rc >= 4) {
        const float *c[3];
        const hf__v4 s101 = HF__SET1(1.01f), s1e4 = HF__SET1(1e-4f);
        hf__v4 vlo[3], vhi[3], vlong = HF__SET1(0.0f);
        int q;
        c[0] = cx;
        c[1] = cy;
        c[2] = cz;
        for (q = 0; q < 3; ++q) {
            vlo[q] = HF__SET1(lx);
            vhi[q] = HF__SET1(hx);
        }
        for (; r + 4 <= rc; r += 4) {
            const hf__v4 len = HF__LD(ro->length + r);
            const hf__v4 L = HF__ADD(HF__MUL(len, s101), s1e4);
            vlong = HF__MAX(len, vlong);
            HF__UNROLL for (q = 0; q < 3; ++q) {
                const hf__v4 x = HF__LD(c[q] + r), t = HF__SUB(x, L);
                vlo[q] = HF__SEL(HF__LT(t, vlo[q]), t, vlo[q]);
                vhi[q] = HF__MAX(HF__ADD(x, L), vhi[q]);
            }
        }
        lx = hf__v4_fold(vlo[0], lx, 0);
        hx = hf__v4_fold(vhi[0], hx, 1);
        ly = hf__v4_fold(vlo[1], ly, 0);
        hy = hf__v4_fold(vhi[1], hy, 1);
        lz = hf__v4_fold(vlo[2], lz, 0);
        hz = hf__v4_fold(vhi[2], hz, 1);
        longest = hf__v4_fold(vlong, longest, 1);
    }
#endif
    for (; r < rc; ++r) {
        const float L = ro->length[r] * 1.01f + 1e-4f;
        longest = ro->length[r] > longest ? ro->length[r] : longest;
        lx = cx[r] - L < lx ? cx[r] - L : lx;
        hx = cx[r] + L > hx ? cx[r] + L : hx;
        ly = cy[r] - L < ly ? cy[r] - L : ly;
        hy = cy[r] + L > hy ? cy[r] + L : hy;
        lz = cz[r] - L < lz ? cz[r] - L : lz;
        hz = cz[r] + L > hz ? cz[r] + L : hz;
    }
    lo[0] = lx;
    lo[1] = ly;
    lo[2] = lz;
    hi[0] = hx;
    hi[1] = hy;
    hi[2] = hz;
    for (i = 0; i < 3; ++i) {
        cube[i] = lo[i];
        side = hi[i] - lo[i] > side ? hi[i] - lo[i] : side;
    }
    cube[3] = side / (float)(n - 1);
    if (!(cube[3] >= 1e-6f)) cube[3] = 1e-6f;
    k = longest > 0.0f ? cube[3] * (float)(ro->points - 1) / longest : 1.0f;
    cube[4] = k >= 7.5f ? 8.0f : (k >= 1.0f ? (float)(int)(k + 0.5f) : 1.0f);
}

/* Grid coordinate of c along one axis: the cell k (0 .. n - 2) and the
   fraction f in it; 0 for a point outside the cube. */
HF__INLINE int hf__grid_axis(float c, float o, float inv, int n, int *k,
                             float *f)
{
    float q = (c - o) * inv;
    if (!(q >= 0.0f && q < (float)(n - 1))) return 0;
    *k = (int)q;
    *f = q - (float)*k;
    return 1;
}

/* The grid cell of point i and its place in it: the node index of the
   cell's low corner, its layer kz and the fractions; 0 for a point
   outside the cube. */
HF__INLINE int hf__grid_locate(const hf_ropes *ro, size_t i, const float *cube,
                               float inv, int n, size_t *node, int *kz,
                               float f[3])
{
    int kx, ky;
    if (!hf__grid_axis(ro->z[i], cube[2], inv, n, kz, &f[2]) ||
        !hf__grid_axis(ro->x[i], cube[0], inv, n, &kx, &f[0]) ||
        !hf__grid_axis(ro->y[i], cube[1], inv, n, &ky, &f[1]))
        return 0;
    *node = ((size_t)*kz * (size_t)n + (size_t)ky) * (size_t)n + (size_t)kx;
    return 1;
}

/* o[0..3] += w * v[0..3]: the 4 floats of a node (weight, momentum), as
   one four-lane operation where there is one (the same bytes; the build
   is bound by its stores, four times fewer so). */
HF__INLINE void hf__grid_add4(float *o, float w, const float *v)
{
#if HF__V4
    HF__ST(o, HF__ADD(HF__LD(o), HF__MUL(HF__SET1(w), HF__LD(v))));
#else
    o[0] += w * v[0];
    o[1] += w * v[1];
    o[2] += w * v[2];
    o[3] += w * v[3];
#endif
}

/* 1 / the last sub-step (0 before the first): a step of 10^-6 s or less
   counts as 10^-6 s, so that velocities stay finite whatever the time
   scale (1 / a denormal step is infinite). */
HF__INLINE float hf__grid_hv(float last_h)
{
    return last_h > 0.0f ? 1.0f / (last_h > 1e-6f ? last_h : 1e-6f) : 0.0f;
}

/* The velocity of point i of rope r, times `weight` (v[0] = weight). */
HF__INLINE void hf__grid_velocity(const hf_ropes *ro, size_t i, float hv,
                                  float weight, float v[4])
{
    v[0] = weight;
    v[1] = weight * ((ro->x[i] - ro->px[i]) * hv);
    v[2] = weight * ((ro->y[i] - ro->py[i]) * hv);
    v[3] = weight * ((ro->z[i] - ro->pz[i]) * hv);
}

/* Sum of the two corner weights' squares along one axis: a point's own
   share of the weight its trilinear read finds (in the product of the
   three axes). */
HF__INLINE float hf__grid_self(float f)
{
    return (1.0f - f) * (1.0f - f) + f * f;
}

/* The grid at a point (cell `node`, fractions f): the weight and momentum
   (a[0..3]) and the weight's gradient in grid units (g[0..2]: along each
   axis, the differences across the cell blended by the other two axes'
   weights), the point's own share (v, as hf__grid_velocity) taken out of
   both. */
HF__PRIVATE void hf__grid_read(const hf_grid *grid, size_t node,
                               const float f[3], const float v[4], float a[4],
                               float g[3])
{
    const size_t n = (size_t)grid->resolution, n2 = n * n;
    const float *q[8], wx0 = 1.0f - f[0], wy0 = 1.0f - f[1];
    const float wz0 = 1.0f - f[2];
    /* corner c = dx + 2 dy + 4 dz; weights of the y-z, x-z and x-y edges */
    const float wyz[4] = {wy0 * wz0, f[1] * wz0, wy0 * f[2], f[1] * f[2]};
    const float wxz[4] = {wx0 * wz0, f[0] * wz0, wx0 * f[2], f[0] * f[2]};
    const float wxy[4] = {wx0 * wy0, f[0] * wy0, wx0 * f[1], f[0] * f[1]};
    float sx, sy, sz, ms;
    int c, k;
    for (c = 0; c < 8; ++c)
        q[c] = grid->node + 4u * (node + (size_t)(c >> 2) * n2 +
                                  (size_t)((c >> 1) & 1) * n + (size_t)(c & 1));
    for (k = 0; k < 4; ++k) a[k] = 0.0f;
    for (c = 0; c < 4; ++c) {
        hf__grid_add4(a, wx0 * wyz[c], q[2 * c]);
        hf__grid_add4(a, f[0] * wyz[c], q[2 * c + 1]);
    }
    g[0] = wyz[0] * (q[1][0] - q[0][0]) + wyz[1] * (q[3][0] - q[2][0]) +
           wyz[2] * (q[5][0] - q[4][0]) + wyz[3] * (q[7][0] - q[6][0]);
    g[1] = wxz[0] * (q[2][0] - q[0][0]) + wxz[1] * (q[3][0] - q[1][0]) +
           wxz[2] * (q[6][0] - q[4][0]) + wxz[3] * (q[7][0] - q[5][0]);
    g[2] = wxy[0] * (q[4][0] - q[0][0]) + wxy[1] * (q[5][0] - q[1][0]) +
           wxy[2] * (q[6][0] - q[2][0]) + wxy[3] * (q[7][0] - q[3][0]);
    /* take the point's own share out: alone, it feels nothing */
    sx = hf__grid_self(f[0]);
    sy = hf__grid_self(f[1]);
    sz = hf__grid_self(f[2]);
    ms = sx * (sy * sz);
    for (k = 0; k < 4; ++k) a[k] -= ms * v[k];
    g[0] -= v[0] * ((2.0f * f[0] - 1.0f) * (sy * sz));
    g[1] -= v[0] * ((2.0f * f[1] - 1.0f) * (sx * sz));
    g[2] -= v[0] * ((2.0f * f[2] - 1.0f) * (sx * sy));
}

#if HF__V4
/* q[0..3] transposed: four lanes' four floats (a node's weight and
   momentum, or a point's velocity) to each float across the lanes, or
   back (the transpose is its own inverse). */
HF__INLINE void hf__grid_t4_v4(hf__v4 q[4])
{
#if HF__SSE
    _MM_TRANSPOSE4_PS(q[0], q[1], q[2], q[3]);
#else
    const float32x4x2_t t01 = vtrnq_f32(q[0], q[1]);
    const float32x4x2_t t23 = vtrnq_f32(q[2], q[3]);
    q[0] = vcombine_f32(vget_low_f32(t01.val[0]), vget_low_f32(t23.val[0]));
    q[1] = vcombine_f32(vget_low_f32(t01.val[1]), vget_low_f32(t23.val[1]));
    q[2] = vcombine_f32(vget_high_f32(t01.val[0]), vget_high_f32(t23.val[0]));
    q[3] = vcombine_f32(vget_high_f32(t01.val[1]), vget_high_f32(t23.val[1]));
#endif
}

/* A corner of four lanes' cells (node: the corner's offset from the low
   one; at: each lane's low corner, in floats): their nodes' four floats,
   transposed to weight and momentum x, y, z across the lanes. */
HF__INLINE void hf__grid_corner_v4(const float *node, const int *at,
                                   hf__v4 q[4])
{
    int l;
    HF__UNROLL for (l = 0; l < 4; ++l) q[l] = HF__LD(node + at[l]);
    hf__grid_t4_v4(q);
}

/* Corners dx = 0 and 1 of one y-z edge (node: the low one's offset):
   hf__grid_corner_v4 of each. */
HF__INLINE void hf__grid_corner2_v4(const float *node, const int *at,
                                    hf__v4 q0[4], hf__v4 q1[4])
{
    hf__grid_corner_v4(node, at, q0);
    hf__grid_corner_v4(node + 4, at, q1);
}

/* Four lanes' velocities v[0..3] (weight, momentum) as each lane's four
   floats: lane l's at out + 4 l. */
HF__INLINE void hf__grid_aos_v4(const hf__v4 v[4], float *out)
{
    hf__v4 q[4];
    int l;
    for (l = 0; l < 4; ++l) q[l] = v[l];
    hf__grid_t4_v4(q);
    for (l = 0; l < 4; ++l) HF__ST(out + 4 * l, q[l]);
}

/* One axis of four points (hf__grid_axis): the cell k (truncated, as the
   scalar cast, as a float) and the fraction f, and the lanes inside the
   cube. */
HF__INLINE hf__v4 hf__grid_axis_v4(hf__v4 c, float o, float inv, int n,
                                   hf__v4 *k, hf__v4 *f)
{
    const hf__v4 q = HF__MUL(HF__SUB(c, HF__SET1(o)), HF__SET1(inv));
#if HF__SSE
    *k = _mm_cvtepi32_ps(_mm_cvttps_epi32(q));
#else
    *k = vcvtq_f32_s32(vcvtq_s32_f32(q));
#endif
    *f = HF__SUB(q, *k);
    return HF__AND(HF__LE(HF__SET1(0.0f), q),
                   HF__LT(q, HF__SET1((float)(n - 1))));
}

/* Four whole floats (node indices, cells) as ints in out[0..3]. */
HF__INLINE void hf__grid_ints_v4(hf__v4 v, int *out)
{
#if HF__SSE
    _mm_storeu_si128((__m128i *)(void *)out, _mm_cvttps_epi32(v));
#else
    vst1q_s32(out, vcvtq_s32_f32(v));
#endif
}

#endif

#if HF__AVX2
/* hf__grid_t4_v4 within each half of eight lanes */
HF__TARGET_AVX2 HF__INLINE void hf__grid_t4_v8(__m256 q[4])
{
    const __m256 t0 = _mm256_unpacklo_ps(q[0], q[1]);
    const __m256 t1 = _mm256_unpackhi_ps(q[0], q[1]);
    const __m256 t2 = _mm256_unpacklo_ps(q[2], q[3]);
    const __m256 t3 = _mm256_unpackhi_ps(q[2], q[3]);
    q[0] = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
    q[1] = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    q[2] = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
    q[3] = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
}

/* hf__grid_corner_v4 for eight lanes: lanes l and l + 4 loaded into the
   two halves of one register (the load's insert is not a shuffle), then
   one four-lane transpose within the halves: 8 shuffles, not 20. */
HF__TARGET_AVX2 HF__INLINE void hf__grid_corner_v8(const float *node,
                                                     const int *at,
                                                     __m256 q[4])
{
    int l;
    HF__UNROLL for (l = 0; l < 4; ++l)
        q[l] = _mm256_insertf128_ps(
            _mm256_castps128_ps256(_mm_loadu_ps(node + at[l])),
            _mm_loadu_ps(node + at[l + 4]), 1);
    hf__grid_t4_v8(q);
}

/* hf__grid_corner2_v4 for eight lanes */
HF__TARGET_AVX2 HF__INLINE void hf__grid_corner2_v8(const float *node,
                                                      const int *at,
                                                      __m256 q0[4],
                                                      __m256 q1[4])
{
    hf__grid_corner_v8(node, at, q0);
    hf__grid_corner_v8(node + 4, at, q1);
}

/* hf__grid_aos_v4 for eight lanes */
HF__TARGET_AVX2 HF__INLINE void hf__grid_aos_v8(const __m256 v[4], float *out)
{
    __m256 q[4];
    int l;
    for (l = 0; l < 4; ++l) q[l] = v[l];
    hf__grid_t4_v8(q);
    for (l = 0; l < 4; ++l) {
        _mm_storeu_ps(out + 4 * l, _mm256_castps256_ps128(q[l]));
        _mm_storeu_ps(out + 4 * (l + 4), _mm256_extractf128_ps(q[l], 1));
    }
}

/* hf__grid_axis_v4 for eight points */
HF__TARGET_AVX2 HF__INLINE __m256 hf__grid_axis_v8(__m256 c, float o,
                                                     float inv, int n,
                                                     __m256 *k, __m256 *f)
{
    const __m256 q = _mm256_mul_ps(_mm256_sub_ps(c, _mm256_set1_ps(o)),
                                   _mm256_set1_ps(inv));
    *k = _mm256_cvtepi32_ps(_mm256_cvttps_epi32(q));
    *f = _mm256_sub_ps(q, *k);
    return _mm256_and_ps(_mm256_cmp_ps(q, _mm256_setzero_ps(), _CMP_GE_OQ),
                         _mm256_cmp_ps(q, _mm256_set1_ps((float)(n - 1)),
                                       _CMP_LT_OQ));
}

/* hf__grid_ints_v4 for eight */
HF__TARGET_AVX2 HF__INLINE void hf__grid_ints_v8(__m256 v, int *out)
{
    _mm256_storeu_si256((__m256i *)(void *)out, _mm256_cvttps_epi32(v));
}

#endif

#if HF__AVX512
/* hf__grid_t4_v4 within each quarter of sixteen lanes (the masked
   forms: see HF__VSQRT) */
HF__TARGET_AVX512 HF__INLINE void hf__grid_t4_v16(__m512 q[4])
{
    const __m512 t0 = _mm512_maskz_unpacklo_ps(0xffff, q[0], q[1]);
    const __m512 t1 = _mm512_maskz_unpackhi_ps(0xffff, q[0], q[1]);
    const __m512 t2 = _mm512_maskz_unpacklo_ps(0xffff, q[2], q[3]);
    const __m512 t3 = _mm512_maskz_unpackhi_ps(0xffff, q[2], q[3]);
    q[0] = _mm512_maskz_shuffle_ps(0xffff, t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
    q[1] = _mm512_maskz_shuffle_ps(0xffff, t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    q[2] = _mm512_maskz_shuffle_ps(0xffff, t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
    q[3] = _mm512_maskz_shuffle_ps(0xffff, t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
}

/* hf__grid_corner_v8 for sixteen lanes: lanes l, l + 4, l + 8 and l + 12
   in the four quarters of one register */
HF__TARGET_AVX512 HF__INLINE void hf__grid_corner_v16(const float *node,
                                                      const int *at,
                                                      __m512 q[4])
{
    int l;
    HF__UNROLL for (l = 0; l < 4; ++l) {
        q[l] = _mm512_maskz_broadcast_f32x4(0xffff,
                                            _mm_loadu_ps(node + at[l]));
        q[l] = _mm512_maskz_insertf32x4(0xffff, q[l],
                                        _mm_loadu_ps(node + at[l + 4]), 1);
        q[l] = _mm512_maskz_insertf32x4(0xffff, q[l],
                                        _mm_loadu_ps(node + at[l + 8]), 2);
        q[l] = _mm512_maskz_insertf32x4(0xffff, q[l],
                                        _mm_loadu_ps(node + at[l + 12]), 3);
    }
    hf__grid_t4_v16(q);
}

/* 32 bytes at a, then 32 at b (AVX-512F's forms: no DQ) */
HF__TARGET_AVX512 HF__INLINE __m512 hf__grid_pair2_v16(const float *a,
                                                       const float *b)
{
    const __m512d q = _mm512_maskz_broadcast_f64x4(
        0xff, _mm256_castps_pd(_mm256_loadu_ps(a)));
    return _mm512_castpd_ps(_mm512_maskz_insertf64x4(
        0xff, q, _mm256_castps_pd(_mm256_loadu_ps(b)), 1));
}

/* hf__grid_corner2_v4 for sixteen lanes: a lane's two nodes (dx = 0,
   1) are 32 bytes in a row, so one load each, two lanes a register
   (lanes e and e + 4, or e + 8 and e + 12), then one shuffle of 128-bit
   blocks per corner gives hf__grid_corner_v16's registers: for the two
   corners 16 loads (8 of them inserts) and 8 shuffles instead of 32
   loads (24 inserts) */
HF__TARGET_AVX512 HF__INLINE void hf__grid_corner2_v16(const float *node,
                                                       const int *at,
                                                       __m512 q0[4],
                                                       __m512 q1[4])
{
    int e;
    HF__UNROLL for (e = 0; e < 4; ++e) {
        const __m512 lo = hf__grid_pair2_v16(node + at[e], node + at[e + 4]);
        const __m512 hi = hf__grid_pair2_v16(node + at[e + 8],
                                             node + at[e + 12]);
        q0[e] = _mm512_maskz_shuffle_f32x4(0xffff, lo, hi,
                                           _MM_SHUFFLE(2, 0, 2, 0));
        q1[e] = _mm512_maskz_shuffle_f32x4(0xffff, lo, hi,
                                           _MM_SHUFFLE(3, 1, 3, 1));
    }
    hf__grid_t4_v16(q0);
    hf__grid_t4_v16(q1);
}

/* hf__grid_aos_v4 for sixteen lanes */
HF__TARGET_AVX512 HF__INLINE void hf__grid_aos_v16(const __m512 v[4],
                                                   float *out)
{
    __m512 q[4];
    int l;
    for (l = 0; l < 4; ++l) q[l] = v[l];
    hf__grid_t4_v16(q);
    for (l = 0; l < 4; ++l) {
        _mm_storeu_ps(out + 4 * l, _mm512_maskz_extractf32x4_ps(0xf, q[l], 0));
        _mm_storeu_ps(out + 4 * (l + 4),
                      _mm512_maskz_extractf32x4_ps(0xf, q[l], 1));
        _mm_storeu_ps(out + 4 * (l + 8),
                      _mm512_maskz_extractf32x4_ps(0xf, q[l], 2));
        _mm_storeu_ps(out + 4 * (l + 12),
                      _mm512_maskz_extractf32x4_ps(0xf, q[l], 3));
    }
}

/* hf__grid_axis_v4 for sixteen points */
HF__TARGET_AVX512 HF__INLINE __m512 hf__grid_axis_v16(__m512 c, float o,
                                                      float inv, int n,
                                                      __m512 *k, __m512 *f)
{
    const __m512 q = _mm512_mul_ps(_mm512_sub_ps(c, _mm512_set1_ps(o)),
                                   _mm512_set1_ps(inv));
    *k = _mm512_maskz_cvtepi32_ps(0xffff, _mm512_maskz_cvttps_epi32(0xffff, q));
    *f = _mm512_sub_ps(q, *k);
    return hf__m16(
        _mm512_cmp_ps_mask(q, _mm512_setzero_ps(), _CMP_GE_OQ) &
        _mm512_cmp_ps_mask(q, _mm512_set1_ps((float)(n - 1)), _CMP_LT_OQ));
}

/* hf__grid_ints_v4 for sixteen */
HF__TARGET_AVX512 HF__INLINE void hf__grid_ints_v16(__m512 v, int *out)
{
    _mm512_storeu_si512((void *)out, _mm512_maskz_cvttps_epi32(0xffff, v));
}
#endif

/* Point i of rope r (standing for `weight` points) into the grid's
   layers [first, end): the scalar reference. */
HF__PRIVATE void hf__grid_splat1(hf_grid *grid, const hf_ropes *ropes,
                                 const float *cube, float inv, size_t i,
                                 int r, float weight, int first, int end)
{
    const int n = grid->resolution;
    const size_t n2 = (size_t)n * (size_t)n;
    float f[3], v[4], hv, wy[2], wz[2];
    size_t node;
    int kx, ky, kz, dz;
    /* the layer first: a call for some layers skips the rest of the
       points at once */
    if (!hf__grid_axis(ropes->z[i], cube[2], inv, n, &kz, &f[2]) ||
        kz + 1 < first || kz >= end ||
        !hf__grid_axis(ropes->x[i], cube[0], inv, n, &kx, &f[0]) ||
        !hf__grid_axis(ropes->y[i], cube[1], inv, n, &ky, &f[1]))
        return;
    node = ((size_t)kz * (size_t)n + (size_t)ky) * (size_t)n + (size_t)kx;
    hv = hf__grid_hv(ropes->last_h[r]);
    hf__grid_velocity(ropes, i, hv, weight, v);
    wy[0] = 1.0f - f[1];
    wy[1] = f[1];
    wz[0] = 1.0f - f[2];
    wz[1] = f[2];
    for (dz = 0; dz < 2; ++dz) {
        float *o = grid->node + 4u * (node + (size_t)dz * n2);
        int dy;
        if (kz + dz < first || kz + dz >= end) continue;
        for (dy = 0; dy < 2; ++dy) {
            float *q = o + 4u * (size_t)dy * (size_t)n;
            const float w = wy[dy] * wz[dz];
            hf__grid_add4(q, (1.0f - f[0]) * w, v);
            hf__grid_add4(q + 4, f[0] * w, v);
        }
    }
}

/* hf_grid_build's row j for ropes [r, e) (the points each standing for
   `weight`) and, where pair > 0, ropes [r + pair, e + pair), taken in
   turn (r, r + pair, r + 1, ...), layers [first, end): the scalar
   reference; returns e. */
HF__PRIVATE int hf__grid_splat_v1(hf_grid *grid, const hf_ropes *ropes,
                                  const float *cube, float inv, int j, int r,
                                  int e, int pair, float weight, int first,
                                  int end)
{
    const size_t row = (size_t)j * (size_t)ropes->rope_count;
    for (; r < e; ++r) {
        hf__grid_splat1(grid, ropes, cube, inv, row + (size_t)r, r, weight,
                        first, end);
        if (pair > 0)
            hf__grid_splat1(grid, ropes, cube, inv, row + (size_t)(r + pair),
                            r + pair, weight, first, end);
    }
    return e;
}

/* What hf_ropes_apply_grid's row j (standing for rows j .. last - 1)
   needs besides the ropes: the grid, its layer 0's cube and stride, and
   the push's constants. */
typedef struct hf__grid_push {
    const hf_grid *grid;
    const float *sl;
    float inv, push, fric, ref, h;
} hf__grid_push;

/* hf_ropes_apply_grid's row j for ropes [r, e): the scalar reference, one
   rope at a time; returns e. */
HF__PRIVATE int hf__grid_apply_v1(hf_ropes *ropes, const hf__grid_push *gp,
                                  int j, int last, int r, int e)
{
    const size_t R = (size_t)ropes->rope_count;
    const hf_grid *grid = gp->grid;
    const float *sl = gp->sl;
    const float inv = gp->inv, push = gp->push, fric = gp->fric,
                ref = gp->ref, h = gp->h;
    const int n = grid->resolution;
    for (; r < e; ++r) {
        const size_t i = (size_t)j * R + (size_t)r;
        float f[3], v[4], a[4], g[3], dv[3], hl, hv, gn, gs;
        size_t node;
        int kz, q;
        if (hf__rope_kind(ropes, r) != 0 ||
            !hf__grid_locate(ropes, i, sl, inv, n, &node, &kz, f))
            continue;
        hl = ropes->last_h[r] > 0.0f ? ropes->last_h[r] : h;
        hv = hf__grid_hv(ropes->last_h[r]);
        hf__grid_velocity(ropes, i, hv, (float)(last - j), v);
        hf__grid_read(grid, node, f, v, a, g);
        /* at most volume x gravity: a density step of more than the
           typical density across a cell pushes no harder, so a
           crowd cannot throw hair (the push is one frame late) */
        gn = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
        gs = gn > ref * ref ? ref / HF_SQRTF(gn) : 1.0f;
        for (q = 0; q < 3; ++q) dv[q] = -push * (g[q] * gs);
        if (fric > 0.0f && a[0] > 1e-6f * ref) {
            const float ia = 1.0f / a[0], iw = 1.0f / v[0];
            float b = fric * (a[0] < ref ? a[0] / ref : 1.0f);
            for (q = 0; q < 3; ++q)
                dv[q] += b * (a[q + 1] * ia - v[q + 1] * iw);
        }
        for (q = 0; q < 3; ++q) dv[q] *= hl;
        /* the change read at point j moves the points it stands for
           (the root stays on the skin) */
        for (q = j > 0 ? j : 1; q < last; ++q) {
            const size_t iq = (size_t)q * R + (size_t)r;
            ropes->px[iq] -= dv[0];
            ropes->py[iq] -= dv[1];
            ropes->pz[iq] -= dv[2];
        }
    }
    return e;
}

/* ---- 6.10 the grid's splat and push: kernel texts at 4, 8, 16 lanes ----- */

/* A prefetch of the bytes 1 KiB after p (an address, so no pointer
   past an array is formed) */
#define HF__GRID_AHEAD(p)                                                      \
    HF__PREFETCH((const void *)((uintptr_t)(const void *)(p) + 1024u))

#endif /* !HF__PASS */

#if defined(HF__PASS) && HF__PASS == HF__PASS_GRID
/* The node index of cells k[0..2] (whole floats): (kz n + ky) n + kx,
   exact in a float for every grid (128^3 < 2^24). */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__grid_node)(const HF__VEC *k, int n)
{
    const HF__VEC nn = HF__VSET1((float)n);
    return HF__VADD(HF__VMUL(HF__VADD(HF__VMUL(k[2], nn), k[1]), nn), k[0]);
}

/* One group of HF__W lanes of hf_grid_build's row j, ready to scatter:
   each lane's eight corner weights, its velocity (weight, momentum) as
   four floats, its low corner's first float and its layer. */
typedef struct HF__KN(hf__grid_group) {
    float cw[8][HF__W], va[4 * HF__W];
    int at[HF__W], kz[HF__W];
} HF__KN(hf__grid_group);

/* hf_grid_build at point row j for ropes r .. r + HF__W - 1 (the points
   each standing for `weight`), layers [first, end): the positions, cells,
   weights and velocities across the lanes, in the scalar code's
   operations; returns the lanes to scatter. */
HF__VTARGET HF__PRIVATE int
HF__KN(hf__grid_prep)(const hf_ropes *ro, const float *cube, float inv,
                      int n, int j, int r, float weight, int first, int end,
                      HF__KN(hf__grid_group) *g)
{
    const size_t R = (size_t)ro->rope_count, i = (size_t)j * R + (size_t)r;
    const HF__VEC one = HF__VSET1(1.0f), wt = HF__VSET1(weight);
    const HF__VEC x = HF__VLD(ro->x + i), y = HF__VLD(ro->y + i);
    const HF__VEC z = HF__VLD(ro->z + i);
    const HF__VEC lh = HF__VLD(ro->last_h + r);
    HF__VEC f[3], k[3], v[4], hv, wx0, wy[2], wz[2], in;
    int l, c, mask;
    /* the rows 1 KiB ahead: the step has pushed them out of the
       nearer caches, and the two streams of ropes are twelve rows for
       the hardware's prefetcher (measured on scene V with 4 MiB read
       between calls: 0.27-0.28 -> 0.25-0.26 ms); a prefetch past a
       row's end does not fault */
    HF__GRID_AHEAD(ro->x + i);
    HF__GRID_AHEAD(ro->y + i);
    HF__GRID_AHEAD(ro->z + i);
    HF__GRID_AHEAD(ro->px + i);
    HF__GRID_AHEAD(ro->py + i);
    HF__GRID_AHEAD(ro->pz + i);
    in = HF__VAND(HF__KN(hf__grid_axis)(z, cube[2], inv, n, &k[2], &f[2]),
                  HF__VAND(HF__KN(hf__grid_axis)(x, cube[0], inv, n, &k[0],
                                                 &f[0]),
                           HF__KN(hf__grid_axis)(y, cube[1], inv, n, &k[1],
                                                 &f[1])));
    mask = HF__VMASK(in);
    /* the low corners' first floats (4 a node: exact below 2^24, as
       128^3 x 4 is) */
    HF__KN(hf__grid_ints)(HF__VSEL(in,
                                   HF__VMUL(HF__KN(hf__grid_node)(k, n),
                                            HF__VSET1(4.0f)),
                                   HF__VSET1(0.0f)),
                          g->at);
    HF__KN(hf__grid_ints)(HF__VSEL(in, k[2], HF__VSET1(0.0f)), g->kz);
    if (first > 0 || end < n) /* some layers: the lanes that reach them */
        for (l = 0; l < HF__W; ++l)
            if (g->kz[l] + 1 < first || g->kz[l] >= end) mask &= ~(1 << l);
    if (!mask) return 0;
    /* hf__grid_hv and hf__grid_velocity */
    hv = HF__VSEL(HF__VGT(lh, HF__VSET1(0.0f)),
                  HF__VDIV(one, HF__VMAX(lh, HF__VSET1(1e-6f))),
                  HF__VSET1(0.0f));
    v[0] = wt;
    v[1] = HF__VMUL(wt, HF__VMUL(HF__VSUB(x, HF__VLD(ro->px + i)), hv));
    v[2] = HF__VMUL(wt, HF__VMUL(HF__VSUB(y, HF__VLD(ro->py + i)), hv));
    v[3] = HF__VMUL(wt, HF__VMUL(HF__VSUB(z, HF__VLD(ro->pz + i)), hv));
    HF__KN(hf__grid_aos)(v, g->va);
    /* corner c = dx + 2 dy + 4 dz: its weight (1 - fx or fx) (wy wz) */
    wx0 = HF__VSUB(one, f[0]);
    wy[0] = HF__VSUB(one, f[1]);
    wy[1] = f[1];
    wz[0] = HF__VSUB(one, f[2]);
    wz[1] = f[2];
    HF__UNROLL for (c = 0; c < 4; ++c) {
        const HF__VEC w = HF__VMUL(wy[c & 1], wz[c >> 1]);
        HF__VST(g->cw[2 * c], HF__VMUL(wx0, w));
        HF__VST(g->cw[2 * c + 1], HF__VMUL(f[0], w));
    }
    return mask;
}

/* Lane l of g into its eight nodes (dy1, dz1: the floats from a node to
   the next along y and z), those in layers [first, end), in the scalar
   code's order: four floats a read-modify-write. */
HF__VTARGET HF__INLINE void
HF__KN(hf__grid_scatter)(float *node, const HF__KN(hf__grid_group) *g,
                         int l, size_t dy1, size_t dz1, int first, int end)
{
    const hf__v4 vl = HF__LD(g->va + 4 * l);
    float *o = node + g->at[l];
    int dz, dy, c;
    if (g->kz[l] >= first && g->kz[l] + 1 < end) {
        /* both layers: straight-line code (every lane of a whole grid's
           call) */
        HF__UNROLL for (c = 0; c < 8; c += 2) {
            float *q = o + (c & 4 ? dz1 : 0u) + (c & 2 ? dy1 : 0u);
            HF__ST(q, HF__ADD(HF__LD(q), HF__MUL(HF__SET1(g->cw[c][l]), vl)));
            HF__ST(q + 4, HF__ADD(HF__LD(q + 4),
                                  HF__MUL(HF__SET1(g->cw[c + 1][l]), vl)));
        }
        return;
    }
    for (dz = 0; dz < 2; ++dz) {
        if (g->kz[l] + dz < first || g->kz[l] + dz >= end) continue;
        HF__UNROLL for (dy = 0; dy < 2; ++dy) {
            float *q = o + (dz ? dz1 : 0u) + (dy ? dy1 : 0u);
            c = 2 * dy + 4 * dz;
            HF__ST(q, HF__ADD(HF__LD(q), HF__MUL(HF__SET1(g->cw[c][l]), vl)));
            HF__ST(q + 4, HF__ADD(HF__LD(q + 4),
                                  HF__MUL(HF__SET1(g->cw[c + 1][l]), vl)));
        }
    }
}

/* hf_grid_build at point row j for ropes r .. r + HF__W - 1 and, where
   pair > 0, ropes r + pair .. r + pair + HF__W - 1, their lanes taken in
   turn (r, r + pair, r + 1, r + pair + 1, ...: the order of
   hf__grid_splat_v1) */
HF__VTARGET HF__PRIVATE void
HF__KN(hf__grid_splat)(hf_grid *grid, const hf_ropes *ro, const float *cube,
                       float inv, int j, int r, int pair, float weight,
                       int first, int end)
{
    const int n = grid->resolution;
    const size_t dy1 = 4u * (size_t)n, dz1 = dy1 * (size_t)n;
    float *const node = grid->node; /* not reloaded after each store */
    HF__KN(hf__grid_group) g[2];
    int l, ma, mb = 0;
    ma = HF__KN(hf__grid_prep)(ro, cube, inv, n, j, r, weight, first, end,
                               &g[0]);
    if (pair > 0)
        mb = HF__KN(hf__grid_prep)(ro, cube, inv, n, j, r + pair, weight,
                                   first, end, &g[1]);
    for (l = 0; l < HF__W; ++l) {
        if (ma >> l & 1)
            HF__KN(hf__grid_scatter)(node, &g[0], l, dy1, dz1, first, end);
        if (mb >> l & 1)
            HF__KN(hf__grid_scatter)(node, &g[1], l, dy1, dz1, first, end);
    }
    HF__VZEROUPPER();
}

/* hf_ropes_apply_grid at point row j for ropes r .. r + HF__W - 1 (the
   lanes of `act` simulated), group j .. last - 1: the scalar code's
   operations lane by lane (hf__grid_read, the cap, the friction), so its
   bytes. */
HF__VTARGET HF__PRIVATE void
HF__KN(hf__grid_apply)(hf_ropes *ro, const hf__grid_push *gp, int j, int last,
                       int r, int act)
{
    const hf_grid *grid = gp->grid;
    const float *sl = gp->sl;
    const float inv = gp->inv, push = gp->push, fric = gp->fric,
                ref = gp->ref, h = gp->h;
    const size_t R = (size_t)ro->rope_count, i = (size_t)j * R + (size_t)r;
    const int n = grid->resolution;
    const size_t n2 = (size_t)n * (size_t)n;
    const HF__VEC one = HF__VSET1(1.0f), two = HF__VSET1(2.0f);
    const HF__VEC x = HF__VLD(ro->x + i), y = HF__VLD(ro->y + i);
    const HF__VEC z = HF__VLD(ro->z + i);
    const HF__VEC lh = HF__VLD(ro->last_h + r);
    HF__VEC f[3], in, w[3], v[4], a[4], g[3], m8[8], hv, hl, lhm;
    HF__VEC a0, a1, a2, a3;
    HF__VEC wx0, wy0, wz0, wyz[4], sx, sy, sz, ms, gn, gs;
    HF__VEC dv[3], k[3];
    int at[HF__W], c, mask, p;
    HF__GRID_AHEAD(ro->x + i); /* as hf__grid_prep */
    HF__GRID_AHEAD(ro->y + i);
    HF__GRID_AHEAD(ro->z + i);
    for (c = j; c < last; ++c) {
        const size_t ic = (size_t)c * R + (size_t)r;
        HF__GRID_AHEAD(ro->px + ic);
        HF__GRID_AHEAD(ro->py + ic);
        HF__GRID_AHEAD(ro->pz + ic);
    }
    in = HF__VAND(HF__KN(hf__grid_axis)(z, sl[2], inv, n, &k[2], &f[2]),
                  HF__VAND(HF__KN(hf__grid_axis)(x, sl[0], inv, n, &k[0], &f[0]),
                           HF__KN(hf__grid_axis)(y, sl[1], inv, n, &k[1],
                                                 &f[1])));
    mask = HF__VMASK(in) & act;
    if (!mask) {
        HF__VZEROUPPER();
        return;
    }
    /* the low corners' first floats (4 a node: exact below 2^24, as
       128^3 x 4 is); lanes out of the cube read node 0 */
    HF__KN(hf__grid_ints)(HF__VSEL(in,
                                   HF__VMUL(HF__KN(hf__grid_node)(k, n),
                                            HF__VSET1(4.0f)),
                                   HF__VSET1(0.0f)),
                          at);
    /* hf__grid_hv and the step's sub-step */
    lhm = HF__VGT(lh, HF__VSET1(0.0f));
    hv = HF__VSEL(
        lhm, HF__VDIV(one, HF__VMAX(lh, HF__VSET1(1e-6f))),
        HF__VSET1(0.0f));
    hl = HF__VSEL(lhm, lh, HF__VSET1(h));
    v[0] = HF__VSET1((float)(last - j));
    v[1] = HF__VSUB(x, HF__VLD(ro->px + i));
    v[2] = HF__VSUB(y, HF__VLD(ro->py + i));
    v[3] = HF__VSUB(z, HF__VLD(ro->pz + i));
    HF__UNROLL for (p = 1; p < 4; ++p)
        v[p] = HF__VMUL(v[0], HF__VMUL(v[p], hv));
    wx0 = HF__VSUB(one, f[0]);
    wy0 = HF__VSUB(one, f[1]);
    wz0 = HF__VSUB(one, f[2]);
    wyz[0] = HF__VMUL(wy0, wz0);
    wyz[1] = HF__VMUL(f[1], wz0);
    wyz[2] = HF__VMUL(wy0, f[2]);
    wyz[3] = HF__VMUL(f[1], f[2]);
    /* the y-z edges in the scalar order (corners 2 e, 2 e + 1), the sums
       in registers; each gradient term as soon as its two corners are
       read, in the scalar sums' order, so that few corners stay live */
    a0 = a1 = a2 = a3 = HF__VSET1(0.0f);
#define HF__GRID_D(e, hi, lo) HF__VMUL(e, HF__VSUB(m8[hi], m8[lo]))
    HF__UNROLL for (c = 0; c < 4; ++c) {
        HF__VEC t0[4], t1[4], w0, w1;
        HF__KN(hf__grid_corner2)(grid->node +
                                     4u * ((size_t)(c >> 1) * n2 +
                                           (size_t)(c & 1) * (size_t)n),
                                 at, t0, t1);
        w0 = HF__VMUL(wx0, wyz[c]);
        w1 = HF__VMUL(f[0], wyz[c]);
        a0 = HF__VADD(HF__VADD(a0, HF__VMUL(w0, t0[0])), HF__VMUL(w1, t1[0]));
        a1 = HF__VADD(HF__VADD(a1, HF__VMUL(w0, t0[1])), HF__VMUL(w1, t1[1]));
        a2 = HF__VADD(HF__VADD(a2, HF__VMUL(w0, t0[2])), HF__VMUL(w1, t1[2]));
        a3 = HF__VADD(HF__VADD(a3, HF__VMUL(w0, t0[3])), HF__VMUL(w1, t1[3]));
        m8[2 * c] = t0[0];
        m8[2 * c + 1] = t1[0];
        if (c == 0) {
            g[0] = HF__GRID_D(wyz[0], 1, 0);
        } else if (c == 1) {
            g[0] = HF__VADD(g[0], HF__GRID_D(wyz[1], 3, 2));
            g[1] = HF__VADD(HF__GRID_D(HF__VMUL(wx0, wz0), 2, 0),
                            HF__GRID_D(HF__VMUL(f[0], wz0), 3, 1));
        } else if (c == 2) {
            g[0] = HF__VADD(g[0], HF__GRID_D(wyz[2], 5, 4));
            g[2] = HF__VADD(HF__GRID_D(HF__VMUL(wx0, wy0), 4, 0),
                            HF__GRID_D(HF__VMUL(f[0], wy0), 5, 1));
        } else {
            g[0] = HF__VADD(g[0], HF__GRID_D(wyz[3], 7, 6));
            g[1] = HF__VADD(HF__VADD(g[1], HF__GRID_D(HF__VMUL(wx0, f[2]),
                                                      6, 4)),
                            HF__GRID_D(HF__VMUL(f[0], f[2]), 7, 5));
            g[2] = HF__VADD(HF__VADD(g[2], HF__GRID_D(HF__VMUL(wx0, f[1]),
                                                      6, 2)),
                            HF__GRID_D(HF__VMUL(f[0], f[1]), 7, 3));
        }
    }
#undef HF__GRID_D
    a[0] = a0;
    a[1] = a1;
    a[2] = a2;
    a[3] = a3;
    sx = HF__VADD(HF__VMUL(wx0, wx0), HF__VMUL(f[0], f[0]));
    sy = HF__VADD(HF__VMUL(wy0, wy0), HF__VMUL(f[1], f[1]));
    sz = HF__VADD(HF__VMUL(wz0, wz0), HF__VMUL(f[2], f[2]));
    ms = HF__VMUL(sx, HF__VMUL(sy, sz));
    HF__UNROLL for (p = 0; p < 4; ++p)
        a[p] = HF__VSUB(a[p], HF__VMUL(ms, v[p]));
    w[0] = HF__VMUL(sy, sz);
    w[1] = HF__VMUL(sx, sz);
    w[2] = HF__VMUL(sx, sy);
    HF__UNROLL for (p = 0; p < 3; ++p)
        g[p] = HF__VSUB(
            g[p], HF__VMUL(v[0], HF__VMUL(HF__VSUB(HF__VMUL(two, f[p]),
                                                         one),
                                              w[p])));
    gn = HF__VADD(HF__VADD(HF__VMUL(g[0], g[0]), HF__VMUL(g[1], g[1])),
                    HF__VMUL(g[2], g[2]));
    gs = HF__VGT(gn, HF__VSET1(ref * ref));
    gs = HF__VMASK(gs) ? HF__VSEL(gs, HF__VDIV(HF__VSET1(ref),
                                                          HF__VSQRT(gn)),
                                           one)
                             : one; /* no lane capped: skip the root */
    HF__UNROLL for (p = 0; p < 3; ++p)
        dv[p] = HF__VMUL(HF__VSET1(-push), HF__VMUL(g[p], gs));
    if (fric > 0.0f) {
        const HF__VEC fm = HF__VGT(a[0], HF__VSET1(1e-6f * ref));
        const HF__VEC ia = HF__VDIV(one, a[0]);
        const HF__VEC iw = HF__VSET1(1.0f / (float)(last - j)); /* v[0] */
        const HF__VEC b = HF__VMUL(
            HF__VSET1(fric),
            HF__VSEL(HF__VLT(a[0], HF__VSET1(ref)),
                        HF__VDIV(a[0], HF__VSET1(ref)), one));
        HF__UNROLL for (p = 0; p < 3; ++p)
            dv[p] = HF__VSEL(
                fm,
                HF__VADD(dv[p],
                           HF__VMUL(b, HF__VSUB(HF__VMUL(a[p + 1], ia),
                                                    HF__VMUL(v[p + 1], iw)))),
                dv[p]);
    }
    {
        const HF__VEC m = HF__VLANES(mask);
        float *px = ro->px, *py = ro->py, *pz = ro->pz;
        HF__UNROLL for (p = 0; p < 3; ++p) dv[p] = HF__VMUL(dv[p], hl);
        for (c = j > 0 ? j : 1; c < last; ++c) {
            float *o[3];
            o[0] = px + (size_t)c * R + (size_t)r;
            o[1] = py + (size_t)c * R + (size_t)r;
            o[2] = pz + (size_t)c * R + (size_t)r;
            HF__UNROLL for (p = 0; p < 3; ++p) {
                const HF__VEC was = HF__VLD(o[p]);
                HF__VST(o[p],
                              HF__VSEL(m, HF__VSUB(was, dv[p]), was));
            }
        }
    }
    HF__VZEROUPPER();
}

/* hf_grid_build's row j for ropes [r, e) (and [r + pair, e + pair) in
   turn, where pair > 0), whole groups of HF__W; returns where it
   stopped */
HF__VTARGET HF__PRIVATE int
HF__KN(hf__grid_splat_rows)(hf_grid *grid, const hf_ropes *ro,
                            const float *cube, float inv, int j, int r, int e,
                            int pair, float weight, int first, int end)
{
    for (; r + HF__W <= e; r += HF__W)
        HF__KN(hf__grid_splat)(grid, ro, cube, inv, j, r, pair, weight,
                               first, end);
    return r;
}

/* hf_ropes_apply_grid's row j for ropes [r, e), whole groups of HF__W,
   the simulated ones; returns where it stopped */
HF__VTARGET HF__PRIVATE int HF__KN(hf__grid_apply_rows)(hf_ropes *ro,
                                                      const hf__grid_push *gp,
                                                      int j, int last, int r,
                                                      int e)
{
    for (; r + HF__W <= e; r += HF__W) {
        int act = 0, l;
        HF__UNROLL for (l = 0; l < HF__W; ++l)
            act |= (hf__rope_kind(ro, r + l) == 0) << l;
        if (act) HF__KN(hf__grid_apply)(ro, gp, j, last, r, act);
    }
    return r;
}
#endif /* HF__PASS_GRID */

#ifndef HF__PASS

/* the grid's splat and push at four lanes (SSE2, NEON), eight (AVX2),
   sixteen (AVX-512) */
#if HF__V4
#define HF__PASS HF__PASS_GRID
#define HF__W 4
#include HF_HEADER_FILENAME
#endif
#if HF__AVX2
#define HF__PASS HF__PASS_GRID
#define HF__W 8
#include HF_HEADER_FILENAME
#endif
#if HF__AVX512
#define HF__PASS HF__PASS_GRID
#define HF__W 16
#include HF_HEADER_FILENAME
#endif

/* The grid's kernels per width: a row's points from rope r on, whole
   groups of the width's lanes; each returns where it stopped. */
typedef struct hf__grid_kernels {
    hf__isa isa;
    int (*splat)(hf_grid *, const hf_ropes *, const float *, float, int, int,
                 int, int, float, int, int);
    int (*push)(hf_ropes *, const hf__grid_push *, int, int, int, int);
} hf__grid_kernels;

static const hf__grid_kernels hf__grid_widths[] = {
#if HF__AVX512
    {{HF__ISA_V16}, hf__grid_splat_rows_v16, hf__grid_apply_rows_v16},
#endif
#if HF__AVX2
    {{HF__ISA_V8}, hf__grid_splat_rows_v8, hf__grid_apply_rows_v8},
#endif
#if HF__V4
    {{HF__ISA_V4}, hf__grid_splat_rows_v4, hf__grid_apply_rows_v4},
#endif
    {{HF__ISA_V1}, hf__grid_splat_v1, hf__grid_apply_v1}};

HFDEF hf_result hf_grid_build(hf_grid *grid, const hf_ropes *ropes,
                              int rope_count, int first, int count)
{
    const hf__grid_kernels *kd;
    size_t n2;
    float cube[5], inv;
    int n, end, j, r, s, k, P, half;
    if (!grid || !grid->node || !hf__ropes_ok(ropes))
        return HF_ERROR_NULL_POINTER;
    n = grid->resolution;
    if (!hf__range_ok(first, count) || first + count > n ||
        rope_count < 0 || rope_count > ropes->rope_count)
        return HF_ERROR_BAD_RANGE;
    if (!hf__kernels_ok(grid->simd, 0)) return HF_ERROR_BAD_PARAMETER;
    kd = hf__kernels_for(hf__grid_widths, grid->simd);
    end = first + count;
    P = ropes->points;
    n2 = (size_t)n * (size_t)n;
    HF_MEMSET(grid->node + 4u * n2 * (size_t)first, 0,
              4u * n2 * (size_t)count * sizeof(float));
    hf__grid_cube(ropes, rope_count, n, cube);
    inv = 1.0f / cube[3];
    k = (int)cube[4];
    half = rope_count / 2;
    for (j = 0; j < P; j += k) {
        /* the points this one stands for: j .. j + k - 1 */
        const float weight = (float)(j + k <= P ? k : P - j);
        const hf__grid_kernels *d = kd;
        /* ropes r and r + half in turn, then the odd one: neighbouring
           ropes share nodes, and each read-modify-write of a node would
           wait for the last one's store; ropes half the guides apart are
           far apart, so the two streams' work overlaps */
        for (r = 0; r < half; ++d)
            r = d->splat(grid, ropes, cube, inv, j, r, half, half, weight,
                         first, end);
        for (r = 2 * half, d = kd; r < rope_count; ++d)
            r = d->splat(grid, ropes, cube, inv, j, r, rope_count, 0, weight,
                         first, end);
    }
    for (s = first; s < end; ++s) {
        const float *o = grid->node + 4u * n2 * (size_t)s;
        float *sl = grid->slab + HF__GRID_SLAB * s;
        /* four sums of every fourth node, added up in one order: four
           chains of additions, not one (n^2 is a multiple of 4 or 1
           more, the odd node in the first sum) */
        double w[4] = {0.0, 0.0, 0.0, 0.0}, w2[4] = {0.0, 0.0, 0.0, 0.0};
        size_t c = 0;
#if HF__SSE
        { /* the same four chains, two to a register (the same bytes) */
            __m128d w01 = _mm_setzero_pd(), w23 = w01, s01 = w01, s23 = w01;
            for (; c + 4 <= n2; c += 4) {
                const float *q = o + 4 * c;
                const __m128d a = _mm_cvtps_pd(
                    _mm_unpacklo_ps(_mm_loadu_ps(q), _mm_loadu_ps(q + 4)));
                const __m128d b = _mm_cvtps_pd(_mm_unpacklo_ps(
                    _mm_loadu_ps(q + 8), _mm_loadu_ps(q + 12)));
                w01 = _mm_add_pd(w01, a);
                s01 = _mm_add_pd(s01, _mm_mul_pd(a, a));
                w23 = _mm_add_pd(w23, b);
                s23 = _mm_add_pd(s23, _mm_mul_pd(b, b));
            }
            _mm_storeu_pd(w, w01);
            _mm_storeu_pd(w + 2, w23);
            _mm_storeu_pd(w2, s01);
            _mm_storeu_pd(w2 + 2, s23);
        }
#endif
        for (; c + 4 <= n2; c += 4)
            HF__UNROLL for (k = 0; k < 4; ++k) {
                const double q = (double)o[4 * (c + (size_t)k)];
                w[k] += q;
                w2[k] += q * q;
            }
        for (; c < n2; ++c) {
            w[0] += (double)o[4 * c];
            w2[0] += (double)o[4 * c] * (double)o[4 * c];
        }
        for (k = 0; k < 5; ++k) sl[k] = cube[k];
        sl[5] = (float)((w[0] + w[1]) + (w[2] + w[3]));
        sl[6] = (float)((w2[0] + w2[1]) + (w2[2] + w2[3]));
    }
    return HF_OK;
}

HFDEF hf_result hf_ropes_apply_grid(hf_ropes *ropes, int first, int count,
                                    float dt, const hf_rope_params *params,
                                    const hf_grid *grid)
{
    hf_rope_params prm;
    hf_result res;
    hf__grid_push gp;
    const hf__grid_kernels *kd;
    const float *sl;
    double w = 0.0, w2 = 0.0;
    float ref, push, fric, gmag, h;
    int n, r, j, s, k, P, steps;
    if (!hf__ropes_ok(ropes) || !params || !grid || !grid->node)
        return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(ropes, first, count)) return HF_ERROR_BAD_RANGE;
    if (!hf__finitef(dt) || !(dt > 0.0f)) return HF_ERROR_BAD_TIME_STEP;
    hf__rope_params_resolve(params, &prm);
    if ((res = hf__rope_params_check(&prm, NULL)) != HF_OK) return res;
    n = grid->resolution;
    sl = grid->slab;
    for (s = 0; s < n; ++s) {
        w += (double)sl[HF__GRID_SLAB * s + 5];
        w2 += (double)sl[HF__GRID_SLAB * s + 6];
    }
    if (count == 0 || !(w > 0.0) || !(sl[3] > 0.0f)) return HF_OK;
    h = hf__rope_substeps(&prm, dt, &steps);
    /* the density around the average point: the unit of the push */
    ref = (float)(w2 / w);
    /* volume 1: a density step of the typical density across a cell
       pushes as hard as gravity pulls (9.81 m/s^2 without gravity) */
    gmag = HF_SQRTF(prm.gravity[0] * prm.gravity[0] +
                    prm.gravity[1] * prm.gravity[1] +
                    prm.gravity[2] * prm.gravity[2]);
    if (!(gmag > 0.0f)) gmag = 9.81f;
    push = prm.volume * gmag * (h * (float)steps) / ref;
    fric = hf__rope_k(prm.friction, h * (float)steps);
    if (!(push > 0.0f) && !(fric > 0.0f)) return HF_OK;
    P = ropes->points;
    k = (int)sl[4];
    kd = hf__kernels_for(hf__grid_widths, prm.simd);
    gp.grid = grid;
    gp.sl = sl;
    gp.inv = 1.0f / sl[3];
    gp.push = push;
    gp.fric = fric;
    gp.ref = ref;
    gp.h = h;
    /* point rows outermost, as the grid was built: neighbouring ropes
       read neighbouring nodes */
    for (j = 0; j < P; j += k) {
        const int last = j + k <= P ? j + k : P;
        const hf__grid_kernels *d = kd;
        for (r = first; r < first + count; ++d)
            r = d->push(ropes, &gp, j, last, r, first + count);
    }
    return HF_OK;
}

#undef HF__ROW

/* ---- 7. interpolation and LOD ------------------------------------------- */

#if HF__SSE
/* A streaming store into a page the TLB does not hold waits for the
   page's walk, and the walk for page tables the frame's other stages
   have pushed out of the cache (measured: scene L's strands, 19 MB
   streamed after a frame's ribbons, 1.1 ms, 0.6 with their pages walked
   ahead). The streaming kernels call this for each strand's stores at
   p .. p + bytes: a prefetch for each page they enter, HF__PAGE_AHEAD
   bytes ahead, walks it early. Any address will do: a prefetch does not
   fault. Ordinary stores do not use it: their ribbons measured 0.8x with
   it in some processes and 1.5x in others (docs/performance.md). */
#define HF__PAGE_AHEAD 16384u
HF__INLINE void hf__page_ahead(const void *p, size_t bytes)
{
    uintptr_t q = ((uintptr_t)p + 4095u) & ~(uintptr_t)4095u;
    for (; q < (uintptr_t)p + bytes; q += 4096u) /* each page start once */
        _mm_prefetch((const char *)(q + HF__PAGE_AHEAD), _MM_HINT_T0);
}

/* Floats [i, i + 4) of a strand; R is (1 - sc) root in the phase of i. The
   operations and their order are the scalar loop's in hf_interpolate. */
HF__INLINE void hf__interp_v4(const float *g0, const float *g1, const float *g2,
                              const float *gn, const float *ctab, float *o,
                              int i, __m128 W0, __m128 W1, __m128 W2, __m128 SC,
                              __m128 R, int nt)
{
    __m128 p = _mm_add_ps(_mm_add_ps(_mm_mul_ps(W0, _mm_loadu_ps(g0 + i)),
                                     _mm_mul_ps(W1, _mm_loadu_ps(g1 + i))),
                          _mm_mul_ps(W2, _mm_loadu_ps(g2 + i)));
    p = _mm_add_ps(_mm_mul_ps(SC, p), R);
    if (gn) /* clumping: NULL when clump is 0, two loads fewer */
        p = _mm_add_ps(p, _mm_mul_ps(_mm_loadu_ps(ctab + i),
                                     _mm_sub_ps(_mm_loadu_ps(gn + i), p)));
    if (nt)
        _mm_stream_ps(o + i, p);
    else
        _mm_storeu_ps(o + i, p);
}
#endif

/* One strand's floats [i, 3 P) of hf__interpolate_run: p = the weighted
   guides, scaled about the root (rb = (1 - sc) root, twice), then pulled
   toward guide gn (NULL: no clumping) by ctab. */
HF__PRIVATE void hf__interp_strand_v1(const float *g0, const float *g1,
                                      const float *g2, const float *gn,
                                      const float *ctab, float *o, int i, int P,
                                      float w0, float w1, float w2, float sc,
                                      const float *rb)
{
    for (; i < 3 * P; ++i) {
        float p = w0 * g0[i] + w1 * g1[i] + w2 * g2[i];
        p = sc * p + rb[i % 3];
        o[i] = gn ? p + ctab[i] * (gn[i] - p) : p;
    }
}

#if HF__SSE
/* hf__interp_strand_v1 on whole vectors from float 0; returns where they
   end. */
HF__PRIVATE int hf__interp_strand_v4(const float *g0, const float *g1,
                                     const float *g2, const float *gn,
                                     const float *ctab, float *o, int P,
                                     float w0, float w1, float w2, float sc,
                                     const float *rb, int nt)
{
    const __m128 W0 = _mm_set1_ps(w0), W1 = _mm_set1_ps(w1);
    const __m128 W2 = _mm_set1_ps(w2), SC = _mm_set1_ps(sc);
    /* (1 - sc) root, repeating every 3 floats: 3 phases of 4, built
       in registers (loading them from rb would wait on its narrow
       stores: a third of the time) */
    const __m128 R0 = _mm_setr_ps(rb[0], rb[1], rb[2], rb[0]);
    const __m128 R1 = _mm_setr_ps(rb[1], rb[2], rb[0], rb[1]);
    const __m128 R2 = _mm_setr_ps(rb[2], rb[0], rb[1], rb[2]);
    int i = 0;
    /* three vectors a turn, so each gets its phase without a test */
    for (; i + 12 <= 3 * P; i += 12) {
        hf__interp_v4(g0, g1, g2, gn, ctab, o, i, W0, W1, W2, SC, R0, nt);
        hf__interp_v4(g0, g1, g2, gn, ctab, o, i + 4, W0, W1, W2, SC, R1, nt);
        hf__interp_v4(g0, g1, g2, gn, ctab, o, i + 8, W0, W1, W2, SC, R2, nt);
    }
    if (i + 4 <= 3 * P) {
        hf__interp_v4(g0, g1, g2, gn, ctab, o, i, W0, W1, W2, SC, R0, nt);
        i += 4;
    }
    if (i + 4 <= 3 * P) {
        hf__interp_v4(g0, g1, g2, gn, ctab, o, i, W0, W1, W2, SC, R1, nt);
        i += 4;
    }
    return i;
}
#endif

/* A range of strands to interpolate, and one strand's inputs from its
   binding. */
typedef struct hf__irun {
    const float *guides;
    const hf_strand_binding *bindings;
    const float *ctab; /* clump weight of each float of a strand */
    float *out;        /* strand s at out + (s - out_first) * 3 P */
    int P, out_first, clump;
    int nt; /* streaming stores (where a strand's row is 16-byte aligned) */
} hf__irun;

typedef struct hf__istrand {
    const float *g0, *g1, *g2, *gn; /* gn: NULL without clumping */
    float w0, w1, w2, sc, rb[6];     /* rb: (1 - sc) root, twice */
    float *o;
} hf__istrand;

/* The guide a strand clumps to: the one of largest weight (the first of
   equals), picked without a branch: weights are random, so a branch would
   miss half the time. */
HF__INLINE size_t hf__clump_guide(const hf_strand_binding *b)
{
    const float w0 = b->weight[0], w1 = b->weight[1], w2 = b->weight[2];
    const int n0 = (w0 >= w1) & (w0 >= w2), n1 = !n0 & (w1 >= w2);
    return (size_t)b->guide[2 - 2 * n0 - n1];
}

HF__INLINE void hf__interp_setup(const hf__irun *run, int s, hf__istrand *t)
{
    const hf_strand_binding *b = &run->bindings[s];
    const size_t row = (size_t)run->P * 3u;
    t->g0 = run->guides + (size_t)b->guide[0] * row;
    t->g1 = run->guides + (size_t)b->guide[1] * row;
    t->g2 = run->guides + (size_t)b->guide[2] * row;
    t->w0 = b->weight[0];
    t->w1 = b->weight[1];
    t->w2 = b->weight[2];
    t->sc = b->length_scale;
    t->o = run->out + (size_t)(s - run->out_first) * row;
    t->gn = run->clump ? run->guides + hf__clump_guide(b) * row : NULL;
}

/* p' = sc p + (1 - sc) root keeps the root and scales the offsets; with
   sc = 1 it is p exactly, so a strand on a guide equals it */
HF__INLINE void hf__interp_root(hf__istrand *t)
{
    int k;
    for (k = 0; k < 3; ++k) {
        t->rb[k] = (1.0f - t->sc) *
                   (t->w0 * t->g0[k] + t->w1 * t->g1[k] + t->w2 * t->g2[k]);
        t->rb[k + 3] = t->rb[k];
    }
}

/* Strands [first, first + count) of a run: the reference, and at four
   lanes (SSE2 or NEON) below, at eight and sixteen in 7.1; each returns
   1 (all written), the sixteen-lane entry 0 for a P it leaves to eight
   lanes (hf__interp_widths). */
HF__PRIVATE int hf__interp_range_v1(const hf__irun *run, int first, int count)
{
    hf__istrand t;
    int s;
    for (s = first; s < first + count; ++s) {
        hf__interp_setup(run, s, &t);
        hf__interp_root(&t);
        hf__interp_strand_v1(t.g0, t.g1, t.g2, t.gn, run->ctab, t.o, 0, run->P,
                             t.w0, t.w1, t.w2, t.sc, t.rb);
    }
    return 1;
}

#if HF__SSE
HF__PRIVATE int hf__interp_range_v4(const hf__irun *run, int first, int count)
{
    hf__istrand t;
    int s, i;
    for (s = first; s < first + count; ++s) {
        int nt;
        hf__interp_setup(run, s, &t);
        hf__interp_root(&t);
        nt = run->nt && ((uintptr_t)t.o & 15u) == 0;
        if (nt) hf__page_ahead(t.o, 12u * (size_t)run->P);
        i = hf__interp_strand_v4(t.g0, t.g1, t.g2, t.gn, run->ctab, t.o, run->P,
                                 t.w0, t.w1, t.w2, t.sc, t.rb, nt);
        if (i < 3 * run->P)
            hf__interp_strand_v1(t.g0, t.g1, t.g2, t.gn, run->ctab, t.o, i,
                                 run->P, t.w0, t.w1, t.w2, t.sc, t.rb);
    }
    return 1;
}
#endif

/* The last floats of a strand, from float i, in scalar code: cold, so
   kept out of the vector loops. */
HF__NOINLINE HF__PRIVATE void hf__interp_tail(const hf__irun *run,
                                             hf__istrand *t, int i)
{
    hf__interp_root(t);
    hf__interp_strand_v1(t->g0, t->g1, t->g2, t->gn, run->ctab, t->o, i, run->P,
                         t->w0, t->w1, t->w2, t->sc, t->rb);
}

#if HF__NEON
/* hf__interp_strand_v4 on ARM64: four floats a vector, the same
   operations in the same order, so the same bytes. */
HF__INLINE void hf__interp_v4(const hf__istrand *t, const float *ctab, int i,
                              float32x4_t W0, float32x4_t W1, float32x4_t W2,
                              float32x4_t SC, float32x4_t R)
{
    float32x4_t p = vaddq_f32(vaddq_f32(vmulq_f32(W0, vld1q_f32(t->g0 + i)),
                                        vmulq_f32(W1, vld1q_f32(t->g1 + i))),
                              vmulq_f32(W2, vld1q_f32(t->g2 + i)));
    p = vaddq_f32(vmulq_f32(SC, p), R);
    if (t->gn)
        p = vaddq_f32(p, vmulq_f32(vld1q_f32(ctab + i),
                                   vsubq_f32(vld1q_f32(t->gn + i), p)));
    vst1q_f32(t->o + i, p);
}

HF__PRIVATE int hf__interp_range_v4(const hf__irun *run, int first, int count)
{
    const int n = 3 * run->P;
    hf__istrand t;
    int s, i;
    for (s = first; s < first + count; ++s) {
        float32x4_t W0, W1, W2, SC, R0, R1, R2;
        hf__interp_setup(run, s, &t);
        hf__interp_root(&t);
        W0 = vdupq_n_f32(t.w0);
        W1 = vdupq_n_f32(t.w1);
        W2 = vdupq_n_f32(t.w2);
        SC = vdupq_n_f32(t.sc);
        /* phases 0, 1, 2 at floats 0, 4, 8: rb holds the root twice */
        R0 = vld1q_f32(t.rb);
        R1 = vld1q_f32(t.rb + 1);
        R2 = vld1q_f32(t.rb + 2);
        for (i = 0; i + 12 <= n; i += 12) {
            hf__interp_v4(&t, run->ctab, i, W0, W1, W2, SC, R0);
            hf__interp_v4(&t, run->ctab, i + 4, W0, W1, W2, SC, R1);
            hf__interp_v4(&t, run->ctab, i + 8, W0, W1, W2, SC, R2);
        }
        if (i + 4 <= n) {
            hf__interp_v4(&t, run->ctab, i, W0, W1, W2, SC, R0);
            i += 4;
        }
        if (i + 4 <= n) {
            hf__interp_v4(&t, run->ctab, i, W0, W1, W2, SC, R1);
            i += 4;
        }
        if (i < n)
            hf__interp_strand_v1(t.g0, t.g1, t.g2, t.gn, run->ctab, t.o, i,
                                 run->P, t.w0, t.w1, t.w2, t.sc, t.rb);
    }
    return 1;
}
#endif

#if HF__AVX2 || HF__AVX512
/* How a wide kernel writes to o when streaming (nt) is asked: 2, whole
   vectors (o aligned to them: `whole` is their size - 1); 1, 16-byte
   pieces (o 16-byte aligned); 0, plain stores. */
HF__INLINE int hf__stream_mode(int nt, const void *o, uintptr_t whole)
{
    if (!nt) return 0;
    if (((uintptr_t)o & whole) == 0) return 2;
    return ((uintptr_t)o & 15u) == 0;
}
#endif

#if HF__AVX2
/* A strand's root at eight lanes, (1 - sc) root in its phases at floats
   0, 8, 16 (0, 2, 1: it repeats every 3 floats) into R[0 .. 3), from s0,
   the sum of floats [0, 8) (the root's sum in lanes 0-2), so the root
   costs no loads of its own. */
HF__TARGET_AVX2 HF__INLINE void hf__roots_v8(__m256 sc, __m256 s0,
                                             __m256 *R)
{
    const __m256i x0 = _mm256_setr_epi32(0, 1, 2, 0, 1, 2, 0, 1);
    const __m256i x2 = _mm256_setr_epi32(2, 0, 1, 2, 0, 1, 2, 0);
    const __m256i x1 = _mm256_setr_epi32(1, 2, 0, 1, 2, 0, 1, 2);
    const __m256 r = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(1.0f), sc),
                                   s0);
    R[0] = _mm256_permutevar8x32_ps(r, x0);
    R[1] = _mm256_permutevar8x32_ps(r, x2);
    R[2] = _mm256_permutevar8x32_ps(r, x1);
}

/* Eight floats at o, as hf__stream_mode says: a plain store (0), two
   streaming halves (1: 16-byte aligned) or one streaming store (2:
   32-byte aligned). */
HF__TARGET_AVX2 HF__INLINE void hf__put_v8(float *o, __m256 q, int mode)
{
    if (mode == 2) {
        _mm256_stream_ps(o, q);
    } else if (mode == 1) {
        _mm_stream_ps(o, _mm256_castps256_ps128(q));
        _mm_stream_ps(o + 4, _mm256_extractf128_ps(q, 1));
    } else {
        _mm256_storeu_ps(o, q);
    }
}

/* F(..., c, m) with a call's clumping c (0 or 1) and stream mode m (0, 1,
   2: hf__stream_mode's) as constants: one inlined copy of the loop F for
   each, with no test of either in it. */
#define HF__CLUMP_MODE_CASES(c, m, F, ...)                                     \
    do {                                                                       \
        if (c) {                                                               \
            if ((m) == 2) F(__VA_ARGS__, 1, 2);                                \
            else if (m) F(__VA_ARGS__, 1, 1);                                  \
            else F(__VA_ARGS__, 1, 0);                                         \
        } else {                                                               \
            if ((m) == 2) F(__VA_ARGS__, 0, 2);                                \
            else if (m) F(__VA_ARGS__, 0, 1);                                  \
            else F(__VA_ARGS__, 0, 0);                                         \
        }                                                                      \
    } while (0)

/* r floats from q to o (16-byte aligned) in streaming stores, r a
   multiple of 4 (strands stream only with P one, hf__irun_init) */
HF__INLINE void hf__stream_floats(float *o, const float *q, size_t r)
{
    size_t k;
    for (k = 0; k < r; k += 4) _mm_stream_ps(o + k, _mm_loadu_ps(q + k));
}
#endif
/* ---- 7.1 interpolation at 8 and 16 lanes: a kernel text ----------------- */

#endif /* !HF__PASS */

#if defined(HF__PASS) && HF__PASS == HF__PASS_INTERP
/* One strand's inputs at W lanes, straight from its binding (taken
   through hf__istrand and a record of its vectors, the sixteen-lane
   kernel ran 1.3x slower on 100,000 strands): its guides (gn: the one it
   clumps to, NULL without clumping), weights, scale, and (1 - sc) root
   in its three phases (hf__roots_v<W>). The kernels pass the run's
   fields in: their vector stores may alias anything, so fields read
   through the run would be read again after each. */
typedef struct HF__KN(hf__is) {
    const float *g0, *g1, *g2, *gn;
    HF__VEC W0, W1, W2, SC, R[3];
} HF__KN(hf__is);

HF__VTARGET HF__INLINE void HF__KN(hf__strand)(const float *G, int clump,
                                               const hf_strand_binding *b,
                                               size_t n, HF__KN(hf__is) *v)
{
    v->g0 = G + (size_t)b->guide[0] * n;
    v->g1 = G + (size_t)b->guide[1] * n;
    v->g2 = G + (size_t)b->guide[2] * n;
    v->gn = clump ? G + hf__clump_guide(b) * n : NULL;
    v->W0 = HF__VSET1(b->weight[0]);
    v->W1 = HF__VSET1(b->weight[1]);
    v->W2 = HF__VSET1(b->weight[2]);
    v->SC = HF__VSET1(b->length_scale);
}

/* The weighted sum of the guides' floats [q, q + W): the operations of
   hf__interp_strand_v1 in its order (no FMA), so the same bytes. */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__sum)(const HF__KN(hf__is) *v,
                                               size_t q)
{
    return HF__VDOT3(v->W0, v->W1, v->W2, HF__VLD(v->g0 + q),
                     HF__VLD(v->g1 + q), HF__VLD(v->g2 + q));
}

/* Floats [q, q + W) of the strand from their sum p, in root phase R[k] */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__finish)(const HF__KN(hf__is) *v,
                                                  const float *ctab,
                                                  HF__VEC p, size_t q, int k)
{
    p = HF__VADD(HF__VMUL(v->SC, p), v->R[k]);
    if (v->gn)
        p = HF__VADD(p, HF__VMUL(HF__VLD(ctab + q),
                                 HF__VSUB(HF__VLD(v->gn + q), p)));
    return p;
}

HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__blend)(const HF__KN(hf__is) *v,
                                                 const float *ctab, size_t q,
                                                 int k)
{
    return HF__KN(hf__finish)(v, ctab, HF__KN(hf__sum)(v, q), q, k);
}

/* The strands of a range, W floats a vector, in one target function
   (HF__VTARGET; no call per strand), as two kernels built from one text.
   hf__interp_groups_v<W>: P a multiple of W, a strand whole groups of three
   vectors: the stream mode once, since every strand's 12 P bytes keep the
   first's alignment, and no tail (with one, the sixteen-lane loop
   measured 1.1x slower). Its loop is inlined once for each clumping and
   stream mode, passed as constants: tested in every vector, they took a
   third of its instructions at AVX2. hf__interp_range_v<W>: any P, three
   vectors a turn, then one or two, then the strand's last W floats over
   the end of those (with fewer than W floats, the scalar tail): at P = 12
   and 20, 7.5-12 ns a strand in L2 where the scalar tail took 18-32. */
/* Floats [i, i + 3 W) of the strand at o + i, from sa, the sum of the
   first W: a turn of the loops below, the root phases by constants, so
   v stays in registers */
HF__VTARGET HF__INLINE void HF__KN(hf__turn)(float *o,
                                             const HF__KN(hf__is) *v,
                                             const float *ctab, HF__VEC sa,
                                             size_t i, int nt)
{
    HF__KN(hf__put)(o + i, HF__KN(hf__finish)(v, ctab, sa, i, 0), nt);
    HF__KN(hf__put)(o + i + HF__W, HF__KN(hf__blend)(v, ctab, i + HF__W, 1),
                    nt);
    HF__KN(hf__put)(o + i + 2 * HF__W,
                    HF__KN(hf__blend)(v, ctab, i + 2 * HF__W, 2), nt);
}

HF__VTARGET HF__INLINE void HF__KN(hf__interp_whole)(const hf__irun *run,
                                                     int first, int count,
                                                     int clump, int nt)
{
    const size_t n = 3u * (size_t)run->P;
    const hf_strand_binding *b = run->bindings + first;
    const float *G = run->guides, *ctab = run->ctab;
    float *o = run->out + (size_t)(first - run->out_first) * n;
    int s;
    for (s = 0; s < count; ++s, ++b, o += n) {
        HF__KN(hf__is) v;
        HF__VEC sa;
        size_t i;
        if (nt) hf__page_ahead(o, 4u * n);
        HF__KN(hf__strand)(G, clump, b, n, &v);
        sa = HF__KN(hf__sum)(&v, 0); /* the root's, and the first vector's */
        HF__KN(hf__roots)(v.SC, sa, v.R);
        for (i = 0;; sa = HF__KN(hf__sum)(&v, i)) {
            HF__KN(hf__turn)(o, &v, ctab, sa, i, nt);
            if ((i += 3 * HF__W) >= n) break;
        }
    }
}

HF__VTARGET HF__PRIVATE void HF__KN(hf__interp_groups)(const hf__irun *run,
                                                       int first, int count)
{
    const float *o = run->out + (size_t)(first - run->out_first) *
                                    (3u * (size_t)run->P);
    const int nt = hf__stream_mode(run->nt, o, 4u * HF__W - 1u);
    HF__CLUMP_MODE_CASES(run->clump, nt, HF__KN(hf__interp_whole), run, first,
                         count);
    HF__VZEROUPPER(); /* see HF__TARGET_AVX2 */
}

HF__VTARGET HF__PRIVATE int HF__KN(hf__interp_range)(const hf__irun *run,
                                                     int first, int count)
{
    const size_t n = 3u * (size_t)run->P;
    const hf_strand_binding *b = run->bindings + first;
    const float *G = run->guides, *ctab = run->ctab;
    const int clump = run->clump;
    float *o = run->out + (size_t)(first - run->out_first) * n;
    int s;
    if (n % (3 * HF__W) == 0) {
        HF__KN(hf__interp_groups)(run, first, count);
        return 1;
    }
    for (s = first; s < first + count; ++s, ++b, o += n) {
        const int nt = hf__stream_mode(run->nt, o, 4u * HF__W - 1u);
        HF__KN(hf__is) v;
        HF__VEC sa = HF__VSET1(0.0f);
        size_t i;
        if (nt) hf__page_ahead(o, 4u * n);
        HF__KN(hf__strand)(G, clump, b, n, &v);
        /* the root's sum, and the first vector's (below W floats only the
           scalar tail runs, with a root of its own) */
        if (n >= HF__W) sa = HF__KN(hf__sum)(&v, 0);
        HF__KN(hf__roots)(v.SC, sa, v.R);
        /* sa: the sum of floats [i, i + W) wherever i + W <= n */
        for (i = 0; i + 3 * HF__W <= n;) {
            HF__KN(hf__turn)(o, &v, ctab, sa, i, nt);
            if ((i += 3 * HF__W) + HF__W <= n) sa = HF__KN(hf__sum)(&v, i);
        }
        if (i + HF__W <= n) {
            HF__KN(hf__put)(o + i, HF__KN(hf__finish)(&v, ctab, sa, i, 0), nt);
            i += HF__W;
        }
        if (i + HF__W <= n) {
            HF__KN(hf__put)(o + i, HF__KN(hf__blend)(&v, ctab, i, 1), nt);
            i += HF__W;
        }
        if (i < n && n >= HF__W) {
            /* the last W floats (their phase 2, since n - W = 2 W mod 3):
               over some already written (the same values), or streamed,
               only those past i: a line streamed twice goes out twice */
            float t[HF__W];
            HF__KN(hf__put)(nt ? t : o + n - HF__W,
                            HF__KN(hf__blend)(&v, ctab, n - HF__W, 2), 0);
            if (nt) hf__stream_floats(o + i, t + HF__W - (n - i), n - i);
        } else if (i < n) {
            hf__istrand t;
            /* the tail is SSE code: with the upper halves dirty it would
               run at half speed or worse */
            HF__VZEROUPPER();
            hf__interp_setup(run, s, &t);
            hf__interp_tail(run, &t, (int)i);
        }
    }
    HF__VZEROUPPER(); /* see HF__TARGET_AVX2 */
    return 1;
}
#endif /* HF__PASS_INTERP */

#ifndef HF__PASS

/* ---- 7.2 the interpolation kernels per width, hf_interpolate ------------ */
#if HF__AVX2
#define HF__PASS HF__PASS_INTERP
#define HF__W 8
#include HF_HEADER_FILENAME
#endif

#if HF__AVX512
/* hf__roots_v8 at sixteen lanes: phases 0, 1, 2 at floats 0, 16, 32 */
HF__TARGET_AVX512 HF__INLINE void hf__roots_v16(__m512 sc, __m512 s0,
                                               __m512 *R)
{
    const __m512i x0 = _mm512_setr_epi32(0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2,
                                         0, 1, 2, 0);
    const __m512i x1 = _mm512_setr_epi32(1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0,
                                         1, 2, 0, 1);
    const __m512i x2 = _mm512_setr_epi32(2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1,
                                         2, 0, 1, 2);
    const __m512 r = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(1.0f), sc),
                                   s0);
    R[0] = _mm512_maskz_permutexvar_ps(0xffff, x0, r);
    R[1] = _mm512_maskz_permutexvar_ps(0xffff, x1, r);
    R[2] = _mm512_maskz_permutexvar_ps(0xffff, x2, r);
}

/* Sixteen floats at o, as hf__put_v8: a plain store, four streaming
   quarters (16-byte aligned) or one streaming store (64-byte aligned). */
HF__TARGET_AVX512 HF__INLINE void hf__put_v16(float *o, __m512 p, int mode)
{
    if (!mode) {
        _mm512_storeu_ps(o, p);
    } else if (mode == 2) {
        _mm512_stream_ps(o, p);
    } else {
        _mm_stream_ps(o, _mm512_maskz_extractf32x4_ps(0xf, p, 0));
        _mm_stream_ps(o + 4, _mm512_maskz_extractf32x4_ps(0xf, p, 1));
        _mm_stream_ps(o + 8, _mm512_maskz_extractf32x4_ps(0xf, p, 2));
        _mm_stream_ps(o + 12, _mm512_maskz_extractf32x4_ps(0xf, p, 3));
    }
}

#define HF__PASS HF__PASS_INTERP
#define HF__W 16
#include HF_HEADER_FILENAME

/* Sixteen lanes, but for P a multiple of 8 and not of 16: those go to
   eight lanes in whole groups (returns 0): P = 24 and 40 took 0.43 and
   0.42 ns a point against sixteen lanes' 0.48 and 0.45 (a group and a
   part of one, in L2). */
HF__PRIVATE int hf__interp_fit_v16(const hf__irun *run, int first, int count)
{
    if (run->P % 16 != 0 && run->P % 8 == 0) return 0;
    return hf__interp_range_v16(run, first, count);
}
#endif

typedef struct hf__interp_kernels {
    hf__isa isa;
    int (*range)(const hf__irun *, int, int);
} hf__interp_kernels;

static const hf__interp_kernels hf__interp_widths[] = {
#if HF__AVX512
    {{HF__ISA_V16}, hf__interp_fit_v16},
#endif
#if HF__AVX2
    {{HF__ISA_V8}, hf__interp_range_v8},
#endif
#if HF__V4
    {{HF__ISA_V4}, hf__interp_range_v4},
#endif
    {{HF__ISA_V1}, hf__interp_range_v1}};

/* A run's fields; ctab (3 P floats) filled here */
HF__PRIVATE void hf__irun_init(hf__irun *run, const float *guide_points,
                               const hf_strand_binding *bindings, int P,
                               float clump, float *ctab, float *out_points,
                               int out_first, int nt)
{
    int i;
    /* clump weight of float i of a strand: clump * (i / 3) / (P - 1),
       read only with clumping (every call pays for it) */
    if (clump != 0.0f)
        for (i = 0; i < 3 * P; ++i)
            ctab[i] = clump / (float)(P - 1) * (float)(i / 3);
    run->guides = guide_points;
    run->bindings = bindings;
    run->ctab = ctab;
    run->out = out_points;
    run->P = P;
    run->out_first = out_first;
    run->clump = clump != 0.0f;
    /* streaming only where every strand keeps the first's alignment to
       16 bytes (P a multiple of 4): otherwise some strands would stream
       and the others, unaligned, take ordinary stores into the lines
       they share, which cost 98-192 ns a strand against 7.8-12.4 with
       ordinary stores throughout (P = 9 to 14, 100,000 strands) */
    run->nt = nt && P % 4 == 0;
}

/* Strands [first, first + count) from inputs already checked: the loop of
   hf_interpolate, at SIMD level `simd` (hf__interp_widths: the widest
   kernel that takes the run). */
HF__PRIVATE void hf__interpolate_run(const float *guide_points,
                                     const hf_strand_binding *bindings,
                                     int first, int count, int P, float clump,
                                     float *out_points, int out_first, int simd,
                                     int nt)
{
    const hf__interp_kernels *k = hf__kernels_for(hf__interp_widths, simd);
    float ctab[3 * HF_MAX_POINTS];
    hf__irun run;
    hf__irun_init(&run, guide_points, bindings, P, clump, ctab, out_points,
                  out_first, nt);
    while (!k->range(&run, first, count)) ++k;
#if HF__SSE
    if (nt && k->isa.lanes > 1)
        _mm_sfence(); /* streamed stores visible before we return */
#endif
}

HFDEF hf_result hf_interpolate(const float *guide_points, int guide_count,
                               const hf_strand_binding *bindings, int first,
                               int count, const hf_interp_params *params,
                               float *out_points)
{
    int s, i, k, P;
    float clump;
    if (!guide_points || !bindings || !params || !out_points)
        return HF_ERROR_NULL_POINTER;
    P = params->points_per_strand;
    if (P < 2 || P > HF_MAX_POINTS || guide_count < 1)
        return HF_ERROR_BAD_COUNT;
    if (!hf__range_ok(first, count) || params->out_first < 0 ||
        first < params->out_first)
        return HF_ERROR_BAD_RANGE;
    clump = params->clump;
    if (!hf__finitef(clump)) return HF_ERROR_NON_FINITE;
    if (clump < 0.0f || clump > 1.0f ||
        !hf__kernels_ok(params->simd, params->nontemporal))
        return HF_ERROR_BAD_PARAMETER;
    /* validate the whole range before writing anything */
    for (s = first; s < first + count; ++s) {
        const hf_strand_binding *b = &bindings[s];
        for (k = 0; k < 3; ++k) {
            if (b->guide[k] >= (uint32_t)guide_count)
                return HF_ERROR_INDEX_OUT_OF_RANGE;
            if (!hf__finitef(b->weight[k])) return HF_ERROR_NON_FINITE;
        }
        if (!hf__finitef(b->length_scale)) return HF_ERROR_NON_FINITE;
        if (b->length_scale > HF_MAX_ABS || b->length_scale < -HF_MAX_ABS)
            return HF_ERROR_BAD_PARAMETER;
    }
    /* the guides: every call checks all of them (0.1 ms for 3,600 guides
       of 16 points), which is why hf_fur, whose guides are finite and
       bounded by construction, calls hf__interpolate_run directly */
    for (i = 0; i < guide_count * P * 3; ++i) {
        const float g = guide_points[i];
        if (!hf__finitef(g)) return HF_ERROR_NON_FINITE;
        if (g > HF_MAX_ABS || g < -HF_MAX_ABS) return HF_ERROR_BAD_PARAMETER;
    }
    hf__interpolate_run(guide_points, bindings, first, count, P, clump,
                        out_points, params->out_first, params->simd,
                        hf__streaming(params->nontemporal,
                                      (size_t)count * (size_t)P * 12u,
                                      HF_STREAM_MIN_BYTES));
    return HF_OK;
}

/* ---- 7.3 level of detail ------------------------------------------------ */

HFDEF int hf_lod_strand_count(int total, float lod)
{
    /* round(lod * total) exactly, in integers: lod = m 2^-k with a 24-bit
       m, so m * total fits 55 bits (float arithmetic is off by a few
       strands above 2^24) */
    uint32_t bits, m;
    uint64_t prod;
    int e, k, drawn;
    if (total <= 0 || !(lod > 0.0f)) return 0;
    if (lod >= 1.0f) return total;
    HF_MEMCPY(&bits, &lod, sizeof bits);
    e = (int)((bits >> 23) & 0xffu);
    m = bits & 0x7fffffu;
    if (e) m |= 0x800000u; else e = 1;
    k = 150 - e; /* lod < 1: k >= 24 */
    prod = (uint64_t)m * (uint64_t)total;
    drawn = k >= 64 ? 0
                    : (int)((prod + ((uint64_t)1 << (k - 1))) >> k);
    return drawn < 1 ? 1 : drawn;
}

HFDEF float hf_lod_width_scale(int total, int drawn)
{
    if (drawn <= 0 || drawn >= total) return 1.0f;
    return (float)HF_SQRT((double)total / (double)drawn);
}

HFDEF float hf_lod_from_distance(float distance, float full_detail_distance,
                                 float cull_distance)
{
    float r;
    if (!hf__finitef(distance) || !hf__finitef(full_detail_distance) ||
        !hf__finitef(cull_distance) || distance < 0.0f ||
        full_detail_distance < 0.0f)
        return 1.0f;
    if (distance <= full_detail_distance) return 1.0f;
    if (distance >= cull_distance) return 0.0f;
    r = full_detail_distance / distance;
    return r * r;
}

/* ---- 8. ribbons --------------------------------------------------------- */

/* ---- 8.1 inputs: checks, widths, finite points -------------------------- */

/* Resolve the defaults of `in` into *p and validate everything hf_ribbons
   and hf_ribbon_points share. */
HF__PRIVATE hf_result hf__ribbon_check(const hf_ribbon_strands *strands,
                                       int first, int count,
                                       const hf_ribbon_params *in,
                                       hf_ribbon_params *p)
{
    int k, c;
    if (!strands || !in || !strands->points) return HF_ERROR_NULL_POINTER;
    hf__ribbon_params_resolve(in, p);
    if (p->points_per_strand < 2 || p->points_per_strand > HF_MAX_POINTS)
        return HF_ERROR_BAD_COUNT;
    if (!hf__range_ok(first, count) || p->out_first < 0 ||
        first < p->out_first)
        return HF_ERROR_BAD_RANGE;
    for (k = 0; k < 3; ++k)
        if (!hf__finitef(p->eye[k]) || !hf__finitef(p->view_dir[k]))
            return HF_ERROR_NON_FINITE;
    if (!hf__finitef(p->root_width) || !hf__finitef(p->tip_width) ||
        !hf__finitef(p->taper_power) || !hf__finitef(p->width_scale) ||
        !hf__finitef(p->alpha_root) || !hf__finitef(p->alpha_tip))
        return HF_ERROR_NON_FINITE;
    /* widths and scale bounded so half widths stay finite; alpha is an
       opacity */
    if (p->root_width < 0.0f || p->tip_width < 0.0f ||
        p->taper_power < 0.0f || p->width_scale < 0.0f ||
        p->root_width > HF_MAX_ABS || p->tip_width > HF_MAX_ABS ||
        p->width_scale > HF_MAX_ABS || p->alpha_root < 0.0f ||
        p->alpha_root > 1.0f || p->alpha_tip < 0.0f || p->alpha_tip > 1.0f ||
        !hf__kernels_ok(p->simd, p->nontemporal))
        return HF_ERROR_BAD_PARAMETER;
    if (p->point_format != HF_POINT_F32 && p->point_format != HF_POINT_COMPACT)
        return HF_ERROR_BAD_FORMAT;
    for (k = 0; k < 3; ++k) {
        if (!hf__finitef(p->point_origin[k])) return HF_ERROR_NON_FINITE;
        if (p->point_origin[k] > HF_MAX_ABS || p->point_origin[k] < -HF_MAX_ABS)
            return HF_ERROR_BAD_PARAMETER;
    }
    if (!hf__finitef(p->point_scale)) return HF_ERROR_NON_FINITE;
    if (p->point_scale != 0.0f && !(p->point_scale >= 1.0f / HF_MAX_ABS &&
                                    p->point_scale <= HF_MAX_ABS))
        return HF_ERROR_BAD_PARAMETER;
    if (p->orthographic) {
        /* a view_dir too short to square in float is scaled up by a
           power of two: exact, so the sides are those of its direction */
        float v2 = hf__dot3(p->view_dir, p->view_dir);
        for (k = 0; k < 4 && v2 < 1e-30f; ++k) {
            HF__UNROLL for (c = 0; c < 3; ++c)
                p->view_dir[c] *= 1099511627776.0f;
            v2 = hf__dot3(p->view_dir, p->view_dir);
        }
        if (v2 == 0.0f) return HF_ERROR_DEGENERATE;
    }
    return HF_OK;
}

/* Half widths at t = j / (P - 1) from point j on, with the taper curve
   (resolved p), and t itself where tt is not NULL; *m: the largest so
   far. The reference, any taper; returns P. */
HF__PRIVATE int hf__half_widths_v1(const hf_ribbon_params *p, float *hw,
                                   float *tt, int j, float *m)
{
    const int P = p->points_per_strand;
    const float scale = p->width_scale;
    const float power = p->taper_power;
    for (; j < P; ++j) {
        float t = (float)j / (float)(P - 1);
        float f = power == 1.0f ? t : (float)HF_POW((double)t, (double)power);
        if (j == P - 1) f = 1.0f; /* exact tip width whatever pow rounds */
        /* this form gives root and tip widths exactly at f = 0 and 1 */
        hw[j] = 0.5f * scale * ((1.0f - f) * p->root_width + f * p->tip_width);
        if (tt) tt[j] = t;
        *m = hw[j] > *m ? hw[j] : *m;
    }
    return P;
}

#if HF__SSE
/* The linear taper four points a vector (the same operations, the same
   values); returns where the whole groups end (j, any other taper). */
HF__PRIVATE int hf__half_widths_v4(const hf_ribbon_params *p, float *hw,
                                   float *tt, int j, float *m)
{
    const int P = p->points_per_strand;
    const float scale = p->width_scale;
    if (p->taper_power == 1.0f) {
        const __m128 d = _mm_set1_ps((float)(P - 1)),
                     hs = _mm_set1_ps(0.5f * scale), one = _mm_set1_ps(1.0f),
                     rw = _mm_set1_ps(p->root_width),
                     tw = _mm_set1_ps(p->tip_width);
        __m128 jv = _mm_setr_ps((float)j, (float)j + 1.0f, (float)j + 2.0f,
                                (float)j + 3.0f),
               mv = _mm_set1_ps(*m);
        float mm[4];
        int i;
        for (; j + 4 <= P; j += 4, jv = _mm_add_ps(jv, _mm_set1_ps(4.0f))) {
            const __m128 t = _mm_div_ps(jv, d),
                         h = _mm_mul_ps(
                             hs, _mm_add_ps(_mm_mul_ps(_mm_sub_ps(one, t), rw),
                                            _mm_mul_ps(t, tw)));
            _mm_storeu_ps(hw + j, h);
            if (tt) _mm_storeu_ps(tt + j, t);
            mv = _mm_max_ps(mv, h);
        }
        _mm_storeu_ps(mm, mv);
        for (i = 0; i < 4; ++i) *m = mm[i] > *m ? mm[i] : *m;
    }
    return j;
}
#endif

typedef struct hf__taper_kernels {
    hf__isa isa;
    int (*widths)(const hf_ribbon_params *, float *, float *, int, float *);
} hf__taper_kernels;

static const hf__taper_kernels hf__taper_widths[] = {
#if HF__SSE
    {{HF__ISA_V4}, hf__half_widths_v4},
#endif
    {{HF__ISA_V1}, hf__half_widths_v1}};

/* Half width at t = j / (P - 1), with the taper curve (resolved p, at its
   SIMD level: hf__taper_widths), and t itself where tt is not NULL.
   Returns the largest strand multiplier for them: the product, a
   vertex's half width, stays within HF_MAX_ABS (each factor may reach
   it: their product would overflow to infinity, and a side's zero
   component times infinity is NaN). Every call pays for this (P
   divisions), so the linear taper takes four points a vector. */
HF__PRIVATE float hf__half_widths(const hf_ribbon_params *p, float *hw,
                                  float *tt)
{
    const hf__taper_kernels *k = hf__kernels_for(hf__taper_widths, p->simd);
    float m = 1.0f;
    int j = 0;
    for (; j < p->points_per_strand; ++k) j = k->widths(p, hw, tt, j, &m);
    return HF_MAX_ABS / m;
}

/* A unit vector perpendicular to unit t, chosen deterministically. */
HF__PRIVATE void hf__any_perp(const float *t, float *o)
{
    float a[3] = {0.0f, 0.0f, 0.0f}, l;
    /* cross with the axis least aligned with t */
    float ax = HF_FABS(t[0]), ay = HF_FABS(t[1]), az = HF_FABS(t[2]);
    a[(ax <= ay && ax <= az) ? 0 : (ay <= az ? 1 : 2)] = 1.0f;
    hf__cross3(o, t, a);
    l = HF_SQRTF(hf__dot3(o, o));
    o[0] /= l;
    o[1] /= l;
    o[2] /= l;
}

/* inv[i] = 1 / sqrt(x[i]), for the reference frame */
HF__PRIVATE void hf__inv_sqrt_n(const float *x, float *inv, int n)
{
    int i;
    for (i = 0; i < n; ++i) inv[i] = 1.0f / HF_SQRTF(x[i]);
}

/* 1 when the n coordinates from float i of a strand are finite: x * 0 is
   0 for finite x and NaN for NaN or infinity, and the sum keeps any NaN.
   The reference (i = 0), and the tail of hf__points_finite_v4. */
HF__PRIVATE int hf__points_finite_from(const float *pts, int i, int n)
{
    float acc0 = 0.0f, acc1 = 0.0f;
    for (; i + 2 <= n; i += 2) {
        acc0 += pts[i] * 0.0f;
        acc1 += pts[i + 1] * 0.0f;
    }
    if (i < n) acc0 += pts[i] * 0.0f;
    return acc0 + acc1 == 0.0f;
}
HF__PRIVATE int hf__points_finite_v1(const float *pts, int n)
{
    return hf__points_finite_from(pts, 0, n);
}
#if HF__SSE
/* The same test, whole groups of 8 floats with two independent vector
   sums (a single scalar chain of dependent adds cost a sixth of the
   ribbon time), the rest by the reference. */
HF__PRIVATE int hf__points_finite_v4(const float *pts, int n)
{
    const __m128 z = _mm_setzero_ps();
    __m128 a0 = z, a1 = z;
    int i = 0;
    for (; i + 8 <= n; i += 8) {
        a0 = _mm_add_ps(a0, _mm_mul_ps(_mm_loadu_ps(pts + i), z));
        a1 = _mm_add_ps(a1, _mm_mul_ps(_mm_loadu_ps(pts + i + 4), z));
    }
    if (_mm_movemask_ps(_mm_cmpeq_ps(_mm_add_ps(a0, a1), z)) != 0xf) return 0;
    return hf__points_finite_from(pts, i, n);
}
#endif

/* A strand whose points are not all finite is drawn collapsed: every
   point at the origin with zero width, so nothing shows and no NaN reaches
   the vertex buffer. */
static const float hf__zero_points[3 * HF_MAX_POINTS] = {0.0f};

/* Optional per-strand inputs are copied through; a non-finite one reads as
   0, so no NaN reaches a vertex. */
HF__PRIVATE float hf__fin0(float x) { return hf__finitef(x) ? x : 0.0f; }

/* Strand s's width multiplier from the strands' width array: 1 without
   the array, else the value, with negative or non-finite read as 0, and
   at most cap (what hf__half_widths returns). The kernels pass the
   array's address read once a call: their stores may alias the strands'
   record. */
HF__INLINE float hf__width_at(const float *width, int s, float cap)
{
    const float w = width ? hf__fin0(width[s]) : 1.0f;
    return w > 0.0f ? (w < cap ? w : cap) : 0.0f;
}

/* ---- 8.2 the strand frame: tangents and sides --------------------------- */

/* One strand in structure-of-arrays rows, so that four points load as one
   vector: in every row, point j is at index 4 + j. The point rows repeat
   point 0 before it and point P - 1 after it (one-sided differences at the
   ends then fall out of the central ones); entries past P - 1 in the other
   rows hold copies, so a partial group of four or eight computes on
   finite values. */
#define HF__RROW (HF_MAX_POINTS + 12)
typedef struct hf__rframe {
    float p[3][HF__RROW]; /* points */
    float t[3][HF__RROW]; /* unit tangents */
    float s[3][HF__RROW]; /* unit sides */
} hf__rframe;

/* Below this sin^2 of the angle between view and tangent (about half a
   degree) a side is computed in double (hf__side_precise): float
   cancellation in the cross product tilts it by a few 1e-8 / sin, 3e-6 at
   this bound (measured). */
#define HF__SIDE_SIN2 1e-4f

/* The side of point j in double: unit cross(t, v) rounded once. 0 when t
   and v are parallel (to 1e-6) or the eye sits on the point. */
HF__PRIVATE int hf__side_precise(hf__rframe *fr, const float *pts, int j,
                                 const hf_ribbon_params *params)
{
    double t[3], v[3], c[3], c2, v2;
    int k;
    for (k = 0; k < 3; ++k) {
        t[k] = (double)fr->t[k][4 + j];
        v[k] = params->orthographic
                   ? -(double)params->view_dir[k]
                   : (double)params->eye[k] - (double)pts[3 * j + k];
    }
    c[0] = t[1] * v[2] - t[2] * v[1];
    c[1] = t[2] * v[0] - t[0] * v[2];
    c[2] = t[0] * v[1] - t[1] * v[0];
    c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (!(c2 > 1e-12 * v2 && c2 > 1e-300 && c2 < 1e300)) return 0;
    c2 = 1.0 / HF_SQRT(c2);
    for (k = 0; k < 3; ++k) fr->s[k][4 + j] = (float)(c[k] * c2);
    return 1;
}

/* Point j takes point `from`'s side minus its component along j's own
   tangent, renormalised; a fixed perpendicular of the tangent where the
   two are parallel. */
HF__PRIVATE void hf__side_borrow(hf__rframe *fr, int j, int from)
{
    float t[3], s[3], st, l2;
    int k;
    for (k = 0; k < 3; ++k) {
        t[k] = fr->t[k][4 + j];
        s[k] = fr->s[k][4 + from];
    }
    st = hf__dot3(s, t);
    for (k = 0; k < 3; ++k) s[k] -= st * t[k];
    l2 = hf__dot3(s, s);
    if (l2 > 1e-12f) {
        l2 = 1.0f / HF_SQRTF(l2);
        for (k = 0; k < 3; ++k) s[k] *= l2;
    } else {
        hf__any_perp(t, s);
    }
    for (k = 0; k < 3; ++k) fr->s[k][4 + j] = s[k];
}

/* The reference: unit tangents and sides of one strand, a point at a time
   (see hf_ribbons for the rules on degenerate points). The four-lane
   and AVX2 kernels below give the same bytes where they apply. */
HF__PRIVATE void hf__strand_frame_v1(const float *pts, int P,
                                     const hf_ribbon_params *params,
                                     hf__rframe *fr)
{
    float d[HF_MAX_POINTS * 3], l2[HF_MAX_POINTS], inv[HF_MAX_POINTS];
    float last[3] = {0.0f, 1.0f, 0.0f};
    const int ortho = params->orthographic != 0, end = ((P + 7) & ~7) + 8;
    int j, k, first_t = -1, first_ok = -1;
    if (P < 2 || P > HF_MAX_POINTS) return; /* checked by the callers */
    HF__UNROLL for (k = 0; k < 3; ++k) {
        float *row = fr->p[k];
        HF__UNROLL for (j = 0; j < 4; ++j) row[j] = pts[k];
        for (j = 0; j < P; ++j) row[4 + j] = pts[3 * j + k];
        for (j = 4 + P; j < end; ++j) row[j] = pts[3 * (P - 1) + k];
    }
    /* tangents: central differences, one-sided at the ends */
    for (j = 0; j < P; ++j) {
        const float *a = pts + 3 * (j > 0 ? j - 1 : 0);
        const float *b = pts + 3 * (j < P - 1 ? j + 1 : P - 1);
        float *dj = d + 3 * j;
        hf__sub3(dj, b, a);
        l2[j] = hf__dot3(dj, dj);
    }
    hf__inv_sqrt_n(l2, inv, P);
    for (j = 0; j < P; ++j) {
        /* a zero-length segment keeps the previous tangent */
        if (l2[j] > 1e-30f && hf__finitef(l2[j])) {
            last[0] = d[3 * j] * inv[j];
            last[1] = d[3 * j + 1] * inv[j];
            last[2] = d[3 * j + 2] * inv[j];
            if (first_t < 0) first_t = j;
        }
        HF__UNROLL for (k = 0; k < 3; ++k) fr->t[k][4 + j] = last[k];
    }
    /* points before the first that has a tangent take that one */
    for (j = first_t - 1; j >= 0; --j)
        HF__UNROLL for (k = 0; k < 3; ++k) fr->t[k][4 + j] = fr->t[k][5 + j];
    /* sides: cross(a, v), v = eye - p or -view_dir, a the difference d
       where the point has a tangent of its own (so the side need not wait
       for the tangent's normalisation: the kernels run both at once), else
       its borrowed unit tangent; d now holds the cross products and inv
       their reciprocal lengths. In float where the view is at least
       HF__SIDE_SIN2 off the tangent (|c|^2 = |v|^2 |a|^2 sin^2); nearer,
       float cancellation would tilt the side, so those points are marked
       (-2) and done in double below */
    for (j = 0; j < P; ++j) {
        const int own = l2[j] > 1e-30f && hf__finitef(l2[j]);
        const float a2 = own ? l2[j] : 1.0f;
        float v[3], a[3];
        HF__UNROLL for (k = 0; k < 3; ++k) {
            a[k] = own ? d[3 * j + k] : fr->t[k][4 + j];
            v[k] = ortho ? -params->view_dir[k]
                         : params->eye[k] - pts[3 * j + k];
        }
        hf__cross3(d + 3 * j, a, v);
        l2[j] = hf__dot3(d + 3 * j, d + 3 * j);
        inv[j] = hf__dot3(v, v); /* parked: |v|^2 */
        if (!(l2[j] > HF__SIDE_SIN2 * inv[j] * a2 && l2[j] > 1e-30f &&
              hf__finitef(l2[j])))
            l2[j] = -2.0f;
    }
    for (j = 0; j < P; ++j) inv[j] = l2[j] > 0.0f ? l2[j] : 1.0f;
    hf__inv_sqrt_n(inv, inv, P);
    for (j = 0; j < P; ++j) {
        if (l2[j] > 0.0f)
            HF__UNROLL for (k = 0; k < 3; ++k)
                fr->s[k][4 + j] = d[3 * j + k] * inv[j];
        else if (hf__side_precise(fr, pts, j, params))
            l2[j] = 1.0f;
        else
            l2[j] = -1.0f; /* no side: parallel view, or the eye on p */
        if (l2[j] > 0.0f && first_ok < 0) first_ok = j;
    }
    if (first_ok < 0) {
        /* no point has a side: a fixed perpendicular of the tangent */
        float t0[3], s0[3];
        for (k = 0; k < 3; ++k) t0[k] = fr->t[k][4];
        hf__any_perp(t0, s0);
        for (k = 0; k < 3; ++k) fr->s[k][4] = s0[k];
        first_ok = 0;
        l2[0] = 1.0f;
    }
    /* a point without a side borrows its neighbour's (the previous one,
       before the first side the next one), made perpendicular to its own
       tangent */
    for (j = first_ok + 1; j < P; ++j)
        if (l2[j] < 0.0f) hf__side_borrow(fr, j, j - 1);
    for (j = first_ok - 1; j >= 0; --j) hf__side_borrow(fr, j, j + 1);
    for (j = 4 + P; j < end - 4; ++j)
        HF__UNROLL for (k = 0; k < 3; ++k) {
            fr->t[k][j] = fr->t[k][3 + P];
            fr->s[k][j] = fr->s[k][3 + P];
        }
}

#if HF__V4
/* (p3, c0, c1, c2) and (c1, c2, c3, n0): each point's neighbours; and
   four points (12 floats at q) as their x, y and z. */
#if HF__SSE
HF__INLINE __m128 hf__prev_v4(__m128 p, __m128 c)
{
    return _mm_shuffle_ps(_mm_shuffle_ps(p, c, _MM_SHUFFLE(0, 0, 3, 3)), c,
                          _MM_SHUFFLE(2, 1, 2, 0));
}
HF__INLINE __m128 hf__next_v4(__m128 c, __m128 n)
{
    return _mm_shuffle_ps(c, _mm_shuffle_ps(c, n, _MM_SHUFFLE(0, 0, 3, 3)),
                          _MM_SHUFFLE(2, 0, 2, 1));
}
/* The last n (1-3) lanes of q moved to the first n, the last repeated
   after them. */
HF__INLINE __m128 hf__tail_v4(__m128 q, int n)
{
    if (n == 1) return _mm_shuffle_ps(q, q, _MM_SHUFFLE(3, 3, 3, 3));
    if (n == 2) return _mm_shuffle_ps(q, q, _MM_SHUFFLE(3, 3, 3, 2));
    return _mm_shuffle_ps(q, q, _MM_SHUFFLE(3, 3, 2, 1));
}
/* by shuffles, so no load waits on the narrow stores of a just-written
   array */
HF__INLINE void hf__load3_v4(const float *q, __m128 *X, __m128 *Y, __m128 *Z)
{
    const __m128 a0 = _mm_loadu_ps(q), a1 = _mm_loadu_ps(q + 4),
                 a2 = _mm_loadu_ps(q + 8);
    /* a0 = x0 y0 z0 x1, a1 = y1 z1 x2 y2, a2 = z2 x3 y3 z3 */
    const __m128 u = _mm_shuffle_ps(a1, a2, _MM_SHUFFLE(0, 1, 3, 2));
    const __m128 v = _mm_shuffle_ps(a0, a1, _MM_SHUFFLE(1, 0, 2, 1));
    const __m128 w = _mm_shuffle_ps(a1, a2, _MM_SHUFFLE(3, 2, 2, 3));
    *X = _mm_shuffle_ps(a0, u, _MM_SHUFFLE(2, 0, 3, 0));
    *Y = _mm_shuffle_ps(v, w, _MM_SHUFFLE(2, 0, 2, 0));
    *Z = _mm_shuffle_ps(v, _mm_shuffle_ps(u, w, _MM_SHUFFLE(3, 0, 0, 3)),
                        _MM_SHUFFLE(3, 0, 3, 1));
}
#else
HF__INLINE float32x4_t hf__prev_v4(float32x4_t p,
                                                  float32x4_t c)
{
    return vextq_f32(p, c, 3);
}
HF__INLINE float32x4_t hf__next_v4(float32x4_t c,
                                                  float32x4_t n)
{
    return vextq_f32(c, n, 1);
}
HF__INLINE float32x4_t hf__tail_v4(float32x4_t q, int n)
{
    const float32x4_t tip = vdupq_laneq_f32(q, 3);
    if (n == 1) return tip;
    if (n == 2) return vextq_f32(q, tip, 2);
    return vextq_f32(q, tip, 1);
}
HF__INLINE void hf__load3_v4(const float *q, float32x4_t *X,
                                            float32x4_t *Y, float32x4_t *Z)
{
    const float32x4x3_t v = vld3q_f32(q);
    *X = v.val[0];
    *Y = v.val[1];
    *Z = v.val[2];
}
#endif

/* Group k of a frame's point rows, its finiteness added to acc (x * 0 is
   NaN for NaN or infinity). */
HF__INLINE hf__v4 hf__row_put_v4(hf__rframe *fr, int k, hf__v4 X, hf__v4 Y,
                                 hf__v4 Z, hf__v4 acc)
{
    const hf__v4 zero = HF__SET1(0.0f);
    HF__ST(fr->p[0] + 4 + 4 * k, X);
    HF__ST(fr->p[1] + 4 + 4 * k, Y);
    HF__ST(fr->p[2] + 4 + 4 * k, Z);
    return HF__ADD(acc, HF__ADD(HF__MUL(X, zero),
                                HF__ADD(HF__MUL(Y, zero), HF__MUL(Z, zero))));
}

/* hf__strand_frame_v1 four points at a time (SSE2 or NEON), with the same
   IEEE operations per point. Returns 0 and leaves the strand to the
   reference when a point is not finite (*finite = 0), has no tangent, or
   sees the view within HF__SIDE_SIN2 of its tangent: the rare cases whose
   rules look along the strand or need double precision. */
HF__PRIVATE int hf__strand_frame_v4(const float *pts, int P,
                                                 const hf_ribbon_params *params,
                                                 hf__rframe *fr, int *finite)
{
    static const float lanes[4] = {0.0f, 1.0f, 2.0f, 3.0f};
    const int G = (P + 3) >> 2, ortho = params->orthographic != 0;
    const hf__v4 zero = HF__SET1(0.0f), one = HF__SET1(1.0f);
    const hf__v4 tiny = HF__SET1(1e-30f);
    const hf__v4 side_sin2 = HF__SET1(HF__SIDE_SIN2);
    const hf__v4 big = HF__SET1(3.40282347e+38f);
    const hf__v4 lane = HF__LD(lanes);
    hf__v4 acc = zero, e[3];
    int k, c, bad = 0;
    /* rows: four points a group, deinterleaved; the whole groups in a
       loop of their own */
    for (k = 0; 4 * k + 4 <= P; ++k) {
        hf__v4 X, Y, Z;
        hf__load3_v4(pts + 12 * k, &X, &Y, &Z);
        acc = hf__row_put_v4(fr, k, X, Y, Z, acc);
    }
    if (4 * k < P) {
        const int n = P - 4 * k;
        hf__v4 X, Y, Z;
        if (P >= 4) {
            /* the last, partial group from the strand's last four points,
               moved down and the tip repeated (a copy through the stack
               would wait on failed store forwards) */
            hf__load3_v4(pts + 3 * (P - 4), &X, &Y, &Z);
            X = hf__tail_v4(X, n);
            Y = hf__tail_v4(Y, n);
            Z = hf__tail_v4(Z, n);
        } else { /* P < 4: the only group repeats the tip */
            float r[3][4];
            int i;
            HF__UNROLL for (i = 0; i < 4; ++i)
                HF__UNROLL for (c = 0; c < 3; ++c)
                    r[c][i] = pts[3 * (i < n ? i : n - 1) + c];
            X = HF__LD(r[0]);
            Y = HF__LD(r[1]);
            Z = HF__LD(r[2]);
        }
        acc = hf__row_put_v4(fr, k, X, Y, Z, acc);
    }
    if (HF__MASK(HF__EQ(acc, zero)) != 0xf) {
        *finite = 0;
        return 0;
    }
    *finite = 1;
    HF__UNROLL for (c = 0; c < 3; ++c) {
        HF__ST(fr->p[c], HF__SET1(pts[c]));
        HF__ST(fr->p[c] + 4 + 4 * G, HF__SET1(pts[3 * (P - 1) + c]));
        e[c] = HF__SET1(ortho ? -params->view_dir[c] : params->eye[c]);
    }
    for (k = 0; k < G; ++k) {
        const int o = 4 + 4 * k;
        const int live = HF__MASK(HF__LT(lane, HF__SET1((float)(P - 4 * k))));
        hf__v4 d[3], t[3], v[3], s[3], l2, c2, vv, ok, ok2, inv;
        HF__UNROLL for (c = 0; c < 3; ++c) {
            const float *r = fr->p[c] + o;
            const hf__v4 cur = HF__LD(r);
            d[c] = HF__SUB(hf__next_v4(cur, HF__LD(r + 4)),
                           hf__prev_v4(HF__LD(r - 4), cur));
            v[c] = ortho ? e[c] : HF__SUB(e[c], cur);
        }
        l2 = HF__DOT3(d[0], d[1], d[2], d[0], d[1], d[2]);
        ok = HF__AND(HF__GT(l2, tiny), HF__LE(l2, big));
        /* 1 where undefined: no division by zero for any lane */
        inv = HF__DIV(one, HF__SQRT(HF__SEL(ok, l2, one)));
        HF__UNROLL for (c = 0; c < 3; ++c) t[c] = HF__MUL(d[c], inv);
        HF__CROSS3(s, d, v);
        c2 = HF__DOT3(s[0], s[1], s[2], s[0], s[1], s[2]);
        vv = HF__DOT3(v[0], v[1], v[2], v[0], v[1], v[2]);
        ok2 = HF__AND(HF__GT(c2, HF__MUL(HF__MUL(side_sin2, vv), l2)),
                      HF__AND(HF__GT(c2, tiny), HF__LE(c2, big)));
        bad |= live & ~HF__MASK(HF__AND(ok, ok2));
        inv = HF__DIV(one, HF__SQRT(HF__SEL(ok2, c2, one)));
        HF__UNROLL for (c = 0; c < 3; ++c) {
            HF__ST(fr->t[c] + o, t[c]);
            HF__ST(fr->s[c] + o, HF__MUL(s[c], inv));
        }
    }
    return bad == 0;
}
#endif

#if HF__AVX2
/* Lanes (p7, c0 .. c6) and (c1 .. c7, n0): each point's neighbours across
   two groups of eight. */
HF__TARGET_AVX2 HF__INLINE __m256 hf__prev_v8(__m256 p, __m256 c)
{
    const __m256 t = _mm256_permute2f128_ps(p, c, 0x21);
    return _mm256_castsi256_ps(_mm256_alignr_epi8(
        _mm256_castps_si256(c), _mm256_castps_si256(t), 12));
}
HF__TARGET_AVX2 HF__INLINE __m256 hf__next_v8(__m256 c, __m256 n)
{
    const __m256 t = _mm256_permute2f128_ps(c, n, 0x21);
    return _mm256_castsi256_ps(_mm256_alignr_epi8(
        _mm256_castps_si256(t), _mm256_castps_si256(c), 4));
}

/* One coordinate's central differences for the group whose values `cur`
   sit at row[0..8): the next group follows in the row, or the tip
   repeats after the last; *prev carries the group before. */
HF__TARGET_AVX2 HF__INLINE __m256 hf__diff_v8(const float *row, int last,
                                              float tip, __m256 cur,
                                              __m256 *prev)
{
    const __m256 next =
        last ? _mm256_set1_ps(tip) : _mm256_loadu_ps(row + 8);
    const __m256 d =
        _mm256_sub_ps(hf__next_v8(cur, next), hf__prev_v8(*prev, cur));
    *prev = cur;
    return d;
}

/* Group k of the AVX2 frame (points 8 k ..): tangents and sides into
   fr; returns the live lanes whose tangent or side is left to the
   reference. last: the tip repeats after it; ortho: e is the view
   direction (negated), else the eye. Inlined with both as constants. */
HF__TARGET_AVX2 HF__INLINE int
hf__frame_group_v8(hf__rframe *fr, int k, int P, int last, int ortho,
                   const float *tip, __m256 ex, __m256 ey, __m256 ez,
                   __m256 *px, __m256 *py, __m256 *pz)
{
    const __m256 one = _mm256_set1_ps(1.0f);
    const __m256 tiny = _mm256_set1_ps(1e-30f);
    const __m256 side_sin2 = _mm256_set1_ps(HF__SIDE_SIN2);
    const __m256 big = _mm256_set1_ps(3.40282347e+38f);
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const int o = 4 + 8 * k;
    /* lanes of points that exist: all but in the last group */
    const __m256 live =
        last ? _mm256_castsi256_ps(
                   _mm256_cmpgt_epi32(_mm256_set1_epi32(P - 8 * k), lane))
             : _mm256_castsi256_ps(_mm256_set1_epi32(-1));
    const __m256 cx = _mm256_loadu_ps(fr->p[0] + o),
                 cy = _mm256_loadu_ps(fr->p[1] + o),
                 cz = _mm256_loadu_ps(fr->p[2] + o);
    const __m256 dx = hf__diff_v8(fr->p[0] + o, last, tip[0], cx, px),
                 dy = hf__diff_v8(fr->p[1] + o, last, tip[1], cy, py),
                 dz = hf__diff_v8(fr->p[2] + o, last, tip[2], cz, pz);
    const __m256 vx = ortho ? ex : _mm256_sub_ps(ex, cx),
                 vy = ortho ? ey : _mm256_sub_ps(ey, cy),
                 vz = ortho ? ez : _mm256_sub_ps(ez, cz);
    const __m256 l2 = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
        _mm256_mul_ps(dz, dz));
    const __m256 ok = _mm256_and_ps(_mm256_cmp_ps(l2, tiny, _CMP_GT_OQ),
                                    _mm256_cmp_ps(l2, big, _CMP_LE_OQ));
    /* 1 where undefined: no division by zero for any lane */
    const __m256 inv = _mm256_div_ps(
        one, _mm256_sqrt_ps(_mm256_blendv_ps(one, l2, ok)));
    const __m256 tx = _mm256_mul_ps(dx, inv), ty = _mm256_mul_ps(dy, inv),
                 tz = _mm256_mul_ps(dz, inv);
    const __m256 sx = _mm256_sub_ps(_mm256_mul_ps(dy, vz), _mm256_mul_ps(dz, vy)),
                 sy = _mm256_sub_ps(_mm256_mul_ps(dz, vx), _mm256_mul_ps(dx, vz)),
                 sz = _mm256_sub_ps(_mm256_mul_ps(dx, vy), _mm256_mul_ps(dy, vx));
    const __m256 c2 = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(sx, sx), _mm256_mul_ps(sy, sy)),
        _mm256_mul_ps(sz, sz));
    const __m256 vv = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(vx, vx), _mm256_mul_ps(vy, vy)),
        _mm256_mul_ps(vz, vz));
    const __m256 ok2 = _mm256_and_ps(
        _mm256_cmp_ps(c2, _mm256_mul_ps(_mm256_mul_ps(side_sin2, vv), l2),
                      _CMP_GT_OQ),
        _mm256_and_ps(_mm256_cmp_ps(c2, tiny, _CMP_GT_OQ),
                      _mm256_cmp_ps(c2, big, _CMP_LE_OQ)));
    const __m256 inv2 = _mm256_div_ps(
        one, _mm256_sqrt_ps(_mm256_blendv_ps(one, c2, ok2)));
    _mm256_storeu_ps(fr->t[0] + o, tx);
    _mm256_storeu_ps(fr->t[1] + o, ty);
    _mm256_storeu_ps(fr->t[2] + o, tz);
    _mm256_storeu_ps(fr->s[0] + o, _mm256_mul_ps(sx, inv2));
    _mm256_storeu_ps(fr->s[1] + o, _mm256_mul_ps(sy, inv2));
    _mm256_storeu_ps(fr->s[2] + o, _mm256_mul_ps(sz, inv2));
    return _mm256_movemask_ps(_mm256_andnot_ps(_mm256_and_ps(ok, ok2), live));
}

/* One group's point rows into fr, their finiteness added to *acc (x * 0
   is NaN for NaN or infinity). */
HF__TARGET_AVX2 HF__INLINE void hf__row_put_v8(hf__rframe *fr, int k, __m256 X,
                                               __m256 Y, __m256 Z, __m256 *acc)
{
    const __m256 zero = _mm256_setzero_ps();
    *acc = _mm256_add_ps(
        *acc, _mm256_add_ps(_mm256_mul_ps(X, zero),
                            _mm256_add_ps(_mm256_mul_ps(Y, zero),
                                          _mm256_mul_ps(Z, zero))));
    _mm256_storeu_ps(fr->p[0] + 4 + 8 * k, X);
    _mm256_storeu_ps(fr->p[1] + 4 + 8 * k, Y);
    _mm256_storeu_ps(fr->p[2] + 4 + 8 * k, Z);
}

/* The frame's e in every lane: the view direction, negated, for an
   orthographic view, else the eye; once per call. */
HF__TARGET_AVX2 HF__INLINE void hf__frame_eye_v8(const hf_ribbon_params *params,
                                                 __m256 *e)
{
    int c;
    HF__UNROLL for (c = 0; c < 3; ++c)
        e[c] = _mm256_set1_ps(params->orthographic ? -params->view_dir[c]
                                                   : params->eye[c]);
}

/* Eight points' x, y and z (24 floats at q) in three vectors, by
   shuffles. */
HF__TARGET_AVX2 HF__INLINE void hf__load8_v8(const float *q, __m256 *xyz)
{
#define HF__LD2(a, b)                                                          \
    _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(q + (a))),      \
                         _mm_loadu_ps(q + (b)), 1)
    /* halves: points 0-3 and 4-7, as x0 y0 z0 x1 | y1 z1 x2 y2 |
       z2 x3 y3 z3 */
    const __m256 m03 = HF__LD2(0, 12), m14 = HF__LD2(4, 16),
                 m25 = HF__LD2(8, 20);
#undef HF__LD2
    const __m256 xy = _mm256_shuffle_ps(m14, m25, _MM_SHUFFLE(2, 1, 3, 2));
    const __m256 yz = _mm256_shuffle_ps(m03, m14, _MM_SHUFFLE(1, 0, 2, 1));
    xyz[0] = _mm256_shuffle_ps(m03, xy, _MM_SHUFFLE(2, 0, 3, 0));
    xyz[1] = _mm256_shuffle_ps(yz, xy, _MM_SHUFFLE(3, 1, 2, 0));
    xyz[2] = _mm256_shuffle_ps(yz, m25, _MM_SHUFFLE(3, 0, 3, 1));
}

/* hf__strand_frame_v4 eight points at a time, with the same IEEE
   operations per point, and the same cases left to the reference;
   ortho and e as hf__frame_eye_v8 gives them. */
HF__TARGET_AVX2 HF__INLINE int
hf__strand_frame_v8_in(const float *pts, int P, int ortho, const __m256 *e,
                       hf__rframe *fr, int *finite)
{
    const __m256 ex = e[0], ey = e[1], ez = e[2];
    const int G = (P + 7) >> 3;
    const __m256 zero = _mm256_setzero_ps();
    __m256 acc = zero, px, py, pz;
    float tip[3];
    int k, c, bad = 0;
    /* rows: eight points (24 floats) deinterleaved by shuffles; the
       whole groups in a loop of their own (no test for the last) */
    for (k = 0; 8 * k + 8 <= P; ++k) {
        __m256 xyz[3];
        hf__load8_v8(pts + 24 * k, xyz);
        hf__row_put_v8(fr, k, xyz[0], xyz[1], xyz[2], &acc);
    }
    if (8 * k < P && P >= 8) {
        /* the last, partial group from the strand's last eight points,
           moved down to its first and the tip repeated past the end (a
           copy through the stack would wait on failed store forwards) */
        const int n = P - 8 * k;
        const __m256i shift = _mm256_min_epi32(
            _mm256_add_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7),
                             _mm256_set1_epi32(8 - n)),
            _mm256_set1_epi32(7));
        __m256 xyz[3];
        hf__load8_v8(pts + 3 * (P - 8), xyz);
        hf__row_put_v8(fr, k, _mm256_permutevar8x32_ps(xyz[0], shift),
                       _mm256_permutevar8x32_ps(xyz[1], shift),
                       _mm256_permutevar8x32_ps(xyz[2], shift), &acc);
    } else if (8 * k < P) { /* P < 8: the only group repeats the tip */
        const int n = P - 8 * k;
        float r[3][8];
        int i;
        for (i = 0; i < 8; ++i)
            HF__UNROLL for (c = 0; c < 3; ++c)
                r[c][i] = pts[3 * (8 * k + (i < n ? i : n - 1)) + c];
        hf__row_put_v8(fr, k, _mm256_loadu_ps(r[0]), _mm256_loadu_ps(r[1]),
                       _mm256_loadu_ps(r[2]), &acc);
    }
    if (_mm256_movemask_ps(_mm256_cmp_ps(acc, zero, _CMP_EQ_OQ)) != 0xff) {
        *finite = 0;
        return 0;
    }
    *finite = 1;
    HF__UNROLL for (c = 0; c < 3; ++c) {
        _mm_storeu_ps(fr->p[c], _mm_set1_ps(pts[c]));
        tip[c] = pts[3 * (P - 1) + c];
    }
    px = _mm256_set1_ps(pts[0]);
    py = _mm256_set1_ps(pts[1]);
    pz = _mm256_set1_ps(pts[2]);
    /* every group but the last reads its next neighbours from the row;
       the perspective and orthographic bodies apart: no test per group */
    if (ortho) {
        for (k = 0; k + 1 < G; ++k)
            bad |= hf__frame_group_v8(fr, k, P, 0, 1, tip, ex, ey, ez, &px, &py,
                                      &pz);
        bad |=
            hf__frame_group_v8(fr, k, P, 1, 1, tip, ex, ey, ez, &px, &py, &pz);
    } else {
        for (k = 0; k + 1 < G; ++k)
            bad |= hf__frame_group_v8(fr, k, P, 0, 0, tip, ex, ey, ez, &px, &py,
                                      &pz);
        bad |=
            hf__frame_group_v8(fr, k, P, 1, 0, tip, ex, ey, ez, &px, &py, &pz);
    }
    return bad == 0;
}

/* the frame above as a call, for the dispatch of one strand (the inline
   bodies, *_v8_in, leave the upper halves to the function they are
   inlined in: its calls and its return clear them) */
HF__TARGET_AVX2 HF__PRIVATE int
hf__strand_frame_v8(const float *pts, int P, const hf_ribbon_params *params,
                    hf__rframe *fr, int *finite)
{
    __m256 e[3];
    int ok;
    hf__frame_eye_v8(params, e);
    ok = hf__strand_frame_v8_in(pts, P, params->orthographic != 0, e, fr,
                                finite);
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
    return ok;
}
#endif

/* A strand's frame by the reference, also where a vector frame left it:
   *finite says whether its points are (-1: not known yet); one that is
   not is framed collapsed. Returns 1, done. */
HF__PRIVATE int hf__strand_frame_rest(const float *pts, int P,
                                      const hf_ribbon_params *params,
                                      hf__rframe *fr, int *finite)
{
    if (*finite < 0) *finite = hf__points_finite_v1(pts, 3 * P);
    hf__strand_frame_v1(*finite ? pts : hf__zero_points, P, params, fr);
    return 1;
}

typedef struct hf__frame_kernels {
    hf__isa isa;
    int (*frame)(const float *, int, const hf_ribbon_params *, hf__rframe *,
                 int *);
} hf__frame_kernels;

/* The strand frames per width; the AVX-512 level runs the AVX2 kernel. */
static const hf__frame_kernels hf__frame_widths[] = {
#if HF__AVX2
    {{HF__ISA_V8}, hf__strand_frame_v8},
#endif
#if HF__V4
    {{HF__ISA_V4}, hf__strand_frame_v4},
#endif
    {{HF__ISA_V1}, hf__strand_frame_rest}};

/* The dispatch of the strand frame with the kernels k (hf__frame_widths,
   resolved once a call): tangents and sides, and *wscale 0 for a strand
   with a non-finite point, which is framed collapsed. A vector kernel
   declines the strands whose rules look along the strand or need double
   precision: those go to the reference, not to the next width. */
HF__PRIVATE void hf__strand_frame(const float *pts, int P,
                                  const hf_ribbon_params *params,
                                  hf__rframe *fr, float *wscale,
                                  const hf__frame_kernels *k)
{
    int finite = -1;
    if (!k->frame(pts, P, params, fr, &finite))
        hf__strand_frame_rest(pts, P, params, fr, &finite);
    *wscale = finite ? 1.0f : 0.0f;
}

/* ---- 8.3 vertex formats: encoding --------------------------------------- */

HFDEF int hf_format_bytes(int format)
{
    switch (format) {
    case HF_FORMAT_F32: return 4;
    case HF_FORMAT_F16:
    case HF_FORMAT_SNORM16:
    case HF_FORMAT_UNORM16: return 2;
    case HF_FORMAT_SNORM8:
    case HF_FORMAT_UNORM8: return 1;
    default: return 0;
    }
}

/* round to nearest even for |v| <= 2^22: adding 1.5 * 2^23 leaves no
   fraction bits, and the subtraction is exact (t is a float variable so
   that x87 excess precision cannot keep the fraction) */
HF__PRIVATE float hf__round_even(float v)
{
    const float t = v + 12582912.0f;
    return t - 12582912.0f;
}

HF__PRIVATE float hf__clampf(float x, float lo, float hi)
{
    return x < lo ? lo : (x > hi ? hi : x);
}

/* One component in a non-float format, as the low bits of the result.
   The SSE encoder below performs the same operations on four lanes. */
HF__PRIVATE uint32_t hf__encode1(float x, int fmt)
{
    uint32_t u, sign, h;
    switch (fmt) {
    case HF_FORMAT_F16:
        /* round to nearest even; beyond the largest half, the largest
           half (a vertex never gets infinity) */
        x = hf__clampf(x, -65504.0f, 65504.0f);
        HF_MEMCPY(&u, &x, 4);
        sign = (u >> 16) & 0x8000u;
        u &= 0x7fffffffu;
        if (u < 0x38800000u) { /* below 2^-14: subnormal half */
            float a;
            HF_MEMCPY(&a, &u, 4);
            a += 0.5f; /* rounds to a multiple of 2^-24 in the low bits */
            HF_MEMCPY(&h, &a, 4);
            h -= 0x3f000000u;
        } else {
            h = (u + 0xc8000fffu + ((u >> 13) & 1u)) >> 13;
        }
        return h | sign;
    case HF_FORMAT_SNORM16:
        return (uint32_t)(int32_t)hf__round_even(
                   hf__clampf(x, -1.0f, 1.0f) * 32767.0f) & 0xffffu;
    case HF_FORMAT_UNORM16:
        return (uint32_t)hf__round_even(hf__clampf(x, 0.0f, 1.0f) * 65535.0f);
    case HF_FORMAT_SNORM8:
        return (uint32_t)(int32_t)hf__round_even(
                   hf__clampf(x, -1.0f, 1.0f) * 127.0f) & 0xffu;
    default: /* HF_FORMAT_UNORM8 */
        return (uint32_t)hf__round_even(hf__clampf(x, 0.0f, 1.0f) * 255.0f);
    }
}

/* One vertex: components c[0, nc) at o in format fmt. */
HF__PRIVATE void hf__emit1(unsigned char *o, const float *c, int nc, int fmt)
{
    int i;
    const int size = hf_format_bytes(fmt);
    for (i = 0; i < nc; ++i, o += size) {
        if (fmt == HF_FORMAT_F32) {
            HF_MEMCPY(o, c + i, 4);
        } else if (size == 2) {
            const uint16_t h = (uint16_t)hf__encode1(c[i], fmt);
            HF_MEMCPY(o, &h, 2);
        } else {
            *o = (unsigned char)hf__encode1(c[i], fmt);
        }
    }
}

/* A normalized format's clamp floor (-1 signed, 0 unsigned, in *lo) and
   scale: the constants of the vector encoders below, one table for all of
   them. */
HF__INLINE float hf__norm_scale(int fmt, float *lo)
{
    switch (fmt) {
    case HF_FORMAT_SNORM16: *lo = -1.0f; return 32767.0f;
    case HF_FORMAT_UNORM16: *lo = 0.0f; return 65535.0f;
    case HF_FORMAT_SNORM8: *lo = -1.0f; return 127.0f;
    default: *lo = 0.0f; return 255.0f;
    }
}

#if HF__SSE
/* A normalized format's codes from hf__encode1's clamp and scale: the
   conversion rounds to nearest even in the default rounding mode, as
   adding and taking away 1.5 * 2^23 does there (two operations fewer;
   every level's bytes are the same in that mode) */
HF__INLINE __m128i hf__encode_v4(__m128 x, int fmt)
{
    float lo, scale;
    __m128 v;
    if (fmt == HF_FORMAT_F16) {
        const __m128i u0 = _mm_castps_si128(_mm_min_ps(
            _mm_max_ps(x, _mm_set1_ps(-65504.0f)), _mm_set1_ps(65504.0f)));
        const __m128i sign =
            _mm_and_si128(_mm_srli_epi32(u0, 16), _mm_set1_epi32(0x8000));
        const __m128i u = _mm_and_si128(u0, _mm_set1_epi32(0x7fffffff));
        const __m128i sub = _mm_sub_epi32(
            _mm_castps_si128(
                _mm_add_ps(_mm_castsi128_ps(u), _mm_set1_ps(0.5f))),
            _mm_set1_epi32(0x3f000000));
        const __m128i odd =
            _mm_and_si128(_mm_srli_epi32(u, 13), _mm_set1_epi32(1));
        const __m128i nrm = _mm_srli_epi32(
            _mm_add_epi32(_mm_add_epi32(u, _mm_set1_epi32(-939520001) /* 0xc8000fff */),
                          odd),
            13);
        /* u < 0x38800000 as signed ints: u has no sign bit */
        const __m128i is_sub =
            _mm_cmplt_epi32(u, _mm_set1_epi32(0x38800000));
        return _mm_or_si128(_mm_or_si128(_mm_and_si128(is_sub, sub),
                                         _mm_andnot_si128(is_sub, nrm)),
                            sign);
    }
    scale = hf__norm_scale(fmt, &lo);
    v = _mm_min_ps(_mm_max_ps(x, _mm_set1_ps(lo)), _mm_set1_ps(1.0f));
    return _mm_and_si128(_mm_cvtps_epi32(_mm_mul_ps(v, _mm_set1_ps(scale))),
                         _mm_set1_epi32(hf_format_bytes(fmt) == 2 ? 0xffff
                                                                  : 0xff));
}

/* Floats x, y (and z) of lane i < n at o + i * step: the pairs straight
   from unpacked registers, z from its lane, so nothing goes through a
   stack copy. */
HF__INLINE void hf__put_f32_v4(unsigned char *o, size_t step, int n, __m128 x,
                               __m128 y, __m128 z, int nc)
{
    const __m128 lo = _mm_unpacklo_ps(x, y), hi = _mm_unpackhi_ps(x, y);
    float zz[4];
    int i;
    if (n == 4) {
        _mm_storel_pi((__m64 *)(void *)o, lo);
        _mm_storeh_pi((__m64 *)(void *)(o + step), lo);
        _mm_storel_pi((__m64 *)(void *)(o + 2 * step), hi);
        _mm_storeh_pi((__m64 *)(void *)(o + 3 * step), hi);
        if (nc == 3) {
            zz[0] = _mm_cvtss_f32(z);
            zz[1] = _mm_cvtss_f32(_mm_shuffle_ps(z, z, 1));
            zz[2] = _mm_cvtss_f32(_mm_movehl_ps(z, z));
            zz[3] = _mm_cvtss_f32(_mm_shuffle_ps(z, z, 3));
            HF_MEMCPY(o + 8, zz, 4);
            HF_MEMCPY(o + step + 8, zz + 1, 4);
            HF_MEMCPY(o + 2 * step + 8, zz + 2, 4);
            HF_MEMCPY(o + 3 * step + 8, zz + 3, 4);
        }
        return;
    }
    _mm_storeu_ps(zz, z);
    for (i = 0; i < n; ++i, o += step) {
        if (i & 1)
            _mm_storeh_pi((__m64 *)(void *)o, i < 2 ? lo : hi);
        else
            _mm_storel_pi((__m64 *)(void *)o, i < 2 ? lo : hi);
        if (nc == 3) HF_MEMCPY(o + 8, zz + i, 4);
    }
}

/* Components c[0, nc) of four vertices encoded and packed into the bytes
   of each vertex: lane i of *w0 holds its first 4 bytes, of *w1 the rest
   (x86 is little-endian, so byte order is component order). */
HF__INLINE void hf__pack_v4(const __m128 *c, int nc, int fmt, __m128i *w0,
                            __m128i *w1)
{
    const __m128i e0 = hf__encode_v4(c[0], fmt), e1 = hf__encode_v4(c[1], fmt);
    const __m128i e2 = nc > 2 ? hf__encode_v4(c[2], fmt) : _mm_setzero_si128();
    const __m128i e3 = nc > 3 ? hf__encode_v4(c[3], fmt) : _mm_setzero_si128();
    if (hf_format_bytes(fmt) == 2) {
        *w0 = _mm_or_si128(e0, _mm_slli_epi32(e1, 16));
        *w1 = _mm_or_si128(e2, _mm_slli_epi32(e3, 16));
    } else {
        *w0 = _mm_or_si128(_mm_or_si128(e0, _mm_slli_epi32(e1, 8)),
                           _mm_or_si128(_mm_slli_epi32(e2, 16),
                                        _mm_slli_epi32(e3, 24)));
        *w1 = _mm_setzero_si128();
    }
}

/* Lane i of v, taken in registers (a load from a just-stored copy would
   wait on the store). */
HF__INLINE uint32_t hf__lane_v4(__m128i v, int i)
{
    switch (i) {
    case 0: return (uint32_t)_mm_cvtsi128_si32(v);
    case 1: return (uint32_t)_mm_cvtsi128_si32(_mm_shuffle_epi32(v, 1));
    case 2: return (uint32_t)_mm_cvtsi128_si32(_mm_shuffle_epi32(v, 2));
    default: return (uint32_t)_mm_cvtsi128_si32(_mm_shuffle_epi32(v, 3));
    }
}

/* One vertex's packed bytes (see hf__pack_v4) at o. */
HF__INLINE void hf__put_packed_v4(unsigned char *o, uint32_t w0, uint32_t w1,
                                  int nc, int size)
{
    if (size == 2) {
        HF_MEMCPY(o, &w0, 4);
        if (nc == 3) {
            const uint16_t z = (uint16_t)w1;
            HF_MEMCPY(o + 4, &z, 2);
        } else if (nc == 4) {
            HF_MEMCPY(o + 4, &w1, 4);
        }
    } else if (nc == 4) {
        HF_MEMCPY(o, &w0, 4);
    } else {
        const uint16_t xy = (uint16_t)w0;
        HF_MEMCPY(o, &xy, 2);
        if (nc == 3) o[2] = (unsigned char)(w0 >> 16);
    }
}

/* Both vertices of points i < n of a group of four: lane i of L at
   o + 2 i st, of R at o + (2 i + 1) st. R may be L (tangents, texcoords,
   colours): then it is encoded once. */
HF__INLINE void hf__emit_pair_fmt_v4(unsigned char *o, size_t st, int n,
                                     const __m128 *L, const __m128 *R, int nc,
                                     int fmt)
{
    int i, side;
    if (fmt == HF_FORMAT_F32) {
        HF__UNROLL for (side = 0; side < 2; ++side) {
            const __m128 *c = side ? R : L;
            unsigned char *b = o + (size_t)side * st;
            if (nc < 4) {
                hf__put_f32_v4(b, 2 * st, n, c[0], c[1], nc > 2 ? c[2] : c[0],
                               nc);
            } else {
                __m128 v0 = c[0], v1 = c[1], v2 = c[2], v3 = c[3];
                _MM_TRANSPOSE4_PS(v0, v1, v2, v3);
                _mm_storeu_ps((float *)(void *)b, v0);
                if (n > 1) _mm_storeu_ps((float *)(void *)(b + 2 * st), v1);
                if (n > 2) _mm_storeu_ps((float *)(void *)(b + 4 * st), v2);
                if (n > 3) _mm_storeu_ps((float *)(void *)(b + 6 * st), v3);
            }
        }
    } else {
        const int size = hf_format_bytes(fmt);
        __m128i l0, l1, r0, r1;
        hf__pack_v4(L, nc, fmt, &l0, &l1);
        if (R != L) {
            hf__pack_v4(R, nc, fmt, &r0, &r1);
        } else {
            r0 = l0;
            r1 = l1;
        }
        if (n == 4) { /* whole groups: the lanes constants */
            HF__UNROLL for (i = 0; i < 4; ++i, o += 2 * st) {
                hf__put_packed_v4(o, hf__lane_v4(l0, i), hf__lane_v4(l1, i), nc,
                                  size);
                hf__put_packed_v4(o + st, hf__lane_v4(r0, i),
                                  hf__lane_v4(r1, i), nc, size);
            }
            return;
        }
        for (i = 0; i < n; ++i, o += 2 * st) {
            hf__put_packed_v4(o, hf__lane_v4(l0, i), hf__lane_v4(l1, i), nc,
                              size);
            hf__put_packed_v4(o + st, hf__lane_v4(r0, i), hf__lane_v4(r1, i),
                              nc, size);
        }
    }
}
/* hf__emit_pair_fmt_v4 with the format a constant in each copy, so its
   tests on the format fold away. */
HF__INLINE void hf__emit_pair_v4(unsigned char *o, size_t st, int n,
                                 const __m128 *L, const __m128 *R, int nc,
                                 int fmt)
{
    switch (fmt) {
    case HF_FORMAT_F32:
        hf__emit_pair_fmt_v4(o, st, n, L, R, nc, HF_FORMAT_F32);
        break;
    case HF_FORMAT_F16:
        hf__emit_pair_fmt_v4(o, st, n, L, R, nc, HF_FORMAT_F16);
        break;
    case HF_FORMAT_SNORM16:
        hf__emit_pair_fmt_v4(o, st, n, L, R, nc, HF_FORMAT_SNORM16);
        break;
    case HF_FORMAT_UNORM16:
        hf__emit_pair_fmt_v4(o, st, n, L, R, nc, HF_FORMAT_UNORM16);
        break;
    case HF_FORMAT_SNORM8:
        hf__emit_pair_fmt_v4(o, st, n, L, R, nc, HF_FORMAT_SNORM8);
        break;
    default: hf__emit_pair_fmt_v4(o, st, n, L, R, nc, HF_FORMAT_UNORM8); break;
    }
}
#endif


/* ---- 8.4 the writers: one strand's vertices ----------------------------- */

/* Where each stream goes, resolved once per call. */
typedef struct hf__rout {
    unsigned char *base[5];
    size_t stride[5];
    int fmt[5];
    float origin[3], inv_scale;
    int run; /* hf__float_run of the streams, once per call */
    int rest; /* 1 where a stream is left after the float run */
    /* The table writer's plan (hf__rout_layout): nw streams in address
       order, wq[m] the stream and wb[m] the bytes each copy writes (its
       element, or the next power of two where the bytes past it belong to
       streams stored after it in the same vertex); nw 0 where streams of
       one stride overlap inside a vertex. */
    int nw;
    unsigned char wq[5], wb[5];
    /* Where every stream's element sits in one run of wl = 9..16 bytes
       from the first (same stride, no gaps): the run is assembled in a
       register, byte k from element byte wm[q][k] of stream q (0x80:
       none), and stored in two 8-byte stores (the second from bytes
       wsh[0..8)). wl 0 otherwise. */
    int wl;
    unsigned char wm[5][16], wsh[16];
    /* The vertex size where the streams tile one interleaved vertex
       exactly (one stride, no gaps, no overlap), else 0: what streaming
       ribbons copy out whole (hf__ribbon_stage). */
    size_t tile;
    /* 1 for the compact vertex: position and texcoord in 16-bit
       normalized formats, tangent in an 8-bit one, abutting at 0, 6 and
       12 of one stride (15 bytes), no other stream; written by a kernel
       of its own at AVX2 (a half format takes the table writer) */
    int c16;
} hf__rout;

enum { HF__S_POS, HF__S_TAN, HF__S_TEX, HF__S_COL, HF__S_C3D };
static const int hf__stream_nc[5] = {3, 3, 3, 4, 2};

/* Per call: half widths, t and the alpha fade, padded to groups of four. */
typedef struct hf__rconst {
    float hw[HF_MAX_POINTS + 4], tt[HF_MAX_POINTS + 4];
    float fade[HF_MAX_POINTS + 4];
    float wcap; /* the cap of the strand multiplier (hf__half_widths) */
} hf__rconst;

HF__PRIVATE void hf__rconst_init(hf__rconst *K, const hf_ribbon_params *p)
{
    const int P = p->points_per_strand;
    /* zeros past the last point, as far as a group of sixteen reads */
    const size_t pad = (size_t)(HF_MAX_POINTS + 4 - P < 16
                                    ? HF_MAX_POINTS + 4 - P
                                    : 16) * sizeof(float);
    int j;
    K->wcap = hf__half_widths(p, K->hw, K->tt);
    for (j = 0; j < P; ++j)
        K->fade[j] = (1.0f - K->tt[j]) * p->alpha_root + K->tt[j] * p->alpha_tip;
    HF_MEMSET(K->hw + P, 0, pad);
    HF_MEMSET(K->tt + P, 0, pad);
    HF_MEMSET(K->fade + P, 0, pad);
}

/* Per strand: the optional inputs, already made finite. */
typedef struct hf__rstrand {
    float uv[2], rgba[4], c3x, wscale;
} hf__rstrand;

/* Vertices v (a) and v + 1 (b) of stream q, one point at a time. */
HF__PRIVATE void hf__emit2(const hf__rout *ro, int q, size_t v,
                           const float *a, const float *b)
{
    const size_t st = ro->stride[q];
    hf__emit1(ro->base[q] + v * st, a, hf__stream_nc[q], ro->fmt[q]);
    hf__emit1(ro->base[q] + (v + 1u) * st, b, hf__stream_nc[q], ro->fmt[q]);
}

/* Every stream's vertices of one strand from its frame, a point at a
   time: the reference for the SSE writer below. Vertex 2 j + k of the
   strand (k = 0: -side) starts at v0. */
HF__PRIVATE int hf__ribbon_write_v1(const hf__rframe *fr, int P,
                                    const hf__rconst *K, const hf__rstrand *str,
                                    const hf__rout *ro, size_t v0)
{
    int j, c, q;
    for (j = 0; j < P; ++j) {
        const size_t v = v0 + 2u * (size_t)j;
        float a[4], b[4];
        if (ro->base[HF__S_POS]) {
            const float w = K->hw[j] * str->wscale;
            HF__UNROLL for (c = 0; c < 3; ++c) {
                const float p = fr->p[c][4 + j], sw = fr->s[c][4 + j] * w;
                a[c] = ((p - sw) - ro->origin[c]) * ro->inv_scale;
                b[c] = ((p + sw) - ro->origin[c]) * ro->inv_scale;
            }
            hf__emit2(ro, HF__S_POS, v, a, b);
        }
        for (q = HF__S_TAN; q <= HF__S_C3D; ++q) {
            if (!ro->base[q]) continue;
            switch (q) { /* the same on both sides */
            case HF__S_TAN:
                HF__UNROLL for (c = 0; c < 3; ++c) a[c] = fr->t[c][4 + j];
                break;
            case HF__S_TEX:
                a[0] = str->uv[0];
                a[1] = str->uv[1];
                a[2] = K->tt[j];
                break;
            case HF__S_COL:
                HF__UNROLL for (c = 0; c < 3; ++c) a[c] = str->rgba[c];
                a[3] = str->rgba[3] * K->fade[j];
                break;
            default: /* HF__S_C3D */
                a[0] = str->c3x;
                a[1] = K->tt[j];
                break;
            }
            hf__emit2(ro, q, v, a, a);
        }
    }
    return 1;
}

/* 2 when position and tangent are floats side by side in one vertex, 3
   when the texcoord follows them too (the usual 36-byte layout); else 0. */
HF__PRIVATE int hf__float_run(const hf__rout *ro)
{
    const unsigned char *p = ro->base[HF__S_POS];
    const size_t st = ro->stride[HF__S_POS];
    if (!p || ro->base[HF__S_TAN] != p + 12 || ro->stride[HF__S_TAN] != st ||
        ro->fmt[HF__S_POS] != HF_FORMAT_F32 ||
        ro->fmt[HF__S_TAN] != HF_FORMAT_F32)
        return 0;
    return ro->base[HF__S_TEX] == p + 24 && ro->stride[HF__S_TEX] == st &&
                   ro->fmt[HF__S_TEX] == HF_FORMAT_F32
               ? 3
               : 2;
}

/* The float run, the table writer's plan and the stage's block of ro's
   streams (see hf__rout), once per call. Addresses are compared as
   integers: the streams may be in different buffers. */
HF__PRIVATE void hf__rout_layout(hf__rout *ro)
{
    uintptr_t at[5];
    size_t z[5], end = 0, st;
    int q, m, r, n = 0;
    ro->run = hf__float_run(ro);
    ro->rest = (ro->base[HF__S_TEX] && ro->run == 2) ||
               ro->base[HF__S_COL] || ro->base[HF__S_C3D];
    ro->nw = ro->wl = 0;
    ro->tile = 0;
    ro->c16 = 0;
    for (q = 0; q < 5; ++q) {
        z[q] = (size_t)hf_format_bytes(ro->fmt[q]) * (size_t)hf__stream_nc[q];
        at[q] = (uintptr_t)ro->base[q];
        if (!ro->base[q]) continue;
        for (m = n++; m > 0 && at[ro->wq[m - 1]] > at[q]; --m)
            ro->wq[m] = ro->wq[m - 1];
        ro->wq[m] = (unsigned char)q;
    }
    for (m = 0; m < n; ++m) {
        const int a = ro->wq[m];
        /* 3, 6 and 12 bytes take two copies unless widened to 4, 8, 16 */
        const size_t w = z[a] == 3 ? 4 : z[a] == 6 ? 8 : z[a] == 12 ? 16 : z[a];
        size_t b, covered = z[a];
        st = ro->stride[a];
        for (r = m + 1; r < n; ++r) {
            const int c = ro->wq[r];
            const size_t d = (size_t)(at[c] - at[a]);
            if (ro->stride[c] != st || d >= st) continue;
            if (d < z[a] || d + z[c] > st) return; /* overlap in one vertex */
        }
        /* the widened copy's extra bytes, each inside a later element of
           the same vertex (rewritten after it) */
        for (b = z[a]; b < w; ++b)
            for (r = m + 1; r < n; ++r) {
                const int c = ro->wq[r];
                const size_t d = (size_t)(at[c] - at[a]);
                if (ro->stride[c] == st && d <= b && b < d + z[c]) {
                    ++covered;
                    break;
                }
            }
        ro->wb[m] = (unsigned char)(covered == w ? w : z[a]);
    }
    ro->nw = n;
    /* every stream of one stride, elements abutting from the first: the
       stage's block where they fill the stride, the register run where
       they take 9 to 16 bytes */
    if (n == 0) return;
    st = ro->stride[ro->wq[0]];
    for (m = 0; m < n; ++m) {
        const int a = ro->wq[m];
        if (ro->stride[a] != st || at[a] - at[ro->wq[0]] != end) return;
        end += z[a];
    }
    if (end == st) ro->tile = st;
    if (end < 9 || end > 16 || end > st) return;
    HF_MEMSET(ro->wm, 0x80, sizeof ro->wm);
    for (q = 0; q < 5; ++q) { /* each element inside the run's end bytes */
        const size_t d = (size_t)(at[q] - at[ro->wq[0]]);
        size_t k;
        if (!ro->base[q]) continue;
        for (k = 0; k < z[q]; ++k) ro->wm[q][d + k] = (unsigned char)k;
    }
    for (m = 0; m < 16; ++m)
        ro->wsh[m] =
            (unsigned char)((size_t)m + end - 8 < 16 ? (size_t)m + end - 8 : 0x80);
    ro->wl = (int)end;
    ro->c16 = end == 15 && n == 3 && z[HF__S_POS] == 6 &&
              z[HF__S_TEX] == 6 && z[HF__S_TAN] == 3 &&
              ro->wq[0] == HF__S_POS && at[HF__S_TEX] - at[HF__S_POS] == 6 &&
              ro->fmt[HF__S_POS] != HF_FORMAT_F16 &&
              ro->fmt[HF__S_TEX] != HF_FORMAT_F16;
}

/* One stream's elements of points i < n at o + 2 i st (side 0, from
   table slot L + i ts) and a stride later (side 1, from R + i ts; R == L
   for the streams both sides share, read once): each in `wb` bytes
   (hf__rout's wb) as a head of n0 bytes and a tail of n1, constants in
   each copy hf__elems_put inlines. */
HF__INLINE void hf__elems_run(unsigned char *o, size_t st, int n,
                              const unsigned char *L, const unsigned char *R,
                              size_t ts, size_t n0, size_t n1)
{
    int i;
    for (i = 0; i < n; ++i, o += 2 * st, L += ts, R += ts) {
        uint64_t x0 = 0, y0 = 0, x1, y1;
        HF_MEMCPY(&x0, L, n0);
        HF_MEMCPY(&y0, L + n0, n1);
        x1 = x0;
        y1 = y0;
        if (R != L) {
            HF_MEMCPY(&x1, R, n0);
            HF_MEMCPY(&y1, R + n0, n1);
        }
        HF_MEMCPY(o, &x0, n0);
        HF_MEMCPY(o + n0, &y0, n1);
        HF_MEMCPY(o + st, &x1, n0);
        HF_MEMCPY(o + st + n0, &y1, n1);
    }
}
HF__INLINE void hf__elems_put(unsigned char *o, size_t st, int n,
                              const unsigned char *L, const unsigned char *R,
                              size_t ts, int wb)
{
    switch (wb) {
    case 2: hf__elems_run(o, st, n, L, R, ts, 2, 0); break;
    case 3: hf__elems_run(o, st, n, L, R, ts, 2, 1); break;
    case 4: hf__elems_run(o, st, n, L, R, ts, 4, 0); break;
    case 6: hf__elems_run(o, st, n, L, R, ts, 4, 2); break;
    case 8: hf__elems_run(o, st, n, L, R, ts, 8, 0); break;
    case 12: hf__elems_run(o, st, n, L, R, ts, 8, 4); break;
    default: hf__elems_run(o, st, n, L, R, ts, 8, 8); break;
    }
}

#if HF__SSE
/* A float run (see hf__float_run) for points i < n of a group: left
   position L, right position R, tangent T, and with uv the texcoord
   (uv, t). Each vertex takes two or three stores instead of six. */
HF__INLINE void hf__put_run_v4(unsigned char *o, size_t st, int n,
                               const __m128 *L, const __m128 *R,
                               const __m128 *T, const float *uv, const float *t)
{
    __m128 l0 = L[0], l1 = L[1], l2 = L[2], l3 = T[0];
    __m128 r0 = R[0], r1 = R[1], r2 = R[2], r3 = T[0];
    __m128 q[4];
    int i;
    _MM_TRANSPOSE4_PS(l0, l1, l2, l3); /* x y z tx of each left vertex */
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    if (uv) { /* ty tz u v */
        __m128 u = _mm_set1_ps(uv[0]), v = _mm_set1_ps(uv[1]);
        q[0] = T[1];
        q[1] = T[2];
        _MM_TRANSPOSE4_PS(q[0], q[1], u, v);
        q[2] = u;
        q[3] = v;
    } else { /* ty tz pairs */
        q[0] = _mm_unpacklo_ps(T[1], T[2]);
        q[1] = _mm_movehl_ps(q[0], q[0]);
        q[2] = _mm_unpackhi_ps(T[1], T[2]);
        q[3] = _mm_movehl_ps(q[2], q[2]);
    }
    for (i = 0; i < n; ++i, o += 2 * st) {
        const __m128 lv = i == 0 ? l0 : i == 1 ? l1 : i == 2 ? l2 : l3;
        const __m128 rv = i == 0 ? r0 : i == 1 ? r1 : i == 2 ? r2 : r3;
        _mm_storeu_ps((float *)(void *)o, lv);
        _mm_storeu_ps((float *)(void *)(o + st), rv);
        if (uv) {
            _mm_storeu_ps((float *)(void *)(o + 16), q[i]);
            _mm_storeu_ps((float *)(void *)(o + st + 16), q[i]);
            HF_MEMCPY(o + 32, t + i, 4);
            HF_MEMCPY(o + st + 32, t + i, 4);
        } else {
            _mm_storel_pi((__m64 *)(void *)(o + 16), q[i]);
            _mm_storel_pi((__m64 *)(void *)(o + st + 16), q[i]);
        }
    }
}

/* The two vertex positions of four points (rows from o): L = p - s w,
   R = p + s w, relative to the origin and scale, as in the reference. */
HF__INLINE void hf__ribbon_sides_v4(const hf__rframe *fr, int o, __m128 w,
                                    const hf__rout *ro, __m128 is, __m128 *L,
                                    __m128 *R)
{
    int c;
    HF__UNROLL for (c = 0; c < 3; ++c) {
        const __m128 p = _mm_loadu_ps(fr->p[c] + o);
        const __m128 sw = _mm_mul_ps(_mm_loadu_ps(fr->s[c] + o), w);
        const __m128 og = _mm_set1_ps(ro->origin[c]);
        L[c] = _mm_mul_ps(_mm_sub_ps(_mm_sub_ps(p, sw), og), is);
        R[c] = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(p, sw), og), is);
    }
}

/* Stream q's values (tangent, texcoord, colour or 3D colour: the same on
   both sides of the ribbon) for the four points of group k. */
HF__INLINE void hf__stream_values_v4(int q, const hf__rframe *fr,
                                     const hf__rconst *K,
                                     const hf__rstrand *str, int k, __m128 *v)
{
    const __m128 tt = _mm_loadu_ps(K->tt + 4 * k);
    int c;
    switch (q) {
    case HF__S_TAN:
        HF__UNROLL for (c = 0; c < 3; ++c)
            v[c] = _mm_loadu_ps(fr->t[c] + 4 + 4 * k);
        break;
    case HF__S_TEX:
        v[0] = _mm_set1_ps(str->uv[0]);
        v[1] = _mm_set1_ps(str->uv[1]);
        v[2] = tt;
        break;
    case HF__S_COL:
        HF__UNROLL for (c = 0; c < 3; ++c) v[c] = _mm_set1_ps(str->rgba[c]);
        v[3] = _mm_mul_ps(_mm_set1_ps(str->rgba[3]),
                          _mm_loadu_ps(K->fade + 4 * k));
        break;
    default: /* HF__S_C3D */
        v[0] = _mm_set1_ps(str->c3x);
        v[1] = tt;
        break;
    }
}

/* All of stream q (nc = hf__stream_nc[q]) for one strand: both vertices
   of each point get the same values. */
HF__INLINE void hf__stream_v4(int q, int nc, const hf__rframe *fr, int P,
                              const hf__rconst *K, const hf__rstrand *str,
                              const hf__rout *ro, size_t v0)
{
    const size_t st = ro->stride[q];
    unsigned char *b = ro->base[q] + v0 * st;
    __m128 v[4];
    int k;
    for (k = 0; 4 * k < P; ++k, b += 8 * st) {
        hf__stream_values_v4(q, fr, K, str, k, v);
        hf__emit_pair_v4(b, st, P - 4 * k < 4 ? P - 4 * k : 4, v, v, nc,
                         ro->fmt[q]);
    }
}

/* hf__ribbon_write_v1 four points at a time: the same values in the same
   operations, so the same bytes. */
HF__PRIVATE int hf__ribbon_write_v4(const hf__rframe *fr, int P,
                                    const hf__rconst *K, const hf__rstrand *str,
                                    const hf__rout *ro, size_t v0)
{
    /* stream by stream, as the scalar loop per point writes: the first
       stream touches every cache line of the strand with few stores, so
       the misses that bring the lines in overlap */
    const int G = (P + 3) >> 2, run = ro->run;
    const __m128 ws = _mm_set1_ps(str->wscale), is = _mm_set1_ps(ro->inv_scale);
    __m128 L[4], R[4];
    size_t st;
    unsigned char *b;
    int k, c;
    if (run) {
        st = ro->stride[HF__S_POS];
        b = ro->base[HF__S_POS] + v0 * st;
        for (k = 0; k < G; ++k, b += 8 * st) {
            const int o = 4 + 4 * k, n = P - 4 * k < 4 ? P - 4 * k : 4;
            const __m128 w = _mm_mul_ps(_mm_loadu_ps(K->hw + 4 * k), ws);
            __m128 T[3];
            hf__ribbon_sides_v4(fr, o, w, ro, is, L, R);
            HF__UNROLL for (c = 0; c < 3; ++c)
                T[c] = _mm_loadu_ps(fr->t[c] + o);
            hf__put_run_v4(b, st, n, L, R, T, run == 3 ? str->uv : NULL,
                           K->tt + 4 * k);
        }
    } else if (ro->base[HF__S_POS]) {
        st = ro->stride[HF__S_POS];
        b = ro->base[HF__S_POS] + v0 * st;
        for (k = 0; k < G; ++k, b += 8 * st) {
            const int o = 4 + 4 * k, n = P - 4 * k < 4 ? P - 4 * k : 4;
            const __m128 w = _mm_mul_ps(_mm_loadu_ps(K->hw + 4 * k), ws);
            hf__ribbon_sides_v4(fr, o, w, ro, is, L, R);
            hf__emit_pair_v4(b, st, n, L, R, 3, ro->fmt[HF__S_POS]);
        }
    }
    /* the other streams, unless written with the position run; a call
       each, so the component count is a constant in every inlined copy */
    if (ro->base[HF__S_TAN] && !run)
        hf__stream_v4(HF__S_TAN, 3, fr, P, K, str, ro, v0);
    if (ro->base[HF__S_TEX] && run < 3)
        hf__stream_v4(HF__S_TEX, 3, fr, P, K, str, ro, v0);
    if (ro->base[HF__S_COL]) hf__stream_v4(HF__S_COL, 4, fr, P, K, str, ro, v0);
    if (ro->base[HF__S_C3D]) hf__stream_v4(HF__S_C3D, 2, fr, P, K, str, ro, v0);
    return 1;
}
#endif

#if HF__AVX2
/* A group's x y z tx of points i and i + 4 (the two halves) in a[i],
   which joined to ty tz u v (B[i]) make a float run's vertex */
HF__TARGET_AVX2 HF__INLINE void hf__side_rows_v8(__m256 x, __m256 y, __m256 z,
                                                 __m256 tx, __m256 *a)
{
    const __m256 xy0 = _mm256_unpacklo_ps(x, y), xy1 = _mm256_unpackhi_ps(x, y),
                 zt0 = _mm256_unpacklo_ps(z, tx), zt1 = _mm256_unpackhi_ps(z, tx);
    a[0] = _mm256_shuffle_ps(xy0, zt0, _MM_SHUFFLE(1, 0, 1, 0));
    a[1] = _mm256_shuffle_ps(xy0, zt0, _MM_SHUFFLE(3, 2, 3, 2));
    a[2] = _mm256_shuffle_ps(xy1, zt1, _MM_SHUFFLE(1, 0, 1, 0));
    a[3] = _mm256_shuffle_ps(xy1, zt1, _MM_SHUFFLE(3, 2, 3, 2));
}

/* A whole group of the 36-byte vertex (run 3), both sides, in address
   order: point i's left vertex at o + 2 i st, its right one st after,
   each its first eight floats in one store and t after them. Each point's
   t is read once for both (read per side, gcc loaded it again after
   every store), and the stores go through the output in order (a side
   at a time measured 5 % slower). */
HF__TARGET_AVX2 HF__INLINE void hf__put_pair_v8(unsigned char *o, size_t st,
                                                __m256 xl, __m256 yl, __m256 zl,
                                                __m256 xr, __m256 yr, __m256 zr,
                                                __m256 tx, const __m256 *B,
                                                const float *tt)
{
    __m256 l[4], r[4];
    hf__side_rows_v8(xl, yl, zl, tx, l);
    hf__side_rows_v8(xr, yr, zr, tx, r);
    /* each vertex built just before its store (built all first, gcc
       spilled some) */
#define HF__PUT_P(i, h)                                                        \
    do {                                                                       \
        unsigned char *v = o + 2u * (i) * st;                                  \
        const float t = tt[i];                                                 \
        _mm256_storeu_ps((float *)(void *)v,                                   \
                         _mm256_permute2f128_ps(l[(i) & 3], B[(i) & 3], h));   \
        HF_MEMCPY(v + 32, &t, 4);                                              \
        _mm256_storeu_ps((float *)(void *)(v + st),                            \
                         _mm256_permute2f128_ps(r[(i) & 3], B[(i) & 3], h));   \
        HF_MEMCPY(v + st + 32, &t, 4);                                         \
    } while (0)
    HF__PUT_P(0, 0x20);
    HF__PUT_P(1, 0x20);
    HF__PUT_P(2, 0x20);
    HF__PUT_P(3, 0x20);
    HF__PUT_P(4, 0x31);
    HF__PUT_P(5, 0x31);
    HF__PUT_P(6, 0x31);
    HF__PUT_P(7, 0x31);
#undef HF__PUT_P
}

/* One side's vertices of a group (vertex i at o + i * st2): whole groups
   of the 24-byte run (run 2: position and tangent, x y z tx in one store,
   ty tz in another), and the last, partial group of either run. */
HF__TARGET_AVX2 HF__INLINE void
hf__put_side_v8(unsigned char *o, size_t st2, int n, int run, __m256 x,
                __m256 y, __m256 z, __m256 tx, const __m256 *B, const float *tt)
{
    __m256 a[4];
    hf__side_rows_v8(x, y, z, tx, a);
    if (n == 8) {
        int k;
        HF__UNROLL for (k = 0; k < 4; ++k) {
            unsigned char *lo = o + (size_t)k * st2, *hi = lo + 4 * st2;
            _mm_storeu_ps((float *)(void *)lo, _mm256_castps256_ps128(a[k]));
            _mm_storel_pi((__m64 *)(void *)(lo + 16),
                          _mm256_castps256_ps128(B[k]));
            _mm_storeu_ps((float *)(void *)hi, _mm256_extractf128_ps(a[k], 1));
            _mm_storel_pi((__m64 *)(void *)(hi + 16),
                          _mm256_extractf128_ps(B[k], 1));
        }
    } else {
        float f[8][8];
        int i;
        for (i = 0; i < 4; ++i) {
            _mm256_storeu_ps(f[i], _mm256_permute2f128_ps(a[i], B[i], 0x20));
            _mm256_storeu_ps(f[i + 4],
                             _mm256_permute2f128_ps(a[i], B[i], 0x31));
        }
        for (i = 0; i < n; ++i, o += st2) {
            if (run == 2) {
                HF_MEMCPY(o, f[i], 24);
                continue;
            }
            HF_MEMCPY(o, f[i], 32);
            HF_MEMCPY(o + 32, tt + i, 4);
        }
    }
}

/* A group's left and right positions from frame row offset o, w the
   half widths: L = p - s w, R = p + s w, relative to the origin and
   scale (ov as hf__rout_vec_v8) */
HF__TARGET_AVX2 HF__INLINE void hf__sides_v8(const hf__rframe *fr, int o,
                                             __m256 w, const __m256 *ov,
                                             __m256 *L, __m256 *R)
{
    int c;
    HF__UNROLL for (c = 0; c < 3; ++c) {
        const __m256 p = _mm256_loadu_ps(fr->p[c] + o);
        const __m256 sw = _mm256_mul_ps(_mm256_loadu_ps(fr->s[c] + o), w);
        L[c] = _mm256_mul_ps(_mm256_sub_ps(_mm256_sub_ps(p, sw), ov[1 + c]),
                             ov[0]);
        R[c] = _mm256_mul_ps(_mm256_sub_ps(_mm256_add_ps(p, sw), ov[1 + c]),
                             ov[0]);
    }
}

/* One group of n points (8 but for the last), the run's vertices from
   point 8 k on at b: the writer's loop body, inlined with n and run as
   constants where it can (the common groups then take no branch) */
HF__TARGET_AVX2 HF__INLINE void
hf__ribbon_group_v8(const hf__rframe *fr, const hf__rconst *K, int k, int n,
                    int run, unsigned char *b, size_t st, __m256 ws,
                    const __m256 *ov, __m256 uv)
{
    const int o = 4 + 8 * k;
    const __m256 w = _mm256_mul_ps(_mm256_loadu_ps(K->hw + 8 * k), ws);
    const __m256 ty = _mm256_loadu_ps(fr->t[1] + o),
                 tz = _mm256_loadu_ps(fr->t[2] + o);
    const __m256 lo = _mm256_unpacklo_ps(ty, tz),
                 hi = _mm256_unpackhi_ps(ty, tz);
    const __m256 tx = _mm256_loadu_ps(fr->t[0] + o);
    __m256 B[4], L[3], R[3];
    /* ty tz u v of points i and i + 4: the same on both sides */
    B[0] = _mm256_shuffle_ps(lo, uv, _MM_SHUFFLE(1, 0, 1, 0));
    B[1] = _mm256_shuffle_ps(lo, uv, _MM_SHUFFLE(1, 0, 3, 2));
    B[2] = _mm256_shuffle_ps(hi, uv, _MM_SHUFFLE(1, 0, 1, 0));
    B[3] = _mm256_shuffle_ps(hi, uv, _MM_SHUFFLE(1, 0, 3, 2));
    hf__sides_v8(fr, o, w, ov, L, R);
    if (n == 8 && run == 3) {
        hf__put_pair_v8(b, st, L[0], L[1], L[2], R[0], R[1], R[2], tx, B,
                        K->tt + 8 * k);
        return;
    }
    hf__put_side_v8(b, 2 * st, n, run, L[0], L[1], L[2], tx, B, K->tt + 8 * k);
    hf__put_side_v8(b + st, 2 * st, n, run, R[0], R[1], R[2], tx, B,
                    K->tt + 8 * k);
}

/* 1 / scale and the origin in every lane, once per call: ov[0..4) */
HF__TARGET_AVX2 HF__INLINE void hf__rout_vec_v8(const hf__rout *ro, __m256 *ov)
{
    int c;
    ov[0] = _mm256_set1_ps(ro->inv_scale);
    HF__UNROLL for (c = 0; c < 3; ++c)
        ov[1 + c] = _mm256_set1_ps(ro->origin[c]);
}

/* hf__ribbon_write_v4 eight points at a time for the float runs
   (position, tangent and texcoord, the 36-byte vertex: hf__float_run 3;
   position and tangent: 2, the other streams as the SSE writer writes
   them); the dispatch gives other layouts to the table writer below or
   the SSE one (calling the SSE writer from here would run SSE code with
   the upper halves of the registers dirty, at twice its time or more). */
HF__TARGET_AVX2 HF__INLINE void
hf__ribbon_write_run_v8_in(const hf__rframe *fr, int P, const hf__rconst *K,
                       const hf__rstrand *str, const hf__rout *ro, size_t v0,
                       const __m256 *ov)
{
    const size_t st = ro->stride[HF__S_POS];
    const __m256 ws = _mm256_set1_ps(str->wscale);
    /* u v u v ..: from two scalar loads (gcc made the set one 32-byte
       load of *str, which waits for the scalar stores that just filled it
       to drain: a failed store forward, 14 % of this writer's time) */
    const __m256 uv = _mm256_unpacklo_ps(_mm256_set1_ps(str->uv[0]),
                                         _mm256_set1_ps(str->uv[1]));
    unsigned char *b = ro->base[HF__S_POS] + v0 * st;
    int k;
    if (ro->run == 3 && st == 36) {
        /* the packed vertex: every store's offset a constant */
        for (k = 0; 8 * k + 8 <= P; ++k, b += 16 * 36)
            hf__ribbon_group_v8(fr, K, k, 8, 3, b, 36, ws, ov, uv);
    } else if (ro->run == 3) {
        for (k = 0; 8 * k + 8 <= P; ++k, b += 16 * st)
            hf__ribbon_group_v8(fr, K, k, 8, 3, b, st, ws, ov, uv);
    } else {
        for (k = 0; 8 * k + 8 <= P; ++k, b += 16 * st)
            hf__ribbon_group_v8(fr, K, k, 8, 2, b, st, ws, ov, uv);
    }
    if (8 * k < P)
        hf__ribbon_group_v8(fr, K, k, P - 8 * k, ro->run, b, st, ws, ov, uv);
    if (!ro->rest) return; /* one test a strand for the three below */
    if (ro->base[HF__S_TEX] && ro->run == 2)
        hf__stream_v4(HF__S_TEX, 3, fr, P, K, str, ro, v0);
    if (ro->base[HF__S_COL]) hf__stream_v4(HF__S_COL, 4, fr, P, K, str, ro, v0);
    if (ro->base[HF__S_C3D]) hf__stream_v4(HF__S_C3D, 2, fr, P, K, str, ro, v0);
}

/* the writer above as a call, for the dispatch of one strand */
HF__TARGET_AVX2 HF__PRIVATE void
hf__ribbon_write_run_v8(const hf__rframe *fr, int P, const hf__rconst *K,
                        const hf__rstrand *str, const hf__rout *ro, size_t v0)
{
    __m256 ov[4];
    hf__rout_vec_v8(ro, ov);
    hf__ribbon_write_run_v8_in(fr, P, K, str, ro, v0, ov);
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
}

/* hf__encode_v4 at eight lanes: the same operations. */
HF__TARGET_AVX2 HF__INLINE __m256i hf__encode_v8(__m256 x, int fmt)
{
    float lo, scale;
    __m256 v;
    if (fmt == HF_FORMAT_F16) {
        const __m256i u0 = _mm256_castps_si256(_mm256_min_ps(
            _mm256_max_ps(x, _mm256_set1_ps(-65504.0f)),
            _mm256_set1_ps(65504.0f)));
        const __m256i sign = _mm256_and_si256(_mm256_srli_epi32(u0, 16),
                                              _mm256_set1_epi32(0x8000));
        const __m256i u = _mm256_and_si256(u0, _mm256_set1_epi32(0x7fffffff));
        const __m256i sub = _mm256_sub_epi32(
            _mm256_castps_si256(_mm256_add_ps(_mm256_castsi256_ps(u),
                                              _mm256_set1_ps(0.5f))),
            _mm256_set1_epi32(0x3f000000));
        const __m256i odd =
            _mm256_and_si256(_mm256_srli_epi32(u, 13), _mm256_set1_epi32(1));
        const __m256i nrm = _mm256_srli_epi32(
            _mm256_add_epi32(
                _mm256_add_epi32(u, _mm256_set1_epi32(-939520001)), odd),
            13);
        const __m256i is_sub =
            _mm256_cmpgt_epi32(_mm256_set1_epi32(0x38800000), u);
        return _mm256_or_si256(_mm256_blendv_epi8(nrm, sub, is_sub), sign);
    }
    scale = hf__norm_scale(fmt, &lo);
    v = _mm256_min_ps(_mm256_max_ps(x, _mm256_set1_ps(lo)), _mm256_set1_ps(1.0f));
    return _mm256_and_si256(
        _mm256_cvtps_epi32(_mm256_mul_ps(v, _mm256_set1_ps(scale))),
        _mm256_set1_epi32(hf_format_bytes(fmt) == 2 ? 0xffff : 0xff));
}

/* One stream's components c[0, nc) of eight points into table t, a slot
   of 16 (float), 8 (2-byte formats) or 4 bytes (1-byte) a point holding
   the point's element as the vertex stores it, then zeros or spare
   bytes. */
HF__TARGET_AVX2 HF__INLINE void
hf__table_fmt_v8(unsigned char *t, const __m256 *c, int nc, int fmt)
{
    const int size = hf_format_bytes(fmt);
    __m256i e[4], w0, w1;
    int i;
    if (fmt == HF_FORMAT_F32) {
        const __m256 z = _mm256_setzero_ps();
        const __m256 c2 = nc > 2 ? c[2] : z, c3 = nc > 3 ? c[3] : z;
        const __m256 a = _mm256_unpacklo_ps(c[0], c[1]),
                     b = _mm256_unpackhi_ps(c[0], c[1]),
                     g = _mm256_unpacklo_ps(c2, c3),
                     h = _mm256_unpackhi_ps(c2, c3);
        /* points 0 and 4, 1 and 5, 2 and 6, 3 and 7 */
        const __m256 r0 = _mm256_shuffle_ps(a, g, _MM_SHUFFLE(1, 0, 1, 0)),
                     r1 = _mm256_shuffle_ps(a, g, _MM_SHUFFLE(3, 2, 3, 2)),
                     r2 = _mm256_shuffle_ps(b, h, _MM_SHUFFLE(1, 0, 1, 0)),
                     r3 = _mm256_shuffle_ps(b, h, _MM_SHUFFLE(3, 2, 3, 2));
        float *f = (float *)(void *)t;
        _mm256_storeu_ps(f, _mm256_permute2f128_ps(r0, r1, 0x20));
        _mm256_storeu_ps(f + 8, _mm256_permute2f128_ps(r2, r3, 0x20));
        _mm256_storeu_ps(f + 16, _mm256_permute2f128_ps(r0, r1, 0x31));
        _mm256_storeu_ps(f + 24, _mm256_permute2f128_ps(r2, r3, 0x31));
        return;
    }
    HF__UNROLL for (i = 0; i < 4; ++i) e[i] = i < nc ? hf__encode_v8(c[i], fmt)
                                                     : _mm256_setzero_si256();
    if (size == 2) {
        w0 = _mm256_or_si256(e[0], _mm256_slli_epi32(e[1], 16));
        w1 = _mm256_or_si256(e[2], _mm256_slli_epi32(e[3], 16));
        /* points 0 1 | 4 5 and 2 3 | 6 7, eight bytes each */
        e[0] = _mm256_unpacklo_epi32(w0, w1);
        e[1] = _mm256_unpackhi_epi32(w0, w1);
        _mm256_storeu_si256((__m256i *)(void *)t,
                            _mm256_permute2x128_si256(e[0], e[1], 0x20));
        _mm256_storeu_si256((__m256i *)(void *)(t + 32),
                            _mm256_permute2x128_si256(e[0], e[1], 0x31));
    } else {
        w0 = _mm256_or_si256(_mm256_or_si256(e[0], _mm256_slli_epi32(e[1], 8)),
                             _mm256_or_si256(_mm256_slli_epi32(e[2], 16),
                                             _mm256_slli_epi32(e[3], 24)));
        _mm256_storeu_si256((__m256i *)(void *)t, w0);
    }
}

/* hf__table_fmt_v8 with the format a constant in each copy. */
HF__TARGET_AVX2 HF__INLINE void hf__table_v8(unsigned char *t, const __m256 *c,
                                             int nc, int fmt)
{
    switch (fmt) {
    case HF_FORMAT_F32: hf__table_fmt_v8(t, c, nc, HF_FORMAT_F32); break;
    case HF_FORMAT_F16: hf__table_fmt_v8(t, c, nc, HF_FORMAT_F16); break;
    case HF_FORMAT_SNORM16:
        hf__table_fmt_v8(t, c, nc, HF_FORMAT_SNORM16);
        break;
    case HF_FORMAT_UNORM16:
        hf__table_fmt_v8(t, c, nc, HF_FORMAT_UNORM16);
        break;
    case HF_FORMAT_SNORM8: hf__table_fmt_v8(t, c, nc, HF_FORMAT_SNORM8); break;
    default: hf__table_fmt_v8(t, c, nc, HF_FORMAT_UNORM8); break;
    }
}

#define HF__TB 32 /* points a block of the table writer's tables */

/* Points i < n of a block from the tables (see hf__ribbon_write_table_v8)
   when every element abuts in one run (hf__rout wl): each vertex's run
   assembled by byte shuffles, the streams both sides share once a point,
   then two 8-byte stores (overlapping when the run is under 16 bytes). */
HF__TARGET_AVX2 HF__INLINE __m128i hf__slot_v8(const unsigned char *t,
                                               size_t ts, int i, __m128i mask)
{
    return _mm_shuffle_epi8(
        _mm_loadu_si128((const __m128i *)(const void *)(t + (size_t)i * ts)),
        mask);
}

/* The or of the slots of the ns streams (0 to 4, a constant where it is
   inlined) that both sides of point i share, in the table's order */
HF__TARGET_AVX2 HF__INLINE __m128i
hf__window_shared_v8(const unsigned char *const *t, const size_t *ts,
                     const __m128i *mk, int i, int ns)
{
    __m128i s01;
    if (ns == 0) return _mm_setzero_si128();
    if (ns == 1) return hf__slot_v8(t[0], ts[0], i, mk[0]);
    s01 = _mm_or_si128(hf__slot_v8(t[0], ts[0], i, mk[0]),
                       hf__slot_v8(t[1], ts[1], i, mk[1]));
    if (ns == 2) return s01;
    if (ns == 3) return _mm_or_si128(s01, hf__slot_v8(t[2], ts[2], i, mk[2]));
    return _mm_or_si128(s01, _mm_or_si128(hf__slot_v8(t[2], ts[2], i, mk[2]),
                                          hf__slot_v8(t[3], ts[3], i, mk[3])));
}

/* hf__window_put_v8 with t, ts and mk the slots, strides and masks of
   the ns streams both sides share besides the position (ns a constant in
   each copy it inlines) */
HF__TARGET_AVX2 HF__INLINE void
hf__window_rows_v8(const hf__rout *ro, unsigned char tab[6][HF__TB * 16],
                   const size_t *tsq, size_t v, int n,
                   const unsigned char *const *t, const size_t *ts,
                   const __m128i *mk, int ns)
{
    const int q0 = ro->wq[0], L = ro->wl;
    const size_t st = ro->stride[q0];
    const __m128i sh = _mm_loadu_si128((const __m128i *)(const void *)ro->wsh);
    const int pos = ro->base[HF__S_POS] != NULL;
    const __m128i mp =
        _mm_loadu_si128((const __m128i *)(const void *)ro->wm[HF__S_POS]);
    const size_t tp = tsq[HF__S_POS];
    unsigned char *o = ro->base[q0] + v * st;
    int i;
    for (i = 0; i < n; ++i, o += 2 * st) {
        __m128i a = hf__window_shared_v8(t, ts, mk, i, ns), b = a;
        if (pos) {
            a = _mm_or_si128(a, hf__slot_v8(tab[HF__S_POS], tp, i, mp));
            b = _mm_or_si128(b, hf__slot_v8(tab[5], tp, i, mp));
        }
        _mm_storel_epi64((__m128i *)(void *)o, a);
        _mm_storel_epi64((__m128i *)(void *)(o + L - 8),
                         _mm_shuffle_epi8(a, sh));
        _mm_storel_epi64((__m128i *)(void *)(o + st), b);
        _mm_storel_epi64((__m128i *)(void *)(o + st + L - 8),
                         _mm_shuffle_epi8(b, sh));
    }
}

HF__TARGET_AVX2 HF__INLINE void
hf__window_put_v8(const hf__rout *ro, unsigned char tab[6][HF__TB * 16],
                  const size_t *tsq, size_t v, int n)
{
    const unsigned char *t[4];
    __m128i mk[4];
    size_t ts[4];
    int q, ns = 0;
    for (q = HF__S_TAN; q <= HF__S_C3D; ++q) {
        if (!ro->base[q]) continue;
        t[ns] = tab[q];
        ts[ns] = tsq[q];
        mk[ns++] = _mm_loadu_si128((const __m128i *)(const void *)ro->wm[q]);
    }
    switch (ns) {
    case 0: hf__window_rows_v8(ro, tab, tsq, v, n, t, ts, mk, 0); break;
    case 1: hf__window_rows_v8(ro, tab, tsq, v, n, t, ts, mk, 1); break;
    case 2: hf__window_rows_v8(ro, tab, tsq, v, n, t, ts, mk, 2); break;
    case 3: hf__window_rows_v8(ro, tab, tsq, v, n, t, ts, mk, 3); break;
    default: hf__window_rows_v8(ro, tab, tsq, v, n, t, ts, mk, 4); break;
    }
}

/* Every stream of a layout the table writer takes (hf__rout nw > 0), in
   blocks of up to HF__TB points: each stream's values encoded into a
   table eight points at a time (hf__table_v8), then written out, as a
   run assembled in a register a vertex where the elements abut
   (hf__window_put_v8), else stream by stream in address order, an
   element in one or two scalar stores (hf__elems_put). Same values, same
   operations: the same bytes as the reference. */
HF__TARGET_AVX2 HF__INLINE void
hf__ribbon_write_table_v8_in(const hf__rframe *fr, int P, const hf__rconst *K,
                             const hf__rstrand *str, const hf__rout *ro,
                             size_t v0, const __m256 *ov)
{
    /* rows: the five streams, then the right side's positions; blocks of
       up to HF__TB points, so the copies' set-up is shared */
    unsigned char tab[6][HF__TB * 16];
    const __m256 ws = _mm256_set1_ps(str->wscale);
    const __m256 u = _mm256_set1_ps(str->uv[0]), v = _mm256_set1_ps(str->uv[1]);
    size_t ts[5];
    int j0, k, c, m, q;
    for (q = 0; q < 5; ++q) {
        const int size = hf_format_bytes(ro->fmt[q]);
        ts[q] = (size_t)(size == 4 ? 16 : 4 * size);
    }
    for (j0 = 0; j0 < P; j0 += HF__TB) {
        const int n = P - j0 < HF__TB ? P - j0 : HF__TB;
        for (k = j0 / 8; 8 * k < j0 + n; ++k) {
            const int o = 4 + 8 * k;
            const size_t g = 8u * (size_t)(k - j0 / 8);
            const __m256 tt = _mm256_loadu_ps(K->tt + 8 * k);
            __m256 L[4], R[4];
            if (ro->base[HF__S_POS]) {
                const __m256 w =
                    _mm256_mul_ps(_mm256_loadu_ps(K->hw + 8 * k), ws);
                HF__UNROLL for (c = 0; c < 3; ++c) {
                    const __m256 p = _mm256_loadu_ps(fr->p[c] + o);
                    const __m256 sw =
                        _mm256_mul_ps(_mm256_loadu_ps(fr->s[c] + o), w);
                    L[c] = _mm256_mul_ps(
                        _mm256_sub_ps(_mm256_sub_ps(p, sw), ov[1 + c]),
                        ov[0]);
                    R[c] = _mm256_mul_ps(
                        _mm256_sub_ps(_mm256_add_ps(p, sw), ov[1 + c]),
                        ov[0]);
                }
                hf__table_v8(tab[HF__S_POS] + g * ts[HF__S_POS], L, 3,
                             ro->fmt[HF__S_POS]);
                hf__table_v8(tab[5] + g * ts[HF__S_POS], R, 3,
                             ro->fmt[HF__S_POS]);
            }
            if (ro->base[HF__S_TAN]) {
                HF__UNROLL for (c = 0; c < 3; ++c)
                    L[c] = _mm256_loadu_ps(fr->t[c] + o);
                hf__table_v8(tab[HF__S_TAN] + g * ts[HF__S_TAN], L, 3,
                             ro->fmt[HF__S_TAN]);
            }
            if (ro->base[HF__S_TEX]) {
                L[0] = u;
                L[1] = v;
                L[2] = tt;
                hf__table_v8(tab[HF__S_TEX] + g * ts[HF__S_TEX], L, 3,
                             ro->fmt[HF__S_TEX]);
            }
            if (ro->base[HF__S_COL]) {
                HF__UNROLL for (c = 0; c < 3; ++c)
                    L[c] = _mm256_set1_ps(str->rgba[c]);
                L[3] = _mm256_mul_ps(_mm256_set1_ps(str->rgba[3]),
                                     _mm256_loadu_ps(K->fade + 8 * k));
                hf__table_v8(tab[HF__S_COL] + g * ts[HF__S_COL], L, 4,
                             ro->fmt[HF__S_COL]);
            }
            if (ro->base[HF__S_C3D]) {
                L[0] = _mm256_set1_ps(str->c3x);
                L[1] = tt;
                hf__table_v8(tab[HF__S_C3D] + g * ts[HF__S_C3D], L, 2,
                             ro->fmt[HF__S_C3D]);
            }
        }
        if (ro->wl) {
            hf__window_put_v8(ro, tab, ts, v0 + 2u * (size_t)j0, n);
            continue;
        }
        for (m = 0; m < ro->nw; ++m) {
            const size_t st = ro->stride[q = ro->wq[m]];
            hf__elems_put(ro->base[q] + (v0 + 2u * (size_t)j0) * st, st, n,
                          tab[q], tab[q == HF__S_POS ? 5 : q], ts[q],
                          ro->wb[m]);
        }
    }
}

/* the writer above as a call, for the dispatch of one strand */
HF__TARGET_AVX2 HF__PRIVATE void
hf__ribbon_write_table_v8(const hf__rframe *fr, int P, const hf__rconst *K,
                          const hf__rstrand *str, const hf__rout *ro, size_t v0)
{
    __m256 ov[4];
    hf__rout_vec_v8(ro, ov);
    hf__ribbon_write_table_v8_in(fr, P, K, str, ro, v0, ov);
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
}

/* A normalized format's encoding as per-call vectors, for a kernel that
   meets the format at run time: the clamp's bounds, the scale and the
   code's mask (hf__encode_v8's operations with them in memory). */
typedef struct hf__enc8 {
    __m256 lo, scale, one;
    __m256i mask;
} hf__enc8;

HF__TARGET_AVX2 HF__INLINE void hf__enc8_init(hf__enc8 *e, int fmt)
{
    float lo;
    e->scale = _mm256_set1_ps(hf__norm_scale(fmt, &lo));
    e->lo = _mm256_set1_ps(lo);
    /* in memory beside them, so that each use is an operand, not a
       broadcast */
    e->one = _mm256_set1_ps(1.0f);
    e->mask = _mm256_set1_epi32(hf_format_bytes(fmt) == 2 ? 0xffff : 0xff);
}

/* hf__encode_v8's operations, the format from e */
HF__TARGET_AVX2 HF__INLINE __m256i hf__encode_var_v8(__m256 x,
                                                     const hf__enc8 *e)
{
    const __m256 v = _mm256_min_ps(_mm256_max_ps(x, e->lo), e->one);
    return _mm256_and_si256(_mm256_cvtps_epi32(_mm256_mul_ps(v, e->scale)),
                            e->mask);
}

/* One side's compact vertices of a group of n points at o (vertex i at
   o + i st2) from its words: d0 = x y, d1 = z u, and the words both sides
   share, v t and the tangent, already interleaved (s02: points 0 1 | 4 5,
   s13: 2 3 | 6 7). Two 8-byte stores a vertex, the second over bytes
   7..14: the pad byte is never written. */
HF__TARGET_AVX2 HF__INLINE void hf__c16_put_v8(unsigned char *o, size_t st2,
                                               int n, __m256i d0, __m256i d1,
                                               __m256i s02, __m256i s13)
{
    const __m256i a = _mm256_unpacklo_epi32(d0, d1),
                  b = _mm256_unpackhi_epi32(d0, d1);
    __m256i v[4];
    int k;
    /* vertices i | i + 4, i = 0..3 */
    v[0] = _mm256_unpacklo_epi64(a, s02);
    v[1] = _mm256_unpackhi_epi64(a, s02);
    v[2] = _mm256_unpacklo_epi64(b, s13);
    v[3] = _mm256_unpackhi_epi64(b, s13);
    if (n == 8) {
        HF__UNROLL for (k = 0; k < 4; ++k) {
            const __m256i sh = _mm256_srli_si256(v[k], 7);
            unsigned char *lo = o + (size_t)k * st2, *hi = lo + 4 * st2;
            _mm_storel_epi64((__m128i *)(void *)lo,
                             _mm256_castsi256_si128(v[k]));
            _mm_storel_epi64((__m128i *)(void *)(lo + 7),
                             _mm256_castsi256_si128(sh));
            _mm_storel_epi64((__m128i *)(void *)hi,
                             _mm256_extracti128_si256(v[k], 1));
            _mm_storel_epi64((__m128i *)(void *)(hi + 7),
                             _mm256_extracti128_si256(sh, 1));
        }
    } else { /* the last, partial group */
        unsigned char f[8][16];
        int i;
        HF__UNROLL for (k = 0; k < 4; ++k) {
            _mm_storeu_si128((__m128i *)(void *)f[k],
                             _mm256_castsi256_si128(v[k]));
            _mm_storeu_si128((__m128i *)(void *)f[k + 4],
                             _mm256_extracti128_si256(v[k], 1));
        }
        for (i = 0; i < n; ++i) HF_MEMCPY(o + (size_t)i * st2, f[i], 15);
    }
}

/* Group k of the compact vertex's writer below: n points (8 but for the
   last, a constant where inlined) at b. */
HF__TARGET_AVX2 HF__INLINE void
hf__c16_group_v8(const hf__rframe *fr, const hf__rconst *K, int k, int n,
                 unsigned char *b, size_t st, __m256 ws, __m256i eu, __m256i ev,
                 const __m256 *ov, const hf__enc8 *enc)
{
    const int o = 4 + 8 * k;
    const __m256 w = _mm256_mul_ps(_mm256_loadu_ps(K->hw + 8 * k), ws);
    __m256i eL[3], eR[3], et[3], d2, d3, s02, s13;
    int c;
    HF__UNROLL for (c = 0; c < 3; ++c) {
        const __m256 p = _mm256_loadu_ps(fr->p[c] + o);
        const __m256 sw = _mm256_mul_ps(_mm256_loadu_ps(fr->s[c] + o), w);
        eL[c] =
            hf__encode_var_v8(_mm256_mul_ps(_mm256_sub_ps(_mm256_sub_ps(p, sw),
                                                          ov[1 + c]),
                                            ov[0]),
                              &enc[0]);
        eR[c] =
            hf__encode_var_v8(_mm256_mul_ps(_mm256_sub_ps(_mm256_add_ps(p, sw),
                                                          ov[1 + c]),
                                            ov[0]),
                              &enc[0]);
        et[c] = hf__encode_var_v8(_mm256_loadu_ps(fr->t[c] + o), &enc[2]);
    }
    d2 = _mm256_or_si256(
        ev, _mm256_slli_epi32(hf__encode_var_v8(_mm256_loadu_ps(K->tt + 8 * k),
                                                &enc[1]),
                              16));
    d3 = _mm256_or_si256(_mm256_or_si256(et[0], _mm256_slli_epi32(et[1], 8)),
                         _mm256_slli_epi32(et[2], 16));
    s02 = _mm256_unpacklo_epi32(d2, d3);
    s13 = _mm256_unpackhi_epi32(d2, d3);
    hf__c16_put_v8(b, 2 * st, n,
                   _mm256_or_si256(eL[0], _mm256_slli_epi32(eL[1], 16)),
                   _mm256_or_si256(eL[2], eu), s02, s13);
    hf__c16_put_v8(b + st, 2 * st, n,
                   _mm256_or_si256(eR[0], _mm256_slli_epi32(eR[1], 16)),
                   _mm256_or_si256(eR[2], eu), s02, s13);
}

/* The compact vertex (hf__rout c16) eight points at a time without the
   tables: the table writer's values and encodings (so the same bytes),
   packed into four 32-bit words a vertex (x y | z u | v t | tangent),
   transposed in registers and stored. enc: the position's, texcoord's
   and tangent's formats (hf__enc8_init); ov as hf__rout_vec_v8. */
HF__TARGET_AVX2 HF__INLINE void
hf__ribbon_write_c16_v8_in(const hf__rframe *fr, int P, const hf__rconst *K,
                           const hf__rstrand *str, const hf__rout *ro,
                           size_t v0, const __m256 *ov, const hf__enc8 *enc)
{
    const size_t st = ro->stride[HF__S_POS];
    const __m256 ws = _mm256_set1_ps(str->wscale);
    /* u and v are the strand's: encoded once */
    const __m256i eu = _mm256_slli_epi32(
        hf__encode_var_v8(_mm256_set1_ps(str->uv[0]), &enc[1]), 16);
    const __m256i ev = hf__encode_var_v8(_mm256_set1_ps(str->uv[1]), &enc[1]);
    unsigned char *b = ro->base[HF__S_POS] + v0 * st;
    int k;
    for (k = 0; 8 * k + 8 <= P; ++k, b += 16 * st)
        hf__c16_group_v8(fr, K, k, 8, b, st, ws, eu, ev, ov, enc);
    if (8 * k < P)
        hf__c16_group_v8(fr, K, k, P - 8 * k, b, st, ws, eu, ev, ov, enc);
}
#endif

#if HF__NEON
/* hf__encode_v4 in NEON: the same clamps and rounding (vcvt_f16_f32
   rounds to nearest even, subnormal halves included, as hf__encode1 does
   by hand), so the same codes. */
HF__INLINE uint32x4_t hf__encode_v4(float32x4_t x, int fmt)
{
    const float32x4_t m = vdupq_n_f32(12582912.0f);
    float lo, scale;
    float32x4_t v;
    if (fmt == HF_FORMAT_F16) {
        const float32x4_t c = vminq_f32(vmaxq_f32(x, vdupq_n_f32(-65504.0f)),
                                        vdupq_n_f32(65504.0f));
        return vmovl_u16(vreinterpret_u16_f16(vcvt_f16_f32(c)));
    }
    scale = hf__norm_scale(fmt, &lo);
    v = vminq_f32(vmaxq_f32(x, vdupq_n_f32(lo)), vdupq_n_f32(1.0f));
    v = vsubq_f32(vaddq_f32(vmulq_f32(v, vdupq_n_f32(scale)), m), m);
    return vandq_u32(vreinterpretq_u32_s32(vcvtq_s32_f32(v)),
                     vdupq_n_u32(hf_format_bytes(fmt) == 2 ? 0xffffu : 0xffu));
}

HF__INLINE void hf__transpose4_v4(float32x4_t *r)
{
    const float32x4x2_t a = vtrnq_f32(r[0], r[1]), b = vtrnq_f32(r[2], r[3]);
    r[0] = vcombine_f32(vget_low_f32(a.val[0]), vget_low_f32(b.val[0]));
    r[1] = vcombine_f32(vget_low_f32(a.val[1]), vget_low_f32(b.val[1]));
    r[2] = vcombine_f32(vget_high_f32(a.val[0]), vget_high_f32(b.val[0]));
    r[3] = vcombine_f32(vget_high_f32(a.val[1]), vget_high_f32(b.val[1]));
}

/* Components c[0, nc) of n < 5 points at o, both vertices of each (L at
   o + 2 i st, R a stride later; R may be L), in format fmt: floats as
   they are, other formats encoded four lanes at a time, then each
   vertex's bytes copied out in component order. */
HF__PRIVATE void hf__emit_pair_v4(unsigned char *o, size_t st, int n,
                                  const float32x4_t *L, const float32x4_t *R,
                                  int nc, int fmt)
{
    const int size = hf_format_bytes(fmt);
    int side, i, c;
    HF__UNROLL for (side = 0; side < 2; ++side) {
        const float32x4_t *v = side ? R : L;
        uint32_t lane[4][4];
        for (c = 0; c < nc; ++c)
            vst1q_u32(lane[c], fmt == HF_FORMAT_F32
                                   ? vreinterpretq_u32_f32(v[c])
                                   : hf__encode_v4(v[c], fmt));
        for (i = 0; i < n; ++i) {
            unsigned char *q = o + (2u * (size_t)i + (size_t)side) * st;
            for (c = 0; c < nc; ++c, q += size) {
                if (size == 4) {
                    HF_MEMCPY(q, &lane[c][i], 4);
                } else if (size == 2) {
                    const uint16_t h = (uint16_t)lane[c][i];
                    HF_MEMCPY(q, &h, 2);
                } else {
                    *q = (unsigned char)lane[c][i];
                }
            }
        }
    }
}

/* hf__ribbon_write_v4 in NEON, four points at a time: the float runs
   (see hf__float_run) by a 4 x 4 transpose, x y z tx and ty tz u v of
   each vertex, as hf__put_run_v4 does; every other stream component by
   component in its format. */
HF__PRIVATE int hf__ribbon_write_v4(const hf__rframe *fr, int P,
                                    const hf__rconst *K, const hf__rstrand *str,
                                    const hf__rout *ro, size_t v0)
{
    const int run = ro->run;
    const float32x4_t ws = vdupq_n_f32(str->wscale);
    const float32x4_t is = vdupq_n_f32(ro->inv_scale);
    int k, c, i, q;
    for (k = 0; 4 * k < P; ++k) {
        const int o = 4 + 4 * k, n = P - 4 * k < 4 ? P - 4 * k : 4;
        const size_t v = v0 + 8u * (size_t)k;
        const float32x4_t w = vmulq_f32(vld1q_f32(K->hw + 4 * k), ws);
        const float32x4_t tt = vld1q_f32(K->tt + 4 * k);
        float32x4_t L[4], R[4], T[4], V[4];
        HF__UNROLL for (c = 0; c < 3; ++c) {
            const float32x4_t p = vld1q_f32(fr->p[c] + o);
            const float32x4_t sw = vmulq_f32(vld1q_f32(fr->s[c] + o), w);
            const float32x4_t og = vdupq_n_f32(ro->origin[c]);
            L[c] = vmulq_f32(vsubq_f32(vsubq_f32(p, sw), og), is);
            R[c] = vmulq_f32(vsubq_f32(vaddq_f32(p, sw), og), is);
            T[c] = vld1q_f32(fr->t[c] + o);
        }
        if (run) {
            const size_t st = ro->stride[HF__S_POS];
            unsigned char *b = ro->base[HF__S_POS] + v * st;
            L[3] = R[3] = T[0];
            V[0] = T[1];
            V[1] = T[2];
            V[2] = vdupq_n_f32(str->uv[0]);
            V[3] = vdupq_n_f32(str->uv[1]);
            hf__transpose4_v4(L); /* x y z tx of each left vertex */
            hf__transpose4_v4(R);
            hf__transpose4_v4(V); /* ty tz u v */
            for (i = 0; i < n; ++i, b += 2 * st) {
                vst1q_f32((float *)(void *)b, L[i]);
                vst1q_f32((float *)(void *)(b + st), R[i]);
                if (run == 3) {
                    vst1q_f32((float *)(void *)(b + 16), V[i]);
                    vst1q_f32((float *)(void *)(b + st + 16), V[i]);
                    HF_MEMCPY(b + 32, K->tt + 4 * k + i, 4);
                    HF_MEMCPY(b + st + 32, K->tt + 4 * k + i, 4);
                } else {
                    vst1_f32((float *)(void *)(b + 16), vget_low_f32(V[i]));
                    vst1_f32((float *)(void *)(b + st + 16), vget_low_f32(V[i]));
                }
            }
        } else if (ro->base[HF__S_POS]) {
            hf__emit_pair_v4(ro->base[HF__S_POS] + v * ro->stride[HF__S_POS],
                             ro->stride[HF__S_POS], n, L, R, 3,
                             ro->fmt[HF__S_POS]);
        }
        for (q = HF__S_TAN; q <= HF__S_C3D; ++q) {
            if (!ro->base[q] || (q == HF__S_TAN && run) ||
                (q == HF__S_TEX && run == 3))
                continue;
            switch (q) { /* the same on both sides, as the reference */
            case HF__S_TAN:
                V[0] = T[0];
                V[1] = T[1];
                V[2] = T[2];
                break;
            case HF__S_TEX:
                V[0] = vdupq_n_f32(str->uv[0]);
                V[1] = vdupq_n_f32(str->uv[1]);
                V[2] = tt;
                break;
            case HF__S_COL:
                HF__UNROLL for (c = 0; c < 3; ++c)
                    V[c] = vdupq_n_f32(str->rgba[c]);
                V[3] = vmulq_f32(vdupq_n_f32(str->rgba[3]),
                                 vld1q_f32(K->fade + 4 * k));
                break;
            default: /* HF__S_C3D */
                V[0] = vdupq_n_f32(str->c3x);
                V[1] = tt;
                break;
            }
            hf__emit_pair_v4(ro->base[q] + v * ro->stride[q], ro->stride[q], n,
                             V, V, hf__stream_nc[q], ro->fmt[q]);
        }
    }
    return 1;
}
#endif

#if HF__AVX2
/* One strand's vertices at eight lanes: the float run (ro->run) or the
   windows (ro->nw) the layout has; other layouts are left to four lanes
   (returns 0). */
HF__PRIVATE int hf__ribbon_write_v8(const hf__rframe *fr, int P,
                                    const hf__rconst *K, const hf__rstrand *str,
                                    const hf__rout *ro, size_t v0)
{
    if (ro->run)
        hf__ribbon_write_run_v8(fr, P, K, str, ro, v0);
    else if (ro->nw)
        hf__ribbon_write_table_v8(fr, P, K, str, ro, v0);
    return ro->run || ro->nw;
}
#endif

typedef struct hf__write_kernels {
    hf__isa isa;
    int (*write)(const hf__rframe *, int, const hf__rconst *,
                 const hf__rstrand *, const hf__rout *, size_t);
} hf__write_kernels;

/* The writers per width; the AVX-512 level runs the AVX2 ones. */
static const hf__write_kernels hf__write_widths[] = {
#if HF__AVX2
    {{HF__ISA_V8}, hf__ribbon_write_v8},
#endif
#if HF__V4
    {{HF__ISA_V4}, hf__ribbon_write_v4},
#endif
    {{HF__ISA_V1}, hf__ribbon_write_v1}};

/* The dispatch of the writers with the kernels k (hf__write_widths,
   resolved once a call): one strand's vertices from its frame, by the
   widest kernel that takes the layout. */
HF__PRIVATE void hf__ribbon_write(const hf__rframe *fr, int P,
                                  const hf__rconst *K, const hf__rstrand *str,
                                  const hf__rout *ro, size_t v0,
                                  const hf__write_kernels *k)
{
    while (!k->write(fr, P, K, str, ro, v0)) ++k;
}

/* ---- 8.5 streaming stores: the stage ------------------------------------ */

/* Streaming stores for ribbons (hf_ribbon_params.nontemporal) go through
   a stage: a strand's vertices are written there by the usual kernels,
   then copied out in 16-byte streaming stores. The copy writes whole
   blocks, so the streams must tile one interleaved vertex exactly
   (hf__rout's tile), a strand's vertices must fit the stage, and every
   strand's block must start 16-byte aligned (v0: the call's first
   vertex): strands that stream beside ones whose ends take ordinary
   stores into the lines they share ran 3x slower (P = 9 and 11, 36-byte
   vertices). Returns 1 with the vertex size and the first byte of
   vertex 0 when so. */
#define HF__STAGE_BYTES 8192
HF__PRIVATE int hf__ribbon_stage(const hf__rout *ro, int P, size_t v0,
                                 size_t *block, unsigned char **first)
{
    const size_t sb = 2u * (size_t)P * ro->tile;
    if (!HF__SSE || !ro->tile || sb > HF__STAGE_BYTES || sb % 16u != 0 ||
        ((uintptr_t)ro->base[ro->wq[0]] + v0 * ro->tile) % 16u != 0)
        return 0;
    *block = ro->tile;
    *first = ro->base[ro->wq[0]];
    return 1;
}

/* Where the streamed ribbons' scratch goes: no frame row's points and no
   stage across a 4 KiB page boundary. With a tangent row or the stage
   across one, scene L's streamed ribbons at AVX2 ran 2.3-2.6x slower (63
   ns a strand against 141-195, by where the stack put them: about a
   third of runs under address randomisation); page-split stores, queued
   behind the streaming stores and read back, are the likely cause.
   hf__frame_in_page: the first page boundary in room (HF__RIBBON_ROOM
   floats: a frame, the boundary's slack, then a second frame or the
   stage); the rows then start at 0, 1072, 2144 and 3216 bytes into a
   page and at 192, 1264, 2336, 3408 and 384 past the next ones, so none
   crosses with P <= 160 (the second frame's with P <= 64).
   hf__stage_in_page: a stage of `need` bytes in buf (HF__STAGE_BYTES),
   moved to the next page boundary where it would cross one and fits in
   one (buf off bytes into a page: the boundary leaves 4096 + off bytes,
   >= need). */
#define HF__RIBBON_ROOM                                                        \
    ((sizeof(hf__rframe) + 4096 +                                              \
      (sizeof(hf__rframe) > HF__STAGE_BYTES ? sizeof(hf__rframe)               \
                                            : HF__STAGE_BYTES)) /              \
     sizeof(float))
/* the first page boundary at or past p */
HF__PRIVATE float *hf__page_up(float *p)
{
    return p + ((4096u - ((uintptr_t)p & 4095u)) & 4095u) / 4u;
}

HF__PRIVATE hf__rframe *hf__frame_in_page(float *room)
{
    return (hf__rframe *)(void *)hf__page_up(room);
}

HF__PRIVATE float *hf__stage_in_page(float *buf, size_t need)
{
    return need <= 4096u && ((uintptr_t)buf & 4095u) + need > 4096u
               ? hf__page_up(buf)
               : buf;
}

/* The layout ro with its streams moved into the stage: a strand's
   vertices are written there as the strand at vertex 0. */
HF__PRIVATE void hf__rout_staged(const hf__rout *ro, float *stage,
                                 const unsigned char *dst0, hf__rout *so)
{
    int k;
    *so = *ro;
    for (k = 0; k < 5; ++k)
        if (ro->base[k])
            so->base[k] = (unsigned char *)stage + (ro->base[k] - dst0);
}

/* n bytes from src to dst (a strand's vertices out of the stage): the
   reference, a plain copy */
HF__PRIVATE void hf__stream_copy_v1(unsigned char *dst, const float *src,
                                    size_t n)
{
    HF_MEMCPY(dst, src, n);
}

#if HF__SSE
/* streaming 16-byte stores from dst's first 16-byte boundary, plain
   copies for the ends */
HF__PRIVATE void hf__stream_copy_v4(unsigned char *dst, const float *src,
                                    size_t n)
{
    const unsigned char *from = (const unsigned char *)src;
    size_t head = (16u - ((uintptr_t)dst & 15u)) & 15u, i;
    if (head > n) head = n;
    HF_MEMCPY(dst, from, head);
    i = head;
    hf__page_ahead(dst, n);
    for (; i + 16 <= n; i += 16)
        _mm_stream_si128((__m128i *)(void *)(dst + i),
                         _mm_loadu_si128(
                             (const __m128i *)(const void *)(from + i)));
    HF_MEMCPY(dst + i, from + i, n - i);
}
#endif

/* The copies out of the stage per width, for the loops a strand at a
   time (hf__ribbons_each; the eight-lane loops stream by their own,
   hf__stream_copy_v8) */
typedef struct hf__stream_kernels {
    hf__isa isa;
    void (*copy)(unsigned char *, const float *, size_t);
} hf__stream_kernels;

static const hf__stream_kernels hf__stream_widths[] = {
#if HF__SSE
    {{HF__ISA_V4}, hf__stream_copy_v4},
#endif
    {{HF__ISA_V1}, hf__stream_copy_v1}};

#if HF__AVX2
/* hf__stream_copy_v4 in 32-byte streaming stores where dst is aligned to
   them (a strand's block is, in a buffer aligned as a mapped one); the
   rest, and a block that is not aligned, by hf__stream_copy_v4 (each
   part's pages walked ahead once) */
HF__TARGET_AVX2 HF__INLINE void hf__stream_copy_v8(unsigned char *dst,
                                                   const float *src, size_t n)
{
    const size_t m = ((uintptr_t)dst & 31u) == 0 ? n & ~(size_t)31u : 0;
    size_t i;
    hf__page_ahead(dst, m);
    for (i = 0; i < m; i += 32)
        _mm256_stream_ps((float *)(void *)(dst + i),
                         _mm256_loadu_ps(src + i / 4));
    if (m < n) hf__stream_copy_v4(dst + m, src + m / 4, n - m);
}
#endif

/* ---- 8.6 the whole-call loops (AVX2, AVX-512) --------------------------- */

/* Strand s's width multiplier (times the frame's; at most cap), root
   UV, colour and 3D-colour x, non-finite inputs read as 0 */
HF__INLINE void hf__rstrand_fill(const hf_ribbon_strands *sv, int s,
                                 float cap, hf__rstrand *str)
{
    int k;
    str->wscale *= hf__width_at(sv->width, s, cap);
    HF__UNROLL for (k = 0; k < 2; ++k)
        str->uv[k] =
            sv->root_uv ? hf__fin0(sv->root_uv[2 * (size_t)s + k]) : 0.0f;
    HF__UNROLL for (k = 0; k < 4; ++k)
        str->rgba[k] =
            sv->color ? hf__fin0(sv->color[4 * (size_t)s + k]) : 1.0f;
    str->c3x = sv->color3d_x ? hf__fin0(sv->color3d_x[s]) : 0.0f;
}

#if HF__AVX2
/* Strand pts's frame into fr at AVX2, or by the reference where the
   vector frame leaves it (as in hf__strand_frame); *wscale 0 for a strand
   framed collapsed */
HF__TARGET_AVX2 HF__INLINE void
hf__frame_strand_v8(const float *pts, int P, int ortho, const __m256 *e,
                    const hf_ribbon_params *params, hf__rframe *fr,
                    float *wscale)
{
    int finite;
    if (!hf__strand_frame_v8_in(pts, P, ortho, e, fr, &finite)) {
        _mm256_zeroupper(); /* the reference is SSE code */
        hf__strand_frame_rest(pts, P, params, fr, &finite);
    }
    *wscale = finite ? 1.0f : 0.0f;
}

/* Strand s's frame (hf__frame_strand_v8) where s < end: the runs make
   each strand's frame while the strand before is written */
HF__TARGET_AVX2 HF__INLINE void hf__frame_at_v8(const hf_ribbon_strands *sv,
                                                int s, int end, int P,
                                                int ortho, const __m256 *e,
                                                const hf_ribbon_params *params,
                                                hf__rframe *fr, float *wscale)
{
    if (s < end)
        hf__frame_strand_v8(sv->points + (size_t)s * (size_t)P * 3u, P, ortho,
                            e, params, fr, wscale);
}

/* hf_ribbons' strands at AVX2 in one target function, for the float runs
   (mode 0), the layouts of the table writer (1) and the compact vertex
   (2, hf__rout c16): each strand's frame and vertices inlined, where a
   call each, with their set-up, took an eighth of the instructions of the
   float runs (7 % of the table writer's). A strand's frame is made one
   strand ahead of its vertices, in two frames by turns (fr, fr2): the
   frame's chains of square roots and divisions then run beside the stores
   of the strand before. Streaming (stage, hf__ribbon_stage's block and
   first byte dst0; NULL or not, a constant in each inlined copy) writes
   each strand into the stage, which takes fr2's place on the stack (one
   frame, made after the strand before is written), then out with
   hf__stream_copy_v8. */
HF__TARGET_AVX2 HF__INLINE void
hf__ribbons_loop_v8(const hf_ribbon_strands *sv, int first, int count,
                    const hf_ribbon_params *params, const hf__rconst *K,
                    const hf__rout *out, int out_first, hf__rframe *fr,
                    hf__rframe *fr2, int mode, float *stage,
                    unsigned char *dst0, size_t block)
{
    const int P = params->points_per_strand,
              ortho = params->orthographic != 0, end = first + count;
    const size_t sb = 2u * (size_t)P * block;
    const hf_ribbon_strands svl = *sv; /* no reload after every store */
    hf__rframe *F[2];
    float wsc[2];
    __m256 e[3], ov[4];
    hf__enc8 enc[3];
    hf__rout so;
    const hf__rout *ro = out;
    int s;
    if (stage) {
        hf__rout_staged(out, stage, dst0, &so);
        ro = &so;
    }
    hf__frame_eye_v8(params, e);
    hf__rout_vec_v8(ro, ov);
    if (mode == 2) {
        hf__enc8_init(&enc[0], ro->fmt[HF__S_POS]);
        hf__enc8_init(&enc[1], ro->fmt[HF__S_TEX]);
        hf__enc8_init(&enc[2], ro->fmt[HF__S_TAN]);
    }
    F[0] = fr;
    F[1] = fr2;
    hf__frame_at_v8(&svl, first, end, P, ortho, e, params, F[0], &wsc[0]);
    for (s = first; s < end; ++s) {
        const int j = stage ? 0 : (s - first) & 1;
        const size_t v0 = (size_t)(s - out_first) * (size_t)P * 2u,
                     w0 = stage ? 0 : v0;
        hf__rstrand str;
        if (!stage)
            hf__frame_at_v8(&svl, s + 1, end, P, ortho, e, params, F[j ^ 1],
                            &wsc[j ^ 1]);
        str.wscale = wsc[j];
        hf__rstrand_fill(&svl, s, K->wcap, &str);
        if (mode == 2)
            hf__ribbon_write_c16_v8_in(F[j], P, K, &str, ro, w0, ov, enc);
        else if (mode == 1)
            hf__ribbon_write_table_v8_in(F[j], P, K, &str, ro, w0, ov);
        else
            hf__ribbon_write_run_v8_in(F[j], P, K, &str, ro, w0, ov);
        if (stage) {
            hf__stream_copy_v8(dst0 + v0 * block, stage, sb);
            hf__frame_at_v8(&svl, s + 1, end, P, ortho, e, params, F[0],
                            &wsc[0]);
        }
    }
}

HF__TARGET_AVX2 HF__PRIVATE void
hf__ribbons_run_v8(const hf_ribbon_strands *sv, int first, int count,
                   const hf_ribbon_params *params, const hf__rconst *K,
                   const hf__rout *ro, int out_first, hf__rframe *fr,
                   hf__rframe *fr2, float *stage, unsigned char *dst0,
                   size_t block)
{
    /* (the compact vertex leaves a byte of its stride: never staged) */
    if (stage) {
        if (ro->run)
            hf__ribbons_loop_v8(sv, first, count, params, K, ro, out_first, fr,
                                NULL, 0, stage, dst0, block);
        else
            hf__ribbons_loop_v8(sv, first, count, params, K, ro, out_first, fr,
                                NULL, 1, stage, dst0, block);
        _mm_sfence(); /* streamed stores visible before we return */
    } else if (ro->run)
        hf__ribbons_loop_v8(sv, first, count, params, K, ro, out_first, fr, fr2,
                            0, NULL, NULL, 0);
    else if (ro->c16)
        hf__ribbons_loop_v8(sv, first, count, params, K, ro, out_first, fr, fr2,
                            2, NULL, NULL, 0);
    else
        hf__ribbons_loop_v8(sv, first, count, params, K, ro, out_first, fr, fr2,
                            1, NULL, NULL, 0);
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
}
#endif

#if HF__AVX512
/* Streamed float runs at AVX-512 without the stage: a group of eight
   points is 16 vertices of F = 9 floats (the 36-byte vertex, run 3) or
   6 (24 bytes, run 2), so F whole lines where the strand's block starts
   a line (P a multiple of 8, the output aligned). Each line is gathered
   in a register from six sources of sixteen floats (left and right x, y,
   z; tx ty; tz and t; u v) by three two-source permutes and two blends,
   and written with one 64-byte streaming store: no stage written and
   read back, no partial line. The same values in the same operations as
   hf__ribbon_group_v8, so the same bytes. Scene L's streamed ribbons:
   0.81-0.94x the staged AVX2 run's time, and 0.875-0.927x of that with
   the frame in registers too (hf__ribbon_fused_v16;
   docs/performance.md). */
typedef struct hf__lines {
    __m512i idx[9][3];   /* line c's lanes from source pair q */
    __mmask16 m[9][2];   /* lanes from pair 1, from pair 2 */
    int F;
} hf__lines;

/* The permutes' indices for F floats a vertex: float f of vertex w
   (point w / 2, left or right by w % 2) at 9 w + f of the group's
   stream. Pairs: (x, y), (z, tx ty), (tz t, u v), each source's lanes
   0-7 left or tx or tz, 8-15 right or ty or t. */
HF__TARGET_AVX512 HF__INLINE void hf__lines_init(hf__lines *t, int F)
{
    /* by float f of a vertex: its pair, its lane in the pair, 8 where left
       and right differ (x y z), 1 where it goes by point (all but u v).
       Every call sets these up, so no division or branch: w = g / F as a
       multiply (exact for g < 16 F, F 6 or 9) */
    const __m512i pair = _mm512_setr_epi32(0, 0, 1, 1, 1, 2, 2, 2, 2, 0, 0,
                                           0, 0, 0, 0, 0),
                  base = _mm512_setr_epi32(0, 16, 0, 16, 24, 0, 16, 17, 8, 0,
                                           0, 0, 0, 0, 0, 0),
                  side = _mm512_setr_epi32(8, 8, 8, 0, 0, 0, 0, 0, 0, 0, 0,
                                           0, 0, 0, 0, 0),
                  point = _mm512_setr_epi32(1, 1, 1, 1, 1, 1, 0, 0, 1, 0, 0,
                                            0, 0, 0, 0, 0),
                  lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10,
                                           11, 12, 13, 14, 15),
                  inv = _mm512_set1_epi32((65535 + F) / F),
                  vf = _mm512_set1_epi32(F), one = _mm512_set1_epi32(1),
                  two = _mm512_set1_epi32(2);
    int c;
    t->F = F;
#define HF__BY_F(tab) _mm512_maskz_permutexvar_epi32(0xffff, f, tab)
    for (c = 0; c < F; ++c) { /* float g = 16 c + l: float f of vertex w */
        const __m512i g = _mm512_add_epi32(_mm512_set1_epi32(16 * c), lane),
                      w = _mm512_maskz_srli_epi32(
                          0xffff, _mm512_mullo_epi32(g, inv), 16),
                      f = _mm512_sub_epi32(g, _mm512_mullo_epi32(w, vf)),
                      q = HF__BY_F(pair),
                      ix = _mm512_add_epi32(
                          HF__BY_F(base),
                          _mm512_add_epi32(
                              _mm512_mullo_epi32(
                                  HF__BY_F(side),
                                  _mm512_and_si512(w, one)),
                              _mm512_mullo_epi32(
                                  HF__BY_F(point),
                                  _mm512_maskz_srli_epi32(0xffff, w, 1))));
        const __mmask16 m1 = _mm512_cmpeq_epi32_mask(q, one),
                        m2 = _mm512_cmpeq_epi32_mask(q, two);
        t->idx[c][0] = _mm512_maskz_mov_epi32((__mmask16)~(m1 | m2), ix);
        t->idx[c][1] = _mm512_maskz_mov_epi32(m1, ix);
        t->idx[c][2] = _mm512_maskz_mov_epi32(m2, ix);
        t->m[c][0] = m1;
        t->m[c][1] = m2;
    }
#undef HF__BY_F
}

/* lo in lanes 0-7, hi in 8-15 (the masked form: gcc's plain one takes
   an "undefined" operand, which its C++ front end warns about) */
HF__TARGET_AVX512 HF__INLINE __m512 hf__join16(__m256 lo, __m256 hi)
{
    return _mm512_castpd_ps(_mm512_maskz_insertf64x4(
        0xff, _mm512_castpd256_pd512(_mm256_castps_pd(lo)),
        _mm256_castps_pd(hi), 1));
}

/* A strand's u v in lanes 0 and 1 (the lines' sixth source) */
HF__TARGET_AVX512 HF__INLINE __m512 hf__uv16(const hf__rstrand *str)
{
    return _mm512_castps128_ps512(
        _mm_unpacklo_ps(_mm_set1_ps(str->uv[0]), _mm_set1_ps(str->uv[1])));
}

/* A group's F lines at b from its sources S (left | right x, y, z; tx |
   ty; tz | t) and uv */
HF__TARGET_AVX512 HF__INLINE void hf__lines_out(unsigned char *b,
                                                const __m512 *S, __m512 uv,
                                                const hf__lines *t)
{
    int c;
    for (c = 0; c < t->F; ++c) {
        const __m512i *ix = t->idx[c];
        const __m512 a = _mm512_permutex2var_ps(S[0], ix[0], S[1]),
                     d = _mm512_permutex2var_ps(S[2], ix[1], S[3]),
                     e = _mm512_permutex2var_ps(S[4], ix[2], uv);
        _mm512_stream_ps(
            (float *)(void *)(b + 64 * c),
            _mm512_mask_blend_ps(t->m[c][1],
                                 _mm512_mask_blend_ps(t->m[c][0], a, d), e));
    }
}

/* One strand's vertices at ro's position base + v0 vertices, as lines */
HF__TARGET_AVX512 HF__INLINE void
hf__ribbon_lines_v16(const hf__rframe *fr, int P, const hf__rconst *K,
                     const hf__rstrand *str, const hf__rout *ro, size_t v0,
                     const __m256 *ov, const hf__lines *t)
{
    const int F = t->F;
    unsigned char *b = ro->base[HF__S_POS] + v0 * 4u * (size_t)F;
    const __m256 ws = _mm256_set1_ps(str->wscale);
    const __m512 uv = hf__uv16(str);
    int k, c;
    hf__page_ahead(b, 8u * (size_t)P * (size_t)F);
    for (k = 0; 8 * k < P; ++k, b += 64 * F) {
        const int o = 4 + 8 * k;
        __m256 L[3], R[3];
        __m512 S[5];
        hf__sides_v8(fr, o, _mm256_mul_ps(_mm256_loadu_ps(K->hw + 8 * k), ws),
                     ov, L, R);
        HF__UNROLL for (c = 0; c < 3; ++c) S[c] = hf__join16(L[c], R[c]);
        S[3] = hf__join16(_mm256_loadu_ps(fr->t[0] + o),
                          _mm256_loadu_ps(fr->t[1] + o));
        S[4] = hf__join16(_mm256_loadu_ps(fr->t[2] + o),
                          _mm256_loadu_ps(K->tt + 8 * k));
        hf__lines_out(b, S, uv, t);
    }
}

/* Sixteen points' x y z (floats 0-47 of q) as rows */
HF__TARGET_AVX512 HF__INLINE void hf__rows16(const float *q, __m512 *X,
                                             __m512 *Y, __m512 *Z)
{
    const __m512 a = _mm512_loadu_ps(q), b = _mm512_loadu_ps(q + 16),
                 c = _mm512_loadu_ps(q + 32);
    /* lanes from a and b by one permute, the last five (z: six) from c */
    *X = _mm512_mask_permutexvar_ps(
        _mm512_permutex2var_ps(a, _mm512_setr_epi32(0, 3, 6, 9, 12, 15, 18,
                                                    21, 24, 27, 30, 0, 0, 0,
                                                    0, 0), b),
        0xf800, _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 4, 7,
                                  10, 13), c);
    *Y = _mm512_mask_permutexvar_ps(
        _mm512_permutex2var_ps(a, _mm512_setr_epi32(1, 4, 7, 10, 13, 16, 19,
                                                    22, 25, 28, 31, 0, 0, 0,
                                                    0, 0), b),
        0xf800, _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 5, 8,
                                  11, 14), c);
    *Z = _mm512_mask_permutexvar_ps(
        _mm512_permutex2var_ps(a, _mm512_setr_epi32(2, 5, 8, 11, 14, 17, 20,
                                                    23, 26, 29, 0, 0, 0, 0,
                                                    0, 0), b),
        0xfc00, _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3, 6, 9,
                                  12, 15), c);
}

/* hf__enc8 at sixteen lanes: h's values in both halves */
typedef struct hf__enc16 {
    __m512 lo, scale, one;
    __m512i mask;
} hf__enc16;

HF__TARGET_AVX512 HF__INLINE void hf__enc16_init(hf__enc16 *e,
                                                const hf__enc8 *h)
{
    const __m256 m = _mm256_castsi256_ps(h->mask);
    e->lo = hf__join16(h->lo, h->lo);
    e->scale = hf__join16(h->scale, h->scale);
    e->one = hf__join16(h->one, h->one);
    e->mask = _mm512_castps_si512(hf__join16(m, m));
}

/* x << n in each 32-bit lane. The masked forms of this and of min, max,
   the conversion and the unpacks below: gcc's plain ones take an
   "undefined" operand, which g++ -O1 warns about. */
#define HF__SLL16(x, n) _mm512_maskz_slli_epi32(0xffff, x, n)

/* hf__encode_var_v8 at sixteen lanes */
HF__TARGET_AVX512 HF__INLINE __m512i hf__encode16(__m512 x,
                                                 const hf__enc16 *e)
{
    __m512 v = _mm512_maskz_max_ps(0xffff, x, e->lo);
    v = _mm512_mul_ps(_mm512_maskz_min_ps(0xffff, v, e->one), e->scale);
    return _mm512_and_si512(_mm512_maskz_cvtps_epi32(0xffff, v), e->mask);
}

/* One compact vertex at p from x's low 16 bytes: two 8-byte stores, the
   second over bytes 7..14 (the pad byte is never written) */
HF__INLINE void hf__c16_vertex(unsigned char *p, __m128i x)
{
    _mm_storel_epi64((__m128i *)(void *)p, x);
    _mm_storel_epi64((__m128i *)(void *)(p + 7), _mm_srli_si128(x, 7));
}

/* One side's compact vertices of sixteen points by 128-bit lane, from
   their dwords (d0, d1 the side's; s02, s13 the ones both sides share,
   unpacked): lane q of v[k] is point 4 q + k's (the unpacks work within
   lanes) */
HF__TARGET_AVX512 HF__INLINE void hf__c16_lanes16(__m512i d0, __m512i d1,
                                                 __m512i s02, __m512i s13,
                                                 __m512i *v)
{
    const __m512i a = _mm512_maskz_unpacklo_epi32(0xffff, d0, d1),
                  b = _mm512_maskz_unpackhi_epi32(0xffff, d0, d1);
    v[0] = _mm512_maskz_unpacklo_epi64(0xff, a, s02);
    v[1] = _mm512_maskz_unpackhi_epi64(0xff, a, s02);
    v[2] = _mm512_maskz_unpacklo_epi64(0xff, b, s13);
    v[3] = _mm512_maskz_unpackhi_epi64(0xff, b, s13);
}

/* hf__c16_put_v8 at sixteen points, all of them: one side's vertices
   (hf__c16_lanes16) at o, vertex i at o + i st2, two 8-byte stores a
   vertex, the pad byte never written */
HF__TARGET_AVX512 HF__INLINE void hf__c16_put16(unsigned char *o, size_t st2,
                                               const __m512i *v)
{
    int k;
    HF__UNROLL for (k = 0; k < 4; ++k) { /* lanes as immediates */
        unsigned char *p = o + (size_t)k * st2;
        hf__c16_vertex(p, _mm512_maskz_extracti32x4_epi32(0xf, v[k], 0));
        hf__c16_vertex(p + 4 * st2,
                       _mm512_maskz_extracti32x4_epi32(0xf, v[k], 1));
        hf__c16_vertex(p + 8 * st2,
                       _mm512_maskz_extracti32x4_epi32(0xf, v[k], 2));
        hf__c16_vertex(p + 12 * st2,
                       _mm512_maskz_extracti32x4_epi32(0xf, v[k], 3));
    }
}

/* Both sides' vertices of sixteen points with a stride of 16 bytes, so
   that points 2 j and 2 j + 1 (left, right, left, right) are the 64
   bytes at o + 64 j: eight stores masked by byte (the pad bytes never
   written) where hf__c16_put16 makes 64 stores of 8 bytes and 64
   extractions. l, r: hf__c16_lanes16 of the left and the right side. */
HF__TARGET_AVX512 HF__INLINE void hf__c16_put16_tight(unsigned char *o,
                                                     const __m512i *l,
                                                     const __m512i *r)
{
    const __mmask64 pad = 0x7fff7fff7fff7fffull;
    const __m512i lo = _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11),
                  hi = _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15);
    __m512i p[2][4]; /* p[h][k]: points 8 h + k and 8 h + 4 + k, each
                        left then right */
    int k, h;
    HF__UNROLL for (k = 0; k < 4; ++k) {
        p[0][k] = _mm512_permutex2var_epi64(l[k], lo, r[k]);
        p[1][k] = _mm512_permutex2var_epi64(l[k], hi, r[k]);
    }
    HF__UNROLL for (h = 0; h < 2; ++h) {
        unsigned char *q = o + 256 * h; /* point 8 h */
        HF__UNROLL for (k = 0; k < 4; k += 2) { /* points 8 h + k, + 1 */
            _mm512_mask_storeu_epi8(
                q + 32 * k, pad,
                _mm512_maskz_shuffle_i64x2(0xff, p[h][k], p[h][k + 1], 0x44));
            _mm512_mask_storeu_epi8(
                q + 32 * k + 128, pad,
                _mm512_maskz_shuffle_i64x2(0xff, p[h][k], p[h][k + 1], 0xee));
        }
    }
}

/* hf__c16_group_v8 at sixteen points from registers: the left and
   right positions (relative to the origin and scale), the tangents and
   t, the strand's u and v already encoded (eu shifted) */
HF__TARGET_AVX512 HF__INLINE void
hf__c16_group16(unsigned char *b, size_t st, const __m512 *L, const __m512 *R,
                const __m512 *T, __m512 tt, __m512i eu, __m512i ev,
                const hf__enc16 *enc)
{
    __m512i eL[3], eR[3], et[3], d2, d3, s02, s13, vl[4], vr[4];
    int c;
    HF__UNROLL for (c = 0; c < 3; ++c) {
        eL[c] = hf__encode16(L[c], &enc[0]);
        eR[c] = hf__encode16(R[c], &enc[0]);
        et[c] = hf__encode16(T[c], &enc[2]);
    }
    d2 = _mm512_or_si512(ev, HF__SLL16(hf__encode16(tt, &enc[1]), 16));
    d3 = _mm512_or_si512(_mm512_or_si512(et[0], HF__SLL16(et[1], 8)),
                         HF__SLL16(et[2], 16));
    s02 = _mm512_maskz_unpacklo_epi32(0xffff, d2, d3);
    s13 = _mm512_maskz_unpackhi_epi32(0xffff, d2, d3);
    hf__c16_lanes16(_mm512_or_si512(eL[0], HF__SLL16(eL[1], 16)),
                    _mm512_or_si512(eL[2], eu), s02, s13, vl);
    hf__c16_lanes16(_mm512_or_si512(eR[0], HF__SLL16(eR[1], 16)),
                    _mm512_or_si512(eR[2], eu), s02, s13, vr);
    if (st == 16) {
        hf__c16_put16_tight(b, vl, vr);
    } else {
        hf__c16_put16(b, 2 * st, vl);
        hf__c16_put16(b + st, 2 * st, vr);
    }
}

/* A strand's frame and vertices in registers, sixteen points a turn (P a
   multiple of 16): hf__frame_group_v8's operations on sixteen lanes (a
   512-bit square root or division costs what a 256-bit one does on Zen
   5), no frame rows written and read back. The vertices go out as lines
   (t; enc NULL) for hf__ribbons_lines_v16, or as compact vertices
   (enc: hf__enc16 of position, texcoord and tangent) for
   hf__ribbons_c16_v16. Returns 0, with vertices perhaps written,
   where a point is not finite or a lane is left to the reference: the
   caller writes the strand again from hf__frame_strand_v8's rows. */
HF__TARGET_AVX512 HF__INLINE int
hf__ribbon_fused_v16(const float *pts, int P, int ortho, const __m512 *e,
                     const hf__rconst *K, const hf__rstrand *str,
                     const hf__rout *ro, size_t v0, const __m512 *ov,
                     const hf__lines *t, const hf__enc16 *enc)
{
    const int F = enc ? 0 : t->F;
    const size_t st = ro->stride[HF__S_POS];
    const __m512 one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps(),
                 tiny = _mm512_set1_ps(1e-30f),
                 big = _mm512_set1_ps(3.40282347e+38f),
                 side_sin2 = _mm512_set1_ps(HF__SIDE_SIN2),
                 ws = _mm512_set1_ps(str->wscale);
    __m512 uv = zero;
    __m512i eu = _mm512_setzero_si512(), ev = eu;
    unsigned char *b = ro->base[HF__S_POS] +
                       (enc ? v0 * st : v0 * 4u * (size_t)F);
    __m512 cx, cy, cz, nx, ny, nz, px, py, pz;
    int g, c, h;
    if (enc) { /* u and v are the strand's: encoded once */
        eu = HF__SLL16(hf__encode16(_mm512_set1_ps(str->uv[0]), &enc[1]),
                       16);
        ev = hf__encode16(_mm512_set1_ps(str->uv[1]), &enc[1]);
    } else {
        uv = hf__uv16(str);
        hf__page_ahead(b, 8u * (size_t)P * (size_t)F);
    }
    hf__rows16(pts, &cx, &cy, &cz);
    px = _mm512_set1_ps(pts[0]); /* the root repeats before it */
    py = _mm512_set1_ps(pts[1]);
    pz = _mm512_set1_ps(pts[2]);
    for (g = 0; 16 * g < P; ++g) {
        const __m512 tt = _mm512_loadu_ps(K->tt + 16 * g);
        __m512 T[3], L[3], R[3], S[5], acc, dx, dy, dz, vx, vy, vz, l2, sx,
            sy, sz, c2, vv, inv, inv2, w;
        __mmask16 ok, ok2;
        if (16 * g + 16 < P) {
            hf__rows16(pts + 48 * (g + 1), &nx, &ny, &nz);
        } else { /* the tip repeats after it */
            nx = _mm512_set1_ps(pts[3 * (P - 1)]);
            ny = _mm512_set1_ps(pts[3 * (P - 1) + 1]);
            nz = _mm512_set1_ps(pts[3 * (P - 1) + 2]);
        }
        acc = _mm512_add_ps(_mm512_mul_ps(cx, zero),
                            _mm512_add_ps(_mm512_mul_ps(cy, zero),
                                          _mm512_mul_ps(cz, zero)));
        if (_mm512_cmp_ps_mask(acc, zero, _CMP_EQ_OQ) != 0xffff) return 0;
#define HF__D(c, n, p)                                                         \
    _mm512_sub_ps(                                                             \
        _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(                         \
            0xffff, _mm512_castps_si512(n), _mm512_castps_si512(c), 1)),       \
        _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(                         \
            0xffff, _mm512_castps_si512(c), _mm512_castps_si512(p), 15)))
        dx = HF__D(cx, nx, px);
        dy = HF__D(cy, ny, py);
        dz = HF__D(cz, nz, pz);
#undef HF__D
        vx = ortho ? e[0] : _mm512_sub_ps(e[0], cx);
        vy = ortho ? e[1] : _mm512_sub_ps(e[1], cy);
        vz = ortho ? e[2] : _mm512_sub_ps(e[2], cz);
        l2 = _mm512_add_ps(
            _mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)),
            _mm512_mul_ps(dz, dz));
        ok = _mm512_cmp_ps_mask(l2, tiny, _CMP_GT_OQ) &
             _mm512_cmp_ps_mask(l2, big, _CMP_LE_OQ);
        /* 1 where undefined: no division by zero for any lane */
        inv = _mm512_div_ps(
            one, _mm512_maskz_sqrt_ps(0xffff,
                                      _mm512_mask_blend_ps(ok, one, l2)));
        T[0] = _mm512_mul_ps(dx, inv);
        T[1] = _mm512_mul_ps(dy, inv);
        T[2] = _mm512_mul_ps(dz, inv);
        sx = _mm512_sub_ps(_mm512_mul_ps(dy, vz), _mm512_mul_ps(dz, vy));
        sy = _mm512_sub_ps(_mm512_mul_ps(dz, vx), _mm512_mul_ps(dx, vz));
        sz = _mm512_sub_ps(_mm512_mul_ps(dx, vy), _mm512_mul_ps(dy, vx));
        c2 = _mm512_add_ps(
            _mm512_add_ps(_mm512_mul_ps(sx, sx), _mm512_mul_ps(sy, sy)),
            _mm512_mul_ps(sz, sz));
        vv = _mm512_add_ps(
            _mm512_add_ps(_mm512_mul_ps(vx, vx), _mm512_mul_ps(vy, vy)),
            _mm512_mul_ps(vz, vz));
        ok2 = _mm512_cmp_ps_mask(
                  c2, _mm512_mul_ps(_mm512_mul_ps(side_sin2, vv), l2),
                  _CMP_GT_OQ) &
              _mm512_cmp_ps_mask(c2, tiny, _CMP_GT_OQ) &
              _mm512_cmp_ps_mask(c2, big, _CMP_LE_OQ);
        if ((ok & ok2) != 0xffff) return 0;
        inv2 = _mm512_div_ps(
            one, _mm512_maskz_sqrt_ps(0xffff,
                                      _mm512_mask_blend_ps(ok2, one, c2)));
        /* L = p - s w, R = p + s w, relative to the origin and scale, as
           hf__ribbon_group_v8 */
        w = _mm512_mul_ps(_mm512_loadu_ps(K->hw + 16 * g), ws);
        {
            const __m512 cc[3] = {cx, cy, cz}, ss[3] = {sx, sy, sz};
            HF__UNROLL for (c = 0; c < 3; ++c) {
                const __m512 sw = _mm512_mul_ps(_mm512_mul_ps(ss[c], inv2), w);
                L[c] = _mm512_mul_ps(
                    _mm512_sub_ps(_mm512_sub_ps(cc[c], sw), ov[1 + c]), ov[0]);
                R[c] = _mm512_mul_ps(
                    _mm512_sub_ps(_mm512_add_ps(cc[c], sw), ov[1 + c]), ov[0]);
            }
        }
        if (enc) {
            hf__c16_group16(b, st, L, R, T, tt, eu, ev, enc);
            b += 32 * st;
        } else for (h = 0; h < 2; ++h, b += 64 * F) {
#define HF__HALF(a, b2)                                                        \
    (h ? _mm512_maskz_shuffle_f32x4(0xffff, a, b2, 0xee)                       \
       : _mm512_maskz_shuffle_f32x4(0xffff, a, b2, 0x44))
            S[0] = HF__HALF(L[0], R[0]);
            S[1] = HF__HALF(L[1], R[1]);
            S[2] = HF__HALF(L[2], R[2]);
            S[3] = HF__HALF(T[0], T[1]);
            S[4] = HF__HALF(T[2], tt);
#undef HF__HALF
            hf__lines_out(b, S, uv, t);
        }
        px = cx;
        py = cy;
        pz = cz;
        cx = nx;
        cy = ny;
        cz = nz;
    }
    return 1;
}
#undef HF__SLL16

/* Whether a streamed call goes out as lines (above): the stage's vertex
   (hf__ribbon_stage: block bytes, every stream inside it, dst0 the first
   byte of vertex 0) is the float run alone, 4 F bytes, P a multiple of 8
   (so every strand's block keeps the first's alignment) and strand
   `first`'s block starts a line */
HF__PRIVATE int hf__lines_fit(const hf__rout *ro, int P,
                              const unsigned char *dst0, size_t block,
                              int first, int out_first)
{
    return ro->run && block == (ro->run == 3 ? 36u : 24u) && P % 8 == 0 &&
           (((uintptr_t)dst0 +
             (size_t)(first - out_first) * 2u * (size_t)P * block) &
            63u) == 0;
}

/* The eye (hf__frame_eye_v8) and the output's scale and origin
   (hf__rout_vec_v8) as vectors of eight lanes and of sixteen, the
   same in every lane */
HF__TARGET_AVX512 HF__INLINE void
hf__vecs16_init(const hf_ribbon_params *params, const hf__rout *ro, __m256 *e,
                __m256 *ov, __m512 *e16, __m512 *ov16)
{
    int c;
    hf__frame_eye_v8(params, e);
    hf__rout_vec_v8(ro, ov);
    HF__UNROLL for (c = 0; c < 4; ++c) {
        if (c < 3) e16[c] = hf__join16(e[c], e[c]);
        ov16[c] = hf__join16(ov[c], ov[c]);
    }
}

/* Strand s with P a multiple of 16: its frame and vertices in registers
   (hf__ribbon_fused_v16), or, where that leaves the strand, framed by
   hf__frame_strand_v8 into fr and written from the rows; as lines (t)
   or as compact vertices (enc16 and enc, the AVX2 writer's). e, ov: the
   eye and output vectors at eight lanes, e16, ov16 at sixteen. */
HF__TARGET_AVX512 HF__INLINE void
hf__ribbon_strand16(const hf_ribbon_strands *sv, int s, int end,
                    const hf_ribbon_params *params, const hf__rconst *K,
                    const hf__rout *ro, int out_first, const __m256 *e,
                    const __m256 *ov, const __m512 *e16, const __m512 *ov16,
                    hf__rframe *fr, const hf__lines *t,
                    const hf__enc16 *enc16, const hf__enc8 *enc)
{
    const int P = params->points_per_strand,
              ortho = params->orthographic != 0;
    const size_t v0 = (size_t)(s - out_first) * (size_t)P * 2u;
    hf__rstrand str;
    float wsc;
    str.wscale = 1.0f;
    hf__rstrand_fill(sv, s, K->wcap, &str);
    if (hf__ribbon_fused_v16(sv->points + (size_t)s * (size_t)P * 3u, P, ortho,
                             e16, K, &str, ro, v0, ov16, t, enc16))
        return;
    hf__frame_at_v8(sv, s, end, P, ortho, e, params, fr, &wsc);
    str.wscale = wsc;
    hf__rstrand_fill(sv, s, K->wcap, &str);
    if (enc)
        hf__ribbon_write_c16_v8_in(fr, P, K, &str, ro, v0, ov, enc);
    else
        hf__ribbon_lines_v16(fr, P, K, &str, ro, v0, ov, t);
}

/* The strands of a streamed call as lines (hf__lines_fit). P a multiple
   of 16: each strand's frame in registers (hf__ribbon_fused_v16), a
   strand it leaves framed by hf__frame_strand_v8 and written from the
   rows. Else hf__ribbons_loop_v8's plain path (each frame a strand
   ahead, in fr and fr2 by turns) with the lines for the writer. */
HF__TARGET_AVX512 HF__PRIVATE void
hf__ribbons_lines_v16(const hf_ribbon_strands *sv, int first, int count,
                      const hf_ribbon_params *params, const hf__rconst *K,
                      const hf__rout *ro, int out_first, hf__rframe *fr,
                      hf__rframe *fr2)
{
    const int P = params->points_per_strand,
              ortho = params->orthographic != 0, end = first + count;
    const hf_ribbon_strands svl = *sv; /* no reload after every store */
    hf__rframe *F[2];
    float wsc[2];
    __m256 e[3], ov[4];
    __m512 e16[3], ov16[4];
    hf__lines t;
    int s;
    hf__lines_init(&t, ro->run == 3 ? 9 : 6);
    hf__vecs16_init(params, ro, e, ov, e16, ov16);
    F[0] = fr;
    F[1] = fr2;
    if (P % 16 == 0) {
        for (s = first; s < end; ++s)
            hf__ribbon_strand16(&svl, s, end, params, K, ro, out_first, e, ov,
                                e16, ov16, fr, &t, NULL, NULL);
    } else {
        hf__frame_at_v8(&svl, first, end, P, ortho, e, params, F[0], &wsc[0]);
        for (s = first; s < end; ++s) {
            const int j = (s - first) & 1;
            hf__rstrand str;
            hf__frame_at_v8(&svl, s + 1, end, P, ortho, e, params, F[j ^ 1],
                            &wsc[j ^ 1]);
            str.wscale = wsc[j];
            hf__rstrand_fill(&svl, s, K->wcap, &str);
            hf__ribbon_lines_v16(F[j], P, K, &str, ro,
                                 (size_t)(s - out_first) * (size_t)P * 2u, ov,
                                 &t);
        }
    }
    _mm_sfence(); /* streamed stores visible before we return */
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
}

/* The compact vertex (hf__rout c16) of a call at AVX-512, P a multiple
   of 16: each strand's frame and vertices in registers
   (hf__ribbon_fused_v16); a strand it leaves, framed by
   hf__frame_strand_v8 and written from the rows by the AVX2 writer. */
HF__TARGET_AVX512 HF__PRIVATE void
hf__ribbons_c16_v16(const hf_ribbon_strands *sv, int first, int count,
                    const hf_ribbon_params *params, const hf__rconst *K,
                    const hf__rout *ro, int out_first, hf__rframe *fr)
{
    static const int q[3] = {HF__S_POS, HF__S_TEX, HF__S_TAN};
    const int end = first + count;
    const hf_ribbon_strands svl = *sv; /* no reload after every store */
    __m256 e[3], ov[4];
    __m512 e16[3], ov16[4];
    hf__enc8 enc[3];
    hf__enc16 enc16[3];
    int s, c;
    hf__vecs16_init(params, ro, e, ov, e16, ov16);
    HF__UNROLL for (c = 0; c < 3; ++c) {
        hf__enc8_init(&enc[c], ro->fmt[q[c]]);
        hf__enc16_init(&enc16[c], &enc[c]);
    }
    for (s = first; s < end; ++s)
        hf__ribbon_strand16(&svl, s, end, params, K, ro, out_first, e, ov,
                            e16, ov16, fr, NULL, enc16, enc);
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
}
#endif

/* ---- 8.7 hf_ribbons: the call ------------------------------------------- */

/* floor(x / y) for y > 0 */
HF__PRIVATE long long hf__floordiv(long long x, long long y)
{
    return x >= 0 ? x / y : -((-x + y - 1) / y);
}

/* x^-1 modulo m, for x and m > 0 coprime (extended Euclid; 0 for m 1) */
HF__PRIVATE long long hf__inverse_mod(long long x, long long m)
{
    long long r0 = m, r1 = x % m, s0 = 0, s1 = 1;
    while (r1) {
        const long long q = r0 / r1, r = r0 - q * r1, s = s0 - q * s1;
        r0 = r1;
        r1 = r;
        s0 = s1;
        s1 = s;
    }
    return m == 1 ? 0 : (s0 % m + m) % m;
}

/* Whether vertex v of one stream (at a + v sa, ea bytes) and vertex w
   != v of another (b + w sb, eb bytes) share a byte, for v and w among
   the n vertices from v0 this call writes. Such streams would make the
   bytes depend on the order of the stores (the level, the split), so
   they are refused; streams that share bytes inside one vertex are
   allowed (the later stream's bytes win at every level). They meet
   where y = a0 - b0 + v sa - w sb lies in (-ea, eb), a multiple of g =
   gcd(sa, sb) away from a0 - b0: for each such y (at most ea + eb of
   them) the pairs (v, w) form one family (v + t pa, w + t pb), pa =
   sb / g, pb = sa / g, whose members in [0, n) are a range of t; v - w
   changes along it unless the strides are equal. Equal strides, the
   usual interleaved vertex, take one division: v - w alone decides.
   Strides are positive (a stream's own, or its element's size). */
HF__PRIVATE int hf__streams_cross(uintptr_t a, size_t sa, size_t ea,
                                  uintptr_t b, size_t sb, size_t eb,
                                  size_t v0, size_t n)
{
    const uintptr_t a0 = a + v0 * sa, b0 = b + v0 * sb;
    const long long end = (long long)n; /* vertices counted from v0 */
    const long long d = a0 >= b0 ? (long long)(a0 - b0)
                                 : -(long long)(b0 - a0);
    long long g = (long long)sa, h = (long long)sb, pa, pb, inv, y;
    if (n == 0 || a0 + (n - 1) * sa + ea <= b0 ||
        b0 + (n - 1) * sb + eb <= a0)
        return 0; /* the spans do not meet */
    if (sa == sb) { /* one stride: v - w = k != 0 with d + k sa in
                       (-ea, eb), the least such k tried */
        const long long s = (long long)sa, m = end - 1;
        long long k = hf__floordiv(-(long long)ea - d, s) + 1;
        if (k < -m) k = -m;
        if (k == 0) k = 1;
        return k <= m && d + k * s < (long long)eb;
    }
    while (h) { /* g = gcd(sa, sb) */
        const long long t = g % h;
        g = h;
        h = t;
    }
    pa = (long long)sb / g;
    pb = (long long)sa / g;
    inv = hf__inverse_mod(pb, pa);
    /* the first y above -ea that is d modulo g */
    y = -(long long)ea + 1;
    y += ((d - y) % g + g) % g;
    for (; y < (long long)eb; y += g) {
        /* v pb - w pa = r: v = vs + t pa, w = ws + t pb */
        const long long r = (y - d) / g;
        const long long vs = ((r % pa + pa) % pa) * inv % pa;
        const long long ws = (vs * pb - r) / pa;
        /* t >= 0 keeps v >= 0 (vs < pa); the rest bound t by floors */
        const long long lo = ws >= 0 ? 0 : -hf__floordiv(ws, pb),
                        hv = hf__floordiv(end - 1 - vs, pa),
                        hw = hf__floordiv(end - 1 - ws, pb),
                        hi = hv < hw ? hv : hw;
        if (lo > hi) continue;
        if (pa == pb ? vs != ws : hi > lo || vs + lo * pa != ws + lo * pb)
            return 1;
    }
    return 0;
}

/* A call of hf_ribbons, checked and laid out, for its whole-call loops */
typedef struct hf__rcall {
    const hf_ribbon_strands *sv; /* the inputs of the streams written */
    const hf_ribbon_params *params;
    const hf__rconst *K;
    const hf__rout *ro;
    int first, count, out_first, P;
    hf__rframe *fr, *fr2; /* a strand's frame rows, a second one */
    int stage;            /* streamed through stage_buf: */
    float *stage_buf;     /* (in fr2's room) */
    unsigned char *dst0;  /* the first byte of vertex 0 */
    size_t block;         /* a vertex's bytes in the stage */
    const struct hf__frame_kernels *frame; /* the call's level's */
    const struct hf__write_kernels *write;
    const struct hf__stream_kernels *stream;
} hf__rcall;

/* The whole-call loops, one a width, each returning 0 for a call it
   leaves to the next (hf__ribbons_widths). */
#if HF__AVX512
/* sixteen lanes: a streamed call that fits lines (hf__lines_fit), or
   the compact vertex with P a multiple of 16 */
HF__PRIVATE int hf__ribbons_v16(const hf__rcall *c)
{
    if (c->stage &&
        hf__lines_fit(c->ro, c->P, c->dst0, c->block, c->first, c->out_first)) {
        hf__ribbons_lines_v16(c->sv, c->first, c->count, c->params, c->K, c->ro,
                              c->out_first, c->fr, c->fr2);
        return 1;
    }
    if (!c->stage && c->ro->c16 && c->P % 16 == 0) {
        hf__ribbons_c16_v16(c->sv, c->first, c->count, c->params, c->K, c->ro,
                            c->out_first, c->fr);
        return 1;
    }
    return 0;
}
#endif

#if HF__AVX2
/* eight lanes: the layouts with a float run or windows */
HF__PRIVATE int hf__ribbons_v8(const hf__rcall *c)
{
    if (!c->ro->run && !c->ro->nw) return 0;
    hf__ribbons_run_v8(c->sv, c->first, c->count, c->params, c->K, c->ro,
                       c->out_first, c->fr, c->stage ? NULL : c->fr2,
                       c->stage ? c->stage_buf : NULL, c->dst0, c->block);
    return 1;
}
#endif

/* four lanes and one: a strand at a time, its frame and its vertices by
   the call's kernels (hf__strand_frame, hf__ribbon_write), through the
   stage in a streamed call */
HF__PRIVATE int hf__ribbons_each(const hf__rcall *c)
{
    /* the inputs in locals, read once: the kernels are calls whose
       stores may alias anything reached through a pointer */
    const hf_ribbon_strands sv = *c->sv;
    const hf_ribbon_params *params = c->params;
    const hf__frame_kernels *kf = c->frame;
    const hf__write_kernels *kw = c->write;
    const int P = c->P, out_first = c->out_first, stage = c->stage;
    hf__rframe *const fr = c->fr;
    hf__rout so;
    int s;
    if (stage) hf__rout_staged(c->ro, c->stage_buf, c->dst0, &so);
    for (s = c->first; s < c->first + c->count; ++s) {
        const float *pts = sv.points + (size_t)s * (size_t)P * 3u;
        const size_t v0 = (size_t)(s - out_first) * (size_t)P * 2u;
        hf__rstrand str;
        hf__strand_frame(pts, P, params, fr, &str.wscale, kf);
        hf__rstrand_fill(&sv, s, c->K->wcap, &str);
        if (stage) {
            /* the strand's vertices into the stage (in L1), then out to
               its block with streaming stores */
            hf__ribbon_write(fr, P, c->K, &str, &so, 0, kw);
            c->stream->copy(c->dst0 + v0 * c->block, c->stage_buf,
                            2u * (size_t)P * c->block);
        } else {
            hf__ribbon_write(fr, P, c->K, &str, c->ro, v0, kw);
        }
    }
#if HF__SSE
    if (stage) _mm_sfence(); /* streamed stores visible before we return */
#endif
    return 1;
}

typedef struct hf__ribbons_kernels {
    hf__isa isa;
    int (*call)(const hf__rcall *);
} hf__ribbons_kernels;

static const hf__ribbons_kernels hf__ribbons_widths[] = {
#if HF__AVX512
    {{HF__ISA_V16}, hf__ribbons_v16},
#endif
#if HF__AVX2
    {{HF__ISA_V8}, hf__ribbons_v8},
#endif
#if HF__V4
    {{HF__ISA_V4}, hf__ribbons_each},
#endif
    {{HF__ISA_V1}, hf__ribbons_each}};

/* hf_ribbons, with streaming stores by size (nontemporal 0) chosen as
   for `sized` strands: the call's count, or a fur's drawn strands */
HF__PRIVATE hf_result hf__ribbons(const hf_ribbon_strands *strands,
                                  int first, int count,
                                  const hf_ribbon_params *view,
                                  const hf_ribbon_output *out, int sized)
{
    hf__rconst K;
    hf__rout ro;
    hf_ribbon_params prm;
    const hf_ribbon_params *params = &prm;
    hf_ribbon_strands sv;
    const hf_stream *streams[5];
    /* a strand's frame rows from a page boundary, then a second frame
       (the AVX2 run's plain path, the AVX-512 lines) or the stage (a
       streamed call) */
    float room[HF__RIBBON_ROOM];
    hf__rframe *const fr = hf__frame_in_page(room), *const fr2 = fr + 1;
    float *stage_buf = NULL;
    unsigned char *dst0 = NULL;
    size_t block = 0, elem[5];
    size_t nv, call_v0; /* vertices a strand; the call's first vertex */
    int k, P, stage;
    hf_result r = hf__ribbon_check(strands, first, count, view, &prm);
    if (r != HF_OK) return r;
    if (!out) return HF_ERROR_NULL_POINTER;
    nv = 2u * (size_t)prm.points_per_strand;
    call_v0 = (size_t)(first - prm.out_first) * nv;
    streams[HF__S_POS] = &out->position;
    streams[HF__S_TAN] = &out->tangent;
    streams[HF__S_TEX] = &out->texcoord;
    streams[HF__S_COL] = &out->color;
    streams[HF__S_C3D] = &out->color3d;
    for (k = 0; k < 5; ++k) {
        const int size = hf_format_bytes(streams[k]->format);
        if (size == 0) return HF_ERROR_BAD_FORMAT;
        /* a stride must hold the element: no vertex overwrites another */
        if (streams[k]->stride < 0 ||
            (streams[k]->stride > 0 &&
             streams[k]->stride < size * hf__stream_nc[k]))
            return HF_ERROR_BAD_STRIDE;
        elem[k] = (size_t)size * (size_t)hf__stream_nc[k];
        ro.base[k] = (unsigned char *)streams[k]->data;
        ro.stride[k] =
            streams[k]->stride ? (size_t)streams[k]->stride : elem[k];
        ro.fmt[k] = streams[k]->format;
    }
    {
        int m;
        for (k = 0; k < 5; ++k)
            for (m = k + 1; m < 5; ++m)
                if (ro.base[k] && ro.base[m] &&
                    hf__streams_cross((uintptr_t)ro.base[k], ro.stride[k],
                                      elem[k], (uintptr_t)ro.base[m],
                                      ro.stride[m], elem[m], call_v0,
                                      (size_t)count * nv))
                    return HF_ERROR_BAD_STRIDE;
    }
    HF__UNROLL for (k = 0; k < 3; ++k) {
        if (!hf__finitef(out->position_origin[k])) return HF_ERROR_NON_FINITE;
        if (out->position_origin[k] > HF_MAX_ABS ||
            out->position_origin[k] < -HF_MAX_ABS)
            return HF_ERROR_BAD_PARAMETER;
        ro.origin[k] = out->position_origin[k];
    }
    if (!hf__finitef(out->position_scale)) return HF_ERROR_NON_FINITE;
    /* bounded both ways so 1 / scale is finite and positive */
    if (out->position_scale != 0.0f &&
        !(out->position_scale >= 1.0f / HF_MAX_ABS &&
          out->position_scale <= HF_MAX_ABS))
        return HF_ERROR_BAD_PARAMETER;
    ro.inv_scale =
        out->position_scale != 0.0f ? 1.0f / out->position_scale : 1.0f;
    hf__rout_layout(&ro); /* the stage keeps the layout: the same */

    P = params->points_per_strand;
    hf__rconst_init(&K, params);

    stage = hf__streaming(params->nontemporal,
                          (size_t)sized * 2u * (size_t)P * ro.tile,
                          HF_STREAM_MIN_VERTEX_BYTES)
                ? hf__ribbon_stage(&ro, P, call_v0, &block, &dst0)
                : 0;
    if (stage)
        stage_buf =
            hf__stage_in_page((float *)(void *)fr2, 2u * (size_t)P * block);
    sv = *strands;
    /* the inputs of the streams not written are not read */
    if (!ro.base[HF__S_TEX]) sv.root_uv = NULL;
    if (!ro.base[HF__S_COL]) sv.color = NULL;
    if (!ro.base[HF__S_C3D]) sv.color3d_x = NULL;
    {
        /* the call, with its kernels resolved once: the frames, writers
           and copies out of the stage, and the whole-call loop */
        const hf__rcall c = {
            &sv, params, &K, &ro, first, count, params->out_first, P, fr, fr2,
            stage, stage_buf, dst0, block,
            hf__kernels_for(hf__frame_widths, params->simd),
            hf__kernels_for(hf__write_widths, params->simd),
            hf__kernels_for(hf__stream_widths, params->simd)};
        const hf__ribbons_kernels *kc =
            hf__kernels_for(hf__ribbons_widths, params->simd);
        while (!kc->call(&c)) ++kc;
    }
    return HF_OK;
}

HFDEF hf_result hf_ribbons(const hf_ribbon_strands *strands, int first,
                           int count, const hf_ribbon_params *view,
                           const hf_ribbon_output *out)
{
    return hf__ribbons(strands, first, count, view, out, count);
}

/* ---- 8.8 GPU points (hf_ribbon_points) ---------------------------------- */

/* GPU points of one strand: (x, y, z, hw[j] * ws) for point j; nt asks
   for streaming stores (the reference makes none). */
HF__PRIVATE void hf__points_strand_v1(const float *p, const float *hw, float ws,
                                      float *o, int P, int nt)
{
    int j;
    (void)nt;
    for (j = 0; j < P; ++j) {
        o[4 * j] = p[3 * j];
        o[4 * j + 1] = p[3 * j + 1];
        o[4 * j + 2] = p[3 * j + 2];
        o[4 * j + 3] = hw[j] * ws;
    }
}

#if HF__SSE
/* A point a vector: xyz loaded with the next point's x,
   which the width replaces; the last point loads from one float earlier
   and shifts, so nothing past the strand is read and every point is
   written here (a scalar store into a line being streamed would stall).
   Streaming stores where asked and aligned. P >= 2. */
HF__INLINE void hf__point_put_v4(float *o, __m128 v, float w, int nt)
{
    const __m128 xyz = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
    v = _mm_or_ps(_mm_and_ps(v, xyz), _mm_set_ps(w, 0.0f, 0.0f, 0.0f));
    if (nt)
        _mm_stream_ps(o, v);
    else
        _mm_storeu_ps(o, v);
}

HF__PRIVATE void hf__points_strand_v4(const float *p, const float *hw, float ws,
                                      float *o, int P, int nt)
{
    int j;
    nt = nt && ((uintptr_t)o & 15u) == 0;
    if (nt) hf__page_ahead(o, 16u * (size_t)P);
    for (j = 0; j + 1 < P; ++j)
        hf__point_put_v4(o + 4 * j, _mm_loadu_ps(p + 3 * j), hw[j] * ws, nt);
    if (j < P) { /* the last: (z', x, y, z) to (x, y, z, z') */
        const __m128 v = _mm_loadu_ps(p + 3 * j - 1);
        hf__point_put_v4(o + 4 * j,
                         _mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 3, 2, 1)),
                         hw[j] * ws, nt);
    }
}
#endif

#if HF__NEON
/* hf__points_strand_v4 on ARM64 (no streaming stores there). */
HF__PRIVATE void hf__points_strand_v4(const float *p, const float *hw, float ws,
                                      float *o, int P, int nt)
{
    int j;
    (void)nt;
    for (j = 0; j + 1 < P; ++j)
        vst1q_f32(o + 4 * j,
                  vsetq_lane_f32(hw[j] * ws, vld1q_f32(p + 3 * j), 3));
    if (j < P) { /* the last: (z', x, y, z) to (x, y, z, z') */
        const float32x4_t v = vld1q_f32(p + 3 * j - 1);
        vst1q_f32(o + 4 * j, vsetq_lane_f32(hw[j] * ws, vextq_f32(v, v, 1), 3));
    }
}
#endif

#if HF__AVX2
/* The widths of two points a vector, as the AVX2 points kernel blends
   them in: (0, 0, 0, hw[j], 0, 0, 0, hw[j + 1]) at pair j / 2 (j even),
   and at pair (P + 1) / 2 the last two points'. Built once a call. */
typedef struct hf__pair_widths {
    float v[(HF_MAX_POINTS / 2 + 2) * 8];
} hf__pair_widths;

HF__PRIVATE void hf__pair_widths_init(hf__pair_widths *pw, const float *hw,
                                      int P)
{
    float *last = pw->v + 8 * ((P + 1) / 2);
    int j;
    HF_MEMSET(pw->v, 0, sizeof(float) * 8u * (size_t)(P / 2 + 2));
    for (j = 0; j + 1 < P; j += 2) {
        pw->v[4 * j + 3] = hw[j];
        pw->v[4 * j + 7] = hw[j + 1];
    }
    last[3] = hw[P - 2];
    last[7] = hw[P - 1];
}

/* One strand's GPU points, two a vector: eight floats from point j
   (x0 .. y2) spread to x0 y0 z0 . x1 y1 z1 ., the widths blended in; the
   last one or two points from the strand's last eight floats, so nothing
   past the strand is read and no point is written twice. The finiteness
   test rides on the same vectors (x * 0 is NaN for NaN or infinity):
   returns 0 when a point is not finite, with the strand written from
   its points as they are (the caller writes it again, collapsed). P >= 3. */
HF__TARGET_AVX2 HF__INLINE int
hf__points_strand_v8_in(const float *p, const hf__pair_widths *pw, float ws,
                        float *o, int P, int mode)
{
    const __m256i spread = _mm256_setr_epi32(0, 1, 2, 0, 3, 4, 5, 0);
    const __m256i spread_last = _mm256_setr_epi32(2, 3, 4, 0, 5, 6, 7, 0);
    const __m256 W = _mm256_set1_ps(ws), zero = _mm256_setzero_ps();
    __m256 acc = zero, q;
    int j, ok;
    for (j = 0; 3 * j + 8 <= 3 * P; j += 2) {
        q = _mm256_blend_ps(
            _mm256_permutevar8x32_ps(_mm256_loadu_ps(p + 3 * j), spread),
            _mm256_mul_ps(_mm256_loadu_ps(pw->v + 4 * j), W), 0x88);
        acc = _mm256_add_ps(acc, _mm256_mul_ps(q, zero));
        hf__put_v8(o + 4 * j, q, mode);
    }
    if (j < P) { /* points P - 2 and P - 1: one or both still to write */
        q = _mm256_blend_ps(
            _mm256_permutevar8x32_ps(_mm256_loadu_ps(p + 3 * P - 8),
                                     spread_last),
            _mm256_mul_ps(_mm256_loadu_ps(pw->v + 8 * ((P + 1) / 2)), W),
            0x88);
        acc = _mm256_add_ps(acc, _mm256_mul_ps(q, zero));
        if (j == P - 2) /* P even: at o + 32 (P / 2 - 1) bytes */
            hf__put_v8(o + 4 * j, q, mode);
        else if (mode)
            _mm_stream_ps(o + 4 * j, _mm256_extractf128_ps(q, 1));
        else
            _mm_storeu_ps(o + 4 * j, _mm256_extractf128_ps(q, 1));
    }
    ok = _mm256_movemask_ps(_mm256_cmp_ps(acc, zero, _CMP_EQ_OQ)) == 0xff;
    return ok;
}

/* the strand above as a call (mode: hf__stream_mode's) */
HF__TARGET_AVX2 HF__PRIVATE int hf__points_strand_v8(const float *p,
                                                     const hf__pair_widths *pw,
                                                     float ws, float *o, int P,
                                                     int nt)
{
    const int ok =
        hf__points_strand_v8_in(p, pw, ws, o, P, hf__stream_mode(nt, o, 31u));
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
    return ok;
}
#endif

/* What a points call works out once: the half widths of the points and
   the kernel. */
typedef struct hf__points_kit {
    float hw[HF_MAX_POINTS];
#if HF__AVX2
    hf__pair_widths pw;
#endif
    float wcap; /* the cap of the strand multiplier (hf__half_widths) */
    int P, level, nt;
    int compact;           /* HF_POINT_COMPACT: */
    float origin[3], inv;  /* its box: (p - origin) * inv */
    /* the level's kernels (hf__kernels_for): points, compact encoders */
    const struct hf__points_kernels *kernels;
    const struct hf__encode_kernels *encode;
} hf__points_kit;

#if HF__AVX2
/* A strand at o that is not finite, written again collapsed (every point
   at the origin, width 0) by the AVX2 points kernel, after the streamed
   stores already made; rare, so a call of its own. */
HF__PRIVATE void hf__points_collapse_v8(const hf__points_kit *k, float *o)
{
    if (k->nt) _mm_sfence();
    hf__points_strand_v8(hf__zero_points, &k->pw, 0.0f, o, k->P, k->nt);
}

/* The strands of a points call at AVX2 in one target function, the
   strand inlined: a call each, with its stream mode and vzeroupper, took
   two fifths of the instructions. With P even every strand's 16 P bytes
   keep the first's alignment, so the mode is one for the call and a
   constant in the loop; with P odd it alternates, found per strand. */
HF__TARGET_AVX2 HF__INLINE void
hf__points_loop_v8(const hf__points_kit *k, const hf_ribbon_strands *strands,
                   const float *pts, int pts_first, int first, int count,
                   int out_first, float *out4, int mode)
{
    const int P = k->P;
    /* read once: the stores may alias k and strands */
    const float wcap = k->wcap, *wd = strands->width;
    int s;
    for (s = first; s < first + count; ++s) {
        const float *p = pts + (size_t)(s - pts_first) * (size_t)P * 3u;
        float *o = out4 + (size_t)(s - out_first) * (size_t)P * 4u;
        const int m = mode >= 0 ? mode : hf__stream_mode(k->nt, o, 31u);
        if (m) hf__page_ahead(o, 16u * (size_t)P);
        if (!hf__points_strand_v8_in(p, &k->pw, hf__width_at(wd, s, wcap), o, P,
                                     m)) {
            _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
            hf__points_collapse_v8(k, o);
        }
    }
}

HF__TARGET_AVX2 HF__PRIVATE void
hf__points_pairs_v8(const hf__points_kit *k, const hf_ribbon_strands *strands,
                    const float *pts, int pts_first, int first, int count,
                    int out_first, float *out4)
{
    const int mode = hf__stream_mode(
        k->nt, out4 + (size_t)(first - out_first) * (size_t)k->P * 4u, 31u);
    if (k->P % 2)
        hf__points_loop_v8(k, strands, pts, pts_first, first, count, out_first,
                           out4, -1);
    else if (mode == 2)
        hf__points_loop_v8(k, strands, pts, pts_first, first, count, out_first,
                           out4, 2);
    else if (mode)
        hf__points_loop_v8(k, strands, pts, pts_first, first, count, out_first,
                           out4, 1);
    else
        hf__points_loop_v8(k, strands, pts, pts_first, first, count, out_first,
                           out4, 0);
    _mm256_zeroupper(); /* see HF__TARGET_AVX2 */
}
#endif

#endif /* !HF__PASS */

#if defined(HF__PASS) && HF__PASS == HF__PASS_POINTS
/* hf__interp_range_v<W> and the GPU points kernel in one, for P at least
   W (8 at AVX2, 16 at AVX-512) and a multiple of W / 4 (a vector of
   points' worth), one text built at both widths: the strand's whole
   groups, then, where points are left, the group that ends at the tip,
   written from the first vector of points not yet written. Three
   vectors of a strand's floats (W points) stay in
   registers and go out as four vectors of points (hf__points_out_v<W>),
   the same values in the same order as the two kernels write them. The
   finiteness test rides on the same vectors (x * 0 is NaN for NaN or
   infinity); a strand that is not finite is written again, collapsed,
   as hf__points_run does. hf__points_groups_v<W>: the GPU points kernel
   alone (P a multiple of W), the same text loading the strand's points. */

/* acc + q * 0: stays zero while every lane of q is finite */
HF__VTARGET HF__INLINE HF__VEC HF__KN(hf__nan_acc)(HF__VEC acc, HF__VEC q)
{
    return HF__VADD(acc, HF__VMUL(q, HF__VSET1(0.0f)));
}

/* W points' floats a, b, c: their finiteness into acc, their points out
   from output vector q on (0: all four) */
HF__VTARGET HF__INLINE void HF__KN(hf__points_abc)(float *o, HF__VEC a,
                                                   HF__VEC b, HF__VEC c,
                                                   const float *pw, HF__VEC WS,
                                                   HF__VEC *acc, int mode,
                                                   int q)
{
    *acc = HF__KN(hf__nan_acc)(*acc, a);
    *acc = HF__KN(hf__nan_acc)(*acc, b);
    *acc = HF__KN(hf__nan_acc)(*acc, c);
    HF__KN(hf__points_out)(o, a, b, c, pw, WS, mode, q);
}

HF__VTARGET HF__INLINE void HF__KN(hf__interp_points_whole)(
    const hf__irun *run, const hf__points_kit *k, const hf_ribbon_strands *st,
    int first, int count, int out_first, float *out4, int clump, int mode)
{
    const int P = run->P;
    const size_t n = 3u * (size_t)P;
    const float *G = run->guides, *ctab = run->ctab;
    /* read once: the stores may alias k, st and run */
    const float wcap = k->wcap, *wd = st->width;
    const hf_strand_binding *B = run->bindings;
    int s, i, j;
    for (s = first; s < first + count; ++s) {
        float *o = out4 + (size_t)(s - out_first) * (size_t)P * 4u;
        const HF__VEC WS = HF__VSET1(hf__width_at(wd, s, wcap));
        HF__VEC acc = HF__VSET1(0.0f), sa;
        HF__KN(hf__is) v;
        if (mode) hf__page_ahead(o, 16u * (size_t)P);
        HF__KN(hf__strand)(G, clump, B + s, n, &v);
        sa = HF__KN(hf__sum)(&v, 0); /* the root's, and the first vector's */
        HF__KN(hf__roots)(v.SC, sa, v.R);
        for (i = 0, j = 0;; sa = HF__KN(hf__sum)(&v, (size_t)i)) {
            const HF__VEC a = HF__KN(hf__finish)(&v, ctab, sa, (size_t)i, 0);
            const HF__VEC b = HF__KN(hf__blend)(&v, ctab, (size_t)i + HF__W, 1);
            const HF__VEC c =
                HF__KN(hf__blend)(&v, ctab, (size_t)i + 2 * HF__W, 2);
            HF__KN(hf__points_abc)(o + 4 * j, a, b, c, HF__KN(hf__widths)(k, j),
                                   WS, &acc, mode, 0);
            i += 3 * HF__W;
            if ((j += HF__W) + HF__W > P) break;
        }
        if (j < P) {
            /* the last points: the group of W that ends at the tip (its
               first float's phase is 0 too), written from the output
               vector that holds point j on, so no point is written twice;
               apart from the loop, whose stores then take no test */
            const int q = (j + HF__W - P) / (HF__W / 4);
            HF__VEC a, b, c;
            j = P - HF__W;
            i = 3 * j;
            a = HF__KN(hf__blend)(&v, ctab, (size_t)i, 0);
            b = HF__KN(hf__blend)(&v, ctab, (size_t)i + HF__W, 1);
            c = HF__KN(hf__blend)(&v, ctab, (size_t)i + 2 * HF__W, 2);
            HF__KN(hf__points_abc)(o + 4 * j, a, b, c, HF__KN(hf__widths)(k, j),
                                   WS, &acc, mode, q);
        }
        if (!HF__KN(hf__all_zero)(acc)) hf__points_collapse_v8(k, o);
    }
}

/* every strand's 16 P bytes keep the first's alignment (a multiple of 4 W
   bytes, P a multiple of W / 4), so the stream mode, like the clumping, is
   one for the call: both passed to the loop as constants */
HF__VTARGET HF__PRIVATE void
HF__KN(hf__interp_points)(const hf__irun *run, const hf__points_kit *k,
                          const hf_ribbon_strands *st, int first, int count,
                          int out_first, float *out4)
{
    const int mode = hf__stream_mode(
        k->nt, out4 + (size_t)(first - out_first) * (size_t)run->P * 4u,
        4u * HF__W - 1u);
    HF__CLUMP_MODE_CASES(run->clump, mode, HF__KN(hf__interp_points_whole), run,
                         k, st, first, count, out_first, out4);
    HF__VZEROUPPER(); /* see HF__TARGET_AVX2 */
}

/* hf__points_run's kernel for P a multiple of W: the kernel above with
   three loads of the strand's points where it interpolates them */
HF__VTARGET HF__INLINE void
HF__KN(hf__points_whole)(const hf__points_kit *k, const hf_ribbon_strands *st,
                         const float *pts, int pts_first, int first, int count,
                         int out_first, float *out4, int mode)
{
    const int P = k->P;
    /* read once: the stores may alias k and st */
    const float wcap = k->wcap, *wd = st->width;
    int s, j;
    for (s = first; s < first + count; ++s) {
        const float *p = pts + (size_t)(s - pts_first) * (size_t)P * 3u;
        float *o = out4 + (size_t)(s - out_first) * (size_t)P * 4u;
        const HF__VEC WS = HF__VSET1(hf__width_at(wd, s, wcap));
        HF__VEC acc = HF__VSET1(0.0f);
        if (mode) hf__page_ahead(o, 16u * (size_t)P);
        for (j = 0; j < P; j += HF__W) {
            const HF__VEC a = HF__VLD(p + 3 * j);
            const HF__VEC b = HF__VLD(p + 3 * j + HF__W);
            const HF__VEC c = HF__VLD(p + 3 * j + 2 * HF__W);
            HF__KN(hf__points_abc)(o + 4 * j, a, b, c, HF__KN(hf__widths)(k, j),
                                   WS, &acc, mode, 0);
        }
        if (!HF__KN(hf__all_zero)(acc)) hf__points_collapse_v8(k, o);
    }
}

HF__VTARGET HF__PRIVATE void
HF__KN(hf__points_groups)(const hf__points_kit *k, const hf_ribbon_strands *st,
                          const float *pts, int pts_first, int first, int count,
                          int out_first, float *out4)
{
    const int mode = hf__stream_mode(
        k->nt, out4 + (size_t)(first - out_first) * (size_t)k->P * 4u,
        4u * HF__W - 1u);
    if (mode == 2) /* the mode a constant in each loop, as above */
        HF__KN(hf__points_whole)(k, st, pts, pts_first, first, count,
                                 out_first, out4, 2);
    else if (mode)
        HF__KN(hf__points_whole)(k, st, pts, pts_first, first, count,
                                 out_first, out4, 1);
    else
        HF__KN(hf__points_whole)(k, st, pts, pts_first, first, count,
                                 out_first, out4, 0);
    HF__VZEROUPPER(); /* see HF__TARGET_AVX2 */
}
#endif /* HF__PASS_POINTS */

#ifndef HF__PASS
#if HF__AVX2
HF__TARGET_AVX2 HF__INLINE int hf__all_zero_v8(__m256 acc)
{
    return _mm256_movemask_ps(_mm256_cmp_ps(acc, _mm256_setzero_ps(),
                                            _CMP_EQ_OQ)) == 0xff;
}

/* Two points' x y z in q, their widths (pw, as hf__pair_widths) times ws
   blended in, out at o */
HF__TARGET_AVX2 HF__INLINE void hf__point_pair_w(float *o, __m256 q,
                                                 const float *pw, __m256 ws,
                                                 int mode)
{
    hf__put_v8(
        o, _mm256_blend_ps(q, _mm256_mul_ps(_mm256_loadu_ps(pw), ws), 0x88),
        mode);
}

/* Points j .. j + 7 out at o from a strand's floats 3 j .. 3 j + 24 in a,
   b, c, two a vector; pw: the pair widths from point j (written out, not
   looped: an array of the four would go through the stack) */
HF__TARGET_AVX2 HF__INLINE void hf__points_out_v8(float *o, __m256 a, __m256 b,
                                                __m256 c, const float *pw,
                                                __m256 ws, int mode, int q)
{
    const __m256i lo = _mm256_setr_epi32(0, 1, 2, 0, 3, 4, 5, 0);
    const __m256i hi = _mm256_setr_epi32(2, 3, 4, 0, 5, 6, 7, 0);
    if (q <= 0)
        hf__point_pair_w(o, _mm256_permutevar8x32_ps(a, lo), pw, ws, mode);
    if (q <= 1)
        hf__point_pair_w(o + 8,
                         _mm256_permutevar8x32_ps(
                             _mm256_permute2f128_ps(a, b, 0x21), hi),
                         pw + 8, ws, mode);
    if (q <= 2)
        hf__point_pair_w(o + 16,
                         _mm256_permutevar8x32_ps(
                             _mm256_permute2f128_ps(b, c, 0x21), lo),
                         pw + 16, ws, mode);
    hf__point_pair_w(o + 24, _mm256_permutevar8x32_ps(c, hi), pw + 24, ws,
                     mode);
}

/* the widths hf__points_out_v8 takes from point j: pair widths */
HF__INLINE const float *hf__widths_v8(const hf__points_kit *k, int j)
{
    return k->pw.v + 4 * j;
}

#define HF__PASS HF__PASS_POINTS
#define HF__W 8
#include HF_HEADER_FILENAME
#endif

#if HF__AVX512
HF__TARGET_AVX512 HF__INLINE int hf__all_zero_v16(__m512 acc)
{
    return _mm512_cmp_ps_mask(acc, _mm512_setzero_ps(), _CMP_EQ_OQ) == 0xffff;
}

/* the widths hf__points_out_v16 takes from point j: the half widths */
HF__INLINE const float *hf__widths_v16(const hf__points_kit *k, int j)
{
    return k->hw + j;
}

/* hf__points_out_v8 at sixteen points: four vectors of four points, one
   64-byte line a store where the output is aligned so. The sixteen
   widths (hw times ws, one product a point as the pair widths give) go
   in as the second source of each two-source permute, so a point's width
   costs no blend or multiply of its own; the two middle vectors draw on
   three sources, so their third (four floats of a or c) is first moved
   into lanes of the widths the permute does not read. */
HF__TARGET_AVX512 HF__INLINE void hf__points_out_v16(float *o, __m512 a,
                                                   __m512 b, __m512 c,
                                                   const float *hw,
                                                   __m512 ws, int mode, int q)
{
    /* index >= 16: the second source. Points 0-3: a's floats 0-11, w's
       0-3; points 4-7: a's 12-15 (moved into w's lanes 12-15: x), b's
       0-7, w's 4-7; points 8-11: b's 8-15, c's 0-3 (moved into w's lanes
       0-3: y), w's 8-11; points 12-15: c's 4-15, w's 12-15 */
    const __m512i i0 = _mm512_setr_epi32(0, 1, 2, 16, 3, 4, 5, 17, 6, 7, 8,
                                         18, 9, 10, 11, 19);
    const __m512i i1 = _mm512_setr_epi32(12, 13, 14, 4, 15, 16, 17, 5, 18,
                                         19, 20, 6, 21, 22, 23, 7);
    const __m512i i2 = _mm512_setr_epi32(8, 9, 10, 24, 11, 12, 13, 25, 14,
                                         15, 16, 26, 17, 18, 19, 27);
    const __m512i i3 = _mm512_setr_epi32(4, 5, 6, 28, 7, 8, 9, 29, 10, 11,
                                         12, 30, 13, 14, 15, 31);
    const __m512 w = _mm512_mul_ps(_mm512_loadu_ps(hw), ws);
    const __m512 x = _mm512_mask_mov_ps(w, 0xf000, a);
    const __m512 y = _mm512_mask_mov_ps(w, 0x000f, c);
    if (q <= 0) hf__put_v16(o, _mm512_permutex2var_ps(a, i0, w), mode);
    if (q <= 1) hf__put_v16(o + 16, _mm512_permutex2var_ps(x, i1, b), mode);
    if (q <= 2) hf__put_v16(o + 32, _mm512_permutex2var_ps(b, i2, y), mode);
    hf__put_v16(o + 48, _mm512_permutex2var_ps(c, i3, w), mode);
}

#define HF__PASS HF__PASS_POINTS
#define HF__W 16
#include HF_HEADER_FILENAME
#endif
#undef HF__CLUMP_MODE_CASES

/* Interpolation into GPU points in one kernel (hf_fur_interpolate_points)
   per width, each returning 0 for a P it leaves to the next: P even and
   at least 8 at eight lanes, a multiple of 4 and at least 16 at sixteen;
   none at four lanes and one (fused 0: the strands go through memory). */
typedef struct hf__ipoints_kernels {
    hf__isa isa;
    int (*fused)(const hf__irun *, const hf__points_kit *,
                 const hf_ribbon_strands *, int, int, int, float *);
} hf__ipoints_kernels;

#if HF__AVX2
HF__PRIVATE int hf__interp_points_fit_v8(const hf__irun *run,
                                         const hf__points_kit *k,
                                         const hf_ribbon_strands *st, int first,
                                         int count, int out_first, float *out4)
{
    if (run->P % 2 != 0 || run->P < 8) return 0;
    hf__interp_points_v8(run, k, st, first, count, out_first, out4);
    return 1;
}
#endif
#if HF__AVX512
HF__PRIVATE int hf__interp_points_fit_v16(const hf__irun *run,
                                          const hf__points_kit *k,
                                          const hf_ribbon_strands *st,
                                          int first, int count, int out_first,
                                          float *out4)
{
    if (run->P % 4 != 0 || run->P < 16) return 0;
    hf__interp_points_v16(run, k, st, first, count, out_first, out4);
    return 1;
}
#endif

static const hf__ipoints_kernels hf__ipoints_widths[] = {
#if HF__AVX512
    {{HF__ISA_V16}, hf__interp_points_fit_v16},
#endif
#if HF__AVX2
    {{HF__ISA_V8}, hf__interp_points_fit_v8},
#endif
    {{HF__ISA_V1}, NULL}};

/* Compact points (HF_POINT_COMPACT) from float ones: n points (x, y, z,
   half width) at in to 8 bytes each at o, native byte order; the vector
   encoders (hf__encode_v4, hf__encode_v8) perform hf__encode1's
   operations, so every level writes the same bytes. */
HF__PRIVATE void hf__points_encode_v1(const hf__points_kit *k, const float *in,
                                      size_t n, unsigned char *o, int nt)
{
    size_t i;
    int c;
    (void)nt;
    for (i = 0; i < n; ++i, in += 4, o += 8) {
        uint16_t code[4];
        for (c = 0; c < 3; ++c)
            code[c] = (uint16_t)hf__encode1((in[c] - k->origin[c]) * k->inv,
                                            HF_FORMAT_SNORM16);
        code[3] = (uint16_t)hf__encode1(in[3], HF_FORMAT_F16);
        HF_MEMCPY(o, code, 8);
    }
}

#if HF__SSE
/* One point's four codes (x, y, z SNORM16, w F16) in 32-bit lanes. */
HF__INLINE __m128i hf__point_codes_v4(__m128 v, __m128 o, __m128 inv)
{
    const __m128i xyz = _mm_setr_epi32(-1, -1, -1, 0);
    const __m128i sn =
        hf__encode_v4(_mm_mul_ps(_mm_sub_ps(v, o), inv), HF_FORMAT_SNORM16);
    const __m128i h = hf__encode_v4(v, HF_FORMAT_F16);
    const __m128i c = _mm_or_si128(_mm_and_si128(xyz, sn),
                                   _mm_andnot_si128(xyz, h));
    return _mm_srai_epi32(_mm_slli_epi32(c, 16), 16); /* for packs */
}

HF__PRIVATE void hf__points_encode_v4(const hf__points_kit *k, const float *in,
                                      size_t n, unsigned char *o, int nt)
{
    const __m128 org = _mm_setr_ps(k->origin[0], k->origin[1], k->origin[2],
                                   0.0f),
                 inv = _mm_setr_ps(k->inv, k->inv, k->inv, 1.0f);
    size_t i = 0;
    nt = nt && ((uintptr_t)o & 15u) == 0;
    for (; i + 2 <= n; i += 2, in += 8, o += 16) {
        const __m128i two =
            _mm_packs_epi32(hf__point_codes_v4(_mm_loadu_ps(in), org, inv),
                            hf__point_codes_v4(_mm_loadu_ps(in + 4), org, inv));
        if (nt)
            _mm_stream_si128((__m128i *)(void *)o, two);
        else
            _mm_storeu_si128((__m128i *)(void *)o, two);
    }
    if (i < n)
        _mm_storel_epi64((__m128i *)(void *)o,
                         _mm_packs_epi32(hf__point_codes_v4(_mm_loadu_ps(in),
                                                            org, inv),
                                         _mm_setzero_si128()));
}
#endif

#if HF__AVX2
/* hf__points_encode_v4 eight points at a time: the positions two points
   a vector, the eight half widths gathered into one vector for a single
   half conversion, then put back into each point's fourth lane. */
HF__TARGET_AVX2 HF__PRIVATE void hf__points_encode_v8(const hf__points_kit *k,
                                                      const float *in, size_t n,
                                                      unsigned char *o, int nt)
{
    const __m256 org = _mm256_setr_ps(k->origin[0], k->origin[1],
                                      k->origin[2], 0.0f, k->origin[0],
                                      k->origin[1], k->origin[2], 0.0f),
                 inv = _mm256_set1_ps(k->inv);
    size_t i = 0;
    nt = nt && ((uintptr_t)o & 31u) == 0;
    for (; i + 8 <= n; i += 8, in += 32, o += 64) {
        const __m256 v0 = _mm256_loadu_ps(in), v1 = _mm256_loadu_ps(in + 8),
                     v2 = _mm256_loadu_ps(in + 16),
                     v3 = _mm256_loadu_ps(in + 24);
        /* w0 w2 w4 w6 | w1 w3 w5 w7 */
        const __m256i w = hf__encode_v8(
            _mm256_shuffle_ps(
                _mm256_shuffle_ps(v0, v1, _MM_SHUFFLE(3, 3, 3, 3)),
                _mm256_shuffle_ps(v2, v3, _MM_SHUFFLE(3, 3, 3, 3)),
                _MM_SHUFFLE(2, 0, 2, 0)),
            HF_FORMAT_F16);
        __m256i c0 = hf__encode_v8(_mm256_mul_ps(_mm256_sub_ps(v0, org), inv),
                                   HF_FORMAT_SNORM16),
                c1 = hf__encode_v8(_mm256_mul_ps(_mm256_sub_ps(v1, org), inv),
                                   HF_FORMAT_SNORM16),
                c2 = hf__encode_v8(_mm256_mul_ps(_mm256_sub_ps(v2, org), inv),
                                   HF_FORMAT_SNORM16),
                c3 = hf__encode_v8(_mm256_mul_ps(_mm256_sub_ps(v3, org), inv),
                                   HF_FORMAT_SNORM16),
                out0, out1;
        /* each point's half width into its fourth lane, then the codes
           sign-extended for packs */
        c0 = _mm256_blend_epi32(c0, _mm256_shuffle_epi32(w, 0x00), 0x88);
        c1 = _mm256_blend_epi32(c1, _mm256_shuffle_epi32(w, 0x55), 0x88);
        c2 = _mm256_blend_epi32(c2, _mm256_shuffle_epi32(w, 0xaa), 0x88);
        c3 = _mm256_blend_epi32(c3, _mm256_shuffle_epi32(w, 0xff), 0x88);
        c0 = _mm256_srai_epi32(_mm256_slli_epi32(c0, 16), 16);
        c1 = _mm256_srai_epi32(_mm256_slli_epi32(c1, 16), 16);
        c2 = _mm256_srai_epi32(_mm256_slli_epi32(c2, 16), 16);
        c3 = _mm256_srai_epi32(_mm256_slli_epi32(c3, 16), 16);
        /* packs works within 128-bit halves: points 0 2 | 1 3, reordered */
        out0 = _mm256_permute4x64_epi64(_mm256_packs_epi32(c0, c1),
                                        _MM_SHUFFLE(3, 1, 2, 0));
        out1 = _mm256_permute4x64_epi64(_mm256_packs_epi32(c2, c3),
                                        _MM_SHUFFLE(3, 1, 2, 0));
        if (nt) {
            _mm256_stream_si256((__m256i *)(void *)o, out0);
            _mm256_stream_si256((__m256i *)(void *)(o + 32), out1);
        } else {
            _mm256_storeu_si256((__m256i *)(void *)o, out0);
            _mm256_storeu_si256((__m256i *)(void *)(o + 32), out1);
        }
    }
    _mm256_zeroupper();
    if (i < n) hf__points_encode_v4(k, in, n - i, o, 0);
}
#endif

#if HF__AVX512
/* Four points a vector: the positions' codes as the other encoders
   make them, the half widths by the conversion instruction, which rounds
   to nearest even as hf__encode1 does (after its clamp to the largest
   half, subnormals included); each a 32-bit lane, narrowed to 16. */
HF__TARGET_AVX512 HF__PRIVATE void
hf__points_encode_v16(const hf__points_kit *k, const float *in, size_t n,
                      unsigned char *o, int nt)
{
    const __m512 org = _mm512_setr_ps(
        k->origin[0], k->origin[1], k->origin[2], 0.0f, k->origin[0],
        k->origin[1], k->origin[2], 0.0f, k->origin[0], k->origin[1],
        k->origin[2], 0.0f, k->origin[0], k->origin[1], k->origin[2], 0.0f);
    const __m512 inv = _mm512_set1_ps(k->inv),
                 big = _mm512_set1_ps(65504.0f),
                 nbig = _mm512_set1_ps(-65504.0f);
    hf__enc8 e8;
    hf__enc16 sn;
    size_t i = 0;
    hf__enc8_init(&e8, HF_FORMAT_SNORM16);
    hf__enc16_init(&sn, &e8);
    nt = nt && ((uintptr_t)o & 31u) == 0;
    for (; i + 4 <= n; i += 4, in += 16, o += 32) {
        const __m512 v = _mm512_loadu_ps(in);
        __m512i c = hf__encode16(_mm512_mul_ps(_mm512_sub_ps(v, org), inv),
                                 &sn);
        __m256i four;
        /* the masked forms, as HF__SQRT's */
        c = _mm512_mask_blend_epi32(
            0x8888, c,
            _mm512_maskz_cvtepu16_epi32(
                0xffff,
                _mm512_maskz_cvtps_ph(
                    0xffff,
                    _mm512_maskz_min_ps(0xffff,
                                        _mm512_maskz_max_ps(0xffff, v, nbig),
                                        big),
                    _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)));
        four = _mm512_maskz_cvtepi32_epi16(0xffff, c);
        if (nt)
            _mm256_stream_si256((__m256i *)(void *)o, four);
        else
            _mm256_storeu_si256((__m256i *)(void *)o, four);
    }
    _mm256_zeroupper();
    if (i < n) hf__points_encode_v4(k, in, n - i, o, 0);
}
#endif

#if HF__NEON
HF__PRIVATE void hf__points_encode_v4(const hf__points_kit *k, const float *in,
                                      size_t n, unsigned char *o, int nt)
{
    const float32x4_t inv = {k->inv, k->inv, k->inv, 1.0f};
    const float32x4_t org = {k->origin[0], k->origin[1], k->origin[2], 0.0f};
    const uint32x4_t xyz = {0xffffffffu, 0xffffffffu, 0xffffffffu, 0u};
    size_t i;
    (void)nt; /* no streaming stores on ARM64 */
    for (i = 0; i < n; ++i, in += 4, o += 8) {
        const float32x4_t v = vld1q_f32(in);
        const uint32x4_t c =
            vbslq_u32(xyz,
                      hf__encode_v4(vmulq_f32(vsubq_f32(v, org), inv),
                                    HF_FORMAT_SNORM16),
                      hf__encode_v4(v, HF_FORMAT_F16));
        vst1_u16((uint16_t *)(void *)o, vmovn_u32(c));
    }
}
#endif

/* The points kernels of one width (hf__points_widths): at eight and
   sixteen lanes a kernel for whole calls (run: 0 for a P it leaves to the
   next width), finiteness found on the way (a strand that is not is
   written again, collapsed, streamed stores ordered first); at four
   lanes and one a strand at a time (strand, after finite). */
typedef struct hf__points_kernels {
    hf__isa isa;
    int (*run)(const hf__points_kit *, const hf_ribbon_strands *, const float *,
               int, int, int, int, float *);
    int (*finite)(const float *, int);
    void (*strand)(const float *, const float *, float, float *, int, int);
} hf__points_kernels;

#if HF__AVX2
/* Whole groups of W points where P allows (with its input and output in
   L2, 100,000 strands of 16 points took 0.41-0.48 ms against the pairs'
   0.64-0.67), else two points a vector; P >= 3. */
HF__PRIVATE int hf__points_run_v8(const hf__points_kit *k,
                                  const hf_ribbon_strands *strands,
                                  const float *pts, int pts_first, int first,
                                  int count, int out_first, float *out4)
{
    if (k->P < 3) return 0;
    if (k->P % 8 == 0)
        hf__points_groups_v8(k, strands, pts, pts_first, first, count,
                             out_first, out4);
    else
        hf__points_pairs_v8(k, strands, pts, pts_first, first, count, out_first,
                            out4);
    return 1;
}
#endif
#if HF__AVX512
/* P a multiple of 16 */
HF__PRIVATE int hf__points_run_v16(const hf__points_kit *k,
                                   const hf_ribbon_strands *strands,
                                   const float *pts, int pts_first, int first,
                                   int count, int out_first, float *out4)
{
    if (k->P % 16 != 0) return 0;
    hf__points_groups_v16(k, strands, pts, pts_first, first, count, out_first,
                          out4);
    return 1;
}
#endif

static const hf__points_kernels hf__points_widths[] = {
#if HF__AVX512
    {{HF__ISA_V16}, hf__points_run_v16, NULL, NULL},
#endif
#if HF__AVX2
    {{HF__ISA_V8}, hf__points_run_v8, NULL, NULL},
#endif
#if HF__SSE
    {{HF__ISA_V4}, NULL, hf__points_finite_v4, hf__points_strand_v4},
#elif HF__NEON
    {{HF__ISA_V4}, NULL, hf__points_finite_v1, hf__points_strand_v4},
#endif
    {{HF__ISA_V1}, NULL, hf__points_finite_v1, hf__points_strand_v1}};

HF__PRIVATE void hf__points_run(const hf__points_kit *k,
                                const hf_ribbon_strands *strands,
                                const float *pts, int pts_first, int first,
                                int count, int out_first, float *out4);

typedef struct hf__encode_kernels {
    hf__isa isa;
    void (*encode)(const hf__points_kit *, const float *, size_t,
                   unsigned char *, int);
} hf__encode_kernels;

static const hf__encode_kernels hf__encode_widths[] = {
#if HF__AVX512
    {{HF__ISA_V16}, hf__points_encode_v16},
#endif
#if HF__AVX2
    {{HF__ISA_V8}, hf__points_encode_v8},
#endif
#if HF__V4
    {{HF__ISA_V4}, hf__points_encode_v4},
#endif
    {{HF__ISA_V1}, hf__points_encode_v1}};

/* The dispatch of the compact encoders (hf__encode_widths, resolved by
   hf__points_kit_init): n points at in to o. */
HF__PRIVATE void hf__points_encode(const hf__points_kit *k, const float *in,
                                   size_t n, unsigned char *o)
{
    k->encode->encode(k, in, n, o, k->nt);
}

/* Compact points of strands [first, first + count): the float points of
   a few strands at a time into a 4 KiB stage (ordinary stores, so it
   stays in L1), then encoded from there to out + (s - out_first) * 8 P
   bytes. */
#define HF__POINTS_STAGE 1024
HF__PRIVATE void hf__points_run_compact(const hf__points_kit *k,
                                        const hf_ribbon_strands *strands,
                                        const float *pts, int pts_first,
                                        int first, int count, int out_first,
                                        unsigned char *out)
{
    float stage[HF__POINTS_STAGE];
    hf__points_kit f32 = *k;
    const int P = k->P, per = HF__POINTS_STAGE / 4 / P;
    int s, n;
    f32.compact = 0;
    f32.nt = 0;
    for (s = first; s < first + count; s += n) {
        n = first + count - s < per ? first + count - s : per;
        hf__points_run(&f32, strands, pts, pts_first, s, n, s, stage);
        hf__points_encode(k, stage, (size_t)n * (size_t)P,
                          out + (size_t)(s - out_first) * (size_t)P * 8u);
    }
}

/* GPU points of strands [first, first + count): strand s's points at
   pts + (s - pts_first) * 3 P, written to out4 + (s - out_first) * 4 P
   (compact ones: hf__points_run_compact). The caller fences streamed
   stores. */
HF__PRIVATE void hf__points_run(const hf__points_kit *k,
                                const hf_ribbon_strands *strands,
                                const float *pts, int pts_first, int first,
                                int count, int out_first, float *out4)
{
    const int P = k->P;
    int s;
    const hf__points_kernels *kr = k->kernels;
    if (k->compact) {
        hf__points_run_compact(k, strands, pts, pts_first, first, count,
                               out_first, (unsigned char *)out4);
        return;
    }
    for (; kr->run; ++kr)
        if (kr->run(k, strands, pts, pts_first, first, count, out_first, out4))
            return;
    for (s = first; s < first + count; ++s) {
        const float *p = pts + (size_t)(s - pts_first) * (size_t)P * 3u;
        float *o = out4 + (size_t)(s - out_first) * (size_t)P * 4u;
        float wscale = 0.0f;
        if (kr->finite(p, 3 * P))
            wscale = hf__width_at(strands->width, s, k->wcap);
        else
            p = hf__zero_points; /* collapsed, as hf_ribbons */
        kr->strand(p, k->hw, wscale, o, P, k->nt);
    }
}

/* A points call's kit from resolved params, for `count` strands */
HF__PRIVATE void hf__points_kit_init(hf__points_kit *k,
                                     const hf_ribbon_params *params, int count)
{
    int c;
    k->P = params->points_per_strand;
    k->level = hf_simd_resolve(params->simd);
    k->kernels = hf__kernels_for(hf__points_widths, k->level);
    k->encode = hf__kernels_for(hf__encode_widths, k->level);
    k->compact = params->point_format == HF_POINT_COMPACT;
    for (c = 0; c < 3; ++c) k->origin[c] = params->point_origin[c];
    k->inv = 1.0f / params->point_scale; /* resolved: not 0 */
    k->nt =
        hf__streaming(params->nontemporal,
                      (size_t)count * (size_t)k->P * (k->compact ? 8u : 16u),
                      HF_STREAM_MIN_VERTEX_BYTES);
    k->wcap = hf__half_widths(params, k->hw, NULL);
#if HF__AVX2
    /* the pair widths of the kernels at eight lanes and more (P >= 3) */
    if (k->kernels->isa.lanes >= 8 && k->P >= 3)
        hf__pair_widths_init(&k->pw, k->hw, k->P);
#endif
}

/* hf_ribbon_points, with the stores chosen as for `sized` strands (as
   hf__ribbons) */
HF__PRIVATE hf_result hf__ribbon_points(const hf_ribbon_strands *strands,
                                        int first, int count,
                                        const hf_ribbon_params *view,
                                        float *out4, int sized)
{
    hf__points_kit kit;
    hf_ribbon_params prm;
    hf_result r = hf__ribbon_check(strands, first, count, view, &prm);
    if (r != HF_OK) return r;
    if (!out4) return HF_ERROR_NULL_POINTER;
    hf__points_kit_init(&kit, &prm, sized);
    hf__points_run(&kit, strands, strands->points, 0, first, count,
                   prm.out_first, out4);
#if HF__SSE
    if (kit.nt) _mm_sfence(); /* streamed stores visible before we return */
#endif
    return HF_OK;
}

HFDEF hf_result hf_ribbon_points(const hf_ribbon_strands *strands, int first,
                                 int count, const hf_ribbon_params *view,
                                 float *out4)
{
    return hf__ribbon_points(strands, first, count, view, out4, count);
}

/* ---- 8.9 indices -------------------------------------------------------- */

HFDEF long long hf_ribbon_index_count(int strand_count, int points_per_strand,
                                      int topology)
{
    long long per, n;
    if (strand_count < 0 || points_per_strand < 2) return -1;
    if (topology == HF_TRIANGLES)
        per = 6LL * (points_per_strand - 1);
    else if (topology == HF_STRIP_RESTART)
        per = 2LL * points_per_strand + 1;
    else
        return -1;
    if (strand_count > 0 && per > 0x7fffffffLL / strand_count) return -1;
    n = per * strand_count;
    return n;
}

/* Index i of a 32-bit (out32) or 16-bit (out16) buffer. */
HF__INLINE void hf__put_index(uint32_t *out32, uint16_t *out16, long long i,
                              uint32_t v)
{
    if (out32)
        out32[i] = v;
    else
        out16[i] = (uint16_t)v;
}

/* hf_ribbon_indices into either width; vertex numbers stay below
   `restart` (the restart index, which no vertex may take). */
HF__PRIVATE hf_result hf__ribbon_indices_any(int strand_count, int P,
                                             int topology, uint32_t *out32,
                                             uint16_t *out16,
                                             long long capacity,
                                             long long restart)
{
    long long n = hf_ribbon_index_count(strand_count, P, topology), i = 0;
    int s, j;
    if (!out32 && !out16) return HF_ERROR_NULL_POINTER;
    if (n < 0) {
        if (strand_count < 0 || P < 2) return HF_ERROR_BAD_COUNT;
        if (topology != HF_TRIANGLES && topology != HF_STRIP_RESTART)
            return HF_ERROR_BAD_PARAMETER;
        return HF_ERROR_OVERFLOW;
    }
    if (capacity < n) return HF_ERROR_BUFFER_TOO_SMALL;
    /* the last vertex number, 2 P strand_count - 1, must fit and stay
       below the restart index */
    if (2LL * P * strand_count > restart) return HF_ERROR_OVERFLOW;
    for (s = 0; s < strand_count; ++s) {
        const uint32_t base = (uint32_t)s * (uint32_t)P * 2u;
        if (topology == HF_TRIANGLES) {
            for (j = 0; j < P - 1; ++j) {
                const uint32_t a = base + 2u * (uint32_t)j;
                /* (a, a+1, a+2) and (a+2, a+1, a+3): counter-clockwise
                   seen from the camera, since side x tangent faces it */
                hf__put_index(out32, out16, i++, a);
                hf__put_index(out32, out16, i++, a + 1);
                hf__put_index(out32, out16, i++, a + 2);
                hf__put_index(out32, out16, i++, a + 2);
                hf__put_index(out32, out16, i++, a + 1);
                hf__put_index(out32, out16, i++, a + 3);
            }
        } else {
            for (j = 0; j < 2 * P; ++j)
                hf__put_index(out32, out16, i++, base + (uint32_t)j);
            hf__put_index(out32, out16, i++, (uint32_t)restart);
        }
    }
    return HF_OK;
}

HFDEF hf_result hf_ribbon_indices(int strand_count, int points_per_strand,
                                  int topology, uint32_t *out,
                                  long long capacity)
{
    if (!out) return HF_ERROR_NULL_POINTER;
    return hf__ribbon_indices_any(strand_count, points_per_strand, topology,
                                  out, NULL, capacity, 0xffffffffLL);
}

HFDEF int hf_ribbon_chunk_strands(int points_per_strand, int topology)
{
    /* vertex numbers 0 .. 0xFFFE: 0xFFFF is the strip restart index, and
       the triangle lists keep the same bound so one chunk size fits both */
    if (points_per_strand < 2 || points_per_strand > HF_MAX_POINTS ||
        (topology != HF_TRIANGLES && topology != HF_STRIP_RESTART))
        return 0;
    return 0xffff / (2 * points_per_strand);
}

HFDEF hf_result hf_ribbon_indices16(int strand_count, int points_per_strand,
                                    int topology, uint16_t *out,
                                    long long capacity)
{
    if (!out) return HF_ERROR_NULL_POINTER;
    return hf__ribbon_indices_any(strand_count, points_per_strand, topology,
                                  NULL, out, capacity, 0xffffLL);
}

/* ---- 9. LUT baking ------------------------------------------------------ */
/* Marschner M and N lookup textures; the contract is docs/marschner-spec.md,
   whose sections the comments of section 9 cite by number ("section 6.3":
   the spec's, not this header's). Every quantity is double; each texel is
   rounded to float once. */

#define HF__LUT_PI 3.14159265358979323846
#define HF__LUT_HALF_PI (0.5 * HF__LUT_PI)
#define HF__LUT_COS_TD_MIN 1e-4 /* lower clamp of |cos theta_d| in N */
#define HF__LUT_J_MIN 0.02      /* lower clamp of 2 |dPhi/dh| in N */
#define HF__LUT_FLT_MAX 3.40282346638528859812e+38
#define HF__LUT_BLOCK 32 /* columns whose setup is computed together */

/* The HF_LUT_ENERGY bakes, further down. */
HF__PRIVATE void hf__lut_bake_m_energy(const hf_lut_params *p, int first_row,
                                       int row_count, float *out);
HF__PRIVATE void hf__lut_bake_n_energy(const hf_lut_params *p, int first_row,
                                       int row_count, float *out);

HFDEF void hf_lut_params_init(hf_lut_params *p)
{
    hf_lut_params zero;
    if (!p) return;
    HF_MEMSET(&zero, 0, sizeof zero);
    hf__lut_params_resolve(&zero, p);
}

/* Finite test on the bits, so it survives -ffast-math. */
HF__PRIVATE int hf__lut_finite(double x)
{
    uint64_t u;
    HF_MEMCPY(&u, &x, sizeof u);
    return (u & 0x7ff0000000000000ull) != 0x7ff0000000000000ull;
}

/* Resolve `in` into *p (the defaults), then check *p. */
HF__PRIVATE hf_result hf__lut_check(const hf_lut_params *in, hf_lut_params *p,
                                    hf_diag *diag, int check_size)
{
    static const char *const rgb_name[3] = {"sigma_a_rgb[0]",
                                            "sigma_a_rgb[1]",
                                            "sigma_a_rgb[2]"};
    int k;
    if (!in)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "params", -1,
                        "LUT params is NULL");
    hf__lut_params_resolve(in, p);
    if (!hf__lut_finite(p->eta))
        return hf__fail(diag, HF_ERROR_NON_FINITE, "eta", -1,
                        "eta is NaN or infinite");
    if (!hf__lut_finite(p->alpha_r_deg))
        return hf__fail(diag, HF_ERROR_NON_FINITE, "alpha_r_deg", -1,
                        "alpha_r_deg is NaN or infinite");
    if (!hf__lut_finite(p->beta_r_deg))
        return hf__fail(diag, HF_ERROR_NON_FINITE, "beta_r_deg", -1,
                        "beta_r_deg is NaN or infinite");
    if (!hf__lut_finite(p->sigma_a))
        return hf__fail(diag, HF_ERROR_NON_FINITE, "sigma_a", -1,
                        "sigma_a is NaN or infinite");
    for (k = 0; k < 3; ++k)
        if (!hf__lut_finite(p->sigma_a_rgb[k]))
            return hf__fail(diag, HF_ERROR_NON_FINITE, rgb_name[k], k,
                            "%s is NaN or infinite", rgb_name[k]);
    /* section 6.3 relies on eta in [1.2, 3]: then one wrapped target finds
       every root */
    if (!(p->eta >= 1.2 && p->eta <= 3.0))
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "eta", -1,
                        "eta %g is outside [1.2, 3]", p->eta);
    if (!(p->beta_r_deg > 0.0))
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "beta_r_deg", -1,
                        "beta_r_deg %g is not > 0", p->beta_r_deg);
    if (p->sigma_a < 0.0)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "sigma_a", -1,
                        "sigma_a %g is negative", p->sigma_a);
    for (k = 0; k < 3; ++k)
        if (p->sigma_a_rgb[k] < 0.0)
            return hf__fail(diag, HF_ERROR_BAD_PARAMETER, rgb_name[k], k,
                            "%s %g is negative", rgb_name[k],
                            p->sigma_a_rgb[k]);
    if (p->variant != HF_LUT_CUBIC && p->variant != HF_LUT_EXACT)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "variant", -1,
                        "variant %d is neither HF_LUT_CUBIC nor "
                        "HF_LUT_EXACT",
                        p->variant);
    if (p->model != HF_LUT_MARSCHNER && p->model != HF_LUT_ENERGY)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "model", -1,
                        "model %d is neither HF_LUT_MARSCHNER nor "
                        "HF_LUT_ENERGY",
                        p->model);
    if (check_size && (p->size < 1 || p->size > HF_LUT_MAX_SIZE))
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "size", -1,
                        "size %d is outside [1, %d]", p->size,
                        HF_LUT_MAX_SIZE);
    hf__ok(diag);
    return HF_OK;
}

HFDEF hf_result hf_lut_validate(const hf_lut_params *params, hf_diag *diag)
{
    hf_lut_params p;
    return hf__lut_check(params, &p, diag, 1);
}

/* Params, output pointers and row range, in that order, before anything
   is written. */
HF__PRIVATE hf_result hf__lut_check_bake(const hf_lut_params *in,
                                         hf_lut_params *p, int first_row,
                                         int row_count, const float *out0,
                                         const float *out1)
{
    hf_result r = hf__lut_check(in, p, NULL, 1);
    if (r != HF_OK) return r;
    if (!out0 || !out1) return HF_ERROR_NULL_POINTER;
    if (first_row < 0 || row_count < 0 || first_row > p->size ||
        row_count > p->size - first_row)
        return HF_ERROR_BAD_RANGE;
    return HF_OK;
}

/* 2 u - 1 at the centre of texel i of n: (2i + 1 - n) / n, one rounding. */
HF__PRIVATE double hf__lut_axis(int i, int n)
{
    return (double)(2 * i + 1 - n) / (double)n;
}

/* Round to float once; only a degenerate beta can exceed the float range,
   and it is stored as FLT_MAX rather than inf. Values are never negative. */
HF__PRIVATE float hf__lut_f(double x)
{
    return x > HF__LUT_FLT_MAX ? (float)HF__LUT_FLT_MAX : (float)x;
}

/* ---- 9.1 M: three Gaussians in theta_h ---------------------------------- */

typedef struct hf__lut_m {
    double alpha[3]; /* shift per lobe, radians */
    double beta[3];  /* width per lobe, radians */
    double den[3];   /* beta sqrt(2 pi): unit area */
} hf__lut_m;

HF__PRIVATE void hf__lut_m_setup(const hf_lut_params *p, hf__lut_m *m)
{
    const double d2r = HF__LUT_PI / 180.0;
    double a = p->alpha_r_deg * d2r, b = p->beta_r_deg * d2r;
    int k;
    /* A width below 1e-150 rad gives the same floats as the true one (0
       off the peak, above FLT_MAX on it) but keeps every step finite,
       even for a subnormal beta_r_deg. */
    if (b < 1e-150) b = 1e-150;
    m->alpha[0] = a;
    m->alpha[1] = -a / 2.0;
    m->alpha[2] = -3.0 * a / 2.0;
    m->beta[0] = b;
    m->beta[1] = b / 2.0;
    m->beta[2] = 2.0 * b;
    for (k = 0; k < 3; ++k)
        m->den[k] = m->beta[k] * HF_SQRT(2.0 * HF__LUT_PI);
}

/* g(beta, theta_h - alpha) of section 4; an underflowed exponential
   divides to 0, never to NaN. */
HF__PRIVATE double hf__lut_gauss(const hf__lut_m *m, int k, double theta_h)
{
    double q = (theta_h - m->alpha[k]) / m->beta[k];
    return HF_EXP(-0.5 * q * q) / m->den[k];
}

HFDEF hf_result hf_lut_eval_m(const hf_lut_params *params, double theta_h,
                              double out[3])
{
    hf_lut_params q;
    const hf_lut_params *p = &q;
    hf__lut_m m;
    int k;
    hf_result r = hf__lut_check(params, &q, NULL, 0);
    if (r != HF_OK) return r;
    if (p->model != HF_LUT_MARSCHNER) return HF_ERROR_BAD_PARAMETER;
    if (!out) return HF_ERROR_NULL_POINTER;
    if (!hf__lut_finite(theta_h)) return HF_ERROR_NON_FINITE;
    hf__lut_m_setup(p, &m);
    for (k = 0; k < 3; ++k) out[k] = hf__lut_gauss(&m, k, theta_h);
    return HF_OK;
}

HFDEF hf_result hf_lut_bake_m(const hf_lut_params *params, int first_row,
                              int row_count, float *out)
{
    hf_lut_params q;
    const hf_lut_params *p = &q;
    hf__lut_m m;
    double theta_i[HF__LUT_BLOCK];
    int n, i0, i, j;
    hf_result r = hf__lut_check_bake(params, &q, first_row, row_count, out, out);
    if (r != HF_OK) return r;
    if (p->model == HF_LUT_ENERGY) {
        hf__lut_bake_m_energy(p, first_row, row_count, out);
        return HF_OK;
    }
    n = p->size;
    hf__lut_m_setup(p, &m);
    for (i0 = 0; i0 < n; i0 += HF__LUT_BLOCK) {
        int i1 = n - i0 < HF__LUT_BLOCK ? n : i0 + HF__LUT_BLOCK;
        for (i = i0; i < i1; ++i) theta_i[i - i0] = HF_ASIN(hf__lut_axis(i, n));
        for (j = first_row; j < first_row + row_count; ++j) {
            double theta_r = HF_ASIN(hf__lut_axis(j, n));
            float *o = out + 4 * ((size_t)j * (size_t)n + (size_t)i0);
            for (i = i0; i < i1; ++i, o += 4) {
                double ti = theta_i[i - i0];
                /* both written so that (i, j) and (j, i) round alike */
                double th = 0.5 * (ti + theta_r);
                double td = 0.5 * HF_FABS(theta_r - ti);
                o[0] = hf__lut_f(hf__lut_gauss(&m, 0, th));
                o[1] = hf__lut_f(hf__lut_gauss(&m, 1, th));
                o[2] = hf__lut_f(hf__lut_gauss(&m, 2, th));
                o[3] = (float)HF_COS(td);
            }
        }
    }
    return HF_OK;
}

/* ---- 9.2 N: roots of Phi(p, gamma) = phi, Fresnel, absorption ----------- */

/* Everything that depends only on theta_d (one texture column). */
typedef struct hf__lut_col {
    double eta1, eta2;  /* Bravais indices eta', eta'' */
    double inv_cos_tt;  /* 1 / cos(theta_t); sigma_a' = sigma_a * this */
    double a[3], b[3];  /* cubic: Phi(p, g) - p pi = a g^3 + b g */
    double f_end[3];    /* exact: Phi(p, pi/2) - p pi (the function is odd) */
    double g_c, f_c;    /* exact TRT fold gamma_c > 0 and its Phi - 2 pi;
                           g_c < 0 when eta' >= 2 (no fold) */
} hf__lut_col;

/* Exact Phi(p, g) - p pi and its derivative (section 6.5). */
HF__PRIVATE double hf__lut_phi_exact(double eta1, int p, double g)
{
    return 2.0 * p * HF_ASIN(HF_SIN(g) / eta1) - 2.0 * g;
}

HF__PRIVATE double hf__lut_dphi_exact(double eta1, int p, double g)
{
    double s = HF_SIN(g);
    return 2.0 * p * HF_COS(g) / HF_SQRT(eta1 * eta1 - s * s) - 2.0;
}

HF__PRIVATE void hf__lut_col_setup(hf__lut_col *col, double eta, double cd,
                                   int exact)
{
    const double pi3 = HF__LUT_PI * HF__LUT_PI * HF__LUT_PI;
    double s2 = 1.0 - cd * cd;
    double root = HF_SQRT(eta * eta - s2); /* eta cos(theta_t) */
    double c;
    int p;
    col->eta1 = root / cd;
    col->eta2 = eta * eta / col->eta1;
    col->inv_cos_tt = eta / root;
    c = HF_ASIN(1.0 / col->eta1);
    for (p = 0; p < 3; ++p) {
        col->a[p] = -8.0 * p * c / pi3;
        col->b[p] = 6.0 * p * c / HF__LUT_PI - 2.0;
        col->f_end[p] = 0.0;
    }
    col->g_c = -1.0;
    col->f_c = 0.0;
    if (exact) {
        for (p = 1; p < 3; ++p)
            col->f_end[p] = hf__lut_phi_exact(col->eta1, p, HF__LUT_HALF_PI);
        if (col->eta1 < 2.0) {
            col->g_c = HF_ASIN(
                HF_SQRT((4.0 - col->eta1 * col->eta1) / 3.0));
            col->f_c = hf__lut_phi_exact(col->eta1, 2, col->g_c);
        }
    }
}

/* Real roots of a g^3 + b g = t (section 6.3), each polished by up to two
   Newton steps that do not increase the residual. Returns the count. */
HF__PRIVATE int hf__lut_cubic_roots(double a, double b, double t,
                                    double g[3])
{
    int n, k, it;
    if (a == 0.0) { /* R: b = -2 */
        g[0] = t / b;
        return 1;
    }
    {
        double P = b / a, Q = -t / a; /* x^3 + P x + Q = 0 */
        double disc = 0.25 * Q * Q + P * P * P / 27.0;
        if (disc > 0.0) {
            /* one real root; the sign avoids cancellation in -Q/2 +- sqrt */
            double hq = -0.5 * Q, sq = HF_SQRT(disc);
            double A = HF_CBRT(hq >= 0.0 ? hq + sq : hq - sq);
            g[0] = A - P / (3.0 * A);
            n = 1;
        } else if (P < 0.0) {
            double m = 2.0 * HF_SQRT(-P / 3.0);
            double x = 3.0 * Q / (P * m), th;
            x = x < -1.0 ? -1.0 : (x > 1.0 ? 1.0 : x);
            th = HF_ACOS(x) / 3.0;
            for (k = 0; k < 3; ++k)
                g[k] = m * HF_COS(th - 2.0 * HF__LUT_PI * k / 3.0);
            n = 3;
        } else { /* disc <= 0 with P >= 0 only when P = Q = 0 */
            g[0] = 0.0;
            n = 1;
        }
    }
    for (k = 0; k < n; ++k) {
        double x = g[k], fx = (a * x * x + b) * x - t;
        for (it = 0; it < 2; ++it) {
            double d = 3.0 * a * x * x + b, y, fy;
            if (d == 0.0) break;
            y = x - fx / d;
            fy = (a * y * y + b) * y - t;
            if (!(HF_FABS(fy) <= HF_FABS(fx))) break;
            x = y;
            fx = fy;
        }
        g[k] = x;
    }
    return n;
}

/* The root of the exact Phi - p pi = t in a monotonic piece whose end
   residuals r_lo, r_hi do not have the same sign: Newton, falling back to
   bisection whenever a step leaves the bracket, to 1e-12 rad. */
HF__PRIVATE double hf__lut_refine(double eta1, int p, double t, double lo,
                                  double hi, double r_lo, double r_hi)
{
    double neg, pos, x;
    int it;
    if (r_lo == 0.0) return lo;
    if (r_hi == 0.0) return hi;
    neg = r_lo < 0.0 ? lo : hi; /* residual < 0 at neg, > 0 at pos */
    pos = r_lo < 0.0 ? hi : lo;
    x = 0.5 * (lo + hi);
    for (it = 0; it < 200; ++it) {
        double fx = hf__lut_phi_exact(eta1, p, x) - t, d, xn;
        if (fx == 0.0) return x;
        if (fx < 0.0)
            neg = x;
        else
            pos = x;
        d = hf__lut_dphi_exact(eta1, p, x);
        xn = d != 0.0 ? x - fx / d : x;
        if (d == 0.0 || !((xn - neg) * (xn - pos) < 0.0))
            xn = 0.5 * (neg + pos);
        if (HF_FABS(xn - x) <= 1e-13 || HF_FABS(pos - neg) <= 1e-12)
            return xn;
        x = xn;
    }
    return x;
}

/* Roots of the exact Phi(p, g) - p pi = t in [-pi/2, pi/2] (section 6.5):
   refine each monotonic piece whose end values straddle t. */
HF__PRIVATE int hf__lut_exact_roots(const hf__lut_col *col, int p, double t,
                                    double g[3])
{
    double e[4], f[4];
    int pieces, k, n = 0;
    if (p == 0) {
        g[0] = -0.5 * t;
        return 1;
    }
    e[0] = -HF__LUT_HALF_PI;
    f[0] = -col->f_end[p];
    if (p == 2 && col->g_c >= 0.0) {
        e[1] = -col->g_c;
        f[1] = -col->f_c;
        e[2] = col->g_c;
        f[2] = col->f_c;
        e[3] = HF__LUT_HALF_PI;
        f[3] = col->f_end[p];
        pieces = 3;
    } else {
        e[1] = HF__LUT_HALF_PI;
        f[1] = col->f_end[p];
        pieces = 1;
    }
    for (k = 0; k < pieces; ++k) {
        double r0 = f[k] - t, r1 = f[k + 1] - t;
        if ((r0 <= 0.0 && r1 >= 0.0) || (r0 >= 0.0 && r1 <= 0.0))
            g[n++] = hf__lut_refine(col->eta1, p, t, e[k], e[k + 1], r0, r1);
    }
    return n;
}

/* Fresnel reflectance for relative index n, given s = sin(x) / n and
   ci = |cos x| (section 6.4); total internal reflection gives 1. */
HF__PRIVATE double hf__lut_rs(double n, double s, double ci)
{
    double ct, r;
    if (s * s >= 1.0) return 1.0;
    ct = HF_SQRT(1.0 - s * s);
    r = (ci - n * ct) / (ci + n * ct);
    return r * r;
}

HF__PRIVATE double hf__lut_rp(double n, double s, double ci)
{
    double ct, r;
    if (s * s >= 1.0) return 1.0;
    ct = HF_SQRT(1.0 - s * s);
    r = (n * ci - ct) / (n * ci + ct);
    return r * r;
}

/* A(p, h) without the absorption: F_ext for p = 0, else
   (1 - F_ext)^2 F_int^(p-1). Also returns cos^2(gamma_t), from which
   T = exp(-2 sigma' (1 + cos 2 gamma_t)) = exp(-4 sigma' cos^2 gamma_t). */
HF__PRIVATE double hf__lut_fresnel_part(const hf__lut_col *col, int p,
                                        double h, double cg, double *ct2)
{
    double e1 = col->eta1, e2 = col->eta2;
    double f_ext = 0.5 * (hf__lut_rs(e1, h / e1, cg) +
                          hf__lut_rp(e2, h / e2, cg));
    double st = h / e1, base;
    *ct2 = 1.0 - st * st;
    if (p == 0) return f_ext;
    base = (1.0 - f_ext) * (1.0 - f_ext);
    if (p == 2) {
        /* inside: relative indices 1/eta', 1/eta'' at gamma_t; s is
           sin(gamma_t) eta' = h and sin(gamma_t) eta'' */
        double ci = HF_SQRT(*ct2);
        base *= 0.5 * (hf__lut_rs(1.0 / e1, h, ci) +
                       hf__lut_rp(1.0 / e2, st * e2, ci));
    }
    return base;
}

/* N_p at wrapped target t (section 6.1) for nsig absorptions, sig4[k] =
   4 sigma_k' (p = 0 ignores them and writes out[0] only). j_min is the
   Jacobian clamp (HF__LUT_J_MIN; tests pass 0 to see the bare model). */
HF__PRIVATE void hf__lut_lobe(const hf__lut_col *col, int p, double t,
                              int exact, double j_min, const double *sig4,
                              int nsig, double *out)
{
    double g[3];
    int n, r, k;
    n = exact ? hf__lut_exact_roots(col, p, t, g)
              : hf__lut_cubic_roots(col->a[p], col->b[p], t, g);
    for (k = 0; k < nsig; ++k) out[k] = 0.0;
    for (r = 0; r < n; ++r) {
        double x = g[r], h, cg, dphi, jac, w, base, ct2;
        if (!(HF_FABS(x) <= HF__LUT_HALF_PI)) continue;
        h = HF_SIN(x);
        cg = HF_COS(x);
        dphi = exact ? hf__lut_dphi_exact(col->eta1, p, x)
                     : 3.0 * col->a[p] * x * x + col->b[p];
        jac = 2.0 * HF_FABS(dphi);
        if (jac < j_min * cg) jac = j_min * cg;
        if (!(jac > 0.0)) continue; /* only j_min = 0 exactly on the fold */
        w = cg / jac; /* = 1 / max(2 |dPhi/dh|, J_MIN) */
        base = hf__lut_fresnel_part(col, p, h, cg, &ct2);
        if (p == 0) {
            out[0] += base * w;
            continue;
        }
        for (k = 0; k < nsig; ++k) {
            double T = HF_EXP(-sig4[k] * ct2);
            out[k] += (p == 2 ? base * T * T : base * T) * w;
        }
    }
}

/* One texel of N at azimuth phi in [0, pi]: targets wrap(phi - p pi). */
HF__PRIVATE void hf__lut_n_texel(const hf__lut_col *col, double phi,
                                 int exact, double j_min, const double *sig4,
                                 int nsig, double *n_r, double *n_tt,
                                 double *n_trt)
{
    double t02 = phi < HF__LUT_PI ? phi : phi - 2.0 * HF__LUT_PI;
    hf__lut_lobe(col, 0, t02, exact, j_min, sig4, 1, n_r);
    hf__lut_lobe(col, 1, phi - HF__LUT_PI, exact, j_min, sig4, nsig, n_tt);
    hf__lut_lobe(col, 2, t02, exact, j_min, sig4, nsig, n_trt);
}

HF__PRIVATE double hf__lut_cd(double x)
{
    x = HF_FABS(x);
    return x > HF__LUT_COS_TD_MIN ? x : HF__LUT_COS_TD_MIN;
}

/* hf_lut_eval_n with the Jacobian clamp as a parameter (tests). */
HF__PRIVATE void hf__lut_eval_n_clamp(const hf_lut_params *p, double cd,
                                      double phi, double j_min,
                                      double out[3])
{
    hf__lut_col col;
    double sig4;
    hf__lut_col_setup(&col, p->eta, hf__lut_cd(cd),
                      p->variant == HF_LUT_EXACT);
    sig4 = 4.0 * p->sigma_a * col.inv_cos_tt;
    hf__lut_n_texel(&col, phi, p->variant == HF_LUT_EXACT, j_min, &sig4, 1,
                    &out[0], &out[1], &out[2]);
}

HFDEF hf_result hf_lut_eval_n(const hf_lut_params *params,
                              double cos_theta_d, double phi, double out[3])
{
    hf_lut_params q;
    const hf_lut_params *p = &q;
    hf_result r = hf__lut_check(params, &q, NULL, 0);
    if (r != HF_OK) return r;
    if (p->model != HF_LUT_MARSCHNER) return HF_ERROR_BAD_PARAMETER;
    if (!out) return HF_ERROR_NULL_POINTER;
    if (!hf__lut_finite(cos_theta_d) || !hf__lut_finite(phi))
        return HF_ERROR_NON_FINITE;
    if (!(cos_theta_d >= -1.0 && cos_theta_d <= 1.0) ||
        !(phi >= 0.0 && phi <= HF__LUT_PI))
        return HF_ERROR_BAD_PARAMETER;
    hf__lut_eval_n_clamp(p, cos_theta_d, phi, HF__LUT_J_MIN, out);
    return HF_OK;
}

/* N (out_trt NULL: RGBA = N_R, N_TT, N_TRT, 1) or the two per-RGB
   textures. Columns i and n-1-i hold the same |cos theta_d|, so only the
   right half is computed and mirrored. */
HF__PRIVATE hf_result hf__lut_bake_n_any(const hf_lut_params *params,
                                         int first_row, int row_count,
                                         float *out, float *out_trt)
{
    hf_lut_params q;
    const hf_lut_params *p = &q;
    hf__lut_col col[HF__LUT_BLOCK];
    double sig4[HF__LUT_BLOCK][3];
    int n, i0, i, j, k, exact, rgb = out_trt != NULL, nsig;
    hf_result r = hf__lut_check_bake(params, &q, first_row, row_count, out,
                                     rgb ? out_trt : out);
    if (r != HF_OK) return r;
    if (p->model == HF_LUT_ENERGY) {
        if (rgb) return HF_ERROR_BAD_PARAMETER;
        hf__lut_bake_n_energy(p, first_row, row_count, out);
        return HF_OK;
    }
    n = p->size;
    exact = p->variant == HF_LUT_EXACT;
    nsig = rgb ? 3 : 1;
    for (i0 = n / 2; i0 < n; i0 += HF__LUT_BLOCK) {
        int i1 = n - i0 < HF__LUT_BLOCK ? n : i0 + HF__LUT_BLOCK;
        for (i = i0; i < i1; ++i) {
            hf__lut_col *c = &col[i - i0];
            hf__lut_col_setup(c, p->eta, hf__lut_cd(hf__lut_axis(i, n)),
                              exact);
            for (k = 0; k < nsig; ++k)
                sig4[i - i0][k] =
                    4.0 * (double)(rgb ? p->sigma_a_rgb[k] : p->sigma_a) *
                    c->inv_cos_tt;
        }
        for (j = first_row; j < first_row + row_count; ++j) {
            double phi = HF_ACOS(hf__lut_axis(j, n));
            size_t row = (size_t)j * (size_t)n;
            for (i = i0; i < i1; ++i) {
                double nr, ntt[3], ntrt[3];
                float v[8];
                float *o0, *o1;
                hf__lut_n_texel(&col[i - i0], phi, exact, HF__LUT_J_MIN,
                                sig4[i - i0], nsig, &nr, ntt, ntrt);
                if (rgb) {
                    for (k = 0; k < 3; ++k) {
                        v[k] = hf__lut_f(ntt[k]);
                        v[4 + k] = hf__lut_f(ntrt[k]);
                    }
                    v[3] = v[7] = hf__lut_f(nr);
                } else {
                    v[0] = hf__lut_f(nr);
                    v[1] = hf__lut_f(ntt[0]);
                    v[2] = hf__lut_f(ntrt[0]);
                    v[3] = 1.0f;
                }
                o0 = out + 4 * (row + (size_t)i);
                o1 = out + 4 * (row + (size_t)(n - 1 - i));
                HF_MEMCPY(o0, v, 4 * sizeof(float));
                HF_MEMCPY(o1, v, 4 * sizeof(float));
                if (rgb) {
                    o0 = out_trt + 4 * (row + (size_t)i);
                    o1 = out_trt + 4 * (row + (size_t)(n - 1 - i));
                    HF_MEMCPY(o0, v + 4, 4 * sizeof(float));
                    HF_MEMCPY(o1, v + 4, 4 * sizeof(float));
                }
            }
        }
    }
    return HF_OK;
}

HFDEF hf_result hf_lut_bake_n(const hf_lut_params *p, int first_row,
                              int row_count, float *out)
{
    return hf__lut_bake_n_any(p, first_row, row_count, out, NULL);
}

HFDEF hf_result hf_lut_bake_n_rgb(const hf_lut_params *p, int first_row,
                                  int row_count, float *out_tt_rgb,
                                  float *out_trt_rgb)
{
    if (!out_trt_rgb) return HF_ERROR_NULL_POINTER;
    return hf__lut_bake_n_any(p, first_row, row_count, out_tt_rgb,
                              out_trt_rgb);
}

/* ---- 9.3 the energy-conserving fibre (HF_LUT_ENERGY) -------------------- */
/* docs/marschner-spec.md sections 14 and 15. Along the outgoing axis (v)
   every texel holds its lobe's mean over the texel's cell, integrated by
   5-point Gauss-Legendre on pieces that follow the lobe. */

#define HF__LUT_COS_R_MIN 1e-2 /* the energy shader's guard on cos theta_r */
#define HF__LUT_GL_STEP 0.0625 /* widest Gauss-Legendre piece in gamma */
#define HF__LUT_NCHUNK 64      /* N cells whose roots are sorted together */
#define HF__LUT_NBRK (2 * 3 * (HF__LUT_NCHUNK + 1) + 4)

/* 5-point Gauss-Legendre nodes and weights on [-1, 1], in closed form. */
HF__PRIVATE void hf__lut_gl5(double x[5], double w[5])
{
    double a = 2.0 * HF_SQRT(10.0 / 7.0), r = HF_SQRT(70.0);
    x[0] = -HF_SQRT(5.0 + a) / 3.0;
    x[1] = -HF_SQRT(5.0 - a) / 3.0;
    x[2] = 0.0;
    x[3] = -x[1];
    x[4] = -x[0];
    w[0] = w[4] = (322.0 - 13.0 * r) / 900.0;
    w[1] = w[3] = (322.0 + 13.0 * r) / 900.0;
    w[2] = 128.0 / 225.0;
}

/* exp(-x) I0(x), x >= 0: the power series below 20, the asymptotic series
   from 20 on (its terms keep falling until k ~ 2x, far below 1e-17). */
HF__PRIVATE double hf__lut_i0e(double x)
{
    double t = 1.0, s = 1.0;
    int k;
    if (x < 20.0) {
        double q = 0.25 * x * x;
        for (k = 1; k < 100 && t > 1e-17 * s; ++k) {
            t *= q / ((double)k * (double)k);
            s += t;
        }
        return s * HF_EXP(-x);
    }
    for (k = 1; k < 40 && t > 1e-17 * s; ++k) {
        t *= (2.0 * k - 1.0) * (2.0 * k - 1.0) / (8.0 * k * x);
        s += t;
    }
    return s / HF_SQRT(2.0 * HF__LUT_PI * x);
}

/* One longitudinal lobe of the energy-conserving fibre. */
typedef struct hf__lut_lobe_e {
    double v;     /* variance (2 beta_p)^2, radians^2 of theta_r */
    double sd;    /* sqrt(v) */
    double den;   /* v (1 - exp(-2 / v)) = 2 v sinh(1 / v) exp(-1 / v) */
    double alpha; /* shift alpha_p (radians of theta_h) */
} hf__lut_lobe_e;

/* Shifts and widths (radians of theta_h) of R, TT, TRT and p >= 3. */
HF__PRIVATE void hf__lut_lobes_ab(const hf_lut_params *p, double alpha[4],
                                  double beta[4])
{
    const double d2r = HF__LUT_PI / 180.0;
    double a = p->alpha_r_deg * d2r, b = p->beta_r_deg * d2r;
    alpha[0] = a;
    alpha[1] = -a / 2.0;
    alpha[2] = -3.0 * a / 2.0;
    alpha[3] = 0.0;
    beta[0] = b;
    beta[1] = b / 2.0;
    beta[2] = 2.0 * b;
    beta[3] = 2.0 * b;
}

HF__PRIVATE void hf__lut_lobes_e(const hf_lut_params *p, hf__lut_lobe_e L[4])
{
    double alpha[4], beta[4];
    int k;
    hf__lut_lobes_ab(p, alpha, beta);
    for (k = 0; k < 4; ++k) {
        double v = 4.0 * beta[k] * beta[k], x;
        /* the same floats as the true variance beyond these ends, with
           every step finite */
        if (!(v >= 4e-300)) v = 4e-300;
        if (v > 1e30) v = 1e30;
        x = 2.0 / v;
        L[k].v = v;
        L[k].sd = HF_SQRT(v);
        L[k].den = v * (x < 1e-4 ? x * (1.0 - x / 2.0 + x * x / 6.0)
                                 : 1.0 - HF_EXP(-x));
        L[k].alpha = alpha[k];
    }
}

/* d'Eon's lobe, exp(-sin ti sin tr / v) I0(cos ti cos tr / v) /
   (2 v sinh(1 / v)), for ti in [-pi/2, pi/2] (the shifted incident
   inclination folded back: same sine, |cosine|): a density per unit of
   sin(theta_r) over [-1, 1] for every ti. As written here nothing
   overflows: exp(-sin ti sin tr / v) I0(a) exp(-1 / v) =
   i0e(a) exp((cos(ti + tr) - 1) / v), a = cos ti cos tr / v, and
   cos(ti + tr) - 1 = -2 sin^2((ti + tr) / 2) loses no digits. */
HF__PRIVATE double hf__lut_deon(const hf__lut_lobe_e *L, double ti,
                                double tr)
{
    double h = HF_SIN(0.5 * (ti + tr));
    double a = HF_COS(ti) * HF_COS(tr) / L->v;
    if (a < 0.0) a = 0.0;
    return hf__lut_i0e(a) * HF_EXP(-2.0 * h * h / L->v) / L->den;
}

/* The mean of one lobe over theta_r in [t0, t1] (a cell of sin theta_r,
   width ds): pieces no wider than half the lobe's width inside 12 widths
   of its peak, nothing outside (below exp(-72) of the peak). */
HF__PRIVATE double hf__lut_m_cell(const hf__lut_lobe_e *L, double ti,
                                  double t0, double t1, double ds,
                                  const double *gx, const double *gw)
{
    double lo = -ti - 12.0 * L->sd, hi = -ti + 12.0 * L->sd, sum = 0.0, len;
    int m, k, q;
    if (lo < t0) lo = t0;
    if (hi > t1) hi = t1;
    if (!(hi > lo)) return 0.0;
    len = hi - lo;
    m = len > 32.0 * L->sd ? 64 : (int)HF_CEIL(len / (0.5 * L->sd));
    if (m < 1) m = 1;
    for (k = 0; k < m; ++k) {
        double a = lo + len * k / m, b = k + 1 == m ? hi : lo + len * (k + 1) / m;
        double c = 0.5 * (a + b), hl = 0.5 * (b - a);
        for (q = 0; q < 5; ++q) {
            double tr = c + hl * gx[q];
            sum += gw[q] * hl * hf__lut_deon(L, ti, tr) * HF_COS(tr);
        }
    }
    return sum / ds;
}

/* M of HF_LUT_ENERGY: texel (i, j) = the mean of each lobe over sin(theta_r)
   in [(2j - n) / n, (2j + 2 - n) / n], theta_i at the column's centre. */
HF__PRIVATE void hf__lut_bake_m_energy(const hf_lut_params *p, int first_row,
                                       int row_count, float *out)
{
    hf__lut_lobe_e L[4];
    double ti[HF__LUT_BLOCK][4], gx[5], gw[5];
    int n = p->size, i0, i, j, k;
    hf__lut_lobes_e(p, L);
    hf__lut_gl5(gx, gw);
    for (i0 = 0; i0 < n; i0 += HF__LUT_BLOCK) {
        int i1 = n - i0 < HF__LUT_BLOCK ? n : i0 + HF__LUT_BLOCK;
        for (i = i0; i < i1; ++i) {
            double t = HF_ASIN(hf__lut_axis(i, n));
            /* light at theta_i - 2 alpha_p puts the lobe's peak at
               theta_r = 2 alpha_p - theta_i, theta_h = alpha_p */
            for (k = 0; k < 4; ++k)
                ti[i - i0][k] = HF_ASIN(HF_SIN(t - 2.0 * L[k].alpha));
        }
        for (j = first_row; j < first_row + row_count; ++j) {
            double t0 = HF_ASIN((double)(2 * j - n) / (double)n);
            double t1 = HF_ASIN((double)(2 * j + 2 - n) / (double)n);
            float *o = out + 4 * ((size_t)j * (size_t)n + (size_t)i0);
            for (i = i0; i < i1; ++i, o += 4)
                for (k = 0; k < 4; ++k)
                    o[k] = hf__lut_f(hf__lut_m_cell(&L[k], ti[i - i0][k], t0,
                                                    t1, 2.0 / n, gx, gw));
        }
    }
}

/* Attenuation of the energy-conserving fibre at offset h = sin(gamma):
   one Fresnel factor F (section 6.4's F_ext) at every interface, the
   absorption T = exp(-sig * e) along the chord, e = 2 cos(gamma_t) /
   cos(theta_t). Returns F and e. */
HF__PRIVATE double hf__lut_fresnel_e(const hf__lut_col *col, double g,
                                     double *e)
{
    double h = HF_SIN(g), cg = HF_COS(g), st = h / col->eta1;
    *e = 2.0 * HF_SQRT(1.0 - st * st) * col->inv_cos_tt;
    return 0.5 * (hf__lut_rs(col->eta1, h / col->eta1, cg) +
                  hf__lut_rp(col->eta2, h / col->eta2, cg));
}

/* A_p for p = 0, 1, 2 and the sum over p >= 3, given F and T. */
HF__PRIVATE void hf__lut_atten_e(double F, double T, double A[4])
{
    double t = (1.0 - F) * (1.0 - F);
    A[0] = F;
    A[1] = t * T;
    A[2] = A[1] * F * T;
    A[3] = A[2] * F * T / (1.0 - F * T);
}

/* The R_p kink: gamma where |h| = eta'' (eta'' < 1), else pi/2. */
HF__PRIVATE double hf__lut_kink(const hf__lut_col *col)
{
    return col->eta2 < 1.0 ? HF_ASIN(col->eta2) : HF__LUT_HALF_PI;
}

/* Nodes g and weights w (Gauss-Legendre weight times the piece's half
   width, times cos(gamma): dh = cos(gamma) dgamma) for an integral over h
   of gamma in [a, b] (0 <= a < b <= pi/2), in pieces no wider than
   HF__LUT_GL_STEP. Where b is the kink (sqrt_b) R_p goes like
   sqrt(b - gamma), so the pieces are in t = sqrt(b - gamma), where the
   integrand is smooth. Returns the count, at most HF__LUT_MAX_NODES. */
#define HF__LUT_MAX_NODES 130 /* 5 * ceil((pi / 2) / HF__LUT_GL_STEP) */
HF__PRIVATE int hf__lut_nodes(double a, double b, int sqrt_b,
                              const double *gx, const double *gw, double *g,
                              double *w)
{
    double lo = sqrt_b ? 0.0 : a, hi = sqrt_b ? HF_SQRT(b - a) : b;
    double len = hi - lo;
    int m = (int)HF_CEIL(len / HF__LUT_GL_STEP), k, q, nn = 0;
    if (m < 1) m = 1;
    for (k = 0; k < m; ++k) {
        double x0 = lo + len * k / m, x1 = k + 1 == m ? hi : lo + len * (k + 1) / m;
        double c = 0.5 * (x0 + x1), hl = 0.5 * (x1 - x0);
        for (q = 0; q < 5; ++q) {
            double x = c + hl * gx[q], gg = sqrt_b ? b - x * x : x;
            g[nn] = gg;
            w[nn++] = gw[q] * hl * (sqrt_b ? 2.0 * x : 1.0) * HF_COS(gg);
        }
    }
    return nn;
}

/* Energy of the p >= 3 lobe, 1/2 the integral of A_3 over h in [-1, 1]. */
HF__PRIVATE double hf__lut_e3(const hf__lut_col *col, double sig,
                              const double *gx, const double *gw)
{
    double ends[3], sum = 0.0, g[HF__LUT_MAX_NODES], w[HF__LUT_MAX_NODES];
    int s, k, nn;
    ends[0] = 0.0;
    ends[1] = hf__lut_kink(col);
    ends[2] = HF__LUT_HALF_PI;
    for (s = 0; s < 2; ++s) {
        if (!(ends[s + 1] > ends[s])) continue;
        nn = hf__lut_nodes(ends[s], ends[s + 1], s == 0 && col->eta2 < 1.0,
                           gx, gw, g, w);
        for (k = 0; k < nn; ++k) {
            double e, A[4], F = hf__lut_fresnel_e(col, g[k], &e);
            hf__lut_atten_e(F, HF_EXP(-sig * e), A);
            sum += w[k] * A[3];
        }
    }
    return sum;
}

/* Exit azimuth: cos(Phi(p, gamma)) (cubic or exact). */
HF__PRIVATE double hf__lut_cos_exit(const hf__lut_col *col, int p, int exact,
                                    double g)
{
    double t = exact ? hf__lut_phi_exact(col->eta1, p, g)
                     : (col->a[p] * g * g + col->b[p]) * g;
    return (p & 1) ? -HF_COS(t) : HF_COS(t);
}

/* Roots gamma in (0, pi/2) of |Phi(p, gamma)| = phi_b (mod 2 pi), added
   to brk. */
HF__PRIVATE int hf__lut_exit_roots(const hf__lut_col *col, int p, int exact,
                                   double phi_b, double *brk, int nb)
{
    int sg, r;
    for (sg = -1; sg <= 1; sg += 2) {
        double t = sg * phi_b - p * HF__LUT_PI, g[3];
        int nr;
        while (t >= HF__LUT_PI) t -= 2.0 * HF__LUT_PI;
        while (t < -HF__LUT_PI) t += 2.0 * HF__LUT_PI;
        nr = exact ? hf__lut_exact_roots(col, p, t, g)
                   : hf__lut_cubic_roots(col->a[p], col->b[p], t, g);
        for (r = 0; r < nr; ++r)
            if (g[r] > 0.0 && g[r] < HF__LUT_HALF_PI) brk[nb++] = g[r];
    }
    return nb;
}

/* Ascending heap sort (no allocation, the same order every time). */
HF__PRIVATE void hf__lut_sort(double *a, int n)
{
    int start, end;
    for (start = n / 2 - 1, end = n; end > 1;) {
        int root, child;
        double t;
        if (start >= 0) {
            root = start--;
        } else {
            --end;
            t = a[0];
            a[0] = a[end];
            a[end] = t;
            root = 0;
        }
        while ((child = 2 * root + 1) < end) {
            if (child + 1 < end && a[child + 1] > a[child]) ++child;
            if (!(a[child] > a[root])) break;
            t = a[root];
            a[root] = a[child];
            a[child] = t;
            root = child;
        }
    }
}

/* cos(phi) at the edge b of the N cells: (2b - n) / n, -1 and 1 exactly. */
HF__PRIVATE double hf__lut_cell_edge(int b, int n)
{
    return (double)(2 * b - n) / (double)n;
}

/* One column of N of HF_LUT_ENERGY, cells [j0, j1) (at most
   HF__LUT_NCHUNK): e[4 (j - j0) + p] = the energy of lobe p leaving with
   cos(phi) in cell j (both signs of phi), p = 0, 1, 2. Every interval of
   gamma between consecutive roots of the cells' edges falls in one cell;
   the intervals of cell j are bounded by the roots of its own two edges
   (and the kink), so the sums do not depend on the chunking. */
HF__PRIVATE void hf__lut_n_cells(const hf__lut_col *col, int exact, double sig,
                                 int n, int j0, int j1, const double *gx,
                                 const double *gw, double *e)
{
    double brk[HF__LUT_NBRK], g[HF__LUT_MAX_NODES], w[HF__LUT_MAX_NODES];
    double kink = hf__lut_kink(col);
    int p, b, k, nb;
    for (k = 0; k < 4 * (j1 - j0); ++k) e[k] = 0.0;
    for (p = 0; p < 3; ++p) {
        nb = 0;
        brk[nb++] = 0.0;
        brk[nb++] = HF__LUT_HALF_PI;
        if (col->eta2 < 1.0) brk[nb++] = kink;
        for (b = j0; b <= j1; ++b) {
            double c = hf__lut_cell_edge(b, n);
            nb = hf__lut_exit_roots(col, p, exact, HF_ACOS(c), brk, nb);
        }
        hf__lut_sort(brk, nb);
        for (k = 0; k + 1 < nb; ++k) {
            double g0 = brk[k], g1 = brk[k + 1], sum = 0.0, cm;
            int jc, nn, r;
            if (!(g1 > g0)) continue;
            cm = hf__lut_cos_exit(col, p, exact, 0.5 * (g0 + g1));
            jc = (int)HF_FLOOR((cm + 1.0) * 0.5 * n);
            if (jc > n - 1) jc = n - 1;
            if (jc < j0 || jc >= j1) continue;
            nn = hf__lut_nodes(g0, g1, col->eta2 < 1.0 && g1 == kink, gx, gw,
                               g, w);
            for (r = 0; r < nn; ++r) {
                double ee, A[4], F = hf__lut_fresnel_e(col, g[r], &ee);
                hf__lut_atten_e(F, p ? HF_EXP(-sig * ee) : 1.0, A);
                sum += w[r] * A[p];
            }
            e[4 * (jc - j0) + p] += sum;
        }
    }
}

/* N of HF_LUT_ENERGY: columns by cos(theta_i) (the right half computed,
   the left mirrored, as for N), each cell's mean over phi. */
HF__PRIVATE void hf__lut_bake_n_energy(const hf_lut_params *p, int first_row,
                                       int row_count, float *out)
{
    double gx[5], gw[5], e[4 * HF__LUT_NCHUNK];
    int n = p->size, exact = p->variant == HF_LUT_EXACT, i, j0, j, k;
    hf__lut_gl5(gx, gw);
    for (i = n / 2; i < n; ++i) {
        hf__lut_col col;
        double n3;
        hf__lut_col_setup(&col, p->eta, hf__lut_cd(hf__lut_axis(i, n)), exact);
        n3 = hf__lut_e3(&col, p->sigma_a, gx, gw) / (2.0 * HF__LUT_PI);
        for (j0 = first_row; j0 < first_row + row_count; j0 += HF__LUT_NCHUNK) {
            int j1 = first_row + row_count - j0 < HF__LUT_NCHUNK
                         ? first_row + row_count
                         : j0 + HF__LUT_NCHUNK;
            hf__lut_n_cells(&col, exact, p->sigma_a, n, j0, j1, gx, gw, e);
            for (j = j0; j < j1; ++j) {
                size_t row = (size_t)j * (size_t)n;
                double dphi = HF_ACOS(hf__lut_cell_edge(j, n)) -
                              HF_ACOS(hf__lut_cell_edge(j + 1, n));
                float v[4];
                for (k = 0; k < 3; ++k)
                    v[k] = hf__lut_f(e[4 * (j - j0) + k] / (2.0 * dphi));
                v[3] = hf__lut_f(n3);
                HF_MEMCPY(out + 4 * (row + (size_t)i), v, sizeof v);
                HF_MEMCPY(out + 4 * (row + (size_t)(n - 1 - i)), v, sizeof v);
            }
        }
    }
}

/* ---- 9.4 white furnace -------------------------------------------------- */

/* A texture read as GL_LINEAR with clamp-to-edge does it, in double. */
HF__PRIVATE void hf__lut_tex(const float *t, int n, double u, double v,
                             double o[4])
{
    double x = u * n - 0.5, y = v * n - 0.5, fx, fy;
    double xf = HF_FLOOR(x), yf = HF_FLOOR(y);
    int i0 = (int)xf, j0 = (int)yf, i1 = i0 + 1, j1 = j0 + 1, c;
    const float *a, *b, *d, *e;
    fx = x - xf;
    fy = y - yf;
    i0 = i0 < 0 ? 0 : (i0 > n - 1 ? n - 1 : i0);
    i1 = i1 < 0 ? 0 : (i1 > n - 1 ? n - 1 : i1);
    j0 = j0 < 0 ? 0 : (j0 > n - 1 ? n - 1 : j0);
    j1 = j1 < 0 ? 0 : (j1 > n - 1 ? n - 1 : j1);
    a = t + 4 * ((size_t)j0 * (size_t)n + (size_t)i0);
    b = t + 4 * ((size_t)j0 * (size_t)n + (size_t)i1);
    d = t + 4 * ((size_t)j1 * (size_t)n + (size_t)i0);
    e = t + 4 * ((size_t)j1 * (size_t)n + (size_t)i1);
    for (c = 0; c < 4; ++c)
        o[c] = ((double)a[c] * (1.0 - fx) + (double)b[c] * fx) * (1.0 - fy) +
               ((double)d[c] * (1.0 - fx) + (double)e[c] * fx) * fy;
}

HFDEF hf_result hf_lut_furnace(const hf_lut_params *params, const float *m,
                               const float *nt, double theta_i,
                               double *albedo)
{
    hf_lut_params q;
    const hf_lut_params *p = &q;
    double si, ci, sum = 0.0, ds, dp;
    size_t i, count;
    int n, K, a, b, c;
    hf_result r = hf__lut_check(params, &q, NULL, 1);
    if (r != HF_OK) return r;
    if (!m || !nt || !albedo) return HF_ERROR_NULL_POINTER;
    if (!hf__lut_finite(theta_i)) return HF_ERROR_NON_FINITE;
    if (!(theta_i >= -HF__LUT_HALF_PI && theta_i <= HF__LUT_HALF_PI))
        return HF_ERROR_BAD_PARAMETER;
    n = p->size;
    count = 4u * (size_t)n * (size_t)n;
    for (i = 0; i < count; ++i)
        if (!hf__finitef(m[i]) || !hf__finitef(nt[i]))
            return HF_ERROR_NON_FINITE;
    K = 4 * n > 1024 ? 4 * n : 1024;
    ds = 2.0 / K;
    dp = HF__LUT_PI / K;
    si = HF_SIN(theta_i);
    ci = HF_COS(theta_i);
    if (p->model == HF_LUT_ENERGY) {
        /* N does not depend on theta_r, M not on phi: two sums */
        double ms[4] = {0, 0, 0, 0}, ns[4] = {0, 0, 0, 0}, o[4];
        for (a = 0; a < K; ++a) {
            double s = -1.0 + (a + 0.5) * ds, cr = HF_SQRT(1.0 - s * s);
            double w = ds * cr / (cr > HF__LUT_COS_R_MIN ? cr : HF__LUT_COS_R_MIN);
            hf__lut_tex(m, n, si * 0.5 + 0.5, s * 0.5 + 0.5, o);
            for (c = 0; c < 4; ++c) ms[c] += w * o[c];
        }
        for (b = 0; b < K; ++b) {
            double phi = (b + 0.5) * dp;
            hf__lut_tex(nt, n, ci * 0.5 + 0.5, HF_COS(phi) * 0.5 + 0.5, o);
            for (c = 0; c < 4; ++c) ns[c] += dp * o[c];
        }
        for (c = 0; c < 4; ++c) sum += ms[c] * ns[c];
    } else {
        for (a = 0; a < K; ++a) {
            double s = -1.0 + (a + 0.5) * ds, cr = HF_SQRT(1.0 - s * s);
            double M[4], inv, row = 0.0;
            hf__lut_tex(m, n, si * 0.5 + 0.5, s * 0.5 + 0.5, M);
            inv = M[3] * M[3] > 1e-2 ? 1.0 / (M[3] * M[3]) : 1e2;
            for (b = 0; b < K; ++b) {
                double N[4], phi = (b + 0.5) * dp;
                hf__lut_tex(nt, n, M[3] * 0.5 + 0.5, HF_COS(phi) * 0.5 + 0.5, N);
                row += M[0] * N[0] + M[1] * N[1] + M[2] * N[2];
            }
            sum += row * inv * cr * ds * dp;
        }
    }
    *albedo = 2.0 * sum; /* phi in (-pi, 0) mirrors (0, pi) */
    return HF_OK;
}

/* ---- 9.5 dual scattering tables ----------------------------------------- */

/* Round a value of either sign to float once, held to +-FLT_MAX. */
HF__PRIVATE float hf__lut_fs(double x)
{
    if (x > HF__LUT_FLT_MAX) return (float)HF__LUT_FLT_MAX;
    if (x < -HF__LUT_FLT_MAX) return (float)-HF__LUT_FLT_MAX;
    return (float)x;
}

#define HF__LUT_DUAL_NODES 400 /* 5 Gauss-Legendre nodes on <= 80 pieces */

HFDEF hf_result hf_lut_bake_dual(const hf_lut_params *params, int first_row,
                                 int row_count, float *out)
{
    hf_lut_params q;
    const hf_lut_params *p = &q;
    double gx[5], gw[5], alpha[4], beta[4];
    double nw[HF__LUT_DUAL_NODES], nf[HF__LUT_DUAL_NODES],
        ne[HF__LUT_DUAL_NODES];
    unsigned char fwd[HF__LUT_DUAL_NODES];
    size_t plane;
    int n, exact, i, j, k;
    hf_result r = hf__lut_check_bake(params, &q, first_row, row_count, out, out);
    if (r != HF_OK) return r;
    n = p->size;
    plane = 4u * (size_t)n * (size_t)n;
    exact = p->variant == HF_LUT_EXACT;
    hf__lut_gl5(gx, gw);
    hf__lut_lobes_ab(p, alpha, beta);
    for (j = first_row; j < first_row + row_count; ++j) {
        hf__lut_col col;
        double brk[16], kink, g[HF__LUT_MAX_NODES], w[HF__LUT_MAX_NODES];
        int nb = 0, nn = 0, s, pp;
        hf__lut_col_setup(&col, p->eta,
                          hf__lut_cd((double)(2 * j + 1) / (double)(2 * n)),
                          exact);
        /* where a lobe turns from backward (cos phi > 0) to forward: R at
           gamma = pi/4, TT and TRT where |Phi| = pi/2; and the kink */
        brk[nb++] = 0.0;
        brk[nb++] = HF__LUT_HALF_PI;
        brk[nb++] = 0.25 * HF__LUT_PI;
        kink = hf__lut_kink(&col);
        if (col.eta2 < 1.0) brk[nb++] = kink;
        for (pp = 1; pp < 3; ++pp)
            nb = hf__lut_exit_roots(&col, pp, exact, HF__LUT_HALF_PI, brk, nb);
        hf__lut_sort(brk, nb);
        for (s = 0; s + 1 < nb; ++s) {
            double g0 = brk[s], g1 = brk[s + 1], mid;
            unsigned char bits = 0;
            int m;
            if (!(g1 > g0)) continue;
            mid = 0.5 * (g0 + g1);
            for (pp = 0; pp < 3; ++pp)
                if (hf__lut_cos_exit(&col, pp, exact, mid) < 0.0)
                    bits |= (unsigned char)(1u << pp);
            m = hf__lut_nodes(g0, g1, col.eta2 < 1.0 && g1 == kink, gx, gw, g,
                              w);
            for (k = 0; k < m && nn < HF__LUT_DUAL_NODES; ++k) {
                nf[nn] = hf__lut_fresnel_e(&col, g[k], &ne[nn]);
                nw[nn] = w[k];
                fwd[nn++] = bits;
            }
        }
        for (i = 0; i < n; ++i) {
            double u = (double)(2 * i + 1) / (double)(2 * n);
            double sig = u / (1.0 - u), af[4] = {0, 0, 0, 0},
                   ab[4] = {0, 0, 0, 0};
            double Af = 0.0, Ab = 0.0, mf = 0.0, mb = 0.0, vf = 0.0, vb = 0.0;
            double af2, qq, A_b, d_b, s_b, v[12];
            size_t at = 4 * ((size_t)j * (size_t)n + (size_t)i);
            for (k = 0; k < nn; ++k) {
                double A[4];
                hf__lut_atten_e(nf[k], HF_EXP(-sig * ne[k]), A);
                for (pp = 0; pp < 3; ++pp) {
                    if (fwd[k] & (1u << pp))
                        af[pp] += nw[k] * A[pp];
                    else
                        ab[pp] += nw[k] * A[pp];
                }
                af[3] += 0.5 * nw[k] * A[3]; /* p >= 3: uniform in phi */
                ab[3] += 0.5 * nw[k] * A[3];
            }
            for (pp = 0; pp < 4; ++pp) {
                Af += af[pp];
                Ab += ab[pp];
                if (af[pp] > 0.0) {
                    mf += af[pp] * alpha[pp];
                    vf += af[pp] * beta[pp] * beta[pp];
                }
                if (ab[pp] > 0.0) {
                    mb += ab[pp] * alpha[pp];
                    vb += ab[pp] * beta[pp] * beta[pp];
                }
            }
            if (Af > 0.0) {
                mf /= Af;
                vf /= Af;
            }
            if (Ab > 0.0) {
                mb /= Ab;
                vb /= Ab;
            }
            /* Zinke et al. eqs. 14, 16, 17 (section 16) */
            af2 = Af * Af;
            qq = 1.0 - af2;
            if (qq < 1e-12) qq = 1e-12;
            A_b = Ab * af2 / qq + Ab * Ab * Ab * af2 / (qq * qq * qq);
            d_b = mb * (1.0 - 2.0 * Ab * Ab / (qq * qq)) +
                  mf * (2.0 * qq * qq + 4.0 * af2 * Ab * Ab) / (qq * qq * qq);
            s_b = Ab > 0.0
                      ? (1.0 + HF_LUT_DUAL_DB * af2) *
                            (Ab * HF_SQRT(2.0 * vf + vb) +
                             Ab * Ab * Ab * HF_SQRT(2.0 * vf + 3.0 * vb)) /
                            (Ab + Ab * Ab * Ab)
                      : 0.0;
            v[0] = Af;
            v[1] = mf;
            v[2] = HF_SQRT(vf);
            v[4] = Ab;
            v[5] = mb;
            v[6] = HF_SQRT(vb);
            v[8] = A_b;
            v[9] = d_b;
            v[10] = s_b;
            v[3] = v[7] = v[11] = 1.0;
            for (k = 0; k < 12; ++k)
                out[plane * (size_t)(k / 4) + at + (size_t)(k & 3)] =
                    hf__lut_fs(v[k]);
        }
    }
    return HF_OK;
}

/* ---- 9.6 8-bit conversion ----------------------------------------------- */

HFDEF hf_result hf_lut_to_u8(const float *rgba, int n,
                             const float *scales_in,
                             unsigned char *out_rgba8, float scales_out[4])
{
    float mx[4] = {0.0f, 0.0f, 0.0f, 0.0f}, sc[4];
    size_t count, i;
    int c;
    if (!rgba || !out_rgba8) return HF_ERROR_NULL_POINTER;
    if (n < 1 || n > HF_LUT_MAX_SIZE) return HF_ERROR_BAD_COUNT;
    count = 4u * (size_t)n * (size_t)n; /* <= 2^26: no overflow */
    if (scales_in)
        for (c = 0; c < 4; ++c)
            if (!hf__finitef(scales_in[c]) || !(scales_in[c] > 0.0f))
                return HF_ERROR_BAD_PARAMETER;
    for (i = 0; i < count; ++i) {
        float x = rgba[i];
        if (!hf__finitef(x)) return HF_ERROR_NON_FINITE;
        if (x > mx[i & 3]) mx[i & 3] = x;
    }
    for (c = 0; c < 4; ++c)
        sc[c] = scales_in ? scales_in[c] : (mx[c] > 0.0f ? mx[c] : 1.0f);
    for (i = 0; i < count; ++i) {
        double y = (double)rgba[i] / (double)sc[i & 3];
        y = y < 0.0 ? 0.0 : (y > 1.0 ? 1.0 : y);
        /* floor(255 y + 0.5); the argument is >= 0, so truncation floors */
        out_rgba8[i] = (unsigned char)(255.0 * y + 0.5);
    }
    if (scales_out)
        for (c = 0; c < 4; ++c) scales_out[c] = sc[c];
    return HF_OK;
}

/* ---- 10. the fur object ------------------------------------------------- */

struct hf_fur {
    hf_allocator alloc;
    int P, vertex_count, base_triangle_count;
    int guide_count, pure_count, lod_count;
    int strand_count, drawn, triangle_count;
    int lod_sim, simd, nontemporal;
    float lod, width_scale, lod_threshold, clump;
    hf_rope_params rope[HF_FUR_ROPE_SETS]; /* the parameter sets in use */
    unsigned char *rope_of;                /* per guide: its set */
    unsigned char *user_mode; /* per guide: hf_fur_set_mode's choice */
    float *strand_width;   /* width_variation > 0: per strand multiplier */
    float *strand_clump;   /* clump_map: per strand clump strength */
    uint32_t *leader;      /* clump_size > 0: per strand, the strand whose
                              shape it clumps to (itself for a leader) */
    hf_ropes *ropes;
    hf_grid *grid;        /* NULL: no hair-hair interaction */
    float *guide_points;  /* guide_count * P * 3, rope-major */
    float *strand_points; /* strand_count * P * 3 */
    hf_strand *strands;
    hf_strand_binding *bindings;     /* per strand, over all guides */
    hf_strand_binding *lod_bindings; /* per LOD guide, over pure guides */
    float *strand_lengths, *strand_rgba, *strand_uv, *strand_c3x;
    hf_tess_vertex *added; /* lod_count records */
    uint32_t *ref;         /* 3 per guide: root vertex, tangent edge end,
                              third corner (face normal without normals) */
    float *root_pos, *root_nrm, *root_tan; /* 3 per guide, per frame */
    float *rest_frame;     /* 9 per guide: root position, normal and
                              tangent at creation (hf_fur_set_transform) */
    int groom;             /* made by hf_fur_create_groom: no mesh */
    float *scalp_bind;     /* groom with a scalp: per guide u, v on its
                              triangle (ref), then the triangle's rest
                              point, normal and tangent (11 floats) */
    float *offsets;        /* groom: P * 3 per strand, its rest points
                              minus its guides' blend, in their rest frames */
    float *rest_seg;       /* keep_length: P - 1 per strand, its segments'
                              lengths at creation */
};

/* Allocation that remembers nothing: hf_fur_destroy frees each array by
   name, and every pointer starts NULL, so a failed create unwinds by
   calling destroy. hf__fur_lines: the guide and strand points, which the
   interpolation reads and writes sixteen floats at a time (hf__alloc64). */
HF__PRIVATE void *hf__fur_alloc(hf_fur *f, size_t count, size_t size,
                                int lines, hf_result *r)
{
    size_t bytes;
    void *p;
    if (*r != HF_OK) return NULL;
    if (!hf__mul_size(count ? count : 1, size, &bytes)) {
        *r = HF_ERROR_OVERFLOW;
        return NULL;
    }
    p = lines ? hf__alloc64(&f->alloc, bytes) : hf__alloc(&f->alloc, bytes);
    if (!p) *r = HF_ERROR_OUT_OF_MEMORY;
    return p;
}

HF__PRIVATE void *hf__fur_array(hf_fur *f, size_t count, size_t size,
                                hf_result *r)
{
    return hf__fur_alloc(f, count, size, 0, r);
}

HF__PRIVATE float *hf__fur_lines(hf_fur *f, size_t count, hf_result *r)
{
    return (float *)hf__fur_alloc(f, count, sizeof(float), 1, r);
}

HFDEF void hf_fur_destroy(hf_fur *f)
{
    hf_allocator a;
    if (!f) return;
    a = f->alloc;
    hf_ropes_destroy(f->ropes);
    hf_grid_destroy(f->grid);
    hf__free64(&a, f->guide_points);
    hf__free64(&a, f->strand_points);
    hf__free(&a, f->strands);
    hf__free(&a, f->bindings);
    hf__free(&a, f->lod_bindings);
    hf__free(&a, f->strand_lengths);
    hf__free(&a, f->strand_rgba);
    hf__free(&a, f->strand_uv);
    hf__free(&a, f->strand_c3x);
    hf__free(&a, f->added);
    hf__free(&a, f->ref);
    hf__free(&a, f->root_pos);
    hf__free(&a, f->root_nrm);
    hf__free(&a, f->root_tan);
    hf__free(&a, f->rest_frame);
    hf__free(&a, f->offsets);
    hf__free(&a, f->rope_of);
    hf__free(&a, f->user_mode);
    hf__free(&a, f->leader);
    hf__free(&a, f->strand_width);
    hf__free(&a, f->strand_clump);
    hf__free(&a, f->scalp_bind);
    hf__free(&a, f->rest_seg);
    hf__free(&a, f);
}

/* Binding of barycentric weights over three guides, with the length ratio
   that lets the blend keep the strand's own length. */
HF__PRIVATE void hf__bind(hf_strand_binding *b, const uint32_t *g,
                          const float *w, float own_length,
                          const float *guide_lengths)
{
    float blended = 0.0f;
    int k;
    for (k = 0; k < 3; ++k) {
        b->guide[k] = g[k];
        b->weight[k] = w[k];
        blended += w[k] * guide_lengths[g[k]];
    }
    b->length_scale = blended > 1e-20f ? own_length / blended : 1.0f;
    if (b->length_scale == 0.0f) b->length_scale = 1e-20f; /* 0 means 1 */
}

/* What hf_fur_create builds on the way and frees on both exits. */
typedef struct hf__fur_build {
    hf_fur_desc desc;    /* resolved */
    hf_rope_params rope; /* resolved, desc.rope_params points here */
    hf_mesh gm;          /* the rest mesh with normals, then the guide mesh
                            (tessellated positions, uvs, triangles) */
    hf_tess_output to;
    hf_guide_params gp;
    float *normals, *tess_pos, *tess_uv;
    float *rest_points, *guide_len, *guide_nrm;
    uint32_t *tess_idx, *tess_base, *guide_of;
} hf__fur_build;

HF__PRIVATE void hf__fur_build_free(const hf_allocator *a, hf__fur_build *b)
{
    hf__free(a, b->normals);
    hf__free(a, b->tess_pos);
    hf__free(a, b->tess_uv);
    hf__free(a, b->tess_idx);
    hf__free(a, b->tess_base);
    hf__free(a, b->rest_points);
    hf__free(a, b->guide_len);
    hf__free(a, b->guide_nrm);
    hf__free(a, b->guide_of);
}

/* The resolved description's own fields (the stages check the rest). */
/* Guide curves and styling: counts, points and values. */
HF__PRIVATE hf_result hf__fur_style_check(const hf_fur_desc *d, hf_diag *diag)
{
    const float v[8] = {d->curl_radius, d->curl_turns, d->wave_amplitude,
                        d->wave_count, d->frizz, d->clump_size,
                        d->color_variation, d->width_variation};
    static const char *const names[8] = {"curl_radius", "curl_turns",
                                         "wave_amplitude", "wave_count",
                                         "frizz", "clump_size",
                                         "color_variation", "width_variation"};
    const hf_map *maps[7];
    hf_result r;
    long long total = 0;
    int i, k;
    for (i = 0; i < 8; ++i)
        if (!hf__finitef(v[i]) || v[i] < 0.0f || v[i] > HF_ROPE_MAX_COORD ||
            (i >= 6 && v[i] > 1.0f))
            return hf__fail(diag, HF_ERROR_BAD_PARAMETER, names[i], -1,
                            "%s %g is negative, non-finite or too large%s",
                            names[i], (double)v[i],
                            i >= 6 ? " (at most 1)" : "");
    maps[0] = d->curl_map; maps[1] = d->wave_map; maps[2] = d->frizz_map;
    maps[3] = d->clump_map; maps[4] = d->color_variation_map;
    maps[5] = d->width_variation_map;
    maps[6] = d->clump_size_map;
    for (i = 0; i < 7; ++i) {
        if (!maps[i]) continue;
        if (!d->mesh.uvs)
            return hf__fail(diag, HF_ERROR_NULL_POINTER, "mesh.uvs", -1,
                            "a styling map needs mesh UVs");
        if ((r = hf_map_validate(maps[i], diag)) != HF_OK) return r;
    }
    if (d->guide_curve_count < 0)
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "guide_curve_count", -1,
                        "guide_curve_count %d is negative",
                        d->guide_curve_count);
    if (d->guide_curve_count == 0) return HF_OK;
    if (!d->guide_curves || !d->guide_curve_points)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "guide_curves", -1,
                        "guide_curve_count %d with a NULL array",
                        d->guide_curve_count);
    for (i = 0; i < d->guide_curve_count; ++i) {
        int n = d->guide_curve_points[i];
        const float *p;
        double len = 0.0;
        if (n < 2 || n > (1 << 24))
            return hf__fail(diag, HF_ERROR_BAD_COUNT, "guide_curve_points", i,
                            "curve %d has %d points (2 .. 16777216)", i, n);
        p = d->guide_curves + 3 * total;
        for (k = 0; k < 3 * n; ++k)
            if (!hf__finitef(p[k]) || HF_FABS(p[k]) > HF_ROPE_MAX_COORD)
                return hf__fail(diag, HF_ERROR_NON_FINITE, "guide_curves",
                                total + k / 3, "curve %d, point %d is "
                                "non-finite or too large", i, k / 3);
        for (k = 1; k < n; ++k) {
            double dx = p[3 * k] - p[3 * k - 3], dy = p[3 * k + 1] - p[3 * k - 2],
                   dz = p[3 * k + 2] - p[3 * k - 1];
            len += HF_SQRT(dx * dx + dy * dy + dz * dz);
        }
        if (!(len > 0.0))
            return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "guide_curves", i,
                            "curve %d has zero length", i);
        total += n;
        if (total > 0x7fffffffLL)
            return hf__fail(diag, HF_ERROR_OVERFLOW, "guide_curve_points", i,
                            "more than 2^31 curve points");
    }
    return HF_OK;
}

/* The options a fur and a groom share: the grid's resolution (0: none)
   and keep_length. */
HF__PRIVATE hf_result hf__fur_options_check(int grid_resolution,
                                            int keep_length, hf_diag *diag)
{
    if (grid_resolution != 0 &&
        (grid_resolution < 4 || grid_resolution > HF_GRID_MAX_RESOLUTION))
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "grid_resolution", -1,
                        "grid_resolution %d is not 0 (no grid) or in "
                        "4..%d", grid_resolution, HF_GRID_MAX_RESOLUTION);
    if (keep_length != 0 && keep_length != 1)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "keep_length", -1,
                        "keep_length %d is not 0 or 1", keep_length);
    return HF_OK;
}

HF__PRIVATE hf_result hf__fur_desc_check(const hf_fur_desc *d, hf_diag *diag)
{
    const int P = d->points_per_strand;
    hf_result r;
    if (P < 2 || P > HF_MAX_POINTS)
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "points_per_strand", -1,
                        "points_per_strand %d is outside 2..%d", P,
                        HF_MAX_POINTS);
    if (!hf__finitef(d->clump) || d->clump < 0.0f || d->clump > 1.0f)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "clump", -1,
                        "clump %g is outside [0, 1]", (double)d->clump);
    if (!hf__finitef(d->lod_simulate_threshold) ||
        d->lod_simulate_threshold < 0.0f || d->lod_simulate_threshold > 1.0f)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER,
                        "lod_simulate_threshold", -1,
                        "lod_simulate_threshold %g is outside [0, 1]",
                        (double)d->lod_simulate_threshold);
    if (!hf__finitef(d->max_length) || d->max_length < 0.0f)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "max_length", -1,
                        "max_length %g is negative or non-finite",
                        (double)d->max_length);
    if (!hf__finitef(d->tess_factor) || d->tess_factor < 0.0f)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "tess_factor", -1,
                        "tess_factor %g is negative or non-finite",
                        (double)d->tess_factor);
    if ((r = hf__fur_options_check(d->grid_resolution, d->keep_length,
                                   diag)) != HF_OK)
        return r;
    if (!hf__kernels_ok(d->simd, 0))
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "simd", -1,
                        "simd %d is not an hf_simd_level (0..4)", d->simd);
    if (!hf__kernels_ok(0, d->nontemporal))
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "nontemporal", -1,
                        "nontemporal %d is not 0, 1 or 2", d->nontemporal);
    if (!hf__finitef(d->strands_per_area) || d->strands_per_area < 0.0f)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "strands_per_area", -1,
                        "strands_per_area %g is negative or non-finite",
                        (double)d->strands_per_area);
    if (d->total_strands < 0)
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "total_strands", -1,
                        "total_strands %d is negative", d->total_strands);
    if ((r = hf__fur_style_check(d, diag)) != HF_OK) return r;
    return hf__rope_params_check(d->rope_params, diag);
}

/* Normals of the rest mesh, when it has none. */
HF__PRIVATE hf_result hf__fur_rest_normals(hf_fur *f, hf__fur_build *b)
{
    hf_result r = HF_OK;
    b->gm = b->desc.mesh;
    if (b->gm.normals) return HF_OK;
    b->normals = (float *)hf__fur_array(f, (size_t)f->vertex_count * 3u,
                                        sizeof(float), &r);
    if (r == HF_OK) r = hf_mesh_compute_normals(&b->gm, b->normals);
    b->gm.normals = b->normals;
    b->gm.normal_stride = 0;
    return r;
}

/* Stage 1: density tessellation, two calls; none for tess_factor 0. */
HF__PRIVATE hf_result hf__fur_tessellate(hf_fur *f, hf__fur_build *b)
{
    hf_tess_params tp;
    hf_tess_output *to = &b->to;
    hf_result r = HF_OK;
    HF_MEMSET(to, 0, sizeof *to);
    if (b->desc.tess_factor > 0.0f) {
        HF_MEMSET(&tp, 0, sizeof tp);
        tp.factor = b->desc.tess_factor;
        tp.estimator = b->desc.tess_estimator;
        tp.split = b->desc.tess_split;
        tp.seed = b->desc.seed;
        tp.max_triangles = b->desc.tess_max_triangles;
        if ((r = hf_tessellate(&b->gm, b->desc.density_map, &tp, to)) != HF_OK)
            return r;
        b->tess_idx = (uint32_t *)hf__fur_array(
            f, (size_t)to->triangle_count * 3u, sizeof(uint32_t), &r);
        b->tess_base = (uint32_t *)hf__fur_array(
            f, (size_t)to->triangle_count, sizeof(uint32_t), &r);
        f->added = (hf_tess_vertex *)hf__fur_array(
            f, (size_t)to->added_count, sizeof(hf_tess_vertex), &r);
        b->tess_pos = (float *)hf__fur_array(
            f, (size_t)to->vertex_count * 3u, sizeof(float), &r);
        if (b->gm.uvs)
            b->tess_uv = (float *)hf__fur_array(
                f, (size_t)to->vertex_count * 2u, sizeof(float), &r);
        if (r != HF_OK) return r;
        to->indices = b->tess_idx;
        to->triangle_base = b->tess_base;
        to->added = f->added;
        to->positions = b->tess_pos;
        to->uvs = b->tess_uv;
        to->triangle_capacity = to->triangle_count;
        to->added_capacity = to->added_count;
        to->vertex_capacity = to->vertex_count;
        r = hf_tessellate(&b->gm, b->desc.density_map, &tp, to);
    }
    f->lod_count = to->added_count;
    return r;
}

/* Stage 2: rest shapes of the pure and LOD guides, two calls; then the
   guide mesh that placement grows strands on. */
HF__PRIVATE hf_result hf__fur_guides(hf_fur *f, hf__fur_build *b)
{
    hf_guide_output go;
    hf_result r;
    const int P = f->P;
    int G;
    HF_MEMSET(&b->gp, 0, sizeof b->gp);
    b->gp.points = P;
    b->gp.max_length = b->desc.max_length;
    b->gp.length_map = b->desc.length_map;
    b->gp.comb = b->desc.comb;
    b->gp.comb_stride = b->desc.comb_stride;
    b->gp.comb_map = b->desc.comb_map;
    HF_MEMSET(&go, 0, sizeof go);
    if ((r = hf_guides_rest(&b->gm, f->added, f->lod_count, &b->gp, &go,
                            &f->alloc)) != HF_OK)
        return r;
    G = go.guide_count;
    b->rest_points = (float *)hf__fur_array(f, (size_t)G * (size_t)P * 3u,
                                            sizeof(float), &r);
    b->guide_len = (float *)hf__fur_array(f, (size_t)G, sizeof(float), &r);
    b->guide_nrm = (float *)hf__fur_array(f, (size_t)G * 3u, sizeof(float), &r);
    b->guide_of = (uint32_t *)hf__fur_array(
        f, (size_t)f->vertex_count + (size_t)f->lod_count, sizeof(uint32_t),
        &r);
    if (r != HF_OK) return r;
    go.points = b->rest_points;
    go.lengths = b->guide_len;
    go.normals = b->guide_nrm;
    go.guide_of_vertex = b->guide_of;
    go.guide_capacity = G;
    if ((r = hf_guides_rest(&b->gm, f->added, f->lod_count, &b->gp, &go,
                            &f->alloc)) != HF_OK)
        return r;
    f->guide_count = G;
    f->pure_count = go.pure_guide_count;
    if (b->tess_idx) {
        HF_MEMSET(&b->gm, 0, sizeof b->gm);
        b->gm.positions = b->tess_pos;
        b->gm.uvs = b->tess_uv;
        b->gm.vertex_count = b->to.vertex_count;
        b->gm.indices = b->tess_idx;
        b->gm.triangle_count = b->to.triangle_count;
    }
    f->triangle_count = b->gm.triangle_count;
    return HF_OK;
}

/* The rotation taking unit vector a to unit vector b, applied to v. */
HF__PRIVATE void hf__rotate_onto(const double *a, const double *b,
                                 const double *v, double *o)
{
    double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2], x[3], k, d;
    x[0] = a[1] * b[2] - a[2] * b[1];
    x[1] = a[2] * b[0] - a[0] * b[2];
    x[2] = a[0] * b[1] - a[1] * b[0];
    if (c < -1.0 + 1e-9) { /* opposite: a half turn about an axis normal to a */
        double u[3], l;
        /* u = a x e, e the x axis (the y axis when a is near x) */
        if (HF_FABS(a[0]) < 0.9) { u[0] = 0.0; u[1] = a[2]; u[2] = -a[1]; }
        else { u[0] = -a[2]; u[1] = 0.0; u[2] = a[0]; }
        l = HF_SQRT(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        d = (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / (l * l);
        o[0] = 2.0 * d * u[0] - v[0];
        o[1] = 2.0 * d * u[1] - v[1];
        o[2] = 2.0 * d * u[2] - v[2];
        return;
    }
    /* Rodrigues: v + x × v + x × (x × v) / (1 + c) */
    {
        double xv[3], xxv[3];
        xv[0] = x[1] * v[2] - x[2] * v[1];
        xv[1] = x[2] * v[0] - x[0] * v[2];
        xv[2] = x[0] * v[1] - x[1] * v[0];
        xxv[0] = x[1] * xv[2] - x[2] * xv[1];
        xxv[1] = x[2] * xv[0] - x[0] * xv[2];
        xxv[2] = x[0] * xv[1] - x[1] * xv[0];
        k = 1.0 / (1.0 + c);
        o[0] = v[0] + xv[0] + k * xxv[0];
        o[1] = v[1] + xv[1] + k * xxv[1];
        o[2] = v[2] + xv[2] + k * xxv[2];
    }
}

/* Curve c resampled to P points evenly along its length, as offsets from
   its first point (into o, 3 P doubles); returns its length. */
HF__PRIVATE double hf__curve_resample(const float *p, int n, int P, double *o)
{
    double len = 0.0, at = 0.0, step;
    int j, k = 1;
    for (j = 1; j < n; ++j) {
        double dx = p[3 * j] - p[3 * j - 3], dy = p[3 * j + 1] - p[3 * j - 2],
               dz = p[3 * j + 2] - p[3 * j - 1];
        len += HF_SQRT(dx * dx + dy * dy + dz * dz);
    }
    step = len / (P - 1);
    o[0] = o[1] = o[2] = 0.0;
    for (j = 1; j < P; ++j) {
        double want = step * j, seg = 0.0, t;
        int m;
        /* walk to the segment holding arc length `want` */
        for (;;) {
            double dx = p[3 * k] - p[3 * k - 3], dy = p[3 * k + 1] - p[3 * k - 2],
                   dz = p[3 * k + 2] - p[3 * k - 1];
            seg = HF_SQRT(dx * dx + dy * dy + dz * dz);
            if (at + seg >= want || k == n - 1) break;
            at += seg;
            ++k;
        }
        t = seg > 0.0 ? (want - at) / seg : 1.0;
        if (t > 1.0) t = 1.0;
        if (t < 0.0) t = 0.0;
        for (m = 0; m < 3; ++m)
            o[3 * j + m] = p[3 * (k - 1) + m] +
                           t * (p[3 * k + m] - p[3 * (k - 1) + m]) - p[m];
    }
    return len;
}

/* Stage 2b: authored guide curves become the guides' rest shapes (see
   hf_fur_desc.guide_curves). */
HF__PRIVATE hf_result hf__fur_curves(hf_fur *f, hf__fur_build *b)
{
    const hf_fur_desc *d = &b->desc;
    const int C = d->guide_curve_count, G = f->guide_count, P = f->P;
    hf_result r = HF_OK;
    double *shape, *cn;
    const float **start;
    int c, g, j, k;
    if (C == 0) return HF_OK;
    shape = (double *)hf__fur_array(f, (size_t)C * (size_t)P * 3u, sizeof(double), &r);
    cn = (double *)hf__fur_array(f, (size_t)C * 3u, sizeof(double), &r);
    start = (const float **)hf__fur_array(f, (size_t)C, sizeof(float *), &r);
    if (r != HF_OK) {
        hf__free(&f->alloc, shape);
        hf__free(&f->alloc, cn);
        hf__free(&f->alloc, (void *)start);
        return r;
    }
    /* each curve: its shape, and the normal of the guide rooted nearest */
    {
        const float *p = d->guide_curves;
        for (c = 0; c < C; ++c) {
            double best = -1.0;
            int bg = 0;
            start[c] = p;
            hf__curve_resample(p, d->guide_curve_points[c], P,
                               shape + (size_t)c * (size_t)P * 3u);
            for (g = 0; g < G; ++g) {
                const float *q = b->rest_points + (size_t)g * (size_t)P * 3u;
                double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2],
                       e = dx * dx + dy * dy + dz * dz;
                if (best < 0.0 || e < best) { best = e; bg = g; }
            }
            for (k = 0; k < 3; ++k) cn[3 * c + k] = b->guide_nrm[3 * bg + k];
            p += 3 * d->guide_curve_points[c];
        }
    }
    /* each guide: the nearest 3 curves, blended in its own frame */
    for (g = 0; g < G; ++g) {
        float *q = b->rest_points + (size_t)g * (size_t)P * 3u;
        double root[3], n[3], dist[3] = {-1.0, -1.0, -1.0}, wsum = 0.0, len = 0.0;
        int near[3] = {-1, -1, -1};
        for (k = 0; k < 3; ++k) {
            root[k] = q[k];
            n[k] = b->guide_nrm[3 * g + k];
        }
        for (c = 0; c < C; ++c) {
            double dx = start[c][0] - root[0], dy = start[c][1] - root[1],
                   dz = start[c][2] - root[2], e = dx * dx + dy * dy + dz * dz;
            int at = 3;
            while (at > 0 && (near[at - 1] < 0 || e < dist[at - 1])) --at;
            if (at == 3) continue;
            for (k = 2; k > at; --k) {
                near[k] = near[k - 1];
                dist[k] = dist[k - 1];
            }
            near[at] = c;
            dist[at] = e;
        }
        for (j = 0; j < P; ++j) for (k = 0; k < 3; ++k) q[3 * j + k] = 0.0f;
        {
            double acc[3 * HF_MAX_POINTS];
            for (j = 0; j < 3 * P; ++j) acc[j] = 0.0;
            for (c = 0; c < 3 && near[c] >= 0; ++c) {
                const double *o = shape + (size_t)near[c] * (size_t)P * 3u;
                double w = 1.0 / (dist[c] + 1e-20), v[3];
                for (j = 0; j < P; ++j) {
                    hf__rotate_onto(cn + 3 * near[c], n, o + 3 * j, v);
                    for (k = 0; k < 3; ++k) acc[3 * j + k] += w * v[k];
                }
                wsum += w;
            }
            for (j = 0; j < P; ++j)
                for (k = 0; k < 3; ++k)
                    q[3 * j + k] = (float)(root[k] + acc[3 * j + k] / wsum);
        }
        for (j = 1; j < P; ++j) {
            double dx = q[3 * j] - q[3 * j - 3], dy = q[3 * j + 1] - q[3 * j - 2],
                   dz = q[3 * j + 2] - q[3 * j - 1];
            len += HF_SQRT(dx * dx + dy * dy + dz * dz);
        }
        b->guide_len[g] = (float)len;
    }
    hf__free(&f->alloc, shape);
    hf__free(&f->alloc, cn);
    hf__free(&f->alloc, (void *)start);
    return HF_OK;
}

/* A guide's root UV (for the styling maps): the UV of the first vertex of
   the guide mesh that the guide grows from. */
HF__PRIVATE void hf__fur_guide_uvs(const hf__fur_build *b, int G, float *uv)
{
    int v;
    for (v = 0; v < 2 * G; ++v) uv[v] = -1.0f;
    for (v = 0; v < b->gm.vertex_count; ++v) {
        uint32_t g = b->guide_of[v];
        if ((int)g < G && uv[2 * g] < 0.0f) {
            const float *t = hf__mesh_uv(&b->gm, v);
            uv[2 * g] = t[0];
            uv[2 * g + 1] = t[1];
        }
    }
}

/* Stage 2c: curl, wave and frizz on the guides' rest shapes. The frame
   along a guide is carried from its root (the normal, and the tangent
   across it) by parallel transport, so a curl turns smoothly. */
HF__PRIVATE hf_result hf__fur_style(hf_fur *f, hf__fur_build *b)
{
    const hf_fur_desc *d = &b->desc;
    const int G = f->guide_count, P = f->P;
    hf_result r = HF_OK;
    float *uv = NULL;
    hf_rng rng;
    int g, j, k;
    if (d->curl_radius == 0.0f && d->wave_amplitude == 0.0f && d->frizz == 0.0f)
        return HF_OK;
    if (d->curl_map || d->wave_map || d->frizz_map) {
        uv = (float *)hf__fur_array(f, (size_t)G * 2u, sizeof(float), &r);
        if (r != HF_OK) return r;
        hf__fur_guide_uvs(b, G, uv);
    }
    hf_rng_seed(&rng, d->seed, 0x5757u);
    for (g = 0; g < G; ++g) {
        float *q = b->rest_points + (size_t)g * (size_t)P * 3u;
        double base[3 * HF_MAX_POINTS], u[3], t[3], s = 0.0, len = 0.0;
        double curl = d->curl_radius, wave = d->wave_amplitude, frizz = d->frizz;
        const hf_map *maps[3];
        double *amp[3];
        maps[0] = d->curl_map; maps[1] = d->wave_map; maps[2] = d->frizz_map;
        amp[0] = &curl; amp[1] = &wave; amp[2] = &frizz;
        for (k = 0; k < 3; ++k)
            if (maps[k] && uv && uv[2 * g] >= 0.0f) {
                float m[4];
                hf_map_sample_fast(maps[k], uv[2 * g], uv[2 * g + 1], m);
                *amp[k] *= m[0];
            }
        for (j = 0; j < 3 * P; ++j) base[j] = q[j];
        for (j = 1; j < P; ++j) {
            double dx = base[3 * j] - base[3 * j - 3],
                   dy = base[3 * j + 1] - base[3 * j - 2],
                   dz = base[3 * j + 2] - base[3 * j - 1];
            len += HF_SQRT(dx * dx + dy * dy + dz * dz);
        }
        if (!(len > 0.0)) continue;
        /* u: a unit vector across the first segment, x projected onto
           it, so that neighbouring guides curl in phase and the strands
           between them keep the curl (a switch of axis at some angle
           would put a seam of opposite phases across the fur); only
           within a degree of x, where that is undefined, y */
        for (k = 0; k < 3; ++k) t[k] = base[3 + k] - base[k];
        {
            double a[3] = {1.0, 0.0, 0.0}, l, dt;
            l = HF_SQRT(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
            for (k = 0; k < 3; ++k) t[k] /= l;
            if (HF_FABS(t[0]) > 0.99985) { a[0] = 0.0; a[1] = 1.0; }
            dt = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
            for (k = 0; k < 3; ++k) u[k] = a[k] - dt * t[k];
            l = HF_SQRT(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
            for (k = 0; k < 3; ++k) u[k] /= l;
        }
        for (j = 1; j < P; ++j) {
            double nt[3], v[3], l, seg, ramp, ang, off[3], du;
            /* the tangent here, and u carried onto it */
            for (k = 0; k < 3; ++k)
                nt[k] = base[3 * (j < P - 1 ? j + 1 : j) + k] -
                        base[3 * (j - 1) + k];
            l = HF_SQRT(nt[0] * nt[0] + nt[1] * nt[1] + nt[2] * nt[2]);
            if (l > 0.0) {
                for (k = 0; k < 3; ++k) nt[k] /= l;
                hf__rotate_onto(t, nt, u, v);
                for (k = 0; k < 3; ++k) { u[k] = v[k]; t[k] = nt[k]; }
            }
            v[0] = t[1] * u[2] - t[2] * u[1];
            v[1] = t[2] * u[0] - t[0] * u[2];
            v[2] = t[0] * u[1] - t[1] * u[0];
            seg = HF_SQRT((base[3 * j] - base[3 * j - 3]) * (base[3 * j] - base[3 * j - 3]) +
                          (base[3 * j + 1] - base[3 * j - 2]) * (base[3 * j + 1] - base[3 * j - 2]) +
                          (base[3 * j + 2] - base[3 * j - 1]) * (base[3 * j + 2] - base[3 * j - 1]));
            s += seg;
            ramp = s / (0.2 * len);
            if (ramp > 1.0) ramp = 1.0;
            ramp = ramp * ramp * (3.0 - 2.0 * ramp);
            ang = 6.283185307179586 * d->curl_turns * s / len;
            du = wave * HF_SIN(6.283185307179586 * d->wave_count * s / len);
            for (k = 0; k < 3; ++k)
                off[k] = ramp * (curl * (HF_COS(ang) * u[k] + HF_SIN(ang) * v[k] - u[k]) +
                                 du * u[k]);
            if (frizz > 0.0) {
                double fr = frizz * seg * (s / len);
                for (k = 0; k < 3; ++k)
                    off[k] += fr * (2.0 * hf_rng_float(&rng) - 1.0);
            }
            for (k = 0; k < 3; ++k) q[3 * j + k] = (float)(base[3 * j + k] + off[k]);
        }
        /* guide_len stays the unstyled length: strands scale by their own
           length over it, so a curl keeps its size */
    }
    hf__free(&f->alloc, uv);
    return HF_OK;
}

/* Stage 3: strand records in LOD order, two calls. strands_per_area wins
   over total_strands, as hf_fur_desc documents. */
HF__PRIVATE hf_result hf__fur_place(hf_fur *f, hf__fur_build *b)
{
    hf_place_params pp;
    hf_result r;
    int count;
    HF_MEMSET(&pp, 0, sizeof pp);
    pp.strands_per_area = b->desc.strands_per_area;
    pp.total_strands = b->desc.strands_per_area > 0.0f ? 0
                                                        : b->desc.total_strands;
    pp.estimator = b->desc.tess_estimator;
    pp.sampler = b->desc.sampler;
    pp.seed = b->desc.seed;
    if ((r = hf_place_strands(&b->gm, b->desc.density_map, &pp, NULL, 0,
                              &count, &f->alloc)) != HF_OK)
        return r;
    f->strands = (hf_strand *)hf__fur_array(f, (size_t)count,
                                            sizeof(hf_strand), &r);
    if (r != HF_OK) return r;
    if ((r = hf_place_strands(&b->gm, b->desc.density_map, &pp, f->strands,
                              count, &count, &f->alloc)) != HF_OK)
        return r;
    f->strand_count = f->drawn = count;
    return HF_OK;
}

/* A control map's first channel at uv (1 without a map). */
HF__PRIVATE float hf__map_at(const hf_map *m, const float *uv)
{
    float v[4];
    if (!m) return 1.0f;
    hf_map_sample_fast(m, uv[0], uv[1], v);
    return v[0];
}

/* Per-strand length, colour, root UV and 3D-colour coordinate. */
HF__PRIVATE hf_result hf__fur_strand_maps(hf_fur *f, hf__fur_build *b)
{
    const hf_fur_desc *d = &b->desc;
    const int n_strands = f->strand_count;
    hf_result r = HF_OK;
    int i;
    f->strand_lengths = (float *)hf__fur_array(f, (size_t)n_strands, sizeof(float), &r);
    f->strand_rgba = (float *)hf__fur_array(f, (size_t)n_strands * 4u, sizeof(float), &r);
    f->strand_uv = (float *)hf__fur_array(f, (size_t)n_strands * 2u, sizeof(float), &r);
    f->strand_c3x = (float *)hf__fur_array(f, (size_t)n_strands, sizeof(float), &r);
    if (r != HF_OK) return r;
    if ((r = hf_strand_lengths(f->strands, n_strands, 0, n_strands, d->length_map,
                               d->max_length, f->strand_lengths)) != HF_OK)
        return r;
    if (d->color_map) {
        r = hf_strand_colors(f->strands, n_strands, 0, n_strands, d->color_map,
                             f->strand_rgba);
        if (r != HF_OK) return r;
    } else {
        for (i = 0; i < 4 * n_strands; ++i) f->strand_rgba[i] = 1.0f;
    }
    if (d->width_variation > 0.0f) { /* per strand, in strand order */
        hf_rng rng;
        f->strand_width = (float *)hf__fur_array(f, (size_t)n_strands,
                                                 sizeof(float), &r);
        if (r != HF_OK) return r;
        hf_rng_seed(&rng, d->seed, 0x5757u + 1u);
        for (i = 0; i < n_strands; ++i)
            f->strand_width[i] =
                1.0f + d->width_variation *
                           hf__map_at(d->width_variation_map, f->strands[i].uv) *
                           (2.0f * hf_rng_float(&rng) - 1.0f);
    }
    if (d->clump_map && d->clump > 0.0f) { /* per strand strength */
        f->strand_clump = (float *)hf__fur_array(f, (size_t)n_strands,
                                                 sizeof(float), &r);
        if (r != HF_OK) return r;
        for (i = 0; i < n_strands; ++i) {
            float c = d->clump * hf__map_at(d->clump_map, f->strands[i].uv);
            f->strand_clump[i] = c < 0.0f ? 0.0f : c > 1.0f ? 1.0f : c;
        }
    }
    if (d->color_variation > 0.0f) { /* per strand, in strand order */
        hf_rng rng;
        hf_rng_seed(&rng, d->seed, 0x4343u);
        for (i = 0; i < n_strands; ++i) {
            float m = 1.0f + d->color_variation *
                                 hf__map_at(d->color_variation_map, f->strands[i].uv) *
                                 (2.0f * hf_rng_float(&rng) - 1.0f);
            int k;
            for (k = 0; k < 3; ++k) {
                float c = f->strand_rgba[4 * i + k] * m;
                f->strand_rgba[4 * i + k] = c > 1.0f ? 1.0f : c;
            }
        }
    }
    for (i = 0; i < n_strands; ++i) {
        const hf_strand *s = &f->strands[i];
        f->strand_uv[2 * i] = s->uv[0];
        f->strand_uv[2 * i + 1] = s->uv[1];
        f->strand_c3x[i] = 0.0f;
        if (d->color3d_index_map) {
            float xy[2];
            if ((r = hf_color3d_coord(d->color3d_index_map, s->uv[0],
                                      s->uv[1], 0.0f, xy)) != HF_OK)
                return r;
            f->strand_c3x[i] = xy[0];
        }
    }
    return HF_OK;
}

/* Strands bind to the guides of their guide triangle; LOD guides bind to
   the pure guides of their base triangle the same way, keeping their own
   length. */
HF__PRIVATE hf_result hf__fur_bind(hf_fur *f, hf__fur_build *b)
{
    const int n_strands = f->strand_count;
    hf_result r = HF_OK;
    int i, k;
    f->bindings = (hf_strand_binding *)hf__fur_array(
        f, (size_t)n_strands, sizeof(hf_strand_binding), &r);
    f->lod_bindings = (hf_strand_binding *)hf__fur_array(
        f, (size_t)f->lod_count, sizeof(hf_strand_binding), &r);
    if (r != HF_OK) return r;
    if ((r = hf_bind_strands(&b->gm, b->guide_of, f->guide_count, f->strands,
                             n_strands, 0, n_strands, f->strand_lengths, b->guide_len,
                             f->bindings)) != HF_OK)
        return r;
    if (b->desc.guide_curve_count > 0) /* lengths come from the curves */
        for (i = 0; i < n_strands; ++i) {
            hf_strand_binding *s = &f->bindings[i];
            f->strand_lengths[i] = s->weight[0] * b->guide_len[s->guide[0]] +
                                   s->weight[1] * b->guide_len[s->guide[1]] +
                                   s->weight[2] * b->guide_len[s->guide[2]];
            s->length_scale = 1.0f;
        }
    for (i = 0; i < f->lod_count; ++i) {
        const hf_tess_vertex *a = &f->added[i];
        const uint32_t *tri = b->desc.mesh.indices + 3u * (size_t)a->triangle;
        uint32_t g[3];
        for (k = 0; k < 3; ++k) g[k] = b->guide_of[tri[k]];
        hf__bind(&f->lod_bindings[i], g, a->bary,
                 b->guide_len[f->pure_count + i], b->guide_len);
    }
    return HF_OK;
}

/* Clump leaders (hf_fur_desc.clump_size): in LOD order, a strand whose
   root has no leader within its clump radius (clump_size, times the
   clump_size_map there) becomes one; every other strand clumps to its
   nearest leader. A hash grid of cells as wide as the largest radius in
   use keeps it linear, and a cell (a hash bucket) takes at most
   HF__CLUMP_CELL leaders: where a map makes radii far smaller than the
   largest, leaders would crowd a cell and every strand near it would
   test them all (906,642 strands took minutes); a strand that would
   lead one more there stands alone instead. Leaders are at least a
   radius apart: with one radius everywhere a cell held at most 4
   (measured, six sizes, up to 100,000 strands), so only radii some 2x
   smaller than the largest can fill one. */
#define HF__CLUMP_CELL 16
HF__PRIVATE long long hf__clump_cell(double x)
{
    x = HF_FLOOR(x); /* clamped: the cast of a larger one is undefined */
    return (long long)(x > 4e18 ? 4e18 : x < -4e18 ? -4e18 : x);
}

HF__PRIVATE hf_result hf__fur_clumps(hf_fur *f, hf__fur_build *b)
{
    const int S = f->strand_count, P = f->P;
    const float size = b->desc.clump_size;
    double inv, rmax = 0.0;
    hf_result r = HF_OK;
    float *root, *r2;
    uint32_t *head, *next, cap = 1;
    unsigned char *fill;
    int i, k;
    if (!(size > 0.0f) || b->desc.clump == 0.0f || S == 0) return HF_OK;
    while (cap < 2u * (uint32_t)S && cap < (1u << 30)) cap <<= 1;
    f->leader = (uint32_t *)hf__fur_array(f, (size_t)S, sizeof(uint32_t), &r);
    root = (float *)hf__fur_array(f, (size_t)S * 3u, sizeof(float), &r);
    r2 = (float *)hf__fur_array(f, (size_t)S, sizeof(float), &r);
    head = (uint32_t *)hf__fur_array(f, cap, sizeof(uint32_t), &r);
    fill = (unsigned char *)hf__fur_array(f, cap, 1, &r);
    next = (uint32_t *)hf__fur_array(f, (size_t)S, sizeof(uint32_t), &r);
    if (r != HF_OK) goto done;
    for (i = 0; i < (int)cap; ++i) {
        head[i] = 0xffffffffu;
        fill[i] = 0;
    }
    for (i = 0; i < S; ++i) { /* rest roots (the blend of the guides'), radii */
        const hf_strand_binding *bd = &f->bindings[i];
        double ri = size;
        for (k = 0; k < 3; ++k)
            root[3 * i + k] =
                bd->weight[0] * b->rest_points[(size_t)bd->guide[0] * (size_t)P * 3u + (size_t)k] +
                bd->weight[1] * b->rest_points[(size_t)bd->guide[1] * (size_t)P * 3u + (size_t)k] +
                bd->weight[2] * b->rest_points[(size_t)bd->guide[2] * (size_t)P * 3u + (size_t)k];
        if (b->desc.clump_size_map) {
            float m = hf__map_at(b->desc.clump_size_map, f->strands[i].uv);
            m = m > 0.0f ? (m < 1.0f ? m : 1.0f) : 0.0f; /* NaN: 0 */
            ri = (double)size * m;
        }
        r2[i] = (float)(ri * ri);
        if (ri > rmax) rmax = ri;
    }
    inv = rmax > 0.0 ? 1.0 / rmax : 0.0;
    for (i = 0; i < S; ++i) {
        const float *q = root + 3 * i;
        long long c[3];
        double best = r2[i];
        const double ri = HF_SQRT(best);
        uint32_t lead = 0xffffffffu, h;
        int dx, dy, dz, lo[3], hi[3];
        for (k = 0; k < 3; ++k) {
            c[k] = hf__clump_cell(q[k] * inv);
            /* the neighbour cells the radius reaches (all of them for the
               largest radius): the same candidates in the same order as
               all 27, fewer where radii are small */
            lo[k] = hf__clump_cell((q[k] - ri) * inv) < c[k] ? -1 : 0;
            hi[k] = hf__clump_cell((q[k] + ri) * inv) > c[k] ? 1 : 0;
        }
        if (best > 0.0)
            for (dx = lo[0]; dx <= hi[0]; ++dx)
                for (dy = lo[1]; dy <= hi[1]; ++dy)
                    for (dz = lo[2]; dz <= hi[2]; ++dz) {
                        uint64_t key = (uint64_t)(c[0] + dx) * 73856093u ^
                                       (uint64_t)(c[1] + dy) * 19349663u ^
                                       (uint64_t)(c[2] + dz) * 83492791u;
                        uint32_t j = head[(uint32_t)(key ^ (key >> 29)) & (cap - 1)];
                        for (; j != 0xffffffffu; j = next[j]) {
                            const float *p = root + 3 * j;
                            double e = ((double)p[0] - q[0]) * ((double)p[0] - q[0]) +
                                       ((double)p[1] - q[1]) * ((double)p[1] - q[1]) +
                                       ((double)p[2] - q[2]) * ((double)p[2] - q[2]);
                            if (e < best) { best = e; lead = j; }
                        }
                    }
        if (lead == 0xffffffffu) { /* a new leader, into its cell */
            uint64_t key = (uint64_t)c[0] * 73856093u ^ (uint64_t)c[1] * 19349663u ^
                           (uint64_t)c[2] * 83492791u;
            h = (uint32_t)(key ^ (key >> 29)) & (cap - 1);
            if (r2[i] > 0.0f && fill[h] < HF__CLUMP_CELL) {
                next[i] = head[h];
                head[h] = (uint32_t)i;
                ++fill[h];
            }
            lead = (uint32_t)i;
        }
        f->leader[i] = lead;
    }
done:
    hf__free(&f->alloc, root);
    hf__free(&f->alloc, r2);
    hf__free(&f->alloc, head);
    hf__free(&f->alloc, fill);
    hf__free(&f->alloc, next);
    return r;
}
#undef HF__CLUMP_CELL

/* Clumping strand by strand (clump_size or clump_map): point j moves
   clump * j / (P - 1) of the way to the leader's point j (the leader's
   blend of its guides, unclumped), or without leaders to its main guide's
   point j, as the interpolation kernel does; the strength per strand with
   a clump map. Strand s's points are at pts + (s - pts_first) * 3 P. */
HF__PRIVATE void hf__fur_clump_pass(const hf_fur *f, int first, int count,
                                    float *pts, int pts_first)
{
    const int P = f->P;
    int s, j, k;
    for (s = first; s < first + count; ++s) {
        const float strength = f->strand_clump ? f->strand_clump[s] : f->clump;
        float *o = pts + (size_t)(s - pts_first) * (size_t)P * 3u;
        if (strength == 0.0f) continue;
        if (f->leader) {
            const uint32_t l = f->leader[s];
            const hf_strand_binding *b = &f->bindings[l];
            const float *g[3];
            float root[3];
            if ((int)l == s) continue;
            for (k = 0; k < 3; ++k)
                g[k] = f->guide_points + (size_t)b->guide[k] * (size_t)P * 3u;
            for (k = 0; k < 3; ++k)
                root[k] = b->weight[0] * g[0][k] + b->weight[1] * g[1][k] +
                          b->weight[2] * g[2][k];
            for (j = 1; j < P; ++j) {
                const float c = strength * (float)j / (float)(P - 1);
                for (k = 0; k < 3; ++k) {
                    float lp = b->weight[0] * g[0][3 * j + k] +
                               b->weight[1] * g[1][3 * j + k] +
                               b->weight[2] * g[2][3 * j + k];
                    lp = root[k] + b->length_scale * (lp - root[k]);
                    o[3 * j + k] += c * (lp - o[3 * j + k]);
                }
            }
        } else { /* to the guide of largest weight (the first of equals) */
            const hf_strand_binding *b = &f->bindings[s];
            const float w0 = b->weight[0], w1 = b->weight[1], w2 = b->weight[2];
            const int n = (w0 >= w1 && w0 >= w2) ? 0 : (w1 >= w2 ? 1 : 2);
            const float *g = f->guide_points + (size_t)b->guide[n] * (size_t)P * 3u;
            for (j = 1; j < P; ++j) {
                const float c = strength * (float)j / (float)(P - 1);
                for (k = 0; k < 3; ++k)
                    o[3 * j + k] += c * (g[3 * j + k] - o[3 * j + k]);
            }
        }
    }
}

/* Frame references of every guide: the root vertex, an edge for the
   tangent and a third corner for the face normal. A pure guide takes the
   first non-degenerate triangle of its vertex, a LOD guide its base
   triangle. */
HF__PRIVATE hf_result hf__fur_root_refs(hf_fur *f, hf__fur_build *b)
{
    const hf_mesh *m = &b->desc.mesh;
    const int G = f->guide_count;
    hf_result r = HF_OK;
    int i, k;
    f->ref = (uint32_t *)hf__fur_array(f, (size_t)G * 3u, sizeof(uint32_t), &r);
    if (r != HF_OK) return r;
    for (i = 0; i < G * 3; ++i) f->ref[i] = 0xffffffffu;
    for (i = 0; i < m->triangle_count; ++i) {
        const uint32_t *tri = m->indices + 3u * (size_t)i;
        float area = hf_triangle_area(hf__mesh_pos(m, (int)tri[0]),
                                      hf__mesh_pos(m, (int)tri[1]),
                                      hf__mesh_pos(m, (int)tri[2]));
        for (k = 0; k < 3; ++k) {
            uint32_t g = b->guide_of[tri[k]];
            if (f->ref[3 * g] == 0xffffffffu ||
                (area > 0.0f && f->ref[3 * g + 2] == 0xfffffffeu)) {
                f->ref[3 * g] = tri[k];
                f->ref[3 * g + 1] = tri[(k + 1) % 3];
                /* mark a degenerate pick so a later good triangle replaces it */
                f->ref[3 * g + 2] = area > 0.0f ? tri[(k + 2) % 3] : 0xfffffffeu;
            }
        }
    }
    for (i = 0; i < f->pure_count; ++i) /* unused vertices: no tangent edge */
        for (k = 0; k < 3; ++k)
            if (f->ref[3 * i + k] >= 0xfffffffeu)
                f->ref[3 * i + k] = f->ref[3 * i] < 0xfffffffeu ? f->ref[3 * i] : 0u;
    for (i = 0; i < f->lod_count; ++i) {
        const uint32_t *tri = m->indices + 3u * (size_t)f->added[i].triangle;
        for (k = 0; k < 3; ++k) f->ref[3 * (f->pure_count + i) + k] = tri[k];
    }
    return HF_OK;
}

/* The root frames at creation, for hf_fur_set_transform, and every
   guide's rope parameter set (0). */
HF__PRIVATE hf_result hf__fur_keep_rest_frames(hf_fur *f)
{
    const size_t G = (size_t)f->guide_count;
    hf_result r = HF_OK;
    size_t g;
    f->rest_frame = (float *)hf__fur_array(f, G * 9u, sizeof(float), &r);
    f->rope_of = (unsigned char *)hf__fur_array(f, G, 1, &r);
    f->user_mode = (unsigned char *)hf__fur_array(f, G, 1, &r);
    if (r != HF_OK) return r;
    HF_MEMSET(f->rope_of, 0, G); /* every guide: set 0, the desc's */
    HF_MEMSET(f->user_mode, HF_ROPE_SIMULATED, G);
    for (g = 0; g < G; ++g) {
        HF_MEMCPY(f->rest_frame + 9 * g, f->root_pos + 3 * g, 12);
        HF_MEMCPY(f->rest_frame + 9 * g + 3, f->root_nrm + 3 * g, 12);
        HF_MEMCPY(f->rest_frame + 9 * g + 6, f->root_tan + 3 * g, 12);
    }
    return HF_OK;
}

/* keep_length: strands [first, first + count) at pts + (s - pts_first)
   * 3 P, each segment scaled to its rest length along its own direction,
   from the root out (the root stays; a segment of no length takes the
   direction of the one before it, or at the root of the first one with
   a length; a strand of no length stays so). */
HF__PRIVATE void hf__fur_keep_length(const hf_fur *f, int first, int count,
                                     float *pts, int pts_first)
{
    const int P = f->P, n = P - 1;
    /* the segments apart, then their reciprocal lengths four at a time
       (square roots and divisions are what it costs), then the walk */
    float dx[HF_MAX_POINTS], dy[HF_MAX_POINTS], dz[HF_MAX_POINTS];
    float inv[HF_MAX_POINTS];
    int s, j;
    for (s = first; s < first + count; ++s) {
        float *o = pts + (size_t)(s - pts_first) * (size_t)P * 3u;
        const float *L = f->rest_seg + (size_t)s * (size_t)n;
        float ax = o[0], ay = o[1], az = o[2];
        float ux = 0.0f, uy = 0.0f, uz = 0.0f; /* the last direction */
        for (j = 0; j < n; ++j) {
            dx[j] = o[3 * j + 3] - o[3 * j];
            dy[j] = o[3 * j + 4] - o[3 * j + 1];
            dz[j] = o[3 * j + 5] - o[3 * j + 2];
        }
        j = 0;
#if HF__V4
        for (; j + 4 <= n; j += 4) {
            const hf__v4 x = HF__LD(dx + j), y = HF__LD(dy + j),
                         z = HF__LD(dz + j);
            const hf__v4 d2 = HF__ADD(HF__ADD(HF__MUL(x, x), HF__MUL(y, y)),
                                      HF__MUL(z, z));
            HF__ST(inv + j, HF__SEL(HF__GT(d2, HF__SET1(1e-30f)),
                                    HF__DIV(HF__SET1(1.0f), HF__SQRT(d2)),
                                    HF__SET1(0.0f)));
        }
#endif
        for (; j < n; ++j) {
            const float d2 = (dx[j] * dx[j] + dy[j] * dy[j]) + dz[j] * dz[j];
            inv[j] = d2 > 1e-30f ? 1.0f / HF_SQRTF(d2) : 0.0f;
        }
        /* segments of no length at the root take the first direction */
        for (j = 0; j < n && !(inv[j] > 0.0f); ++j) {
        }
        if (j < n) {
            ux = dx[j] * inv[j];
            uy = dy[j] * inv[j];
            uz = dz[j] * inv[j];
        }
        for (j = 0; j < n; ++j) {
            if (inv[j] > 0.0f) { /* else the direction before it */
                ux = dx[j] * inv[j];
                uy = dy[j] * inv[j];
                uz = dz[j] * inv[j];
            }
            ax += ux * L[j];
            ay += uy * L[j];
            az += uz * L[j];
            o[3 * j + 3] = ax;
            o[3 * j + 4] = ay;
            o[3 * j + 5] = az;
        }
    }
}

/* keep_length: every strand's segment lengths as interpolated at
   creation (the rest shape the pass keeps). */
HF__PRIVATE hf_result hf__fur_rest_segments(hf_fur *f)
{
    const int P = f->P;
    hf_result r = HF_OK;
    int s, j;
    f->rest_seg = (float *)hf__fur_array(
        f, (size_t)f->strand_count * (size_t)(P - 1), sizeof(float), &r);
    if (r != HF_OK) return r;
    for (s = 0; s < f->strand_count; ++s) {
        const float *o = f->strand_points + (size_t)s * (size_t)P * 3u;
        for (j = 1; j < P; ++j) {
            const float dx = o[3 * j] - o[3 * j - 3],
                        dy = o[3 * j + 1] - o[3 * j - 2],
                        dz = o[3 * j + 2] - o[3 * j - 1];
            f->rest_seg[(size_t)s * (size_t)(P - 1) + (size_t)(j - 1)] =
                HF_SQRTF(dx * dx + dy * dy + dz * dz);
        }
    }
    return HF_OK;
}

/* Stage 4: the ropes at rest, roots from the rest mesh, and the strands
   interpolated once so the first frame has points to draw. */
HF__PRIVATE hf_result hf__fur_ropes(hf_fur *f, hf__fur_build *b)
{
    const size_t G = (size_t)f->guide_count, P = (size_t)f->P;
    const size_t n_strands = (size_t)f->strand_count;
    hf_result r = HF_OK;
    f->root_pos = (float *)hf__fur_array(f, G * 3u, sizeof(float), &r);
    f->root_nrm = (float *)hf__fur_array(f, G * 3u, sizeof(float), &r);
    f->root_tan = (float *)hf__fur_array(f, G * 3u, sizeof(float), &r);
    f->guide_points = hf__fur_lines(f, G * P * 3u, &r);
    f->strand_points = hf__fur_lines(f, n_strands * P * 3u, &r);
    if (r != HF_OK) return r;
    HF_MEMCPY(f->guide_points, b->rest_points, sizeof(float) * G * P * 3u);
    if ((r = hf_ropes_create(f->guide_count, f->P, &f->alloc, &f->ropes)) !=
            HF_OK ||
        (r = hf_fur_set_roots(f, &b->desc.mesh, 0, f->guide_count)) != HF_OK ||
        (r = hf__ropes_set_rest(f->ropes, 0, f->guide_count, b->rest_points, 0,
                                f->root_pos, f->root_nrm, f->root_tan, 0,
                                f->simd)) != HF_OK)
        return r;
    if ((r = hf__fur_keep_rest_frames(f)) != HF_OK) return r;
    if (b->desc.grid_resolution > 0) {
        if ((r = hf_grid_create(b->desc.grid_resolution, &f->alloc,
                                &f->grid)) != HF_OK)
            return r;
        f->grid->simd = f->simd; /* the fur's kernel level */
    }
    f->lod = 1.0f;
    f->width_scale = 1.0f;
    f->lod_sim = 1;
    if ((r = hf_fur_interpolate(f, 0, f->strand_count)) != HF_OK) return r;
    return b->desc.keep_length ? hf__fur_rest_segments(f) : HF_OK;
}

HFDEF hf_result hf_fur_create(const hf_fur_desc *desc, hf_fur **out_fur,
                              hf_diag *diag)
{
    /* the steps in order, each named in the diagnostic when it fails */
    static const struct {
        const char *name;
        hf_result (*run)(hf_fur *, hf__fur_build *);
    } steps[] = {{"normals", hf__fur_rest_normals},
                 {"tessellation", hf__fur_tessellate},
                 {"guides", hf__fur_guides},
                 {"guide curves", hf__fur_curves},
                 {"styling", hf__fur_style},
                 {"strand placement", hf__fur_place},
                 {"strand maps", hf__fur_strand_maps},
                 {"strand bindings", hf__fur_bind},
                 {"clumps", hf__fur_clumps},
                 {"root frames", hf__fur_root_refs},
                 {"ropes", hf__fur_ropes}};
    hf__fur_build b;
    hf_fur *f;
    hf_allocator alloc;
    hf_result r;
    size_t i;

    if (!desc || !out_fur)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "desc", -1,
                        "desc or out_fur is NULL");
    if ((r = hf_mesh_validate(&desc->mesh, diag)) != HF_OK) return r;
    HF_MEMSET(&b, 0, sizeof b);
    hf__fur_desc_resolve(desc, &b.desc, &b.rope);
    if ((r = hf__fur_desc_check(&b.desc, diag)) != HF_OK) return r;

    HF_MEMSET(&alloc, 0, sizeof alloc);
    if (desc->allocator) alloc = *desc->allocator;
    f = (hf_fur *)hf__alloc(&alloc, sizeof *f);
    if (!f)
        return hf__fail(diag, HF_ERROR_OUT_OF_MEMORY, "fur", -1,
                        "out of memory");
    HF_MEMSET(f, 0, sizeof *f);
    f->alloc = alloc;
    f->P = b.desc.points_per_strand;
    f->vertex_count = desc->mesh.vertex_count;
    f->base_triangle_count = desc->mesh.triangle_count;
    f->clump = b.desc.clump;
    f->simd = b.desc.simd;
    f->nontemporal = b.desc.nontemporal;
    f->lod_threshold = b.desc.lod_simulate_threshold;
    f->rope[0] = b.rope;

    for (i = 0; i < sizeof steps / sizeof steps[0]; ++i)
        if ((r = steps[i].run(f, &b)) != HF_OK) break;
    hf__fur_build_free(&alloc, &b);
    if (r != HF_OK) {
        hf_fur_destroy(f);
        return hf__fail(diag, r, steps[i].name, -1, "hf_fur_create: %s: %s",
                        steps[i].name, hf_result_string(r));
    }
    *out_fur = f;
    hf__ok(diag);
    return HF_OK;
}

/* ---- 10.1 grooms -------------------------------------------------------- */

/* Orthonormal frame (tangent, normal, binormal) as columns of o[9] (row
   major 3x3) from a normal and a tangent that need not be unit or
   perpendicular. */
HF__PRIVATE void hf__groom_frame(const float *n, const float *t, double *o)
{
    double nn[3], tt[3], bb[3], l, d;
    int k;
    l = HF_SQRT((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    for (k = 0; k < 3; ++k) nn[k] = l > 0.0 ? n[k] / l : (k == 1);
    d = t[0] * nn[0] + t[1] * nn[1] + t[2] * nn[2];
    for (k = 0; k < 3; ++k) tt[k] = t[k] - d * nn[k];
    l = HF_SQRT(tt[0] * tt[0] + tt[1] * tt[1] + tt[2] * tt[2]);
    if (!(l > 0.0)) { /* any perpendicular */
        tt[0] = HF_FABS(nn[0]) < 0.9 ? 0.0 : -nn[2];
        tt[1] = HF_FABS(nn[0]) < 0.9 ? nn[2] : 0.0;
        tt[2] = HF_FABS(nn[0]) < 0.9 ? -nn[1] : nn[0];
        l = HF_SQRT(tt[0] * tt[0] + tt[1] * tt[1] + tt[2] * tt[2]);
    }
    for (k = 0; k < 3; ++k) tt[k] /= l;
    bb[0] = nn[1] * tt[2] - nn[2] * tt[1];
    bb[1] = nn[2] * tt[0] - nn[0] * tt[2];
    bb[2] = nn[0] * tt[1] - nn[1] * tt[0];
    for (k = 0; k < 3; ++k) {
        o[3 * k] = tt[k];
        o[3 * k + 1] = nn[k];
        o[3 * k + 2] = bb[k];
    }
}

/* Groom strands [first, first + count): add each strand's rest offsets,
   turned by the blend of its guides' rotations from rest (current frame
   times rest frame transposed). Runs after the blend of guide points, on
   points laid out as hf__fur_clump_pass's. */
HF__PRIVATE void hf__groom_offsets(const hf_fur *f, int first, int count,
                                   float *pts, int pts_first)
{
    const int P = f->P;
    int s, k, i, j, c;
    for (s = first; s < first + count; ++s) {
        const hf_strand_binding *b = &f->bindings[s];
        const float *off = f->offsets + (size_t)s * (size_t)P * 3u;
        float *out = pts + (size_t)(s - pts_first) * (size_t)P * 3u;
        double R[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        for (k = 0; k < 3; ++k) {
            const uint32_t g = b->guide[k];
            double cur[9], rest[9];
            if (b->weight[k] == 0.0f) continue;
            hf__groom_frame(f->root_nrm + 3 * g, f->root_tan + 3 * g, cur);
            hf__groom_frame(f->rest_frame + 9 * g + 3, f->rest_frame + 9 * g + 6,
                            rest);
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) {
                    double m = 0.0;
                    for (c = 0; c < 3; ++c) m += cur[3 * i + c] * rest[3 * j + c];
                    R[3 * i + j] += b->weight[k] * m;
                }
        }
        for (j = 0; j < P; ++j) {
            const float *o = off + 3 * j;
            for (i = 0; i < 3; ++i)
                out[3 * j + i] += (float)(R[3 * i] * o[0] + R[3 * i + 1] * o[1] +
                                          R[3 * i + 2] * o[2]);
        }
    }
}

/* Closest point to p on triangle abc, as barycentric (u, v) on b - a and
   c - a (Ericson, Real-Time Collision Detection, 5.1.5). */
HF__PRIVATE void hf__closest_on_triangle(const double *p, const double *a,
                                         const double *b, const double *c,
                                         double *u, double *v)
{
    double ab[3], ac[3], ap[3], bp[3], cp[3], d1, d2, d3, d4, d5, d6, va, vb, vc, den;
    int k;
    for (k = 0; k < 3; ++k) {
        ab[k] = b[k] - a[k]; ac[k] = c[k] - a[k]; ap[k] = p[k] - a[k];
        bp[k] = p[k] - b[k]; cp[k] = p[k] - c[k];
    }
    d1 = ab[0] * ap[0] + ab[1] * ap[1] + ab[2] * ap[2];
    d2 = ac[0] * ap[0] + ac[1] * ap[1] + ac[2] * ap[2];
    if (d1 <= 0.0 && d2 <= 0.0) { *u = 0.0; *v = 0.0; return; }
    d3 = ab[0] * bp[0] + ab[1] * bp[1] + ab[2] * bp[2];
    d4 = ac[0] * bp[0] + ac[1] * bp[1] + ac[2] * bp[2];
    if (d3 >= 0.0 && d4 <= d3) { *u = 1.0; *v = 0.0; return; }
    vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        *u = d1 - d3 != 0.0 ? d1 / (d1 - d3) : 0.0; *v = 0.0; return;
    }
    d5 = ab[0] * cp[0] + ab[1] * cp[1] + ab[2] * cp[2];
    d6 = ac[0] * cp[0] + ac[1] * cp[1] + ac[2] * cp[2];
    if (d6 >= 0.0 && d5 <= d6) { *u = 0.0; *v = 1.0; return; }
    vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        *u = 0.0; *v = d2 - d6 != 0.0 ? d2 / (d2 - d6) : 0.0; return;
    }
    va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        double w = (d4 - d3) + (d5 - d6);
        w = w != 0.0 ? (d4 - d3) / w : 0.0;
        *u = 1.0 - w; *v = w; return;
    }
    den = va + vb + vc;
    if (den == 0.0) { *u = *v = 0.0; return; }
    *u = vb / den;
    *v = vc / den;
}

/* A scalp triangle's frame: the point at (u, v), the face normal and the
   first edge (float, as the roots are). */
HF__PRIVATE void hf__scalp_frame(const hf_mesh *m, const uint32_t *ref,
                                 float u, float v, float *pos, float *nrm,
                                 float *tan)
{
    const float *a = hf__mesh_pos(m, (int)ref[0]), *b = hf__mesh_pos(m, (int)ref[1]),
                *c = hf__mesh_pos(m, (int)ref[2]);
    float e1[3], e2[3];
    int k;
    hf__sub3(e1, b, a);
    hf__sub3(e2, c, a);
    for (k = 0; k < 3; ++k) pos[k] = a[k] + u * e1[k] + v * e2[k];
    hf__cross3(nrm, e1, e2);
    HF_MEMCPY(tan, e1, 12);
}

/* Each guide root to its nearest point on the scalp at rest. */
HF__PRIVATE hf_result hf__groom_bind_scalp(hf_fur *f, const hf_mesh *m)
{
    const int G = f->guide_count, T = m->triangle_count;
    hf_result r = HF_OK;
    int g, t, k;
    f->ref = (uint32_t *)hf__fur_array(f, (size_t)G * 3u, sizeof(uint32_t), &r);
    f->scalp_bind = (float *)hf__fur_array(f, (size_t)G * 11u, sizeof(float), &r);
    if (r != HF_OK) return r;
    for (g = 0; g < G; ++g) {
        double p[3], best = -1.0, bu = 0.0, bv = 0.0;
        int bt = 0;
        float *sb = f->scalp_bind + 11 * g;
        for (k = 0; k < 3; ++k) p[k] = f->root_pos[3 * g + k];
        for (t = 0; t < T; ++t) {
            double a[3], b[3], c[3], u, v, e = 0.0;
            const float *pa = hf__mesh_pos(m, (int)m->indices[3 * t]),
                        *pb = hf__mesh_pos(m, (int)m->indices[3 * t + 1]),
                        *pc = hf__mesh_pos(m, (int)m->indices[3 * t + 2]);
            for (k = 0; k < 3; ++k) { a[k] = pa[k]; b[k] = pb[k]; c[k] = pc[k]; }
            hf__closest_on_triangle(p, a, b, c, &u, &v);
            for (k = 0; k < 3; ++k) {
                double q = a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]) - p[k];
                e += q * q;
            }
            if (best < 0.0 || e < best) { best = e; bt = t; bu = u; bv = v; }
        }
        for (k = 0; k < 3; ++k) f->ref[3 * g + k] = m->indices[3 * bt + k];
        sb[0] = (float)bu;
        sb[1] = (float)bv;
        hf__scalp_frame(m, f->ref + 3 * g, sb[0], sb[1], sb + 2, sb + 5, sb + 8);
    }
    f->vertex_count = m->vertex_count;
    f->base_triangle_count = m->triangle_count;
    return HF_OK;
}

/* A groom's root frame of guide g from the skinned scalp: its rest root
   frame turned and moved as its triangle's frame was. */
HF__PRIVATE void hf__groom_root_from_scalp(const hf_fur *f, const hf_mesh *m,
                                           int g, float *pos, float *nrm,
                                           float *tan)
{
    const float *sb = f->scalp_bind + 11 * g, *rf = f->rest_frame + 9 * g;
    float at[3], n[3], t[3];
    double cur[9], rest[9], R[9], d[3];
    int i, j, c;
    hf__scalp_frame(m, f->ref + 3 * g, sb[0], sb[1], at, n, t);
    hf__groom_frame(n, t, cur);
    hf__groom_frame(sb + 5, sb + 8, rest);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            R[3 * i + j] = 0.0;
            for (c = 0; c < 3; ++c) R[3 * i + j] += cur[3 * i + c] * rest[3 * j + c];
        }
    for (i = 0; i < 3; ++i) d[i] = (double)rf[i] - sb[2 + i];
    for (i = 0; i < 3; ++i) {
        pos[i] = (float)(at[i] + R[3 * i] * d[0] + R[3 * i + 1] * d[1] +
                         R[3 * i + 2] * d[2]);
        nrm[i] = (float)(R[3 * i] * rf[3] + R[3 * i + 1] * rf[4] +
                         R[3 * i + 2] * rf[5]);
        tan[i] = (float)(R[3 * i] * rf[6] + R[3 * i + 1] * rf[7] +
                         R[3 * i + 2] * rf[8]);
    }
}

/* Guides [first, first + count) of a groom: their root frames from the
   skinned scalp, all computed and checked (within HF_ROPE_MAX_COORD)
   before any is stored, so that a refused call sets nothing. */
HF__PRIVATE hf_result hf__groom_roots_from_scalp(hf_fur *f, const hf_mesh *m,
                                                 int first, int count)
{
    float pos[3], nrm[3], tan[3];
    int g;
    for (g = first; g < first + count; ++g) {
        hf__groom_root_from_scalp(f, m, g, pos, nrm, tan);
        if (!hf__rope_coord_ok(pos)) return HF_ERROR_BAD_PARAMETER;
    }
    for (g = first; g < first + count; ++g)
        hf__groom_root_from_scalp(f, m, g, f->root_pos + 3 * g,
                                  f->root_nrm + 3 * g, f->root_tan + 3 * g);
    return HF_OK;
}

/* The groom's own fields (the ropes check their parameters). */
HF__PRIVATE hf_result hf__groom_check(const hf_groom_desc *d, int P,
                                      float fraction, hf_diag *diag)
{
    long long total = 0;
    hf_result r;
    int i, k;
    if (!d->points || !d->strand_points)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "points", -1,
                        "points or strand_points is NULL");
    if (d->strand_count < 1 || d->strand_count > (1 << 24))
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "strand_count", -1,
                        "strand_count %d is outside 1 .. 16777216",
                        d->strand_count);
    if (P < 2 || P > HF_MAX_POINTS)
        return hf__fail(diag, HF_ERROR_BAD_COUNT, "points_per_strand", -1,
                        "points_per_strand %d is outside 2..%d", P,
                        HF_MAX_POINTS);
    if (!hf__finitef(fraction) || !(fraction > 0.0f) || fraction > 1.0f)
        return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "guide_fraction", -1,
                        "guide_fraction %g is outside (0, 1]",
                        (double)fraction);
    if ((r = hf__fur_options_check(d->grid_resolution, d->keep_length,
                                   diag)) != HF_OK)
        return r;
    for (i = 0; i < d->strand_count; ++i) {
        const int n = d->strand_points[i];
        const float *p;
        double len = 0.0;
        if (n < 2 || n > (1 << 24))
            return hf__fail(diag, HF_ERROR_BAD_COUNT, "strand_points", i,
                            "strand %d has %d points (2 .. 16777216)", i, n);
        p = d->points + 3 * total;
        for (k = 0; k < 3 * n; ++k) {
            if (!hf__finitef(p[k]))
                return hf__fail(diag, HF_ERROR_NON_FINITE, "points",
                                total + k / 3, "strand %d, point %d is "
                                "non-finite", i, k / 3);
            if (HF_FABS(p[k]) > HF_ROPE_MAX_COORD)
                return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "points",
                                total + k / 3, "strand %d, point %d is "
                                "beyond HF_ROPE_MAX_COORD", i, k / 3);
        }
        for (k = 1; k < n; ++k) {
            double dx = p[3 * k] - p[3 * k - 3], dy = p[3 * k + 1] - p[3 * k - 2],
                   dz = p[3 * k + 2] - p[3 * k - 1];
            len += HF_SQRT(dx * dx + dy * dy + dz * dz);
        }
        if (!(len > 0.0))
            return hf__fail(diag, HF_ERROR_BAD_PARAMETER, "strand_points", i,
                            "strand %d has zero length", i);
        total += n;
        if (total > 0x7fffffffLL)
            return hf__fail(diag, HF_ERROR_OVERFLOW, "strand_points", i,
                            "more than 2^31 points");
        if (d->colors)
            for (k = 0; k < 3; ++k)
                if (!hf__finitef(d->colors[3 * i + k]))
                    return hf__fail(diag, HF_ERROR_NON_FINITE, "colors", i,
                                    "strand %d's colour is non-finite", i);
    }
    return HF_OK;
}

/* The groom's strands resampled in LOD order, the guides, bindings,
   offsets, records and ropes. */
HF__PRIVATE hf_result hf__groom_build(hf_fur *f, const hf_groom_desc *d,
                                      float fraction)
{
    const int S = d->strand_count, P = f->P;
    const size_t SP3 = (size_t)S * (size_t)P * 3u;
    int G, i, j, k;
    hf_result r = HF_OK;
    uint32_t *order;
    long long *start;
    double *tmp;
    hf_rng rng;
    G = (int)(fraction * (float)S + 0.5f);
    if (G < 1) G = 1;
    if (G > S) G = S;
    f->strand_count = f->drawn = S;
    f->guide_count = f->pure_count = G;
    f->strands = (hf_strand *)hf__fur_array(f, (size_t)S, sizeof(hf_strand), &r);
    f->bindings = (hf_strand_binding *)hf__fur_array(f, (size_t)S,
                                                     sizeof(hf_strand_binding), &r);
    f->strand_lengths = (float *)hf__fur_array(f, (size_t)S, sizeof(float), &r);
    f->strand_rgba = (float *)hf__fur_array(f, (size_t)S * 4u, sizeof(float), &r);
    f->strand_uv = (float *)hf__fur_array(f, (size_t)S * 2u, sizeof(float), &r);
    f->strand_c3x = (float *)hf__fur_array(f, (size_t)S, sizeof(float), &r);
    f->strand_points = hf__fur_lines(f, SP3, &r);
    f->offsets = (float *)hf__fur_array(f, SP3, sizeof(float), &r);
    f->guide_points = hf__fur_lines(f, (size_t)G * (size_t)P * 3u, &r);
    f->root_pos = (float *)hf__fur_array(f, (size_t)G * 3u, sizeof(float), &r);
    f->root_nrm = (float *)hf__fur_array(f, (size_t)G * 3u, sizeof(float), &r);
    f->root_tan = (float *)hf__fur_array(f, (size_t)G * 3u, sizeof(float), &r);
    order = (uint32_t *)hf__fur_array(f, (size_t)S, sizeof(uint32_t), &r);
    start = (long long *)hf__fur_array(f, (size_t)S, sizeof(long long), &r);
    tmp = (double *)hf__fur_array(f, (size_t)P * 3u, sizeof(double), &r);
    if (r != HF_OK) goto done;
    HF_MEMSET(f->strands, 0, sizeof(hf_strand) * (size_t)S);
    HF_MEMSET(f->strand_uv, 0, sizeof(float) * 2u * (size_t)S);
    HF_MEMSET(f->strand_c3x, 0, sizeof(float) * (size_t)S);
    /* LOD order: a shuffle, so every prefix is spread over the groom */
    for (i = 0; i < S; ++i) order[i] = (uint32_t)i;
    hf_rng_seed(&rng, d->seed, 0x6700u);
    for (i = S - 1; i > 0; --i) {
        uint32_t t, x = hf_rng_below(&rng, (uint32_t)i + 1u);
        t = order[i]; order[i] = order[x]; order[x] = t;
    }
    start[0] = 0;
    for (i = 1; i < S; ++i) start[i] = start[i - 1] + d->strand_points[i - 1];
    /* each strand, resampled, at its place in LOD order */
    for (i = 0; i < S; ++i) {
        const uint32_t src = order[i];
        float *o = f->strand_points + (size_t)i * (size_t)P * 3u;
        const float *p = d->points + 3 * start[src];
        double len = hf__curve_resample(p, d->strand_points[src], P, tmp);
        for (j = 0; j < 3 * P; ++j) o[j] = (float)(p[j % 3] + tmp[j]);
        f->strand_lengths[i] = (float)len;
        for (k = 0; k < 3; ++k)
            f->strand_rgba[4 * i + k] = d->colors ? d->colors[3 * src + k] : 1.0f;
        f->strand_rgba[4 * i + 3] = 1.0f;
    }
    /* guides: the first G strands; root frame from the first segment */
    HF_MEMCPY(f->guide_points, f->strand_points,
              sizeof(float) * (size_t)G * (size_t)P * 3u);
    for (i = 0; i < G; ++i) {
        const float *q = f->guide_points + (size_t)i * (size_t)P * 3u;
        float *n = f->root_nrm + 3 * i, *t = f->root_tan + 3 * i;
        double l;
        for (k = 0; k < 3; ++k) n[k] = q[3 + k] - q[k];
        l = HF_SQRT((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (l > 0.0) for (k = 0; k < 3; ++k) n[k] = (float)(n[k] / l);
        else { n[0] = 0.0f; n[1] = 1.0f; n[2] = 0.0f; }
        /* a tangent across it: n x (x or y axis) */
        if (HF_FABS(n[0]) < 0.9f) { t[0] = 0.0f; t[1] = n[2]; t[2] = -n[1]; }
        else { t[0] = -n[2]; t[1] = 0.0f; t[2] = n[0]; }
        HF_MEMCPY(f->root_pos + 3 * i, q, 12);
    }
    /* bindings: a guide to itself; others to the nearest three guides */
    for (i = 0; i < S; ++i) {
        hf_strand_binding *b = &f->bindings[i];
        const float *q = f->strand_points + (size_t)i * (size_t)P * 3u;
        double dist[3] = {-1.0, -1.0, -1.0}, wsum = 0.0;
        int near[3] = {-1, -1, -1}, g;
        b->length_scale = 1.0f;
        if (i < G) {
            b->guide[0] = b->guide[1] = b->guide[2] = (uint32_t)i;
            b->weight[0] = 1.0f;
            b->weight[1] = b->weight[2] = 0.0f;
        } else {
            for (g = 0; g < G; ++g) {
                const float *gr = f->root_pos + 3 * g;
                double dx = gr[0] - q[0], dy = gr[1] - q[1], dz = gr[2] - q[2],
                       e = dx * dx + dy * dy + dz * dz;
                int at = 3;
                while (at > 0 && (near[at - 1] < 0 || e < dist[at - 1])) --at;
                if (at == 3) continue;
                for (k = 2; k > at; --k) {
                    near[k] = near[k - 1];
                    dist[k] = dist[k - 1];
                }
                near[at] = g;
                dist[at] = e;
            }
            for (k = 0; k < 3; ++k)
                if (near[k] >= 0) wsum += 1.0 / (dist[k] + 1e-30);
            for (k = 0; k < 3; ++k) {
                b->guide[k] = (uint32_t)(near[k] >= 0 ? near[k] : near[0]);
                b->weight[k] = near[k] >= 0
                                   ? (float)(1.0 / (dist[k] + 1e-30) / wsum)
                                   : 0.0f;
            }
        }
    }
    /* offsets: own rest points minus the blend of the guides' */
    for (i = 0; i < S; ++i) {
        const hf_strand_binding *b = &f->bindings[i];
        const float *q = f->strand_points + (size_t)i * (size_t)P * 3u;
        float *o = f->offsets + (size_t)i * (size_t)P * 3u;
        for (j = 0; j < 3 * P; ++j) {
            float blend = 0.0f;
            for (k = 0; k < 3; ++k)
                blend += b->weight[k] *
                         f->guide_points[(size_t)b->guide[k] * (size_t)P * 3u +
                                         (size_t)j];
            o[j] = q[j] - blend;
        }
    }
    if ((r = hf_ropes_create(G, P, &f->alloc, &f->ropes)) != HF_OK ||
        (r = hf__ropes_set_rest(f->ropes, 0, G, f->guide_points, 0, f->root_pos,
                                f->root_nrm, f->root_tan, 0, f->simd)) !=
            HF_OK ||
        (r = hf__fur_keep_rest_frames(f)) != HF_OK ||
        (d->scalp && (r = hf__groom_bind_scalp(f, d->scalp)) != HF_OK) ||
        (d->grid_resolution > 0 &&
         (r = hf_grid_create(d->grid_resolution, &f->alloc, &f->grid)) !=
             HF_OK))
        goto done;
    f->lod = 1.0f;
    f->width_scale = 1.0f;
    f->lod_sim = 1;
    r = hf_fur_interpolate(f, 0, S);
    if (r == HF_OK && d->keep_length) r = hf__fur_rest_segments(f);
done:
    hf__free(&f->alloc, order);
    hf__free(&f->alloc, start);
    hf__free(&f->alloc, tmp);
    return r;
}

HFDEF hf_result hf_fur_create_groom(const hf_groom_desc *desc, hf_fur **out_fur,
                                    hf_diag *diag)
{
    hf_rope_params rope, zero;
    hf_allocator alloc;
    hf_fur *f;
    hf_result r;
    int P;
    float fraction;
    if (!desc || !out_fur)
        return hf__fail(diag, HF_ERROR_NULL_POINTER, "desc", -1,
                        "desc or out_fur is NULL");
    P = hf__def_i(desc->points_per_strand, 16);
    fraction = hf__def_f(desc->guide_fraction, 0.1f);
    if ((r = hf__groom_check(desc, P, fraction, diag)) != HF_OK) return r;
    if (desc->scalp && (r = hf_mesh_validate(desc->scalp, diag)) != HF_OK)
        return r;
    HF_MEMSET(&zero, 0, sizeof zero);
    hf__rope_params_resolve(desc->rope_params ? desc->rope_params : &zero, &rope);
    if ((r = hf__rope_params_check(&rope, diag)) != HF_OK) return r;
    HF_MEMSET(&alloc, 0, sizeof alloc);
    if (desc->allocator) alloc = *desc->allocator;
    f = (hf_fur *)hf__alloc(&alloc, sizeof *f);
    if (!f)
        return hf__fail(diag, HF_ERROR_OUT_OF_MEMORY, "fur", -1,
                        "out of memory");
    HF_MEMSET(f, 0, sizeof *f);
    f->alloc = alloc;
    f->P = P;
    f->groom = 1;
    f->rope[0] = rope;
    f->lod_threshold = 0.5f;
    if ((r = hf__groom_build(f, desc, fraction)) != HF_OK) {
        hf_fur_destroy(f);
        return hf__fail(diag, r, "groom", -1, "making the groom: %s",
                        hf_result_string(r));
    }
    *out_fur = f;
    return HF_OK;
}

HFDEF hf_result hf_fur_set_transform(hf_fur *f, const float m[12], int first,
                                     int count)
{
    int g, k;
    if (!f || !m) return HF_ERROR_NULL_POINTER;
    if (!hf__range_ok(first, count) || first + count > f->guide_count)
        return HF_ERROR_BAD_RANGE;
    for (k = 0; k < 12; ++k)
        if (!hf__finitef(m[k])) return HF_ERROR_NON_FINITE;
    for (g = first; g < first + count; ++g) {
        const float *rf = f->rest_frame + 9 * g;
        for (k = 0; k < 3; ++k) {
            const float *row = m + 4 * k;
            f->root_pos[3 * g + k] = row[0] * rf[0] + row[1] * rf[1] +
                                     row[2] * rf[2] + row[3];
            f->root_nrm[3 * g + k] = row[0] * rf[3] + row[1] * rf[4] +
                                     row[2] * rf[5];
            f->root_tan[3 * g + k] = row[0] * rf[6] + row[1] * rf[7] +
                                     row[2] * rf[8];
        }
    }
    return hf__ropes_set_roots(f->ropes, first, count, f->root_pos, f->root_nrm,
                               f->root_tan, 0, f->simd);
}

HFDEF hf_result hf_fur_get_info(const hf_fur *f, hf_fur_info *info)
{
    if (!f || !info) return HF_ERROR_NULL_POINTER;
    HF_MEMSET(info, 0, sizeof *info);
    info->points_per_strand = f->P;
    info->guide_count = f->guide_count;
    info->pure_guide_count = f->pure_count;
    info->lod_guide_count = f->lod_count;
    info->strand_count = f->strand_count;
    info->drawn_strand_count = f->drawn;
    info->lod_guides_simulated = f->lod_sim;
    info->lod = f->lod;
    info->width_scale = f->width_scale;
    info->triangle_count = f->triangle_count;
    hf_ropes_roots_inside(f->ropes, 0, f->guide_count, &info->roots_inside);
    info->grid_resolution = f->grid ? f->grid->resolution : 0;
    info->guide_points = f->guide_points;
    info->strand_points = f->strand_points;
    info->strands = f->strands;
    info->strand_lengths = f->strand_lengths;
    info->strand_colors = f->strand_rgba;
    info->strand_uv = f->strand_uv;
    info->strand_color3d_x = f->strand_c3x;
    return HF_OK;
}

HFDEF hf_result hf_fur_set_lod(hf_fur *f, float lod)
{
    int sim;
    if (!f) return HF_ERROR_NULL_POINTER;
    if (!(lod > 0.0f)) lod = 0.0f; /* NaN too */
    if (lod > 1.0f) lod = 1.0f;
    f->lod = lod;
    f->drawn = hf_lod_strand_count(f->strand_count, lod);
    f->width_scale = hf_lod_width_scale(f->strand_count, f->drawn);
    sim = lod >= f->lod_threshold;
    if (sim && !f->lod_sim && f->lod_count > 0) {
        /* LOD guides wake up where they are drawn (interpolated), at rest
           velocity: no jump; those the caller set animated stay so.
           Point-major rope state: [j * G + r]. */
        hf_ropes *ro = f->ropes;
        const int G = f->guide_count;
        int r, j;
        for (r = f->pure_count; r < G; ++r) {
            if (f->user_mode[r] != HF_ROPE_SIMULATED) continue;
            hf_ropes_set_mode(ro, r, 1, HF_ROPE_SIMULATED);
            for (j = 0; j < f->P; ++j) {
                const float *p = f->guide_points + ((size_t)r * f->P + j) * 3u;
                const size_t e = (size_t)j * (size_t)G + (size_t)r;
                ro->x[e] = ro->px[e] = p[0];
                ro->y[e] = ro->py[e] = p[1];
                ro->z[e] = ro->pz[e] = p[2];
            }
        }
    } else if (!sim && f->lod_sim && f->lod_count > 0) {
        /* asleep they are carried rigidly (cheap) and drawn interpolated */
        hf_ropes_set_mode(f->ropes, f->pure_count, f->lod_count,
                          HF_ROPE_ANIMATED);
    }
    f->lod_sim = sim;
    return HF_OK;
}

HF__PRIVATE int hf__finite3(const float *p)
{
    return hf__finitef(p[0]) && hf__finitef(p[1]) && hf__finitef(p[2]);
}

HFDEF hf_result hf_fur_set_roots(hf_fur *f, const hf_mesh *m, int first,
                                 int count)
{
    int g, k;
    hf_result r;
    if (!f || !m || !m->positions) return HF_ERROR_NULL_POINTER;
    if (f->groom && !f->scalp_bind)
        return HF_ERROR_BAD_PARAMETER; /* no scalp: hf_fur_set_transform */
    if (m->vertex_count != f->vertex_count ||
        m->triangle_count != f->base_triangle_count)
        return HF_ERROR_BAD_COUNT;
    if (!hf__range_ok(first, count) || first + count > f->guide_count)
        return HF_ERROR_BAD_RANGE;
    if (!hf__stride_ok(m->positions, m->position_stride, 12) ||
        !hf__stride_ok(m->normals, m->normal_stride, 12))
        return HF_ERROR_BAD_STRIDE;
    /* check every value read before anything is set */
    for (g = first; g < first + count; ++g)
        for (k = 0; k < 3; ++k) {
            const int v = (int)f->ref[3 * g + k];
            if (!hf__finite3(hf__mesh_pos(m, v)) ||
                (m->normals && k == 0 &&
                 !hf__finite3(hf__attr(m->normals, m->normal_stride, 12, v))))
                return HF_ERROR_NON_FINITE;
        }
    if (f->groom) { /* roots bound to scalp triangles */
        if ((r = hf__groom_roots_from_scalp(f, m, first, count)) != HF_OK)
            return r;
        return hf__ropes_set_roots(f->ropes, first, count, f->root_pos,
                                   f->root_nrm, f->root_tan, 0, f->simd);
    }
    /* LOD guides: positions (and normals) blended on their base triangle */
    {
        int lf = first > f->pure_count ? first - f->pure_count : 0;
        int le = first + count - f->pure_count;
        if (le > lf) {
            r = hf_tess_evaluate(m, f->added, f->lod_count, lf, le - lf,
                                 f->root_pos + 3u * (size_t)f->pure_count,
                                 m->normals ? f->root_nrm +
                                                  3u * (size_t)f->pure_count
                                            : NULL,
                                 NULL);
            if (r != HF_OK) return r;
        }
    }
    for (g = first; g < first + count; ++g) {
        const uint32_t *ref = f->ref + 3 * g;
        const float *a = hf__mesh_pos(m, (int)ref[0]);
        const float *b = hf__mesh_pos(m, (int)ref[1]);
        const float *c = hf__mesh_pos(m, (int)ref[2]);
        float *pos = f->root_pos + 3 * g, *nrm = f->root_nrm + 3 * g;
        float e1[3], e2[3];
        hf__sub3(e1, b, a);
        hf__sub3(e2, c, a);
        HF_MEMCPY(f->root_tan + 3 * g, e1, sizeof e1);
        if (g < f->pure_count) {
            HF_MEMCPY(pos, a, 12);
            if (m->normals)
                HF_MEMCPY(nrm, hf__attr(m->normals, m->normal_stride, 12,
                                        (int)ref[0]),
                          12);
        }
        if (!m->normals || hf__dot3(nrm, nrm) == 0.0f) {
            /* face normal; a degenerate face keeps the rest-time up axis */
            hf__cross3(nrm, e1, e2);
            if (!(hf__dot3(nrm, nrm) > 0.0f) || !hf__finite3(nrm)) {
                nrm[0] = 0.0f;
                nrm[1] = 0.0f;
                nrm[2] = 1.0f;
            }
        }
    }
    return hf__ropes_set_roots(f->ropes, first, count, f->root_pos, f->root_nrm,
                               f->root_tan, 0, f->simd);
}

/* Step guides [first, end) in runs that share a rope parameter set (each
   rope is stepped on its own, so runs give the bytes one call would). */
/* Step guides [first, end) run by run of one parameter set, each pushed
   by the grid first where there is one. The step's own checks come first,
   so that a refused call changes nothing. */
HF__PRIVATE hf_result hf__fur_step_runs(hf_fur *f, int first, int end,
                                        float dt, const hf_collider *colliders,
                                        int collider_count)
{
    hf_result r;
    int a = first;
    if ((r = hf__colliders_check(colliders, collider_count)) != HF_OK)
        return r;
    if (!hf__finitef(dt) || !(dt > 0.0f)) return HF_ERROR_BAD_TIME_STEP;
    while (a < end) {
        int b = a + 1;
        hf_rope_params p = f->rope[f->rope_of[a]];
        while (b < end && f->rope_of[b] == f->rope_of[a]) ++b;
        p.simd = f->simd; /* the fur's kernel level (hf_fur_set_kernels) */
        if (f->grid &&
            (r = hf_ropes_apply_grid(f->ropes, a, b - a, dt, &p, f->grid)) !=
                HF_OK)
            return r;
        r = hf_ropes_step(f->ropes, a, b - a, dt, &p, colliders,
                          collider_count);
        if (r != HF_OK) return r;
        a = b;
    }
    return HF_OK;
}

HFDEF hf_result hf_fur_build_grid(hf_fur *f, int first, int count)
{
    if (!f) return HF_ERROR_NULL_POINTER;
    if (!f->grid) return first == 0 && count == 0 ? HF_OK : HF_ERROR_BAD_RANGE;
    return hf_grid_build(f->grid, f->ropes,
                         f->lod_sim ? f->guide_count : f->pure_count, first,
                         count);
}

HFDEF hf_result hf_fur_settle_rest(hf_fur *f, float seconds,
                                   const hf_collider *colliders,
                                   int collider_count)
{
    hf_rope_params keep[HF_FUR_ROPE_SETS];
    unsigned char *mode;
    hf_result r;
    int steps, s, k, g, G;
    if (!f) return HF_ERROR_NULL_POINTER;
    if (!hf__finitef(seconds) || seconds < 0.0f || seconds > 600.0f)
        return HF_ERROR_BAD_PARAMETER;
    if ((r = hf__colliders_check(colliders, collider_count)) != HF_OK)
        return r;
    G = f->guide_count;
    mode = (unsigned char *)hf__alloc(&f->alloc, (size_t)G);
    if (!mode) return HF_ERROR_OUT_OF_MEMORY;
    /* every guide simulated, the sets made into settling ones */
    for (g = 0; g < G; ++g) {
        mode[g] = f->ropes->mode[g];
        f->ropes->mode[g] = HF_ROPE_SIMULATED;
        f->ropes->blend[g] = 0.0f;
    }
    for (k = 0; k < HF_FUR_ROPE_SETS; ++k) {
        hf_rope_params *p = &f->rope[k];
        keep[k] = *p;
        p->global_stiffness_root = p->global_stiffness_tip = 0.0f;
        p->wind[0] = p->wind[1] = p->wind[2] = 0.0f;
        p->turbulence = 0.0f;
        if (p->damping < 0.1f) p->damping = 0.1f;
    }
    steps = (int)(seconds * 60.0f + 0.5f);
    for (s = 0; s < steps && r == HF_OK; ++s) {
        if (f->grid) r = hf_grid_build(f->grid, f->ropes, G, 0,
                                       f->grid->resolution);
        if (r == HF_OK)
            r = hf__fur_step_runs(f, 0, G, 1.0f / 60.0f, colliders,
                                  collider_count);
    }
    for (k = 0; k < HF_FUR_ROPE_SETS; ++k) f->rope[k] = keep[k];
    if (r == HF_OK) r = hf_ropes_rest_from_pose(f->ropes, 0, G);
    for (g = 0; g < G; ++g) {
        f->ropes->mode[g] = mode[g];
        f->ropes->blend[g] = mode[g] == HF_ROPE_ANIMATED ? 1.0f : 0.0f;
    }
    hf__free(&f->alloc, mode);
    if (r != HF_OK) return r;
    hf__ropes_copy(f->ropes, 0, G, f->guide_points, 12, 0, f->simd);
    return HF_OK;
}

HFDEF hf_result hf_fur_simulate(hf_fur *f, int first, int count, float dt,
                                const hf_collider *colliders,
                                int collider_count)
{
    hf_result r;
    int end;
    if (!f) return HF_ERROR_NULL_POINTER;
    if (!hf__range_ok(first, count) || first + count > f->guide_count)
        return HF_ERROR_BAD_RANGE;
    end = first + count;
    if (!f->lod_sim && end > f->pure_count) {
        /* sleeping LOD guides are still carried by their roots, so they
           wake up in place; they are stepped but not copied out */
        int lf = first > f->pure_count ? first : f->pure_count;
        r = hf__fur_step_runs(f, lf, end, dt, colliders, collider_count);
        if (r != HF_OK) return r;
        end = lf;
    }
    if (end <= first) return HF_OK;
    r = hf__fur_step_runs(f, first, end, dt, colliders, collider_count);
    if (r != HF_OK) return r;
    hf__ropes_copy(f->ropes, first, end, f->guide_points, 12, 0, f->simd);
    return HF_OK;
}

/* The fur's guides, bindings and parameters are valid by construction
   (guides come from the ropes, finite and within reach of their roots),
   so its calls skip hf_interpolate's per-call checks. */
HFDEF hf_result hf_fur_interpolate_guides(hf_fur *f, int first, int count)
{
    if (!f) return HF_ERROR_NULL_POINTER;
    if (!hf__range_ok(first, count) || first + count > f->lod_count)
        return HF_ERROR_BAD_RANGE;
    if (f->lod_sim || count == 0) return HF_OK;
    hf__interpolate_run(f->guide_points, f->lod_bindings, first, count, f->P,
                        0.0f,
                        f->guide_points +
                            (size_t)f->pure_count * (size_t)f->P * 3u,
                        0, f->simd, 0);
    return HF_OK;
}

/* Whether a fur's strands are the guides' blend alone (clumped to the
   main guide at most): no clump pass or groom offsets follow it. */
HF__PRIVATE int hf__fur_blend_only(const hf_fur *f)
{
    return !f->leader && !f->strand_clump && !f->offsets && !f->rest_seg;
}

/* Strands [first, first + count) blended from the guides, clumped and
   groomed, into pts + (s - pts_first) * 3 P. */
HF__PRIVATE void hf__fur_strands(const hf_fur *f, int first, int count,
                                 float *pts, int pts_first, int nt)
{
    const int pass = f->leader || f->strand_clump; /* clumps of their own */
    hf__interpolate_run(f->guide_points, f->bindings, first, count, f->P,
                        pass ? 0.0f : f->clump, pts, pts_first, f->simd, nt);
    if (pass) hf__fur_clump_pass(f, first, count, pts, pts_first);
    if (f->offsets) hf__groom_offsets(f, first, count, pts, pts_first);
    if (f->rest_seg) hf__fur_keep_length(f, first, count, pts, pts_first);
}

/* The strands a fur call's streaming stores are chosen for
   (nontemporal 0): the LOD's drawn strands, or the call's if more, so
   that every range of a frame split over threads or jobs chooses alike */
HF__PRIVATE int hf__fur_sized(const hf_fur *f, int count)
{
    return count > f->drawn ? count : f->drawn;
}

HFDEF hf_result hf_fur_interpolate(hf_fur *f, int first, int count)
{
    if (!f) return HF_ERROR_NULL_POINTER;
    if (!hf__range_ok(first, count) || first + count > f->strand_count)
        return HF_ERROR_BAD_RANGE;
    hf__fur_strands(f, first, count, f->strand_points, 0,
                    hf__streaming(f->nontemporal,
                                  (size_t)hf__fur_sized(f, count) *
                                      (size_t)f->P * 12u,
                                  HF_STREAM_MIN_BYTES));
    return HF_OK;
}

HF__PRIVATE hf_result hf__fur_view(const hf_fur *f, int first, int count,
                                   const hf_ribbon_params *view,
                                   hf_ribbon_params *p, hf_ribbon_strands *s)
{
    if (!f || !view) return HF_ERROR_NULL_POINTER;
    if (!hf__range_ok(first, count) || first + count > f->strand_count)
        return HF_ERROR_BAD_RANGE;
    hf__ribbon_params_resolve(view, p);
    p->points_per_strand = f->P;
    /* a valid view stays valid whatever the LOD's scale (the product is
       clamped); an invalid one is left for hf_ribbons to reject */
    if (p->width_scale >= 0.0f && p->width_scale <= HF_MAX_ABS) {
        p->width_scale *= f->width_scale;
        if (p->width_scale > HF_MAX_ABS) p->width_scale = HF_MAX_ABS;
    }
    HF_MEMSET(s, 0, sizeof *s);
    s->points = f->strand_points;
    s->root_uv = f->strand_uv;
    s->color = f->strand_rgba;
    s->color3d_x = f->strand_c3x;
    s->width = f->strand_width;
    return HF_OK;
}

HFDEF hf_result hf_fur_ribbons(const hf_fur *f, int first, int count,
                               const hf_ribbon_params *view,
                               const hf_ribbon_output *out)
{
    hf_ribbon_params p;
    hf_ribbon_strands s;
    hf_result r = hf__fur_view(f, first, count, view, &p, &s);
    return r != HF_OK ? r
                      : hf__ribbons(&s, first, count, &p, out,
                                    hf__fur_sized(f, count));
}

HFDEF hf_result hf_fur_points(const hf_fur *f, int first, int count,
                              const hf_ribbon_params *view, float *out4)
{
    hf_ribbon_params p;
    hf_ribbon_strands s;
    hf_result r = hf__fur_view(f, first, count, view, &p, &s);
    return r != HF_OK ? r
                      : hf__ribbon_points(&s, first, count, &p, out4,
                                          hf__fur_sized(f, count));
}

/* hf_fur_interpolate_points' strands go through a buffer of this many
   floats (8 KiB, in L1 while it is read back), a block at a time */
#define HF__POINTS_BLOCK (8 * HF_MAX_POINTS)

HFDEF hf_result hf_fur_interpolate_points(const hf_fur *f, int first,
                                          int count,
                                          const hf_ribbon_params *view,
                                          float *out4)
{
    float buf[HF__POINTS_BLOCK];
    hf__points_kit kit;
    hf_ribbon_params p, prm;
    hf_ribbon_strands st;
    const hf__ipoints_kernels *k;
    int s, n, per, lv;
    hf_result r = hf__fur_view(f, first, count, view, &p, &st);
    if (r == HF_OK) r = hf__ribbon_check(&st, first, count, &p, &prm);
    if (r != HF_OK) return r;
    if (!out4) return HF_ERROR_NULL_POINTER;
    hf__points_kit_init(&kit, &prm, hf__fur_sized(f, count));
    /* interpolation and points in one kernel at the lower of the two
       levels (the fur's and the params'); else the strands at the fur's,
       through buf, and their points at the params' */
    lv = hf_simd_resolve(f->simd);
    k = hf__kernels_for(hf__ipoints_widths, lv < kit.level ? lv : kit.level);
    if (k->fused && !kit.compact && hf__fur_blend_only(f)) {
        /* in registers, nothing through memory (the run's own output is
           not written: the kernels write points to out4) */
        float ctab[3 * HF_MAX_POINTS];
        hf__irun run;
        hf__irun_init(&run, f->guide_points, f->bindings, f->P, f->clump,
                      ctab, out4, first, 0);
        for (; k->fused; ++k)
            if (k->fused(&run, &kit, &st, first, count, prm.out_first, out4)) {
                count = 0;
                break;
            }
    }
    per = HF__POINTS_BLOCK / (3 * f->P);
    for (s = first; s < first + count; s += n) {
        n = first + count - s < per ? first + count - s : per;
        hf__fur_strands(f, s, n, buf, s, 0);
        hf__points_run(&kit, &st, buf, s, s, n, prm.out_first, out4);
    }
#if HF__SSE
    if (kit.nt) _mm_sfence(); /* streamed stores visible before we return */
#endif
    return HF_OK;
}

HFDEF hf_result hf_fur_set_rope_params(hf_fur *f,
                                       const hf_rope_params *params)
{
    hf_rope_params p;
    hf_result r;
    if (!f || !params) return HF_ERROR_NULL_POINTER;
    hf__rope_params_resolve(params, &p);
    if ((r = hf__rope_params_check(&p, NULL)) != HF_OK) return r;
    f->rope[0] = p;
    HF_MEMSET(f->rope_of, 0, (size_t)f->guide_count);
    return HF_OK;
}

HF__PRIVATE int hf__same_bytes(const void *a, const void *b, size_t n)
{
    const unsigned char *x = (const unsigned char *)a, *y = (const unsigned char *)b;
    size_t i;
    for (i = 0; i < n; ++i)
        if (x[i] != y[i]) return 0;
    return 1;
}

HFDEF hf_result hf_fur_set_rope_params_range(hf_fur *f, int first, int count,
                                             const hf_rope_params *params)
{
    hf_rope_params p;
    hf_result r;
    int outside[HF_FUR_ROPE_SETS], used[HF_FUR_ROPE_SETS], g, k, slot = -1;
    if (!f || !params) return HF_ERROR_NULL_POINTER;
    if (!hf__range_ok(first, count) || first + count > f->guide_count)
        return HF_ERROR_BAD_RANGE;
    hf__rope_params_resolve(params, &p);
    if ((r = hf__rope_params_check(&p, NULL)) != HF_OK) return r;
    if (count == 0) return HF_OK;
    for (k = 0; k < HF_FUR_ROPE_SETS; ++k) outside[k] = used[k] = 0;
    for (g = 0; g < f->guide_count; ++g) {
        ++used[f->rope_of[g]];
        if (g < first || g >= first + count) ++outside[f->rope_of[g]];
    }
    /* a set already holding these parameters, else one only this range
       uses (or nobody does) */
    for (k = 0; k < HF_FUR_ROPE_SETS && slot < 0; ++k)
        if (used[k] > 0 && hf__same_bytes(&f->rope[k], &p, sizeof p)) slot = k;
    for (k = 0; k < HF_FUR_ROPE_SETS && slot < 0; ++k)
        if (outside[k] == 0) slot = k;
    if (slot < 0) return HF_ERROR_BAD_COUNT;
    f->rope[slot] = p;
    for (g = first; g < first + count; ++g) f->rope_of[g] = (unsigned char)slot;
    return HF_OK;
}

HFDEF hf_result hf_fur_set_mode(hf_fur *f, int first, int count, int mode)
{
    int g, end;
    if (!f) return HF_ERROR_NULL_POINTER;
    if (!hf__ropes_range(f->ropes, first, count)) return HF_ERROR_BAD_RANGE;
    if (mode != HF_ROPE_SIMULATED && mode != HF_ROPE_ANIMATED)
        return HF_ERROR_BAD_PARAMETER;
    for (g = first; g < first + count; ++g)
        f->user_mode[g] = (unsigned char)mode;
    /* LOD guides asleep (animated, drawn interpolated) keep sleeping and
       take the mode when they wake */
    end = first + count;
    if (!f->lod_sim && end > f->pure_count)
        end = first > f->pure_count ? first : f->pure_count;
    return hf_ropes_set_mode(f->ropes, first, end - first, mode);
}

HFDEF hf_result hf_fur_set_kernels(hf_fur *f, int simd, int nontemporal)
{
    if (!f) return HF_ERROR_NULL_POINTER;
    if (!hf__kernels_ok(simd, nontemporal))
        return HF_ERROR_BAD_PARAMETER;
    f->simd = simd;
    f->nontemporal = nontemporal;
    if (f->grid) f->grid->simd = simd;
    return HF_OK;
}

HFDEF hf_result hf_fur_reset(hf_fur *f)
{
    hf_result r;
    if (!f) return HF_ERROR_NULL_POINTER;
    r = hf_ropes_reset(f->ropes, 0, f->guide_count);
    if (r != HF_OK) return r;
    return hf_ropes_get_positions(f->ropes, 0, f->guide_count,
                                  f->guide_points, 0);
}

HFDEF hf_result hf_fur_max_stretch(const hf_fur *f, float *out_stretch)
{
    if (!f || !out_stretch) return HF_ERROR_NULL_POINTER;
    return hf_ropes_max_stretch(f->ropes, 0,
                                f->lod_sim ? f->guide_count : f->pure_count,
                                out_stretch);
}

#ifdef __cplusplus
}
#endif

#if defined(__clang__) /* back to the command line's setting */
#pragma STDC FP_CONTRACT DEFAULT
#elif defined(__GNUC__)
#pragma GCC pop_options
#endif
#else /* HF__PASS: its end; its words go, for the next pass to set anew */
#undef HF__KN
#undef HF__VEC
#undef HF__VTARGET
#undef HF__VZEROUPPER
#undef HF__VGATHER
#undef HF__VLD
#undef HF__VST
#undef HF__VSET1
#undef HF__VADD
#undef HF__VSUB
#undef HF__VMUL
#undef HF__VDIV
#undef HF__VSQRT
#undef HF__VMAX
#undef HF__VGT
#undef HF__VLT
#undef HF__VEQ
#undef HF__VLE
#undef HF__VAND
#undef HF__VSEL
#undef HF__VMASK
#undef HF__VLANES
#undef HF__VALL
#undef HF__VOR
#undef HF__VDOT3
#undef HF__VCROSS3
#undef HF__VPOSE
#undef HF__W
#undef HF__PASS
#endif /* HF__PASS */

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
