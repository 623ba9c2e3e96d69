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

#endif /* HAIRFUR_H */

#endif
