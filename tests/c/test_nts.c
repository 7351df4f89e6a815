/* test_nts.c: node-to-surface Lagrange-multiplier contact: slave nodes and
 * areas, constraint rows against their geometric definition, forces and
 * the open / stick / slide / release transitions, bad input. */
#include "ffc_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NV 41

static ffc_nts_law law_default(void)
{
    ffc_nts_law l = {0.3, 0.3, 1e-12, 1e-9, 8, 1.0};
    return l;
}

/* the 41-node scene of ffc_test.h (3-node facets) */
static void scene(double X[3 * NV], long Fm[32 * 3], long Fs[18 * 3], ffc_pair *p, double u[3 * NV])
{
    test_pair_scene(X, Fm, Fs);
    memset(u, 0, 3 * NV * sizeof u[0]);
    ffc_pair q = {3, 18, Fs, 3, 32, Fm, NV, X, u, NULL, NULL, NULL};
    *p = q;
}

/* gap of slave node c over master facet f (flat), by projection */
static double gap_of(const ffc_pair *p, const double *u, long c, long f)
{
    double Xm[3][3], x[3];
    for (int a = 0; a < 3; a++)
        for (int i = 0; i < 3; i++) Xm[a][i] = p->X[3 * p->Fm[3 * f + a] + i] + u[3 * p->Fm[3 * f + a] + i];
    for (int i = 0; i < 3; i++) x[i] = p->X[3 * c + i] + u[3 * c + i];
    ffc_proj pr;
    ffc_project(3, Xm, x, &pr);
    return pr.gap;
}

static void test_nodes(void **state)
{
    (void)state;
    double X[3 * NV], u[3 * NV];
    long Fm[96], Fs[54];
    ffc_pair p;
    scene(X, Fm, Fs, &p, u);
    ffc_nts_node nd[16];
    long need = 0;
    assert_int_equal(ffc_nts_nodes(&p, 3, nd, &need), FFC_ERR_CAPACITY);
    assert_int_equal(need, 16);
    assert_int_equal(ffc_nts_nodes(&p, 16, nd, &need), 16);
    double A = 0, sum = 0;
    ffc_surface_area(3, 18, Fs, NV, X, NULL, 2, &A);
    for (int k = 0; k < 16; k++) {
        assert_int_equal(nd[k].node, 25 + k);
        assert_int_equal(nd[k].state, FFC_NTS_OPEN);
        assert_true(nd[k].area > 0);
        sum += nd[k].area;
    }
    /* the tributary areas partition the slave surface */
    assert_close(sum, A, 1e-14 * A);
    /* a corner node has one or two facets, an interior one six: 1/6 .. 6/6 of 6 facets' thirds */
    assert_true(nd[5].area > nd[0].area);
}

/* Puts every slave node exactly on the master (g = 0) and locates. */
static long touching_scene(double X[3 * NV], long Fm[96], long Fs[54], ffc_pair *p, double u[3 * NV],
                           ffc_nts_node nd[16], const ffc_nts_law *law)
{
    scene(X, Fm, Fs, p, u);
    long need;
    long nn = ffc_nts_nodes(p, 16, nd, &need);
    assert_int_equal(ffc_nts_locate(p, law, NULL, 1, nn, nd), FFC_OK);
    for (long k = 0; k < nn; k++) {
        assert_true(nd[k].mf >= 0);
        for (int i = 0; i < 3; i++) u[3 * nd[k].node + i] -= nd[k].gap * nd[k].n[i];
    }
    assert_int_equal(ffc_nts_locate(p, law, NULL, 1, nn, nd), FFC_OK);
    for (long k = 0; k < nn; k++) {
        assert_close(nd[k].gap, 0.0, 1e-15);
        assert_int_equal(nd[k].state, FFC_NTS_STICK);
    }
    return nn;
}

/* rho = B v - c for the triplets */
static void row_residual(long nt, const long Bi[], const long Bj[], const double Bv[], long nr,
                         const double c[], const double v[], double rho[])
{
    for (long r = 0; r < nr; r++) rho[r] = -c[r];
    for (long t = 0; t < nt; t++) rho[Bi[t]] += Bv[t] * v[Bj[t]];
}

static void test_rows_geometry(void **state)
{
    (void)state;
    double X[3 * NV], u[3 * NV], u0[3 * NV];
    long Fm[96], Fs[54];
    ffc_pair p;
    ffc_nts_node nd[16];
    ffc_nts_law law = law_default();
    law.scale = 7.5;
    const long nn = touching_scene(X, Fm, Fs, &p, u, nd, &law);
    memcpy(u0, u, sizeof u0);
    p.u_prev = u0;
    enum { CAP = 16 * 3 * 12 };
    long Bi[CAP], Bj[CAP], nt, nr;
    double Bv[CAP], Fv[CAP], c[48];
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, nn, nd, CAP, Bi, Bj, Bv, Fv, 48, c, &nt, &nr), FFC_OK);
    assert_int_equal(nr, 3 * nn);     /* all stick: three rows each */
    for (long t = 0; t < nt; t++) assert_true(Bv[t] == Fv[t]);   /* no sliding friction in stick */
    double rho[48];
    /* at the state the rows were built: satisfied */
    row_residual(nt, Bi, Bj, Bv, nr, c, u, rho);
    for (long r = 0; r < nr; r++) assert_close(rho[r], 0.0, 1e-14 * law.scale);
    /* an infinitesimal rigid motion of the pair keeps every row satisfied */
    const double tr[3] = {0.3, -0.7, 0.2}, w[3] = {0.4, 0.1, -0.9};
    double v[3 * NV];
    for (int a = 0; a < NV; a++) {
        double x[3] = {X[3 * a] + u[3 * a], X[3 * a + 1] + u[3 * a + 1], X[3 * a + 2] + u[3 * a + 2]}, wx[3];
        wx[0] = w[1] * x[2] - w[2] * x[1];
        wx[1] = w[2] * x[0] - w[0] * x[2];
        wx[2] = w[0] * x[1] - w[1] * x[0];
        for (int i = 0; i < 3; i++) v[3 * a + i] = u[3 * a + i] + tr[i] + wx[i];
    }
    row_residual(nt, Bi, Bj, Bv, nr, c, v, rho);
    for (long r = 0; r < nr; r++) assert_close(rho[r], 0.0, 1e-13 * law.scale);
    /* a normal separation s of one node violates its normal row by s, only it */
    for (long k = 0; k < nn; k++) {
        memcpy(v, u, sizeof v);
        const double s = 1e-3 * (k + 1);
        for (int i = 0; i < 3; i++) v[3 * nd[k].node + i] += s * nd[k].n[i];
        row_residual(nt, Bi, Bj, Bv, nr, c, v, rho);
        for (long r = 0; r < nr; r++) assert_close(rho[r], r == nd[k].row ? law.scale * s : 0.0, 1e-14 * law.scale);
    }
    /* the normal row is dg/du: central differences of the projected gap */
    for (long k = 0; k < nn; k++) {
        double G[3 * NV];
        memset(G, 0, sizeof G);
        for (long t = 0; t < nt; t++)
            if (Bi[t] == nd[k].row) G[Bj[t]] += Bv[t] / law.scale;
        const long dofs[4] = {nd[k].node, Fm[3 * nd[k].mf], Fm[3 * nd[k].mf + 1], Fm[3 * nd[k].mf + 2]};
        for (int a = 0; a < 4; a++)
            for (int i = 0; i < 3; i++) {
                const long j = 3 * dofs[a] + i;
                const double h = 1e-6;
                memcpy(v, u, sizeof v);
                v[j] += h;
                double gp = gap_of(&p, v, nd[k].node, nd[k].mf);
                v[j] -= 2 * h;
                double gm = gap_of(&p, v, nd[k].node, nd[k].mf);
                assert_close(G[j], (gp - gm) / (2 * h), 1e-8);
            }
    }
    /* Dirichlet columns go to the right-hand side: the same residual for any
     * u that keeps the fixed values */
    double fixed[3 * NV];
    memset(fixed, 0, sizeof fixed);
    for (int j = 0; j < 3 * 5; j++) fixed[j] = 1;       /* master nodes 0..4 */
    long Bi2[CAP], Bj2[CAP], nt2, nr2;
    double Bv2[CAP], Fv2[CAP], c2[48], rho2[48];
    assert_int_equal(ffc_nts_rows(&p, &law, fixed, nn, nd, CAP, Bi2, Bj2, Bv2, Fv2, 48, c2, &nt2, &nr2), FFC_OK);
    assert_int_equal(nr2, nr);
    assert_true(nt2 < nt);
    for (long t = 0; t < nt2; t++) assert_true(fixed[Bj2[t]] == 0);
    memcpy(v, u, sizeof v);
    for (int j = 15; j < 3 * NV; j++) v[j] += 1e-3 * sin(j);
    row_residual(nt, Bi, Bj, Bv, nr, c, v, rho);
    row_residual(nt2, Bi2, Bj2, Bv2, nr2, c2, v, rho2);
    for (long r = 0; r < nr; r++) assert_close(rho2[r], rho[r], 1e-13 * law.scale);
    /* capacity: sizes reported */
    long ntc, nrc;
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, nn, nd, 5, Bi2, Bj2, Bv2, Fv2, 2, c2, &ntc, &nrc), FFC_ERR_CAPACITY);
    assert_int_equal(ntc, nt);
    assert_int_equal(nrc, nr);
}

/* One slave node over one big master facet, driven through open -> stick
 * -> slide -> stick -> release by scripted displacements and multipliers. */
/* One master facet (nodes 0, 1, 2) and one slave facet (3, 4, 5) at X,
 * zero displacements, the law of the friction tests; the slave nodes made
 * (not yet located: set up[] first where the slip matters). */
typedef struct {
    double X[18], u[18], up[18];
    long Fm[3], Fs[3];
    ffc_pair p;
    ffc_nts_law law;
    ffc_nts_node nd[3];
} one_facet;

static void one_facet_init(one_facet *f, const double X[18])
{
    memcpy(f->X, X, sizeof f->X);
    memset(f->u, 0, sizeof f->u);
    memset(f->up, 0, sizeof f->up);
    for (int a = 0; a < 3; a++) {
        f->Fm[a] = a;
        f->Fs[a] = 3 + a;
    }
    ffc_pair q = {3, 1, f->Fs, 3, 1, f->Fm, 6, f->X, f->u, f->up, NULL, NULL};
    ffc_nts_law l = {0.5, 0.4, 1e-12, 1e-9, 20, 2.0};
    f->p = q;
    f->law = l;
    long need;
    assert_int_equal(ffc_nts_nodes(&f->p, 3, f->nd, &need), 3);
}

static void test_transitions(void **state)
{
    (void)state;
    /* master facet nodes 0, 1, 2 (z = 0, normal +z); slave facet nodes 3, 4, 5 above,
     * normal down */
    const double X0[6 * 3] = {-5, -5, 0, 5, -5, 0, 0, 5, 0, 0, 0, 0.1, 0, 1, 0.1, 1, 0, 0.1};
    one_facet f;
    one_facet_init(&f, X0);
    double *X = f.X, *u = f.u, *up = f.up;
    ffc_pair p = f.p;
    ffc_nts_law law = f.law;
    ffc_nts_node *nd = f.nd;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, 3, nd), FFC_OK);
    ffc_nts_node *c = &nd[0];   /* node 3 */
    assert_int_equal(c->state, FFC_NTS_OPEN);
    assert_close(c->gap, 0.1, 1e-15);
    ffc_nts_stats st;
    long Bi[64], Bj[64], nt, nr;
    double Bv[64], Fv[64], cc[9], m[9];
    /* open, not touching: no rows, stays open */
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, cc, &nt, &nr), FFC_OK);
    assert_int_equal(nr, 0);
    assert_int_equal(ffc_nts_update(&law, 0, m, 3, nd, &st), FFC_OK);
    assert_int_equal(c->state, FFC_NTS_OPEN);
    assert_int_equal(st.changes, 0);
    assert_close(st.min_gap_open, 0.1, 1e-15);
    /* penetrates: contact, sticking (nu_s > 0) */
    for (int a = 3; a < 6; a++) u[3 * a + 2] = -0.11;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 0, 3, nd), FFC_OK);
    assert_int_equal(ffc_nts_update(&law, 0, m, 3, nd, &st), FFC_OK);
    assert_int_equal(c->state, FFC_NTS_STICK);
    assert_int_equal(st.changes, 3);
    assert_close(st.max_pen, 0.01, 1e-15);
    /* stick rows: three per node; the multipliers give the force
     * F = -scale (m_n n + m_1 t1 + m_2 t2) */
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, cc, &nt, &nr), FFC_OK);
    assert_int_equal(nr, 9);
    assert_int_equal(c->row, 0);
    /* normal row right-hand side closes the gap: B u_new = c with u_new on the surface */
    assert_close(cc[0], law.scale * (-0.11 + 0.01), 1e-14);
    /* F_n = 10, |F_t| = 4 < nu_s F_n = 5: stays stuck */
    memset(m, 0, sizeof m);
    for (int k = 0; k < 3; k++) m[3 * k] = -10 / law.scale;
    /* the tangent basis of (0,0,1): t1 = e_x x n = (0,-1,0), t2 = n x t1 = (1,0,0) */
    m[1] = 4 / law.scale;   /* F_t = -4 t1 = (0, 4, 0) */
    for (int a = 3; a < 6; a++) u[3 * a + 2] = -0.1;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 0, 3, nd), FFC_OK);
    assert_int_equal(ffc_nts_update(&law, 9, m, 3, nd, &st), FFC_OK);
    assert_int_equal(c->state, FFC_NTS_STICK);
    assert_close(c->fn, 10, 1e-13);
    assert_close(c->f[1], 4, 1e-13);
    assert_close(st.force[2], 30, 1e-12);
    assert_close(st.max_ratio, 0.4, 1e-14);
    /* |F_t| = 6 > 5: slides, in the direction against F_t (-y) */
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, cc, &nt, &nr), FFC_OK);
    m[1] = 6 / law.scale;
    assert_int_equal(ffc_nts_update(&law, 9, m, 3, nd, &st), FFC_OK);
    assert_int_equal(c->state, FFC_NTS_SLIDE);
    assert_close(c->dir[1], -1, 1e-15);
    assert_int_equal(st.slide, 1);
    /* slide rows: the normal row and two sliding rows (Coulomb's law
     * linearized; their multiplier block C sits in columns 3 nv + row);
     * the force directions (Bf) are n, t1, t2 as in stick */
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, cc, &nt, &nr), FFC_OK);
    assert_int_equal(nr, 9);
    int seen = 0;
    for (long t = 0; t < nt; t++) {
        if (Bj[t] >= 18) {
            assert_true(Bi[t] == 1 || Bi[t] == 2);      /* only the sliding node's rows */
            assert_true(Bj[t] - 18 <= 2);                /* and its own multipliers */
            assert_close(Fv[t], 0, 0);
            seen++;
        }
        if (Bi[t] == 1 && Bj[t] == 3 * 3 + 1) assert_close(Fv[t], -law.scale, 1e-15);   /* t1 = (0,-1,0) */
    }
    assert_true(seen >= 2);
    memset(m, 0, sizeof m);
    m[0] = -10 / law.scale;
    m[1] = 4 / law.scale;   /* F_t = -4 t1 = (0, 4, 0) = nu_d F_n against the slip (-y) */
    /* sliding on along dir: stays sliding, Coulomb's law satisfied */
    for (int i = 0; i < 18; i++) up[i] = u[i];
    u[3 * 3 + 1] -= 0.02;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 0, 3, nd), FFC_OK);
    assert_int_equal(ffc_nts_update(&law, 9, m, 3, nd, &st), FFC_OK);
    assert_int_equal(c->state, FFC_NTS_SLIDE);
    assert_close(c->fn, 10, 1e-13);
    assert_close(c->f[1], law.nu_d * 10, 1e-13);   /* friction against the slip (-y) */
    assert_close(c->f[0], 0, 1e-15);
    assert_close(c->dir[1], -1, 1e-15);
    assert_close(st.max_slide_res, 0, 1e-15);
    assert_int_equal(ffc_nts_nrows(3, nd), 9);
    /* per-node output: pressure and traction per tributary area, state,
     * dissipation |F_t . slip| / area */
    double P[3 * FFC_POINT_COLS];
    long bad;
    assert_int_equal(ffc_nts_points(6, X, u, 3, nd, P, &bad), 3);
    assert_close(P[2], 0.1 - 0.1, 1e-15);                    /* z at X + u */
    assert_close(P[4], 10 / c->area, 1e-12);
    assert_close(P[9], law.nu_d * 10 / c->area, 1e-12);
    assert_close(P[11], FFC_NTS_SLIDE, 0);
    assert_close(P[12], law.nu_d * 10 * 0.02 / c->area, 1e-12);
    const double area1 = nd[1].area;
    nd[1].area = 0;
    assert_int_equal(ffc_nts_points(6, X, u, 3, nd, P, &bad), FFC_ERR_VALUE);
    assert_int_equal(bad, 1);
    nd[1].area = area1;
    /* slip reversed: sticks again */
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, cc, &nt, &nr), FFC_OK);
    u[3 * 3 + 1] += 0.04;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 0, 3, nd), FFC_OK);
    assert_int_equal(ffc_nts_update(&law, nr, m, 3, nd, &st), FFC_OK);
    assert_int_equal(c->state, FFC_NTS_STICK);
    /* tension: released, no force afterwards */
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, cc, &nt, &nr), FFC_OK);
    memset(m, 0, sizeof m);
    m[0] = 3 / law.scale;      /* F_n = -3 < 0 */
    m[3] = -10 / law.scale;
    m[6] = -10 / law.scale;
    assert_int_equal(ffc_nts_update(&law, nr, m, 3, nd, &st), FFC_OK);
    assert_int_equal(c->state, FFC_NTS_OPEN);
    assert_int_equal(st.released, 1);
    assert_close(st.min_fn, -3, 1e-13);
    assert_int_equal(c->flips, 4);   /* open -> stick -> slide -> stick -> open */
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, cc, &nt, &nr), FFC_OK);
    assert_int_equal(c->row, -1);
    assert_int_equal(nr, 6);
}

/* The sliding rows against Coulomb's law Phi = m_t - nu_d mu p/|p|,
 * p = m_t + s, mu = -m_n, on a flat fixed master (the foot's motion does
 * not enter s): at the point of linearization the rows' residual is
 * scale Phi, wherever that point is; on the law (m_t = nu_d mu p/|p|,
 * where the damped linearization is the exact one) their entries (B on
 * the slave dofs, C) are scale times the central differences of Phi; the
 * master columns are -L_a times the slave's. */
static double slide_phi(int a, const double t[3][3], double nu, const double up[3], const double uc[3],
                        const double m[3])
{
    double mt[3], p[3];
    const double un = uc[2] - up[2];   /* n = e_z */
    for (int i = 0; i < 3; i++) {
        mt[i] = m[1] * t[1][i] + m[2] * t[2][i];
        p[i] = mt[i] + (uc[i] - up[i]) - (i == 2) * un;
    }
    const double pn = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    double phi = 0;
    for (int i = 0; i < 3; i++) phi += t[a][i] * (mt[i] + nu * m[0] * p[i] / pn);
    return phi;
}

static void check_slide_rows(const double mt_force[2], int exact)
{
    const double X0[6 * 3] = {-1, -1, 0, 2, -1, 0, 0, 2, 0, 0.1, 0.1, 0, 0.1, 1.1, 0, 1.1, 0.1, 0};
    one_facet f;
    one_facet_init(&f, X0);
    double *u = f.u, *up = f.up;
    up[9] = 1.0;        /* slip s = u_c - up_c = (-1, 1, 0) */
    up[10] = -1.0;
    ffc_pair p = f.p;
    ffc_nts_law law = f.law;
    ffc_nts_node *nd = f.nd;
    long Bi[64], Bj[64], nt, nr;
    double Bv[64], Fv[64], c[9];
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, 3, nd), FFC_OK);
    nd[0].state = FFC_NTS_SLIDE;
    nd[1].state = nd[2].state = FFC_NTS_OPEN;
    /* the tangent basis from the force directions of the rows */
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, c, &nt, &nr), FFC_OK);
    assert_int_equal(nr, 3);
    double t[3][3] = {{0}};
    for (long k = 0; k < nt; k++)
        if (Bj[k] >= 9 && Bj[k] < 12) t[Bi[k]][Bj[k] - 9] = Fv[k] / law.scale;
    assert_close(t[0][2], 1, 1e-15);
    /* m0 from the force F = -scale (m_n n + m_t): F_n = 10 */
    const double m0[3] = {-10 / law.scale, -(mt_force[0] * t[1][0] + mt_force[1] * t[1][1]) / law.scale,
                          -(mt_force[0] * t[2][0] + mt_force[1] * t[2][1]) / law.scale};
    for (int i = 0; i < 3; i++) nd[0].f[i] = -law.scale * (m0[0] * t[0][i] + m0[1] * t[1][i] + m0[2] * t[2][i]);
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, c, &nt, &nr), FFC_OK);
    assert_int_equal(nr, 3);
    double B[3][21] = {{0}};   /* 18 displacement columns, 3 multiplier columns */
    for (long k = 0; k < nt; k++) B[Bi[k]][Bj[k]] += Bv[k];
    const double h = 1e-6;
    for (int a = 1; a < 3; a++) {
        double res = -c[a];
        for (int j = 0; j < 18; j++) res += B[a][j] * u[j];
        for (int j = 0; j < 3; j++) res += B[a][18 + j] * m0[j];
        assert_close(res, law.scale * slide_phi(a, t, law.nu_d, up + 9, u + 9, m0), 1e-13);
        for (int b = 0; b < 3; b++)       /* master columns: -L_b times the slave's */
            for (int i = 0; i < 3; i++) assert_close(B[a][3 * b + i], -nd[0].L[b] * B[a][9 + i], 1e-14);
        if (!exact) continue;
        for (int i = 0; i < 3; i++) {
            double uc[3] = {u[9], u[10], u[11]}, um[3] = {u[9], u[10], u[11]};
            uc[i] += h;
            um[i] -= h;
            const double fd = law.scale * (slide_phi(a, t, law.nu_d, up + 9, uc, m0) -
                                           slide_phi(a, t, law.nu_d, up + 9, um, m0)) / (2 * h);
            assert_close(B[a][9 + i], fd, 1e-8);
        }
        for (int j = 0; j < 3; j++) {
            double mp[3] = {m0[0], m0[1], m0[2]}, mm[3] = {m0[0], m0[1], m0[2]};
            mp[j] += h;
            mm[j] -= h;
            const double fd = law.scale * (slide_phi(a, t, law.nu_d, up + 9, u + 9, mp) -
                                           slide_phi(a, t, law.nu_d, up + 9, u + 9, mm)) / (2 * h);
            assert_close(B[a][18 + j], fd, 1e-8);
        }
    }
}

static void test_slide_rows_fd(void **state)
{
    (void)state;
    /* s = (-1, 1, 0): the friction force nu_d F_n = 4 against it */
    const double on_law[2] = {4 / sqrt(2.0), -4 / sqrt(2.0)};
    const double inside[2] = {3, -1};     /* |F_t| = 3.2 < nu_d F_n = 4 */
    const double outside[2] = {5, -4};    /* |F_t| = 6.4 > 4 */
    check_slide_rows(on_law, 1);
    check_slide_rows(inside, 0);
    check_slide_rows(outside, 0);
}

/* friction at a contact node with a prescribed tangential dof (a symmetry
 * plane): no row along that direction t1, stick and slide along t2 = n x t1
 * alone (Coulomb in one dimension: the sliding row's residual at its point
 * of linearization is scale Phi_2, Phi_2 = m_2 - nu_d mu sign(p_2)) */
static void test_fixed_tangent(void **state)
{
    (void)state;
    const double X0[6 * 3] = {-5, -5, 0, 5, -5, 0, 0, 5, 0, 0, 0, 0, 0, 1, 0, 1, 0, 0};
    one_facet f;
    one_facet_init(&f, X0);
    double *u = f.u, *up = f.up, fixed[18];
    memset(fixed, 0, sizeof fixed);
    ffc_pair p = f.p;
    ffc_nts_law law = f.law;
    ffc_nts_node *nd = f.nd;
    long Bi[64], Bj[64], nt, nr;
    double Bv[64], Fv[64], c[9];
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, 3, nd), FFC_OK);
    fixed[3 * 4 + 2] = 1;     /* node 4: normal dof prescribed: all rows */
    fixed[3 * 5 + 1] = 1;     /* node 5: y prescribed: no row along y */
    assert_int_equal(ffc_nts_rows(&p, &law, fixed, 3, nd, 64, Bi, Bj, Bv, Fv, 9, c, &nt, &nr), FFC_OK);
    assert_int_equal(nr, 3 + 3 + 2);
    assert_int_equal(nd[1].tfix, 0);
    assert_int_equal(nd[2].tfix, 2);
    assert_int_equal(nd[2].rmask, 1 | 4);
    /* node 5's tangential row: t2 = n x e_y = (-1, 0, 0) */
    for (long t = 0; t < nt; t++)
        if (Bi[t] == 7 && Bj[t] < 18 && Bj[t] / 3 == 5) {
            assert_close(Fv[t], Bj[t] % 3 == 0 ? -law.scale : 0, 1e-15);
        }
    /* sliding along x: F_t = (6, 0, 0) outside the disc nu_d F_n = 4, slip
     * (-1, 0, 0) since up: one sliding row with its C entries */
    nd[2].state = FFC_NTS_SLIDE;
    up[3 * 5] = 1.0;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 0, 3, nd), FFC_OK);
    nd[2].f[0] = 6;
    nd[2].f[2] = 10;
    assert_int_equal(ffc_nts_rows(&p, &law, fixed, 3, nd, 64, Bi, Bj, Bv, Fv, 9, c, &nt, &nr), FFC_OK);
    assert_int_equal(nr, 8);
    const double m0[2] = {-10 / law.scale, 6 / law.scale};   /* m_n; m_2 (F_t = -scale m_2 t2) */
    double res = -c[7];
    int ncol = 0;
    for (long t = 0; t < nt; t++) {
        if (Bi[t] != 7) continue;
        if (Bj[t] >= 18) {
            assert_true(Bj[t] - 18 == 6 || Bj[t] - 18 == 7);   /* its own normal and tangent multipliers */
            res += Bv[t] * m0[Bj[t] - 18 - 6];
            ncol++;
        } else {
            res += Bv[t] * u[Bj[t]];
        }
    }
    assert_int_equal(ncol, 2);
    /* p_2 = m_2 + s_2 = 3 + 1 (s = -1 along x = +1 along t2) > 0 */
    const double phi = m0[1] - law.nu_d * (-m0[0]);
    assert_close(res, law.scale * phi, 1e-13);
}

/* Two master facets meeting at the edge x = 0 (A: z = -0.1 x, x < 0, and
 * B: z = 0.1 x, x > 0) and a slave facet whose node 6 (at (0, 0, 0.05),
 * moved by u[18..20]) is the test's contact node */
typedef struct {
    double X[9 * 3], u[27];
    long Fm[6], Fs[3];
    ffc_pair p;
    ffc_nts_law law;
    ffc_nts_node nd[3];
} valley;

static void valley_init(valley *v)
{
    const double X[9 * 3] = {0, -2, 0, 0, 2, 0, -2, 0, 0.2, 0, 2, 0, 0, -2, 0, 2, 0, 0.2,
                             0, 0, 0.05, 0, 0.5, 1, 0.5, 0, 1};
    const long Fm[6] = {0, 1, 2, 3, 4, 5}, Fs[3] = {6, 7, 8};
    memcpy(v->X, X, sizeof X);
    memcpy(v->Fm, Fm, sizeof Fm);
    memcpy(v->Fs, Fs, sizeof Fs);
    memset(v->u, 0, sizeof v->u);
    const ffc_pair p = {3, 1, v->Fs, 3, 2, v->Fm, 9, v->X, v->u, NULL, NULL, NULL};
    const ffc_nts_law law = {0, 0, 1e-12, 1e-9, 8, 1.0};
    v->p = p;
    v->law = law;
    long need;
    assert_int_equal(ffc_nts_nodes(&v->p, 3, v->nd, &need), 3);
}

/* a node in a valley of the master (facets A: z = -0.1 x, x < 0, and B:
 * z = 0.1 x, x > 0) whose facet goes A -> B -> A keeps A: its gap is then
 * the distance to A's plane even where B is closer */
static void test_valley_freeze(void **state)
{
    (void)state;
    valley v;
    valley_init(&v);
    double *u6 = v.u + 18;
    ffc_nts_node *nd = v.nd;
    const double side[4] = {-0.3, 0.3, -0.3, 0.3};
    const long facet[4] = {0, 1, 0, 0}, before[4] = {-1, 0, 1, 1};
    const int frozen[4] = {0, 0, 1, 1};
    for (int k = 0; k < 4; k++) {
        u6[0] = side[k];
        u6[2] = -0.1;
        assert_int_equal(ffc_nts_locate(&v.p, &v.law, NULL, k == 0, 3, nd), FFC_OK);
        if (k == 0) assert_int_equal(nd[0].state, FFC_NTS_SLIDE);
        assert_int_equal(nd[0].mf, facet[k]);
        assert_int_equal(nd[0].mfprev, before[k]);
        assert_int_equal(nd[0].frozen, frozen[k]);
    }
    /* kept on A at x = 0.3: n_A . (x - 0) with n_A = (0.1, 0, 1) / sqrt(1.01) */
    assert_close(nd[0].gap, (0.1 * 0.3 - 0.05) / sqrt(1.01), 1e-14);
    assert_close(nd[0].L[0] + nd[0].L[1] + nd[0].L[2], 1, 1e-14);
    /* a new step (init) searches again */
    assert_int_equal(ffc_nts_locate(&v.p, &v.law, NULL, 1, 3, nd), FFC_OK);
    assert_int_equal(nd[0].mf, 1);
    assert_int_equal(nd[0].frozen, 0);
}

/* a contact node on the edge two facets share (A: z = -0.1 x, x < 0, and
 * B: z = 0.1 x, x > 0) keeps its facet while its foot stays on it to
 * round-off: 1e-11 past the edge, where B is the closer facet, it stays on
 * A (which facet the search gives there is round-off, and their normals
 * differ); 1e-2 past it, it moves to B */
static void test_edge_keep(void **state)
{
    (void)state;
    valley v;
    valley_init(&v);
    double *u6 = v.u + 18;
    ffc_nts_node *nd = v.nd;
    u6[0] = -1e-11;            /* on A, at the edge, gap -1e-12 / sqrt(1.01) */
    u6[2] = -0.05;
    assert_int_equal(ffc_nts_locate(&v.p, &v.law, NULL, 1, 3, nd), FFC_OK);
    assert_int_equal(nd[0].state, FFC_NTS_SLIDE);
    assert_int_equal(nd[0].mf, 0);
    u6[0] = 1e-11;             /* past the edge: B's interior at distance 1e-12, A's edge at 1e-11 */
    ffc_search_opts o = {1.0, 0.0, 0.0, 0};   /* (edge_tol 0: the search itself keeps nothing) */
    assert_int_equal(ffc_nts_locate(&v.p, &v.law, &o, 0, 3, nd), FFC_OK);
    assert_int_equal(nd[0].mf, 0);
    assert_int_equal(nd[0].mfprev, -1);
    assert_int_equal(nd[0].frozen, 0);
    assert_close(nd[0].gap, (0.1 * 1e-11) / sqrt(1.01), 1e-20);   /* to A's plane */
    u6[0] = 1e-2;              /* on B */
    assert_int_equal(ffc_nts_locate(&v.p, &v.law, &o, 0, 3, nd), FFC_OK);
    assert_int_equal(nd[0].mf, 1);
    assert_int_equal(nd[0].mfprev, 0);
}

/* a contact node held in a plane that cuts the master at its rim (a
 * symmetry plane): slightly above a tilted facet its foot lies past the
 * rim by less than its gap, and it keeps its facet; farther past the rim
 * it has no partner */
static void test_rim_keep(void **state)
{
    (void)state;
    const double X0[6 * 3] = {-1, 0, 0, 2, 0, 0, 0, 2, -0.2, 0.5, 0, 0, 0.5, 0.5, 1, 1, 0.3, 1};
    one_facet f;
    one_facet_init(&f, X0);
    double *u = f.u;
    ffc_pair p = f.p;
    ffc_nts_law law = f.law;
    law.nu_s = law.nu_d = 0;
    ffc_nts_node *nd = f.nd;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, 3, nd), FFC_OK);
    assert_int_equal(nd[0].state, FFC_NTS_SLIDE);
    assert_int_equal(nd[0].mf, 0);
    u[3 * 3 + 2] = 1e-3;       /* lifted: the foot 1e-4 past the rim y = 0 */
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 0, 3, nd), FFC_OK);
    assert_int_equal(nd[0].mf, 0);
    assert_close(nd[0].gap, 1e-3 / sqrt(1.01), 1e-15);
    u[3 * 3 + 1] = -0.1;       /* 0.1 past the rim: no partner */
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 0, 3, nd), FFC_OK);
    assert_int_equal(nd[0].mf, -1);
}

/* frictionless: contact nodes slide, one row each, B == Bf (symmetric) */
static void test_frictionless(void **state)
{
    (void)state;
    double X[3 * NV], u[3 * NV];
    long Fm[96], Fs[54];
    ffc_pair p;
    scene(X, Fm, Fs, &p, u);
    ffc_nts_law law = {0, 0, 0, 1e-9, 8, 1};
    ffc_nts_node nd[16];
    long need, nt, nr;
    const long nn = ffc_nts_nodes(&p, 16, nd, &need);
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, nn, nd), FFC_OK);
    long ncontact = 0;
    for (long k = 0; k < nn; k++) {
        if (nd[k].state != FFC_NTS_OPEN) {
            assert_int_equal(nd[k].state, FFC_NTS_SLIDE);
            assert_true(nd[k].gap <= 0);
            ncontact++;
        } else {
            assert_true(nd[k].gap > 0);
        }
    }
    assert_true(ncontact > 0 && ncontact < nn);   /* the scene is partly open */
    long Bi[200], Bj[200];
    double Bv[200], Fv[200], c[16];
    assert_int_equal(ffc_nts_rows(&p, &law, NULL, nn, nd, 200, Bi, Bj, Bv, Fv, 16, c, &nt, &nr), FFC_OK);
    assert_int_equal(nr, ncontact);
    for (long t = 0; t < nt; t++) assert_true(Bv[t] == Fv[t]);
}

/* chattering guard: once nodes have flipped max_flips times, one change
 * per update, at the first node in order */
static void test_chattering_guard(void **state)
{
    (void)state;
    double X[6 * 3] = {-5, -5, 0, 5, -5, 0, 0, 5, 0, 0, 0, -0.01, 0, 1, -0.01, 1, 0, -0.01};
    long Fm[3] = {0, 1, 2}, Fs[3] = {3, 4, 5};
    double u[18];
    memset(u, 0, sizeof u);
    ffc_pair p = {3, 1, Fs, 3, 1, Fm, 6, X, u, NULL, NULL, NULL};
    ffc_nts_law law = {0, 0, 1e-12, 1e-9, 3, 1.0};
    ffc_nts_node nd[3];
    long need, nt, nr, Bi[64], Bj[64];
    double Bv[64], Fv[64], c[9], m[3];
    ffc_nts_stats st;
    ffc_nts_nodes(&p, 3, nd, &need);
    ffc_nts_locate(&p, &law, NULL, 1, 3, nd);
    assert_int_equal(nd[0].state, FFC_NTS_SLIDE);
    /* scripted to chatter: tension whenever in contact, penetration when open */
    const long expect[7] = {3, 3, 3, 1, 1, 1, 1};
    for (int it = 0; it < 7; it++) {
        int before[3] = {nd[0].state, nd[1].state, nd[2].state};
        ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, c, &nt, &nr);
        for (long r = 0; r < nr; r++) m[r] = 1.0;
        assert_int_equal(ffc_nts_update(&law, nr, m, 3, nd, &st), FFC_OK);
        assert_int_equal(st.changes, expect[it]);
        if (it >= 3) {
            /* the guard acts: only the first node that asks changes */
            assert_int_equal(st.chatter, 3);
            assert_true(nd[0].state != before[0]);
            assert_int_equal(nd[1].state, before[1]);
            assert_int_equal(nd[2].state, before[2]);
        }
    }
    /* node 0 has changed state 7 times (>= 2 max_flips) and is open: it
     * penetrates but stays open, reported; the next node changes instead */
    assert_int_equal(nd[0].state, FFC_NTS_OPEN);
    assert_true(nd[0].flips >= 2 * law.max_flips);
    ffc_nts_rows(&p, &law, NULL, 3, nd, 64, Bi, Bj, Bv, Fv, 9, c, &nt, &nr);
    for (long r = 0; r < nr; r++) m[r] = 1.0;
    const int before1 = nd[1].state;
    assert_int_equal(ffc_nts_update(&law, nr, m, 3, nd, &st), FFC_OK);
    assert_int_equal(nd[0].state, FFC_NTS_OPEN);
    assert_int_equal(st.locked, 1);
    assert_close(st.min_gap_open, -0.01, 1e-15);
    assert_true(nd[1].state != before1);
}

static void test_bad_input(void **state)
{
    (void)state;
    double X[3 * NV], u[3 * NV];
    long Fm[96], Fs[54];
    ffc_pair p;
    scene(X, Fm, Fs, &p, u);
    ffc_nts_node nd[16];
    long need;
    const long nn = ffc_nts_nodes(&p, 16, nd, &need);
    ffc_nts_law law = law_default();
    law.nu_d = 0.5;   /* above nu_s */
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, nn, nd), FFC_ERR_VALUE);
    law = law_default();
    law.nu_s = -0.1;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, nn, nd), FFC_ERR_VALUE);
    law = law_default();
    law.scale = 0;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, nn, nd), FFC_ERR_VALUE);
    law = law_default();
    law.max_flips = 0;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, nn, nd), FFC_ERR_VALUE);
    law = law_default();
    ffc_pair q = p;
    q.ns = q.nm = 6;
    assert_int_equal(ffc_nts_nodes(&q, 16, nd, &need), FFC_ERR_NODES);
    q = p;
    q.nfs = 0;
    assert_int_equal(ffc_nts_nodes(&q, 16, nd, &need), FFC_ERR_EMPTY);
    u[3 * 30] = NAN;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, nn, nd), FFC_ERR_NONFINITE);
    u[3 * 30] = 0;
    double m[2] = {1, INFINITY};
    ffc_nts_stats st;
    assert_int_equal(ffc_nts_update(&law, 2, m, nn, nd, &st), FFC_ERR_NONFINITE);
    nd[0].node = NV;
    assert_int_equal(ffc_nts_locate(&p, &law, NULL, 1, nn, nd), FFC_ERR_INDEX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nodes),
        cmocka_unit_test(test_rows_geometry),
        cmocka_unit_test(test_transitions),
        cmocka_unit_test(test_slide_rows_fd),
        cmocka_unit_test(test_valley_freeze),
        cmocka_unit_test(test_rim_keep),
        cmocka_unit_test(test_edge_keep),
        cmocka_unit_test(test_fixed_tangent),
        cmocka_unit_test(test_frictionless),
        cmocka_unit_test(test_chattering_guard),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
