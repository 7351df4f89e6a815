/* test_bulk.c: the scene's bulk factorization: (K + Kc) x = b solved on
 * the contact dofs against a dense elimination, a body held only by
 * contact, the compliance grown only for new dofs, iterative refinement
 * and bad input. */
#include <stdlib.h>
#include <string.h>

#include "ffc_test.h"
#include "ffc_bulk.h"

void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, double *b,
             const int *ldb, int *info);

/* 16 nodes, 48 dofs: body A = dofs 0..23 (a spring chain, dofs 0..2
 * Dirichlet rows with diagonal TGV), body B = dofs 24..47 (a free chain:
 * singular on its own, one rigid mode) */
#define NV 16
#define N (3 * NV)
static const double TGV = 1e30, KS = 50.0;

static ffc_scene *scene(void)
{
    double X[3 * NV];
    for (int i = 0; i < 3 * NV; i++) X[i] = 0.1 * i;
    ffc_effects fx = {0, 0, 0};
    ffc_scene *s = NULL;
    assert_int_equal(ffc_scene_create(3, NV, X, 0, NULL, &fx, &s), FFC_OK);
    return s;
}

/* K's triplets (both triangles) and its dense copy */
static long bulk_dir(int ndir, long Ti[], long Tj[], double Tv[], double Kd[N * N]);
static long bulk(long Ti[], long Tj[], double Tv[], double Kd[N * N]) { return bulk_dir(3, Ti, Tj, Tv, Kd); }
/* ... with the first ndir dofs on Dirichlet rows */
static long bulk_dir(int ndir, long Ti[], long Tj[], double Tv[], double Kd[N * N])
{
    long t = 0;
    memset(Kd, 0, sizeof(double) * N * N);
    for (int body = 0; body < 2; body++) {
        const int a = 24 * body;
        for (int i = a; i < a + 23; i++) { /* springs between neighbours, stiffness KS (1 + i/10) */
            const double k = KS * (1.0 + 0.1 * i);
            const int p[4][2] = {{i, i}, {i + 1, i + 1}, {i, i + 1}, {i + 1, i}};
            const double v[4] = {k, k, -k, -k};
            for (int e = 0; e < 4; e++) { Ti[t] = p[e][0]; Tj[t] = p[e][1]; Tv[t] = v[e]; t++; }
        }
    }
    for (int i = 0; i < ndir; i++) { Ti[t] = i; Tj[t] = i; Tv[t] = TGV; t++; } /* Dirichlet rows */
    for (long k = 0; k < t; k++) Kd[Ti[k] * N + Tj[k]] += Tv[k];
    return t;
}

/* a non-symmetric contact tangent coupling the two bodies at dofs c[nc] */
static long contact(const int c[], int nc, double scale, long Ti[], long Tj[], double Tv[])
{
    long t = 0;
    uint64_t seed = 7;
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < nc; b++) {
            Ti[t] = c[a];
            Tj[t] = c[b];
            Tv[t] = scale * (a == b ? 2.0 : test_rand(&seed, -0.5, 0.5)); /* diagonally dominant */
            t++;
        }
    return t;
}


static void rhs(double b[N])
{
    uint64_t seed = 3;
    for (int i = 0; i < N; i++) b[i] = test_rand(&seed, -1, 1);
    for (int i = 0; i < 3; i++) b[i] = TGV * 0.01 * (i + 1); /* imposed values 0.01, 0.02, 0.03 */
}

/* x against a reference solution xr, to 1e-10 of the largest |xr|: both
 * solves are backward stable on a matrix of condition ~1e4 (free rows) */
static void check_same(const double x[N], const double xr[N])
{
    double xmax = 0;
    for (int i = 0; i < N; i++) xmax = fmax(xmax, fabs(xr[i]));
    for (int i = 0; i < N; i++) assert_close(x[i], xr[i], 1e-10 * xmax);
}

/* x against a dense solve of K + Kc (Kd += Kc) */
static void check_dense(double Kd[N * N], long nc, const long ci[], const long cj[], const double cv[],
                        const double b[N], const double x[N])
{
    double bd[N], xd[N];
    for (long k = 0; k < nc; k++) Kd[ci[k] * N + cj[k]] += cv[k];
    memcpy(bd, b, sizeof bd);
    test_dense_solve(N, Kd, bd, xd);
    check_same(x, xd);
}

/* the reduced solve against a dense solve of K + Kc, with body B held
 * only by the contact tangent (K singular: the shift makes it factorizable) */
static void test_matches_dense(void **state)
{
    (void)state;
    ffc_scene *s = scene();
    long Ti[200], Tj[200], ci[100], cj[100], bad = -1;
    double Tv[200], cv[100], Kd[N * N], b[N], x[N];
    const long nt = bulk(Ti, Tj, Tv, Kd);
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    const int c[] = {20, 21, 22, 30, 31, 32};
    const long nc = contact(c, 6, 40.0, ci, cj, cv);
    rhs(b);
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_OK);
    check_dense(Kd, nc, ci, cj, cv, b, x);
    for (int i = 0; i < 3; i++) assert_close(x[i], 0.01 * (i + 1), 1e-15);
    ffc_solve_info in;
    assert_int_equal(ffc_scene_solve_info(s, &in), FFC_OK);
    assert_int_equal(in.factorizations, 1);
    assert_int_equal(in.columns, 6);
    assert_int_equal(in.m, 6);
    assert_true(in.shift > 0);
    assert_true(in.residual <= 1e-13);
    ffc_scene_free(s);
}

/* more Dirichlet rows than free ones (30 of 48: the median diagonal is a
 * tgv): they are still told apart from the free rows, and the solve matches
 * the dense one */
static void test_mostly_dirichlet(void **state)
{
    (void)state;
    ffc_scene *s = scene();
    long Ti[250], Tj[250], ci[100], cj[100], bad = -1;
    double Tv[250], cv[100], Kd[N * N], b[N], x[N];
    const long nt = bulk_dir(30, Ti, Tj, Tv, Kd);
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    const int c[] = {35, 36, 37, 40, 41, 42};
    const long nc = contact(c, 6, 40.0, ci, cj, cv);
    rhs(b);
    for (int i = 3; i < 30; i++) b[i] = 0.0; /* imposed values 0 on the further Dirichlet rows */
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_OK);
    check_dense(Kd, nc, ci, cj, cv, b, x);
    ffc_solve_info in;
    assert_int_equal(ffc_scene_solve_info(s, &in), FFC_OK);
    assert_true(in.rcond > 1e-12);     /* the tgv rows are not in the factorized matrix's conditioning */
    assert_true(in.residual <= 1e-13);
    ffc_scene_free(s);
}

/* the compliance grows only for dofs Kc touches for the first time; one
 * factorization throughout; a new K starts afresh */
static void test_columns_grow(void **state)
{
    (void)state;
    ffc_scene *s = scene();
    long Ti[200], Tj[200], ci[100], cj[100], bad = -1;
    double Tv[200], cv[100], Kd[N * N], b[N], x[N];
    const long nt = bulk(Ti, Tj, Tv, Kd);
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    rhs(b);
    const int c1[] = {20, 30}, c2[] = {20, 30, 31, 40};
    long nc = contact(c1, 2, 40.0, ci, cj, cv);
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_OK);
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_OK);
    ffc_solve_info in;
    ffc_scene_solve_info(s, &in);
    assert_int_equal(in.columns, 2);
    assert_int_equal(in.solves, 2);
    nc = contact(c2, 4, 40.0, ci, cj, cv);
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_OK);
    ffc_scene_solve_info(s, &in);
    assert_int_equal(in.columns, 4);
    assert_int_equal(in.factorizations, 1);
    assert_int_equal(in.solves, 3);
    assert_true(in.t_factor > 0.0 && in.t_columns > 0.0); /* their wall times are counted */
    const double tf = in.t_factor;
    /* the same answer as a fresh scene that sees Kc first */
    ffc_scene *s2 = scene();
    double x2[N];
    assert_int_equal(ffc_scene_set_bulk(s2, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    assert_int_equal(ffc_scene_solve(s2, nc, ci, cj, cv, b, x2, &bad), FFC_OK);
    check_same(x, x2);
    ffc_scene_free(s2);
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    ffc_scene_solve_info(s, &in);
    assert_int_equal(in.columns, 0);
    assert_int_equal(in.factorizations, 0);
    assert_true(in.t_factor == 0.0 && in.t_columns == 0.0 && tf > 0.0); /* and start afresh with K */
    ffc_scene_free(s);
}

static void test_bad_input(void **state)
{
    (void)state;
    ffc_scene *s = scene();
    long Ti[200], Tj[200], ci[100], cj[100], bad = -1;
    double Tv[200], cv[100], Kd[N * N], b[N], x[N];
    const long nt = bulk(Ti, Tj, Tv, Kd);
    rhs(b);
    const int c[] = {20, 30, 31};
    const long nc = contact(c, 3, 40.0, ci, cj, cv);
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_ERR_EMPTY);
    assert_int_equal(ffc_scene_set_bulk(s, N - 3, nt, Ti, Tj, Tv, 1000, &bad), FFC_ERR_SIZE);
    Ti[5] = N;
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_ERR_INDEX);
    assert_int_equal(bad, 5);
    Ti[5] = Tj[5];
    Tv[7] = NAN;
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_ERR_NONFINITE);
    assert_int_equal(bad, 7);
    bulk(Ti, Tj, Tv, Kd);
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_OK);
    /* body B is held by nothing: K alone is singular */
    assert_int_equal(ffc_scene_solve(s, 0, ci, cj, cv, b, x, &bad), FFC_ERR_SINGULAR);
    ffc_error e;   /* (the engine's reason, one line) */
    assert_int_equal(ffc_scene_solve_error(s, &e), FFC_OK);
    assert_int_equal(e.status, FFC_ERR_SINGULAR);
    assert_non_null(strstr(e.msg, "CHOLMOD: the matrix is not positive definite"));
    /* ... and the factorization is tried again with the next contact tangent */
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_OK);
    assert_int_equal(ffc_scene_solve_error(s, &e), FFC_OK);
    assert_int_equal(e.status, 0);   /* (a call that succeeds leaves no reason) */
    ci[2] = -1;
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_ERR_INDEX);
    assert_int_equal(bad, 2);
    ci[2] = c[0];
    b[9] = INFINITY;
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_ERR_NONFINITE);
    assert_int_equal(bad, 9);
    rhs(b);
    /* more contact dofs than the path takes */
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 2, &bad), FFC_OK);
    assert_int_equal(ffc_scene_solve(s, nc, ci, cj, cv, b, x, &bad), FFC_ERR_CAPACITY);
    assert_int_equal(bad, 3);
    /* a diagonal that is not positive */
    for (long k = 0; k < nt; k++)
        if (Ti[k] == 10 && Tj[k] == 10) Tv[k] = -1e6;
    assert_int_equal(ffc_scene_set_bulk(s, N, nt, Ti, Tj, Tv, 1000, &bad), FFC_ERR_SINGULAR);
    assert_int_equal(bad, 10);
    ffc_scene_free(s);
}

/* a build without MPI: one rank, and parallel MUMPS refused by name */
static void test_no_mpi(void **state)
{
    (void)state;
    ffc_scene *s = scene();
    int r = -1, n = -1, fc = -1;
    assert_int_equal(ffc_mpi_world(&r, &n, &fc), FFC_OK);
    assert_int_equal(r, 0);
    assert_int_equal(n, 1);
    assert_int_equal(ffc_has_mpi(), 0);
    const ffc_parallel mumps = {FFC_ENGINE_MUMPS, 0, 0, 0}, chol = {FFC_ENGINE_CHOLMOD, 0, 0, 0};
    assert_int_equal(ffc_scene_set_parallel(s, &mumps), FFC_ERR_UNAVAILABLE);
    assert_non_null(strstr(ffc_strerror(FFC_ERR_UNAVAILABLE), "MUMPS"));
    assert_int_equal(ffc_scene_set_parallel(s, &chol), FFC_OK);
    long i0 = 0;
    double v0 = 1.0, b0 = 1.0, x0 = 0.0;
    assert_int_equal(ffc_parallel_solve(&mumps, 1, 1, &i0, &i0, &v0, &b0, &x0, NULL), FFC_ERR_UNAVAILABLE);
    double v[2] = {3.0, -1.0};
    assert_int_equal(ffc_mpi_allreduce(v, 2, 1), FFC_OK);
    assert_close(v[0], 3.0, 0.0);
    assert_int_equal(ffc_mpi_allreduce(v, 2, 5), FFC_ERR_VALUE);
    assert_int_equal(ffc_mpi_allreduce(NULL, 2, 0), FFC_ERR_NULL);
    /* one rank: the gathered triplets are a copy; capacity, then arguments */
    const long gi[3] = {0, 2, 1}, gj[3] = {1, 2, 0};
    const double gv[3] = {1.5, -2.0, 4.0};
    long oi[3], oj[3], total = -1;
    double ov[3];
    assert_int_equal(ffc_mpi_gather_triplets(3, gi, gj, gv, 2, oi, oj, ov, &total), FFC_ERR_CAPACITY);
    assert_int_equal(total, 3);
    assert_int_equal(ffc_mpi_gather_triplets(3, gi, gj, gv, 3, oi, oj, ov, &total), FFC_OK);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(oi[k], gi[k]);
        assert_int_equal(oj[k], gj[k]);
        assert_close(ov[k], gv[k], 0.0);
    }
    assert_int_equal(ffc_mpi_gather_triplets(-1, gi, gj, gv, 3, oi, oj, ov, &total), FFC_ERR_SIZE);
    assert_int_equal(ffc_mpi_gather_triplets(3, NULL, gj, gv, 3, oi, oj, ov, &total), FFC_ERR_NULL);
    assert_int_equal(ffc_mpi_gather_triplets(3, gi, gj, gv, 3, oi, NULL, ov, &total), FFC_ERR_NULL);
    assert_int_equal(ffc_mpi_gather_triplets(3, gi, gj, gv, 3, oi, oj, ov, NULL), FFC_ERR_NULL);
    assert_true(ffc_peak_mb() > 0.0);
    ffc_solve_info in;
    assert_int_equal(ffc_scene_solve_info(s, &in), FFC_OK);
    assert_int_equal(in.ranks, 1);
    ffc_scene_free(s);
}


#define LN 6
#define LD (3 * LN * LN * LN)

/* a bulk's compliance (ffc__bulk_compliance's outputs) */
typedef struct {
    const long *dof;     /* [m] C's dofs */
    const double *G, *H; /* G (ld x m), H (nr x m) */
    long ld;
    int super;           /* 1: L supernodal */
    double share;        /* the share of L the last pruned backward solves visited */
} compliance;

static long compliance_of(ffc__bulk *b, compliance *c)
{
    c->super = -1;
    c->share = -1.0;
    return ffc__bulk_compliance(b, &c->dof, &c->G, &c->ld, &c->H, &c->super, &c->share);
}

/* The dense reference: the columns of K^-1 (K = Kd[n * n], factorized in
 * place) at C's dofs cd = nd1 then nd2 into Kinv[n * CT] (zero on entry);
 * returns their largest entry */
static double inverse_columns(int n, double Kd[], const long nd1[LATTICE_C1], const long nd2[LATTICE_C2],
                              long cd[LATTICE_C1 + LATTICE_C2], double Kinv[])
{
    enum { C1 = LATTICE_C1, CT = LATTICE_C1 + LATTICE_C2 };
    for (long k = 0; k < CT; k++) {
        cd[k] = k < C1 ? nd1[k] : nd2[k - C1];
        Kinv[cd[k] + k * n] = 1.0;
    }
    int nrhs = CT, info = 0;
    dpotrf_("L", &n, Kd, &n, &info);
    assert_int_equal(info, 0);
    dpotrs_("L", &n, &nrhs, Kd, &n, Kinv, &n, &info);
    assert_int_equal(info, 0);
    double kmax = 0.0;
    for (long k = 0; k < (long)n * CT; k++) kmax = fmax(kmax, fabs(Kinv[k]));
    return kmax;
}

/* The compliance columns G (C x C) and H (R x C) against K^-1 from a dense
 * Cholesky of the lattice's K, with a supernodal factor and pruned solves,
 * the same factor and whole back-solves, and the factor CHOLMOD chooses;
 * C grown in two calls (72 columns: two blocks of solves; then 30),
 * some of its dofs outside R.  Tolerance: 1e-10 of
 * the largest entry of K^-1 (backward-stable solves of a matrix of
 * condition ~1e3 on its free rows; the Dirichlet rows' entries are 1/TGV
 * in the dense inverse and 0 in the factor's, both far below it). */
static void test_pruned_columns(void **state)
{
    (void)state;
    enum { NT = 40 * LN * LN * LN };
    long *Ti = malloc(NT * sizeof(long)), *Tj = malloc(NT * sizeof(long)), bad = -1;
    double *Tv = malloc(NT * sizeof(double)), *Kd = malloc(sizeof(double) * LD * LD);
    const long nt = test_lattice(LN, TGV, Ti, Tj, Tv, Kd);
    assert_true(nt <= NT);
    /* R: the dofs of the top plane; C: 72 of them (two blocks of solves), then 30 more of which 9
     * interior ones */
    enum { C1 = LATTICE_C1, C2 = LATTICE_C2, CT = C1 + C2 };
    long rows[3 * LN * LN], nd1[C1], nd2[C2];
    test_lattice_sets(LN, rows, nd1, nd2);
    /* the dense reference: columns of K^-1 at C's dofs */
    double *Kinv = calloc((size_t)LD * CT, sizeof(double));
    long cd[CT];
    const double kmax = inverse_columns(LD, Kd, nd1, nd2, cd, Kinv);
    /* modes: pruned, whole supernodal, simplicial; and pruned with C grown
     * 7 dofs a call (G re-laid out as its leading dimension grows with
     * columns already in it) */
    const int modes[4][2] = {{1, 1}, {1, 0}, {0, 1}, {1, 1}};
    for (int md = 0; md < 4; md++) {
        ffc__bulk *b = NULL;
        assert_int_equal(ffc__bulk_create(LD, nt, Ti, Tj, Tv, 1000, &b, &bad), FFC_OK);
        ffc__bulk_set_columns_mode(b, modes[md][0], modes[md][1]);
        if (md < 3) {
            assert_int_equal(ffc__bulk_columns(b, 3 * LN * LN, rows, C1, nd1, &bad), FFC_OK);
            assert_int_equal(ffc__bulk_columns(b, 3 * LN * LN, rows, C2, nd2, &bad), FFC_OK);
        } else {
            for (long k = 0; k < C1; k += 7)
                assert_int_equal(ffc__bulk_columns(b, 3 * LN * LN, rows, k + 7 < C1 ? 7 : C1 - k, nd1 + k, &bad), FFC_OK);
            for (long k = 0; k < C2; k += 7)
                assert_int_equal(ffc__bulk_columns(b, 3 * LN * LN, rows, k + 7 < C2 ? 7 : C2 - k, nd2 + k, &bad), FFC_OK);
        }
        compliance c;
        assert_int_equal(compliance_of(b, &c), CT);
        if (md != 2) assert_int_equal(c.super, 1);
        if (md == 0) assert_true(c.share > 0.0 && c.share < 0.9);   /* the premise: the solves were pruned */
        if (md == 3) assert_true(c.ld >= CT && c.ld % 64 == 0 && c.ld < 2 * CT);   /* grown in steps, not doubled past */
        if (md == 1) assert_true(c.share == 0.0);
        long col[CT];   /* C's order is the solves' (L's order with pruning): the reference column of each */
        for (long j = 0; j < CT; j++) {
            col[j] = -1;
            for (long k = 0; k < CT; k++)
                if (cd[k] == c.dof[j]) col[j] = k;
            assert_true(col[j] >= 0 && (j < C1) == (col[j] < C1));   /* each dof once, the first call's first */
        }
        for (long j = 0; j < CT; j++) {
            for (long i = 0; i < CT; i++) assert_close(c.G[i + j * c.ld], Kinv[c.dof[i] + col[j] * LD], 1e-10 * kmax);
            for (long r = 0; r < 3 * LN * LN; r++)
                assert_close(c.H[r + j * 3 * LN * LN], Kinv[rows[r] + col[j] * LD], 1e-10 * kmax);
        }
        ffc__bulk_free(b);
    }
    free(Ti); free(Tj); free(Tv); free(Kd); free(Kinv);
}

/* Two bodies (L's forest of two trees): the pruned solves take the
 * backward solve in the trees of a block's dofs alone (a block of the
 * bodies' alternating dofs: both).  G and H against
 * the dense inverse, as above (1e-10 of its largest entry); the entries
 * between the bodies exactly zero, as in the dense inverse (a block's
 * solve touches nothing of the other tree). */
static void test_pruned_forest(void **state)
{
    (void)state;
    enum { N2 = 2 * LD, NT = 80 * LN * LN * LN, NR = 6 * LN * LN, C1 = LATTICE_C1, C2 = LATTICE_C2, CT = C1 + C2 };
    long *Ti = malloc(NT * sizeof(long)), *Tj = malloc(NT * sizeof(long)), bad = -1;
    double *Tv = malloc(NT * sizeof(double)), *Kd = malloc(sizeof(double) * N2 * N2);
    const long nt = test_lattice_pair(LN, TGV, Ti, Tj, Tv, Kd);
    assert_true(nt <= NT);
    long rows[NR], nd1[C1], nd2[C2], cd[CT];
    test_lattice_pair_sets(LN, rows, nd1, nd2);
    double *Kinv = calloc((size_t)N2 * CT, sizeof(double));
    const double kmax = inverse_columns(N2, Kd, nd1, nd2, cd, Kinv);
    ffc__bulk *b = NULL;
    assert_int_equal(ffc__bulk_create(N2, nt, Ti, Tj, Tv, 1000, &b, &bad), FFC_OK);
    ffc__bulk_set_columns_mode(b, 1, 1);
    assert_int_equal(ffc__bulk_columns(b, NR, rows, C1, nd1, &bad), FFC_OK);
    assert_int_equal(ffc__bulk_columns(b, NR, rows, C2, nd2, &bad), FFC_OK);
    compliance c;
    assert_int_equal(compliance_of(b, &c), CT);
    assert_true(c.super == 1 && c.share > 0.0 && c.share < 0.9);   /* pruned */
    for (long j = 0; j < CT; j++) {
        long cj = -1;
        for (long k = 0; k < CT; k++)
            if (cd[k] == c.dof[j]) cj = k;
        assert_true(cj >= 0);
        for (long i = 0; i < CT; i++) {
            assert_close(c.G[i + j * c.ld], Kinv[c.dof[i] + cj * N2], 1e-10 * kmax);
            if ((c.dof[i] < LD) != (c.dof[j] < LD)) assert_true(c.G[i + j * c.ld] == 0.0);
        }
        for (long r = 0; r < NR; r++) {
            assert_close(c.H[r + j * NR], Kinv[rows[r] + cj * N2], 1e-10 * kmax);
            if ((rows[r] < LD) != (c.dof[j] < LD)) assert_true(c.H[r + j * NR] == 0.0);
        }
    }
    ffc__bulk_free(b);
    free(Ti); free(Tj); free(Tv); free(Kd); free(Kinv);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_mpi),
        cmocka_unit_test(test_matches_dense),
        cmocka_unit_test(test_mostly_dirichlet),
        cmocka_unit_test(test_columns_grow),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_pruned_columns),
        cmocka_unit_test(test_pruned_forest),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
