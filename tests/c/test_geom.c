/* test_geom.c: shape functions, facet geometry and Gauss rules. */
#include "ffc_test.h"

static double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

static void test_partition_of_unity(void **state)
{
    (void)state;
    uint64_t s = 1;
    for (int nn = 3; nn <= 6; nn += 3)
        for (int k = 0; k < 50; k++) {
            double xi[2] = {test_rand(&s, -0.5, 1.5), test_rand(&s, -0.5, 1.5)};
            double N[6], dN[6][2], sum = 0, d0 = 0, d1 = 0;
            assert_int_equal(ffc_shape(nn, xi, N, dN), FFC_OK);
            for (int a = 0; a < nn; a++) { sum += N[a]; d0 += dN[a][0]; d1 += dN[a][1]; }
            assert_close(sum, 1.0, 1e-14);
            assert_close(d0, 0.0, 1e-13);
            assert_close(d1, 0.0, 1e-13);
        }
}

static void test_nodal_delta(void **state)
{
    (void)state;
    for (int nn = 3; nn <= 6; nn += 3)
        for (int b = 0; b < nn; b++) {
            double N[6];
            assert_int_equal(ffc_shape(nn, test_node_xi[b], N, NULL), FFC_OK);
            for (int a = 0; a < nn; a++) assert_close(N[a], a == b ? 1.0 : 0.0, 1e-15);
        }
}

/* 3 nodes reproduce linear fields, 6 nodes quadratic ones */
static void test_interpolation(void **state)
{
    (void)state;
    uint64_t s = 7;
    for (int nn = 3; nn <= 6; nn += 3)
        for (int k = 0; k < 30; k++) {
            double c[6];
            for (int i = 0; i < 6; i++) c[i] = test_rand(&s, -1, 1);
            if (nn == 3) c[3] = c[4] = c[5] = 0.0;
#define FIELD(x, y) (c[0] + c[1] * (x) + c[2] * (y) + c[3] * (x) * (x) + c[4] * (x) * (y) + c[5] * (y) * (y))
            double xi[2] = {test_rand(&s, 0, 1), test_rand(&s, 0, 1)};
            double N[6], f = 0;
            ffc_shape(nn, xi, N, NULL);
            for (int a = 0; a < nn; a++) f += N[a] * FIELD(test_node_xi[a][0], test_node_xi[a][1]);
            assert_close(f, FIELD(xi[0], xi[1]), 1e-13);
#undef FIELD
        }
}

/* first and second derivatives against central differences; the shapes are
 * at most quadratic, so central differences are exact up to round-off
 * (eps/h ~ 1e-10 with h = 1e-6) */
static void test_shape_derivatives(void **state)
{
    (void)state;
    const double h = 1e-6;
    double xi[2] = {0.21, 0.33};
    for (int nn = 3; nn <= 6; nn += 3) {
        double N[6], dN[6][2], d2N[6][3];
        ffc_shape(nn, xi, N, dN);
        assert_int_equal(ffc_shape_d2(nn, xi, d2N), FFC_OK);
        for (int b = 0; b < 2; b++) {
            double xp[2] = {xi[0], xi[1]}, xm[2] = {xi[0], xi[1]};
            xp[b] += h; xm[b] -= h;
            double Np[6], Nm[6], dNp[6][2], dNm[6][2];
            ffc_shape(nn, xp, Np, dNp);
            ffc_shape(nn, xm, Nm, dNm);
            for (int a = 0; a < nn; a++) {
                assert_close(dN[a][b], (Np[a] - Nm[a]) / (2 * h), 1e-8);
                /* d2N columns: 11, 12, 22 */
                assert_close(d2N[a][b], (dNp[a][0] - dNm[a][0]) / (2 * h), 1e-8);
                assert_close(d2N[a][b + 1], (dNp[a][1] - dNm[a][1]) / (2 * h), 1e-8);
            }
        }
    }
    double N[6];
    assert_int_equal(ffc_shape(4, xi, N, NULL), FFC_ERR_NODES);
}

/* each rule integrates every monomial xi1^i xi2^j, i + j <= degree,
 * exactly: int_T xi1^i xi2^j = i! j! / (i + j + 2)! */
static void test_quadrature_exactness(void **state)
{
    (void)state;
    static const int npts[7] = {0, 1, 3, 6, 6, 7, 12};
    for (int deg = 1; deg <= 6; deg++) {
        double xi[16][2], w[16];
        int n = ffc_quad(deg, 16, xi, w);
        assert_int_equal(n, npts[deg]);
        assert_int_equal(ffc_quad_size(deg), npts[deg]);
        for (int q = 0; q < n; q++) {
            assert_true(w[q] > 0.0);
            assert_true(xi[q][0] > 0.0 && xi[q][1] > 0.0 && xi[q][0] + xi[q][1] < 1.0);
        }
        for (int i = 0; i <= deg; i++)
            for (int j = 0; i + j <= deg; j++) {
                double sum = 0.0;
                for (int q = 0; q < n; q++) sum += w[q] * pow(xi[q][0], i) * pow(xi[q][1], j);
                double exact = factorial(i) * factorial(j) / factorial(i + j + 2);
                assert_close(sum, exact, 1e-15);
            }
    }
    double xi[16][2], w[16];
    assert_int_equal(ffc_quad(0, 16, xi, w), FFC_ERR_QUAD);
    assert_int_equal(ffc_quad(7, 16, xi, w), FFC_ERR_QUAD);
    assert_int_equal(ffc_quad(6, 11, xi, w), FFC_ERR_CAPACITY);
}

/* tangents, normal, metric and area element of a flat and a curved facet */
static void test_facet_point(void **state)
{
    (void)state;
    const double X[3][3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
    ffc_point p;
    const double xi[2] = {0.2, 0.3};
    assert_int_equal(ffc_facet_point(3, X, xi, &p), FFC_OK);
    assert_close(p.x[0], 0.4, 1e-15);
    assert_close(p.x[1], 0.9, 1e-15);
    assert_close(p.j, 6.0, 1e-14); /* twice the area 3 */
    assert_close(p.n[2], 1.0, 1e-15);
    assert_close(p.m[0][0], 4.0, 1e-15);
    assert_close(p.m[1][1], 9.0, 1e-15);
    assert_close(p.m[0][1], 0.0, 1e-15);
    assert_close(p.minv[0][0] * p.m[0][0], 1.0, 1e-15);

    double S[6][3];
    test_sphere_facet(2.0, 0.4, S);
    assert_int_equal(ffc_facet_point(6, (const double(*)[3])S, xi, &p), FFC_OK);
    /* normal: unit, orthogonal to both tangents, outward on the sphere cap */
    assert_close(p.n[0] * p.n[0] + p.n[1] * p.n[1] + p.n[2] * p.n[2], 1.0, 1e-14);
    for (int a = 0; a < 2; a++)
        assert_close(p.n[0] * p.tau[a][0] + p.n[1] * p.tau[a][1] + p.n[2] * p.tau[a][2], 0.0, 1e-14);
    double r = sqrt(p.x[0] * p.x[0] + p.x[1] * p.x[1] + p.x[2] * p.x[2]);
    assert_true((p.n[0] * p.x[0] + p.n[1] * p.x[1] + p.n[2] * p.x[2]) / r > 0.999);
    /* inverse metric */
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            assert_close(p.m[a][0] * p.minv[0][b] + p.m[a][1] * p.minv[1][b], a == b, 1e-12);

    const double D[3][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    assert_int_equal(ffc_facet_point(3, D, xi, &p), FFC_ERR_DEGENERATE);
    const double Nn[3][3] = {{0, 0, 0}, {1, NAN, 0}, {0, 1, 0}};
    assert_int_equal(ffc_facet_point(3, Nn, xi, &p), FFC_ERR_NONFINITE);
}

static void test_strerror(void **state)
{
    (void)state;
    for (int s = -18; s <= 2; s++) {
        const char *m = ffc_strerror(s);
        assert_non_null(m);
        assert_string_not_equal(m, "unknown status");
    }
    assert_string_equal(ffc_strerror(-99), "unknown status");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_partition_of_unity),
        cmocka_unit_test(test_nodal_delta),
        cmocka_unit_test(test_interpolation),
        cmocka_unit_test(test_shape_derivatives),
        cmocka_unit_test(test_quadrature_exactness),
        cmocka_unit_test(test_facet_point),
        cmocka_unit_test(test_strerror),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
