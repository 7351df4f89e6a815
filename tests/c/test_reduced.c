/* test_reduced.c: the contact-reduced linear solve against a dense solve
 * of K + Kc (random symmetric positive definite K, or a singular one with
 * three zero eigenvalues factorized with a shift on contact dofs, as for a
 * body held only by contact; non-symmetric Kc on a subset of dofs that
 * grows between two solves), its bookkeeping and its bad input; and the
 * summing of duplicate triplets the plugin hands to FreeFEM. */
#include "ffc_test.h"

#include <stdlib.h>
#include <string.h>

enum { N = 40, CAP = 16 };


typedef struct {
    double K[N][N], Ks[N][N], sh[N];  /* K, the factorized K + diag(sh) */
    long Ti[128], Tj[128];
    double Tv[128];
    long nt;
    long dof[CAP], m;
    double G[CAP * CAP];
} rscene;

/* K = B B^T + N I, or (singular) B B^T with B of rank N - 3; the shift sh
 * = N on the dofs cd[nc] (those of the first contact set) */
static void make_K(rscene *r, int singular, const long cd[], int nc, uint64_t *s)
{
    double B[N][N];
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) B[i][j] = (singular && j >= N - 3) ? 0.0 : test_rand(s, -1, 1);
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double v = (i == j && !singular) ? N : 0.0;
            for (int k = 0; k < N; k++) v += B[i][k] * B[j][k];
            r->K[i][j] = v;
        }
    memcpy(r->Ks, r->K, sizeof r->Ks);
    memset(r->sh, 0, sizeof r->sh);
    for (int a = 0; singular && a < nc; a++) {
        r->sh[cd[a]] = N;
        r->Ks[cd[a]][cd[a]] += N;
    }
    r->m = 0;
}

static void make_Kc(rscene *r, const long cd[], int nc, uint64_t *s)
{
    r->nt = 0;
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < nc; b++)
            if ((a + 2 * b) % 3 != 1) {
                r->Ti[r->nt] = cd[a];
                r->Tj[r->nt] = cd[b];
                r->Tv[r->nt++] = test_rand(s, -20, 40) + (a == b ? 60 : 0);
            }
}

/* grows G with the missing dofs, solves, and checks x against the dense
 * solve of K + Kc (relative 1e-12: round-off of the dense solves, whose
 * condition numbers are below ~1e4 here; measured at most 3e-14) */
static void reduced_check(rscene *r, uint64_t *s)
{
    long miss[N], nmiss, pos[N];
    assert_int_equal(ffc_reduced_missing(N, r->m, r->dof, r->nt, r->Ti, r->Tj, r->Tv, N, miss, &nmiss, pos), FFC_OK);
    for (int i = 0; i < N; i++) assert_int_equal(pos[i], -1);
    for (long k = 0; k < nmiss; k++) {
        double e[N] = {0}, x[N];
        e[miss[k]] = 1.0;
        test_dense_solve(N, &r->Ks[0][0], e, x);
        assert_int_equal(ffc_reduced_add(N, CAP, r->m, r->dof, r->G, x, miss[k]), FFC_OK);
        r->m++;
    }
    assert_int_equal(ffc_reduced_missing(N, r->m, r->dof, r->nt, r->Ti, r->Tj, r->Tv, N, miss, &nmiss, pos), FFC_OK);
    assert_int_equal(nmiss, 0);
    double b[N], y[N], w[N], z[N], x[N], xr[N], xc[CAP], A[CAP * CAP];
    long piv[CAP];
    for (int i = 0; i < N; i++) b[i] = test_rand(s, -1, 1);
    test_dense_solve(N, &r->Ks[0][0], b, y);
    assert_int_equal(ffc_reduced_solve(N, CAP, r->m, r->dof, r->G, r->nt, r->Ti, r->Tj, r->Tv, r->sh, y, xc, w, A, piv, pos),
                     FFC_OK);
    test_dense_solve(N, &r->Ks[0][0], w, z);
    for (int i = 0; i < N; i++) xr[i] = y[i] - z[i];
    double M[N][N];
    memcpy(M, r->K, sizeof M);
    for (long t = 0; t < r->nt; t++) M[r->Ti[t]][r->Tj[t]] += r->Tv[t];
    test_dense_solve(N, &M[0][0], b, x);
    double err = 0, sc = 0;
    for (int i = 0; i < N; i++) { err = fmax(err, fabs(xr[i] - x[i])); sc = fmax(sc, fabs(x[i])); }
    if (!(err <= 1e-12 * sc)) fail_msg("reduced solve error %.3g of %.3g (m = %ld)", err, sc, r->m);
    for (int i = 0; i < N; i++) assert_int_equal(pos[i], -1);
}

static void test_reduced_matches_dense(void **state)
{
    (void)state;
    uint64_t s = 31;
    for (int trial = 0; trial < 6; trial++) {
        rscene r;
        const long c1[6] = {3, 17, 4, 29, 11, 38}, c2[10] = {3, 17, 4, 29, 11, 38, 0, 22, 35, 9};
        make_K(&r, trial % 2, c1, 6, &s);
        make_Kc(&r, c1, 6, &s);     /* the first contact set */
        reduced_check(&r, &s);
        assert_int_equal(r.m, 6);
        make_Kc(&r, c2, 10, &s);    /* the contact zone grows: 4 more columns */
        reduced_check(&r, &s);
        assert_int_equal(r.m, 10);
        /* G is symmetric, as K^-1 */
        for (long i = 0; i < r.m; i++)
            for (long j = 0; j < r.m; j++) assert_close(r.G[i + j * CAP], r.G[j + i * CAP], 1e-14);
    }
}

static void test_reduced_bad_input(void **state)
{
    (void)state;
    uint64_t s = 32;
    rscene r;
    const long c[3] = {1, 5, 7};
    make_K(&r, 0, c, 3, &s);
    make_Kc(&r, c, 3, &s);
    long miss[N], nmiss, pos[N], piv[CAP];
    double x[N], y[N], w[N], xc[CAP], A[CAP * CAP];
    for (int i = 0; i < N; i++) x[i] = y[i] = 0.5;
    /* capacity of the missing list: the count needed comes back */
    assert_int_equal(ffc_reduced_missing(N, 0, r.dof, r.nt, r.Ti, r.Tj, r.Tv, 2, miss, &nmiss, pos), FFC_ERR_CAPACITY);
    assert_int_equal(nmiss, 3);
    /* a triplet off the contact dofs: refused by the solve */
    assert_int_equal(ffc_reduced_add(N, CAP, 0, r.dof, r.G, x, 1), FFC_OK);
    assert_int_equal(ffc_reduced_solve(N, CAP, 1, r.dof, r.G, r.nt, r.Ti, r.Tj, r.Tv, NULL, y, xc, w, A, piv, pos),
                     FFC_ERR_INDEX);
    /* a dof twice, out of range, capacity, NaN */
    assert_int_equal(ffc_reduced_add(N, CAP, 1, r.dof, r.G, x, 1), FFC_ERR_INDEX);
    assert_int_equal(ffc_reduced_add(N, CAP, 1, r.dof, r.G, x, N), FFC_ERR_INDEX);
    assert_int_equal(ffc_reduced_add(N, 1, 1, r.dof, r.G, x, 2), FFC_ERR_CAPACITY);
    x[2] = NAN;
    assert_int_equal(ffc_reduced_add(N, CAP, 1, r.dof, r.G, x, 2), FFC_ERR_NONFINITE);
    /* singular: one contact dof with Kcc = -1 / G */
    long Ti[1] = {1}, Tj[1] = {1};
    double Tv[1] = {-1.0 / r.G[0]};
    assert_int_equal(ffc_reduced_solve(N, CAP, 1, r.dof, r.G, 1, Ti, Tj, Tv, NULL, y, xc, w, A, piv, pos), FFC_ERR_SINGULAR);
    /* a shift on a dof that is not a contact dof */
    double sh[N] = {0};
    sh[20] = 1.0;
    Tv[0] = 1.0;
    assert_int_equal(ffc_reduced_solve(N, CAP, 1, r.dof, r.G, 1, Ti, Tj, Tv, sh, y, xc, w, A, piv, pos), FFC_ERR_INDEX);
    Tv[0] = NAN;
    assert_int_equal(ffc_reduced_solve(N, CAP, 1, r.dof, r.G, 1, Ti, Tj, Tv, NULL, y, xc, w, A, piv, pos), FFC_ERR_NONFINITE);
    assert_int_equal(ffc_reduced_solve(N, CAP, 1, NULL, r.G, 1, Ti, Tj, Tv, NULL, y, xc, w, A, piv, pos), FFC_ERR_NULL);
}

/* duplicates summed: against a dense accumulation, rows ascending, every
 * (row, column) once */
static void test_triplets_sum(void **state)
{
    (void)state;
    uint64_t s = 33;
    enum { NT = 500 };
    long Ti[NT], Tj[NT], Ci[NT], Cj[NT], rp[N + 1], w[N];
    double Tv[NT], Cv[NT], D[N][N] = {{0}}, E[N][N] = {{0}};
    for (int t = 0; t < NT; t++) {
        Ti[t] = (long)test_rand(&s, 0, 12);   /* 12 x 12 block: many duplicates */
        Tj[t] = (long)test_rand(&s, 0, 12);
        Tv[t] = test_rand(&s, -1, 1);
        D[Ti[t]][Tj[t]] += Tv[t];
    }
    const long nz = ffc_triplets_sum(N, NT, Ti, Tj, Tv, Ci, Cj, Cv, rp, w);
    assert_true(nz > 0 && nz <= 144);
    for (long k = 0; k < nz; k++) {
        if (k > 0) assert_true(Ci[k] >= Ci[k - 1]);
        assert_true(E[Ci[k]][Cj[k]] == 0.0);   /* once each */
        E[Ci[k]][Cj[k]] = Cv[k];
    }
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) assert_close(E[i][j], D[i][j], 1e-13);
    Ti[7] = N;
    assert_int_equal(ffc_triplets_sum(N, NT, Ti, Tj, Tv, Ci, Cj, Cv, rp, w), FFC_ERR_INDEX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reduced_matches_dense),
        cmocka_unit_test(test_reduced_bad_input),
        cmocka_unit_test(test_triplets_sum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
