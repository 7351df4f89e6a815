/* test_surface.c: selection by label, outward orientation, validation and
 * area of boundary surfaces given as plain arrays; the tetrahedra's shape
 * quality. */
#include "ffc_test.h"

/* one tetrahedron, faces given with mixed orientation, labels 1..4 */
static const double TX[4 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const long TBE[4 * 3] = {1, 2, 3, 0, 2, 3, 0, 3, 1, 0, 1, 2};
static const long TOPP[4] = {0, 1, 2, 3};
static const long TLAB[4] = {1, 2, 2, 4};

static void test_select_orients_outward(void **state)
{
    (void)state;
    const long labs[3] = {1, 2, 4};
    long F[12], bad;
    int nf = ffc_surface_select(3, 4, TBE, TLAB, TOPP, 4, TX, 3, labs, 4, F, &bad);
    assert_int_equal(nf, 4);
    /* closed surface: sum of n dA vanishes; (1/3) int x.n dA = volume 1/6 */
    double vec[3] = {0, 0, 0}, vol = 0;
    for (int f = 0; f < nf; f++) {
        double P[3][3];
        for (int a = 0; a < 3; a++)
            for (int i = 0; i < 3; i++) P[a][i] = TX[3 * F[3 * f + a] + i];
        ffc_point g;
        const double c[2] = {1.0 / 3, 1.0 / 3};
        assert_int_equal(ffc_facet_point(3, (const double(*)[3])P, c, &g), FFC_OK);
        for (int i = 0; i < 3; i++) vec[i] += 0.5 * g.j * g.n[i];
        vol += 0.5 * g.j * (g.x[0] * g.n[0] + g.x[1] * g.n[1] + g.x[2] * g.n[2]) / 3.0;
    }
    for (int i = 0; i < 3; i++) assert_close(vec[i], 0.0, 1e-15);
    assert_close(vol, 1.0 / 6.0, 1e-15);
}

static void test_select_by_label(void **state)
{
    (void)state;
    const long two[1] = {2};
    long F[12], bad;
    assert_int_equal(ffc_surface_select(3, 4, TBE, TLAB, TOPP, 4, TX, 1, two, 4, F, &bad), 2);
    /* a missing label is reported with its value */
    const long miss[2] = {2, 7};
    assert_int_equal(ffc_surface_select(3, 4, TBE, TLAB, TOPP, 4, TX, 2, miss, 4, F, &bad), FFC_ERR_LABEL);
    assert_int_equal(bad, 7);
    /* too small a buffer reports the size needed */
    const long all[3] = {1, 2, 4};
    assert_int_equal(ffc_surface_select(3, 4, TBE, TLAB, TOPP, 4, TX, 3, all, 2, F, &bad), FFC_ERR_CAPACITY);
    assert_int_equal(bad, 4);
    assert_int_equal(ffc_surface_select(3, 4, TBE, TLAB, TOPP, 4, TX, 0, all, 4, F, &bad), FFC_ERR_EMPTY);
    long out[4];
    assert_int_equal(ffc_labels_present(4, TLAB, 4, out), 3);
    assert_int_equal(out[0], 1);
    assert_int_equal(out[1], 2);
    assert_int_equal(out[2], 4);
}

static void test_check_errors(void **state)
{
    (void)state;
    long bad;
    const long F[6] = {1, 2, 3, 0, 2, 1};
    assert_int_equal(ffc_surface_check(3, 2, F, 4, TX, NULL, &bad), FFC_OK);
    double u[12] = {0};
    u[3 * 2 + 1] = NAN;
    assert_int_equal(ffc_surface_check(3, 2, F, 4, TX, u, &bad), FFC_ERR_NONFINITE);
    assert_int_equal(bad, 2);
    /* move vertex 3 onto vertex 2: facet 0 collapses */
    double v[12] = {0};
    v[9] = 0; v[10] = 1; v[11] = -1;
    assert_int_equal(ffc_surface_check(3, 2, F, 4, TX, v, &bad), FFC_ERR_DEGENERATE);
    assert_int_equal(bad, 0);
    /* the tetrahedron: fine, rotated by 180 degrees (fine), reflected
     * x -> -x (inside out), flattened (collapsed) */
    const long T[4] = {0, 1, 2, 3};
    double w[12] = {0};
    assert_int_equal(ffc_volume_check(1, T, 4, TX, w, &bad), FFC_OK);
    for (int v = 0; v < 4; v++) { w[3 * v] = -2 * TX[3 * v]; w[3 * v + 1] = -2 * TX[3 * v + 1]; }
    assert_int_equal(ffc_volume_check(1, T, 4, TX, w, &bad), FFC_OK);
    for (int v = 0; v < 4; v++) { w[3 * v] = -2 * TX[3 * v]; w[3 * v + 1] = 0; }
    assert_int_equal(ffc_volume_check(1, T, 4, TX, w, &bad), FFC_ERR_INVERTED);
    assert_int_equal(bad, 0);
    w[0] = w[3] = 0;
    w[11] = -1; /* vertex 3 onto the plane z = 0 */
    assert_int_equal(ffc_volume_check(1, T, 4, TX, w, &bad), FFC_ERR_INVERTED);
    const long G[3] = {0, 1, 9};
    assert_int_equal(ffc_surface_check(3, 1, G, 4, TX, NULL, &bad), FFC_ERR_INDEX);
    assert_int_equal(bad, 0);
    assert_int_equal(ffc_surface_check(3, 0, G, 4, TX, NULL, &bad), FFC_ERR_EMPTY);
    assert_int_equal(ffc_surface_check(5, 1, G, 4, TX, NULL, &bad), FFC_ERR_NODES);
}

/* The scene's inversion check (reference volumes kept from its creation)
 * against ffc_volume_check, on the tetrahedron in both orientations:
 * unmoved, rotated by 180 degrees, reflected, one corner moved through
 * the opposite face. */
static void test_scene_volume(void **state)
{
    (void)state;
    const long T[8] = {0, 1, 2, 3, 0, 2, 1, 3};
    const ffc_effects fx = {0, 0, 0};
    ffc_scene *s = NULL;
    assert_int_equal(ffc_scene_create(3, 4, TX, 2, T, &fx, &s), FFC_OK);
    double w[4][12] = {{0}};
    for (int v = 0; v < 4; v++) {
        w[1][3 * v] = w[2][3 * v] = -2 * TX[3 * v];
        w[1][3 * v + 1] = -2 * TX[3 * v + 1];
    }
    w[3][11] = -2.0;
    const int expect[4] = {FFC_OK, FFC_OK, FFC_ERR_INVERTED, FFC_ERR_INVERTED};
    for (int k = 0; k < 4; k++) {
        long b1 = -2, b2 = -3;
        assert_int_equal(ffc_volume_check(2, T, 4, TX, w[k], &b1), expect[k]);
        assert_int_equal(ffc_scene_check_volume(s, w[k], &b2), expect[k]);
        assert_int_equal(b1, b2);
    }
    ffc_scene_free(s);
}

/* area of the tetrahedron's faces: 3 * 1/2 + sqrt(3)/2; and of a curved
 * 6-node facet on a sphere against a fine flat triangulation of it */
static void test_area(void **state)
{
    (void)state;
    const long F[12] = {1, 2, 3, 0, 2, 3, 0, 3, 1, 0, 1, 2};
    double A;
    assert_int_equal(ffc_surface_area(3, 4, F, 4, TX, NULL, 1, &A), FFC_OK);
    assert_close(A, 1.5 + sqrt(3.0) / 2.0, 1e-14);
    /* a displacement that doubles every coordinate multiplies areas by 4 */
    double u[12];
    for (int i = 0; i < 12; i++) u[i] = TX[i];
    assert_int_equal(ffc_surface_area(3, 4, F, 4, TX, u, 1, &A), FFC_OK);
    assert_close(A, 4 * (1.5 + sqrt(3.0) / 2.0), 1e-13);
    assert_int_equal(ffc_surface_area(3, 4, F, 4, TX, NULL, 9, &A), FFC_ERR_QUAD);

    /* the quadratic facet's area from the degree-6 rule against a
     * 200 x 200 subdivision into flat triangles (second-order accurate:
     * relative error ~1e-5 for this smooth patch) */
    double S[6][3];
    test_sphere_facet(1.0, 0.8, S);
    double X[18];
    const long Q[6] = {0, 1, 2, 3, 4, 5};
    for (int a = 0; a < 6; a++)
        for (int i = 0; i < 3; i++) X[3 * a + i] = S[a][i];
    assert_int_equal(ffc_surface_area(6, 1, Q, 6, X, NULL, 6, &A), FFC_OK);
    const int M = 200;
    double ref = 0;
    for (int i = 0; i < M; i++)
        for (int j = 0; i + j < M; j++)
            for (int up = 0; up < 2; up++) {
                if (up && i + j + 1 >= M) continue;
                double c[3][2] = {{i, j}, {i + 1, j}, {i, j + 1}};
                if (up) { c[0][0] = i + 1; c[0][1] = j + 1; }
                double P[3][3];
                for (int k = 0; k < 3; k++) {
                    ffc_point g;
                    double xi[2] = {c[k][0] / M, c[k][1] / M};
                    ffc_facet_point(6, (const double(*)[3])S, xi, &g);
                    for (int d = 0; d < 3; d++) P[k][d] = g.x[d];
                }
                double e1[3], e2[3], n[3];
                for (int d = 0; d < 3; d++) { e1[d] = P[1][d] - P[0][d]; e2[d] = P[2][d] - P[0][d]; }
                n[0] = e1[1] * e2[2] - e1[2] * e2[1];
                n[1] = e1[2] * e2[0] - e1[0] * e2[2];
                n[2] = e1[0] * e2[1] - e1[1] * e2[0];
                ref += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            }
    assert_close(A, ref, 1e-4 * ref);
}

/* ffc_mesh_quality against hand values of the mean ratio 12 (3|V|)^(2/3)
 * / sum l^2: the regular tetrahedron 1; the corner one (0, e_x, e_y, e_z:
 * 3V = 1/2, sum l^2 = 3 + 6) (4/3) 2^(-2/3); the unit square's corners
 * with the fourth lifted by e = 1e-3 (3V = e / 2, sum l^2 = 8 + 3 e^2).
 * The same values scaled by 7, turned (axes permuted) and moved; the
 * lowest and its tetrahedron, the count below a bound; bad input (a NaN
 * or infinite coordinate refused, not read as a flat tetrahedron).
 * Tolerance 1e-14: a few roundings of numbers of order one. */
static void test_mesh_quality(void **state)
{
    (void)state;
    const double e = 1e-3;
    const double X[12 * 3] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1,   /* regular */
                              0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, e,     /* sliver */
                              0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};    /* corner */
    const long T[3 * 4] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    const double qs = 12.0 * cbrt(e * e / 4.0) / (8.0 + 3.0 * e * e), qc = 4.0 / 3.0 * pow(2.0, -2.0 / 3.0);
    const double want[3] = {1.0, qs, qc};
    double w;
    long wt, below;
    for (int k = 0; k < 3; k++) {
        assert_int_equal(ffc_mesh_quality(1, T + 4 * k, 12, X, 0.5, &w, &wt, &below), FFC_OK);
        assert_close(w, want[k], 1e-14);
        assert_int_equal(wt, 0);
        assert_int_equal(below, want[k] < 0.5);
        double Y[12 * 3];   /* 7 (y, z, x) + (3, -2, 5) */
        for (int v = 0; v < 12; v++)
            for (int i = 0; i < 3; i++) Y[3 * v + i] = 7.0 * X[3 * v + (i + 1) % 3] + (i == 0 ? 3.0 : i == 1 ? -2.0 : 5.0);
        assert_int_equal(ffc_mesh_quality(1, T + 4 * k, 12, Y, 0.5, &w, &wt, &below), FFC_OK);
        assert_close(w, want[k], 1e-14);
    }
    assert_true(qs > 0.0094 && qs < 0.0095);   /* (a sliver: about 0.00945) */
    assert_int_equal(ffc_mesh_quality(3, T, 12, X, 0.9, &w, &wt, &below), FFC_OK);
    assert_close(w, qs, 1e-14);
    assert_int_equal(wt, 1);
    assert_int_equal(below, 2);
    /* bad input */
    const long Tbad[4] = {0, 1, 2, 12};
    assert_int_equal(ffc_mesh_quality(1, Tbad, 12, X, 0.5, &w, &wt, &below), FFC_ERR_INDEX);
    assert_int_equal(wt, 0);
    assert_int_equal(ffc_mesh_quality(0, T, 12, X, 0.5, &w, &wt, &below), FFC_ERR_SIZE);
    assert_int_equal(ffc_mesh_quality(1, T, 12, X, -1.0, &w, &wt, &below), FFC_ERR_VALUE);
    assert_int_equal(ffc_mesh_quality(1, T, 12, X, NAN, &w, &wt, &below), FFC_ERR_VALUE);
    double Xn[12 * 3];   /* a coordinate not finite, of the second tetrahedron */
    memcpy(Xn, X, sizeof Xn);
    Xn[3 * 6 + 1] = NAN;
    assert_int_equal(ffc_mesh_quality(3, T, 12, Xn, 0.5, &w, &wt, &below), FFC_ERR_NONFINITE);
    assert_int_equal(wt, 1);
    Xn[3 * 6 + 1] = INFINITY;
    assert_int_equal(ffc_mesh_quality(3, T, 12, Xn, 0.5, &w, &wt, &below), FFC_ERR_NONFINITE);
    assert_int_equal(ffc_mesh_quality(1, NULL, 12, X, 0.5, &w, &wt, &below), FFC_ERR_NULL);
    assert_int_equal(ffc_mesh_quality(1, T, 12, X, 0.5, NULL, &wt, &below), FFC_ERR_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_select_orients_outward),
        cmocka_unit_test(test_select_by_label),
        cmocka_unit_test(test_check_errors),
        cmocka_unit_test(test_scene_volume),
        cmocka_unit_test(test_area),
        cmocka_unit_test(test_mesh_quality),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
