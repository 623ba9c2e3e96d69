/* fuzz_ropes.c - ropes with fuzz-built parameters, rest poses, root motion
   (teleports, spins, NaN), colliders, modes, resets and time steps.

   Two rope sets on caller memory get the same calls; set A steps every
   rope in one range at the best level, set B in up to four ranges split
   where the input says, at the SSE2 (NEON) level. Contracts checked (abort() on violation): every result is HF_OK or
   a table code; a failed call leaves the whole rope memory and struct
   byte for byte as they were; every range of a split call returns what
   the whole call returned; A and B stay byte-identical but for the
   scratch rows (per-call temporaries, see hf_ropes_init); on success every
   position is finite; hf_ropes_max_stretch is finite and >= 0;
   hf_ropes_get_positions writes exactly its range; hf_ropes_create with
   a failing or counting allocator leaks nothing. Some frames also build
   a hair-hair grid (A in one call, B in layers split where the input
   says: the same bytes) and push the ropes with it before the step
   (A whole, B in ranges); a refused push changes nothing.

   libFuzzer: clang -g -O1 -fsanitize=fuzzer,address,undefined fuzz_ropes.c
   replay:    gcc -O1 -g fuzz_main.c fuzz_ropes.c -lm (see the Makefile) */
#define HAIRFUR_IMPLEMENTATION
#include "../../hairfur.h"
#include "fuzz_common.h"

#include <math.h>

#define FZ_COLS 40 /* colliders at most */
#define FZ_GRID 6  /* nodes along each axis of the fuzzed grids */

typedef struct fz_ropeset {
    hf_ropes ropes;
    void *mem; /* 64-byte aligned in raw, so that A and B lay out alike */
    void *raw;
    size_t bytes;
    /* snapshot for "nothing written" */
    hf_ropes ropes0;
    void *mem0;
} fz_ropeset;

static void fz_snap(fz_ropeset *s)
{
    s->ropes0 = s->ropes;
    memcpy(s->mem0, s->mem, s->bytes);
}
static int fz_same_as_snap(const fz_ropeset *s)
{
    return memcmp(&s->ropes0, &s->ropes, sizeof s->ropes) == 0 &&
           memcmp(s->mem0, s->mem, s->bytes) == 0;
}

/* A and B hold the same state: every byte of their memory but the
   scratch rows, whose temporaries depend on how a step was split. */
static int fz_same_state(const fz_ropeset *a, const fz_ropeset *b)
{
    const unsigned char *ma = (const unsigned char *)a->mem;
    const unsigned char *mb = (const unsigned char *)b->mem;
    const size_t s0 = (size_t)((const unsigned char *)a->ropes.scratch - ma);
    const size_t s1 = s0 + (size_t)a->ropes.rope_count * HF__RS_ROWS * 4u;
    return s1 <= a->bytes &&
           (size_t)((const unsigned char *)b->ropes.scratch - mb) == s0 &&
           memcmp(ma, mb, s0) == 0 &&
           memcmp(ma + s1, mb + s1, a->bytes - s1) == 0;
}

static int fz_ropes_finite(const hf_ropes *r)
{
    size_t n = (size_t)r->rope_count * (size_t)r->points;
    return fz_all_finite(r->x, n) && fz_all_finite(r->y, n) &&
           fz_all_finite(r->z, n) && fz_all_finite(r->px, n) &&
           fz_all_finite(r->py, n) && fz_all_finite(r->pz, n);
}

/* Roots of R ropes: 3 floats each for position, normal, tangent. */
static void fz_roots(fz_reader *r, int R, float *pos, float *nrm, float *tan,
                     const float *prev_pos, float teleport)
{
    int i, k;
    for (i = 0; i < R; ++i)
        for (k = 0; k < 3; ++k) {
            float base = prev_pos ? prev_pos[3 * i + k] : 0.0f;
            pos[3 * i + k] = base + fz_float(r, teleport);
            nrm[3 * i + k] = fz_float(r, 1.0f);
            tan[3 * i + k] = fz_float(r, 1.0f);
        }
}

/* A random field of the params to a fuzz value. */
static void fz_mutate_params(fz_reader *r, hf_rope_params *p)
{
    switch (fz_u8(r) % 23) {
    case 0: p->gravity[fz_u8(r) % 3] = fz_float(r, 100.0f); break;
    case 1: p->wind[fz_u8(r) % 3] = fz_float(r, 100.0f); break;
    case 2: p->turbulence = fz_float(r, 50.0f); break;
    case 3: p->turbulence_frequency = fz_float(r, 20.0f); break;
    case 4: p->damping = fz_float(r, 1.0f); break;
    case 5: p->time_scale = fz_float(r, 100.0f); break;
    case 6: p->substep = fz_float(r, 0.1f); break;
    case 7: p->max_substeps = fz_int(r, -2, 40); break;
    case 8: p->max_dt = fz_float(r, 1.0f); break;
    case 9: p->iterations = fz_int(r, -1, 12); break;
    case 10: p->solver = fz_int(r, -1, 2); break;
    case 11: p->ftl_damping = fz_float(r, 1.0f); break;
    case 12: p->root_stiffness = fz_float(r, 1.0f); break;
    case 13: p->global_stiffness_root = fz_float(r, 1.0f); break;
    case 14: p->global_stiffness_tip = fz_float(r, 1.0f); break;
    case 15: p->local_stiffness_root = fz_float(r, 1.0f); break;
    case 16: p->local_stiffness_tip = fz_float(r, 1.0f); break;
    case 17: p->collision_margin = fz_float(r, 0.1f); break;
    case 18: p->mode_blend_time = fz_float(r, 1.0f); break;
    case 19: p->explicit_zero = fz_int(r, 0, 255); break;
    case 21: p->volume = fz_float(r, 5.0f); break;
    case 22: p->friction = fz_float(r, 1.0f); break;
    default: p->max_substeps = fz_int(r, 1, 1000); break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader r;
    fz_ropeset A, B;
    hf_rope_params params;
    hf_result ra, rb, rv;
    size_t bytes = 0;
    float *rest, *rpos, *rnrm, *rtan, *out;
    hf_collider col[FZ_COLS];
    int R, P, frames, f, i, nmut;

    fz_init(&r, data, size);
    R = fz_int(&r, 1, 6);
    P = fz_int(&r, 2, 12);

    /* ---- create / destroy with a counting, failing allocator ----------- */
    {
        fz_counter cnt;
        hf_allocator a = fz_counting(&cnt, fz_chance(&r, 64) ? 0 : -1,
                                     (size_t)1 << 24);
        hf_ropes *cr = (hf_ropes *)&cnt; /* sentinel */
        rv = hf_ropes_create(fz_chance(&r, 250) ? R : fz_int(&r, -2, 0), P,
                             &a, &cr);
        FZ_REQUIRE(fz_known_result(rv));
        if (rv == HF_OK) {
            FZ_REQUIRE(cr != NULL && cr != (hf_ropes *)&cnt);
            hf_ropes_destroy(cr);
        } else {
            FZ_REQUIRE(cr == (hf_ropes *)&cnt);
        }
        FZ_REQUIRE(cnt.live == 0);
    }

    /* ---- init two sets on caller memory -------------------------------- */
    rv = hf_ropes_memory_size(R, P, &bytes);
    FZ_REQUIRE(rv == HF_OK && bytes > 0 && bytes < ((size_t)1 << 24));
    {
        fz_ropeset *sets[2];
        int k;
        sets[0] = &A;
        sets[1] = &B;
        for (k = 0; k < 2; ++k) {
            fz_ropeset *s = sets[k];
            hf_ropes sentinel;
            memset(s, 0, sizeof *s);
            s->bytes = bytes;
            /* the same alignment for both: hf_ropes_init aligns its
               arrays within the memory, and the states are compared
               byte for byte */
            s->raw = malloc(bytes + 64u);
            s->mem0 = malloc(bytes);
            if (!s->raw || !s->mem0) abort();
            s->mem = (unsigned char *)s->raw +
                     (64u - (size_t)((uintptr_t)s->raw & 63u));
            memset(s->mem, 0x5A, bytes);
            /* too small: untouched */
            memset(&sentinel, FZ_SENTINEL, sizeof sentinel);
            s->ropes = sentinel;
            rv = hf_ropes_init(&s->ropes, R, P, s->mem, bytes - 1);
            FZ_REQUIRE(rv == HF_ERROR_BUFFER_TOO_SMALL);
            FZ_REQUIRE(memcmp(&s->ropes, &sentinel, sizeof sentinel) == 0);
            rv = hf_ropes_init(&s->ropes, R, P, s->mem, bytes);
            FZ_REQUIRE(rv == HF_OK);
            FZ_REQUIRE(fz_ropes_finite(&s->ropes));
        }
    }

    rest = (float *)malloc(sizeof(float) * 3u * (size_t)R * (size_t)P);
    rpos = (float *)malloc(sizeof(float) * 3u * (size_t)R);
    rnrm = (float *)malloc(sizeof(float) * 3u * (size_t)R);
    rtan = (float *)malloc(sizeof(float) * 3u * (size_t)R);
    out = (float *)malloc(sizeof(float) * 3u * (size_t)R * (size_t)P);
    if (!rest || !rpos || !rnrm || !rtan || !out) abort();

    /* ---- rest pose ------------------------------------------------------ */
    fz_roots(&r, R, rpos, rnrm, rtan, NULL, 2.0f);
    for (i = 0; i < R * P; ++i) {
        int rope = i / P, j = i % P, k;
        /* mostly a hair along the normal, sometimes anything */
        for (k = 0; k < 3; ++k)
            rest[3 * i + k] = fz_chance(&r, 200)
                                  ? rpos[3 * rope + k] +
                                        0.05f * (float)j * rnrm[3 * rope + k]
                                  : fz_float(&r, 2.0f);
    }
    fz_snap(&A);
    ra = hf_ropes_set_rest(&A.ropes, 0, R, rest, 0, rpos, rnrm, rtan, 0);
    rb = hf_ropes_set_rest(&B.ropes, 0, R, rest, 0, rpos, rnrm, rtan, 0);
    FZ_REQUIRE(fz_known_result(ra) && ra == rb);
    if (ra != HF_OK) FZ_REQUIRE(fz_same_as_snap(&A));
    FZ_REQUIRE(fz_ropes_finite(&A.ropes));

    /* ---- params ---------------------------------------------------------- */
    hf_rope_params_init(&params);
    FZ_REQUIRE(hf_rope_params_validate(&params, NULL) == HF_OK);
    nmut = fz_int(&r, 0, 4);
    for (i = 0; i < nmut; ++i) fz_mutate_params(&r, &params);
    {
        hf_diag d;
        rv = hf_rope_params_validate(&params, &d);
        FZ_REQUIRE(fz_known_result(rv) && d.result == rv);
    }

    /* ---- frames ----------------------------------------------------------- */
    frames = fz_int(&r, 1, 12);
    for (f = 0; f < frames; ++f) {
        int op = fz_u8(&r), nc, k, first, count;
        float dt, stretch;
        float teleport = (op & 0x80) ? 1000.0f : 0.2f;

        /* root motion */
        if (op & 1) {
            fz_roots(&r, R, rpos, rnrm, rtan, rpos, teleport);
            fz_snap(&A);
            ra = hf_ropes_set_roots(&A.ropes, 0, R, rpos, rnrm, rtan, 0);
            rb = hf_ropes_set_roots(&B.ropes, 0, R, rpos, rnrm, rtan, 0);
            FZ_REQUIRE(fz_known_result(ra) && ra == rb);
            if (ra != HF_OK) FZ_REQUIRE(fz_same_as_snap(&A));
        }
        /* a mode switch on a range */
        if (op & 2) {
            int mode = fz_chance(&r, 240) ? fz_int(&r, 0, 1) : fz_int(&r, -1, 5);
            fz_range(&r, R, &first, &count);
            fz_snap(&A);
            ra = hf_ropes_set_mode(&A.ropes, first, count, mode);
            rb = hf_ropes_set_mode(&B.ropes, first, count, mode);
            FZ_REQUIRE(fz_known_result(ra) && ra == rb);
            if (ra != HF_OK) FZ_REQUIRE(fz_same_as_snap(&A));
        }
        /* teleport */
        if ((op & 0x0C) == 0x0C) {
            fz_range(&r, R, &first, &count);
            fz_snap(&A);
            ra = hf_ropes_reset(&A.ropes, first, count);
            rb = hf_ropes_reset(&B.ropes, first, count);
            FZ_REQUIRE(fz_known_result(ra) && ra == rb);
            if (ra != HF_OK) FZ_REQUIRE(fz_same_as_snap(&A));
            FZ_REQUIRE(fz_ropes_finite(&A.ropes));
        }
        /* a params change */
        if (op & 0x10) {
            fz_mutate_params(&r, &params);
        }
        /* colliders */
        /* a few, or a body's worth and more (the broadphase), some far */
        nc = fz_chance(&r, 200) ? fz_int(&r, 0, 3) : fz_int(&r, 4, FZ_COLS);
        for (k = 0; k < nc; ++k) {
            int c;
            const float far_ = fz_chance(&r, 180) ? 0.0f : fz_float(&r, 50.0f);
            memset(&col[k], 0, sizeof col[k]);
            col[k].type = fz_chance(&r, 250) ? fz_int(&r, 0, 1)
                                              : fz_int(&r, -1, 3);
            for (c = 0; c < 3; ++c) {
                col[k].a[c] = rpos[c] + far_ + fz_float(&r, 0.5f);
                col[k].b[c] = rpos[c] + far_ + fz_float(&r, 0.5f);
            }
            col[k].radius = fz_chance(&r, 240) ? fz_float_in(&r, 0.0f, 0.5f)
                                               : fz_float(&r, 1e6f);
            if (fz_chance(&r, 64)) /* around rope 0's root: it holds it */
                for (c = 0; c < 3; ++c) col[k].a[c] = rpos[c];
        }
        dt = fz_chance(&r, 220) ? fz_float_in(&r, 0.0f, 0.05f)
                                : fz_float(&r, 1.0f);

        /* hair-hair: a grid each, built (B in layers) and pushed with */
        if (op & 0x20) {
            static unsigned char ga_mem[65536], gb_mem[65536];
            static hf_grid ga, gb;
            size_t gsz = 0;
            int done = 0, parts = fz_int(&r, 1, 3), p;
            FZ_REQUIRE(hf_grid_memory_size(FZ_GRID, &gsz) == HF_OK &&
                       gsz <= sizeof ga_mem);
            if (!ga.node) {
                FZ_REQUIRE(hf_grid_init(&ga, FZ_GRID, ga_mem, gsz) == HF_OK);
                FZ_REQUIRE(hf_grid_init(&gb, FZ_GRID, gb_mem, gsz) == HF_OK);
            }
            FZ_REQUIRE(hf_grid_build(&ga, &A.ropes, R, 0, FZ_GRID) == HF_OK);
            for (p = 0; p < parts; ++p) {
                int cnt = p == parts - 1 ? FZ_GRID - done
                                         : fz_int(&r, 0, FZ_GRID - done);
                FZ_REQUIRE(hf_grid_build(&gb, &B.ropes, R, done, cnt) ==
                           HF_OK);
                done += cnt;
            }
            FZ_REQUIRE(memcmp(ga.node, gb.node, sizeof(float) * 4u *
                              FZ_GRID * FZ_GRID * FZ_GRID) == 0);
            fz_snap(&A);
            ra = hf_ropes_apply_grid(&A.ropes, 0, R, dt, &params, &ga);
            FZ_REQUIRE(fz_known_result(ra));
            if (ra != HF_OK) FZ_REQUIRE(fz_same_as_snap(&A));
            done = 0;
            for (p = 0; p < parts; ++p) {
                int cnt = p == parts - 1 ? R - done : fz_int(&r, 0, R - done);
                rb = hf_ropes_apply_grid(&B.ropes, done, cnt, dt, &params,
                                         &gb);
                FZ_REQUIRE(rb == ra);
                done += cnt;
            }
            FZ_REQUIRE(fz_same_state(&A, &B));
            FZ_REQUIRE(fz_ropes_finite(&A.ropes));
        }

        /* step: A whole at the level the params ask (the best the CPU
           runs, unless fuzzed), B in up to four ranges at the SSE2 (NEON)
           level: every level gives the same bytes */
        fz_snap(&A);
        ra = hf_ropes_step(&A.ropes, 0, R, dt, &params, nc ? col : NULL, nc);
        FZ_REQUIRE(fz_known_result(ra));
        if (ra != HF_OK) FZ_REQUIRE(fz_same_as_snap(&A));
        {
            int parts = fz_int(&r, 1, 4), done = 0, p;
            hf_rope_params pb = params;
            pb.simd = HF_SIMD_SSE2;
            for (p = 0; p < parts; ++p) {
                int cnt = p == parts - 1 ? R - done : fz_int(&r, 0, R - done);
                rb = hf_ropes_step(&B.ropes, done, cnt, dt, &pb,
                                   nc ? col : NULL, nc);
                /* an empty range may succeed where the whole fails? no:
                   params, dt and colliders are checked first */
                FZ_REQUIRE(rb == ra);
                done += cnt;
            }
        }
        FZ_REQUIRE(fz_same_state(&A, &B));
        FZ_REQUIRE(fz_ropes_finite(&A.ropes));

        stretch = -7.0f;
        ra = hf_ropes_max_stretch(&A.ropes, 0, R, &stretch);
        FZ_REQUIRE(ra == HF_OK && fz_finite(stretch) && stretch >= 0.0f);
        if (rb == HF_OK && params.solver == HF_ROPE_SOLVER_FTL &&
            !(params.explicit_zero & HF_ROPE_ZERO_ITERATIONS)) {
            /* follow-the-leader with a pass is inextensible, colliders
               (roots inside them too) or not: each segment keeps its rest
               length, to float resolution at its coordinates */
            int k2, j2;
            for (k2 = 0; k2 < R; ++k2) {
                if (A.ropes.mode[k2] != HF_ROPE_SIMULATED ||
                    A.ropes.blend[k2] != 0.0f)
                    continue;
                for (j2 = 0; j2 + 1 < P; ++j2) {
                    const size_t a0 = (size_t)j2 * (size_t)R + (size_t)k2;
                    const size_t a1 = a0 + (size_t)R;
                    const double dx = (double)A.ropes.x[a1] - A.ropes.x[a0];
                    const double dy = (double)A.ropes.y[a1] - A.ropes.y[a0];
                    const double dz = (double)A.ropes.z[a1] - A.ropes.z[a0];
                    const double m = fabs((double)A.ropes.x[a0]) +
                                     fabs((double)A.ropes.y[a0]) +
                                     fabs((double)A.ropes.z[a0]);
                    const double l = sqrt(dx * dx + dy * dy + dz * dz);
                    const double rest = A.ropes.rest_length[a0];
                    FZ_REQUIRE(fabs(l - rest) <= 1e-3 * rest + 1e-6 * (1.0 + m));
                }
            }
        }

        /* positions out, on a fuzz range with a fuzz stride */
        {
            int stride = fz_chance(&r, 240) ? 0 : fz_int(&r, -4, 12);
            size_t ob = sizeof(float) * 3u * (size_t)R * (size_t)P;
            if (stride > 0 && stride < 12) stride = -stride; /* refused */
            memset(out, FZ_SENTINEL, ob);
            fz_range(&r, R, &first, &count);
            ra = hf_ropes_get_positions(&A.ropes, first, count, out, stride);
            FZ_REQUIRE(fz_known_result(ra));
            if (ra != HF_OK) {
                FZ_REQUIRE(fz_untouched(out, ob));
            } else {
                size_t a0 = (size_t)first * (size_t)P * 3u;
                size_t n = (size_t)count * (size_t)P * 3u;
                FZ_REQUIRE(fz_untouched(out, a0 * 4u));
                FZ_REQUIRE(fz_all_finite(out + a0, n));
                FZ_REQUIRE(fz_untouched(out + a0 + n, ob - (a0 + n) * 4u));
            }
        }
    }

    free(rest);
    free(rpos);
    free(rnrm);
    free(rtan);
    free(out);
    free(A.raw);
    free(A.mem0);
    free(B.raw);
    free(B.mem0);
    return 0;
}
