/* Tests for packet_hit: four rays at once give bvh_hit's hit records bit for bit (t, prim,
   point, normal, side), for rays at the prims' corners, edges and faces (where two prims tie),
   along the axes, from hit points (t_min) and in two lane positions; in the library's build
   (AVX2 here) and in the baseline's. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bvh.h"
#include "box_point.h"
#include "check.h"
#include "geom/packet.h"
#include "base/rng.h"
#include "scenefile/scene_load.h"
#include "geom/shape.h"

/* packet.c again, built for the baseline alone (SSE2 pairs; the library's packet_hit is the AVX2
   copy on a CPU that has it): both must agree with bvh_hit. */
int baseline_packet_hit(const struct packet_scene *ps, const ray *const r[PACKET_LANES], double t_min,
                        double t_max, struct packet_hits *ph);
int baseline_packet_usable(const struct scene *sc);
struct packet_scene *baseline_packet_scene_new(const struct scene *sc);
void baseline_packet_scene_free(struct packet_scene *ps);
#define PACKET_CLONES
#define packet_hit baseline_packet_hit
#define packet_usable baseline_packet_usable
#define packet_scene_new baseline_packet_scene_new
#define packet_scene_free baseline_packet_scene_free
#include "../common/geom/packet.c"
#undef packet_hit
#undef packet_usable
#undef packet_scene_new
#undef packet_scene_free

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static int same_hit(const struct hit *a, const struct hit *b)
{
    return same_bits(a->t, b->t) && a->prim == b->prim && same_bits(a->p.x, b->p.x) &&
           same_bits(a->p.y, b->p.y) && same_bits(a->p.z, b->p.z) && same_bits(a->n.x, b->n.x) &&
           same_bits(a->n.y, b->n.y) && same_bits(a->n.z, b->n.z) && a->front == b->front;
}

/* The four rays of q through packet_hit and one by one through bvh_hit: 1 when they agree. */
static int packet_agrees(const struct scene *sc, const struct packet_scene *ps, const ray q[PACKET_LANES],
                         double t_min, int *hits)
{
    const ray *rp[PACKET_LANES] = {&q[0], &q[1], &q[2], &q[3]};
    struct packet_hits ph, pb;
    int got = packet_hit(ps, rp, t_min, DBL_MAX, &ph),
        got_b = baseline_packet_hit(ps, rp, t_min, DBL_MAX, &pb);
    int ok = 1;
    for (int i = 0; i < PACKET_LANES; i++) {
        struct hit a, b = ph.h[i], c = pb.h[i];
        int ga = bvh_hit(sc, &q[i], t_min, DBL_MAX, &a);
        *hits += ga;
        if (ga != (got >> i & 1) || ga != (got_b >> i & 1) ||
            (ga && (!same_hit(&a, &b) || !same_hit(&a, &c)))) {
            ok = 0;
            fprintf(stderr,
                    "lane %d: bvh %d t %.17g prim %d, packet %d t %.17g prim %d, baseline %d t %.17g\n", i,
                    ga, ga ? a.t : 0, ga ? a.prim : -1, got >> i & 1, b.t, b.prim, got_b >> i & 1, c.t);
        }
    }
    return ok;
}

/* Rays toward 27 points of every prim's box from random points in the scene, from `eye` and along
   the axes, four at a time (each ray in two lanes), then the rays from their hits. usable: what
   packet_usable should say (packet_hit works either way). */
static void test_scene(const char *path, vec3 eye, int usable)
{
    struct scene_file sf = {0};
    struct err e;
    CHECK(scene_load(path, &sf, &e) == 0);
    if (!sf.scene)
        return;
    const struct scene *sc = sf.scene;
    CHECK(packet_usable(sc) == usable);
    struct packet_scene *ps = packet_scene_new(sc);
    CHECK(ps != NULL);
    if (!ps) {
        scene_file_free(&sf);
        return;
    }
    vec3 lo, hi;
    scene_box(sc, &lo, &hi);
    struct rng r;
    rng_seed(&r, 5, 5);
    int ok = 1, hits = 0, rays = 0, n = 0;
    ray q[PACKET_LANES];
    for (int i = 0; i < sc->n_prims; i++) {
        vec3 pl, ph;
        shape_bounds(&sc->prims[i], &pl, &ph);
        for (int k = 0; k < 27; k++) {
            vec3 target = box_point(pl, ph, k);
            vec3 inside = v3(lo.x + rng_uniform(&r) * (hi.x - lo.x), lo.y + rng_uniform(&r) * (hi.y - lo.y),
                             lo.z + rng_uniform(&r) * (hi.z - lo.z));
            ray set[5] = {
                {inside, v3_sub(target, inside), 0},
                {eye, v3_sub(target, eye), 0},
                {target, v3(k % 3 == 0 ? 1 : 0, k % 3 == 1 ? -1 : 0, k % 3 == 2 ? 1 : 0), 0},
                {v3_add(target, v3(0, 0.5, 0)), v3(-0.0, -1, -0.0), 0},
                {inside, v3(rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5), 0},
            };
            for (int s = 0; s < 5; s++) {
                q[n++ % PACKET_LANES] = set[s];
                if (n % PACKET_LANES)
                    continue;
                ok &= packet_agrees(sc, ps, q, HIT_EPS, &hits);
                /* the same rays rotated by a lane, and again from their hits (as paths go on) */
                ray turned[PACKET_LANES] = {q[3], q[0], q[1], q[2]};
                ok &= packet_agrees(sc, ps, turned, HIT_EPS, &hits);
                for (int j = 0; j < PACKET_LANES; j++) {
                    struct hit h;
                    if (bvh_hit(sc, &q[j], HIT_EPS, DBL_MAX, &h))
                        q[j] = (ray){h.p, q[(j + 1) % PACKET_LANES].dir, 0};
                }
                ok &= packet_agrees(sc, ps, q, HIT_EPS, &hits);
                ok &= packet_agrees(sc, ps, q, 0, &hits);
                rays += 4 * PACKET_LANES;
            }
        }
    }
    fprintf(stderr, "%s: %d rays, %d hits\n", path, rays, hits);
    CHECK(ok);
    CHECK(hits > rays / 4);
    packet_scene_free(ps);
    scene_file_free(&sf);
}

int main(void)
{
    test_scene("scenes/cornell-book3.yaml", v3(278, 278, -800), 1);
    test_scene("scenes/cornell.yaml", v3(278, 278, -800), 0); /* its cylinder: by shape_hit */
    test_scene("scenes/checker.yaml", v3(13, 2, 3), 1);
    return check_report("test_packet");
}
