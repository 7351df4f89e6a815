/* test_hyper.c: the hyperelastic laws and their assembly (ffc_hyper_point,
 * ffc_hyper_assemble): P against central differences of W and A against
 * those of P at large stretch and compression, for each law; A at F = I
 * is the linear-elastic tensor; the assembled force against differences
 * of the stored energy and the tangent against differences of the force,
 * P1 and P2; the tangent at u = 0 against ffc_elastic_p1 / _p2; a
 * homogeneous deformation's energy; capacity and bad input. */
#include "ffc_test.h"

#define NLAWS 3
static const int laws[NLAWS] = {FFC_HYPER_NEOHOOKEAN, FFC_HYPER_SVK, FFC_HYPER_MOONEYRIVLIN};
/* the Mooney-Rivlin law's c01 as a share of mu (0 < 0.3 < 1/2: both of
 * its invariant terms act; the other laws ignore it) */
#define C01S 0.3

/* F = R diag(s) Q plus a shear: a stretch s1 along one axis, s2, s3 */
static void test_F(uint64_t *seed, double s1, double s2, double s3, double F[9])
{
    double R[3][3], Q[3][3];
    const double a1[3] = {test_rand(seed, -1, 1), test_rand(seed, -1, 1), 1}, a2[3] = {1, test_rand(seed, -1, 1), 0.3};
    test_rotation(a1, test_rand(seed, 0, 3), R);
    test_rotation(a2, test_rand(seed, 0, 3), Q);
    const double s[3] = {s1, s2, s3};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double v = 0;
            for (int k = 0; k < 3; k++) v += R[i][k] * s[k] * Q[k][j];
            F[3 * i + j] = v;
        }
}

/* Central differences with step h on entries of F: the error is h^2 / 6
 * times a third derivative, about 1e-10 relative for h = 1e-5 at these
 * stretches; round-off adds eps |W| / h ~ 1e-11: 1e-7 of the entry's
 * scale is three orders above both and far below any error of a term. */
static void test_point_fd(void **state)
{
    (void)state;
    uint64_t seed = 7;
    const double stretches[3][3] = {{1.8, 1.1, 0.9}, {0.5, 0.6, 0.8}, {1.3, 0.45, 1.6}};
    const double lam = 2.3, mu = 0.7, h = 1e-5;
    for (int l = 0; l < NLAWS; l++)
        for (int c = 0; c < 3; c++) {
            double F[9], W, P[9], A[81], pmax = 0, amax = 0;
            test_F(&seed, stretches[c][0], stretches[c][1], stretches[c][2], F);
            assert_int_equal(ffc_hyper_point(laws[l], lam, mu, C01S * mu, F, &W, P, A), FFC_OK);
            for (int k = 0; k < 9; k++) pmax = fmax(pmax, fabs(P[k]));
            for (int k = 0; k < 81; k++) amax = fmax(amax, fabs(A[k]));
            for (int m = 0; m < 9; m++) {
                double Fp[9], Fm[9], Wp, Wm, Pp[9], Pm[9];
                memcpy(Fp, F, sizeof Fp); memcpy(Fm, F, sizeof Fm);
                Fp[m] += h; Fm[m] -= h;
                assert_int_equal(ffc_hyper_point(laws[l], lam, mu, C01S * mu, Fp, &Wp, Pp, NULL), FFC_OK);
                assert_int_equal(ffc_hyper_point(laws[l], lam, mu, C01S * mu, Fm, &Wm, Pm, NULL), FFC_OK);
                assert_close(P[m], (Wp - Wm) / (2 * h), 1e-7 * pmax);
                for (int k = 0; k < 9; k++) assert_close(A[9 * k + m], (Pp[k] - Pm[k]) / (2 * h), 1e-7 * amax);
            }
            /* a stored energy's tangent is major-symmetric */
            for (int a = 0; a < 9; a++)
                for (int b = 0; b < 9; b++) assert_close(A[9 * a + b], A[9 * b + a], 1e-14 * amax);
        }
}

/* at F = I: W = 0, P = 0, A = lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_Jk) exactly */
static void test_point_linearization(void **state)
{
    (void)state;
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, lam = 1.7, mu = 0.4;
    for (int l = 0; l < NLAWS; l++) {
        double W, P[9], A[81];
        assert_int_equal(ffc_hyper_point(laws[l], lam, mu, C01S * mu, I, &W, P, A), FFC_OK);
        assert_close(W, 0.0, 1e-15);
        for (int k = 0; k < 9; k++) assert_close(P[k], 0.0, 1e-15);
        for (int i = 0; i < 3; i++)
            for (int J = 0; J < 3; J++)
                for (int k = 0; k < 3; k++)
                    for (int L = 0; L < 3; L++) {
                        const double want = lam * (i == J) * (k == L) + mu * ((i == k) * (J == L) + (i == L) * (J == k));
                        assert_close(A[27 * i + 9 * J + 3 * k + L], want, 1e-15);
                    }
    }
}

/* the two tetrahedra of test_elastic (one negatively numbered) */
static void two_tets(uint64_t *s, double X[15], long T[8])
{
    const double X0[15] = {0, 0, -1, 1, 0, 0, 0, 1, 0, -1, -1, 0.2, 0.1, 0.2, 1};
    for (int k = 0; k < 15; k++) X[k] = X0[k] + test_rand(s, -0.1, 0.1);
    const long T0[8] = {0, 1, 2, 3, 4, 2, 1, 3};
    memcpy(T, T0, sizeof T0);
}

/* the mesh of two tetrahedra, P1 or P2 (node numbering by ffc_p2_number) */
typedef struct {
    double X[15];
    long T[8], node[20], nn;
    ffc_tets m;
    long rp[16], adj[200], nb;
} two_mesh;

static void make_mesh(uint64_t *s, int p2, two_mesh *g)
{
    two_tets(s, g->X, g->T);
    g->nn = 5;
    if (p2) assert_int_equal(ffc_p2_number(2, g->T, 5, g->node, &g->nn), FFC_OK);
    g->m = (ffc_tets){5, g->X, 2, g->T, p2 ? 10 : 4, g->nn, p2 ? g->node : g->T};
    ffc_error err;
    assert_int_equal(ffc_tets_pattern(&g->m, 200, g->rp, g->adj, &g->nb, &err), FFC_OK);
}

/* Force and tangent against central differences of the energy and of the
 * force, at a displacement of about 30 % strain; h = 1e-6 of the element
 * size, tolerance as in test_point_fd. */
static void test_assemble_fd(void **state)
{
    (void)state;
    uint64_t seed = 11;
    for (int p2 = 0; p2 < 2; p2++)
        for (int l = 0; l < NLAWS; l++) {
            two_mesh g;
            make_mesh(&seed, p2, &g);
            const long n = 3 * g.nn, nz = 9 * g.nb;
            double lam[2] = {1.5, 0.8}, mu[2] = {0.6, 0.3}, c01[2] = {C01S * 0.6, C01S * 0.3}, u[42], f[42], W,
                   *Kv = malloc((size_t)nz * sizeof *Kv);
            long *Ki = malloc((size_t)nz * sizeof *Ki), *Kj = malloc((size_t)nz * sizeof *Kj);
            for (long k = 0; k < n; k++) u[k] = test_rand(&seed, -0.15, 0.15);
            ffc_error err;
            assert_int_equal(ffc_hyper_assemble(laws[l], &g.m, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_OK);
            ffc_tets_pattern_ij(g.nn, g.rp, g.adj, Ki, Kj);
            double K[42][42] = {{0}}, fmx = 0, kmx = 0;
            for (long e = 0; e < nz; e++) { K[Ki[e]][Kj[e]] += Kv[e]; kmx = fmax(kmx, fabs(Kv[e])); }
            for (long k = 0; k < n; k++) fmx = fmax(fmx, fabs(f[k]));
            const double h = 1e-6;
            for (long j = 0; j < n; j++) {
                double up[42], um[42], fp[42], fm[42], Wp, Wm;
                memcpy(up, u, sizeof up); memcpy(um, u, sizeof um);
                up[j] += h; um[j] -= h;
                assert_int_equal(ffc_hyper_assemble(laws[l], &g.m, lam, mu, c01, up, g.rp, g.adj, &Wp, fp, NULL, &err), FFC_OK);
                assert_int_equal(ffc_hyper_assemble(laws[l], &g.m, lam, mu, c01, um, g.rp, g.adj, &Wm, fm, NULL, &err), FFC_OK);
                assert_close(f[j], (Wp - Wm) / (2 * h), 1e-7 * fmx);
                for (long i = 0; i < n; i++) assert_close(K[i][j], (fp[i] - fm[i]) / (2 * h), 1e-7 * kmx);
            }
            for (long i = 0; i < n; i++)
                for (long j = 0; j < n; j++) assert_close(K[i][j], K[j][i], 1e-13 * kmx);
            free(Kv); free(Ki); free(Kj);
        }
}

/* At u = 0 the tangent is linear elasticity's stiffness, for each law:
 * ffc_elastic_p1 / _p2's entry for entry (the same pattern; P2's 14-point
 * rule and the elastic 4-point one are both exact for its quadratic
 * integrand) */
static void test_assemble_small_strain(void **state)
{
    (void)state;
    uint64_t seed = 3;
    for (int p2 = 0; p2 < 2; p2++)
    for (int l = 0; l < NLAWS; l++) {
        two_mesh g;
        make_mesh(&seed, p2, &g);
        const long nz = 9 * g.nb;
        double lam[2] = {1.5, 0.8}, mu[2] = {0.6, 0.3}, c01[2] = {C01S * 0.6, C01S * 0.3}, u[42] = {0}, f[42], W, Kv[2000],
               Ev[2000];
        long Ki[2000], Kj[2000], Ei[2000], Ej[2000], nnz = 0, bad;
        assert_true(nz <= 2000);
        ffc_error err;
        assert_int_equal(ffc_hyper_assemble(laws[l], &g.m, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_OK);
        ffc_tets_pattern_ij(g.nn, g.rp, g.adj, Ki, Kj);
        if (p2) assert_int_equal(ffc_elastic_p2(5, g.X, 2, g.T, g.nn, g.node, lam, mu, 2000, Ei, Ej, Ev, &nnz, &bad), FFC_OK);
        else assert_int_equal(ffc_elastic_p1(5, g.X, 2, g.T, lam, mu, 2000, Ei, Ej, Ev, &nnz, &bad), FFC_OK);
        assert_int_equal(nnz, nz);
        double emx = 0;
        for (long e = 0; e < nz; e++) emx = fmax(emx, fabs(Ev[e]));
        for (long e = 0; e < nz; e++) {
            assert_int_equal(Ki[e], Ei[e]);
            assert_int_equal(Kj[e], Ej[e]);
            assert_close(Kv[e], Ev[e], 1e-13 * emx);
        }
        assert_close(W, 0.0, 1e-15);
        for (long k = 0; k < 3 * g.nn; k++) assert_close(f[k], 0.0, 1e-15);
    }
}

/* A homogeneous deformation u = (F0 - I) x: every point has F0, the
 * energy is (total volume) W(F0), the force is that of the constant
 * stress P0 (the nodes of the shared face get no net force from inside). */
static void test_assemble_homogeneous(void **state)
{
    (void)state;
    uint64_t seed = 5;
    for (int p2 = 0; p2 < 2; p2++)
        for (int l = 0; l < NLAWS; l++) {
            two_mesh g;
            make_mesh(&seed, p2, &g);
            double F0[9], P0[9], W0, XN[42], u[42], f[42], W;
            test_F(&seed, 1.4, 0.7, 1.1, F0);
            assert_int_equal(ffc_hyper_point(laws[l], 1.0, 0.5, C01S * 0.5, F0, &W0, P0, NULL), FFC_OK);
            if (p2) assert_int_equal(ffc_p2_positions(2, g.T, g.node, g.X, g.nn, XN), FFC_OK);
            else memcpy(XN, g.X, sizeof g.X);
            for (long i = 0; i < g.nn; i++)
                for (int r = 0; r < 3; r++)
                    u[3 * i + r] = (F0[3 * r] - (r == 0)) * XN[3 * i] + (F0[3 * r + 1] - (r == 1)) * XN[3 * i + 1]
                                   + (F0[3 * r + 2] - (r == 2)) * XN[3 * i + 2];
            double lam[2] = {1, 1}, mu[2] = {0.5, 0.5}, c01[2] = {C01S * 0.5, C01S * 0.5}, V = 0;
            for (int t = 0; t < 2; t++) {
                const double *a = g.X + 3 * g.T[4 * t], *b = g.X + 3 * g.T[4 * t + 1], *c = g.X + 3 * g.T[4 * t + 2], *d = g.X + 3 * g.T[4 * t + 3];
                double e1[3], e2[3], e3[3], x[3];
                for (int r = 0; r < 3; r++) { e1[r] = b[r] - a[r]; e2[r] = c[r] - a[r]; e3[r] = d[r] - a[r]; }
                x[0] = e2[1] * e3[2] - e2[2] * e3[1]; x[1] = e2[2] * e3[0] - e2[0] * e3[2]; x[2] = e2[0] * e3[1] - e2[1] * e3[0];
                V += fabs(e1[0] * x[0] + e1[1] * x[1] + e1[2] * x[2]) / 6;
            }
            ffc_error err;
            assert_int_equal(ffc_hyper_assemble(laws[l], &g.m, lam, mu, c01, u, g.rp, g.adj, &W, f, NULL, &err), FFC_OK);
            assert_close(W, V * W0, 1e-13 * fabs(V * W0) * 10);
            /* the net force vanishes (a constant stress is in equilibrium) */
            for (int r = 0; r < 3; r++) {
                double s = 0, sc = 0;
                for (long i = 0; i < g.nn; i++) { s += f[3 * i + r]; sc += fabs(f[3 * i + r]); }
                assert_close(s, 0.0, 1e-13 * sc * 10);
            }
        }
}

static void test_hyper_errors(void **state)
{
    (void)state;
    uint64_t seed = 9;
    two_mesh g;
    make_mesh(&seed, 0, &g);
    double lam[2] = {1, 1}, mu[2] = {1, 1}, c01[2] = {0.2, 0.2}, u[15] = {0}, f[15], W, P[9], Kv[500];
    ffc_error err;
    /* the pattern's capacity: the count needed with FFC_ERR_CAPACITY */
    long rp[6], adj[30], nb = 0;
    assert_int_equal(ffc_tets_pattern(&g.m, 3, rp, adj, &nb, &err), FFC_ERR_CAPACITY);
    assert_int_equal(nb, g.nb);
    assert_int_equal(err.where, FFC_AT_COUNT);
    assert_int_equal(ffc_tets_pattern(&g.m, nb, rp, adj, &nb, &err), FFC_OK);
    /* an unknown law */
    assert_int_equal(ffc_hyper_assemble(7, &g.m, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_ERR_VALUE);
    assert_int_equal(ffc_hyper_point(7, 1, 1, 0, (double[9]){1, 0, 0, 0, 1, 0, 0, 0, 1}, &W, P, NULL), FFC_ERR_VALUE);
    /* det F <= 0: the Neo-Hookean law refuses, naming the tetrahedron */
    const double Fi[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
    assert_int_equal(ffc_hyper_point(FFC_HYPER_NEOHOOKEAN, 1, 1, 0, Fi, &W, P, NULL), FFC_ERR_INVERTED);
    for (int r = 0; r < 3; r++) u[3 * 4 + r] = -3 * (g.X[3 * 4 + r] - g.X[3 * 1 + r]);   /* vertex 4 pushed through face 1 2 3 */
    assert_int_equal(ffc_hyper_assemble(FFC_HYPER_NEOHOOKEAN, &g.m, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_ERR_INVERTED);
    assert_int_equal(err.where, FFC_AT_ELEMENT);
    assert_int_equal(err.index, 1);
    assert_true(strstr(err.msg, "tetrahedron 1") != NULL);
    /* Mooney-Rivlin: det F <= 0 refused too; its c01 present and within [0, mu / 2] */
    assert_int_equal(ffc_hyper_point(FFC_HYPER_MOONEYRIVLIN, 1, 1, 0.2, Fi, &W, P, NULL), FFC_ERR_INVERTED);
    assert_int_equal(ffc_hyper_assemble(FFC_HYPER_MOONEYRIVLIN, &g.m, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_ERR_INVERTED);
    memset(u, 0, sizeof u);
    assert_int_equal(ffc_hyper_assemble(FFC_HYPER_MOONEYRIVLIN, &g.m, lam, mu, NULL, u, g.rp, g.adj, &W, f, Kv, &err), FFC_ERR_NULL);
    const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    assert_int_equal(ffc_hyper_point(FFC_HYPER_MOONEYRIVLIN, 1, 1, 0.6, I3, &W, P, NULL), FFC_ERR_VALUE);
    assert_int_equal(ffc_hyper_point(FFC_HYPER_MOONEYRIVLIN, 1, 1, -0.1, I3, &W, P, NULL), FFC_ERR_VALUE);
    c01[1] = 0.7;
    assert_int_equal(ffc_hyper_assemble(FFC_HYPER_MOONEYRIVLIN, &g.m, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_ERR_VALUE);
    assert_int_equal(err.where, FFC_AT_ELEMENT);
    assert_int_equal(err.index, 1);
    assert_true(strstr(err.msg, "c01 = 0.7") != NULL);
    c01[1] = 0.2;
    /* a NaN displacement names its dof */
    memset(u, 0, sizeof u);
    u[7] = NAN;
    assert_int_equal(ffc_hyper_assemble(FFC_HYPER_SVK, &g.m, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_ERR_NONFINITE);
    assert_int_equal(err.where, FFC_AT_DOF);
    assert_int_equal(err.index, 7);
    u[7] = 0;
    /* a node outside the mesh */
    long Tb[8];
    memcpy(Tb, g.T, sizeof Tb);
    Tb[5] = 9;
    ffc_tets mb = g.m;
    mb.T = Tb; mb.E = Tb;
    assert_int_equal(ffc_hyper_assemble(FFC_HYPER_SVK, &mb, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_ERR_INDEX);
    assert_int_equal(err.index, 1);
    /* a pattern that lacks a pair of the mesh */
    long adj2[200];
    memcpy(adj2, g.adj, sizeof adj2);
    adj2[g.rp[0] + 1] = adj2[g.rp[0]];
    assert_int_equal(ffc_hyper_assemble(FFC_HYPER_SVK, &g.m, lam, mu, c01, u, g.rp, adj2, &W, f, Kv, &err), FFC_ERR_INDEX);
    /* a degenerate tetrahedron */
    double X2[15];
    memcpy(X2, g.X, sizeof X2);
    for (int r = 0; r < 3; r++) X2[3 * 4 + r] = (X2[3 * 1 + r] + X2[3 * 2 + r] + X2[3 * 3 + r]) / 3;
    mb = g.m;
    mb.X = X2;
    assert_int_equal(ffc_hyper_assemble(FFC_HYPER_SVK, &mb, lam, mu, c01, u, g.rp, g.adj, &W, f, Kv, &err), FFC_ERR_DEGENERATE);
    assert_int_equal(err.index, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_fd),
        cmocka_unit_test(test_point_linearization),
        cmocka_unit_test(test_assemble_fd),
        cmocka_unit_test(test_assemble_small_strain),
        cmocka_unit_test(test_assemble_homogeneous),
        cmocka_unit_test(test_hyper_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
