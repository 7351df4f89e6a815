/* test_elastic.c: the linear-elastic stiffness of linear and quadratic
 * tetrahedra (ffc_elastic_p1, ffc_elastic_p2) against the continuum: for
 * linear fields u = A x + c and w = B x + d (every P1 field of one
 * tetrahedron is one), U' K W = V (lambda tr A tr B + 2 mu eps(A) :
 * eps(B)); for quadratic fields (every P2 field of one tetrahedron is one)
 * the integral of products of linear gradients by the exact formula for
 * products of linear functions; rigid motions in the null space; the
 * pattern, its order and count; capacity and bad input. */
#include "ffc_test.h"

/* U[3 nv] of the field A x + c at the vertices X[3 nv] */
static void linear_field(long nv, const double X[], const double A[3][3], const double c[3], double U[])
{
    for (long i = 0; i < nv; i++)
        for (int r = 0; r < 3; r++)
            U[3 * i + r] = c[r] + A[r][0] * X[3 * i] + A[r][1] * X[3 * i + 1] + A[r][2] * X[3 * i + 2];
}

/* V (lambda tr A tr B + 2 mu sym(A) : sym(B)) */
static double continuum(double V, double lam, double mu, const double A[3][3], const double B[3][3])
{
    double e = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) e += 0.25 * (A[i][j] + A[j][i]) * (B[i][j] + B[j][i]);
    return V * (lam * (A[0][0] + A[1][1] + A[2][2]) * (B[0][0] + B[1][1] + B[2][2]) + 2 * mu * e);
}

static double tet_volume(const double X[], const long T[4])
{
    double a[3], b[3], c[3];
    for (int r = 0; r < 3; r++) {
        a[r] = X[3 * T[1] + r] - X[3 * T[0] + r];
        b[r] = X[3 * T[2] + r] - X[3 * T[0] + r];
        c[r] = X[3 * T[3] + r] - X[3 * T[0] + r];
    }
    return fabs(a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
}

/* U' K W from the entries */
static double form(long nnz, const long Ki[], const long Kj[], const double Kv[], const double U[], const double W[])
{
    double s = 0;
    for (long e = 0; e < nnz; e++) s += U[Ki[e]] * Kv[e] * W[Kj[e]];
    return s;
}

/* two tetrahedra sharing the face 1 2 3, apexes 0 and 4, one of them
 * numbered with negative orientation; random perturbations of a
 * regular shape */
static void two_tets(uint64_t *s, double X[15], long T[8])
{
    const double X0[15] = {0, 0, -1, 1, 0, 0, 0, 1, 0, -1, -1, 0.2, 0.1, 0.2, 1};
    for (int k = 0; k < 15; k++) X[k] = X0[k] + test_rand(s, -0.1, 0.1);
    const long T0[8] = {0, 1, 2, 3, 4, 2, 1, 3};
    memcpy(T, T0, sizeof T0);
}

static void test_elastic_linear_fields(void **state)
{
    (void)state;
    uint64_t s = 7;
    double X[15];
    long T[8];
    two_tets(&s, X, T);
    const double lam[2] = {2.5, 0.7}, mu[2] = {1.5, 3.0};
    enum { CAP = 9 * 25 };
    long Ki[CAP], Kj[CAP], nnz = -1, bad = 0;
    double Kv[CAP];
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, CAP, Ki, Kj, Kv, &nnz, &bad), FFC_OK);
    /* pattern: 5 vertices with themselves, 9 edges both ways; apexes 0, 4 not coupled */
    assert_int_equal(nnz, 9 * (5 + 2 * 9));
    for (long e = 1; e < nnz; e++) assert_true(Ki[e - 1] < Ki[e] || (Ki[e - 1] == Ki[e] && Kj[e - 1] < Kj[e]));
    for (long e = 0; e < nnz; e++) assert_false((Ki[e] / 3 == 0 && Kj[e] / 3 == 4) || (Ki[e] / 3 == 4 && Kj[e] / 3 == 0));
    /* symmetric: entry (i, j) equals (j, i) */
    for (long e = 0; e < nnz; e++) {
        long f = 0;
        while (f < nnz && !(Ki[f] == Kj[e] && Kj[f] == Ki[e])) f++;
        assert_true(f < nnz);
        assert_close(Kv[f], Kv[e], 1e-13 * fabs(Kv[e]) + 1e-300);
    }
    /* each tetrahedron alone against the continuum, and the two together,
     * for random linear fields (12 dimensions per tetrahedron: all of them) */
    const double V[2] = {tet_volume(X, T), tet_volume(X, T + 4)};
    for (int trial = 0; trial < 20; trial++) {
        double A[3][3], B[3][3], a[3], b[3], U[15], W[15];
        for (int i = 0; i < 3; i++) {
            a[i] = test_rand(&s, -1, 1);
            b[i] = test_rand(&s, -1, 1);
            for (int j = 0; j < 3; j++) {
                A[i][j] = test_rand(&s, -1, 1);
                B[i][j] = test_rand(&s, -1, 1);
            }
        }
        linear_field(5, X, A, a, U);
        linear_field(5, X, B, b, W);
        const double want = continuum(V[0], lam[0], mu[0], A, B) + continuum(V[1], lam[1], mu[1], A, B);
        /* (relative to the size of the terms: round-off of sums of order |K| |U| |W|) */
        assert_close(form(nnz, Ki, Kj, Kv, U, W), want, 1e-12 * (1 + fabs(want)) * 20);
        for (int t = 0; t < 2; t++) {
            long Ki1[9 * 17], Kj1[9 * 17], n1 = 0;   /* (4 x 4 blocks, and the fifth vertex's own) */
            double Kv1[9 * 17];
            assert_int_equal(ffc_elastic_p1(5, X, 1, T + 4 * t, lam + t, mu + t, 9 * 17, Ki1, Kj1, Kv1, &n1, &bad), FFC_OK);
            assert_int_equal(n1, 9 * 17);
            const double w1 = continuum(V[t], lam[t], mu[t], A, B);
            assert_close(form(n1, Ki1, Kj1, Kv1, U, W), w1, 1e-12 * (1 + fabs(w1)) * 20);
        }
    }
    /* rigid motions: K U = 0 (a translation and an infinitesimal rotation) */
    const double R[3][3] = {{0, -0.3, 0.2}, {0.3, 0, -0.5}, {-0.2, 0.5, 0}}, c[3] = {0.4, -1.0, 2.0};
    double U[15], KU[15] = {0}, kmax = 0;
    linear_field(5, X, R, c, U);
    for (long e = 0; e < nnz; e++) {
        KU[Ki[e]] += Kv[e] * U[Kj[e]];
        kmax = fmax(kmax, fabs(Kv[e]));
    }
    for (int i = 0; i < 15; i++) assert_close(KU[i], 0.0, 1e-13 * kmax * 10);
}

static void test_elastic_capacity_and_errors(void **state)
{
    (void)state;
    uint64_t s = 11;
    double X[15];
    long T[8];
    two_tets(&s, X, T);
    double lam[2] = {1, 1}, mu[2] = {1, 1}, Kv[9 * 23];
    long Ki[9 * 23], Kj[9 * 23], nnz = -1, bad = -7;
    /* the count asked first, then too small by one */
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, 0, NULL, NULL, NULL, &nnz, &bad), FFC_ERR_CAPACITY);
    assert_int_equal(nnz, 9 * 23);
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, 9 * 23 - 1, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_CAPACITY);
    assert_int_equal(nnz, 9 * 23);
    /* bad input */
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, 9 * 23, Ki, Kj, Kv, NULL, &bad), FFC_ERR_NULL);
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, NULL, mu, 9 * 23, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_NULL);
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, -1, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_SIZE);
    assert_int_equal(ffc_elastic_p1(-1, X, 2, T, lam, mu, 9 * 23, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_SIZE);
    T[6] = 5;
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, 9 * 23, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_INDEX);
    assert_int_equal(bad, 1);
    T[6] = 1;
    lam[1] = NAN;
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, 9 * 23, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_NONFINITE);
    assert_int_equal(bad, 1);
    lam[1] = 1;
    X[3 * 3 + 1] = INFINITY;
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, 9 * 23, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_NONFINITE);
    assert_int_equal(bad, 3);
    /* a flat tetrahedron: the apex 4 moved into the plane of 1 2 3 */
    two_tets(&s, X, T);
    for (int r = 0; r < 3; r++) X[12 + r] = (X[3 + r] + X[6 + r] + X[9 + r]) / 3;
    assert_int_equal(ffc_elastic_p1(5, X, 2, T, lam, mu, 9 * 23, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_DEGENERATE);
    assert_int_equal(bad, 1);
    /* no tetrahedra: the vertices alone, each block zero */
    assert_int_equal(ffc_elastic_p1(5, X, 0, T, lam, mu, 9 * 23, Ki, Kj, Kv, &nnz, &bad), FFC_OK);
    assert_int_equal(nnz, 9 * 5);
    for (long e = 0; e < nnz; e++) assert_true(Kv[e] == 0.0);
}

/* a quadratic field u_r = c_r + A_rj x_j + Q_rjk x_j x_k at x */
static void quad_field(const double c[3], const double A[3][3], const double Q[3][3][3], const double x[3], double u[3],
                       double grad[3][3])
{
    for (int r = 0; r < 3; r++) {
        u[r] = c[r];
        for (int j = 0; j < 3; j++) {
            u[r] += A[r][j] * x[j];
            grad[r][j] = A[r][j];
            for (int k = 0; k < 3; k++) {
                u[r] += Q[r][j][k] * x[j] * x[k];
                grad[r][j] += (Q[r][j][k] + Q[r][k][j]) * x[k];
            }
        }
    }
}

static void random_quad(uint64_t *s, double c[3], double A[3][3], double Q[3][3][3])
{
    for (int r = 0; r < 3; r++) {
        c[r] = test_rand(s, -1, 1);
        for (int j = 0; j < 3; j++) {
            A[r][j] = test_rand(s, -1, 1);
            for (int k = 0; k < 3; k++) Q[r][j][k] = test_rand(s, -1, 1);
        }
    }
}

static void test_elastic_p2_quadratic_fields(void **state)
{
    (void)state;
    uint64_t s = 23;
    double X[15];
    long T[8];
    two_tets(&s, X, T);
    long node[20], nn = 0, bad = 0;
    assert_int_equal(ffc_p2_number(2, T, 5, node, &nn), FFC_OK);
    assert_int_equal(nn, 5 + 9);
    double X2[3 * 14];
    assert_int_equal(ffc_p2_positions(2, T, node, X, nn, X2), FFC_OK);
    const double lam[2] = {2.5, 0.7}, mu[2] = {1.5, 3.0};
    /* the pattern: the 10 nodes of each tetrahedron with one another, the
     * face's 6 shared: 2 x 100 - 36 blocks */
    long nnz = -1;
    assert_int_equal(ffc_elastic_p2(5, X, 2, T, nn, node, lam, mu, 0, NULL, NULL, NULL, &nnz, &bad), FFC_ERR_CAPACITY);
    assert_int_equal(nnz, 9 * (2 * 100 - 36));
    long *Ki = malloc(nnz * sizeof(long)), *Kj = malloc(nnz * sizeof(long));
    double *Kv = malloc(nnz * sizeof(double));
    assert_int_equal(ffc_elastic_p2(5, X, 2, T, nn, node, lam, mu, nnz, Ki, Kj, Kv, &nnz, &bad), FFC_OK);
    for (long e = 1; e < nnz; e++) assert_true(Ki[e - 1] < Ki[e] || (Ki[e - 1] == Ki[e] && Kj[e - 1] < Kj[e]));
    for (int trial = 0; trial < 10; trial++) {
        double c[3], A[3][3], Q[3][3][3], d[3], B[3][3], R[3][3][3], U[42], W[42], gu[3][3], gw[3][3];
        random_quad(&s, c, A, Q);
        random_quad(&s, d, B, R);
        for (long i = 0; i < nn; i++) {
            quad_field(c, A, Q, X2 + 3 * i, U + 3 * i, gu);
            quad_field(d, B, R, X2 + 3 * i, W + 3 * i, gw);
        }
        /* per tetrahedron: the integrand lambda div u div w + 2 mu eps(u) :
         * eps(w) is a sum of products f g of linear functions, whose
         * integral is V / 20 (sum_a f_a g_a + sum_a f_a sum_a g_a) over
         * the vertex values */
        double want = 0;
        for (int t = 0; t < 2; t++) {
            double du[4], dw[4], eu[4][3][3], ew[4][3][3];
            for (int a = 0; a < 4; a++) {
                double uu[3], ww[3];
                quad_field(c, A, Q, X + 3 * T[4 * t + a], uu, gu);
                quad_field(d, B, R, X + 3 * T[4 * t + a], ww, gw);
                du[a] = gu[0][0] + gu[1][1] + gu[2][2];
                dw[a] = gw[0][0] + gw[1][1] + gw[2][2];
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) {
                        eu[a][i][j] = 0.5 * (gu[i][j] + gu[j][i]);
                        ew[a][i][j] = 0.5 * (gw[i][j] + gw[j][i]);
                    }
            }
            const double V = tet_volume(X, T + 4 * t);
            double sdd = 0, sd1 = 0, sd2 = 0;
            for (int a = 0; a < 4; a++) { sdd += du[a] * dw[a]; sd1 += du[a]; sd2 += dw[a]; }
            want += lam[t] * V / 20 * (sdd + sd1 * sd2);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    double see = 0, s1 = 0, s2 = 0;
                    for (int a = 0; a < 4; a++) { see += eu[a][i][j] * ew[a][i][j]; s1 += eu[a][i][j]; s2 += ew[a][i][j]; }
                    want += 2 * mu[t] * V / 20 * (see + s1 * s2);
                }
        }
        assert_close(form(nnz, Ki, Kj, Kv, U, W), want, 1e-12 * (1 + fabs(want)) * 50);
    }
    /* a rigid rotation: K U = 0 */
    double c[3] = {0.4, -1.0, 2.0}, Rr[3][3] = {{0, -0.3, 0.2}, {0.3, 0, -0.5}, {-0.2, 0.5, 0}}, Q0[3][3][3] = {{{0}}};
    double U[42], KU[42] = {0}, g0[3][3], kmax = 0;
    for (long i = 0; i < nn; i++) quad_field(c, Rr, Q0, X2 + 3 * i, U + 3 * i, g0);
    for (long e = 0; e < nnz; e++) {
        KU[Ki[e]] += Kv[e] * U[Kj[e]];
        kmax = fmax(kmax, fabs(Kv[e]));
    }
    for (int i = 0; i < 42; i++) assert_close(KU[i], 0.0, 1e-13 * kmax * 30);
    /* a node outside [0, nn) */
    node[13] = nn;
    assert_int_equal(ffc_elastic_p2(5, X, 2, T, nn, node, lam, mu, nnz, Ki, Kj, Kv, &nnz, &bad), FFC_ERR_INDEX);
    assert_int_equal(bad, 1);
    free(Ki); free(Kj); free(Kv);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_elastic_linear_fields),
        cmocka_unit_test(test_elastic_capacity_and_errors),
        cmocka_unit_test(test_elastic_p2_quadratic_fields),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
