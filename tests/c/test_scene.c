/* test_scene.c: contact scenes with several pairs: independent
 * multipliers, assembly as the sum of the pairs, checkpoints, statistics
 * by name, capacities and bad input. */
#include <stdlib.h>
#include <string.h>

#include "ffc_test.h"

/* Two pairs of unit squares (two triangles each), 16 nodes:
 *   pair 0: slave square at z = -d0 facing down onto a master square at
 *           z = 0 facing up (nodes 0-3 slave, 4-7 master);
 *   pair 1: the same at z = 1 - d1 onto z = 1 (nodes 8-11, 12-15).
 * Each slave penetrates its master uniformly by d. */
#define NV 16
static const double D0 = 1e-3, D1 = 3e-3, EPS = 1e3;

/* facets of the square at base: up = 1 normal +z, 0 normal -z */
static void facets(long base, int up, long F[6])
{
    const long t[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int f = 0; f < 2; f++)
        for (int a = 0; a < 3; a++) F[3 * f + a] = base + t[f][up ? a : 2 - a];
}
static void geometry(double X[3 * NV], long Fs0[6], long Fm0[6], long Fs1[6], long Fm1[6])
{
    test_unit_square(-D0, X, 0);
    test_unit_square(0.0, X, 4);
    test_unit_square(1.0 - D1, X, 8);
    test_unit_square(1.0, X, 12);
    facets(0, 0, Fs0);
    facets(4, 1, Fm0);
    facets(8, 0, Fs1);
    facets(12, 1, Fm1);
}

static ffc_pair_opts opts(double mu)
{
    ffc_pair_opts o = ffc_pair_defaults();
    o.eps_n = EPS;
    o.mu = mu;
    o.qdeg = 2;
    return o;
}

/* a scene with pair 0, pair 1 or both (which: bit 0, bit 1) */
static ffc_scene *make(int which, int friction)
{
    double X[3 * NV];
    long Fs0[6], Fm0[6], Fs1[6], Fm1[6], bad;
    geometry(X, Fs0, Fm0, Fs1, Fm1);
    ffc_effects fx = {friction, 0, 0};
    ffc_scene *s = NULL;
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
    ffc_pair_opts o0 = opts(friction ? 0.3 : 0.0), o1 = opts(0.0);
    if (which & 1) assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o0, &bad), 0);
    if (which & 2) assert_int_equal(ffc_scene_add_pair(s, 2, Fs1, 2, Fm1, &o1, &bad), (which & 1) ? 1 : 0);
    return s;
}

static double stat(const ffc_scene *s, int k, const char *name)
{
    double v = NAN;
    assert_int_equal(ffc_scene_stat(s, k, name, 0, &v), FFC_OK);
    return v;
}

/* Uniform penetration d (u = 0 throughout): the weighted nodal gap is -d
 * at every slave node, so each augmentation adds eps d to lambda there;
 * after three, an assembly presses with t = 3 eps d + eps d = 4 eps d over
 * the unit area. */
static void test_two_pairs_independent(void **state)
{
    (void)state;
    double u[3 * NV] = {0};
    ffc_scene *both = make(3, 0), *one = make(1, 0), *two = make(2, 0);
    ffc_scene *sc[3] = {both, one, two};
    for (int i = 0; i < 3; i++) {
        long linked;
        assert_int_equal(ffc_scene_search(sc[i], u, &linked, NULL), FFC_OK);
        assert_int_equal(linked, (i == 0 ? 2 : 1) * 2 * 3);
        for (int it = 0; it < 3; it++) {
            assert_int_equal(ffc_scene_augment(sc[i], u, NULL), FFC_OK);
            if (it == 0) {
                /* lambda = eps d at the pair's slave nodes, zero elsewhere */
                double lam[NV];
                long n;
                assert_int_equal(ffc_scene_multipliers(sc[i], 0, NV, lam, NULL, &n), FFC_OK);
                assert_int_equal(n, NV);
                const long base = i == 2 ? 8 : 0;
                const double d = i == 2 ? D1 : D0;
                for (long v = 0; v < NV; v++)
                    assert_close(lam[v], (v >= base && v < base + 4) ? EPS * d : 0.0, 1e-12);
            }
        }
    }
    /* each pair of the two-pair scene has the multipliers it has alone */
    double a[NV], b[NV];
    long n;
    for (int k = 0; k < 2; k++) {
        assert_int_equal(ffc_scene_multipliers(both, k, NV, a, NULL, &n), FFC_OK);
        assert_int_equal(ffc_scene_multipliers(k ? two : one, 0, NV, b, NULL, &n), FFC_OK);
        for (long v = 0; v < NV; v++) assert_close(a[v], b[v], 0.0);
    }
    /* the assembled forces: 4 eps d per pair; the total is their sum */
    double R[3 * NV] = {0};
    long nt;
    assert_int_equal(ffc_scene_assemble(both, u, FFC_TANGENT_NONE, R, 0, NULL, NULL, NULL, &nt, NULL), FFC_OK);
    assert_close(stat(both, 0, "Fz"), 4 * EPS * D0, 1e-12);
    assert_close(stat(both, 1, "Fz"), 4 * EPS * D1, 1e-12);
    assert_close(stat(both, -1, "Fz"), 4 * EPS * (D0 + D1), 1e-12);
    assert_close(stat(both, -1, "maxPen"), D1, 1e-15);
    assert_close(stat(both, 0, "maxPen"), D0, 1e-15);
    /* the slave nodes of each pair carry its force, downward (-z) */
    double f0 = 0, f1 = 0;
    for (long v = 0; v < 4; v++) f0 += R[3 * v + 2];
    for (long v = 8; v < 12; v++) f1 += R[3 * v + 2];
    assert_close(f0, -4 * EPS * D0, 1e-12);
    assert_close(f1, -4 * EPS * D1, 1e-12);
    for (int i = 0; i < 3; i++) ffc_scene_free(sc[i]);
}

/* The kernel itself: augmenting pair 1 in an array shared with pair 0
 * leaves pair 0's entries as they are (it used to zero every node). */
static void test_augment_shared_array(void **state)
{
    (void)state;
    double X[3 * NV], u[3 * NV] = {0}, lam[NV], lam0[NV];
    long Fs0[6], Fm0[6], Fs1[6], Fm1[6], bad;
    geometry(X, Fs0, Fm0, Fs1, Fm1);
    ffc_effects fx = {0, 0, 0};
    ffc_law law = {.eps_n = EPS, .nodal = 1};
    ffc_pair p0 = {3, 2, Fs0, 3, 2, Fm0, NV, X, u, NULL, NULL, NULL}, p1 = {3, 2, Fs1, 3, 2, Fm1, NV, X, u, NULL, NULL, NULL};
    ffc_link L0[6], L1[6];
    ffc_tree *t0, *t1;
    assert_int_equal(ffc_tree_build(3, 2, Fm0, NV, X, &t0), FFC_OK);
    assert_int_equal(ffc_tree_build(3, 2, Fm1, NV, X, &t1), FFC_OK);
    ffc_search_opts so = ffc_search_defaults();
    assert_int_equal(ffc_search(t0, 3, 2, Fs0, NV, X, 2, &so, 6, L0), 6);
    assert_int_equal(ffc_search(t1, 3, 2, Fs1, NV, X, 2, &so, 6, L1), 6);
    for (long v = 0; v < NV; v++) lam[v] = 0.0;
    assert_int_equal(ffc_augment(&fx, &p0, 2, 6, L0, lam, NULL, &law, NULL, &bad), FFC_OK);
    memcpy(lam0, lam, sizeof lam);
    assert_int_equal(ffc_augment(&fx, &p1, 2, 6, L1, lam, NULL, &law, NULL, &bad), FFC_OK);
    for (long v = 0; v < 4; v++) assert_close(lam[v], lam0[v], 0.0);
    for (long v = 0; v < 4; v++) assert_close(lam[v], EPS * D0, 1e-12);
    for (long v = 8; v < 12; v++) assert_close(lam[v], EPS * D1, 1e-12);
    ffc_tree_free(t0);
    ffc_tree_free(t1);
}

/* The scene's assembly is the sum of the kernels' per-pair assemblies. */
static void test_assembly_is_sum(void **state)
{
    (void)state;
    double u[3 * NV];
    uint64_t seed = 7;
    for (int i = 0; i < 3 * NV; i++) u[i] = test_rand(&seed, -2e-4, 2e-4);
    ffc_scene *both = make(3, 0), *one = make(1, 0), *two = make(2, 0);
    ffc_scene *sc[3] = {both, one, two};
    double R[3][3 * NV];
    long need[3];
    double *A[3];
    for (int i = 0; i < 3; i++) {
        assert_int_equal(ffc_scene_search(sc[i], u, NULL, NULL), FFC_OK);
        assert_int_equal(ffc_scene_augment(sc[i], u, NULL), FFC_OK);
        memset(R[i], 0, sizeof R[i]);
        /* no room: the count needed */
        assert_int_equal(ffc_scene_assemble(sc[i], u, FFC_TANGENT_CONSISTENT, R[i], 0, (long[1]){0}, (long[1]){0},
                                            (double[1]){0}, &need[i], NULL),
                         FFC_ERR_CAPACITY);
        assert_true(need[i] > 0);
        long *Ti = malloc(need[i] * sizeof *Ti), *Tj = malloc(need[i] * sizeof *Tj), nt;
        double *Tv = malloc(need[i] * sizeof *Tv);
        memset(R[i], 0, sizeof R[i]);
        assert_int_equal(ffc_scene_assemble(sc[i], u, FFC_TANGENT_CONSISTENT, R[i], need[i], Ti, Tj, Tv, &nt, NULL),
                         FFC_OK);
        assert_int_equal(nt, need[i]);
        A[i] = calloc(9 * NV * NV, sizeof *A[i]);
        for (long k = 0; k < nt; k++) A[i][Ti[k] * 3 * NV + Tj[k]] += Tv[k];
        free(Ti); free(Tj); free(Tv);
    }
    assert_int_equal(need[0], need[1] + need[2]);
    /* room for the first pair only: the count needed is still the whole */
    {
        long *Ti = malloc(need[1] * sizeof *Ti), *Tj = malloc(need[1] * sizeof *Tj), nt = 0;
        double *Tv = malloc(need[1] * sizeof *Tv), Rx[3 * NV] = {0};
        assert_int_equal(ffc_scene_assemble(both, u, FFC_TANGENT_CONSISTENT, Rx, need[1], Ti, Tj, Tv, &nt, NULL),
                         FFC_ERR_CAPACITY);
        assert_int_equal(nt, need[0]);
        free(Ti); free(Tj); free(Tv);
    }
    for (int i = 0; i < 3 * NV; i++) assert_close(R[0][i], R[1][i] + R[2][i], 1e-12);
    for (int i = 0; i < 9 * NV * NV; i++) assert_close(A[0][i], A[1][i] + A[2][i], 1e-9);
    for (int i = 0; i < 3; i++) { free(A[i]); ffc_scene_free(sc[i]); }
}

/* A step cut goes back to the multipliers of the last commit. */
static void test_commit_restore(void **state)
{
    (void)state;
    double u[3 * NV] = {0}, a[NV], b[NV];
    long n;
    ffc_scene *s = make(3, 0);
    assert_int_equal(ffc_scene_search(s, u, NULL, NULL), FFC_OK);
    assert_int_equal(ffc_scene_augment(s, u, NULL), FFC_OK);
    assert_int_equal(ffc_scene_commit(s, u), FFC_OK);
    assert_int_equal(ffc_scene_multipliers(s, 1, NV, a, NULL, &n), FFC_OK);
    assert_int_equal(ffc_scene_augment(s, u, NULL), FFC_OK);
    assert_int_equal(ffc_scene_multipliers(s, 1, NV, b, NULL, &n), FFC_OK);
    assert_true(b[8] > a[8] * 1.5);
    assert_int_equal(ffc_scene_restore(s), FFC_OK);
    assert_int_equal(ffc_scene_multipliers(s, 1, NV, b, NULL, &n), FFC_OK);
    for (long v = 0; v < NV; v++) assert_close(a[v], b[v], 0.0);
    assert_int_equal(ffc_scene_reset(s), FFC_OK);
    assert_int_equal(ffc_scene_multipliers(s, 1, NV, b, NULL, &n), FFC_OK);
    for (long v = 0; v < NV; v++) assert_close(b[v], 0.0, 0.0);
    ffc_scene_free(s);
}

/* The prescribed dofs: copied, cleared by NULL, a NaN refused (the old
 * mask kept), a null scene refused. */
static void test_set_fixed(void **state)
{
    (void)state;
    double f[3 * NV] = {0};
    ffc_scene *s = make(3, 0);
    f[5] = 1.0;
    assert_int_equal(ffc_scene_set_fixed(s, f), FFC_OK);
    f[7] = NAN;
    assert_int_equal(ffc_scene_set_fixed(s, f), FFC_ERR_NONFINITE);
    assert_int_equal(ffc_scene_set_fixed(s, NULL), FFC_OK);
    assert_int_equal(ffc_scene_set_fixed(NULL, f), FFC_ERR_NULL);
    ffc_scene_free(s);
}

/* Friction belongs to the pair: a frictional pair beside a frictionless
 * one; only the first computes friction, and its tangent is non-symmetric. */
static void test_friction_per_pair(void **state)
{
    (void)state;
    double u[3 * NV] = {0};
    ffc_scene *s = make(3, 1);
    assert_int_equal(ffc_scene_search(s, u, NULL, NULL), FFC_OK);
    assert_int_equal(ffc_scene_augment(s, u, NULL), FFC_OK);
    assert_int_equal(ffc_scene_commit(s, u), FFC_OK);
    for (int v = 0; v < 4; v++) u[3 * v] = 1e-2;      /* slide pair 0's slave */
    for (int v = 8; v < 12; v++) u[3 * v] = 1e-2;     /* and pair 1's */
    double R[3 * NV] = {0};
    long nt;
    assert_int_equal(ffc_scene_assemble(s, u, FFC_TANGENT_NONE, R, 0, NULL, NULL, NULL, &nt, NULL), FFC_OK);
    assert_close(stat(s, 0, "slip"), 4, 0);
    assert_close(stat(s, 1, "slip") + stat(s, 1, "stick"), 0, 0);
    /* pair 0 slides at mu t_N: |Ft| = 0.3 |Fz| */
    assert_close(fabs(stat(s, 0, "Ftx")), 0.3 * stat(s, 0, "Fz"), 1e-9);
    assert_close(stat(s, 1, "Ftx"), 0.0, 0.0);
    /* the slip since the commit: the slave moved by 1e-2 over a fixed master */
    assert_close(stat(s, 0, "maxSlip"), 1e-2, 1e-12);
    assert_close(stat(s, 1, "maxSlip"), 0.0, 0.0);
    /* after a commit the next assembly sees no slip; the step's statistics
     * keep what the converged step had */
    assert_int_equal(ffc_scene_commit(s, u), FFC_OK);
    assert_int_equal(ffc_scene_assemble(s, u, FFC_TANGENT_NONE, R, 0, NULL, NULL, NULL, &nt, NULL), FFC_OK);
    assert_close(stat(s, 0, "maxSlip"), 0.0, 0.0);
    double v = 0;
    assert_int_equal(ffc_scene_stat(s, 0, "maxSlip", 1, &v), FFC_OK);
    assert_close(v, 1e-2, 1e-12);
    assert_int_equal(ffc_scene_stat(s, 0, "slip", 1, &v), FFC_OK);
    assert_close(v, 4, 0);
    ffc_scene_free(s);
}

/* A touching slave (gap exactly 0, no multiplier yet) with friction holds
 * tangentially in the tangent (the stick branch at the kink of the return
 * map): the x rows of its nodes get eps_T times their area, while the
 * residual stays zero; without friction those rows stay empty. */
static void test_touching_stick(void **state)
{
    (void)state;
    double X[3 * NV], u[3 * NV] = {0}, R[3 * NV];
    long Fs0[6], Fm0[6], Fs1[6], Fm1[6], bad, nt;
    geometry(X, Fs0, Fm0, Fs1, Fm1);
    test_unit_square(0.0, X, 0); /* pair 0's slave touches its master */
    for (int mu10 = 0; mu10 <= 3; mu10 += 3) {
        ffc_effects fx = {1, 0, 0};
        ffc_scene *s = NULL;
        assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
        ffc_pair_opts o = opts(0.1 * mu10);
        assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), 0);
        assert_int_equal(ffc_scene_search(s, u, NULL, NULL), FFC_OK);
        long Ti[4096], Tj[4096];
        double Tv[4096], kxx = 0.0;
        memset(R, 0, sizeof R);
        assert_int_equal(ffc_scene_assemble(s, u, FFC_TANGENT_CONSISTENT, R, 4096, Ti, Tj, Tv, &nt, NULL), FFC_OK);
        for (long k = 0; k < nt; k++)
            if (Ti[k] % 3 == 0 && Ti[k] < 12 && Tj[k] % 3 == 0 && Tj[k] < 12) kxx += Tv[k];
        for (int i = 0; i < 3 * NV; i++) assert_close(R[i], 0.0, 0.0);
        /* the slave's x block sums to eps_T times the unit area: a rigid
         * slip r of the slave is resisted by eps_T r A */
        assert_close(kxx, mu10 ? EPS : 0.0, 1e-9 * EPS);
        ffc_scene_free(s);
    }
}

/* The automatic penalty: 200 / (1/k_s + 1/k_m), k = mean E'/h of a side;
 * the unit squares' triangles have h = sqrt(2). Equal sides: 100 E' / h;
 * a soft slave on a stiff master: 200 k_s, to 1e-6 relative. */
static void test_auto_penalty(void **state)
{
    (void)state;
    ffc_scene *s = make(1, 0);
    const double h = sqrt(2.0), E = 1000.0;
    double Es[2] = {E, E}, Em[2] = {E, E}, eps = 0;
    assert_int_equal(ffc_scene_auto_penalty(s, 0, Es, Em, &eps), FFC_OK);
    assert_close(eps, 100 * E / h, 1e-9 * eps);
    double soft[2] = {1, 1}, stiff[2] = {1e6, 1e6};
    assert_int_equal(ffc_scene_auto_penalty(s, 0, soft, stiff, &eps), FFC_OK);
    assert_close(eps, 200 / h, 1e-6 * 200 / h);
    /* the modulus of Lame's constants: E' = E / (1 - nu^2) */
    const double nu = 0.3, l = E * nu / ((1 + nu) * (1 - 2 * nu)), m = E / (2 * (1 + nu));
    assert_close(ffc_plane_modulus(l, m), E / (1 - nu * nu), 1e-12 * E);
    soft[1] = 0;
    assert_int_equal(ffc_scene_auto_penalty(s, 0, soft, stiff, &eps), FFC_ERR_VALUE);
    assert_int_equal(ffc_scene_auto_penalty(s, 1, Es, Em, &eps), FFC_ERR_INDEX);
    assert_int_equal(ffc_scene_nfacets(s, 0, 0), 2);
    ffc_scene_free(s);
}

static void test_bad_input(void **state)
{
    (void)state;
    double X[3 * NV], v;
    long Fs0[6], Fm0[6], Fs1[6], Fm1[6], bad;
    geometry(X, Fs0, Fm0, Fs1, Fm1);
    ffc_effects fx = {0, 0, 0};
    ffc_scene *s = NULL;
    assert_int_equal(ffc_scene_create(4, NV, X, 0, NULL, &fx, &s), FFC_ERR_NODES);
    assert_null(s);
    assert_int_equal(ffc_scene_create(3, 0, X, 0, NULL, &fx, &s), FFC_ERR_SIZE);
    X[5] = NAN;
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_ERR_NONFINITE);
    X[5] = -D0;
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
    ffc_pair_opts o = opts(0.0);
    o.qdeg = 9;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), FFC_ERR_QUAD);
    o = opts(0.0);
    o.mu = -1;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), FFC_ERR_VALUE);
    /* dual_t: 0 or 1, and only where it acts (the nodal law of the augmented Lagrangian) */
    o = opts(0.0);
    o.dual_t = 2;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), FFC_ERR_VALUE);
    o.dual_t = 1;
    o.nodal = 0;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), FFC_ERR_VALUE);
    o.nodal = 1;
    o.method = FFC_METHOD_NTS;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), FFC_ERR_VALUE);
    o = opts(0.0);
    Fm0[4] = NV;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), FFC_ERR_INDEX);
    assert_int_equal(bad, 4);
    Fm0[4] = 6;
    /* a slave facet on master nodes: the surfaces are fused */
    long Fused[6] = {0, 1, 2, 4, 6, 5};
    assert_int_equal(ffc_scene_add_pair(s, 2, Fused, 2, Fm0, &o, &bad), FFC_ERR_FUSED);
    assert_int_equal(bad, 1);
    assert_string_equal(ffc_strerror(FFC_ERR_FUSED), "slave and master surfaces share their nodes");
    o.eps_n = -1;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), FFC_ERR_VALUE);
    /* eps_n 0: added, but no assembly or augmentation until it is set */
    o.eps_n = 0;
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), 0);
    double u0[3 * NV] = {0}, R0[3 * NV] = {0};
    long nt0;
    assert_int_equal(ffc_scene_assemble(s, u0, FFC_TANGENT_NONE, R0, 0, NULL, NULL, NULL, &nt0, &bad), FFC_ERR_VALUE);
    assert_int_equal(bad, 0);
    assert_int_equal(ffc_scene_augment(s, u0, &bad), FFC_ERR_VALUE);
    o.eps_n = EPS;
    assert_int_equal(ffc_scene_set_pair_opts(s, 0, &o), FFC_OK);
    assert_int_equal(ffc_scene_assemble(s, u0, FFC_TANGENT_NONE, R0, 0, NULL, NULL, NULL, &nt0, &bad), FFC_OK);
    assert_int_equal(ffc_scene_stat(s, 0, "noSuchStatistic", 0, &v), FFC_ERR_LABEL);
    assert_int_equal(ffc_scene_stat(s, 1, "maxPen", 0, &v), FFC_ERR_INDEX);
    assert_int_equal(ffc_scene_stat(s, -1, "maxPen", 0, &v), FFC_OK);
    for (int i = 0; ffc_scene_stat_name(i); i++)
        assert_int_equal(ffc_scene_stat(s, 0, ffc_scene_stat_name(i), 0, &v), FFC_OK);
    double u[3 * NV] = {0}, w[3 * NV] = {0};
    u[7] = INFINITY;
    assert_int_equal(ffc_scene_search(s, u, NULL, &bad), FFC_ERR_NONFINITE);
    assert_int_equal(bad, 2);
    assert_int_equal(ffc_scene_set_motion(s, w, 0.1, 1.0), FFC_ERR_VALUE); /* not a dynamic scene */
    assert_int_equal(ffc_scene_assemble(s, w, 7, w, 0, NULL, NULL, NULL, &bad, NULL), FFC_ERR_VALUE);
    ffc_scene_free(s);
    ffc_scene_free(NULL);
}


/* Node-to-surface pairs in a scene: the rows of two pairs stacked (the
 * second pair's after the first's, each the rows of that pair alone), the
 * forces of each from its own multipliers, one method per scene, linear
 * facets only, capacity. Uniform penetration d: each slave node's row
 * asks its gap to close, c = scale d (frictionless: one row per node). */
static void test_nts_pairs(void **state)
{
    (void)state;
    double X[3 * NV], u[3 * NV] = {0};
    long Fs0[6], Fm0[6], Fs1[6], Fm1[6], bad;
    geometry(X, Fs0, Fm0, Fs1, Fm1);
    ffc_effects fx = {0, 0, 0};
    ffc_pair_opts o = ffc_pair_defaults();
    o.method = FFC_METHOD_NTS;
    o.scale = 100.0;
    ffc_scene *s = NULL, *one = NULL;
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &one), FFC_OK);
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs0, 2, Fm0, &o, &bad), 0);
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs1, 2, Fm1, &o, &bad), 1);
    assert_int_equal(ffc_scene_add_pair(one, 2, Fs1, 2, Fm1, &o, &bad), 0);
    ffc_pair_opts al = opts(0.0);
    assert_int_equal(ffc_scene_add_pair(s, 2, Fs1, 2, Fm1, &al, &bad), FFC_ERR_VALUE); /* one method per scene */
    assert_int_equal(ffc_scene_nts_step(s), FFC_OK);
    assert_int_equal(ffc_scene_nts_step(one), FFC_OK);
    long nt = 0, nr = 0;
    assert_int_equal(ffc_scene_nts_rows(s, u, NULL, 0, NULL, NULL, NULL, NULL, 0, NULL, &nt, &nr, &bad), FFC_ERR_CAPACITY);
    assert_int_equal(nr, 8);
    long Bi[200], Bj[200], Bi1[200], Bj1[200], nt1 = 0, nr1 = 0;
    double Bv[200], Fv[200], c[16], Bv1[200], Fv1[200], c1[16];
    assert_true(nt <= 200);
    assert_int_equal(ffc_scene_nts_rows(s, u, NULL, 200, Bi, Bj, Bv, Fv, 16, c, &nt, &nr, &bad), FFC_OK);
    assert_int_equal(ffc_scene_nts_rows(one, u, NULL, 200, Bi1, Bj1, Bv1, Fv1, 16, c1, &nt1, &nr1, &bad), FFC_OK);
    assert_int_equal(nr1, 4);
    for (int r = 0; r < 4; r++) {
        assert_close(c[r], o.scale * D0, 1e-12 * o.scale * D0);
        assert_close(c[4 + r], c1[r], 1e-15);       /* pair 1's rows: the lone pair's, after pair 0's */
        assert_close(c1[r], o.scale * D1, 1e-12 * o.scale * D1);
    }
    long t1 = 0;
    for (long t = 0; t < nt; t++) {
        if (Bi[t] < 4) continue;
        assert_int_equal(Bi[t] - 4, Bi1[t1]);
        assert_int_equal(Bj[t], Bj1[t1]);
        assert_close(Bv[t], Bv1[t1], 1e-15);
        t1++;
    }
    assert_int_equal(t1, nt1);
    /* multipliers: -1 on pair 0's rows, -2 on pair 1's (F = -m n, n the
     * master normal +z: compressive); each pair's force is its own */
    double m[8] = {-1, -1, -1, -1, -2, -2, -2, -2};
    long changes = -1;
    assert_int_equal(ffc_scene_nts_update(s, u, 7, m, &changes, &bad), FFC_ERR_SIZE);
    assert_int_equal(ffc_scene_nts_update(s, u, 8, m, &changes, &bad), FFC_OK);
    assert_int_equal(changes, 0);
    assert_close(stat(s, 0, "active"), 4, 0);
    assert_close(stat(s, 1, "Fz") / stat(s, 0, "Fz"), 2.0, 1e-12);
    assert_close(fabs(stat(s, 0, "Fz")), 4 * o.scale, 1e-9 * o.scale);
    assert_close(stat(s, -1, "changes"), 0, 0);
    /* the points of an NTS pair are its slave nodes */
    assert_int_equal(ffc_scene_nlinks(s, 1), 4);
    ffc_scene_free(s);
    ffc_scene_free(one);
    /* quadratic facets: refused */
    ffc_scene *q = NULL;
    double X6[3 * NV];
    memcpy(X6, X, sizeof X6);
    assert_int_equal(ffc_scene_create(6, NV, X6, 0, NULL, &fx, &q), FFC_OK);
    long F6[12] = {0, 1, 2, 3, 4, 5, 0, 2, 3, 5, 6, 7};
    assert_int_equal(ffc_scene_add_pair(q, 1, F6, 1, F6 + 6, &o, &bad), FFC_ERR_NODES);
    ffc_scene_free(q);
}

/* a contact facet between two tetrahedra (inside the mesh: the bodies on
 * its sides meshed as one) refused, slave or master; the same facet on
 * the boundary (one tetrahedron) accepted */
static void test_interior_facet(void **state)
{
    (void)state;
    const double X[5 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 1, 0.2, 0.2, -1};
    const long T[8] = {0, 1, 2, 3, 0, 1, 2, 4};
    const long mid[3] = {0, 2, 1}, side[3] = {0, 1, 3};
    ffc_effects fx = {0, 0, 0};
    ffc_pair_opts o = opts(0.0);
    long bad = -1;
    ffc_scene *s = NULL;
    assert_int_equal(ffc_scene_create(3, 5, X, 2, T, &fx, &s), FFC_OK);
    assert_int_equal(ffc_scene_add_pair(s, 1, mid, 1, side, &o, &bad), FFC_ERR_INTERIOR);
    assert_int_equal(bad, 0);
    assert_int_equal(ffc_scene_add_pair(s, 1, side, 1, mid, &o, &bad), FFC_ERR_INTERIOR);
    assert_int_equal(bad, 1);   /* (master facet 0, after the slave one) */
    assert_int_equal(ffc_scene_npairs(s), 0);
    assert_non_null(strstr(ffc_strerror(FFC_ERR_INTERIOR), "inside the mesh"));
    ffc_scene_free(s);
    assert_int_equal(ffc_scene_create(3, 5, X, 1, T, &fx, &s), FFC_OK);   /* only the upper tetrahedron */
    assert_int_equal(ffc_scene_add_pair(s, 1, mid, 1, side, &o, &bad), 0);
    ffc_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_interior_facet),
        cmocka_unit_test(test_two_pairs_independent),
        cmocka_unit_test(test_augment_shared_array),
        cmocka_unit_test(test_assembly_is_sum),
        cmocka_unit_test(test_set_fixed),
        cmocka_unit_test(test_commit_restore),
        cmocka_unit_test(test_friction_per_pair),
        cmocka_unit_test(test_touching_stick),
        cmocka_unit_test(test_auto_penalty),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_nts_pairs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
