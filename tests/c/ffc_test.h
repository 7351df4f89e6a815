/* ffc_test.h: helpers shared by the C unit tests (cmocka): closeness
 * assertions, a deterministic random generator, rigid motions and test
 * facets. */
#ifndef FFC_TEST_H
#define FFC_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "ffc.h"

/* |a - b| <= tol, with both values in the failure message */
#define assert_close(a, b, tol)                                                \
    do {                                                                       \
        double a_ = (a), b_ = (b), t_ = (tol);                                 \
        if (!(fabs(a_ - b_) <= t_))                                            \
            fail_msg("%s = %.17g, %s = %.17g, |diff| = %.3g > %.3g", #a, a_,   \
                     #b, b_, fabs(a_ - b_), t_);                               \
    } while (0)

/* deterministic uniform numbers in [lo, hi) */
static inline double test_rand(uint64_t *s, double lo, double hi)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * (double)(*s >> 11) / 9007199254740992.0;
}

/* rotation matrix from axis (normalised here) and angle */
static inline void test_rotation(const double ax[3], double ang, double R[3][3])
{
    double l = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    double k[3] = {ax[0] / l, ax[1] / l, ax[2] / l}, c = cos(ang), s = sin(ang);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            R[i][j] = (i == j ? c : 0.0) + (1.0 - c) * k[i] * k[j];
    R[0][1] -= s * k[2]; R[0][2] += s * k[1];
    R[1][0] += s * k[2]; R[1][2] -= s * k[0];
    R[2][0] -= s * k[1]; R[2][1] += s * k[0];
}

/* y = R x + t */
static inline void test_move(const double R[3][3], const double t[3],
                             const double x[3], double y[3])
{
    for (int i = 0; i < 3; i++)
        y[i] = R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2] + t[i];
}

/* reference-element positions of the 6 facet nodes */
static const double test_node_xi[6][2] = {{0, 0}, {1, 0}, {0, 1},
                                          {0.5, 0}, {0.5, 0.5}, {0, 0.5}};

/* A curved 6-node facet whose nodes lie on the sphere of radius R centred
 * at the origin, around the north pole, spanning about `span` radians. */
static inline void test_sphere_facet(double R, double span, double X[6][3])
{
    for (int a = 0; a < 6; a++) {
        double u = span * (test_node_xi[a][0] - 1.0 / 3.0);
        double v = span * (test_node_xi[a][1] - 1.0 / 3.0);
        double d[3] = {u, v, 1.0}, l = sqrt(u * u + v * v + 1.0);
        for (int i = 0; i < 3; i++) X[a][i] = R * d[i] / l;
    }
}

/* One link's geometry, in two halves so that a caller may draw between
 * them.  test_link_master: a master facet Xm (nm = 3: a fixed flat
 * triangle; 6: a sphere facet), perturbed, a master point g inside it and
 * the slave point's local coordinates xs. */
static inline void test_link_master(int nm, uint64_t *s, double Xm[6][3], ffc_point *g, double xs[2])
{
    static const double T3[3][3] = {{0.1, -0.2, 0.3}, {1.3, 0.1, 0.2}, {0.2, 1.1, 0.5}};
    if (nm == 3)
        for (int a = 0; a < 3; a++)
            for (int i = 0; i < 3; i++) Xm[a][i] = T3[a][i];
    else test_sphere_facet(1.0, 0.8, Xm);
    for (int a = 0; a < 6; a++)
        for (int i = 0; i < 3; i++) Xm[a][i] += test_rand(s, -0.03, 0.03);
    const double xm[2] = {test_rand(s, 0.25, 0.4), test_rand(s, 0.25, 0.4)};
    ffc_facet_point(nm, (const double(*)[3])Xm, xm, g);
    xs[0] = test_rand(s, 0.15, 0.45);
    xs[1] = test_rand(s, 0.15, 0.4);
}

/* test_link_slave: a reversed small slave facet Xs whose point xs sits at
 * g.x + offset g.n (perturbed), and its reference positions Xs0. */
static inline void test_link_slave(int ns, const ffc_point *g, const double xs[2], double offset, uint64_t *s,
                                   double Xs[6][3], double Xs0[6][3])
{
    for (int a = 0; a < ns; a++)
        for (int i = 0; i < 3; i++) {
            Xs[a][i] = g->x[i] + offset * g->n[i] + 0.4 * (test_node_xi[a][1] - xs[1]) * g->tau[0][i] +
                       0.4 * (test_node_xi[a][0] - xs[0]) * g->tau[1][i] + test_rand(s, -0.02, 0.02);
            Xs0[a][i] = Xs[a][i] + test_rand(s, -0.05, 0.05);
        }
}

/* A contact pair of 41 nodes: a wavy 5 x 5 master grid (nodes 0..24, 32
 * facets, normals up) and a tilted 4 x 4 slave grid just below z = 0
 * (nodes 25..40, 18 facets, normals down), overlapping the master: part
 * of the slave points penetrate, part are open. */
static inline void test_pair_scene(double X[], long Fm[], long Fs[])
{
    int v = 0;
    for (int j = 0; j <= 4; j++)
        for (int i = 0; i <= 4; i++, v++) {
            double x = i / 4.0 + (i % 4 ? 0.02 * sin(3.0 * j + i) : 0), y = j / 4.0;
            X[3 * v] = x; X[3 * v + 1] = y; X[3 * v + 2] = 0.02 * sin(2 * x + 1) * cos(3 * y);
        }
    for (int j = 0; j <= 3; j++)
        for (int i = 0; i <= 3; i++, v++) {
            double x = 0.1 + 0.8 * i / 3.0, y = 0.1 + 0.8 * j / 3.0;
            X[3 * v] = x; X[3 * v + 1] = y; X[3 * v + 2] = -0.004 + 0.012 * (x - 0.5) + 0.003 * y;
        }
    int f = 0;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            long a = j * 5 + i, b = a + 1, d = a + 5, c = d + 1;
            long t[6] = {a, b, d, b, c, d};
            for (int k = 0; k < 6; k++) Fm[6 * f + k] = t[k];
            f++;
        }
    f = 0;
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            long a = 25 + j * 4 + i, b = a + 1, d = a + 4, c = d + 1;
            long t[6] = {a, d, b, b, d, c};  /* reversed: normals down */
            for (int k = 0; k < 6; k++) Fs[6 * f + k] = t[k];
            f++;
        }
}

/* x = M^-1 b, M row-major n x n, by Gaussian elimination with partial
 * pivoting on a copy (a test's own reference solve) */
static inline void test_dense_solve(int n, const double *M, const double *b, double *x)
{
    double *A = malloc(sizeof(double) * n * n), *c = malloc(sizeof(double) * n);
    if (!A || !c) fail_msg("test_dense_solve: out of memory");
    memcpy(A, M, sizeof(double) * n * n);
    memcpy(c, b, sizeof(double) * n);
    for (int k = 0; k < n; k++) {
        int p = k;
        for (int i = k + 1; i < n; i++)
            if (fabs(A[i * n + k]) > fabs(A[p * n + k])) p = i;
        for (int j = 0; j < n; j++) { const double t = A[k * n + j]; A[k * n + j] = A[p * n + j]; A[p * n + j] = t; }
        const double t = c[k]; c[k] = c[p]; c[p] = t;
        for (int i = k + 1; i < n; i++) {
            const double f = A[i * n + k] / A[k * n + k];
            for (int j = k; j < n; j++) A[i * n + j] -= f * A[k * n + j];
            c[i] -= f * c[k];
        }
    }
    for (int i = n - 1; i >= 0; i--) {
        double v = c[i];
        for (int j = i + 1; j < n; j++) v -= A[i * n + j] * x[j];
        x[i] = v / A[i * n + i];
    }
    free(A);
    free(c);
}

/* the unit square [0,1]^2 at height z: nodes base..base+3 of X */
static inline void test_unit_square(double z, double X[], long base)
{
    const double c[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int a = 0; a < 4; a++) {
        X[3 * (base + a)] = c[a][0];
        X[3 * (base + a) + 1] = c[a][1];
        X[3 * (base + a) + 2] = z;
    }
}

/* A lattice of ln^3 nodes joined by springs along the axes, each a 3 x 3
 * stiffness k (d d' + I / 5) (d the spring's direction), the nodes of the
 * plane z = 0 on Dirichlet rows (diagonal tgv); n = 3 ln^3 dofs.  K's
 * triplets (both triangles, at most 40 ln^3) and, unless Kd is NULL, its
 * dense copy Kd[n * n].  Returns the triplets' count. */
static inline long test_lattice(int ln, double tgv, long Ti[], long Tj[], double Tv[], double *Kd)
{
    const long n = 3L * ln * ln * ln;
    long t = 0;
    for (int z = 0; z < ln; z++)
        for (int y = 0; y < ln; y++)
            for (int x = 0; x < ln; x++)
                for (int d = 0; d < 3; d++) {
                    const int c[3] = {x + (d == 0), y + (d == 1), z + (d == 2)};
                    if (c[d] >= ln) continue;
                    const long a = x + ln * (y + ln * z), e = c[0] + ln * (c[1] + ln * c[2]);
                    const double k = 10.0 + (a % 7);
                    for (int i = 0; i < 3; i++)
                        for (int j = 0; j < 3; j++) {
                            const double v = k * ((i == d && j == d) + (i == j) / 5.0);
                            if (v == 0.0) continue;
                            const long p[4][2] = {{a, a}, {e, e}, {a, e}, {e, a}};
                            const double sg[4] = {v, v, -v, -v};
                            for (int q = 0; q < 4; q++) {
                                Ti[t] = 3 * p[q][0] + i; Tj[t] = 3 * p[q][1] + j; Tv[t] = sg[q]; t++;
                            }
                        }
                }
    for (long i = 0; i < 3L * ln * ln; i++) { Ti[t] = i; Tj[t] = i; Tv[t] = tgv; t++; }
    if (Kd) {
        memset(Kd, 0, sizeof(double) * n * n);
        for (long k = 0; k < t; k++) Kd[Ti[k] * n + Tj[k]] += Tv[k];
    }
    return t;
}

/* The lattice's contact sets of the compliance tests: the rows R = the
 * dofs of its top plane (3 ln^2), C grown in two calls: nd1 = R's first
 * 72 dofs (more than one block of solves), then nd2 = 21 more of R and 9
 * interior dofs outside R (ln >= 6). */
enum { LATTICE_C1 = 72, LATTICE_C2 = 30 };
static inline void test_lattice_sets(int ln, long rows[], long nd1[LATTICE_C1], long nd2[LATTICE_C2])
{
    const long top = 3L * ln * ln * (ln - 1);
    for (long k = 0; k < 3L * ln * ln; k++) rows[k] = top + k;
    for (long k = 0; k < LATTICE_C1; k++) nd1[k] = top + k;
    for (long k = 0; k < LATTICE_C2 - 9; k++) nd2[k] = top + LATTICE_C1 + k;
    for (long k = 0; k < 9; k++) nd2[LATTICE_C2 - 9 + k] = 3L * ln * ln * 2 + 5 * k + 2;
}

/* Two such lattices that nothing couples (two bodies before contact: K
 * block diagonal, L's supernodal forest of two trees), the second's dofs
 * after the first's: n = 6 ln^3.  Triplets (at most 80 ln^3) and, unless
 * Kd is NULL, the dense copy Kd[n * n].  Returns the triplets' count. */
static inline long test_lattice_pair(int ln, double tgv, long Ti[], long Tj[], double Tv[], double *Kd)
{
    const long n1 = 3L * ln * ln * ln, t1 = test_lattice(ln, tgv, Ti, Tj, Tv, NULL);
    const long t2 = test_lattice(ln, tgv, Ti + t1, Tj + t1, Tv + t1, NULL);
    for (long k = t1; k < t1 + t2; k++) { Ti[k] += n1; Tj[k] += n1; }
    if (Kd) {
        memset(Kd, 0, sizeof(double) * 4 * n1 * n1);
        for (long k = 0; k < t1 + t2; k++) Kd[Ti[k] * 2 * n1 + Tj[k]] += Tv[k];
    }
    return t1 + t2;
}

/* Their contact sets: R = both top planes (6 ln^2 rows); nd1 = 72 dofs of
 * the top planes, the bodies' alternating (a block of solves holds both
 * trees); nd2 = the second body's nd2 of test_lattice_sets (some interior
 * dofs).  6 <= ln <= 16. */
static inline void test_lattice_pair_sets(int ln, long rows[], long nd1[LATTICE_C1], long nd2[LATTICE_C2])
{
    const long n1 = 3L * ln * ln * ln, nr = 3L * ln * ln;
    long r1[3 * 16 * 16], a1[LATTICE_C1];
    test_lattice_sets(ln, r1, a1, nd2);
    for (long k = 0; k < nr; k++) { rows[k] = r1[k]; rows[nr + k] = r1[k] + n1; }
    for (long k = 0; k < LATTICE_C1; k++) nd1[k] = a1[k / 2] + (k % 2 ? n1 : 0);
    for (long k = 0; k < LATTICE_C2; k++) nd2[k] += n1;
}

/* Central differences of one link's residual against its tangent K[nd][nd]:
 * coordinate l is *x[l] (and *m[l] moves with it when m is not NULL: a
 * friction motion x - x^n), moved by +-h; eval(ctx, st, R) evaluates the
 * residual; the states at +-h must keep st0's contact and friction state.
 * *err the largest |FD - K|, *scale the largest |K|. */
typedef int (*test_link_eval)(void *ctx, ffc_link_state *st, double R[FFC_MAXDOF]);
static inline void test_link_fd(int nd, double *x[], double *m[], double h, test_link_eval eval, void *ctx,
                                const ffc_link_state *st0, double K[FFC_MAXDOF][FFC_MAXDOF], double *err, double *scale)
{
    *err = 0;
    *scale = 0;
    for (int l = 0; l < nd; l++) {
        double x0 = *x[l], m0 = m ? *m[l] : 0.0, Rp[FFC_MAXDOF], Rm[FFC_MAXDOF];
        ffc_link_state sp, sm;
        *x[l] = x0 + h; if (m) *m[l] = m0 + h;
        assert_int_equal(eval(ctx, &sp, Rp), FFC_OK);
        *x[l] = x0 - h; if (m) *m[l] = m0 - h;
        assert_int_equal(eval(ctx, &sm, Rm), FFC_OK);
        *x[l] = x0; if (m) *m[l] = m0;
        assert_int_equal(sp.active, st0->active);
        assert_int_equal(sm.active, st0->active);
        assert_int_equal(sp.fstate, st0->fstate);
        assert_int_equal(sm.fstate, st0->fstate);
        for (int k = 0; k < nd; k++) {
            *err = fmax(*err, fabs((Rp[k] - Rm[k]) / (2 * h) - K[k][l]));
            *scale = fmax(*scale, fabs(K[k][l]));
        }
    }
}

#endif
