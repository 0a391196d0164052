/*
 * bench_kinematics - cost of one control step's kinematics: a full 4-leg
 * body IK + leg IK + servo byte encoding, in the core's integer arithmetic
 * and, for comparison, the same computation in double precision (libm),
 * both compiled here with -O2.
 *
 *   bench_kinematics fixed  N    N steps of the integer version
 *   bench_kinematics double N    N steps of the double version
 *   bench_kinematics [both [N]]  both (default N = 20000)
 *
 * Each step is one call of bench_fixed_step / bench_double_step (never
 * inlined), so instruction counts per step come from callgrind:
 *
 *   valgrind --tool=callgrind --callgrind-out-file=/dev/null \
 *       --toggle-collect=bench_fixed_step build/bench_kinematics fixed 10000
 *
 * (the "Collected" total divided by N). Wall-clock ns/step is printed for
 * information only. The inputs are 256 poses spread over the Mini's body
 * register ranges, with the feet moved around the stance as in a gait; both
 * versions see the same poses, and the bench reports how many servo bytes
 * they agree on.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "codec.h"
#include "reference.h"
#include "kinematics.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#if defined(__GNUC__)
#define BENCH_NOINLINE __attribute__((noinline))
#else
#define BENCH_NOINLINE
#endif

#define N_POSES 256

typedef struct {
    double x, y, z, roll, pitch, yaw; /* mm, radians */
} dpose_t;

typedef struct {
    double x, y, z;
} dvec_t;

static xgo_body_pose_t fposes[N_POSES];
static xgo_vec3_t ffeet[N_POSES][4];
static dpose_t dposes[N_POSES];
static dvec_t dfeet[N_POSES][4];

/* ------------------------------------------------------------ integer */

BENCH_NOINLINE void bench_fixed_step(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                                     const xgo_vec3_t feet[4], uint8_t out[12]);

void bench_fixed_step(const xgo_profile_t *p, const xgo_body_pose_t *pose, const xgo_vec3_t feet[4],
                      uint8_t out[12])
{
    int32_t q[4][3];
    (void)xgo_body_to_joints(p, pose, feet, q);
    xgo_joints_to_bytes(p, (const int32_t(*)[3])q, out);
}

/* ------------------------------------------------------------ double */

typedef struct {
    double l1, l2, d, knee_off, hip_x, hip_y;
    double lo[3], hi[3]; /* joint limits, radians */
    double blo[3], bhi[3]; /* byte ranges, degrees */
} dprofile_t;

static dprofile_t dprof;

static double clampd(double v, double lo, double hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static uint8_t encode_d(double deg, double lo, double hi)
{
    double f = floor(255.0 * (deg - lo) / (hi - lo));
    return (uint8_t)clampd(f, 0.0, 255.0);
}

BENCH_NOINLINE void bench_double_step(const dprofile_t *p, const dpose_t *pose, const dvec_t feet[4],
                                      uint8_t out[12]);

void bench_double_step(const dprofile_t *p, const dpose_t *pose, const dvec_t feet[4], uint8_t out[12])
{
    double m[3][3];
    int leg;
    xgo_ref_rotation(pose->roll, pose->pitch, pose->yaw, m);
    for (leg = 0; leg < 4; ++leg) {
        double sx = (leg == 0 || leg == 1) ? 1.0 : -1.0;
        double s = (leg == 0 || leg == 3) ? 1.0 : -1.0;
        double vx = feet[leg].x - pose->x, vy = feet[leg].y - pose->y, vz = feet[leg].z - pose->z;
        /* body IK */
        double x = m[0][0] * vx + m[1][0] * vy + m[2][0] * vz - sx * p->hip_x;
        double y = m[0][1] * vx + m[1][1] * vy + m[2][1] * vz - s * (p->hip_y + p->d);
        double z = -(m[0][2] * vx + m[1][2] * vy + m[2][2] * vz);
        /* leg IK */
        double wp = s * y + p->d;
        double h2 = wp * wp + z * z - p->d * p->d;
        double h = h2 > 0 ? sqrt(h2) : 0.0;
        double phi = atan2(wp, z) - atan2(p->d, h);
        double sg = clampd((x * x + h * h - p->l1 * p->l1 - p->l2 * p->l2) / (2 * p->l1 * p->l2), -1.0, 1.0);
        double g = asin(sg);
        double t2 = atan2(-x, h) + atan2(p->l2 * cos(g), p->l1 + p->l2 * sg);
        double q[3];
        int j;
        q[0] = clampd(g - p->knee_off, p->lo[0], p->hi[0]);
        q[1] = clampd(t2, p->lo[1], p->hi[1]);
        q[2] = clampd(phi, p->lo[2], p->hi[2]);
        for (j = 0; j < 3; ++j) {
            out[leg * 3 + j] = encode_d(q[j] * (180.0 / M_PI), p->blo[j], p->bhi[j]);
        }
    }
}

/* ------------------------------------------------------------ driver */

static uint32_t lcg = 12345u;
static int32_t rnd_range(int32_t lo, int32_t hi)
{
    lcg = lcg * 1664525u + 1013904223u;
    return lo + (int32_t)((lcg >> 8) % (uint32_t)(hi - lo + 1));
}

static void make_inputs(const xgo_profile_t *p)
{
    xgo_vec3_t stance[4];
    int i, leg, j;
    xgo_stance_feet(p, stance);
    for (i = 0; i < N_POSES; ++i) {
        xgo_body_pose_t *fp = &fposes[i];
        /* a third of the body ranges, feet within a step of the stance: poses a
         * gait combines, all reachable (the bench reports if one is not) */
        fp->x_um = rnd_range(p->body_um[0].lo / 3, p->body_um[0].hi / 3);
        fp->y_um = rnd_range(p->body_um[1].lo / 3, p->body_um[1].hi / 3);
        fp->z_um = rnd_range(90000, 105000);
        fp->roll_mdeg = rnd_range(p->body_mdeg[0].lo / 3, p->body_mdeg[0].hi / 3);
        fp->pitch_mdeg = rnd_range(p->body_mdeg[1].lo / 3, p->body_mdeg[1].hi / 3);
        fp->yaw_mdeg = rnd_range(p->body_mdeg[2].lo / 3, p->body_mdeg[2].hi / 3);
        dposes[i].x = fp->x_um / 1000.0;
        dposes[i].y = fp->y_um / 1000.0;
        dposes[i].z = fp->z_um / 1000.0;
        dposes[i].roll = fp->roll_mdeg / 1000.0 * (M_PI / 180.0);
        dposes[i].pitch = fp->pitch_mdeg / 1000.0 * (M_PI / 180.0);
        dposes[i].yaw = fp->yaw_mdeg / 1000.0 * (M_PI / 180.0);
        for (leg = 0; leg < 4; ++leg) {
            ffeet[i][leg].x = stance[leg].x + rnd_range(-15000, 15000);
            ffeet[i][leg].y = stance[leg].y + rnd_range(-8000, 8000);
            ffeet[i][leg].z = rnd_range(0, 10000);
            dfeet[i][leg].x = ffeet[i][leg].x / 1000.0;
            dfeet[i][leg].y = ffeet[i][leg].y / 1000.0;
            dfeet[i][leg].z = ffeet[i][leg].z / 1000.0;
        }
    }
    dprof.l1 = p->thigh_um / 1000.0;
    dprof.l2 = p->shank_um / 1000.0;
    dprof.d = p->abad_offset_um / 1000.0;
    dprof.knee_off = p->knee_offset_mdeg / 1000.0 * (M_PI / 180.0);
    dprof.hip_x = p->hip_x_um / 1000.0;
    dprof.hip_y = p->hip_y_um / 1000.0;
    for (j = 0; j < 3; ++j) {
        dprof.blo[j] = p->joint_mdeg[j].lo / 1000.0;
        dprof.bhi[j] = p->joint_mdeg[j].hi / 1000.0;
        dprof.lo[j] = dprof.blo[j] * (M_PI / 180.0);
        dprof.hi[j] = dprof.bhi[j] * (M_PI / 180.0);
    }
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static uint32_t run_fixed(const xgo_profile_t *p, long n, double *ns_per_step)
{
    uint8_t out[12];
    uint32_t sum = 0;
    long i;
    double t0 = now_ns();
    for (i = 0; i < n; ++i) {
        int k;
        bench_fixed_step(p, &fposes[i % N_POSES], ffeet[i % N_POSES], out);
        for (k = 0; k < 12; ++k) {
            sum = sum * 31u + out[k];
        }
    }
    *ns_per_step = (now_ns() - t0) / (double)n;
    return sum;
}

static uint32_t run_double(long n, double *ns_per_step)
{
    uint8_t out[12];
    uint32_t sum = 0;
    long i;
    double t0 = now_ns();
    for (i = 0; i < n; ++i) {
        int k;
        bench_double_step(&dprof, &dposes[i % N_POSES], dfeet[i % N_POSES], out);
        for (k = 0; k < 12; ++k) {
            sum = sum * 31u + out[k];
        }
    }
    *ns_per_step = (now_ns() - t0) / (double)n;
    return sum;
}

/* How many of the 256 x 12 servo bytes the two versions agree on (they can
 * differ by one where a value sits on a byte boundary). */
static void compare(const xgo_profile_t *p)
{
    int i, k, same = 0, off_by_one = 0, other = 0, projected = 0;
    for (i = 0; i < N_POSES; ++i) {
        uint8_t a[12], b[12];
        int32_t q[4][3];
        unsigned mask = xgo_body_to_joints(p, &fposes[i], ffeet[i], q);
        for (k = 0; k < 4; ++k) {
            projected += (int)((mask >> k) & 1u);
        }
        bench_fixed_step(p, &fposes[i], ffeet[i], a);
        bench_double_step(&dprof, &dposes[i], dfeet[i], b);
        for (k = 0; k < 12; ++k) {
            int d = (int)a[k] - (int)b[k];
            if (d == 0) {
                ++same;
            } else if (d == 1 || d == -1) {
                ++off_by_one;
            } else {
                ++other;
            }
        }
    }
    printf("servo bytes, fixed vs double over %d steps: %d equal, %d off by one, %d other; "
           "%d of %d legs projected\n",
           N_POSES, same, off_by_one, other, projected, 4 * N_POSES);
}

int main(int argc, char **argv)
{
    const xgo_profile_t *p = xgo_profile_mini();
    const char *mode = argc > 1 ? argv[1] : "both";
    long n = argc > 2 ? atol(argv[2]) : 20000;
    double ns;
    uint32_t sum;
    if (n <= 0 || (strcmp(mode, "fixed") != 0 && strcmp(mode, "double") != 0 && strcmp(mode, "both") != 0)) {
        fprintf(stderr, "usage: %s [fixed|double|both] [steps]\n", argv[0]);
        return 2;
    }
    make_inputs(p);
    if (strcmp(mode, "fixed") == 0 || strcmp(mode, "both") == 0) {
        sum = run_fixed(p, n, &ns);
        printf("fixed : %ld steps (4-leg body IK + leg IK + 12 servo bytes), %.1f ns/step, checksum %08x\n",
               n, ns, (unsigned)sum);
    }
    if (strcmp(mode, "double") == 0 || strcmp(mode, "both") == 0) {
        sum = run_double(n, &ns);
        printf("double: %ld steps (same computation, libm, -O2),          %.1f ns/step, checksum %08x\n",
               n, ns, (unsigned)sum);
    }
    if (strcmp(mode, "both") == 0) {
        compare(p);
        printf("instructions per step: valgrind --tool=callgrind --toggle-collect=bench_fixed_step "
               "(or bench_double_step) %s fixed|double N, then Collected / N\n", argv[0]);
    }
    return 0;
}
