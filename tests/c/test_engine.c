/* test_engine.c: the linear engines behind one interface (CHOLMOD,
 * UMFPACK) against each other and against a dense elimination on the same
 * systems; their reasons (a singular matrix, out of memory, a call out of
 * order) as one line naming the cause; the full solver's reuse of its
 * analysis; the Newton loops' line search. */
#include <stdio.h>
#include <sys/resource.h>

#include "ffc_test.h"
#include "engine_test.h" /* (internal: the engines) */

#define N 40

/* under AddressSanitizer an address-space limit cannot hold its shadow memory */
#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif

/* an SPD matrix: a 1D Laplacian (2, -1) plus a random symmetric coupling
 * of rows 5 apart, diagonally dominant; lower triangle into (ti, tj, tv),
 * the whole into D (column-major) */
static long spd(int ti[], int tj[], double tv[], double D[N * N])
{
    uint64_t s = 11;
    long nz = 0;
    memset(D, 0, sizeof(double) * N * N);
    for (int i = 0; i < N; i++) {
        ti[nz] = i; tj[nz] = i; tv[nz] = 4.0; nz++;
        D[i + i * N] += 4.0;
        if (i > 0) { ti[nz] = i; tj[nz] = i - 1; tv[nz] = -1.0; nz++; D[i + (i - 1) * N] = D[i - 1 + i * N] = -1.0; }
        if (i >= 5) {
            const double v = test_rand(&s, -0.5, 0.5);
            ti[nz] = i; tj[nz] = i - 5; tv[nz] = v; nz++;
            D[i + (i - 5) * N] = D[i - 5 + i * N] = v;
        }
    }
    return nz;
}

static ffc__ranks one = {0, 0, 1, NULL};

/* CHOLMOD and UMFPACK (the symmetric lower triangle expanded): the same
 * solution and entries of the inverse as a dense elimination, to 1e-13
 * (a condition number below 10: round-off of a few ulps each) */
static void test_same_solutions(void **state)
{
    (void)state;
    static int ti[3 * N], tj[3 * N];
    static double tv[3 * N], D[N * N];
    const long nz = spd(ti, tj, tv, D);
    const ffc__tri A = {N, nz, ti, tj, tv, 1};
    double b[N], xd[N];
    for (int i = 0; i < N; i++) b[i] = sin(1.0 + i);
    test_dense_solve(N, D, b, xd);
    const long cols[4] = {17, 3, 39, 0}, rows[6] = {0, 39, 5, 17, 22, 3};
    double Xd[24];
    for (int c = 0; c < 4; c++) {
        double e[N] = {0}, x[N];
        e[cols[c]] = 1.0;
        test_dense_solve(N, D, e, x);
        for (int r = 0; r < 6; r++) Xd[r + 6 * c] = x[rows[r]];
    }
    for (int k = 0; k < 2; k++) {
        ffc_solve_info info = {0};
        ffc__engine *e = NULL;
        assert_int_equal(k ? ffc__umfpack_create(&info, &e) : ffc__cholmod_create(&info, &one, &e), FFC_OK);
        double x[N], X[24];
        assert_int_equal(e->op->analyze(e, &A), FFC_OK);
        assert_int_equal(e->op->factorize(e, &A), FFC_OK);
        assert_int_equal(e->op->solve(e, b, x), FFC_OK);
        for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-13);
        assert_int_equal(test_inverse(e, 4, cols, 6, rows, X), FFC_OK);
        for (int i = 0; i < 24; i++) assert_close(X[i], Xd[i], 1e-13);
        assert_true(info.rcond > 0.05 && info.rcond <= 1.0);
        /* new values on the same pattern: factorized again without a new analysis */
        tv[0] = 5.0;
        D[0] = 5.0;
        assert_int_equal(e->op->factorize(e, &A), FFC_OK);
        double x2[N], xd2[N];
        assert_int_equal(e->op->solve(e, b, x2), FFC_OK);
        test_dense_solve(N, D, b, xd2);
        for (int i = 0; i < N; i++) assert_close(x2[i], xd2[i], 1e-13);
        assert_true(fabs(x2[0] - x[0]) > 1e-3);   /* (the change shows) */
        tv[0] = 4.0;
        D[0] = 4.0;
        e->op->free(e);
    }
}

/* a general matrix (UMFPACK): the dense elimination's solution */
static void test_unsymmetric(void **state)
{
    (void)state;
    uint64_t s = 3;
    static int ti[4 * N + 1], tj[4 * N + 1];
    static double tv[4 * N + 1], D[N * N];
    memset(D, 0, sizeof D);
    long nz = 0;
    for (int i = 0; i < N; i++) {
        ti[nz] = i; tj[nz] = i; tv[nz] = 3.0 + test_rand(&s, 0, 1); D[i * N + i] = tv[nz]; nz++;
        const int j = (i * 7 + 3) % N;
        if (j != i) { ti[nz] = i; tj[nz] = j; tv[nz] = test_rand(&s, -1, 1); D[i * N + j] += tv[nz]; nz++; }
        const int k = (i * 13 + 5) % N;
        if (k != i && k != j) { ti[nz] = k; tj[nz] = i; tv[nz] = test_rand(&s, -1, 1); D[k * N + i] += tv[nz]; nz++; }
    }
    const ffc__tri A = {N, nz, ti, tj, tv, 0};
    double b[N], x[N], xd[N];
    for (int i = 0; i < N; i++) b[i] = cos(0.3 * i);
    test_dense_solve(N, D, b, xd);
    ffc_solve_info info = {0};
    ffc__engine *e = NULL;
    assert_int_equal(ffc__umfpack_create(&info, &e), FFC_OK);
    assert_int_equal(e->op->analyze(e, &A), FFC_OK);
    assert_int_equal(e->op->factorize(e, &A), FFC_OK);
    assert_int_equal(e->op->solve(e, b, x), FFC_OK);
    for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-12);
    /* new values on the same triplets (filled through the analysis's map),
     * a duplicate of the first entry among them; then the same entries in
     * another order (converted again): the dense solutions each time */
    tv[1] *= -2.0;
    D[ti[1] * N + tj[1]] = 0.0;
    for (long k = 1; k < nz; k++)
        if (ti[k] == ti[1] && tj[k] == tj[1]) D[ti[k] * N + tj[k]] += tv[k];
    ti[nz] = ti[0]; tj[nz] = tj[0]; tv[nz] = 0.5; D[ti[0] * N + tj[0]] += 0.5;
    const ffc__tri A2 = {N, nz + 1, ti, tj, tv, 0};
    assert_int_equal(e->op->analyze(e, &A2), FFC_OK);
    for (int round = 0; round < 2; round++) {
        tv[0] += 1.0; D[ti[0] * N + tj[0]] += 1.0;
        assert_int_equal(e->op->factorize(e, &A2), FFC_OK);
        assert_int_equal(e->op->solve(e, b, x), FFC_OK);
        test_dense_solve(N, D, b, xd);
        for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-12);
    }
    static int ri[4 * N + 1], rj[4 * N + 1];
    static double rv[4 * N + 1];
    for (long k = 0; k <= nz; k++) { ri[k] = ti[nz - k]; rj[k] = tj[nz - k]; rv[k] = tv[nz - k]; }
    const ffc__tri A3 = {N, nz + 1, ri, rj, rv, 0};
    assert_int_equal(e->op->factorize(e, &A3), FFC_OK);
    assert_int_equal(e->op->solve(e, b, x), FFC_OK);
    for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-12);
    e->op->free(e);
    /* CHOLMOD refuses a general matrix, naming it */
    assert_int_equal(ffc__cholmod_create(&info, &one, &e), FFC_OK);
    assert_int_equal(e->op->analyze(e, &A), FFC_ERR_VALUE);
    assert_string_equal(e->err.msg, "CHOLMOD: the matrix is not symmetric");
    e->op->free(e);
}

/* the reasons: a singular matrix (a zero row), a call out of order, each
 * engine's own line */
static void test_reasons(void **state)
{
    (void)state;
    int ti[3] = {0, 1, 2}, tj[3] = {0, 1, 2};
    double tv[3] = {1.0, 0.0, 2.0}, b[3] = {1, 1, 1}, x[3];
    const ffc__tri A = {3, 3, ti, tj, tv, 1};
    ffc_solve_info info = {0};
    for (int k = 0; k < 2; k++) {
        ffc__engine *e = NULL;
        assert_int_equal(k ? ffc__umfpack_create(&info, &e) : ffc__cholmod_create(&info, &one, &e), FFC_OK);
        assert_int_equal(e->op->factorize(e, &A), FFC_ERR_EMPTY);
        assert_non_null(strstr(e->err.msg, "not analysed"));
        assert_int_equal(e->op->analyze(e, &A), FFC_OK);
        assert_int_equal(e->op->solve(e, b, x), FFC_ERR_EMPTY);
        assert_non_null(strstr(e->err.msg, "not factorized"));
        assert_int_equal(e->op->factorize(e, &A), FFC_ERR_SINGULAR);
        assert_int_equal(e->err.status, FFC_ERR_SINGULAR);
        assert_non_null(strstr(e->err.msg, k ? "UMFPACK: the matrix is singular" : "CHOLMOD: the matrix is not "
                                                                                    "positive definite"));
        assert_null(strchr(e->err.msg, '\n'));
        e->op->free(e);
    }
}

/* out of memory: a matrix of 20 million rows under a 600 MB address
 * space limit; the engine says so, with the order it failed on, and the
 * process goes on (the limit lifted) */
static void test_out_of_memory(void **state)
{
    (void)state;
#ifdef UNDER_ASAN
    skip();
#endif
    const long n = 20000000;
    int *ti = malloc((size_t)n * sizeof *ti);
    double *tv = malloc((size_t)n * sizeof *tv);
    assert_non_null(ti);
    assert_non_null(tv);
    for (long i = 0; i < n; i++) { ti[i] = (int)i; tv[i] = 1.0; }
    const ffc__tri A = {n, n, ti, ti, tv, 1};
    struct rlimit old, lim;
    getrlimit(RLIMIT_AS, &old);
    for (int k = 0; k < 2; k++) {
        ffc_solve_info info = {0};
        ffc__engine *e = NULL;
        assert_int_equal(k ? ffc__umfpack_create(&info, &e) : ffc__cholmod_create(&info, &one, &e), FFC_OK);
        lim = old;
        lim.rlim_cur = 600UL << 20;
        assert_int_equal(setrlimit(RLIMIT_AS, &lim), 0);
        const int st = e->op->analyze(e, &A);
        setrlimit(RLIMIT_AS, &old);
        assert_int_equal(st, FFC_ERR_MEMORY);
        assert_int_equal(e->err.where, FFC_AT_COUNT);
        assert_int_equal(e->err.index, n);
        char want[64];
        snprintf(want, sizeof want, "out of memory analysing a matrix of order %ld", n);
        assert_non_null(strstr(e->err.msg, want));
        e->op->free(e);
    }
    free(ti);
    free(tv);
}

/* spd's matrix with both triangles, as the full solver takes it (long
 * triplets); *k0 (unless NULL): the position of the entry (0, 0) */
static long spd_whole(long Ti[6 * N], long Tj[6 * N], double Tv[6 * N], double D[N * N], long *k0)
{
    static int ti[3 * N], tj[3 * N];
    static double tv[3 * N];
    const long nz = spd(ti, tj, tv, D);
    long nt = 0;
    for (long k = 0; k < nz; k++) {
        if (k0 && ti[k] == 0 && tj[k] == 0) *k0 = nt;
        Ti[nt] = ti[k]; Tj[nt] = tj[k]; Tv[nt++] = tv[k];
        if (ti[k] != tj[k]) { Ti[nt] = tj[k]; Tj[nt] = ti[k]; Tv[nt++] = tv[k]; }
    }
    return nt;
}

/* the full solver: two solves on one pattern, one analysis; a subset of
 * it, none; a new coupling, a second; bad input named */
static void test_full_reuse(void **state)
{
    (void)state;
    static double D[N * N];
    static long Ti[6 * N], Tj[6 * N];
    static double Tv[6 * N];
    long nt = spd_whole(Ti, Tj, Tv, D, NULL);
    ffc_full *f = NULL;
    assert_int_equal(ffc_full_create(&f), FFC_OK);
    double b[N], x[N], xd[N];
    for (int i = 0; i < N; i++) b[i] = 1.0 + i;
    ffc_error err;
    for (int pass = 0; pass < 2; pass++) {
        if (pass) { Tv[0] *= 2; D[0] *= 2; }
        assert_int_equal(ffc_full_solve(f, N, nt, Ti, Tj, Tv, 0, b, x, &err), FFC_OK);
        test_dense_solve(N, D, b, xd);
        for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-13);
    }
    ffc_solve_info in;
    long analyses = 0;
    assert_int_equal(ffc_full_info(f, &in, &analyses, NULL, NULL), FFC_OK);
    assert_int_equal(analyses, 1);
    assert_int_equal(in.factorizations, 2);
    /* the same entries in the reverse order, a value changed: the dense
     * solution */
    {
        static long Ri[6 * N], Rj[6 * N];
        static double Rv[6 * N];
        for (long k = 0; k < nt; k++) { Ri[k] = Ti[nt - 1 - k]; Rj[k] = Tj[nt - 1 - k]; Rv[k] = Tv[nt - 1 - k]; }
        Rv[nt - 1] += 1.0;   /* (Tv[0], a diagonal entry) */
        D[Ti[0] * N + Tj[0]] += 1.0;
        assert_int_equal(ffc_full_solve(f, N, nt, Ri, Rj, Rv, 0, b, x, &err), FFC_OK);
        test_dense_solve(N, D, b, xd);
        for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-13);
        D[Ti[0] * N + Tj[0]] -= 1.0;
    }
    /* a matrix of fewer entries lies in the analysed pattern: no analysis */
    assert_int_equal(ffc_full_solve(f, N, nt - 1, Ti, Tj, Tv, 0, b, x, &err), FFC_OK);
    assert_int_equal(ffc_full_info(f, &in, &analyses, NULL, NULL), FFC_OK);
    assert_int_equal(analyses, 1);
    /* one that couples two dofs the pattern does not: the union analysed */
    Ti[nt] = 0; Tj[nt] = N - 1; Tv[nt] = 0.25;
    Ti[nt + 1] = N - 1; Tj[nt + 1] = 0; Tv[nt + 1] = 0.25;
    D[(N - 1) * N] = D[N - 1] = 0.25;
    assert_int_equal(ffc_full_solve(f, N, nt + 2, Ti, Tj, Tv, 0, b, x, &err), FFC_OK);
    test_dense_solve(N, D, b, xd);
    for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-13);
    assert_int_equal(ffc_full_info(f, &in, &analyses, NULL, NULL), FFC_OK);
    assert_int_equal(analyses, 2);
    Tv[3] = NAN;
    assert_int_equal(ffc_full_solve(f, N, nt, Ti, Tj, Tv, 0, b, x, &err), FFC_ERR_NONFINITE);
    assert_int_equal(err.where, FFC_AT_TRIPLET);
    assert_int_equal(err.index, 3);
    ffc_full_free(f);
}

/* the full solver on symmetric matrices: a positive definite one by
 * CHOLMOD (analysed once for two values of one pattern), a symmetric
 * indefinite one (its first diagonal entry made negative) by UMFPACK,
 * both against a dense elimination; a diagonal of tgv = 1e30 (FreeFEM's
 * Dirichlet rows) is no failure */
static void test_full_symmetric(void **state)
{
    (void)state;
    static double D[N * N];
    static long Ti[6 * N], Tj[6 * N];
    static double Tv[6 * N];
    long k0 = -1;
    const long nt = spd_whole(Ti, Tj, Tv, D, &k0);
    assert_true(k0 >= 0);
    ffc_full *f = NULL;
    assert_int_equal(ffc_full_create(&f), FFC_OK);
    double b[N], x[N], xd[N];
    for (int i = 0; i < N; i++) b[i] = 1.0 + i;
    ffc_error err;
    ffc_solve_info in;
    long analyses = 0, chol = 0, npd = 0;
    for (int pass = 0; pass < 3; pass++) {
        if (pass == 1) { Tv[k0] *= 2; D[0] *= 2; }
        if (pass == 2) { Tv[k0] = 1e30; D[0] = 1e30; }
        assert_int_equal(ffc_full_solve(f, N, nt, Ti, Tj, Tv, 1, b, x, &err), FFC_OK);
        test_dense_solve(N, D, b, xd);
        for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-12 * (1 + fabs(xd[i])));
    }
    assert_int_equal(ffc_full_info(f, &in, &analyses, &chol, &npd), FFC_OK);
    assert_int_equal(chol, 3);
    assert_int_equal(npd, 0);
    assert_int_equal(analyses, 1);
    /* factor reuse: a nearby symmetric matrix by GMRES on the last LL^T,
     * the product by the whole symmetric matrix (its lower triangle
     * mirrored), against a dense elimination */
    assert_int_equal(ffc_full_set_reuse(f, 8), FFC_OK);
    for (long k = 0; k < nt; k++)
        if (Ti[k] != Tj[k]) Tv[k] *= 1.01;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            if (i != j) D[i + j * N] *= 1.01;
    assert_int_equal(ffc_full_solve(f, N, nt, Ti, Tj, Tv, 1, b, x, &err), FFC_OK);
    test_dense_solve(N, D, b, xd);
    for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-12 * (1 + fabs(xd[i])));
    long reused = 0;
    assert_int_equal(ffc_full_reuse_info(f, &reused, NULL), FFC_OK);
    assert_int_equal(reused, 1);
    assert_int_equal(ffc_full_set_reuse(f, 0), FFC_OK);
    Tv[k0] = -D[N + 1]; D[0] = -D[N + 1];   /* indefinite */
    assert_int_equal(ffc_full_solve(f, N, nt, Ti, Tj, Tv, 1, b, x, &err), FFC_OK);
    test_dense_solve(N, D, b, xd);
    for (int i = 0; i < N; i++) assert_close(x[i], xd[i], 1e-10 * (1 + fabs(xd[i])));
    /* (CHOLMOD's simplicial LDL^T, its choice on a matrix this small, may
     * factorize it; its supernodal LL^T, on larger ones, does not) */
    assert_int_equal(ffc_full_info(f, &in, &analyses, &chol, &npd), FFC_OK);
    assert_int_equal(chol + npd, 4);
    ffc_full_free(f);
}

/* the line search on g(a) = (a - 0.3) (a + 1) (a root at 0.3, g(0) < 0):
 * phase 1 brackets the root and takes a point within ls_tol; a rejected
 * point moves the upper bound to the middle; phase 2 halves a step whose
 * |r| grew more than tenfold */
static void test_line_search(void **state)
{
    (void)state;
    ffc_linesearch s;
    double a = 0.0;
    assert_int_equal(ffc_ls_start(&s, 8, 0.5, 1.0, -0.3, 1.0, 1, 1), FFC_OK);
    int evals = 0;
    while (ffc_ls_next(&s, &a) == 1) {
        evals++;
        assert_int_equal(ffc_ls_report(&s, (a - 0.3) * (a + 1), 1.0, 0), FFC_OK);
    }
    assert_true(fabs((a - 0.3) * (a + 1)) <= 0.5 * 0.3);
    assert_true(evals >= 2 && evals <= 8);
    /* the point last evaluated is not evaluated again in phase 2 */
    assert_int_equal(s.at, a);
    /* a rejected point: the next is the middle of [0, a] */
    assert_int_equal(ffc_ls_start(&s, 8, 0.5, 1.0, -0.3, 1.0, 1, 0), FFC_OK);
    assert_int_equal(ffc_ls_next(&s, &a), 1);
    assert_int_equal(ffc_ls_reject(&s), FFC_OK);
    assert_int_equal(ffc_ls_next(&s, &a), 1);
    assert_close(a, 0.5, 0);
    /* the full step taken on |r| alone at a = 1 */
    assert_int_equal(ffc_ls_start(&s, 8, 0.5, 1.0, -0.3, 1.0, 1, 0), FFC_OK);
    assert_int_equal(ffc_ls_next(&s, &a), 1);
    assert_int_equal(ffc_ls_report(&s, 5.0, 0.1, 1), FFC_OK);
    assert_int_equal(ffc_ls_next(&s, &a), 0);
    assert_close(a, 1.0, 0);
    /* phase 2 alone: |r| 100 at a = 1, 5 at 0.5 (<= 10 |r(0)| = 10) */
    assert_int_equal(ffc_ls_start(&s, 8, 0.5, 1.0, -0.3, 1.0, 0, 1), FFC_OK);
    assert_int_equal(ffc_ls_next(&s, &a), 1);
    assert_int_equal(ffc_ls_report(&s, 0.0, 100.0, 0), FFC_OK);
    assert_int_equal(ffc_ls_next(&s, &a), 1);
    assert_close(a, 0.5, 0);
    assert_int_equal(ffc_ls_report(&s, 0.0, 5.0, 0), FFC_OK);
    assert_int_equal(ffc_ls_next(&s, &a), 0);
    assert_close(a, 0.5, 0);
    assert_int_equal(s.cuts, 1);
    /* bad settings; a report with nothing handed out */
    assert_int_equal(ffc_ls_start(&s, -1, 0.5, 1.0, -1, 1, 1, 1), FFC_ERR_VALUE);
    assert_int_equal(ffc_ls_start(&s, 8, 1.0, 1.0, -1, 1, 1, 1), FFC_ERR_VALUE);
    assert_int_equal(ffc_ls_start(&s, 0, 0.5, 1.0, -1, 1, 1, 1), FFC_OK);
    assert_int_equal(ffc_ls_next(&s, &a), 0);
    assert_int_equal(ffc_ls_report(&s, 0, 0, 0), FFC_ERR_VALUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_solutions), cmocka_unit_test(test_unsymmetric), cmocka_unit_test(test_reasons),
        cmocka_unit_test(test_out_of_memory), cmocka_unit_test(test_full_reuse), cmocka_unit_test(test_full_symmetric),cmocka_unit_test(test_line_search),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
