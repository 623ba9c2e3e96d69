/* soak.c - a million rope steps under abuse (make soak; minutes; not CI).

       gcc -std=c99 -O2 tests/soak.c -o build/soak -lm && build/soak [steps]

   1000 ropes of 16 points, `steps` frames (default 1000: a million rope
   steps), each frame:
   - violent root motion: smooth drift at up to 20 m/s, random spins of
     the root frames, and teleports of up to 10 m (1 % of frames per rope);
   - random colliders, re-drawn every 25 frames: 0 to 6 spheres and
     capsules, radii from 0.1 mm to 30 cm, now and then a huge one (1 km,
     its surface through the ropes) or a zero-radius one, often
     overlapping;
   - a random time step: 0, negative, NaN, infinite (each must return
     HF_ERROR_BAD_TIME_STEP and change no byte), 1e-9 s, 1 s (clamped to
     max_dt), or 1/240 .. 1/15 s;
   - the ropes stepped in 1 to 4 ranges split at random;
   - every 100 frames new valid parameters (solver, iterations, sub-steps,
     damping, stiffnesses, wind, turbulence, margin), and random mode
     switches and resets.
   Checks: every result code as documented, no NaN or inf ever in the
   state, and the stretch (hf_ropes_max_stretch) after every step, reported
   as a distribution per solver. Exits non-zero on any NaN, any unexpected
   result, or an FTL stretch above SOAK_MAX_FTL_STRETCH. */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define ROPES 1000
#define POINTS 16
#define SEG 0.02f /* rest segment length: 30 cm ropes */
/* The documented bound: a rope thrown further than 8 * length + 0.01 m
   from its root is reset, so no segment can be longer than twice that.
   Colliders reach it (a root teleported deep inside a huge collider has
   its other points pushed out to the surface, metres away); without
   colliders FTL stays below 100 % (compression while a rope glides to
   its rest pose after a switch to animated; build with
   -DSOAK_NO_COLLIDERS to see it). */
#ifndef SOAK_MAX_FTL_STRETCH
#define SOAK_MAX_FTL_STRETCH                                                   \
    (2.0 * (8.0 * SEG * (POINTS - 1) + 0.01) / SEG - 1.0)
#endif

static hf_rng g_rng;
static float frand(void) { return hf_rng_float(&g_rng); }
static float srand1(void) { return 2.0f * frand() - 1.0f; }

static int all_finite(const hf_ropes *r)
{
    size_t n = (size_t)r->rope_count * (size_t)r->points, i;
    for (i = 0; i < n; ++i) {
        float s = r->x[i] + r->y[i] + r->z[i] + r->px[i] + r->py[i] + r->pz[i];
        if (!(s - s == 0.0f)) return 0;
    }
    return 1;
}

static void rotate(float *v, const float *axis, float ang)
{
    /* Rodrigues, axis unit */
    float c = cosf(ang), s = sinf(ang), d = axis[0] * v[0] + axis[1] * v[1] +
                                            axis[2] * v[2];
    float x[3];
    x[0] = axis[1] * v[2] - axis[2] * v[1];
    x[1] = axis[2] * v[0] - axis[0] * v[2];
    x[2] = axis[0] * v[1] - axis[1] * v[0];
    v[0] = v[0] * c + x[0] * s + axis[0] * d * (1 - c);
    v[1] = v[1] * c + x[1] * s + axis[1] * d * (1 - c);
    v[2] = v[2] * c + x[2] * s + axis[2] * d * (1 - c);
}

static void random_unit(float *v)
{
    float l;
    do {
        v[0] = srand1();
        v[1] = srand1();
        v[2] = srand1();
        l = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    } while (l < 1e-4f || l > 1.0f);
    l = sqrtf(l);
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

static void random_params(hf_rope_params *p)
{
    hf_rope_params_init(p);
    p->solver = frand() < 0.8f ? HF_ROPE_SOLVER_FTL : HF_ROPE_SOLVER_DISTANCE;
    p->iterations = (int)(frand() * 5.0f);
    p->max_substeps = 1 + (int)(frand() * 12.0f);
    p->substep = frand() < 0.5f ? 1.0f / 120.0f : 1e-5f + frand() * 0.05f;
    p->damping = frand() * frand();
    p->ftl_damping = frand();
    p->root_stiffness = frand() < 0.5f ? 0.0f : frand();
    p->global_stiffness_root = frand() < 0.5f ? 0.0f : frand();
    p->global_stiffness_tip = frand() < 0.5f ? 0.0f : frand();
    p->local_stiffness_root = frand() < 0.5f ? 0.0f : frand();
    p->local_stiffness_tip = frand() < 0.5f ? 0.0f : frand();
    p->wind[0] = srand1() * 50.0f;
    p->turbulence = frand() < 0.5f ? 0.0f : frand() * 100.0f;
    p->turbulence_frequency = frand() * 10.0f;
    p->collision_margin = frand() < 0.2f ? 0.0f : frand() * 0.01f;
    p->time_scale = frand() < 0.8f ? 1.0f : 0.1f + frand() * 5.0f;
    p->mode_blend_time = frand() < 0.3f ? 0.0f : frand();
    /* the zeros above are meant literally (no margin, no passes, ...) */
    p->explicit_zero = HF_ROPE_ZERO_DAMPING | HF_ROPE_ZERO_ITERATIONS |
                       HF_ROPE_ZERO_FTL_DAMPING | HF_ROPE_ZERO_MARGIN |
                       HF_ROPE_ZERO_BLEND_TIME;
}

int main(int argc, char **argv)
{
    static float rest[ROPES * POINTS * 3];
    static float rpos[ROPES * 3], rnrm[ROPES * 3], rtan[ROPES * 3];
    static float vel[ROPES * 3];
    hf_ropes ropes_struct, *ropes = &ropes_struct;
    void *mem;
    hf_rope_params params;
    hf_collider col[6];
    int steps = argc > 1 ? atoi(argv[1]) : 1000, ncol = 0, s, i, k;
    long bad_dt = 0, good = 0, teleports = 0, failures = 0;
    long hist[2][7]; /* per solver: <1e-4 <1e-3 <1e-2 <0.05 <0.2 <1 >=1 */
    double max_stretch[2] = {0, 0}, sum_stretch[2] = {0, 0};
    long n_stretch[2] = {0, 0};
    size_t bytes;
    unsigned char *snap;
    clock_t t0 = clock();

    memset(hist, 0, sizeof hist);
    hf_rng_seed(&g_rng, 2026, 11);
    if (hf_ropes_memory_size(ROPES, POINTS, &bytes) != HF_OK) return 1;
    mem = malloc(bytes);
    snap = (unsigned char *)malloc(bytes);
    if (!mem || !snap || hf_ropes_init(ropes, ROPES, POINTS, mem, bytes) != HF_OK)
        return 1;

    for (i = 0; i < ROPES; ++i) {
        float *p = rpos + 3 * i, *n = rnrm + 3 * i, *t = rtan + 3 * i;
        p[0] = srand1();
        p[1] = srand1();
        p[2] = srand1();
        random_unit(n);
        random_unit(t);
        for (k = 0; k < POINTS; ++k) {
            float *q = rest + 3 * (i * POINTS + k);
            q[0] = p[0] + n[0] * SEG * (float)k;
            q[1] = p[1] + n[1] * SEG * (float)k;
            q[2] = p[2] + n[2] * SEG * (float)k;
        }
    }
    if (hf_ropes_set_rest(ropes, 0, ROPES, rest, 0, rpos, rnrm, rtan, 0) !=
        HF_OK) {
        printf("soak: set_rest failed\n");
        return 1;
    }
    random_params(&params);

    for (s = 0; s < steps; ++s) {
        float dt;
        int dt_bad = 0, parts, first;
        hf_result r;
        int solver;
        /* root motion */
        for (i = 0; i < ROPES; ++i) {
            float *p = rpos + 3 * i, *v = vel + 3 * i, axis[3];
#ifdef SOAK_NO_TELEPORT
            if (0) {
#else
            if (frand() < 0.01f) { /* teleport */
#endif
                for (k = 0; k < 3; ++k) p[k] += srand1() * 10.0f;
                ++teleports;
            }
            if (frand() < 0.05f)
                for (k = 0; k < 3; ++k) v[k] = srand1() * 20.0f;
            for (k = 0; k < 3; ++k) {
                p[k] += v[k] * (1.0f / 60.0f);
                if (p[k] > 50.0f || p[k] < -50.0f) v[k] = -v[k];
            }
            if (frand() < 0.1f) { /* spin */
                random_unit(axis);
                rotate(rnrm + 3 * i, axis, srand1() * 3.14159f);
                rotate(rtan + 3 * i, axis, srand1() * 3.14159f);
            }
        }
        if (hf_ropes_set_roots(ropes, 0, ROPES, rpos, rnrm, rtan, 0) != HF_OK) {
            printf("soak: set_roots failed at step %d\n", s);
            ++failures;
        }
        /* colliders around a random rope's root */
        if (s % 25 == 0) {
            ncol = (int)(frand() * 7.0f);
#ifdef SOAK_NO_COLLIDERS
            ncol = 0;
#endif
            for (i = 0; i < ncol; ++i) {
                const float *c = rpos + 3 * (int)(frand() * (ROPES - 1));
                float u = frand();
                memset(&col[i], 0, sizeof col[i]);
                col[i].type = frand() < 0.5f ? HF_COLLIDER_SPHERE
                                             : HF_COLLIDER_CAPSULE;
                for (k = 0; k < 3; ++k) {
                    col[i].a[k] = c[k] + srand1() * 0.3f;
                    col[i].b[k] = frand() < 0.1f ? col[i].a[k]
                                                 : c[k] + srand1() * 0.5f;
                }
                col[i].radius = u < 0.05f ? 0.0f
                                : u < 0.1f ? 1e-4f
                                : u < 0.15f ? 1000.0f
                                            : frand() * 0.3f;
                if (col[i].radius == 1000.0f) col[i].a[1] -= 1000.0f;
            }
        }
        /* new parameters, modes, resets */
        if (s % 100 == 99) random_params(&params);
        if (frand() < 0.02f) {
            first = (int)(frand() * ROPES);
            hf_ropes_set_mode(ropes, first, (ROPES - first) / 2,
                              frand() < 0.5f ? HF_ROPE_ANIMATED
                                             : HF_ROPE_SIMULATED);
        }
        if (frand() < 0.005f) hf_ropes_reset(ropes, 0, ROPES / 3);
        /* the time step */
        {
            float u = frand();
            if (u < 0.02f) { dt = 0.0f; dt_bad = 1; }
            else if (u < 0.04f) { dt = -0.01f; dt_bad = 1; }
            else if (u < 0.06f) { dt = (float)NAN; dt_bad = 1; }
            else if (u < 0.07f) { dt = (float)INFINITY; dt_bad = 1; }
            else if (u < 0.10f) dt = 1e-9f;
            else if (u < 0.13f) dt = 1.0f;
            else dt = 1.0f / 240.0f + frand() * (1.0f / 15.0f - 1.0f / 240.0f);
        }
        if (dt_bad) {
            memcpy(snap, mem, bytes);
        }
        parts = 1 + (int)(frand() * 4.0f);
        first = 0;
        for (i = 0; i < parts; ++i) {
            int cnt = i == parts - 1 ? ROPES - first
                                     : (int)(frand() * (float)(ROPES - first));
            r = hf_ropes_step(ropes, first, cnt, dt, &params, col, ncol);
            if (dt_bad ? r != HF_ERROR_BAD_TIME_STEP : r != HF_OK) {
                printf("soak: step %d dt %g: %s\n", s, (double)dt,
                       hf_result_string(r));
                ++failures;
            }
            first += cnt;
        }
        if (dt_bad) {
            ++bad_dt;
            if (memcmp(snap, mem, bytes) != 0) {
                printf("soak: step %d: a refused step changed the state\n", s);
                ++failures;
            }
            continue;
        }
        ++good;
        if (!all_finite(ropes)) {
            printf("soak: step %d: NaN or inf in the rope state\n", s);
            return 1;
        }
        {
            float st = -1.0f;
            int b;
            solver = params.solver == HF_ROPE_SOLVER_FTL ? 0 : 1;
            if (hf_ropes_max_stretch(ropes, 0, ROPES, &st) != HF_OK ||
                !(st >= 0.0f) || !(st - st == 0.0f)) {
                printf("soak: step %d: bad stretch %g\n", s, (double)st);
                return 1;
            }
            b = st < 1e-4f ? 0 : st < 1e-3f ? 1 : st < 1e-2f ? 2
              : st < 0.05f ? 3 : st < 0.2f ? 4 : st < 1.0f ? 5 : 6;
            ++hist[solver][b];
            if (st > max_stretch[solver]) max_stretch[solver] = st;
            sum_stretch[solver] += st;
            ++n_stretch[solver];
        }
    }

    {
        static const char *names[7] = {"<0.01%", "<0.1%", "<1%", "<5%",
                                       "<20%", "<100%", ">=100%"};
        int sv, b;
        printf("soak: %d frames x %d ropes of %d points = %ld rope steps "
               "(%ld taken, %ld refused bad dt), %ld teleports, %.1f s\n",
               steps, ROPES, POINTS, (long)steps * ROPES, good * ROPES,
               bad_dt * ROPES, teleports,
               (double)(clock() - t0) / CLOCKS_PER_SEC);
        printf("soak: no NaN or inf in %ld checked states\n", good);
        for (sv = 0; sv < 2; ++sv) {
            if (!n_stretch[sv]) continue;
            printf("soak: %s solver, worst rope per frame: max stretch %.4g "
                   "(%.2f%%), mean %.4g; frames by worst stretch:",
                   sv ? "distance" : "FTL", max_stretch[sv],
                   100.0 * max_stretch[sv], sum_stretch[sv] / n_stretch[sv]);
            for (b = 0; b < 7; ++b) printf(" %s %ld", names[b], hist[sv][b]);
            printf("\n");
        }
        if (max_stretch[0] > SOAK_MAX_FTL_STRETCH) {
            printf("soak: FAILED: FTL stretch %.4g above %.4g\n",
                   max_stretch[0], (double)SOAK_MAX_FTL_STRETCH);
            ++failures;
        }
        printf("soak: %s (%ld failures)\n", failures ? "FAILED" : "passed",
               failures);
    }
    free(mem);
    free(snap);
    return failures ? 1 : 0;
}
