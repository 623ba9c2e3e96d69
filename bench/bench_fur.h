/* bench_fur.h - the benchmarks' fur: the built-in head (examples/
   head_mesh.h) with its hairline density, 16 points a strand, 25 cm at
   most, seed 1, stiff roots. One description for bench.c and both sides
   of bench_ab.c, so that they measure the same scene. Include it after
   hairfur.h and head_mesh.h. */
#ifndef BENCH_FUR_H
#define BENCH_FUR_H

#define BENCH_P 16

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

#endif
