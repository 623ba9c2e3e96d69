/* bench_fur.h - the benchmarks' fur: the built-in head (examples/
   head_mesh.h) with its hairline density, 16 points a strand, 25 cm at
   most, seed 1, stiff roots; the views, layouts and collider the stages
   are measured with. One description for bench.c and both sides of
   bench_ab.c, so that they measure the same scene. The functions need
   hairfur.h and head_mesh.h included before; the sizes need nothing. */
#ifndef BENCH_FUR_H
#define BENCH_FUR_H

#define BENCH_P 16
#define BENCH_HEAD_RADIUS 0.1f
/* scene L: 100,000 strands on about 1,000 guides */
#define BENCH_L_RINGS 26
#define BENCH_L_SEGMENTS 40
#define BENCH_L_STRANDS 100000
/* scene V, a character at Veilguard's scale: 50,000 strands of 32 points
   on about 5,000 guides, 0.3 m of hair, the head on a 24-proxy body */
#define BENCH_V_RINGS 56
#define BENCH_V_SEGMENTS 92
#define BENCH_V_STRANDS 50000
#define BENCH_V_POINTS 32
#define BENCH_V_LENGTH 0.3f
#define BENCH_BODY 24       /* proxies of bench_body */
#define BENCH_MAX_COLLIDERS 64

#ifdef HAIRFUR_H

/* Fill *d (and the density map and rope parameters it points to) for
   `strands` strands on `head`, whose density image (256 x 256) is px. */
static void bench_fur_desc(hf_fur_desc *d, hf_map *density,
                           hf_rope_params *rp, const hm_mesh *head,
                           const unsigned char *px, int strands,
                           float tess_factor)
{
    memset(density, 0, sizeof *density);
    density->data = px;
    density->width = density->height = 256;
    density->channels = 1;
    memset(d, 0, sizeof *d);
    d->mesh.positions = head->vertices[0].pos;
    d->mesh.normals = head->vertices[0].normal;
    d->mesh.uvs = head->vertices[0].uv;
    d->mesh.position_stride = d->mesh.normal_stride = d->mesh.uv_stride =
        (int)sizeof(hm_vertex);
    d->mesh.vertex_count = head->vertex_count;
    d->mesh.indices = head->indices;
    d->mesh.triangle_count = head->triangle_count;
    d->density_map = density;
    d->points_per_strand = BENCH_P;
    d->max_length = 0.25f;
    d->total_strands = strands;
    d->tess_factor = tess_factor;
    d->seed = 1;
    hf_rope_params_init(rp);
    rp->global_stiffness_root = 0.2f;
    rp->local_stiffness_root = 0.3f;
    rp->root_stiffness = 0.5f;
    d->rope_params = rp;
}

/* The views and vertex layouts every ribbon and point stage is measured
   with: a camera 0.6 m in front of the head; view_gpu streams, as into a
   mapped buffer. out: a common engine layout, position, tangent and
   texcoord floats interleaved (36 bytes, vbuf); out16: the same
   attributes in 16 bytes (cbuf): position SNORM16 x3 in a 0.5 m box
   around the head, texcoord UNORM16 x3, tangent SNORM8 x3, one pad. */
static void bench_views(hf_ribbon_params *view, hf_ribbon_params *view_gpu,
                        hf_ribbon_output *out, float *vbuf,
                        hf_ribbon_output *out16, unsigned char *cbuf)
{
    memset(view, 0, sizeof *view);
    view->eye[2] = 0.6f;
    view->root_width = 0.001f;
    view->tip_width = 0.0002f;
    *view_gpu = *view;
    view_gpu->nontemporal = 1;
    memset(out, 0, sizeof *out);
    out->position.data = vbuf;
    out->tangent.data = vbuf + 3;
    out->texcoord.data = vbuf + 6;
    out->position.stride = out->tangent.stride = out->texcoord.stride = 36;
    memset(out16, 0, sizeof *out16);
    out16->position.data = cbuf;
    out16->position.format = HF_FORMAT_SNORM16;
    out16->texcoord.data = cbuf + 6;
    out16->texcoord.format = HF_FORMAT_UNORM16;
    out16->tangent.data = cbuf + 12;
    out16->tangent.format = HF_FORMAT_SNORM8;
    out16->position.stride = out16->tangent.stride = out16->texcoord.stride =
        16;
    out16->position_scale = 0.5f;
}

/* the head's sphere collider, just inside its skin */
static void bench_collider(hf_collider *c)
{
    memset(c, 0, sizeof *c);
    c->type = HF_COLLIDER_SPHERE;
    c->radius = 0.097f; /* the head: BENCH_HEAD_RADIUS */
}

/* A humanoid body of BENCH_BODY proxies under the head (radius 0.1 m,
   centred at (dx, 0, dz)), as an engine's physics asset gives one:
   neck, chest, belly, pelvis, back, shoulders, arms, hands, legs, feet and
   chin, overlapping at the joints. Writes c[0 .. BENCH_BODY). */
static void bench_body(hf_collider *c, float dx, float dz)
{
    static const float caps[19][7] = {
        /* a (x, y, z), b (x, y, z), radius */
        {0, -0.09f, -0.01f, 0, -0.17f, -0.01f, 0.055f},         /* neck */
        {-0.12f, -0.30f, 0, 0.12f, -0.30f, 0, 0.11f},           /* chest */
        {-0.10f, -0.42f, 0, 0.10f, -0.42f, 0, 0.11f},           /* ribs */
        {-0.08f, -0.55f, 0, 0.08f, -0.55f, 0, 0.10f},           /* belly */
        {-0.10f, -0.70f, 0, 0.10f, -0.70f, 0, 0.11f},           /* pelvis */
        {-0.10f, -0.28f, -0.06f, 0.10f, -0.45f, -0.06f, 0.09f}, /* back */
        {-0.05f, -0.19f, -0.02f, -0.17f, -0.23f, -0.02f, 0.06f}, /* traps */
        {0.05f, -0.19f, -0.02f, 0.17f, -0.23f, -0.02f, 0.06f},
        {-0.20f, -0.25f, 0, -0.22f, -0.52f, 0, 0.05f},          /* arms */
        {0.20f, -0.25f, 0, 0.22f, -0.52f, 0, 0.05f},
        {-0.22f, -0.52f, 0, -0.24f, -0.78f, 0.03f, 0.04f},      /* forearms */
        {0.22f, -0.52f, 0, 0.24f, -0.78f, 0.03f, 0.04f},
        {-0.12f, -0.80f, 0, -0.13f, -1.20f, 0, 0.08f},          /* thighs */
        {0.12f, -0.80f, 0, 0.13f, -1.20f, 0, 0.08f},
        {-0.13f, -1.20f, 0, -0.13f, -1.60f, 0, 0.06f},          /* shins */
        {0.13f, -1.20f, 0, 0.13f, -1.60f, 0, 0.06f},
        {-0.13f, -1.66f, -0.02f, -0.13f, -1.66f, 0.12f, 0.04f}, /* feet */
        {0.13f, -1.66f, -0.02f, 0.13f, -1.66f, 0.12f, 0.04f},
        {-0.04f, -0.30f, 0.07f, 0.04f, -0.30f, 0.07f, 0.06f}};  /* sternum */
    static const float sph[5][4] = {{-0.19f, -0.24f, 0, 0.065f}, /* shoulders */
                                    {0.19f, -0.24f, 0, 0.065f},
                                    {-0.25f, -0.84f, 0.04f, 0.05f}, /* hands */
                                    {0.25f, -0.84f, 0.04f, 0.05f},
                                    {0, -0.02f, 0.09f, 0.04f}}; /* chin */
    int i, k;
    for (i = 0; i < BENCH_BODY; ++i) {
        hf_collider *o = c + i;
        const float *q = i < 19 ? caps[i] : sph[i - 19];
        memset(o, 0, sizeof *o);
        o->type = i < 19 ? HF_COLLIDER_CAPSULE : HF_COLLIDER_SPHERE;
        for (k = 0; k < 3; ++k) {
            const float off = k == 0 ? dx : (k == 2 ? dz : 0.0f);
            o->a[k] = q[k] + off;
            o->b[k] = (i < 19 ? q[3 + k] : q[k]) + off;
        }
        o->radius = i < 19 ? q[6] : q[3];
    }
}

#endif /* HAIRFUR_H */

#endif
