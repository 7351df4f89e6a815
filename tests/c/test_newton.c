/* test_newton.c: the condensed Newton (ffc_scene_newton) against Newton on
 * the full system with dense solves, frictionless and with friction
 * (stick and slip), a body held only by contact, its convergence order,
 * and bad input. */
#include <stdlib.h>
#include <string.h>

#include "ffc_test.h"

/* A slave unit square (nodes 0-3, two facets facing down) penetrating by
 * D a master unit square (nodes 4-7, facing up) at z = 0; a third square
 * (nodes 8-11) off the contact, springs tying it to the master.  The bulk:
 * each node on a ground spring KG (dofs of the slave square: KGS, 0 for a
 * body held only by contact), springs KS between the nodes of each square,
 * and the master's node 4 x-dof a Dirichlet row (TGV, value 0). */
#define NV 12
#define N (3 * NV)
static const double D = 2e-3, EPS = 2e3, KG = 100.0, KS = 300.0, TGV = 1e30;


static double XSHIFT = 0.0; /* the slave square's offset along x */
static double ZSLAVE = -D;  /* the slave square's height (-D: penetrating by D) */
static double KXZ = 0.0;    /* a coupling of the x and z dofs of each slave node (< its ground springs) */
static int METHOD = FFC_METHOD_AL; /* the pair's method */

/* a spring KS between dofs i and j: four triplets at *t */
static void spring(long i, long j, long Ti[], long Tj[], double Tv[], long *t)
{
    const long p[4][2] = {{i, i}, {j, j}, {i, j}, {j, i}};
    const double v[4] = {KS, KS, -KS, -KS};
    for (int e = 0; e < 4; e++) { Ti[*t] = p[e][0]; Tj[*t] = p[e][1]; Tv[(*t)++] = v[e]; }
}

static ffc_scene *make(double mu, double kgs, long *nt, long Ti[], long Tj[], double Tv[], double Kd[N * N])
{
    double X[3 * NV];
    test_unit_square(ZSLAVE, X, 0);
    for (int a = 0; a < 4; a++) X[3 * a] += XSHIFT;
    test_unit_square(0.0, X, 4);
    test_unit_square(-1.0, X, 8);
    const long Fs[6] = {0, 2, 1, 0, 3, 2}, Fm[6] = {4, 5, 6, 4, 6, 7};
    ffc_effects fx = {mu > 0, 0, 0};
    ffc_scene *s = NULL;
    long bad = -1;
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
    ffc_pair_opts o = ffc_pair_defaults();
    o.eps_n = EPS;
    o.eps_t = EPS;
    o.mu = mu;
    o.qdeg = 2;
    o.method = METHOD;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs, 2, Fm, &o, &bad), 0);
    long t = 0;
    for (int i = 0; i < NV; i++)
        for (int c = 0; c < 3; c++) {
            const long d = 3 * i + c;
            Ti[t] = Tj[t] = d;
            Tv[t++] = (i < 4 ? kgs : KG) * (1.0 + 0.05 * d) + (d == 12 ? TGV : 0.0);
        }
    for (int sq = 0; sq < 3; sq++)
        for (int a = 0; a < 4; a++)
            for (int b = a + 1; b < 4; b++)
                for (int c = 0; c < 3; c++) spring(3 * (4 * sq + a) + c, 3 * (4 * sq + b) + c, Ti, Tj, Tv, &t);
    for (int a = 0; a < 4 && KXZ != 0.0; a++) { /* x-z coupling of the slave nodes */
        Ti[t] = 3 * a; Tj[t] = 3 * a + 2; Tv[t++] = KXZ;
        Ti[t] = 3 * a + 2; Tj[t] = 3 * a; Tv[t++] = KXZ;
    }
    for (int a = 0; a < 4; a++) /* master and third square tied */
        for (int c = 0; c < 3; c++) spring(3 * (4 + a) + c, 3 * (8 + a) + c, Ti, Tj, Tv, &t);
    *nt = t;
    memset(Kd, 0, sizeof(double) * N * N);
    for (long k = 0; k < t; k++) Kd[Ti[k] * N + Tj[k]] += Tv[k];
    assert_int_equal(ffc_scene_set_bulk(s, N, t, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    long linked = 0;
    double u0[N] = {0};
    assert_int_equal(ffc_scene_search(s, u0, &linked, &bad), FFC_OK);
    assert_true(linked > 0 || METHOD == FFC_METHOD_NTS); /* (node-to-surface pairs locate their nodes instead) */
    return s;
}

/* the loads: the slave square pulled along x by fx per node (a tangential
 * load for the friction cases) and pressed along -z by pz per node */
static void loads(double fx, double pz, double f[N])
{
    memset(f, 0, sizeof(double) * N);
    for (int a = 0; a < 4; a++) {
        f[3 * a] = fx;
        f[3 * a + 2] = -pz;
    }
}

/* r(u) = K u - f + F_c(u) on the free rows, TGV (u - 0) on the Dirichlet
 * row (dof 12); with Kc into Kt = K + Kc when Kt is given */
static void residual(ffc_scene *s, const double Kd[N * N], const double f[N], const double u[N], double r[N],
                     double Kt[N * N])
{
    enum { CAP = 1 << 16 };
    static long ci[CAP], cj[CAP];
    static double cv[CAP];
    double R[N] = {0};
    long nt = 0, bad = -1;
    assert_int_equal(ffc_scene_assemble(s, u, Kt ? FFC_TANGENT_CONSISTENT : FFC_TANGENT_NONE, R, CAP, ci, cj, cv,
                                        &nt, &bad),
                     FFC_OK);
    for (int i = 0; i < N; i++) {
        double k = -f[i];
        for (int j = 0; j < N; j++) k += Kd[i * N + j] * u[j];
        r[i] = i == 12 ? k : k + R[i];
    }
    if (Kt) {
        memcpy(Kt, Kd, sizeof(double) * N * N);
        for (long e = 0; e < nt; e++)
            if (ci[e] != 12) Kt[ci[e] * N + cj[e]] += cv[e];
    }
}


static double free_norm(const double r[N])
{
    double v = 0.0;
    for (int i = 0; i < N; i++)
        if (i != 12) v += r[i] * r[i];
    return sqrt(v);
}

/* uc = uf to 1e-10 of uf's largest entry */
static void check_same(const double uc[N], const double uf[N])
{
    double umax = 0;
    for (int i = 0; i < N; i++) umax = fmax(umax, fabs(uf[i]));
    for (int i = 0; i < N; i++) assert_close(uc[i], uf[i], 1e-10 * umax);
}

/* Newton on the full system (dense), to |r| <= 1e-13 x the contact force */
static void full_newton(ffc_scene *s, const double Kd[N * N], const double f[N], double u[N])
{
    double r[N], Kt[N * N], dx[N];
    for (int it = 0; it < 60; it++) {
        residual(s, Kd, f, u, r, Kt);
        double fz = 0.0;
        assert_int_equal(ffc_scene_stat(s, -1, "Fz", 0, &fz), FFC_OK);
        if (free_norm(r) <= 1e-13 * fabs(fz) && it > 0) return;
        for (int i = 0; i < N; i++) r[i] = -r[i];
        test_dense_solve(N, Kt, r, dx);
        for (int i = 0; i < N; i++) u[i] += dx[i];
    }
    fail_msg("the full Newton did not converge");
}

/* The condensed Newton from u = 0 against the full one: the same
 * displacement to 1e-10 of its largest entry (both converge to 1e-12 of
 * the contact force on a system of condition ~1e3), the converged
 * residual below its tolerance, one factorization; in the slip case some
 * directions come from GMRES preconditioned with the LU of an earlier
 * one on the same support. */
static void check_case(double mu, double fx, double pz, double kgs, const char *regime)
{
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], uf[N] = {0}, uc[N] = {0}, r[N];
    ffc_scene *s = make(mu, kgs, &nt, Ti, Tj, Tv, Kd);
    loads(fx, pz, f);
    full_newton(s, Kd, f, uf);
    double fz = 0.0;
    ffc_scene_stat(s, -1, "Fz", 0, &fz);
    assert_true(fabs(fz) > 0.1);
    double stick = 0, slip = 0;
    ffc_scene_stat(s, -1, "stick", 0, &stick);
    ffc_scene_stat(s, -1, "slip", 0, &slip);
    if (!strcmp(regime, "stick")) assert_true(stick > 0 && slip == 0);
    if (!strcmp(regime, "slip")) assert_true(slip > 0 && stick == 0);
    residual(s, Kd, f, uc, r, NULL);
    ffc_newton_opts o = ffc_newton_defaults();
    o.ftol = 1e-12 * fabs(fz);
    ffc_newton_info in;
    assert_int_equal(ffc_scene_newton(s, r, uc, &o, &in, &bad), FFC_OK);
    check_same(uc, uf);
    residual(s, Kd, f, uc, r, NULL);
    assert_true(free_norm(r) <= 2 * o.ftol);
    assert_true(in.res <= o.ftol);
    assert_true(in.iters >= 1 && in.nhist == in.iters + 1);
    ffc_solve_info si;
    ffc_scene_solve_info(s, &si);
    assert_int_equal(si.factorizations, 1);
    if (kgs == 0) assert_true(si.shift > 0);
    else assert_true(si.shift == 0);
    /* the shift on three nodes of each body the contact touches (the
     * slave square and the master's, at most 18 dofs), not on the 23 free
     * dofs of the 8 nodes the contact force reaches */
    if (kgs == 0) assert_true(si.shifted >= 3 && si.shifted <= 18);
    else assert_true(si.shifted == 0);
    /* slip: directions on the support of an earlier one, solved by GMRES
     * with its LU (the same answer: checked above) */
    if (!strcmp(regime, "slip")) assert_true(si.kept > 0);
    ffc_scene_free(s);
}

static void test_frictionless(void **state)
{
    (void)state;
    check_case(0.0, 0.0, 0.0, KG, "");
}

static void test_stick(void **state)
{
    (void)state;
    check_case(0.5, 0.02, 0.0, KG, "stick");
}

static void test_slip(void **state)
{
    (void)state;
    check_case(0.3, 3.0, 0.0, KG, "slip");
}

/* the slave square has no ground springs: K is singular, the shift holds
 * it (and sticking friction holds it along the contact plane) */
static void test_held_by_contact(void **state)
{
    (void)state;
    check_case(0.5, 0.02, 0.2, 0.0, "stick");
}

/* Quadratic convergence (the slip case: 6.7, 5.7, 5.2e-5, 8.2e-13,
 * 2.8e-16, the same residuals as the full Newton): once the residual is
 * below 1e-2 of the first, each iteration squares its relative size
 * (r_{k+1} / r_0 <= 10 (r_k / r_0)^2) until round-off (1e-13); a linearly
 * converging iteration would gain a fixed factor instead. */
static void test_quadratic(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], u[N] = {0}, r[N];
    ffc_scene *s = make(0.3, KG, &nt, Ti, Tj, Tv, Kd);
    loads(3.0, 0.0, f);
    residual(s, Kd, f, u, r, NULL);
    ffc_newton_opts o = ffc_newton_defaults();
    o.ftol = 1e-300;
    o.frel = 1e-15;
    ffc_newton_info in;
    int st = ffc_scene_newton(s, r, u, &o, &in, &bad);
    assert_true(st == FFC_NEWTON_CONVERGED || st == FFC_NEWTON_MAXIT);
    int checked = 0;
    for (int k = 0; k + 1 < in.nhist; k++) {
        const double e = in.hist[k] / in.hist[0], e1 = in.hist[k + 1] / in.hist[0];
        if (e > 1e-2 || e < 1e-13 || e1 < 1e-13) continue;
        assert_true(e1 <= 10 * e * e);
        checked++;
    }
    assert_true(checked >= 1);
    assert_true(in.hist[in.nhist - 1] <= 1e-13 * in.hist[0]);
    ffc_scene_free(s);
}

/* The contact dofs grow between two calls (the compliance gains columns
 * and its Cholesky factor is extended): the slave square first overhangs
 * the master by 0.8 (its points beyond x = 1 unlinked), then is moved back
 * over it and searched again; each call matches the full Newton from the
 * same state. */
static void test_growth(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], uf[N] = {0}, uc[N] = {0}, r[N];
    XSHIFT = 0.8;
    ffc_scene *s = make(0.0, KG, &nt, Ti, Tj, Tv, Kd);
    XSHIFT = 0.0;
    loads(0.0, 0.0, f);
    ffc_newton_opts o = ffc_newton_defaults();
    o.ftol = 1e-12;
    ffc_newton_info in;
    long m[2];
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) { /* back over the master: every point linked */
            for (int a = 0; a < 4; a++) uf[3 * a] = uc[3 * a] = -0.8;
            long linked = 0;
            assert_int_equal(ffc_scene_search(s, uc, &linked, &bad), FFC_OK);
            for (int i = 0; i < N; i++) uf[i] = uc[i];
        }
        full_newton(s, Kd, f, uf);
        residual(s, Kd, f, uc, r, NULL);
        assert_int_equal(ffc_scene_newton(s, r, uc, &o, &in, &bad), FFC_OK);
        check_same(uc, uf);
        m[pass] = in.m;
    }
    assert_true(m[1] > m[0]);
    ffc_scene_free(s);
}

/* one condensed Newton call from uc against the full Newton from the same
 * state: the same answer, a residual within the tolerance, and the count
 * of first solves taken from the last closing one */
static void call_against_full(ffc_scene *s, const double Kd[N * N], const double f[N], double uc[N], long reused)
{
    double uf[N], r[N];
    long bad = -1;
    ffc_newton_opts o = ffc_newton_defaults();
    o.ftol = 1e-12;
    ffc_newton_info in;
    ffc_solve_info si;
    memcpy(uf, uc, sizeof uf);
    full_newton(s, Kd, f, uf);
    residual(s, Kd, f, uc, r, NULL);
    assert_int_equal(ffc_scene_newton(s, r, uc, &o, &in, &bad), FFC_OK);
    ffc_scene_solve_info(s, &si);
    assert_int_equal(si.reused, reused);
    check_same(uc, uf);
    residual(s, Kd, f, uc, r, NULL);
    assert_true(free_norm(r) <= 2 * o.ftol);
}

/* An augmentation of the same load: the second call's first solve is the
 * first call's closing one (b' = -P_C^T z to round-off), and its answer
 * is the full Newton's at the augmented multipliers; a changed load is
 * solved afresh. */
static void test_closing_reused(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], uc[N] = {0};
    ffc_scene *s = make(0.0, KG, &nt, Ti, Tj, Tv, Kd);
    loads(0.0, 0.0, f);
    call_against_full(s, Kd, f, uc, 0);
    assert_int_equal(ffc_scene_augment(s, uc, &bad), FFC_OK);
    call_against_full(s, Kd, f, uc, 1);
    loads(0.0, 0.01, f); /* a load: b' is no longer the closing solve's right-hand side */
    call_against_full(s, Kd, f, uc, 1);
    ffc_scene_free(s);
}

/* The contact closes during the call: the slave square starts 2e-3 above
 * the master, with no contact force, and a load presses it down by about
 * 1e-2.  C starts empty and grows as the force reaches dofs (at the
 * start, whose state moves the whole square by the load); the answer is
 * the full Newton's, with one compliance column per dof of C, every one
 * of them joined during the call; again with the slave nodes' x and z
 * dofs coupled in K (the normal reactions move the x dofs, the square
 * tilts) and the material tangent (linear convergence). */
static void test_contact_closes(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], uf[N] = {0}, uc[N] = {0}, r[N];
    ZSLAVE = 2e-3;
    for (int tangent = 0; tangent < 2; tangent++) {
    KXZ = tangent ? 0.5 * KG : 0.0;
    memset(uf, 0, sizeof uf);
    memset(uc, 0, sizeof uc);
    ffc_scene *s = make(0.0, KG, &nt, Ti, Tj, Tv, Kd);
    loads(0.0, 1.0, f);
    residual(s, Kd, f, uc, r, NULL);
    double fz = 1.0;
    assert_int_equal(ffc_scene_stat(s, -1, "Fz", 0, &fz), FFC_OK);
    assert_true(fz == 0.0); /* separated at the start */
    full_newton(s, Kd, f, uf);
    ffc_scene_stat(s, -1, "Fz", 0, &fz);
    assert_true(fabs(fz) > 1.0);
    ffc_newton_opts o = ffc_newton_defaults();
    o.ftol = 1e-12 * fabs(fz);
    o.max_iter = 60;
    if (tangent) o.tangent = FFC_TANGENT_MATERIAL;
    ffc_newton_info in;
    assert_int_equal(ffc_scene_newton(s, r, uc, &o, &in, &bad), FFC_OK);
    check_same(uc, uf);
    assert_true(in.grown > 0 && in.grown == in.m);
    ffc_solve_info si;
    ffc_scene_solve_info(s, &si);
    assert_int_equal(si.columns, in.m);
    ffc_scene_free(s);
    }
    ZSLAVE = -D;
    KXZ = 0.0;
}

/* The ranked tangent (FFC_TANGENT_RANKED): its terms sum to the material
 * tangent (sum_k U_k V_k^T against the material triplets, dense, to 1e-12
 * of the largest entry) in each regime, at the full Newton's converged
 * state; and the condensed Newton with it takes the material tangent's
 * directions (Woodbury on the terms instead of the LU on the support: the
 * same iterates to round-off, the same iteration count) to the full
 * Newton's displacement.  Regimes: frictionless, stick, slip, and a body
 * held only by contact (the shift's terms). */
static void test_ranked(void **state)
{
    (void)state;
    enum { CAP = 1 << 16 };
    static long ci[CAP], cj[CAP];
    static double cv[CAP], Km[N * N], Kr[N * N], U[N * 64], V[N * 64];
    const struct { double mu, fx, pz, kgs; const char *regime; } c[4] = {
        {0.0, 0.0, 0.0, KG, ""}, {0.5, 0.02, 0.0, KG, "stick"}, {0.3, 3.0, 0.0, KG, "slip"}, {0.5, 0.02, 0.2, 0.0, "stick"}};
    for (int k = 0; k < 4; k++) {
        long Ti[1024], Tj[1024], nt = 0, bad = -1;
        double Tv[1024], Kd[N * N], f[N], uf[N] = {0}, r[N];
        ffc_scene *s = make(c[k].mu, c[k].kgs, &nt, Ti, Tj, Tv, Kd);
        loads(c[k].fx, c[k].pz, f);
        full_newton(s, Kd, f, uf);
        double R[N] = {0}, kmax = 0.0, stick = 0, slip = 0;
        ffc_scene_stat(s, -1, "stick", 0, &stick);
        ffc_scene_stat(s, -1, "slip", 0, &slip);
        if (!strcmp(c[k].regime, "stick")) assert_true(stick > 0 && slip == 0);
        if (!strcmp(c[k].regime, "slip")) assert_true(slip > 0 && stick == 0);
        assert_int_equal(ffc_scene_assemble(s, uf, FFC_TANGENT_MATERIAL, R, CAP, ci, cj, cv, &nt, &bad), FFC_OK);
        memset(Km, 0, sizeof Km);
        for (long e = 0; e < nt; e++) Km[ci[e] * N + cj[e]] += cv[e];
        assert_int_equal(ffc_scene_assemble(s, uf, FFC_TANGENT_RANKED, R, CAP, ci, cj, cv, &nt, &bad), FFC_OK);
        memset(U, 0, sizeof U);
        memset(V, 0, sizeof V);
        long p = 0;
        for (long e = 0; e < nt; e++) {
            assert_true(ci[e] >= 0 && ci[e] < N && cj[e] >= 0 && cj[e] < 2 * 64);
            double *W = cj[e] % 2 ? V : U;
            W[(cj[e] / 2) * N + ci[e]] += cv[e];
            if (cj[e] / 2 + 1 > p) p = cj[e] / 2 + 1;
        }
        assert_true(p >= 4 && p <= (c[k].mu > 0 ? 16 : 4)); /* one term per active slave node, four with friction */
        memset(Kr, 0, sizeof Kr);
        for (long t = 0; t < p; t++)
            for (int i = 0; i < N; i++)
                for (int j = 0; j < N; j++) Kr[i * N + j] += U[t * N + i] * V[t * N + j];
        for (int i = 0; i < N * N; i++) kmax = fmax(kmax, fabs(Km[i]));
        assert_true(kmax > 0.0);
        for (int i = 0; i < N * N; i++) assert_close(Kr[i], Km[i], 1e-12 * kmax);
        /* the condensed Newton, material and ranked, from u = 0 */
        ffc_newton_info in[2];
        double uc[2][N];
        for (int t = 0; t < 2; t++) {
            memset(uc[t], 0, sizeof uc[t]);
            residual(s, Kd, f, uc[t], r, NULL);
            double fz = 0.0;
            ffc_scene_stat(s, -1, "Fz", 0, &fz);
            ffc_newton_opts o = ffc_newton_defaults();
            o.ftol = 1e-12 * fmax(fabs(fz), 0.1);
            o.max_iter = 80;
            o.tangent = t ? FFC_TANGENT_RANKED : FFC_TANGENT_MATERIAL;
            assert_int_equal(ffc_scene_newton(s, r, uc[t], &o, &in[t], &bad), FFC_OK);
            check_same(uc[t], uf);
        }
        assert_int_equal(in[1].iters, in[0].iters);
        for (int h = 0; h < in[0].nhist && h < 4; h++) assert_close(in[1].hist[h], in[0].hist[h], 1e-8 * in[0].hist[0]);
        /* the dense system: a term per active node (four with friction), and
         * one per shifted dof of C when K is singular */
        assert_true(in[1].support <= (c[k].mu > 0 ? 16 : 4) + (c[k].kgs == 0 ? in[1].m : 0));
        ffc_scene_free(s);
    }
}

/* min_iter = 1 (after an augmentation): from the converged state, whose
 * residual is within the tolerance but not zero, the call takes one
 * iteration (with 0: none) and stays at the answer (min_iter = 2 is
 * refused: test_bad_input). */
static void test_min_iter(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], uf[N] = {0}, r[N];
    ffc_scene *s = make(0.0, KG, &nt, Ti, Tj, Tv, Kd);
    loads(0.0, 0.0, f);
    full_newton(s, Kd, f, uf);
    double fz = 0.0;
    ffc_scene_stat(s, -1, "Fz", 0, &fz);
    for (int mi = 0; mi < 2; mi++) {
        double u[N];
        memcpy(u, uf, sizeof u);
        residual(s, Kd, f, u, r, NULL);
        assert_true(free_norm(r) > 0.0);
        ffc_newton_opts o = ffc_newton_defaults();
        o.ftol = 1e-6 * fabs(fz); /* the full Newton's state is well within it */
        o.min_iter = mi;
        ffc_newton_info in;
        assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_OK);
        assert_int_equal(in.iters, mi);
        check_same(u, uf);
    }
    ffc_scene_free(s);
}

/* FFC_TANGENT_RANKED needs nodal multipliers: a pair with them at
 * quadrature points is refused by the assembly (naming the pair) and by
 * the condensed Newton, before any work */
static void test_ranked_bad_input(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1, ci[64], cj[64];
    double Tv[1024], Kd[N * N], R[N] = {0}, u[N] = {0}, r[N] = {0}, cv[64];
    ffc_scene *s = make(0.0, KG, &nt, Ti, Tj, Tv, Kd); /* pair 0: nodal */
    const long Fs[6] = {0, 2, 1, 0, 3, 2}, Fm[6] = {4, 5, 6, 4, 6, 7};
    ffc_pair_opts o = ffc_pair_defaults();
    o.eps_n = EPS;
    o.nodal = 0;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs, 2, Fm, &o, &bad), 1);
    assert_int_equal(ffc_scene_assemble(s, u, FFC_TANGENT_RANKED, R, 64, ci, cj, cv, &nt, &bad), FFC_ERR_VALUE);
    assert_int_equal(bad, 1);
    ffc_newton_opts no = ffc_newton_defaults();
    no.ftol = 1e-9;
    no.tangent = FFC_TANGENT_RANKED;
    ffc_newton_info in;
    assert_int_equal(ffc_scene_newton(s, r, u, &no, &in, &bad), FFC_ERR_VALUE);
    assert_int_equal(bad, 1);
    ffc_scene_free(s);
}

/* The node-to-surface saddle point on the factored bulk
 * (ffc_scene_nts_solve) against a dense solve of the whole system
 * [K Bf'; B Cm] [x; m] = [f; c] with the same rows: x and m to 1e-10 of
 * their largest entries.  Frictionless (B = Bf); with friction, first
 * sticking rows, then, after the update under a tangential load larger
 * than mu times the pressing one, sliding rows (a C block, a
 * non-symmetric system); and a slave square held only by the sticking
 * contact (K singular and shifted: the coupled form). */
static void nts_case(double mu, double fx, double pz, double kgs, int slide)
{
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], u[N] = {0}, x[N];
    METHOD = FFC_METHOD_NTS;
    ffc_scene *s = make(mu, kgs, &nt, Ti, Tj, Tv, Kd);
    METHOD = FFC_METHOD_AL;
    loads(fx, pz, f);
    const double fixed[N] = {[12] = 1.0};
    assert_int_equal(ffc_scene_nts_step(s), FFC_OK);
    long changes = 0, nr = 0;
    double m[64];
    for (int pass = 0; pass <= slide; pass++) {
        if (pass) assert_int_equal(ffc_scene_nts_update(s, u, nr, m, &changes, &bad), FFC_OK);
        /* the rows and the dense system */
        long Bi[512], Bj[512], ntr = 0;
        double Bv[512], Fv[512], c[64];
        assert_int_equal(ffc_scene_nts_rows(s, u, fixed, 512, Bi, Bj, Bv, Fv, 64, c, &ntr, &nr, &bad), FFC_OK);
        assert_true(nr > 0);
        const int na = N + (int)nr;
        double *A = calloc((size_t)na * na, sizeof(double)), rhs[N + 64], sol[N + 64];
        for (int i = 0; i < N; i++) {
            for (int j = 0; j < N; j++) A[i * na + j] = Kd[i * N + j];
            rhs[i] = f[i];
        }
        int cblock = 0;
        for (long e = 0; e < ntr; e++) {
            if (Bj[e] >= N) { A[(N + Bi[e]) * na + Bj[e]] += Bv[e]; cblock++; continue; }
            A[(N + Bi[e]) * na + Bj[e]] += Bv[e];
            A[Bj[e] * na + N + Bi[e]] += Fv[e];
        }
        for (long r = 0; r < nr; r++) rhs[N + r] = c[r];
        if (pass == 1) assert_true(cblock > 0); /* sliding rows */
        test_dense_solve(na, A, rhs, sol);
        free(A);
        /* the same on the factored bulk */
        long nr2 = 0;
        assert_int_equal(ffc_scene_nts_solve(s, u, fixed, f, x, 64, m, &nr2, &bad), FFC_OK);
        assert_int_equal(nr2, nr);
        double xmax = 0.0, mmax = 0.0;
        for (int i = 0; i < N; i++) xmax = fmax(xmax, fabs(sol[i]));
        for (long r = 0; r < nr; r++) mmax = fmax(mmax, fabs(sol[N + r]));
        assert_true(xmax > 0 && mmax > 0);
        for (int i = 0; i < N; i++) assert_close(x[i], sol[i], 1e-10 * xmax);
        for (long r = 0; r < nr; r++) assert_close(m[r], sol[N + r], 1e-10 * mmax);
        memcpy(u, x, sizeof u);
    }
    ffc_solve_info si;
    ffc_scene_solve_info(s, &si);
    assert_int_equal(si.factorizations, 1);
    if (kgs == 0) assert_true(si.shift > 0);
    ffc_scene_free(s);
}

static void test_nts_saddle(void **state)
{
    (void)state;
    nts_case(0.0, 0.0, 0.0, KG, 0);    /* frictionless */
    nts_case(0.3, 3.0, 0.0, KG, 1);    /* stick, then slide */
    nts_case(0.5, 0.02, 0.2, 0.0, 0);  /* held only by the contact (sticking) */
}

/* the saddle solve's bad input: no bulk; a multiplier array too small (the
 * count needed returned); a non-finite right-hand side */
static void test_nts_saddle_bad_input(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1, nr = 0;
    double Tv[1024], Kd[N * N], f[N] = {0}, u[N] = {0}, x[N], m[64];
    const double fixed[N] = {[12] = 1.0};
    METHOD = FFC_METHOD_NTS;
    ffc_scene *s = make(0.0, KG, &nt, Ti, Tj, Tv, Kd);
    METHOD = FFC_METHOD_AL;
    assert_int_equal(ffc_scene_nts_step(s), FFC_OK);
    assert_int_equal(ffc_scene_nts_solve(s, u, fixed, f, x, 0, m, &nr, &bad), FFC_ERR_CAPACITY);
    assert_true(nr > 0);
    assert_int_equal(ffc_scene_nts_solve(s, u, fixed, f, x, nr, m, &nr, &bad), FFC_OK);
    f[5] = NAN;
    assert_int_equal(ffc_scene_nts_solve(s, u, fixed, f, x, 64, m, &nr, &bad), FFC_ERR_NONFINITE);
    assert_int_equal(bad, 5);
    assert_int_equal(ffc_scene_nts_solve(NULL, u, fixed, f, x, 64, m, &nr, &bad), FFC_ERR_NULL);
    ffc_scene_free(s);
    double X[3 * NV] = {0};
    ffc_effects fx = {0, 0, 0};
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
    f[5] = 0.0;
    assert_int_equal(ffc_scene_nts_solve(s, u, fixed, f, x, 64, m, &nr, &bad), FFC_ERR_EMPTY);
    ffc_scene_free(s);
}

static void test_bad_input(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], u[N] = {0}, r[N];
    ffc_scene *s = make(0.0, KG, &nt, Ti, Tj, Tv, Kd);
    loads(0.0, 0.0, f);
    residual(s, Kd, f, u, r, NULL);
    ffc_newton_opts o = ffc_newton_defaults();
    ffc_newton_info in;
    assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_ERR_VALUE); /* ftol not set */
    o.ftol = 1e-9;
    assert_int_equal(ffc_scene_newton(NULL, r, u, &o, &in, &bad), FFC_ERR_NULL);
    assert_int_equal(ffc_scene_newton(s, NULL, u, &o, &in, &bad), FFC_ERR_NULL);
    o.ls_tol = 1.0;
    assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_ERR_VALUE);
    o.ls_tol = 0.5;
    o.max_iter = 0;
    assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_ERR_VALUE);
    o.max_iter = 25;
    o.min_iter = 2;
    assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_ERR_VALUE);
    o.min_iter = 0;
    o.tangent = FFC_TANGENT_NONE;
    assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_ERR_VALUE);
    o.tangent = FFC_TANGENT_CONSISTENT;
    double rn[N];
    memcpy(rn, r, sizeof rn);
    rn[7] = NAN;
    assert_int_equal(ffc_scene_newton(s, rn, u, &o, &in, &bad), FFC_ERR_NONFINITE);
    assert_int_equal(bad, 7);
    for (int i = 0; i < N; i++) assert_true(u[i] == 0.0); /* u kept */
    /* more contact dofs than the bulk takes */
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 5, &bad), FFC_OK);
    assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_ERR_CAPACITY);
    assert_true(bad > 5);
    for (int i = 0; i < N; i++) assert_true(u[i] == 0.0);
    ffc_scene_free(s);
    /* no bulk matrix */
    double X[3 * NV] = {0};
    ffc_effects fx = {0, 0, 0};
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
    assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_ERR_EMPTY);
    ffc_scene_free(s);
}

/* A bulk that is not positive definite (a negative ground spring on a
 * contact dof) is refused with FFC_ERR_SINGULAR, u kept. */
static void test_not_positive_definite(void **state)
{
    (void)state;
    long Ti[1024], Tj[1024], nt = 0, bad = -1;
    double Tv[1024], Kd[N * N], f[N], u[N] = {0}, r[N];
    ffc_scene *s = make(0.0, KG, &nt, Ti, Tj, Tv, Kd);
    Ti[nt] = Tj[nt] = 2;        /* the z dof of slave node 0: an indefinite K */
    Tv[nt] = -1e4;
    Kd[2 * N + 2] += -1e4;
    assert_int_equal(ffc_scene_set_bulk(s, N, nt + 1, Ti, Tj, Tv, 1000, &bad), FFC_ERR_SINGULAR);
    /* positive diagonal but indefinite: two springs of opposite sign */
    Tv[nt] = 1.0;
    Ti[nt + 1] = 2; Tj[nt + 1] = 5; Tv[nt + 1] = 1e5;
    Ti[nt + 2] = 5; Tj[nt + 2] = 2; Tv[nt + 2] = 1e5;
    assert_int_equal(ffc_scene_set_bulk(s, N, nt + 3, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    loads(0.0, 0.0, f);
    residual(s, Kd, f, u, r, NULL);
    ffc_newton_opts o = ffc_newton_defaults();
    o.ftol = 1e-9;
    ffc_newton_info in;
    assert_int_equal(ffc_scene_newton(s, r, u, &o, &in, &bad), FFC_ERR_SINGULAR);
    for (int i = 0; i < N; i++) assert_true(u[i] == 0.0);
    ffc_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frictionless),   cmocka_unit_test(test_stick),
        cmocka_unit_test(test_slip),           cmocka_unit_test(test_held_by_contact),
        cmocka_unit_test(test_quadratic),      cmocka_unit_test(test_growth),
        cmocka_unit_test(test_closing_reused),
        cmocka_unit_test(test_contact_closes), cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_nts_saddle),     cmocka_unit_test(test_nts_saddle_bad_input),
        cmocka_unit_test(test_not_positive_definite), cmocka_unit_test(test_ranked),
        cmocka_unit_test(test_ranked_bad_input), cmocka_unit_test(test_min_iter),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
