/* test_friction.c: Coulomb friction: the return map (regimes, cone,
 * idempotence, objectivity, limits, derivatives), the link tangent in
 * stick and in slip against central differences (flat and curved facets,
 * small strain and finite deformation), the assembled tangent of both
 * multiplier laws, the Uzawa update, mu = 0 against frictionless, and the
 * velocity form (stiffness at fixed velocities, damping matrix against
 * differences in the velocities, agreement with the incremental form). */
#include "ffc_test.h"

#include <stdlib.h>
#include <string.h>

static void unit(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) v[i] /= l;
}

static void test_map_regimes(void **state)
{
    (void)state;
    const double n[3] = {0, 0, 1}, lam[3] = {0, 0, 7.0}; /* normal part of lambda ignored */
    ffc_fric f;
    const double r1[3] = {1e-3, 0, 0};
    assert_int_equal(ffc_friction_map(n, lam, r1, 0.5, 100.0, 1.0, &f), FFC_OK);
    assert_int_equal(f.state, FFC_FRIC_STICK);
    assert_close(f.t[0], 0.1, 1e-15);
    assert_close(f.t[1], 0.0, 0.0);
    assert_close(f.t[2], 0.0, 1e-15);
    const double r2[3] = {0, -1e-2, 0};
    assert_int_equal(ffc_friction_map(n, lam, r2, 0.5, 100.0, 1.0, &f), FFC_OK);
    assert_int_equal(f.state, FFC_FRIC_SLIP);
    assert_close(f.t[1], -0.5, 1e-15);
    assert_close(f.dt_dtn[1], -0.5, 1e-15);
    /* open: no pressure, no traction */
    assert_int_equal(ffc_friction_map(n, lam, r2, 0.5, 100.0, 0.0, &f), FFC_OK);
    assert_int_equal(f.state, FFC_FRIC_OPEN);
    for (int i = 0; i < 3; i++) assert_close(f.t[i], 0.0, 0.0);
}

static void test_map_limits(void **state)
{
    (void)state;
    const double n[3] = {0, 1, 0}, z[3] = {0, 0, 0}, r[3] = {0.3, 0, 0.1};
    ffc_fric f;
    /* no trial traction and no pressure: no division by zero */
    assert_int_equal(ffc_friction_map(n, z, z, 0.3, 10.0, 0.0, &f), FFC_OK);
    assert_int_equal(f.state, FFC_FRIC_OPEN);
    /* mu = 0 with pressure, with and without slip: T = 0, finite derivatives */
    for (int k = 0; k < 2; k++) {
        assert_int_equal(ffc_friction_map(n, z, k ? r : z, 0.0, 10.0, 2.0, &f), FFC_OK);
        assert_int_equal(f.state, FFC_FRIC_SLIP);
        for (int i = 0; i < 3; i++) {
            assert_close(f.t[i], 0.0, 0.0);
            assert_true(isfinite(f.dt_dtn[i]));
            for (int j = 0; j < 3; j++) assert_true(f.dt_dr[i][j] == 0.0 && f.dt_dn[i][j] == 0.0);
        }
    }
    /* tiny pressure and tiny slip: bounded traction, no NaN */
    const double rt[3] = {1e-300, 0, 0};
    assert_int_equal(ffc_friction_map(n, z, rt, 0.3, 10.0, 1e-300, &f), FFC_OK);
    for (int i = 0; i < 3; i++) assert_true(isfinite(f.t[i]) && fabs(f.t[i]) <= 1e-299);
    /* bad input */
    assert_int_equal(ffc_friction_map(n, z, r, -0.1, 10.0, 1.0, &f), FFC_ERR_VALUE);
    assert_int_equal(ffc_friction_map(n, z, r, 0.3, 0.0, 1.0, &f), FFC_ERR_VALUE);
    assert_int_equal(ffc_friction_map(n, z, r, 0.3, -1.0, 1.0, &f), FFC_ERR_VALUE);
    assert_int_equal(ffc_friction_map(n, z, r, INFINITY, 1.0, 1.0, &f), FFC_ERR_VALUE);
    const double rn[3] = {NAN, 0, 0};
    assert_int_equal(ffc_friction_map(n, z, rn, 0.3, 1.0, 1.0, &f), FFC_ERR_NONFINITE);
    assert_int_equal(ffc_friction_map(n, z, r, 0.3, 1.0, NAN, &f), FFC_ERR_NONFINITE);
    assert_int_equal(ffc_friction_map(NULL, z, r, 0.3, 1.0, 1.0, &f), FFC_ERR_NULL);
}

/* inside the cone, tangent, idempotent, objective: random inputs */
static void test_map_properties(void **state)
{
    (void)state;
    uint64_t s = 11;
    for (int trial = 0; trial < 200; trial++) {
        double n[3], lam[3], r[3];
        for (int i = 0; i < 3; i++) {
            n[i] = test_rand(&s, -1, 1);
            lam[i] = test_rand(&s, -2, 2);
            r[i] = test_rand(&s, -0.02, 0.02);
        }
        unit(n);
        const double mu = test_rand(&s, 0.05, 1.0), et = test_rand(&s, 10, 300), tn = test_rand(&s, 0.1, 5);
        ffc_fric f, g;
        assert_int_equal(ffc_friction_map(n, lam, r, mu, et, tn, &f), FFC_OK);
        const double tt = sqrt(f.t[0] * f.t[0] + f.t[1] * f.t[1] + f.t[2] * f.t[2]);
        assert_true(tt <= mu * tn * (1 + 1e-14));
        assert_close(f.t[0] * n[0] + f.t[1] * n[1] + f.t[2] * n[2], 0.0, 1e-14 * (1 + tt));
        /* the map applied to its own result with no further slip */
        const double z[3] = {0, 0, 0};
        assert_int_equal(ffc_friction_map(n, f.t, z, mu, et, tn, &g), FFC_OK);
        for (int i = 0; i < 3; i++) assert_close(g.t[i], f.t[i], 1e-14 * (1 + tt));
        /* rotate the scene: the traction rotates with it */
        double Rm[3][3], ax[3] = {test_rand(&s, -1, 1), test_rand(&s, -1, 1), test_rand(&s, -1, 1)};
        test_rotation(ax, test_rand(&s, 0, 6.28), Rm);
        double nr[3], lr[3], rr[3], tr[3];
        const double o[3] = {0, 0, 0};
        test_move(Rm, o, n, nr);
        test_move(Rm, o, lam, lr);
        test_move(Rm, o, r, rr);
        test_move(Rm, o, f.t, tr);
        assert_int_equal(ffc_friction_map(nr, lr, rr, mu, et, tn, &g), FFC_OK);
        assert_int_equal(g.state, f.state);
        for (int i = 0; i < 3; i++) assert_close(g.t[i], tr[i], 1e-13 * (1 + tt));
    }
}

/* derivatives of the map against central differences (h = 1e-7 on O(1)
 * inputs: error ~1e-14/h + h^2 ~ 1e-7 of the scale at worst; 1e-6 bound) */
static void test_map_derivatives(void **state)
{
    (void)state;
    uint64_t s = 12;
    for (int trial = 0; trial < 40; trial++) {
        double n[3], lam[3], r[3];
        for (int i = 0; i < 3; i++) {
            n[i] = test_rand(&s, -1, 1);
            lam[i] = test_rand(&s, -1, 1);
            r[i] = test_rand(&s, -0.01, 0.01);
        }
        unit(n);
        const double et = 100, tn = 2.0;
        ffc_fric f;
        assert_int_equal(ffc_friction_map(n, lam, r, 10.0, et, tn, &f), FFC_OK);
        const double ttr = sqrt(f.t[0] * f.t[0] + f.t[1] * f.t[1] + f.t[2] * f.t[2]);
        /* stick (mu t_N = 2 |T_tr|) or slip (mu t_N = |T_tr| / 2) */
        const double mu = (trial % 2 ? 0.5 : 2.0) * ttr / tn;
        assert_int_equal(ffc_friction_map(n, lam, r, mu, et, tn, &f), FFC_OK);
        assert_int_equal(f.state, trial % 2 ? FFC_FRIC_SLIP : FFC_FRIC_STICK);
        const double h = 1e-7;
        double err = 0, scale = 1e-300;
        for (int j = 0; j < 7; j++) {
            double np[3], nm[3], rp[3], rm[3], tp = tn, tm = tn;
            memcpy(np, n, sizeof np); memcpy(nm, n, sizeof nm);
            memcpy(rp, r, sizeof rp); memcpy(rm, r, sizeof rm);
            if (j < 3) { rp[j] += h; rm[j] -= h; }
            else if (j < 6) { np[j - 3] += h; nm[j - 3] -= h; }
            else { tp += h; tm -= h; }
            ffc_fric a, b;
            assert_int_equal(ffc_friction_map(np, lam, rp, mu, et, tp, &a), FFC_OK);
            assert_int_equal(ffc_friction_map(nm, lam, rm, mu, et, tm, &b), FFC_OK);
            for (int i = 0; i < 3; i++) {
                const double fd = (a.t[i] - b.t[i]) / (2 * h);
                const double an = j < 3 ? f.dt_dr[i][j] : j < 6 ? f.dt_dn[i][j - 3] : f.dt_dtn[i];
                err = fmax(err, fabs(fd - an));
                scale = fmax(scale, fabs(an));
            }
        }
        if (!(err <= 1e-6 * scale)) fail_msg("map derivative error %.3g of %.3g (trial %d)", err, scale, trial);
    }
}

/* ------------------------------------------------------------ one link */
typedef struct {
    int ns, nm;
    double Xs[6][3], Xs0[6][3], Ds[6][3], Xm[6][3], Dm[6][3]; /* D: motion (x - x^n, or velocity) */
    double xs[2], w, lambda, lam_t[3];
    ffc_effects fx;
    ffc_law law;
} fcase;

static int fc_eval(const fcase *c, ffc_link_state *st, double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF])
{
    return ffc_link_contact(&c->fx, c->ns, (const double(*)[3])c->Xs, (const double(*)[3])c->Xs0,
                            (const double(*)[3])c->Ds, c->xs, c->w, c->nm, (const double(*)[3])c->Xm,
                            (const double(*)[3])c->Dm, c->lambda, c->lam_t, &c->law, st, R, K);
}

static double *fc_coord(fcase *c, int k)
{
    return k < 3 * c->ns ? &c->Xs[k / 3][k % 3] : &c->Xm[(k - 3 * c->ns) / 3][k % 3];
}

static double *fc_motion(fcase *c, int k)
{
    return k < 3 * c->ns ? &c->Ds[k / 3][k % 3] : &c->Dm[(k - 3 * c->ns) / 3][k % 3];
}

/* a slave point pressed on a (flat or curved) master facet, moved since the
 * previous step by random increments; regime 1 stick, 2 slip */
static void fc_make(fcase *c, int ns, int nm, int finite, int regime, uint64_t *s)
{
    memset(c, 0, sizeof *c);
    c->ns = ns;
    c->nm = nm;
    c->fx.finite_def = finite;
    c->fx.friction = 1;
    ffc_point g;
    test_link_master(nm, s, c->Xm, &g, c->xs);
    const double off = test_rand(s, -0.03, -0.005);
    test_link_slave(ns, &g, c->xs, off, s, c->Xs, c->Xs0);
    for (int a = 0; a < 6; a++)
        for (int i = 0; i < 3; i++) {
            c->Ds[a][i] = test_rand(s, -0.02, 0.02);
            c->Dm[a][i] = test_rand(s, -0.02, 0.02);
        }
    for (int i = 0; i < 3; i++) c->lam_t[i] = test_rand(s, -0.5, 0.5);
    c->w = 0.5;
    c->lambda = test_rand(s, 0.0, 1.0);
    c->law.eps_n = 50.0;
    c->law.eps_t = 40.0;
    /* the trial traction with a huge mu (stick), then mu away from the
     * stick/slip boundary by a factor 2 */
    c->law.mu = 1e6;
    ffc_link_state st;
    double R[FFC_MAXDOF];
    assert_int_equal(fc_eval(c, &st, R, NULL), FFC_OK);
    assert_true(st.active && st.fstate == FFC_FRIC_STICK);
    const double ttr = sqrt(st.t[0] * st.t[0] + st.t[1] * st.t[1] + st.t[2] * st.t[2]);
    c->law.mu = (regime == FFC_FRIC_STICK ? 2.0 : 0.5) * ttr / st.tn;
}

/* Central differences, h = 1e-6 on unit-size facets (as test_link.c).
 * A change h of a nodal position changes the node's motion by cm h (1 for
 * x - x^n; the integrator's dv/du for a velocity) and the motion alone by
 * cv h; the matrix checked is K (cm = coef, cv = 0: law->dvdu = coef in
 * the velocity form) or the damping matrix D (cm = 0, cv = 1: the
 * difference of the tangents with dvdu = 1 and dvdu = 0). */
static void fc_check_motion(fcase *c, int regime, double cm, int damping)
{
    const double h = 1e-6;
    ffc_link_state st;
    double R[FFC_MAXDOF], K[FFC_MAXDOF][FFC_MAXDOF];
    if (damping) {
        double K0[FFC_MAXDOF][FFC_MAXDOF];
        c->law.dvdu = 0.0;
        assert_int_equal(fc_eval(c, &st, R, K0), FFC_OK);
        c->law.dvdu = 1.0;
        assert_int_equal(fc_eval(c, &st, R, K), FFC_OK);
        for (int k = 0; k < FFC_MAXDOF; k++)
            for (int l = 0; l < FFC_MAXDOF; l++) K[k][l] -= K0[k][l];
    } else {
        if (c->fx.dynamic) c->law.dvdu = cm;
        assert_int_equal(fc_eval(c, &st, R, K), FFC_OK);
    }
    assert_int_equal(st.fstate, regime);
    const int nd = 3 * (c->ns + c->nm);
    double err = 0, scale = 0, asym = 0;
    for (int l = 0; l < nd; l++) {
        double *x = fc_coord(c, l), x0 = *x, *d = fc_motion(c, l), d0 = *d, Rp[FFC_MAXDOF], Rm[FFC_MAXDOF];
        const double hx = damping ? 0.0 : h, hd = damping ? h : cm * h;
        ffc_link_state sp, sm;
        *x = x0 + hx; *d = d0 + hd; assert_int_equal(fc_eval(c, &sp, Rp, NULL), FFC_OK);
        *x = x0 - hx; *d = d0 - hd; assert_int_equal(fc_eval(c, &sm, Rm, NULL), FFC_OK);
        *x = x0; *d = d0;
        assert_int_equal(sp.fstate, regime);
        assert_int_equal(sm.fstate, regime);
        for (int k = 0; k < nd; k++) {
            err = fmax(err, fabs((Rp[k] - Rm[k]) / (2 * h) - K[k][l]));
            scale = fmax(scale, fabs(K[k][l]));
            asym = fmax(asym, fabs(K[k][l] - K[l][k]));
        }
    }
    if (!(err <= 1e-6 * scale))
        fail_msg("friction %s error %.3g of scale %.3g (ns %d nm %d finite %d dynamic %d regime %d)",
                 damping ? "damping matrix" : "tangent", err, scale, c->ns, c->nm, c->fx.finite_def, c->fx.dynamic,
                 regime);
    if (!c->fx.dynamic) assert_true(asym > 1e-6 * scale); /* friction makes it non-symmetric */
}

static void fc_check(fcase *c, int regime)
{
    fc_check_motion(c, regime, 1.0, 0);
}

static void test_link_tangent(void **state)
{
    (void)state;
    uint64_t s = 21;
    for (int regime = FFC_FRIC_STICK; regime <= FFC_FRIC_SLIP; regime++)
        for (int finite = 0; finite <= 1; finite++)
            for (int ns = 3; ns <= 6; ns += 3)
                for (int nm = 3; nm <= 6; nm += 3)
                    for (int trial = 0; trial < 3; trial++) {
                        fcase c;
                        fc_make(&c, ns, nm, finite, regime, &s);
                        fc_check(&c, regime);
                    }
}

/* The velocity form on one link, stick and slip, flat and curved facets:
 * K at fixed velocities (dvdu = 0), with an integrator's dv/du = 0.7, and
 * the damping matrix D = dR/dv. */
static void test_link_velocity_form(void **state)
{
    (void)state;
    uint64_t s = 25;
    for (int regime = FFC_FRIC_STICK; regime <= FFC_FRIC_SLIP; regime++)
        for (int finite = 0; finite <= 1; finite++)
            for (int nm = 3; nm <= 6; nm += 3)
                for (int trial = 0; trial < 2; trial++) {
                    fcase c;
                    fc_make(&c, 3, nm, finite, regime, &s);
                    c.fx.dynamic = 1;
                    c.law.dt = 0.01;
                    fc_check_motion(&c, regime, 0.0, 0);
                    fc_check_motion(&c, regime, 0.7, 0);
                    fc_check_motion(&c, regime, 0.0, 1);
                }
}

/* The velocity form with the backward-difference velocity v = (x - x^n) / dt,
 * eps_T dt and dv/du = 1 / dt is the incremental form: the same traction,
 * residual, slip and tangent (to round-off of the rescaling). */
static void test_velocity_matches_incremental(void **state)
{
    (void)state;
    uint64_t s = 26;
    for (int trial = 0; trial < 8; trial++) {
        fcase c;
        const int regime = trial % 2 ? FFC_FRIC_SLIP : FFC_FRIC_STICK;
        fc_make(&c, trial % 4 < 2 ? 3 : 6, 3, trial % 3 == 0, regime, &s);
        ffc_link_state a, b;
        double Ra[FFC_MAXDOF], Rb[FFC_MAXDOF], Ka[FFC_MAXDOF][FFC_MAXDOF], Kb[FFC_MAXDOF][FFC_MAXDOF];
        assert_int_equal(fc_eval(&c, &a, Ra, Ka), FFC_OK);
        const double dt = 0.05;
        fcase d = c;
        d.fx.dynamic = 1;
        d.law.dt = dt;
        d.law.dvdu = 1.0 / dt;
        d.law.eps_t = c.law.eps_t * dt;
        for (int k = 0; k < 6; k++)
            for (int i = 0; i < 3; i++) { d.Ds[k][i] = c.Ds[k][i] / dt; d.Dm[k][i] = c.Dm[k][i] / dt; }
        assert_int_equal(fc_eval(&d, &b, Rb, Kb), FFC_OK);
        assert_int_equal(b.fstate, a.fstate);
        assert_int_equal(a.fstate, regime);
        const int nd = 3 * (c.ns + c.nm);
        double rs = 0, ks = 0;
        for (int k = 0; k < nd; k++) {
            rs = fmax(rs, fabs(Ra[k]));
            for (int l = 0; l < nd; l++) ks = fmax(ks, fabs(Ka[k][l]));
        }
        for (int k = 0; k < nd; k++) {
            assert_close(Rb[k], Ra[k], 1e-13 * rs);
            for (int l = 0; l < nd; l++) assert_close(Kb[k][l], Ka[k][l], 1e-13 * ks);
        }
        for (int i = 0; i < 3; i++) {
            assert_close(b.slip[i], a.slip[i], 1e-15);
            assert_close(b.t[i], a.t[i], 1e-13 * (fabs(a.t[i]) + 1e-3));
        }
        /* bad time data: dt <= 0, dv/du < 0, NaN */
        d.law.dt = 0.0;
        assert_int_equal(fc_eval(&d, &b, Rb, NULL), FFC_ERR_VALUE);
        d.law.dt = dt;
        d.law.dvdu = -1.0;
        assert_int_equal(fc_eval(&d, &b, Rb, NULL), FFC_ERR_VALUE);
        d.law.dvdu = NAN;
        assert_int_equal(fc_eval(&d, &b, Rb, NULL), FFC_ERR_VALUE);
    }
}

/* mu = 0 with friction on: the frictionless residual and tangent, bit for
 * bit; and the slave and master forces balance (action = reaction) */
static void test_link_mu_zero_and_balance(void **state)
{
    (void)state;
    uint64_t s = 22;
    for (int trial = 0; trial < 8; trial++) {
        fcase c;
        fc_make(&c, trial % 2 ? 6 : 3, trial % 4 < 2 ? 3 : 6, trial % 3 == 0, FFC_FRIC_SLIP, &s);
        ffc_link_state a, b;
        double Ra[FFC_MAXDOF], Rb[FFC_MAXDOF], Ka[FFC_MAXDOF][FFC_MAXDOF], Kb[FFC_MAXDOF][FFC_MAXDOF];
        assert_int_equal(fc_eval(&c, &a, Ra, Ka), FFC_OK);
        const double mu = c.law.mu;
        c.law.mu = 0.0;
        assert_int_equal(fc_eval(&c, &b, Rb, Kb), FFC_OK);
        ffc_link_state n0;
        double Rn[FFC_MAXDOF], Kn[FFC_MAXDOF][FFC_MAXDOF];
        assert_int_equal(ffc_link_normal(&c.fx, c.ns, (const double(*)[3])c.Xs, (const double(*)[3])c.Xs0, c.xs, c.w,
                                         c.nm, (const double(*)[3])c.Xm, c.lambda, c.law.eps_n, &n0, Rn, Kn),
                         FFC_OK);
        const int nd = 3 * (c.ns + c.nm);
        for (int k = 0; k < nd; k++) {
            assert_true(Rb[k] == Rn[k]);
            for (int l = 0; l < nd; l++) assert_true(Kb[k][l] == Kn[k][l]);
        }
        /* with friction: total force on the link zero in each direction */
        double sum[3] = {0, 0, 0}, tot = 0;
        for (int k = 0; k < nd; k++) { sum[k % 3] += Ra[k]; tot += fabs(Ra[k]); }
        for (int i = 0; i < 3; i++) assert_close(sum[i], 0.0, 1e-14 * tot);
        /* slip traction on the cone */
        const double tt = sqrt(a.t[0] * a.t[0] + a.t[1] * a.t[1] + a.t[2] * a.t[2]);
        assert_close(tt, mu * a.tn, 1e-13 * tt);
    }
}

/* --------------------------------------------------- assembled tangents */
enum { NV = 41, NFM = 32, NFS = 18, NQ = 3, NL = NFS * NQ, CAP = 400000 };

typedef struct {
    double X[NV * 3], u[NV * 3], up[NV * 3], v[NV * 3];
    long Fm[NFM * 3], Fs[NFS * 3];
    ffc_link L[NL];
    double lam[NV > NL ? NV : NL], lam_t[NL * 3];
    ffc_pair P;
} ascene;

static void ascene_make(ascene *a, int nodal, uint64_t *s)
{
    test_pair_scene(a->X, a->Fm, a->Fs);
    double x[NV * 3];
    for (int i = 0; i < NV * 3; i++) {
        a->u[i] = test_rand(s, -0.002, 0.002);
        a->up[i] = a->u[i] - test_rand(s, -0.003, 0.003);
        x[i] = a->X[i] + a->u[i];
    }
    /* press the slave down so that most points are active */
    for (int v = 25; v < NV; v++) a->u[3 * v + 2] -= 0.004;
    for (int i = 0; i < NV * 3; i++) x[i] = a->X[i] + a->u[i];
    for (int i = 0; i < NV * 3; i++) a->v[i] = (a->u[i] - a->up[i]) / 0.01; /* velocity form: dt = 0.01 */
    ffc_tree *t;
    assert_int_equal(ffc_tree_build(3, NFM, a->Fm, NV, x, &t), FFC_OK);
    ffc_search_opts o = ffc_search_defaults();
    assert_int_equal(ffc_search(t, 3, NFS, a->Fs, NV, x, 2, &o, NL, a->L), NL);
    ffc_tree_free(t);
    memset(a->lam, 0, sizeof a->lam);
    const long nlam = nodal ? NV : NL;
    for (long k = 0; k < nlam; k++) a->lam[k] = (nodal && k < 25) ? 0.0 : test_rand(s, 0.0, 0.3);
    for (int k = 0; k < NL * 3; k++) a->lam_t[k] = test_rand(s, -0.05, 0.05);
    ffc_pair P = {3, NFS, a->Fs, 3, NFM, a->Fm, NV, a->X, a->u, a->up, a->v, NULL};
    a->P = P;
}

/* the assembled tangent of law, dense, added into K with the factor f */
static void assembled_dense(ascene *a, const ffc_effects *fx, const ffc_law *law, double f, double K[][NV * 3],
                            ffc_stats *st)
{
    long *Ti = malloc(CAP * sizeof *Ti), *Tj = malloc(CAP * sizeof *Tj), nt, bad;
    double *Tv = malloc(CAP * sizeof *Tv);
    double R[NV * 3] = {0};
    assert_int_equal(ffc_assemble(fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, law, R, CAP, Ti, Tj, Tv, &nt, st, &bad),
                     FFC_OK);
    for (long k = 0; k < nt; k++) K[Ti[k]][Tj[k]] += f * Tv[k];
    free(Ti); free(Tj); free(Tv);
}

/* Central differences of the assembled residual, h = 1e-7 against
 * displacements ~1e-2 (as the nodal test of test_link.c).  A change h of
 * u changes the velocities by law->dvdu h in the velocity form; with
 * damping the matrix checked is D = dR/dv (the tangent with dvdu = 1
 * minus the one with dvdu = 0) against changes of v alone. */
static void assembled_check_motion(ascene *a, const ffc_effects *fx, const ffc_law *law, int regime, int damping)
{
    static double K[NV * 3][NV * 3];
    long nt, bad;
    ffc_stats st;
    memset(K, 0, sizeof K);
    if (damping) {
        ffc_law l0 = *law, l1 = *law;
        l0.dvdu = 0.0;
        l1.dvdu = 1.0;
        assembled_dense(a, fx, &l1, 1.0, K, &st);
        assembled_dense(a, fx, &l0, -1.0, K, &st);
    } else
        assembled_dense(a, fx, law, 1.0, K, &st);
    assert_true(st.active > 0);
    /* all stick or all slip (counted per link, or per node for the nodal law) */
    assert_true((regime == FFC_FRIC_STICK ? st.stick : st.slip) > 0);
    assert_int_equal(regime == FFC_FRIC_STICK ? st.slip : st.stick, 0);
    const double h = 1e-7, hu = damping ? 0.0 : h, hv = damping ? h : fx->dynamic ? law->dvdu * h : 0.0;
    double err = 0, scale = 0;
    for (int l = 0; l < NV * 3; l++) {
        double Rp[NV * 3] = {0}, Rm[NV * 3] = {0}, u0 = a->u[l], v0 = a->v[l];
        ffc_stats sp, sm;
        a->u[l] = u0 + hu;
        a->v[l] = v0 + hv;
        assert_int_equal(ffc_assemble(fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, law, Rp, 0, NULL, NULL, NULL, &nt, &sp,
                                      &bad), FFC_OK);
        a->u[l] = u0 - hu;
        a->v[l] = v0 - hv;
        assert_int_equal(ffc_assemble(fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, law, Rm, 0, NULL, NULL, NULL, &nt, &sm,
                                      &bad), FFC_OK);
        a->u[l] = u0;
        a->v[l] = v0;
        assert_int_equal(sp.active, st.active);
        assert_int_equal(sm.active, st.active);
        assert_int_equal(sp.stick, st.stick);
        assert_int_equal(sm.stick, st.stick);
        for (int k = 0; k < NV * 3; k++) {
            err = fmax(err, fabs((Rp[k] - Rm[k]) / (2 * h) - K[k][l]));
            scale = fmax(scale, fabs(K[k][l]));
        }
    }
    if (!(err <= 1e-6 * scale))
        fail_msg("assembled friction %s error %.3g of scale %.3g (nodal %d, dynamic %d, stick %ld slip %ld)",
                 damping ? "damping matrix" : "tangent", err, scale, law->nodal, fx->dynamic, st.stick, st.slip);
}

static void assembled_check(ascene *a, const ffc_effects *fx, const ffc_law *law, int regime)
{
    assembled_check_motion(a, fx, law, regime, 0);
}

static void test_assembled_tangent(void **state)
{
    (void)state;
    uint64_t s = 23;
    /* nodal 2: the nodal law with the friction sums in the dual basis (tdual) */
    for (int nodal = 0; nodal <= 2; nodal++)
        for (int finite = 0; finite <= 1; finite++) {
            ascene *a = malloc(sizeof *a);
            ascene_make(a, nodal > 0, &s);
            ffc_effects fx = {1, 0, finite};
            /* all stick (a huge mu), all slip (eps_T |r| >> mu t_N) */
            ffc_law stick = {60, nodal > 0, 0, 1e6, 5.0, 0.0, 0.0, NULL, NULL, 0, NULL, nodal == 2, NULL, NULL, NULL};
            assembled_check(a, &fx, &stick, FFC_FRIC_STICK);
            ffc_law slip = {60, nodal > 0, 0, 0.3, 2000.0, 0.0, 0.0, NULL, NULL, 0, NULL, nodal == 2, NULL, NULL, NULL};
            assembled_check(a, &fx, &slip, FFC_FRIC_SLIP);
            free(a);
        }
}

/* Shares of the links (ffc_law.lsel, nsum): the pair's links split by
 * slave facet into 2 and 3 shares (one of the 3 with no facet at all), the
 * node sums completed by nsum (simulated: a first pass records each
 * share's partial sums, the second hands every share their sum in share
 * order).  The shares' residuals, ranked terms (U and V columns, as
 * triplets) and link statistics add up to the whole assembly's (to
 * round-off of the other summation order, 1e-13), their node statistics
 * equal it; frictionless, all stick and all slip. */
typedef struct {
    int rec;              /* 1: record the share's sums and stop; 0: hand over the total */
    int share, nshare;
    double *part[3];      /* [8 nn] each share's partial sums */
    long n;
    int calls, st_seen;
} shares_ctx;

enum { SHARES_STOP = -900 };

static int shares_nsum(void *ctx, int st, long n, double buf[])
{
    shares_ctx *c = ctx;
    c->calls++;
    c->st_seen = st;
    if (st) return st;
    if (c->rec) {
        c->n = n;
        c->part[c->share] = malloc((size_t)(n > 0 ? n : 1) * sizeof(double));
        memcpy(c->part[c->share], buf, (size_t)n * sizeof(double));
        return SHARES_STOP;
    }
    assert_int_equal(n, c->n);
    for (long i = 0; i < n; i++) {
        double t = 0.0;
        for (int r = 0; r < c->nshare; r++) t += c->part[r][i];
        buf[i] = t;
    }
    return FFC_OK;
}

/* the ranked terms as dense columns D[row][col] (col < 2 nterm) */
static void shares_dense(const long *Ti, const long *Tj, const double *Tv, long nt, double *D, long ncol)
{
    for (long k = 0; k < nt; k++) {
        assert_true(Tj[k] >= 0 && Tj[k] < ncol);
        D[Ti[k] * ncol + Tj[k]] += Tv[k];
    }
}

static void test_assembled_shares(void **state)
{
    (void)state;
    uint64_t s = 37;
    enum { NCOL = 2 * 4 * NV };   /* at most 4 terms a node (normal, 3 friction) */
    for (int regime = 0; regime <= 2; regime++) {     /* frictionless, stick, slip */
        ascene *a = malloc(sizeof *a);
        ascene_make(a, 1, &s);
        ffc_effects fx = {regime > 0, 0, 0};
        ffc_law law = {60, 1, FFC_TANGENT_RANKED, regime == 1 ? 1e6 : 0.3, regime == 1 ? 5.0 : 2000.0, 0.0, 0.0, NULL, NULL, 0, NULL, 0,
                       NULL, NULL, NULL};
        long *Ti = malloc(CAP * sizeof *Ti), *Tj = malloc(CAP * sizeof *Tj), nt, bad;
        double *Tv = malloc(CAP * sizeof *Tv);
        double *Dw = calloc((size_t)NV * 3 * NCOL, sizeof *Dw), *Ds = calloc((size_t)NV * 3 * NCOL, sizeof *Ds);
        double Rw[NV * 3] = {0};
        ffc_stats sw;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &law, Rw, CAP, Ti, Tj, Tv, &nt, &sw,
                                      &bad), FFC_OK);
        assert_true(sw.active > 0);
        if (regime) assert_true((regime == 1 ? sw.stick : sw.slip) > 0);
        shares_dense(Ti, Tj, Tv, nt, Dw, NCOL);
        for (int nshare = 2; nshare <= 3; nshare++) {
            unsigned char sel[3][NL];
            for (int r = 0; r < nshare; r++)
                for (int k = 0; k < NL; k++) {
                    const long f = a->L[k].sf;
                    /* 3 shares: the first half, none, the second half */
                    const int owner = nshare == 2 ? f * 2 / NFS : (f < NFS / 2 ? 0 : 2);
                    sel[r][k] = owner == r;
                }
            shares_ctx c = {1, 0, nshare, {NULL, NULL, NULL}, 0, 0, 0};
            ffc_law ls = law;
            ls.nsum = shares_nsum;
            ls.nsum_ctx = &c;
            for (int r = 0; r < nshare; r++) {   /* pass 1: each share's partial sums */
                double R[NV * 3] = {0};
                c.share = r;
                ls.lsel = sel[r];
                assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &ls, R, CAP, Ti, Tj, Tv, &nt,
                                              NULL, &bad), SHARES_STOP);
            }
            c.rec = 0;
            double Rs[NV * 3] = {0};
            memset(Ds, 0, (size_t)NV * 3 * NCOL * sizeof *Ds);
            long linked = 0, active = 0;
            double force[3] = {0, 0, 0}, force_t[3] = {0, 0, 0}, max_pen = 0, max_tn = 0;
            for (int r = 0; r < nshare; r++) {   /* pass 2: the shares with the total sums */
                double R[NV * 3] = {0};
                ffc_stats st;
                c.share = r;
                c.calls = 0;
                ls.lsel = sel[r];
                assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &ls, R, CAP, Ti, Tj, Tv, &nt,
                                              &st, &bad), FFC_OK);
                assert_int_equal(c.calls, 1);
                if (nshare == 3 && r == 1) {      /* no facet: nothing */
                    assert_int_equal(st.linked, 0);
                    for (int i = 0; i < NV * 3; i++) assert_true(R[i] == 0.0);
                    for (long k = 0; k < nt; k++) assert_true(Tv[k] == 0.0);
                }
                for (int i = 0; i < NV * 3; i++) Rs[i] += R[i];
                shares_dense(Ti, Tj, Tv, nt, Ds, NCOL);
                linked += st.linked;
                active += st.active;
                for (int i = 0; i < 3; i++) { force[i] += st.force[i]; force_t[i] += st.force_t[i]; }
                max_pen = fmax(max_pen, st.max_pen);
                max_tn = fmax(max_tn, st.max_tn);
                /* the node statistics: every share's are the whole's */
                assert_int_equal(st.stick, sw.stick);
                assert_int_equal(st.slip, sw.slip);
                assert_true(st.max_pen_node == sw.max_pen_node);
                assert_close(st.dissipation, sw.dissipation, 1e-13 * (fabs(sw.dissipation) + 1e-300));
            }
            double rs = 0, ds = 0, fs = 0;
            for (int i = 0; i < NV * 3; i++) rs = fmax(rs, fabs(Rw[i]));
            for (long i = 0; i < (long)NV * 3 * NCOL; i++) ds = fmax(ds, fabs(Dw[i]));
            for (int i = 0; i < NV * 3; i++) assert_close(Rs[i], Rw[i], 1e-13 * rs);
            for (long i = 0; i < (long)NV * 3 * NCOL; i++) assert_close(Ds[i], Dw[i], 1e-13 * ds);
            assert_int_equal(linked, sw.linked);
            assert_int_equal(active, sw.active);
            for (int i = 0; i < 3; i++) {
                fs = fmax(fs, fabs(sw.force[i]) + fabs(sw.force_t[i]));
            }
            for (int i = 0; i < 3; i++) {
                assert_close(force[i], sw.force[i], 1e-13 * fs);
                assert_close(force_t[i], sw.force_t[i], 1e-13 * fs);
            }
            assert_true(max_pen == sw.max_pen);
            assert_true(max_tn == sw.max_tn);
            for (int r = 0; r < nshare; r++) free(c.part[r]);
        }
        /* refused: pointwise multipliers, no nsum, a consistent tangent */
        unsigned char all[NL];
        memset(all, 1, sizeof all);
        shares_ctx c = {0, 0, 1, {NULL, NULL, NULL}, 0, 0, 0};
        ffc_law ls = law;
        ls.lsel = all;
        double R[NV * 3];
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &ls, R, CAP, Ti, Tj, Tv, &nt, NULL, &bad),
                         FFC_ERR_NULL);
        ls.nsum = shares_nsum;
        ls.nsum_ctx = &c;
        ls.tangent = FFC_TANGENT_CONSISTENT;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &ls, R, CAP, Ti, Tj, Tv, &nt, NULL, &bad),
                         FFC_ERR_VALUE);
        ls.nodal = 0;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &ls, R, CAP, Ti, Tj, Tv, &nt, NULL, &bad),
                         FFC_ERR_VALUE);
        assert_int_equal(c.calls, 0);
        free(Ti); free(Tj); free(Tv); free(Dw); free(Ds); free(a);
    }
}

/* Nodal friction with prescribed directions (ffc_law.fixed): every slave
 * node's x dof held at zero (x lies in the contact plane): the tangent of
 * the dropped law against central differences, all stick and all slip,
 * small strain and finite deformation; the update leaves lambda_T,x = 0 at
 * every slave node, and a node without a prescribed dof is unchanged; the
 * same dofs moved (fixed < 0) drop nothing. */
static void test_assembled_fixed_direction(void **state)
{
    (void)state;
    uint64_t s = 31;
    static double fixed[NV * 3];
    memset(fixed, 0, sizeof fixed);
    for (int v = 25; v < NV; v++) fixed[3 * v] = 1.0;      /* the slave nodes' x */
    for (int finite = 0; finite <= 1; finite++) {
        ascene *a = malloc(sizeof *a);
        ascene_make(a, 1, &s);
        ffc_effects fx = {1, 0, finite};
        ffc_law stick = {60, 1, 0, 1e6, 5.0, 0.0, 0.0, fixed, NULL, 0, NULL, 0, NULL, NULL, NULL};
        assembled_check(a, &fx, &stick, FFC_FRIC_STICK);
        ffc_law slip = {60, 1, 0, 0.3, 2e5, 0.0, 0.0, fixed, NULL, 0, NULL, 0, NULL, NULL, NULL};   // (the y slip alone must exceed the cone)
        assembled_check(a, &fx, &slip, FFC_FRIC_SLIP);
        /* the update: no x traction at any slave node; the residual differs
         * from the undropped law's (the x friction is gone) */
        long bad;
        ffc_stats st;
        double lt0[NL * 3];
        memcpy(lt0, a->lam_t, sizeof lt0);
        assert_int_equal(ffc_augment(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &slip, &st, &bad), FFC_OK);
        assert_true(st.slip > 0);
        for (int v = 25; v < NV; v++) assert_true(a->lam_t[3 * v] == 0.0);
        double tymax = 0;
        for (int v = 25; v < NV; v++) tymax = fmax(tymax, fabs(a->lam_t[3 * v + 1]));
        assert_true(tymax > 0.0);
        memcpy(a->lam_t, lt0, sizeof lt0);
        ffc_law plain = slip;
        plain.fixed = NULL;
        double R0[NV * 3] = {0}, R1[NV * 3] = {0};
        long nt;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &plain, R0, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_OK);
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &slip, R1, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_OK);
        double d = 0;
        for (int i = 0; i < NV * 3; i++) d = fmax(d, fabs(R1[i] - R0[i]));
        assert_true(d > 1e-6);
        /* the same dofs moved (fixed < 0: a face pushed along the contact)
         * keep their friction: the plain law's residual, bit for bit */
        static double moved[NV * 3];
        for (int i = 0; i < NV * 3; i++) moved[i] = -fixed[i];
        ffc_law pushed = slip;
        pushed.fixed = moved;
        double R2[NV * 3] = {0};
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &pushed, R2, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_OK);
        for (int i = 0; i < NV * 3; i++) assert_true(R2[i] == R0[i]);
        free(a);
    }
}

/* The velocity form assembled, both laws, all stick and all slip: the
 * tangent with the integrator's dv/du = 50 (dt 0.01), and the damping
 * matrix; with v = (u - u^n) / dt, eps_T dt and dv/du = 1 / dt the
 * residual equals the incremental one. */
static void test_assembled_velocity_form(void **state)
{
    (void)state;
    uint64_t s = 27;
    const double dt = 0.01;
    for (int nodal = 0; nodal <= 1; nodal++) {
        ascene *a = malloc(sizeof *a);
        ascene_make(a, nodal, &s);
        ffc_effects fx = {1, 1, 0};
        ffc_law stick = {60, nodal, 0, 1e6, 5.0 * dt, dt, 50.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
        assembled_check_motion(a, &fx, &stick, FFC_FRIC_STICK, 0);
        assembled_check_motion(a, &fx, &stick, FFC_FRIC_STICK, 1);
        ffc_law slip = {60, nodal, 0, 0.3, 2000.0 * dt, dt, 50.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
        assembled_check_motion(a, &fx, &slip, FFC_FRIC_SLIP, 0);
        assembled_check_motion(a, &fx, &slip, FFC_FRIC_SLIP, 1);
        /* agreement with the incremental form (ascene_make: v = (u - u^n) / 0.01) */
        ffc_effects qs = {1, 0, 0};
        ffc_law inc = slip;
        inc.eps_t = 2000.0;
        slip.dvdu = 1.0 / dt;
        double R0[NV * 3] = {0}, R1[NV * 3] = {0};
        long nt, bad;
        ffc_stats s0, s1;
        assert_int_equal(ffc_assemble(&qs, &a->P, 2, NL, a->L, a->lam, a->lam_t, &inc, R0, 0, NULL, NULL, NULL, &nt, &s0, &bad), FFC_OK);
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &slip, R1, 0, NULL, NULL, NULL, &nt, &s1, &bad), FFC_OK);
        double rs = 0;
        for (int i = 0; i < NV * 3; i++) rs = fmax(rs, fabs(R0[i]));
        for (int i = 0; i < NV * 3; i++) assert_close(R1[i], R0[i], 1e-12 * rs);
        assert_close(s1.dissipation, s0.dissipation, 1e-12 * fabs(s0.dissipation));
        assert_int_equal(s1.slip, s0.slip);
        /* the velocity form reads v, not u_prev; a missing or NaN v and a bad dt are refused */
        a->P.u_prev = NULL;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &slip, R1, 0, NULL, NULL, NULL, &nt, &s1, &bad), FFC_OK);
        a->P.v = NULL;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &slip, R1, 0, NULL, NULL, NULL, &nt, &s1, &bad), FFC_ERR_NULL);
        a->P.v = a->v;
        a->v[5] = NAN;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &slip, R1, 0, NULL, NULL, NULL, &nt, &s1, &bad), FFC_ERR_NONFINITE);
        a->v[5] = 0.0;
        slip.dt = -dt;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &slip, R1, 0, NULL, NULL, NULL, &nt, &s1, &bad), FFC_ERR_VALUE);
        free(a);
    }
}

/* Uzawa update: lam_t becomes the traction (tangent, inside the cone);
 * friction off or mu = 0 leaves the frictionless result unchanged */
static void test_augment(void **state)
{
    (void)state;
    uint64_t s = 24;
    for (int nodal = 0; nodal <= 1; nodal++) {
        ascene *a = malloc(sizeof *a);
        ascene_make(a, nodal, &s);
        ffc_effects fx = {1, 0, 0};
        ffc_law law = {60, nodal, 0, 0.3, 30.0, 0.0, 0.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
        double P[NL * FFC_POINT_COLS], lt0[NL * 3];
        long bad;
        assert_int_equal(ffc_points(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &law, P, &bad), FFC_OK);
        memcpy(lt0, a->lam_t, sizeof lt0);
        ffc_stats st;
        assert_int_equal(ffc_augment(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &law, &st, &bad), FFC_OK);
        assert_true(st.active > 0 && (nodal ? st.stick + st.slip > 0 : st.stick + st.slip == st.active));
        assert_true(st.max_dlam_t > 0);
        double ft[3] = {0, 0, 0};
        for (int k = 0; k < NL; k++) {
            const double *row = P + k * FFC_POINT_COLS;
            if (row[5] > 0)
                for (int i = 0; i < 3; i++) ft[i] += row[8 + i] * row[6];
            if (nodal) continue;
            /* pointwise: the update is the traction the point reported (on
             * the slave: -T), inside the cone of its pressure */
            const double *t = a->lam_t + 3 * k;
            for (int i = 0; i < 3; i++) assert_close(t[i], -row[8 + i], 1e-14);
            const double tt = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
            assert_true(tt <= 0.3 * row[4] * (1 + 1e-13));
            if (!(row[5] > 0)) assert_true(tt == 0.0);
        }
        /* nodal: the master nodes (0..24) keep their entries (another pair's),
         * the slave nodes' lie inside the cone of the updated nodal pressure */
        if (nodal)
            for (int k = 0; k < 3 * 25; k++) assert_true(a->lam_t[k] == lt0[k]);
        if (nodal)
            for (int v = 25; v < NV; v++) {
                const double *t = a->lam_t + 3 * v;
                const double tt = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
                assert_true(tt <= 0.3 * a->lam[v] * (1 + 1e-13));
            }
        for (int i = 0; i < 3; i++) assert_close(ft[i], st.force_t[i], 1e-13);
        /* mu = 0 (friction on) equals friction off */
        ffc_law l0 = law, l1 = law;
        l0.mu = 0.0;
        ffc_effects off = {0, 0, 0};
        double R0[NV * 3] = {0}, R1[NV * 3] = {0};
        long nt;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &l0, R0, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_OK);
        assert_int_equal(ffc_assemble(&off, &a->P, 2, NL, a->L, a->lam, NULL, &l1, R1, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_OK);
        for (int i = 0; i < NV * 3; i++) assert_true(R0[i] == R1[i]);
        /* bad input: negative mu, zero eps_t, non-finite history */
        ffc_law bad_mu = law, bad_et = law;
        bad_mu.mu = -0.1;
        bad_et.eps_t = 0.0;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &bad_mu, R0, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_ERR_VALUE);
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &bad_et, R0, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_ERR_VALUE);
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, NULL, &law, R0, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_ERR_NULL);
        a->lam_t[7] = NAN;
        assert_int_equal(ffc_assemble(&fx, &a->P, 2, NL, a->L, a->lam, a->lam_t, &law, R0, 0, NULL, NULL, NULL, &nt, &st, &bad), FFC_ERR_NONFINITE);
        assert_int_equal(bad, 2);
        free(a);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_map_regimes),
        cmocka_unit_test(test_map_limits),
        cmocka_unit_test(test_map_properties),
        cmocka_unit_test(test_map_derivatives),
        cmocka_unit_test(test_link_tangent),
        cmocka_unit_test(test_link_mu_zero_and_balance),
        cmocka_unit_test(test_link_velocity_form),
        cmocka_unit_test(test_velocity_matches_incremental),
        cmocka_unit_test(test_assembled_tangent),
        cmocka_unit_test(test_assembled_shares),
        cmocka_unit_test(test_assembled_fixed_direction),
        cmocka_unit_test(test_assembled_velocity_form),
        cmocka_unit_test(test_augment),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
