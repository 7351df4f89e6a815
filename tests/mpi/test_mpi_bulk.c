/* test_mpi_bulk.c: a scene's bulk factorized by parallel MUMPS over the
 * ranks of MPI_COMM_WORLD (run by mpiexec, 2 ranks in make test): the
 * same solutions as CHOLMOD's in one process (the compliance columns of
 * many contact dofs included, as entries of K^-1), every rank with the
 * same bits, a singular K refused on every rank, entries of the inverse
 * against a dense elimination, the engine's bad input; every rank's
 * triplets gathered on every rank in rank order (a bad argument on one
 * rank answered alike on all). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dmumps_c.h>
#include <mpi.h>

#include "ffc_test.h"
#include "ffc_pdense.h"   /* (internal: the shared dense LU) */
#include "engine_test.h" /* (internal: the linear engines) */
#include "ffc_bulk.h"     /* (internal: the bulk's compliance columns) */

#define NV 300
#define N (3 * NV)
#define NC 90 /* contact dofs: three blocks of the block back-solve */

static ffc_scene *scene(ffc_engine eng)
{
    static double X[3 * NV];
    for (int i = 0; i < 3 * NV; i++) X[i] = 0.01 * i;
    ffc_effects fx = {0, 0, 0};
    ffc_scene *s = NULL;
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
    int fc;
    ffc_mpi_world(NULL, NULL, &fc);
    const ffc_parallel p = {eng, fc, 0, 0};
    assert_int_equal(ffc_scene_set_parallel(s, &p), FFC_OK);
    return s;
}

/* K (both triangles): springs between dof i and i + 1 and i + 3 (a 3D
 * chain), the first ndir dofs on Dirichlet rows (diagonal 1e30) */
static long bulk(int ndir, long Ti[], long Tj[], double Tv[])
{
    long t = 0;
    for (int i = 0; i < N; i++)
        for (int o = 1; o <= 3; o += 2) {
            if (i + o >= N) continue;
            const double k = 50.0 * (1.0 + 0.01 * i + 0.3 * o);
            const int p[4][2] = {{i, i}, {i + o, i + o}, {i, i + o}, {i + o, i}};
            const double v[4] = {k, k, -k, -k};
            for (int e = 0; e < 4; e++) { Ti[t] = p[e][0]; Tj[t] = p[e][1]; Tv[t] = v[e]; t++; }
        }
    for (int i = 0; i < ndir; i++) { Ti[t] = i; Tj[t] = i; Tv[t] = 1e30; t++; }
    return t;
}

/* a non-symmetric, diagonally dominant contact tangent on NC dofs */
static long contact(long Ti[], long Tj[], double Tv[], int c[NC])
{
    uint64_t seed = 11;
    for (int a = 0; a < NC; a++) c[a] = N / 3 + 6 * a;
    long t = 0;
    for (int a = 0; a < NC; a++)
        for (int b = a - 2; b <= a + 2; b++) {
            if (b < 0 || b >= NC) continue;
            Ti[t] = c[a]; Tj[t] = c[b];
            Tv[t] = 200.0 * (a == b ? 3.0 : test_rand(&seed, -0.5, 0.5));
            t++;
        }
    return t;
}

static long Ti[16 * N], Tj[16 * N], Ci[5 * NC], Cj[5 * NC];
static double Tv[16 * N], Cv[5 * NC], b[N], x1[N], x2[N];

static void solve(ffc_engine eng, int ndir, int with_contact, double x[N], int *st)
{
    ffc_scene *s = scene(eng);
    long bad = -1;
    const long nt = bulk(ndir, Ti, Tj, Tv);
    int c[NC];
    const long nc = with_contact ? contact(Ci, Cj, Cv, c) : 0;
    uint64_t seed = 5;
    for (int i = 0; i < N; i++) b[i] = i < ndir ? 0.0 : test_rand(&seed, -1.0, 1.0);
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    *st = ffc_scene_solve(s, nc, Ci, Cj, Cv, b, x, &bad);
    ffc_solve_info in;
    assert_int_equal(ffc_scene_solve_info(s, &in), FFC_OK);
    int ranks;
    ffc_mpi_world(NULL, &ranks, NULL);
    if (*st == FFC_OK) {
        assert_int_equal(in.ranks, eng == FFC_ENGINE_CHOLMOD ? 1 : ranks);
        if (eng == FFC_ENGINE_MUMPS) assert_true(in.factor_mb_max > 0);
        if (with_contact) assert_int_equal(in.m, NC);
    }
    ffc_scene_free(s);
}

/* the largest difference between this rank's x[n] and rank 0's (0 when
 * every rank holds the same bits) */
static double rank_spread(int n, const double x[])
{
    double *x0 = malloc(sizeof(double) * n);
    assert_non_null(x0);
    memcpy(x0, x, sizeof(double) * n);
    MPI_Bcast(x0, n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    double d = 0.0;
    for (int i = 0; i < n; i++) d = fmax(d, fabs(x[i] - x0[i]));
    free(x0);
    assert_int_equal(ffc_mpi_allreduce(&d, 1, 1), FFC_OK);
    return d;
}

/* MUMPS's solution and the replicated CHOLMOD's (its compliance columns
 * solved by one rank or another) against CHOLMOD's in one process, with
 * and without contact dofs; the
 * tolerance: both are backward stable with iterative refinement to 1e-13
 * of the residual scale, and K's condition here is below 1e4 */
static void test_same_as_cholmod(void **state)
{
    (void)state;
    for (int wc = 0; wc < 4; wc++) {   /* (2, 3: the replicated CHOLMOD, its columns shared out) */
        int st1, st2;
        solve(FFC_ENGINE_CHOLMOD, 3, wc % 2, x1, &st1);
        solve(wc < 2 ? FFC_ENGINE_MUMPS : FFC_ENGINE_REPLICATED, 3, wc % 2, x2, &st2);
        assert_int_equal(st1, FFC_OK);
        assert_int_equal(st2, FFC_OK);
        double d = 0.0, xm = 0.0;
        for (int i = 0; i < N; i++) { d = fmax(d, fabs(x1[i] - x2[i])); xm = fmax(xm, fabs(x1[i])); }
        assert_true(xm > 1e-3);
        assert_close(d / xm, 0.0, 1e-10);
        assert_close(rank_spread(N, x2), 0.0, 0.0);
    }
}

/* a free chain (no Dirichlet row): K is singular, and no contact tangent
 * to shift it: refused, on every rank */
static void test_singular(void **state)
{
    (void)state;
    int st;
    solve(FFC_ENGINE_MUMPS, 0, 0, x2, &st);
    assert_int_equal(st, FFC_ERR_SINGULAR);
}

/* a general (non-symmetric) sparse system solved once, the entries the
 * same on every rank or each rank's own share (their sum is A), against a
 * dense Gaussian elimination with partial pivoting; a singular one */
#define NG 60
static void test_general_solve(void **state)
{
    (void)state;
    int rank, ranks, fc;
    ffc_mpi_world(&rank, &ranks, &fc);
    static long gi[6 * NG], gj[6 * NG];
    static double gv[6 * NG], A[NG * NG], bb[NG], xr[NG], xs[NG], xo[NG];
    uint64_t seed = 3;
    long nt = 0;
    memset(A, 0, sizeof A);
    for (int i = 0; i < NG; i++) {
        const int cols[3] = {i, (i + 1) % NG, (i + 7) % NG};
        for (int c = 0; c < 3; c++) {
            const double v = c == 0 ? 4.0 + test_rand(&seed, 0, 1) : test_rand(&seed, -1, 1);
            /* each entry in two halves: the own mode sums them over the ranks */
            for (int h = 0; h < 2; h++) { gi[nt] = i; gj[nt] = cols[c]; gv[nt] = 0.5 * v; nt++; }
            A[i * NG + cols[c]] += v;
        }
        bb[i] = test_rand(&seed, -1, 1);
    }
    test_dense_solve(NG, A, bb, xr);   /* the reference */
    long bad = -1;
    const ffc_parallel shared = {FFC_ENGINE_MUMPS, fc, 0, 0}, own = {FFC_ENGINE_MUMPS, fc, 1, 0};
    assert_int_equal(ffc_parallel_solve(&shared, NG, nt, gi, gj, gv, bb, xs, &bad), FFC_OK);
    /* own: the ranks split the entries (rank r the r-th share of the list) */
    const long lo = nt * rank / ranks, hi = nt * (rank + 1) / ranks;
    assert_int_equal(ffc_parallel_solve(&own, NG, hi - lo, gi + lo, gj + lo, gv + lo, bb, xo, &bad), FFC_OK);
    for (int i = 0; i < NG; i++) {   /* A diagonally dominant: condition below 10 */
        assert_close(xs[i], xr[i], 1e-12);
        assert_close(xo[i], xr[i], 1e-12);
    }
    assert_close(rank_spread(NG, xo), 0.0, 0.0);
    /* a zero row: singular, on every rank */
    for (long t = 0; t < nt; t++) if (gi[t] == 5) gv[t] = 0.0;
    assert_int_equal(ffc_parallel_solve(&shared, NG, nt, gi, gj, gv, bb, xs, &bad), FFC_ERR_SINGULAR);
    /* bad input, before any collective call */
    gi[3] = NG;
    assert_int_equal(ffc_parallel_solve(&shared, NG, nt, gi, gj, gv, bb, xs, &bad), FFC_ERR_INDEX);
    assert_int_equal(bad, 3);
    const ffc_parallel chol = {FFC_ENGINE_CHOLMOD, 0, 0, 0};
    assert_int_equal(ffc_parallel_solve(&chol, NG, nt, gi, gj, gv, bb, xs, &bad), FFC_ERR_UNAVAILABLE);
}

/* entries of K^-1 (the MUMPS engine's inverse) on rows other than the
 * columns, in no particular order, after a dense solve (whose right-hand
 * side MUMPS must not keep on the other ranks): a dense elimination's to
 * 1e-13 (K tridiagonal 4, -1: condition below 3); the refusals */
#define NI 30
static void test_inverse_entries(void **state)
{
    (void)state;
    int fc;
    ffc_mpi_world(NULL, NULL, &fc);
    ffc_solve_info info = {0};
    ffc__engine *m = NULL;
    assert_int_equal(ffc__mumps_create(&info, fc, 1, &m), FFC_OK);
    int ti[2 * NI], tj[2 * NI];
    double tv[2 * NI], A[NI * NI] = {0};
    long nz = 0;
    for (int i = 0; i < NI; i++) {
        ti[nz] = i; tj[nz] = i; tv[nz] = 4.0; nz++;
        A[i * NI + i] = 4.0;
        if (i > 0) { ti[nz] = i; tj[nz] = i - 1; tv[nz] = -1.0; nz++; A[i * NI + i - 1] = A[(i - 1) * NI + i] = -1.0; }
    }
    const ffc__tri K = {NI, nz, ti, tj, tv, 1};
    const long cols[3] = {7, 2, 19}, rows[5] = {0, 5, 2, 29, 7};
    double X[15], B[NI], Bx[NI];
    assert_int_equal(test_inverse(m, 3, cols, 5, rows, X), FFC_ERR_EMPTY);
    assert_string_equal(m->err.msg, "MUMPS: not factorized");
    assert_int_equal(m->op->analyze(m, &K), FFC_OK);
    assert_int_equal(m->op->factorize(m, &K), FFC_OK);
    for (int i = 0; i < NI; i++) B[i] = 1.0;
    assert_int_equal(m->op->solve(m, B, Bx), FFC_OK);
    assert_int_equal(test_inverse(m, 3, cols, 5, rows, X), FFC_OK);
    for (int c = 0; c < 3; c++) {
        double e[NI] = {0}, x[NI];
        e[cols[c]] = 1.0;
        test_dense_solve(NI, A, e, x);
        for (int r = 0; r < 5; r++) assert_close(X[r + 5 * c], x[rows[r]], 1e-13);
    }
    const long twice[2] = {3, 3}, out[1] = {NI};
    assert_int_equal(test_inverse(m, 2, twice, 5, rows, X), FFC_ERR_VALUE);
    assert_int_equal(test_inverse(m, 3, cols, 2, twice, X), FFC_ERR_VALUE);
    assert_int_equal(test_inverse(m, 3, cols, 1, out, X), FFC_ERR_INDEX);
    assert_int_equal(test_inverse(m, 1, out, 5, rows, X), FFC_ERR_INDEX);
    /* and a dense solve after it */
    for (int i = 0; i < NI; i++) B[i] = 1.0;
    assert_int_equal(m->op->solve(m, B, Bx), FFC_OK);
    double x1[NI], b1[NI];
    for (int i = 0; i < NI; i++) b1[i] = 1.0;
    test_dense_solve(NI, A, b1, x1);
    for (int i = 0; i < NI; i++) assert_close(Bx[i], x1[i], 1e-13);
    /* the same entries from CHOLMOD and UMFPACK (one process each, on every rank) */
    ffc__ranks one = {0, 0, 1, NULL};
    ffc__engine *others[2] = {NULL, NULL};
    assert_int_equal(ffc__cholmod_create(&info, &one, &others[0]), FFC_OK);
    assert_int_equal(ffc__umfpack_create(&info, &others[1]), FFC_OK);
    for (int k = 0; k < 2; k++) {
        double Y[15];
        assert_int_equal(others[k]->op->analyze(others[k], &K), FFC_OK);
        assert_int_equal(others[k]->op->factorize(others[k], &K), FFC_OK);
        assert_int_equal(test_inverse(others[k], 3, cols, 5, rows, Y), FFC_OK);
        for (int e = 0; e < 15; e++) assert_close(Y[e], X[e], 1e-14);
        others[k]->op->free(others[k]);
    }
    m->op->free(m);
}

/* a matrix whose pivoting overruns MUMPS's workspace estimate: rows of
 * a tiny diagonal (1e-8) in the first half and three random pairs of
 * entries each, which on 2 ranks stops the default estimate with
 * INFOG(1) = -9; ffc_parallel_solve runs it again with more room and
 * solves it, as the dense elimination does (the backward error below
 * 1e-12 of |A| |x| + |b|: partial pivoting with refinement) */
#define NP 200
static void test_pivoting_workspace(void **state)
{
    (void)state;
    int fc;
    ffc_mpi_world(NULL, NULL, &fc);
    static long pi[7 * NP], pj[7 * NP];
    static double pv[7 * NP], bb[NP], x[NP];
    uint64_t seed = 7;   /* (seeds 1, 3 and 7 overrun the estimate; 2, 4, 5, 6 and 8 do not) */
    long nt = 0;
    for (int i = 0; i < NP; i++) {
        if (i < NP / 2) { pi[nt] = i; pj[nt] = i; pv[nt] = 1e-8; nt++; }
        for (int k = 0; k < 3; k++) {
            const int j = (int)test_rand(&seed, 0, NP - 1e-9);
            pi[nt] = i; pj[nt] = j; pv[nt] = test_rand(&seed, 0, 1); nt++;
            pi[nt] = j; pj[nt] = i; pv[nt] = test_rand(&seed, 0, 1); nt++;
        }
        bb[i] = 1.0;
    }
    /* the premise: MUMPS itself, as ffc_parallel_solve sets it up but with
     * its default workspace, runs short (a MUMPS that no longer does wants
     * another matrix here, not a test that passes without a retry) */
    {
        int rank, ranks;
        ffc_mpi_world(&rank, &ranks, NULL);
        const long lo = nt * rank / ranks, hi = nt * (rank + 1) / ranks;
        static MUMPS_INT ri[7 * NP], rj[7 * NP];
        static double rv[7 * NP], rb[NP];
        for (long t = lo; t < hi; t++) { ri[t - lo] = (MUMPS_INT)pi[t] + 1; rj[t - lo] = (MUMPS_INT)pj[t] + 1; rv[t - lo] = pv[t]; }
        for (int i = 0; i < NP; i++) rb[i] = bb[i];
        DMUMPS_STRUC_C id;
        memset(&id, 0, sizeof id);
        id.comm_fortran = (MUMPS_INT)fc;
        id.par = 1;
        id.sym = 0;
        id.job = -1;
        dmumps_c(&id);
        id.icntl[0] = id.icntl[1] = id.icntl[2] = -1; id.icntl[3] = 0;
        id.icntl[17] = 3; id.icntl[23] = 0; id.icntl[9] = -2;   /* ICNTL(18), (24), (10) as ffc_parallel_solve */
        id.n = NP;
        id.nnz_loc = hi - lo; id.nz_loc = (MUMPS_INT)(hi - lo);
        id.irn_loc = ri; id.jcn_loc = rj; id.a_loc = rv;
        if (rank == 0) { id.rhs = rb; id.nrhs = 1; id.lrhs = NP; }
        id.job = 6;
        dmumps_c(&id);
        const int e = id.infog[0];
        id.job = -2;
        dmumps_c(&id);
        assert_true(e == -8 || e == -9 || e == -11 || e == -14 || e == -15 || e == -17 || e == -20);
    }
    long bad = -1;
    const ffc_parallel shared = {FFC_ENGINE_MUMPS, fc, 0, 0};
    assert_int_equal(ffc_parallel_solve(&shared, NP, nt, pi, pj, pv, bb, x, &bad), FFC_OK);
    static double r[NP], scale[NP];
    for (int i = 0; i < NP; i++) { r[i] = -bb[i]; scale[i] = fabs(bb[i]); }
    for (long t = 0; t < nt; t++) {
        r[pi[t]] += pv[t] * x[pj[t]];
        scale[pi[t]] += fabs(pv[t] * x[pj[t]]);
    }
    for (int i = 0; i < NP; i++) assert_true(fabs(r[i]) <= 1e-12 * scale[i]);
    assert_close(rank_spread(NP, x), 0.0, 0.0);
}

/* the dense LU shared over the ranks (the condensed Newton's, ScaLAPACK)
 * against a dense elimination of the whole matrix on every rank: 1e-12
 * (diagonally dominant, condition below 10); a singular one refused */
#define ND 300
static void test_shared_lu(void **state)
{
    (void)state;
    int fc;
    ffc_mpi_world(NULL, NULL, &fc);
    ffc__pdense *d = NULL;
    assert_int_equal(ffc__pdense_create(fc, &d), FFC_OK);
    static double A[ND * ND], M[ND * ND], t[ND], x[ND];
    uint64_t seed = 9;
    for (int j = 0; j < ND; j++)
        for (int i = 0; i < ND; i++) A[i + j * ND] = (i == j ? 5.0 : 0.0) + test_rand(&seed, -1, 1) / ND * 3;
    for (int i = 0; i < ND; i++) t[i] = x[i] = test_rand(&seed, -1, 1);
    for (int pass = 0; pass < 2; pass++) {   /* (twice: the storage reused) */
        double *Al = ffc__pdense_reserve(d, ND);
        assert_non_null(Al);
        for (int j = 0; j < ND; j++) {
            const long jl = ffc__pdense_local(d, j);
            if (jl >= 0) memcpy(Al + jl * ND, A + j * ND, ND * sizeof(double));
        }
        assert_int_equal(ffc__pdense_factor(d, ND), FFC_OK);
        memcpy(t, x, sizeof t);
        assert_int_equal(ffc__pdense_solve(d, ND, t), FFC_OK);
    }
    /* the reference (A is column-major: its row-major copy) */
    double y[ND];
    for (int i = 0; i < ND; i++)
        for (int j = 0; j < ND; j++) M[i * ND + j] = A[i + j * ND];
    test_dense_solve(ND, M, x, y);
    for (int i = 0; i < ND; i++) assert_close(t[i], y[i], 1e-12);
    assert_close(rank_spread(ND, t), 0.0, 0.0);
    /* two equal columns: singular, refused on every rank */
    double *Al = ffc__pdense_reserve(d, ND);
    assert_non_null(Al);
    for (int j = 0; j < ND; j++) {
        const long jl = ffc__pdense_local(d, j);
        if (jl >= 0) memcpy(Al + jl * ND, A + (j == ND - 1 ? 0 : j) * ND, ND * sizeof(double));
    }
    assert_int_equal(ffc__pdense_factor(d, ND), FFC_ERR_SINGULAR);
    assert_int_equal(ffc__pdense_solve(d, ND, t), FFC_ERR_EMPTY);
    ffc__pdense_free(d);
}


/* The replicated CHOLMOD (supernodal, pruned solves) shares the
 * compliance columns out over the ranks: every rank ends with the same G
 * and H (same bits) as one process's computing them all, in the same
 * order; C grown in two calls (72 columns, two blocks of solves on one
 * process; then 30: the shares are uneven on 4 ranks), some columns
 * outside the rows R.  Every rank makes the whole factor.  Without
 * Dirichlet rows (tgv 0) K is singular: the factorization fails, and
 * every rank returns it, as one process does.  Two lattices (bodies = 2:
 * L's forest has a tree for each) take shares of equal work, by the
 * trees' backward solves.  Tolerance: the same factor's solves in blocks
 * of other widths, 1e-14 of K^-1's largest entry (K's condition below
 * 1e3). */
static void replicated_columns(double tgv, int bodies)
{
    enum { LN = 6, NT = 80 * LN * LN * LN, C1 = LATTICE_C1, C2 = LATTICE_C2, CT = C1 + C2 };
    const long LD = 3L * LN * LN * LN * bodies, NR = 3L * LN * LN * bodies;
    long *Li = malloc(NT * sizeof(long)), *Lj = malloc(NT * sizeof(long)), bad = -1;
    double *Lv = malloc(NT * sizeof(double));
    const long nt = bodies == 2 ? test_lattice_pair(LN, tgv, Li, Lj, Lv, NULL) : test_lattice(LN, tgv, Li, Lj, Lv, NULL);
    long rows[6 * LN * LN], nd1[C1], nd2[C2];
    if (bodies == 2) test_lattice_pair_sets(LN, rows, nd1, nd2);
    else test_lattice_sets(LN, rows, nd1, nd2);
    int fc, ranks;
    ffc_mpi_world(NULL, &ranks, &fc);
    ffc__bulk *b[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) {
        assert_int_equal(ffc__bulk_create(LD, nt, Li, Lj, Lv, 1000, &b[k], &bad), FFC_OK);
        if (k == 1) assert_int_equal(ffc__bulk_set_replicated(b[k], fc), FFC_OK);
        ffc__bulk_set_columns_mode(b[k], 1, 1);
        if (tgv == 0.0) {   /* refused alike on one process and on every rank; the factor's memory freed */
            assert_int_equal(ffc__bulk_columns(b[k], NR, rows, C1, nd1, &bad), FFC_ERR_SINGULAR);
            continue;
        }
        assert_int_equal(ffc__bulk_columns(b[k], NR, rows, C1, nd1, &bad), FFC_OK);
        assert_int_equal(ffc__bulk_columns(b[k], NR, rows, C2, nd2, &bad), FFC_OK);
    }
    if (tgv == 0.0) {
        for (int k = 0; k < 2; k++) ffc__bulk_free(b[k]);
        free(Li); free(Lj); free(Lv);
        return;
    }
    const long *dof[2];
    const double *G[2], *H[2];
    long ld[2];
    int super[2];
    double share[2];
    for (int k = 0; k < 2; k++)
        assert_int_equal(ffc__bulk_compliance(b[k], &dof[k], &G[k], &ld[k], &H[k], &super[k], &share[k]), CT);
    assert_true(super[0] && super[1] && share[1] > 0.0 && share[1] < 0.9);   /* pruned */
    ffc_solve_info in;
    ffc__bulk_info(b[1], &in);
    assert_int_equal(in.ranks, ranks);
    assert_int_equal(in.columns, CT);
    assert_int_equal(in.factorizations, 1);
    if (ranks > 1) assert_true(in.backsolves < CT);   /* each rank solved its share only */
    double gmax = 0.0, d = 0.0;
    for (long j = 0; j < CT; j++) {
        assert_int_equal(dof[1][j], dof[0][j]);
        for (long i = 0; i < CT; i++) {
            gmax = fmax(gmax, fabs(G[0][i + j * ld[0]]));
            d = fmax(d, fabs(G[1][i + j * ld[1]] - G[0][i + j * ld[0]]));
        }
        for (long r = 0; r < NR; r++) d = fmax(d, fabs(H[1][r + j * NR] - H[0][r + j * NR]));
    }
    assert_true(gmax > 0.0);
    assert_close(d, 0.0, 1e-14 * gmax);
    /* every rank the same bits: G, H and C's dofs */
    double *g = malloc((CT * CT + NR * CT + CT) * sizeof(double));
    for (long j = 0; j < CT; j++) {
        for (long i = 0; i < CT; i++) g[i + CT * j] = G[1][i + j * ld[1]];
        for (long r = 0; r < NR; r++) g[CT * CT + r + NR * j] = H[1][r + j * NR];
        g[CT * CT + NR * CT + j] = (double)dof[1][j];
    }
    assert_close(rank_spread(CT * CT + NR * CT + CT, g), 0.0, 0.0);
    free(g);
    /* a single back-solve on every rank against one process's: 1e-13 of
     * the solution (K's condition below 1e3), a residual that needs no
     * iterative refinement (which would mend a wrong solve), and every
     * rank the same bits */
    double *rhs = malloc(3 * LD * sizeof(double)), *xs0 = rhs + LD, *xs1 = xs0 + LD;
    uint64_t seed = 17;
    for (long i = 0; i < LD; i++) rhs[i] = test_rand(&seed, -1, 1);
    assert_int_equal(ffc__bulk_solve(b[0], 0, NULL, NULL, NULL, rhs, xs0, &bad), FFC_OK);
    ffc__bulk_info(b[1], &in);
    const long refined0 = in.refinements;
    assert_int_equal(ffc__bulk_solve(b[1], 0, NULL, NULL, NULL, rhs, xs1, &bad), FFC_OK);
    ffc__bulk_info(b[1], &in);
    assert_int_equal(in.refinements, refined0);   /* (its residual below 1e-13 at once: no correction) */
    double xm = 0.0;
    d = 0.0;
    for (long i = 0; i < LD; i++) { xm = fmax(xm, fabs(xs0[i])); d = fmax(d, fabs(xs1[i] - xs0[i])); }
    assert_true(xm > 0.0);
    assert_close(d, 0.0, 1e-13 * xm);
    assert_close(rank_spread((int)LD, xs1), 0.0, 0.0);
    free(rhs);
    for (int k = 0; k < 2; k++) ffc__bulk_free(b[k]);
    free(Li); free(Lj); free(Lv);
}

static void test_replicated_columns(void **state)
{
    (void)state;
    replicated_columns(1e30, 1);
    replicated_columns(1e30, 2);
    replicated_columns(0.0, 1);
}

static void test_bad_engine(void **state)
{
    (void)state;
    ffc_scene *s = scene(FFC_ENGINE_CHOLMOD);
    const ffc_parallel p = {(ffc_engine)7, 0, 0, 0};
    assert_int_equal(ffc_scene_set_parallel(s, &p), FFC_ERR_VALUE);
    assert_int_equal(ffc_scene_set_parallel(s, NULL), FFC_ERR_NULL);
    assert_int_equal(ffc_has_mpi(), 1);
    double v = 1.0;
    assert_int_equal(ffc_mpi_allreduce(&v, 1, 3), FFC_ERR_VALUE);
    int ranks;
    ffc_mpi_world(NULL, &ranks, NULL);
    assert_int_equal(ffc_mpi_allreduce(&v, 1, 0), FFC_OK);
    assert_close(v, ranks, 0.0);
    ffc_scene_free(s);
}

/* ffc_mpi_gather_triplets: a matrix's pieces gathered on every rank.
 * Rank r's piece: rows 3r .. 3r + 2 of a chain matrix on n = 3 size + 1
 * dofs, the shared dof 3r + 3 (the next piece's first) on both pieces */
static long piece(int r, long Ti[], long Tj[], double Tv[])
{
    long t = 0;
    for (int e = 0; e < 3; e++) {
        const long a = 3L * r + e, b = a + 1;
        const double k = 1.0 + 0.25 * (double)a;
        const long p[4][2] = {{a, a}, {b, b}, {a, b}, {b, a}};
        const double v[4] = {k, k, -k, -k};
        for (int q = 0; q < 4; q++) { Ti[t] = p[q][0]; Tj[t] = p[q][1]; Tv[t] = v[q]; t++; }
    }
    return t;
}

static void test_gathered_in_rank_order(void **state)
{
    (void)state;
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    long Ti[12], Tj[12];
    double Tv[12];
    const long nt = piece(rank, Ti, Tj, Tv);
    long total = -1;
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, Tv, 0, NULL, NULL, NULL, &total), FFC_ERR_CAPACITY);
    assert_int_equal(total, 12L * size);
    long *Oi = malloc((size_t)total * sizeof *Oi), *Oj = malloc((size_t)total * sizeof *Oj);
    double *Ov = malloc((size_t)total * sizeof *Ov);
    assert_non_null(Oi); assert_non_null(Oj); assert_non_null(Ov);
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, Tv, total, Oi, Oj, Ov, &total), FFC_OK);
    for (int r = 0; r < size; r++) {   /* rank r's piece at 12 r */
        long Ri[12], Rj[12];
        double Rv[12];
        piece(r, Ri, Rj, Rv);
        for (int k = 0; k < 12; k++) {
            assert_int_equal(Oi[12 * r + k], Ri[k]);
            assert_int_equal(Oj[12 * r + k], Rj[k]);
            assert_close(Ov[12 * r + k], Rv[k], 0.0);
        }
    }
    /* summed: the chain of 3 size springs, one process's matrix */
    const long n = 3L * size + 1;
    long *Ci = malloc((size_t)total * sizeof *Ci), *Cj = malloc((size_t)total * sizeof *Cj);
    long *rp = malloc((size_t)(n + 1) * sizeof *rp), *w = malloc((size_t)n * sizeof *w);
    double *Cv = malloc((size_t)total * sizeof *Cv);
    const long nz = ffc_triplets_sum(n, total, Oi, Oj, Ov, Ci, Cj, Cv, rp, w);
    assert_int_equal(nz, 3 * n - 2);
    for (long t = 0; t < nz; t++) {
        const long a = Ci[t], b = Cj[t];
        const double ka = 1.0 + 0.25 * (double)a, kl = 1.0 + 0.25 * (double)(a - 1);
        double want;
        if (a == b) want = (a < n - 1 ? ka : 0.0) + (a > 0 ? kl : 0.0);
        else want = -(1.0 + 0.25 * (double)(a < b ? a : b));
        assert_close(Cv[t], want, 1e-15);
    }
    free(Oi); free(Oj); free(Ov); free(Ci); free(Cj); free(Cv); free(rp); free(w);
}

static void test_bad_argument_on_one_rank(void **state)
{
    (void)state;
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    long Ti[12], Tj[12], Oi[96], Oj[96], total = -1;   /* (up to 8 ranks) */
    double Tv[12], Ov[96];
    const long nt = piece(rank, Ti, Tj, Tv);
    /* rank 1 passes no values: both ranks get FFC_ERR_NULL */
    const double *v = rank == 1 ? NULL : Tv;
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, v, 96, Oi, Oj, Ov, &total), FFC_ERR_NULL);
    /* rank 0 a negative count, rank 1 no values: the most negative status */
    const long m = rank == 0 ? -1 : nt;
    const int want = FFC_ERR_NULL < FFC_ERR_SIZE ? FFC_ERR_NULL : FFC_ERR_SIZE;
    assert_int_equal(ffc_mpi_gather_triplets(m, Ti, Tj, v, 96, Oi, Oj, Ov, &total), want);
    /* rank 0's capacity too small: every rank is told */
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, Tv, rank == 0 ? 4 : 96, Oi, Oj, Ov, &total), FFC_ERR_CAPACITY);
    /* and then it works */
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, Tv, 96, Oi, Oj, Ov, &total), FFC_OK);
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank > 0 && !freopen("/dev/null", "w", stdout)) return 1; /* one report */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_as_cholmod),
        cmocka_unit_test(test_singular),
        cmocka_unit_test(test_general_solve),
        cmocka_unit_test(test_pivoting_workspace),
        cmocka_unit_test(test_inverse_entries),
        cmocka_unit_test(test_shared_lu),
        cmocka_unit_test(test_replicated_columns),
        cmocka_unit_test(test_bad_engine),
        cmocka_unit_test(test_gathered_in_rank_order),
        cmocka_unit_test(test_bad_argument_on_one_rank),
    };
    const int failed = cmocka_run_group_tests(tests, NULL, NULL);
    MPI_Finalize();
    return failed;
}
