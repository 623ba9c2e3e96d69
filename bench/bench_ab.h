/* bench_ab.h - what bench_ab.c asks of each of its two sides (ab_side.c,
   built once with each version of hairfur.h). */
#ifndef BENCH_AB_H
#define BENCH_AB_H

/* the stages, each run on every strand (or guide) of the scene */
enum {
    AB_STRANDS,       /* hf_fur_interpolate, the fur's default stores */
    AB_RIBBONS,       /* hf_fur_ribbons: position, tangent, texcoord floats */
    AB_RIBBONS16,     /* the same in 16 bytes (SNORM16, UNORM16, SNORM8) */
    AB_POINTS,        /* hf_fur_points, ordinary stores */
    AB_INTERP_POINTS, /* hf_fur_interpolate_points, streaming stores */
    AB_ROPES,         /* hf_fur_simulate, 1/60 s, the head's sphere */
    AB_N
};

/* One side's functions: make a scene of `strands` strands of `points`
   points on `head` (density image px, 256 x 256; NULL and a message on
   stderr when it cannot), run a stage once over the whole scene in calls
   of `range` strands or guides (the last call takes what is left; 0 for
   one call; 0, or the first failing hf_result), free the scene. */
typedef struct ab_side {
    void *(*make)(const hm_mesh *head, const unsigned char *px, int strands,
                  int points);
    int (*run)(void *scene, int stage, int range);
    void (*free_scene)(void *scene);
} ab_side;

extern const ab_side ab_base, ab_new;

#endif
