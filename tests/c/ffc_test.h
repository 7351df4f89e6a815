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

#endif
