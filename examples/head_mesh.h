/* head_mesh.h - the built-in test subject of the examples and benchmarks:
   a head-like UV sphere with a procedural hairline density map, a bangs
   length map and a colour map. Not part of the library.

   The sphere is an engine-style mesh: interleaved vertices, a UV seam (the
   first column is repeated at u = 1) and split poles, so it exercises the
   library's welding of guides across seams. The face looks along +z; u runs
   around the head from the back (u = 0 and 1 at -z) through +x (u = 0.25),
   the face (u = 0.5) and -x (u = 0.75); v runs from the crown (v = 0) to the
   chin (v = 1).

   Include it in one file with HEAD_MESH_IMPLEMENTATION defined. */
#ifndef HEAD_MESH_H
#define HEAD_MESH_H

#include <stdint.h>

typedef struct hm_vertex {
    float pos[3];
    float normal[3];
    float uv[2];
} hm_vertex;

typedef struct hm_mesh {
    hm_vertex *vertices;
    uint32_t *indices;
    int vertex_count, triangle_count;
} hm_mesh;

/* A sphere of `radius` centred at the origin: rings >= 2 latitude bands,
   segments >= 3 around. (rings + 1) * (segments + 1) vertices, 2 * rings *
   segments triangles (the pole triangles have zero area: engines export
   such meshes, and the library must cope). Returns 0 on out of memory. */
int hm_sphere(int rings, int segments, float radius, hm_mesh *out);
void hm_free(hm_mesh *m);

/* Maps, 8-bit single channel (colour: RGB), w x h, row 0 = v = 0. */
void hm_hairline_density(unsigned char *px, int w, int h);
/* The head's motion at time t (s) in the examples: a sideways swing
   (0.05 m at 1 Hz) and a turn (+-25 degrees at 0.5 Hz) about y; still:
   the rest pose. Rows of a 3x4 matrix. */
void hm_pose(double t, int still, float m[12]);
/* o = m p, p a point (w = 1) or a direction (w = 0). */
void hm_xform(const float m[12], const float *p, float w, float *o);
void hm_bangs_length(unsigned char *px, int w, int h);
void hm_hair_color(unsigned char *rgb, int w, int h);

#endif

#ifdef HEAD_MESH_IMPLEMENTATION
#include <math.h>
#include <stdlib.h>

int hm_sphere(int rings, int segments, float radius, hm_mesh *out)
{
    int r, s, k = 0;
    const double pi = 3.14159265358979323846;
    out->vertex_count = (rings + 1) * (segments + 1);
    out->triangle_count = 2 * rings * segments;
    out->vertices =
        (hm_vertex *)malloc(sizeof(hm_vertex) * (size_t)out->vertex_count);
    out->indices =
        (uint32_t *)malloc(sizeof(uint32_t) * 3u * (size_t)out->triangle_count);
    if (!out->vertices || !out->indices) {
        hm_free(out);
        return 0;
    }
    for (r = 0; r <= rings; ++r)
        for (s = 0; s <= segments; ++s) {
            hm_vertex *v = &out->vertices[r * (segments + 1) + s];
            double theta = pi * r / rings;        /* from the crown */
            double phi = 2.0 * pi * (s % segments) / segments;
            /* exact poles (sin(pi) is 1e-16): the split pole vertices share
               one position, as an exporter writes them */
            double st = (r == 0 || r == rings) ? 0.0 : sin(theta);
            double ct = r == 0 ? 1.0 : (r == rings ? -1.0 : cos(theta));
            double n[3];
            n[0] = st * sin(phi);
            n[1] = ct;
            n[2] = -st * cos(phi);
            v->normal[0] = (float)n[0];
            v->normal[1] = (float)n[1];
            v->normal[2] = (float)n[2];
            v->pos[0] = radius * (float)n[0];
            v->pos[1] = radius * (float)n[1];
            v->pos[2] = radius * (float)n[2];
            v->uv[0] = (float)s / (float)segments;
            v->uv[1] = (float)r / (float)rings;
        }
    for (r = 0; r < rings; ++r)
        for (s = 0; s < segments; ++s) {
            uint32_t a = (uint32_t)(r * (segments + 1) + s), b = a + 1;
            uint32_t c = a + (uint32_t)(segments + 1), d = c + 1;
            /* counter-clockwise seen from outside */
            out->indices[k++] = a; out->indices[k++] = c; out->indices[k++] = b;
            out->indices[k++] = b; out->indices[k++] = c; out->indices[k++] = d;
        }
    return 1;
}

void hm_free(hm_mesh *m)
{
    free(m->vertices);
    free(m->indices);
    m->vertices = NULL;
    m->indices = NULL;
}

static double hm__smooth(double e0, double e1, double x)
{
    double t = (x - e0) / (e1 - e0);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return t * t * (3 - 2 * t);
}

/* Angular distance of u from the face direction (u = 0.5), in turns. */
static double hm__from_face(double u)
{
    double d = u - 0.5;
    return d < 0 ? -d : d;
}

void hm_pose(double t, int still, float m[12])
{
    const double pi = 3.14159265358979f; /* as the viewer always had it */
    double yaw = still ? 0.0 : 0.436 * sin(pi * t);
    double dx = still ? 0.0 : 0.05 * sin(2.0 * pi * t);
    float c = (float)cos(yaw), s = (float)sin(yaw);
    int k;
    for (k = 0; k < 12; ++k) m[k] = 0.0f;
    m[0] = c; m[2] = s; m[3] = (float)dx; m[5] = 1; m[8] = -s; m[10] = c;
}

void hm_xform(const float m[12], const float *p, float w, float *o)
{
    int k;
    for (k = 0; k < 3; ++k)
        o[k] = m[4 * k] * p[0] + m[4 * k + 1] * p[1] + m[4 * k + 2] * p[2] +
               m[4 * k + 3] * w;
}

void hm_hairline_density(unsigned char *px, int w, int h)
{
    int x, y;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double u = (x + 0.5) / w, v = (y + 0.5) / h;
            double f = hm__from_face(u);
            /* hairline: low on the forehead (v 0.3), lower at the temples,
               down to the nape at the back (v 0.62) */
            double line = 0.30 + 0.32 * hm__smooth(0.05, 0.45, f);
            double d = 1.0 - hm__smooth(line - 0.03, line + 0.03, v);
            /* thinner at the crown whorl */
            d *= 0.75 + 0.25 * hm__smooth(0.0, 0.12, v);
            px[y * w + x] = (unsigned char)(255.0 * d + 0.5);
        }
}

void hm_bangs_length(unsigned char *px, int w, int h)
{
    int x, y;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double u = (x + 0.5) / w, v = (y + 0.5) / h;
            double f = hm__from_face(u);
            /* bangs: the front of the scalp is cut to 40 %, the back
               grows longest */
            double front = 1.0 - hm__smooth(0.10, 0.22, f);
            double len = 0.75 + 0.25 * hm__smooth(0.2, 0.5, f);
            len = len * (1.0 - 0.6 * front * hm__smooth(0.05, 0.2, v));
            px[y * w + x] = (unsigned char)(255.0 * len + 0.5);
        }
}

void hm_hair_color(unsigned char *rgb, int w, int h)
{
    int x, y;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double u = (x + 0.5) / w, v = (y + 0.5) / h;
            /* warm brown with lighter streaks */
            double streak = 0.5 + 0.5 * sin(u * 2.0 * 3.14159265 * 9.0 + v * 7.0);
            double k = 0.8 + 0.2 * streak * streak;
            unsigned char *p = rgb + 3 * (y * w + x);
            p[0] = (unsigned char)(255.0 * 0.42 * k + 0.5);
            p[1] = (unsigned char)(255.0 * 0.27 * k + 0.5);
            p[2] = (unsigned char)(255.0 * 0.15 * k + 0.5);
        }
}
#endif
