/* test_project.c: closest-point projection onto 3- and 6-node facets and
 * the derivatives of foot, gap and normal against central differences. */
#include "ffc_test.h"
#include "ffc_internal.h"   /* (internal: the free foot from a start) */

#include <string.h>

static const double T3[3][3] = {{0.1, -0.2, 0.3}, {1.3, 0.1, 0.2}, {0.2, 1.1, 0.5}};

/* brute-force minimum distance over a fine grid of the facet */
static double brute_min_dist(int nn, const double X[][3], const double p[3])
{
    double best = INFINITY;
    const int M = 400;
    for (int i = 0; i <= M; i++)
        for (int j = 0; i + j <= M; j++) {
            double xi[2] = {(double)i / M, (double)j / M};
            ffc_point g;
            ffc_facet_point(nn, X, xi, &g);
            double d[3] = {p[0] - g.x[0], p[1] - g.x[1], p[2] - g.x[2]};
            double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (l < best) best = l;
        }
    return best;
}

/* p = x(xi0) + h n(xi0): the foot is xi0 and the gap h, above and below */
static void check_normal_offset(int nn, const double X[][3], const double xi0[2], double h)
{
    ffc_point g;
    assert_int_equal(ffc_facet_point(nn, X, xi0, &g), FFC_OK);
    double p[3];
    for (int i = 0; i < 3; i++) p[i] = g.x[i] + h * g.n[i];
    ffc_proj pr;
    assert_int_equal(ffc_project(nn, X, p, &pr), FFC_OK);
    assert_int_equal(pr.where, FFC_FOOT_INSIDE);
    assert_close(pr.xi[0], xi0[0], 1e-11);
    assert_close(pr.xi[1], xi0[1], 1e-11);
    assert_close(pr.gap, h, 1e-12 * (1 + fabs(h)));
    assert_close(pr.dist, fabs(h), 1e-12 * (1 + fabs(h)));
}

static void test_interior_above_below(void **state)
{
    (void)state;
    const double xi0[2] = {0.3, 0.25};
    check_normal_offset(3, T3, xi0, 0.2);
    check_normal_offset(3, T3, xi0, -0.15);  /* below: negative gap */
    check_normal_offset(3, T3, xi0, 0.0);
    check_normal_offset(3, T3, xi0, 1e3);    /* far away */
    double S[6][3];
    test_sphere_facet(1.0, 0.5, S);
    check_normal_offset(6, (const double(*)[3])S, xi0, 0.05);
    check_normal_offset(6, (const double(*)[3])S, xi0, -0.05);
    const double xi1[2] = {0.05, 0.9};
    check_normal_offset(6, (const double(*)[3])S, xi1, 0.02);
}

/* feet outside the facet are clamped onto the right edge or vertex, and
 * the distance equals a brute-force minimum over the facet */
static void test_edges_and_vertices(void **state)
{
    (void)state;
    double S[6][3];
    test_sphere_facet(1.0, 0.5, S);
    struct { double xi[2]; int where; } cases[] = {
        {{0.4, -0.3}, FFC_FOOT_EDGE0}, {{0.8, 0.7}, FFC_FOOT_EDGE1},
        {{-0.3, 0.5}, FFC_FOOT_EDGE2}, {{-0.4, -0.4}, FFC_FOOT_VERTEX0},
        {{1.6, -0.2}, FFC_FOOT_VERTEX1}, {{-0.2, 1.6}, FFC_FOOT_VERTEX2}};
    for (int nn = 3; nn <= 6; nn += 3) {
        const double(*X)[3] = nn == 3 ? T3 : (const double(*)[3])S;
        for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
            /* a point above the extended facet at local coordinates xi */
            ffc_point g;
            ffc_facet_point(nn, X, cases[c].xi, &g);
            double p[3];
            for (int i = 0; i < 3; i++) p[i] = g.x[i] + 0.1 * g.n[i];
            ffc_proj pr;
            int st = ffc_project(nn, X, p, &pr);
            assert_int_equal(pr.where, cases[c].where);
            assert_int_equal(st, cases[c].where >= FFC_FOOT_VERTEX0 ? FFC_INFO_VERTEX : FFC_INFO_EDGE);
            assert_true(pr.xi[0] >= 0 && pr.xi[1] >= 0 && pr.xi[0] + pr.xi[1] <= 1 + 1e-15);
            /* the grid has spacing 1/400: its minimum is above the true one
             * by at most O(spacing^2 * facet size) ~ 1e-5 */
            double bd = brute_min_dist(nn, X, p);
            assert_true(pr.dist <= bd + 1e-14);
            assert_true(pr.dist >= bd - 2e-5);
        }
    }
}

/* a rigid rotation and translation of point and facet leaves the local
 * coordinates, the gap and the distance unchanged */
static void test_rigid_invariance(void **state)
{
    (void)state;
    double S[6][3];
    test_sphere_facet(1.5, 0.6, S);
    double R[3][3];
    const double ax[3] = {0.3, -1.0, 0.7}, tr[3] = {10.0, -3.0, 7.5};
    test_rotation(ax, 1.234, R);
    uint64_t s = 3;
    for (int nn = 3; nn <= 6; nn += 3) {
        const double(*X)[3] = nn == 3 ? T3 : (const double(*)[3])S;
        double Y[6][3];
        for (int a = 0; a < nn; a++) test_move(R, tr, X[a], Y[a]);
        for (int k = 0; k < 40; k++) {
            double p[3] = {test_rand(&s, -0.5, 1.5), test_rand(&s, -0.5, 1.5),
                           test_rand(&s, -0.5, 1.5)}, q[3];
            if (nn == 6) p[2] += 1.5;
            test_move(R, tr, p, q);
            ffc_proj a, b;
            int sa = ffc_project(nn, X, p, &a), sb = ffc_project(nn, (const double(*)[3])Y, q, &b);
            assert_true(sa >= 0);
            assert_int_equal(sa, sb);
            assert_int_equal(a.where, b.where);
            assert_close(a.xi[0], b.xi[0], 1e-10);
            assert_close(a.xi[1], b.xi[1], 1e-10);
            assert_close(a.gap, b.gap, 1e-12 * (1 + fabs(a.gap)) * 20);
            assert_close(a.dist, b.dist, 1e-12 * (1 + a.dist) * 20);
        }
    }
}

static void test_bad_input(void **state)
{
    (void)state;
    ffc_proj pr;
    double p[3] = {0, 0, 1};
    assert_int_equal(ffc_project(4, T3, p, &pr), FFC_ERR_NODES);
    assert_int_equal(ffc_project(3, T3, NULL, &pr), FFC_ERR_NULL);
    double q[3] = {0, NAN, 1};
    assert_int_equal(ffc_project(3, T3, q, &pr), FFC_ERR_NONFINITE);
    const double D[3][3] = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
    assert_int_equal(ffc_project(3, D, p, &pr), FFC_ERR_DEGENERATE);
    const double I[3][3] = {{0, 0, 0}, {INFINITY, 0, 0}, {0, 1, 0}};
    assert_int_equal(ffc_project(3, I, p, &pr), FFC_ERR_NONFINITE);
}

/* ---------------------------------------------------- derivatives vs FD */
/* Configuration: a slave facet (ns nodes) whose point at xs lies above the
 * master facet (nm nodes); state vector = all nodal positions. */
typedef struct {
    int ns, nm;
    double Xs[6][3], Xm[6][3];
    double xs[2];
} pair_t;

static int project_pair(const pair_t *c, ffc_proj *pr, double Ns[6])
{
    double dN[6][2], p[3] = {0, 0, 0};
    ffc_shape(c->ns, c->xs, Ns, dN);
    for (int a = 0; a < c->ns; a++)
        for (int i = 0; i < 3; i++) p[i] += Ns[a] * c->Xs[a][i];
    return ffc_project(c->nm, (const double(*)[3])c->Xm, p, pr);
}

static double *coord(pair_t *c, int k)
{
    return k < 3 * c->ns ? &c->Xs[k / 3][k % 3] : &c->Xm[(k - 3 * c->ns) / 3][k % 3];
}

/* Central differences with h = 1e-5 on unit-size facets: truncation
 * O(h^2 |f'''|) ~ 1e-10 and round-off O(eps / h) ~ 1e-11, so a relative
 * error of 1e-6 leaves four orders of margin. */
static void check_derivs(pair_t *c)
{
    const double h = 1e-5;
    ffc_proj pr;
    double Ns[6];
    assert_int_equal(project_pair(c, &pr, Ns), FFC_OK);
    double dxi[2][FFC_MAXDOF], dg[FFC_MAXDOF], dn[3][FFC_MAXDOF];
    assert_int_equal(ffc_project_deriv(c->ns, Ns, c->nm, (const double(*)[3])c->Xm, &pr, dxi, dg, dn), FFC_OK);
    const int nd = 3 * (c->ns + c->nm);
    double err = 0, scale = 0;
    for (int k = 0; k < nd; k++) {
        double *x = coord(c, k), x0 = *x;
        ffc_proj pp, pm;
        *x = x0 + h; assert_int_equal(project_pair(c, &pp, Ns), FFC_OK);
        *x = x0 - h; assert_int_equal(project_pair(c, &pm, Ns), FFC_OK);
        *x = x0;
        double fd[6] = {(pp.xi[0] - pm.xi[0]) / (2 * h), (pp.xi[1] - pm.xi[1]) / (2 * h),
                        (pp.gap - pm.gap) / (2 * h), (pp.n[0] - pm.n[0]) / (2 * h),
                        (pp.n[1] - pm.n[1]) / (2 * h), (pp.n[2] - pm.n[2]) / (2 * h)};
        double an[6] = {dxi[0][k], dxi[1][k], dg[k], dn[0][k], dn[1][k], dn[2][k]};
        for (int i = 0; i < 6; i++) {
            err = fmax(err, fabs(fd[i] - an[i]));
            scale = fmax(scale, fabs(an[i]));
        }
    }
    if (!(err <= 1e-6 * scale)) fail_msg("derivative error %.3g, scale %.3g (ns %d nm %d)", err, scale, c->ns, c->nm);
}

static void test_derivatives(void **state)
{
    (void)state;
    uint64_t s = 11;
    for (int ns = 3; ns <= 6; ns += 3)
        for (int nm = 3; nm <= 6; nm += 3)
            for (int trial = 0; trial < 5; trial++) {
                pair_t c;
                memset(&c, 0, sizeof c);
                c.ns = ns;
                c.nm = nm;
                if (nm == 3) memcpy(c.Xm, T3, sizeof T3);
                else test_sphere_facet(1.0, 0.8, c.Xm);
                for (int a = 0; a < 6; a++)
                    for (int i = 0; i < 3; i++) c.Xm[a][i] += test_rand(&s, -0.03, 0.03);
                /* slave facet: a small perturbed triangle above the master,
                 * its point xs projecting inside the master facet */
                ffc_point g;
                const double xm[2] = {test_rand(&s, 0.2, 0.4), test_rand(&s, 0.2, 0.4)};
                ffc_facet_point(nm, (const double(*)[3])c.Xm, xm, &g);
                double off = test_rand(&s, -0.05, 0.1);
                for (int a = 0; a < ns; a++)
                    for (int i = 0; i < 3; i++)
                        c.Xs[a][i] = g.x[i] + off * g.n[i] +
                                     0.3 * (test_node_xi[a][0] - 1.0 / 3.0) * g.tau[0][i] +
                                     0.3 * (test_node_xi[a][1] - 1.0 / 3.0) * g.tau[1][i] +
                                     test_rand(&s, -0.02, 0.02);
                c.xs[0] = test_rand(&s, 0.1, 0.5);
                c.xs[1] = test_rand(&s, 0.1, 0.4);
                check_derivs(&c);
            }
}

static void test_deriv_rejects_clamped(void **state)
{
    (void)state;
    ffc_proj pr;
    double p[3] = {-1, -1, 1};
    assert_int_equal(ffc_project(3, T3, p, &pr), FFC_INFO_VERTEX);
    double Ns[1] = {1.0}, dxi[2][FFC_MAXDOF], dg[FFC_MAXDOF], dn[3][FFC_MAXDOF];
    assert_int_equal(ffc_project_deriv(1, Ns, 3, T3, &pr, dxi, dg, dn), FFC_ERR_VALUE);
}

/* the foot of a curved facet is stationary to round-off: tau_a . (p - x)
 * ~ 1e-15 (a foot left 1e-6 short by a stalled line search would show
 * up as 1e-4 errors in finite-difference checks of contact tangents) */
static void test_curved_foot_precision(void **state)
{
    (void)state;
    uint64_t s = 77;
    double X[6][3];
    test_sphere_facet(1.0, 0.8, X);
    for (int trial = 0; trial < 500; trial++) {
        ffc_point g;
        const double xi[2] = {test_rand(&s, 0.1, 0.45), test_rand(&s, 0.1, 0.45)};
        ffc_facet_point(6, (const double(*)[3])X, xi, &g);
        double p[3];
        const double off = test_rand(&s, -0.05, 0.05);
        for (int i = 0; i < 3; i++)
            p[i] = g.x[i] + off * g.n[i] + test_rand(&s, -1e-3, 1e-3) * (g.tau[0][i] + g.tau[1][i]);
        ffc_proj pr;
        assert_true(ffc_project(6, (const double(*)[3])X, p, &pr) >= 0);
        ffc_point f;
        ffc_facet_point(6, (const double(*)[3])X, pr.xi, &f);
        for (int a = 0; a < 2; a++) {
            double r = 0;
            for (int i = 0; i < 3; i++) r += f.tau[a][i] * (p[i] - f.x[i]);
            assert_close(r, 0.0, 1e-14);
        }
    }
}

/* A point far off a straight-sided 6-node facet (its free foot at xi =
 * (-2.4, 3.8), outside the neighbourhood [-2, 3]^2 where the iteration
 * keeps its iterates): the free foot is the vertex triangle's, as the
 * closed form of 3 nodes gives it, not a failure to converge (a mortar
 * pair's far points over a flat master) */
static void test_far_free_foot(void **state)
{
    (void)state;
    double X6[6][3];
    for (int a = 0; a < 3; a++)
        for (int i = 0; i < 3; i++) {
            X6[a][i] = T3[a][i];
            X6[3 + a][i] = 0.5 * (T3[a][i] + T3[(a + 1) % 3][i]);
        }
    const double xi0[2] = {-2.4, 3.8};
    ffc_point g;
    assert_int_equal(ffc_facet_point(3, T3, xi0, &g), FFC_OK);
    double p[3];
    for (int i = 0; i < 3; i++) p[i] = g.x[i] + 0.7 * g.n[i];
    ffc_proj p3, p6;
    assert_true(ffc_project(3, T3, p, &p3) >= 0);
    assert_true(ffc_project(6, (const double(*)[3])X6, p, &p6) >= 0);
    for (int a = 0; a < 2; a++) {
        assert_close(p3.xi_free[a], xi0[a], 1e-12);
        assert_close(p6.xi_free[a], xi0[a], 1e-12);
        assert_close(p6.xi[a], p3.xi[a], 1e-12); /* the clamped foot: the same boundary point */
    }
    assert_close(p6.gap, p3.gap, 1e-12);
}

/* The free foot on a curved facet started at a foot found before
 * (ffc__project_free_from: a link's stored foot): from the foot itself,
 * the same foot in one Newton step; from a start 0.2 away, the same
 * stationary point; a non-finite start is the vertex triangle's.  Points
 * above and below a sphere facet; tolerance 1e-13 in xi (Newton's
 * stopping test, 1e-13 of the coordinates, on a quadratically converging
 * sequence). */
static void test_warm_start(void **state)
{
    (void)state;
    uint64_t s = 91;
    double X[6][3];
    test_sphere_facet(1.0, 0.8, X);
    const double bad[2] = {NAN, 0.0};
    for (int trial = 0; trial < 200; trial++) {
        ffc_point g;
        const double xi[2] = {test_rand(&s, 0.0, 0.6), test_rand(&s, 0.0, 0.4)};
        ffc_facet_point(6, (const double(*)[3])X, xi, &g);
        double p[3];
        const double off = test_rand(&s, -0.05, 0.05);
        for (int i = 0; i < 3; i++) p[i] = g.x[i] + off * g.n[i];
        ffc_proj cold, warm, near, nan0;
        assert_int_equal(ffc__project_free(6, (const double(*)[3])X, p, &cold), FFC_OK);
        assert_int_equal(ffc__project_free_from(6, (const double(*)[3])X, p, cold.xi_free, &warm), FFC_OK);
        const double x0[2] = {cold.xi_free[0] + 0.2, cold.xi_free[1] - 0.15};
        assert_int_equal(ffc__project_free_from(6, (const double(*)[3])X, p, x0, &near), FFC_OK);
        assert_int_equal(ffc__project_free_from(6, (const double(*)[3])X, p, bad, &nan0), FFC_OK);
        assert_true(warm.iters <= 1);
        for (int a = 0; a < 2; a++) {
            assert_close(cold.xi_free[a], xi[a], 1e-12);
            assert_close(warm.xi_free[a], cold.xi_free[a], 1e-13);
            assert_close(near.xi_free[a], cold.xi_free[a], 1e-13);
            assert_true(nan0.xi_free[a] == cold.xi_free[a]);
        }
        assert_close(warm.gap, cold.gap, 1e-13);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_interior_above_below),
        cmocka_unit_test(test_edges_and_vertices),
        cmocka_unit_test(test_rigid_invariance),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_derivatives),
        cmocka_unit_test(test_deriv_rejects_clamped),
        cmocka_unit_test(test_curved_foot_precision),
        cmocka_unit_test(test_far_free_foot),
        cmocka_unit_test(test_warm_start),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
