/* bench_peers.cpp - hairfur.h ropes against Bullet soft-body ropes.
 *
 *   make bench-peers        (needs Debian's libbullet-dev: make deps)
 *   build/bench_peers [--steps N] [--world-steps N] [--ropes K,K,...]
 *                     [--bullet-voxel M] [--no-sweep]
 *
 * The scenario, the same for both libraries:
 *   K ropes of 16 segments (17 points), 0.3 m long, rooted on a sphere of
 *   radius 0.1 m. Roots cover the upper hemisphere on a Fibonacci spiral:
 *   rope i has normal n = (r cos(i*ga), y, r sin(i*ga)) with
 *   y = 1 - (i + 0.5) / K, r = sqrt(1 - y^2), ga = pi * (3 - sqrt 5); the
 *   root is centre + 0.1 n and the rope is grown straight along n.
 *   The sphere (and every root with it) swings sideways:
 *       centre(t) = (0.2 * sin(2 pi t), 0, 0)   [m; t in s]
 *   i.e. amplitude 0.2 m (0.4 m peak to peak) at 1 Hz, peak speed 1.26 m/s.
 *   Gravity (0, -9.81, 0). 300 steps of 1/60 s; before step k the roots
 *   (and the collider) are put at t = (k + 1) / 60.
 *   The sphere is a collider for both (hairfur: hf_collider sphere;
 *   Bullet: a kinematic btRigidBody with a btSphereShape). At 1,000 ropes
 *   a pair without the collider is run too (pure solver cost).
 *
 * hairfur: hf_rope_params_init defaults (FTL solver, 2 iterations,
 *   1/60 s sub-steps, time scale 1), one hf_ropes_set_roots +
 *   hf_ropes_step per step, single thread.
 * Bullet 3.24 (the 2010 hair plugin's settings): btSoftBodyHelpers::
 *   CreateRope, m_cfg.kDP = 0.08, m_cfg.piterations = 16,
 *   m_cfg.timescale = 2, root node mass 0 (setMass, then updateConstants()
 *   at once AND m_bUpdateRtCst = false: in 3.24 updateConstants() leaves
 *   the flag set, so the first step would recompute every rest length from
 *   the moved pose), other nodes mass 1,
 *   soft-body collision margin 0.002 m (hairfur's collision_margin; the
 *   default 0.25 m would keep every node 0.25 m off a 0.1 m sphere),
 *   sparse-SDF voxel 0.01 m (the default 0.25 m gets a 0.1 m sphere's
 *   normals wrong; see g_voxel).
 *   The root node's m_x is set to the root each step. Three ways:
 *     solver only  no world: per rope predictMotion, the rope-vs-sphere
 *                  collision handler (what the world's dispatcher calls),
 *                  solveConstraints, integrateMotion. No soft-soft pair
 *                  tests at all. THE FAIR BASELINE, used in the `bench`
 *                  lines.
 *     world, filtered  btSoftRigidDynamicsWorld::stepSimulation with
 *                  collision filter groups that let ropes meet the sphere
 *                  but not one another (broadphase still runs).
 *     full world   btSoftRigidDynamicsWorld with default filters: every
 *                  overlapping rope pair gets a soft-soft collision
 *                  algorithm (ropes on one head all overlap: quadratic).
 *                  The two world rows run the first --world-steps steps
 *                  only (default 60; at 5,000 ropes 10 filtered and 3
 *                  full-world steps, seconds each) and say so.
 *
 * Timing: each step is timed alone, both by the wall clock (steady_clock)
 * and by this thread's CPU time (CLOCK_THREAD_CPUTIME_ID), and scaled to ms
 * per step per 1,000 ropes. The table shows the wall median, the wall mean
 * (total/steps) and the CPU median; the ratio column and the `bench` lines
 * use the CPU MEDIAN, because on a shared machine the wall clock also
 * counts time spent waiting for a core, which hits Bullet's long steps far
 * more often than hairfur's short ones. On an idle machine the two agree.
 * Stretch: max over steps and segments of |length - rest| / rest, measured
 * after each step outside the timing
 * (hairfur: hf_ropes_max_stretch; Bullet: node positions against each
 * link's rest length m_rl). "settled" is the same over steps 60..299 (after
 * the first fall). "pen" is the deepest any non-root point ends inside the
 * sphere (mm; 0 = none).
 */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"

#include <btBulletDynamicsCommon.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

static const int SEGS = 16;
static const int PTS = SEGS + 1;
static const float LEN = 0.3f;
static const float RAD = 0.1f;
static const float AMP = 0.2f;  /* centre x = AMP * sin(2 pi t) */
static const float FREQ = 1.0f; /* Hz */
static const float DT = 1.0f / 60.0f;
static const float GRAV = -9.81f;
static const float MARGIN = 0.002f;
static const int SETTLE = 60;
/* Bullet's sparse SDF voxel (m). Its default, 0.25 m, samples a 0.1 m
   sphere so coarsely that the contact normals point the wrong way (about
   (0.58, 0.58, 0.58) everywhere) and points up to 13 mm inside read as
   outside; 0.01 m gives the exact distance and normal. --bullet-voxel. */
static float g_voxel = 0.01f;
static const double PI = 3.14159265358979323846;

struct Scene {
    int K;
    std::vector<float> nrm;  /* K * 3, unit normals */
    std::vector<float> tan;  /* K * 3 */
};

static void make_scene(Scene &s, int K)
{
    s.K = K;
    s.nrm.resize((size_t)K * 3);
    s.tan.resize((size_t)K * 3);
    const double ga = PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < K; ++i) {
        double y = 1.0 - (i + 0.5) / K;
        double r = std::sqrt(std::max(0.0, 1.0 - y * y));
        double ph = ga * i;
        double n[3] = {r * std::cos(ph), y, r * std::sin(ph)};
        /* tangent: the azimuthal direction (perpendicular to n) */
        double t[3] = {-std::sin(ph), 0.0, std::cos(ph)};
        for (int c = 0; c < 3; ++c) {
            s.nrm[i * 3 + c] = (float)n[c];
            s.tan[i * 3 + c] = (float)t[c];
        }
    }
}

static float centre_x(double t) { return (float)(AMP * std::sin(2.0 * PI * FREQ * t)); }

static void roots_at(const Scene &s, double t, std::vector<float> &pos)
{
    float cx = centre_x(t);
    pos.resize((size_t)s.K * 3);
    for (int i = 0; i < s.K; ++i) {
        pos[i * 3 + 0] = cx + RAD * s.nrm[i * 3 + 0];
        pos[i * 3 + 1] = RAD * s.nrm[i * 3 + 1];
        pos[i * 3 + 2] = RAD * s.nrm[i * 3 + 2];
    }
}

#include <time.h>
typedef std::chrono::steady_clock Clock;
/* this thread's CPU time (ms): unlike the wall clock, it does not count
   time spent waiting for a core on a busy machine */
static double cpu_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}
static double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Result {
    double median_ms; /* per step, whole set, wall clock */
    double cpu_median_ms; /* the same in thread CPU time */
    double mean_ms;
    int steps;
    double stretch, settled, pen_mm;
    double inside; /* fraction of (non-root point, step) pairs > 1 mm inside */
    double setup_s, teardown_s; /* Bullet: building / freeing (untimed) */
    long long pairs; /* Bullet world: overlapping broadphase pairs at the end */
    bool ok;
};

static double median_of(std::vector<double> t)
{
    std::sort(t.begin(), t.end());
    size_t n = t.size();
    return n == 0 ? 0 : (n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]));
}

static void finish_times(std::vector<double> &t, std::vector<double> &c,
                         Result &r)
{
    r.cpu_median_ms = median_of(c);
    r.steps = (int)t.size();
    double sum = 0;
    for (size_t i = 0; i < t.size(); ++i) sum += t[i];
    r.mean_ms = t.empty() ? 0 : sum / t.size();
    std::sort(t.begin(), t.end());
    size_t n = t.size();
    r.median_ms = n == 0 ? 0 : (n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]));
}

/* ---------------------------------------------------------------- hairfur */

static Result run_hairfur(const Scene &s, int steps, const hf_rope_params &p,
                          bool collider)
{
    Result res;
    memset(&res, 0, sizeof res);
    const int K = s.K;
    hf_ropes *ropes = 0;
    if (hf_ropes_create(K, PTS, 0, &ropes) != HF_OK) {
        fprintf(stderr, "hf_ropes_create failed\n");
        return res;
    }
    std::vector<float> root, pts((size_t)K * PTS * 3);
    roots_at(s, 0.0, root);
    for (int i = 0; i < K; ++i)
        for (int j = 0; j < PTS; ++j)
            for (int c = 0; c < 3; ++c)
                pts[((size_t)i * PTS + j) * 3 + c] =
                    root[i * 3 + c] + s.nrm[i * 3 + c] * (LEN * j / SEGS);
    hf_result rc = hf_ropes_set_rest(ropes, 0, K, pts.data(), 0, root.data(),
                                     s.nrm.data(), s.tan.data(), 0);
    if (rc != HF_OK) {
        fprintf(stderr, "hf_ropes_set_rest: %s\n", hf_result_string(rc));
        hf_ropes_destroy(ropes);
        return res;
    }
    std::vector<double> times, ctimes;
    times.reserve(steps);
    ctimes.reserve(steps);
    double worst = 0, settled = 0, pen = 0;
    long long n_in = 0, n_all = 0;
    for (int k = 0; k < steps; ++k) {
        double t = (k + 1) * (double)DT;
        roots_at(s, t, root);
        hf_collider col;
        memset(&col, 0, sizeof col);
        col.type = HF_COLLIDER_SPHERE;
        col.a[0] = centre_x(t);
        col.radius = RAD;
        double c0 = cpu_ms();
        Clock::time_point t0 = Clock::now();
        hf_ropes_set_roots(ropes, 0, K, root.data(), s.nrm.data(),
                           s.tan.data(), 0);
        rc = hf_ropes_step(ropes, 0, K, DT, &p, collider ? &col : 0,
                           collider ? 1 : 0);
        times.push_back(ms_since(t0));
        ctimes.push_back(cpu_ms() - c0);
        if (rc != HF_OK) {
            fprintf(stderr, "hf_ropes_step: %s\n", hf_result_string(rc));
            hf_ropes_destroy(ropes);
            return res;
        }
        float st = 0;
        hf_ropes_max_stretch(ropes, 0, K, &st);
        worst = std::max(worst, (double)st);
        if (k >= SETTLE) settled = std::max(settled, (double)st);
        for (int j = 1; j < PTS; ++j)
            for (int i = 0; i < K; ++i) {
                size_t e = (size_t)j * K + i;
                double dx = ropes->x[e] - col.a[0], dy = ropes->y[e],
                       dz = ropes->z[e];
                double d = std::sqrt(dx * dx + dy * dy + dz * dz);
                pen = std::max(pen, RAD - d);
                if (RAD - d > 0.001) ++n_in;
                ++n_all;
            }
    }
    hf_ropes_destroy(ropes);
    res.inside = (double)n_in / (n_all ? n_all : 1);
    finish_times(times, ctimes, res);
    res.stretch = worst;
    res.settled = settled;
    res.pen_mm = pen * 1000.0;
    res.ok = true;
    return res;
}

/* ----------------------------------------------------------------- Bullet */

enum BulletMode { B_SOLVER = 0, B_WORLD_FILTERED = 1, B_WORLD_FULL = 2 };

static double bullet_stretch(const std::vector<btSoftBody *> &ropes)
{
    double worst = 0;
    for (size_t r = 0; r < ropes.size(); ++r) {
        const btSoftBody *b = ropes[r];
        for (int l = 0; l < b->m_links.size(); ++l) {
            const btSoftBody::Link &L = b->m_links[l];
            double len = (L.m_n[0]->m_x - L.m_n[1]->m_x).length();
            worst = std::max(worst, std::fabs(len - L.m_rl) / L.m_rl);
        }
    }
    return worst;
}

static Result run_bullet(const Scene &s, int steps, BulletMode mode,
                         bool collider, double *rest_err)
{
    Result res;
    memset(&res, 0, sizeof res);
    const int K = s.K;

    btSoftBodyRigidBodyCollisionConfiguration *conf = 0;
    btCollisionDispatcher *disp = 0;
    btBroadphaseInterface *bp = 0;
    btSequentialImpulseConstraintSolver *solver = 0;
    btSoftBodySolver *sbsolver = 0;
    btSoftRigidDynamicsWorld *world = 0;
    btSoftBodyWorldInfo own_info;
    btSoftBodyWorldInfo *info = &own_info;
    if (mode != B_SOLVER) {
        conf = new btSoftBodyRigidBodyCollisionConfiguration();
        disp = new btCollisionDispatcher(conf);
        bp = new btDbvtBroadphase();
        solver = new btSequentialImpulseConstraintSolver();
        sbsolver = new btDefaultSoftBodySolver();
        world = new btSoftRigidDynamicsWorld(disp, bp, solver, conf, sbsolver);
        world->setGravity(btVector3(0, GRAV, 0));
        info = &world->getWorldInfo();
        info->m_broadphase = bp;
        info->m_dispatcher = disp;
    }
    info->m_gravity.setValue(0, GRAV, 0);
    info->air_density = 0;
    info->water_density = 0;
    info->m_sparsesdf.Initialize();
    info->m_sparsesdf.setDefaultVoxelsz(g_voxel);
    info->m_sparsesdf.Reset();

    /* the sphere: kinematic rigid body */
    btSphereShape *sphere = new btSphereShape(RAD);
    btTransform tr;
    tr.setIdentity();
    tr.setOrigin(btVector3(centre_x(0.0), 0, 0));
    btDefaultMotionState *ms = new btDefaultMotionState(tr);
    btRigidBody::btRigidBodyConstructionInfo ci(0, ms, sphere, btVector3(0, 0, 0));
    btRigidBody *body = new btRigidBody(ci);
    body->setCollisionFlags(body->getCollisionFlags() |
                            btCollisionObject::CF_KINEMATIC_OBJECT);
    body->setActivationState(DISABLE_DEACTIVATION);
    const int G_SPHERE = 0x40, G_ROPE = 0x80;
    if (world && collider) {
        if (mode == B_WORLD_FILTERED)
            world->addRigidBody(body, G_SPHERE, G_ROPE);
        else
            world->addRigidBody(body);
    }

    Clock::time_point t_setup = Clock::now();
    std::vector<float> root;
    roots_at(s, 0.0, root);
    std::vector<btSoftBody *> ropes((size_t)K);
    double rerr = 0;
    const double rest = (double)LEN / SEGS;
    for (int i = 0; i < K; ++i) {
        btVector3 a(root[i * 3], root[i * 3 + 1], root[i * 3 + 2]);
        btVector3 n(s.nrm[i * 3], s.nrm[i * 3 + 1], s.nrm[i * 3 + 2]);
        btSoftBody *b = btSoftBodyHelpers::CreateRope(*info, a, a + n * LEN,
                                                      PTS - 2, 0);
        b->m_cfg.kDP = 0.08f;
        b->m_cfg.piterations = 16;
        b->m_cfg.timescale = 2.0f;
        b->getCollisionShape()->setMargin(MARGIN);
        b->setMass(0, 0);      /* pinned root */
        b->updateConstants(); /* rest lengths from the built pose, now */
        /* 3.24: setMass() set m_bUpdateRtCst and updateConstants() does not
           clear it, so the first solveConstraints() would recompute every
           rest length again from the moved pose (the root link then
           "stretches" by hundreds of %). Clear it. */
        b->m_bUpdateRtCst = false;
        b->setActivationState(DISABLE_DEACTIVATION);
        for (int l = 0; l < b->m_links.size(); ++l)
            rerr = std::max(rerr, std::fabs(b->m_links[l].m_rl - rest) / rest);
        if (world) {
            if (mode == B_WORLD_FILTERED)
                world->addSoftBody(b, G_ROPE, G_SPHERE);
            else
                world->addSoftBody(b);
        }
        ropes[i] = b;
    }
    if (rest_err) rest_err[0] = rerr;
    res.setup_s = ms_since(t_setup) / 1000.0;

    std::vector<double> times, ctimes;
    times.reserve(steps);
    ctimes.reserve(steps);
    double worst = 0, settled = 0, pen = 0;
    long long n_in = 0, n_all = 0;
    for (int k = 0; k < steps; ++k) {
        double t = (k + 1) * (double)DT;
        roots_at(s, t, root);
        btTransform st;
        st.setIdentity();
        st.setOrigin(btVector3(centre_x(t), 0, 0));
        double c0 = cpu_ms();
        Clock::time_point t0 = Clock::now();
        for (int i = 0; i < K; ++i) {
            btSoftBody::Node &n0 = ropes[i]->m_nodes[0];
            n0.m_x.setValue(root[i * 3], root[i * 3 + 1], root[i * 3 + 2]);
            n0.m_v.setValue(0, 0, 0);
        }
        if (world) {
            ms->setWorldTransform(st); /* kinematic: read by the world */
            world->stepSimulation(DT, 0);
        } else {
            body->setLinearVelocity((st.getOrigin() - body->getWorldTransform().getOrigin()) / DT);
            body->setWorldTransform(st);
            body->setInterpolationWorldTransform(st);
            btCollisionObjectWrapper wrap(0, sphere, body, st, -1, -1);
            for (int i = 0; i < K; ++i) {
                btSoftBody *b = ropes[i];
                b->predictMotion(DT);
                if (collider) b->defaultCollisionHandler(&wrap);
                b->solveConstraints();
                b->integrateMotion();
            }
        }
        info->m_sparsesdf.GarbageCollect();
        times.push_back(ms_since(t0));
        ctimes.push_back(cpu_ms() - c0);
        double sk = bullet_stretch(ropes);
        worst = std::max(worst, sk);
        if (k >= SETTLE) settled = std::max(settled, sk);
        for (int i = 0; i < K; ++i)
            for (int j = 1; j < ropes[i]->m_nodes.size(); ++j) {
                btVector3 d = ropes[i]->m_nodes[j].m_x - st.getOrigin();
                pen = std::max(pen, (double)RAD - d.length());
                if (RAD - d.length() > 0.001) ++n_in;
                ++n_all;
            }
    }

    res.inside = (double)n_in / (n_all ? n_all : 1);
    double drift = 0;
    for (int i = 0; i < K; ++i)
        for (int l = 0; l < ropes[i]->m_links.size(); ++l)
            drift = std::max(drift, std::fabs(ropes[i]->m_links[l].m_rl - rest) / rest);
    if (rest_err) rest_err[1] = drift;
    Clock::time_point t_down = Clock::now();
    if (world) {
        /* Drop every overlapping pair first: removing a body makes the
           hashed pair cache scan all its pairs, and the full world holds
           one per rope pair (12.5 million at 5,000 ropes), so removing the
           ropes one by one would take minutes. */
        btOverlappingPairCache *pc = bp->getOverlappingPairCache();
        btBroadphasePairArray &pairs = pc->getOverlappingPairArray();
        res.pairs = pairs.size();
        while (pairs.size() > 0) {
            btBroadphasePair &pr = pairs[pairs.size() - 1];
            pc->removeOverlappingPair(pr.m_pProxy0, pr.m_pProxy1, disp);
        }
    }
    for (int i = 0; i < K; ++i) {
        if (world) world->removeSoftBody(ropes[i]);
        delete ropes[i];
    }
    if (world && collider) world->removeRigidBody(body);
    delete body;
    delete ms;
    delete sphere;
    delete world;
    delete sbsolver;
    delete solver;
    delete bp;
    delete disp;
    delete conf;
    res.teardown_s = ms_since(t_down) / 1000.0;

    finish_times(times, ctimes, res);
    res.stretch = worst;
    res.settled = settled;
    res.pen_mm = pen * 1000.0;
    res.ok = true;
    return res;
}

/* ------------------------------------------------------------------- main */

static double per1k(double ms, int K) { return ms * 1000.0 / K; }

static void row(const char *name, const Result &r, int K, double ref_ms)
{
    char settled[32];
    if (r.steps > SETTLE)
        snprintf(settled, sizeof settled, "%8.3f%%", r.settled * 100);
    else
        snprintf(settled, sizeof settled, "%9s", "-");
    printf("  %-30s %8.3f %8.3f %8.3f %9.3f%% %s %7.1f %7.2f%% %6d %7.1f\n",
           name, per1k(r.median_ms, K), per1k(r.mean_ms, K),
           per1k(r.cpu_median_ms, K), r.stretch * 100,
           settled, r.pen_mm, r.inside * 100, r.steps,
           r.cpu_median_ms / ref_ms);
    fflush(stdout);
}

static void header(void)
{
    printf("  %-30s %8s %8s %8s %10s %9s %7s %8s %6s %7s\n", "", "ms/1k",
           "mean", "cpu", "stretch", "settled", "pen mm", "inside", "steps",
           "ratio");
}

int main(int argc, char **argv)
{
    int steps = 300, world_steps = 60, world_steps_5k = 10, full_5k = 3;
    bool sweep = true;
    std::vector<int> counts;
    for (int a = 1; a < argc; ++a) {
        if (!strcmp(argv[a], "--steps") && a + 1 < argc) steps = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--world-steps") && a + 1 < argc) {
            world_steps = atoi(argv[++a]);
            world_steps_5k = full_5k = world_steps;
        } else if (!strcmp(argv[a], "--bullet-voxel") && a + 1 < argc)
            g_voxel = (float)atof(argv[++a]);
        else if (!strcmp(argv[a], "--ropes") && a + 1 < argc) {
            std::string l(argv[++a]);
            size_t p = 0;
            while (p < l.size()) {
                counts.push_back(atoi(l.c_str() + p));
                size_t q = l.find(',', p);
                if (q == std::string::npos) break;
                p = q + 1;
            }
        } else if (!strcmp(argv[a], "--no-sweep")) sweep = false;
        else {
            fprintf(stderr,
                    "usage: %s [--steps N] [--world-steps N] [--ropes K,K,...]"
                    " [--bullet-voxel M] [--no-sweep]\n", argv[0]);
            return 2;
        }
    }
    if (counts.empty()) {
        counts.push_back(367);
        counts.push_back(1000);
        counts.push_back(5000);
    }
    world_steps = std::min(world_steps, steps);
    world_steps_5k = std::min(world_steps_5k, steps);
    full_5k = std::min(full_5k, steps);

    hf_rope_params p;
    hf_rope_params_init(&p);
    printf("hairfur.h ropes vs Bullet %d.%02d soft-body ropes, single thread\n",
           btGetVersion() / 100, btGetVersion() % 100);
    printf("  scene: K ropes of %d segments, %.2f m, roots on a %.2f m sphere "
           "(Fibonacci spiral, upper hemisphere), grown along the normal;\n"
           "         sphere centre x = %.1f*sin(2 pi t) m (%.0f Hz), gravity "
           "%.2f, dt 1/60 s, %d steps; the sphere collides with both\n",
           SEGS, LEN, RAD, AMP, FREQ, GRAV, steps);
    printf("  hairfur: hf_rope_params_init defaults (FTL, iterations %d, "
           "substep 1/%.0f s, time scale %.0f, collision margin %.3f m)\n",
           p.iterations, 1.0 / p.substep, p.time_scale, p.collision_margin);
    printf("  Bullet: kDP 0.08, piterations 16, timescale 2, root mass 0 "
           "(+ updateConstants, m_bUpdateRtCst cleared), margin %.3f m, "
           "SDF voxel %.3f m\n", MARGIN, g_voxel);
    printf("    solver only    = predictMotion + rope-vs-sphere handler + "
           "solveConstraints + integrateMotion per rope, no world, no "
           "soft-soft tests (the baseline)\n"
           "    world,filtered = btSoftRigidDynamicsWorld::stepSimulation, "
           "filter groups: ropes meet the sphere, never each other\n"
           "    full world     = btSoftRigidDynamicsWorld with default "
           "filters: a soft-soft pair per overlapping rope pair (quadratic)\n");
    printf("  ms/1k = median wall ms per step per 1,000 ropes, mean = its "
           "mean (total/steps), cpu = MEDIAN THREAD-CPU ms per step per 1,000 "
           "ropes;\n  ratio and the bench lines use cpu (on a busy machine "
           "wall time also counts waiting for a core); stretch = max over steps and segments of |len-rest|/rest;\n"
           "  settled = the same over steps >= %d; pen = deepest non-root "
           "point inside the sphere; inside = share of (point, step) > 1 mm "
           "inside;\n  ratio = this row's cpu over hairfur's\n\n",
           SETTLE);

    std::vector<std::string> lines;
    for (size_t c = 0; c < counts.size(); ++c) {
        int K = counts[c];
        Scene s;
        make_scene(s, K);
        Result h = run_hairfur(s, steps, p, true);
        double rerr[2] = {0, 0};
        Result bs = run_bullet(s, steps, B_SOLVER, true, rerr);
        int ws = K >= 5000 ? world_steps_5k : world_steps;
        Result bf = run_bullet(s, ws, B_WORLD_FILTERED, true, 0);
        Result bw = run_bullet(s, K >= 5000 ? full_5k : ws, B_WORLD_FULL,
                               true, 0);
        if (!h.ok || !bs.ok) return 1;
        printf("ropes=%d\n", K);
        header();
        row("hairfur (defaults)", h, K, h.cpu_median_ms);
        row("Bullet solver only", bs, K, h.cpu_median_ms);
        row("Bullet world, filtered", bf, K, h.cpu_median_ms);
        row("Bullet full world", bw, K, h.cpu_median_ms);
        if (bf.steps < steps)
            printf("  (world rows: first %d / %d steps only, to keep the run "
                   "short)\n", bf.steps, bw.steps);
        printf("  (broadphase pairs at the end: filtered %lld, full world "
               "%lld; setup+teardown s: solver %.1f, filtered %.1f, full "
               "%.1f)\n", bf.pairs, bw.pairs, bs.setup_s + bs.teardown_s,
               bf.setup_s + bf.teardown_s, bw.setup_s + bw.teardown_s);
        if (rerr[1] > 1e-4)
            printf("  WARNING: Bullet rest lengths changed during the run "
                   "(max %.1e)\n", rerr[1]);
        if (K == 1000) {
            Result h0 = run_hairfur(s, steps, p, false);
            Result b0 = run_bullet(s, steps, B_SOLVER, false, 0);
            row("hairfur, no collider", h0, K, h.cpu_median_ms);
            row("Bullet solver, no collider", b0, K, h.cpu_median_ms);
            printf("  (no-collider pair: Bullet/hairfur = %.1f)\n",
                   b0.cpu_median_ms / h0.cpu_median_ms);
        }
        printf("\n");
        char buf[512];
        snprintf(buf, sizeof buf,
                 "bench stage=ropes_vs_bullet ropes=%d hairfur_ms=%.4f "
                 "bullet_ms=%.4f ratio=%.1f stretch=%.6f bullet_stretch=%.4f",
                 K, per1k(h.cpu_median_ms, K), per1k(bs.cpu_median_ms, K),
                 bs.cpu_median_ms / h.cpu_median_ms, h.stretch, bs.stretch);
        lines.push_back(buf);
        snprintf(buf, sizeof buf,
                 "bench stage=ropes_vs_bullet_world ropes=%d "
                 "filtered_ms=%.4f full_world_ms=%.4f filtered_steps=%d "
                 "full_world_steps=%d", K, per1k(bf.cpu_median_ms, K),
                 per1k(bw.cpu_median_ms, K), bf.steps, bw.steps);
        lines.push_back(buf);
    }

    if (sweep) {
        Scene s;
        make_scene(s, 1000);
        printf("hairfur params, 1,000 ropes, same scene (stretch target "
               "< 0.5 %%):\n");
        header();
        struct V { const char *name; int it; float sub; float ts; } v[] = {
            {"defaults (iterations 2)", 2, 0, 0},
            {"iterations 1", 1, 0, 0},
            {"iterations 4", 4, 0, 0},
            {"substep 1/240 s", 2, 1.0f / 240, 0},
            {"time_scale 2 (as Bullet's)", 2, 0, 2},
            {"time_scale 2, substep 1/30 s", 2, 1.0f / 30, 2}};
        double ref = 0;
        for (size_t i = 0; i < sizeof v / sizeof v[0]; ++i) {
            hf_rope_params q;
            hf_rope_params_init(&q);
            q.iterations = v[i].it;
            if (v[i].sub > 0) q.substep = v[i].sub;
            if (v[i].ts > 0) q.time_scale = v[i].ts;
            Result r = run_hairfur(s, steps, q, true);
            if (i == 0) ref = r.cpu_median_ms;
            row(v[i].name, r, 1000, ref);
        }
        printf("\n");
    }
    for (size_t i = 0; i < lines.size(); ++i) printf("%s\n", lines[i].c_str());
    return 0;
}
