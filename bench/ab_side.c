/* ab_side.c - one side of bench_ab.c, built twice: with AB_HEADER (a
   version of hairfur.h, every function static, so both versions live in
   one program) and AB_SIDE (base or new, the name of the ab_side it
   defines). Each side grows its own fur from the same description
   (bench_fur.h): the versions may lay out their fur differently. */
#define _POSIX_C_SOURCE 200809L
#define HAIRFUR_STATIC
#define HAIRFUR_IMPLEMENTATION
#include AB_HEADER
#include "../examples/head_mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_ab.h"
#include "bench_fur.h"

typedef struct ab_scene {
    hf_fur *fur;
    hf_fur_info info;
    float *vbuf, *pbuf;  /* 36-byte vertices, GPU points */
    unsigned char *cbuf; /* 16-byte vertices */
    hf_ribbon_params view, view_gpu;
    hf_ribbon_output out, out16;
    hf_collider col;
} ab_scene;

/* as a mapped OpenGL buffer is: 64-byte aligned, pages touched */
static void *ab_buffer(size_t bytes)
{
    void *q = NULL;
    if (posix_memalign(&q, 64, bytes)) return NULL;
    memset(q, 0, bytes);
    return q;
}

static void ab_free(void *scene)
{
    ab_scene *s = (ab_scene *)scene;
    if (!s) return;
    hf_fur_destroy(s->fur);
    free(s->vbuf);
    free(s->pbuf);
    free(s->cbuf);
    free(s);
}

static void *ab_make(const hm_mesh *head, const unsigned char *px,
                     int strands, int points)
{
    hf_fur_desc d;
    hf_map density;
    hf_rope_params rp;
    hf_diag diag;
    size_t nv;
    ab_scene *s = (ab_scene *)calloc(1, sizeof *s);
    if (!s) return NULL;
    bench_fur_desc(&d, &density, &rp, head, px, strands, 0.0f);
    d.points_per_strand = points;
    if (hf_fur_create(&d, &s->fur, &diag) != HF_OK) {
        fprintf(stderr, "bench_ab: %s\n", diag.message);
        free(s);
        return NULL;
    }
    hf_fur_get_info(s->fur, &s->info);
    nv = (size_t)s->info.strand_count * (size_t)points * 2u;
    s->vbuf = (float *)ab_buffer(nv * 36u);
    s->cbuf = (unsigned char *)ab_buffer(nv * 16u);
    s->pbuf = (float *)ab_buffer(nv * 8u); /* 16 bytes a point */
    if (!s->vbuf || !s->cbuf || !s->pbuf) {
        fprintf(stderr, "bench_ab: out of memory\n");
        ab_free(s);
        return NULL;
    }
    bench_views(&s->view, &s->view_gpu, &s->out, s->vbuf, &s->out16,
                s->cbuf);
    bench_collider(&s->col);
    return s;
}

static int ab_call(ab_scene *s, int stage, int first, int count)
{
    switch (stage) {
    case AB_STRANDS: return (int)hf_fur_interpolate(s->fur, first, count);
    case AB_RIBBONS:
        return (int)hf_fur_ribbons(s->fur, first, count, &s->view, &s->out);
    case AB_RIBBONS16:
        return (int)hf_fur_ribbons(s->fur, first, count, &s->view, &s->out16);
    case AB_POINTS:
        return (int)hf_fur_points(s->fur, first, count, &s->view, s->pbuf);
    case AB_INTERP_POINTS:
        return (int)hf_fur_interpolate_points(s->fur, first, count,
                                              &s->view_gpu, s->pbuf);
    case AB_ROPES:
        return (int)hf_fur_simulate(s->fur, first, count, 1.0f / 60.0f,
                                    &s->col, 1);
    default: return -1;
    }
}

static int ab_run(void *scene, int stage, int range)
{
    ab_scene *s = (ab_scene *)scene;
    const int n = stage == AB_ROPES ? s->info.guide_count
                                    : s->info.strand_count,
              step = range > 0 && range < n ? range : n;
    int first, r = 0;
    for (first = 0; first < n && r == 0; first += step)
        r = ab_call(s, stage, first, n - first < step ? n - first : step);
    return r;
}

const ab_side AB_SIDE = {ab_make, ab_run, ab_free};
