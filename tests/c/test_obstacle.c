/* test_obstacle.c: rigid obstacles: gap, normal and curvature against their
 * closed forms and central differences; a link's tangent against central
 * differences of its residual (separated, pressed, stick, slip; 3 and 6
 * nodes; small strain and finite deformation); the nodal law's assembly;
 * the search; bad input. */
#include "ffc_test.h"

static ffc_obstacle plane(void)
{
    ffc_obstacle o = {FFC_OBST_PLANE, {0.1, -0.2, 0.3}, {0.0, 0.6, 0.8}, 0.0, 0, {0, 0, 0}};
    return o;
}
static ffc_obstacle sphere(int inside)
{
    ffc_obstacle o = {FFC_OBST_SPHERE, {0.2, 0.1, -1.0}, {0, 0, 0}, 1.3, inside, {0, 0, 0}};
    return o;
}
static ffc_obstacle cylinder(int inside)
{
    const double s = 1.0 / sqrt(3.0);
    ffc_obstacle o = {FFC_OBST_CYLINDER, {0.0, 0.3, -0.8}, {s, s, s}, 0.9, inside, {0, 0, 0}};
    return o;
}

static void test_values(void **state)
{
    (void)state;
    double g, n[3];
    ffc_obstacle p = plane();
    const double x[3] = {3.0, 1.0, 2.0};
    assert_int_equal(ffc_obstacle_gap(&p, x, &g, n, NULL), FFC_OK);
    assert_close(g, 0.6 * 1.2 + 0.8 * 1.7, 1e-15);
    ffc_obstacle s = {FFC_OBST_SPHERE, {0, 0, 0}, {0, 0, 0}, 1.0, 0, {0, 0, 0}};
    const double xs[3] = {0.0, 0.0, 1.5};
    assert_int_equal(ffc_obstacle_gap(&s, xs, &g, n, NULL), FFC_OK);
    assert_close(g, 0.5, 1e-15);
    assert_close(n[2], 1.0, 1e-15);
    s.inside = 1;   /* a body inside the ball of radius 1: the point is 0.5 outside it */
    assert_int_equal(ffc_obstacle_gap(&s, xs, &g, n, NULL), FFC_OK);
    assert_close(g, -0.5, 1e-15);
    assert_close(n[2], -1.0, 1e-15);
    ffc_obstacle c = {FFC_OBST_CYLINDER, {0, 0, 0}, {0, 0, 1}, 0.5, 0, {0, 0, 0}};
    const double xc[3] = {0.0, 1.0, 7.0};
    double H[3][3];
    assert_int_equal(ffc_obstacle_gap(&c, xc, &g, n, H), FFC_OK);
    assert_close(g, 0.5, 1e-15);
    assert_close(n[1], 1.0, 1e-15);
    /* the normal turns along x (the circle's tangent) at 1/|d|, not along the axis */
    assert_close(H[0][0], 1.0, 1e-15);
    assert_close(H[2][2], 0.0, 1e-15);
    assert_close(H[1][1], 0.0, 1e-15);
    /* no normal on the axis or at the centre */
    const double on[3] = {0.0, 0.0, 3.0};
    assert_int_equal(ffc_obstacle_gap(&c, on, &g, n, H), FFC_ERR_DEGENERATE);
    s.inside = 0;
    const double ctr[3] = {0, 0, 0};
    assert_int_equal(ffc_obstacle_gap(&s, ctr, &g, n, H), FFC_ERR_DEGENERATE);
}

/* n against central differences of g, H of n: h = 1e-6 at distances ~1,
 * truncation h^2 |g'''| ~ 1e-12, round-off 1e-16 / h ~ 1e-10: bound 1e-8 */
static void test_derivatives(void **state)
{
    (void)state;
    uint64_t seed = 3;
    const ffc_obstacle all[5] = {plane(), sphere(0), sphere(1), cylinder(0), cylinder(1)};
    for (int k = 0; k < 5; k++)
        for (int t = 0; t < 10; t++) {
            double x[3], g, n[3], H[3][3];
            for (int i = 0; i < 3; i++) x[i] = all[k].c[i] + test_rand(&seed, -1.5, 1.5);
            assert_int_equal(ffc_obstacle_gap(&all[k], x, &g, n, H), FFC_OK);
            assert_close(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-14);
            const double h = 1e-6;
            for (int j = 0; j < 3; j++) {
                double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, gp, gm, np[3], nm[3];
                xp[j] += h;
                xm[j] -= h;
                assert_int_equal(ffc_obstacle_gap(&all[k], xp, &gp, np, NULL), FFC_OK);
                assert_int_equal(ffc_obstacle_gap(&all[k], xm, &gm, nm, NULL), FFC_OK);
                assert_close((gp - gm) / (2 * h), n[j], 1e-8);
                for (int i = 0; i < 3; i++) assert_close((np[i] - nm[i]) / (2 * h), H[i][j], 1e-8 * (1 + fabs(H[i][j])));
            }
        }
}

typedef struct {
    int ns;
    double Xs[6][3], Xs0[6][3], Ds[6][3], xs[2], w, lambda, lam_t[3];
    ffc_obstacle ob;
    ffc_effects fx;
    ffc_law law;
} ocase;

static int oc_eval(const ocase *c, ffc_link_state *st, double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF])
{
    return ffc_link_obstacle(&c->fx, c->ns, (const double(*)[3])c->Xs, (const double(*)[3])c->Xs0,
                             (const double(*)[3])c->Ds, c->xs, c->w, &c->ob, c->lambda, c->lam_t, &c->law, st, R, K);
}

static int oc_eval_r(void *c, ffc_link_state *st, double R[FFC_MAXDOF]) { return oc_eval(c, st, R, NULL); }

/* A slave facet (normal toward the obstacle) whose point sits at gap
 * `offset` from the obstacle's surface, near the point x0 of it. */
static void oc_make(ocase *c, int ns, const ffc_obstacle *ob, int finite, double offset, uint64_t *s)
{
    memset(c, 0, sizeof *c);
    c->ns = ns;
    c->ob = *ob;
    c->fx.finite_def = finite;
    c->xs[0] = 0.3;
    c->xs[1] = 0.25;
    c->w = 0.5;
    c->law.eps_n = 50.0;
    /* a surface point of the obstacle and its tangent frame */
    double q[3] = {ob->c[0] + 0.3, ob->c[1] + 0.9, ob->c[2] + 0.7}, g, n[3];
    assert_int_equal(ffc_obstacle_gap(ob, q, &g, n, NULL), FFC_OK);
    for (int i = 0; i < 3; i++) q[i] -= (g - offset) * n[i];
    double t1[3] = {1, 0, 0};
    if (fabs(n[0]) > 0.8) t1[0] = 0, t1[1] = 1;
    const double d = t1[0] * n[0] + t1[1] * n[1] + t1[2] * n[2];
    for (int i = 0; i < 3; i++) t1[i] -= d * n[i];
    const double l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (int i = 0; i < 3; i++) t1[i] /= l;
    const double t2[3] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]};
    for (int a = 0; a < ns; a++)
        for (int i = 0; i < 3; i++) {
            /* reversed orientation (xi_1 along t2, xi_2 along t1): the facet's normal is -n */
            c->Xs[a][i] = q[i] + 0.3 * (test_node_xi[a][1] - c->xs[1]) * t1[i] +
                          0.3 * (test_node_xi[a][0] - c->xs[0]) * t2[i] + test_rand(s, -0.01, 0.01);
            c->Xs0[a][i] = c->Xs[a][i] + test_rand(s, -0.03, 0.03);
        }
}

/* Central differences of the residual, h = 1e-6 on facets of size 0.3:
 * truncation h^2 |R'''| ~ 1e-11 relative, round-off eps |R| / h ~ 1e-10:
 * the bound 1e-6 keeps four orders.  The quasi-static motion D = x - x^n
 * moves with x. */
static double oc_fd(ocase *c, int want_state)
{
    ffc_link_state st;
    double R[FFC_MAXDOF], K[FFC_MAXDOF][FFC_MAXDOF];
    assert_int_equal(oc_eval(c, &st, R, K), FFC_OK);
    if (want_state >= 0) assert_int_equal(st.fstate, want_state);
    const int nd = 3 * c->ns;
    double *x[FFC_MAXDOF], *m[FFC_MAXDOF], err, scale;
    for (int l = 0; l < nd; l++) { x[l] = &c->Xs[l / 3][l % 3]; m[l] = &c->Ds[l / 3][l % 3]; }
    test_link_fd(nd, x, m, 1e-6, oc_eval_r, c, &st, K, &err, &scale);
    if (!st.active) {
        assert_true(scale == 0.0 && err == 0.0);
        return 0.0;
    }
    if (!(err <= 1e-6 * scale))
        fail_msg("tangent error %.3g of scale %.3g (kind %d inside %d ns %d finite %d)", err, scale, c->ob.kind,
                 c->ob.inside, c->ns, c->fx.finite_def);
    return scale;
}

static void test_link_tangent(void **state)
{
    (void)state;
    uint64_t s = 11;
    const ffc_obstacle all[5] = {plane(), sphere(0), sphere(1), cylinder(0), cylinder(1)};
    for (int k = 0; k < 5; k++)
        for (int ns = 3; ns <= 6; ns += 3)
            for (int finite = 0; finite <= 1; finite++) {
                ocase c;
                /* separated: nothing */
                oc_make(&c, ns, &all[k], finite, 0.05, &s);
                assert_true(oc_fd(&c, FFC_FRIC_OPEN) == 0.0);
                /* pressed, frictionless */
                oc_make(&c, ns, &all[k], finite, -0.01, &s);
                c.lambda = 0.2;
                assert_true(oc_fd(&c, FFC_FRIC_OPEN) > 0.0);
                /* with friction, the obstacle moving: stick (small slip), then slip */
                c.fx.friction = 1;
                c.law.mu = 0.4;
                c.law.eps_t = 40.0;
                c.ob.d[0] = 0.001;
                c.ob.d[1] = -0.0005;
                for (int a = 0; a < ns; a++)
                    for (int i = 0; i < 3; i++) c.Ds[a][i] = test_rand(&s, -1e-4, 1e-4);
                assert_true(oc_fd(&c, FFC_FRIC_STICK) > 0.0);
                c.ob.d[0] = 0.05;
                c.ob.d[2] = 0.03;
                assert_true(oc_fd(&c, FFC_FRIC_SLIP) > 0.0);
            }
}

/* A frictionless point against a plane: the closed-form values (pressure
 * <lambda - eps g>, force da t_N n on the slave: R = -da t_N G) */
static void test_plane_values(void **state)
{
    (void)state;
    uint64_t s = 5;
    ocase c;
    ffc_obstacle p = plane();
    oc_make(&c, 3, &p, 0, -0.01, &s);
    c.lambda = 0.2;
    ffc_link_state st;
    double R[FFC_MAXDOF];
    assert_int_equal(oc_eval(&c, &st, R, NULL), FFC_OK);
    assert_true(st.active);
    assert_close(st.tn, 0.2 - 50.0 * st.gap, 1e-14);
    double N[6], dN[6][2], f[3] = {0, 0, 0};
    ffc_shape(3, c.xs, N, dN);
    for (int a = 0; a < 3; a++)
        for (int i = 0; i < 3; i++) {
            assert_close(R[3 * a + i], -st.da * st.tn * N[a] * p.a[i], 1e-15);
            f[i] -= R[3 * a + i];
        }
    for (int i = 0; i < 3; i++) assert_close(f[i], st.da * st.tn * p.a[i], 1e-15);
}

/* The nodal law over a small surface on a sphere, through ffc_assemble
 * and ffc_augment: its assembled tangent against central differences of
 * the assembled residual, frictionless and with friction (stick, slip). */
#define GN 4
#define GV ((GN + 1) * (GN + 1))
#define GF (2 * GN * GN)
static void grid_on_sphere(double X[], long F[], const ffc_obstacle *ob, double pen)
{
    int v = 0;
    for (int j = 0; j <= GN; j++)
        for (int i = 0; i <= GN; i++, v++) {
            const double x = -0.4 + 0.8 * i / GN + 0.01 * sin(3.0 * j), y = -0.4 + 0.8 * j / GN;
            X[3 * v] = ob->c[0] + x;
            X[3 * v + 1] = ob->c[1] + y;
            X[3 * v + 2] = ob->c[2] + ob->r - pen + 0.3 * (x * x + y * y);
        }
    int f = 0;
    for (int j = 0; j < GN; j++)
        for (int i = 0; i < GN; i++) {
            const long a = j * (GN + 1) + i, b = a + 1, d = a + GN + 1, c = d + 1;
            const long t[6] = {a, d, b, b, d, c};   /* normals down, toward the sphere */
            for (int k = 0; k < 6; k++) F[6 * f + k] = t[k];
            f++;
        }
}

static void assembled_fd(int fric, double slip, int want)
{
    double X[3 * GV], u[3 * GV], up[3 * GV], x[3 * GV];
    long F[3 * GF];
    ffc_obstacle ob = {FFC_OBST_SPHERE, {0, 0, 0}, {0, 0, 0}, 1.0, 0, {slip, 0.3 * slip, 0}};
    grid_on_sphere(X, F, &ob, 0.02);
    uint64_t s = 7;
    for (int i = 0; i < 3 * GV; i++) {
        u[i] = test_rand(&s, -1e-3, 1e-3);
        up[i] = u[i] - test_rand(&s, -1e-4, 1e-4);
        x[i] = X[i] + u[i];
    }
    const int nq = ffc_quad_size(2);
    ffc_link L[GF * 16];
    assert_true(ffc_obstacle_search(&ob, 3, GF, F, GV, x, 2, NULL, GF * nq, L) > 0);
    ffc_pair P = {3, GF, F, 0, 0, NULL, GV, X, u, up, NULL, &ob};
    ffc_effects fx = {fric, 0, 0};
    ffc_law law = {.eps_n = 100.0, .nodal = 1, .mu = fric ? 0.3 : 0.0, .eps_t = 100.0};
    double lam[GV], lam_t[3 * GV];
    for (int i = 0; i < GV; i++) lam[i] = 1.0;
    memset(lam_t, 0, sizeof lam_t);
    enum { CAP = 200000 };
    static long Ti[CAP], Tj[CAP];
    static double Tv[CAP], K[3 * GV][3 * GV];
    double R[3 * GV] = {0};
    long nt, bad;
    ffc_stats st;
    assert_int_equal(ffc_assemble(&fx, &P, 2, GF * nq, L, lam, lam_t, &law, R, CAP, Ti, Tj, Tv, &nt, &st, &bad), FFC_OK);
    assert_true(st.active > 0);
    if (fric) assert_true((want == FFC_FRIC_STICK ? st.stick : st.slip) > 0);
    if (fric) assert_int_equal(want == FFC_FRIC_STICK ? st.slip : st.stick, 0);
    memset(K, 0, sizeof K);
    for (long k = 0; k < nt; k++) K[Ti[k]][Tj[k]] += Tv[k];
    const double h = 1e-7;
    double err = 0, scale = 0;
    for (int l = 0; l < 3 * GV; l++) {
        double Rp[3 * GV] = {0}, Rm[3 * GV] = {0}, u0 = u[l];
        u[l] = u0 + h;
        assert_int_equal(ffc_assemble(&fx, &P, 2, GF * nq, L, lam, lam_t, &law, Rp, 0, NULL, NULL, NULL, &nt, NULL, &bad), FFC_OK);
        u[l] = u0 - h;
        assert_int_equal(ffc_assemble(&fx, &P, 2, GF * nq, L, lam, lam_t, &law, Rm, 0, NULL, NULL, NULL, &nt, NULL, &bad), FFC_OK);
        u[l] = u0;
        for (int k = 0; k < 3 * GV; k++) {
            err = fmax(err, fabs((Rp[k] - Rm[k]) / (2 * h) - K[k][l]));
            scale = fmax(scale, fabs(K[k][l]));
        }
    }
    /* h = 1e-7 against displacements ~1e-3 and elements of 0.2: round-off
     * eps |R| / h ~ 1e-9 relative; bound 1e-5 */
    if (!(err <= 1e-5 * scale)) fail_msg("assembled tangent error %.3g of scale %.3g (friction %d)", err, scale, fric);
    /* the augmentation moves the multipliers of pressed nodes */
    ffc_stats sa;
    assert_int_equal(ffc_augment(&fx, &P, 2, GF * nq, L, lam, lam_t, &law, &sa, &bad), FFC_OK);
    assert_true(sa.max_dlam > 0.0);
}

static void test_assembled(void **state)
{
    (void)state;
    assembled_fd(0, 0.0, FFC_FRIC_OPEN);
    assembled_fd(1, 1e-5, FFC_FRIC_STICK);
    assembled_fd(1, 0.05, FFC_FRIC_SLIP);
}

/* the search: every point of a surface pressed into a sphere is linked,
 * none of one far away; the capture distance counts in the slave facet */
static void test_search(void **state)
{
    (void)state;
    double X[3 * GV];
    long F[3 * GF];
    ffc_obstacle ob = {FFC_OBST_SPHERE, {0, 0, 0}, {0, 0, 0}, 1.0, 0, {0, 0, 0}};
    grid_on_sphere(X, F, &ob, 0.004);
    ffc_link L[GF * 3];
    assert_int_equal(ffc_obstacle_search(&ob, 3, GF, F, GV, X, 2, NULL, GF * 3, L), GF * 3);
    for (int k = 0; k < GF * 3; k++) {
        double g, n[3], N[6], dN[6][2], p[3] = {0, 0, 0};
        ffc_shape(3, L[k].xs, N, dN);
        for (int a = 0; a < 3; a++)
            for (int i = 0; i < 3; i++) p[i] += N[a] * X[3 * F[3 * L[k].sf + a] + i];
        ffc_obstacle_gap(&ob, p, &g, n, NULL);
        assert_int_equal(L[k].mf, 0);
        assert_close(L[k].gap, g, 1e-15);
    }
    /* the surface faces the sphere (its facets' normals point down, toward it);
     * inside the same sphere, none faces it */
    assert_int_equal(ffc_obstacle_facing(&ob, 3, GF, F, GV, X), GF);
    ob.inside = 1;
    assert_int_equal(ffc_obstacle_facing(&ob, 3, GF, F, GV, X), 0);
    ob.inside = 0;
    ob.c[2] = -10.0;
    assert_int_equal(ffc_obstacle_search(&ob, 3, GF, F, GV, X, 2, NULL, GF * 3, L), 0);
    for (int k = 0; k < GF * 3; k++) assert_int_equal(L[k].mf, -1);
    assert_int_equal(ffc_obstacle_search(&ob, 3, GF, F, GV, X, 2, NULL, GF * 3 - 1, L), FFC_ERR_CAPACITY);
}

static void test_bad_input(void **state)
{
    (void)state;
    ffc_obstacle o = sphere(0);
    assert_int_equal(ffc_obstacle_check(&o), FFC_OK);
    o.kind = 9;
    assert_int_equal(ffc_obstacle_check(&o), FFC_ERR_VALUE);
    o = sphere(0);
    o.r = 0.0;
    assert_int_equal(ffc_obstacle_check(&o), FFC_ERR_VALUE);
    o.r = NAN;
    assert_int_equal(ffc_obstacle_check(&o), FFC_ERR_NONFINITE);
    o = cylinder(0);
    o.a[0] *= 1.001;
    assert_int_equal(ffc_obstacle_check(&o), FFC_ERR_VALUE);
    o = plane();
    o.inside = 1;
    assert_int_equal(ffc_obstacle_check(&o), FFC_ERR_VALUE);
    o = plane();
    o.c[1] = INFINITY;
    assert_int_equal(ffc_obstacle_check(&o), FFC_ERR_NONFINITE);
    assert_int_equal(ffc_obstacle_check(NULL), FFC_ERR_NULL);
    /* a link against a bad obstacle is refused before any work */
    ocase c;
    uint64_t s = 1;
    ffc_obstacle p = plane();
    oc_make(&c, 3, &p, 0, -0.01, &s);
    c.ob.kind = 0;
    ffc_link_state st;
    double R[FFC_MAXDOF];
    assert_int_equal(oc_eval(&c, &st, R, NULL), FFC_ERR_VALUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values),     cmocka_unit_test(test_derivatives), cmocka_unit_test(test_link_tangent),
        cmocka_unit_test(test_plane_values), cmocka_unit_test(test_assembled), cmocka_unit_test(test_search),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
